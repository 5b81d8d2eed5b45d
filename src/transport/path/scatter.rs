//! What scatters light at a path vertex, for next-event estimation and MIS: a BRDF, a rough
//! glass interface with its tint, or a BRDF with a diffuse transmission on the far side.

use crate::shading::brdf::Brdf;
use crate::shading::principled_transmission::DiffuseTransmission;
use crate::shading::rough_dielectric::RoughDielectric;
use glam::Vec3;

/// What scatters light at a surface vertex, for next-event estimation: a BRDF, or a rough
/// glass interface with its tint.
#[derive(Clone, Copy)]
pub(super) enum Scatter<'b> {
    Brdf(&'b Brdf),
    Rough(RoughDielectric, Vec3),
    /// A BRDF with a Lambertian BTDF on the other side (principled diffuse transmission).
    Translucent(&'b Brdf, DiffuseTransmission),
}

impl Scatter<'_> {
    /// f(l, v) in the local frame (the tint on a refraction).
    pub(super) fn eval(&self, ll: Vec3, vl: Vec3) -> Vec3 {
        match self {
            Scatter::Brdf(b) => b.eval(ll, vl),
            Scatter::Rough(r, tint) => {
                let f = Vec3::splat(r.eval(ll, vl));
                if ll.z * vl.z < 0.0 { f * *tint } else { f }
            }
            Scatter::Translucent(b, d) => {
                if ll.z * vl.z < 0.0 {
                    d.value
                } else {
                    b.eval(ll, vl)
                }
            }
        }
    }

    /// The pdf of sampling l from v.
    pub(super) fn pdf(&self, vl: Vec3, ll: Vec3) -> f32 {
        match self {
            Scatter::Brdf(b) => b.pdf(vl, ll),
            Scatter::Rough(r, _) => r.pdf(vl, ll),
            Scatter::Translucent(b, d) => {
                if ll.z * vl.z < 0.0 {
                    d.q * d.pdf(vl, ll)
                } else {
                    (1.0 - d.q) * b.pdf(vl, ll)
                }
            }
        }
    }
}
