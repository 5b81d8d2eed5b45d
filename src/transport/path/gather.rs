//! Indirect light at a camera path's first diffuse vertex without going on
//! (`[render] indirect = "photons"` or `"none"`): the final gather of Jensen 1996
//! (Jensen 2001, §9.3.4).
//!
//! **Which light paths it counts.** At the first vertex x with a BRDF, next-event estimation
//! has given direct light and the caustic map the caustics (`trace`). With `"photons"` and
//! `gather_rays` = N > 0, N rays are drawn from x's BRDF (cosine-weighted for a Lambertian
//! one), stratified across the pixel's paths; each follows mirrors and smooth glass to the
//! first diffuse surface y, where the global map's radiance estimate L_r(y → x) is read, with
//! no further recursion: L_ind(x) ≈ (1/N) Σ f cos / pdf · L_r(y). On the way a ray also brings
//! what a path's next segment would (a lamp or emitter it hits straight from x, weighted by
//! MIS against next-event estimation; the environment; emitters through glass), so x's light
//! is counted once. With N = 0 the global map, holding only the photons that bounced off a
//! diffuse surface before, is read at x itself: its blotches show (Jensen's "direct
//! visualisation"). With `"none"` the path ends at x: local illumination (with caustics).

use super::photons::PhotonMap;
use super::{Last, PathCounts, PathTracer, Slot, Stream, power};
use crate::geometry::sampling::hash3;
use crate::lesson::settings::Indirect;
use crate::scene::Model;
use crate::shading::brdf::{Brdf, from_local, local_frame, to_local};
use crate::transport::rays::Origin;
use crate::transport::surfaces::RayHit;
use glam::Vec3;

/// The BRDF at `p` (geometric normal `ng` on the view's side, shading frame of `n`) seen from
/// local `vl` times the photons of `map` near it: the map's L_r.
fn read(map: &PhotonMap, brdf: &Brdf, p: Vec3, n: Vec3, ng: Vec3, vl: Vec3) -> Vec3 {
    let (t, b) = local_frame(n);
    let l = map.estimate(p, ng, |wi| {
        let ll = to_local(wi, t, b, n);
        if ll.z > 0.0 { brdf.eval(ll, vl) } else { Vec3::ZERO }
    });
    if l.is_finite() { l } else { Vec3::ZERO }
}

impl PathTracer<'_> {
    /// The indirect light at the path's first diffuse vertex `s` (shading normal `n`, face
    /// normal `ng`, both on the view's side, `vl` the view in the local frame), by the global
    /// map and `gather_rays` rays, or none.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn indirect_at(
        &self,
        brdf: &Brdf,
        s: &RayHit,
        n: Vec3,
        ng: Vec3,
        vl: Vec3,
        here: &Origin,
        stream: &Stream,
        depth: u32,
        counts: &mut PathCounts,
    ) -> Vec3 {
        let Some(global) = self.photons.as_ref().and_then(|m| m.global.as_ref()).filter(|_| self.indirect == Indirect::Photons) else {
            return Vec3::ZERO;
        };
        if self.gather_rays == 0 {
            return read(global, brdf, s.p, n, ng, vl);
        }
        let (t, b) = local_frame(n);
        let rays = self.gather_rays;
        let mut sum = Vec3::ZERO;
        for i in 0..rays {
            // Ray i of the pixel sample's k-th path: index k·N + i of spp·N, so the N rays of
            // all the pixel's paths are one stratified set.
            let g =
                Stream { sampler: self.sampler, k: stream.k * rays + i, n: stream.n * rays, seed: hash3(stream.seed, depth, 0x6a7e_0f6a) };
            let Some(bs) = brdf.sample(vl, g.u1(0, Slot::Lobe), g.u2(0, Slot::Direction)) else { continue };
            let d = from_local(bs.l, t, b, n).normalize_or_zero();
            if d == Vec3::ZERO || d.dot(ng) <= 0.0 {
                continue;
            }
            let l = self.gather_ray(global, *here, d, bs.weight(), Last::Bsdf { pdf: bs.pdf, n }, &g, depth, counts);
            if l.is_finite() {
                sum += l;
            }
        }
        sum / rays as f32
    }

    /// One final-gather ray from `from` along `d` with weight `w`: through mirrors and smooth
    /// glass to the first diffuse surface, whose global-map radiance it reads.
    #[allow(clippy::too_many_arguments)]
    fn gather_ray(
        &self,
        global: &PhotonMap,
        mut from: Origin,
        mut d: Vec3,
        mut w: Vec3,
        mut last: Last,
        g: &Stream,
        depth: u32,
        counts: &mut PathCounts,
    ) -> Vec3 {
        let mut sum = Vec3::ZERO;
        for at in depth + 1..=self.max_depth {
            counts.gather_rays += 1;
            let hit = self.rays.closest(&from, d);
            // Straight from x a lamp is direct light, weighted against next-event estimation;
            // through mirrors and glass it is the caustic map's.
            if matches!(last, Last::Bsdf { .. }) {
                sum += w * self.lights_crossed(from.p, d, hit.map_or(f32::INFINITY, |h| h.t), last.pdf());
            }
            let Some(hit) = hit else {
                return sum + w * self.escaped(d, at, last);
            };
            let s = self.surface(&hit);
            let v = -d;
            let front = s.face.dot(v) > 0.0;
            if front && s.material.emission != Vec3::ZERO {
                let mis = match last.pdf() {
                    Some(pb) => self.emitters.pdf(s.face, d, hit.t).map_or(1.0, |pl| power(pb, pl)),
                    None => 1.0,
                };
                sum += w * s.material.emission * mis;
            }
            let (n, ng) = match (&s.material.model, front) {
                (Model::Glass(_), _) | (_, true) => (s.n, s.face),
                (_, false) if self.two_sided => (-s.n, -s.face),
                _ => return sum,
            };
            let (t, b) = local_frame(n);
            let vl = to_local(v, t, b, n);
            let next = match &s.material.model {
                // A principled surface that lets light through ends the ray, as rough glass does.
                Model::Physical(Brdf::Principled(p)) if p.transmits() => None,
                Model::Physical(brdf) => return sum + w * read(global, brdf, s.p, n, ng, vl),
                Model::Mirror(m) => m.sample(vl),
                Model::Glass(gl) if gl.roughness == 0.0 => gl.sample(vl, g.u1(at, Slot::Lobe), None),
                // Rough glass and the classic models end the ray (photons stop at rough glass too).
                _ => None,
            };
            let Some(ds) = next else { return sum };
            w *= ds.weight;
            last = Last::Delta;
            from = Origin { p: s.p, ng: s.face, tri: hit.tri, object: hit.object };
            d = from_local(ds.l, t, b, n).normalize_or_zero();
            if d == Vec3::ZERO {
                return sum;
            }
        }
        sum
    }
}
