//! Form factors by ray casting, point to patch: Lambert's closed form for the unoccluded
//! form factor from the centre of patch i to the polygon j (`geometry::polygon`, Baum,
//! Rushmeier and Winget 1989), times the fraction of rays from that centre to points
//! spread over j that reach j (the any-hit query of the render's rays): F_ij ≈ F(c_i → j) · V_ij.
//!
//! Exact for unoccluded patches seen from their centre; the errors are the point-to-area
//! assumption (F from the centre only, as the hemicube's) and the sampled visibility (4
//! rays, 16 towards an emitter, whose shadows matter most).

use super::RayQuery;
use super::mesh::Patches;
use crate::geometry::polygon::polygon_form_factor;
use crate::geometry::subdivide::{lattice, sub_triangles};
use crate::geometry::triangle::offset_ray_origin;
use glam::Vec3;

/// Below this an unoccluded form factor is not worth its rays (10⁻⁷ of the hemisphere).
const NEGLIGIBLE: f32 = 1e-7;

/// The points towards which visibility rays go: the centroids of the k² sub-triangles of
/// j (k = 2, or 4 for an emitter).
pub(super) fn targets(corners: [Vec3; 3], emitter: bool) -> Vec<Vec3> {
    let k = if emitter { 4 } else { 2 };
    let [a, b, c] = corners;
    sub_triangles(k).map(|s| s.map(|(i, j)| lattice(a, b, c, k, i, j)).iter().sum::<Vec3>() / 3.0).collect()
}

/// The fraction of the rays from `p` (unit normal `n`) to `targets` that nothing blocks.
pub(super) fn visibility(bvh: &dyn RayQuery, p: Vec3, n: Vec3, targets: &[Vec3]) -> f32 {
    let o = offset_ray_origin(p, n);
    let seen = targets
        .iter()
        .filter(|q| {
            let d = **q - o;
            let len = d.length();
            // Stop just short of the target, which lies on j itself.
            len > 0.0 && !bvh.occluded(o, d / len, len * (1.0 - 1e-4))
        })
        .count();
    seen as f32 / targets.len().max(1) as f32
}

/// The light of every patch gathered at a point: Σ_j F(p → j) V(p, j) value_j over the
/// patches whose front faces p, or with `row`, the form factors themselves.
pub(super) fn gather_row(
    p: Vec3,
    n: Vec3,
    skip: Option<usize>,
    patches: &Patches,
    bvh: &dyn RayQuery,
    targets: &[Vec<Vec3>],
) -> Vec<(u32, f32)> {
    let mut out = Vec::new();
    for (j, to) in targets.iter().enumerate().take(patches.len()) {
        if Some(j) == skip || !patches.faces(j, p) {
            continue;
        }
        let f = polygon_form_factor(p, n, &patches.corners[j]);
        if f < NEGLIGIBLE {
            continue;
        }
        let v = visibility(bvh, p, n, to);
        if v > 0.0 {
            out.push((j as u32, f * v));
        }
    }
    out
}

/// Row i of the form-factor matrix by ray casting.
pub(super) fn row(i: usize, patches: &Patches, bvh: &dyn RayQuery, targets: &[Vec<Vec3>]) -> Vec<(u32, f32)> {
    if patches.area[i] <= 0.0 {
        return Vec::new();
    }
    gather_row(patches.centre[i], patches.normal[i], Some(i), patches, bvh, targets)
}
