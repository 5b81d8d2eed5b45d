//! The fog pass per sample: the classic blends, or the ray-marched single-scattering integral
//! of a homogeneous participating medium along the sample's eye ray.
//!
//! Which light paths it counts: light → (medium, attenuated) → one scattering event in the
//! medium → (attenuated) → eye, plus the surface's radiance attenuated on its way to the eye
//! (the surface itself is lit by light attenuated on its way there, [`super::incidents`]).
//! Multiple scattering is not counted. The radiance reaching the eye along a ray of length d
//! (Sun et al. 2005, eq. 1; Pharr, Jakob & Humphreys, pbrt-v4 §11.1, the volume rendering
//! equation restricted to single scattering):
//!
//! L = L_surface·T(d) + ∫₀ᵈ T(s) σ_s Σ_lights p(θ) E⊥(x(s)) V(x(s)) ds,  T(s) = e^(−σ_t s),
//!
//! with E⊥ = I·C_spot·e^(−σ_t r)/r² for a point or spot light r away (radiometric: the
//! falloff physically based surfaces see; the classic `attenuation` coefficients are a
//! surface convention and are not read here) and E⊥ = L for a directional light (taken to
//! arrive with the given strength: a light infinitely far in an infinite medium would be
//! extinguished), V the light's shadow method seen from the medium point. Lights with extent
//! (rect, disk, sphere, line, sky) and ambient light light the surfaces through the medium
//! but scatter nothing into the eye ray.
//!
//! The integral is a jittered Riemann sum of N steps: s_k = (k + u) d/N, u in [0, 1) one
//! hash per sample, so the estimate is unbiased and the error falls as N grows (measured in
//! docs/accuracy-and-cost.md, `fog_steps`). The transmittances are exact exponentials.

use super::rays::Origin;
use super::visibility::Shadows;
use crate::effects::fog::medium::{far_bound, scatters, transmittance, transmittance_many};
use crate::effects::fog::phase::henyey_greenstein;
use crate::effects::fog::{FAR_CAP_SCENES, blend_factor};
use crate::geometry::equiangular::{Equiangular, MANY};
use crate::geometry::sampler::Sampler;
use crate::geometry::sampling::hash3;
use crate::lesson::fog::{Fog, FogDistance, FogKind, FogSampling, Medium};
use crate::light::{Light, LightKind, Point, Spot};
use crate::scene::Scene;
use glam::Vec3;

/// The count of samples the fog pass treated (every sample of the image, covered or not).
pub const FOG_SAMPLES: &str = "fog: samples marched or blended";
/// The count of ray-march steps the medium took (samples × steps; 0 for the classic blends).
pub const FOG_STEPS: &str = "fog: ray-march steps";

/// One render's fog: what every sample needs.
#[derive(Debug, Clone, Copy)]
pub struct FogPass<'a> {
    /// The fog.
    pub fog: Fog,
    /// The lights the plan keeps (in-scattering).
    pub lights: &'a [Light],
    /// Their shadow state (light shafts).
    pub shadows: &'a Shadows,
    /// The camera's unit forward axis (view depth).
    pub forward: Vec3,
    /// How far an eye ray that hits nothing is marched.
    pub far: f32,
    /// The camera background (seen at the far bound through the medium).
    pub background: Vec3,
    /// Where the in-scattering samples fall (`[render] sampler`).
    pub sampler: Sampler,
}

/// How far from the eye the medium reaches: where an eye ray's transmittance falls to 10⁻⁴,
/// capped at [`FAR_CAP_SCENES`] times the scene's size about the eye (its objects and its
/// point and spot lights): the march's far bound, and the path tracer's medium ball.
pub fn far(scene: &Scene, lights: &[Light], sigma_t: f32) -> f32 {
    let eye = scene.spec.camera.position;
    let mut size = scene.geometry.objects.iter().map(|o| (o.centre - eye).length() + o.radius).fold(1.0f32, f32::max);
    for l in lights {
        if let LightKind::Point(Point { position }) | LightKind::Spot(Spot { position, .. }) = l.kind {
            size = size.max((position - eye).length());
        }
    }
    far_bound(sigma_t, FAR_CAP_SCENES * size)
}

impl<'a> FogPass<'a> {
    /// The pass for `scene`, lit by `lights` (the plan's) with their `shadows`; `None` without fog.
    pub fn new(scene: &Scene, lights: &'a [Light], shadows: &'a Shadows) -> Option<FogPass<'a>> {
        let fog = scene.spec.fog?;
        let cam = &scene.spec.camera;
        let eye = cam.position;
        let far = fog.medium().map_or(f32::INFINITY, |m| far(scene, lights, m.sigma_t()));
        let sampler = scene.spec.settings.sampler;
        Some(FogPass { fog, lights, shadows, forward: (cam.look_at - eye).normalize(), far, background: cam.background, sampler })
    }

    /// Steps a sample's eye ray takes (0 for the classic blends).
    pub fn steps(&self) -> u32 {
        self.fog.medium().map_or(0, |m| if m.sigma_s > 0.0 { m.steps.max(1) } else { 0 })
    }

    /// The radiance of one sample after fog: its eye ray from `eye` along unit `dir` hits a
    /// surface of radiance `surface` at eye distance `hit`, or nothing (`None`: then `surface`
    /// is what the ray sees beyond the far bound, the camera background or the skybox, and
    /// the medium attenuates it; the classic blends show the fog colour); `seed` names the
    /// sample's streams: the jitter of the uniform march and each light's equiangular samples.
    #[inline]
    pub fn apply(&self, eye: Vec3, dir: Vec3, hit: Option<f32>, surface: Vec3, seed: u32) -> Vec3 {
        match &self.fog.kind {
            FogKind::Medium(m) => {
                let (length, end) = match hit {
                    Some(t) => (t, surface),
                    None => (self.far, surface),
                };
                // One jitter per sample (DESIGN.md, Determinism).
                let u = (seed >> 8) as f32 * (1.0 / (1u32 << 24) as f32);
                march(m, self.lights, self.shadows, EyeRay { origin: eye, dir, length }, end, u, self.sampler, seed)
            }
            kind => {
                let Some(t) = hit else { return self.fog.color };
                let z = match self.fog.distance {
                    FogDistance::Radial => t,
                    FogDistance::Depth => t * dir.dot(self.forward),
                };
                let f = blend_factor(kind, z);
                surface * f + self.fog.color * (1.0 - f)
            }
        }
    }
}

/// The light of light `i` scattered towards the eye per unit length and per unit σ_s,
/// p(θ) E⊥ V, at up to sixteen points along the eye ray, `eye + dir · s[j]` for each lane j
/// set in `lanes` (zero elsewhere), `dir` its unit direction. Counts its shadow queries.
#[allow(clippy::too_many_arguments)]
fn scattered_many(
    m: &Medium,
    i: usize,
    light: &Light,
    shadows: &Shadows,
    eye: Vec3,
    dir: Vec3,
    s: &[f32; MANY],
    lanes: u16,
) -> [Vec3; MANY] {
    let mut out = [Vec3::ZERO; MANY];
    let mut weight = [0.0f32; MANY];
    let mut origins = [Origin::NONE; MANY];
    let mut l = [Vec3::Z; MANY];
    let mut distance = [0.0f32; MANY];
    let mut want = 0u16;
    let mut inv_r2 = [0.0f32; MANY];
    let mut c_spot = [0.0f32; MANY];
    let mut lit = 0u16;
    for j in (0..MANY).filter(|j| lanes & (1 << j) != 0) {
        let x = eye + dir * s[j];
        let inc = light.incident::<f32>(x.into());
        let lj = Vec3::from(inc.l);
        if inc.c_spot <= 0.0 || lj == Vec3::ZERO {
            continue;
        }
        (origins[j].p, l[j], distance[j], inv_r2[j], c_spot[j]) = (x, lj, inc.distance, inc.inv_r2, inc.c_spot);
        lit |= 1 << j;
    }
    // The medium between each point and the light, sixteen at once.
    let through = transmittance_many(m.sigma_t(), &distance);
    for j in (0..MANY).filter(|j| lit & (1 << j) != 0) {
        let (x, lj) = (origins[j].p, l[j]);
        let e = if distance[j].is_finite() { inv_r2[j] * through[j] } else { 1.0 };
        let w = e * c_spot[j] * henyey_greenstein(lj.dot(dir), m.g);
        if w.is_nan() || w <= 0.0 {
            continue;
        }
        weight[j] = w;
        // A point in the medium lies on no surface: no triangle or object to skip, and
        // its "normal" faces the light (no offset sideways, no slope bias).
        origins[j] = Origin { p: x, ng: lj, tri: u32::MAX, object: u32::MAX };
        want |= 1 << j;
    }
    // One ray at a time: measured faster here than a packet, whose rays in a thin fog
    // mostly miss every object's bounding ball, which a single ray tests first.
    let casts = shadows.casts(i);
    if casts {
        shadows.counted(i, want.count_ones() as u64);
    }
    for j in (0..MANY).filter(|j| want & (1 << j) != 0) {
        let v = if casts { shadows.visibility(i, &origins[j], l[j], distance[j]) } else { 1.0 };
        out[j] = light.radiance * (weight[j] * v);
    }
    out
}

/// The first `count` (≤ 16) lanes as a mask.
#[inline]
fn first(count: usize) -> u16 {
    ((1u32 << count) - 1) as u16
}

/// A stretch of an eye ray: from `origin` along unit `dir` for `length`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EyeRay {
    /// The eye.
    pub origin: Vec3,
    /// Unit direction, away from the eye.
    pub dir: Vec3,
    /// How far it crosses the medium (to the surface it hits, or the far bound).
    pub length: f32,
}

/// True when light `l`'s in-scattering is sampled equiangularly in medium `m`: a light at a
/// point (point, spot) when the medium asks for it.
#[inline]
fn equiangular(m: &Medium, l: &Light) -> bool {
    m.sampling == FogSampling::Equiangular && l.kind.position().is_some()
}

/// `ray` through the medium, with `surface` the radiance at its end: L_surface·T(length) +
/// the in-scattering of `lights` (with their `shadows`). Lights at a point are sampled at
/// `m.steps` equiangular distances each (Kulla & Fajardo 2012, placed by `sampler` in the
/// stream `seed`), unless the medium asks for the uniform march; the others (and then all)
/// are marched in `m.steps` equal steps jittered by `u` in [0, 1).
#[allow(clippy::too_many_arguments)]
pub fn march(m: &Medium, lights: &[Light], shadows: &Shadows, ray: EyeRay, surface: Vec3, u: f32, sampler: Sampler, seed: u32) -> Vec3 {
    let EyeRay { origin: eye, dir, length } = ray;
    let sigma_t = m.sigma_t();
    let attenuated = surface * transmittance(sigma_t, length);
    // A zero (or NaN) length has nothing to march.
    if m.sigma_s == 0.0 || length.is_nan() || length <= 0.0 {
        return attenuated;
    }
    let n = m.steps.max(1);
    let mut scattered_sum = Vec3::ZERO;
    if lights.iter().any(|l| scatters(l) && !equiangular(m, l)) {
        let ds = length / n as f32;
        let mut sum = Vec3::ZERO;
        // Sixteen steps at a time, each light's shadow rays as a packet; each step's lights
        // summed in their order, as `in_scatter` does.
        let mut s = [0.0; MANY];
        for k0 in (0..n).step_by(MANY) {
            let count = (n - k0).min(MANY as u32) as usize;
            for (j, s) in s[..count].iter_mut().enumerate() {
                *s = ((k0 + j as u32) as f32 + u) * ds;
            }
            let mut steps = [Vec3::ZERO; MANY];
            for (i, light) in lights.iter().enumerate() {
                if scatters(light) && !equiangular(m, light) {
                    let each = scattered_many(m, i, light, shadows, eye, dir, &s, first(count));
                    for (step, v) in steps[..count].iter_mut().zip(each) {
                        *step += v;
                    }
                }
            }
            let through = transmittance_many(sigma_t, &s);
            for (step, through) in steps[..count].iter().zip(through) {
                sum += *step * through;
            }
        }
        scattered_sum += sum * ds;
    }
    for (i, light) in lights.iter().enumerate() {
        let Some(position) = light.kind.position().filter(|_| scatters(light) && equiangular(m, light)) else { continue };
        let eq = Equiangular::new(eye, dir, 0.0, length, position);
        let stream = hash3(seed, i as u32, 0xe9a1_7c0d);
        let mut sum = Vec3::ZERO;
        // The distances are drawn sixteen at a time, before any is lit: they depend on
        // nothing the lighting computes, and apart from it their f64 chains run in lanes.
        let mut u = [0.0; MANY];
        for k0 in (0..n).step_by(MANY) {
            let count = (n - k0).min(MANY as u32) as usize;
            for (j, u) in u[..count].iter_mut().enumerate() {
                *u = sampler.u1(k0 + j as u32, n, stream);
            }
            let (ts, weights) = eq.sample_many(&u);
            // A distance of no weight is neither lit nor added.
            let valid = (0..count).filter(|&j| weights[j] > 0.0 && weights[j].is_finite()).fold(0u16, |v, j| v | 1 << j);
            let light_at = scattered_many(m, i, light, shadows, eye, dir, &ts, valid);
            let through = transmittance_many(sigma_t, &ts);
            for j in (0..count).filter(|j| valid & (1 << j) != 0) {
                sum += light_at[j] * (through[j] * weights[j]);
            }
        }
        scattered_sum += sum / n as f32;
    }
    attenuated + scattered_sum * m.sigma_s
}

#[cfg(test)]
mod tests;
