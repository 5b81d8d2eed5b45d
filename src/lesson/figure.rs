//! Figure specifications from `[[figure]]` tables: which key varies over which values.

use super::path::KeyPath;
use crate::shading::components::Layer;

/// The closed set of figure kinds (the `kind` key); [`FigureBody`] carries each one's keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FigureKind {
    /// One row: the same scene with one key changed per column (e.g. interpolation).
    Compare,
    /// One row: a parameter swept over values.
    Sweep,
    /// Rows × columns: two keys varied together.
    Grid,
    /// One render read out per layer (ambient, diffuse, specular, total).
    Split,
    /// Polar plot of the lobes of materials in the plane of incidence.
    Lobe,
    /// Directional albedo of physically based materials against the angle of incidence.
    Albedo,
    /// A quality ladder: each rung's render above its error heatmap, with times and errors.
    Cost,
    /// Radiosity: each solver's residual against the iteration, on a log scale.
    Convergence,
    /// Chosen pixels explained: the render with each point's vectors and a chart of its terms.
    Probe,
    /// A random walk in a scattering slab: where and in which colour the light leaves.
    Walk,
    /// A rough dielectric's BRDF and BTDF beside the smooth glass: lobes and energy split.
    Bsdf,
    /// Where light leaves a subsurface material's half-space: the walk's R(r) against diffusion.
    Bssrdf,
}

impl FigureKind {
    /// Every kind, in the order messages list them.
    pub const ALL: [FigureKind; 12] = [
        FigureKind::Compare,
        FigureKind::Sweep,
        FigureKind::Grid,
        FigureKind::Split,
        FigureKind::Lobe,
        FigureKind::Albedo,
        FigureKind::Cost,
        FigureKind::Convergence,
        FigureKind::Probe,
        FigureKind::Walk,
        FigureKind::Bsdf,
        FigureKind::Bssrdf,
    ];

    /// The name used in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            FigureKind::Compare => "compare",
            FigureKind::Sweep => "sweep",
            FigureKind::Grid => "grid",
            FigureKind::Split => "split",
            FigureKind::Lobe => "lobe",
            FigureKind::Albedo => "albedo",
            FigureKind::Cost => "cost",
            FigureKind::Convergence => "convergence",
            FigureKind::Probe => "probe",
            FigureKind::Walk => "walk",
            FigureKind::Bsdf => "bsdf",
            FigureKind::Bssrdf => "bssrdf",
        }
    }
}

/// Which normals an overlay draws (`normals = "face"`, `"vertex"` or `"both"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Normals {
    /// One per front-facing triangle, from its centroid.
    Face,
    /// One per visible vertex: the averaged (or weighted) vertex normal.
    Vertex,
    /// Both.
    Both,
}

/// The closed set of quality ladders (a `cost` figure's `ladder`, `shadelab cost --ladder`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LadderKind {
    /// flat → Gouraud → Phong → exact (analytic normals, ray cast).
    Interpolation,
    /// Mesh resolution of the first object, coarse → fine.
    Tessellation,
    /// Supersamples per pixel side: 1, 2, 4, 8.
    Aa,
    /// Schlick's approximation vs the exact dielectric Fresnel (physically based materials).
    Fresnel,
    /// Shadow-map resolution: 256², 512², 1024², 2048², 4096² texels, against ray-cast shadows.
    ShadowMap,
    /// Percentage-closer filter width: 1, 3, 5, 9 texels, against ray-cast shadows.
    Pcf,
    /// Samples per sampled light: 1, 4, 16, 64, 256, placed by area and by solid angle (two
    /// series), against the exact rect-light irradiance (nothing occludes) or 4096 samples.
    AreaSamples,
    /// Where a light's samples fall: independent, stratified and Sobol (three series) at 4, 16
    /// and 64 samples, against the `area_samples` reference.
    Sampler,
    /// Constant shadow-map depth bias: 0, 0.001, 0.005, 0.02, 0.1, 0.5, against ray-cast
    /// shadows (acne at one end, peter-panning at the other).
    ShadowBias,
    /// Screen-space (the course's scanline) → perspective-correct barycentrics.
    InterpolationSpace,
    /// Vertex normals carried by W itself (the mistake) → by (W⁻¹)ᵀ.
    NormalTransform,
    /// Samples along the eye rays of a `[fog] kind = "medium"`: 4 → 256, uniform and
    /// equiangular (two series), against 1024 equiangular samples.
    FogSteps,
    /// Image-based lighting: SH, prefiltered, reference, against the reference at 2048 samples.
    Ibl,
    /// Monte Carlo samples of the environment: 16 → 4096, against 16384.
    EnvSamples,
    /// Width of the prefiltered maps: 32 → 512, against the Monte Carlo reference.
    PrefilterSize,
    /// Radiosity patch size: 1.0 → 0.2 world units, against 0.14.
    Patches,
    /// Radiosity hemicube resolution: 8 → 64 cells a side, against 256.
    Hemicube,
    /// Jacobi iterations (bounces) of radiosity: 0 → 16, against the converged solution.
    Iterations,
    /// Reflection probes: naive and box-projected lookups at 32² → 256² texels a face, against the traced reflection.
    Probe,
    /// Texture filtering: nearest, bilinear, trilinear, against bilinear at 8 × 8 supersamples.
    TextureFilter,
    /// Glass: `max_bounces` 1 → 8, against 16.
    MaxBounces,
    /// The path tracer's paths a pixel sample: `spp` 1 → 256, against 4096.
    Spp,
    /// The path tracer's longest path: `max_depth` 1 → 8, against 64 (with 16 × the paths).
    MaxDepth,
    /// The four hard-shadow methods (ray, map, volume, polygons; four series) as the curved
    /// objects get finer, against ray-cast shadows on the finest meshes.
    ShadowMethods,
}

impl LadderKind {
    /// Every ladder, in the order `cost` runs them by default.
    pub const ALL: [LadderKind; 24] = [
        LadderKind::Interpolation,
        LadderKind::Tessellation,
        LadderKind::Aa,
        LadderKind::Fresnel,
        LadderKind::ShadowMap,
        LadderKind::Pcf,
        LadderKind::AreaSamples,
        LadderKind::Sampler,
        LadderKind::ShadowBias,
        LadderKind::InterpolationSpace,
        LadderKind::NormalTransform,
        LadderKind::FogSteps,
        LadderKind::Ibl,
        LadderKind::EnvSamples,
        LadderKind::PrefilterSize,
        LadderKind::Patches,
        LadderKind::Hemicube,
        LadderKind::Iterations,
        LadderKind::Probe,
        LadderKind::TextureFilter,
        LadderKind::MaxBounces,
        LadderKind::Spp,
        LadderKind::MaxDepth,
        LadderKind::ShadowMethods,
    ];

    /// The name on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            LadderKind::Interpolation => "interpolation",
            LadderKind::Tessellation => "tessellation",
            LadderKind::Aa => "aa",
            LadderKind::Fresnel => "fresnel",
            LadderKind::ShadowMap => "shadow_map",
            LadderKind::Pcf => "pcf",
            LadderKind::AreaSamples => "area_samples",
            LadderKind::Sampler => "sampler",
            LadderKind::ShadowBias => "shadow_bias",
            LadderKind::InterpolationSpace => "interpolation_space",
            LadderKind::NormalTransform => "normal_transform",
            LadderKind::FogSteps => "fog_steps",
            LadderKind::Ibl => "ibl",
            LadderKind::EnvSamples => "env_samples",
            LadderKind::PrefilterSize => "prefilter_size",
            LadderKind::Patches => "patches",
            LadderKind::Hemicube => "hemicube",
            LadderKind::Iterations => "iterations",
            LadderKind::Probe => "probe",
            LadderKind::TextureFilter => "texture_filter",
            LadderKind::MaxBounces => "max_bounces",
            LadderKind::Spp => "spp",
            LadderKind::MaxDepth => "max_depth",
            LadderKind::ShadowMethods => "shadow_methods",
        }
    }

    /// The ladder named `s`, if any.
    pub fn parse(s: &str) -> Option<LadderKind> {
        LadderKind::ALL.into_iter().find(|l| l.name() == s)
    }
}

/// One varied key and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The dotted key that varies (same paths as `--set`).
    pub key: KeyPath,
    /// The values, as TOML (validated when the variants are built).
    pub values: Vec<toml::Value>,
    /// Labels given in the lesson (one per value), if any.
    pub labels: Option<Vec<String>>,
    /// Where the values stand in the lesson file (`figure.N.values`), for error messages.
    pub origin: KeyPath,
}

/// A validated `[[figure]]`: the keys every kind reads, and the kind with its own keys.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureSpec {
    /// File name (letters, digits, `-`, `_`).
    pub name: String,
    /// Title (default: the lesson title, or the chart's or ladder's own).
    pub title: Option<String>,
    /// Caption below the figure.
    pub caption: Option<String>,
    /// Cell size in pixels (default: the camera size); lobe and albedo charts ignore it
    /// (a lesson cannot give them one).
    pub cell: Option<(u32, u32)>,
    /// The kind and the keys only it reads.
    pub body: FigureBody,
    /// compare and sweep: a second row of |difference| heatmaps against the first cell.
    pub diff: bool,
    /// Laid out for a slide of this size (`fit`), if given.
    pub fit: Option<(u32, u32)>,
    /// compare, sweep and grid: the bar that reads a quantity off the cells' greys.
    pub colorbar: Option<ValueBar>,
}

/// `colorbar`: what a figure's greys measure, for the bar under its cells.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueBar {
    /// What is measured, with its unit (`irradiance E (W/m²)`).
    pub label: String,
    /// The linear radiance one unit gives in the cells (ρ/π for a white Lambertian floor
    /// showing irradiance).
    pub radiance_per_unit: f32,
}

/// A figure's kind with the keys that kind reads, so no kind carries another's.
#[derive(Debug, Clone, PartialEq)]
pub enum FigureBody {
    /// One row: the same scene with one key changed per column (e.g. interpolation).
    Compare {
        /// Varied across the columns.
        cols: Axis,
        /// The layer every cell shows.
        layer: Layer,
        /// Normals drawn over each cell.
        normals: Option<Normals>,
    },
    /// One row: a parameter swept over values.
    Sweep {
        /// Varied across the columns.
        cols: Axis,
        /// The layer every cell shows.
        layer: Layer,
        /// Normals drawn over each cell.
        normals: Option<Normals>,
    },
    /// Rows × columns: two keys varied together.
    Grid {
        /// Varied down the rows.
        rows: Axis,
        /// Varied across the columns.
        cols: Axis,
        /// The layer every cell shows.
        layer: Layer,
        /// Normals drawn over each cell.
        normals: Option<Normals>,
    },
    /// One render read out per layer.
    Split {
        /// The columns, in order.
        layers: Vec<Layer>,
        /// Normals drawn over each cell.
        normals: Option<Normals>,
    },
    /// Polar plot of spot lights' distributions I(θ) (a `lobe` figure with `lights`).
    Distribution {
        /// Indices of the lesson's `[[light]]` tables, each a spot.
        lights: Vec<usize>,
    },
    /// Polar plot in the plane of incidence: f·cos θ_o of physically based materials, the
    /// course's I(θ_o) for a unit light of classic ones.
    Lobe {
        /// The materials plotted.
        materials: Vec<String>,
        /// Each material's legend entry (`labels`, else its name).
        legend: Vec<String>,
        /// Angles of incidence in degrees.
        incidence: Vec<f64>,
        /// Azimuths φ_o − φ_i of the outgoing slices in degrees (empty: the plane of incidence).
        azimuth: Vec<f64>,
        /// Also draw each lobe with l and v exchanged in f.
        swap: bool,
        /// Cook-Torrance partial products drawn instead of the whole f (empty: the whole f).
        terms: Vec<crate::shading::cook_torrance::Terms>,
    },
    /// Directional albedo of physically based materials against the angle of incidence.
    Albedo {
        /// The materials plotted.
        materials: Vec<String>,
        /// Each material's legend entry (`labels`, else its name).
        legend: Vec<String>,
    },
    /// A quality ladder: each rung's render above its error heatmap, with times and errors.
    Cost {
        /// The ladder measured.
        ladder: LadderKind,
        /// Timed runs per rung.
        repeat: usize,
    },
    /// Radiosity: the residual of each solver against the iteration (a `method = "radiosity"` lesson).
    Convergence {
        /// The solvers drawn, in legend order.
        solvers: Vec<crate::lesson::settings::Solver>,
        /// Each solver runs until its residual is at most this (default: `[render] tolerance`).
        tolerance: Option<f32>,
    },
    /// Pixels explained (`explain --pixel` as a figure): the render with each probed point's
    /// N, V, L, R and H drawn, and a bar chart of its terms per light.
    Probe {
        /// The probed pixels (x, y), origin top-left, inside the camera's image.
        pixels: Vec<(u32, u32)>,
        /// A key varied across the panels (e.g. `render.interpolation`), each panel the
        /// same pixels explained; `None`: one panel, the lesson as it is.
        cols: Option<Axis>,
    },
    /// A random walk in a slab of isotropic scatterers (`transport::slab`): the exit
    /// directions against Lambert's law and the colour the absorption leaves.
    Walk {
        /// Single-scattering albedo ω per channel.
        albedo: glam::Vec3,
        /// Angle of incidence in degrees.
        incidence: f64,
        /// Walks traced.
        walks: u32,
        /// Optical thickness (`None`: a half-space).
        thickness: Option<f64>,
    },
    /// A rough dielectric boundary (`shading::rough_dielectric`, Walter et al. 2007) at each
    /// roughness: its BSDF lobes in the plane of incidence and its energy split, beside the
    /// smooth glass's Fresnel split.
    Bsdf {
        /// Index of the inside relative to the outside.
        ior: f64,
        /// The roughnesses drawn (α = roughness²).
        roughness: Vec<f64>,
        /// Angle of incidence of the lobes, in degrees.
        incidence: f64,
    },
    /// The radial exit profile R(r) of a subsurface material's half-space, per channel: the
    /// path tracer's random walk against Burley 2015 and the dipole (Jensen et al. 2001).
    Bssrdf {
        /// The principled material with a subsurface radius.
        material: String,
    },
}

impl FigureBody {
    /// A compare figure of `total` cells without normals.
    pub fn compare(cols: Axis) -> FigureBody {
        FigureBody::Compare { cols, layer: Layer::Total, normals: None }
    }

    /// A sweep figure of `total` cells without normals.
    pub fn sweep(cols: Axis) -> FigureBody {
        FigureBody::Sweep { cols, layer: Layer::Total, normals: None }
    }

    /// A grid figure of `total` cells without normals.
    pub fn grid(rows: Axis, cols: Axis) -> FigureBody {
        FigureBody::Grid { rows, cols, layer: Layer::Total, normals: None }
    }

    /// A split figure of these layers without normals.
    pub fn split(layers: Vec<Layer>) -> FigureBody {
        FigureBody::Split { layers, normals: None }
    }

    /// The kind, as named in lesson files.
    pub fn kind(&self) -> FigureKind {
        match self {
            FigureBody::Compare { .. } => FigureKind::Compare,
            FigureBody::Sweep { .. } => FigureKind::Sweep,
            FigureBody::Grid { .. } => FigureKind::Grid,
            FigureBody::Split { .. } => FigureKind::Split,
            FigureBody::Lobe { .. } | FigureBody::Distribution { .. } => FigureKind::Lobe,
            FigureBody::Albedo { .. } => FigureKind::Albedo,
            FigureBody::Cost { .. } => FigureKind::Cost,
            FigureBody::Convergence { .. } => FigureKind::Convergence,
            FigureBody::Probe { .. } => FigureKind::Probe,
            FigureBody::Walk { .. } => FigureKind::Walk,
            FigureBody::Bsdf { .. } => FigureKind::Bsdf,
            FigureBody::Bssrdf { .. } => FigureKind::Bssrdf,
        }
    }
}

/// `"1920x1080"` (or `1920×1080`) as (width, height); `None` if it is not two whole numbers.
pub fn parse_slide_size(s: &str) -> Option<(i64, i64)> {
    let (w, h) = s.trim().split_once(['x', 'X', '×'])?;
    Some((w.trim().parse().ok()?, h.trim().parse().ok()?))
}

impl FigureSpec {
    /// A figure of this name and body with no title or caption and the lesson's cell size:
    /// the base that commands fill in.
    pub fn new(name: &str, body: FigureBody) -> FigureSpec {
        FigureSpec { name: name.into(), title: None, caption: None, cell: None, body, diff: false, fit: None, colorbar: None }
    }

    /// The kind, from the body.
    pub fn kind(&self) -> FigureKind {
        self.body.kind()
    }
}

/// Timed runs per rung of a `cost` figure when the lesson does not say.
pub const DEFAULT_REPEAT: usize = 5;
/// Most timed runs per rung.
pub const MAX_REPEAT: i64 = 1000;
/// Random walks of a `walk` figure when the lesson does not say.
pub const DEFAULT_WALKS: u32 = 200_000;
/// Most random walks of a `walk` figure (about a minute of walking at ω = 1).
pub const MAX_WALKS: u32 = 10_000_000;

/// Most cells a figure may have.
pub const MAX_CELLS: usize = 64;

/// Most pixels a `probe` figure explains (more would not fit its chart).
pub const MAX_PROBES: usize = 8;

/// Parses `A..B:log:N` (N values spaced geometrically), `A..B:lin:N` or `A..B` (integers A to B)
/// into values rounded to 4 significant digits (so labels read `4.884`, not `4.8840234`).
///
/// # Errors
/// A message naming the expected form.
pub fn parse_range(s: &str) -> Result<Vec<f64>, String> {
    let form = "expected A..B, A..B:lin:N or A..B:log:N (e.g. 1..256:log:8)";
    let mut parts = s.split(':');
    let (a, b) = parts.next().and_then(|r| r.split_once("..")).ok_or_else(|| format!("`{s}`: {form}"))?;
    let a: f64 = a.trim().parse().map_err(|_| format!("`{a}` is not a number; {form}"))?;
    let b: f64 = b.trim().parse().map_err(|_| format!("`{b}` is not a number; {form}"))?;
    if !a.is_finite() || !b.is_finite() {
        return Err(format!("`{s}`: the ends must be finite"));
    }
    let values: Vec<f64> = match (parts.next(), parts.next(), parts.next()) {
        (None, None, None) => {
            if a.fract() != 0.0 || b.fract() != 0.0 || b < a || b - a >= MAX_CELLS as f64 {
                return Err(format!("`{s}`: A..B needs integers A ≤ B with at most {MAX_CELLS} values; {form}"));
            }
            (a as i64..=b as i64).map(|v| v as f64).collect()
        }
        (Some(scale), Some(n), None) => {
            let n: usize = n.trim().parse().map_err(|_| format!("`{n}` is not a count; {form}"))?;
            if !(2..=MAX_CELLS).contains(&n) {
                return Err(format!("`{s}`: the count must be 2 to {MAX_CELLS}"));
            }
            let t = |i: usize| i as f64 / (n - 1) as f64;
            match scale.trim() {
                "lin" => (0..n).map(|i| a + (b - a) * t(i)).collect(),
                "log" if a > 0.0 && b > 0.0 => (0..n).map(|i| a * (b / a).powf(t(i))).collect(),
                "log" => return Err(format!("`{s}`: a log range needs positive ends")),
                other => return Err(format!("`{other}` is not lin or log; {form}")),
            }
        }
        _ => return Err(format!("`{s}`: {form}")),
    };
    Ok(values.into_iter().map(round_sig).collect())
}

/// Rounds to 4 significant digits.
fn round_sig(v: f64) -> f64 {
    if v == 0.0 {
        return 0.0;
    }
    let scale = 10f64.powi(3 - v.abs().log10().floor() as i32);
    (v * scale).round() / scale
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges() {
        assert_eq!(parse_range("1..256:log:9").unwrap(), vec![1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 256.0]);
        assert_eq!(parse_range("0..1:lin:5").unwrap(), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(parse_range("3..6").unwrap(), vec![3.0, 4.0, 5.0, 6.0]);
        assert_eq!(parse_range("1..256:log:8").unwrap()[1], 2.208);
        assert!(parse_range("0..1:log:4").is_err());
        assert!(parse_range("1..2:cubic:4").is_err());
        assert!(parse_range("1..x").is_err());
        assert!(parse_range("1..2:lin:1000").is_err());
    }
}
