//! The validated textures of a material: which parameter reads which texture.
//!
//! A material parameter is a constant (kept in the shading [`Material`](crate::shading::material::Material))
//! or a texture reference (kept here, beside it); the scene loads the files and the
//! renderer samples them per shaded point, so shading stays a pure function of values.

use glam::Vec3;
use std::path::PathBuf;

/// Where a texture's texels come from.
#[derive(Debug, Clone, PartialEq)]
pub enum TextureSource {
    /// An image file (PNG, JPEG, OpenEXR, Radiance HDR).
    File {
        /// The file, resolved against the lesson's folder and confined to it.
        path: PathBuf,
        /// The path as the lesson wrote it (for messages).
        written: String,
        /// The channel a data key reads (`channel`: 0 red, 1 green, 2 blue); 0 for colours.
        channel: u8,
    },
    /// The procedural checker: `scale` squares per unit of uv, `a` at the uv origin's square.
    Checker {
        /// Squares per unit of u and of v.
        scale: u32,
        /// Colour (or value, in its first channel) of the squares with ⌊u·scale⌋ + ⌊v·scale⌋ even.
        a: Vec3,
        /// Colour of the others.
        b: Vec3,
    },
}

/// One textured parameter: the key that names it and its source.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureRef {
    /// The material key (`diffuse`, `base_color`, `roughness`, `metallic`, `normal_map`, `occlusion_map`).
    pub key: &'static str,
    /// Its texels.
    pub source: TextureSource,
}

/// A material's textured parameters (all `None`: an untextured material).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MaterialMaps {
    /// The albedo: `diffuse` (classic and diffuse-based models) or `base_color` (principled); sRGB.
    pub albedo: Option<TextureRef>,
    /// Perceptual roughness (cook_torrance: α = roughness²; principled); linear, red channel.
    pub roughness: Option<TextureRef>,
    /// Metallic (principled); linear, red channel.
    pub metallic: Option<TextureRef>,
    /// A tangent-space normal map (linear, n = 2c − 1).
    pub normal: Option<TextureRef>,
    /// An ambient-occlusion map (linear, red channel): scales K_amb.
    pub occlusion: Option<TextureRef>,
    /// `ambient` was not given, so it follows the albedo texture as it follows a constant albedo.
    pub ambient_follows_albedo: bool,
}

impl MaterialMaps {
    /// True when no parameter is textured.
    pub fn is_empty(&self) -> bool {
        self.albedo.is_none() && self.roughness.is_none() && self.metallic.is_none() && self.normal.is_none() && self.occlusion.is_none()
    }
}
