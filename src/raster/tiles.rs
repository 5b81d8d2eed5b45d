//! How a depth-only strip (a shadow map's) is laid out in memory: rows, or tiles of
//! [`DEPTH_TILE`]² texels so that neighbouring lookups share cache lines.

/// How a depth-only strip is laid out in memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthLayout {
    /// Row-major, `width` samples a row.
    Rows {
        /// Samples per row.
        width: usize,
    },
    /// Tiles of [`DEPTH_TILE`]² samples, `tiles` tiles a row of tiles (see [`tiled`]).
    Tiles {
        /// Tiles per row of tiles.
        tiles: usize,
    },
}

/// Samples per side of a [`DepthLayout::Tiles`] tile.
pub const DEPTH_TILE: usize = 8;

/// Index of sample (x, y) in a buffer of rows of `tiles` tiles of [`DEPTH_TILE`]² samples,
/// each tile row-major: the lookups of neighbouring points fall in a few cache lines
/// whatever the direction they move in.
#[inline(always)]
pub fn tiled(x: usize, y: usize, tiles: usize) -> usize {
    ((y / DEPTH_TILE) * tiles + x / DEPTH_TILE) * (DEPTH_TILE * DEPTH_TILE) + (y % DEPTH_TILE) * DEPTH_TILE + x % DEPTH_TILE
}
