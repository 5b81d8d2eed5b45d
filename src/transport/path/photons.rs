//! The caustic photon map (Jensen 1996; Jensen 2001, "Realistic Image Synthesis Using Photon
//! Mapping", ch. 7 and 9): light focused by mirrors and glass, traced from the lamps.
//!
//! **Tracing.** Each light with a surface (rect, disk, sphere) sends photons in proportion to
//! its power Φ = π L A: a point uniform in area, a cosine-weighted direction about its normal,
//! so every photon carries Φ / n. A photon follows mirrors and smooth glass (their delta lobes, glass
//! choosing reflection or refraction by Fresnel: the flux splits, no η² as radiance has) and
//! is stored where it first meets any other surface, if it passed at least one mirror or glass
//! on the way: the paths L S⁺ D of Heckbert's notation. Rough glass ends a photon unstored:
//! the path tracer samples it with next-event estimation and keeps every path through it. The photons' numbers are the render's
//! sampler at the photon's index, in streams hashed from the light, the depth and the purpose:
//! the same map on every thread count.
//!
//! **Gathering.** At a point x with BRDF f seen from ω_o, the reflected radiance of the map's
//! light is L_r ≈ Σ f(ω_p, ω_o) ΔΦ_p / (π r²) over the photons within r of x that arrived on
//! x's side (Jensen 2001, eq. 7.6), with the sphere flattened to a disc (|(x_p − x)·n| ≤ r/4)
//! so a nearby wall's photons do not leak in. The estimate is biased (the caustic is blurred
//! over r) and consistent: it converges as photons grow and r shrinks. The photons are kept in
//! a hashed grid of cells of side r (pbrt-v3's SPPM grid), so a gather reads 27 cells.
//!
//! **With the path tracer.** The map replaces exactly the paths it holds: the camera's path
//! gathers it at the first surface that is not a mirror or glass, and from there a path that
//! reaches a lamp through mirrors and glass only (D S⁺ L) no longer counts that lamp.

use super::shapes::Shape;
use crate::geometry::sampler::Sampler;
use crate::geometry::sampling::{cosine_hemisphere, hash3};
use crate::light::Light;
use crate::scene::{Model, Scene};
use crate::shading::brdf::{from_local, local_frame, to_local};
use crate::transport::rays::{Origin, SceneRays};
use glam::Vec3;
use rayon::prelude::*;

/// One stored photon.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Photon {
    /// Where it landed.
    pub p: Vec3,
    /// Unit direction back to where it came from.
    pub wi: Vec3,
    /// Its flux ΔΦ (W).
    pub power: Vec3,
}

/// The caustic photon map: the photons, sorted by grid cell, and the gather radius.
#[derive(Debug, Clone)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// For hashed cell h, its photons are `photons[starts[h]..starts[h + 1]]`.
    starts: Vec<u32>,
    radius: f32,
    /// Photons sent from the lamps.
    pub emitted: u32,
}

/// Photons traced per parallel task (their order is kept: the map is the same on any thread count).
const CHUNK: u32 = 4096;

impl PhotonMap {
    /// About `n` photons sent from `lights` (the ones with a surface; the rest send none) into
    /// `scene`, followed through at most `max_depth` segments, gathered within `radius`.
    pub fn trace(scene: &Scene, rays: &SceneRays, lights: &[Light], n: u32, radius: f32, max_depth: u32, sampler: Sampler) -> PhotonMap {
        let two_sided = scene.spec.settings.cull == crate::lesson::Cull::None;
        let shapes: Vec<(usize, Shape, Vec3)> =
            lights.iter().enumerate().filter_map(|(i, l)| Shape::of(l).map(|s| (i, s, l.radiance))).collect();
        let power = |s: &Shape, l: Vec3| std::f32::consts::PI * s.area() * l.max_element().max(0.0);
        let total: f32 = shapes.iter().map(|(_, s, l)| power(s, *l)).sum();
        let mut photons = Vec::new();
        let mut emitted = 0u32;
        if total > 0.0 && total.is_finite() {
            for (i, shape, radiance) in &shapes {
                let count = ((n as f64 * f64::from(power(shape, *radiance) / total)).round() as u32).max(1);
                emitted += count;
                let each = *radiance * (std::f32::consts::PI * shape.area() / count as f32);
                let chunks: Vec<Vec<Photon>> = (0..count.div_ceil(CHUNK))
                    .into_par_iter()
                    .map(|c| {
                        let mut out = Vec::new();
                        for k in c * CHUNK..((c + 1) * CHUNK).min(count) {
                            let u = |depth: u32, slot: u32| sampler.u2(k, count, hash3(*i as u32, depth, slot));
                            let (y, m) = shape.point(u(0, 0));
                            let (t, b) = local_frame(m);
                            let d = from_local(cosine_hemisphere(u(0, 1)), t, b, m).normalize_or_zero();
                            let from = Origin { p: y, ng: m, tri: u32::MAX, object: u32::MAX };
                            if let Some(p) = follow(scene, rays, from, d, each, max_depth, two_sided, &u) {
                                out.push(p);
                            }
                        }
                        out
                    })
                    .collect();
                photons.extend(chunks.into_iter().flatten());
            }
        }
        PhotonMap::build(photons, radius, emitted)
    }

    /// The map of `photons` gathered within `radius`: sorted by hashed cell (a counting sort).
    pub fn build(mut photons: Vec<Photon>, radius: f32, emitted: u32) -> PhotonMap {
        let cells = (2 * photons.len()).next_power_of_two().max(1);
        let key = |p: &Photon| cell_hash(cell_of(p.p, radius), cells);
        let mut starts = vec![0u32; cells + 1];
        photons.iter().for_each(|p| starts[key(p) + 1] += 1);
        for h in 0..cells {
            starts[h + 1] += starts[h];
        }
        photons.sort_by_key(key);
        PhotonMap { photons, starts, radius, emitted }
    }

    /// Photons stored.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// True when no photon was stored.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// L_r at `x` with unit geometric normal `ng` (the side the view is on): Σ f(ω_p) ΔΦ_p /
    /// (π r²) over the photons in the disc of radius r about x that arrived on that side;
    /// `f(ω_p)` is the BRDF towards the viewer for the world direction ω_p.
    pub fn estimate(&self, x: Vec3, ng: Vec3, f: impl Fn(Vec3) -> Vec3) -> Vec3 {
        if self.photons.is_empty() {
            return Vec3::ZERO;
        }
        let r = self.radius;
        let cells = self.starts.len() - 1;
        let c = cell_of(x, r);
        let mut sum = Vec3::ZERO;
        let mut seen = [usize::MAX; 27];
        for (j, o) in (0..27).map(|j| (j, [j % 3, (j / 3) % 3, j / 9])) {
            let h = cell_hash([c[0] + o[0] as i32 - 1, c[1] + o[1] as i32 - 1, c[2] + o[2] as i32 - 1], cells);
            // Two neighbours may hash alike: read each bucket once.
            if seen[..j].contains(&h) {
                continue;
            }
            seen[j] = h;
            for p in &self.photons[self.starts[h] as usize..self.starts[h + 1] as usize] {
                let to = p.p - x;
                let along = to.dot(ng);
                if to.length_squared() <= r * r && along.abs() <= 0.25 * r && p.wi.dot(ng) > 0.0 {
                    sum += f(p.wi) * p.power;
                }
            }
        }
        sum / (std::f32::consts::PI * r * r)
    }
}

/// The grid cell of `p` for cells of side `r`.
fn cell_of(p: Vec3, r: f32) -> [i32; 3] {
    let c = (p / r).floor();
    [c.x as i32, c.y as i32, c.z as i32]
}

/// The bucket of cell `c` among `cells` (a power of two).
fn cell_hash(c: [i32; 3], cells: usize) -> usize {
    hash3(c[0] as u32, c[1] as u32, c[2] as u32) as usize & (cells - 1)
}

/// A photon from `from` along `d` with flux `power`, through mirrors and glass: where it
/// lands on another surface after at least one of them, or `None`.
#[allow(clippy::too_many_arguments)]
fn follow(
    scene: &Scene,
    rays: &SceneRays,
    mut from: Origin,
    mut d: Vec3,
    mut power: Vec3,
    max_depth: u32,
    two_sided: bool,
    u: &impl Fn(u32, u32) -> glam::Vec2,
) -> Option<Photon> {
    let mut specular = false;
    for depth in 1..=max_depth {
        if d == Vec3::ZERO {
            return None;
        }
        let hit = rays.closest(&from, d)?;
        let s = crate::transport::surfaces::surface_at(&scene.geometry, &scene.materials, &hit);
        let v = -d;
        let front = s.face.dot(v) > 0.0;
        let n = match (&s.material.model, front) {
            (Model::Glass(_), _) | (_, true) => s.n,
            (_, false) if two_sided => -s.n,
            _ => return None,
        };
        let (t, b) = local_frame(n);
        let vl = to_local(v, t, b, n);
        let (l, weight) = match &s.material.model {
            // Rough glass is not a delta: the path tracer keeps every path through it.
            Model::Glass(g) if g.roughness > 0.0 => return None,
            Model::Glass(g) => g.sample(vl, u(depth, 2).x, None).map(|s| (s.l, s.weight))?,
            Model::Mirror(m) => m.sample(vl).map(|s| (s.l, s.weight))?,
            _ => return specular.then_some(Photon { p: s.p, wi: v, power }),
        };
        power *= weight;
        specular = true;
        if power.max_element() <= 0.0 || !power.is_finite() {
            return None;
        }
        from = Origin { p: s.p, ng: s.face, tri: hit.tri, object: hit.object };
        d = from_local(l, t, b, n).normalize_or_zero();
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_flux_gives_its_irradiance_times_the_brdf() {
        // Photons of 1e-4 W each, 1e4 per m² on the plane y = 0: E = 1 W/m²; a Lambertian
        // BRDF ρ/π reflects ρE/π.
        let mut photons = Vec::new();
        for i in 0..400 {
            for j in 0..400 {
                let p = Vec3::new(-2.0 + (i as f32 + 0.5) * 0.01, 0.0, -2.0 + (j as f32 + 0.5) * 0.01);
                photons.push(Photon { p, wi: Vec3::new(0.3, 0.9, 0.1).normalize(), power: Vec3::splat(1e-4) });
            }
        }
        let map = PhotonMap::build(photons, 0.1, 160_000);
        let rho = 0.5;
        let l = map.estimate(Vec3::new(0.013, 0.0, -0.27), Vec3::Y, |_| Vec3::splat(rho / std::f32::consts::PI));
        let expected = rho / std::f32::consts::PI;
        assert!((l.x / expected - 1.0).abs() < 0.02, "{l} against {expected}");
        // The other side of the plane, and a point a disc's thickness above it, see none.
        assert_eq!(map.estimate(Vec3::new(0.0, 0.0, 0.0), -Vec3::Y, |_| Vec3::ONE), Vec3::ZERO);
        assert_eq!(map.estimate(Vec3::new(0.0, 0.05, 0.0), Vec3::Y, |_| Vec3::ONE), Vec3::ZERO);
    }

    #[test]
    fn the_grid_finds_every_photon_within_the_radius() {
        // Scattered photons: the gather equals a brute-force sum over all of them.
        let photons: Vec<Photon> = (0..5000u32)
            .map(|k| {
                let h = |s: u32| (hash3(k, s, 7) >> 8) as f32 / (1u32 << 24) as f32;
                Photon { p: Vec3::new(h(0) * 2.0 - 1.0, (h(1) - 0.5) * 0.02, h(2) * 2.0 - 1.0), wi: Vec3::Y, power: Vec3::splat(h(3)) }
            })
            .collect();
        let r = 0.07;
        let map = PhotonMap::build(photons.clone(), r, 5000);
        for q in [Vec3::ZERO, Vec3::new(0.5, 0.0, -0.93), Vec3::new(-0.999, 0.0, 0.999)] {
            let brute: Vec3 = photons
                .iter()
                .filter(|p| (p.p - q).length_squared() <= r * r && (p.p - q).y.abs() <= 0.25 * r)
                .map(|p| p.power)
                .sum::<Vec3>()
                / (std::f32::consts::PI * r * r);
            let got = map.estimate(q, Vec3::Y, |_| Vec3::ONE);
            assert!((got - brute).abs().max_element() <= 1e-4 * brute.max_element().max(1.0), "{got} against {brute}");
        }
    }
}
