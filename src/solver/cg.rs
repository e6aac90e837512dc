//! Preconditioned conjugate gradients on a fixed contact set C:
//! (K p)_C = (d − h)_C, p = 0 off C. The system is symmetric positive definite on C.
//!
//! All vectors and CG's scalars stay on the backend's device; the host reads the residual
//! norm back only every `check_every` iterations to decide convergence.

use crate::backend::{Backend, BackendError, Slot};
use crate::model::CgSettings;

/// r·z of the current iteration.
const RZ: Slot = Slot(0);
/// r·z of the previous iteration.
const RZ_OLD: Slot = Slot(1);
/// s·(K s).
const SQ: Slot = Slot(2);
/// r·r.
const RR: Slot = Slot(3);
/// ‖(d − h)_C‖², the right-hand side's norm.
const BB: Slot = Slot(4);
/// A register that is never written, so it stays 0.
const ZERO: Slot = Slot(7);

/// The work fields CG needs, allocated once per run.
pub struct CgWork<F> {
    /// Residual r (length).
    pub r: F,
    /// Preconditioned residual z.
    pub z: F,
    /// Search direction s.
    pub s: F,
    /// K s (length).
    pub q: F,
    /// A field that stays zero (to evaluate the right-hand side d − h).
    zero: F,
}

impl<F> CgWork<F> {
    /// Allocate the work fields on `backend`.
    pub fn new<B: Backend<Field = F>>(backend: &mut B) -> Result<Self, BackendError> {
        Ok(CgWork {
            r: backend.field()?,
            z: backend.field()?,
            s: backend.field()?,
            q: backend.field()?,
            zero: backend.field()?,
        })
    }
}

/// How a CG solve ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CgReport {
    /// Iterations made (convolutions of a search direction).
    pub iterations: usize,
    /// Final relative residual ‖r‖/‖(d − h)_C‖ (dimensionless).
    pub residual: f64,
    /// Whether the tolerance was reached.
    pub converged: bool,
    /// Whether a non-finite value appeared.
    pub non_finite: bool,
}

impl CgReport {
    /// Mark the report converged or non-finite from its residual; true if CG should stop.
    fn finished(&mut self, tolerance: f64) -> bool {
        self.non_finite = !self.residual.is_finite();
        self.converged = self.residual <= tolerance;
        self.non_finite || self.converged
    }
}

/// Solve for p on the backend's contact set at approach `d` (length), warm-started from
/// the p given (which must be zero off C).
pub fn solve<B: Backend>(
    backend: &mut B,
    work: &mut CgWork<B::Field>,
    p: &mut B::Field,
    d: f64,
    settings: &CgSettings,
) -> Result<CgReport, BackendError> {
    let CgWork { r, z, s, q, zero } = work;
    // ‖(d − h)_C‖², and the initial residual r = (d − h − K p)_C.
    backend.residual(zero, d, r)?;
    backend.dot(r, r, BB)?;
    backend.convolve(p, q)?;
    backend.residual(q, d, r)?;
    backend.dot(r, r, RR)?;
    let mut v = [0.0; 2];
    backend.read_slots(&[RR, BB], &mut v)?;
    let norm_rhs = v[1].sqrt();
    let relative = |rr: f64| {
        if norm_rhs > 0.0 {
            rr.sqrt() / norm_rhs
        } else {
            rr.sqrt()
        }
    };
    let mut report = CgReport {
        iterations: 0,
        residual: relative(v[0]),
        converged: false,
        non_finite: false,
    };
    if report.finished(settings.tolerance) {
        return Ok(report);
    }
    backend.precondition(r, z)?;
    backend.dot(r, z, RZ)?;
    // s = z (the ratio 0/0 counts as 0, so the old direction vanishes).
    backend.xpay_ratio(s, z, ZERO, ZERO)?;
    for k in 1..=settings.max_iterations {
        backend.convolve(s, q)?;
        backend.dot(s, q, SQ)?;
        backend.axpy_ratio(p, s, RZ, SQ, 1.0)?;
        backend.axpy_ratio(r, q, RZ, SQ, -1.0)?;
        report.iterations = k;
        if k % settings.check_every == 0 || k == settings.max_iterations {
            backend.dot(r, r, RR)?;
            let mut rr = [0.0];
            backend.read_slots(&[RR], &mut rr)?;
            report.residual = relative(rr[0]);
            if report.finished(settings.tolerance) {
                return Ok(report);
            }
        }
        backend.copy_slot(RZ, RZ_OLD)?;
        backend.precondition(r, z)?;
        backend.dot(r, z, RZ)?;
        backend.xpay_ratio(s, z, RZ, RZ_OLD)?;
    }
    Ok(report)
}
