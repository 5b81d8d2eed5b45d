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
