//! `[environment]`: the map file (or the gradient sky), its intensity, white balance, rotation
//! and background.

use super::{R, Validator};
use crate::lesson::environment::{ENV_KINDS, EnvKind, EnvSource, EnvironmentSpec};
use crate::lesson::limits::{MAX_ENV_SIDE, MAX_ENV_TEXELS};
use crate::lesson::path::KeyPath;
use crate::lesson::raw::RawEnvironment;
use crate::lesson::spans::Target;
use glam::Vec3;
use std::path::Path;

impl Validator<'_> {
    pub(super) fn environment(&self, p: &KeyPath, e: &RawEnvironment) -> R<EnvironmentSpec> {
        let kind = match &e.kind {
            Some(k) => self.choice(&p.key("kind"), k, &ENV_KINDS)?,
            None => EnvKind::LatLong,
        };
        let name = ENV_KINDS.iter().find(|(_, k)| *k == kind).map_or("", |(n, _)| n);
        let why = format!("by `kind = \"{name}\"` (it reads: {})", kind.keys().join(", "));
        for (key, set) in [
            ("map", e.map.is_some()),
            ("faces", e.faces.is_some()),
            ("cross", e.cross.is_some()),
            ("zenith", e.zenith.is_some()),
            ("horizon", e.horizon.is_some()),
            ("ground", e.ground.is_some()),
        ] {
            if set && !kind.keys().contains(&key) {
                self.unused(p, key, &Some(()), &why)?;
            }
        }
        let source = match kind {
            EnvKind::LatLong => {
                let Some(written) = &e.map else {
                    return Err(self.err(
                        &p.key("map"),
                        Target::Key,
                        "a `latlong` environment needs `map`",
                        Some(
                            "add `map = \"hdri/studio_small_03_1k.hdr\"` (relative to the lesson file), or use kind = \"gradient\"".into(),
                        ),
                    ));
                };
                let path = self.asset_path(&p.key("map"), written)?;
                let (w, h) = self.map_header(&p.key("map"), written, &path, "latitude-longitude map")?;
                if let Some(what) = crate::lesson::environment::latlong_shape_error(w, h) {
                    return Err(self.err(
                        &p.key("map"),
                        Target::Value,
                        format!("{written}: {what}"),
                        Some("give an equirectangular map, 2:1 (e.g. 1024×512)".into()),
                    ));
                }
                EnvSource::LatLong { path, written: written.clone() }
            }
            EnvKind::Cube => self.cube(p, e)?,
            EnvKind::MirrorBall => {
                let Some(written) = &e.map else {
                    return Err(self.err(
                        &p.key("map"),
                        Target::Key,
                        "a `mirror_ball` environment needs `map`",
                        Some(
                            "add `map = \"hdri/ball.hdr\"`: a square image of a mirrored ball, rim to rim (`shadelab envmap` makes one)"
                                .into(),
                        ),
                    ));
                };
                let path = self.asset_path(&p.key("map"), written)?;
                let (w, h) = self.map_header(&p.key("map"), written, &path, "mirror-ball image")?;
                if w != h {
                    return Err(self.err(
                        &p.key("map"),
                        Target::Value,
                        format!("{written}: {w}×{h} is not a mirror ball"),
                        Some("give a square image of the ball, cropped rim to rim (e.g. 512×512)".into()),
                    ));
                }
                EnvSource::MirrorBall { path, written: written.clone() }
            }
            EnvKind::Gradient => {
                let c = |key: &str, v: &Option<crate::lesson::raw::RawColor>, d: Vec3| -> R<Vec3> {
                    v.as_ref().map_or(Ok(d), |c| self.color(&p.key(key), c, 0.0, 1e6))
                };
                EnvSource::Gradient {
                    zenith: c("zenith", &e.zenith, Vec3::new(0.25, 0.45, 0.9))?,
                    horizon: c("horizon", &e.horizon, Vec3::new(0.9, 0.9, 0.95))?,
                    ground: c("ground", &e.ground, Vec3::splat(0.2))?,
                }
            }
        };
        Ok(EnvironmentSpec {
            source,
            intensity: e.intensity.map_or(Ok(1.0), |v| self.number(&p.key("intensity"), v, 0.0, 1e6))?,
            white_balance: e.white_balance.as_ref().map_or(Ok(Vec3::ONE), |c| self.triple(&p.key("white_balance"), c, 1e-3, 1e3))?,
            rotate_deg: e.rotate_deg.map_or(Ok(0.0), |v| self.number(&p.key("rotate_deg"), v, -1e5, 1e5))?,
            background: e.background.unwrap_or(true),
        })
    }

    /// `kind = "cube"`: exactly one of `faces` (six square files of one size) and `cross` (a 4:3 image).
    fn cube(&self, p: &KeyPath, e: &RawEnvironment) -> R<EnvSource> {
        let hint = "give `faces = [\"px.png\", \"nx.png\", \"py.png\", \"ny.png\", \"pz.png\", \"nz.png\"]` or `cross = \"cross.hdr\"`";
        match (&e.faces, &e.cross) {
            (Some(_), Some(_)) => Err(self.err(
                &p.key("cross"),
                Target::Key,
                "a `cube` environment reads `faces` or `cross`, not both",
                Some("keep one of them".into()),
            )),
            (None, None) => Err(self.err(&p.key("faces"), Target::Key, "a `cube` environment needs `faces` or `cross`", Some(hint.into()))),
            (Some(faces), None) => {
                if faces.len() != 6 {
                    return Err(self.err(
                        &p.key("faces"),
                        Target::Value,
                        format!("a cube map has 6 faces, not {}", faces.len()),
                        Some("list them in OpenGL order: px, nx, py, ny, pz, nz (+x, −x, +y, −y, +z, −z)".into()),
                    ));
                }
                let mut paths = Vec::with_capacity(6);
                let mut first: Option<(u32, &str)> = None;
                for (k, written) in faces.iter().enumerate() {
                    let key = p.key("faces").index(k);
                    let path = self.asset_path(&key, written)?;
                    let (w, h) = self.map_header(&key, written, &path, "square cube face")?;
                    let bad = |message: String| {
                        self.err(
                            &key,
                            Target::Value,
                            format!("{written}: {message}"),
                            Some("the six faces are square images of one size".into()),
                        )
                    };
                    if w != h {
                        return Err(bad(format!("{w}×{h} is not a square cube face")));
                    }
                    match first {
                        Some((n, name)) if n != w => {
                            return Err(bad(format!("{w}×{h} is not the size of the first face ({name}, {n}×{n})")));
                        }
                        None => first = Some((w, written)),
                        _ => {}
                    }
                    paths.push(path);
                }
                Ok(EnvSource::CubeFaces { paths, written: faces.clone() })
            }
            (None, Some(written)) => {
                let key = p.key("cross");
                let path = self.asset_path(&key, written)?;
                let (w, h) = self.map_header(&key, written, &path, "horizontal cross")?;
                if !w.is_multiple_of(4) || w / 4 * 3 != h || w == 0 {
                    return Err(self.err(
                        &key,
                        Target::Value,
                        format!("{written}: {w}×{h} is not a horizontal cross (4:3, its width a multiple of 4)"),
                        Some("a 4N × 3N image: +y above, −y below, the middle row −x, +z, +x, −z".into()),
                    ));
                }
                Ok(EnvSource::CubeCross { path, written: written.clone() })
            }
        }
    }

    /// Reads only the header of a map file (`what` it should be): it must be an image the
    /// decoders know, within the size limits; its (width, height). The pixels are decoded when
    /// the scene is built.
    fn map_header(&self, key: &KeyPath, written: &str, path: &Path, what: &str) -> R<(u32, u32)> {
        let formats = format!("give a Radiance .hdr, OpenEXR .exr, PNG or JPEG {what}");
        let bad = |message: String, hint: &str| self.err(key, Target::Value, format!("{written}: {message}"), Some(hint.to_string()));
        let reader =
            crate::files::image_reader(path).map_err(|e| bad(format!("cannot read the map: {e}"), "check the file can be read"))?;
        if reader.format().is_none() {
            return Err(bad("not an image file shadelab can decode".into(), &formats));
        }
        let (w, h) = reader.into_dimensions().map_err(|e| bad(format!("not a readable image ({e})"), &formats))?;
        if w > MAX_ENV_SIDE || h > MAX_ENV_SIDE || w as u64 * h as u64 > MAX_ENV_TEXELS {
            return Err(bad(
                format!("{w}×{h} texels is more than the limit ({MAX_ENV_SIDE} a side, {MAX_ENV_TEXELS} in all)"),
                "downsample the map (an 8K map is plenty for any figure)",
            ));
        }
        Ok((w, h))
    }
}
