//! Straight contact fronts along the grid: the share of a contact's edge that runs straight
//! along a grid axis or a diagonal over a length comparable to the contact itself. The
//! Pohrt–Popov criterion pins such a front (its energy release rate converges to 1.82 Δγ
//! along an axis, docs/failures.md), so an answer decided by one is biased high by far more
//! than its uncertainty; a circle's or an ellipse's staircase edge, and a rough contact's
//! patches, have only short straight runs.

/// Fewest elements a straight run must span to count (elements).
pub const MIN_RUN: usize = 8;

/// Share of the contact's size, √(elements in contact), a straight run must span to count
/// (dimensionless): a circle of radius R elements has flats of about 2√(2R) at its poles,
/// well under √(πR²)/2 from R = 8 on; a strip's fronts run its whole length.
pub const RUN_SHARE_OF_SIZE: f64 = 0.5;

/// Share of the edge in straight runs from which the fronts decide the answer
/// (dimensionless).
pub const STRAIGHT_SHARE_LIMIT: f64 = 0.5;

/// What the edge of a contact set is made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StraightFronts {
    /// Element faces between contact and gap (the edge's length in elements).
    pub edge: usize,
    /// The share of them in straight runs along an axis or a diagonal at least
    /// `min_run` long (dimensionless, 0–1).
    pub share: f64,
    /// The shortest run counted (elements).
    pub min_run: usize,
}

impl StraightFronts {
    /// Whether straight fronts make up enough of the edge to decide the answer.
    pub fn decide(&self) -> bool {
        self.share >= STRAIGHT_SHARE_LIMIT
    }
}

/// The straight fronts of the row-major (x fastest) `nx` × `ny` contact `mask` (true: in
/// contact), its sides adjacent across the domain's edges (a periodic domain's seam; an
/// isolated contact never reaches them). `None` for an empty or full contact.
pub fn straight_fronts(mask: &[bool], nx: usize, ny: usize) -> Option<StraightFronts> {
    assert_eq!(mask.len(), nx * ny, "a mask of the grid's size");
    let n_contact = mask.iter().filter(|&&c| c).count();
    if n_contact == 0 || n_contact == mask.len() {
        return None;
    }
    let min_run = MIN_RUN.max((RUN_SHARE_OF_SIZE * (n_contact as f64).sqrt()).ceil() as usize);
    let at = |i: usize, j: usize| mask[(j % ny) * nx + (i % nx)];
    // A face's kind: which side of it is in contact (0: none, 1: the lower index, 2: the
    // higher), so that a run is one front, not two that meet.
    let face = |a: bool, b: bool| match (a, b) {
        (true, false) => 1u8,
        (false, true) => 2,
        _ => 0,
    };
    let mut edge = 0usize;
    let mut straight = 0usize;
    // Faces between rows j and j+1, runs along x; between columns i and i+1, runs along y.
    let mut count_runs = |len: usize, lines: usize, kind: &dyn Fn(usize, usize) -> u8| {
        for line in 0..lines {
            let mut run = 0usize;
            let mut last = 0u8;
            for k in 0..=len {
                let f = if k < len { kind(line, k) } else { 0 };
                if f != 0 {
                    edge += 1;
                }
                if f != 0 && f == last {
                    run += 1;
                } else {
                    if run >= min_run {
                        straight += run;
                    }
                    run = usize::from(f != 0);
                }
                last = f;
            }
        }
    };
    count_runs(nx, ny, &|j, i| face(at(i, j), at(i, j + 1)));
    count_runs(ny, nx, &|i, j| face(at(i, j), at(i + 1, j)));
    // Diagonal fronts: staircases of edge elements, each with its two faces on one side.
    let exposed = |i: usize, j: usize, di: isize, dj: isize| -> bool {
        let (ii, jj) = (
            (i as isize + di).rem_euclid(nx as isize) as usize,
            (j as isize + dj).rem_euclid(ny as isize) as usize,
        );
        at(i, j) && !at(ii, jj)
    };
    for (sx, sy) in [(1isize, 1isize), (1, -1), (-1, 1), (-1, -1)] {
        // An element of a front facing (sx, sy): gap beyond it along x and along y, contact
        // behind it; a diagonal front of this facing runs along (1, −sx·sy).
        let on_front = |i: usize, j: usize| exposed(i, j, sx, 0) && exposed(i, j, 0, sy);
        let step = -sx * sy;
        for j0 in 0..ny {
            for i0 in 0..nx {
                if !on_front(i0, j0) {
                    continue;
                }
                // Start of a run only: its predecessor is not on the front.
                let pi = (i0 + nx - 1) % nx;
                let pj = (j0 as isize - step).rem_euclid(ny as isize) as usize;
                if on_front(pi, pj) {
                    continue;
                }
                let mut len = 0usize;
                let (mut i, mut j) = (i0, j0);
                while on_front(i, j) && len < nx.min(ny) {
                    len += 1;
                    i = (i + 1) % nx;
                    j = (j as isize + step).rem_euclid(ny as isize) as usize;
                }
                if len >= min_run {
                    straight += 2 * len;
                }
            }
        }
    }
    Some(StraightFronts {
        edge,
        share: (straight as f64 / edge as f64).min(1.0),
        min_run,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(nx: usize, ny: usize, inside: impl Fn(f64, f64) -> bool) -> Vec<bool> {
        (0..nx * ny)
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                inside(
                    i as f64 + 0.5 - nx as f64 / 2.0,
                    j as f64 + 0.5 - ny as f64 / 2.0,
                )
            })
            .collect()
    }

    #[test]
    fn a_strip_along_an_axis_is_all_straight_fronts() {
        // The extruded wave's contact on its period: a strip along y, 26 of 64 wide.
        let m = mask(64, 16, |x, _| x.abs() < 13.0);
        let f = straight_fronts(&m, 64, 16).unwrap();
        assert_eq!(f.edge, 32);
        assert!(f.decide() && f.share == 1.0, "{f:?}");
    }

    #[test]
    fn a_strip_along_a_diagonal_is_straight_fronts_too() {
        let m = mask(128, 128, |x, y| (x - y).abs() < 20.0);
        let f = straight_fronts(&m, 128, 128).unwrap();
        assert!(f.decide(), "{f:?}");
    }

    #[test]
    fn circles_ellipses_and_patches_are_not() {
        for r in [6.0, 12.0, 25.0, 50.0, 100.0] {
            let n = (4.0 * r) as usize + 8;
            let m = mask(n, n, |x, y| x * x + y * y < r * r);
            let f = straight_fronts(&m, n, n).unwrap();
            assert!(!f.decide(), "circle of radius {r}: {f:?}");
        }
        for (a, b) in [(40.0, 20.0), (100.0, 20.0), (60.0, 6.0)] {
            let n = (2.5 * a) as usize;
            let m = mask(n, n, |x, y| (x / a).powi(2) + (y / b).powi(2) < 1.0);
            let f = straight_fronts(&m, n, n).unwrap();
            assert!(!f.decide(), "ellipse {a} × {b}: {f:?}");
        }
        // Patches: small discs scattered over a nominally flat surface.
        let m = mask(256, 256, |x, y| {
            let (u, v) = ((x + 300.0) % 23.0 - 11.5, (y + 300.0) % 29.0 - 14.5);
            u * u + v * v < 16.0 + 8.0 * ((x * 0.37).sin() * (y * 0.21).cos()).abs()
        });
        let f = straight_fronts(&m, 256, 256).unwrap();
        assert!(!f.decide(), "patches: {f:?}");
        assert!(straight_fronts(&[false; 16], 4, 4).is_none());
        assert!(straight_fronts(&[true; 16], 4, 4).is_none());
    }
}
