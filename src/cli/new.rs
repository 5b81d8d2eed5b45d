//! `shadelab new`: write a commented starter lesson from a template.

use super::CliError;
use std::path::{Path, PathBuf};

/// Arguments of `shadelab new`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  A classic Blinn-Phong lesson, my-lesson.toml in the current folder, then its image:
    shadelab new my-lesson
    shadelab render my-lesson.toml -o out/
  A physically based lesson (Cook-Torrance: a dielectric and gold) beside the others:
    shadelab new 31-gold --template pbr -o lessons/
  Lights and shadows, then its figure:
    shadelab new spot --template lights && shadelab figures spot.toml -o out/
  The homework: three lights on a scene imported from Blender (written beside it):
    shadelab import lessons/gltf/three-point.glb -o scene.toml && shadelab new homework --template three-point --scene scene.toml
  A course repository: two lessons, blessed snapshots, CI for GitHub and GitLab:
    shadelab new --course my-course && sh my-course/ci/run-checks.sh")]
pub struct NewArgs {
    /// The lesson's name: the file is NAME.toml (letters, digits, `-`, `_`, `.`).
    #[arg(value_name = "NAME", required_unless_present = "course", conflicts_with = "course")]
    pub name: Option<String>,
    /// Write a course repository in DIR instead: lessons/ with two starters, snapshots/
    /// blessed, ci/run-checks.sh, CI workflows for GitHub Actions and GitLab CI, a README.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["template", "output"])]
    pub course: Option<PathBuf>,
    /// With --course: the git URL the course's CI installs shadelab from.
    #[arg(long, value_name = "URL", requires = "course", default_value = "")]
    pub shadelab_git: String,
    /// With --course: the revision (tag or commit) of shadelab the CI pins.
    #[arg(long, value_name = "REV", requires = "course", default_value = concat!("v", env!("CARGO_PKG_VERSION")))]
    pub shadelab_rev: String,
    /// What the lesson starts from.
    #[arg(long, value_enum, default_value = "classic")]
    pub template: Template,
    /// Folder to write NAME.toml into, created if needed [default: the current folder].
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// With --template three-point: the lesson whose scene (camera, objects, materials) is lit,
    /// e.g. one `shadelab import` wrote; the new lesson goes in its folder.
    #[arg(long, value_name = "LESSON", conflicts_with = "course")]
    pub scene: Option<PathBuf>,
}

/// `--template` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Template {
    /// The course's classic model: a Blinn-Phong sphere, one light, a term-by-term split.
    Classic,
    /// Physically based: a Cook-Torrance dielectric and a gold sphere, a roughness sweep.
    Pbr,
    /// Lights: a spot over a floor with ray-traced shadows, a spot-exponent sweep.
    Lights,
    /// Three-point lighting placed from the camera (of `--scene LESSON`, e.g. an imported scene).
    ThreePoint,
}

impl Template {
    /// Every template.
    #[cfg(test)]
    pub const ALL: [Template; 4] = [Template::Classic, Template::Pbr, Template::Lights, Template::ThreePoint];

    /// The template's text, with `{NAME}` and `{FILE}` still to fill in.
    fn text(self) -> &'static str {
        match self {
            Template::Classic => include_str!("templates/classic.toml"),
            Template::Pbr => include_str!("templates/pbr.toml"),
            Template::Lights => include_str!("templates/lights.toml"),
            Template::ThreePoint => include_str!("templates/three-point.toml"),
        }
    }

    /// The template's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Template::Classic => "classic",
            Template::Pbr => "pbr",
            Template::Lights => "lights",
            Template::ThreePoint => "three-point",
        }
    }
}

/// The lesson text for `name`, written to `file` (named in its `Try:` lines).
pub fn lesson_text(template: Template, name: &str, file: &Path) -> String {
    let text = template.text().replace("{NAME}", name).replace("{FILE}", &file.display().to_string());
    if template == Template::ThreePoint {
        let lesson = crate::lesson::parse(DEFAULT_SCENE, file, &[]).expect("the default scene is valid");
        let lights = crate::bridge::three_point::text(&crate::bridge::three_point::place(&lesson.scene.camera, true), true);
        return text.replace("{SCENE}", DEFAULT_SCENE.trim_end()).replace("{LIGHTS}", lights.trim_end());
    }
    text
}

/// The three-point template's scene without `--scene`: a physically based ball on a floor.
const DEFAULT_SCENE: &str = "[camera]
position = [0.0, 1.3, 5.0]
look_at = [0.0, 1.0, 0.0]
fov_deg = 40.0
size = [512, 512]
background = [0.02, 0.02, 0.03]

[[object]]
shape = \"uv_sphere\"
segments = 64
rings = 32
translate = [0.0, 1.0, 0.0]
material = \"subject\"

[[object]]
shape = \"plane\"
scale = 4
material = \"floor\"

[material.subject]
model = \"principled\"
base_color = [0.7, 0.7, 0.7]
roughness = 0.4

[material.floor]
model = \"principled\"
base_color = [0.08, 0.08, 0.08]
roughness = 0.9
";

/// `--scene LESSON`'s scene for the three-point template: its tables except `[lesson]`,
/// `[[light]]`, `[[figure]]` (its text as written, comments kept), and whether its materials
/// are physically based. The new lesson must be in the scene's folder (its paths stay valid).
fn scene_of(scene: &Path, file: &Path) -> Result<(String, crate::geometry::Camera, bool), CliError> {
    let lesson = crate::lesson::load(scene, &[])?;
    let here = |p: &Path| match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.canonicalize().ok(),
        _ => Path::new(".").canonicalize().ok(),
    };
    if here(scene) != here(file) {
        return Err(CliError::Input(format!(
            "--scene {}: the new lesson must be in the scene's folder, so the files it names stay where they are\n  hint: add -o {}",
            scene.display(),
            scene.parent().filter(|d| !d.as_os_str().is_empty()).map_or_else(|| ".".into(), |d| d.display().to_string())
        )));
    }
    let physical = lesson.materials.iter().all(|m| m.classic().is_none());
    let mut kept = String::new();
    let mut keep = false;
    for line in lesson.source.lines() {
        if line.starts_with('[') {
            let header = line.split('#').next().unwrap_or("").trim();
            keep = !matches!(header, "[lesson]" | "[[light]]" | "[[figure]]");
        }
        if keep {
            kept.push_str(line);
            kept.push('\n');
        }
    }
    Ok((kept, lesson.scene.camera, physical))
}

/// A name that is safe as a file name and inside a TOML string: no quotes, slashes or spaces.
fn check_name(name: &str) -> Result<&str, CliError> {
    let stem = name.strip_suffix(".toml").unwrap_or(name);
    let ok = !stem.is_empty()
        && stem.len() <= 64
        && !stem.starts_with('.')
        && stem.chars().all(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | '.'));
    if ok {
        Ok(stem)
    } else {
        Err(CliError::Input(format!(
            "new {name}: a lesson name is 1 to 64 letters, digits, `-`, `_` or `.` (not first)\n  hint: e.g. `shadelab new 31-my-lesson`; put it in a folder with -o DIR"
        )))
    }
}

/// Writes the starter lesson; refuses to overwrite a file.
pub fn run(args: NewArgs, quiet: bool) -> Result<(), CliError> {
    if let Some(dir) = &args.course {
        return course(dir, &args.shadelab_git, &args.shadelab_rev, quiet);
    }
    let name = check_name(args.name.as_deref().unwrap_or_default())?;
    let dir = args.output.clone().unwrap_or_default();
    let file = dir.join(format!("{name}.toml"));
    if file.exists() || file.is_symlink() {
        return Err(CliError::Input(format!(
            "{}: already exists; `new` does not overwrite a lesson\n  hint: choose another name, or another folder with -o DIR",
            file.display()
        )));
    }
    if !dir.as_os_str().is_empty() {
        crate::output::check_folder(&dir, &dir)?;
    }
    let text = match &args.scene {
        Some(scene) if args.template == Template::ThreePoint => {
            let (kept, camera, physical) = scene_of(scene, &file)?;
            let lights = crate::bridge::three_point::text(&crate::bridge::three_point::place(&camera, physical), physical);
            let from = format!("# The scene of {}, its lights replaced:\n{}", scene.display(), kept.trim_end());
            Template::ThreePoint
                .text()
                .replace("{NAME}", name)
                .replace("{FILE}", &file.display().to_string())
                .replace("{SCENE}", &from)
                .replace("{LIGHTS}", lights.trim_end())
        }
        Some(_) => {
            return Err(CliError::Input(
                "--scene lights a scene with three lights: it goes with --template three-point\n  hint: add --template three-point".into(),
            ));
        }
        None => lesson_text(args.template, name, &file),
    };
    // A template that does not parse is our bug, not the user's: say so before writing.
    crate::lesson::parse(&text, &file, &[])
        .map_err(|e| CliError::Internal(format!("the {} template is not a valid lesson: {e}", args.template.name())))?;
    crate::output::write_atomic(&file, |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))?;
    if !quiet {
        outln!("wrote {} ({} template)\n  next: shadelab render {}", file.display(), args.template.name(), file.display())?;
    }
    Ok(())
}

/// The course repository's files: (path in it, template text).
const COURSE: [(&str, &str); 4] = [
    ("README.md", include_str!("templates/course/README.md")),
    ("ci/run-checks.sh", include_str!("templates/course/run-checks.sh")),
    (".github/workflows/shadelab.yml", include_str!("templates/course/github.yml")),
    (".gitlab-ci.yml", include_str!("templates/course/gitlab.yml")),
];

/// `new --course DIR`: a course repository whose checks pass as written.
fn course(dir: &Path, git: &str, rev: &str, quiet: bool) -> Result<(), CliError> {
    if dir.exists() && std::fs::read_dir(dir).map_or(true, |mut d| d.next().is_some()) {
        return Err(CliError::Input(format!(
            "{}: exists and is not an empty folder; `new --course` does not write into one\n  hint: name a new folder",
            dir.display()
        )));
    }
    let name = dir.file_name().map_or_else(|| "course".to_string(), |n| n.to_string_lossy().into_owned());
    let lessons = dir.join("lessons");
    for (stem, template) in [("01-classic", Template::Classic), ("02-pbr", Template::Pbr)] {
        let file = lessons.join(format!("{stem}.toml"));
        let text = lesson_text(template, stem, &Path::new("lessons").join(format!("{stem}.toml")));
        crate::output::write_atomic(&file, |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))?;
    }
    for (path, text) in COURSE {
        let text = text.replace("{NAME}", &name).replace("{GIT}", git).replace("{REV}", rev);
        crate::output::write_atomic(&dir.join(path), |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))?;
    }
    // The snapshots CI compares with, blessed by this very program (small cells keep CI fast).
    let snapshot = super::snapshot::SnapshotArgs {
        paths: vec![lessons],
        dir: dir.join("snapshots"),
        bless: true,
        tolerance: 2,
        max_diff: 0.1,
        strict: false,
        junit: None,
        shard: None,
        report: None,
        only: Vec::new(),
        set: super::SetArgs::default(),
        report_flags: super::diagnostics::ReportFlags { format: super::diagnostics::MessageFormat::Text, annotations: None },
        look: super::snapshot::SnapshotLook { theme: None, scale: Some(0.5), cell: Some((128, 128)) },
    };
    super::snapshot::run(snapshot, true)?;
    if !quiet {
        outln!("wrote the course {} (2 lessons, their snapshots, CI for GitHub and GitLab)", dir.display())?;
        if git.is_empty() {
            outln!("  next: set SHADELAB_GIT (the git URL of shadelab) in .github/workflows/shadelab.yml or .gitlab-ci.yml")?;
        }
        outln!("  check it as CI will: sh {}", dir.join("ci/run-checks.sh").display())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_that_would_break_a_path_or_a_toml_string_are_refused() {
        assert_eq!(check_name("31-gold").ok(), Some("31-gold"));
        assert_eq!(check_name("lesson.toml").ok(), Some("lesson"));
        for bad in ["", ".hidden", "a/b", "a\"b", "a b", "../x", &"x".repeat(65)] {
            assert!(check_name(bad).is_err(), "{bad:?} was accepted");
        }
    }

    #[test]
    fn every_template_fills_in_its_name_and_file() {
        for t in Template::ALL {
            let text = lesson_text(t, "demo", Path::new("demo.toml"));
            assert!(!text.contains("{NAME}") && !text.contains("{FILE}"), "{}", t.name());
            assert!(text.contains("title = \"demo\"") && text.contains("shadelab render demo.toml"), "{}", t.name());
        }
    }
}
