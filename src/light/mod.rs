//! Lights: one file per kind, each with its parameters, what it delivers at a shaded point
//! (its incident radiance, or one sample of it for a light with extent) and how it may be
//! shadowed. The seam to shading is [`Incident`]: render asks each light for one or more
//! per shaded point and shading, which knows no light kinds, turns them into terms.
//!
//! | kind | file | delivers |
//! | --- | --- | --- |
//! | [`LightKind::Directional`] | `directional.rs` | one incident, L = −direction |
//! | [`LightKind::Point`] | `point.rs` | one incident, attenuation d = 1/(S_c + S_l r + S_q r²), 1/r² |
//! | [`LightKind::Spot`] | `spot.rs` | a point light × C_spot (cos^L_exp or a goniometric profile) |
//! | [`LightKind::Ambient`] | `ambient.rs` | only I_amb = K_amb ⊗ L_amb |
//! | [`LightKind::Rect`] | `rect.rs` | samples by solid angle (its spherical rectangle) or by area; the exact unoccluded irradiance (Lambert) for references |
//! | [`LightKind::Disk`] | `disk.rs` | samples by area |
//! | [`LightKind::Sphere`] | `sphere.rs` | samples in the cone it subtends, or by area |
//! | [`LightKind::Line`] | `line.rs` | samples by the angle the tube subtends, or along it |
//! | [`LightKind::Sky`] | `sky.rs` | cosine-weighted samples of the sky and the ground |
//!
//! [`shadow`] holds the one place a light's shadow method is chosen. A light is built from the
//! lesson's validated [`LightSpec`] ([`Light::from_spec`]): the lesson says what the file
//! holds, each kind's file what it means.

pub mod ambient;
pub mod directional;
pub mod disk;
pub mod line;
pub mod point;
pub mod rect;
pub mod sample;
pub mod shadow;
pub mod sky;
pub mod sphere;
pub mod spot;

pub use directional::Directional;
pub use disk::Disk;
pub use line::{Line, LineFrom};
pub use point::Point;
pub use rect::{Rect, RectFrom};
pub use sample::{AreaSample, LightSampling};
pub use shadow::{ShadowMethod, Shadowing};
pub use sky::Sky;
pub use sphere::Sphere;
pub use spot::{MAX_PROFILE_POINTS, Spot, SpotProfile};

use crate::lesson::kinds::LightType;
use crate::lesson::light::LightSpec;
use crate::shading::incident::Incident;
use crate::simd::lanes::{Lanes, V3};
use glam::{Vec2, Vec3};

/// The closed set of light kinds, each with its parameters.
// A spot's profile is held inline (a fixed array) so that lights stay `Copy`.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightKind {
    /// Parallel light ([`Directional`]).
    Directional(Directional),
    /// Light from a point ([`Point`]).
    Point(Point),
    /// A point light restricted to a cone ([`Spot`]).
    Spot(Spot),
    /// Only an ambient contribution I_amb = K_amb ⊗ L_amb.
    Ambient,
    /// A one-sided emitting rectangle ([`Rect`]).
    Rect(Rect),
    /// A one-sided emitting disk ([`Disk`]).
    Disk(Disk),
    /// A sphere emitting all round ([`Sphere`]).
    Sphere(Sphere),
    /// A thin emitting tube ([`Line`]).
    Line(Line),
    /// A hemisphere light: the sky above the horizon, the ground below ([`Sky`]).
    Sky(Sky),
}

impl LightKind {
    /// Which kind this is, as the lesson names it.
    pub fn light_type(&self) -> LightType {
        match self {
            LightKind::Directional(_) => LightType::Directional,
            LightKind::Point(_) => LightType::Point,
            LightKind::Spot(_) => LightType::Spot,
            LightKind::Ambient => LightType::Ambient,
            LightKind::Rect(_) => LightType::Rect,
            LightKind::Disk(_) => LightType::Disk,
            LightKind::Sphere(_) => LightType::Sphere,
            LightKind::Line(_) => LightType::Line,
            LightKind::Sky(_) => LightType::Sky,
        }
    }

    /// The name in lesson files.
    pub fn name(&self) -> &'static str {
        self.light_type().name()
    }

    /// True for the lights sampled at several points (rect, disk, sphere, line, sky).
    pub fn is_sampled(&self) -> bool {
        matches!(self, LightKind::Rect(_) | LightKind::Disk(_) | LightKind::Sphere(_) | LightKind::Line(_) | LightKind::Sky(_))
    }

    /// The light's position, for the kinds that have one point (point, spot).
    pub fn position(&self) -> Option<Vec3> {
        match self {
            LightKind::Point(p) => Some(p.position),
            LightKind::Spot(s) => Some(s.position),
            _ => None,
        }
    }
}

/// One light of the illumination equation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Kind and geometry.
    pub kind: LightKind,
    /// L_diff: colour × intensity (for `Ambient`, this is L_amb); the physically based
    /// models read it for their whole BRDF.
    pub radiance: Vec3,
    /// L_spec of the classic models: `specular` × intensity, or `radiance` when not given.
    pub specular: Vec3,
    /// This light's ambient part L_amb^k (for `Ambient` lights equal to `radiance`).
    pub ambient: Vec3,
    /// [S_c, S_l, S_q] for d = 1/(S_c + S_l r + S_q r²); ignored by directional lights.
    pub attenuation: Vec3,
    /// Samples per shaded point for the sampled kinds (1 for the others).
    pub samples: u32,
    /// This light's own shadow method (`None`: the `[render]` one).
    pub shadows: Option<ShadowMethod>,
}

impl Light {
    /// The light a validated `[[light]]` describes.
    pub fn from_spec(l: &LightSpec) -> Light {
        let kind = match l.kind {
            LightType::Directional => LightKind::Directional(Directional { direction: l.direction }),
            LightType::Point => LightKind::Point(Point { position: l.position }),
            LightType::Spot => LightKind::Spot(Spot::from_spec(l)),
            LightType::Ambient => LightKind::Ambient,
            LightType::Rect => LightKind::Rect(Rect::from_spec(l)),
            LightType::Disk => LightKind::Disk(Disk { position: l.position, direction: l.direction, radius: l.radius }),
            LightType::Sphere => LightKind::Sphere(Sphere { position: l.position, radius: l.radius, sampling: l.sampling }),
            LightType::Line => LightKind::Line(Line { start: l.ends[0], end: l.ends[1], radius: l.radius, sampling: l.sampling }),
            LightType::Sky => LightKind::Sky(Sky { ground: l.ground }),
        };
        Light {
            kind,
            radiance: l.radiance,
            specular: l.specular,
            ambient: l.ambient,
            attenuation: l.attenuation,
            samples: l.samples,
            shadows: l.shadows,
        }
    }

    /// What this light delivers at point `p` (one lane) or at lanes of points, for the kinds
    /// that are not sampled; a sampled kind gives an incident with C_spot = 0 here (its light
    /// comes from [`Light::area_sample`]).
    ///
    /// A point or spot light exactly at the point (r = 0) has no direction: L is the zero
    /// vector there, so the diffuse and specular terms vanish instead of NaN.
    #[inline(always)]
    pub fn incident<F: Lanes>(&self, p: V3<F>) -> Incident<F> {
        let unlit = unlit(self.radiance, self.specular, self.ambient);
        match &self.kind {
            LightKind::Directional(d) => d.incident(unlit),
            LightKind::Point(pt) => pt.incident(self.attenuation, p, unlit),
            LightKind::Spot(s) => s.incident(self.attenuation, p, unlit),
            LightKind::Ambient => ambient::incident(unlit),
            LightKind::Rect(_) | LightKind::Disk(_) | LightKind::Sphere(_) | LightKind::Line(_) | LightKind::Sky(_) => {
                Incident { c_spot: F::splat(0.0), ..unlit }
            }
        }
    }

    /// This light seen from point `p` with unit normal `n`: what its samples there share
    /// (a spherical rectangle, a thin tube), computed once for all of them.
    pub fn from_point(&self, p: Vec3, n: Vec3) -> FromPoint {
        match &self.kind {
            LightKind::Rect(r) => FromPoint::Rect(r.from(p, n)),
            LightKind::Line(l) => FromPoint::Line(l.from(p)),
            LightKind::Disk(_) | LightKind::Sphere(_) => FromPoint::At(p),
            LightKind::Sky(_) => FromPoint::At(n),
            LightKind::Directional(_) | LightKind::Point(_) | LightKind::Spot(_) | LightKind::Ambient => FromPoint::None,
        }
    }

    /// The sample at u ∈ [0, 1)² from `from` ([`Light::from_point`]), carrying 1/`samples`
    /// of its solid angle; [`AreaSample::NONE`] for the kinds that are not sampled.
    pub fn sample_from(&self, from: &FromPoint, u: Vec2) -> AreaSample {
        let per = 1.0 / self.samples.max(1) as f32;
        let le = self.radiance;
        match (&self.kind, from) {
            (LightKind::Rect(r), FromPoint::Rect(f)) => r.sample(f, u, per, le),
            (LightKind::Line(l), FromPoint::Line(f)) => l.sample(f, u, per, le),
            (LightKind::Disk(d), FromPoint::At(p)) => d.sample(*p, u, per, le),
            (LightKind::Sphere(s), FromPoint::At(p)) => s.sample(*p, u, per, le),
            (LightKind::Sky(s), FromPoint::At(n)) => s.sample(*n, u, per, le),
            _ => AreaSample::NONE,
        }
    }

    /// The sample at `u` seen from `p` with unit normal `n` ([`Light::from_point`] and
    /// [`Light::sample_from`] in one, for a single sample).
    pub fn area_sample(&self, p: Vec3, n: Vec3, u: Vec2) -> AreaSample {
        self.sample_from(&self.from_point(p, n), u)
    }

    /// The radiance a sky sample brings from below the horizon (`None` for other kinds).
    pub fn ground(&self) -> Option<Vec3> {
        match self.kind {
            LightKind::Sky(s) => Some(s.ground),
            _ => None,
        }
    }
}

/// A sampled light seen from one shaded point ([`Light::from_point`]).
#[derive(Debug, Clone, Copy)]
pub enum FromPoint {
    /// Not a sampled light.
    None,
    /// A rect light's view.
    Rect(RectFrom),
    /// A line light's view.
    Line(LineFrom),
    /// The point (disk, sphere) or the normal (sky) the samples start from.
    At(Vec3),
}

/// The incident every kind starts from: no direction, unattenuated, fully visible.
#[inline(always)]
fn unlit<F: Lanes>(radiance: Vec3, specular: Vec3, ambient: Vec3) -> Incident<F> {
    let one = F::splat(1.0);
    Incident {
        l: V3::zero(),
        distance: F::splat(f32::INFINITY),
        attenuation: one,
        inv_r2: one,
        c_spot: one,
        visibility: one,
        radiance,
        specular,
        ambient,
        ambient_only: false,
    }
}

#[cfg(test)]
mod tests;
