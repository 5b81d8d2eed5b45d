//! Files around the lesson: meshes (missing, malformed, and ones that render), a missing lesson, the
//! output file's extension, and `check` over several lessons.

use super::{BASE, Workspace, append, edit, fails};
use crate::helpers::shadelab;

// ---- meshes --------------------------------------------------------------------------------

#[test]
fn missing_mesh_file() {
    // The same form as an OBJ that does not load: the lesson's place, the key, the file as written.
    fails(&edit("shape = \"uv_sphere\"", "shape = \"mesh\"\npath = \"nope.obj\""))
        .at(7, 8)
        .key("object.0.path")
        .says("`object.0.path`: nope.obj: file not found (looked for ")
        .hint("relative to the lesson file");
    // Chosen by --set: the --set is blamed.
    Workspace::new(BASE)
        .render_fails(&["--set", "object.0.shape=mesh", "--set", "object.0.path=gone.obj"])
        .says("in --set object.0.path=gone.obj: `object.0.path`: gone.obj: file not found");
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
    assert!(stderr.contains("1 of 2 lessons is invalid"), "{shown}");
    assert!(!stderr.contains("panicked"), "{shown}");
}

// ---- meshes that should render ----------------------------------------------------------

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

// ---- environment maps ----------------------------------------------------------------------

/// A 2:1 Radiance HDR of `w` × `w/2` texels, every one `c`.
fn hdr_bytes(w: u32, c: f32) -> Vec<u8> {
    let img = image::Rgb32FImage::from_pixel(w, w / 2, image::Rgb([c, c, c]));
    let mut out = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb32F(img).write_to(&mut out, image::ImageFormat::Hdr).expect("encode HDR");
    out.into_inner()
}

#[test]
fn bad_environment_maps() {
    // Line 18 is `[environment]`, line 19 `map = ...`, its value at column 7.
    let with_map = |map: &str| append(&format!("\n[environment]\nmap = \"{map}\"\n"));
    fails(&with_map("nope.hdr")).at(19, 7).key("environment.map").says("nope.hdr: file not found").hint("relative to the lesson file");
    // Not an image at all.
    let ws = Workspace::new(&with_map("sky.hdr"));
    ws.write("sky.hdr", "hello, world\n");
    ws.render_fails(&[]).at(19, 7).key("environment.map").says("sky.hdr: ").hint("latitude-longitude map");
    // An image that is not 2:1.
    let ws = Workspace::new(&with_map("square.png"));
    image::RgbImage::new(8, 8).save(ws.path("square.png")).expect("write PNG");
    ws.render_fails(&[]).at(19, 7).says("square.png: 8×8 is not a latitude-longitude map").hint("2:1");
    // Truncated: the header is fine, the pixels stop half way.
    let ws = Workspace::new(&with_map("cut.hdr"));
    let bytes = hdr_bytes(64, 1.0);
    std::fs::write(ws.path("cut.hdr"), &bytes[..bytes.len() / 2]).expect("write");
    ws.render_fails(&[]).at(19, 7).key("environment.map").says("cut.hdr: cannot decode the map");
    // A latlong environment without a map, and a key the gradient does not read.
    fails(&append("\n[environment]\nintensity = 2\n")).key("environment.map").says("needs `map`").hint("gradient");
    fails(&append("\n[environment]\nkind = \"gradient\"\nmap = \"sky.hdr\"\n"))
        .at(20, 1)
        .says("`map` is not used by `kind = \"gradient\"`");
    // Limits and ranges.
    fails(&append("\n[render]\nenv_samples = 100000\n")).at(19, 15).key("render.env_samples");
    fails(&append("\n[environment]\nkind = \"gradient\"\nintensity = -1\n")).key("environment.intensity");
    fails(&append("\n[render]\nibl = \"magic\"\n")).key("render.ibl").hint("reference");
    // A mirror reads only its tint.
    fails(&edit("model = \"blinn_phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 32", "model = \"mirror\"\nshininess = 32"))
        .key("material.plastic.shininess")
        .says("not used by `mirror`");
    // A good map renders.
    let ws = Workspace::new(&with_map("sky.hdr"));
    std::fs::write(ws.path("sky.hdr"), hdr_bytes(16, 0.5)).expect("write");
    ws.render_ok(&[]);
}

#[test]
fn bad_cube_maps() {
    // Line 18 is `[environment]`, 19 `kind = "cube"`, 20 `faces = [...]` (value at column 9) or `cross = ...`.
    let with = |key: &str, value: &str| append(&format!("\n[environment]\nkind = \"cube\"\n{key} = {value}\n"));
    let six = r#"["px.png", "nx.png", "py.png", "ny.png", "pz.png", "nz.png"]"#;
    let write_faces = |ws: &Workspace, sizes: [u32; 6]| {
        for (name, n) in ["px", "nx", "py", "ny", "pz", "nz"].into_iter().zip(sizes) {
            image::RgbImage::from_pixel(n, n, image::Rgb([40, 80, 120])).save(ws.path(&format!("{name}.png"))).expect("write PNG");
        }
    };
    // Six faces of one size render.
    let ws = Workspace::new(&with("faces", six));
    write_faces(&ws, [8; 6]);
    ws.render_ok(&[]);
    // Faces of unequal size: the face at fault is named, with its index.
    let ws = Workspace::new(&with("faces", six));
    write_faces(&ws, [8, 8, 8, 16, 8, 8]);
    ws.render_fails(&[]).key("environment.faces.3").says("ny.png: 16×16 is not the size of the first face (px.png, 8×8)").hint("one size");
    // Not square.
    let ws = Workspace::new(&with("faces", six));
    write_faces(&ws, [8; 6]);
    image::RgbImage::new(8, 4).save(ws.path("pz.png")).expect("write PNG");
    ws.render_fails(&[]).key("environment.faces.4").says("pz.png: 8×4 is not a square cube face");
    // Five faces.
    let ws = Workspace::new(&with("faces", r#"["px.png", "nx.png", "py.png", "ny.png", "pz.png"]"#));
    write_faces(&ws, [8; 6]);
    ws.render_fails(&[]).at(20, 9).key("environment.faces").says("a cube map has 6 faces, not 5").hint("px, nx, py, ny, pz, nz");
    // A missing face and a face that is no image.
    let ws = Workspace::new(&with("faces", six));
    write_faces(&ws, [8; 6]);
    std::fs::remove_file(ws.path("py.png")).expect("remove");
    ws.render_fails(&[]).key("environment.faces.2").says("py.png: file not found");
    ws.write("py.png", "hello, world\n");
    ws.render_fails(&[]).key("environment.faces.2").says("py.png: ").hint("square cube face");
    // A cross that is not 4:3, or whose width is not a multiple of 4.
    for (w, h) in [(32, 16), (30, 24)] {
        let ws = Workspace::new(&with("cross", "\"cross.png\""));
        image::RgbImage::new(w, h).save(ws.path("cross.png")).expect("write PNG");
        ws.render_fails(&[])
            .at(20, 9)
            .key("environment.cross")
            .says(&format!("cross.png: {w}×{h} is not a horizontal cross"))
            .hint("4N × 3N");
    }
    // A good cross renders.
    let ws = Workspace::new(&with("cross", "\"cross.png\""));
    image::RgbImage::new(32, 24).save(ws.path("cross.png")).expect("write PNG");
    ws.render_ok(&[]);
    // Neither key, both keys, and a latlong key on a cube.
    fails(&append("\n[environment]\nkind = \"cube\"\n")).key("environment.faces").says("needs `faces` or `cross`");
    fails(&with("faces", &format!("{six}\ncross = \"c.png\""))).key("environment.cross").says("not both");
    fails(&with("map", "\"sky.hdr\"")).says("`map` is not used by `kind = \"cube\"`");
}
