//! `--set`, `--vary` and the shorthand flags, and figures naming what the lesson has; plus the
//! `--set`s that should work.

use super::{BASE, Workspace, append, edit, fails};
use crate::helpers::shadelab;

// ---- --set and shorthand flags ---------------------------------------------------------------

#[test]
fn set_unknown_key() {
    Workspace::new(BASE)
        .render_fails(&["--set", "material.plastic.shininez=3"])
        .says("lesson.toml: in --set material.plastic.shininez=3: ")
        .key("material.plastic.shininez")
        .says("unknown key `shininez`")
        .hint("did you mean `shininess`?");
    // A typo in a list name is an unknown key too, not a complaint about indices.
    Workspace::new(BASE)
        .render_fails(&["--set", "lighht.0.intensity=2"])
        .says("in --set lighht.0.intensity=2: ")
        .key("lighht")
        .hint("did you mean `light`?");
    // A key under a table the --set created is blamed on the --set, not the file.
    Workspace::new(BASE).render_fails(&["--set", "render.foo.bar=1"]).says("in --set render.foo.bar=1: ").key("render.foo");
}

#[test]
fn set_bad_value() {
    let ws = Workspace::new(BASE);
    ws.render_fails(&["--set", "material.plastic.shininess=abc"])
        .says("in --set material.plastic.shininess=abc: ")
        .key("material.plastic.shininess")
        .says("expected a number");
    ws.render_fails(&["--set", "material.plastic.shininess=-3"])
        .says("in --set material.plastic.shininess=-3: ")
        .says("-3 is out of range");
    ws.render_fails(&["--set", "material.plastic.model=phongg"])
        .says("in --set material.plastic.model=phongg: ")
        .hint("did you mean `phong`?");
    // The last --set of a key wins, and is the one blamed.
    ws.render_fails(&["--set", "light.0.intensity=2", "--set", "light.0.intensity=-1"]).says("in --set light.0.intensity=-1: ");
    ws.render_fails(&["--set", "camera.position.x=1"]).says("`camera.position` is an array, not a table");
}

#[test]
fn set_misspelt_material_name() {
    // Not "missing required key `model`": the name is the mistake.
    Workspace::new(BASE)
        .render_fails(&["--set", "material.plastik.shininess=3"])
        .says("in --set material.plastik.shininess=3: ")
        .key("material.plastik")
        .says("the lesson has no material `plastik`")
        .hint("did you mean `plastic`?")
        .hint("also set its model");
    // Defining a material with --set still works, in either order.
    let ws = Workspace::new(BASE);
    ws.render_ok(&["--set", "material.matte.model=lambert", "--set", "object.0.material=matte"]);
    ws.render_ok(&["--set", "material.matte.diffuse=0.3", "--set", "material.matte.model=lambert", "--set", "object.0.material=matte"]);
    Workspace::new(BASE)
        .render_fails(&["--set", "object.3.material=plastic"])
        .says("`object` has 1 entry (index 0), so there is no `object.3`");
}

#[test]
fn set_value_that_is_broken_toml() {
    let ws = Workspace::new(BASE);
    ws.render_fails(&["--set", "material.plastic.shininess=[1,2"])
        .says("in --set material.plastic.shininess=[1,2: ")
        .says("the value `[1,2` starts like an array but is not valid TOML")
        .hint("closing `]`");
    ws.render_fails(&["--set", "light.0={ kind = \"point\""]).says("starts like an inline table").hint("closing `}`");
    ws.render_fails(&["--set", "render.interpolation=\"phong"]).says("starts like a quoted string");
    // The same for a --vary value.
    let out = shadelab()
        .arg("compare")
        .arg(ws.lesson())
        .args(["--vary", "camera.background=[0, 0, 0],[1, 1", "-o"])
        .arg(ws.output())
        .output()
        .expect("run shadelab");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--vary camera.background=") && stderr.contains("starts like an array"), "{stderr}");
}

#[test]
fn set_reaches_names_with_spaces_and_dots() {
    let named = edit("material = \"plastic\"", "material = \"GGX r = 1 (α = 1)\"")
        .replace("[material.plastic]", "[material.\"GGX r = 1 (α = 1)\"]");
    let ws = Workspace::new(&named);
    let plain = ws.render_ok(&[]);
    let double = ws.render_ok(&["--set", "material.\"GGX r = 1 (α = 1)\".shininess=4"]);
    let single = ws.render_ok(&["--set", "material.'GGX r = 1 (α = 1)'.shininess=4"]);
    assert_ne!(plain.as_raw(), double.as_raw(), "the quoted --set changed nothing");
    assert_eq!(double.as_raw(), single.as_raw(), "single and double quotes reach the same key");
    // Errors name the key the way it is typed.
    let ws = Workspace::new(&named);
    ws.render_fails(&["--set", "material.'GGX r = 1 (α = 1)'.shininess=-4"]).key("material.\"GGX r = 1 (α = 1)\".shininess");
    // An unclosed quote leaves no `=` outside the quotes.
    ws.render_fails(&["--set", "material.\"GGX r = 1.shininess=4"]).says("is not KEY=VALUE");
    ws.render_fails(&["--set", "material.\"GGX\"x.shininess=4"]).says("not a dotted key path");
}

#[test]
fn set_index_past_the_end() {
    Workspace::new(BASE)
        .render_fails(&["--set", "light.5.intensity=2"])
        .says("in --set light.5.intensity=2: ")
        .key("light.5.intensity")
        .says("`light` has 1 entry (index 0), so there is no `light.5`")
        .hint("add it to the lesson file");
    Workspace::new(&edit("[[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\n", ""))
        .render_fails(&["--set", "light.0.intensity=2"])
        .says("the lesson has no `light`");
}

#[test]
fn set_without_equals() {
    let ws = Workspace::new(BASE);
    ws.render_fails(&["--set", "novalue"]).says("--set").says("`novalue` is not KEY=VALUE");
    ws.render_fails(&["--set", "=3"]).says("`=3` has no key");
    ws.render_fails(&["--set", "a..b=3"]).says("not a dotted key path");
}

#[test]
fn size_flag_errors() {
    // A zero side is rejected as the flag itself, before it becomes `camera.size`.
    Workspace::new(BASE).render_fails(&["--size", "0x10"]).says("--size").says("at least 1");
    Workspace::new(BASE).render_fails(&["--size", "abc"]).says("abc").says("WxH");
    Workspace::new(BASE).render_fails(&["--aa", "0"]).key("render.aa").says("0 is out of range");
}

// ---- figures -----------------------------------------------------------------------------

#[test]
fn figure_vary_names_what_the_lesson_has() {
    // Line 18 is the `vary` of a figure appended after BASE; its value starts at column 8.
    let figure = |vary: &str| append(&format!("\n[[figure]]\nname = \"f\"\nkind = \"sweep\"\nvary = \"{vary}\"\nvalues = [1, 2]\n"));
    fails(&figure("material.plastik.shininess"))
        .at(21, 8)
        .key("figure.0.vary")
        .says("the lesson has no material `plastik`")
        .hint("did you mean `plastic`?");
    fails(&figure("light.2.intensity")).at(21, 8).key("figure.0.vary").says("`light` has 1 entry (index 0), so there is no `light.2`");
    fails(&figure("object.1.segments")).at(21, 8).says("`object` has 1 entry (index 0), so there is no `object.1`");
    fails(&figure("material.plastic.shininez")).at(21, 8).says("unknown key `shininez`").hint("did you mean `shininess`?");
    fails(&figure("lihgt.0.intensity")).at(21, 8).says("unknown key `lihgt`").hint("did you mean `light`?");
}

#[test]
fn lobe_figure_names_a_material_that_does_not_exist() {
    let physical = "\n[material.Blinn]\nmodel = \"cook_torrance\"\nndf = \"blinn\"\n";
    let figure = |materials: &str| append(&format!("{physical}\n[[figure]]\nname = \"lobes\"\nkind = \"lobe\"\nmaterials = {materials}\n"));
    fails(&figure("[\"Blinn\", \"Blin\"]"))
        .at(25, 23)
        .key("figure.0.materials.1")
        .says("no material named `Blin`")
        .hint("did you mean `Blinn`?");
    // Lobes plot classic materials too; albedo figures need a BRDF.
    let albedo =
        |materials: &str| append(&format!("{physical}\n[[figure]]\nname = \"albedo\"\nkind = \"albedo\"\nmaterials = {materials}\n"));
    fails(&albedo("[\"plastic\"]"))
        .at(25, 14)
        .key("figure.0.materials.0")
        .says("`plastic` is a classic material (blinn_phong)")
        .hint("physically based materials here: Blinn");
}

#[test]
fn lobe_swap_and_terms_are_checked() {
    let physical = "\n[material.Blinn]\nmodel = \"cook_torrance\"\nndf = \"blinn\"\n";
    let figure = |kind: &str, tail: &str| {
        append(&format!("{physical}\n[[figure]]\nname = \"lobes\"\nkind = \"{kind}\"\nmaterials = [\"Blinn\", \"plastic\"]\n{tail}"))
    };
    // terms split the Cook-Torrance numerator: a classic material in the figure is refused.
    fails(&figure("lobe", "terms = [\"D\", \"DG\"]\n")).key("figure.0.materials.1").says("`plastic` is not a `cook_torrance` material");
    fails(&figure("lobe", "terms = [\"DF\"]\n")).key("figure.0.terms.0").says("DF");
    // Only lobe figures exchange l and v.
    fails(&append(&format!("{physical}\n[[figure]]\nname = \"a\"\nkind = \"albedo\"\nmaterials = [\"Blinn\"]\nswap = true\n")))
        .says("`swap` is not used by an `albedo` figure");
    // Slices out of the plane of incidence: angles in range, at most eight, lobe figures only;
    // a legend entry per material.
    fails(&figure("lobe", "azimuth_deg = [0, 270]\n")).key("figure.0.azimuth_deg.1").says("-180 to 180");
    fails(&figure("lobe", "azimuth_deg = []\n")).key("figure.0.azimuth_deg").says("1 to 8 azimuths");
    fails(&append(&format!("{physical}\n[[figure]]\nname = \"a\"\nkind = \"albedo\"\nmaterials = [\"Blinn\"]\nazimuth_deg = [90]\n")))
        .says("`azimuth_deg` is not used by an `albedo` figure");
    fails(&figure("lobe", "labels = [\"one\"]\n")).key("figure.0.labels").says("1 labels for 2 materials");
}

#[test]
fn a_colour_bar_is_checked_where_it_is_given() {
    let sweep = |tail: &str| {
        append(&format!("\n[[figure]]\nname = \"f\"\nkind = \"sweep\"\nvary = \"light.0.intensity\"\nvalues = [1, 2]\n{tail}"))
    };
    // Line 23 holds the colour bar (the figure starts on line 18 after BASE); column 47 its number.
    fails(&sweep("colorbar = { label = \"E\", radiance_per_unit = -1 }\n"))
        .at(23, 47)
        .key("figure.0.colorbar.radiance_per_unit")
        .says("-1");
    fails(&sweep("colorbar = { label = \" \", radiance_per_unit = 0.25 }\n")).key("figure.0.colorbar.label").says("needs a label");
    fails(&sweep("colorbar = { label = \"E\", radiance = 0.25 }\n")).says("unknown").says("radiance");
    fails(&sweep("diff = true\ncolorbar = { label = \"E\", radiance_per_unit = 0.25 }\n"))
        .key("figure.0.colorbar")
        .says("difference row has its own colour bar");
    fails(&append("\n[[figure]]\nname = \"s\"\nkind = \"split\"\ncolorbar = { label = \"E\", radiance_per_unit = 0.25 }\n"))
        .key("figure.0.colorbar")
        .says("only `compare`, `sweep` and `grid`");
}

#[test]
fn a_walk_figure_is_checked_where_it_is_given() {
    let walk = |tail: &str| append(&format!("\n[[figure]]\nname = \"w\"\nkind = \"walk\"\n{tail}"));
    // ω is a share kept at each scattering: required, three numbers (or one) in [0, 1].
    fails(&walk("")).key("figure.0").says("needs `scattering_albedo`").hint("scattering_albedo = [0.999, 0.98, 0.9]");
    fails(&walk("scattering_albedo = [1.2, 0.5, 0.5]\n")).at(21, 22).key("figure.0.scattering_albedo").says("1.2");
    fails(&walk("scattering_albedo = \"orange\"\n")).key("figure.0.scattering_albedo").says("is text");
    // One angle of incidence; enough walks; a positive thickness.
    fails(&walk("scattering_albedo = 0.9\nincidence = [0, 60]\n")).key("figure.0.incidence").says("one angle of incidence");
    fails(&walk("scattering_albedo = 0.9\nincidence = [95]\n")).key("figure.0.incidence.0").says("95");
    fails(&walk("scattering_albedo = 0.9\nwalks = 10\n")).key("figure.0.walks").says("1000 to 10000000");
    fails(&walk("scattering_albedo = 0.9\nthickness = 0\n")).key("figure.0.thickness").says("0 is out of range");
    // Keys of other kinds, and a walk's keys on other kinds.
    fails(&walk("scattering_albedo = 0.9\nmaterials = [\"plastic\"]\n")).says("`materials` is not used by a `walk` figure");
    fails(&append("\n[[figure]]\nname = \"s\"\nkind = \"split\"\nwalks = 5000\n")).key("figure.0.walks").says("other than `walk`");
}

#[test]
fn a_bsdf_figure_is_checked_where_it_is_given() {
    let bsdf = |tail: &str| append(&format!("\n[[figure]]\nname = \"b\"\nkind = \"bsdf\"\n{tail}"));
    // η = 1 has no boundary; roughness 0 is the smooth glass, drawn beside the others.
    fails(&bsdf("ior = 1.0\n")).at(21, 7).key("figure.0.ior").says("1 is out of range");
    fails(&bsdf("roughness = [0.3, 0]\n")).key("figure.0.roughness.1").says("0 is out of range");
    fails(&bsdf("roughness = []\n")).key("figure.0.roughness").says("1 to 4 roughnesses");
    fails(&bsdf("incidence = [10, 20]\n")).key("figure.0.incidence").says("one angle of incidence");
    fails(&bsdf("walks = 5000\n")).key("figure.0.walks").says("other than `walk`");
    fails(&append("\n[[figure]]\nname = \"w\"\nkind = \"walk\"\nscattering_albedo = 0.9\nior = 1.5\n"))
        .key("figure.0.ior")
        .says("only `bsdf` figures");
    fails(&append("\n[[figure]]\nname = \"s\"\nkind = \"split\"\nroughness = [0.2]\n")).key("figure.0.roughness").says("other than `bsdf`");
}

#[test]
fn a_bssrdf_figure_needs_one_material_that_walks() {
    let fig = |tail: &str| append(&format!("\n[[figure]]\nname = \"p\"\nkind = \"bssrdf\"\n{tail}"));
    fails(&fig("")).key("figure.0").says("needs `materials`").hint("no material here walks");
    // BASE's only material is a Blinn-Phong: no medium under it.
    fails(&fig("materials = [\"plastic\"]\n"))
        .at(21, 14)
        .key("figure.0.materials.0")
        .says("`plastic` does not walk under its surface")
        .hint("subsurface_radius");
    fails(&fig("materials = [\"skin\"]\n")).key("figure.0.materials.0").says("`skin` is not a material here");
    fails(&fig("materials = [\"plastic\", \"plastic\"]\n")).key("figure.0.materials").says("takes one material");
    fails(&fig("materials = [\"plastic\"]\nwalks = 5000\n")).key("figure.0.walks").says("by a `bssrdf` figure");
}

#[test]
fn a_lights_specular_part_is_only_for_the_lights_of_the_classic_equation() {
    fails(&append("\n[[light]]\nkind = \"ambient\"\nspecular = 0.5\n")).key("light.1.specular").says("not used by an `ambient` light");
    fails(&edit("direction = [0, 0, -1]", "direction = [0, 0, -1]\nspecular = [1, -1, 0]")).key("light.0.specular").says("-1");
}

// ---- what should work ------------------------------------------------------------------------

#[test]
fn valid_sets_render() {
    let ws = Workspace::new(BASE);
    let plain = ws.render_ok(&[]);
    let set = ws.render_ok(&["--set", "material.plastic.shininess=64", "--set", "render.interpolation=gouraud"]);
    assert_eq!(set.dimensions(), (32, 32));
    assert_ne!(plain.as_raw(), set.as_raw(), "the --set values changed nothing");
    // Bare words are strings, TOML values are TOML; --size sets camera.size.
    let sized = ws.render_ok(&["--set", "camera.background=[0.1, 0.2, 0.3]", "--size", "40x24", "--aa", "2"]);
    assert_eq!(sized.dimensions(), (40, 24));
}
