//! Preconditioned conjugate gradients on a fixed contact set C:
//! (K p)_C = (d − h)_C, p = 0 off C. The system is symmetric positive definite on C.
//!
//! All vectors and CG's scalars stay on the backend's device; the host reads the residual
//! norm back only every `check_every` iterations to decide convergence.
//!
//! Two modes, both generic over the backend:
//! - [`solve`], the normal mode, follows the recurrence residual r ← r − α K s. Its checked
//!   values form a [`ResidualHistory`] that ends the solve early when it stagnates or
//!   diverges. When the recurrence reaches the tolerance, the true residual (d − h − K p)_C is
//!   recomputed once from p: in finite precision the recurrence goes on falling far below the
//!   arithmetic's floor (measured in f32: to 1e-24 and then 0, while the true residual stays
//!   at 8.6e-8), so only the true residual can tell that the tolerance is out of reach.
//! - [`solve_safe`], the safer mode, reads the residual every iteration and restarts CG from
//!   the true residual at least every [`REPLACE_EVERY`] iterations (residual replacement, which
//!   removes the drift of the recurrence); its history holds true residuals only, and it
//!   returns the best p it saw.

use crate::backend::{BackendError, CgKernels, CgStop, Slot};
use crate::model::CgSettings;
use std::fmt;

/// CG's scalar registers on the backend's device.
#[derive(Debug, Clone, Copy)]
pub struct CgSlots {
    /// r·z: the two slots take turns (the current iteration's and the previous one's), so
    /// that the new direction β = r·z / (r·z)_old needs no copy of a slot.
    rz: [Slot; 2],
    /// s·(K s).
    sq: Slot,
    /// r·r.
    rr: Slot,
    /// ‖(d − h)_C‖², the right-hand side's norm.
    bb: Slot,
    /// r·r of the warm start, kept where its read is deferred to the first progress read
    /// ([`CgKernels::defers_cg_start`]).
    rr_start: Slot,
    /// max over C of |M r|, the error estimate read with a solve's last read.
    eps: Slot,
    /// A register that is never written, so it stays 0.
    zero: Slot,
}

impl CgSlots {
    /// Registers for one CG workspace, handed out by `backend`.
    pub fn new<B: CgKernels>(backend: &mut B) -> Result<Self, BackendError> {
        Ok(CgSlots {
            rz: [backend.slot()?, backend.slot()?],
            sq: backend.slot()?,
            rr: backend.slot()?,
            bb: backend.slot()?,
            rr_start: backend.slot()?,
            eps: backend.slot()?,
            zero: backend.slot()?,
        })
    }
}

/// A checked residual above this multiple of the best one so far means CG has diverged.
/// CG's residual norm is not monotone, but in healthy solves it rises above its best by a
/// few times at most; a rise of three orders of magnitude is not round-off.
pub const DIVERGENCE_FACTOR: f64 = 1e3;
/// CG has stagnated when its best residual has not fallen below this fraction of the best
/// residual one stagnation window earlier.
pub const STAGNATION_FACTOR: f64 = 0.5;
/// The stagnation window is at least this many iterations. Preconditioned CG on this problem
/// halves its residual in one or two iterations, unpreconditioned CG in a few; 50 leaves a
/// wide margin for a slow stretch and still stops a stalled solve long before the limit.
pub const STAGNATION_MIN_WINDOW: usize = 50;
/// … and at least this fraction of the iterations made so far, so that a long solve that
/// still converges slowly is given more patience.
pub const STAGNATION_WINDOW_FRACTION: f64 = 0.25;
/// … and at least this many residual checks.
pub const STAGNATION_MIN_CHECKS: usize = 3;
/// A solve whose recurrence residual reached the tolerance counts as converged when its true
/// residual, recomputed from p, is within this factor of the tolerance. The recurrence is
/// trusted that far because f32 arithmetic (the GPU backend) cannot bring the true residual
/// below about 1e-7 whatever the recurrence says, and the default tolerance is 1e-8: over
/// whole GPU pull-offs at 32² and 64² the worst true residual was 1.5e-7.
pub const TRUE_RESIDUAL_SLACK: f64 = 100.0;
/// The safer mode recomputes the true residual, and restarts CG from it, at least every
/// this many iterations (and whenever the recurrence reaches the tolerance).
pub const REPLACE_EVERY: usize = 50;

/// The work fields CG needs, allocated once per run.
pub struct CgWork<F> {
    /// Residual r (length).
    pub r: F,
    /// Preconditioned residual z.
    pub z: F,
    /// Search direction s.
    pub s: F,
    /// K s (length); K p after a solve that ended [`CgEnd::Converged`].
    pub q: F,
    /// The pressure of the smallest true residual in the safer mode (force/length²).
    best: F,
    /// A field that stays zero (to evaluate the right-hand side d − h).
    zero: F,
    /// The scalar registers.
    slots: CgSlots,
    /// Whether an exact solve on a backend that defers its reads also reads its error
    /// estimate ([`CgReport::error_estimate`]) with its last read (a loose solve always
    /// does); false until the caller asks.
    pub estimate_exact: bool,
}

impl<F> CgWork<F> {
    /// Allocate the work fields on `backend`.
    pub fn new<B: CgKernels<Field = F>>(backend: &mut B) -> Result<Self, BackendError> {
        Ok(CgWork {
            slots: CgSlots::new(backend)?,
            r: backend.field()?,
            z: backend.field()?,
            s: backend.field()?,
            q: backend.field()?,
            best: backend.field()?,
            zero: backend.field()?,
            estimate_exact: false,
        })
    }

    /// A field that is zero everywhere.
    pub fn zero(&self) -> &F {
        &self.zero
    }
}

/// What ended a CG solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CgEnd {
    /// The tolerance was reached, by the true residual within [`TRUE_RESIDUAL_SLACK`].
    Converged,
    /// The best residual stopped improving (see [`ResidualHistory`]).
    Stagnated,
    /// The residual grew above [`DIVERGENCE_FACTOR`] times its best.
    Diverged,
    /// A NaN or infinity appeared.
    NonFinite,
    /// The iteration limit was reached first.
    IterationLimit,
    /// The recurrence residual reached the tolerance but the true one, recomputed from p,
    /// stayed above [`TRUE_RESIDUAL_SLACK`] times it: the arithmetic's precision floor.
    ResidualGap,
}

impl fmt::Display for CgEnd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            CgEnd::Converged => "converged",
            CgEnd::Stagnated => "stagnated (its best residual stopped halving)",
            CgEnd::Diverged => "diverged (its residual rose 1000 times above its best)",
            CgEnd::NonFinite => "produced a non-finite value",
            CgEnd::IterationLimit => {
                return write!(
                    f,
                    "reached the iteration limit ({})",
                    crate::params::CG_MAX_ITERATIONS
                )
            }
            CgEnd::ResidualGap => {
                "reached the tolerance in its recurrence but not in the true residual \
                 recomputed from p (the arithmetic's precision floor)"
            }
        })
    }
}

/// How a CG solve ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CgReport {
    /// Iterations made (convolutions of a search direction).
    pub iterations: usize,
    /// Relative residual ‖r‖/‖(d − h)_C‖ of the p returned (dimensionless): the true
    /// residual, recomputed from p, when the solve ended converged or with a residual gap
    /// and always in the safer mode; otherwise the recurrence's at the last check.
    pub residual: f64,
    /// The smallest relative residual the solve's checks saw (dimensionless).
    pub best: f64,
    /// What ended the solve.
    pub end: CgEnd,
    /// Convolutions made outside the iterations: the start residual (unless K p was
    /// given) and each recomputed true residual.
    pub convolutions: usize,
    /// max over C of |M r| for the r the solve left (stress), read with its last read on a
    /// backend that defers its reads ([`CgKernels::defers_cg_start`]): a loose solve's that
    /// converged, an exact one's with [`CgWork::estimate_exact`]; `None` otherwise, where
    /// the caller that needs it computes it.
    pub error_estimate: Option<f64>,
}

impl CgReport {
    /// Whether the tolerance was reached.
    pub fn converged(&self) -> bool {
        self.end == CgEnd::Converged
    }
}

/// The checked relative residuals of one solve, and the verdict they give. A check that is
/// not finite ends the solve as [`CgEnd::NonFinite`]; one above [`DIVERGENCE_FACTOR`] times
/// the best before it as [`CgEnd::Diverged`]; and the solve has [`CgEnd::Stagnated`] when
/// the best residual has not fallen below [`STAGNATION_FACTOR`] times the best residual of a
/// window earlier, the window being the largest of [`STAGNATION_MIN_WINDOW`] iterations,
/// [`STAGNATION_WINDOW_FRACTION`] of the iterations made and [`STAGNATION_MIN_CHECKS`] checks.
#[derive(Debug, Clone)]
pub struct ResidualHistory {
    /// (iteration, best relative residual up to it), one entry per check.
    best: Vec<(usize, f64)>,
    /// The smallest window (iterations).
    min_window: usize,
}

impl ResidualHistory {
    /// An empty history for checks every `check_every` iterations.
    pub fn new(check_every: usize) -> Self {
        ResidualHistory {
            best: Vec::new(),
            min_window: STAGNATION_MIN_WINDOW
                .max(STAGNATION_MIN_CHECKS.saturating_mul(check_every)),
        }
    }

    /// The smallest relative residual recorded (infinity before the first).
    pub fn best(&self) -> f64 {
        self.best.last().map_or(f64::INFINITY, |b| b.1)
    }

    /// The stagnation window (iterations) at `iteration`.
    pub fn window(&self, iteration: usize) -> usize {
        let fraction = (STAGNATION_WINDOW_FRACTION * iteration as f64).ceil() as usize;
        self.min_window.max(fraction)
    }

    /// Record the relative residual checked after `iteration` iterations (iterations must
    /// increase); returns what ends the solve, if the history says it should end.
    pub fn push(&mut self, iteration: usize, residual: f64) -> Option<CgEnd> {
        if !residual.is_finite() {
            return Some(CgEnd::NonFinite);
        }
        let best = self.best();
        if residual > DIVERGENCE_FACTOR * best {
            return Some(CgEnd::Diverged);
        }
        let best = best.min(residual);
        self.best.push((iteration, best));
        let earlier = iteration.checked_sub(self.window(iteration))?;
        let n = self.best.partition_point(|&(k, _)| k <= earlier);
        let then = self.best[..n].last()?.1;
        (best > STAGNATION_FACTOR * then).then_some(CgEnd::Stagnated)
    }
}

/// Turns r·r into the relative residual ‖r‖/‖(d − h)_C‖ (the absolute one if d − h = 0 on C).
#[derive(Debug, Clone, Copy)]
struct Scale(f64);

impl Scale {
    fn relative(self, rr: f64) -> f64 {
        if self.0 > 0.0 {
            rr.sqrt() / self.0
        } else {
            rr.sqrt()
        }
    }
}

/// Start a solve at approach `d` (length): r = (d − h − K p)_C, the true residual of the warm
/// start, with K p taken from `known` where the caller has it (else convolved into q).
/// Returns the scale ‖(d − h)_C‖ and that residual's relative norm, read back together
/// (`None` with `read` false: r·r is then kept in the `rr_start` slot for a later read), and
/// the convolutions made (0 or 1).
fn start<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
    p: &B::Field,
    d: f64,
    known: Option<&B::Field>,
    read: bool,
) -> Result<(Option<(Scale, f64)>, usize), BackendError> {
    let CgSlots {
        rr, bb, rr_start, ..
    } = work.slots;
    backend.residual(c, &work.zero, d, &mut work.r)?;
    backend.dot(c, &work.r, &work.r, bb)?;
    let convolutions = match known {
        Some(u) => {
            backend.residual(c, u, d, &mut work.r)?;
            0
        }
        None => {
            backend.convolve(p, &mut work.q)?;
            backend.residual(c, &work.q, d, &mut work.r)?;
            1
        }
    };
    backend.dot(c, &work.r, &work.r, rr)?;
    if !read {
        backend.copy_slot(rr, rr_start)?;
        return Ok((None, convolutions));
    }
    let mut v = [0.0; 2];
    backend.read_slots(&[rr, bb], &mut v)?;
    let scale = Scale(v[1].sqrt());
    Ok((Some((scale, scale.relative(v[0]))), convolutions))
}

/// The warm start's relative residual `initial` judged as the solve begins: the report's
/// first residual, and the end of a solve whose warm start met the tolerance (converged, no
/// iteration) or is not finite.
fn judge_start(
    report: &mut CgReport,
    history: &mut ResidualHistory,
    initial: f64,
    settings: &CgSettings,
) -> Option<CgEnd> {
    report.residual = initial;
    report.best = initial;
    if initial <= settings.tolerance {
        return Some(CgEnd::Converged);
    }
    history.push(0, initial)
}

/// z = M r and its max over C into the `eps` slot: the error estimate of the r in `work`,
/// left on the device for the next read.
fn estimate<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
) -> Result<(), BackendError> {
    backend.precondition(c, &work.r, &mut work.z)?;
    backend.max_abs_to(c, &work.z, work.slots.eps)
}

/// The relative residual of r, with r·r already in its slot, read back from the device.
fn read_rr<B: CgKernels>(backend: &mut B, rr: Slot, scale: Scale) -> Result<f64, BackendError> {
    let mut v = [0.0];
    backend.read_slots(&[rr], &mut v)?;
    Ok(scale.relative(v[0]))
}

/// q = K p and r = (d − h − q)_C, the true residual: its relative norm and, with
/// `with_estimate`, its error estimate (max over C of |M r|, stress), read back together.
fn true_residual<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    p: &B::Field,
    work: &mut CgWork<B::Field>,
    d: f64,
    scale: Scale,
    with_estimate: bool,
) -> Result<(f64, Option<f64>), BackendError> {
    backend.convolve(p, &mut work.q)?;
    backend.residual(c, &work.q, d, &mut work.r)?;
    backend.dot(c, &work.r, &work.r, work.slots.rr)?;
    if with_estimate {
        estimate(backend, c, work)?;
    }
    let mut v = [0.0; 2];
    backend.read_slots(&[work.slots.rr, work.slots.eps], &mut v)?;
    Ok((scale.relative(v[0]), with_estimate.then_some(v[1])))
}

/// Start CG's directions from the residual in `work.r`: z = M r with r·z in the first r·z
/// slot, s = z.
/// Returns the index of the r·z slot in use.
fn start_directions<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
) -> Result<usize, BackendError> {
    let CgSlots { rz, zero, .. } = work.slots;
    backend.precondition_dot(c, &work.r, &mut work.z, rz[0])?;
    // s = z (the ratio 0/0 counts as 0, so the old direction vanishes).
    backend.xpay_ratio(c, &mut work.s, &work.z, zero, zero)?;
    Ok(0)
}

/// One step along s: q = K s with s·q, then p += α s, r −= α q with α = r·z / s·q, and r·r
/// into its slot. `rz` is the index of the r·z slot in use.
fn step<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
    p: &mut B::Field,
    rz: usize,
) -> Result<(), BackendError> {
    let slots = work.slots;
    backend.convolve_dot(c, &work.s, &mut work.q, slots.sq)?;
    let CgWork { r, s, q, .. } = work;
    backend.cg_update(c, p, r, s, q, slots.rz[rz], slots.sq, slots.rr)
}

/// The next direction: z = M r, s = z + β s with β = r·z / (r·z)_old; the new r·z goes to the
/// other slot of the pair. Returns the index of the r·z slot now in use.
fn next_direction<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
    rz: usize,
) -> Result<usize, BackendError> {
    let new = 1 - rz;
    let slots = work.slots.rz;
    backend.precondition_dot(c, &work.r, &mut work.z, slots[new])?;
    backend.xpay_ratio(c, &mut work.s, &work.z, slots[new], slots[rz])?;
    Ok(new)
}

/// The settings the solver's solves on `backend` run with: the tolerance raised to the
/// backend's residual floor ([`CgKernels::residual_floor`]), below which its arithmetic
/// cannot bring the true residual, so that iterations past it buy nothing. ([`solve`]
/// itself takes the settings as given: a tolerance of 0 makes every iteration asked.)
pub fn effective<B: CgKernels>(backend: &B, settings: &CgSettings) -> CgSettings {
    CgSettings {
        tolerance: settings.tolerance.max(backend.residual_floor()),
        ..*settings
    }
}

/// What a solve is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Goal {
    /// A state: converged when the true residual, recomputed from p, is within
    /// [`TRUE_RESIDUAL_SLACK`] of the tolerance; `work.q` then holds K p.
    Exact,
    /// Only an approximate p (a cascade round that decides which elements are over σ_c):
    /// converged when the recurrence reaches the tolerance, with no true residual
    /// recomputed, so `work.q` does not hold K p.
    Loose,
}

/// Solve for p on the backend's contact set at approach `d` (length), warm-started from
/// the p given (which must be zero off C), in the normal mode (see the module's notes).
/// Ends converged, stagnated, diverged, non-finite, at the iteration limit or with a
/// residual gap; after [`CgEnd::Converged`], `work.q` holds K p.
pub fn solve<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
    p: &mut B::Field,
    d: f64,
    settings: &CgSettings,
) -> Result<CgReport, BackendError> {
    solve_with(backend, c, work, p, d, settings, None, Goal::Exact)
}

/// [`solve`] with K p of the warm start `known` where the caller has it (its convolution is
/// then saved), for the `goal` given. After [`CgEnd::Converged`] with [`Goal::Exact`],
/// `work.q` holds K p, except when the warm start already met the tolerance with K p
/// `known` (no iteration made: K p is that field, and `work.q` is untouched).
#[allow(clippy::too_many_arguments)]
pub fn solve_with<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
    p: &mut B::Field,
    d: f64,
    settings: &CgSettings,
    known: Option<&B::Field>,
    goal: Goal,
) -> Result<CgReport, BackendError> {
    // A device that guards its iterations reads the warm start's residual with the first
    // progress read: it makes no step where the warm start meets the tolerance.
    let defer = backend.defers_cg_start();
    let estimate_loose = defer && goal == Goal::Loose;
    let (started, convolutions) = start(backend, c, work, p, d, known, !defer)?;
    let mut report = CgReport {
        iterations: 0,
        residual: f64::NAN,
        best: f64::NAN,
        end: CgEnd::Converged,
        convolutions,
        error_estimate: None,
    };
    let mut history = ResidualHistory::new(settings.check_every);
    let mut scale = Scale(f64::NAN);
    if let Some((s, initial)) = started {
        scale = s;
        if let Some(end) = judge_start(&mut report, &mut history, initial, settings) {
            report.end = end;
            return Ok(report);
        }
    }
    let mut pending_start = started.is_none();
    // A device backend stops the iterations it has queued once the tolerance is reached, so
    // it can be read rarely without doing more iterations than the solve needs.
    let guard = CgStop {
        rr: work.slots.rr,
        bb: work.slots.bb,
        tolerance: settings.tolerance,
    };
    backend.guard_cg(Some(guard))?;
    let mut rz = start_directions(backend, c, work)?;
    let mut k = 0;
    let end = loop {
        let at_limit = k == settings.max_iterations;
        if at_limit && !pending_start {
            break None;
        }
        if !at_limit {
            k += 1;
            step(backend, c, work, p, rz)?;
            if k % settings.check_every != 0 && k != settings.max_iterations {
                rz = next_direction(backend, c, work, rz)?;
                continue;
            }
        }
        let slots = work.slots;
        if estimate_loose {
            // The error estimate of the r read now, in the same read: the last read's is
            // the loose round's.
            estimate(backend, c, work)?;
        }
        let mut v = [0.0; 4];
        let made =
            backend.read_cg_status(&[slots.rr, slots.rr_start, slots.bb, slots.eps], &mut v)?;
        report.error_estimate = estimate_loose.then_some(v[3]);
        if pending_start {
            pending_start = false;
            scale = Scale(v[2].sqrt());
            let end = judge_start(&mut report, &mut history, scale.relative(v[1]), settings);
            // Whether no step was made: none recorded, or the device's guard stopped before
            // the first because the warm start met its test of the tolerance (in f32) or is
            // not finite. The host's test of the warm start then decides, as at a read start.
            let no_step = k == 0 || made == Some(0);
            match end {
                Some(end) if no_step => break Some(Some(end)),
                None if no_step && !at_limit => {
                    // Within rounding of the tolerance, above it here: iterate from the
                    // directions already made, as after a start read at once.
                    backend.guard_cg(Some(guard))?;
                    k = 0;
                    continue;
                }
                _ => {}
            }
            if at_limit {
                break None;
            }
        }
        // Under a guard the device stops before the k-th step once its test of the
        // tolerance holds (in f32): the solve has then converged, which the true residual
        // recomputed by `verify` confirms or not.
        let stopped = made.is_some_and(|m| m < k);
        k = made.unwrap_or(k);
        report.iterations = k;
        report.residual = scale.relative(v[0]);
        report.best = report.best.min(report.residual);
        if report.residual.is_finite() && (report.residual <= settings.tolerance || stopped) {
            break Some(None);
        }
        if let Some(end) = history.push(k, report.residual) {
            break Some(Some(end));
        }
        rz = next_direction(backend, c, work, rz)?;
    };
    backend.guard_cg(None)?;
    match end {
        Some(None) if goal == Goal::Exact => {
            verify(backend, c, work, p, d, scale, settings, report)
        }
        Some(None) => Ok(report),
        Some(Some(end)) => {
            report.end = end;
            Ok(report)
        }
        None => {
            report.iterations = k;
            report.end = CgEnd::IterationLimit;
            Ok(report)
        }
    }
}

/// The recurrence reached the tolerance: recompute the true residual from p and end
/// converged if it is within [`TRUE_RESIDUAL_SLACK`] of the tolerance, with a residual gap
/// otherwise.
#[allow(clippy::too_many_arguments)]
fn verify<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
    p: &B::Field,
    d: f64,
    scale: Scale,
    settings: &CgSettings,
    mut report: CgReport,
) -> Result<CgReport, BackendError> {
    // The error estimate of the true residual, read with it where asked for.
    let with_estimate = backend.defers_cg_start() && work.estimate_exact;
    let (t, eps) = true_residual(backend, c, p, work, d, scale, with_estimate)?;
    report.error_estimate = eps;
    report.convolutions += 1;
    report.residual = t;
    if t <= TRUE_RESIDUAL_SLACK * settings.tolerance {
        report.end = CgEnd::Converged;
    } else {
        report.end = CgEnd::ResidualGap;
        report.best = t;
    }
    Ok(report)
}

/// Solve as [`solve`] does, in the safer mode: the residual is read every iteration, and CG
/// restarts from the true residual (d − h − K p)_C whenever the recurrence reaches the
/// tolerance and at least every [`REPLACE_EVERY`] iterations, up to the iteration limit.
/// The history judges the true residuals only. p is left at the smallest true residual
/// seen, which the report gives; after [`CgEnd::Converged`], `work.q` holds K p.
pub fn solve_safe<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
    p: &mut B::Field,
    d: f64,
    settings: &CgSettings,
) -> Result<CgReport, BackendError> {
    let (started, convolutions) = start(backend, c, work, p, d, None, true)?;
    let (scale, mut t) = started.expect("a start read at once is read");
    let mut history = ResidualHistory::new(1);
    let mut report = CgReport {
        iterations: 0,
        residual: f64::INFINITY,
        best: f64::INFINITY,
        end: CgEnd::IterationLimit,
        convolutions,
        error_estimate: None,
    };
    loop {
        if t < report.best {
            report.best = t;
            backend.copy(p, &mut work.best)?;
        }
        let end = if t <= settings.tolerance {
            Some(CgEnd::Converged)
        } else if let Some(end) = history.push(report.iterations, t) {
            Some(end)
        } else if report.iterations >= settings.max_iterations {
            Some(CgEnd::IterationLimit)
        } else {
            None
        };
        if let Some(end) = end {
            report.end = end;
            report.residual = t;
            if end != CgEnd::Converged && report.best.is_finite() {
                backend.copy(&work.best, p)?;
                report.residual = report.best;
            }
            return Ok(report);
        }
        let n = REPLACE_EVERY.min(settings.max_iterations - report.iterations);
        report.iterations += segment(backend, c, work, p, scale, settings.tolerance, n)?;
        t = true_residual(backend, c, p, work, d, scale, false)?.0;
        report.convolutions += 1;
    }
}

/// Up to `n` CG iterations from the true residual in `work.r`, reading the recurrence
/// residual every iteration; stops early when it reaches `tolerance` or is not finite.
/// Returns the iterations made.
fn segment<B: CgKernels>(
    backend: &mut B,
    c: &B::Mask,
    work: &mut CgWork<B::Field>,
    p: &mut B::Field,
    scale: Scale,
    tolerance: f64,
    n: usize,
) -> Result<usize, BackendError> {
    let mut rz = start_directions(backend, c, work)?;
    for k in 1..=n {
        step(backend, c, work, p, rz)?;
        let rel = read_rr(backend, work.slots.rr, scale)?;
        if rel <= tolerance || !rel.is_finite() {
            return Ok(k);
        }
        rz = next_direction(backend, c, work, rz)?;
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feed `residuals` (one per iteration from 0) to a history checked every
    /// `check_every` iterations; returns the verdict and the iteration it came at.
    fn judge(
        residuals: impl Fn(usize) -> f64,
        check_every: usize,
        n: usize,
    ) -> Option<(CgEnd, usize)> {
        let mut h = ResidualHistory::new(check_every);
        (0..=n)
            .step_by(check_every)
            .find_map(|k| h.push(k, residuals(k)).map(|e| (e, k)))
    }

    #[test]
    fn steady_convergence_is_never_flagged() {
        // Preconditioned CG: a factor 10 per iteration.
        assert_eq!(judge(|k| 10f64.powi(-(k as i32)), 1, 300), None);
        // Slow, unpreconditioned CG: a factor 2 every 40 iterations, for 2000 iterations.
        assert_eq!(judge(|k| 0.5f64.powf(k as f64 / 40.0), 1, 2000), None);
    }

    #[test]
    fn a_non_monotone_healthy_residual_is_not_flagged() {
        // CG's residual norm rises and falls: spikes of ×30 above the trend, which itself
        // falls by 2 every 20 iterations.
        let spiky = |k: usize| 0.5f64.powf(k as f64 / 20.0) * if k % 7 == 3 { 30.0 } else { 1.0 };
        assert_eq!(judge(spiky, 1, 1000), None);
        assert_eq!(judge(spiky, 2, 1000), None);
    }

    #[test]
    fn a_noisy_plateau_is_flagged_as_stagnation_one_window_after_it_starts() {
        // f32-like: falls by 10 per iteration to 1e-7 at iteration 7, then wanders around
        // 1e-7 by ±40 %.
        let plateau = |k: usize| {
            let noise = 1.0 + 0.4 * ((k * 2654435761) % 1000) as f64 / 1000.0 - 0.2;
            10f64.powi(-(k.min(7) as i32)) * noise
        };
        let (end, at) = judge(plateau, 1, 5000).expect("flagged");
        assert_eq!(end, CgEnd::Stagnated);
        assert!((50..=60).contains(&at), "flagged at {at}");
        // Checked every 2 iterations, as on the GPU: the same.
        let (end, at) = judge(plateau, 2, 5000).expect("flagged");
        assert_eq!(end, CgEnd::Stagnated);
        assert!((50..=60).contains(&at), "flagged at {at}");
    }

    #[test]
    fn a_late_plateau_is_given_a_window_of_a_quarter_of_the_iterations() {
        // Converges slowly for 400 iterations (a factor 2 per 40), then stalls. The best
        // residual of iteration 360 is twice the final one, so the verdict waits until the
        // window, a quarter of the iterations, reaches back past 360: k − k/4 > 360, k = 482.
        let late = |k: usize| 0.5f64.powf(k.min(400) as f64 / 40.0);
        assert_eq!(judge(late, 1, 5000), Some((CgEnd::Stagnated, 482)));
    }

    #[test]
    fn a_blow_up_is_flagged_as_divergence() {
        let blow = |k: usize| {
            if k < 20 {
                0.5f64.powi(k as i32)
            } else {
                0.5f64.powi(20) * 10f64.powi(k as i32 - 20)
            }
        };
        assert_eq!(judge(blow, 1, 100), Some((CgEnd::Diverged, 24)));
    }

    #[test]
    fn a_nan_or_infinity_is_flagged_at_once() {
        assert_eq!(
            judge(|k| if k == 5 { f64::NAN } else { 0.1 }, 1, 100),
            Some((CgEnd::NonFinite, 5))
        );
        assert_eq!(
            judge(|k| if k == 3 { f64::INFINITY } else { 0.1 }, 1, 100),
            Some((CgEnd::NonFinite, 3))
        );
    }

    #[test]
    fn rare_checks_widen_the_window_to_three_checks() {
        // Checked every 40 iterations: the window is 120, not 50.
        let h = ResidualHistory::new(40);
        assert_eq!(h.window(0), 120);
        let flat = |_| 1e-3;
        assert_eq!(judge(flat, 40, 5000), Some((CgEnd::Stagnated, 120)));
    }
}
