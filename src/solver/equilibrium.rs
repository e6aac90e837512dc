//! The detachment/attachment loop at one approach (physics §6.2): solve on a fixed contact
//! set, detach over-stressed elements, attach overlapping ones, repeat until nothing changes.
//!
//! A cascade's intermediate rounds only have to find which elements are over σ_c: they are
//! solved to [`LOOSE_TOLERANCE`] and detach only the elements beyond σ_c by more than twice
//! the error CG's preconditioner estimates ([`LOOSE_SAFETY`]; never one that the exact solve
//! would keep), and attach none. Once
//! such a round detaches nothing, the round is solved exactly and swept with the exact rule,
//! attachments included, so the cascade ends on the same contact set as with every round
//! solved exactly: the detachment rule is monotone (removing an element or pulling further
//! never lowers the tension on the others), so the set it ends on is the greatest stable
//! subset of the one it started from, whatever the order in which elements left.
//!
//! A loose round that detaches nothing may still leave elements over σ_c by less than its
//! margin: that round is solved once more, to [`TIGHT_TOLERANCE`] (a margin ten times
//! narrower), and swept again before the exact solve, so that such elements leave in a cheap
//! round rather than each costing an exact solve and a loose round after it.
//!
//! Each round's solve starts from the load of the elements just detached handed to the
//! contact elements around them by their shares ([`crate::backend::shares`]): CG has less
//! left to correct.

use super::cg::{self, CgEnd, CgWork, Goal};
use super::cost::Work;
use super::retry::{CgRetry, RetryVerdict};
use super::SolverError;
use crate::backend::{Backend, BackendError};
use crate::model::Model;

/// Relative CG residual to which a cascade's intermediate rounds are solved (dimensionless).
pub const LOOSE_TOLERANCE: f64 = 1e-5;

/// Relative CG residual to which a loose round that detached nothing is solved again before
/// the exact solve (dimensionless; within the range over which [`LOOSE_SAFETY`] was
/// measured). Measured, 5:1 adhesive force: 9 225 → 8 832 CG iterations at 1024×512 (the
/// exact solves per cascade 2.7 → 1.0), 4 421 → 4 394 at 512×256, every contact set equal.
pub const TIGHT_TOLERANCE: f64 = 1e-6;

/// An approximately solved round detaches only elements with p < −σ_c − this × ε
/// (dimensionless), ε = max over C of |M r|, the preconditioned residual: the estimate of the
/// largest error in p that CG's own preconditioner gives. Measured against the exact solve
/// over 10 500 loose rounds (sphere 256², 5:1 at 512×256, 25:1 at 512×128, tolerances 1e-4
/// to 1e-6): the largest error was at most 1.04 ε (median 0.8 ε), so that no element is
/// detached that the exact solve would keep.
pub const LOOSE_SAFETY: f64 = 2.0;

/// ε of [`LOOSE_SAFETY`] for the loose solve just made: max over C of |M r| (stress), with
/// r the residual CG left in its work fields.
fn error_estimate<B: Backend>(
    backend: &mut B,
    fields: &mut Fields<B::Field, B::Mask>,
) -> Result<f64, BackendError> {
    let cg = &mut fields.cg;
    backend.precondition(&fields.c, &cg.r, &mut cg.z)?;
    backend.max_abs(&fields.c, &cg.z)
}

/// Account a cascade's `solve` (of its warm start, or of a round) in `eq`. Returns whether
/// it was exact; the error estimate of the p it left (stress), where a loose round or the
/// certification needs it; and the margin (stress) beyond σ_c by which a loosely solved
/// element is surely over it (0 after an exact solve, whose sweep uses σ_c itself).
fn round_solved<B: Backend>(
    backend: &mut B,
    fields: &mut Fields<B::Field, B::Mask>,
    eq: &mut Equilibrium,
    solve: Solve,
    certify: bool,
) -> Result<(bool, Option<f64>, f64), BackendError> {
    let exact = solve.exact;
    let known = solve.error_estimate;
    eq.add_solve(solve);
    if exact && !certify {
        return Ok((true, None, 0.0));
    }
    let eps = match known {
        Some(eps) => eps,
        None => error_estimate(backend, fields)?,
    };
    let margin = if exact { 0.0 } else { LOOSE_SAFETY * eps };
    Ok((exact, Some(eps), margin))
}

/// The fields a phase leaves and the state it ended on (where the next phase starts).
pub type Reached<F, M> = (Fields<F, M>, crate::solver::state::State);

/// The result of equilibrating one approach.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Equilibrium {
    /// The solver's work: solves, CG iterations, convolutions outside CG, rounds (sweeps
    /// that changed the contact set).
    pub work: Work,
    /// Elements in contact at the end.
    pub n_contact: usize,
    /// The largest relative residual of its exact CG solves (dimensionless; see [`Solve`]).
    pub cg_residual: f64,
    /// The solves that needed CG's safer retry, in order.
    pub retries: Vec<CgRetry>,
}

impl Equilibrium {
    /// Add one solve's work (its residual counts only if the solve was exact).
    pub fn add_solve(&mut self, solve: Solve) {
        self.work.solves += 1;
        self.work.exact_solves += solve.exact as usize;
        self.work.cg_iterations += solve.iterations;
        self.work.convolutions += solve.convolutions;
        if solve.exact {
            self.cg_residual = self.cg_residual.max(solve.residual);
        }
        self.retries.extend(solve.retry);
    }

    /// Add the work of another equilibrium reached on the way (its contact count is taken
    /// as the current one).
    pub fn absorb(&mut self, other: Equilibrium) {
        self.work.add(other.work);
        self.n_contact = other.n_contact;
        self.cg_residual = self.cg_residual.max(other.cg_residual);
        self.retries.extend(other.retries);
    }
}

/// One solve on a fixed contact set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solve {
    /// CG iterations, the safer retry's included.
    pub iterations: usize,
    /// Convolutions made outside the iterations.
    pub convolutions: usize,
    /// Relative residual ‖(d − h − K p)_C‖/‖(d − h)_C‖ of the p kept (dimensionless):
    /// recomputed from p for an exact solve, the recurrence's for a loose one.
    pub residual: f64,
    /// Whether p is the state's solution (to the CG tolerance), not a loose round's.
    pub exact: bool,
    /// The safer retry, if the normal mode failed.
    pub retry: Option<CgRetry>,
    /// The error estimate of the p kept (stress), where CG read it with its last read
    /// ([`cg::CgReport::error_estimate`]); `None`: computed where needed.
    pub error_estimate: Option<f64>,
}

/// Fields the loop works on: the pressure p (force/length²) and the displacement u = K p
/// (length), the contact set C they live on (`M`, the backend's mask), plus the
/// protocol's and CG's work fields.
pub struct Fields<F, M> {
    /// The contact set C.
    pub c: M,
    /// Pressure, zero off C.
    pub p: F,
    /// Displacement K p, where `u_valid` says it is that of the p held.
    pub u: F,
    /// Whether `u` = K p for the p held now.
    pub u_valid: bool,
    /// Pressure at the start of a probe: the stable state the load moves on from.
    pub p_base: F,
    /// Pressure of the last probe (the unchanged contact set solved at the load step's end).
    pub p_probe: F,
    /// Pressure at the previous load step's end (for the next probe's predicted start).
    pub p_last: F,
    /// Pressure at a detachment onset.
    pub p_onset: F,
    /// Pressure a solve started from, to retry from if it diverges.
    pub p_start: F,
    /// Pressure before a cascade's sweep (the load the elements it detaches hand on).
    pub p_before: F,
    /// CG work fields.
    pub cg: CgWork<F>,
}

impl<F, M> Fields<F, M> {
    /// Allocate the fields on `backend`, with the contact set `c`.
    pub fn new<B: Backend<Field = F, Mask = M>>(
        backend: &mut B,
        c: M,
    ) -> Result<Self, BackendError> {
        Ok(Fields {
            c,
            p: backend.field()?,
            u: backend.field()?,
            u_valid: false,
            p_base: backend.field()?,
            p_probe: backend.field()?,
            p_last: backend.field()?,
            p_onset: backend.field()?,
            p_start: backend.field()?,
            p_before: backend.field()?,
            cg: CgWork::new(backend)?,
        })
    }

    /// Make `u` = K p if it is not (a convolution, counted in `work`).
    pub fn ensure_u<B: Backend<Field = F, Mask = M>>(
        &mut self,
        backend: &mut B,
        work: &mut Work,
    ) -> Result<(), BackendError> {
        if !self.u_valid {
            backend.convolve(&self.p, &mut self.u)?;
            work.convolutions += 1;
            self.u_valid = true;
        }
        Ok(())
    }
}

/// Solve for p on the unchanged contact set at approach `d` (length) and leave u = K p.
/// A solve that stagnates, diverges, hits the iteration limit or misses the tolerance in
/// its true residual is retried once in CG's safer mode, from where it stopped (if it
/// diverged, from where it started, or from p = 0 if that start was not finite). A retry
/// that stops above the tolerance is accepted when its residual is within `accept`;
/// otherwise the solve fails.
pub fn solve_fixed<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field, B::Mask>,
    d: f64,
) -> Result<Solve, SolverError> {
    solve_for(backend, model, fields, d, Goal::Exact)
}

/// A solve for `goal` at approach `d` (length). [`Goal::Loose`] solves to
/// [`LOOSE_TOLERANCE`] and leaves `u` invalid; a loose solve that fails in any way is made
/// exact instead, as [`solve_fixed`] does.
pub fn solve_for<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field, B::Mask>,
    d: f64,
    goal: Goal,
) -> Result<Solve, SolverError> {
    solve_to(backend, model, fields, d, goal, LOOSE_TOLERANCE)
}

/// [`solve_for`], a loose solve made to the relative residual `loose` (dimensionless).
fn solve_to<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field, B::Mask>,
    d: f64,
    goal: Goal,
    loose: f64,
) -> Result<Solve, SolverError> {
    backend.copy(&fields.p, &mut fields.p_start)?;
    let settings = cg::effective(backend, &model.cg);
    let known = fields.u_valid.then_some(&fields.u);
    let mut spent = (0, 0);
    if goal == Goal::Loose {
        let loose = crate::model::CgSettings {
            tolerance: loose.max(settings.tolerance),
            ..settings
        };
        let r = cg::solve_with(
            backend,
            &fields.c,
            &mut fields.cg,
            &mut fields.p,
            d,
            &loose,
            known,
            goal,
        )?;
        if r.converged() {
            fields.u_valid &= r.iterations == 0;
            return Ok(Solve {
                iterations: r.iterations,
                convolutions: r.convolutions,
                residual: r.residual,
                exact: false,
                retry: None,
                error_estimate: r.error_estimate,
            });
        }
        // A loose solve that went wrong: solve exactly, from its start if it diverged.
        spent = (r.iterations, r.convolutions);
        if matches!(r.end, CgEnd::Diverged | CgEnd::NonFinite) {
            backend.copy(&fields.p_start, &mut fields.p)?;
        }
        fields.u_valid = false;
    }
    let known = fields.u_valid.then_some(&fields.u);
    let first = cg::solve_with(
        backend,
        &fields.c,
        &mut fields.cg,
        &mut fields.p,
        d,
        &settings,
        known,
        Goal::Exact,
    )?;
    let spent_iterations = spent.0 + first.iterations;
    let spent_convolutions = spent.1 + first.convolutions;
    if first.converged() {
        if !(fields.u_valid && first.iterations == 0) {
            backend.copy(&fields.cg.q, &mut fields.u)?;
        }
        fields.u_valid = true;
        return Ok(Solve {
            iterations: spent_iterations,
            convolutions: spent_convolutions,
            residual: first.residual,
            exact: true,
            retry: None,
            error_estimate: first.error_estimate,
        });
    }
    if matches!(first.end, CgEnd::Diverged | CgEnd::NonFinite) {
        // Back to the warm start, or to p = 0 if the warm start itself was not finite.
        let start = if first.iterations == 0 {
            fields.cg.zero()
        } else {
            &fields.p_start
        };
        backend.copy(start, &mut fields.p)?;
    }
    let second = cg::solve_safe(
        backend,
        &fields.c,
        &mut fields.cg,
        &mut fields.p,
        d,
        &settings,
    )?;
    let d_bar = d / model.scene.scales().approach;
    let retry = CgRetry::new(d_bar, first, second, &settings);
    if retry.verdict == RetryVerdict::Failed {
        return Err(SolverError::CgNotConverged {
            d_bar,
            first: first.end,
            end: second.end,
            residual: second.residual,
            iterations: spent.0 + retry.iterations(),
            tolerance: settings.tolerance,
            accept: settings.acceptable(),
        });
    }
    backend.convolve(&fields.p, &mut fields.u)?;
    fields.u_valid = true;
    Ok(Solve {
        iterations: spent.0 + retry.iterations(),
        convolutions: spent_convolutions + second.convolutions + 1,
        residual: second.residual,
        exact: true,
        retry: Some(retry),
        error_estimate: None,
    })
}

/// How the p held when a cascade starts was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Held {
    /// Only a warm start: solve first.
    WarmStart,
    /// The exact solution on the contact set at the cascade's approach (a solve's, or an
    /// interpolation between two on the same set); `u` may or may not be K p.
    Solved,
}

/// Equilibrate the contact at approach `d` (length) with detachment stress `sigma_c`
/// (force/length²; 0 for a non-adhesive contact), from the p `held`.
pub fn equilibrate<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field, B::Mask>,
    d: f64,
    sigma_c: f64,
) -> Result<Equilibrium, SolverError> {
    settle(backend, model, fields, d, sigma_c, Held::WarmStart)
}

/// The cascade at approach `d` (length): sweep, solve, sweep … until a sweep of an exactly
/// solved round changes nothing. With [`Model::loose_rounds`] and σ_c > 0 the rounds after a
/// detachment are solved loosely (see the module's notes).
pub fn settle<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field, B::Mask>,
    d: f64,
    sigma_c: f64,
    held: Held,
) -> Result<Equilibrium, SolverError> {
    // An exact solve's error estimate is needed where the certification takes it, and only
    // within the cascade: the solves outside it (probes, loading) read none.
    fields.cg.estimate_exact = model.certify_detached && sigma_c > 0.0;
    let settled = cascade(backend, model, fields, d, sigma_c, held);
    fields.cg.estimate_exact = false;
    settled
}

/// [`settle`]'s loop.
fn cascade<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field, B::Mask>,
    d: f64,
    sigma_c: f64,
    held: Held,
) -> Result<Equilibrium, SolverError> {
    let d_bar = d / model.scene.scales().approach;
    let loose_rounds = model.loose_rounds && sigma_c > 0.0;
    let spread = model.spread_detached && sigma_c > 0.0;
    let certify = model.certify_detached && sigma_c > 0.0;
    let tighten = model.tighten_stalls && loose_rounds;
    let mut eq = Equilibrium::default();
    // Whether the p held is a state's (an exact solve's, or the one the cascade starts from);
    // the error estimate of the p held (stress), where a solve gave it; and beyond σ_c by
    // how much (stress) a loosely solved element is surely over it.
    let (mut exact, mut eps, mut margin) = (true, None, 0.0);
    if held == Held::WarmStart {
        let solve = solve_fixed(backend, model, fields, d)?;
        (exact, eps, margin) = round_solved(backend, fields, &mut eq, solve, certify)?;
    }
    // Whether the p held was solved to TIGHT_TOLERANCE after a loose round detached nothing.
    let mut tightened = false;
    loop {
        // An exact round attaches only where u = K p is known; a loose round never does,
        // and detaches only beyond the margin.
        let (attach_at, threshold) = if exact {
            (fields.u_valid.then_some(d), sigma_c)
        } else {
            (None, sigma_c + margin)
        };
        if spread || certify {
            backend.copy(&fields.p, &mut fields.p_before)?;
        }
        let mut change = backend.update_contact(
            &mut fields.c,
            &mut fields.p,
            &fields.u,
            attach_at,
            threshold,
        )?;
        // Whether the certification set the round's predicted start.
        let mut predicted = false;
        if let (true, Some(eps)) = (certify, eps) {
            if change.detached > 0 && change.attached == 0 {
                // The elements certain to follow go now, without a solve of their own.
                if let Some(more) = backend.certify_detached(
                    &mut fields.c,
                    &fields.p_before,
                    &mut fields.p,
                    sigma_c,
                    eps,
                )? {
                    predicted = true;
                    change.detached += more;
                    change.n_contact -= more;
                    eq.work.certified += more;
                }
            }
        }
        eq.n_contact = change.n_contact;
        // On a height map's window the domain's edge is the surface's: nothing beyond it
        // touches, so a contact there is the problem's own, not a domain too small.
        if change.at_edge > 0 && model.scene.window_half().is_none() {
            return Err(SolverError::ContactAtEdge {
                d_bar,
                elements: change.at_edge,
            });
        }
        if change.n_contact == 0 {
            return Ok(eq);
        }
        if change.detached + change.attached > 0 {
            tightened = false;
            fields.u_valid = false;
            if spread && change.detached > 0 && !predicted {
                // The round's solve starts from the detached load handed on (a prediction
                // that CG corrects: the state is the same, the iterations fewer); the
                // certification's bound predicts it better where it ran.
                backend.spread_detached(&fields.c, &fields.p_before, &mut fields.p)?;
            }
            eq.work.rounds += 1;
            if eq.work.rounds >= model.max_sweeps {
                return Err(SolverError::DetachmentCycles {
                    d_bar,
                    sweeps: eq.work.rounds,
                    detached: change.detached,
                    attached: change.attached,
                });
            }
            let goal = if loose_rounds {
                Goal::Loose
            } else {
                Goal::Exact
            };
            let solve = solve_for(backend, model, fields, d, goal)?;
            (exact, eps, margin) = round_solved(backend, fields, &mut eq, solve, certify)?;
        } else if !exact && tighten && !tightened {
            // Nothing is surely over σ_c at the loose margin: solve to a narrower one first.
            tightened = true;
            let solve = solve_to(backend, model, fields, d, Goal::Loose, TIGHT_TOLERANCE)?;
            (exact, eps, margin) = round_solved(backend, fields, &mut eq, solve, certify)?;
        } else if !exact {
            // Nothing more is surely over σ_c: solve this round exactly and sweep it again.
            let solve = solve_for(backend, model, fields, d, Goal::Exact)?;
            (exact, eps, margin) = round_solved(backend, fields, &mut eq, solve, certify)?;
        } else if attach_at.is_none() {
            // Stable under detachment, but attachment is still to be checked: it needs u.
            fields.ensure_u(backend, &mut eq.work)?;
        } else {
            return Ok(eq);
        }
    }
}
