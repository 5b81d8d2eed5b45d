//! The course's illumination equation for one surface point, term by term.

use super::blinn_phong::blinn_phong_lobe_lanes;
use super::components::{ComponentLanes, Components};
use super::incident::Incident;
use super::material::{Classic, ClassicModel, Material};
use super::phong::phong_lobe_lanes;
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// Evaluates I_tot = L_glob⊗K_amb + L_emi + Σ_k C_spot^k { I_amb^k + v^k d^k (I_diff^k + I_spec^k) }
/// for material `m` with classic model `c`, one term per incident light (v^k its visibility).
///
/// Preconditions: `n` and `v` normalized. Returns the terms separately (see
/// [`Components`]); `counts` receives the number of light and specular evaluations performed.
#[inline(always)]
pub fn shade_classic(
    m: &Material,
    c: &Classic,
    incidents: impl IntoIterator<Item = Incident<f32>>,
    global_ambient: Vec3,
    n: Vec3,
    v: Vec3,
    counts: &mut EvalCounts,
) -> Components {
    shade_classic_lanes::<f32>(m, c, incidents, global_ambient, n.into(), v.into(), true, counts).into()
}

/// [`shade_classic`] for lanes of points: the one formula, lane by lane (see
/// [`crate::simd::lanes`]). Only lanes set in `active` are counted; the others are computed
/// (on valid inputs) and ignored by the caller.
///
/// Each term is added only in lanes where the scalar code adds it (`select(m, c + x, c)`),
/// so every lane gives the bits [`shade_classic`] gives for that point.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn shade_classic_lanes<F: Lanes>(
    m: &Material,
    classic: &Classic,
    incidents: impl IntoIterator<Item = Incident<F>>,
    global_ambient: Vec3,
    n: V3<F>,
    v: V3<F>,
    active: F::Mask,
    counts: &mut EvalCounts,
) -> ComponentLanes<F> {
    let mut c = ComponentLanes {
        emission: V3::splat(m.emission),
        ambient: V3::splat(global_ambient * m.ambient),
        diffuse: V3::zero(),
        specular: V3::zero(),
    };
    let has_specular = classic.has_specular();
    let has_diffuse = classic.diffuse != Vec3::ZERO;
    let zero = F::splat(0.0);
    for inc in incidents {
        counts.lights += F::count(active);
        // C_spot ≤ 0: the light adds nothing here, not even its ambient part.
        let lit = !inc.c_spot.le(zero);
        c.ambient = V3::select_mostly(lit, c.ambient + V3::splat(inc.ambient).scale(inc.c_spot) * V3::splat(m.ambient), c.ambient);
        // Visibility scales the direct terms only (1 unshadowed: the bits without it).
        let w = inc.c_spot * inc.attenuation * inc.visibility;
        let n_dot_l = n.dot(inc.l);
        // Direct terms where the light has a direction (not ambient, not at the point) and N·L > 0.
        let front = active & lit & inc.l.ne_zero() & n_dot_l.gt(zero);
        let lanes_in_front = F::count(front);
        // Unclamped (a lesson's switch): every lane the light reaches, N·L < 0 too.
        let diffuse_lanes = if classic.clamp_n_dot_l { front } else { active & lit & inc.l.ne_zero() };
        let lanes_diffuse = F::count(diffuse_lanes);
        if has_diffuse && lanes_diffuse > 0 {
            counts.diffuse += lanes_diffuse;
            // Lambert: max(N·L, 0) = N·L in these lanes (or N·L as it is, unclamped).
            let x = V3::splat(classic.diffuse).scale(w * n_dot_l) * V3::splat(inc.radiance);
            c.diffuse = V3::select_mostly(diffuse_lanes, c.diffuse + x, c.diffuse);
        }
        if has_specular && lanes_in_front > 0 {
            counts.specular += lanes_in_front;
            let s = match classic.model {
                ClassicModel::Phong => phong_lobe_lanes(n, inc.l, v, classic.shininess),
                ClassicModel::BlinnPhong => blinn_phong_lobe_lanes(n, inc.l, v, classic.shininess),
                ClassicModel::Lambert => zero,
            };
            let x = V3::splat(classic.specular).scale(w * s) * V3::splat(inc.specular);
            c.specular = V3::select_mostly(front, c.specular + x, c.specular);
        }
    }
    c
}

/// The direct part of the course's equation for one white light of unit intensity:
/// I = K_diff (N·L) + K_spec max(R·V, 0)^K_shi (Phong) or max(N·H, 0)^K_shi (Blinn-Phong),
/// zero when N·L ≤ 0. What [`shade_classic`] returns as diffuse + specular for that light
/// (for lobe charts; shading itself goes through the lanes).
///
/// Preconditions: `n`, `l`, `v` normalized.
pub fn classic_intensity(c: &Classic, n: Vec3, l: Vec3, v: Vec3) -> Vec3 {
    let n_dot_l = n.dot(l);
    if n_dot_l <= 0.0 {
        return if c.clamp_n_dot_l { Vec3::ZERO } else { c.diffuse * n_dot_l };
    }
    let s = match c.model {
        ClassicModel::Phong => super::phong::phong(n, l, v, c.shininess),
        ClassicModel::BlinnPhong => super::blinn_phong::blinn_phong(n, l, v, c.shininess),
        ClassicModel::Lambert => 0.0,
    };
    c.diffuse * n_dot_l + c.specular * s
}

/// How much work shading did (summed into the render stats).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EvalCounts {
    /// Light evaluations (one per light per shading point).
    pub lights: u64,
    /// Diffuse-term evaluations (lit side only).
    pub diffuse: u64,
    /// Specular-lobe evaluations.
    pub specular: u64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::incident::directional;
    use crate::shading::material::Model;
    use crate::simd::lanes::MAX_WIDTH;

    /// K_diff = (0.8, 0.4, 0.2), K_spec = 0.5, K_shi = 16, K_amb = 0.2, L_emi = (0, 0, 0.1).
    fn classic(model: ClassicModel) -> Classic {
        Classic { model, diffuse: Vec3::new(0.8, 0.4, 0.2), specular: Vec3::splat(0.5), shininess: 16.0, clamp_n_dot_l: true }
    }

    fn mat(c: Classic) -> Material {
        Material { name: "m".into(), model: Model::Classic(c), ambient: Vec3::splat(0.2), emission: Vec3::new(0.0, 0.0, 0.1) }
    }

    /// Shades material `m` (classic) lit by `incidents`.
    pub(super) fn shade_with(m: &Material, incidents: &[Incident<f32>], amb: Vec3, n: Vec3, v: Vec3, k: &mut EvalCounts) -> Components {
        shade_classic(m, m.classic().unwrap(), incidents.iter().copied(), amb, n, v, k)
    }

    /// Per lane of an incident: L (zero: no direction), d, C_spot and visibility.
    type LaneValues = [(Vec3, f32, f32, f32); MAX_WIDTH];

    /// A light's L_spec in these tests: apart from its L_diff, so a mix-up shows.
    fn spec_of(radiance: Vec3) -> Vec3 {
        radiance * Vec3::new(0.5, 1.0, 2.0)
    }

    /// One incident in lanes from per-lane values, and the same for lane `i` alone.
    fn incident_lanes<F: Lanes>(x: &LaneValues, radiance: Vec3, ambient: Vec3, ambient_only: bool) -> Incident<F> {
        let f = |g: fn(&(Vec3, f32, f32, f32)) -> f32| F::load(&x.map(|x| g(&x)));
        Incident {
            l: V3 { x: f(|x| x.0.x), y: f(|x| x.0.y), z: f(|x| x.0.z) },
            distance: F::splat(f32::INFINITY),
            attenuation: f(|x| x.1),
            inv_r2: F::splat(1.0),
            c_spot: f(|x| x.2),
            visibility: f(|x| x.3),
            radiance,
            specular: spec_of(radiance),
            ambient,
            ambient_only,
        }
    }

    #[test]
    fn an_unclamped_n_dot_l_subtracts_a_light_from_behind_and_only_the_diffuse_term() {
        // A light 60° behind the surface: N·L = -0.5.
        let l_dir = Vec3::new(0.0, 3f32.sqrt() / 2.0, -0.5);
        let light = directional(l_dir, Vec3::splat(2.0), Vec3::splat(0.5));
        let (n, v, mut k) = (Vec3::Z, Vec3::Z, EvalCounts::default());
        let clamped = mat(classic(ClassicModel::Phong));
        let unclamped = mat(Classic { clamp_n_dot_l: false, ..classic(ClassicModel::Phong) });
        let c = shade_with(&clamped, &[light], Vec3::ZERO, n, v, &mut k);
        assert_eq!((c.diffuse, c.specular), (Vec3::ZERO, Vec3::ZERO));
        let u = shade_with(&unclamped, &[light], Vec3::ZERO, n, v, &mut k);
        assert!((u.diffuse - (-0.5 * 2.0) * Vec3::new(0.8, 0.4, 0.2)).length() < 1e-6, "{:?}", u.diffuse);
        assert_eq!((u.specular, u.ambient), (Vec3::ZERO, c.ambient), "only the diffuse term changes");
        // In front, the clamp changes nothing.
        let front = directional(Vec3::new(0.0, 0.6, 0.8), Vec3::ONE, Vec3::ZERO);
        let (a, b) = (shade_with(&clamped, &[front], Vec3::ZERO, n, v, &mut k), shade_with(&unclamped, &[front], Vec3::ZERO, n, v, &mut k));
        assert_eq!((a.diffuse, a.specular), (b.diffuse, b.specular));
        assert_eq!(classic_intensity(unclamped.classic().unwrap(), n, l_dir, v), -0.5 * Vec3::new(0.8, 0.4, 0.2));
    }

    #[test]
    fn equation_term_by_term() {
        let cm = classic(ClassicModel::BlinnPhong);
        let m = mat(cm);
        let l_dir = Vec3::new(0.0, 1.0, 1.0).normalize();
        let light = directional(l_dir, Vec3::splat(2.0), Vec3::splat(0.5));
        let n = Vec3::Z;
        let v = Vec3::Z;
        let mut k = EvalCounts::default();
        let c = shade_with(&m, &[light], Vec3::splat(0.1), n, v, &mut k);
        assert_eq!(c.emission, m.emission);
        assert!((c.ambient - (0.1 * m.ambient + 0.5 * m.ambient)).length() < 1e-6);
        let cos = l_dir.z;
        assert!((c.diffuse - cos * cm.diffuse * 2.0).length() < 1e-6);
        let h = (l_dir + v).normalize();
        assert!((c.specular - h.z.powf(16.0) * cm.specular * 2.0).length() < 1e-5);
        assert_eq!(k, EvalCounts { lights: 1, diffuse: 1, specular: 1 });
    }

    /// [`check_lanes`] at a token's widths, compiled with its features as the strips are.
    #[derive(Clone, Copy)]
    struct CheckLanes;

    impl crate::simd::lanes::LaneTask for CheckLanes {
        type Output = ();
        #[inline(always)]
        fn run<W: Lanes, H: Lanes>(self) {
            check_lanes::<W>();
            check_lanes::<H>();
        }
    }

    /// The lane path is the scalar path: four, eight and sixteen random points shaded at once
    /// give, lane by lane, the bits of shading each alone (every model and exponent path).
    #[test]
    fn every_lane_width_gives_the_scalar_bits() {
        crate::simd::at_every_width(CheckLanes);
    }

    /// Random normals, view vectors and incidents (with a direction or none, ambient only,
    /// C_spot = 0 or not, partly visible), every classic model, exponents from 0 to 1e6: each
    /// lane of `F` gives the bits the scalar formula gives.
    #[inline(always)]
    fn check_lanes<F: Lanes>() {
        let mut r = crate::simd::lanes::test_rng(0x2545_f491_4f6c_dd1d, 1.0);
        // (radiance, L_amb, ambient only) of each incident.
        let kinds = [
            (Vec3::ONE, Vec3::splat(0.1), false),
            (Vec3::new(2.0, 1.5, 1.0), Vec3::ZERO, false),
            (Vec3::splat(3.0), Vec3::splat(0.05), false),
            (Vec3::splat(0.2), Vec3::splat(0.2), true),
        ];
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        for model in [ClassicModel::Lambert, ClassicModel::Phong, ClassicModel::BlinnPhong] {
            for shininess in [0.0, 1e-6, 32.0, 37.5, 1e4, 1e6] {
                let m = mat(Classic { shininess, ..classic(model) });
                for _ in 0..200 {
                    let mut unit = || Vec3::new(r(), r(), r()).normalize_or(Vec3::Z);
                    let nv: [(Vec3, Vec3); MAX_WIDTH] = std::array::from_fn(|_| (unit(), unit()));
                    let values: Vec<LaneValues> = kinds
                        .iter()
                        .map(|&(_, _, ambient_only)| {
                            std::array::from_fn(|_| {
                                let l =
                                    if ambient_only || r() < -0.8 { Vec3::ZERO } else { Vec3::new(r(), r(), r()).normalize_or(Vec3::Z) };
                                let c_spot = if r() < -0.6 { 0.0 } else { r().abs() };
                                (l, r().abs(), c_spot, if r() < 0.0 { 1.0 } else { r().abs() })
                            })
                        })
                        .collect();
                    let load = |f: fn(&(Vec3, Vec3)) -> Vec3| {
                        let v = nv.map(|p| f(&p));
                        V3 { x: F::load(&v.map(|v| v.x)), y: F::load(&v.map(|v| v.y)), z: F::load(&v.map(|v| v.z)) }
                    };
                    let (n, v) = (load(|p| p.0), load(|p| p.1));
                    let incidents = values.iter().zip(&kinds).map(|(x, &(rad, amb, only))| incident_lanes::<F>(x, rad, amb, only));
                    let mut k_lanes = EvalCounts::default();
                    let c =
                        shade_classic_lanes(&m, m.classic().unwrap(), incidents, Vec3::splat(0.1), n, v, F::first(F::WIDTH), &mut k_lanes);
                    let of = |v: V3<F>| {
                        let (mut x, mut y, mut z) = ([0f32; MAX_WIDTH], [0f32; MAX_WIDTH], [0f32; MAX_WIDTH]);
                        v.x.store(&mut x);
                        v.y.store(&mut y);
                        v.z.store(&mut z);
                        std::array::from_fn::<Vec3, MAX_WIDTH, _>(|i| Vec3::new(x[i], y[i], z[i]))
                    };
                    let (e, a, d, s) = (of(c.emission), of(c.ambient), of(c.diffuse), of(c.specular));
                    let mut k1 = EvalCounts::default();
                    for (i, (n, v)) in nv.iter().take(F::WIDTH).enumerate() {
                        let one: Vec<Incident<f32>> = values
                            .iter()
                            .zip(&kinds)
                            .map(|(x, &(radiance, ambient, ambient_only))| {
                                let (l, attenuation, c_spot, visibility) = x[i];
                                let (distance, inv_r2) = (f32::INFINITY, 1.0);
                                let specular = spec_of(radiance);
                                Incident {
                                    l: l.into(),
                                    distance,
                                    attenuation,
                                    inv_r2,
                                    c_spot,
                                    visibility,
                                    radiance,
                                    specular,
                                    ambient,
                                    ambient_only,
                                }
                            })
                            .collect();
                        let c = shade_with(&m, &one, Vec3::splat(0.1), *n, *v, &mut k1);
                        assert_eq!(bits(c.emission), bits(e[i]));
                        assert_eq!(bits(c.ambient), bits(a[i]), "{model:?} {shininess}");
                        assert_eq!(bits(c.diffuse), bits(d[i]), "{model:?} {shininess}");
                        assert_eq!(bits(c.specular), bits(s[i]), "{model:?} {shininess}");
                    }
                    assert_eq!(k1, k_lanes);
                }
            }
        }
    }

    #[test]
    fn classic_intensity_is_the_shaded_direct_light() {
        let l = Vec3::new(-0.5, 0.1, 0.8).normalize();
        for model in [ClassicModel::Lambert, ClassicModel::Phong, ClassicModel::BlinnPhong] {
            let m = mat(classic(model));
            for v in [Vec3::Z, Vec3::new(0.5, 0.0, 0.8).normalize(), Vec3::new(0.3, -0.2, 0.9).normalize()] {
                let c = shade_with(&m, &[directional(l, Vec3::ONE, Vec3::ZERO)], Vec3::ZERO, Vec3::Z, v, &mut EvalCounts::default());
                let i = classic_intensity(m.classic().unwrap(), Vec3::Z, l, v);
                assert!((i - (c.diffuse + c.specular)).abs().max_element() < 1e-6, "{model:?} {v}: {i} vs {c:?}");
            }
        }
        assert_eq!(classic_intensity(&classic(ClassicModel::Phong), Vec3::Z, -l, Vec3::Z), Vec3::ZERO);
    }

    #[test]
    fn lambert_material_never_evaluates_specular() {
        let cm = Classic { specular: Vec3::ZERO, ..classic(ClassicModel::Lambert) };
        let m = mat(cm);
        let light = directional(Vec3::Z, Vec3::ONE, Vec3::ZERO);
        let mut k = EvalCounts::default();
        let c = shade_with(&m, &[light], Vec3::ZERO, Vec3::Z, Vec3::Z, &mut k);
        assert_eq!(c.specular, Vec3::ZERO);
        assert_eq!(k.specular, 0);
        assert!((c.diffuse - cm.diffuse).length() < 1e-6);
    }
}

#[cfg(test)]
mod properties {
    use super::tests::shade_with;
    use super::*;
    use crate::shading::incident::directional;
    use crate::shading::material::Model;

    fn mat(model: ClassicModel, k_amb: Vec3, shininess: f32) -> Material {
        let c = Classic { model, diffuse: Vec3::ONE, specular: Vec3::ONE, shininess, clamp_n_dot_l: true };
        Material { name: "m".into(), model: Model::Classic(c), ambient: k_amb, emission: Vec3::ZERO }
    }
    use proptest::prelude::*;

    fn unit() -> impl Strategy<Value = Vec3> {
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0).prop_filter_map("non-zero", |(x, y, z)| Vec3::new(x, y, z).try_normalize())
    }

    proptest! {
        /// Every term is finite and non-negative for any unit n, l, v and any exponent in range.
        #[test]
        fn terms_are_finite_and_non_negative(n in unit(), l in unit(), v in unit(), k in prop::sample::select(vec![0.0f32, 1e-6, 1.0, 32.0, 1e4, 1e6]), phong in any::<bool>()) {
            let model = if phong { ClassicModel::Phong } else { ClassicModel::BlinnPhong };
            let m = mat(model, Vec3::ONE, k);
            let light = directional(l, Vec3::ONE, Vec3::ONE);
            let c = shade_with(&m, &[light], Vec3::ONE, n, v, &mut EvalCounts::default());
            prop_assert!(c.is_finite());
            for t in [c.ambient, c.diffuse, c.specular] {
                prop_assert!(t.min_element() >= 0.0);
            }
            // The classic terms are bounded by the coefficients: N·L ≤ 1 and the lobe ≤ 1.
            prop_assert!(c.diffuse.max_element() <= 1.0 + 1e-6 && c.specular.max_element() <= 1.0 + 1e-6);
        }
    }

    #[test]
    fn grazing_and_opposite_directions() {
        let m = mat(ClassicModel::BlinnPhong, Vec3::ZERO, 1e6);
        let n = Vec3::Z;
        // Light exactly at grazing (N·L = 0), and l = −v.
        for (l, v) in [(Vec3::X, Vec3::Z), (Vec3::new(1.0, 0.0, 1e-7).normalize(), Vec3::new(-1.0, 0.0, -1e-7).normalize())] {
            let light = directional(l, Vec3::ONE, Vec3::ZERO);
            let c = shade_with(&m, &[light], Vec3::ZERO, n, v, &mut EvalCounts::default());
            assert!(c.is_finite() && c.total().min_element() >= 0.0);
            assert!(c.diffuse.max_element() < 1e-6);
        }
    }
}
