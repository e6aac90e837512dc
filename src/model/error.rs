//! An invalid model choice, named by the parameter that sets it.

use super::limits::{
    MAX_GRID, MIN_ELEMENTS_AT_MINIMUM, MIN_ELEMENTS_FIRST_CONTACT, MIN_GRID,
    MIN_MAP_SPACINGS_AT_MINIMUM,
};
use crate::params::{Spec, GRID, HEIGHT_MAP, SPACING};
use crate::text::compact;
use thiserror::Error;

/// An invalid model choice, named by the parameter that sets it (its [`Spec`], which each
/// front end words).
#[derive(Debug, Error, PartialEq)]
pub enum ModelError {
    /// A grid side that is not a power of two in [[`MIN_GRID`], [`MAX_GRID`]].
    #[error("{param} = {value} is invalid: the grid must be a power of two from {MIN_GRID} to {MAX_GRID} (e.g. 64, 128, 256, 512)")]
    Grid {
        /// The parameter.
        param: &'static Spec,
        /// The value given.
        value: usize,
    },
    /// Any other out-of-range value.
    #[error("{param} = {value} is invalid: {expected}")]
    Invalid {
        /// The parameter.
        param: &'static Spec,
        /// The value given, as text.
        value: String,
        /// What is accepted, and what to change.
        expected: String,
    },
    /// The grid resolves the scene's contact by too few elements.
    #[error(
        "{GRID} {nx} is too coarse for this scene ({scene}): the first contact spans \
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
    /// A height map too coarse for the contact it must resolve: too few map spacings across
    /// the contact's minor axis at the force minimum.
    #[error(
        "{HEIGHT_MAP}: the {map} is too coarse for the contact it must resolve: at the force \
         minimum the contact is expected to span {} map spacings across its minor axis \
         (2b ≈ {}; at least {MIN_MAP_SPACINGS_AT_MINIMUM} are needed, or the solver works on \
         the map's flat facets instead of the surface's shape and its answer is wrong); give a \
         map of {SPACING} {} or finer over the same area, or a scene whose contact is larger \
         (the contact scales as c_r = (9π Re² Δγ / (4E*))^(1/3), here {}: a larger Δγ / E*)",
        compact_count(*at_minimum), compact(*width), compact(*needed_spacing), compact(*c_r)
    )]
    MapTooCoarse {
        /// The map in words (its file, nodes and spacing).
        map: String,
        /// Predicted map spacings across the minor axis at the force minimum.
        at_minimum: f64,
        /// The predicted width 2b there (length).
        width: f64,
        /// The spacing that would resolve it (length).
        needed_spacing: f64,
        /// The contact length scale c_r (length).
        c_r: f64,
    },
    /// A height map on a window too small, in map spacings, for any contact it holds to be
    /// resolved.
    #[error(
        "{HEIGHT_MAP}: the {map} is too coarse for any contact it can hold: the whole window \
         spans {} map spacings across (its mean diameter 2√(A/π) ≈ {}), and the contact at the \
         force minimum spans fewer; at least {MIN_MAP_SPACINGS_AT_MINIMUM} are needed there, or \
         the solver works on the map's flat facets instead of the surface's shape and its \
         answer is wrong: give a map of {SPACING} {} or finer over the same area, or a larger \
         map",
        compact_count(*across), compact(*width), compact(*needed_spacing)
    )]
    WindowMapTooCoarse {
        /// The map in words (its file, nodes and spacing).
        map: String,
        /// Map spacings across the window's mean diameter.
        across: f64,
        /// The window's mean diameter 2√(A/π) (length).
        width: f64,
        /// The spacing that would give it the map spacings needed (length).
        needed_spacing: f64,
    },
    /// An environment variable's value cannot be used (`JKRBEM_MEMORY_LIMIT`).
    #[error("{variable} = {value} is invalid: {expected}")]
    Environment {
        /// The variable.
        variable: &'static str,
        /// The value given, as text.
        value: String,
        /// What is accepted, and what to change.
        expected: String,
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
