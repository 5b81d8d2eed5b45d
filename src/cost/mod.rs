//! What accuracy costs in time: quality ladders, exact references, error metrics,
//! and timing (the speed benchmark, `crate::bench`, shares the timing).
//!
//! `ladder` names the rungs of each approximation, `reference` ray-casts the exact
//! image, `metrics` compares a frame with it, `measure` runs a whole ladder (time and
//! error per rung), `timing` is the warm-up + median helper they share with [`crate::bench`].

pub mod flip;
pub mod ladder;
pub mod measure;
pub mod metrics;
pub mod radiosity;
pub mod reference;
pub mod rungs;
pub mod timing;

pub use measure::{CostError, CostOptions, LadderReport, ReferenceSource, RungResult, measure};
