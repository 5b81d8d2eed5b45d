//! Shadows and lights with extent against analytic values: the shadow ellipse of a sphere,
//! the dark point under it, the polygon formula and the sampled irradiance that converges
//! to it, the sphere light's E = πL(r/d)², a rect light against many small point lights in
//! the far field, determinism across thread counts, no NaN at grazing light, zero-size lights
//! refused.

use crate::helpers::{lesson_file, shadelab};
use glam::{DVec3, Vec3};
use shadelab::effects::shadows::map::SHADOW_MAP_TEXELS;
use shadelab::lesson::{self, Override};
use shadelab::render::{self, Frame, Layer, RenderStats};
use shadelab::scene::build::build;
use shadelab::transport::rays::BVH_NODES;
use shadelab::transport::visibility::{SHADOW_MAP_LOOKUPS, SHADOW_RAYS};
use std::path::Path;

fn render_text(text: &str, sets: &[&str]) -> (Frame, RenderStats, shadelab::lesson::Lesson) {
    let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    let lesson = lesson::parse(text, Path::new("test.toml"), &sets).unwrap_or_else(|e| panic!("{e}"));
    let scene = build(&lesson).unwrap();
    let (f, st) = render::render(&scene, &[Layer::Total]);
    (f, st, lesson)
}

/// A unit sphere over the floor y = −1 seen from straight above; Lambert, no ambient, one
/// directional light travelling along `d`.
fn sphere_over_floor(d: Vec3, size: u32) -> String {
    format!(
        r#"
[camera]
position = [0, 8, 0]
look_at = [0, -1, 0]
up = [0, 0, -1]
fov_deg = 50
size = [{size}, {size}]

[[object]]
shape = "uv_sphere"
segments = 128
rings = 64
material = "m"

[[object]]
shape = "plane"
scale = 6
translate = [0, -1, 0]
material = "m"

[material.m]
model = "lambert"
ambient = 0
diffuse = 1

[[light]]
kind = "directional"
direction = [{}, {}, {}]
"#,
        d.x, d.y, d.z
    )
}

/// The shadow of the unit sphere on the floor under a directional light is the analytic
/// ellipse: every floor pixel whose line to the light passes 0.06 or more inside the sphere
/// is black, every one passing 0.06 or more outside is fully lit (N·L), for ray-cast
/// shadows and for a shadow map at the default bias.
#[test]
fn the_shadow_of_a_sphere_is_the_analytic_ellipse() {
    let d = Vec3::new(1.0, -0.8, 0.3).normalize();
    let text = sphere_over_floor(d, 129);
    let l = -d.as_dvec3();
    let lit = l.y as f32; // N·L on the floor, K_diff = 1, radiance 1
    for method in ["ray", "map"] {
        let set = format!("render.shadows=\"{method}\"");
        let (frame, st, lesson) = render_text(&text, &[&set, "render.shadow_map_size=2048"]);
        let rays = lesson.scene.camera.rays();
        let (mut inside, mut outside) = (0, 0);
        for y in 0..frame.height {
            for x in 0..frame.width {
                let r = rays.ray((x, y), (0, 0), 1);
                let dir = r.dir.normalize();
                // Skip pixels that see the sphere (or come within 0.05 of its outline).
                let b = r.origin.dot(dir);
                let closest = (r.origin - dir * b).length();
                if closest < 1.05 {
                    continue;
                }
                let t = (-1.0 - r.origin.y) / dir.y;
                let q = r.origin + dir * t;
                if q.x.abs() > 5.5 || q.z.abs() > 5.5 {
                    continue;
                }
                // Distance from the sphere's centre to the line from q towards the light.
                let dist = (q - l * q.dot(l)).length();
                let v = frame.at(Layer::Total, x, y).x;
                if dist < 0.94 {
                    inside += 1;
                    assert!(v < 0.01, "{method}: floor point {q:?} {dist:.3} inside the shadow is lit: {v}");
                } else if dist > 1.06 {
                    outside += 1;
                    assert!((v - lit).abs() < 2e-3, "{method}: floor point {q:?} {dist:.3} outside the shadow: {v}, want {lit}");
                }
            }
        }
        assert!(inside > 300 && outside > 3000, "{method}: too few pixels checked ({inside} in the shadow, {outside} outside)");
        if method == "ray" {
            assert!(st.count(SHADOW_RAYS) > 0 && st.count(BVH_NODES) > 0, "{st:?}");
        } else {
            assert!(st.count(SHADOW_MAP_LOOKUPS) > 0 && st.count(SHADOW_MAP_TEXELS) > 0, "{st:?}");
        }
    }
}

/// The floor directly under the sphere is dark under a point light straight above, with
/// rays and with a shadow map at the default bias; without shadows it is lit.
#[test]
fn the_floor_under_the_sphere_is_dark() {
    // The sphere floats 1 above the floor; the camera looks under it at the floor's origin.
    let text = sphere_over_floor(Vec3::NEG_Y, 65)
        .replace(
            "kind = \"directional\"\ndirection = [0, -1, 0]",
            "kind = \"point\"\nposition = [0, 4, 0]\nattenuation = [0, 0, 1]\nintensity = 25",
        )
        .replace("position = [0, 8, 0]\nlook_at = [0, -1, 0]\nup = [0, 0, -1]", "position = [0, -0.5, 5]\nlook_at = [0, -1, 0]")
        .replace("material = \"m\"\n\n[[object]]", "material = \"m\"\ntranslate = [0, 1, 0]\n\n[[object]]");
    assert!(text.contains("kind = \"point\"") && text.contains("translate = [0, 1, 0]") && text.contains("[0, -0.5, 5]"));
    let centre = |set: &str| render_text(&text, &[set]).0.at(Layer::Total, 32, 32).x;
    assert!(centre("render.shadows=\"ray\"") == 0.0);
    assert!(centre("render.shadows=\"map\"") == 0.0);
    // Unshadowed: 25 / r² with r = 5, N·L = 1.
    assert!((centre("render.shadows=\"none\"") - 1.0).abs() < 1e-3);
}

/// A lesson lit by one rect light of radiance `le` at height `h` above a floor facing up,
/// seen from above (Lambert diffuse 1: the classic diffuse is L_e·A′).
fn rect_over_floor(size: [f32; 2], h: f32, samples: u32, model: &str) -> String {
    format!(
        r#"
[camera]
position = [0, 3, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
fov_deg = 20
size = [33, 33]

[[object]]
shape = "plane"
scale = 2
material = "m"

[material.m]
model = "{model}"
ambient = 0
diffuse = 1

[[light]]
kind = "rect"
position = [0, {h}, 0]
direction = [0, -1, 0]
size = [{}, {}]
samples = {samples}
"#,
        size[0], size[1]
    )
}

/// The form factor of a unit square at height 1 over a point on its axis is 0.239456
/// (Lambert's polygon formula): the classic A′ = πF there, and the sampled irradiance
/// converges to it with an error falling like 1/√N.
#[test]
fn sampled_rect_light_converges_to_the_polygon_formula() {
    let f = shadelab::geometry::polygon::polygon_form_factor(
        Vec3::ZERO,
        Vec3::Y,
        &[Vec3::new(-0.5, 1.0, -0.5), Vec3::new(0.5, 1.0, -0.5), Vec3::new(0.5, 1.0, 0.5), Vec3::new(-0.5, 1.0, 0.5)],
    );
    assert!((f - 0.239456).abs() < 1e-6, "{f}");
    let exact = std::f32::consts::PI * f;
    // Error of the centre pixel over many pixels: RMS over the frame against the frame's own
    // analytic values is overkill here; the centre pixel's error averaged over 25 pixels near it.
    let err = |n: u32| {
        let (frame, _, _) = render_text(&rect_over_floor([1.0, 1.0], 1.0, n, "lambert"), &[]);
        let mut sq = 0.0;
        for y in 14..19 {
            for x in 14..19 {
                // Points off the axis have their own exact value.
                let lesson = lesson::parse(&rect_over_floor([1.0, 1.0], 1.0, n, "lambert"), Path::new("t.toml"), &[]).unwrap();
                let r = lesson.scene.camera.rays().ray((x, y), (0, 0), 1);
                let t = -r.origin.y / r.dir.y;
                let p = (r.origin + r.dir * t).as_vec3();
                let corners = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]].map(|[a, b]| Vec3::new(a, 1.0, b));
                let want = std::f32::consts::PI * shadelab::geometry::polygon::polygon_form_factor(p, Vec3::Y, &corners);
                let e = frame.at(Layer::Total, x, y).x - want;
                sq += e * e;
            }
        }
        (sq / 25.0).sqrt()
    };
    let (e4, e64, e1024) = (err(4), err(64), err(1024));
    // 1/√N: 16× the samples, ¼ the error (stratified samples do at least as well).
    assert!(e64 < e4 / 3.0 && e1024 < e64 / 3.0, "errors {e4} {e64} {e1024}");
    assert!(e1024 < 2e-3 * exact, "1024 samples: {e1024} against {exact}");
    // The centre with many samples is πF.
    let (frame, _, _) = render_text(&rect_over_floor([1.0, 1.0], 1.0, 4096, "lambert"), &[]);
    assert!((frame.at(Layer::Total, 16, 16).x - exact).abs() < 2e-3, "{} vs {exact}", frame.at(Layer::Total, 16, 16).x);
}

/// A sphere light of radius r at distance d over a point facing it gives E = πL(r/d)²: a
/// Lambertian `diffuse` BRDF (ρ/π) shows L_o = ρ L (r/d)².
#[test]
fn a_sphere_light_gives_pi_l_r_over_d_squared() {
    let text = rect_over_floor([1.0, 1.0], 1.0, 1, "diffuse").replace(
        "kind = \"rect\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\nsize = [1, 1]\nsamples = 1",
        "kind = \"sphere\"\nposition = [0, 2, 0]\nradius = 0.5\nsamples = 64\nintensity = 3",
    );
    assert!(text.contains("sphere\""));
    let (frame, _, _) = render_text(&text, &[]);
    let want = 3.0 * (0.5f32 / 2.0).powi(2);
    let got = frame.at(Layer::Total, 16, 16).x;
    assert!((got - want).abs() < 1e-3 * want, "{got} vs {want}");
}

/// In the far field a rect light is a point light of intensity L_e·A·cos θ_l: a 0.2 × 0.2
/// rect of radiance 100 at height 10 and a 5 × 5 grid of point lights with the same total
/// intensity agree on the floor to 0.5%.
#[test]
fn a_far_rect_light_equals_many_small_point_lights() {
    let rect = rect_over_floor([0.2, 0.2], 10.0, 16, "diffuse").replace("samples = 16", "samples = 16\nintensity = 100");
    let mut points = rect_over_floor([0.2, 0.2], 10.0, 16, "diffuse");
    let start = points.find("[[light]]").unwrap();
    points.truncate(start);
    for i in 0..5 {
        for j in 0..5 {
            let (x, z) = (-0.08 + 0.04 * i as f32, -0.08 + 0.04 * j as f32);
            // I = L_e A / 25 each, towards the floor below (cos θ_l ≈ 1 in the far field).
            points.push_str(&format!("[[light]]\nkind = \"point\"\nposition = [{x}, 10, {z}]\nintensity = {}\n", 100.0 * 0.04 / 25.0));
        }
    }
    let (a, _, _) = render_text(&rect, &[]);
    let (b, _, _) = render_text(&points, &[]);
    for (p, q) in a.raw(Layer::Total).unwrap().iter().zip(b.raw(Layer::Total).unwrap()) {
        assert!((p.x - q.x).abs() <= 5e-3 * q.x.max(1e-6), "{p} vs {q}");
    }
}

/// The same lesson gives the same bytes with one worker thread and with four, for hard
/// shadows by ray and by map and for a sampled area light with soft shadows.
#[test]
fn shadows_and_area_lights_do_not_depend_on_the_thread_count() {
    let text = sphere_over_floor(Vec3::new(1.0, -2.0, 0.5).normalize(), 96);
    let area = text.replace(
        "kind = \"directional\"\ndirection = [",
        "kind = \"rect\"\nposition = [1, 3, 0]\nsize = [1, 2]\nsamples = 8\nintensity = 3\ndirection = [",
    );
    let (dir, path) = lesson_file("s.toml", &text);
    let area_path = dir.path().join("a.toml");
    std::fs::write(&area_path, &area).unwrap();
    for (lesson, set) in [(&path, "render.shadows=ray"), (&path, "render.shadows=map"), (&area_path, "render.shadows=ray")] {
        let mut outs = Vec::new();
        for threads in ["1", "4"] {
            let out = dir.path().join(format!("out-{threads}.png"));
            shadelab().args(["--threads", threads, "render"]).arg(lesson).args(["--set", set, "-q", "-o"]).arg(&out).assert().success();
            outs.push(std::fs::read(&out).unwrap());
        }
        assert!(outs[0] == outs[1], "{} with {set}: the bytes depend on the thread count", lesson.display());
    }
}

/// Light grazing the floor (1e-4 above the horizon) and lights of every kind at the hardest
/// places give finite pixels: no NaN sample.
#[test]
fn grazing_and_degenerate_light_positions_give_no_nan() {
    let grazing = sphere_over_floor(Vec3::new(1.0, -1e-4, 0.0).normalize(), 48);
    for method in ["ray", "map"] {
        let (_, st, _) = render_text(&grazing, &[&format!("render.shadows=\"{method}\"")]);
        assert_eq!(st.nan_samples, 0, "{method}");
    }
    // Emitters touching or inside the scene's surfaces.
    for light in [
        "{kind=\"rect\",position=[0,-1,0],direction=[0,-1,0],size=[1,1]}",
        "{kind=\"rect\",position=[0,-1,0],direction=[1,0,0],size=[1,1]}",
        "{kind=\"disk\",position=[0,0,0],direction=[0,-1,0],radius=0.5}",
        "{kind=\"sphere\",position=[0,0,0],radius=2}",
        "{kind=\"sphere\",position=[0,1,0],radius=0.01}",
        "{kind=\"line\",start=[0,-1,-3],end=[0,-1,3],radius=0.01}",
        "{kind=\"sky\",color=1,ground_color=0.5}",
        "{kind=\"point\",position=[0,-1,0]}",
        "{kind=\"spot\",position=[0,1,0],direction=[0,-1,0],cutoff_deg=30}",
    ] {
        for method in ["ray", "map", "none"] {
            let set = format!("light=[{light}]");
            let (f, st, _) = render_text(&grazing, &[&set, &format!("render.shadows=\"{method}\""), "render.shadow_map_size=64"]);
            assert_eq!(st.nan_samples, 0, "{light} {method}");
            assert!(f.raw(Layer::Total).unwrap().iter().all(|c| c.is_finite() && c.min_element() >= 0.0), "{light} {method}");
        }
    }
}

/// A light of zero size is refused at load time with the key, the line and a fix; exit 2.
#[test]
fn zero_size_lights_are_errors() {
    let base = "[camera]\nposition = [0, 0, 4]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[material.m]\nmodel = \"lambert\"\n";
    for (light, key) in [
        ("kind = \"rect\"\nposition = [0, 2, 0]\ndirection = [0, -1, 0]\nsize = [0, 1]", "light.0.size"),
        ("kind = \"disk\"\nposition = [0, 2, 0]\ndirection = [0, -1, 0]\nradius = 0", "light.0.radius"),
        ("kind = \"sphere\"\nposition = [0, 2, 0]\nradius = 0", "light.0.radius"),
        ("kind = \"line\"\nstart = [0, 2, 0]\nend = [0, 2, 0]\nradius = 0.1", "light.0.end"),
        ("kind = \"rect\"\nposition = [0, 2, 0]\ndirection = [0, -1, 0]", "light.0.size"),
    ] {
        let (_dir, path) = lesson_file("zero.toml", &format!("{base}[[light]]\n{light}\n"));
        let out = shadelab().arg("render").arg(&path).arg("-o").arg(path.with_extension("png")).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{light}: {err}");
        assert!(err.contains(&format!("`{key}`")) && err.contains("zero.toml:") && err.contains("hint"), "{light}: {err}");
        assert!(!path.with_extension("png").exists());
    }
}

/// One convex object runs no shadow pass (nothing can block its light), and `explain` says why.
#[test]
fn a_single_sphere_needs_no_shadow_pass() {
    let text = "[camera]\nposition = [0, 0, 4]\nsize = [32, 32]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[material.m]\nmodel = \"lambert\"\n[[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\n";
    let (_, st, _) = render_text(text, &[]);
    assert_eq!((st.count(SHADOW_RAYS), st.count(BVH_NODES), st.count(SHADOW_MAP_TEXELS)), (0, 0, 0));
    let (_dir, path) = lesson_file("one.toml", text);
    let out = shadelab().arg("explain").arg(&path).output().unwrap();
    let s = String::from_utf8_lossy(&out.stdout);
    assert!(s.contains("shadows: none") && s.contains("nothing can block it"), "{s}");
    let _ = DVec3::ZERO;
}

/// The exact reference of `cost` casts exact shadows (rays against the analytic shapes):
/// its floor is black inside the sphere's shadow ellipse, and the Phong render with ray-cast
/// shadows agrees with it but along outlines.
#[test]
fn the_exact_reference_casts_shadows() {
    let d = Vec3::new(1.0, -0.8, 0.3).normalize();
    let text = sphere_over_floor(d, 65);
    let lesson = lesson::parse(&text, Path::new("t.toml"), &[]).unwrap();
    let scene = build(&lesson).unwrap();
    let exact = shadelab::cost::reference::reference(&lesson, &scene, &[Layer::Total], 1).unwrap();
    let (raster, _) = render::render(&scene, &[Layer::Total]);
    let rays = lesson.scene.camera.rays();
    let l = -d.as_dvec3();
    let (mut dark, mut differ) = (0, 0);
    for y in 0..65 {
        for x in 0..65 {
            let r = rays.ray((x, y), (0, 0), 1);
            let dir = r.dir.normalize();
            if (r.origin - dir * r.origin.dot(dir)).length() < 1.05 {
                continue;
            }
            let q = r.origin + dir * ((-1.0 - r.origin.y) / dir.y);
            if (q - l * q.dot(l)).length() < 0.9 {
                dark += 1;
                assert_eq!(exact.at(Layer::Total, x, y).x, 0.0, "{q:?}");
            }
            differ += ((exact.at(Layer::Total, x, y) - raster.at(Layer::Total, x, y)).abs().max_element() > 0.02) as u32;
        }
    }
    assert!(dark > 50, "{dark} pixels in the shadow");
    assert!(differ < 65 * 65 / 50, "{differ} pixels differ between the raster and the exact reference");
}

/// The floor beside a low wall, lit by a rect light sampled by area, seen from above: the
/// row of pixels from the wall's shadow through its penumbra to the light, stopping short of
/// the wall, under `pattern` (`[render] sample_pattern`).
fn penumbra_row(pattern: &str) -> Vec<f32> {
    let text = r#"
[camera]
position = [-1, 6, 0]
look_at = [-1, 0, 0]
up = [0, 0, -1]
fov_deg = 40
size = [192, 192]

[[object]]
shape = "plane"
scale = 4
material = "floor"

[[object]]
shape = "cube"
scale = [0.05, 0.5, 2]
translate = [-1.0, 0.5, 0]
material = "floor"

[material.floor]
model = "lambert"
ambient = 0
diffuse = 0.8

[[light]]
kind = "rect"
position = [0.5, 3, 0]
direction = [0, -1, 0]
size = [1.5, 1.5]
samples = 8
sampling = "area"

[render]
aa = 1
"#;
    let (frame, _, _) = render_text(text, &[&format!("render.sample_pattern=\"{pattern}\"")]);
    // Columns 0..88 lie left of x = −1.1, short of the wall's lit top.
    (0..88).map(|x| frame.at(Layer::Total, x, 96).x).collect()
}

/// How many times the row falls from one pixel to the next, going towards the wall.
fn drops(row: &[f32]) -> usize {
    row.windows(2).filter(|w| w[1] - w[0] < -1e-6).count()
}

#[test]
fn a_shared_light_pattern_draws_the_penumbra_as_steps_and_a_pattern_per_point_as_grain() {
    let shared = penumbra_row("shared");
    let per_point = penumbra_row("per_point");
    // The row runs from the open floor into the wall's shadow.
    let hi = shared.iter().cloned().fold(0.0, f32::max);
    assert!(shared[0] > 0.3 * hi && *shared.last().unwrap() == 0.0, "{shared:?}");
    // Towards the wall the floor nears the light and brightens; it darkens only where one of
    // the light's points goes behind the wall. Every point sees the same 8 points of the light,
    // so that happens at 8 places at most: a staircase. Per point, each pixel's own 8 points
    // give an estimate off by its own amount, and the row falls again and again: grain.
    assert!((3..=8).contains(&drops(&shared)), "shared: {} drops\n{shared:?}", drops(&shared));
    assert!(drops(&per_point) >= 24, "per point: {} drops\n{per_point:?}", drops(&per_point));
}
