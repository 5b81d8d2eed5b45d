//! Tests of the BVH: brute-force agreement, the wide tree and the packets against the scalar
//! reference bit for bit (every lane width this CPU has), skips, degenerate input,
//! determinism, depth.
use super::packet::Query;
use super::reference::Reference;
use super::wide::{LEAF, Node8, WIDTH};
use super::*;
use crate::geometry::triangle::{RayPrecomp, intersect};
use crate::simd::lanes::{F32x4, LaneTask, test_rng};
use crate::simd::pair::Pair;

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

/// The nearest hit by testing every triangle up to t_max (of equal t, the smallest index).
fn brute_closest(p: &[Vec3], tris: &[[u32; 3]], o: Vec3, d: Vec3, t_max: f32, skip: Range<u32>) -> Option<TriHit> {
    let pre = RayPrecomp::new(d);
    let mut best: Option<TriHit> = None;
    for (i, t) in tris.iter().enumerate() {
        let [a, b, c] = t.map(|k| p.get(k as usize).copied().unwrap_or(Vec3::NAN));
        if skip.contains(&(i as u32)) || (b - a).cross(c - a) == Vec3::ZERO {
            continue;
        }
        if let Some((t, b1, b2)) = intersect(&pre, o, a, b, c, t_max)
            && best.is_none_or(|h| t < h.t)
        {
            best = Some(TriHit { t, tri: i as u32, b1, b2 });
        }
    }
    best
}

/// Checks closest_hit and occluded against brute force and the scalar reference on `rays`
/// (the reference bit for bit), and the packets against the single rays at every lane
/// width; returns the number of hits.
fn agree_with_brute_force(p: &[Vec3], tris: &[[u32; 3]], rays: &[(Vec3, Vec3, f32)], skip: Range<u32>) -> usize {
    let bvh = Bvh::build(p, tris);
    let reference = Reference::build(p, tris);
    let mut hits = 0;
    for &(o, d, t_max) in rays {
        let got = bvh.closest_hit(o, d, t_max, skip.clone());
        let want = brute_closest(p, tris, o, d, t_max, skip.clone());
        assert_eq!(got, want, "ray {o} {d} {t_max}");
        assert_eq!(got, reference.closest_hit(o, d, t_max, skip.clone()), "ray {o} {d} {t_max}");
        hits += got.is_some() as usize;
        assert_eq!(bvh.occluded(o, d, t_max, skip.clone()), want.is_some(), "any-hit of ray {o} {d}");
        assert_eq!(reference.occluded(o, d, t_max, skip.clone()), want.is_some(), "reference any-hit of ray {o} {d}");
    }
    let skips = vec![skip; rays.len()];
    packets_agree(&bvh, rays, &skips);
    hits
}

/// The results of `q` at every lane width this CPU has (four SSE lanes, two pairs of them,
/// sixteen AVX or AVX-512F lanes), saying which widths it skipped.
fn at_every_width<const ANY: bool>(q: Query<'_, ANY>) -> Vec<[Option<TriHit>; RayPacket::MAX]> {
    let mut all = vec![q.run::<F32x4, F32x4>(), q.run::<Pair<F32x4>, F32x4>()];
    #[cfg(target_arch = "x86_64")]
    {
        let cpu = crate::simd::Cpu::get();
        match cpu.avx() {
            Some(t) => all.push(t.run(q)),
            None => crate::simd::cpu::missing(crate::simd::Level::Avx, "AVX"),
        }
        match cpu.avx512() {
            Some(t) => all.push(t.run(q)),
            None => crate::simd::cpu::missing(crate::simd::Level::Avx512, "AVX-512"),
        }
    }
    all
}

/// Traces `rays` in packets of sixteen (every lane, then a pseudo-random half of them) at
/// every lane width and checks each lane against the single ray, bit for bit.
fn packets_agree(bvh: &Bvh, rays: &[(Vec3, Vec3, f32)], skips: &[Range<u32>]) {
    let mut rng = test_rng(99, 1.0);
    for (chunk, skips) in rays.chunks(RayPacket::MAX).zip(skips.chunks(RayPacket::MAX)) {
        let mut packet = RayPacket::default();
        for (i, (&(o, d, t_max), skip)) in chunk.iter().zip(skips).enumerate() {
            packet.set(i, o, d, t_max, skip.clone());
        }
        let full = ((1u32 << chunk.len()) - 1) as u16;
        let half = full & (rng().to_bits() as u16 | 1);
        for active in [full, half] {
            let closest = at_every_width(Query::<false> { tree: &bvh.tree, packet: &packet, active });
            let any = at_every_width(Query::<true> { tree: &bvh.tree, packet: &packet, active });
            for (i, (&(o, d, t_max), skip)) in chunk.iter().zip(skips).enumerate() {
                let on = active >> i & 1 == 1;
                let want = bvh.closest_hit(o, d, t_max, skip.clone()).filter(|_| on);
                for (w, got) in closest.iter().enumerate() {
                    assert_eq!(got[i], want, "width {w}, lane {i}: ray {o} {d} {t_max}");
                }
                for (w, got) in any.iter().enumerate() {
                    assert_eq!(got[i].is_some(), want.is_some(), "any-hit, width {w}, lane {i}: ray {o} {d} {t_max}");
                }
            }
            assert_eq!(bvh.occluded_packet(&packet, active), any[0].iter().enumerate().fold(0, |m, (i, h)| m | (h.is_some() as u16) << i));
            assert_eq!(bvh.closest_packet(&packet, active), closest[0]);
        }
    }
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

/// Rays aimed at the vertices, edge midpoints and centres of `tris` from random points
/// `spread` around, half of them through the target and on (t_max ∞), half stopping at it
/// (t_max 1, the open bound).
fn aimed_rays(p: &[Vec3], tris: &[[u32; 3]], n: usize, seed: u64, spread: f32) -> Vec<(Vec3, Vec3, f32)> {
    let mut rng = test_rng(seed, 1.0);
    (0..n)
        .map(|i| {
            let [a, b, c] = tris[i % tris.len()].map(|k| p[k as usize]);
            let target = match i % 4 {
                0 => a,
                1 => (a + b) * 0.5,
                2 => (a + b + c) / 3.0,
                _ => b + (c - b) * (rng() * 0.5 + 0.5),
            };
            let o = target + Vec3::new(rng(), rng(), rng()) * spread;
            (o, target - o, if i % 2 == 0 { f32::INFINITY } else { 1.0 })
        })
        .collect()
}

#[test]
fn wide_tree_and_packets_equal_the_scalar_reference_on_adversarial_rays() {
    // A closed sphere and a flat grid: shared edges and vertices, boxes with zero extent.
    let (mut p, mut tris) = uv_sphere(Vec3::new(0.3, -0.2, 0.1), 32, 16);
    let base = p.len() as u32;
    p.extend((0..9 * 9).map(|i| Vec3::new((i % 9) as f32 - 4.0, -2.5, (i / 9) as f32 - 4.0)));
    for j in 0..8 {
        for i in 0..8 {
            let v = |di: u32, dj: u32| base + (j + dj) * 9 + i + di;
            tris.push([v(0, 0), v(1, 0), v(1, 1)]);
            tris.push([v(0, 0), v(1, 1), v(0, 1)]);
        }
    }
    // Degenerate triangles among them (left out), and a duplicate of a triangle (a tie in t).
    tris.push([0, 0, 1]);
    tris.push([base, base + 1, base + 2]);
    tris.push(tris[40]);
    let mut rays = aimed_rays(&p, &tris[..tris.len() - 3], 4000, 21, 6.0);
    let mut rng = test_rng(22, 1.0);
    for i in 0..2000 {
        // Axis-parallel rays (two zero components) through grid lines and vertices, rays in
        // the grid's plane, and origins inside the sphere's boxes.
        let axis = i % 3;
        let mut d = Vec3::ZERO;
        d[axis] = if i % 2 == 0 { 1.0 } else { -1.0 };
        let snap = |x: f32| if i % 4 < 2 { (x * 4.0).round() / 4.0 } else { x.round() };
        let o = Vec3::new(snap(rng() * 4.0), snap(rng() * 3.0), snap(rng() * 4.0));
        rays.push((o, d, f32::INFINITY));
        rays.push((Vec3::new(rng() * 4.0, -2.5, rng() * 4.0), Vec3::new(rng(), 0.0, rng()), f32::INFINITY));
        rays.push((Vec3::new(0.3, -0.2, 0.1) + Vec3::new(rng(), rng(), rng()) * 1.9, Vec3::new(rng(), rng(), rng()), 2.0 + rng()));
    }
    // Grazing rays along the sphere's silhouette, and non-finite rays.
    for i in 0..500 {
        let n = Vec3::new(rng(), rng(), rng()).normalize_or(Vec3::X);
        let t = n.any_orthogonal_vector().normalize();
        rays.push((Vec3::new(0.3, -0.2, 0.1) + n * 2.0 - t * 5.0, t + n * (i as f32 * 1e-6), f32::INFINITY));
    }
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        rays.push((Vec3::new(bad, 0.0, 0.0), Vec3::X, f32::INFINITY));
        rays.push((Vec3::ZERO, Vec3::new(bad, 1.0, 0.0), f32::INFINITY));
        rays.push((Vec3::ZERO, Vec3::Y, bad));
        rays.push((Vec3::ZERO, Vec3::splat(bad), f32::INFINITY));
    }
    rays.push((Vec3::new(0.3, 5.0, 0.1), Vec3::ZERO, f32::INFINITY));
    let hits = agree_with_brute_force(&p, &tris, &rays, 0..0);
    assert!(hits > 5000, "{hits}");
    // The duplicate: the same t from two triangles, the smaller index wins.
    let [a, b, c] = tris[40].map(|k| p[k as usize]);
    let target = (a + b + c) / 3.0;
    let o = target + (b - a).cross(c - a).normalize() * 3.0;
    let bvh = Bvh::build(&p, &tris);
    assert_eq!(bvh.closest_hit(o, target - o, f32::INFINITY, 0..0).map(|h| h.tri), Some(40));
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
    let rays = random_rays(1000, 6, 12.0);
    let hits = agree_with_brute_force(&p, &tris, &rays, 100..300);
    assert!(hits > 100, "{hits}");
    // A different skip per lane of a packet.
    let skips: Vec<Range<u32>> = (0..rays.len() as u32).map(|i| (i * 7) % 500..(i * 7) % 500 + i % 40).collect();
    packets_agree(&Bvh::build(&p, &tris), &rays, &skips);
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
    let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
    let b = pool(1).install(|| Bvh::build(&p, &tris));
    let c = pool(3).install(|| Bvh::build(&p, &tris));
    assert!(a.node_count() > 10_000);
    assert_eq!(a, b);
    assert_eq!(a, c);
    // The binary tree too (the parallel build moves the right halves' nodes).
    assert_eq!(pool(1).install(|| build::build(&p, &tris)), pool(3).install(|| build::build(&p, &tris)));
}

#[test]
fn sah_tree_is_shallow_with_small_leaves() {
    let (p, tris) = soup(100_000, 0.2, 8);
    let bvh = Bvh::build(&p, &tris);
    assert_eq!(bvh.triangle_count(), 100_000);
    // log8(100k / 4) ≈ 4.9: a balanced eight-wide tree is 6 deep; SAH trees are a little deeper.
    assert!(bvh.depth() <= 10, "depth {}", bvh.depth());
    let w = &bvh.tree;
    assert_eq!(w.blocks.iter().flat_map(|b| b.ids).filter(|&i| i != u32::MAX).count(), 100_000);
    assert_eq!(bvh.node_count(), w.nodes.len() + w.blocks.len());
    // Every child's box lies inside its parent's, each child is referenced once, and each
    // octant's order lists every slot once.
    let mut seen = vec![0u32; w.nodes.len() + w.blocks.len()];
    for n in &w.nodes {
        let valid = Node8::valid(n.order[0]);
        for s in 0..WIDTH {
            if valid >> s & 1 == 0 {
                continue;
            }
            let c = n.child[s];
            let k = if c & LEAF == 0 { c as usize } else { w.nodes.len() + (c & !LEAF) as usize };
            seen[k] += 1;
            if c & LEAF == 0 {
                let child = &w.nodes[c as usize];
                for (axis, plane) in child.planes.iter().enumerate() {
                    let lo = axis % 2 == 0;
                    for (cs, &x) in plane.iter().enumerate() {
                        if Node8::valid(child.order[0]) >> cs & 1 == 1 {
                            let bound = n.planes[axis][s];
                            assert!(if lo { x >= bound } else { x <= bound });
                        }
                    }
                }
            }
        }
        for o in 0..8 {
            let mut slots: Vec<usize> = (0..WIDTH).map(|k| Node8::slot(n.order[o], k)).collect();
            slots.sort();
            assert_eq!(slots, (0..WIDTH).collect::<Vec<_>>());
            assert_eq!(Node8::valid(n.order[o]), valid);
        }
    }
    assert!(seen[1..].iter().all(|&c| c == 1));
    // A sorted line of triangles of doubling size (a bad case for SAH) still stays below the stack.
    let p: Vec<Vec3> = (0..3000)
        .flat_map(|i| {
            let x = 1.01f32.powi(i);
            [Vec3::new(x, 0.0, 0.0), Vec3::new(x, 1.0, 0.0), Vec3::new(x, 0.0, 1.0)]
        })
        .collect();
    let tris: Vec<[u32; 3]> = (0..3000).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    let bin = build::build(&p, &tris);
    assert!(bin.depth < 64, "{}", bin.depth);
    let bvh = Bvh::build(&p, &tris);
    assert!(bvh.depth() <= bin.depth);
    let rays: Vec<_> = (0..500).map(|i| (Vec3::new(i as f32 * 0.3, 0.2, -1.0), Vec3::new(0.01, 0.0, 1.0), f32::INFINITY)).collect();
    agree_with_brute_force(&p, &tris, &rays, 0..0);
}

#[test]
fn the_early_exit_never_drops_a_box_the_slab_test_keeps() {
    // `moves_away` must imply a slab-test miss, including zero, signed-zero, infinite and
    // NaN components; and it must answer often enough to matter.
    let mut rng = test_rng(31, 1.0);
    let special = [0.0, -0.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN, 1e-40, -1e-40, 3e38, -3e38];
    let mut away = 0;
    for i in 0..200_000 {
        let mut v = |k: usize| if (i + k).is_multiple_of(11) { special[(i / 11 + k) % special.len()] } else { rng() * 4.0 };
        let (o, d) = (Vec3::new(v(0), v(1), v(2)), Vec3::new(v(3), v(4), v(5)));
        let (a, b) = (Vec3::new(rng(), rng(), rng()), Vec3::new(rng(), rng(), rng()));
        let (min, max) = (a.min(b), a.max(b));
        let t_max = if i % 3 == 0 { f32::INFINITY } else { rng().abs() * 10.0 };
        if traverse::moves_away(o, d, min, max) {
            away += 1;
            assert!(!traverse::SlabRay::new(o, d).hits(min, max, t_max), "{o} {d} {min} {max} {t_max}");
        }
    }
    assert!(away > 50_000, "{away}");
}
