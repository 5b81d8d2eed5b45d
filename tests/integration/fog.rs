//! Fog through the whole renderer against analytic values: the transmittance of an eye ray to
//! a surface at a known distance, the light a surface receives through the medium, the
//! classic blends with radial and view-depth z, exactly no in-scattering in a light's
//! shadow (light shafts), the pass in the plan and the stats, and the same bits for any
//! thread count.

use crate::helpers::{lesson_file, read_png, shadelab};
use shadelab::lesson;
use shadelab::render::plan::{Pass, plan};
use shadelab::render::{Frame, Layer, RenderStats};
use shadelab::scene::build::build;
use shadelab::transport::medium::{FOG_SAMPLES, FOG_STEPS};
use shadelab::transport::visibility::SHADOW_RAYS;
use std::path::Path;

fn render_text(text: &str, sets: &[&str]) -> (Frame, RenderStats) {
    crate::helpers::render_text(text, sets, &[Layer::Total])
}

/// A floor (the plane y = 0, 20 × 20) seen from `h` straight above, 33 × 33 pixels so the
/// centre pixel's ray is the axis; physically based `diffuse`, emission 1, no light, in a
/// `[fog]` of `fog` keys.
fn floor_from_above(h: f64, fog: &str) -> String {
    format!(
        r#"
[camera]
position = [0, {h}, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
fov_deg = 60
size = [33, 33]

[[object]]
shape = "plane"
scale = 10
material = "glow"

[material.glow]
model = "diffuse"
diffuse = 0
emission = 1

[fog]
{fog}
"#
    )
}

/// The pixel (x, y) of a 33 × 33, 60° camera: the tangent of its ray's angle to the axis.
fn tan_off_axis(x: u32, y: u32) -> f64 {
    let t = (30f64).to_radians().tan();
    let (nx, ny) = ((2.0 * (x as f64 + 0.5) / 33.0 - 1.0) * t, (1.0 - 2.0 * (y as f64 + 0.5) / 33.0) * t);
    (nx * nx + ny * ny).sqrt()
}

#[test]
fn an_absorbing_slab_transmits_exactly_e_to_the_minus_sigma_t_d() {
    let (f, st) = render_text(&floor_from_above(3.0, "kind = \"medium\"\nsigma_s = 0\nsigma_a = 0.4"), &[]);
    for (x, y) in [(16, 16), (3, 16), (30, 2), (0, 0)] {
        // The eye distance to the floor along this pixel's ray: h / cos α.
        let d = 3.0 * (1.0 + tan_off_axis(x, y).powi(2)).sqrt();
        let want = (-0.4 * d).exp();
        let got = f.at(Layer::Total, x, y).x as f64;
        assert!((got - want).abs() < 2e-6 * want.max(1.0), "pixel ({x}, {y}): {got} vs e^(−σ_t d) = {want}");
    }
    // σ_s = 0: nothing marched.
    assert_eq!(st.count(FOG_STEPS), 0);
    assert_eq!(st.count(FOG_SAMPLES), 33 * 33);
}

#[test]
fn classic_blends_use_the_eye_distance_or_the_view_depth() {
    let lin = "kind = \"linear\"\nstart = 2\nend = 8\ncolor = 0.25";
    let (radial, _) = render_text(&floor_from_above(3.0, lin), &[]);
    let (depth, _) = render_text(&floor_from_above(3.0, &format!("{lin}\ndistance = \"depth\"")), &[]);
    for (x, y) in [(16, 16), (0, 0), (5, 20)] {
        let r = 3.0 * (1.0 + tan_off_axis(x, y).powi(2)).sqrt();
        for (frame, z) in [(&radial, r), (&depth, 3.0)] {
            let f = ((8.0 - z) / 6.0).clamp(0.0, 1.0);
            let want = f + (1.0 - f) * 0.25;
            let got = frame.at(Layer::Total, x, y).x as f64;
            assert!((got - want).abs() < 2e-6, "pixel ({x}, {y}), z = {z}: {got} vs {want}");
        }
    }
    // exp and exp² at the centre, z = 3.
    let (e, _) = render_text(&floor_from_above(3.0, "kind = \"exp\"\ndensity = 0.2\ncolor = 0"), &[]);
    let (e2, _) = render_text(&floor_from_above(3.0, "kind = \"exp2\"\ndensity = 0.2\ncolor = 0"), &[]);
    assert!((e.at(Layer::Total, 16, 16).x as f64 - (-0.6f64).exp()).abs() < 2e-6);
    assert!((e2.at(Layer::Total, 16, 16).x as f64 - (-0.36f64).exp()).abs() < 2e-6);
}

#[test]
fn a_surface_receives_light_attenuated_by_the_medium() {
    // A white diffuse floor under a point light of I = 10 at h = 2, seen from the light's
    // position: E = I/h² e^(−σ_t h), L = ρ/π E, then e^(−σ_t h) again on the way to the eye.
    let text = floor_from_above(2.0, "kind = \"medium\"\nsigma_s = 0\nsigma_a = 0.3").replace("diffuse = 0\nemission = 1", "diffuse = 1")
        + "\n[[light]]\nkind = \"point\"\nposition = [0, 2, 0]\nintensity = 10\n";
    let (f, _) = render_text(&text, &[]);
    let want = std::f64::consts::FRAC_1_PI * 10.0 / 4.0 * (-0.3f64 * 2.0).exp() * (-0.3f64 * 2.0).exp();
    let got = f.at(Layer::Total, 16, 16).x as f64;
    assert!((got - want).abs() < 1e-5 * want, "{got} vs ρ/π I/h² e^(−2σ_t h) = {want}");
}

/// A narrow spot pointing down from y = 3 with a plate at y = 1 under it; the camera at y = 0
/// looks along −z through the cone below the plate.
const SHAFT: &str = r#"
[camera]
position = [0, 0, 6]
look_at = [0, 0, 0]
size = [32, 32]

[[object]]
shape = "plane"
scale = 2
translate = [0, 1, 0]
material = "m"

[material.m]
model = "diffuse"
diffuse = 0.5

[[light]]
kind = "spot"
position = [0, 3, 0]
direction = [0, -1, 0]
cutoff_deg = 10
intensity = 50

[fog]
kind = "medium"
sigma_s = 0.2
sigma_a = 0.05
steps = 32
"#;

#[test]
fn the_shadowed_part_of_a_cone_scatters_nothing_and_the_plan_says_so() {
    let lesson = lesson::parse(SHAFT, Path::new("t.toml"), &[]).unwrap();
    let scene = build(&lesson).unwrap();
    let p = plan(&scene);
    // One flat object is an occluder in a scattering medium: its shadow in the fog.
    assert_eq!(p.shadows[0].method, Some(shadelab::light::ShadowMethod::Ray));
    let fog = p.passes.iter().find(|s| s.pass == Pass::Fog).unwrap();
    assert!(fog.runs && fog.why.contains("32 steps per sample"), "{}", fog.why);
    // The centre row looks through the cone under the plate: everything there is in its shadow.
    let (shadowed, st) = render_text(SHAFT, &[]);
    let (open, _) = render_text(SHAFT, &["render.shadows=none"]);
    let mid = |f: &Frame| f.at(Layer::Total, 16, 16).x;
    assert_eq!(mid(&shadowed), 0.0, "light scattered from the shadow of the plate");
    assert!(mid(&open) > 1e-3, "without shadows the cone lights the fog: {}", mid(&open));
    assert_eq!(st.passes & Pass::Fog.bit(), Pass::Fog.bit());
    assert_eq!(st.passes, p.running_bits());
    assert_eq!(st.count(FOG_STEPS), 32 * 32 * 32);
    assert!(st.count(SHADOW_RAYS) > 0);
}

#[test]
fn explain_lists_the_fog_pass_and_a_lesson_without_fog_skips_it() {
    let (_dir, path) = lesson_file("shaft.toml", SHAFT);
    let out = shadelab().arg("explain").arg(&path).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.lines().any(|l| l.contains("fog") && l.contains("runs") && l.contains("32 steps per sample × 1024 samples")), "{text}");
    assert!(text.contains("fog: ray-march steps") && text.contains("32768"), "{text}");
    // The same scene without its [fog] table.
    let (_d2, plain) = lesson_file("plain.toml", SHAFT.split("[fog]").next().unwrap());
    let out = shadelab().arg("explain").arg(&plain).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.lines().any(|l| l.contains("fog") && l.contains("skipped") && l.contains("no [fog]")), "{text}");
}

#[test]
fn the_same_bytes_for_one_thread_and_two() {
    let dir = tempfile::tempdir().unwrap();
    let lesson = crate::helpers::lessons_dir().join("26-fog.toml");
    let run = |threads: &str| {
        let out = dir.path().join(format!("t{threads}.png"));
        shadelab()
            .args(["render", "--threads", threads, "--size", "64x64", "--set", "fog.steps=16", "-o"])
            .arg(&out)
            .arg(&lesson)
            .assert()
            .success();
        read_png(&out)
    };
    assert_eq!(run("1").into_raw(), run("2").into_raw());
}

#[test]
fn a_ray_that_hits_nothing_sees_the_skybox_through_the_medium() {
    // A constant sky of radiance 2 behind a purely absorbing medium (σ_a = 0.5): an eye ray
    // that hits nothing is marched to where T = 10⁻⁴ (ln 10⁴ / σ_t = 18.4, inside the cap of
    // 20 × the scene's size), so it sees 2 × 10⁻⁴ of the sky.
    let text = r#"
[camera]
position = [0, 0, 0]
look_at = [0, 0, -1]
fov_deg = 60
size = [9, 9]

[[object]]
shape = "uv_sphere"
translate = [0, 0, -5]
scale = 0.5
material = "m"

[material.m]
model = "diffuse"
diffuse = 0.5

[environment]
kind = "gradient"
zenith = 2
horizon = 2
ground = 2

[fog]
kind = "medium"
sigma_s = 0
sigma_a = 0.5
"#;
    let (f, _) = render_text(text, &[]);
    let corner = f.layer(Layer::Total).unwrap()[0];
    for c in corner.to_array() {
        assert!((c as f64 - 2e-4).abs() < 2e-7, "sky through the fog: {corner}");
    }
}
