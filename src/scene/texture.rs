//! Image textures: decoded once per file (sRGB for colours, linear for data), a box-filtered
//! mip chain, and nearest, bilinear or trilinear lookups; the procedural checker baked into
//! the same form so it filters like an image.
//!
//! Conventions: u runs left to right, v bottom to top (OBJ's and OpenGL's, so row 0 of the
//! image is v = 1); texel centres sit at ((i + ½)/w, 1 − (j + ½)/h); both axes repeat.

use crate::lesson::TextureFilter;
use crate::lesson::limits::MAX_TEXTURE_SIDE;
use crate::lesson::texture::TextureSource;
use crate::shading::brdf::Brdf;
use crate::shading::material::{Material, Model};
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

/// How a texture's stored values become numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TexelSpace {
    /// A colour: 8- and 16-bit images are sRGB-encoded and decoded to linear (float images are linear already).
    Srgb,
    /// Data (roughness, metallic, normal map): the stored value c/(2ⁿ − 1) as it is.
    Linear,
}

/// A texture that could not be loaded.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{message}")]
pub struct TextureError {
    /// What went wrong, for the lesson's error message.
    pub message: String,
}

/// One level of the mip chain, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
struct Level {
    width: u32,
    height: u32,
    texels: Vec<Vec3>,
}

impl Level {
    /// Texel (i, j), both wrapped (repeat).
    #[inline]
    fn texel(&self, i: i64, j: i64) -> Vec3 {
        let i = i.rem_euclid(self.width as i64) as usize;
        let j = j.rem_euclid(self.height as i64) as usize;
        self.texels[j * self.width as usize + i]
    }

    /// The texel whose square contains `uv`.
    fn nearest(&self, uv: Vec2) -> Vec3 {
        let x = (uv.x * self.width as f32).floor() as i64;
        let y = ((1.0 - uv.y) * self.height as f32).floor() as i64;
        self.texel(x, y)
    }

    /// Bilinear between the four texel centres around `uv` (exactly a texel at its centre).
    fn bilinear(&self, uv: Vec2) -> Vec3 {
        let x = uv.x * self.width as f32 - 0.5;
        let y = (1.0 - uv.y) * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (i, j) = (x0 as i64, y0 as i64);
        let top = self.texel(i, j) * (1.0 - fx) + self.texel(i + 1, j) * fx;
        let bottom = self.texel(i, j + 1) * (1.0 - fx) + self.texel(i + 1, j + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// The next level: each texel the mean of a 2 × 2 block (a box filter; an odd last
    /// row or column is dropped, so the mean is kept exactly for power-of-two sides).
    fn half(&self) -> Level {
        let (w, h) = ((self.width / 2).max(1), (self.height / 2).max(1));
        let mut texels = Vec::with_capacity((w * h) as usize);
        for j in 0..h as i64 {
            for i in 0..w as i64 {
                let (i0, j0) = (2 * i, 2 * j);
                // A side of 1 repeats its one texel (the clamp), so the mean stays the texel.
                let (i1, j1) = ((i0 + 1).min(self.width as i64 - 1), (j0 + 1).min(self.height as i64 - 1));
                let sum = self.texel(i0, j0) + self.texel(i1, j0) + self.texel(i0, j1) + self.texel(i1, j1);
                texels.push(sum * 0.25);
            }
        }
        Level { width: w, height: h, texels }
    }
}

/// A texture with its mip chain (level 0 the image, the last 1 × 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    levels: Vec<Level>,
}

impl Texture {
    /// A texture from linear texels, row 0 at the top (`texels.len() == width·height`, both ≥ 1).
    pub fn from_texels(width: u32, height: u32, texels: Vec<Vec3>) -> Texture {
        assert!(width >= 1 && height >= 1 && texels.len() == (width * height) as usize, "texture size");
        let mut levels = vec![Level { width, height, texels }];
        while let Some(last) = levels.last()
            && (last.width > 1 || last.height > 1)
        {
            let next = last.half();
            levels.push(next);
        }
        Texture { levels }
    }

    /// The checker `squares` × `squares` per unit of uv, `a` where ⌊u·squares⌋ + ⌊v·squares⌋
    /// is even, baked at [`CHECKER_TEXELS`] texels a square so it filters like an image.
    pub fn checker(squares: u32, a: Vec3, b: Vec3) -> Texture {
        let squares = squares.max(1);
        let side = squares * CHECKER_TEXELS;
        let mut texels = Vec::with_capacity((side * side) as usize);
        for j in 0..side {
            // Row j counts from the top, v from the bottom.
            let row = squares - 1 - j / CHECKER_TEXELS;
            for i in 0..side {
                texels.push(if (i / CHECKER_TEXELS + row).is_multiple_of(2) { a } else { b });
            }
        }
        Texture::from_texels(side, side, texels)
    }

    /// Texels over every level (what the texture keeps in memory, 12 bytes each).
    pub fn texel_count(&self) -> usize {
        self.levels.iter().map(|l| l.texels.len()).sum()
    }

    /// Width and height of level 0.
    pub fn size(&self) -> (u32, u32) {
        (self.levels[0].width, self.levels[0].height)
    }

    /// Number of mip levels.
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// Texel (i, j) of mip level `level` (row 0 at the top), for tests and figures.
    pub fn texel(&self, level: usize, i: u32, j: u32) -> Vec3 {
        self.levels[level].texel(i as i64, j as i64)
    }

    /// The mean of all texels (the 1 × 1 level): what a texture gives where there is no uv
    /// footprint to filter by (Gouraud vertices, flat faces).
    pub fn mean(&self) -> Vec3 {
        self.levels[self.levels.len() - 1].texels[0]
    }

    /// The mip level of a footprint: log₂ of the longer of the screen axes' steps in
    /// level-0 texels (the OpenGL 4.6 §8.14.1 scale factor ρ), ≥ 0.
    ///
    /// `duv` holds ∂(u, v)/∂x and ∂(u, v)/∂y for one sample step; a non-finite one (a ray
    /// past the horizon) selects the coarsest level.
    pub fn lod(&self, duv: [Vec2; 2]) -> f32 {
        let (w, h) = self.size();
        let scale = Vec2::new(w as f32, h as f32);
        let rho = (duv[0] * scale).length().max((duv[1] * scale).length());
        if rho.is_finite() { rho.max(1.0).log2() } else { (self.levels.len() - 1) as f32 }
    }

    /// The filtered value at `uv` for a footprint `duv` (see [`Texture::lod`]): `nearest`
    /// and `bilinear` read level 0 only (no mip-mapping, so they alias when minified);
    /// `trilinear` blends bilinear lookups in the two levels around the footprint's level.
    pub fn sample(&self, uv: Vec2, duv: [Vec2; 2], filter: TextureFilter) -> Vec3 {
        // A non-finite uv (a damaged mesh) reads the origin rather than a NaN index.
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        match filter {
            TextureFilter::Nearest => self.levels[0].nearest(uv),
            TextureFilter::Bilinear => self.levels[0].bilinear(uv),
            TextureFilter::Trilinear => {
                let top = (self.levels.len() - 1) as f32;
                let lod = self.lod(duv).min(top);
                let k = lod.floor();
                let f = lod - k;
                let lo = self.levels[k as usize].bilinear(uv);
                if f == 0.0 { lo } else { lo * (1.0 - f) + self.levels[k as usize + 1].bilinear(uv) * f }
            }
        }
    }
}

/// Texels per checker square side: enough that bilinear magnification blurs only a thin
/// band at the edges, few enough that 128 squares stay a 1024² texture.
pub const CHECKER_TEXELS: u32 = 8;

/// The sRGB transfer inverted (IEC 61966-2-1), with the project's deterministic `pow`.
#[inline]
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { crate::simd::pow::pow((c + 0.055) / 1.055, 2.4) }
}

/// Refuses a JPEG whose data ends before its image does: the decoder `image` uses fills the
/// missing rows grey and says nothing (a 632-byte file whose header says 8000 × 8000 rendered
/// as a flat texture). Decoded once more, strictly, by the same decoder (zune-jpeg); other
/// formats' decoders already fail on a cut file.
///
/// # Errors
/// Why, in words, when the file is a JPEG that does not decode whole.
pub fn check_jpeg_whole(path: &Path) -> Result<(), String> {
    let bytes = crate::files::read(path).map_err(|e| format!("cannot read the image: {e}"))?;
    if !bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
        return Ok(());
    }
    let side = MAX_TEXTURE_SIDE as usize;
    let options = zune_core::options::DecoderOptions::default().set_strict_mode(true).set_max_width(side).set_max_height(side);
    zune_jpeg::JpegDecoder::new_with_options(std::io::Cursor::new(&bytes), options)
        .decode()
        .map(|_| ())
        .map_err(|e| format!("the JPEG is damaged or cut short ({e}); export it again"))
}

/// Texels that were not finite or were negative, per file, since the last
/// [`take_texel_repairs`]: read as 0, and said in a warning.
static TEXEL_REPAIRS: Mutex<Vec<(PathBuf, u64)>> = Mutex::new(Vec::new());

/// Records that `n` texels of `path` were repaired (nothing when `n` is 0).
pub fn record_texel_repairs(path: &Path, n: u64) {
    if n > 0 {
        TEXEL_REPAIRS.lock().unwrap_or_else(|e| e.into_inner()).push((path.to_path_buf(), n));
    }
}

/// The files whose texels were repaired since the last call, with how many.
pub fn take_texel_repairs() -> Vec<(PathBuf, u64)> {
    std::mem::take(&mut *TEXEL_REPAIRS.lock().unwrap_or_else(|e| e.into_inner()))
}

/// Decodes `path` into a texture in `space`, its side checked against
/// [`MAX_TEXTURE_SIDE`] before decoding.
///
/// # Errors
/// [`TextureError`] when the file cannot be read, is not an image, or is too large.
pub fn load(path: &Path, space: TexelSpace) -> Result<Texture, TextureError> {
    let err = |message: String| TextureError { message };
    let reader = crate::files::image_reader(path).map_err(|e| err(format!("cannot read the texture: {e}")))?;
    let (w, h) = reader.into_dimensions().map_err(|e| err(format!("not an image this program reads: {e}")))?;
    if w == 0 || h == 0 || w as i64 > MAX_TEXTURE_SIDE || h as i64 > MAX_TEXTURE_SIDE {
        return Err(err(format!("the image is {w} × {h}; a side must be 1 to {MAX_TEXTURE_SIDE} texels")));
    }
    check_jpeg_whole(path).map_err(err)?;
    let reader = crate::files::image_reader(path).map_err(|e| err(format!("cannot read the texture: {e}")))?;
    let img = reader.decode().map_err(|e| err(format!("not an image this program reads: {e}")))?;
    let float = matches!(img.color(), image::ColorType::Rgb32F | image::ColorType::Rgba32F);
    let decode = |c: f32| if space == TexelSpace::Srgb && !float { srgb_to_linear(c) } else { c };
    let (texels, repaired) = repaired_texels(img.into_rgb32f().pixels().map(|p| Vec3::new(decode(p[0]), decode(p[1]), decode(p[2]))));
    record_texel_repairs(path, repaired);
    Ok(Texture::from_texels(w, h, texels))
}

/// The largest texel value read as it is: far above any radiance a map records (HDRIs of
/// the sun reach about 10⁸), far enough below f32's 3.4·10³⁸ that filtering, sums over a
/// whole map and exposure cannot overflow (a damaged EXR's 1.7·10³⁸ made infinite pixels).
pub const MAX_TEXEL: f32 = 1e12;

/// Texels with every non-finite, negative or larger than [`MAX_TEXEL`] channel repaired (read
/// as 0, or as `MAX_TEXEL`: they would break shading and sampling), and how many were.
pub fn repaired_texels(texels: impl Iterator<Item = Vec3>) -> (Vec<Vec3>, u64) {
    let mut repaired = 0;
    let out = texels
        .map(|c| {
            if c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= MAX_TEXEL {
                c.max(Vec3::ZERO)
            } else {
                repaired += 1;
                if c.is_finite() { c.clamp(Vec3::ZERO, Vec3::splat(MAX_TEXEL)) } else { Vec3::ZERO }
            }
        })
        .collect();
    (out, repaired)
}

/// [`load`] through a cache: each file is decoded once per run and space (keyed by path,
/// length and modification time, so an edited file is read again).
///
/// # Errors
/// As [`load`].
pub fn load_cached(path: &Path, space: TexelSpace) -> Result<Arc<Texture>, TextureError> {
    type Key = (PathBuf, u64, Option<std::time::SystemTime>, TexelSpace);
    static CACHE: OnceLock<Mutex<HashMap<Key, Arc<Texture>>>> = OnceLock::new();
    let meta = crate::files::metadata(path).map_err(|e| TextureError { message: format!("cannot read the texture: {e}") })?;
    let key = (path.to_path_buf(), meta.len, meta.modified, space);
    let cache = CACHE.get_or_init(Default::default);
    if let Some(t) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return Ok(t.clone());
    }
    let t = Arc::new(load(path, space)?);
    cache.lock().unwrap_or_else(|e| e.into_inner()).insert(key, t.clone());
    Ok(t)
}

/// A material's loaded textures (parallel to `Scene::materials`).
#[derive(Debug, Clone, Default)]
pub struct MaterialTextures {
    /// Albedo (`diffuse` or `base_color`), linear RGB.
    pub albedo: Option<Arc<Texture>>,
    /// Perceptual roughness in the red channel.
    pub roughness: Option<Arc<Texture>>,
    /// Metallic in the red channel.
    pub metallic: Option<Arc<Texture>>,
    /// Tangent-space normal map, n = 2c − 1.
    pub normal: Option<Arc<Texture>>,
    /// Ambient occlusion in the red channel: scales K_amb.
    pub occlusion: Option<Arc<Texture>>,
    /// The ambient reflectance follows the albedo texture (the lesson gave no `ambient`).
    pub ambient_follows_albedo: bool,
}

impl MaterialTextures {
    /// True when some parameter is textured.
    pub fn any(&self) -> bool {
        self.albedo.is_some() || self.roughness.is_some() || self.metallic.is_some() || self.normal.is_some() || self.occlusion.is_some()
    }
}

/// Values read from a material's textures at one point (`None`: not textured).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TexValues {
    /// Albedo (linear RGB).
    pub albedo: Option<Vec3>,
    /// Perceptual roughness.
    pub roughness: Option<f32>,
    /// Metallic.
    pub metallic: Option<f32>,
    /// Ambient occlusion, 0 (the ambient light cannot reach) to 1 (open).
    pub occlusion: Option<f32>,
}

impl MaterialTextures {
    /// The textures' means (their 1 × 1 mip levels): what a point without a uv footprint
    /// reads (Gouraud vertices, flat faces, the environment's per-material terms).
    pub fn means(&self) -> TexValues {
        TexValues {
            albedo: self.albedo.as_ref().map(|t| t.mean()),
            roughness: self.roughness.as_ref().map(|t| t.mean().x.clamp(0.0, 1.0)),
            metallic: self.metallic.as_ref().map(|t| t.mean().x.clamp(0.0, 1.0)),
            occlusion: self.occlusion.as_ref().map(|t| t.mean().x.clamp(0.0, 1.0)),
        }
    }

    /// The values at `uv` with footprint `duv` (see [`Texture::sample`]).
    pub fn sample(&self, uv: Vec2, duv: [Vec2; 2], filter: TextureFilter) -> TexValues {
        TexValues {
            albedo: self.albedo.as_ref().map(|t| t.sample(uv, duv, filter).min(Vec3::ONE)),
            roughness: self.roughness.as_ref().map(|t| t.sample(uv, duv, filter).x.clamp(0.0, 1.0)),
            metallic: self.metallic.as_ref().map(|t| t.sample(uv, duv, filter).x.clamp(0.0, 1.0)),
            occlusion: self.occlusion.as_ref().map(|t| t.sample(uv, duv, filter).x.clamp(0.0, 1.0)),
        }
    }

    /// `m` with the values `v` in place of its constants: the albedo as K_diff, ρ or the base
    /// colour, the roughness as α = roughness² (cook_torrance) or roughness (principled),
    /// K_amb following the albedo when the lesson gave no `ambient` (as validation does for a
    /// constant albedo), and K_amb times the ambient occlusion. The name is left empty: this is a per-point copy.
    pub fn apply(&self, m: &Material, v: TexValues) -> Material {
        let mut model = m.model;
        let mut ambient = m.ambient;
        match &mut model {
            Model::Classic(c) => {
                if let Some(a) = v.albedo {
                    c.diffuse = a;
                }
                if self.ambient_follows_albedo {
                    ambient = c.diffuse;
                }
            }
            Model::Physical(brdf) => {
                match brdf {
                    Brdf::Diffuse(d) => d.albedo = v.albedo.unwrap_or(d.albedo),
                    Brdf::OrenNayar(o) => o.albedo = v.albedo.unwrap_or(o.albedo),
                    Brdf::CookTorrance(c) => {
                        c.diffuse = v.albedo.unwrap_or(c.diffuse);
                        c.alpha = v.roughness.map_or(c.alpha, |r| r * r);
                    }
                    Brdf::Principled(p) => {
                        p.base_color = v.albedo.unwrap_or(p.base_color);
                        p.roughness = v.roughness.unwrap_or(p.roughness);
                        p.metallic = v.metallic.unwrap_or(p.metallic);
                    }
                    Brdf::NormalizedPhong(n) => n.diffuse = v.albedo.unwrap_or(n.diffuse),
                    Brdf::NormalizedBlinnPhong(n) => n.diffuse = v.albedo.unwrap_or(n.diffuse),
                }
                if self.ambient_follows_albedo {
                    // The same defaults as validation's.
                    ambient = brdf.ambient_albedo();
                }
            }
            Model::Mirror(_) | Model::Glass(_) => {}
        }
        // Ambient occlusion: the share of the ambient light that reaches the point.
        let ambient = ambient * v.occlusion.unwrap_or(1.0);
        Material { name: String::new(), model, ambient, emission: m.emission }
    }
}

/// The texture of `source` in `space`: a file through the cache, a checker baked (cached
/// by its parameters, a few per run).
///
/// # Errors
/// [`TextureError`] when a file cannot be loaded.
pub fn resolve(source: &TextureSource, space: TexelSpace) -> Result<Arc<Texture>, TextureError> {
    match source {
        TextureSource::File { path, channel: 0, .. } => load_cached(path, space),
        // One channel of the file in all three (a glTF metallic-roughness image's green or blue).
        TextureSource::File { path, channel, .. } => {
            let t = load_cached(path, space)?;
            let base = &t.levels[0];
            let texels = base.texels.iter().map(|v| Vec3::splat(v[*channel as usize])).collect();
            Ok(Arc::new(Texture::from_texels(base.width, base.height, texels)))
        }
        TextureSource::Checker { scale, a, b } => {
            type Key = (u32, [u32; 6]);
            static BAKED: Mutex<Vec<(Key, Arc<Texture>)>> = Mutex::new(Vec::new());
            let key = (*scale, [a.x, a.y, a.z, b.x, b.y, b.z].map(f32::to_bits));
            let mut baked = BAKED.lock().unwrap_or_else(|e| e.into_inner());
            if let Some((_, t)) = baked.iter().find(|(k, _)| *k == key) {
                return Ok(t.clone());
            }
            let t = Arc::new(Texture::checker(*scale, *a, *b));
            // A few checkers per run at most; keep the last eight.
            if baked.len() >= 8 {
                baked.remove(0);
            }
            baked.push((key, t.clone()));
            Ok(t)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(w: u32, h: u32) -> Texture {
        Texture::from_texels(w, h, (0..w * h).map(|k| Vec3::new(k as f32, (k * 7 % 5) as f32, 1.0)).collect())
    }

    #[test]
    fn srgb_decode_matches_the_formula() {
        for k in 0..=255u32 {
            let c = k as f32 / 255.0;
            let want = if c as f64 <= 0.04045 { c as f64 / 12.92 } else { ((c as f64 + 0.055) / 1.055).powf(2.4) };
            assert!((srgb_to_linear(c) as f64 - want).abs() <= 1e-6 * want.max(1e-3), "{k}: {} vs {want}", srgb_to_linear(c));
        }
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn bilinear_and_nearest_at_texel_centres_return_texels() {
        let t = ramp(4, 3);
        for j in 0..3 {
            for i in 0..4 {
                let uv = Vec2::new((i as f32 + 0.5) / 4.0, 1.0 - (j as f32 + 0.5) / 3.0);
                let want = t.texel(0, i, j);
                assert_eq!(t.sample(uv, [Vec2::ZERO; 2], TextureFilter::Nearest), want);
                let got = t.sample(uv, [Vec2::ZERO; 2], TextureFilter::Bilinear);
                assert!((got - want).abs().max_element() < 1e-5, "({i}, {j}): {got} vs {want}");
                // Trilinear with no minification is level 0's bilinear.
                assert_eq!(t.sample(uv, [Vec2::ZERO; 2], TextureFilter::Trilinear), got);
            }
        }
        // Half-way between two centres in u: their mean; and u wraps.
        let mid = t.sample(Vec2::new(0.25, 1.0 - 0.5 / 3.0), [Vec2::ZERO; 2], TextureFilter::Bilinear);
        assert!((mid - (t.texel(0, 0, 0) + t.texel(0, 1, 0)) * 0.5).abs().max_element() < 1e-5);
        let wrap = t.sample(Vec2::new(0.0, 1.0 - 0.5 / 3.0), [Vec2::ZERO; 2], TextureFilter::Bilinear);
        assert!((wrap - (t.texel(0, 3, 0) + t.texel(0, 0, 0)) * 0.5).abs().max_element() < 1e-5);
    }

    #[test]
    fn mip_chain_box_filters_and_keeps_the_mean() {
        let c = Vec3::new(0.2, 0.5, 0.9);
        let flat = Texture::from_texels(16, 8, vec![c; 128]);
        assert_eq!(flat.level_count(), 5); // 16×8, 8×4, 4×2, 2×1, 1×1
        for k in 0..flat.level_count() {
            let (w, h) = (16 >> k, (8u32 >> k).max(1));
            for j in 0..h {
                for i in 0..w {
                    assert_eq!(flat.texel(k, i, j), c);
                }
            }
        }
        let t = ramp(8, 8);
        let mean = (0..64).map(|k| t.texel(0, k % 8, k / 8)).sum::<Vec3>() / 64.0;
        assert!((t.mean() - mean).abs().max_element() < 1e-4, "{} vs {mean}", t.mean());
        // Level 1 texel (1, 2) is the mean of level 0's block (2..4, 4..6).
        let block = (t.texel(0, 2, 4) + t.texel(0, 3, 4) + t.texel(0, 2, 5) + t.texel(0, 3, 5)) * 0.25;
        assert_eq!(t.texel(1, 1, 2), block);
    }

    #[test]
    fn trilinear_picks_the_level_of_the_footprint() {
        let t = ramp(8, 8);
        let uv = Vec2::new(0.5, 0.5);
        // A step of 4 texels per sample: level 2 exactly.
        let duv = [Vec2::new(0.5, 0.0), Vec2::new(0.0, 0.5)];
        assert_eq!(t.lod(duv), 2.0);
        assert_eq!(t.sample(uv, duv, TextureFilter::Trilinear), t.levels[2].bilinear(uv));
        // Past the horizon: the coarsest level, the mean.
        let far = [Vec2::splat(f32::INFINITY); 2];
        assert_eq!(t.sample(uv, far, TextureFilter::Trilinear), t.mean());
        assert!(t.sample(Vec2::NAN, far, TextureFilter::Trilinear).is_finite());
    }

    #[test]
    fn checker_squares_have_their_colours() {
        let (a, b) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
        let t = Texture::checker(4, a, b);
        let at = |u: f32, v: f32| t.sample(Vec2::new(u, v), [Vec2::ZERO; 2], TextureFilter::Bilinear);
        // Square (0, 0) at the uv origin is `a`, its neighbours `b`, diagonal `a` again.
        assert_eq!(at(0.125, 0.125), a);
        assert_eq!(at(0.375, 0.125), b);
        assert_eq!(at(0.125, 0.375), b);
        assert_eq!(at(0.375, 0.375), a);
        // Half a and half b: the mean is their average.
        assert!((t.mean() - (a + b) * 0.5).abs().max_element() < 1e-6);
    }
}
