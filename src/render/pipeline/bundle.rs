//! A bundle of one triangle's samples shaded in lanes: Phong with a classic material (the
//! lights' incidents per lane, the course's equation in `shading::classic`) and Gouraud (the
//! lit vertices interpolated), each the scalar formula lane by lane, so the same bits.

use super::dispatch::Renderer;
use super::strip::Totals;
use crate::raster::{Owned, StripTri};
use crate::scene::{Classic, Material};
use crate::shading::Components;
use crate::shading::classic::{EvalCounts, shade_classic_lanes};
use crate::simd::lanes::{Lanes, MAX_WIDTH, V3};
use crate::transport::incidents::{incidents, plain_incidents};
use crate::transport::lighting::{At, LaneIds};
use glam::Vec3;

impl Renderer<'_> {
    /// Phong with classic material `m = (material, its classic model)`: shades the samples `run` of the samples triangle `t`
    /// owns, `F::WIDTH` at a time, with the triangle's vertices in every lane (loaded once)
    /// and the perspective division done for the whole bundle ([`StripTri::resolve`]).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn phong_lanes<F: Lanes>(
        &self,
        t: &StripTri,
        clipped: &[[Vec3; 3]],
        owned: &Owned,
        run: std::ops::Range<usize>,
        m: (&Material, &Classic),
        totals: &mut (impl Totals + ?Sized),
        mut terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        if run.is_empty() {
            return;
        }
        let g = self.g;
        let orig = t.orig as usize;
        let v = g.triangles[orig].map(|i| i as usize);
        let (p, n) = (splat3(&g.positions, v), splat3(&g.normals, v));
        let face = V3::<F>::splat(g.face_normals[orig]);
        let object = g.object_of_triangle(orig);
        for j in run.clone().step_by(F::WIDTH) {
            let (active, b1, b2) = bundle::<F>(t, clipped, owned, j, run.end);
            let index = &owned.index[j..(j + F::WIDTH).min(run.end)];
            self.phong_bundle(m, active, b1, b2, &p, &n, (face, orig as u32, object), index, &mut *totals, terms.as_deref_mut(), k);
        }
    }

    /// Phong with classic material `m`: shades one bundle of samples (perspective-correct
    /// barycentrics b1, b2 and the vertex positions `p`, normals `n` and face normal, index
    /// and object of the lanes' triangle) into `totals[index[lane]]` (and `terms`) for the
    /// lanes in `index`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn phong_bundle<F: Lanes>(
        &self,
        m: (&Material, &Classic),
        active: F::Mask,
        b1: F,
        b2: F,
        p: &[V3<F>; 3],
        n: &[V3<F>; 3],
        triangle: (V3<F>, u32, u32),
        index: &[u32],
        totals: &mut (impl Totals + ?Sized),
        terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        let (pos, normal) = surface_lanes(p, n, b1, b2);
        self.phong_surface(m, active, pos, normal, (triangle.0, triangle.1, triangle.2, None), index, totals, terms, k);
    }

    /// Phong with classic material `m` at lanes of surface points: positions `pos`,
    /// interpolated (not yet renormalized) vertex normals `n_interp`, face normals, and the
    /// triangle and object of every lane (or of each, `per_lane`, when they come from
    /// several triangles), into `totals[index[lane]]` (and `terms`) for the lanes in
    /// `index`. Each lane's bits depend on its own inputs only.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn phong_surface<F: Lanes>(
        &self,
        (m, classic): (&Material, &Classic),
        active: F::Mask,
        pos: V3<F>,
        n_interp: V3<F>,
        (face, tri, object, per_lane): (V3<F>, u32, u32, Option<LaneIds>),
        index: &[u32],
        totals: &mut (impl Totals + ?Sized),
        terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        // Interpolated normals are renormalized per sample (Phong 1975).
        let mut normal = n_interp.normalize_or(face);
        let view = (V3::splat(self.eye) - pos).normalize_or(face);
        if self.two_sided {
            let back = face.dot(view).lt(F::splat(0.0));
            normal = V3::select(back, -normal, normal);
        }
        let c = if self.lighting.is_plain() {
            shade_classic_lanes(m, classic, plain_incidents(&self.lighting.lights, pos), self.scene.spec.ambient, normal, view, active, k)
        } else {
            let at = At { p: pos, n: normal, ng: face, tri, object, per_lane };
            shade_classic_lanes(m, classic, incidents(&self.lighting, &at, active), self.scene.spec.ambient, normal, view, active, k)
        };
        totals.put(c.total(), index);
        if let Some(terms) = terms {
            let (e, a, d, s) = (lanes_of(c.emission), lanes_of(c.ambient), lanes_of(c.diffuse), lanes_of(c.specular));
            for (lane, &i) in index.iter().enumerate() {
                terms[i as usize] = Components {
                    emission: e[lane],
                    ambient: a[lane],
                    diffuse: d[lane],
                    specular: s[lane],
                    reflection: Vec3::ZERO,
                    transmission: Vec3::ZERO,
                };
            }
        }
    }

    /// Gouraud: interpolates the lit vertex values over the samples `run` of the samples
    /// triangle `t` owns, `F::WIDTH` at a time (the vertex values in every lane, loaded once).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn gouraud_lanes<F: Lanes>(
        &self,
        t: &StripTri,
        clipped: &[[Vec3; 3]],
        owned: &Owned,
        run: std::ops::Range<usize>,
        (lit_totals, lit_terms): (&[Vec3], &[Components]),
        totals: &mut (impl Totals + ?Sized),
        mut terms: Option<&mut [Components]>,
    ) {
        if run.is_empty() {
            return;
        }
        let v = self.g.triangles[t.orig as usize].map(|i| i as usize);
        let tot = splat3(lit_totals, v);
        for j in run.clone().step_by(F::WIDTH) {
            let (_, b1, b2) = bundle::<F>(t, clipped, owned, j, run.end);
            // Each layer interpolates its vertex values, as `Vec3 * f32` and `+` do for one sample.
            let b0 = F::splat(1.0) - b1 - b2;
            let index = &owned.index[j..(j + F::WIDTH).min(run.end)];
            totals.put(interpolate(&tot, b0, b1, b2), index);
            if let Some(terms) = terms.as_deref_mut() {
                let c = [lit_terms[v[0]], lit_terms[v[1]], lit_terms[v[2]]];
                let layer = |e: [Vec3; 3]| [V3::<F>::splat(e[0]), V3::splat(e[1]), V3::splat(e[2])];
                let e = lanes_of(interpolate(&layer([c[0].emission, c[1].emission, c[2].emission]), b0, b1, b2));
                let a = lanes_of(interpolate(&layer([c[0].ambient, c[1].ambient, c[2].ambient]), b0, b1, b2));
                let d = lanes_of(interpolate(&layer([c[0].diffuse, c[1].diffuse, c[2].diffuse]), b0, b1, b2));
                let s = lanes_of(interpolate(&layer([c[0].specular, c[1].specular, c[2].specular]), b0, b1, b2));
                for (lane, &i) in index.iter().enumerate() {
                    terms[i as usize] = Components {
                        emission: e[lane],
                        ambient: a[lane],
                        diffuse: d[lane],
                        specular: s[lane],
                        reflection: Vec3::ZERO,
                        transmission: Vec3::ZERO,
                    };
                }
            }
        }
    }
}

/// Lanes `j..j + F::WIDTH` of the samples `t` owns: which lanes hold one (those before
/// `end`), and their perspective-correct barycentrics (b1, b2). Lanes past the end repeat
/// the first sample, so they compute valid values that nobody reads.
#[inline(always)]
pub(super) fn bundle<F: Lanes>(t: &StripTri, clipped: &[[Vec3; 3]], owned: &Owned, j: usize, end: usize) -> (F::Mask, F, F) {
    let active = F::first(end - j);
    let l1 = F::select(active, F::load(&owned.l1[j..]), F::splat(owned.l1[j]));
    let l2 = F::select(active, F::load(&owned.l2[j..]), F::splat(owned.l2[j]));
    let (b1, b2) = t.resolve(clipped, l1, l2);
    (active, b1, b2)
}

/// The position and the interpolated (not yet renormalized) vertex normal at barycentrics
/// (1 − b1 − b2, b1, b2) of a triangle with vertex positions `p` and normals `n` in every
/// lane, as `VisSample::bary` and glam compute them for one sample.
#[inline(always)]
pub(super) fn surface_lanes<F: Lanes>(p: &[V3<F>; 3], n: &[V3<F>; 3], b1: F, b2: F) -> (V3<F>, V3<F>) {
    let b0 = F::splat(1.0) - b1 - b2;
    (interpolate(p, b0, b1, b2), interpolate(n, b0, b1, b2))
}

/// `a[v[0]]`, `a[v[1]]`, `a[v[2]]` in every lane (a triangle's vertex values).
#[inline(always)]
pub(super) fn splat3<F: Lanes>(a: &[Vec3], v: [usize; 3]) -> [V3<F>; 3] {
    [V3::splat(a[v[0]]), V3::splat(a[v[1]]), V3::splat(a[v[2]])]
}

/// a0 b0 + a1 b1 + a2 b2 per lane, as glam computes `a0 * b0 + a1 * b1 + a2 * b2` for one sample.
#[inline(always)]
pub(super) fn interpolate<F: Lanes>(a: &[V3<F>; 3], b0: F, b1: F, b2: F) -> V3<F> {
    a[0].scale(b0) + a[1].scale(b1) + a[2].scale(b2)
}

/// The lanes of `v` as vectors (the first `F::WIDTH` of the array).
#[inline(always)]
pub(super) fn lanes_of<F: Lanes>(v: V3<F>) -> [Vec3; MAX_WIDTH] {
    let (mut x, mut y, mut z) = ([0f32; MAX_WIDTH], [0f32; MAX_WIDTH], [0f32; MAX_WIDTH]);
    v.x.store(&mut x);
    v.y.store(&mut y);
    v.z.store(&mut z);
    std::array::from_fn(|i| Vec3::new(x[i], y[i], z[i]))
}

/// Writes lane `lane` of `v` to `out[index[lane]]` for each of the given sample indices.
#[inline(always)]
pub(super) fn scatter<F: Lanes>(v: V3<F>, index: &[u32], out: &mut [Vec3]) {
    let v = lanes_of(v);
    for (lane, &i) in index.iter().enumerate() {
        out[i as usize] = v[lane];
    }
}

/// The widest lane register this CPU runs, which picks the shading bundles' path: 16 with
/// AVX-512F, 8 with AVX (whose bundles are a pair of eight-lane registers), else 4 (a pair
/// of SSE2 registers; a test on this thread may ask for fewer, to compare widths).
pub(super) fn bundle_lanes() -> usize {
    #[cfg(test)]
    let most = super::tests::MAX_LANES.with(|f| f.get());
    #[cfg(not(test))]
    let most = 16;
    #[cfg(not(target_arch = "x86_64"))]
    let _ = most;
    #[cfg(target_arch = "x86_64")]
    if most >= 16 && crate::simd::Cpu::get().avx512().is_some() {
        return 16;
    }
    #[cfg(target_arch = "x86_64")]
    if most >= 8 && crate::simd::Cpu::get().avx().is_some() {
        return 8;
    }
    4
}
