//! The fields of a picked state, rebuilt after its run: its contact set solved again at its
//! approach on the CPU backend (f64, whichever backend ran the pull-off), giving the
//! pressure, the displacement and so the gap. The state's contact set and approach determine
//! its fields, so the rebuilt ones are the run's own (to the solver's tolerance), without
//! holding a field per state while the run goes.

use super::{failed, RunError};
use crate::analysis::fields::{Pick, StateFields};
use crate::backend::cpu::CpuBackend;
use crate::backend::FieldStore;
use crate::model::Model;
use crate::solver::equilibrium::{solve_fixed, Fields};

/// The fields of each of `picks`, states of `model`'s run (each on the re-gridded model where
/// the run had re-gridded by then, as its Δx says), in order. Picks on one grid share one CPU
/// backend (its FFT plans and kernel are made once per Δx).
pub fn rebuild(model: &Model, picks: Vec<Pick>) -> Vec<Result<StateFields, RunError>> {
    let mut opened: Option<(f64, Model, CpuBackend)> = None;
    picks
        .into_iter()
        .map(|pick| {
            let dx = pick.state.dx;
            if opened.as_ref().is_none_or(|(at, _, _)| *at != dx) {
                let m = if (dx - model.dx).abs() > 1e-12 * model.dx {
                    model.regridded(dx / model.dx)
                } else {
                    model.clone()
                };
                let cpu = CpuBackend::new(&m.grid_setup()).map_err(|e| cannot(&pick, &e))?;
                opened = Some((dx, m, cpu));
            }
            let (_, m, cpu) = opened.as_mut().expect("opened above");
            rebuild_on(m, cpu, pick)
        })
        .collect()
}

/// Why the fields of `pick` cannot be rebuilt.
fn cannot(pick: &Pick, e: &dyn std::fmt::Display) -> RunError {
    failed(format!(
        "the fields of state {} ({}) cannot be rebuilt: {e}",
        pick.index, pick.label
    ))
}

/// The fields of `pick` on `m`, its grid, solved on `cpu`.
fn rebuild_on(m: &Model, cpu: &mut CpuBackend, pick: Pick) -> Result<StateFields, RunError> {
    let n = m.nx * m.ny;
    if pick.mask.len() != n {
        return Err(cannot(
            &pick,
            &format!(
                "its contact set has {} elements, the grid {n}",
                pick.mask.len()
            ),
        ));
    }
    let mut fields = Fields::new(cpu, pick.mask.clone()).map_err(|e| cannot(&pick, &e))?;
    let d = pick.state.d;
    solve_fixed(cpu, m, &mut fields, d).map_err(|e| cannot(&pick, &e))?;
    let mut pressure = vec![0.0; n];
    let mut u = vec![0.0; n];
    cpu.download(&fields.p, &mut pressure)
        .map_err(|e| cannot(&pick, &e))?;
    cpu.download(&fields.u, &mut u)
        .map_err(|e| cannot(&pick, &e))?;
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
