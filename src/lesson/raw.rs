//! Serde structs that mirror the TOML file one to one (stage one of parsing).
//!
//! Every struct denies unknown keys; values are checked in [`super::validate`].

use serde::Deserialize;
use std::collections::BTreeMap;

/// An RGB colour or a scalar grey (`0.5` means `[0.5, 0.5, 0.5]`), or as text: sRGB hex or a CSS name.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum RawColor {
    /// One value for all three channels.
    Scalar(f64),
    /// Linear red, green, blue.
    Rgb([f64; 3]),
    /// `"#rgb"`, `"#rrggbb"` (sRGB) or a CSS colour name, decoded by [`crate::lesson::color`].
    Text(String),
}

/// A material parameter: a constant (as [`RawColor`]) or a table naming a texture
/// (`{ texture = "wood.png" }` or `{ checker = { scale = 8, a = .., b = .. } }`), whose keys
/// are checked in validation.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum RawParam {
    /// A constant: one number or `[r, g, b]`.
    Constant(RawColor),
    /// A texture table.
    Map(toml::Table),
}

/// The whole lesson file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLesson {
    /// `[lesson]`: title, summary, notes.
    #[serde(default)]
    pub lesson: RawInfo,
    /// `[camera]`.
    pub camera: RawCamera,
    /// `[[object]]`.
    #[serde(default)]
    pub object: Vec<RawObject>,
    /// `[material.NAME]`.
    #[serde(default)]
    pub material: BTreeMap<String, RawMaterial>,
    /// `[[light]]`.
    #[serde(default)]
    pub light: Vec<RawLight>,
    /// `[scene]`.
    #[serde(default)]
    pub scene: RawSceneSettings,
    /// `[render]`.
    #[serde(default)]
    pub render: RawRender,
    /// `[fog]`.
    pub fog: Option<RawFog>,
    /// `[environment]`: the distant light all round the scene.
    pub environment: Option<RawEnvironment>,
    /// `[[probe]]`: reflection probes.
    #[serde(default)]
    pub probe: Vec<RawProbe>,
    /// `[[figure]]`.
    #[serde(default)]
    pub figure: Vec<RawFigure>,
}

/// `[[probe]]`: a cube map rendered from a point, with the box of its parallax correction.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawProbe {
    /// The capture point.
    pub position: [f64; 3],
    /// Texels along a face's side.
    pub size: Option<i64>,
    /// The box's smallest corner.
    pub box_min: [f64; 3],
    /// The box's largest corner.
    pub box_max: [f64; 3],
    /// Where the probe is read from after it moved (C′), its capture staying at `position`.
    pub moved_to: Option<[f64; 3]>,
}

/// `[[figure]]`: a grid of variants of the lesson.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFigure {
    /// File name of the figure (without extension).
    pub name: String,
    /// `compare`, `sweep`, `grid`, `split`, `lobe`, `albedo`, `cost`, `convergence`, `probe`, `walk`, `bsdf` or `bssrdf`.
    pub kind: String,
    /// compare/sweep: the dotted key that varies.
    pub vary: Option<String>,
    /// compare/sweep: its values (an array, or a range string such as "1..256:log:8").
    pub values: Option<toml::Value>,
    /// grid: the key and values down the rows.
    pub rows: Option<RawAxis>,
    /// grid: the key and values across the columns.
    pub cols: Option<RawAxis>,
    /// compare/sweep: a label per value instead of the generated ones (each a string or `{ en, ja }`).
    pub labels: Option<Vec<toml::Value>>,
    /// Title above the figure (default: the lesson title); a string or `{ en, ja }`.
    pub title: Option<toml::Value>,
    /// Caption below the figure; a string or `{ en, ja }`.
    pub caption: Option<toml::Value>,
    /// split: the layers to show.
    pub layers: Option<Vec<String>>,
    /// compare/sweep/grid: the layer every cell shows (default `total`).
    pub layer: Option<String>,
    /// Size of one cell in pixels (default: the camera size).
    pub cell: Option<[i64; 2]>,
    /// The slide the figure is laid out for: `"1920x1080"` or `[1920, 1080]`.
    pub fit: Option<toml::Value>,
    /// lobe/albedo: names of physically based materials to plot; bssrdf: the one subsurface material.
    pub materials: Option<Vec<String>>,
    /// lobe: indices of spot lights whose distribution I(θ) is plotted instead of materials.
    pub lights: Option<Vec<i64>>,
    /// lobe: angles of incidence in degrees.
    pub incidence: Option<Vec<f64>>,
    /// lobe: azimuths φ_o − φ_i of the outgoing slices in degrees (default: 0, the plane of incidence).
    pub azimuth_deg: Option<Vec<f64>>,
    /// lobe: also draw each lobe with l and v exchanged in f (reciprocity).
    pub swap: Option<bool>,
    /// lobe: Cook-Torrance partial products to draw (`D`, `DG`, `DGF`) instead of the whole f.
    pub terms: Option<Vec<String>>,
    /// compare/sweep/grid/split: draw `face`, `vertex` or `both` normals over each cell.
    pub normals: Option<String>,
    /// cost: the quality ladder (`interpolation`, `tessellation`, `aa`, `fresnel`, `shadow_map`,
    /// `pcf`, `area_samples`, `shadow_bias`).
    pub ladder: Option<String>,
    /// cost: timed runs per rung.
    pub repeat: Option<i64>,
    /// convergence: the radiosity solvers drawn (`jacobi`, `gauss_seidel`, `progressive`).
    pub solvers: Option<Vec<String>>,
    /// convergence: run each solver until its residual is at most this.
    pub tolerance: Option<f64>,
    /// compare, sweep: add a row of |difference| heatmaps against the first cell.
    pub diff: Option<bool>,
    /// probe: the pixels [x, y] explained.
    pub pixels: Option<Vec<[i64; 2]>>,
    /// compare, sweep, grid: a bar of the cells' greys with the quantity they show.
    pub colorbar: Option<RawColorbar>,
    /// walk: the slab's single-scattering albedo ω per channel.
    pub scattering_albedo: Option<RawColor>,
    /// walk: the number of random walks traced.
    pub walks: Option<i64>,
    /// walk: the slab's optical thickness (default: a half-space).
    pub thickness: Option<f64>,
    /// bsdf: the index of refraction of the inside relative to the outside.
    pub ior: Option<f64>,
    /// bsdf: the roughnesses drawn.
    pub roughness: Option<Vec<f64>>,
}

/// `colorbar = { label = "...", radiance_per_unit = ... }` of a `[[figure]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawColorbar {
    /// What the greys measure, with its unit: a string or `{ en, ja }`.
    pub label: toml::Value,
    /// The linear radiance one unit of it gives in the cells.
    pub radiance_per_unit: f64,
}

impl RawFigure {
    /// Whether the optional key `key` is given (`false` for names that are not keys).
    pub fn is_set(&self, key: &str) -> bool {
        match key {
            "vary" => self.vary.is_some(),
            "values" => self.values.is_some(),
            "rows" => self.rows.is_some(),
            "cols" => self.cols.is_some(),
            "labels" => self.labels.is_some(),
            "title" => self.title.is_some(),
            "caption" => self.caption.is_some(),
            "layers" => self.layers.is_some(),
            "layer" => self.layer.is_some(),
            "cell" => self.cell.is_some(),
            "materials" => self.materials.is_some(),
            "lights" => self.lights.is_some(),
            "incidence" => self.incidence.is_some(),
            "azimuth_deg" => self.azimuth_deg.is_some(),
            "swap" => self.swap.is_some(),
            "terms" => self.terms.is_some(),
            "normals" => self.normals.is_some(),
            "ladder" => self.ladder.is_some(),
            "repeat" => self.repeat.is_some(),
            "solvers" => self.solvers.is_some(),
            "tolerance" => self.tolerance.is_some(),
            "diff" => self.diff.is_some(),
            "pixels" => self.pixels.is_some(),
            "colorbar" => self.colorbar.is_some(),
            "scattering_albedo" => self.scattering_albedo.is_some(),
            "walks" => self.walks.is_some(),
            "thickness" => self.thickness.is_some(),
            "ior" => self.ior.is_some(),
            "roughness" => self.roughness.is_some(),
            _ => false,
        }
    }
}

/// One axis of a grid figure.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawAxis {
    /// The dotted key that varies along the axis.
    pub vary: String,
    /// Its values (an array, or a range string).
    pub values: toml::Value,
    /// A label per value instead of the generated ones (each a string or `{ en, ja }`).
    pub labels: Option<Vec<toml::Value>>,
}

/// `[lesson]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawInfo {
    /// Short title: a string, or `{ en = "...", ja = "..." }`.
    pub title: Option<toml::Value>,
    /// One-sentence summary (a string or `{ en, ja }`).
    pub summary: Option<toml::Value>,
    /// What to look at, printed after a render (a string or `{ en, ja }`).
    pub notes: Option<toml::Value>,
    /// Language of built-in labels: `en` or `ja`.
    pub lang: Option<String>,
}

/// `[camera]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCamera {
    /// Eye position.
    pub position: [f64; 3],
    /// Point looked at.
    pub look_at: Option<[f64; 3]>,
    /// Up vector.
    pub up: Option<[f64; 3]>,
    /// Vertical field of view in degrees.
    pub fov_deg: Option<f64>,
    /// Image size in pixels.
    pub size: Option<[i64; 2]>,
    /// Linear RGB background.
    pub background: Option<RawColor>,
    /// Near clipping distance.
    pub near: Option<f64>,
}

/// `[[object]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObject {
    /// `uv_sphere`, `icosphere`, `plane`, `cube`, `torus` or `mesh`.
    pub shape: String,
    /// Name of a `[material.NAME]` table.
    pub material: String,
    /// uv_sphere: segments around the axis.
    pub segments: Option<i64>,
    /// uv_sphere: rings from pole to pole.
    pub rings: Option<i64>,
    /// icosphere: subdivision level.
    pub subdivisions: Option<i64>,
    /// torus: radius of the centre circle.
    pub major_radius: Option<f64>,
    /// torus: radius of the tube.
    pub minor_radius: Option<f64>,
    /// torus: segments around the tube.
    pub sides: Option<i64>,
    /// mesh: OBJ or glTF path relative to the lesson file.
    pub path: Option<String>,
    /// mesh from a glTF file: the node (name or index) whose mesh is taken.
    pub node: Option<toml::Value>,
    /// mesh from a glTF file: one primitive of the node's mesh.
    pub primitive: Option<i64>,
    /// Translation.
    pub translate: Option<[f64; 3]>,
    /// Rotation in degrees about x, then y, then z.
    pub rotate_deg: Option<[f64; 3]>,
    /// Uniform or per-axis scale.
    pub scale: Option<RawColor>,
    /// Auto-smooth: faces meeting at more than this angle (degrees) keep their own normals.
    pub crease_deg: Option<f64>,
}

/// `[material.NAME]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    /// Classic: `lambert`, `phong`, `blinn_phong`; physically based: `diffuse`,
    /// `cook_torrance`, `oren_nayar`, `principled`, `normalized_phong`, `normalized_blinn_phong`.
    pub model: String,
    /// K_amb (classic), or the reflectance the ambient light sees (physically based).
    pub ambient: Option<RawParam>,
    /// K_diff (classic), or the diffuse albedo ρ (physically based).
    pub diffuse: Option<RawParam>,
    /// K_spec (classic), the specular tint (cook_torrance, normalized models) or Disney `specular` (principled).
    pub specular: Option<RawParam>,
    /// K_shi (classic and normalized models).
    pub shininess: Option<f64>,
    /// Classic models: `false` drops the max(·, 0) of the diffuse term's N·L (a teaching
    /// switch: what forgetting the clamp does).
    pub clamp_n_dot_l: Option<bool>,
    /// L_emi.
    pub emission: Option<RawParam>,
    /// cook_torrance: `blinn`, `beckmann`, `ggx`, `gaussian`.
    pub ndf: Option<String>,
    /// cook_torrance: `cook_torrance`, `smith`, `smith_correlated`.
    pub masking: Option<String>,
    /// cook_torrance: `schlick`, `dielectric`, `conductor`, `none`.
    pub fresnel: Option<String>,
    /// Relative index of refraction (dielectric and Schlick Fresnel).
    pub ior: Option<RawColor>,
    /// Conductor Fresnel: real part η of the complex index, per channel.
    pub eta: Option<RawParam>,
    /// Conductor Fresnel: absorption k, per channel.
    pub k: Option<RawParam>,
    /// Conductor Fresnel: a named metal (`gold`, `silver`, ...) giving `eta` and `k`.
    pub preset: Option<String>,
    /// Perceptual roughness in [0, 1]; α = roughness² (cook_torrance, principled).
    pub roughness: Option<RawParam>,
    /// Microfacet α directly (cook_torrance; not with `roughness`).
    pub alpha: Option<f64>,
    /// oren_nayar: surface slope deviation σ in degrees.
    pub sigma_deg: Option<f64>,
    /// oren_nayar: `full` or `qualitative`.
    pub variant: Option<String>,
    /// principled: base colour.
    pub base_color: Option<RawParam>,
    /// principled: metallic in [0, 1].
    pub metallic: Option<RawParam>,
    /// principled: specular tint in [0, 1].
    pub specular_tint: Option<f64>,
    /// principled: sheen in [0, 1].
    pub sheen: Option<f64>,
    /// principled: sheen tint in [0, 1].
    pub sheen_tint: Option<f64>,
    /// principled: clearcoat in [0, 1].
    pub clearcoat: Option<f64>,
    /// principled: clearcoat gloss in [0, 1].
    pub clearcoat_gloss: Option<f64>,
    /// principled: subsurface in [0, 1].
    pub subsurface: Option<f64>,
    /// principled: anisotropic in [0, 1].
    pub anisotropic: Option<f64>,
    /// principled: share of the dielectric that is a rough glass boundary, in [0, 1].
    pub specular_transmission: Option<f64>,
    /// principled: the colour light keeps after `transmittance_distance` inside.
    pub transmittance_color: Option<RawColor>,
    /// principled: the distance at which light inside has `transmittance_color`.
    pub transmittance_distance: Option<f64>,
    /// principled: share of the diffuse lobe sent through to the other side, in [0, 1].
    pub diffuse_transmission: Option<f64>,
    /// principled: mean free path per channel under the surface (path tracer only).
    pub subsurface_radius: Option<RawColor>,
    /// principled: world-unit multiplier of `subsurface_radius`.
    pub subsurface_scale: Option<f64>,
    /// A tangent-space normal map (any model but `mirror` and `glass`).
    pub normal_map: Option<String>,
    /// An ambient-occlusion map (linear grey, red channel) that scales the ambient term.
    pub occlusion_map: Option<String>,
    /// mirror: the colour the reflection is multiplied by; glass: the colour each refraction is multiplied by.
    pub tint: Option<RawParam>,
    /// glass: one interface only (the course's "surface only").
    pub thin: Option<bool>,
}

/// `[[light]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLight {
    /// `directional`, `point`, `spot` or `ambient`.
    pub kind: String,
    /// Linear RGB colour.
    pub color: Option<RawColor>,
    /// Scale on the colour.
    pub intensity: Option<f64>,
    /// Point and spot: position.
    pub position: Option<[f64; 3]>,
    /// Directional and spot: the way the light travels.
    pub direction: Option<[f64; 3]>,
    /// `[S_c, S_l, S_q]`.
    pub attenuation: Option<[f64; 3]>,
    /// Spot exponent L_exp.
    pub exponent: Option<f64>,
    /// Spot hard cutoff half-angle in degrees.
    pub cutoff_deg: Option<f64>,
    /// Spot: a goniometric distribution `[[θ_deg, I], ...]` replacing the cos^L_exp law.
    pub profile: Option<Vec<[f64; 2]>>,
    /// This light's ambient part L_amb^k.
    pub ambient: Option<RawColor>,
    /// This light's specular part L_spec^k, scaled by `intensity` (default: its colour, L_spec = L_diff).
    pub specular: Option<RawColor>,
    /// Rect: `[w, h]`.
    pub size: Option<[f64; 2]>,
    /// Rect: orients the `w` side.
    pub up: Option<[f64; 3]>,
    /// Disk, sphere, line: radius.
    pub radius: Option<f64>,
    /// Line: one end.
    pub start: Option<[f64; 3]>,
    /// Line: the other end.
    pub end: Option<[f64; 3]>,
    /// Sky: radiance from below the horizon.
    pub ground_color: Option<RawColor>,
    /// Samples per shaded point (area, line and sky lights).
    pub samples: Option<i64>,
    /// `ray`, `map` or `none`: this light's shadow method.
    pub shadows: Option<String>,
    /// Rect, sphere and line lights: `solid_angle` (the default) or `area`.
    pub sampling: Option<String>,
}

/// `[scene]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSceneSettings {
    /// Global ambient L_glob.
    pub ambient: Option<RawColor>,
}

/// `[render]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRender {
    /// `flat`, `gouraud` or `phong`.
    pub interpolation: Option<String>,
    /// `perspective` or `screen`.
    pub interpolation_space: Option<String>,
    /// Texture filtering: `nearest`, `bilinear` or `trilinear` (mip-mapped).
    pub texture_filter: Option<String>,
    /// `average`, `area` or `angle`.
    pub normals: Option<String>,
    /// `inverse_transpose` or `naive`.
    pub normal_transform: Option<String>,
    /// Supersamples per pixel side.
    pub aa: Option<i64>,
    /// Exposure in stops.
    pub exposure: Option<f64>,
    /// `clamp`, `reinhard` or `aces`.
    pub tonemap: Option<String>,
    /// `back` or `none`.
    pub cull: Option<String>,
    /// `ray`, `map` or `none`.
    pub shadows: Option<String>,
    /// Shadow-map texels per side.
    pub shadow_map_size: Option<i64>,
    /// Constant shadow-map depth bias.
    pub shadow_bias: Option<f64>,
    /// Slope-scaled shadow-map bias.
    pub shadow_slope_bias: Option<f64>,
    /// Shadow-map normal offset in texels.
    pub shadow_normal_offset: Option<f64>,
    /// Percentage-closer filter width in texels.
    pub shadow_pcf: Option<i64>,
    /// `raster`, `radiosity` or `path`.
    pub method: Option<String>,
    /// Path tracer: paths per pixel sample.
    pub spp: Option<i64>,
    /// Path tracer: the longest path in segments from the camera.
    pub max_depth: Option<i64>,
    /// Path tracer: `path` or `photons` (a caustic photon map).
    pub caustics: Option<String>,
    /// Path tracer: photons emitted for the caustic map.
    pub photons: Option<i64>,
    /// Path tracer: the radius photons are gathered within.
    pub photon_radius: Option<f64>,
    /// Path tracer: `path`, `photons` (a global photon map with a final gather) or `none`.
    pub indirect: Option<String>,
    /// Path tracer: final-gather rays per first diffuse vertex.
    pub gather_rays: Option<i64>,
    /// Path tracer: photons emitted for the global photon map.
    pub global_photons: Option<i64>,
    /// Path tracer: the radius the global photon map is gathered within.
    pub global_radius: Option<f64>,
    /// Path tracer: `radius` or `nearest` photons.
    pub photon_gather: Option<String>,
    /// Path tracer: k of the k-nearest photon gather.
    pub photon_nearest: Option<i64>,
    /// Radiosity: longest patch edge in world units.
    pub patch_size: Option<f64>,
    /// Radiosity: `hemicube` or `ray`.
    pub form_factors: Option<String>,
    /// Radiosity: hemicube cells per side.
    pub hemicube_size: Option<i64>,
    /// Radiosity: `jacobi`, `gauss_seidel` or `progressive`.
    pub solver: Option<String>,
    /// Radiosity: most iterations.
    pub iterations: Option<i64>,
    /// Radiosity: relative residual to stop at.
    pub tolerance: Option<f64>,
    /// Radiosity: `flat` or `gouraud`.
    pub display: Option<String>,
    /// Radiosity: gather once more at each displayed point.
    pub final_gather: Option<bool>,
    /// Radiosity (progressive): the ambient correction.
    pub ambient_correction: Option<bool>,
    /// How the environment lights materials: `sh`, `prefiltered` or `reference` (Monte Carlo).
    pub ibl: Option<String>,
    /// Monte Carlo samples of the environment per shaded point.
    pub env_samples: Option<i64>,
    /// Width of the first convolved level of the prefiltered environment.
    pub prefilter_size: Option<i64>,
    /// How mirrors find what they reflect: `traced`, `probe` or `probe_box`.
    pub reflections: Option<String>,
    /// Glass: most interface events (reflections or refractions) on a traced path.
    pub max_bounces: Option<i64>,
    /// Where light samples and fog steps fall: `independent`, `stratified` or `sobol`.
    pub sampler: Option<String>,
    /// Whose light samples they are: `per_point` or `shared` by every point.
    pub sample_pattern: Option<String>,
}

/// `[environment]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEnvironment {
    /// `latlong` (a `map` file, the default), `cube` (`faces` or `cross`) or `gradient` (a procedural sky).
    pub kind: Option<String>,
    /// latlong: the image, relative to the lesson file.
    pub map: Option<String>,
    /// cube: six face images, `px, nx, py, ny, pz, nz`, relative to the lesson file.
    pub faces: Option<Vec<String>>,
    /// cube: one horizontal-cross image, relative to the lesson file.
    pub cross: Option<String>,
    /// Scale on the radiance.
    pub intensity: Option<f64>,
    /// The map's colour that should look neutral (its light's colour): the map is divided by it,
    /// at equal luminance.
    pub white_balance: Option<RawColor>,
    /// Rotation of the sky about +y in degrees.
    pub rotate_deg: Option<f64>,
    /// Draw the environment behind the objects instead of the camera's background colour.
    pub background: Option<bool>,
    /// gradient: radiance straight up.
    pub zenith: Option<RawColor>,
    /// gradient: radiance at the horizon (seen from above).
    pub horizon: Option<RawColor>,
    /// gradient: radiance from below the horizon.
    pub ground: Option<RawColor>,
}

/// `[fog]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFog {
    /// `linear`, `exp`, `exp2` or `medium`.
    pub kind: String,
    /// C_fog of the classic blends.
    pub color: Option<RawColor>,
    /// linear: z where the fog begins.
    pub start: Option<f64>,
    /// linear: z where the fog is complete.
    pub end: Option<f64>,
    /// exp, exp2: density per unit length.
    pub density: Option<f64>,
    /// linear, exp, exp2: `radial` (eye distance) or `depth` (view depth).
    pub distance: Option<String>,
    /// medium: scattering coefficient σ_s per unit length.
    pub sigma_s: Option<f64>,
    /// medium: absorption coefficient σ_a per unit length.
    pub sigma_a: Option<f64>,
    /// medium: Henyey-Greenstein asymmetry g in (−1, 1).
    pub g: Option<f64>,
    /// medium: ray-march steps per sample.
    pub steps: Option<i64>,
    /// medium: how point and spot lights' in-scattering is sampled: `equiangular` or `uniform`.
    pub sampling: Option<String>,
}
