//! Form factors by the hemicube (Cohen and Greenberg, "The Hemi-Cube", SIGGRAPH 1985),
//! rendered by the project's own rasterizer.
//!
//! Around the centre of patch i stands half a cube: a top face along the normal and four
//! half faces around it. Each face is a 90° view rendered with [`raster::rasterize`]: the
//! visibility buffer gives, per cell, the nearest triangle, i.e. the patch seen through it.
//! A cell at (x, y, 1) on the top face of a unit hemicube carries the delta form factor
//! ΔF = ΔA / (π (x² + y² + 1)²), a cell at height z on a side face ΔF = z ΔA / (π (x² + z² + 1)²)
//! (Cohen & Greenberg 1985, eqs. 8 and 9); F_ij is the sum of ΔF over the cells that see j.
//! The table of ΔF is scaled to sum to exactly 1 (its midpoint rule is off by 0.1 % at 64²),
//! so a closed room's rows sum to 1 up to the cells no patch covers.
//!
//! Faces are drawn two-sided: a patch seen from behind still hides what lies beyond it,
//! but its back sends nothing (one-sided patches, as a one-sided area emitter), so its cells
//! are dropped. Errors, as the references say: aliasing of small or distant patches
//! (each is seen in whole cells), and the point-to-area assumption (F from the centre).

use super::mesh::Patches;
use crate::geometry::Camera;
use crate::raster::{self, CullMode, NO_TRIANGLE, StripVis};
use glam::{Vec3, Vec4};

/// The delta form factors of one hemicube: the top face (res² cells), then the upper half
/// of a side face (res/2 rows of res cells, row 0 at the top: at the normal's height).
pub(super) struct DeltaTable {
    res: usize,
    top: Vec<f32>,
    side: Vec<f32>,
}

impl DeltaTable {
    /// The table for `res` cells per side (res even: rounded up).
    pub(super) fn new(res: u32) -> DeltaTable {
        let res = (res as usize).div_ceil(2) * 2;
        let h = 2.0 / res as f64;
        let da = h * h;
        let mid = |k: usize| -1.0 + (k as f64 + 0.5) * h;
        let pi = std::f64::consts::PI;
        let top: Vec<f64> = (0..res * res)
            .map(|c| {
                let (x, y) = (mid(c % res), mid(c / res));
                da / (pi * (x * x + y * y + 1.0).powi(2))
            })
            .collect();
        // Row r of the upper half: z = 1 − (r + ½)h above the horizon.
        let side: Vec<f64> = (0..res / 2 * res)
            .map(|c| {
                let (x, z) = (mid(c % res), -mid(c / res));
                z * da / (pi * (x * x + z * z + 1.0).powi(2))
            })
            .collect();
        let total = top.iter().sum::<f64>() + 4.0 * side.iter().sum::<f64>();
        let scale = |v: Vec<f64>| v.into_iter().map(|d| (d / total) as f32).collect();
        DeltaTable { res, top: scale(top), side: scale(side) }
    }
}

/// Row i of the form-factor matrix by hemicube: (j, F_ij) for every patch j that i sees.
pub(super) fn row(
    i: usize,
    patches: &Patches,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    table: &DeltaTable,
    near: f32,
    strip: &mut StripVis,
) -> Vec<(u32, f32)> {
    let mut f = vec![0f32; patches.len()];
    let (n, c) = (patches.normal[i], patches.centre[i]);
    if patches.area[i] <= 0.0 {
        return Vec::new();
    }
    // Just above the surface, so the patch and its coplanar neighbours are seen edge-on.
    let eye = c + n * near;
    // Which patches send light to the eye: asked once per patch, not once per cell.
    let sends: Vec<bool> = (0..patches.len()).map(|j| j != i && patches.faces(j, eye)).collect();
    let (t, b) = crate::geometry::sampling::basis(n);
    let res = table.res as u32;
    // (view direction, up, delta table, rows used).
    let faces = [
        (n, t, &table.top, res),
        (t, n, &table.side, res / 2),
        (-t, n, &table.side, res / 2),
        (b, n, &table.side, res / 2),
        (-b, n, &table.side, res / 2),
    ];
    for (dir, up, delta, rows) in faces {
        let cam = Camera { position: eye, look_at: eye + dir, up, fov_y_deg: 90.0, width: res, height: res, near, background: Vec3::ZERO };
        let vp = cam.view_projection();
        let clip: Vec<Vec4> = positions.iter().map(|p| vp * p.extend(1.0)).collect();
        // Only the rows the table covers are rasterized (a side face's upper half).
        let seen = raster::nearest_triangles(&clip, triangles, res, res, rows, CullMode::None, strip);
        for (cell, &j) in seen.iter().enumerate() {
            if j != NO_TRIANGLE && sends[j as usize] {
                f[j as usize] += delta[cell];
            }
        }
    }
    f.into_iter().enumerate().filter(|(_, v)| *v > 0.0).map(|(j, v)| (j as u32, v)).collect()
}
