//! `shadelab import`: a glTF 2.0 scene (Blender's File → Export → glTF 2.0) as a lesson.

use super::CliError;
use crate::bridge::import;
use crate::scene::gltf::GltfErrorKind;
use std::path::PathBuf;

/// Arguments of `shadelab import`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  A scene exported from Blender as a lesson here (File → Export → glTF 2.0, .glb; the .glb
  is copied beside the lesson, since a lesson reads only files inside its folder):
    shadelab import lessons/gltf/three-point.glb -o my-scene.toml
  Then its terms side by side:
    shadelab split my-scene.toml -o my-scene-split.png
  Write over a lesson imported before:
    shadelab import lessons/gltf/three-point.glb -o my-scene.toml --force")]
pub struct ImportArgs {
    /// The glTF 2.0 file: a .glb, or a .gltf with its buffers and images in its folder.
    #[arg(value_name = "SCENE")]
    pub scene: PathBuf,
    /// The lesson to write (a .toml file, or a folder ending in / for SCENE-NAME.toml in it).
    /// It must lie in the scene's folder or above it (a lesson reads only files inside its
    /// folder); else a .glb is copied beside it [default: SCENE-NAME.toml beside the scene].
    #[arg(short, long, value_name = "LESSON")]
    pub output: Option<PathBuf>,
    /// Overwrite the lesson (and extracted textures) when they exist.
    #[arg(long)]
    pub force: bool,
}

/// Writes the lesson, checks it parses and validates, and reports what was not read.
pub fn run(args: ImportArgs, quiet: bool) -> Result<(), CliError> {
    if !crate::scene::gltf::is_gltf(&args.scene) {
        return Err(CliError::Input(format!(
            "{}: not a glTF file (the name does not end in .glb or .gltf)\n  hint: export it from Blender with File → Export → glTF 2.0",
            args.scene.display()
        )));
    }
    let stem = args.scene.file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
    let lesson_path = match &args.output {
        Some(p) if p.is_dir() || p.as_os_str().to_string_lossy().ends_with(['/', '\\']) => p.join(format!("{stem}.toml")),
        Some(p) if p.extension().is_some_and(|e| e == "toml") => p.clone(),
        Some(p) => {
            return Err(CliError::Input(format!(
                "-o {}: a lesson's name ends in .toml\n  hint: name it {}, or end the name with / for a folder",
                p.display(),
                p.with_extension("toml").display()
            )));
        }
        None => args.scene.with_extension("toml"),
    };
    if let Some(dir) = lesson_path.parent().filter(|d| !d.as_os_str().is_empty()) {
        crate::output::check_folder(dir, dir)?;
    }
    let imported = import::import(&args.scene, &lesson_path).map_err(|e| {
        let hint = match e.kind {
            GltfErrorKind::Missing => "check the path; a .gltf's buffers and images must be in its folder",
            GltfErrorKind::Outside => "a glTF file may read only files in its own folder (or data: URIs)",
            GltfErrorKind::Limit => "simplify (decimate) the scene in Blender before exporting it",
            GltfErrorKind::Invalid => "export it again (Blender: File → Export → glTF 2.0), or check it with the Khronos glTF validator",
            GltfErrorKind::Selection => "the scene needs at least one mesh",
        };
        CliError::Input(format!("{e}\n  hint: {hint}"))
    })?;
    let mut targets = vec![lesson_path.clone()];
    targets.extend(imported.files.iter().map(|(p, _)| p.clone()));
    if !args.force
        && let Some(exists) = targets
            .iter()
            .find(|p| p.exists() && !imported.files.iter().any(|(f, b)| f == *p && std::fs::read(p).is_ok_and(|old| old == *b)))
    {
        return Err(CliError::Input(format!(
            "{}: already exists; `import` does not overwrite\n  hint: add --force, or choose another name with -o",
            exists.display()
        )));
    }
    // The lesson must validate as written (its textures in place): a failure is our bug,
    // and what was written for it is removed.
    for (path, bytes) in &imported.files {
        crate::output::write_atomic(path, |w| w.write_all(bytes).map_err(|e| e.to_string()))?;
    }
    let parsed = crate::lesson::parse(&imported.lesson, &lesson_path, &[]);
    if let Err(e) = parsed {
        for (path, _) in &imported.files {
            let _ = std::fs::remove_file(path);
        }
        return Err(CliError::Internal(format!("the imported lesson does not validate: {e}\n--- lesson ---\n{}", imported.lesson)));
    }
    crate::output::write_atomic(&lesson_path, |w| w.write_all(imported.lesson.as_bytes()).map_err(|e| e.to_string()))?;
    for w in &imported.warnings {
        super::diagnostics::warn(
            super::diagnostics::Diagnostic::warning("gltf", w.clone(), Some(args.scene.clone()), None),
            format_args!("warning: {}: {w}", args.scene.display()),
        );
    }
    if !quiet {
        for n in &imported.notes {
            outln!("note: {n}")?;
        }
        outln!("wrote {}\n  next: shadelab render {}", lesson_path.display(), lesson_path.display())?;
    }
    Ok(())
}
