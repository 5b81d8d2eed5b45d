//! Cube maps: six square faces (or one horizontal cross) resampled once, when loaded, into a
//! latitude-longitude [`EnvMap`], so every lookup, sampler, prefilter and SH projection reads
//! them unchanged.
//!
//! **Faces** are in OpenGL order, `px, nx, py, ny, pz, nz` (+x, −x, +y, −y, +z, −z), and
//! oriented as the OpenGL specification's table "Selection of cube map images": for a
//! direction r the face is that of the major axis ma (the largest |r_i|), and
//!
//! | face | sc | tc |
//! | --- | --- | --- |
//! | +x | −r_z | −r_y |
//! | −x | +r_z | −r_y |
//! | +y | +r_x | +r_z |
//! | −y | +r_x | −r_z |
//! | +z | +r_x | −r_y |
//! | −z | −r_x | −r_y |
//!
//! s = ½(sc/|ma| + 1) runs along a face image's columns (left to right), t = ½(tc/|ma| + 1)
//! along its rows (top row first, as the file stores it). Within a face the radiance is
//! bilinear between texel centres and clamped to the face's edge texels, so no lookup reads
//! outside its face and there is no gap at an edge.
//!
//! **A horizontal cross** is 4N × 3N: +y above, −y below, and the middle row −x, +z, +x, −z;
//! each face sits in it as its own image would be, so the cross folds into a cube.
//!
//! The lat-long map is 4N × 2N (the 2:1 shape a loaded map has): one texel per cube texel
//! along the equator.

use super::environment::{EnvError, EnvMap, cached, decode_rgb};
use glam::Vec3;
use std::path::PathBuf;
use std::sync::Arc;

/// The faces in lesson order: OpenGL's `px, nx, py, ny, pz, nz`.
pub const FACE_NAMES: [&str; 6] = ["px", "nx", "py", "ny", "pz", "nz"];

/// Where each face sits in a horizontal cross, as (column, row) in units of the face size.
pub const CROSS_CELLS: [(u32, u32); 6] = [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (3, 1)];

/// Six square faces of one size, linear RGB, each row-major from its top row.
#[derive(Debug, Clone, PartialEq)]
pub struct CubeFaces {
    /// Texels along a face's side.
    pub size: u32,
    /// The faces in [`FACE_NAMES`] order.
    pub faces: [Vec<Vec3>; 6],
}

impl CubeFaces {
    /// Six decoded images `(width, height, texels)` as faces.
    ///
    /// # Errors
    /// (index of the face, [`EnvError`]) when a face is not square or not the size of the first.
    pub fn from_images(images: Vec<(u32, u32, Vec<Vec3>)>) -> Result<CubeFaces, (usize, EnvError)> {
        if images.len() != 6 {
            return Err((0, EnvError { message: format!("a cube map has 6 faces, not {}", images.len()) }));
        }
        let size = images[0].0;
        let mut faces: [Vec<Vec3>; 6] = Default::default();
        for (k, (w, h, texels)) in images.into_iter().enumerate() {
            if w != h || w == 0 {
                return Err((k, EnvError { message: format!("{w}×{h} is not a square cube face") }));
            }
            if w != size {
                return Err((k, EnvError { message: format!("{w}×{h} is not the size of the first face ({size}×{size})") }));
            }
            faces[k] = texels;
        }
        Ok(CubeFaces { size, faces })
    }

    /// The faces cut out of a horizontal cross `width` × `height` (see the module docs).
    ///
    /// # Errors
    /// [`EnvError`] when the image is not 4:3 with a side divisible by 4.
    pub fn from_cross(width: u32, height: u32, texels: &[Vec3]) -> Result<CubeFaces, EnvError> {
        if width == 0 || !width.is_multiple_of(4) || width / 4 * 3 != height {
            return Err(EnvError { message: format!("{width}×{height} is not a horizontal cross (4:3, its width a multiple of 4)") });
        }
        let n = width / 4;
        let faces = CROSS_CELLS.map(|(cx, cy)| {
            (0..n)
                .flat_map(|y| {
                    let row = ((cy * n + y) * width + cx * n) as usize;
                    texels[row..row + n as usize].iter().copied()
                })
                .collect()
        });
        Ok(CubeFaces { size: n, faces })
    }

    /// The face (index in [`FACE_NAMES`]) and (s, t) in [0, 1]² of a direction, by the OpenGL table.
    #[inline]
    pub fn face_st(d: Vec3) -> (usize, f32, f32) {
        let a = d.abs();
        // Ties go to x, then y: one face for every direction, the same on every machine.
        let (face, sc, tc, ma) = if a.x >= a.y && a.x >= a.z {
            if d.x >= 0.0 { (0, -d.z, -d.y, a.x) } else { (1, d.z, -d.y, a.x) }
        } else if a.y >= a.z {
            if d.y >= 0.0 { (2, d.x, d.z, a.y) } else { (3, d.x, -d.z, a.y) }
        } else if d.z >= 0.0 {
            (4, d.x, -d.y, a.z)
        } else {
            (5, -d.x, -d.y, a.z)
        };
        (face, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0))
    }

    /// Bilinear radiance along the direction `d` (need not be unit; zero for a zero or
    /// non-finite `d`), clamped to the face's edge texels.
    pub fn sample(&self, d: Vec3) -> Vec3 {
        if !d.is_finite() || d == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let (face, s, t) = CubeFaces::face_st(d);
        let n = self.size as f32;
        let last = self.size - 1;
        // Texel centres are at (i + ½)/n.
        let x = (s * n - 0.5).clamp(0.0, last as f32);
        let y = (t * n - 0.5).clamp(0.0, last as f32);
        let (i, j) = (x as u32, y as u32);
        let (fx, fy) = (x - i as f32, y - j as f32);
        let (i1, j1) = ((i + 1).min(last), (j + 1).min(last));
        let f = &self.faces[face];
        let at = |i: u32, j: u32| f[(j * self.size + i) as usize];
        let top = at(i, j) * (1.0 - fx) + at(i1, j) * fx;
        let bottom = at(i, j1) * (1.0 - fx) + at(i1, j1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// The cube resampled into a 4N × 2N latitude-longitude map, at most
    /// [`MAX_ENV_SIDE`](crate::lesson::limits::MAX_ENV_SIDE) wide: six 4096² faces would
    /// otherwise make a 16384 × 8192 map (3.6 GB, two minutes), past the documented side.
    pub fn to_latlong(&self) -> EnvMap {
        let n = latlong_n(self.size);
        EnvMap::from_fn(4 * n, 2 * n, |d| self.sample(d))
    }
}

/// The direction through (s, t) of face `face` (index in [`FACE_NAMES`]): the OpenGL
/// table read backwards, with sc = 2s − 1 and tc = 2t − 1 (not unit length).
pub fn face_direction(face: usize, s: f32, t: f32) -> Vec3 {
    let (sc, tc) = (2.0 * s - 1.0, 2.0 * t - 1.0);
    match face {
        0 => Vec3::new(1.0, -tc, -sc),
        1 => Vec3::new(-1.0, -tc, sc),
        2 => Vec3::new(sc, 1.0, tc),
        3 => Vec3::new(sc, -1.0, -tc),
        4 => Vec3::new(sc, -tc, 1.0),
        _ => Vec3::new(-sc, -tc, -1.0),
    }
}

/// `env` as a 4N × 3N horizontal cross of N² faces (black where no face sits): each texel the
/// mean of the map's bilinear radiance over a 4 × 4 grid of directions across it, so a small
/// bright source (a sun of a few texels) keeps its power when the faces are coarser than the
/// map. (width, height, texels).
pub fn cross_from_latlong(env: &EnvMap, n: u32) -> (u32, u32, Vec<Vec3>) {
    const K: u32 = 4;
    let (w, h) = (4 * n, 3 * n);
    let mut texels = vec![Vec3::ZERO; (w * h) as usize];
    for (face, (cx, cy)) in CROSS_CELLS.iter().enumerate() {
        for y in 0..n {
            for x in 0..n {
                let mut sum = Vec3::ZERO;
                for (i, j) in (0..K * K).map(|k| (k % K, k / K)) {
                    let s = (x as f32 + (i as f32 + 0.5) / K as f32) / n as f32;
                    let t = (y as f32 + (j as f32 + 0.5) / K as f32) / n as f32;
                    // Equal weights: a texel near a face's corner spans a little less solid angle.
                    sum += env.lookup(super::environment::direction_to_uv(face_direction(face, s, t).normalize()));
                }
                texels[((cy * n + y) * w + cx * n + x) as usize] = sum / (K * K) as f32;
            }
        }
    }
    (w, h, texels)
}

/// N of the 4N × 2N map a cube of `size`² faces becomes: `size`, capped at a quarter of
/// [`MAX_ENV_SIDE`](crate::lesson::limits::MAX_ENV_SIDE).
fn latlong_n(size: u32) -> u32 {
    size.min(crate::lesson::limits::MAX_ENV_SIDE / 4)
}

/// The lat-long map of six face files (in [`FACE_NAMES`] order), decoded once per run.
///
/// # Errors
/// (index of the face at fault, [`EnvError`]) when a face cannot be read or decoded, is not
/// square, or is not the size of the first.
pub fn load_faces(paths: &[PathBuf]) -> Result<Arc<EnvMap>, (usize, EnvError)> {
    cached("faces", paths, |paths| {
        let images = paths.iter().enumerate().map(|(k, p)| decode_rgb(p).map_err(|e| (k, e))).collect::<Result<Vec<_>, _>>()?;
        Ok(CubeFaces::from_images(images)?.to_latlong())
    })
}

/// The lat-long map of a horizontal-cross file, decoded once per run.
///
/// # Errors
/// [`EnvError`] when the file cannot be read or decoded or is not a 4:3 cross.
pub fn load_cross(path: &std::path::Path) -> Result<Arc<EnvMap>, EnvError> {
    cached("cross", &[path.to_path_buf()], |_| {
        let (w, h, texels) = decode_rgb(path).map_err(|e| (0, e))?;
        Ok(CubeFaces::from_cross(w, h, &texels).map_err(|e| (0, e))?.to_latlong())
    })
    .map_err(|(_, e)| e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::environment::direction_to_uv;

    /// Six 8 × 8 faces, face k a constant (k + 1)/8 in red and k/16 in blue, with green the
    /// column index s and (face ≥ 2's) nothing else; `gradient` puts (column + row·8) in green.
    fn faces(gradient: bool) -> CubeFaces {
        let faces = std::array::from_fn(|k| {
            (0..64).map(|p| Vec3::new((k + 1) as f32 / 8.0, if gradient { p as f32 } else { 0.0 }, k as f32 / 16.0)).collect()
        });
        CubeFaces { size: 8, faces }
    }

    #[test]
    fn a_face_point_and_its_direction_are_inverse_and_a_cross_round_trip_keeps_the_map() {
        for face in 0..6 {
            for (s, t) in [(0.1, 0.2), (0.5, 0.5), (0.9, 0.7)] {
                let (f, s2, t2) = CubeFaces::face_st(face_direction(face, s, t));
                assert_eq!(f, face);
                assert!((s2 - s).abs() < 1e-6 && (t2 - t).abs() < 1e-6, "face {face}: ({s}, {t}) → ({s2}, {t2})");
            }
        }
        let sky = EnvMap::from_fn(128, 64, |d| Vec3::new(1.0 + d.x, 1.0 + d.y, 1.0 + 0.5 * d.z));
        let (w, h, texels) = cross_from_latlong(&sky, 64);
        let back = CubeFaces::from_cross(w, h, &texels).unwrap().to_latlong();
        let worst = (0..back.texels.len())
            .map(|k| {
                let uv = glam::Vec2::new(
                    ((k as u32 % back.width) as f32 + 0.5) / back.width as f32,
                    ((k as u32 / back.width) as f32 + 0.5) / back.height as f32,
                );
                (back.lookup(uv) - sky.lookup(uv)).abs().max_element()
            })
            .fold(0.0f32, f32::max);
        assert!(worst < 0.01, "round-trip error {worst}");
    }

    /// Reliability round two, finding 2: six 4096² faces became a 16384 × 8192 map.
    #[test]
    fn the_latlong_map_of_a_large_cube_stays_within_the_side_limit() {
        assert_eq!(latlong_n(8), 8);
        assert_eq!(latlong_n(2048), 2048);
        assert_eq!(4 * latlong_n(4096), crate::lesson::limits::MAX_ENV_SIDE);
    }

    #[test]
    fn each_axis_reads_its_own_face_through_the_latlong_map() {
        let m = faces(false).to_latlong();
        assert_eq!((m.width, m.height), (32, 16));
        for (k, d) in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].into_iter().enumerate() {
            let want = Vec3::new((k + 1) as f32 / 8.0, 0.0, k as f32 / 16.0);
            let got = m.lookup(direction_to_uv(d));
            assert!((got - want).abs().max_element() < 1e-6, "{} along {d}: {got} against {want}", FACE_NAMES[k]);
        }
    }

    #[test]
    fn faces_are_oriented_as_the_opengl_table() {
        // Green is column + 8·row of the face image; the texel centre (i + ½)/8 is read exactly.
        let c = faces(true);
        let texel = |i: f32, j: f32| i + 8.0 * j;
        let at = |s: f32, t: f32| (s * 8.0 - 0.5, t * 8.0 - 0.5);
        // +x: sc = −z, tc = −y. A direction up and towards +z is at small s (left) and small t (top).
        let (s, t) = (1.5 / 8.0, 2.5 / 8.0);
        let d = Vec3::new(1.0, -(2.0 * t - 1.0), -(2.0 * s - 1.0));
        let (i, j) = at(s, t);
        assert_eq!(CubeFaces::face_st(d).0, 0);
        assert!((c.sample(d).y - texel(i, j)).abs() < 1e-4, "{}", c.sample(d).y);
        // −x: sc = +z; +y: sc = +x, tc = +z; −y: tc = −z; +z: sc = +x; −z: sc = −x.
        // Each face's direction from (sc, tc), inverting its row of the table.
        type Dir = fn(f32, f32) -> Vec3;
        let cases: [(usize, Dir); 5] = [
            (1, |sc, tc| Vec3::new(-1.0, -tc, sc)),
            (2, |sc, tc| Vec3::new(sc, 1.0, tc)),
            (3, |sc, tc| Vec3::new(sc, -1.0, -tc)),
            (4, |sc, tc| Vec3::new(sc, -tc, 1.0)),
            (5, |sc, tc| Vec3::new(-sc, -tc, -1.0)),
        ];
        for (face, dir) in cases {
            for (s, t) in [(0.5 / 8.0, 6.5 / 8.0), (5.5 / 8.0, 1.5 / 8.0), (3.5 / 8.0, 3.5 / 8.0)] {
                let d = dir(2.0 * s - 1.0, 2.0 * t - 1.0);
                let (i, j) = at(s, t);
                assert_eq!(CubeFaces::face_st(d), (face, s, t), "{d}");
                assert!((c.sample(d).y - texel(i, j)).abs() < 1e-4, "{} at {d}: {}", FACE_NAMES[face], c.sample(d).y);
            }
        }
        // Concretely: straight up reads the +y face's centre; the +x face's top row is towards +y.
        let near = |(f, s, t): (usize, f32, f32), want: (usize, f32, f32)| f == want.0 && (s - want.1).abs() + (t - want.2).abs() < 1e-6;
        assert!(near(CubeFaces::face_st(Vec3::new(1.0, 0.9, 0.0)), (0, 0.5, 0.05)));
        assert!(near(CubeFaces::face_st(Vec3::new(0.0, 1.0, 0.9)), (2, 0.5, 0.95)));
        assert!(near(CubeFaces::face_st(Vec3::new(0.0, -0.9, -1.0)), (5, 0.5, 0.95)));
    }

    #[test]
    fn a_cross_cut_into_faces_gives_the_same_map_bit_for_bit() {
        let c = faces(true);
        let n = 8u32;
        let mut cross = vec![Vec3::splat(-1.0); (4 * n * 3 * n) as usize];
        for (k, (cx, cy)) in CROSS_CELLS.into_iter().enumerate() {
            for y in 0..n {
                for x in 0..n {
                    cross[((cy * n + y) * 4 * n + cx * n + x) as usize] = c.faces[k][(y * n + x) as usize];
                }
            }
        }
        let cut = CubeFaces::from_cross(4 * n, 3 * n, &cross).expect("a cross");
        assert_eq!(cut, c);
        assert_eq!(cut.to_latlong(), c.to_latlong());
        assert!(CubeFaces::from_cross(32, 25, &cross).is_err() && CubeFaces::from_cross(30, 24, &cross).is_err());
    }

    #[test]
    fn unequal_or_missing_faces_are_errors_naming_the_face() {
        let face = |n: u32, m: u32| (n, m, vec![Vec3::ONE; (n * m) as usize]);
        let mut six: Vec<_> = (0..6).map(|_| face(4, 4)).collect();
        assert!(CubeFaces::from_images(six.clone()).is_ok());
        six[3] = face(8, 8);
        assert_eq!(CubeFaces::from_images(six.clone()).unwrap_err().0, 3);
        six[3] = face(4, 2);
        assert_eq!(CubeFaces::from_images(six.clone()).unwrap_err().0, 3);
        six.pop();
        assert!(CubeFaces::from_images(six).unwrap_err().1.message.contains("6 faces, not 5"));
    }

    #[test]
    fn the_edges_between_faces_have_no_gap() {
        // A constant cube resamples to the constant everywhere, edges and corners included.
        let c = CubeFaces { size: 4, faces: std::array::from_fn(|_| vec![Vec3::splat(0.75); 16]) };
        let m = c.to_latlong();
        assert!(m.texels.iter().all(|t| (*t - Vec3::splat(0.75)).abs().max_element() < 1e-6));
    }
}
