//! Tests of the cost ladders: each ladder's rungs, references and when it applies.

use super::*;
use crate::lesson;
use std::path::Path;

/// A fixture of the shadow and area ladders (tests/fixtures/cost), with overrides.
fn fixture(name: &str, sets: &[&str]) -> Lesson {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/cost").join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    let sets: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    lesson::parse(&text, &path, &sets).unwrap()
}

fn names(l: &Ladder) -> Vec<&str> {
    l.rungs.iter().map(|r| r.name.as_str()).collect()
}

#[test]
fn the_docs_list_each_ladders_rungs_in_order() {
    let docs = include_str!("../../docs/accuracy-and-cost.md");
    let format = include_str!("../../docs/lesson-format.md");
    let ladder_key = format.lines().find(|l| l.starts_with("| `ladder` |")).expect("the `ladder` key's row");
    let (shadow, area) = (fixture("shadow.toml", &[]), fixture("area.toml", &[]));
    let fog = fixture("shadow.toml", &[MEDIUM]);
    let env_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/30-image-based-lighting.toml");
    let env = lesson::load(&env_path, &[]).unwrap();
    let rad = lesson::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/27-radiosity.toml"), &[]).unwrap();
    let probe = lesson::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/32-reflection-probes.toml"), &[]).unwrap();
    let tex = lesson::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/33-textures.toml"), &[]).unwrap();
    let glass = lesson::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/31-refraction.toml"), &[]).unwrap();
    let path = lesson::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/42-rasterizer-vs-path-tracer.toml"), &[]).unwrap();
    for kind in LadderKind::ALL {
        let name = kind.name();
        let row = docs.lines().find(|l| l.starts_with(&format!("| `{name}` |"))).unwrap_or_else(|| panic!("no row for {name}"));
        assert!(ladder_key.contains(&format!("`{name}`")), "lesson-format.md's `ladder` row lacks {name}");
        let lesson = match kind {
            LadderKind::AreaSamples | LadderKind::Sampler => &area,
            LadderKind::FogSteps => &fog,
            LadderKind::Ibl | LadderKind::EnvSamples | LadderKind::PrefilterSize => &env,
            LadderKind::Patches | LadderKind::Hemicube | LadderKind::Iterations => &rad,
            LadderKind::Probe => &probe,
            LadderKind::TextureFilter => &tex,
            LadderKind::MaxBounces => &glass,
            LadderKind::Spp | LadderKind::MaxDepth => &path,
            _ => &shadow,
        };
        if matches!(kind, LadderKind::Tessellation | LadderKind::Fresnel) {
            continue; // rungs that depend on the shape or the materials: described, not listed
        }
        let listed = ladder(kind, lesson).unwrap().rungs.iter().map(|r| format!("`{}`", r.name)).collect::<Vec<_>>().join(", ");
        assert!(row.split('|').nth(2).unwrap().contains(&listed), "{row}\nshould list {listed}");
    }
}

#[test]
fn shadow_ladders_step_one_key_with_shadow_maps_and_name_the_ray_cast_reference() {
    let l = fixture("shadow.toml", &[]);
    let map = ladder(LadderKind::ShadowMap, &l).unwrap();
    assert_eq!(names(&map), ["map 256", "map 512", "map 1024", "map 2048", "map 4096"]);
    let args = |r: &Rung| r.sets.iter().map(|s| s.arg.as_str()).collect::<Vec<_>>().join(" ");
    assert_eq!(args(&map.rungs[0]), "render.shadows=\"map\" render.shadow_map_size=256");
    let reference = map.reference.unwrap();
    assert_eq!(reference.sets.iter().map(|s| s.arg.as_str()).collect::<Vec<_>>(), ["render.shadows=\"ray\""]);
    assert!(!reference.exact_area);
    let pcf = ladder(LadderKind::Pcf, &l).unwrap();
    assert_eq!(names(&pcf), ["pcf 1", "pcf 3", "pcf 5", "pcf 9"]);
    let bias = ladder(LadderKind::ShadowBias, &l).unwrap();
    assert_eq!(names(&bias), ["bias 0", "bias 0.001", "bias 0.005", "bias 0.02", "bias 0.1", "bias 0.5"]);
    // The constant bias alone: the slope bias and the normal offset are 0 in every rung.
    assert_eq!(
        args(&bias.rungs[1]),
        "render.shadows=\"map\" render.shadow_slope_bias=0.0 render.shadow_normal_offset=0.0 render.shadow_bias=0.001"
    );
    // Every rung validates.
    for r in map.rungs.iter().chain(&pcf.rungs).chain(&bias.rungs) {
        let sets: Vec<Override> = r.sets.clone();
        lesson::parse(&l.source, &l.path, &sets).unwrap();
    }
}

#[test]
fn area_samples_reference_is_exact_only_when_the_polygon_formula_is() {
    // Nothing blocks the light, rect light, Lambert materials: the polygon formula.
    let open = ladder(LadderKind::AreaSamples, &fixture("area.toml", &["render.shadows=none"])).unwrap();
    assert_eq!(
        names(&open),
        [
            "by area 1",
            "by area 4",
            "by area 16",
            "by area 64",
            "by area 256",
            "by solid angle 1",
            "by solid angle 4",
            "by solid angle 16",
            "by solid angle 64",
            "by solid angle 256"
        ]
    );
    let args = |r: &Rung| r.sets.iter().map(|s| s.arg.as_str()).collect::<Vec<_>>().join(" ");
    assert_eq!(args(&open.rungs[2]), "light.0.sampling=\"area\" light.0.samples=16");
    assert_eq!(args(&open.rungs[7]), "light.0.sampling=\"solid_angle\" light.0.samples=16");
    assert_eq!((open.rungs[2].series.as_str(), open.rungs[7].series.as_str()), ("by area", "by solid angle"));
    let r = open.reference.unwrap();
    assert!(r.exact_area && r.sets.is_empty() && r.describe.contains("Lambert's polygon formula"), "{r:?}");
    // The sphere can shadow the plane: 4096 samples, and the reason why.
    let shadowed = ladder(LadderKind::AreaSamples, &fixture("area.toml", &[])).unwrap().reference.unwrap();
    assert!(!shadowed.exact_area && shadowed.describe.contains("something can block light 0"), "{shadowed:?}");
    assert_eq!(shadowed.sets[0].arg, "light.0.samples=4096");
    // A specular material or a disk light has no closed form here either.
    let glossy = fixture("area.toml", &["render.shadows=none", "material.floor.model=\"blinn_phong\"", "material.floor.specular=0.5"]);
    let r = ladder(LadderKind::AreaSamples, &glossy).unwrap().reference.unwrap();
    assert!(!r.exact_area && r.describe.contains("material `floor` is not diffuse-only"), "{r:?}");
    let rect = fixture("area.toml", &["render.shadows=none"]);
    let text = rect.source.replace("kind = \"rect\"", "kind = \"disk\"").replace("size = [1.0, 1.0]", "radius = 0.5");
    let disk = lesson::parse(&text, &rect.path, &rect.overrides).unwrap();
    let r = ladder(LadderKind::AreaSamples, &disk).unwrap().reference.unwrap();
    assert!(!r.exact_area && r.describe.contains("light 0 is not a rect light"), "{r:?}");
}

#[test]
fn ladders_that_do_not_apply_say_why() {
    let one = fixture("shadow.toml", &[]);
    let mut alone = one.clone();
    alone.objects.truncate(1);
    for kind in [LadderKind::ShadowMap, LadderKind::Pcf, LadderKind::ShadowBias] {
        let e = ladder(kind, &alone).unwrap_err();
        assert!(e.contains(kind.name()) && e.contains("something that can cast a shadow"), "{e}");
    }
    let e = ladder(LadderKind::AreaSamples, &one).unwrap_err();
    assert!(e.contains("sampled light"), "{e}");
    let e = ladder(LadderKind::ShadowMap, &fixture("area.toml", &[])).unwrap_err();
    assert!(e.contains("directional, point or spot"), "{e}");
    // A light with its own method is left alone: nothing for the ladder to change.
    let own = fixture("shadow.toml", &["light.0.shadows=\"ray\""]);
    assert!(ladder(LadderKind::Pcf, &own).is_err());
    // Flat shading interpolates nothing: both spaces give the same image.
    let flat = fixture("shadow.toml", &["render.interpolation=\"flat\""]);
    let e = ladder(LadderKind::InterpolationSpace, &flat).unwrap_err();
    assert!(e.contains("interpolation_space") && e.contains("Gouraud or Phong"), "{e}");
    let e = ladder(LadderKind::NormalTransform, &flat).unwrap_err();
    assert!(e.contains("normal_transform") && e.contains("face normals"), "{e}");
    // The path tracer's ladders need the path tracer.
    for kind in [LadderKind::Spp, LadderKind::MaxDepth] {
        let e = ladder(kind, &one).unwrap_err();
        assert!(e.contains(kind.name()) && e.contains("method = \"path\""), "{e}");
    }
}

/// A scattering medium for the fixtures.
const MEDIUM: &str = "fog={ kind = \"medium\", sigma_s = 0.1, sigma_a = 0.02 }";

#[test]
fn fog_steps_steps_the_march_against_its_reference_and_needs_a_scattering_medium() {
    let l = ladder(LadderKind::FogSteps, &fixture("shadow.toml", &[MEDIUM])).unwrap();
    assert_eq!(
        names(&l),
        ["uniform 4", "uniform 16", "uniform 64", "uniform 256", "equiangular 4", "equiangular 16", "equiangular 64", "equiangular 256"]
    );
    assert_eq!(l.rungs[0].sets[0].arg, "fog.sampling=\"uniform\"");
    assert_eq!(l.rungs[0].sets[1].arg, "fog.steps=4");
    let r = l.reference.unwrap();
    assert_eq!(r.sets[0].arg, "fog.sampling=\"equiangular\"");
    assert_eq!(r.sets[1].arg, format!("fog.steps={FOG_REFERENCE_STEPS}"));
    assert!(!r.exact_area);
    // Four times the best rung's samples, the margin docs/accuracy-and-cost.md states.
    assert_eq!(FOG_REFERENCE_STEPS, 4 * FOG_STEPS[3]);
    // Every rung and the reference validate.
    for sets in l.rungs.iter().map(|r| &r.sets).chain([&r.sets]) {
        let mut all = vec![Override::parse(MEDIUM).unwrap()];
        all.extend(sets.iter().cloned());
        let f = fixture("shadow.toml", &[]);
        lesson::parse(&f.source, &f.path, &all).unwrap();
    }
    for sets in [&[][..], &["fog={ kind = \"exp\", density = 0.1 }"], &["fog={ kind = \"medium\", sigma_s = 0, sigma_a = 0.3 }"]] {
        let e = ladder(LadderKind::FogSteps, &fixture("shadow.toml", sets)).unwrap_err();
        assert!(e.contains("fog_steps") && e.contains("sigma_s > 0"), "{e}");
    }
}

#[test]
fn the_probe_ladder_steps_both_lookups_against_the_traced_reflection_and_needs_a_probe() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/32-reflection-probes.toml");
    let l = ladder(LadderKind::Probe, &lesson::load(&path, &[]).unwrap()).unwrap();
    assert_eq!(names(&l), ["naive 32", "naive 64", "naive 128", "naive 256", "box 32", "box 64", "box 128", "box 256"]);
    let args = |r: &Rung| r.sets.iter().map(|s| s.arg.as_str()).collect::<Vec<_>>().join(" ");
    assert_eq!(args(&l.rungs[5]), "render.reflections=\"probe_box\" probe.0.size=64");
    assert_eq!(l.reference.unwrap().sets[0].arg, "render.reflections=\"traced\"");
    let e = ladder(LadderKind::Probe, &fixture("shadow.toml", &[])).unwrap_err();
    assert!(e.contains("probe") && e.contains("mirror"), "{e}");
}

#[test]
fn the_first_four_ladders_leave_the_reference_to_measure() {
    let l = fixture("shadow.toml", &[]);
    for kind in
        [LadderKind::Interpolation, LadderKind::Tessellation, LadderKind::Aa, LadderKind::InterpolationSpace, LadderKind::NormalTransform]
    {
        assert_eq!(ladder(kind, &l).unwrap().reference, None);
    }
}
