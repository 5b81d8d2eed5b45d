//! The closed sets of names a lesson file chooses from: material models, shapes, light
//! kinds and Fresnel terms, each with its name and the keys it reads.
//!
//! Validation, hints, `explain`, the CLI and the reference renderer take names and keys
//! from here, so adding a model, shape or light touches this file and the exhaustive
//! `match`es it leads to.

use super::shape::Shape;
use crate::shading::material::ClassicModel;

/// A `model = "…"` of a `[material.NAME]` table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelKind {
    /// One of the course's classic models (no π, coefficients in [0, 1]).
    Classic(ClassicModel),
    /// Lambert's BRDF ρ/π.
    Diffuse,
    /// Cook-Torrance microfacet BRDF (+ optional Lambert diffuse).
    CookTorrance,
    /// Oren-Nayar rough diffuse.
    OrenNayar,
    /// The Disney principled BRDF.
    Principled,
    /// Energy-normalized Phong.
    NormalizedPhong,
    /// Energy-normalized Blinn-Phong.
    NormalizedBlinnPhong,
    /// The classic Phong lobe as a BRDF, without normalization.
    UnnormalizedPhong,
    /// A perfect mirror.
    Mirror,
    /// A smooth dielectric: reflection and refraction.
    Glass,
}

impl ModelKind {
    /// Every model, in the order messages list them.
    pub const ALL: [ModelKind; 12] = [
        ModelKind::Classic(ClassicModel::Lambert),
        ModelKind::Classic(ClassicModel::Phong),
        ModelKind::Classic(ClassicModel::BlinnPhong),
        ModelKind::Diffuse,
        ModelKind::CookTorrance,
        ModelKind::OrenNayar,
        ModelKind::Principled,
        ModelKind::NormalizedPhong,
        ModelKind::NormalizedBlinnPhong,
        ModelKind::UnnormalizedPhong,
        ModelKind::Mirror,
        ModelKind::Glass,
    ];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            ModelKind::Classic(c) => c.name(),
            ModelKind::Diffuse => "diffuse",
            ModelKind::CookTorrance => "cook_torrance",
            ModelKind::OrenNayar => "oren_nayar",
            ModelKind::Principled => "principled",
            ModelKind::NormalizedPhong => "normalized_phong",
            ModelKind::NormalizedBlinnPhong => "normalized_blinn_phong",
            ModelKind::UnnormalizedPhong => "unnormalized_phong",
            ModelKind::Mirror => "mirror",
            ModelKind::Glass => "glass",
        }
    }

    /// The model named `s` (any case: every name is lower case and distinct), if any.
    pub fn parse(s: &str) -> Option<ModelKind> {
        ModelKind::ALL.into_iter().find(|m| m.name().eq_ignore_ascii_case(s))
    }

    /// The keys it reads besides `model`, `ambient` and `emission`.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            ModelKind::Classic(ClassicModel::Lambert) => &["diffuse", "clamp_n_dot_l"],
            ModelKind::Diffuse => &["diffuse"],
            ModelKind::Classic(_) => &["diffuse", "specular", "shininess", "clamp_n_dot_l"],
            ModelKind::NormalizedPhong | ModelKind::NormalizedBlinnPhong | ModelKind::UnnormalizedPhong => {
                &["diffuse", "specular", "shininess"]
            }
            ModelKind::OrenNayar => &["diffuse", "sigma_deg", "variant"],
            ModelKind::Mirror => &["tint"],
            ModelKind::Glass => &["ior", "thin", "tint", "roughness"],
            ModelKind::CookTorrance => {
                &["ndf", "masking", "fresnel", "ior", "eta", "k", "preset", "roughness", "alpha", "specular", "diffuse"]
            }
            ModelKind::Principled => &[
                "base_color",
                "metallic",
                "roughness",
                "specular",
                "specular_tint",
                "sheen",
                "sheen_tint",
                "clearcoat",
                "clearcoat_gloss",
                "subsurface",
                "anisotropic",
                "specular_transmission",
                "ior",
                "transmittance_color",
                "transmittance_distance",
                "diffuse_transmission",
                "subsurface_radius",
                "subsurface_scale",
            ],
        }
    }
}

/// A `shape = "…"` of an `[[object]]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeKind {
    /// Latitude-longitude sphere.
    UvSphere,
    /// Subdivided icosahedron.
    Icosphere,
    /// The unit square in xz.
    Plane,
    /// The cube [−1, 1]³.
    Cube,
    /// A torus around y.
    Torus,
    /// An OBJ file.
    Mesh,
}

impl ShapeKind {
    /// Every shape, in the order messages list them.
    pub const ALL: [ShapeKind; 6] =
        [ShapeKind::UvSphere, ShapeKind::Icosphere, ShapeKind::Plane, ShapeKind::Cube, ShapeKind::Torus, ShapeKind::Mesh];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            ShapeKind::UvSphere => "uv_sphere",
            ShapeKind::Icosphere => "icosphere",
            ShapeKind::Plane => "plane",
            ShapeKind::Cube => "cube",
            ShapeKind::Torus => "torus",
            ShapeKind::Mesh => "mesh",
        }
    }

    /// The one named `s` (any case), if any.
    pub fn parse(s: &str) -> Option<ShapeKind> {
        ShapeKind::ALL.into_iter().find(|k| k.name().eq_ignore_ascii_case(s))
    }

    /// The keys it reads besides `shape`, `material` and the transform.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            ShapeKind::UvSphere => &["segments", "rings"],
            ShapeKind::Icosphere => &["subdivisions"],
            ShapeKind::Plane | ShapeKind::Cube => &[],
            ShapeKind::Torus => &["major_radius", "minor_radius", "segments", "sides"],
            ShapeKind::Mesh => &["path", "node", "primitive"],
        }
    }
}

impl Shape {
    /// Which shape this is.
    pub fn kind(&self) -> ShapeKind {
        match self {
            Shape::UvSphere { .. } => ShapeKind::UvSphere,
            Shape::Icosphere { .. } => ShapeKind::Icosphere,
            Shape::Plane => ShapeKind::Plane,
            Shape::Cube => ShapeKind::Cube,
            Shape::Torus { .. } => ShapeKind::Torus,
            Shape::Mesh { .. } => ShapeKind::Mesh,
        }
    }

    /// The name in lesson files.
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }
}

/// A `kind = "…"` of a `[[light]]` (the light room's `LightKind` holds each kind's parameters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LightType {
    /// Parallel light.
    Directional,
    /// Light from a point.
    Point,
    /// A point light in a cone.
    Spot,
    /// Only an ambient part.
    Ambient,
    /// A one-sided rectangle.
    Rect,
    /// A one-sided disk.
    Disk,
    /// A sphere emitting all round.
    Sphere,
    /// A thin tube (fluorescent lamp).
    Line,
    /// A hemisphere of sky above and ground below.
    Sky,
}

impl LightType {
    /// Every light kind, in the order messages list them.
    pub const ALL: [LightType; 9] = [
        LightType::Directional,
        LightType::Point,
        LightType::Spot,
        LightType::Ambient,
        LightType::Rect,
        LightType::Disk,
        LightType::Sphere,
        LightType::Line,
        LightType::Sky,
    ];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            LightType::Directional => "directional",
            LightType::Point => "point",
            LightType::Spot => "spot",
            LightType::Ambient => "ambient",
            LightType::Rect => "rect",
            LightType::Disk => "disk",
            LightType::Sphere => "sphere",
            LightType::Line => "line",
            LightType::Sky => "sky",
        }
    }

    /// The one named `s` (any case), if any.
    pub fn parse(s: &str) -> Option<LightType> {
        LightType::ALL.into_iter().find(|k| k.name().eq_ignore_ascii_case(s))
    }

    /// True for the kinds sampled at several points (rect, disk, sphere, line, sky).
    pub fn is_sampled(self) -> bool {
        self.keys().contains(&"samples")
    }

    /// The keys it reads besides `kind`, `color` and `intensity`.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            LightType::Directional => &["direction", "ambient", "specular", "shadows"],
            LightType::Point => &["position", "attenuation", "ambient", "specular", "shadows"],
            LightType::Spot => {
                &["position", "direction", "attenuation", "exponent", "profile", "cutoff_deg", "ambient", "specular", "shadows"]
            }
            LightType::Ambient => &[],
            LightType::Rect => &["position", "direction", "size", "up", "samples", "shadows", "sampling"],
            LightType::Disk => &["position", "direction", "radius", "samples", "shadows"],
            LightType::Sphere => &["position", "radius", "samples", "shadows", "sampling"],
            LightType::Line => &["start", "end", "radius", "samples", "shadows", "sampling"],
            LightType::Sky => &["ground_color", "samples", "shadows"],
        }
    }
}

/// A `fresnel = "…"` of a `cook_torrance` material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FresnelKind {
    /// Schlick's approximation with F₀ from `ior`.
    Schlick,
    /// The exact dielectric Fresnel with η = `ior`.
    Dielectric,
    /// The exact conductor Fresnel with complex index `eta` + i`k`.
    Conductor,
    /// F = 1.
    None,
}

impl FresnelKind {
    /// Every Fresnel term, in the order messages list them.
    pub const ALL: [FresnelKind; 4] = [FresnelKind::Schlick, FresnelKind::Dielectric, FresnelKind::Conductor, FresnelKind::None];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            FresnelKind::Schlick => "schlick",
            FresnelKind::Dielectric => "dielectric",
            FresnelKind::Conductor => "conductor",
            FresnelKind::None => "none",
        }
    }

    /// The one named `s` (any case), if any.
    pub fn parse(s: &str) -> Option<FresnelKind> {
        FresnelKind::ALL.into_iter().find(|k| k.name().eq_ignore_ascii_case(s))
    }

    /// The keys it reads.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            FresnelKind::Schlick | FresnelKind::Dielectric => &["ior"],
            FresnelKind::Conductor => &["eta", "k", "preset"],
            FresnelKind::None => &[],
        }
    }
}

/// `(name, kind)` pairs of a closed set, as validation's `choice` takes them.
pub fn choices<T: Copy, const N: usize>(all: [T; N], name: impl Fn(T) -> &'static str) -> [(&'static str, T); N] {
    all.map(|k| (name(k), k))
}

/// How a light's visibility is found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShadowMethod {
    /// A shadow ray per light (sample) per shaded point: exact hard shadows, the reference.
    #[default]
    Ray,
    /// The two-pass method: depth rendered from the light, then compared.
    Map,
    /// Shadow volumes (Crow 1977): silhouette edges extruded from the light, counted along
    /// the eye's ray (z-pass).
    Volume,
    /// Object-space shadow polygons (Atherton, Weiler & Greenberg 1978): occluders projected
    /// onto each receiver from the light, then point-in-polygon from the eye.
    Polygons,
    /// Nothing blocks light.
    None,
}

impl ShadowMethod {
    /// Every method with its name in lesson files.
    pub const NAMES: [(&'static str, ShadowMethod); 5] = [
        ("ray", ShadowMethod::Ray),
        ("map", ShadowMethod::Map),
        ("volume", ShadowMethod::Volume),
        ("polygons", ShadowMethod::Polygons),
        ("none", ShadowMethod::None),
    ];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            ShadowMethod::Ray => "ray",
            ShadowMethod::Map => "map",
            ShadowMethod::Volume => "volume",
            ShadowMethod::Polygons => "polygons",
            ShadowMethod::None => "none",
        }
    }
}

/// How a light with extent turns u ∈ [0, 1)² into a point of itself (`[[light]] sampling`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LightSampling {
    /// Uniform over its area (or its axis): dω = A cos θ_l / r², large when the light is near.
    Area,
    /// Uniform over the solid angle it subtends from the point: every sample carries the same dω.
    #[default]
    SolidAngle,
}

impl LightSampling {
    /// Every method with its name in lesson files.
    pub const NAMES: [(&'static str, LightSampling); 2] = [("area", LightSampling::Area), ("solid_angle", LightSampling::SolidAngle)];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            LightSampling::Area => "area",
            LightSampling::SolidAngle => "solid_angle",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_are_distinct() {
        for m in ModelKind::ALL {
            assert_eq!(ModelKind::parse(m.name()), Some(m));
        }
        assert!(ShapeKind::ALL.iter().all(|&k| ShapeKind::parse(k.name()) == Some(k)));
        assert!(LightType::ALL.iter().all(|&k| LightType::parse(k.name()) == Some(k)));
        assert!(FresnelKind::ALL.iter().all(|&k| FresnelKind::parse(k.name()) == Some(k)));
        let mut names: Vec<&str> = ShapeKind::ALL.iter().map(|s| s.name()).collect();
        names.extend(LightType::ALL.iter().map(|l| l.name()));
        names.extend(FresnelKind::ALL.iter().map(|f| f.name()));
        let n = names.len();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), n);
        assert_eq!(ModelKind::parse("gouraud"), None);
    }

    #[test]
    fn names_parse_in_any_case() {
        assert_eq!(ModelKind::parse("Blinn_Phong"), Some(ModelKind::Classic(ClassicModel::BlinnPhong)));
        assert_eq!(ModelKind::parse("COOK_TORRANCE"), Some(ModelKind::CookTorrance));
        assert_eq!(ShapeKind::parse("UV_Sphere"), Some(ShapeKind::UvSphere));
        assert_eq!(LightType::parse("Point"), Some(LightType::Point));
        assert_eq!(FresnelKind::parse("Schlick"), Some(FresnelKind::Schlick));
        // Unambiguous: no two names of a set differ only in case.
        let lower = |v: Vec<&str>| {
            let mut l: Vec<String> = v.iter().map(|n| n.to_ascii_lowercase()).collect();
            l.sort();
            l.dedup();
            l.len() == v.len()
        };
        assert!(lower(ModelKind::ALL.iter().map(|m| m.name()).collect()));
    }

    #[test]
    fn a_shape_and_a_light_name_their_kind() {
        assert_eq!(Shape::Torus { major_radius: 1.0, minor_radius: 0.3, segments: 8, sides: 4 }.name(), "torus");
        assert_eq!(LightType::Ambient.name(), "ambient");
        assert!(LightType::Sky.is_sampled() && !LightType::Spot.is_sampled());
        assert!(ShapeKind::Torus.keys().contains(&"sides") && !ShapeKind::Plane.keys().contains(&"sides"));
    }
}
