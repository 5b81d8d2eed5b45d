//! Shading: pure functions of unit vectors, testable without a scene.
//!
//! Conventions (docs/conventions.md): `n` is the unit surface normal, `l` the unit
//! vector towards the light, `v` the unit vector towards the viewer; all point away
//! from the surface. The classic models follow the course's illumination equation
//! exactly (no π, coefficients in [0, 1]):
//!
//! I_tot = L_glob⊗K_amb + L_emi + Σ_k C_spot^k { I_amb^k + d^k (I_diff^k + I_spec^k) }

pub mod blinn_phong;
pub mod brdf;
pub mod classic;
pub mod components;
pub mod cook_torrance;
pub mod diffuse;
pub mod glass;
pub mod incident;
pub mod lambert;
pub mod lobe;
#[cfg(test)]
mod lobe_tests;
pub mod material;
pub mod metals;
pub mod microfacet;
pub mod mirror;
pub mod normalized_phong;
pub mod oren_nayar;
pub mod phong;
pub mod physical;
pub mod principled;
pub mod principled_transmission;
pub mod rough_dielectric;
#[cfg(test)]
mod sampling_tests;
pub mod shade;

pub use classic::shade_classic;
pub use components::Components;
