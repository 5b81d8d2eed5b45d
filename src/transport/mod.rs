//! Light transport at a point: the per-point integrator and the ray-query service it uses
//! (layer 2, between `effects`, whose passes it reads, and `render`, whose pipeline asks it).
//!
//! Which light paths it counts, by file:
//! - [`incidents`]: the seam. Every shaded point (a vertex, a face centroid, a sample, one
//!   lane or a bundle) asks each kept light for its [`Incident`](crate::shading::incident::Incident)s
//!   — direct light, with each light's visibility ([`visibility`]) and the medium's
//!   attenuation on the way — and hands them to shading; [`shade_point`] adds what the
//!   environment, mirrors and glass bring.
//! - [`environment`]: the environment's light on a physically based material (Monte Carlo
//!   or the split sum, blocked by the scene where it can block itself) and a mirror's ray,
//!   followed through up to `MAX_MIRROR_DEPTH` mirrors.
//! - [`glass`]: the Fresnel-weighted reflected and refracted rays of glass, up to
//!   `max_bounces` interface events.
//! - [`medium`]: the fog pass per sample: the classic blends, or single scattering along the
//!   eye ray, ray-marched, with each light's visibility from points in the medium.
//! - [`path`]: the path tracer (`method = "path"`): whole light paths from the camera, with
//!   next-event estimation, multiple importance sampling and the medium's free flights.
//! - [`rays`]: the one ray-query structure of a render's scene ([`SceneRays`]), built once
//!   and shared by every ray; [`surfaces`]: what traced rays need to shade what they find.

pub mod environment;
pub mod glass;
pub mod incidents;
pub mod lighting;
pub mod medium;
pub mod path;
pub mod rays;
pub mod shade;
pub mod slab;
pub mod surfaces;
pub mod visibility;

pub use lighting::{At, Lighting};
pub use rays::{Occluders, Origin, SceneHit, SceneRays, ShadowRay};
pub use shade::shade_point;
pub use surfaces::Tracing;
pub use visibility::{LightShadow, ShadowCounts, Shadows};
