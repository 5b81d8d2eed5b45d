//! A random walk in a slab of scattering and absorbing matter: why diffuse reflection is
//! coloured and nearly Lambertian (the course's lecture on scattering and absorption).
//!
//! Light enters a plane-parallel slab, flies free paths of mean 1 (optical units: σ_t = 1),
//! scatters isotropically, and at each event keeps the fraction ω_c of channel c (the
//! single-scattering albedo; the rest is absorbed). The paths are the same for every
//! channel, so a walk that leaves after n events carries ω_cⁿ: the long walks lose the
//! absorbed wavelengths, and what leaves is coloured. Isotropic scattering in a
//! plane-parallel medium needs only the depth and the direction's cosine.
//!
//! The reference is Chandrasekhar's (1960, ch. IV): for a half-space of isotropic
//! scatterers lit at μ₀ = cos θ₀, the plane albedo is 1 − H(μ₀)√(1 − ω) and the reflected
//! radiance is proportional to H(μ)H(μ₀)/(μ + μ₀), with H his H-function ([`h_function`]).

use crate::geometry::sampling::hash3;
use glam::Vec3;
use rayon::prelude::*;

/// Exit-angle bins, equal in sin²θ: equal projected solid angle, so a Lambertian exit
/// fills them evenly.
pub const BINS: usize = 18;
/// Scattering events counted one by one; walks leaving after more are counted in the last.
pub const EVENTS: usize = 4096;
/// A walk is cut after this many events (its weight is reported as `lost`).
pub const MAX_EVENTS: u32 = 1 << 16;
/// Groups of the exit distribution by the events before leaving: 1, 2–9, 10 or more.
pub const GROUPS: [(u32, u32); 3] = [(1, 1), (2, 9), (10, u32::MAX)];
/// Below this largest channel weight a walk plays Russian roulette: it survives with
/// probability weight/[`ROULETTE`], its weights divided by that probability (unbiased; the
/// long walks of ω close to 1 then cost a few steps more instead of thousands).
const ROULETTE: f64 = 0.05;
/// The roulette's numbers: a stream apart from the free paths' and the directions'.
const ROULETTE_STREAM: u32 = 0x9e37_79b9;
/// Walks per parallel chunk: the chunks' sums are added in order (the same bits on any
/// thread count).
const CHUNK: u32 = 2048;

/// The slab walked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slab {
    /// Single-scattering albedo ω per channel, in [0, 1].
    pub albedo: Vec3,
    /// cos θ₀ of the incident beam, in (0, 1].
    pub cos_incidence: f64,
    /// Optical thickness (`None`: a half-space).
    pub thickness: Option<f64>,
}

/// What the walks measured, as fractions of the incident energy.
#[derive(Debug, Clone, PartialEq)]
pub struct SlabWalk {
    /// Walks traced.
    pub walks: u32,
    /// Reflected energy per channel (the slab's directional albedo).
    pub reflected: [f64; 3],
    /// Energy per channel leaving through the bottom of a finite slab.
    pub transmitted: [f64; 3],
    /// Energy per channel still walking at [`MAX_EVENTS`] (neither reflected nor absorbed).
    pub lost: [f64; 3],
    /// Reflected energy per channel by the events before leaving: entry n − 1 for n events,
    /// the last entry for [`EVENTS`] or more.
    pub by_events: Vec<[f64; 3]>,
    /// Reflected energy (luminance) per [`GROUPS`] entry and exit bin (bin k: sin²θ in [k, k + 1)/[`BINS`]).
    pub exits: [[f64; BINS]; 3],
}

/// Rec. 709 luminance of per-channel values.
fn luminance(c: [f64; 3]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// A uniform number in [0, 1) from walk `w`, draw `k` (24 bits, exact in f64).
fn uniform(w: u32, k: u32, seed: u32) -> f64 {
    (hash3(w, k, seed) >> 8) as f64 / (1u32 << 24) as f64
}

impl SlabWalk {
    /// The exit bin's relative radiance for group `g` (`None`: all groups): its share of the
    /// group's reflected energy times [`BINS`], 1 for a Lambertian exit in every bin.
    pub fn relative_radiance(&self, g: Option<usize>) -> [f64; BINS] {
        let mut bins = [0.0; BINS];
        for (i, row) in self.exits.iter().enumerate() {
            if g.is_none_or(|g| g == i) {
                for (b, v) in bins.iter_mut().zip(row) {
                    *b += v;
                }
            }
        }
        let total: f64 = bins.iter().sum();
        if total > 0.0 {
            bins.iter_mut().for_each(|b| *b *= BINS as f64 / total);
        }
        bins
    }

    /// The exit angle θ (degrees) at the middle of bin `k` (in sin²θ).
    pub fn bin_angle(k: usize) -> f64 {
        ((k as f64 + 0.5) / BINS as f64).sqrt().asin().to_degrees()
    }

    /// Luminance share of the reflected energy that left after each group's events.
    pub fn group_shares(&self) -> [f64; 3] {
        let sums = self.exits.map(|row| row.iter().sum::<f64>());
        let total: f64 = sums.iter().sum();
        sums.map(|s| if total > 0.0 { s / total } else { 0.0 })
    }
}

/// Walks `walks` paths into `slab` (seeded by `seed`): deterministic, the same numbers on
/// every thread count.
pub fn walk(slab: &Slab, walks: u32, seed: u32) -> SlabWalk {
    let chunks: Vec<SlabWalk> = (0..walks.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let range = c * CHUNK..((c + 1) * CHUNK).min(walks);
            let mut acc = empty(range.len() as u32);
            for w in range {
                walk_one(slab, w, seed, &mut acc);
            }
            acc
        })
        .collect();
    let mut out = empty(walks);
    for c in &chunks {
        for ch in 0..3 {
            out.reflected[ch] += c.reflected[ch];
            out.transmitted[ch] += c.transmitted[ch];
            out.lost[ch] += c.lost[ch];
        }
        for (o, v) in out.by_events.iter_mut().zip(&c.by_events) {
            (0..3).for_each(|ch| o[ch] += v[ch]);
        }
        for (o, v) in out.exits.iter_mut().zip(&c.exits) {
            o.iter_mut().zip(v).for_each(|(o, v)| *o += v);
        }
    }
    let n = walks.max(1) as f64;
    let scale = |v: &mut [f64; 3]| v.iter_mut().for_each(|x| *x /= n);
    scale(&mut out.reflected);
    scale(&mut out.transmitted);
    scale(&mut out.lost);
    out.by_events.iter_mut().for_each(scale);
    out.exits.iter_mut().flatten().for_each(|x| *x /= n);
    out
}

fn empty(walks: u32) -> SlabWalk {
    SlabWalk {
        walks,
        reflected: [0.0; 3],
        transmitted: [0.0; 3],
        lost: [0.0; 3],
        by_events: vec![[0.0; 3]; EVENTS],
        exits: [[0.0; BINS]; 3],
    }
}

/// One walk, added to `acc` (unnormalized).
fn walk_one(slab: &Slab, w: u32, seed: u32, acc: &mut SlabWalk) {
    let albedo = [slab.albedo.x as f64, slab.albedo.y as f64, slab.albedo.z as f64];
    let (mut z, mut mu) = (0.0f64, slab.cos_incidence);
    let mut weight = [1.0f64; 3];
    let mut events = 0u32;
    loop {
        // A free path of mean 1 (1 − u in (0, 1]: the logarithm stays finite).
        let s = -(1.0 - uniform(w, 2 * events, seed)).ln();
        z += s * mu;
        if z < 0.0 {
            // Left through the top, travelling at cos θ = −μ from the normal.
            (0..3).for_each(|c| acc.reflected[c] += weight[c]);
            let slot = (events as usize).clamp(1, EVENTS) - 1;
            (0..3).for_each(|c| acc.by_events[slot][c] += weight[c]);
            let sin2 = (1.0 - mu * mu).clamp(0.0, 1.0);
            let bin = ((sin2 * BINS as f64) as usize).min(BINS - 1);
            let group = GROUPS.iter().position(|&(lo, hi)| (lo..=hi).contains(&events)).unwrap_or(0);
            acc.exits[group][bin] += luminance(weight);
            return;
        }
        if slab.thickness.is_some_and(|t| z > t) {
            (0..3).for_each(|c| acc.transmitted[c] += weight[c]);
            return;
        }
        events += 1;
        (0..3).for_each(|c| weight[c] *= albedo[c]);
        let top = weight.iter().copied().fold(0.0, f64::max);
        if top < ROULETTE {
            let survive = top / ROULETTE;
            if top == 0.0 || uniform(w, events, seed ^ ROULETTE_STREAM) >= survive {
                return;
            }
            (0..3).for_each(|c| weight[c] /= survive);
        }
        if events >= MAX_EVENTS {
            (0..3).for_each(|c| acc.lost[c] += weight[c]);
            return;
        }
        // Isotropic: the new direction's cosine is uniform in [−1, 1].
        mu = 2.0 * uniform(w, 2 * events - 1, seed) - 1.0;
    }
}

/// Chandrasekhar's H-function for isotropic scattering of albedo `albedo` at `mu`, from the
/// integral equation 1/H(μ) = √(1 − ω) + (ω/2) ∫₀¹ μ′ H(μ′)/(μ + μ′) dμ′ (Chandrasekhar
/// 1960, eq. IV.(55)), iterated on 64 Gauss-Legendre nodes to 1e-12.
/// The nodes are fixed, so the quadrature's error is below 1e-4 near μ = 0, less elsewhere.
pub fn h_function(albedo: f64, mu: f64) -> f64 {
    let rule: Vec<(f64, f64)> = crate::shading::brdf::gauss_legendre(64).into_iter().map(|(x, w)| (0.5 * (x + 1.0), 0.5 * w)).collect();
    let root = (1.0 - albedo).max(0.0).sqrt();
    let at = |mu: f64, h: &[f64]| 1.0 / (root + 0.5 * albedo * rule.iter().zip(h).map(|(&(m, w), h)| w * m * h / (mu + m)).sum::<f64>());
    let mut h = vec![1.0; rule.len()];
    for _ in 0..10_000 {
        // The geometric mean of two iterates: the plain iteration at ω = 1 swaps H and H/c
        // for 1/c forever (the equation fixes H's scale only through the product).
        let next: Vec<f64> = rule.iter().zip(&h).map(|(&(m, _), old)| (at(m, &h) * old).sqrt()).collect();
        let change = next.iter().zip(&h).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        h = next;
        if change < 1e-12 {
            break;
        }
    }
    at(mu, &h)
}

/// The plane albedo of a half-space of isotropic scatterers lit at `cos_incidence`:
/// 1 − H(μ₀)√(1 − ω) (Chandrasekhar 1960, eq. IV.(63)).
pub fn half_space_albedo(albedo: f64, cos_incidence: f64) -> f64 {
    1.0 - h_function(albedo, cos_incidence) * (1.0 - albedo).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slab(albedo: f32, mu: f64) -> Slab {
        Slab { albedo: Vec3::splat(albedo), cos_incidence: mu, thickness: None }
    }

    #[test]
    fn h_function_matches_chandrasekhars_table() {
        // Chandrasekhar 1960 (ω₀ = 1): H(0) = 1 and H(1) = 2.9078 (table XI); the moments
        // ∫ H dμ = 2 and ∫ μ H dμ = 2/√3 (eqs. V.(13), V.(28)).
        for (mu, h) in [(0.0, 1.0), (1.0, 2.9078)] {
            let got = h_function(1.0, mu);
            assert!((got - h).abs() < 2e-3, "H({mu}) = {got}, table {h}");
        }
        let rule = crate::shading::brdf::gauss_legendre(32);
        let moment =
            |k: i32| rule.iter().map(|&(x, w)| 0.5 * w * (0.5 * (x + 1.0)).powi(k) * h_function(1.0, 0.5 * (x + 1.0))).sum::<f64>();
        assert!((moment(0) - 2.0).abs() < 1e-3, "{}", moment(0));
        assert!((moment(1) - 2.0 / 3f64.sqrt()).abs() < 1e-3, "{}", moment(1));
        // ω = 0: no scattering, H = 1 and the albedo is 0.
        assert!((h_function(0.0, 0.7) - 1.0).abs() < 1e-12);
        assert!(half_space_albedo(0.0, 0.7).abs() < 1e-12);
    }

    #[test]
    fn the_walk_reflects_the_exact_albedo_of_a_half_space() {
        for (omega, mu) in [(0.9f32, 1.0), (0.6, 1.0), (0.99, 0.5)] {
            let r = walk(&slab(omega, mu), 100_000, 7);
            let exact = half_space_albedo(omega as f64, mu);
            // 100 000 walks: the standard error is below 0.0015.
            assert!((r.reflected[0] - exact).abs() < 0.006, "ω = {omega}, μ₀ = {mu}: walk {} vs {exact}", r.reflected[0]);
            assert_eq!(r.transmitted, [0.0; 3]);
        }
    }

    #[test]
    fn single_scattering_is_lommel_seeliger_and_many_events_are_nearly_lambertian() {
        let r = walk(&slab(1.0, 1.0), 200_000, 3);
        // Once-scattered light: albedo (ω/2)(1 − μ₀ ln(1 + 1/μ₀)) = (1 − ln 2)/2 at μ₀ = 1.
        let once = r.by_events[0][0];
        let exact = 0.5 * (1.0 - 2f64.ln());
        assert!((once - exact).abs() < 0.004, "{once} vs {exact}");
        // ... with radiance ∝ 1/(μ + μ₀): twice as bright at the horizon as along the normal.
        let single = r.relative_radiance(Some(0));
        assert!(single[BINS - 1] > 1.7 * single[0], "{single:?}");
        // All of it, ω = 1: ∝ H(μ)/(μ + μ₀) (Chandrasekhar), within the bins' noise.
        let all = r.relative_radiance(None);
        let shape: Vec<f64> = (0..BINS)
            .map(|k| {
                let mu = SlabWalk::bin_angle(k).to_radians().cos();
                h_function(1.0, mu) / (mu + 1.0)
            })
            .collect();
        let mean = shape.iter().sum::<f64>() / BINS as f64;
        for k in 0..BINS - 1 {
            let want = shape[k] / mean;
            assert!((all[k] - want).abs() < 0.06, "bin {k}: walk {} vs {want}", all[k]);
        }
        // Energy: what is not reflected is still walking at the cut (ω = 1 absorbs nothing).
        assert!((r.reflected[0] + r.lost[0] - 1.0).abs() < 1e-9, "{:?} {:?}", r.reflected, r.lost);
        assert!(r.lost[0] < 0.01);
    }

    #[test]
    fn channels_share_the_paths_and_a_thin_slab_transmits() {
        let coloured = Slab { albedo: Vec3::new(0.99, 0.9, 0.6), cos_incidence: 1.0, thickness: None };
        let r = walk(&coloured, 50_000, 1);
        assert!(r.reflected[0] > r.reflected[1] && r.reflected[1] > r.reflected[2], "{:?}", r.reflected);
        // The same bits whatever the thread count.
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap().install(|| walk(&coloured, 50_000, 1));
        assert_eq!(one, r);
        // A slab of optical thickness 0.1 lets e^{−0.1} of the beam through unscattered, and more.
        let thin = walk(&Slab { thickness: Some(0.1), ..slab(1.0, 1.0) }, 50_000, 2);
        assert!(thin.transmitted[0] > (-0.1f64).exp() - 0.01, "{:?}", thin.transmitted);
        assert!((thin.reflected[0] + thin.transmitted[0] + thin.lost[0] - 1.0).abs() < 1e-9);
    }
}
