//! Shadow volumes (Crow 1977, "Shadow algorithms for computer graphics"): each silhouette
//! edge of an occluder, seen from the light, is extruded away from the light into a
//! semi-infinite quad; the quads with the occluder's light-facing triangles (the front cap)
//! bound the region the occluder shadows. A point is in shadow when it lies inside a volume.
//!
//! Crow's z-pass count: along the eye's ray to the visible point, every volume face crossed
//! in front of the point adds +1 when the ray enters (a front face) and −1 when it leaves (a
//! back face); a count > 0 means shadowed. This is what a GPU's stencil buffer counts per
//! sample when the volume faces are drawn against the depth buffer; here the count is made
//! per shaded point along the segment from the eye to it, which gives the same number (the
//! volume faces in front of the visible surface) without a stencil pass.
//!
//! Where z-pass alone would be wrong, and what is done:
//! - The eye inside a volume: every count would be one short. The count of volumes holding
//!   the eye is found once per light by counting from the light (or, for a directional
//!   light, from a point beyond the scene towards it) to the eye with the caps included, and
//!   added to every point's count (Bergeron 1986's correction).
//! - A point that is not a visible sample (a Gouraud vertex, a flat face's centre, a point
//!   in fog) may lie behind an occluder, so its eye segment may cross a front cap: its count
//!   includes the caps, which makes it the exact number of volumes holding it.
//! - Meshes that are not closed (or hold the light) are cast triangle by triangle
//!   (`occluders`): more quads, the same answer.
//!
//! Cost: building is linear in the triangles (welding, edge counts); each query tests every
//! silhouette quad (and, off the visible surface, every cap), so the time a point grows
//! with the silhouette's length: ∝ √n triangles for a smooth tessellated object.

use super::occluders::{Edge, LightFrom, Occluders};
use crate::light::LightKind;
use crate::scene::Scene;
use glam::Vec3;

/// The count of shadow-volume quads tested (each query tests them all).
pub const VOLUME_QUAD_TESTS: &str = "shadow-volume quads tested";
/// The count of shadow-volume quads built (silhouette edges, with their multiplicity).
pub const VOLUME_QUADS: &str = "shadow-volume quads";

/// A query's segment ends this far (relative) short of the point, so the point's own
/// surface (a front cap, or a quad starting at its edge) is not counted.
const END: f32 = 1e-4;

/// One light's shadow volumes and the eye they are counted from.
#[derive(Debug, Clone)]
pub struct ShadowVolume {
    from: LightFrom,
    eye: Vec3,
    edges: Vec<Edge>,
    caps: Vec<[Vec3; 3]>,
    /// Volumes holding the eye (Bergeron's correction).
    eye_count: i32,
    /// Objects cast by silhouette and triangle by triangle.
    pub closed_objects: usize,
    /// Objects cast triangle by triangle (open meshes, or the light inside).
    pub open_objects: usize,
}

impl ShadowVolume {
    /// The shadow volumes of light `kind` in `scene`, counted from the scene's camera;
    /// `None` for a light with extent (it has no one silhouette).
    pub fn build(scene: &Scene, kind: &LightKind) -> Option<ShadowVolume> {
        let from = LightFrom::of(kind)?;
        let occ = Occluders::find(scene, from);
        let eye = scene.spec.camera.position;
        let mut v = ShadowVolume {
            from,
            eye,
            edges: occ.edges,
            caps: occ.caps,
            eye_count: 0,
            closed_objects: occ.closed_objects,
            open_objects: occ.open_objects,
        };
        let start = match from {
            LightFrom::Point(l) => l,
            LightFrom::Direction(d) => {
                // Beyond every object on the way to the light: outside every volume.
                let far = scene.geometry.objects.iter().map(|o| (o.centre - eye).length() + o.radius).fold(1.0, f32::max);
                eye - d * (2.0 * far)
            }
        };
        v.eye_count = v.count(start, eye, true, 0.0);
        Some(v)
    }

    /// Silhouette quads (with multiplicity): what each visible point tests.
    pub fn quads(&self) -> u64 {
        self.edges.iter().map(|e| e.weight as u64).sum()
    }

    /// Volumes holding the eye (0 unless the camera stands in a shadow).
    pub fn eye_count(&self) -> i32 {
        self.eye_count
    }

    /// 0 when `p` is inside a shadow volume, else 1. `visible` says `p` is the surface the
    /// eye sees there (a shaded sample): then the front caps cannot lie in front of it and
    /// are not tested (Crow's z-pass).
    pub fn visibility(&self, p: Vec3, visible: bool) -> f32 {
        if self.eye_count + self.count(self.eye, p, !visible, END) > 0 { 0.0 } else { 1.0 }
    }

    /// Quads (and caps) a query tests.
    pub fn tests(&self, visible: bool) -> u64 {
        self.edges.len() as u64 + if visible { 0 } else { self.caps.len() as u64 }
    }

    /// Σ over the volume faces the segment `s → e` crosses (short of `e` by `end`,
    /// relative) of +weight entering, −weight leaving.
    fn count(&self, s: Vec3, e: Vec3, caps: bool, end: f32) -> i32 {
        let d = e - s;
        let t_max = 1.0 - end;
        let mut n = 0;
        for q in &self.edges {
            if let Some(enter) = self.crosses_quad(q, s, d, t_max) {
                n += if enter { q.weight } else { -q.weight };
            }
        }
        if caps {
            for c in &self.caps {
                if let Some(enter) = crosses_triangle(c, s, d, t_max) {
                    n += if enter { 1 } else { -1 };
                }
            }
        }
        n
    }

    /// Whether the segment `s + t d`, 0 < t < t_max, crosses the semi-infinite quad extruded
    /// from `q` away from the light, and whether it enters the volume there.
    fn crosses_quad(&self, q: &Edge, s: Vec3, d: Vec3, t_max: f32) -> Option<bool> {
        let (a, b) = (q.a, q.b);
        // The quad's outward normal, e × (b − a) with e the extrusion direction.
        let (n, apex_a, apex_b) = match self.from {
            LightFrom::Point(l) => ((a - l).cross(b - l), a - l, b - l),
            LightFrom::Direction(dir) => (dir.cross(b - a), dir, dir),
        };
        let dn = d.dot(n);
        if dn == 0.0 || !dn.is_finite() {
            return None; // parallel to the quad's plane: it cannot cross it
        }
        let t = (a - s).dot(n) / dn;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        let x = s + d * t;
        // Inside: beyond the edge (on the side away from the light) and between the two
        // extrusion rays from a and from b.
        let beyond = n.dot((b - a).cross(x - a)) <= 0.0;
        let past_a = n.dot(apex_a.cross(x - a)) >= 0.0;
        let before_b = n.dot((x - b).cross(apex_b)) >= 0.0;
        (beyond && past_a && before_b).then_some(dn < 0.0)
    }
}

/// Whether the segment `s + t d`, 0 < t < t_max, crosses the triangle `c` (wound to face the
/// light, its normal pointing out of the volume), and whether it enters the volume there.
fn crosses_triangle(c: &[Vec3; 3], s: Vec3, d: Vec3, t_max: f32) -> Option<bool> {
    let (e1, e2) = (c[1] - c[0], c[2] - c[0]);
    let n = e1.cross(e2);
    let dn = d.dot(n);
    if dn == 0.0 || !dn.is_finite() {
        return None;
    }
    let t = (c[0] - s).dot(n) / dn;
    if !(t > 0.0 && t < t_max) {
        return None;
    }
    let x = s + d * t;
    let inside = (0..3).all(|k| n.dot((c[(k + 1) % 3] - c[k]).cross(x - c[k])) >= 0.0);
    inside.then_some(dn < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn volume(from: LightFrom, occ: Occluders, eye: Vec3) -> ShadowVolume {
        let mut v = ShadowVolume { from, eye, edges: occ.edges, caps: occ.caps, eye_count: 0, closed_objects: 0, open_objects: 0 };
        let start = match from {
            LightFrom::Point(l) => l,
            LightFrom::Direction(d) => eye - d * 100.0,
        };
        v.eye_count = v.count(start, eye, true, 0.0);
        v
    }

    /// A square [−1, 1]² at height 1 facing up, as its two triangles' silhouette.
    fn square() -> Occluders {
        let p = [Vec3::new(-1.0, 1.0, -1.0), Vec3::new(1.0, 1.0, -1.0), Vec3::new(1.0, 1.0, 1.0), Vec3::new(-1.0, 1.0, 1.0)];
        // Wound counter-clockwise seen from above (normal +y).
        let caps = vec![[p[0], p[2], p[1]], [p[0], p[3], p[2]]];
        let edges = vec![
            Edge { a: p[0], b: p[3], weight: 1 },
            Edge { a: p[3], b: p[2], weight: 1 },
            Edge { a: p[2], b: p[1], weight: 1 },
            Edge { a: p[1], b: p[0], weight: 1 },
        ];
        Occluders { caps, edges, closed_objects: 0, open_objects: 1, skipped: 0 }
    }

    #[test]
    fn a_square_over_the_floor_shadows_the_analytic_square_twice_its_size() {
        // A point light at height 2 over a square at height 1: on the floor (y = 0) the
        // shadow is the square scaled by 2 / (2 − 1) = 2, i.e. [−2, 2]².
        let v = volume(LightFrom::Point(Vec3::new(0.0, 2.0, 0.0)), square(), Vec3::new(0.3, 5.0, 7.0));
        assert_eq!(v.eye_count(), 0);
        for (x, z, shadowed) in
            [(0.0, 0.0, true), (1.95, 1.95, true), (-1.95, 0.5, true), (2.05, 0.0, false), (0.0, -2.05, false), (3.0, 3.0, false)]
        {
            let vis = v.visibility(Vec3::new(x, 0.0, z), true);
            assert_eq!(vis == 0.0, shadowed, "({x}, {z})");
        }
    }

    #[test]
    fn a_directional_light_extrudes_parallel_quads() {
        // Light straight down: the shadow is the square itself.
        let v = volume(LightFrom::Direction(-Vec3::Y), square(), Vec3::new(0.0, 5.0, 6.0));
        assert_eq!(v.visibility(Vec3::new(0.9, 0.0, 0.9), true), 0.0);
        assert_eq!(v.visibility(Vec3::new(1.1, 0.0, 0.0), true), 1.0);
    }

    #[test]
    fn an_eye_inside_the_volume_is_counted_once_and_corrected() {
        // The eye under the square, looking at floor points: z-pass alone would see no
        // face in front of (0, 0, 0) and call it lit.
        let v = volume(LightFrom::Point(Vec3::new(0.0, 2.0, 0.0)), square(), Vec3::new(0.2, 0.5, 0.1));
        assert_eq!(v.eye_count(), 1);
        assert_eq!(v.visibility(Vec3::ZERO, true), 0.0);
        assert_eq!(v.visibility(Vec3::new(3.0, 0.0, 0.0), true), 1.0, "leaving through a side quad");
    }

    #[test]
    fn a_hidden_point_counts_the_caps() {
        // A point above the square, seen through it from below: only with the caps is it lit.
        // (Off the squares' shared diagonal, which a segment would cross twice.)
        let v = volume(LightFrom::Point(Vec3::new(0.0, 2.0, 0.0)), square(), Vec3::new(0.13, -3.0, 0.07));
        assert_eq!(v.eye_count(), 1, "the eye below the square is in its shadow");
        assert_eq!(v.visibility(Vec3::new(0.1, 1.5, 0.03), false), 1.0);
        assert_eq!(v.visibility(Vec3::new(0.1, 0.5, 0.03), false), 0.0);
    }

    #[test]
    fn degenerate_input_gives_finite_answers() {
        let mut occ = square();
        occ.edges.push(Edge { a: Vec3::ONE, b: Vec3::ONE, weight: 1 }); // a zero-length edge
        occ.caps.push([Vec3::ONE; 3]);
        // The light on the square's plane: every quad is edge-on.
        for from in [LightFrom::Point(Vec3::new(0.0, 1.0, 0.0)), LightFrom::Point(Vec3::new(5.0, 1.0, 0.0))] {
            let v = volume(from, occ.clone(), Vec3::new(0.0, 3.0, 3.0));
            for p in [Vec3::ZERO, Vec3::ONE, Vec3::new(0.0, 1.0, 0.0)] {
                let vis = v.visibility(p, true);
                assert!(vis == 0.0 || vis == 1.0);
            }
        }
    }
}
