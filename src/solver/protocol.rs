//! The approach and pull-off protocol (physics §6): a non-adhesive press to d0, then the
//! approach decreases step by step until the contact vanishes or d passes its final value.
//!
//! Every load step starts with a *probe*: the contact set it starts from, solved at the
//! step's end. The probe is a lower bound of the step: the detachment rule is monotone, so
//! every onset inside the step (a local minimum of the sawtooth F(d)) has a force at least
//! the probe's. With [`Onsets::NearMinimum`] the steps are taken whole (the probe, then the
//! detachment cascade at the step's end) until the force minimum is confirmed; then the
//! steps whose probe lies below the lowest onset known are gone back to and their onsets
//! located, lowest bound first, each pruned as soon as its remaining bound lies above the
//! lowest onset found (`search`, on the bounds [`super::window`] keeps). With
//! `regrid` the grid is refined as the contact shrinks.

use super::cost::CostAccount;
use super::emit::{record, Emitter, Progress};
use super::equilibrium::{equilibrate, settle, Equilibrium, Fields, Held, Reached};
use super::onsets;
use super::probe::Through;
use super::retry::{self, CgRetry};
use super::state::{Phase, RegridEvent, State};
use super::window::{Refinement, Window};
use super::SolverError;
use crate::backend::Backend;
use crate::model::{Measure, Model, Onsets};

pub use super::emit::{CONFIRM_D_BAR, CONFIRM_RISE};
pub use super::onsets::JUMP_FRACTION;

/// How a run's force minimum was confirmed: the first state after it that shows, by the
/// protocol's test, that no later state lies lower (the contact gone, or the approach
/// [`CONFIRM_D_BAR`] past it with the force [`CONFIRM_RISE`] of its size above it). An
/// adhesive-force run stops only at such a state, the minimum its search found included; a
/// run marked stopped without one (a guard: it does not happen) is given its furthest state.
/// The onsets between the two are each located, or bounded above the minimum (the window's
/// margin, [`Refinement::margin_f_bar`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Confirmation {
    /// d̄ of the confirming state (dimensionless).
    pub d_bar: f64,
    /// How far past the minimum it lies in d̄ (dimensionless).
    pub past_d_bar: f64,
    /// How far its force lies above the minimum's, relative to |min F̄| (dimensionless).
    pub rise: f64,
    /// Whether the contact was gone there (the jump off the surface).
    pub vanished: bool,
}

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
    /// Where the run spent its work.
    pub cost: CostAccount,
    /// Which load steps had their onsets located, and the check that they hold the force
    /// minimum ([`Onsets::NearMinimum`]; `None` otherwise or before any such step).
    pub refinement: Option<Refinement>,
    /// For a measured surface (a height map, roughness): the least-force pull-off state of
    /// the last grid and its contact mask (row-major, x fastest), kept for the straight
    /// fronts' check (the analysis of the fronts); `None` for the smooth shapes.
    pub min_contact: Option<(State, Vec<bool>)>,
}

impl Outcome {
    /// The contact mask at the force minimum, where it was kept
    /// ([`Outcome::min_contact`]) and is that state's.
    pub fn contact_at_minimum(&self) -> Option<&[bool]> {
        let (kept, mask) = self.min_contact.as_ref()?;
        let min = self.force_minimum()?;
        (kept.d == min.d && kept.force == min.force && !mask.is_empty()).then_some(mask.as_slice())
    }

    /// Whether the protocol ran to its end (or to its confirmed minimum).
    pub fn complete(&self) -> bool {
        self.error.is_none()
    }

    /// Total CG iterations of the run, those of states that were not kept included.
    pub fn cg_iterations(&self) -> usize {
        self.cost.work.cg_iterations
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
            .filter(|s| s.dx == last_dx && !s.phase.is_loading())
            .min_by(|a, b| a.force.total_cmp(&b.force))
    }

    /// Whether the run reached the force minimum, so that [`Outcome::force_minimum`] is the
    /// adhesive force and not just the lowest force recorded: the minimum state is in contact,
    /// and after it the contact jumped off, or the run stopped once the minimum was confirmed,
    /// or the approach went [`CONFIRM_D_BAR`] past it with the force [`CONFIRM_RISE`] of its
    /// size above it. A run stopped by `--final-d` (or an error) while the force was still
    /// falling has not.
    pub fn min_reached(&self) -> bool {
        self.confirmation().is_some()
    }

    /// How the force minimum was confirmed ([`Confirmation`]); `None` where it was not
    /// reached ([`Outcome::min_reached`]).
    pub fn confirmation(&self) -> Option<Confirmation> {
        let min = self.force_minimum()?;
        if min.n_contact == 0 || !min.force.is_finite() {
            return None;
        }
        let k = self
            .states
            .iter()
            .rposition(|s| std::ptr::eq(s, min))
            .unwrap_or(self.states.len());
        let after = &self.states[k + 1..];
        let confirms = |s: &&State| {
            s.n_contact == 0
                || (s.d_bar <= min.d_bar - CONFIRM_D_BAR
                    && s.force - min.force >= CONFIRM_RISE * min.force.abs())
        };
        let by = after.iter().find(confirms).or_else(|| {
            self.stopped_after_minimum
                .then(|| after.iter().min_by(|a, b| a.d.total_cmp(&b.d)))
                .flatten()
        });
        match by {
            Some(s) => Some(Confirmation {
                d_bar: s.d_bar,
                past_d_bar: min.d_bar - s.d_bar,
                rise: (s.force - min.force) / min.force.abs(),
                vanished: s.n_contact == 0,
            }),
            // Stopped at the minimum's own state: nothing after it to show.
            None if self.stopped_after_minimum => Some(Confirmation {
                d_bar: min.d_bar,
                past_d_bar: 0.0,
                rise: 0.0,
                vanished: false,
            }),
            None => None,
        }
    }
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
/// go on: once it returns false (say, its states can no longer be written, or its caller was
/// interrupted), the run stops before its next state with [`SolverError::Interrupted`],
/// keeping the states recorded so far.
pub fn run_until<B: Backend>(
    backend: &mut B,
    model: &Model,
    with_contact: bool,
    observe: &mut dyn FnMut(&State, Option<&[bool]>) -> bool,
) -> Outcome {
    run_watched(backend, model, with_contact, observe, &mut |_| true)
}

/// Like [`run_until`], and `held` sees each state that is held back when it is found (a
/// step's end while the search for the force minimum may still go back to it, an onset
/// located on going back): it is handed to `observe` later, in the order of the load. For
/// progress only; it returns whether to go on, as `observe` does, so that a run can be
/// stopped while it searches, when no state is handed on for a long time.
pub fn run_watched<B: Backend>(
    backend: &mut B,
    model: &Model,
    with_contact: bool,
    observe: &mut dyn FnMut(&State, Option<&[bool]>) -> bool,
    held: &mut dyn FnMut(&State) -> bool,
) -> Outcome {
    let mut states = Vec::new();
    let go_on = std::cell::Cell::new(true);
    let readbacks = backend.counters().readbacks;
    let floor = backend.residual_floor();
    let mut push = |s: State, mask: Option<&[bool]>| {
        if !observe(&s, mask) {
            go_on.set(false);
        }
        states.push(s);
    };
    let mut out = Emitter::new(&mut push, held, with_contact, &go_on);
    if model.scene.indenter.map_spacing().is_some() {
        out.keep_min_contact();
    }
    let error = run_inner(backend, model, &mut out).err();
    out.release(usize::MAX);
    out.cost.readbacks = backend.counters().readbacks.saturating_sub(readbacks);
    let Emitter {
        regrids,
        stopped_after_minimum,
        retries,
        cost,
        refinement,
        ledger,
        min_contact,
        ..
    } = out;
    let mut warnings = retry::warnings(&retries, &model.cg);
    let worst = states.iter().map(|s| s.cg_residual).reduce(f64::max);
    warnings.extend(retry::floor_warning(
        floor,
        &model.cg,
        backend.precision(),
        worst,
    ));
    let mut outcome = Outcome {
        states,
        error,
        regrids,
        stopped_after_minimum,
        cg_retries: retries,
        warnings,
        cost,
        refinement,
        min_contact,
    };
    let d_min = outcome
        .min_reached()
        .then(|| outcome.force_minimum().map(|s| s.d));
    outcome.cost.split_at_minimum(&ledger, d_min.flatten());
    outcome
}

/// The least fraction of a load step taken once a step end meets one of the tests that
/// confirm the minimum ([`confirming_end`]).
const CONFIRMING_STEP: f64 = 0.25;

/// Re-grid once the contact (with its margin) fits in this fraction of the domain.
pub const REGRID_BELOW: f64 = 0.8;

/// Re-grid only while the mean contact radius c̄ is above this: the force minimum lies below
/// it (c̄ = 0.74–0.84 in our runs, 0.63–0.79 in the closed forms), so that it is resolved on
/// the last, finest grid, where [`Outcome::force_minimum`] looks for it.
pub const REGRID_ABOVE_C_BAR: f64 = 0.9;

/// How a load step ended.
struct StepEnd {
    force: f64,
    d_bar: f64,
    c_bar: f64,
    bounds: Option<[usize; 4]>,
    vanished: bool,
}

fn run_inner<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &mut Emitter,
) -> Result<(), SolverError> {
    let (fields, held, model) = match model.loading {
        Some(_) => {
            // 1. Pressed on to the preload; the pull-off steps down from where it stopped.
            let (fields, state) = super::loading::press(backend, model, out)?;
            let mut from_preload = model.clone();
            from_preload.load.d0 = state.d;
            (fields, state, std::borrow::Cow::Owned(from_preload))
        }
        None => {
            let (fields, state) = first_contact(backend, model, out)?;
            (fields, state, std::borrow::Cow::Borrowed(model))
        }
    };
    let model = model.as_ref();
    let mut run = Progress {
        model: model.clone(),
        fields,
        held,
        last_d: None,
        best: f64::INFINITY,
        window: Window::new(model.onsets == Onsets::NearMinimum, model.nx * model.ny),
        may_regrid: true,
    };
    let result = pull_off(backend, &mut run, out, model);
    out.refinement = run.window.report(&run.model, run.best);
    result
}

/// The non-adhesive press to d0 (the protocol's first part), the first contact built in
/// one piece from the model's initial guess; returns the fields and the state there.
fn first_contact<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &mut Emitter,
) -> Result<Reached<B::Field, B::Mask>, SolverError> {
    let mut c = backend.mask()?;
    backend.upload_mask(&mut c, &model.initial_contact())?;
    let mut fields = Fields::new(backend, c)?;
    let mut eq = equilibrate(backend, model, &mut fields, model.load.d0, 0.0)?;
    let (state, _) = record(
        backend,
        model,
        &fields.c,
        &fields.p,
        0,
        Phase::Approach,
        model.load.d0,
        &eq,
    )?;
    if state.n_contact == 0 {
        return Err(SolverError::NoFirstContact { d_bar: state.d_bar });
    }
    let held = state.clone();
    out.emit(backend, &fields.c, state, &mut eq, false)?;
    Ok((fields, held))
}

/// 2. The adhesive pull-off, step by step.
fn pull_off<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
    model: &Model,
) -> Result<(), SolverError> {
    let mut d_prev = model.load.d0;
    let mut step = 0;
    // Load steps of the schedule reached (a step ended early to confirm the minimum is not
    // one of them).
    let mut planned = 0;
    // Whether the steps are shortened to confirm the minimum ([`confirming_end`]).
    let mut confirming = false;
    loop {
        if !out.go_on() {
            return Err(SolverError::Interrupted);
        }
        step += 1;
        let mut d = model.load.approach(planned + 1);
        if d < model.load.d_final {
            break;
        }
        let held = run.held.force;
        // The schedule's whole step: a step after a shortened one starts off the schedule.
        let whole = model.load.approach(planned) - d;
        match confirming_end(out, &run.model, held, &mut confirming, d_prev, d, whole) {
            Some(d_confirm) => d = d_confirm,
            None => planned += 1,
        }
        let end = load_step(backend, run, out, step, d_prev, d)?;
        d_prev = d;
        if end.vanished {
            break;
        }
        if model.confirm_minimum && out.minimum_confirmed(end.force, end.d_bar) {
            run.may_regrid = false;
            super::search::refine(backend, run, out)?;
            // The search may have found the minimum further on, beyond the reach of this
            // step end's test: the steps then go on until one confirms that minimum too.
            if model.measure == Measure::AdhesiveForce
                && out.minimum_confirmed(end.force, end.d_bar)
            {
                out.stopped_after_minimum = true;
                return Ok(());
            }
        }
        if run.model.regrid && run.may_regrid && end.c_bar > REGRID_ABOVE_C_BAR {
            if let Some(bounds) = end.bounds {
                regrid_if_shrunk(backend, run, step, d, bounds, out)?;
            }
        }
    }
    // The contact vanished, or the final approach came first: locate what is left to locate.
    super::search::refine(backend, run, out)
}

/// Where a step from `d_prev` to `d` (lengths) ends instead when only the adhesive force is
/// measured, once the state held at `d_prev` (force `held`) meets one of the two tests that
/// confirm the minimum known, [`CONFIRM_D_BAR`] past it or [`CONFIRM_RISE`] above it
/// (`confirming`, latched here): at the first approach [`CONFIRM_D_BAR`] past the minimum,
/// or [`CONFIRMING_STEP`] of a `whole` step of the schedule (length) if that lies further.
/// The minimum does not depend on where the steps end (the contact set at a load is the
/// greatest stable subset of the one it came from); what the shorter steps save is their
/// cascades: past the minimum the contact shrinks fast, and a whole step there detaches a
/// wide ring.
fn confirming_end(
    out: &Emitter,
    model: &Model,
    held: f64,
    confirming: &mut bool,
    d_prev: f64,
    d: f64,
    whole: f64,
) -> Option<f64> {
    if model.measure != Measure::AdhesiveForce || !model.confirm_minimum {
        return None;
    }
    let (f_min, d_bar_min) = out.minimum()?;
    let scale = model.scene.scales().approach;
    // A hair beyond, so that the step end's d̄ passes the test despite rounding.
    let d_confirm = (d_bar_min - CONFIRM_D_BAR - 1e-9) * scale;
    *confirming |= d_prev <= d_confirm || held - f_min >= CONFIRM_RISE * f_min.abs();
    let end = d_confirm.min(d_prev - CONFIRMING_STEP * whole);
    (*confirming && end > d).then_some(end)
}

/// One load step from `d_prev` to `d` (lengths): the probe, then the step taken whole or
/// through its onsets, as the onset policy says; the step-end state is recorded.
fn load_step<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
    step: usize,
    d_prev: f64,
    d: f64,
) -> Result<StepEnd, SolverError> {
    let m = run.model.clone();
    let mut eq = Equilibrium::default();
    let probe = onsets::probe(backend, run, d_prev, d, run.last_d, run.held.force, &mut eq)?;
    let refine = match m.onsets {
        Onsets::All => true,
        Onsets::None => false,
        Onsets::NearMinimum => {
            run.window
                .note(backend, &run.fields, step, d_prev, d, &probe)?;
            run.window.is_done() && probe.lower < run.best
        }
    };
    let hold = run.window.holds(step);
    // The step's first onset is known exactly from its probe, at no cost: recorded unless
    // only step ends are asked for.
    if m.onsets != Onsets::None {
        if let Some(state) = onsets::first_onset_state(run, &probe, step, d_prev, d) {
            run.best = run.best.min(state.force);
            out.emit(
                backend,
                &run.fields.c,
                state,
                &mut Equilibrium::default(),
                hold,
            )?;
        }
    }
    let through = Through {
        step,
        d_from: d_prev,
        d_to: d,
        prune: m.onsets != Onsets::All,
        finish: true,
        hold,
        record_first: false,
    };
    let vanished = if refine {
        run.window.walked_online(step);
        onsets::through(backend, run, out, &through, probe, &mut eq)?
    } else {
        let settled = settle(backend, &m, &mut run.fields, d, m.sigma_c, Held::Solved)?;
        let vanished = settled.n_contact == 0;
        eq.absorb(settled);
        vanished
    };
    // The next probe may start on the line through this step's start and end if the
    // contact set did not change in between.
    run.last_d = None;
    if eq.work.rounds == 0 && probe.t >= 1.0 {
        run.last_d = Some(d_prev);
        backend.copy(&run.fields.p_base, &mut run.fields.p_last)?;
    }
    let (state, bounds) = record(
        backend,
        &m,
        &run.fields.c,
        &run.fields.p,
        step,
        Phase::Pulloff,
        d,
        &eq,
    )?;
    run.held = state.clone();
    let end = StepEnd {
        force: state.force,
        d_bar: state.d_bar,
        c_bar: state.c_bar,
        bounds,
        vanished,
    };
    run.window.step_ended(step, state.c_bar);
    out.emit(backend, &run.fields.c, state, &mut eq, hold)?;
    out.release(run.window.hold_from());
    Ok(end)
}

/// If the contact (index box `bounds`, with the model's margin) now fits in
/// [`REGRID_BELOW`] of the domain, carry it to the same grid on a domain fitted to it: finer
/// Δx, σ_c for that Δx, the contact set and p resampled (read back for it), then
/// re-equilibrated at the same approach `d` (length).
fn regrid_if_shrunk<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
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
    backend.download_mask(&run.fields.c, &mut coarse_mask)?;
    let mask = m.resample(&fine, &coarse_mask, false);
    // The kept states of the coarse grid go first, so that both grids are not held at once.
    run.window.reset();
    *backend = backend.sibling(&fine.grid_setup())?;
    let mut c = backend.mask()?;
    backend.upload_mask(&mut c, &mask)?;
    let mut fields = Fields::new(backend, c)?;
    backend.upload(&mut fields.p, &p)?;
    out.release(usize::MAX);
    out.least = None;
    out.regrids.push(RegridEvent {
        d_bar: d / m.scene.scales().approach,
        dx_from: m.dx,
        dx_to: fine.dx,
    });
    run.best = f64::INFINITY;
    run.last_d = None;
    run.fields = fields;
    run.model = fine;
    let mut eq = equilibrate(backend, &run.model, &mut run.fields, d, run.model.sigma_c)?;
    let (state, _) = record(
        backend,
        &run.model,
        &run.fields.c,
        &run.fields.p,
        step,
        Phase::Regrid,
        d,
        &eq,
    )?;
    run.held = state.clone();
    out.emit(backend, &run.fields.c, state, &mut eq, false)?;
    Ok(())
}
