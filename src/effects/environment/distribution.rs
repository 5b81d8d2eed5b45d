//! Importance sampling of an environment map by luminance (the piecewise-constant 2D
//! distribution of pbrt-v4's `PiecewiseConstant2D` and Mitsuba 3's `envmap.cpp`), with the
//! Jacobian of the latitude-longitude map folded in exactly.
//!
//! The bilinear lookup (scene::environment) interpolates between texel positions, so the
//! natural cells are the quads between four neighbouring texels: cell (i, j), i in 0..W
//! (the last one wraps to column 0), j in 0..H − 1, spans u ∈ [(i + ½)/W, (i + 3/2)/W) and
//! θ ∈ [jπ/(H − 1), (j + 1)π/(H − 1)]. Its weight is the mean luminance of its corners times
//! its solid angle Ω_ij = (2π/W)(cos θ_j − cos θ_{j+1}) (the integral of sin θ dθ dφ: the
//! sin θ Jacobian, exact per cell); within a cell a direction is uniform in φ and cos θ, i.e.
//! uniform in solid angle, so pdf(ω) = P_ij / Ω_ij, finite at the poles. A cell whose corners
//! are all black has probability 0, and the lookup is 0 everywhere in it: the pdf is positive
//! wherever the radiance is.
//!
//! **Finding the cell.** Both the row and the column are found in a cumulative table; a
//! guide table (Chen & Asau 1974; Devroye 1986, §III.2.4) splits [0, 1) into 2^k equal
//! buckets and keeps, per bucket, the first edge above its start, so a search only looks
//! between two neighbouring entries: O(1) expected, and exactly the index a binary search over
//! the whole table returns (pbrt-v4's `PiecewiseConstant1D`), since the bucket's entries bound it.

use crate::geometry::sampling::sin_cos;
use crate::scene::EnvMap;
use crate::scene::environment::{direction_to_uv, luminance};
use glam::{Vec2, Vec3};
use std::f64::consts::PI;

/// The sampling tables of one map.
#[derive(Debug, Clone, PartialEq)]
pub struct EnvDistribution {
    /// Columns of cells (the map's width).
    width: u32,
    /// Rows of cells (the map's height − 1).
    rows: u32,
    /// cos θ at each row edge (rows + 1 values, from 1 down to −1).
    cos_edge: Vec<f32>,
    /// Cumulative probability of the rows (rows + 1 values, from 0 to 1).
    row_cdf: Vec<f32>,
    /// Per row, the cumulative probability of its cells given the row ((width + 1) values each).
    col_cdf: Vec<f32>,
    /// Probability of each cell (row-major).
    cell_p: Vec<f32>,
    /// Guide table of `row_cdf`; `None` when a table is not monotone (binary search then).
    row_guide: Option<Guide>,
    /// Guide tables of the rows of `col_cdf`, one after another.
    col_guide: Option<Guide>,
}

/// Guide tables (Chen & Asau 1974) of one or more cumulative tables of the same length.
#[derive(Debug, Clone, PartialEq)]
struct Guide {
    /// Buckets per table M, a power of two (so a bucket's start b/M and u·M are exact).
    buckets: usize,
    /// Per table, M + 1 entries: entry b is the number of edges ≤ b/M.
    start: Vec<u32>,
}

impl Guide {
    /// The guide tables of the `tables` consecutive tables of `cdf` (each `len` values), or
    /// `None` when one is not monotone (its binary search would not be well defined).
    fn new(cdf: &[f32], len: usize, tables: usize) -> Option<Guide> {
        // About eight edges a bucket: the tables of a 1k map's rows then take 0.26 MB, not 2 MB
        // (with a bucket an edge, loading the bucket's entry was a cache miss a sample); a
        // bucket's few edges are searched within one or two cache lines.
        let buckets = ((len - 1).next_power_of_two() / 8).max(1);
        let mut start = Vec::with_capacity(tables * (buckets + 1));
        for table in cdf.chunks_exact(len).take(tables) {
            if !table.windows(2).all(|w| w[0] <= w[1]) {
                return None;
            }
            // One merge pass: the count of edges ≤ b/M only grows with b.
            let mut p = 0;
            for b in 0..=buckets {
                let t = b as f32 / buckets as f32;
                while p < len && table[p] <= t {
                    p += 1;
                }
                start.push(p as u32);
            }
        }
        Some(Guide { buckets, start })
    }

    /// The first index of `cdf` (table `table`) whose value is above `u`: `partition_point(c ≤ u)`.
    #[inline]
    fn first_above(&self, cdf: &[f32], table: usize, u: f32) -> usize {
        // Outside [0, 1) (and for NaN) the buckets do not bound the answer: search it all.
        if !(0.0..1.0).contains(&u) {
            return cdf.partition_point(|&c| c <= u);
        }
        // u·M is exact (M a power of two), so b/M ≤ u < (b + 1)/M and the answer lies between
        // the two entries.
        let b = (u * self.buckets as f32) as usize;
        let at = table * (self.buckets + 1) + b;
        let (lo, hi) = (self.start[at] as usize, self.start[at + 1] as usize);
        lo + cdf[lo..hi].partition_point(|&c| c <= u)
    }
}

impl EnvDistribution {
    /// The tables of `map`, or `None` when the map is black everywhere (nothing to sample).
    pub fn new(map: &EnvMap) -> Option<EnvDistribution> {
        let (w, rows) = (map.width, map.height - 1);
        let cos_edge: Vec<f32> = (0..=rows).map(|j| (j as f64 * PI / rows as f64).cos() as f32).collect();
        let lum: Vec<f64> = map.texels.iter().map(|c| luminance(*c) as f64).collect();
        let at = |i: u32, j: u32| lum[(j * w + i % w) as usize];
        let mut weight = vec![0f64; (w * rows) as usize];
        for j in 0..rows {
            let omega = (2.0 * PI / w as f64) * ((j as f64 * PI / rows as f64).cos() - ((j + 1) as f64 * PI / rows as f64).cos());
            for i in 0..w {
                let mean = 0.25 * (at(i, j) + at(i + 1, j) + at(i, j + 1) + at(i + 1, j + 1));
                weight[(j * w + i) as usize] = mean * omega;
            }
        }
        let total: f64 = weight.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let mut row_cdf = Vec::with_capacity(rows as usize + 1);
        let mut col_cdf = Vec::with_capacity(((w + 1) * rows) as usize);
        let mut acc = 0f64;
        row_cdf.push(0.0);
        for j in 0..rows {
            let row = &weight[(j * w) as usize..((j + 1) * w) as usize];
            let row_sum: f64 = row.iter().sum();
            let mut c = 0f64;
            col_cdf.push(0.0);
            for x in row {
                c += x;
                // An empty row is never chosen; give it a uniform table anyway.
                col_cdf.push(if row_sum > 0.0 { (c / row_sum) as f32 } else { 0.0 });
            }
            if row_sum <= 0.0 {
                let start = col_cdf.len() - w as usize - 1;
                for (k, v) in col_cdf[start..].iter_mut().enumerate() {
                    *v = k as f32 / w as f32;
                }
            }
            *col_cdf.last_mut().expect("a row") = 1.0;
            acc += row_sum;
            row_cdf.push((acc / total) as f32);
        }
        *row_cdf.last_mut().expect("a row") = 1.0;
        let cell_p = weight.iter().map(|x| (x / total) as f32).collect();
        let row_guide = Guide::new(&row_cdf, rows as usize + 1, 1);
        let col_guide = Guide::new(&col_cdf, w as usize + 1, rows as usize);
        Some(EnvDistribution { width: w, rows, cos_edge, row_cdf, col_cdf, cell_p, row_guide, col_guide })
    }

    /// A direction in the map's frame for u in [0, 1)², with its pdf in 1/sr.
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let (j, fy) = pick(&self.row_cdf, self.row_guide.as_ref().map(|g| (g, 0)), u.y);
        let w = self.width as usize;
        let (i, fx) = pick(&self.col_cdf[j * (w + 1)..(j + 1) * (w + 1)], self.col_guide.as_ref().map(|g| (g, j)), u.x);
        // Uniform in φ and cos θ within the cell: uniform in solid angle.
        let (c0, c1) = (self.cos_edge[j], self.cos_edge[j + 1]);
        let cos_t = (c0 + (c1 - c0) * fy).clamp(-1.0, 1.0);
        let sin_t = ((1.0 - cos_t) * (1.0 + cos_t)).max(0.0).sqrt();
        let u_map = (i as f32 + 0.5 + fx) / self.width as f32;
        let (sin_p, cos_p) = sin_cos(std::f32::consts::TAU * u_map);
        let d = Vec3::new(sin_p * sin_t, cos_t, -cos_p * sin_t);
        (d, self.cell_p[j * w + i] / self.omega(j))
    }

    /// The pdf (1/sr) of sampling the map-frame unit direction `d`.
    pub fn pdf(&self, d: Vec3) -> f32 {
        self.pdf_at(direction_to_uv(d))
    }

    /// [`pdf`](Self::pdf) of the direction whose map coordinates are `uv` ([`direction_to_uv`]).
    #[inline]
    pub fn pdf_at(&self, uv: Vec2) -> f32 {
        if !uv.is_finite() {
            return 0.0;
        }
        let w = self.width as f32;
        let x = uv.x - 0.5 / w;
        let x = (x - x.floor()) * w;
        let i = (x as u32).min(self.width - 1);
        let j = ((uv.y * self.rows as f32) as u32).min(self.rows - 1);
        self.cell_p[(j * self.width + i) as usize] / self.omega(j as usize)
    }

    /// Solid angle of a cell of row `j`.
    #[inline]
    fn omega(&self, j: usize) -> f32 {
        (std::f32::consts::TAU / self.width as f32) * (self.cos_edge[j] - self.cos_edge[j + 1])
    }
}

/// The interval k of a cumulative table with cdf[k] ≤ u < cdf[k + 1] (never an empty one),
/// and u's position within it in [0, 1); `guide` (a guide table and which of its tables is
/// `cdf`) only makes the search faster.
#[inline]
fn pick(cdf: &[f32], guide: Option<(&Guide, usize)>, u: f32) -> (usize, f32) {
    let n = cdf.len() - 1;
    // The first edge above u, minus one; skip intervals of zero width.
    let above = match guide {
        Some((g, table)) => g.first_above(cdf, table, u),
        None => cdf.partition_point(|&c| c <= u),
    };
    let mut k = above.saturating_sub(1).min(n - 1);
    while k + 1 < n && cdf[k + 1] <= cdf[k] {
        k += 1;
    }
    while k > 0 && cdf[k + 1] <= cdf[k] {
        k -= 1;
    }
    let width = cdf[k + 1] - cdf[k];
    let f = if width > 0.0 { ((u - cdf[k]) / width).clamp(0.0, 1.0 - f32::EPSILON / 2.0) } else { 0.5 };
    (k, f)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sampling::sample_2d;
    use crate::scene::environment::uv_to_direction;

    /// A 64 × 32 map with a bright patch and a dim rest.
    fn patchy() -> EnvMap {
        EnvMap::from_fn(64, 32, |d| if d.x > 0.7 && d.y > 0.2 { Vec3::new(50.0, 40.0, 30.0) } else { Vec3::splat(0.2) })
    }

    /// Random values in [0, 1) with the awkward ones: 0, 1 − ε, the tables' own steps and
    /// their neighbours, bucket edges, and values outside [0, 1).
    fn probes(cdf: &[f32], seed: u32) -> Vec<f32> {
        let mut u: Vec<f32> = (0..4000).map(|k| sample_2d(k, seed).x).collect();
        u.extend([0.0, 1.0 - f32::EPSILON / 2.0, 0.5, 0.25, 1.0, 1.5, -0.0, -1e-9, f32::NAN, f32::INFINITY]);
        for &c in cdf {
            u.extend([c, c.next_down(), c.next_up()]);
        }
        u
    }

    /// A table with empty intervals, runs of equal steps and a steep part.
    fn awkward_cdf() -> Vec<f32> {
        let w = [0.0, 0.0, 3.0, 0.0, 1e-6, 1e-6, 5.0, 0.0, 0.0, 0.25, 0.25, 0.25, 40.0, 0.0, 1.0, 0.0];
        let total: f32 = w.iter().sum();
        let mut c = vec![0.0];
        let mut acc = 0.0;
        for x in w {
            acc += x;
            c.push(acc / total);
        }
        *c.last_mut().unwrap() = 1.0;
        c
    }

    #[test]
    fn the_guide_table_finds_the_index_the_binary_search_finds() {
        let cdf = awkward_cdf();
        let guide = Guide::new(&cdf, cdf.len(), 1).expect("monotone");
        for u in probes(&cdf, 5) {
            let want = cdf.partition_point(|&c| c <= u);
            assert_eq!(guide.first_above(&cdf, 0, u), want, "u = {u}");
            let (a, b) = (pick(&cdf, Some((&guide, 0)), u), pick(&cdf, None, u));
            assert!(a.0 == b.0 && a.1.to_bits() == b.1.to_bits(), "u = {u}: {a:?} against {b:?}");
        }
        // Every bucket entry is the count of edges at or below the bucket's start.
        for b in 0..=guide.buckets {
            let t = b as f32 / guide.buckets as f32;
            assert_eq!(guide.start[b] as usize, cdf.partition_point(|&c| c <= t), "bucket {b}");
        }
        // A table that is not monotone gets no guide.
        assert_eq!(Guide::new(&[0.0, 0.6, 0.4, 1.0], 4, 1), None);
    }

    #[test]
    fn guided_sampling_of_a_map_equals_the_binary_search_bit_for_bit() {
        let dist = EnvDistribution::new(&patchy()).unwrap();
        let plain = EnvDistribution { row_guide: None, col_guide: None, ..dist.clone() };
        let w = dist.width as usize + 1;
        for k in 0..20000 {
            let u = sample_2d(k, 11);
            let (a, b) = (dist.sample(u), plain.sample(u));
            assert!(a.0.to_array().map(f32::to_bits) == b.0.to_array().map(f32::to_bits) && a.1.to_bits() == b.1.to_bits(), "u = {u:?}");
        }
        // Row by row, on each table's own steps.
        for j in 0..dist.rows as usize {
            let cdf = &dist.col_cdf[j * w..(j + 1) * w];
            for u in probes(cdf, j as u32).into_iter().step_by(7) {
                assert_eq!(dist.col_guide.as_ref().unwrap().first_above(cdf, j, u), cdf.partition_point(|&c| c <= u), "row {j}, u = {u}");
            }
        }
    }

    #[test]
    fn the_pdf_integrates_to_one_and_matches_the_sampled_pdf() {
        let map = patchy();
        let dist = EnvDistribution::new(&map).unwrap();
        // ∫ pdf dω by a fine midpoint rule in (u, cos θ).
        let (nu, nc) = (512, 512);
        let mut sum = 0f64;
        for a in 0..nu {
            for b in 0..nc {
                let cos_t = 1.0 - 2.0 * (b as f64 + 0.5) / nc as f64;
                let v = cos_t.acos() / PI;
                let d = uv_to_direction(Vec2::new((a as f32 + 0.5) / nu as f32, v as f32));
                sum += dist.pdf(d) as f64 * (4.0 * PI / (nu * nc) as f64);
            }
        }
        assert!((sum - 1.0).abs() < 2e-3, "∫ pdf = {sum}");
        for k in 0..2000 {
            let (d, pdf) = dist.sample(sample_2d(k, 7));
            assert!((d.length() - 1.0).abs() < 1e-5);
            let again = dist.pdf(d);
            assert!((pdf - again).abs() <= 1e-3 * pdf.max(1e-3), "sample {k}: {pdf} vs {again} at {d:?}");
        }
    }

    #[test]
    fn the_estimate_of_the_maps_power_is_exact_in_expectation() {
        // E[L(ω)/pdf(ω)] = ∫ L dω: the mean of L/pdf over many samples approaches the
        // integral by the fine rule.
        let map = patchy();
        let dist = EnvDistribution::new(&map).unwrap();
        let lum = |d: Vec3| luminance(map.lookup(direction_to_uv(d))) as f64;
        let n = 1 << 16;
        let mc: f64 = (0..n)
            .map(|k| {
                let (d, pdf) = dist.sample(sample_2d(k, 3));
                lum(d) / pdf as f64
            })
            .sum::<f64>()
            / n as f64;
        let (nu, nc) = (1024, 1024);
        let mut exact = 0f64;
        for a in 0..nu {
            for b in 0..nc {
                let cos_t = 1.0 - 2.0 * (b as f64 + 0.5) / nc as f64;
                let d = uv_to_direction(Vec2::new((a as f32 + 0.5) / nu as f32, (cos_t.acos() / PI) as f32));
                exact += lum(d) * 4.0 * PI / (nu * nc) as f64;
            }
        }
        assert!((mc / exact - 1.0).abs() < 5e-3, "MC {mc} against {exact}");
    }
}
