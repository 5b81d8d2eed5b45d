//! Figures for slides: equal-size cells in a grid, with a title, column and row labels, per-cell
//! timings and a caption.
//!
//! Top to bottom: margin; the title, centred on the figure; the column header, centred over the
//! cells; one line holding the row header (right-aligned over the row labels) and the column
//! labels (centred over their columns); the rows of cells, each with its label to the left
//! (right-aligned, vertically centred) and, when timings are shown, "12.3 ms" under each cell
//! (followed by the cell's note, if it has one);
//! the caption, wrapped to the figure width; margin. A part with no text takes no space.
//!
//! Sizes are in pixels at `scale` 1 and all multiply by it, except the cells: the caller renders
//! those at the size it wants. A column is as wide as its cell or, if wider, its label; a title or
//! caption word wider than the grid widens the figure and the grid is centred. Nothing is ever
//! clipped, and the output is deterministic (see [`super::text`]).

use super::text::{self, Align, Paint, blend_over};
use image::{Rgba, RgbaImage};

/// Title size in pixels (em) at scale 1.
const TITLE_PX: f32 = 28.0;
/// Column header, column labels, row header and row labels.
const LABEL_PX: f32 = 20.0;
/// Caption.
const CAPTION_PX: f32 = 16.0;
/// Per-cell timings: the smallest text of a figure.
pub(super) const TIMING_PX: f32 = 13.0;
/// Around the whole figure.
const MARGIN_PX: f32 = 24.0;
/// Between cells, between the row labels and the cells, and around the title and caption blocks.
const GUTTER_PX: f32 = 12.0;
/// Between a label line and the cells it names: tighter than a gutter so the label reads as theirs.
const LABEL_GAP_PX: f32 = 6.0;
/// Between a cell and its timing.
const TIMING_GAP_PX: f32 = 3.0;
/// Scales outside this range are clamped: below it text is unreadable, above it images get huge.
const SCALE_RANGE: (f32, f32) = (0.25, 8.0);

/// Background and text colours of a figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Theme {
    /// White background, near-black text: light slides and print.
    #[default]
    Light,
    /// Near-black background, light text: dark slides.
    Dark,
    /// Transparent background, dark text with a white halo so it reads on any slide colour.
    Transparent,
}

impl Theme {
    /// The figure background.
    pub fn background(self) -> Rgba<u8> {
        match self {
            Theme::Light => Rgba([255, 255, 255, 255]),
            Theme::Dark => Rgba([18, 18, 20, 255]),
            // White, not black, under zero alpha: viewers that filter without premultiplying
            // then fringe edges towards white, which the halo already is.
            Theme::Transparent => Rgba([255, 255, 255, 0]),
        }
    }

    /// Titles and labels.
    fn ink(self) -> Paint {
        match self {
            Theme::Light => Paint { color: [20, 20, 20, 255], halo: None },
            Theme::Dark => Paint { color: [236, 236, 236, 255], halo: None },
            Theme::Transparent => Paint { color: [20, 20, 20, 255], halo: Some([255, 255, 255, 230]) },
        }
    }

    /// Timings: present but quieter than the labels.
    fn muted(self) -> Paint {
        match self {
            Theme::Light => Paint { color: [100, 100, 100, 255], halo: None },
            Theme::Dark => Paint { color: [160, 160, 160, 255], halo: None },
            Theme::Transparent => Paint { color: [80, 80, 80, 255], halo: Some([255, 255, 255, 230]) },
        }
    }
}

/// One rendered variant and how long it took.
#[derive(Debug, Clone)]
pub struct Cell {
    /// The rendered image; every cell of a grid should have the same size.
    pub image: RgbaImage,
    /// Render time in milliseconds, shown under the cell when [`GridSpec::show_timings`] is set.
    pub time_ms: Option<f64>,
    /// A short line always shown under the cell (after the timing, if both are shown).
    pub note: Option<String>,
}

impl Cell {
    /// A cell with an image and nothing under it.
    pub fn new(image: RgbaImage) -> Cell {
        Cell { image, time_ms: None, note: None }
    }

    /// The line under the cell, if any: the timing (when shown), then the note.
    fn under(&self, show_timings: bool) -> Option<String> {
        let time = self.time_ms.filter(|_| show_timings).map(format_ms);
        match (time, self.note.as_deref().filter(|n| !n.is_empty())) {
            (Some(t), Some(n)) => Some(format!("{t} · {n}")),
            (Some(t), None) => Some(t),
            (None, Some(n)) => Some(n.to_string()),
            (None, None) => None,
        }
    }
}

/// The text and look of a figure. All text uses the markup of [`super::text`] (`K_shi`, `r^2`).
#[derive(Debug, Clone)]
pub struct GridSpec {
    /// Large, centred on top.
    pub title: Option<String>,
    /// Wrapped to the figure width under the grid.
    pub caption: Option<String>,
    /// Names what varies across the columns; centred over the cells.
    pub col_header: Option<String>,
    /// One per column, centred over it; missing or empty labels leave the column unlabelled.
    pub col_labels: Vec<String>,
    /// Names what varies down the rows; above the row labels, right-aligned like them.
    pub row_header: Option<String>,
    /// One per row, left of it.
    pub row_labels: Vec<String>,
    /// Colours.
    pub theme: Theme,
    /// Multiplies every font size, margin and gutter (2 for high-DPI slides); cells are not scaled.
    /// Clamped to [0.25, 8]; a non-finite value counts as 1.
    pub scale: f32,
    /// Show each cell's `time_ms` under it.
    pub show_timings: bool,
    /// A colour bar under the cells, for figures whose rows include heatmaps.
    pub colorbar: Option<super::colorbar::ColorBar>,
    /// Wrap column labels to the cell width instead of widening the column (slides).
    pub wrap_labels: bool,
    /// One label per cell, on a line above each row: a one-row figure reflowed into several
    /// rows. Replaces `col_labels` when not empty.
    pub cell_labels: Vec<Vec<String>>,
}

impl Default for GridSpec {
    fn default() -> Self {
        GridSpec {
            title: None,
            caption: None,
            col_header: None,
            col_labels: Vec::new(),
            row_header: None,
            row_labels: Vec::new(),
            theme: Theme::Light,
            scale: 1.0,
            show_timings: false,
            colorbar: None,
            wrap_labels: false,
            cell_labels: Vec::new(),
        }
    }
}

/// A finished figure.
#[derive(Debug, Clone)]
pub struct Composed {
    /// The figure, straight-alpha sRGB.
    pub image: RgbaImage,
    /// Characters in the figure's text that the font lacks (drawn as boxes), each once.
    pub missing_glyphs: Vec<char>,
}

/// Composes `cells[row][col]` into a labelled figure.
///
/// Precondition: all cells have the size of the first one. A cell of another size is cropped to
/// it or padded with the background; a short row leaves its last slots empty. Never panics.
pub fn compose(cells: &[Vec<Cell>], spec: &GridSpec) -> Composed {
    let l = plan(&Shape::of(cells, spec.show_timings), spec);
    let theme = spec.theme;
    let mut img = RgbaImage::from_pixel(l.width, l.height, theme.background());
    let mut missing: Vec<char> = Vec::new();
    let mut label = |img: &mut RgbaImage, x: i32, y: i32, s: &str, size: f32, paint: Paint, align: Align| {
        for c in text::draw_with(img, x, y, s, size, paint, align).missing {
            if !missing.contains(&c) {
                missing.push(c);
            }
        }
    };
    let (ink, muted) = (theme.ink(), theme.muted());
    let center_x = (l.width / 2) as i32;

    if let Some((y, title)) = l.title {
        label(&mut img, center_x, y, title, l.sizes.title, ink, Align::Center);
    }
    if let Some((y, header)) = l.col_header {
        label(&mut img, l.cells_center_x, y, header, l.sizes.label, ink, Align::Center);
    }
    if let Some(y) = l.header_line_y {
        if let Some(header) = nonempty(&spec.row_header) {
            label(&mut img, l.label_right_x, y, header, l.sizes.label, ink, Align::Right);
        }
        for (c, &x) in l.col_x.iter().enumerate() {
            let s = spec.col_labels.get(c).map_or("", String::as_str);
            for (i, line) in l.label_lines(s).iter().enumerate() {
                let y = y + (i as u32 * l.sizes.label_h) as i32;
                label(&mut img, x + (l.col_w / 2) as i32, y, line, l.sizes.label, ink, Align::Center);
            }
        }
    }
    for (r, &y) in l.cell_label_y.iter().enumerate() {
        for (c, &x) in l.col_x.iter().enumerate() {
            let s = spec.cell_labels.get(r).and_then(|row| row.get(c)).map_or("", String::as_str);
            for (i, line) in l.label_lines(s).iter().enumerate() {
                let y = y + (i as u32 * l.sizes.label_h) as i32;
                label(&mut img, x + (l.col_w / 2) as i32, y, line, l.sizes.label, ink, Align::Center);
            }
        }
    }
    for (r, &row_y) in l.row_y.iter().enumerate() {
        if let Some(s) = spec.row_labels.get(r) {
            let y = row_y + (l.row_h as i32 - l.sizes.label_h as i32) / 2;
            label(&mut img, l.label_right_x, y, s, l.sizes.label, ink, Align::Right);
        }
        for (c, cell) in cells[r].iter().enumerate() {
            let (x, y) = l.cell_origin(r, c);
            blit(&mut img, &cell.image, x, y, l.cell);
            if l.timings
                && let Some(t) = cell.under(spec.show_timings)
            {
                let below = row_y + l.row_h as i32 + l.sizes.timing_gap as i32;
                label(&mut img, x + (l.cell.0 / 2) as i32, below, &t, l.sizes.timing, muted, Align::Center);
            }
        }
    }
    for (i, line) in l.caption.iter().enumerate() {
        let y = l.caption_y + (i as u32 * l.sizes.caption_h) as i32;
        label(&mut img, center_x, y, line, l.sizes.caption, ink, Align::Center);
    }
    if let (Some(bar), Some((at, size))) = (&spec.colorbar, l.colorbar) {
        for c in super::colorbar::draw(&mut img, bar, at, size, l.sizes.caption, ink) {
            if !missing.contains(&c) {
                missing.push(c);
            }
        }
    }
    Composed { image: img, missing_glyphs: missing }
}

/// Font sizes (em px) and spacings (px) at one scale, with the line heights they imply.
struct Sizes {
    scale: f32,
    title: f32,
    label: f32,
    caption: f32,
    timing: f32,
    margin: u32,
    gutter: u32,
    label_gap: u32,
    timing_gap: u32,
    title_h: u32,
    label_h: u32,
    caption_h: u32,
    timing_h: u32,
}

impl Sizes {
    fn new(scale: f32) -> Sizes {
        let s = if scale.is_finite() { scale.clamp(SCALE_RANGE.0, SCALE_RANGE.1) } else { 1.0 };
        let px = |base: f32| (base * s).round() as u32;
        let (title, label, caption, timing) = (TITLE_PX * s, LABEL_PX * s, CAPTION_PX * s, TIMING_PX * s);
        Sizes {
            scale: s,
            title,
            label,
            caption,
            timing,
            margin: px(MARGIN_PX),
            gutter: px(GUTTER_PX),
            label_gap: px(LABEL_GAP_PX),
            timing_gap: px(TIMING_GAP_PX),
            title_h: text::line_height(title),
            label_h: text::line_height(label),
            caption_h: text::line_height(caption),
            timing_h: text::line_height(timing),
        }
    }
}

/// Where everything goes, computed before anything is drawn.
struct Layout<'a> {
    sizes: Sizes,
    width: u32,
    height: u32,
    /// The size every cell is drawn at.
    cell: (u32, u32),
    /// Left edge of each column slot, `col_w` wide; the cell is centred in it.
    col_x: Vec<i32>,
    col_w: u32,
    /// Top of each row, `row_h` tall; the cell is centred in it.
    row_y: Vec<i32>,
    row_h: u32,
    /// Right edge of the row-label column (row labels and the row header are right-aligned to it).
    label_right_x: i32,
    cells_center_x: i32,
    /// Line tops.
    title: Option<(i32, &'a str)>,
    col_header: Option<(i32, &'a str)>,
    header_line_y: Option<i32>,
    /// Top of each row's own label line (`cell_labels`).
    cell_label_y: Vec<i32>,
    /// Wrap labels to this width, if set.
    wrap_w: Option<u32>,
    timings: bool,
    /// The colour bar's top-left corner and size.
    colorbar: Option<((i32, i32), (u32, u32))>,
    caption: Vec<String>,
    caption_y: i32,
}

impl Layout<'_> {
    /// A column label's lines: wrapped to the cell width when asked, else one line.
    fn label_lines(&self, s: &str) -> Vec<String> {
        label_lines(s, self.sizes.label, self.wrap_w)
    }

    /// Top-left pixel of cell (`r`, `c`).
    fn cell_origin(&self, r: usize, c: usize) -> (i32, i32) {
        (self.col_x[c] + (self.col_w - self.cell.0) as i32 / 2, self.row_y[r] + (self.row_h - self.cell.1) as i32 / 2)
    }
}

fn label_lines(s: &str, size: f32, wrap_w: Option<u32>) -> Vec<String> {
    match wrap_w {
        Some(w) if !s.is_empty() => text::wrap(s, size, w),
        _ => vec![s.to_string()],
    }
}

fn nonempty(s: &Option<String>) -> Option<&str> {
    s.as_deref().filter(|s| !s.is_empty())
}

/// What the layout needs of the cells: their count, size and the lines under them.
#[derive(Debug, Clone)]
pub struct Shape {
    /// Rows.
    pub rows: usize,
    /// Columns (of the longest row).
    pub cols: usize,
    /// The size of every cell.
    pub cell: (u32, u32),
    /// The line under each cell that has one (timing and note).
    pub unders: Vec<String>,
}

impl Shape {
    fn of(cells: &[Vec<Cell>], show_timings: bool) -> Shape {
        Shape {
            rows: cells.len(),
            cols: cells.iter().map(Vec::len).max().unwrap_or(0),
            cell: cells.iter().flatten().next().map_or((0, 0), |c| c.image.dimensions()),
            unders: cells.iter().flatten().filter_map(|c| c.under(show_timings)).collect(),
        }
    }
}

/// The size [`compose`] would give cells of `shape` under `spec`, without drawing.
pub fn measure(shape: &Shape, spec: &GridSpec) -> (u32, u32) {
    let l = plan(shape, spec);
    (l.width, l.height)
}

fn plan<'a>(shape: &Shape, spec: &'a GridSpec) -> Layout<'a> {
    let z = Sizes::new(spec.scale);
    let (rows, cols, cell) = (shape.rows, shape.cols, shape.cell);
    let width_of = |s: &str, size: f32| text::measure(s, size).0;

    let title = nonempty(&spec.title);
    let col_header = nonempty(&spec.col_header);
    let row_header = nonempty(&spec.row_header);
    let per_row = !spec.cell_labels.is_empty();
    let col_labels = if per_row { &[][..] } else { &spec.col_labels[..spec.col_labels.len().min(cols)] };
    let row_labels = &spec.row_labels[..spec.row_labels.len().min(rows)];
    let header_line = row_header.is_some() || col_labels.iter().any(|l| !l.is_empty());
    let wrap_w = spec.wrap_labels.then_some(cell.0);
    let lines = |s: &str| label_lines(s, z.label, wrap_w);
    let all_labels = || col_labels.iter().chain(spec.cell_labels.iter().flatten());
    // Label lines a header needs: the most any of its labels wraps to.
    let depth = |labels: &mut dyn Iterator<Item = &String>| labels.map(|s| lines(s).len() as u32).max().unwrap_or(0).max(1);
    let timings = !shape.unders.is_empty();

    // Widths: the row-label column, then columns wide enough for their cell, label and timing.
    let label_col_w = row_labels.iter().map(String::as_str).chain(row_header).map(|s| width_of(s, z.label)).max().unwrap_or(0);
    let label_span = if label_col_w > 0 { label_col_w + z.gutter } else { 0 };
    let widest_col_label = all_labels().flat_map(|s| lines(s)).map(|s| width_of(&s, z.label)).max().unwrap_or(0);
    let timing_widths = shape.unders.iter().map(|t| width_of(t, z.timing));
    let widest_timing = if timings { timing_widths.max().unwrap_or(0) } else { 0 };
    let col_w = cell.0.max(widest_col_label).max(widest_timing);
    let cells_w = cols as u32 * col_w + (cols as u32).saturating_sub(1) * z.gutter;
    let grid_w = label_span + cells_w;

    // The column header is centred on the cells and may overhang the grid on either side.
    let header_w = col_header.map_or(0, |s| width_of(s, z.label)) as i32;
    let header_left = label_span as i32 + (cells_w as i32 - header_w) / 2;
    let block_left = header_left.min(0);
    let block_w = (header_left + header_w).max(grid_w as i32) - block_left;
    let title_w = title.map_or(0, |s| width_of(s, z.title));
    // Wrapping to zero width puts each word alone on a line: the widest is the narrowest the caption can go.
    let caption_word_w =
        nonempty(&spec.caption).map_or(0, |s| text::wrap(s, z.caption, 0).iter().map(|w| width_of(w, z.caption)).max().unwrap_or(0));
    let content_w = (block_w as u32).max(title_w).max(caption_word_w);
    let width = 2 * z.margin + content_w;
    let grid_x = z.margin as i32 + (content_w as i32 - block_w) / 2 - block_left;

    // Heights, top to bottom.
    let mut y = z.margin as i32;
    let title = title.map(|s| {
        let top = y;
        y += (z.title_h + z.gutter) as i32;
        (top, s)
    });
    let col_header = col_header.map(|s| {
        let top = y;
        y += (z.label_h + z.label_gap) as i32;
        (top, s)
    });
    let header_line_y = header_line.then(|| {
        let top = y;
        y += (depth(&mut col_labels.iter()) * z.label_h + z.label_gap) as i32;
        top
    });
    // A row is as tall as its cell, or its label when cells are tiny.
    let row_h = if label_col_w > 0 { cell.1.max(z.label_h) } else { cell.1 };
    let mut row_y = Vec::with_capacity(rows);
    let mut cell_label_y = Vec::new();
    for r in 0..rows {
        if r > 0 {
            y += z.gutter as i32;
        }
        if let Some(labels) = spec.cell_labels.get(r) {
            cell_label_y.push(y);
            y += (depth(&mut labels.iter()) * z.label_h + z.label_gap) as i32;
        }
        row_y.push(y);
        y += row_h as i32;
        if timings {
            y += (z.timing_gap + z.timing_h) as i32;
        }
    }
    let colorbar = spec.colorbar.as_ref().map(|bar| {
        y += z.gutter as i32;
        let w = ((super::colorbar::BAR_W_PX * z.scale).round() as u32).max(super::colorbar::min_width(bar, z.caption)).min(content_w);
        let top = (grid_x + label_span as i32 + cells_w as i32 / 2 - w as i32 / 2, y);
        y += super::colorbar::height(bar, z.scale, z.caption) as i32;
        (top, (w, (super::colorbar::BAR_H_PX * z.scale).round() as u32))
    });
    let caption = nonempty(&spec.caption).map_or(Vec::new(), |s| text::wrap(s, z.caption, content_w));
    if !caption.is_empty() {
        y += z.gutter as i32;
    }
    let caption_y = y;
    y += (caption.len() as u32 * z.caption_h) as i32 + z.margin as i32;

    Layout {
        width,
        height: y as u32,
        cell,
        col_x: (0..cols).map(|c| grid_x + (label_span + c as u32 * (col_w + z.gutter)) as i32).collect(),
        col_w,
        row_y,
        row_h,
        label_right_x: grid_x + label_col_w as i32,
        cells_center_x: grid_x + label_span as i32 + cells_w as i32 / 2,
        title,
        col_header,
        header_line_y,
        cell_label_y,
        wrap_w,
        timings,
        colorbar,
        caption,
        caption_y,
        sizes: z,
    }
}

/// Composites `src`, cropped to `size`, over `dst` at (`x`, `y`); opaque pixels are copied exactly.
fn blit(dst: &mut RgbaImage, src: &RgbaImage, x: i32, y: i32, size: (u32, u32)) {
    for sy in 0..src.height().min(size.1) {
        for sx in 0..src.width().min(size.0) {
            let (dx, dy) = (x + sx as i32, y + sy as i32);
            if dx >= 0 && dy >= 0 && (dx as u32) < dst.width() && (dy as u32) < dst.height() {
                blend_over(dst.get_pixel_mut(dx as u32, dy as u32), src.get_pixel(sx, sy).0, 1.0);
            }
        }
    }
}

/// A render time with three significant digits, in ms throughout so cells compare at a glance:
/// `1.23 ms`, `12.3 ms`, `123 ms`.
pub fn format_ms(t: f64) -> String {
    match t {
        t if !t.is_finite() || t < 0.0 => "n/a".to_string(),
        t if t >= 99.95 => format!("{t:.0} ms"),
        t if t >= 9.995 => format!("{t:.1} ms"),
        t => format!("{t:.2} ms"),
    }
}

#[cfg(test)]
#[path = "grid_tests.rs"]
mod tests;
