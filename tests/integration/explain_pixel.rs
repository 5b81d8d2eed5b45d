//! `explain --pixel`: the command as a user and a tool outside this repository run it (the
//! flag and field names are a contract), and the `probe` figure's validation.

use crate::helpers::{lesson_file, lessons_dir, shadelab};
use serde_json::Value;

/// `explain LESSON --pixel ... EXTRA` on a bundled lesson.
fn explain(name: &str, pixels: &[&str], extra: &[&str]) -> std::process::Output {
    let mut cmd = shadelab();
    cmd.args(["--threads", "2", "explain"]).arg(lessons_dir().join(name));
    for p in pixels {
        cmd.args(["--pixel", p]);
    }
    cmd.args(extra).output().unwrap()
}

#[test]
fn jsonl_gives_the_pngs_codes_and_the_rendered_values_under_the_documented_names() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("r.png");
    let exr = dir.path().join("r.exr");
    for out in [&png, &exr] {
        let st = shadelab().args(["render"]).arg(lessons_dir().join("37-one-pixel.toml")).arg("-o").arg(out).output().unwrap();
        assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
    }
    let img = image::open(&png).unwrap().to_rgb8();
    let linear = image::open(&exr).unwrap().to_rgb32f();
    let pixels = ["115,136", "185,180", "350,103", "5,5"];
    let out = explain("37-one-pixel.toml", &pixels, &["--format", "jsonl"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let lines: Vec<Value> = String::from_utf8(out.stdout).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), pixels.len(), "one object per pixel");
    for (o, p) in lines.iter().zip(pixels) {
        let (x, y) = p.split_once(',').unwrap();
        let (x, y): (u32, u32) = (x.parse().unwrap(), y.parse().unwrap());
        assert_eq!(o["pixel"], serde_json::json!([x, y]));
        let srgb: Vec<u8> = o["srgb"].as_array().unwrap().iter().map(|v| v.as_u64().unwrap() as u8).collect();
        assert_eq!(srgb, img.get_pixel(x, y).0, "{p}: the PNG's code");
        let lin: Vec<f32> = o["linear"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap() as f32).collect();
        let want = linear.get_pixel(x, y).0;
        for c in 0..3 {
            assert!((lin[c] - want[c]).abs() <= 1e-5 * want[c].abs().max(1e-3), "{p}: linear {lin:?} vs the EXR's {want:?}");
        }
        if o["background"] == true {
            assert!(o["object"].is_null() && o["lights"].as_array().unwrap().is_empty(), "{o}");
            continue;
        }
        assert!(o["object"].is_u64() && o["material"].is_string(), "{o}");
        let lights = o["lights"].as_array().unwrap();
        assert_eq!(lights.len(), 2, "the key and the rim light");
        for l in lights {
            assert!(l["n_dot_l"].is_f64() && l["terms"]["diffuse"].is_array(), "{l}");
        }
        assert_eq!(o["difference"], serde_json::json!([0.0, 0.0, 0.0]), "{p}: the explanation is the render's arithmetic");
    }
    // The shadowed floor point: the key light blocked by the first ball.
    let floor = &lines[1];
    assert_eq!(floor["material"], "floor");
    assert_eq!(floor["lights"][0]["visibility"], 0.0);
    assert_eq!(floor["lights"][0]["occluder"], 0);
    assert_eq!(floor["lights"][0]["terms"]["diffuse"], serde_json::json!([0.0, 0.0, 0.0]));
}

#[test]
fn text_names_every_vector_and_term_and_the_background_is_said_plainly() {
    let out = explain("01-first-light.toml", &["300,200", "3,3"], &[]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    for want in ["N·L = ", "R·V = ", "N·H = ", "H = (", "K_spec max(N·H, 0)^48", "global ambient", "rendered − sum = (0, 0, 0)", "sRGB ("]
    {
        assert!(text.contains(want), "no `{want}` in\n{text}");
    }
    // Lesson 01 renders at aa = 2: the centre sample is explained, and said so.
    assert!(text.contains("aa = 2: this explains the pixel's centre sample"), "{text}");
    assert!(text.contains("pixel (3, 3): the background"), "{text}");
}

#[test]
fn a_pixel_outside_the_image_or_malformed_is_bad_input() {
    let out = explain("01-first-light.toml", &["512,0"], &[]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("01-first-light.toml") && err.contains("pixel 512,0 is outside the 512×512 image") && err.contains("0..=511"),
        "{err}"
    );
    for bad in ["12", "a,3", "-1,4", "3,"] {
        let out = explain("01-first-light.toml", &[bad], &[]);
        assert_eq!(out.status.code(), Some(2), "--pixel {bad}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("--pixel"), "--pixel {bad}");
    }
    // --format and -o belong to --pixel.
    let out = shadelab().args(["explain"]).arg(lessons_dir().join("01-first-light.toml")).args(["--format", "jsonl"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn the_probe_picture_is_written_whole_and_larger_than_the_render() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("probe.png");
    let out = explain("37-one-pixel.toml", &["115,136", "224,138"], &["-q", "-o", png.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stdout.is_empty(), "-q prints nothing");
    let img = image::open(&png).unwrap().to_rgb8();
    // 480 × 300 enlarged twice, with the chart beside it and the legend and captions under it.
    assert!(img.width() > 960 + 400 && img.height() > 600 + 100, "{}×{}", img.width(), img.height());
    // The ring at the first point: white pixels around (115.5, 136.5) × 2 + the margin.
    let (cx, cy) = (16 + 231, 16 + 273);
    let white = (0..360).step_by(10).filter(|a| {
        let t = (*a as f32).to_radians();
        let p = img.get_pixel((cx as f32 + 6.0 * t.cos()).round() as u32, (cy as f32 + 6.0 * t.sin()).round() as u32);
        p.0.iter().all(|&c| c > 200)
    });
    assert!(white.count() > 20, "a white ring marks the probed pixel");
}

#[test]
fn a_probe_figure_is_validated_where_it_is_written() {
    let lesson = |figure: &str| {
        format!(
            "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nsize = [64, 48]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[material.m]\nmodel = \"lambert\"\n[[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\n[[figure]]\nname = \"p\"\n{figure}"
        )
    };
    // Each case: the figure, the message, and the key whose line the error names (none: anywhere).
    let cases = [
        ("kind = \"probe\"\npixels = [[10, 10], [64, 3]]\n", "pixel [64, 3] is outside the 64×48 image", Some("pixels")),
        ("kind = \"probe\"\n", "a `probe` figure needs `pixels`", None),
        ("kind = \"probe\"\npixels = []\n", "0 pixels: a probe figure explains 1 to 8", Some("pixels")),
        (
            "kind = \"compare\"\nvary = \"render.interpolation\"\nvalues = [\"flat\", \"phong\"]\npixels = [[1, 1]]\n",
            "`pixels` is not used",
            Some("pixels"),
        ),
        ("kind = \"probe\"\npixels = [[1, 1]]\nvary = \"render.interpolation\"\n", "`vary` needs `values`", None),
    ];
    for (figure, message, key) in cases {
        let text = lesson(figure);
        let (_dir, path) = lesson_file("probe.toml", &text);
        let out = shadelab().arg("check").arg(&path).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{figure}");
        let err = String::from_utf8(out.stderr).unwrap();
        let at = match key {
            Some(k) => format!("probe.toml:{}:", text.lines().position(|l| l.starts_with(k)).unwrap() + 1),
            None => "probe.toml:".into(),
        };
        assert!(err.contains(message) && err.contains(&at), "{figure} → {err} (want {at})");
    }
    // A good one renders: the figure is the probe picture under the title.
    let (dir, path) = lesson_file("probe.toml", &lesson("kind = \"probe\"\npixels = [[32, 24], [1, 1]]\n"));
    let out = shadelab().arg("figures").arg(&path).arg("-o").arg(dir.path()).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let img = image::open(dir.path().join("probe").join("p.png")).unwrap();
    assert!(img.width() > 720, "the 64-pixel render enlarged: {}", img.width());
}
