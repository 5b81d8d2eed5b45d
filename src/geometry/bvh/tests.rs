//! Tests of the BVH: brute-force agreement, skips, degenerate input, determinism, depth.
use super::*;
use crate::simd::lanes::test_rng;

/// A random soup of `n` triangles of size up to `size` in [−10, 10]³.
fn soup(n: usize, size: f32, seed: u64) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut rng = test_rng(seed, 1.0);
    let mut positions = Vec::with_capacity(3 * n);
    for _ in 0..n {
        let c = Vec3::new(rng(), rng(), rng()) * 10.0;
        for _ in 0..3 {
            positions.push(c + Vec3::new(rng(), rng(), rng()) * size);
        }
    }
    let triangles = (0..n as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    (positions, triangles)
}

/// A closed uv sphere of radius 2 at `centre`, `segments` × `rings` (pole rows are fans of
/// triangles sharing the pole vertex, so every edge is shared).
fn uv_sphere(centre: Vec3, segments: u32, rings: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut positions = vec![centre + Vec3::Y * 2.0];
    for r in 1..rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            positions.push(centre + 2.0 * Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()));
        }
    }
    positions.push(centre - Vec3::Y * 2.0);
    let bottom = positions.len() as u32 - 1;
    let ring = |r: u32, s: u32| 1 + (r - 1) * segments + s % segments;
    let mut triangles = Vec::new();
    for s in 0..segments {
        triangles.push([0, ring(1, s + 1), ring(1, s)]);
        for r in 1..rings - 1 {
            triangles.push([ring(r, s), ring(r, s + 1), ring(r + 1, s + 1)]);
            triangles.push([ring(r, s), ring(r + 1, s + 1), ring(r + 1, s)]);
        }
        triangles.push([bottom, ring(rings - 1, s), ring(rings - 1, s + 1)]);
    }
    (positions, triangles)
}

/// The nearest hit by testing every triangle (the first of equal t wins).
fn brute_closest(p: &[Vec3], tris: &[[u32; 3]], o: Vec3, d: Vec3, t_max: f32, skip: Range<u32>) -> Option<TriHit> {
    let pre = RayPrecomp::new(d);
    let mut best: Option<TriHit> = None;
    for (i, t) in tris.iter().enumerate() {
        if skip.contains(&(i as u32)) {
            continue;
        }
        let limit = best.map_or(t_max, |b| b.t);
        if let Some((t, b1, b2)) = intersect(&pre, o, p[t[0] as usize], p[t[1] as usize], p[t[2] as usize], limit) {
            best = Some(TriHit { t, tri: i as u32, b1, b2 });
        }
    }
    best
}

/// Checks closest_hit and occluded against brute force on `rays` rays; returns the number of hits.
fn agree_with_brute_force(p: &[Vec3], tris: &[[u32; 3]], rays: &[(Vec3, Vec3, f32)], skip: Range<u32>) -> usize {
    let bvh = Bvh::build(p, tris);
    let mut hits = 0;
    for &(o, d, t_max) in rays {
        let got = bvh.closest_hit(o, d, t_max, skip.clone());
        let want = brute_closest(p, tris, o, d, t_max, skip.clone());
        match (got, want) {
            (Some(g), Some(w)) => {
                // Another triangle at the same distance (a shared edge) is as good; the
                // t of a triangle does not depend on the order of the tests.
                assert!(g.t == w.t || (g.t - w.t).abs() <= 1e-6 * w.t, "ray {o} {d}: {g:?} vs {w:?}");
                if g.tri == w.tri {
                    assert_eq!(g, w);
                }
                hits += 1;
            }
            (g, w) => assert_eq!(g, w, "ray {o} {d}"),
        }
        assert_eq!(bvh.occluded(o, d, t_max, skip.clone()), want.is_some(), "any-hit of ray {o} {d}");
    }
    hits
}

fn random_rays(n: usize, seed: u64, spread: f32) -> Vec<(Vec3, Vec3, f32)> {
    let mut rng = test_rng(seed, 1.0);
    (0..n)
        .map(|i| {
            let o = Vec3::new(rng(), rng(), rng()) * spread;
            // Some directions with zero components, to exercise the slab test's ±∞.
            let mut d = Vec3::new(rng(), rng(), rng());
            if i % 5 == 0 {
                d[i % 3] = 0.0;
            }
            let t_max = if i % 3 == 0 { 4.0 + rng() * 3.0 } else { f32::INFINITY };
            (o, d * (1.0 + rng().abs() * 3.0), t_max)
        })
        .collect()
}

#[test]
fn closest_and_any_hit_equal_brute_force_on_a_random_soup() {
    let (p, tris) = soup(3000, 1.5, 1);
    let hits = agree_with_brute_force(&p, &tris, &random_rays(3000, 2, 12.0), 0..0);
    assert!(hits > 1000, "{hits} hits: too few to test anything");
}

#[test]
fn closest_and_any_hit_equal_brute_force_on_a_tessellated_sphere() {
    let (p, tris) = uv_sphere(Vec3::new(0.3, -0.2, 0.1), 48, 24);
    let mut rays = random_rays(2000, 3, 4.0);
    // Rays towards the sphere's centre from outside it (grazing and head-on) and from inside.
    let mut rng = test_rng(4, 1.0);
    for _ in 0..2000 {
        let o = Vec3::new(rng(), rng(), rng()) * 5.0;
        let target = Vec3::new(0.3, -0.2, 0.1) + Vec3::new(rng(), rng(), rng()) * 2.2;
        rays.push((o, target - o, f32::INFINITY));
    }
    let hits = agree_with_brute_force(&p, &tris, &rays, 0..0);
    assert!(hits > 1500, "{hits}");
    // The mesh is closed and the test watertight: every ray from inside leaves through it.
    let bvh = Bvh::build(&p, &tris);
    for _ in 0..20_000 {
        let o = Vec3::new(0.3, -0.2, 0.1) + Vec3::new(rng(), rng(), rng()) * 1.0;
        let d = Vec3::new(rng(), rng(), rng());
        if d == Vec3::ZERO {
            continue;
        }
        assert!(bvh.closest_hit(o, d, f32::INFINITY, 0..0).is_some(), "ray {o} {d} escaped");
        assert!(bvh.occluded(o, d, f32::INFINITY, 0..0));
    }
}

#[test]
fn rays_in_the_plane_of_a_box_face_find_the_edges_there() {
    // A 16×16 grid of unit quads at y = 0: every leaf box has faces at integer x. Rays
    // with dir.x = 0 at integer x (or dir.z = 0 at integer z) run in such a face, where the slab distance is 0·∞.
    let p: Vec<Vec3> = (0..17 * 17).map(|i| Vec3::new((i % 17) as f32, 0.0, (i / 17) as f32)).collect();
    let mut tris = Vec::new();
    for j in 0..16 {
        for i in 0..16 {
            let v = |di: u32, dj: u32| (j + dj) * 17 + i + di;
            tris.push([v(0, 0), v(1, 0), v(1, 1)]);
            tris.push([v(0, 0), v(1, 1), v(0, 1)]);
        }
    }
    let mut rng = test_rng(12, 1.0);
    let rays: Vec<_> = (0..2000)
        .map(|i| {
            // In a face x = const or z = const (the slab test's first and last axis), aimed
            // so that the ray lands on the grid.
            let (face, along) = ((1 + i % 15) as f32, rng() * 3.0 + 8.0);
            let (down, across) = (-1.0 - rng().abs(), rng());
            if i % 2 == 0 {
                (Vec3::new(face, 5.0, along), Vec3::new(0.0, down, across), f32::INFINITY)
            } else {
                (Vec3::new(along, 5.0, face), Vec3::new(across, down, 0.0), f32::INFINITY)
            }
        })
        .collect();
    let hits = agree_with_brute_force(&p, &tris, &rays, 0..0);
    assert_eq!(hits, 2000, "every ray meets the grid along an edge");
}

#[test]
fn skip_ignores_a_range_of_triangles() {
    let (p, tris) = soup(500, 2.0, 5);
    let hits = agree_with_brute_force(&p, &tris, &random_rays(1000, 6, 12.0), 100..300);
    assert!(hits > 100, "{hits}");
    // Two stacked quads: skipping the near one reveals the far one.
    let p = [-1.0f32, 1.0]
        .iter()
        .flat_map(|&z| [Vec3::new(-1.0, -1.0, z), Vec3::new(1.0, -1.0, z), Vec3::new(1.0, 1.0, z), Vec3::new(-1.0, 1.0, z)])
        .collect::<Vec<_>>();
    let tris = [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
    let bvh = Bvh::build(&p, &tris);
    let (o, d) = (Vec3::new(0.2, 0.1, 5.0), -Vec3::Z);
    assert_eq!(bvh.closest_hit(o, d, f32::INFINITY, 0..0).map(|h| (h.t, h.tri)), Some((4.0, 2)));
    assert_eq!(bvh.closest_hit(o, d, f32::INFINITY, 2..4).map(|h| (h.t, h.tri)), Some((6.0, 0)));
    assert_eq!(bvh.closest_hit(o, d, f32::INFINITY, 0..4), None);
    assert!(bvh.occluded(o, d, 5.0, 0..2));
    assert!(!bvh.occluded(o, d, 5.0, 2..4));
    assert!(!bvh.occluded(o, d, 4.0, 0..0), "t_max is an open bound");
}

#[test]
fn empty_and_degenerate_input_hits_nothing() {
    let empty = Bvh::default();
    let built = Bvh::build(&[], &[]);
    assert_eq!(built, empty);
    let p = vec![Vec3::ZERO, Vec3::X, Vec3::new(2.0, 0.0, 0.0), Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Y, Vec3::new(f32::INFINITY, 1.0, 1.0)];
    // Collinear, coincident, NaN, infinite and out-of-range triangles.
    let tris = [[0, 1, 2], [1, 1, 4], [0, 3, 4], [0, 4, 5], [0, 1, 99]];
    let degenerate = Bvh::build(&p, &tris);
    for bvh in [empty, built, degenerate] {
        assert_eq!((bvh.node_count(), bvh.triangle_count(), bvh.depth()), (0, 0, 0));
        assert_eq!(bvh.bounds(), (Vec3::INFINITY, Vec3::NEG_INFINITY));
        let mut rng = test_rng(9, 1.0);
        for _ in 0..100 {
            let (o, d) = (Vec3::new(rng(), rng(), 1.0), Vec3::new(rng(), rng(), -1.0));
            assert_eq!(bvh.closest_hit(o, d, f32::INFINITY, 0..0), None);
            assert!(!bvh.occluded(o, d, f32::INFINITY, 0..0));
        }
    }
    // A valid triangle among them is kept and hit, with its original index.
    let mut tris = tris.to_vec();
    tris.push([0, 1, 4]);
    let bvh = Bvh::build(&p, &tris);
    assert_eq!((bvh.triangle_count(), bvh.depth()), (1, 1));
    assert_eq!(bvh.bounds(), (Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0)));
    let h = bvh.closest_hit(Vec3::new(0.25, 0.5, 1.0), -Vec3::Z, f32::INFINITY, 0..0).unwrap();
    assert_eq!(h, TriHit { t: 1.0, tri: 5, b1: 0.25, b2: 0.5 });
}

#[test]
fn build_is_deterministic() {
    // Large enough that the top splits run in parallel.
    let (p, tris) = soup(40_000, 0.5, 7);
    let a = Bvh::build(&p, &tris);
    let b = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap().install(|| Bvh::build(&p, &tris));
    let c = Bvh::build(&p, &tris);
    assert!(a.node_count() > 10_000);
    assert_eq!(a, b);
    assert_eq!(a, c);
}

#[test]
fn sah_tree_is_shallow_with_small_leaves() {
    let (p, tris) = soup(100_000, 0.2, 8);
    let bvh = Bvh::build(&p, &tris);
    assert_eq!(bvh.triangle_count(), 100_000);
    // log2(100k / 4) ≈ 14.6: a balanced tree is 16 deep; SAH trees are a little deeper.
    assert!(bvh.depth() <= 32, "depth {}", bvh.depth());
    assert!(bvh.nodes.iter().all(|n| n.count as usize <= MAX_LEAF));
    let leaves = bvh.nodes.iter().filter(|n| n.count > 0).count();
    assert_eq!(bvh.node_count(), 2 * leaves - 1);
    assert_eq!(bvh.nodes.iter().map(|n| n.count as usize).sum::<usize>(), 100_000);
    // Every child's box lies inside its parent's.
    for (i, n) in bvh.nodes.iter().enumerate() {
        if n.count == 0 {
            for c in [&bvh.nodes[i + 1], &bvh.nodes[n.index as usize]] {
                assert!(c.min.cmpge(n.min).all() && c.max.cmple(n.max).all());
            }
        }
    }
    // A sorted line of triangles of doubling size (a bad case for SAH) still stays below the stack.
    let p: Vec<Vec3> = (0..3000)
        .flat_map(|i| {
            let x = 1.01f32.powi(i);
            [Vec3::new(x, 0.0, 0.0), Vec3::new(x, 1.0, 0.0), Vec3::new(x, 0.0, 1.0)]
        })
        .collect();
    let tris: Vec<[u32; 3]> = (0..3000).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    let bvh = Bvh::build(&p, &tris);
    assert!(bvh.depth() <= STACK, "{}", bvh.depth());
}
