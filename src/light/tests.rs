//! The lights' tests: each kind's incident against the course's formulas and each sampled
//! kind's solid angle against its closed form; every lane width gives the scalar incident.

use super::*;
use crate::geometry::sampler::Sampler;
use crate::geometry::sampling::hash;

fn light(kind: LightKind, att: Vec3) -> Light {
    Light { kind, radiance: Vec3::ONE, specular: Vec3::ONE, ambient: Vec3::ZERO, attenuation: att, samples: 1, shadows: None }
}

fn at(l: &Light, p: Vec3) -> Incident<f32> {
    l.incident::<f32>(p.into())
}

#[test]
fn directional_l_is_minus_direction() {
    let i = at(&light(LightKind::Directional(Directional { direction: -Vec3::Y }), Vec3::X), Vec3::ZERO);
    assert_eq!(Vec3::from(i.l), Vec3::Y);
    assert_eq!((i.attenuation, i.c_spot, i.inv_r2, i.visibility), (1.0, 1.0, 1.0, 1.0));
    assert_eq!(i.distance, f32::INFINITY);
}

#[test]
fn attenuation_follows_the_course_formula() {
    let p = Vec3::new(0.0, 2.0, 0.0);
    let i = at(&light(LightKind::Point(Point { position: p }), Vec3::new(1.0, 0.5, 0.25)), Vec3::ZERO);
    assert!((i.attenuation - 1.0 / (1.0 + 0.5 * 2.0 + 0.25 * 4.0)).abs() < 1e-6);
    assert_eq!((Vec3::from(i.l), i.distance, i.inv_r2), (Vec3::Y, 2.0, 0.25));
    // r = 0 with pure inverse-square: finite, no direction.
    let at0 = at(&light(LightKind::Point(Point { position: Vec3::ZERO }), Vec3::Z), Vec3::ZERO);
    assert!(at0.attenuation.is_finite() && Vec3::from(at0.l) == Vec3::ZERO);
}

#[test]
fn spot_factor_is_cos_to_the_exponent_inside_the_cutoff() {
    let kind = LightKind::Spot(Spot {
        position: Vec3::new(0.0, 1.0, 0.0),
        direction: -Vec3::Y,
        exponent: 4.0,
        cos_cutoff: 30f32.to_radians().cos(),
        profile: None,
    });
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
    let profile = SpotProfile::new(&[(0.0, 0.2), (20.0, 0.6), (40.0, 1.0), (60.0, 0.0)]);
    let kind = LightKind::Spot(Spot {
        position: Vec3::new(0.0, 1.0, 0.0),
        direction: -Vec3::Y,
        exponent: 1.0,
        cos_cutoff: -1.0,
        profile: Some(profile),
    });
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
        light(LightKind::Directional(Directional { direction: Vec3::new(-1.0, -1.0, -1.0).normalize() }), Vec3::X),
        light(LightKind::Point(Point { position: Vec3::new(0.5, 2.0, 1.0) }), Vec3::new(1.0, 0.1, 0.05)),
        light(
            LightKind::Spot(Spot {
                position: Vec3::new(0.0, 3.0, 0.0),
                direction: -Vec3::Y,
                exponent: 7.3,
                cos_cutoff: 40f32.to_radians().cos(),
                profile: None,
            }),
            Vec3::new(0.0, 0.0, 1.0),
        ),
        light(
            LightKind::Spot(Spot {
                position: Vec3::new(0.0, 3.0, 0.0),
                direction: -Vec3::Y,
                exponent: 1.0,
                cos_cutoff: -1.0,
                profile: Some(SpotProfile::new(&[(0.0, 0.3), (35.0, 1.0), (60.0, 0.0)])),
            }),
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
        specular: Vec3::splat(0.3),
        ambient: Vec3::splat(0.3),
        attenuation: Vec3::X,
        samples: 1,
        shadows: None,
    };
    let i = at(&a, Vec3::new(1.0, 2.0, 3.0));
    assert!(i.ambient_only && Vec3::from(i.l) == Vec3::ZERO && i.ambient == Vec3::splat(0.3));
}

fn area_light(kind: LightKind, samples: u32) -> Light {
    Light {
        kind,
        radiance: Vec3::ONE,
        specular: Vec3::ONE,
        ambient: Vec3::ZERO,
        attenuation: Vec3::X,
        samples,
        shadows: None::<ShadowMethod>,
    }
}

/// A sampled light's projected solid angle A′ = Σ cos θ dω at p (normal n), averaged over
/// `seeds` patterns.
fn projected(l: &Light, p: Vec3, n: Vec3, seeds: u32) -> f64 {
    let mut sum = 0.0;
    for seed in 0..seeds {
        for k in 0..l.samples {
            let s = l.area_sample(p, n, Sampler::Sobol.u2(k, l.samples, hash(seed + 1)));
            sum += (s.weight * s.l.dot(n).max(0.0)) as f64;
        }
    }
    sum / seeds as f64
}

/// On the axis of a disk of radius R at height h, facing it: A′ = π R²/(h² + R²).
#[test]
fn a_disk_gives_its_analytic_projected_solid_angle() {
    let (r, h) = (0.5f32, 2.0f32);
    let disk = area_light(LightKind::Disk(Disk { position: Vec3::new(0.0, h, 0.0), direction: -Vec3::Y, radius: r }), 64);
    let want = std::f64::consts::PI * (r * r / (h * h + r * r)) as f64;
    let got = projected(&disk, Vec3::ZERO, Vec3::Y, 64);
    assert!((got - want).abs() < 2e-3 * want, "{got} vs {want}");
    // One-sided: from above (behind the emitting side) nothing arrives.
    assert_eq!(projected(&disk, Vec3::new(0.0, 2.0 * h, 0.0), -Vec3::Y, 4), 0.0);
}

/// A sphere of radius r at distance d over a point facing it: A′ = π (r/d)² (E = πL(r/d)²),
/// to rounding whatever the sample count (the cone is sampled, and cos is nearly 1 in it).
#[test]
fn a_sphere_gives_pi_r_over_d_squared() {
    for (r, d) in [(0.5f32, 2.0f32), (0.01, 10.0), (1.0, 1.001)] {
        let s =
            area_light(LightKind::Sphere(Sphere { position: Vec3::new(0.0, d, 0.0), radius: r, sampling: LightSampling::SolidAngle }), 256);
        let want = std::f64::consts::PI * (r as f64 / d as f64).powi(2);
        let got = projected(&s, Vec3::ZERO, Vec3::Y, 4);
        assert!((got - want).abs() < 3e-3 * want, "r {r} d {d}: {got} vs {want}");
    }
}

/// A sky of one colour over a surface facing up: A′ = π exactly (cosine-weighted samples).
#[test]
fn a_sky_over_a_floor_gives_pi() {
    let sky = area_light(LightKind::Sky(Sky { ground: Vec3::ONE }), 7);
    assert!((projected(&sky, Vec3::ZERO, Vec3::Y, 3) - std::f64::consts::PI).abs() < 1e-4);
}

/// Every kind gives finite, non-negative samples for points on, inside and far from the
/// emitter and for degenerate normals.
#[test]
fn samples_are_finite_everywhere() {
    let mut kinds = vec![
        LightKind::Rect(Rect {
            position: Vec3::ZERO,
            direction: -Vec3::Y,
            half_w: Vec3::X * 0.5,
            half_h: Vec3::Z * 0.5,
            sampling: LightSampling::SolidAngle,
        }),
        LightKind::Disk(Disk { position: Vec3::ZERO, direction: -Vec3::Y, radius: 1e-6 }),
        LightKind::Sphere(Sphere { position: Vec3::ZERO, radius: 1.0, sampling: LightSampling::SolidAngle }),
        LightKind::Line(Line { start: Vec3::ZERO, end: Vec3::X, radius: 0.01, sampling: LightSampling::SolidAngle }),
        LightKind::Sky(Sky { ground: Vec3::ZERO }),
    ];
    // The same kinds sampled by area.
    kinds.extend(kinds.clone().into_iter().filter_map(|k| match k {
        LightKind::Rect(r) => Some(LightKind::Rect(Rect { sampling: LightSampling::Area, ..r })),
        LightKind::Sphere(r) => Some(LightKind::Sphere(Sphere { sampling: LightSampling::Area, ..r })),
        LightKind::Line(r) => Some(LightKind::Line(Line { sampling: LightSampling::Area, ..r })),
        _ => None,
    }));
    let points = [Vec3::ZERO, Vec3::new(0.5, 0.0, 0.5), Vec3::new(0.2, 0.0, 0.0), Vec3::splat(1e6), Vec3::new(0.0, -1e-7, 0.0)];
    for kind in kinds {
        let l = area_light(kind, 8);
        for p in points {
            for n in [Vec3::Y, -Vec3::Y, Vec3::X] {
                for k in 0..8 {
                    let s = l.area_sample(p, n, Sampler::Sobol.u2(k, 8, 12345));
                    assert!(s.weight.is_finite() && s.weight >= 0.0 && s.l.is_finite() && !s.distance.is_nan(), "{kind:?} at {p}: {s:?}");
                }
            }
        }
    }
}

/// Both ways of placing samples estimate the same projected solid angle A′ (a rect's is
/// Lambert's polygon formula; a sphere's π (r/d)²); by solid angle the estimate is far less
/// noisy (RMSE over 400 points' hashed patterns, 16 Sobol samples each).
#[test]
fn area_and_solid_angle_sampling_agree_and_solid_angle_is_quieter() {
    let rect = |sampling| Rect {
        position: Vec3::new(0.3, 1.0, -0.2),
        direction: -Vec3::Y,
        half_w: Vec3::X * 0.8,
        half_h: Vec3::Z * 0.5,
        sampling,
    };
    let sphere = |sampling| Sphere { position: Vec3::new(0.4, 0.6, 0.0), radius: 0.4, sampling };
    let line = |sampling| Line { start: Vec3::new(-1.0, 0.5, 0.0), end: Vec3::new(1.5, 0.6, 0.2), radius: 0.02, sampling };
    let cases: [(&str, LightKind, LightKind); 3] = [
        ("rect", LightKind::Rect(rect(LightSampling::Area)), LightKind::Rect(rect(LightSampling::SolidAngle))),
        ("sphere", LightKind::Sphere(sphere(LightSampling::Area)), LightKind::Sphere(sphere(LightSampling::SolidAngle))),
        ("line", LightKind::Line(line(LightSampling::Area)), LightKind::Line(line(LightSampling::SolidAngle))),
    ];
    let n = 16;
    for (name, by_area, by_angle) in cases {
        let (a, b) = (area_light(by_area, n), area_light(by_angle, n));
        // Points on the floor y = 0 below the light, facing up.
        let estimates = |l: &Light, seed: u32, p: Vec3| -> f64 {
            (0..n)
                .map(|k| {
                    let s = l.area_sample(p, Vec3::Y, Sampler::Sobol.u2(k, n, hash(seed)));
                    (s.weight * s.l.dot(Vec3::Y).max(0.0)) as f64
                })
                .sum()
        };
        let (mut err_a, mut err_b, mut mean_a, mut mean_b) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        let points = 400;
        for i in 0..points {
            let p = Vec3::new(-0.5 + (i % 20) as f32 * 0.05, 0.0, -0.5 + (i / 20) as f32 * 0.05);
            // The reference: 64 patterns of 16 solid-angle samples at the same point.
            let truth = (0..64).map(|j| estimates(&b, 1000 + j, p)).sum::<f64>() / 64.0;
            let (ea, eb) = (estimates(&a, i, p), estimates(&b, i, p));
            mean_a += ea - truth;
            mean_b += eb - truth;
            err_a += (ea - truth).powi(2);
            err_b += (eb - truth).powi(2);
        }
        let (rmse_a, rmse_b) = ((err_a / points as f64).sqrt(), (err_b / points as f64).sqrt());
        // Both unbiased: the mean error within 4 standard errors of 0.
        assert!(
            (mean_a / points as f64).abs() < 4.0 * rmse_a / (points as f64).sqrt() + 1e-6,
            "{name}: area bias {}",
            mean_a / points as f64
        );
        assert!(
            (mean_b / points as f64).abs() < 4.0 * rmse_b / (points as f64).sqrt() + 1e-6,
            "{name}: solid-angle bias {}",
            mean_b / points as f64
        );
        assert!(rmse_b < rmse_a / 2.0, "{name}: solid-angle RMSE {rmse_b} is not below half the area RMSE {rmse_a}");
    }
}

/// The exact projected solid angle of a rect (Lambert) is what its samples estimate.
#[test]
fn a_rect_sampled_by_solid_angle_gives_lamberts_projected_solid_angle() {
    let r = Rect {
        position: Vec3::new(0.0, 2.0, 0.0),
        direction: -Vec3::Y,
        half_w: Vec3::X * 0.5,
        half_h: Vec3::Z * 0.3,
        sampling: LightSampling::SolidAngle,
    };
    let l = area_light(LightKind::Rect(r), 256);
    for p in [Vec3::ZERO, Vec3::new(1.0, 0.0, 0.5), Vec3::new(-2.0, 0.3, 1.0)] {
        let want = r.projected_solid_angle(p, Vec3::Y, &r.corners()) as f64;
        let got = projected(&l, p, Vec3::Y, 4);
        assert!((got - want).abs() < 2e-3 * want, "{p}: {got} vs {want}");
    }
}
