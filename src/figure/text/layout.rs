//! Font metrics and line layout: glyphs placed on one line box, measuring and wrapping.

use super::markup::{Script, parse};
use super::{SCRIPT_SCALE, SUB_DROP, font, glyph_for};
use ab_glyph::{Font, GlyphId, OutlinedGlyph, PxScale, ScaleFont, point};
use std::sync::OnceLock;

/// Placeholder box for a missing glyph: width and side bearing in ems of its run.
const PLACEHOLDER_WIDTH: f32 = 0.55;
const PLACEHOLDER_BEARING: f32 = 0.1;
/// Largest size drawn; larger requests are clamped so a typo cannot allocate gigabytes.
const MAX_SIZE_PX: f32 = 2048.0;

/// The width and line height, in pixels, of `text` (markup) at `size_px` ems.
///
/// The width covers every glyph's advance and ink; the height is [`line_height`]. A size that
/// is not finite and positive measures (0, 0).
pub fn measure(text: &str, size_px: f32) -> (u32, u32) {
    let l = layout(text, size_px);
    (l.width, l.height)
}

/// The height of every line box at `size_px` ems: the font's ascender plus room for subscripted descenders.
pub fn line_height(size_px: f32) -> u32 {
    match sanitize(size_px) {
        Some(size) => line_box(size).1,
        None => 0,
    }
}

/// Splits `text` (markup) into lines no wider than `max_width` pixels at `size_px`, breaking at
/// spaces outside scripts, between Japanese characters (kana and kanji carry no spaces; a line
/// never starts with closing punctuation such as 、。」 or ends with an opening 「), and always
/// at `\n`.
///
/// Runs of plain spaces collapse to one. A single word wider than `max_width` stays whole on its
/// own line (check with [`measure`]); an empty paragraph gives an empty line.
pub fn wrap(text: &str, size_px: f32, max_width: u32) -> Vec<String> {
    let mut lines = Vec::new();
    for paragraph in text.split('\n') {
        let mut line = String::new();
        for (word, spaced) in words(paragraph) {
            if line.is_empty() {
                line = word.to_string();
                continue;
            }
            let candidate = if spaced { format!("{line} {word}") } else { format!("{line}{word}") };
            if measure(&candidate, size_px).0 <= max_width {
                line = candidate;
            } else {
                lines.push(std::mem::replace(&mut line, word.to_string()));
            }
        }
        lines.push(line);
    }
    lines
}

/// Vertical metrics of the font in ems.
struct Metrics {
    units_per_em: f32,
    ascent: f32,
    /// Below the baseline, positive.
    descent: f32,
    cap_height: f32,
}

fn metrics() -> &'static Metrics {
    static METRICS: OnceLock<Metrics> = OnceLock::new();
    METRICS.get_or_init(|| {
        let f = font();
        let upem = f.units_per_em().unwrap_or(2048.0);
        // ab_glyph stores an outline's y extent flipped (min.y is the top); take the larger either way.
        let cap = f.outline(f.glyph_id('H')).map(|o| o.bounds.min.y.max(o.bounds.max.y)).unwrap_or(0.7 * upem);
        Metrics { units_per_em: upem, ascent: f.ascent_unscaled() / upem, descent: -f.descent_unscaled() / upem, cap_height: cap / upem }
    })
}

/// `size_px` if it can be drawn, clamped to [`MAX_SIZE_PX`].
fn sanitize(size_px: f32) -> Option<f32> {
    (size_px.is_finite() && size_px > 0.0).then(|| size_px.min(MAX_SIZE_PX))
}

/// ab_glyph's scale is the pixel height of ascent − descent, not the em; convert.
fn px_scale(em_px: f32) -> PxScale {
    PxScale::from(em_px * font().height_unscaled() / metrics().units_per_em)
}

/// [`px_scale`] for a glyph of font `f`: the same em size in that font's own units.
fn px_scale_of(f: &ab_glyph::FontRef<'_>, em_px: f32) -> PxScale {
    if std::ptr::eq(f, font()) { px_scale(em_px) } else { PxScale::from(em_px * f.height_unscaled() / f.units_per_em().unwrap_or(1000.0)) }
}

/// (baseline below the top, line height) at `size` ems; the baseline is whole so stems stay crisp.
fn line_box(size: f32) -> (f32, u32) {
    let m = metrics();
    let baseline = (m.ascent * size).round();
    // A subscript's descenders reach below the full-size descender.
    let below = m.descent.max(SUB_DROP + SCRIPT_SCALE * m.descent) * size;
    (baseline, (baseline + below).ceil() as u32)
}

/// The words of one paragraph: pieces between spaces that are plain text, not inside a script.
/// The pieces a paragraph may break between, each with whether a space joins it to the one
/// before (false between Japanese characters).
fn words(paragraph: &str) -> Vec<(&str, bool)> {
    let mut out = Vec::new();
    let (mut start, mut spaced, mut prev) = (0, true, ' ');
    for t in parse(paragraph) {
        // An escaped space does not exist, so a plain ' ' token is always the space character at `t.at`.
        if t.ch == ' ' && t.script == Script::Normal {
            out.push((&paragraph[start..t.at], spaced));
            (start, spaced) = (t.at + 1, true);
        } else if t.script == Script::Normal && t.at > start && breaks_between(prev, t.ch) {
            out.push((&paragraph[start..t.at], spaced));
            (start, spaced) = (t.at, false);
        }
        prev = t.ch;
    }
    out.push((&paragraph[start..], spaced));
    out.retain(|(w, _)| !w.is_empty());
    out
}

/// Whether a line may break between `a` and `b` without a space: next to a Japanese
/// character, unless `b` may not start a line or `a` may not end one (JIS X 4051's
/// 行頭禁則 and 行末禁則, the common subset).
fn breaks_between(a: char, b: char) -> bool {
    let japanese = |c: char| matches!(c, '\u{3040}'..='\u{30ff}' | '\u{3400}'..='\u{9fff}' | '\u{f900}'..='\u{faff}' | '\u{ff01}'..='\u{ff60}' | '\u{3000}'..='\u{303f}');
    let no_start = "、。，．・：；？！ー…‥）」』】〕〉》｝])ぁぃぅぇぉっゃゅょゎァィゥェォッャュョヮヵヶ々";
    let no_end = "（「『【〔〈《｛[(";
    (japanese(a) || japanese(b)) && !no_start.contains(b) && !no_end.contains(a)
}

/// A hollow rectangle in line-box pixels: [x0, y0, x1, y1) and the stroke width.
pub(super) struct Placeholder {
    pub(super) rect: [i32; 4],
    pub(super) stroke: i32,
}

/// A laid-out line: outlines positioned relative to the line box, which starts at x = −`shift`.
pub(super) struct Layout {
    pub(super) size: f32,
    pub(super) width: u32,
    pub(super) height: u32,
    /// Added to glyph x so ink starting left of the pen origin (a negative bearing) stays in the box.
    pub(super) shift: i32,
    pub(super) glyphs: Vec<OutlinedGlyph>,
    pub(super) placeholders: Vec<Placeholder>,
    pub(super) missing: Vec<char>,
}

pub(super) fn layout(text: &str, size_px: f32) -> Layout {
    let Some(size) = sanitize(size_px) else {
        return Layout { size: 0.0, width: 0, height: 0, shift: 0, glyphs: Vec::new(), placeholders: Vec::new(), missing: Vec::new() };
    };
    let m = metrics();
    let (baseline, height) = line_box(size);
    let (mut glyphs, mut placeholders, mut missing) = (Vec::new(), Vec::new(), Vec::new());
    let mut pen = 0.0f32;
    let (mut ink_min, mut ink_max) = (0.0f32, 0.0f32);
    let mut prev: Option<(GlyphId, Script, *const ab_glyph::FontRef<'static>)> = None;
    for t in parse(text) {
        let (factor, shift) = t.script.placement();
        let (em, base) = (size * factor, (baseline + shift * size).round());
        let Some((f, id)) = glyph_for(t.ch) else {
            if !missing.contains(&t.ch) {
                missing.push(t.ch);
            }
            let x0 = (pen + PLACEHOLDER_BEARING * em).round() as i32;
            let x1 = x0 + (PLACEHOLDER_WIDTH * em).round().max(3.0) as i32;
            let y0 = (base - m.cap_height * em).round() as i32;
            placeholders.push(Placeholder { rect: [x0, y0, x1, base as i32], stroke: (0.07 * em).round().max(1.0) as i32 });
            pen += (PLACEHOLDER_WIDTH + 2.0 * PLACEHOLDER_BEARING) * em;
            ink_max = ink_max.max(x1 as f32);
            prev = None;
            continue;
        };
        let scale = px_scale_of(f, em);
        let scaled = f.as_scaled(scale);
        // Kerning pairs are defined within one size; across a script change the gap is the advance.
        if let Some((p, s, pf)) = prev
            && s == t.script
            && std::ptr::eq(pf, f)
        {
            pen += scaled.kern(p, id);
        }
        if let Some(og) = f.outline_glyph(id.with_scale_and_position(scale, point(pen, base))) {
            let b = og.px_bounds();
            ink_min = ink_min.min(b.min.x);
            ink_max = ink_max.max(b.max.x);
            glyphs.push(og);
        }
        pen += scaled.h_advance(id);
        prev = Some((id, t.script, f));
    }
    let shift = -(ink_min.floor() as i32);
    let width = (ink_max.max(pen) + shift as f32).ceil().max(0.0) as u32;
    Layout { size, width, height, shift, glyphs, placeholders, missing }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::text::tests::INK;
    use crate::figure::text::{Align, draw};
    use image::{Rgba, RgbaImage};

    #[test]
    fn embedded_font_parses_and_has_sane_metrics() {
        let m = metrics();
        assert_eq!(m.units_per_em, 2048.0);
        assert!(m.ascent > 0.8 && m.ascent < 1.0, "ascent {}", m.ascent);
        assert!(m.descent > 0.1 && m.descent < 0.4, "descent {}", m.descent);
        // DejaVu Sans capitals are 1493 units tall.
        assert!((m.cap_height - 1493.0 / 2048.0).abs() < 1e-3, "cap height {}", m.cap_height);
    }

    #[test]
    fn measure_grows_with_text_length() {
        let mut last = 0;
        for n in 1..8 {
            let (w, h) = measure(&"Gouraud ".repeat(n), 20.0);
            assert!(w > last, "{n}: {w} <= {last}");
            assert_eq!(h, line_height(20.0));
            last = w;
        }
        assert_eq!(measure("", 20.0), (0, line_height(20.0)));
        assert!(line_height(40.0) > line_height(20.0));
        assert_eq!(measure("abc", 0.0), (0, 0));
        assert_eq!(measure("abc", f32::NAN), (0, 0));
    }

    #[test]
    fn subscript_is_narrower_than_the_same_letters_at_full_size() {
        let (sub, _) = measure("K_shi", 20.0);
        let (full, _) = measure("Kshi", 20.0);
        let (k, _) = measure("K", 20.0);
        assert!(sub < full, "subscript {sub} vs full {full}");
        assert!(sub > k, "the subscript takes space: {sub} vs {k}");
        assert_eq!(measure("K_{shi}", 20.0), measure("K_shi", 20.0));
        // A script of a script is smaller still.
        assert!(measure("x^{K_shi}", 20.0).0 < measure("x^{Kshi}", 20.0).0);
    }

    #[test]
    fn wrap_breaks_at_spaces_outside_scripts() {
        let text = "The specular term K_{spec  shiny} grows with K_shi while the diffuse term stays";
        let lines = wrap(text, 16.0, 150);
        assert!(lines.len() > 2, "{lines:?}");
        for l in &lines {
            assert!(measure(l, 16.0).0 <= 150 || !l.contains(' '), "{l:?} too wide");
            assert!(!l.starts_with(' ') && !l.ends_with(' '));
        }
        assert!(lines.iter().any(|l| l.contains("K_{spec  shiny}")), "a braced script is never split: {lines:?}");
        assert_eq!(lines.join(" "), text, "nothing lost, the double space inside the braces kept");
        assert_eq!(wrap("one\n\ntwo", 16.0, 1000), ["one", "", "two"]);
        assert_eq!(wrap("", 16.0, 100), [""]);
        assert_eq!(wrap("unbreakable", 16.0, 5), ["unbreakable"]);
    }

    #[test]
    fn japanese_wraps_between_characters_but_not_before_closing_punctuation() {
        let text = "粗い球: フラットは面ごとに一色、グーローは頂点で計算、フォンは画素ごとに計算。K_shi は変えない";
        let lines = wrap(text, 16.0, 120);
        assert!(lines.len() > 3, "{lines:?}");
        for l in &lines {
            assert!(measure(l, 16.0).0 <= 120, "{l:?} too wide");
            assert!(!l.starts_with(['、', '。', 'ー']), "{l:?} starts with closing punctuation");
        }
        // An ASCII parenthesis in Japanese text keeps to its word too, at every width.
        let paren = "同じ重み (パネルの手前の角も奥の角も同じ重み)。立体角で";
        for width in 40..400 {
            for l in wrap(paren, 16.0, width) {
                assert!(!l.starts_with(')') && !l.ends_with('('), "{l:?} at {width} px");
            }
        }
        // Nothing lost: the pieces join without spaces, except where the text had one.
        assert_eq!(lines.concat().replace(' ', ""), text.replace(' ', ""));
        assert!(lines.iter().any(|l| l.contains("K_shi")), "notation stays whole: {lines:?}");
        // English breaks only at spaces, as before.
        assert_eq!(wrap("flat Gouraud", 16.0, 40), ["flat", "Gouraud"]);
    }

    #[test]
    fn missing_glyphs_are_reported_once_and_drawn_as_boxes() {
        // Neither DejaVu Sans nor the Japanese subset has private-use or Hangul glyphs (DejaVu has U+1F600).
        let bg = Rgba([255, 255, 255, 255]);
        let size = 30.0;
        for c in ['\u{E000}', '한'] {
            let mut img = RgbaImage::from_pixel(160, 50, bg);
            let report = draw(&mut img, 0, 0, &format!("a{c}b{c}"), size, [0, 0, 0, 255], Align::Left);
            assert_eq!(report.missing, [c]);
            // Along a row through the middle of the first box: a dark left edge, then paper inside it.
            let mid_y = (metrics().ascent * size - metrics().cap_height * size / 2.0) as u32;
            let start = measure("a", size).0;
            let row: Vec<u8> = (start..start + 30).map(|x| img.get_pixel(x, mid_y)[0]).collect();
            let edge = row.iter().position(|&v| v < 64).expect("the box's left edge");
            assert!(row[edge + (PLACEHOLDER_WIDTH * size / 2.0) as usize] > 200, "{c:?}: box not hollow: {row:?}");
        }
        let mut img = RgbaImage::new(200, 40);
        assert_eq!(draw(&mut img, 0, 0, "ok \u{E000} 한\u{E000}", 20.0, INK, Align::Left).missing, ['\u{E000}', '한']);
        assert!(draw(&mut img, 0, 0, "K_shi · θ ≤ π ⊗ Σ \u{1F600}", 20.0, INK, Align::Left).missing.is_empty());
    }
}
