//! Renders checked against analytic values: pixels, highlights, attenuation, layers, determinism.

use crate::helpers::{lesson_file, lessons_dir, render_text, shadelab};
use glam::Vec3;
use shadelab::lesson::{self, Override};
use shadelab::render::{self, Frame, Layer};
use shadelab::scene::build::build;
use std::path::Path;

/// Camera at (0, 0, 4) looking at a unit sphere; fov 30°, odd size so the centre pixel is exact.
fn sphere_lesson(model: &str, extra_material: &str, light_dir: Vec3) -> String {
    format!(
        r#"
[camera]
position = [0, 0, 4]
fov_deg = 30
size = [101, 101]

[[object]]
shape = "uv_sphere"
segments = 256
rings = 128
material = "m"

[material.m]
model = "{model}"
ambient = 0
diffuse = [0.6, 0.3, 0.1]
{extra_material}

[[light]]
kind = "directional"
direction = [{}, {}, {}]
"#,
        light_dir.x, light_dir.y, light_dir.z
    )
}

/// Where the camera ray through pixel (x, y) hits the unit sphere, if it does.
fn hit_sphere(x: u32, y: u32, size: u32) -> Option<Vec3> {
    let eye = Vec3::new(0.0, 0.0, 4.0);
    let t = (15f32).to_radians().tan();
    let px = (2.0 * (x as f32 + 0.5) / size as f32 - 1.0) * t;
    let py = (1.0 - 2.0 * (y as f32 + 0.5) / size as f32) * t;
    let d = Vec3::new(px, py, -1.0).normalize();
    // |eye + s d|² = 1
    let b = eye.dot(d);
    let c = eye.length_squared() - 1.0;
    let disc = b * b - c;
    (disc >= 0.0).then(|| eye + (-b - disc.sqrt()) * d)
}

#[test]
fn lambert_centre_pixel_is_k_diff_times_light_within_one_code() {
    let dir = tempfile::tempdir().unwrap();
    let lesson = dir.path().join("lambert.toml");
    std::fs::write(&lesson, sphere_lesson("lambert", "", Vec3::new(0.0, 0.0, -1.0))).unwrap();
    let out = dir.path().join("out.png");
    shadelab().arg("render").arg(&lesson).arg("-o").arg(&out).assert().success();
    let img = image::open(&out).unwrap().to_rgb8();
    let px = img.get_pixel(50, 50).0;
    // Expected: K_diff ⊗ I_l with N·L = 1, through the exact sRGB transfer.
    let expect = [0.6f32, 0.3, 0.1].map(|c| {
        let e = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
        (e * 255.0).round() as i32
    });
    assert_eq!(expect, [203, 149, 89], "reference sRGB values");
    for c in 0..3 {
        assert!((px[c] as i32 - expect[c]).abs() <= 1, "channel {c}: {} vs {}", px[c], expect[c]);
    }
}

#[test]
fn every_pixel_equals_max_n_dot_l_times_k_diff() {
    let l = Vec3::new(1.0, 2.0, 2.0).normalize();
    let (frame, stats) = render_text(&sphere_lesson("lambert", "", -l), &[], &[Layer::Total]);
    let mut checked = 0;
    for y in 0..101 {
        for x in 0..101 {
            // Skip the silhouette, where a pixel is partly background.
            let Some(p) = hit_sphere(x, y, 101) else { continue };
            if p.z < 0.3 {
                continue;
            }
            let n = p.normalize();
            let expect = n.dot(l).max(0.0) * Vec3::new(0.6, 0.3, 0.1);
            let got = frame.at(Layer::Total, x, y);
            assert!((got - expect).abs().max_element() < 4e-3, "pixel {x},{y}: {got} vs {expect}");
            checked += 1;
        }
    }
    assert!(checked > 3000, "{checked}");
    assert_eq!(stats.nan_samples, 0);
}

#[test]
fn phong_highlight_peaks_where_r_equals_v() {
    let l = Vec3::new(0.6, 0.5, 1.0).normalize();
    let text = sphere_lesson("phong", "specular = 1\nshininess = 400", -l);
    let (frame, _) = render_text(&text, &[], &[Layer::Specular]);
    let spec = frame.layer(Layer::Specular).unwrap();
    let (i, peak) = spec.iter().enumerate().max_by(|a, b| a.1.x.total_cmp(&b.1.x)).unwrap();
    assert!(peak.x > 0.9, "peak {peak}");
    let (x, y) = (i as u32 % 101, i as u32 / 101);
    let p = hit_sphere(x, y, 101).expect("the peak is on the sphere");
    let n = p.normalize();
    let r = 2.0 * l.dot(n) * n - l;
    let v = (Vec3::new(0.0, 0.0, 4.0) - p).normalize();
    // Within a pixel of the exact mirror point: R·V is 1 there and falls off around it.
    assert!(r.dot(v) > 0.999, "R·V = {} at the rendered peak ({x}, {y})", r.dot(v));
}

#[test]
fn blinn_phong_highlight_peaks_where_h_equals_n() {
    let l = Vec3::new(-0.5, 0.7, 1.0).normalize();
    let text = sphere_lesson("blinn_phong", "specular = 1\nshininess = 800", -l);
    let (frame, _) = render_text(&text, &[], &[Layer::Specular]);
    let spec = frame.layer(Layer::Specular).unwrap();
    let (i, _) = spec.iter().enumerate().max_by(|a, b| a.1.x.total_cmp(&b.1.x)).unwrap();
    let p = hit_sphere(i as u32 % 101, i as u32 / 101, 101).unwrap();
    let n = p.normalize();
    let h = (l + (Vec3::new(0.0, 0.0, 4.0) - p).normalize()).normalize();
    assert!(n.dot(h) > 0.9995, "N·H = {}", n.dot(h));
}

#[test]
fn layers_add_up_to_the_total() {
    let text = std::fs::read_to_string(crate::helpers::lessons_dir().join("01-first-light.toml")).unwrap();
    let (frame, _) = render_text(&text, &["camera.size=[64, 64]", "material.plastic.emission=[0.05, 0, 0]"], &Layer::ALL);
    let sum: Vec<Vec3> = {
        let raw = |l: Layer| frame.layers.iter().find(|(k, _)| *k == l).unwrap().1.clone();
        let (a, d, s, e) = (raw(Layer::Ambient), raw(Layer::Diffuse), raw(Layer::Specular), raw(Layer::Emission));
        (0..a.len()).map(|i| a[i] + d[i] + s[i] + e[i]).collect()
    };
    let total = &frame.layers.iter().find(|(k, _)| *k == Layer::Total).unwrap().1;
    assert!(sum.iter().zip(total).all(|(a, b)| (*a - *b).abs().max_element() < 1e-6));
    // Each term is really there.
    for l in [Layer::Ambient, Layer::Diffuse, Layer::Specular, Layer::Emission] {
        let raw = &frame.layers.iter().find(|(k, _)| *k == l).unwrap().1;
        assert!(raw.iter().any(|c| c.max_element() > 0.01), "{l:?} is empty");
    }
}

/// A plane y = 0 seen from above, lit by one light; returns the linear frame.
fn plane_under(light: &str, size: u32) -> Frame {
    let text = format!(
        r#"
[camera]
position = [0, 6, 0.001]
look_at = [0, 0, 0]
up = [0, 0, -1]
fov_deg = 90
size = [{size}, {size}]

[[object]]
shape = "plane"
scale = 4
material = "m"

[material.m]
model = "lambert"
ambient = 0.5
diffuse = 0.8

[scene]
ambient = 0.1

[[light]]
{light}
"#
    );
    render_text(&text, &[], &[Layer::Total]).0
}

#[test]
fn point_light_attenuation_follows_one_over_sc_sl_r_sq_r2() {
    let f = plane_under("kind = \"point\"\nposition = [0, 2, 0]\nattenuation = [1, 0.5, 0.25]\nintensity = 3", 101);
    let centre = f.at(Layer::Total, 50, 50);
    let d = 1.0 / (1.0 + 0.5 * 2.0 + 0.25 * 4.0);
    // Global ambient 0.1 × K_amb 0.5, plus d · N·L (= 1) · K_diff · I.
    let expect = 0.1 * 0.5 + d * 0.8 * 3.0;
    assert!((centre.x - expect).abs() < 1e-3, "{} vs {expect}", centre.x);
}

#[test]
fn spot_light_is_dark_outside_its_cone_and_cos_power_inside() {
    let f = plane_under("kind = \"spot\"\nposition = [0, 2, 0]\ndirection = [0, -1, 0]\nexponent = 8\ncutoff_deg = 30", 101);
    let ambient_only = 0.1 * 0.5;
    // Looking straight down from height 6 with fov 90°, pixel column px sees world x = 6·ndc_x.
    let x_world = |px: u32| 6.0 * (2.0 * (px as f32 + 0.5) / 101.0 - 1.0);
    let edge = f.at(Layer::Total, 80, 50);
    assert!(x_world(80) > 2.0 * 30f32.to_radians().tan() && x_world(80) < 4.0);
    assert!((edge.x - ambient_only).abs() < 1e-5, "outside the cone: {}", edge.x);
    let px = 55;
    let x = x_world(px);
    let r = (x * x + 4.0f32).sqrt();
    let cos_axis = 2.0 / r;
    let expect = ambient_only + cos_axis.powf(8.0) * cos_axis * 0.8;
    let got = f.at(Layer::Total, px, 50).x;
    assert!((got - expect).abs() < 2e-3, "{got} vs {expect}");
}

#[test]
fn gouraud_lights_vertices_only_and_flat_lights_faces_only() {
    let text = std::fs::read_to_string(crate::helpers::lessons_dir().join("01-first-light.toml")).unwrap();
    let (_, g) = render_text(&text, &["render.interpolation=gouraud", "camera.size=[64, 64]"], &[Layer::Total]);
    // 64 × 32 sphere: 2 + 64·31 vertices, one light.
    assert_eq!(g.vertices_lit, 2 + 64 * 31);
    assert_eq!(g.light_evaluations, g.vertices_lit);
    assert_eq!(g.light_evaluations_per_sample, 0);
    let (_, f) = render_text(&text, &["render.interpolation=flat", "camera.size=[64, 64]"], &[Layer::Total]);
    assert_eq!(f.faces_lit, 2 * 64 * 31);
    assert_eq!(f.light_evaluations_per_sample, 0);
    let (_, p) = render_text(&text, &["camera.size=[64, 64]", "render.aa=1"], &[Layer::Total]);
    assert_eq!(p.light_evaluations_per_sample, p.samples_shaded);
    // Two lights: vertex_count × lights evaluations, still none per sample.
    let two = format!("{text}\n[[light]]\nkind = \"point\"\nposition = [2.0, 2.0, 3.0]\n");
    let (_, g2) = render_text(&two, &["render.interpolation=gouraud", "camera.size=[64, 64]"], &[Layer::Total]);
    assert_eq!(g2.vertices_lit, 2 + 64 * 31);
    assert_eq!(g2.light_evaluations, 2 * g2.vertices_lit);
    assert_eq!(g2.light_evaluations_per_sample, 0);
    let (_, p2) = render_text(&two, &["camera.size=[64, 64]", "render.aa=1"], &[Layer::Total]);
    assert_eq!(p2.light_evaluations_per_sample, 2 * p2.samples_shaded);
}

#[test]
fn gouraud_misses_a_highlight_inside_a_triangle_that_phong_catches() {
    // A coarse sphere with a sharp highlight: Gouraud only sees it at vertices.
    let l = Vec3::new(0.15, 0.1, 1.0).normalize();
    let text = sphere_lesson("blinn_phong", "specular = 1\nshininess = 300", -l);
    let peak = |interp: &str| {
        let (f, _) =
            render_text(&text, &["object.0.segments=8", "object.0.rings=5", &format!("render.interpolation={interp}")], &[Layer::Specular]);
        f.layer(Layer::Specular).unwrap().iter().map(|c| c.x).fold(0.0, f32::max)
    };
    let (phong, gouraud) = (peak("phong"), peak("gouraud"));
    assert!(phong > 0.9, "phong peak {phong}");
    assert!(gouraud < 0.5 * phong, "gouraud peak {gouraud}");
}

#[test]
fn render_image_gives_the_bytes_of_develop() {
    // Straight-to-8-bit rendering is the frame's develop, byte for byte, for every layer,
    // with supersampling, Gouraud, flat, a tone map and exposure.
    let text = std::fs::read_to_string(crate::helpers::lessons_dir().join("01-first-light.toml")).unwrap();
    for extra in [
        &["camera.size=[96, 80]"][..],
        &["camera.size=[50, 40]", "render.aa=3"],
        &["camera.size=[64, 64]", "render.interpolation=gouraud", "render.tonemap=aces", "render.exposure=1.5"],
        &["camera.size=[64, 64]", "render.interpolation=flat", "render.cull=none"],
        &["camera.size=[50, 40]", "render.tonemap=agx", "render.exposure=1.5"],
        &["camera.size=[50, 40]", "render.aa=2", "render.tonemap=agx"],
    ] {
        let sets: Vec<Override> = extra.iter().map(|s| Override::parse(s).unwrap()).collect();
        let scene = build(&lesson::parse(&text, Path::new("01.toml"), &sets).unwrap()).unwrap();
        for layer in Layer::ALL {
            let (frame, stats) = render::render(&scene, &[layer]);
            let developed = render::develop::develop(&frame, layer, scene.spec.settings.exposure, scene.spec.settings.tonemap).unwrap();
            let (bytes, image_stats) = render::render_image(&scene, layer, scene.spec.settings.exposure, scene.spec.settings.tonemap);
            assert!(bytes == developed, "{extra:?} {layer:?}");
            assert_eq!(stats, image_stats);
        }
    }
}

#[test]
fn same_frame_for_one_thread_and_many() {
    let text = std::fs::read_to_string(crate::helpers::lessons_dir().join("01-first-light.toml")).unwrap();
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| render_text(&text, &["camera.size=[96, 80]", "render.aa=3"], &Layer::ALL))
    };
    let (a, b) = (run(1), run(3));
    assert_eq!(a.1, b.1);
    let bits = |f: &Frame| f.layers.iter().flat_map(|(_, v)| v.iter().flat_map(|c| c.to_array().map(f32::to_bits))).collect::<Vec<u32>>();
    assert_eq!(bits(&a.0), bits(&b.0));
}

#[test]
fn png_bytes_are_identical_across_thread_counts() {
    let lesson = crate::helpers::lessons_dir().join("01-first-light.toml");
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for threads in ["1", "4"] {
        for tonemap in ["clamp", "agx"] {
            let out = dir.path().join(format!("t{threads}-{tonemap}.png"));
            let set = format!("render.tonemap=\"{tonemap}\"");
            shadelab()
                .args(["--threads", threads, "render"])
                .arg(&lesson)
                .args(["--set", &set, "--size", "80x60", "-q", "-o"])
                .arg(&out)
                .assert()
                .success();
            files.push(std::fs::read(&out).unwrap());
        }
    }
    assert_eq!(files[0], files[2], "clamp");
    assert_eq!(files[1], files[3], "agx");
    assert_ne!(files[0], files[1], "agx is not clamp");
}

/// `SHADELAB_SIMD` caps the probe's level: every level gives the same PNG and EXR bytes (the
/// walk, the shading bundles, the encode, the projection and the shadow-map gathers at four,
/// eight and sixteen lanes). A level above this CPU's runs its widest paths.
#[test]
fn png_and_exr_bytes_are_identical_at_every_simd_level() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 6] = [
        ("01-first-light.toml", &[]),
        ("01-first-light.toml", &["render.tonemap=\"agx\"", "render.exposure=1"]),
        ("17-shadow-map-artefacts.toml", &[]),
        ("05-gouraud-vs-phong.toml", &["render.interpolation=\"gouraud\""]),
        ("16-shadows.toml", &["render.shadows=\"map\"", "render.aa=2"]),
        ("18-area-lights.toml", &[]),
    ];
    for (lesson, sets) in cases {
        for format in ["png", "exr"] {
            let mut files = Vec::new();
            for level in ["sse2", "avx", "avx2", "avx512"] {
                let out = dir.path().join(format!("{level}.{format}"));
                let mut cmd = shadelab();
                cmd.env("SHADELAB_SIMD", level).arg("render").arg(crate::helpers::lessons_dir().join(lesson));
                for s in sets {
                    cmd.args(["--set", s]);
                }
                cmd.args(["--size", "96x72", "--format", format, "-q", "-o"]).arg(&out).assert().success();
                files.push((level, std::fs::read(&out).unwrap()));
            }
            for (level, bytes) in &files[1..] {
                assert!(*bytes == files[0].1, "{lesson} {sets:?} as {format}: SHADELAB_SIMD={level} differs from sse2");
            }
        }
    }
}

#[test]
fn exr_output_is_linear_radiance() {
    let (dir, lesson) = lesson_file("lambert.toml", &sphere_lesson("lambert", "", Vec3::new(0.0, 0.0, -1.0)));
    let out = dir.path().join("linear.exr");
    shadelab().arg("render").arg(&lesson).args(["--format", "exr", "-q", "-o"]).arg(&out).assert().success();
    let img = image::open(&out).unwrap().to_rgb32f();
    let c = img.get_pixel(50, 50).0;
    for (got, want) in c.iter().zip([0.6f32, 0.3, 0.1]) {
        assert!((got - want).abs() < 2e-3, "{got} vs {want}");
    }
}

#[test]
fn layer_flag_writes_that_term_only() {
    let lesson = crate::helpers::lessons_dir().join("01-first-light.toml");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ambient.png");
    shadelab().arg("render").arg(&lesson).args(["--layer", "ambient", "--size", "65x65", "-q", "-o"]).arg(&out).assert().success();
    let img = image::open(&out).unwrap().to_rgb8();
    // The ambient term is the same on the whole disc: L_glob K_amb (no light has an ambient part).
    let a = img.get_pixel(32, 32).0;
    let b = img.get_pixel(20, 40).0;
    assert_eq!(a, b);
    assert!(a[0] > a[1]);
}

#[test]
fn hard_cases_render_without_nan() {
    // Huge exponent, light exactly at grazing, a silhouette, a camera inside a torus tube's reach.
    let text = r#"
[camera]
position = [0, 0, 3]
size = [48, 48]
[[object]]
shape = "torus"
material = "m"
[[object]]
shape = "icosphere"
subdivisions = 2
scale = 0.3
material = "m"
[material.m]
model = "phong"
shininess = 1000000
specular = 1
[[light]]
kind = "directional"
direction = [0, -1, 0]
[[light]]
kind = "point"
position = [0, 0, 0]
attenuation = [0, 0, 1]
[render]
cull = "none"
aa = 2
"#;
    for interp in ["flat", "gouraud", "phong"] {
        let (f, stats) = render_text(text, &[&format!("render.interpolation={interp}")], &Layer::ALL);
        assert_eq!(stats.nan_samples, 0);
        assert!(f.layers.iter().all(|(_, v)| v.iter().all(|c| c.is_finite())));
    }
}

#[test]
fn output_to_a_folder_is_named_after_the_lesson() {
    let lesson = crate::helpers::lessons_dir().join("01-first-light.toml");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("figs");
    shadelab().arg("render").arg(&lesson).args(["--size", "16x16", "-q", "-o"]).arg(format!("{}/", out.display())).assert().success();
    let img = crate::helpers::read_png(&out.join("01-first-light.png"));
    assert_eq!(img.dimensions(), (16, 16));
}

#[test]
fn the_plan_is_visible_in_the_stats() {
    // A Lambert-only lesson performs no specular evaluation at all.
    let text = sphere_lesson("lambert", "", Vec3::new(0.0, 0.0, -1.0));
    let (_, s) = render_text(&text, &["camera.size=[32, 32]"], &[Layer::Total]);
    assert_eq!(s.specular_evaluations, 0);
    assert!(s.diffuse_evaluations > 0);
    // K_spec = 0 on a Blinn-Phong material: also none.
    let (_, s) =
        render_text(&sphere_lesson("blinn_phong", "specular = 0", Vec3::new(0.0, 0.0, -1.0)), &["camera.size=[32, 32]"], &[Layer::Total]);
    assert_eq!(s.specular_evaluations, 0);
    // A spot aimed away from every object is culled: no light evaluation anywhere.
    let spot = format!(
        "{}\n[[light]]\nkind = \"spot\"\nposition = [0, 3, 0]\ndirection = [0, 1, 0]\ncutoff_deg = 20\n",
        sphere_lesson("blinn_phong", "", Vec3::new(0.0, 0.0, -1.0))
    );
    let (_, with_spot) = render_text(&spot, &["camera.size=[32, 32]"], &[Layer::Total]);
    let (_, without) =
        render_text(&sphere_lesson("blinn_phong", "", Vec3::new(0.0, 0.0, -1.0)), &["camera.size=[32, 32]"], &[Layer::Total]);
    assert_eq!(with_spot.light_evaluations, without.light_evaluations);
    assert_eq!(without.light_evaluations, without.samples_shaded);
}

/// An ambient-occlusion map of code 128 (linear data: 128/255) halves, nearly, the ambient
/// term of a flat patch and leaves its diffuse term as it was.
#[test]
fn an_occlusion_map_scales_the_ambient_term_and_nothing_else() {
    let dir = tempfile::tempdir().unwrap();
    image::GrayImage::from_pixel(4, 4, image::Luma([128])).save(dir.path().join("ao.png")).unwrap();
    let at_centre = |ao: &str| {
        let text = format!(
            "[camera]\nposition = [0, 0, 4]\nsize = [32, 32]\n\n[[object]]\nshape = \"plane\"\nrotate_deg = [90, 0, 0]\nmaterial = \"m\"\n\n\
             [material.m]\nmodel = \"lambert\"\ndiffuse = 0.8\n{ao}\n\n[[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\n\n\
             [scene]\nambient = 0.5\n"
        );
        let lesson = lesson::parse(&text, &dir.path().join("t.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
        let scene = build(&lesson).unwrap();
        let (f, _) = render::render(&scene, &[Layer::Ambient, Layer::Diffuse]);
        (f.at(Layer::Ambient, 16, 16), f.at(Layer::Diffuse, 16, 16))
    };
    let (amb, diff) = at_centre("");
    let (amb_ao, diff_ao) = at_centre("occlusion_map = \"ao.png\"");
    assert!((amb.x - 0.4).abs() < 1e-5, "L_glob K_amb = 0.5 × 0.8: {amb}");
    assert!((amb_ao.x / amb.x - 128.0 / 255.0).abs() < 1e-5, "{amb_ao} against {amb}");
    assert_eq!(diff_ao, diff, "the direct light is not the map's");
}

#[test]
fn an_emitters_pixels_keep_their_radiance_while_its_solid_angle_falls_as_one_over_d_squared() {
    // Lesson 41: a 1 × 1 panel of radiance 0.5 seen from 2, 4 and 8 units (no anti-aliasing).
    let path = lessons_dir().join("41-solid-angle-and-radiance.toml");
    let lit = |set: &str| {
        let lesson = lesson::load(&path, &[Override::parse(set).unwrap()]).unwrap_or_else(|e| panic!("{e}"));
        let scene = build(&lesson).unwrap();
        let (f, _) = render::render(&scene, &[Layer::Total]);
        let (w, h) = (lesson.scene.camera.width, lesson.scene.camera.height);
        (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).map(|(x, y)| f.at(Layer::Total, x, y).x).filter(|v| *v > 0.0).collect::<Vec<f32>>()
    };
    let mut counts = Vec::new();
    for d in [2, 4, 8] {
        let covered = lit(&format!("camera.position=[0, 0, {d}]"));
        // Radiance: every covered pixel is the panel's L, whatever the distance.
        assert!(covered.iter().all(|v| (v - 0.5).abs() < 1e-6), "d = {d}");
        counts.push(covered.len() as f64);
    }
    // The image of a square facing a pinhole is (f/d)² in area: 219.8/d pixels a side, rounded.
    for (c, d) in counts.iter().zip([2.0f64, 4.0, 8.0]) {
        let side = 80.0 / 20f64.to_radians().tan() / d;
        assert!((c.sqrt() - side).abs() <= 1.0, "d = {d}: {c} pixels, side {side}");
    }
}

#[test]
fn a_metallic_map_switches_the_diffuse_term_texel_by_texel() {
    let dir = tempfile::tempdir().unwrap();
    for (name, code) in [("metal.png", 255u8), ("paint.png", 0)] {
        image::GrayImage::from_pixel(4, 4, image::Luma([code])).save(dir.path().join(name)).unwrap();
    }
    let at_centre = |metallic: &str| {
        let text = format!(
            "[camera]\nposition = [0, 0, 4]\nsize = [32, 32]\n\n[[object]]\nshape = \"plane\"\nrotate_deg = [90, 0, 0]\nmaterial = \"m\"\n\n\
             [material.m]\nmodel = \"principled\"\nbase_color = [0.8, 0.3, 0.2]\nroughness = 0.4\nmetallic = {metallic}\n\n\
             [[light]]\nkind = \"directional\"\ndirection = [0.3, -0.2, -1]\n"
        );
        let lesson = lesson::parse(&text, &dir.path().join("t.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
        let (f, _) = render::render(&build(&lesson).unwrap(), &[Layer::Diffuse, Layer::Specular]);
        (f.at(Layer::Diffuse, 16, 16), f.at(Layer::Specular, 16, 16))
    };
    // A texel of 255 is metal: no diffuse term, a specular tinted by the base colour; a texel
    // of 0 is the constant metallic 0, bit for bit.
    let (diff_metal, spec_metal) = at_centre("{ texture = \"metal.png\" }");
    let (diff_paint, spec_paint) = at_centre("{ texture = \"paint.png\" }");
    assert_eq!(at_centre("0.0"), (diff_paint, spec_paint));
    assert_eq!(at_centre("1.0"), (diff_metal, spec_metal));
    assert_eq!(diff_metal, Vec3::ZERO);
    assert!(diff_paint.x > 0.05, "{diff_paint}");
    assert!(spec_metal.x > spec_metal.z * 2.0 && spec_metal.x > spec_paint.x, "{spec_metal} against {spec_paint}");
}

#[test]
fn a_lights_specular_colour_changes_only_the_classic_specular_term() {
    let dir = tempfile::tempdir().unwrap();
    let terms = |model: &str, light_tail: &str| {
        let text = format!(
            "[camera]\nposition = [0, 0, 4]\nsize = [32, 32]\n\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n\n\
             [material.m]\nmodel = \"{model}\"\ndiffuse = 0.5\nspecular = 0.5\n{}\n\n\
             [[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\nintensity = 2\n{light_tail}\n",
            if model == "cook_torrance" { "roughness = 0.3" } else { "shininess = 20" }
        );
        let lesson = lesson::parse(&text, &dir.path().join("t.toml"), &[]).unwrap_or_else(|e| panic!("{e}"));
        let (f, _) = render::render(&build(&lesson).unwrap(), &[Layer::Diffuse, Layer::Specular]);
        (f.at(Layer::Diffuse, 16, 16), f.at(Layer::Specular, 16, 16))
    };
    // L_spec = specular × intensity replaces color × intensity in the specular term only.
    let (d, s) = terms("blinn_phong", "");
    assert!(s.x > 0.1, "{s}");
    let (d2, s2) = terms("blinn_phong", "specular = [0.5, 1, 0]");
    assert_eq!(d2, d);
    assert!((s2 - s * Vec3::new(0.5, 1.0, 0.0)).abs().max_element() < 1e-6, "{s2} against {s}");
    // `specular = color` is the default, bit for bit; a physically based BRDF reads `color` only.
    assert_eq!(terms("blinn_phong", "specular = 1"), (d, s));
    assert_eq!(terms("cook_torrance", "specular = 0"), terms("cook_torrance", ""));
}
