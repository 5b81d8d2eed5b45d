//! The edge-function walk of a triangle's bounding box within a strip: one sample at a time
//! in i64, or four (SSE2), eight (AVX2, `walk_avx2.rs`) or sixteen (AVX-512,
//! `walk_avx512.rs`) samples of a row at a time in i32 lanes when the edge values fit.

use super::edge::{Edges, MAX_WALK_LANES, SetupTri, depth_at, edges, row_span, small_edges};
use super::strip::StripVis;

/// The lane walk this CPU runs: sixteen AVX-512 lanes when detection finds AVX-512BW, eight
/// AVX2 lanes when it finds AVX2, else four SSE2 lanes. Chosen once per strip
/// ([`WalkWidth::detect`]); every width gives the same bits.
#[derive(Debug, Clone, Copy)]
pub(super) struct WalkWidth {
    #[cfg(target_arch = "x86_64")]
    pub(super) avx2: Option<crate::simd::avx2::Avx2>,
    /// Present when this CPU runs AVX-512BW: the listing walk then takes sixteen lanes.
    #[cfg(target_arch = "x86_64")]
    pub(super) avx512: Option<crate::simd::avx512::Avx512Bw>,
    /// Tests force the one-sample walk with this.
    one_sample: bool,
}

impl WalkWidth {
    /// The widest walk this CPU runs (in tests, the width the thread-local `WALK_WIDTH` asks for).
    pub(super) fn detect() -> WalkWidth {
        #[cfg(test)]
        let asked = tests::WALK_WIDTH.with(|w| w.get());
        #[cfg(not(test))]
        let asked = 0;
        WalkWidth {
            #[cfg(target_arch = "x86_64")]
            avx2: if asked == 0 || asked == 8 { crate::simd::Cpu::get().avx2() } else { None },
            #[cfg(target_arch = "x86_64")]
            avx512: if asked == 0 || asked == 16 { crate::simd::Cpu::get().avx512bw() } else { None },
            one_sample: asked == 1,
        }
    }
}

/// Edge walk of one triangle over its bounding box clipped to the strip: each covered
/// sample nearer than what the strip holds takes the triangle's depth and a new entry in
/// the owned-sample list (its screen-space barycentrics). Returns the covered samples.
///
/// Triangles whose edge values fit i32 over their box (small ones: every triangle of the
/// `sphere` bench) are walked four samples at a time ([`walk_lanes`]), or sixteen with
/// AVX-512BW or eight with AVX2 when the box is wider than four samples (`walk_avx512.rs`,
/// `walk_avx2.rs`); the others here, one row span at a time.
///
/// Before, the walk resolved at the depth test: a `divss` on the path of every passing
/// sample (perf: a quarter of the walk's time stalled on it) and 16-byte samples cleared
/// per strip. Now it lists the screen-space barycentrics and the depth is the only per-sample
/// word cleared; the measurements are in docs/performance.md.
#[inline(always)]
pub(super) fn walk(t: &SetupTri, out: &mut StripVis, width: WalkWidth) -> u64 {
    let (sy0, sy1) = (out.y0 as i32, (out.y0 + out.rows) as i32 - 1);
    let (bx0, by0, bx1, by1) = (t.bbox[0], t.bbox[1].max(sy0), t.bbox[2], t.bbox[3].min(sy1));
    // The owned-sample list grows by at most the box's samples: room made once, written by index.
    out.reserve(((bx1 - bx0 + 1).max(0) * (by1 - by0 + 1).max(0)) as usize);
    if by0 > by1 || bx0 > bx1 {
        return 0;
    }
    let bbox = [bx0, by0, bx1, by1];
    if !width.one_sample
        && let Some(e) = small_edges(t, bx0, by0)
    {
        return walk_fitting(t, out, bbox, e, width);
    }
    let Edges { mut e_row, step_x, step_y, bias } = edges(t, bx0, by0);
    // Edge values at the corners of the box (widened by the lanes past its right end) bound
    // every value the walk computes (each is linear in x and y): within ±2^30, i32 lanes hold
    // them exactly.
    let (wide_x, tall_y) = ((bx1 - bx0) as i64 + 2 * MAX_WALK_LANES as i64, (by1 - by0) as i64 + 1);
    // (Written out: the arrays' `map` here was once left out of line, a call per triangle.)
    let fits = (0..3).all(|i| {
        let (e, dx, dy) = (e_row[i], step_x[i] * wide_x, step_y[i] * tall_y);
        [e, e + dx, e + dy, e + dx + dy].iter().all(|e| e.abs() < 1 << 30)
    });
    if fits && !width.one_sample {
        let to_i32 = |a: [i64; 3]| [a[0] as i32, a[1] as i32, a[2] as i32];
        return walk_fitting(t, out, bbox, [to_i32(e_row), to_i32(step_x), to_i32(step_y), to_i32(bias)], width);
    }
    #[cfg(target_arch = "x86_64")]
    if let (Some(t512), false) = (width.avx512, width.one_sample) {
        return super::walk_avx512::walk_spans16(t512, t, out, bbox, Edges { e_row, step_x, step_y, bias });
    }
    let mut n = out.listed;
    let depth = &mut out.depth[..];
    let (index, list_l1, list_l2) = (&mut out.index[..], &mut out.l1[..], &mut out.l2[..]);
    let mut covered = 0u64;
    let last = (bx1 - bx0) as i64;
    for y in by0..=by1 {
        // The covered samples of a row are contiguous (each edge function is linear along the
        // row, so the inside set is an intersection of intervals), solved from the edges
        // (the triangles here are large: a floor spans the image, and testing each sample
        // from the box's left edge cost a test per sample left of the span).
        let (lo, hi) = row_span(&e_row, &step_x, &bias, last);
        // An empty span's `lo` may be far past the box (and past i32).
        let (lo, hi) = if lo <= hi { (lo as i32, hi as i32) } else { (1, 0) };
        let mut e = [0, 1, 2].map(|i| e_row[i] + step_x[i] * lo as i64);
        let row = ((y - sy0) as u32 * out.width) as usize;
        for x in bx0 + lo..=bx0 + hi {
            covered += 1;
            // Screen-space barycentrics of vertices 1 and 2, and the depth they interpolate.
            let l1 = e[1] as f32 * t.inv_area;
            let l2 = e[2] as f32 * t.inv_area;
            let z = depth_at(&t.z, l1, l2);
            // Reversed z: larger is nearer. The nearer sample becomes this triangle's.
            let i = row + x as usize;
            let d = &mut depth[i];
            if z > *d {
                *d = z;
                (index[n], list_l1[n], list_l2[n]) = (i as u32, l1, l2);
                n += 1;
            }
            for i in 0..3 {
                e[i] += step_x[i];
            }
        }
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
    }
    out.listed = n;
    covered
}

/// The lane walks of a triangle whose edge values fit i32 over its box (`[e_row, step_x,
/// step_y, bias]` at the box's first sample): a box narrower than four samples one group of
/// four lanes a row ([`walk_narrow`]); a wider one sixteen lanes at a time with AVX-512BW
/// (`walk_avx512.rs`), eight with AVX2 (`walk_avx2.rs`), else four.
#[inline(always)]
fn walk_fitting(t: &SetupTri, out: &mut StripVis, bbox: [i32; 4], [e_row, step_x, step_y, bias]: [[i32; 3]; 4], width: WalkWidth) -> u64 {
    let narrow = bbox[2] - bbox[0] < WALK_LANES as i32;
    if narrow {
        return walk_narrow(t, out, bbox, [e_row, step_x, step_y, bias]);
    }
    // Sixteen or eight lanes pay for boxes wider than four samples (a call across the
    // AVX-512 or AVX2 boundary); the four-lane walks inline here.
    #[cfg(target_arch = "x86_64")]
    if let Some(avx512) = width.avx512 {
        return super::walk_avx512::walk_lanes16(avx512, t, out, bbox, e_row, step_x, step_y, bias);
    }
    #[cfg(target_arch = "x86_64")]
    if let Some(avx2) = width.avx2 {
        return super::walk_avx2::walk_lanes8(avx2, t, out, bbox, e_row, step_x, step_y, bias);
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = width;
    walk_lanes(t, out, bbox, e_row, step_x, step_y, bias)
}

/// [`walk_lanes`] for a box narrower than four samples: each row is one group of four lanes
/// from the box's left edge, tested once (the general walk first finds the row's span, then
/// starts its lanes there: two groups a row). The same samples, depths, barycentrics and
/// entries in the same order: each lane computes its own sample's values, and the nearer
/// lanes are listed in x order.
#[inline(always)]
fn walk_narrow(t: &SetupTri, out: &mut StripVis, [bx0, by0, bx1, by1]: [i32; 4], edges: [[i32; 3]; 4]) -> u64 {
    let [mut e_row, step_x, step_y, bias] = edges;
    use wide::{f32x4, i32x4};
    let off = [0, 1, 2].map(|i| i32x4::new([bias[i], bias[i] + step_x[i], bias[i] + 2 * step_x[i], bias[i] + 3 * step_x[i]]));
    let (inv_area, z0) = (f32x4::splat(t.inv_area), f32x4::splat(t.z[0]));
    let (dz1, dz2) = (f32x4::splat(t.z[1] - t.z[0]), f32x4::splat(t.z[2] - t.z[0]));
    let in_box = 0b1111u32 >> (3 - (bx1 - bx0));
    let mut n = out.listed;
    let (width, sy0) = (out.width as usize, out.y0 as i32);
    let depth = &mut out.depth[..];
    let (index, list_l1, list_l2) = (&mut out.index[..], &mut out.l1[..], &mut out.l2[..]);
    let mut covered = 0u64;
    for y in by0..=by1 {
        // Biased edge values of the row's four samples (≥ 0 inside: no sign bit).
        let e = [0, 1, 2].map(|i| i32x4::splat(e_row[i]) + off[i]);
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
        let inside = !(e[0] | e[1] | e[2]).to_bitmask() & in_box;
        if inside == 0 {
            continue;
        }
        covered += inside.count_ones() as u64;
        // The unbiased edge values: barycentrics and depth as `depth_at`.
        let l1 = (e[1] - i32x4::splat(bias[1])).round_float() * inv_area;
        let l2 = (e[2] - i32x4::splat(bias[2])).round_float() * inv_area;
        let z = z0 + l1 * dz1 + l2 * dz2;
        let i = (y - sy0) as usize * width + bx0 as usize;
        let d = f32x4::new(depth[i..i + WALK_LANES].try_into().expect("four samples"));
        let nearer = inside & z.simd_gt(d).to_bitmask();
        if nearer != 0 {
            let keep: f32x4 = wide::bytemuck::cast(lane_mask(nearer));
            depth[i..i + WALK_LANES].copy_from_slice(&keep.bitselect(z, d).to_array());
            let (l1, l2) = (l1.to_array(), l2.to_array());
            for k in 0..WALK_LANES {
                (index[n], list_l1[n], list_l2[n]) = ((i + k) as u32, l1[k], l2[k]);
                n += (nearer >> k) as usize & 1;
            }
        }
    }
    out.listed = n;
    covered
}

/// Samples of a row the lane walk tests at once.
const WALK_LANES: usize = 4;

/// [`walk`] four samples of a row at a time, for a triangle whose edge values fit i32 over its
/// box (`e_row`, `step_x`, `step_y` and `bias` as [`walk`] computes them, at the box's first
/// sample): the same samples, depths, barycentrics and entries in the same order. Each lane
/// computes what the one-sample walk computes for its sample (an i32 edge value converts to
/// the f32 an i64 one does: the same integer, rounded once), and lanes past the box are
/// masked off (their depths loaded and stored back unchanged).
#[allow(clippy::too_many_arguments)]
fn walk_lanes(
    t: &SetupTri,
    out: &mut StripVis,
    [bx0, by0, bx1, by1]: [i32; 4],
    e_row: [i32; 3],
    step_x: [i32; 3],
    step_y: [i32; 3],
    bias: [i32; 3],
) -> u64 {
    use wide::{f32x4, i32x4};
    let lane = |s: i32| i32x4::new([0, s, 2 * s, 3 * s]);
    let (off, step4) = (step_x.map(lane), step_x.map(|s| i32x4::splat(WALK_LANES as i32 * s)));
    let bias = bias.map(i32x4::splat);
    let inv_area = f32x4::splat(t.inv_area);
    let (z0, dz1, dz2) = (f32x4::splat(t.z[0]), f32x4::splat(t.z[1] - t.z[0]), f32x4::splat(t.z[2] - t.z[0]));
    let sample = i32x4::new([0, 1, 2, 3]);
    let mut n = out.listed;
    let width = out.width as usize;
    let sy0 = out.y0 as i32;
    let depth = &mut out.depth[..];
    let (index, list_l1, list_l2) = (&mut out.index[..], &mut out.l1[..], &mut out.l2[..]);
    let mut covered = 0u64;
    let mut e_row = e_row;
    for y in by0..=by1 {
        let mut e = [0, 1, 2].map(|i| i32x4::splat(e_row[i]) + off[i]);
        let row = (y - sy0) as usize * width;
        let (mut x, mut aligned) = (bx0, false);
        while x <= bx1 {
            // Lanes inside every edge (biased edge values ≥ 0: no sign bit) and inside the box.
            let outside = ((e[0] + bias[0]) | (e[1] + bias[1]) | (e[2] + bias[2])).to_bitmask();
            let in_box = 0b1111 >> (3 - (bx1 - x).min(3));
            let inside = !outside & in_box;
            if !aligned {
                if inside != 0 {
                    // The row's span starts at lane k: start the lanes there, so that its
                    // bundles are full but for the last and each one's inside lanes come first.
                    let k = inside.trailing_zeros() as i32;
                    aligned = true;
                    for i in 0..3 {
                        e[i] += i32x4::splat(k * step_x[i]);
                    }
                    x += k;
                    continue;
                }
            } else {
                // The covered samples of a row are contiguous from the span's start (lane 0 of
                // the first aligned bundle): the inside lanes are the first `m`.
                let m = (!inside).trailing_zeros() as usize;
                if m == 0 {
                    break;
                }
                covered += m as u64;
                // Screen-space barycentrics of vertices 1 and 2 and their depth, as `depth_at`.
                let l1 = e[1].round_float() * inv_area;
                let l2 = e[2].round_float() * inv_area;
                let z = z0 + l1 * dz1 + l2 * dz2;
                let i = row + x as usize;
                let d = f32x4::new(depth[i..i + WALK_LANES].try_into().expect("four samples"));
                // Reversed z: the nearer samples become this triangle's.
                let nearer = inside & z.simd_gt(d).to_bitmask();
                if nearer != 0 {
                    let keep: f32x4 = wide::bytemuck::cast(lane_mask(nearer));
                    depth[i..i + WALK_LANES].copy_from_slice(&keep.bitselect(z, d).to_array());
                    let entries = (i32x4::splat(i as i32) + sample).to_array().map(|v| v as u32);
                    let (l1, l2) = (l1.to_array(), l2.to_array());
                    if nearer & (nearer + 1) == 0 {
                        // The first lanes (no overdraw): all four written, the nearer ones kept.
                        index[n..n + WALK_LANES].copy_from_slice(&entries);
                        list_l1[n..n + WALK_LANES].copy_from_slice(&l1);
                        list_l2[n..n + WALK_LANES].copy_from_slice(&l2);
                        n += (!nearer).trailing_zeros() as usize;
                    } else {
                        for k in 0..WALK_LANES {
                            (index[n], list_l1[n], list_l2[n]) = (entries[k], l1[k], l2[k]);
                            n += (nearer >> k) as usize & 1;
                        }
                    }
                }
                if m < WALK_LANES {
                    break;
                }
            }
            for i in 0..3 {
                e[i] += step4[i];
            }
            x += WALK_LANES as i32;
        }
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
    }
    out.listed = n;
    covered
}

/// Lanes of a four-bit set as an i32 mask (lane k all ones where bit k is set).
#[inline(always)]
fn lane_mask(bits: u32) -> wide::i32x4 {
    let bit = wide::i32x4::new([1, 2, 4, 8]);
    (wide::i32x4::splat(bits as i32) & bit).simd_eq(bit)
}

#[cfg(test)]
mod tests {
    use crate::raster::tests::{H, W, camera};
    use crate::raster::{CullMode, NO_TRIANGLE, StripVis, VisSample, rasterize, setup};
    use glam::{Vec2, Vec3, Vec4};

    thread_local! {
        /// Set by a test: strips rasterized on this thread walk this many samples at a time
        /// (1, 4, 8 or 16; 0: the widest this CPU runs).
        pub(super) static WALK_WIDTH: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
    }

    /// Clip-space vertex (w = 1) for a sample-grid position.
    fn at(sx: f32, sy: f32) -> Vec4 {
        Vec4::new(2.0 * sx / W as f32 - 1.0, 1.0 - 2.0 * sy / H as f32, 0.5, 1.0)
    }

    fn covered(v: &[Vec4], tris: &[[u32; 3]]) -> Vec<bool> {
        rasterize(v, tris, W, H, CullMode::None).samples.iter().map(|s| s.tri != NO_TRIANGLE).collect()
    }

    /// Counts, per sample, how many triangles of a mesh cover it (each rasterized alone).
    fn cover_counts(v: &[Vec4], tris: &[[u32; 3]]) -> Vec<u32> {
        let mut counts = vec![0u32; (W * H) as usize];
        for t in tris {
            for (c, hit) in counts.iter_mut().zip(covered(v, &[*t])) {
                *c += hit as u32;
            }
        }
        counts
    }

    #[test]
    fn fan_covers_every_sample_exactly_once() {
        // A fan around a centre that sits exactly on a sample centre, with rim vertices on
        // sample centres and half-way points, so many edges pass exactly through samples.
        let centre = Vec2::new(32.5, 24.5);
        let mut v = vec![at(centre.x, centre.y)];
        let rim = [(12.5, 24.5), (16.0, 8.5), (32.5, 4.5), (50.5, 10.0), (56.5, 24.5), (48.5, 40.5), (32.5, 44.5), (14.5, 38.5)];
        for (x, y) in rim {
            v.push(at(x, y));
        }
        let n = rim.len() as u32;
        // Counter-clockwise on screen with y down is clockwise in NDC; winding does not matter with CullMode::None.
        let tris: Vec<[u32; 3]> = (0..n).map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect();
        let counts = cover_counts(&v, &tris);
        assert!(counts.iter().all(|&c| c <= 1), "a sample is covered twice");
        // No holes: every sample strictly inside the (convex) rim polygon is covered.
        let inside = |p: Vec2| {
            (0..rim.len()).all(|i| {
                let a = Vec2::from(rim[i]);
                let b = Vec2::from(rim[(i + 1) % rim.len()]);
                (b - a).perp_dot(p - a) > 1e-3
            })
        };
        let mut interior = 0;
        for y in 0..H {
            for x in 0..W {
                let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                if inside(p) {
                    interior += 1;
                    assert_eq!(counts[(y * W + x) as usize], 1, "hole at {x},{y}");
                }
            }
        }
        assert!(interior > 500);
    }

    #[test]
    fn quad_split_along_its_diagonal_covers_each_sample_once() {
        // Corners on sample centres: the top and left edges are in, bottom and right out.
        let v = [at(4.5, 4.5), at(20.5, 4.5), at(20.5, 12.5), at(4.5, 12.5)];
        let counts = cover_counts(&v, &[[0, 1, 2], [0, 2, 3]]);
        assert!(counts.iter().all(|&c| c <= 1));
        let total: u32 = counts.iter().sum();
        // Top-left rule: columns 4..20 (16) × rows 4..12 (8).
        assert_eq!(total, 16 * 8);
        assert_eq!(counts[(4 * W + 4) as usize], 1, "top-left corner sample belongs to the quad");
        assert_eq!(counts[(12 * W + 4) as usize], 0, "bottom edge is excluded");
        assert_eq!(counts[(4 * W + 20) as usize], 0, "right edge is excluded");
    }

    #[test]
    fn nearer_triangle_wins_regardless_of_order() {
        let near = [Vec4::new(-1.0, -1.0, 0.5, 1.0), Vec4::new(1.0, -1.0, 0.5, 1.0), Vec4::new(0.0, 1.0, 0.5, 1.0)];
        let far = near.map(|v| Vec4::new(v.x, v.y, 0.2, 1.0));
        let v: Vec<Vec4> = near.iter().chain(far.iter()).copied().collect();
        for tris in [[[0u32, 1, 2], [3, 4, 5]], [[3, 4, 5], [0, 1, 2]]] {
            let vis = rasterize(&v, &tris, W, H, CullMode::Back);
            let centre = vis.samples[(H / 2 * W + W / 2) as usize];
            assert_eq!(tris[centre.tri as usize], [0, 1, 2]);
            assert!((centre.depth - 0.5).abs() < 1e-6);
        }
    }

    /// A sphere (small triangles: the lane walks) and a finer one (boxes under four samples
    /// wide: the narrow walk), with their back faces (overdraw), over a large floor quad
    /// (edge values past i32: the one-sample walk either way), in clip space.
    fn sphere_over_floor() -> (Vec<Vec4>, Vec<[u32; 3]>) {
        let cam = camera();
        let (mut clip, mut tris) = (Vec::new(), Vec::new());
        for (segments, rings, at) in [(40, 20, Vec3::new(0.0, 0.5, -2.0)), (200, 100, Vec3::new(1.2, 0.8, -3.0))] {
            let mesh = super::super::tests::uv_sphere(segments, rings);
            let vp = cam.view_projection() * glam::Mat4::from_translation(at);
            let base = clip.len() as u32;
            clip.extend(mesh.positions.iter().map(|p| vp * p.extend(1.0)));
            tris.extend(mesh.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        let floor = [Vec3::new(-9.0, 0.0, 1.0), Vec3::new(9.0, 0.0, 1.0), Vec3::new(9.0, 0.0, -30.0), Vec3::new(-9.0, 0.0, -30.0)];
        let base = clip.len() as u32;
        clip.extend(floor.iter().map(|p| cam.view_projection() * p.extend(1.0)));
        tris.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
        (clip, tris)
    }

    #[test]
    fn every_walk_width_gives_the_one_sample_walk() {
        let (clip, tris) = sphere_over_floor();
        let (w, h) = (W * 3, H * 3);
        let run = |width: usize| {
            WALK_WIDTH.with(|f| f.set(width));
            let setup = setup(&clip, &tris, w, h, 16, CullMode::None);
            let mut samples = vec![VisSample::EMPTY; (w * h) as usize];
            let (mut strip, mut stats) = (StripVis::default(), setup.stats);
            for (s, chunk) in samples.chunks_mut(16 * w as usize).enumerate() {
                stats += setup.rasterize_strip(s, &mut strip);
                strip.write_resolved(chunk);
            }
            WALK_WIDTH.with(|f| f.set(0));
            let bits: Vec<[u32; 4]> = samples.iter().map(|s| [s.tri, s.b1.to_bits(), s.b2.to_bits(), s.depth.to_bits()]).collect();
            (bits, stats)
        };
        let one = run(1);
        assert!(one.1.samples_rasterized > one.0.iter().filter(|s| s[0] != NO_TRIANGLE).count() as u64, "overdraw");
        assert_eq!(run(4), one, "four lanes");
        #[cfg(target_arch = "x86_64")]
        match crate::simd::Cpu::get().avx2() {
            Some(_) => assert_eq!(run(8), one, "eight lanes"),
            None => crate::simd::cpu::missing(crate::simd::Level::Avx2, "AVX2"),
        }
        #[cfg(target_arch = "x86_64")]
        match crate::simd::Cpu::get().avx512bw() {
            Some(_) => assert_eq!(run(16), one, "sixteen lanes"),
            None => crate::simd::cpu::missing(crate::simd::Level::Avx512, "AVX-512BW"),
        }
    }

    /// The depth-only walk covers exactly the samples the listing walk covers (the same
    /// top-left rule), with the nearest depth to a few ULP, on a sphere with overdraw over a
    /// floor whose edge values exceed i32.
    #[test]
    fn depth_only_walk_covers_the_same_samples() {
        let (clip, tris) = sphere_over_floor();
        let (w, h) = (W * 3, H * 3);
        let setup = setup(&clip, &tris, w, h, 16, CullMode::None);
        let mut strip = StripVis::default();
        let mut depth = vec![0f32; 16 * w as usize];
        let mut covered = 0;
        for s in 0..setup.strip_count() {
            let a = setup.rasterize_strip(s, &mut strip);
            let b = setup.depth_strip(s, crate::raster::DepthLayout::Rows { width: w as usize }, &mut depth);
            assert_eq!(a.samples_rasterized, b.samples_rasterized, "strip {s}");
            for (i, (&want, &got)) in strip.depth().iter().zip(&depth).enumerate() {
                assert_eq!(want > 0.0, got > 0.0, "strip {s} sample {i}");
                assert!((want - got).abs() <= 1e-5 * want.abs().max(1e-3), "strip {s} sample {i}: {want} vs {got}");
                covered += (got > 0.0) as u32;
            }
        }
        assert!(covered > 1000);
    }

    /// The depth-only walk gives the same bits at every width (its fills vectorized to four
    /// or eight lanes), in rows and in tiles.
    #[test]
    fn depth_walk_widths_agree_bit_for_bit() {
        let (clip, tris) = sphere_over_floor();
        let (w, h) = (W * 3, H * 3);
        let setup = setup(&clip, &tris, w, h, 16, CullMode::None);
        let tiles = (w as usize).div_ceil(crate::raster::DEPTH_TILE);
        let run = |width: usize, layout: crate::raster::DepthLayout, per_strip: usize| {
            WALK_WIDTH.with(|f| f.set(width));
            let mut depth = vec![0f32; per_strip * setup.strip_count()];
            for (s, out) in depth.chunks_mut(per_strip).enumerate() {
                setup.depth_strip(s, layout, out);
            }
            WALK_WIDTH.with(|f| f.set(0));
            depth.iter().map(|d| d.to_bits()).collect::<Vec<u32>>()
        };
        let rows = (crate::raster::DepthLayout::Rows { width: w as usize }, 16 * w as usize);
        let tiled = (crate::raster::DepthLayout::Tiles { tiles }, 16 * tiles * crate::raster::DEPTH_TILE);
        for (layout, per_strip) in [rows, tiled] {
            let four = run(4, layout, per_strip);
            assert!(four.iter().filter(|&&d| d != 0).count() > 1000, "{layout:?}: covered");
            #[cfg(target_arch = "x86_64")]
            match crate::simd::Cpu::get().avx2() {
                Some(_) => assert_eq!(run(8, layout, per_strip), four, "{layout:?}: eight lanes"),
                None => crate::simd::cpu::missing(crate::simd::Level::Avx2, "AVX2"),
            }
            // Sixteen lanes alone (small boxes; the others take the reference), then with
            // eight for the rest, as a render runs them.
            #[cfg(target_arch = "x86_64")]
            match crate::simd::Cpu::get().avx512bw() {
                Some(_) => {
                    assert_eq!(run(16, layout, per_strip), four, "{layout:?}: sixteen lanes");
                    assert_eq!(run(0, layout, per_strip), four, "{layout:?}: every width");
                }
                None => crate::simd::cpu::missing(crate::simd::Level::Avx512, "AVX-512BW"),
            }
        }
    }
}
