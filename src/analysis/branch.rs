//! The adhesive branch of a simulated pull-off: the states to compare with JKR/JG and to fit
//! (SPEC §8.4).

use crate::solver::{Phase, State};

/// One point of the adhesive branch in the SPEC §2 normalisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchPoint {
    /// Mean contact radius c̄ (dimensionless).
    pub c_bar: f64,
    /// Approach d̄ (dimensionless).
    pub d_bar: f64,
    /// Force F̄ (dimensionless).
    pub f_bar: f64,
}

/// The adhesive branch of a pull-off: its [`Phase::Onset`] states with contact, in the order
/// recorded (c̄ decreasing).
///
/// An onset is the state at which, with the contact set held, the first element reaches the
/// detachment stress σ_c: the discrete form of the JKR/JG equilibrium (energy release rate =
/// Δγ at the front), and a local minimum of the sawtooth F(d). There is one per contact set,
/// from the initial contact (its critical state lies on the branch too) through the force
/// minimum to the last contact before it jumps off, so the branch runs over the whole stable
/// range of displacement control. The other states are left out because they are not
/// equilibria of the criterion: the approach (non-adhesive, [`Phase::Approach`]) and the
/// load steps ([`Phase::Pulloff`]), at which every element of the contact is below σ_c, so
/// F̄ and d̄ lie above the branch for their c̄ by up to one sawtooth tooth — before the first
/// onset, by the whole way from the Hertz state. States without contact (after the jump-off)
/// have no c̄ to fit.
pub fn adhesive_branch(states: &[State]) -> Vec<BranchPoint> {
    states
        .iter()
        .filter(|s| s.phase == Phase::Onset && s.n_contact > 0)
        .map(|s| BranchPoint {
            c_bar: s.c_bar,
            d_bar: s.d_bar,
            f_bar: s.f_bar,
        })
        .collect()
}

/// The columns (c̄, d̄, F̄) of branch points, ready for [`super::fit_d_of_c`] and
/// [`super::fit_f_of_c`].
pub fn columns(points: &[BranchPoint]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    (
        points.iter().map(|p| p.c_bar).collect(),
        points.iter().map(|p| p.d_bar).collect(),
        points.iter().map(|p| p.f_bar).collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(phase: Phase, n_contact: usize, c_bar: f64) -> State {
        State {
            step: 1,
            phase,
            d: 0.0,
            force: 0.0,
            area: 0.0,
            mean_radius: 0.0,
            a_axis: 0.0,
            b_axis: 0.0,
            n_contact,
            cg_iterations: 0,
            detach_sweeps: 0,
            d_bar: -c_bar,
            f_bar: -2.0 * c_bar,
            c_bar,
            a_bar: c_bar,
            b_bar: c_bar,
            cg_residual: 0.0,
            dx: 0.1,
        }
    }

    #[test]
    fn branch_keeps_onsets_with_contact_in_order() {
        let states = [
            state(Phase::Approach, 100, 1.5),
            state(Phase::Pulloff, 100, 1.5),
            state(Phase::Onset, 100, 1.5),
            state(Phase::Pulloff, 90, 1.4),
            state(Phase::Onset, 90, 1.4),
            state(Phase::Onset, 80, 1.3),
            state(Phase::Onset, 0, 0.0),
            state(Phase::Pulloff, 0, 0.0),
        ];
        let b = adhesive_branch(&states);
        let (c, d, f) = columns(&b);
        assert_eq!(c, [1.5, 1.4, 1.3]);
        assert_eq!(d, [-1.5, -1.4, -1.3]);
        assert_eq!(f, [-3.0, -2.8, -2.6]);
    }
}
