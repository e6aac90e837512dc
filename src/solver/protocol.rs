//! The approach and pull-off protocol (SPEC §6): a non-adhesive press to d0, then the
//! approach decreases step by step until the contact vanishes or d passes its final value.

use super::equilibrium::{equilibrate, Equilibrium, Fields};
use super::state::{axis_half_lengths, Phase, State};
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

/// Measure and normalise the state on the backend after equilibrium.
fn record<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &Fields<B::Field>,
    mask: &mut [bool],
    step: usize,
    phase: Phase,
    d: f64,
    eq: &Equilibrium,
) -> Result<State, SolverError> {
    let (sum, n) = backend.sum_and_count(&fields.p)?;
    backend.contact(mask)?;
    let (a_el, b_el) = axis_half_lengths(mask, model.nx, model.ny);
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
    let mut states = Vec::new();
    let error = run_inner(backend, model, &mut |s| {
        observe(&s);
        states.push(s);
    })
    .err();
    Outcome { states, error }
}

fn run_inner<B: Backend>(
    backend: &mut B,
    model: &Model,
    push: &mut dyn FnMut(State),
) -> Result<(), SolverError> {
    let mut mask = model.initial_contact();
    backend.set_contact(&mask)?;
    let mut fields = Fields {
        p: backend.field()?,
        u: backend.field()?,
        cg: super::cg::CgWork::new(backend)?,
    };
    // 1. Non-adhesive press to d0.
    let eq = equilibrate(backend, model, &mut fields, model.d0, 0.0)?;
    push(record(
        backend,
        model,
        &fields,
        &mut mask,
        0,
        Phase::Approach,
        model.d0,
        &eq,
    )?);
    // 2. Adhesive pull-off.
    let mut step = 0;
    loop {
        step += 1;
        let d = model.d0 - step as f64 * model.d_step;
        if d < model.d_final {
            return Ok(());
        }
        let eq = equilibrate(backend, model, &mut fields, d, model.sigma_c)?;
        push(record(
            backend,
            model,
            &fields,
            &mut mask,
            step,
            Phase::Pulloff,
            d,
            &eq,
        )?);
        if eq.n_contact == 0 {
            return Ok(());
        }
    }
}
