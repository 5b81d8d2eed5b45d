//! Bad input in the lesson's structure: TOML syntax, unknown keys, unknown names, missing keys and
//! keys the chosen variant does not read.

use super::{BASE, append, edit, fails};

// ---- TOML syntax -------------------------------------------------------------------------

#[test]
fn toml_syntax_errors() {
    fails(&edit(r#"model = "blinn_phong""#, "model = blinn_phong"))
        .at(10, 9)
        .says("not valid TOML")
        .says("must be quoted")
        .hint(r#"model = "phong""#);
    fails(&append("\n[render\naa = 2\n")).at(18, 8).says("not valid TOML").says("unclosed table");
    fails(&edit("shininess = 32", "shininess = 32\nshininess = 8"))
        .at(13, 1)
        .says("duplicate key `shininess` in `[material.plastic]`, first set on line 12")
        .hint("only once");
    fails(&append("\n[material.plastic]\nspecular = 0.3\n"))
        .at(18, 11)
        .says("table `[material.plastic]` is defined twice (first on line 9)")
        .hint("under one `[material.plastic]` header");
}

// ---- unknown keys ----------------------------------------------------------------------------

#[test]
fn unknown_key_at_top_level() {
    fails(&format!("titel = \"First light\"\n{BASE}")).at(1, 1).key("titel").says("unknown key `titel`").hint("lesson, camera, object");
    fails(&edit("[[light]]", "[[lights]]")).at(14, 3).key("lights").hint("did you mean `light`?");
    fails(&edit("[camera]", "[camra]")).at(1, 2).key("camra").hint("did you mean `camera`?");
}

#[test]
fn unknown_key_in_camera() {
    fails(&edit("size = [32, 32]", "fovy_deg = 30")).at(3, 1).key("camera.fovy_deg").hint("did you mean `fov_deg`?");
}

#[test]
fn unknown_key_in_material() {
    fails(&edit("shininess = 32", "shininez = 32"))
        .at(12, 1)
        .key("material.plastic.shininez")
        .says("unknown key `shininez`")
        .hint("did you mean `shininess`?");
}

#[test]
fn unknown_key_hint_lists_only_the_keys_of_the_model() {
    // A classic material: its own keys, not the 19 keys of the physically based models.
    let f = fails(&edit("shininess = 32", "shininez = 32"));
    f.hint("Keys allowed here: model, ambient, diffuse, specular, shininess, clamp_n_dot_l, emission");
    assert!(!f.stderr.contains("roughness"), "physically based keys listed for a classic material\n{}", f.shown);
    // A physically based key on a classic model: still suggested, and said to be unused.
    fails(&edit("shininess = 32", "roughnes = 0.5"))
        .key("material.plastic.roughnes")
        .hint("did you mean `roughness`? It is not read by model `blinn_phong`");
    let cook = edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", "model = \"cook_torrance\"\nroughnes = 0.5");
    let f = fails(&cook);
    f.at(11, 1).hint("did you mean `roughness`? Keys allowed here: model, ambient, ndf, masking, fresnel, ior");
    assert!(!f.stderr.contains("shininess"), "{}", f.shown);
    // Lights and objects: the keys of their kind and shape.
    fails(&append("exponent = 3\nintesity = 2\n")).hint("Keys allowed here: kind, color, intensity, direction, ambient");
    fails(&edit("shape = \"uv_sphere\"", "shape = \"cube\"\nsegmets = 3")).hint("allowed here: shape, material, translate");
}

#[test]
fn unknown_key_in_light() {
    fails(&append("intesity = 2\n")).at(17, 1).key("light.0.intesity").hint("did you mean `intensity`?");
}

#[test]
fn unknown_key_in_object_and_inline_table() {
    fails(&edit(r#"material = "plastic""#, "material = \"plastic\"\nrotate = [0, 45, 0]"))
        .at(8, 1)
        .key("object.0.rotate")
        .hint("did you mean `rotate_deg`?");
    let inline = "[material]\nplastic = { model = \"phong\", shininez = 3 }";
    fails(&edit("[material.plastic]\nmodel = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", inline))
        .at(10, 30)
        .key("material.plastic.shininez")
        .hint("did you mean `shininess`?");
}

// ---- unknown names ---------------------------------------------------------------------------

#[test]
fn unknown_model() {
    fails(&edit(r#"model = "blinn_phong""#, r#"model = "phongg""#))
        .at(10, 9)
        .key("material.plastic.model")
        .says("unknown value `phongg`")
        .hint("did you mean `phong`? Allowed: lambert, phong, blinn_phong");
}

#[test]
fn unknown_render_choices() {
    let cases = [
        ("interpolation = \"gouraudd\"", 17, "render.interpolation", "did you mean `gouraud`?"),
        ("tonemap = \"acse\"", 11, "render.tonemap", "did you mean `aces`?"),
        ("normals = \"angel\"", 11, "render.normals", "did you mean `angle`?"),
        ("cull = \"front\"", 8, "render.cull", "allowed: back, none"),
    ];
    for (line, col, key, hint) in cases {
        fails(&append(&format!("\n[render]\n{line}\n"))).at(19, col).key(key).hint(hint);
    }
}

#[test]
fn unknown_light_kind_and_shape() {
    fails(&edit(r#"kind = "directional""#, r#"kind = "pointt""#)).at(15, 8).key("light.0.kind").hint("did you mean `point`?");
    fails(&edit(r#"shape = "uv_sphere""#, r#"shape = "sphere""#)).at(6, 9).key("object.0.shape").hint("uv_sphere, icosphere");
}

#[test]
fn material_that_does_not_exist() {
    fails(&edit(r#"material = "plastic""#, r#"material = "plastik""#))
        .at(7, 12)
        .key("object.0.material")
        .says("no material named `plastik`")
        .hint("did you mean `plastic`?");
}

// ---- missing keys ----------------------------------------------------------------------------

#[test]
fn missing_camera_position() {
    // The key is absent, so the position is its table's header.
    fails(&edit("position = [0, 0, 4]\n", ""))
        .at(1, 1)
        .key("camera.position")
        .says("missing required key `position`")
        .hint("add `position");
    fails(&edit("[camera]\nposition = [0, 0, 4]\nsize = [32, 32]\n", "")).at(1, 1).key("camera").hint("add a `[camera]` table");
}

#[test]
fn point_light_without_position() {
    fails(&edit("kind = \"directional\"\ndirection = [0, 0, -1]", "kind = \"point\""))
        .at(14, 1)
        .key("light.0.position")
        .says("a `point` light needs `position`")
        .hint("add `position = [x, y, z]`");
    fails(&edit("kind = \"directional\"\n", "")).at(14, 1).key("light.0.kind").says("missing required key `kind`");
    fails(&edit("shape = \"uv_sphere\"", "shape = \"mesh\"")).at(5, 1).key("object.0.path").says("needs `path`");
}

// ---- keys the chosen variant does not read -------------------------------------------------------

#[test]
fn keys_the_variant_does_not_use() {
    fails(&edit("model = \"blinn_phong\"", "model = \"lambert\"").replace("shininess = 32", "specular = 0.5"))
        .at(12, 1)
        .key("material.plastic.specular")
        .says("not used by `lambert`")
        .hint("remove `specular`");
    fails(&edit("shape = \"uv_sphere\"", "shape = \"cube\"\nsegments = 8"))
        .at(7, 1)
        .key("object.0.segments")
        .says("not used by shape `cube`");
    fails(&edit("kind = \"directional\"\ndirection = [0, 0, -1]", "kind = \"point\"\nposition = [0, 2, 2]\nexponent = 8"))
        .at(17, 1)
        .key("light.0.exponent")
        .says("not used by a `point` light")
        .hint("remove `exponent`");
    fails(&edit("kind = \"directional\"", "kind = \"ambient\"")).at(16, 1).key("light.0.direction").says("not used by an `ambient` light");
}
