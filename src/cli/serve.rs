//! `shadelab watch --serve`: the output folder over HTTP on 127.0.0.1, with live reload.
//!
//! hyper parses the requests, on one tokio thread; this file only decides which file
//! answers and bounds what a client may take (reliability round two: a client that never
//! read its 8 MB answer stalled every other request; a 64 MB request line and 500k headers
//! were read; 1,000 idle connections held 1,003 threads). Now connections are served
//! concurrently on that one thread, so a slow client waits alone; at most
//! [`MAX_CONNECTIONS`] are open (one more is closed at once); a request's head is at
//! most [`MAX_HEAD_BYTES`] with [`MAX_HEADERS`] headers, read within [`HEAD_TIMEOUT`]; a
//! connection lives at most [`CONNECTION_TIMEOUT`].
//!
//! Only files under the output folder are served: a path with a `..` segment is refused
//! before the file system is asked, and a symlink leading out of the folder is refused after
//! it. HTML pages get a small script at serve time (never written to disk, so `shadelab site`
//! output stays script-free) that polls [`VERSION_PATH`] every 500 ms and reloads when the
//! build counter changes.

use super::CliError;
use http_body_util::Full;
use hyper::body::Bytes;
use hyper::{Method, Request, Response};
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::thread::JoinHandle;
use std::time::Duration;

/// The endpoint that answers the build counter as text.
pub const VERSION_PATH: &str = "/__shadelab_version";
/// Connections open at once (a browser opens six; each idle one keeps at most a 16 KB
/// buffer); one more is closed as soon as it is accepted.
pub const MAX_CONNECTIONS: usize = 128;
/// Largest request line and headers together, in bytes (a page request is under 1 KB).
pub const MAX_HEAD_BYTES: usize = 16 * 1024;
/// Most headers in one request (a browser sends about 15).
pub const MAX_HEADERS: usize = 64;
/// Time a client has to send a request's head, the first and each next on a kept connection.
pub const HEAD_TIMEOUT: Duration = Duration::from_secs(5);
/// The longest a connection stays open: a client that stops reading its answer is dropped
/// then, and a browser's polling reconnects.
pub const CONNECTION_TIMEOUT: Duration = Duration::from_secs(30);

/// A running server: its thread, its address and the build counter it reports.
pub struct Server {
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    thread: Option<JoinHandle<()>>,
    version: Arc<AtomicU64>,
    addr: SocketAddr,
}

impl Server {
    /// Serves `root` (created if missing) on 127.0.0.1:`port` (0: any free port).
    ///
    /// # Errors
    /// [`CliError::Input`] when the port cannot be listened on (in use, or privileged).
    pub fn start(root: &Path, port: u16) -> Result<Server, CliError> {
        std::fs::create_dir_all(root).map_err(|e| CliError::Input(format!("{}: cannot create the folder: {e}", root.display())))?;
        let root = root.canonicalize().map_err(|e| CliError::Input(format!("{}: {e}", root.display())))?;
        let listener = std::net::TcpListener::bind(("127.0.0.1", port)).map_err(|e| {
            CliError::Input(format!(
                "--port {port}: cannot listen on 127.0.0.1:{port}: {e}\n  hint: give another port, or --port 0 for any free one"
            ))
        })?;
        let addr = listener.local_addr().map_err(|e| CliError::Internal(format!("the server has no address: {e}")))?;
        listener.set_nonblocking(true).map_err(|e| CliError::Internal(format!("cannot serve: {e}")))?;
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_io()
            .enable_time()
            .build()
            .map_err(|e| CliError::Internal(format!("cannot start the server: {e}")))?;
        let version = Arc::new(AtomicU64::new(0));
        let (stop, stopped) = tokio::sync::oneshot::channel();
        let v = Arc::clone(&version);
        let thread = std::thread::spawn(move || runtime.block_on(serve(listener, Arc::new(root), v, stopped)));
        Ok(Server { stop: Some(stop), thread: Some(thread), version, addr })
    }

    /// The address pages are served at, e.g. `http://127.0.0.1:8000/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Counts one more rebuild: open pages reload at their next poll.
    pub fn bump(&self) {
        self.version.fetch_add(1, Ordering::SeqCst);
    }

    /// Stops accepting requests, drops open connections and waits for the thread.
    pub fn stop(mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Accepts connections until `stopped`, each served as its own task within the limits.
async fn serve(
    listener: std::net::TcpListener,
    root: Arc<PathBuf>,
    version: Arc<AtomicU64>,
    mut stopped: tokio::sync::oneshot::Receiver<()>,
) {
    let Ok(listener) = tokio::net::TcpListener::from_std(listener) else { return };
    let slots = Arc::new(tokio::sync::Semaphore::new(MAX_CONNECTIONS));
    let mut http = hyper::server::conn::http1::Builder::new();
    http.timer(hyper_util::rt::TokioTimer::new())
        .header_read_timeout(HEAD_TIMEOUT)
        .max_buf_size(MAX_HEAD_BYTES)
        .max_header_size(MAX_HEAD_BYTES)
        .max_headers(MAX_HEADERS);
    let http = Arc::new(http);
    let mut tasks = tokio::task::JoinSet::new();
    loop {
        let stream = tokio::select! {
            _ = &mut stopped => break,
            a = listener.accept() => match a { Ok((s, _)) => s, Err(_) => continue },
        };
        // Beyond the limit a connection is closed at once rather than queued behind idle ones
        // (which the head timeout closes within seconds; a browser's poll comes back).
        let Ok(slot) = Arc::clone(&slots).try_acquire_owned() else {
            drop(stream);
            continue;
        };
        let (root, version, http) = (Arc::clone(&root), Arc::clone(&version), Arc::clone(&http));
        tasks.spawn(async move {
            let service = hyper::service::service_fn(move |req: Request<hyper::body::Incoming>| {
                let answer = respond(&req, &root, version.load(Ordering::SeqCst));
                async move { Ok::<_, std::convert::Infallible>(answer) }
            });
            let conn = http.serve_connection(hyper_util::rt::TokioIo::new(stream), service);
            // A client gone, slow or malformed is not an error of ours: the connection ends.
            let _ = tokio::time::timeout(CONNECTION_TIMEOUT, conn).await;
            drop(slot);
        });
        // Finished connections are reaped as we go, so the set stays at most MAX_CONNECTIONS.
        while tasks.try_join_next().is_some() {}
    }
    tasks.abort_all();
}

/// The response to one request.
fn respond(req: &Request<hyper::body::Incoming>, root: &Path, version: u64) -> Response<Full<Bytes>> {
    let (status, body, kind) = answer(req.method(), req.uri().path(), root, version);
    Response::builder()
        .status(status)
        .header("Content-Type", kind)
        // Images change under the same name at every rebuild.
        .header("Cache-Control", "no-store")
        .body(Full::new(Bytes::from(body)))
        .unwrap_or_else(|_| Response::new(Full::new(Bytes::new())))
}

/// The status, body and content type for `method url`.
fn answer(method: &Method, url: &str, root: &Path, version: u64) -> (u16, Vec<u8>, &'static str) {
    let text = |status: u16, m: &str| (status, m.as_bytes().to_vec(), "text/plain; charset=utf-8");
    if !matches!(*method, Method::GET | Method::HEAD) {
        return text(405, "only GET and HEAD\n");
    }
    let path = url.split(['?', '#']).next().unwrap_or("");
    if path == VERSION_PATH {
        return text(200, &version.to_string());
    }
    let file = match file_for(root, path) {
        Ok(f) => f,
        Err(400) => return text(400, "bad path\n"),
        Err(_) => return text(404, "not found\n"),
    };
    let Ok(bytes) = std::fs::read(&file) else { return text(404, "not found\n") };
    let kind = content_type(&file);
    if kind.starts_with("text/html") {
        return (200, with_reload_script(&String::from_utf8_lossy(&bytes), version).into_bytes(), kind);
    }
    (200, bytes, kind)
}

/// The file under `root` (canonical) that `path` (a URL path) names: `index.html` for a
/// folder. Err(400) for a malformed path or one with a `..` segment, Err(404) otherwise.
fn file_for(root: &Path, path: &str) -> Result<PathBuf, u16> {
    let decoded = percent_decode(path).ok_or(400u16)?;
    let mut rel = PathBuf::new();
    for segment in decoded.split('/') {
        match segment {
            "" | "." => {}
            ".." => return Err(400),
            s if s.contains(['\\', '\0']) => return Err(400),
            s => rel.push(s),
        }
    }
    let mut full = root.join(rel);
    if full.is_dir() {
        full.push("index.html");
    }
    // After symlinks are followed the file must still lie under the root.
    let canonical = full.canonicalize().map_err(|_| 404u16)?;
    if canonical.starts_with(root) && canonical.is_file() { Ok(canonical) } else { Err(404) }
}

/// `%XX` escapes decoded; `None` for a bad escape or bytes that are not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// The Content-Type of the files a site holds.
fn content_type(file: &Path) -> &'static str {
    match file.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("html") => "text/html; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        // The live lab's scripts (a page refuses a script served as anything else under nosniff).
        Some("js") => "text/javascript; charset=utf-8",
        Some("otf") => "font/otf",
        Some("png") => "image/png",
        Some("svg") => "image/svg+xml",
        Some("exr") => "image/x-exr",
        Some("toml" | "txt") => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

/// `html` with the reload script before `</body>`: it knows the version it was served at, so
/// a rebuild between the page load and the first poll still reloads.
pub fn with_reload_script(html: &str, version: u64) -> String {
    let script = format!(
        "<script>/* shadelab watch: reload after a rebuild */(function(){{var v=\"{version}\";setInterval(function(){{fetch(\"{VERSION_PATH}\",{{cache:\"no-store\"}}).then(function(r){{return r.text()}}).then(function(t){{if(t!==v)location.reload()}}).catch(function(){{}})}},500)}})();</script>\n"
    );
    match html.rfind("</body>") {
        Some(at) => format!("{}{script}{}", &html[..at], &html[at..]),
        None => format!("{html}{script}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_with_dot_dot_are_refused_and_files_outside_are_not_found() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path().join("site");
        std::fs::create_dir_all(&root).unwrap();
        std::fs::write(root.join("index.html"), "<body></body>").unwrap();
        std::fs::write(dir.path().join("secret.txt"), "no").unwrap();
        let root = root.canonicalize().unwrap();
        assert_eq!(file_for(&root, "/../secret.txt"), Err(400));
        assert_eq!(file_for(&root, "/%2e%2e/secret.txt"), Err(400));
        assert_eq!(file_for(&root, "/a/../../secret.txt"), Err(400));
        assert_eq!(file_for(&root, "/nope.png"), Err(404));
        assert_eq!(file_for(&root, "/").unwrap(), root.join("index.html"));
        assert_eq!(file_for(&root, "/index.html").unwrap(), root.join("index.html"));
    }

    #[test]
    fn the_script_goes_before_the_end_of_the_body() {
        let page = with_reload_script("<html><body><p>x</p></body></html>", 3);
        let at = page.find("<script>").unwrap();
        assert!(at < page.find("</body>").unwrap() && page.contains(VERSION_PATH) && page.contains("var v=\"3\""), "{page}");
    }
}
