//! The probe capture pass (`Pass::ProbeCapture`): each `[[probe]]` rendered into its six
//! cube faces by this very pipeline, from the scene without its mirrors
//! ([`effects::probe::capture_scene`](crate::effects::probe::capture_scene)). It lives in
//! `render` because it renders; what a probe is and how mirrors read it are in `effects::probe`.

use crate::effects::probe::{ProbeMap, capture_scene, face_camera, orient};
use crate::render::frame::Layer;
use crate::render::pipeline::render;
use crate::scene::Scene;
use crate::scene::cube::CubeFaces;

/// The count of cube-map texels the probe capture rendered (six faces of size² per probe).
pub const PROBE_TEXELS: &str = "probe capture: cube-map texels rendered";

/// Every probe of `scene`, captured (six renders each, in `scene::cube::FACE_NAMES` order).
pub fn capture(scene: &Scene) -> Vec<ProbeMap> {
    let mut s = capture_scene(scene);
    scene
        .spec
        .probes
        .iter()
        .map(|spec| {
            let faces = std::array::from_fn(|k| {
                let (camera, flip) = face_camera(spec, k, scene.spec.camera.near, scene.spec.camera.background);
                s.spec.camera = camera;
                let (frame, _) = render(&s, &[Layer::Total]);
                orient(frame.layer(Layer::Total).expect("the total was kept"), spec.size, flip)
            });
            ProbeMap { spec: *spec, faces: CubeFaces { size: spec.size, faces } }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use std::path::Path;

    /// A closed room [−2, 2] × [0, 3] × [−2, 2], each wall emitting its own colour, with a
    /// small emitting cube near the +x wall, high and towards +z; a mirror ball round the probe.
    const ROOM: &str = r#"
[camera]
position = [0, 1.5, 1.5]
look_at = [0, 1.5, 0]
size = [16, 16]
[render]
reflections = "probe_box"
[[probe]]
position = [0, 1.5, 0]
size = 32
box_min = [-2, 0, -2]
box_max = [2, 3, 2]
[[object]]
shape = "uv_sphere"
scale = 0.5
translate = [0, 1.5, 0]
material = "chrome"
[material.chrome]
model = "mirror"
[material.px]
model = "lambert"
diffuse = 0
emission = [1, 0, 0]
[material.nx]
model = "lambert"
diffuse = 0
emission = [0, 1, 0]
[material.py]
model = "lambert"
diffuse = 0
emission = [0, 0, 1]
[material.ny]
model = "lambert"
diffuse = 0
emission = [1, 1, 0]
[material.pz]
model = "lambert"
diffuse = 0
emission = [0, 1, 1]
[material.nz]
model = "lambert"
diffuse = 0
emission = [1, 0, 1]
[material.spot]
model = "lambert"
diffuse = 0
emission = [1, 1, 1]
[[object]]
shape = "plane"
scale = [3, 1, 3]
rotate_deg = [0, 0, 90]
translate = [2, 1.5, 0]
material = "px"
[[object]]
shape = "plane"
scale = [3, 1, 3]
rotate_deg = [0, 0, -90]
translate = [-2, 1.5, 0]
material = "nx"
[[object]]
shape = "plane"
scale = [3, 1, 3]
rotate_deg = [180, 0, 0]
translate = [0, 3, 0]
material = "py"
[[object]]
shape = "plane"
scale = [3, 1, 3]
material = "ny"
[[object]]
shape = "plane"
scale = [3, 1, 3]
rotate_deg = [-90, 0, 0]
translate = [0, 1.5, 2]
material = "pz"
[[object]]
shape = "plane"
scale = [3, 1, 3]
rotate_deg = [90, 0, 0]
translate = [0, 1.5, -2]
material = "nz"
[[object]]
shape = "cube"
scale = 0.2
translate = [1.7, 2.4, 0.9]
material = "spot"
"#;

    fn room() -> Scene {
        crate::scene::build::build(&crate::lesson::parse(ROOM, Path::new("t.toml"), &[]).unwrap()).unwrap()
    }

    #[test]
    fn each_wall_appears_in_its_own_face_and_in_the_right_place_within_it() {
        let scene = room();
        let probes = capture(&scene);
        let faces = &probes[0].faces;
        let c = probes[0].spec.position;
        let colours = [Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 1.0), Vec3::new(1.0, 0.0, 1.0)];
        for (k, colour) in colours.iter().enumerate() {
            // The centre texels of face k: its own wall (the mirror ball is left out of the capture).
            let n = faces.size as usize;
            let centre = faces.faces[k][(n / 2) * n + n / 2];
            assert!((centre - *colour).abs().max_element() < 1e-5, "face {k}: {centre} instead of {colour}");
        }
        // The small cube: looked at through the map along the direction from C to its centre,
        // and the +x wall beside it (mirrored top-bottom and left-right: not the cube).
        let to_cube = Vec3::new(1.7, 2.4, 0.9) - c;
        assert!((faces.sample(to_cube) - Vec3::ONE).abs().max_element() < 1e-5, "{}", faces.sample(to_cube));
        for wrong in [Vec3::new(1.7, 0.6, 0.9), Vec3::new(1.7, 2.4, -0.9), Vec3::new(1.7, 0.6, -0.9)] {
            assert!((faces.sample(wrong - c) - Vec3::X).abs().max_element() < 1e-5, "{wrong}: {}", faces.sample(wrong - c));
        }
    }

    #[test]
    fn box_projection_reads_what_the_traced_ray_hits_on_the_walls() {
        use crate::effects::probe::Probes;
        use crate::lesson::settings::Reflections;
        // The room is exactly the probe's box: for every point and direction, the
        // box-projected lookup reads the wall the traced ray hits (same colour), away from
        // the walls' edges and the cube (a texel apart there).
        let scene = room();
        let maps = capture(&scene);
        let probes = Probes { maps, reflections: Reflections::ProbeBox };
        let naive = Probes { reflections: Reflections::Probe, ..probes.clone() };
        let bvh = crate::transport::SceneRays::build(&capture_scene(&scene));
        let (mut same, mut naive_same, mut n) = (0, 0, 0);
        for i in 0..4000u32 {
            let h = |k: u32| crate::geometry::sampling::hash3(i, k, 0x51ed) as f32 / u32::MAX as f32;
            let x = Vec3::new(-1.8 + 3.6 * h(1), 0.2 + 2.6 * h(2), -1.8 + 3.6 * h(3));
            let (z, phi) = (2.0 * h(4) - 1.0, std::f32::consts::TAU * h(5));
            let s = (1.0 - z * z).sqrt();
            let r = Vec3::new(s * phi.cos(), z, s * phi.sin());
            let origin = crate::transport::Origin { p: x, ng: r, tri: u32::MAX, object: u32::MAX };
            let Some(hit) = bvh.closest(&origin, r) else { continue };
            let p = x + hit.t * r;
            // Skip hits within 0.25 of a wall's edge, or where the small cube (dilated by
            // 0.25) stands between C and the hit: there the map's texels blend two surfaces.
            let near_edge = (0..3).filter(|&a| (p[a] - B_MIN[a]).abs() < 0.25 || (p[a] - B_MAX[a]).abs() < 0.25).count() > 1;
            let c = probes.maps[0].spec.position;
            let shadowed = (0..=64).any(|j| (c + (p - c) * (j as f32 / 64.0) - CUBE).abs().max_element() < 0.45);
            if near_edge || shadowed {
                continue;
            }
            let traced = wall_colour(p);
            n += 1;
            same += ((probes.radiance(x, r).unwrap() - traced).abs().max_element() < 1e-5) as u32;
            naive_same += ((naive.radiance(x, r).unwrap() - traced).abs().max_element() < 1e-5) as u32;
        }
        assert!(n > 2000, "{n} rays");
        assert_eq!(same, n, "box projection: {same} of {n} rays read the traced wall");
        // Naive reads the wrong wall for many of them (the parallax the box corrects).
        assert!(naive_same < n * 9 / 10, "naive: {naive_same} of {n}");
    }

    const B_MIN: Vec3 = Vec3::new(-2.0, 0.0, -2.0);
    const B_MAX: Vec3 = Vec3::new(2.0, 3.0, 2.0);
    const CUBE: Vec3 = Vec3::new(1.7, 2.4, 0.9);

    /// The colour of the wall holding `p` (on the box's surface).
    fn wall_colour(p: Vec3) -> Vec3 {
        let d = [(2.0 - p.x).abs(), (p.x + 2.0).abs(), (3.0 - p.y).abs(), p.y.abs(), (2.0 - p.z).abs(), (p.z + 2.0).abs()];
        let k = (0..6).min_by(|a, b| d[*a].total_cmp(&d[*b])).unwrap();
        [Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 1.0), Vec3::new(1.0, 0.0, 1.0)][k]
    }
}
