//! The site's HTML: the index, a lesson's page, a cost table, and the style sheet. No
//! script, no external resource: every page reads only files the site itself holds.

use super::PageFigure;
use super::math::Equation;
use crate::cost::LadderReport;
use crate::lesson::Lesson;

/// Text as HTML: `&`, `<`, `>`, `"` and `'` escaped (for element content and attributes).
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Prose as paragraphs: blank lines separate them, `` `code` `` becomes `<code>`, and the
/// course notation (`K_shi`, `cos^L_exp`) sub- and superscripts ([`prose`]).
pub fn paragraphs(text: &str) -> String {
    let mut out = String::new();
    for para in text.split("\n\n").map(str::trim).filter(|p| !p.is_empty()) {
        let joined = para.lines().map(str::trim).collect::<Vec<_>>().join(" ");
        out.push_str("<p>");
        out.push_str(&prose(&joined));
        out.push_str("</p>\n");
    }
    out
}

/// A line of prose as HTML: `` `x` `` becomes `<code>x</code>` (literal: keys such as
/// `shadow_map_size` keep their underscores), the rest is the figures' label markup (`K_shi`
/// → K<sub>shi</sub>), every character escaped. An unpaired backtick stays.
pub fn prose(text: &str) -> String {
    let parts: Vec<&str> = text.split('`').collect();
    let mut out = String::new();
    for (i, part) in parts.iter().enumerate() {
        let closes_pair = i % 2 == 1 && i + 1 < parts.len();
        match (i % 2, closes_pair) {
            (1, true) => out.push_str(&format!("<code>{}</code>", escape(part))),
            (1, false) => {
                out.push('`');
                out.push_str(&crate::figure::text::to_html(part, &escape));
            }
            _ => out.push_str(&crate::figure::text::to_html(part, &escape)),
        }
    }
    out
}

/// The head of every page.
fn head(title: &str, lang: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"{lang}\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n<link rel=\"stylesheet\" href=\"style.css\">\n</head>\n<body>\n",
        escape(title)
    )
}

/// One lesson on the index.
#[derive(Debug, Clone)]
pub struct Card {
    /// Its page.
    pub page: String,
    /// Its title.
    pub title: String,
    /// Its one-line summary.
    pub summary: String,
    /// Its image.
    pub thumb: String,
    /// The image's size.
    pub thumb_size: (u32, u32),
    /// How many figures its page has.
    pub figures: usize,
}

/// Bytes of a file name kept as they are in a link: the URL's unreserved characters
/// (RFC 3986, section 2.3); everything else, `:` `#` `?` `%` and non-ASCII included, is
/// percent-encoded.
const SEGMENT: &percent_encoding::AsciiSet = &percent_encoding::NON_ALPHANUMERIC.remove(b'-').remove(b'.').remove(b'_').remove(b'~');

/// A relative link to the site's file `path` (`/`-separated): each segment percent-encoded,
/// so a lesson named `javascript:alert(1)` links to its own page, not a script, and `#` or
/// `?` in a name do not cut the link short.
pub fn url(path: &str) -> String {
    path.split('/').map(|seg| percent_encoding::utf8_percent_encode(seg, SEGMENT).to_string()).collect::<Vec<_>>().join("/")
}

/// The index: a card per lesson.
pub fn index_page(cards: &[Card]) -> String {
    let mut s = head("shadelab lessons", "en");
    s.push_str("<header><h1>shadelab lessons</h1>\n<p class=\"summary\">Each lesson: its image, notes, equations, figures, what runs and why, and its source. The course's terms in both languages: <a href=\"glossary.html\">glossary · 用語集</a>.</p></header>\n<main>\n<ol class=\"cards\">\n");
    for c in cards {
        s.push_str(&format!(
            "<li class=\"card\"><a href=\"{page}\"><img src=\"{thumb}\" width=\"{w}\" height=\"{h}\" alt=\"{title}\"><span class=\"title\">{title}</span></a>\n<p>{summary}</p>\n<p class=\"meta\">{n} figure{plural}</p></li>\n",
            page = escape(&url(&c.page)),
            thumb = escape(&url(&c.thumb)),
            w = c.thumb_size.0,
            h = c.thumb_size.1,
            title = escape(&c.title),
            summary = prose(&c.summary),
            n = c.figures,
            plural = if c.figures == 1 { "" } else { "s" },
        ));
    }
    s.push_str("</ol>\n</main>\n<footer>Made by <code>shadelab site</code>.</footer>\n</body>\n</html>\n");
    s
}

/// The glossary: the course's terms in English and in the lectures' Japanese, by topic
/// ([`crate::lesson::glossary::GLOSSARY`]).
pub fn glossary_page() -> String {
    use crate::lesson::glossary::{GLOSSARY, topics};
    let mut s = head("Glossary · 用語集", "en");
    s.push_str("<header><p><a href=\"index.html\">All lessons</a></p><h1>Glossary · <span lang=\"ja\">用語集</span></h1>\n<p class=\"summary\">The course's terms as the lessons write them in English and as the lectures write them in Japanese (<code>--lang ja</code> uses the same words).</p></header>\n<main>\n");
    for topic in topics() {
        s.push_str(&format!(
            "<section>\n<h2>{}</h2>\n<table>\n<tr><th>English</th><th lang=\"ja\">日本語</th><th>notation</th></tr>\n",
            escape(topic)
        ));
        for t in GLOSSARY.iter().filter(|t| t.topic == topic) {
            s.push_str(&format!("<tr><td>{}</td><td lang=\"ja\">{}</td><td>{}</td></tr>\n", escape(t.en), escape(t.ja), escape(t.note)));
        }
        s.push_str("</table>\n</section>\n");
    }
    s.push_str("</main>\n<footer>Made by <code>shadelab site</code>.</footer>\n</body>\n</html>\n");
    s
}

/// Links to the neighbouring lessons: (page, title).
#[derive(Debug, Clone, Default)]
pub struct Nav {
    /// The lesson before.
    pub prev: Option<(String, String)>,
    /// The lesson after.
    pub next: Option<(String, String)>,
}

/// What a lesson's page shows.
#[derive(Debug)]
pub struct LessonPage<'a> {
    /// The lesson's file stem.
    pub stem: &'a str,
    /// The lesson.
    pub lesson: &'a Lesson,
    /// Its image, relative to the site.
    pub thumb: &'a str,
    /// The image's size.
    pub thumb_size: (u32, u32),
    /// Its figures, made.
    pub figures: &'a [PageFigure],
    /// The equations of its materials.
    pub equations: &'a [Equation],
    /// `shadelab explain`'s text.
    pub explain: &'a str,
    /// The live view's data script, when the site has the live lab.
    pub live: Option<&'a str>,
    /// Neighbours.
    pub nav: Nav,
}

/// A lesson's page.
pub fn lesson_page(p: &LessonPage<'_>) -> String {
    let l = p.lesson;
    let mut s = head(&format!("{} — shadelab", l.title), l.lang.name());
    let mut nav = String::from("<nav class=\"top\"><a href=\"index.html\">All lessons</a>");
    if let Some((page, title)) = &p.nav.prev {
        nav.push_str(&format!(" · <a href=\"{}\" rel=\"prev\">← {}</a>", escape(&url(page)), escape(title)));
    }
    if let Some((page, title)) = &p.nav.next {
        nav.push_str(&format!(" · <a href=\"{}\" rel=\"next\">{} →</a>", escape(&url(page)), escape(title)));
    }
    nav.push_str("</nav>\n");
    s.push_str(&nav);
    s.push_str(&format!("<header><h1>{}</h1>\n<p class=\"summary\">{}</p></header>\n", escape(&l.title), prose(&l.summary)));
    s.push_str("<nav class=\"toc\"><a href=\"#notes\">Notes</a> <a href=\"#equations\">Equations</a> <a href=\"#figures\">Figures</a> <a href=\"#explain\">What runs and why</a> <a href=\"#source\">Source</a></nav>\n<main>\n");

    s.push_str(&format!(
        "<section id=\"notes\"><h2>Notes</h2>\n<img class=\"render\" src=\"{}\" width=\"{}\" height=\"{}\" alt=\"{}: the lesson's render\">\n{}</section>\n",
        escape(&url(p.thumb)),
        p.thumb_size.0,
        p.thumb_size.1,
        escape(&l.title),
        if l.notes.trim().is_empty() { "<p>(no notes)</p>\n".to_string() } else { paragraphs(&l.notes) }
    ));

    if let Some(data) = p.live {
        s.push_str(&live_section(data, l.lang == crate::lesson::i18n::Lang::Ja));
    }

    s.push_str("<section id=\"equations\"><h2>Equations</h2>\n");
    if p.equations.is_empty() {
        s.push_str("<p>(no materials)</p>\n");
    }
    for e in p.equations {
        s.push_str(&format!("<h3>{}</h3>\n{}\n<p class=\"source\">{}</p>\n", escape(e.name), e.mathml, escape(e.source)));
    }
    s.push_str("</section>\n");

    s.push_str("<section id=\"figures\"><h2>Figures</h2>\n");
    if p.figures.is_empty() {
        s.push_str("<p>(no figures)</p>\n");
    }
    for f in p.figures {
        let heading = f.title.clone().unwrap_or_else(|| f.name.clone());
        s.push_str(&format!(
            "<figure id=\"fig-{name}\"><h3>{heading} <a class=\"anchor\" href=\"#fig-{name}\">#</a></h3>\n<img src=\"{png}\" width=\"{w}\" height=\"{h}\" alt=\"{alt}\">\n",
            name = escape(&f.name),
            heading = escape(&heading),
            png = escape(&url(&f.png)),
            w = f.size.0,
            h = f.size.1,
            alt = escape(f.caption.as_deref().unwrap_or(&heading)),
        ));
        if let Some(c) = &f.caption {
            s.push_str(&format!("<figcaption>{}</figcaption>\n", prose(c)));
        }
        if let Some(cost) = &f.cost {
            s.push_str(&cost.table);
            if let Some(svg) = &cost.svg {
                s.push_str(&format!(
                    "<img class=\"chart\" src=\"{0}\" alt=\"error against time, {1}\">\n",
                    escape(&url(svg)),
                    escape(&f.name)
                ));
            }
        }
        s.push_str("</figure>\n");
    }
    s.push_str("</section>\n");

    s.push_str(&format!(
        "<section id=\"explain\"><h2>What runs and why</h2>\n<p>The output of <code>shadelab explain lessons/{}.toml</code>:</p>\n<pre>{}</pre></section>\n",
        escape(p.stem),
        escape(p.explain)
    ));
    s.push_str(&format!(
        "<section id=\"source\"><h2>Source: {}.toml</h2>\n<pre><code>{}</code></pre></section>\n",
        escape(p.stem),
        escape(&l.source)
    ));
    s.push_str("</main>\n");
    s.push_str(&nav.replace("class=\"top\"", "class=\"bottom\""));
    s.push_str("</body>\n</html>\n");
    s
}

/// The live lab's section: hidden until its script has loaded the renderer (a page without
/// script keeps its static figures), then the canvases, the controls, the frame time, the
/// CLI line that reproduces the picture, and the CLI's error messages.
fn live_section(data: &str, ja: bool) -> String {
    let t = |en: &'static str, jp: &'static str| if ja { jp } else { en };
    format!(
        "<section id=\"live\"><h2>{title}</h2>\n<noscript><p>{noscript}</p></noscript>\n\
<div class=\"lab\" id=\"live-lab\" hidden data-t-azel=\"{azel}\" data-t-az=\"{az}\" data-t-el=\"{el}\" data-t-preview=\"{preview}\" data-t-full=\"{full}\" data-t-nan=\"{nan}\">\n\
<div class=\"views\"><canvas id=\"live-total\" class=\"total\"></canvas>\n\
<div class=\"terms\"><figure><canvas id=\"live-ambient\"></canvas><figcaption>{amb}</figcaption></figure>\
<figure><canvas id=\"live-diffuse\"></canvas><figcaption>{diff}</figcaption></figure>\
<figure><canvas id=\"live-specular\"></canvas><figcaption>{spec}</figcaption></figure></div></div>\n\
<form id=\"live-controls\" class=\"controls\"></form>\n\
<p class=\"status\" id=\"live-status\"></p>\n<pre class=\"error\" id=\"live-error\" hidden></pre>\n\
<p>{cli}</p>\n<pre id=\"live-cli\"></pre>\n<button type=\"button\" id=\"live-copy\">{copy}</button> <button type=\"button\" id=\"live-reset\">{reset}</button>\n\
</div>\n\
<script src=\"live/shadelab_wasm_bg.js\"></script>\n<script src=\"live/shadelab_wasm.js\"></script>\n<script src=\"{data}\"></script>\n<script src=\"live/lab.js\"></script>\n</section>\n",
        title = t("Live lab", "ライブ実験"),
        noscript = t(
            "The live lab needs JavaScript; the figures below are the static ones.",
            "ライブ実験には JavaScript が必要です。下の図は静的な図です。"
        ),
        amb = t("ambient", "環境光"),
        diff = t("diffuse", "拡散反射"),
        spec = t("specular", "鏡面反射"),
        cli = t("The same picture from the command line:", "同じ画像をコマンドラインで:"),
        copy = t("Copy", "コピー"),
        // The script's words are in the page, so the Japanese font subset holds them.
        azel = t(" (azimuth, elevation)", " (方位角, 仰角)"),
        az = t("azimuth (degrees)", "方位角 (度)"),
        el = t("elevation (degrees)", "仰角 (度)"),
        preview = t("preview {size}: {ms} ms a frame", "プレビュー {size}: 1 フレーム {ms} ms"),
        full = t("full size {size}: {ms} ms", "フルサイズ {size}: {ms} ms"),
        nan = t(" ({n} samples not finite, set to black)", " (有限でないサンプル {n} 個を黒に)"),
        reset = t("Reset", "元に戻す"),
        data = escape(&url(data)),
    )
}

/// The live lab's styles, added to `style.css` when the site has it.
pub const LIVE_STYLE: &str = r#"
#live .views { display: flex; flex-wrap: wrap; gap: 1rem; align-items: flex-start; }
#live canvas.total { max-width: 100%; image-rendering: auto; border: 1px solid #ccc; }
#live .terms { display: flex; flex-direction: column; gap: 0.25rem; }
#live .terms figure { margin: 0; }
#live .terms canvas { width: 160px; border: 1px solid #ccc; }
#live .terms figcaption { font-size: 0.85rem; }
#live .controls { display: grid; grid-template-columns: repeat(auto-fill, minmax(21rem, 1fr)); gap: 0.3rem 1.5rem; margin: 1rem 0; }
#live .controls label { display: grid; grid-template-columns: 11rem 1fr 5.5rem; gap: 0.5rem; align-items: center; font-size: 0.85rem; }
#live .controls label > span { display: flex; flex-direction: column; }
#live pre { white-space: pre-wrap; overflow-wrap: anywhere; }
#live .controls code { overflow-wrap: anywhere; font-family: "shadelab-ja", ui-monospace, monospace; }
#live .status { color: #555; font-size: 0.9rem; }
#live button, #live select, #live output { font: inherit; }
#live .error { color: #a00; white-space: pre-wrap; }
"#;

/// A measured ladder as a `<table>` (the columns of `shadelab cost`'s table).
pub fn cost_table(r: &LadderReport) -> String {
    let front = r.pareto();
    let mut s = format!(
        "<table class=\"cost\">\n<caption>The {} ladder; reference: {}</caption>\n<thead><tr><th>rung</th><th>triangles</th><th>median ms</th><th>min ms</th><th>max ms</th><th>RMSE</th><th>max err</th><th>PSNR</th><th>visible %</th><th>front</th></tr></thead>\n<tbody>\n",
        escape(r.ladder.name()),
        escape(&r.reference.describe())
    );
    for (i, x) in r.rungs.iter().enumerate() {
        let m = &x.metrics;
        let mark = match (front.contains(&i), x.is_reference) {
            (_, true) => "reference",
            (true, false) => "*",
            (false, false) => "",
        };
        s.push_str(&format!(
            "<tr><td>{}</td><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{:.2}</td><td>{:.2e}</td><td>{:.2e}</td><td>{}</td><td>{:.2}</td><td>{}</td></tr>\n",
            escape(&x.name),
            if x.exact { "ray cast".to_string() } else { x.triangles.to_string() },
            x.timing.median_ms,
            x.timing.min_ms,
            x.timing.max_ms,
            m.rmse,
            m.max_err,
            escape(&crate::cost::metrics::psnr_text(m.psnr)),
            m.visible_pct,
            mark
        ));
    }
    s.push_str("</tbody>\n</table>\n");
    s
}

/// The style sheet: readable on screen and printed, light and dark.
pub const STYLE: &str = r#"body { font-family: "shadelab-ja", system-ui, sans-serif; max-width: 72rem; margin: 0 auto; padding: 0 1rem 2rem; line-height: 1.5; color: #1b1b1f; background: #fafafa; }
h1 { margin: 1rem 0 0.25rem; }
.summary { color: #4a4a55; margin-top: 0; }
nav.top, nav.bottom, nav.toc { margin: 0.75rem 0; }
nav.toc a { margin-right: 1rem; }
img { max-width: 100%; height: auto; }
img.render { float: right; margin: 0 0 1rem 1rem; max-width: 40%; border-radius: 4px; }
section { clear: both; margin-top: 2rem; }
figure { margin: 1.5rem 0; }
figcaption { color: #333; max-width: 60rem; }
a.anchor { font-size: 0.8em; color: #999; text-decoration: none; }
pre { font-family: "shadelab-ja", ui-monospace, monospace; background: #f0f0f3; padding: 0.75rem; overflow-x: auto; font-size: 0.85rem; line-height: 1.35; }
math { font-size: 1.15rem; margin: 0.5rem 0; }
.source { color: #666; font-size: 0.85rem; }
ol.cards { list-style: none; padding: 0; display: grid; grid-template-columns: repeat(auto-fill, minmax(15rem, 1fr)); gap: 1.25rem; }
.card { background: #fff; border: 1px solid #ddd; border-radius: 6px; padding: 0.75rem; }
.card a { text-decoration: none; color: inherit; }
.card img { display: block; width: 100%; height: auto; border-radius: 4px; background: #000; }
.card .title { display: block; font-weight: 600; margin-top: 0.5rem; }
.card p { margin: 0.25rem 0; font-size: 0.9rem; }
.card .meta { color: #777; }
table.cost { border-collapse: collapse; margin: 1rem 0; font-size: 0.85rem; font-variant-numeric: tabular-nums; }
table.cost caption { text-align: left; font-weight: 600; padding-bottom: 0.25rem; }
table.cost th, table.cost td { border: 1px solid #ccc; padding: 0.2rem 0.5rem; text-align: right; }
table.cost td:first-child, table.cost th:first-child { text-align: left; }
img.chart { display: block; background: #fff; }
footer { margin-top: 3rem; color: #777; font-size: 0.85rem; }
@media (prefers-color-scheme: dark) {
  body { color: #e4e4e8; background: #17171a; }
  .summary, figcaption { color: #c0c0c8; }
  pre { background: #232328; }
  .card { background: #202024; border-color: #333; }
  a { color: #8ab4f8; }
}
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_glossary_page_lists_every_term_with_its_japanese() {
        let page = glossary_page();
        let rows = page.matches("<tr><td>").count();
        assert_eq!(rows, crate::lesson::glossary::GLOSSARY.len());
        assert!(page.contains("<tr><td>emission</td><td lang=\"ja\">自己発光</td>"), "{page}");
        assert!(page.contains("<td lang=\"ja\">半影</td>") && page.contains("<h2>Radiometry</h2>"));
        assert!(index_page(&[]).contains("href=\"glossary.html\""));
    }

    #[test]
    fn escapes_markup_and_quotes() {
        assert_eq!(escape(r#"<a href="x">&'"#), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;");
        // Links from names: no scheme, no fragment or query, non-ASCII as UTF-8 bytes.
        assert_eq!(url("javascript:alert(document.domain).html"), "javascript%3Aalert%28document.domain%29.html");
        assert_eq!(url("a#b?c%d/render.png"), "a%23b%3Fc%25d/render.png");
        assert_eq!(url("光/x y.png"), "%E5%85%89/x%20y.png");
        assert_eq!(url("01-first-light.html"), "01-first-light.html");
    }

    #[test]
    fn paragraphs_join_lines_and_mark_code() {
        let p = paragraphs("one\ntwo `a<b`\n\nthree ` lone");
        assert_eq!(p, "<p>one two <code>a&lt;b</code></p>\n<p>three ` lone</p>\n");
    }

    #[test]
    fn prose_sets_the_course_notation_and_keeps_keys_literal() {
        assert_eq!(prose("K_shi sets the highlight"), "K<sub>shi</sub> sets the highlight");
        assert_eq!(prose("the cos^{L_exp} law"), "the cos<sup>L<sub>exp</sub></sup> law");
        assert_eq!(prose("`max_bounces` and `a<b`"), "<code>max_bounces</code> and <code>a&lt;b</code>");
        assert_eq!(prose("r^2 < x_{a&b}"), "r<sup>2</sup> &lt; x<sub>a&amp;b</sub>");
        assert_eq!(prose("a lone ` K_d"), "a lone ` K<sub>d</sub>");
        assert_eq!(prose("max(R·V, 0)^{K_shi} K_spec"), "max(R·V, 0)<sup>K<sub>shi</sub></sup> K<sub>spec</sub>");
    }
}
