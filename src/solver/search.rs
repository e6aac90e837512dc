//! Which parts of the pull-off have their onsets located
//! ([`Onsets::NearMinimum`](crate::model::Onsets)): a branch and bound over the load, on the
//! bounds and start states [`super::window`] keeps.
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

use super::cost::Activity;
use super::emit::{force_and_c_bar, Emitter, Progress};
use super::equilibrium::{equilibrate, settle, Equilibrium, Fields, Held};
use super::onsets;
use super::probe::{bound_meets, Probe, Through};
use super::window::Snap;
use super::SolverError;
use crate::backend::Backend;

/// A part of the load whose first onset lies in this first fraction of it is split rather
/// than walked: its onsets are dense.
const SPLIT_BELOW: f64 = 0.25;

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

/// Passes of widening before the window takes every step.
const MAX_WIDENINGS: usize = 3;

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
    out.activity = Activity::Search;
    let searched = search_window(backend, run, out);
    out.activity = Activity::WholeSteps;
    searched
}

/// [`refine`]'s search, its work charged as [`Activity::Search`].
fn search_window<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
) -> Result<(), SolverError> {
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
            out.charge(b.step, b.c_bar, b.d_from, &mut eq);
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

/// Charge the work in `eq` to the account at the contact held now (its c̄) and the approach
/// `d` (length), for the end state of `step`.
fn charge_here<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
    step: usize,
    d: f64,
    eq: &mut Equilibrium,
) -> Result<(), SolverError> {
    let (_, c_bar) = force_and_c_bar(backend, &run.model, &run.fields.c, &run.fields.p)?;
    out.charge(step, c_bar, d, eq);
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
            charge_here(backend, run, out, part.step, part.d_from, eq)?;
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
        let (base, c_bar) = force_and_c_bar(backend, &m, &run.fields.c, &run.fields.p)?;
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
            out.charge(part.step, c_bar, d_split, eq);
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
        out.charge(part.step, c_bar, d_split, eq);
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
    use crate::solver::probe::MEET_ABOVE;

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
