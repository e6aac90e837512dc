//! The detachment/attachment loop at one approach (SPEC §6.2): solve on a fixed contact
//! set, detach over-stressed elements, attach overlapping ones, repeat until nothing changes.

use super::cg::{self, CgEnd, CgWork};
use super::SolverError;
use crate::backend::Backend;
use crate::model::Model;

/// The result of equilibrating one approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Equilibrium {
    /// CG iterations over all sweeps.
    pub cg_iterations: usize,
    /// Sweeps that changed the contact set.
    pub sweeps: usize,
    /// Elements in contact at the end.
    pub n_contact: usize,
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
            cg: CgWork::new(backend)?,
        })
    }
}

/// Solve for p on the unchanged contact set at approach `d` (length); returns the CG
/// iterations spent.
pub fn solve_fixed<B: Backend>(
    backend: &mut B,
    model: &Model,
    fields: &mut Fields<B::Field>,
    d: f64,
) -> Result<usize, SolverError> {
    let d_bar = d / model.scene.scales().approach;
    let rep = cg::solve(backend, &mut fields.cg, &mut fields.p, d, &model.cg)?;
    if rep.end == CgEnd::NonFinite {
        return Err(SolverError::NonFinite {
            d_bar,
            iterations: rep.iterations,
        });
    }
    if !rep.converged() {
        return Err(SolverError::CgNotConverged {
            d_bar,
            residual: rep.residual,
            iterations: rep.iterations,
            tolerance: model.cg.tolerance,
        });
    }
    Ok(rep.iterations)
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
    let mut eq = Equilibrium {
        cg_iterations: 0,
        sweeps: 0,
        n_contact: 0,
    };
    loop {
        eq.cg_iterations += solve_fixed(backend, model, fields, d)?;
        backend.convolve(&fields.p, &mut fields.u)?;
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
