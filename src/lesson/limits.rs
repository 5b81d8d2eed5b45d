//! Resource limits, checked before any work.

/// Most radiosity patches: the dense form-factor matrix holds N² f32, 256 MiB at 8192
/// patches, and a hemicube pass rasterizes every patch once per patch (N² triangle setups).
pub const MAX_PATCHES: usize = 8192;

/// Largest hemicube side in cells: 1024² cells on five faces are 4 M samples per patch,
/// already seconds per patch; the form factors stop changing long before (64 is the default).
pub const MAX_HEMICUBE: i64 = 1024;

/// Most radiosity iterations: each is N² multiply-adds, and a closed room of albedo 0.9
/// converges to 10⁻⁶ in about 130 Jacobi sweeps (0.9¹³⁰ ≈ 10⁻⁶).
pub const MAX_ITERATIONS: i64 = 10_000;
