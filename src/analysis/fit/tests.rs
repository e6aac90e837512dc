//! Tests of the fits: JKR and Johnson–Greenwood branches, synthetic data with and without
//! noise, and refused data.

use super::*;
use crate::theory::{self, jkr_point, TheoryModel};
use std::f64::consts::SQRT_2;

/// `n` evenly spaced values from `lo` to `hi`.
fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
        .collect()
}

/// Deterministic pseudo-random values in [−1, 1) (64-bit LCG, top 53 bits).
fn noise(n: usize, seed: u64) -> Vec<f64> {
    let mut x = seed;
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

/// The JKR branch over the stable range of displacement control and a little beyond:
/// c̄ from 0.3 to 1.5 (end of contact at 0.38, force minimum at 0.79, start at c̄0 = 1.5).
fn jkr_branch() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let c = linspace(0.3, 1.5, 61);
    let d = c.iter().map(|&c| jkr_point(c).d_bar).collect();
    let f = c.iter().map(|&c| jkr_point(c).f_bar).collect();
    (c, d, f)
}

#[test]
fn jkr_approach_fit_recovers_a_one_and_b_minus_two_thirds_root_two() {
    let (c, d, _) = jkr_branch();
    let fit = fit_d_of_c(&c, &d).unwrap();
    println!("JKR d̄(c̄): {fit:?}");
    assert!((fit.a - 1.0).abs() < 1e-13, "A = {}", fit.a);
    assert!((fit.b + 2.0 / 3.0 * SQRT_2).abs() < 1e-13, "B = {}", fit.b);
    assert!(fit.quality.r_squared > 1.0 - 1e-15 && fit.quality.max_residual < 1e-14);
    assert_eq!(fit.quality.points, 61);
}

#[test]
fn jkr_force_fit_recovers_c1_one_c2_minus_root_two_alpha_three_halves() {
    let (c, _, f) = jkr_branch();
    let fit = fit_f_of_c(&c, &f).unwrap();
    println!("JKR F̄(c̄): {fit:?}");
    assert!((fit.alpha - 1.5).abs() < 1e-9, "α = {}", fit.alpha);
    assert!((fit.c1 - 1.0).abs() < 1e-9, "c1 = {}", fit.c1);
    assert!((fit.c2 + SQRT_2).abs() < 1e-9, "c2 = {}", fit.c2);
    assert!(!fit.alpha_at_bound && fit.quality.max_residual < 1e-9);
}

#[test]
fn johnson_greenwood_branches_are_close_to_the_fitted_forms() {
    // Not an identity: how well the JKR-shaped forms describe JG for ellipsoids (physics §8.4),
    // over the branch from the end of contact to c̄ = 1.5.
    for ratio in [2.0, 10.0, 25.0] {
        let end = theory::pull_off(TheoryModel::Jg, ratio)
            .unwrap()
            .end_of_contact
            .c_bar;
        let pts: Vec<_> = theory::curve(TheoryModel::Jg, ratio, 600)
            .unwrap()
            .into_iter()
            .filter(|p| (end..=1.5).contains(&p.c_bar))
            .collect();
        let c: Vec<f64> = pts.iter().map(|p| p.c_bar).collect();
        let d: Vec<f64> = pts.iter().map(|p| p.d_bar).collect();
        let f: Vec<f64> = pts.iter().map(|p| p.f_bar).collect();
        let (fd, ff) = (fit_d_of_c(&c, &d).unwrap(), fit_f_of_c(&c, &f).unwrap());
        println!(
            "JG R1/R2 = {ratio}: A = {:.5}, B = {:.5} (R² = {:.7}, RMS {:.1e}); c1 = {:.5}, \
             c2 = {:.5}, α = {:.5} (R² = {:.7}, RMS {:.1e}); {} points",
            fd.a,
            fd.b,
            fd.quality.r_squared,
            fd.quality.rms_residual,
            ff.c1,
            ff.c2,
            ff.alpha,
            ff.quality.r_squared,
            ff.quality.rms_residual,
            ff.quality.points
        );
        assert!(fd.quality.r_squared > 0.999 && ff.quality.r_squared > 0.999);
        assert!(!ff.alpha_at_bound);
    }
}

#[test]
fn synthetic_branch_coefficients_are_recovered_exactly_and_under_noise() {
    let c = linspace(0.35, 1.5, 80);
    let (a, b) = (0.83, -1.07);
    let (c1, c2, alpha) = (0.91, -1.62, 1.31);
    let d: Vec<f64> = c.iter().map(|c| a * c * c + b * c.sqrt()).collect();
    let f: Vec<f64> = c
        .iter()
        .map(|c| c1 * c.powi(3) + c2 * c.powf(alpha))
        .collect();
    let fd = fit_d_of_c(&c, &d).unwrap();
    let ff = fit_f_of_c(&c, &f).unwrap();
    assert!(
        (fd.a - a).abs() < 1e-13 && (fd.b - b).abs() < 1e-13,
        "{fd:?}"
    );
    assert!(
        (ff.c1 - c1).abs() < 1e-9 && (ff.c2 - c2).abs() < 1e-9 && (ff.alpha - alpha).abs() < 1e-9,
        "{ff:?}"
    );
    // Uniform noise of amplitude 1e-3 (RMS 5.8e-4), about the scatter of a 256² pull-off.
    let amp = 1e-3;
    let dn: Vec<f64> = d
        .iter()
        .zip(noise(80, 1))
        .map(|(v, e)| v + amp * e)
        .collect();
    let fnoisy: Vec<f64> = f
        .iter()
        .zip(noise(80, 2))
        .map(|(v, e)| v + amp * e)
        .collect();
    let fd = fit_d_of_c(&c, &dn).unwrap();
    let ff = fit_f_of_c(&c, &fnoisy).unwrap();
    println!("noisy d̄(c̄): {fd:?}\nnoisy F̄(c̄): {ff:?}");
    assert!((fd.a - a).abs() < 5e-4 && (fd.b - b).abs() < 5e-4, "{fd:?}");
    assert!(
        (ff.c1 - c1).abs() < 5e-3 && (ff.c2 - c2).abs() < 5e-3 && (ff.alpha - alpha).abs() < 5e-3,
        "{ff:?}"
    );
    // The residual is the noise: RMS amp/√3, R² close to 1.
    for q in [fd.quality, ff.quality] {
        assert!(
            (q.rms_residual / (amp / 3f64.sqrt()) - 1.0).abs() < 0.25,
            "{q:?}"
        );
        assert!(q.r_squared > 0.9999 && q.max_residual <= amp * 1.2, "{q:?}");
    }
}

#[test]
fn power_laws_are_recovered_from_the_study_ratios() {
    let x = [1.0, 2.0, 5.0, 10.0, 25.0, 50.0];
    for (k1, k2, k3) in [
        (0.8, 0.6, 0.3),
        (-0.5, -0.7, 1.2),
        (0.02, 1.9, -0.4),
        (2.0, 0.05, -1.0),
        (-1.5, -0.04, 0.2),
    ] {
        let y: Vec<f64> = x.iter().map(|x: &f64| k1 * x.powf(k2) + k3).collect();
        let fit = fit_power_law(&x, &y).unwrap();
        let tol = 1e-8 * (1.0 + k1.abs().max(k3.abs()) / k2.abs());
        assert!(
            (fit.k1 - k1).abs() < tol && (fit.k2 - k2).abs() < 1e-9 && (fit.k3 - k3).abs() < tol,
            "({k1}, {k2}, {k3}): {fit:?}"
        );
        assert!(!fit.k2_at_bound && fit.quality.r_squared > 1.0 - 1e-14);
    }
}

#[test]
fn noisy_power_law_is_recovered_within_its_scatter() {
    let x = linspace(1.0, 50.0, 25);
    let (k1, k2, k3) = (0.35, 0.45, 0.62);
    let amp = 1e-3;
    let y: Vec<f64> = x
        .iter()
        .zip(noise(25, 7))
        .map(|(x, e)| k1 * x.powf(k2) + k3 + amp * e)
        .collect();
    let fit = fit_power_law(&x, &y).unwrap();
    println!("noisy power law: {fit:?}");
    assert!(
        (fit.k1 - k1).abs() < 0.02 && (fit.k2 - k2).abs() < 0.01 && (fit.k3 - k3).abs() < 0.03,
        "{fit:?}"
    );
    assert!(fit.quality.rms_residual < amp && fit.quality.points == 25);
}

#[test]
fn exponents_outside_the_search_range_are_flagged() {
    let c = linspace(0.3, 1.5, 30);
    let f: Vec<f64> = c.iter().map(|c| c.powi(3) - c.powf(0.2)).collect();
    let fit = fit_f_of_c(&c, &f).unwrap();
    assert!(fit.alpha_at_bound && fit.alpha == ALPHA_RANGE.0, "{fit:?}");
    let x = [1.0, 2.0, 4.0, 8.0];
    let y: Vec<f64> = x.iter().map(|x: &f64| x.powi(4)).collect();
    let fit = fit_power_law(&x, &y).unwrap();
    assert!(fit.k2_at_bound && fit.k2 == K2_RANGE.1, "{fit:?}");
}

#[test]
fn logarithmic_data_are_refused_as_a_power_law() {
    let x = [1.0, 2.0, 5.0, 10.0, 25.0, 50.0];
    let y: Vec<f64> = x.iter().map(|x: &f64| 0.7 * x.ln() + 0.1).collect();
    let e = fit_power_law(&x, &y).unwrap_err();
    assert!(e.to_string().contains("logarithm"), "{e}");
}

#[test]
fn bad_data_are_refused_with_the_reason() {
    let c = [0.5, 0.8, 1.1, 1.4];
    let y = [0.1, 0.2, 0.3, 0.5];
    let msg = |e: FitError| e.to_string();
    assert!(msg(fit_d_of_c(&c, &y[..3]).unwrap_err()).contains("4 values but d_bar has 3"));
    assert!(matches!(
        fit_d_of_c(&c[..1], &y[..1]),
        Err(FitError::TooFewPoints {
            needed: 2,
            got: 1,
            ..
        })
    ));
    assert!(matches!(
        fit_f_of_c(&c[..2], &y[..2]),
        Err(FitError::TooFewPoints {
            needed: 3,
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        fit_power_law(&c[..2], &y[..2]),
        Err(FitError::TooFewPoints {
            needed: 3,
            got: 2,
            ..
        })
    ));
    assert!(msg(fit_d_of_c(&c, &[0.1, f64::NAN, 0.3, 0.5]).unwrap_err()).contains("d_bar[1] = NaN"));
    assert!(msg(fit_f_of_c(&[0.5, 0.0, 1.1, 1.4], &y).unwrap_err()).contains("c_bar[1] = 0"));
    assert!(msg(fit_power_law(&[1.0, 2.0, 2.0, 1.0], &y).unwrap_err()).contains("2 distinct"));
    assert!(msg(fit_d_of_c(&c, &[0.3; 4]).unwrap_err()).contains("R² is undefined"));
    assert!(fit_power_law(&[1.0, -2.0, 3.0], &[1.0, 2.0, 3.0]).is_err());
}

#[test]
fn evaluated_fits_reproduce_their_coefficients() {
    let q = FitQuality::NONE;
    let d = LinearFit2 {
        a: 1.0,
        b: -2.0,
        quality: q,
    };
    assert_eq!(d.eval(4.0), 16.0 - 4.0);
    let f = PowerFit {
        c1: 1.0,
        c2: -1.0,
        alpha: 0.5,
        alpha_at_bound: false,
        quality: q,
    };
    assert_eq!(f.eval(4.0), 64.0 - 2.0);
    let p = PowerLawFit {
        k1: 2.0,
        k2: 2.0,
        k3: 1.0,
        k2_at_bound: false,
        quality: q,
    };
    assert_eq!(p.eval(3.0), 19.0);
}
