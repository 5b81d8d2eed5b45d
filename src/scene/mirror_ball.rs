//! Mirror-ball environments (sphere maps): a photograph of a mirrored ball from far away, as
//! light probes are shot. Loaded once into a latitude-longitude [`EnvMap`], as cube maps are,
//! so every lookup, sampler and prefilter reads it unchanged; and written from one, for
//! `shadelab envmap`.
//!
//! **Convention** (OpenGL's sphere map, `glTexGen(GL_SPHERE_MAP)`, OpenGL 4.6 compatibility
//! profile, section 12.1.3): the ball is seen along −z from far away, image up is +y. A pixel
//! at (s, t) (s along the columns, t along the rows from the top, both in [0, 1]) shows the
//! ball's normal n = (x, y, √(1 − x² − y²)) with x = 2s − 1, y = 1 − 2t, and reflects the
//! direction r = 2 n_z n − (0, 0, 1): the centre shows +z (behind the camera), the rim −z.
//! The inverse: m = 2√(r_x² + r_y² + (r_z + 1)²), s = r_x/m + ½, t = ½ − r_y/m. The whole
//! sphere of directions fits in the disc; the rim, where −z lies, is stretched thin.

use super::environment::{EnvError, EnvMap, cached, decode_rgb, direction_to_uv};
use glam::{Vec2, Vec3};

/// Where the unit direction `d` lands in a mirror-ball image, (s, t) in [0, 1]² (t from the
/// top row); straight back (−z), the rim's every point, lands at its right end.
#[inline]
pub fn direction_to_st(d: Vec3) -> Vec2 {
    let m = 2.0 * (d.x * d.x + d.y * d.y + (d.z + 1.0) * (d.z + 1.0)).sqrt();
    // Straight back, or a NaN: the rim.
    if m.is_nan() || m <= 1e-6 {
        return Vec2::new(1.0, 0.5);
    }
    Vec2::new(d.x / m + 0.5, 0.5 - d.y / m)
}

/// The direction the ball reflects at (s, t) of its image, or `None` outside the ball.
#[inline]
pub fn st_to_direction(st: Vec2) -> Option<Vec3> {
    let (x, y) = (2.0 * st.x - 1.0, 1.0 - 2.0 * st.y);
    let r2 = x * x + y * y;
    if r2.is_nan() || r2 > 1.0 {
        return None;
    }
    let z = (1.0 - r2).sqrt();
    Some(Vec3::new(2.0 * z * x, 2.0 * z * y, 2.0 * z * z - 1.0))
}

/// Bilinear radiance of an `n` × `n` ball image along `d`, read a texel inside the rim so
/// the black outside the ball never bleeds in.
fn sample(n: u32, texels: &[Vec3], d: Vec3) -> Vec3 {
    let st = direction_to_st(d.normalize_or_zero());
    let size = n as f32;
    // Pull the point towards the centre by a texel: the rim's texels are partly outside.
    let c = Vec2::splat(0.5);
    let st = c + (st - c) * (1.0 - 1.5 / size).max(0.0);
    let last = n - 1;
    let x = (st.x * size - 0.5).clamp(0.0, last as f32);
    let y = (st.y * size - 0.5).clamp(0.0, last as f32);
    let (i, j) = (x as u32, y as u32);
    let (fx, fy) = (x - i as f32, y - j as f32);
    let (i1, j1) = ((i + 1).min(last), (j + 1).min(last));
    let at = |i: u32, j: u32| texels[(j * n + i) as usize];
    let top = at(i, j) * (1.0 - fx) + at(i1, j) * fx;
    let bottom = at(i, j1) * (1.0 - fx) + at(i1, j1) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// A square ball image as a 2N × N latitude-longitude map (N its side, at most half
/// [`MAX_ENV_SIDE`](crate::lesson::limits::MAX_ENV_SIDE)).
///
/// # Errors
/// [`EnvError`] when the image is not square.
pub fn to_latlong(width: u32, height: u32, texels: &[Vec3]) -> Result<EnvMap, EnvError> {
    if width != height || width < 2 {
        return Err(EnvError { message: format!("{width}×{height} is not a mirror ball (a square image of the ball, rim to rim)") });
    }
    let n = width.min(crate::lesson::limits::MAX_ENV_SIDE / 2);
    Ok(EnvMap::from_fn(2 * n, n, |d| sample(width, texels, d)))
}

/// The lat-long map of a mirror-ball file, decoded once per run.
///
/// # Errors
/// [`EnvError`] when the file cannot be read or decoded or is not square.
pub fn load(path: &std::path::Path) -> Result<std::sync::Arc<EnvMap>, EnvError> {
    cached("mirror_ball", &[path.to_path_buf()], |_| {
        let (w, h, texels) = decode_rgb(path).map_err(|e| (0, e))?;
        to_latlong(w, h, &texels).map_err(|e| (0, e))
    })
    .map_err(|(_, e)| e)
}

/// `env` as an `n` × `n` mirror-ball image (black outside the ball), each pixel the mean of
/// the map's bilinear radiance over the directions a 4 × 4 grid across it reflects (those
/// inside the ball), so small bright sources keep their power in a coarse ball.
pub fn from_latlong(env: &EnvMap, n: u32) -> Vec<Vec3> {
    const K: u32 = 4;
    (0..n * n)
        .map(|p| {
            let (mut sum, mut inside) = (Vec3::ZERO, 0u32);
            for (i, j) in (0..K * K).map(|k| (k % K, k / K)) {
                let st = Vec2::new(
                    ((p % n) as f32 + (i as f32 + 0.5) / K as f32) / n as f32,
                    ((p / n) as f32 + (j as f32 + 0.5) / K as f32) / n as f32,
                );
                if let Some(d) = st_to_direction(st) {
                    sum += env.lookup(direction_to_uv(d));
                    inside += 1;
                }
            }
            if inside == 0 { Vec3::ZERO } else { sum / inside as f32 }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::environment::uv_to_direction;

    #[test]
    fn the_centre_reflects_the_camera_and_the_axes_land_where_opengl_puts_them() {
        let near = |a: Vec2, b: Vec2| (a - b).abs().max_element() < 1e-6;
        assert!(near(direction_to_st(Vec3::Z), Vec2::new(0.5, 0.5)));
        // +x and +y at 45° of the ball's normal: halfway out, right and up (t from the top).
        let h = 0.5 + 0.5 * std::f32::consts::FRAC_1_SQRT_2;
        assert!(near(direction_to_st(Vec3::X), Vec2::new(h, 0.5)), "{}", direction_to_st(Vec3::X));
        assert!(near(direction_to_st(Vec3::Y), Vec2::new(0.5, 1.0 - h)));
        assert_eq!(direction_to_st(-Vec3::Z), Vec2::new(1.0, 0.5));
        assert!(st_to_direction(Vec2::new(0.99, 0.99)).is_none(), "a corner is outside the ball");
    }

    #[test]
    fn direction_and_image_point_are_inverse_over_the_sphere() {
        for i in 0..64 {
            for j in 1..32 {
                let d = uv_to_direction(Vec2::new((i as f32 + 0.5) / 64.0, j as f32 / 32.0));
                if d.z < -0.95 {
                    continue; // the rim: a thin ring holds the whole back cap
                }
                let back = st_to_direction(direction_to_st(d)).unwrap();
                assert!((back - d).length() < 1e-4, "{d} → {back}");
            }
        }
    }

    #[test]
    fn a_map_survives_the_round_trip_through_a_ball_except_straight_behind() {
        // A smooth sky: the ball keeps it to a few parts in a thousand where it has room.
        let sky = EnvMap::from_fn(256, 128, |d| Vec3::new(1.0 + d.x, 1.0 + d.y, 1.0 + 0.5 * d.z));
        let ball = from_latlong(&sky, 512);
        let back = to_latlong(512, 512, &ball).unwrap();
        let mut worst: f32 = 0.0;
        for i in 0..64 {
            for j in 2..30 {
                let d = uv_to_direction(Vec2::new((i as f32 + 0.5) / 64.0, j as f32 / 32.0));
                if d.z < -0.7 {
                    continue;
                }
                let uv = direction_to_uv(d);
                worst = worst.max((back.lookup(uv) - sky.lookup(uv)).abs().max_element());
            }
        }
        assert!(worst < 0.01, "round-trip error {worst}");
        assert!(to_latlong(4, 3, &[Vec3::ONE; 12]).is_err());
    }
}
