//! Fog: a pass after per-sample lighting and before the resolve, per sample with its depth.
//!
//! Which light paths it counts: the classic blends count none (they are a depth cue, not
//! light transport): C = f C_obj + (1 − f) C_fog with
//! - `linear`: f = (end − z)/(end − start), clamped to [0, 1];
//! - `exp`: f = e^(−density·z);
//! - `exp2`: f = e^(−(density·z)²)
//!
//! (the OpenGL 1.x fixed-function fog, OpenGL 2.1 specification §3.11). z is the eye
//! distance |p − eye| (`distance = "radial"`, the default: the fog depends on how far the
//! point is, whatever the direction) or the view depth along the camera axis (`"depth"`,
//! what fixed-function hardware used: cheaper, but the fog then changes when the camera
//! turns, and points at the image's edges look less fogged than points at the same distance
//! in the centre). A sample that hits nothing is at z = ∞: f = 0, it shows C_fog.
//!
//! `medium` is light transport: single scattering in a homogeneous participating medium,
//! ray-marched per sample by `transport::medium` (it asks each light's visibility from points
//! in the medium). This module holds what decides and bounds it: [`needed`], the medium's
//! transmittance and far bound ([`medium`]) and the phase function ([`phase`]). An eye ray that
//! hits a surface is marched to it; one that hits nothing is marched to [`medium::far_bound`]
//! (where the transmittance is 10⁻⁴, capped at [`FAR_CAP_SCENES`] times the scene's size),
//! where it sees the camera background (or the skybox of an `[environment]` with
//! `background = true`) attenuated by T there.
//!
//! Term layers (ambient, diffuse, ...) show the surface before fog; `total` is fogged. With
//! fog every sample is covered: the fog fills the background too.

pub mod medium;
pub mod phase;

use crate::lesson::fog::{FogDistance, FogKind};
use crate::scene::Scene;

/// The far bound of an eye ray that hits nothing is at most this many times the scene's
/// size (the farthest object or point light from the eye): a point light's E⊥ falls as
/// 1/r², so far beyond the lights a thin medium adds little.
pub const FAR_CAP_SCENES: f32 = 20.0;

/// Whether the fog pass is needed for `scene`, and why (with its step count when marched).
pub fn needed(scene: &Scene) -> (bool, String) {
    let Some(fog) = &scene.spec.fog else { return (false, "no [fog]".into()) };
    let z = match fog.distance {
        FogDistance::Radial => "z = eye distance",
        FogDistance::Depth => "z = view depth",
    };
    let samples = scene.spec.camera.width as u64 * scene.spec.camera.height as u64 * (scene.spec.settings.aa as u64).pow(2);
    match fog.kind {
        FogKind::Linear { start, end } => {
            (true, format!("linear fog f = (end − z)/(end − start), start {start}, end {end}, {z}; {samples} samples"))
        }
        FogKind::Exp { density: 0.0 } | FogKind::Exp2 { density: 0.0 } => (false, "density = 0: f = 1, no fog".into()),
        FogKind::Exp { density } => (true, format!("exp fog f = e^(−{density}·z), {z}; {samples} samples")),
        FogKind::Exp2 { density } => (true, format!("exp2 fog f = e^(−({density}·z)²), {z}; {samples} samples")),
        FogKind::Medium(m) if m.sigma_t() == 0.0 => (false, "σ_s = σ_a = 0: the medium is a vacuum".into()),
        FogKind::Medium(m) => {
            let lights = scene.lights.iter().filter(|l| medium::scatters(l)).count();
            let steps = if m.sigma_s > 0.0 { m.steps } else { 0 };
            (
                true,
                format!(
                    "medium σ_s {}, σ_a {}, g {}: {steps} steps per sample × {samples} samples, {lights} light{} scattering",
                    m.sigma_s,
                    m.sigma_a,
                    m.g,
                    if lights == 1 { "" } else { "s" }
                ),
            )
        }
    }
}

/// The extinction σ_t that light rays cross on their way to surfaces (0 without a medium).
pub fn extinction(scene: &Scene) -> f32 {
    scene.spec.fog.as_ref().and_then(|f| f.medium()).map_or(0.0, |m| m.sigma_t())
}

/// True when a medium scatters light: then a convex object shadows the medium behind it
/// and a spot whose cone misses every object still lights the fog.
pub fn scatters(scene: &Scene) -> bool {
    scene.spec.fog.as_ref().and_then(|f| f.medium()).is_some_and(|m| m.sigma_s > 0.0)
}

/// f, the share of the object's colour the classic blends keep at distance `z`.
#[inline]
pub fn blend_factor(kind: &FogKind, z: f32) -> f32 {
    let f = match *kind {
        FogKind::Linear { start, end } => (end - z) / (end - start),
        FogKind::Exp { density } => (-(density as f64) * z as f64).exp() as f32,
        FogKind::Exp2 { density } => (-(density as f64 * z as f64).powi(2)).exp() as f32,
        FogKind::Medium(_) => 1.0,
    };
    // z = ∞ gives 0 (exp) or −∞ (linear): both clamp to no object at all.
    if f.is_nan() { 0.0 } else { f.clamp(0.0, 1.0) }
}
