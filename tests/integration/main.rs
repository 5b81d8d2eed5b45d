//! The one integration-test binary: runs the real program and the public API.

mod bad_input;
mod budget;
mod cache;
mod cli;
mod cost;
mod docs;
mod environment;
mod figures;
mod fog;
mod fuzz;
mod glass;
mod grain;
mod help;
mod helpers;
mod lang;
mod layers;
mod physical;
mod radiosity;
mod radiosity_reference;
mod reliability;
mod render;
mod shadows;
mod site;
mod snapshots;
mod stability;
mod watch;
