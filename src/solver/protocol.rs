//! The approach and pull-off protocol (SPEC §6): a non-adhesive press to d0, then the
//! approach decreases step by step until the contact vanishes or d passes its final value.

use super::equilibrium::{equilibrate, solve_fixed, Equilibrium, Fields};
use super::state::{axis_half_lengths, axis_half_lengths_along, Phase, State};
use super::SolverError;
use crate::backend::Backend;
use crate::model::Model;
use std::f64::consts::PI;

/// What a run produced: the states recorded so far and, if it stopped early, why.
#[derive(Debug)]
pub struct Outcome {
    /// Recorded states, in order.
    pub states: Vec<State>,
    /// The error that ended the run early, if any.
    pub error: Option<SolverError>,
}

impl Outcome {
    /// Whether the protocol ran to its end.
    pub fn complete(&self) -> bool {
        self.error.is_none()
    }

    /// Total CG iterations over all states.
    pub fn cg_iterations(&self) -> usize {
        self.states.iter().map(|s| s.cg_iterations).sum()
    }

    /// The state of minimum force (the adhesive force is its |F̄|), if any state was recorded.
    pub fn force_minimum(&self) -> Option<&State> {
        self.states
            .iter()
            .min_by(|a, b| a.force.total_cmp(&b.force))
    }
}

/// Measure and normalise the state of pressure `p` on the backend's contact set.
#[allow(clippy::too_many_arguments)]
fn record<B: Backend>(
    backend: &mut B,
    model: &Model,
    p: &B::Field,
    mask: &mut [bool],
    step: usize,
    phase: Phase,
    d: f64,
    eq: &Equilibrium,
) -> Result<State, SolverError> {
    let (sum, n) = backend.sum_and_count(p)?;
    backend.contact(mask)?;
    let (a_el, b_el) = if model.mesh.is_aligned() {
        axis_half_lengths(mask, model.nx, model.ny)
    } else {
        let m = model.mesh;
        axis_half_lengths_along(mask, model.nx, model.ny, m.cos, m.sin)
    };
    let dx = model.dx;
    let sc = model.scene.scales();
    let area = n as f64 * dx * dx;
    let force = sum * dx * dx;
    let mean_radius = (area / PI).sqrt();
    Ok(State {
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
        d_bar: d / sc.approach,
        f_bar: force / sc.force,
        c_bar: mean_radius / sc.length,
        a_bar: a_el * dx / sc.length,
        b_bar: b_el * dx / sc.length,
    })
}

/// Run the whole protocol on `backend`, calling `observe` with each recorded state.
pub fn run<B: Backend>(backend: &mut B, model: &Model, observe: &mut dyn FnMut(&State)) -> Outcome {
    run_with_contact(backend, model, &mut |s, _| observe(s))
}

/// Like [`run`], but `observe` also sees the contact mask of each state (row-major nx × ny,
/// true = in contact), for contours and snapshots.
pub fn run_with_contact<B: Backend>(
    backend: &mut B,
    model: &Model,
    observe: &mut dyn FnMut(&State, &[bool]),
) -> Outcome {
    let mut states = Vec::new();
    let error = run_inner(backend, model, &mut |s, mask| {
        observe(&s, mask);
        states.push(s);
    })
    .err();
    Outcome { states, error }
}

fn run_inner<B: Backend>(
    backend: &mut B,
    model: &Model,
    push: &mut dyn FnMut(State, &[bool]),
) -> Result<(), SolverError> {
    let mut mask = model.initial_contact();
    backend.set_contact(&mask)?;
    let mut fields = Fields::new(backend)?;
    // 1. Non-adhesive press to d0.
    let eq = equilibrate(backend, model, &mut fields, model.d0, 0.0)?;
    let state = record(
        backend,
        model,
        &fields.p,
        &mut mask,
        0,
        Phase::Approach,
        model.d0,
        &eq,
    )?;
    push(state, &mask);
    // 2. Adhesive pull-off, step by step.
    let mut d_prev = model.d0;
    let mut step = 0;
    loop {
        step += 1;
        let d = model.d0 - step as f64 * model.d_step;
        if d < model.d_final {
            return Ok(());
        }
        let mut eq = advance_through_onsets(
            backend,
            model,
            &mut fields,
            &mut mask,
            step,
            d_prev,
            d,
            push,
        )?;
        let last = equilibrate(backend, model, &mut fields, d, model.sigma_c)?;
        eq.cg_iterations += last.cg_iterations;
        eq.sweeps += last.sweeps;
        eq.n_contact = last.n_contact;
        let state = record(
            backend,
            model,
            &fields.p,
            &mut mask,
            step,
            Phase::Pulloff,
            d,
            &eq,
        )?;
        push(state, &mask);
        d_prev = d;
        if eq.n_contact == 0 {
            return Ok(());
        }
    }
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
#[allow(clippy::too_many_arguments)]
fn advance_through_onsets<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field>,
    mask: &mut [bool],
    step: usize,
    d_from: f64,
    d_to: f64,
    push: &mut dyn FnMut(State, &[bool]),
) -> Result<Equilibrium, SolverError> {
    let no_work = Equilibrium {
        cg_iterations: 0,
        sweeps: 0,
        n_contact: 0,
    };
    let mut total = no_work;
    let mut d_c = d_from;
    for _ in 0..MAX_ONSETS_PER_STEP {
        backend.copy(&fields.p, &mut fields.p_prev)?;
        total.cg_iterations += solve_fixed(backend, model, fields, d_to)?;
        let t = backend.first_crossing(&fields.p_prev, &fields.p, model.sigma_c)?;
        if t >= 1.0 {
            break;
        }
        backend.lerp(&fields.p_prev, &fields.p, t, &mut fields.p_onset)?;
        let d_on = d_c + t * (d_to - d_c);
        let state = record(
            backend,
            model,
            &fields.p_onset,
            mask,
            step,
            Phase::Onset,
            d_on,
            &no_work,
        )?;
        push(state, mask);
        let t_push = (t + ONSET_PUSH).min(1.0);
        backend.lerp(&fields.p_prev, &fields.p, t_push, &mut fields.p_onset)?;
        backend.copy(&fields.p_onset, &mut fields.p)?;
        d_c += t_push * (d_to - d_c);
        let eq = equilibrate(backend, model, fields, d_c, model.sigma_c)?;
        total.cg_iterations += eq.cg_iterations;
        total.sweeps += eq.sweeps;
        if eq.n_contact == 0 || t_push >= 1.0 {
            break;
        }
    }
    Ok(total)
}
