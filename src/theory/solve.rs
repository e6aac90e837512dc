//! Scalar bisection and minimisation used to invert and search the theory branches.

/// Bisection on `above(x)` = "the sought point lies above x" (true below it, false above it;
/// NaN-producing points should answer true/false consistently). Narrows [lo, hi] to adjacent
/// floats or 200 halvings and returns the final bracket.
pub(super) fn bisect(mut lo: f64, mut hi: f64, above: impl Fn(f64) -> bool) -> (f64, f64) {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if above(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo, hi)
}

/// Minimiser of `f` over s ∈ (0, 1): a scan of `n_grid` interior points (NaN counts as +∞)
/// brackets the minimum, golden-section search then narrows the bracket below `tol`.
pub(super) fn minimise_on_unit(f: impl Fn(f64) -> f64, n_grid: usize, tol: f64) -> f64 {
    let step = 1.0 / n_grid as f64;
    let (mut best_i, mut best) = (1, f64::INFINITY);
    for i in 1..n_grid {
        let v = f(i as f64 * step);
        if v < best {
            (best_i, best) = (i, v);
        }
    }
    let (mut lo, mut hi) = ((best_i - 1) as f64 * step, (best_i + 1) as f64 * step);
    let r = (5f64.sqrt() - 1.0) / 2.0; // inverse golden ratio (√5 − 1)/2
    let (mut x1, mut x2) = (hi - r * (hi - lo), lo + r * (hi - lo));
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..200 {
        if hi - lo <= tol {
            break;
        }
        if f1 <= f2 {
            (hi, x2, f2) = (x2, x1, f1);
            x1 = hi - r * (hi - lo);
            f1 = f(x1);
        } else {
            (lo, x1, f1) = (x1, x2, f2);
            x2 = lo + r * (hi - lo);
            f2 = f(x2);
        }
    }
    if f1 <= f2 {
        x1
    } else {
        x2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisect_finds_square_root_of_two() {
        let (lo, hi) = bisect(1.0, 2.0, |x| x * x < 2.0);
        assert!((lo - 2f64.sqrt()).abs() < 1e-15 && hi - lo <= 4.0 * f64::EPSILON);
    }

    #[test]
    fn minimise_on_unit_finds_parabola_vertex() {
        let s = minimise_on_unit(|s| (s - 0.3137).powi(2) - 1.0, 64, 1e-12);
        assert!((s - 0.3137).abs() < 1e-7);
    }
}
