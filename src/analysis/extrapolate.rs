//! Extrapolation of a grid-dependent result to Δx → 0 (physics §7: the mesh-dependent criterion
//! converges at first order in Δx).

use serde::Serialize;

/// A result extrapolated to Δx → 0 from runs on successively finer grids.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Extrapolated {
    /// First-order estimate from the two finest grids: v_f + (v_f − v_c)·Δx_f/(Δx_c − Δx_f).
    pub value: f64,
    /// Error bar: |value − the same estimate from the next coarser pair| (0 with two grids,
    /// where no spread can be measured).
    pub error_bar: f64,
    /// Observed order p of convergence from three grids, log(|v1 − v2|/|v2 − v3|)/log(h1/h2)
    /// for equal refinement ratios (None with two grids or no monotone convergence).
    pub observed_order: Option<f64>,
    /// The value on the finest grid.
    pub finest: f64,
}

/// Extrapolate `values` computed at element sizes `dx` (any consistent unit, strictly
/// decreasing, at least two). Returns None for fewer than two points or non-decreasing Δx.
pub fn extrapolate_first_order(dx: &[f64], values: &[f64]) -> Option<Extrapolated> {
    let n = dx.len();
    if n < 2
        || values.len() != n
        || dx
            .windows(2)
            .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Less))
    {
        return None;
    }
    let pair = |c: usize, f: usize| values[f] + (values[f] - values[c]) * dx[f] / (dx[c] - dx[f]);
    let value = pair(n - 2, n - 1);
    let error_bar = if n >= 3 {
        (value - pair(n - 3, n - 2)).abs()
    } else {
        0.0
    };
    let observed_order = (n >= 3).then(|| {
        let (d1, d2) = (values[n - 3] - values[n - 2], values[n - 2] - values[n - 1]);
        let r = dx[n - 3] / dx[n - 2];
        (d1 / d2 > 0.0).then(|| (d1 / d2).ln() / r.ln())
    });
    Some(Extrapolated {
        value,
        error_bar,
        observed_order: observed_order.flatten(),
        finest: values[n - 1],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_first_order_law_is_extrapolated_exactly() {
        let dx = [0.4, 0.2, 0.1];
        let v: Vec<f64> = dx.iter().map(|h| -0.5 + 0.3 * h).collect();
        let e = extrapolate_first_order(&dx, &v).unwrap();
        assert!((e.value + 0.5).abs() < 1e-14);
        assert!(e.error_bar < 1e-14);
        assert!((e.observed_order.unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_second_order_term_shows_in_the_error_bar_and_the_order() {
        let dx = [0.4, 0.2, 0.1];
        let v: Vec<f64> = dx.iter().map(|h| 1.0 + h + 2.0 * h * h).collect();
        let e = extrapolate_first_order(&dx, &v).unwrap();
        // Pair (0.2, 0.1) leaves −2·h_f·h_c = −0.04; pair (0.4, 0.2) leaves −0.16.
        assert!((e.value - 0.96).abs() < 1e-12);
        assert!((e.error_bar - 0.12).abs() < 1e-12);
        let p = e.observed_order.unwrap();
        assert!(p > 1.0 && p < 2.0, "{p}");
        assert!(extrapolate_first_order(&[0.1, 0.2], &[1.0, 2.0]).is_none());
        assert!(extrapolate_first_order(&[0.1], &[1.0]).is_none());
    }
}
