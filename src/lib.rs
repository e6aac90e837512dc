//! jkrbem: FFT-based boundary element solver for JKR-type adhesive contact of a rigid
//! ellipsoid with an elastic half-space, with the Pohrt–Popov mesh-dependent detachment
//! criterion.
//!
//! [`params`] is the ground floor: every parameter's name, range, unit and words, which
//! every room reads and which reads none of them. Data flows one way: [`scene`] → [`model`] →
//! [`solver`] (over a [`backend`]) → states → [`analysis`] → [`output`]. [`theory`] holds the
//! closed forms the results are checked against, [`analysis`] every number derived from the
//! states (estimates and their uncertainties, fits, contours), [`plan`] the grids and the
//! memory a request needs, [`session`] the typed request and its run (one pull-off, a scene
//! to an accuracy, a batch of scenes) handed to `output`, [`studies`] what is built on
//! sessions (sweeps, the study, references and coverage, timings), and [`bench`](mod@bench)
//! times the backend operations and whole pull-offs (`jkrbem bench`). Each room imports only
//! rooms below it.
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
pub mod params;
pub mod plan;
pub mod scene;
pub mod session;
pub mod setup;
pub mod solver;
pub mod studies;
pub mod text;
pub mod theory;
