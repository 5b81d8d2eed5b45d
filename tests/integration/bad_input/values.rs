//! Bad values: wrong types, out of range, non-finite numbers, and camera and light geometry that
//! cannot work.

use super::{append, edit, fails};

// ---- wrong types -----------------------------------------------------------------------------

#[test]
fn string_where_a_number_belongs() {
    fails(&edit("shininess = 32", r#"shininess = "high""#))
        .at(12, 13)
        .key("material.plastic.shininess")
        .says("expected a number")
        .hint("give a number (no quotes)")
        .hint("32 is typical");
}

#[test]
fn two_numbers_where_a_vector_belongs() {
    fails(&edit("direction = [0, 0, -1]", "direction = [0, -1]")).at(16, 13).key("light.0.direction").says("expected [x, y, z]");
}

#[test]
fn other_wrong_types() {
    // A wrong element is pointed at, and named by its index (the `--set` path syntax).
    fails(&edit("position = [0, 0, 4]", r#"position = [0, "4", 4]"#)).at(2, 16).key("camera.position.1").says("expected a number");
    fails(&edit("size = [32, 32]", "size = [32.5, 32]")).at(3, 9).key("camera.size.0").says("expected an integer");
    // Internal type names (RawMaterial) never reach the user.
    fails(&append("\n[material]\nmatte = 3\n")).at(19, 9).key("material.matte").says("expected a table");
    fails(&edit("diffuse = [0.8, 0.2, 0.2]", "diffuse = [0.8, 0.2]")).at(11, 11).key("material.plastic.diffuse").says("[r, g, b]");
    let f = fails(&edit("diffuse = [0.8, 0.2, 0.2]", "diffuse = true"));
    f.at(11, 11).key("material.plastic.diffuse").says("expected a number, [r, g, b]").hint("reflectance from 0 to 1");
    assert!(!f.stderr.contains("Raw"), "internal type name leaked\n{}", f.shown);
    // Text is a colour (sRGB hex or a CSS name); a misspelt name gets the nearest.
    let f = fails(&edit("diffuse = [0.8, 0.2, 0.2]", r#"diffuse = "rde""#));
    f.at(11, 11).key("material.plastic.diffuse").says("unknown colour name `rde`").hint("did you mean `red`?");
    assert!(!f.stderr.contains("Raw"), "internal type name leaked\n{}", f.shown);
}

// ---- out of range ----------------------------------------------------------------------------

#[test]
fn negative_image_size() {
    // Pointed at the offending element, named by the key.
    fails(&edit("size = [32, 32]", "size = [-32, 32]"))
        .at(3, 9)
        .key("camera.size")
        .says("width: -32 is out of range: allowed 1 to 16384")
        .hint("[width, height] in pixels, e.g. [512, 512]");
    fails(&edit("size = [32, 32]", "size = [32, 0]")).at(3, 13).key("camera.size").says("height: 0 is out of range");
    fails(&edit("size = [32, 32]", "size = [20000, 32]")).at(3, 9).says("allowed 1 to 16384");
}

#[test]
fn negative_shininess() {
    fails(&edit("shininess = 32", "shininess = -1"))
        .at(12, 13)
        .key("material.plastic.shininess")
        .says("-1 is out of range: allowed 0 to 1000000")
        .hint("the exponent K_shi");
}

#[test]
fn field_of_view_out_of_range() {
    for fov in ["0", "200"] {
        fails(&edit("size = [32, 32]", &format!("fov_deg = {fov}")))
            .at(3, 11)
            .key("camera.fov_deg")
            .says(&format!("{fov} is out of range: allowed 1 to 179"))
            .hint("vertical field of view in degrees; 30 to 60");
    }
}

#[test]
fn supersampling_out_of_range() {
    for aa in ["0", "100"] {
        fails(&append(&format!("\n[render]\naa = {aa}\n")))
            .at(19, 6)
            .key("render.aa")
            .says(&format!("{aa} is out of range: allowed 1 to 16"))
            .hint("supersamples per pixel side")
            .hint("2 or 4 smooths edges");
    }
}

#[test]
fn coefficient_above_one() {
    fails(&edit("diffuse = [0.8, 0.2, 0.2]", "diffuse = [0.8, 1.5, 0.2]"))
        .at(11, 17)
        .key("material.plastic.diffuse")
        .says("component 1: 1.5 is out of range: allowed 0 to 1")
        .hint("K_diff")
        .hint("raise the light's intensity");
    fails(&edit("shininess = 32", "specular = 2"))
        .at(12, 12)
        .key("material.plastic.specular")
        .says("2 is out of range: allowed 0 to 1")
        .hint("K_spec, a reflectance from 0 to 1");
}

#[test]
fn every_range_and_type_error_has_a_hint() {
    let cases = [
        append("intensity = -1\n"),
        append("\n[render]\nexposure = 30\n"),
        append("\n[scene]\nambient = -1\n"),
        edit("shape = \"uv_sphere\"", "shape = \"uv_sphere\"\nrings = 1"),
        edit("shape = \"uv_sphere\"", "shape = \"torus\"\nsides = 1"),
        edit("size = [32, 32]", "near = 0"),
        edit("size = [32, 32]", "size = \"big\""),
        edit("direction = [0, 0, -1]", "direction = \"down\""),
        edit("shininess = 32", "emission = -1"),
        append("\n[render]\naa = \"2\"\n"),
    ];
    for text in cases {
        let f = fails(&text);
        assert!(f.stderr.contains("\n  hint: "), "no hint\n{}", f.shown);
    }
}

#[test]
fn other_out_of_range_values() {
    fails(&append("intensity = -1\n")).at(17, 13).key("light.0.intensity").says("out of range");
    fails(&edit("shape = \"uv_sphere\"", "shape = \"uv_sphere\"\nsegments = 2"))
        .at(7, 12)
        .key("object.0.segments")
        .says("allowed 3 to 2048")
        .hint("32 to 64 looks round");
    fails(&edit("shape = \"uv_sphere\"", "shape = \"icosphere\"\nsubdivisions = 12"))
        .at(7, 16)
        .key("object.0.subdivisions")
        .says("allowed 0 to 9");
    fails(&edit(r#"material = "plastic""#, "material = \"plastic\"\nscale = [1, 0, 1]")).at(8, 13).key("object.0.scale").hint("positive");
}

// ---- non-finite numbers (TOML has nan and inf) -------------------------------------------------

#[test]
fn nan_and_inf() {
    fails(&edit("shininess = 32", "shininess = nan")).at(12, 13).key("material.plastic.shininess").says("must be a finite number");
    fails(&edit("shininess = 32", "shininess = inf")).at(12, 13).key("material.plastic.shininess").says("must be a finite number, got inf");
    fails(&edit("direction = [0, 0, -1]", "direction = [0, -inf, -1]"))
        .at(16, 17)
        .key("light.0.direction")
        .says("component 1: must be a finite number");
    fails(&append("intensity = +inf\n")).at(17, 13).key("light.0.intensity").says("finite");
    fails(&edit("position = [0, 0, 4]", "position = [0, 0, nan]")).at(2, 19).key("camera.position").says("finite");
}

// ---- camera and light geometry -------------------------------------------------------------

#[test]
fn camera_up_parallel_to_view() {
    fails(&edit("size = [32, 32]", "up = [0, 0, 2]")).at(3, 6).key("camera.up").says("parallel to the view direction");
    // Looking straight down with the default up: no `up` to point at, so its table.
    fails(&edit("position = [0, 0, 4]", "position = [0, 4, 0]")).at(1, 1).key("camera.up").hint("defaults to [0, 1, 0]");
    fails(&edit("size = [32, 32]", "up = [0, 0, 0]")).at(3, 6).key("camera.up").says("cannot be [0, 0, 0]");
}

#[test]
fn camera_looks_at_its_position() {
    fails(&edit("size = [32, 32]", "look_at = [0, 0, 4]")).at(3, 11).key("camera.look_at").says("looks at its own position");
    // `look_at` absent: it is the origin, so blame `position`.
    fails(&edit("position = [0, 0, 4]", "position = [0, 0, 0]")).at(2, 12).key("camera.position").hint("defaults to [0, 0, 0]");
}

#[test]
fn attenuation_all_zero() {
    fails(&edit("kind = \"directional\"\ndirection = [0, 0, -1]", "kind = \"point\"\nposition = [0, 2, 2]\nattenuation = [0, 0, 0]"))
        .at(17, 15)
        .key("light.0.attenuation")
        .says("divides by zero")
        .hint("[1, 0, 0]");
    fails(&edit("direction = [0, 0, -1]", "direction = [0, 0, 0]")).at(16, 13).key("light.0.direction").says("cannot be [0, 0, 0]");
}

// ---- glass ---------------------------------------------------------------------------------

/// The glass lines of [`BASE`]: line 10 `model = "glass"`, line 11 the key under test.
fn glass(line: &str) -> String {
    edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", &format!("model = \"glass\"\n{line}"))
}

#[test]
fn glass_ior_must_be_finite_and_positive() {
    fails(&glass("ior = -1.5"))
        .at(11, 7)
        .key("material.plastic.ior")
        .says("-1.5 is out of range: allowed 0.1 to 10")
        .hint("relative index of refraction");
    fails(&glass("ior = 0")).at(11, 7).says("0 is out of range: allowed 0.1 to 10");
    fails(&glass("ior = nan")).at(11, 7).key("material.plastic.ior").says("must be a finite number, got NaN");
    fails(&glass("ior = inf")).at(11, 7).says("must be a finite number, got inf");
    // Per channel: the component is named.
    fails(&glass("ior = [1.5, -inf, 1.5]")).key("material.plastic.ior").says("component 1: must be a finite number");
    // Only glass takes an index per channel.
    fails(&edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", "model = \"cook_torrance\"\nior = [1.4, 1.5, 1.6]"))
        .at(11, 7)
        .says("cook_torrance `ior` is one number")
        .hint("only `glass` takes one per channel");
}

#[test]
fn glass_keys_it_does_not_read_and_wrong_types() {
    fails(&glass("diffuse = 0.5")).key("material.plastic.diffuse").says("`diffuse` is not used by `glass`").hint("remove `diffuse`");
    fails(&glass("ambient = 0.5")).key("material.plastic.ambient").says("not used by `glass`");
    fails(&glass("thin = \"yes\"")).at(11, 8).key("material.plastic.thin").says("expected a boolean");
    fails(&glass("tint = 2")).at(11, 8).says("2 is out of range: allowed 0 to 1");
}

#[test]
fn max_bounces_out_of_range() {
    for n in [0, 17, -1] {
        fails(&append(&format!("\n[render]\nmax_bounces = {n}\n")))
            .at(19, 15)
            .key("render.max_bounces")
            .says(&format!("{n} is out of range: allowed 1 to 16"));
    }
}

/// The principled material's transmission keys: their ranges, the models that do not read
/// them, and the rasterizer that does not draw them (refused at the key, nothing written).
#[test]
fn principled_transmission_keys() {
    let principled = |extra: &str| {
        edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", &format!("model = \"principled\"\n{extra}"))
    };
    fails(&principled("ior = 5")).at(11, 7).key("material.plastic.ior").says("5 is out of range: allowed 1 to 3");
    fails(&principled("transmittance_distance = 0")).key("material.plastic.transmittance_distance").says("out of range");
    fails(&principled("diffuse_transmission = 1.5")).key("material.plastic.diffuse_transmission").says("out of range");
    fails(&principled("transmittance_color = [1, 2, 0]")).key("material.plastic.transmittance_color").says("out of range");
    fails(&edit("shininess = 32", "shininess = 32\nspecular_transmission = 0.5")).key("material.plastic.specular_transmission");
    fails(&principled("specular_transmission = 0.5\nsubsurface = 1\nsubsurface_radius = 1"))
        .key("material.plastic.subsurface_radius")
        .says("light either goes through the surface or walks under it");
    // The default method is the rasterizer: refused at the key, with the way out.
    fails(&principled("specular_transmission = 0.5"))
        .at(11, 25)
        .key("material.plastic.specular_transmission")
        .says("only method = \"path\" draws")
        .hint("set `[render] method = \"path\"`");
}

#[test]
fn a_shadow_volume_on_a_light_with_extent() {
    // Volumes and shadow polygons are cast from one point: a rect light has no one silhouette.
    fails(&edit(
        "kind = \"directional\"\ndirection = [0, 0, -1]",
        "kind = \"rect\"\nposition = [0, 2, 0]\ndirection = [0, -1, 0]\nsize = [1, 1]\nshadows = \"volume\"",
    ))
    .at(19, 11)
    .key("light.0.shadows")
    .says("shadows = \"volume\" needs a point, spot or directional light, not a rect light")
    .hint("use \"ray\"");
    fails(&edit("kind = \"directional\"\ndirection = [0, 0, -1]", "kind = \"sky\"\nshadows = \"polygons\""))
        .at(16, 11)
        .key("light.0.shadows")
        .says("not a sky light");
}

#[test]
fn photon_map_keys_out_of_range_and_combinations() {
    let render = |lines: &str| append(&format!("\n[render]\nmethod = \"path\"\n{lines}\n"));
    fails(&render("indirect = \"photon\"")).at(20, 12).key("render.indirect").says("photon").hint("photons");
    fails(&render("caustics = \"photons\"\ngather_rays = 2000")).at(21, 15).key("render.gather_rays").says("allowed 0 to 1024");
    fails(&render("global_photons = 10")).at(20, 18).key("render.global_photons").says("allowed 1000 to 10000000");
    fails(&render("global_radius = 0")).at(20, 17).key("render.global_radius").says("out of range");
    fails(&render("photon_gather = \"knn\"")).at(20, 17).key("render.photon_gather").says("knn");
    fails(&render("photon_nearest = 0")).at(20, 18).key("render.photon_nearest").says("allowed 1 to 1000");
    fails(&render("gather_rays = 1.5")).at(20, 15).key("render.gather_rays").says("expected an integer");
    // The final gather leaves the caustics to the caustic map: without it they would be lost.
    fails(&render("indirect = \"photons\""))
        .at(20, 12)
        .key("render.indirect")
        .says("needs caustics = \"photons\"")
        .hint("caustics = \"photons\"");
}

// ---- subsurface ----------------------------------------------------------------------------

/// The principled lines of [`BASE`]: line 10 `model = "principled"`, lines 11 on the keys under test.
fn principled(lines: &str) -> String {
    edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", &format!("model = \"principled\"\n{lines}"))
}

#[test]
fn subsurface_radius_and_scale_out_of_range_or_misplaced() {
    fails(&principled("subsurface = 1\nsubsurface_radius = [1, -0.2, 0.1]"))
        .at(12, 25)
        .key("material.plastic.subsurface_radius")
        .says("component 1: -0.2 is out of range: allowed 0 to 10000")
        .hint("mean free path per channel");
    fails(&principled("subsurface_scale = -1"))
        .at(11, 20)
        .key("material.plastic.subsurface_scale")
        .says("out of range")
        .hint("world units");
    fails(&principled("subsurface_radius = nan")).key("material.plastic.subsurface_radius").says("must be a finite number");
    // A metal lets no light in; a model that is not principled does not read it.
    fails(&principled("metallic = 1\nsubsurface = 1\nsubsurface_radius = 1"))
        .at(13, 1)
        .key("material.plastic.subsurface_radius")
        .says("a metal lets no light under its surface")
        .hint("metallic = 0");
    fails(&edit("shininess = 32", "shininess = 32\nsubsurface_radius = [1, 0.2, 0.1]"))
        .key("material.plastic.subsurface_radius")
        .says("not used by `blinn_phong`");
}
