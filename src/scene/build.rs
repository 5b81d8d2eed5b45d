//! Lesson → runtime scene: meshes generated or loaded, normals computed, placed in the world.

use super::mesh::{Mesh, MeshRepairs};
use super::normals::compute_vertex_normals;
use super::{Camera, Light, Material, Shape, obj, shapes};
use crate::lesson::Lesson;
use crate::render::RenderSettings;
use glam::{Affine3A, Vec3};

/// All objects' triangles in one world-space soup, ready for the vertex stage.
#[derive(Debug, Clone, Default)]
pub struct Geometry {
    /// World positions.
    pub positions: Vec<Vec3>,
    /// Unit world vertex normals.
    pub normals: Vec<Vec3>,
    /// Triangles (indices into the arrays above).
    pub triangles: Vec<[u32; 3]>,
    /// Material index per triangle.
    pub material: Vec<u32>,
    /// Unit world face normal per triangle (+y for a degenerate triangle, which the rasterizer skips anyway).
    pub face_normals: Vec<Vec3>,
    /// One entry per object, in lesson order.
    pub objects: Vec<ObjectBounds>,
}

/// Where an object's triangles are and a sphere around them (for culling lights).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectBounds {
    /// Its triangles are `first_triangle..first_triangle + triangles`.
    pub first_triangle: usize,
    /// Triangle count.
    pub triangles: usize,
    /// Vertex count.
    pub vertices: usize,
    /// Centre of the bounding sphere (the centre of the bounding box).
    pub centre: Vec3,
    /// Radius of the bounding sphere.
    pub radius: f32,
    /// Material index.
    pub material: u32,
}

/// The runtime scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Camera.
    pub camera: Camera,
    /// Geometry of every object.
    pub geometry: Geometry,
    /// Materials (indexed by `Geometry::material`).
    pub materials: Vec<Material>,
    /// Lights.
    pub lights: Vec<Light>,
    /// Global ambient L_glob.
    pub ambient: Vec3,
    /// Render settings.
    pub settings: RenderSettings,
    /// What mesh repair found.
    pub repairs: MeshRepairs,
}

/// A mesh that could not be loaded (bad input: exit code 2).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct SceneError(#[from] pub obj::ObjError);

/// Builds the scene of a validated lesson.
///
/// # Errors
/// [`SceneError`] when an OBJ file cannot be parsed.
pub fn build(lesson: &Lesson) -> Result<Scene, SceneError> {
    let mut geometry = Geometry::default();
    let mut repairs = MeshRepairs::default();
    for o in &lesson.objects {
        let mut mesh = match &o.shape {
            Shape::UvSphere { segments, rings } => shapes::uv_sphere(*segments, *rings),
            Shape::Icosphere { subdivisions } => shapes::icosphere(*subdivisions),
            Shape::Plane => shapes::plane(),
            Shape::Cube => shapes::cube(),
            Shape::Torus { major_radius, minor_radius, segments, sides } => shapes::torus(*major_radius, *minor_radius, *segments, *sides),
            Shape::Mesh { path } => {
                let loaded = obj::load_obj(path)?;
                let mut mesh = loaded.mesh;
                if loaded.had_normals {
                    repairs.degenerate_triangles += loaded.repairs.degenerate_triangles;
                    repairs.repaired_normals += loaded.repairs.repaired_normals;
                } else {
                    // Recompute with the lesson's weighting (the loader used the plain average).
                    mesh.normals.clear();
                }
                mesh
            }
        };
        if mesh.normals.len() != mesh.positions.len() {
            let r = compute_vertex_normals(&mut mesh, lesson.render.normals);
            repairs.degenerate_triangles += r.degenerate_triangles;
            repairs.repaired_normals += r.repaired_normals;
        }
        append(&mut geometry, &mesh, o.transform, o.material as u32);
    }
    Ok(Scene {
        camera: lesson.camera,
        geometry,
        materials: lesson.materials.clone(),
        lights: lesson.lights.clone(),
        ambient: lesson.ambient,
        settings: lesson.render,
        repairs,
    })
}

/// Appends `mesh` placed in the world by `m`.
fn append(g: &mut Geometry, mesh: &Mesh, m: Affine3A, material: u32) {
    let base = g.positions.len() as u32;
    let mesh = mesh.transformed(m);
    let (lo, hi) = mesh.positions.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let centre = if mesh.positions.is_empty() { Vec3::ZERO } else { (lo + hi) * 0.5 };
    let radius = mesh.positions.iter().map(|p| p.distance(centre)).fold(0.0, f32::max);
    g.objects.push(ObjectBounds {
        first_triangle: g.triangles.len(),
        triangles: mesh.triangles.len(),
        vertices: mesh.positions.len(),
        centre,
        radius,
        material,
    });
    g.positions.extend_from_slice(&mesh.positions);
    g.normals.extend_from_slice(&mesh.normals);
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| g.positions[(base + i) as usize]);
        g.triangles.push(t.map(|i| base + i));
        g.material.push(material);
        g.face_normals.push((b - a).cross(c - a).normalize_or(Vec3::Y));
    }
}
