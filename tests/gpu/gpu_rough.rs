//! A generated rough sphere (rms slope 0.1, Hurst 0.8, cut-off 0.2) pressed on and pulled off
//! on one 32² grid (`--measure adhesive-force`) on the GPU backend (f32) and the CPU backend
//! (f64; no backend has another precision): |min F̄| must agree within 1e-5 (relative), and the
//! states around each run's minimum, offset by offset, must be the same states (load step,
//! phase, contact elements) with F̄ within 1e-5 of |min F̄| and d̄ within 1e-5 of |d̄| at the
//! minimum. Measured on lavapipe at 32²: |min F̄| within 8.8e-7, the 11 states around it within
//! 8.8e-7 in F̄ and 1.6e-6 in d̄ (an onset's approach is located to f32's resolution), and every
//! one of the 450 states the same on both backends (at 64²: 4.7e-7, 1.0e-6, 2.0e-6, 467
//! states, but 7 minutes on a software adapter). About 40 s on two cores, hence `slow_`.
//!
//! Skips with a message when no GPU adapter exists, unless `JKRBEM_REQUIRE_GPU=1`.

use crate::common;

use common::{gpu_backend, rough_sphere, run_model};
use jkrbem::model::{Measure, Model, ModelOptions};
use jkrbem::solver::{self, Outcome, State};

/// How many states on each side of the force minimum are compared.
const AROUND: usize = 5;

fn slow_rough_sphere_pulloff_matches_cpu() {
    let scene = rough_sphere(0.1, 3);
    let model = Model::build(
        &scene,
        &ModelOptions {
            nx: 32,
            measure: Measure::AdhesiveForce,
            ..ModelOptions::default()
        },
    )
    .unwrap();
    assert!(model.loading.is_some(), "a rough shape is pressed on");
    let Some(mut gpu) = gpu_backend(&model.grid_setup()) else {
        return;
    };
    let g = solver::run(&mut gpu, &model, &mut |_| {});
    assert!(g.complete() && g.min_reached(), "GPU run: {:?}", g.error);
    let c = run_model(model.clone()).outcome;
    assert!(c.complete() && c.min_reached(), "CPU run: {:?}", c.error);
    let (fg, fc) = (g.force_minimum().unwrap(), c.force_minimum().unwrap());
    assert!(!fc.phase.is_loading(), "the minimum is on the pull-off");
    let rel = (fg.f_bar / fc.f_bar - 1.0).abs();
    // The states around each run's minimum, offset by offset: the same load step, phase and
    // contact set (its element count), and F̄ and d̄ within 1e-5 of |min F̄| and |d̄| there.
    let index = |o: &'static str, states: &[State], min: &State| {
        states
            .iter()
            .position(|s| std::ptr::eq(s, min))
            .unwrap_or_else(|| panic!("the {o} minimum is one of its states"))
    };
    let (at_g, at_c) = (index("GPU", &g.states, fg), index("CPU", &c.states, fc));
    let (before, after) = (
        AROUND.min(at_g).min(at_c),
        AROUND
            .min(g.states.len() - 1 - at_g)
            .min(c.states.len() - 1 - at_c),
    );
    let (mut f_dev, mut d_dev): (f64, f64) = (0.0, 0.0);
    for k in 0..=before + after {
        let (sg, sc) = (&g.states[at_g - before + k], &c.states[at_c - before + k]);
        println!(
            "{:+}: step {} {:?}, {} elements: F̄ GPU {:.9} CPU {:.9}, d̄ GPU {:.9} CPU {:.9}",
            k as isize - before as isize,
            sc.step,
            sc.phase,
            sc.n_contact,
            sg.f_bar,
            sc.f_bar,
            sg.d_bar,
            sc.d_bar
        );
        assert_eq!(
            (sg.step, sg.phase, sg.n_contact),
            (sc.step, sc.phase, sc.n_contact),
            "the runs part near the minimum"
        );
        f_dev = f_dev.max((sg.f_bar - sc.f_bar).abs() / fc.f_bar.abs());
        d_dev = d_dev.max((sg.d_bar - sc.d_bar).abs() / fc.d_bar.abs());
    }
    // The whole loop, for the report: where the two runs first take different states.
    let parted = g
        .states
        .iter()
        .zip(&c.states)
        .position(|(a, b)| (a.step, a.phase, a.n_contact) != (b.step, b.phase, b.n_contact));
    let loading = |o: &Outcome| o.states.iter().filter(|s| s.phase.is_loading()).count();
    println!(
        "rough sphere (rms slope 0.1, Hurst 0.8) {}×{}: |min F̄| GPU (f32) {:.7} vs CPU (f64) \
         {:.7}, relative difference {rel:.2e}; the {} states around the minimum differ by at \
         most {f_dev:.2e} of |min F̄| in F̄ and {d_dev:.2e} of |d̄| in d̄; {} vs {} states ({} vs {} \
         loading), first parting {}; CG iterations {} vs {}",
        model.nx,
        model.ny,
        -fg.f_bar,
        -fc.f_bar,
        before + after + 1,
        g.states.len(),
        c.states.len(),
        loading(&g),
        loading(&c),
        parted.map_or("none".to_string(), |i| format!("at state {i}")),
        g.cg_iterations(),
        c.cg_iterations()
    );
    assert!(
        rel < 1e-5,
        "GPU (f32) and CPU (f64) adhesive forces differ by {rel:e}"
    );
    assert!(
        f_dev < 1e-5,
        "F̄ differs by {f_dev:e} of |min F̄| near the minimum"
    );
    assert!(
        d_dev < 1e-5,
        "d̄ differs by {d_dev:e} of |d̄| at the minimum near it"
    );
}

/// This file's tests, for `tests/gpu/main.rs`; `missing`: why there is no GPU adapter.
pub fn trials(missing: Option<&str>) -> Vec<libtest_mimic::Trial> {
    common::gpu_trials(
        "gpu_rough",
        &[(
            "slow_rough_sphere_pulloff_matches_cpu",
            slow_rough_sphere_pulloff_matches_cpu,
        )],
        &[],
        &[],
        missing,
    )
}
