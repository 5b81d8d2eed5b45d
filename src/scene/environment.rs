//! The environment: a distant light all round the scene, read from a latitude-longitude map
//! (or a procedural gradient sky baked into one), with its intensity and rotation.
//!
//! **Convention** (Mitsuba 3's `envmap`, so a map looks the same in both): for a unit
//! direction d in the map's frame (y up), u = atan2(d.x, −d.z)/(2π) wrapped into [0, 1),
//! v = acos(d.y)/π; row 0 is the top of the image (v = 0, straight up), u = 0 looks down −z,
//! u = ¼ down +x. Texel (i, j) of a W × H map holds the radiance at u = (i + ½)/W,
//! v = j/(H − 1): columns at their centres, the first and last rows on the poles (Mitsuba's
//! `eval_spectrum`: `uv.x −= ½/W`, `uv × (W, H − 1)`). Between texels the radiance is
//! bilinear; the column after the last is the first again (the seam at u = 0 wraps), and the
//! rows are clamped, so there is no NaN at the poles.
//!
//! `rotate_deg` = θ turns the sky about +y (right-handed, as Mitsuba's `to_world` rotation):
//! the world direction d reads the map at R_y(−θ) d.
//!
//! Maps are decoded once per file and kept (an `Arc` per file, keyed by path, length and
//! modification time), so the cells of a figure share one decoded map.

use crate::geometry::sampling::sin_cos;
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::f32::consts::{PI, TAU};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

pub use crate::lesson::environment::{EnvSource, EnvironmentSpec};

/// Linear RGB radiance on a latitude-longitude grid (see the module docs for the convention).
#[derive(Debug, Clone, PartialEq)]
pub struct EnvMap {
    /// Columns.
    pub width: u32,
    /// Rows (row 0 at the top, on the pole above).
    pub height: u32,
    /// Row-major texels, linear RGB.
    pub texels: Vec<Vec3>,
}

/// A map file that cannot be used (bad input).
#[derive(Debug, Clone, thiserror::Error)]
#[error("{message}")]
pub struct EnvError {
    /// What went wrong, without the file name (the caller names the file as the lesson wrote it).
    pub message: String,
}

/// Rec. 709 luminance of linear RGB, Mitsuba's `luminance` (importance sampling weights texels by it).
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    0.212_671 * c.x + 0.715_160 * c.y + 0.072_169 * c.z
}

/// (u, v) of a unit direction in the map's frame: u = atan2(d.x, −d.z)/(2π) in [0, 1), v = acos(d.y)/π in [0, 1].
#[inline]
pub fn direction_to_uv(d: Vec3) -> Vec2 {
    // atan2 and acos in f64, rounded once: the same bits on every machine (as `sampling::sin_cos`).
    let u = ((d.x as f64).atan2(-(d.z as f64)) * (0.5 / std::f64::consts::PI)) as f32;
    let u = u - u.floor();
    // A tiny negative u wraps to exactly 1.
    let u = if u >= 1.0 { 0.0 } else { u };
    Vec2::new(u, ((d.y as f64).clamp(-1.0, 1.0).acos() * std::f64::consts::FRAC_1_PI) as f32)
}

/// The unit direction at (u, v): the inverse of [`direction_to_uv`].
#[inline]
pub fn uv_to_direction(uv: Vec2) -> Vec3 {
    let (sin_t, cos_t) = sin_cos(uv.y * PI);
    let (sin_p, cos_p) = sin_cos(uv.x * TAU);
    Vec3::new(sin_p * sin_t, cos_t, -cos_p * sin_t)
}

impl EnvMap {
    /// A map whose every texel is `c` (tests and the white furnace).
    pub fn constant(c: Vec3, width: u32) -> EnvMap {
        let width = width.max(2);
        let height = (width / 2).max(2);
        EnvMap { width, height, texels: vec![c; (width * height) as usize] }
    }

    /// The map of a function of direction, sampled at the texel positions of the convention.
    pub fn from_fn(width: u32, height: u32, f: impl Fn(Vec3) -> Vec3) -> EnvMap {
        let mut texels = Vec::with_capacity((width * height) as usize);
        for j in 0..height {
            for i in 0..width {
                let uv = Vec2::new((i as f32 + 0.5) / width as f32, j as f32 / (height - 1) as f32);
                texels.push(f(uv_to_direction(uv)));
            }
        }
        EnvMap { width, height, texels }
    }

    /// The procedural sky: L = horizon + (zenith − horizon)·d.y above the horizon (linear in
    /// cos θ, so its irradiance has a closed form), `ground` below; baked at 1024 × 512.
    pub fn gradient(zenith: Vec3, horizon: Vec3, ground: Vec3) -> EnvMap {
        EnvMap::from_fn(1024, 512, |d| if d.y >= 0.0 { horizon + (zenith - horizon) * d.y } else { ground })
    }

    /// Texel (i, j), i wrapping, j clamped.
    #[inline]
    pub fn texel(&self, i: u32, j: u32) -> Vec3 {
        let i = i % self.width;
        let j = j.min(self.height - 1);
        self.texels[(j * self.width + i) as usize]
    }

    /// Bilinear radiance at (u, v) (u wraps, v clamped to [0, 1]); zero for a non-finite (u, v).
    #[inline]
    pub fn lookup(&self, uv: Vec2) -> Vec3 {
        if !uv.is_finite() {
            return Vec3::ZERO;
        }
        let (w, h) = (self.width as f32, self.height as f32);
        let u = uv.x - 0.5 / w;
        let u = u - u.floor();
        let x = u * w;
        let y = uv.y.clamp(0.0, 1.0) * (h - 1.0);
        let i = (x as u32).min(self.width - 1);
        let j = (y as u32).min(self.height - 2);
        let (fx, fy) = ((x - i as f32).clamp(0.0, 1.0), (y - j as f32).clamp(0.0, 1.0));
        let top = self.texel(i, j) * (1.0 - fx) + self.texel(i + 1, j) * fx;
        let bottom = self.texel(i, j + 1) * (1.0 - fx) + self.texel(i + 1, j + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// Decodes a latitude-longitude map: Radiance `.hdr` and OpenEXR as linear radiance, 8-
    /// and 16-bit PNG and JPEG decoded from sRGB.
    ///
    /// # Errors
    /// [`EnvError`] when the file cannot be read or decoded, or is not 2:1.
    pub fn load(path: &Path) -> Result<EnvMap, EnvError> {
        let (width, height, texels) = decode_rgb(path)?;
        if let Some(message) = crate::lesson::environment::latlong_shape_error(width, height) {
            return Err(EnvError { message });
        }
        Ok(EnvMap { width, height, texels })
    }

    /// [`EnvMap::load`] through the cache: each file is decoded once per run.
    ///
    /// # Errors
    /// As [`EnvMap::load`].
    pub fn load_cached(path: &Path) -> Result<Arc<EnvMap>, EnvError> {
        cached("latlong", &[path.to_path_buf()], |_| EnvMap::load(path).map_err(|e| (0, e))).map_err(|(_, e)| e)
    }
}

/// The map made by `make` from `paths`, decoded once per run: keyed by how the files are read
/// (`how`: a file read as a lat-long map and as a cube cross are two maps) and each file's
/// path, length and modification time (an edited file is read again). The prefilter cache is keyed
/// by the `Arc`, so a shared map also shares its prefiltered levels.
///
/// # Errors
/// What `make` returns, or (index of the file, error) when a file's metadata cannot be read.
pub fn cached(
    how: &'static str,
    paths: &[PathBuf],
    make: impl FnOnce(&[PathBuf]) -> Result<EnvMap, (usize, EnvError)>,
) -> Result<Arc<EnvMap>, (usize, EnvError)> {
    type Key = (&'static str, Vec<(PathBuf, u64, Option<std::time::SystemTime>)>);
    static CACHE: OnceLock<Mutex<HashMap<Key, Arc<EnvMap>>>> = OnceLock::new();
    let mut key: Key = (how, Vec::new());
    for (k, path) in paths.iter().enumerate() {
        let meta = crate::files::metadata(path).map_err(|e| (k, EnvError { message: format!("cannot read the map: {e}") }))?;
        key.1.push((path.clone(), meta.len, meta.modified));
    }
    let cache = CACHE.get_or_init(Default::default);
    if let Some(m) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return Ok(m.clone());
    }
    let map = Arc::new(make(paths)?);
    cache.lock().unwrap_or_else(|e| e.into_inner()).insert(key, map.clone());
    Ok(map)
}

/// Decodes an image to linear RGB texels, row-major from the top row: Radiance `.hdr` and
/// OpenEXR as linear, 8- and 16-bit PNG and JPEG from sRGB; negative or non-finite texels are zero.
///
/// # Errors
/// [`EnvError`] when the file cannot be read or decoded.
pub fn decode_rgb(path: &Path) -> Result<(u32, u32, Vec<Vec3>), EnvError> {
    crate::scene::texture::check_jpeg_whole(path).map_err(|message| EnvError { message })?;
    let reader = crate::files::image_reader(path).map_err(|e| EnvError { message: format!("cannot read the map: {e}") })?;
    let img = reader.decode().map_err(|e| EnvError { message: format!("cannot decode the map: {e}") })?;
    let (width, height) = (img.width(), img.height());
    let linear = matches!(img.color(), image::ColorType::Rgb32F | image::ColorType::Rgba32F);
    let rgb = img.into_rgb32f();
    let decode = |c: f32| if linear { c } else { srgb_to_linear(c) };
    // Negative or non-finite texels (a damaged EXR) would break sampling: read as 0, said.
    let (texels, repaired) =
        crate::scene::texture::repaired_texels(rgb.pixels().map(|p| Vec3::new(decode(p[0]), decode(p[1]), decode(p[2]))));
    crate::scene::texture::record_texel_repairs(path, repaired);
    Ok((width, height, texels))
}

/// The sRGB transfer function inverted (IEC 61966-2-1).
#[inline]
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// The scene's environment: a map, its scale and rotation, and whether it is the background.
#[derive(Debug, Clone, PartialEq)]
pub struct Environment {
    /// The radiance map.
    pub map: Arc<EnvMap>,
    /// Scale on the map's radiance per channel: the lesson's intensity and white balance
    /// (`EnvironmentSpec::scale`).
    pub scale: Vec3,
    /// Rotation about +y in degrees.
    pub rotate_deg: f32,
    /// sin and cos of the rotation.
    sin_cos: (f32, f32),
    /// Drawn behind the objects.
    pub background: bool,
}

impl Environment {
    /// `map` scaled by `scale` (per channel), turned by `rotate_deg` about +y.
    pub fn new(map: Arc<EnvMap>, scale: Vec3, rotate_deg: f32, background: bool) -> Environment {
        // The angle in f64, reduced first, so 360° turns give the identity to the last bit.
        let r = (rotate_deg as f64).rem_euclid(360.0).to_radians();
        let sin_cos = if rotate_deg.rem_euclid(360.0) == 0.0 { (0.0, 1.0) } else { (r.sin() as f32, r.cos() as f32) };
        Environment { map, scale, rotate_deg, sin_cos, background }
    }

    /// A world direction in the map's frame: R_y(−θ) d.
    #[inline]
    pub fn to_map(&self, d: Vec3) -> Vec3 {
        let (s, c) = self.sin_cos;
        Vec3::new(c * d.x - s * d.z, d.y, s * d.x + c * d.z)
    }

    /// A direction of the map's frame in the world: R_y(θ) d.
    #[inline]
    pub fn from_map(&self, d: Vec3) -> Vec3 {
        let (s, c) = self.sin_cos;
        Vec3::new(c * d.x + s * d.z, d.y, -s * d.x + c * d.z)
    }

    /// Radiance arriving from the world direction `d` (unit): scale × the bilinear map.
    #[inline]
    pub fn radiance(&self, d: Vec3) -> Vec3 {
        self.radiance_at(direction_to_uv(self.to_map(d)))
    }

    /// Radiance at the map coordinates `uv` (of a direction's [`to_map`](Self::to_map)): for
    /// callers that also need the coordinates, to find them once.
    #[inline]
    pub fn radiance_at(&self, uv: Vec2) -> Vec3 {
        self.map.lookup(uv) * self.scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 8 × 4 map whose texel (i, j) is (i, j, 1).
    fn indexed() -> EnvMap {
        let texels = (0..4).flat_map(|j| (0..8).map(move |i| Vec3::new(i as f32, j as f32, 1.0))).collect();
        EnvMap { width: 8, height: 4, texels }
    }

    #[test]
    fn directions_read_the_texels_mitsuba_reads() {
        let m = indexed();
        // Straight up is row 0, straight down the last row, whatever u.
        assert_eq!(m.lookup(direction_to_uv(Vec3::Y)).y, 0.0);
        assert_eq!(m.lookup(direction_to_uv(-Vec3::Y)).y, 3.0);
        // −z is u = 0; texel 0's centre is u = 1/16, so u = 0 is halfway between texel 7 and texel 0.
        let uv = direction_to_uv(-Vec3::Z);
        assert_eq!(uv, Vec2::new(0.0, 0.5));
        assert!((m.lookup(uv).x - 3.5).abs() < 1e-5, "{:?}", m.lookup(uv));
        // +x is u = ¼: the centre of texel 1 is 3/16, of texel 2 5/16; ¼ is halfway.
        assert!((direction_to_uv(Vec3::X).x - 0.25).abs() < 1e-7);
        assert!((m.lookup(direction_to_uv(Vec3::X)).x - 1.5).abs() < 1e-5);
        // +z is u = ½, −x is u = ¾.
        assert!((direction_to_uv(Vec3::Z).x - 0.5).abs() < 1e-7 && (direction_to_uv(-Vec3::X).x - 0.75).abs() < 1e-7);
        // Texel centres give the texel exactly: (i + ½)/W, j/(H − 1).
        for (i, j) in [(0u32, 1u32), (5, 2), (7, 1)] {
            let uv = Vec2::new((i as f32 + 0.5) / 8.0, j as f32 / 3.0);
            let c = m.lookup(direction_to_uv(uv_to_direction(uv)));
            assert!((c - Vec3::new(i as f32, j as f32, 1.0)).abs().max_element() < 1e-4, "{i},{j}: {c:?}");
        }
    }

    #[test]
    fn the_seam_wraps_and_the_poles_are_finite() {
        let m = indexed();
        // Just either side of u = 0 the value is continuous (texel 7 blends into texel 0).
        let a = m.lookup(Vec2::new(1.0 - 1e-6, 0.5));
        let b = m.lookup(Vec2::new(1e-6, 0.5));
        assert!((a - b).abs().max_element() < 1e-3, "{a:?} {b:?}");
        for d in [Vec3::Y, -Vec3::Y, Vec3::new(0.0, 1.0, -0.0), Vec3::new(-0.0, -1.0, 0.0)] {
            assert!(m.lookup(direction_to_uv(d)).is_finite());
        }
        assert_eq!(m.lookup(Vec2::NAN), Vec3::ZERO);
    }

    #[test]
    fn uv_and_direction_are_inverse() {
        for k in 0..200 {
            let uv = Vec2::new((k as f32 * 0.618_034).fract(), 0.02 + 0.96 * (k as f32 * 0.414_213).fract());
            let back = direction_to_uv(uv_to_direction(uv));
            let du = (back.x - uv.x).abs().min(1.0 - (back.x - uv.x).abs());
            assert!(du < 1e-5 && (back.y - uv.y).abs() < 1e-5, "{uv:?} → {back:?}");
        }
    }

    #[test]
    fn rotating_by_360_degrees_is_the_identity_and_by_90_turns_minus_z_into_plus_x() {
        let map = Arc::new(indexed());
        let plain = Environment::new(map.clone(), Vec3::ONE, 0.0, true);
        let full = Environment::new(map.clone(), Vec3::ONE, 360.0, true);
        let quarter = Environment::new(map, Vec3::ONE, 90.0, true);
        for k in 0..100 {
            let d = uv_to_direction(Vec2::new((k as f32 * 0.618_034).fract(), (k as f32 * 0.414_213).fract())).normalize();
            assert_eq!(plain.radiance(d), full.radiance(d));
        }
        // Turning the sky by +90° about +y carries what was at −z to −x (R_y(90°)(0, 0, −1) = (−1, 0, 0)).
        let was = plain.radiance(-Vec3::Z);
        let now = quarter.radiance(-Vec3::X);
        assert!((was - now).abs().max_element() < 1e-4, "{was:?} {now:?}");
    }

    #[test]
    fn the_gradient_is_linear_in_cos_theta_above_and_constant_below() {
        let (z, h, g) = (Vec3::new(0.2, 0.4, 1.0), Vec3::ONE, Vec3::splat(0.3));
        let env = Environment::new(Arc::new(EnvMap::gradient(z, h, g)), Vec3::splat(2.0), 0.0, true);
        assert!((env.radiance(Vec3::Y) - 2.0 * z).abs().max_element() < 1e-3);
        let d = Vec3::new(0.6, 0.8, 0.0);
        assert!((env.radiance(d) - 2.0 * (h + (z - h) * 0.8)).abs().max_element() < 2e-3);
        assert!((env.radiance(-Vec3::Y) - 2.0 * g).abs().max_element() < 1e-6);
    }
}
