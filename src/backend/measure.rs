//! What a state's record needs of the contact set C and the pressure on it, reduced where the
//! fields live ([`crate::backend::ContactKernels::measure`]): the total pressure and count, the
//! contact's chords along the ellipsoid's axes through the grid centre, and its bounding box.
//! The functions here are the host (CPU twin) definitions that the device kernels
//! (shaders/reduce.wgsl `measure_partials`) are compared with.

pub use crate::setup::ChordAxes;

/// A state's measurement of C (all in elements or in the pressure's units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactMeasure {
    /// Σ_C p (stress; multiply by Δx² for force).
    pub sum: f64,
    /// |C|, the elements in contact.
    pub count: usize,
    /// Half-lengths of C along the major and minor chord through the grid centre (elements),
    /// as [`axis_half_lengths_along`] defines them.
    pub half_lengths: (f64, f64),
    /// The elements' index box (i_min, i_max, j_min, j_max) of C, `None` when C is empty.
    pub bounds: Option<[usize; 4]>,
}

/// The measurement of `p` on the contact `mask` (both row-major nx × ny): the host definition.
pub fn measure_mask(
    p: &[f64],
    mask: &[bool],
    nx: usize,
    ny: usize,
    axes: ChordAxes,
) -> ContactMeasure {
    let (sum, count) = p
        .iter()
        .zip(mask)
        .filter(|(_, &m)| m)
        .fold((0.0, 0), |(s, c), (v, _)| (s + v, c + 1));
    with_shape(sum, count, mask, nx, ny, axes)
}

/// The measurement with Σ_C p and |C| already known: the shape of `mask` (chords along
/// `axes`, index box) added.
pub fn with_shape(
    sum: f64,
    count: usize,
    mask: &[bool],
    nx: usize,
    ny: usize,
    axes: ChordAxes,
) -> ContactMeasure {
    let half_lengths = if axes.is_aligned() {
        axis_half_lengths(mask, nx, ny)
    } else {
        axis_half_lengths_along(mask, nx, ny, axes.cos, axes.sin)
    };
    ContactMeasure {
        sum,
        count,
        half_lengths,
        bounds: bounds(mask, nx),
    }
}

/// The index box (i_min, i_max, j_min, j_max) of the true elements of a row-major mask with
/// rows of `nx`; `None` if there are none.
pub fn bounds(mask: &[bool], nx: usize) -> Option<[usize; 4]> {
    // Row by row: a row's first and last contact element are found scanning in from its two
    // ends, so a contact row is not walked element by element (this runs for every state).
    let mut b: Option<[usize; 4]> = None;
    for (j, row) in mask.chunks(nx).enumerate() {
        let Some(first) = row.iter().position(|&m| m) else {
            continue;
        };
        let last = row.iter().rposition(|&m| m).unwrap_or(first);
        b = Some(match b {
            None => [first, last, j, j],
            Some([a, c, e, _]) => [a.min(first), c.max(last), e, j],
        });
    }
    b
}

/// Half-lengths (in elements) of a contact mask along the two axes through the centre of an
/// nx × ny grid (both even): contact elements in the two middle rows (columns), averaged, halved.
pub fn axis_half_lengths(mask: &[bool], nx: usize, ny: usize) -> (f64, f64) {
    let row = |j: usize| mask[j * nx..(j + 1) * nx].iter().filter(|&&m| m).count();
    let col = |i: usize| (0..ny).filter(|&j| mask[j * nx + i]).count();
    let a = (row(ny / 2 - 1) + row(ny / 2)) as f64 / 4.0;
    let b = (col(nx / 2 - 1) + col(nx / 2)) as f64 / 4.0;
    (a, b)
}

/// Half-lengths (in elements) of a contact mask along the lines through the centre of an
/// nx × ny grid (both even) in the directions (cos θ, sin θ) and (−sin θ, cos θ).
///
/// Each line's chord is the area of the contact squares inside a band one element wide
/// centred on it, divided by that width: the chord averaged over the parallel lines within
/// half an element, computed exactly square by square. For θ = 0 the band covers half of
/// each of the two middle rows (columns), so this equals [`axis_half_lengths`]; at other
/// angles it avoids the √2·Δx steps of a single diagonal line.
pub fn axis_half_lengths_along(
    mask: &[bool],
    nx: usize,
    ny: usize,
    cos: f64,
    sin: f64,
) -> (f64, f64) {
    let (mut a, mut b) = (0.0, 0.0);
    for j in 0..ny {
        let y0 = j as f64 - (ny / 2) as f64;
        for i in 0..nx {
            if mask[j * nx + i] {
                let x0 = i as f64 - (nx / 2) as f64;
                // The band around the major axis has normal (−sin, cos), around the minor
                // axis (cos, sin).
                a += band_area(x0, y0, -sin, cos);
                b += band_area(x0, y0, cos, sin);
            }
        }
    }
    (a / 2.0, b / 2.0)
}

/// Area of the unit square [x0, x0+1] × [y0, y0+1] within |n·(x, y)| < ½, for a unit
/// normal n = (nx, ny) (all in elements).
fn band_area(x0: f64, y0: f64, nx: f64, ny: f64) -> f64 {
    // Over the square, n·(x, y) = low + U·p + V·q with U, V uniform on [0, 1].
    let low = nx * x0 + ny * y0 + nx.min(0.0) + ny.min(0.0);
    let (p, q) = (nx.abs().max(ny.abs()), nx.abs().min(ny.abs()));
    below(0.5 - low, p, q) - below(-0.5 - low, p, q)
}

/// P(U·p + V·q ≤ s) for U, V uniform on [0, 1] and p ≥ q ≥ 0, p > 0: the area of the unit
/// square below a line.
fn below(s: f64, p: f64, q: f64) -> f64 {
    let ramp = |s: f64| (s / p).clamp(0.0, 1.0);
    if q < 1e-9 {
        return ramp(s);
    }
    // The ramp's antiderivative, G' = ramp, and the mean of the ramp over [s − q, s].
    let g = |s: f64| {
        if s <= 0.0 {
            0.0
        } else if s <= p {
            s * s / (2.0 * p)
        } else {
            s - p / 2.0
        }
    };
    ((g(s) - g(s - q)) / q).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn measurement_of_a_block() {
        // A 6 × 2 block at columns 1..7, rows 1..3 of an 8 × 4 grid, p = 2 on it.
        let (nx, ny) = (8, 4);
        let mask: Vec<bool> = (0..nx * ny)
            .map(|k| (1..7).contains(&(k % nx)) && (1..3).contains(&(k / nx)))
            .collect();
        let p = vec![2.0; nx * ny];
        let m = measure_mask(&p, &mask, nx, ny, ChordAxes::ALIGNED);
        assert_eq!(m.sum, 24.0);
        assert_eq!(m.count, 12);
        assert_eq!(m.half_lengths, (3.0, 1.0));
        assert_eq!(m.bounds, Some([1, 6, 1, 2]));
        assert_eq!(bounds(&vec![false; nx * ny], nx), None);
    }

    #[test]
    fn axis_half_lengths_of_a_rectangle() {
        // A 6 × 2 block of contact centred on an 8 × 4 grid: half-lengths 3 and 1 elements.
        let (nx, ny) = (8, 4);
        let mask: Vec<bool> = (0..nx * ny)
            .map(|k| (1..7).contains(&(k % nx)) && (1..3).contains(&(k / nx)))
            .collect();
        assert_eq!(axis_half_lengths(&mask, nx, ny), (3.0, 1.0));
    }

    #[test]
    fn chords_along_the_grid_axes_equal_the_row_and_column_counts() {
        // An irregular blob: the exact chords at θ = 0 and θ = 90° are the counts of the
        // middle rows and columns (θ = 90° swaps the axes).
        let (nx, ny) = (16, 8);
        let mask: Vec<bool> = (0..nx * ny)
            .map(|k| {
                let (i, j) = ((k % nx) as f64 - 7.3, (k / nx) as f64 - 3.6);
                i * i / 30.0 + j * j / 5.0 + 0.1 * (i * j).sin() < 1.0
            })
            .collect();
        let (a, b) = axis_half_lengths(&mask, nx, ny);
        assert_eq!(axis_half_lengths_along(&mask, nx, ny, 1.0, 0.0), (a, b));
        assert_eq!(axis_half_lengths_along(&mask, nx, ny, 0.0, 1.0), (b, a));
    }

    #[test]
    fn chord_along_the_diagonal_of_a_square_block() {
        // A 4 × 4 block centred on an 8 × 8 grid: its diagonals are 4√2 elements long, and
        // the band one element wide around one loses a triangle of ⅛ on each side of each
        // corner: chord 4√2 − ½.
        let (nx, ny) = (8, 8);
        let mask: Vec<bool> = (0..nx * ny)
            .map(|k| (2..6).contains(&(k % nx)) && (2..6).contains(&(k / nx)))
            .collect();
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let (a, b) = axis_half_lengths_along(&mask, nx, ny, h, h);
        let expected = 2.0 * 2f64.sqrt() - 0.25;
        assert!((a - expected).abs() < 1e-12, "a = {a}");
        assert!((b - expected).abs() < 1e-12, "b = {b}");
    }

    #[test]
    fn band_areas_of_a_square_add_up_to_its_area() {
        // Bands tiling the plane at any angle share each square's unit area out.
        for deg in [0.0, 7.0, 30.0, 45.0, 61.0, 90.0, 135.0, 200.0f64] {
            let (s, c) = deg.to_radians().sin_cos();
            for (x0, y0) in [(0.0, 0.0), (-1.0, 2.0), (3.0, -4.0)] {
                let total: f64 = (-10..=10)
                    .map(|k| band_area(x0 - k as f64 * c, y0 - k as f64 * s, c, s))
                    .sum();
                assert!(
                    (total - 1.0).abs() < 1e-12,
                    "{deg}° at ({x0}, {y0}): {total}"
                );
            }
        }
    }

    #[test]
    fn chords_of_a_turned_ellipse_match_its_half_axes() {
        // An ellipse of half-axes 40 and 12 elements turned by 30°: the band-averaged chords
        // are its axes within a fraction of an element.
        let (nx, ny) = (128, 128);
        let (s, c) = 30f64.to_radians().sin_cos();
        let mask: Vec<bool> = (0..nx * ny)
            .map(|k| {
                let (x, y) = ((k % nx) as f64 - 63.5, (k / nx) as f64 - 63.5);
                let (xi, eta) = (x * c + y * s, -x * s + y * c);
                (xi / 40.0).powi(2) + (eta / 12.0).powi(2) < 1.0
            })
            .collect();
        let (a, b) = axis_half_lengths_along(&mask, nx, ny, c, s);
        assert!(
            (a - 40.0).abs() < 0.5 && (b - 12.0).abs() < 0.5,
            "a = {a}, b = {b}"
        );
    }
}
