//! `shadelab explain`: the equation each material uses, with its values, and the render plan
//! (the text is `render::explain::text`, shared with `shadelab site`).

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab explain`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Each material's equation with its values, the plan and what one render ran:
    shadelab explain lessons/07-lights.toml
  The plan only, after a change of shadow method (no render):
    shadelab explain lessons/16-shadows.toml --set render.shadows=map --no-render
  Every vector, cosine and term behind two pixels, and a picture of them:
    shadelab explain lessons/37-one-pixel.toml --pixel 115,136 --pixel 185,180 -o probe.png
  The same as one JSON object per pixel:
    shadelab explain lessons/37-one-pixel.toml --pixel 115,136 --format jsonl")]
pub struct ExplainArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// Print the plan only: skip the render whose counts prove it.
    #[arg(long, conflicts_with = "pixel")]
    pub no_render: bool,
    /// Explain one pixel instead: X,Y in the rendered image's pixels, origin top-left as in
    /// the PNG (repeatable).
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub pixel: Vec<(u32, u32)>,
    /// With --pixel: text, or one JSON object per pixel (fields in docs/cli.md).
    #[arg(long, value_enum, default_value = "text", requires = "pixel")]
    pub format: PixelFormat,
    /// With --pixel: also write the render with each probed point, its vectors and a chart
    /// of its terms (PNG).
    #[arg(short, long, value_name = "FILE", requires = "pixel")]
    pub output: Option<PathBuf>,
}

/// How `explain --pixel` prints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PixelFormat {
    /// Text in explain's notation.
    Text,
    /// One JSON object per pixel, one per line.
    Jsonl,
}

/// Parses `X,Y` (e.g. `120,64`) into a pixel.
fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let (x, y) = s.split_once(',').ok_or_else(|| format!("`{s}` is not X,Y, e.g. 120,64 (pixels from the top-left corner)"))?;
    let x: u32 = x.trim().parse().map_err(|_| format!("X `{x}` is not a whole number of pixels from the left (0 or more)"))?;
    let y: u32 = y.trim().parse().map_err(|_| format!("Y `{y}` is not a whole number of pixels from the top (0 or more)"))?;
    Ok((x, y))
}

/// Prints the materials' equations and the plan.
pub fn run(args: ExplainArgs, quiet: bool) -> Result<(), CliError> {
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let lesson = crate::lesson::load(&args.lesson, &sets)?;
    let scene = crate::scene::build::build(&lesson)?;
    if !args.pixel.is_empty() {
        return pixels(&args, &lesson, &scene, quiet);
    }
    // The explanation is the result: -q only checks that the lesson can be explained.
    if quiet {
        return Ok(());
    }
    outln!("{} ({})\n", lesson.title, args.lesson.display())?;
    out!("{}", crate::render::explain::text(&scene, !args.no_render, lesson.lang))
}

/// `explain --pixel`: each pixel's report, printed, and the probe picture with `-o`.
fn pixels(args: &ExplainArgs, lesson: &crate::lesson::Lesson, scene: &crate::scene::Scene, quiet: bool) -> Result<(), CliError> {
    let place = args.lesson.display();
    crate::render::budget::check(scene).map_err(|e| e.at(&place))?;
    if let Some(why) = crate::render::pixel::unexplained(scene) {
        return Err(CliError::Input(format!("{place}: {why}")));
    }
    let reports = crate::render::pixel::explain_pixels(scene, &args.pixel)
        .map_err(|e| CliError::Input(format!("{place}: {e}\n  hint: `shadelab check {place}` prints the image size")))?;
    if let Some(out) = &args.output {
        let png = crate::figure::probe::probe_image(scene, &reports, lesson.lang, 1.0).map_err(CliError::Internal)?;
        crate::output::write_png_rgba(out, &png)?;
    }
    if quiet {
        return Ok(());
    }
    if args.format == PixelFormat::Jsonl {
        for r in &reports {
            outln!("{}", crate::render::pixel_text::json(r))?;
        }
        return Ok(());
    }
    outln!("{} ({})\n", lesson.title, place)?;
    for (i, r) in reports.iter().enumerate() {
        if i > 0 {
            outln!()?;
        }
        out!("{}", crate::render::pixel_text::text(r, scene, lesson.lang))?;
    }
    Ok(())
}
