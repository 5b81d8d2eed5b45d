//! Tests of [`super`]: sizes, positions, themes, scale, text.

use super::*;
use crate::figure::text::{line_height, measure};

/// A cell whose every pixel encodes its row, column and position, so a misplaced blit shows.
fn cell(w: u32, h: u32, r: usize, c: usize, time_ms: Option<f64>) -> Cell {
    let image = RgbaImage::from_fn(w, h, |x, y| Rgba([(x % 256) as u8, (y % 256) as u8, (r * 100 + c * 40 + 7) as u8, 255]));
    Cell { image, time_ms, note: None }
}

fn grid(rows: usize, cols: usize, w: u32, h: u32) -> Vec<Vec<Cell>> {
    (0..rows).map(|r| (0..cols).map(|c| cell(w, h, r, c, Some(1.5 + (r * cols + c) as f64 * 10.0))).collect()).collect()
}

fn labelled_spec() -> GridSpec {
    GridSpec {
        title: Some("Shininess".into()),
        caption: Some("Short caption.".into()),
        col_labels: vec!["Flat".into(), "Gouraud".into(), "Phong".into()],
        row_labels: vec!["K_shi = 10".into(), "K_shi = 50".into()],
        show_timings: true,
        ..GridSpec::default()
    }
}

#[test]
fn composed_size_is_the_sum_of_its_parts() {
    let spec = labelled_spec();
    let out = compose(&grid(2, 3, 120, 90), &spec);
    let label_w = measure("K_shi = 10", 20.0).0.max(measure("K_shi = 50", 20.0).0);
    assert!(label_w > 40);
    // margin, label column, gutter, 3 cells with 2 gutters, margin.
    let width = 24 + label_w + 12 + 3 * 120 + 2 * 12 + 24;
    // margin, title + gutter, labels + label gap, 2 × (cell + timing gap + timing), gutter
    // between the rows, gutter + caption, margin.
    let height = 24 + line_height(28.0) + 12 + line_height(20.0) + 6 + 2 * (90 + 3 + line_height(13.0)) + 12 + 12 + line_height(16.0) + 24;
    assert_eq!(out.image.dimensions(), (width, height));
    assert!(out.missing_glyphs.is_empty());
}

#[test]
fn every_cell_is_copied_exactly_at_its_position() {
    let cells = grid(2, 3, 120, 90);
    let out = compose(&cells, &labelled_spec());
    let label_w = measure("K_shi = 10", 20.0).0.max(measure("K_shi = 50", 20.0).0);
    let white = Rgba([255, 255, 255, 255]);
    for (r, row) in cells.iter().enumerate() {
        for (c, cell) in row.iter().enumerate() {
            let x0 = 24 + label_w + 12 + c as u32 * (120 + 12);
            let y0 = 24 + line_height(28.0) + 12 + line_height(20.0) + 6 + r as u32 * (90 + 3 + line_height(13.0) + 12);
            for (x, y) in [(0, 0), (119, 0), (0, 89), (119, 89), (60, 45), (13, 71)] {
                assert_eq!(out.image.get_pixel(x0 + x, y0 + y), cell.image.get_pixel(x, y), "cell {r},{c} at {x},{y}");
            }
            // The gutter to the right of the cell is background.
            assert_eq!(*out.image.get_pixel(x0 + 120 + 6, y0 + 45), white, "gutter after cell {r},{c}");
        }
    }
}

#[test]
fn theme_sets_the_background() {
    let cells = grid(1, 1, 10, 10);
    let at_margin = |theme| *compose(&cells, &GridSpec { theme, ..labelled_spec() }).image.get_pixel(3, 3);
    assert_eq!(at_margin(Theme::Light), Rgba([255, 255, 255, 255]));
    assert_eq!(at_margin(Theme::Transparent)[3], 0);
    let dark = at_margin(Theme::Dark);
    assert!(dark[3] == 255 && dark[0] < 40 && dark[1] < 40 && dark[2] < 40, "{dark:?}");
}

#[test]
fn text_colour_follows_the_theme() {
    let cells = grid(1, 1, 10, 10);
    for (theme, dark_text) in [(Theme::Light, true), (Theme::Dark, false), (Theme::Transparent, true)] {
        let out = compose(&cells, &GridSpec { title: Some("Title".into()), theme, ..GridSpec::default() });
        // The most opaque title pixel carries the ink colour.
        let title_rows = 24..24 + line_height(28.0);
        let ink = out.image.enumerate_pixels().filter(|(_, y, _)| title_rows.contains(y)).map(|(_, _, p)| *p).max_by_key(|p| {
            let contrast = if dark_text { 255 - p[0] as u32 } else { p[0] as u32 };
            contrast * p[3] as u32
        });
        let ink = ink.expect("title drawn");
        assert_eq!(ink[0] < 128, dark_text, "{theme:?}: {ink:?}");
    }
}

#[test]
fn a_single_unlabelled_cell_is_the_cell_plus_margins() {
    let cells = vec![vec![cell(50, 30, 0, 0, Some(3.0))]];
    let out = compose(&cells, &GridSpec::default());
    assert_eq!(out.image.dimensions(), (50 + 48, 30 + 48));
    assert_eq!(out.image.get_pixel(24, 24), cells[0][0].image.get_pixel(0, 0));
    assert_eq!(out.image.get_pixel(73, 53), cells[0][0].image.get_pixel(49, 29));
    assert_eq!(*out.image.get_pixel(23, 24), Rgba([255, 255, 255, 255]));
    assert_eq!(*out.image.get_pixel(74, 54), Rgba([255, 255, 255, 255]));
}

#[test]
fn scale_two_doubles_margins_and_text_but_not_cells() {
    let cells = vec![vec![cell(50, 30, 0, 0, None)]];
    let out = compose(&cells, &GridSpec { scale: 2.0, ..GridSpec::default() });
    assert_eq!(out.image.dimensions(), (50 + 96, 30 + 96));
    assert_eq!(*out.image.get_pixel(47, 47), Rgba([255, 255, 255, 255]));
    assert_eq!(out.image.get_pixel(48, 48), cells[0][0].image.get_pixel(0, 0));

    let labelled = |scale| {
        let spec = GridSpec { row_labels: vec!["Gouraud".into()], scale, ..GridSpec::default() };
        compose(&cells, &spec).image.width()
    };
    assert_eq!(labelled(2.0) - 50, 2 * 24 * 2 + measure("Gouraud", 40.0).0 + 24);
    assert_eq!(labelled(1.0) - 50, 2 * 24 + measure("Gouraud", 20.0).0 + 12);
    // Out-of-range scales are tamed, not obeyed.
    assert_eq!(compose(&cells, &GridSpec { scale: f32::NAN, ..GridSpec::default() }).image.dimensions(), (98, 78));
    assert_eq!(compose(&cells, &GridSpec { scale: -3.0, ..GridSpec::default() }).image.dimensions(), (50 + 12, 30 + 12));
}

#[test]
fn missing_glyphs_are_collected_once() {
    let spec =
        GridSpec { title: Some("한 title".into()), row_labels: vec!["a\u{E000}".into(), "\u{E000}한".into()], ..GridSpec::default() };
    let out = compose(&grid(2, 1, 20, 20), &spec);
    assert_eq!(out.missing_glyphs, ['한', '\u{E000}']);
    assert!(compose(&grid(2, 1, 20, 20), &labelled_spec()).missing_glyphs.is_empty());
}

#[test]
fn wide_text_widens_the_figure_and_the_caption_wraps() {
    let cells = grid(1, 2, 40, 40);
    let narrow = compose(&cells, &GridSpec::default()).image;
    assert_eq!(narrow.width(), 24 + 40 + 12 + 40 + 24);
    // A long title widens the figure; the grid moves to its centre.
    let title = "A title much wider than two small cells";
    let titled = compose(&cells, &GridSpec { title: Some(title.into()), ..GridSpec::default() }).image;
    let title_w = measure(title, 28.0).0;
    assert_eq!(titled.width(), 48 + title_w);
    let x0 = 24 + (title_w - 92) / 2;
    let y0 = 24 + line_height(28.0) + 12;
    assert_eq!(titled.get_pixel(x0, y0), cells[0][0].image.get_pixel(0, 0));
    // A long caption wraps to the width instead of widening.
    let caption = "Gouraud interpolates colours computed at the vertices, so a highlight between vertices is lost";
    let captioned = compose(&cells, &GridSpec { caption: Some(caption.into()), ..GridSpec::default() }).image;
    let content_w = caption.split(' ').map(|w| measure(w, 16.0).0).fold(92, u32::max);
    let lines = text::wrap(caption, 16.0, content_w).len() as u32;
    assert!(lines > 3);
    assert_eq!(captioned.width(), 48 + content_w);
    assert_eq!(captioned.height(), narrow.height() + 12 + lines * line_height(16.0));
}

#[test]
fn columns_widen_for_long_labels_so_nothing_overlaps() {
    let cells = grid(1, 2, 20, 20);
    let spec = GridSpec { col_labels: vec!["Blinn-Phong".into(), "Cook-Torrance".into()], ..GridSpec::default() };
    let out = compose(&cells, &spec);
    let col_w = measure("Cook-Torrance", 20.0).0;
    assert_eq!(out.image.width(), 48 + 2 * col_w + 12);
    // Each cell is centred in its widened column.
    let y0 = 24 + line_height(20.0) + 6;
    assert_eq!(out.image.get_pixel(24 + (col_w - 20) / 2, y0), cells[0][0].image.get_pixel(0, 0));
}

#[test]
fn mismatched_ragged_or_empty_grids_do_not_panic() {
    let cells = vec![vec![cell(40, 30, 0, 0, None), cell(60, 10, 0, 1, None)], vec![cell(40, 30, 1, 0, None)]];
    let out = compose(&cells, &labelled_spec());
    assert!(out.image.width() > 2 * 40);
    // The 60×10 cell is cropped to 40 wide and padded below with background.
    let out = compose(&cells, &GridSpec::default());
    assert_eq!(out.image.dimensions(), (48 + 2 * 40 + 12, 48 + 2 * 30 + 12));
    let (x1, y0) = (24 + 40 + 12, 24);
    assert_eq!(out.image.get_pixel(x1 + 39, y0 + 9), cells[0][1].image.get_pixel(39, 9));
    assert_eq!(*out.image.get_pixel(x1 + 39, y0 + 10), Rgba([255, 255, 255, 255]));
    assert_eq!(*out.image.get_pixel(x1 + 39, y0 + 30 + 12 + 5), Rgba([255, 255, 255, 255]), "the short row's empty slot");

    assert_eq!(compose(&[], &GridSpec::default()).image.dimensions(), (48, 48));
    assert_eq!(compose(&[vec![], vec![]], &labelled_spec()).missing_glyphs, Vec::<char>::new());
}

#[test]
fn composing_is_deterministic() {
    let spec = GridSpec {
        theme: Theme::Transparent,
        col_header: Some("Interpolation".into()),
        row_header: Some("K_shi".into()),
        ..labelled_spec()
    };
    let a = compose(&grid(2, 3, 32, 24), &spec);
    let b = compose(&grid(2, 3, 32, 24), &spec);
    assert_eq!(a.image.as_raw(), b.image.as_raw());
}

#[test]
fn timings_read_with_three_significant_digits() {
    assert_eq!(format_ms(12.34), "12.3 ms");
    assert_eq!(format_ms(1.234), "1.23 ms");
    assert_eq!(format_ms(123.4), "123 ms");
    assert_eq!(format_ms(9.999), "10.0 ms");
    assert_eq!(format_ms(99.97), "100 ms");
    assert_eq!(format_ms(f64::NAN), "n/a");
}
