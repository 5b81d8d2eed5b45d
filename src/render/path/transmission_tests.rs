//! The principled material's transmission in the path tracer against closed forms: its
//! specular transmission is rough glass, Beer-Lambert absorption through a ball's centre,
//! diffuse transmission through a backlit sheet, and the same bits on any thread count.

use super::tests::{assert_same_on_one_thread_and_four, furnace, scene};
use crate::render::frame::Layer;
use glam::Vec3;
use std::path::Path;

/// The raw totals of `text`'s render.
fn totals(text: &str) -> Vec<Vec3> {
    let (frame, _) = crate::render::render(&scene(text), &[Layer::Total]);
    frame.raw(Layer::Total).unwrap().to_vec()
}

/// A white principled material that is all specular transmission is the rough glass of
/// its roughness and ior, to the bit: the same boundary, tint 1 and random numbers.
#[test]
fn full_specular_transmission_is_rough_glass_to_the_bit() {
    let glass = totals(&furnace("model = \"glass\"\nior = 1.5\nroughness = 0.3", 8));
    let principled = totals(&furnace("model = \"principled\"\nbase_color = 1\nspecular_transmission = 1\nior = 1.5\nroughness = 0.3", 8));
    assert!(glass.iter().any(|c| c.x > 0.5), "the sphere is drawn");
    assert_eq!(glass, principled);
}

/// Through a ball's centre in a uniform environment of 1, a nearly smooth boundary (α =
/// 0.0025) sends F back and (1 − F)² T/(1 − F T) through, summing the internal reflections,
/// with F = 0.04 at normal incidence (η = 1.5) and T = T_c at a diameter of d_T.
#[test]
fn absorption_follows_beer_lambert_through_the_centre() {
    let text = furnace(
        "model = \"principled\"\nbase_color = 1\nspecular_transmission = 1\nroughness = 0.05\n\
         transmittance_color = [0.5, 0.25, 0.9]\ntransmittance_distance = 2",
        256,
    )
    .replace("size = [24, 24]", "size = [16, 16]\nfov_deg = 8");
    let t = totals(&text);
    // The centre 4 × 4: the rays cross within 0.04 of the centre (a path of at least 1.998).
    let centre = (6..10).flat_map(|y| (6..10).map(move |x| (x, y))).map(|(x, y)| t[y * 16 + x]).sum::<Vec3>() / 16.0;
    let f = 0.04f32;
    let want = Vec3::new(0.5, 0.25, 0.9).map(|tc| f + (1.0 - f) * (1.0 - f) * tc / (1.0 - f * tc));
    eprintln!("centre {centre:?} against {want:?}");
    assert!(((centre - want) / want).abs().max_element() < 0.01, "{centre:?} against {want:?}");
    // Without absorption the same ball returns all of it.
    let clear = totals(&text.replace("transmittance_distance = 2", ""));
    let c = (6..10).flat_map(|y| (6..10).map(move |x| (x, y))).map(|(x, y)| clear[y * 16 + x]).sum::<Vec3>() / 16.0;
    assert!((c - Vec3::ONE).abs().max_element() < 0.01, "{c:?}");
}

/// A sheet lit from behind by a directional light E = 2 at normal incidence shows
/// d_t (1 − metallic) C/π · E on its unlit face, exactly (one light sample, no noise), and
/// nothing at all without diffuse transmission.
#[test]
fn a_backlit_sheet_shows_its_diffuse_transmission() {
    let sheet = |dt: f32| {
        format!(
            "[camera]\nposition = [0, 0, 3]\nsize = [8, 8]\nfov_deg = 20\n[[object]]\nshape = \"plane\"\nrotate_deg = [90, 0, 0]\n\
             material = \"m\"\n[material.m]\nmodel = \"principled\"\nbase_color = [0.6, 0.3, 0.1]\nmetallic = 0.25\n\
             diffuse_transmission = {dt}\n[[light]]\nkind = \"directional\"\ndirection = [0, 0, 1]\nintensity = 2\n\
             [render]\nmethod = \"path\"\nspp = 1\nmax_depth = 2\n"
        )
    };
    let lit = totals(&sheet(0.5));
    let want = Vec3::new(0.6, 0.3, 0.1) * (0.5 * 0.75 * 2.0 / std::f32::consts::PI);
    for c in &lit {
        assert!((*c - want).abs().max_element() < 1e-5, "{c:?} against {want:?}");
    }
    assert!(totals(&sheet(0.0)).iter().all(|c| *c == Vec3::ZERO));
}

/// Transmission draws the same bits on one thread and on four (its part choice is hashed).
#[test]
fn transmission_is_the_same_on_one_thread_and_four() {
    let text = furnace(
        "model = \"principled\"\nbase_color = [0.8, 0.5, 0.3]\nspecular_transmission = 0.6\ndiffuse_transmission = 0.3\n\
         roughness = 0.3\ntransmittance_color = [0.9, 0.6, 0.3]\ntransmittance_distance = 1",
        4,
    );
    assert_same_on_one_thread_and_four(&scene(&text));
}

/// The rasterizer and radiosity refuse a material that lets light through, at its key.
#[test]
fn only_the_path_tracer_draws_transmission() {
    for (key, m) in [("specular_transmission", "specular_transmission = 0.5"), ("diffuse_transmission", "diffuse_transmission = 0.2")] {
        let text = furnace(&format!("model = \"principled\"\n{m}"), 4).replace("method = \"path\"", "method = \"raster\"");
        let lesson = crate::lesson::parse(&text, Path::new("t.toml"), &[]).unwrap();
        let e = crate::scene::build::build(&lesson).expect_err("refused").to_string();
        assert!(e.contains(&format!("material.m.{key}")) && e.contains("only method = \"path\" draws"), "{e}");
    }
}
