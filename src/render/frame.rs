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

    /// The frame as bytes for the cache: exact (every `f32` bit kept), little-endian.
    pub fn to_bytes(&self) -> Vec<u8> {
        let n = self.coverage.len();
        let mut b = Vec::with_capacity(32 + n * 4 * (1 + 3 * self.layers.len()));
        b.extend(self.width.to_le_bytes());
        b.extend(self.height.to_le_bytes());
        crate::cache::put_f32s(&mut b, self.background.to_array());
        b.push(self.layers.len() as u8);
        for (layer, px) in &self.layers {
            b.push(Layer::ALL.iter().position(|l| l == layer).expect("a layer of ALL") as u8);
            crate::cache::put_f32s(&mut b, px.iter().flat_map(|p| p.to_array()));
        }
        crate::cache::put_f32s(&mut b, self.coverage.iter().copied());
        b
    }

    /// A frame from [`Frame::to_bytes`], or `None` when the bytes are not one.
    pub fn from_bytes(b: &[u8]) -> Option<Frame> {
        let mut r = crate::cache::Reader::new(b);
        let (width, height) = (r.u32()?, r.u32()?);
        let n = usize::try_from(u64::from(width) * u64::from(height)).ok()?;
        let background = r.vec3s(1)?[0];
        let count = r.u8()? as usize;
        let mut layers = Vec::with_capacity(count);
        for _ in 0..count {
            let layer = *Layer::ALL.get(r.u8()? as usize)?;
            layers.push((layer, r.vec3s(n)?));
        }
        let coverage = r.f32s(n)?;
        r.is_done().then_some(Frame { width, height, layers, coverage, background })
    }
}

/// A pixel with coverage `a` (its value already weighted by `a`) over the background.
#[inline]
pub fn over(c: Vec3, a: f32, background: Vec3) -> Vec3 {
    c + background * (1.0 - a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_survives_bytes_bit_for_bit_and_damaged_bytes_are_refused() {
        let px = |k: f32| (0..6).map(|i| Vec3::new(i as f32 * k, f32::MIN_POSITIVE, -0.0)).collect::<Vec<_>>();
        let f = Frame {
            width: 3,
            height: 2,
            layers: vec![(Layer::Diffuse, px(0.1)), (Layer::Normal, px(1e30))],
            coverage: vec![1.0, 0.5, 0.0, 0.25, 1.0, 0.75],
            background: Vec3::new(0.2, 0.3, 0.4),
        };
        let b = f.to_bytes();
        let g = Frame::from_bytes(&b).expect("decodes");
        assert_eq!(g, f);
        assert!(g.layers[0].1.iter().zip(&f.layers[0].1).all(|(a, b)| a.z.to_bits() == b.z.to_bits()));
        assert_eq!(Frame::from_bytes(&b[..b.len() - 1]), None);
        assert_eq!(Frame::from_bytes(&[b.as_slice(), &[0]].concat()), None);
        let mut bad = b.clone();
        bad[21] = 200; // no such layer
        assert_eq!(Frame::from_bytes(&bad), None);
    }
}
