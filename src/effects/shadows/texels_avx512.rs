//! The four texel compares of a bundle's shadow-map lookups with AVX-512 gathers, for CPUs
//! with AVX-512F (chosen at run time through the [`Avx512`] token).
//!
//! [`ShadowMap::visibility_lanes`](super::ShadowMap::visibility_lanes) computes each lane's
//! texel (u0, w0) and reference depth in lanes; the compares of the four texels around it
//! were a scalar loop over the lanes (an address, bounds tests and a branch per texel), the
//! larger part of the lookup's cost (~11 ns a lookup, perf, `shadow`). Here each texel of
//! the footprint is one masked gather for all lanes: its tiled index in i32 lanes, lanes
//! outside the map or skipped masked off (they count as lit, as in the scalar loop). The
//! compare is the scalar `reference ≥ texel` (ordered: a NaN texel shadows in both), so the
//! 0/1 results, and the visibility built from them, have the same bits (tested:
//! `gathered_texels_are_the_scalar_texels`).

use crate::raster::DEPTH_TILE as TILE;
use crate::simd::avx512::Avx512;
use std::arch::x86_64::*;

/// One lookup per lane: the texel (u0, w0) at the footprint's top left, the reference
/// depth, and whether the lane is lit whatever the map says.
pub(super) struct Footprints<'a> {
    /// u0 + k and w0 + k (k keeps them positive for the truncation that made them).
    pub iu: &'a [i32; 16],
    pub iw: &'a [i32; 16],
    pub k: i32,
    pub reference: &'a [f32; 16],
    /// Non-zero: lit anyway.
    pub skip: &'a [f32; 16],
    /// Lanes in use (the bundle's width).
    pub lanes: usize,
}

/// The lit (1) or shadowed (0) value of texels (u0, w0), (u0 + 1, w0), (u0, w0 + 1),
/// (u0 + 1, w0 + 1) of each lane, and u0, w0 as f32, for a map of `size`² texels stored in
/// tiles ([`tiled`](crate::raster::tiled)).
#[inline]
pub(super) fn texels_lit(
    _: Avx512,
    depth: &[f32],
    size: u32,
    f: &Footprints,
    corners: &mut [[f32; 16]; 4],
    fu0: &mut [f32; 16],
    fw0: &mut [f32; 16],
) {
    assert!(f.lanes <= 16 && depth.len() >= (size as usize).div_ceil(TILE).pow(2) * TILE * TILE);
    // SAFETY: an `Avx512` token exists only when detection found every feature enabled
    // below; `depth` holds every texel of the map (asserted), the only ones gathered.
    unsafe { texels_lit_avx512(depth, size, f, corners, fu0, fw0) }
}

// Inlined into the AVX-512 shading bundles that call it: a call per bundle (the inliner
// dropped it once when an unrelated function changed) cost the `shadow` bench 5%.
#[inline]
#[target_feature(enable = "avx512f")]
unsafe fn texels_lit_avx512(
    depth: &[f32],
    size: u32,
    f: &Footprints,
    corners: &mut [[f32; 16]; 4],
    fu0: &mut [f32; 16],
    fw0: &mut [f32; 16],
) {
    const _: () = assert!(TILE == 8, "the tiled index below shifts by 3");
    let tiles = (size as usize).div_ceil(TILE) as i32;
    let k = _mm512_set1_epi32(f.k);
    // SAFETY: each array holds sixteen 4-byte values.
    let (u0, w0, reference, skip) = unsafe {
        (
            _mm512_sub_epi32(_mm512_loadu_si512(f.iu.as_ptr().cast()), k),
            _mm512_sub_epi32(_mm512_loadu_si512(f.iw.as_ptr().cast()), k),
            _mm512_loadu_ps(f.reference.as_ptr()),
            _mm512_loadu_ps(f.skip.as_ptr()),
        )
    };
    let lanes = ((1u32 << f.lanes) - 1) as u16;
    let active = lanes & _mm512_cmp_ps_mask::<_CMP_EQ_OQ>(skip, _mm512_setzero_ps());
    let (n, one, seven) = (_mm512_set1_epi32(size as i32), _mm512_set1_epi32(1), _mm512_set1_epi32(7));
    for (c, (du, dw)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
        let (tx, ty) = (if du == 1 { _mm512_add_epi32(u0, one) } else { u0 }, if dw == 1 { _mm512_add_epi32(w0, one) } else { w0 });
        // In the map: 0 ≤ tx, ty < size (one unsigned compare each).
        let inside = active & _mm512_cmplt_epu32_mask(tx, n) & _mm512_cmplt_epu32_mask(ty, n);
        // tiled(tx, ty): ((ty / 8)·tiles + tx / 8)·64 + (ty mod 8)·8 + tx mod 8.
        let tile = _mm512_add_epi32(_mm512_mullo_epi32(_mm512_srli_epi32::<3>(ty), _mm512_set1_epi32(tiles)), _mm512_srli_epi32::<3>(tx));
        let index = _mm512_or_si512(
            _mm512_slli_epi32::<6>(tile),
            _mm512_or_si512(_mm512_slli_epi32::<3>(_mm512_and_si512(ty, seven)), _mm512_and_si512(tx, seven)),
        );
        // SAFETY: the lanes in `inside` index texels of the map, within `depth`.
        let d = unsafe { _mm512_mask_i32gather_ps::<4>(_mm512_setzero_ps(), inside, index, depth.as_ptr()) };
        // Lit where outside the map, skipped, or the reference is not nearer than the texel.
        let shadowed = _mm512_mask_cmp_ps_mask::<_CMP_NGE_UQ>(inside, reference, d);
        let lit = _mm512_mask_blend_ps(shadowed, _mm512_set1_ps(1.0), _mm512_setzero_ps());
        // SAFETY: each corner holds sixteen f32.
        unsafe { _mm512_storeu_ps(corners[c].as_mut_ptr(), lit) };
    }
    // SAFETY: as above.
    unsafe {
        _mm512_storeu_ps(fu0.as_mut_ptr(), _mm512_cvtepi32_ps(u0));
        _mm512_storeu_ps(fw0.as_mut_ptr(), _mm512_cvtepi32_ps(w0));
    }
}
