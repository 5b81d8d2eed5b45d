//! Shadow volumes and shadow polygons against the references: the analytic shadow of a
//! sphere (the ellipse of `shadows.rs`), ray-cast shadows on lesson 45 (few pixels differ,
//! all on outlines), a light inside a box and an eye inside a volume (documented
//! behaviour: the same as rays), determinism across thread counts, and the counters.

use crate::helpers::{lesson_file, lessons_dir, render_text, shadelab};
use glam::Vec3;
use shadelab::effects::shadows::polygons::{POLYGON_PAIRS, POLYGON_TESTS};
use shadelab::effects::shadows::volume::{VOLUME_QUAD_TESTS, VOLUME_QUADS};
use shadelab::lesson::{self, Override};
use shadelab::render::{self, Frame, Layer};
use shadelab::scene::build::build;

/// A unit sphere (32 × 16) over the floor y = −1 seen from straight above; Lambert, no
/// ambient, one directional light travelling along `d`.
fn sphere_over_floor(d: Vec3, size: u32) -> String {
    format!(
        "[camera]\nposition = [0, 8, 0]\nlook_at = [0, -1, 0]\nup = [0, 0, -1]\nfov_deg = 50\nsize = [{size}, {size}]\n\n\
         [[object]]\nshape = \"uv_sphere\"\nsegments = 32\nrings = 16\nmaterial = \"m\"\n\n\
         [[object]]\nshape = \"plane\"\nscale = 6\ntranslate = [0, -1, 0]\nmaterial = \"m\"\n\n\
         [material.m]\nmodel = \"lambert\"\nambient = 0\ndiffuse = 1\n\n\
         [[light]]\nkind = \"directional\"\ndirection = [{}, {}, {}]\n",
        d.x, d.y, d.z
    )
}

/// The floor under the faceted sphere is in the analytic ellipse's shadow with volumes and
/// with polygons: every floor pixel whose line to the light passes 0.06 or more inside the
/// unit sphere is black (the 32 × 16 facets lie within 0.005 of it), every one passing 0.06
/// or more outside is lit (N·L).
#[test]
fn volumes_and_polygons_cast_the_analytic_ellipse() {
    let d = Vec3::new(1.0, -0.8, 0.3).normalize();
    let text = sphere_over_floor(d, 97);
    let l = -d;
    for method in ["volume", "polygons"] {
        let (frame, st) = render_text(&text, &[&format!("render.shadows=\"{method}\"")], &[Layer::Total]);
        let lesson = lesson::parse(&text, std::path::Path::new("t.toml"), &[]).unwrap();
        let rays = lesson.scene.camera.rays();
        let (mut inside, mut outside) = (0, 0);
        for y in 0..frame.height {
            for x in 0..frame.width {
                let r = rays.ray((x, y), (0, 0), 1);
                let (o, dir) = (r.origin.as_vec3(), r.dir.as_vec3().normalize());
                if (o - dir * o.dot(dir)).length() < 1.05 {
                    continue; // the sphere or its outline
                }
                let q = o + dir * ((-1.0 - o.y) / dir.y);
                if q.x.abs() > 5.5 || q.z.abs() > 5.5 {
                    continue;
                }
                let dist = (q - l * q.dot(l)).length();
                let v = frame.at(Layer::Total, x, y).x;
                if dist < 0.94 {
                    inside += 1;
                    assert!(v < 0.01, "{method}: {q:?} at {dist:.3} inside the shadow is lit: {v}");
                } else if dist > 1.06 {
                    outside += 1;
                    assert!((v - l.y).abs() < 2e-3, "{method}: {q:?} at {dist:.3} outside the shadow: {v}, want {}", l.y);
                }
            }
        }
        assert!(inside > 150 && outside > 1500, "{method}: too few pixels checked ({inside} in, {outside} out)");
        match method {
            "volume" => assert!(st.count(VOLUME_QUADS) > 0 && st.count(VOLUME_QUAD_TESTS) > 0, "{st:?}"),
            _ => assert!(st.count(POLYGON_PAIRS) > 0 && st.count(POLYGON_TESTS) > 0, "{st:?}"),
        }
    }
}

fn render_lesson45(sets: &[&str]) -> Frame {
    let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    let lesson = lesson::load(&lessons_dir().join("45-classic-shadows.toml"), &sets).unwrap_or_else(|e| panic!("{e}"));
    render::render(&build(&lesson).unwrap(), &[Layer::Diffuse]).0
}

/// Pixels of `a` that differ from the reference `r` (diffuse layer, 1% of the brightest
/// value), and how many of them lie away from every outline of `r` (no pixel within two
/// whose value in `r` differs from theirs by as much).
fn differing(a: &Frame, r: &Frame) -> (usize, usize, usize) {
    let (w, h) = (r.width as i64, r.height as i64);
    let v = |f: &Frame, x: i64, y: i64| f.at(Layer::Diffuse, x as u32, y as u32).max_element();
    let peak = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).map(|(x, y)| v(r, x, y)).fold(0.0, f32::max);
    let tol = 0.01 * peak;
    let (mut n, mut off_edge) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            if (v(a, x, y) - v(r, x, y)).abs() <= tol {
                continue;
            }
            n += 1;
            let edge = (-2..=2).any(|dy: i64| {
                (-2..=2).any(|dx: i64| {
                    let (u, t) = (x + dx, y + dy);
                    (0..w).contains(&u) && (0..h).contains(&t) && (v(r, u, t) - v(r, x, y)).abs() > tol
                })
            });
            if !edge {
                off_edge += 1;
            }
        }
    }
    (n, off_edge, (w * h) as usize)
}

/// Lesson 45 with volumes and with polygons against ray-cast shadows: under 1% of the pixels
/// differ, and every differing pixel lies on an outline (of a shadow or an object).
#[test]
fn volumes_and_polygons_agree_with_rays_except_on_outlines() {
    let ray = render_lesson45(&["render.shadows=\"ray\""]);
    for method in ["volume", "polygons"] {
        let f = render_lesson45(&[&format!("render.shadows=\"{method}\"")]);
        let (n, off_edge, all) = differing(&f, &ray);
        let share = n as f64 / all as f64;
        assert!(share < 0.01, "{method}: {n} of {all} pixels differ ({:.2}%)", 100.0 * share);
        assert_eq!(off_edge, 0, "{method}: {off_edge} of the {n} differing pixels lie away from every outline");
        // Not vacuous: without shadows far more pixels differ.
        if method == "volume" {
            let (none, _, _) = differing(&render_lesson45(&["render.shadows=\"none\""]), &ray);
            assert!(none > 20 * n.max(1), "no shadows: {none} pixels differ, {method}: {n}");
        }
    }
}

/// A small box over a floor, lit by a point light inside or above it, seen from `eye`.
fn box_scene(light: Vec3, eye: Vec3) -> String {
    format!(
        "[camera]\nposition = [{}, {}, {}]\nlook_at = [0.3, 0, 0.2]\nfov_deg = 60\nsize = [64, 64]\n\n\
         [[object]]\nshape = \"cube\"\nscale = 0.6\ntranslate = [0, 1.2, 0]\nmaterial = \"m\"\n\n\
         [[object]]\nshape = \"plane\"\nscale = 4\nmaterial = \"m\"\n\n\
         [material.m]\nmodel = \"lambert\"\nambient = 0\ndiffuse = 0.8\n\n\
         [scene]\nambient = 0.1\n\n\
         [[light]]\nkind = \"point\"\nposition = [{}, {}, {}]\nattenuation = [0, 0, 1]\nintensity = 6\n",
        eye.x, eye.y, eye.z, light.x, light.y, light.z
    )
}

/// The documented hard cases give what rays give: a light inside a closed box (cast triangle
/// by triangle: everything outside is in shadow), and an eye standing in the box's shadow
/// (the count of volumes holding the eye is added). No pixel differs by more than 1% of the
/// brightest beyond 1% of the image, and none is NaN.
#[test]
fn a_light_inside_a_box_and_an_eye_in_its_shadow_match_rays() {
    let cases = [
        ("light inside", Vec3::new(0.0, 1.2, 0.0), Vec3::new(0.5, 3.0, 4.0)),
        ("eye in the shadow", Vec3::new(0.0, 3.5, 0.0), Vec3::new(0.05, 0.4, 0.1)),
    ];
    for (what, light, eye) in cases {
        let text = box_scene(light, eye);
        let (ray, _) = render_text(&text, &["render.shadows=\"ray\""], &[Layer::Diffuse]);
        for method in ["volume", "polygons"] {
            let (f, _) = render_text(&text, &[&format!("render.shadows=\"{method}\"")], &[Layer::Diffuse]);
            let mut bad = 0;
            for y in 0..f.height {
                for x in 0..f.width {
                    let (a, b) = (f.at(Layer::Diffuse, x, y), ray.at(Layer::Diffuse, x, y));
                    assert!(a.is_finite(), "{what}, {method}: NaN at ({x}, {y})");
                    if (a - b).abs().max_element() > 0.01 * 6.0 {
                        bad += 1;
                    }
                }
            }
            assert!(bad <= (f.width * f.height / 100) as usize, "{what}, {method}: {bad} pixels differ from rays");
        }
        if what == "light inside" {
            // Everything the eye sees is outside the box: no direct light at all.
            let peak = ray.raw(Layer::Diffuse).unwrap().iter().map(|c| c.max_element()).fold(0.0, f32::max);
            assert_eq!(peak, 0.0, "rays: the box holds the light");
        }
    }
}

/// Volumes and polygons give the same bytes with one worker thread and with four.
#[test]
fn volumes_and_polygons_do_not_depend_on_the_thread_count() {
    let path = lessons_dir().join("45-classic-shadows.toml");
    let dir = tempfile::tempdir().unwrap();
    for set in ["render.shadows=volume", "render.shadows=polygons"] {
        let mut outs = Vec::new();
        for threads in ["1", "4"] {
            let out = dir.path().join(format!("out-{threads}.png"));
            shadelab()
                .args(["--threads", threads, "render"])
                .arg(&path)
                .args(["--set", set, "--set", "camera.size=[160, 120]", "-q", "-o"])
                .arg(&out)
                .assert()
                .success();
            outs.push(std::fs::read(&out).unwrap());
        }
        assert!(outs[0] == outs[1], "{set}: the bytes depend on the thread count");
    }
}

/// `explain` names the method that runs and why; with an area light the render's default
/// `volume` falls back to rays and says so.
#[test]
fn explain_says_which_shadow_method_runs_and_why() {
    let path = lessons_dir().join("45-classic-shadows.toml");
    let out = shadelab().args(["explain"]).arg(&path).args(["--set", "render.shadows=volume"]).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("shadows: volume") && text.contains("Crow 1977"), "{text}");
    assert!(text.contains("shadow-volume quads tested"), "{text}");
    let out = shadelab().args(["explain"]).arg(&path).args(["--set", "render.shadows=polygons"]).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("shadow-polygon pairs projected") && text.contains("n² pairs"), "{text}");
    let area = box_scene(Vec3::new(0.0, 3.0, 0.0), Vec3::new(0.5, 3.0, 4.0)).replace(
        "kind = \"point\"\nposition = [0, 3, 0]\nattenuation = [0, 0, 1]",
        "kind = \"rect\"\nposition = [0, 3, 0]\ndirection = [0, -1, 0]\nsize = [0.5, 0.5]",
    );
    assert!(area.contains("kind = \"rect\""));
    let (_d, file) = lesson_file("area.toml", &area);
    let out = shadelab().args(["explain"]).arg(&file).args(["--set", "render.shadows=volume"]).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("cast from one point, not from an area light"), "{text}");
}
