//! `shadelab watch --serve`: the output folder over HTTP on 127.0.0.1, with live reload.
//!
//! tiny_http parses the requests; this file only decides which file answers. Only files
//! under the output folder are served: a path with a `..` segment is refused before the file
//! system is asked, and a symlink leading out of the folder is refused after it. HTML pages
//! get a small script at serve time (never written to disk, so `shadelab site` output stays
//! script-free) that polls [`VERSION_PATH`] every 500 ms and reloads when the build counter
//! changes.

use super::CliError;
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::thread::JoinHandle;

/// The endpoint that answers the build counter as text.
pub const VERSION_PATH: &str = "/__shadelab_version";

/// A running server: its thread, its address and the build counter it reports.
pub struct Server {
    http: Arc<tiny_http::Server>,
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
        let http = tiny_http::Server::http(("127.0.0.1", port)).map_err(|e| {
            CliError::Input(format!(
                "--port {port}: cannot listen on 127.0.0.1:{port}: {e}\n  hint: give another port, or --port 0 for any free one"
            ))
        })?;
        let addr = http.server_addr().to_ip().ok_or_else(|| CliError::Internal("the server has no IP address".into()))?;
        let http = Arc::new(http);
        let version = Arc::new(AtomicU64::new(0));
        let (h, v) = (Arc::clone(&http), Arc::clone(&version));
        let thread = std::thread::spawn(move || {
            // Ends when `stop` unblocks the server.
            for request in h.incoming_requests() {
                respond(request, &root, v.load(Ordering::SeqCst));
            }
        });
        Ok(Server { http, thread: Some(thread), version, addr })
    }

    /// The address pages are served at, e.g. `http://127.0.0.1:8000/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Counts one more rebuild: open pages reload at their next poll.
    pub fn bump(&self) {
        self.version.fetch_add(1, Ordering::SeqCst);
    }

    /// Stops accepting requests and waits for the thread.
    pub fn stop(mut self) {
        self.http.unblock();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Answers one request; a client that went away is not an error of ours.
fn respond(request: tiny_http::Request, root: &Path, version: u64) {
    let (status, body, kind) = answer(request.method(), request.url(), root, version);
    let header = |k: &str, v: &str| tiny_http::Header::from_bytes(k.as_bytes(), v.as_bytes()).expect("a valid header");
    let response = tiny_http::Response::from_data(body)
        .with_status_code(status)
        .with_header(header("Content-Type", kind))
        // Images change under the same name at every rebuild.
        .with_header(header("Cache-Control", "no-store"));
    let _ = request.respond(response);
}

/// The status, body and content type for `method url`.
fn answer(method: &tiny_http::Method, url: &str, root: &Path, version: u64) -> (u16, Vec<u8>, &'static str) {
    let text = |status: u16, m: &str| (status, m.as_bytes().to_vec(), "text/plain; charset=utf-8");
    if !matches!(method, tiny_http::Method::Get | tiny_http::Method::Head) {
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
