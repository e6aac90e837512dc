//! A straight line y = a + b·x fitted to points with known standard deviations, with a
//! Gaussian prior on the slope b (weighted least squares; the prior is one more observation).
//! With one point the prior alone fixes the slope; with several the data refine it.

/// One observation: abscissa, value and its standard deviation (same unit as the value, > 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// The abscissa x.
    pub x: f64,
    /// The observed value y.
    pub y: f64,
    /// Standard deviation of y (> 0).
    pub sd: f64,
}

/// A Gaussian prior on the slope: its mean and standard deviation (> 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlopePrior {
    /// Prior mean of the slope b.
    pub mean: f64,
    /// Prior standard deviation of b (> 0).
    pub sd: f64,
}

/// The fitted line and the intercept's standard deviation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineFit {
    /// Intercept a: the value at x = 0.
    pub intercept: f64,
    /// Standard deviation of the intercept, from the points' and the prior's deviations only.
    pub intercept_sd: f64,
    /// Slope b.
    pub slope: f64,
    /// Standard deviation of the slope, from the points' and the prior's deviations only.
    pub slope_sd: f64,
    /// Covariance of intercept and slope, from the points' and the prior's deviations only.
    pub covariance: f64,
    /// χ² of the fit (points and prior), dimensionless.
    pub chi2: f64,
    /// Degrees of freedom: points (+ 1 with a prior on the slope) − 2.
    pub dof: usize,
}

impl LineFit {
    /// √(χ²/dof) where the points scatter more than their deviations say (the Birge ratio),
    /// else 1 (never below).
    pub fn birge(&self) -> f64 {
        if self.dof > 0 {
            (self.chi2 / self.dof as f64).sqrt().max(1.0)
        } else {
            1.0
        }
    }

    /// The intercept's standard deviation scaled up by the [`LineFit::birge`] ratio.
    pub fn intercept_sd_from_residuals(&self) -> f64 {
        self.intercept_sd * self.birge()
    }
}

/// The 90 % quantile of the Birge ratio √(χ²/dof) of a fit with `dof` degrees of freedom
/// whose points scatter exactly as their deviations say (dimensionless; 1 for `dof` 0, where
/// no ratio is formed): one fit in ten widens its interval by more than this. From the χ²
/// distribution's 90 % quantiles (tabled to 8 degrees of freedom, Wilson–Hilferty beyond).
pub fn birge_quantile_90(dof: usize) -> f64 {
    const CHI2_90: [f64; 8] = [
        2.705_54, 4.605_17, 6.251_39, 7.779_44, 9.236_36, 10.644_64, 12.017_04, 13.361_57,
    ];
    let chi2 = match dof {
        0 => return 1.0,
        1..=8 => CHI2_90[dof - 1],
        _ => {
            let v = dof as f64;
            let h = 2.0 / (9.0 * v);
            v * (1.0 - h + 1.281_552 * h.sqrt()).powi(3)
        }
    };
    (chi2 / dof as f64).sqrt().max(1.0)
}

/// Fit y = a + b·x to `points` with the slope's `prior`. `None` if there are no points, a
/// deviation is not positive and finite, or the system is singular.
pub fn fit_line(points: &[Point], prior: SlopePrior) -> Option<LineFit> {
    if !(prior.sd > 0.0 && prior.sd.is_finite() && prior.mean.is_finite()) {
        return None;
    }
    fit(points, Some(prior))
}

/// Fit y = a + b·x to `points` with no prior on the slope (at least two distinct x). `None`
/// if there are too few points, a deviation is not positive and finite, or the system is
/// singular.
pub fn fit_free_line(points: &[Point]) -> Option<LineFit> {
    fit(points, None)
}

/// The weighted least-squares line, with the slope's prior as one more observation if given.
fn fit(points: &[Point], prior: Option<SlopePrior>) -> Option<LineFit> {
    if points.is_empty()
        || points
            .iter()
            .any(|p| !(p.sd > 0.0 && p.sd.is_finite() && p.x.is_finite() && p.y.is_finite()))
    {
        return None;
    }
    // Normal equations [[s, sx], [sx, sxx + 1/σb²]] (a, b) = (sy, sxy + μb/σb²).
    let (mut s, mut sx, mut sxx, mut sy, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for p in points {
        let w = 1.0 / (p.sd * p.sd);
        s += w;
        sx += w * p.x;
        sxx += w * p.x * p.x;
        sy += w * p.y;
        sxy += w * p.x * p.y;
    }
    let (mean, wb) = prior.map_or((0.0, 0.0), |p| (p.mean, 1.0 / (p.sd * p.sd)));
    let (m11, m12, m22) = (s, sx, sxx + wb);
    let det = m11 * m22 - m12 * m12;
    if !(det > 0.0 && det.is_finite()) {
        return None;
    }
    let (r1, r2) = (sy, sxy + mean * wb);
    let a = (m22 * r1 - m12 * r2) / det;
    let b = (m11 * r2 - m12 * r1) / det;
    let chi2 = points
        .iter()
        .map(|p| ((p.y - a - b * p.x) / p.sd).powi(2))
        .sum::<f64>()
        + prior.map_or(0.0, |p| ((b - p.mean) / p.sd).powi(2));
    Some(LineFit {
        intercept: a,
        intercept_sd: (m22 / det).sqrt(),
        slope: b,
        slope_sd: (m11 / det).sqrt(),
        covariance: -m12 / det,
        chi2,
        dof: (points.len() + usize::from(prior.is_some())).saturating_sub(2),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_point_takes_its_slope_from_the_prior() {
        let p = [Point {
            x: 0.1,
            y: 1.3,
            sd: 0.01,
        }];
        let f = fit_line(&p, SlopePrior { mean: 3.0, sd: 0.5 }).unwrap();
        assert!((f.intercept - 1.0).abs() < 1e-12);
        // var = sd² + x²·σb²
        assert!((f.intercept_sd - (0.01f64.powi(2) + 0.05f64.powi(2)).sqrt()).abs() < 1e-12);
        assert_eq!(f.dof, 0);
        assert!(f.chi2 < 1e-20);
    }

    #[test]
    fn exact_points_recover_the_line_whatever_the_prior() {
        let p: Vec<Point> = [0.1, 0.05, 0.025]
            .iter()
            .map(|&x| Point {
                x,
                y: 0.5 + 1.6 * x,
                sd: 1e-9,
            })
            .collect();
        let f = fit_line(&p, SlopePrior { mean: 0.0, sd: 1.0 }).unwrap();
        assert!((f.intercept - 0.5).abs() < 1e-9, "{f:?}");
        assert!((f.slope - 1.6).abs() < 1e-6, "{f:?}");
    }

    #[test]
    fn the_birge_quantile_follows_the_chi_squared_distribution() {
        // √(χ²_0.9/dof): 1.645 (the two-sided 90 % normal point) for one degree of freedom.
        assert!((birge_quantile_90(1) - 1.644_85).abs() < 1e-4);
        assert_eq!(birge_quantile_90(0), 1.0);
        // Wilson–Hilferty beyond the table: χ²_0.9 = 14.684 for 9, 28.412 for 20.
        assert!((birge_quantile_90(9) - (14.684f64 / 9.0).sqrt()).abs() < 2e-3);
        assert!((birge_quantile_90(20) - (28.412f64 / 20.0).sqrt()).abs() < 2e-3);
        // More degrees of freedom, a tighter bound, towards 1.
        for dof in 1..40 {
            assert!(birge_quantile_90(dof + 1) < birge_quantile_90(dof));
            assert!(birge_quantile_90(dof) > 1.0);
        }
    }

    #[test]
    fn inconsistent_points_widen_the_interval_by_the_birge_ratio() {
        let p = [
            Point {
                x: 0.1,
                y: 1.0,
                sd: 0.001,
            },
            Point {
                x: 0.05,
                y: 0.9,
                sd: 0.001,
            },
            Point {
                x: 0.025,
                y: 1.0,
                sd: 0.001,
            },
        ];
        let f = fit_line(
            &p,
            SlopePrior {
                mean: 0.0,
                sd: 10.0,
            },
        )
        .unwrap();
        assert!(
            f.intercept_sd_from_residuals() > 10.0 * f.intercept_sd,
            "{f:?}"
        );
    }

    #[test]
    fn bad_input_is_none() {
        let prior = SlopePrior { mean: 0.0, sd: 1.0 };
        assert!(fit_line(&[], prior).is_none());
        let bad = Point {
            x: 0.1,
            y: f64::NAN,
            sd: 0.1,
        };
        assert!(fit_line(&[bad], prior).is_none());
    }
}
