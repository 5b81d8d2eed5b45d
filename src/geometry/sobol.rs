//! Shuffled, Owen-scrambled Sobol points: stratified samples that stay deterministic per
//! pixel, light and purpose.
//!
//! The Sobol sequence in base 2 is x_i = Σ_k b_k(i) V_k (XOR), b_k(i) the bits of the index
//! and V_k the direction numbers of a dimension (I. M. Sobol', "On the distribution of points
//! in a cube and the approximate evaluation of integrals", 1967). Dimension 0 is the van der
//! Corput sequence (the index's bits reversed); dimensions 1–3 use the direction numbers of
//! S. Joe and F. Y. Kuo, "Constructing Sobol sequences with better two-dimensional
//! projections", SIAM J. Sci. Comput. 30, 2008 (file `new-joe-kuo-6.21201`, lines d = 2, 3, 4).
//! Dimensions 0 and 1 form a (0, 2)-sequence: every aligned block of 2^m points has exactly one
//! point in each elementary interval of area 2^−m (the 2^a × 2^(m−a) grids).
//!
//! Each stream is made independent of every other by hashing, as in B. Burley, "Practical
//! Hash-based Owen Scrambling", JCGT 9(4), 2020:
//! - **Owen scrambling** of each coordinate ([`nested_uniform_scramble`], Burley's listings 1–2):
//!   the bits are reversed, permuted so that each bit is flipped by a hash of the bits below it
//!   (of the higher-order digits of the coordinate), and reversed back. That is a nested uniform
//!   (Owen 1995) scramble, which keeps every net property above and makes each point uniformly
//!   distributed in [0, 1). The permutation is the Laine–Karras form with the constants of
//!   N. Vegdahl, "Building a Better LK Hash" (psychopath.io, 2021, the final hash), which pbrt-v4
//!   uses as `FastOwenScrambler`; Burley's original constants avalanche less well.
//! - **Shuffling** of the index by the same scramble (Burley's listing 3): a nested uniform scramble of the
//!   index permutes each aligned block of 2^m indices among itself, so the first 2^m samples of a
//!   shuffled stream are still one full (0, m, 2)-net, but different seeds visit the points in
//!   decorrelated orders. This is what lets two streams (say the light's position and a fog
//!   distance) be padded side by side without their samples lining up.
//!
//! Seeding: a stream is named by its seed, by convention a hash of what the samples are for,
//! e.g. `hash3(point_seed(p), light_index, purpose)` ([`super::sampling::hash3`]): the same
//! pixel, light and purpose give the same samples on every run and thread (DESIGN.md,
//! Determinism), while different pixels get independent scrambles (as pbrt-v4's
//! `PaddedSobolSampler`). Sample k of N is `sobol_2d(k, seed)` for k = 0 … N−1; N a power of two
//! gives a full net, other N a prefix of one, still far better stratified than independent points.
//!
//! Everything is integer arithmetic (the same bits on every machine); a coordinate becomes an
//! f32 from its top 24 bits, exactly, so it lies in [0, 1 − 2⁻²⁴] like
//! [`super::sampling::sample_2d`].

use super::sampling::hash;
use glam::{Vec2, Vec4};

/// How many Sobol dimensions this module generates (0–3).
pub const DIMENSIONS: usize = 4;

/// Joe–Kuo parameters (s, a, m₁ … m_s) of dimensions 1–3: the degree s of the primitive
/// polynomial, its inner coefficients a as bits, and the initial direction integers m_k.
const JOE_KUO: [(u32, u32, [u32; 3]); DIMENSIONS - 1] = [(1, 0, [1, 0, 0]), (2, 1, [1, 3, 0]), (3, 1, [1, 3, 1])];

/// The direction numbers V_k (k = 1 … 32) of each dimension as 0.32 fixed point.
const DIRECTIONS: [[u32; 32]; DIMENSIONS] = directions();

/// Builds the direction numbers: V_k = m_k 2^(32−k) for k ≤ s, then the recurrence
/// V_k = V_{k−s} ⊕ (V_{k−s} ≫ s) ⊕ ⊕_{j=1}^{s−1} a_j V_{k−j} (P. Bratley and B. L. Fox, "Algorithm 659",
/// ACM TOMS 14(1), 1988; the same loop as Joe and Kuo's reference generator).
const fn directions() -> [[u32; 32]; DIMENSIONS] {
    let mut v = [[0u32; 32]; DIMENSIONS];
    // Dimension 0: the identity matrix, i.e. the bit reversal of the index.
    let mut k = 0;
    while k < 32 {
        v[0][k] = 1 << (31 - k);
        k += 1;
    }
    let mut dim = 1;
    while dim < DIMENSIONS {
        let (s, a, m) = JOE_KUO[dim - 1];
        let s = s as usize;
        let mut k = 0;
        while k < 32 {
            v[dim][k] = if k < s {
                m[k] << (31 - k)
            } else {
                let mut x = v[dim][k - s] ^ (v[dim][k - s] >> s);
                let mut j = 1;
                while j < s {
                    if (a >> (s - 1 - j)) & 1 == 1 {
                        x ^= v[dim][k - j];
                    }
                    j += 1;
                }
                x
            };
            k += 1;
        }
        dim += 1;
    }
    v
}

/// The unscrambled Sobol point `index` in dimension `dim` (< [`DIMENSIONS`]) as 0.32 fixed point.
///
/// The point is linear in the index's bits over GF(2) (the XOR of the direction numbers of
/// its set bits), so it is the XOR of four byte tables' entries, one per byte of the index:
/// four lookups instead of one XOR per set bit (a shuffled index has about 16). Dimension 0
/// is the bit reversal. Panics if `dim` ≥ [`DIMENSIONS`].
#[inline]
pub fn sobol_bits(index: u32, dim: usize) -> u32 {
    if dim == 0 {
        return index.reverse_bits();
    }
    let t = &BYTE_TABLES[dim];
    let b = index.to_le_bytes();
    t[0][b[0] as usize] ^ t[1][b[1] as usize] ^ t[2][b[2] as usize] ^ t[3][b[3] as usize]
}

/// [`sobol_bits`] one XOR per set bit of the index: the definition the byte tables are made from.
#[cfg(test)]
fn sobol_bits_by_bit(index: u32, dim: usize) -> u32 {
    let v = &DIRECTIONS[dim];
    let mut x = 0;
    let mut i = index;
    while i != 0 {
        let k = i.trailing_zeros();
        x ^= v[k as usize];
        i &= i - 1;
    }
    x
}

/// Per dimension and byte of the index, the XOR of the direction numbers of each byte value's
/// set bits (16 KB, built at compile time).
const BYTE_TABLES: [[[u32; 256]; 4]; DIMENSIONS] = byte_tables();

const fn byte_tables() -> [[[u32; 256]; 4]; DIMENSIONS] {
    let mut t = [[[0u32; 256]; 4]; DIMENSIONS];
    let mut dim = 0;
    while dim < DIMENSIONS {
        let mut byte = 0;
        while byte < 4 {
            let mut value = 0;
            while value < 256 {
                let mut x = 0u32;
                let mut bit = 0;
                while bit < 8 {
                    if (value >> bit) & 1 == 1 {
                        x ^= DIRECTIONS[dim][byte * 8 + bit];
                    }
                    bit += 1;
                }
                t[dim][byte][value] = x;
                value += 1;
            }
            byte += 1;
        }
        dim += 1;
    }
    t
}

/// Owen's nested uniform scramble of a 0.32 fixed-point coordinate, keyed by `seed`
/// (Burley 2020, listing 2, with Vegdahl's 2021 permutation; see the module docs).
///
/// Bit k of the result is bit k of `x` flipped by a hash of `seed` and the bits above k, so
/// values that agree in their top m bits still agree in their top m bits afterwards: every
/// aligned interval of length 2^−m is mapped onto one, and nets stay nets. A bijection of u32.
#[inline]
pub fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    scramble_reversed(x.reverse_bits(), seed).reverse_bits()
}

/// [`nested_uniform_scramble`] between its two bit reversals: the permutation of the reversed
/// value `v`. The streams below call it directly where a reversal would undo another (a bit
/// reversal is not one instruction on x86-64; the streams do three to five fewer a point).
#[inline]
fn scramble_reversed(mut v: u32, seed: u32) -> u32 {
    // In reversed order, "the bits above" become "the bits below", which is what a multiply by an
    // even constant (x·c changes bit k only through bits < k), an add and an odd multiply touch.
    v ^= v.wrapping_mul(0x3d20_adea);
    v = v.wrapping_add(seed);
    v = v.wrapping_mul((seed >> 16) | 1);
    v ^= v.wrapping_mul(0x0552_6c56);
    v ^= v.wrapping_mul(0x53a2_2864);
    v
}

/// Coordinate `dim` of the shuffled index `i`, Owen-scrambled with `seed`:
/// `nested_uniform_scramble(sobol_bits(i, dim), seed)` with the reversals that cancel left out
/// (dimension 0 is the reversal itself; the others read [`REVERSED_TABLES`]).
#[inline]
fn scrambled_coordinate(i: u32, dim: usize, seed: u32) -> u32 {
    let reversed = if dim == 0 {
        i
    } else {
        let t = &REVERSED_TABLES[dim];
        let b = i.to_le_bytes();
        t[0][b[0] as usize] ^ t[1][b[1] as usize] ^ t[2][b[2] as usize] ^ t[3][b[3] as usize]
    };
    scramble_reversed(reversed, seed).reverse_bits()
}

/// [`BYTE_TABLES`] with every entry's bits reversed (the reversal of a XOR is the XOR of the reversals).
const REVERSED_TABLES: [[[u32; 256]; 4]; DIMENSIONS] = reversed_tables();

const fn reversed_tables() -> [[[u32; 256]; 4]; DIMENSIONS] {
    let mut t = BYTE_TABLES;
    let mut dim = 0;
    while dim < DIMENSIONS {
        let mut byte = 0;
        while byte < 4 {
            let mut value = 0;
            while value < 256 {
                t[dim][byte][value] = t[dim][byte][value].reverse_bits();
                value += 1;
            }
            byte += 1;
        }
        dim += 1;
    }
    t
}

/// The top 24 bits of a 0.32 fixed-point value as an f32 in [0, 1 − 2⁻²⁴] (exact).
#[inline]
fn to_unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// The seed of coordinate `dim` of a stream, independent of the index shuffle's seed.
#[inline]
fn dimension_seed(seed: u32, dim: u32) -> u32 {
    // Two rounds so that seeds differing in one bit give unrelated scrambles in every dimension.
    hash(hash(seed ^ 0x68e3_1da4).wrapping_add(dim.wrapping_mul(0x9e37_79b9)))
}

/// The shuffled index of sample `index` in the stream `seed`: the index Owen-scrambled before
/// the lookup (Burley 2020, listing 3).
#[inline]
fn shuffled(index: u32, seed: u32) -> u32 {
    nested_uniform_scramble(index, seed)
}

/// Sample `index` of the 1D stream `seed` in [0, 1): the shuffled, Owen-scrambled van der
/// Corput sequence. The first 2^m samples put exactly one in each interval [j 2^−m, (j+1) 2^−m).
#[inline]
pub fn sobol_1d(index: u32, seed: u32) -> f32 {
    to_unit(sobol_bits_1d(index, seed))
}

/// [`sobol_1d`] as 0.32 fixed point (for callers that need more than 24 bits).
#[inline]
pub fn sobol_bits_1d(index: u32, seed: u32) -> u32 {
    // nested_uniform_scramble(shuffled(index, seed).reverse_bits(), dimension_seed(seed, 0)),
    // whose inner reversal undoes that explicit one.
    scrambled_coordinate(shuffled(index, seed), 0, dimension_seed(seed, 0))
}

/// Sample `index` of the 2D stream `seed` in [0, 1)²: Sobol dimensions 0 and 1, shuffled
/// and Owen-scrambled (Burley 2020, listing 3). The first 2^m samples (and every aligned
/// block of 2^m) form a (0, m, 2)-net: one point in each elementary interval of area 2^−m.
#[inline]
pub fn sobol_2d(index: u32, seed: u32) -> Vec2 {
    let [x, y] = sobol_bits_2d(index, seed);
    Vec2::new(to_unit(x), to_unit(y))
}

/// [`sobol_2d`] as 0.32 fixed point.
#[inline]
pub fn sobol_bits_2d(index: u32, seed: u32) -> [u32; 2] {
    let i = shuffled(index, seed);
    [scrambled_coordinate(i, 0, dimension_seed(seed, 0)), scrambled_coordinate(i, 1, dimension_seed(seed, 1))]
}

/// Sample `index` of the 4D stream `seed` in [0, 1)⁴: Sobol dimensions 0–3 with one shared
/// shuffle, each coordinate Owen-scrambled. Every coordinate is stratified in 1D and (x, y) is a
/// (0, 2)-sequence; the other pairs have a larger t (Joe–Kuo chose them for good, not perfect,
/// 2D projections), so prefer independent [`sobol_2d`] streams unless the four must be joint.
#[inline]
pub fn sobol_4d(index: u32, seed: u32) -> Vec4 {
    let i = shuffled(index, seed);
    let c = |d: usize| to_unit(scrambled_coordinate(i, d, dimension_seed(seed, d as u32)));
    Vec4::new(c(0), c(1), c(2), c(3))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The streams without the reversals that cancel are the definitions (shuffle, then
    /// `nested_uniform_scramble` of `sobol_bits`) bit for bit.
    #[test]
    fn the_streams_are_their_definitions_bit_for_bit() {
        let definition = |index: u32, seed: u32, dim: usize| {
            nested_uniform_scramble(sobol_bits(nested_uniform_scramble(index, seed), dim), dimension_seed(seed, dim as u32))
        };
        for k in 0..300_000u32 {
            let index = if k < 1000 { k } else { k.wrapping_mul(0x9e37_79b9) ^ (k >> 5) };
            let seed = hash(k ^ 0x5eed) ^ (k & 3).wrapping_mul(0x8000_0001);
            let bits_1d = nested_uniform_scramble(nested_uniform_scramble(index, seed).reverse_bits(), dimension_seed(seed, 0));
            assert_eq!(sobol_bits_1d(index, seed), bits_1d, "1D: index {index}, seed {seed}");
            assert_eq!(
                sobol_bits_2d(index, seed),
                [definition(index, seed, 0), definition(index, seed, 1)],
                "2D: index {index}, seed {seed}"
            );
            let four = sobol_4d(index, seed).to_array().map(f32::to_bits);
            let want = [0, 1, 2, 3].map(|d| to_unit(definition(index, seed, d)).to_bits());
            assert_eq!(four, want, "4D: index {index}, seed {seed}");
        }
        for dim in 0..DIMENSIONS {
            for k in 0..5000u32 {
                let (x, seed) = (hash(k.wrapping_add(dim as u32)), hash(k ^ 0xabcd));
                assert_eq!(scrambled_coordinate(x, dim, seed), nested_uniform_scramble(sobol_bits(x, dim), seed));
            }
        }
    }

    /// The byte tables give the definition's bits: every dimension, every byte position.
    #[test]
    fn byte_tables_equal_one_xor_per_set_bit() {
        for dim in 0..DIMENSIONS {
            for k in 0..200_000u32 {
                let i = k.wrapping_mul(0x9e37_79b9) ^ (k >> 3);
                assert_eq!(sobol_bits(i, dim), sobol_bits_by_bit(i, dim), "dim {dim}, index {i:#x}");
            }
            assert_eq!(sobol_bits(u32::MAX, dim), sobol_bits_by_bit(u32::MAX, dim));
        }
    }

    /// True when the 2^m points `pts` (0.32 fixed point) have exactly one point in every
    /// elementary interval of area 2^−m: for each a, the 2^a × 2^(m−a) grid.
    fn is_02_net(pts: &[[u32; 2]], m: u32) -> bool {
        assert_eq!(pts.len(), 1 << m);
        (0..=m).all(|a| {
            let mut seen = vec![false; 1 << m];
            pts.iter().all(|&[x, y]| {
                // Shifts by 32 (a = 0 or a = m) must give cell 0: checked_shr returns None there.
                let cx = x.checked_shr(32 - a).unwrap_or(0);
                let cy = y.checked_shr(32 - (m - a)).unwrap_or(0);
                let cell = ((cy << a) | cx) as usize;
                !std::mem::replace(&mut seen[cell], true)
            })
        })
    }

    #[test]
    fn direction_numbers_match_joe_kuo() {
        // The first columns of pbrt-v4's `SobolMatrices32` (generated from new-joe-kuo-6.21201).
        let want: [[u32; 10]; 3] = [
            [
                0x8000_0000,
                0xc000_0000,
                0xa000_0000,
                0xf000_0000,
                0x8800_0000,
                0xcc00_0000,
                0xaa00_0000,
                0xff00_0000,
                0x8080_0000,
                0xc0c0_0000,
            ],
            [
                0x8000_0000,
                0xc000_0000,
                0x6000_0000,
                0x9000_0000,
                0xe800_0000,
                0x5c00_0000,
                0x8e00_0000,
                0xc500_0000,
                0x6880_0000,
                0x9cc0_0000,
            ],
            [
                0x8000_0000,
                0xc000_0000,
                0x2000_0000,
                0x5000_0000,
                0xf800_0000,
                0x7400_0000,
                0xa200_0000,
                0x9300_0000,
                0xd880_0000,
                0x2540_0000,
            ],
        ];
        for (dim, w) in want.iter().enumerate() {
            assert_eq!(&DIRECTIONS[dim + 1][..10], w, "dimension {}", dim + 1);
        }
        // The second dimension is Pascal's triangle mod 2: its last column is all ones.
        assert_eq!(DIRECTIONS[1][31], 0xffff_ffff);
        // The first points of the sequence: (0, 0), (½, ½), (¼, ¾), (¾, ¼), (⅜, ⅝).
        let first: Vec<[u32; 2]> = (0..5).map(|i| [sobol_bits(i, 0), sobol_bits(i, 1)]).collect();
        let q = |x: u32| x << 29;
        assert_eq!(first, [[0, 0], [q(4), q(4)], [q(2), q(6)], [q(6), q(2)], [q(1), q(5)]]);
    }

    #[test]
    fn the_first_two_dimensions_are_a_02_sequence_before_and_after_scrambling() {
        for m in 0..=10 {
            // Every aligned block of 2^m indices, unscrambled.
            for block in [0u32, 1, 5, 1000] {
                let start = block << m;
                let pts: Vec<[u32; 2]> = (start..start + (1 << m)).map(|i| [sobol_bits(i, 0), sobol_bits(i, 1)]).collect();
                assert!(is_02_net(&pts, m), "unscrambled, m = {m}, block {block}");
            }
            // Shuffled and scrambled: the first 2^m samples of each stream, and a later block.
            for seed in [0, 1, 0x5eed_a11c, 0xffff_ffff, hash(12345)] {
                let pts: Vec<[u32; 2]> = (0..1u32 << m).map(|k| sobol_bits_2d(k, seed)).collect();
                assert!(is_02_net(&pts, m), "scrambled, m = {m}, seed {seed:#x}");
                let start = 7u32 << m;
                let pts: Vec<[u32; 2]> = (start..start + (1 << m)).map(|k| sobol_bits_2d(k, seed)).collect();
                assert!(is_02_net(&pts, m), "scrambled, m = {m}, seed {seed:#x}, block 7");
                // The f32 values keep the net for m ≤ 24 (their cells are decided by the top bits).
                let f: Vec<[u32; 2]> = (0..1u32 << m)
                    .map(|k| {
                        let u = sobol_2d(k, seed);
                        [(u.x as f64 * 2f64.powi(32)) as u32, (u.y as f64 * 2f64.powi(32)) as u32]
                    })
                    .collect();
                assert!(is_02_net(&f, m), "as f32, m = {m}, seed {seed:#x}");
            }
        }
    }

    #[test]
    fn one_dimensional_streams_are_stratified() {
        for seed in [0, 3, 0xdead_beef] {
            for m in 0..=12 {
                let mut seen = vec![false; 1 << m];
                for k in 0..1u32 << m {
                    let cell = sobol_bits_1d(k, seed).checked_shr(32 - m).unwrap_or(0) as usize;
                    assert!(!std::mem::replace(&mut seen[cell], true), "m = {m}, seed {seed}");
                }
            }
            // Each coordinate of the 4D stream is stratified too.
            for d in 0..4 {
                let mut seen = [false; 256];
                for k in 0..256 {
                    let cell = (sobol_4d(k, seed)[d] * 256.0) as usize;
                    assert!(!std::mem::replace(&mut seen[cell], true), "4D dimension {d}, seed {seed}");
                }
            }
        }
    }

    #[test]
    fn scrambling_is_a_nested_bijection() {
        // Values agreeing in their top m bits agree in their top m bits after the scramble.
        for seed in [0u32, 1, 0x8000_0000, hash(99)] {
            for i in 0..2000u32 {
                let x = hash(i);
                let y = x ^ (hash(i ^ 0x55) >> (i % 32));
                let common = (x ^ y).leading_zeros();
                let (sx, sy) = (nested_uniform_scramble(x, seed), nested_uniform_scramble(y, seed));
                assert!((sx ^ sy).leading_zeros() >= common, "{x:#x} {y:#x} seed {seed:#x}");
                // Top bits equal ⇒ top bits equal; and distinct values stay distinct.
                assert_eq!(x == y, sx == sy);
            }
            // A bijection on every aligned block of 2^12: all 4096 low parts are hit once.
            let mut seen = vec![false; 4096];
            for i in 0..4096u32 {
                let v = nested_uniform_scramble(0xabcd_e000 | i, seed);
                assert_eq!(v >> 12, nested_uniform_scramble(0xabcd_e000, seed) >> 12);
                assert!(!std::mem::replace(&mut seen[(v & 0xfff) as usize], true));
            }
        }
    }

    #[test]
    fn streams_are_deterministic_in_range_and_decorrelated() {
        let max = 1.0 - 2f32.powi(-24);
        for seed in [0, 1, 0xffff_ffff] {
            for k in (0..4096).chain([u32::MAX - 1, u32::MAX]) {
                let u = sobol_2d(k, seed);
                assert_eq!(u.to_array().map(f32::to_bits), sobol_2d(k, seed).to_array().map(f32::to_bits));
                assert!(u.cmpge(Vec2::ZERO).all() && u.cmple(Vec2::splat(max)).all(), "{k} {seed}: {u}");
                let v = sobol_4d(k, seed);
                assert!(v.cmpge(Vec4::ZERO).all() && v.cmple(Vec4::splat(max)).all(), "{k} {seed}: {v}");
                let w = sobol_1d(k, seed);
                assert!((0.0..=max).contains(&w));
            }
        }
        // Fixed bits: a change here changes every picture's noise, so it should be deliberate.
        let pinned = [sobol_bits_2d(0, 1), sobol_bits_2d(5, 0x5eed_a11c)];
        assert_eq!(pinned, PINNED, "{pinned:x?}");
        // Streams with neighbouring seeds are uncorrelated: over 4096 seed pairs the correlation
        // of their first samples is within 4σ = 4/√4096 of 0, and so is that of the index order
        // (sample 3 of one stream against sample 3 of the next).
        let n = 4096;
        let corr = |k: u32, dim: usize| {
            let (mut sxy, mut sx, mut sy, mut sxx, mut syy) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for s in 0..n {
                let a = sobol_2d(k, s)[dim] as f64;
                let b = sobol_2d(k, s + 1)[dim] as f64;
                sxy += a * b;
                sx += a;
                sy += b;
                sxx += a * a;
                syy += b * b;
            }
            let nf = n as f64;
            (sxy / nf - sx * sy / (nf * nf)) / ((sxx / nf - (sx / nf).powi(2)) * (syy / nf - (sy / nf).powi(2))).sqrt()
        };
        for (k, dim) in [(0, 0), (0, 1), (3, 0), (3, 1)] {
            let c = corr(k, dim);
            assert!(c.abs() < 4.0 / (n as f64).sqrt(), "sample {k} dim {dim}: correlation {c}");
        }
    }

    /// The bits of two samples at the time the sequence was written.
    const PINNED: [[u32; 2]; 2] = [[0xf8bd_e59a, 0xebf6_c6fe], [0x2d09_3b09, 0x8ebe_e355]];
}
