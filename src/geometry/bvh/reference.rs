//! The scalar reference the wide tree and the packets are tested against: the binary tree
//! walked one node at a time with the scalar slab test and one triangle at a time with
//! [`intersect`] (the traversal before the wide tree), with the same rule for ties: the
//! smallest (t, triangle index) wins, each triangle tested up to the ray's own t_max.

use super::TriHit;
use super::build::{self, Binary, vertices};
use super::traverse::SlabRay;
use crate::geometry::triangle::{RayPrecomp, intersect};
use glam::Vec3;
use std::ops::Range;

/// Traversal stack entries: more than the deepest binary tree the build can make.
const STACK: usize = 64;

/// The binary tree with its triangles in leaf order.
#[derive(Debug, Clone)]
pub(super) struct Reference {
    /// The tree.
    pub bin: Binary,
    /// Each kept triangle's vertices, in leaf order.
    tris: Vec<[Vec3; 3]>,
}

impl Reference {
    /// The binary tree of the same build as [`super::Bvh::build`].
    pub fn build(positions: &[Vec3], triangles: &[[u32; 3]]) -> Reference {
        let bin = build::build(positions, triangles);
        let tris = bin.ids.iter().map(|&id| vertices(positions, &triangles[id as usize]).expect("kept")).collect();
        Reference { bin, tris }
    }

    /// The nearest hit, as [`super::Bvh::closest_hit`].
    pub fn closest_hit(&self, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> Option<TriHit> {
        self.traverse::<false>(origin, dir, t_max, skip)
    }

    /// Any hit, as [`super::Bvh::occluded`].
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> bool {
        self.traverse::<true>(origin, dir, t_max, skip).is_some()
    }

    /// Front to back by the direction's sign on each split axis; with `ANY` it returns the
    /// first hit found, else it keeps the smallest (t, index), testing boxes up to its t.
    fn traverse<const ANY: bool>(&self, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> Option<TriHit> {
        let nodes = &self.bin.nodes;
        if nodes.is_empty() {
            return None;
        }
        let ray = SlabRay::new(origin, dir);
        let pre = RayPrecomp::new(dir);
        let mut best: Option<TriHit> = None;
        let mut t_best = t_max;
        let mut stack = [0u32; STACK];
        let mut sp = 0;
        let mut i = 0usize;
        loop {
            let node = &nodes[i];
            if ray.hits(node.min, node.max, t_best) {
                if node.count > 0 {
                    let first = node.index as usize;
                    for k in first..first + node.count as usize {
                        let id = self.bin.ids[k];
                        if skip.contains(&id) {
                            continue;
                        }
                        let [a, b, c] = self.tris[k];
                        if let Some((t, b1, b2)) = intersect(&pre, origin, a, b, c, t_max) {
                            if ANY {
                                return Some(TriHit { t, tri: id, b1, b2 });
                            }
                            if best.is_none_or(|h| t < h.t || (t == h.t && id < h.tri)) {
                                t_best = t;
                                best = Some(TriHit { t, tri: id, b1, b2 });
                            }
                        }
                    }
                } else {
                    let (near, far) = if ray.neg[node.axis as usize] { (node.index, i as u32 + 1) } else { (i as u32 + 1, node.index) };
                    stack[sp] = far;
                    sp += 1;
                    i = near as usize;
                    continue;
                }
            }
            if sp == 0 {
                return best;
            }
            sp -= 1;
            i = stack[sp] as usize;
        }
    }
}
