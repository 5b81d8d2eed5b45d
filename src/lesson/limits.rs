//! Resource limits, checked before any work.
//!
//! One `pub const` per limit, each with how its number was chosen. The budget behind them:
//! a render should stay within a few GB on a 24 GB machine, so a lesson that passes
//! validation cannot exhaust memory. Every limit is listed in docs/lesson-format.md
//! ("Limits"); limits of later effects (area-light samples, environment samples, fog
//! steps, radiosity patches) are added here, beside the others.

/// Largest image side in pixels (a 16K frame; a side is also bounded by the area below).
pub const MAX_SIDE: i64 = 16384;
/// Largest image area in pixels (about 8K × 5K): a frame keeps ~28 bytes per pixel of
/// linear layers, so 40 M pixels is about 1.1 GB.
pub const MAX_PIXELS: i64 = 40_000_000;
/// Most samples per image, width × height × aa²: four times [`MAX_PIXELS`], since the
/// visibility of a strip is kept per sample only for the strip being shaded.
pub const MAX_SAMPLES: i64 = 4 * MAX_PIXELS;
/// Largest supersampling factor per pixel side (16² = 256 samples per pixel).
pub const MAX_AA: i64 = 16;
/// Most samples one area, line or sky light may take per shaded point: 4096 is the
/// count the cost ladders use as their reference, beyond which the error is below 8-bit.
pub const MAX_LIGHT_SAMPLES: i64 = 4096;
/// Largest shadow-map side in texels (a point light has six such faces: 6 × 8192² × 4
/// bytes = 1.6 GB).
pub const MAX_SHADOW_MAP: i64 = 8192;
/// Most shadow-map texels over all lights together: one point light's six faces at
/// [`MAX_SHADOW_MAP`] (403 M texels, 1.6 GB). Four such lights took 6.15 GB (reliability
/// round two): each light within its own limit, the sum unbounded.
pub const MAX_SHADOW_MAP_TEXELS: u64 = 6 * (MAX_SHADOW_MAP as u64) * (MAX_SHADOW_MAP as u64);
/// Most `[[light]]` tables: every shaded sample asks each light, so 100,000 point lights did
/// not finish in minutes; a lesson has a handful (three-point lighting is three).
pub const MAX_LIGHTS: usize = 256;
/// Most light samples per shaded point over all sampled lights together: four lights at
/// [`MAX_LIGHT_SAMPLES`]. 1,000 rect lights × 4,096 samples (4 M per point) did not finish.
pub const MAX_LIGHT_SAMPLES_TOTAL: i64 = 4 * MAX_LIGHT_SAMPLES;
/// Most triangles over all objects after tessellation. Measured: six 2048 × 2048 tori
/// (50 M triangles) took 2.8 GB, about 56 bytes a triangle with its vertices; 20 M is
/// about 1.1 GB, and a shadow-ray BVH over it about as much again.
pub const MAX_TRIANGLES: u64 = 20_000_000;
/// Largest OBJ file in bytes (512 MiB): an OBJ spends at least ~25 bytes on each `v` and
/// `f` line, so a larger file would hold more than [`MAX_TRIANGLES`] anyway; the file is
/// read whole, so this also bounds the text kept in memory.
pub const MAX_OBJ_BYTES: u64 = 512 * 1024 * 1024;
/// Largest magnitude of an OBJ coordinate (`v`, `vn`, and `v` after dividing by `w`): the
/// range of positions in a lesson; beyond it f32 products overflow in the transforms.
pub const MAX_OBJ_COORD: f32 = 1e6;
/// Most pixels of a figure, all cells together, and of a cost strip (renders and heatmaps
/// together): one [`MAX_PIXELS`] image. Cells are kept as 8-bit RGBA (4 bytes a pixel)
/// until composed, so this bounds a figure at a few hundred MB.
pub const MAX_FIGURE_PIXELS: u64 = MAX_PIXELS as u64;
/// Most errors one validation run reports (the rest are counted, not shown).
pub const MAX_ERRORS: usize = 20;

/// Most ray-march steps `[fog] steps` may ask for per sample: four times the `fog_steps` cost
/// ladder's reference (1024), and 4096 steps × a 16-million-sample image is already minutes
/// of work on two cores; more buys nothing a reference needs.
pub const MAX_FOG_STEPS: i64 = 4096;

/// Most environment samples per shaded point (`[render] env_samples`): 16384 samples of a
/// 512² frame are 4·10⁹ BRDF evaluations, minutes on two cores; the convergence chart needs
/// no more than 4096.
pub const MAX_ENV_SAMPLES: i64 = 16384;

/// Most interface events on a glass path (`[render] max_bounces`): each event may split a
/// ray in two (reflected and refracted), so a sample may cost up to 2^16 rays among several
/// glass objects (a lone convex one costs at most 2 per event); in a sphere of η = 1.5 an
/// internal reflection keeps ≤ 4% of the light away from grazing, so 16 events leave
/// nothing an 8-bit code shows.
pub const MAX_BOUNCES: i64 = 16;

/// Most paths per pixel sample of the path tracer (`[render] spp`).
pub const MAX_SPP: i64 = 65536;

/// Longest path of the path tracer in segments (`[render] max_depth`).
pub const MAX_DEPTH: i64 = 64;

/// Most photons of the caustic map (`[render] photons`): 32 bytes each, 320 MB at most.
pub const MAX_PHOTONS: i64 = 10_000_000;
/// Most final-gather rays a first diffuse vertex sends (`[render] gather_rays`).
pub const MAX_GATHER_RAYS: i64 = 1024;
/// Most photons a k-nearest gather reads (`[render] photon_nearest`).
pub const MAX_PHOTON_NEAREST: i64 = 1000;

/// Largest width of the first prefiltered level (`[render] prefilter_size`): 2048 × 1024 texels
/// × 64 samples is about 10⁸ lookups, a few seconds; the chain halves from there.
pub const MAX_PREFILTER_SIZE: i64 = 2048;

/// Largest side of an environment map in texels: 8K latitude-longitude maps are the largest
/// commonly published; bigger ones add nothing a 512² figure can show.
pub const MAX_ENV_SIDE: u32 = 8192;

/// Most texels of an environment map (8192 × 4096, 400 MB as linear f32 RGB): the map and
/// its sampling tables must fit in memory beside the render.
pub const MAX_ENV_TEXELS: u64 = 8192 * 4096;

/// Most radiosity patches: the dense form-factor matrix holds N² f32, 256 MiB at 8192
/// patches, and a hemicube pass rasterizes every patch once per patch (N² triangle setups).
pub const MAX_PATCHES: usize = 8192;

/// Largest hemicube side in cells: 1024² cells on five faces are 4 M samples per patch,
/// already seconds per patch; the form factors stop changing long before (64 is the default).
pub const MAX_HEMICUBE: i64 = 1024;

/// Most radiosity iterations: each is N² multiply-adds, and a closed room of albedo 0.9
/// converges to 10⁻⁶ in about 130 Jacobi sweeps (0.9¹³⁰ ≈ 10⁻⁶).
pub const MAX_ITERATIONS: i64 = 10_000;

/// Largest probe face in texels (`[[probe]] size`): six 1024² faces are 6 M shaded samples
/// per probe per render, seconds on two cores; a 512² figure cannot show more detail.
pub const MAX_PROBE_SIZE: i64 = 1024;

/// Smallest probe face: below 8 texels a face is a few blurred colours.
pub const MIN_PROBE_SIZE: i64 = 8;

/// Most `[[probe]]` tables: each is six renders of the scene before the frame.
pub const MAX_PROBES: usize = 16;
/// Largest side of a material texture in texels: 8K textures with their mip chain are
/// 1 GB as linear f32 RGB; lesson textures are a few hundred texels.
pub const MAX_TEXTURE_SIDE: i64 = 8192;

/// Most checker squares per unit of uv (`checker = { scale }`): baked at 8 texels a square,
/// 128 squares make a 1024² texture (12 MB with its mip chain).
pub const MAX_CHECKER_SCALE: i64 = 128;

/// Smallest and largest side of a `fit` slide in pixels: below 320 no label fits at the
/// minimum text size; 8K is the largest display a figure is made for.
pub const FIT_SIDE: (i64, i64) = (320, 7680);

/// Most points of a spot light's `profile`: a measured lamp's table has a few dozen, and the
/// light room holds them inline so that lights stay `Copy`.
pub const MAX_PROFILE_POINTS: usize = 32;
