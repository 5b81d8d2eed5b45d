//! Lights as the course defines them: colour, position or direction, attenuation, spot cone;
//! and what each delivers at a shaded point, as shading's [`Incident`].

pub use crate::lesson::light::{Light, LightKind};
use crate::shading::incident::Incident;
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

impl Light {
    /// What this light delivers at point `p` (one lane) or at lanes of points.
    ///
    /// A point or spot light exactly at the point (r = 0) has no direction: L is the zero
    /// vector there, so the diffuse and specular terms vanish instead of NaN.
    #[inline(always)]
    pub fn incident<F: Lanes>(&self, p: V3<F>) -> Incident<F> {
        let one = F::splat(1.0);
        let far = F::splat(f32::INFINITY);
        let (radiance, ambient) = (self.radiance, self.ambient);
        let unlit = Incident {
            l: V3::zero(),
            distance: far,
            attenuation: one,
            inv_r2: one,
            c_spot: one,
            visibility: one,
            radiance,
            ambient,
            ambient_only: false,
        };
        match self.kind {
            LightKind::Directional { direction } => Incident { l: V3::splat(-direction), ..unlit },
            LightKind::Point { position } => {
                let (l, r, inv_r2) = towards(V3::splat(position), p);
                Incident { l, distance: r, attenuation: attenuation(self.attenuation, r), inv_r2, ..unlit }
            }
            LightKind::Spot { position, direction, exponent, cos_cutoff, profile } => {
                let (l, r, inv_r2) = towards(V3::splat(position), p);
                let cos_axis = (-l).dot(V3::splat(direction));
                // C_spot = 0 outside the cutoff or behind the light, else min(cos, 1)^L_exp,
                // or the profile's I(θ) lane by lane.
                let outside = cos_axis.lt(F::splat(cos_cutoff)) | cos_axis.le(F::splat(0.0));
                let cos = F::select(cos_axis.lt(one), cos_axis, one);
                let law = match profile {
                    None => cos.pow(exponent),
                    Some(profile) => {
                        let mut c = [0f32; crate::simd::lanes::MAX_WIDTH];
                        cos.store(&mut c);
                        for x in c.iter_mut().take(F::WIDTH) {
                            *x = profile.at_cos(*x);
                        }
                        F::load(&c)
                    }
                };
                let c_spot = F::select(outside, F::splat(0.0), law);
                Incident { l, distance: r, attenuation: attenuation(self.attenuation, r), inv_r2, c_spot, ..unlit }
            }
            LightKind::Ambient => Incident { ambient_only: true, ..unlit },
            // Lights with extent deliver one incident per sample ([`Light::area_sample`]).
            LightKind::Rect { .. } | LightKind::Disk { .. } | LightKind::Sphere { .. } | LightKind::Line { .. } | LightKind::Sky { .. } => {
                Incident { c_spot: F::splat(0.0), ..unlit }
            }
        }
    }
}

/// Unit vector from `p` to `position` (zero when they coincide), the distance and 1/r².
#[inline(always)]
fn towards<F: Lanes>(position: V3<F>, p: V3<F>) -> (V3<F>, F, F) {
    let to = position - p;
    let r2 = to.dot(to);
    let r = r2.sqrt();
    let l = V3 { x: to.x / r, y: to.y / r, z: to.z / r };
    (V3::select(r.gt(F::splat(0.0)), l, V3::zero()), r, F::splat(1.0) / r2)
}

/// d = 1/(S_c + S_l r + S_q r²), capped at 1/1e-12 so r → 0 with S_c = 0 stays finite.
#[inline(always)]
pub fn attenuation<F: Lanes>(s: Vec3, r: F) -> F {
    let denom = F::splat(s.x) + F::splat(s.y) * r + F::splat(s.z) * r * r;
    // max(denom, 1e-12) as f32::max: a NaN denominator gives the cap.
    let cap = F::splat(1e-12);
    F::splat(1.0) / F::select(denom.gt(cap), denom, cap)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(kind: LightKind, att: Vec3) -> Light {
        Light { kind, radiance: Vec3::ONE, ambient: Vec3::ZERO, attenuation: att, samples: 1, shadows: None }
    }

    fn at(l: &Light, p: Vec3) -> Incident<f32> {
        l.incident::<f32>(p.into())
    }

    #[test]
    fn directional_l_is_minus_direction() {
        let i = at(&light(LightKind::Directional { direction: -Vec3::Y }, Vec3::X), Vec3::ZERO);
        assert_eq!(Vec3::from(i.l), Vec3::Y);
        assert_eq!((i.attenuation, i.c_spot, i.inv_r2, i.visibility), (1.0, 1.0, 1.0, 1.0));
        assert_eq!(i.distance, f32::INFINITY);
    }

    #[test]
    fn attenuation_follows_the_course_formula() {
        let p = Vec3::new(0.0, 2.0, 0.0);
        let i = at(&light(LightKind::Point { position: p }, Vec3::new(1.0, 0.5, 0.25)), Vec3::ZERO);
        assert!((i.attenuation - 1.0 / (1.0 + 0.5 * 2.0 + 0.25 * 4.0)).abs() < 1e-6);
        assert_eq!((Vec3::from(i.l), i.distance, i.inv_r2), (Vec3::Y, 2.0, 0.25));
        // r = 0 with pure inverse-square: finite, no direction.
        let at0 = at(&light(LightKind::Point { position: Vec3::ZERO }, Vec3::Z), Vec3::ZERO);
        assert!(at0.attenuation.is_finite() && Vec3::from(at0.l) == Vec3::ZERO);
    }

    #[test]
    fn spot_factor_is_cos_to_the_exponent_inside_the_cutoff() {
        let kind = LightKind::Spot {
            position: Vec3::new(0.0, 1.0, 0.0),
            direction: -Vec3::Y,
            exponent: 4.0,
            cos_cutoff: 30f32.to_radians().cos(),
            profile: None,
        };
        let l = light(kind, Vec3::X);
        assert!((at(&l, Vec3::ZERO).c_spot - 1.0).abs() < 1e-6);
        // 20° off axis: cos(20°)^4.
        let p = Vec3::new(20f32.to_radians().tan(), 0.0, 0.0);
        assert!((at(&l, p).c_spot - 20f32.to_radians().cos().powf(4.0)).abs() < 1e-5);
        // 40° off axis: outside the 30° cutoff.
        let q = Vec3::new(40f32.to_radians().tan(), 0.0, 0.0);
        assert_eq!(at(&l, q).c_spot, 0.0);
    }

    #[test]
    fn spot_profile_is_interpolated_in_theta() {
        use crate::lesson::light::SpotProfile;
        let profile = SpotProfile::new(&[(0.0, 0.2), (20.0, 0.6), (40.0, 1.0), (60.0, 0.0)]);
        let kind = LightKind::Spot {
            position: Vec3::new(0.0, 1.0, 0.0),
            direction: -Vec3::Y,
            exponent: 1.0,
            cos_cutoff: -1.0,
            profile: Some(profile),
        };
        let l = light(kind, Vec3::X);
        let off = |deg: f32| Vec3::new(deg.to_radians().tan(), 0.0, 0.0);
        // At a point of the profile: its I.
        assert!((at(&l, Vec3::ZERO).c_spot - 0.2).abs() < 1e-6);
        assert!((at(&l, off(20.0)).c_spot - 0.6).abs() < 1e-4);
        assert!((at(&l, off(40.0)).c_spot - 1.0).abs() < 1e-4);
        // Halfway between two points: their mean.
        assert!((at(&l, off(30.0)).c_spot - 0.8).abs() < 1e-4);
        assert!((at(&l, off(10.0)).c_spot - 0.4).abs() < 1e-4);
        // Beyond the last angle: 0.
        assert_eq!(at(&l, off(70.0)).c_spot, 0.0);
        assert_eq!(profile.at(60.5), 0.0);
    }

    /// Each lane of a light's incidents is the scalar incident of that point, to the bit, for
    /// every kind (the lanes shade Phong bundles, the scalar Gouraud vertices and the reference).
    #[inline(always)]
    fn check_lanes<F: Lanes>() {
        use crate::simd::lanes::MAX_WIDTH;
        let lights = [
            light(LightKind::Directional { direction: Vec3::new(-1.0, -1.0, -1.0).normalize() }, Vec3::X),
            light(LightKind::Point { position: Vec3::new(0.5, 2.0, 1.0) }, Vec3::new(1.0, 0.1, 0.05)),
            light(
                LightKind::Spot {
                    position: Vec3::new(0.0, 3.0, 0.0),
                    direction: -Vec3::Y,
                    exponent: 7.3,
                    cos_cutoff: 40f32.to_radians().cos(),
                    profile: None,
                },
                Vec3::new(0.0, 0.0, 1.0),
            ),
            light(
                LightKind::Spot {
                    position: Vec3::new(0.0, 3.0, 0.0),
                    direction: -Vec3::Y,
                    exponent: 1.0,
                    cos_cutoff: -1.0,
                    profile: Some(crate::lesson::light::SpotProfile::new(&[(0.0, 0.3), (35.0, 1.0), (60.0, 0.0)])),
                },
                Vec3::new(0.0, 0.0, 1.0),
            ),
            light(LightKind::Ambient, Vec3::X),
        ];
        let mut r = crate::simd::lanes::test_rng(0x9e37_79b9_7f4a_7c15, 2.0);
        let bits = |x: f32| x.to_bits();
        for _ in 0..500 {
            // Random points, one of them exactly at the point light.
            let mut pts: [Vec3; MAX_WIDTH] = std::array::from_fn(|_| Vec3::new(r(), r(), r()));
            pts[1] = Vec3::new(0.5, 2.0, 1.0);
            let p = V3 { x: F::load(&pts.map(|p| p.x)), y: F::load(&pts.map(|p| p.y)), z: F::load(&pts.map(|p| p.z)) };
            for l in &lights {
                let lanes = l.incident::<F>(p);
                let lane = |v: F| {
                    let mut out = [0f32; MAX_WIDTH];
                    v.store(&mut out);
                    out
                };
                let (lx, ly, lz) = (lane(lanes.l.x), lane(lanes.l.y), lane(lanes.l.z));
                let (d, a, i, c, vis) =
                    (lane(lanes.distance), lane(lanes.attenuation), lane(lanes.inv_r2), lane(lanes.c_spot), lane(lanes.visibility));
                for (k, q) in pts.iter().take(F::WIDTH).enumerate() {
                    let one = at(l, *q);
                    let l1 = Vec3::from(one.l);
                    assert_eq!([bits(l1.x), bits(l1.y), bits(l1.z)], [bits(lx[k]), bits(ly[k]), bits(lz[k])], "{:?} at {q}", l.kind);
                    assert_eq!(
                        [bits(one.distance), bits(one.attenuation), bits(one.inv_r2), bits(one.c_spot), bits(one.visibility)],
                        [bits(d[k]), bits(a[k]), bits(i[k]), bits(c[k]), bits(vis[k])],
                        "{:?} at {q}",
                        l.kind
                    );
                }
            }
        }
    }

    #[derive(Clone, Copy)]
    struct CheckLanes;

    impl crate::simd::lanes::LaneTask for CheckLanes {
        type Output = ();
        #[inline(always)]
        fn run<W: Lanes, H: Lanes>(self) {
            check_lanes::<W>();
        }
    }

    #[test]
    fn every_lane_width_gives_the_scalar_incidents() {
        crate::simd::at_every_width(CheckLanes);
    }

    #[test]
    fn ambient_lights_are_ambient_only() {
        let a = Light {
            kind: LightKind::Ambient,
            radiance: Vec3::splat(0.3),
            ambient: Vec3::splat(0.3),
            attenuation: Vec3::X,
            samples: 1,
            shadows: None,
        };
        let i = at(&a, Vec3::new(1.0, 2.0, 3.0));
        assert!(i.ambient_only && Vec3::from(i.l) == Vec3::ZERO && i.ambient == Vec3::splat(0.3));
    }
}
