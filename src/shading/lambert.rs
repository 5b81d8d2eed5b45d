//! Lambert's cosine law, the course's diffuse term.
//!
//! | parameter | range | meaning |
//! | --- | --- | --- |
//! | `diffuse` K_diff | [0, 1] RGB | fraction of light scattered diffusely |
//!
//! I_diff = max(N·L, 0) K_diff ⊗ L_diff (Lambert 1760; course notation, no π).

/// The Lambert factor max(N·L, 0) for `n_dot_l` = N·L.
#[inline]
pub fn lambert(n_dot_l: f32) -> f32 {
    n_dot_l.max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cosine_law_and_clamp() {
        assert_eq!(lambert(1.0), 1.0);
        assert!((lambert(60f32.to_radians().cos()) - 0.5).abs() < 1e-6);
        assert_eq!(lambert(-0.3), 0.0);
    }
}
