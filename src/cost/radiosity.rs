//! The radiosity ladders: patch size, hemicube resolution and Jacobi iterations (bounces),
//! each against the same lesson solved with that one knob turned far past the last rung.
//!
//! Only the knob moves: the rungs and the reference share the lesson's display, final gather
//! and everything else, so the error is the knob's alone.

use super::rungs::{Ladder, NamedReference, Rung, set};
use crate::lesson::settings::RenderMethod;
use crate::lesson::{LadderKind, Lesson};

/// Patch sizes (longest patch edge, world units) of the `patches` ladder, coarse to fine.
pub const PATCH_SIZES: [f64; 5] = [1.0, 0.5, 0.35, 0.25, 0.2];
/// Patch size of the `patches` reference: finer than every rung and, on lesson 27's box,
/// well under the 8192-patch limit.
pub const REFERENCE_PATCH_SIZE: f64 = 0.14;
/// Hemicube cells per side of the `hemicube` ladder.
pub const HEMICUBE_SIZES: [i64; 4] = [8, 16, 32, 64];
/// Hemicube cells per side of the `hemicube` reference.
pub const REFERENCE_HEMICUBE_SIZE: i64 = 256;
/// Jacobi iterations of the `iterations` ladder: iteration k adds the k-th bounce.
pub const ITERATIONS: [i64; 6] = [0, 1, 2, 4, 8, 16];
/// Jacobi iterations of the `iterations` reference, with tolerance 0: far past the point
/// where an f32 solution of a room of reflectance ≤ 0.75 stops changing.
pub const REFERENCE_ITERATIONS: i64 = 1000;

/// The `patches`, `hemicube` or `iterations` ladder for `lesson`, or why it does not apply.
///
/// # Errors
/// When the lesson is not solved by radiosity (the knobs would change nothing).
///
/// # Panics
/// If `kind` is not one of the three radiosity ladders.
pub fn ladder(kind: LadderKind, lesson: &Lesson) -> Result<Ladder, String> {
    if lesson.scene.settings.method != RenderMethod::Radiosity {
        return Err(format!("the {} ladder needs `[render] method = \"radiosity\"` (only radiosity has patches to solve)", kind.name()));
    }
    let rung = |name: String, sets| Rung { name, sets, exact: false, series: String::new() };
    let reference = |name: String, sets, describe: String| Some(NamedReference { name, sets, exact_area: false, describe });
    let (rungs, reference) = match kind {
        LadderKind::Patches => (
            PATCH_SIZES.iter().map(|p| rung(format!("patch {p:?}"), vec![set("render.patch_size", (*p).into())])).collect(),
            reference(
                format!("patch size {REFERENCE_PATCH_SIZE}"),
                vec![set("render.patch_size", REFERENCE_PATCH_SIZE.into())],
                format!(
                    "the lesson solved with patches of at most {REFERENCE_PATCH_SIZE} units (the lesson's form factors and \
                     solver), rendered by the rasterizer"
                ),
            ),
        ),
        LadderKind::Hemicube => (
            HEMICUBE_SIZES.iter().map(|n| rung(format!("hemicube {n}"), vec![set("render.hemicube_size", (*n).into())])).collect(),
            reference(
                format!("hemicube {REFERENCE_HEMICUBE_SIZE}"),
                vec![set("render.hemicube_size", REFERENCE_HEMICUBE_SIZE.into())],
                format!(
                    "the lesson's patches with form factors from a {REFERENCE_HEMICUBE_SIZE} × {REFERENCE_HEMICUBE_SIZE} \
                     hemicube, rendered by the rasterizer"
                ),
            ),
        ),
        LadderKind::Iterations => {
            // Jacobi so that iteration k is exactly k bounces; tolerance 0 so no rung stops early.
            let jacobi = |k: i64| {
                vec![set("render.solver", "jacobi".into()), set("render.iterations", k.into()), set("render.tolerance", 0.0.into())]
            };
            (
                ITERATIONS.iter().map(|k| rung(format!("iterations {k}"), jacobi(*k))).collect(),
                reference(
                    "converged".into(),
                    jacobi(REFERENCE_ITERATIONS),
                    format!(
                        "the lesson solved by {REFERENCE_ITERATIONS} Jacobi iterations with tolerance 0 (converged to f32 \
                         precision), rendered by the rasterizer"
                    ),
                ),
            )
        }
        _ => panic!("{} is not a radiosity ladder", kind.name()),
    };
    Ok(Ladder { rungs, reference })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::{self, Override};
    use std::path::Path;

    fn box_lesson(sets: &[&str]) -> Lesson {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/27-radiosity.toml");
        let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
        lesson::load(&path, &sets).unwrap()
    }

    fn args(sets: &[Override]) -> Vec<&str> {
        sets.iter().map(|s| s.arg.as_str()).collect()
    }

    #[test]
    fn radiosity_ladders_step_one_knob_in_order_past_their_references() {
        let l = box_lesson(&[]);
        let patches = ladder(LadderKind::Patches, &l).unwrap();
        let names: Vec<&str> = patches.rungs.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["patch 1.0", "patch 0.5", "patch 0.35", "patch 0.25", "patch 0.2"]);
        assert_eq!(args(&patches.rungs[2].sets), ["render.patch_size=0.35"]);
        // Coarse to fine, and the reference finer than the finest rung.
        assert!(PATCH_SIZES.windows(2).all(|w| w[0] > w[1]) && REFERENCE_PATCH_SIZE < PATCH_SIZES[4]);
        assert_eq!(args(&patches.reference.as_ref().unwrap().sets), ["render.patch_size=0.14"]);
        let hemi = ladder(LadderKind::Hemicube, &l).unwrap();
        assert_eq!(
            hemi.rungs.iter().map(|r| r.name.as_str()).collect::<Vec<_>>(),
            ["hemicube 8", "hemicube 16", "hemicube 32", "hemicube 64"]
        );
        assert_eq!(args(&hemi.reference.as_ref().unwrap().sets), ["render.hemicube_size=256"]);
        let it = ladder(LadderKind::Iterations, &l).unwrap();
        assert_eq!(it.rungs.len(), 6);
        // Jacobi (iteration k = k bounces) and tolerance 0 (no rung stops early) in every rung.
        assert_eq!(args(&it.rungs[3].sets), ["render.solver=\"jacobi\"", "render.iterations=4", "render.tolerance=0.0"]);
        let r = it.reference.clone().unwrap();
        assert_eq!(args(&r.sets), ["render.solver=\"jacobi\"", "render.iterations=1000", "render.tolerance=0.0"]);
        assert!(!r.exact_area && r.name == "converged");
        // Every rung and reference validates on lesson 27.
        let all = [patches, hemi, it];
        for sets in all.iter().flat_map(|l| l.rungs.iter().map(|r| &r.sets).chain(l.reference.as_ref().map(|r| &r.sets))) {
            let v = lesson::parse(&l.source, &l.path, sets).unwrap();
            assert_eq!(v.scene.settings.method, RenderMethod::Radiosity);
        }
    }

    #[test]
    fn radiosity_ladders_need_a_radiosity_lesson() {
        let raster = box_lesson(&["render.method=\"raster\""]);
        for kind in [LadderKind::Patches, LadderKind::Hemicube, LadderKind::Iterations] {
            let e = ladder(kind, &raster).unwrap_err();
            assert!(e.contains(kind.name()) && e.contains("method = \"radiosity\""), "{e}");
        }
    }
}
