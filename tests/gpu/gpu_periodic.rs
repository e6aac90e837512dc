//! The periodic convolution on the GPU against the CPU's (the same symbol, f32 against f64),
//! and Johnson's wavy surface on fixed strips (`tests/physics/johnson_wave.rs` on the CPU):
//! the mean pressure CG finds on the GPU within 1e-6 of the CPU's. Small grids: lavapipe is
//! slow.

use crate::common;

use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::gpu::{test_context, GpuBackend};
use jkrbem::backend::prelude::*;
use jkrbem::backend::{GridSetup, Preconditioner};
use jkrbem::model::CgSettings;
use jkrbem::solver::cg::{self, CgWork};
use jkrbem::theory::johnson_wave::Wave;
use std::f64::consts::PI;

/// A wave of one wavelength on nx × 4 elements (λ = 1, Δ = 0.02, E* = 1).
fn wave_setup(nx: usize) -> (Wave, GridSetup) {
    let w = Wave {
        lambda: 1.0,
        delta: 0.02,
        e_star: 1.0,
        work_of_adhesion: 0.09 * PI * PI * 0.02 * 0.02 / 2.0,
    };
    let dx = w.lambda / nx as f64;
    let profile = (0..nx * 4)
        .map(|i| w.height(((i % nx) as f64 + 0.5 - nx as f64 / 2.0) * dx))
        .collect();
    let setup = GridSetup {
        nx,
        ny: 4,
        dx,
        e_star: w.e_star,
        profile,
        preconditioner: Preconditioner::Stiffness,
    };
    (w, setup)
}

/// The mean pressure on the strips of the central `2m` elements of every row at approach d.
fn strip_mean<B: Backend>(b: &mut B, m: usize, d: f64) -> f64 {
    let (nx, ny) = b.shape();
    let host: Vec<bool> = (0..nx * ny)
        .map(|i| (nx / 2 - m..nx / 2 + m).contains(&(i % nx)))
        .collect();
    let mut c = b.mask().unwrap();
    b.upload_mask(&mut c, &host).unwrap();
    let mut work = CgWork::new(b).unwrap();
    let mut p = b.field().unwrap();
    let settings = cg::effective(
        b,
        &CgSettings {
            tolerance: 1e-12,
            max_iterations: 20_000,
            check_every: b.check_every(),
            accept: 1e-6,
        },
    );
    let report = cg::solve(b, &c, &mut work, &mut p, d, &settings).unwrap();
    assert!(report.converged(), "{report:?}");
    let mut out = vec![0.0; nx * ny];
    b.download(&p, &mut out).unwrap();
    out.iter().sum::<f64>() / (nx * ny) as f64
}

fn periodic_convolution_matches_the_cpu() {
    let Some(ctx) = test_context() else { return };
    for (nx, ny) in [(32, 32), (64, 16), (16, 64)] {
        let setup = GridSetup {
            nx,
            ny,
            dx: 0.1,
            e_star: 2.0,
            profile: vec![0.0; nx * ny],
            preconditioner: Preconditioner::None,
        };
        let mut gpu = GpuBackend::new_periodic(ctx.clone(), &setup).unwrap();
        let mut cpu = CpuBackend::new_periodic(&setup).unwrap();
        assert_eq!(gpu.name(), "gpu-periodic");
        let p = common::pseudo_random(nx * ny, (nx + 3 * ny) as u64);
        let mut fp = gpu.field().unwrap();
        gpu.upload(&mut fp, &p).unwrap();
        let mut fu = gpu.field().unwrap();
        gpu.convolve(&fp, &mut fu).unwrap();
        let mut got = vec![0.0; nx * ny];
        gpu.download(&fu, &mut got).unwrap();
        let mut want = vec![0.0; nx * ny];
        cpu.convolve(&p, &mut want).unwrap();
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = got
            .iter()
            .zip(&want)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / scale;
        println!("{nx}×{ny}: periodic convolution, GPU against CPU, max relative {err:.2e}");
        assert!(err < 2e-6, "{nx}×{ny}: {err:e}");
    }
}

fn johnson_strips_mean_pressure_matches_the_cpu() {
    let Some(ctx) = test_context() else { return };
    let nx = 64;
    let (w, setup) = wave_setup(nx);
    let mut gpu = GpuBackend::new_periodic(ctx, &setup).unwrap();
    let mut cpu = CpuBackend::new_periodic(&setup).unwrap();
    // Westergaard's state on a = λ/4 (p̄ = p*/2, far from zero).
    let a = 0.25 * w.lambda;
    let d = w.approach(a, w.westergaard_mean_pressure(a));
    let (on_gpu, on_cpu) = (
        strip_mean(&mut gpu, nx / 4, d),
        strip_mean(&mut cpu, nx / 4, d),
    );
    let dev = on_gpu / on_cpu - 1.0;
    println!(
        "{nx}×4, a = λ/4: p̄ {on_gpu:.9} on the GPU, {on_cpu:.9} on the CPU ({dev:+.2e}); \
         Westergaard's {:.9}",
        w.westergaard_mean_pressure(a)
    );
    assert!(dev.abs() < 1e-6, "{dev}");
}

/// This file's tests, for `tests/gpu/main.rs`; `missing`: why there is no GPU adapter.
pub fn trials(missing: Option<&str>) -> Vec<libtest_mimic::Trial> {
    common::gpu_trials(
        "gpu_periodic",
        &[
            (
                "periodic_convolution_matches_the_cpu",
                periodic_convolution_matches_the_cpu,
            ),
            (
                "johnson_strips_mean_pressure_matches_the_cpu",
                johnson_strips_mean_pressure_matches_the_cpu,
            ),
        ],
        &[],
        &[],
        missing,
    )
}
