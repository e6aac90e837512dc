//! The vocabulary the model and the backends share: what a backend is built from
//! ([`GridSetup`]), how CG is preconditioned and the axes a contact's chords are measured
//! along. The model builds these; the backends take them; neither imports the other for them.

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

/// How the elastic operator's inverse is approximated for preconditioning.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Preconditioner {
    /// No preconditioning: z = r.
    None,
    /// z = P·S·P r with S the half-space stiffness E*|q|/2 applied in Fourier space on the
    /// periodic Nx × Ny grid (an approximate inverse of the influence operator).
    Stiffness,
}

/// The directions of the two chords: the ellipsoid's major axis (cos θ, sin θ) and minor axis
/// (−sin θ, cos θ) in the grid's frame (dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChordAxes {
    /// cos θ.
    pub cos: f64,
    /// sin θ.
    pub sin: f64,
}

impl ChordAxes {
    /// The grid's own axes (θ = 0).
    pub const ALIGNED: ChordAxes = ChordAxes { cos: 1.0, sin: 0.0 };

    /// Whether these are the grid's own axes.
    pub fn is_aligned(&self) -> bool {
        *self == Self::ALIGNED
    }
}
