//! Labels drawn with the embedded DejaVu Sans (and Noto Sans JP for the Japanese it lacks): a tiny markup for course notation, measuring,
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

mod draw;
mod layout;
mod markup;

pub(crate) use draw::blend_over;
pub use draw::{draw, draw_with};
pub use layout::{line_height, measure, wrap};
pub use markup::{escape, to_html, to_plain_text};

use ab_glyph::FontRef;
use std::sync::OnceLock;

/// Appends `text` (one drawn line, as plain text) to the file `$SHADELAB_TEXT_LOG` names, if
/// any: the project's tests render the gallery in Japanese with it set and check what a
/// student would read for English left behind.
pub(crate) fn log_drawn(text: &str) {
    use std::io::Write;
    if let Some(file) = text_log() {
        let mut f = file.lock().unwrap_or_else(|e| e.into_inner());
        let _ = writeln!(f, "{}", text.replace('\n', " "));
    }
}

/// True when drawn text is logged ([`log_drawn`]): a figure must then be drawn, not read
/// back from the cache, for its text to reach the log.
pub(crate) fn logging_text() -> bool {
    text_log().is_some()
}

/// The file `$SHADELAB_TEXT_LOG` names, opened once for appending.
fn text_log() -> Option<&'static std::sync::Mutex<std::fs::File>> {
    static LOG: OnceLock<Option<std::sync::Mutex<std::fs::File>>> = OnceLock::new();
    LOG.get_or_init(|| {
        let path = std::env::var_os("SHADELAB_TEXT_LOG")?;
        std::fs::OpenOptions::new().create(true).append(true).open(path).ok().map(std::sync::Mutex::new)
    })
    .as_ref()
}

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

/// Horizontal anchoring of a line at the `x` given to [`draw`](fn@draw).
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

/// The parsed font, once.
fn font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    // The bytes are compiled in and tested to parse, so this cannot fail at run time.
    FONT.get_or_init(|| FontRef::try_from_slice(FONT_BYTES).expect("embedded DejaVu Sans parses"))
}

/// Noto Sans CJK JP 2.004 (SIL Open Font License 1.1), subset to kana, the JIS X 0208
/// kanji and symbols, CJK punctuation and full-width forms (assets/fonts/README.md):
/// Japanese labels and captions draw on every machine alike.
static CJK_BYTES: &[u8] = include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/fonts/NotoSansJP-Subset.otf"));

/// The embedded Japanese font file (Noto Sans JP, the subset above): the site ships the
/// glyphs its pages use from it.
pub fn cjk_font_bytes() -> &'static [u8] {
    CJK_BYTES
}

/// The parsed fallback font, once.
fn cjk_font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    FONT.get_or_init(|| FontRef::try_from_slice(CJK_BYTES).expect("embedded Noto Sans JP parses"))
}

/// The font that draws `ch` and its glyph: DejaVu Sans first, so text it covers keeps
/// its exact bytes; Noto Sans JP for what DejaVu lacks; `None` when neither has it.
fn glyph_for(ch: char) -> Option<(&'static FontRef<'static>, ab_glyph::GlyphId)> {
    use ab_glyph::Font;
    [font(), cjk_font()].into_iter().map(|f| (f, f.glyph_id(ch))).find(|(_, id)| id.0 != 0)
}

/// True when DejaVu Sans has a glyph for every character of `s` (charts hand such text to
/// plotters, which draws with DejaVu alone).
pub fn covers(s: &str) -> bool {
    use ab_glyph::Font;
    s.chars().all(|c| c.is_control() || font().glyph_id(c).0 != 0)
}

/// The em size whose DejaVu ascent-to-descent height is `height` pixels (plotters sizes its
/// fonts by that height; [`draw`](fn@draw) by the em).
pub fn em_for_height(height: f32) -> f32 {
    use ab_glyph::Font;
    let f = font();
    height * f.units_per_em().unwrap_or(2048.0) / f.height_unscaled()
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{Rgba, RgbaImage};

    /// The ink of the drawing tests in `layout` and `draw` too.
    pub(super) const INK: [u8; 4] = [20, 40, 200, 255];

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
}
