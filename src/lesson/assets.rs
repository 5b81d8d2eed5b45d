//! Files a lesson names (meshes; later environment maps, cube faces, textures, fonts):
//! the one place that decides whether a path as written may be opened.
//!
//! The rule: after following every symlink, the file lies inside the lesson file's
//! folder tree, or inside a folder given with `--allow-dir DIR`; and it is a regular
//! file (not a folder, FIFO, socket or device). A refused file is never opened, so no
//! byte of it can reach a message. [`resolve`] is called by the validator's
//! `asset_path` for every such key.
//!
//! The allowed folders are a property of the command line, like the thread count, and
//! every validation of the run (the lesson, each figure cell, each ladder rung) must see
//! the same ones, so they are kept for the process: [`allow_dirs`] sets them once.

use crate::output::io_reason;
use std::path::{Component, Path, PathBuf};
use std::sync::RwLock;

/// Folders given with `--allow-dir`, canonical.
static ALLOWED: RwLock<Vec<PathBuf>> = RwLock::new(Vec::new());

/// Why a path a lesson names was refused: the message and the hint of its lesson error.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refused {
    /// What is wrong, naming the path as written.
    pub message: String,
    /// How to fix it.
    pub hint: String,
}

/// Adds folders that lessons may read files from besides their own folder tree
/// (`--allow-dir DIR`).
///
/// # Errors
/// The message for a folder that does not exist or is not a folder.
pub fn allow_dirs(dirs: &[PathBuf]) -> Result<(), String> {
    let mut canonical = Vec::with_capacity(dirs.len());
    for d in dirs {
        let c = d.canonicalize().map_err(|e| format!("--allow-dir {}: {}", d.display(), io_reason(&e)))?;
        if !c.is_dir() {
            return Err(format!("--allow-dir {}: not a folder", d.display()));
        }
        canonical.push(c);
    }
    ALLOWED.write().unwrap_or_else(|e| e.into_inner()).extend(canonical);
    Ok(())
}

/// `path` with `.` and `..` removed lexically (no file system access).
fn lexical(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                // Above the root is the root; above a relative start is kept.
                if !out.pop() && !out.has_root() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

/// `path` (absolute) as the file system resolves it, for a file that may not exist: each
/// existing prefix canonicalized (symlinks followed, so a `..` after a symlinked folder goes
/// to its target's parent, as the OS goes), the missing rest appended lexically.
fn physical(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    let mut parts = path.components();
    for c in parts.by_ref() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => {
                let next = out.join(other);
                match crate::files::canonicalize(&next) {
                    Ok(real) => out = real,
                    Err(_) => {
                        out = next;
                        break;
                    }
                }
            }
        }
    }
    lexical(&out.join(parts.as_path()))
}

/// Resolves `written`, a path as a lesson at `lesson_file` writes it (relative to the
/// lesson's folder, or absolute), to the canonical path of a regular file inside the
/// lesson's folder tree or an allowed folder.
///
/// # Errors
/// [`Refused`] for an empty path, a path (or a symlink's target) outside those folders,
/// a missing file, a folder, a FIFO, a socket or a device.
pub fn resolve(lesson_file: &Path, written: &str) -> Result<PathBuf, Refused> {
    let rule = "files a lesson names must lie inside the lesson file's folder (symlinks are followed)";
    let allow = "or pass --allow-dir DIR to also allow files under DIR";
    if written.trim().is_empty() {
        return Err(Refused {
            message: "the path is empty".into(),
            hint: format!("give a file relative to the lesson, e.g. \"meshes/bunny.obj\"; {rule}"),
        });
    }
    if written.contains('\0') {
        return Err(Refused {
            message: "the path contains a NUL character".into(),
            hint: format!("give a file relative to the lesson; {rule}"),
        });
    }
    let folder = match lesson_file.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let root = crate::files::absolute(folder).map(|a| crate::files::canonicalize(&a).unwrap_or(a)).unwrap_or_else(|_| folder.to_path_buf());
    let allowed = ALLOWED.read().unwrap_or_else(|e| e.into_inner()).clone();
    let inside = |p: &Path| p.starts_with(&root) || allowed.iter().any(|a| p.starts_with(a));
    let outside = || Refused {
        message: format!("{written}: outside the lesson's folder ({})", root.display()),
        hint: format!("{rule}; copy the file into the lesson's folder, {allow}"),
    };
    let joined = root.join(written);
    let canonical = match crate::files::canonicalize(&joined) {
        Ok(c) => c,
        Err(e) => {
            // Where the OS looked: through symlinked folders, `..` after one leaves its target.
            let looked = physical(&joined);
            // Only say "not found" for a place the lesson may look; elsewhere the rule.
            if !inside(&looked) {
                return Err(outside());
            }
            let what = match e.kind() {
                std::io::ErrorKind::NotFound => "file not found".to_string(),
                _ => io_reason(&e),
            };
            return Err(Refused {
                message: format!("{written}: {what} (looked for {})", looked.display()),
                hint: "the path is relative to the lesson file's folder, e.g. path = \"meshes/bunny.obj\"".into(),
            });
        }
    };
    if !inside(&canonical) {
        return Err(outside());
    }
    let meta = crate::files::metadata(&canonical)
        .map_err(|e| Refused { message: format!("{written}: {}", io_reason(&e)), hint: "check the file's permissions".into() })?;
    let kind = meta.kind.described();
    if meta.kind != crate::files::Kind::File {
        return Err(Refused {
            message: format!("{written}: is {kind}, not a regular file"),
            hint: "give an ordinary file (lessons read only regular files)".into(),
        });
    }
    Ok(canonical)
}

/// The files a `.gltf` file's buffers and images name (relative URIs beside it; data URIs
/// and a `.glb`'s own chunks are inside the file), for cache keys. Nothing when the file
/// does not parse: loading it reports that.
pub fn gltf_external_files(path: &Path) -> Vec<PathBuf> {
    let is_gltf = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("gltf"));
    let Some(json) = is_gltf.then(|| crate::files::read(path).ok()).flatten() else { return Vec::new() };
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(&json) else { return Vec::new() };
    let folder = path.parent().unwrap_or(Path::new("."));
    ["buffers", "images"]
        .iter()
        .filter_map(|k| v.get(k)?.as_array())
        .flatten()
        .filter_map(|e| e.get("uri")?.as_str())
        .filter(|u| !u.starts_with("data:") && !u.contains(':'))
        .map(|u| folder.join(percent_encoding::percent_decode_str(u).decode_utf8_lossy().as_ref()))
        .collect()
}

/// How to show `resolved` (a path from [`resolve`]) to the user: relative to the lesson's
/// folder when inside it, else in full.
pub fn shown(lesson_file: &Path, resolved: &Path) -> String {
    let folder = match lesson_file.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let root = crate::files::canonicalize(folder).unwrap_or_else(|_| folder.to_path_buf());
    match resolved.strip_prefix(&root).or_else(|_| resolved.strip_prefix(folder)) {
        Ok(rel) if !rel.as_os_str().is_empty() => rel.display().to_string(),
        _ => resolved.display().to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lesson folder `lessons/` with `meshes/a.obj`, and a secret beside it.
    fn tree() -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let lessons = dir.path().join("lessons");
        std::fs::create_dir_all(lessons.join("meshes")).unwrap();
        std::fs::write(lessons.join("meshes/a.obj"), "v 0 0 0\n").unwrap();
        std::fs::write(dir.path().join("secret.obj"), "v secret_api_key=1\n").unwrap();
        let lesson = lessons.join("l.toml");
        (dir, lesson)
    }

    #[test]
    fn a_file_inside_resolves_to_its_canonical_path() {
        let (_d, lesson) = tree();
        let got = resolve(&lesson, "meshes/./a.obj").unwrap();
        assert_eq!(got, lesson.parent().unwrap().join("meshes/a.obj").canonicalize().unwrap());
        // `..` that stays inside is fine.
        assert!(resolve(&lesson, "meshes/../meshes/a.obj").is_ok());
    }

    #[test]
    fn dot_dot_and_absolute_paths_outside_are_refused_without_reading() {
        let (_d, lesson) = tree();
        for written in ["../secret.obj", "../../../../../../../etc/passwd", "/etc/passwd", "/proc/self/status", "../absent.obj"] {
            let e = resolve(&lesson, written).unwrap_err();
            assert!(e.message.starts_with(&format!("{written}: outside the lesson's folder")), "{written}: {e:?}");
            assert!(e.hint.contains("--allow-dir"), "{e:?}");
            assert!(!e.message.contains("secret_api_key") && !e.message.contains("root:"), "{e:?}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn symlinks_are_followed_in_and_out() {
        let (d, lesson) = tree();
        let folder = lesson.parent().unwrap();
        std::os::unix::fs::symlink(folder.join("meshes/a.obj"), folder.join("in.obj")).unwrap();
        std::os::unix::fs::symlink(d.path().join("secret.obj"), folder.join("out.obj")).unwrap();
        std::os::unix::fs::symlink("/dev/zero", folder.join("zero.obj")).unwrap();
        assert!(resolve(&lesson, "in.obj").is_ok());
        assert!(resolve(&lesson, "out.obj").unwrap_err().message.contains("outside the lesson's folder"));
        assert!(resolve(&lesson, "zero.obj").unwrap_err().message.contains("outside the lesson's folder"));
    }

    /// Reliability round two, finding 8: `sub/../ok.obj` through a symlinked `sub` was
    /// reported as looked for beside the lesson, where the OS never looked.
    #[cfg(unix)]
    #[test]
    fn a_missing_file_through_a_symlinked_folder_names_where_the_os_looked() {
        let (_d, lesson) = tree();
        let folder = lesson.parent().unwrap().canonicalize().unwrap();
        std::fs::create_dir_all(folder.join("a/b")).unwrap();
        std::os::unix::fs::symlink(folder.join("a/b"), folder.join("sub")).unwrap();
        let e = resolve(&lesson, "sub/../ok.obj").unwrap_err().message;
        assert!(e.contains(&format!("looked for {}", folder.join("a/ok.obj").display())), "{e}");
        // Without symlinks it is the lexical place, as before.
        let e = resolve(&lesson, "meshes/../none.obj").unwrap_err().message;
        assert!(e.contains(&format!("looked for {}", folder.join("none.obj").display())), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn folders_fifos_devices_and_missing_files_get_accurate_messages() {
        let (_d, lesson) = tree();
        let folder = lesson.parent().unwrap();
        assert_eq!(resolve(&lesson, "meshes").unwrap_err().message, "meshes: is a folder, not a regular file");
        let fifo = folder.join("pipe.obj");
        let status = std::process::Command::new("mkfifo").arg(&fifo).status();
        if status.is_ok_and(|s| s.success()) {
            assert_eq!(resolve(&lesson, "pipe.obj").unwrap_err().message, "pipe.obj: is a FIFO (named pipe), not a regular file");
        }
        // A device, for a lesson whose folder holds one.
        #[cfg(target_os = "linux")]
        assert_eq!(resolve(Path::new("/dev/l.toml"), "zero").unwrap_err().message, "zero: is a device, not a regular file");
        let e = resolve(&lesson, "meshes/b.obj").unwrap_err();
        assert!(e.message.starts_with("meshes/b.obj: file not found"), "{e:?}");
        assert!(resolve(&lesson, "").unwrap_err().message.contains("empty"));
    }

    #[test]
    fn lexical_removes_dots() {
        assert_eq!(lexical(Path::new("/a/b/../c/./d")), PathBuf::from("/a/c/d"));
        assert_eq!(lexical(Path::new("/a/../../x")), PathBuf::from("/x"));
    }
}
