//! Johnson's (1995) adhesive wavy surface (`theory::johnson_wave`) against the periodic
//! convolution, at the backend's level: a rigid wave h(x) = Δ(1 − cos 2πx/λ), one wavelength
//! along x and a few elements along y (uniform in y, so that the periodic convolution makes it
//! plane strain), against a flat half-space. On fixed contact strips |x| < a solved by the
//! solver's CG, the mean pressure and the approach (from the mean plane) are compared with the
//! closed forms; with the Pohrt–Popov detachment stress σ_c, the load at which the strips'
//! edge element reaches −σ_c with Johnson's adhesive branch as the grid is refined; and the
//! whole detachment loop (`equilibrate`) with Johnson's half-width at a given approach.
//!
//! Then the whole pipeline: the wave written as an .npy map of one period, run through the
//! library's request (`Request` → `simulate`) with the periodic convolution, pressed on and
//! pulled off, its pull-off stress |min F| / (the period's area) against Johnson's.

use crate::common;

use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::prelude::*;
use jkrbem::backend::{GridSetup, Preconditioner};
use jkrbem::model::{kappa, CgSettings, ModelOptions};
use jkrbem::scene::height_map::HeightMap;
use jkrbem::session::request::Request;
use jkrbem::session::simulate::{simulate, Sink};
use jkrbem::solver::cg::{self, CgWork};
use jkrbem::solver::equilibrium::{equilibrate, Fields};
use jkrbem::theory::johnson_wave::Wave;
use std::f64::consts::PI;

/// Elements along y (the surface is uniform in y).
const NY: usize = 4;

/// λ = 1, Δ = 0.02, E* = 1 and Δγ such that Johnson's α = 0.3 (below α₀ ≈ 0.57: the contact
/// holds at zero load without jumping into full contact).
fn wave() -> Wave {
    let (lambda, delta, e_star, alpha) = (1.0, 0.02, 1.0, 0.3);
    Wave {
        lambda,
        delta,
        e_star,
        work_of_adhesion: alpha * alpha * PI * PI * e_star * delta * delta / (2.0 * lambda),
    }
}

/// Element centres along x, symmetric about the trough x = 0.
fn centres(nx: usize, dx: f64) -> Vec<f64> {
    (0..nx)
        .map(|i| (i as f64 + 0.5 - nx as f64 / 2.0) * dx)
        .collect()
}

/// The setup of one wavelength on `nx` × NY elements.
fn setup(w: &Wave, nx: usize) -> GridSetup {
    let dx = w.lambda / nx as f64;
    let xs = centres(nx, dx);
    GridSetup {
        nx,
        ny: NY,
        dx,
        e_star: w.e_star,
        profile: (0..nx * NY).map(|i| w.height(xs[i % nx])).collect(),
        preconditioner: Preconditioner::Stiffness,
    }
}

/// The strips |x| < m Δx (the central 2m elements of every row).
fn strips(nx: usize, m: usize) -> Vec<bool> {
    (0..nx * NY)
        .map(|i| (nx / 2 - m..nx / 2 + m).contains(&(i % nx)))
        .collect()
}

/// p on the fixed set `c` at approach `d`, solved by CG to 1e-12, as one row (the rows are
/// equal), and its mean over the domain.
fn solve<B: Backend>(b: &mut B, c: &[bool], d: f64) -> (Vec<f64>, f64) {
    let (nx, ny) = b.shape();
    let mut mask = b.mask().unwrap();
    b.upload_mask(&mut mask, c).unwrap();
    let mut work = CgWork::new(b).unwrap();
    let mut p = b.field().unwrap();
    let settings = CgSettings {
        tolerance: 1e-12,
        max_iterations: 20_000,
        check_every: b.check_every(),
        accept: 1e-6,
    };
    let settings = cg::effective(b, &settings);
    let report = cg::solve(b, &mask, &mut work, &mut p, d, &settings).unwrap();
    assert!(report.converged(), "{report:?}");
    let mut host = vec![0.0; nx * ny];
    b.download(&p, &mut host).unwrap();
    let mean = host.iter().sum::<f64>() / (nx * ny) as f64;
    (host[..nx].to_vec(), mean)
}

/// The solution on the strips of half-width m Δx at approach d, from two solves (p is
/// affine in d on a fixed set): (p̄(d), and the row of p) as functions of d.
struct Affine {
    p0: Vec<f64>,
    p1: Vec<f64>,
    mean0: f64,
    mean1: f64,
}

impl Affine {
    fn new<B: Backend>(b: &mut B, c: &[bool], scale: f64) -> Affine {
        let (p0, mean0) = solve(b, c, 0.0);
        let (pd, meand) = solve(b, c, scale);
        Affine {
            p1: pd.iter().zip(&p0).map(|(a, b)| (a - b) / scale).collect(),
            mean1: (meand - mean0) / scale,
            p0,
            mean0,
        }
    }
    fn mean(&self, d: f64) -> f64 {
        self.mean0 + d * self.mean1
    }
    fn at(&self, i: usize, d: f64) -> f64 {
        self.p0[i] + d * self.p1[i]
    }
    /// The approach at which element `i` carries `p`.
    fn d_for(&self, i: usize, p: f64) -> f64 {
        (p - self.p0[i]) / self.p1[i]
    }
}

#[test]
fn fixed_strips_carry_westergaards_pressure_and_approach() {
    // On strips of half-width a = λ/4, the approach of Westergaard's state (no edge
    // stress), d = Δ sin²ψ (1 − ln sin²ψ), must give his mean pressure p* sin²ψ, and the
    // pressure between the edges his profile, with the mean plane as the approach's origin.
    let w = wave();
    let a = 0.25 * w.lambda;
    let mut last = (f64::INFINITY, f64::INFINITY);
    for nx in [64usize, 128, 256, 512] {
        let dx = w.lambda / nx as f64;
        let mut b = CpuBackend::new_periodic(&setup(&w, nx)).unwrap();
        let s = strips(nx, nx / 4);
        let sol = Affine::new(&mut b, &s, w.delta);
        let d = w.approach(a, w.westergaard_mean_pressure(a));
        let mean_dev = sol.mean(d) / w.westergaard_mean_pressure(a) - 1.0;
        // The profile at the elements well inside (|x| < a/2), against p* (its scale).
        let xs = centres(nx, dx);
        let profile_dev = (0..nx)
            .filter(|&i| xs[i].abs() < 0.5 * a)
            .map(|i| (sol.at(i, d) - w.pressure(xs[i], a, sol.mean(d))).abs() / w.p_star())
            .fold(0.0, f64::max);
        // The compliance: p̄ rises by 1/C(a) per unit approach.
        let compliance_dev = 1.0 / (sol.mean1 * w.punch_compliance(a)) - 1.0;
        println!(
            "Westergaard, a = λ/4, {nx}×{NY}: p̄ {:+.3e} relative, profile inside a/2 {:.3e} \
             of p*, compliance {:+.3e}",
            mean_dev, profile_dev, compliance_dev
        );
        assert!(mean_dev.abs() < last.0 && compliance_dev.abs() < last.1);
        last = (mean_dev.abs(), compliance_dev.abs());
        if nx == 512 {
            assert!(mean_dev.abs() < 2e-3, "{mean_dev}");
            assert!(profile_dev < 2e-3, "{profile_dev}");
            assert!(compliance_dev.abs() < 5e-3, "{compliance_dev}");
        }
    }
}

#[test]
fn the_edge_reaching_sigma_c_is_a_crack_of_one_energy_release_rate() {
    // For strips of half-width a, the load at which the edge element reaches −σ_c
    // (σ_c = √(E*Δγ/(κΔx))) against Johnson's p̄(a). The solved pressure is Johnson's
    // two-term profile for its own p̄ (the Westergaard test), so that load has a stress
    // intensity K = (p* sin²ψ − p̄)√(λ/tan ψ) and an energy release rate G = K²/(2E*): the
    // edge criterion is consistent if G converges, as Δx → 0, to one value for every a.
    // Measured (2026, 64…512 elements a wavelength): it converges (the differences about
    // halve) to G = 1.822 Δγ for a = λ/8, λ/4 and 3λ/8 alike, on these grid-aligned
    // straight edges, not to Johnson's Δγ: the Pohrt–Popov σ_c, whose κ is calibrated on the
    // sphere's staircase edges, makes a straight edge aligned with the grid 1.82 times as
    // sticky. The operator is not the cause: the same solves give Westergaard's pressure,
    // profile and compliance to 1e-5 (the test above).
    let w = wave();
    println!(
        "Johnson's α = {:.3}, p* = {:.5}, load-controlled pull-off p̄ = {:.5} at a = {:.4} λ",
        w.alpha(),
        w.p_star(),
        w.pull_off_mean_pressure().unwrap(),
        w.pull_off_half_width().unwrap() / w.lambda
    );
    let mut limits = Vec::new();
    for frac in [0.125, 0.25, 0.375] {
        let a = frac * w.lambda;
        let want = w.adhesive_mean_pressure(a);
        let mut g = Vec::new();
        for nx in [64usize, 128, 256, 512] {
            let dx = w.lambda / nx as f64;
            let sigma_c = (w.e_star * w.work_of_adhesion / (kappa() * dx)).sqrt();
            let mut b = CpuBackend::new_periodic(&setup(&w, nx)).unwrap();
            let m = (frac * nx as f64).round() as usize;
            let sol = Affine::new(&mut b, &strips(nx, m), w.delta);
            let edge = nx / 2 + m - 1;
            let d = sol.d_for(edge, -sigma_c);
            let got = sol.mean(d);
            let k = w.stress_intensity(a, got);
            let ratio = k * k / (2.0 * w.e_star) / w.work_of_adhesion;
            println!(
                "a = {frac} λ, {nx}×{NY}: p̄ at the edge's −σ_c {got:+.6} against Johnson's \
                 {want:+.6} ({:+.3e} of p*); its approach {:+.3e} of Δ from Johnson's; \
                 G/Δγ = {ratio:.4}",
                (got - want) / w.p_star(),
                (d - w.approach(a, want)) / w.delta,
            );
            g.push(ratio);
        }
        let steps: Vec<f64> = g.windows(2).map(|p| p[1] - p[0]).collect();
        // Converging: each refinement changes G less (by about half, first order).
        for s in steps.windows(2) {
            let r = s[1] / s[0];
            assert!((0.0..0.6).contains(&r), "a = {frac} λ: G/Δγ {g:?}");
        }
        let limit = 2.0 * g[3] - g[2];
        println!("a = {frac} λ: G/Δγ extrapolated to Δx → 0: {limit:.4}");
        limits.push(limit);
    }
    let (lo, hi) = limits
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(*v), h.max(*v)));
    assert!(
        hi / lo - 1.0 < 0.02,
        "G/Δγ differs between the widths: {limits:?}"
    );
}

#[test]
fn the_detachment_loop_ends_where_the_edge_criterion_says() {
    // From strips wider than Johnson's at the approach of his state with a = 0.3 λ, the
    // detachment loop (the solver's `equilibrate`, on the periodic backend, with the
    // settings of a model of any scene: it reads only its CG settings and switches) detaches
    // the edges until the edge element holds −σ_c: the strips of m elements a side hold
    // (edge p ≥ −σ_c at d), those of m + 1 do not. Its half-width against Johnson's is
    // reported (wider: the edge criterion's G exceeds Δγ, the test above).
    let w = wave();
    let a_j = 0.3 * w.lambda;
    let d = w.adhesive_approach(a_j);
    let model = common::model_for(1.0, ModelOptions::default());
    for nx in [128usize, 256] {
        let dx = w.lambda / nx as f64;
        let sigma_c = (w.e_star * w.work_of_adhesion / (kappa() * dx)).sqrt();
        let mut b = CpuBackend::new_periodic(&setup(&w, nx)).unwrap();
        let mut c = b.mask().unwrap();
        b.upload_mask(&mut c, &strips(nx, (0.42 * nx as f64) as usize))
            .unwrap();
        let mut fields = Fields::new(&mut b, c).unwrap();
        let eq = equilibrate(&mut b, &model, &mut fields, d, sigma_c).unwrap();
        let mut host = vec![false; nx * NY];
        b.download_mask(&fields.c, &mut host).unwrap();
        let width = host[..nx].iter().filter(|&&m| m).count();
        assert_eq!(eq.n_contact, width * NY, "the rows should agree");
        assert_eq!(host, strips(nx, width / 2), "centred strips");
        let m = width / 2;
        let edge_at = |m: usize, b: &mut CpuBackend| {
            let (p, _) = solve(b, &strips(nx, m), d);
            p[nx / 2 + m - 1]
        };
        let (held, next) = (edge_at(m, &mut b), edge_at(m + 1, &mut b));
        let a = m as f64 * dx;
        println!(
            "equilibrate at Johnson's d (a = 0.3 λ), {nx}×{NY}: a = {:.5} λ ({:+.2} elements \
             from Johnson's); edge p/σ_c {:.4} there, {:.4} one element wider",
            a / w.lambda,
            (a - a_j) / dx,
            held / sigma_c,
            next / sigma_c
        );
        assert!(held >= -sigma_c && next < -sigma_c, "{nx}: {held}, {next}");
    }
}

/// The energy release rate, in Δγ, that the edge criterion gives on `nx` elements a
/// wavelength for strips of `m` elements a side (the test above's measure).
fn criterion_g(w: &Wave, nx: usize, m: usize) -> f64 {
    let dx = w.lambda / nx as f64;
    let sigma_c = (w.e_star * w.work_of_adhesion / (kappa() * dx)).sqrt();
    let mut b = CpuBackend::new_periodic(&setup(w, nx)).unwrap();
    let sol = Affine::new(&mut b, &strips(nx, m), w.delta);
    let d = sol.d_for(nx / 2 + m - 1, -sigma_c);
    let k = w.stress_intensity(m as f64 * dx, sol.mean(d));
    k * k / (2.0 * w.e_star) / w.work_of_adhesion
}

/// Rows of the map (and elements along y: the map's nodes are the grid's element centres).
const MAP_ROWS: usize = 16;

/// The pull-off stress |min F| / (the period's area) of the wave written as an .npy map of
/// `nx` × [`MAP_ROWS`] nodes (one wavelength along x, uniform along y; its trough on the
/// seam, between the last node and the first), run through the library's request with the
/// periodic convolution on an `nx` grid: pressed on to 40 % of the period, pulled off.
fn pipeline_pull_off(w: &Wave, nx: usize, dir: &std::path::Path) -> f64 {
    let s = w.lambda / nx as f64;
    let heights = (0..nx * MAP_ROWS)
        .map(|k| w.height((((k % nx) as f64) + 0.5) * s))
        .collect();
    let map = HeightMap::new(nx, MAP_ROWS, s, heights).unwrap();
    let path = dir.join(format!("wave-{nx}.npy"));
    std::fs::write(
        &path,
        jkrbem::output::roughness_npy::npy_bytes(&map).unwrap(),
    )
    .unwrap();
    let path = path.display().to_string();
    let (e, dg, sp, grid) = (
        w.e_star.to_string(),
        w.work_of_adhesion.to_string(),
        s.to_string(),
        nx.to_string(),
    );
    let request = Request::from_texts([
        ("indenter", "height-map"),
        ("height_map", path.as_str()),
        ("spacing", sp.as_str()),
        ("e_star", e.as_str()),
        ("work_of_adhesion", dg.as_str()),
        ("convolution", "periodic"),
        ("grid", grid.as_str()),
        ("preload_area", "0.4"),
        ("backend", "cpu"),
    ])
    .unwrap();
    let simulated = simulate(
        &request.simulate_request(Sink::Memory, None).unwrap(),
        &jkrbem::session::Quiet,
    )
    .unwrap();
    let run = &simulated.runs[0];
    assert!(run.complete, "{:?}", simulated.failure);
    // The domain is the period: Δx the map's spacing, the rows the map's.
    assert_eq!(run.grid, (nx, MAP_ROWS));
    assert!((run.dx / s - 1.0).abs() < 1e-12, "{} vs {s}", run.dx);
    let min_f = run
        .states
        .iter()
        .map(|st| st.force)
        .fold(f64::INFINITY, f64::min);
    assert!(min_f < 0.0, "no adhesive force: {min_f}");
    -min_f / (w.lambda * MAP_ROWS as f64 * s)
}

#[test]
fn johnsons_wave_through_the_whole_pipeline() {
    // The wave above (α = 0.3), written as a map, pulled off through `simulate`. Johnson's
    // pull-off is the minimum of p̄(a) along his adhesive branch, which the approach-
    // controlled run passes through (it jumps off later, at the least approach). The edge
    // criterion's crack has G ≈ 1.82 Δγ, not Δγ (the test above: a grid-aligned straight
    // front, extrapolated Δx → 0), and on a grid its own G_h (first order in Δx, measured
    // there at Johnson's pull-off width): the pipeline must give Johnson's pull-off at G_h
    // (what the backend's criterion implies: the map, its period, the wrap across the seam,
    // the loading and the pull-off add nothing), and approach Johnson's at 1.822 Δγ as the
    // grid is refined. Its deviation from Johnson at the nominal Δγ is reported.
    let w = wave();
    let dir = tempfile::tempdir().unwrap();
    let johnson = |g: f64| {
        -Wave {
            work_of_adhesion: g * w.work_of_adhesion,
            ..w
        }
        .pull_off_mean_pressure()
        .unwrap()
    };
    let converged = 1.822;
    let mut deviations = Vec::new();
    for nx in [64usize, 128] {
        let dx = w.lambda / nx as f64;
        // G_h at Johnson's pull-off width for G_h itself (a fixed point, two rounds).
        let mut g = converged;
        for _ in 0..3 {
            let a1 = Wave {
                work_of_adhesion: g * w.work_of_adhesion,
                ..w
            }
            .pull_off_half_width()
            .unwrap();
            g = criterion_g(&w, nx, (a1 / dx).round() as usize);
        }
        let got = pipeline_pull_off(&w, nx, dir.path());
        let (at_grid, at_limit, nominal) = (johnson(g), johnson(converged), johnson(1.0));
        println!(
            "pipeline {nx}×{MAP_ROWS}: |min F|/area {got:.6e}; Johnson at the grid's G_h = \
             {g:.4} Δγ {at_grid:.6e} ({:+.2} %), at 1.822 Δγ {at_limit:.6e} ({:+.2} %), at Δγ \
             {nominal:.6e} ({:+.2} %)",
            100.0 * (got / at_grid - 1.0),
            100.0 * (got / at_limit - 1.0),
            100.0 * (got / nominal - 1.0),
        );
        // Measured (2026): −0.08 % at 64, +0.29 % at 128 (the contact's width moves by whole
        // elements, and G_h is taken at the nearest one).
        assert!(
            (got / at_grid - 1.0).abs() < 0.01,
            "{nx}: {got} against Johnson's {at_grid} at G_h = {g} Δγ"
        );
        deviations.push((got, got / at_limit - 1.0));
    }
    // First order towards Johnson at the criterion's 1.822 Δγ (measured +5.42 %, +2.73 %),
    // and the extrapolation 2 F(128) − F(64) on it (measured +0.05 %).
    let (coarse, fine) = (deviations[0], deviations[1]);
    let ratio = fine.1 / coarse.1;
    assert!((0.35..0.65).contains(&ratio), "{coarse:?} → {fine:?}");
    let extrapolated = 2.0 * fine.0 - coarse.0;
    let at_limit = johnson(converged);
    println!(
        "extrapolated 2 F(128) − F(64): {extrapolated:.6e}, {:+.2} % from Johnson at 1.822 Δγ",
        100.0 * (extrapolated / at_limit - 1.0)
    );
    assert!((extrapolated / at_limit - 1.0).abs() < 0.01);
}
