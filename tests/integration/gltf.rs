//! glTF 2.0: `export` then `import` renders the same picture, `import` converts a
//! Blender-style file's lights, camera and materials by the specification's units, and a
//! broken or hostile file is exit 2 with its JSON path and nothing written.

use crate::helpers::{read_png, shadelab};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Renders `lesson` to a PNG in `dir` named `name`.
fn render(lesson: &Path, dir: &Path, name: &str) -> image::RgbImage {
    let out = dir.join(name);
    shadelab().arg("render").arg(lesson).arg("-o").arg(&out).arg("-q").assert().success();
    read_png(&out)
}

/// The largest difference of any channel, and how many channels differ.
fn diff(a: &image::RgbImage, b: &image::RgbImage) -> (u8, usize) {
    assert_eq!(a.dimensions(), b.dimensions());
    let d: Vec<u8> = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| x.abs_diff(*y)).collect();
    (d.iter().copied().max().unwrap_or(0), d.iter().filter(|x| **x > 0).count())
}

/// Exports `source`, imports the .glb beside a lesson in the same folder, renders both.
fn round_trip(source: &Path) -> (image::RgbImage, image::RgbImage, String) {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("scene.glb");
    shadelab().arg("export").arg(source).arg("-o").arg(&glb).arg("-q").assert().success();
    let lesson = dir.path().join("scene.toml");
    shadelab().arg("import").arg(&glb).arg("-o").arg(&lesson).arg("-q").assert().success();
    let text = std::fs::read_to_string(&lesson).unwrap();
    (render(source, dir.path(), "a.png"), render(&lesson, dir.path(), "b.png"), text)
}

#[test]
fn export_then_import_renders_the_same_picture() {
    // The bundled scene: principled materials (metal, clearcoat), two profile spots, a point light.
    let (a, b, text) = round_trip(&root().join("tools/gltf/three-point.toml"));
    let (max, n) = diff(&a, &b);
    assert!(max <= 1, "the round trip moved a channel by {max} codes ({n} channels differ)\n{text}");
    // Glass, a mirror, emission, a directional light and a cos^n spot.
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("mixed.toml");
    std::fs::write(
        &src,
        r#"[camera]
position = [0.0, 1.5, 5.0]
look_at = [0.0, 0.6, 0.0]
size = [96, 72]
background = [0.1, 0.12, 0.2]

[[object]]
shape = "icosphere"
subdivisions = 3
translate = [-0.9, 0.7, 0.0]
scale = 0.6
material = "glass"

[[object]]
shape = "uv_sphere"
translate = [0.9, 0.7, 0.0]
scale = 0.6
material = "lamp"

[[object]]
shape = "cube"
translate = [0.0, 0.3, -1.2]
scale = 0.3
material = "chrome"

[[object]]
shape = "plane"
scale = 4
material = "floor"

[material.glass]
model = "glass"
ior = 1.45

[material.lamp]
model = "principled"
base_color = [0.9, 0.3, 0.2]
roughness = 0.4
emission = [2.0, 1.5, 0.5]

[material.chrome]
model = "mirror"
tint = 0.9

[material.floor]
model = "principled"
base_color = [0.5, 0.5, 0.5]
roughness = 0.7

[[light]]
kind = "directional"
direction = [-0.3, -1.0, -0.4]
intensity = 2.0
color = [1.0, 0.95, 0.9]

[[light]]
kind = "spot"
position = [2.0, 3.0, 2.0]
direction = [-2.0, -3.0, -2.0]
exponent = 8
cutoff_deg = 35
intensity = 6.0
"#,
    )
    .unwrap();
    let (a, b, text) = round_trip(&src);
    let (max, n) = diff(&a, &b);
    assert!(max <= 1, "the round trip moved a channel by {max} codes ({n} channels differ)\n{text}");
    assert!(text.contains("model = \"glass\"") && text.contains("exponent = 8.0") && text.contains("cutoff_deg = 35"), "{text}");
}

/// A one-triangle glTF (separate `tri.bin`) in `dir` with `edit` applied to its JSON.
fn triangle_gltf(dir: &Path, edit: impl FnOnce(&mut Value)) -> PathBuf {
    let mut bin: Vec<u8> = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
    bin.extend([0u16, 1, 2, 0].iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(dir.join("tri.bin"), &bin).unwrap();
    let mut doc = json!({
        "asset": { "version": "2.0", "generator": "test" },
        "scene": 0,
        "scenes": [{ "nodes": [0, 1, 2, 3, 4] }],
        "nodes": [
            { "mesh": 0, "name": "Tri" },
            { "camera": 0, "translation": [0.3, 0.3, 3.0], "name": "Camera" },
            { "extensions": { "KHR_lights_punctual": { "light": 0 } }, "translation": [0.0, 2.0, 2.0], "name": "Lamp" },
            { "extensions": { "KHR_lights_punctual": { "light": 1 } }, "translation": [0.0, 3.0, 0.0],
              "rotation": [-0.70710677, 0.0, 0.0, 0.70710677], "name": "Spot" },
            { "extensions": { "KHR_lights_punctual": { "light": 2 } }, "name": "Sun" }
        ],
        "cameras": [{ "type": "perspective", "perspective": { "yfov": 0.6, "aspectRatio": 1.5, "znear": 0.1 } }],
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "point", "intensity": 54351.4, "color": [1.0, 0.9, 0.8] },
            { "type": "spot", "intensity": 683.0, "spot": { "innerConeAngle": 0.2, "outerConeAngle": 0.5 }, "range": 10.0 },
            { "type": "directional", "intensity": 2049.0 }
        ] } },
        "materials": [{ "name": "Red", "pbrMetallicRoughness": { "baseColorFactor": [0.8, 0.1, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.4 },
            "emissiveFactor": [1.0, 0.5, 0.0], "extensions": { "KHR_materials_emissive_strength": { "emissiveStrength": 3.0 } } }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1, "material": 0 }] }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR" }
        ],
        "bufferViews": [{ "buffer": 0, "byteLength": 36 }, { "buffer": 0, "byteOffset": 36, "byteLength": 6 }],
        "buffers": [{ "uri": "tri.bin", "byteLength": 44 }],
        "animations": [{ "channels": [], "samplers": [] }]
    });
    edit(&mut doc);
    let path = dir.join("tri.gltf");
    std::fs::write(&path, serde_json::to_string_pretty(&doc).unwrap()).unwrap();
    path
}

/// The number after `key = ` in the table that follows `header` in `text`.
fn value_after(text: &str, header: &str, key: &str) -> f64 {
    let from = text.find(header).unwrap_or_else(|| panic!("no {header} in\n{text}"));
    let line = text[from..].lines().find(|l| l.starts_with(&format!("{key} = "))).unwrap_or_else(|| panic!("no {key} after {header}"));
    line[key.len() + 3..].split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn import_converts_lights_camera_and_materials_by_the_specification() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf(dir.path(), |_| {});
    let out = shadelab().arg("import").arg(&gltf).arg("-o").arg(dir.path().join("tri.toml")).assert().success().get_output().clone();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let text = std::fs::read_to_string(dir.path().join("tri.toml")).unwrap();
    // Point: candela / 683 = W/sr (54351.4 cd is Blender's 1000 W: 79.58 W/sr).
    assert!((value_after(&text, "# Lamp", "intensity") - 54351.4 / 683.0).abs() < 1e-3, "{text}");
    // Spot: 683 cd is 1 W/sr on the axis; the cone runs out at 0.5 rad = 28.648°.
    assert!((value_after(&text, "# Spot", "intensity") - 1.0).abs() < 1e-6);
    assert!((value_after(&text, "# Spot", "cutoff_deg") - 0.5f64.to_degrees()).abs() < 1e-3);
    // Rotated -90° about x: the spot points down.
    assert!(text.contains("direction = [0.0, -1.0, 0.0]") || text.contains("direction = [0.0, -1.0, -0.0]"), "{text}");
    // Directional: lux / 683 = W/m².
    assert!((value_after(&text, "# Sun", "intensity") - 3.0).abs() < 1e-6);
    // Camera: yfov 0.6 rad, aspect 1.5 → 640 × 427.
    assert!((value_after(&text, "[camera]", "fov_deg") - 0.6f64.to_degrees()).abs() < 1e-3);
    assert!(text.contains("size = [640, 427]"), "{text}");
    // Emission = emissiveFactor × emissiveStrength; Disney specular 0.5 at the default η.
    assert!(text.contains("emission = [3.0, 1.5, 0.0]"), "{text}");
    assert!((value_after(&text, "[material.Red]", "specular") - 0.5).abs() < 1e-6);
    // What is not read is said, with where.
    assert!(stderr.contains("range is not read") && stderr.contains("/extensions/KHR_lights_punctual/lights/1"), "{stderr}");
    assert!(stderr.contains("1 animation not read"), "{stderr}");
    // The lesson renders: the warm, brightly lit triangle is on screen, the background is not.
    let img = render(&dir.path().join("tri.toml"), dir.path(), "tri.png");
    let [r, _, b] = img.get_pixel(300, 200).0;
    assert!(r > 200 && r > b + 20, "the triangle is not in the picture: {:?}", img.get_pixel(300, 200));
    assert!(img.get_pixel(10, 10).0[0] < 100);
}

/// Standard base64 with padding (for data URIs in test files).
fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16 | (*c.get(1).unwrap_or(&0) as u32) << 8 | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            out.push(if k <= c.len() { ABC[(n >> (18 - 6 * k) & 63) as usize] as char } else { '=' });
        }
    }
    out
}

/// A 2 × 2 PNG of one colour.
fn png(rgb: [u8; 3]) -> Vec<u8> {
    let img = image::RgbImage::from_pixel(2, 2, image::Rgb(rgb));
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

#[test]
fn textures_are_extracted_or_named_and_exported_embedded() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // An embedded image (a data URI) is written beside the lesson; an image file is named.
    let data = png([200, 40, 40]);
    let g = triangle_gltf(d, |j| {
        j["images"] = json!([{ "uri": format!("data:image/png;base64,{}", base64(&data)) }, { "uri": "tex%20file.png" }]);
        j["textures"] = json!([{ "source": 0 }, { "source": 1 }]);
        j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
        j["materials"][0]["normalTexture"] = json!({ "index": 1, "scale": 0.5 });
        j["materials"][0]["occlusionTexture"] = json!({ "index": 1 });
    });
    std::fs::write(d.join("tex file.png"), png([128, 128, 255])).unwrap();
    let out = shadelab().arg("import").arg(&g).arg("-o").arg(d.join("tri.toml")).assert().success().get_output().clone();
    let text = std::fs::read_to_string(d.join("tri.toml")).unwrap();
    assert!(text.contains("base_color = { texture = \"tri-textures/image-0.png\" }"), "{text}");
    assert!(text.contains("normal_map = \"tex file.png\""), "{text}");
    assert!(text.contains("occlusion_map = \"tex file.png\""), "glTF's occlusion is the ambient-occlusion map: {text}");
    assert_eq!(std::fs::read(d.join("tri-textures/image-0.png")).unwrap(), data);
    assert!(String::from_utf8_lossy(&out.stderr).contains("/materials/0/normalTexture: scale 0.5 is not read"));
    shadelab().arg("check").arg(d.join("tri.toml")).assert().success();
    // An image that does not decode is dropped aloud: the factor stands, the lesson renders.
    let g = triangle_gltf(d, |j| {
        j["images"] = json!([{ "uri": format!("data:image/png;base64,{}", base64(&data[..40])) }]);
        j["textures"] = json!([{ "source": 0 }]);
        j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    });
    let out = shadelab().arg("import").arg(&g).arg("-o").arg(d.join("cut.toml")).assert().success().get_output().clone();
    assert!(String::from_utf8_lossy(&out.stderr).contains("image 0 does not decode"), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(d.join("cut.toml")).unwrap();
    assert!(text.contains("base_color = [0.8, 0.1, 0.1]"), "{text}");
    render(&d.join("cut.toml"), d, "cut.png");
    // A textured lesson exports its base colour embedded, and comes back the same.
    std::fs::write(d.join("checker.png"), {
        let img =
            image::RgbImage::from_fn(
                8,
                8,
                |x, y| if (x / 2 + y / 2) % 2 == 0 { image::Rgb([220, 180, 60]) } else { image::Rgb([30, 60, 160]) },
            );
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Png).unwrap();
        out.into_inner()
    })
    .unwrap();
    // Roughness in green and metallic in blue of one image, as glTF packs them.
    std::fs::write(d.join("mr.png"), {
        let img = image::RgbImage::from_fn(8, 8, |x, _| image::Rgb([0, 40 + 25 * x as u8, if x < 4 { 0 } else { 255 }]));
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Png).unwrap();
        out.into_inner()
    })
    .unwrap();
    std::fs::write(
        d.join("textured.toml"),
        "[camera]\nposition = [0.0, 2.0, 3.0]\nsize = [64, 48]\n\n[[object]]\nshape = \"plane\"\nmaterial = \"m\"\n\n[material.m]\nmodel = \"principled\"\nbase_color = { texture = \"checker.png\" }\nroughness = { texture = \"mr.png\", channel = \"g\" }\nmetallic = { texture = \"mr.png\", channel = \"b\" }\nocclusion_map = \"checker.png\"\n\n[[light]]\nkind = \"directional\"\ndirection = [0.0, -1.0, -0.5]\nintensity = 3.0\n",
    )
    .unwrap();
    let (a, b, text) = round_trip(&d.join("textured.toml"));
    assert!(text.contains("base_color = { texture = \"scene-textures/image-0.png\" }"), "{text}");
    assert!(text.contains("roughness = { texture = \"scene-textures/image-2.png\", channel = \"g\" }"), "{text}");
    assert!(text.contains("occlusion_map = \"scene-textures/image-1.png\""), "the ambient-occlusion map goes out and comes back: {text}");
    // The channel is read: red (0 everywhere) as roughness would be a mirror-smooth floor.
    let plain = d.join("plain.toml");
    std::fs::write(&plain, std::fs::read_to_string(d.join("textured.toml")).unwrap().replace(", channel = \"g\"", "")).unwrap();
    let red = render(&plain, d, "red.png");
    assert!(diff(&a, &red).0 > 10, "reading the red channel looked the same as the green");
    shadelab().arg("check").arg(&plain).assert().success();
    std::fs::write(
        &plain,
        std::fs::read_to_string(d.join("textured.toml")).unwrap().replace("\"checker.png\" }", "\"checker.png\", channel = \"g\" }"),
    )
    .unwrap();
    let out = shadelab().arg("check").arg(&plain).assert().code(2).get_output().clone();
    assert!(String::from_utf8_lossy(&out.stderr).contains("`base_color` is a colour"), "{}", String::from_utf8_lossy(&out.stderr));
    let (max, n) = diff(&a, &b);
    assert!(max <= 1, "the textured round trip moved a channel by {max} codes ({n} channels differ)");
}

/// Imports `gltf` into `dir/out.toml`: exit 2, the message holds each of `says`, and nothing is written.
fn refused(dir: &Path, gltf: &Path, says: &[&str]) {
    let out = shadelab().arg("import").arg(gltf).arg("-o").arg(dir.join("out.toml")).assert().code(2).get_output().clone();
    let stderr = String::from_utf8_lossy(&out.stderr);
    for s in says {
        assert!(stderr.contains(s), "expected {s:?} in:\n{stderr}");
    }
    assert!(stderr.contains("hint:"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!dir.join("out.toml").exists(), "a lesson was written");
}

#[test]
fn a_broken_or_hostile_file_is_refused_with_its_json_path() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let g = triangle_gltf(d, |j| j["buffers"][0]["uri"] = json!("missing.bin"));
    refused(d, &g, &["tri.gltf", "/buffers/0/uri", "missing.bin", "not found"]);
    let g = triangle_gltf(d, |j| j["buffers"][0]["uri"] = json!("../secret.bin"));
    refused(d, &g, &["/buffers/0/uri", "outside the glTF file's folder"]);
    let g = triangle_gltf(d, |j| j["buffers"][0]["uri"] = json!("file:///etc/passwd"));
    refused(d, &g, &["outside the glTF file's folder"]);
    // A missing image, and one outside the folder, as a missing buffer.
    let texture = |uri: &str| {
        let uri = uri.to_string();
        move |j: &mut Value| {
            j["images"] = json!([{ "uri": uri }]);
            j["textures"] = json!([{ "source": 0 }]);
            j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
        }
    };
    let g = triangle_gltf(d, texture("gone.png"));
    refused(d, &g, &["/images/0/uri", "gone.png", "not found"]);
    let g = triangle_gltf(d, texture("../../etc/hosts"));
    refused(d, &g, &["/images/0/uri", "outside the glTF file's folder"]);
    // An index past the vertices, an attribute naming no accessor (the crate panics on it).
    std::fs::write(d.join("tri.bin"), b"").unwrap();
    let g = triangle_gltf(d, |_| {});
    let mut bin: Vec<u8> = [0.0f32; 9].iter().flat_map(|f| f.to_le_bytes()).collect();
    bin.extend([0u16, 1, 7, 0].iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(d.join("tri.bin"), &bin).unwrap();
    refused(d, &g, &["/meshes/0/primitives/0/indices", "index 7 is out of range (3 vertices)"]);
    let g = triangle_gltf(d, |j| j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(9));
    refused(d, &g, &["/meshes/0/primitives/0/attributes/POSITION", "accessor 9 does not exist"]);
    // A view longer than its buffer; a cycle of children; a node with two parents.
    let g = triangle_gltf(d, |j| j["bufferViews"][0]["byteLength"] = json!(4000));
    refused(d, &g, &["does not fit"]);
    let g = triangle_gltf(d, |j| {
        j["nodes"][0]["children"] = json!([1]);
        j["nodes"][1]["children"] = json!([0]);
    });
    refused(d, &g, &["cycle"]);
    let g = triangle_gltf(d, |j| {
        j["nodes"][0]["children"] = json!([2]);
        j["nodes"][1]["children"] = json!([2]);
    });
    refused(d, &g, &["two parents"]);
    // Non-finite positions.
    let g = triangle_gltf(d, |_| {});
    let mut bin: Vec<u8> = [f32::NAN, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0].iter().flat_map(|f| f.to_le_bytes()).collect();
    bin.extend([0u16, 1, 2, 0].iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(d.join("tri.bin"), &bin).unwrap();
    refused(d, &g, &["/meshes/0/primitives/0/attributes/POSITION", "not finite"]);
    // A .glb cut short, and a file that is not glTF at all.
    std::fs::write(d.join("cut.glb"), b"glTF\x02\x00\x00\x00\x04\x00\x00\x00").unwrap();
    refused(d, &d.join("cut.glb"), &["cut.glb", "header"]);
    std::fs::write(d.join("junk.glb"), b"not a scene").unwrap();
    refused(d, &d.join("junk.glb"), &["junk.glb", "not a valid glTF"]);
}

#[test]
fn an_object_names_a_node_and_bad_names_are_placed_in_the_lesson() {
    let dir = tempfile::tempdir().unwrap();
    triangle_gltf(dir.path(), |_| {});
    let lesson = |object: &str| {
        format!(
            "[camera]\nposition = [0.3, 0.3, 3.0]\nlook_at = [0.3, 0.3, 0.0]\nsize = [32, 32]\n\n[[object]]\nshape = \"mesh\"\npath = \"tri.gltf\"\n{object}material = \"m\"\n\n[material.m]\nmodel = \"lambert\"\n\n[[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\n"
        )
    };
    let path = dir.path().join("l.toml");
    std::fs::write(&path, lesson("node = \"Tri\"\n")).unwrap();
    let img = render(&path, dir.path(), "l.png");
    assert!(img.get_pixel(16, 16).0[0] > 100, "the triangle covers the centre");
    std::fs::write(&path, lesson("node = \"Trí\"\n")).unwrap();
    let out = shadelab().arg("render").arg(&path).arg("-o").arg(dir.path().join("x.png")).assert().code(2).get_output().clone();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("l.toml:9:8") && stderr.contains("no mesh node `Trí`") && stderr.contains("`Tri`"), "{stderr}");
    // `node` on an OBJ mesh, `primitive` without `node`.
    std::fs::write(dir.path().join("m.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(&path, lesson("node = 0\n").replace("tri.gltf", "m.obj")).unwrap();
    let out = shadelab().arg("check").arg(&path).assert().code(2).get_output().clone();
    assert!(String::from_utf8_lossy(&out.stderr).contains("only glTF files have nodes"));
    std::fs::write(&path, lesson("primitive = 0\n")).unwrap();
    let out = shadelab().arg("check").arg(&path).assert().code(2).get_output().clone();
    assert!(String::from_utf8_lossy(&out.stderr).contains("`primitive` needs `node`"));
}

#[test]
fn a_glb_outside_the_lessons_folder_is_copied_beside_it() {
    let src = tempfile::tempdir().unwrap();
    let dst = tempfile::tempdir().unwrap();
    let glb = src.path().join("scene.glb");
    std::fs::copy(root().join("lessons/gltf/three-point.glb"), &glb).unwrap();
    let out = shadelab().arg("import").arg(&glb).arg("-o").arg(dst.path().join("s.toml")).assert().success().get_output().clone();
    assert!(String::from_utf8_lossy(&out.stdout).contains("copied scene.glb beside the lesson"));
    assert_eq!(std::fs::read(dst.path().join("scene.glb")).unwrap(), std::fs::read(&glb).unwrap());
    shadelab().arg("check").arg(dst.path().join("s.toml")).assert().success();
    // A second import does not overwrite the lesson without --force.
    shadelab().arg("import").arg(&glb).arg("-o").arg(dst.path().join("s.toml")).assert().code(2);
    shadelab().arg("import").arg(&glb).arg("-o").arg(dst.path().join("s.toml")).arg("--force").assert().success();
}
