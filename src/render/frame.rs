//! The HDR frame: one linear layer per term of the illumination equation.

pub use crate::shading::components::Layer;
use glam::Vec3;

/// A rendered frame in linear radiance, before exposure and tone mapping.
///
/// Only the layers asked for are kept: a plain render keeps `Total` (12 bytes a pixel);
/// a split keeps every term of the same render, so it costs no extra rasterization.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The kept layers: per pixel, the term averaged over its samples (uncovered samples count as zero).
    pub layers: Vec<(Layer, Vec<Vec3>)>,
    /// Per pixel, the covered share of its samples (0..=1).
    pub coverage: Vec<f32>,
    /// Linear background shown where coverage < 1.
    pub background: Vec3,
}

impl Frame {
    /// One kept layer as rendered (not composited), or `None` when it was not kept.
    pub fn raw(&self, layer: Layer) -> Option<&[Vec3]> {
        self.layers.iter().find(|(l, _)| *l == layer).map(|(_, px)| px.as_slice())
    }

    /// One kept layer composited over the background, or `None` when it was not kept.
    pub fn layer(&self, layer: Layer) -> Option<Vec<Vec3>> {
        let px = self.raw(layer)?;
        Some(px.iter().zip(&self.coverage).map(|(c, a)| over(*c, *a, self.background)).collect())
    }

    /// One kept layer at pixel (x, y) over the background.
    ///
    /// # Panics
    /// When the layer was not kept or (x, y) is outside the frame.
    pub fn at(&self, layer: Layer, x: u32, y: u32) -> Vec3 {
        let i = (y * self.width + x) as usize;
        over(self.raw(layer).expect("layer was rendered")[i], self.coverage[i], self.background)
    }
}

/// A pixel with coverage `a` (its value already weighted by `a`) over the background.
#[inline]
pub fn over(c: Vec3, a: f32, background: Vec3) -> Vec3 {
    c + background * (1.0 - a)
}
