//! The one integration-test binary: runs the real program and the public API.

mod bad_input;
mod cli;
mod cost;
mod docs;
mod environment;
mod figures;
mod fuzz;
mod fog;
mod helpers;
mod layers;
mod physical;
mod reliability;
mod render;
mod shadows;
mod snapshots;
mod stability;
