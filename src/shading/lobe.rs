//! Lobes, parts and importance sampling: pbrt-v4's BxDF interface (`Flags`, `f`, `Sample_f`,
//! `PDF`) for the physically based BRDFs, and the delta lobes of mirror and glass.
//!
//! **Lobes.** [`Brdf::lobes`] lists a model's lobes, each with a [`LobeKind`] (after pbrt-v4's
//! `BxDFFlags`: diffuse, glossy, or a Dirac delta in reflection or transmission) and a
//! **weight**: an RGB estimate of the lobe's albedo that does not depend on the directions.
//! The weights serve three purposes, and are the one split of a BRDF into parts that other
//! modules should use (DESIGN.md, "One BRDF interface"):
//! 1. choosing a lobe when sampling, with probability ∝ the mean of its weight's channels
//!    ([`LobeSet::probabilities`]; the mean, not the luminance, so a blue lobe under a white
//!    one is not starved);
//! 2. the diffuse reflectance ρ of the material for radiosity and ambient-like uses
//!    ([`LobeSet::weight`] of [`Part::Diffuse`]);
//! 3. the diffuse albedo of the split sum.
//!
//! A weight is 0 only when the lobe's f is 0 for every pair of directions, so choosing by weight
//! never leaves a lobe with f > 0 unsampled (which would bias every estimate that uses [`Brdf::pdf`]).
//!
//! **Parts.** Each non-delta lobe belongs to a [`Part`], the layer of the frame that shows it:
//! [`Part::Diffuse`] (diffuse lobes) or [`Part::Specular`] (glossy lobes). [`Brdf::eval_part`]
//! evaluates one part; [`Brdf::eval_parts`] both at once: the frame's diffuse and specular
//! layers (`shading::physical`), and the one split every user of a BRDF's parts reads
//! (radiosity's reflectance, the split sum's diffuse albedo, the plan's terms). The parts sum
//! to [`Brdf::eval`] up to the rounding of the sum's order (exactly for every model but the
//! principled one, whose `eval` adds its four sub-lobes in another order).
//!
//! | model | lobes (kind: weight) | diffuse part | specular part |
//! | --- | --- | --- | --- |
//! | diffuse | diffuse: ρ | ρ/π | 0 |
//! | oren_nayar | diffuse: ρ | the whole f | 0 |
//! | cook_torrance | diffuse: ρ; glossy: k_s ⊗ F̄ | ρ/π | k_s D G F/(4 (n·l)(n·v)) |
//! | principled | diffuse: (1 − m)(C + sheen C_sheen s̄); glossy (specular): C_spec0 + (1 − C_spec0)/21; glossy (clearcoat): 0.25 clearcoat (0.04 + 0.96/21) | Disney diffuse with the subsurface blend, and sheen | GGX specular and clearcoat |
//! | normalized_phong, normalized_blinn_phong | diffuse: k_d; glossy: k_s | k_d/π | the k_s lobe |
//!
//! F̄ = F(1) + (1 − F(1))/21 is Schlick's cosine-weighted hemispherical average 2∫F(c) c dc
//! applied to the model's F through its normal-incidence value ([`Fresnel::average`](super::microfacet::Fresnel::average));
//! s̄ = [`SHEEN_ALBEDO`]. The details are in each model's file.
//!
//! **Sampling.** [`Brdf::sample`] chooses lobe i with probability P_i by `u_lobe`, draws l
//! from that lobe's strategy with `u`, and returns f = [`Brdf::eval`] (cosine excluded) and the
//! pdf of the whole mixture, p(l) = Σ_i P_i p_i(l) = [`Brdf::pdf`] (Veach 1997, §9.2.1, the
//! "one-sample model"; pbrt-v4 and Mitsuba 3 do the same). The estimate f cos θ_l / p is
//! then unbiased whichever lobe produced l. A strategy may reflect l below the surface: the
//! sample is lost (`None`), and ∫ p dω over the upper hemisphere is below 1 by exactly the
//! lost fraction. `None` also when v.z ≤ 0 (the BRDFs are one-sided) or when every weight is 0
//! (a black material, whose f is 0 everywhere: nothing to sample). [`Brdf::pdf`] is 0 for
//! v.z ≤ 0 or l.z ≤ 0.
//!
//! The BRDFs have no delta lobes: α is clamped to [`ALPHA_MIN`](super::microfacet::ALPHA_MIN)
//! as in `eval`, so a roughness of 0 gives a needle lobe with a finite pdf. Mirror and glass
//! are pure deltas and have their own `sample` returning a [`DeltaSample`].

use super::brdf::Brdf;
use super::physical::Lobes;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// What a lobe is (pbrt-v4's `BxDFFlags` for one lobe), and so which layer of the frame shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LobeKind {
    /// Diffuse reflection, wide and sampled by the cosine (the `diffuse` layer).
    Diffuse,
    /// Glossy reflection about the mirror direction, a microfacet or Phong lobe (the `specular` layer).
    Glossy,
    /// Perfectly specular reflection, a Dirac delta (mirror, glass; the `reflection` layer).
    DeltaReflection,
    /// Perfectly specular transmission, a Dirac delta (glass; the `transmission` layer).
    DeltaTransmission,
}

impl LobeKind {
    /// True for the Dirac deltas, which `eval` and `pdf` cannot represent.
    pub fn is_delta(self) -> bool {
        matches!(self, LobeKind::DeltaReflection | LobeKind::DeltaTransmission)
    }

    /// True when light leaves on the other side of the surface.
    pub fn is_transmission(self) -> bool {
        self == LobeKind::DeltaTransmission
    }

    /// The part of f it belongs to; `None` for the delta lobes (reflection, transmission layers).
    pub fn part(self) -> Option<Part> {
        match self {
            LobeKind::Diffuse => Some(Part::Diffuse),
            LobeKind::Glossy => Some(Part::Specular),
            LobeKind::DeltaReflection | LobeKind::DeltaTransmission => None,
        }
    }
}

/// A part of f(l, v): the diffuse and specular layers of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The diffuse lobes.
    Diffuse,
    /// The glossy lobes.
    Specular,
}

impl Part {
    /// Both parts, in the frame's order.
    pub const ALL: [Part; 2] = [Part::Diffuse, Part::Specular];
}

/// One lobe: its kind and its albedo estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lobe {
    /// What it is.
    pub kind: LobeKind,
    /// RGB albedo estimate, independent of the directions (module docs).
    pub weight: Vec3,
}

impl Lobe {
    /// A lobe of `kind` with albedo estimate `weight`.
    pub const fn new(kind: LobeKind, weight: Vec3) -> Lobe {
        Lobe { kind, weight }
    }
}

/// The most lobes a model has (principled: diffuse, specular, clearcoat).
pub const MAX_LOBES: usize = 3;

/// A model's lobes in a fixed order (the index a model's sampling understands), without allocation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LobeSet {
    lobes: [Lobe; MAX_LOBES],
    len: usize,
}

impl LobeSet {
    /// The set of `lobes` (at most [`MAX_LOBES`]; more is a bug in the model and panics).
    pub fn new(lobes: &[Lobe]) -> LobeSet {
        assert!(lobes.len() <= MAX_LOBES, "a model has at most {MAX_LOBES} lobes");
        let mut all = [Lobe::new(LobeKind::Diffuse, Vec3::ZERO); MAX_LOBES];
        all[..lobes.len()].copy_from_slice(lobes);
        LobeSet { lobes: all, len: lobes.len() }
    }

    /// The lobes, in the model's order.
    pub fn as_slice(&self) -> &[Lobe] {
        &self.lobes[..self.len]
    }

    /// Sum of the weights of the lobes of `part`: the part's albedo estimate (for
    /// [`Part::Diffuse`], the diffuse reflectance ρ radiosity and ambient light see).
    pub fn weight(&self, part: Part) -> Vec3 {
        self.as_slice().iter().filter(|l| l.kind.part() == Some(part)).map(|l| l.weight).sum()
    }

    /// True when `part` has a lobe with a non-zero weight, i.e. can be non-zero.
    pub fn has(&self, part: Part) -> bool {
        self.weight(part) != Vec3::ZERO
    }

    /// The probability of choosing each lobe: the mean of its weight's channels (negative
    /// channels as 0) over the sum of them; `None` when every weight is 0.
    pub fn probabilities(&self) -> Option<[f32; MAX_LOBES]> {
        let mut p = [0.0; MAX_LOBES];
        let mut total = 0.0;
        for (pi, lobe) in p.iter_mut().zip(self.as_slice()) {
            // The channels' sum: their mean up to the factor 3, which cancels in the ratio.
            *pi = lobe.weight.max(Vec3::ZERO).element_sum();
            total += *pi;
        }
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        Some(p.map(|x| x / total))
    }

    /// The lobe `u` in [0, 1) chooses (inverting the cumulative [`probabilities`](Self::probabilities));
    /// `None` when every weight is 0.
    pub fn choose(&self, u: f32) -> Option<usize> {
        self.choose_by(&self.probabilities()?, u)
    }

    /// [`choose`](Self::choose) with the [`probabilities`](Self::probabilities) `p` already known.
    #[inline]
    fn choose_by(&self, p: &[f32; MAX_LOBES], u: f32) -> Option<usize> {
        let mut cdf = 0.0;
        let mut last = None;
        for (i, &pi) in p[..self.len].iter().enumerate() {
            if pi > 0.0 {
                cdf += pi;
                last = Some(i);
                if u < cdf {
                    return last;
                }
            }
        }
        // u at or above the rounded total: the last lobe that can be chosen.
        last
    }
}

/// The hemispherical average of the sheen lobe's F_H = (1 − l·h)⁵: ∫∫ F_H cos θ_l cos θ_v dω_l dω_v / π,
/// by quadrature (0.01158; at normal incidence ∫ F_H cos θ_l dω_l is only 2.6e-4, at grazing it is larger).
pub const SHEEN_ALBEDO: f32 = 0.01158;

/// A direction drawn from a BRDF, with everything an estimator needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BrdfSample {
    /// The direction towards the light, unit, local frame, l.z > 0.
    pub l: Vec3,
    /// f(l, v) = [`Brdf::eval`]`(l, v)` in 1/sr, cosine excluded.
    pub f: Vec3,
    /// The pdf of the whole mixture at l (1/sr) = [`Brdf::pdf`]`(v, l)`, > 0.
    pub pdf: f32,
    /// Index in [`Brdf::lobes`] of the lobe that drew l.
    pub lobe: usize,
    /// Its kind.
    pub kind: LobeKind,
    /// True for a Dirac delta (never for a [`Brdf`]: α is clamped above 0).
    pub delta: bool,
}

impl BrdfSample {
    /// The estimator's weight f cos θ_l / p.
    pub fn weight(&self) -> Vec3 {
        self.f * (self.l.z / self.pdf)
    }
}

/// A direction drawn from a Dirac delta lobe (mirror, glass): the weight replaces f and the pdf.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeltaSample {
    /// The outgoing direction, unit, local frame (below the surface for a refraction).
    pub l: Vec3,
    /// The factor on the radiance arriving along l: f cos θ_l / p with the delta integrated out.
    pub weight: Vec3,
    /// The probability with which this lobe was chosen (1 when there is one).
    pub probability: f32,
    /// [`LobeKind::DeltaReflection`] or [`LobeKind::DeltaTransmission`].
    pub kind: LobeKind,
}

/// Cosine-weighted hemisphere (Malley's method), the strategy of every diffuse lobe: l for
/// u in [0, 1)², or `None` on the rim (u on the border of the square, a pdf of 0).
#[inline]
pub fn sample_cosine(u: Vec2) -> Option<Vec3> {
    let l = crate::geometry::sampling::cosine_hemisphere(u);
    (l.z > 0.0).then_some(l)
}

/// The pdf cos θ_l/π of [`sample_cosine`]; 0 for l.z ≤ 0.
#[inline]
pub fn cosine_pdf(l: Vec3) -> f32 {
    l.z.max(0.0) * FRAC_1_PI
}

impl Brdf {
    /// The lobes with their kinds and albedo estimates (module docs and each model's file).
    #[inline]
    pub fn lobes(&self) -> LobeSet {
        match self {
            Brdf::Diffuse(m) => m.lobes(),
            Brdf::CookTorrance(m) => m.lobes(),
            Brdf::OrenNayar(m) => m.lobes(),
            Brdf::Principled(m) => m.lobes(),
            Brdf::NormalizedPhong(m) => m.lobes(),
            Brdf::NormalizedBlinnPhong(m) => m.lobes(),
        }
    }

    /// f(l, v) split into its diffuse and specular parts (local frame; 1/sr, cosine excluded).
    ///
    /// The split of the module docs; both zero when l.z ≤ 0 or v.z ≤ 0. The frame's layers are
    /// these values.
    #[inline]
    pub fn eval_parts(&self, l: Vec3, v: Vec3) -> Lobes {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Lobes::default();
        }
        match self {
            Brdf::Diffuse(_) | Brdf::OrenNayar(_) => Lobes { diffuse: self.eval(l, v), specular: Vec3::ZERO },
            Brdf::CookTorrance(m) => Lobes { diffuse: m.eval_diffuse(l, v), specular: m.eval_specular(l, v) },
            Brdf::Principled(m) => {
                let p = m.eval_lobes(l, v);
                Lobes { diffuse: p.diffuse + p.sheen, specular: p.specular + p.clearcoat }
            }
            Brdf::NormalizedPhong(m) => {
                Lobes { diffuse: m.diffuse * FRAC_1_PI, specular: m.specular * super::normalized_phong::phong_lobe(l, v, m.shininess) }
            }
            Brdf::NormalizedBlinnPhong(m) => Lobes {
                diffuse: m.diffuse * FRAC_1_PI,
                specular: m.specular * super::normalized_phong::blinn_phong_lobe(l, v, m.shininess),
            },
        }
    }

    /// One part of f(l, v) (1/sr, cosine excluded): the [`eval_parts`](Self::eval_parts) field of `part`.
    #[inline]
    pub fn eval_part(&self, part: Part, l: Vec3, v: Vec3) -> Vec3 {
        let parts = self.eval_parts(l, v);
        match part {
            Part::Diffuse => parts.diffuse,
            Part::Specular => parts.specular,
        }
    }

    /// A direction l drawn for the viewer at unit `v` (local frame), `u_lobe` choosing the
    /// lobe and `u` the direction (both in [0, 1)); `None` for v.z ≤ 0, a black material, or a
    /// direction the chosen strategy reflected below the surface (module docs).
    #[inline]
    pub fn sample(&self, v: Vec3, u_lobe: f32, u: Vec2) -> Option<BrdfSample> {
        // A NaN viewer samples nothing either (v.z > 0 is false for NaN).
        if v.z.is_nan() || v.z <= 0.0 {
            return None;
        }
        let prepared = self.prepare();
        let (l, pdf, lobe) = prepared.sample_direction(v, u_lobe, u)?;
        Some(BrdfSample { l, f: self.eval(l, v), pdf, lobe, kind: prepared.lobes.as_slice()[lobe].kind, delta: false })
    }

    /// The BRDF with its lobes' probabilities worked out, for many [`pdf`](Self::pdf)s and
    /// samples at one point (they do not depend on the directions).
    #[inline]
    pub fn prepare(&self) -> PreparedBrdf<'_> {
        let lobes = self.lobes();
        PreparedBrdf { brdf: self, lobes, probabilities: lobes.probabilities() }
    }

    /// The solid-angle pdf (1/sr) with which [`sample`](Self::sample) returns `l` seen from
    /// `v` (note the order: viewer first, as pbrt's `PDF(wo, wi)`): Σ_i P_i p_i(l); 0 when
    /// v.z ≤ 0, l.z ≤ 0 or the material is black.
    #[inline]
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        if !(v.z > 0.0 && l.z > 0.0) {
            return 0.0;
        }
        self.prepare().pdf(v, l)
    }

    /// Draws l from lobe `lobe`'s own strategy (`None`: below the surface or degenerate).
    #[inline]
    fn sample_lobe(&self, lobe: usize, v: Vec3, u: Vec2) -> Option<Vec3> {
        match self {
            Brdf::Diffuse(_) | Brdf::OrenNayar(_) => sample_cosine(u),
            Brdf::CookTorrance(m) => m.sample_lobe(lobe, v, u),
            Brdf::Principled(m) => m.sample_lobe(lobe, v, u),
            Brdf::NormalizedPhong(m) => m.sample_lobe(lobe, v, u),
            Brdf::NormalizedBlinnPhong(m) => m.sample_lobe(lobe, v, u),
        }
    }

    /// The pdf of lobe `lobe`'s strategy at l. Preconditions: l.z > 0, v.z > 0.
    #[inline]
    fn lobe_pdf(&self, lobe: usize, v: Vec3, l: Vec3) -> f32 {
        match self {
            Brdf::Diffuse(_) | Brdf::OrenNayar(_) => cosine_pdf(l),
            Brdf::CookTorrance(m) => m.lobe_pdf(lobe, v, l),
            Brdf::Principled(m) => m.lobe_pdf(lobe, v, l),
            Brdf::NormalizedPhong(m) => m.lobe_pdf(lobe, v, l),
            Brdf::NormalizedBlinnPhong(m) => m.lobe_pdf(lobe, v, l),
        }
    }
}

/// A [`Brdf`] with its lobes and their probabilities computed once ([`Brdf::prepare`]): the
/// same [`pdf`](Self::pdf) and directions as the BRDF's own, bit for bit, without
/// recomputing the weights (a conductor's F(1), say) for every sample.
#[derive(Debug, Clone, Copy)]
pub struct PreparedBrdf<'a> {
    brdf: &'a Brdf,
    lobes: LobeSet,
    probabilities: Option<[f32; MAX_LOBES]>,
}

impl PreparedBrdf<'_> {
    /// [`Brdf::pdf`]`(v, l)`.
    #[inline]
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        if !(v.z > 0.0 && l.z > 0.0) {
            return 0.0;
        }
        let Some(p) = self.probabilities else { return 0.0 };
        let mut sum = 0.0;
        for (i, &pi) in p.iter().enumerate() {
            if pi > 0.0 {
                sum += pi * self.brdf.lobe_pdf(i, v, l);
            }
        }
        sum.min(f32::MAX)
    }

    /// The direction, pdf and lobe of [`Brdf::sample`]`(v, u_lobe, u)`, without evaluating f
    /// (for estimators that evaluate it elsewhere).
    #[inline]
    pub fn sample_direction(&self, v: Vec3, u_lobe: f32, u: Vec2) -> Option<(Vec3, f32, usize)> {
        // A NaN viewer samples nothing either (v.z > 0 is false for NaN).
        if v.z.is_nan() || v.z <= 0.0 {
            return None;
        }
        let lobe = self.lobes.choose_by(self.probabilities.as_ref()?, u_lobe)?;
        let l = self.brdf.sample_lobe(lobe, v, u)?;
        if l.z.is_nan() || l.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf(v, l);
        if pdf.is_nan() || pdf <= 0.0 {
            return None; // only on the rim of a lobe's support, a set of measure 0
        }
        Some((l, pdf, lobe))
    }
}

#[cfg(test)]
mod tests {
    use super::super::sampling_tests::{all_cases, uniform};
    use super::*;

    /// The body of `Brdf::pdf` before [`PreparedBrdf`], kept verbatim.
    fn pdf_before(brdf: &Brdf, v: Vec3, l: Vec3) -> f32 {
        if !(v.z > 0.0 && l.z > 0.0) {
            return 0.0;
        }
        let Some(p) = brdf.lobes().probabilities() else { return 0.0 };
        let mut sum = 0.0;
        for (i, &pi) in p.iter().enumerate() {
            if pi > 0.0 {
                sum += pi * brdf.lobe_pdf(i, v, l);
            }
        }
        sum.min(f32::MAX)
    }

    /// The body of `Brdf::sample` before [`PreparedBrdf`], kept verbatim.
    fn sample_before(brdf: &Brdf, v: Vec3, u_lobe: f32, u: Vec2) -> Option<BrdfSample> {
        if v.z.is_nan() || v.z <= 0.0 {
            return None;
        }
        let lobes = brdf.lobes();
        let lobe = lobes.choose(u_lobe)?;
        let l = brdf.sample_lobe(lobe, v, u)?;
        if l.z.is_nan() || l.z <= 0.0 {
            return None;
        }
        let pdf = pdf_before(brdf, v, l);
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        Some(BrdfSample { l, f: brdf.eval(l, v), pdf, lobe, kind: lobes.as_slice()[lobe].kind, delta: false })
    }

    /// A direction on the sphere from two uniforms, sometimes exactly at the pole or the horizon.
    fn direction(k: u32, seed: u32) -> Vec3 {
        match k % 11 {
            0 => Vec3::Z,
            1 => Vec3::X,
            _ => {
                let z = 2.0 * uniform(k, seed, 1) - 1.0;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = std::f32::consts::TAU * uniform(k, seed, 2);
                Vec3::new(r * phi.cos(), r * phi.sin(), z)
            }
        }
    }

    #[test]
    fn a_prepared_brdf_gives_the_pdfs_and_samples_of_before_bit_for_bit() {
        let bits = |x: Vec3| x.to_array().map(f32::to_bits);
        let black = ("black", Brdf::Diffuse(super::super::diffuse::Diffuse { albedo: Vec3::ZERO }));
        for (name, brdf) in all_cases().into_iter().chain([black]) {
            let prepared = brdf.prepare();
            for k in 0..3000 {
                let (v, l) = (direction(k, 1), direction(k, 2));
                let want = pdf_before(&brdf, v, l).to_bits();
                assert_eq!(brdf.pdf(v, l).to_bits(), want, "{name}: pdf at v {v:?}, l {l:?}");
                assert_eq!(prepared.pdf(v, l).to_bits(), want, "{name}: prepared pdf at v {v:?}, l {l:?}");
                let u_lobe = if k % 13 == 0 { 1.0 - f32::EPSILON / 2.0 } else { uniform(k, 3, 0) };
                let u = Vec2::new(uniform(k, 4, 0), uniform(k, 5, 0));
                let before = sample_before(&brdf, v, u_lobe, u);
                let now = brdf.sample(v, u_lobe, u);
                let direction_only = prepared.sample_direction(v, u_lobe, u);
                assert_eq!(before.is_some(), now.is_some(), "{name}: sample at v {v:?}");
                assert_eq!(before.is_some(), direction_only.is_some(), "{name}: direction at v {v:?}");
                if let (Some(a), Some(b), Some((l, pdf, lobe))) = (before, now, direction_only) {
                    assert!(bits(a.l) == bits(b.l) && bits(a.f) == bits(b.f) && a.pdf.to_bits() == b.pdf.to_bits(), "{name}");
                    assert!(a.lobe == b.lobe && a.kind == b.kind, "{name}");
                    assert!(bits(a.l) == bits(l) && a.pdf.to_bits() == pdf.to_bits() && a.lobe == lobe, "{name}");
                }
            }
        }
    }
}
