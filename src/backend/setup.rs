//! What a backend is built from, whatever its kind.

use super::Preconditioner;

/// What a backend is built from: the grid, the element size, the material and the profile.
#[derive(Debug, Clone)]
pub struct GridSetup {
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Element side Δx (length).
    pub dx: f64,
    /// Effective modulus E* (stress).
    pub e_star: f64,
    /// Indenter profile h at element centres (length), row-major nx × ny.
    pub profile: Vec<f64>,
    /// Preconditioner to apply in CG.
    pub preconditioner: Preconditioner,
}
