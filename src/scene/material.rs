//! Materials: which shading model and its coefficients.

use glam::Vec3;

/// The classic models of the course (no π, coefficients in [0, 1]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClassicModel {
    /// Ambient + Lambert diffuse, no specular term.
    Lambert,
    /// Phong specular: max(R·V, 0)^K_shi.
    Phong,
    /// Blinn-Phong specular: max(N·H, 0)^K_shi.
    BlinnPhong,
}

impl ClassicModel {
    /// The name used in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            ClassicModel::Lambert => "lambert",
            ClassicModel::Phong => "phong",
            ClassicModel::BlinnPhong => "blinn_phong",
        }
    }
}

/// A named material with the course's coefficients.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// The `[material.NAME]` name.
    pub name: String,
    /// Which model.
    pub model: ClassicModel,
    /// K_amb.
    pub ambient: Vec3,
    /// K_diff.
    pub diffuse: Vec3,
    /// K_spec (zero for Lambert).
    pub specular: Vec3,
    /// K_shi.
    pub shininess: f32,
    /// L_emi.
    pub emission: Vec3,
    /// A physically based BRDF; when set, it replaces the classic model (`model`, `diffuse`,
    /// `specular` and `shininess` are then unused) and `ambient` is the reflectance the
    /// ambient light sees.
    pub physical: Option<crate::shading::brdf::Brdf>,
}

impl Material {
    /// True when the specular term can contribute (a non-Lambert classic model with K_spec ≠ 0,
    /// or a physically based BRDF with a specular lobe).
    pub fn has_specular(&self) -> bool {
        match &self.physical {
            Some(b) => crate::shading::physical::has_specular_lobe(b),
            None => self.model != ClassicModel::Lambert && self.specular != Vec3::ZERO,
        }
    }
}
