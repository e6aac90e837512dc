//! What one preconditioned CG iteration costs the GPU, counted by the backend as it records
//! the kernels: at most 12 dispatches (it makes 8: the convolution's three passes with s·Ks
//! fused in, the update of p and r with r·r, the preconditioner's three passes with r·z, the
//! new direction), and bytes moved within 1.3× of the iteration's floor (the fields each
//! operation must read and write, and the half spectra at the FFTs' pass boundaries). The
//! bytes are what each kernel's code reads and writes (`backend::gpu::traffic`), so a kernel
//! that starts reading more than it should shows here. Without a preconditioner the iteration
//! is the convolution, the update, one dot product and the direction: 6 dispatches.
//!
//! Skips with a message when no GPU adapter exists, unless `JKRBEM_REQUIRE_GPU=1`.

use crate::common;

use common::gpu_backend;
use jkrbem::backend::gpu::traffic::cg_iteration_floor;
use jkrbem::backend::prelude::*;
use jkrbem::backend::{Counters, Preconditioner};
use jkrbem::model::{CgSettings, Model, ModelOptions};
use jkrbem::scene::Scene;
use jkrbem::solver::cg::{self, CgWork};

/// Counter growth per iteration of a CG solve of `n` iterations, less CG's start (a solve of
/// 0 iterations), on the model's first contact set.
fn per_iteration(model: &Model, pre: Preconditioner, n: usize) -> Option<(f64, f64)> {
    let mut setup = model.grid_setup();
    setup.preconditioner = pre;
    let mut gpu = gpu_backend(&setup)?;
    let mut gpu_c = gpu.mask().unwrap();
    gpu.upload_mask(&mut gpu_c, &model.initial_contact())
        .unwrap();
    let mut work = CgWork::new(&mut gpu).unwrap();
    let mut p = gpu.field().unwrap();
    let mut solve = |iterations: usize| -> (Counters, usize) {
        gpu.upload(&mut p, &vec![0.0; model.nx * model.ny]).unwrap();
        let settings = CgSettings {
            tolerance: 0.0,
            max_iterations: iterations,
            check_every: usize::MAX,
            accept: 1e-5,
        };
        let before = gpu.counters();
        let made = cg::solve(
            &mut gpu,
            &gpu_c,
            &mut work,
            &mut p,
            model.load.d0,
            &settings,
        )
        .unwrap()
        .iterations;
        let after = gpu.counters();
        (
            Counters {
                dispatches: after.dispatches - before.dispatches,
                bytes: after.bytes - before.bytes,
                ..Counters::default()
            },
            made,
        )
    };
    let (start, _) = solve(0);
    let (full, made) = solve(n);
    assert_eq!(made, n, "tolerance 0: every iteration is made");
    let per = |a: u64, b: u64| (a - b) as f64 / n as f64;
    Some((
        per(full.dispatches, start.dispatches),
        per(full.bytes, start.bytes),
    ))
}

fn a_preconditioned_cg_iteration_is_8_dispatches_within_1_3_times_its_byte_floor() {
    for (ratio, nx) in [(1.0, 64), (1.0, 256), (5.0, 128)] {
        let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).unwrap();
        let model = Model::build(
            &scene,
            &ModelOptions {
                nx,
                ..ModelOptions::default()
            },
        )
        .unwrap();
        for (pre, dispatches) in [
            (Preconditioner::Stiffness, 8.0),
            (Preconditioner::None, 6.0),
        ] {
            let Some((d, bytes)) = per_iteration(&model, pre, 12) else {
                return;
            };
            let floor = cg_iteration_floor(model.nx, model.ny, pre == Preconditioner::Stiffness);
            let ratio_to_floor = bytes / floor as f64;
            println!(
                "R1/R2 = {ratio}, {}×{}, {pre:?}: {d} dispatches, {:.2} MB per iteration = \
                 {ratio_to_floor:.3}× the floor of {:.2} MB",
                model.nx,
                model.ny,
                bytes / 1e6,
                floor as f64 / 1e6
            );
            assert!(d <= 12.0, "at most 12 dispatches per iteration, got {d}");
            // The residual is read once per solve (not per iteration): the rest is the
            // iteration's own work.
            assert!(
                (d - dispatches).abs() < 0.2,
                "{pre:?}: {dispatches} dispatches per iteration expected, got {d}"
            );
            assert!(
                ratio_to_floor <= 1.3,
                "{pre:?}: {ratio_to_floor:.3}× the byte floor, more than 1.3×"
            );
            assert!(
                ratio_to_floor >= 1.0,
                "the floor is a floor: {ratio_to_floor:.3}"
            );
        }
    }
}

/// This file's tests, for `tests/gpu/main.rs`; `missing`: why there is no GPU adapter.
pub fn trials(missing: Option<&str>) -> Vec<libtest_mimic::Trial> {
    common::gpu_trials(
        "gpu_traffic",
        &[(
            "a_preconditioned_cg_iteration_is_8_dispatches_within_1_3_times_its_byte_floor",
            a_preconditioned_cg_iteration_is_8_dispatches_within_1_3_times_its_byte_floor,
        )],
        &[],
        &[],
        missing,
    )
}
