//! The colour bar under a heatmap row: the ramp from 0 to its scale, with the two ends and
//! what the colours measure written under it, so a heatmap can be read without its caption.

use super::text::{self, Align, Paint};
use crate::cost::metrics::heat_colour;
use image::{Rgba, RgbaImage};

/// Width of the bar at scale 1, in pixels (narrower if the cells are).
pub const BAR_W_PX: f32 = 360.0;
/// Height of the bar at scale 1.
pub const BAR_H_PX: f32 = 14.0;

/// What a heatmap's colours mean.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorBar {
    /// What is measured, e.g. `|error| (linear radiance)`.
    pub label: String,
    /// The value of the darkest colour (usually `0`).
    pub lo: String,
    /// The value of the brightest colour (the heatmap's scale; larger values saturate).
    pub hi: String,
}

/// Draws the ramp `w`×`h` with its top-left at (`x`, `y`), and under it `lo` at the left end,
/// `hi` (prefixed `≥`) at the right end and the label centred, in `size` px text.
pub fn draw(img: &mut RgbaImage, bar: &ColorBar, (x, y): (i32, i32), (w, h): (u32, u32), size: f32, ink: Paint) -> Vec<char> {
    for i in 0..w {
        let t = if w > 1 { i as f32 / (w - 1) as f32 } else { 0.0 };
        let [r, g, b] = heat_colour(t);
        for j in 0..h {
            let (px, py) = (x + i as i32, y + j as i32);
            if px >= 0 && py >= 0 && (px as u32) < img.width() && (py as u32) < img.height() {
                img.put_pixel(px as u32, py as u32, Rgba([r, g, b, 255]));
            }
        }
    }
    let under = y + h as i32 + (size * 0.25).round() as i32;
    let mut missing = Vec::new();
    missing.extend(text::draw_with(img, x, under, &bar.lo, size, ink, Align::Left).missing);
    missing.extend(text::draw_with(img, x + w as i32, under, &format!("≥ {}", bar.hi), size, ink, Align::Right).missing);
    missing.extend(text::draw_with(img, x + w as i32 / 2, under, &bar.label, size, ink, Align::Center).missing);
    missing
}

/// The height the bar and its labels take: the ramp, a small gap and one line of text.
pub fn height(scale: f32, size: f32) -> u32 {
    (BAR_H_PX * scale).round() as u32 + (size * 0.25).round() as u32 + text::line_height(size)
}

/// The narrowest the bar can be and still show its three labels apart: the label is
/// centred, so each half of the bar holds half the label, a gap of one em and the longer
/// of the two end values.
pub fn min_width(bar: &ColorBar, size: f32) -> u32 {
    let w = |s: &str| text::measure(s, size).0;
    w(&bar.label) + 2 * (w(&bar.lo).max(w(&format!("≥ {}", bar.hi))) + size.ceil() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::grid::{Cell, GridSpec, compose};

    /// Rows of `img` that hold the whole ramp: both end colours and many shades between.
    fn ramp_rows(img: &RgbaImage) -> Vec<u32> {
        let (lo, hi) = (heat_colour(0.0), heat_colour(1.0));
        (0..img.height())
            .filter(|&y| {
                let mut shades: Vec<[u8; 3]> = (0..img.width()).map(|x| [0, 1, 2].map(|c| img.get_pixel(x, y).0[c])).collect();
                let ends = shades.contains(&lo) && shades.contains(&hi);
                shades.sort_unstable();
                shades.dedup();
                ends && shades.len() > 100
            })
            .collect()
    }

    #[test]
    fn a_grid_with_a_colour_bar_draws_the_ramp_under_the_cells() {
        let cells = vec![vec![Cell::new(RgbaImage::from_pixel(200, 100, Rgba([255, 255, 255, 255])))]; 2];
        let bar = ColorBar { label: "|error|".into(), lo: "0".into(), hi: "1.0e-2".into() };
        let with = compose(&cells, &GridSpec { colorbar: Some(bar), ..GridSpec::default() });
        let without = compose(&cells, &GridSpec::default());
        let rows = ramp_rows(&with.image);
        assert_eq!(rows.len() as f32, BAR_H_PX, "the bar is {BAR_H_PX} px tall");
        assert!(rows[0] > 2 * 100, "under both rows of cells");
        assert!(ramp_rows(&without.image).is_empty());
        assert!(with.image.height() >= without.image.height() + height(1.0, 16.0));
        assert!(with.missing_glyphs.is_empty());
    }

    #[test]
    fn the_centred_label_clears_both_end_values() {
        // A long scale value and a long label (the difference row's, at snapshot scale).
        let bar = ColorBar { label: "|difference| from the first cell, total layer".into(), lo: "0".into(), hi: "6.2e-2".into() };
        for size in [8.0, 16.0, 20.0] {
            let w = |s: &str| text::measure(s, size).0 as i32;
            let bar_w = min_width(&bar, size) as i32;
            let (label_left, label_right) = (bar_w / 2 - w(&bar.label) / 2, bar_w / 2 + w(&bar.label) / 2);
            assert!(label_left > w(&bar.lo), "size {size}: the label runs into `0`");
            assert!(label_right < bar_w - w(&format!("≥ {}", bar.hi)), "size {size}: the label runs into the scale");
        }
    }
}
