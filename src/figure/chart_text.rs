//! Chart text in the lesson's language: a plotters backend wrapper that translates every
//! string a chart draws ([`Lang::say`]) and, on bitmaps, draws text DejaVu Sans cannot
//! (Japanese) with the figure text renderer, whose per-glyph fallback has Noto Sans JP.
//!
//! English text, and any text DejaVu covers, goes to the wrapped backend unchanged, so
//! English charts keep their exact bytes.

use super::text;
use crate::lesson::i18n::Lang;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind};

/// A backend whose text is translated, and drawn by [`text`] where DejaVu lacks a glyph.
pub struct Localized<B> {
    inner: B,
    lang: Lang,
    /// True for bitmaps: text DejaVu cannot draw is rasterized here. False for SVG, whose
    /// viewer falls back to its own fonts glyph by glyph.
    raster: bool,
}

impl<B: DrawingBackend> Localized<B> {
    /// `inner` drawing in `lang`; `raster` as for bitmap backends.
    pub fn new(inner: B, lang: Lang, raster: bool) -> Self {
        Localized { inner, lang, raster }
    }

    /// The translated text, and whether this wrapper must draw it itself.
    fn own(&self, s: &str) -> (String, bool) {
        let t = self.lang.say(s);
        let own = self.raster && !text::covers(&t);
        (t, own)
    }
}

/// The em size [`text`] takes for plotters' pixel size (the font's ascent-to-descent height).
fn em(style: &impl BackendTextStyle) -> f32 {
    text::em_for_height(style.size() as f32)
}

impl<B: DrawingBackend> DrawingBackend for Localized<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }
    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_pixel(point, color)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(from, to, style)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_path(path, style)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_circle(center, radius, style, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.fill_polygon(vert, style)
    }
    fn blit_bitmap(&mut self, pos: BackendCoord, size: (u32, u32), src: &[u8]) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.blit_bitmap(pos, size, src)
    }

    fn draw_text<S: BackendTextStyle>(&mut self, s: &str, style: &S, pos: BackendCoord) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let (t, own) = self.own(s);
        if !own {
            text::log_drawn(&t);
            return self.inner.draw_text(&t, style, pos);
        }
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        // Drawn white-on-transparent into a line box, then each covered pixel blended in at
        // its coverage, placed and turned as plotters places its own text.
        let literal = text::escape(&t);
        let (w, h) = text::measure(&literal, em(style));
        let mut mask = image::RgbaImage::new(w, h);
        text::draw(&mut mask, 0, 0, &literal, em(style), [255, 255, 255, 255], text::Align::Left);
        let anchor = style.anchor();
        let dx = match anchor.h_pos {
            HPos::Left => 0,
            HPos::Right => -(w as i32),
            HPos::Center => -(w as i32) / 2,
        };
        let dy = match anchor.v_pos {
            VPos::Top => 0,
            VPos::Center => -(h as i32) / 2,
            VPos::Bottom => -(h as i32),
        };
        let turn = style.transform();
        let (cw, ch) = self.get_size();
        for (x, y, p) in mask.enumerate_pixels() {
            if p[3] == 0 {
                continue;
            }
            let (tx, ty) = turn.transform(x as i32 + dx, y as i32 + dy);
            let (px, py) = (pos.0 + tx, pos.1 + ty);
            if px >= 0 && py >= 0 && (px as u32) < cw && (py as u32) < ch {
                let alpha = color.alpha * p[3] as f64 / 255.0;
                self.inner.draw_pixel((px, py), BackendColor { alpha, rgb: color.rgb })?;
            }
        }
        Ok(())
    }

    fn estimate_text_size<S: BackendTextStyle>(&self, s: &str, style: &S) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let (t, own) = self.own(s);
        if own { Ok(text::measure(&text::escape(&t), em(style))) } else { self.inner.estimate_text_size(&t, style) }
    }
}

/// `label` with spaces after it where it has characters DejaVu Sans lacks (Japanese): plotters
/// sizes the legend box with DejaVu alone, which counts them narrow, while the chart draws
/// them with Noto Sans JP; the spaces, drawn as nothing, make the box wide enough.
pub fn legend_label(label: &str) -> String {
    let missing: String = label.chars().filter(|c| !text::covers(c.encode_utf8(&mut [0; 4]))).collect();
    if missing.is_empty() {
        return label.to_string();
    }
    let px = 14.0;
    let wide = text::measure(&text::escape(&missing), px).0 as f32;
    let space = (text::measure("a a", px).0 as f32 - text::measure("aa", px).0 as f32).max(1.0);
    format!("{label}{}", " ".repeat((wide / space).ceil() as usize))
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::prelude::*;

    #[test]
    fn a_japanese_legend_entry_gets_room_and_an_english_one_is_left_as_it_is() {
        assert_eq!(legend_label("GGX r = 0.5"), "GGX r = 0.5");
        let ja = legend_label("正規化フォン n = 10");
        let pad = ja.len() - "正規化フォン n = 10".len();
        // Six CJK characters, each about an em, are several spaces wide each.
        assert!(ja.starts_with("正規化フォン n = 10") && ja.trim_end() == "正規化フォン n = 10" && pad >= 12, "{pad} spaces");
    }

    /// "albedo" drawn upright and turned (as an axis title) through `wrap`; the pixels.
    fn drawn(lang: Option<Lang>) -> Vec<u8> {
        let size = (240u32, 120u32);
        let mut buf = vec![255u8; (size.0 * size.1 * 3) as usize];
        {
            let raw = BitMapBackend::with_buffer(&mut buf, size);
            match lang {
                None => draw_albedo(raw.into_drawing_area()),
                Some(lang) => draw_albedo(Localized::new(raw, lang, true).into_drawing_area()),
            }
        }
        buf
    }

    fn draw_albedo<DB: DrawingBackend>(area: DrawingArea<DB, plotters::coord::Shift>) {
        let style = (crate::figure::plot::font(), 20).into_font().color(&BLACK);
        let turned = (crate::figure::plot::font(), 20).into_font().transform(FontTransform::Rotate270).color(&BLACK);
        area.draw_text("albedo", &style, (10, 10)).unwrap();
        area.draw_text("albedo", &turned, (200, 110)).unwrap();
        area.present().unwrap();
    }

    #[test]
    fn english_passes_through_unchanged_and_japanese_is_drawn_with_its_glyphs() {
        let plain = drawn(None);
        assert_eq!(drawn(Some(Lang::En)), plain, "English keeps plotters' bytes");
        let ja = drawn(Some(Lang::Ja));
        assert_ne!(ja, plain);
        // アルベド has ink, upright (top-left) and turned (right), and no placeholder boxes.
        let ink = |x0: usize, x1: usize, y0: usize, y1: usize| {
            (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x, y))).filter(|&(x, y)| ja[3 * (y * 240 + x)] < 128).count()
        };
        assert!(ink(0, 120, 0, 45) > 40, "upright text drawn");
        assert!(ink(185, 240, 20, 120) > 40, "turned text drawn");
        assert!(!text::covers("アルベド") && text::covers("albedo"));
        let mut img = image::RgbaImage::new(200, 40);
        assert!(text::draw(&mut img, 0, 0, "アルベド", 20.0, [0, 0, 0, 255], text::Align::Left).missing.is_empty());
    }

    #[test]
    fn svg_text_is_translated_and_left_to_the_viewer_fonts() {
        let mut doc = String::new();
        {
            let area = Localized::new(SVGBackend::with_string(&mut doc, (200, 60)), Lang::Ja, false).into_drawing_area();
            area.draw_text("iteration", &(crate::figure::plot::font(), 14).into_font().color(&BLACK), (5, 5)).unwrap();
            area.present().unwrap();
        }
        assert!(doc.contains("反復") && !doc.contains("iteration"), "{doc}");
    }
}
