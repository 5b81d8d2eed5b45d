//! Shadow maps: the two-pass method (Williams 1978). Pass 1 renders depth as seen from the
//! light with the project's own rasterizer; pass 2 looks each shaded point up and compares.
//!
//! - A directional light gets an orthographic map fitted to the scene's vertices as the
//!   light sees them (their box in the light's view, 1% larger), a
//!   spot with a cutoff below 80° one perspective map over its cone, a point light (or a
//!   wider spot) six 90° faces of a cube.
//! - The map holds the rasterizer's reversed depth; a lookup turns its point's biased
//!   distance along the light's axis into the same depth, so the biases are in world units
//!   whatever the projection: a point is lit when `d − shadow_bias − shadow_slope_bias·tan θ`
//!   is no farther than the map's surface (θ between the normal and L, tan θ capped at 10),
//!   after moving it `shadow_normal_offset` texels along its normal.
//! - Percentage-closer filtering (Reeves, Salesin & Cook 1987): the lit share of a box
//!   `shadow_pcf` texels wide centred on the point, each texel's compare weighted by its
//!   overlap with the box. A width of 1 is one bilinearly weighted compare of the four
//!   nearest texels, what a GPU's `sampler2DShadow` with linear filtering returns. A wider
//!   box adds its extra reach × tan θ to the bias (a receiver-plane bias), so the far texels
//!   of the box do not shadow a lit slope.
//! - The artefacts are the lesson: zero bias gives acne (the surface shadows itself between
//!   texel centres), a large bias detaches the shadow (peter-panning), a small map is blocky.
//!   Cube faces are filtered within their face (a seam may show at an edge of the cube).

use crate::lesson::settings::ShadowMapSettings;
use crate::light::{Directional, LightKind, Point, Spot};
use crate::raster::{self, CullMode, DEPTH_TILE, DepthLayout, tiled};
use crate::scene::Scene;
use crate::simd::lanes::{Lanes, MAX_WIDTH, V3};
use glam::{Affine3A, Mat4, Vec2, Vec3, Vec4};
use rayon::prelude::*;
use std::sync::Mutex;

/// The count of shadow-map texels the depth pass wrote (covered texels of every face).
pub const SHADOW_MAP_TEXELS: &str = "shadow-map texels written";
/// Rows per rasterized strip of a map: two rows of tiles.
const STRIP_ROWS: u32 = 2 * TILE as u32;

/// Texels per side of a storage tile.
pub(super) const TILE: usize = DEPTH_TILE;

/// Depth buffers of dropped maps, reused (at most [`POOL_SIZE`] kept).
static POOL: Mutex<Vec<Vec<f32>>> = Mutex::new(Vec::new());

/// Buffers the pool keeps: a cube's six faces.
const POOL_SIZE: usize = 6;

/// A buffer of `len` texels (contents unspecified: every strip clears its part), from the
/// pool when one is large enough.
fn pooled(len: usize) -> Vec<f32> {
    let mut pool = POOL.lock().unwrap_or_else(|e| e.into_inner());
    let mut v = match pool.iter().position(|b| b.capacity() >= len) {
        Some(i) => pool.swap_remove(i),
        None => Vec::with_capacity(len),
    };
    drop(pool);
    v.resize(len, 0.0);
    v
}

impl Drop for Face {
    fn drop(&mut self) {
        let mut pool = POOL.lock().unwrap_or_else(|e| e.into_inner());
        if pool.len() < POOL_SIZE {
            pool.push(std::mem::take(&mut self.depth));
        }
    }
}

/// How a face projects.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Projection {
    /// Orthographic: x in centre.x ± half.x, y in centre.y ± half.y, depth in [near, far].
    Ortho { centre: Vec2, half: Vec2, near: f32, far: f32 },
    /// Perspective: x/d, y/d in [−1/f, 1/f] (f = cot of half the field of view).
    Persp { f: f32, near: f32 },
}

/// One face of a shadow map: the light's view and its depth texels.
#[derive(Debug, Clone)]
struct Face {
    /// World → light view (looking down −z).
    view: Affine3A,
    projection: Projection,
    /// Per texel (in tiles: [`tiled`]), row 0 at the top: the rasterizer's reversed depth of the nearest surface
    /// (near/d for a perspective face, (far − d)/(far − near) for an orthographic one), 0
    /// where none.
    depth: Vec<f32>,
}

/// Where a point falls in a shadow map ([`ShadowMap::lookup`]).
struct Lookup {
    face: usize,
    /// Continuous texel coordinates.
    u: f32,
    w: f32,
    /// The biased depth in the map's reversed depth.
    reference: f32,
    /// The point's (normal-offset) distance along the light's view axis, and after the biases.
    distance: f32,
    biased: f32,
}

/// A map's depth against a point's, as distances along the light's view axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapDepths {
    /// The face looked up (0 for a one-face map; a cube's in `scene::cube::FACE_NAMES` order).
    pub face: usize,
    /// The texel nearest the point.
    pub texel: (i32, i32),
    /// The nearest surface the light sees there (infinite where nothing was drawn).
    pub stored: f32,
    /// The point's own distance (after the normal offset).
    pub point: f32,
    /// The point's distance after the constant and slope biases: in shadow where it exceeds `stored`.
    pub biased: f32,
}

/// A light's shadow map (one face, or six for a cube).
#[derive(Debug, Clone)]
pub struct ShadowMap {
    faces: Vec<Face>,
    /// Texels per side.
    size: u32,
    /// Light position (cube maps pick their face from it).
    position: Vec3,
    settings: ShadowMapSettings,
    /// Texels written by pass 1 (covered texels of every face).
    pub texels_written: u64,
    /// Present when this CPU gathers: lookups in lanes then compare their texels with
    /// AVX-512 gathers (`texels_avx512.rs`) instead of lane by lane.
    avx512: Option<Gathers>,
}

/// The token of the gathered texel compares.
#[cfg(target_arch = "x86_64")]
type Gathers = crate::simd::avx512::Avx512;
/// No gathered form off x86-64.
#[cfg(not(target_arch = "x86_64"))]
type Gathers = ();

/// How many faces light `l`'s map has: six for a point light and a spot wider than 80°, one
/// for a directional light and a narrower spot, none for the other kinds (as [`ShadowMap::render`]).
pub fn faces_for(l: &crate::light::Light) -> usize {
    match l.kind {
        LightKind::Directional(_) => 1,
        LightKind::Spot(Spot { cos_cutoff, .. }) if cos_cutoff > 80f32.to_radians().cos() => 1,
        LightKind::Point(_) | LightKind::Spot(_) => 6,
        _ => 0,
    }
}

impl ShadowMap {
    /// Pass 1: renders the depth of `scene` from light `kind` into `settings.size`² texels per face.
    /// `None` for lights that cast no map (ambient, or the sampled kinds).
    pub fn render(scene: &Scene, kind: &LightKind, settings: ShadowMapSettings) -> Option<ShadowMap> {
        let g = &scene.geometry;
        // The scene's bounding sphere: every object's.
        let (lo, hi) = g.objects.iter().fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), o| {
            (lo.min(o.centre - Vec3::splat(o.radius)), hi.max(o.centre + Vec3::splat(o.radius)))
        });
        let (centre, radius) =
            if g.objects.is_empty() { (Vec3::ZERO, 1.0) } else { ((lo + hi) * 0.5, ((hi - lo) * 0.5).length().max(1e-3)) };
        let views: Vec<(Vec3, Vec3, Vec3, Projection)> = match *kind {
            LightKind::Directional(Directional { direction }) => {
                // Fitted to the scene's vertices seen along the light: every texel on the scene.
                let up = any_up(direction);
                let view = Affine3A::from_mat4(look_along(Vec3::ZERO, direction, up));
                let (lo, hi) = g
                    .positions
                    .par_iter()
                    .map(|&p| view.transform_point3(p))
                    .filter(|v| v.is_finite())
                    .fold(|| (Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
                    .reduce(|| (Vec3::INFINITY, Vec3::NEG_INFINITY), |a, b| (a.0.min(b.0), a.1.max(b.1)));
                if lo.x > hi.x {
                    return None;
                }
                // A margin of 1% (and a floor's zero thickness made some depth range).
                let pad = ((hi - lo).max_element() * 0.01).max(1e-4);
                let half = ((hi - lo).truncate() * 0.5 + Vec2::splat(pad)).max(Vec2::splat(1e-4));
                let centre = (hi + lo).truncate() * 0.5;
                vec![(Vec3::ZERO, direction, up, Projection::Ortho { centre, half, near: -hi.z - pad, far: -lo.z + pad })]
            }
            LightKind::Spot(Spot { position, direction, cos_cutoff, .. }) if cos_cutoff > 80f32.to_radians().cos() => {
                let half = cos_cutoff.acos() * 1.02;
                vec![(
                    position,
                    direction,
                    any_up(direction),
                    Projection::Persp { f: 1.0 / half.tan(), near: near_plane(position, centre, radius) },
                )]
            }
            LightKind::Point(Point { position }) | LightKind::Spot(Spot { position, .. }) => {
                let near = near_plane(position, centre, radius);
                CUBE.iter().map(|&(axis, up)| (position, axis, up, Projection::Persp { f: 1.0, near })).collect()
            }
            _ => return None,
        };
        let position = match *kind {
            LightKind::Point(Point { position }) | LightKind::Spot(Spot { position, .. }) => position,
            _ => Vec3::ZERO,
        };
        let size = settings.size;
        let mut texels_written = 0;
        let faces = views
            .into_iter()
            .map(|(eye, axis, up, projection)| {
                let view = Affine3A::from_mat4(look_along(eye, axis, up));
                let (depth, written) = rasterize_depth(scene, view, projection, size);
                texels_written += written;
                Face { view, projection, depth }
            })
            .collect();
        #[cfg(target_arch = "x86_64")]
        let avx512 = crate::simd::Cpu::get().avx512();
        #[cfg(not(target_arch = "x86_64"))]
        let avx512 = None;
        Some(ShadowMap { faces, size, position, settings, texels_written, avx512 })
    }

    /// Where point `p` (unit geometric normal `ng`, `l` towards the light) falls in the map:
    /// its face, continuous texel coordinates and biased reversed depth; `None` where it is
    /// lit whatever the map holds (behind a perspective face's eye, or not finite).
    fn lookup(&self, p: Vec3, ng: Vec3, l: Vec3) -> Option<Lookup> {
        let s = &self.settings;
        let fi = if self.faces.len() == 6 { cube_face(p - self.position) } else { 0 };
        let face = &self.faces[fi];
        let ng = if ng.dot(l) < 0.0 { -ng } else { ng };
        let size = self.size as f32;
        // Normal offset, in texels of the map at the point's depth.
        let vp = face.view.transform_point3(p);
        let texel = match face.projection {
            Projection::Ortho { half, .. } => 2.0 * half.max_element() / size,
            Projection::Persp { f, .. } => 2.0 * (-vp.z).max(0.0) / (f * size),
        };
        // The offset point q = p + k·n in view space: one more rotation, not a transform.
        let v = vp + face.view.transform_vector3(ng * (s.normal_offset * texel));
        let d = -v.z;
        let (x, y) = match face.projection {
            Projection::Ortho { centre, half, .. } => ((v.x - centre.x) / half.x, (v.y - centre.y) / half.y),
            Projection::Persp { f, .. } => {
                if d <= 0.0 {
                    return None;
                }
                (f * v.x / d, f * v.y / d)
            }
        };
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        let cos = ng.dot(l).clamp(1e-4, 1.0);
        let tan = ((1.0 - cos * cos).sqrt() / cos).min(10.0);
        // The biased depth, in the map's reversed depth (the rasterizer's z/w, decreasing with
        // distance): lit where reference ≥ the texel's value (0 where nothing was drawn).
        // A box wider than one texel compares texels up to (pcf − 1)/2 texels farther away,
        // where a surface tilted by θ to the light lies deeper by that distance × tan θ
        // (the receiver-plane bias of Isidoro 2006, for the box's extra reach): without it
        // wide filters shadow lit slopes.
        let reach = (s.pcf as f32 - 1.0) * 0.5 * texel;
        let biased = d - s.bias - (s.slope_bias + reach) * tan;
        let reference = match face.projection {
            Projection::Ortho { near, far, .. } => (far - biased) / (far - near),
            Projection::Persp { near, .. } if biased > 0.0 => near / biased,
            Projection::Persp { .. } => return None,
        };
        // Continuous texel coordinates: texel i covers [i, i + 1), its centre at i + ½.
        // Clamped far outside the map so the integer conversions below stay exact.
        let (u, w) =
            (((x + 1.0) * 0.5 * size).clamp(-4.0 - size, 2.0 * size + 4.0), ((1.0 - y) * 0.5 * size).clamp(-4.0 - size, 2.0 * size + 4.0));
        Some(Lookup { face: fi, u, w, reference, distance: d, biased })
    }

    /// What the map holds at the texel nearest point `p` against the point's own depth, both
    /// as distances along the light's view axis (`explain --pixel`); `None` where the lookup
    /// finds the point lit whatever the map holds. Nothing drawn at the texel: infinite.
    pub fn depths(&self, p: Vec3, ng: Vec3, l: Vec3) -> Option<MapDepths> {
        let Lookup { face, u, w, distance, biased, .. } = self.lookup(p, ng, l)?;
        let (tx, ty) = (u.floor() as i32, w.floor() as i32);
        let n = self.size as i32;
        let f = &self.faces[face];
        let value = if tx < 0 || ty < 0 || tx >= n || ty >= n {
            0.0
        } else {
            f.depth[tiled(tx as usize, ty as usize, (self.size as usize).div_ceil(TILE))]
        };
        // The reversed depth back to a distance: z/w = near/d (perspective), (far − d)/(far − near) (orthographic).
        let stored = match f.projection {
            _ if value <= 0.0 => f32::INFINITY,
            Projection::Ortho { near, far, .. } => far - value * (far - near),
            Projection::Persp { near, .. } => near / value,
        };
        Some(MapDepths { face, texel: (tx, ty), stored, point: distance, biased })
    }

    /// Pass 2: the lit share in [0, 1] of point `p` (unit geometric normal `ng`, `l` towards the light).
    pub fn visibility(&self, p: Vec3, ng: Vec3, l: Vec3) -> f32 {
        let Some(Lookup { face, u, w, reference, .. }) = self.lookup(p, ng, l) else { return 1.0 };
        let face = &self.faces[face];
        let s = &self.settings;
        let n = self.size as i32;
        let tiles = (self.size as usize).div_ceil(TILE);
        // Outside the map nothing was rendered: lit.
        let lit_at = |tx: i32, ty: i32| -> f32 {
            if tx < 0 || ty < 0 || tx >= n || ty >= n || reference >= face.depth[tiled(tx as usize, ty as usize, tiles)] {
                1.0
            } else {
                0.0
            }
        };
        if s.pcf == 1 {
            // A box one texel wide is the bilinear weighting of the four nearest texel centres.
            let (fu, fw) = (u - 0.5, w - 0.5);
            let (iu, iw) = (floor(fu), floor(fw));
            let (au, aw) = (fu - iu as f32, fw - iw as f32);
            let top = lit_at(iu, iw) * (1.0 - au) + lit_at(iu + 1, iw) * au;
            let bottom = lit_at(iu, iw + 1) * (1.0 - au) + lit_at(iu + 1, iw + 1) * au;
            return (top * (1.0 - aw) + bottom * aw).clamp(0.0, 1.0);
        }
        let half_box = s.pcf as f32 * 0.5;
        let (u0, u1, w0, w1) = (u - half_box, u + half_box, w - half_box, w + half_box);
        let (mut lit, mut total) = (0.0f32, 0.0f32);
        for ty in floor(w0)..=floor(w1) {
            let wy = overlap(ty as f32, w0, w1);
            if wy <= 0.0 {
                continue;
            }
            for tx in floor(u0)..=floor(u1) {
                let wx = overlap(tx as f32, u0, u1);
                if wx > 0.0 {
                    total += wx * wy;
                    lit += wx * wy * lit_at(tx, ty);
                }
            }
        }
        if total > 0.0 { (lit / total).clamp(0.0, 1.0) } else { 1.0 }
    }

    /// True when [`ShadowMap::visibility_lanes`] applies: one face and a one-texel filter.
    #[inline(always)]
    pub fn has_lanes(&self) -> bool {
        self.faces.len() == 1 && self.settings.pcf == 1
    }

    /// [`ShadowMap::visibility`] for lanes of points (precondition: [`ShadowMap::has_lanes`]):
    /// the same formula in lanes up to the four texel fetches, done lane by lane. Lanes where
    /// `reached` is false get 1 (the light adds nothing there anyway).
    #[inline(always)]
    pub fn visibility_lanes<F: Lanes>(&self, p: V3<F>, ng: V3<F>, l: V3<F>, reached: F::Mask) -> F {
        let s = &self.settings;
        let face = &self.faces[0];
        let (zero, one) = (F::splat(0.0), F::splat(1.0));
        let size = self.size as f32;
        let cos_raw = ng.dot(l);
        let ng = V3::select(cos_raw.lt(zero), -ng, ng);
        let vp = affine(&face.view, p);
        let texel = match face.projection {
            Projection::Ortho { half, .. } => F::splat(2.0 * half.max_element() / size),
            Projection::Persp { f, .. } => {
                let d = zero - vp.z;
                F::select(d.gt(zero), d, zero) * F::splat(2.0 / (f * size))
            }
        };
        let v = vp + linear(&face.view, ng).scale(texel * F::splat(s.normal_offset));
        let d = zero - v.z;
        let (x, y, behind) = match face.projection {
            Projection::Ortho { centre, half, .. } => {
                ((v.x - F::splat(centre.x)) / F::splat(half.x), (v.y - F::splat(centre.y)) / F::splat(half.y), F::mask(false))
            }
            Projection::Persp { f, .. } => {
                let safe = F::select(d.gt(zero), d, one);
                (F::splat(f) * v.x / safe, F::splat(f) * v.y / safe, d.le(zero))
            }
        };
        let cos = ng.dot(l);
        let cos = F::select(cos.lt(F::splat(1e-4)), F::splat(1e-4), F::select(cos.gt(one), one, cos));
        let tan = (one - cos * cos).sqrt() / cos;
        let tan = F::select(tan.gt(F::splat(10.0)), F::splat(10.0), tan);
        let biased = d - F::splat(s.bias) - F::splat(s.slope_bias) * tan;
        let (reference, never) = match face.projection {
            Projection::Ortho { near, far, .. } => ((F::splat(far) - biased) / F::splat(far - near), behind),
            Projection::Persp { near, .. } => {
                let ok = biased.gt(zero);
                (F::splat(near) / F::select(ok, biased, one), behind | !ok)
            }
        };
        // Lanes that are lit whatever the map says, or whose coordinates are not finite.
        let lit_anyway = !reached | never | !x.is_finite() | !y.is_finite();
        // Not a closure: a closure is a function of its own, compiled without the AVX of the
        // `run_avx` this inlines into, and its lane operations became calls (perf, `shadow`).
        let (lo, hi) = (F::splat(-4.0 - size), F::splat(2.0 * size + 4.0));
        let half_size = F::splat(0.5 * size);
        let fu = clamp_lanes((x + one) * half_size, lo, hi) - F::splat(0.5);
        let fw = clamp_lanes((one - y) * half_size, lo, hi) - F::splat(0.5);
        // ⌊t⌋ by truncating t + K (positive for every clamped t).
        let k = 2.0 * size + 16.0;
        let (mut iu, mut iw) = ([0i32; MAX_WIDTH], [0i32; MAX_WIDTH]);
        (fu + F::splat(k)).trunc_i32(&mut iu);
        (fw + F::splat(k)).trunc_i32(&mut iw);
        let (mut refs, mut skip) = ([0f32; MAX_WIDTH], [0f32; MAX_WIDTH]);
        reference.store(&mut refs);
        F::select(lit_anyway, one, zero).store(&mut skip);
        // The four texels' lit values (1 where a lane is skipped), and u0, w0 as f32.
        let mut corners = [[1f32; MAX_WIDTH]; 4];
        let (mut fiu, mut fiw) = ([0f32; MAX_WIDTH], [0f32; MAX_WIDTH]);
        let k = k as i32;
        match self.avx512 {
            #[cfg(target_arch = "x86_64")]
            Some(avx512) => {
                let f = super::texels_avx512::Footprints { iu: &iu, iw: &iw, k, reference: &refs, skip: &skip, lanes: F::WIDTH };
                super::texels_avx512::texels_lit(avx512, &face.depth, self.size, &f, &mut corners, &mut fiu, &mut fiw);
            }
            _ => self.texels_lit(face, k, &iu, &iw, &refs, &skip, &mut corners, &mut fiu, &mut fiw, F::WIDTH),
        }
        let (au, aw) = (fu - F::load(&fiu), fw - F::load(&fiw));
        let [t00, t10, t01, t11] = corners.map(|c| F::load(&c));
        let top = t00 * (one - au) + t10 * au;
        let bottom = t01 * (one - au) + t11 * au;
        let v = top * (one - aw) + bottom * aw;
        let v = F::select(v.lt(zero), zero, F::select(v.gt(one), one, v));
        F::select(lit_anyway, one, v)
    }

    /// [`ShadowMap::visibility_lanes`]' texel compares lane by lane (see `texels_avx512.rs`
    /// for the gathered form): 1 where a texel is lit, outside the map or the lane skipped.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn texels_lit(
        &self,
        face: &Face,
        k: i32,
        iu: &[i32; MAX_WIDTH],
        iw: &[i32; MAX_WIDTH],
        refs: &[f32; MAX_WIDTH],
        skip: &[f32; MAX_WIDTH],
        [t00, t10, t01, t11]: &mut [[f32; MAX_WIDTH]; 4],
        fiu: &mut [f32; MAX_WIDTH],
        fiw: &mut [f32; MAX_WIDTH],
        width: usize,
    ) {
        let n = self.size as i32;
        let tiles = (self.size as usize).div_ceil(TILE);
        for j in 0..width {
            let (u0, w0) = (iu[j] - k, iw[j] - k);
            (fiu[j], fiw[j]) = (u0 as f32, w0 as f32);
            if skip[j] != 0.0 {
                continue;
            }
            let r = refs[j];
            let (tu, tw) = (u0 as usize % TILE, w0 as usize % TILE);
            if u0 >= 0 && w0 >= 0 && u0 + 1 < n && w0 + 1 < n && tu + 1 < TILE && tw + 1 < TILE {
                // The four texels in one tile (49 of 64 footprints): one address, one bounds
                // check, the same texels as the general path below.
                let base = tiled(u0 as usize, w0 as usize, tiles);
                let q = &face.depth[base..base + TILE + 2];
                let lit = |d: f32| if r >= d { 1.0 } else { 0.0 };
                (t00[j], t10[j], t01[j], t11[j]) = (lit(q[0]), lit(q[1]), lit(q[TILE]), lit(q[TILE + 1]));
                continue;
            }
            let lit_at = |tx: i32, ty: i32| -> f32 {
                if tx < 0 || ty < 0 || tx >= n || ty >= n || r >= face.depth[tiled(tx as usize, ty as usize, tiles)] { 1.0 } else { 0.0 }
            };
            (t00[j], t10[j], t01[j], t11[j]) = (lit_at(u0, w0), lit_at(u0 + 1, w0), lit_at(u0, w0 + 1), lit_at(u0 + 1, w0 + 1));
        }
    }

    /// This map with its lookups' texels compared lane by lane (the reference of the gathers).
    #[cfg(test)]
    pub(crate) fn without_gathers(mut self) -> ShadowMap {
        self.avx512 = None;
        self
    }

    /// Faces (1, or 6 for a cube).
    pub fn faces(&self) -> usize {
        self.faces.len()
    }
}

/// `t` clamped to [lo, hi], lane by lane.
#[inline(always)]
fn clamp_lanes<F: Lanes>(t: F, lo: F, hi: F) -> F {
    F::select(t.lt(lo), lo, F::select(t.gt(hi), hi, t))
}

/// ⌊x⌋ for |x| < 2³¹ without a libm call (baseline x86-64 has no `roundss`).
#[inline]
fn floor(x: f32) -> i32 {
    let t = x as i32;
    t - (x < t as f32) as i32
}

/// `m` applied to lanes of points.
#[inline(always)]
fn affine<F: Lanes>(m: &Affine3A, p: V3<F>) -> V3<F> {
    let t = m.translation;
    linear(m, p) + V3::splat(Vec3::new(t.x, t.y, t.z))
}

/// `m`'s linear part applied to lanes of vectors.
#[inline(always)]
fn linear<F: Lanes>(m: &Affine3A, v: V3<F>) -> V3<F> {
    let (c0, c1, c2) = (m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis);
    V3 {
        x: F::splat(c0.x) * v.x + F::splat(c1.x) * v.y + F::splat(c2.x) * v.z,
        y: F::splat(c0.y) * v.x + F::splat(c1.y) * v.y + F::splat(c2.y) * v.z,
        z: F::splat(c0.z) * v.x + F::splat(c1.z) * v.y + F::splat(c2.z) * v.z,
    }
}

/// Length of [i, i + 1) ∩ [a, b].
#[inline]
fn overlap(i: f32, a: f32, b: f32) -> f32 {
    ((i + 1.0).min(b) - i.max(a)).max(0.0)
}

/// The cube's faces: the axis each looks along and its up (the OpenGL cube-map convention).
const CUBE: [(Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::NEG_Y),
    (Vec3::NEG_X, Vec3::NEG_Y),
    (Vec3::Y, Vec3::Z),
    (Vec3::NEG_Y, Vec3::NEG_Z),
    (Vec3::Z, Vec3::NEG_Y),
    (Vec3::NEG_Z, Vec3::NEG_Y),
];

/// The cube face that sees direction `d` (its largest component).
#[inline]
fn cube_face(d: Vec3) -> usize {
    let a = d.abs();
    if a.x >= a.y && a.x >= a.z {
        if d.x >= 0.0 { 0 } else { 1 }
    } else if a.y >= a.z {
        if d.y >= 0.0 { 2 } else { 3 }
    } else if d.z >= 0.0 {
        4
    } else {
        5
    }
}

/// World → view for an eye at `eye` looking along unit `axis` (−z in view space) with `up`
/// (as `Camera::view`).
fn look_along(eye: Vec3, axis: Vec3, up: Vec3) -> Mat4 {
    let f = axis;
    let s = f.cross(up).normalize();
    let u = s.cross(f);
    Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
    )
}

/// An up vector not parallel to `axis`.
fn any_up(axis: Vec3) -> Vec3 {
    if axis.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y }
}

/// A near plane for a perspective map from `eye`: close enough to keep every surface of the
/// scene's bounding sphere, far enough for depth precision.
fn near_plane(eye: Vec3, centre: Vec3, radius: f32) -> f32 {
    let gap = (eye - centre).length() - radius;
    if gap > 0.0 { (gap * 0.5).max(1e-3 * radius) } else { 1e-3 * radius }
}

/// Renders the scene's depth from `view` with `projection` into size² texels (reversed
/// depth, 0 where empty) with the rasterizer (no culling: both sides of a surface cast shadows).
/// Returns the texels and how many were covered.
fn rasterize_depth(scene: &Scene, view: Affine3A, projection: Projection, size: u32) -> (Vec<f32>, u64) {
    let g = &scene.geometry;
    // Clip space in the rasterizer's convention: reversed depth, 1 at the near plane.
    let to_clip = |p: Vec3| -> Vec4 {
        let v = view.transform_point3(p);
        match projection {
            // z/w = (far − d)/(far − near), with w = 1: 1 at the near plane, 0 at the far one.
            Projection::Ortho { centre, half, near, far } => {
                Vec4::new((v.x - centre.x) / half.x, (v.y - centre.y) / half.y, (far + v.z) / (far - near), 1.0)
            }
            // As the camera: z_c = near, w_c = −z, so z/w = near/d.
            Projection::Persp { f, near } => Vec4::new(f * v.x, f * v.y, near, -v.z),
        }
    };
    let clip = |i: usize| to_clip(g.positions[i]);
    let setup = raster::setup_with(g.positions.len(), clip, &g.triangles, size, size, STRIP_ROWS, CullMode::None);
    // Stored in tiles of 8 × 8 texels, row after row of tiles: the lookups of neighbouring
    // pixels fall in the same few cache lines whatever the angle between the image and the
    // map (row-major texels spent half of the `shadow` bench waiting on memory). A strip of
    // 16 rows is two rows of tiles, one contiguous chunk; the buffer comes from the pool of
    // dropped maps (a fresh 16 MB allocation cost its page faults every frame).
    let tiles = (size as usize).div_ceil(TILE);
    let mut depth = pooled(tiles * tiles * TILE * TILE);
    let layout = DepthLayout::Tiles { tiles };
    let written: u64 = depth
        .par_chunks_mut(STRIP_ROWS as usize * tiles * TILE)
        .enumerate()
        .map(|(s, out)| {
            // The rasterizer's reversed depth is kept as it is: lookups convert their point.
            setup.depth_strip(s, layout, out);
            // A branch-free sum (it vectorizes; `filter().count()` did not): a strip holds
            // far fewer than 2^32 texels.
            out.iter().map(|&z| (z > 0.0) as u32).sum::<u32>() as u64
        })
        .sum();
    (depth, written)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::lanes::F32x4;
    use std::path::Path;

    /// A sphere over a floor under `light`, mapped at 256² with no bias (acne: lit,
    /// shadowed and partly lit lookups side by side).
    fn map(light: &str) -> (ShadowMap, LightKind) {
        let text = format!(
            r#"[lesson]
title = "t"
[camera]
position = [0, 2, 6]
look_at = [0, -0.5, 0]
[[object]]
shape = "uv_sphere"
material = "m"
[[object]]
shape = "plane"
scale = 3
translate = [0, -1, 0]
material = "m"
[material.m]
model = "lambert"
diffuse = [0.8, 0.2, 0.2]
[[light]]
{light}
[render]
shadows = "map"
shadow_map_size = 256
shadow_bias = 0
shadow_slope_bias = 0
shadow_normal_offset = 0
"#
        );
        let scene = crate::scene::build::build(&crate::lesson::parse(&text, Path::new("t.toml"), &[]).unwrap()).unwrap();
        let kind = scene.lights[0].kind;
        (ShadowMap::render(&scene, &kind, scene.spec.settings.shadow_map).expect("a map"), kind)
    }

    #[test]
    fn gathered_texels_are_the_scalar_texels() {
        // A directional map (fitted to the scene, empty at its edges) and a spot's (the
        // floor reaches past its edges: footprints straddle them).
        let lights = [
            "kind = \"directional\"\ndirection = [-1, -1, -0.5]",
            "kind = \"spot\"\nposition = [1, 3, 1]\ndirection = [-0.3, -1, -0.3]\ncutoff_deg = 30",
        ];
        if crate::simd::Cpu::get().avx512().is_none() {
            // Without the gathers both sides are the lane-by-lane loop: nothing to compare.
            crate::simd::cpu::missing(crate::simd::Level::Avx512, "AVX-512 (texel gathers)");
            return;
        }
        for light in lights {
            let (map, kind) = map(light);
            assert!(map.has_lanes());
            let plain = map.clone().without_gathers();
            let mut next = crate::simd::lanes::test_rng(7, 3.5);
            let (mut seen, mut differ) = ([0u32; 3], 0);
            for i in 0..20_000 {
                // Points on and around the floor and sphere, some outside the map, normals up
                // or random, some lanes not reached.
                let points: [Vec3; 4] = std::array::from_fn(|_| Vec3::new(next(), next() * 0.6 - 0.6, next()));
                let ng = V3::<F32x4>::from_lanes(&std::array::from_fn(|_| {
                    if i % 2 == 0 { Vec3::Y } else { Vec3::new(next(), next(), next()).normalize_or(Vec3::Y) }
                }));
                let l = V3::<F32x4>::from_lanes(&points.map(|p| match kind {
                    LightKind::Directional(Directional { direction }) => -direction,
                    LightKind::Spot(Spot { position, .. }) => (position - p).normalize(),
                    _ => unreachable!("a directional light or a spot"),
                }));
                let p = V3::<F32x4>::from_lanes(&points);
                let reached = F32x4::first(if i % 5 == 0 { 3 } else { 4 });
                let (a, b) = (map.visibility_lanes(p, ng, l, reached), plain.visibility_lanes(p, ng, l, reached));
                for (x, y) in a.to_array().into_iter().zip(b.to_array()) {
                    differ += (x.to_bits() != y.to_bits()) as u32;
                    seen[if y == 0.0 {
                        0
                    } else if y == 1.0 {
                        2
                    } else {
                        1
                    }] += 1;
                }
            }
            assert_eq!(differ, 0, "{light}: lookups differing from the lane-by-lane compares");
            assert!(seen.iter().all(|&n| n > 300), "{light}: shadowed, partly lit and lit lookups: {seen:?}");
        }
    }
}
