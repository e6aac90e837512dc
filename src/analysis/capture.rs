//! Keeping the contact masks of a few chosen states of a run (for contours and snapshots)
//! without holding every state's mask: the first pull-off state at or below each of some
//! contact radii c̄, and the state of minimum force.

use super::contour::{ellipse_departure, quarter_contour_for, Departure};
use crate::model::Model;
use crate::solver::{Phase, State};
use serde::{Deserialize, Serialize};

/// A state and its contact mask (row-major nx × ny, true = in contact).
#[derive(Debug, Clone)]
pub struct Snapshot {
    /// What the state was chosen for, e.g. "c̄ ≤ 1.0" or "force minimum".
    pub label: String,
    /// The state.
    pub state: State,
    /// Its contact mask.
    pub mask: Vec<bool>,
}

/// What sees every recorded state of a run with its contact mask (row-major nx × ny, true =
/// in contact).
pub trait MaskObserver {
    /// Look at one recorded state and its mask.
    fn observe(&mut self, state: &State, mask: &[bool]);
}

impl MaskObserver for ContactCapture {
    fn observe(&mut self, state: &State, mask: &[bool]) {
        ContactCapture::observe(self, state, mask)
    }
}

/// Collects [`Snapshot`]s as a run records states (see `solver::run_with_contact`).
#[derive(Debug, Clone, Default)]
pub struct ContactCapture {
    /// Contact radii c̄ still waiting for their state, largest first.
    pending: Vec<f64>,
    taken: Vec<Snapshot>,
    minimum: Option<Snapshot>,
}

impl ContactCapture {
    /// Capture the first pull-off state with c̄ ≤ each of `c_bar_thresholds` (dimensionless),
    /// and the state of minimum force.
    pub fn new(c_bar_thresholds: &[f64]) -> Self {
        let mut pending = c_bar_thresholds.to_vec();
        pending.sort_by(|a, b| b.total_cmp(a));
        ContactCapture {
            pending,
            ..Default::default()
        }
    }

    /// Look at one recorded state and its mask.
    pub fn observe(&mut self, state: &State, mask: &[bool]) {
        if state.phase == Phase::Approach || state.n_contact == 0 {
            return;
        }
        if self
            .minimum
            .as_ref()
            .is_none_or(|m| state.force < m.state.force)
        {
            self.minimum = Some(Snapshot {
                label: "force minimum".into(),
                state: state.clone(),
                mask: mask.to_vec(),
            });
        }
        while let Some(&c) = self.pending.first() {
            if state.c_bar > c {
                break;
            }
            self.pending.remove(0);
            self.taken.push(Snapshot {
                label: format!("c̄ ≤ {c}"),
                state: state.clone(),
                mask: mask.to_vec(),
            });
        }
    }

    /// The snapshots taken, the force minimum last (labelled as only the lowest force seen
    /// where the run did not reach the minimum, `min_reached` false).
    pub fn into_snapshots(self, min_reached: bool) -> Vec<Snapshot> {
        let mut all = self.taken;
        all.extend(self.minimum.map(|mut m| {
            m.label = super::fields::minimum_label(min_reached).into();
            m
        }));
        all
    }
}

/// One point of a quarter contour, normalised (physics §2), with its state and ellipse.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ContourRow {
    /// What the state was chosen for.
    pub label: String,
    /// c̄ and F̄ of the state.
    pub c_bar: f64,
    /// F̄ of the state.
    pub f_bar: f64,
    /// Half-axes ā, b̄ of the contact (through its centre).
    pub a_bar: f64,
    /// b̄.
    pub b_bar: f64,
    /// Departure of the contour from the ellipse ā, b̄: RMS and max of r/r_e − 1.
    pub departure_rms: f64,
    /// Largest |r/r_e − 1|.
    pub departure_max: f64,
    /// Boundary point x/c_r.
    pub x_bar: f64,
    /// Boundary point y/c_r.
    pub y_bar: f64,
    /// d̄ of the state (the last column, so that readers of the first ten keep working).
    pub d_bar: f64,
}

/// The quarter contour of every snapshot as rows, with its departure from the ellipse of
/// the same half-axes; snapshots whose contour cannot be traced are left out.
pub fn contour_rows(model: &Model, snapshots: &[Snapshot]) -> Vec<ContourRow> {
    let length = model.scene.scales().length;
    let mut rows = Vec::new();
    for s in snapshots {
        let Ok(points) = quarter_contour_for(model, &s.mask) else {
            continue;
        };
        let Ok(Departure { rms, max, .. }) =
            ellipse_departure(&points, s.state.a_axis, s.state.b_axis)
        else {
            continue;
        };
        rows.extend(points.iter().map(|p| ContourRow {
            label: s.label.clone(),
            c_bar: s.state.c_bar,
            f_bar: s.state.f_bar,
            a_bar: s.state.a_bar,
            b_bar: s.state.b_bar,
            departure_rms: rms,
            departure_max: max,
            x_bar: p.x / length,
            y_bar: p.y / length,
            d_bar: s.state.d_bar,
        }));
    }
    rows
}
