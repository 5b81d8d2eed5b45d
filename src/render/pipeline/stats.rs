//! What a render did: counts of every kind of work, summed over the strips.

use crate::raster::RasterStats;

/// What a render did, returned with every frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Rasterizer counts.
    pub raster: RasterStats,
    /// Visible samples shaded (interpolated or lit).
    pub samples_shaded: u64,
    /// Light evaluations, wherever they ran (vertices, faces or samples).
    pub light_evaluations: u64,
    /// Light evaluations at samples (Phong interpolation only).
    pub light_evaluations_per_sample: u64,
    /// Diffuse-term evaluations (lit side only).
    pub diffuse_evaluations: u64,
    /// Specular-lobe evaluations.
    pub specular_evaluations: u64,
    /// Vertices lit (Gouraud).
    pub vertices_lit: u64,
    /// Faces lit (flat).
    pub faces_lit: u64,
    /// Samples whose shading was not finite (replaced by zero; always 0 unless there is a bug).
    pub nan_samples: u64,
    /// Degenerate mesh triangles found while building normals.
    pub degenerate_mesh_triangles: u64,
    /// Vertex normals repaired.
    pub repaired_normals: u64,
    /// Shadow rays traced.
    pub shadow_rays: u64,
    /// Nodes of the BVH the shadow rays query (0 when none was built).
    pub bvh_nodes: u64,
    /// Shadow-map texels written by the depth pass (covered texels of every face).
    pub shadow_map_texels: u64,
    /// Shadow-map lookups (one per light per shaded point; each filters `shadow_pcf` texels).
    pub shadow_map_lookups: u64,
    /// Samples the fog pass treated (every sample of the image, covered or not).
    pub fog_samples: u64,
    /// Ray-march steps the medium took (samples × steps; 0 for the classic blends).
    pub fog_steps: u64,
    /// Radiosity patches (0 unless `method = "radiosity"`).
    pub patches: u64,
    /// Non-zero radiosity form factors stored.
    pub form_factors: u64,
    /// Radiosity solver iterations.
    pub radiosity_iterations: u64,
    /// Cube-map texels the probe capture rendered (six faces of size² per probe).
    pub probe_texels: u64,
    /// The passes that ran, one [`Pass::bit`](crate::render::plan::Pass::bit) each, set where
    /// each pass's work is done: the plan's [`Plan::running_bits`](crate::render::plan::Plan::running_bits),
    /// less the vertex stage when a kept visibility buffer is shaded again.
    pub passes: u32,
}

impl std::ops::AddAssign<&RenderStats> for RenderStats {
    fn add_assign(&mut self, o: &RenderStats) {
        self.raster += o.raster;
        self.samples_shaded += o.samples_shaded;
        self.light_evaluations += o.light_evaluations;
        self.light_evaluations_per_sample += o.light_evaluations_per_sample;
        self.diffuse_evaluations += o.diffuse_evaluations;
        self.specular_evaluations += o.specular_evaluations;
        self.vertices_lit += o.vertices_lit;
        self.faces_lit += o.faces_lit;
        self.nan_samples += o.nan_samples;
        self.degenerate_mesh_triangles += o.degenerate_mesh_triangles;
        self.repaired_normals += o.repaired_normals;
        self.shadow_rays += o.shadow_rays;
        self.bvh_nodes += o.bvh_nodes;
        self.shadow_map_texels += o.shadow_map_texels;
        self.shadow_map_lookups += o.shadow_map_lookups;
        self.fog_samples += o.fog_samples;
        self.fog_steps += o.fog_steps;
        self.patches += o.patches;
        self.form_factors += o.form_factors;
        self.radiosity_iterations += o.radiosity_iterations;
        self.probe_texels += o.probe_texels;
        self.passes |= o.passes;
    }
}
