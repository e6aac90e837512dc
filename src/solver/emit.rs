//! Where a pull-off's states go and what it carries from state to state: the [`Emitter`]
//! (states handed on, or held while onsets may still be located among them, and the run's
//! account), the pull-off's [`Progress`] (grid, fields, window), and the measurement of a
//! state ([`record`], [`force_of`]). The protocol, the onsets' walk and the window's search
//! all build on these; this module imports none of them.

use super::cost::{Activity, CostAccount, Work};
use super::equilibrium::{Equilibrium, Fields};
use super::retry::CgRetry;
use super::state::{Phase, RegridEvent, State};
use super::window::{Refinement, Window};
use super::SolverError;
use crate::backend::{Backend, ContactKernels, ContactMeasure};
use crate::model::Model;
use std::f64::consts::PI;

/// Measure and normalise the state of pressure `p` on the backend's contact set (reduced on
/// the backend's device); also returns the contact's index box (`None` without contact).
#[allow(clippy::too_many_arguments)]
pub(super) fn record<B: Backend>(
    backend: &mut B,
    model: &Model,
    c: &B::Mask,
    p: &B::Field,
    step: usize,
    phase: Phase,
    d: f64,
    eq: &Equilibrium,
) -> Result<(State, Option<[usize; 4]>), SolverError> {
    let m = backend.measure(c, p, model.mesh.chord_axes())?;
    let (a_el, b_el) = m.half_lengths;
    let n = m.count;
    let dx = model.dx;
    let sc = model.scene.scales();
    let (force, area, mean_radius) = force_area_radius(model, &m);
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
        cg_iterations: eq.work.cg_iterations,
        detach_sweeps: eq.work.rounds,
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

/// A measurement's force (force), contact area (length²) and mean contact radius √(A/π)
/// (length).
fn force_area_radius(model: &Model, m: &ContactMeasure) -> (f64, f64, f64) {
    let dx = model.dx;
    let area = m.count as f64 * dx * dx;
    (m.sum * dx * dx, area, (area / PI).sqrt())
}

/// The force (force) of pressure `p` on the backend's contact set, reduced on its device.
pub(super) fn force_of<B: Backend>(
    backend: &mut B,
    model: &Model,
    c: &B::Mask,
    p: &B::Field,
) -> Result<f64, SolverError> {
    Ok(force_and_c_bar(backend, model, c, p)?.0)
}

/// The force (force) of pressure `p` on the backend's contact set and that contact's mean
/// radius c̄ (dimensionless), reduced on its device.
pub(super) fn force_and_c_bar<B: Backend>(
    backend: &mut B,
    model: &Model,
    c: &B::Mask,
    p: &B::Field,
) -> Result<(f64, f64), SolverError> {
    let m = backend.measure(c, p, model.mesh.chord_axes())?;
    let (force, _, radius) = force_area_radius(model, &m);
    Ok((force, radius / model.scene.scales().length))
}

/// Where states go: to the observer at once, or held while onsets may still be located
/// among them; and the run's account.
pub(super) struct Emitter<'a> {
    push: &'a mut dyn FnMut(State, Option<&[bool]>),
    /// Sees each state held back when it is found; false: stop.
    held: &'a mut dyn FnMut(&State) -> bool,
    /// Whether the observer sees each state's contact mask.
    with_contact: bool,
    /// Whether to keep the contact mask of the least-force pull-off state (read back only
    /// when a state lowers it): the straight fronts' check of a measured surface.
    keep_min_contact: bool,
    /// That state and its mask, on the grid of the latest state.
    pub(super) min_contact: Option<(State, Vec<bool>)>,
    /// False once the observer asked to stop.
    go_on: &'a std::cell::Cell<bool>,
    /// States held back, with their masks if the observer sees them.
    pending: Vec<(State, Option<Vec<bool>>)>,
    /// Least force (force) handed on since the last re-grid, and its d̄.
    pub(super) least: Option<(f64, f64)>,
    /// The grid changes made so far.
    pub(super) regrids: Vec<RegridEvent>,
    /// Whether the run stopped once the force minimum was confirmed.
    pub(super) stopped_after_minimum: bool,
    /// The safer CG retries of every equilibrium so far.
    pub(super) retries: Vec<CgRetry>,
    /// The run's cost account.
    pub(super) cost: CostAccount,
    /// The window of located onsets, once there is one.
    pub(super) refinement: Option<Refinement>,
    /// What the work charged now is for.
    pub(super) activity: Activity,
    /// Every piece of work charged: the approach it was done at (length), what for, the
    /// work; split at the force minimum once the run ends ([`CostAccount::split_at_minimum`]).
    pub(super) ledger: Vec<(f64, Activity, Work)>,
}

impl<'a> Emitter<'a> {
    /// An emitter that hands states to `push` (with their masks if `with_contact`), shows
    /// held ones to `held`, and stops recording once `go_on` is false.
    pub(super) fn new(
        push: &'a mut dyn FnMut(State, Option<&[bool]>),
        held: &'a mut dyn FnMut(&State) -> bool,
        with_contact: bool,
        go_on: &'a std::cell::Cell<bool>,
    ) -> Self {
        Emitter {
            push,
            held,
            with_contact,
            keep_min_contact: false,
            min_contact: None,
            go_on,
            pending: Vec::new(),
            least: None,
            regrids: Vec::new(),
            stopped_after_minimum: false,
            retries: Vec::new(),
            cost: CostAccount::default(),
            refinement: None,
            activity: Activity::WholeSteps,
            ledger: Vec::new(),
        }
    }

    /// Record a state: its work goes to the account (in its c̄ band), its retries to the
    /// run's; then it is handed on, or held if `hold`, with the contact mask read back if
    /// the observer sees masks. Once the observer has asked to stop, no state is recorded:
    /// the run ends here with [`SolverError::Interrupted`].
    pub(super) fn emit<B: ContactKernels>(
        &mut self,
        backend: &mut B,
        c: &B::Mask,
        state: State,
        eq: &mut Equilibrium,
        hold: bool,
    ) -> Result<(), SolverError> {
        if !self.go_on() {
            return Err(SolverError::Interrupted);
        }
        self.cost.charge(state.c_bar, eq.work);
        self.ledger.push((state.d, self.activity, eq.work));
        eq.work = Work::default();
        self.retries.append(&mut eq.retries);
        if state.phase == Phase::Onset {
            self.cost.onset(state.c_bar);
        } else if state.phase == Phase::Pulloff {
            self.cost.step(state.c_bar);
        }
        let lowers = self.keep_min_contact
            && !state.phase.is_loading()
            && state.phase != Phase::Approach
            && self
                .min_contact
                .as_ref()
                .is_none_or(|(m, _)| m.dx != state.dx || state.force < m.force);
        let mask = if self.with_contact || lowers {
            let (nx, ny) = backend.shape();
            let mut mask = vec![false; nx * ny];
            backend.download_mask(c, &mut mask)?;
            Some(mask)
        } else {
            None
        };
        let mut mask = mask;
        if lowers {
            // Moved where the observer does not see masks, copied where it does.
            let kept = if self.with_contact {
                mask.clone()
            } else {
                mask.take()
            };
            self.min_contact = Some((state.clone(), kept.unwrap_or_default()));
        }
        self.cost.states += 1;
        if hold && !(self.held)(&state) {
            self.go_on.set(false);
        }
        self.pending.push((state, mask));
        if !hold {
            self.release(usize::MAX);
        }
        Ok(())
    }

    /// Charge work that produced no state of its own (a step's onsets located on going
    /// back), done at a contact of mean radius `c_bar` and approach `d` (length), to the
    /// account, and to the end state of `step` if it is still held (so that the states'
    /// `cg_iterations` add up to the run's).
    pub(super) fn charge(&mut self, step: usize, c_bar: f64, d: f64, eq: &mut Equilibrium) {
        self.cost.charge(c_bar, eq.work);
        self.ledger.push((d, self.activity, eq.work));
        if let Some((s, _)) = self
            .pending
            .iter_mut()
            .find(|(s, _)| s.step == step && s.phase == Phase::Pulloff)
        {
            s.cg_iterations += eq.work.cg_iterations;
            s.detach_sweeps += eq.work.rounds;
            s.cg_residual = s.cg_residual.max(eq.cg_residual);
        }
        eq.work = Work::default();
        self.retries.append(&mut eq.retries);
    }

    /// Keep the contact mask of the least-force pull-off state ([`Emitter::min_contact`]).
    pub(super) fn keep_min_contact(&mut self) {
        self.keep_min_contact = true;
    }

    /// Hand on the held states of load steps before `step`, in the order of the load
    /// (decreasing approach; an onset before the step end it precedes).
    pub(super) fn release(&mut self, step: usize) {
        self.pending.sort_by(|a, b| b.0.d.total_cmp(&a.0.d));
        let n = self.pending.iter().take_while(|s| s.0.step < step).count();
        let released: Vec<_> = self.pending.drain(..n).collect();
        for (s, m) in released {
            if !self.go_on() {
                break;
            }
            if self.least.is_none_or(|(f, _)| s.force < f) {
                self.least = Some((s.force, s.d_bar));
            }
            (self.push)(s, m.as_deref());
        }
    }

    /// Whether the observer still wants states.
    pub(super) fn go_on(&self) -> bool {
        self.go_on.get()
    }

    /// Least force (force) since the last re-grid, held states included, and its d̄.
    pub(super) fn minimum(&self) -> Option<(f64, f64)> {
        self.pending
            .iter()
            .map(|(s, _)| (s.force, s.d_bar))
            .chain(self.least)
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// Whether a step-end state of `force` (force) at `d_bar` confirms the minimum:
    /// [`CONFIRM_D_BAR`] or more past it and above it by [`CONFIRM_RISE`] of its size.
    pub(super) fn minimum_confirmed(&self, force: f64, d_bar: f64) -> bool {
        self.minimum().is_some_and(|(f_min, d_min)| {
            d_bar <= d_min - CONFIRM_D_BAR && force - f_min >= CONFIRM_RISE * f_min.abs()
        })
    }
}

/// How far past the force minimum (in d̄) the approach must go to confirm it: the sawtooth's
/// period on coarse grids is a few hundredths; on JKR's curve F̄ has risen by 3.4 % there.
pub const CONFIRM_D_BAR: f64 = 0.1;

/// Rise of the step-end force above its minimum (of |F_min|) needed, with
/// [`CONFIRM_D_BAR`], to confirm the minimum.
pub const CONFIRM_RISE: f64 = 0.02;

/// The pull-off's progress: the current grid and fields, and what the onset policy keeps.
pub(super) struct Progress<F, M> {
    /// The model of the current grid.
    pub model: Model,
    /// The solver's fields.
    pub fields: Fields<F, M>,
    /// The approach (length) of the state whose p `fields.p_last` holds, if it is the step
    /// end before the current one on this grid (for the probe's predicted start).
    pub last_d: Option<f64>,
    /// The stable state held at the last step's end (or the press, or the re-grid).
    pub held: State,
    /// The least force (force) of an onset located exactly on this grid (+∞ before any).
    pub best: f64,
    /// The steps' bounds and the snapshots to go back to ([`Onsets::NearMinimum`]).
    pub window: Window<F, M>,
    /// Whether re-gridding is still allowed (not once the minimum is confirmed).
    pub may_regrid: bool,
}
