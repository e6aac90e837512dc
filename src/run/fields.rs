//! The fields of a picked state, rebuilt after its run: its contact set solved again at its
//! approach on the CPU backend (f64, whichever backend ran the pull-off), giving the
//! pressure, the displacement and so the gap. The state's contact set and approach determine
//! its fields, so the rebuilt ones are the run's own (to the solver's tolerance), without
//! holding a field per state while the run goes.

use super::{failed, RunError};
use crate::analysis::fields::{Pick, StateFields};
use crate::backend::cpu::CpuBackend;
use crate::backend::Device;
use crate::model::Model;
use crate::solver::equilibrium::{solve_fixed, Fields};

/// The fields of `pick`, a state of `model`'s run (on the re-gridded model where the run had
/// re-gridded by then, as the state's Δx says).
pub fn rebuild(model: &Model, pick: Pick) -> Result<StateFields, RunError> {
    let m = if (pick.state.dx - model.dx).abs() > 1e-12 * model.dx {
        model.regridded(pick.state.dx / model.dx)
    } else {
        model.clone()
    };
    let n = m.nx * m.ny;
    if pick.mask.len() != n {
        return Err(failed(format!(
            "the fields of state {} cannot be rebuilt: its contact set has {} elements, the grid \
             {}",
            pick.index,
            pick.mask.len(),
            n
        )));
    }
    let why = |e: &dyn std::fmt::Display| {
        failed(format!(
            "the fields of state {} ({}) cannot be rebuilt: {e}",
            pick.index, pick.label
        ))
    };
    let mut cpu = CpuBackend::new(&m.grid_setup()).map_err(|e| why(&e))?;
    let mut fields = Fields::new(&mut cpu, pick.mask.clone()).map_err(|e| why(&e))?;
    let d = pick.state.d;
    solve_fixed(&mut cpu, &m, &mut fields, d).map_err(|e| why(&e))?;
    let mut pressure = vec![0.0; n];
    let mut u = vec![0.0; n];
    cpu.download(&fields.p, &mut pressure)
        .map_err(|e| why(&e))?;
    cpu.download(&fields.u, &mut u).map_err(|e| why(&e))?;
    let gap = m.profile().iter().zip(&u).map(|(h, u)| h - d + u).collect();
    Ok(StateFields {
        index: pick.index,
        label: pick.label,
        state: pick.state,
        nx: m.nx,
        ny: m.ny,
        dx: m.dx,
        x: (0..m.nx).map(|i| m.x(i)).collect(),
        y: (0..m.ny).map(|j| m.y(j)).collect(),
        pressure,
        gap,
        contact: pick.mask,
        sigma_c: m.sigma_c,
    })
}
