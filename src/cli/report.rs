//! `snapshot --report DIR`: a review page for a CI artifact. `DIR/index.html` shows the
//! failures first, each as blessed | actual | difference side by side with its numbers,
//! and folds the passes; it needs no script and opens from `file://`.

use super::CliError;
use crate::site::html::{escape, url};
use std::path::{Path, PathBuf};

/// How one figure's check ended, for the page.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// It differed (or its snapshot is missing).
    Failed,
    /// It could not be checked (the lesson does not validate).
    Error,
    /// It matched.
    Passed,
    /// It was blessed in this run.
    Blessed,
}

/// One figure on the page.
#[derive(Debug, Clone)]
pub struct Entry {
    /// `LESSON/FIGURE`.
    pub id: String,
    /// How it ended.
    pub status: Status,
    /// The numbers, or why.
    pub message: String,
    /// The blessed image, the actual one and the difference, where they exist.
    pub images: [Option<PathBuf>; 3],
}

/// Writes `dir/index.html` and copies the failures' images under `dir/images/`.
/// `per_pixel` is the tolerance in codes (the difference image's scale starts above it).
pub fn write(dir: &Path, entries: &[Entry], per_pixel: u8, max_share: f64) -> Result<(), CliError> {
    crate::output::check_folder(dir, dir)?;
    std::fs::create_dir_all(dir).map_err(|e| CliError::Input(format!("{}: cannot create the folder: {e}", dir.display())))?;
    let count = |s: Status| entries.iter().filter(|e| e.status == s).count();
    let mut body = String::new();
    let failing: Vec<&Entry> =
        entries.iter().filter(|e| e.status == Status::Failed).chain(entries.iter().filter(|e| e.status == Status::Error)).collect();
    for e in &failing {
        body.push_str(&format!(
            "<section class=\"{}\"><h2 id=\"{}\">{}</h2>\n<p class=\"numbers\">{}</p>\n<div class=\"row\">",
            if e.status == Status::Error { "error" } else { "failed" },
            escape(&e.id),
            escape(&e.id),
            escape(&e.message)
        ));
        for (k, (what, img)) in ["blessed", "actual", "difference"].iter().zip(&e.images).enumerate() {
            let Some(src) = img else { continue };
            let name = format!("images/{}-{what}.png", e.id);
            let to = dir.join(&name);
            if let Some(parent) = to.parent() {
                std::fs::create_dir_all(parent).map_err(|e| CliError::Input(format!("{}: {e}", parent.display())))?;
            }
            let bytes = std::fs::read(src).map_err(|e| CliError::Internal(format!("{}: {e}", src.display())))?;
            crate::output::write_atomic(&to, |w| w.write_all(&bytes).map_err(|e| e.to_string()))?;
            let scale = if k == 2 { "<span class=\"scale\"></span>" } else { "" };
            body.push_str(&format!(
                "<figure><img src=\"{}\" alt=\"{} {what}\"><figcaption>{what}{scale}</figcaption></figure>",
                escape(&url(&name)),
                escape(&e.id)
            ));
        }
        body.push_str("</div></section>\n");
    }
    let passes: Vec<&Entry> = entries.iter().filter(|e| matches!(e.status, Status::Passed | Status::Blessed)).collect();
    if !passes.is_empty() {
        body.push_str(&format!("<details><summary>{} passed or blessed</summary><ul>\n", passes.len()));
        for e in passes {
            let how = if e.status == Status::Blessed { "blessed" } else { "passed" };
            body.push_str(&format!("<li>{} — {how}: {}</li>\n", escape(&e.id), escape(&e.message)));
        }
        body.push_str("</ul></details>\n");
    }
    let summary = format!(
        "{} figures: {} failed, {} could not be checked, {} passed, {} blessed. A pixel differs when a channel differs by more than {per_pixel} codes; a figure fails when more than {:.3}% of its pixels differ.",
        entries.len(),
        count(Status::Failed),
        count(Status::Error),
        count(Status::Passed),
        count(Status::Blessed),
        max_share * 100.0
    );
    let legend = format!(
        "Difference: the blessed image in grey, each differing pixel in red from dark (Δ = {} codes) to bright (Δ = 255).",
        u16::from(per_pixel) + 1
    );
    let mut style = String::new();
    let page_text = format!("{body}{summary}");
    if let Some((bytes, _)) = crate::site::font::subset_for(&page_text).map_err(CliError::Internal)? {
        let to = dir.join(crate::site::font::FILE);
        crate::output::write_atomic(&to, |w| w.write_all(&bytes).map_err(|e| e.to_string()))?;
        style.push_str(&crate::site::font::face_rule());
    }
    style.push_str(STYLE);
    let verdict = if failing.is_empty() { "all figures match" } else { "figures differ" };
    let html = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>shadelab snapshot report: {verdict}</title>\n<style>\n{style}</style>\n</head>\n<body>\n<h1>shadelab snapshot report: {verdict}</h1>\n<p>{}</p>\n<p class=\"legend\">{}</p>\n{body}</body>\n</html>\n",
        escape(&summary),
        escape(&legend)
    );
    crate::output::write_atomic(&dir.join("index.html"), |w| w.write_all(html.as_bytes()).map_err(|e| e.to_string()))?;
    Ok(())
}

/// The page's style: failures in a row of three, the red scale of the difference image.
const STYLE: &str = "body { font-family: \"shadelab-ja\", system-ui, sans-serif; margin: 1rem 2rem; color: #1b1b1f; background: #fafafa; }
section { margin: 1.5rem 0; padding-top: 0.5rem; border-top: 1px solid #ddd; }
section.error h2 { color: #a00; }
.row { display: flex; flex-wrap: wrap; gap: 1rem; align-items: flex-start; }
figure { margin: 0; max-width: 32%; }
img { max-width: 100%; height: auto; border: 1px solid #ccc; }
.scale { display: inline-block; width: 6rem; height: 0.7rem; margin-left: 0.5rem; background: linear-gradient(to right, rgb(129,0,0), rgb(255,0,0)); vertical-align: middle; }
.numbers { font-family: \"shadelab-ja\", ui-monospace, monospace; }
details { margin-top: 2rem; }
";
