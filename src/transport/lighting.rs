//! What lights a shaded point: the render's lights with their visibility, the environment
//! and what traced rays need ([`Lighting`]), and the point itself ([`At`], one lane or a
//! bundle of lanes).

use super::rays::Origin;
use super::surfaces::Tracing;
use super::visibility::Shadows;
use crate::effects::environment::EnvLighting;
use crate::geometry::sampler::Sampler;
use crate::light::Light;
use crate::scene::Material;
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
use crate::simd::lanes::{Lanes, MAX_WIDTH, V3};
use glam::Vec3;
use std::sync::Arc;

/// The lights of one render with their shadow state: what every shaded point asks.
#[derive(Debug, Clone, Default)]
pub struct Lighting {
    /// The lights the plan keeps.
    pub lights: Vec<Light>,
    /// How each light's visibility is found.
    pub shadows: Shadows,
    /// Rect lights give their exact unoccluded irradiance (Lambert's polygon formula, one
    /// incident along the normal) instead of samples: the reference of the `area_samples`
    /// ladder, exact for the diffuse term only.
    pub exact_area: bool,
    /// The extinction σ_t of a participating medium light crosses on its way to a surface
    /// (0 without one; set by [`Lighting::through_medium`]).
    pub(super) extinction: f32,
    /// Some light is sampled or shadowed, or crosses a medium: points need their normals and triangle.
    pub(super) involved: bool,
    /// The environment's light, when a material needs it.
    pub env: Option<Arc<EnvLighting>>,
    /// What mirrors, glass and the environment's visibility trace (the scene's rays and surfaces).
    pub tracing: Tracing,
    /// Where the samples of sampled lights fall (`[render] sampler`).
    pub sampler: Sampler,
    /// Whether each point has its own samples of a light (`[render] sample_pattern`).
    pub pattern: crate::geometry::sampler::SamplePattern,
}

impl Lighting {
    /// `lights` with their shadow state.
    pub fn new(lights: Vec<Light>, shadows: Shadows) -> Lighting {
        let involved = lights.iter().enumerate().any(|(i, l)| l.kind.is_sampled() || shadows.casts(i));
        Lighting {
            lights,
            shadows,
            exact_area: false,
            extinction: 0.0,
            involved,
            env: None,
            tracing: Tracing::default(),
            sampler: Sampler::default(),
            pattern: crate::geometry::sampler::SamplePattern::default(),
        }
    }

    /// These lights seen through a homogeneous medium of extinction `sigma_t`: a surface
    /// point r away from a light (sample) gets its light × e^(−σ_t r); a directional or sky
    /// light arrives with its own strength (`effects::fog::medium`).
    pub fn through_medium(mut self, sigma_t: f32) -> Lighting {
        self.extinction = sigma_t;
        self.involved |= sigma_t > 0.0;
        self
    }

    /// `lights` with nothing shadowed.
    pub fn unshadowed(lights: Vec<Light>) -> Lighting {
        let n = lights.len();
        Lighting::new(lights, Shadows::unshadowed(n))
    }
}

impl Lighting {
    /// True when no light is sampled or shadowed: [`plain_incidents`] gives every incident.
    #[inline(always)]
    pub fn is_plain(&self) -> bool {
        !self.involved
    }
}

/// A shaded point, one lane or lanes of them: position, unit shading normal, unit
/// geometric normal, and where it lies (shadow rays ignore its own triangle, or its whole
/// object when that is convex).
#[derive(Debug, Clone, Copy)]
pub struct At<F: Lanes> {
    /// Position.
    pub p: V3<F>,
    /// Unit shading normal (area and sky samples lie on its side).
    pub n: V3<F>,
    /// Unit geometric normal (shadow rays leave along it).
    pub ng: V3<F>,
    /// The triangle (the same for every lane), or `u32::MAX` for a vertex or an analytic hit.
    pub tri: u32,
    /// The object, or `u32::MAX` when none.
    pub object: u32,
    /// Each lane's own triangle and object, when the lanes come from several triangles (a
    /// gathered bundle); `tri` and `object` then stand for none.
    pub per_lane: Option<LaneIds>,
}

/// The triangle and object of each lane of a bundle gathered from several triangles.
#[derive(Debug, Clone, Copy)]
pub struct LaneIds {
    /// Triangle of each lane.
    pub tri: [u32; MAX_WIDTH],
    /// Object of each lane.
    pub object: [u32; MAX_WIDTH],
}

impl<F: Lanes> At<F> {
    /// Where lane `j` lies, for its shadow rays: at `p`, leaving along `ng`.
    #[inline(always)]
    pub(super) fn origin(&self, j: usize, p: Vec3, ng: Vec3) -> Origin {
        let (tri, object) = match &self.per_lane {
            Some(ids) => (ids.tri[j], ids.object[j]),
            None => (self.tri, self.object),
        };
        Origin { p, ng, tri, object }
    }
}

impl At<f32> {
    /// One point with no triangle or object (a vertex or an analytic hit), its shading
    /// normal standing for the geometric one.
    pub fn point(p: Vec3, n: Vec3) -> At<f32> {
        At { p: p.into(), n: n.into(), ng: n.into(), tri: u32::MAX, object: u32::MAX, per_lane: None }
    }
}

/// Shades what a traced ray (a mirror's or glass's) finds, as a camera sample would be at
/// that `depth` of the path: material, point, the way back along the ray, the evaluation
/// counts. The integrator ([`super::shade::shade_point_at_depth`]) passes itself, so the
/// environment and glass rays recurse without knowing the integrator.
pub type HitShader<'a> = &'a dyn Fn(&Material, At<f32>, Vec3, &mut EvalCounts, u32) -> Components;
