//! The adhesive branch of a simulated pull-off: the states to compare with JKR/JG and to fit
//! (physics §8.4).

use crate::solver::{Phase, State};

/// One point of the adhesive branch in the physics §2 normalisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchPoint {
    /// Mean contact radius c̄ (dimensionless).
    pub c_bar: f64,
    /// Approach d̄ (dimensionless).
    pub d_bar: f64,
    /// Force F̄ (dimensionless).
    pub f_bar: f64,
    /// One over the elements across the contact's minor axis there, Δx/(2b) (dimensionless):
    /// the abscissa in which the discretisation error is first order.
    pub inv_n: f64,
}

/// The adhesive branch of a pull-off: its [`Phase::Onset`] states with contact, in the order
/// recorded (c̄ decreasing), from the first at which the crack front has left its initial
/// position all round.
///
/// An onset is the state at which, with the contact set held, the first element reaches the
/// detachment stress σ_c: the discrete form of the JKR/JG equilibrium (energy release rate =
/// Δγ at the front), and a local minimum of the sawtooth F(d). The other states are left out
/// because they are not equilibria of the criterion: the approach (non-adhesive,
/// [`Phase::Approach`]) and the load steps ([`Phase::Pulloff`]), at which every element of the
/// contact is below σ_c, so F̄ and d̄ lie above the branch for their c̄ by up to one sawtooth
/// tooth. States without contact (after the jump-off) have no c̄ to fit.
///
/// Right after the non-adhesive press the front is pinned where the energy release rate is
/// lowest: the first onsets detach only part of it (for slender contacts the ends of the major
/// axis move while the minor axis holds), and F̄ there lies far off the propagating branch
/// (R1/R2 = 25: 2.98 at c̄ = 1.51). Since the release rate around an elliptical front is
/// extreme at the ends of its axes, the front has moved all round once the contact's
/// half-lengths along both axes ([`State::a_axis`], [`State::b_axis`]) are below those of the
/// first contact; onsets before that are the pinned transient and are dropped. See
/// [`pinned_transient`].
pub fn adhesive_branch(states: &[State]) -> Vec<BranchPoint> {
    let skip = pinned_transient(states);
    states[skip..]
        .iter()
        .filter(|s| s.phase == Phase::Onset && s.n_contact > 0)
        .map(|s| BranchPoint {
            c_bar: s.c_bar,
            d_bar: s.d_bar,
            f_bar: s.f_bar,
            inv_n: s.dx / (2.0 * s.b_axis),
        })
        .collect()
}

/// How many leading states belong to the pinned transient after the press: those before the
/// first state whose contact half-lengths along x and y are both below the first contact's
/// (by more than rounding). All of them if the front never moves all round.
pub fn pinned_transient(states: &[State]) -> usize {
    let Some(first) = states.iter().find(|s| s.n_contact > 0) else {
        return states.len();
    };
    let (a0, b0) = (first.a_axis, first.b_axis);
    let below = |v: f64, v0: f64| v < v0 * (1.0 - 1e-9);
    states
        .iter()
        .position(|s| s.n_contact > 0 && below(s.a_axis, a0) && below(s.b_axis, b0))
        .unwrap_or(states.len())
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
            a_axis: c_bar,
            b_axis: c_bar,
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
        // The onset at the first contact's size is the pinned transient.
        assert_eq!(c, [1.4, 1.3]);
        assert_eq!(d, [-1.4, -1.3]);
        assert_eq!(f, [-2.8, -2.6]);
    }

    #[test]
    fn onsets_before_the_front_moves_along_both_axes_are_the_pinned_transient() {
        let mut states = vec![state(Phase::Approach, 100, 1.5)];
        // The major axis shrinks while the minor axis holds: still pinned.
        for (i, c) in [1.49, 1.48, 1.47].into_iter().enumerate() {
            let mut s = state(Phase::Onset, 99 - i, c);
            s.b_axis = 1.5;
            states.push(s);
        }
        states.push(state(Phase::Onset, 90, 1.4));
        states.push(state(Phase::Onset, 80, 1.3));
        assert_eq!(pinned_transient(&states), 4);
        let (c, _, _) = columns(&adhesive_branch(&states));
        assert_eq!(c, [1.4, 1.3]);
        // A front that never moves all round leaves no branch.
        assert_eq!(pinned_transient(&states[..4]), 4);
        assert!(adhesive_branch(&states[..4]).is_empty());
    }
}
