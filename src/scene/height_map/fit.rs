//! Local quadratic fits to a height map: [`QuadraticFit`], its principal
//! radii, and the Givens-rotation least squares behind
//! [`HeightMap::curvature_fit`].

use super::{HeightMap, MAX_NODES};

/// Relative size below which a diagonal entry of the fit's triangular factor
/// is treated as zero (dimensionless).
const FIT_RANK_TOLERANCE: f64 = 1e-10;

/// A local quadratic model of a surface,
/// `h ≈ c0 + gx x + gy y + ½ (kxx x² + 2 kxy x y + kyy y²)`, from
/// [`HeightMap::curvature_fit`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraticFit {
    /// Height at the fit's origin (length).
    pub c0: f64,
    /// Slope along x at the origin (dimensionless).
    pub gx: f64,
    /// Slope along y at the origin (dimensionless).
    pub gy: f64,
    /// Curvature ∂²h/∂x² (1/length).
    pub kxx: f64,
    /// Mixed curvature ∂²h/∂x∂y (1/length).
    pub kxy: f64,
    /// Curvature ∂²h/∂y² (1/length).
    pub kyy: f64,
}

impl QuadraticFit {
    /// Principal radii of curvature `(R1, R2)` (length) with `R1 >= R2`: the
    /// reciprocals of the eigenvalues of `[[kxx, kxy], [kxy, kyy]]`.
    ///
    /// Returns `None` unless both eigenvalues are positive (a locally convex
    /// indenter tip) and both radii are finite.
    pub fn principal_radii(&self) -> Option<(f64, f64)> {
        let mean = 0.5 * (self.kxx + self.kyy);
        let half_difference = 0.5 * (self.kxx - self.kyy);
        let largest = mean + half_difference.hypot(self.kxy);
        if largest.is_nan() || largest <= 0.0 {
            return None;
        }
        // The smaller root from the determinant avoids cancellation in
        // `mean - hypot(...)` when the eigenvalues differ greatly.
        let smallest = (self.kxx * self.kyy - self.kxy * self.kxy) / largest;
        if smallest.is_nan() || smallest <= 0.0 {
            return None;
        }
        let (a, b) = (1.0 / smallest, 1.0 / largest);
        let (r1, r2) = if a >= b { (a, b) } else { (b, a) };
        (r1.is_finite() && r2.is_finite()).then_some((r1, r2))
    }
}

/// Fits the quadratic model around the lowest node of `map`, using the nodes
/// within `radius` (length) of it: the work behind
/// [`HeightMap::curvature_fit`], whose documentation gives the model, the
/// coordinates and when `None` is returned.
pub(super) fn curvature_fit(map: &HeightMap, radius: f64) -> Option<QuadraticFit> {
    if radius.is_nan() || radius <= 0.0 {
        return None;
    }
    let (li, lj) = map.lowest_node();
    // Nodes more than `reach` lattice steps away along an axis are outside.
    let reach = (radius / map.spacing).floor().min(MAX_NODES as f64) as usize;
    let i_lo = li.saturating_sub(reach);
    let i_hi = li.saturating_add(reach).min(map.nx - 1);
    let j_lo = lj.saturating_sub(reach);
    let j_hi = lj.saturating_add(reach).min(map.ny - 1);
    // Coordinates are divided by `scale` (length) to keep the columns of
    // the least-squares problem comparable in size.
    let diagonal =
        HeightMap::half_span(map.nx).hypot(HeightMap::half_span(map.ny)) * 2.0 * map.spacing;
    let scale = radius.min(diagonal);
    let radius_sq = radius * radius;
    let mut fit = LeastSquares6::default();
    for j in j_lo..=j_hi {
        let dy = (j as f64 - lj as f64) * map.spacing;
        for i in i_lo..=i_hi {
            let dx = (i as f64 - li as f64) * map.spacing;
            if dx * dx + dy * dy > radius_sq {
                continue;
            }
            let h = map.heights.get(j * map.nx + i)? - map.min;
            let (u, v) = (dx / scale, dy / scale);
            fit.add([1.0, u, v, 0.5 * u * u, u * v, 0.5 * v * v], h);
        }
    }
    if fit.rows < 6 {
        return None;
    }
    let [c0, gx, gy, kxx, kxy, kyy] = fit.solve()?;
    let scale_sq = scale * scale;
    let result = QuadraticFit {
        c0: c0 + map.min,
        gx: gx / scale,
        gy: gy / scale,
        kxx: kxx / scale_sq,
        kxy: kxy / scale_sq,
        kyy: kyy / scale_sq,
    };
    let values = [
        result.c0, result.gx, result.gy, result.kxx, result.kxy, result.kyy,
    ];
    values.iter().all(|c| c.is_finite()).then_some(result)
}

/// Linear least squares with six unknowns, accumulated one row at a time by
/// Givens rotations into an upper-triangular factor `r` and rotated
/// right-hand side `z`, in constant memory.
#[derive(Debug, Default)]
struct LeastSquares6 {
    /// Upper-triangular factor of the design matrix.
    r: [[f64; 6]; 6],
    /// Rotated right-hand side.
    z: [f64; 6],
    /// Squared Euclidean norm of each design-matrix column.
    column_norm_sq: [f64; 6],
    /// Number of rows added, a count.
    rows: usize,
}

impl LeastSquares6 {
    /// Adds the equation `a · c = b`.
    fn add(&mut self, mut a: [f64; 6], mut b: f64) {
        self.rows += 1;
        for (norm, value) in self.column_norm_sq.iter_mut().zip(a.iter()) {
            *norm += value * value;
        }
        for (k, (r_row, z_k)) in self.r.iter_mut().zip(self.z.iter_mut()).enumerate() {
            let (Some(&a_k), Some(&r_kk)) = (a.get(k), r_row.get(k)) else {
                continue;
            };
            if a_k == 0.0 {
                continue;
            }
            let norm = r_kk.hypot(a_k);
            let (c, s) = (r_kk / norm, a_k / norm);
            for (r_value, a_value) in r_row.iter_mut().zip(a.iter_mut()).skip(k) {
                let (rv, av) = (*r_value, *a_value);
                *r_value = c * rv + s * av;
                *a_value = c * av - s * rv;
            }
            let zv = *z_k;
            *z_k = c * zv + s * b;
            b = c * b - s * zv;
        }
    }

    /// Back-substitutes for the coefficients, or `None` if the problem is
    /// rank-deficient.
    fn solve(&self) -> Option<[f64; 6]> {
        for (k, r_row) in self.r.iter().enumerate() {
            let r_kk = r_row.get(k).copied().unwrap_or(0.0).abs();
            let column = self.column_norm_sq.get(k).copied().unwrap_or(0.0).sqrt();
            if r_kk.is_nan() || r_kk <= FIT_RANK_TOLERANCE * column {
                return None;
            }
        }
        let mut solution = [0.0; 6];
        for k in (0..6).rev() {
            let r_row = self.r.get(k)?;
            let mut sum = *self.z.get(k)?;
            for (r_value, known) in r_row.iter().zip(solution.iter()).skip(k + 1) {
                sum -= r_value * known;
            }
            let value = sum / r_row.get(k)?;
            *solution.get_mut(k)? = value;
        }
        solution.iter().all(|c| c.is_finite()).then_some(solution)
    }
}

#[cfg(test)]
mod tests {
    use super::super::HeightMap;
    use super::QuadraticFit;

    fn ellipsoid(angle: f64) -> HeightMap {
        let (n, spacing) = (64, 0.05);
        let (sin, cos) = angle.sin_cos();
        let mut heights = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                let x = (i as f64 - 31.5) * spacing;
                let y = (j as f64 - 31.5) * spacing;
                let u = cos * x + sin * y;
                let v = -sin * x + cos * y;
                heights.push(u * u / (2.0 * 5.0) + v * v / (2.0 * 1.0) + 0.3);
            }
        }
        HeightMap::new(n, n, spacing, heights).unwrap()
    }

    #[test]
    fn curvature_fit_recovers_ellipsoid_radii() {
        for angle in [0.0, 30.0_f64.to_radians()] {
            let map = ellipsoid(angle);
            let fit = map.curvature_fit(0.8).unwrap();
            let (r1, r2) = fit.principal_radii().unwrap();
            assert!((r1 - 5.0).abs() < 1e-9, "angle {angle}: R1 = {r1}");
            assert!((r2 - 1.0).abs() < 1e-9, "angle {angle}: R2 = {r2}");
            if angle == 0.0 {
                assert!((fit.kxx - 0.2).abs() < 1e-9 && (fit.kyy - 1.0).abs() < 1e-9);
                assert!(fit.kxy.abs() < 1e-9);
                // Lowest node (first of four ties) is at (-0.025, -0.025).
                let (x0, y0) = map.lowest_point();
                assert!((x0 + 0.025).abs() < 1e-15 && (y0 + 0.025).abs() < 1e-15);
                assert!((fit.gx - x0 / 5.0).abs() < 1e-9 && (fit.gy - y0).abs() < 1e-9);
                assert!((fit.c0 - map.min_height()).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn curvature_fit_refuses_too_few_nodes_and_saddles() {
        let map = ellipsoid(0.0);
        assert!(map.curvature_fit(0.05).is_none()); // 5 nodes
        assert!(map.curvature_fit(0.0).is_none());
        assert!(map.curvature_fit(-1.0).is_none());
        assert!(map.curvature_fit(f64::NAN).is_none());
        assert!(map.curvature_fit(f64::INFINITY).is_some());
        let saddle = QuadraticFit {
            c0: 0.0,
            gx: 0.0,
            gy: 0.0,
            kxx: 1.0,
            kxy: 0.0,
            kyy: -1.0,
        };
        assert_eq!(saddle.principal_radii(), None);
        let tilted = QuadraticFit {
            kxx: 0.6,
            kxy: 0.2,
            kyy: 0.6,
            ..saddle
        };
        let (r1, r2) = tilted.principal_radii().unwrap();
        assert!((r1 - 2.5).abs() < 1e-12 && (r2 - 1.25).abs() < 1e-12);
    }
}
