//! The prefilter pass: the map convolved once per map and size, so that shading reads
//! image-based lighting with a few lookups (Karis 2013, "Real Shading in Unreal Engine 4",
//! the split sum; the diffuse part as in Ramamoorthi & Hanrahan 2001 and as a convolved map).
//!
//! - **Specular**: [`LEVELS`] maps for roughness r_k = k/(LEVELS − 1) (α = r²): level 0 is the
//!   map itself (a mirror), level k the map convolved with the GGX lobe about n = v = r,
//!   weighted by n·l (Karis' `PrefilterEnvMap`, his eq. 5 right-hand factor), at
//!   `prefilter_size` × `prefilter_size`/2 texels halving with each level. Each texel takes the same
//!   [`PREFILTER_SAMPLES`] GGX samples read from a mip of the map chosen by the sample's pdf
//!   (filtered importance sampling, Colbert & Křivánek 2007, GPU Gems 3 ch. 20), so a bright
//!   spot does not alias into sparkles. Between levels, [`Prefiltered::radiance_lod`] blends
//!   linearly in r.
//! - **Diffuse**: the irradiance E(n) = ∫ L max(n·l, 0) dω as 9 SH coefficients
//!   ([`ShIrradiance`]) and as a 64 × 32 map convolved by brute force from a 128 × 64 mip.
//!
//! Results are kept per map and size for the run ([`Prefiltered::cached`]): the cells of a
//! figure convolve once.

use super::sh::ShIrradiance;
use crate::geometry::sampling::{hash, sample_2d, sin_cos};
use crate::scene::EnvMap;
use crate::scene::environment::{direction_to_uv, uv_to_direction};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Roughness levels of the specular chain.
pub const LEVELS: usize = 6;
/// GGX samples per prefiltered texel.
pub const PREFILTER_SAMPLES: u32 = 128;

/// A map convolved for image-based lighting.
#[derive(Debug, Clone)]
pub struct Prefiltered {
    /// Level k holds the map convolved for roughness k/(LEVELS − 1); level 0 is the map itself.
    pub levels: Vec<Arc<EnvMap>>,
    /// Irradiance E(n) on a 64 × 32 map.
    pub irradiance: EnvMap,
    /// Irradiance as nine SH coefficients.
    pub sh: ShIrradiance,
    /// Width of level 1.
    pub size: u32,
    /// Wall time of the convolution, in milliseconds.
    pub millis: f64,
}

/// The cache: (map address, size) → its convolution (the entry holds the map, so the address is never reused).
type Cache = Mutex<Vec<(Arc<EnvMap>, u32, Arc<Prefiltered>)>>;
static CACHE: Cache = Mutex::new(Vec::new());

impl Prefiltered {
    /// The convolution of `map` at `size` from the cache, and whether it was there; computed
    /// and kept when not.
    pub fn cached(map: &Arc<EnvMap>, size: u32) -> (Arc<Prefiltered>, bool) {
        if let Some(p) = Prefiltered::lookup(map, size) {
            return (p, true);
        }
        // Then an earlier run's, from the on-disk cache, keyed by the map's texels.
        let key = crate::cache::dir().map(|_| {
            let mut k = crate::cache::KeyBuilder::new("prefilter");
            k.part(&size.to_le_bytes()).part(&[map.width, map.height].map(u32::to_le_bytes).concat());
            let mut texels = Vec::with_capacity(map.texels.len() * 12);
            crate::cache::put_f32s(&mut texels, map.texels.iter().flat_map(|t| t.to_array()));
            k.part(&texels);
            k.finish()
        });
        let kept = key.as_ref().and_then(crate::cache::get).and_then(|b| Prefiltered::from_bytes(map, size, &b));
        let p = Arc::new(match kept {
            Some(p) => p,
            None => {
                let p = Prefiltered::new(map, size);
                if let Some(key) = key.filter(|_| p.millis >= crate::cache::MIN_KEPT_MS) {
                    crate::cache::put(&key, &p.to_bytes());
                }
                p
            }
        });
        let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        // A few maps per run; keep the last sixteen.
        if cache.len() >= 16 {
            cache.remove(0);
        }
        cache.push((map.clone(), size, p.clone()));
        (p, false)
    }

    /// The cached convolution of `map` at `size`, if any.
    pub fn lookup(map: &Arc<EnvMap>, size: u32) -> Option<Arc<Prefiltered>> {
        let cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        cache.iter().find(|(m, s, _)| Arc::ptr_eq(m, map) && *s == size).map(|(_, _, p)| p.clone())
    }

    /// The levels above 0, the irradiance map, the SH coefficients and the time as bytes,
    /// every float bit-exact (the map itself, level 0, is the key's).
    fn to_bytes(&self) -> Vec<u8> {
        let mut b = self.millis.to_le_bytes().to_vec();
        for m in self.levels.iter().skip(1).map(|m| &**m).chain([&self.irradiance]) {
            b.extend([m.width, m.height].map(u32::to_le_bytes).concat());
            crate::cache::put_f32s(&mut b, m.texels.iter().flat_map(|t| t.to_array()));
        }
        crate::cache::put_f32s(&mut b, self.sh.coefficients.iter().flat_map(|c| c.to_array()));
        b
    }

    /// [`Prefiltered::to_bytes`] read back for `map` at `size`, or `None` when the bytes are
    /// not that.
    fn from_bytes(map: &Arc<EnvMap>, size: u32, b: &[u8]) -> Option<Prefiltered> {
        let mut r = crate::cache::Reader::new(b);
        let millis = r.f64()?;
        let mut maps = Vec::with_capacity(LEVELS);
        for _ in 0..LEVELS {
            let (width, height) = (r.u32()?, r.u32()?);
            let texels = r.vec3s((width as usize).checked_mul(height as usize)?)?;
            maps.push(EnvMap { width, height, texels });
        }
        let sh = r.vec3s(9)?;
        if !r.is_done() {
            return None;
        }
        let irradiance = maps.pop().expect("LEVELS maps");
        let coefficients = std::array::from_fn(|i| sh[i]);
        let levels = std::iter::once(map.clone()).chain(maps.into_iter().map(Arc::new)).collect();
        Some(Prefiltered { levels, irradiance, sh: ShIrradiance { coefficients }, size, millis })
    }

    /// Convolves `map`: the specular chain with level 1 `size` texels wide, the irradiance.
    pub fn new(map: &Arc<EnvMap>, size: u32) -> Prefiltered {
        let start = Instant::now();
        let mips = mip_chain(map);
        let mut levels = vec![map.clone()];
        for k in 1..LEVELS {
            let r = k as f32 / (LEVELS - 1) as f32;
            let w = (size >> (k - 1)).max(16);
            levels.push(Arc::new(convolve_ggx(&mips, r * r, w)));
        }
        let small = mips.iter().find(|m| m.width <= 128).unwrap_or(mips.last().expect("a mip"));
        let irradiance = irradiance_map(small, 64);
        let sh = ShIrradiance::project(small);
        Prefiltered { levels, irradiance, sh, size, millis: start.elapsed().as_secs_f64() * 1e3 }
    }

    /// The prefiltered radiance about the map-frame direction `r` for perceptual roughness
    /// `roughness` in [0, 1]: linear between the two nearest levels.
    #[inline]
    pub fn radiance_lod(&self, r: Vec3, roughness: f32) -> Vec3 {
        let x = roughness.clamp(0.0, 1.0) * (LEVELS - 1) as f32;
        let k = (x as usize).min(LEVELS - 2);
        let f = x - k as f32;
        let uv = direction_to_uv(r);
        let a = self.levels[k].lookup(uv);
        if f <= 0.0 {
            return a;
        }
        a * (1.0 - f) + self.levels[k + 1].lookup(uv) * f
    }

    /// Irradiance at the map-frame unit normal `n`, from the convolved map.
    #[inline]
    pub fn irradiance_map(&self, n: Vec3) -> Vec3 {
        self.irradiance.lookup(direction_to_uv(n))
    }
}

/// The map and its box-filtered halvings down to 8 × 4.
fn mip_chain(map: &EnvMap) -> Vec<EnvMap> {
    let mut mips = vec![map.clone()];
    while mips.last().expect("a mip").width >= 16 && mips.last().expect("a mip").height >= 8 {
        let m = mips.last().expect("a mip");
        let (w, h) = (m.width / 2, m.height / 2);
        let texels = (0..h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| {
                (m.texel(2 * i, 2 * j) + m.texel(2 * i + 1, 2 * j) + m.texel(2 * i, 2 * j + 1) + m.texel(2 * i + 1, 2 * j + 1)) * 0.25
            })
            .collect();
        mips.push(EnvMap { width: w, height: h, texels });
    }
    mips
}

/// Radiance at `uv` from the mip chain at fractional level `lod`.
fn sample_mips(mips: &[EnvMap], uv: Vec2, lod: f32) -> Vec3 {
    let lod = lod.clamp(0.0, (mips.len() - 1) as f32);
    let k = (lod as usize).min(mips.len() - 1);
    let f = lod - k as f32;
    let a = mips[k].lookup(uv);
    if f <= 0.0 || k + 1 >= mips.len() { a } else { a * (1.0 - f) + mips[k + 1].lookup(uv) * f }
}

/// The map convolved with GGX of width `alpha` about n = v = r (Karis 2013), `width` texels wide.
fn convolve_ggx(mips: &[EnvMap], alpha: f32, width: u32) -> EnvMap {
    let height = width / 2;
    let a2 = alpha * alpha;
    let texel_omega = 4.0 * std::f32::consts::PI / (mips[0].width * mips[0].height) as f32;
    let rows: Vec<Vec<Vec3>> = (0..height)
        .into_par_iter()
        .map(|j| {
            (0..width)
                .map(|i| {
                    let uv = Vec2::new((i as f32 + 0.5) / width as f32, j as f32 / (height - 1) as f32);
                    let n = uv_to_direction(uv);
                    let (t, b) = crate::geometry::sampling::basis(n);
                    // One sample pattern for every texel (as Karis' Hammersley set): the
                    // error is then smooth across the map instead of noise from texel to texel.
                    let seed = hash(0x5eed);
                    let (mut sum, mut weight) = (Vec3::ZERO, 0f32);
                    for s in 0..PREFILTER_SAMPLES {
                        let u = sample_2d(s, seed);
                        // GGX half vector (Walter et al. 2007, eqs. 35–36).
                        let cos2 = ((1.0 - u.x) / (1.0 + (a2 - 1.0) * u.x)).clamp(0.0, 1.0);
                        let (cos_h, sin_h) = (cos2.sqrt(), (1.0 - cos2).max(0.0).sqrt());
                        let (sp, cp) = sin_cos(std::f32::consts::TAU * u.y);
                        let h = t * (sin_h * cp) + b * (sin_h * sp) + n * cos_h;
                        let l = 2.0 * n.dot(h) * h - n;
                        let n_l = n.dot(l);
                        if n_l <= 0.0 {
                            continue;
                        }
                        // pdf(l) = D(h) cos θ_h / (4 v·h) = D / 4 with v = n.
                        let d = a2 / (std::f32::consts::PI * ((a2 - 1.0) * cos2 + 1.0).powi(2));
                        let omega_s = 4.0 / (PREFILTER_SAMPLES as f32 * d);
                        // Colbert & Křivánek add 1 to this level; without it the blur leaks less
                        // of the studio's lamps into the dark around them (the ibl ladder of
                        // lesson 30 at 128²: RMSE 2.33 → 2.22 against Monte Carlo).
                        let lod = 0.5 * (omega_s / texel_omega).log2();
                        sum += sample_mips(mips, direction_to_uv(l.normalize()), lod) * n_l;
                        weight += n_l;
                    }
                    if weight > 0.0 { sum / weight } else { Vec3::ZERO }
                })
                .collect()
        })
        .collect();
    EnvMap { width, height, texels: rows.concat() }
}

/// E(n) = Σ_texels L max(n·l, 0) Ω on a `width` × `width`/2 map, from the small map `m`.
fn irradiance_map(m: &EnvMap, width: u32) -> EnvMap {
    let height = width / 2;
    let step = std::f64::consts::PI / (m.height - 1) as f64;
    let sources: Vec<(Vec3, Vec3)> = (0..m.height)
        .flat_map(|j| (0..m.width).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (a, b) = (((j as f64 - 0.5) * step).max(0.0), ((j as f64 + 0.5) * step).min(std::f64::consts::PI));
            let omega = (2.0 * std::f64::consts::PI / m.width as f64) * (a.cos() - b.cos());
            let d = uv_to_direction(Vec2::new((i as f32 + 0.5) / m.width as f32, j as f32 / (m.height - 1) as f32));
            (d, m.texel(i, j) * omega as f32)
        })
        .collect();
    let texels: Vec<Vec3> = (0..height * width)
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k % width, k / width);
            let n = uv_to_direction(Vec2::new((i as f32 + 0.5) / width as f32, j as f32 / (height - 1) as f32));
            sources.iter().fold(Vec3::ZERO, |e, (d, l)| e + *l * n.dot(*d).max(0.0))
        })
        .collect();
    EnvMap { width, height, texels }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_map_stays_constant_at_every_roughness_and_its_irradiance_is_pi_l() {
        let map = Arc::new(EnvMap::constant(Vec3::splat(2.0), 128));
        let p = Prefiltered::new(&map, 64);
        for r in [0.0, 0.3, 0.7, 1.0] {
            for d in [Vec3::Y, Vec3::X, Vec3::new(0.0, -0.6, 0.8)] {
                let c = p.radiance_lod(d, r);
                assert!((c - Vec3::splat(2.0)).abs().max_element() < 1e-4, "r {r}, {d:?}: {c:?}");
            }
        }
        let e = p.irradiance_map(Vec3::new(0.36, 0.48, 0.8));
        assert!((e.x / (2.0 * std::f32::consts::PI) - 1.0).abs() < 2e-3, "{e:?}");
    }

    #[test]
    fn a_convolution_survives_bytes_bit_for_bit() {
        let map = Arc::new(EnvMap::gradient(Vec3::new(2.0, 1.5, 1.0), Vec3::splat(0.5), Vec3::splat(0.1)));
        let p = Prefiltered::new(&map, 32);
        let b = p.to_bytes();
        let q = Prefiltered::from_bytes(&map, 32, &b).expect("decodes");
        assert!(q.levels.iter().zip(&p.levels).all(|(a, b)| a == b) && q.levels.len() == LEVELS);
        assert!(Arc::ptr_eq(&q.levels[0], &map), "level 0 is the map itself");
        assert_eq!((q.irradiance == p.irradiance, q.sh, q.size, q.millis), (true, p.sh, 32, p.millis));
        assert!(Prefiltered::from_bytes(&map, 32, &b[..b.len() - 1]).is_none());
        assert!(Prefiltered::from_bytes(&map, 32, &[b.as_slice(), &[0]].concat()).is_none());
    }

    #[test]
    fn the_cache_convolves_a_map_once_per_size() {
        let map = Arc::new(EnvMap::constant(Vec3::ONE, 32));
        let (a, hit_a) = Prefiltered::cached(&map, 32);
        let (b, hit_b) = Prefiltered::cached(&map, 32);
        let (_, hit_c) = Prefiltered::cached(&map, 16);
        assert!(!hit_a && hit_b && !hit_c && Arc::ptr_eq(&a, &b));
    }
}
