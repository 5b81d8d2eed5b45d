//! glTF 2.0 files (`.glb`, `.gltf` with its buffers) read safely into meshes.
//!
//! The `gltf` crate parses and validates the JSON; what it leaves unchecked is checked here
//! before any read, because it would panic or loop: an attribute's accessor index (checked
//! before validation), node cycles and nodes with two parents, accessor types and byte
//! ranges, index values, and buffer URIs (only files inside the glTF file's own folder, data
//! URIs up to [`MAX_DATA_URI_BYTES`]). Every error names the file and the JSON path of what
//! is wrong (`/meshes/0/primitives/1/indices`).

use std::path::{Component, Path, PathBuf};

use glam::{Affine3A, Mat4, Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use super::mesh::Mesh;
use crate::lesson::limits::{MAX_OBJ_BYTES, MAX_TRIANGLES};
use crate::lesson::shape::{MeshPart as Selection, NodeRef};

/// The largest data URI a buffer or image may be written as (decoded bytes).
pub const MAX_DATA_URI_BYTES: usize = 64 * 1024 * 1024;

/// Why a glTF file could not be used: the file, where in it, and what.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {at}{}{what}", file.display(), if at.is_empty() { "" } else { ": " })]
pub struct GltfError {
    /// The glTF file.
    pub file: PathBuf,
    /// The JSON path of the part that is wrong (`/nodes/3/children`), or empty for the whole file.
    pub at: String,
    /// What is wrong.
    pub what: String,
    /// The kind, for the hint a command gives.
    pub kind: GltfErrorKind,
}

/// The kinds of [`GltfError`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GltfErrorKind {
    /// The file (or a buffer or image it names) does not exist or cannot be read.
    Missing,
    /// Not a glTF 2.0 file, or its JSON does not validate.
    Invalid,
    /// A URI that leaves the file's folder, or a scheme other than `data:`.
    Outside,
    /// Over a limit (file size, data URI, triangles).
    Limit,
    /// The selected node or primitive does not exist or has no triangles.
    Selection,
}

/// A parsed, validated glTF file with its buffers loaded.
pub struct GltfFile {
    /// The file.
    pub path: PathBuf,
    /// The document (validated).
    pub doc: gltf::Document,
    /// Each buffer's bytes, by index.
    pub buffers: Vec<Vec<u8>>,
}

/// A mesh node of the default scene, with its world transform.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshNode {
    /// The node's index.
    pub node: usize,
    /// The node's name, if it has one.
    pub name: Option<String>,
    /// Object space to world.
    pub world: Mat4,
}

/// A selection read into one mesh (in world space), with what was read.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedGltf {
    /// The merged mesh, each primitive moved by its node's world transform.
    pub mesh: Mesh,
    /// Whether every primitive gave normals.
    pub had_normals: bool,
    /// Primitives skipped because they are points or lines (JSON paths).
    pub skipped: Vec<String>,
}

impl GltfFile {
    /// An error about this file at `at`.
    pub fn err(&self, at: impl Into<String>, what: impl Into<String>, kind: GltfErrorKind) -> GltfError {
        GltfError { file: self.path.clone(), at: at.into(), what: what.into(), kind }
    }

    /// Every mesh node of the default scene (else the first scene, else every root node),
    /// depth first, with its world transform.
    pub fn mesh_nodes(&self) -> Vec<MeshNode> {
        let mut out = Vec::new();
        self.walk(&mut |node, world| {
            if node.mesh().is_some() {
                out.push(MeshNode { node: node.index(), name: node.name().map(str::to_string), world });
            }
        });
        out
    }

    /// Calls `visit` on every node of the scene shown, parents first, with its world transform.
    pub fn walk(&self, visit: &mut dyn FnMut(&gltf::Node, Mat4)) {
        fn go(node: gltf::Node, parent: Mat4, visit: &mut dyn FnMut(&gltf::Node, Mat4)) {
            let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            visit(&node, world);
            for c in node.children() {
                go(c, world, visit);
            }
        }
        let roots: Vec<gltf::Node> = match self.doc.default_scene().or_else(|| self.doc.scenes().next()) {
            Some(scene) => scene.nodes().collect(),
            None => {
                let mut child = vec![false; self.doc.nodes().len()];
                self.doc.nodes().flat_map(|n| n.children()).for_each(|c| child[c.index()] = true);
                self.doc.nodes().filter(|n| !child[n.index()]).collect()
            }
        };
        for root in roots {
            go(root, Mat4::IDENTITY, visit);
        }
    }

    /// The mesh nodes `sel` names.
    fn selected(&self, sel: &Selection) -> Result<Vec<MeshNode>, GltfError> {
        let all = self.mesh_nodes();
        let Some(want) = &sel.node else {
            if all.is_empty() {
                return Err(self.err("/nodes", "the scene has no mesh node", GltfErrorKind::Selection));
            }
            return Ok(all);
        };
        let found: Vec<MeshNode> = all
            .iter()
            .filter(|n| match want {
                NodeRef::Name(name) => n.name.as_deref() == Some(name.as_str()),
                NodeRef::Index(i) => n.node == *i as usize,
            })
            .cloned()
            .collect();
        if found.is_empty() {
            let names: Vec<String> =
                all.iter().take(12).map(|n| n.name.as_ref().map_or_else(|| n.node.to_string(), |s| format!("`{s}`"))).collect();
            return Err(self.err(
                "/nodes",
                format!("no mesh node {want} in the scene (mesh nodes: {})", names.join(", ")),
                GltfErrorKind::Selection,
            ));
        }
        Ok(found)
    }

    /// The selection as one world-space mesh. `triangles_before` is the scene's count so far,
    /// for the limit.
    ///
    /// # Errors
    /// [`GltfError`] for a selection that names nothing, an accessor that does not fit its
    /// buffer, an index out of range, or more than [`MAX_TRIANGLES`] in all.
    pub fn load(&self, sel: &Selection, triangles_before: u64) -> Result<LoadedGltf, GltfError> {
        let mut mesh = Mesh::default();
        let (mut had_normals, mut skipped) = (true, Vec::new());
        for n in self.selected(sel)? {
            let node = self.doc.nodes().nth(n.node).expect("a node of the document");
            let gmesh = node.mesh().expect("a mesh node");
            let count = gmesh.primitives().len();
            if let Some(p) = sel.primitive
                && p as usize >= count
            {
                let at = format!("/meshes/{}/primitives", gmesh.index());
                return Err(self.err(at, format!("primitive {p} does not exist ({count} primitives)"), GltfErrorKind::Selection));
            }
            for prim in gmesh.primitives().filter(|p| sel.primitive.is_none_or(|want| want as usize == p.index())) {
                let at = format!("/meshes/{}/primitives/{}", gmesh.index(), prim.index());
                let Some(part) = self.primitive(&prim, &at)? else {
                    skipped.push(at);
                    continue;
                };
                had_normals &= !part.normals.is_empty();
                let total = triangles_before + mesh.triangles.len() as u64 + part.triangles.len() as u64;
                if total > MAX_TRIANGLES {
                    return Err(self.err(
                        at,
                        format!("its triangles bring the scene to {total}, more than the limit of {MAX_TRIANGLES}"),
                        GltfErrorKind::Limit,
                    ));
                }
                append(&mut mesh, &part.transformed(Affine3A::from_mat4(n.world)));
            }
        }
        if mesh.triangles.is_empty() {
            return Err(self.err("/meshes", "the selection has no triangles", GltfErrorKind::Selection));
        }
        if !had_normals {
            mesh.normals.clear();
        }
        Ok(LoadedGltf { mesh, had_normals, skipped })
    }

    /// One primitive as an object-space mesh (uvs per corner, v flipped to the bottom-up
    /// convention); `None` for points and lines.
    fn primitive(&self, prim: &gltf::Primitive, at: &str) -> Result<Option<Mesh>, GltfError> {
        if matches!(prim.mode(), Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip) {
            return Ok(None);
        }
        let attr = |name: &str| format!("{at}/attributes/{name}");
        let pos = prim
            .get(&gltf::Semantic::Positions)
            .ok_or_else(|| self.err(attr("POSITION"), "a triangle primitive needs POSITION", GltfErrorKind::Invalid))?;
        self.check_accessor(&pos, Dimensions::Vec3, &[DataType::F32], &attr("POSITION"))?;
        let read = prim.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice));
        let positions: Vec<Vec3> = read.read_positions().map(|it| it.map(Vec3::from).collect()).unwrap_or_default();
        if let Some(i) = positions.iter().position(|p| !p.is_finite() || p.abs().max_element() > 1e6) {
            return Err(self.err(
                attr("POSITION"),
                format!("vertex {i} is {:?} (not finite, or above 10⁶)", positions[i]),
                GltfErrorKind::Invalid,
            ));
        }
        let mut normals = Vec::new();
        if let Some(a) = prim.get(&gltf::Semantic::Normals) {
            self.check_accessor(&a, Dimensions::Vec3, &[DataType::F32], &attr("NORMAL"))?;
            normals = read.read_normals().map(|it| it.map(Vec3::from).collect()).unwrap_or_default();
            if a.count() != pos.count() {
                return Err(self.err(
                    attr("NORMAL"),
                    format!("{} normals for {} positions", a.count(), pos.count()),
                    GltfErrorKind::Invalid,
                ));
            }
            // A zero or broken normal is repaired later, as an OBJ's is.
            normals.iter_mut().for_each(|n| *n = if n.is_finite() { n.normalize_or_zero() } else { Vec3::ZERO });
        }
        let mut uv_of_vertex = Vec::new();
        if let Some(a) = prim.get(&gltf::Semantic::TexCoords(0)) {
            self.check_accessor(&a, Dimensions::Vec2, &[DataType::F32, DataType::U8, DataType::U16], &attr("TEXCOORD_0"))?;
            if a.data_type() != DataType::F32 && !a.normalized() {
                return Err(self.err(attr("TEXCOORD_0"), "integer texture coordinates must be normalized", GltfErrorKind::Invalid));
            }
            uv_of_vertex = read
                .read_tex_coords(0)
                .map(|t| {
                    t.into_f32().map(|[u, v]| if u.is_finite() && v.is_finite() { Vec2::new(u, 1.0 - v) } else { Vec2::ZERO }).collect()
                })
                .unwrap_or_default();
            if a.count() != pos.count() {
                return Err(self.err(
                    attr("TEXCOORD_0"),
                    format!("{} uvs for {} positions", a.count(), pos.count()),
                    GltfErrorKind::Invalid,
                ));
            }
        }
        let n = positions.len();
        let indices: Vec<u32> = match prim.indices() {
            Some(a) => {
                let at = format!("{at}/indices");
                self.check_accessor(&a, Dimensions::Scalar, &[DataType::U8, DataType::U16, DataType::U32], &at)?;
                let idx: Vec<u32> = read.read_indices().map(|i| i.into_u32().collect()).unwrap_or_default();
                if let Some(bad) = idx.iter().find(|&&i| i as usize >= n) {
                    return Err(self.err(at, format!("index {bad} is out of range ({n} vertices)"), GltfErrorKind::Invalid));
                }
                idx
            }
            None => (0..n as u32).collect(),
        };
        let triangles: Vec<[u32; 3]> =
            match prim.mode() {
                Mode::TriangleStrip => (2..indices.len())
                    .map(|i| {
                        if i % 2 == 0 { [indices[i - 2], indices[i - 1], indices[i]] } else { [indices[i - 1], indices[i - 2], indices[i]] }
                    })
                    .collect(),
                Mode::TriangleFan => (2..indices.len()).map(|i| [indices[0], indices[i - 1], indices[i]]).collect(),
                _ => indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
            };
        let uvs =
            if uv_of_vertex.is_empty() { Vec::new() } else { triangles.iter().map(|t| t.map(|i| uv_of_vertex[i as usize])).collect() };
        Ok(Some(Mesh { positions, normals, triangles, uvs }))
    }

    /// Checks an accessor before the reader touches it (the reader panics on a wrong type,
    /// a zero count or a range past its buffer).
    fn check_accessor(&self, a: &gltf::Accessor, dims: Dimensions, types: &[DataType], at: &str) -> Result<(), GltfError> {
        let bad = |what: String| Err(self.err(format!("{at} (accessor {})", a.index()), what, GltfErrorKind::Invalid));
        if a.dimensions() != dims || !types.contains(&a.data_type()) {
            return bad(format!("is {:?} of {:?}, expected {dims:?} of {types:?}", a.dimensions(), a.data_type()));
        }
        if a.count() == 0 {
            return bad("has no elements".into());
        }
        if a.sparse().is_some() {
            return bad("is sparse, which is not read".into());
        }
        let Some(view) = a.view() else { return bad("has no buffer view".into()) };
        let size = a.size();
        let stride = view.stride().unwrap_or(size);
        let need = (a.count() - 1).checked_mul(stride).and_then(|x| x.checked_add(size)).and_then(|x| x.checked_add(a.offset()));
        let view_end = view.offset().checked_add(view.length());
        let buffer = self.buffers.get(view.buffer().index()).map_or(0, Vec::len);
        match (need, view_end) {
            (Some(need), Some(end)) if stride >= size && need <= view.length() && end <= buffer => Ok(()),
            _ => bad(format!("does not fit in buffer view {} (or the view does not fit in its buffer)", view.index())),
        }
    }
}

/// Appends `part` to `mesh`, offsetting its indices.
fn append(mesh: &mut Mesh, part: &Mesh) {
    let offset = mesh.positions.len() as u32;
    mesh.positions.extend_from_slice(&part.positions);
    mesh.normals.extend_from_slice(&part.normals);
    mesh.triangles.extend(part.triangles.iter().map(|t| t.map(|i| i + offset)));
    if !part.uvs.is_empty() || !mesh.uvs.is_empty() {
        let before = mesh.triangles.len() - part.triangles.len();
        mesh.uvs.resize(before, [Vec2::ZERO; 3]);
        if part.uvs.is_empty() {
            mesh.uvs.resize(mesh.triangles.len(), [Vec2::ZERO; 3]);
        } else {
            mesh.uvs.extend_from_slice(&part.uvs);
        }
    }
}

/// Opens a `.glb` or `.gltf` file, validates it and loads its buffers.
///
/// # Errors
/// [`GltfError`] as the module says.
pub fn open(path: &Path) -> Result<GltfFile, GltfError> {
    let err = |at: &str, what: String, kind| GltfError { file: path.to_owned(), at: at.into(), what, kind };
    let bytes = read_limited(path).map_err(|(what, kind)| err("", what, kind))?;
    if bytes.starts_with(b"glTF") {
        // The crate subtracts the header from the declared length unchecked.
        let len = bytes.get(8..12).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
        if !len.is_some_and(|l| (20..=bytes.len()).contains(&l)) {
            return Err(err(
                "",
                "not a valid .glb (its header's length is wrong: the file is cut short or damaged)".into(),
                GltfErrorKind::Invalid,
            ));
        }
    }
    let raw = gltf::Gltf::from_slice_without_validation(&bytes)
        .map_err(|e| err("", format!("not a valid glTF 2.0 file ({e})"), GltfErrorKind::Invalid))?;
    // Validation itself indexes the accessors by each attribute unchecked.
    let json = raw.document.as_json();
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            for (name, a) in &prim.attributes {
                if a.value() >= json.accessors.len() {
                    let name = match name {
                        gltf::json::validation::Checked::Valid(s) => s.to_string(),
                        _ => "?".into(),
                    };
                    let at = format!("/meshes/{m}/primitives/{p}/attributes/{name}");
                    return Err(err(
                        &at,
                        format!("accessor {} does not exist ({} accessors)", a.value(), json.accessors.len()),
                        GltfErrorKind::Invalid,
                    ));
                }
            }
        }
    }
    let gltf::Gltf { document, mut blob } = raw;
    let doc = gltf::Document::from_json(document.into_json()).map_err(|e| match e {
        gltf::Error::Validation(list) => {
            let (at, what) =
                list.first().map_or_else(|| (String::new(), "invalid".to_string()), |(p, e)| (json_pointer(&p.to_string()), e.to_string()));
            err(
                &at,
                format!("{what}{}", if list.len() > 1 { format!(" (and {} more problems)", list.len() - 1) } else { String::new() }),
                GltfErrorKind::Invalid,
            )
        }
        other => err("", other.to_string(), GltfErrorKind::Invalid),
    })?;
    check_node_graph(&doc).map_err(|(at, what)| err(&at, what, GltfErrorKind::Invalid))?;
    let folder = path.parent().unwrap_or(Path::new("."));
    let mut buffers = Vec::new();
    for b in doc.buffers() {
        let at = format!("/buffers/{}", b.index());
        let data = match b.source() {
            gltf::buffer::Source::Bin => {
                blob.take().ok_or_else(|| err(&at, "the .glb has no binary chunk".into(), GltfErrorKind::Invalid))?
            }
            gltf::buffer::Source::Uri(uri) => read_uri(folder, uri).map_err(|(what, kind)| err(&format!("{at}/uri"), what, kind))?,
        };
        if data.len() < b.length() {
            return Err(err(&at, format!("{} bytes, shorter than its byteLength {}", data.len(), b.length()), GltfErrorKind::Invalid));
        }
        buffers.push(data);
    }
    Ok(GltfFile { path: path.to_owned(), doc, buffers })
}

/// `meshes[0].primitives[1]` as a JSON pointer, `/meshes/0/primitives/1`.
fn json_pointer(dotted: &str) -> String {
    let mut out = String::new();
    for part in dotted.split(['.', '[', ']']).filter(|s| !s.is_empty()) {
        out.push('/');
        out.push_str(part);
    }
    out
}

/// A file's bytes, refused above [`MAX_OBJ_BYTES`] (the same bound as a mesh file).
fn read_limited(path: &Path) -> Result<Vec<u8>, (String, GltfErrorKind)> {
    let raw = crate::files::read_limited(path, MAX_OBJ_BYTES).map_err(|e| (io_what(&e), GltfErrorKind::Missing))?;
    if raw.len() as u64 > MAX_OBJ_BYTES {
        return Err((format!("more than the limit of {MAX_OBJ_BYTES} bytes"), GltfErrorKind::Limit));
    }
    Ok(raw)
}

fn io_what(e: &std::io::Error) -> String {
    if e.kind() == std::io::ErrorKind::NotFound { "file not found".into() } else { format!("cannot read the file: {e}") }
}

/// The bytes a buffer or image URI names: a base64 data URI, or a relative path inside `folder`.
///
/// # Errors
/// What is wrong and its kind.
pub fn read_uri(folder: &Path, uri: &str) -> Result<Vec<u8>, (String, GltfErrorKind)> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((meta, payload)) = rest.split_once(',') else {
            return Err(("a data URI without a comma".into(), GltfErrorKind::Invalid));
        };
        if !meta.ends_with(";base64") {
            return Err(("a data URI that is not base64".into(), GltfErrorKind::Invalid));
        }
        if payload.len() / 4 * 3 > MAX_DATA_URI_BYTES {
            return Err((
                format!("a data URI of about {} bytes, more than the limit of {MAX_DATA_URI_BYTES}", payload.len() / 4 * 3),
                GltfErrorKind::Limit,
            ));
        }
        return decode_base64(payload).ok_or_else(|| ("a data URI that is not valid base64".into(), GltfErrorKind::Invalid));
    }
    let outside = || (format!("`{uri}` is outside the glTF file's folder"), GltfErrorKind::Outside);
    if uri.contains(':') || uri.starts_with('/') || uri.starts_with('\\') {
        return Err(outside());
    }
    let decoded = percent_encoding::percent_decode_str(uri).decode_utf8_lossy().into_owned();
    let rel = Path::new(&decoded);
    if rel.components().any(|c| !matches!(c, Component::Normal(_) | Component::CurDir)) {
        return Err(outside());
    }
    let base = crate::files::canonicalize(folder).map_err(|e| (io_what(&e), GltfErrorKind::Missing))?;
    let full = crate::files::canonicalize(&base.join(rel)).map_err(|e| (format!("`{uri}`: {}", io_what(&e)), GltfErrorKind::Missing))?;
    if !full.starts_with(&base) {
        return Err(outside());
    }
    read_limited(&full).map_err(|(what, kind)| (format!("`{uri}`: {what}"), kind))
}

/// Standard base64 (RFC 4648, padding optional).
fn decode_base64(s: &str) -> Option<Vec<u8>> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    };
    let bytes: Vec<u8> = s.bytes().filter(|c| !c.is_ascii_whitespace()).collect();
    let body = bytes.strip_suffix(b"==").or_else(|| bytes.strip_suffix(b"=")).unwrap_or(&bytes);
    let mut out = Vec::with_capacity(body.len() * 3 / 4);
    for chunk in body.chunks(4) {
        let v: Option<Vec<u8>> = chunk.iter().map(|&c| value(c)).collect();
        let v = v?;
        let n = v.iter().fold(0u32, |acc, &x| (acc << 6) | x as u32) << (6 * (4 - v.len()));
        let take = match v.len() {
            4 => 3,
            3 => 2,
            2 => 1,
            _ => return None,
        };
        out.extend_from_slice(&n.to_be_bytes()[1..1 + take]);
    }
    Some(out)
}

/// Refuses node graphs the crate accepts but a walk cannot: a node that is its own child,
/// has two parents, or lies on a cycle.
fn check_node_graph(doc: &gltf::Document) -> Result<(), (String, String)> {
    let n = doc.nodes().len();
    let mut parent = vec![None::<usize>; n];
    for node in doc.nodes() {
        for c in node.children() {
            if c.index() == node.index() {
                return Err((format!("/nodes/{}/children", node.index()), format!("node {} is its own child", c.index())));
            }
            if let Some(first) = parent[c.index()].replace(node.index()) {
                return Err((
                    format!("/nodes/{}/children", node.index()),
                    format!("node {} has two parents ({first} and {}); glTF nodes form a tree", c.index(), node.index()),
                ));
            }
        }
    }
    for start in 0..n {
        let (mut at, mut steps) = (start, 0);
        while let Some(p) = parent[at] {
            at = p;
            steps += 1;
            if steps > n {
                return Err((format!("/nodes/{start}"), format!("node {start} is on a cycle of children")));
            }
        }
    }
    Ok(())
}

/// Whether `path` names a glTF file (by its extension).
pub fn is_gltf(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("glb") || e.eq_ignore_ascii_case("gltf"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_with_and_without_padding() {
        assert_eq!(decode_base64("AAECAw==").unwrap(), [0, 1, 2, 3]);
        assert_eq!(decode_base64("AAECAw").unwrap(), [0, 1, 2, 3]);
        assert_eq!(decode_base64("TWFu").unwrap(), b"Man");
        assert!(decode_base64("A").is_none());
        assert!(decode_base64("A*==").is_none());
    }

    #[test]
    fn json_paths_read_as_pointers() {
        assert_eq!(json_pointer("meshes[0].primitives[1].indices"), "/meshes/0/primitives/1/indices");
    }
}
