//! A material as shading reads it: the model with its coefficients, K_amb and L_emi.
//!
//! Two families (docs/models.md): the course's classic models, with coefficients in [0, 1]
//! and no π, and physically based BRDFs in 1/sr. [`Model`] holds one or the other, so a
//! physically based material carries no unused classic coefficients.

use super::brdf::Brdf;
use super::glass::Glass;
use super::mirror::Mirror;
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

/// A classic model with its coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Classic {
    /// Which model.
    pub model: ClassicModel,
    /// K_diff.
    pub diffuse: Vec3,
    /// K_spec (zero for Lambert).
    pub specular: Vec3,
    /// K_shi.
    pub shininess: f32,
    /// The diffuse term's max(N·L, 0); `false` (a lesson's teaching switch) uses N·L as it
    /// is, so a light behind the surface subtracts.
    pub clamp_n_dot_l: bool,
}

impl Classic {
    /// True when the specular term can contribute (not Lambert, K_spec ≠ 0).
    pub fn has_specular(&self) -> bool {
        self.model != ClassicModel::Lambert && self.specular != Vec3::ZERO
    }
}

/// How a material reflects the lights: one of the two families.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Model {
    /// The course's equation with a classic model.
    Classic(Classic),
    /// A physically based BRDF: L_o = Σ f E cos.
    Physical(Brdf),
    /// A perfect mirror: L_o = tint ⊗ L_i(r), lit only by what its reflected ray finds.
    Mirror(Mirror),
    /// A smooth dielectric: Fresnel-weighted reflection plus refraction, lit only by its rays.
    Glass(Glass),
}

/// A named material.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// The `[material.NAME]` name.
    pub name: String,
    /// The model and its coefficients.
    pub model: Model,
    /// K_amb (for a physically based model, the reflectance the ambient light sees).
    pub ambient: Vec3,
    /// L_emi.
    pub emission: Vec3,
}

impl Material {
    /// The BRDF of a physically based material.
    pub fn brdf(&self) -> Option<&Brdf> {
        match &self.model {
            Model::Physical(b) => Some(b),
            Model::Classic(_) | Model::Mirror(_) | Model::Glass(_) => None,
        }
    }

    /// The classic model and coefficients of a classic material.
    pub fn classic(&self) -> Option<&Classic> {
        match &self.model {
            Model::Classic(c) => Some(c),
            Model::Physical(_) | Model::Mirror(_) | Model::Glass(_) => None,
        }
    }

    /// The model's family and name for messages: `lambert`, `phong`, `blinn_phong` or `physically based`.
    pub fn family_name(&self) -> &'static str {
        match &self.model {
            Model::Classic(c) => c.model.name(),
            Model::Physical(_) => "physically based",
            Model::Mirror(_) => "mirror",
            Model::Glass(_) => "glass",
        }
    }
}
