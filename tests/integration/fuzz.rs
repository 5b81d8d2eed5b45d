//! A structured fuzzer of lessons and OBJ files, through the real binary.
//!
//! Each case takes a bundled lesson (or one that places an OBJ mesh), applies a few
//! mutations to its TOML (a value replaced by a hostile one: NaN, ±∞, huge, negative,
//! the wrong type, a path outside the folder; a key removed or made up; objects
//! multiplied; the text cut, given a byte-order mark or bytes that are not UTF-8) and to
//! the OBJ (numbers replaced, values added, indices broken, comments, a byte-order mark),
//! may give the first material a texture or the lesson an environment map from an image
//! file that is cut short or has bytes flipped (PNG, JPEG, OpenEXR, Radiance HDR), runs one
//! command (render to PNG or EXR, check, explain, split, figures, compare, snapshot --bless,
//! site, brdf lobe) and checks the property every input must keep:
//!
//! - the exit code is 0 or 2 (2 with an `error:` message), never a panic, a signal or 1;
//! - a failed command leaves no file at all in the output folder (no partial output),
//!   and no command leaves a temporary file;
//! - no message quotes a byte of a file outside the lesson's folder (a canary);
//! - an EXR written holds only finite pixels.
//!
//! `cargo test --release` runs [`DEFAULT_CASES`] cases (well under a minute). For a long
//! run set `SHADELAB_FUZZ_SECS` (seconds; cases keep coming with fresh seeds until then) or
//! `SHADELAB_FUZZ_CASES`; `SHADELAB_FUZZ_LOG=FILE` appends the case count and every
//! finding to FILE; `SHADELAB_FUZZ_BIN` runs another copy of the binary.

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// Cases run by the test suite.
const DEFAULT_CASES: u32 = 160;
/// A command that runs longer than this is a finding (a hang).
const TIMEOUT: Duration = Duration::from_secs(120);
/// Written outside the lesson's folder; no message may quote it.
const CANARY: &str = "canary_5e1f0a_secret";

/// Bundled lessons the cases start from (quick to render at the fuzzer's size).
const BASES: [&str; 9] = [
    "01-first-light.toml",
    "02-lambert.toml",
    "05-gouraud-vs-phong.toml",
    "06-flat-vs-smooth.toml",
    "16-shadows.toml",
    "18-area-lights.toml",
    "24-transforming-normals.toml",
    "26-fog.toml",
    // Its patches coarsened in `lesson_text`, so a case takes well under a second.
    "27-radiosity.toml",
];

/// A small valid OBJ: a quad and a triangle, with normals on some lines.
const OBJ: &str = "# fuzz base\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nvn 0 0 1\nvt 0 0\nvt 1 1\nf 1 2 3 4\nf 1/1 2/2 5/1\n";

/// One change to a lesson.
#[derive(Debug, Clone)]
enum LessonMutation {
    /// Replace the value at leaf `n` (modulo the leaf count) by the `v`-th hostile value.
    Set(usize, usize),
    /// Remove leaf `n`.
    Remove(usize),
    /// Add a key nobody reads to table `n`.
    Unknown(usize),
    /// Make object 0 a mesh with the `n`-th path.
    Mesh(usize),
    /// Repeat the objects `n` times.
    Multiply(usize),
}

/// One change to the text after mutation.
#[derive(Debug, Clone)]
enum TextMutation {
    /// Leave it.
    None,
    /// Cut it at this fraction (per mille) of its length.
    Cut(usize),
    /// Put a byte-order mark in front.
    Bom,
    /// Put a byte that is not UTF-8 at this fraction (per mille).
    NotUtf8(usize),
}

/// One change to the OBJ file.
#[derive(Debug, Clone)]
enum ObjMutation {
    /// Replace word `w` of line `n` by the `v`-th hostile word.
    Word(usize, usize, usize),
    /// Append a hostile word to line `n`.
    Append(usize, usize),
    /// Insert a hostile line before line `n`.
    Line(usize, usize),
    /// Put a byte-order mark in front.
    Bom,
}

/// The command a case runs.
#[derive(Debug, Clone, Copy)]
enum Cmd {
    RenderPng,
    RenderExr,
    Check,
    Explain,
    Split,
    Figures,
    Compare,
    Snapshot,
    Site,
    BrdfLobe,
}

/// An image file the lesson reads, and how it is damaged.
#[derive(Debug, Clone)]
struct ImageCase {
    /// 0 PNG, 1 JPEG, 2 OpenEXR, 3 Radiance HDR.
    format: usize,
    /// True: the environment map; false: the first material's texture.
    environment: bool,
    /// Cut at this fraction (per mille) of the file, when below 1000.
    cut: usize,
    /// Bytes flipped: (position per mille, xor mask).
    flips: Vec<(usize, u8)>,
}

/// One fuzz case.
#[derive(Debug, Clone)]
struct Case {
    base: usize,
    lesson: Vec<LessonMutation>,
    text: TextMutation,
    obj: Vec<ObjMutation>,
    image: Option<ImageCase>,
    cmd: Cmd,
}

fn hostile_value(i: usize) -> toml::Value {
    use toml::Value as V;
    let all = [
        V::Float(f64::NAN),
        V::Float(f64::INFINITY),
        V::Float(f64::NEG_INFINITY),
        V::Float(1e300),
        V::Float(-1e300),
        V::Float(1e39),
        V::Float(-1.0),
        V::Float(0.0),
        V::Float(-0.0),
        V::Float(1e-300),
        V::Float(0.5),
        V::Float(179.999),
        V::Integer(0),
        V::Integer(-1),
        V::Integer(1),
        V::Integer(3),
        V::Integer(64),
        V::Integer(4097),
        V::Integer(i64::MAX),
        V::Integer(i64::MIN),
        V::String(String::new()),
        V::String("mesh".into()),
        V::String("torus".into()),
        V::String("phong".into()),
        V::String("ggx".into()),
        V::String("ray".into()),
        V::String("map".into()),
        V::String("ÿ\u{0}é\u{202e}".into()),
        V::Boolean(true),
        V::Array(vec![]),
        V::Array(vec![V::Float(f64::NAN), V::Float(0.0), V::Float(0.0)]),
        V::Array(vec![V::Float(0.0), V::Float(0.0), V::Float(0.0)]),
        V::Array(vec![V::Float(1e30), V::Float(1e30), V::Float(1e30)]),
        V::Array(vec![V::Integer(1), V::Integer(2)]),
        V::Array(vec![V::Integer(16384), V::Integer(16384)]),
        V::Table(toml::Table::new()),
    ];
    all[i % all.len()].clone()
}

/// Paths a mesh object may name: inside, outside, through symlinks, special files.
const PATHS: [&str; 12] = [
    "m.obj",
    "./sub/../m.obj",
    "../secret.obj",
    "../../../../../../etc/passwd",
    "/etc/passwd",
    "/proc/self/status",
    "link_out.obj",
    "link_in.obj",
    "link_zero.obj",
    "sub",
    "absent.obj",
    "",
];

fn hostile_word(i: usize) -> &'static str {
    const WORDS: [&str; 20] = [
        "nan",
        "inf",
        "-inf",
        "1e39",
        "-1e39",
        "0",
        "1e-45",
        "1e6",
        "2e6",
        "x",
        "#",
        "# c",
        "0/0",
        "1//1",
        "-9",
        "99999999999999999999",
        "1/1/1/1",
        "\u{feff}",
        "1e-30",
        "",
    ];
    WORDS[i % WORDS.len()]
}

fn hostile_line(i: usize) -> &'static str {
    const LINES: [&str; 12] = [
        "v nan 0 0",
        "v 0 0 0 0",
        "v 1 2 3 4 5",
        "vn 0 0 inf",
        "vt 1e40 0",
        "f 1 2",
        "f 1 2 99",
        "f -1 -2 -3",
        "f 0 1 2",
        "usemtl",
        "mtllib /etc/passwd",
        "o object",
    ];
    LINES[i % LINES.len()]
}

fn case() -> impl Strategy<Value = Case> {
    let lesson = prop_oneof![
        (any::<usize>(), any::<usize>()).prop_map(|(n, v)| LessonMutation::Set(n, v)),
        any::<usize>().prop_map(LessonMutation::Remove),
        any::<usize>().prop_map(LessonMutation::Unknown),
        any::<usize>().prop_map(LessonMutation::Mesh),
        (1usize..8).prop_map(LessonMutation::Multiply),
    ];
    let text = prop_oneof![
        6 => Just(TextMutation::None),
        1 => (0usize..1000).prop_map(TextMutation::Cut),
        1 => Just(TextMutation::Bom),
        1 => (0usize..1000).prop_map(TextMutation::NotUtf8),
    ];
    let obj = prop_oneof![
        (any::<usize>(), any::<usize>(), any::<usize>()).prop_map(|(n, w, v)| ObjMutation::Word(n, w, v)),
        (any::<usize>(), any::<usize>()).prop_map(|(n, v)| ObjMutation::Append(n, v)),
        (any::<usize>(), any::<usize>()).prop_map(|(n, v)| ObjMutation::Line(n, v)),
        Just(ObjMutation::Bom),
    ];
    let cmd = prop_oneof![
        Just(Cmd::RenderPng),
        Just(Cmd::RenderExr),
        Just(Cmd::Check),
        Just(Cmd::Explain),
        Just(Cmd::Split),
        Just(Cmd::Figures),
        Just(Cmd::Compare),
        Just(Cmd::Snapshot),
        Just(Cmd::Site),
        Just(Cmd::BrdfLobe),
    ];
    let image = prop::option::weighted(
        0.3,
        (0usize..4, any::<bool>(), prop_oneof![Just(1000usize), 0usize..1000], prop::collection::vec((0usize..1000, 1u8..=255), 0..3))
            .prop_map(|(format, environment, cut, flips)| ImageCase { format, environment, cut, flips }),
    );
    (0..BASES.len() + 2, prop::collection::vec(lesson, 0..4), text, prop::collection::vec(obj, 0..3), image, cmd)
        .prop_map(|(base, lesson, text, obj, image, cmd)| Case { base, lesson, text, obj, image, cmd })
}

/// Every key path to a leaf (scalar or array) of `t`, and every table.
fn leaves(t: &toml::Table, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>, tables: &mut Vec<Vec<String>>) {
    tables.push(prefix.clone());
    for (k, v) in t {
        prefix.push(k.clone());
        match v {
            toml::Value::Table(inner) => leaves(inner, prefix, out, tables),
            toml::Value::Array(a) if a.iter().all(toml::Value::is_table) && !a.is_empty() => {
                for (i, item) in a.iter().enumerate() {
                    prefix.push(i.to_string());
                    leaves(item.as_table().expect("a table"), prefix, out, tables);
                    prefix.pop();
                }
            }
            _ => out.push(prefix.clone()),
        }
        prefix.pop();
    }
}

/// The table at `path` (array indices as numbers) in `root`.
fn table_at<'a>(root: &'a mut toml::Table, path: &[String]) -> Option<&'a mut toml::Table> {
    let mut t = root;
    let mut i = 0;
    while i < path.len() {
        let v = t.get_mut(&path[i])?;
        t = match v {
            toml::Value::Table(inner) => inner,
            toml::Value::Array(a) => {
                i += 1;
                a.get_mut(path.get(i)?.parse::<usize>().ok()?)?.as_table_mut()?
            }
            _ => return None,
        };
        i += 1;
    }
    Some(t)
}

/// The lesson text a case runs.
fn lesson_text(case: &Case) -> Vec<u8> {
    let base =
        match case.base {
            i if i < BASES.len() => std::fs::read_to_string(crate::helpers::lessons_dir().join(BASES[i]))
                .expect("bundled lesson")
                .replacen("patch_size = 0.2", "patch_size = 0.7", 1),
            // A lesson that places the OBJ.
            _ => std::fs::read_to_string(crate::helpers::lessons_dir().join(BASES[0]))
                .expect("bundled lesson")
                .replacen("shape = \"uv_sphere\"", "shape = \"mesh\"\npath = \"m.obj\"", 1)
                .replacen("segments = 64\nrings = 32\n", "", 1),
        };
    let mut table: toml::Table = toml::from_str(&base).expect("bundled lessons parse");
    for m in &case.lesson {
        let (mut all, mut tables) = (Vec::new(), Vec::new());
        leaves(&table, &mut Vec::new(), &mut all, &mut tables);
        match *m {
            LessonMutation::Set(n, v) if !all.is_empty() => {
                let path = &all[n % all.len()];
                if let Some(t) = table_at(&mut table, &path[..path.len() - 1]) {
                    t.insert(path[path.len() - 1].clone(), hostile_value(v));
                }
            }
            LessonMutation::Remove(n) if !all.is_empty() => {
                let path = &all[n % all.len()];
                if let Some(t) = table_at(&mut table, &path[..path.len() - 1]) {
                    t.remove(&path[path.len() - 1]);
                }
            }
            LessonMutation::Unknown(n) => {
                if let Some(t) = table_at(&mut table, &tables[n % tables.len()]) {
                    t.insert("fuzz_unknown".into(), toml::Value::Integer(1));
                }
            }
            LessonMutation::Mesh(n) => {
                if let Some(toml::Value::Array(objects)) = table.get_mut("object")
                    && let Some(toml::Value::Table(o)) = objects.first_mut()
                {
                    for k in ["segments", "rings", "subdivisions", "sides", "major_radius", "minor_radius"] {
                        o.remove(k);
                    }
                    o.insert("shape".into(), "mesh".into());
                    o.insert("path".into(), PATHS[n % PATHS.len()].into());
                }
            }
            LessonMutation::Multiply(n) => {
                if let Some(toml::Value::Array(objects)) = table.get_mut("object") {
                    let copy = objects.clone();
                    for _ in 1..n {
                        objects.extend(copy.iter().cloned());
                    }
                }
            }
            _ => {}
        }
    }
    if let Some(img) = &case.image {
        let file = format!("t.{}", IMAGE_EXTENSIONS[img.format]);
        if img.environment {
            let mut env = toml::Table::new();
            env.insert("map".into(), file.into());
            table.insert("environment".into(), toml::Value::Table(env));
        } else if let Some(toml::Value::Table(materials)) = table.get_mut("material")
            && let Some((_, toml::Value::Table(m))) = materials.iter_mut().next()
        {
            let mut t = toml::Table::new();
            t.insert("texture".into(), file.into());
            m.insert("diffuse".into(), toml::Value::Table(t));
        }
    }
    let mut bytes = toml::to_string(&table).unwrap_or(base).into_bytes();
    match case.text {
        TextMutation::None => {}
        TextMutation::Cut(f) => bytes.truncate(bytes.len() * f / 1000),
        TextMutation::Bom => bytes.splice(0..0, "\u{feff}".bytes()).for_each(drop),
        TextMutation::NotUtf8(f) => {
            let at = bytes.len() * f / 1000;
            bytes.insert(at, 0xff);
        }
    }
    bytes
}

/// The extensions of [`ImageCase::format`].
const IMAGE_EXTENSIONS: [&str; 4] = ["png", "jpg", "exr", "hdr"];

/// The image file a case writes beside the lesson: a 64 × 32 gradient in its format, cut
/// and with bytes flipped.
fn image_bytes(img: &ImageCase) -> Vec<u8> {
    let rgb = image::RgbImage::from_fn(64, 32, |x, y| image::Rgb([(x * 4) as u8, (y * 8) as u8, ((x + y) * 2) as u8]));
    let format = [image::ImageFormat::Png, image::ImageFormat::Jpeg, image::ImageFormat::OpenExr, image::ImageFormat::Hdr][img.format];
    let mut bytes = Vec::new();
    let dynamic =
        if img.format >= 2 { image::DynamicImage::ImageRgb32F(image::DynamicImage::ImageRgb8(rgb).to_rgb32f()) } else { rgb.into() };
    dynamic.write_to(&mut std::io::Cursor::new(&mut bytes), format).expect("encodes");
    for &(at, mask) in &img.flips {
        let i = bytes.len() * at / 1000;
        bytes[i] ^= mask;
    }
    bytes.truncate(bytes.len() * img.cut.min(1000) / 1000);
    bytes
}

/// The name of the first `[material.NAME]` of a lesson text, for `brdf lobe`.
fn first_material(text: &[u8]) -> String {
    let text = String::from_utf8_lossy(text);
    text.lines()
        .find_map(|l| l.trim().strip_prefix("[material."))
        .map(|l| l.trim_end_matches(']').trim_matches('"').to_string())
        .unwrap_or("m".into())
}

/// The OBJ file a case writes beside the lesson.
fn obj_text(case: &Case) -> Vec<u8> {
    let mut lines: Vec<String> = OBJ.lines().map(String::from).collect();
    let mut bom = false;
    for m in &case.obj {
        let n = lines.len();
        match *m {
            ObjMutation::Word(l, w, v) => {
                let line = &mut lines[l % n];
                let mut words: Vec<&str> = line.split(' ').collect();
                let k = w % words.len();
                words[k] = hostile_word(v);
                *line = words.join(" ");
            }
            ObjMutation::Append(l, v) => {
                let line = &mut lines[l % n];
                line.push(' ');
                line.push_str(hostile_word(v));
            }
            ObjMutation::Line(l, v) => lines.insert(l % (n + 1), hostile_line(v).into()),
            ObjMutation::Bom => bom = true,
        }
    }
    let text = lines.join("\n") + "\n";
    if bom { format!("\u{feff}{text}").into_bytes() } else { text.into_bytes() }
}

/// The binary under test.
fn binary() -> PathBuf {
    std::env::var_os("SHADELAB_FUZZ_BIN").map(PathBuf::from).unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_shadelab")))
}

/// Every file under `dir` (recursively).
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    if let Ok(rd) = std::fs::read_dir(dir) {
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() { out.extend(files(&p)) } else { out.push(p) }
        }
    }
    out
}

/// Runs one case and checks the property.
fn run_case(case: &Case) -> Result<(), TestCaseError> {
    let root = tempfile::tempdir().map_err(|e| TestCaseError::fail(e.to_string()))?;
    let folder = root.path().join("lesson");
    let out = root.path().join("out");
    std::fs::create_dir_all(folder.join("sub")).expect("folders");
    std::fs::write(root.path().join("secret.obj"), format!("v {CANARY}\nf {CANARY}\n")).expect("canary");
    std::fs::write(folder.join("m.obj"), obj_text(case)).expect("obj");
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(root.path().join("secret.obj"), folder.join("link_out.obj")).expect("symlink");
        std::os::unix::fs::symlink(folder.join("m.obj"), folder.join("link_in.obj")).expect("symlink");
        std::os::unix::fs::symlink("/dev/zero", folder.join("link_zero.obj")).expect("symlink");
    }
    if let Some(img) = &case.image {
        std::fs::write(folder.join(format!("t.{}", IMAGE_EXTENSIONS[img.format])), image_bytes(img)).expect("image");
    }
    let lesson = folder.join("lesson.toml");
    let text = lesson_text(case);
    std::fs::write(&lesson, &text).expect("lesson");

    let mut cmd = Command::new(binary());
    cmd.env("SHADELAB_NO_CACHE", "1").args(["--threads", "1"]);
    let image = |ext: &str| out.join(format!("x.{ext}"));
    match case.cmd {
        Cmd::RenderPng => cmd.arg("render").arg(&lesson).arg("-o").arg(image("png")).args(["--size", "40x30"]),
        Cmd::RenderExr => cmd.arg("render").arg(&lesson).arg("-o").arg(image("exr")).args(["--size", "40x30"]),
        Cmd::Check => cmd.arg("check").arg(&lesson),
        Cmd::Explain => cmd.arg("explain").arg(&lesson),
        Cmd::Split => cmd.arg("split").arg(&lesson).arg("-o").arg(image("png")).args(["--cell", "32x24", "-q"]),
        Cmd::Figures => cmd.arg("figures").arg(&lesson).arg("-o").arg(&out).args(["--cell", "32x24", "-q"]),
        Cmd::Compare => {
            cmd.arg("compare").arg(&lesson).arg("-o").arg(image("png")).args(["--vary", "camera.fov_deg=20,40", "--cell", "32x24", "-q"])
        }
        Cmd::Snapshot => cmd.arg("snapshot").arg(&lesson).arg("-o").arg(&out).args(["--bless", "--cell", "32x24", "-q"]),
        Cmd::Site => cmd.arg("site").arg(&lesson).arg("-o").arg(&out).args(["--cell", "32x24", "--thumb-width", "48", "-q"]),
        Cmd::BrdfLobe => cmd.args(["brdf", "lobe"]).arg(&lesson).args(["--material", &first_material(&text), "-o"]).arg(image("png")),
    };
    let mut child = cmd.stdout(Stdio::null()).stderr(Stdio::piped()).spawn().expect("run shadelab");
    let mut stderr = child.stderr.take().expect("piped");
    let reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        std::io::Read::read_to_end(&mut stderr, &mut s).ok();
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if start.elapsed() > TIMEOUT {
            child.kill().ok();
            child.wait().ok();
            return Err(TestCaseError::fail(format!("no answer after {TIMEOUT:?}")));
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let stderr = String::from_utf8_lossy(&reader.join().expect("reader")).into_owned();
    let code = status.code();
    prop_assert!(!stderr.contains("panicked"), "a panic (exit {code:?}):\n{stderr}");
    prop_assert!(code == Some(0) || code == Some(2), "exit {code:?} (only 0 or 2 are allowed):\n{stderr}");
    prop_assert!(!stderr.contains(CANARY), "a message quotes a file outside the lesson's folder:\n{stderr}");
    let written = files(&out);
    prop_assert!(!written.iter().any(|p| p.to_string_lossy().contains(".shadelab-")), "a temporary file is left: {written:?}");
    if code == Some(2) {
        prop_assert!(stderr.starts_with("error: "), "exit 2 without a message:\n{stderr}");
        prop_assert!(written.is_empty(), "a failed command wrote {written:?}:\n{stderr}");
    }
    if code == Some(0) && matches!(case.cmd, Cmd::RenderExr) {
        let img = image::open(image("exr")).map_err(|e| TestCaseError::fail(format!("unreadable EXR: {e}")))?.to_rgb32f();
        let bad = img.pixels().filter(|p| p.0.iter().any(|c| !c.is_finite())).count();
        prop_assert!(bad == 0, "{bad} non-finite pixels in the EXR");
    }
    Ok(())
}

/// Appends `line` to the log named by `SHADELAB_FUZZ_LOG`, if any.
fn log(line: &str) {
    if let Some(path) = std::env::var_os("SHADELAB_FUZZ_LOG")
        && let Ok(mut f) = std::fs::OpenOptions::new().create(true).append(true).open(path)
    {
        writeln!(f, "{line}").ok();
    }
}

#[test]
fn fuzz_lessons_and_obj_files() {
    let env = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<u64>().ok());
    let secs = env("SHADELAB_FUZZ_SECS");
    let cases = env("SHADELAB_FUZZ_CASES").unwrap_or(if secs.is_some() { u64::MAX } else { DEFAULT_CASES as u64 });
    let deadline = secs.map(|s| Instant::now() + Duration::from_secs(s));
    let count = AtomicU64::new(0);
    let mut findings = Vec::new();
    let mut seed: u64 = 0x5ade_1ab0;
    // Batches with fresh seeds, so a long run keeps going after a finding (and logs it).
    while count.load(Ordering::Relaxed) < cases && deadline.is_none_or(|d| Instant::now() < d) {
        let batch = (cases - count.load(Ordering::Relaxed)).min(if deadline.is_some() { 200 } else { cases }) as u32;
        let config = Config { cases: batch, failure_persistence: None, max_shrink_iters: 200, ..Config::default() };
        let mut bytes = [0u8; 32];
        bytes[..8].copy_from_slice(&seed.to_le_bytes());
        let mut runner = TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &bytes));
        let result = runner.run(&case(), |c| {
            count.fetch_add(1, Ordering::Relaxed);
            run_case(&c)
        });
        if let Err(e) = result {
            let line = format!("finding (seed {seed:#x}): {e}");
            log(&line);
            findings.push(line);
            if deadline.is_none() {
                break;
            }
        }
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        if deadline.is_some() {
            log(&format!("{} cases, {} findings", count.load(Ordering::Relaxed), findings.len()));
        }
    }
    log(&format!("done: {} cases, {} findings", count.load(Ordering::Relaxed), findings.len()));
    assert!(findings.is_empty(), "{} cases, findings:\n{}", count.load(Ordering::Relaxed), findings.join("\n"));
}
