//! What accuracy costs in time: timing helpers and the speed benchmark.

pub mod bench;
pub mod ladder;
pub mod metrics;
pub mod reference;
pub mod timing;
