//! An invalid model choice, named as the flag that sets it.

use super::limits::{MAX_GRID, MIN_ELEMENTS_AT_MINIMUM, MIN_ELEMENTS_FIRST_CONTACT, MIN_GRID};
use crate::text::compact;
use thiserror::Error;

/// An invalid model choice, named as the flag that sets it.
#[derive(Debug, Error, PartialEq)]
pub enum ModelError {
    /// A grid side that is not a power of two in [[`MIN_GRID`], [`MAX_GRID`]].
    #[error("{flag} = {value} is invalid: the grid must be a power of two from {MIN_GRID} to {MAX_GRID} (e.g. 64, 128, 256, 512)")]
    Grid {
        /// The flag.
        flag: &'static str,
        /// The value given.
        value: usize,
    },
    /// Any other out-of-range value.
    #[error("{flag} = {value} is invalid: {expected}")]
    Invalid {
        /// The flag.
        flag: &'static str,
        /// The value given, as text.
        value: String,
        /// What is accepted, and what to change.
        expected: String,
    },
    /// The grid resolves the scene's contact by too few elements.
    #[error(
        "--grid {nx} is too coarse for this scene ({scene}): the first contact spans \
         {} elements across its minor axis (at least {MIN_ELEMENTS_FIRST_CONTACT} needed) and \
         the contact at the force minimum about {} (at least {MIN_ELEMENTS_AT_MINIMUM}); {advice}",
        compact_count(*first), compact_count(*at_minimum)
    )]
    TooCoarse {
        /// The scene in a few words ("R1/R2 = 5", or the indenter's description).
        scene: String,
        /// Elements along x.
        nx: usize,
        /// Elements across the first contact's minor axis.
        first: f64,
        /// Predicted elements across the minor axis at the force minimum.
        at_minimum: f64,
        /// The grid that resolves it, or what else to change.
        advice: String,
    },
    /// A scale of the problem is not a number the backend can hold.
    #[error(
        "{quantity} = {} is out of the range the {precision} arithmetic holds safely \
         [{}, {}]: {advice}",
        compact(*value), compact(range.0), compact(range.1)
    )]
    Scale {
        /// The quantity, with its unit.
        quantity: &'static str,
        /// Its value.
        value: f64,
        /// "f64" or "f32".
        precision: &'static str,
        /// The range accepted.
        range: (f64, f64),
        /// What to change.
        advice: String,
    },
}

/// A count of elements for messages: one decimal.
fn compact_count(v: f64) -> String {
    format!("{:.1}", v)
}
