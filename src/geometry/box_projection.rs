//! Box projection (parallax correction) of a reflection probe: the direction from the
//! probe's centre C to where a reflected ray leaves the probe's box.
//!
//! A probe's cube map records the scene as seen from C. Looking it up along the reflected
//! direction R alone (naive) treats the scene as infinitely far, so a mirror at x ≠ C sees
//! the wrong wall. Lagarde & Zanuttini, "Local image-based lighting with parallax-corrected
//! cubemap" (SIGGRAPH 2012), and the course: with the box [B_min, B_max] standing in for the
//! room, the ray x + dR leaves it at
//!
//! d = min over axes i of max((B_max,i − x_i)/R_i, (B_min,i − x_i)/R_i),  P = x + dR,
//!
//! and the map is read along R′ = P − C. For a room that is exactly the box, P is the point
//! the traced ray hits, so the lookup is exact up to the map's resolution.
//!
//! **A moved probe** (the course's s′): a probe captured at C but read as if it stood at C′
//! (it moved with the object it serves, and recapturing costs six renders). The capture is a
//! projector at C: the wall point P shows in it along s = P − C. The moved probe's ray from
//! C′ meets the wall (B, n) at P, so for any point x on that ray
//!
//! s′ = x − C + [((B − x)·n) / ((C′ − x)·n)] (C′ − x)   (= P − C),
//!
//! which [`moved_centre`] computes as written and [`moved_project`] by the box's exit.
//!
//! Guards: an axis with R_i = 0 never bounds d (the ray runs parallel to its slab), so no
//! 0/0; a point outside the box is first clamped onto it (a mirror a hair outside by
//! rounding); R = 0 or a non-finite R, and R′ = 0, give R back unchanged.

use glam::Vec3;

/// Where the ray from `x` (clamped into the box) along `r` leaves the box `[b_min, b_max]`,
/// or `None` when `r` is zero or not finite.
pub fn box_exit(x: Vec3, r: Vec3, b_min: Vec3, b_max: Vec3) -> Option<Vec3> {
    if !r.is_finite() || r == Vec3::ZERO || !x.is_finite() {
        return None;
    }
    let x = x.clamp(b_min, b_max);
    let mut d = f32::INFINITY;
    for i in 0..3 {
        // max((B_max − x)/R, (B_min − x)/R) is the far slab plane: B_max for R_i > 0, B_min for R_i < 0.
        let t = if r[i] > 0.0 {
            (b_max[i] - x[i]) / r[i]
        } else if r[i] < 0.0 {
            (b_min[i] - x[i]) / r[i]
        } else {
            continue;
        };
        d = d.min(t.max(0.0));
    }
    // Some R_i ≠ 0, so d is finite; the exit is pinned to the box against rounding.
    Some((x + d * r).clamp(b_min, b_max))
}

/// The box-projected lookup direction R′ = P − C for a point `x`, reflected direction `r`,
/// probe centre `c` and box `[b_min, b_max]`; `r` itself where R′ is undefined.
pub fn box_project(x: Vec3, r: Vec3, c: Vec3, b_min: Vec3, b_max: Vec3) -> Vec3 {
    match box_exit(x, r, b_min, b_max) {
        Some(p) => {
            let rp = p - c;
            if rp.is_finite() && rp.length_squared() > 0.0 { rp } else { r }
        }
        None => r,
    }
}

/// The course's moved-centre lookup s′ = x − C + [((B − x)·n)/((C′ − x)·n)](C′ − x): the
/// direction from the capture point `c` to where the line through `x` and the moved centre
/// `c_moved` meets the plane through `b` with normal `n`; `None` when the line runs parallel
/// to the plane (the denominator is 0) or the result is not finite.
pub fn moved_centre(x: Vec3, c: Vec3, c_moved: Vec3, b: Vec3, n: Vec3) -> Option<Vec3> {
    let den = (c_moved - x).dot(n);
    if den == 0.0 {
        return None;
    }
    let s = x - c + ((b - x).dot(n) / den) * (c_moved - x);
    s.is_finite().then_some(s)
}

/// The lookup direction of a probe captured at `c` and read from `c_moved` along the unit
/// direction `r`: s′ = P − C with P where the ray from C′ leaves the box (the moved-centre
/// formula with x on that ray and (B, n) the wall it leaves by); `r` where s′ is undefined.
/// With C′ = C it is the naive lookup along R.
pub fn moved_project(r: Vec3, c: Vec3, c_moved: Vec3, b_min: Vec3, b_max: Vec3) -> Vec3 {
    box_project(c_moved, r, c, b_min, b_max)
}

#[cfg(test)]
mod tests {
    use super::*;

    const B_MIN: Vec3 = Vec3::new(-2.0, 0.0, -1.5);
    const B_MAX: Vec3 = Vec3::new(2.0, 3.0, 2.5);

    /// A deterministic spread of points inside the box and unit directions.
    fn cases() -> impl Iterator<Item = (Vec3, Vec3)> {
        (0..2000u32).map(|i| {
            let h = |k: u32| crate::geometry::sampling::hash3(i, k, 0x9e37) as f32 / u32::MAX as f32;
            let x = B_MIN + (B_MAX - B_MIN) * Vec3::new(h(1), h(2), h(3));
            let (z, phi) = (2.0 * h(4) - 1.0, std::f32::consts::TAU * h(5));
            let s = (1.0 - z * z).max(0.0).sqrt();
            (x, Vec3::new(s * phi.cos(), z, s * phi.sin()))
        })
    }

    #[test]
    fn the_exit_lies_on_a_wall_along_the_ray() {
        for (x, r) in cases() {
            let p = box_exit(x, r, B_MIN, B_MAX).unwrap();
            // On a wall: one coordinate at B_min or B_max (to f32 rounding of a 4-unit box).
            let on_wall = (0..3).any(|i| (p[i] - B_MIN[i]).abs() < 1e-5 || (p[i] - B_MAX[i]).abs() < 1e-5);
            assert!(on_wall, "x {x} r {r}: P {p} is not on a wall");
            // Along the ray, forwards: P − x is parallel to R with a non-negative length.
            let d = (p - x).dot(r);
            assert!(d >= -1e-6 && ((p - x) - d * r).length() < 1e-4, "x {x} r {r}: P {p} is off the ray");
        }
    }

    #[test]
    fn naive_and_box_projected_agree_when_the_point_is_the_centre() {
        // Points within 0.01 of a wall are skipped: there P − x is a few ulps long and f32
        // rounding alone turns R′ by ~1e-4 (the formula is exact there; the test is not).
        let inside = |x: Vec3| (x - B_MIN).min_element() > 0.01 && (B_MAX - x).min_element() > 0.01;
        for (x, r) in cases().filter(|(x, _)| inside(*x)) {
            let rp = box_project(x, r, x, B_MIN, B_MAX).normalize();
            assert!((rp - r).length() < 1e-4, "x {x}: R {r} vs R' {rp}");
        }
    }

    #[test]
    fn zero_components_and_degenerate_input_give_no_nan() {
        let c = Vec3::new(0.0, 1.5, 0.5);
        let x = Vec3::new(1.0, 1.0, 1.0);
        for r in [Vec3::X, Vec3::NEG_Y, Vec3::Z, Vec3::new(0.0, 0.6, 0.8), Vec3::new(-0.6, 0.0, 0.8)] {
            let p = box_exit(x, r, B_MIN, B_MAX).unwrap();
            assert!(p.is_finite(), "{r}: {p}");
            assert!(box_project(x, r, c, B_MIN, B_MAX).is_finite());
        }
        // x on a wall and R along it: the 0/0 of the formula is never formed.
        let on = Vec3::new(2.0, 1.0, 0.0);
        assert_eq!(box_exit(on, Vec3::Z, B_MIN, B_MAX), Some(Vec3::new(2.0, 1.0, 2.5)));
        assert_eq!(box_exit(on, Vec3::X, B_MIN, B_MAX), Some(on));
        assert_eq!(box_exit(x, Vec3::ZERO, B_MIN, B_MAX), None);
        assert_eq!(box_exit(x, Vec3::NAN, B_MIN, B_MAX), None);
        assert_eq!(box_project(x, Vec3::ZERO, c, B_MIN, B_MAX), Vec3::ZERO);
        // Outside the box: clamped onto it first, still on a wall.
        let p = box_exit(Vec3::new(5.0, 1.0, 0.0), Vec3::NEG_X, B_MIN, B_MAX).unwrap();
        assert_eq!(p, Vec3::new(-2.0, 1.0, 0.0));
        // The exit at the centre itself: R' would be 0, so R is returned.
        let corner_c = Vec3::new(2.0, 1.0, 0.0);
        assert_eq!(box_project(corner_c, Vec3::X, corner_c, B_MIN, B_MAX), Vec3::X);
    }

    #[test]
    fn the_moved_lookup_is_the_course_formula_on_the_wall_its_ray_leaves_by() {
        let c = Vec3::new(0.3, 1.5, 0.2);
        let inside = |x: Vec3| (x - B_MIN).min_element() > 0.05 && (B_MAX - x).min_element() > 0.05;
        let mut checked = 0;
        for (c_moved, r) in cases().filter(|(x, _)| inside(*x)) {
            let p = box_exit(c_moved, r, B_MIN, B_MAX).unwrap();
            // The wall P lies on, and its inward normal.
            let axis = (0..3).min_by(|&i, &j| {
                let d = |k: usize| (p[k] - B_MIN[k]).abs().min((p[k] - B_MAX[k]).abs());
                d(i).total_cmp(&d(j))
            });
            let mut n = Vec3::ZERO;
            n[axis.unwrap()] = 1.0;
            // Any point of the moved probe's ray serves as x: here one unit along it.
            let s = moved_centre(c_moved + 0.5 * r, c, c_moved, p, n).unwrap();
            let ours = moved_project(r, c, c_moved, B_MIN, B_MAX);
            assert!((s - ours).length() < 1e-4 * (1.0 + s.length()), "C′ {c_moved} r {r}: formula {s}, lookup {ours}");
            // Unmoved, the lookup is the naive one along R.
            assert!((moved_project(r, c_moved, c_moved, B_MIN, B_MAX).normalize() - r).length() < 1e-4);
            checked += 1;
        }
        assert!(checked > 1000, "{checked}");
        // A line parallel to the plane meets it nowhere.
        assert_eq!(moved_centre(Vec3::ZERO, c, Vec3::X, Vec3::Y, Vec3::Y), None);
    }

    #[test]
    fn an_axis_aligned_ray_from_the_floor_hits_the_ceiling_straight_above() {
        let x = Vec3::new(0.5, 0.0, 1.0);
        let c = Vec3::new(0.0, 1.5, 0.5);
        assert_eq!(box_exit(x, Vec3::Y, B_MIN, B_MAX), Some(Vec3::new(0.5, 3.0, 1.0)));
        assert_eq!(box_project(x, Vec3::Y, c, B_MIN, B_MAX), Vec3::new(0.5, 1.5, 0.5));
    }
}
