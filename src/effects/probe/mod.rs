//! Reflection probes: a cube map rendered from a point, read by mirrors instead of tracing
//! their reflected ray (`[render] reflections = "probe"` or `"probe_box"`).
//!
//! **Capture** ([`Pass::ProbeCapture`](crate::render::plan::Pass::ProbeCapture)): the scene
//! is rendered by the project's own rasterizer from the probe's `position` into six square
//! 90° faces, oriented as OpenGL's cube-map table (`scene::cube`). The probe sees the scene
//! *without its mirrors* ([`capture_scene`]): a mirror would otherwise appear in its own
//! reflection (a sphere round the probe hides everything), and a probe that saw mirrors would
//! need itself to shade them. Where a face sees nothing it records what a traced mirror ray
//! would: the environment (drawn as background in the capture) or the camera's background.
//! The render pipeline runs the capture (`render::probe`): effects sit below render.
//!
//! **Lookup** ([`Probes::radiance`]): a mirror point x inside a probe's box (the first such
//! probe in file order) reads the map along R (naive: the scene treated as infinitely far)
//! or along the box-projected R′ = P − C ([`crate::geometry::box_projection`]), or as a
//! probe moved to C′ (`moved_to`) reads it: along s′ = P − C, P where R from C′ leaves the
//! box, the same lookup for every point of the mirror as a probe at C′ would give. A point in
//! no probe's box traces its ray as before.

use crate::geometry::Camera;
use crate::geometry::box_projection::{box_project, moved_project};
use crate::lesson::probe::ProbeSpec;
use crate::lesson::settings::Reflections;
use crate::scene::build::Geometry;
use crate::scene::cube::CubeFaces;
use crate::scene::{Model, Scene};
use glam::Vec3;

/// Each face's axis A, and the directions S, T that its columns and rows run along
/// (d = A + sc S + tc T), in `scene::cube::FACE_NAMES` order: OpenGL's table inverted.
pub const FACE_BASIS: [[Vec3; 3]; 6] = [
    [Vec3::X, Vec3::NEG_Z, Vec3::NEG_Y],
    [Vec3::NEG_X, Vec3::Z, Vec3::NEG_Y],
    [Vec3::Y, Vec3::X, Vec3::Z],
    [Vec3::NEG_Y, Vec3::X, Vec3::NEG_Z],
    [Vec3::Z, Vec3::X, Vec3::NEG_Y],
    [Vec3::NEG_Z, Vec3::NEG_X, Vec3::NEG_Y],
];

/// One captured probe.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeMap {
    /// Where it was captured and its box.
    pub spec: ProbeSpec,
    /// Its six faces.
    pub faces: CubeFaces,
}

/// The captured probes and how mirrors read them.
#[derive(Debug, Clone, PartialEq)]
pub struct Probes {
    /// The probes, in file order.
    pub maps: Vec<ProbeMap>,
    /// `probe` (naive) or `probe_box` (box-projected).
    pub reflections: Reflections,
}

impl Probes {
    /// Radiance arriving at `x` along the unit reflected direction `r`, from the first probe
    /// whose box holds `x`; `None` when no box does (the caller traces the ray). A projector
    /// needs the traced surface ([`Probes::projected`]); without it, this reads along `r`.
    pub fn radiance(&self, x: Vec3, r: Vec3) -> Option<Vec3> {
        let m = self.maps.iter().find(|m| holds(&m.spec, x))?;
        if self.reflections == Reflections::ProbeProjector {
            return Some(m.faces.sample(r));
        }
        let d = match self.reflections {
            Reflections::ProbeBox => box_project(x, r, m.spec.position, m.spec.box_min, m.spec.box_max),
            Reflections::ProbeMoved => moved_project(r, m.spec.position, m.spec.moved_to, m.spec.box_min, m.spec.box_max),
            _ => r,
        };
        Some(m.faces.sample(d))
    }
}

impl Probes {
    /// The probe as a light projector (`probe_projector`): radiance arriving at the mirror
    /// point `x` along `r` from the surface point `hit` the traced ray found, read from the
    /// capture along s = hit − C; along `r` when the ray left the scene (`hit` = `None`: the
    /// capture recorded the environment there). `None` when no probe's box holds `x`.
    pub fn projected(&self, x: Vec3, hit: Option<Vec3>, r: Vec3) -> Option<Vec3> {
        let m = self.maps.iter().find(|m| holds(&m.spec, x))?;
        let s = hit.map(|p| p - m.spec.position).filter(|s| s.is_finite() && s.length_squared() > 0.0).unwrap_or(r);
        Some(m.faces.sample(s))
    }
}

/// True when `x` is in the probe's box, give or take rounding (1e-4 of the box's size): a
/// mirror lying on a wall of the box counts as inside.
fn holds(p: &ProbeSpec, x: Vec3) -> bool {
    let slack = (p.box_max - p.box_min) * 1e-4;
    x.cmpge(p.box_min - slack).all() && x.cmple(p.box_max + slack).all()
}

/// Whether probe capture is needed for `scene`, and why: a `[[probe]]`, `reflections` set
/// to a probe method, and a drawn mirror to read it.
pub fn needed(scene: &Scene) -> (bool, String) {
    let g = &scene.geometry;
    let drawn = |m: usize| g.objects.iter().any(|o| o.material as usize == m && o.triangles > 0);
    let mirrors = scene.materials.iter().enumerate().any(|(i, m)| drawn(i) && matches!(m.model, Model::Mirror(_)));
    let how = scene.spec.settings.reflections;
    match (scene.spec.probes.len(), how, mirrors) {
        (0, _, _) => (false, "no [[probe]]".into()),
        (_, Reflections::Traced, _) => (false, "reflections = \"traced\": mirrors trace their rays".into()),
        (_, _, false) => (false, "no mirror is drawn to read a probe".into()),
        (n, how, true) => {
            let sizes: Vec<String> = scene.spec.probes.iter().map(|p| format!("{}²", p.size)).collect();
            let lookup = match how {
                Reflections::ProbeBox => "box-projected R' = P − C",
                Reflections::ProbeMoved => "moved to C': s' = P − C, P where R from C' leaves the box",
                Reflections::ProbeProjector => "as a projector: R traced to the surface x, read along s = x − C",
                _ => "naive, along R",
            };
            (
                true,
                format!(
                    "{n} probe{}: 6 faces of {} texels each, the scene without its mirrors; lookup {lookup}",
                    if n == 1 { "" } else { "s" },
                    sizes.join(", ")
                ),
            )
        }
    }
}

/// The scene a probe sees: without its mirror objects, the environment drawn where nothing
/// is hit (what a traced mirror ray would see), mirrors traced, no probes.
pub fn capture_scene(scene: &Scene) -> Scene {
    let mirror = |m: u32| matches!(scene.materials[m as usize].model, Model::Mirror(_));
    let g = &scene.geometry;
    let mut out = Geometry::default();
    for o in g.objects.iter().filter(|o| !mirror(o.material)) {
        let base = out.positions.len() as u32;
        let (vertices, triangles) = (o.first_vertex..o.first_vertex + o.vertices, o.first_triangle..o.first_triangle + o.triangles);
        let mut kept = *o;
        kept.first_vertex = out.positions.len();
        kept.first_triangle = out.triangles.len();
        out.positions.extend_from_slice(&g.positions[vertices.clone()]);
        out.normals.extend_from_slice(&g.normals[vertices]);
        let shift = base as i64 - o.first_vertex as i64;
        out.triangles.extend(g.triangles[triangles.clone()].iter().map(|t| t.map(|i| (i as i64 + shift) as u32)));
        out.material.extend_from_slice(&g.material[triangles.clone()]);
        out.face_normals.extend_from_slice(&g.face_normals[triangles]);
        out.objects.push(kept);
    }
    let mut s = Scene { geometry: out, ..scene.clone() };
    s.spec.probes = Vec::new();
    s.spec.settings.reflections = Reflections::Traced;
    if let Some(e) = &mut s.environment {
        e.background = true;
    }
    s
}

/// The camera of face `k` of probe `p` (90°, square, `p.size` pixels), and whether its
/// image must be mirrored left to right to match the face: the table is left-handed, the
/// camera right-handed.
pub fn face_camera(p: &ProbeSpec, k: usize, near: f32, background: Vec3) -> (Camera, bool) {
    let [a, s, t] = FACE_BASIS[k];
    // Rows run along T from the top, so the camera's up is −T.
    let up = -t;
    let right = a.cross(up);
    let camera =
        Camera { position: p.position, look_at: p.position + a, up, fov_y_deg: 90.0, width: p.size, height: p.size, near, background };
    (camera, right.dot(s) < 0.0)
}

/// A face image (row-major, top row first) put in the face's orientation.
pub fn orient(mut pixels: Vec<Vec3>, size: u32, flip: bool) -> Vec<Vec3> {
    if flip {
        for row in pixels.chunks_mut(size as usize) {
            row.reverse();
        }
    }
    pixels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_face_basis_inverts_the_opengl_table() {
        for (k, [a, s, t]) in FACE_BASIS.iter().enumerate() {
            for (sc, tc) in [(-0.5f32, 0.25f32), (0.75, -0.5), (0.0, 0.0)] {
                let (face, fs, ft) = CubeFaces::face_st(*a + sc * *s + tc * *t);
                assert_eq!(face, k);
                assert!((fs - 0.5 * (sc + 1.0)).abs() < 1e-6 && (ft - 0.5 * (tc + 1.0)).abs() < 1e-6, "face {k}: {fs} {ft}");
            }
        }
    }

    #[test]
    fn a_probe_reads_only_inside_its_box_and_box_projection_differs_from_naive_off_centre() {
        let spec = ProbeSpec {
            position: Vec3::ZERO,
            size: 8,
            box_min: Vec3::splat(-1.0),
            box_max: Vec3::splat(1.0),
            moved_to: Vec3::new(0.0, 0.0, 0.5),
        };
        // Each face one colour: the lookup names the face it read.
        let faces = CubeFaces { size: 8, faces: std::array::from_fn(|k| vec![Vec3::splat(k as f32); 64]) };
        let mut probes = Probes { maps: vec![ProbeMap { spec, faces }], reflections: Reflections::Probe };
        assert_eq!(probes.radiance(Vec3::new(0.0, 0.0, 2.0), Vec3::X), None);
        // From near the +z wall looking at (1, 0, 0.3): naive reads +x; the ray leaves by the +z wall.
        let (x, r) = (Vec3::new(0.0, 0.0, 0.9), Vec3::new(1.0, 0.0, 1.0).normalize());
        assert_eq!(probes.radiance(x, r), Some(Vec3::splat(0.0)));
        probes.reflections = Reflections::ProbeBox;
        assert_eq!(probes.radiance(x, r), Some(Vec3::splat(4.0)));
        // Moved to (0, 0, 0.5): the same for every point. Along +x it leaves by the +x wall at
        // (1, 0, 0.5), which C sees on +x; along (1, 0, 1) it leaves at (0.5, 0, 1), on +z.
        probes.reflections = Reflections::ProbeMoved;
        assert_eq!(probes.radiance(x, Vec3::X), Some(Vec3::splat(0.0)));
        assert_eq!(probes.radiance(Vec3::new(-0.8, 0.5, -0.8), r), Some(Vec3::splat(4.0)));
        assert_eq!(probes.radiance(Vec3::new(-0.8, 0.5, -0.8), Vec3::new(1.0, 0.0, 0.2).normalize()), Some(Vec3::splat(0.0)));
    }
}
