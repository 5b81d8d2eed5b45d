//! Three-point lighting for any scene: key, fill and back lights placed from its camera
//! (`shadelab new --template three-point`, the lecture's homework on an imported scene).
//!
//! The subject is the camera's `look_at`, at distance d from the eye. The key stands 45° to
//! the camera's left and 40° above the subject, the fill 60° to the right near eye height,
//! the back light behind the subject opposite the camera and 55° up, each at 1.2 d.
//! Physically based lights fall off as 1/r², so their intensities I = E r² give the subject
//! the irradiance E: 3 (key), 0.75 (fill, a quarter) and 4 (back, a rim brighter than the
//! key, as photographers set it); classic lights do not fall off and get 1, 0.25 and 1.3.

use std::fmt::Write as _;

use glam::Vec3;

use crate::geometry::Camera;

/// One light of the setup: its role, where it is and its intensity.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// `key`, `fill` or `back`.
    pub role: &'static str,
    /// Where the point light stands.
    pub position: Vec3,
    /// Its `intensity`.
    pub intensity: f32,
    /// Its colour (a warm key, a cool fill, a white back light).
    pub color: Vec3,
}

/// The three lights for `camera`; `physical` when the scene's materials are physically based.
pub fn place(camera: &Camera, physical: bool) -> [Placed; 3] {
    let subject = camera.look_at;
    let to_eye = camera.position - subject;
    let d = to_eye.length().max(1e-3);
    let up = camera.up.normalize_or(Vec3::Y);
    // The camera's horizontal frame about the subject: `back` away from the eye, `right` to its right.
    let flat = (to_eye - up * to_eye.dot(up)).normalize_or(Vec3::Z);
    let right = up.cross(flat).normalize_or(Vec3::X);
    let at = |azimuth_deg: f32, elevation_deg: f32| {
        let (a, e) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        let horizontal = flat * a.cos() + right * a.sin();
        subject + (horizontal * e.cos() + up * e.sin()) * 1.2 * d
    };
    let r2 = (1.2 * d) * (1.2 * d);
    let (key, fill, back) = if physical { (3.0 * r2, 0.75 * r2, 4.0 * r2) } else { (1.0, 0.25, 1.3) };
    [
        Placed { role: "key", position: at(-45.0, 40.0), intensity: key, color: Vec3::new(1.0, 0.93, 0.85) },
        Placed { role: "fill", position: at(60.0, 10.0), intensity: fill, color: Vec3::new(0.85, 0.9, 1.0) },
        Placed { role: "back", position: at(160.0, 55.0), intensity: back, color: Vec3::ONE },
    ]
}

fn num(x: f32) -> String {
    let s = format!("{}", (x as f64 * 1e4).round() / 1e4);
    if s.contains('.') { s } else { format!("{s}.0") }
}

fn vec3(v: Vec3) -> String {
    format!("[{}, {}, {}]", num(v.x), num(v.y), num(v.z))
}

/// The `[[light]]` tables of `lights`, commented with their roles, and a `build-up` figure
/// that adds them one by one.
pub fn text(lights: &[Placed; 3], physical: bool) -> String {
    let mut t = String::new();
    let unit = if physical { "W/sr: E = I/r² at the subject" } else { "classic: no falloff" };
    let why = [
        "the main light, above and to the left of the camera: it gives the shape and the highlight",
        "weaker, from the right near eye height: it lifts the shadow side without a second highlight",
        "behind the subject and above: a bright rim along its outline separates it from the background",
    ];
    for (l, why) in lights.iter().zip(why) {
        let _ = writeln!(t, "[[light]]                      # {}: {why}", l.role);
        let _ = writeln!(t, "kind = \"point\"");
        let _ = writeln!(t, "position = {}", vec3(l.position));
        let _ = writeln!(t, "color = {}", vec3(l.color));
        let _ = writeln!(t, "intensity = {}          # {unit}", num(l.intensity));
        t.push('\n');
    }
    let table = |l: &Placed| {
        format!("{{ kind = \"point\", position = {}, color = {}, intensity = {} }}", vec3(l.position), vec3(l.color), num(l.intensity))
    };
    let _ = writeln!(t, "[[figure]]");
    let _ = writeln!(t, "name = \"build-up\"");
    let _ = writeln!(t, "kind = \"compare\"");
    let _ = writeln!(t, "title = \"Three-point lighting, light by light\"");
    let _ = writeln!(t, "vary = \"light\"");
    let _ = writeln!(t, "values = [");
    for n in 1..=3 {
        let _ = writeln!(t, "    [{}],", lights[..n].iter().map(table).collect::<Vec<_>>().join(", "));
    }
    let _ = writeln!(t, "]");
    let _ = writeln!(t, "labels = [\"key\", \"key + fill\", \"key + fill + back\"]");
    let _ = writeln!(
        t,
        "caption = \"The key alone gives the shape and leaves the far side dark; the fill opens the shadow side; the back light draws the rim that separates the subject from the background.\""
    );
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            position: Vec3::new(0.0, 1.0, 5.0),
            look_at: Vec3::new(0.0, 1.0, 0.0),
            up: Vec3::Y,
            fov_y_deg: 40.0,
            width: 64,
            height: 64,
            near: 0.05,
            background: Vec3::ZERO,
        }
    }

    #[test]
    fn the_roles_stand_where_photographers_put_them() {
        let [key, fill, back] = place(&camera(), true);
        // Key: camera side (+z), to the left (−x), above.
        assert!(key.position.z > 1.0 && key.position.x < -1.0 && key.position.y > 2.0, "{key:?}");
        // Fill: camera side, to the right, near eye height.
        assert!(fill.position.z > 0.0 && fill.position.x > 1.0 && (fill.position.y - 1.0).abs() < 1.5, "{fill:?}");
        // Back: behind the subject (−z), above.
        assert!(back.position.z < -1.0 && back.position.y > 3.0, "{back:?}");
        // Each at 1.2 d = 6 from the subject; E at the subject = I / r².
        for (l, e) in [(&key, 3.0), (&fill, 0.75), (&back, 4.0)] {
            let r = (l.position - Vec3::new(0.0, 1.0, 0.0)).length();
            assert!((r - 6.0).abs() < 1e-4);
            assert!((l.intensity / (r * r) - e).abs() < 1e-4);
        }
        assert!(text(&place(&camera(), false), false).contains("intensity = 1.0"));
    }
}
