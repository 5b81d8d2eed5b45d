//! The reference image-based lighting: Monte Carlo integration of
//! L_o(v) = ∫ L_env(l) f(l, v) (n·l) dω_l over the sphere, deterministic from a hash.
//!
//! Which light paths it counts: the environment seen directly from the shaded point (blocked
//! by the scene when it can block itself), one reflection: Mitsuba's `direct` integrator for
//! an `envmap` emitter. Two strategies share the samples: half sample the map by luminance
//! ([`EnvDistribution`]), half the BRDF ([`BrdfSampler`]); each sample is weighted by the
//! balance heuristic of the multi-sample estimator, f L cos / (n_env p_env + n_brdf p_brdf)
//! (Veach 1997, eq. 9.12), which is unbiased and keeps both small bright light sources (the
//! map's strategy) and sharp lobes (the BRDF's) at low noise. The sample points are the R2
//! sequence rotated by a hash of the point ([`sample_2d`]), so a pixel has the same samples
//! on every run and thread.

use super::brdf_sampling::BrdfSampler;
use super::distribution::EnvDistribution;
use crate::geometry::sampling::{hash, sample_2d};
use crate::scene::Environment;
use crate::shading::brdf::{Brdf, from_local, local_frame, to_local};
use glam::Vec3;

/// ∫ L_env f cos dω at a point with unit normal `n`, seen from unit `v`, by `samples` samples
/// seeded by `seed`; `visible(l)` says whether the environment is seen along the world `l`.
#[allow(clippy::too_many_arguments)]
pub fn estimate(
    brdf: &Brdf,
    n: Vec3,
    v: Vec3,
    env: &Environment,
    dist: Option<&EnvDistribution>,
    samples: u32,
    seed: u32,
    visible: impl Fn(Vec3) -> bool,
) -> Vec3 {
    let (t, b) = local_frame(n);
    let vl = to_local(v, t, b, n);
    if vl.z <= 0.0 || samples == 0 {
        return Vec3::ZERO;
    }
    let sampler = BrdfSampler::of(brdf);
    let n_env = if dist.is_some() { samples.div_ceil(2) } else { 0 };
    let n_brdf = samples - n_env;
    let (ne, nb) = (n_env as f32, n_brdf as f32);
    let contribution = |lw: Vec3, ll: Vec3| -> Vec3 {
        if ll.z <= 0.0 {
            return Vec3::ZERO;
        }
        let f = brdf.eval(ll, vl);
        if f == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let radiance = env.radiance(lw);
        if radiance == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let p_env = dist.map_or(0.0, |d| d.pdf(env.to_map(lw)));
        let denominator = ne * p_env + nb * sampler.pdf(ll, vl);
        if !(denominator > 0.0) || !visible(lw) {
            return Vec3::ZERO;
        }
        f * radiance * (ll.z / denominator)
    };
    let mut sum = Vec3::ZERO;
    if let Some(dist) = dist {
        for k in 0..n_env {
            let (dm, _) = dist.sample(sample_2d(k, seed));
            let lw = env.from_map(dm);
            sum += contribution(lw, to_local(lw, t, b, n));
        }
    }
    let seed_b = hash(seed ^ 0x0b5d_f00d);
    for k in 0..n_brdf {
        if let Some(ll) = sampler.sample(sample_2d(k, seed_b), vl) {
            let lw = from_local(ll, t, b, n).normalize();
            sum += contribution(lw, to_local(lw, t, b, n));
        }
    }
    if sum.is_finite() { sum.max(Vec3::ZERO) } else { Vec3::ZERO }
}
