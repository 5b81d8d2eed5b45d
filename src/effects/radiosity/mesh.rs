//! Meshing: every triangle of the scene cut into patches whose longest edge is at most
//! `patch_size` ([`crate::geometry::subdivide`]), and the patch data the solvers read.
//!
//! The patch mesh is also the display mesh: patch i is triangle i of the meshed scene, so
//! the flat display gives triangle i the radiance of patch i, and the Gouraud display gives
//! each vertex the area-weighted mean of the patches around it. Lattice points that two
//! triangles of one object share (the diagonal of a quad) are merged when their positions
//! and normals agree, so Gouraud interpolation runs across them; hard edges (a cube's) keep
//! a vertex per face.

use crate::geometry::subdivide::{divisions, lattice, sub_triangles};
use crate::lesson::settings::{Interpolation, RadiosityDisplay};
use crate::scene::build::{Geometry, ObjectBounds};
use crate::scene::{Material, Model, Scene};
use crate::shading::lobe::Part;
use glam::Vec3;
use std::collections::HashMap;

/// The scene with its surfaces cut into patches (one triangle each), displayed flat or
/// Gouraud as `display` says.
pub fn mesh_scene(scene: &Scene) -> Scene {
    let r = scene.spec.settings.radiosity;
    let g = &scene.geometry;
    let mut out = Geometry::default();
    for o in &g.objects {
        let first_vertex = out.positions.len();
        let first_triangle = out.triangles.len();
        // Merged lattice points of this object: quantized position and normal → index.
        let mut seen: HashMap<([i64; 3], [i64; 3]), u32> = HashMap::new();
        for t in o.first_triangle..o.first_triangle + o.triangles {
            let tri = g.triangles[t];
            let [a, b, c] = tri.map(|i| g.positions[i as usize]);
            let [na, nb, nc] = tri.map(|i| g.normals[i as usize]);
            let k = divisions(a, b, c, r.patch_size);
            let mut index = |i: u32, j: u32| -> u32 {
                let p = lattice(a, b, c, k, i, j);
                let n = lattice(na, nb, nc, k, i, j).normalize_or(g.face_normals[t]);
                // 2⁻¹⁶ in position, 10⁻³ in normal: merges the same lattice point computed
                // from either triangle of a quad, never two distinct patch corners.
                let key = (quantize(p, 65536.0), quantize(n, 1000.0));
                *seen.entry(key).or_insert_with(|| {
                    out.positions.push(p);
                    out.normals.push(n);
                    (out.positions.len() - 1) as u32
                })
            };
            for s in sub_triangles(k) {
                let v = s.map(|(i, j)| index(i, j));
                out.triangles.push(v);
                out.material.push(g.material[t]);
                // Radiosity displays flat or Gouraud, where a texture gives its mean: no uv needed,
                // but `uvs` stays parallel to the triangles when the scene has them.
                if !g.uvs.is_empty() {
                    out.uvs.push([glam::Vec2::ZERO; 3]);
                }
                // The patch faces as its parent does (its corners may round onto a line).
                out.face_normals.push(g.face_normals[t]);
            }
        }
        out.objects.push(ObjectBounds {
            first_triangle,
            triangles: out.triangles.len() - first_triangle,
            first_vertex,
            vertices: out.positions.len() - first_vertex,
            ..*o
        });
    }
    let mut settings = scene.spec.settings;
    settings.interpolation = match r.display {
        RadiosityDisplay::Flat => Interpolation::Flat,
        RadiosityDisplay::Gouraud => Interpolation::Gouraud,
    };
    let mut meshed = Scene { geometry: out, ..scene.clone() };
    meshed.spec.settings = settings;
    meshed
}

fn quantize(v: Vec3, scale: f32) -> [i64; 3] {
    v.to_array().map(|x| (x * scale).round() as i64)
}

/// The radiosity data of every patch (triangle) of a meshed scene.
#[derive(Debug, Clone)]
pub struct Patches {
    /// The three corners of each patch.
    pub corners: Vec<[Vec3; 3]>,
    /// Unit normal (the side that sends and receives light).
    pub normal: Vec<Vec3>,
    /// Centroid.
    pub centre: Vec<Vec3>,
    /// Area A_i (0 for a degenerate patch, which then exchanges no light).
    pub area: Vec<f32>,
    /// Emitted radiance E_i (the material's `emission`).
    pub emission: Vec<Vec3>,
    /// Diffuse reflectance ρ_i.
    pub reflectance: Vec<Vec3>,
}

impl Patches {
    /// The patches of `scene` (already meshed by [`mesh_scene`]).
    pub fn of(scene: &Scene) -> Patches {
        let g = &scene.geometry;
        let material = |t: usize| &scene.materials[g.material[t] as usize];
        let e: Vec<Vec3> = (0..g.triangles.len()).map(|t| material(t).emission).collect();
        let rho: Vec<Vec3> = (0..g.triangles.len()).map(|t| reflectance(material(t))).collect();
        Patches::from_triangles(&g.positions, &g.triangles, &g.face_normals, e, rho)
    }

    /// Patches from triangles (indices into `positions`) with their unit normals, emitted
    /// radiance and reflectance.
    pub fn from_triangles(
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        normal: &[Vec3],
        emission: Vec<Vec3>,
        reflectance: Vec<Vec3>,
    ) -> Patches {
        let corners: Vec<[Vec3; 3]> = triangles.iter().map(|t| t.map(|i| positions[i as usize])).collect();
        let area =
            corners.iter().map(|[a, b, c]| 0.5 * (*b - *a).cross(*c - *a).length()).map(|x| if x.is_finite() { x } else { 0.0 }).collect();
        let centre = corners.iter().map(|[a, b, c]| (*a + *b + *c) / 3.0).collect();
        Patches { normal: normal.to_vec(), centre, area, emission, reflectance, corners }
    }

    /// Patch count N.
    pub fn len(&self) -> usize {
        self.corners.len()
    }

    /// True when there are no patches.
    pub fn is_empty(&self) -> bool {
        self.corners.is_empty()
    }

    /// True when patch j's front side faces point `p`: only then does it send light to p.
    #[inline]
    pub fn faces(&self, j: usize, p: Vec3) -> bool {
        self.area[j] > 0.0 && self.normal[j].dot(p - self.centre[j]) > 0.0
    }
}

/// The diffuse reflectance ρ of a material, what radiosity reflects: K_diff for the classic
/// models, the weight of the BRDF's diffuse part (`Brdf::lobes`: the albedo of `diffuse` and
/// `oren_nayar`, the Lambert base of `cook_torrance` and the normalized Phongs, principled's
/// (1 − metallic)·base colour with its sheen); 0 for mirrors and glass, whose specular lobes
/// radiosity cannot represent (`explain` says so). Glossy lobes are left out: radiosity
/// exchanges diffuse light only.
pub fn reflectance(m: &Material) -> Vec3 {
    let rho = match &m.model {
        Model::Classic(c) => c.diffuse,
        Model::Physical(brdf) => brdf.lobes().weight(Part::Diffuse),
        Model::Mirror(_) | Model::Glass(_) => Vec3::ZERO,
    };
    // ρ ≤ 1 keeps the iteration a contraction; the lesson format allows no more anyway.
    rho.clamp(Vec3::ZERO, Vec3::ONE)
}
