//! Textures: a file outside the lesson's folder, missing or not an image, an unknown key in a
//! texture table, a texture on a key that cannot take one.

use super::{Workspace, edit, fails};

/// [`super::BASE`] with `diffuse` (line 11, value at column 11) set to `value`.
fn diffuse(value: &str) -> String {
    edit("diffuse = [0.8, 0.2, 0.2]", &format!("diffuse = {value}"))
}

#[test]
fn bad_texture_files() {
    fails(&diffuse("{ texture = \"../outside.png\" }")).key("material.plastic.diffuse.texture").says("outside the lesson's folder");
    fails(&diffuse("{ texture = \"nope.png\" }")).key("material.plastic.diffuse.texture").says("nope.png: file not found");
    let ws = Workspace::new(&diffuse("{ texture = \"notes.png\" }"));
    ws.write("notes.png", "not an image at all");
    ws.render_fails(&[]).key("material.plastic.diffuse.texture").says("notes.png: not an image").hint("PNG, JPEG");
    let ws = Workspace::new(&edit("shininess = 32", "shininess = 32\nnormal_map = \"../n.png\""));
    ws.render_fails(&[]).key("material.plastic.normal_map").says("outside the lesson's folder");
}

#[test]
fn bad_texture_keys() {
    fails(&diffuse("{ texure = \"a.png\" }"))
        .key("material.plastic.diffuse.texure")
        .says("unknown key `texure`")
        .hint("did you mean `texture`?");
    fails(&diffuse("{ checker = { scale = 0 } }")).key("material.plastic.diffuse.checker.scale").says("1 to 128");
    fails(&diffuse("{ checker = { scale = 4, c = 1 } }")).key("material.plastic.diffuse.checker.c").says("unknown key `c`");
    fails(&diffuse("{ texture = \"a.png\", checker = { scale = 4 } }")).key("material.plastic.diffuse").says("exactly one");
    fails(&diffuse("{ texture = 3 }")).key("material.plastic.diffuse.texture").says("a file name");
    // A key that cannot take a texture, and a mirror's normal map.
    fails(&edit("shininess = 32", "shininess = 32\nspecular = { texture = \"a.png\" }"))
        .key("material.plastic.specular")
        .says("`specular` cannot take a texture")
        .hint("`diffuse`");
    fails(&edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", "model = \"mirror\"\nnormal_map = \"n.png\""))
        .key("material.plastic.normal_map")
        .says("not used by `mirror`");
    fails(&edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", "model = \"glass\"\nnormal_map = \"n.png\""))
        .key("material.plastic.normal_map")
        .says("not used by `glass`");
    fails(&edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", "model = \"mirror\"\nocclusion_map = \"ao.png\""))
        .key("material.plastic.occlusion_map")
        .says("not used by `mirror`");
    fails(&edit("shininess = 32", "shininess = 32\nocclusion_map = \"../ao.png\""))
        .key("material.plastic.occlusion_map")
        .says("outside the lesson's folder");
    // A colour name is a colour for a checker square too; a scalar key refuses a colour.
    fails(&diffuse("{ checker = { a = \"rde\" } }")).key("material.plastic.diffuse.checker.a").says("unknown colour name `rde`");
}

#[test]
fn a_checker_renders_and_needs_no_file() {
    let ws = Workspace::new(&diffuse("{ checker = { scale = 4, a = [1, 0, 0], b = [0, 0, 1] } }"));
    let img = ws.render_ok(&[]);
    // Both colours show on the sphere (measured: 90 red and 91 blue pixels of 32 × 32; the
    // white highlight is neither).
    let (mut red, mut blue) = (0, 0);
    for p in img.pixels() {
        red += (p[0] > 40 && p[2] < 10) as u32;
        blue += (p[2] > 40 && p[0] < 10) as u32;
    }
    assert!(red > 60 && blue > 60, "red {red}, blue {blue}");
}
