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
        Some(EnvDistribution { width: w, rows, cos_edge, row_cdf, col_cdf, cell_p })
    }

    /// A direction in the map's frame for u in [0, 1)², with its pdf in 1/sr.
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let (j, fy) = pick(&self.row_cdf, u.y);
        let w = self.width as usize;
        let (i, fx) = pick(&self.col_cdf[j * (w + 1)..(j + 1) * (w + 1)], u.x);
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
        let uv = direction_to_uv(d);
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
/// and u's position within it in [0, 1).
fn pick(cdf: &[f32], u: f32) -> (usize, f32) {
    let n = cdf.len() - 1;
    // The first edge above u, minus one; skip intervals of zero width.
    let mut k = cdf.partition_point(|&c| c <= u).saturating_sub(1).min(n - 1);
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
