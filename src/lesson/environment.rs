//! The validated `[environment]` table: where the distant light comes from and how it is shown.

use glam::Vec3;
use std::path::PathBuf;

/// What the environment's radiance is read from.
#[derive(Debug, Clone, PartialEq)]
pub enum EnvSource {
    /// A latitude-longitude image (Radiance `.hdr`, OpenEXR, or sRGB PNG/JPEG), 2:1.
    LatLong {
        /// The file, resolved against the lesson's folder.
        path: PathBuf,
        /// The path as the lesson wrote it (for messages).
        written: String,
    },
    /// A cube map: six face files in OpenGL order `px, nx, py, ny, pz, nz`.
    CubeFaces {
        /// The files, resolved against the lesson's folder.
        paths: Vec<PathBuf>,
        /// The paths as the lesson wrote them (for messages).
        written: Vec<String>,
    },
    /// A cube map in one horizontal-cross image (4:3).
    CubeCross {
        /// The file, resolved against the lesson's folder.
        path: PathBuf,
        /// The path as the lesson wrote it (for messages).
        written: String,
    },
    /// A mirror ball (sphere map): a square image of a mirrored ball seen along −z.
    MirrorBall {
        /// The file, resolved against the lesson's folder.
        path: PathBuf,
        /// The path as the lesson wrote it (for messages).
        written: String,
    },
    /// A procedural sky: `zenith` straight up blending to `horizon` at the horizon, `ground` below.
    Gradient {
        /// Radiance straight up.
        zenith: Vec3,
        /// Radiance just above the horizon.
        horizon: Vec3,
        /// Radiance from below the horizon.
        ground: Vec3,
    },
}

/// The kinds an `[environment]` may be, with their names in lesson files.
pub const ENV_KINDS: [(&str, EnvKind); 4] =
    [("latlong", EnvKind::LatLong), ("cube", EnvKind::Cube), ("mirror_ball", EnvKind::MirrorBall), ("gradient", EnvKind::Gradient)];

/// An `[environment] kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EnvKind {
    /// A latitude-longitude map file.
    LatLong,
    /// A cube map: six faces or one horizontal cross.
    Cube,
    /// A mirror-ball image (sphere map).
    MirrorBall,
    /// A procedural gradient sky.
    Gradient,
}

impl EnvKind {
    /// The keys this kind reads besides `kind`, `intensity`, `white_balance`, `rotate_deg` and
    /// `background`.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            EnvKind::LatLong | EnvKind::MirrorBall => &["map"],
            EnvKind::Cube => &["faces", "cross"],
            EnvKind::Gradient => &["zenith", "horizon", "ground"],
        }
    }
}

/// A validated `[environment]`.
#[derive(Debug, Clone, PartialEq)]
pub struct EnvironmentSpec {
    /// Where the radiance comes from.
    pub source: EnvSource,
    /// Scale on the radiance.
    pub intensity: f32,
    /// The map's colour that should look neutral (every channel positive): `[1, 1, 1]` leaves
    /// the map as it is.
    pub white_balance: Vec3,
    /// Rotation of the sky about +y, in degrees.
    pub rotate_deg: f32,
    /// Draw the environment behind the objects.
    pub background: bool,
}

impl EnvironmentSpec {
    /// The scale on the map's radiance per channel: `intensity` × Y(w)/w for the white balance
    /// w (Y its Rec. 709 luminance), so a texel of colour w comes out grey at its own
    /// luminance (a von Kries gain in RGB, as a camera's white balance), and `intensity` alone
    /// when w = [1, 1, 1].
    pub fn scale(&self) -> Vec3 {
        let w = self.white_balance;
        if w == Vec3::ONE {
            return Vec3::splat(self.intensity);
        }
        let y = 0.212_671 * w.x + 0.715_160 * w.y + 0.072_169 * w.z;
        Vec3::splat(self.intensity * y) / w
    }
}

/// Why a `w`×`h` image is no latitude-longitude map, or `None` when it is one: 2:1, at
/// least 4×2 texels (one texel a hemisphere cannot be interpolated).
pub fn latlong_shape_error(w: u32, h: u32) -> Option<String> {
    if w != 2 * h {
        Some(format!("{w}×{h} is not a latitude-longitude map (its width must be twice its height)"))
    } else if h < 2 {
        Some(format!("{w}×{h} is too small for a latitude-longitude map (at least 4×2 texels)"))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 42: the white balance turns its own colour grey at its luminance and leaves the
    /// map alone at [1, 1, 1] (the same bits as the intensity alone).
    #[test]
    fn the_white_balance_makes_its_colour_grey_at_its_luminance() {
        let spec = |w: Vec3, intensity: f32| EnvironmentSpec {
            source: EnvSource::Gradient { zenith: Vec3::ONE, horizon: Vec3::ONE, ground: Vec3::ONE },
            intensity,
            white_balance: w,
            rotate_deg: 0.0,
            background: true,
        };
        assert_eq!(spec(Vec3::ONE, 0.7).scale(), Vec3::splat(0.7));
        let w = Vec3::new(1.0, 1.15, 1.30);
        let grey = w * spec(w, 2.0).scale();
        let y = |c: Vec3| 0.212_671 * c.x + 0.715_160 * c.y + 0.072_169 * c.z;
        assert!((grey - Vec3::splat(grey.x)).abs().max_element() < 1e-6, "{grey:?}");
        assert!((y(grey) - 2.0 * y(w)).abs() < 1e-5, "{grey:?}");
    }

    /// Reliability round two, finding 8: a 2 × 1 map was refused as "not twice its height".
    #[test]
    fn a_map_too_small_is_not_called_the_wrong_shape() {
        let e = super::latlong_shape_error(2, 1).unwrap();
        assert!(e.contains("too small") && !e.contains("twice"), "{e}");
        assert!(super::latlong_shape_error(3, 1).unwrap().contains("twice its height"));
        assert_eq!(super::latlong_shape_error(4, 2), None);
    }
}
