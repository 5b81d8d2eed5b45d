//! Resource limits, checked before any work.

/// Most environment samples per shaded point (`[render] env_samples`): 16384 samples of a
/// 512² frame are 4·10⁹ BRDF evaluations, minutes on two cores; the convergence chart needs
/// no more than 4096.
pub const MAX_ENV_SAMPLES: i64 = 16384;

/// Largest width of the first prefiltered level (`[render] prefilter_size`): 2048 × 1024 texels
/// × 64 samples is about 10⁸ lookups, a few seconds; the chain halves from there.
pub const MAX_PREFILTER_SIZE: i64 = 2048;

/// Largest side of an environment map in texels: 8K latitude-longitude maps are the largest
/// commonly published; bigger ones add nothing a 512² figure can show.
pub const MAX_ENV_SIDE: u32 = 8192;

/// Most texels of an environment map (8192 × 4096, 400 MB as linear f32 RGB): the map and
/// its sampling tables must fit in memory beside the render.
pub const MAX_ENV_TEXELS: u64 = 8192 * 4096;
