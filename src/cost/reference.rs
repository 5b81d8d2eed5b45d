//! The exact reference image: a ray per sample against the lesson's analytic shapes.
//!
//! Accuracy is measured against what the meshes approximate, not against another mesh.
//! Spheres (`uv_sphere`, `icosphere`: the unit sphere under the object's transform) and
//! planes (`plane`: the square [−1, 1]² in xz at y = 0 under its transform) are
//! intersected exactly (in f64, by [`crate::geometry::Analytic`]), with the exact position and the exact normal
//! (the object normal by the cofactor matrix det·M⁻ᵀ, as [`Mesh::transformed`] moves mesh
//! normals; so a non-uniformly scaled sphere is an exact ellipsoid). Each hit is then
//! shaded by [`shade_point`] exactly as the pipeline's per-sample (Phong) path does:
//! v = normalize(eye − p), the normal flipped towards the viewer when `cull = none`,
//! back faces dropped when `cull = back`, the near plane respected, non-finite shading
//! counted as zero. Every light the renderer shadows (by ray or by map) casts exact
//! shadows here: a shadow ray per light (sample) against the analytic shapes
//! ([`Occluders::Analytic`]). The only differences between a raster render with ray-cast
//! shadows and this reference are therefore tessellation, interpolation and (when
//! `samples_per_side` ≠ `aa`) sampling; a shadow map's error counts too.
//!
//! Sampling: `n × n` samples per pixel on the grid the rasterizer uses for `aa = n`
//! (sample centres at `x + (i + ½)/n`), averaged with a box filter; uncovered samples
//! count as zero and coverage is the covered share, as in [`render`](crate::render::render).
//! Rows run in parallel; each pixel's work is independent of scheduling, so the image
//! is the same for any thread count.
//!
//! [`Mesh::transformed`]: crate::scene::Mesh::transformed

use crate::effects::shadows::shadowing;
use crate::geometry::{Analytic, AnalyticKind, Hit, Ray};
use crate::lesson::Lesson;
use crate::lesson::settings::Cull;
use crate::render::develop::srgb_decode;
use crate::render::frame::{Frame, Layer};
use crate::scene::{Scene, Shape};
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
use crate::transport::{At, Lighting, shade_point};
use crate::transport::{LightShadow, Occluders, Shadows};
use glam::{DAffine3, Vec3};
use rayon::prelude::*;

/// The largest `samples_per_side` accepted (64² = 4096 rays a pixel).
pub const MAX_SAMPLES_PER_SIDE: u32 = 64;

/// Why a lesson has no exact reference.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// An object whose shape has no analytic form here (cube, torus, mesh).
    #[error("object {object} is a {shape}: the exact reference ray-casts only spheres (uv_sphere, icosphere) and planes")]
    Unsupported {
        /// Index of the object in the lesson.
        object: usize,
        /// The shape's name in the lesson format.
        shape: &'static str,
    },
    /// The lesson has `[fog]`, which the exact reference does not render.
    #[error("the lesson has [fog]: the exact reference ray-casts surfaces in a vacuum")]
    Fog,
    /// An object whose transform cannot be inverted.
    #[error("object {object} has a singular transform")]
    Singular {
        /// Index of the object in the lesson.
        object: usize,
    },
    /// `samples_per_side` outside 1..=[`MAX_SAMPLES_PER_SIDE`].
    #[error("samples per pixel side must be in 1..={MAX_SAMPLES_PER_SIDE}, got {samples_per_side}")]
    Samples {
        /// The value given.
        samples_per_side: u32,
    },
    /// The scene was not built from this lesson (object or material counts differ).
    #[error("the scene was not built from this lesson")]
    Mismatch,
}

/// One object's analytic surface and its material.
#[derive(Debug, Clone, Copy)]
struct Surface {
    /// The exact sphere or plane.
    shape: Analytic,
    /// Index into `Scene::materials`.
    material: usize,
}

/// Checks that every object of `lesson` has an analytic form, without rendering.
///
/// # Errors
/// [`ReferenceError::Unsupported`] for the first cube, torus or mesh;
/// [`ReferenceError::Singular`] for a transform that cannot be inverted.
pub fn check(lesson: &Lesson) -> Result<(), ReferenceError> {
    if lesson.scene.fog.is_some() {
        return Err(ReferenceError::Fog);
    }
    surfaces(lesson).map(|_| ())
}

/// The analytic surfaces of the lesson's objects, in lesson order.
fn surfaces(lesson: &Lesson) -> Result<Vec<Surface>, ReferenceError> {
    lesson
        .objects
        .iter()
        .enumerate()
        .map(|(object, o)| {
            let kind = match o.shape {
                Shape::UvSphere { .. } | Shape::Icosphere { .. } => AnalyticKind::Sphere,
                Shape::Plane => AnalyticKind::Plane,
                _ => return Err(ReferenceError::Unsupported { object, shape: o.shape.name() }),
            };
            let m = DAffine3::from_mat3_translation(
                glam::Mat3::from(o.transform.matrix3).as_dmat3(),
                Vec3::from(o.transform.translation).as_dvec3(),
            );
            let shape = Analytic::new(kind, m).ok_or(ReferenceError::Singular { object })?;
            Ok(Surface { shape, material: o.material })
        })
        .collect()
}

/// A unit normal as a linear colour that encodes to (N + 1)/2 in sRGB (as the pipeline's normal layer).
#[inline]
fn normal_colour(n: Vec3) -> Vec3 {
    let e = (n + Vec3::ONE) * 0.5;
    Vec3::new(srgb_decode(e.x), srgb_decode(e.y), srgb_decode(e.z))
}

/// Renders the exact reference of `lesson` (whose scene is `scene`, built from it) with
/// `samples_per_side²` rays per pixel, keeping the given layers (deduplicated, in order)
/// with the coverage semantics of [`render`](crate::render::render).
///
/// Camera, materials, lights, ambient and culling come from `scene`; shapes and
/// transforms from `lesson`. `scene.spec.settings.aa` and `interpolation` are ignored: the
/// normals are exact and shading runs at every sample. Every light of the scene is
/// evaluated (the plan's light culling relies on mesh bounds; a light it culls adds
/// exactly zero anyway).
///
/// # Errors
/// [`ReferenceError::Unsupported`] when an object is a cube, torus or mesh (use the
/// finest raster rung as the reference instead), [`ReferenceError::Singular`],
/// [`ReferenceError::Samples`] and [`ReferenceError::Mismatch`].
pub fn reference(lesson: &Lesson, scene: &Scene, layers: &[Layer], samples_per_side: u32) -> Result<Frame, ReferenceError> {
    if !(1..=MAX_SAMPLES_PER_SIDE).contains(&samples_per_side) {
        return Err(ReferenceError::Samples { samples_per_side });
    }
    check(lesson)?;
    let surfaces = surfaces(lesson)?;
    if scene.geometry.objects.len() != surfaces.len() || surfaces.iter().any(|s| s.material >= scene.materials.len()) {
        return Err(ReferenceError::Mismatch);
    }
    let mut wanted: Vec<Layer> = Vec::new();
    for l in layers {
        if !wanted.contains(l) {
            wanted.push(*l);
        }
    }

    let cam = &scene.spec.camera;
    let (w, h, n) = (cam.width, cam.height, samples_per_side);
    let rays = cam.rays();
    let near = cam.near as f64;
    let two_sided = scene.spec.settings.cull == Cull::None;
    let want_normal = wanted.contains(&Layer::Normal);
    let inv = 1.0 / (n * n) as f32;

    // The nearest hit of a camera ray (its direction has unit forward component, so t is the view depth).
    let trace = |ray: &Ray| -> Option<Hit> {
        let mut best: Option<Hit> = None;
        for (k, surface) in surfaces.iter().enumerate() {
            for (t, q) in surface.shape.intersect(ray).into_iter().flatten() {
                // The rasterizer clips at the near plane; a nearer hit of this object was already kept.
                if t < near || !t.is_finite() || best.is_some_and(|b| t >= b.t) {
                    continue;
                }
                let normal = surface.shape.normal(q);
                // Back faces (normal away from the eye) are culled unless two-sided.
                if !two_sided && normal.dot(ray.dir) > 0.0 {
                    continue;
                }
                best = Some(Hit { t, n: normal, id: k });
                break;
            }
        }
        best
    };

    // Every light the renderer shadows (by ray or map) casts exact shadows here: a shadow
    // ray per light sample against the analytic shapes.
    let per_light = scene
        .lights
        .iter()
        .map(|l| if shadowing(l, scene).method.is_some() { LightShadow::Ray } else { LightShadow::Unshadowed })
        .collect();
    let occluders = Occluders::Analytic(surfaces.iter().map(|s| s.shape).collect());
    let mut lighting = Lighting::new(scene.lights.clone(), Shadows::new(per_light, Some(occluders)));
    lighting.sampler = scene.spec.settings.sampler;
    let rows: Vec<(Vec<Vec<Vec3>>, Vec<f32>)> = (0..h)
        .into_par_iter()
        .map(|y| {
            let mut out: Vec<Vec<Vec3>> = wanted.iter().map(|_| vec![Vec3::ZERO; w as usize]).collect();
            let mut cov = vec![0f32; w as usize];
            for x in 0..w {
                let mut sum = Components::ZERO;
                let mut normal_sum = Vec3::ZERO;
                let mut covered = 0u32;
                for sy in 0..n {
                    for sx in 0..n {
                        // Sample centres on the rasterizer's grid for aa = n.
                        let ray = rays.ray((x, y), (sx, sy), n);
                        let Some(hit) = trace(&ray) else { continue };
                        covered += 1;
                        let p = ray.at(hit.t);
                        let v = (ray.origin - p).normalize();
                        // Two-sided: the normal turned towards the viewer (the pipeline's flip).
                        let normal = if two_sided && hit.n.dot(v) < 0.0 { -hit.n } else { hit.n };
                        let (p, v, normal) = (p.as_vec3(), v.as_vec3(), normal.as_vec3());
                        let mut k = EvalCounts::default();
                        let at = At { object: hit.id as u32, ..At::point(p, normal) };
                        let c = shade_point(&scene.materials[surfaces[hit.id].material], &lighting, scene.spec.ambient, at, v, &mut k);
                        if want_normal {
                            normal_sum += normal_colour(normal);
                        }
                        // Non-finite shading counts as zero, as in the pipeline.
                        if c.is_finite() {
                            sum += c;
                        }
                    }
                }
                if covered == 0 {
                    continue;
                }
                let i = x as usize;
                for (layer, buf) in wanted.iter().zip(out.iter_mut()) {
                    buf[i] = if *layer == Layer::Normal { normal_sum * inv } else { layer.of(&sum) * inv };
                }
                cov[i] = covered as f32 * inv;
            }
            (out, cov)
        })
        .collect();

    let mut buffers: Vec<Vec<Vec3>> = wanted.iter().map(|_| Vec::with_capacity((w * h) as usize)).collect();
    let mut coverage = Vec::with_capacity((w * h) as usize);
    for (row, cov) in rows {
        for (buf, r) in buffers.iter_mut().zip(row) {
            buf.extend(r);
        }
        coverage.extend(cov);
    }
    Ok(Frame { width: w, height: h, layers: wanted.into_iter().zip(buffers).collect(), coverage, background: cam.background })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cost::metrics::{ErrorMetrics, error_metrics};
    use crate::lesson::{self, Lesson};
    use crate::render::{Interpolation, render};
    use std::path::Path;

    /// One Lambert sphere (K_diff = 0.8) under one directional light, no ambient.
    fn sphere_lesson(size: u32, shape: &str, interpolation: &str, aa: u32, extra: &str) -> Lesson {
        let text = format!(
            r#"
[camera]
position = [0.0, 0.0, 4.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 35.0
size = [{size}, {size}]
background = [0.0, 0.0, 0.0]

[[object]]
{shape}
material = "matte"
{extra}

[material.matte]
model = "lambert"
diffuse = 0.8

[[light]]
kind = "directional"
direction = [-0.75, -0.55, -0.35]
intensity = 1.0

[scene]
ambient = 0.0

[render]
interpolation = "{interpolation}"
aa = {aa}
"#
        );
        lesson::parse(&text, Path::new("t.toml"), &[]).unwrap()
    }

    fn uv(segments: u32) -> String {
        format!("shape = \"uv_sphere\"\nsegments = {segments}\nrings = {}", segments / 2)
    }

    fn build(l: &Lesson) -> Scene {
        crate::scene::build::build(l).unwrap()
    }

    /// Raster render of `l` against its exact reference with the same sampling.
    fn raster_error(l: &Lesson) -> ErrorMetrics {
        raster_errors(l).0
    }

    /// [`raster_error`] and the RMSE over the pixels fully covered in both frames (the
    /// shading error alone, without the silhouette's coverage error).
    fn raster_errors(l: &Lesson) -> (ErrorMetrics, f64) {
        let scene = build(l);
        let (frame, _) = render(&scene, &[Layer::Total]);
        let exact = reference(l, &scene, &[Layer::Total], scene.spec.settings.aa).unwrap();
        let (a, b) = (frame.layer(Layer::Total).unwrap(), exact.layer(Layer::Total).unwrap());
        let (mut sum, mut n) = (0.0, 0);
        for i in 0..a.len() {
            if frame.coverage[i] == 1.0 && exact.coverage[i] == 1.0 {
                sum += (a[i] - b[i]).length_squared() as f64;
                n += 3;
            }
        }
        (error_metrics(&frame, &exact, Layer::Total, 0.0).unwrap(), (sum / n as f64).sqrt())
    }

    #[test]
    fn centre_pixel_is_the_lambert_cosine_law() {
        let l = sphere_lesson(65, &uv(16), "phong", 1, "");
        let scene = build(&l);
        let f = reference(&l, &scene, &[Layer::Diffuse, Layer::Total, Layer::Diffuse], 1).unwrap();
        assert_eq!(f.layers.iter().map(|(l, _)| *l).collect::<Vec<_>>(), vec![Layer::Diffuse, Layer::Total]);
        // The centre ray hits (0, 0, 1), where N = +z.
        let light = Vec3::new(0.75, 0.55, 0.35).normalize();
        let expected = 0.8 * light.z.max(0.0);
        for layer in [Layer::Diffuse, Layer::Total] {
            let c = f.at(layer, 32, 32);
            assert!((c - Vec3::splat(expected)).abs().max_element() < 1e-6, "{layer:?}: {c} vs {expected}");
        }
        assert_eq!(f.coverage[32 * 65 + 32], 1.0);
        // A corner misses: background, no coverage.
        assert_eq!(f.coverage[0], 0.0);
        assert_eq!(f.at(Layer::Total, 0, 0), Vec3::ZERO);
    }

    #[test]
    fn fine_phong_sphere_is_close_to_the_reference() {
        let m = raster_error(&sphere_lesson(96, &uv(256), "phong", 2, ""));
        assert!(m.rmse < 2e-3, "{m:?}");
    }

    #[test]
    fn error_ordering_flat_gouraud_phong_on_a_coarse_sphere() {
        let err = |i: &str| raster_errors(&sphere_lesson(96, &uv(16), i, 2, ""));
        let (flat, gouraud, phong) = (err("flat"), err("gouraud"), err("phong"));
        let (f, g, p) = (flat.0.rmse, gouraud.0.rmse, phong.0.rmse);
        assert!(f > g && g > p, "flat {f}, gouraud {g}, phong {p}");
        // The silhouette (the same polygon for all three) dominates those; inside it the
        // interpolation is all that differs, and the gaps are wide.
        let (f, g, p) = (flat.1, gouraud.1, phong.1);
        assert!(f > 2.0 * g && g > 2.0 * p, "inside: flat {f}, gouraud {g}, phong {p}");
        // The 8 × 4 flat sphere is much worse than the fine Phong one.
        let coarse = raster_error(&sphere_lesson(96, &uv(8), "flat", 2, "")).rmse;
        let fine = raster_error(&sphere_lesson(96, &uv(256), "phong", 2, "")).rmse;
        assert!(coarse > 10.0 * fine, "coarse flat {coarse}, fine phong {fine}");
    }

    #[test]
    fn error_falls_as_tessellation_rises() {
        let errors: Vec<f64> =
            [8, 16, 32, 64, 128].iter().map(|&s| raster_error(&sphere_lesson(96, &uv(s), "phong", 2, "")).rmse).collect();
        assert!(errors.windows(2).all(|w| w[0] > w[1]), "{errors:?}");
    }

    #[test]
    fn silhouette_coverage_is_fractional_and_the_disc_has_the_right_area() {
        let l = sphere_lesson(64, &uv(16), "phong", 1, "");
        let scene = build(&l);
        let one = reference(&l, &scene, &[Layer::Total], 1).unwrap();
        assert!(one.coverage.iter().all(|&c| c == 0.0 || c == 1.0));
        let four = reference(&l, &scene, &[Layer::Total], 4).unwrap();
        let partial = four.coverage.iter().filter(|&&c| c > 0.0 && c < 1.0).count();
        assert!(partial > 50, "{partial} partly covered pixels");
        // The silhouette of a unit sphere seen from distance 4 subtends asin(1/4).
        let r_ndc = (0.25f64.asin().tan()) / (17.5f64.to_radians().tan());
        let area = std::f64::consts::PI * (r_ndc * 32.0).powi(2);
        let covered: f64 = four.coverage.iter().map(|&c| c as f64).sum();
        assert!((covered / area - 1.0).abs() < 0.01, "covered {covered} vs {area}");
    }

    #[test]
    fn non_uniform_scale_is_an_exact_ellipsoid() {
        let (m, inside) =
            raster_errors(&sphere_lesson(96, &uv(256), "phong", 2, "scale = [1.4, 0.7, 1.0]\nrotate_deg = [20.0, 30.0, 0.0]"));
        // Shading matches closely; a couple of silhouette samples flip (the 128 rings' chords).
        assert!(inside < 2e-4, "{inside}");
        assert!(m.rmse < 5e-3 && m.visible_pct < 0.1, "{m:?}");
    }

    #[test]
    fn icosphere_is_a_sphere_too() {
        let m = raster_error(&sphere_lesson(96, "shape = \"icosphere\"\nsubdivisions = 5", "phong", 2, ""));
        assert!(m.rmse < 3e-3, "{m:?}");
    }

    #[test]
    fn planes_are_culled_or_two_sided_like_the_pipeline() {
        let plane = "shape = \"plane\"\nscale = 0.9";
        let facing = sphere_lesson(64, plane, "phong", 2, "rotate_deg = [90.0, 0.0, 0.0]");
        let m = raster_error(&facing);
        assert!(m.rmse < 1e-3, "{m:?}");
        // Seen from behind: nothing with back-face culling...
        let away = sphere_lesson(64, plane, "phong", 2, "rotate_deg = [-90.0, 0.0, 0.0]");
        let scene = build(&away);
        let f = reference(&away, &scene, &[Layer::Total], 2).unwrap();
        assert!(f.coverage.iter().all(|&c| c == 0.0));
        // ...and lit with the flipped normal (+z, towards the camera) when two-sided.
        let mut scene = build(&away);
        scene.spec.settings.cull = Cull::None;
        let f = reference(&away, &scene, &[Layer::Total], 1).unwrap();
        let expected = 0.8 * Vec3::new(0.75, 0.55, 0.35).normalize().z;
        assert!((f.at(Layer::Total, 32, 32) - Vec3::splat(expected)).abs().max_element() < 1e-6);
        let (raster, _) = render(&scene, &[Layer::Total]);
        let exact = reference(&away, &scene, &[Layer::Total], scene.spec.settings.aa).unwrap();
        let m = error_metrics(&raster, &exact, Layer::Total, 0.0).unwrap();
        assert!(m.rmse < 1e-3, "{m:?}");
    }

    #[test]
    fn normal_layer_matches_the_pipeline_convention() {
        let l = sphere_lesson(65, &uv(256), "phong", 1, "");
        let scene = build(&l);
        let f = reference(&l, &scene, &[Layer::Normal], 1).unwrap();
        // N = +z at the centre: encodes to (128, 128, 255) or so.
        let c = f.at(Layer::Normal, 32, 32);
        assert!((c - normal_colour(Vec3::Z)).abs().max_element() < 1e-5, "{c}");
        let (raster, _) = render(&scene, &[Layer::Normal]);
        let m = error_metrics(&raster, &f, Layer::Normal, 0.0).unwrap();
        assert!(m.rmse < 5e-3, "{m:?}");
    }

    #[test]
    fn unsupported_shapes_and_bad_arguments_are_errors() {
        let l = sphere_lesson(16, "shape = \"cube\"", "phong", 1, "");
        let scene = build(&l);
        assert_eq!(reference(&l, &scene, &[Layer::Total], 2), Err(ReferenceError::Unsupported { object: 0, shape: "cube" }));
        assert_eq!(check(&l), Err(ReferenceError::Unsupported { object: 0, shape: "cube" }));
        let l = sphere_lesson(16, &uv(8), "phong", 1, "");
        let scene = build(&l);
        assert_eq!(check(&l), Ok(()));
        assert_eq!(reference(&l, &scene, &[Layer::Total], 0), Err(ReferenceError::Samples { samples_per_side: 0 }));
        assert_eq!(reference(&l, &scene, &[Layer::Total], 65), Err(ReferenceError::Samples { samples_per_side: 65 }));
        let mut other = l.clone();
        other.objects.push(other.objects[0].clone());
        assert_eq!(reference(&other, &scene, &[Layer::Total], 1), Err(ReferenceError::Mismatch));
        // The ray cast renders no fog: a lesson with [fog] has no exact reference.
        let fogged = lesson::parse(&format!("{}\n[fog]\nkind = \"exp\"\ndensity = 0.1\n", l.source), &l.path, &[]).unwrap();
        assert_eq!(check(&fogged), Err(ReferenceError::Fog));
        assert_eq!(reference(&fogged, &build(&fogged), &[Layer::Total], 1), Err(ReferenceError::Fog));
    }

    #[test]
    fn same_image_for_one_thread_and_four() {
        let l = sphere_lesson(80, &uv(16), "phong", 1, "");
        let scene = build(&l);
        let run = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| reference(&l, &scene, &[Layer::Total, Layer::Diffuse], 3).unwrap())
        };
        let (a, b) = (run(1), run(4));
        let bits = |f: &Frame| -> Vec<u32> {
            f.layers
                .iter()
                .flat_map(|(_, px)| px.iter().flat_map(|c| c.to_array().map(f32::to_bits)))
                .chain(f.coverage.iter().map(|c| c.to_bits()))
                .collect()
        };
        assert_eq!(bits(&a), bits(&b));
    }

    #[test]
    fn interpolation_setting_is_ignored_by_the_reference() {
        let a = sphere_lesson(32, &uv(8), "flat", 1, "");
        let b = sphere_lesson(32, &uv(64), "phong", 1, "");
        assert_eq!(build(&a).spec.settings.interpolation, Interpolation::Flat);
        assert_eq!(reference(&a, &build(&a), &[Layer::Total], 2).unwrap(), reference(&b, &build(&b), &[Layer::Total], 2).unwrap());
    }
}
