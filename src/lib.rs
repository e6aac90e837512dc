//! jkrbem: FFT-based boundary element solver for JKR-type adhesive contact of a rigid
//! ellipsoid with an elastic half-space, with the Pohrt–Popov mesh-dependent detachment
//! criterion.
//!
//! Data flows one way: [`scene`] → [`model`] → [`solver`] (over a [`backend`]) → states →
//! [`output`]. [`theory`] holds the closed forms the results are checked against,
//! [`analysis`] every number derived from the states (estimates and their uncertainties, fits,
//! contours), [`run`] the session layer that plans, runs and hands results to `output`, and
//! [`bench`](mod@bench) times the backend operations and whole pull-offs (`jkrbem bench`).
//!
//! Cargo features, all on by default: `gpu` (the wgpu backend), `cli` (the `jkrbem` command:
//! clap and indicatif; it takes `figures`) and `figures` (drawing the charts as SVG, PDF and
//! PNG). A library built without `figures` computes every chart's data but draws none:
//! writing a chart fails with [`output::figure::NOT_DRAWN`].

#![warn(missing_docs)]

pub mod analysis;
pub mod backend;
pub mod bench;
pub mod model;
pub mod output;
pub mod plan;
pub mod run;
pub mod scene;
pub mod setup;
pub mod solver;
pub mod text;
pub mod theory;
