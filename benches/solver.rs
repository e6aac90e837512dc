//! Cost of the CPU solver against its FFT floor, on the sphere scene (R1/R2 = 1).
//!
//! Measures, for square grids N = 64, 128, 256, 512:
//! - one CG iteration on the backend (the exact call sequence of `cg::solve`'s loop) on the
//!   Hertz initial contact set, with the stiffness preconditioner and without;
//! - the bare FFT pairs it cannot avoid: a forward r2c + inverse c2r 2-D transform of the
//!   padded 2N × 2N grid (the convolution) and of the N × N grid (the preconditioner);
//!
//! then prints a summary table (medians of simple repeated timings) with the ratios
//! t_iter / t_fft_pair, and the CG iterations per converged state of full pull-offs at
//! N = 64, 128 (and 256 with `JKRBEM_BENCH_FULL=1`), with and without preconditioner.
//!
//! Run: `cargo bench --bench solver` (add `JKRBEM_BENCH_FULL=1` for the N = 256 pull-off;
//! criterion's filter, e.g. `-- cg_iteration`, narrows its part but the summary always runs).

use criterion::Criterion;
use jkrbem::backend::cpu::spectral::SpectralFilter;
use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::prelude::*;
use jkrbem::backend::{Preconditioner, Slot};
use jkrbem::model::{Model, ModelOptions};
use jkrbem::scene::Scene;
use jkrbem::solver::{self, Phase};
use std::hint::black_box;
use std::time::{Duration, Instant};

const GRIDS: [usize; 4] = [64, 128, 256, 512];
const PRECONDITIONERS: [(Preconditioner, &str); 2] = [
    (Preconditioner::None, "none"),
    (Preconditioner::Stiffness, "stiffness"),
];
/// CG's registers (as in `solver::cg`): r·z, previous r·z, s·Ks, r·r, and one never written.
struct Registers {
    rz: Slot,
    rz_old: Slot,
    sq: Slot,
    rr: Slot,
    zero: Slot,
}
/// Iterations after which the CG state is restarted (so it never runs into round-off).
const RESTART: usize = 50;

fn model(n: usize, preconditioner: Preconditioner) -> Model {
    let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).expect("the sphere scene is valid");
    let opt = ModelOptions {
        nx: n,
        preconditioner,
        ..Default::default()
    };
    Model::build(&scene, &opt).expect("the grids are powers of two")
}

fn backend(model: &Model) -> CpuBackend {
    let setup = model.grid_setup();
    CpuBackend::new(&setup).expect("the profile fits the grid")
}

/// A CG solve in progress on the initial contact set: its fields and its iteration count.
struct CgState {
    backend: CpuBackend,
    /// The contact set (the model's first).
    c: Vec<bool>,
    d: f64,
    p: Vec<f64>,
    r: Vec<f64>,
    z: Vec<f64>,
    s: Vec<f64>,
    q: Vec<f64>,
    done: usize,
    slots: Registers,
}

impl CgState {
    fn new(n: usize, preconditioner: Preconditioner) -> Self {
        let model = model(n, preconditioner);
        let mut backend = backend(&model);
        let c = model.initial_contact();
        let zero = vec![0.0; model.nx * model.ny];
        let mut slot = || backend.slot().expect("the CPU has registers");
        let slots = Registers {
            rz: slot(),
            rz_old: slot(),
            sq: slot(),
            rr: slot(),
            zero: slot(),
        };
        let mut st = CgState {
            slots,
            backend,
            c,
            d: model.load.d0,
            p: zero.clone(),
            r: zero.clone(),
            z: zero.clone(),
            s: zero.clone(),
            q: zero,
            done: 0,
        };
        st.restart();
        st
    }

    /// CG's start from p = 0: r = (d − h)_C, z = M r, s = z.
    fn restart(&mut self) {
        let (b, k) = (&mut self.backend, &self.slots);
        self.p.iter_mut().for_each(|v| *v = 0.0);
        b.residual(&self.c, &self.p, self.d, &mut self.r).unwrap();
        b.precondition(&self.c, &self.r, &mut self.z).unwrap();
        b.dot(&self.c, &self.r, &self.z, k.rz).unwrap();
        b.xpay_ratio(&self.c, &mut self.s, &self.z, k.zero, k.zero)
            .unwrap();
        self.done = 0;
    }

    /// One iteration of `cg::solve`'s loop, residual check included; returns its duration.
    fn iterate(&mut self) -> Duration {
        if self.done == RESTART {
            self.restart();
        }
        self.done += 1;
        let (b, k, t0) = (&mut self.backend, &self.slots, Instant::now());
        b.convolve(&self.s, &mut self.q).unwrap();
        b.dot(&self.c, &self.s, &self.q, k.sq).unwrap();
        b.axpy_ratio(&self.c, &mut self.p, &self.s, k.rz, k.sq, 1.0)
            .unwrap();
        b.axpy_ratio(&self.c, &mut self.r, &self.q, k.rz, k.sq, -1.0)
            .unwrap();
        b.dot(&self.c, &self.r, &self.r, k.rr).unwrap();
        let mut rr = [0.0];
        b.read_slots(&[k.rr], &mut rr).unwrap();
        black_box(rr);
        b.copy_slot(k.rz, k.rz_old).unwrap();
        b.precondition(&self.c, &self.r, &mut self.z).unwrap();
        b.dot(&self.c, &self.r, &self.z, k.rz).unwrap();
        b.xpay_ratio(&self.c, &mut self.s, &self.z, k.rz, k.rz_old)
            .unwrap();
        t0.elapsed()
    }
}

/// A forward + inverse 2-D real FFT of a full m × m field (unit symbol, no padding).
struct FftPair {
    filter: SpectralFilter,
    src: Vec<f64>,
    dst: Vec<f64>,
}

impl FftPair {
    fn new(m: usize) -> Self {
        let src = (0..m * m).map(|i| (i as f64 * 0.37).sin()).collect();
        FftPair {
            filter: SpectralFilter::new(m, m, m, m),
            src,
            dst: vec![0.0; m * m],
        }
    }
    fn run(&mut self) {
        self.filter.apply(black_box(&self.src), &mut self.dst);
        black_box(&self.dst);
    }
}

fn criterion_benches(c: &mut Criterion) {
    let mut g = c.benchmark_group("cg_iteration");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for (pre, name) in PRECONDITIONERS {
        for n in GRIDS {
            let mut st = CgState::new(n, pre);
            g.bench_function(format!("{name}/{n}"), |b| {
                b.iter_custom(|iters| (0..iters).map(|_| st.iterate()).sum())
            });
        }
    }
    g.finish();
    let mut g = c.benchmark_group("fft_pair");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for n in GRIDS {
        for (m, label) in [(2 * n, "padded_2n"), (n, "n")] {
            let mut fft = FftPair::new(m);
            g.bench_function(format!("{label}/{n}"), |b| b.iter(|| fft.run()));
        }
    }
    g.finish();
}

/// Median in ms of timings of `f`: after 0.2 s of warm-up, at least `reps` of them and at
/// least 0.5 s worth (so that the short ones are not at the mercy of a single hiccup).
fn median_ms(reps: usize, mut f: impl FnMut() -> Duration) -> f64 {
    let t0 = Instant::now();
    while t0.elapsed() < Duration::from_millis(200) {
        f();
    }
    let (mut t, t0) = (Vec::new(), Instant::now());
    while t.len() < reps || (t0.elapsed() < Duration::from_millis(500) && t.len() < 10_000) {
        t.push(f().as_secs_f64() * 1e3);
    }
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn timed(f: impl FnOnce()) -> Duration {
    let t0 = Instant::now();
    f();
    t0.elapsed()
}

fn summary(cores: usize) {
    const REPS: usize = 20;
    println!(
        "\n## CG iteration vs FFT floor (sphere, medians of ≥ {REPS} timings, {cores} cores)\n"
    );
    println!("| grid | cores | t_iter none (ms) | t_iter stiffness (ms) | t_fft_pair 2N² (ms) | t_fft_pair N² (ms) | none / 2N² pair | stiffness / (2N² + N² pair) |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|");
    for n in GRIDS {
        let [none, stiff] = PRECONDITIONERS.map(|(pre, _)| {
            let mut st = CgState::new(n, pre);
            median_ms(REPS, || st.iterate())
        });
        let [big, small] = [2 * n, n].map(|m| {
            let mut fft = FftPair::new(m);
            median_ms(REPS, || timed(|| fft.run()))
        });
        println!(
            "| {n}² | {cores} | {none:.3} | {stiff:.3} | {big:.3} | {small:.3} | {:.2} | {:.2} |",
            none / big,
            stiff / (big + small)
        );
    }

    let full = std::env::var("JKRBEM_BENCH_FULL").is_ok_and(|v| v == "1");
    let grids: &[usize] = if full { &[64, 128, 256] } else { &[64, 128] };
    println!("\n## Full sphere pull-off (CPU, {cores} cores)\n");
    println!("| grid | preconditioner | cores | wall (s) | CG iterations | states | sweeps | it / pull-off state | it / solve | \\|min F̄\\| |");
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &n in grids {
        for (pre, name) in PRECONDITIONERS {
            let model = model(n, pre);
            let mut backend = backend(&model);
            let t0 = Instant::now();
            let out = solver::run(&mut backend, &model, &mut |_| {});
            let wall = t0.elapsed().as_secs_f64();
            if let Some(e) = &out.error {
                println!("| {n}² | {name} | {cores} | {wall:.1} | run stopped early: {e} |");
                continue;
            }
            let total = out.cg_iterations();
            let sweeps: usize = out.states.iter().map(|s| s.detach_sweeps).sum();
            let pulloff: Vec<_> = out
                .states
                .iter()
                .filter(|s| s.phase == Phase::Pulloff)
                .collect();
            let per_state = pulloff.iter().map(|s| s.cg_iterations).sum::<usize>() as f64
                / pulloff.len().max(1) as f64;
            let per_solve = total as f64 / (out.states.len() + sweeps) as f64;
            let f_min = out.force_minimum().map_or(f64::NAN, |s| s.f_bar.abs());
            println!(
                "| {n}² | {name} | {cores} | {wall:.1} | {total} | {} | {sweeps} | {per_state:.1} | {per_solve:.1} | {f_min:.4} |",
                out.states.len()
            );
        }
    }
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    criterion_benches(&mut c);
    c.final_summary();
    // `cargo test --benches` runs this without `--bench`: skip the long summary there.
    let args: Vec<String> = std::env::args().collect();
    if args.iter().any(|a| a == "--bench") && !args.iter().any(|a| a == "--list") {
        summary(std::thread::available_parallelism().map_or(1, |n| n.get()));
    }
}
