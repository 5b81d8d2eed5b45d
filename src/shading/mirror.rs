//! The perfect mirror: all light leaves in the mirror direction r = 2(n·v)n − v.
//!
//! | parameter | range | meaning |
//! | --- | --- | --- |
//! | `tint` | [0, 1]³ | the reflectance (1: a perfect mirror, as Mitsuba's `conductor` with `material = "none"`) |
//!
//! L_o(v) = tint ⊗ L_i(r). The BRDF is a Dirac delta, so a point, spot or area light (a set
//! of measure zero or a finite set of directions) is never seen in it: a mirror shows only
//! what its reflected ray finds, the environment or another object (the reflection layer,
//! added by render). Its direct diffuse and specular terms are zero.
//!
//! **Lobes and sampling** ([`super::lobe`]): one delta-reflection lobe of weight `tint` (no
//! diffuse or specular part: radiosity and ambient light see ρ = 0). [`Mirror::sample`] returns
//! the mirror direction in the local frame (z = the normal on the viewer's side) with
//! weight `tint` and probability 1, as render's mirror does (`tint ⊗ L_i(r)`).

use super::lobe::{DeltaSample, Lobe, LobeKind, LobeSet};
use glam::Vec3;

/// A perfect specular reflector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mirror {
    /// Reflectance per channel.
    pub tint: Vec3,
}

impl Mirror {
    /// One delta-reflection lobe of weight `tint`.
    pub fn lobes(&self) -> LobeSet {
        LobeSet::new(&[Lobe::new(LobeKind::DeltaReflection, self.tint)])
    }

    /// The reflected direction r = 2(n·v)n − v = (−v_x, −v_y, v_z) for unit `v` in the local
    /// frame, weight `tint`; `None` for v.z ≤ 0 (the viewer behind the mirror's frame).
    #[inline]
    pub fn sample(&self, v: Vec3) -> Option<DeltaSample> {
        (v.z > 0.0).then(|| DeltaSample {
            l: Vec3::new(-v.x, -v.y, v.z),
            weight: self.tint,
            probability: 1.0,
            kind: LobeKind::DeltaReflection,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_is_the_mirror_direction_with_the_tint() {
        let m = Mirror { tint: Vec3::new(0.9, 0.5, 0.1) };
        let v = Vec3::new(0.6, -0.48, 0.64);
        let s = m.sample(v).unwrap();
        assert_eq!(s.l, crate::geometry::vector::reflect(v, Vec3::Z));
        assert_eq!((s.weight, s.probability, s.kind), (m.tint, 1.0, LobeKind::DeltaReflection));
        assert!(m.sample(Vec3::new(0.6, 0.8, 0.0)).is_none() && m.sample(-v).is_none());
        assert_eq!(m.lobes().as_slice(), &[Lobe::new(LobeKind::DeltaReflection, m.tint)]);
    }
}
