//! The live lab in headless Chromium, driven over the DevTools protocol: a lesson page's
//! first picture is the native `shadelab render`'s, byte for byte; moving a slider re-renders
//! it to the native render of the `--set` line the page shows; a bad value gives the CLI's
//! message; nothing is logged to the console. Needs the WebAssembly build (tools/build-live.sh,
//! run by .ci/run): `SHADELAB_LIVE` or target/live. Under `SHADELAB_REQUIRE_LIVE=1` (CI) a
//! missing build fails the test rather than skipping it.

use crate::helpers::{lessons_dir, shadelab};
use base64::Engine as _;
use serde_json::{Value, json};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The live lab's build, or `None` (with a note) when it was not built and not required.
fn live_dir() -> Option<PathBuf> {
    let dir =
        std::env::var_os("SHADELAB_LIVE").map(PathBuf::from).unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("target/live"));
    if dir.join("shadelab_wasm_bg.wasm").is_file() {
        return Some(dir);
    }
    let required = std::env::var("SHADELAB_REQUIRE_LIVE").is_ok_and(|v| v == "1");
    assert!(!required, "no live lab build in {}: run tools/build-live.sh", dir.display());
    eprintln!("note: no live lab build in {}; the live lab's browser test did not run", dir.display());
    None
}

/// Headless Chromium on `url` with a DevTools port; killed when dropped.
struct Browser {
    child: Child,
    _profile: tempfile::TempDir,
    socket: tungstenite::WebSocket<TcpStream>,
    next_id: u64,
    /// Console errors, exceptions and log errors seen so far.
    errors: Vec<String>,
}

impl Drop for Browser {
    fn drop(&mut self) {
        self.child.kill().ok();
        self.child.wait().ok();
    }
}

impl Browser {
    fn open(url: &str) -> Browser {
        let bin = std::env::var("SHADELAB_CHROMIUM").unwrap_or_else(|_| "chromium".into());
        let profile = tempfile::tempdir().unwrap();
        let mut child = Command::new(&bin)
            .args([
                "--headless=new",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--remote-debugging-port=0",
                "--window-size=1280,1400",
            ])
            .arg(format!("--user-data-dir={}", profile.path().display()))
            .arg(url)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start `{bin}` ({e}): apt-get install -y chromium, as .ci/run does"));
        // "DevTools listening on ws://127.0.0.1:PORT/devtools/browser/ID".
        let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
        let port = loop {
            let line = lines.next().expect("chromium ended before it listened").unwrap();
            if let Some(rest) = line.strip_prefix("DevTools listening on ws://127.0.0.1:") {
                break rest.split('/').next().unwrap().parse::<u16>().unwrap();
            }
        };
        // Keep draining stderr so the browser never blocks on a full pipe.
        std::thread::spawn(move || for _ in lines {});
        let start = Instant::now();
        let page = loop {
            let list: Value = serde_json::from_str(&http_get(port, "/json/list")).unwrap();
            if let Some(p) =
                list.as_array().unwrap().iter().find(|t| t["type"] == "page" && t["url"].as_str().is_some_and(|u| u.starts_with("file:")))
            {
                break p["webSocketDebuggerUrl"].as_str().unwrap().to_string();
            }
            assert!(start.elapsed() < Duration::from_secs(30), "no page target: {list}");
            std::thread::sleep(Duration::from_millis(100));
        };
        let stream = TcpStream::connect(("127.0.0.1", port)).unwrap();
        stream.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
        let (socket, _) = tungstenite::client(page.as_str(), stream).expect("DevTools WebSocket");
        let mut b = Browser { child, _profile: profile, socket, next_id: 0, errors: Vec::new() };
        b.call("Runtime.enable", json!({}));
        b.call("Log.enable", json!({}));
        b
    }

    /// Sends a DevTools command and returns its result, noting error events on the way.
    fn call(&mut self, method: &str, params: Value) -> Value {
        self.try_call(method, params).unwrap_or_else(|e| panic!("{method}: {e}"))
    }

    /// [`Browser::call`], with the protocol's error as an `Err`.
    fn try_call(&mut self, method: &str, params: Value) -> Result<Value, Value> {
        self.next_id += 1;
        let id = self.next_id;
        self.socket.send(tungstenite::Message::text(json!({"id": id, "method": method, "params": params}).to_string())).unwrap();
        loop {
            let msg = self.socket.read().expect("DevTools message");
            let Ok(text) = msg.to_text() else { continue };
            let v: Value = serde_json::from_str(text).unwrap();
            if v["id"] == id {
                return match v.get("error") {
                    Some(e) => Err(e.clone()),
                    None => Ok(v["result"].clone()),
                };
            }
            match v["method"].as_str() {
                Some("Runtime.exceptionThrown") => self.errors.push(v["params"]["exceptionDetails"].to_string()),
                Some("Runtime.consoleAPICalled") if matches!(v["params"]["type"].as_str(), Some("error" | "warning" | "assert")) => {
                    self.errors.push(v["params"]["args"].to_string())
                }
                Some("Log.entryAdded") if v["params"]["entry"]["level"] == "error" => self.errors.push(v["params"]["entry"].to_string()),
                _ => {}
            }
        }
    }

    /// Evaluates `js` (awaiting a promise) and returns its value.
    fn eval(&mut self, js: &str) -> Value {
        let params = json!({"expression": js, "awaitPromise": true, "returnByValue": true});
        let mut r = self.try_call("Runtime.evaluate", params.clone());
        // The page may still be committing its navigation from about:blank when the test
        // attaches: that destroys the context an evaluation started in, so it runs again.
        for _ in 0..50 {
            match &r {
                Err(e) if e["message"].as_str().is_some_and(|m| m.contains("context")) => {
                    std::thread::sleep(Duration::from_millis(100));
                    r = self.try_call("Runtime.evaluate", params.clone());
                }
                _ => break,
            }
        }
        let r = r.unwrap_or_else(|e| panic!("Runtime.evaluate: {e}"));
        assert!(r.get("exceptionDetails").is_none(), "{js}: {r}");
        r["result"]["value"].clone()
    }

    /// Fails on any console error, exception or logged error so far.
    fn assert_quiet(&mut self) {
        self.call("Runtime.evaluate", json!({"expression": "0"}));
        assert!(self.errors.is_empty(), "console errors: {:#?}", self.errors);
    }

    /// Waits until the lab is idle after at least `renders` renders.
    fn settle(&mut self, renders: u64) {
        let js = format!(
            "(async () => {{ const t0 = Date.now(); while (!(window.shadelabLab && window.shadelabLab.ready)) {{ if (Date.now() - t0 > 60000) return -1; await new Promise(r => setTimeout(r, 20)); }} await window.shadelabLab.ready; \
             while (window.shadelabLab.busy || window.shadelabLab.renders < {renders}) {{ if (Date.now() - t0 > 60000) return -1; await new Promise(r => setTimeout(r, 20)); }} return window.shadelabLab.renders; }})()"
        );
        let got = self.eval(&js);
        assert!(got.as_i64().unwrap_or(-1) >= renders as i64, "the lab did not render: {got}");
    }

    /// The total canvas's RGBA pixels.
    fn canvas(&mut self) -> (u32, u32, Vec<u8>) {
        let v = self.eval(
            "(() => { const c = document.getElementById('live-total'); const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data; \
             let s = ''; for (let i = 0; i < d.length; i += 0x8000) s += String.fromCharCode.apply(null, d.subarray(i, i + 0x8000)); \
             return [c.width, c.height, btoa(s)]; })()",
        );
        let px = base64::engine::general_purpose::STANDARD.decode(v[2].as_str().unwrap()).unwrap();
        (v[0].as_u64().unwrap() as u32, v[1].as_u64().unwrap() as u32, px)
    }
}

/// A plain HTTP/1.1 GET on the DevTools port (it does not answer HTTP/1.0).
fn http_get(port: u16, path: &str) -> String {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    write!(s, "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n").unwrap();
    let mut r = BufReader::new(s);
    let mut len = 0;
    loop {
        let mut line = String::new();
        r.read_line(&mut line).unwrap();
        if line.trim().is_empty() {
            break;
        }
        if let Some((k, v)) = line.split_once(':')
            && k.eq_ignore_ascii_case("content-length")
        {
            len = v.trim().parse().unwrap();
        }
    }
    let mut body = vec![0; len];
    r.read_exact(&mut body).unwrap();
    String::from_utf8(body).unwrap()
}

/// The native render of lesson `stem` with `sets`, as RGB bytes.
fn native(stem: &str, sets: &[&str]) -> (u32, u32, Vec<u8>) {
    let out = tempfile::tempdir().unwrap();
    let png = out.path().join("n.png");
    let mut cmd = shadelab();
    cmd.current_dir(lessons_dir().parent().unwrap()).args(["render", &format!("lessons/{stem}.toml"), "-o"]).arg(&png);
    for s in sets {
        cmd.args(["--set", s]);
    }
    cmd.assert().success();
    let img = crate::helpers::read_png(&png);
    (img.width(), img.height(), img.into_raw())
}

/// What `shadelab render` of lesson `stem` with `set` prints when it refuses it (exit 2).
fn native_error(stem: &str, set: &str) -> String {
    let out = tempfile::tempdir().unwrap();
    let err = shadelab()
        .current_dir(lessons_dir().parent().unwrap())
        .args(["render", &format!("lessons/{stem}.toml"), "--set", set, "-o"])
        .arg(out.path().join("x.png"))
        .assert()
        .code(2)
        .get_output()
        .stderr
        .clone();
    String::from_utf8(err).unwrap()
}

/// The canvas against the native render: the number of channel values that differ and the
/// largest difference.
fn compare(canvas: &(u32, u32, Vec<u8>), native: &(u32, u32, Vec<u8>)) -> (usize, u8) {
    assert_eq!((canvas.0, canvas.1), (native.0, native.1), "sizes");
    let rgb = canvas.2.chunks(4).flat_map(|p| [p[0], p[1], p[2]]);
    let diffs: Vec<u8> = rgb.zip(native.2.iter()).map(|(a, &b)| a.abs_diff(b)).filter(|&d| d > 0).collect();
    (diffs.len(), diffs.iter().copied().max().unwrap_or(0))
}

/// The site of lesson `stem` with the live lab, open in the browser once its first picture is
/// drawn (the site's folder lives as long as the browser needs it).
fn open_page(stem: &str, live: &Path) -> (tempfile::TempDir, Browser) {
    let site = site_for(&[stem], live);
    let url = format!("file://{}", site.path().join(format!("{stem}.html")).display());
    let mut b = Browser::open(&url);
    b.settle(1);
    (site, b)
}

fn site_for(lessons: &[&str], live: &Path) -> tempfile::TempDir {
    let out = tempfile::tempdir().unwrap();
    let mut cmd = shadelab();
    cmd.current_dir(lessons_dir().parent().unwrap()).arg("site");
    for l in lessons {
        cmd.arg(format!("lessons/{l}.toml"));
    }
    cmd.args(["--cell", "64x64", "--live"]).arg(live).arg("-o").arg(out.path()).assert().success();
    out
}

#[test]
fn a_slider_re_renders_the_lesson_as_the_cli_would() {
    let Some(live) = live_dir() else { return };
    let (_site, mut b) = open_page("01-first-light", &live);

    // The first picture is `shadelab render`'s, byte for byte.
    let first = b.canvas();
    assert_eq!(compare(&first, &native("01-first-light", &[])), (0, 0), "the page's first picture against shadelab render");

    // Drag the shininess slider: previews while it moves, the full frame when let go.
    let before = b.eval("window.shadelabLab.renders").as_u64().unwrap();
    b.eval(
        "(() => { const s = document.querySelector('input[data-key=\"material.plastic.shininess\"]'); s.value = 150; \
         s.dispatchEvent(new Event('input')); s.value = 200; s.dispatchEvent(new Event('input')); s.dispatchEvent(new Event('change')); return 0; })()",
    );
    b.settle(before + 1);
    let frame = b.eval("window.shadelabLab.frame");
    assert_eq!(frame["preview"], false, "{frame}");
    let cli = b.eval("document.getElementById('live-cli').textContent");
    let cli = cli.as_str().unwrap();
    let set = cli.split(" --set ").nth(1).unwrap_or_else(|| panic!("no --set in `{cli}`"));
    assert!(set.starts_with("material.plastic.shininess=") && cli.starts_with("shadelab render lessons/01-first-light.toml"), "{cli}");
    let moved = b.canvas();
    assert_ne!(moved.2, first.2, "the canvas did not change");
    assert_eq!(compare(&moved, &native("01-first-light", &[set])), (0, 0), "after the slider, against `{cli}`");

    // A value the validator refuses: the CLI's message, word for word.
    let wasm_err = b.eval(
        "(() => { try { wasm_bindgen.render(SHADELAB_LESSON.path, SHADELAB_LESSON.text, ['material.plastic.shininess=-1']); return 'no error'; } catch (e) { return String(e); } })()",
    );
    let cli_err = native_error("01-first-light", "material.plastic.shininess=-1");
    assert_eq!(wasm_err.as_str().unwrap().trim(), cli_err.trim(), "the page's error against the CLI's");
    b.assert_quiet();
}

#[test]
fn a_lesson_that_reads_files_renders_from_memory_as_from_disk() {
    let Some(live) = live_dir() else { return };
    // Lesson 33 reads six textures through the same resolver and decoders as on disk.
    let (_site, mut b) = open_page("33-textures", &live);
    let (n, max) = compare(&b.canvas(), &native("33-textures", &[]));
    assert!(n == 0, "{n} channel values differ (largest {max}) from shadelab render");
    b.assert_quiet();
}

/// A benchmark, not a test (it asserts no time): the preview frame time of lesson 01 while a
/// slider is dragged, in headless Chromium. Run it with
/// `cargo test --release --test integration live_preview_benchmark -- --ignored --nocapture`.
#[test]
#[ignore = "a benchmark: run with --ignored --nocapture"]
fn live_preview_benchmark() {
    let Some(live) = live_dir() else { return };
    let (_site, mut b) = open_page("01-first-light", &live);
    // Each step moves the slider once and waits for its preview: the time the renderer and
    // the drawing take, as the page shows it.
    let v = b.eval(
        "(async () => { const s = document.querySelector('input[data-key=\"material.plastic.shininess\"]'); const ms = []; \
         for (let i = 0; i < 120; i++) { const n = window.shadelabLab.renders; s.value = 200 + (i * 37) % 600; s.dispatchEvent(new Event('input')); \
         while (window.shadelabLab.renders === n) await new Promise(r => requestAnimationFrame(r)); \
         if (!window.shadelabLab.frame.preview) return 'not a preview'; ms.push(window.shadelabLab.lastMs); } \
         return [window.shadelabLab.frame.width, window.shadelabLab.frame.height, ms]; })()",
    );
    let mut ms: Vec<f64> = v[2].as_array().unwrap_or_else(|| panic!("{v}")).iter().map(|x| x.as_f64().unwrap()).collect();
    // The first 20 frames warm the engine's tiers up.
    let mut warm = ms.split_off(20);
    warm.sort_by(f64::total_cmp);
    let q = |p: f64| warm[((warm.len() - 1) as f64 * p).round() as usize];
    println!(
        "live preview of lesson 01 ({}×{}, aa 1): median {:.2} ms, 10% {:.2} ms, 90% {:.2} ms over {} frames (first {:.1} ms)",
        v[0],
        v[1],
        q(0.5),
        q(0.1),
        q(0.9),
        warm.len(),
        ms[0]
    );
}

/// Every bundled lesson, rendered small by the WebAssembly build in the browser (its files
/// handed over in memory), against `shadelab render` with the same `--set`.
#[test]
fn every_lesson_renders_in_the_browser_as_on_the_command_line() {
    let Some(live) = live_dir() else { return };
    let (_site, mut b) = open_page("01-first-light", &live);
    let mut files: Vec<PathBuf> = std::fs::read_dir(lessons_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    let size = "camera.size=[40, 32]";
    let mut report = Vec::new();
    for path in &files {
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        let lesson = shadelab::lesson::load(path, &[]).unwrap();
        for f in lesson.asset_files() {
            let rel = f.strip_prefix(lessons_dir().canonicalize().unwrap()).unwrap();
            let b64 = base64::engine::general_purpose::STANDARD.encode(std::fs::read(&f).unwrap());
            b.eval(&format!(
                "wasm_bindgen.provide_file({:?}, Uint8Array.from(atob({b64:?}), c => c.charCodeAt(0))) || 0",
                format!("lessons/{}", rel.display())
            ));
        }
        let text = serde_json::to_string(&lesson.source).unwrap();
        let mut render = |sets: &[&str]| {
            let sets = serde_json::to_string(sets).unwrap();
            b.eval(&format!(
                "(() => {{ try {{ const f = wasm_bindgen.render('lessons/{stem}.toml', {text}, {sets}); const d = f.layer(0); let s = ''; \
                 for (let i = 0; i < d.length; i += 0x8000) s += String.fromCharCode.apply(null, d.subarray(i, i + 0x8000)); \
                 const out = [f.width, f.height, btoa(s)]; f.free(); return out; }} catch (e) {{ return String(e); }} }})()"
            ))
        };
        let mut sets = vec![size];
        let mut v = render(&sets);
        if let Some(message) = v.as_str() {
            // Too small for the lesson (lesson 37's pixel figures): the CLI says the same, and
            // the lesson is rendered at its own size instead.
            assert_eq!(message.trim(), native_error(&stem, size).trim(), "{stem}: the error");
            sets.clear();
            v = render(&sets);
        }
        let px = base64::engine::general_purpose::STANDARD.decode(v[2].as_str().unwrap_or_else(|| panic!("{stem}: {v}"))).unwrap();
        let (n, max) = compare(&(v[0].as_u64().unwrap() as u32, v[1].as_u64().unwrap() as u32, px), &native(&stem, &sets));
        if n > 0 {
            report.push(format!("{stem}: {n} channel values differ, the largest by {max}"));
        }
    }
    assert!(report.is_empty(), "the browser's renders differ from the CLI's:\n{}", report.join("\n"));
    b.assert_quiet();
}
