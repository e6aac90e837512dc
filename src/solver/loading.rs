//! The loading phase (physics §6, pressed on): from the first touch the approach rises step
//! by step, each step equilibrated with the adhesive rule, elements attaching where their
//! gap closes and detaching beyond σ_c, until the preload is reached; the pull-off starts
//! from the contact it left. A smooth shape pressed on to its first contact's approach d0
//! ends on the contact that the one-piece non-adhesive press builds, so its pull-off is
//! today's; a rough one keeps what formed on the way in.

use super::emit::{record, Emitter};
use super::equilibrium::{equilibrate, Fields, Reached};
use super::state::{Phase, State};
use super::SolverError;
use crate::backend::Backend;
use crate::model::{LoadTarget, Model};

/// A force or area target counts as reached within this fraction of it (dimensionless).
const TARGET_TOLERANCE: f64 = 1e-3;

/// Most loading steps (a target the surface never reaches, say an area it cannot cover,
/// stops here with an error).
const MAX_LOADING_STEPS: usize = 100_000;

/// Press on from the first touch to the model's preload, recording each loading step's
/// state ([`Phase::Loading`]); returns the fields and the last state, where the pull-off
/// starts.
pub(super) fn press<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &mut Emitter,
) -> Result<Reached<B::Field, B::Mask>, SolverError> {
    let loading = model.loading.expect("a model that presses on");
    let profile = model.profile();
    // The first touch: the elements at the least height.
    let touch: Vec<bool> = profile.iter().map(|&h| h <= loading.d_touch).collect();
    let mut c = backend.mask()?;
    backend.upload_mask(&mut c, &touch)?;
    let mut fields = Fields::new(backend, c)?;
    let domain = (model.nx * model.ny) as f64 * model.dx * model.dx;
    let mut last: Option<State> = None;
    let mut before: Option<(f64, f64)> = None;
    for step in 1..=MAX_LOADING_STEPS {
        if !out.go_on() {
            return Err(SolverError::Interrupted);
        }
        let d = match loading.target {
            LoadTarget::Depth(d_pre) => loading.depth_approach(step, d_pre),
            LoadTarget::Force(goal) => aimed(&loading, last.as_ref(), before, goal, |s| s.force),
            LoadTarget::AreaFraction(goal) => {
                aimed(&loading, last.as_ref(), before, goal * domain, |s| s.area)
            }
        };
        let mut eq = equilibrate(backend, model, &mut fields, d, model.sigma_c)?;
        let (state, _) = record(
            backend,
            model,
            &fields.c,
            &fields.p,
            step,
            Phase::Loading,
            d,
            &eq,
        )?;
        let done = match loading.target {
            LoadTarget::Depth(d_pre) => d >= d_pre,
            LoadTarget::Force(goal) => state.force >= goal * (1.0 - TARGET_TOLERANCE),
            LoadTarget::AreaFraction(goal) => {
                state.area >= goal * domain * (1.0 - TARGET_TOLERANCE)
            }
        };
        out.emit(backend, &fields.c, state.clone(), &mut eq, false)?;
        if let Some(l) = &last {
            before = Some((l.d, value_of(&loading.target, l)));
        }
        last = Some(state);
        if done {
            break;
        }
    }
    let state = last.expect("at least one loading step");
    // The pull-off's minimum is of the unloading only.
    out.least = None;
    Ok((fields, state))
}

/// The monitored quantity of a force or area target (force, or length²).
fn value_of(target: &LoadTarget, s: &State) -> f64 {
    match target {
        LoadTarget::AreaFraction(_) => s.area,
        _ => s.force,
    }
}

/// The next approach towards `goal` of the quantity `of` (force or area): the secant
/// through the last two states where they rise, at most one load step further (and at least
/// a hundredth of one), else one load step.
fn aimed(
    loading: &crate::model::Loading,
    last: Option<&State>,
    before: Option<(f64, f64)>,
    goal: f64,
    of: impl Fn(&State) -> f64,
) -> f64 {
    let Some(last) = last else {
        return loading.d_touch + loading.d_step;
    };
    let step = loading.d_step;
    let ahead = match before {
        Some((d0, v0)) if of(last) > v0 && last.d > d0 => {
            let slope = (of(last) - v0) / (last.d - d0);
            ((goal - of(last)) / slope).clamp(0.01 * step, step)
        }
        _ => step,
    };
    last.d + ahead
}
