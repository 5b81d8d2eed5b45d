//! Resource limits, checked before any work.

/// Most ray-march steps `[fog] steps` may ask for per sample: the `fog_steps` cost ladder's
/// 4096-step reference must be expressible, and 4096 steps × a 16-million-sample image is
/// already minutes of work on two cores; more buys nothing the reference does not show.
pub const MAX_FOG_STEPS: i64 = 4096;
