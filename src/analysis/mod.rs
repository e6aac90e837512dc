//! Analysis of recorded pull-offs for the study (physics §8): least-squares fits of the branch
//! and of coefficients against R1/R2, quarter contours of the contact beside an ellipse, and
//! the crossed-cylinder form of the scene. Pure functions of states, masks and numbers.

pub mod branch;
pub mod branch_limit;
pub mod capture;
pub mod contour;
pub mod convergence;
pub mod crossed;
pub mod estimate;
pub mod extrapolate;
pub mod fields;
pub mod fit;
pub mod fronts;
pub mod generic_limit;
pub mod jkr_sphere;
pub mod line_fit;
mod lstsq;
pub mod report;
pub mod study_fits;

pub use branch::{adhesive_branch, BranchPoint};
pub use contour::{ellipse_departure, quarter_contour, ContourError, Departure, Point};
pub use crossed::CrossedCylinders;
pub use fit::{
    fit_d_of_c, fit_f_of_c, fit_power_law, FitError, FitQuality, LinearFit2, PowerFit, PowerLawFit,
};
