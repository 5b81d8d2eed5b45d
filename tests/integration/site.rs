//! `shadelab site`: the gallery opened in headless Chromium (Debian's `chromium`, installed
//! by .ci/run; `SHADELAB_CHROMIUM` names another binary). Every image loads, no console
//! message is logged, every internal link and anchor resolves, nothing is fetched from the
//! network, and the index's screenshot is not blank.

use crate::helpers::{lessons_dir, shadelab};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Three cheap lessons: a split, a sweep, and the cost ladders (tables and SVG charts).
const LESSONS: [&str; 3] = ["01-first-light.toml", "04-shininess.toml", "15-cost.toml"];

fn chromium() -> String {
    let bin = std::env::var("SHADELAB_CHROMIUM").unwrap_or_else(|_| "chromium".into());
    let found = Command::new(&bin).arg("--version").stdout(Stdio::null()).stderr(Stdio::null()).status().is_ok_and(|s| s.success());
    assert!(found, "`{bin}` not found: install it (apt-get install -y chromium, as .ci/run does) or set SHADELAB_CHROMIUM");
    bin
}

/// Runs headless Chromium with `args` and a private profile; returns (stdout, stderr).
/// Killed after two minutes: a hung browser fails the test instead of stalling the suite.
fn run_chromium(bin: &str, profile: &Path, args: &[String]) -> (String, String) {
    let out = tempfile::tempdir().unwrap();
    let (so, se) = (out.path().join("stdout"), out.path().join("stderr"));
    let mut child = Command::new(bin)
        .args([
            "--headless=new",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--hide-scrollbars",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .stdout(std::fs::File::create(&so).unwrap())
        .stderr(std::fs::File::create(&se).unwrap())
        .spawn()
        .expect("start chromium");
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if start.elapsed() > Duration::from_secs(120) {
            child.kill().ok();
            child.wait().ok();
            panic!("chromium did not finish in 120 s: {args:?}");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    (std::fs::read_to_string(so).unwrap(), std::fs::read_to_string(se).unwrap())
}

/// Every value of `attr="..."` in `html`.
fn attrs<'a>(html: &'a str, attr: &str) -> Vec<&'a str> {
    let pat = format!(" {attr}=\"");
    html.match_indices(&pat).map(|(at, _)| &html[at + pat.len()..]).map(|rest| &rest[..rest.find('"').unwrap()]).collect()
}

/// The pages of the site, sorted.
fn pages(site: &Path) -> Vec<PathBuf> {
    let mut pages: Vec<PathBuf> = std::fs::read_dir(site)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "html") && !p.ends_with("check.html"))
        .collect();
    pages.sort();
    pages
}

/// Every `href` and `src` of every page names a file of the site (and an `id` of it after `#`).
fn check_links(site: &Path) -> usize {
    let mut checked = 0;
    for page in pages(site) {
        let html = std::fs::read_to_string(&page).unwrap();
        for target in attrs(&html, "href").into_iter().chain(attrs(&html, "src")) {
            assert!(!target.contains("://") && !target.starts_with("//"), "{}: `{target}` leaves the site", page.display());
            // No scheme (`javascript:`): a colon only ever appears percent-encoded.
            assert!(!target.split('/').next().unwrap().contains(':'), "{}: `{target}` has a scheme", page.display());
            let (file, fragment) = target.split_once('#').unwrap_or((target, ""));
            let file = percent_encoding::percent_decode_str(file).decode_utf8().unwrap().into_owned();
            let file = if file.is_empty() { page.clone() } else { site.join(file) };
            assert!(file.is_file(), "{}: `{target}` does not resolve", page.display());
            if !fragment.is_empty() {
                let text = std::fs::read_to_string(&file).unwrap();
                assert!(text.contains(&format!("id=\"{fragment}\"")), "{}: `{target}`: no such anchor", page.display());
            }
            checked += 1;
        }
    }
    checked
}

/// A page that loads each page in turn in an iframe and lists its images with their
/// natural widths: `IMG page src naturalWidth`, then `DONE`.
fn check_page(pages: &[String]) -> String {
    let list: Vec<String> = pages.iter().map(|p| format!("\"{}\"", shadelab::site::html::url(p))).collect();
    format!(
        r#"<!DOCTYPE html><html><body><pre id="out"></pre><script>
const pages = [{}];
const out = document.getElementById("out");
let i = 0;
function next() {{
  if (i >= pages.length) {{ out.textContent += "DONE\n"; return; }}
  const f = document.createElement("iframe");
  f.src = pages[i];
  f.onload = () => {{
    const d = f.contentDocument;
    if (!d) out.textContent += "NOACCESS " + pages[i] + "\n";
    else for (const img of d.images) out.textContent += "IMG " + pages[i] + " " + img.getAttribute("src") + " " + (img.complete ? img.naturalWidth : -1) + "\n";
    f.remove();
    i++;
    next();
  }};
  document.body.appendChild(f);
}}
next();
</script></body></html>
"#,
        list.join(", ")
    )
}

#[test]
fn the_site_opens_in_a_browser_with_every_image_and_link() {
    let bin = chromium();
    let tmp = tempfile::tempdir().unwrap();
    let site = tmp.path().join("site");
    let mut lessons: Vec<PathBuf> = LESSONS.iter().map(|l| lessons_dir().join(l)).collect();
    // A lesson whose name is a script URL: its card must link to its page, not run script.
    let hostile = tmp.path().join("javascript:alert(document.domain).toml");
    std::fs::copy(lessons_dir().join("01-first-light.toml"), &hostile).unwrap();
    lessons.push(hostile);
    shadelab().arg("site").args(&lessons).args(["--cell", "64x64", "--thumb-width", "96", "-q", "-o"]).arg(&site).assert().success();

    // What the site holds: an index, the glossary, a page per lesson, every figure, the cost charts.
    let names: Vec<String> = pages(&site).iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    assert_eq!(
        names,
        [
            "01-first-light.html",
            "04-shininess.html",
            "15-cost.html",
            "glossary.html",
            "index.html",
            "javascript:alert(document.domain).html"
        ]
    );
    let glossary = std::fs::read_to_string(site.join("glossary.html")).unwrap();
    assert!(glossary.contains("自己発光") && glossary.contains("<td>umbra</td>"), "the glossary lists the course's terms");
    let cost = std::fs::read_to_string(site.join("15-cost.html")).unwrap();
    assert_eq!(cost.matches("<table class=\"cost\">").count(), 2, "one table per ladder");
    assert!(site.join("15-cost/interpolation-chart.svg").is_file() && site.join("15-cost/tessellation-chart.svg").is_file());
    let first = std::fs::read_to_string(site.join("01-first-light.html")).unwrap();
    assert!(first.contains("<math display=\"block\">"), "the equations are MathML");
    assert!(first.contains("[lesson]") && first.contains("<pre>") && first.contains("Passes"), "the source and the explain text");
    // Script only for the live lab (when its build is there), from files beside the page and
    // none inline, its section hidden until the script shows it: without script, the page is
    // the static one.
    let scripts: Vec<&str> = attrs(&first, "src").into_iter().filter(|s| s.ends_with(".js")).collect();
    assert_eq!(first.matches("<script").count(), scripts.len(), "no inline script");
    assert!(scripts.iter().all(|s| s.starts_with("live/") || *s == "01-first-light/live.js"), "{scripts:?}");
    assert!(scripts.is_empty() || first.contains("id=\"live-lab\" hidden"), "the live lab shows only once its script runs");
    let index = std::fs::read_to_string(site.join("index.html")).unwrap();
    assert_eq!(attrs(&index, "src").len(), 4, "a thumbnail per lesson");
    assert!(index.contains("href=\"javascript%3Aalert%28document.domain%29.html\""), "the hostile name's link is encoded");

    let links = check_links(&site);
    assert!(links > 30, "only {links} links and images checked");

    // Every image loads in the browser, and nothing is logged to the console.
    let profile = tmp.path().join("profile");
    let page_names: Vec<String> = names.clone();
    std::fs::write(site.join("check.html"), check_page(&page_names)).unwrap();
    let url = format!("file://{}", site.join("check.html").display());
    let (dom, log) = run_chromium(
        &bin,
        &profile,
        &["--allow-file-access-from-files".into(), "--virtual-time-budget=30000".into(), "--dump-dom".into(), url],
    );
    // Only the results, not the check page's own script (which names NOACCESS too).
    let dom = dom.split("</pre>").next().unwrap_or_default();
    assert!(dom.contains("DONE"), "the check page did not finish:\n{dom}\n{log}");
    assert!(!dom.contains("NOACCESS"), "a page could not be read:\n{dom}");
    // The first result shares its line with the `<pre>` that holds them all.
    let images: Vec<&str> = dom.lines().filter_map(|l| l.find("IMG ").map(|i| &l[i..])).collect();
    let expected: usize = page_names.iter().map(|p| std::fs::read_to_string(site.join(p)).unwrap().matches("<img ").count()).sum();
    assert_eq!(images.len(), expected, "images seen by the browser:\n{}", images.join("\n"));
    for line in &images {
        let width: i64 = line.rsplit(' ').next().unwrap().parse().unwrap();
        assert!(width > 0, "an image did not load: {line}");
    }
    let console: Vec<&str> = log.lines().filter(|l| l.contains(":CONSOLE")).collect();
    assert!(console.is_empty(), "console messages:\n{}", console.join("\n"));

    // The index's screenshot is not blank: many colours, and much of it not the background.
    let shot = tmp.path().join("index.png");
    let url = format!("file://{}", site.join("index.html").display());
    run_chromium(&bin, &profile, &[format!("--screenshot={}", shot.display()), "--window-size=1280,900".into(), url]);
    let img = image::open(&shot).unwrap_or_else(|e| panic!("no screenshot: {e}")).to_rgb8();
    assert_eq!(img.dimensions(), (1280, 900));
    let mut counts = std::collections::HashMap::new();
    for p in img.pixels() {
        *counts.entry(p.0).or_insert(0usize) += 1;
    }
    let background = counts.values().max().copied().unwrap();
    let drawn = 1.0 - background as f64 / (1280.0 * 900.0);
    assert!(counts.len() > 200, "{} colours in the screenshot", counts.len());
    assert!(drawn > 0.05, "{:.1}% of the screenshot differs from the background", drawn * 100.0);
    // Kept for a person to look at.
    let keep = Path::new(env!("CARGO_TARGET_TMPDIR")).join("site-index.png");
    std::fs::copy(&shot, &keep).ok();
}

/// A page laid out as the site's pages are (their style sheet, `lang="ja"`, a bold h1, a
/// paragraph, a `<pre>`), each holding `text` in a fixed row, so two screenshots compare row
/// by row.
fn font_rows_page(text: &str) -> String {
    let row =
        |top: u32, tag: &str| format!("<{tag} style=\"position:absolute;top:{top}px;left:8px;margin:0;white-space:nowrap\">{text}</{tag}>");
    format!(
        "<!doctype html><html lang=\"ja\"><head><meta charset=\"utf-8\"><link rel=\"stylesheet\" href=\"style.css\"></head><body>{}{}{}</body></html>",
        row(0, "h1"),
        row(80, "p"),
        row(140, "pre")
    )
}

/// Issue "figures a teacher can put on a slide", item 1: on a machine without a CJK font,
/// lesson 34's Japanese showed as empty boxes. The site now ships the Japanese font cut to
/// its pages' characters. The browser draws a heading, a paragraph and a `<pre>` of the
/// page's Japanese, and each row must differ from the same row of characters no font has
/// (private-use code points, drawn as the boxes of missing glyphs), and two rows of
/// different characters must differ from each other.
#[test]
fn the_sites_japanese_is_drawn_with_the_font_it_ships() {
    let bin = chromium();
    let tmp = tempfile::tempdir().unwrap();
    let site = tmp.path().join("site");
    let lessons = [lessons_dir().join("34-japanese-labels.toml"), lessons_dir().join("01-first-light.toml")];
    shadelab().arg("site").args(&lessons).args(["--cell", "64x64", "--thumb-width", "96", "-q", "-o"]).arg(&site).assert().success();
    let style = std::fs::read_to_string(site.join("style.css")).unwrap();
    assert!(style.starts_with("@font-face { font-family: \"shadelab-ja\"; src: url(\"shadelab-ja.otf\")"), "{style}");
    assert!(site.join("shadelab-ja-LICENSE.txt").is_file(), "the font's license travels with it");
    let font = std::fs::metadata(site.join("shadelab-ja.otf")).unwrap().len();
    assert!(font < 100_000, "the font is cut to the pages' characters: {font} bytes");
    // The Japanese of lesson 34's page (its title first), in two different runs of eight.
    let page = std::fs::read_to_string(site.join("34-japanese-labels.html")).unwrap();
    let mut seen = std::collections::BTreeSet::new();
    let japanese: Vec<char> = page.chars().filter(|&c| ('\u{3040}'..='\u{9fff}').contains(&c) && seen.insert(c)).collect();
    assert!(japanese.len() >= 16, "lesson 34's page has Japanese: {japanese:?}");
    let (a, b): (String, String) = (japanese[..8].iter().collect(), japanese[8..16].iter().collect());
    let tofu: String = (0..8).map(|i| char::from_u32(0xE000 + i).unwrap()).collect();
    let profile = tmp.path().join("profile");
    let shot = |name: &str, text: &str| {
        std::fs::write(site.join(format!("{name}.html")), font_rows_page(text)).unwrap();
        let png = tmp.path().join(format!("{name}.png"));
        let url = format!("file://{}", site.join(format!("{name}.html")).display());
        run_chromium(
            &bin,
            &profile,
            &["--virtual-time-budget=10000".into(), format!("--screenshot={}", png.display()), "--window-size=640,200".into(), url],
        );
        image::open(&png).unwrap_or_else(|e| panic!("no screenshot: {e}")).to_rgb8()
    };
    let (ja_a, ja_b, boxes) = (shot("ja-a", &a), shot("ja-b", &b), shot("tofu", &tofu));
    // Rows: the h1 (0–80), the paragraph (80–140), the pre (140–200).
    let row = |img: &image::RgbImage, y0: u32, y1: u32| -> Vec<[u8; 3]> {
        (y0..y1).flat_map(|y| (0..640).map(move |x| img.get_pixel(x, y).0)).collect()
    };
    let ink = |r: &[[u8; 3]]| r.iter().filter(|p| p.iter().any(|&c| c < 128)).count();
    for (what, y0, y1) in [("h1", 0, 80), ("p", 80, 140), ("pre", 140, 200)] {
        let (ra, rb, rt) = (row(&ja_a, y0, y1), row(&ja_b, y0, y1), row(&boxes, y0, y1));
        assert!(ink(&ra) > 100 && ink(&rb) > 100, "{what}: the Japanese drew ink");
        assert_ne!(ra, rt, "{what}: {a} drew as missing glyphs do");
        assert_ne!(rb, rt, "{what}: {b} drew as missing glyphs do");
        assert_ne!(ra, rb, "{what}: two different runs of characters drew the same (boxes)");
    }
    // Kept for a person to look at.
    std::fs::copy(tmp.path().join("ja-a.png"), Path::new(env!("CARGO_TARGET_TMPDIR")).join("site-japanese.png")).ok();
}
