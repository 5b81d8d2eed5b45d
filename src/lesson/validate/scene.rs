//! The scene sections: `[camera]`, `[[object]]`, `[[light]]` and `[render]`.

use super::hints::suggest;
use super::{MAX_AA, MAX_LIGHT_SAMPLES, MAX_PIXELS, MAX_SHADOW_MAP, MAX_SIDE, R, Validator};
use crate::geometry::Camera;
use crate::geometry::sampler::Sampler;
use crate::lesson::ObjectSpec;
use crate::lesson::error::LessonError;
use crate::lesson::kinds::{LightSampling, ShadowMethod};
use crate::lesson::kinds::{LightType, ShapeKind, choices};
use crate::lesson::light::LightSpec;
use crate::lesson::limits::MAX_OBJ_BYTES;
use crate::lesson::limits::MAX_PROFILE_POINTS;
use crate::lesson::limits::{
    MAX_BOUNCES, MAX_DEPTH, MAX_ENV_SAMPLES, MAX_GATHER_RAYS, MAX_HEMICUBE, MAX_ITERATIONS, MAX_PHOTON_NEAREST, MAX_PHOTONS,
    MAX_PREFILTER_SIZE, MAX_SPP,
};
use crate::lesson::path::KeyPath;
use crate::lesson::raw::{RawCamera, RawLight, RawObject, RawRender};
use crate::lesson::settings::{
    Caustics, FormFactorMethod, Indirect, PathSettings, PhotonGather, RadiosityDisplay, RadiositySettings, RenderMethod, Solver,
};
use crate::lesson::settings::{Ibl, Reflections, ShadowMapSettings, TextureFilter};
use crate::lesson::shape::{MeshPart, NodeRef};
use crate::lesson::spans::Target;
use crate::lesson::{Cull, Interpolation, InterpolationSpace, NormalTransform, NormalWeighting, RenderSettings, Shape, Tonemap};
use crate::shading::material::Material;
use glam::{Affine3A, EulerRot, Quat, Vec3};

impl Validator<'_> {
    pub(super) fn camera(&self, p: &KeyPath, c: &RawCamera) -> R<Camera> {
        let position = self.vec3(&p.key("position"), c.position, -1e6, 1e6)?;
        let look_at = match c.look_at {
            Some(v) => self.vec3(&p.key("look_at"), v, -1e6, 1e6)?,
            None => Vec3::ZERO,
        };
        let up = match c.up {
            Some(v) => self.vec3(&p.key("up"), v, -1e6, 1e6)?,
            None => Vec3::Y,
        };
        let forward = look_at - position;
        if forward.length() < 1e-6 {
            // Name the key the user wrote; an absent `look_at` is the origin.
            let (key, hint) = match c.look_at {
                Some(_) => ("look_at", "move `camera.position` away from `camera.look_at`"),
                None => ("position", "`camera.look_at` defaults to [0, 0, 0]: move `camera.position` or set `look_at`"),
            };
            return Err(self.err(&p.key(key), Target::Value, "the camera looks at its own position", Some(hint.into())));
        }
        if up.length() < 1e-6 {
            return Err(self.err(&p.key("up"), Target::Value, "`up` cannot be [0, 0, 0]", Some("use e.g. [0, 1, 0]".into())));
        }
        if forward.normalize().cross(up.normalize()).length() < 1e-4 {
            let default = if c.up.is_none() { "`up` defaults to [0, 1, 0]; " } else { "" };
            return Err(self.err(
                &p.key("up"),
                Target::Value,
                "`up` is parallel to the view direction (look_at − position)",
                Some(format!("{default}choose an `up` across the view direction, e.g. [0, 0, -1] when looking straight down")),
            ));
        }
        let fov_y_deg = match c.fov_deg {
            Some(v) => self.number(&p.key("fov_deg"), v, 1.0, 179.0)?,
            None => 40.0,
        };
        let (width, height) = match c.size {
            Some([w, h]) => {
                let sp = p.key("size");
                let side = |i: usize, v: i64, name: &str| {
                    self.integer(&sp.index(i), v, 1, MAX_SIDE).map_err(|e| LessonError {
                        key: Some(sp.to_string()),
                        message: format!("{name}: {}", e.message),
                        ..e
                    })
                };
                let (w, h) = (side(0, w, "width")?, side(1, h, "height")?);
                if w as i64 * h as i64 > MAX_PIXELS {
                    return Err(self.err(&sp, Target::Value, format!("{w}×{h} is more than {MAX_PIXELS} pixels"), None));
                }
                (w, h)
            }
            None => (512, 512),
        };
        let near = match c.near {
            Some(v) => self.number(&p.key("near"), v, 1e-4, 1e4)?,
            None => 0.05,
        };
        let background = match &c.background {
            Some(b) => self.color(&p.key("background"), b, 0.0, 1e6)?,
            None => Vec3::ZERO,
        };
        Ok(Camera { position, look_at, up, fov_y_deg, width, height, near, background })
    }

    pub(super) fn object(&self, p: &KeyPath, o: &RawObject, materials: &[Material]) -> R<ObjectSpec> {
        let kind = self.choice(&p.key("shape"), &o.shape, &choices(ShapeKind::ALL, ShapeKind::name))?;
        let int = |key: &str, v: Option<i64>, default: i64, lo: i64, hi: i64| -> R<u32> {
            self.integer(&p.key(key), v.unwrap_or(default), lo, hi)
        };
        let why = format!("by shape `{}`", kind.name());
        let shape = match kind {
            ShapeKind::UvSphere => {
                Shape::UvSphere { segments: int("segments", o.segments, 32, 3, 2048)?, rings: int("rings", o.rings, 16, 2, 1024)? }
            }
            ShapeKind::Icosphere => Shape::Icosphere { subdivisions: int("subdivisions", o.subdivisions, 3, 0, 9)? },
            ShapeKind::Plane => Shape::Plane,
            ShapeKind::Cube => Shape::Cube,
            ShapeKind::Torus => {
                let major_radius = self.number(&p.key("major_radius"), o.major_radius.unwrap_or(1.0), 1e-4, 1e4)?;
                let minor_radius = self.number(&p.key("minor_radius"), o.minor_radius.unwrap_or(0.35), 1e-4, 1e4)?;
                Shape::Torus {
                    major_radius,
                    minor_radius,
                    segments: int("segments", o.segments, 48, 3, 2048)?,
                    sides: int("sides", o.sides, 24, 3, 2048)?,
                }
            }
            ShapeKind::Mesh => {
                let Some(rel) = &o.path else {
                    return Err(self.err(
                        &p.key("path"),
                        Target::Key,
                        "shape `mesh` needs `path`",
                        Some("add `path = \"model.obj\"` (relative to the lesson file)".into()),
                    ));
                };
                let full = self.asset_path(&p.key("path"), rel)?;
                // The size first: the file is read whole.
                let bytes = crate::files::metadata(&full).map(|m| m.len).unwrap_or(0);
                if bytes > MAX_OBJ_BYTES {
                    return Err(self.err(
                        &p.key("path"),
                        Target::Value,
                        format!("{rel}: {bytes} bytes, more than the limit of {MAX_OBJ_BYTES} bytes for an OBJ file"),
                        Some("simplify the mesh (e.g. decimate it) or split it into several objects".into()),
                    ));
                }
                let part = self.mesh_part(p, o, &full)?;
                Shape::Mesh { path: full, part }
            }
        };
        for (key, set) in [
            ("segments", o.segments.is_some()),
            ("rings", o.rings.is_some()),
            ("subdivisions", o.subdivisions.is_some()),
            ("sides", o.sides.is_some()),
            ("major_radius", o.major_radius.is_some()),
            ("minor_radius", o.minor_radius.is_some()),
            ("path", o.path.is_some()),
            ("node", o.node.is_some()),
            ("primitive", o.primitive.is_some()),
        ] {
            if set && !kind.keys().contains(&key) {
                self.unused(p, key, &Some(()), &why)?;
            }
        }
        let material = materials.iter().position(|m| m.name == o.material).ok_or_else(|| {
            let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
            let hint = match suggest(&o.material, &names) {
                Some(s) => format!("did you mean `{s}`? Defined: {}", names.join(", ")),
                None if names.is_empty() => format!("define it with a [material.{}] table", o.material),
                None => format!("defined materials: {}", names.join(", ")),
            };
            self.err(&p.key("material"), Target::Value, format!("no material named `{}`", o.material), Some(hint))
        })?;
        let translate = o.translate.map_or(Ok(Vec3::ZERO), |v| self.vec3(&p.key("translate"), v, -1e6, 1e6))?;
        let rot = o.rotate_deg.map_or(Ok(Vec3::ZERO), |v| self.vec3(&p.key("rotate_deg"), v, -1e5, 1e5))?;
        let scale = match &o.scale {
            Some(s) => self.triple(&p.key("scale"), s, 1e-6, 1e6).map_err(|mut e| {
                e.hint = Some("scale must be positive; mirror an object with rotate_deg instead".into());
                e
            })?,
            None => Vec3::ONE,
        };
        // Rotate about x, then y, then z: R = Rz·Ry·Rx.
        let rotation = Quat::from_euler(EulerRot::ZYX, rot.z.to_radians(), rot.y.to_radians(), rot.x.to_radians());
        let transform = Affine3A::from_scale_rotation_translation(scale, rotation, translate);
        let crease_deg = o.crease_deg.map(|d| self.number(&p.key("crease_deg"), d, 0.0, 180.0)).transpose()?;
        Ok(ObjectSpec { shape, transform, material, crease_deg })
    }

    /// `node` and `primitive`: which meshes of a glTF file; refused for an OBJ file.
    fn mesh_part(&self, p: &KeyPath, o: &RawObject, file: &std::path::Path) -> R<MeshPart> {
        let gltf =
            file.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("glb") || e.eq_ignore_ascii_case("gltf"));
        if !gltf {
            self.unused(p, "node", &o.node, "by an OBJ mesh (only glTF files have nodes)")?;
            self.unused(p, "primitive", &o.primitive, "by an OBJ mesh (only glTF files have primitives)")?;
            return Ok(MeshPart::default());
        }
        let node = match &o.node {
            None => None,
            Some(toml::Value::String(name)) => Some(NodeRef::Name(name.clone())),
            Some(toml::Value::Integer(i)) => Some(NodeRef::Index(self.integer(&p.key("node"), *i, 0, u32::MAX as i64)?)),
            Some(_) => {
                return Err(self.err(
                    &p.key("node"),
                    Target::Value,
                    "`node` is a node's name or index",
                    Some("e.g. `node = \"Suzanne\"` or `node = 3`".into()),
                ));
            }
        };
        if o.primitive.is_some() && node.is_none() {
            return Err(self.err(
                &p.key("primitive"),
                Target::Key,
                "`primitive` needs `node`",
                Some("name the node whose mesh's primitive you mean, e.g. `node = \"Suzanne\"`".into()),
            ));
        }
        let primitive = o.primitive.map(|i| self.integer(&p.key("primitive"), i, 0, 65_535)).transpose()?;
        Ok(MeshPart { node, primitive })
    }

    pub(super) fn light(&self, p: &KeyPath, l: &RawLight) -> R<LightSpec> {
        use LightType as K;
        let kind = self.choice(&p.key("kind"), &l.kind, &choices(LightType::ALL, LightType::name))?;
        let color = l.color.as_ref().map_or(Ok(Vec3::ONE), |c| self.color(&p.key("color"), c, 0.0, 1e6))?;
        let intensity = l.intensity.map_or(Ok(1.0), |v| self.number(&p.key("intensity"), v, 0.0, 1e9))?;
        let radiance = color * intensity;
        let name = l.kind.as_str();
        let article = if matches!(kind, K::Ambient) { "an" } else { "a" };
        let why = format!("by {article} `{name}` light");
        let need = |key: &str, v: Option<[f64; 3]>| -> R<[f64; 3]> {
            v.ok_or_else(|| {
                self.err(&p.key(key), Target::Key, format!("a `{name}` light needs `{key}`"), Some(format!("add `{key} = [x, y, z]`")))
            })
        };
        if kind == K::Ambient {
            self.unused(p, "ambient", &l.ambient, "by an `ambient` light (its colour is its ambient part)")?;
        }
        // Keys the kind does not read are errors (parameters nobody reads are reported).
        for (key, set) in [
            ("position", l.position.is_some()),
            ("direction", l.direction.is_some()),
            ("attenuation", l.attenuation.is_some()),
            ("exponent", l.exponent.is_some()),
            ("cutoff_deg", l.cutoff_deg.is_some()),
            ("profile", l.profile.is_some()),
            ("ambient", l.ambient.is_some()),
            ("specular", l.specular.is_some()),
            ("size", l.size.is_some()),
            ("up", l.up.is_some()),
            ("radius", l.radius.is_some()),
            ("start", l.start.is_some()),
            ("end", l.end.is_some()),
            ("ground_color", l.ground_color.is_some()),
            ("samples", l.samples.is_some()),
            ("shadows", l.shadows.is_some()),
            ("sampling", l.sampling.is_some()),
        ] {
            if set && !kind.keys().contains(&key) {
                self.unused(p, key, &Some(()), &why)?;
            }
        }
        let attenuation = match l.attenuation {
            Some(a) => {
                let a = self.vec3(&p.key("attenuation"), a, 0.0, 1e6)?;
                if a == Vec3::ZERO {
                    return Err(self.err(
                        &p.key("attenuation"),
                        Target::Value,
                        "[0, 0, 0] divides by zero",
                        Some("use [1, 0, 0] for no attenuation, [0, 1, 0] for 1/r, [0, 0, 1] for 1/r²".into()),
                    ));
                }
                a
            }
            None => Vec3::X,
        };
        let ambient = match (kind, &l.ambient) {
            (K::Ambient, _) => radiance,
            (_, Some(c)) => self.color(&p.key("ambient"), c, 0.0, 1e6)?,
            (_, None) => Vec3::ZERO,
        };
        let position = || self.vec3(&p.key("position"), need("position", l.position)?, -1e6, 1e6);
        let direction = || self.direction(&p.key("direction"), need("direction", l.direction)?);
        // A light of zero size emits nothing and divides by its area: an error, not a point.
        let radius = || -> R<f32> {
            let Some(r) = l.radius else {
                return Err(self.err(
                    &p.key("radius"),
                    Target::Key,
                    format!("a `{name}` light needs `radius`"),
                    Some("add `radius = 0.25` (world units)".into()),
                ));
            };
            self.number(&p.key("radius"), r, 1e-6, 1e6).map_err(|e| LessonError {
                hint: Some("a light needs a size above 0; for a point of light use kind = \"point\"".into()),
                ..e
            })
        };
        let mut out = LightSpec::new(kind, radiance);
        if let Some(s) = &l.sampling {
            out.sampling = self.choice(&p.key("sampling"), s, &LightSampling::NAMES)?;
        }
        match kind {
            K::Directional => out.direction = direction()?,
            K::Point => out.position = position()?,
            K::Spot => {
                (out.position, out.direction) = (position()?, direction()?);
                out.exponent = l.exponent.map_or(Ok(1.0), |v| self.number(&p.key("exponent"), v, 0.0, 1e6))?;
                if let Some(v) = l.cutoff_deg {
                    out.cos_cutoff = self.number(&p.key("cutoff_deg"), v, 0.0, 180.0)?.to_radians().cos();
                }
                if let Some(points) = &l.profile {
                    out.profile = Some(self.spot_profile(p, points, l.exponent.is_some())?);
                }
            }
            K::Ambient => {}
            K::Rect => {
                let (position, direction) = (position()?, direction()?);
                let sp = p.key("size");
                let Some([w, h]) = l.size else {
                    return Err(self.err(
                        &sp,
                        Target::Key,
                        "a `rect` light needs `size`",
                        Some("add `size = [1, 1]` (width, height in world units)".into()),
                    ));
                };
                let side = |i: usize, v: f64| {
                    self.number(&sp.index(i), v, 1e-6, 1e6).map_err(|e| LessonError {
                        key: Some(sp.to_string()),
                        message: format!("{}: {}", ["width", "height"][i], e.message),
                        hint: Some("a light needs a size above 0 on both sides; for a point of light use kind = \"point\"".into()),
                        ..e
                    })
                };
                let (w, h) = (side(0, w)?, side(1, h)?);
                // The default `up` is +y, or −z for a light facing straight up or down (as a camera looking down).
                let up = match l.up {
                    Some(u) => self.vec3(&p.key("up"), u, -1e6, 1e6)?,
                    None if direction.y.abs() > 0.999 => -Vec3::Z,
                    None => Vec3::Y,
                };
                let right = direction.cross(up);
                if right.length() < 1e-6 * up.length().max(1e-30) || up.length() < 1e-12 {
                    return Err(self.err(
                        &p.key("up"),
                        Target::Value,
                        "`up` is parallel to the light's `direction` (or zero)",
                        Some("give an `up` across the direction, e.g. [0, 0, -1] for a light facing down".into()),
                    ));
                }
                let right = right.normalize();
                (out.position, out.direction, out.size, out.frame) = (position, direction, [w, h], [right, right.cross(direction)]);
            }
            K::Disk => (out.position, out.direction, out.radius) = (position()?, direction()?, radius()?),
            K::Sphere => (out.position, out.radius) = (position()?, radius()?),
            K::Line => {
                let start = self.vec3(&p.key("start"), need("start", l.start)?, -1e6, 1e6)?;
                let end = self.vec3(&p.key("end"), need("end", l.end)?, -1e6, 1e6)?;
                if (end - start).length() < 1e-6 {
                    return Err(self.err(
                        &p.key("end"),
                        Target::Value,
                        "`end` equals `start`: the line has no length",
                        Some("a line light needs two different ends; for a point of light use kind = \"point\"".into()),
                    ));
                }
                (out.ends, out.radius) = ([start, end], radius()?);
            }
            K::Sky => {
                let ground = l.ground_color.as_ref().map_or(Ok(Vec3::ZERO), |c| self.color(&p.key("ground_color"), c, 0.0, 1e6))?;
                out.ground = ground * intensity;
            }
        }
        let default_samples = if kind == K::Sky { 64 } else { 16 };
        out.samples = match l.samples {
            Some(v) => self.integer(&p.key("samples"), v, 1, MAX_LIGHT_SAMPLES)?,
            None if kind.keys().contains(&"samples") => default_samples,
            None => 1,
        };
        if let Some(s) = &l.shadows {
            let method = self.choice(&p.key("shadows"), s, &ShadowMethod::NAMES)?;
            // Volumes and shadow polygons are cast from one point (or one direction): a light
            // with extent has no single silhouette.
            if matches!(method, ShadowMethod::Volume | ShadowMethod::Polygons)
                && matches!(kind, K::Rect | K::Disk | K::Sphere | K::Line | K::Sky)
            {
                return Err(self.err(
                    &p.key("shadows"),
                    Target::Value,
                    format!("shadows = \"{}\" needs a point, spot or directional light, not a {} light", method.name(), kind.name()),
                    Some("a light with extent casts soft shadows: use \"ray\" (its samples), or make it a point or spot light".into()),
                ));
            }
            out.shadows = Some(method);
        }
        (out.ambient, out.attenuation) = (ambient, attenuation);
        if let Some(c) = &l.specular {
            out.specular = self.color(&p.key("specular"), c, 0.0, 1e6)? * intensity;
        }
        Ok(out)
    }

    /// A spot's `profile = [[θ_deg, I], ...]`: θ increasing from 0 up to 90, I ≥ 0.
    fn spot_profile(&self, p: &KeyPath, points: &[[f64; 2]], exponent: bool) -> R<Vec<(f32, f32)>> {
        let pp = p.key("profile");
        if exponent {
            return Err(self.err(
                &p.key("exponent"),
                Target::Key,
                "`exponent` and `profile` both give the spot's distribution",
                Some("drop `exponent` (the profile replaces the cos^L_exp law) or drop `profile`".into()),
            ));
        }
        if points.is_empty() || points.len() > MAX_PROFILE_POINTS {
            return Err(self.err(
                &pp,
                Target::Value,
                format!("{} points; a profile has 1 to {MAX_PROFILE_POINTS}", points.len()),
                Some("give e.g. `profile = [[0, 0.5], [35, 1.0], [60, 0]]` (θ in degrees, I)".into()),
            ));
        }
        let mut out = Vec::with_capacity(points.len());
        for (i, [t, v]) in points.iter().enumerate() {
            let at = pp.index(i);
            let theta = self.number(&at.index(0), *t, 0.0, 90.0)?;
            let value = self.number(&at.index(1), *v, 0.0, 1e6)?;
            if i == 0 && theta != 0.0 {
                return Err(self.err(
                    &at.index(0),
                    Target::Value,
                    format!("the profile starts at θ = {t}°"),
                    Some("the first point is on the axis: θ = 0".into()),
                ));
            }
            if let Some(&(prev, _)) = out.last()
                && theta <= prev
            {
                return Err(self.err(
                    &at.index(0),
                    Target::Value,
                    format!("θ = {t}° does not increase (the point before is at {prev}°)"),
                    Some("list the angles in increasing order".into()),
                ));
            }
            out.push((theta, value));
        }
        Ok(out)
    }

    pub(super) fn render(&self, p: &KeyPath, r: &RawRender) -> R<RenderSettings> {
        let d = RenderSettings::default();
        Ok(RenderSettings {
            interpolation: self.choice_or(
                &p.key("interpolation"),
                &r.interpolation,
                &[("flat", Interpolation::Flat), ("gouraud", Interpolation::Gouraud), ("phong", Interpolation::Phong)],
                d.interpolation,
            )?,
            interpolation_space: match &r.interpolation_space {
                Some(s) => self.choice(
                    &p.key("interpolation_space"),
                    s,
                    &[("perspective", InterpolationSpace::Perspective), ("screen", InterpolationSpace::Screen)],
                )?,
                None => d.interpolation_space,
            },
            texture_filter: match &r.texture_filter {
                Some(s) => self.choice(&p.key("texture_filter"), s, &TextureFilter::CHOICES)?,
                None => d.texture_filter,
            },
            normals: match &r.normals {
                Some(s) => self.choice(
                    &p.key("normals"),
                    s,
                    &[("average", NormalWeighting::Average), ("area", NormalWeighting::Area), ("angle", NormalWeighting::Angle)],
                )?,
                None => d.normals,
            },
            normal_transform: match &r.normal_transform {
                Some(s) => self.choice(
                    &p.key("normal_transform"),
                    s,
                    &[("inverse_transpose", NormalTransform::InverseTranspose), ("naive", NormalTransform::Naive)],
                )?,
                None => d.normal_transform,
            },
            aa: match r.aa {
                Some(v) => self.integer(&p.key("aa"), v, 1, MAX_AA)?,
                None => d.aa,
            },
            exposure: match r.exposure {
                Some(v) => self.number(&p.key("exposure"), v, -20.0, 20.0)?,
                None => d.exposure,
            },
            tonemap: match &r.tonemap {
                Some(s) => self.choice(
                    &p.key("tonemap"),
                    s,
                    &[("clamp", Tonemap::Clamp), ("reinhard", Tonemap::Reinhard), ("aces", Tonemap::Aces), ("agx", Tonemap::Agx)],
                )?,
                None => d.tonemap,
            },
            cull: match &r.cull {
                Some(s) => self.choice(&p.key("cull"), s, &[("back", Cull::Back), ("none", Cull::None)])?,
                None => d.cull,
            },
            shadows: self.choice_or(&p.key("shadows"), &r.shadows, &ShadowMethod::NAMES, d.shadows)?,
            shadow_map: {
                let m = d.shadow_map;
                ShadowMapSettings {
                    size: self.integer_or(&p.key("shadow_map_size"), r.shadow_map_size, 8, MAX_SHADOW_MAP, m.size)?,
                    bias: r.shadow_bias.map_or(Ok(m.bias), |v| self.number(&p.key("shadow_bias"), v, 0.0, 100.0))?,
                    slope_bias: r
                        .shadow_slope_bias
                        .map_or(Ok(m.slope_bias), |v| self.number(&p.key("shadow_slope_bias"), v, 0.0, 100.0))?,
                    normal_offset: r
                        .shadow_normal_offset
                        .map_or(Ok(m.normal_offset), |v| self.number(&p.key("shadow_normal_offset"), v, 0.0, 100.0))?,
                    pcf: r.shadow_pcf.map_or(Ok(m.pcf), |v| self.integer(&p.key("shadow_pcf"), v, 1, 32))?,
                }
            },
            method: match &r.method {
                Some(s) => self.choice(&p.key("method"), s, &RenderMethod::NAMES)?,
                None => d.method,
            },
            path: self.path_settings(p, r)?,
            radiosity: self.radiosity(p, r)?,
            area_reference: false,
            ibl: match &r.ibl {
                Some(v) => self.choice(&p.key("ibl"), v, &Ibl::NAMES)?,
                None => d.ibl,
            },
            env_samples: match r.env_samples {
                Some(v) => self.integer(&p.key("env_samples"), v, 1, MAX_ENV_SAMPLES)?,
                None => d.env_samples,
            },
            prefilter_size: match r.prefilter_size {
                Some(v) => self.integer(&p.key("prefilter_size"), v, 16, MAX_PREFILTER_SIZE)?,
                None => d.prefilter_size,
            },
            sampler: match &r.sampler {
                Some(v) => self.choice(&p.key("sampler"), v, &Sampler::NAMES)?,
                None => d.sampler,
            },
            sample_pattern: match &r.sample_pattern {
                Some(v) => self.choice(&p.key("sample_pattern"), v, &crate::geometry::sampler::SamplePattern::NAMES)?,
                None => d.sample_pattern,
            },
            reflections: match &r.reflections {
                Some(v) => self.choice(&p.key("reflections"), v, &Reflections::NAMES)?,
                None => d.reflections,
            },
            max_bounces: match r.max_bounces {
                Some(v) => self.integer(&p.key("max_bounces"), v, 1, MAX_BOUNCES)?,
                None => d.max_bounces,
            },
        })
    }

    fn path_settings(&self, p: &KeyPath, r: &RawRender) -> R<PathSettings> {
        let d = PathSettings::default();
        let path = PathSettings {
            spp: r.spp.map_or(Ok(d.spp), |v| self.integer(&p.key("spp"), v, 1, MAX_SPP))?,
            max_depth: r.max_depth.map_or(Ok(d.max_depth), |v| self.integer(&p.key("max_depth"), v, 1, MAX_DEPTH))?,
            caustics: match &r.caustics {
                Some(s) => self.choice(&p.key("caustics"), s, &Caustics::NAMES)?,
                None => d.caustics,
            },
            photons: r.photons.map_or(Ok(d.photons), |v| self.integer(&p.key("photons"), v, 1000, MAX_PHOTONS))?,
            photon_radius: r.photon_radius.map_or(Ok(d.photon_radius), |v| self.number(&p.key("photon_radius"), v, 1e-4, 10.0))?,
            indirect: match &r.indirect {
                Some(s) => self.choice(&p.key("indirect"), s, &Indirect::NAMES)?,
                None => d.indirect,
            },
            gather_rays: r.gather_rays.map_or(Ok(d.gather_rays), |v| self.integer(&p.key("gather_rays"), v, 0, MAX_GATHER_RAYS))?,
            global_photons: r
                .global_photons
                .map_or(Ok(d.global_photons), |v| self.integer(&p.key("global_photons"), v, 1000, MAX_PHOTONS))?,
            global_radius: r.global_radius.map_or(Ok(d.global_radius), |v| self.number(&p.key("global_radius"), v, 1e-3, 10.0))?,
            photon_gather: match &r.photon_gather {
                Some(s) => self.choice(&p.key("photon_gather"), s, &PhotonGather::NAMES)?,
                None => d.photon_gather,
            },
            photon_nearest: r
                .photon_nearest
                .map_or(Ok(d.photon_nearest), |v| self.integer(&p.key("photon_nearest"), v, 1, MAX_PHOTON_NEAREST))?,
        };
        // The final gather reads the global map where its rays land, and that map holds the
        // caustics too: light through glass would be counted twice by a path.
        if path.indirect == Indirect::Photons && path.caustics != Caustics::Photons {
            return Err(self.err(
                &p.key("indirect"),
                Target::Value,
                "indirect = \"photons\" needs caustics = \"photons\"".to_string(),
                Some("add `caustics = \"photons\"`: the final gather leaves the caustics to the caustic photon map (Jensen 1996)".into()),
            ));
        }
        Ok(path)
    }

    fn radiosity(&self, p: &KeyPath, r: &RawRender) -> R<RadiositySettings> {
        let d = RadiositySettings::default();
        let patch_size = match r.patch_size {
            // Zero or less cannot be met by any patch; the hint gives the scale.
            Some(v) if v.is_finite() && v <= 0.0 => {
                return Err(self.err(
                    &p.key("patch_size"),
                    Target::Value,
                    format!("patch_size must be greater than 0, got {v}"),
                    Some("patch_size is the longest patch edge in world units: 0.25 is coarse in a 2-unit room, 0.1 fine".into()),
                ));
            }
            Some(v) => self.number(&p.key("patch_size"), v, 0.0, 1e6)?,
            None => d.patch_size,
        };
        Ok(RadiositySettings {
            patch_size,
            form_factors: match &r.form_factors {
                Some(s) => {
                    self.choice(&p.key("form_factors"), s, &[("hemicube", FormFactorMethod::Hemicube), ("ray", FormFactorMethod::Ray)])?
                }
                None => d.form_factors,
            },
            hemicube_size: r.hemicube_size.map_or(Ok(d.hemicube_size), |v| self.integer(&p.key("hemicube_size"), v, 4, MAX_HEMICUBE))?,
            solver: match &r.solver {
                Some(s) => self.choice(&p.key("solver"), s, &Solver::ALL.map(|s| (s.name(), s)))?,
                None => d.solver,
            },
            iterations: r.iterations.map_or(Ok(d.iterations), |v| self.integer(&p.key("iterations"), v, 0, MAX_ITERATIONS))?,
            tolerance: r.tolerance.map_or(Ok(d.tolerance), |v| self.number(&p.key("tolerance"), v, 0.0, 1.0))?,
            display: match &r.display {
                Some(s) => {
                    self.choice(&p.key("display"), s, &[("flat", RadiosityDisplay::Flat), ("gouraud", RadiosityDisplay::Gouraud)])?
                }
                None => d.display,
            },
            final_gather: r.final_gather.unwrap_or(d.final_gather),
            ambient_correction: r.ambient_correction.unwrap_or(d.ambient_correction),
        })
    }
}
