//! Optional light-transport passes, one file each (layer 2, below `render`: the plan asks
//! each effect whether it is needed, and an effect uses only `scene` and the layers below).
//!
//! Each effect is a [`Pass`](crate::render::plan::Pass) variant that the plan asks, in
//! [`needed`](crate::render::plan::needed), "is it needed for this scene, and why?" by
//! calling its file's `needed(scene)`; the pipeline runs it where its pass stands. Where
//! the coming effects plug in (docs/architecture.md, "Where the effects plug in"):
//! ray-cast shadows and shadow maps set `Incident::visibility`; area and sky lights give
//! several incidents per point; environment, probes and refraction add reflection and
//! transmission layers from rays in `geometry`; fog is a pass after per-sample lighting and
//! before the resolve, per sample with its depth; radiosity bakes per-vertex radiosity before
//! the raster.
//!
//! - [`environment`]: the environment as a light (importance sampling of the map, the
//!   Monte Carlo reference, the scene's rays for mirrors) and whether a scene needs it.
//! - [`fog`]: the classic fog blends and the ray-marched participating medium, a pass after
//!   per-sample lighting, per sample with its depth.
//! - [`probe`]: reflection probes, whether a scene needs their capture, the scene a probe
//!   sees, the face cameras and the mirrors' naive or box-projected lookup.
//! - [`radiosity`]: patches, form factors (hemicube, ray cast), the solvers and the display
//!   values baked before the raster pass.
//! - [`refraction`]: whether a scene has glass, which paths the glass rays count, and the
//!   scene's rays and surfaces they need.
//! - [`shadows`]: each light's shadow method and whether it is needed ([`shadows::shadowing`]),
//!   the ray pass (BVH) and the shadow-map pass, and the visibility they give an incident.

pub mod environment;
pub mod fog;
pub mod probe;
pub mod radiosity;
pub mod refraction;
pub mod shadows;
