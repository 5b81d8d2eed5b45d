//! Random-walk subsurface scattering: the path tracer's BSSRDF (Chiang, Kutz & Burley 2016,
//! "Practical and Controllable Subsurface Scattering for Production Path Tracing", as Cycles'
//! "Random Walk" and pbrt-v4's `SubsurfaceMaterial` do it). Light leaves the surface away
//! from where it entered.
//!
//! | key (principled) | meaning here |
//! | --- | --- |
//! | `subsurface` s | the share of the diffuse lobe that goes under the surface |
//! | `subsurface_radius` r (RGB) × `subsurface_scale` k | the mean free path per channel: σ_t = 1/(r k) |
//! | `base_color` C | the colour the walk should return: the single-scattering albedo α per channel is the van de Hulst inversion fit of Chiang et al. 2016 (Cycles' `subsurface_random_walk_remap`, isotropic) |
//!
//! **The vertex.** A principled surface with s > 0 and a radius is the mixture
//! f = f_surface + s (1 − metallic) BSSRDF, with f_surface the principled BRDF with the base
//! colour C (1 − s) and no flattening (the Disney diffuse's share that stays on the surface,
//! and the whole specular, sheen and clearcoat). A path picks the walk with probability q ∝
//! the walk's mean weight s C̄ against the surface lobes' ([`Subsurface::q`]), and divides by it.
//!
//! **The walk.** The path enters by a cosine-weighted direction about the inward face normal
//! (a white diffuse transmission, weight 1), then flies through a homogeneous medium with
//! isotropic scattering until it crosses a surface: there it leaves through a white Lambert
//! exit (f = 1/π about the outward normal, weight 1), with next-event estimation as at any
//! vertex. No Fresnel at either crossing (index-matched, as Cycles' random walk). Chromatic:
//! each step draws a channel c with probability ∝ w_c α_c (w the walk's weight so far), a
//! distance from σ_t,c e^(−σ_t,c t), and the weight is multiplied by
//! σ_s T(t) / Σ_c p_c σ_t,c T_c(t) when it scatters or T(t) / Σ_c p_c T_c(t) when it
//! leaves (the balance heuristic over channels: the one-sample MIS of pbrt-v4's
//! `SampleT_maj` with a hero channel, and Cycles').
//!
//! **Caps.** A walk has at most [`MAX_STEPS`] scattering events (Cycles' 256); one still
//! inside after them is absorbed (lost energy; `explain` counts the walks' segments). When
//! every channel's mean free path is below [`MIN_FREE_PATH`] the walk would be shorter than
//! the rays' offset from the surface (and would need ~(offset/path)² steps to come back): the
//! light leaves where it entered with the colour C, the limit of the walk as the radius → 0.
//! A segment that meets no surface scatters anyway (an open mesh has no inside: such walks
//! end at the cap).

use super::{PathCounts, PathTracer, Stream};
use crate::geometry::sampling::{hash3, sin_cos};
use crate::scene::Model;
use crate::shading::brdf::{Brdf, local_frame};
use crate::shading::diffuse::Diffuse;
use crate::shading::lobe::Part;
use crate::shading::material::Material;
use crate::shading::principled::Principled;
use crate::transport::rays::{Origin, SceneHit};
use crate::transport::surfaces::RayHit;
use glam::{Vec2, Vec3};

/// The most scattering events of one walk (Cycles' `BSSRDF_MAX_BOUNCES`).
pub const MAX_STEPS: u32 = 256;
/// The mean free path (world units) below which light leaves where it entered: the rays'
/// offset from a surface is of this order.
pub const MIN_FREE_PATH: f32 = 1e-4;
/// Counter label: scattering events and exits of the subsurface walks (closest-hit rays).
pub const WALK_STEPS: &str = "subsurface walk steps";

/// The medium under a surface: extinction σ_t and single-scattering albedo α per channel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interior {
    /// σ_t = 1 / mean free path, per channel (1/world unit).
    pub sigma_t: Vec3,
    /// α = σ_s / σ_t per channel.
    pub albedo: Vec3,
}

impl Interior {
    /// The medium that returns the colour `color` (its multiple-scattering albedo) with mean
    /// free paths `free_path` (world units; raised to [`MIN_FREE_PATH`] to keep σ_t finite).
    pub fn new(color: Vec3, free_path: Vec3) -> Interior {
        let sigma_t = Vec3::ONE / free_path.max(Vec3::splat(MIN_FREE_PATH));
        let albedo = Vec3::from_array(color.to_array().map(single_scattering_albedo));
        Interior { sigma_t, albedo }
    }

    /// The principled material's medium when the path tracer walks under it: subsurface > 0
    /// and a radius given.
    pub fn of(p: &Principled) -> Option<Interior> {
        p.walks().then(|| Interior::new(p.base_color, p.subsurface_radius * p.subsurface_scale))
    }
}

/// The single-scattering albedo α whose walk in a half-space returns `a` (the van de Hulst
/// inversion fit of Chiang, Kutz & Burley 2016 for isotropic scattering, with Cycles'
/// constants at g = 0): α(0) = 0, α(1) = 1 (clamped: the fit gives 1.0016 there).
pub fn single_scattering_albedo(a: f32) -> f32 {
    // In f64, rounded once to f32: the same bits whichever libm variant runs (once a material).
    let a = f64::from(a.clamp(0.0, 1.0));
    let (aa, b, c) = (1.826_052_378_2, 5.112_467_903_29, 1.096_861_024_24);
    let (d, e, f) = (0.496_310_210_422, 4.235_009_036_5, 2.406_029_994_08);
    let blend = a.sqrt().sqrt();
    let alpha = (1.0 - blend) * aa * (b * a).atan().powf(c) + blend * d * (e * a).atan().powf(f);
    alpha.clamp(0.0, 1.0) as f32
}

/// The end of a walk that left through a surface.
#[derive(Debug, Clone, Copy)]
pub struct Exit<H> {
    /// What the caller's ray cast found there.
    pub hit: H,
    /// The point where the walk crossed the surface.
    pub p: Vec3,
    /// The direction it crossed with.
    pub d: Vec3,
    /// The walk's weight per channel (its expected value is the energy that leaves).
    pub weight: Vec3,
}

/// A walk through `m` from `p` along unit `d` (into the medium). `u(step, purpose)` gives
/// uniform numbers (purposes 0: channel, 1: distance, 2 and 3: direction); `cast(step, p, d)`
/// the distance to the first surface along p + t d and what is there, `None` when nothing is.
/// Returns where it left, or `None` when it was absorbed (weight 0 or [`MAX_STEPS`] reached);
/// `steps` counts the segments cast.
pub fn walk<H>(
    m: &Interior,
    mut p: Vec3,
    mut d: Vec3,
    mut u: impl FnMut(u32, u32) -> f32,
    mut cast: impl FnMut(u32, Vec3, Vec3) -> Option<(f32, H)>,
    steps: &mut u64,
) -> Option<Exit<H>> {
    let sigma_s = m.sigma_t * m.albedo;
    let mut w = Vec3::ONE;
    for step in 0..=MAX_STEPS {
        // A channel by w α (one with nothing to give is never drawn; all zero: uniform).
        let share = w * m.albedo;
        let sum = share.element_sum();
        let p_c = if sum > 0.0 && sum.is_finite() { share / sum } else { Vec3::splat(1.0 / 3.0) };
        let uc = u(step, 0);
        let c = if uc < p_c.x {
            0
        } else if uc < p_c.x + p_c.y {
            1
        } else {
            2
        };
        let t = -(1.0 - u(step, 1)).ln() / m.sigma_t[c];
        *steps += 1;
        let found = cast(step, p, d);
        match found {
            Some((t_hit, hit)) if t_hit <= t => {
                // Leaves: each channel's probability of flying that far, over the mixture's.
                let tr = (-m.sigma_t * t_hit).exp();
                let pdf = p_c.dot(tr);
                w *= if pdf > 0.0 { tr / pdf } else { Vec3::ZERO };
                let p = p + d * t_hit;
                return (w.is_finite() && w != Vec3::ZERO).then_some(Exit { hit, p, d, weight: w });
            }
            _ => {
                if step == MAX_STEPS {
                    return None;
                }
                // Scatters at t: σ_s T over the mixture's density Σ p_c σ_t,c T_c.
                let tr = (-m.sigma_t * t).exp();
                let pdf = p_c.dot(m.sigma_t * tr);
                w *= if pdf > 0.0 { sigma_s * tr / pdf } else { Vec3::ZERO };
                if !w.is_finite() || w == Vec3::ZERO {
                    return None;
                }
                p += d * t;
                d = uniform_sphere(Vec2::new(u(step, 2), u(step, 3)));
            }
        }
    }
    None
}

/// A uniform direction on the unit sphere (the isotropic phase, 1/(4π)).
fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = ((1.0 - z) * (1.0 + z)).max(0.0).sqrt();
    let (s, c) = sin_cos(std::f32::consts::TAU * u.y);
    Vec3::new(r * c, r * s, z)
}

/// A cosine-weighted direction about unit `n` (pdf cos/π).
pub fn cosine_about(n: Vec3, u: Vec2) -> Vec3 {
    let r = u.x.sqrt();
    let (s, c) = sin_cos(std::f32::consts::TAU * u.y);
    let (t, b) = local_frame(n);
    (t * (r * c) + b * (r * s) + n * (1.0 - u.x).max(0.0).sqrt()).normalize_or(n)
}

/// One material's walk: its medium, the surface part it keeps, and the choice between them.
#[derive(Debug, Clone)]
struct Walker {
    interior: Interior,
    /// The colour the walk returns (the base colour).
    color: Vec3,
    /// Every mean free path below [`MIN_FREE_PATH`]: light leaves where it entered.
    short: bool,
    /// The principled BRDF without the share that walks: base colour C (1 − s), no flattening.
    surface: Material,
    /// The probability of walking.
    q: f32,
    /// s / q: the walk's weight (its colour comes from α).
    walk_weight: f32,
}

/// The walks of a scene's materials, one per material that has one.
pub(super) struct Subsurface {
    walkers: Vec<Option<Walker>>,
    /// The white Lambert through which a walk leaves.
    exit: Material,
}

impl Subsurface {
    /// The walkers of `materials` (principled, subsurface > 0, a radius given, not metallic:
    /// the validator refuses a radius on a metal).
    pub(super) fn new(materials: &[Material]) -> Subsurface {
        let walkers = materials
            .iter()
            .map(|m| {
                let Model::Physical(Brdf::Principled(p)) = &m.model else { return None };
                let interior = Interior::of(p)?;
                let s = p.subsurface;
                let kept = Principled { subsurface: 0.0, base_color: p.base_color * (1.0 - s), subsurface_radius: Vec3::ZERO, ..*p };
                let lobes = Brdf::Principled(kept).lobes();
                let w_surface = (lobes.weight(Part::Diffuse) + lobes.weight(Part::Specular)).element_sum() / 3.0;
                let w_walk = s * (1.0 - p.metallic) * p.base_color.element_sum() / 3.0;
                let q = Self::q(w_walk, w_surface);
                let surface = Material { model: Model::Physical(Brdf::Principled(kept)), ..m.clone() };
                let short = (p.subsurface_radius * p.subsurface_scale).max_element() < MIN_FREE_PATH;
                Some(Walker {
                    interior,
                    color: p.base_color,
                    short,
                    surface,
                    q,
                    walk_weight: if q > 0.0 { s * (1.0 - p.metallic) / q } else { 0.0 },
                })
            })
            .collect();
        let white = Brdf::Diffuse(Diffuse { albedo: Vec3::ONE });
        let exit = Material { name: String::new(), model: Model::Physical(white), ambient: Vec3::ONE, emission: Vec3::ZERO };
        Subsurface { walkers, exit }
    }

    /// The probability of walking: the walk's share of the mean lobe weights.
    fn q(walk: f32, surface: f32) -> f32 {
        if walk + surface > 0.0 { (walk / (walk + surface)).clamp(0.0, 1.0) } else { 0.0 }
    }
}

/// A walk's own purposes in the sample streams (beside the path's slots).
const WALK_SEED: u32 = 0x55b5_3a11;

impl<'a> PathTracer<'a> {
    /// At a surface hit `s` (`hit`, seen from `v`, `front` when on its front face): when its
    /// material walks, either the surface part (the hit with that material) or a walk that
    /// enters here and leaves elsewhere (the exit as a hit with the white Lambert exit, seen
    /// along its outward normal), with `beta` weighted by the choice. Other materials come
    /// back unchanged; `None` when the walk was absorbed.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn subsurface<'s>(
        &'s self,
        s: RayHit<'a>,
        hit: SceneHit,
        v: Vec3,
        front: bool,
        stream: &Stream,
        depth: u32,
        beta: &mut Vec3,
        counts: &mut PathCounts,
    ) -> Option<(RayHit<'s>, SceneHit, Vec3, bool)> {
        let walker = self.walks.walkers.get(self.scene.geometry.material[hit.tri as usize] as usize).and_then(Option::as_ref);
        let Some(walker) = walker.filter(|_| front || self.two_sided) else { return Some((s, hit, v, front)) };
        let seed = hash3(stream.seed, depth, WALK_SEED);
        let draw = |step: u32, purpose: u32| stream.sampler.u1(stream.k, stream.n, hash3(seed, step, purpose));
        if draw(u32::MAX, 0) >= walker.q {
            *beta /= 1.0 - walker.q;
            return Some((RayHit { material: &walker.surface, ..s }, hit, v, front));
        }
        *beta *= walker.walk_weight;
        let out = if front { s.face } else { -s.face };
        if walker.short {
            // Shorter than the rays' offset: out where it came in, with the walk's colour C.
            *beta *= walker.color;
            let n = if s.n.dot(out) >= 0.0 { s.n } else { -s.n };
            return Some((RayHit { face: out, n, material: &self.walks.exit, ..s }, hit, n, true));
        }
        // In through a white diffuse transmission about the inward face normal (weight 1).
        let d = cosine_about(-out, Vec2::new(draw(u32::MAX, 1), draw(u32::MAX, 2)));
        let entry = Origin { p: s.p, ng: out, tri: hit.tri, object: hit.object };
        let cast = |step: u32, p: Vec3, d: Vec3| {
            let o = if step == 0 { entry } else { Origin { p, ng: d, tri: u32::MAX, object: u32::MAX } };
            self.rays.closest(&o, d).map(|h| (h.t, h))
        };
        let exit = walk(&walker.interior, s.p, d, draw, cast, &mut counts.walk_steps)?;
        *beta *= exit.weight;
        let e = self.surface(&exit.hit);
        // Out through the white Lambert about the face's side the walk crossed towards.
        let face = if e.face.dot(exit.d) >= 0.0 { e.face } else { -e.face };
        let n = if e.n.dot(face) >= 0.0 { e.n } else { -e.n };
        Some((RayHit { p: e.p, n, face, material: &self.walks.exit }, exit.hit, n, true))
    }
}

/// Walks `n` light paths into the half-space z < 0 of medium `m` from the origin (entering by a
/// cosine-weighted direction about −z, as at a surface), and calls `exit(r, weight)` with the
/// distance r from the entry point where each one leaves through z = 0 (hash-seeded: the same
/// numbers every run). The radial profile R(r) of a flat, semi-infinite slab.
pub fn half_space_exits(m: &Interior, n: u32, mut exit: impl FnMut(f32, Vec3)) {
    use crate::geometry::sampler::Sampler;
    let mut steps = 0;
    for i in 0..n {
        let u = |step: u32, purpose: u32| Sampler::Independent.u1(i, n, hash3(step, purpose, 0x0bad_5eed));
        let d = cosine_about(-Vec3::Z, Vec2::new(u(u32::MAX, 0), u(u32::MAX, 1)));
        // From inside, the plane z = 0 is met going up: t = −z/d.z.
        let cast = |_: u32, p: Vec3, d: Vec3| (d.z > 0.0).then(|| ((-p.z / d.z).max(0.0), ()));
        if let Some(e) = walk(m, Vec3::ZERO, d, u, cast, &mut steps) {
            exit(e.p.truncate().length(), e.weight);
        }
    }
}

/// Burley's normalized diffusion R(r) = A s (e^(−s r/ℓ) + e^(−s r/(3ℓ))) / (8π ℓ r) with the
/// scaling s = 1.9 − A + 3.5 (A − 0.8)² that Christensen & Burley 2015 (eq. 6) fit to
/// Monte Carlo walks entering by diffuse transmission (ℓ the mean free path, A the
/// multiple-scattering albedo); ∫ R 2πr dr = A and the mean exit radius is 2.5 ℓ/s.
pub fn burley_profile(a: f32, free_path: f32, r: f32) -> f32 {
    let s = burley_scale(a);
    let d = free_path / s;
    a * ((-r / d).exp() + (-r / (3.0 * d)).exp()) / (8.0 * std::f32::consts::PI * d * r.max(1e-12))
}

/// Christensen & Burley 2015's s(A) for diffuse surface transmission (eq. 6).
pub fn burley_scale(a: f32) -> f32 {
    1.9 - a + 3.5 * (a - 0.8) * (a - 0.8)
}

/// The classical diffusion dipole's R_d(r) (Jensen et al. 2001, eq. 4) for an index-matched
/// boundary (η = 1, F_dr = −1.440 + 0.710 + 0.668 + 0.0636 ≈ 0.0016), isotropic scattering
/// (σ_s' = σ_s) and σ_t = 1/ℓ, with single-scattering albedo α.
pub fn dipole_profile(alpha: f32, free_path: f32, r: f32) -> f32 {
    let sigma_t = 1.0 / free_path;
    let (sigma_s, sigma_a) = (alpha * sigma_t, (1.0 - alpha) * sigma_t);
    let sigma_tr = (3.0 * sigma_a * sigma_t).sqrt();
    let f_dr = -1.440 + 0.710 + 0.668 + 0.0636;
    let big_a = (1.0 + f_dr) / (1.0 - f_dr);
    let z_r = 1.0 / sigma_t;
    let z_v = z_r * (1.0 + 4.0 / 3.0 * big_a);
    let (d_r, d_v) = ((r * r + z_r * z_r).sqrt(), (r * r + z_v * z_v).sqrt());
    let term = |z: f32, d: f32| z * (1.0 + sigma_tr * d) * (-sigma_tr * d).exp() / (d * d * d);
    (sigma_s / sigma_t) / (4.0 * std::f32::consts::PI) * (term(z_r, d_r) + term(z_v, d_v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sampler::Sampler;

    #[test]
    fn the_albedo_inversion_keeps_black_black_and_white_white_and_grows() {
        assert_eq!(single_scattering_albedo(0.0), 0.0);
        assert_eq!(single_scattering_albedo(1.0), 1.0);
        let mut last = 0.0;
        for i in 1..=100 {
            let a = single_scattering_albedo(i as f32 / 100.0);
            // Strictly below 0.98; the fit reaches 1 (clamped) from there.
            assert!((a > last || a == 1.0) && a <= 1.0, "α({}) = {a} after {last}", i as f32 / 100.0);
            last = a;
        }
    }

    /// The furnace of the walk: in a closed ball of non-absorbing medium (α = 1) every walk
    /// leaves, so the mean weight is 1 in every channel, whatever the channels' σ_t.
    #[test]
    fn a_white_walk_in_a_ball_returns_everything() {
        let m = Interior { sigma_t: Vec3::new(1.0 / 0.5, 1.0 / 0.3, 1.0 / 0.2), albedo: Vec3::ONE };
        let n = 40_000;
        let (mut sum, mut lost, mut steps) = (Vec3::ZERO, 0, 0);
        for i in 0..n {
            let u = |step: u32, purpose: u32| Sampler::Independent.u1(i, n, hash3(step, purpose, 7));
            let d = cosine_about(-Vec3::Z, Vec2::new(u(u32::MAX, 0), u(u32::MAX, 1)));
            // Inside the unit ball: the far root of |p + t d| = 1.
            let cast = |_: u32, p: Vec3, d: Vec3| {
                let b = p.dot(d);
                Some(((b * b - p.length_squared() + 1.0).max(0.0).sqrt() - b, ()))
            };
            match walk(&m, Vec3::Z, d, u, cast, &mut steps) {
                Some(e) => sum += e.weight,
                None => lost += 1,
            }
        }
        let mean = sum / n as f32;
        eprintln!("mean {mean:?}, {lost} lost, {:.1} steps a walk", steps as f64 / n as f64);
        assert!(lost < n / 1000, "{lost} walks reached the cap");
        assert!((mean - Vec3::ONE).abs().max_element() < 0.01, "{mean:?}");
    }

    /// In a semi-infinite medium the walk returns the colour asked for within 5% (the
    /// inversion of Chiang et al. 2016; measured: +2.2%, +1.5%, +1.5%, −3.2%) and, up to
    /// A = 0.8, leaves within 10% of Christensen & Burley 2015's mean distance 2.5 ℓ/s
    /// (measured: +0.4%, −5.2%, +6.1%; at A = 0.95 the walk's is 25% longer, see
    /// docs/accuracy-and-cost.md).
    #[test]
    fn the_half_space_profile_matches_the_albedo_and_burleys_fit() {
        for a in [0.2f32, 0.5, 0.8, 0.95] {
            let m = Interior::new(Vec3::splat(a), Vec3::ONE);
            let n = 40_000;
            let (mut total, mut moment) = (0.0f64, 0.0f64);
            half_space_exits(&m, n, |r, w| {
                total += f64::from(w.x);
                moment += f64::from(w.x * r);
            });
            let (albedo, mean_r) = (total / f64::from(n), moment / total);
            let burley = 2.5 / f64::from(burley_scale(a));
            eprintln!("A = {a}: albedo {albedo:.4}, mean exit radius {mean_r:.3} against Burley's {burley:.3}");
            assert!((albedo / f64::from(a) - 1.0).abs() < 0.05, "A = {a}: {albedo}");
            assert!(a > 0.9 || (mean_r / burley - 1.0).abs() < 0.10, "A = {a}: {mean_r} against {burley}");
        }
    }

    /// Burley's profile integrates to A over the plane (2π r dr), a check on its constants.
    #[test]
    fn burleys_profile_integrates_to_its_albedo() {
        for a in [0.3f32, 0.8] {
            let dr = 1e-3f32;
            let sum: f32 =
                (0..40_000).map(|i| (i as f32 + 0.5) * dr).map(|r| burley_profile(a, 1.0, r) * std::f32::consts::TAU * r * dr).sum();
            assert!((sum / a - 1.0).abs() < 1e-3, "A = {a}: {sum}");
        }
    }

    #[test]
    fn nothing_is_nan_at_tiny_or_huge_free_paths_or_black() {
        for (color, path) in [(Vec3::ONE, 1e-9f32), (Vec3::splat(0.5), 1e6), (Vec3::ZERO, 1.0), (Vec3::new(1.0, 0.0, 0.5), 1e-3)] {
            let m = Interior::new(color, Vec3::splat(path));
            assert!(m.sigma_t.is_finite() && m.albedo.is_finite(), "{m:?}");
            half_space_exits(&m, 200, |r, w| assert!(r.is_finite() && w.is_finite() && w.min_element() >= 0.0, "{r} {w}"));
        }
    }
}
