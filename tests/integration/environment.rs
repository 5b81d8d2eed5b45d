//! Environment maps end to end: the white furnace, the gradient sky's closed forms, the
//! skybox, rotation, mirrors (of the sky and of the scene), determinism and the plan.

use crate::helpers::{lesson_file, shadelab, sky_sphere};
use glam::Vec3;
use shadelab::lesson;
use shadelab::render::{self, Layer};
use std::path::Path;

fn frame(text: &str, sets: &[&str]) -> render::Frame {
    let sets: Vec<lesson::Override> = sets.iter().map(|s| lesson::Override::parse(s).unwrap()).collect();
    let l = lesson::parse(text, Path::new("t.toml"), &sets).unwrap_or_else(|e| panic!("{e}"));
    let scene = shadelab::scene::build::build(&l).unwrap_or_else(|e| panic!("{e}"));
    render::render(&scene, &[Layer::Total, Layer::Reflection]).0
}

/// [`sky_sphere`] of `material`.
fn with(material: &str) -> String {
    sky_sphere("", material)
}

/// The white furnace: a constant environment L lights a Lambert sphere to ρL everywhere.
#[test]
fn white_furnace_lambert_sphere_is_rho_l_everywhere() {
    let text = with("model = \"diffuse\"\ndiffuse = 0.8");
    let f = frame(
        &text,
        &[
            "environment.background=false",
            "environment.zenith=1.5",
            "environment.horizon=1.5",
            "environment.ground=1.5",
            "render.env_samples=1024",
        ],
    );
    let (mut n, mut worst) = (0, 0f32);
    for y in 0..41 {
        for x in 0..41 {
            let i = (y * 41 + x) as usize;
            if f.coverage[i] < 1.0 {
                continue;
            }
            let c = f.raw(Layer::Total).unwrap()[i];
            worst = worst.max(((c - Vec3::splat(1.2)) / 1.2).abs().max_element());
            n += 1;
        }
    }
    // 1024 samples a point: the measured worst pixel is 1.3 % off (Monte Carlo noise).
    assert!(n > 300 && worst < 0.03, "{n} pixels, worst relative error {worst}");
}

/// Looking straight down at the sphere's top, the point faces the zenith: L_o = ρ (h + 2(z − h)/3).
#[test]
fn the_gradient_sky_lights_the_top_of_a_lambert_sphere_as_its_closed_form() {
    let text = with("model = \"diffuse\"\ndiffuse = 1.0");
    let f = frame(&text, &["camera.position=[0, 4, 0]", "camera.up=[0, 0, -1]", "render.env_samples=4096"]);
    let c = f.at(Layer::Total, 20, 20).x;
    let want = 0.5 + 2.0 * 1.5 / 3.0;
    assert!((c - want).abs() < 0.015 * want, "{c} against {want}");
}

/// The skybox: a pixel beside the sphere shows the environment along its camera ray, and
/// `background = false` shows the camera's background colour instead.
#[test]
fn the_background_is_the_sky_along_each_camera_ray() {
    let text = with("model = \"diffuse\"");
    let f = frame(&text, &[]);
    // Pixel (20, 0): the ray leaves upwards at (15° − half a pixel) above −z: L = h + (z − h) sin(elevation).
    let elevation = (((1.0 - 2.0 * 0.5 / 41.0) * 15f64.to_radians().tan()).atan()) as f32;
    let want = 0.5 + 1.5 * elevation.sin();
    let got = f.at(Layer::Total, 20, 0).x;
    assert!((got - want).abs() < 2e-3, "{got} against {want}");
    let plain = frame(&text, &["environment.background=false", "camera.background=[0.3, 0, 0]"]);
    assert_eq!(plain.at(Layer::Total, 20, 0), Vec3::new(0.3, 0.0, 0.0));
}

/// A mirror sphere's centre reflects the ray straight back: tint ⊗ L(+z) = tint × horizon
/// (the ground set to the horizon's radiance: +z lies on the horizon, where the sky's step to
/// the ground is spread over one texel row).
#[test]
fn a_mirror_sphere_reflects_the_sky_behind_the_camera() {
    let f = frame(&with("model = \"mirror\"\ntint = [1, 0.5, 0.25]"), &["environment.ground=0.5"]);
    let c = f.at(Layer::Reflection, 20, 20);
    // The tessellated sphere's interpolated normal tilts r by about 10⁻³ rad, up the sky's
    // slope of 1.5 per unit of d.y: measured 0.5023 instead of 0.5.
    assert!((c - Vec3::new(0.5, 0.25, 0.125)).abs().max_element() < 4e-3, "{c:?}");
}

/// A mirror shows other objects: a mirror wall facing the camera reflects an emitting sphere
/// behind the camera, which the camera does not see directly.
#[test]
fn a_mirror_reflects_the_scene() {
    let text = r#"
[camera]
position = [0, 0, 4]
fov_deg = 20
size = [21, 21]

[[object]]
shape = "plane"
rotate_deg = [90, 0, 0]
scale = 10
material = "glass"

[[object]]
shape = "uv_sphere"
translate = [0, 0, 7]
material = "lamp"

[material.glass]
model = "mirror"
tint = 0.9

[material.lamp]
model = "diffuse"
diffuse = 0
emission = [2, 1, 0.5]

[environment]
kind = "gradient"
zenith = 0.1
horizon = 0.1
ground = 0.1
"#;
    let f = frame(text, &[]);
    let c = f.at(Layer::Total, 10, 10);
    assert!((c - 0.9 * Vec3::new(2.0, 1.0, 0.5)).abs().max_element() < 1e-4, "{c:?}");
    // A corner pixel's ray misses the lamp: the mirrored sky.
    let corner = f.at(Layer::Total, 0, 0);
    assert!((corner - Vec3::splat(0.09)).abs().max_element() < 1e-4, "{corner:?}");
}

/// Turning the sky by 360° changes no bit; by 90° it moves the sky.
#[test]
fn rotating_the_sky_by_360_degrees_is_the_identity() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("sky.hdr");
    let img = image::Rgb32FImage::from_fn(64, 32, |x, y| image::Rgb([x as f32 / 8.0, y as f32 / 16.0, 0.5]));
    image::DynamicImage::ImageRgb32F(img).save(&map).unwrap();
    let text = "[camera]\nposition = [0, 0, 4]\nsize = [48, 32]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[material.m]\nmodel = \"mirror\"\n[environment]\nmap = \"sky.hdr\"\n";
    let path = dir.path().join("t.toml");
    let load = |deg: &str| {
        let l = lesson::parse(text, &path, &[lesson::Override::parse(&format!("environment.rotate_deg={deg}")).unwrap()]).unwrap();
        render::render(&shadelab::scene::build::build(&l).unwrap(), &[Layer::Total]).0
    };
    assert_eq!(load("0").raw(Layer::Total), load("360").raw(Layer::Total));
    assert_eq!(load("-90").raw(Layer::Total), load("270").raw(Layer::Total));
    assert_ne!(load("0").raw(Layer::Total), load("90").raw(Layer::Total));
}

/// Image-based lighting is hashed per point: the same bytes on one thread and on four.
#[test]
fn environment_lighting_is_the_same_for_any_thread_count() {
    let (_dir, path) = lesson_file("t.toml", &with("model = \"cook_torrance\"\nroughness = 0.5\ndiffuse = 0.3"));
    let run = |threads: &str| {
        let out = tempfile::tempdir().unwrap();
        let png = out.path().join("a.png");
        shadelab().args(["render", "--threads", threads, "-o"]).arg(&png).arg(&path).assert().success();
        std::fs::read(&png).unwrap()
    };
    assert_eq!(run("1"), run("4"));
}

/// `explain` lists the environment pass, and it runs only when a material needs it.
#[test]
fn the_plan_runs_the_environment_pass_only_for_materials_it_lights() {
    let (_dir, path) = lesson_file("t.toml", &with("model = \"diffuse\""));
    let out = shadelab().arg("explain").arg(&path).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("environment light") && text.contains("1024×512 map"), "{text}");
    let classic = lesson::parse(&with("model = \"lambert\""), Path::new("t.toml"), &[]).unwrap();
    let plan = render::plan(&shadelab::scene::build::build(&classic).unwrap());
    let step = plan.passes.iter().find(|s| s.pass == render::plan::Pass::Environment).unwrap();
    assert!(!step.runs, "{}", step.why);
}

/// The environment of [`sky_sphere`] with the sky's keys replaced by `env`, parsed as `dir/t.toml` (its files read from `dir`).
fn environment_in(dir: &Path, env: &str) -> shadelab::scene::Environment {
    let text = with("model = \"diffuse\"").replace("kind = \"gradient\"\nzenith = 2.0\nhorizon = 0.5\nground = 0.1\n", env);
    assert!(text.contains(env), "the sky is replaced");
    let l = lesson::parse(&text, &dir.join("t.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    shadelab::scene::build::build(&l).unwrap_or_else(|e| panic!("{e}")).environment.expect("an environment")
}

/// Cube faces written as 8 × 8 OpenEXR files, each a distinct constant linear colour, read
/// along the six axes give each face's colour; the same faces in one cross give the same map.
#[test]
fn cube_faces_and_a_cross_resample_to_the_same_map_and_each_axis_sees_its_face() {
    let dir = tempfile::tempdir().expect("temp dir");
    let colours: [[f32; 3]; 6] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0], [1.0, 0.0, 1.0]];
    let names = ["px", "nx", "py", "ny", "pz", "nz"];
    // The cross: +y above +z, −y below, the middle row −x, +z, +x, −z.
    let cells = [(2u32, 1u32), (0, 1), (1, 0), (1, 2), (1, 1), (3, 1)];
    let mut cross = image::Rgb32FImage::new(32, 24);
    for (k, c) in colours.iter().enumerate() {
        let face = image::Rgb32FImage::from_pixel(8, 8, image::Rgb(*c));
        image::DynamicImage::ImageRgb32F(face).save(dir.path().join(format!("{}.exr", names[k]))).expect("write EXR");
        for y in 0..8 {
            for x in 0..8 {
                cross.put_pixel(cells[k].0 * 8 + x, cells[k].1 * 8 + y, image::Rgb(*c));
            }
        }
    }
    image::DynamicImage::ImageRgb32F(cross).save(dir.path().join("cross.exr")).expect("write EXR");
    let faces =
        environment_in(dir.path(), "kind = \"cube\"\nfaces = [\"px.exr\", \"nx.exr\", \"py.exr\", \"ny.exr\", \"pz.exr\", \"nz.exr\"]\n");
    let crossed = environment_in(dir.path(), "kind = \"cube\"\ncross = \"cross.exr\"\n");
    assert_eq!((faces.map.width, faces.map.height), (32, 16));
    for (k, d) in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].into_iter().enumerate() {
        let got = faces.radiance(d);
        assert!((got - Vec3::from(colours[k])).abs().max_element() < 1e-6, "{} along {d}: {got}", names[k]);
    }
    assert!(*faces.map == *crossed.map, "the cross and the six faces differ");
}

/// `shadelab envmap` turns the bundled sunset into a cross and a mirror ball; each, read back
/// as a lesson's `[environment]`, gives the sunset's radiance in the directions the layout
/// keeps well (the ball: away from straight behind it), and the ball's centre is +z.
#[test]
fn envmap_writes_each_layout_and_a_lesson_reads_it_back_as_the_same_sky() {
    let dir = tempfile::tempdir().expect("temp dir");
    let src = crate::helpers::lessons_dir().join("hdri/venice_sunset_1k.hdr");
    for (to, file) in [("cross", "cross.exr"), ("mirror_ball", "ball.exr"), ("latlong", "same.hdr")] {
        shadelab().arg("envmap").arg(&src).args(["--to", to, "-q", "-o"]).arg(dir.path().join(file)).assert().success();
    }
    let sunset = environment_in(dir.path(), "map = \"same.hdr\"\n");
    let cross = environment_in(dir.path(), "kind = \"cube\"\ncross = \"cross.exr\"\n");
    let ball = environment_in(dir.path(), "kind = \"mirror_ball\"\nmap = \"ball.exr\"\n");
    // Mean radiance over many directions, and point by point where the layout has detail.
    let dirs: Vec<Vec3> = (0..400)
        .map(|k| {
            let (u, v) = ((k % 20) as f32 / 20.0 + 0.025, (k / 20) as f32 / 20.0 + 0.025);
            let (phi, z) = (u * std::f32::consts::TAU, 2.0 * v - 1.0);
            let r = (1.0 - z * z).sqrt();
            Vec3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect();
    let mean = |e: &shadelab::scene::Environment, keep: &dyn Fn(Vec3) -> bool| {
        let kept: Vec<Vec3> = dirs.iter().copied().filter(|d| keep(*d)).collect();
        kept.iter().map(|d| e.radiance(*d)).sum::<Vec3>() / kept.len() as f32
    };
    let all = |_: Vec3| true;
    let want = mean(&sunset, &all);
    for (name, e) in [("cross", &cross), ("ball", &ball)] {
        let got = mean(e, &all);
        assert!(((got - want).abs() / want).max_element() < 0.03, "{name}: mean {got} against {want}");
    }
    let front = |d: Vec3| d.z > -0.5;
    let (got, want) = (mean(&ball, &front), mean(&sunset, &front));
    assert!(((got - want).abs() / want).max_element() < 0.03, "ball away from its rim: {got} against {want}");
}

#[test]
fn envmap_and_a_mirror_ball_lesson_refuse_bad_input_with_the_fix() {
    let dir = tempfile::tempdir().expect("temp dir");
    let odd = dir.path().join("odd.exr");
    image::DynamicImage::ImageRgb32F(image::Rgb32FImage::new(30, 20)).save(&odd).expect("write EXR");
    let a = shadelab().arg("envmap").arg(&odd).args(["--to", "cross", "-o"]).arg(dir.path().join("x.hdr")).assert().code(2);
    let err = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(err.contains("30×20 is none of the layouts") && err.contains("4:3"), "{err}");
    assert!(!dir.path().join("x.hdr").exists(), "nothing written");
    let a = shadelab().arg("envmap").arg(&odd).args(["--to", "cross", "-o"]).arg(dir.path().join("x.jpg")).assert().code(2);
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains(".hdr, .exr or .png"));
    // A lesson naming a non-square ball: the key, its line, and what to give.
    let text = with("model = \"diffuse\"")
        .replace("kind = \"gradient\"\nzenith = 2.0\nhorizon = 0.5\nground = 0.1\n", "kind = \"mirror_ball\"\nmap = \"odd.exr\"\n");
    std::fs::write(dir.path().join("t.toml"), &text).unwrap();
    let a = shadelab().arg("check").arg(dir.path().join("t.toml")).assert().code(2);
    let err = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(err.contains("environment.map") && err.contains("30×20 is not a mirror ball") && err.contains("square"), "{err}");
}
