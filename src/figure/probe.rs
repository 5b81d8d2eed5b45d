//! The probe picture (`explain --pixel ... -o`, figure kind `probe`): the render with each
//! probed point marked and its vectors N, V, L, R and H drawn from it as arrows projected
//! into the image, beside a bar chart of each point's terms per light, with a caption
//! written from the numbers.
//!
//! Arrows are unit vectors drawn with one world length per point (chosen so N's arrow would
//! be a sixth of the image's height if it lay in the image plane), so foreshortening shows:
//! a vector pointing at the camera is short.

use super::grid::{Cell, GridSpec};
use super::overlay::{dot, line};
use super::text::{self, Align, Paint, escape};
use super::{Figure, FigureError, FigureOptions};
use crate::lesson::i18n::Lang;
use crate::lesson::{FigureSpec, Lesson};
use crate::render::develop::develop_rgba;
use crate::render::frame::Layer;
use crate::render::pipeline::RenderStats;
use crate::render::pipeline::render;
use crate::render::pixel::{PixelReport, SurfaceReport};
use crate::render::pixel_text::num;
use crate::scene::Scene;
use glam::{Vec2, Vec3, Vec4};
use image::{Rgba, RgbaImage};

/// The arrows' colours and names, in legend order.
pub const ARROWS: [(&str, &str, [u8; 3]); 5] = [
    ("N", "normal", [255, 255, 255]),
    ("V", "toward the eye", [60, 210, 255]),
    ("L", "toward the light", [255, 210, 40]),
    ("R", "mirror direction of L", [255, 90, 200]),
    ("H", "half vector", [90, 230, 110]),
];

/// The bars' colours: ambient, diffuse, specular, other (emission, reflection, transmission).
const BARS: [[u8; 3]; 4] = [[120, 140, 190], [235, 150, 60], [90, 90, 90], [150, 110, 200]];

/// Text size in pixels: at least 16 (readable on a slide).
const TEXT: f32 = 16.0;

/// The render is enlarged to at least this width, so the arrows have room.
const MIN_WIDTH: u32 = 720;

/// The probe picture of `reports` (made by `explain_pixels` from `scene`).
/// `scale` sizes its text and spacing as a figure's `--scale` does (16 px text at 1).
pub fn probe_image(scene: &Scene, reports: &[PixelReport], lang: Lang, scale: f32) -> Result<RgbaImage, String> {
    let t = TEXT * scale.clamp(0.25, 8.0);
    let cam = &scene.spec.camera;
    let s = &scene.spec.settings;
    let (frame, _) = render(scene, &[Layer::Total]);
    let rgba = develop_rgba(&frame, Layer::Total, s.exposure, s.tonemap, false).ok_or("the total was kept")?;
    let shot = RgbaImage::from_raw(cam.width, cam.height, rgba).ok_or("an image of the camera's size")?;
    // A small render is enlarged by a whole factor (each pixel a k × k block, so no value
    // is invented) until the arrows have room.
    let zoom = (MIN_WIDTH.div_ceil(cam.width.max(1))).clamp(1, 4);
    let mut shot = image::imageops::resize(&shot, cam.width * zoom, cam.height * zoom, image::imageops::FilterType::Nearest);
    let vp = cam.view_projection();
    let (w, h) = ((cam.width * zoom) as f32, (cam.height * zoom) as f32);
    let project = |p: Vec3| -> Option<Vec2> {
        let c: Vec4 = vp * p.extend(1.0);
        (c.w > cam.near).then(|| Vec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h))
    };
    let width = (h / 256.0).clamp(1.5, 3.0);
    // The camera's own up, square to the view: a step along it crosses the image vertically.
    let forward = (cam.look_at - cam.position).normalize_or(Vec3::NEG_Z);
    let up = forward.cross(cam.up).cross(forward).normalize_or(Vec3::Y);
    for (k, r) in reports.iter().enumerate() {
        let centre = Vec2::new(r.pixel.0 as f32 + 0.5, r.pixel.1 as f32 + 0.5) * zoom as f32;
        if let Some(surf) = &r.surface {
            // World length of an arrow: a sixth of the image height, measured across the view.
            let p = surf.position;
            let scale = project(p + up * 1e-2).zip(project(p)).map_or(0.0, |(a, b)| (a - b).length() / 1e-2);
            let len = if scale > 0.0 { h / 6.0 / scale } else { 0.0 };
            for (name, dir, colour) in arrows(surf) {
                if let Some(tip) = project(p + dir * len) {
                    arrow(&mut shot, centre, tip, width, colour);
                    label(&mut shot, tip + (tip - centre).normalize_or_zero() * 10.0, &name, colour, t);
                }
            }
        }
        ring(&mut shot, centre, 6.0, width);
        label(&mut shot, centre + Vec2::new(-12.0, -14.0), &format!("{}", k + 1), [255, 255, 255], t);
    }
    Ok(compose(shot, reports, lang, t))
}

/// The arrows of one point: N, V, every light's L (numbered when there are several), and R
/// and H of the light whose specular term is largest.
fn arrows(s: &SurfaceReport) -> Vec<(String, Vec3, [u8; 3])> {
    let colour = |i: usize| ARROWS[i].2;
    let mut out = vec![("N".to_string(), s.n, colour(0)), ("V".to_string(), s.v, colour(1))];
    // The lights that reach the point's side (N·L > 0), shadowed or not.
    let lit: Vec<_> = s.lights.iter().filter(|l| l.l != Vec3::ZERO && l.n_dot_l > 0.0).collect();
    for l in &lit {
        let name = if lit.len() > 1 { format!("L{}", l.index) } else { "L".into() };
        out.push((name, l.l, colour(2)));
    }
    let luminance = |v: Vec3| luma(v);
    let brightest = lit.iter().max_by(|a, b| luminance(a.terms.specular).total_cmp(&luminance(b.terms.specular)));
    if let Some(l) = brightest.filter(|l| luminance(l.terms.specular) > 0.0) {
        out.push(("R".into(), l.r, colour(3)));
        out.push(("H".into(), l.h, colour(4)));
    }
    out
}

/// Relative luminance of a linear colour (Rec. 709 weights, ITU-R BT.709-6).
fn luma(v: Vec3) -> f32 {
    v.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// A segment from `a` to `b` with a head at `b`.
fn arrow(img: &mut RgbaImage, a: Vec2, b: Vec2, width: f32, colour: [u8; 3]) {
    let d = b - a;
    let len = d.length();
    // A dark outline first, so a white arrow shows on a white highlight.
    for (w, c) in [(width + 2.0, [20, 20, 20]), (width, colour)] {
        line(img, a, b, w, c);
        if len > 4.0 {
            let u = d / len;
            let side = Vec2::new(-u.y, u.x);
            let head = (len * 0.3).min(10.0);
            line(img, b, b - u * head + side * head * 0.5, w, c);
            line(img, b, b - u * head - side * head * 0.5, w, c);
        }
    }
}

/// A ring marking a probed pixel.
fn ring(img: &mut RgbaImage, c: Vec2, r: f32, width: f32) {
    for (w, colour) in [(width + 2.0, [20, 20, 20]), (width, [255, 255, 255])] {
        let steps = 32;
        for i in 0..steps {
            let t0 = i as f32 / steps as f32 * std::f32::consts::TAU;
            let t1 = (i + 1) as f32 / steps as f32 * std::f32::consts::TAU;
            line(img, c + Vec2::new(t0.cos(), t0.sin()) * r, c + Vec2::new(t1.cos(), t1.sin()) * r, w, colour);
        }
    }
    dot(img, c, 1.0, [255, 255, 255]);
}

/// A short label centred at `at`, with a dark halo.
fn label(img: &mut RgbaImage, at: Vec2, s: &str, colour: [u8; 3], t: f32) {
    let paint = Paint { color: [colour[0], colour[1], colour[2], 255], halo: Some([0, 0, 0, 230]) };
    text::draw_with(img, at.x as i32, at.y as i32 - (t * 0.6) as i32, &escape(s), t, paint, Align::Center);
}

/// One bar of the chart: its label, value (luminance) and colour.
struct Bar {
    label: String,
    value: f32,
    colour: [u8; 3],
}

/// The bars of one probed point: each light's ambient, diffuse and specular, then the
/// global ambient, emission, reflection and transmission where they are not zero.
fn bars(s: &SurfaceReport, lang: Lang) -> Vec<Bar> {
    let tr = |t: &'static str| lang.tr(t).to_string();
    let mut out = Vec::new();
    if s.radiosity.is_some() {
        out.push(Bar { label: tr("radiosity B"), value: luma(s.recomputed.total()), colour: BARS[1] });
        return out;
    }
    for l in &s.lights {
        // A light that faces the point but is blocked keeps its (zero) bars: the shadow is the point.
        let shadowed = l.n_dot_l > 0.0 && l.visibility < 1.0;
        for (name, v, c) in
            [("ambient", l.terms.ambient, BARS[0]), ("diffuse", l.terms.diffuse, BARS[1]), ("specular", l.terms.specular, BARS[2])]
        {
            if v != Vec3::ZERO || (shadowed && name == "diffuse") {
                let mut label = format!("{} {} {}", tr("light"), l.index, tr(name));
                if shadowed {
                    label = format!("{label} (V = {})", num(l.visibility));
                }
                out.push(Bar { label, value: luma(v), colour: c });
            }
        }
    }
    for (name, v, c) in [
        ("global ambient", s.global_ambient, BARS[0]),
        ("emission", s.emission, BARS[3]),
        ("reflection", s.recomputed.reflection, BARS[3]),
        ("transmission", s.recomputed.transmission, BARS[3]),
    ] {
        if v != Vec3::ZERO {
            out.push(Bar { label: tr(name), value: luma(v), colour: c });
        }
    }
    out
}

/// The render on the left with its legend below; the bar charts on the right; the caption under both.
fn compose(shot: RgbaImage, reports: &[PixelReport], lang: Lang, t: f32) -> RgbaImage {
    // Spacing in units of the text size.
    let em = |x: f32| (x * t / TEXT).round() as i32;
    let tr = |t: &'static str| lang.tr(t);
    let line_h = text::line_height(t) as i32;
    let pad = em(16.0);
    let chart_w = em(440.0);
    let blocks: Vec<(String, Vec<Bar>)> = reports
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let head = match &r.surface {
                Some(s) => format!("{} ({}, {}): \"{}\"", k + 1, r.pixel.0, r.pixel.1, s.material),
                None => format!("{} ({}, {}): {}", k + 1, r.pixel.0, r.pixel.1, tr("background")),
            };
            (head, r.surface.as_ref().map_or_else(Vec::new, |s| bars(s, lang)))
        })
        .collect();
    let chart_h: i32 = blocks.iter().map(|(_, b)| (b.len() as i32 + 2) * line_h).sum::<i32>() + line_h;
    let legend_h = line_h * ARROWS.len() as i32;
    let captions = caption_lines(reports, lang);
    let left_w = shot.width() as i32;
    let body_h = (shot.height() as i32 + pad + legend_h).max(chart_h);
    let caption_w = (left_w + pad + chart_w) as u32;
    let wrapped: Vec<String> = captions.iter().flat_map(|c| text::wrap(&escape(c), t, caption_w)).collect();
    let total_w = (pad * 3 + left_w + chart_w) as u32;
    let total_h = (pad * 3 + body_h + line_h * wrapped.len() as i32) as u32;
    let mut img = RgbaImage::from_pixel(total_w, total_h, Rgba([255, 255, 255, 255]));
    image::imageops::overlay(&mut img, &shot, pad as i64, pad as i64);
    let ink = [30, 30, 30, 255];
    // The legend: each arrow's colour and name.
    let mut y = pad * 2 + shot.height() as i32;
    for (sym, name, colour) in ARROWS {
        let c = Vec2::new((pad + em(10.0)) as f32, (y + line_h / 2) as f32);
        let half = Vec2::new(em(8.0) as f32, 0.0);
        line(&mut img, c - half, c + half, 5.0, [20, 20, 20]);
        line(&mut img, c - half, c + half, 3.0, colour);
        text::draw(&mut img, pad + em(26.0), y, &escape(&format!("{sym}: {}", tr(name))), t, ink, Align::Left);
        y += line_h;
    }
    // The charts: one block per probed point, bars on one scale for every block.
    let x0 = pad * 2 + left_w;
    let label_w = em(230.0);
    let bar_w = chart_w - label_w - em(70.0);
    let max = blocks.iter().flat_map(|(_, b)| b.iter().map(|b| b.value)).fold(0f32, f32::max).max(1e-12);
    let mut y = pad;
    text::draw(&mut img, x0, y, &escape(tr("terms as relative luminance Y (linear)")), t, ink, Align::Left);
    y += line_h;
    for (head, bars) in &blocks {
        y += line_h / 2;
        text::draw(&mut img, x0, y, &escape(head), t, ink, Align::Left);
        y += line_h;
        for b in bars {
            text::draw(&mut img, x0 + label_w - em(8.0), y, &escape(&b.label), t, ink, Align::Right);
            let len = (b.value.max(0.0) / max * bar_w as f32).round() as u32;
            let (bx, by) = (x0 + label_w, y + line_h / 5);
            for yy in by..by + line_h * 3 / 5 {
                for xx in bx..bx + len as i32 {
                    if xx >= 0 && yy >= 0 && (xx as u32) < img.width() && (yy as u32) < img.height() {
                        img.put_pixel(xx as u32, yy as u32, Rgba([b.colour[0], b.colour[1], b.colour[2], 255]));
                    }
                }
            }
            text::draw(&mut img, bx + len as i32 + em(6.0), y, &num(b.value), t, ink, Align::Left);
            y += line_h;
        }
    }
    let mut y = pad * 2 + body_h;
    for l in &wrapped {
        text::draw(&mut img, pad, y, l, t, ink, Align::Left);
        y += line_h;
    }
    img
}

/// One sentence per probed point, from its numbers: the total, its largest term and the
/// cosines that decided it.
pub fn caption_lines(reports: &[PixelReport], lang: Lang) -> Vec<String> {
    reports
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let Some(s) = &r.surface else {
                return lang.say(&format!("{}: the background; nothing is shaded there.", k + 1));
            };
            let total = luma(s.recomputed.total());
            let mut parts: Vec<(String, f32, usize)> = Vec::new();
            for l in &s.lights {
                parts.push((format!("light {} diffuse", l.index), luma(l.terms.diffuse), l.index));
                parts.push((format!("light {} specular", l.index), luma(l.terms.specular), l.index));
            }
            let ambient = luma(s.global_ambient) + s.lights.iter().map(|l| luma(l.terms.ambient)).sum::<f32>();
            parts.push(("ambient".into(), ambient, usize::MAX));
            parts.push(("reflection".into(), luma(s.recomputed.reflection), usize::MAX));
            parts.push(("transmission".into(), luma(s.recomputed.transmission), usize::MAX));
            parts.push(("emission".into(), luma(s.emission), usize::MAX));
            let (name, value, light) = parts.into_iter().max_by(|a, b| a.1.total_cmp(&b.1)).unwrap_or(("ambient".into(), 0.0, usize::MAX));
            let share = if total > 0.0 { value / total * 100.0 } else { 0.0 };
            // Each fragment is said on its own, so a translation can order its holes.
            let mut fragments = vec![
                lang.say(&format!("{}: Y = {} at \"{}\"", k + 1, num(total), s.material)),
                lang.say(&format!("the largest term is {} ({share:.0}%)", lang.say(&name))),
            ];
            if let Some(l) = s.lights.iter().find(|l| l.index == light) {
                fragments.push(lang.say(&format!("with N·L = {}", num(l.n_dot_l))));
                if name.ends_with("specular") {
                    fragments.push(match l.brdf.and_then(|b| b.dgf) {
                        Some((d, g, f)) => format!("D = {}, G = {}, F = {}", num(d), num(g), num(luma(f))),
                        None => format!("R·V = {}, N·H = {}", num(l.r_dot_v), num(l.n_dot_h)),
                    });
                }
            }
            let dark: Vec<String> = s
                .lights
                .iter()
                .filter(|l| l.visibility < 1.0)
                .map(|l| lang.say(&format!("light {} visibility {}", l.index, num(l.visibility))))
                .collect();
            if !dark.is_empty() {
                fragments.push(lang.say(&format!("shadowed: {}", dark.join(", "))));
            }
            if !s.vertices.is_empty() {
                let values: Vec<String> = s.vertices.iter().map(|v| num(luma(v.total))).collect();
                let weights: Vec<String> = s.vertices.iter().map(|v| num(v.weight)).collect();
                fragments.push(lang.say(&format!(
                    "Gouraud: the vertices' values (Y {}) weighted {}",
                    values.join(", "),
                    weights.join(", ")
                )));
            }
            fragments.join("; ") + "."
        })
        .collect()
}

/// A `probe` figure: the lesson's render with the pixels explained (`explain --pixel -o`).
/// With `cols`, one panel per value of the varied key, side by side.
pub(super) fn probe_figure(
    base: &Lesson,
    spec: &FigureSpec,
    pixels: &[(u32, u32)],
    cols: Option<&crate::lesson::figure::Axis>,
    opts: &FigureOptions,
) -> Result<Figure, FigureError> {
    let at = || format!("{}: figure `{}`", base.path.display(), spec.name);
    let (lessons, labels) = match cols {
        Some(cols) => {
            let g = super::variants::expand(base, super::variants::Layout::Row(cols), &[])?;
            (g.variants.into_iter().map(|v| v.lesson).collect(), g.col_labels)
        }
        None => (vec![base.clone()], Vec::new()),
    };
    let mut cells = Vec::with_capacity(lessons.len());
    for lesson in &lessons {
        let scene = super::build(lesson)?;
        crate::render::budget::check(&scene).map_err(|e| e.at(at()))?;
        if let Some(why) = crate::render::pixel::unexplained(&scene) {
            return Err(FigureError::Chart(format!("{}: {why}", at())));
        }
        let reports = crate::render::pixel::explain_pixels(&scene, pixels).map_err(|e| FigureError::Chart(format!("{}: {e}", at())))?;
        cells.push(Cell::new(probe_image(&scene, &reports, base.lang, opts.scale).map_err(FigureError::Chart)?));
    }
    let title = spec.title.clone().unwrap_or_else(|| base.lang.tr("One pixel, explained").to_string());
    let spec_grid = GridSpec {
        title: Some(title),
        caption: spec.caption.clone(),
        col_labels: labels,
        theme: opts.theme,
        scale: opts.scale,
        ..GridSpec::default()
    };
    let composed = super::grid::compose(&[cells], &spec_grid);
    Ok(Figure {
        image: composed.image,
        stats: RenderStats::default(),
        rasterizations: lessons.len(),
        cached: 0,
        missing_glyphs: composed.missing_glyphs,
        kept: false,
    })
}
