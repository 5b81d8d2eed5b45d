//! The difference row of a `compare` or `sweep` figure (`diff = true`): each cell's
//! |difference| from the first cell as a heatmap, on one scale shared by the row, so cells
//! that look alike (Schlick against the exact Fresnel) show where and by how much they differ.

use super::colorbar::ColorBar;
use super::grid::Cell;
use crate::cost::metrics::{error_heatmap, pixel_errors, quantile};
use crate::render::{Frame, Layer};
use image::DynamicImage;

/// Share of pixels the top colour may saturate, as in the cost strips: the scale is the 99th
/// percentile of the nonzero differences, so a few edge pixels do not hide the rest.
const DIFF_QUANTILE: f64 = 0.99;

/// The heatmap cells, one per frame (the first is all black: it is the reference), and the
/// colour bar: 0 to the scale, which is 0 when every frame equals the first.
pub fn row(frames: &[Frame], layer: Layer, lang: crate::lesson::i18n::Lang) -> (Vec<Cell>, ColorBar) {
    let first = &frames[0];
    let mut all = Vec::new();
    for f in &frames[1..] {
        if let Ok(e) = pixel_errors(f, first, layer) {
            all.extend(e.into_iter().filter(|x| *x > 0.0));
        }
    }
    let scale = quantile(&all, DIFF_QUANTILE);
    let cells = frames
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let map = error_heatmap(f, first, layer, scale).expect("cells of one figure share a size");
            let note = (i == 0).then(|| lang.tr("the reference").to_string());
            Cell { image: DynamicImage::ImageRgb8(map).to_rgba8(), time_ms: None, note }
        })
        .collect();
    let hi = if scale == 0.0 { "0".to_string() } else { format!("{scale:.1e}") };
    (cells, ColorBar::heat(lang.say(&format!("|difference| from the first cell, {} layer", layer.name())), "0", hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A 4×3 frame of 0.5 grey, with column 1 at `v`, fully covered.
    fn frame(v: f32) -> Frame {
        let px = (0..12).map(|i| Vec3::splat(if i % 4 == 1 { v } else { 0.5 })).collect();
        Frame { width: 4, height: 3, layers: vec![(Layer::Total, px)], coverage: vec![1.0; 12], background: Vec3::ZERO }
    }

    #[test]
    fn identical_cells_differ_by_zero_and_the_scale_says_so() {
        let (cells, bar) = row(&[frame(0.5), frame(0.5), frame(0.5)], Layer::Total, crate::lesson::i18n::Lang::En);
        assert_eq!(cells.len(), 3);
        let black = crate::cost::metrics::heat_colour(0.0);
        assert!(cells.iter().all(|c| c.image.pixels().all(|p| p.0[..3] == black)));
        assert_eq!((bar.lo.as_str(), bar.hi.as_str()), ("0", "≥ 0"));
    }

    #[test]
    fn a_difference_shows_where_it_is_at_its_size() {
        let (cells, bar) = row(&[frame(0.5), frame(0.75)], Layer::Total, crate::lesson::i18n::Lang::En);
        assert_eq!(bar.hi, "≥ 2.5e-1");
        let top = crate::cost::metrics::heat_colour(1.0);
        assert_eq!(cells[1].image.get_pixel(1, 0).0[..3], top);
        assert_eq!(cells[1].image.get_pixel(0, 0).0[..3], crate::cost::metrics::heat_colour(0.0));
    }
}
