//! `shadelab render`: one lesson → one image.

use super::CliError;
use crate::output::{self, Format};
use crate::render::{self, Layer};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `shadelab render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    /// Output file, or a folder to write LESSON-NAME.png into (default: the current folder).
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Override a value by dotted path, e.g. material.plastic.shininess=64 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Image size in pixels, e.g. 1024x768 (same as --set camera.size=[W,H]).
    #[arg(long, value_name = "WxH", value_parser = super::parse_size)]
    pub size: Option<(u32, u32)>,
    /// Supersamples per pixel side (same as --set render.aa=N).
    #[arg(long, value_name = "N")]
    pub aa: Option<u32>,
    /// Which term to write.
    #[arg(long, value_enum, default_value = "total")]
    pub layer: LayerArg,
    /// Output format (default: from the file extension, else png).
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub quiet: bool,
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
}

/// `--format` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum FormatArg {
    /// 8-bit sRGB PNG.
    Png,
    /// Linear 32-bit float OpenEXR (no exposure, no tone map).
    Exr,
}

/// Renders the lesson and writes the image.
pub fn run(args: RenderArgs) -> Result<(), CliError> {
    let mut extra = Vec::new();
    if let Some((w, h)) = args.size {
        extra.push(format!("camera.size=[{w}, {h}]"));
    }
    if let Some(aa) = args.aa {
        extra.push(format!("render.aa={aa}"));
    }
    let sets = super::overrides(&args.sets, extra)?;
    let lesson = crate::lesson::load(&args.lesson, &sets)?;
    let format = match (args.format, &args.output) {
        (Some(FormatArg::Png), _) => Format::Png,
        (Some(FormatArg::Exr), _) => Format::Exr,
        (None, Some(p)) => Format::from_path(p).unwrap_or(Format::Png),
        (None, None) => Format::Png,
    };
    let stem = args.lesson.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "render".into());
    let file_name = format!("{stem}.{}", if format == Format::Exr { "exr" } else { "png" });
    // `-o DIR/` (or an existing folder) means "in that folder, named after the lesson".
    let output = match args.output.clone() {
        Some(p) if p.is_dir() || p.as_os_str().to_string_lossy().ends_with(['/', '\\']) => p.join(file_name),
        Some(p) => p,
        None => PathBuf::from(file_name),
    };

    let start = Instant::now();
    let scene = crate::scene::build::build(&lesson)?;
    let layer = match args.layer {
        LayerArg::Ambient => Layer::Ambient,
        LayerArg::Diffuse => Layer::Diffuse,
        LayerArg::Specular => Layer::Specular,
        LayerArg::Emission => Layer::Emission,
        LayerArg::Total => Layer::Total,
        LayerArg::Normal => Layer::Normal,
    };
    let (width, height) = (scene.camera.width, scene.camera.height);
    let (stats, elapsed) = match format {
        Format::Png => {
            // Straight to 8-bit sRGB: the same bytes as developing the linear frame.
            let (rgb, stats) = render::render_image(&scene, layer, scene.settings.exposure, scene.settings.tonemap);
            let elapsed = start.elapsed();
            output::write_png(&output, width, height, &rgb)?;
            (stats, elapsed)
        }
        Format::Exr => {
            let (frame, stats) = render::render(&scene, &[layer]);
            let elapsed = start.elapsed();
            output::write_exr(&output, width, height, &frame.layer(layer).expect("the layer asked for is kept"))?;
            (stats, elapsed)
        }
    };
    if !args.quiet {
        println!(
            "wrote {} ({}×{}, {} layer, aa {}, {} triangles, {:.1} ms)",
            output.display(),
            width,
            height,
            layer.name(),
            scene.settings.aa,
            stats.raster.triangles_in,
            elapsed.as_secs_f64() * 1e3
        );
        if stats.nan_samples > 0 {
            eprintln!("warning: {} samples were not finite and were set to black", stats.nan_samples);
        }
        if !lesson.notes.trim().is_empty() {
            println!("\n{}\n{}", lesson.title, lesson.notes.trim_end());
        }
    }
    Ok(())
}
