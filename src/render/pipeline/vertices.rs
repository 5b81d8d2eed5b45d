//! Gouraud's vertex lighting in lanes: for plain lighting (no sampled or shadowed light, no
//! environment) and classic materials, a run of vertices that share a material is lit
//! sixteen (AVX-512F), eight (AVX) or four at a time with the per-sample bundles' formula,
//! [`shade_classic_lanes`]. Every lane computes what the one-vertex path computes for its
//! vertex (the same view vector, two-sided flip and equation, nothing fused), so the bits
//! are the same (tested: `lit_vertices_in_lanes_are_the_scalar_ones`).

#[cfg(target_arch = "x86_64")]
use super::bundle::bundle_lanes;
use super::bundle::lanes_of;
use crate::scene::Scene;
use crate::shading::Components;
use crate::shading::classic::{EvalCounts, shade_classic_lanes};
use crate::simd::lanes::{F32x4, LaneTask, Lanes, MAX_WIDTH, V3};
use crate::simd::pair::Pair;
use crate::transport::Lighting;
use crate::transport::incidents::plain_incidents;
use glam::Vec3;

/// Whether [`light_vertices`] can light this scene's vertices: plain lighting and classic
/// materials only (the other cases take the one-vertex path, `shade_point`).
pub(super) fn lanes_apply(scene: &Scene, lighting: &Lighting) -> bool {
    lighting.is_plain() && lighting.env.is_none() && scene.materials.iter().all(|m| m.classic().is_some())
}

/// Where [`light_vertices`] writes a run of vertices: their totals and, when a term layer
/// is kept, their terms (the same length).
pub(super) struct VertexOut<'a> {
    /// Each vertex's [`Components::total`].
    pub totals: &'a mut [Vec3],
    /// Each vertex's terms, or nothing (a plain render reads the totals only).
    pub terms: Option<&'a mut [Components]>,
}

/// Lights vertices `first..first + out.totals.len()` into `out` (each vertex with the
/// material `material[i]`, its normal flipped toward the eye when `two_sided`, a non-finite
/// result as zero), counting the evaluations in `k`. Precondition: [`lanes_apply`].
pub(super) fn light_vertices(
    scene: &Scene,
    lighting: &Lighting,
    two_sided: bool,
    material: &[u32],
    first: usize,
    out: VertexOut,
    k: &mut EvalCounts,
) {
    let task = LightVertices { scene, lighting, two_sided, material, first, out, k };
    // The token again (a cached check): only a token runs the AVX lanes.
    #[cfg(target_arch = "x86_64")]
    match bundle_lanes() {
        16 => {
            if let Some(t) = crate::simd::Cpu::get().avx512() {
                return t.run(task);
            }
        }
        8 => {
            if let Some(t) = crate::simd::Cpu::get().avx() {
                return t.run(task);
            }
        }
        _ => {}
    }
    task.run::<Pair<F32x4>, F32x4>()
}

/// [`light_vertices`]' arguments, run in lanes.
struct LightVertices<'a> {
    scene: &'a Scene,
    lighting: &'a Lighting,
    two_sided: bool,
    material: &'a [u32],
    first: usize,
    out: VertexOut<'a>,
    k: &'a mut EvalCounts,
}

impl LaneTask for LightVertices<'_> {
    type Output = ();
    // Inlined into the token's `#[target_feature]` function, as the lanes are.
    #[inline(always)]
    fn run<W: Lanes, H: Lanes>(self) {
        let mut t = self;
        let (material, first, n) = (t.material, t.first, t.out.totals.len());
        let mut j = 0;
        while j < n {
            let m = material[first + j];
            // A run of W vertices with one material takes W lanes; the rest goes one at a time.
            let same = |w: usize| j + w <= n && material[first + j..first + j + w].iter().all(|&x| x == m);
            j += if same(W::WIDTH) {
                t.light::<W>(j)
            } else if same(H::WIDTH) {
                t.light::<H>(j)
            } else {
                t.light::<f32>(j)
            };
        }
    }
}

impl LightVertices<'_> {
    /// Lights vertices `first + j..` in `F::WIDTH` lanes (one material); returns how many.
    #[inline(always)]
    fn light<F: Lanes>(&mut self, j: usize) -> usize {
        let g = &self.scene.geometry;
        let i0 = self.first + j;
        let m = &self.scene.materials[self.material[i0] as usize];
        let classic = m.classic().expect("lanes_apply checked every material is classic");
        let (p, n) = (load::<F>(&g.positions[i0..]), load::<F>(&g.normals[i0..]));
        // As the one-vertex path: the view vector (the normal where the eye is on the vertex),
        // the normal turned toward it when both sides are lit.
        let v = (V3::splat(self.scene.spec.camera.position) - p).normalize_or(n);
        let n = if self.two_sided { V3::select(n.dot(v).lt(F::splat(0.0)), -n, n) } else { n };
        let c = shade_classic_lanes(
            m,
            classic,
            plain_incidents(&self.lighting.lights, p),
            self.scene.spec.ambient,
            n,
            v,
            F::first(F::WIDTH),
            self.k,
        );
        let (e, a, d, s) = (lanes_of(c.emission), lanes_of(c.ambient), lanes_of(c.diffuse), lanes_of(c.specular));
        for l in 0..F::WIDTH {
            let c = Components {
                emission: e[l],
                ambient: a[l],
                diffuse: d[l],
                specular: s[l],
                reflection: Vec3::ZERO,
                transmission: Vec3::ZERO,
            };
            let c = if c.is_finite() { c } else { Components::ZERO };
            self.out.totals[j + l] = c.total();
            if let Some(terms) = self.out.terms.as_deref_mut() {
                terms[j + l] = c;
            }
        }
        F::WIDTH
    }
}

/// `a`'s `F::WIDTH` vectors in lanes. (A function, not a closure: a closure is not compiled
/// with the token function's target features, and its lane loads became calls.)
#[inline(always)]
fn load<F: Lanes>(a: &[Vec3]) -> V3<F> {
    let (mut x, mut y, mut z) = ([0f32; MAX_WIDTH], [0f32; MAX_WIDTH], [0f32; MAX_WIDTH]);
    for (l, v) in a[..F::WIDTH].iter().enumerate() {
        (x[l], y[l], z[l]) = (v.x, v.y, v.z);
    }
    V3 { x: F::load(&x), y: F::load(&y), z: F::load(&z) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::pipeline::tests::MAX_LANES;
    use crate::transport::{At, shade_point};

    /// The one-vertex path of the Gouraud pass (`light_ahead`), the reference.
    fn one_vertex(scene: &Scene, lighting: &Lighting, two_sided: bool, m: u32, i: usize, k: &mut EvalCounts) -> Components {
        let g = &scene.geometry;
        let (p, n) = (g.positions[i], g.normals[i]);
        let v = (scene.spec.camera.position - p).normalize_or(n);
        let n = if two_sided && n.dot(v) < 0.0 { -n } else { n };
        let c = shade_point(&scene.materials[m as usize], lighting, scene.spec.ambient, At::point(p, n), v, k);
        if c.is_finite() { c } else { Components::ZERO }
    }

    #[test]
    fn lit_vertices_in_lanes_are_the_scalar_ones() {
        // Every lane width against the one-vertex path, bit for bit, with materials that
        // change every few vertices (runs shorter and longer than a register), both sides
        // lit or not, and a vertex at the eye (its view vector falls back to the normal).
        // The pipeline tests' scene (a floor, a sphere and a torus under four kinds of plain
        // light), its physically based material made classic.
        let mut scene = crate::render::pipeline::tests::scene(&[]);
        let classic = scene.materials.iter().find(|m| m.classic().is_some()).expect("a classic material").clone();
        for m in scene.materials.iter_mut().filter(|m| m.classic().is_none()) {
            *m = classic.clone();
        }
        scene.spec.camera.position = scene.geometry.positions[100];
        let lighting = Lighting::unshadowed(scene.lights.clone());
        assert!(lanes_apply(&scene, &lighting));
        let n = scene.geometry.positions.len();
        let material: Vec<u32> = (0..n).map(|i| ((i / 7) % 3 == 0) as u32).collect();
        let bits = |c: &Components| [c.emission, c.ambient, c.diffuse, c.specular].map(|v| v.to_array().map(f32::to_bits));
        for two_sided in [false, true] {
            let mut k_one = EvalCounts::default();
            let want: Vec<_> = (0..n).map(|i| bits(&one_vertex(&scene, &lighting, two_sided, material[i], i, &mut k_one))).collect();
            assert!(want.iter().any(|c| c[3] != [0; 3]), "some specular");
            for lanes in [4, 8, 16] {
                MAX_LANES.with(|f| f.set(lanes));
                let (mut out, mut totals) = (vec![Components::ZERO; n - 3], vec![Vec3::NAN; n - 3]);
                let mut k = EvalCounts::default();
                let to = VertexOut { totals: &mut totals, terms: Some(&mut out) };
                light_vertices(&scene, &lighting, two_sided, &material, 3, to, &mut k);
                let mut only = vec![Vec3::NAN; n - 3];
                let to = VertexOut { totals: &mut only, terms: None };
                light_vertices(&scene, &lighting, two_sided, &material, 3, to, &mut EvalCounts::default());
                MAX_LANES.with(|f| f.set(16));
                let got: Vec<_> = out.iter().map(bits).collect();
                assert_eq!(got, want[3..], "{lanes} lanes, two-sided {two_sided}");
                // The totals, with or without the terms, are the terms' `total`.
                let total_bits = |v: &[Vec3]| v.iter().map(|t| t.to_array().map(f32::to_bits)).collect::<Vec<_>>();
                let want_totals: Vec<Vec3> = out.iter().map(Components::total).collect();
                assert_eq!(total_bits(&totals), total_bits(&want_totals), "{lanes} lanes");
                assert_eq!(total_bits(&only), total_bits(&want_totals), "{lanes} lanes, totals only");
                let mut k_want = EvalCounts::default();
                (3..n).for_each(|i| _ = one_vertex(&scene, &lighting, two_sided, material[i], i, &mut k_want));
                assert_eq!((k.lights, k.diffuse, k.specular), (k_want.lights, k_want.diffuse, k_want.specular), "{lanes} lanes");
            }
        }
    }
}
