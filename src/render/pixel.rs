//! `explain --pixel X,Y`: every vector, cosine and term behind one pixel.
//!
//! The numbers come from the renderer's own code, never from a second model of it: the
//! pixel's value and layers are read from a render of the lesson (one sample per pixel, at
//! the pixel's centre); the surface, the material shading read and the points the lighting
//! was evaluated at come from the strips' code ([`sample_inputs`]); each light's share is
//! what shading gives for that light's incidents alone ([`light_incidents`]), and the sum
//! of the shares is checked against the rendered value ([`PixelReport::difference`]).

use crate::effects::shadows::MapDepths;
use crate::geometry::vector::reflect;
use crate::lesson::settings::{Interpolation, Tonemap};
use crate::light::ShadowMethod;
use crate::render::develop::develop;
use crate::render::frame::Layer;
use crate::render::pipeline::{LitBy, LitPoint, render, sample_inputs};
use crate::render::plan::{Pass, plan};
use crate::scene::{Model, Scene};
use crate::shading::Components;
use crate::shading::brdf::{Brdf, local_frame, to_local};
use crate::shading::classic::EvalCounts;
use crate::shading::incident::Incident;
use crate::shading::microfacet::{clamp_alpha, half_vector};
use crate::shading::shade::shade;
use crate::transport::incidents::light_incidents;
use crate::transport::{At, LightShadow, Lighting, Origin, SceneRays, shade_point};
use glam::Vec3;

/// The layers a pixel's explanation reads from the render, in [`Components`] order.
const TERM_LAYERS: [Layer; 6] = [Layer::Emission, Layer::Ambient, Layer::Diffuse, Layer::Specular, Layer::Reflection, Layer::Transmission];

/// A pixel that is not in the image.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutsideImage {
    /// The pixel asked for.
    pub pixel: (u32, u32),
    /// The image's size.
    pub size: (u32, u32),
}

impl std::fmt::Display for OutsideImage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ((x, y), (w, h)) = (self.pixel, self.size);
        write!(
            f,
            "pixel {x},{y} is outside the {w}×{h} image: X must be 0..={} and Y 0..={} (origin top-left, as in the PNG)",
            w - 1,
            h - 1
        )
    }
}

/// One pixel explained.
#[derive(Debug, Clone)]
pub struct PixelReport {
    /// (x, y) in the image, origin top-left.
    pub pixel: (u32, u32),
    /// The lesson's samples per pixel side: above 1, the explanation is of the centre sample.
    pub aa: u32,
    /// The rendered pixel, linear (the mean of its aa² samples).
    pub linear: Vec3,
    /// The pixel's 8-bit sRGB code, as the PNG holds it.
    pub srgb: [u8; 3],
    /// The centre sample's value, linear (a render at one sample per pixel).
    pub sample: Vec3,
    /// The centre sample's term layers, as rendered.
    pub layers: Components,
    /// Exposure (a factor on the linear value before the tone map).
    pub exposure: f32,
    /// The tone map.
    pub tonemap: Tonemap,
    /// The surface the centre sample sees; `None` for the background.
    pub surface: Option<SurfaceReport>,
}

/// What the pixel's surface point is and what lights it.
#[derive(Debug, Clone)]
pub struct SurfaceReport {
    /// The object, in file order from 0.
    pub object: u32,
    /// Its material's name.
    pub material: String,
    /// The material's model (`phong`, `cook_torrance`, ...).
    pub model: String,
    /// The triangle, in the scene's numbering.
    pub triangle: u32,
    /// Position p.
    pub position: Vec3,
    /// Unit view vector V.
    pub v: Vec3,
    /// The shading normal N at the sample (interpolated and renormalized; flat: the face's).
    pub n: Vec3,
    /// The geometric (face) normal.
    pub ng: Vec3,
    /// How the lighting was evaluated.
    pub lit_by: LitBy,
    /// The interpolation setting.
    pub interpolation: Interpolation,
    /// Under Gouraud: each vertex, its barycentric weight, normal and lit value.
    pub vertices: Vec<VertexReport>,
    /// Each light the plan keeps, in file order.
    pub lights: Vec<LightReport>,
    /// The global ambient term K_amb ⊗ L_glob.
    pub global_ambient: Vec3,
    /// The emission term.
    pub emission: Vec3,
    /// The surface's terms as shading recomputes them here (the weighted points' sum).
    pub recomputed: Components,
    /// The radiosity solution's value at the sample (radiosity renders only).
    pub radiosity: Option<Vec3>,
    /// What the fog pass changed: rendered total − the surface's total (with fog only).
    pub fog: Option<Vec3>,
}

/// A vertex of a Gouraud-shaded triangle.
#[derive(Debug, Clone)]
pub struct VertexReport {
    /// Vertex index.
    pub vertex: u32,
    /// Its barycentric weight at the sample.
    pub weight: f32,
    /// Its normal as lit.
    pub n: Vec3,
    /// Its lit value (all terms).
    pub total: Vec3,
}

/// One light at the pixel's point.
#[derive(Debug, Clone)]
pub struct LightReport {
    /// The light's number in file order, from 0.
    pub index: usize,
    /// Its kind (`point`, `spot`, `rect`, ...).
    pub kind: &'static str,
    /// Incidents it delivers per point (area samples; 2 per sample for a sky).
    pub incidents: usize,
    /// Unit L toward the light (the mean over samples for a sampled light), zero when none.
    pub l: Vec3,
    /// Distance r (infinite for a distant light).
    pub distance: f32,
    /// The classic attenuation d = 1/(S_c + S_l r + S_q r²).
    pub attenuation: f32,
    /// The radiometric falloff 1/r² of physically based shading (a sample weight for area lights).
    pub inv_r2: f32,
    /// The spot factor C_spot.
    pub c_spot: f32,
    /// Share of the light that reaches the point, in [0, 1].
    pub visibility: f32,
    /// The shadow method that decided the visibility, if any.
    pub shadow: Option<ShadowMethod>,
    /// The object that blocks the light's centre (ray-cast shadows).
    pub occluder: Option<u32>,
    /// The shadow map's depth at the point's texel against the point's (map shadows).
    pub map: Option<MapDepths>,
    /// N·L.
    pub n_dot_l: f32,
    /// R = 2(N·L)N − L.
    pub r: Vec3,
    /// R·V.
    pub r_dot_v: f32,
    /// H = (L + V)/|L + V|.
    pub h: Vec3,
    /// N·H.
    pub n_dot_h: f32,
    /// The light's terms at the pixel (weighted over the points lit).
    pub terms: Components,
    /// For a physically based material: the BRDF at (L, V).
    pub brdf: Option<BrdfAt>,
}

/// A physically based BRDF evaluated for one light.
#[derive(Debug, Clone, Copy)]
pub struct BrdfAt {
    /// Diffuse part f_d (1/sr).
    pub f_diffuse: Vec3,
    /// Specular part f_s (1/sr).
    pub f_specular: Vec3,
    /// cos θ = N·L (0 below the horizon).
    pub cos_theta: f32,
    /// Microfacet D, G and F (Cook-Torrance only): D(h), G(l, v, h), F(v·h).
    pub dgf: Option<(f32, f32, Vec3)>,
}

impl PixelReport {
    /// The rendered surface value − the recomputed one: the centre sample's total, or with
    /// fog the sum of its term layers (which the fog leaves alone). Zero up to float rounding
    /// when the explanation is the render's arithmetic; `None` under radiosity (the
    /// solution's value is read, not recomputed).
    pub fn difference(&self) -> Option<Vec3> {
        let s = self.surface.as_ref()?;
        if s.radiosity.is_some() {
            return None;
        }
        let rendered = if s.fog.is_some() { self.layers.total() } else { self.sample };
        Some(rendered - s.recomputed.total())
    }
}

/// Why a pixel of `scene` cannot be taken apart, if it cannot: a path-traced pixel is the
/// mean of its paths, not a sum of the equation's terms at one point.
pub fn unexplained(scene: &Scene) -> Option<String> {
    (scene.spec.settings.method == crate::lesson::settings::RenderMethod::Path).then(|| {
        "explain --pixel takes the rasterizer's terms apart, and this lesson renders with method = \"path\" (a pixel is the mean of its paths)\n  hint: add --set render.method=raster to explain the same pixel as the rasterizer renders it".to_string()
    })
}

/// Explains each of `pixels` of `scene`'s render. Errors when a pixel lies outside the image.
pub fn explain_pixels(scene: &Scene, pixels: &[(u32, u32)]) -> Result<Vec<PixelReport>, OutsideImage> {
    let cam = &scene.spec.camera;
    let size = (cam.width, cam.height);
    if let Some(&pixel) = pixels.iter().find(|(x, y)| *x >= size.0 || *y >= size.1) {
        return Err(OutsideImage { pixel, size });
    }
    let settings = &scene.spec.settings;
    let aa = settings.aa;
    let mut one = scene.clone();
    one.spec.settings.aa = 1;
    let mut layers = vec![Layer::Total];
    layers.extend(TERM_LAYERS);
    let (frame1, _) = render(&one, &layers);
    let full = if aa > 1 { render(scene, &[Layer::Total]).0 } else { frame1.clone() };
    let bytes = develop(&full, Layer::Total, settings.exposure, settings.tonemap).expect("the total was kept");
    let fog = plan(&one).running().any(|p| p == Pass::Fog);
    let rays = std::cell::OnceCell::new();
    // The scene rasterized and lit once for every pixel asked.
    let inputs = sample_inputs(&one, pixels);
    let reports = pixels
        .iter()
        .zip(&inputs.surfaces)
        .map(|(&(x, y), surface)| {
            let i = (y * cam.width + x) as usize * 3;
            let at_layer = |l: Layer| frame1.at(l, x, y);
            let layers = Components {
                emission: at_layer(Layer::Emission),
                ambient: at_layer(Layer::Ambient),
                diffuse: at_layer(Layer::Diffuse),
                specular: at_layer(Layer::Specular),
                reflection: at_layer(Layer::Reflection),
                transmission: at_layer(Layer::Transmission),
            };
            let sample = frame1.at(Layer::Total, x, y);
            let surface = surface.as_ref().map(|s| {
                let rays = || rays.get_or_init(|| SceneRays::build(&one));
                surface_report(&one, &inputs.lighting, &inputs.light_index, s, layers, rays, fog.then_some(sample))
            });
            PixelReport {
                pixel: (x, y),
                aa,
                linear: full.at(Layer::Total, x, y),
                srgb: [bytes[i], bytes[i + 1], bytes[i + 2]],
                sample,
                layers,
                exposure: settings.exposure,
                tonemap: settings.tonemap,
                surface,
            }
        })
        .collect();
    Ok(reports)
}

/// The surface part of a pixel's report. `fog_total`: the rendered sample when fog ran.
fn surface_report<'r>(
    scene: &Scene,
    lighting: &Lighting,
    light_index: &[usize],
    s: &crate::render::pipeline::SampleSurface,
    layers: Components,
    rays: impl Fn() -> &'r SceneRays,
    fog_total: Option<Vec3>,
) -> SurfaceReport {
    let material = &scene.materials[s.material];
    let ga = scene.spec.ambient;
    let mut k = EvalCounts::default();
    let weighted = |f: &mut dyn FnMut(&LitPoint) -> Components| s.points.iter().fold(Components::ZERO, |acc, pt| acc + f(pt) * pt.weight);
    // What the render computed at each point, through the one integrator entry point; the
    // lighting passes set a non-finite point to zero.
    let recomputed = weighted(&mut |pt| {
        let c = shade_point(&pt.material, lighting, ga, pt.at, pt.v, &mut k);
        if s.lit_by != LitBy::Sample && !c.is_finite() { Components::ZERO } else { c }
    });
    let base = weighted(&mut |pt| shade(&pt.material, std::iter::empty(), ga, Vec3::from(pt.at.n), pt.v, &mut k));
    let plan = plan(scene);
    let sample_at = At { tri: s.tri, object: s.object, ng: s.ng.into(), ..At::point(s.p, s.n) };
    let lights = lighting
        .lights
        .iter()
        .enumerate()
        .map(|(j, light)| {
            let index = light_index[j];
            let terms = weighted(&mut |pt| {
                let incs = light_incidents(lighting, &pt.at, j);
                // Shading adds the emission once per call: it is the surface's, not the light's.
                Components { emission: Vec3::ZERO, ..shade(&pt.material, incs, Vec3::ZERO, Vec3::from(pt.at.n), pt.v, &mut k) }
            });
            // The geometry at the sample itself (under Gouraud, what Phong would see there).
            let pt = s.points.first().filter(|_| s.lit_by != LitBy::Vertices);
            let (at, n, v, m) = match pt {
                Some(pt) => (pt.at, Vec3::from(pt.at.n), pt.v, &pt.material),
                None => (sample_at, s.n, s.v, material),
            };
            let incs = light_incidents(lighting, &at, j);
            let shadow = plan.shadows.get(index).and_then(|sh| sh.method);
            let mut report = light_report(index, light.kind.name(), &incs, n, v, m, terms, shadow);
            if shadow == Some(ShadowMethod::Ray) && report.visibility < 1.0 && report.l != Vec3::ZERO {
                let o = Origin { p: s.p, ng: s.ng, tri: s.tri, object: s.object };
                report.occluder = rays().closest(&o, report.l).filter(|h| h.t < report.distance).map(|h| h.object);
            }
            if let LightShadow::Map(map) = &lighting.shadows.per_light[j]
                && report.l != Vec3::ZERO
            {
                report.map = map.depths(s.p, s.ng, report.l);
            }
            report
        })
        .collect();
    let vertices = if s.lit_by == LitBy::Vertices {
        s.points
            .iter()
            .map(|pt| {
                let c = shade_point(&pt.material, lighting, ga, pt.at, pt.v, &mut k);
                let total = if c.is_finite() { c.total() } else { Vec3::ZERO };
                VertexReport { vertex: pt.vertex.unwrap_or(u32::MAX), weight: pt.weight, n: Vec3::from(pt.at.n), total }
            })
            .collect()
    } else {
        Vec::new()
    };
    let radiosity = (s.lit_by == LitBy::Radiosity).then(|| layers.total());
    let recomputed = if radiosity.is_some() { layers } else { recomputed };
    SurfaceReport {
        object: s.object,
        material: material.name.clone(),
        model: material.family_name().to_string(),
        triangle: s.tri,
        position: s.p,
        v: s.v,
        n: s.n,
        ng: s.ng,
        lit_by: s.lit_by.clone(),
        interpolation: scene.spec.settings.interpolation,
        vertices,
        lights,
        global_ambient: base.ambient,
        emission: base.emission,
        recomputed,
        radiosity,
        fog: fog_total.map(|t| t - recomputed.total()),
    }
}

/// One light's geometry at a point (`incs`, its incidents there) and its terms.
#[allow(clippy::too_many_arguments)]
fn light_report(
    index: usize,
    kind: &'static str,
    incs: &[Incident<f32>],
    n: Vec3,
    v: Vec3,
    m: &crate::scene::Material,
    terms: Components,
    shadow: Option<ShadowMethod>,
) -> LightReport {
    let count = incs.len().max(1) as f32;
    let mean = |f: &dyn Fn(&Incident<f32>) -> f32| incs.iter().map(f).sum::<f32>() / count;
    let l = incs.iter().map(|i| Vec3::from(i.l)).sum::<Vec3>().normalize_or_zero();
    let n_dot_l = n.dot(l);
    let r = if l == Vec3::ZERO { Vec3::ZERO } else { reflect(l, n) };
    let h = (l + v).normalize_or_zero();
    let brdf = match &m.model {
        Model::Physical(b) if l != Vec3::ZERO => Some(brdf_at(b, n, l, v)),
        _ => None,
    };
    LightReport {
        index,
        kind,
        incidents: incs.len(),
        l,
        distance: mean(&|i| i.distance),
        attenuation: mean(&|i| i.attenuation),
        inv_r2: mean(&|i| i.inv_r2),
        c_spot: mean(&|i| i.c_spot),
        visibility: mean(&|i| i.visibility),
        shadow,
        occluder: None,
        map: None,
        n_dot_l,
        r,
        r_dot_v: r.dot(v),
        h,
        n_dot_h: n.dot(h),
        terms,
        brdf,
    }
}

/// The BRDF `b` at (l, v) about n, with Cook-Torrance's D, G and F.
fn brdf_at(b: &Brdf, n: Vec3, l: Vec3, v: Vec3) -> BrdfAt {
    let (t, bt) = local_frame(n);
    let (ll, vl) = (to_local(l, t, bt, n), to_local(v, t, bt, n));
    let parts = b.eval_parts(ll, vl);
    let dgf = match b {
        Brdf::CookTorrance(ct) if ll.z > 0.0 && vl.z > 0.0 => {
            let alpha = clamp_alpha(ct.alpha);
            let h = half_vector(ll, vl);
            Some((ct.ndf.d(h, alpha), ct.masking.g(ct.ndf, ll, vl, h, alpha), ct.fresnel.eval(vl.dot(h))))
        }
        _ => None,
    };
    BrdfAt { f_diffuse: parts.diffuse, f_specular: parts.specular, cos_theta: ll.z.max(0.0), dgf }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::pipeline::render_image;
    use std::path::Path;

    fn scene_of(toml: &str) -> Scene {
        let lesson = crate::lesson::parse(toml, Path::new("pixel.toml"), &[]).expect("a valid lesson");
        crate::scene::build::build(&lesson).expect("a scene")
    }

    /// A floor (normal +y) filling the view from straight above, a spot light above it on the axis.
    const PLANE: &str = r#"
[camera]
position = [0, 3, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
fov_deg = 30
size = [33, 33]
[[object]]
shape = "plane"
scale = 4
material = "m"
[material.m]
model = "phong"
diffuse = [0.5, 0.25, 1.0]
specular = 0.2
shininess = 10
ambient = 0.1
[[light]]
kind = "spot"
position = [0, 2, 0]
direction = [0, -1, 0]
cutoff_deg = 40
exponent = 2
attenuation = [1, 0.5, 0.25]
intensity = 2
[scene]
ambient = 0.5
"#;

    #[test]
    fn the_centre_of_a_lit_plane_has_the_textbook_numbers() {
        let scene = scene_of(PLANE);
        let r = &explain_pixels(&scene, &[(16, 16)]).expect("inside")[0];
        let s = r.surface.as_ref().expect("the plane");
        assert!((s.n - Vec3::Y).length() < 1e-5 && (s.v - Vec3::Y).length() < 1e-3, "{:?} {:?}", s.n, s.v);
        let l = &s.lights[0];
        // Straight below the spot: L = N = V = R = H, r = 2, d = 1/(1 + 0.5·2 + 0.25·4) = 1/3.
        assert!((l.l - Vec3::Y).length() < 1e-3 && (l.distance - 2.0).abs() < 1e-3, "{:?} {}", l.l, l.distance);
        assert!((l.attenuation - 1.0 / 3.0).abs() < 1e-4 && (l.c_spot - 1.0).abs() < 1e-5, "{} {}", l.attenuation, l.c_spot);
        assert!(l.n_dot_l > 0.9999 && l.r_dot_v > 0.999 && l.n_dot_h > 0.9999);
        // diffuse = K_diff (N·L) d C_spot L = (0.5, 0.25, 1) · 2/3; specular = 0.2 · 2/3 (R·V)^10.
        let want = Vec3::new(0.5, 0.25, 1.0) * 2.0 / 3.0;
        assert!((l.terms.diffuse - want).length() < 2e-3, "{:?}", l.terms.diffuse);
        let spec = 0.2 * 2.0 / 3.0 * l.r_dot_v.powf(10.0);
        assert!((l.terms.specular - Vec3::splat(spec)).length() < 1e-4, "{:?} {spec}", l.terms.specular);
        // K_amb ⊗ L_glob.
        assert!((s.global_ambient - Vec3::splat(0.05)).length() < 1e-6, "{:?}", s.global_ambient);
        assert_eq!(r.difference(), Some(Vec3::ZERO));
    }

    #[test]
    fn a_pixel_outside_the_image_is_refused() {
        let scene = scene_of(PLANE);
        let e = explain_pixels(&scene, &[(1, 1), (33, 0)]).expect_err("x = 33 is outside 33 pixels");
        assert_eq!(e.pixel, (33, 0));
        assert!(e.to_string().contains("0..=32"), "{e}");
    }

    /// Pixels on a 3 × 3 grid inside the image.
    fn grid(scene: &Scene) -> Vec<(u32, u32)> {
        let (w, h) = (scene.spec.camera.width, scene.spec.camera.height);
        [0.3, 0.5, 0.7].iter().flat_map(|fx| [0.35, 0.5, 0.65].map(|fy| ((w as f32 * fx) as u32, (h as f32 * fy) as u32))).collect()
    }

    /// The explanation cannot drift from the renderer: on every bundled lesson, at sampled
    /// pixels, the terms recomputed from the explained inputs sum to the rendered sample (to
    /// 1e-5 relative; they are the same bits today), each light's share plus the global
    /// ambient, emission, reflection and transmission make that sum, and the 8-bit code is
    /// the PNG path's byte for byte.
    #[test]
    fn every_bundled_lesson_is_explained_to_the_rendered_value() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
        let mut files: Vec<_> = std::fs::read_dir(&dir).expect("lessons/").filter_map(|e| e.ok()).map(|e| e.path()).collect();
        files.retain(|p| p.extension().is_some_and(|e| e == "toml"));
        files.sort();
        assert!(files.len() >= 35, "{files:?}");
        let (mut checked, mut split) = (0, 0);
        for f in &files {
            let lesson = crate::lesson::load(f, &[]).expect("a bundled lesson loads");
            let scene = crate::scene::build::build(&lesson).expect("and builds");
            if unexplained(&scene).is_some() {
                continue;
            }
            let pixels = grid(&scene);
            let reports = explain_pixels(&scene, &pixels).expect("inside");
            let (png, _) = render_image(&scene, Layer::Total, scene.spec.settings.exposure, scene.spec.settings.tonemap);
            let w = scene.spec.camera.width;
            for r in &reports {
                let (x, y) = r.pixel;
                let i = ((y * w + x) * 3) as usize;
                assert_eq!(r.srgb, [png[i], png[i + 1], png[i + 2]], "{} {x},{y}: the PNG's code", f.display());
                if r.aa == 1 {
                    assert_eq!(r.linear, r.sample, "{}: at aa = 1 the pixel is its sample", f.display());
                }
                let Some(s) = &r.surface else { continue };
                let Some(d) = r.difference() else { continue };
                let rendered = if s.fog.is_some() { r.layers.total() } else { r.sample };
                let scale = rendered.abs().max_element().max(1e-3);
                assert!(
                    d.abs().max_element() <= 1e-5 * scale,
                    "{} {x},{y}: rendered {rendered:?}, explained {:?}",
                    f.display(),
                    s.recomputed
                );
                checked += 1;
                if s.lit_by == LitBy::Sample {
                    // Light by light, plus what no light gives, is the whole.
                    let parts = s.lights.iter().fold(Components::ZERO, |a, l| a + l.terms);
                    let whole = parts.total() + s.global_ambient + s.emission + s.recomputed.reflection + s.recomputed.transmission;
                    let t = s.recomputed.total();
                    assert!(
                        (whole - t).abs().max_element() <= 1e-5 * t.abs().max_element().max(1e-3),
                        "{} {x},{y}: {whole:?} vs {t:?}",
                        f.display()
                    );
                    split += 1;
                }
            }
        }
        assert!(checked > 250 && split > 200, "{checked} pixels checked, {split} split by light");
    }

    #[test]
    fn gouraud_explains_a_pixel_by_its_vertices_and_weights() {
        let mut scene = scene_of(PLANE);
        scene.spec.settings.interpolation = Interpolation::Gouraud;
        let r = &explain_pixels(&scene, &[(10, 20)]).expect("inside")[0];
        let s = r.surface.as_ref().expect("the plane");
        assert_eq!(s.lit_by, LitBy::Vertices);
        assert_eq!(s.vertices.len(), 3);
        let weights: f32 = s.vertices.iter().map(|v| v.weight).sum();
        assert!((weights - 1.0).abs() < 1e-5, "{weights}");
        let interpolated: Vec3 = s.vertices.iter().map(|v| v.total * v.weight).sum();
        assert!((interpolated - r.sample).abs().max_element() < 1e-5, "{interpolated:?} vs {:?}", r.sample);
    }

    /// Lesson 37's captions, as its pixels measure them.
    #[test]
    fn lesson_37s_captions_are_what_its_pixels_say() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/37-one-pixel.toml");
        let lesson = crate::lesson::load(&path, &[]).expect("lesson 37");
        let scene = crate::scene::build::build(&lesson).expect("a scene");
        let r = explain_pixels(&scene, &[(115, 136), (224, 138), (185, 180), (350, 103)]).expect("inside");
        let s: Vec<&SurfaceReport> = r.iter().map(|r| r.surface.as_ref().expect("a surface")).collect();
        let y = |v: Vec3| v.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        // 1, 2: the specular term is most of each highlight's peak (0.57 of 0.81, 0.44 of 0.72).
        for (k, (spec, total)) in [(0.5708, 0.8096), (0.4416, 0.7161)].into_iter().enumerate() {
            let (sp, t) = (y(s[k].lights[0].terms.specular), y(s[k].recomputed.total()));
            assert!((sp - spec).abs() < 5e-4 && (t - total).abs() < 5e-4 && sp / t > 0.6, "{k}: {sp} of {t}");
        }
        assert!(s[0].lights[0].r_dot_v > 0.9997 && s[1].lights[0].n_dot_h > 0.9998);
        // The two highlights cover about the same area: pixels above half their peak specular.
        // The key light's highlights alone (the rim light puts its own on the balls' top edges).
        let mut key_only = scene.clone();
        key_only.lights[1].radiance = Vec3::ZERO;
        key_only.lights[1].specular = Vec3::ZERO;
        let (frame, _) = render(&key_only, &[Layer::Specular]);
        let area = |x0: u32, x1: u32| {
            let v: Vec<f32> =
                (x0..x1).flat_map(|x| (60..220).map(move |yy| (x, yy))).map(|(x, yy)| y(frame.at(Layer::Specular, x, yy))).collect();
            let peak = v.iter().cloned().fold(0.0, f32::max);
            v.iter().filter(|&&a| a >= peak / 2.0).count()
        };
        let (phong, blinn) = (area(60, 185), area(185, 300));
        assert!((100..130).contains(&phong) && (95..120).contains(&blinn), "{phong} and {blinn} pixels");
        // 3: the key light blocked by the first ball; the rim light and the ambient term remain.
        let key = &s[2].lights[0];
        assert_eq!((key.visibility, key.occluder, key.terms.diffuse), (0.0, Some(0), Vec3::ZERO));
        assert!((y(s[2].lights[1].terms.diffuse) - 0.0896).abs() < 5e-4 && (y(s[2].global_ambient) - 0.027).abs() < 1e-4);
        // 4: F at the glaze's edge under the rim light against the key light's, near normal incidence.
        let f = |l: &LightReport| y(l.brdf.and_then(|b| b.dgf).expect("Cook-Torrance").2);
        assert!(
            (f(&s[3].lights[1]) - 0.356).abs() < 2e-3 && (f(&s[3].lights[0]) - 0.0403).abs() < 5e-4,
            "{} {}",
            f(&s[3].lights[1]),
            f(&s[3].lights[0])
        );
        // The `gouraud` figure: the same peak lit at the vertices keeps 0.26 of its 0.44.
        let mut g = scene.clone();
        g.spec.settings.interpolation = Interpolation::Gouraud;
        let r = &explain_pixels(&g, &[(224, 138)]).expect("inside")[0];
        let gs = r.surface.as_ref().expect("the ball");
        assert!((y(gs.lights[0].terms.specular) - 0.2629).abs() < 5e-4, "{:?}", gs.lights[0].terms.specular);
        let w: Vec<f32> = gs.vertices.iter().map(|v| v.weight).collect();
        assert!((w[0] - 0.6347).abs() < 1e-3 && (w[1] - 0.3303).abs() < 1e-3 && (w[2] - 0.035).abs() < 1e-3, "{w:?}");
        // And the floor's shadow is lost between its vertices: the shadowed point above is lit.
        let floor = &explain_pixels(&g, &[(185, 180)]).expect("inside")[0];
        assert!(y(floor.sample) > 1.5 * y(s[2].recomputed.total()), "{:?}", floor.sample);
    }
}
