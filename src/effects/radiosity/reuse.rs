//! Form factors computed once per run: every render, figure cell and `explain` of the same
//! patch mesh with the same form-factor settings shares them (the cells of lesson 27's
//! `bounces` figure differ only in `iterations`, which the form factors do not read). Across
//! runs they are kept in the on-disk cache ([`crate::cache`]) under the same key.
//!
//! The key is exact, not a hash: the patch mesh's positions, triangles and normals as bits,
//! which patches emit (the ray-cast method aims more rays at them), the method, the hemicube's
//! size and the scene's scale. Equal keys give equal rows, so reuse changes no picture. The
//! cost ladders time their renders [`without_reuse`], so a rung's time still includes the
//! form factors it would compute alone.
//!
//! The final gather's rows (F(c_t → j) V(c_t, j) from every patch centre, `display`) read
//! only the patch mesh and the ray queries, not the solution: the cells of `bounces` gathered
//! the same 3,074 rows four times. [`gather_rows`] keeps them per run (in memory only) under
//! the patch mesh's exact key and the ray query's kind.

use super::Patches;
use crate::lesson::settings::FormFactorMethod;
use crate::scene::Scene;
use std::cell::Cell;
use std::sync::{Arc, Mutex};
use web_time::Instant;

/// One row per patch: (j, F_ij) for the non-zero form factors.
pub type Rows = Vec<Vec<(u32, f32)>>;

/// A scene's form factors, and whether an earlier render of this run computed them.
#[derive(Debug, Clone)]
pub struct FormFactors {
    /// The rows.
    pub rows: Arc<Rows>,
    /// The time they took to compute, in milliseconds (when reused: the first time's).
    pub ms: f64,
    /// True when taken from this run's earlier work or the on-disk cache.
    pub reused: bool,
    /// True when read from the on-disk cache (an earlier run computed them).
    pub cached: bool,
}

/// Entries kept: a run's figures use a handful of patch meshes.
const KEEP: usize = 8;

/// (key, form factors) of this run, oldest first.
static DONE: Mutex<Vec<(Vec<u32>, FormFactors)>> = Mutex::new(Vec::new());

thread_local! {
    /// Greater than 0 while this thread's caller wants every form factor computed afresh (a
    /// render bakes on the thread that asked for it; other threads keep reusing).
    static OFF: Cell<usize> = const { Cell::new(0) };
}

/// What the form factors of `scene` (meshed) read.
fn key(scene: &Scene, patches: &Patches) -> Vec<u32> {
    let g = &scene.geometry;
    let r = &scene.spec.settings.radiosity;
    let method = match r.form_factors {
        FormFactorMethod::Hemicube => 0,
        FormFactorMethod::Ray => 1,
    };
    let mut k = vec![method, r.hemicube_size, super::scene_scale(scene).to_bits(), g.positions.len() as u32, g.triangles.len() as u32];
    mesh_key(scene, patches, &mut k);
    k
}

/// The patch mesh's bits: positions, triangles, normals and which patches emit.
fn mesh_key(scene: &Scene, patches: &Patches, k: &mut Vec<u32>) {
    let g = &scene.geometry;
    k.extend(g.positions.iter().flat_map(|p| p.to_array().map(f32::to_bits)));
    k.extend(g.triangles.iter().flatten());
    k.extend(g.face_normals.iter().flat_map(|n| n.to_array().map(f32::to_bits)));
    k.extend(patches.emission.iter().map(|e| (*e != glam::Vec3::ZERO) as u32));
}

/// What the final gather of `scene` (meshed) through a ray query of `kind` reads: the patch
/// mesh, its objects (a render's ray queries are per object) and the query's kind.
fn gather_key(scene: &Scene, patches: &Patches, kind: &str) -> Vec<u32> {
    let g = &scene.geometry;
    let mut k = vec![g.positions.len() as u32, g.triangles.len() as u32, g.objects.len() as u32];
    k.extend(g.objects.iter().flat_map(|o| [o.first_triangle as u32, o.triangles as u32]));
    k.extend(kind.bytes().map(u32::from));
    k.push(u32::MAX);
    mesh_key(scene, patches, &mut k);
    k
}

/// (key, rows) of this run's final gathers, oldest first.
static GATHERED: Mutex<Vec<(Vec<u32>, Arc<Rows>)>> = Mutex::new(Vec::new());

/// The final gather's rows of `scene` (meshed) and its `patches` through ray queries of
/// `kind`: this run's earlier ones when the key matches, else `compute()`'s, kept for later
/// renders of the run (not on disk: the figures that show them are kept whole).
pub fn gather_rows(scene: &Scene, patches: &Patches, kind: &str, compute: impl FnOnce() -> Rows) -> Arc<Rows> {
    let reuse = OFF.with(Cell::get) == 0;
    let k = gather_key(scene, patches, kind);
    if reuse {
        let done = GATHERED.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, rows)) = done.iter().find(|(key, _)| *key == k) {
            return Arc::clone(rows);
        }
    }
    let rows = Arc::new(compute());
    let mut done = GATHERED.lock().unwrap_or_else(|e| e.into_inner());
    done.retain(|(key, _)| *key != k);
    if done.len() >= KEEP {
        done.remove(0);
    }
    done.push((k, Arc::clone(&rows)));
    rows
}

/// The form factors of `scene` (meshed) and its `patches`: this run's earlier ones when the
/// key matches, else an earlier run's from the on-disk cache, else `compute()`'s, kept for
/// later renders and runs.
pub fn cached(scene: &Scene, patches: &Patches, compute: impl FnOnce() -> Rows) -> FormFactors {
    let reuse = OFF.with(Cell::get) == 0;
    let k = key(scene, patches);
    if reuse {
        let done = DONE.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, f)) = done.iter().find(|(key, _)| *key == k) {
            return FormFactors { reused: true, ..f.clone() };
        }
    }
    let disk = crate::cache::dir().map(|_| {
        let bytes: Vec<u8> = k.iter().flat_map(|x| x.to_le_bytes()).collect();
        crate::cache::KeyBuilder::new("form-factors").part(&bytes).finish()
    });
    let kept = disk.as_ref().filter(|_| reuse).and_then(crate::cache::get).and_then(|b| from_bytes(&b));
    let f = match kept {
        Some((rows, ms)) => FormFactors { rows: Arc::new(rows), ms, reused: true, cached: true },
        None => {
            let start = Instant::now();
            let rows = Arc::new(compute());
            let ms = start.elapsed().as_secs_f64() * 1e3;
            if let Some(disk) = disk.filter(|_| ms >= crate::cache::MIN_KEPT_MS) {
                crate::cache::put(&disk, &to_bytes(&rows, ms));
            }
            FormFactors { rows, ms, reused: false, cached: false }
        }
    };
    let mut done = DONE.lock().unwrap_or_else(|e| e.into_inner());
    done.retain(|(key, _)| *key != k);
    if done.len() >= KEEP {
        done.remove(0);
    }
    done.push((k, f.clone()));
    f
}

/// The rows and the time they took, as bytes: the time, then per row its length and its
/// (j, F_ij) pairs, every number little-endian and bit-exact.
fn to_bytes(rows: &Rows, ms: f64) -> Vec<u8> {
    let mut b = ms.to_le_bytes().to_vec();
    for row in rows {
        b.extend((row.len() as u32).to_le_bytes());
        b.extend(row.iter().flat_map(|(j, f)| j.to_le_bytes().into_iter().chain(f.to_le_bytes())));
    }
    b
}

/// [`to_bytes`] read back, or `None` when the bytes are not rows.
fn from_bytes(b: &[u8]) -> Option<(Rows, f64)> {
    let mut r = crate::cache::Reader::new(b);
    let ms = r.f64()?;
    let mut rows = Vec::new();
    while !r.is_done() {
        let n = r.u32()? as usize;
        rows.push((0..n).map(|_| Some((r.u32()?, f32::from_bits(r.u32()?)))).collect::<Option<Vec<_>>>()?);
    }
    Some((rows, ms))
}

/// `f()` with every form factor computed afresh (what a cost ladder times).
pub fn without_reuse<T>(f: impl FnOnce() -> T) -> T {
    OFF.with(|o| o.set(o.get() + 1));
    // Restored even if `f` panics, so a caught panic does not switch reuse off for good.
    struct On;
    impl Drop for On {
        fn drop(&mut self) {
            OFF.with(|o| o.set(o.get() - 1));
        }
    }
    let _on = On;
    f()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::radiosity::{RayQuery, bake, mesh_scene};
    use crate::geometry::bvh::Bvh;
    use crate::lesson::{self, Override};
    use std::path::Path;

    /// Lesson 27's box, coarse, with `sets`.
    fn meshed(sets: &[&str]) -> Scene {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/27-radiosity.toml");
        let mut all = vec!["render.patch_size=1.0", "render.hemicube_size=16"];
        all.extend_from_slice(sets);
        let sets: Vec<Override> = all.iter().map(|s| Override::parse(s).unwrap()).collect();
        mesh_scene(&crate::scene::build::build(&lesson::load(&path, &sets).unwrap()).unwrap())
    }

    /// The bake with the patches' own BVH (effects sit below transport's `SceneRays`).
    fn baked(scene: &Scene) -> crate::effects::radiosity::Baked {
        let g = &scene.geometry;
        bake(scene, &Bvh::build(&g.positions, &g.triangles))
    }

    #[test]
    fn a_second_render_reuses_the_form_factors_and_gives_the_same_bake() {
        let first = baked(&meshed(&["render.iterations=3"]));
        // Another cell of the `bounces` figure: only `iterations` differs.
        let second = baked(&meshed(&["render.iterations=5"]));
        assert!(second.report.form_factors_reused);
        assert_eq!(second.report.form_factors, first.report.form_factors);
        // The same rows: the same bake as a fresh one.
        let fresh = without_reuse(|| baked(&meshed(&["render.iterations=5"])));
        assert!(!fresh.report.form_factors_reused);
        assert_eq!(format!("{:?}", fresh.values), format!("{:?}", second.values));
        assert_ne!(format!("{:?}", first.values), format!("{:?}", second.values), "more bounces, more light");
    }

    #[test]
    fn final_gather_rows_are_kept_per_mesh_and_ray_query() {
        // Its own patch sizes, so no other test's meshes share these keys.
        let scene = meshed(&["render.patch_size=0.9"]);
        let patches = Patches::of(&scene);
        let first = gather_rows(&scene, &patches, "test rays", || vec![vec![(3, 0.5)]]);
        let again = gather_rows(&scene, &patches, "test rays", || vec![vec![(4, 0.25)]]);
        assert!(Arc::ptr_eq(&first, &again), "the same mesh and query: kept");
        // Another ray query, another mesh, or reuse switched off: computed afresh.
        assert!(gather_rows(&scene, &patches, "other rays", Vec::new).is_empty());
        let other = meshed(&["render.patch_size=0.8"]);
        assert!(gather_rows(&other, &Patches::of(&other), "test rays", Vec::new).is_empty());
        assert!(without_reuse(|| gather_rows(&scene, &patches, "test rays", Vec::new)).is_empty());
    }

    #[test]
    fn a_second_render_reuses_the_final_gather_and_gives_the_same_bake() {
        let sets = ["render.patch_size=0.7", "render.final_gather=true", "render.display=\"flat\""];
        let first = baked(&meshed(&[&sets[..], &["render.iterations=4"]].concat()));
        let scene = meshed(&[&sets[..], &["render.iterations=6"]].concat());
        let patches = Patches::of(&scene);
        let g = &scene.geometry;
        let kept = gather_rows(&scene, &patches, Bvh::build(&g.positions, &g.triangles).kind(), || unreachable!("kept by the first bake"));
        assert!(kept.iter().map(Vec::len).sum::<usize>() > 0);
        let second = baked(&scene);
        let fresh = without_reuse(|| baked(&scene));
        assert_eq!(format!("{:?}", fresh.values), format!("{:?}", second.values));
        assert_ne!(format!("{:?}", first.values), format!("{:?}", second.values));
    }

    #[test]
    fn rows_survive_bytes_bit_for_bit() {
        let rows: Rows = vec![vec![(1, 0.25), (7, f32::MIN_POSITIVE)], vec![], vec![(0, 1.0 / 3.0)]];
        let b = to_bytes(&rows, 12.5);
        assert_eq!(from_bytes(&b), Some((rows, 12.5)));
        assert_eq!(from_bytes(&b[..b.len() - 2]), None);
    }

    #[test]
    fn what_the_form_factors_read_is_in_the_key() {
        let base = meshed(&[]);
        let patches = Patches::of(&base);
        let k = key(&base, &patches);
        for sets in [&["render.hemicube_size=32"][..], &["render.form_factors=\"ray\""], &["render.patch_size=0.5"]] {
            let other = meshed(sets);
            assert_ne!(key(&other, &Patches::of(&other)), k, "{sets:?}");
        }
        // The solver and the display do not read the form factors' inputs.
        let solver = meshed(&["render.solver=\"jacobi\"", "render.iterations=2"]);
        assert_eq!(key(&solver, &Patches::of(&solver)), k);
    }
}
