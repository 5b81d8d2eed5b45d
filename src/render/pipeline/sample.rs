//! One sample as the strips shade it, taken apart for `explain --pixel`
//! ([`crate::render::pixel`]): the surface the sample sees, the material its shading reads
//! (textures applied), and the points the lighting was evaluated at (the sample itself under
//! Phong interpolation, the triangle's three vertices under Gouraud, its centroid when flat),
//! with the render's own [`Lighting`] (its shadow maps, rays and environment). Every value
//! is made by the code the strips and the lighting passes run, so an explanation built from
//! them is the render's arithmetic, not a second model of it.

use super::dispatch::{Lit, Renderer, radiosity_mesh, rasterize};
use crate::lesson::settings::RenderMethod;
use crate::raster::NO_TRIANGLE;
use crate::render::frame::Layer;
use crate::render::texturing;
use crate::scene::{Material, Scene};
use crate::transport::{At, Lighting};
use glam::Vec3;

/// How the sample's lighting was evaluated.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LitBy {
    /// Per sample (Phong interpolation): one point, the sample.
    Sample,
    /// At the triangle's vertices, the sample interpolating their values (Gouraud).
    Vertices,
    /// Once per face at its centroid (flat).
    Face,
    /// By the radiosity solution baked before the strips (its patches' values).
    Radiosity,
}

/// A point the lighting was evaluated at, and its share of the sample's value.
#[derive(Debug, Clone)]
pub struct LitPoint {
    /// Its weight in the sample (the barycentric weight of a vertex; 1 otherwise).
    pub weight: f32,
    /// The vertex, under Gouraud interpolation.
    pub vertex: Option<u32>,
    /// The point as shading received it (unit normal turned toward the eye when two-sided).
    pub at: At<f32>,
    /// Unit view vector V.
    pub v: Vec3,
    /// The material shading read there (textured at the sample under Phong).
    pub material: Material,
}

/// The surface one sample sees.
#[derive(Debug, Clone)]
pub struct SampleSurface {
    /// The triangle (scene numbering).
    pub tri: u32,
    /// The object it belongs to (lesson order).
    pub object: u32,
    /// The material index of the triangle.
    pub material: usize,
    /// Perspective-correct barycentric weights (b0, b1, b2) of the sample.
    pub bary: Vec3,
    /// Position.
    pub p: Vec3,
    /// The interpolated (or, flat, the face) unit shading normal, toward the eye when two-sided.
    pub n: Vec3,
    /// Unit geometric (face) normal.
    pub ng: Vec3,
    /// Unit view vector V = (eye − p)/|eye − p|.
    pub v: Vec3,
    /// How its lighting was evaluated.
    pub lit_by: LitBy,
    /// The points the lighting was evaluated at (none under radiosity).
    pub points: Vec<LitPoint>,
}

/// What the render evaluated for some pixels at one sample per pixel.
#[derive(Debug, Clone)]
pub struct SampleInputs {
    /// The render's lighting: the lights the plan keeps, their shadows, the environment.
    pub lighting: Lighting,
    /// The lesson index of each light of `lighting.lights`.
    pub light_index: Vec<usize>,
    /// Per pixel asked for, the surface its centre sees, or `None` for the background.
    pub surfaces: Vec<Option<SampleSurface>>,
}

/// The inputs of each of `pixels`' samples: the scene rasterized and its lighting built once
/// for all of them. Precondition: `scene.spec.settings.aa == 1` (one sample per pixel, at
/// its centre) and every pixel lies in the image.
pub fn sample_inputs(scene: &Scene, pixels: &[(u32, u32)]) -> SampleInputs {
    debug_assert_eq!(scene.spec.settings.aa, 1, "one sample per pixel");
    let plan = crate::render::plan::plan(scene);
    let light_index = plan.lights.iter().enumerate().filter(|(_, d)| d.runs).map(|(i, _)| i).collect();
    let vis = rasterize(scene);
    let at = |(x, y): (u32, u32)| vis.samples[(y * vis.width + x) as usize];
    if scene.spec.settings.method == RenderMethod::Radiosity {
        // The solution lit every patch before the strips: no light is evaluated at the
        // sample, so no lighting is built (a second bake would cost seconds).
        let meshed = radiosity_mesh(scene).expect("a radiosity render meshes its scene");
        let surfaces = pixels
            .iter()
            .map(|&p| {
                let s = at(p);
                (s.tri != NO_TRIANGLE).then(|| baked_surface(&meshed, s.tri as usize, s.bary()))
            })
            .collect();
        return SampleInputs { lighting: Lighting::default(), light_index: Vec::new(), surfaces };
    }
    let r = Renderer::new(scene, &[Layer::Total], None);
    let surfaces = pixels
        .iter()
        .map(|&p| {
            let s = at(p);
            (s.tri != NO_TRIANGLE).then(|| surface(&r, s.tri as usize, s.bary(), p))
        })
        .collect();
    SampleInputs { lighting: r.lighting.clone(), light_index, surfaces }
}

/// The surface of a radiosity render's patch triangle `t` at barycentrics `b`.
fn baked_surface(scene: &Scene, t: usize, b: Vec3) -> SampleSurface {
    let g = &scene.geometry;
    let [i0, i1, i2] = g.triangles[t].map(|i| i as usize);
    let p = g.positions[i0] * b.x + g.positions[i1] * b.y + g.positions[i2] * b.z;
    let ng = g.face_normals[t];
    let n = (g.normals[i0] * b.x + g.normals[i1] * b.y + g.normals[i2] * b.z).normalize_or(ng);
    let v = (scene.spec.camera.position - p).normalize_or(ng);
    let object = g.object_of_triangle(t);
    SampleSurface {
        tri: t as u32,
        object,
        material: g.material[t] as usize,
        bary: b,
        p,
        n,
        ng,
        v,
        lit_by: LitBy::Radiosity,
        points: Vec::new(),
    }
}

/// The surface of triangle `t` at barycentrics `b`, and where its lighting was evaluated.
fn surface(r: &Renderer, t: usize, b: Vec3, pixel: (u32, u32)) -> SampleSurface {
    let g = &r.scene.geometry;
    let (p, n_sample, v) = r.surface(t, b);
    let n = r.normal(t, b);
    let ng = g.face_normals[t];
    let object = g.object_of_triangle(t);
    let mi = g.material[t] as usize;
    let eye = r.eye;
    // A point lit ahead of the strips, as `light_ahead` lights it.
    let ahead = |weight: f32, vertex: Option<u32>, at: At<f32>, m: usize| {
        let (pp, nn) = (Vec3::from(at.p), Vec3::from(at.n));
        let v = (eye - pp).normalize_or(nn);
        let nn = if r.two_sided && nn.dot(v) < 0.0 { -nn } else { nn };
        LitPoint { weight, vertex, at: At { n: nn.into(), ..at }, v, material: r.scene.materials[m].clone() }
    };
    let (lit_by, points) = {
        match r.lit {
            Lit::Vertices { .. } => {
                let tri = g.triangles[t];
                let points = (0..3)
                    .map(|k| {
                        let i = tri[k] as usize;
                        let at = At { object: g.object_of_vertex(i), ..At::point(g.positions[i], g.normals[i]) };
                        ahead(b[k], Some(i as u32), at, vertex_material(r, i))
                    })
                    .collect();
                (LitBy::Vertices, points)
            }
            Lit::Faces { .. } => {
                let centroid = g.triangles[t].iter().map(|&i| g.positions[i as usize]).sum::<Vec3>() / 3.0;
                let at = At { tri: t as u32, object, ..At::point(centroid, ng) };
                (LitBy::Face, vec![ahead(1.0, None, at, mi)])
            }
            Lit::Samples | Lit::Nothing => {
                let m = &r.scene.materials[mi];
                let mut n = n_sample;
                let mut material = m.clone();
                if let Some(tex) = r.scene.textures.get(mi).filter(|t| t.any()) {
                    // As the strips' textured path reads the material at the sample's uv.
                    let rays = r.scene.spec.camera.rays();
                    let filter = r.scene.spec.settings.texture_filter;
                    let uv = texturing::uv_at(g, t, b);
                    let duv = texturing::uv_footprint(g, t, &rays, pixel, r.aa);
                    material = tex.apply(m, tex.sample(uv, duv, filter));
                    if let Some(map) = &tex.normal {
                        n = texturing::bend_normal(n, texturing::triangle_tangent(g, t), map.sample(uv, duv, filter));
                    }
                }
                let at = At { tri: t as u32, object, ng: ng.into(), ..At::point(p, n) };
                (LitBy::Sample, vec![LitPoint { weight: 1.0, vertex: None, at, v, material }])
            }
        }
    };
    SampleSurface { tri: t as u32, object, material: mi, bary: b, p, n, ng, v, lit_by, points }
}

/// The material a vertex is lit with under Gouraud: that of the first triangle using it
/// (as `light_ahead` assigns it).
fn vertex_material(r: &Renderer, i: usize) -> usize {
    let g = r.g;
    g.triangles.iter().position(|tri| tri.contains(&(i as u32))).map_or(0, |t| g.material[t] as usize)
}
