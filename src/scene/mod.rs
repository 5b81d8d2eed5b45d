//! The runtime scene: camera, lights, materials and meshes placed in the world.

pub mod build;
pub mod cube;
pub mod env_layout;
pub mod environment;
pub mod gltf;
pub mod mesh;
pub mod mirror_ball;
pub mod normals;
pub mod obj;
pub mod shapes;
pub mod smoothing;
pub mod texture;

pub use crate::geometry::Camera;
pub use crate::lesson::Shape;
pub use crate::lesson::settings::NormalWeighting;
pub use crate::shading::material::{Classic, ClassicModel, Material, Model};
pub use build::{Geometry, Scene};
pub use environment::{EnvMap, Environment};
pub use mesh::{Mesh, MeshRepairs};
