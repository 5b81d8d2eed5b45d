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
    /// An OBJ file (already resolved against the lesson's folder).
    Mesh {
        /// Path to the OBJ file.
        path: PathBuf,
    },
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
