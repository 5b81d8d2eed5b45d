//! The path tracer against closed forms and the raster renderer: the white furnace, the
//! direct-light equality at `max_depth = 2`, single scattering in the medium, the phase
//! sampler's mean cosine, and determinism across thread counts.

use crate::render::frame::Layer;
use crate::scene::Scene;
use crate::shading::brdf::Brdf;
use crate::transport::path::sample_henyey_greenstein;
use glam::Vec3;
use std::path::Path;

pub(super) fn scene(text: &str) -> Scene {
    crate::scene::build::build(&crate::lesson::parse(text, Path::new("t.toml"), &[]).unwrap()).unwrap()
}

/// The mean total over the covered pixels (and the covered count).
fn covered_mean(scene: &Scene) -> (Vec3, usize) {
    let (frame, _) = crate::render::render(scene, &[Layer::Total]);
    let total = frame.raw(Layer::Total).unwrap();
    let mut sum = Vec3::ZERO;
    let mut n = 0;
    for (px, c) in total.iter().zip(&frame.coverage) {
        if *c == 1.0 {
            sum += *px;
            n += 1;
        }
    }
    (sum / n.max(1) as f32, n)
}

/// A unit sphere filling most of a 24² image inside a uniform environment of radiance 1.
pub(super) fn furnace(material: &str, spp: u32) -> String {
    format!(
        "[camera]\nposition = [0, 0, 3.2]\nsize = [24, 24]\n[[object]]\nshape = \"uv_sphere\"\nsegments = 48\nrings = 24\nmaterial = \"m\"\n\
         [material.m]\n{material}\n[environment]\nkind = \"gradient\"\nzenith = 1\nhorizon = 1\nground = 1\nbackground = false\n\
         [render]\nmethod = \"path\"\nspp = {spp}\nmax_depth = 64\n"
    )
}

/// The white furnace: inside a uniform environment L = 1, a material that reflects (and
/// transmits) everything returns exactly 1 at every pixel, whatever the path length; the
/// others never return more than 1 (no energy gain).
#[test]
fn the_white_furnace_returns_what_falls_in_and_never_more() {
    // Lossless: every path escapes with weight 1 (the sphere is convex, so diffuse paths
    // leave after one bounce; glass paths after any number of interface events).
    for (name, m) in [
        ("diffuse ρ = 1", "model = \"diffuse\"\ndiffuse = 1"),
        ("mirror", "model = \"mirror\""),
        ("glass η = 1.5", "model = \"glass\"\nior = 1.5"),
    ] {
        let (mean, n) = covered_mean(&scene(&furnace(m, 16)));
        assert!(n > 250, "{name}: {n} covered pixels");
        eprintln!("{name}: {mean:?}");
        assert!((mean - Vec3::ONE).abs().max_element() < 0.01, "{name}: {mean:?} against 1");
    }
    // Every other model: a convex sphere returns each path after one bounce, so each pixel
    // is the BRDF's directional albedo ρ(v) = ∫ f cos dω at its view angle, and the tracer adds
    // nothing to it. (Disney's diffuse is not energy-conserving: its albedo reaches 1.04 at
    // 60° for a white rough base, and the furnace shows exactly that.)
    for (name, m) in [
        ("GGX α = 0.3, no Fresnel, ρ = 0", "model = \"cook_torrance\"\ndiffuse = 0\nspecular = 1\nfresnel = \"none\"\nalpha = 0.3"),
        ("Oren-Nayar σ = 40°", "model = \"oren_nayar\"\ndiffuse = 1\nsigma_deg = 40"),
        ("principled, white, rough", "model = \"principled\"\nbase_color = 1\nroughness = 0.6"),
        ("principled metal", "model = \"principled\"\nbase_color = 1\nmetallic = 1\nroughness = 0.3"),
        ("normalized Blinn-Phong", "model = \"normalized_blinn_phong\"\ndiffuse = 0.5\nspecular = 0.5\nshininess = 50"),
    ] {
        let s = scene(&furnace(m, 32));
        let (mean, n) = covered_mean(&s);
        let brdf = *s.materials[0].brdf().unwrap();
        let want = albedo_seen(&s, &brdf);
        eprintln!("{name}: {:.4} against the albedo {:.4}", mean.x, want.x);
        assert!(n > 250 && ((mean - want) / want).abs().max_element() < 0.01, "{name}: {mean:?} against the albedo {want:?}");
    }
}

/// The mean over the fully covered pixels of the furnace image of the directional albedo at
/// each pixel centre's view angle (the sphere's normal there against the way to the eye).
fn albedo_seen(s: &Scene, brdf: &Brdf) -> Vec3 {
    let (frame, _) = crate::render::render(s, &[Layer::Total]);
    let rays = s.spec.camera.rays();
    let mut sum = glam::DVec3::ZERO;
    let mut n = 0;
    let mut cache = std::collections::HashMap::new();
    for (i, c) in frame.coverage.iter().enumerate() {
        if *c < 1.0 {
            continue;
        }
        let (x, y) = (i as u32 % frame.width, i as u32 / frame.width);
        let ray = rays.ray((x, y), (0, 0), 1);
        let (o, d) = (ray.origin.as_vec3(), ray.dir.as_vec3().normalize());
        // The unit sphere at the origin: the nearer root of |o + t d|² = 1.
        let b = o.dot(d);
        let t = -b - (b * b - o.length_squared() + 1.0).max(0.0).sqrt();
        let cos = (o + d * t).normalize().dot(-d).clamp(0.0, 1.0);
        let key = (cos * 200.0).round() as i32;
        let a = *cache.entry(key).or_insert_with(|| crate::shading::brdf::directional_albedo_rgb(brdf, key as f64 / 200.0, 12).0);
        sum += a;
        n += 1;
    }
    (sum / n.max(1) as f64).as_vec3()
}

/// A ball on a floor lit by a point light, a rect light and a sky: path traced with
/// `max_depth = 2` (direct light only) equals the raster render with ray-cast shadows.
#[test]
fn depth_two_is_the_raster_renders_direct_light() {
    let base = "[camera]\nposition = [0, 2.2, 5]\nlook_at = [0, 0.6, 0]\nsize = [48, 36]\n\
        [[object]]\nshape = \"uv_sphere\"\nsegments = 64\nrings = 32\ntranslate = [0, 1, 0]\nmaterial = \"ball\"\n\
        [[object]]\nshape = \"plane\"\nscale = 6\nmaterial = \"floor\"\n\
        [material.ball]\nmodel = \"cook_torrance\"\ndiffuse = [0.6, 0.3, 0.2]\nspecular = 1\nalpha = 0.2\n\
        [material.floor]\nmodel = \"diffuse\"\ndiffuse = 0.7\n\
        [[light]]\nkind = \"point\"\nposition = [2, 4, 2]\nintensity = 20\n\
        [[light]]\nkind = \"rect\"\nposition = [-2, 3, 1]\ndirection = [1, -1.5, -0.5]\nsize = [1, 1]\nintensity = 6\nsamples = 256\n\
        [[light]]\nkind = \"sky\"\nintensity = 0.2\nground_color = 0.25\nsamples = 256\n";
    let raster = covered_mean(&scene(&format!("{base}[render]\naa = 4\n"))).0;
    let path = covered_mean(&scene(&format!("{base}[render]\naa = 2\nmethod = \"path\"\nspp = 64\nmax_depth = 2\n"))).0;
    let rel = ((path - raster) / raster).abs().max_element();
    eprintln!("direct light: path {path:?} raster {raster:?} ({:.2} %)", rel * 100.0);
    assert!(rel < 0.01, "path {path:?} against raster {raster:?} ({:.2} %)", rel * 100.0);
    // And region by region: the floor's shadow and the ball's highlight are where they should be.
    let frame = |t: &str| crate::render::render(&scene(t), &[Layer::Total]).0;
    let (r, p) = (
        frame(&format!("{base}[render]\naa = 4\n")),
        frame(&format!("{base}[render]\naa = 2\nmethod = \"path\"\nspp = 64\nmax_depth = 2\n")),
    );
    let (rt, pt) = (r.raw(Layer::Total).unwrap(), p.raw(Layer::Total).unwrap());
    for ry in 0..3 {
        for rx in 0..4 {
            let (mut a, mut b) = (0.0, 0.0);
            for y in ry * 12..(ry + 1) * 12 {
                for x in rx * 12..(rx + 1) * 12 {
                    a += rt[y * 48 + x].element_sum();
                    b += pt[y * 48 + x].element_sum();
                }
            }
            // Regions of background only are 0 in both.
            assert!((a == 0.0 && b == 0.0) || (b / a - 1.0).abs() < 0.05, "region ({rx}, {ry}): path {b} raster {a}");
        }
    }
}

/// Every other physically based model under every other light kind: spot, directional, disk,
/// sphere and line lights, and the environment (against the rasterizer's Monte Carlo IBL with
/// the scene's visibility), `max_depth = 2` against the raster render, image mean.
#[test]
fn depth_two_matches_the_raster_for_every_model_and_light_kind() {
    let scene_with = |material: &str, extra: &str| {
        format!(
            "[camera]\nposition = [0, 2.2, 5]\nlook_at = [0, 0.6, 0]\nsize = [40, 30]\n\
             [[object]]\nshape = \"uv_sphere\"\nsegments = 64\nrings = 32\ntranslate = [0, 1, 0]\nmaterial = \"ball\"\n\
             [[object]]\nshape = \"plane\"\nscale = 6\nmaterial = \"floor\"\n\
             [material.ball]\n{material}\n[material.floor]\nmodel = \"oren_nayar\"\ndiffuse = 0.6\nsigma_deg = 30\n{extra}"
        )
    };
    let lights = "[[light]]\nkind = \"spot\"\nposition = [1, 4, 1]\ndirection = [-0.2, -1, -0.2]\ncutoff_deg = 35\nexponent = 4\nintensity = 25\n\
        [[light]]\nkind = \"directional\"\ndirection = [1, -1, -0.5]\nintensity = 0.8\n\
        [[light]]\nkind = \"disk\"\nposition = [-2, 3, 1]\ndirection = [1, -1.5, -0.5]\nradius = 0.5\nintensity = 6\nsamples = 256\n\
        [[light]]\nkind = \"sphere\"\nposition = [2, 2.5, -1]\nradius = 0.3\nintensity = 10\nsamples = 256\n\
        [[light]]\nkind = \"line\"\nstart = [-1.5, 3, 2]\nend = [1.5, 3, 2]\nradius = 0.05\nintensity = 8\nsamples = 256\n";
    let env = "[environment]\nkind = \"gradient\"\nzenith = [0.3, 0.4, 0.6]\nhorizon = [0.6, 0.6, 0.6]\nground = 0.1\nbackground = false\n";
    for (name, material) in [
        ("principled", "model = \"principled\"\nbase_color = [0.7, 0.4, 0.2]\nroughness = 0.4\nclearcoat = 0.5\nsheen = 0.3"),
        ("principled metal", "model = \"principled\"\nbase_color = [0.9, 0.6, 0.3]\nmetallic = 1\nroughness = 0.35"),
        ("normalized Phong", "model = \"normalized_phong\"\ndiffuse = 0.4\nspecular = 0.3\nshininess = 40"),
        ("Beckmann", "model = \"cook_torrance\"\nndf = \"beckmann\"\ndiffuse = 0.3\nspecular = 1\nalpha = 0.3"),
    ] {
        for (what, extra, raster_render) in
            [("lights", lights, "[render]\naa = 4\n"), ("environment", env, "[render]\naa = 4\nibl = \"reference\"\nenv_samples = 256\n")]
        {
            let raster = covered_mean(&scene(&format!("{}{raster_render}", scene_with(material, extra)))).0;
            let path = covered_mean(&scene(&format!(
                "{}[render]\naa = 2\nmethod = \"path\"\nspp = 64\nmax_depth = 2\n",
                scene_with(material, extra)
            )))
            .0;
            let rel = ((path - raster) / raster).abs().max_element();
            eprintln!("{name}, {what}: {:.2} %", rel * 100.0);
            assert!(rel < 0.015, "{name}, {what}: path {path:?} against raster {raster:?} ({:.2} %)", rel * 100.0);
        }
    }
}

/// Glass: the path tracer's stochastic Fresnel choice against the rasterizer's traced glass
/// (both branches followed, up to 16 interface events; its closed-form sphere path is tested
/// in `transport::glass`), a glass ball in a gradient environment, image mean and regions.
#[test]
fn glass_matches_the_rasterizers_traced_glass() {
    let base = "[camera]\nposition = [0, 0, 3.2]\nsize = [32, 32]\n\
        [[object]]\nshape = \"uv_sphere\"\nsegments = 96\nrings = 48\nmaterial = \"glass\"\n\
        [material.glass]\nmodel = \"glass\"\nior = 1.5\n\
        [environment]\nkind = \"gradient\"\nzenith = [0.2, 0.5, 1.0]\nhorizon = 1\nground = [0.3, 0.15, 0.05]\nbackground = false\n";
    let raster = covered_mean(&scene(&format!("{base}[render]\naa = 4\nmax_bounces = 16\n"))).0;
    let path = covered_mean(&scene(&format!("{base}[render]\naa = 2\nmethod = \"path\"\nspp = 64\nmax_depth = 17\n"))).0;
    let rel = ((path - raster) / raster).abs().max_element();
    eprintln!("glass: path {path:?} raster {raster:?} ({:.2} %)", rel * 100.0);
    assert!(rel < 0.01, "glass: path {path:?} against raster {raster:?} ({:.2} %)", rel * 100.0);
}

/// In the medium, `max_depth = 2` is single scattering: the raster's march (uniform steps,
/// many) and the path tracer's free flights with next-event estimation agree.
#[test]
fn depth_two_in_the_medium_is_the_single_scattering_march() {
    let base = "[camera]\nposition = [0, 1, 6]\nlook_at = [0, 1, 0]\nsize = [32, 24]\nbackground = 0.02\n\
        [[object]]\nshape = \"plane\"\nscale = 8\nmaterial = \"floor\"\n\
        [material.floor]\nmodel = \"diffuse\"\ndiffuse = 0.5\n\
        [[light]]\nkind = \"point\"\nposition = [0, 2.5, 0]\nintensity = 12\n";
    let fog = "[fog]\nkind = \"medium\"\nsigma_s = 0.15\nsigma_a = 0.05\ng = 0.3\nsteps = 256\n";
    let raster = covered_mean(&scene(&format!("{base}{fog}[render]\naa = 2\n"))).0;
    let path = covered_mean(&scene(&format!("{base}{fog}[render]\naa = 2\nmethod = \"path\"\nspp = 256\nmax_depth = 2\n"))).0;
    let rel = ((path - raster) / raster).abs().max_element();
    eprintln!("single scattering: path {path:?} march {raster:?} ({:.2} %)", rel * 100.0);
    assert!(rel < 0.02, "path {path:?} against the march {raster:?} ({:.2} %)", rel * 100.0);
    // Multiple scattering only adds light.
    let multiple = covered_mean(&scene(&format!("{base}{fog}[render]\naa = 2\nmethod = \"path\"\nspp = 64\nmax_depth = 16\n"))).0;
    assert!(multiple.min_element() > path.max_element(), "{multiple:?} against single {path:?}");
}

/// The furnace in fog: a medium that scatters everything (σ_a = 0) under a sky and a ground of
/// radiance 1, the camera's background 1: every path ends in light of radiance 1 with weight
/// 1, however often it scatters, so every pixel is 1 (the sky reaches the medium only by the
/// phase's samples that escape, and nothing is counted twice).
#[test]
fn the_furnace_in_fog_returns_one_for_any_scattering() {
    for g in [0.0, 0.6] {
        let text = format!(
            "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nsize = [16, 16]\nbackground = 1\n\
             [[light]]\nkind = \"sky\"\nground_color = 1\n\
             [fog]\nkind = \"medium\"\nsigma_s = 0.2\nsigma_a = 0\ng = {g}\n\
             [render]\nmethod = \"path\"\nspp = 16\nmax_depth = 64\n"
        );
        let (mean, n) = covered_mean(&scene(&text));
        eprintln!("fog furnace, g = {g}: {mean:?} over {n} pixels");
        assert!(n == 256 && (mean - Vec3::ONE).abs().max_element() < 0.01, "g = {g}: {mean:?} over {n} pixels");
    }
}

/// max_depth = 1 sees only emitters: a lit diffuse ball is black, an emitting one shows L_emi.
#[test]
fn depth_one_sees_only_emitters() {
    let text = |emission: &str| {
        format!(
            "[camera]\nposition = [0, 0, 3.2]\nsize = [16, 16]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n\
             [material.m]\nmodel = \"diffuse\"\ndiffuse = 0.8\n{emission}\n[[light]]\nkind = \"point\"\nposition = [0, 0, 4]\nintensity = 10\n\
             [render]\nmethod = \"path\"\nspp = 4\nmax_depth = 1\n"
        )
    };
    assert_eq!(covered_mean(&scene(&text(""))).0, Vec3::ZERO);
    let (lit, _) = covered_mean(&scene(&text("emission = [0.5, 0.25, 0.125]")));
    assert!((lit - Vec3::new(0.5, 0.25, 0.125)).abs().max_element() < 1e-6, "{lit:?}");
}

/// The phase sampler draws μ = l·d with the Henyey-Greenstein mean ⟨μ⟩ = g, and its pdf
/// (the phase) integrates to 1 over the histogram of what it draws.
#[test]
fn henyey_greenstein_samples_have_mean_cosine_g() {
    let d = Vec3::new(0.3, -0.5, 0.81).normalize();
    for g in [-0.7f32, 0.0, 0.3, 0.9] {
        let n = 20000;
        let mean: f64 =
            (0..n).map(|k| sample_henyey_greenstein(d, g, crate::geometry::sobol::sobol_2d(k, 7)).dot(d) as f64).sum::<f64>() / n as f64;
        assert!((mean - g as f64).abs() < 0.01, "g {g}: mean cosine {mean}");
    }
}

/// The same bytes on one thread and on four.
#[test]
fn the_same_image_on_one_thread_and_four() {
    let text = furnace("model = \"principled\"\nbase_color = [0.8, 0.4, 0.2]\nroughness = 0.4", 4);
    assert_same_on_one_thread_and_four(&scene(&text));
}

/// Asserts that `s` renders to the same bits on one thread and on four.
pub(super) fn assert_same_on_one_thread_and_four(s: &Scene) {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| crate::render::render(s, &[Layer::Total]).0)
    };
    let bits =
        |f: &crate::render::Frame| f.raw(Layer::Total).unwrap().iter().flat_map(|v| v.to_array().map(f32::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(&run(1)), bits(&run(4)));
}

/// Bad input is refused before any work: out-of-range keys and a classic material.
#[test]
fn out_of_range_keys_and_classic_materials_are_refused() {
    let base = "[camera]\nposition = [0, 0, 3]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[material.m]\n";
    let parse = |t: &str| crate::lesson::parse(t, Path::new("t.toml"), &[]);
    for bad in ["spp = 0", "max_depth = 0", "max_depth = 1000"] {
        let e = parse(&format!("{base}model = \"diffuse\"\n[render]\nmethod = \"path\"\n{bad}\n")).unwrap_err().to_string();
        assert!(e.contains("out of range"), "{bad}: {e}");
    }
    let lesson = parse(&format!("{base}model = \"phong\"\n[render]\nmethod = \"path\"\n")).unwrap();
    let e = crate::scene::build::build(&lesson).unwrap_err().to_string();
    assert!(e.contains("t.toml:7:") && e.contains("`phong`") && e.contains("normalized_phong"), "{e}");
}

/// Lesson 44's scene, small: a glass ball focusing a softbox onto the floor.
fn caustic_scene(caustics: &str, spp: u32) -> Scene {
    scene(&format!(
        "[camera]\nposition = [0, 3, 3]\nlook_at = [0, 0.3, 0]\nfov_deg = 40\nsize = [40, 40]\n\
         [[object]]\nshape = \"uv_sphere\"\nsegments = 64\nrings = 32\nscale = 0.6\ntranslate = [0, 0.6, 0]\nmaterial = \"glass\"\n\
         [[object]]\nshape = \"plane\"\nscale = 4\nmaterial = \"floor\"\n\
         [material.glass]\nmodel = \"glass\"\nior = 1.5\n[material.floor]\nmodel = \"diffuse\"\ndiffuse = 0.7\n\
         [[light]]\nkind = \"rect\"\nposition = [0, 2, -2]\ndirection = [0, -0.57, 0.82]\nsize = [0.5, 0.5]\nintensity = 12\n\
         [render]\nmethod = \"path\"\nspp = {spp}\ncaustics = \"{caustics}\"\nphotons = 400000\nphoton_radius = 0.03\n"
    ))
}

/// The photon map holds the caustic the path tracer finds by chance: at 16 paths a pixel
/// its caustic is within 10% of a 2048-path reference on average and far less noisy than the
/// path tracer's own at 16, and it changes nothing else (the image outside within 2%).
#[test]
fn the_photon_caustic_matches_the_path_tracer_and_is_smoother() {
    let total = |s: &Scene| crate::render::render(s, &[Layer::Total]).0.raw(Layer::Total).unwrap().to_vec();
    let reference = total(&caustic_scene("path", 2048));
    let photons = total(&caustic_scene("photons", 16));
    let path = total(&caustic_scene("path", 16));
    let y = |v: &Vec3| v.element_sum() / 3.0;
    // The open floor's level, far from the ball, and the caustic: 3 times brighter or more.
    let floor = y(&reference[38 * 40 + 2]);
    let caustic: Vec<usize> = (0..reference.len()).filter(|&i| y(&reference[i]) > 3.0 * floor).collect();
    assert!(caustic.len() >= 12, "{} caustic pixels, floor {floor}", caustic.len());
    let mean = |img: &[Vec3], px: &[usize]| px.iter().map(|&i| y(&img[i])).sum::<f32>() / px.len() as f32;
    let rmse =
        |img: &[Vec3], px: &[usize]| (px.iter().map(|&i| (y(&img[i]) - y(&reference[i])).powi(2)).sum::<f32>() / px.len() as f32).sqrt();
    let (m_ref, m_ph) = (mean(&reference, &caustic), mean(&photons, &caustic));
    assert!((m_ph / m_ref - 1.0).abs() < 0.10, "caustic {m_ph} against {m_ref}");
    let (e_ph, e_pt) = (rmse(&photons, &caustic), rmse(&path, &caustic));
    assert!(e_ph < 0.5 * e_pt, "caustic RMSE: photons {e_ph}, path {e_pt}");
    let rest: Vec<usize> = (0..reference.len()).filter(|i| !caustic.contains(i)).collect();
    let (r_ref, r_ph) = (mean(&reference, &rest), mean(&photons, &rest));
    assert!((r_ph / r_ref - 1.0).abs() < 0.02, "elsewhere {r_ph} against {r_ref}");
    eprintln!("caustic {m_ph} / {m_ref}, RMSE {e_ph} against {e_pt}; elsewhere {r_ph} / {r_ref}");
}

#[test]
fn the_photon_map_is_the_same_on_one_thread_and_four() {
    assert_same_on_one_thread_and_four(&caustic_scene("photons", 2));
}

/// Rough glass in the white furnace against Mitsuba 3.9.1's `roughdielectric`
/// (`tools/mitsuba_rough_glass.py`: a unit sphere, η = 1.5, a constant environment of 1,
/// depth 64, 512 independent samples, the centre 12 × 12 of 32²): 0.9852 at α = 0.09 and
/// 0.7872 at α = 0.36. Single-scattering microfacets lose the light meant for a second facet,
/// and a lamp seen straight through the glass's own inside would add light that is not
/// there (it came out 0.834 at α = 0.36 before next-event estimation kept to the outside).
#[test]
fn rough_glass_in_the_furnace_matches_mitsuba() {
    for (roughness, mitsuba) in [(0.3f32, 0.9852f32), (0.6, 0.7872)] {
        let text = format!(
            "[camera]\nposition = [0, 0, 3.2]\nfov_deg = 40\nsize = [32, 32]\n[[object]]\nshape = \"uv_sphere\"\nsegments = 128\nrings = 64\n\
             material = \"m\"\n[material.m]\nmodel = \"glass\"\nior = 1.5\nroughness = {roughness}\n[environment]\nkind = \"gradient\"\n\
             zenith = 1\nhorizon = 1\nground = 1\n[render]\nmethod = \"path\"\nspp = 512\nmax_depth = 64\n"
        );
        let (frame, _) = crate::render::render(&scene(&text), &[Layer::Total]);
        let total = frame.raw(Layer::Total).unwrap();
        let centre: f32 = (10..22).flat_map(|y| (10..22).map(move |x| (x, y))).map(|(x, y)| total[y * 32 + x].x).sum::<f32>() / 144.0;
        eprintln!("roughness {roughness}: {centre} against Mitsuba's {mitsuba}");
        assert!((centre / mitsuba - 1.0).abs() < 0.01, "roughness {roughness}: {centre} against Mitsuba's {mitsuba}");
    }
}

/// Rough glass is drawn by the path tracer only: the rasterizer refuses it at its key.
#[test]
fn the_rasterizer_refuses_rough_glass_at_its_key() {
    let text = furnace("model = \"glass\"\nroughness = 0.3", 4).replace("method = \"path\"", "method = \"raster\"");
    let lesson = crate::lesson::parse(&text, Path::new("t.toml"), &[]).unwrap();
    let e = crate::scene::build::build(&lesson).expect_err("refused").to_string();
    assert!(e.contains("material.m.roughness") && e.contains("only method = \"path\" draws"), "{e}");
}

/// The furnace with random-walk subsurface scattering: a white walk (α = 1) leaves a closed
/// sphere with all it took in, so each pixel is 1 + the albedo of the surface part the
/// principled material keeps (its specular, `subsurface_radius` aside), measured the same way.
#[test]
fn the_subsurface_walk_in_the_furnace_returns_what_falls_in() {
    let walk = "model = \"principled\"\nbase_color = 1\nroughness = 0.5\nsubsurface = 1\nsubsurface_radius = [1, 0.6, 0.3]\nsubsurface_scale = 0.5";
    let s = scene(&furnace(walk, 64));
    let (mean, n) = covered_mean(&s);
    let Some(Brdf::Principled(p)) = s.materials[0].brdf().copied() else { panic!() };
    let kept = Brdf::Principled(crate::shading::principled::Principled { base_color: Vec3::ZERO, subsurface: 0.0, ..p });
    let want = Vec3::ONE + albedo_seen(&s, &kept);
    eprintln!("walk: {mean:?} against 1 + the surface part's albedo {want:?}");
    assert!(n > 250 && ((mean - want) / want).abs().max_element() < 0.01, "{mean:?} against {want:?}");
}

/// With subsurface = 0 the radius changes nothing: the same bits as without it.
#[test]
fn no_subsurface_weight_is_the_opaque_surface_bit_for_bit() {
    let plain = "model = \"principled\"\nbase_color = [0.8, 0.4, 0.2]\nroughness = 0.4";
    let with = format!("{plain}\nsubsurface_radius = [1, 0.2, 0.1]\nsubsurface_scale = 0.3");
    let bits = |text: &str| {
        let (f, _) = crate::render::render(&scene(&furnace(text, 4)), &[Layer::Total]);
        f.raw(Layer::Total).unwrap().iter().flat_map(|v| v.to_array().map(f32::to_bits)).collect::<Vec<_>>()
    };
    assert_eq!(bits(plain), bits(&with));
}

#[test]
fn the_subsurface_walk_is_the_same_on_one_thread_and_four() {
    let text = furnace(
        "model = \"principled\"\nbase_color = [0.8, 0.4, 0.3]\nsubsurface = 0.7\nsubsurface_radius = [1, 0.2, 0.1]\nsubsurface_scale = 0.4",
        4,
    );
    assert_same_on_one_thread_and_four(&scene(&text));
}

/// A radius far below the rays' offset, or far beyond the object, and a black base: finite
/// pixels, never above the furnace's 1 + the surface part (a little, for the specular).
#[test]
fn tiny_and_huge_radii_give_finite_pixels() {
    for (radius, color) in [("0.000001", "1"), ("10000", "1"), ("0.3", "0"), ("[0, 0.2, 0]", "[0.9, 0.5, 0.1]")] {
        let m = format!("model = \"principled\"\nbase_color = {color}\nsubsurface = 1\nsubsurface_radius = {radius}");
        let (frame, _) = crate::render::render(&scene(&furnace(&m, 8)), &[Layer::Total]);
        let total = frame.raw(Layer::Total).unwrap();
        let (mean, n) = covered_mean(&scene(&furnace(&m, 8)));
        eprintln!("radius {radius}, colour {color}: {mean:?} over {n} pixels");
        assert!(total.iter().all(|v| v.is_finite() && v.min_element() >= 0.0), "radius {radius}");
        assert!(mean.max_element() < 1.1, "radius {radius}: {mean:?}");
    }
}

/// `subsurface_radius` is refused where no walk can read it: a negative value, a material that
/// is not principled, a metal.
#[test]
fn bad_subsurface_keys_are_refused() {
    let base = "[camera]\nposition = [0, 0, 3]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[material.m]\n";
    let parse = |t: &str| crate::lesson::parse(&format!("{base}{t}\n"), Path::new("t.toml"), &[]).map(|_| ()).unwrap_err().to_string();
    let e = parse("model = \"principled\"\nsubsurface = 1\nsubsurface_radius = [1, -0.2, 0.1]");
    assert!(e.contains("t.toml:9:") && e.contains("out of range"), "{e}");
    let e = parse("model = \"principled\"\nsubsurface_scale = -1");
    assert!(e.contains("t.toml:8:") && e.contains("out of range"), "{e}");
    let e = parse("model = \"diffuse\"\nsubsurface_radius = 1");
    assert!(e.contains("subsurface_radius"), "{e}");
    let e = parse("model = \"principled\"\nmetallic = 1\nsubsurface = 1\nsubsurface_radius = 1");
    assert!(e.contains("t.toml:10:") && e.contains("metal"), "{e}");
}
