//! Which parts of the pull-off have their onsets located
//! ([`Onsets::NearMinimum`](crate::model::Onsets)): a branch and bound over the load.
//!
//! Every step taken whole leaves a bound: its probe's force, below which none of its onsets
//! lies; and, when an element crossed σ_c in it, its first onset's force exactly. While the
//! force falls the steps are taken whole, the bound of each is noted, and the start state of
//! each step whose bound lies below the lowest onset known so far is kept with its probe (a
//! snapshot on the device; going back to the step then solves nothing again). Once the minimum
//! is confirmed, the search goes back to those steps, lowest bound first. A part of the load it
//! searches (a step, or a piece of one) is pruned when its bound lies at or above the lowest
//! onset found; else its first onset is recorded, and if more are likely to follow closely it
//! is split in two: the first piece keeps the part's start and has as bound the same contact
//! set at the piece's end (an interpolation), the second starts from the cascade at the split
//! and is probed to the end. The split lies where the part's bound, a straight line in the
//! load, reaches the lowest onset found (`split_at`): the first piece is then pruned at once,
//! and the search goes on from there; where that point lies before the part's first onset, at
//! the midpoint. Pieces with few onsets are walked through them, the walk stopping as soon as
//! the rest lies above the lowest onset.
//!
//! Every part left unsearched thus has its bound at or above the force minimum found, which
//! the report states as the window's margin. Each located onset is checked against the bound
//! of the part it lies in: should one fall below it (the monotonicity the bound rests on
//! failing on this discrete kernel), the window is widened by twice the shortfall and searched
//! again. After the window, each later step (a whole curve) is walked at once if its bound
//! lies below the lowest onset.

use super::equilibrium::{equilibrate, settle, Equilibrium, Fields, Held};
use super::onsets::{self, Probe, Through};
use super::protocol::{force_of, Emitter, Progress};
use super::SolverError;
use crate::backend::Backend;
use crate::model::Model;
use serde::{Deserialize, Serialize};

/// A part of the load whose first onset lies in this first fraction of it is split rather
/// than walked: its onsets are dense.
const SPLIT_BELOW: f64 = 0.25;

/// Where a part is split ([`split_at`]) or a walk skips ahead ([`bound_meets`]), the bound
/// of the stretch left behind lies this fraction of the force above the lowest onset found:
/// the bound's CG error is covered by [`BOUND_TOLERANCE`], a hundredth of this.
const MEET_ABOVE: f64 = 1e-5;

/// The fraction of a stretch of the load at which its bound, the line from the force `base`
/// at its start to its probe's `lower` (forces), reaches `level` (force) raised by
/// [`MEET_ABOVE`]: none of the stretch's onsets before it lies below that (dimensionless;
/// not finite, or outside (0, 1), where the line does not cross it inside).
pub(super) fn bound_meets(base: f64, lower: f64, level: f64) -> f64 {
    let level = level + MEET_ABOVE * level.abs();
    (base - level) / (base - lower)
}

/// The fraction of `part` at which it is split, given the force (force) below which onsets
/// are searched for (the lowest onset found plus the slack): where the part's bound reaches
/// it ([`bound_meets`]; the first piece is then pruned at once, its onsets all above the
/// level), if that lies after the part's first onset and before its end; else the midpoint.
fn split_at(part: &Part, level: f64) -> f64 {
    let at = bound_meets(part.base, part.lower, level);
    if at.is_finite() && at > part.t && at < 1.0 {
        at
    } else {
        0.5
    }
}

/// Parts are not split below this fraction of a load step.
const MIN_SPLIT: f64 = 1.0 / 4096.0;

/// A located onset counts as below its bound when it is lower by more than this fraction of
/// the force (the CG tolerance's share in both, with a wide margin).
const BOUND_TOLERANCE: f64 = 1e-7;

/// Passes of widening before the window takes every step.
const MAX_WIDENINGS: usize = 3;

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
struct Bound {
    step: usize,
    /// Approach at the step's start and end (lengths).
    d_from: f64,
    d_to: f64,
    /// The probe's force (force): no onset of the step lies below it.
    lower: f64,
    /// Force of the step's start state (force).
    base: f64,
    /// Fraction of the step at which its first element reaches σ_c (1: none does).
    t: f64,
    /// c̄ at the step's end (for the account).
    c_bar: f64,
    /// The pool slot holding the step's start, if kept.
    snapshot: Option<usize>,
    /// Whether it was searched for onsets.
    searched: bool,
}

/// A part of the load to search: from the state kept in `slot` (stable at `d_from`) to
/// `d_from + frac·(d_end − d_from)`, `d_end` being where the slot's probe was solved.
#[derive(Debug, Clone, Copy)]
struct Part {
    step: usize,
    slot: usize,
    d_from: f64,
    d_end: f64,
    frac: f64,
    /// Force at `d_from` (force).
    base: f64,
    /// Force of the part's probe (force): the bound of its onsets.
    lower: f64,
    /// Fraction of the part at which its first element reaches σ_c (1: none does).
    t: f64,
    /// Whether its first onset has been recorded already.
    first_known: bool,
    /// Fraction of a load step it spans.
    share: f64,
}

impl Part {
    /// Approach at the part's end (length).
    fn d_to(&self) -> f64 {
        self.d_from + self.frac * (self.d_end - self.d_from)
    }
}

/// A state kept on the device: its pressure, its contact set and, once probed, the pressure
/// of its contact set at `d_end` of the parts that use it.
struct Snap<F, M> {
    p: F,
    contact: M,
    probe: F,
    /// Parts and bounds that use it.
    refs: usize,
    /// Whether `probe` holds the probe.
    probed: bool,
    /// The probe's relative CG residual.
    residual: f64,
}

/// The device states kept, handed out as slots: at most `capacity`
/// ([`crate::model::snapshot_slots`]). Where none is free, a step's start is reached again
/// by whole steps from an earlier one, and a part of the load is walked instead of split.
struct Pool<F, M> {
    snaps: Vec<Snap<F, M>>,
    capacity: usize,
}

impl<F, M> Pool<F, M> {
    /// A slot with one user, if one is free or can still be made.
    fn take<B: Backend<Field = F, Mask = M>>(
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
    fn release(&mut self, slot: usize) {
        let r = &mut self.snaps[slot].refs;
        *r = r.saturating_sub(1);
    }

    /// Whether a slot is free or can be made.
    fn has_room(&self) -> bool {
        self.snaps.len() < self.capacity || self.snaps.iter().any(|s| s.refs == 0)
    }
}

/// The bounds of the steps and the snapshots to go back to.
pub(super) struct Window<F, M> {
    enabled: bool,
    done: bool,
    bounds: Vec<Bound>,
    /// The least force (force) of an onset known exactly (first onsets of whole steps).
    upper: f64,
    pool: Pool<F, M>,
    /// The start of the first step noted (never evicted).
    origin: Option<usize>,
    /// The largest shortfall of an onset below its bound (force).
    violation: f64,
    /// The least bound (force) of a part set aside unsearched (pruned, or the rest of a walk
    /// cut short).
    least_set_aside: f64,
    report: Refinement,
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
    fn set_aside(&mut self, lower: f64) {
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

/// Make the state of `slot` the one held (u is then unknown).
fn restore<B: Backend>(
    backend: &mut B,
    fields: &mut Fields<B::Field, B::Mask>,
    s: &Snap<B::Field, B::Mask>,
) -> Result<(), SolverError> {
    backend.copy(&s.p, &mut fields.p)?;
    backend.copy_mask(&s.contact, &mut fields.c)?;
    fields.u_valid = false;
    Ok(())
}

/// Go back to the steps that may hold the force minimum and search them for onsets (see
/// the module's notes); then resume from the state held now. Does nothing unless the window
/// is enabled and not yet gone back to.
pub(super) fn refine<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
) -> Result<(), SolverError> {
    if run.window.is_done() {
        return Ok(());
    }
    run.window.done = true;
    run.best = run.best.min(run.window.upper);
    // Keep the state held now, to resume from: in a slot of its own (evicting the kept start
    // with the highest bound if none is free), or, failing that, on the host.
    let resume = Resume::keep(backend, run)?;
    let mut slack = 0.0;
    for pass in 0..=MAX_WIDENINGS {
        let best = run.best;
        let mut order: Vec<usize> = (0..run.window.bounds.len())
            .filter(|&i| {
                let b = &run.window.bounds[i];
                !b.searched && b.lower < best + slack
            })
            .collect();
        if pass == 0 {
            run.window.report.candidates = order.len();
        }
        order.sort_by(|&a, &b| {
            let w = &run.window.bounds;
            w[a].lower.total_cmp(&w[b].lower)
        });
        let violation_before = run.window.violation;
        for i in order {
            let b = run.window.bounds[i];
            if b.lower >= run.best + slack {
                run.window.report.pruned += 1;
                run.window.set_aside(b.lower);
                continue;
            }
            let mut eq = Equilibrium::default();
            let part = root_part(backend, run, i, &mut eq)?;
            search(backend, run, out, part, slack, &mut eq)?;
            run.window.bounds[i].searched = true;
            out.charge(b.step, b.c_bar, &mut eq);
        }
        if run.window.violation <= violation_before {
            break;
        }
        // A located onset fell below its bound: widen by twice the shortfall and search
        // again (every step, after the last pass).
        run.window.report.widened = true;
        slack = if pass + 1 == MAX_WIDENINGS {
            f64::INFINITY
        } else {
            2.0 * run.window.violation
        };
    }
    resume.restore(backend, run)?;
    out.release(usize::MAX);
    Ok(())
}

/// The state a run resumes from after going back: in a pool slot, or on the host.
enum Resume {
    Slot(usize),
    Host { p: Vec<f64>, mask: Vec<bool> },
}

impl Resume {
    /// Keep the state held now.
    fn keep<B: Backend>(
        backend: &mut B,
        run: &mut Progress<B::Field, B::Mask>,
    ) -> Result<Self, SolverError> {
        if let Some(slot) = run.window.pool.take(backend)? {
            let s = &mut run.window.pool.snaps[slot];
            backend.copy(&run.fields.p, &mut s.p)?;
            backend.copy_mask(&run.fields.c, &mut s.contact)?;
            return Ok(Resume::Slot(slot));
        }
        let (nx, ny) = backend.shape();
        let mut p = vec![0.0; nx * ny];
        let mut mask = vec![false; nx * ny];
        backend.download(&run.fields.p, &mut p)?;
        backend.download_mask(&run.fields.c, &mut mask)?;
        Ok(Resume::Host { p, mask })
    }

    /// Make it the state held again.
    fn restore<B: Backend>(
        self,
        backend: &mut B,
        run: &mut Progress<B::Field, B::Mask>,
    ) -> Result<(), SolverError> {
        match self {
            Resume::Slot(slot) => {
                restore(backend, &mut run.fields, &run.window.pool.snaps[slot])?;
                run.window.pool.release(slot);
            }
            Resume::Host { p, mask } => {
                backend.upload(&mut run.fields.p, &p)?;
                backend.upload_mask(&mut run.fields.c, &mask)?;
                run.fields.u_valid = false;
            }
        }
        Ok(())
    }
}

/// The part of the load that is the window's step `i`, its start in a slot: its snapshot, or
/// the state reached again by whole steps from the latest kept start before it (the first
/// step's start is always kept). Its probe is solved when the part is searched.
fn root_part<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    i: usize,
    eq: &mut Equilibrium,
) -> Result<Part, SolverError> {
    let b = run.window.bounds[i];
    let slot = match b.snapshot {
        Some(slot) => {
            run.window.pool.snaps[slot].refs += 1;
            slot
        }
        None => {
            run.window.report.recomputed += 1;
            let from = (0..i)
                .rev()
                .find(|&j| run.window.bounds[j].snapshot.is_some())
                .ok_or_else(|| {
                    SolverError::Backend(crate::backend::BackendError::Unavailable(
                        "no start state was kept to go back to".into(),
                    ))
                })?;
            let start = run.window.bounds[from].snapshot.unwrap_or_default();
            restore(backend, &mut run.fields, &run.window.pool.snaps[start])?;
            let m = run.model.clone();
            for j in from..i {
                let d = run.window.bounds[j].d_to;
                let settled = equilibrate(backend, &m, &mut run.fields, d, m.sigma_c)?;
                eq.absorb(settled);
            }
            match run.window.pool.take(backend)? {
                Some(slot) => {
                    let s = &mut run.window.pool.snaps[slot];
                    backend.copy(&run.fields.p, &mut s.p)?;
                    backend.copy_mask(&run.fields.c, &mut s.contact)?;
                    slot
                }
                None => {
                    // No room: evict the kept start with the highest bound.
                    let origin = run.window.origin;
                    let k = (0..run.window.bounds.len())
                        .filter(|&k| k != i)
                        .filter(|&k| {
                            let s = run.window.bounds[k].snapshot;
                            s.is_some() && s != origin
                        })
                        .max_by(|&a, &c| {
                            let w = &run.window.bounds;
                            w[a].lower.total_cmp(&w[c].lower)
                        })
                        .ok_or_else(|| {
                            SolverError::Backend(crate::backend::BackendError::Unavailable(
                                "no room to keep a start state".into(),
                            ))
                        })?;
                    let slot = run.window.bounds[k].snapshot.take().unwrap_or_default();
                    let s = &mut run.window.pool.snaps[slot];
                    s.refs = 1;
                    s.probed = false;
                    backend.copy(&run.fields.p, &mut s.p)?;
                    backend.copy_mask(&run.fields.c, &mut s.contact)?;
                    slot
                }
            }
        }
    };
    Ok(Part {
        step: b.step,
        slot,
        d_from: b.d_from,
        d_end: b.d_to,
        frac: 1.0,
        base: b.base,
        lower: b.lower,
        t: b.t,
        // Recorded when the step was taken whole.
        first_known: true,
        share: 1.0,
    })
}

/// Search `root` (and the parts it splits into) for the lowest onset, lowest bound first,
/// with the bounds compared to the lowest onset plus `slack` (force).
fn search<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
    root: Part,
    slack: f64,
    eq: &mut Equilibrium,
) -> Result<(), SolverError> {
    let m = run.model.clone();
    let mut open = vec![root];
    let mut unprobed = true;
    while let Some(k) = (0..open.len()).min_by(|&a, &b| open[a].lower.total_cmp(&open[b].lower)) {
        let mut part = open.swap_remove(k);
        if part.lower >= run.best + slack {
            run.window.report.pruned += 1;
            run.window.set_aside(part.lower);
            run.window.pool.release(part.slot);
            continue;
        }
        // The part's start, and its probe: an interpolation of its slot's probe.
        let snap = &run.window.pool.snaps[part.slot];
        restore(backend, &mut run.fields, snap)?;
        if !snap.probed {
            // The root, its start reached again: probe its step now.
            run.window.report.probed_again += 1;
            let probe = onsets::probe(backend, run, part.d_from, part.d_end, None, part.base, eq)?;
            let s = &mut run.window.pool.snaps[part.slot];
            backend.copy(&run.fields.p, &mut s.probe)?;
            s.probed = true;
            s.residual = probe.residual;
            part.lower = probe.lower;
            part.t = probe.t;
            debug_assert!(unprobed);
            unprobed = false;
            if part.lower >= run.best + slack {
                open.push(part);
                continue;
            }
        }
        let s = &run.window.pool.snaps[part.slot];
        let f = &mut run.fields;
        backend.copy(&s.p, &mut f.p_base)?;
        backend.lerp(&f.c, &s.p, &s.probe, part.frac, &mut f.p)?;
        let residual = s.residual;
        if part.t >= 1.0 {
            run.window.pool.release(part.slot);
            continue;
        }
        let probe = Probe {
            base: part.base,
            lower: part.lower,
            t: part.t,
            residual,
        };
        let walk = Through {
            step: part.step,
            d_from: part.d_from,
            d_to: part.d_to(),
            prune: slack.is_finite(),
            finish: false,
            hold: true,
            record_first: !part.first_known,
        };
        let split =
            part.t < SPLIT_BELOW && part.share / 2.0 >= MIN_SPLIT && run.window.pool.has_room();
        if !split {
            run.window.report.walks += 1;
            onsets::through(backend, run, out, &walk, probe, eq)?;
            run.window.pool.release(part.slot);
            continue;
        }
        run.window.report.splits += 1;
        // Its first onset, exactly: it lies in the first piece.
        if !part.first_known {
            let d_on = part.d_from + part.t * (part.d_to() - part.d_from);
            onsets::record_onset(backend, run, out, &walk, &probe, d_on)?;
        }
        let at = split_at(&part, run.best + slack);
        // The first piece: the same start, the same contact set to the split.
        let first = Part {
            frac: part.frac * at,
            lower: part.base + at * (part.lower - part.base),
            t: part.t / at,
            first_known: true,
            share: part.share * at,
            ..part
        };
        run.window.pool.snaps[part.slot].refs += 1;
        open.push(first);
        // The second piece: the cascade at the split, probed to the part's end.
        let d_split = part.d_from + at * (part.d_to() - part.d_from);
        {
            let s = &run.window.pool.snaps[part.slot];
            let f = &mut run.fields;
            backend.lerp(&f.c, &s.p, &s.probe, part.frac * at, &mut f.p)?;
            f.u_valid = false;
        }
        run.window.pool.release(part.slot);
        let settled = settle(
            backend,
            &m,
            &mut run.fields,
            d_split,
            m.sigma_c,
            Held::Solved,
        )?;
        let vanished = settled.n_contact == 0;
        eq.absorb(settled);
        if vanished {
            continue;
        }
        let base = force_of(backend, &m, &run.fields.c, &run.fields.p)?;
        let Some(slot) = run.window.pool.take(backend)? else {
            // No room to keep it: walk the second piece from here.
            let probe = onsets::probe(backend, run, d_split, part.d_to(), None, base, eq)?;
            let walk = Through {
                d_from: d_split,
                record_first: true,
                ..walk
            };
            run.window.report.walks += 1;
            onsets::through(backend, run, out, &walk, probe, eq)?;
            continue;
        };
        {
            let s = &mut run.window.pool.snaps[slot];
            backend.copy(&run.fields.p, &mut s.p)?;
            backend.copy_mask(&run.fields.c, &mut s.contact)?;
        }
        let probe = onsets::probe(backend, run, d_split, part.d_to(), None, base, eq)?;
        let s = &mut run.window.pool.snaps[slot];
        backend.copy(&run.fields.p, &mut s.probe)?;
        s.probed = true;
        s.residual = probe.residual;
        if probe.t >= 1.0 || probe.lower >= run.best + slack {
            if probe.t < 1.0 {
                run.window.report.pruned += 1;
                run.window.set_aside(probe.lower);
            }
            run.window.pool.release(slot);
            continue;
        }
        open.push(Part {
            slot,
            d_from: d_split,
            d_end: part.d_to(),
            frac: 1.0,
            base,
            lower: probe.lower,
            t: probe.t,
            first_known: false,
            share: part.share * (1.0 - at),
            ..part
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part(base: f64, lower: f64, t: f64) -> Part {
        Part {
            step: 1,
            slot: 0,
            d_from: 1.0,
            d_end: 0.0,
            frac: 1.0,
            base,
            lower,
            t,
            first_known: true,
            share: 1.0,
        }
    }

    #[test]
    fn a_part_is_split_where_its_bound_meets_the_lowest_onset() {
        // Bound from −1.0 at the start to −2.0 at the end; first onset at 0.1 (−1.1).
        let p = part(-1.0, -2.0, 0.1);
        let level = -1.8;
        let at = split_at(&p, level);
        let bound = p.base + at * (p.lower - p.base);
        // The first piece's bound lies above the level, by MEET_ABOVE of it: pruned at once.
        assert!(bound > level, "{at} {bound}");
        assert!(
            (bound - level - MEET_ABOVE * level.abs()).abs() < 1e-12,
            "{bound}"
        );
        assert!((at - 0.8).abs() < 1e-4, "{at}");
        // Where the level is met before the first onset, or not inside the part: the midpoint.
        assert_eq!(split_at(&part(-1.0, -2.0, 0.6), -1.5), 0.5);
        assert_eq!(split_at(&part(-1.0, -2.0, 0.1), -2.5), 0.5);
        assert_eq!(split_at(&part(-1.0, -1.0, 0.1), -1.5), 0.5);
        assert_eq!(split_at(&part(-1.0, -2.0, 0.1), f64::NEG_INFINITY), 0.5);
    }
}
