//! Timing what the solver spends its time on, on one model's grid: one convolution, one CG
//! iteration and one whole pull-off. Generic over [`Backend`]; it never knows which backend
//! runs it, so the same code times the CPU and the GPU.
//!
//! **Synchronisation.** A device backend may queue work and return before it has run. Every
//! timed repetition therefore ends with a blocking readback of one scalar (a masked dot
//! product into a spare slot, then [`Scalars::read_slots`](crate::backend::Scalars::read_slots)): when the clock stops, the work
//! has finished. Each timing thus includes one small reduction and one scalar readback.
//!
//! **Statistics.** Each short measurement (a convolution, a CG solve) is repeated untimed for
//! [`WARM_UP`] (at least once), then timed in `repeats` samples; a sample is the mean over a
//! group of calls lasting at least [`MIN_SAMPLE`] (a single call if it is longer). The median
//! of the samples is reported. Ratios between backends or grids are
//! only meaningful within one run on one machine.

#[cfg(feature = "gpu")]
use crate::backend::gpu::GpuBackend;
#[cfg(feature = "gpu")]
use crate::backend::FieldStore;
use crate::backend::{Backend, BackendError, Counters, Slot};
use crate::model::{CgSettings, Model};
use crate::solver::cg::{self, CgWork};
use crate::solver::{self, SolverError};
use std::time::{Duration, Instant};

/// How long each short measurement is repeated untimed first (thread pools, FFT plans, GPU
/// pipelines and caches settle).
pub const WARM_UP: Duration = Duration::from_millis(200);

/// Shortest sample: calls shorter than this are timed in groups, and a sample is the mean of
/// a group (scheduler noise and timer resolution then weigh little on sub-millisecond calls).
pub const MIN_SAMPLE: Duration = Duration::from_millis(20);

/// What to measure, and how often.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BenchOptions {
    /// Timed samples of each short measurement, after the warm-up; the median is reported.
    /// At least 1.
    pub repeats: usize,
    /// CG iterations per timed solve (the solve runs with tolerance 0, so it makes exactly
    /// this many unless the residual reaches exactly zero). At least 1.
    pub cg_iterations: usize,
    /// Whether to time a whole pull-off (slow on large grids), once.
    pub pulloff: bool,
}

impl Default for BenchOptions {
    fn default() -> Self {
        BenchOptions {
            repeats: 5,
            cg_iterations: 20,
            pulloff: true,
        }
    }
}

/// Backend work per CG iteration: differences of [`crate::backend::Device::counters`] over a solve, less
/// those of CG's start, divided by the iterations made.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WorkPerIteration {
    /// Compute kernels launched per iteration (0 on the CPU).
    pub dispatches: f64,
    /// Blocking host readbacks per iteration (CG reads its residual once per solve here, so
    /// 1 / iterations on a backend that counts readbacks).
    pub readbacks: f64,
    /// Queue submissions per iteration.
    pub submits: f64,
    /// Bytes the kernels read and wrote per iteration, as counted from their code (0 on the
    /// CPU).
    pub bytes: f64,
}

/// One timed pull-off (the whole protocol of [`solver::run`]).
#[derive(Debug)]
pub struct PulloffTiming {
    /// Wall time of the run (s).
    pub wall_s: f64,
    /// CG iterations over all states.
    pub cg_iterations: usize,
    /// States recorded.
    pub states: usize,
    /// The adhesive force |min F̄| (dimensionless), if any state was recorded.
    pub f_ad_bar: Option<f64>,
    /// Where the run spent its work: states, steps, onsets, rounds, solves, CG iterations
    /// and convolutions outside CG.
    pub cost: crate::solver::cost::CostAccount,
    /// Why the run stopped early, if it did (the other fields then describe the part run).
    pub error: Option<SolverError>,
    /// The backend's work over the run: dispatches, readbacks, submissions, bytes, and the
    /// host's time blocked on readbacks and submitting (zeros on the CPU).
    pub host: Counters,
}

/// One kernel's totals over a whole pull-off (GPU timestamps around each dispatch).
#[derive(Debug, Clone, PartialEq)]
pub struct KernelTotal {
    /// The kernel (WGSL entry point).
    pub kernel: &'static str,
    /// Its dispatches.
    pub dispatches: u64,
    /// Its GPU time, summed between each dispatch's timestamps (s).
    pub seconds: f64,
    /// Bytes it read and wrote in device memory, as counted from its code.
    pub bytes: u64,
}

/// Where a whole pull-off's wall time goes on a device: the unprofiled run's wall time and
/// the host's blocked reads and submissions, and a second, profiled run's GPU time per
/// kernel (profiling submits and waits every 1024 dispatches, so that run's wall time is
/// longer; its kernel times are not).
#[derive(Debug, Clone)]
pub struct PulloffProfile {
    /// "--backends gpu 2048×1024".
    pub label: String,
    /// Wall time of the unprofiled pull-off (s).
    pub wall_s: f64,
    /// Its CG iterations.
    pub cg_iterations: usize,
    /// Its cascade rounds.
    pub rounds: usize,
    /// The backend's work over it (readbacks, submissions, the host's blocked time).
    pub host: Counters,
    /// Wall time of the profiled run (s).
    pub profiled_wall_s: f64,
    /// Per kernel, over the profiled run, slowest first.
    pub kernels: Vec<KernelTotal>,
}

impl PulloffProfile {
    /// The kernels' summed GPU time (s).
    pub fn kernel_s(&self) -> f64 {
        self.kernels.iter().map(|k| k.seconds).sum()
    }
}

/// Everything measured for one backend on one grid.
#[derive(Debug)]
pub struct Measurement {
    /// Backend name ("cpu", "gpu").
    pub backend: &'static str,
    /// Arithmetic precision of its fields ("f64", "f32").
    pub precision: &'static str,
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Repetitions each median is taken over.
    pub repeats: usize,
    /// Median time of one convolution u = K ∗ p, readback included (ms).
    pub convolution_ms: f64,
    /// Median time of one preconditioned CG iteration on the initial Hertz contact set, CG's
    /// start excluded (ms).
    pub cg_iteration_ms: f64,
    /// CG iterations per timed solve.
    pub cg_iterations: usize,
    /// Backend work per CG iteration.
    pub work_per_iteration: WorkPerIteration,
    /// The pull-off, if it was asked for.
    pub pulloff: Option<PulloffTiming>,
}

/// Median of `samples` (the mean of the middle two for an even count); NaN if empty.
pub fn median(samples: &mut [f64]) -> f64 {
    if samples.is_empty() {
        return f64::NAN;
    }
    samples.sort_by(f64::total_cmp);
    let n = samples.len();
    if n % 2 == 1 {
        samples[n / 2]
    } else {
        0.5 * (samples[n / 2 - 1] + samples[n / 2])
    }
}

/// A pressure (arbitrary stress units) shaped like the Hertz pressure of the model's first
/// contact, √(1 − x²/a² − y²/b²) inside the ellipse and 0 outside, row-major nx × ny.
pub fn hertz_like_pressure(model: &Model) -> Vec<f64> {
    let (a, b) = (model.initial.a, model.initial.b);
    let mut p = Vec::with_capacity(model.nx * model.ny);
    for j in 0..model.ny {
        for i in 0..model.nx {
            let (x, y) = (model.x(i) / a, model.y(j) / b);
            p.push((1.0 - x * x - y * y).max(0.0).sqrt());
        }
    }
    p
}

/// Wait until the backend has finished the work queued so far, by reading back Σ_C f·f over
/// the contact set `c` into the register `sync` (one of the bench's own, not CG's).
fn sync<B: Backend>(
    backend: &mut B,
    c: &B::Mask,
    f: &B::Field,
    sync: Slot,
) -> Result<(), BackendError> {
    backend.dot(c, f, f, sync)?;
    let mut v = [0.0];
    backend.read_slots(&[sync], &mut v)?;
    std::hint::black_box(v);
    Ok(())
}

/// Samples of the duration of `f` (ms per call): calls until [`WARM_UP`] has passed (at
/// least one, untimed), then `repeats` samples, each the mean over a group of calls that
/// lasts about [`MIN_SAMPLE`] (one call if a call is longer). `f` returns the duration of
/// the part of the call to be timed.
fn repeat_ms<E>(repeats: usize, mut f: impl FnMut() -> Result<Duration, E>) -> Result<Vec<f64>, E> {
    let t0 = Instant::now();
    let (mut calls, mut spent) = (0u32, Duration::ZERO);
    loop {
        spent += f()?;
        calls += 1;
        if t0.elapsed() >= WARM_UP {
            break;
        }
    }
    let per_call = spent.as_secs_f64() / f64::from(calls);
    let group = (MIN_SAMPLE.as_secs_f64() / per_call.max(1e-9))
        .ceil()
        .clamp(1.0, 1e6) as usize;
    (0..repeats)
        .map(|_| {
            let mut sum = Duration::ZERO;
            for _ in 0..group {
                sum += f()?;
            }
            Ok(sum.as_secs_f64() * 1e3 / group as f64)
        })
        .collect()
}

/// Difference `after − before` of two counter readings, per `n` (0 if `n` is 0).
fn per(before: Counters, after: Counters, n: usize) -> WorkPerIteration {
    let n = n.max(1) as f64;
    WorkPerIteration {
        dispatches: after.dispatches.saturating_sub(before.dispatches) as f64 / n,
        readbacks: after.readbacks.saturating_sub(before.readbacks) as f64 / n,
        submits: after.submits.saturating_sub(before.submits) as f64 / n,
        bytes: after.bytes.saturating_sub(before.bytes) as f64 / n,
    }
}

/// The counters' growth from `before` to `after`.
fn delta(before: Counters, after: Counters) -> Counters {
    Counters {
        dispatches: after.dispatches - before.dispatches,
        readbacks: after.readbacks - before.readbacks,
        readback_bytes: after.readback_bytes - before.readback_bytes,
        submits: after.submits - before.submits,
        bytes: after.bytes - before.bytes,
        wait_ns: after.wait_ns - before.wait_ns,
        submit_ns: after.submit_ns - before.submit_ns,
    }
}

/// Time the convolution: one call of `convolve` on a Hertz-like pressure, ended by a scalar
/// readback; the median of `repeats` samples (ms).
pub fn time_convolution<B: Backend>(
    backend: &mut B,
    model: &Model,
    repeats: usize,
) -> Result<f64, BackendError> {
    let mut p = backend.field()?;
    backend.upload(&mut p, &hertz_like_pressure(model))?;
    let mut u = backend.field()?;
    let slot = backend.slot()?;
    let c = first_contact(backend, model)?;
    let mut t = repeat_ms(repeats, || {
        let t0 = Instant::now();
        backend.convolve(&p, &mut u)?;
        sync(backend, &c, &u, slot)?;
        Ok(t0.elapsed())
    })?;
    Ok(median(&mut t))
}

/// The model's first contact set (its initial Hertz ellipse) on the device.
fn first_contact<B: Backend>(backend: &mut B, model: &Model) -> Result<B::Mask, BackendError> {
    let mut c = backend.mask()?;
    backend.upload_mask(&mut c, &model.initial_contact())?;
    Ok(c)
}

/// Time CG iterations on the model's first contact set at its first approach
/// d0: the difference of the median times (ms, `repeats` samples each) and of the counter
/// deltas of a solve of `iterations` iterations and of CG's start alone (0 iterations), each
/// from p = 0 and ended by a scalar readback, divided by the iterations made.
/// Returns (ms per iteration, iterations made, work per iteration).
pub fn time_cg_iteration<B: Backend>(
    backend: &mut B,
    model: &Model,
    repeats: usize,
    iterations: usize,
) -> Result<(f64, usize, WorkPerIteration), BackendError> {
    let mut work = CgWork::new(backend)?;
    let mut p = backend.field()?;
    let slot = backend.slot()?;
    let c = first_contact(backend, model)?;
    let zeros = vec![0.0; model.nx * model.ny];
    // Tolerance 0: never converged, so CG makes `max_iterations` iterations and reads its
    // residual back once, at the end.
    let settings = |max_iterations| CgSettings {
        tolerance: 0.0,
        max_iterations,
        check_every: usize::MAX,
        accept: model.cg.accept,
    };
    let mut made = 0;
    let mut counted = [Counters::default(); 2];
    let mut run = |n: usize, made: &mut usize, counted: &mut Counters| {
        repeat_ms(repeats, || {
            backend.upload(&mut p, &zeros)?;
            let before = backend.counters();
            let t0 = Instant::now();
            let report = cg::solve(backend, &c, &mut work, &mut p, model.load.d0, &settings(n))?;
            sync(backend, &c, &p, slot)?;
            let elapsed = t0.elapsed();
            let after = backend.counters();
            *made = report.iterations;
            *counted = delta(before, after);
            Ok::<_, BackendError>(elapsed)
        })
    };
    let mut start = run(0, &mut 0, &mut counted[0])?;
    let mut full = run(iterations, &mut made, &mut counted[1])?;
    let t = (median(&mut full) - median(&mut start)).max(0.0) / made.max(1) as f64;
    Ok((t, made, per(counted[0], counted[1], made)))
}

/// One kernel's share of a CG iteration, from GPU timestamps.
#[derive(Debug, Clone, PartialEq)]
pub struct KernelProfile {
    /// The kernel (its WGSL entry point).
    pub kernel: &'static str,
    /// Dispatches of it per CG iteration.
    pub dispatches_per_iteration: f64,
    /// GPU time per CG iteration, from each dispatch's start and end timestamps (ms).
    pub ms_per_iteration: f64,
    /// Bytes it reads and writes per CG iteration, as counted from its code.
    pub bytes_per_iteration: f64,
}

impl KernelProfile {
    /// Achieved bandwidth (GB/s = 1e9 bytes/s); 0 if no time was measured.
    pub fn gb_per_s(&self) -> f64 {
        if self.ms_per_iteration > 0.0 {
            self.bytes_per_iteration / (self.ms_per_iteration * 1e-3) / 1e9
        } else {
            0.0
        }
    }
}

/// Profile CG iterations on the GPU with timestamp queries: every kernel of a solve of
/// `iterations` iterations (from p = 0 at the model's first approach, on its first
/// contact set, tolerance 0) less those of CG's start alone, per iteration, slowest first.
/// Fails where the adapter cannot write timestamps.
#[cfg(feature = "gpu")]
pub fn profile_cg_iteration(
    gpu: &mut GpuBackend,
    model: &Model,
    iterations: usize,
) -> Result<Vec<KernelProfile>, BackendError> {
    let mut work = CgWork::new(gpu)?;
    let mut p = gpu.field()?;
    let c = first_contact(gpu, model)?;
    let zeros = vec![0.0; model.nx * model.ny];
    let mut solve = |gpu: &mut GpuBackend, n: usize| {
        gpu.upload(&mut p, &zeros)?;
        gpu.set_profiling(true)?;
        let settings = CgSettings {
            tolerance: 0.0,
            max_iterations: n,
            check_every: usize::MAX,
            accept: model.cg.accept,
        };
        let made = cg::solve(gpu, &c, &mut work, &mut p, model.load.d0, &settings)?.iterations;
        let profile = gpu.profile()?.unwrap_or_default();
        gpu.set_profiling(false)?;
        Ok::<_, BackendError>((made, profile))
    };
    // A warm-up solve first: pipelines, caches and clocks settle.
    solve(gpu, iterations)?;
    let (made, full) = solve(gpu, iterations)?;
    let (_, start) = solve(gpu, 0)?;
    let per = made.max(1) as f64;
    let mut rows: Vec<KernelProfile> = full
        .iter()
        .map(|(&kernel, t)| {
            let s = start.get(kernel).copied().unwrap_or_default();
            KernelProfile {
                kernel,
                dispatches_per_iteration: t.dispatches.saturating_sub(s.dispatches) as f64 / per,
                ms_per_iteration: (t.seconds - s.seconds).max(0.0) * 1e3 / per,
                bytes_per_iteration: t.bytes.saturating_sub(s.bytes) as f64 / per,
            }
        })
        .filter(|r| r.dispatches_per_iteration > 0.0)
        .collect();
    rows.sort_by(|a, b| b.ms_per_iteration.total_cmp(&a.ms_per_iteration));
    Ok(rows)
}

/// Profile a whole pull-off of `model` on the GPU: `timed` is its unprofiled run (wall time,
/// readbacks, the host's blocked time); this runs it again with a timestamp around every
/// dispatch and totals the GPU time per kernel. Fails where the adapter cannot write
/// timestamps.
#[cfg(feature = "gpu")]
pub fn profile_pulloff(
    gpu: &mut GpuBackend,
    model: &Model,
    timed: &PulloffTiming,
    label: String,
) -> Result<PulloffProfile, BackendError> {
    gpu.set_profiling(true)?;
    let t0 = Instant::now();
    let outcome = solver::run(gpu, model, &mut |_| {});
    let profiled_wall_s = t0.elapsed().as_secs_f64();
    let totals = gpu.profile()?.unwrap_or_default();
    gpu.set_profiling(false)?;
    if let Some(e) = outcome.error {
        return Err(BackendError::Unavailable(format!(
            "the profiled pull-off stopped early: {e}"
        )));
    }
    let mut kernels: Vec<KernelTotal> = totals
        .iter()
        .map(|(&kernel, t)| KernelTotal {
            kernel,
            dispatches: t.dispatches,
            seconds: t.seconds,
            bytes: t.bytes,
        })
        .collect();
    kernels.sort_by(|a, b| b.seconds.total_cmp(&a.seconds));
    Ok(PulloffProfile {
        label,
        wall_s: timed.wall_s,
        cg_iterations: timed.cg_iterations,
        rounds: timed.cost.work.rounds,
        host: timed.host,
        profiled_wall_s,
        kernels,
    })
}

/// Time one whole pull-off of `model` ([`solver::run`], which resets the contact set).
pub fn time_pulloff<B: Backend>(backend: &mut B, model: &Model) -> PulloffTiming {
    let before = backend.counters();
    let t0 = Instant::now();
    let outcome = solver::run(backend, model, &mut |_| {});
    let wall_s = t0.elapsed().as_secs_f64();
    PulloffTiming {
        host: delta(before, backend.counters()),
        wall_s,
        cg_iterations: outcome.cg_iterations(),
        states: outcome.states.len(),
        f_ad_bar: outcome.force_minimum().map(|s| s.f_bar.abs()),
        cost: outcome.cost,
        error: outcome.error,
    }
}

/// Measure everything for `model` on `backend`: the convolution and the CG iteration (on the
/// initial Hertz contact set), then, if asked, a whole pull-off. `progress` is told what is
/// about to run.
pub fn measure<B: Backend>(
    backend: &mut B,
    model: &Model,
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<Measurement, BackendError> {
    let repeats = options.repeats.max(1);
    progress("convolution");
    let convolution_ms = time_convolution(backend, model, repeats)?;
    progress("CG iteration");
    let (cg_iteration_ms, cg_iterations, work_per_iteration) =
        time_cg_iteration(backend, model, repeats, options.cg_iterations.max(1))?;
    let pulloff = if options.pulloff {
        progress("pull-off");
        Some(time_pulloff(backend, model))
    } else {
        None
    };
    Ok(Measurement {
        backend: backend.name(),
        precision: backend.precision(),
        nx: model.nx,
        ny: model.ny,
        repeats,
        convolution_ms,
        cg_iteration_ms,
        cg_iterations,
        work_per_iteration,
        pulloff,
    })
}

/// One grid's kernel profile.
#[derive(Debug, Clone)]
pub struct GridProfile {
    /// "--backends gpu 256×256".
    pub label: String,
    /// Per kernel, per CG iteration.
    pub kernels: Vec<KernelProfile>,
    /// The bytes one CG iteration must move at least (its floor).
    pub floor_bytes: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
        assert!(median(&mut []).is_nan());
    }

    #[test]
    fn counter_differences_per_iteration() {
        let c = |d, r, s, b| Counters {
            dispatches: d,
            readbacks: r,
            submits: s,
            bytes: b,
            ..Counters::default()
        };
        let w = per(c(4, 1, 2, 100), c(204, 2, 22, 2100), 20);
        assert_eq!(
            [w.dispatches, w.readbacks, w.submits, w.bytes],
            [10.0, 0.05, 1.0, 100.0]
        );
    }
}
