//! Figures laid out for a slide (`--fit 1920x1080`, `[[figure]] fit`).
//!
//! The text is sized for the slide, never below [`MIN_TEXT_PX`]: on 1920 × 1080 the title is
//! 35 px, labels 25 px, captions 20 px and timings 16 px (a 1080-px slide projected is about
//! 30 cm tall, so 16 px is about 4.5 mm, the least a back row reads). Then the cells get the
//! largest size, at their aspect ratio, whose figure fits the slide: a one-row figure (compare,
//! sweep) may be reflowed into several rows, each with its labels above it; labels wrap to the
//! cell width instead of spreading the columns apart. The figure is centred on a canvas of
//! exactly the slide's size. Charts and cost figures keep their layout, at the slide's text
//! size, centred on the slide when they fit.

use super::grid::{self, GridSpec, Shape, TIMING_PX};
use image::{Rgba, RgbaImage};

/// No text of a fitted figure is smaller than this many pixels (em), at any slide size.
pub const MIN_TEXT_PX: f32 = 16.0;

/// The text scale on a 1920 × 1080 slide (labels 20 × 1.25 = 25 px).
const SLIDE_SCALE: f32 = 1.25;

/// Cells are never laid out smaller than this many pixels wide.
const MIN_CELL_W: u32 = 16;

/// The text scale for a slide of `size`: [`SLIDE_SCALE`] at 1920 × 1080, proportional to
/// the slide, and never so small that the smallest text is under [`MIN_TEXT_PX`].
pub fn text_scale((w, h): (u32, u32)) -> f32 {
    (SLIDE_SCALE * (w as f32 / 1920.0).min(h as f32 / 1080.0)).max(MIN_TEXT_PX / TIMING_PX)
}

/// The text scale of a figure `width` px wide made without a slide (cost figures): its
/// smallest text is [`MIN_TEXT_PX`] on the figure, and still that once the figure is
/// shrunk onto a 1920-px-wide slide.
pub fn wide_text_scale(width: u32) -> f32 {
    MIN_TEXT_PX / TIMING_PX * (width as f32 / 1920.0).max(1.0)
}

/// How a figure of cells is laid out on the slide.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Arrangement {
    /// Cells per row.
    pub cols: usize,
    /// Rows of cells.
    pub rows: usize,
    /// The size each cell is rendered at.
    pub cell: (u32, u32),
}

/// The arrangement with the largest cells whose figure fits `slide`. `count` cells in `rows`
/// rows of `cols`; `reflow` lets a one-row figure wrap onto several rows. `aspect` is the
/// cell's height / width; `spec` is the figure's text with `wrap_labels` set and its scale;
/// `under` the widest line under a cell, if any. When nothing fits, the smallest cells.
pub fn arrange(
    rows: usize,
    cols: usize,
    reflow: bool,
    aspect: f32,
    slide: (u32, u32),
    spec: &GridSpec,
    under: Option<&str>,
) -> Arrangement {
    let count = rows * cols;
    let options: Vec<(usize, usize)> =
        if reflow && rows == 1 { (1..=cols).map(|c| (count.div_ceil(c), c)).collect() } else { vec![(rows, cols)] };
    let fits = |(r, c): (usize, usize), w: u32| {
        let cell = (w, ((w as f32 * aspect).round() as u32).max(1));
        let mut spec = spec.clone();
        if r > 1 && rows == 1 {
            // Reflowed: the labels move above each row.
            spec.cell_labels = spec.col_labels.chunks(c).map(<[String]>::to_vec).collect();
            spec.col_labels.clear();
        }
        let shape = Shape { rows: r, cols: c, cell, unders: under.map(|u| vec![u.to_string()]).unwrap_or_default() };
        let (fw, fh) = grid::measure(&shape, &spec);
        fw <= slide.0 && fh <= slide.1
    };
    let mut best = Arrangement { rows, cols, cell: (MIN_CELL_W, ((MIN_CELL_W as f32 * aspect).round() as u32).max(1)) };
    let mut best_area = 0u64;
    for (r, c) in options {
        if !fits((r, c), MIN_CELL_W) {
            continue;
        }
        // The largest width that fits: the figure grows with the cell, so bisect.
        let (mut lo, mut hi) = (MIN_CELL_W, slide.0);
        while lo < hi {
            let mid = (lo + hi).div_ceil(2);
            if fits((r, c), mid) { lo = mid } else { hi = mid - 1 }
        }
        let cell = (lo, ((lo as f32 * aspect).round() as u32).max(1));
        let area = u64::from(cell.0) * u64::from(cell.1);
        // Larger cells win; on a tie, fewer rows.
        if area > best_area {
            (best, best_area) = (Arrangement { rows: r, cols: c, cell }, area);
        }
    }
    best
}

/// `image` centred on a `slide`-sized canvas of `background`; unchanged when it is larger.
pub fn on_slide(image: RgbaImage, slide: (u32, u32), background: Rgba<u8>) -> RgbaImage {
    let (w, h) = image.dimensions();
    if w > slide.0 || h > slide.1 {
        return image;
    }
    let mut canvas = RgbaImage::from_pixel(slide.0, slide.1, background);
    image::imageops::replace(&mut canvas, &image, i64::from((slide.0 - w) / 2), i64::from((slide.1 - h) / 2));
    canvas
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(labels: &[&str]) -> GridSpec {
        GridSpec {
            title: Some("A title".into()),
            col_labels: labels.iter().map(|s| s.to_string()).collect(),
            caption: Some("A caption of a few words.".into()),
            scale: text_scale((1920, 1080)),
            wrap_labels: true,
            ..GridSpec::default()
        }
    }

    #[test]
    fn text_is_never_below_the_minimum() {
        assert_eq!(text_scale((1920, 1080)), 1.25);
        assert_eq!(text_scale((3840, 2160)), 2.5);
        // A small slide keeps the smallest text (timings) at the minimum.
        assert!((text_scale((640, 360)) * TIMING_PX - MIN_TEXT_PX).abs() < 1e-4);
    }

    #[test]
    fn a_wide_figure_keeps_its_smallest_text_readable_on_a_slide() {
        // On the figure: at least the minimum.
        assert!((wide_text_scale(800) * TIMING_PX - MIN_TEXT_PX).abs() < 1e-4);
        // Lesson 17's map-size-cost, 2782 px wide, shrunk onto a 1920-px slide.
        let shown = wide_text_scale(2782) * TIMING_PX * 1920.0 / 2782.0;
        assert!((shown - MIN_TEXT_PX).abs() < 1e-3, "{shown}");
    }

    #[test]
    fn eight_square_cells_on_a_wide_slide_use_two_rows_and_fit() {
        let labels = ["1", "2", "3", "4", "5", "6", "7", "8"];
        let a = arrange(1, 8, true, 1.0, (1920, 1080), &spec(&labels), None);
        assert_eq!((a.rows, a.cols), (2, 4), "{a:?}");
        // One row of eight would give cells under 1920/8 = 240 px; two rows give far more.
        assert!(a.cell.0 > 300, "{a:?}");
        let one_row = arrange(1, 8, false, 1.0, (1920, 1080), &spec(&labels), None);
        assert_eq!((one_row.rows, one_row.cols), (1, 8));
        assert!(one_row.cell.0 < 240 && one_row.cell.0 < a.cell.0, "{one_row:?}");
        // The chosen cells fit, and one pixel more would not.
        let mut s = spec(&labels);
        s.cell_labels = s.col_labels.chunks(4).map(<[String]>::to_vec).collect();
        s.col_labels.clear();
        let measure = |w: u32| grid::measure(&Shape { rows: 2, cols: 4, cell: (w, w), unders: vec![] }, &s);
        let (fw, fh) = measure(a.cell.0);
        assert!(fw <= 1920 && fh <= 1080, "{fw}×{fh}");
        let (fw, fh) = measure(a.cell.0 + 1);
        assert!(fw > 1920 || fh > 1080, "{fw}×{fh}");
    }

    #[test]
    fn long_labels_wrap_instead_of_widening_columns() {
        let long = "K_shi = 2.21 with a long explanation that would not fit";
        let s = spec(&[long, long, long]);
        let shape = Shape { rows: 1, cols: 3, cell: (200, 200), unders: vec![] };
        let (wrapped, _) = grid::measure(&shape, &s);
        let (unwrapped, _) = grid::measure(&shape, &GridSpec { wrap_labels: false, ..s.clone() });
        assert!(wrapped < unwrapped, "{wrapped} vs {unwrapped}");
        // Three 200-px columns, two gutters, two margins (at scale 1.25): wrapping keeps the grid narrow.
        assert!(wrapped <= 3 * 200 + 2 * 15 + 2 * 30 + 1, "{wrapped}");
    }

    #[test]
    fn the_canvas_is_the_slide() {
        let img = RgbaImage::from_pixel(100, 50, Rgba([1, 2, 3, 255]));
        let out = on_slide(img.clone(), (300, 200), Rgba([255, 255, 255, 255]));
        assert_eq!(out.dimensions(), (300, 200));
        assert_eq!(*out.get_pixel(100, 75), Rgba([1, 2, 3, 255]));
        assert_eq!(*out.get_pixel(0, 0), Rgba([255, 255, 255, 255]));
        assert_eq!(on_slide(img, (50, 50), Rgba([0, 0, 0, 0])).dimensions(), (100, 50));
    }
}
