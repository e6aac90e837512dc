//! Shared set-up for the integration tests: build a scene's model and run it on the CPU.
#![allow(dead_code)]

pub mod cg_failures;
pub mod same_answers;

use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::prelude::*;
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
    CpuBackend::new(&model.grid_setup()).expect("grid setup is consistent")
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

/// Deterministic pseudo-random values in [−1, 1) (64-bit LCG, top bits).
pub fn pseudo_random(n: usize, seed: u64) -> Vec<f64> {
    let mut x = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

/// The GPU backend for a setup on the best adapter; `None` (test skipped, reason printed)
/// when there is no adapter, unless `JKRBEM_REQUIRE_GPU=1`, which makes that a failure.
#[cfg(feature = "gpu")]
pub fn gpu_backend(setup: &jkrbem::backend::GridSetup) -> Option<jkrbem::backend::gpu::GpuBackend> {
    let ctx = jkrbem::backend::gpu::test_context()?;
    Some(jkrbem::backend::gpu::GpuBackend::new(ctx, setup).expect("GPU backend opens"))
}

/// Run the `jkrbem` binary with `args` in `dir` and wait for it.
pub fn jkrbem(args: &[&str], dir: &std::path::Path) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_jkrbem"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// A process's standard error as text.
pub fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The harness of the GPU test files (`harness = false`): runs `tests` (name, function) with
/// libtest's command line. Where no GPU adapter exists, every test is reported as ignored with
/// the reason, never as passed; with `JKRBEM_REQUIRE_GPU=1` that is a failure instead. Tests
/// named in `slow` are marked ignored unless `--include-ignored` (or `--ignored`) is given.
#[cfg(feature = "gpu")]
pub fn run_gpu_tests(tests: &[(&'static str, fn())], slow: &[&str]) -> ! {
    use libtest_mimic::{Arguments, Trial};
    let args = Arguments::from_args();
    let missing = match jkrbem::backend::gpu::GpuContext::new(Default::default()) {
        Ok(_) => None,
        Err(e) if gpu_required() => {
            panic!("JKRBEM_REQUIRE_GPU=1 but no GPU adapter is usable: {e}")
        }
        Err(e) => {
            let reason = e.to_string();
            eprintln!("no GPU adapter, so these tests are ignored: {reason}");
            Some(
                reason
                    .lines()
                    .next()
                    .unwrap_or("no GPU adapter")
                    .to_string(),
            )
        }
    };
    let trials = tests
        .iter()
        .map(|&(name, f)| {
            let t = Trial::test(name, move || {
                f();
                Ok(())
            });
            match &missing {
                Some(_) => t.with_ignored_flag(true).with_kind("no GPU adapter"),
                None => t.with_ignored_flag(slow.contains(&name)),
            }
        })
        .collect();
    libtest_mimic::run(&args, trials).exit()
}
