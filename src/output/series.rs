//! Point series computed outside `output` (closed forms, fitted laws, a run's branch), as the
//! charts receive them: `output` only draws what it is given.

/// A named series of (x, y) points: a closed form beside a run ("JKR", "JG").
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Named {
    /// The name shown in the legend.
    pub name: String,
    /// The points, in the chart's units.
    pub points: Vec<(f64, f64)>,
}

/// A power law y = k1·x^k2 + k3 fitted to a chart's points, and the points of it to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct LawCurve {
    /// (k1, k2, k3): k1 and k3 in the units of y, k2 dimensionless.
    pub k: [f64; 3],
    /// R² of the fit in y (dimensionless).
    pub r_squared: f64,
    /// (x, law(x)) along the chart's range.
    pub points: Vec<(f64, f64)>,
}
