//! Render settings from the `[render]` table: interpolation, vertex normals, supersampling,
//! exposure, tone map and culling.

/// How lighting is interpolated across a triangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Lighting once per face, at its centroid, with the face normal.
    Flat,
    /// Lighting at the vertices, colours interpolated.
    Gouraud,
    /// Normals interpolated and renormalized, lighting per sample.
    #[default]
    Phong,
}

/// Tone-mapping operator applied after exposure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tonemap {
    /// Clamp to [0, 1].
    #[default]
    Clamp,
    /// x / (1 + x) (Reinhard et al. 2002, eq. 3).
    Reinhard,
    /// Narkowicz 2015 fit of the ACES filmic curve.
    Aces,
}

/// Which triangles are discarded by facing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Cull {
    /// Discard triangles facing away from the camera.
    #[default]
    Back,
    /// Keep all; back faces are lit with the flipped normal (two-sided).
    None,
}

/// Everything `[render]` sets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Flat, Gouraud or Phong.
    pub interpolation: Interpolation,
    /// Vertex-normal weighting.
    pub normals: NormalWeighting,
    /// Supersamples per pixel side (aa² samples per pixel).
    pub aa: u32,
    /// Exposure in stops: radiance × 2^exposure before tone mapping.
    pub exposure: f32,
    /// Tone map.
    pub tonemap: Tonemap,
    /// Face culling.
    pub cull: Cull,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            interpolation: Interpolation::Phong,
            normals: NormalWeighting::Average,
            aa: 1,
            exposure: 0.0,
            tonemap: Tonemap::Clamp,
            cull: Cull::Back,
        }
    }
}

/// How a vertex normal weights the normals of the faces around it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NormalWeighting {
    /// Plain average of adjacent unit face normals (the course's definition).
    #[default]
    Average,
    /// Weighted by face area (the unnormalized cross product).
    Area,
    /// Weighted by the face's interior angle at the vertex (Thürmer & Wüthrich 1998).
    Angle,
}
