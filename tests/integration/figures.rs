//! Figures: variants, reuse of one rasterization, labels, errors, snapshots.

use crate::helpers::{lesson_file, lessons_dir, read_png, shadelab};
use shadelab::figure::{FigureOptions, render_figure};
use shadelab::lesson::{self, Axis, FigureBody, FigureSpec, KeyPath};
use shadelab::render::Layer;

fn first_light() -> lesson::Lesson {
    lesson::load(&lessons_dir().join("01-first-light.toml"), &[]).unwrap()
}

fn axis(key: &str, values: Vec<toml::Value>) -> Axis {
    Axis { key: KeyPath::parse(key).unwrap(), values, labels: None, origin: KeyPath::default() }
}

fn spec(body: FigureBody) -> FigureSpec {
    FigureSpec { cell: Some((48, 48)), ..FigureSpec::new("t", body) }
}

#[test]
fn a_material_sweep_rasterizes_once_and_shades_every_cell() {
    let base = first_light();
    let s = spec(FigureBody::sweep(axis("material.plastic.shininess", vec![5.into(), 50.into()])));
    let fig = render_figure(&base, &s, &FigureOptions::default()).unwrap();
    assert_eq!(fig.rasterizations, 1);
    // One rasterization's worth of samples, two cells' worth of shading.
    let one = render_figure(&base, &spec(FigureBody::sweep(axis("material.plastic.shininess", vec![5.into()]))), &FigureOptions::default())
        .unwrap();
    assert_eq!(fig.stats.raster.samples_rasterized, one.stats.raster.samples_rasterized);
    assert_eq!(fig.stats.samples_shaded, 2 * one.stats.samples_shaded);
}

#[test]
fn interpolation_compare_shares_the_raster_but_a_camera_sweep_does_not() {
    let base = first_light();
    let interp = axis("render.interpolation", vec!["flat".into(), "gouraud".into(), "phong".into()]);
    assert_eq!(render_figure(&base, &spec(FigureBody::compare(interp)), &FigureOptions::default()).unwrap().rasterizations, 1);
    let cams =
        axis("camera.position", vec![toml::Value::try_from([0.0, 0.0, 4.0]).unwrap(), toml::Value::try_from([0.0, 1.0, 4.0]).unwrap()]);
    assert_eq!(render_figure(&base, &spec(FigureBody::sweep(cams)), &FigureOptions::default()).unwrap().rasterizations, 2);
}

#[test]
fn grid_figure_has_rows_times_columns_cells() {
    let base = first_light();
    let rows = axis("material.plastic.specular", vec![0.3.into(), 0.6.into()]);
    let cols = axis("material.plastic.shininess", vec![3.into(), 10.into(), 100.into()]);
    let fig = render_figure(&base, &spec(FigureBody::grid(rows, cols)), &FigureOptions::default()).unwrap();
    assert_eq!(fig.rasterizations, 1);
    assert_eq!(fig.stats.samples_shaded % 6, 0);
    let single =
        render_figure(&base, &spec(FigureBody::sweep(axis("material.plastic.shininess", vec![3.into()]))), &FigureOptions::default())
            .unwrap();
    assert_eq!(fig.stats.samples_shaded, 6 * single.stats.samples_shaded);
    // The grid is wider and taller than one cell row.
    assert!(fig.image.width() > 3 * 48 && fig.image.height() > 2 * 48);
}

#[test]
fn a_split_is_one_render_read_out_per_layer() {
    let base = first_light();
    let s = spec(FigureBody::split(vec![Layer::Ambient, Layer::Diffuse, Layer::Specular, Layer::Total]));
    let fig = render_figure(&base, &s, &FigureOptions::default()).unwrap();
    assert_eq!(fig.rasterizations, 1);
    let frame_px = 48 * 48;
    // aa 2 in the lesson: at most 4 samples a pixel, shaded once for all four layers.
    assert!(fig.stats.samples_shaded <= 4 * frame_px as u64);
}

#[test]
fn figure_values_are_validated_and_errors_point_at_the_value() {
    let text = std::fs::read_to_string(lessons_dir().join("01-first-light.toml")).unwrap()
        + "\n[[figure]]\nname = \"bad\"\nkind = \"sweep\"\nvary = \"material.plastic.shininess\"\nvalues = [10, -5]\n";
    let (dir, path) = lesson_file("bad-figure.toml", &text);
    let line = text.lines().count();
    let out = dir.path().join("out");
    let a = shadelab().arg("figures").arg(&path).arg("-o").arg(&out).assert().code(2);
    let err = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(err.contains(&format!("bad-figure.toml:{line}:15:")), "{err}");
    assert!(err.contains("material.plastic.shininess") && err.contains("-5"), "{err}");
    assert!(!out.exists() || std::fs::read_dir(&out).unwrap().next().is_none());
}

#[test]
fn sweep_and_compare_commands_write_labelled_figures() {
    let dir = tempfile::tempdir().unwrap();
    let lesson = lessons_dir().join("01-first-light.toml");
    let one = dir.path().join("sweep.png");
    shadelab()
        .arg("sweep")
        .arg(&lesson)
        .args(["--vary", "material.plastic.shininess=1..256:log:4", "--cell", "40x40", "-q", "-o"])
        .arg(&one)
        .assert()
        .success();
    let two = dir.path().join("grid.png");
    shadelab()
        .arg("sweep")
        .arg(&lesson)
        .args([
            "--vary",
            "material.plastic.specular=0.3,0.6",
            "--vary",
            "material.plastic.shininess=3,5,10,100",
            "--cell",
            "40x40",
            "-q",
            "-o",
        ])
        .arg(&two)
        .assert()
        .success();
    let (a, b) = (read_png(&one), read_png(&two));
    // Four columns each; the grid has two rows and a column of row labels.
    assert!(b.height() > a.height() + 40 && b.width() > a.width());
    let cmp = dir.path().join("cmp.png");
    shadelab()
        .arg("compare")
        .arg(&lesson)
        .args(["--vary", "render.interpolation=flat,gouraud,phong", "--cell", "40x40", "--theme", "dark", "-q", "-o"])
        .arg(&cmp)
        .assert()
        .success();
    shadelab()
        .arg("compare")
        .arg(&lesson)
        .args(["--vary", "render.interpolation=flat,goraud", "-q", "-o"])
        .arg(dir.path().join("x.png"))
        .assert()
        .code(2);
    shadelab()
        .arg("compare")
        .arg(&lesson)
        .args(["--vary", "material.plastic.shininess=1..0:log:3", "-q", "-o"])
        .arg(dir.path().join("y.png"))
        .assert()
        .code(2);
    // --labels replaces the column labels: the cells stay, the header row changes.
    let labelled = dir.path().join("labelled.png");
    shadelab()
        .arg("compare")
        .arg(&lesson)
        .args(["--vary", "render.interpolation=flat,gouraud,phong", "--labels", "a,b,c", "--cell", "40x40", "--theme", "dark", "-q", "-o"])
        .arg(&labelled)
        .assert()
        .success();
    let (plain, labelled) = (read_png(&cmp), read_png(&labelled));
    assert_eq!(plain.height(), labelled.height());
    assert_ne!(plain.as_raw(), labelled.as_raw());
    let a = shadelab()
        .arg("compare")
        .arg(&lesson)
        .args(["--vary", "render.interpolation=flat,gouraud", "--labels", "one", "-q", "-o"])
        .arg(dir.path().join("z.png"))
        .assert()
        .code(2);
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("--labels: 1 label for 2 values"));
    assert!(!dir.path().join("z.png").exists());
}

#[test]
fn transparent_theme_keeps_coverage_as_alpha() {
    let base = first_light();
    let s = spec(FigureBody::sweep(axis("material.plastic.shininess", vec![5.into()])));
    let opts = FigureOptions { theme: shadelab::figure::grid::Theme::Transparent, ..FigureOptions::default() };
    let fig = render_figure(&base, &s, &opts).unwrap();
    let alphas: Vec<u8> = fig.image.pixels().map(|p| p[3]).collect();
    assert_eq!(alphas[0], 0, "margin is transparent");
    assert!(alphas.contains(&255), "the sphere is opaque");
    assert!(alphas.iter().any(|&a| a > 0 && a < 255), "antialiased edges are partly transparent");
}

#[test]
fn lessons_command_lists_every_bundled_lesson_with_its_title() {
    let a = shadelab().arg("lessons").arg(lessons_dir()).assert().success();
    let out = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    for entry in std::fs::read_dir(lessons_dir()).unwrap() {
        let path = entry.unwrap().path();
        // The lessons' own files (the HDRIs in lessons/hdri) sit beside them.
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let l = lesson::load(&path, &[]).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let line = out.lines().find(|line| line.starts_with(&name)).unwrap_or_else(|| panic!("{name} not listed:\n{out}"));
        assert!(line.contains(&l.title), "{line}");
    }
}

#[test]
fn a_label_the_font_cannot_draw_becomes_a_box_and_a_warning() {
    let text = std::fs::read_to_string(lessons_dir().join("01-first-light.toml")).unwrap()
        + "\n[[figure]]\nname = \"glyphs\"\nkind = \"compare\"\nvary = \"material.plastic.shininess\"\nvalues = [8, 64]\nlabels = [\"\u{E000} private\", \"한\"]\ncell = [32, 32]\n";
    let (dir, path) = lesson_file("glyphs.toml", &text);
    let out = dir.path().join("out");
    let a = shadelab().arg("figures").arg(&path).arg("-o").arg(&out).assert().success();
    let err = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(err.contains("warning") && err.contains("no glyph"), "{err}");
    assert!(out.join("glyphs/glyphs.png").is_file());
}

#[test]
fn explain_prints_the_equation_with_values_and_the_plan() {
    let a = shadelab()
        .arg("explain")
        .arg(lessons_dir().join("01-first-light.toml"))
        .args(["--set", "render.interpolation=gouraud"])
        .assert()
        .success();
    let out = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(out.contains("plastic (blinn_phong)"), "{out}");
    assert!(out.contains("max(N·H, 0)^48 0.6⊗L_spec"), "values substituted: {out}");
    let line =
        |what: &str| out.lines().find(|l| l.trim_start().starts_with(what)).unwrap_or_else(|| panic!("no `{what}` in {out}")).to_string();
    assert!(line("lighting at vertices").contains("runs"));
    assert!(line("lighting per sample").contains("skipped"));
    assert!(line("emission").contains("skipped") && line("emission").contains("L_emi = 0"));
    // The render's counts prove the plan: Gouraud lights each vertex once per light, no sample.
    let count = |what: &str| -> u64 { line(what).split_whitespace().last().unwrap().parse().unwrap() };
    let vertices = count("vertices lit (Gouraud)");
    assert!(vertices > 0);
    assert_eq!(count("light evaluations"), vertices, "one light");
    assert_eq!(count("of them per sample (Phong)"), 0);
    assert_eq!(count("NaN samples"), 0);
    assert!(count("samples shaded") > 0 && count("faces lit (flat)") == 0);
    // The passes the render ran are the plan's passes marked `runs`, in order.
    let planned: Vec<String> = out
        .lines()
        .skip_while(|l| *l != "Passes")
        .skip(1)
        .take_while(|l| !l.is_empty())
        .filter(|l| l.split_whitespace().any(|w| w == "runs"))
        .map(|l| l.trim_start().split("  ").next().unwrap().to_string())
        .collect();
    assert_eq!(planned, ["vertex stage", "lighting at vertices", "rasterization", "resolve"], "{out}");
    assert_eq!(line("passes:"), format!("  passes: {}", planned.join(", ")));
}

#[test]
fn a_fitted_figure_fills_its_slide_with_two_rows_and_bad_sizes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sweep.png");
    let lesson = lessons_dir().join("04-shininess.toml");
    let vary = "material.plastic.shininess=1..256:log:8";
    shadelab().args(["sweep"]).arg(&lesson).args(["--vary", vary, "--fit", "1280x720", "-o"]).arg(&out).assert().success();
    let img = read_png(&out);
    assert_eq!(img.dimensions(), (1280, 720));
    // Two rows of four: rows of pixels crossing the cells (mostly not white) form two bands,
    // separated by white and a line of labels (text alone never covers 400 pixels of a row).
    let dark_rows: Vec<u32> =
        (0..720).filter(|&y| (0..1280).filter(|&x| img.get_pixel(x, y).0.iter().any(|&c| c < 200)).count() > 400).collect();
    let bands = dark_rows.windows(2).filter(|w| w[1] > w[0] + 1).count() + 1;
    assert_eq!(bands, 2, "rows of cells");
    // The same sweep on one row would have cells under 1280 / 8 = 160 px tall.
    assert!(dark_rows.len() > 2 * 200, "{} dark rows", dark_rows.len());
    // A lesson's `fit` does the same; a bad one exits 2 with its line.
    let text = std::fs::read_to_string(lessons_dir().join("01-first-light.toml")).unwrap();
    let (_d, path) = lesson_file(
        "fit.toml",
        &format!(
            "{text}\n[[figure]]\nname = \"f\"\nkind = \"compare\"\nvary = \"render.interpolation\"\nvalues = [\"flat\", \"phong\"]\nfit = \"1024x768\"\n"
        ),
    );
    let figs = dir.path().join("figs");
    shadelab().args(["figures"]).arg(&path).arg("-o").arg(&figs).assert().success();
    assert_eq!(read_png(&figs.join("fit/f.png")).dimensions(), (1024, 768));
    let bad = std::fs::read_to_string(&path).unwrap().replace("fit = \"1024x768\"", "fit = \"wide\"");
    // The line of the bad `fit` (lesson 01's length may change).
    let line = bad.lines().position(|l| l == "fit = \"wide\"").expect("the fit line") + 1;
    std::fs::write(&path, bad).unwrap();
    let assert = shadelab().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).to_string();
    // The appended figure comes after lesson 01's own.
    let index = crate::helpers::figure_names(&lessons_dir().join("01-first-light.toml")).len();
    assert!(stderr.contains(&format!("fit.toml:{line}:7: `figure.{index}.fit`: `fit` is a slide size")), "{stderr}");
    shadelab().arg("sweep").arg(&lesson).args(["--vary", vary, "--fit", "100x100", "-o"]).arg(&out).assert().code(2);
}

#[test]
fn one_figure_commands_take_a_folder_and_draw_readable_cells_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("made");
    let lesson = lessons_dir().join("04-shininess.toml");
    // `-o DIR/` writes the default name in it (it was refused for figures, accepted by render).
    let with_slash = format!("{}/", folder.display());
    shadelab().arg("compare").arg(&lesson).args(["--vary", "material.plastic.shininess=8,32,128", "-o", &with_slash]).assert().success();
    let made = folder.join("04-shininess-compare.png");
    let img = image::open(&made).expect("LESSON-compare.png in the folder").to_rgba8();
    // The lesson's camera is 512² but an ad-hoc figure's cells are at most 256 px a side.
    assert!(img.height() < 512 && img.width() < 3 * 512, "{}×{}", img.width(), img.height());
    // An existing folder without the slash works the same; --cell still decides when given.
    shadelab().arg("split").arg(&lesson).arg("-o").arg(&folder).assert().success();
    assert!(folder.join("04-shininess-split.png").is_file());
    shadelab()
        .arg("sweep")
        .arg(&lesson)
        .args(["--vary", "material.plastic.shininess=8,32", "--cell", "300x300", "-o"])
        .arg(&folder)
        .assert()
        .success();
    assert!(image::open(folder.join("04-shininess-sweep.png")).unwrap().height() > 300);
}
