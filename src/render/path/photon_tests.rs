//! The global photon map and its final gather against closed forms and the path tracer, the
//! point light's caustic against a small sphere light's, and determinism.

use super::tests::{assert_same_on_one_thread_and_four, scene};
use crate::render::frame::Layer;
use crate::scene::Scene;
use glam::Vec3;

fn total(s: &Scene) -> Vec<Vec3> {
    crate::render::render(s, &[Layer::Total]).0.raw(Layer::Total).unwrap().to_vec()
}

/// The inside of a closed diffuse sphere of radius 1 and albedo ρ with a point light of
/// intensity I at its centre, seen from near the centre.
fn closed_sphere(rho: f32, render: &str) -> Scene {
    scene(&format!(
        "[camera]\nposition = [0, 0, 0.05]\nlook_at = [0, 0, -1]\nfov_deg = 60\nsize = [24, 24]\n\
         [[object]]\nshape = \"uv_sphere\"\nsegments = 128\nrings = 64\nmaterial = \"wall\"\n\
         [material.wall]\nmodel = \"diffuse\"\ndiffuse = {rho}\n\
         [[light]]\nkind = \"point\"\nposition = [0, 0, 0]\nintensity = 2\n\
         [render]\nmethod = \"path\"\ncull = \"none\"\nmax_depth = 32\n{render}\n"
    ))
}

/// In a closed sphere lit from its centre, every wall point has direct irradiance
/// E_d = I / R² and radiosity B = ρ (E_d + B), so L = ρ E_d / (π (1 − ρ)) (Cohen and Wallace
/// 1993, the furnace's geometric series). The global map read through a final gather and
/// read directly (its indirect photons only) both give it within 3%, as the path tracer does.
#[test]
fn the_global_map_gives_the_closed_spheres_radiance() {
    let rho = 0.5;
    let expected = rho * 2.0 / (std::f32::consts::PI * (1.0 - rho));
    let photons = "caustics = \"photons\"\nindirect = \"photons\"\nglobal_photons = 200000\nglobal_radius = 0.1\n";
    for (name, render) in [
        ("path tracer", "spp = 64\n".to_string()),
        ("final gather", format!("spp = 4\n{photons}gather_rays = 16\n")),
        ("direct visualisation", format!("spp = 4\n{photons}gather_rays = 0\n")),
        ("final gather, 50 nearest", format!("spp = 4\n{photons}gather_rays = 16\nphoton_gather = \"nearest\"\nphoton_nearest = 50\n")),
    ] {
        let img = total(&closed_sphere(rho, &render));
        assert!(img.iter().all(|v| v.is_finite() && v.min_element() >= 0.0), "{name}: a NaN or negative pixel");
        let mean = img.iter().map(|v| v.x).sum::<f32>() / img.len() as f32;
        eprintln!("{name}: {mean} against {expected}");
        assert!((mean / expected - 1.0).abs() < 0.03, "{name}: {mean} against {expected}");
    }
    // Local illumination alone is the direct term ρ E_d / π: half of it at ρ = 0.5.
    let img = total(&closed_sphere(rho, "spp = 4\nindirect = \"none\"\n"));
    let mean = img.iter().map(|v| v.x).sum::<f32>() / img.len() as f32;
    assert!((mean / (expected * (1.0 - rho)) - 1.0).abs() < 0.02, "local: {mean}");
}

/// A glass ball over a floor, lit from above by `light`.
fn ball(light: &str, render: &str) -> Scene {
    scene(&format!(
        "[camera]\nposition = [0, 3, 3]\nlook_at = [0, 0.3, 0]\nfov_deg = 40\nsize = [48, 48]\n\
         [[object]]\nshape = \"uv_sphere\"\nsegments = 64\nrings = 32\nscale = 0.6\ntranslate = [0, 0.6, 0]\nmaterial = \"glass\"\n\
         [[object]]\nshape = \"plane\"\nscale = 4\nmaterial = \"floor\"\n\
         [material.glass]\nmodel = \"glass\"\nior = 1.5\n[material.floor]\nmodel = \"diffuse\"\ndiffuse = 0.7\n\
         [[light]]\n{light}\n[render]\nmethod = \"path\"\nspp = 16\nphotons = 400000\nphoton_radius = 0.04\n{render}\n"
    ))
}

/// A point light's caustic: the path tracer cannot find it (a point is never hit), the photon
/// map finds it, and it matches a sphere light of radius 0.02 and the same power (Φ = 4π I =
/// 4π² r² L) traced the same way within 5%: the point is that sphere's limit as r → 0.
#[test]
fn a_point_lights_caustic_comes_from_photons_and_matches_a_small_spheres() {
    let (i, r) = (3.0f32, 0.02f32);
    let point = format!("kind = \"point\"\nposition = [0.3, 2.2, -0.2]\nintensity = {i}");
    let sphere_l = i / (std::f32::consts::PI * r * r);
    let sphere = format!("kind = \"sphere\"\nposition = [0.3, 2.2, -0.2]\nradius = {r}\nintensity = {sphere_l}");
    let pt = total(&ball(&point, "caustics = \"path\""));
    let ph = total(&ball(&point, "caustics = \"photons\""));
    let sp = total(&ball(&sphere, "caustics = \"photons\""));
    let y = |v: &Vec3| v.element_sum() / 3.0;
    // The caustic: pixels the photons make 2 times brighter than the path tracer's direct light.
    let caustic: Vec<usize> = (0..ph.len()).filter(|&k| y(&ph[k]) > 2.0 * y(&pt[k]) + 0.05).collect();
    assert!(caustic.len() >= 8, "{} caustic pixels", caustic.len());
    let mean = |img: &[Vec3]| caustic.iter().map(|&k| y(&img[k])).sum::<f32>() / caustic.len() as f32;
    let (m_pt, m_ph, m_sp) = (mean(&pt), mean(&ph), mean(&sp));
    eprintln!("{} caustic pixels: path {m_pt}, point photons {m_ph}, sphere photons {m_sp}", caustic.len());
    assert!(m_ph > 3.0 * m_pt, "the caustic is not there: {m_ph} against {m_pt}");
    assert!((m_ph / m_sp - 1.0).abs() < 0.05, "point {m_ph} against sphere {m_sp}");
    assert!(ph.iter().chain(&sp).all(|v| v.is_finite()));
}

/// A spot light sends photons within its cone only: with no falloff (L_exp = 0) its caustic
/// is the point light's inside the cone within 5%, and a spot pointing up lights nothing.
#[test]
fn a_spots_photons_follow_its_cone() {
    let spot = |direction: &str| {
        format!("kind = \"spot\"\nposition = [0.3, 2.2, -0.2]\ndirection = {direction}\nexponent = 0\ncutoff_deg = 30\nintensity = 3")
    };
    let point = total(&ball("kind = \"point\"\nposition = [0.3, 2.2, -0.2]\nintensity = 3", "caustics = \"photons\""));
    // A 30° cone about the ball's centre (the ball spans 21.5° from the lamp), and one upwards.
    let wide = total(&ball(&spot("[-0.3, -1.6, 0.2]"), "caustics = \"photons\""));
    let up = total(&ball(&spot("[0, 1, 0]"), "caustics = \"photons\""));
    let y = |v: &Vec3| v.element_sum() / 3.0;
    // The caustic under the ball (on the cone's axis): the same for the point and the 30° spot.
    let centre: Vec<usize> = (0..point.len()).filter(|&k| y(&point[k]) > 1.0).collect();
    assert!(centre.len() >= 4, "{} bright pixels", centre.len());
    let mean = |img: &[Vec3]| centre.iter().map(|&k| y(&img[k])).sum::<f32>() / centre.len() as f32;
    assert!((mean(&wide) / mean(&point) - 1.0).abs() < 0.05, "spot {} against point {}", mean(&wide), mean(&point));
    // Upwards, nothing reaches the floor: no photon leaves the cone.
    assert_eq!(mean(&up), 0.0);
}

#[test]
fn the_global_map_and_final_gather_are_the_same_on_one_thread_and_four() {
    assert_same_on_one_thread_and_four(&closed_sphere(
        0.5,
        "spp = 2\ncaustics = \"photons\"\nindirect = \"photons\"\nglobal_photons = 20000\ngather_rays = 4\nphoton_gather = \"nearest\"\n",
    ));
}
