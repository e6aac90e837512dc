//! What zero padding buys (physics §4): whole pull-offs of an ISOLATED sphere with the
//! periodic convolution against the padded one.
//!
//! The periodic convolution (`backend::kernel`) is right for a surface periodic over the
//! domain (a wave, a nominally flat rough surface: `tests/physics/johnson_wave.rs`), and
//! wrong for an isolated contact in two ways: the contact feels its periodic images (their
//! pull flattens the elastic surface's response to a long-range load), and the mean
//! displacement of a periodic pressure is undefined, so it is set to zero: the approach is
//! measured from the elastic surface's mean plane instead of from the surface far away. An
//! isolated sphere's padded displacement has a positive mean over the domain, so at the same
//! approach the periodic run presses in deeper than the isolated one by that mean, and its
//! force and its pull-off are wrong.

use crate::common;

use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::prelude::*;
use jkrbem::model::ModelOptions;
use jkrbem::solver;

#[test]
fn periodic_convolution_cannot_press_an_isolated_sphere() {
    // Measured (64², c̄0 = 1.5): the padded pull-off completes; the periodic one does not.
    // At the Hertz press d0, measured from the mean plane, the sphere overlaps the whole
    // domain: full contact, where the zero-mean operator has no solution (d ≠ h̄), and CG
    // diverges on the first solve.
    let model = common::model_for(
        1.0,
        ModelOptions {
            nx: 64,
            ..Default::default()
        },
    );
    let padded = solver::run(&mut common::cpu_backend(&model), &model, &mut |_| {});
    assert!(padded.complete(), "{:?}", padded.error);
    let mut periodic_backend = CpuBackend::new_periodic(&model.grid_setup()).unwrap();
    let periodic = solver::run(&mut periodic_backend, &model, &mut |_| {});
    println!(
        "sphere 64²: padded complete ({} states); periodic: {:?}",
        padded.states.len(),
        periodic.error
    );
    assert!(!periodic.complete());
}

#[test]
fn periodic_convolution_drops_an_isolated_contacts_mean_displacement() {
    // A uniform disk of pressure over 80 % of the model's 64² domain: the padded (isolated)
    // displacement has a large positive mean over the domain, which the periodic one sets to
    // zero; what is left of their difference is the images' pull. Measured: the padded mean
    // is 65.6 % of the peak displacement, the images' pull up to 10.5 % of it.
    let model = common::model_for(
        1.0,
        ModelOptions {
            nx: 64,
            ..Default::default()
        },
    );
    let setup = model.grid_setup();
    let (nx, ny) = (setup.nx, setup.ny);
    let r = 0.4 * nx.min(ny) as f64;
    let p: Vec<f64> = (0..nx * ny)
        .map(|i| {
            let (x, y) = (
                (i % nx) as f64 + 0.5 - nx as f64 / 2.0,
                (i / nx) as f64 + 0.5 - ny as f64 / 2.0,
            );
            if x * x + y * y < r * r {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    let convolve = |b: &mut CpuBackend| {
        let mut u = vec![0.0; nx * ny];
        b.convolve(&p, &mut u).unwrap();
        u
    };
    let padded = convolve(&mut CpuBackend::new(&setup).unwrap());
    let periodic = convolve(&mut CpuBackend::new_periodic(&setup).unwrap());
    let mean = |u: &[f64]| u.iter().sum::<f64>() / u.len() as f64;
    let peak = padded.iter().fold(0.0f64, |m, v| m.max(*v));
    let (mean_padded, mean_periodic) = (mean(&padded), mean(&periodic));
    let images = padded
        .iter()
        .zip(&periodic)
        .map(|(a, b)| (b - (a - mean_padded)).abs())
        .fold(0.0, f64::max);
    println!(
        "disk over 80 % of 64²: padded mean displacement {:.1} % of its peak, periodic {:.1e}; \
         the images' pull beyond it up to {:.1} % of the peak",
        100.0 * mean_padded / peak,
        mean_periodic / peak,
        100.0 * images / peak
    );
    assert!(mean_periodic.abs() < 1e-12 * peak);
    assert!(mean_padded > 0.3 * peak, "{mean_padded} vs {peak}");
    assert!(images > 0.05 * peak, "{images} vs {peak}");
}
