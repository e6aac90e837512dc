//! The loading phase (physics §6, pressed on): from the first touch the approach rises step
//! by step, each step equilibrated with the adhesive rule, elements attaching where their
//! gap closes and detaching beyond σ_c, until the preload is reached; the pull-off starts
//! from the contact it left. A smooth shape pressed on to its first contact's approach d0
//! ends on the contact that the one-piece non-adhesive press builds, so its pull-off is
//! today's; a rough one keeps what formed on the way in.

use super::cost::Work;
use super::emit::{force_of, record, Emitter};
use super::equilibrium::{settle, solve_fixed, Equilibrium, Fields, Held, Reached};
use super::onsets::JUMP_FRACTION;
use super::state::{Phase, State};
use super::SolverError;
use crate::backend::Backend;
use crate::model::{LoadTarget, Model, MAX_LOADING_STEPS};
use crate::scene::Indenter;

/// A force or area target counts as reached within this fraction of it (dimensionless).
const TARGET_TOLERANCE: f64 = 1e-3;

/// Halvings of a loading step at most, while its cascade moves the force from that of the
/// contact it started from by more than [`JUMP_FRACTION`]: a jump (a patch snapping in or
/// off) is then located within 1/64 of a step, and both its sides are recorded.
pub const JUMP_HALVINGS: u32 = 6;

/// The range of the part of a step's force discrepancy (the cascade's change of the force)
/// that its first half shows when the change is spread over the step (a contact growing
/// smoothly, about half): below it the change lies in the step's second half, above it in
/// its first (a jump).
const SMOOTH_PART: (f64, f64) = (0.2, 0.8);

/// Press on from the first touch to the model's preload, recording each loading step's
/// state ([`Phase::Loading`]); returns the fields and the last state, where the pull-off
/// starts. A step whose cascade (attachments where the gap closed, detachments beyond σ_c)
/// moves the force by more than [`JUMP_FRACTION`] (of the largest force so far) from the force
/// of the contact set it started from, solved at the step's end, is taken again in halves, up to [`JUMP_HALVINGS`]
/// times: a smooth growth of the contact then falls below the fraction, while a jump does
/// not, and is recorded as [`Phase::LoadingJump`] within 1/64 of a step of the state before it.
///
/// Under the periodic convolution, a press that drives the contact towards the whole period
/// meets a problem with no finite answer (a period in full contact is the half-space pressed
/// uniformly: its mean pressure is not set by the displacements), where CG fails: that
/// failure is the preload's, said so.
pub(super) fn press<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &mut Emitter,
) -> Result<Reached<B::Field, B::Mask>, SolverError> {
    let periodic = matches!(model.scene.indenter, Indenter::HeightMap(ref m) if m.is_periodic());
    let steps = std::cell::Cell::new(0usize);
    let share = std::cell::Cell::new(0.0f64);
    match press_on(backend, model, out, &steps, &share) {
        Err(SolverError::CgNotConverged { d_bar, .. })
            if periodic && share.get() >= NEAR_FULL_PERIOD =>
        {
            Err(SolverError::PreloadUnreachable {
                d_bar,
                steps: steps.get(),
                why: format!(
                    "under the periodic convolution the contact neared the whole period (it \
                     covered {:.1} % of it at the last loading state), where the press has no \
                     finite answer (a period in full contact is the half-space pressed \
                     uniformly, its mean pressure set by nothing), and conjugate gradients \
                     failed there",
                    100.0 * share.get()
                ),
            })
        }
        other => other,
    }
}

/// The share of a periodic domain in contact (dimensionless) from which a loading whose
/// conjugate gradients then fail is said to have neared full contact: a half. Below it the
/// solver's own error stands, as it does on a padded domain.
pub(super) const NEAR_FULL_PERIOD: f64 = 0.5;

/// [`press`], counting the loading steps recorded in `steps` and keeping the share of the
/// domain in contact at the last of them in `share` (dimensionless).
fn press_on<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &mut Emitter,
    steps: &std::cell::Cell<usize>,
    share: &std::cell::Cell<f64>,
) -> Result<Reached<B::Field, B::Mask>, SolverError> {
    let loading = model.loading.expect("a model that presses on");
    let profile = model.profile();
    // The first touch: the elements at the least height.
    let touch: Vec<bool> = profile.iter().map(|&h| h <= loading.d_touch).collect();
    let mut c = backend.mask()?;
    backend.upload_mask(&mut c, &touch)?;
    let mut fields = Fields::new(backend, c)?;
    // The state a step starts from, to take the step again in halves.
    let mut saved_c = backend.mask()?;
    let mut saved_p = backend.field()?;
    let domain = (model.nx * model.ny) as f64 * model.dx * model.dx;
    let mut last: Option<State> = None;
    let mut before: Option<(f64, f64)> = None;
    let mut d_from = loading.d_touch;
    // The largest |F| of the loading's states so far (force).
    let mut seen: f64 = 0.0;
    // The depth schedule's next step (it moves on once a step lands on it whole).
    let mut planned = 1;
    // Whether the preload was reached.
    let mut reached = false;
    for recorded in 0..MAX_LOADING_STEPS {
        if !out.go_on() {
            return Err(SolverError::Interrupted);
        }
        let d_planned = match loading.target {
            LoadTarget::Depth(d_pre) => loading.depth_approach(planned, d_pre),
            LoadTarget::Force(goal) => aimed(&loading, last.as_ref(), before, goal, |s| s.force),
            LoadTarget::AreaFraction(goal) => {
                aimed(&loading, last.as_ref(), before, goal * domain, |s| s.area)
            }
        };
        // Sub-steps towards the planned approach: a step whose cascade moves the force too
        // far is taken again in half. If the half moves it by a middling part of what the
        // whole did (SMOOTH_PART), the change is spread over the step (the contact grows
        // smoothly) and the whole step is taken after all; if by nearly all of it, the jump
        // lies in the half, which is halved again, down to 1/2^JUMP_HALVINGS of the step; if
        // by little, the half is kept and the jump sought in the rest.
        let full = d_planned - d_from;
        // An approach that no longer moves in floating point (d + Δd == d) never gets there.
        if !(full > 0.0 && d_planned.is_finite()) {
            return Err(unreachable(
                model,
                last.as_ref(),
                recorded,
                "the approach no longer grows in floating point (d + Δd = d)".into(),
            ));
        }
        let mut halvings = 0;
        // The discrepancy of the try twice as long as this one (force), and whether the next
        // try is taken whole without the test.
        let mut parent: Option<f64> = None;
        let mut whole = false;
        // The work of the tries taken again.
        let mut spent = Work::default();
        let (state, mut eq) = loop {
            let d = if halvings == 0 {
                d_planned
            } else {
                d_from + full / f64::from(1u32 << halvings)
            };
            backend.copy_mask(&fields.c, &mut saved_c)?;
            backend.copy(&fields.p, &mut saved_p)?;
            let mut eq = Equilibrium::default();
            eq.add_solve(solve_fixed(backend, model, &mut fields, d)?);
            let kept = force_of(backend, model, &fields.c, &fields.p)?;
            eq.absorb(settle(
                backend,
                model,
                &mut fields,
                d,
                model.sigma_c,
                Held::Solved,
            )?);
            let (state, _) = record(
                backend,
                model,
                &fields.c,
                &fields.p,
                recorded + 1,
                Phase::Loading,
                d,
                &eq,
            )?;
            // Measured against the largest force of the loading so far, so that a force
            // passing through zero does not count as a jump.
            let size = state.force.abs().max(kept.abs()).max(seen);
            let moved = (state.force - kept).abs();
            let jumped = !whole && moved > JUMP_FRACTION * size;
            let smooth = parent.is_some_and(|whole_moved| {
                moved > SMOOTH_PART.0 * whole_moved && moved < SMOOTH_PART.1 * whole_moved
            });
            if !jumped || halvings == JUMP_HALVINGS || smooth {
                if !smooth || !jumped {
                    let phase = if jumped {
                        Phase::LoadingJump
                    } else {
                        Phase::Loading
                    };
                    eq.work.add(spent);
                    break (State { phase, ..state }, eq);
                }
                // Spread over the step: take the try twice as long, whole.
                halvings -= 1;
                whole = true;
            } else {
                halvings += 1;
            }
            spent.add(eq.work);
            parent = Some(moved);
            backend.copy_mask(&saved_c, &mut fields.c)?;
            backend.copy(&saved_p, &mut fields.p)?;
            fields.u_valid = false;
        };
        let d = state.d;
        d_from = d;
        seen = seen.max(state.force.abs());
        if halvings == 0 {
            planned += 1;
        }
        let done = match loading.target {
            LoadTarget::Depth(d_pre) => d >= d_pre,
            LoadTarget::Force(goal) => state.force >= goal * (1.0 - TARGET_TOLERANCE),
            LoadTarget::AreaFraction(goal) => {
                state.area >= goal * domain * (1.0 - TARGET_TOLERANCE)
            }
        };
        // A contact over every element of the domain cannot take more load: the surface
        // beyond it is not modelled (a window of a height map ends there).
        let full_cover = !done && state.area >= domain * (1.0 - 1e-12);
        out.emit(backend, &fields.c, state.clone(), &mut eq, false)?;
        steps.set(recorded + 1);
        share.set(state.area / domain);
        if let Some(l) = &last {
            before = Some((l.d, value_of(&loading.target, l)));
        }
        last = Some(state);
        if done {
            reached = true;
            break;
        }
        if full_cover {
            return Err(unreachable(
                model,
                last.as_ref(),
                recorded + 1,
                "the contact covers the whole domain".into(),
            ));
        }
    }
    if !reached {
        return Err(unreachable(
            model,
            last.as_ref(),
            MAX_LOADING_STEPS,
            format!("{MAX_LOADING_STEPS} loading steps did not reach it"),
        ));
    }
    let state = last.expect("at least one loading step");
    // The pull-off's minimum is of the unloading only.
    out.least = None;
    Ok((fields, state))
}

/// The error of a loading phase that cannot reach its preload, at `last` (the last loading
/// state, if any) after `steps` steps.
fn unreachable(model: &Model, last: Option<&State>, steps: usize, why: String) -> SolverError {
    let d = last.map_or(model.loading.map_or(0.0, |l| l.d_touch), |s| s.d);
    SolverError::PreloadUnreachable {
        d_bar: d / model.scene.scales().approach,
        steps,
        why,
    }
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
