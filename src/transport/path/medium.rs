//! The `[fog]` medium of the path tracer: where a ray is inside its ball, and the
//! transmittance along a segment.

use super::{PathCounts, PathTracer, Slot, Stream, power};
use crate::effects::fog::medium::transmittance;
use crate::effects::fog::phase::henyey_greenstein;
use crate::geometry::sampling::sin_cos;
use crate::light::LightKind;
use crate::shading::brdf::local_frame;
use crate::simd::lanes::V3;
use crate::transport::rays::Origin;
use glam::{Vec2, Vec3};

/// The `[fog]` medium as the path tracer sees it: grey coefficients in a ball about the eye.
#[derive(Debug, Clone, Copy)]
pub(super) struct Medium {
    pub(super) sigma_s: f32,
    pub(super) sigma_t: f32,
    pub(super) g: f32,
    pub(super) centre: Vec3,
    pub(super) radius: f32,
}

impl Medium {
    /// The part [t0, t1] of the ray o + t d (unit d, t ≥ 0) inside the ball, or `None`.
    pub(super) fn interval(&self, o: Vec3, d: Vec3) -> Option<(f32, f32)> {
        let oc = o - self.centre;
        let b = oc.dot(d);
        let c = oc.length_squared() - self.radius * self.radius;
        let disc = b * b - c;
        if disc.is_nan() || disc <= 0.0 {
            return None;
        }
        let s = disc.sqrt();
        let (t0, t1) = ((-b - s).max(0.0), -b + s);
        (t1 > t0).then_some((t0, t1))
    }

    /// Transmittance along o + t d for t in [0, distance] (∞ for a light at infinity).
    pub(super) fn transmittance(&self, o: Vec3, d: Vec3, distance: f32) -> f32 {
        match self.interval(o, d) {
            Some((t0, t1)) => transmittance(self.sigma_t, (t1.min(distance) - t0).max(0.0)),
            None => 1.0,
        }
    }
}

impl PathTracer<'_> {
    /// Next-event estimation at a point in the medium travelling along `d`: point, spot and
    /// directional lights (the lights the raster's march scatters), an emitter point and an
    /// environment direction, each times the phase p(l·d).
    pub(super) fn next_event_in_medium(&self, p: Vec3, d: Vec3, m: &Medium, stream: &Stream, depth: u32, counts: &mut PathCounts) -> Vec3 {
        let here = Origin { p, ng: d, tri: u32::MAX, object: u32::MAX };
        let mut sum = Vec3::ZERO;
        let mut visible = |l: Vec3, distance: f32| {
            counts.nee_rays += 1;
            let o = Origin { ng: l, ..here };
            !self.rays.occluded(&o, l, distance)
        };
        for (i, (light, shape)) in self.lights.iter().zip(&self.shapes).enumerate() {
            if let Some(shape) = shape {
                let u = stream.u2_at(depth, Slot::Light as u32 + i as u32);
                if let Some(h) = shape.sample(p, u, light.radiance)
                    && visible(h.l, h.t)
                {
                    let ph = henyey_greenstein(h.l.dot(d), m.g);
                    sum += h.radiance * ph * (power(h.pdf, ph) / h.pdf) * m.transmittance(p, h.l, h.t);
                }
                continue;
            }
            if matches!(light.kind, LightKind::Line(_)) {
                // A thin tube: its sample from the point (the normal is not used), dω each.
                let a = light.area_sample(p, d, stream.u2_at(depth, Slot::Light as u32 + i as u32));
                if a.weight > 0.0 && visible(a.l, a.distance) {
                    sum += a.radiance * (a.weight * henyey_greenstein(a.l.dot(d), m.g)) * m.transmittance(p, a.l, a.distance);
                }
                continue;
            }
            // Sky lights reach the medium by the phase's samples that escape (`escaped`).
            if !crate::effects::fog::medium::scatters(light) {
                continue;
            }
            let inc = light.incident::<f32>(V3::from(p));
            let l = Vec3::from(inc.l);
            if l == Vec3::ZERO || inc.c_spot.is_nan() || inc.c_spot <= 0.0 {
                continue;
            }
            if visible(l, inc.distance) {
                let e = light.radiance * (inc.inv_r2 * inc.c_spot);
                sum += e * henyey_greenstein(l.dot(d), m.g) * m.transmittance(p, l, inc.distance);
            }
        }
        if let Some(es) = self.emitters.sample(self.scene, p, stream.u1(depth, Slot::EmitterPick), stream.u2(depth, Slot::EmitterPoint))
            && visible(es.l, es.distance)
        {
            let ph = henyey_greenstein(es.l.dot(d), m.g);
            sum += es.radiance * ph * (power(es.pdf, ph) / es.pdf) * m.transmittance(p, es.l, es.distance);
        }
        if let (Some(env), Some(dist)) = (self.env, &self.env_dist) {
            let (dm, pe) = dist.sample(stream.u2(depth, Slot::Environment));
            let l = env.from_map(dm);
            if pe > 0.0 && visible(l, f32::INFINITY) {
                let ph = henyey_greenstein(l.dot(d), m.g);
                sum += env.radiance(l) * ph * (power(pe, ph) / pe) * m.transmittance(p, l, f32::INFINITY);
            }
        }
        if sum.is_finite() { sum } else { Vec3::ZERO }
    }
}

/// A direction drawn from the Henyey-Greenstein phase about the travel direction `d` (unit),
/// by inverting its cumulative distribution in μ = cos θ (pbrt-v3 §15.2.3): the pdf is the
/// phase itself, p(μ) of [`henyey_greenstein`] with μ = l·d.
pub fn sample_henyey_greenstein(d: Vec3, g: f32, u: Vec2) -> Vec3 {
    let mu = if g.abs() < 1e-3 {
        1.0 - 2.0 * u.x
    } else {
        let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
        (1.0 + g * g - s * s) / (2.0 * g)
    }
    .clamp(-1.0, 1.0);
    let sin = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let (sp, cp) = sin_cos(std::f32::consts::TAU * u.y);
    let (t, b) = local_frame(d);
    (t * (sin * cp) + b * (sin * sp) + d * mu).normalize_or(d)
}
