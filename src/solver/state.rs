//! A recorded, converged state of the pull-off, dimensional and normalised.

use serde::{Deserialize, Serialize};

/// Which part of the protocol a state belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Phase {
    /// The first, non-adhesive press to d0.
    Approach,
    /// A step of the adhesive pull-off.
    Pulloff,
    /// Inside a pull-off step, the approach at which the first element of the unchanged
    /// contact set reaches σ_c: a local minimum of the sawtooth F(d), recorded so that the
    /// force minimum does not depend on the step size.
    Onset,
    /// The state just after re-gridding: the contact carried to a finer grid and
    /// re-equilibrated at the same approach.
    Regrid,
}

/// One converged state. Dimensional values are in the scene's units; `*_bar` values are
/// normalised as in SPEC §2.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct State {
    /// Load step (0 for the approach).
    pub step: usize,
    /// Protocol phase.
    pub phase: Phase,
    /// Approach d (length; > 0 presses in).
    pub d: f64,
    /// Force F = Σ p Δx² (force; > 0 compressive).
    pub force: f64,
    /// Contact area A (length²).
    pub area: f64,
    /// Mean contact radius c = √(A/π) (length).
    pub mean_radius: f64,
    /// Half-length of the contact along the x axis through the centre (length).
    pub a_axis: f64,
    /// Half-length of the contact along the y axis through the centre (length).
    pub b_axis: f64,
    /// Elements in contact.
    pub n_contact: usize,
    /// CG iterations spent on this state.
    pub cg_iterations: usize,
    /// Detachment/attachment sweeps that changed the contact set at this state.
    pub detach_sweeps: usize,
    /// d̄ (dimensionless).
    pub d_bar: f64,
    /// F̄ (dimensionless).
    pub f_bar: f64,
    /// c̄ (dimensionless).
    pub c_bar: f64,
    /// ā (dimensionless).
    pub a_bar: f64,
    /// b̄ (dimensionless).
    pub b_bar: f64,
    /// The largest relative residual ‖(d − h − K p)_C‖/‖(d − h)_C‖ of the CG solves behind
    /// this state, recomputed from p (dimensionless). Normally below the CG tolerance (or
    /// near 1e-7 in f32); above it, the state was accepted after CG's safer retry fell
    /// short. NaN when read from a file written before the column existed.
    #[serde(default = "not_recorded")]
    pub cg_residual: f64,
    /// Element side Δx of the grid this state was computed on (length); it changes only
    /// when the run re-grids.
    #[serde(default)]
    pub dx: f64,
}

/// The value of a column missing from an older file.
fn not_recorded() -> f64 {
    f64::NAN
}

/// Half-lengths (in elements) of a contact mask along the two axes through the centre of an
/// nx × ny grid (both even): contact elements in the two middle rows (columns), averaged, halved.
pub fn axis_half_lengths(mask: &[bool], nx: usize, ny: usize) -> (f64, f64) {
    let row = |j: usize| mask[j * nx..(j + 1) * nx].iter().filter(|&&m| m).count();
    let col = |i: usize| (0..ny).filter(|&j| mask[j * nx + i]).count();
    let a = (row(ny / 2 - 1) + row(ny / 2)) as f64 / 4.0;
    let b = (col(nx / 2 - 1) + col(nx / 2)) as f64 / 4.0;
    (a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_half_lengths_of_a_rectangle() {
        // A 6 × 2 block of contact centred on an 8 × 4 grid: half-lengths 3 and 1 elements.
        let (nx, ny) = (8, 4);
        let mask: Vec<bool> = (0..nx * ny)
            .map(|k| (1..7).contains(&(k % nx)) && (1..3).contains(&(k / nx)))
            .collect();
        assert_eq!(axis_half_lengths(&mask, nx, ny), (3.0, 1.0));
    }
}
