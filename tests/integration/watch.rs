//! `shadelab watch`: a save re-renders, a broken save is reported and survived, `--serve`
//! serves the site with its reload counter and refuses paths out of the folder.

use crate::helpers::lesson_file;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// How long a save may take to show: the debounce is 200 ms, a tiny lesson renders in
/// milliseconds, but a loaded machine is slow.
const PATIENCE: Duration = Duration::from_secs(20);

/// A small lesson (64×64, one split figure of 32×32 cells) with a diffuse colour.
fn tiny(diffuse: &str) -> String {
    format!(
        r#"[lesson]
title = "Tiny"

[camera]
position = [0.0, 0.0, 4.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 35.0
size = [64, 64]

[[object]]
shape = "uv_sphere"
segments = 16
rings = 8
material = "plastic"

[material.plastic]
model = "blinn_phong"
ambient = {diffuse}
diffuse = {diffuse}
specular = 0.6
shininess = 48

[[light]]
kind = "directional"
direction = [-1.0, -1.0, -1.0]

[scene]
ambient = 0.1

[[figure]]
name = "split"
kind = "split"
layers = ["diffuse", "total"]
cell = [32, 32]
"#
    )
}

/// A running `shadelab watch` whose stdout and stderr are collected as they come; killed on drop.
struct Watching {
    child: Child,
    stdout: Arc<Mutex<String>>,
    stderr: Arc<Mutex<String>>,
}

impl Watching {
    fn start(args: &[&std::ffi::OsStr]) -> Watching {
        let mut child = Command::new(assert_cmd::cargo::cargo_bin("shadelab"))
            .env("SHADELAB_NO_CACHE", "1")
            .arg("watch")
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start shadelab watch");
        let collect = |mut from: Box<dyn Read + Send>| {
            let text = Arc::new(Mutex::new(String::new()));
            let to = Arc::clone(&text);
            std::thread::spawn(move || {
                let mut buf = [0u8; 4096];
                while let Ok(n) = from.read(&mut buf) {
                    if n == 0 {
                        break;
                    }
                    to.lock().unwrap().push_str(&String::from_utf8_lossy(&buf[..n]));
                }
            });
            text
        };
        let stdout = collect(Box::new(child.stdout.take().unwrap()));
        let stderr = collect(Box::new(child.stderr.take().unwrap()));
        Watching { child, stdout, stderr }
    }

    fn stdout(&self) -> String {
        self.stdout.lock().unwrap().clone()
    }

    fn stderr(&self) -> String {
        self.stderr.lock().unwrap().clone()
    }

    /// Waits until `done` holds; panics with both streams after [`PATIENCE`].
    fn wait_for(&mut self, what: &str, mut done: impl FnMut(&Watching) -> bool) {
        let start = Instant::now();
        while start.elapsed() < PATIENCE {
            if done(self) {
                return;
            }
            if let Ok(Some(status)) = self.child.try_wait() {
                panic!("shadelab watch ended ({status}) while waiting for {what}\nstdout:\n{}\nstderr:\n{}", self.stdout(), self.stderr());
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        panic!("no {what} after {PATIENCE:?}\nstdout:\n{}\nstderr:\n{}", self.stdout(), self.stderr());
    }

    fn alive(&mut self) -> bool {
        self.child.try_wait().unwrap().is_none()
    }
}

impl Drop for Watching {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn bytes(p: &Path) -> Option<Vec<u8>> {
    std::fs::read(p).ok()
}

/// Starts watching a fresh copy of [`tiny`] into `out/`; returns after the first build, once
/// the watch has said it is watching.
fn watch_tiny(extra: &[&str]) -> (tempfile::TempDir, PathBuf, PathBuf, Watching) {
    let (dir, lesson) = lesson_file("tiny.toml", &tiny("[0.7, 0.04, 0.03]"));
    let out = dir.path().join("out");
    let mut args: Vec<&std::ffi::OsStr> = vec![lesson.as_os_str(), "-o".as_ref(), out.as_os_str()];
    args.extend(extra.iter().map(|s| std::ffi::OsStr::new(*s)));
    let mut w = Watching::start(&args);
    w.wait_for("`watching` line", |w| w.stdout().contains("watching "));
    (dir, lesson, out, w)
}

#[test]
fn a_save_renders_the_figure_again() {
    let (_dir, lesson, out, mut w) = watch_tiny(&[]);
    let figure = out.join("tiny").join("split.png");
    let before = bytes(&figure).expect("the first build wrote the figure");
    assert!(out.join("tiny.png").is_file(), "the lesson's image is written too");
    assert!(w.stdout().contains("tiny.toml: 1 figure in "), "{}", w.stdout());
    std::fs::write(&lesson, tiny("[0.1, 0.5, 0.9]")).unwrap();
    w.wait_for("new figure bytes", |_| bytes(&figure).is_some_and(|b| b != before));
    w.wait_for("a second summary line", |w| w.stdout().matches("tiny.toml: 1 figure in ").count() == 2);
}

#[test]
fn a_broken_save_is_reported_with_its_line_and_column_and_the_next_good_one_renders() {
    let (_dir, lesson, out, mut w) = watch_tiny(&[]);
    let figure = out.join("tiny").join("split.png");
    let before = bytes(&figure).unwrap();
    let broken = tiny("[0.7, 0.04, 0.03]").replace("shininess = 48", "shininess = \"shiny\"");
    let line = broken.lines().position(|l| l.starts_with("shininess")).unwrap() + 1;
    std::fs::write(&lesson, &broken).unwrap();
    let at = format!("tiny.toml:{line}:13: ");
    w.wait_for("the error on stderr", |w| w.stderr().contains(&at));
    assert!(w.stderr().contains("error: "), "{}", w.stderr());
    std::thread::sleep(Duration::from_millis(300));
    assert!(w.alive(), "watch ended on a broken lesson:\n{}", w.stderr());
    assert_eq!(bytes(&figure).unwrap(), before, "a broken save keeps the last good figure");
    std::fs::write(&lesson, tiny("[0.1, 0.5, 0.9]")).unwrap();
    w.wait_for("the figure of the fixed lesson", |_| bytes(&figure).is_some_and(|b| b != before));
}

/// `GET path` sent as written (no normalisation); the status code and the body.
fn get(port: u16, path: &str) -> (u16, String) {
    let mut s = std::net::TcpStream::connect(("127.0.0.1", port)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    write!(s, "GET {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n").unwrap();
    let mut raw = Vec::new();
    s.read_to_end(&mut raw).expect("read the response");
    let text = String::from_utf8_lossy(&raw);
    let status = text.split(' ').nth(1).and_then(|c| c.parse().ok()).unwrap_or_else(|| panic!("no status in {text:?}"));
    let body = text.split_once("\r\n\r\n").map(|(_, b)| b.to_string()).unwrap_or_default();
    (status, body)
}

#[test]
fn serve_answers_pages_with_the_reload_script_a_rising_counter_and_no_file_outside() {
    let (_dir, lesson, out, mut w) = watch_tiny(&["--serve", "--port", "0"]);
    let stdout = w.stdout();
    let port: u16 = stdout
        .split("http://127.0.0.1:")
        .nth(1)
        .and_then(|r| r.split('/').next())
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no address in {stdout}"));

    let (status, index) = get(port, "/");
    assert_eq!(status, 200, "{index}");
    assert!(index.contains("tiny.html") && index.contains("<script>") && index.contains("/__shadelab_version"), "{index}");
    let on_disk = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(!on_disk.contains("<script"), "the script is added when served, not written: {on_disk}");
    assert_eq!(get(port, "/tiny/split.png").0, 200);
    // With the live lab's build beside the program (target/live, as .ci/run makes it), the
    // served page carries the live view and its scripts are served.
    if Path::new(env!("CARGO_MANIFEST_DIR")).join("target/live/shadelab_wasm_bg.wasm").is_file()
        && std::env::var_os("SHADELAB_LIVE").is_none()
    {
        let (status, page) = get(port, "/tiny.html");
        assert!(status == 200 && page.contains("<script src=\"live/lab.js\"></script>") && page.contains("tiny/live.js"), "{page}");
        let (status, lab) = get(port, "/live/lab.js");
        assert!(status == 200 && lab.contains("shadelabLab"), "GET /live/lab.js: {status}");
    }

    let version = |port| get(port, "/__shadelab_version").1.trim().parse::<u64>().expect("a number");
    let first = version(port);
    assert!(first >= 1, "the first build counts");
    std::fs::write(&lesson, tiny("[0.1, 0.5, 0.9]")).unwrap();
    w.wait_for("a higher version", |_| version(port) > first);

    for outside in ["/../Cargo.toml", "/../tiny.toml", "/%2e%2e/tiny.toml", "/tiny/../../tiny.toml"] {
        let (status, body) = get(port, outside);
        assert!(status == 400 || status == 404, "GET {outside}: {status}\n{body}");
        assert!(!body.contains("shininess"), "GET {outside} leaked the lesson: {body}");
    }
    assert!(w.alive());
}

/// The port `watch --serve --port 0` printed.
fn served_port(w: &Watching) -> u16 {
    let stdout = w.stdout();
    stdout
        .split("http://127.0.0.1:")
        .nth(1)
        .and_then(|r| r.split('/').next())
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no address in {stdout}"))
}

/// A line of the server process's /proc status, as a number (Threads, VmRSS in kB).
fn status(w: &Watching, key: &str) -> u64 {
    let text = std::fs::read_to_string(format!("/proc/{}/status", w.child.id())).unwrap();
    let line = text.lines().find(|l| l.starts_with(key)).unwrap();
    line[key.len()..].trim().trim_end_matches("kB").trim().parse().unwrap()
}

#[test]
fn one_client_cannot_stall_the_server_or_grow_it_without_bound() {
    // Reliability round two: a client that never read its 8 MB answer blocked every other
    // request; a 64 MB request line and 500k headers were read; 1,000 idle connections
    // held 1,003 threads.
    let (_dir, _lesson, out, mut w) = watch_tiny(&["--serve", "--port", "0"]);
    w.wait_for("the address", |w| w.stdout().contains("http://127.0.0.1:"));
    let port = served_port(&w);
    std::fs::write(out.join("big.bin"), vec![7u8; 8 << 20]).unwrap();
    let (threads, rss) = (status(&w, "Threads:"), status(&w, "VmRSS:"));

    // A reader that asks for 8 MB and never reads: the next request is answered meanwhile
    // (`get` gives up after 10 s; the stalled connection lives 30 s).
    let mut stalled = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(stalled, "GET /big.bin HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n").unwrap();
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(get(port, "/__shadelab_version").0, 200, "answered beside a stalled reader");

    // A 4 MB request line and 100k headers: refused after the first 16 KB, not read whole.
    for head in
        [format!("GET /{} HTTP/1.1\r\n\r\n", "a".repeat(4 << 20)), format!("GET / HTTP/1.1\r\n{}\r\n", "X-A: b\r\n".repeat(100_000))]
    {
        let mut s = std::net::TcpStream::connect(("127.0.0.1", port)).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
        // The server closes the connection part-way: the rest of the write may fail.
        let _ = s.write_all(head.as_bytes());
        let mut raw = Vec::new();
        let _ = s.read_to_end(&mut raw);
        let text = String::from_utf8_lossy(&raw);
        assert!(text.is_empty() || text.starts_with("HTTP/1.1 4"), "{}", &text[..text.len().min(200)]);
    }

    // 1,000 idle connections: the server keeps one thread for them all and a bounded set open.
    let idle: Vec<_> = (0..1000).filter_map(|_| std::net::TcpStream::connect(("127.0.0.1", port)).ok()).collect();
    std::thread::sleep(Duration::from_millis(500));
    let (threads_now, rss_now) = (status(&w, "Threads:"), status(&w, "VmRSS:"));
    assert!(threads_now <= threads, "{threads} threads before, {threads_now} with 1,000 idle connections");
    assert!(rss_now < rss + 64 * 1024, "{rss} kB before, {rss_now} kB with the requests above");
    drop(idle);
    // Their slots free within the head timeout; then pages are served again.
    let start = std::time::Instant::now();
    let served = loop {
        let ok =
            std::net::TcpStream::connect(("127.0.0.1", port)).is_ok() && std::panic::catch_unwind(|| get(port, "/").0).ok() == Some(200);
        if ok || start.elapsed() > Duration::from_secs(30) {
            break ok;
        }
        std::thread::sleep(Duration::from_millis(200));
    };
    assert!(served, "the index is served after the idle connections are gone");
    drop(stalled);
    assert!(w.alive());
}

#[test]
fn once_builds_and_exits_and_fails_on_a_broken_lesson() {
    let (dir, lesson) = lesson_file("tiny.toml", &tiny("[0.7, 0.04, 0.03]"));
    let out = dir.path().join("out");
    crate::helpers::shadelab().arg("watch").arg(&lesson).arg("-o").arg(&out).arg("--once").assert().success();
    assert!(out.join("tiny").join("split.png").is_file() && out.join("tiny.png").is_file());
    std::fs::write(&lesson, tiny("[0.7, 0.04, 0.03]").replace("shininess = 48", "shininess = \"shiny\"")).unwrap();
    crate::helpers::shadelab().arg("watch").arg(&lesson).arg("-o").arg(&out).arg("--once").assert().code(2);
}
