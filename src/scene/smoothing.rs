//! Vertex normals with creases: OBJ smoothing groups (`s N`) and an auto-smooth angle
//! (`crease_deg`).
//!
//! Plain vertex normals ([`super::normals`]) average every face that shares a vertex by
//! index, so a cube whose faces share its eight corners becomes a soft blob under Phong
//! shading. Here the faces are joined by position instead (a uv seam does not split a
//! normal), and each corner of a face averages only the faces at that position that are
//! *compatible* with it: the face itself, faces in the same non-zero smoothing group (when
//! the file has groups; group 0 is `s off`, flat), and faces whose normal is within the
//! crease angle of its own (when one is given). The test is pairwise, as in 3ds Max's
//! smoothing groups and Blender's auto-smooth: two faces meeting at more than the angle
//! keep their own normals there. Corners that get different normals become separate
//! vertices; the triangles and their per-corner uvs are unchanged.

use std::collections::HashMap;

use glam::Vec3;

use super::mesh::{Mesh, MeshRepairs};
use super::normals::face_normal;
use crate::lesson::NormalWeighting;

/// A position shared by more corners than this is smoothed without the crease test (all
/// its compatible-by-group faces): the pairwise test is quadratic in the fan, and only a
/// pathological mesh (one apex for thousands of triangles) reaches it.
pub const MAX_CREASE_FAN: usize = 4096;

/// Which faces a corner's normal averages.
#[derive(Debug, Clone, Copy, Default)]
pub struct Smoothing<'a> {
    /// Faces whose normals differ by more than this angle (degrees) are not averaged.
    pub crease_deg: Option<f32>,
    /// A smoothing group per triangle (0: flat), from the OBJ file's `s` lines.
    pub groups: Option<&'a [u32]>,
}

/// Replaces `mesh.normals` by creased vertex normals, splitting vertices whose corners
/// disagree. Degenerate triangles are counted and take the average of every face at
/// their corners' positions (else +y, counted as repaired).
pub fn smooth(mesh: &mut Mesh, weighting: NormalWeighting, how: Smoothing) -> MeshRepairs {
    let cos_crease = how.crease_deg.map(|d| d.to_radians().cos());
    // Weld by position: `+ 0.0` makes −0 and +0 one key.
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let welded: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let key = (*p + Vec3::ZERO).to_array().map(f32::to_bits);
            let next = ids.len() as u32;
            *ids.entry(key).or_insert(next)
        })
        .collect();
    let faces: Vec<Option<Vec3>> = mesh
        .triangles
        .iter()
        .map(|t| match t.map(|i| mesh.positions.get(i as usize).copied()) {
            [Some(a), Some(b), Some(c)] => face_normal(a, b, c),
            _ => None,
        })
        .collect();
    // The corners at each welded position: (triangle, corner 0..3).
    let mut fans: Vec<Vec<(u32, u8)>> = vec![Vec::new(); ids.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for (c, &v) in tri.iter().enumerate() {
            if let Some(&w) = welded.get(v as usize) {
                fans[w as usize].push((t as u32, c as u8));
            }
        }
    }
    let group = |t: u32| how.groups.and_then(|g| g.get(t as usize).copied());
    let mut repairs = MeshRepairs { degenerate_triangles: faces.iter().filter(|f| f.is_none()).count(), repaired_normals: 0 };
    let mut corner_normals = vec![[Vec3::Y; 3]; mesh.triangles.len()];
    for fan in &fans {
        let weights: Vec<Vec3> = fan.iter().map(|&(t, c)| corner_weight(mesh, &faces, t, c, weighting)).collect();
        let pairwise = fan.len() <= MAX_CREASE_FAN;
        for &(t, c) in fan {
            let own = faces[t as usize];
            let mut sum = Vec3::ZERO;
            for (j, &(u, _)) in fan.iter().enumerate() {
                let joins = match own {
                    // A degenerate face has no normal to compare: it takes them all.
                    None => true,
                    Some(n) => {
                        let same = u == t;
                        let grouped = match (group(t), group(u)) {
                            (Some(a), Some(b)) => a != 0 && a == b,
                            _ => true,
                        };
                        let within = match (cos_crease, faces[u as usize]) {
                            (Some(cos), Some(m)) if pairwise => n.dot(m) >= cos,
                            _ => true,
                        };
                        same || (grouped && within)
                    }
                };
                if joins {
                    sum += weights[j];
                }
            }
            corner_normals[t as usize][c as usize] = match sum.try_normalize().or(own) {
                Some(n) => n,
                None => {
                    repairs.repaired_normals += 1;
                    Vec3::Y
                }
            };
        }
    }
    split(mesh, &corner_normals);
    repairs
}

/// The weight a face gives its corner `c` (as [`super::normals`]' weighting): zero for a
/// degenerate face.
fn corner_weight(mesh: &Mesh, faces: &[Option<Vec3>], t: u32, c: u8, weighting: NormalWeighting) -> Vec3 {
    let Some(n) = faces[t as usize] else { return Vec3::ZERO };
    let tri = mesh.triangles[t as usize];
    let p = |k: usize| mesh.positions[tri[k] as usize];
    let (a, b, d) = (p(c as usize), p((c as usize + 1) % 3), p((c as usize + 2) % 3));
    match weighting {
        NormalWeighting::Average => n,
        NormalWeighting::Area => (b - a).cross(d - a).length() * n,
        NormalWeighting::Angle => {
            let (e1, e2) = (b - a, d - a);
            n * e1.cross(e2).length().atan2(e1.dot(e2))
        }
    }
}

/// Gives every (vertex, normal) pair its own vertex and points the triangles at them.
fn split(mesh: &mut Mesh, corner_normals: &[[Vec3; 3]]) {
    let mut index: HashMap<(u32, [u32; 3]), u32> = HashMap::new();
    let (mut positions, mut normals) = (Vec::with_capacity(mesh.positions.len()), Vec::with_capacity(mesh.positions.len()));
    for (tri, ns) in mesh.triangles.iter_mut().zip(corner_normals) {
        for (v, n) in tri.iter_mut().zip(ns) {
            let Some(&p) = mesh.positions.get(*v as usize) else { continue };
            let next = positions.len() as u32;
            *v = *index.entry((*v, n.to_array().map(f32::to_bits))).or_insert_with(|| {
                positions.push(p);
                normals.push(*n);
                next
            });
        }
    }
    mesh.positions = positions;
    mesh.normals = normals;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::normals::compute_vertex_normals;

    /// A cube whose six faces share its eight corners (as a plain OBJ writes it).
    fn shared_cube() -> Mesh {
        let positions = (0..8).map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32) * 2.0 - 1.0).collect();
        let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let triangles = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
        Mesh { positions, normals: Vec::new(), triangles, uvs: Vec::new() }
    }

    /// Each corner's normal, read through the (split) vertices.
    fn corner_normals(m: &Mesh) -> Vec<Vec3> {
        m.triangles.iter().flat_map(|t| t.map(|v| m.normals[v as usize])).collect()
    }

    #[test]
    fn a_crease_below_ninety_degrees_keeps_a_cube_flat() {
        let mut m = shared_cube();
        let r = smooth(&mut m, NormalWeighting::Average, Smoothing { crease_deg: Some(30.0), groups: None });
        assert_eq!(r, MeshRepairs::default());
        // Every corner's normal is its face's normal: 24 vertices, one per face corner.
        assert_eq!(m.positions.len(), 24);
        for (t, tri) in m.triangles.iter().enumerate() {
            let n = face_normal(m.positions[tri[0] as usize], m.positions[tri[1] as usize], m.positions[tri[2] as usize]).unwrap();
            for v in tri {
                assert!((m.normals[*v as usize] - n).length() < 1e-6, "triangle {t}");
            }
        }
    }

    #[test]
    fn a_crease_of_180_degrees_is_the_plain_average() {
        let (mut creased, mut plain) = (shared_cube(), shared_cube());
        // Angle weights: each face gives a corner 90° however it is cut into triangles.
        smooth(&mut creased, NormalWeighting::Angle, Smoothing { crease_deg: Some(180.0), groups: None });
        compute_vertex_normals(&mut plain, NormalWeighting::Angle);
        assert_eq!(creased.positions.len(), 8);
        for (a, b) in corner_normals(&creased).iter().zip(corner_normals(&plain)) {
            assert!((*a - b).length() < 1e-6, "{a} vs {b}");
            // The corner of a cube: (±1, ±1, ±1)/√3.
            assert!((a.abs() - Vec3::splat(1.0 / 3f32.sqrt())).length() < 1e-6, "{a}");
        }
    }

    #[test]
    fn smoothing_groups_join_only_their_own_faces() {
        // Group 1: the four side faces (x and z), group 0 (flat): top and bottom.
        let mut m = shared_cube();
        let groups = [1, 1, 1, 1, 0, 0, 0, 0, 1, 1, 1, 1];
        smooth(&mut m, NormalWeighting::Angle, Smoothing { crease_deg: None, groups: Some(&groups) });
        for (t, tri) in m.triangles.iter().enumerate() {
            for v in tri {
                let n = m.normals[*v as usize];
                if groups[t] == 0 {
                    assert_eq!(n.x.abs() + n.z.abs(), 0.0, "flat face {t}: {n}");
                } else {
                    // A side corner averages two sides: horizontal, at 45°.
                    assert!(n.y.abs() < 1e-6 && (n.x.abs() - n.z.abs()).abs() < 1e-6, "side {t}: {n}");
                }
            }
        }
    }

    #[test]
    fn uv_seams_do_not_split_normals_and_degenerate_faces_stay_finite() {
        // Two copies of a corner position (as a uv seam makes) join by position.
        let mut m = shared_cube();
        m.positions.push(m.positions[0]);
        m.triangles[0][0] = 8;
        // And a zero-area triangle on a corner.
        m.triangles.push([1, 1, 1]);
        let r = smooth(&mut m, NormalWeighting::Angle, Smoothing { crease_deg: Some(180.0), groups: None });
        assert_eq!(r.degenerate_triangles, 1);
        let ns = corner_normals(&m);
        assert!(ns.iter().all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-5));
        assert!((ns[0] - ns[3]).length() < 1e-6, "the seam split the normal: {} vs {}", ns[0], ns[3]);
    }
}
