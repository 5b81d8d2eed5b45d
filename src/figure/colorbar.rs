//! The colour bar under a heatmap row: the ramp from 0 to its scale, with the two ends and
//! what the colours measure written under it, so a heatmap can be read without its caption.
//! A value bar (`[[figure]] colorbar`) is the same bar with the cells' own greys and ticks:
//! the key for reading a quantity (irradiance, say) off a render.

use super::text::{self, Align, Paint};
use crate::cost::metrics::heat_colour;
use crate::lesson::figure::ValueBar;
use crate::lesson::settings::Tonemap;
use crate::render::develop::develop_rgba;
use crate::render::{Frame, Layer};
use glam::Vec3;
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
    /// The value of the brightest colour, as written at the bar's right end (`≥ 0.24` when
    /// larger values saturate).
    pub hi: String,
    /// The colours from `lo` to `hi`, evenly spaced; empty for the heatmap's ramp.
    pub ramp: Vec<[u8; 3]>,
    /// Values marked along the bar, at their place (0 to 1), between the two ends.
    pub ticks: Vec<(f32, String)>,
}

impl ColorBar {
    /// A heatmap's bar: its ramp from `lo` to `hi` (written `≥ hi`: the scale saturates), no ticks.
    pub fn heat(label: impl Into<String>, lo: impl Into<String>, hi: impl Into<String>) -> ColorBar {
        ColorBar { label: label.into(), lo: lo.into(), hi: format!("≥ {}", hi.into()), ramp: Vec::new(), ticks: Vec::new() }
    }

    /// The colour at `t` (0 to 1) along the bar.
    fn colour(&self, t: f32) -> [u8; 3] {
        if self.ramp.is_empty() {
            return heat_colour(t);
        }
        let i = (t.clamp(0.0, 1.0) * (self.ramp.len() - 1) as f32).round() as usize;
        self.ramp[i]
    }
}

/// Draws the ramp `w`×`h` with its top-left at (`x`, `y`), and under it `lo` at the left end,
/// `hi` (prefixed `≥`) at the right end and the label centred, in `size` px text. With
/// ticks, each tick is marked on the bar and written under it, and the label goes a line lower.
pub fn draw(img: &mut RgbaImage, bar: &ColorBar, (x, y): (i32, i32), (w, h): (u32, u32), size: f32, ink: Paint) -> Vec<char> {
    let mut put = |px: i32, py: i32, c: [u8; 3]| {
        if px >= 0 && py >= 0 && (px as u32) < img.width() && (py as u32) < img.height() {
            img.put_pixel(px as u32, py as u32, Rgba([c[0], c[1], c[2], 255]));
        }
    };
    for i in 0..w {
        let t = if w > 1 { i as f32 / (w - 1) as f32 } else { 0.0 };
        let c = bar.colour(t);
        for j in 0..h {
            put(x + i as i32, y + j as i32, c);
        }
    }
    // A tick: a thin mark under the bar, in the text's colour.
    let mark = (h as f32 * 0.4).round().max(2.0) as i32;
    let ink_rgb = [ink.color[0], ink.color[1], ink.color[2]];
    let place = |t: f32| x + (t * (w.max(1) - 1) as f32).round() as i32;
    for &(t, _) in &bar.ticks {
        for j in 0..mark {
            put(place(t), y + h as i32 + j, ink_rgb);
        }
    }
    let under = y + h as i32 + (size * 0.25).round() as i32 + if bar.ticks.is_empty() { 0 } else { mark };
    let mut missing = Vec::new();
    missing.extend(text::draw_with(img, x, under, &bar.lo, size, ink, Align::Left).missing);
    missing.extend(text::draw_with(img, x + w as i32, under, &bar.hi, size, ink, Align::Right).missing);
    for (t, label) in &bar.ticks {
        missing.extend(text::draw_with(img, place(*t), under, label, size, ink, Align::Center).missing);
    }
    let label_y = if bar.ticks.is_empty() { under } else { under + text::line_height(size) as i32 };
    missing.extend(text::draw_with(img, x + w as i32 / 2, label_y, &bar.label, size, ink, Align::Center).missing);
    missing
}

/// The height `bar` and its labels take: the ramp, a small gap and one line of text (two,
/// and the tick marks, when it has ticks).
pub fn height(bar: &ColorBar, scale: f32, size: f32) -> u32 {
    let h = (BAR_H_PX * scale).round() as u32 + (size * 0.25).round() as u32 + text::line_height(size);
    if bar.ticks.is_empty() { h } else { h + ((BAR_H_PX * scale).round() * 0.4).round().max(2.0) as u32 + text::line_height(size) }
}

/// The narrowest the bar can be and still show its labels apart. Without ticks the label is
/// centred between the ends, so each half of the bar holds half the label, a gap of one em
/// and the longer end value; with ticks (the label a line lower) every value holds its width
/// and an em, at the spacing of the closest pair.
pub fn min_width(bar: &ColorBar, size: f32) -> u32 {
    let w = |s: &str| text::measure(s, size).0;
    let hi = &bar.hi;
    if bar.ticks.is_empty() {
        return w(&bar.label) + 2 * (w(&bar.lo).max(w(hi)) + size.ceil() as u32);
    }
    let em = size.ceil();
    // Each value with its extent about its place (the ends are aligned inward).
    let mut marks = vec![(0.0, 0.0, w(&bar.lo) as f32)];
    marks.extend(bar.ticks.iter().map(|(t, s)| (*t, w(s) as f32 / 2.0, w(s) as f32 / 2.0)));
    marks.push((1.0, w(hi) as f32, 0.0));
    let mut need = w(&bar.label) as f32;
    for pair in marks.windows(2) {
        let ((t0, _, right), (t1, left, _)) = (pair[0], pair[1]);
        need = need.max((right + left + em) / (t1 - t0).max(1e-3));
    }
    need.ceil() as u32
}

/// The bar of a `colorbar` figure: the greys the cells show for the quantity from 0 up to
/// where the display turns white (or, when that is above twice the cells' largest value, up
/// to that value),
/// developed exactly as the cells are (`layer`, `exposure`, `tonemap`), with round ticks.
/// `largest` is the cells' largest linear value.
pub fn value_bar(bar: &ValueBar, layer: Layer, exposure: f32, tonemap: Tonemap, largest: f32) -> ColorBar {
    let rpu = bar.radiance_per_unit;
    let develop = |values: &[f32]| -> Vec<[u8; 3]> {
        let n = values.len();
        let px: Vec<Vec3> = values.iter().map(|v| Vec3::splat(v * rpu)).collect();
        let frame = Frame { width: n as u32, height: 1, layers: vec![(layer, px)], coverage: vec![1.0; n], background: Vec3::ZERO };
        let rgba = develop_rgba(&frame, layer, exposure, tonemap, false).expect("the layer is kept");
        rgba.chunks(4).map(|c| [c[0], c[1], c[2]]).collect()
    };
    let white = |v: f32| develop(&[v])[0] == [255, 255, 255];
    // The least value shown white, by bisection (a tone map that never whitens has none).
    let white_at = white(1e6 / rpu).then(|| {
        let (mut lo, mut hi) = (0.0f32, 1e6 / rpu);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if white(mid) { hi = mid } else { lo = mid }
        }
        hi
    });
    // Up to white when the cells use at least half of that range; else (a curve that whitens
    // only far above the cells, as Reinhard's) up to the cells' largest value.
    let cells = largest / rpu;
    let (top, saturates) = match white_at {
        Some(w) if cells <= 0.0 || w <= 2.0 * cells => (w, true),
        _ => (cells.max(f32::MIN_POSITIVE), false),
    };
    let ramp = develop(&(0..256).map(|i| top * i as f32 / 255.0).collect::<Vec<_>>());
    let step = nice_step(top / 4.0);
    let ticks = (1..).map(|k| k as f32 * step).take_while(|v| *v < top * 0.88).map(|v| (v / top, number(v, step))).collect();
    let hi = number(top, top / 100.0);
    ColorBar { label: bar.label.clone(), lo: "0".into(), hi: if saturates { format!("≥ {hi}") } else { hi }, ramp, ticks }
}

/// 1, 2 or 5 times a power of ten: the round step nearest above `x`.
fn nice_step(x: f32) -> f32 {
    let p = 10f32.powf(x.max(1e-30).log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * p).find(|s| *s >= x * 0.999).unwrap_or(10.0 * p)
}

/// `v` with as many decimals as `step` needs (`3`, `0.5`, `0.25`).
fn number(v: f32, step: f32) -> String {
    let decimals = (-step.log10().floor()).clamp(0.0, 6.0) as usize;
    format!("{v:.decimals$}")
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
        let bar = ColorBar::heat("|error|", "0", "1.0e-2");
        let with = compose(&cells, &GridSpec { colorbar: Some(bar), ..GridSpec::default() });
        let without = compose(&cells, &GridSpec::default());
        let rows = ramp_rows(&with.image);
        assert_eq!(rows.len() as f32, BAR_H_PX, "the bar is {BAR_H_PX} px tall");
        assert!(rows[0] > 2 * 100, "under both rows of cells");
        assert!(ramp_rows(&without.image).is_empty());
        assert!(with.image.height() >= without.image.height() + height(&ColorBar::heat("|error|", "0", "1.0e-2"), 1.0, 16.0));
        assert!(with.missing_glyphs.is_empty());
    }

    #[test]
    fn the_centred_label_clears_both_end_values() {
        // A long scale value and a long label (the difference row's, at snapshot scale).
        let bar = ColorBar::heat("|difference| from the first cell, total layer", "0", "6.2e-2");
        for size in [8.0, 16.0, 20.0] {
            let w = |s: &str| text::measure(s, size).0 as i32;
            let bar_w = min_width(&bar, size) as i32;
            let (label_left, label_right) = (bar_w / 2 - w(&bar.label) / 2, bar_w / 2 + w(&bar.label) / 2);
            assert!(label_left > w(&bar.lo), "size {size}: the label runs into `0`");
            assert!(label_right < bar_w - w(&bar.hi), "size {size}: the label runs into the scale");
        }
    }

    /// The value the bar gives for a colour: the place of its nearest ramp colour.
    fn read(bar: &ColorBar, top: f32, c: [u8; 3]) -> f32 {
        let d = |a: [u8; 3]| (0..3).map(|k| (a[k] as i32 - c[k] as i32).abs()).sum::<i32>();
        let i = (0..bar.ramp.len()).min_by_key(|&i| d(bar.ramp[i])).expect("a ramp");
        top * i as f32 / (bar.ramp.len() - 1) as f32
    }

    #[test]
    fn lesson_21s_bar_reads_the_irradiance_off_the_floor() {
        use crate::lesson::{self, Override};
        use crate::render::develop::develop;
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/21-radiometry.toml");
        let base = lesson::load(&path, &[Override::parse("camera.size=[64,64]").unwrap()]).unwrap();
        let spec = base.figures.iter().find(|f| f.name == "falloff").expect("the falloff figure");
        let vb = spec.colorbar.as_ref().expect("lesson 21 has a colour bar");
        let s = &base.scene.settings;
        let bar = value_bar(vb, Layer::Total, s.exposure, s.tonemap, 0.0);
        // Clamped: white from 1/(ρ/π) = 3.93 (less half a code); ticks at 1, 2, 3.
        let top = 1.0 / vb.radiance_per_unit;
        assert_eq!(bar.hi, "≥ 3.91");
        let ticks: Vec<&str> = bar.ticks.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(ticks, ["1", "2", "3"]);
        assert_eq!(bar.ramp[255], [255, 255, 255]);
        assert_eq!(bar.ramp[0], [0, 0, 0]);
        // The directional floor (E = 3 everywhere) and the point light's pool (E = 3 under
        // it, E = 3 cos³θ at 45°) read back off the bar.
        let top = 3.91f32.max(top * 0.99);
        for (light, (x, y), want) in [
            ("{ kind = \"directional\", direction = [0.0, -1.0, 0.0], intensity = 3.0 }", (32, 32), 3.0),
            ("{ kind = \"point\", position = [0.0, 1.0, 0.0], intensity = 3.0 }", (32, 32), 3.0),
        ] {
            let sets = [Override::parse("camera.size=[64,64]").unwrap(), Override::parse(&format!("light.0={light}")).unwrap()];
            let l = lesson::load(&path, &sets).unwrap();
            let (frame, _) = crate::render::render_with(&crate::scene::build::build(&l).unwrap(), &[Layer::Total], None);
            let rgb = develop(&frame, Layer::Total, s.exposure, s.tonemap).unwrap();
            let i = 3 * (y * 64 + x) as usize;
            let e = read(&bar, top, [rgb[i], rgb[i + 1], rgb[i + 2]]);
            assert!((e - want).abs() < 0.05, "{light}: read {e}, want {want}");
        }
    }

    #[test]
    fn a_tone_map_that_whitens_far_above_the_cells_ends_the_bar_at_their_largest_value() {
        let vb = ValueBar { label: "E".into(), radiance_per_unit: 0.5 };
        let bar = value_bar(&vb, Layer::Total, 0.0, Tonemap::Reinhard, 2.0);
        // 2 / 0.5 = 4 units, written without `≥`; ticks every unit below it.
        assert_eq!(bar.hi, "4.00");
        assert_eq!(bar.ticks.iter().map(|t| t.1.as_str()).collect::<Vec<_>>(), ["1", "2", "3"]);
        assert!(bar.ramp[255] != [255, 255, 255], "Reinhard is far from white at 2");
        assert!(bar.ramp.windows(2).all(|w| w[0][0] <= w[1][0]), "the greys rise along the bar");
        assert!(min_width(&bar, 16.0) > text::measure("E", 16.0).0);
    }

    #[test]
    fn round_steps() {
        assert_eq!(nice_step(0.98), 1.0);
        assert_eq!(nice_step(1.2), 2.0);
        assert_eq!(nice_step(3.0), 5.0);
        assert!((nice_step(0.03) - 0.05).abs() < 1e-6);
        assert_eq!(number(0.5, 0.5), "0.5");
        assert_eq!(number(3.0, 1.0), "3");
    }
}
