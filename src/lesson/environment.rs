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
pub const ENV_KINDS: [(&str, EnvKind); 3] = [("latlong", EnvKind::LatLong), ("cube", EnvKind::Cube), ("gradient", EnvKind::Gradient)];

/// An `[environment] kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EnvKind {
    /// A latitude-longitude map file.
    LatLong,
    /// A cube map: six faces or one horizontal cross.
    Cube,
    /// A procedural gradient sky.
    Gradient,
}

impl EnvKind {
    /// The keys this kind reads besides `kind`, `intensity`, `rotate_deg` and `background`.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            EnvKind::LatLong => &["map"],
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
    /// Rotation of the sky about +y, in degrees.
    pub rotate_deg: f32,
    /// Draw the environment behind the objects.
    pub background: bool,
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
    /// Reliability round two, finding 8: a 2 × 1 map was refused as "not twice its height".
    #[test]
    fn a_map_too_small_is_not_called_the_wrong_shape() {
        let e = super::latlong_shape_error(2, 1).unwrap();
        assert!(e.contains("too small") && !e.contains("twice"), "{e}");
        assert!(super::latlong_shape_error(3, 1).unwrap().contains("twice its height"));
        assert_eq!(super::latlong_shape_error(4, 2), None);
    }
}
