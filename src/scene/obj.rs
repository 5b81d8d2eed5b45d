//! Wavefront OBJ files as one [`Mesh`], read with tobj.
//!
//! Polygons are triangulated as fans and every model (`o`/`g` group) in the file is
//! merged into one mesh; points, lines, texture coordinates and materials are ignored.
//! tobj gives each distinct `v/vt/vn` triple its own vertex, so the file's own `vn`
//! entries decide where edges are hard. Face indices are checked before tobj sees
//! them, so a bad index is an error with a line number, never a panic.

use std::path::{Path, PathBuf};

use glam::Vec3;
use thiserror::Error;

use super::mesh::{Mesh, MeshRepairs, NormalWeighting};
use super::normals::{compute_vertex_normals, repair_vertex_normals};

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
}

/// Why an OBJ file could not be loaded. The message is complete (path and cause), so
/// the underlying error is a plain field, not a `source()` that would print it twice.
#[derive(Debug, Error)]
pub enum ObjError {
    /// The file could not be read (e.g. it does not exist).
    #[error("cannot read {path}: {cause}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error (`cause.kind()` tells not-found from the rest).
        cause: std::io::Error,
    },
    /// tobj rejected the contents.
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
    #[error("{path}: no triangles")]
    NoTriangles {
        /// The file.
        path: PathBuf,
    },
    /// The merged mesh has more vertices than a `u32` index can address.
    #[error("{path}: too many vertices for 32-bit indices")]
    TooLarge {
        /// The file.
        path: PathBuf,
    },
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
    let text = std::fs::read_to_string(path).map_err(|cause| ObjError::Read { path: path.to_owned(), cause })?;
    check_indices(&text, path)?;

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
        let triangles = m.indices.chunks_exact(3);
        mesh.triangles.extend(triangles.map(|t| [t[0], t[1], t[2]].map(|i| i + offset)));
    }
    if mesh.triangles.is_empty() {
        return Err(ObjError::NoTriangles { path: path.to_owned() });
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
    Ok(LoadedObj { mesh, had_normals, repairs })
}

/// Rejects face indices of 0 or beyond the data they refer to. tobj turns these into
/// huge `usize` values and, for texture and normal indices, multiplies them unchecked,
/// which overflows (a panic in debug builds).
fn check_indices(text: &str, path: &Path) -> Result<(), ObjError> {
    const KINDS: [(&str, &str); 3] = [("v", "position"), ("vt", "texture coordinate"), ("vn", "normal")];
    let kind_of = |word: &str| KINDS.iter().position(|(keyword, _)| *keyword == word);
    let mut totals = [0; 3];
    for word in text.lines().filter_map(|line| line.split_whitespace().next()) {
        if let Some(kind) = kind_of(word) {
            totals[kind] += 1;
        }
    }
    let mut seen = [0; 3];
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("f" | "l") => {
                for vertex in words {
                    // `v`, `v/vt`, `v//vn`, `v/vt/vn`; unparsable parts are left to tobj.
                    for (kind, part) in vertex.split('/').take(3).enumerate() {
                        let Ok(index) = part.parse::<i64>() else {
                            continue;
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
            Some(word) => {
                if let Some(kind) = kind_of(word) {
                    seen[kind] += 1;
                }
            }
            None => {}
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
        assert!(matches!(error, ObjError::Parse { .. }), "{error:?}");
        let error = load("v 0 0 0\nv 1 0 0\nl 1 2\n").unwrap_err();
        assert!(matches!(error, ObjError::NoTriangles { .. }), "{error:?}");
    }

    #[test]
    fn degenerate_faces_are_counted_not_fatal() {
        let text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv nan 0 0\nf 1 2 3\nf 1 2 4\n";
        let loaded = load(text).unwrap();
        assert_eq!(loaded.repairs.degenerate_triangles, 2);
        assert!(loaded.mesh.normals.iter().all(|n| n.is_finite()));
    }
}
