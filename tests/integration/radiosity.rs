//! Radiosity through the real program: bad input refused before any work (exit 2, the
//! patch count in the message), the plan and the stats of a radiosity render, a closed
//! white room at E / (1 − ρ) on screen, and the same bytes for any thread count.

use crate::helpers::{lesson_file, lessons_dir, shadelab};
use shadelab::effects::radiosity::{ITERATIONS, PATCHES};
use shadelab::lesson::{self, Override};
use shadelab::render::{self, Layer, plan::Pass};
use shadelab::scene::build::build;
use std::path::Path;

const ROOM: &str = r#"
[camera]
position = [0, 1, 3.8]
look_at = [0, 1, 0]
fov_deg = 38
size = [32, 32]

[[object]]
shape = "plane"
material = "white"

[[object]]
shape = "plane"
scale = 0.25
rotate_deg = [180, 0, 0]
translate = [0, 1.5, 0]
material = "light"

[material.white]
model = "diffuse"
diffuse = 0.75

[material.light]
model = "diffuse"
diffuse = 0
emission = 17

[render]
method = "radiosity"
patch_size = 0.5
"#;

fn run(text: &str, sets: &[&str]) -> std::process::Output {
    let (_dir, path) = lesson_file("room.toml", text);
    let out_png = path.with_extension("png");
    let mut cmd = shadelab();
    cmd.arg("render").arg(&path).arg("-o").arg(&out_png);
    for s in sets {
        cmd.arg("--set").arg(s);
    }
    let out = cmd.output().expect("run shadelab");
    assert!(out.status.code() != Some(2) || !out_png.exists(), "no partial output on bad input");
    out
}

#[test]
fn patch_size_zero_or_negative_is_refused() {
    for v in ["0", "-0.1"] {
        let out = run(ROOM, &[&format!("render.patch_size={v}")]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains("patch_size") && stderr.contains("greater than 0"), "{stderr}");
    }
}

#[test]
fn too_many_patches_is_refused_with_the_count() {
    // The floor's two triangles have hypotenuse 2√2: k = ⌈2.828/0.01⌉ = 283, 2 × 283² = 160178
    // patches, and the light's two: ⌈0.7071/0.01⌉ = 71, 2 × 71² = 10082.
    let out = run(ROOM, &["render.patch_size=0.01"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("170260 patches") && stderr.contains("8192"), "{stderr}");
}

#[test]
fn radiosity_without_an_emitter_is_refused() {
    let out = run(ROOM, &["material.light.emission=0"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("emission"), "{stderr}");
}

#[test]
fn unknown_solver_names_the_choices() {
    let out = run(ROOM, &["render.solver=\"newton\""]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("gauss_seidel") && stderr.contains("progressive"), "{stderr}");
}

/// The plan runs the radiosity pass and no light pass; the stats count the patches (the
/// floor: 2 × ⌈2.83/0.5⌉² = 72, the light: 2 × ⌈0.71/0.5⌉² = 8) and the iterations.
#[test]
fn the_plan_runs_the_radiosity_pass_and_counts_patches() {
    let lesson = lesson::parse(ROOM, Path::new("room.toml"), &[]).unwrap();
    let scene = build(&lesson).unwrap();
    let p = render::plan(&scene);
    let running: Vec<Pass> = p.running().collect();
    assert_eq!(running, [Pass::VertexStage, Pass::Radiosity, Pass::Raster, Pass::Resolve]);
    let (_, st) = render::render(&scene, &[Layer::Total]);
    assert_eq!(st.passes, p.running_bits());
    assert_eq!(st.count(PATCHES), 80);
    assert!(st.count(ITERATIONS) >= 1);
}

/// Lesson 28, coarse, with the final gather and Gouraud display: the same bytes on one thread and on four.
#[test]
fn same_bytes_for_any_thread_count() {
    let path = lessons_dir().join("28-form-factors.toml");
    let sets: Vec<Override> = ["camera.size=[48, 48]", "render.patch_size=0.6", "render.final_gather=true", "render.display=\"gouraud\""]
        .iter()
        .map(|s| Override::parse(s).unwrap())
        .collect();
    let lesson = lesson::load(&path, &sets).unwrap();
    let scene = build(&lesson).unwrap();
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| render::render(&scene, &[Layer::Total]).0)
    };
    let (a, b) = (run(1), run(4));
    let bits = |f: &render::Frame| f.layers[0].1.iter().flat_map(|v| v.to_array().map(f32::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
}

/// A `convergence` figure through the real program: drawn for a radiosity lesson (its legend
/// counts iterations, fewer for Gauss-Seidel than for Jacobi); refused, exit 2, for a raster
/// lesson (naming the figure), an unknown solver or one named twice (with the file's line).
#[test]
fn convergence_figure_is_drawn_and_checked() {
    let figure = "\n[[figure]]\nname = \"conv\"\nkind = \"convergence\"\nsolvers = [\"jacobi\", \"gauss_seidel\"]\ntolerance = 1e-5\n";
    let (dir, path) = lesson_file("room.toml", &format!("{ROOM}{figure}"));
    let out = shadelab().arg("figures").arg(&path).arg("-o").arg(dir.path().join("out")).arg("-q").output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let png = image::open(dir.path().join("out/room/conv.png")).unwrap().to_rgb8();
    assert!(png.width() >= 900 && png.pixels().any(|p| p[2] > 150 && p[0] < 60), "the blue Jacobi line is drawn");
    // The legend's counts come from the solver: on lesson 27's box (coarse patches, where
    // light bounces between walls) Gauss-Seidel settles in fewer sweeps than Jacobi.
    let sets = [Override::parse("render.patch_size=0.7").unwrap()];
    let scene = build(&lesson::load(&lessons_dir().join("27-radiosity.toml"), &sets).unwrap()).unwrap();
    use shadelab::lesson::settings::Solver;
    let c = shadelab::effects::radiosity::convergence(&scene, &Solver::ALL, Some(1e-5));
    let (j, g, p) = (&c.runs[0].1, &c.runs[1].1, &c.runs[2].1);
    assert!(j.residual() <= 1e-5 && g.residual() <= 1e-5 && p.residual() <= 1e-5);
    assert!(g.iterations < j.iterations, "{} vs {}", g.iterations, j.iterations);
    assert!(j.residuals.windows(2).all(|w| w[1] <= w[0]), "{:?}", j.residuals);

    let bad = [
        (ROOM.replace("method = \"radiosity\"", "method = \"raster\""), "plots the radiosity solvers", "figure `conv`"),
        (format!("{ROOM}{}", figure.replace("\"gauss_seidel\"", "\"newton\"")), "newton", "solvers"),
        (format!("{ROOM}{}", figure.replace("\"gauss_seidel\"", "\"jacobi\"")), "listed twice", "solvers"),
    ];
    for (text, needle, key) in bad {
        let text = if text.contains("[[figure]]") { text } else { format!("{text}{figure}") };
        let (_d, p) = lesson_file("bad.toml", &text);
        let out = shadelab().arg("check").arg(&p).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains("bad.toml:") && stderr.contains(key) && stderr.contains(needle), "{stderr}");
    }
}
