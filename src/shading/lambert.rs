//! Lambert's cosine law, the course's diffuse term.
//!
//! | parameter | range | meaning |
//! | --- | --- | --- |
//! | `diffuse` K_diff | [0, 1] RGB | fraction of light scattered diffusely |
//!
//! I_diff = max(N·L, 0) K_diff ⊗ L_diff (Lambert 1760; course notation, no π). The renderer
//! evaluates it in [`shade_classic_lanes`](super::classic::shade_classic_lanes), only where
//! N·L > 0; the test here checks that term.

#[cfg(test)]
mod tests {
    use crate::shading::classic::{EvalCounts, shade_classic};
    use crate::shading::incident::directional;
    use crate::shading::material::{Classic, ClassicModel, Material, Model};
    use glam::Vec3;

    /// I_diff of a Lambert material (K_diff = 0.8) under a unit directional light `deg`
    /// degrees from the normal, as the renderer shades it.
    fn i_diff(deg: f32) -> Vec3 {
        let c =
            Classic { model: ClassicModel::Lambert, diffuse: Vec3::splat(0.8), specular: Vec3::ZERO, shininess: 0.0, clamp_n_dot_l: true };
        let m = Material { name: "m".into(), model: Model::Classic(c), ambient: Vec3::ZERO, emission: Vec3::ZERO };
        let (s, c_) = deg.to_radians().sin_cos();
        let l = Vec3::new(s, 0.0, c_);
        let mut k = EvalCounts::default();
        shade_classic(&m, &c, [directional(l, Vec3::ONE, Vec3::ZERO)], Vec3::ZERO, Vec3::Z, Vec3::Z, &mut k).diffuse
    }

    #[test]
    fn cosine_law_and_clamp() {
        assert_eq!(i_diff(0.0), Vec3::splat(0.8));
        assert!((i_diff(60.0) - Vec3::splat(0.4)).abs().max_element() < 1e-6);
        // Behind the surface (N·L < 0): clamped to zero, not negative.
        assert_eq!(i_diff(120.0), Vec3::ZERO);
    }
}
