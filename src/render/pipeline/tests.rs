//! The pipeline against itself: lane widths, reused visibility, the plan's passes.

use super::*;
use crate::lesson::Override;
use crate::lesson::Tonemap;
use crate::render::frame::Layer;
use crate::scene::Scene;
use crate::transport::visibility::{SHADOW_MAP_LOOKUPS, SHADOW_RAYS};
use std::cell::Cell;
use std::path::Path;

thread_local! {
    /// Set by a test: renders started on this thread shade in at most this many lanes.
    pub(super) static MAX_LANES: Cell<usize> = const { Cell::new(16) };
    /// Whether the strips gather triangles' rests across triangles (`gather.rs`).
    pub(super) static GATHER: Cell<bool> = const { Cell::new(true) };
}

/// Two objects (a classic and a physically based material), four kinds of light, a floor
/// seen at a grazing angle and a sphere crossing the near plane's neighbourhood.
const LESSON: &str = r#"
[lesson]
title = "lanes"
[camera]
position = [0.0, 1.2, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 50
size = [96, 72]
[[object]]
shape = "plane"
scale = 4
material = "floor"
[[object]]
shape = "uv_sphere"
segments = 40
rings = 20
scale = 0.8
translate = [0.3, 0.6, 0.0]
material = "plastic"
[[object]]
shape = "torus"
scale = 0.5
translate = [-1.0, 0.4, 0.8]
material = "metal"
[material.floor]
model = "phong"
diffuse = 0.6
specular = 0.3
shininess = 12.5
[material.plastic]
model = "blinn_phong"
diffuse = [0.7, 0.3, 0.05]
specular = 0.5
shininess = 40
[material.metal]
model = "cook_torrance"
alpha = 0.3
[[light]]
kind = "directional"
direction = [-1.0, -1.0, -0.5]
[[light]]
kind = "point"
position = [1.0, 1.5, 1.0]
attenuation = [1, 0.2, 0.1]
[[light]]
kind = "spot"
position = [0.0, 3.0, 0.0]
direction = [0.0, -1.0, 0.0]
exponent = 8
cutoff_deg = 40
[[light]]
kind = "ambient"
intensity = 0.1
[scene]
ambient = 0.05
"#;

pub(super) fn scene(overrides: &[&str]) -> Scene {
    let o: Vec<Override> = overrides.iter().map(|s| Override::parse(s).expect("override")).collect();
    let lesson = crate::lesson::parse(LESSON, Path::new("lanes.toml"), &o).expect("valid lesson");
    crate::scene::build::build(&lesson).expect("built-in meshes")
}

/// Every layer as bits, and the 8-bit images (ACES, and AgX, which mixes the channels).
fn render_bits(scene: &Scene, lanes: usize) -> (Vec<Vec<u32>>, [Vec<u8>; 2], RenderStats) {
    MAX_LANES.with(|f| f.set(lanes));
    let (frame, stats) = render(scene, &Layer::ALL);
    let image = [Tonemap::Aces, Tonemap::Agx].map(|op| render_image(scene, Layer::Total, 0.0, op).0);
    MAX_LANES.with(|f| f.set(16));
    let layers = frame.layers.iter().map(|(_, v)| v.iter().flat_map(|c| c.to_array().map(f32::to_bits)).collect()).collect();
    (layers, image, stats)
}

#[test]
#[cfg(target_arch = "x86_64")]
fn eight_lanes_give_the_bits_of_four() {
    if crate::simd::Cpu::get().avx().is_none() {
        crate::simd::cpu::missing(crate::simd::Level::Avx, "AVX");
        return;
    }
    let sixteen = crate::simd::Cpu::get().avx512().is_some();
    if !sixteen {
        crate::simd::cpu::missing(crate::simd::Level::Avx512, "AVX-512 (sixteen lanes)");
    }
    for overrides in [
        &[][..],
        &["render.interpolation=\"gouraud\""],
        &["render.interpolation=\"flat\""],
        &["render.cull=\"none\"", "render.aa=2"],
        &["camera.position=[0.0, 0.3, 0.9]", "render.cull=\"none\""],
    ] {
        let s = scene(overrides);
        let (four, eight) = (render_bits(&s, 4), render_bits(&s, 8));
        assert!(four.2.samples_shaded > 1000, "{overrides:?}");
        assert_eq!(four, eight, "{overrides:?}");
        if sixteen {
            assert_eq!(four, render_bits(&s, 16), "sixteen lanes: {overrides:?}");
        }
    }
}

/// A plain render's 8-bit image (one sample a pixel, developed as it is shaded) is the same
/// whether its pixels are encoded with the table, eight AVX2 lanes into 3-byte pixels, or
/// sixteen AVX-512 lanes into the 4-byte strip, whatever the tone map, with background
/// pixels left by every path.
#[test]
fn every_encode_width_gives_the_table_s_image() {
    use crate::render::develop::MAX_ENCODE_LANES;
    for overrides in [&[][..], &["render.interpolation=\"gouraud\"", "camera.position=[0.0, 2.5, 4.0]"]] {
        let s = scene(overrides);
        for op in [Tonemap::Clamp, Tonemap::Aces, Tonemap::Agx] {
            let image = |lanes: usize| {
                MAX_ENCODE_LANES.with(|f| f.set(lanes));
                let (image, stats) = render_image(&s, Layer::Total, 0.5, op);
                MAX_ENCODE_LANES.with(|f| f.set(16));
                (image, stats.nan_samples)
            };
            let table = image(1);
            let background =
                crate::render::develop::DevelopParams::new(Layer::Total, 0.5, op, 3, false, s.spec.camera.background).empty_rgb();
            let pixels: Vec<&[u8]> = table.0.chunks(3).collect();
            assert!(pixels.contains(&&background[..]), "{overrides:?}: some background");
            assert!(pixels.iter().filter(|p| **p != background).count() > 1000, "{overrides:?}: covered pixels");
            assert_eq!(image(8), table, "{overrides:?} {op:?}: eight lanes");
            assert_eq!(image(16), table, "{overrides:?} {op:?}: sixteen lanes");
        }
    }
}

/// Triangles' rests gathered across triangles into full bundles (`gather.rs`) give every
/// layer, the 8-bit image and the counts bit for bit as each triangle's own bundles do: with
/// two classic materials taking turns in the strips (each change shades the partial bundle
/// waiting), term layers kept, two-sided lighting, 4 × 4 samples a pixel, and the tiny
/// triangles of a fine sphere. (Switching gathering off must change nothing but the path:
/// a lane lost or moved in the queue changes a layer or a count.)
#[test]
fn gathered_rests_give_the_bits_of_per_triangle_bundles() {
    let render_with = |s: &Scene, gather: bool, lanes: usize| {
        GATHER.with(|g| g.set(gather));
        let bits = render_bits(s, lanes);
        GATHER.with(|g| g.set(true));
        bits
    };
    // Plain lighting, shadow rays (each lane's ray skips its own triangle: a lane given
    // another's would shadow itself) and shadow maps.
    for overrides in [
        &["render.shadows=\"none\""][..],
        &["render.shadows=\"none\"", "render.cull=\"none\"", "render.aa=4"],
        &["render.shadows=\"none\"", "object.1.segments=400", "object.1.rings=200"],
        &["object.1.segments=400", "object.1.rings=200"],
        &["render.shadows=\"map\"", "render.cull=\"none\""],
    ] {
        let s = scene(overrides);
        for lanes in [4, 8, 16] {
            let (apart, gathered) = (render_with(&s, false, lanes), render_with(&s, true, lanes));
            assert!(apart.2.samples_shaded > 1000 && apart.2.specular_evaluations > 1000, "{overrides:?}");
            assert_eq!(
                apart.2.count(SHADOW_RAYS) + apart.2.count(SHADOW_MAP_LOOKUPS) > 0,
                !overrides.contains(&"render.shadows=\"none\""),
                "{overrides:?}"
            );
            assert_eq!(apart, gathered, "{overrides:?}, {lanes} lanes");
        }
    }
}

/// The pipeline runs exactly the passes the plan lists (what `explain` prints), for each
/// interpolation, with a reused visibility buffer and with nothing to draw.
#[test]
fn the_passes_that_run_are_the_plans() {
    use super::super::plan::{Pass, plan};
    let fogs = ["", "fog={ kind = \"exp\", density = 0.2 }", "fog={ kind = \"medium\", sigma_s = 0.1, steps = 4 }"];
    for (interpolation, fog) in ["flat", "gouraud", "phong"].into_iter().flat_map(|i| fogs.map(|f| (i, f))) {
        let interp = format!("render.interpolation=\"{interpolation}\"");
        let s = scene(&if fog.is_empty() { vec![interp.as_str()] } else { vec![interp.as_str(), fog] });
        let (fresh, st) = render(&s, &[Layer::Total]);
        let p = plan(&s);
        assert_eq!(st.passes, p.running_bits(), "{interpolation} {fog}");
        assert_eq!(st.passes & Pass::Fog.bit() != 0, !fog.is_empty(), "{interpolation} {fog}");
        let lighting = match interpolation {
            "flat" => Pass::LightFaces,
            "gouraud" => Pass::LightVertices,
            _ => Pass::ShadeSamples,
        };
        let others = [Pass::LightFaces, Pass::LightVertices, Pass::ShadeSamples].into_iter().filter(|p| *p != lighting);
        assert!(st.passes & lighting.bit() != 0 && others.clone().all(|p| st.passes & p.bit() == 0), "{interpolation}");
        // Shading a kept visibility buffer again: the vertex stage ran when it was made.
        let (kept, again) = render_with(&s, &[Layer::Total], Some(&rasterize(&s)));
        assert_eq!(again.passes, p.running_bits() & !Pass::VertexStage.bit());
        // Fog reads the kept buffer's depths: the same frame.
        assert_eq!(fresh, kept, "{interpolation} {fog}");
    }
    // Fog with nothing to draw: every sample is fog, fully covered.
    let text = "[camera]\nposition = [0, 0, 4]\nsize = [8, 8]\n[fog]\nkind = \"linear\"\nend = 5\ncolor = 0.3\n";
    let foggy = crate::scene::build::build(&crate::lesson::parse(text, Path::new("f.toml"), &[]).unwrap()).unwrap();
    let (frame, st) = render(&foggy, &[Layer::Total]);
    assert_eq!(st.passes, Pass::Fog.bit() | Pass::Resolve.bit());
    assert!(frame.coverage.iter().all(|&c| c == 1.0) && frame.raw(Layer::Total).unwrap().iter().all(|&c| c == glam::Vec3::splat(0.3)));
    // A lesson without objects has no vertex stage, raster or per-sample lighting, only the resolve.
    let text = "[camera]\nposition = [0, 0, 4]\nsize = [8, 8]\n";
    let empty = crate::scene::build::build(&crate::lesson::parse(text, Path::new("e.toml"), &[]).unwrap()).unwrap();
    let (frame, st) = render(&empty, &[Layer::Total]);
    assert_eq!(st.passes, Pass::Resolve.bit());
    assert_eq!(plan(&empty).running().collect::<Vec<_>>(), [Pass::Resolve]);
    assert!(frame.coverage.iter().all(|&c| c == 0.0));
}

#[test]
fn a_reused_visibility_buffer_gives_the_bits_of_a_render() {
    let s = scene(&["render.aa=2"]);
    let vis = rasterize(&s);
    let (fresh, _) = render(&s, &Layer::ALL);
    let (reused, stats) = render_with(&s, &Layer::ALL, Some(&vis));
    assert!(stats.samples_shaded > 1000);
    for ((_, a), (_, b)) in fresh.layers.iter().zip(&reused.layers) {
        assert!(a.iter().zip(b).all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)));
    }
    assert_eq!(fresh.coverage, reused.coverage);
}

/// A floor of two triangles under a point light, seen as `camera` says.
fn floor(camera: &str, overrides: &[&str]) -> Scene {
    let text = format!(
        "[camera]\n{camera}\nsize = [64, 48]\n[[object]]\nshape = \"plane\"\nscale = 10\n{}material = \"floor\"\n\
         [material.floor]\nmodel = \"phong\"\ndiffuse = 0.6\nspecular = 0.5\nshininess = 20\n\
         [[light]]\nkind = \"point\"\nposition = [0.0, 0.5, 6.0]\n",
        if camera.contains("facing") { "rotate_deg = [90.0, 0.0, 0.0]\n" } else { "" }
    );
    let o: Vec<Override> = overrides.iter().map(|s| Override::parse(s).expect("override")).collect();
    crate::scene::build::build(&crate::lesson::parse(&text, Path::new("floor.toml"), &o).expect("valid lesson")).expect("a plane")
}

/// The largest difference of I_tot between two renders, and the covered samples.
fn largest_difference(a: &Scene, b: &Scene) -> (f32, usize) {
    let ((fa, _), (fb, _)) = (render(a, &[Layer::Total]), render(b, &[Layer::Total]));
    let (ta, tb) = (&fa.layers[0].1, &fb.layers[0].1);
    let covered = fa.coverage.iter().filter(|&&c| c > 0.0).count();
    (ta.iter().zip(tb).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0, f32::max), covered)
}

#[test]
fn screen_space_interpolation_differs_on_a_slanted_floor_and_agrees_on_one_facing_the_camera() {
    let screen = "render.interpolation_space=\"screen\"";
    // Gouraud's vertex colours are all dim (the corners are far from the light): a smaller
    // difference, still hundreds of times rounding.
    for (interpolation, least) in [("render.interpolation=\"phong\"", 0.2), ("render.interpolation=\"gouraud\"", 2e-3)] {
        // Seen at a steep angle, w varies across each triangle: the weights differ.
        let slanted = "position = [0.0, 1.5, 13.0]\nlook_at = [0.0, 0.0, 4.0]";
        let (d, covered) = largest_difference(&floor(slanted, &[interpolation]), &floor(slanted, &[interpolation, screen]));
        assert!(covered > 1000 && d > least, "{interpolation}: {d} over {covered} samples");
        // The floor turned to face the camera, square on: w is the same at every vertex,
        // so the screen-space weights are the perspective-correct ones, to rounding.
        let facing = "position = [0.0, 0.0, 8.0]\nlook_at = [0.0, 0.0, 0.0] # facing";
        let (d, covered) = largest_difference(&floor(facing, &[interpolation]), &floor(facing, &[interpolation, screen]));
        assert!(covered > 1000 && d < 1e-5, "{interpolation}: {d} over {covered} samples");
    }
    // A reused visibility buffer holds the screen-space weights too.
    let s = floor("position = [0.0, 1.5, 13.0]\nlook_at = [0.0, 0.0, 4.0]", &[screen]);
    let (fresh, _) = render(&s, &[Layer::Total]);
    let (reused, _) = render_with(&s, &[Layer::Total], Some(&rasterize(&s)));
    assert_eq!(fresh.layers[0].1, reused.layers[0].1);
    assert!(!same_raster(&s, &floor("position = [0.0, 1.5, 13.0]\nlook_at = [0.0, 0.0, 4.0]", &[])));
}
