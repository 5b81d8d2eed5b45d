//! Lights → incidents → shading: the seam between the scene's lights and shading.
//!
//! Every shaded point asks each light for its [`Incident`](crate::shading::incident::Incident)s
//! (a point, directional or spot light one; a rect, disk, sphere or line light one per
//! sample, a sky two per sample; a shadowed light's with their visibility) and hands them
//! to shading, which knows nothing of light kinds.

use super::lighting::{At, Lighting};
use super::rays::Origin;
use crate::effects::fog::medium::transmittance;
use crate::geometry::sampling::{hash3, point_seed};
use crate::light::{FromPoint, Light, LightKind};
use crate::shading::incident::Incident;
use crate::simd::lanes::{Lanes, MAX_WIDTH, V3};
use glam::Vec3;

/// The incidents of lights that are neither sampled nor shadowed at point(s) `p`: one
/// [`Light::incident`] each. The shading bundles take this path when
/// [`Lighting::is_plain`]: a separate iterator type keeps their hot loop free of the code
/// for samples and shadows (measured on the sphere bench: 548e6 instructions with it (541e6 before shadows),
/// 582e6 when that code was inlined into the one iterator, even untaken).
#[inline(always)]
pub fn plain_incidents<F: Lanes>(lights: &[Light], p: V3<F>) -> PlainIncidents<'_, F> {
    PlainIncidents { lights: lights.iter(), p }
}

/// The iterator [`plain_incidents`] returns.
#[derive(Debug, Clone)]
pub struct PlainIncidents<'a, F> {
    lights: std::slice::Iter<'a, Light>,
    p: V3<F>,
}

impl<F: Lanes> Iterator for PlainIncidents<'_, F> {
    type Item = Incident<F>;

    // Inlined into the shading bundles (and their AVX functions): measured 546e6 → 612e6
    // instructions on the sphere bench when `Map::next` was left out of line.
    #[inline(always)]
    fn next(&mut self) -> Option<Incident<F>> {
        self.lights.next().map(|l| l.incident(self.p))
    }
}

/// The incidents of `lighting` at the point(s) `at`: every shaded point, scalar or in a
/// bundle, asks here, so shadows and area lights change one place. A point or directional
/// light gives one incident, a sampled light one per sample (a sky two: its sky and its
/// ground part); a shadowed light's incidents carry their visibility. Only the `active`
/// lanes cast shadow rays and look up maps (a bundle's other lanes repeat its first point,
/// and nobody reads them), so the counts of that work are the same at every lane width.
#[inline(always)]
pub fn incidents<'a, F: Lanes>(lighting: &'a Lighting, at: &'a At<F>, active: F::Mask) -> Incidents<'a, F> {
    Incidents { lighting, p: at.p, at, active, i: 0, k: 0, pending: None, from: None }
}

/// The incidents of light `i` of `lighting` alone at one point: what [`incidents`] delivers
/// for that light, in the same order and with the same samples (`explain --pixel` splits a
/// point's light by light with it).
pub fn light_incidents(lighting: &Lighting, at: &At<f32>, i: usize) -> Vec<Incident<f32>> {
    let mut it = Incidents { lighting, p: at.p, at, active: true, i, k: 0, pending: None, from: None };
    let mut out = Vec::new();
    // Light i's incidents end when the iterator moves past it with nothing left pending.
    while it.i == i || it.pending.is_some() {
        match it.next() {
            Some(inc) => out.push(inc),
            None => break,
        }
    }
    out
}

/// The iterator [`incidents`] returns.
#[derive(Debug, Clone)]
pub struct Incidents<'a, F: Lanes> {
    lighting: &'a Lighting,
    /// The points (a copy of `at.p`: the fast path reads nothing else).
    p: V3<F>,
    at: &'a At<F>,
    /// The lanes that hold a point to shade.
    active: F::Mask,
    /// The light being delivered.
    i: usize,
    /// Its next sample.
    k: u32,
    /// A sky's ground part, delivered after its sky part.
    pending: Option<Incident<F>>,
    /// The sampled light being delivered, seen from each lane's point (set at its first sample).
    from: Option<[FromPoint; MAX_WIDTH]>,
}

impl<F: Lanes> Iterator for Incidents<'_, F> {
    type Item = Incident<F>;

    // Inlined into the shading bundles (and their AVX functions): measured 546e6 → 612e6
    // instructions on the sphere bench when `Map::next` was left out of line.
    #[inline(always)]
    fn next(&mut self) -> Option<Incident<F>> {
        if !self.lighting.involved {
            // No light sampled or shadowed: the lights' own incidents, nothing more.
            let light = self.lighting.lights.get(self.i)?;
            self.i += 1;
            return Some(light.incident(self.p));
        }
        self.next_involved()
    }
}

impl<F: Lanes> Incidents<'_, F> {
    /// Which lanes are active, lane by lane.
    #[inline(always)]
    fn active_lanes(&self) -> [bool; MAX_WIDTH] {
        let on = lanes(F::select(self.active, F::splat(1.0), F::splat(0.0)));
        on.map(|x| x != 0.0)
    }

    /// [`Iterator::next`] when some light is sampled or shadowed.
    #[inline(always)]
    fn next_involved(&mut self) -> Option<Incident<F>> {
        if let Some(p) = self.pending.take() {
            return Some(p);
        }
        let light = self.lighting.lights.get(self.i)?;
        let i = self.i;
        if !light.kind.is_sampled() {
            self.i += 1;
            let mut inc = light.incident(self.at.p);
            if self.lighting.shadows.casts(i) {
                inc.visibility = self.visibility(i, &inc);
            }
            return Some(self.through_medium(inc));
        }
        if self.lighting.exact_area
            && let LightKind::Rect(_) = light.kind
        {
            self.i += 1;
            return Some(self.exact_rect(light));
        }
        let k = self.k;
        self.k += 1;
        if self.k >= light.samples {
            self.k = 0;
            self.i += 1;
        }
        let inc = self.sample(i, light, k);
        Some(self.through_medium(inc))
    }

    /// `inc` after the medium between the light and the point: attenuation and 1/r² (or dω)
    /// × e^(−σ_t r) lane by lane; an infinitely distant light is not attenuated.
    #[inline(always)]
    fn through_medium(&self, mut inc: Incident<F>) -> Incident<F> {
        let sigma_t = self.lighting.extinction;
        if sigma_t == 0.0 {
            return inc;
        }
        let d = lanes(inc.distance);
        let mut t = [1f32; MAX_WIDTH];
        for j in 0..F::WIDTH {
            if d[j].is_finite() {
                t[j] = transmittance(sigma_t, d[j]);
            }
        }
        let t = F::load(&t);
        inc.attenuation = inc.attenuation * t;
        inc.inv_r2 = inc.inv_r2 * t;
        inc
    }

    /// The visibility lanes of incident `inc` of the (unsampled) light `i`: a shadow query
    /// per lane the light reaches (C_spot > 0, N·L > 0), 1 elsewhere (those lanes add no
    /// direct light anyway). Shadow rays go as one packet.
    #[inline(always)]
    fn visibility(&self, i: usize, inc: &Incident<F>) -> F {
        if let Some(map) = self.lighting.shadows.lane_map(i) {
            // A one-face map with a one-texel filter: the lookup in lanes.
            let zero = F::splat(0.0);
            let reached = self.active & inc.c_spot.gt(zero) & self.at.n.dot(inc.l).gt(zero) & inc.l.ne_zero();
            self.lighting.shadows.counted(i, F::count(reached));
            return map.visibility_lanes(self.at.p, self.at.ng, inc.l, reached);
        }
        let (p, n, ng, l) = (unpack(self.at.p), unpack(self.at.n), unpack(self.at.ng), unpack(inc.l));
        let (d, c) = (lanes(inc.distance), lanes(inc.c_spot));
        let on = self.active_lanes();
        let mut origins = [Origin::NONE; MAX_WIDTH];
        let mut want = 0u16;
        for j in 0..F::WIDTH {
            if on[j] && c[j] > 0.0 && n[j].dot(l[j]) > 0.0 {
                origins[j] = self.at.origin(j, p[j], ng[j]);
                want |= 1 << j;
            }
        }
        self.lighting.shadows.counted(i, want.count_ones() as u64);
        F::load(&self.lighting.shadows.visibility_lanes(i, &origins, &l, &d, want))
    }

    /// Sample `k` of the sampled light `i`, lane by lane (each lane its own hashed pattern,
    /// placed by the render's sampler); a sky leaves its ground part in `pending`. The
    /// light is seen from each lane's point once, at its first sample.
    #[inline(always)]
    fn sample(&mut self, i: usize, light: &Light, k: u32) -> Incident<F> {
        let (p, n, ng) = (unpack(self.at.p), unpack(self.at.n), unpack(self.at.ng));
        let shadowed = self.lighting.shadows.casts(i);
        let on = self.active_lanes();
        if k == 0 || self.from.is_none() {
            self.from = Some(std::array::from_fn(|j| if j < F::WIDTH { light.from_point(p[j], n[j]) } else { FromPoint::None }));
        }
        let from = self.from.as_ref().expect("set above");
        let (mut lx, mut ly, mut lz) = ([0f32; MAX_WIDTH], [0f32; MAX_WIDTH], [0f32; MAX_WIDTH]);
        let (mut up, mut down, mut dist) = ([0f32; MAX_WIDTH], [0f32; MAX_WIDTH], [0f32; MAX_WIDTH]);
        let mut origins = [Origin::NONE; MAX_WIDTH];
        let mut want = 0u16;
        for j in 0..F::WIDTH {
            let seed = hash3(self.lighting.pattern.point(point_seed(p[j])), i as u32, 0x5eed_a11c);
            let s = light.sample_from(&from[j], self.lighting.sampler.u2(k, light.samples, seed));
            (lx[j], ly[j], lz[j], dist[j]) = (s.l.x, s.l.y, s.l.z, s.distance);
            // A sky sample below the horizon brings the ground's radiance: its own incident.
            if s.l.y >= 0.0 || light.ground().is_none() {
                up[j] = s.weight;
            } else {
                down[j] = s.weight;
            }
            if shadowed && on[j] && s.weight > 0.0 && n[j].dot(s.l) > 0.0 {
                origins[j] = self.at.origin(j, p[j], ng[j]);
                want |= 1 << j;
            }
        }
        let l = std::array::from_fn(|j| Vec3::new(lx[j], ly[j], lz[j]));
        let vis = if want != 0 { self.lighting.shadows.visibility_lanes(i, &origins, &l, &dist, want) } else { [1.0; MAX_WIDTH] };
        self.lighting.shadows.counted(i, want.count_ones() as u64);
        let one = F::splat(1.0);
        let w = F::load(&up);
        let inc = Incident {
            l: V3 { x: F::load(&lx), y: F::load(&ly), z: F::load(&lz) },
            distance: F::load(&dist),
            attenuation: w,
            inv_r2: w,
            c_spot: one,
            visibility: F::load(&vis),
            radiance: light.radiance,
            specular: light.specular,
            ambient: Vec3::ZERO,
            ambient_only: false,
        };
        if let Some(ground) = light.ground() {
            let w = F::load(&down);
            self.pending = Some(Incident { attenuation: w, inv_r2: w, radiance: ground, specular: ground, ..inc });
        }
        inc
    }

    /// A rect light's exact unoccluded contribution to a Lambertian receiver: one incident
    /// along the normal carrying the projected solid angle π F (Lambert 1760).
    #[inline(always)]
    fn exact_rect(&self, light: &Light) -> Incident<F> {
        let LightKind::Rect(rect) = light.kind else { unreachable!("a rect light") };
        let (p, n) = (unpack(self.at.p), unpack(self.at.n));
        let corners = rect.corners();
        let mut a = [0f32; MAX_WIDTH];
        for j in 0..F::WIDTH {
            a[j] = rect.projected_solid_angle(p[j], n[j], &corners);
        }
        let w = F::load(&a);
        let one = F::splat(1.0);
        Incident {
            l: self.at.n,
            distance: F::splat(f32::INFINITY),
            attenuation: w,
            inv_r2: w,
            c_spot: one,
            visibility: one,
            radiance: light.radiance,
            specular: light.specular,
            ambient: Vec3::ZERO,
            ambient_only: false,
        }
    }
}

/// The lanes of `v`.
#[inline(always)]
fn lanes<F: Lanes>(v: F) -> [f32; MAX_WIDTH] {
    let mut out = [0f32; MAX_WIDTH];
    v.store(&mut out);
    out
}

/// The lanes of `v` as vectors.
#[inline(always)]
fn unpack<F: Lanes>(v: V3<F>) -> [Vec3; MAX_WIDTH] {
    let (x, y, z) = (lanes(v.x), lanes(v.y), lanes(v.z));
    std::array::from_fn(|i| Vec3::new(x[i], y[i], z[i]))
}
