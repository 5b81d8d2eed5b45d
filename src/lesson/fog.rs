//! The validated `[fog]` table: a classic blend (linear, exp, exp²) or a homogeneous
//! participating medium. What fog does to a sample is computed by `effects::fog`.

use glam::Vec3;

/// Which distance z the classic blends use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FogDistance {
    /// The eye distance |p − eye| (the same fog in every direction: a ring of equal fog
    /// around the eye).
    #[default]
    Radial,
    /// The view depth along the camera's axis (OpenGL's fixed-function fog coordinate): the
    /// fog is constant over planes parallel to the image, so it grows towards the image edges
    /// less than the true distance does.
    Depth,
}

impl FogDistance {
    /// Every choice with its name in lesson files.
    pub const NAMES: [(&'static str, FogDistance); 2] = [("radial", FogDistance::Radial), ("depth", FogDistance::Depth)];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            FogDistance::Radial => "radial",
            FogDistance::Depth => "depth",
        }
    }
}

/// A homogeneous medium filling all space (single scattering).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Medium {
    /// Scattering coefficient σ_s per unit length (grey: the same in every channel).
    pub sigma_s: f32,
    /// Absorption coefficient σ_a per unit length (grey).
    pub sigma_a: f32,
    /// Henyey-Greenstein asymmetry g in (−1, 1): 0 isotropic, > 0 forward scattering.
    pub g: f32,
    /// Ray-march steps per sample (for point and spot lights sampled equiangularly: samples
    /// per light).
    pub steps: u32,
    /// How the in-scattering of point and spot lights is sampled along the eye ray.
    pub sampling: FogSampling,
}

/// How a medium's in-scattering from a point or spot light is sampled along an eye ray.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FogSampling {
    /// Distances ∝ 1/(h² + (t − t_c)²) about the light (Kulla & Fajardo 2012): the samples
    /// gather where the light is strong.
    #[default]
    Equiangular,
    /// The jittered uniform march: N equal steps along the ray.
    Uniform,
}

impl FogSampling {
    /// Every method with its name in lesson files.
    pub const NAMES: [(&'static str, FogSampling); 2] = [("equiangular", FogSampling::Equiangular), ("uniform", FogSampling::Uniform)];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            FogSampling::Equiangular => "equiangular",
            FogSampling::Uniform => "uniform",
        }
    }
}

impl Medium {
    /// The extinction coefficient σ_t = σ_s + σ_a.
    pub fn sigma_t(&self) -> f32 {
        self.sigma_s + self.sigma_a
    }
}

/// The closed set of fog kinds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FogKind {
    /// f = (end − z)/(end − start), clamped to [0, 1].
    Linear {
        /// z where fog begins (f = 1 nearer).
        start: f32,
        /// z where fog is complete (f = 0 farther).
        end: f32,
    },
    /// f = e^(−density·z).
    Exp {
        /// Density per unit length.
        density: f32,
    },
    /// f = e^(−(density·z)²).
    Exp2 {
        /// Density per unit length.
        density: f32,
    },
    /// Radiance marched through a participating medium.
    Medium(Medium),
}

impl FogKind {
    /// The name in lesson files.
    pub fn name(&self) -> &'static str {
        match self {
            FogKind::Linear { .. } => "linear",
            FogKind::Exp { .. } => "exp",
            FogKind::Exp2 { .. } => "exp2",
            FogKind::Medium(_) => "medium",
        }
    }

    /// Every kind's name with the keys it reads (besides `kind`).
    pub const KEYS: [(&'static str, &'static [&'static str]); 4] = [
        ("linear", &["color", "start", "end", "distance"]),
        ("exp", &["color", "density", "distance"]),
        ("exp2", &["color", "density", "distance"]),
        ("medium", &["sigma_s", "sigma_a", "g", "steps", "sampling"]),
    ];
}

/// `[fog]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fog {
    /// The blend or the medium.
    pub kind: FogKind,
    /// C_fog of the classic blends (linear RGB).
    pub color: Vec3,
    /// Radial distance or view depth for the classic blends.
    pub distance: FogDistance,
}

impl Fog {
    /// The medium, when the fog is one.
    pub fn medium(&self) -> Option<&Medium> {
        match &self.kind {
            FogKind::Medium(m) => Some(m),
            _ => None,
        }
    }
}
