//! Photon maps (Jensen 1996; Jensen 2001, "Realistic Image Synthesis Using Photon Mapping",
//! ch. 7 to 9): light traced from the lamps ([`trace`]), stored where it lands and read back
//! by density estimation.
//!
//! **Two maps.** The *caustic map* holds the photons that passed at least one mirror or glass
//! and then met a diffuse surface (the paths L S⁺ D of Heckbert's notation); the *global map*
//! (`[render] indirect = "photons"`) holds the photons at every diffuse surface they meet,
//! carried on by Russian roulette on the BRDF's albedo. Rough glass ends a photon unstored:
//! the path tracer samples it with next-event estimation and keeps every path through it.
//!
//! **Gathering.** At a point x with BRDF f seen from ω_o, the reflected radiance of the map's
//! light is L_r ≈ Σ f(ω_p, ω_o) ΔΦ_p / (π r²) over the photons near x that arrived on x's
//! side (Jensen 2001, eq. 7.6). With `photon_gather = "radius"` they are the photons within a
//! fixed r, the sphere flattened to a disc (|(x_p − x)·n| ≤ r/4) so a nearby wall's photons do
//! not leak in; with `"nearest"` they are the k nearest in the same flattened metric, r the
//! k-th one's distance, capped by the fixed radius (Jensen's maximum search distance). The
//! estimate is biased (the light is blurred over r) and consistent: it converges as photons
//! grow and r shrinks. The photons are kept in a hashed grid (pbrt-v3's SPPM grid): cells of
//! side r for a fixed radius (a gather reads 27 cells), r/4 for the nearest, whose search
//! grows ring by ring until the k-th photon lies inside the rings read.
//!
//! **With the path tracer.** The caustic map replaces exactly the paths it holds: the
//! camera's path gathers it at the first surface that is not a mirror or glass, and from there
//! a path that reaches a lamp through mirrors and glass only (D S⁺ L) no longer counts that
//! lamp. The global map is read by the final gather ([`super::gather`]).

mod trace;

use crate::geometry::sampling::hash3;
use crate::lesson::settings::PhotonGather;
use glam::Vec3;
use std::collections::BinaryHeap;

pub use trace::{Photons, trace};

/// One stored photon.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Photon {
    /// Where it landed.
    pub p: Vec3,
    /// Unit direction back to where it came from.
    pub wi: Vec3,
    /// Its flux ΔΦ (W).
    pub power: Vec3,
}

/// A photon map: the photons, sorted by grid cell, and how it is gathered.
#[derive(Debug, Clone)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// For hashed cell h, its photons are `photons[starts[h]..starts[h + 1]]`.
    starts: Vec<u32>,
    /// The side of a grid cell.
    cell: f32,
    /// The fixed radius, or the k-nearest search's cap.
    radius: f32,
    /// k for a k-nearest gather, 0 for a fixed radius.
    k: u32,
}

/// Grid cells across the fixed radius for a k-nearest gather: its search grows by rings of r/4.
const NEAREST_CELLS: i32 = 4;

impl PhotonMap {
    /// The map of `photons` gathered within `radius` (a counting sort by hashed cell).
    pub fn build(photons: Vec<Photon>, radius: f32) -> PhotonMap {
        PhotonMap::with_gather(photons, radius, PhotonGather::Radius, 0)
    }

    /// The map of `photons` gathered within `radius` or by the `k` nearest within it.
    pub fn with_gather(mut photons: Vec<Photon>, radius: f32, gather: PhotonGather, k: u32) -> PhotonMap {
        let (cell, k) = match gather {
            PhotonGather::Radius => (radius, 0),
            PhotonGather::Nearest => (radius / NEAREST_CELLS as f32, k.max(1)),
        };
        let cells = (2 * photons.len()).next_power_of_two().max(1);
        let key = |p: &Photon| cell_hash(cell_of(p.p, cell), cells);
        let mut starts = vec![0u32; cells + 1];
        photons.iter().for_each(|p| starts[key(p) + 1] += 1);
        for h in 0..cells {
            starts[h + 1] += starts[h];
        }
        photons.sort_by_key(key);
        PhotonMap { photons, starts, cell, radius, k }
    }

    /// Photons stored.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// True when no photon was stored.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// L_r at `x` with unit geometric normal `ng` (the side the view is on): Σ f(ω_p) ΔΦ_p /
    /// (π r²) over the gathered photons that arrived on that side; `f(ω_p)` is the BRDF
    /// towards the viewer for the world direction ω_p.
    pub fn estimate(&self, x: Vec3, ng: Vec3, f: impl Fn(Vec3) -> Vec3) -> Vec3 {
        if self.photons.is_empty() {
            return Vec3::ZERO;
        }
        if self.k > 0 {
            let (near, r2) = self.nearest(x, ng, self.k);
            let sum: Vec3 = near.iter().map(|&i| f(self.photons[i].wi) * self.photons[i].power).sum();
            // r2 > 0: a photon exactly at x alone would set r = 0; the cap's cell keeps it finite.
            return sum / (std::f32::consts::PI * r2.max(self.cell * self.cell * 1e-4));
        }
        let r = self.radius;
        let cells = self.starts.len() - 1;
        let c = cell_of(x, r);
        let mut sum = Vec3::ZERO;
        let mut seen = [usize::MAX; 27];
        for (j, o) in (0..27).map(|j| (j, [j % 3, (j / 3) % 3, j / 9])) {
            let h = cell_hash([c[0] + o[0] as i32 - 1, c[1] + o[1] as i32 - 1, c[2] + o[2] as i32 - 1], cells);
            // Two neighbours may hash alike: read each bucket once.
            if seen[..j].contains(&h) {
                continue;
            }
            seen[j] = h;
            for p in &self.photons[self.starts[h] as usize..self.starts[h + 1] as usize] {
                let to = p.p - x;
                let along = to.dot(ng);
                if to.length_squared() <= r * r && along.abs() <= 0.25 * r && p.wi.dot(ng) > 0.0 {
                    sum += f(p.wi) * p.power;
                }
            }
        }
        sum / (std::f32::consts::PI * r * r)
    }

    /// The (at most) `k` photons nearest `x` on the side of `ng` in the flattened metric
    /// d² = |x_p − x|² + 15 ((x_p − x)·n)² (a disc of thickness r/4, as the fixed radius's),
    /// within the fixed radius: their indices and r², the k-th one's d² (the cap's r² when
    /// fewer are found). The rings of cells about x are read until the k-th photon found lies
    /// within the rings read, whose every point is at least `ring × cell` from x.
    pub fn nearest(&self, x: Vec3, ng: Vec3, k: u32) -> (Vec<usize>, f32) {
        let k = k.max(1) as usize;
        let cells = self.starts.len() - 1;
        let c = cell_of(x, self.cell);
        let cap2 = self.radius * self.radius;
        // A max-heap of (d² as ordered bits, index): d² ≥ 0, so its bits order as the floats.
        let mut heap: BinaryHeap<(u32, usize)> = BinaryHeap::with_capacity(k + 1);
        let rings = (self.radius / self.cell).ceil() as i32 + 1;
        for ring in 0..=rings {
            for dz in -ring..=ring {
                for dy in -ring..=ring {
                    for dx in -ring..=ring {
                        // The shell of the ring only: the inside was read before.
                        if dx.abs().max(dy.abs()).max(dz.abs()) != ring {
                            continue;
                        }
                        let cc = [c[0] + dx, c[1] + dy, c[2] + dz];
                        let h = cell_hash(cc, cells);
                        for i in self.starts[h] as usize..self.starts[h + 1] as usize {
                            let p = &self.photons[i];
                            // A bucket holds every cell hashed to it: take this cell's photons only.
                            if cell_of(p.p, self.cell) != cc || p.wi.dot(ng) <= 0.0 {
                                continue;
                            }
                            let to = p.p - x;
                            let along = to.dot(ng);
                            let d2 = to.length_squared() + 15.0 * along * along;
                            if d2 > cap2 {
                                continue;
                            }
                            if heap.len() < k {
                                heap.push((d2.to_bits(), i));
                            } else if d2.to_bits() < heap.peek().map_or(u32::MAX, |t| t.0) {
                                heap.pop();
                                heap.push((d2.to_bits(), i));
                            }
                        }
                    }
                }
            }
            let reach = ring as f32 * self.cell;
            if heap.len() == k && heap.peek().is_some_and(|t| f32::from_bits(t.0) <= reach * reach) {
                break;
            }
        }
        let r2 = if heap.len() == k { heap.peek().map_or(cap2, |t| f32::from_bits(t.0)) } else { cap2 };
        let mut near: Vec<usize> = heap.into_iter().map(|t| t.1).collect();
        near.sort_unstable();
        (near, r2)
    }
}

/// The grid cell of `p` for cells of side `r`.
fn cell_of(p: Vec3, r: f32) -> [i32; 3] {
    let c = (p / r).floor();
    [c.x as i32, c.y as i32, c.z as i32]
}

/// The bucket of cell `c` among `cells` (a power of two).
fn cell_hash(c: [i32; 3], cells: usize) -> usize {
    hash3(c[0] as u32, c[1] as u32, c[2] as u32) as usize & (cells - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_flux_gives_its_irradiance_times_the_brdf() {
        // Photons of 1e-4 W each, 1e4 per m² on the plane y = 0: E = 1 W/m²; a Lambertian
        // BRDF ρ/π reflects ρE/π.
        let mut photons = Vec::new();
        for i in 0..400 {
            for j in 0..400 {
                let p = Vec3::new(-2.0 + (i as f32 + 0.5) * 0.01, 0.0, -2.0 + (j as f32 + 0.5) * 0.01);
                photons.push(Photon { p, wi: Vec3::new(0.3, 0.9, 0.1).normalize(), power: Vec3::splat(1e-4) });
            }
        }
        let map = PhotonMap::build(photons, 0.1);
        let rho = 0.5;
        let l = map.estimate(Vec3::new(0.013, 0.0, -0.27), Vec3::Y, |_| Vec3::splat(rho / std::f32::consts::PI));
        let expected = rho / std::f32::consts::PI;
        assert!((l.x / expected - 1.0).abs() < 0.02, "{l} against {expected}");
        // The other side of the plane, and a point a disc's thickness above it, see none.
        assert_eq!(map.estimate(Vec3::new(0.0, 0.0, 0.0), -Vec3::Y, |_| Vec3::ONE), Vec3::ZERO);
        assert_eq!(map.estimate(Vec3::new(0.0, 0.05, 0.0), Vec3::Y, |_| Vec3::ONE), Vec3::ZERO);
    }

    #[test]
    fn the_grid_finds_every_photon_within_the_radius() {
        // Scattered photons: the gather equals a brute-force sum over all of them.
        let photons: Vec<Photon> = (0..5000u32)
            .map(|k| {
                let h = |s: u32| (hash3(k, s, 7) >> 8) as f32 / (1u32 << 24) as f32;
                Photon { p: Vec3::new(h(0) * 2.0 - 1.0, (h(1) - 0.5) * 0.02, h(2) * 2.0 - 1.0), wi: Vec3::Y, power: Vec3::splat(h(3)) }
            })
            .collect();
        let r = 0.07;
        let map = PhotonMap::build(photons.clone(), r);
        for q in [Vec3::ZERO, Vec3::new(0.5, 0.0, -0.93), Vec3::new(-0.999, 0.0, 0.999)] {
            let brute: Vec3 = photons
                .iter()
                .filter(|p| (p.p - q).length_squared() <= r * r && (p.p - q).y.abs() <= 0.25 * r)
                .map(|p| p.power)
                .sum::<Vec3>()
                / (std::f32::consts::PI * r * r);
            let got = map.estimate(q, Vec3::Y, |_| Vec3::ONE);
            assert!((got - brute).abs().max_element() <= 1e-4 * brute.max_element().max(1.0), "{got} against {brute}");
        }
    }

    #[test]
    fn the_nearest_are_exactly_the_brute_force_nearest() {
        // Photons on two planes and in between, some arriving from below: the k-nearest
        // search returns the set a sort of all of them by the flattened metric gives (ties
        // by index), and r² is the k-th one's, for k and positions whose search needs
        // several rings, and none when the cap is reached first.
        let photons: Vec<Photon> = (0..20_000u32)
            .map(|k| {
                let h = |s: u32| (hash3(k, s, 11) >> 8) as f32 / (1u32 << 24) as f32;
                let y = if k % 3 == 0 { (h(1) - 0.5) * 0.4 } else { 0.0 };
                let wi = if k % 7 == 0 { -Vec3::Y } else { Vec3::new(h(4) - 0.5, 1.0, 0.2).normalize() };
                Photon { p: Vec3::new(h(0) * 2.0 - 1.0, y, h(2) * 2.0 - 1.0), wi, power: Vec3::splat(h(3)) }
            })
            .collect();
        let cap = 0.3;
        let map = PhotonMap::with_gather(photons.clone(), cap, PhotonGather::Nearest, 50);
        // The map keeps its own order: compare the photons, not the indices.
        let key = |p: &Photon| (p.p.x.to_bits(), p.p.y.to_bits(), p.p.z.to_bits());
        for (q, k) in
            [(Vec3::ZERO, 1), (Vec3::new(0.5, 0.0, -0.93), 50), (Vec3::new(-0.999, 0.0, 0.999), 200), (Vec3::new(0.2, 0.1, 0.3), 7)]
        {
            let d2 = |p: &Photon| {
                let to = p.p - q;
                to.length_squared() + 15.0 * to.y * to.y
            };
            let mut brute: Vec<(f32, &Photon)> =
                photons.iter().filter(|p| p.wi.y > 0.0).map(|p| (d2(p), p)).filter(|(d, _)| *d <= cap * cap).collect();
            brute.sort_by(|a, b| a.0.total_cmp(&b.0));
            brute.truncate(k as usize);
            let (near, r2) = map.nearest(q, Vec3::Y, k);
            let mut got: Vec<_> = near.iter().map(|&i| key(&map.photons[i])).collect();
            let mut want: Vec<_> = brute.iter().map(|(_, p)| key(p)).collect();
            got.sort_unstable();
            want.sort_unstable();
            assert_eq!(got, want, "at {q} with k = {k}");
            let expected_r2 = if brute.len() == k as usize { brute.last().unwrap().0 } else { cap * cap };
            assert_eq!(r2, expected_r2, "at {q} with k = {k}");
        }
        // k = 20000 photons cannot all lie within the cap: r² is the cap's.
        assert_eq!(map.nearest(Vec3::ZERO, Vec3::Y, 20_000).1, cap * cap);
    }

    #[test]
    fn the_nearest_gather_of_a_uniform_flux_gives_its_irradiance() {
        // The same uniform 1 W/m² as above, read by its 100 nearest: ρE/π within 5%
        // (k/(π r²) is the density of k photons, biased by (k − 1)/k at most).
        let mut photons = Vec::new();
        for i in 0..400 {
            for j in 0..400 {
                let p = Vec3::new(-2.0 + (i as f32 + 0.5) * 0.01, 0.0, -2.0 + (j as f32 + 0.5) * 0.01);
                photons.push(Photon { p, wi: Vec3::Y, power: Vec3::splat(1e-4) });
            }
        }
        let map = PhotonMap::with_gather(photons, 0.5, PhotonGather::Nearest, 100);
        let l = map.estimate(Vec3::new(0.013, 0.0, -0.27), Vec3::Y, |_| Vec3::splat(0.5 / std::f32::consts::PI));
        let expected = 0.5 / std::f32::consts::PI;
        assert!((l.x / expected - 1.0).abs() < 0.05, "{l} against {expected}");
    }
}
