//! The physics tests: the solver's answers against theory (Hertz, JKR, ellipsoids), the mesh,
//! the convergence analysis and the committed reference table, and the commands that compute
//! them (`sweep`, `reproduce`, `reference`, `coverage`). One test binary; each former file is a
//! module. Slow tests are `#[ignore]`d (`cargo test --release -- --ignored`) or named `slow_…`
//! (skipped by `cargo fast`).

#[path = "../common/mod.rs"]
mod common;

mod analysis;
mod coverage;
mod ellipsoid;
mod fields;
mod generic_limit;
mod hertz;
mod in_memory;
mod indenters;
mod jkr_sphere;
mod johnson_wave;
mod loading;
mod mesh_angle;
mod pulloff_answers;
mod pulloff_cost;
// The commands' tests run the binary, which is built with the `cli` feature only (so are the
// tests of `coverage` that run it).
#[cfg(feature = "cli")]
mod reference;
#[cfg(feature = "cli")]
mod reproduce;
#[cfg(feature = "cli")]
mod sweep;
