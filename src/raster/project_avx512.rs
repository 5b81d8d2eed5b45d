//! The raster setup's vertex projection sixteen vertices at a time in AVX-512 registers, for
//! CPUs with AVX-512F (chosen at run time through the [`Avx512`] token): each lane makes
//! [`project_one`]'s inside test (finite, guard band, near plane) and projection with the
//! same IEEE operations in the same order (nothing fused), so the same bits (tested:
//! `projected_lanes_are_the_one_vertex_ones`). The `dense` bench projects ~526k vertices a
//! frame: one at a time, that was 12% of its frame.

use super::project::{Projected, project_one};
use crate::simd::avx512::Avx512;
use glam::Vec4;
use std::arch::x86_64::*;

/// Vertices projected at once.
pub(super) const LANES: usize = 16;

// `Projected` is stored as four 4-byte lanes of a vertex: x, y, z, q in this order.
const _: () = assert!(std::mem::size_of::<Projected>() == 16 && std::mem::size_of::<[Vec4; LANES]>() == 16 * LANES);

/// [`project_one`] of sixteen clip-space vertices on a `width` × `height` sample grid with
/// guard-band factor `g`, for a CPU with AVX-512F (the token proves it).
#[inline]
pub(super) fn project16(_: Avx512, clip: &[Vec4; LANES], width: u32, height: u32, g: f32) -> [Projected; LANES] {
    // SAFETY: an `Avx512` token exists only when detection found every feature enabled below.
    unsafe { project16_avx512(clip, width, height, g) }
}

/// Rows `r` of four xyzw quadruples each (four 128-bit lanes) to four registers: the
/// 4 × 4 transpose within each 128-bit lane, so lane 4j + m of register k holds component k
/// of quadruple 4m + j. Applied to its own output it gives back the rows.
#[inline]
#[target_feature(enable = "avx512f")]
fn transpose(r: [__m512; 4]) -> [__m512; 4] {
    let (a, b) = (_mm512_unpacklo_ps(r[0], r[1]), _mm512_unpackhi_ps(r[0], r[1]));
    let (c, d) = (_mm512_unpacklo_ps(r[2], r[3]), _mm512_unpackhi_ps(r[2], r[3]));
    [
        _mm512_shuffle_ps::<0b01_00_01_00>(a, c),
        _mm512_shuffle_ps::<0b11_10_11_10>(a, c),
        _mm512_shuffle_ps::<0b01_00_01_00>(b, d),
        _mm512_shuffle_ps::<0b11_10_11_10>(b, d),
    ]
}

/// [`project16`], compiled with AVX-512F.
#[target_feature(enable = "avx512f")]
fn project16_avx512(clip: &[Vec4; LANES], width: u32, height: u32, g: f32) -> [Projected; LANES] {
    let p = clip.as_ptr().cast::<f32>();
    // SAFETY: four loads of sixteen f32 from the 64 f32 of `clip` (asserted above).
    let [x, y, z, w] = transpose([0, 1, 2, 3].map(|k| unsafe { _mm512_loadu_ps(p.add(16 * k)) }));
    let zero = _mm512_setzero_ps();
    // Finite: an exponent below all ones in every component.
    let exp = _mm512_set1_epi32(0x7f80_0000);
    let finite = [x, y, z, w]
        .map(|c| _mm512_cmpneq_epi32_mask(_mm512_and_si512(_mm512_castps_si512(c), exp), exp))
        .into_iter()
        .fold(u16::MAX, |m, f| m & f);
    // `clip::distances`, each ≥ 0 (false for NaN).
    let gw = _mm512_mul_ps(_mm512_set1_ps(g), w);
    let inside = [_mm512_sub_ps(w, z), _mm512_sub_ps(gw, x), _mm512_add_ps(gw, x), _mm512_sub_ps(gw, y), _mm512_add_ps(gw, y)]
        .map(|d| _mm512_cmp_ps_mask::<_CMP_GE_OQ>(d, zero))
        .into_iter()
        .fold(finite, |m, d| m & d);
    // `project_vertex`.
    let (one, half) = (_mm512_set1_ps(1.0), _mm512_set1_ps(0.5));
    let q = _mm512_div_ps(one, w);
    let sx = _mm512_mul_ps(_mm512_mul_ps(_mm512_add_ps(_mm512_mul_ps(x, q), one), half), _mm512_set1_ps(width as f32));
    let sy = _mm512_mul_ps(_mm512_mul_ps(_mm512_sub_ps(one, _mm512_mul_ps(y, q)), half), _mm512_set1_ps(height as f32));
    let fixed = _mm512_set1_ps(super::ONE as f32);
    let (gx, gy) = (round_half_away(_mm512_mul_ps(sx, fixed)), round_half_away(_mm512_mul_ps(sy, fixed)));
    let zq = _mm512_mul_ps(z, q);
    // Outside: `Projected::CLIP` (x = i32::MIN, the rest 0).
    let gx = _mm512_mask_mov_epi32(_mm512_set1_epi32(Projected::CLIP.x), inside, gx);
    let rows = transpose([
        _mm512_castsi512_ps(gx),
        _mm512_castsi512_ps(_mm512_maskz_mov_epi32(inside, gy)),
        _mm512_maskz_mov_ps(inside, zq),
        _mm512_maskz_mov_ps(inside, q),
    ]);
    let mut out = [Projected::CLIP; LANES];
    let o = out.as_mut_ptr().cast::<f32>();
    for (k, r) in rows.into_iter().enumerate() {
        // SAFETY: four stores of sixteen f32 into the 64 4-byte fields of `out` (asserted
        // above; `Projected` is `repr(C)` of four 4-byte fields, any bits valid).
        unsafe { _mm512_storeu_ps(o.add(16 * k), r) };
    }
    out
}

/// `setup::round_half_away` per lane: truncate (NaN to 0, as `f32 as i32` does; an inside
/// vertex's coordinates are within the guard band, so nothing else saturates), then step
/// away from zero when the dropped fraction is at least ½.
#[inline]
#[target_feature(enable = "avx512f")]
fn round_half_away(x: __m512) -> __m512i {
    let t = _mm512_maskz_cvttps_epi32(_mm512_cmp_ps_mask::<_CMP_ORD_Q>(x, x), x);
    let frac = _mm512_sub_ps(x, _mm512_cvtepi32_ps(t));
    let t = _mm512_mask_add_epi32(t, _mm512_cmp_ps_mask::<_CMP_GE_OQ>(frac, _mm512_set1_ps(0.5)), t, _mm512_set1_epi32(1));
    _mm512_mask_sub_epi32(t, _mm512_cmp_ps_mask::<_CMP_LE_OQ>(frac, _mm512_set1_ps(-0.5)), t, _mm512_set1_epi32(1))
}

/// Vertices `first..first + out.len()` (clip space from `clip`) projected into `out`,
/// sixteen at a time, the rest one at a time: every element of `out` is written.
#[inline]
pub(super) fn project_run(
    t: Avx512,
    clip: &(impl Fn(usize) -> Vec4 + Sync),
    first: usize,
    out: &mut [std::mem::MaybeUninit<Projected>],
    (width, height, g): (u32, u32, f32),
) {
    let mut groups = out.chunks_exact_mut(LANES);
    let mut i = first;
    for group in &mut groups {
        let v: [Vec4; LANES] = std::array::from_fn(|l| clip(i + l));
        for (o, p) in group.iter_mut().zip(project16(t, &v, width, height, g)) {
            o.write(p);
        }
        i += LANES;
    }
    for o in groups.into_remainder() {
        o.write(project_one(clip(i), width, height, g));
        i += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projected_lanes_are_the_one_vertex_ones() {
        // Every lane against `project_one`, bit for bit: inside vertices over the grid and
        // the guard band, fractions at ±½ sample steps, the near plane and the guard band's
        // edges, w = 0 at the eye (x·q is NaN: x = 0), w < 0, NaN and ∞ in each component.
        let Some(t) = crate::simd::Cpu::get().avx512() else {
            crate::simd::cpu::missing(crate::simd::Level::Avx512, "AVX-512F");
            return;
        };
        let (width, height) = (1000, 700);
        let g = (1u32 << 19) as f32 / width as f32;
        let mut v: Vec<Vec4> = Vec::new();
        for i in 0..400 {
            let f = i as f32;
            let w = 0.5 + (i % 7) as f32 * 0.7;
            v.push(Vec4::new((f * 0.37).sin() * w * 1.3, (f * 0.11).cos() * w, (f * 0.05).sin() * w, w));
        }
        // x·q = 2k/width − 1 + exactly half a sub-sample step: the rounding's ties.
        for k in 0..64 {
            let s = (k as f32 + 0.5) / (super::super::ONE as f32);
            v.push(Vec4::new(2.0 * s / width as f32 - 1.0, 1.0 - 2.0 * s / height as f32, 0.3, 1.0));
        }
        let special = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, -0.0, 1e-38, -2.0, 1e30];
        for (a, &s) in special.iter().enumerate() {
            for c in 0..4 {
                let mut p = Vec4::new(0.2, -0.3, 0.4, 1.0);
                p[c] = s;
                v.push(p);
                v.push(Vec4::new(0.0, 0.0, -(a as f32), 0.0));
            }
        }
        // The near plane (w − z = 0) and the guard band (g·w ± x = 0), on and past them.
        v.extend([Vec4::new(0.1, 0.1, 1.0, 1.0), Vec4::new(0.1, 0.1, 1.0001, 1.0), Vec4::new(g, 0.0, 0.0, 1.0)]);
        v.extend([Vec4::new(-g, g, 0.0, 1.0), Vec4::new(g * 1.0001, 0.0, 0.0, 1.0), Vec4::new(0.0, 0.0, 0.0, -1.0)]);
        while !v.len().is_multiple_of(LANES) {
            v.push(Vec4::new(0.0, 0.0, 0.5, 1.0));
        }
        let bits = |p: &Projected| (p.x, p.y, p.z.to_bits(), p.q.to_bits());
        let mut inside = 0;
        for group in v.chunks_exact(LANES) {
            let got = project16(t, group.try_into().expect("sixteen"), width, height, g);
            for (l, (p, &c)) in got.iter().zip(group).enumerate() {
                let want = project_one(c, width, height, g);
                assert_eq!(bits(p), bits(&want), "lane {l}, vertex {c:?}");
                inside += (want.x != Projected::CLIP.x) as usize;
            }
        }
        assert!(inside > 400 && inside < v.len(), "{inside} of {} inside", v.len());
        // A run: groups of sixteen and a remainder, written in place.
        let mut out = vec![std::mem::MaybeUninit::new(Projected::CLIP); 37];
        project_run(t, &|i| v[i], 5, &mut out, (width, height, g));
        for (i, o) in out.iter().enumerate() {
            // SAFETY: initialised above (and written by `project_run`).
            assert_eq!(bits(unsafe { o.assume_init_ref() }), bits(&project_one(v[5 + i], width, height, g)));
        }
    }
}
