//! An ambient light: no direction, only the ambient term I_amb = K_amb ⊗ L_amb of the
//! course's equation. Never shadowed.

use crate::shading::incident::Incident;
use crate::simd::lanes::Lanes;

/// An ambient light's incident: ambient only.
#[inline(always)]
pub fn incident<F: Lanes>(unlit: Incident<F>) -> Incident<F> {
    Incident { ambient_only: true, ..unlit }
}
