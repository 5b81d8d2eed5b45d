//! Geometry: rays and hits, the analytic sphere and plane, the camera, the direction
//! helpers (`reflect`, `refract`, half vectors) in the course's convention, the ray queries
//! on meshes, and the sampling and polygon math of area lights.
//!
//! Conventions (docs/conventions.md): right-handed, y up; in [`vector`] every direction
//! points away from the surface (`l` towards the light, `v` towards the viewer). Rays are
//! f64 so the exact reference is exact to well below an 8-bit code. The ray queries on
//! meshes are f32, on the mesh's own vertices: [`triangle`] (the watertight ray–triangle test
//! and the self-intersection offset) and [`bvh`] (closest-hit and shadow rays over a soup).
//! [`sampling`] holds the hashed, stratified samples of emitters and hemispheres,
//! [`polygon`] Lambert's closed form for the light of a polygon. The samplers that remove
//! grain: [`sobol`] (shuffled, Owen-scrambled Sobol streams, seeded per pixel, light and
//! purpose), [`spherical_rect`] (a rectangle uniformly in solid angle), [`tube`] (a thin line
//! light uniformly in solid angle) and [`equiangular`] (distances along a ray towards a point
//! light, for single scattering in a medium); each is a pure function of its inputs and a u.

pub mod analytic;
pub mod box_projection;
pub mod bvh;
pub mod camera;
pub mod equiangular;
pub mod fdlibm;
pub mod polygon;
pub mod ray;
pub mod refraction;
pub mod sampler;
pub mod sampling;
pub mod sobol;
pub mod spherical_rect;
pub mod subdivide;
#[cfg(test)]
mod test_stats;
pub mod triangle;
pub mod tube;
pub mod vector;

pub use analytic::{Analytic, AnalyticKind};
pub use bvh::{Bvh, RayPacket, TriHit};
pub use camera::{Camera, CameraRays};
pub use ray::{Hit, Ray};
pub use triangle::offset_ray_origin;
pub use vector::{half_vector, reflect, refract};
