//! Render settings from the `[render]` table: interpolation and its space, vertex normals,
//! supersampling, exposure, tone map, culling and shadows.

use super::kinds::ShadowMethod;
use crate::geometry::sampler::Sampler;

/// How lighting is interpolated across a triangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Lighting once per face, at its centroid, with the face normal.
    Flat,
    /// Lighting at the vertices, colours interpolated.
    Gouraud,
    /// Normals interpolated and renormalized, lighting per sample.
    #[default]
    Phong,
}

/// Where barycentric weights across a triangle are linear: which weights interpolate the
/// Phong normals and positions and the Gouraud colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InterpolationSpace {
    /// Linear in world space: screen-space weights divided by w (Heckbert & Moreton 1991).
    #[default]
    Perspective,
    /// Linear in screen space, as the course's scanline algorithm interpolates along edges
    /// and spans: no division by w, so attributes slide towards the far end of a triangle
    /// seen at a slant. A teaching option; exact only when the triangle faces the camera.
    Screen,
}

/// How textures are filtered (OpenGL's minification filters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TextureFilter {
    /// The texel under the sample (GL_NEAREST): blocky up close, aliased far away.
    Nearest,
    /// Bilinear between the four nearest texels of the full-size image (GL_LINEAR): smooth up
    /// close, still aliased far away, since no mip level is used.
    Bilinear,
    /// Bilinear in the two mip levels around the sample's footprint, blended (GL_LINEAR_MIPMAP_LINEAR).
    #[default]
    Trilinear,
}

impl TextureFilter {
    /// The names in lesson files.
    pub const CHOICES: [(&'static str, TextureFilter); 3] =
        [("nearest", TextureFilter::Nearest), ("bilinear", TextureFilter::Bilinear), ("trilinear", TextureFilter::Trilinear)];
}

/// How an object's transform W carries its vertex normals into the world.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NormalTransform {
    /// n = (W⁻¹)ᵀ n_l (as the cofactor matrix, the same directions): normals stay
    /// perpendicular to the transformed surface.
    #[default]
    InverseTranspose,
    /// n = W n_l, the mistake: right for rotations and uniform scales, tilted towards the
    /// stretched axis under a non-uniform scale. A teaching option only.
    Naive,
}

/// Tone-mapping operator applied after exposure (`render::develop` has the formulas and
/// what each does to saturated colours).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tonemap {
    /// Clamp to [0, 1], channel by channel.
    #[default]
    Clamp,
    /// x / (1 + x) channel by channel (Reinhard et al. 2002, eq. 3).
    Reinhard,
    /// Narkowicz 2015 fit of the ACES filmic curve, channel by channel.
    Aces,
    /// AgX (Sobotka), Blender 4's default view transform, as Wrensch's analytic fit: the
    /// channels mixed by an inset matrix, a log₂ encoding, a sigmoid, the outset matrix.
    Agx,
}

impl Tonemap {
    /// The name used in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            Tonemap::Clamp => "clamp",
            Tonemap::Reinhard => "reinhard",
            Tonemap::Aces => "aces",
            Tonemap::Agx => "agx",
        }
    }
}

/// Which triangles are discarded by facing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Cull {
    /// Discard triangles facing away from the camera.
    #[default]
    Back,
    /// Keep all; back faces are lit with the flipped normal (two-sided).
    None,
}

/// Everything `[render]` sets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Flat, Gouraud or Phong.
    pub interpolation: Interpolation,
    /// Perspective-correct or screen-space (affine) weights.
    pub interpolation_space: InterpolationSpace,
    /// How textures are filtered.
    pub texture_filter: TextureFilter,
    /// Vertex-normal weighting.
    pub normals: NormalWeighting,
    /// How vertex normals are transformed into the world.
    pub normal_transform: NormalTransform,
    /// Supersamples per pixel side (aa² samples per pixel).
    pub aa: u32,
    /// Exposure in stops: radiance × 2^exposure before tone mapping.
    pub exposure: f32,
    /// Tone map.
    pub tonemap: Tonemap,
    /// Face culling.
    pub cull: Cull,
    /// How lights find what blocks them, unless a light says otherwise.
    pub shadows: ShadowMethod,
    /// The shadow-map keys (`shadow_map_size`, `shadow_bias`, ...), read when a light uses `map`.
    pub shadow_map: ShadowMapSettings,
    /// How the environment lights materials.
    pub ibl: Ibl,
    /// Monte Carlo samples of the environment per shaded point (`ibl = "reference"`).
    pub env_samples: u32,
    /// Width in texels of the first convolved level of the specular chain (`ibl = "prefiltered"` or `"sh"`).
    pub prefilter_size: u32,
    /// Glass: most interface events (a reflection or a refraction each) on one traced path;
    /// a ray that would need one more contributes nothing.
    pub max_bounces: u32,
    /// `raster` (the direct renderer) or `radiosity` (interreflection between diffuse patches).
    pub method: RenderMethod,
    /// The radiosity keys (`patch_size`, `hemicube_size`, `solver`, ...), read when `method = "radiosity"`.
    pub radiosity: RadiositySettings,
    /// The path tracer's keys (`spp`, `max_depth`), read when `method = "path"`.
    pub path: PathSettings,
    /// How a mirror finds what it reflects: its traced ray, or a `[[probe]]` (naive or box-projected).
    pub reflections: Reflections,
    /// Where the samples of area, line and sky lights and of the fog's in-scattering fall.
    pub sampler: Sampler,
    /// Whether each shaded point has its own light samples or all share one pattern.
    pub sample_pattern: crate::geometry::sampler::SamplePattern,
    /// Not a lesson key: rect lights give their exact unoccluded irradiance instead of samples
    /// (`transport::incidents::Lighting::exact_area`), for the `area_samples` cost ladder's reference.
    pub area_reference: bool,
}

/// The shadow-map keys of `[render]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowMapSettings {
    /// Texels per side of each map (a point light has six).
    pub size: u32,
    /// Constant depth bias, in world units along the light's axis.
    pub bias: f32,
    /// Slope-scaled bias: this × tan θ (θ between the normal and L), in world units.
    pub slope_bias: f32,
    /// Normal offset: the looked-up point moves this many texels along the normal.
    pub normal_offset: f32,
    /// Percentage-closer filter width in texels (1: one bilinearly weighted compare).
    pub pcf: u32,
}

impl Default for ShadowMapSettings {
    fn default() -> Self {
        ShadowMapSettings { size: 1024, bias: 0.005, slope_bias: 0.01, normal_offset: 1.0, pcf: 1 }
    }
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            interpolation: Interpolation::Phong,
            interpolation_space: InterpolationSpace::Perspective,
            texture_filter: TextureFilter::Trilinear,
            normals: NormalWeighting::Average,
            normal_transform: NormalTransform::InverseTranspose,
            aa: 1,
            exposure: 0.0,
            tonemap: Tonemap::Clamp,
            cull: Cull::Back,
            shadows: ShadowMethod::Ray,
            shadow_map: ShadowMapSettings::default(),
            method: RenderMethod::Raster,
            radiosity: RadiositySettings::default(),
            path: PathSettings::default(),
            area_reference: false,
            ibl: Ibl::Prefiltered,
            env_samples: 1024,
            prefilter_size: 256,
            max_bounces: 8,
            reflections: Reflections::Traced,
            sampler: Sampler::Sobol,
            sample_pattern: crate::geometry::sampler::SamplePattern::PerPoint,
        }
    }
}

/// How a mirror finds the radiance it reflects (`[render] reflections`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reflections {
    /// The reflected ray through the scene's BVH: exact, the reference.
    #[default]
    Traced,
    /// The probe's cube map along R (the probe seen as infinitely far: no parallax).
    Probe,
    /// The probe's cube map along R' = P − C, P where R leaves the probe's box (parallax
    /// corrected: Lagarde & Zanuttini 2012).
    ProbeBox,
    /// The probe's capture read as if it stood at its `moved_to` C′, along s′ = P − C with P
    /// where R from C′ leaves the box (the course's moved probe).
    ProbeMoved,
    /// The probe as a light projector: R traced to the nearest surface x, whose radiance is
    /// read from the capture along s = x − C (what the probe recorded there).
    ProbeProjector,
}

impl Reflections {
    /// Every method with its name in lesson files.
    pub const NAMES: [(&'static str, Reflections); 5] = [
        ("traced", Reflections::Traced),
        ("probe", Reflections::Probe),
        ("probe_box", Reflections::ProbeBox),
        ("probe_moved", Reflections::ProbeMoved),
        ("probe_projector", Reflections::ProbeProjector),
    ];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            Reflections::Traced => "traced",
            Reflections::Probe => "probe",
            Reflections::ProbeBox => "probe_box",
            Reflections::ProbeMoved => "probe_moved",
            Reflections::ProbeProjector => "probe_projector",
        }
    }
}

/// How the environment lights a material (`[render] ibl`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ibl {
    /// Diffuse irradiance from nine spherical-harmonic coefficients, specular by the split sum.
    Sh,
    /// Diffuse irradiance from a convolved low-resolution map, specular by the split sum
    /// (prefiltered GGX levels and the specular albedo table).
    #[default]
    Prefiltered,
    /// Monte Carlo integration of L_i f cos over the sphere, importance-sampled on the
    /// map's luminance and on the BRDF, combined by multiple importance sampling.
    Reference,
}

impl Ibl {
    /// Every method with its name in lesson files.
    pub const NAMES: [(&'static str, Ibl); 3] = [("sh", Ibl::Sh), ("prefiltered", Ibl::Prefiltered), ("reference", Ibl::Reference)];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            Ibl::Sh => "sh",
            Ibl::Prefiltered => "prefiltered",
            Ibl::Reference => "reference",
        }
    }
}

/// `[render] method`: how light reaches the surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RenderMethod {
    /// The direct renderer: the lights' incidents at each shaded point, plus the ambient term.
    #[default]
    Raster,
    /// Radiosity: the surfaces split into patches that exchange light (Goral et al. 1984).
    Radiosity,
    /// Unidirectional path tracing (Kajiya 1986) with next-event estimation and multiple
    /// importance sampling (Veach 1997): every light path up to `max_depth` segments.
    Path,
}

impl RenderMethod {
    /// Every method with its name in lesson files.
    pub const NAMES: [(&'static str, RenderMethod); 3] =
        [("raster", RenderMethod::Raster), ("radiosity", RenderMethod::Radiosity), ("path", RenderMethod::Path)];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            RenderMethod::Raster => "raster",
            RenderMethod::Radiosity => "radiosity",
            RenderMethod::Path => "path",
        }
    }
}

/// `[render] caustics`: how the path tracer finds light focused by mirrors and glass onto
/// the surfaces the camera sees.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Caustics {
    /// By the camera's paths alone: a path must pass through the glass and happen to hit the lamp.
    #[default]
    Path,
    /// By a caustic photon map (Jensen 1996): photons traced from the lamps through mirrors and
    /// glass, gathered where the camera's paths first meet a surface that is not a mirror.
    Photons,
}

impl Caustics {
    /// Every choice with its name in lesson files.
    pub const NAMES: [(&'static str, Caustics); 2] = [("path", Caustics::Path), ("photons", Caustics::Photons)];
}

/// `[render] indirect`: how the path tracer finds light reflected by diffuse surfaces
/// (indirect illumination).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Indirect {
    /// By the camera's paths: each bounce samples the BRDF and goes on (Kajiya 1986).
    #[default]
    Path,
    /// By a global photon map (Jensen 1996) read through a final gather: the path ends at its
    /// first diffuse vertex, where `gather_rays` rays read the map where they land.
    Photons,
    /// None: the path ends at its first diffuse vertex after direct light (local illumination).
    None,
}

impl Indirect {
    /// Every choice with its name in lesson files.
    pub const NAMES: [(&'static str, Indirect); 3] = [("path", Indirect::Path), ("photons", Indirect::Photons), ("none", Indirect::None)];
}

/// `[render] photon_gather`: which photons a radiance estimate reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PhotonGather {
    /// Every photon within a fixed radius (`photon_radius`, `global_radius`).
    #[default]
    Radius,
    /// The `photon_nearest` nearest photons, the radius set by the farthest of them and capped
    /// by the fixed one (Jensen 2001, §7.2).
    Nearest,
}

impl PhotonGather {
    /// Every choice with its name in lesson files.
    pub const NAMES: [(&'static str, PhotonGather); 2] = [("radius", PhotonGather::Radius), ("nearest", PhotonGather::Nearest)];
}

/// The path tracer's keys of `[render]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSettings {
    /// Paths per pixel sample (`aa`² samples a pixel, so `aa`² × `spp` paths a pixel).
    pub spp: u32,
    /// The longest path in segments from the camera, as Mitsuba counts: 1 sees only
    /// emitters, 2 adds direct light, 3 one indirect bounce, ...
    pub max_depth: u32,
    /// How caustics are found.
    pub caustics: Caustics,
    /// Photons emitted for the caustic map (`caustics = "photons"`).
    pub photons: u32,
    /// The radius photons are gathered within, in world units.
    pub photon_radius: f32,
    /// How indirect diffuse light is found.
    pub indirect: Indirect,
    /// Final-gather rays a first diffuse vertex sends (`indirect = "photons"`); 0 reads the
    /// global map there directly.
    pub gather_rays: u32,
    /// Photons emitted for the global map (`indirect = "photons"`).
    pub global_photons: u32,
    /// The radius the global map is gathered within, in world units.
    pub global_radius: f32,
    /// Fixed radius or k nearest photons.
    pub photon_gather: PhotonGather,
    /// k of the k-nearest gather.
    pub photon_nearest: u32,
}

impl Default for PathSettings {
    fn default() -> Self {
        PathSettings {
            spp: 16,
            max_depth: 16,
            caustics: Caustics::Path,
            photons: 200_000,
            photon_radius: 0.05,
            indirect: Indirect::Path,
            gather_rays: 32,
            global_photons: 100_000,
            global_radius: 0.2,
            photon_gather: PhotonGather::Radius,
            photon_nearest: 50,
        }
    }
}

/// How radiosity finds the form factors F_ij.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FormFactorMethod {
    /// The hemicube of Cohen and Greenberg (1985), rendered by the project's rasterizer.
    #[default]
    Hemicube,
    /// Point-to-patch: Lambert's polygon form factor from the patch centre, times the
    /// fraction of rays that reach the patch.
    Ray,
}

/// Which radiosity solver iterates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Solver {
    /// Gathering, every patch from the previous sweep's values.
    Jacobi,
    /// Gathering, every patch from the newest values.
    #[default]
    GaussSeidel,
    /// Shooting the largest unshot power first (Cohen et al. 1988).
    Progressive,
}

impl Solver {
    /// Every solver, in the order messages and charts list them.
    pub const ALL: [Solver; 3] = [Solver::Jacobi, Solver::GaussSeidel, Solver::Progressive];

    /// The name used in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            Solver::Jacobi => "jacobi",
            Solver::GaussSeidel => "gauss_seidel",
            Solver::Progressive => "progressive",
        }
    }
}

/// How the patch radiosities are displayed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RadiosityDisplay {
    /// One colour per patch.
    Flat,
    /// Vertex radiosities (the area-weighted mean of the patches around a vertex), interpolated.
    #[default]
    Gouraud,
}

/// The radiosity keys of `[render]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadiositySettings {
    /// Longest patch edge, in world units.
    pub patch_size: f32,
    /// Hemicube or ray-cast form factors.
    pub form_factors: FormFactorMethod,
    /// Hemicube resolution: cells per side of the top face.
    pub hemicube_size: u32,
    /// Jacobi, Gauss-Seidel or progressive refinement.
    pub solver: Solver,
    /// Most iterations (sweeps; for progressive refinement, one iteration is N shots).
    pub iterations: u32,
    /// Stop once the relative residual Σ A|E + ρFL − L| / Σ A L is at most this.
    pub tolerance: f32,
    /// Flat or Gouraud display.
    pub display: RadiosityDisplay,
    /// Gather once more at every displayed point from all patches, with ray-cast visibility.
    pub final_gather: bool,
    /// Progressive refinement: add the ambient estimate of the unshot power to the display.
    pub ambient_correction: bool,
}

impl Default for RadiositySettings {
    fn default() -> Self {
        RadiositySettings {
            patch_size: 0.25,
            form_factors: FormFactorMethod::Hemicube,
            hemicube_size: 64,
            solver: Solver::GaussSeidel,
            iterations: 100,
            tolerance: 1e-4,
            display: RadiosityDisplay::Gouraud,
            final_gather: false,
            ambient_correction: false,
        }
    }
}

/// How a vertex normal weights the normals of the faces around it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NormalWeighting {
    /// Plain average of adjacent unit face normals (the course's definition).
    #[default]
    Average,
    /// Weighted by face area (the unnormalized cross product).
    Area,
    /// Weighted by the face's interior angle at the vertex (Thürmer & Wüthrich 1998).
    Angle,
}
