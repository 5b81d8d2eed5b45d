//! Bad input through the real binary: every class of mistake exits with 2, names the
//! file, the `line:col` and the key path, gives a hint where one helps, never panics and
//! never leaves an image (or a temporary file) behind.

use crate::helpers::{read_png, shadelab};
use std::path::{Path, PathBuf};

/// The lesson most cases edit one line of. Line numbers, for the expected positions:
///
/// ```text
///  1 [camera]                       9 [material.plastic]
///  2 position = [0, 0, 4]          10 model = "blinn_phong"
///  3 size = [32, 32]               11 diffuse = [0.8, 0.2, 0.2]
///  4                               12 shininess = 32
///  5 [[object]]                    13
///  6 shape = "uv_sphere"           14 [[light]]
///  7 material = "plastic"          15 kind = "directional"
///  8                               16 direction = [0, 0, -1]
/// ```
const BASE: &str = r#"[camera]
position = [0, 0, 4]
size = [32, 32]

[[object]]
shape = "uv_sphere"
material = "plastic"

[material.plastic]
model = "blinn_phong"
diffuse = [0.8, 0.2, 0.2]
shininess = 32

[[light]]
kind = "directional"
direction = [0, 0, -1]
"#;

/// [`BASE`] with the text `from` (which must occur exactly once) replaced by `to`.
#[track_caller]
fn edit(from: &str, to: &str) -> String {
    assert_eq!(BASE.matches(from).count(), 1, "`{from}` must occur once in BASE");
    BASE.replacen(from, to, 1)
}

/// [`BASE`] followed by `tail` (line 17 is empty, so a table appended as
/// `"\n[render]\naa = 0\n"` has its header on line 18 and its first key on line 19).
fn append(tail: &str) -> String {
    format!("{BASE}{tail}")
}

/// A folder holding `lesson.toml` and an empty `out/` folder for the image.
struct Workspace {
    dir: tempfile::TempDir,
}

impl Workspace {
    fn new(text: &str) -> Workspace {
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::write(dir.path().join("lesson.toml"), text).expect("write lesson");
        std::fs::create_dir(dir.path().join("out")).expect("create out/");
        Workspace { dir }
    }

    /// Writes another file next to the lesson (an OBJ, a second lesson).
    fn write(&self, name: &str, text: &str) -> &Workspace {
        std::fs::write(self.dir.path().join(name), text).expect("write file");
        self
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn lesson(&self) -> PathBuf {
        self.path("lesson.toml")
    }

    fn output(&self) -> PathBuf {
        self.path("out").join("render.png")
    }

    /// `shadelab render LESSON -o out/render.png ARGS...`: must fail as bad input.
    #[track_caller]
    fn render_fails(&self, args: &[&str]) -> Failure {
        self.fails_with(&self.lesson(), args)
    }

    /// As [`Workspace::render_fails`] for another lesson path.
    #[track_caller]
    fn fails_with(&self, lesson: &Path, args: &[&str]) -> Failure {
        let out = shadelab().arg("render").arg(lesson).arg("-o").arg(self.output()).args(args).output().expect("run shadelab");
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        let shown = format!("args: {args:?}\n--- stderr ---\n{stderr}--- stdout ---\n{stdout}");
        assert_eq!(out.status.code(), Some(2), "expected exit code 2 (bad input)\n{shown}");
        assert!(!stderr.contains("panicked"), "the program panicked\n{shown}");
        assert!(!self.output().exists(), "an image was written despite the error\n{shown}");
        let left: Vec<_> = std::fs::read_dir(self.path("out")).expect("read out/").map(|e| e.expect("entry").file_name()).collect();
        assert!(left.is_empty(), "files left in the output folder: {left:?}\n{shown}");
        Failure { stderr, shown }
    }

    /// `shadelab render LESSON -o out/render.png ARGS...`: must succeed; returns the image.
    #[track_caller]
    fn render_ok(&self, args: &[&str]) -> image::RgbImage {
        let out = shadelab().arg("render").arg(self.lesson()).arg("-o").arg(self.output()).args(args).output().expect("run shadelab");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "expected success, args {args:?}\n--- stderr ---\n{stderr}");
        read_png(&self.output())
    }
}

/// What a failed run printed, with assertions that show it all when they fail.
struct Failure {
    stderr: String,
    shown: String,
}

impl Failure {
    /// The message points at `lesson.toml:LINE:COL: `.
    #[track_caller]
    fn at(&self, line: usize, col: usize) -> &Failure {
        self.says(&format!("lesson.toml:{line}:{col}: "))
    }

    /// The message names the key path in backticks.
    #[track_caller]
    fn key(&self, key: &str) -> &Failure {
        self.says(&format!("`{key}`: "))
    }

    /// The message contains `text`.
    #[track_caller]
    fn says(&self, text: &str) -> &Failure {
        assert!(self.stderr.contains(text), "stderr should contain {text:?}\n{}", self.shown);
        self
    }

    /// A `  hint: ` line contains `text`.
    #[track_caller]
    fn hint(&self, text: &str) -> &Failure {
        let hints: Vec<&str> = self.stderr.lines().filter_map(|l| l.strip_prefix("  hint: ")).collect();
        assert!(hints.iter().any(|h| h.contains(text)), "a hint should contain {text:?}\n{}", self.shown);
        self
    }
}

/// Renders `text` and expects it to fail.
#[track_caller]
fn fails(text: &str) -> Failure {
    Workspace::new(text).render_fails(&[])
}

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
    f.hint("Keys allowed here: model, ambient, diffuse, specular, shininess, emission");
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
    let f = fails(&edit("diffuse = [0.8, 0.2, 0.2]", r#"diffuse = "red""#));
    f.at(11, 11).key("material.plastic.diffuse").says("expected a number or [r, g, b]").hint("reflectance from 0 to 1");
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

// ---- meshes --------------------------------------------------------------------------------

#[test]
fn missing_mesh_file() {
    // The same form as an OBJ that does not load: the lesson's place, the key, the file as written.
    fails(&edit("shape = \"uv_sphere\"", "shape = \"mesh\"\npath = \"nope.obj\""))
        .at(7, 8)
        .key("object.0.path")
        .says("`object.0.path`: nope.obj: mesh file not found (looked for ")
        .hint("relative to the lesson file");
    // Chosen by --set: the --set is blamed.
    Workspace::new(BASE)
        .render_fails(&["--set", "object.0.shape=mesh", "--set", "object.0.path=gone.obj"])
        .says("in --set object.0.path=gone.obj: `object.0.path`: gone.obj: mesh file not found");
}

#[test]
fn malformed_obj_files() {
    let lesson = edit("shape = \"uv_sphere\"", "shape = \"mesh\"\npath = \"bad.obj\"");
    // lesson.toml:7:8 is the value of `path`; then the OBJ file with its own line.
    let obj_fails = |obj: &str| Workspace::new(&lesson).write("bad.obj", obj).render_fails(&[]);
    // Not a number: the line tobj rejects without saying where is found.
    obj_fails("v 0 0 0\nv 1 0 zero\nv 0 1 0\nf 1 2 3\n")
        .at(7, 8)
        .key("object.0.path")
        .says("`object.0.path`: bad.obj:2: `v 1 0 zero`: `zero` is not a number")
        .hint("Wavefront OBJ with `v` and `f` lines");
    obj_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n").at(7, 8).says("bad.obj:4: `f 1 2 x`: `x` is not a vertex");
    obj_fails("v 0 0 0\nvn 0 1\n").at(7, 8).says("bad.obj:2: ").says("a normal needs 3 numbers");
    // A face index past the end: named with the OBJ's line.
    obj_fails("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n")
        .at(7, 8)
        .key("object.0.path")
        .says("bad.obj:4: position index 5 is out of range (3 available)")
        .hint("face indices count from 1");
    // Not an OBJ at all.
    obj_fails("# nothing\n").at(7, 8).key("object.0.path").says("bad.obj: no triangles").hint("Wavefront OBJ");
    obj_fails("hello, world\nthis is no mesh\n").at(7, 8).says("bad.obj: no triangles (the file has 0 `v` lines");
    // `check` reports it the same way.
    let ws = Workspace::new(&lesson);
    ws.write("bad.obj", "v 0 0 0\nv 1 0 zero\n");
    let out = shadelab().arg("check").arg(ws.lesson()).output().expect("run shadelab");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("lesson.toml:7:8: `object.0.path`: bad.obj:2: "), "{stderr}");
}

#[test]
fn lesson_file_that_does_not_exist() {
    let ws = Workspace::new(BASE);
    ws.fails_with(&ws.path("nope.toml"), &[]).says("nope.toml").says("cannot read the lesson").hint("check the path");
}

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

// ---- output file ---------------------------------------------------------------------

#[test]
fn output_extension_must_be_png_or_exr() {
    let ws = Workspace::new(BASE);
    let none: [&str; 0] = [];
    for args in [&none[..], &["--format", "png"], &["--format", "exr"]] {
        let out = shadelab().arg("render").arg(ws.lesson()).arg("-o").arg(ws.path("out/render.jpg")).args(args).output().expect("run");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("render.jpg: shadelab writes PNG (8-bit sRGB) or EXR (linear float) images, not .jpg"), "{stderr}");
        assert!(stderr.contains("hint: name the file") && stderr.contains("render.png"), "{stderr}");
        assert!(!ws.path("out/render.jpg").exists());
    }
    // A known extension that disagrees with --format is refused too.
    ws.render_fails(&["--format", "exr"]).says("the name says .png but --format is exr").hint("render.exr");
    ws.render_ok(&["--format", "png"]);
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
    fails(&figure("[\"plastic\"]"))
        .at(25, 14)
        .key("figure.0.materials.0")
        .says("`plastic` is a classic material (blinn_phong)")
        .hint("physically based materials here: Blinn");
}

// ---- check -----------------------------------------------------------------------------------

#[test]
fn check_reports_each_lesson() {
    let ws = Workspace::new(BASE);
    ws.write("bad.toml", &edit("shininess = 32", "shininess = -1"));
    let out = shadelab().arg("check").arg(ws.lesson()).arg(ws.path("bad.toml")).output().expect("run shadelab");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let shown = format!("--- stdout ---\n{stdout}--- stderr ---\n{stderr}");
    assert_eq!(out.status.code(), Some(2), "{shown}");
    assert!(stdout.lines().any(|l| l.starts_with("ok") && l.contains("lesson.toml")), "no `ok` line for the good lesson\n{shown}");
    assert!(!stdout.contains("bad.toml"), "the bad lesson is not ok\n{shown}");
    assert!(stderr.contains("bad.toml:12:13: `material.plastic.shininess`: -1 is out of range"), "{shown}");
    assert!(stderr.contains("1 of 2 lessons are invalid"), "{shown}");
    assert!(!stderr.contains("panicked"), "{shown}");
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

/// A lesson showing `path` (an OBJ next to it) lit from the camera.
fn mesh_lesson(path: &str) -> String {
    edit("shape = \"uv_sphere\"", &format!("shape = \"mesh\"\npath = \"{path}\""))
}

/// The share of pixels that are clearly not the black background.
fn lit_fraction(img: &image::RgbImage) -> f64 {
    img.pixels().filter(|p| p.0.iter().any(|&c| c > 20)).count() as f64 / (img.width() * img.height()) as f64
}

#[test]
fn obj_without_normals_renders() {
    // A regular tetrahedron, faces wound counter-clockwise seen from outside.
    let tetra = "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
    let ws = Workspace::new(&mesh_lesson("tetra.obj"));
    ws.write("tetra.obj", tetra);
    let img = ws.render_ok(&[]);
    assert_eq!(img.dimensions(), (32, 32));
    let lit = lit_fraction(&img);
    assert!(lit > 0.2, "only {:.0}% of the pixels show the tetrahedron", lit * 100.0);
}

#[test]
fn obj_with_normals_renders() {
    // A quad facing the camera, with its normals in the file, in a subfolder.
    let quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n";
    let ws = Workspace::new(&mesh_lesson("meshes/quad.obj"));
    std::fs::create_dir(ws.path("meshes")).expect("mkdir");
    ws.write("meshes/quad.obj", quad);
    let img = ws.render_ok(&[]);
    let lit = lit_fraction(&img);
    assert!(lit > 0.3, "only {:.0}% of the pixels show the quad", lit * 100.0);
}
