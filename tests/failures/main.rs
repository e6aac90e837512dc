//! Failures provoked on purpose (README, "Failure modes"): too coarse a grid, too large load
//! steps, a detachment loop that does not settle, a turned mesh, the periodic backend's
//! wrap-around. Each test checks that jkrbem detects the failure and says so. One test binary;
//! each former file is a module.

#[path = "../common/mod.rs"]
mod common;

mod failure_mesh;
mod failure_periodic;
mod failures;
