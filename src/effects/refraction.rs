//! Refraction: whether a scene needs the glass pass, and what the pass prepares.
//!
//! Which light paths it counts (the header promise of DESIGN.md): at every `glass` surface
//! a ray meets, the Fresnel share F of the light arriving along the reflected direction
//! r = 2(n·v)n − v and 1 − F (× `tint`) along the refracted direction t (Snell), each ray
//! followed through the scene's BVH to the next surface or the environment. Every
//! reflection or refraction at a glass surface is one *bounce*; a path may have at most
//! `[render] max_bounces` of them (default 8), and a ray that would need one more brings
//! no light. So for a glass sphere seen from outside:
//!
//! | `max_bounces` | paths counted |
//! | --- | --- |
//! | 1 | the Fresnel reflection at entry only (the refracted ray's exit would be bounce 2) |
//! | 2 | + the twice-refracted ray (in, out): the paths of the course's figure and of an independent reference that stops there |
//! | 3 | + one internal reflection (in, reflect, out) |
//! | k | + k − 2 internal reflections |
//!
//! A `thin` surface is one interface: the refracted ray goes on without meeting its own
//! object again (the course's "surface only"). Surfaces that are not glass, seen along a
//! glass ray, are shaded as the camera would see them (mirrors go on reflecting, up to
//! `MAX_MIRROR_DEPTH`). Glass meeting glass (touching objects) is not modelled: each
//! interface is glass against air. Radiosity sees glass as black (ρ = 0), as it sees mirrors.

use crate::scene::{Model, Scene};

/// Whether the refraction pass is needed for `scene`, and why: some drawn object is glass.
pub fn needed(scene: &Scene) -> (bool, String) {
    let g = &scene.geometry;
    let used = |m: usize| g.objects.iter().any(|o| o.material as usize == m && o.triangles > 0);
    let glass: Vec<String> = scene
        .materials
        .iter()
        .enumerate()
        .filter(|(i, _)| used(*i))
        .filter_map(|(_, m)| match &m.model {
            Model::Glass(gl) => {
                let ior = if gl.disperses() {
                    format!("η = [{}, {}, {}], one path per channel", gl.ior.x, gl.ior.y, gl.ior.z)
                } else {
                    format!("η = {}", gl.ior.x)
                };
                Some(format!("`{}` ({ior}{})", m.name, if gl.thin { ", thin" } else { "" }))
            }
            _ => None,
        })
        .collect();
    if glass.is_empty() {
        return (false, "no glass material is drawn".into());
    }
    let b = scene.spec.settings.max_bounces;
    (
        true,
        format!(
            "glass {}: Fresnel-weighted reflected and refracted rays through the scene's BVH, up to {b} bounce{} a path (max_bounces)",
            glass.join(", "),
            if b == 1 { "" } else { "s" }
        ),
    )
}
