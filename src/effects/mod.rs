//! Optional light-transport passes, one file each (layer 2, beside `render`).
//!
//! Each effect is a [`Pass`](crate::render::plan::Pass) variant that the plan asks, in
//! [`needed`](crate::render::plan::needed), "is it needed for this scene, and why?" by
//! calling its file's `needed(scene)`; the pipeline runs it where its pass stands. Where
//! the coming effects plug in (docs/architecture.md, "Where the effects plug in"):
//! ray-cast shadows and shadow maps set `Incident::visibility`; area and sky lights give
//! several incidents per point; environment, probes and refraction add reflection and
//! transmission layers from rays in `geometry`; fog is a pass after the raster, per sample
//! with depth; radiosity bakes per-vertex radiosity before it. None exists yet.
