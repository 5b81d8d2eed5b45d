//! Drawing a laid-out line: glyph coverage, the halo's dilation, and straight-alpha compositing.

use super::layout::{Layout, layout};
use super::{Align, Paint, TextReport};
use image::{Rgba, RgbaImage};

/// Halo radius in ems: wide enough to separate text from any backdrop, narrow enough to keep counters open.
const HALO_RADIUS: f32 = 0.09;

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
    super::log_drawn(&super::to_plain_text(text));
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
    use crate::figure::text::measure;
    use crate::figure::text::tests::INK;

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
}
