//! What the object-space shadow methods (shadow volumes, shadow polygons) need to know of
//! the scene's meshes as one light sees them: where the light is, which triangles face it,
//! whether each object is closed (2-manifold), and the silhouette edges seen from the light.
//!
//! A closed mesh with the light outside is represented by its light-facing triangles only
//! (its back faces lie in their shadow): its silhouette is the edges shared by a lit and an
//! unlit face (Crow 1977). Any other mesh (open, non-manifold, or with the light inside it)
//! is represented by all its triangles, each turned to face the light, and an edge is kept
//! with the multiplicity its turned triangles give it (Aldridge & Woods 2004, "Robust,
//! geometry-independent shadow volumes"): the counts stay right without a manifold.

use crate::light::LightKind;
use crate::scene::Scene;
use glam::Vec3;
use std::collections::HashMap;

/// Triangles with less area than this (world units²) are skipped: they cast nothing.
const MIN_AREA: f32 = 1e-12;

/// Where light comes from, for the object-space methods.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightFrom {
    /// A point (point and spot lights).
    Point(Vec3),
    /// A direction: the unit way the light travels (directional lights).
    Direction(Vec3),
}

impl LightFrom {
    /// The light as seen by the object-space methods; `None` for kinds with extent or none
    /// (an area light is sampled by rays, an ambient one is never shadowed).
    pub fn of(kind: &LightKind) -> Option<LightFrom> {
        match kind {
            LightKind::Directional(d) => Some(LightFrom::Direction(d.direction.normalize_or(-Vec3::Y))),
            _ => kind.position().map(LightFrom::Point),
        }
    }

    /// The (not normalized) direction from `x` towards the light.
    #[inline]
    pub fn towards(self, x: Vec3) -> Vec3 {
        match self {
            LightFrom::Point(l) => l - x,
            LightFrom::Direction(d) => -d,
        }
    }
}

/// One silhouette edge: `a → b` wound as its light-facing triangle(s) wind it, and how many
/// volumes it bounds (two layers of a folded open mesh give 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edge {
    /// First end.
    pub a: Vec3,
    /// Second end.
    pub b: Vec3,
    /// Multiplicity (≥ 1).
    pub weight: i32,
}

/// The scene's occluders seen from one light.
#[derive(Debug, Clone, Default)]
pub struct Occluders {
    /// Triangles that cast shadow, each wound to face the light (front caps).
    pub caps: Vec<[Vec3; 3]>,
    /// Silhouette edges.
    pub edges: Vec<Edge>,
    /// Objects represented by their silhouette (closed, light outside).
    pub closed_objects: usize,
    /// Objects represented triangle by triangle (open, non-manifold, or holding the light).
    pub open_objects: usize,
    /// Triangles skipped as degenerate (zero area) or edge-on to the light.
    pub skipped: usize,
}

/// True when the mesh `tris` (vertex ids welded by position) is closed: every edge is used
/// by exactly two triangles, in opposite directions (a consistently wound 2-manifold).
pub fn is_closed(tris: &[[u32; 3]]) -> bool {
    let mut uses: HashMap<(u32, u32), (i32, u32)> = HashMap::with_capacity(tris.len() * 3 / 2 + 1);
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = uses.entry((a.min(b), a.max(b))).or_insert((0, 0));
            e.0 += if a < b { 1 } else { -1 };
            e.1 += 1;
        }
    }
    !tris.is_empty() && uses.values().all(|&(dir, n)| n == 2 && dir == 0)
}

/// Vertex ids of the triangles `first..first + n` of `scene`, welded by exact position (a
/// sphere's seam and poles repeat positions), skipping degenerate triangles.
fn welded(scene: &Scene, first: usize, n: usize) -> (Vec<Vec3>, Vec<[u32; 3]>, usize) {
    let g = &scene.geometry;
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let mut points = Vec::new();
    let mut tris = Vec::with_capacity(n);
    let mut skipped = 0;
    for t in &g.triangles[first..first + n] {
        let p = t.map(|i| g.positions[i as usize]);
        if (p[1] - p[0]).cross(p[2] - p[0]).length_squared() < MIN_AREA * MIN_AREA * 4.0 || !p.iter().all(|v| v.is_finite()) {
            skipped += 1;
            continue;
        }
        let mut id = |v: Vec3, points: &mut Vec<Vec3>| {
            *ids.entry(v.to_array().map(f32::to_bits)).or_insert_with(|| {
                points.push(v);
                points.len() as u32 - 1
            })
        };
        let w = [id(p[0], &mut points), id(p[1], &mut points), id(p[2], &mut points)];
        if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] {
            skipped += 1;
            continue;
        }
        tris.push(w);
    }
    (points, tris, skipped)
}

/// True when the point light `l` lies inside the closed mesh: a ray from it crosses the
/// surface an odd number of times (the direction is irrational-looking so that it misses
/// edges of axis-aligned meshes).
fn holds(points: &[Vec3], tris: &[[u32; 3]], l: Vec3) -> bool {
    let d = Vec3::new(0.573_21, 0.618_03, 0.537_92).normalize();
    let mut crossings = 0;
    for t in tris {
        let [a, b, c] = t.map(|i| points[i as usize]);
        // Möller–Trumbore.
        let (e1, e2) = (b - a, c - a);
        let q = d.cross(e2);
        let det = e1.dot(q);
        if det.abs() < 1e-20 {
            continue;
        }
        let s = l - a;
        let u = s.dot(q) / det;
        let r = s.cross(e1);
        let v = d.dot(r) / det;
        let t = e2.dot(r) / det;
        if u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 {
            crossings += 1;
        }
    }
    crossings % 2 == 1
}

impl Occluders {
    /// The occluders of every object of `scene` as the light `from` sees them.
    pub fn find(scene: &Scene, from: LightFrom) -> Occluders {
        let mut out = Occluders::default();
        for o in &scene.geometry.objects {
            let (points, tris, skipped) = welded(scene, o.first_triangle, o.triangles);
            out.skipped += skipped;
            let inside = match from {
                LightFrom::Point(l) => holds(&points, &tris, l),
                LightFrom::Direction(_) => false,
            };
            let closed = is_closed(&tris) && !inside;
            if closed {
                out.closed_objects += 1;
            } else if !tris.is_empty() {
                out.open_objects += 1;
            }
            // Each casting triangle, wound to face the light; edges counted by direction.
            let mut mult: HashMap<(u32, u32), i32> = HashMap::new();
            for t in &tris {
                let [a, b, c] = t.map(|i| points[i as usize]);
                let n = (b - a).cross(c - a);
                let facing = n.dot(from.towards((a + b + c) / 3.0));
                if facing == 0.0 || !facing.is_finite() {
                    out.skipped += 1; // edge-on: it casts a shadow of no area
                    continue;
                }
                let w = match (facing > 0.0, closed) {
                    (true, _) => *t,
                    (false, true) => continue, // a closed mesh's back face lies in its front faces' shadow
                    (false, false) => [t[0], t[2], t[1]],
                };
                out.caps.push(w.map(|i| points[i as usize]));
                for k in 0..3 {
                    let (a, b) = (w[k], w[(k + 1) % 3]);
                    *mult.entry((a.min(b), a.max(b))).or_insert(0) += if a < b { 1 } else { -1 };
                }
            }
            // Sorted so the edges come out in the same order on every run.
            let mut kept: Vec<_> = mult.into_iter().filter(|&(_, m)| m != 0).collect();
            kept.sort_unstable();
            for ((lo, hi), m) in kept {
                let (a, b) = if m > 0 { (lo, hi) } else { (hi, lo) };
                out.edges.push(Edge { a: points[a as usize], b: points[b as usize], weight: m.abs() });
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cube_is_closed_and_a_cube_without_a_face_is_not() {
        // The unit cube's twelve triangles, wound outwards.
        let cube = cube_tris();
        assert!(is_closed(&cube));
        assert!(!is_closed(&cube[..10]), "two triangles missing leave four boundary edges");
        let mut flipped = cube.clone();
        flipped[0] = [flipped[0][0], flipped[0][2], flipped[0][1]];
        assert!(!is_closed(&flipped), "an inconsistently wound face breaks the manifold's orientation");
    }

    #[test]
    fn the_light_inside_a_cube_is_found_by_parity() {
        let (p, t) = (cube_points(), cube_tris());
        assert!(holds(&p, &t, Vec3::splat(0.5)));
        assert!(!holds(&p, &t, Vec3::new(0.5, 3.0, 0.5)));
        assert!(!holds(&p, &t, Vec3::new(-2.0, 0.5, 0.5)));
    }

    pub(crate) fn cube_points() -> Vec<Vec3> {
        (0..8).map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32)).collect()
    }

    /// The unit cube's triangles, counter-clockwise seen from outside.
    pub(crate) fn cube_tris() -> Vec<[u32; 3]> {
        let quads = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];
        quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect()
    }

    /// Every silhouette edge found on a cube and on a sphere (with its seam and poles) is
    /// shared by exactly one light-facing and one back-facing triangle, and together they
    /// close into loops (each end used as often by an edge leaving as arriving).
    #[test]
    fn silhouette_edges_are_shared_by_a_lit_and_an_unlit_face() {
        for shape in ["shape = \"cube\"", "shape = \"uv_sphere\"\nsegments = 24\nrings = 12", "shape = \"icosphere\""] {
            let text = format!(
                "[camera]\nposition = [0, 0, 5]\nsize = [8, 8]\n\n[[object]]\n{shape}\nmaterial = \"m\"\n\n\
                 [material.m]\nmodel = \"lambert\"\n\n[[light]]\nkind = \"point\"\nposition = [1.3, 2.9, 0.7]\n"
            );
            let lesson = crate::lesson::parse(&text, std::path::Path::new("t.toml"), &[]).unwrap();
            let scene = crate::scene::build::build(&lesson).unwrap();
            let l = Vec3::new(1.3, 2.9, 0.7);
            let occ = Occluders::find(&scene, LightFrom::Point(l));
            assert_eq!((occ.closed_objects, occ.open_objects), (1, 0), "{shape}: a closed mesh");
            assert!(occ.edges.len() >= 4, "{shape}: {} edges", occ.edges.len());
            let g = &scene.geometry;
            let key = |v: Vec3| v.to_array().map(f32::to_bits);
            let mut ends: HashMap<[u32; 3], i32> = HashMap::new();
            for e in &occ.edges {
                assert_eq!(e.weight, 1, "{shape}: a closed mesh's silhouette is simple");
                let (mut lit, mut unlit) = (0, 0);
                for t in &g.triangles {
                    let p = t.map(|i| g.positions[i as usize]);
                    let uses = |v: Vec3| p.iter().any(|q| key(*q) == key(v));
                    if !uses(e.a) || !uses(e.b) || (p[1] - p[0]).cross(p[2] - p[0]).length() < 1e-9 {
                        continue;
                    }
                    let n = (p[1] - p[0]).cross(p[2] - p[0]);
                    if n.dot(l - (p[0] + p[1] + p[2]) / 3.0) > 0.0 { lit += 1 } else { unlit += 1 }
                }
                assert_eq!((lit, unlit), (1, 1), "{shape}: edge {:?} → {:?}", e.a, e.b);
                *ends.entry(key(e.a)).or_insert(0) += 1;
                *ends.entry(key(e.b)).or_insert(0) -= 1;
            }
            assert!(ends.values().all(|&n| n == 0), "{shape}: the silhouette does not close");
            // The caps are exactly the light-facing triangles.
            assert!(occ.caps.iter().all(|c| (c[1] - c[0]).cross(c[2] - c[0]).dot(l - c[0]) > 0.0));
        }
    }

    #[test]
    fn cube_winding_is_outwards() {
        let (p, t) = (cube_points(), cube_tris());
        for tri in &t {
            let [a, b, c] = tri.map(|i| p[i as usize]);
            let n = (b - a).cross(c - a);
            assert!(n.dot((a + b + c) / 3.0 - Vec3::splat(0.5)) > 0.0, "{tri:?}");
        }
    }
}
