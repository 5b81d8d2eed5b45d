//! Display: the patch radiances turned into what the raster pass shows.
//!
//! - **flat**: triangle i (patch i) shows L_i, one colour per patch;
//! - **Gouraud**: vertex v shows the area-weighted mean of the patches around it,
//!   Σ A_t L_t / Σ A_t (Cohen & Wallace 1993, §9.2), and the rasterizer interpolates it
//!   across each patch, the course's smooth shading;
//! - **final gather** (with either): each patch centroid p gathers once more from every
//!   patch, L(p) = E(p) + ρ(p) Σ_j F(p → j) V(p, j) L_j, with Lambert's point-to-polygon
//!   form factor and ray-cast visibility instead of the hemicube's cells; Gouraud then
//!   averages these to the vertices as above. The light arriving at p is exact up to the
//!   solution's own L_j, and the emitters' direct light is computed at the point.
//!   Gathering at the vertices themselves (Wallace, Elmquist & Haines 1989 do) was tried
//!   first: a vertex in a concave corner sees the dark corner at full weight, and the
//!   interpolation spread that over the whole patch (lesson 27's box: the walls' lower
//!   corners 15–20 % darker than a path tracer, against 1–7 % gathering at centroids).
//!
//! A patch whose centre lies inside a solid (a floor patch under a box: most rays from its
//! centre hit the back of a surface) has the dark value of the inside; the Gouraud vertices
//! leave it out of their mean, and the flat display shows it in the mean of its corners,
//! so a box's footprint does not show black teeth or darken the floor around it.
//!
//! The emitted part goes to the emission layer, the reflected part to the diffuse layer,
//! so a `split` figure separates them.

use super::RayQuery;
use super::Report;
use super::mesh::Patches;
use super::ray_cast::{gather_row, targets};
use crate::lesson::settings::RadiosityDisplay;
use crate::scene::Scene;
use crate::shading::Components;
use glam::Vec3;
use rayon::prelude::*;

/// The baked display values of a meshed scene.
#[derive(Debug, Clone)]
pub struct Baked {
    /// Per triangle (flat) or per vertex (Gouraud): emitted and reflected radiance.
    pub values: Vec<Components>,
    /// True when `values` are per vertex.
    pub per_vertex: bool,
    /// What the pass did.
    pub report: Report,
}

fn split(e: Vec3, l: Vec3) -> Components {
    // Reflected = L − E ≥ 0 up to rounding; the clamp keeps the layer non-negative.
    Components { emission: e, diffuse: (l - e).max(Vec3::ZERO), ..Components::ZERO }
}

/// The display values of `radiance` (per patch) for the scene's display settings.
pub fn display(scene: &Scene, patches: &Patches, radiance: &[Vec3], bvh: &dyn RayQuery) -> Baked {
    let g = &scene.geometry;
    let r = scene.spec.settings.radiosity;
    let per_vertex = r.display == RadiosityDisplay::Gouraud;
    let empty = Report {
        patches: 0,
        form_factors: 0,
        form_factor_ms: 0.0,
        form_factors_reused: false,
        form_factors_cached: false,
        solve_ms: 0.0,
        display_ms: 0.0,
        iterations: 0,
        residuals: Vec::new(),
    };
    let buried: Vec<bool> = (0..patches.len()).into_par_iter().map(|t| is_buried(patches, bvh, t)).collect();
    let per_patch: Vec<Components> = if r.final_gather {
        // The rows read the mesh only: every render of it this run shares them.
        let rows = super::reuse::gather_rows(scene, patches, bvh.kind(), || {
            let targets: Vec<Vec<Vec3>> =
                (0..patches.len()).map(|j| targets(patches.corners[j], patches.emission[j] != Vec3::ZERO)).collect();
            (0..patches.len())
                .into_par_iter()
                .map(|t| gather_row(patches.centre[t], patches.normal[t], Some(t), patches, bvh, &targets))
                .collect()
        });
        rows.par_iter()
            .enumerate()
            .map(|(t, row)| {
                let incoming = row.iter().fold(Vec3::ZERO, |s, &(j, f)| s + radiance[j as usize] * f);
                let e = patches.emission[t];
                let l = e + patches.reflectance[t] * incoming;
                if l.is_finite() { split(e, l) } else { split(e, e) }
            })
            .collect()
    } else {
        (0..patches.len()).map(|t| split(patches.emission[t], radiance[t])).collect()
    };
    // Vertex radiances from the patches that are not buried (all of them where every
    // patch around a vertex is).
    let mut sum = vec![(Components::ZERO, 0f32); g.positions.len()];
    let mut all = vec![(Components::ZERO, 0f32); g.positions.len()];
    for (t, tri) in g.triangles.iter().enumerate() {
        for &v in tri {
            let w = patches.area[t];
            let to = if buried[t] { &mut all } else { &mut sum };
            to[v as usize].0 += per_patch[t] * w;
            to[v as usize].1 += w;
        }
    }
    let vertex: Vec<Components> = sum
        .into_iter()
        .zip(all)
        .map(|(open, (s, w))| {
            let (s, w) = if open.1 > 0.0 { open } else { (open.0 + s, open.1 + w) };
            if w > 0.0 { s * (1.0 / w) } else { Components::ZERO }
        })
        .collect();
    if per_vertex {
        return Baked { values: vertex, per_vertex, report: empty };
    }
    // Flat: a buried patch shows the mean of its corners, the light of its open neighbours.
    let values = (0..patches.len())
        .map(|t| {
            if buried[t] {
                g.triangles[t].iter().fold(Components::ZERO, |a, &v| a + vertex[v as usize]) * (1.0 / 3.0)
            } else {
                per_patch[t]
            }
        })
        .collect();
    Baked { values, per_vertex, report: empty }
}

/// Rays from a patch's centre that find the back of another surface first (of 16): more
/// than half means the centre lies inside a solid (a floor patch under a box, a ceiling
/// patch behind the light), so the patch's own value is the light inside the box, not the
/// light on its visible part.
const BURIED_RAYS: u32 = 16;

/// True when most rays from patch t's centre hit the back of a surface: its centre is buried.
fn is_buried(patches: &Patches, bvh: &dyn RayQuery, t: usize) -> bool {
    if patches.area[t] <= 0.0 {
        return false;
    }
    let n = patches.normal[t];
    let o = crate::geometry::triangle::offset_ray_origin(patches.centre[t], n);
    let (tx, ty) = crate::geometry::sampling::basis(n);
    let seed = crate::geometry::sampling::hash3(t as u32, 0x5ad1, 7);
    let backs = (0..BURIED_RAYS)
        .filter(|&k| {
            let w = crate::geometry::sampling::cosine_hemisphere(crate::geometry::sampling::sample_2d(k, seed));
            let d = (tx * w.x + ty * w.y + n * w.z).normalize_or(n);
            bvh.closest_triangle(o, d).is_some_and(|t| patches.normal[t as usize].dot(d) > 0.0)
        })
        .count() as u32;
    2 * backs > BURIED_RAYS
}
