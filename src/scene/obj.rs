//! Wavefront OBJ files as one [`Mesh`], read with tobj.
//!
//! Polygons are triangulated as fans and every model (`o`/`g` group) in the file is
//! merged into one mesh; points, lines, texture coordinates and materials are ignored.
//! tobj gives each distinct `v/vt/vn` triple its own vertex, so the file's own `vn`
//! entries decide where edges are hard. Every line tobj would reject (a `v` that is not
//! numbers, a face index of 0 or past the end, ...) is found before tobj sees the file,
//! so the error names its line, and a bad index is never a panic.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use thiserror::Error;

use super::mesh::{Mesh, MeshRepairs};
use super::normals::{compute_vertex_normals, repair_vertex_normals};
use crate::lesson::NormalWeighting;
use crate::lesson::limits::{MAX_OBJ_BYTES, MAX_OBJ_COORD, MAX_TRIANGLES};

/// A mesh read from an OBJ file, with normals always filled in.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedObj {
    /// The merged mesh; `normals` has one unit normal per position.
    pub mesh: Mesh,
    /// Whether the normals came from the file's `vn` lines (kept, normalized) rather than
    /// being computed by averaging face normals.
    pub had_normals: bool,
    /// Degenerate triangles found and normals repaired while filling in the normals.
    pub repairs: MeshRepairs,
    /// The smoothing group of each triangle (`s N`; 0 for `s off`), when the file has `s`
    /// lines; the normals above do not use them (see [`super::smoothing`]).
    pub groups: Option<Vec<u32>>,
}

/// Why an OBJ file could not be loaded. `Display` gives `path:line: what`; [`ObjError::line`]
/// and [`ObjError::what`] give the parts, for messages that name the file their own way.
#[derive(Debug, Error)]
pub enum ObjError {
    /// The file could not be read (e.g. it does not exist, or is not text).
    #[error("cannot read {path}: {cause}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error (`cause.kind()` tells not-found from the rest).
        cause: std::io::Error,
    },
    /// A line is not valid OBJ (found before tobj reads the file).
    #[error("{path}:{line}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// The 1-based line.
        line: usize,
        /// What is wrong with it, quoting the line.
        message: String,
    },
    /// tobj rejected the contents for a reason the line check did not foresee.
    #[error("{path}: {cause}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// What tobj found wrong.
        cause: tobj::LoadError,
    },
    /// A face refers to a position, texture coordinate or normal that does not exist.
    #[error("{path}:{line}: {kind} index {index} is out of range ({count} available)")]
    BadIndex {
        /// The file.
        path: PathBuf,
        /// The 1-based line of the face.
        line: usize,
        /// `"position"`, `"texture coordinate"` or `"normal"`.
        kind: &'static str,
        /// The index as written (1-based, negative counts back from the latest entry).
        index: i64,
        /// How many entries of that kind there are: in the file for positive indices,
        /// before the face for negative ones.
        count: usize,
    },
    /// The file holds no faces with three or more vertices.
    #[error("{path}: no triangles (the file has {positions} `v` lines and no `f` line with 3 or more vertices)")]
    NoTriangles {
        /// The file.
        path: PathBuf,
        /// How many `v` lines it has.
        positions: usize,
    },
    /// The file is larger than [`MAX_OBJ_BYTES`] (checked before it is read).
    #[error("{path}: {bytes} bytes, more than the limit of {} bytes for an OBJ file", MAX_OBJ_BYTES)]
    TooBig {
        /// The file.
        path: PathBuf,
        /// Its size.
        bytes: u64,
    },
    /// The file is not UTF-8 text.
    #[error("{path}: not UTF-8 at byte {at} (OBJ files are text)")]
    NotUtf8 {
        /// The file.
        path: PathBuf,
        /// The offset of the first byte that is not UTF-8.
        at: usize,
    },
    /// The file's triangles bring the scene over [`MAX_TRIANGLES`].
    #[error("{path}: its {triangles} triangles bring the scene to {total}, more than the limit of {}", MAX_TRIANGLES)]
    OverLimit {
        /// The file.
        path: PathBuf,
        /// The file's triangles.
        triangles: usize,
        /// The scene's triangles with this file's.
        total: u64,
    },
    /// The merged mesh has more vertices than a `u32` index can address.
    #[error("{path}: too many vertices for 32-bit indices")]
    TooLarge {
        /// The file.
        path: PathBuf,
    },
}

impl ObjError {
    /// The 1-based line of the file the error is on, when there is one.
    pub fn line(&self) -> Option<usize> {
        match self {
            ObjError::Syntax { line, .. } | ObjError::BadIndex { line, .. } => Some(*line),
            _ => None,
        }
    }

    /// What is wrong, without the path and line.
    pub fn what(&self) -> String {
        match self {
            ObjError::Read { cause, .. } if cause.kind() == std::io::ErrorKind::NotFound => "file not found".into(),
            ObjError::Read { cause, .. } if cause.kind() == std::io::ErrorKind::InvalidData => {
                "not a text file (OBJ files are text)".into()
            }
            ObjError::Read { cause, .. } => format!("cannot read the file: {cause}"),
            ObjError::Syntax { message, .. } => message.clone(),
            ObjError::Parse { cause, .. } => format!("not a valid OBJ file ({cause})"),
            ObjError::BadIndex { kind, index, count, .. } => format!("{kind} index {index} is out of range ({count} available)"),
            ObjError::NoTriangles { positions, .. } => {
                format!("no triangles (the file has {positions} `v` lines and no `f` line with 3 or more vertices)")
            }
            ObjError::TooLarge { .. } => "too many vertices for 32-bit indices".into(),
            ObjError::TooBig { bytes, .. } => format!("{bytes} bytes, more than the limit of {MAX_OBJ_BYTES} bytes for an OBJ file"),
            ObjError::NotUtf8 { at, .. } => format!("not UTF-8 at byte {at} (OBJ files are text)"),
            ObjError::OverLimit { triangles, total, .. } => {
                format!("its {triangles} triangles bring the scene to {total}, more than the limit of {MAX_TRIANGLES}")
            }
        }
    }
}

/// Loads every model of the OBJ file at `path` into one mesh.
///
/// Normals in the file are kept (normalized; zero or non-finite ones are repaired as in
/// [`repair_vertex_normals`]) when every vertex has one; otherwise they are computed
/// with [`NormalWeighting::Average`] (call [`compute_vertex_normals`] again for another
/// weighting).
///
/// # Errors
/// [`ObjError`] when the file cannot be read, does not parse, has a face index out of
/// range, has no triangles, or has more than `u32::MAX` vertices.
pub fn load_obj(path: &Path) -> Result<LoadedObj, ObjError> {
    let read = |cause| ObjError::Read { path: path.to_owned(), cause };
    let bytes = crate::files::metadata(path).map_err(read)?.len;
    if bytes > MAX_OBJ_BYTES {
        return Err(ObjError::TooBig { path: path.to_owned(), bytes });
    }
    // Read at most the limit (the file may grow after the check above).
    let raw = crate::files::read_limited(path, MAX_OBJ_BYTES).map_err(read)?;
    if raw.len() as u64 > MAX_OBJ_BYTES {
        return Err(ObjError::TooBig { path: path.to_owned(), bytes: raw.len() as u64 });
    }
    let text = String::from_utf8(raw).map_err(|e| ObjError::NotUtf8 { path: path.to_owned(), at: e.utf8_error().valid_up_to() })?;
    let text = without_comments(&text);
    check_lines(&text, path)?;

    // tobj's `merging`/`reordering` features add fields, hence the struct update.
    #[allow(clippy::needless_update)]
    let options =
        tobj::LoadOptions { single_index: true, triangulate: true, ignore_points: true, ignore_lines: true, ..Default::default() };
    // Materials are not used; answering every `mtllib` with an error skips the file.
    let no_materials = |_: &Path| Err(tobj::LoadError::GenericFailure);
    let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &options, no_materials)
        .map_err(|cause| ObjError::Parse { path: path.to_owned(), cause })?;

    let too_large = || ObjError::TooLarge { path: path.to_owned() };
    let mut mesh = Mesh::default();
    let mut normals = Vec::new();
    let (mut uvs, mut any_uv) = (Vec::new(), false);
    for model in &models {
        let m = &model.mesh;
        let offset = u32::try_from(mesh.positions.len()).map_err(|_| too_large())?;
        let count = u32::try_from(m.positions.len() / 3).map_err(|_| too_large())?;
        offset.checked_add(count).ok_or_else(too_large)?;
        // tobj keeps single-index meshes in range; check rather than trust.
        if m.indices.iter().any(|&i| i >= count) {
            return Err(ObjError::Parse { path: path.to_owned(), cause: tobj::LoadError::FaceVertexOutOfBounds });
        }
        mesh.positions.extend(m.positions.chunks_exact(3).map(Vec3::from_slice));
        normals.extend(m.normals.chunks_exact(3).map(Vec3::from_slice));
        // `vt` per corner: a model whose faces do not all name one reads (0, 0).
        let vt: Vec<Vec2> = m.texcoords.chunks_exact(2).map(Vec2::from_slice).collect();
        let complete = vt.len() == count as usize;
        any_uv |= complete && count > 0;
        for t in m.indices.chunks_exact(3) {
            uvs.push([t[0], t[1], t[2]].map(|i| if complete { vt[i as usize] } else { Vec2::ZERO }));
        }
        let triangles = m.indices.chunks_exact(3);
        mesh.triangles.extend(triangles.map(|t| [t[0], t[1], t[2]].map(|i| i + offset)));
    }
    if any_uv {
        mesh.uvs = uvs;
    }
    if mesh.triangles.is_empty() {
        let positions = text.lines().filter(|l| l.split_whitespace().next() == Some("v")).count();
        return Err(ObjError::NoTriangles { path: path.to_owned(), positions });
    }

    // tobj only emits normals for face vertices that name one, so a partial set would
    // not line up with the positions: use the file's normals only when complete.
    let had_normals = normals.len() == mesh.positions.len();
    let repairs = if had_normals {
        mesh.normals = normals;
        repair_vertex_normals(&mut mesh)
    } else {
        compute_vertex_normals(&mut mesh, NormalWeighting::Average)
    };
    let groups = smoothing_groups(&text).filter(|g| g.len() == mesh.triangles.len());
    Ok(LoadedObj { mesh, had_normals, repairs, groups })
}

/// The smoothing group of each triangle in file order (a face of n vertices is n − 2
/// triangles, as tobj fans it), or `None` when the file has no `s` line.
fn smoothing_groups(text: &str) -> Option<Vec<u32>> {
    let (mut current, mut any, mut groups) = (0, false, Vec::new());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("s") => {
                any = true;
                // `check_lines` accepted the value: `off` or a whole number.
                current = words.next().and_then(|w| w.parse().ok()).unwrap_or(0);
            }
            Some("f") => groups.extend(std::iter::repeat_n(current, words.count().saturating_sub(2))),
            _ => {}
        }
    }
    any.then_some(groups)
}

/// The text without a leading byte-order mark and with every `#` comment cut from its
/// line (tobj only skips lines that start with `#`); line numbers are unchanged.
fn without_comments(text: &str) -> std::borrow::Cow<'_, str> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if !text.contains('#') {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len());
    for line in text.split('\n') {
        out.push_str(line.split_once('#').map_or(line, |(before, _)| before));
        out.push('\n');
    }
    std::borrow::Cow::Owned(out)
}

/// Checks one number of a `v`, `vt` or `vn` line: finite and at most [`MAX_OBJ_COORD`] in
/// magnitude. `Err` says why, for the line's message.
fn coordinate(word: &str, what: &str) -> Result<f32, String> {
    let Ok(x) = word.parse::<f32>() else { return Err(format!("`{word}` is not a number ({what})")) };
    let lower = word.to_ascii_lowercase();
    if lower.contains("nan") || lower.contains("inf") {
        return Err(format!("`{word}` is not a finite number ({what})"));
    }
    if !x.is_finite() || x.abs() > MAX_OBJ_COORD {
        return Err(format!("`{word}` is out of range: OBJ numbers are at most {MAX_OBJ_COORD:e} in magnitude"));
    }
    Ok(x)
}

/// Finds the first line tobj would reject, as tobj reads it (`v` x y z [w | r g b], `vt` u v,
/// `vn` x y z, `f`/`l` with `v`, `v/vt`, `v//vn`, `v/vt/vn` vertices), so the error has a line.
///
/// Also rejects face indices of 0 or beyond the data they refer to: tobj turns these into
/// huge `usize` values and, for texture and normal indices, multiplies them unchecked,
/// which overflows (a panic in debug builds).
fn check_lines(text: &str, path: &Path) -> Result<(), ObjError> {
    check_lines_within(text, path, MAX_TRIANGLES)
}

/// [`check_lines`] with `max_triangles` the most triangles the file may have.
fn check_lines_within(text: &str, path: &Path, max_triangles: u64) -> Result<(), ObjError> {
    const KINDS: [(&str, &str); 3] = [("v", "position"), ("vt", "texture coordinate"), ("vn", "normal")];
    let kind_of = |word: &str| KINDS.iter().position(|(keyword, _)| *keyword == word);
    let mut totals = [0; 3];
    // Triangles counted while scanning, stopping at the limit: a file of faces past it is
    // refused before tobj builds it (400 MB of faces took 5.8 GB and minutes there).
    let mut triangles: usize = 0;
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("f") => {
                triangles += words.count().saturating_sub(2);
                if triangles as u64 > max_triangles {
                    return Err(ObjError::OverLimit { path: path.to_owned(), triangles, total: triangles as u64 });
                }
            }
            Some(word) => {
                if let Some(kind) = kind_of(word) {
                    totals[kind] += 1;
                }
            }
            None => {}
        }
    }
    let mut seen = [0; 3];
    // tobj indexes vertex colours like positions: all `v` lines have one, or none do.
    let mut coloured: Option<(bool, usize)> = None;
    for (number, line) in text.lines().enumerate() {
        let syntax = |what: String| {
            let t = line.trim();
            let shown: String = if t.chars().count() > 50 { t.chars().take(47).chain("...".chars()).collect() } else { t.to_string() };
            ObjError::Syntax { path: path.to_owned(), line: number + 1, message: format!("`{shown}`: {what}") }
        };
        let mut words = line.split_whitespace();
        match words.next() {
            Some(word @ ("v" | "vt" | "vn")) => {
                let (needs, what) = match word {
                    "v" => (3, "a position needs 3 numbers: x y z"),
                    "vt" => (2, "a texture coordinate needs 2 numbers: u v"),
                    _ => (3, "a normal needs 3 numbers: x y z"),
                };
                let numbers: Vec<&str> = words.collect();
                let mut xyz = [0.0f32; 3];
                for (i, w) in numbers.iter().take(needs).enumerate() {
                    xyz[i] = coordinate(w, what).map_err(&syntax)?;
                }
                if numbers.len() < needs {
                    return Err(syntax(format!("{what}, this line has {}", numbers.len())));
                }
                // A position may add a w (which divides it) or a colour r g b, nothing else.
                if word == "v" {
                    match numbers.len() {
                        4 => {
                            let w = coordinate(numbers[3], "the optional w of x y z w").map_err(&syntax)?;
                            if w == 0.0 {
                                return Err(syntax("w = 0 divides the position by zero".into()));
                            }
                            if xyz.iter().any(|x| !(x / w).is_finite() || (x / w).abs() > MAX_OBJ_COORD) {
                                return Err(syntax(format!(
                                    "x y z divided by w = {w} is out of range: OBJ positions are at most {MAX_OBJ_COORD:e} in magnitude"
                                )));
                            }
                        }
                        3 => {}
                        6 => {
                            for c in &numbers[3..] {
                                coordinate(c, "a vertex colour is r g b").map_err(&syntax)?;
                            }
                        }
                        n => return Err(syntax(format!("a position is x y z, x y z w or x y z r g b; this line has {n} values"))),
                    }
                    let has = numbers.len() == 6;
                    match coloured {
                        None => coloured = Some((has, number + 1)),
                        Some((first, at)) if first != has => {
                            let (with, without) = if first { (at, number + 1) } else { (number + 1, at) };
                            return Err(syntax(format!(
                                "vertex colours (x y z r g b) must be on every `v` line or on none: line {with} has one, line {without} not"
                            )));
                        }
                        Some(_) => {}
                    }
                }
                seen[kind_of(word).expect("a kind")] += 1;
            }
            Some("s") => {
                let value = words.next().unwrap_or("");
                if !(value == "off" || value.parse::<u32>().is_ok()) || words.next().is_some() {
                    return Err(syntax("a smoothing group is `s off` or `s N` with N a whole number (0 is off)".into()));
                }
            }
            Some("f" | "l") => {
                for vertex in words {
                    let parts: Vec<&str> = vertex.split('/').collect();
                    let form = "a face vertex is v, v/vt, v//vn or v/vt/vn with indices counted from 1";
                    if parts.len() > 3 {
                        return Err(syntax(format!("`{vertex}` has more than 3 parts ({form})")));
                    }
                    for (kind, part) in parts.iter().enumerate() {
                        // `v//vn` leaves the texture part empty.
                        if part.is_empty() && kind > 0 {
                            continue;
                        }
                        let Ok(index) = part.parse::<i64>() else {
                            return Err(syntax(format!("`{vertex}` is not a vertex ({form})")));
                        };
                        // Positive indices may point forward (tobj resolves them at the
                        // end); negative ones count back from the entries read so far.
                        let count = if index > 0 { totals[kind] } else { seen[kind] };
                        if index == 0 || index.unsigned_abs() > count as u64 {
                            return Err(ObjError::BadIndex { path: path.to_owned(), line: number + 1, kind: KINDS[kind].1, index, count });
                        }
                    }
                }
            }
            Some("usemtl") if line.split_once(' ').is_none_or(|(_, name)| name.trim().is_empty()) => {
                return Err(syntax("`usemtl` needs a material name".into()));
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes `text` to a file in a fresh temporary directory and loads it.
    fn load(text: &str) -> Result<LoadedObj, ObjError> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("test.obj");
        std::fs::write(&path, text).unwrap();
        load_obj(&path)
    }

    const QUAD: &str = "# a unit quad facing +z\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

    #[test]
    fn quad_without_normals_gets_computed_normals() {
        let loaded = load(QUAD).unwrap();
        assert!(!loaded.had_normals);
        assert_eq!(loaded.repairs, MeshRepairs::default());
        assert_eq!(loaded.mesh.positions.len(), 4);
        assert_eq!(loaded.mesh.triangles.len(), 2);
        assert!(loaded.mesh.normals.iter().all(|&n| n == Vec3::Z));
    }

    #[test]
    fn normals_in_the_file_are_kept_and_normalized() {
        // Deliberately not the face normal, so computing would be caught.
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 2 0\nvn 0 0 0\nf 1//1 2//1 3//2\n";
        let loaded = load(text).unwrap();
        assert!(loaded.had_normals);
        assert_eq!(loaded.repairs.repaired_normals, 1);
        // The zero normal is repaired with the face normal.
        assert_eq!(loaded.mesh.normals, vec![Vec3::Y, Vec3::Y, Vec3::Z]);
    }

    #[test]
    fn smoothing_groups_follow_the_faces_across_models_and_quads() {
        // A quad (two triangles) in group 2, then `s off`, then a triangle in a new model.
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ns 2\nf 1 2 3 4\ns off\no b\nf 1 3 4\n";
        assert_eq!(load(text).unwrap().groups, Some(vec![2, 2, 0]));
        assert_eq!(load(QUAD).unwrap().groups, None);
        let loaded = load_obj(&Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/meshes/cylinder-groups.obj")).unwrap();
        let groups = loaded.groups.unwrap();
        assert_eq!(groups.len(), 96);
        assert!(groups[..48].iter().all(|&g| g == 1) && groups[48..].iter().all(|&g| g == 0));
        // A bad group is a syntax error on its line.
        let e = load("v 0 0 0\nv 1 0 0\nv 0 1 0\ns smooth\nf 1 2 3\n").unwrap_err();
        assert_eq!(e.line(), Some(4), "{e}");
        assert!(e.to_string().contains("`s off` or `s N`"), "{e}");
    }

    #[test]
    fn models_are_merged_with_offset_indices() {
        let text = "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n\
                    o b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf -3 -2 -1\n";
        let mesh = load(text).unwrap().mesh;
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(mesh.positions[3], Vec3::Z);
    }

    #[test]
    fn missing_file_is_a_read_error_naming_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("absent.obj");
        let error = load_obj(&path).unwrap_err();
        let ObjError::Read { cause, .. } = &error else {
            panic!("expected a read error, got {error:?}");
        };
        assert_eq!(cause.kind(), std::io::ErrorKind::NotFound);
        assert!(error.to_string().contains("absent.obj"), "{error}");
    }

    #[test]
    fn bad_indices_are_errors_not_panics() {
        let cases = [
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "position", 4),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "position", 0),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n", "position", -4),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//0 3//1\n", "normal", 0),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n", "texture coordinate", 1),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//6148914691236517206\n", "normal", 6148914691236517206),
        ];
        for (text, expected_kind, expected_index) in cases {
            match load(text) {
                Err(ObjError::BadIndex { line, kind, index, .. }) => {
                    assert_eq!((kind, index), (expected_kind, expected_index), "{text}");
                    assert_eq!(line, text.lines().count(), "{text}");
                }
                other => panic!("{text}: expected BadIndex, got {other:?}"),
            }
        }
    }

    #[test]
    fn unparsable_and_empty_files_are_errors() {
        let error = load("v 0 0 zero\n").unwrap_err();
        assert!(matches!(error, ObjError::Syntax { line: 1, .. }), "{error:?}");
        let error = load("v 0 0 0\nv 1 0 0\nl 1 2\n").unwrap_err();
        assert!(matches!(error, ObjError::NoTriangles { .. }), "{error:?}");
    }

    #[test]
    fn lines_tobj_rejects_are_found_with_their_line() {
        let cases = [
            ("v 0 0 0\nv 1 0\nf 1 2 3\n", 2, "needs 3 numbers"),
            ("v 0 0 0\nv 1 0 0 0\n", 2, "w = 0"),
            ("v 0 0 0\nv 1 0 0 1 1\n", 2, "x y z r g b"),
            ("v 0 0 0\nvt 0 x\n", 2, "`x` is not a number"),
            ("v 0 0 0\n\nvn 0 0\n", 3, "a normal needs 3 numbers"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 three\n", 4, "`three` is not a vertex"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", 4, "more than 3 parts"),
            ("usemtl\n", 1, "needs a material name"),
        ];
        for (text, line, what) in cases {
            let error = load(text).unwrap_err();
            assert_eq!(error.line(), Some(line), "{text:?}: {error}");
            assert!(error.what().contains(what), "{text:?}: {error}");
        }
        // What tobj accepts, the check accepts: v//vn, a w, a colour, forward indices.
        let fine = "f 1//1 2//1 3//1\nv 0 0 0 1\nv 1 0 0 2\nv 0 1 0\nvn 0 0 1\nusemtl red\n";
        assert!(load(fine).is_ok(), "{:?}", load(fine));
        let coloured = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
        assert!(load(coloured).is_ok(), "{:?}", load(coloured));
        let error = load("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n").unwrap_err();
        assert_eq!(error.line(), Some(2), "{error}");
    }

    /// Reliability round two, finding 1: the limit was checked after tobj had built the
    /// whole mesh. Now the scan stops at it, before any mesh is built.
    #[test]
    fn a_file_of_faces_past_the_triangle_limit_is_refused_while_scanning() {
        let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n");
        text.push_str(&"f 1 2 4 3\n".repeat(6));
        let e = check_lines_within(&text, Path::new("big.obj"), 11).unwrap_err();
        assert!(matches!(e, ObjError::OverLimit { triangles: 12, .. }), "{e:?}");
        assert!(check_lines_within(&text, Path::new("big.obj"), 12).is_ok());
        // Stopped at the limit: the bad line after it is never reached.
        text.push_str("v nan 0 0\n");
        assert!(matches!(check_lines_within(&text, Path::new("big.obj"), 11), Err(ObjError::OverLimit { .. })));
    }

    #[test]
    fn degenerate_faces_are_counted_not_fatal() {
        // Collinear, and with a repeated vertex.
        let text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 0\nf 1 2 3\nf 1 2 4\n";
        let loaded = load(text).unwrap();
        assert_eq!(loaded.repairs.degenerate_triangles, 2);
        assert!(loaded.mesh.normals.iter().all(|n| n.is_finite()));
    }

    #[test]
    fn non_finite_and_out_of_range_numbers_name_their_line() {
        let cases = [
            ("v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", 2, "`nan` is not a finite number"),
            ("v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n", 2, "`inf` is not a finite number"),
            ("v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n", 3, "`1e39` is out of range"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0 nan\nf 1 2 3\n", 3, "`nan` is not a finite number"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0 1e-30\nf 1 2 3\n", 3, "divided by w"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -inf\nf 1 2 3\n", 4, "`-inf` is not a finite number"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 NaN\nf 1 2 3\n", 4, "`NaN` is not a finite number"),
            ("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 nan\nf 1 2 3\n", 3, "`nan` is not a finite number"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0 2e6\n", 3, "`2e6` is out of range"),
        ];
        for (text, line, what) in cases {
            let error = load(text).unwrap_err();
            assert_eq!(error.line(), Some(line), "{text:?}: {error}");
            assert!(error.what().contains(what), "{text:?}: {error}");
        }
        // The largest allowed coordinate is fine.
        assert!(load("v 0 0 0\nv 1e6 0 0\nv 0 -1e6 0\nf 1 2 3\n").is_ok());
    }

    #[test]
    fn byte_order_mark_and_end_of_line_comments_are_skipped() {
        let loaded = load("\u{feff}v 0 0 0 # origin\nv 1 0 0#x\nv 0 1 0\t# y\nf 1 2 3 # one face\n").unwrap();
        assert_eq!(loaded.mesh.triangles.len(), 1);
        assert_eq!(loaded.mesh.positions[1], Vec3::X);
        // A comment does not hide an error after it on the next line.
        assert_eq!(load("v 0 0 0 # c\nv 1 0\n").unwrap_err().line(), Some(2));
    }

    #[test]
    fn a_file_that_is_not_utf8_says_where() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bin.obj");
        std::fs::write(&path, b"v 0 0 0\nv \xff 0 0\n").unwrap();
        let error = load_obj(&path).unwrap_err();
        assert!(matches!(error, ObjError::NotUtf8 { at: 10, .. }), "{error:?}");
    }
}
