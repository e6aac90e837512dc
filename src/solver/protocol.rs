//! The approach and pull-off protocol (physics §6): a non-adhesive press to d0, then the
//! approach decreases step by step until the contact vanishes or d passes its final value.
//!
//! Two options of the model change how much of it is computed: with
//! [`Measure::AdhesiveForce`] the steps are taken whole (no onset refinement) while the force
//! falls, the last [`WINDOW`] steps are kept so that the run can go back and take them again
//! with every onset refined once the force has turned, and the run stops once the minimum is
//! confirmed; with `regrid` the grid is refined as the contact shrinks.

use super::equilibrium::{equilibrate, solve_fixed, Equilibrium, Fields};
use super::retry::{self, CgRetry};
use super::state::{Phase, State};
use super::SolverError;
use crate::backend::{Backend, ContactKernels};
use crate::model::{Measure, Model, Stepping};
use std::collections::VecDeque;
use std::f64::consts::PI;

/// What a run produced: the states recorded so far and, if it stopped early, why.
#[derive(Debug)]
pub struct Outcome {
    /// Recorded states, in order.
    pub states: Vec<State>,
    /// The error that ended the run early, if any.
    pub error: Option<SolverError>,
    /// The grid changes made on the way (empty unless the model re-grids).
    pub regrids: Vec<RegridEvent>,
    /// Whether the run stopped once the force minimum was confirmed ([`Measure::AdhesiveForce`]).
    pub stopped_after_minimum: bool,
    /// The CG solves that needed the safer retry, in order (empty for a healthy run).
    pub cg_retries: Vec<CgRetry>,
    /// What the user should know about a run that went on: CG retries, and states accepted
    /// above the CG tolerance (empty for a healthy run).
    pub warnings: Vec<String>,
}

/// One change of grid during a run.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RegridEvent {
    /// Approach at which the grid changed (dimensionless).
    pub d_bar: f64,
    /// Element side before (length).
    pub dx_from: f64,
    /// Element side after (length).
    pub dx_to: f64,
}

impl Outcome {
    /// Whether the protocol ran to its end (or to its confirmed minimum).
    pub fn complete(&self) -> bool {
        self.error.is_none()
    }

    /// Total CG iterations over all states.
    pub fn cg_iterations(&self) -> usize {
        self.states.iter().map(|s| s.cg_iterations).sum()
    }

    /// The largest relative CG residual of any recorded state (dimensionless), if any
    /// state was recorded.
    pub fn worst_cg_residual(&self) -> Option<f64> {
        self.states.iter().map(|s| s.cg_residual).reduce(f64::max)
    }

    /// The state of minimum force (the adhesive force is its |F̄|), if any state was recorded.
    ///
    /// After re-grids it is taken on the last grid only (whose first state is the one
    /// re-equilibrated on it): the coarser grids before over-predict the adhesion, and the run
    /// stops re-gridding once the minimum is confirmed.
    pub fn force_minimum(&self) -> Option<&State> {
        let last_dx = self.states.last()?.dx;
        self.states
            .iter()
            .filter(|s| s.dx == last_dx)
            .min_by(|a, b| a.force.total_cmp(&b.force))
    }

    /// Whether the run reached the force minimum, so that [`Outcome::force_minimum`] is the
    /// adhesive force and not just the lowest force recorded: the minimum state is in contact,
    /// and after it the contact jumped off, or the run stopped once the minimum was confirmed,
    /// or the approach went [`CONFIRM_D_BAR`] past it with the force [`CONFIRM_RISE`] of its
    /// size above it. A run stopped by `--final-d` (or an error) while the force was still
    /// falling has not.
    pub fn min_reached(&self) -> bool {
        let Some(min) = self.force_minimum() else {
            return false;
        };
        if min.n_contact == 0 || !min.force.is_finite() {
            return false;
        }
        if self.stopped_after_minimum {
            return true;
        }
        let k = self
            .states
            .iter()
            .rposition(|s| std::ptr::eq(s, min))
            .unwrap_or(self.states.len());
        self.states[k + 1..].iter().any(|s| {
            s.n_contact == 0
                || (s.d_bar <= min.d_bar - CONFIRM_D_BAR
                    && s.force - min.force >= CONFIRM_RISE * min.force.abs())
        })
    }
}

/// Measure and normalise the state of pressure `p` on the backend's contact set (reduced on
/// the backend's device); also returns the contact's index box (`None` without contact).
#[allow(clippy::too_many_arguments)]
fn record<B: Backend>(
    backend: &mut B,
    model: &Model,
    p: &B::Field,
    step: usize,
    phase: Phase,
    d: f64,
    eq: &Equilibrium,
) -> Result<(State, Option<[usize; 4]>), SolverError> {
    let m = backend.measure(p, model.mesh.chord_axes())?;
    let (a_el, b_el) = m.half_lengths;
    let n = m.count;
    let dx = model.dx;
    let sc = model.scene.scales();
    let area = n as f64 * dx * dx;
    let force = m.sum * dx * dx;
    let mean_radius = (area / PI).sqrt();
    let state = State {
        step,
        phase,
        d,
        force,
        area,
        mean_radius,
        a_axis: a_el * dx,
        b_axis: b_el * dx,
        n_contact: n,
        cg_iterations: eq.cg_iterations,
        detach_sweeps: eq.sweeps,
        cg_residual: eq.cg_residual,
        d_bar: d / sc.approach,
        f_bar: force / sc.force,
        c_bar: mean_radius / sc.length,
        a_bar: a_el * dx / sc.length,
        b_bar: b_el * dx / sc.length,
        dx,
    };
    Ok((state, m.bounds))
}

/// Run the whole protocol on `backend`, calling `observe` with each recorded state.
pub fn run<B: Backend>(backend: &mut B, model: &Model, observe: &mut dyn FnMut(&State)) -> Outcome {
    run_until(backend, model, false, &mut |s, _| {
        observe(s);
        true
    })
}

/// Like [`run`], but `observe` also sees the contact mask of each state (row-major nx × ny
/// of the grid the state was computed on, true = in contact), for contours and snapshots.
/// Each mask is read back from the backend's device: a run that needs no masks should use
/// [`run`].
///
/// If the model re-grids, `backend` is replaced by a sibling on the finer grid.
pub fn run_with_contact<B: Backend>(
    backend: &mut B,
    model: &Model,
    observe: &mut dyn FnMut(&State, &[bool]),
) -> Outcome {
    run_until(backend, model, true, &mut |s, mask| {
        observe(s, mask.unwrap_or_default());
        true
    })
}

/// The run behind [`run`] and [`run_with_contact`]: `observe` sees each state, with its
/// contact mask if `with_contact` (else `None`: no mask is read back), and returns whether to
/// go on: once it returns false (say, its states can no longer be written), the run stops at
/// the next load step with [`SolverError::Interrupted`], keeping the states recorded so far.
pub fn run_until<B: Backend>(
    backend: &mut B,
    model: &Model,
    with_contact: bool,
    observe: &mut dyn FnMut(&State, Option<&[bool]>) -> bool,
) -> Outcome {
    let mut states = Vec::new();
    let go_on = std::cell::Cell::new(true);
    let mut out = Emitter {
        push: &mut |s: State, mask: Option<&[bool]>| {
            if !observe(&s, mask) {
                go_on.set(false);
            }
            states.push(s);
        },
        with_contact,
        go_on: &go_on,
        pending: Vec::new(),
        least: None,
        regrids: Vec::new(),
        stopped_after_minimum: false,
        retries: Vec::new(),
    };
    let error = run_inner(backend, model, &mut out).err();
    out.flush(usize::MAX);
    let (regrids, stopped_after_minimum) = (out.regrids, out.stopped_after_minimum);
    let cg_retries = out.retries;
    let warnings = retry::warnings(&cg_retries, &model.cg);
    Outcome {
        states,
        error,
        regrids,
        stopped_after_minimum,
        cg_retries,
        warnings,
    }
}

/// Where states go: to the observer at once, or held while the steps that produced them may
/// still be taken again.
struct Emitter<'a> {
    push: &'a mut dyn FnMut(State, Option<&[bool]>),
    /// Whether the observer sees each state's contact mask.
    with_contact: bool,
    /// False once the observer asked to stop.
    go_on: &'a std::cell::Cell<bool>,
    /// States held back, with their masks if the observer sees them.
    pending: Vec<(State, Option<Vec<bool>>)>,
    /// Least force (force) handed on since the last re-grid, and its d̄.
    least: Option<(f64, f64)>,
    regrids: Vec<RegridEvent>,
    stopped_after_minimum: bool,
    /// The safer CG retries of every equilibrium so far.
    retries: Vec<CgRetry>,
}

impl Emitter<'_> {
    /// Hand a state of `backend`'s current contact on (held if `hold`), with the contact mask
    /// read back if the observer sees masks.
    fn emit<B: ContactKernels>(
        &mut self,
        backend: &mut B,
        state: State,
        hold: bool,
    ) -> Result<(), SolverError> {
        let mask = if self.with_contact {
            let (nx, ny) = backend.shape();
            let mut mask = vec![false; nx * ny];
            backend.contact(&mut mask)?;
            Some(mask)
        } else {
            None
        };
        if hold {
            self.pending.push((state, mask));
        } else {
            self.flush(usize::MAX);
            self.hand_on(state, mask.as_deref());
        }
        Ok(())
    }

    fn hand_on(&mut self, state: State, mask: Option<&[bool]>) {
        if self.least.is_none_or(|(f, _)| state.force < f) {
            self.least = Some((state.force, state.d_bar));
        }
        (self.push)(state, mask);
    }

    /// Hand on the first `n` held states.
    fn flush(&mut self, n: usize) {
        let n = n.min(self.pending.len());
        let held: Vec<_> = self.pending.drain(..n).collect();
        for (s, m) in held {
            self.hand_on(s, m.as_deref());
        }
    }

    /// Least force (force) since the last re-grid, held states included, and its d̄.
    fn minimum(&self) -> Option<(f64, f64)> {
        self.pending
            .iter()
            .map(|(s, _)| (s.force, s.d_bar))
            .chain(self.least)
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// Whether a step-end state of `force` (force) at `d_bar` confirms the minimum:
    /// [`CONFIRM_D_BAR`] or more past it and above it by [`CONFIRM_RISE`] of its size.
    fn minimum_confirmed(&self, force: f64, d_bar: f64) -> bool {
        self.minimum().is_some_and(|(f_min, d_min)| {
            d_bar <= d_min - CONFIRM_D_BAR && force - f_min >= CONFIRM_RISE * f_min.abs()
        })
    }
}

/// Steps kept for going back in [`Measure::AdhesiveForce`]: should the step-end force turn
/// before onsets are refined, these steps are taken again with every onset refined.
pub const WINDOW: usize = 3;

/// Mean contact radius c̄ below which [`Measure::AdhesiveForce`] refines onsets: 1.3× the
/// largest c̄ at the force minimum of the closed forms (JKR's 2^(−1/3) = 0.794) and of our
/// runs (0.74–0.84 from 32² to 128², R1/R2 = 1…50).
pub const REFINE_BELOW_C_BAR: f64 = 1.1;

/// How far past the force minimum (in d̄) the approach must go to confirm it: the sawtooth's
/// period on coarse grids is a few hundredths; on JKR's curve F̄ has risen by 3.4 % there.
pub const CONFIRM_D_BAR: f64 = 0.1;

/// Rise of the step-end force above its minimum (of |F_min|) needed, with
/// [`CONFIRM_D_BAR`], to confirm the minimum.
pub const CONFIRM_RISE: f64 = 0.02;

/// Re-grid once the contact (with its margin) fits in this fraction of the domain.
pub const REGRID_BELOW: f64 = 0.8;

/// Re-grid only while the mean contact radius c̄ is above this: the force minimum lies below
/// it (c̄ = 0.74–0.84 in our runs, 0.63–0.79 in the closed forms), so that it is resolved on
/// the last, finest grid, where [`Outcome::force_minimum`] looks for it.
pub const REGRID_ABOVE_C_BAR: f64 = 0.9;

/// A step-end state kept for going back: the spare fields that hold its p and its contact
/// set (on the device).
struct Snapshot {
    field: usize,
    step: usize,
    d: f64,
    /// States held before this snapshot's.
    held: usize,
}

/// The pull-off's progress: the current grid, fields and contact, and what the measure
/// asks to keep.
struct Progress<F> {
    model: Model,
    fields: Fields<F>,
    /// Whether onsets are refined in the steps now taken.
    refine: bool,
    /// Snapshots of the last steps (measure mode, before refining).
    window: VecDeque<Snapshot>,
    /// Device fields that hold the snapshots' p.
    spare: Vec<F>,
    /// Device fields that hold the snapshots' contact sets.
    spare_contact: Vec<F>,
    /// Whether re-gridding is still allowed (not once the minimum is confirmed).
    may_regrid: bool,
}

fn run_inner<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &mut Emitter,
) -> Result<(), SolverError> {
    let measure = model.measure == Measure::AdhesiveForce;
    backend.set_contact(&model.initial_contact())?;
    let mut fields = Fields::new(backend)?;
    // 1. Non-adhesive press to d0.
    let mut eq = equilibrate(backend, model, &mut fields, model.d0, 0.0)?;
    out.retries.append(&mut eq.retries);
    let (state, _) = record(backend, model, &fields.p, 0, Phase::Approach, model.d0, &eq)?;
    out.emit(backend, state, false)?;
    let (mut spare, mut spare_contact) = (Vec::new(), Vec::new());
    if measure {
        for _ in 0..WINDOW {
            spare.push(backend.field()?);
            spare_contact.push(backend.field()?);
        }
    }
    let mut run = Progress {
        model: model.clone(),
        fields,
        refine: !measure && model.stepping == Stepping::Adaptive,
        window: VecDeque::new(),
        spare,
        spare_contact,
        may_regrid: true,
    };
    // 2. Adhesive pull-off, step by step.
    let mut d_prev = model.d0;
    let mut step = 0;
    loop {
        if !out.go_on.get() {
            return Err(SolverError::Interrupted);
        }
        step += 1;
        let d = model.d0 - step as f64 * model.d_step;
        if d < model.d_final {
            return Ok(());
        }
        let hold = measure && !run.refine;
        let m = run.model.clone();
        let mut eq = if run.refine {
            advance_through_onsets(backend, &m, &mut run, step, d_prev, d, out)?
        } else {
            Equilibrium::default()
        };
        let last = equilibrate(backend, &m, &mut run.fields, d, m.sigma_c)?;
        eq.absorb(last);
        out.retries.append(&mut eq.retries);
        let (state, bounds) = record(backend, &m, &run.fields.p, step, Phase::Pulloff, d, &eq)?;
        let (force, d_bar, c_bar) = (state.force, state.d_bar, state.c_bar);
        out.emit(backend, state, hold)?;
        d_prev = d;
        if eq.n_contact == 0 {
            return Ok(());
        }
        if out.minimum_confirmed(force, d_bar) {
            if measure && run.refine {
                out.stopped_after_minimum = true;
                return Ok(());
            }
            run.may_regrid = false;
        }
        if measure && !run.refine {
            let turned = out
                .minimum()
                .is_some_and(|(f_min, _)| force - f_min > CONFIRM_RISE * f_min.abs());
            if turned {
                // The step-end force has turned: take the last steps again, refined.
                if let Some((s, d_s)) = run.go_back(backend, out)? {
                    (step, d_prev) = (s, d_s);
                }
                continue;
            }
            if c_bar <= REFINE_BELOW_C_BAR {
                run.refine = true;
                run.window.clear();
                out.flush(usize::MAX);
            } else {
                run.keep(backend, step, d, out)?;
            }
        }
        if run.model.regrid && run.may_regrid && c_bar > REGRID_ABOVE_C_BAR {
            if let Some(bounds) = bounds {
                regrid_if_shrunk(backend, &mut run, step, d, bounds, out)?;
            }
        }
    }
}

impl<F> Progress<F> {
    /// Refine from now on, restarting from the oldest snapshot kept: its contact and p are
    /// restored and the states held since are dropped. Returns the step and approach d
    /// (length) to go on from, if there was a snapshot.
    fn go_back<B: Backend<Field = F>>(
        &mut self,
        backend: &mut B,
        out: &mut Emitter,
    ) -> Result<Option<(usize, f64)>, SolverError> {
        let snap = self.window.pop_front();
        self.window.clear();
        self.refine = true;
        let resume = match snap {
            Some(s) => {
                out.pending.truncate(s.held);
                backend.restore_contact(&self.spare_contact[s.field])?;
                backend.copy(&self.spare[s.field], &mut self.fields.p)?;
                Some((s.step, s.d))
            }
            None => None,
        };
        out.flush(usize::MAX);
        Ok(resume)
    }

    /// Keep this step's end state as a snapshot, dropping (and handing on the states of) the
    /// oldest beyond [`WINDOW`].
    fn keep<B: Backend<Field = F>>(
        &mut self,
        backend: &mut B,
        step: usize,
        d: f64,
        out: &mut Emitter,
    ) -> Result<(), SolverError> {
        let field = if self.window.len() == WINDOW {
            let old = self.window.pop_front().map_or(0, |s| s.field);
            let released = self.window.front().map_or(out.pending.len(), |s| s.held);
            out.flush(released);
            for s in &mut self.window {
                s.held -= released;
            }
            old
        } else {
            self.window.len()
        };
        backend.copy(&self.fields.p, &mut self.spare[field])?;
        backend.save_contact(&mut self.spare_contact[field])?;
        self.window.push_back(Snapshot {
            field,
            step,
            d,
            held: out.pending.len(),
        });
        Ok(())
    }
}

/// If the contact (index box `bounds`, with the model's margin) now fits in
/// [`REGRID_BELOW`] of the domain, carry it to the same grid on a domain fitted to it: finer
/// Δx, σ_c for that Δx, the contact set and p resampled (read back for it), then
/// re-equilibrated at the same approach `d` (length).
fn regrid_if_shrunk<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field>,
    step: usize,
    d: f64,
    bounds: [usize; 4],
    out: &mut Emitter,
) -> Result<(), SolverError> {
    let m = &run.model;
    let (ex, ey) = m.extent_of_bounds(bounds);
    let half_x = m.nx as f64 / 2.0 * m.dx;
    let half_y = m.ny as f64 / 2.0 * m.dx;
    let factor = ((1.0 + m.margin) * (ex / half_x).max(ey / half_y)).max(f64::MIN_POSITIVE);
    if factor > REGRID_BELOW || ex == 0.0 {
        return Ok(());
    }
    let fine = m.regridded(factor);
    let mut p = vec![0.0; m.nx * m.ny];
    backend.download(&run.fields.p, &mut p)?;
    let p = m.resample(&fine, &p, 0.0);
    let mut coarse_mask = vec![false; m.nx * m.ny];
    backend.contact(&mut coarse_mask)?;
    let mask = m.resample(&fine, &coarse_mask, false);
    *backend = backend.sibling(&fine.grid_setup())?;
    backend.set_contact(&mask)?;
    let mut fields = Fields::new(backend)?;
    backend.upload(&mut fields.p, &p)?;
    let (mut spare, mut spare_contact) = (Vec::new(), Vec::new());
    for _ in 0..run.spare.len() {
        spare.push(backend.field()?);
        spare_contact.push(backend.field()?);
    }
    out.flush(usize::MAX);
    out.least = None;
    out.regrids.push(RegridEvent {
        d_bar: d / m.scene.scales().approach,
        dx_from: m.dx,
        dx_to: fine.dx,
    });
    run.window.clear();
    run.spare = spare;
    run.spare_contact = spare_contact;
    run.fields = fields;
    run.model = fine;
    let mut eq = equilibrate(backend, &run.model, &mut run.fields, d, run.model.sigma_c)?;
    out.retries.append(&mut eq.retries);
    let (state, _) = record(
        backend,
        &run.model,
        &run.fields.p,
        step,
        Phase::Regrid,
        d,
        &eq,
    )?;
    out.emit(backend, state, false)?;
    Ok(())
}

/// Fraction of the rest of a step by which the load is pushed past an onset, so that the
/// element that reached σ_c is beyond it by more than CG's round-off.
const ONSET_PUSH: f64 = 1e-4;

/// Limit on onsets handled inside one load step before the rest of it is taken at once.
const MAX_ONSETS_PER_STEP: usize = 100_000;

/// Move the load from `d_from` towards `d_to` (lengths) through every detachment onset on
/// the way: with the contact set fixed p is linear in d, so the approach at which the first
/// element reaches σ_c is found exactly; that state (a local minimum of the sawtooth F(d)) is
/// recorded, the detachment cascade is resolved there, and the search goes on. This makes
/// the curve, and its force minimum, independent of the step size.
fn advance_through_onsets<B: Backend>(
    backend: &mut B,
    model: &Model,
    run: &mut Progress<B::Field>,
    step: usize,
    d_from: f64,
    d_to: f64,
    out: &mut Emitter,
) -> Result<Equilibrium, SolverError> {
    let mut total = Equilibrium::default();
    let mut d_c = d_from;
    let fields = &mut run.fields;
    for _ in 0..MAX_ONSETS_PER_STEP {
        backend.copy(&fields.p, &mut fields.p_prev)?;
        let solve = solve_fixed(backend, model, fields, d_to)?;
        // The onset state interpolates to this solve: no work of its own, its residual.
        let onset = Equilibrium {
            cg_residual: solve.residual,
            ..Equilibrium::default()
        };
        total.add_solve(solve);
        let t = backend.first_crossing(&fields.p_prev, &fields.p, model.sigma_c)?;
        if t >= 1.0 {
            break;
        }
        backend.lerp(&fields.p_prev, &fields.p, t, &mut fields.p_onset)?;
        let d_on = d_c + t * (d_to - d_c);
        let (state, _) = record(
            backend,
            model,
            &fields.p_onset,
            step,
            Phase::Onset,
            d_on,
            &onset,
        )?;
        out.emit(backend, state, false)?;
        let t_push = (t + ONSET_PUSH).min(1.0);
        backend.lerp(&fields.p_prev, &fields.p, t_push, &mut fields.p_onset)?;
        backend.copy(&fields.p_onset, &mut fields.p)?;
        d_c += t_push * (d_to - d_c);
        let eq = equilibrate(backend, model, fields, d_c, model.sigma_c)?;
        let vanished = eq.n_contact == 0;
        total.absorb(eq);
        if vanished || t_push >= 1.0 {
            break;
        }
    }
    Ok(total)
}
