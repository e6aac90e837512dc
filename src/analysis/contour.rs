//! The boundary of a contact, one quadrant, and how far it departs from an ellipse
//! (physics §8.3).

use crate::model::Model;
use thiserror::Error;

/// A contact mask or ellipse that cannot be traced or compared.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ContourError {
    /// The mask does not have nx·ny entries.
    #[error("the mask has {len} entries but the grid is {nx} × {ny}: pass the grid's own mask")]
    MaskSize {
        /// Entries in the mask.
        len: usize,
        /// Elements along x.
        nx: usize,
        /// Elements along y.
        ny: usize,
    },
    /// A grid side that is zero or odd, so the centre is not between two elements.
    #[error("the grid {nx} × {ny} must have even sides ≥ 2: its centre lies between the middle elements")]
    OddGrid {
        /// Elements along x.
        nx: usize,
        /// Elements along y.
        ny: usize,
    },
    /// A length that must be positive and finite.
    #[error("{name} = {value} must be a positive finite length")]
    BadLength {
        /// Which length.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// No boundary points to compare.
    #[error("there are no boundary points: the contact does not cover the centre")]
    NoPoints,
}

/// A point in the plane of the contact (x, y in length units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// x (length), along the major axis.
    pub x: f64,
    /// y (length), along the minor axis.
    pub y: f64,
}

/// The boundary of the contact in the quadrant x > 0, y > 0, ordered by polar angle from
/// the x axis to the y axis, for a row-major (x fastest) `nx` × `ny` contact `mask` of square
/// elements of side `dx` (length), centred as in [`Model::x`] and [`Model::y`]: element (i, j)
/// has its centre at ((i + ½ − nx/2)·Δx, (j + ½ − ny/2)·Δx).
///
/// Rows and columns are scanned outwards from the centre lines: for each row j with y_j > 0
/// whose element at x = Δx/2 is in contact, the run of contact from there along +x ends at the
/// outer face of its last element, giving the point (x_face, y_j); for each column with x_i > 0
/// likewise the point (x_i, y_face). Rows resolve the boundary where it is steep (near the
/// x axis), columns where it is flat (near the y axis), and together they sample it about
/// once per element. Faces, not centres, are used because the face is where a rasterised
/// boundary lies to ±Δx/2 without bias, and because the area Δx² per element and the
/// half-axes of [`State`](crate::solver::State) count whole elements too. Contact not
/// connected to the centre lines along a row or column is ignored.
pub fn quarter_contour(
    mask: &[bool],
    nx: usize,
    ny: usize,
    dx: f64,
) -> Result<Vec<Point>, ContourError> {
    if nx == 0 || ny == 0 || nx % 2 == 1 || ny % 2 == 1 {
        return Err(ContourError::OddGrid { nx, ny });
    }
    if mask.len() != nx * ny {
        return Err(ContourError::MaskSize {
            len: mask.len(),
            nx,
            ny,
        });
    }
    if !(dx.is_finite() && dx > 0.0) {
        return Err(ContourError::BadLength {
            name: "dx",
            value: dx,
        });
    }
    let (ci, cj) = (nx / 2, ny / 2);
    let at = |i: usize, j: usize| mask[j * nx + i];
    // Distance (length) from the centre of index `k` of a side of `n` elements.
    let centre = |k: usize, n: usize| (k as f64 + 0.5 - n as f64 / 2.0) * dx;
    // Outer face (length) of a run of `len` contact elements starting at the centre line.
    let face = |len: usize| len as f64 * dx;
    let mut points = Vec::new();
    for j in cj..ny {
        let run = (ci..nx).take_while(|&i| at(i, j)).count();
        if run > 0 {
            points.push(Point {
                x: face(run),
                y: centre(j, ny),
            });
        }
    }
    for i in ci..nx {
        let run = (cj..ny).take_while(|&j| at(i, j)).count();
        if run > 0 {
            points.push(Point {
                x: centre(i, nx),
                y: face(run),
            });
        }
    }
    points.sort_by(|p, q| p.y.atan2(p.x).total_cmp(&q.y.atan2(q.x)));
    Ok(points)
}

/// [`quarter_contour`] of a contact `mask` on `model`'s grid.
pub fn quarter_contour_for(model: &Model, mask: &[bool]) -> Result<Vec<Point>, ContourError> {
    quarter_contour(mask, model.nx, model.ny, model.dx)
}

/// How far a boundary departs from an ellipse, relative to the ellipse's radius at the same
/// polar angle (all dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Departure {
    /// Root mean square of r/r_e − 1 over the points.
    pub rms: f64,
    /// Largest |r/r_e − 1|.
    pub max: f64,
    /// Mean of r/r_e − 1: > 0 where the boundary lies outside the ellipse on average.
    pub mean: f64,
}

/// The departure of `points` from the ellipse x²/a² + y²/b² = 1 with half-axes `a` along x
/// and `b` along y (lengths, positive, in the points' unit): for a point at radius r and polar
/// angle φ, r/r_e(φ) − 1 where r_e(φ) is the ellipse's radius at φ; since r/r_e(φ) =
/// √(x²/a² + y²/b²), this is evaluated as such. A rasterised ellipse departs by O(Δx/b).
pub fn ellipse_departure(points: &[Point], a: f64, b: f64) -> Result<Departure, ContourError> {
    for (name, value) in [("a", a), ("b", b)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(ContourError::BadLength { name, value });
        }
    }
    if points.is_empty() {
        return Err(ContourError::NoPoints);
    }
    let n = points.len() as f64;
    let (mut sum, mut sum_sq, mut max) = (0.0, 0.0, 0.0f64);
    for p in points {
        let dev = (p.x / a).hypot(p.y / b) - 1.0;
        sum += dev;
        sum_sq += dev * dev;
        max = max.max(dev.abs());
    }
    Ok(Departure {
        rms: (sum_sq / n).sqrt(),
        max,
        mean: sum / n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mask of the elements whose centres lie inside the ellipse with half-axes
    /// (a, b) (in elements) on an nx × ny grid of unit elements.
    fn ellipse_mask(nx: usize, ny: usize, a: f64, b: f64) -> Vec<bool> {
        let mut m = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = (
                    i as f64 + 0.5 - nx as f64 / 2.0,
                    j as f64 + 0.5 - ny as f64 / 2.0,
                );
                m.push((x / a).powi(2) + (y / b).powi(2) < 1.0);
            }
        }
        m
    }

    #[test]
    fn rasterised_ellipse_boundary_lies_within_an_element_of_the_ellipse() {
        let (nx, ny, dx) = (128, 64, 0.01);
        let (a, b) = (41.3, 17.6); // in elements
        let pts = quarter_contour(&ellipse_mask(nx, ny, a, b), nx, ny, dx).unwrap();
        // About one point per element of boundary: a + b rows and columns.
        assert!(pts.len() >= 55, "{} points", pts.len());
        let mut last_angle = 0.0;
        for p in &pts {
            assert!(p.x > 0.0 && p.y > 0.0);
            let angle = p.y.atan2(p.x);
            assert!(angle >= last_angle, "not ordered by polar angle");
            last_angle = angle;
            // First-order distance to the ellipse: |F|/|∇F| with F = x²/a² + y²/b² − 1.
            let (ax, bx) = (a * dx, b * dx);
            let f = (p.x / ax).powi(2) + (p.y / bx).powi(2) - 1.0;
            let grad = (2.0 * p.x / (ax * ax)).hypot(2.0 * p.y / (bx * bx));
            assert!(
                f.abs() / grad < dx,
                "{p:?} is {} from the ellipse",
                f.abs() / grad
            );
        }
        let dep = ellipse_departure(&pts, a * dx, b * dx).unwrap();
        println!("ellipse {a} × {b} elements: departure {dep:?}");
        assert!(dep.max < 1.0 / b && dep.rms < 0.5 / b, "{dep:?}");
        assert!(dep.mean.abs() < 0.25 / b, "biased: {dep:?}");
    }

    #[test]
    fn departure_of_a_rasterised_ellipse_shrinks_with_the_element_size() {
        let dep = |scale: f64| {
            let (nx, ny) = ((128.0 * scale) as usize, (64.0 * scale) as usize);
            let (a, b) = (41.3 * scale, 17.6 * scale);
            let pts = quarter_contour(&ellipse_mask(nx, ny, a, b), nx, ny, 1.0 / scale).unwrap();
            ellipse_departure(&pts, a / scale, b / scale).unwrap().rms
        };
        let (coarse, fine) = (dep(1.0), dep(4.0));
        println!("RMS departure: {coarse:.2e} (1×), {fine:.2e} (4×)");
        assert!(fine < 0.5 * coarse, "{coarse} → {fine}");
    }

    #[test]
    fn a_square_contact_departs_clearly_from_its_inscribed_circle() {
        // Elements 12..52 in both directions: a square of half-side 20 about the centre 32.
        let n = 64;
        let side = |k: usize| (12..52).contains(&k);
        let mask: Vec<bool> = (0..n * n).map(|k| side(k % n) && side(k / n)).collect();
        let pts = quarter_contour(&mask, n, n, 1.0).unwrap();
        assert!(pts.iter().all(|p| p.x <= 20.0 && p.y <= 20.0));
        let dep = ellipse_departure(&pts, 20.0, 20.0).unwrap();
        println!("square: departure {dep:?}");
        // The corner lies √2 − 1 ≈ 41 % outside the circle.
        assert!(
            dep.max > 0.35 && dep.rms > 0.1 && dep.mean > 0.05,
            "{dep:?}"
        );
    }

    #[test]
    fn bad_grids_and_axes_are_refused() {
        assert_eq!(
            quarter_contour(&[true; 12], 3, 4, 1.0),
            Err(ContourError::OddGrid { nx: 3, ny: 4 })
        );
        assert!(matches!(
            quarter_contour(&[true; 10], 4, 4, 1.0),
            Err(ContourError::MaskSize { len: 10, .. })
        ));
        assert!(quarter_contour(&[true; 16], 4, 4, f64::NAN).is_err());
        // No contact: no points, and nothing to compare.
        let pts = quarter_contour(&[false; 16], 4, 4, 1.0).unwrap();
        assert_eq!(
            ellipse_departure(&pts, 1.0, 1.0),
            Err(ContourError::NoPoints)
        );
        let p = [Point { x: 1.0, y: 0.0 }];
        assert!(ellipse_departure(&p, 0.0, 1.0)
            .unwrap_err()
            .to_string()
            .contains("a = 0"));
    }
}
