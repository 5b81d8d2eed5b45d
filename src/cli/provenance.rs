//! What made a PNG, carried in it (course CI, item 7): every figure and render shadelab
//! writes as PNG holds the shadelab version, the command that makes it (the lesson, its
//! overrides; never the output path or the thread count, so the bytes stay the same
//! whatever the run), a hash of each file it read and the drawing options, so `shadelab reproduce
//! FILE.png` can render it again and say whether it matches, or which input changed.

use super::CliError;
use crate::figure::FigureOptions;
use crate::figure::grid::Theme;
use crate::lesson::Lesson;
use crate::render::Layer;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// The iTXt keyword of the recipe (JSON).
pub const KEYWORD: &str = "shadelab";

/// What a PNG shows.
pub enum Made<'a> {
    /// `render`: one layer of the lesson.
    Render(Layer),
    /// A figure of the lesson, drawn with these options.
    Figure(&'a str, &'a FigureOptions),
}

/// Each file the lesson's pictures depend on (the lesson, then its meshes, textures and
/// maps) with its BLAKE3 hash.
fn inputs(lesson: &Lesson) -> Vec<(PathBuf, String)> {
    std::iter::once(lesson.path.clone())
        .chain(lesson.asset_files())
        .map(|p| {
            let hash = std::fs::read(&p).map_or_else(|_| "unreadable".to_string(), |b| blake3::hash(&b).to_hex().to_string());
            (p, hash)
        })
        .collect()
}

fn theme_name(t: Theme) -> &'static str {
    match t {
        Theme::Light => "light",
        Theme::Dark => "dark",
        Theme::Transparent => "transparent",
    }
}

/// The text chunks for a PNG of `lesson` made as `made`.
pub fn tags(lesson: &Lesson, made: Made) -> Vec<(&'static str, String)> {
    // No argument that leaves the picture alone (the output path, --threads, -q): the same
    // picture must be the same bytes whatever the run (DESIGN.md, determinism).
    let sets: Vec<String> = lesson.overrides.iter().flat_map(|o| ["--set".to_string(), o.arg.clone()]).collect();
    let mut command = vec!["shadelab".to_string()];
    match &made {
        Made::Render(layer) => command.extend(["render".into(), lesson.path.display().to_string(), "--layer".into(), layer.name().into()]),
        Made::Figure(..) => command.extend(["figures".into(), lesson.path.display().to_string()]),
    }
    command.extend(sets);
    let mut recipe = json!({
        "version": env!("CARGO_PKG_VERSION"),
        "command": command,
        "lesson": lesson.path.display().to_string(),
        "inputs": inputs(lesson).iter().map(|(p, h)| json!({"file": p.display().to_string(), "blake3": h})).collect::<Vec<_>>(),
        "sets": lesson.overrides.iter().map(|o| o.arg.clone()).collect::<Vec<_>>(),
    });
    match made {
        Made::Render(layer) => {
            recipe["kind"] = json!("render");
            recipe["layer"] = json!(layer.name());
        }
        Made::Figure(name, o) => {
            recipe["kind"] = json!("figure");
            recipe["figure"] = json!(name);
            recipe["options"] = json!({
                "theme": theme_name(o.theme),
                "scale": o.scale,
                "cell": o.cell.map(|(w, h)| [w, h]),
                "fit": o.fit.map(|(w, h)| [w, h]),
                "timings": o.timings,
                "measure_time": o.measure_time,
            });
        }
    }
    vec![("Software", format!("shadelab {}", env!("CARGO_PKG_VERSION"))), (KEYWORD, recipe.to_string())]
}

/// Arguments of `shadelab reproduce`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Make a figure, then render it again from what it records and compare:
    shadelab figures lessons/04-shininess.toml -o out/ -q && shadelab reproduce out/04-shininess/sweep.png
  The same for a render (a failed snapshot's .actual.png works too):
    shadelab render lessons/01-first-light.toml -o first.png -q && shadelab reproduce first.png")]
pub struct ReproduceArgs {
    /// A PNG written by shadelab (`render`, `figures`, `snapshot`).
    #[arg(value_name = "PNG")]
    pub png: PathBuf,
}

/// What the recipe asks for, read back.
fn field<'a>(recipe: &'a Value, key: &str, png: &Path) -> Result<&'a Value, CliError> {
    recipe.get(key).ok_or_else(|| CliError::Input(format!("{}: its shadelab record has no `{key}`", png.display())))
}

/// Renders the PNG's recipe again and compares: exit 0 when it matches bit for bit, 1 when
/// it differs (with the inputs that changed), 2 when the file holds no recipe.
pub fn run(args: ReproduceArgs, quiet: bool) -> Result<(), CliError> {
    let png = &args.png;
    let text = crate::output::png_tags(png).into_iter().find(|(k, _)| k == KEYWORD).map(|(_, t)| t).ok_or_else(|| {
        CliError::Input(format!(
            "{}: no shadelab record in this file\n  hint: `reproduce` reads the PNGs that `shadelab render`, `figures` and `snapshot` write",
            png.display()
        ))
    })?;
    let recipe: Value =
        serde_json::from_str(&text).map_err(|e| CliError::Input(format!("{}: the shadelab record is not JSON: {e}", png.display())))?;
    let version = field(&recipe, "version", png)?.as_str().unwrap_or_default().to_string();
    let lesson_path = PathBuf::from(field(&recipe, "lesson", png)?.as_str().unwrap_or_default());
    let mut changed: Vec<String> = Vec::new();
    if version != env!("CARGO_PKG_VERSION") {
        changed.push(format!("made by shadelab {version}, this is {}", env!("CARGO_PKG_VERSION")));
    }
    for i in field(&recipe, "inputs", png)?.as_array().into_iter().flatten() {
        let file = PathBuf::from(i["file"].as_str().unwrap_or_default());
        let now = std::fs::read(&file).map_or_else(|_| "missing".to_string(), |b| blake3::hash(&b).to_hex().to_string());
        if i["blake3"].as_str() != Some(now.as_str()) {
            changed.push(format!("{} {}", file.display(), if now == "missing" { "is gone" } else { "changed" }));
        }
    }
    let sets: Vec<crate::lesson::Override> = field(&recipe, "sets", png)?
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(Value::as_str)
        .map(|a| crate::lesson::Override::parse(a).map_err(|e| CliError::Input(format!("{}: recorded override `{a}`: {e}", png.display()))))
        .collect::<Result<_, _>>()?;
    let lesson = crate::lesson::load(&lesson_path, &sets)?;
    let again: image::RgbaImage = match field(&recipe, "kind", png)?.as_str() {
        Some("render") => {
            let name = field(&recipe, "layer", png)?.as_str().unwrap_or("total");
            let layer = Layer::ALL.into_iter().find(|l| l.name() == name).unwrap_or(Layer::Total);
            let scene = crate::scene::build::build(&lesson)?;
            crate::render::budget::check(&scene).map_err(|e| e.at(lesson_path.display()))?;
            let s = &scene.spec.settings;
            let (rgb, _) = crate::render::render_image(&scene, layer, s.exposure, s.tonemap);
            let (w, h) = (scene.spec.camera.width, scene.spec.camera.height);
            image::DynamicImage::ImageRgb8(image::RgbImage::from_raw(w, h, rgb).expect("the render's size")).to_rgba8()
        }
        Some("figure") => {
            let name = field(&recipe, "figure", png)?.as_str().unwrap_or_default();
            let o = field(&recipe, "options", png)?;
            let pair = |v: &Value| v.as_array().and_then(|a| Some((a.first()?.as_u64()? as u32, a.get(1)?.as_u64()? as u32)));
            let opts = FigureOptions {
                theme: match o["theme"].as_str() {
                    Some("dark") => Theme::Dark,
                    Some("transparent") => Theme::Transparent,
                    _ => Theme::Light,
                },
                scale: o["scale"].as_f64().unwrap_or(1.0) as f32,
                cell: pair(&o["cell"]),
                fit: pair(&o["fit"]),
                timings: o["timings"].as_bool().unwrap_or(false),
                measure_time: o["measure_time"].as_bool().unwrap_or(true),
            };
            let spec = lesson.figures.iter().find(|f| f.name == name).ok_or_else(|| {
                CliError::Mismatch(format!("{}: the lesson has no figure `{name}` any more{}", lesson_path.display(), because(&changed)))
            })?;
            crate::figure::render_figure(&lesson, spec, &opts)?.image
        }
        other => return Err(CliError::Input(format!("{}: a shadelab record of an unknown kind {other:?}", png.display()))),
    };
    let before = image::open(png).map_err(|e| CliError::Input(format!("{}: {e}", png.display())))?.to_rgba8();
    if before.dimensions() != again.dimensions() {
        let (a, b) = (before.dimensions(), again.dimensions());
        return Err(CliError::Mismatch(format!("{}: {}×{} then, {}×{} now{}", png.display(), a.0, a.1, b.0, b.1, because(&changed))));
    }
    let differing = before.pixels().zip(again.pixels()).filter(|(a, b)| a != b).count();
    if differing == 0 {
        if !quiet {
            outln!("{}: reproduced bit for bit ({}×{} pixels){}", png.display(), before.width(), before.height(), note(&changed))?;
        }
        return Ok(());
    }
    let max = before
        .pixels()
        .zip(again.pixels())
        .map(|(a, b)| a.0.iter().zip(b.0).map(|(x, y)| x.abs_diff(y)).max().unwrap_or(0))
        .max()
        .unwrap_or(0);
    Err(CliError::Mismatch(format!(
        "{}: {differing} of {} pixels differ (max Δ {max}){}",
        png.display(),
        before.width() as u64 * before.height() as u64,
        because(&changed)
    )))
}

/// "; what changed: ..." or, when nothing did, a word on what else can differ.
fn because(changed: &[String]) -> String {
    if changed.is_empty() {
        "; no recorded input changed (the same version, lesson and files): a difference is the program's, on this machine".into()
    } else {
        format!("; what changed since: {}", changed.join("; "))
    }
}

/// A match despite changed inputs says so.
fn note(changed: &[String]) -> String {
    if changed.is_empty() { String::new() } else { format!(", although {}", changed.join("; ")) }
}
