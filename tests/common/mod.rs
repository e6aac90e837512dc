//! Shared set-up for the integration tests: build a scene's model and run it on the CPU.
#![allow(dead_code)]

pub mod cg_failures;
pub mod same_answers;
pub mod sweep_rows;

use jkrbem::backend::cpu::CpuBackend;
use jkrbem::model::{Model, ModelOptions};
use jkrbem::scene::Scene;
use jkrbem::solver::{self, Outcome};

/// A finished run: the model, its outcome and the contact mask of its last state.
pub struct Run {
    pub model: Model,
    pub outcome: Outcome,
    pub final_mask: Vec<bool>,
}

/// The CPU backend for a model.
pub fn cpu_backend(model: &Model) -> CpuBackend {
    CpuBackend::new(&model.grid_setup()).expect("grid setup is consistent")
}

/// A grid of `nx` × `ny` elements of side `dx` (length) on a half-space of contact modulus
/// `e_star` (force/length²), with a flat profile and no preconditioner: the backends'
/// convolution alone.
pub fn flat_setup(nx: usize, ny: usize, dx: f64, e_star: f64) -> jkrbem::backend::GridSetup {
    jkrbem::backend::GridSetup {
        nx,
        ny,
        dx,
        e_star,
        profile: vec![0.0; nx * ny],
        preconditioner: jkrbem::backend::Preconditioner::None,
    }
}

/// The model of R1/R2 = `ratio` (R2 = E* = Δγ = 1).
pub fn model_for(ratio: f64, options: ModelOptions) -> Model {
    let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).unwrap();
    Model::build(&scene, &options).unwrap()
}

/// A rough sphere (R = 1, E* = Δγ = 1): the generator's roughness of rms slope `slope` (Hurst
/// 0.8, cut-off 0.2) added to the sphere.
pub fn rough_sphere(slope: f64, seed: u64) -> Scene {
    use jkrbem::scene::roughness::{generate, RoughnessParams};
    use jkrbem::scene::{Indenter, RoughShape};
    let params = RoughnessParams {
        cutoff: Some(0.2),
        seed,
        ..RoughnessParams::with_rms_slope(256, 0.025, 0.8, slope)
    };
    let map = generate(&params).expect("roughness");
    let base = Indenter::ellipsoid(1.0, 1.0);
    let rough = RoughShape::new(base, map, "generated").unwrap();
    Scene::with_indenter(Indenter::Rough(std::sync::Arc::new(rough)), 1.0, 1.0).unwrap()
}

/// Run the pull-off of R1/R2 = `ratio` (R2 = E* = Δγ = 1) on the CPU.
pub fn run_ratio(ratio: f64, options: ModelOptions) -> Run {
    run_model(model_for(ratio, options))
}

/// Run a model's protocol on the CPU.
pub fn run_model(model: Model) -> Run {
    let mut backend = cpu_backend(&model);
    let mut final_mask = vec![false; model.nx * model.ny];
    let outcome = solver::run_with_contact(&mut backend, &model, &mut |_, mask| {
        final_mask.copy_from_slice(mask);
    });
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

/// Run the `jkrbem` binary with `args` in `dir` and wait for it. The binary is built with
/// the `cli` feature only: so is every test that runs it.
#[cfg(feature = "cli")]
pub fn jkrbem(args: &[&str], dir: &std::path::Path) -> std::process::Output {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_jkrbem"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs");
    worded(&o);
    o
}

/// Check that the binary worded every parameter it names as a flag: no library marker
/// (`⟨name⟩`) reaches a user.
pub fn worded(o: &std::process::Output) {
    for text in [&o.stdout, &o.stderr] {
        let text = String::from_utf8_lossy(text);
        assert!(!text.contains('⟨'), "a parameter left unworded:\n{text}");
    }
}

/// A one-grid run of a few seconds or less (32², 20 steps, CPU): a sphere whose 16 elements
/// across the contact draw a too-coarse warning.
pub const SHORT: &[&str] = &[
    "simulate",
    "--ratio",
    "1",
    "--grid",
    "32",
    "--steps",
    "20",
    "--backend",
    "cpu",
];

/// A run's standard output, as text.
pub fn stdout(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The binary as a command, the memory limit of the caller's environment removed (the `cli`
/// feature's, as [`jkrbem`]).
#[cfg(feature = "cli")]
pub fn bin() -> std::process::Command {
    let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_jkrbem"));
    c.env_remove("JKRBEM_MEMORY_LIMIT");
    c
}

/// Run the binary ([`bin`]) in `dir` with `args` and the environment variables `env`; its
/// output as it came, with no check of its wording (see [`run_in`]).
#[cfg(feature = "cli")]
pub fn output_in(
    dir: &std::path::Path,
    args: &[&str],
    env: &[(&str, &str)],
) -> std::process::Output {
    let mut c = bin();
    c.args(args).current_dir(dir);
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("the binary runs")
}

/// Run the binary in `dir` with `args` and the environment variables `env`, the memory
/// limit of the caller's environment removed, and check that it worded every parameter it
/// names ([`worded`]).
#[cfg(feature = "cli")]
pub fn run_in(dir: &std::path::Path, args: &[&str], env: &[(&str, &str)]) -> std::process::Output {
    let o = output_in(dir, args, env);
    worded(&o);
    o
}

/// Files in `dir` whose name matches `pred`.
pub fn names_in(dir: &std::path::Path, pred: impl Fn(&str) -> bool) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| pred(n))
        .collect()
}

/// Wait until `f` holds (polling), at most `limit`.
pub fn wait_for(limit: std::time::Duration, mut f: impl FnMut() -> bool) -> bool {
    let start = std::time::Instant::now();
    while start.elapsed() < limit {
        if f() {
            return true;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    false
}

/// The sphere h = (x² + y²)/2 + `offset` on `n` × `n` nodes `spacing` apart, centred on the
/// map's middle (heights in the spacing's unit), as a text grid for `--height-map`.
pub fn sphere_map_text(n: usize, spacing: f64, offset: f64) -> String {
    let c = (n - 1) as f64 / 2.0;
    let mut text = String::new();
    for j in 0..n {
        let y = (j as f64 - c) * spacing;
        let row: Vec<String> = (0..n)
            .map(|i| {
                let x = (i as f64 - c) * spacing;
                format!("{:e}", 0.5 * (x * x + y * y) + offset)
            })
            .collect();
        text += &row.join(" ");
        text.push('\n');
    }
    text
}

/// A process's standard error as text.
pub fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Whether the GPU tests can run: `None` where a GPU adapter is usable, else the reason (the
/// tests are then reported as ignored with it, never as passed); with `JKRBEM_REQUIRE_GPU=1` a
/// missing adapter is a failure instead. Asked once, by `tests/gpu/main.rs`.
#[cfg(feature = "gpu")]
pub fn gpu_missing() -> Option<String> {
    match jkrbem::backend::gpu::GpuContext::new(Default::default()) {
        Ok(_) => None,
        Err(e) if gpu_required() => {
            panic!("JKRBEM_REQUIRE_GPU=1 but no GPU adapter is usable: {e}")
        }
        Err(e) => {
            let reason = e.to_string();
            eprintln!("no GPU adapter, so the GPU tests and checks are ignored: {reason}");
            Some(
                reason
                    .lines()
                    .next()
                    .unwrap_or("no GPU adapter")
                    .to_string(),
            )
        }
    }
}

/// Held for reading by every test of `tests/gpu/` (libtest-mimic runs them on parallel threads
/// of one process), and for writing by those that measure the process itself (its resident
/// memory), so that no other test runs beside them.
pub static PROCESS: std::sync::RwLock<()> = std::sync::RwLock::new(());

/// Runs `f` holding [`PROCESS`]: alone (`true`) or beside the other tests.
pub fn in_process<T>(alone: bool, f: impl FnOnce() -> T) -> T {
    if alone {
        let _guard = PROCESS.write().unwrap_or_else(|e| e.into_inner());
        f()
    } else {
        let _guard = PROCESS.read().unwrap_or_else(|e| e.into_inner());
        f()
    }
}

/// The trials of one former GPU test file (`harness = false`, libtest-mimic), named
/// `<module>::<test>`. With `missing` (no GPU adapter, see [`gpu_missing`]) every test is
/// reported as ignored with the reason, never as passed. Tests named in `slow` are marked
/// ignored unless `--include-ignored` (or `--ignored`) is given; those named in `alone` run with
/// no other test beside them.
#[cfg(feature = "gpu")]
pub fn gpu_trials(
    module: &str,
    tests: &[(&'static str, fn())],
    slow: &[&str],
    alone: &[&str],
    missing: Option<&str>,
) -> Vec<libtest_mimic::Trial> {
    use libtest_mimic::Trial;
    tests
        .iter()
        .map(|&(name, f)| {
            let by_itself = alone.contains(&name);
            let t = Trial::test(format!("{module}::{name}"), move || {
                in_process(by_itself, f);
                Ok(())
            });
            match missing {
                Some(_) => t.with_ignored_flag(true).with_kind("no GPU adapter"),
                None => t.with_ignored_flag(slow.contains(&name)),
            }
        })
        .collect()
}
