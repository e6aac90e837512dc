//! A load step's probe, and the walk through its detachment onsets.
//!
//! With the contact set fixed, p is affine in the approach d: the probe (the set a step
//! starts from, solved at the step's end) gives every state of that set in between, the
//! approach at which its first element reaches σ_c (an onset: a local minimum of the
//! sawtooth F(d)) and a lower bound of every onset in the step. The walk records each onset
//! (an interpolation, no solve of its own), resolves the detachment cascade just past it and
//! probes again from there, so the curve and its force minimum do not depend on the step
//! size. A walk that may prune stops as soon as the bound of the rest of the step lies at or
//! above the lowest onset located: no onset there can be the minimum; and after each onset it
//! goes on from where the rest's bound (a straight line in the load) reaches the lowest onset,
//! if that lies further: no onset before that point can be the minimum either.

use super::cg::Goal;
use super::emit::{force_of, record, Emitter, Progress};
use super::equilibrium::{settle, solve_for, Equilibrium, Held};
use super::probe::{bound_meets, Probe, Through};
use super::state::{Phase, State};
use super::SolverError;
use crate::backend::Backend;

/// Fraction of the rest of a step by which the load is pushed past an onset, so that the
/// element that reached σ_c is beyond it by more than CG's round-off.
const ONSET_PUSH: f64 = 1e-4;

/// Limit on onsets located inside one load step before the rest of it is taken at once.
const MAX_ONSETS_PER_STEP: usize = 100_000;

/// Probe the step from `d_from` to `d_to` (lengths): keep the stable state held (force
/// `base`) in `p_base` and solve its contact set at `d_to` into `p`. With `last_d`, the
/// approach of the step end before it (whose p is in `p_last`, on the same contact set),
/// the solve starts from the straight line through the two: exact, since p is affine in d
/// on a fixed set. Otherwise it starts from the state held, whose K p is known where the
/// cascade that led to it ended with an exact solve.
pub(super) fn probe<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    d_from: f64,
    d_to: f64,
    last_d: Option<f64>,
    base: f64,
    eq: &mut Equilibrium,
) -> Result<Probe, SolverError> {
    let f = &mut run.fields;
    backend.copy(&f.p, &mut f.p_base)?;
    if let Some(d_last) = last_d.filter(|&dl| dl != d_from) {
        let t = 1.0 + (d_to - d_from) / (d_from - d_last);
        backend.lerp(&f.c, &f.p_last, &f.p_base, t, &mut f.p)?;
        f.u_valid = false;
    }
    let solve = solve_for(backend, &run.model, f, d_to, Goal::Exact)?;
    let residual = solve.residual;
    eq.add_solve(solve);
    let lower = force_of(backend, &run.model, &run.fields.c, &run.fields.p)?;
    let f = &run.fields;
    let t = backend.first_crossing(&f.c, &f.p_base, &f.p, run.model.sigma_c)?;
    Ok(Probe {
        base,
        lower,
        t,
        residual,
    })
}

/// Walk through the onsets of a step whose probe has been made (`probe`, with `p_base` and
/// `p` as [`probe`] left them), recording each; the work goes into `eq`. Returns whether the
/// contact vanished.
pub(super) fn through<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
    walk: &Through,
    probe: Probe,
    eq: &mut Equilibrium,
) -> Result<bool, SolverError> {
    let m = run.model.clone();
    let d_to = walk.d_to;
    let mut d_c = walk.d_from;
    let mut probe = probe;
    let mut record_this = walk.record_first;
    for _ in 0..MAX_ONSETS_PER_STEP {
        if walk.prune && probe.lower >= run.best {
            run.window.pruned_rest(walk.step, probe.lower);
            break;
        }
        if probe.t >= 1.0 {
            break;
        }
        let mut onset_force = None;
        if record_this {
            let d_on = d_c + probe.t * (d_to - d_c);
            onset_force = Some(record_onset(backend, run, out, walk, &probe, d_on)?);
        }
        record_this = true;
        let mut t_push = (probe.t + ONSET_PUSH).min(1.0);
        if walk.prune {
            // No onset lies below the lowest one found before the rest's bound reaches it:
            // the walk goes on from there.
            let meets = bound_meets(probe.base, probe.lower, run.best);
            if meets.is_finite() && meets > t_push && meets < 1.0 {
                let level = probe.base + meets * (probe.lower - probe.base);
                run.window.skipped(level);
                t_push = meets;
            }
        }
        let f = &mut run.fields;
        std::mem::swap(&mut f.p, &mut f.p_probe);
        backend.lerp(&f.c, &f.p_base, &f.p_probe, t_push, &mut f.p)?;
        f.u_valid = false;
        d_c += t_push * (d_to - d_c);
        if t_push >= 1.0 {
            break;
        }
        let settled = settle(backend, &m, f, d_c, m.sigma_c, Held::Solved)?;
        let vanished = settled.n_contact == 0;
        eq.absorb(settled);
        if vanished {
            return Ok(true);
        }
        if let Some(before) = onset_force {
            record_jump(backend, run, out, walk, (d_c, before), eq)?;
        }
        // The next probe starts from the state just reached, whose K p is known (a start
        // from the last probe, on the contact set left, was measured to save nothing); its
        // force is the start of the rest's bound where the walk may skip.
        let base = if walk.prune {
            force_of(backend, &m, &run.fields.c, &run.fields.p)?
        } else {
            f64::NAN
        };
        probe = self::probe(backend, run, d_c, d_to, None, base, eq)?;
    }
    if !walk.finish {
        return Ok(false);
    }
    let settled = settle(backend, &m, &mut run.fields, d_to, m.sigma_c, Held::Solved)?;
    let vanished = settled.n_contact == 0;
    eq.absorb(settled);
    Ok(vanished)
}

/// The first onset of a step from `d_from` to `d_to` (lengths) whose `probe` found one: the
/// stable state held at the step's start (its contact set, chords and c̄ are the onset's)
/// at the interpolated approach and force. Made without any work on the device.
pub(super) fn first_onset_state<F, M>(
    run: &Progress<F, M>,
    probe: &Probe,
    step: usize,
    d_from: f64,
    d_to: f64,
) -> Option<State> {
    let force = probe.first_onset()?;
    let d = d_from + probe.t * (d_to - d_from);
    let sc = run.model.scene.scales();
    Some(State {
        step,
        phase: Phase::Onset,
        d,
        force,
        d_bar: d / sc.approach,
        f_bar: force / sc.force,
        cg_iterations: 0,
        detach_sweeps: 0,
        cg_residual: probe.residual,
        ..run.held.clone()
    })
}

/// Record the onset at fraction `probe.t` between `p_base` and the probe in `p` (an
/// interpolation: no work of its own, the probe's residual), at approach `d_on` (length).
/// Returns its force (force).
pub(super) fn record_onset<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
    walk: &Through,
    probe: &Probe,
    d_on: f64,
) -> Result<f64, SolverError> {
    let f = &mut run.fields;
    backend.lerp(&f.c, &f.p_base, &f.p, probe.t, &mut f.p_onset)?;
    let mut onset = Equilibrium {
        cg_residual: probe.residual,
        ..Equilibrium::default()
    };
    let (state, _) = record(
        backend,
        &run.model,
        &f.c,
        &f.p_onset,
        walk.step,
        Phase::Onset,
        d_on,
        &onset,
    )?;
    let force = state.force;
    run.best = run.best.min(force);
    run.window.onset_found(walk.step, force, probe.lower);
    out.emit(backend, &run.fields.c, state, &mut onset, walk.hold)?;
    Ok(force)
}

/// A cascade past an onset that changes the force by more than this fraction of it
/// (dimensionless) is a jump (a patch snapping off): the state after it is recorded too, at
/// the approach of the onset before it, so that the curve shows the step rather than a line
/// smeared over the load step.
pub const JUMP_FRACTION: f64 = 0.05;

/// Record the state that a cascade just past an onset left at approach `d` (length), as
/// [`Phase::Jump`], if the force stepped by more than [`JUMP_FRACTION`] from the onset's
/// `before` (force).
fn record_jump<B: Backend>(
    backend: &mut B,
    run: &mut Progress<B::Field, B::Mask>,
    out: &mut Emitter,
    walk: &Through,
    (d, before): (f64, f64),
    eq: &mut Equilibrium,
) -> Result<(), SolverError> {
    let f = &run.fields;
    let after = force_of(backend, &run.model, &f.c, &f.p)?;
    if (after - before).abs() <= JUMP_FRACTION * before.abs() {
        return Ok(());
    }
    let (state, _) = record(
        backend,
        &run.model,
        &f.c,
        &f.p,
        walk.step,
        Phase::Jump,
        d,
        eq,
    )?;
    out.emit(backend, &run.fields.c, state, eq, walk.hold)
}
