//! `shadelab snapshot`: render every figure and compare it with a blessed PNG.

use super::{CliError, FigureFlags};
use crate::figure::snapshot::{Tolerance, compare, diff_image};
use std::path::PathBuf;

/// Arguments of `shadelab snapshot`.
#[derive(Debug, clap::Args)]
pub struct SnapshotArgs {
    /// Lesson files or folders of lessons.
    #[arg(required = true, value_name = "PATH")]
    pub paths: Vec<PathBuf>,
    /// Folder of blessed snapshots: DIR/<lesson>/<figure>.png.
    #[arg(long, value_name = "DIR")]
    pub dir: PathBuf,
    /// Write (or overwrite) the snapshots instead of comparing. Every lesson and figure is
    /// validated first: if one is bad, nothing is written.
    #[arg(long)]
    pub bless: bool,
    /// Largest per-channel difference (0–255) that does not count as a difference.
    #[arg(long, value_name = "CODES", default_value_t = 2)]
    pub tolerance: u8,
    /// Largest share of differing pixels, in percent, that still matches.
    #[arg(long, value_name = "PERCENT", default_value_t = 0.1)]
    pub max_diff: f64,
    /// Override a value of every lesson by dotted path (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// How figures are drawn (use the same flags when blessing and checking).
    #[command(flatten)]
    pub look: FigureFlags,
}

/// Compares (or blesses) every figure; exit 1 on any mismatch.
pub fn run(args: SnapshotArgs) -> Result<(), CliError> {
    if !(0.0..=100.0).contains(&args.max_diff) {
        return Err(CliError::Input(format!("--max-diff {}: give a percentage from 0 to 100", args.max_diff)));
    }
    let tol = Tolerance { per_pixel: args.tolerance, max_share: args.max_diff / 100.0 };
    let sets = super::overrides(&args.sets, Vec::new())?;
    // Cost figures are drawn untimed: a snapshot must not depend on how fast the machine is.
    let opts = crate::figure::FigureOptions { measure_time: false, ..args.look.options()? };
    // Validate every lesson and figure (and load the meshes) first: one bad lesson must not
    // leave half the snapshots blessed.
    let mut lessons = Vec::new();
    for path in super::figures::lesson_files(&args.paths)? {
        let lesson = crate::lesson::load(&path, &sets)?;
        for spec in &lesson.figures {
            crate::figure::check_figure(&lesson, spec, &opts)?;
        }
        crate::scene::build::build(&lesson)?;
        lessons.push((path, lesson));
    }
    let (mut passed, mut failed, mut blessed) = (0, 0, 0);
    for (path, lesson) in lessons {
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        for spec in &lesson.figures {
            let id = format!("{stem}/{}", spec.name);
            let file = args.dir.join(&stem).join(format!("{}.png", spec.name));
            let actual = crate::figure::render_figure(&lesson, spec, &opts)?.image;
            if args.bless {
                crate::output::write_png_rgba(&file, &actual)?;
                outln!("blessed {id}")?;
                blessed += 1;
                continue;
            }
            let expected = match image::open(&file) {
                Ok(img) => img.to_rgba8(),
                Err(e) => {
                    outln!("FAILED  {id}: no snapshot at {} ({e}); run with --bless to create it", file.display())?;
                    failed += 1;
                    continue;
                }
            };
            let c = compare(&expected, &actual, &tol);
            if c.matches(&tol) {
                outln!("ok      {id} ({} of {} pixels differ, max Δ {})", c.differing, c.total, c.max_delta)?;
                passed += 1;
            } else {
                let diff = file.with_extension("diff.png");
                let new = file.with_extension("actual.png");
                crate::output::write_png_rgba(&diff, &diff_image(&expected, &actual, &tol))?;
                crate::output::write_png_rgba(&new, &actual)?;
                match c.size_mismatch {
                    Some((e, a)) => outln!("FAILED  {id}: size {}×{} expected, got {}×{}; actual: {}", e.0, e.1, a.0, a.1, new.display())?,
                    None => outln!(
                        "FAILED  {id}: {:.3}% of pixels differ by more than {} (allowed {:.3}%), max Δ {}; diff: {}",
                        c.share() * 100.0,
                        tol.per_pixel,
                        tol.max_share * 100.0,
                        c.max_delta,
                        diff.display()
                    )?,
                }
                failed += 1;
            }
        }
    }
    if args.bless {
        outln!("{blessed} snapshots written to {}", args.dir.display())?;
        return Ok(());
    }
    outln!("snapshots: {passed} passed, {failed} failed")?;
    if failed > 0 {
        return Err(CliError::Mismatch(format!("{failed} snapshot{} did not match", if failed == 1 { "" } else { "s" })));
    }
    Ok(())
}
