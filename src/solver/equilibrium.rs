//! The detachment/attachment loop at one approach (physics §6.2): solve on a fixed contact
//! set, detach over-stressed elements, attach overlapping ones, repeat until nothing changes.

use super::cg::{self, CgEnd, CgWork};
use super::retry::{CgRetry, RetryVerdict};
use super::SolverError;
use crate::backend::Backend;
use crate::model::Model;

/// The result of equilibrating one approach.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Equilibrium {
    /// CG iterations over all sweeps.
    pub cg_iterations: usize,
    /// Sweeps that changed the contact set.
    pub sweeps: usize,
    /// Elements in contact at the end.
    pub n_contact: usize,
    /// The largest relative residual of its CG solves (dimensionless; see [`Solve`]).
    pub cg_residual: f64,
    /// The solves that needed CG's safer retry, in order.
    pub retries: Vec<CgRetry>,
}

impl Equilibrium {
    /// Add one solve's work.
    pub fn add_solve(&mut self, solve: Solve) {
        self.cg_iterations += solve.iterations;
        self.cg_residual = self.cg_residual.max(solve.residual);
        self.retries.extend(solve.retry);
    }

    /// Add the work of another equilibrium reached on the way (its contact count is taken
    /// as the current one).
    pub fn absorb(&mut self, other: Equilibrium) {
        self.cg_iterations += other.cg_iterations;
        self.sweeps += other.sweeps;
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
    /// Relative residual ‖(d − h − K p)_C‖/‖(d − h)_C‖ of the p kept, recomputed from p
    /// (dimensionless).
    pub residual: f64,
    /// The safer retry, if the normal mode failed.
    pub retry: Option<CgRetry>,
}

/// Fields the loop works on: the pressure p (force/length²) and the displacement u = K p
/// (length), plus CG's work fields.
pub struct Fields<F> {
    /// Pressure, zero off C.
    pub p: F,
    /// Displacement K p after the last solve.
    pub u: F,
    /// Pressure at the previous load step's equilibrium.
    pub p_prev: F,
    /// Pressure at a detachment onset inside a step.
    pub p_onset: F,
    /// Pressure a solve started from, to retry from if it diverges.
    pub p_start: F,
    /// CG work fields.
    pub cg: CgWork<F>,
}

impl<F> Fields<F> {
    /// Allocate the fields on `backend`.
    pub fn new<B: Backend<Field = F>>(
        backend: &mut B,
    ) -> Result<Self, crate::backend::BackendError> {
        Ok(Fields {
            p: backend.field()?,
            u: backend.field()?,
            p_prev: backend.field()?,
            p_onset: backend.field()?,
            p_start: backend.field()?,
            cg: CgWork::new(backend)?,
        })
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
    fields: &mut Fields<B::Field>,
    d: f64,
) -> Result<Solve, SolverError> {
    backend.copy(&fields.p, &mut fields.p_start)?;
    let first = cg::solve(backend, &mut fields.cg, &mut fields.p, d, &model.cg)?;
    if first.converged() {
        backend.copy(&fields.cg.q, &mut fields.u)?;
        return Ok(Solve {
            iterations: first.iterations,
            residual: first.residual,
            retry: None,
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
    let second = cg::solve_safe(backend, &mut fields.cg, &mut fields.p, d, &model.cg)?;
    let d_bar = d / model.scene.scales().approach;
    let retry = CgRetry::new(d_bar, first, second, &model.cg);
    if retry.verdict == RetryVerdict::Failed {
        return Err(SolverError::CgNotConverged {
            d_bar,
            first: first.end,
            end: second.end,
            residual: second.residual,
            iterations: retry.iterations(),
            tolerance: model.cg.tolerance,
            accept: model.cg.acceptable(),
        });
    }
    backend.convolve(&fields.p, &mut fields.u)?;
    Ok(Solve {
        iterations: retry.iterations(),
        residual: second.residual,
        retry: Some(retry),
    })
}

/// Equilibrate the contact at approach `d` (length) with detachment stress `sigma_c`
/// (force/length²; 0 for a non-adhesive contact).
pub fn equilibrate<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field>,
    d: f64,
    sigma_c: f64,
) -> Result<Equilibrium, SolverError> {
    let d_bar = d / model.scene.scales().approach;
    let mut eq = Equilibrium::default();
    loop {
        eq.add_solve(solve_fixed(backend, model, fields, d)?);
        let change = backend.update_contact(&mut fields.p, &fields.u, d, sigma_c)?;
        eq.n_contact = change.n_contact;
        if change.at_edge > 0 {
            return Err(SolverError::ContactAtEdge {
                d_bar,
                elements: change.at_edge,
            });
        }
        if change.detached + change.attached == 0 || change.n_contact == 0 {
            return Ok(eq);
        }
        eq.sweeps += 1;
        if eq.sweeps >= model.max_sweeps {
            return Err(SolverError::DetachmentCycles {
                d_bar,
                sweeps: eq.sweeps,
                detached: change.detached,
                attached: change.attached,
            });
        }
    }
}
