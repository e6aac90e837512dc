//! Small dense linear least squares (Householder QR) and a deterministic 1-D minimiser, the
//! numerical core of the fits in [`super::fit`].

/// Columns whose component orthogonal to the earlier ones is below this fraction of their
/// norm count as dependent (dimensionless). Coefficients of nearer-dependent columns would
/// carry relative errors above ~1e-6.
const RANK_TOLERANCE: f64 = 1e-10;

/// Coefficients β (one per column) minimising ‖y − Σ_k β_k cols[k]‖₂, or `None` when the
/// columns are (numerically) linearly dependent or not finite.
///
/// Householder QR of the column-equilibrated n × p matrix: each column is scaled to unit
/// norm first, so |R_kk| is the sine of the angle between column k and the span of the
/// earlier ones and the rank test is scale-free. Solving through QR rather than the normal
/// equations keeps the error proportional to the condition number, not to its square.
pub(super) fn least_squares(cols: &[Vec<f64>], y: &[f64]) -> Option<Vec<f64>> {
    let (n, p) = (y.len(), cols.len());
    if n < p || cols.iter().any(|c| c.len() != n) {
        return None;
    }
    let scale: Vec<f64> = cols.iter().map(|c| norm(c)).collect();
    if scale.iter().any(|s| !(s.is_finite() && *s > 0.0)) {
        return None;
    }
    let mut a: Vec<Vec<f64>> = cols
        .iter()
        .zip(&scale)
        .map(|(c, s)| c.iter().map(|v| v / s).collect())
        .collect();
    let mut b = y.to_vec();
    let mut r_diag = vec![0.0; p];
    for k in 0..p {
        let len = norm(&a[k][k..]);
        if len.is_nan() || len <= RANK_TOLERANCE {
            return None;
        }
        // Reflect a[k][k..] onto −sign(a_kk)·len·e1 (the sign that avoids cancellation).
        let alpha = if a[k][k] >= 0.0 { -len } else { len };
        let mut v = a[k][k..].to_vec();
        v[0] -= alpha;
        let v_sq = dot(&v, &v);
        for col in a.iter_mut().skip(k + 1) {
            reflect(&v, v_sq, &mut col[k..]);
        }
        reflect(&v, v_sq, &mut b[k..]);
        r_diag[k] = alpha;
        a[k][k] = alpha;
    }
    // Back substitution R β' = (Qᵀ y)[..p], then undo the column scaling.
    let mut beta = vec![0.0; p];
    for k in (0..p).rev() {
        let tail: f64 = (k + 1..p).map(|j| a[j][k] * beta[j]).sum();
        beta[k] = (b[k] - tail) / r_diag[k];
    }
    let beta: Vec<f64> = beta.iter().zip(&scale).map(|(c, s)| c / s).collect();
    beta.iter().all(|c| c.is_finite()).then_some(beta)
}

/// x ← (I − 2 v vᵀ/(vᵀv)) x.
fn reflect(v: &[f64], v_sq: f64, x: &mut [f64]) {
    let s = 2.0 * dot(v, x) / v_sq;
    for (xi, vi) in x.iter_mut().zip(v) {
        *xi -= s * vi;
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Euclidean norm, scaled by the largest entry so that it neither overflows nor underflows.
fn norm(a: &[f64]) -> f64 {
    let m = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * a.iter().map(|v| (v / m) * (v / m)).sum::<f64>().sqrt()
}

/// Where a 1-D search ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Minimum {
    /// The minimiser.
    pub x: f64,
    /// The value there.
    pub value: f64,
    /// Whether the minimiser lies at an end of the searched interval.
    pub at_bound: bool,
}

/// Minimiser of `f` over [lo, hi]: a scan of `n_scan` + 1 evenly spaced points (ends
/// included; NaN counts as +∞) picks the best, golden-section search then narrows the
/// bracket of its two neighbours to below `tol`. Deterministic; finds the global minimum
/// when the minima of `f` are further apart than the scan step.
pub(super) fn minimise(
    f: impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    n_scan: usize,
    tol: f64,
) -> Minimum {
    let h = (hi - lo) / n_scan as f64;
    let at = |i: usize| if i == n_scan { hi } else { lo + i as f64 * h };
    let value = |x: f64| {
        let v = f(x);
        if v.is_nan() {
            f64::INFINITY
        } else {
            v
        }
    };
    let (mut best_i, mut best) = (0, f64::INFINITY);
    for i in 0..=n_scan {
        let v = value(at(i));
        if v < best {
            (best_i, best) = (i, v);
        }
    }
    let (mut a, mut b) = (at(best_i.saturating_sub(1)), at((best_i + 1).min(n_scan)));
    let r = (5f64.sqrt() - 1.0) / 2.0; // inverse golden ratio (√5 − 1)/2
    let (mut x1, mut x2) = (b - r * (b - a), a + r * (b - a));
    let (mut f1, mut f2) = (value(x1), value(x2));
    while b - a > tol {
        if f1 <= f2 {
            (b, x2, f2) = (x2, x1, f1);
            x1 = b - r * (b - a);
            f1 = value(x1);
        } else {
            (a, x1, f1) = (x1, x2, f2);
            x2 = a + r * (b - a);
            f2 = value(x2);
        }
    }
    let (mut x, mut v) = if f1 <= f2 { (x1, f1) } else { (x2, f2) };
    // The ends themselves are never golden-section points: keep them if they are better.
    if best < v {
        (x, v) = (at(best_i), best);
    }
    Minimum {
        x,
        value: v,
        at_bound: x - lo <= 2.0 * tol || hi - x <= 2.0 * tol,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_squares_solves_an_exact_three_column_system() {
        let x: Vec<f64> = (0..7).map(|i| 0.3 + 0.4 * i as f64).collect();
        let cols = vec![
            x.iter().map(|v| v * v).collect(),
            x.clone(),
            vec![1.0; x.len()],
        ];
        let y: Vec<f64> = x.iter().map(|v| 2.5 * v * v - 1.25 * v + 1e3).collect();
        let beta = least_squares(&cols, &y).unwrap();
        for (got, want) in beta.iter().zip([2.5, -1.25, 1e3]) {
            assert!((got - want).abs() < 1e-10 * want.abs(), "{beta:?}");
        }
    }

    #[test]
    fn least_squares_residual_is_orthogonal_to_the_columns() {
        let x: Vec<f64> = (1..=9).map(f64::from).collect();
        let cols = vec![x.clone(), vec![1.0; 9]];
        let y: Vec<f64> = x.iter().map(|v| v.sin() + 0.1 * v).collect();
        let beta = least_squares(&cols, &y).unwrap();
        let r: Vec<f64> = (0..9).map(|i| y[i] - beta[0] * x[i] - beta[1]).collect();
        for c in &cols {
            assert!(dot(c, &r).abs() < 1e-12, "{}", dot(c, &r));
        }
    }

    #[test]
    fn least_squares_refuses_dependent_columns() {
        let x = vec![1.0, 2.0, 3.0];
        assert!(least_squares(&[x.clone(), x.iter().map(|v| 3.0 * v).collect()], &x).is_none());
        assert!(least_squares(&[vec![0.0; 3]], &x).is_none());
        assert!(least_squares(&[x.clone(), x.clone(), x.clone(), x.clone()], &x).is_none());
    }

    #[test]
    fn minimise_finds_an_interior_vertex_and_flags_an_end() {
        let m = minimise(|x| (x - 0.3137).powi(2), -1.0, 2.0, 30, 1e-12);
        assert!((m.x - 0.3137).abs() < 1e-7 && !m.at_bound, "{m:?}");
        // A V-shaped minimum is found to the tolerance, not to its square root.
        let m = minimise(|x| (x - 1.5).abs(), 0.5, 2.9, 240, 1e-12);
        assert!((m.x - 1.5).abs() < 1e-11, "{m:?}");
        let m = minimise(|x| x, 0.5, 2.9, 24, 1e-12);
        assert!(m.x == 0.5 && m.at_bound, "{m:?}");
    }
}
