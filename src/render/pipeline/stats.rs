//! What a render did: counts of every kind of work, summed over the strips.
//!
//! The pipeline's own counts are fields; each optional pass reports its work as labelled
//! [`Counters`] (the label a constant beside the pass, e.g. `transport::visibility::SHADOW_RAYS`),
//! which `explain` prints without knowing the pass: a new effect adds a label, not a field.

use crate::raster::RasterStats;

/// The most labelled counters one render keeps (a fixed array keeps [`RenderStats`] `Copy`).
pub const MAX_COUNTERS: usize = 16;

/// Work counts of the optional passes, each under its label, in the order first counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Counters {
    entries: [(&'static str, u64); MAX_COUNTERS],
    len: usize,
}

impl Default for Counters {
    fn default() -> Self {
        Counters { entries: [("", 0); MAX_COUNTERS], len: 0 }
    }
}

impl Counters {
    /// Adds `n` to the count labelled `label` (a new label goes after the others).
    ///
    /// # Panics
    /// When a render counts more than [`MAX_COUNTERS`] labels (raise the constant).
    pub fn add(&mut self, label: &'static str, n: u64) {
        if let Some(e) = self.entries[..self.len].iter_mut().find(|e| e.0 == label) {
            e.1 += n;
            return;
        }
        assert!(self.len < MAX_COUNTERS, "more than {MAX_COUNTERS} labelled counters: raise MAX_COUNTERS");
        self.entries[self.len] = (label, n);
        self.len += 1;
    }

    /// The count labelled `label` (0 when nothing was counted under it).
    pub fn get(&self, label: &str) -> u64 {
        self.entries[..self.len].iter().find(|e| e.0 == label).map_or(0, |e| e.1)
    }

    /// Every label with its count, in the order first counted.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, u64)> + '_ {
        self.entries[..self.len].iter().copied()
    }
}

impl std::ops::AddAssign<&Counters> for Counters {
    fn add_assign(&mut self, o: &Counters) {
        for (label, n) in o.iter() {
            self.add(label, n);
        }
    }
}

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
    /// The optional passes' work, labelled ([`Counters`]).
    pub counters: Counters,
    /// The passes that ran, one [`Pass::bit`](crate::render::plan::Pass::bit) each, set where
    /// each pass's work is done: the plan's [`Plan::running_bits`](crate::render::plan::Plan::running_bits),
    /// less the vertex stage when a kept visibility buffer is shaded again.
    pub passes: u32,
}

/// Adds a strip's or a lighting pass's shadow work to `counters` (nothing when there was none).
pub fn count_shadows(counters: &mut Counters, c: crate::transport::ShadowCounts) {
    use crate::effects::shadows::{polygons::POLYGON_TESTS, volume::VOLUME_QUAD_TESTS};
    use crate::transport::visibility::{SHADOW_MAP_LOOKUPS, SHADOW_RAYS};
    for (label, n) in
        [(SHADOW_RAYS, c.rays), (SHADOW_MAP_LOOKUPS, c.lookups), (VOLUME_QUAD_TESTS, c.volume_tests), (POLYGON_TESTS, c.polygon_tests)]
    {
        if n > 0 {
            counters.add(label, n);
        }
    }
}

impl RenderStats {
    /// The labelled count `label` ([`Counters::get`]).
    pub fn count(&self, label: &str) -> u64 {
        self.counters.get(label)
    }
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
        self.counters += &o.counters;
        self.passes |= o.passes;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counters_add_by_label_keep_their_first_order_and_sum_across_strips() {
        let (mut a, mut b) = (Counters::default(), Counters::default());
        a.add("shadow rays traced", 3);
        a.add("fog: ray-march steps", 10);
        b.add("fog: ray-march steps", 5);
        b.add("radiosity patches", 7);
        a.add("shadow rays traced", 1);
        a += &b;
        assert_eq!(a.iter().collect::<Vec<_>>(), [("shadow rays traced", 4), ("fog: ray-march steps", 15), ("radiosity patches", 7)]);
        assert_eq!((a.get("radiosity patches"), a.get("never counted")), (7, 0));
    }
}
