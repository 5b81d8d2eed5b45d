//! Grain on plain lit floor at the shipped sample counts: the figures of the area-light,
//! light-shape and radiosity lessons render smooth where nothing shadows the light.
//!
//! The measure is the issue's: the mean |difference| between neighbouring pixels (right and
//! down, every channel, in 8-bit codes) over plain lit floor. A noise-free image has some
//! too (the floor's own shading gradient), so the test subtracts the same measure of a
//! reference rendered with 8 times the samples: what is left is grain. "Plain lit" pixels
//! are those whose reference with shadows equals the reference without, all round them (no
//! shadow or penumbra in their 3 × 3 neighbourhood), and that see the floor object.

use shadelab::lesson::{self, Override};
use shadelab::render::{Layer, render_image};
use shadelab::scene::build::build;
use std::path::Path;

/// A figure cell: a bundled lesson with the cell's overrides, at `size`².
struct Cell {
    lesson: &'static str,
    sets: &'static [&'static str],
    /// The floor's object index.
    floor: usize,
}

/// The 8-bit image of `cell` with `extra` overrides.
fn image(cell: &Cell, size: u32, extra: &[String]) -> (Vec<u8>, u32) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons").join(cell.lesson);
    let mut sets: Vec<Override> = cell.sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    sets.push(Override::parse(&format!("camera.size=[{size}, {size}]")).unwrap());
    sets.extend(extra.iter().map(|s| Override::parse(s).unwrap()));
    let lesson = lesson::load(&path, &sets).unwrap_or_else(|e| panic!("{e}"));
    let scene = build(&lesson).unwrap();
    let s = &scene.spec.settings;
    (render_image(&scene, Layer::Total, s.exposure, s.tonemap).0, size)
}

/// The floor pixels: where the floor object alone, rendered white on black, covers the pixel.
fn floor_mask(cell: &Cell, size: u32) -> Vec<bool> {
    let (img, _) = image(
        cell,
        size,
        &[
            format!("object.{}.material=\"mask_white\"", cell.floor),
            "material.mask_white={ model = \"lambert\", diffuse = 0, emission = 1 }".into(),
            "scene.ambient=0".into(),
            "render.shadows=\"none\"".into(),
        ],
    );
    img.chunks(3).map(|p| p[0] == 255 && p[1] == 255 && p[2] == 255).collect()
}

/// Mean |Δ| to the right and down neighbours over the pixels `keep` marks (codes).
fn neighbour_difference(img: &[u8], size: u32, keep: &[bool]) -> f64 {
    let (n, at) = (size as usize, |x: usize, y: usize, c: usize| img[(y * size as usize + x) * 3 + c] as f64);
    let (mut sum, mut count) = (0.0, 0u64);
    for y in 0..n - 1 {
        for x in 0..n - 1 {
            if !keep[y * n + x] {
                continue;
            }
            for c in 0..3 {
                sum += (at(x, y, c) - at(x + 1, y, c)).abs() + (at(x, y, c) - at(x, y + 1, c)).abs();
            }
            count += 6;
        }
    }
    assert!(count > 600, "too few plain lit floor pixels ({})", count / 6);
    sum / count as f64
}

/// (grain at the shipped samples, the reference's own neighbour difference, the pixels measured).
fn grain(cell: &Cell, samples: u32, size: u32) -> (f64, f64, usize) {
    let more = [format!("light.0.samples={}", samples * 8)];
    let (shipped, _) = image(cell, size, &[]);
    let (reference, _) = image(cell, size, &more);
    let (unshadowed, _) = image(cell, size, &[more[0].clone(), "render.shadows=\"none\"".into()]);
    let floor = floor_mask(cell, size);
    let n = size as usize;
    let lit: Vec<bool> =
        reference.chunks(3).zip(unshadowed.chunks(3)).map(|(a, b)| a.iter().zip(b).all(|(x, y)| x.abs_diff(*y) <= 1)).collect();
    // Plain lit floor: floor and unshadowed all round (no penumbra in the 3 × 3 neighbourhood).
    let keep: Vec<bool> = (0..n * n)
        .map(|i| {
            let (x, y) = (i % n, i / n);
            x > 0
                && y > 0
                && x + 2 < n
                && y + 2 < n
                && (0..9).all(|k| {
                    let j = (y + k / 3 - 1) * n + x + k % 3 - 1;
                    lit[j] && floor[j]
                })
        })
        .collect();
    let pixels = keep.iter().filter(|k| **k).count();
    (neighbour_difference(&shipped, size, &keep), neighbour_difference(&reference, size, &keep), pixels)
}

/// The cells the issue names: lesson 16's rect light, lesson 18's 3 × 3 panel, lesson 19's
/// tube along x on the floor and its disk, lesson 27's direct-light cell. Grain (the measure
/// less the reference's) at most 0.3 codes; measured −0.003 to 0.017 at 128² (with independent
/// samples placed by area, as a white-noise baseline, lesson 16's cell alone gives 1.03).
#[test]
fn plain_lit_floor_is_smooth_at_the_shipped_sample_counts() {
    const RECT: &str =
        "light.0={ kind = \"rect\", position = [1.0, 4.0, 0.5], direction = [0.0, -1.0, 0.0], size = [1.5, 1.5], intensity = 7.11 }";
    const BIG: &str =
        "light.0={ kind = \"rect\", position = [1.0, 4.0, 0.5], direction = [0.0, -1.0, 0.0], size = [3.0, 3.0], intensity = 1.78 }";
    const TUBE: &str = "light.0={ kind = \"line\", start = [-1.5, 3.0, 0.3], end = [1.5, 3.0, 0.3], radius = 0.05, intensity = 30.0 }";
    let cells: [(Cell, u32); 4] = [
        (Cell { lesson: "16-shadows.toml", sets: &[RECT], floor: 1 }, 16),
        (Cell { lesson: "18-area-lights.toml", sets: &[BIG], floor: 1 }, 16),
        (Cell { lesson: "19-light-shapes.toml", sets: &[TUBE], floor: 1 }, 16),
        (
            Cell {
                lesson: "27-radiosity.toml",
                sets: &[
                    "light=[{ kind = \"rect\", position = [0.0, 1.999, 0.0], direction = [0.0, -1.0, 0.0], size = [0.5, 0.5], intensity = 17.0, samples = 16 }, { kind = \"ambient\", color = 0.1 }]",
                    "render.method=\"raster\"",
                ],
                floor: 0,
            },
            16,
        ),
    ];
    let mut report = Vec::new();
    for (cell, samples) in &cells {
        let (measured, reference, pixels) = grain(cell, *samples, 128);
        report.push(format!("{}: {measured:.3} − {reference:.3} = {:.3} codes over {pixels} pixels", cell.lesson, measured - reference));
        assert!(
            measured - reference <= 0.3,
            "{}: grain {:.3} codes (measure {measured:.3}, reference {reference:.3})",
            cell.lesson,
            measured - reference
        );
    }
    eprintln!("{}", report.join("\n"));
}
