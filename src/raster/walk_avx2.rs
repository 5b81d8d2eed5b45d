//! [`walk_lanes`](super::walk) eight samples of a row at a time in AVX2 registers, for CPUs
//! with AVX2 (chosen at run time through the [`Avx2`] token).
//!
//! The same samples, depths, barycentrics and owned-sample entries in the same order as the
//! four-lane and one-sample walks: each lane's edge values are the exact i32 the narrower
//! walks compute, `vcvtdq2ps` rounds an i32 to f32 as `cvtdq2ps` and `as f32` do, and the
//! depth is `(z0 + l1·dz1) + l2·dz2` with separate `vmulps`/`vaddps` (no FMA is enabled), so
//! the bits match (tested: `every_walk_width_gives_the_one_sample_walk`).

use super::edge::SetupTri;
use super::strip::StripVis;
use crate::simd::avx2::Avx2;
use std::arch::x86_64::*;

/// Samples of a row the AVX2 walk tests at once.
pub(super) const LANES: usize = 8;

/// [`walk_lanes8_avx2`] for a CPU that has AVX2 (the token proves it).
#[allow(clippy::too_many_arguments)]
#[inline]
pub(super) fn walk_lanes8(
    _: Avx2,
    t: &SetupTri,
    out: &mut StripVis,
    bbox: [i32; 4],
    e_row: [i32; 3],
    step_x: [i32; 3],
    step_y: [i32; 3],
    bias: [i32; 3],
) -> u64 {
    // SAFETY: an `Avx2` token exists only when detection found every feature enabled below.
    unsafe { walk_lanes8_avx2(t, out, bbox, e_row, step_x, step_y, bias) }
}

/// The walk in eight lanes; see [`walk_lanes`](super::walk) for the algorithm, line for line.
#[allow(clippy::too_many_arguments)]
#[target_feature(enable = "avx2")]
fn walk_lanes8_avx2(
    t: &SetupTri,
    out: &mut StripVis,
    [bx0, by0, bx1, by1]: [i32; 4],
    mut e_row: [i32; 3],
    step_x: [i32; 3],
    step_y: [i32; 3],
    bias: [i32; 3],
) -> u64 {
    let lane = |s: i32| _mm256_setr_epi32(0, s, 2 * s, 3 * s, 4 * s, 5 * s, 6 * s, 7 * s);
    let (off, step8) = (step_x.map(lane), step_x.map(|s| _mm256_set1_epi32(LANES as i32 * s)));
    let bias = bias.map(|b| _mm256_set1_epi32(b));
    let inv_area = _mm256_set1_ps(t.inv_area);
    let (z0, dz1, dz2) = (_mm256_set1_ps(t.z[0]), _mm256_set1_ps(t.z[1] - t.z[0]), _mm256_set1_ps(t.z[2] - t.z[0]));
    let sample = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    let bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    let mut n = out.listed;
    let width = out.width as usize;
    let sy0 = out.y0 as i32;
    let depth = &mut out.depth[..];
    let (index, list_l1, list_l2) = (&mut out.index[..], &mut out.l1[..], &mut out.l2[..]);
    let mut covered = 0u64;
    for y in by0..=by1 {
        let mut e = [0, 1, 2].map(|i| _mm256_add_epi32(_mm256_set1_epi32(e_row[i]), off[i]));
        let row = (y - sy0) as usize * width;
        let (mut x, mut aligned) = (bx0, false);
        while x <= bx1 {
            // Lanes inside every edge (biased edge values ≥ 0: no sign bit) and inside the box.
            let any = _mm256_or_si256(
                _mm256_or_si256(_mm256_add_epi32(e[0], bias[0]), _mm256_add_epi32(e[1], bias[1])),
                _mm256_add_epi32(e[2], bias[2]),
            );
            let outside = _mm256_movemask_ps(_mm256_castsi256_ps(any)) as u32;
            let in_box = 0xff >> (7 - (bx1 - x).min(7));
            let inside = !outside & in_box;
            if !aligned {
                if inside != 0 {
                    // Start the lanes at the row's span, as the four-lane walk does.
                    let k = inside.trailing_zeros() as i32;
                    aligned = true;
                    for i in 0..3 {
                        e[i] = _mm256_add_epi32(e[i], _mm256_set1_epi32(k * step_x[i]));
                    }
                    x += k;
                    continue;
                }
            } else {
                let m = (!inside).trailing_zeros() as usize;
                if m == 0 {
                    break;
                }
                covered += m as u64;
                let l1 = _mm256_mul_ps(_mm256_cvtepi32_ps(e[1]), inv_area);
                let l2 = _mm256_mul_ps(_mm256_cvtepi32_ps(e[2]), inv_area);
                let z = _mm256_add_ps(_mm256_add_ps(z0, _mm256_mul_ps(l1, dz1)), _mm256_mul_ps(l2, dz2));
                let i = row + x as usize;
                let cell = &mut depth[i..i + LANES];
                // SAFETY: `cell` holds eight f32 (unaligned loads and stores are allowed).
                let d = unsafe { _mm256_loadu_ps(cell.as_ptr()) };
                let nearer = inside & _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(z, d)) as u32;
                if nearer != 0 {
                    let keep = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(nearer as i32), bit), bit);
                    // SAFETY: as the load above.
                    unsafe { _mm256_storeu_ps(cell.as_mut_ptr(), _mm256_blendv_ps(d, z, _mm256_castsi256_ps(keep))) };
                    let entries = _mm256_add_epi32(_mm256_set1_epi32(i as i32), sample);
                    if nearer & (nearer + 1) == 0 {
                        // The first lanes (no overdraw): all eight written, the nearer ones kept.
                        let (ix, a, b) = (&mut index[n..n + LANES], &mut list_l1[n..n + LANES], &mut list_l2[n..n + LANES]);
                        // SAFETY: each slice holds eight 4-byte entries.
                        unsafe {
                            _mm256_storeu_si256(ix.as_mut_ptr().cast(), entries);
                            _mm256_storeu_ps(a.as_mut_ptr(), l1);
                            _mm256_storeu_ps(b.as_mut_ptr(), l2);
                        }
                        n += (!nearer).trailing_zeros() as usize;
                    } else {
                        let (mut ix, mut a, mut b) = ([0u32; LANES], [0f32; LANES], [0f32; LANES]);
                        // SAFETY: each array holds eight 4-byte values.
                        unsafe {
                            _mm256_storeu_si256(ix.as_mut_ptr().cast(), entries);
                            _mm256_storeu_ps(a.as_mut_ptr(), l1);
                            _mm256_storeu_ps(b.as_mut_ptr(), l2);
                        }
                        for k in 0..LANES {
                            (index[n], list_l1[n], list_l2[n]) = (ix[k], a[k], b[k]);
                            n += (nearer >> k) as usize & 1;
                        }
                    }
                }
                if m < LANES {
                    break;
                }
            }
            for i in 0..3 {
                e[i] = _mm256_add_epi32(e[i], step8[i]);
            }
            x += LANES as i32;
        }
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
    }
    out.listed = n;
    covered
}
