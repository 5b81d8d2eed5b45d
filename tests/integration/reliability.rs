//! Regression tests for the findings of the reliability and security campaign, one per
//! finding, named after it: files outside the lesson's folder, non-finite mesh data, total
//! limits, performance cliffs, misleading messages and output errors (the sRGB rounding slip
//! is `render::develop::tests::srgb_encode_rounding_slip_at_a_midpoint`).

use crate::helpers::{lessons_dir, shadelab};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

const CANARY: &str = "v secret_api_key=canary";

/// A folder with `lesson/lesson.toml` (lesson 01 with object 0 made a mesh at `path`),
/// `lesson/m.obj` (`obj`), and `secret.obj` outside the lesson's folder.
struct Tree {
    dir: tempfile::TempDir,
}

impl Tree {
    fn new(path: &str, obj: &str) -> Tree {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("lesson");
        std::fs::create_dir_all(folder.join("sub")).unwrap();
        std::fs::write(dir.path().join("secret.obj"), format!("{CANARY}\nv 0 0 0\nv 1 0 0\nf 1 2 3\n")).unwrap();
        std::fs::write(folder.join("m.obj"), obj).unwrap();
        let base = std::fs::read_to_string(lessons_dir().join("01-first-light.toml")).unwrap();
        let text = base.replacen("shape = \"uv_sphere\"", &format!("shape = \"mesh\"\npath = {}", toml::Value::from(path)), 1).replacen(
            "segments = 64\nrings = 32\n",
            "",
            1,
        );
        std::fs::write(folder.join("lesson.toml"), text).unwrap();
        Tree { dir }
    }
    fn folder(&self) -> PathBuf {
        self.dir.path().join("lesson")
    }
    fn lesson(&self) -> PathBuf {
        self.folder().join("lesson.toml")
    }
    /// Runs `shadelab ARGS` and returns (exit code, stderr).
    fn run(&self, args: &[&str]) -> (Option<i32>, String) {
        let out = shadelab().args(args).current_dir(self.dir.path()).output().unwrap();
        (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
    }
    /// `render LESSON -o out/x.png` must fail with exit 2 and leave no file.
    fn render_fails(&self, extra: &[&str]) -> String {
        let lesson = self.lesson();
        let out = self.dir.path().join("out").join("x.png");
        let mut args = vec!["render", lesson.to_str().unwrap(), "-o", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        let (code, stderr) = self.run(&args);
        assert_eq!(code, Some(2), "{stderr}");
        assert!(stderr.starts_with("error: "), "{stderr}");
        assert!(!out.exists() && !out.parent().unwrap().exists(), "output written: {stderr}");
        stderr
    }
}

const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

#[test]
fn files_outside_the_lesson_folder_are_read() {
    for path in ["../secret.obj", "../../../../../../../../etc/passwd", "/etc/passwd", "/proc/self/status"] {
        let tree = Tree::new(path, QUAD);
        let stderr = tree.render_fails(&[]);
        assert!(stderr.contains(&format!("{path}: outside the lesson's folder")), "{stderr}");
        assert!(stderr.contains("--allow-dir"), "{stderr}");
        assert!(!stderr.contains("secret_api_key") && !stderr.contains("root:"), "{stderr}");
    }
    #[cfg(unix)]
    {
        // A symlink inside pointing out is refused; one pointing in is followed.
        let tree = Tree::new("out.obj", QUAD);
        std::os::unix::fs::symlink(tree.dir.path().join("secret.obj"), tree.folder().join("out.obj")).unwrap();
        let stderr = tree.render_fails(&[]);
        assert!(stderr.contains("out.obj: outside the lesson's folder") && !stderr.contains("secret_api_key"), "{stderr}");
        let tree = Tree::new("in.obj", QUAD);
        std::os::unix::fs::symlink(tree.folder().join("m.obj"), tree.folder().join("in.obj")).unwrap();
        let (code, stderr) = tree.run(&["check", tree.lesson().to_str().unwrap()]);
        assert_eq!(code, Some(0), "{stderr}");
        // A symlink to /dev/zero is outside; a FIFO and a folder are named for what they are.
        let tree = Tree::new("zero.obj", QUAD);
        std::os::unix::fs::symlink("/dev/zero", tree.folder().join("zero.obj")).unwrap();
        assert!(tree.render_fails(&[]).contains("zero.obj: outside the lesson's folder"));
        let tree = Tree::new("pipe.obj", QUAD);
        if std::process::Command::new("mkfifo").arg(tree.folder().join("pipe.obj")).status().is_ok_and(|s| s.success()) {
            assert!(tree.render_fails(&[]).contains("pipe.obj: is a FIFO (named pipe), not a regular file"));
        }
        let tree = Tree::new("sub", QUAD);
        assert!(tree.render_fails(&[]).contains("sub: is a folder, not a regular file"));
    }
    // --allow-dir lets a lesson read files under another folder.
    let tree = Tree::new("../secret.obj", QUAD);
    let secret_dir = tree.dir.path().to_str().unwrap().to_string();
    let (code, stderr) = tree.run(&["--allow-dir", &secret_dir, "check", tree.lesson().to_str().unwrap()]);
    // Allowed, so read: and then refused as OBJ for its first line (the user allowed it).
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("secret.obj:1:"), "{stderr}");
    let (code, stderr) = tree.run(&["--allow-dir", "/nonexistent-folder", "check", tree.lesson().to_str().unwrap()]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("--allow-dir /nonexistent-folder: not found"), "{stderr}");
}

#[test]
fn non_finite_mesh_data_is_accepted() {
    let cases = [
        ("v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", "m.obj:2: `v 1 0 nan`: `nan` is not a finite number"),
        ("v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n", "m.obj:2: `v 1 0 inf`: `inf` is not a finite number"),
        ("v 0 0 0\nv 1 0 1e39\nv 0 1 0\nf 1 2 3\n", "m.obj:2: `v 1 0 1e39`: `1e39` is out of range"),
        ("v 0 0 0\nv 1 0 0 nan\nv 0 1 0\nf 1 2 3\n", "m.obj:2: `v 1 0 0 nan`: `nan` is not a finite number"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 nan\nf 1//1 2//1 3//1\n", "m.obj:4: `vn 0 0 nan`"),
    ];
    for (obj, says) in cases {
        let tree = Tree::new("m.obj", obj);
        let stderr = tree.render_fails(&[]);
        assert!(stderr.contains("lesson.toml:") && stderr.contains(says), "{obj:?}: {stderr}");
        let (code, stderr) = tree.run(&["check", tree.lesson().to_str().unwrap()]);
        assert_eq!(code, Some(2), "{stderr}");
        assert!(stderr.contains(says), "{stderr}");
    }
}

#[test]
fn no_total_limits() {
    let tree = Tree::new("m.obj", QUAD);
    let lesson = tree.lesson();
    let torus = "{shape=\"torus\",material=\"plastic\",segments=2048,sides=2048}";
    let six = format!("object=[{}]", [torus; 6].join(","));
    let start = Instant::now();
    let stderr = tree.render_fails(&["--set", &six]);
    assert!(start.elapsed() < Duration::from_secs(10), "the limit is checked before work");
    assert!(
        stderr.contains("`object.2`: objects 0 to 2 have 25165824 triangles after tessellation, more than the limit of 20000000"),
        "{stderr}"
    );
    // An OBJ larger than the limit is refused by its size, before it is read (a sparse file).
    let big = std::fs::File::create(tree.folder().join("big.obj")).unwrap();
    big.set_len(600 * 1024 * 1024).unwrap();
    let start = Instant::now();
    let stderr = tree.render_fails(&["--set", "object.0.path=\"big.obj\""]);
    assert!(start.elapsed() < Duration::from_secs(10));
    assert!(stderr.contains("big.obj: 629145600 bytes, more than the limit of 536870912 bytes for an OBJ file"), "{stderr}");
    // A figure of 64 cells of 4096² is refused before any cell is rendered.
    let out = tree.dir.path().join("fig.png");
    let (code, stderr) = tree.run(&[
        "sweep",
        lesson.to_str().unwrap(),
        "--vary",
        "material.plastic.shininess=1..64:log:64",
        "--cell",
        "4096x4096",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("64 cells of 4096×4096 pixels is 1073741824 pixels, more than the limit of 40000000"), "{stderr}");
    assert!(!out.exists());
}

#[test]
fn performance_cliffs_on_valid_input() {
    // The vertex-normal overlay was quadratic (200k triangles: 19 s). A sphere of 2048 × 64
    // has 258k triangles; the whole split with both overlays takes well under a second now.
    let tree = Tree::new("m.obj", QUAD);
    let text = std::fs::read_to_string(tree.lesson()).unwrap().replacen(
        "shape = \"mesh\"\npath = \"m.obj\"",
        "shape = \"uv_sphere\"\nsegments = 2048\nrings = 64",
        1,
    ) + "\n[[figure]]\nname = \"hedgehog\"\nkind = \"split\"\nlayers = [\"total\"]\nnormals = \"both\"\n";
    std::fs::write(tree.lesson(), text).unwrap();
    let out = tree.dir.path().join("figs");
    let start = Instant::now();
    let (code, stderr) = tree.run(&["--threads", "1", "figures", tree.lesson().to_str().unwrap(), "-o", out.to_str().unwrap(), "-q"]);
    assert_eq!(code, Some(0), "{stderr}");
    let took = start.elapsed();
    assert!(took < Duration::from_secs(8), "overlay of 258k triangles took {took:?}");
    assert!(out.join("lesson").join("hedgehog.png").exists());
}

#[test]
fn misleading_messages() {
    // brdf eval reads f64: huge finite values are directions, not [0, 0, 0] or "not finite".
    let lesson = lessons_dir().join("09-microfacet-ndfs.toml");
    let text = std::fs::read_to_string(&lesson).unwrap();
    let material = text.lines().find_map(|l| l.strip_prefix("[material.")).map(|l| l.trim_end_matches(']').to_string()).unwrap();
    let material = material.trim_matches('"').to_string();
    let out = shadelab()
        .args(["brdf", "eval", lesson.to_str().unwrap(), "--material", &material])
        .write_stdin("1e20,0,1e20,0,0,1\n1e150,0,1e150,0,0,1\n0.5,0,0.5,0,0,1\n")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    let rows: Vec<&str> = stdout.lines().skip(1).collect();
    assert_eq!(rows.len(), 3);
    // The same direction three ways: the same value.
    assert_eq!(rows[0], rows[2], "{stdout}");
    assert_eq!(rows[1], rows[2], "{stdout}");

    // An OBJ with a byte-order mark and end-of-line comments loads.
    let tree = Tree::new("m.obj", "\u{feff}v 0 0 0 # c\nv 1 0 0\nv 1 1 0 # corner\nv 0 1 0\nf 1 2 3 4 # the quad\n");
    let (code, stderr) = tree.run(&["check", tree.lesson().to_str().unwrap()]);
    assert_eq!(code, Some(0), "{stderr}");

    // A lesson that is not UTF-8 says where.
    let bad = tree.folder().join("bad.toml");
    std::fs::write(&bad, b"[camera]\nposition = [0, 0, 4]\n# caf\xe9\n").unwrap();
    let (code, stderr) = tree.run(&["check", bad.to_str().unwrap()]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("bad.toml:3:6: not UTF-8 at byte 35"), "{stderr}");
    assert!(!stderr.contains("check the path"), "{stderr}");

    // Every validation error of a run, in file order, each with its place, key and hint.
    let text = std::fs::read_to_string(lessons_dir().join("01-first-light.toml")).unwrap();
    let text = text.replacen("intensity = 1.0", "intensity = -1.0", 1).replacen("segments = 64", "segments = 1", 1).replacen(
        "fov_deg = 35.0",
        "fov_deg = 500",
        1,
    );
    std::fs::write(tree.lesson(), &text).unwrap();
    let (code, stderr) = tree.run(&["check", tree.lesson().to_str().unwrap()]);
    assert_eq!(code, Some(2), "{stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error: ") && l.contains("lesson.toml:")).collect();
    let keys: Vec<&str> = errors.iter().map(|l| l.split('`').nth(1).unwrap_or("")).collect();
    assert_eq!(keys, ["camera.fov_deg", "object.0.segments", "light.0.intensity"], "{stderr}");
    let lines: Vec<usize> = errors.iter().map(|l| l.split(':').nth(2).unwrap().parse().unwrap()).collect();
    assert!(lines.windows(2).all(|w| w[0] < w[1]), "{lines:?}");
    assert_eq!(stderr.matches("  hint: ").count(), 3, "{stderr}");
}

#[test]
fn output_errors() {
    let tree = Tree::new("m.obj", QUAD);
    let lesson = tree.lesson();
    let l = lesson.to_str().unwrap();
    // A folder that cannot be written: exit 2, the path as given, the reason, a hint, no temp name.
    if Path::new("/sys").is_dir() && !Path::new("/sys/x.png").exists() {
        let (code, stderr) = tree.run(&["render", l, "-o", "/sys/x.png"]);
        assert_eq!(code, Some(2), "{stderr}");
        assert!(stderr.starts_with("error: cannot write /sys/x.png: "), "{stderr}");
        assert!(stderr.contains("hint: ") && !stderr.contains(".shadelab-") && !stderr.contains("os error"), "{stderr}");
    }
    // A file where a folder is needed.
    let under_file = format!("{l}/x.png");
    let (code, stderr) = tree.run(&["render", l, "-o", &under_file]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("is a file, not a folder") && stderr.contains("hint: a file is in the way"), "{stderr}");
    // A name without an extension does not say its format: refused, with the name to use.
    let (code, stderr) = tree.run(&["render", l, "-o", "NAME"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("-o NAME: the name has no extension") && stderr.contains("NAME.png"), "{stderr}");
    assert!(!tree.dir.path().join("NAME").exists());
    let (code, stderr) = tree.run(&["split", l, "-o", "NAME"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("-o NAME: the name has no extension"), "{stderr}");
    // A folder command refuses an existing file, before any work.
    let (code, stderr) = tree.run(&["figures", l, "-o", l]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("is a file, not a folder"), "{stderr}");
}

/// Round two, finding 5: text from lessons and file names reached the terminal raw (escape
/// sequences cleared the screen and set the window title; a newline in a file name printed
/// a forged `error:` line).
#[test]
fn lesson_text_cannot_drive_the_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(lessons_dir().join("01-first-light.toml")).unwrap();
    // A title with escape sequences and a file name with them and a newline.
    let titled = base.replacen("title = \"The illumination equation\"", "title = \"x\\u001b]0;pwned\\u0007\\u001b[2J\"", 1);
    std::fs::write(dir.path().join("esc\u{1b}[2J.toml"), &titled).unwrap();
    std::fs::write(dir.path().join("a\nerror: forged.toml"), "[camera]\nbogus = 1\n").unwrap();
    for args in [vec!["check"], vec!["lessons"]] {
        let out = shadelab().args(&args).arg(dir.path()).output().unwrap();
        let all = [out.stdout.as_slice(), out.stderr.as_slice()].concat();
        assert!(
            !all.contains(&0x1b) && !all.contains(&0x07),
            "`{args:?}` printed a control character: {:?}",
            String::from_utf8_lossy(&all)
        );
        let text = String::from_utf8_lossy(&all);
        assert!(!text.lines().any(|l| l.starts_with("error: forged")), "`{args:?}` printed a forged line:\n{text}");
        assert!(text.contains("\\u{1b}"), "the escape is shown, not dropped:\n{text}");
    }
}

/// Round two, finding 6: a cut-short JPEG rendered silently as a flat texture, and NaN, ±∞
/// and negative texels were read as 0 without a word.
#[test]
fn bad_image_data_is_refused_or_repaired_aloud() {
    let dir = tempfile::tempdir().unwrap();
    // Noise, so the JPEG's data cannot be guessed from its first third.
    let noise = image::RgbImage::from_fn(256, 256, |x, y| image::Rgb([(x * 7 + y * 13) as u8, (x * y) as u8, (x ^ y) as u8]));
    let mut jpeg = Vec::new();
    noise.write_to(&mut std::io::Cursor::new(&mut jpeg), image::ImageFormat::Jpeg).unwrap();
    std::fs::write(dir.path().join("whole.jpg"), &jpeg).unwrap();
    std::fs::write(dir.path().join("cut.jpg"), &jpeg[..jpeg.len() / 3]).unwrap();
    // Five bad texels of sixteen: NaN, +∞, −∞, negative and 1.7·10³⁸ (a flipped exponent bit,
    // found by the fuzzer: it made infinite pixels in a render's EXR).
    let mut exr = image::Rgb32FImage::from_pixel(4, 4, image::Rgb([0.5, 0.5, 0.5]));
    for (i, bad) in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -1.0, 1.7e38].into_iter().enumerate() {
        exr.put_pixel(i as u32 % 4, i as u32 / 4, image::Rgb([bad, 0.5, 0.5]));
    }
    exr.save(dir.path().join("bad.exr")).unwrap();
    let base = std::fs::read_to_string(lessons_dir().join("01-first-light.toml")).unwrap();
    let render = |texture: &str| {
        let text = base.replacen("diffuse = [0.7, 0.04, 0.03]", &format!("diffuse = {{ texture = \"{texture}\" }}"), 1);
        assert_ne!(text, base, "the lesson's diffuse line moved");
        let lesson = dir.path().join(format!("{texture}.toml"));
        std::fs::write(&lesson, text).unwrap();
        let out = dir.path().join(format!("{texture}.png"));
        let o = shadelab().arg("render").arg(&lesson).arg("-o").arg(&out).arg("-q").output().unwrap();
        (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned(), out.exists())
    };
    assert_eq!(render("whole.jpg"), (Some(0), String::new(), true));
    let (code, stderr, written) = render("cut.jpg");
    assert_eq!((code, written), (Some(2), false), "{stderr}");
    assert!(stderr.contains("cut.jpg: the JPEG is damaged or cut short"), "{stderr}");
    let (code, stderr, written) = render("bad.exr");
    assert_eq!((code, written), (Some(0), true), "{stderr}");
    assert!(stderr.contains("bad.exr: 5 texels were not finite, negative or above 10¹²"), "{stderr}");
}
