//! The three ways an environment image is laid out, and conversion between them
//! (`shadelab envmap`): a latitude-longitude map (2:1), a horizontal cube cross (4:3) and a
//! mirror ball (1:1). Every conversion goes through the lat-long [`EnvMap`] the renderer
//! reads, with the same lookups a lesson's environment uses.

use super::environment::{EnvError, EnvMap};
use glam::Vec3;

/// An environment image's layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// Latitude-longitude (equirectangular), 2N × N.
    LatLong,
    /// A horizontal cube cross, 4N × 3N.
    Cross,
    /// A mirror ball (sphere map), N × N.
    MirrorBall,
}

impl Layout {
    /// Every layout with its name, as `[environment] kind` spells the same thing.
    pub const NAMES: [(&'static str, Layout); 3] =
        [("latlong", Layout::LatLong), ("cross", Layout::Cross), ("mirror_ball", Layout::MirrorBall)];

    /// The name (`latlong`, `cross`, `mirror_ball`).
    pub fn name(self) -> &'static str {
        Layout::NAMES.iter().find(|(_, l)| *l == self).map_or("", |(n, _)| n)
    }

    /// The layout an image of this shape has: 2:1, 4:3 or square.
    pub fn of_shape(width: u32, height: u32) -> Option<Layout> {
        match (width, height) {
            (w, h) if w == 2 * h && h >= 2 => Some(Layout::LatLong),
            (w, h) if w.is_multiple_of(4) && w / 4 * 3 == h && w > 0 => Some(Layout::Cross),
            (w, h) if w == h && w >= 2 => Some(Layout::MirrorBall),
            _ => None,
        }
    }

    /// N of an image of this layout: the lat-long's height, the cross's face, the ball's side.
    pub fn n_of(self, width: u32) -> u32 {
        match self {
            Layout::LatLong => width / 2,
            Layout::Cross => width / 4,
            Layout::MirrorBall => width,
        }
    }

    /// The N that keeps about the detail of an image of `from` with its own N `n`: along the
    /// equator a lat-long map has 2N texels, a cross 4N, a ball about πN/2.
    pub fn matching_n(self, from: Layout, n: u32) -> u32 {
        let equator = match from {
            Layout::LatLong => 2 * n,
            Layout::Cross => 4 * n,
            Layout::MirrorBall => n * 3 / 2,
        };
        match self {
            Layout::LatLong => equator / 2,
            Layout::Cross => equator / 4,
            Layout::MirrorBall => equator * 2 / 3,
        }
        .max(2)
    }
}

/// An image of `layout` as the lat-long map the renderer reads.
///
/// # Errors
/// [`EnvError`] when the image does not have the layout's shape.
pub fn to_latlong(layout: Layout, width: u32, height: u32, texels: Vec<Vec3>) -> Result<EnvMap, EnvError> {
    match layout {
        Layout::LatLong => match crate::lesson::environment::latlong_shape_error(width, height) {
            Some(message) => Err(EnvError { message }),
            None => Ok(EnvMap { width, height, texels }),
        },
        Layout::Cross => Ok(super::cube::CubeFaces::from_cross(width, height, &texels)?.to_latlong()),
        Layout::MirrorBall => super::mirror_ball::to_latlong(width, height, &texels),
    }
}

/// `env` laid out as `layout` with N = `n`: (width, height, texels).
pub fn from_latlong(env: &EnvMap, layout: Layout, n: u32) -> (u32, u32, Vec<Vec3>) {
    match layout {
        Layout::LatLong if (env.width, env.height) == (2 * n, n) => (env.width, env.height, env.texels.clone()),
        Layout::LatLong => {
            // The mean of a 4 × 4 grid of lookups across each texel, as the other layouts.
            let mut texels = Vec::with_capacity((2 * n * n) as usize);
            for y in 0..n {
                for x in 0..2 * n {
                    let mut sum = Vec3::ZERO;
                    for k in 0..16 {
                        let u = (x as f32 + ((k % 4) as f32 + 0.5) / 4.0) / (2 * n) as f32;
                        let v = (y as f32 + ((k / 4) as f32 + 0.5) / 4.0) / n as f32;
                        sum += env.lookup(glam::Vec2::new(u, v));
                    }
                    texels.push(sum / 16.0);
                }
            }
            (2 * n, n, texels)
        }
        Layout::Cross => super::cube::cross_from_latlong(env, n),
        Layout::MirrorBall => (n, n, super::mirror_ball::from_latlong(env, n)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_name_their_layouts_and_detail_is_kept_along_the_equator() {
        assert_eq!(Layout::of_shape(1024, 512), Some(Layout::LatLong));
        assert_eq!(Layout::of_shape(1024, 768), Some(Layout::Cross));
        assert_eq!(Layout::of_shape(512, 512), Some(Layout::MirrorBall));
        assert_eq!(Layout::of_shape(1000, 700), None);
        assert_eq!(Layout::Cross.matching_n(Layout::LatLong, 512), 256);
        assert_eq!(Layout::MirrorBall.matching_n(Layout::LatLong, 512), 682);
        assert_eq!(Layout::LatLong.matching_n(Layout::Cross, 256), 512);
    }

    /// ∫ L dω over a lat-long map (red channel): each texel times its solid angle.
    fn power(m: &EnvMap) -> f64 {
        let (w, h) = (m.width as f64, m.height as f64);
        (0..m.texels.len())
            .map(|k| {
                let y = (k as u32 / m.width) as f64;
                let band = (std::f64::consts::PI * y / h).cos() - (std::f64::consts::PI * (y + 1.0) / h).cos();
                m.texels[k].x as f64 * band * 2.0 * std::f64::consts::PI / w
            })
            .sum()
    }

    #[test]
    fn a_small_sun_keeps_its_power_in_every_coarser_layout() {
        // A 4 × 4-texel sun of radiance 1000 in a 256 × 128 map, 30° above the horizon ahead.
        let mut sky = EnvMap::from_fn(256, 128, |_| Vec3::splat(0.5));
        for (x, y) in (0..16).map(|k| (126 + k % 4, 40 + k / 4)) {
            sky.texels[(y * 256 + x) as usize] = Vec3::splat(1000.0);
        }
        let want = power(&sky);
        for (layout, n) in [(Layout::LatLong, 32), (Layout::Cross, 16), (Layout::MirrorBall, 64)] {
            let (w, h, texels) = from_latlong(&sky, layout, n);
            let got = power(&to_latlong(layout, w, h, texels).unwrap());
            assert!((got / want - 1.0).abs() < 0.02, "{}: power {got:.2} against {want:.2}", layout.name());
        }
    }

    #[test]
    fn every_layout_round_trips_a_smooth_sky() {
        let sky = EnvMap::from_fn(128, 64, |d| Vec3::new(1.0 + d.x, 1.0 + d.y, 1.0 + 0.5 * d.z));
        for layout in [Layout::LatLong, Layout::Cross, Layout::MirrorBall] {
            let (w, h, texels) = from_latlong(&sky, layout, if layout == Layout::MirrorBall { 256 } else { 64 });
            assert_eq!(Layout::of_shape(w, h), Some(layout));
            let back = to_latlong(layout, w, h, texels).unwrap();
            // Away from straight behind (the ball's rim), every direction reads the sky back.
            let d = Vec3::new(0.3, 0.5, 0.81).normalize();
            let uv = super::super::environment::direction_to_uv(d);
            let err = (back.lookup(uv) - sky.lookup(uv)).abs().max_element();
            assert!(err < 0.01, "{}: {err}", layout.name());
        }
    }
}
