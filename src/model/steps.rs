//! The load path: the approach d from the first press d0 down in equal steps, sized from a
//! hint of where the pull-off ends (the planner's, or the scene's closed form), to a final
//! approach at which a run stops if the contact is still there.

use super::grid::invalid;
use super::limits::MIN_FINAL_D_BAR;
use super::ModelError;
use crate::params::FINAL_D;
use crate::scene::{PullOffHint, Scene};
use crate::text::compact;

/// The hint a scene gives when its indenter has no closed form: the sphere's end of contact
/// at about d̄ = −0.5 and a contact of half-axis b̄ = 0.5 at the force minimum.
const FALLBACK_HINT: PullOffHint = PullOffHint {
    end_d_bar: -0.5,
    b_bar_at_min: 0.5,
};

/// The hint the load path and the resolution check use: `given` (a planner's) or the
/// scene's closed form, else the sphere's (an end of contact at d̄ = −0.5, b̄ = 0.5 at the
/// force minimum).
pub fn hint_for(scene: &Scene, given: Option<PullOffHint>) -> PullOffHint {
    given
        .or_else(|| {
            scene
                .indenter
                .pull_off_hint(scene.e_star, scene.work_of_adhesion)
        })
        .unwrap_or(FALLBACK_HINT)
}

/// The approaches a pull-off steps through (all lengths in the scene's length unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadPath {
    /// Approach of the first, non-adhesive press, d0 (length).
    pub d0: f64,
    /// Decrement of d per load step (length).
    pub d_step: f64,
    /// Stop once d falls below this (length).
    pub d_final: f64,
    /// Where the hint expects the contact to end (length).
    pub d_end: f64,
}

impl LoadPath {
    /// `steps` equal steps from `d0` (length) to the hint's end of contact; the run stops at
    /// `final_d_bar` (normalised by `approach`, the scene's approach scale in length) or, by
    /// default, as far again below the end as d0 lies above it. Refuses a final approach
    /// outside [`MIN_FINAL_D_BAR`, d̄0).
    pub fn new(
        d0: f64,
        approach: f64,
        steps: usize,
        final_d_bar: Option<f64>,
        hint: PullOffHint,
    ) -> Result<Self, ModelError> {
        let d0_bar = d0 / approach;
        let end = hint.end_d_bar;
        if let Some(f) = final_d_bar {
            if !(f >= MIN_FINAL_D_BAR && f < d0_bar) {
                return Err(invalid(
                    FINAL_D,
                    compact(f),
                    format!(
                        "a d̄ in [{MIN_FINAL_D_BAR}, d̄0) below the initial approach d̄0 = {d0_bar:.4}"
                    ),
                ));
            }
        }
        Ok(LoadPath {
            d0,
            d_step: (d0_bar - end) / steps as f64 * approach,
            d_final: final_d_bar.unwrap_or(end - 2.0 * (d0_bar - end)) * approach,
            d_end: end * approach,
        })
    }

    /// The approach after `step` load steps (length).
    pub fn approach(&self, step: usize) -> f64 {
        self.d0 - step as f64 * self.d_step
    }

    /// Load steps the pull-off is expected to take: those to the hint's end of contact, fewer
    /// if the final approach comes first (for a progress line; a run can take a few more, or
    /// stop earlier when it measures only the adhesive force).
    pub fn expected_steps(&self) -> usize {
        let planned = (self.d0 - self.d_final) / self.d_step;
        let to_end = ((self.d0 - self.d_end) / self.d_step).round().max(1.0) as usize;
        (planned.floor() as usize).clamp(1, to_end)
    }
}

/// Where the loading phase stops (see [`crate::model::Preload`], resolved for one model).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LoadTarget {
    /// At this approach d (length).
    Depth(f64),
    /// Once the compressive force reaches this (force).
    Force(f64),
    /// Once the contact covers this fraction of the domain (dimensionless).
    AreaFraction(f64),
}

/// The loading phase: from the first touch, the approach rises in steps of `d_step` (the
/// last one shortened to land on a [`LoadTarget::Depth`]; towards a force or an area the
/// steps are aimed by the secant through the last two states) until the target is reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loading {
    /// The approach at which the indenter first touches the grid: the least height of its
    /// element centres (length).
    pub d_touch: f64,
    /// The approach's increment per loading step (length).
    pub d_step: f64,
    /// Where loading stops.
    pub target: LoadTarget,
}

impl Loading {
    /// Loading steps the phase is expected to take (for a progress line).
    pub fn expected_steps(&self) -> usize {
        match self.target {
            LoadTarget::Depth(d) => ((d - self.d_touch) / self.d_step).ceil().max(1.0) as usize,
            _ => 1,
        }
    }

    /// The approach after `step` loading steps towards a depth `d_pre` (length): equal steps
    /// from the touch, the last landing on `d_pre` exactly.
    pub fn depth_approach(&self, step: usize, d_pre: f64) -> f64 {
        let n = self.expected_steps();
        if step >= n {
            d_pre
        } else {
            self.d_touch + (d_pre - self.d_touch) * step as f64 / n as f64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HINT: PullOffHint = PullOffHint {
        end_d_bar: -0.5,
        b_bar_at_min: 0.5,
    };

    #[test]
    fn steps_reach_the_hinted_end_and_stop_as_far_again_below() {
        let p = LoadPath::new(3.0, 2.0, 100, None, HINT).unwrap();
        // d̄0 = 1.5, end −0.5: 2.0 of d̄ in 100 steps, 0.04 of length each.
        assert!((p.d_step - 0.04).abs() < 1e-15);
        assert!((p.approach(100) - p.d_end).abs() < 1e-12);
        assert!((p.d_final - (-0.5 - 4.0) * 2.0).abs() < 1e-12);
        assert_eq!(p.expected_steps(), 100);
    }

    #[test]
    fn an_early_final_approach_shortens_the_expected_steps() {
        let p = LoadPath::new(3.0, 2.0, 100, Some(0.5), HINT).unwrap();
        assert_eq!(p.expected_steps(), 50);
        assert!((p.d_final - 1.0).abs() < 1e-15);
    }

    #[test]
    fn a_final_approach_above_the_first_is_refused() {
        let e = LoadPath::new(3.0, 2.0, 100, Some(2.0), HINT).unwrap_err();
        assert!(
            matches!(e, ModelError::Invalid { param, .. } if param == FINAL_D),
            "{e}"
        );
    }
}
