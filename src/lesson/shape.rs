//! The shapes a lesson can place.

use std::path::PathBuf;

/// The closed set of shapes a lesson can place.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Latitude-longitude sphere of radius 1.
    UvSphere {
        /// Segments around the y axis.
        segments: u32,
        /// Rings from pole to pole.
        rings: u32,
    },
    /// Subdivided icosahedron of radius 1.
    Icosphere {
        /// Subdivision level (20·4ⁿ triangles).
        subdivisions: u32,
    },
    /// The square [−1, 1]² in the xz plane, facing +y.
    Plane,
    /// The cube [−1, 1]³.
    Cube,
    /// A torus around the y axis.
    Torus {
        /// Radius of the centre circle.
        major_radius: f32,
        /// Radius of the tube.
        minor_radius: f32,
        /// Segments around the y axis.
        segments: u32,
        /// Segments around the tube.
        sides: u32,
    },
    /// An OBJ or glTF file (already resolved against the lesson's folder).
    Mesh {
        /// Path to the OBJ, `.glb` or `.gltf` file.
        path: PathBuf,
        /// For a glTF file: which of its meshes.
        part: MeshPart,
    },
}

/// Which meshes of a glTF file an `[[object]]` takes (`node`, `primitive`).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct MeshPart {
    /// A node by name or index; `None`: every mesh node of the file's scene.
    pub node: Option<NodeRef>,
    /// One primitive of the node's mesh; `None`: all of them.
    pub primitive: Option<u32>,
}

/// A glTF node named in a lesson.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum NodeRef {
    /// By its `name`.
    Name(String),
    /// By its index in the file's `nodes`.
    Index(u32),
}

impl std::fmt::Display for NodeRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NodeRef::Name(n) => write!(f, "`{n}`"),
            NodeRef::Index(i) => write!(f, "{i}"),
        }
    }
}

impl Shape {
    /// Triangles after tessellation (as `scene::shapes` builds them); `None` for a mesh,
    /// whose count is known only once its file is read.
    pub fn triangles(&self) -> Option<u64> {
        match *self {
            Shape::UvSphere { segments, rings } => Some(2 * segments.max(3) as u64 * (rings.max(2) as u64 - 1)),
            Shape::Icosphere { subdivisions } => Some(20 * 4u64.pow(subdivisions)),
            Shape::Plane => Some(2),
            Shape::Cube => Some(12),
            Shape::Torus { segments, sides, .. } => Some(2 * segments.max(3) as u64 * sides.max(3) as u64),
            Shape::Mesh { .. } => None,
        }
    }
}
