//! Geometry: rays and hits, the analytic sphere and plane, the camera, and the direction
//! helpers (`reflect`, `refract`, half vectors) in the course's convention.
//!
//! Conventions (docs/conventions.md): right-handed, y up; in [`vector`] every direction
//! points away from the surface (`l` towards the light, `v` towards the viewer). Rays are
//! f64 so the exact reference is exact to well below an 8-bit code; the ray–triangle test
//! and the BVH that shadows need will live here too.

pub mod analytic;
pub mod camera;
pub mod ray;
pub mod vector;

pub use analytic::{Analytic, AnalyticKind};
pub use camera::{Camera, CameraRays};
pub use ray::{Hit, Ray};
pub use vector::{half_vector, reflect, refract};
