//! The window of load steps that may hold the force minimum
//! ([`Onsets::NearMinimum`](crate::model::Onsets)): each whole step's bound, the start states
//! kept on the device to go back to, and the report of what was searched. The search itself,
//! a branch and bound over these steps, is `search`.

use super::equilibrium::Fields;
use super::probe::Probe;
use super::SolverError;
use crate::backend::Backend;
use crate::model::Model;
use serde::{Deserialize, Serialize};

/// A located onset counts as below its bound when it is lower by more than this fraction of
/// the force (the CG tolerance's share in both, with a wide margin).
const BOUND_TOLERANCE: f64 = 1e-7;

/// Which parts of the load had their onsets located, and the check that they hold the force
/// minimum.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Refinement {
    /// Load steps searched for onsets, in the order of the load.
    pub steps: Vec<usize>,
    /// d̄ at the start of the first of them (dimensionless).
    pub d_bar_from: Option<f64>,
    /// d̄ at the end of the last of them (dimensionless).
    pub d_bar_to: Option<f64>,
    /// Steps whose bound lay below the lowest onset known when the window was gone back to.
    pub candidates: usize,
    /// Parts of the load (steps or pieces) set aside unsearched: the lowest onset found by
    /// then lay at or below their bound.
    pub pruned: usize,
    /// Parts split in two.
    pub splits: usize,
    /// Parts walked through their onsets.
    pub walks: usize,
    /// Walks stopped before their part's end: the rest lay above the lowest onset.
    pub cut_short: usize,
    /// Candidates whose start had not been kept, reached again by whole steps.
    pub recomputed: usize,
    /// Candidates probed again when gone back to: those whose start was reached again (a
    /// kept start keeps its step's probe too).
    #[serde(default)]
    pub probed_again: usize,
    /// Load steps taken whole and not searched, each with its bound checked against the
    /// minimum.
    pub whole_steps: usize,
    /// The least (bound − F̄ of the minimum) over every part of the load left unsearched:
    /// the steps taken whole, the parts pruned and the rests of the walks cut short (≥ 0:
    /// none of them can hold an onset below the minimum; dimensionless); `None` with none.
    pub margin_f_bar: Option<f64>,
    /// The most a located onset fell below the bound of its part (F̄; 0: the bound held
    /// everywhere).
    pub bound_violation_f_bar: f64,
    /// Whether the window was widened because a bound failed.
    pub widened: bool,
}

/// A step's bound.
#[derive(Debug, Clone, Copy)]
pub(super) struct Bound {
    /// The load step.
    pub(super) step: usize,
    /// Approach at the step's start (length).
    pub(super) d_from: f64,
    /// Approach at the step's end (length).
    pub(super) d_to: f64,
    /// The probe's force (force): no onset of the step lies below it.
    pub(super) lower: f64,
    /// Force of the step's start state (force).
    pub(super) base: f64,
    /// Fraction of the step at which its first element reaches σ_c (1: none does).
    pub(super) t: f64,
    /// c̄ at the step's end (for the account).
    pub(super) c_bar: f64,
    /// The pool slot holding the step's start, if kept.
    pub(super) snapshot: Option<usize>,
    /// Whether it was searched for onsets.
    pub(super) searched: bool,
}

/// A state kept on the device: its pressure, its contact set and, once probed, the pressure
/// of its contact set at `d_end` of the parts that use it.
pub(super) struct Snap<F, M> {
    /// The state's pressure.
    pub(super) p: F,
    /// Its contact set.
    pub(super) contact: M,
    /// The pressure of its contact set at the parts' `d_end`, once probed.
    pub(super) probe: F,
    /// Parts and bounds that use it.
    pub(super) refs: usize,
    /// Whether `probe` holds the probe.
    pub(super) probed: bool,
    /// The probe's relative CG residual.
    pub(super) residual: f64,
}

/// The device states kept, handed out as slots: at most `capacity`
/// ([`crate::model::snapshot_slots`]). Where none is free, a step's start is reached again
/// by whole steps from an earlier one, and a part of the load is walked instead of split.
pub(super) struct Pool<F, M> {
    /// The states kept, by slot.
    pub(super) snaps: Vec<Snap<F, M>>,
    /// The most slots there may be.
    capacity: usize,
}

impl<F, M> Pool<F, M> {
    /// A slot with one user, if one is free or can still be made.
    pub(super) fn take<B: Backend<Field = F, Mask = M>>(
        &mut self,
        backend: &mut B,
    ) -> Result<Option<usize>, SolverError> {
        if let Some(k) = self.snaps.iter().position(|s| s.refs == 0) {
            self.snaps[k].refs = 1;
            self.snaps[k].probed = false;
            return Ok(Some(k));
        }
        if self.snaps.len() >= self.capacity {
            return Ok(None);
        }
        self.snaps.push(Snap {
            p: backend.field()?,
            contact: backend.mask()?,
            probe: backend.field()?,
            refs: 1,
            probed: false,
            residual: 0.0,
        });
        Ok(Some(self.snaps.len() - 1))
    }

    /// One user fewer of `slot`.
    pub(super) fn release(&mut self, slot: usize) {
        let r = &mut self.snaps[slot].refs;
        *r = r.saturating_sub(1);
    }

    /// Whether a slot is free or can be made.
    pub(super) fn has_room(&self) -> bool {
        self.snaps.len() < self.capacity || self.snaps.iter().any(|s| s.refs == 0)
    }
}

/// The bounds of the steps and the snapshots to go back to.
pub(super) struct Window<F, M> {
    enabled: bool,
    /// Whether the window has been gone back to.
    pub(super) done: bool,
    /// Every whole step's bound, in the order of the load.
    pub(super) bounds: Vec<Bound>,
    /// The least force (force) of an onset known exactly (first onsets of whole steps).
    pub(super) upper: f64,
    /// The start states kept on the device.
    pub(super) pool: Pool<F, M>,
    /// The start of the first step noted (never evicted).
    pub(super) origin: Option<usize>,
    /// The largest shortfall of an onset below its bound (force).
    pub(super) violation: f64,
    /// The least bound (force) of a part set aside unsearched (pruned, or the rest of a walk
    /// cut short).
    least_set_aside: f64,
    /// What was searched, as counts (completed by [`Window::report`]).
    pub(super) report: Refinement,
}

impl<F, M> Window<F, M> {
    /// A window for a grid of `elements`, used only if `enabled`.
    pub fn new(enabled: bool, elements: usize) -> Self {
        Window {
            enabled,
            done: false,
            bounds: Vec::new(),
            upper: f64::INFINITY,
            pool: Pool {
                snaps: Vec::new(),
                capacity: crate::model::snapshot_slots(elements),
            },
            origin: None,
            violation: 0.0,
            least_set_aside: f64::INFINITY,
            report: Refinement::default(),
        }
    }

    /// Whether the window has been gone back to (steps are then walked as they come).
    pub fn is_done(&self) -> bool {
        !self.enabled || self.done
    }

    /// Forget everything (the grid changed): the snapshots are dropped.
    pub fn reset(&mut self) {
        let capacity = self.pool.capacity;
        *self = Window::new(self.enabled, 0);
        self.pool.capacity = capacity;
    }

    /// The first load step whose states must be held back: the earliest step that may still
    /// be gone back to (`usize::MAX`: none).
    pub fn hold_from(&self) -> usize {
        if self.is_done() {
            return usize::MAX;
        }
        self.bounds
            .iter()
            .filter(|b| b.lower < self.upper)
            .map(|b| b.step)
            .min()
            .unwrap_or(usize::MAX)
    }

    /// Whether the states of `step` must be held back.
    pub fn holds(&self, step: usize) -> bool {
        step >= self.hold_from()
    }

    /// Note the bound of `step` (from `d_from` to `d_to`, lengths) from its `probe`, keeping
    /// its start (the `p_base` and contact set held now) if it may be gone back to.
    pub fn note<B: Backend<Field = F, Mask = M>>(
        &mut self,
        backend: &mut B,
        fields: &Fields<F, M>,
        step: usize,
        d_from: f64,
        d_to: f64,
        probe: &Probe,
    ) -> Result<(), SolverError> {
        if !self.enabled {
            return Ok(());
        }
        let mut snapshot = None;
        if !self.done {
            if let Some(f) = probe.first_onset() {
                self.upper = self.upper.min(f);
            }
            let upper = self.upper;
            for b in &mut self.bounds {
                if b.lower >= upper && b.snapshot.is_some() && b.snapshot != self.origin {
                    if let Some(s) = b.snapshot.take() {
                        self.pool.release(s);
                    }
                }
            }
            if self.origin.is_none() || probe.lower < upper {
                snapshot = self.take_slot(backend, probe.lower)?;
                if let Some(slot) = snapshot {
                    // The start, and the probe just solved from it (in `p`): going back to
                    // the step then needs no probe of its own.
                    let s = &mut self.pool.snaps[slot];
                    backend.copy(&fields.p_base, &mut s.p)?;
                    backend.copy_mask(&fields.c, &mut s.contact)?;
                    backend.copy(&fields.p, &mut s.probe)?;
                    s.probed = true;
                    s.residual = probe.residual;
                    if self.origin.is_none() {
                        self.origin = Some(slot);
                    }
                }
            }
        }
        self.bounds.push(Bound {
            step,
            d_from,
            d_to,
            lower: probe.lower,
            base: probe.base,
            t: probe.t,
            c_bar: f64::NAN,
            snapshot,
            searched: false,
        });
        Ok(())
    }

    /// A pool slot for a step of bound `lower`: a free one, a new one, or that of the kept
    /// step with the highest bound if it lies above `lower` (`None`: not worth keeping). Its
    /// contents are to be overwritten: the start and the probe of the step noted.
    fn take_slot<B: Backend<Field = F, Mask = M>>(
        &mut self,
        backend: &mut B,
        lower: f64,
    ) -> Result<Option<usize>, SolverError> {
        if let Some(s) = self.pool.take(backend)? {
            return Ok(Some(s));
        }
        let origin = self.origin;
        let worst = self
            .bounds
            .iter_mut()
            .filter(|b| b.snapshot.is_some() && b.snapshot != origin)
            .max_by(|a, b| a.lower.total_cmp(&b.lower));
        // The caller fills the slot with the new step's start and probe.
        Ok(match worst {
            Some(b) if b.lower > lower => b.snapshot.take(),
            _ => None,
        })
    }

    /// The step's end state has c̄ = `c_bar`.
    pub fn step_ended(&mut self, step: usize, c_bar: f64) {
        if let Some(b) = self.bounds.iter_mut().rev().find(|b| b.step == step) {
            b.c_bar = c_bar;
        }
    }

    /// A step walked as it came (after the window): noted in the report.
    pub fn walked_online(&mut self, step: usize) {
        if let Some(b) = self.bounds.iter_mut().rev().find(|b| b.step == step) {
            b.searched = true;
        }
        self.report.walks += 1;
    }

    /// An onset of `force` was located in `step`, in a part of it whose bound is `lower`
    /// (forces).
    pub fn onset_found(&mut self, _step: usize, force: f64, lower: f64) {
        let shortfall = lower - force;
        if shortfall > BOUND_TOLERANCE * force.abs() {
            self.violation = self.violation.max(shortfall);
        }
    }

    /// The walk through `step` stopped early: the rest, of bound `lower` (force), lay above
    /// the lowest onset.
    pub fn pruned_rest(&mut self, _step: usize, lower: f64) {
        self.report.cut_short += 1;
        self.set_aside(lower);
    }

    /// A walk skipped a stretch of its part whose bound, `lower` (force), lay above the
    /// lowest onset: set aside unsearched, like a pruned part.
    pub fn skipped(&mut self, lower: f64) {
        self.report.pruned += 1;
        self.set_aside(lower);
    }

    /// A part of bound `lower` (force) was set aside unsearched.
    pub(super) fn set_aside(&mut self, lower: f64) {
        self.least_set_aside = self.least_set_aside.min(lower);
    }

    /// The report, with its d̄ and F̄ in the scales of `model` and the minimum's force `best`.
    pub fn report(&self, model: &Model, best: f64) -> Option<Refinement> {
        if !self.enabled || self.bounds.is_empty() {
            return None;
        }
        let sc = model.scene.scales();
        let mut r = self.report.clone();
        let searched: Vec<&Bound> = self.bounds.iter().filter(|b| b.searched).collect();
        r.steps = searched.iter().map(|b| b.step).collect();
        r.steps.sort_unstable();
        r.steps.dedup();
        r.d_bar_from = searched
            .iter()
            .map(|b| b.d_from)
            .reduce(f64::max)
            .map(|d| d / sc.approach);
        r.d_bar_to = searched
            .iter()
            .map(|b| b.d_to)
            .reduce(f64::min)
            .map(|d| d / sc.approach);
        let whole: Vec<&Bound> = self.bounds.iter().filter(|b| !b.searched).collect();
        r.whole_steps = whole.len();
        r.margin_f_bar = whole
            .iter()
            .map(|b| b.lower)
            .chain(Some(self.least_set_aside).filter(|l| l.is_finite()))
            .map(|lower| (lower - best) / sc.force)
            .reduce(f64::min)
            .filter(|_| best.is_finite());
        r.bound_violation_f_bar = self.violation / sc.force;
        Some(r)
    }
}
