//! Labels drawn with the embedded DejaVu Sans: a tiny markup for course notation, measuring,
//! wrapping, and alpha-correct drawing into RGBA images.
//!
//! # Markup
//! | source | renders |
//! | --- | --- |
//! | `K_shi` | `K` then `shi` as a subscript: the run of letters and digits after `_` |
//! | `L_{spot dir}` | a longer subscript, everything up to the closing `}` |
//! | `r^2`, `x^{-1}` | superscripts, same rules as subscripts |
//! | `(R·V)^{K_shi}`, `e^{-σ_t d}` | a subscript inside a braced superscript (and the reverse) |
//! | `\_`, `\^`, `\{`, `\}`, `\\` | the character itself |
//!
//! Everything else is literal UTF-8. Nesting goes one level and only alternates (deeper or
//! same-kind markers, as in `_{a_b}`, are literal), a `_` or `^` followed by neither `{` nor a
//! letter or digit is literal, and an unclosed `{` runs to the end. Use [`escape`] for text that
//! must appear verbatim (file names, lesson keys).
//!
//! # Sizes and the line box
//! `size_px` is the em size, as in CSS `font-size`. Every line of a given size has the same
//! height ([`line_height`]) and the same baseline, whatever it contains, so labels drawn at the
//! same `y` line up; the box leaves room below for subscripts with descenders. Ink never leaves
//! the measured box: glyph parts above the font's ascender (only stacked accents reach there)
//! are clipped rather than drawn over a neighbour.
//!
//! # Determinism
//! The font bytes are compiled in and ab_glyph rasterizes with plain `f32` arithmetic (no
//! hinting, no system fonts), so the same text gives the same bytes on every machine.

use ab_glyph::{Font, FontRef, GlyphId, OutlinedGlyph, PxScale, ScaleFont, point};
use image::{Rgba, RgbaImage};
use std::sync::OnceLock;

/// DejaVu Sans 2.37, embedded so every machine draws with identical bytes.
static FONT_BYTES: &[u8] = include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/fonts/DejaVuSans.ttf"));

/// The embedded font file (also registered with the chart renderer).
pub fn font_bytes() -> &'static [u8] {
    FONT_BYTES
}

/// Scripts are drawn at this fraction of the base size (TeX uses 0.7 for first-level scripts).
const SCRIPT_SCALE: f32 = 0.7;
/// How far a subscript's baseline drops, in ems of the base size.
const SUB_DROP: f32 = 0.2;
/// How far a superscript's baseline rises, in ems of the base size.
const SUP_RISE: f32 = 0.38;
/// Placeholder box for a missing glyph: width and side bearing in ems of its run.
const PLACEHOLDER_WIDTH: f32 = 0.55;
const PLACEHOLDER_BEARING: f32 = 0.1;
/// Halo radius in ems: wide enough to separate text from any backdrop, narrow enough to keep counters open.
const HALO_RADIUS: f32 = 0.09;
/// Largest size drawn; larger requests are clamped so a typo cannot allocate gigabytes.
const MAX_SIZE_PX: f32 = 2048.0;

/// Horizontal anchoring of a line at the `x` given to [`draw`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Align {
    /// `x` is the left edge of the line box.
    Left,
    /// `x` is the centre of the line box.
    Center,
    /// `x` is the right edge of the line box.
    Right,
}

/// What went wrong while drawing, without failing: characters the font has no glyph for.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct TextReport {
    /// Characters drawn as a hollow placeholder box, each listed once, in order of appearance.
    pub missing: Vec<char>,
}

/// How to colour text: the ink, and optionally a soft halo behind it for legibility on any backdrop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Paint {
    /// Straight-alpha sRGB colour of the glyphs.
    pub color: [u8; 4],
    /// Colour of a halo about 0.09 em wide around the glyphs; it extends that far outside the measured box.
    pub halo: Option<[u8; 4]>,
}

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

/// Draws `text` (markup) with its line box's top at `y` and anchored at `x` by `align`.
///
/// Each pixel gets the glyph coverage × `color`'s alpha composited "over" it, correct for
/// straight-alpha images: onto a transparent pixel the result is exactly `color` with the
/// coverage as alpha. Pixels outside `img` are skipped. Never panics; missing glyphs are drawn
/// as hollow boxes and reported.
pub fn draw(img: &mut RgbaImage, x: i32, y: i32, text: &str, size_px: f32, color: [u8; 4], align: Align) -> TextReport {
    draw_with(img, x, y, text, size_px, Paint { color, halo: None }, align)
}

/// Like [`draw`], with a [`Paint`] that may add a halo under the glyphs.
pub fn draw_with(img: &mut RgbaImage, x: i32, y: i32, text: &str, size_px: f32, paint: Paint, align: Align) -> TextReport {
    let l = layout(text, size_px);
    let left = match align {
        Align::Left => x,
        Align::Center => x - (l.width / 2) as i32,
        Align::Right => x - l.width as i32,
    };
    let mask = coverage(&l);
    if let Some(halo) = paint.halo {
        let radius = (l.size * HALO_RADIUS).max(1.0);
        let pad = radius.ceil() as i32 + 1;
        let (w, h, halo_mask) = dilate(&mask, l.width, l.height, radius, pad);
        blend_mask(img, left - pad, y - pad, w, h, &halo_mask, halo);
    }
    blend_mask(img, left, y, l.width, l.height, &mask, paint.color);
    TextReport { missing: l.missing }
}

/// Splits `text` (markup) into lines no wider than `max_width` pixels at `size_px`, breaking at
/// spaces outside scripts and always at `\n`.
///
/// Runs of plain spaces collapse to one. A single word wider than `max_width` stays whole on its
/// own line (check with [`measure`]); an empty paragraph gives an empty line.
pub fn wrap(text: &str, size_px: f32, max_width: u32) -> Vec<String> {
    let mut lines = Vec::new();
    for paragraph in text.split('\n') {
        let mut line = String::new();
        for word in words(paragraph) {
            if line.is_empty() {
                line = word.to_string();
                continue;
            }
            let candidate = format!("{line} {word}");
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

/// Escapes `literal` so it renders verbatim: `_`, `^` and `\` get a backslash.
pub fn escape(literal: &str) -> String {
    let mut out = String::with_capacity(literal.len());
    for c in literal.chars() {
        if matches!(c, '_' | '^' | '\\') {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

/// Composites `color` with alpha scaled by `coverage` (clamped to [0, 1]) over a straight-alpha pixel.
///
/// Blending happens on the stored sRGB codes, as browsers and slide software composite PNGs, so
/// a figure drawn on a transparent background looks the same once placed as one drawn on the
/// slide's colour directly.
pub(crate) fn blend_over(dst: &mut Rgba<u8>, color: [u8; 4], coverage: f32) {
    let a_s = coverage.clamp(0.0, 1.0) * color[3] as f32 / 255.0;
    if a_s <= 0.0 {
        return;
    }
    let a_d = dst[3] as f32 / 255.0;
    // Premultiplied "over", then divided back to straight alpha.
    let a_o = a_s + a_d * (1.0 - a_s);
    for k in 0..3 {
        let c = (color[k] as f32 * a_s + dst[k] as f32 * a_d * (1.0 - a_s)) / a_o;
        dst[k] = c.round().clamp(0.0, 255.0) as u8;
    }
    dst[3] = (a_o * 255.0).round().clamp(0.0, 255.0) as u8;
}

/// The parsed font, once.
fn font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    // The bytes are compiled in and tested to parse, so this cannot fail at run time.
    FONT.get_or_init(|| FontRef::try_from_slice(FONT_BYTES).expect("embedded DejaVu Sans parses"))
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

/// (baseline below the top, line height) at `size` ems; the baseline is whole so stems stay crisp.
fn line_box(size: f32) -> (f32, u32) {
    let m = metrics();
    let baseline = (m.ascent * size).round();
    // A subscript's descenders reach below the full-size descender.
    let below = m.descent.max(SUB_DROP + SCRIPT_SCALE * m.descent) * size;
    (baseline, (baseline + below).ceil() as u32)
}

/// Where a character sits: on the baseline, in a script, or in a script of a script.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Script {
    Normal,
    Sub,
    Sup,
    /// A subscript inside a superscript: `(R·V)^{K_shi}`.
    SupSub,
    /// A superscript inside a subscript: `L_{x^2}`.
    SubSup,
}

impl Script {
    /// The script a `_` or `^` opens from here, if it opens one.
    fn inner(self, marker: char) -> Option<Script> {
        match (self, marker) {
            (Script::Normal, '_') => Some(Script::Sub),
            (Script::Normal, '^') => Some(Script::Sup),
            (Script::Sup, '_') => Some(Script::SupSub),
            (Script::Sub, '^') => Some(Script::SubSup),
            _ => None,
        }
    }

    /// (size factor, baseline shift down in ems of the base size); each level scales its parent's shift.
    fn placement(self) -> (f32, f32) {
        let s = SCRIPT_SCALE;
        match self {
            Script::Normal => (1.0, 0.0),
            Script::Sub => (s, SUB_DROP),
            Script::Sup => (s, -SUP_RISE),
            Script::SupSub => (s * s, -SUP_RISE + s * SUB_DROP),
            Script::SubSup => (s * s, SUB_DROP - s * SUP_RISE),
        }
    }
}

/// One character of parsed markup and where it came from in the source.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Token {
    ch: char,
    script: Script,
    /// Byte offset of the character (or its escaping backslash) in the source.
    at: usize,
}

fn is_escapable(c: char) -> bool {
    matches!(c, '_' | '^' | '{' | '}' | '\\')
}

/// Markup → characters with their script (see the module docs for the rules).
fn parse(text: &str) -> Vec<Token> {
    let chars: Vec<(usize, char)> = text.char_indices().collect();
    let mut out = Vec::with_capacity(chars.len());
    let mut i = 0;
    parse_run(&chars, &mut i, Script::Normal, false, &mut out);
    out
}

/// Parses `chars` from `*i` at `script` up to the end, or past the closing `}` when `braced`.
fn parse_run(chars: &[(usize, char)], i: &mut usize, script: Script, braced: bool, out: &mut Vec<Token>) {
    let next = |i: usize| chars.get(i).map(|&(_, c)| c);
    while let Some(&(at, c)) = chars.get(*i) {
        if braced && c == '}' {
            *i += 1;
            return;
        }
        if c == '\\' && next(*i + 1).is_some_and(is_escapable) {
            out.push(Token { ch: chars[*i + 1].1, script, at });
            *i += 2;
            continue;
        }
        if let Some(inner) = script.inner(c) {
            match next(*i + 1) {
                Some('{') => {
                    *i += 2;
                    parse_run(chars, i, inner, true, out);
                    continue;
                }
                Some(n) if n.is_alphanumeric() => {
                    *i += 1;
                    while let Some(&(at, c)) = chars.get(*i).filter(|(_, c)| c.is_alphanumeric()) {
                        out.push(Token { ch: c, script: inner, at });
                        *i += 1;
                    }
                    continue;
                }
                // A marker before anything else is just a character.
                _ => {}
            }
        }
        out.push(Token { ch: c, script, at });
        *i += 1;
    }
}

/// The Unicode subscript of `c`, if Unicode has one (digits, signs and some letters).
fn subscript(c: char) -> Option<char> {
    const FROM: &str = "0123456789+-=()aehijklmnoprstuvx";
    const TO: &str = "₀₁₂₃₄₅₆₇₈₉₊₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ";
    FROM.chars().position(|f| f == c).and_then(|i| TO.chars().nth(i))
}

/// The Unicode superscript of `c`, if Unicode has one.
fn superscript(c: char) -> Option<char> {
    const FROM: &str = "0123456789+-=()in";
    const TO: &str = "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁼⁽⁾ⁱⁿ";
    FROM.chars().position(|f| f == c).and_then(|i| TO.chars().nth(i))
}

/// Markup as plain text, for renderers without it (chart legends and titles): a script run
/// becomes Unicode sub- or superscript characters when every one of its characters has
/// one (`K_shi` → `Kₛₕᵢ`, `r^2` → `r²`), and is otherwise written back in markup form
/// (`x_{y z}`), which still reads.
pub fn to_plain_text(text: &str) -> String {
    let tokens = parse(text);
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < tokens.len() {
        let script = tokens[i].script;
        let end = (i..tokens.len()).find(|&j| tokens[j].script != script).unwrap_or(tokens.len());
        let run: String = tokens[i..end].iter().map(|t| t.ch).collect();
        let map = match script {
            Script::Normal => None,
            Script::Sub | Script::SupSub => Some((subscript as fn(char) -> Option<char>, '_')),
            Script::Sup | Script::SubSup => Some((superscript as fn(char) -> Option<char>, '^')),
        };
        match map {
            None => out.push_str(&run),
            Some((f, marker)) => match run.chars().map(f).collect::<Option<String>>() {
                Some(mapped) => out.push_str(&mapped),
                None if run.chars().all(char::is_alphanumeric) => {
                    out.push(marker);
                    out.push_str(&run);
                }
                None => {
                    out.push(marker);
                    out.push('{');
                    out.push_str(&run);
                    out.push('}');
                }
            },
        }
        i = end;
    }
    out
}

/// The words of one paragraph: pieces between spaces that are plain text, not inside a script.
fn words(paragraph: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    for t in parse(paragraph) {
        // An escaped space does not exist, so a plain ' ' token is always the space character at `t.at`.
        if t.ch == ' ' && t.script == Script::Normal {
            out.push(&paragraph[start..t.at]);
            start = t.at + 1;
        }
    }
    out.push(&paragraph[start..]);
    out.retain(|w| !w.is_empty());
    out
}

/// A hollow rectangle in line-box pixels: [x0, y0, x1, y1) and the stroke width.
struct Placeholder {
    rect: [i32; 4],
    stroke: i32,
}

/// A laid-out line: outlines positioned relative to the line box, which starts at x = −`shift`.
struct Layout {
    size: f32,
    width: u32,
    height: u32,
    /// Added to glyph x so ink starting left of the pen origin (a negative bearing) stays in the box.
    shift: i32,
    glyphs: Vec<OutlinedGlyph>,
    placeholders: Vec<Placeholder>,
    missing: Vec<char>,
}

fn layout(text: &str, size_px: f32) -> Layout {
    let Some(size) = sanitize(size_px) else {
        return Layout { size: 0.0, width: 0, height: 0, shift: 0, glyphs: Vec::new(), placeholders: Vec::new(), missing: Vec::new() };
    };
    let f = font();
    let m = metrics();
    let (baseline, height) = line_box(size);
    let (mut glyphs, mut placeholders, mut missing) = (Vec::new(), Vec::new(), Vec::new());
    let mut pen = 0.0f32;
    let (mut ink_min, mut ink_max) = (0.0f32, 0.0f32);
    let mut prev: Option<(GlyphId, Script)> = None;
    for t in parse(text) {
        let (factor, shift) = t.script.placement();
        let (em, base) = (size * factor, (baseline + shift * size).round());
        let scale = px_scale(em);
        let id = f.glyph_id(t.ch);
        if id.0 == 0 {
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
        }
        let scaled = f.as_scaled(scale);
        // Kerning pairs are defined within one size; across a script change the gap is the advance.
        if let Some((p, s)) = prev
            && s == t.script
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
        prev = Some((id, t.script));
    }
    let shift = -(ink_min.floor() as i32);
    let width = (ink_max.max(pen) + shift as f32).ceil().max(0.0) as u32;
    Layout { size, width, height, shift, glyphs, placeholders, missing }
}

/// Coverage in [0, 1] per pixel of the line box, row-major.
fn coverage(l: &Layout) -> Vec<f32> {
    let (w, h) = (l.width as i32, l.height as i32);
    let mut mask = vec![0.0f32; (l.width * l.height) as usize];
    for og in &l.glyphs {
        let b = og.px_bounds();
        let (ox, oy) = (b.min.x as i32 + l.shift, b.min.y as i32);
        og.draw(|gx, gy, c| {
            let (x, y) = (ox + gx as i32, oy + gy as i32);
            if (0..w).contains(&x) && (0..h).contains(&y) {
                // Summed, not maxed: neighbouring glyphs sharing an edge pixel each cover part of it.
                mask[(y * w + x) as usize] += c;
            }
        });
    }
    for p in &l.placeholders {
        let [x0, y0, x1, y1] = p.rect;
        for y in y0.max(0)..y1.min(h) {
            for x in (x0 + l.shift).max(0)..(x1 + l.shift).min(w) {
                let edge = x - l.shift - x0 < p.stroke || x1 - 1 - (x - l.shift) < p.stroke || y - y0 < p.stroke || y1 - 1 - y < p.stroke;
                if edge {
                    mask[(y * w + x) as usize] = 1.0;
                }
            }
        }
    }
    for c in &mut mask {
        *c = c.min(1.0);
    }
    mask
}

/// A soft dilation of `mask` by `radius` pixels into a buffer padded by `pad` on every side.
fn dilate(mask: &[f32], w: u32, h: u32, radius: f32, pad: i32) -> (u32, u32, Vec<f32>) {
    let (w, h) = (w as i32, h as i32);
    let (ow, oh) = (w + 2 * pad, h + 2 * pad);
    let mut out = vec![0.0f32; (ow * oh) as usize];
    let reach = radius.ceil() as i32;
    for y in 0..oh {
        for x in 0..ow {
            let mut best = 0.0f32;
            for dy in -reach..=reach {
                for dx in -reach..=reach {
                    let (sx, sy) = (x - pad + dx, y - pad + dy);
                    if !(0..w).contains(&sx) || !(0..h).contains(&sy) {
                        continue;
                    }
                    // Full strength within the radius, fading over the last pixel for a smooth edge.
                    let falloff = (radius + 0.5 - ((dx * dx + dy * dy) as f32).sqrt()).clamp(0.0, 1.0);
                    best = best.max(mask[(sy * w + sx) as usize] * falloff);
                }
            }
            out[(y * ow + x) as usize] = best;
        }
    }
    (ow as u32, oh as u32, out)
}

/// Composites `color` through a `w`×`h` coverage mask placed with its top-left at (`x`, `y`).
fn blend_mask(img: &mut RgbaImage, x: i32, y: i32, w: u32, h: u32, mask: &[f32], color: [u8; 4]) {
    for my in 0..h {
        for mx in 0..w {
            let c = mask[(my * w + mx) as usize];
            let (px, py) = (x + mx as i32, y + my as i32);
            if c > 0.0 && px >= 0 && py >= 0 && (px as u32) < img.width() && (py as u32) < img.height() {
                blend_over(img.get_pixel_mut(px as u32, py as u32), color, c);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const INK: [u8; 4] = [20, 40, 200, 255];

    fn plain(tokens: &[Token]) -> String {
        tokens.iter().map(|t| t.ch).collect()
    }

    fn scripts(text: &str) -> Vec<(char, Script)> {
        parse(text).iter().map(|t| (t.ch, t.script)).collect()
    }

    /// Bounding box [x0, y0, x1, y1) of pixels that differ from `bg`, if any.
    fn changed_box(img: &RgbaImage, bg: Rgba<u8>) -> Option<[u32; 4]> {
        let mut b: Option<[u32; 4]> = None;
        for (x, y, p) in img.enumerate_pixels() {
            if *p != bg {
                let r = b.get_or_insert([x, y, x + 1, y + 1]);
                *r = [r[0].min(x), r[1].min(y), r[2].max(x + 1), r[3].max(y + 1)];
            }
        }
        b
    }

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
    fn markup_parses_scripts_and_escapes() {
        use Script::*;
        assert_eq!(
            scripts("K_shi = 5"),
            [('K', Normal), ('s', Sub), ('h', Sub), ('i', Sub), (' ', Normal), ('=', Normal), (' ', Normal), ('5', Normal)]
        );
        assert_eq!(scripts("L_{a b}x"), [('L', Normal), ('a', Sub), (' ', Sub), ('b', Sub), ('x', Normal)]);
        assert_eq!(scripts("r^2"), [('r', Normal), ('2', Sup)]);
        assert_eq!(scripts("x^{-1}"), [('x', Normal), ('-', Sup), ('1', Sup)]);
        assert_eq!(plain(&parse(r"blinn\_phong")), "blinn_phong");
        assert!(parse(r"blinn\_phong").iter().all(|t| t.script == Normal));
        // Lone markers and stray braces are literal; an unclosed brace runs to the end.
        assert_eq!(plain(&parse("a_ b^ _")), "a_ b^ _");
        assert_eq!(plain(&parse("{x}")), "{x}");
        assert_eq!(scripts("a_{bc"), [('a', Normal), ('b', Sub), ('c', Sub)]);
        // One level of alternating nesting, for exponents like the Phong term's.
        assert_eq!(
            scripts("V)^{K_shi}x"),
            [('V', Normal), (')', Normal), ('K', Sup), ('s', SupSub), ('h', SupSub), ('i', SupSub), ('x', Normal)]
        );
        assert_eq!(scripts("e^{-σ_{t} d}"), [('e', Normal), ('-', Sup), ('σ', Sup), ('t', SupSub), (' ', Sup), ('d', Sup)]);
        assert_eq!(scripts("L_{x^2}"), [('L', Normal), ('x', Sub), ('2', SubSup)]);
        assert_eq!(to_plain_text("K_shi = 1"), "Kₛₕᵢ = 1");
        assert_eq!(to_plain_text("r^2 and F_0"), "r² and F₀");
        assert_eq!(to_plain_text("L_{spot dir}"), "L_{spot dir}");
        assert_eq!(to_plain_text("K_diff"), "K_diff", "no subscript d exists: written back as markup");
        assert_eq!(to_plain_text("a\\_b"), "a_b");
        assert_eq!(scripts("_{a_b}"), [('a', Sub), ('_', Sub), ('b', Sub)]);
        assert_eq!(scripts("^{a^{b}}"), [('a', Sup), ('^', Sup), ('{', Sup), ('b', Sup), ('}', Normal)]);
        assert_eq!(plain(&parse(r"a\b\\")), r"a\b\");
        assert!(parse("").is_empty());
    }

    #[test]
    fn escape_round_trips_through_the_parser() {
        for s in ["blinn_phong", r"a\_b", "x^2_y", r"\", "_{}^"] {
            let tokens = parse(&escape(s));
            assert_eq!(plain(&tokens), s);
            assert!(tokens.iter().all(|t| t.script == Script::Normal), "{s}");
        }
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
    fn ink_stays_inside_the_measured_box() {
        // Descenders in a subscript, a superscript, a negative left bearing ('j') and a placeholder.
        for text in ["A", "K_shi", "L_{gyp}", "r^2 x^{Ág}", "(R·V)^{K_{gjp}}", "L_{g^{Ág}}", "jjj", "f_{jpq}", "\u{E000}g", "Ș_{Ț}"] {
            let bg = Rgba([255, 255, 255, 255]);
            let mut img = RgbaImage::from_pixel(200, 80, bg);
            let (w, h) = measure(text, 24.0);
            draw(&mut img, 30, 20, text, 24.0, INK, Align::Left);
            let b = changed_box(&img, bg).expect("something drawn");
            assert!(b[0] >= 30 && b[1] >= 20 && b[2] <= 30 + w && b[3] <= 20 + h, "{text}: ink {b:?} outside box 30,20 {w}x{h}");
        }
    }

    #[test]
    fn drawing_a_changes_pixels_inside_its_box_and_none_outside() {
        let bg = Rgba([250, 250, 250, 255]);
        let (w, h) = measure("A", 32.0);
        for (align, left) in [(Align::Left, 40), (Align::Center, 40 - (w / 2) as i32), (Align::Right, 40 - w as i32)] {
            let mut img = RgbaImage::from_pixel(100, 60, bg);
            let report = draw(&mut img, 40, 10, "A", 32.0, INK, align);
            assert!(report.missing.is_empty());
            let b = changed_box(&img, bg).expect("A draws ink");
            let left = left as u32;
            assert!(b[0] >= left && b[1] >= 10 && b[2] <= left + w && b[3] <= 10 + h, "{align:?}: ink {b:?}, box {left},10 {w}x{h}");
            // The ink fills most of the box: the box is not padded far beyond the letter.
            assert!(b[2] - b[0] + 2 >= w, "{align:?}: ink width {} vs box {w}", b[2] - b[0]);
            // A capital sits on the baseline, well inside the line box vertically.
            assert!(b[3] - b[1] >= 20, "A is {} px tall", b[3] - b[1]);
        }
    }

    #[test]
    fn on_transparent_alpha_appears_only_where_ink_is_with_the_exact_colour() {
        let mut img = RgbaImage::new(120, 50);
        draw(&mut img, 5, 5, "K_shi", 24.0, INK, Align::Left);
        let (w, h) = measure("K_shi", 24.0);
        let mut inked = 0;
        for (x, y, p) in img.enumerate_pixels() {
            if p[3] > 0 {
                inked += 1;
                assert!((5..5 + w).contains(&x) && (5..5 + h).contains(&y), "alpha at {x},{y}");
                // Over a transparent pixel the colour is the ink's, not darkened by the empty background.
                assert_eq!([p[0], p[1], p[2]], [INK[0], INK[1], INK[2]], "at {x},{y}");
            }
        }
        assert!(inked > 40, "only {inked} pixels inked");
        // Antialiased: some edge pixels are partly covered.
        assert!(img.pixels().any(|p| p[3] > 0 && p[3] < 255));
        // The line box is mostly empty paper.
        assert!(inked < (w * h) as usize / 2);
    }

    #[test]
    fn blend_over_is_premultiplied_correct() {
        let mut p = Rgba([255, 0, 0, 255]);
        blend_over(&mut p, [0, 0, 255, 255], 0.5);
        assert_eq!(p, Rgba([128, 0, 128, 255]));
        let mut p = Rgba([0, 0, 0, 0]);
        blend_over(&mut p, [0, 0, 255, 255], 0.5);
        assert_eq!(p, Rgba([0, 0, 255, 128]));
        // Half-transparent blue at half coverage over half-transparent red.
        let mut p = Rgba([255, 0, 0, 128]);
        blend_over(&mut p, [0, 0, 255, 128], 1.0);
        let a = 128.0f32 / 255.0;
        let a_o = a + a * (1.0 - a);
        assert_eq!(p, Rgba([(255.0 * a * (1.0 - a) / a_o).round() as u8, 0, (255.0 * a / a_o).round() as u8, (a_o * 255.0).round() as u8]));
        let mut p = Rgba([1, 2, 3, 4]);
        blend_over(&mut p, [9, 9, 9, 255], 0.0);
        assert_eq!(p, Rgba([1, 2, 3, 4]));
    }

    #[test]
    fn missing_glyphs_are_reported_once_and_drawn_as_boxes() {
        // DejaVu Sans has no private-use or CJK glyphs (it does have U+1F600, the grinning face).
        let bg = Rgba([255, 255, 255, 255]);
        let size = 30.0;
        for c in ['\u{E000}', '中'] {
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
        assert_eq!(draw(&mut img, 0, 0, "ok \u{E000} 中\u{E000}", 20.0, INK, Align::Left).missing, ['\u{E000}', '中']);
        assert!(draw(&mut img, 0, 0, "K_shi · θ ≤ π ⊗ Σ \u{1F600}", 20.0, INK, Align::Left).missing.is_empty());
    }

    #[test]
    fn drawing_is_deterministic_and_clips_at_image_edges() {
        let render = || {
            let mut img = RgbaImage::from_pixel(90, 40, Rgba([10, 10, 10, 255]));
            draw(&mut img, -7, -5, "K_shi = 50 \u{E000}", 22.0, [240, 200, 100, 255], Align::Left);
            draw_with(&mut img, 95, 20, "r^2", 22.0, Paint { color: [0, 0, 0, 255], halo: Some([255, 255, 255, 200]) }, Align::Right);
            img
        };
        assert_eq!(render().as_raw(), render().as_raw());
    }

    #[test]
    fn halo_surrounds_the_ink() {
        let paint = Paint { color: [0, 0, 0, 255], halo: Some([255, 255, 255, 255]) };
        let mut with = RgbaImage::new(80, 40);
        draw_with(&mut with, 10, 5, "Hi", 24.0, paint, Align::Left);
        let mut without = RgbaImage::new(80, 40);
        draw(&mut without, 10, 5, "Hi", 24.0, paint.color, Align::Left);
        let count = |img: &RgbaImage| img.pixels().filter(|p| p[3] > 0).count();
        assert!(count(&with) > count(&without) + 20);
        // The ink itself is unchanged where fully covered.
        for (a, b) in with.pixels().zip(without.pixels()) {
            if b[3] == 255 {
                assert_eq!(a, b);
            }
        }
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
}
