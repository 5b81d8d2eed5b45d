//! `shadelab render`: one lesson → one image.

use super::CliError;
use crate::output::{self, Format};
use crate::render::{self, Layer};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `shadelab render`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  The first lesson as an 8-bit sRGB PNG (then its notes):
    shadelab render lessons/01-first-light.toml -o out/first.png
  Change a value, the size and the supersampling without editing the file:
    shadelab render lessons/01-first-light.toml --set material.plastic.shininess=64 --size 512x512 --aa 2 -o out/shiny.png
  One term of the equation only:
    shadelab render lessons/01-first-light.toml --layer specular -o out/spec.png
  Linear float radiance for another tool:
    shadelab render lessons/01-first-light.toml -o out/linear.exr
  Errors and warnings as JSON Lines on stdout, for a tool:
    shadelab render lessons/01-first-light.toml -o out/first.png --format jsonl")]
pub struct RenderArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    /// Output file (`.png` or `.exr`), or a folder (a trailing `/`) to write LESSON.png into
    /// [default: LESSON.png in the current folder].
    #[arg(short, long, value_name = "FILE|DIR/")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// Image size in pixels, e.g. 1024x768 (same as --set camera.size=[W,H]).
    #[arg(long, value_name = "WxH", value_parser = super::parse_size)]
    pub size: Option<(u32, u32)>,
    /// Supersamples per pixel side (same as --set render.aa=N).
    #[arg(long, value_name = "N")]
    pub aa: Option<u32>,
    /// Which term to write.
    #[arg(long, value_enum, default_value = "total")]
    pub layer: LayerArg,
    /// `png` or `exr`: the image file's type [default: from the -o extension, else png]; it
    /// must agree with the extension. `jsonl`: errors and warnings as one JSON object each
    /// on stdout, which then holds nothing else (the image's type from the -o extension).
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,
    /// Also report each error and warning where a CI shows it: `github` (workflow commands
    /// on the lesson's line; the default under GITHUB_ACTIONS=true), `gitlab` (a
    /// code-quality report, gl-code-quality-report.json), `none`.
    #[arg(long, value_enum, value_name = "WHERE")]
    pub annotations: Option<super::diagnostics::Annotations>,
}

/// `--layer` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum LayerArg {
    /// L_glob⊗K_amb + Σ I_amb.
    Ambient,
    /// Σ d I_diff.
    Diffuse,
    /// Σ d I_spec.
    Specular,
    /// L_emi.
    Emission,
    /// The sum of all terms.
    Total,
    /// The shading normal as a colour, (N + 1)/2.
    Normal,
    /// What mirrors and glass reflect.
    Reflection,
    /// What glass transmits (refracted light).
    Transmission,
}

/// `--format` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum FormatArg {
    /// 8-bit sRGB PNG.
    Png,
    /// Linear 32-bit float OpenEXR (no exposure, no tone map).
    Exr,
    /// Messages as text (the default); the image's type from the -o extension.
    Text,
    /// Messages as JSON Lines; the image's type from the -o extension.
    Jsonl,
}

/// Where the image goes: `-o FILE`, or `LESSON-NAME.png` (`.exr`) in `-o DIR/` or the current
/// folder. A file name must end in `.png` or `.exr` and agree with `--format`: PNG bytes in
/// a `.jpg` would mislead whoever opens it.
fn output_path(args: &RenderArgs) -> Result<PathBuf, CliError> {
    let ext = if matches!(args.format, Some(FormatArg::Exr)) { "exr" } else { "png" };
    let stem = args.lesson.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "render".into());
    let file_name = format!("{stem}.{ext}");
    let p = match args.output.clone() {
        // `-o DIR/` (or an existing folder) means "in that folder, named after the lesson".
        Some(p) if p.is_dir() || p.as_os_str().to_string_lossy().ends_with(['/', '\\']) => return Ok(p.join(file_name)),
        Some(p) => p,
        None => return Ok(PathBuf::from(file_name)),
    };
    let Some(given) = p.extension().map(|e| e.to_string_lossy().into_owned()) else {
        // One rule for every command: a file name says its format (docs/cli.md).
        return Err(CliError::Input(format!(
            "-o {}: the name has no extension, so it does not say PNG or EXR\n  hint: name the file {} (or {}), or end the name with / for a folder",
            p.display(),
            p.with_extension(ext).display(),
            p.with_extension(if ext == "png" { "exr" } else { "png" }).display()
        )));
    };
    let named = Format::from_path(&p);
    let asked = args.format.and_then(|f| match f {
        FormatArg::Png => Some(Format::Png),
        FormatArg::Exr => Some(Format::Exr),
        FormatArg::Text | FormatArg::Jsonl => None,
    });
    match (named, asked) {
        (Some(n), Some(a)) if n != a => Err(CliError::Input(format!(
            "-o {}: the name says .{given} but --format is {ext}\n  hint: name the file {} or drop --format",
            p.display(),
            p.with_extension(ext).display()
        ))),
        (Some(_), _) => Ok(p),
        (None, _) => Err(CliError::Input(format!(
            "-o {}: shadelab writes PNG (8-bit sRGB) or EXR (linear float) images, not .{given}\n  hint: name the file {} or {}; --format does not change this, since PNG bytes in a .{given} file would mislead whoever opens it",
            p.display(),
            p.with_extension("png").display(),
            p.with_extension("exr").display()
        ))),
    }
}

/// Renders the lesson and writes the image.
pub fn run(args: RenderArgs, quiet: bool) -> Result<(), CliError> {
    // Under --format jsonl stdout holds only diagnostics: the `wrote` line and notes go.
    let quiet = quiet || super::diagnostics::configure(matches!(args.format, Some(FormatArg::Jsonl)), args.annotations).jsonl;
    let mut extra = Vec::new();
    if let Some((w, h)) = args.size {
        extra.push(format!("camera.size=[{w}, {h}]"));
    }
    if let Some(aa) = args.aa {
        extra.push(format!("render.aa={aa}"));
    }
    let sets = super::overrides(&args.set.sets, extra)?;
    let output = output_path(&args)?;
    crate::output::check_destination(&output)?;
    let lesson = crate::lesson::load(&args.lesson, &sets)?;
    let format = match args.format {
        Some(FormatArg::Exr) => Format::Exr,
        Some(FormatArg::Png) => Format::Png,
        _ => Format::from_path(&output).unwrap_or(Format::Png),
    };

    let start = Instant::now();
    let scene = crate::scene::build::build(&lesson)?;
    crate::render::budget::check(&scene).map_err(|e| e.at(args.lesson.display()))?;
    let layer = match args.layer {
        LayerArg::Ambient => Layer::Ambient,
        LayerArg::Diffuse => Layer::Diffuse,
        LayerArg::Specular => Layer::Specular,
        LayerArg::Emission => Layer::Emission,
        LayerArg::Total => Layer::Total,
        LayerArg::Normal => Layer::Normal,
        LayerArg::Reflection => Layer::Reflection,
        LayerArg::Transmission => Layer::Transmission,
    };
    let (width, height) = (scene.spec.camera.width, scene.spec.camera.height);
    let (stats, elapsed) = match format {
        Format::Png => {
            // Straight to 8-bit sRGB: the same bytes as developing the linear frame.
            let (rgb, stats) = render::render_image(&scene, layer, scene.spec.settings.exposure, scene.spec.settings.tonemap);
            let elapsed = start.elapsed();
            output::write_png_tagged(
                &output,
                (width, height),
                &rgb,
                &super::provenance::tags(&lesson, super::provenance::Made::Render(layer)),
            )?;
            (stats, elapsed)
        }
        Format::Exr => {
            let (frame, stats) = render::render(&scene, &[layer]);
            let elapsed = start.elapsed();
            output::write_exr(&output, width, height, &frame.layer(layer).expect("the layer asked for is kept"))?;
            (stats, elapsed)
        }
    };
    if stats.nan_samples > 0 {
        let message = format!("{} samples were not finite and were set to black", stats.nan_samples);
        super::diagnostics::warn(
            super::diagnostics::Diagnostic::warning("render", message.clone(), Some(args.lesson.clone()), None),
            format_args!("warning: {message}"),
        );
    }
    if !quiet {
        outln!(
            "wrote {} ({}×{}, {} layer, aa {}, {} triangles, {:.1} ms)",
            output.display(),
            width,
            height,
            layer.name(),
            scene.spec.settings.aa,
            stats.raster.triangles_in,
            elapsed.as_secs_f64() * 1e3
        )?;
    }
    if !quiet || super::diagnostics::jsonl() {
        super::repair_notes(&lesson, &scene);
    }
    if !quiet && !lesson.notes.trim().is_empty() {
        outln!("\n{}\n{}", lesson.title, lesson.notes.trim_end())?;
    }
    Ok(())
}
