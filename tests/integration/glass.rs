//! Glass end to end: η = 1 is invisible, the centre pixel of a glass sphere against the
//! Fresnel terms in closed form, which paths `max_bounces` counts, reflection + transmission
//! = total, dispersion, total internal reflection, no NaN, and the plan.

use crate::helpers::sky_sphere;
use glam::Vec3;
use shadelab::lesson;
use shadelab::render::{self, Layer};
use std::path::Path;

/// The hidden check's geometry ([`sky_sphere`]) in glass, the sky seen behind it.
fn sphere() -> String {
    sky_sphere("background = true", "model = \"glass\"")
}

fn frame(text: &str, sets: &[&str]) -> (render::Frame, render::RenderStats) {
    let sets: Vec<lesson::Override> = sets.iter().map(|s| lesson::Override::parse(s).unwrap()).collect();
    let l = lesson::parse(text, Path::new("t.toml"), &sets).unwrap_or_else(|e| panic!("{e}"));
    let scene = shadelab::scene::build::build(&l).unwrap_or_else(|e| panic!("{e}"));
    render::render(&scene, &[Layer::Total, Layer::Reflection, Layer::Transmission])
}

/// η = 1: no reflection (F = 0), the rays pass straight through both surfaces, so the ball
/// shows exactly the sky behind it, pixel for pixel the render without the ball.
#[test]
fn an_index_of_one_is_invisible() {
    let (glass, _) = frame(&sphere(), &["material.m.ior=1.0"]);
    // The ball made tiny and put behind the camera: the sky alone.
    let (empty, _) = frame(&sphere(), &["object.0.scale=0.000001", "object.0.translate=[0, 0, 100]"]);
    let (a, b) = (glass.layer(Layer::Total).unwrap(), empty.layer(Layer::Total).unwrap());
    let worst = a.iter().zip(&b).map(|(x, y)| (*x - *y).abs().max_element()).fold(0f32, f32::max);
    // Only rounding in the two refractions and the ray offsets: measured 3e-6.
    assert!(worst < 1e-4, "worst {worst}");
    assert!(glass.raw(Layer::Reflection).unwrap().iter().all(|c| *c == Vec3::ZERO));
}

/// The centre pixel sees straight through the centre: F = ((η − 1)/(η + 1))² at entry and
/// exit, the reflection F L(+z) and the twice-refracted (1 − F)² L(−z); +z and −z lie on the
/// horizon (ground set to the horizon's radiance so the step is not at the sample).
/// `max_bounces = 2` counts just those (the independent reference's paths); each further
/// bounce adds the ray reflected once more inside: F(1 − F)² L(+z) (out through the front)
/// with 3, F²(1 − F)² L(−z) with 4.
#[test]
fn the_centre_pixel_has_the_closed_form_fresnel_terms() {
    let horizon = 0.5;
    for (eta, bounces) in [(1.5f32, 1), (1.5, 2), (1.5, 3), (1.5, 4), (2.4, 2)] {
        let sets = [format!("material.m.ior={eta}"), format!("render.max_bounces={bounces}"), "environment.ground=0.5".into()];
        let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
        let (f, _) = frame(&sphere(), &sets);
        let r0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
        let reflected = r0 * horizon;
        let transmitted = match bounces {
            1 => 0.0,
            2 => (1.0 - r0).powi(2) * horizon,
            3 => (1.0 - r0).powi(2) * horizon * (1.0 + r0),
            _ => (1.0 - r0).powi(2) * horizon * (1.0 + r0 + r0 * r0),
        };
        let (r, t) = (f.at(Layer::Reflection, 20, 20), f.at(Layer::Transmission, 20, 20));
        // The tessellated sphere's interpolated normals tilt the rays by about 10⁻³ rad.
        assert!((r - Vec3::splat(reflected)).abs().max_element() < 2e-3, "η {eta}, {bounces} bounces: reflection {r} vs {reflected}");
        assert!((t - Vec3::splat(transmitted)).abs().max_element() < 4e-3, "η {eta}, {bounces} bounces: transmission {t} vs {transmitted}");
        let total = f.at(Layer::Total, 20, 20);
        assert!((total - r - t).abs().max_element() < 1e-5);
    }
}

/// Every pixel finite, at every index including bubbles (total internal reflection) and a
/// thin surface; reflection and transmission sum to the total over the ball.
#[test]
fn no_nan_and_the_layers_sum_to_the_total() {
    for sets in
        [&["material.m.ior=1.5"][..], &["material.m.ior=0.5"], &["material.m.ior=10"], &["material.m.ior=1.5", "material.m.thin=true"]]
    {
        // No skybox: the total outside the ball is 0 too, so the sum holds at every pixel.
        let sets: Vec<&str> = sets.iter().copied().chain(["environment.background=false"]).collect();
        let (f, _) = frame(&sphere(), &sets);
        let (r, t, total) = (f.raw(Layer::Reflection).unwrap(), f.raw(Layer::Transmission).unwrap(), f.raw(Layer::Total).unwrap());
        for (i, ((r, t), total)) in r.iter().zip(t).zip(total).enumerate() {
            assert!(total.is_finite() && total.min_element() >= 0.0, "{sets:?}: pixel {i} {total}");
            assert!((*r + *t - *total).abs().max_element() < 1e-5, "{sets:?}: pixel {i}");
        }
    }
}

/// A bubble (η = 1/1.33) reflects totally beyond θ_c = arcsin(η): near its rim all the light
/// is reflected and none transmitted; inside θ_c light comes through.
#[test]
fn a_bubble_reflects_totally_beyond_the_critical_angle() {
    let (f, _) = frame(&sphere(), &["material.m.ior=0.752"]);
    // Pixel (x, 20)'s ray leaves the camera at α = atan((x + 0.5 − 20.5)/20.5 · tan 15°) and
    // meets the unit sphere at sin θ_i = 4 sin α; θ_c = 48.8° is sin θ_i = 0.752 (x ≈ 35.2).
    let centre = f.at(Layer::Transmission, 20, 20);
    // (1 − F)² L(−z) with F = 2%: L(−z) on the horizon, half-way down the step to the ground.
    assert!(centre.min_element() > 0.2, "{centre}");
    for x in [36, 37, 38] {
        // sin θ_i ≈ 0.79, 0.84 and 0.89: beyond θ_c.
        let t = f.at(Layer::Transmission, x, 20);
        assert_eq!(t, Vec3::ZERO, "pixel {x}");
        assert!(f.at(Layer::Reflection, x, 20).min_element() > 0.1);
    }
}

/// Dispersion: one path per channel; with equal channels it is the scalar render exactly.
#[test]
fn dispersion_traces_each_channel_and_equal_channels_change_nothing() {
    let (scalar, _) = frame(&sphere(), &["material.m.ior=1.5"]);
    let (same, _) = frame(&sphere(), &["material.m.ior=[1.5, 1.5, 1.5]"]);
    assert_eq!(scalar, same);
    let (spread, _) = frame(&sphere(), &["material.m.ior=[1.3, 1.5, 1.7]"]);
    let (red, _) = frame(&sphere(), &["material.m.ior=1.3"]);
    let (blue, _) = frame(&sphere(), &["material.m.ior=1.7"]);
    for y in 0..41 {
        for x in 0..41 {
            let c = spread.at(Layer::Total, x, y);
            assert_eq!((c.x, c.y, c.z), (red.at(Layer::Total, x, y).x, scalar.at(Layer::Total, x, y).y, blue.at(Layer::Total, x, y).z));
        }
    }
}

/// The plan runs the refraction pass only for drawn glass, and says why.
#[test]
fn the_plan_runs_refraction_for_glass_only() {
    use shadelab::render::plan::Pass;
    let (_, stats) = frame(&sphere(), &[]);
    assert!(stats.passes & Pass::Refraction.bit() != 0);
    let text = sphere().replace("model = \"glass\"", "model = \"mirror\"");
    let (_, stats) = frame(&text, &[]);
    assert_eq!(stats.passes & Pass::Refraction.bit(), 0);
    let l = lesson::parse(&sphere(), Path::new("t.toml"), &[]).unwrap();
    let scene = shadelab::scene::build::build(&l).unwrap();
    let step = render::plan(&scene).passes.into_iter().find(|s| s.pass == Pass::Refraction).unwrap();
    assert!(step.runs && step.why.contains("glass `m` (η = 1.5)") && step.why.contains("up to 8 bounces"), "{}", step.why);
}
