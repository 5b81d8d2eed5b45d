//! `shadelab export`: a lesson as a glTF 2.0 binary (.glb) for Blender and other tools.

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab export`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  A lesson as a .glb to open in Blender (File → Import → glTF 2.0) and render in Cycles:
    shadelab export lessons/08-three-point-lighting.toml -o three-point.glb
  With a changed value, as `render --set` would draw it:
    shadelab export lessons/30-image-based-lighting.toml --set material.gold.roughness=0.1 -o gold.glb")]
pub struct ExportArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    /// The .glb to write (or a folder ending in / for LESSON-NAME.glb in it) [default: LESSON-NAME.glb].
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub set: super::SetArgs,
}

/// Builds the lesson's scene and writes it as a .glb; warns of every approximation.
pub fn run(args: ExportArgs, quiet: bool) -> Result<(), CliError> {
    let stem = args.lesson.file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
    let out = match &args.output {
        Some(p) if p.is_dir() || p.as_os_str().to_string_lossy().ends_with(['/', '\\']) => p.join(format!("{stem}.glb")),
        Some(p) if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("glb")) => p.clone(),
        Some(p) => {
            return Err(CliError::Input(format!(
                "-o {}: `export` writes a binary glTF, named .glb\n  hint: name it {}, or end the name with / for a folder",
                p.display(),
                p.with_extension("glb").display()
            )));
        }
        None => PathBuf::from(format!("{stem}.glb")),
    };
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let lesson = crate::lesson::load(&args.lesson, &sets)?;
    let scene = crate::scene::build::build(&lesson)?;
    let exported =
        crate::bridge::export::export(&lesson, &scene).map_err(|e| CliError::Input(format!("{}: {e}", args.lesson.display())))?;
    crate::output::write_atomic(&out, |w| w.write_all(&exported.glb).map_err(|e| e.to_string()))?;
    for w in &exported.warnings {
        super::diagnostics::warn(
            super::diagnostics::Diagnostic::warning("gltf", w.clone(), Some(args.lesson.clone()), None),
            format_args!("warning: {}: {w}", args.lesson.display()),
        );
    }
    if !quiet {
        outln!("wrote {} ({} bytes)\n  next: open it in Blender with File → Import → glTF 2.0", out.display(), exported.glb.len())?;
    }
    Ok(())
}
