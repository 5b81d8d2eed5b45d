//! BRDF charts of a lesson's materials: lobes in the plane of incidence and albedo curves.

use super::plot::{Chart, Series, line_chart, polar_distribution, polar_lobe_labelled};
use super::text::to_plain_text;
use crate::lesson::i18n::Lang;
use crate::light::{LightKind, Spot};
use crate::shading::brdf::{Brdf, directional_albedo};
use crate::shading::classic::classic_intensity;
use crate::shading::cook_torrance::Terms;
use crate::shading::material::Classic;
use glam::Vec3;
use rayon::prelude::*;

/// Rec. 709 luminance, one curve per material.
fn luminance(c: Vec3) -> f64 {
    (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) as f64
}

/// A material as a lobe chart plots it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Plotted {
    /// A physically based BRDF: r = f·cos θ_o.
    Brdf(Brdf),
    /// A classic model of the course: r = I(θ_o), the course's direct term for a white light
    /// of unit intensity at θ_i, K_diff (N·L) + K_spec max(R·V, 0)^K_shi (or max(N·H, 0)^K_shi);
    /// no normalization, no cos θ_o.
    Classic(Classic),
}

/// What a lobe chart draws besides the whole lobe of each material.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LobeOptions {
    /// Draw each curve a second time with l and v exchanged in f (Helmholtz reciprocity).
    pub swap: bool,
    /// Cook-Torrance partial products to draw instead of the whole f (empty: the whole f).
    pub terms: Vec<Terms>,
    /// Azimuths φ_o − φ_i of the outgoing slices, in degrees (empty: the plane of incidence).
    pub azimuth: Vec<f64>,
}

/// The lobe of `brdf` lit from the left at `incidence` degrees: points r (sin θ_o, cos θ_o)
/// with r = f·cos θ_o (luminance), θ_o from −90° to 90° in 0.25° steps.
pub fn lobe_points(brdf: &Brdf, incidence: f64) -> Vec<(f64, f64)> {
    lobe_points_of(&Plotted::Brdf(*brdf), incidence, false, None)
}

/// The lobe of `m` lit from the left at `incidence` degrees, θ_o from −90° to 90° in 0.25°
/// steps, as points r (sin θ_o, cos θ_o) (luminance):
///
/// * a BRDF: r = f(l, v)·cos θ_o, or with `terms` the Cook-Torrance partial product
///   k_s D [G] [F] / (4 (n·l)(n·v)) · cos θ_o (other models ignore `terms`);
/// * a classic model: r = I = f_c(l, v)·cos θ_i, where f_c = I/(N·L) is the BRDF the course's
///   equation implies.
///
/// `swap` exchanges l and v in f and keeps the weight (cos θ_o, resp. cos θ_i): a reciprocal
/// f, f(l, v) = f(v, l), draws the same curve. The swapped classic f_c(v, l) = I(v, l)/cos θ_o
/// diverges at the horizon, where it is drawn as 0.
pub fn lobe_points_of(m: &Plotted, incidence: f64, swap: bool, terms: Option<Terms>) -> Vec<(f64, f64)> {
    lobe_slice(m, incidence, 0.0, swap, terms)
}

/// [`lobe_points_of`] in the slice through the normal at `azimuth` degrees (φ_o − φ_i) from
/// the plane of incidence: the light stays at (θ_i, φ_i = 180°), the outgoing direction runs
/// over θ_o in the plane at φ_o = azimuth (its negative half at azimuth + 180°). A BRDF has
/// four angles; the plane of incidence (azimuth 0) is one slice of them.
pub fn lobe_slice(m: &Plotted, incidence: f64, azimuth: f64, swap: bool, terms: Option<Terms>) -> Vec<(f64, f64)> {
    let i = incidence.to_radians() as f32;
    let l = Vec3::new(-i.sin(), 0.0, i.cos());
    let cos_i = incidence.to_radians().cos();
    let (sin_p, cos_p) = (azimuth.to_radians().sin() as f32, azimuth.to_radians().cos() as f32);
    (0..=720)
        .map(|k| (-90.0 + 180.0 * k as f64 / 720.0).to_radians())
        .map(|t| {
            let v = Vec3::new(t.sin() as f32 * cos_p, t.sin() as f32 * sin_p, t.cos() as f32);
            let (a, b) = if swap { (v, l) } else { (l, v) };
            let r = match m {
                Plotted::Brdf(brdf) => {
                    let f = match (brdf, terms) {
                        (Brdf::CookTorrance(ct), Some(terms)) => ct.eval_terms(a, b, terms),
                        _ => brdf.eval(a, b),
                    };
                    luminance(f) * t.cos()
                }
                Plotted::Classic(c) if !swap => luminance(classic_intensity(c, Vec3::Z, l, v)),
                // f_c(v, l)·cos θ_i = I(v, l)·cos θ_i / cos θ_o.
                Plotted::Classic(c) if t.cos() > 1e-6 => luminance(classic_intensity(c, Vec3::Z, v, l)) * cos_i / t.cos(),
                Plotted::Classic(_) => 0.0,
            };
            (r * t.sin(), r * t.cos())
        })
        .collect()
}

/// The distribution C_spot(θ) of a spot light, θ from −90° to 90° in 0.25° steps: points
/// I(θ) (sin θ, cos θ) with I the profile or cos^L_exp θ, 0 outside the cutoff.
pub fn distribution_points(light: &LightKind) -> Vec<(f64, f64)> {
    let LightKind::Spot(Spot { exponent, cos_cutoff, profile, .. }) = *light else { return Vec::new() };
    (-360..=360)
        .map(|k| {
            let theta = (k as f64 * 0.25).to_radians();
            let cos = theta.cos() as f32;
            let i = if cos < cos_cutoff || cos <= 0.0 {
                0.0
            } else {
                match profile {
                    Some(p) => p.at((k as f32 * 0.25).abs()),
                    None => cos.min(1.0).powf(exponent),
                }
            } as f64;
            (i * theta.sin(), i * theta.cos())
        })
        .collect()
}

/// Polar distributions of named spot lights.
///
/// # Errors
/// A message when plotters fails.
pub fn distribution_chart(lights: &[(String, LightKind)], title: &str, lang: Lang) -> Result<Chart, String> {
    let series: Vec<Series> = lights.iter().map(|(label, l)| Series { label: label.clone(), points: distribution_points(l) }).collect();
    polar_distribution(&series, &to_plain_text(title), (900, 520), lang)
}

/// Polar lobes of named BRDFs at the given angles of incidence (degrees, in [0, 90)).
///
/// # Errors
/// A message from the chart backend.
pub fn lobe_chart(brdfs: &[(String, Brdf)], incidence: &[f64], title: &str, lang: Lang) -> Result<Chart, String> {
    let plotted: Vec<(String, Plotted)> = brdfs.iter().map(|(n, b)| (n.clone(), Plotted::Brdf(*b))).collect();
    lobe_chart_of(&plotted, incidence, &LobeOptions::default(), title, lang)
}

/// Polar lobes of named materials (BRDFs or classic models) at the given angles of incidence
/// (degrees, in [0, 90)): per material, per angle, per term, the lobe and (with `swap`) the
/// lobe with l and v exchanged, labelled `… l ↔ v`.
///
/// # Errors
/// A message from the chart backend.
pub fn lobe_chart_of(
    materials: &[(String, Plotted)],
    incidence: &[f64],
    opts: &LobeOptions,
    title: &str,
    lang: Lang,
) -> Result<Chart, String> {
    let mut series = Vec::new();
    let terms: Vec<Option<Terms>> = if opts.terms.is_empty() { vec![None] } else { opts.terms.iter().copied().map(Some).collect() };
    let azimuths = if opts.azimuth.is_empty() { vec![0.0] } else { opts.azimuth.clone() };
    for (name, m) in materials {
        for i in incidence {
            for phi in &azimuths {
                for t in &terms {
                    let mut label = to_plain_text(name);
                    if let Some(t) = t {
                        label = format!("{label}: {}", t.product());
                    }
                    if incidence.len() > 1 {
                        label = format!("{label}, θᵢ = {i}°");
                    }
                    if azimuths.len() > 1 {
                        label = format!("{label}, φ = {phi}°");
                    }
                    series.push(Series { label: label.clone(), points: lobe_slice(m, *i, *phi, false, *t) });
                    if opts.swap {
                        series.push(Series { label: format!("{label}, l ↔ v"), points: lobe_slice(m, *i, *phi, true, *t) });
                    }
                }
            }
        }
    }
    let classic = materials.iter().any(|(_, m)| matches!(m, Plotted::Classic(_)));
    let physical = materials.iter().any(|(_, m)| matches!(m, Plotted::Brdf(_)));
    let x_label = match (classic, physical) {
        (true, true) => "f·cos θₒ (BRDFs), I (classic)  (towards the mirror side →)",
        (true, false) => "I, the course's equation for a unit light  (towards the mirror side →)",
        _ => "f·cos θₒ  (towards the mirror side →)",
    };
    polar_lobe_labelled(&series, incidence, &to_plain_text(title), x_label, (900, 520), lang)
}

/// Directional albedo (largest channel) against the angle of incidence, 0° to 88° every 2°,
/// with the worst integration error bound in the note.
///
/// # Errors
/// A message from the chart backend.
pub fn albedo_chart(brdfs: &[(String, Brdf)], samples: usize, title: &str, lang: Lang) -> Result<Chart, String> {
    let mut series = Vec::new();
    let (mut worst, mut top) = (0.0f64, 1.0f64);
    for (name, b) in brdfs {
        // Each angle is an independent quadrature: in parallel, collected in order.
        let values: Vec<(f64, f64, f64)> = (0..=44)
            .into_par_iter()
            .map(|i| {
                let deg = 2.0 * i as f64;
                let (a, e) = directional_albedo(b, deg.to_radians().cos(), samples);
                (deg, a, e)
            })
            .collect();
        for &(_, a, e) in &values {
            worst = worst.max(e);
            top = top.max(a);
        }
        series.push(Series { label: to_plain_text(name), points: values.iter().map(|&(d, a, _)| (d, a)).collect() });
    }
    let note =
        format!("largest channel; integration error bound ≤ {worst:.1e} (Gauss-Legendre, {samples} vs {} nodes per panel)", 2 * samples);
    line_chart(
        &series,
        &to_plain_text(title),
        "angle of incidence θᵢ (degrees)",
        "albedo",
        (0.0, 90.0),
        (0.0, top * 1.1),
        Some(&note),
        (900, 520),
        lang,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::cook_torrance::CookTorrance;
    use crate::shading::material::ClassicModel;
    use crate::shading::microfacet::Masking;
    use crate::shading::normalized_phong::NormalizedPhong;

    /// Radius and angle from the normal (degrees, positive towards the mirror side) of each point.
    fn polar(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
        points.iter().map(|(x, y)| (x.hypot(*y), x.atan2(*y).to_degrees())).collect()
    }

    fn classic(model: ClassicModel, diffuse: f32, specular: f32, shininess: f32) -> Plotted {
        Plotted::Classic(Classic { model, diffuse: Vec3::splat(diffuse), specular: Vec3::splat(specular), shininess, clamp_n_dot_l: true })
    }

    #[test]
    fn classic_phong_peaks_at_the_mirror_direction_with_k_spec_plus_diffuse() {
        let m = classic(ClassicModel::Phong, 0.2, 0.8, 10.0);
        let points = polar(&lobe_points_of(&m, 45.0, false, None));
        let (r, at) = points.iter().copied().fold((0.0, 0.0), |a, p| if p.0 > a.0 { p } else { a });
        assert!((at - 45.0).abs() < 0.3, "peak at {at}°");
        let expect = 0.8 + 0.2 * 45f64.to_radians().cos();
        assert!((r - expect).abs() < 1e-5, "{r} vs {expect}");
        // The diffuse term alone far from the lobe: K_diff cos θ_i, whatever θ_o.
        let (r, _) = points[40];
        assert!((r - 0.2 * 45f64.to_radians().cos()).abs() < 1e-4, "{r}");
        // Blinn-Phong peaks at the mirror direction too, with the same value.
        let b = polar(&lobe_points_of(&classic(ClassicModel::BlinnPhong, 0.2, 0.8, 10.0), 45.0, false, None));
        let (rb, _) = b[540];
        assert!((rb - expect).abs() < 1e-5, "{rb}");
    }

    #[test]
    fn slices_out_of_the_plane_of_incidence_shrink_and_the_one_across_it_is_symmetric() {
        let phong = Plotted::Brdf(Brdf::NormalizedPhong(NormalizedPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess: 10.0 }));
        let lambert = Plotted::Brdf(Brdf::Diffuse(crate::shading::diffuse::Diffuse { albedo: Vec3::ONE }));
        let peak = |m: &Plotted, phi: f64| polar(&lobe_slice(m, 45.0, phi, false, None)).iter().map(|p| p.0).fold(0.0, f64::max);
        // Azimuth 0 is the plane of incidence, as before; 180 is its mirror image.
        assert_eq!(lobe_slice(&phong, 45.0, 0.0, false, None), lobe_points_of(&phong, 45.0, false, None));
        let (a, b) = (lobe_slice(&phong, 45.0, 0.0, false, None), lobe_slice(&phong, 45.0, 180.0, false, None));
        for (p, q) in a.iter().zip(b.iter().rev()) {
            assert!((p.0 + q.0).abs() < 1e-5 && (p.1 - q.1).abs() < 1e-5, "{p:?} against {q:?}");
        }
        // The lobe is centred on the mirror direction, in the plane of incidence: every slice
        // away from it is smaller; the one across it is symmetric about the normal.
        let peaks: Vec<f64> = [0.0, 30.0, 60.0, 90.0].iter().map(|phi| peak(&phong, *phi)).collect();
        assert!(peaks.windows(2).all(|w| w[1] < w[0]), "{peaks:?}");
        let across = lobe_slice(&phong, 45.0, 90.0, false, None);
        for (p, q) in across.iter().zip(across.iter().rev()) {
            assert!((p.0 + q.0).abs() < 1e-5 && (p.1 - q.1).abs() < 1e-5);
        }
        // Lambert's slice is the same semicircle, ρ/π cos θ_o, whatever the azimuth.
        for phi in [0.0, 45.0, 90.0] {
            assert!((peak(&lambert, phi) - std::f64::consts::FRAC_1_PI).abs() < 1e-6);
        }
    }

    #[test]
    fn swapping_l_and_v_changes_only_the_non_reciprocal_model() {
        let reciprocal = Plotted::Brdf(Brdf::NormalizedPhong(NormalizedPhong {
            diffuse: Vec3::splat(0.1),
            specular: Vec3::splat(0.3),
            shininess: 20.0,
        }));
        let (a, b) = (lobe_points_of(&reciprocal, 30.0, false, None), lobe_points_of(&reciprocal, 30.0, true, None));
        for (p, q) in a.iter().zip(&b) {
            assert!((p.0 - q.0).abs() <= 1e-6 && (p.1 - q.1).abs() <= 1e-6, "{p:?} vs {q:?}");
        }
        let ggx = Plotted::Brdf(Brdf::CookTorrance(CookTorrance::default()));
        for t in [None, Some(Terms::D), Some(Terms::Dg), Some(Terms::Dgf)] {
            let (a, b) = (lobe_points_of(&ggx, 60.0, false, t), lobe_points_of(&ggx, 60.0, true, t));
            for (p, q) in a.iter().zip(&b) {
                let r = p.0.hypot(p.1);
                assert!((p.0 - q.0).abs() <= 1e-5 * (1.0 + r) && (p.1 - q.1).abs() <= 1e-5 * (1.0 + r), "{t:?}: {p:?} vs {q:?}");
            }
        }
        // The course's Phong read as a BRDF, I/(N·L): equal at the mirror direction, apart elsewhere.
        let phong = classic(ClassicModel::Phong, 0.0, 1.0, 20.0);
        let (a, b) = (polar(&lobe_points_of(&phong, 30.0, false, None)), polar(&lobe_points_of(&phong, 30.0, true, None)));
        assert!((a[480].0 - b[480].0).abs() < 1e-6, "mirror: {:?} vs {:?}", a[480], b[480]);
        // θ_o = 50°: swapped is larger by cos 30°/cos 50°.
        let ratio = 30f64.to_radians().cos() / 50f64.to_radians().cos();
        assert!((b[560].0 / a[560].0 - ratio).abs() < 1e-4, "{} vs {ratio}", b[560].0 / a[560].0);
        assert!(b.iter().all(|p| p.0.is_finite()));
    }

    #[test]
    fn d_g_never_exceeds_d() {
        for masking in Masking::ALL {
            let ggx = Plotted::Brdf(Brdf::CookTorrance(CookTorrance { masking, ..CookTorrance::default() }));
            for incidence in [0.0, 45.0, 80.0, 89.0] {
                let d = polar(&lobe_points_of(&ggx, incidence, false, Some(Terms::D)));
                let dg = polar(&lobe_points_of(&ggx, incidence, false, Some(Terms::Dg)));
                let dgf = polar(&lobe_points_of(&ggx, incidence, false, Some(Terms::Dgf)));
                for k in 0..d.len() {
                    assert!(dg[k].0 <= d[k].0 * (1.0 + 1e-6) + 1e-12, "{masking:?} {incidence} {k}");
                    assert!(dgf[k].0 <= dg[k].0 * (1.0 + 1e-5) + 1e-12, "{masking:?} {incidence} {k}");
                }
                // At grazing light G takes a visible part away.
                if incidence == 80.0 && masking != Masking::CookTorrance {
                    let (sd, sdg): (f64, f64) = (d.iter().map(|p| p.0).sum(), dg.iter().map(|p| p.0).sum());
                    assert!(sdg < 0.8 * sd, "{masking:?}: {sdg} vs {sd}");
                }
            }
        }
        // The whole f with terms = DGF and no diffuse term is the plain lobe.
        let ggx = Plotted::Brdf(Brdf::CookTorrance(CookTorrance::default()));
        assert_eq!(lobe_points_of(&ggx, 30.0, false, Some(Terms::Dgf)), lobe_points_of(&ggx, 30.0, false, None));
    }
}
