//! Shared set-up for the integration tests: build a scene's model and run it on the CPU.
#![allow(dead_code)]

use jkrbem::backend::cpu::{CpuBackend, GridSetup};
use jkrbem::backend::Backend;
use jkrbem::model::{Model, ModelOptions};
use jkrbem::scene::Scene;
use jkrbem::solver::{self, Outcome};

/// A finished run: the model, its outcome and the contact mask at the end.
pub struct Run {
    pub model: Model,
    pub outcome: Outcome,
    pub final_mask: Vec<bool>,
}

/// The CPU backend for a model.
pub fn cpu_backend(model: &Model) -> CpuBackend {
    CpuBackend::new(&GridSetup::for_model(model)).expect("grid setup is consistent")
}

/// The model of R1/R2 = `ratio` (R2 = E* = Δγ = 1).
pub fn model_for(ratio: f64, options: ModelOptions) -> Model {
    let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).unwrap();
    Model::build(&scene, &options).unwrap()
}

/// Run the pull-off of R1/R2 = `ratio` (R2 = E* = Δγ = 1) on the CPU.
pub fn run_ratio(ratio: f64, options: ModelOptions) -> Run {
    run_model(model_for(ratio, options))
}

/// Run a model's protocol on the CPU.
pub fn run_model(model: Model) -> Run {
    let mut backend = cpu_backend(&model);
    let outcome = solver::run(&mut backend, &model, &mut |_| {});
    let mut final_mask = vec![false; model.nx * model.ny];
    backend.contact(&mut final_mask).unwrap();
    Run {
        model,
        outcome,
        final_mask,
    }
}

/// Skip-or-fail rule for tests that need a GPU adapter.
pub fn gpu_required() -> bool {
    std::env::var("JKRBEM_REQUIRE_GPU").is_ok_and(|v| v == "1")
}
