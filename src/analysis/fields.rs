//! The fields of chosen states: which states a run keeps them for ([`FieldChoice`]), the
//! contact masks kept as the run goes ([`FieldPicks`]), and the fields themselves
//! ([`StateFields`]: pressure, gap and contact set on the grid, with its coordinates), with the
//! checks they satisfy.

use super::capture::MaskObserver;
use crate::solver::{Phase, State};

pub use crate::params::FieldChoice;

/// The memory the kept fields need.
impl FieldChoice {
    /// The memory the kept fields need on a grid of `elements` whose run records about
    /// `states` states (bytes; [`FIELD_BYTES_PER_ELEMENT`] per element of each kept state).
    pub fn memory_estimate(&self, elements: usize, states: usize) -> u64 {
        (self.kept_states(states) as u64)
            .saturating_mul(elements as u64)
            .saturating_mul(FIELD_BYTES_PER_ELEMENT)
    }
}

/// Memory one kept state's fields take per grid element (bytes): its contact mask while the
/// run goes (1), then its pressure and gap in f64 and its contact set (17), and the arrays the
/// `.npz` is written from (16).
pub const FIELD_BYTES_PER_ELEMENT: u64 = 34;

/// The label of the lowest state of a run that did not reach the force minimum (it holds no
/// "force minimum", which names the reached minimum alone).
pub const LOWEST_NOT_MINIMUM: &str = "lowest force recorded (the run did not reach the minimum)";

/// The label of a run's lowest state: "force minimum" where the run reached it.
pub fn minimum_label(min_reached: bool) -> &'static str {
    if min_reached {
        "force minimum"
    } else {
        LOWEST_NOT_MINIMUM
    }
}

/// A state chosen for its fields, with its contact mask.
#[derive(Debug, Clone)]
pub struct Pick {
    /// Its index among the run's recorded states (0: the first press).
    pub index: usize,
    /// Why it was chosen ("force minimum", "state 12").
    pub label: String,
    /// The state.
    pub state: State,
    /// Its contact set (row-major, ny rows of nx; true = in contact).
    pub mask: Vec<bool>,
}

/// Keeps the masks of the states a [`FieldChoice`] asks for as a run records them; the force
/// minimum's is kept until a lower state replaces it.
#[derive(Debug, Clone, Default)]
pub struct FieldPicks {
    choice: FieldChoice,
    seen: usize,
    picked: Vec<Pick>,
    minimum: Option<Pick>,
}

impl FieldPicks {
    /// Picks for `choice`.
    pub fn new(choice: FieldChoice) -> Self {
        FieldPicks {
            choice,
            ..Default::default()
        }
    }

    /// The indices `--fields states:…` listed that the run never recorded (it recorded
    /// fewer states): they have no fields, which the caller says.
    pub fn unrecorded(&self) -> Vec<usize> {
        match &self.choice {
            FieldChoice::States(v) => v.iter().copied().filter(|&i| i >= self.seen).collect(),
            _ => Vec::new(),
        }
    }

    /// The states picked, by index, the force minimum among them (once, even where it is
    /// also an every-k-th or listed state). Where the run did not reach the force minimum
    /// (`min_reached` false), the lowest state is labelled [`LOWEST_NOT_MINIMUM`] instead:
    /// it is only the lowest force seen.
    pub fn into_picks(self, min_reached: bool) -> Vec<Pick> {
        let mut all = self.picked;
        if let Some(mut m) = self.minimum {
            let label = minimum_label(min_reached);
            match all.iter_mut().find(|p| p.index == m.index) {
                Some(p) => p.label = format!("{}, {label}", p.label),
                None => {
                    m.label = label.into();
                    all.push(m)
                }
            }
        }
        all.sort_by_key(|p| p.index);
        all
    }
}

impl MaskObserver for FieldPicks {
    fn observe(&mut self, state: &State, mask: &[bool]) {
        let index = self.seen;
        self.seen += 1;
        let listed = match &self.choice {
            FieldChoice::None => return,
            FieldChoice::Minimum => false,
            FieldChoice::Every(k) => index.is_multiple_of(*k),
            FieldChoice::States(v) => v.contains(&index),
        };
        if listed {
            self.picked.push(Pick {
                index,
                label: format!("state {index}"),
                state: state.clone(),
                mask: mask.to_vec(),
            });
        }
        let lower = state.phase != Phase::Approach
            && state.n_contact > 0
            && self
                .minimum
                .as_ref()
                .is_none_or(|m| state.force < m.state.force);
        if lower {
            self.minimum = Some(Pick {
                index,
                label: "force minimum".into(),
                state: state.clone(),
                mask: mask.to_vec(),
            });
        }
    }
}

/// The fields of one state on its grid: arrays are row-major, ny rows of nx (index j·nx + i
/// for x(i), y(j)).
#[derive(Debug, Clone)]
pub struct StateFields {
    /// The state's index among the run's recorded states.
    pub index: usize,
    /// Why it was chosen.
    pub label: String,
    /// The state.
    pub state: State,
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Element side Δx at this state (length).
    pub dx: f64,
    /// Element centres along x, from the apex (length).
    pub x: Vec<f64>,
    /// Element centres along y, from the apex (length).
    pub y: Vec<f64>,
    /// Contact pressure p (force/length², compressive positive; zero off the contact).
    pub pressure: Vec<f64>,
    /// Gap g = h − d + u (length; zero on the contact up to the solver's tolerance).
    pub gap: Vec<f64>,
    /// The contact set (true = in contact).
    pub contact: Vec<bool>,
    /// The detachment stress σ_c at this Δx (force/length²).
    pub sigma_c: f64,
}

impl StateFields {
    /// The force Σ p Δx² (force): the state's own force, up to the solver's tolerance.
    pub fn force(&self) -> f64 {
        self.pressure.iter().sum::<f64>() * self.dx * self.dx
    }

    /// The largest |g| on the contact (length).
    pub fn largest_gap_on_contact(&self) -> f64 {
        self.on(true).map(|(_, g)| g.abs()).fold(0.0, f64::max)
    }

    /// The smallest g off the contact (length; +∞ if every element is in contact).
    pub fn smallest_gap_off_contact(&self) -> f64 {
        self.on(false).map(|(_, g)| g).fold(f64::INFINITY, f64::min)
    }

    /// The lowest pressure on the contact (force/length²; +∞ if there is none): the
    /// criterion keeps it at −σ_c or above.
    pub fn lowest_pressure_on_contact(&self) -> f64 {
        self.on(true).map(|(p, _)| p).fold(f64::INFINITY, f64::min)
    }

    /// (p, g) of the elements in (`true`) or out of contact.
    fn on(&self, contact: bool) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.contact
            .iter()
            .zip(self.pressure.iter().zip(&self.gap))
            .filter(move |(c, _)| **c == contact)
            .map(|(_, (p, g))| (*p, *g))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(force: f64, phase: Phase) -> State {
        State {
            force,
            phase,
            n_contact: 1,
            ..State::default()
        }
    }

    #[test]
    fn choices_parse_and_refuse() {
        assert_eq!(FieldChoice::parse("minimum"), Ok(FieldChoice::Minimum));
        assert_eq!(FieldChoice::parse("every:5"), Ok(FieldChoice::Every(5)));
        assert_eq!(
            FieldChoice::parse("states:0, 7"),
            Ok(FieldChoice::States(vec![0, 7]))
        );
        for choice in ["none", "minimum", "every:5", "states:0,7"] {
            assert_eq!(FieldChoice::parse(choice).unwrap().name(), choice);
        }
        for bad in ["every:0", "states:", "max", "every:x"] {
            assert!(FieldChoice::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn picks_keep_the_listed_states_and_the_minimum_once() {
        let mut picks = FieldPicks::new(FieldChoice::Every(2));
        let forces = [5.0, 1.0, -1.0, -3.0, -2.0];
        for (i, f) in forces.iter().enumerate() {
            let phase = if i == 0 {
                Phase::Approach
            } else {
                Phase::Pulloff
            };
            picks.observe(&state(*f, phase), &[i % 2 == 0]);
        }
        let p = picks.into_picks(true);
        let idx: Vec<usize> = p.iter().map(|p| p.index).collect();
        assert_eq!(idx, vec![0, 2, 3, 4]);
        assert_eq!(p[2].label, "force minimum");
        let mut only = FieldPicks::new(FieldChoice::Minimum);
        for (i, f) in forces.iter().enumerate() {
            only.observe(&state(*f, Phase::Pulloff), &[i == 3]);
        }
        let p = only.clone().into_picks(true);
        assert_eq!((p.len(), p[0].index, p[0].mask.clone()), (1, 3, vec![true]));
        assert_eq!(p[0].label, "force minimum");
        // A run that stopped before its minimum: its lowest state is not called one.
        let p = only.into_picks(false);
        assert_eq!((p.len(), p[0].index), (1, 3));
        assert_eq!(p[0].label, LOWEST_NOT_MINIMUM);
        assert!(!p[0].label.contains("force minimum"));
    }
}
