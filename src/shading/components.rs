//! The terms of the illumination equation kept apart, so a split costs no extra render.

use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;
use std::ops::{Add, AddAssign, Mul};

/// Linear RGB radiance split by term.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Components {
    /// L_emi.
    pub emission: Vec3,
    /// L_glob⊗K_amb + Σ C_spot I_amb.
    pub ambient: Vec3,
    /// Σ C_spot d I_diff.
    pub diffuse: Vec3,
    /// Σ C_spot d I_spec.
    pub specular: Vec3,
    /// Light from the environment and from mirrored objects: ∫ L_env f cos dω (image-based
    /// lighting) and tint ⊗ L_i(r) for a mirror; F L_i(r) for glass.
    pub reflection: Vec3,
    /// Light through glass: (1 − F) tint ⊗ L_i(t) along the refracted ray.
    pub transmission: Vec3,
}

impl Components {
    /// All zero.
    pub const ZERO: Components = Components {
        emission: Vec3::ZERO,
        ambient: Vec3::ZERO,
        diffuse: Vec3::ZERO,
        specular: Vec3::ZERO,
        reflection: Vec3::ZERO,
        transmission: Vec3::ZERO,
    };

    /// The sum of all terms: I_tot.
    #[inline]
    pub fn total(&self) -> Vec3 {
        self.emission + self.ambient + self.diffuse + self.specular + self.reflection + self.transmission
    }

    /// True when every channel of every term is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.emission.is_finite()
            && self.ambient.is_finite()
            && self.diffuse.is_finite()
            && self.specular.is_finite()
            && self.reflection.is_finite()
            && self.transmission.is_finite()
    }
}

impl Add for Components {
    type Output = Components;
    #[inline]
    fn add(self, o: Components) -> Components {
        Components {
            emission: self.emission + o.emission,
            ambient: self.ambient + o.ambient,
            diffuse: self.diffuse + o.diffuse,
            specular: self.specular + o.specular,
            reflection: self.reflection + o.reflection,
            transmission: self.transmission + o.transmission,
        }
    }
}

impl AddAssign for Components {
    #[inline]
    fn add_assign(&mut self, o: Components) {
        *self = *self + o;
    }
}

impl Mul<f32> for Components {
    type Output = Components;
    #[inline]
    fn mul(self, s: f32) -> Components {
        Components {
            emission: self.emission * s,
            ambient: self.ambient * s,
            diffuse: self.diffuse * s,
            specular: self.specular * s,
            reflection: self.reflection * s,
            transmission: self.transmission * s,
        }
    }
}

/// [`Components`] for lanes of points (see [`crate::simd::lanes`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComponentLanes<F> {
    /// L_emi.
    pub emission: V3<F>,
    /// L_glob⊗K_amb + Σ C_spot I_amb.
    pub ambient: V3<F>,
    /// Σ C_spot d I_diff.
    pub diffuse: V3<F>,
    /// Σ C_spot d I_spec.
    pub specular: V3<F>,
}

impl<F: Lanes> ComponentLanes<F> {
    /// I_tot, summed in the order of [`Components::total`].
    #[inline(always)]
    pub fn total(&self) -> V3<F> {
        self.emission + self.ambient + self.diffuse + self.specular
    }
}

impl From<ComponentLanes<f32>> for Components {
    #[inline(always)]
    fn from(c: ComponentLanes<f32>) -> Components {
        Components {
            emission: c.emission.into(),
            ambient: c.ambient.into(),
            diffuse: c.diffuse.into(),
            specular: c.specular.into(),
            reflection: Vec3::ZERO,
            transmission: Vec3::ZERO,
        }
    }
}

/// Which layer to read out of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layer {
    /// L_glob⊗K_amb + Σ I_amb.
    Ambient,
    /// Σ d I_diff.
    Diffuse,
    /// Σ d I_spec.
    Specular,
    /// L_emi.
    Emission,
    /// Light from the environment and mirrored objects.
    Reflection,
    /// Light through glass.
    Transmission,
    /// I_tot: the sum of all terms.
    Total,
    /// The shading normal as a colour ((N + 1)/2 after sRGB encoding): not radiance, for
    /// seeing what flat, Gouraud and Phong interpolate.
    Normal,
}

impl Layer {
    /// All layers, in display order.
    pub const ALL: [Layer; 8] = [
        Layer::Ambient,
        Layer::Diffuse,
        Layer::Specular,
        Layer::Emission,
        Layer::Reflection,
        Layer::Transmission,
        Layer::Total,
        Layer::Normal,
    ];
    /// The terms of the illumination equation and their sum.
    pub const TERMS: [Layer; 5] = [Layer::Ambient, Layer::Diffuse, Layer::Specular, Layer::Emission, Layer::Total];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Layer::Ambient => "ambient",
            Layer::Diffuse => "diffuse",
            Layer::Specular => "specular",
            Layer::Emission => "emission",
            Layer::Reflection => "reflection",
            Layer::Transmission => "transmission",
            Layer::Total => "total",
            Layer::Normal => "normal",
        }
    }

    /// This layer's part of a pixel's components (zero for `Normal`, which is not a term).
    #[inline]
    pub fn of(self, c: &Components) -> Vec3 {
        match self {
            Layer::Normal => Vec3::ZERO,
            Layer::Ambient => c.ambient,
            Layer::Diffuse => c.diffuse,
            Layer::Specular => c.specular,
            Layer::Emission => c.emission,
            Layer::Reflection => c.reflection,
            Layer::Transmission => c.transmission,
            Layer::Total => c.total(),
        }
    }
}
