//! The shares of a detached element's load that the contact elements around it take: the
//! predictor with which a cascade round's solve starts.
//!
//! Removing an element j from a contact set at a fixed approach hands its pressure p_j to
//! the elements left in contact (the balayage of p_j onto them): on the whole plane less j,
//! the edge neighbour takes 0.157 of it, the diagonal one 0.041, the rest falls off as 1/r³.
//! A cascade round that detaches a few elements starts CG from p with each detached load
//! handed to the contact elements within [`SHARE_RADIUS`] by these shares, scaled up to what
//! the edge neighbour of a straight front takes (a front element has fewer neighbours in
//! contact). CG then only corrects the prediction: the states are the same, with fewer
//! iterations (5:1 at 512×256: 13 274 → 11 230 CG iterations over the adhesive force run).

use super::kernel::influence;
use std::sync::OnceLock;

/// Elements either side of a detached one (along x and y) that take a share of its load.
pub const SHARE_RADIUS: usize = 3;

/// Radius (elements) of the patch on which the shares are solved: large enough that the
/// shares within [`SHARE_RADIUS`] do not change with it (to 1e-4 from 12 to 16).
const PATCH_RADIUS: i64 = 12;

/// The shares, (2R+1)² of them with R = [`SHARE_RADIUS`], row-major: offset (ox, oy) at
/// `(oy + R)·(2R + 1) + (ox + R)`; the centre is 0 (dimensionless: a fraction of the detached
/// element's pressure). Computed once from Love's coefficients (they do not depend on Δx or
/// E*).
pub fn detachment_shares() -> &'static [f64] {
    static SHARES: OnceLock<Vec<f64>> = OnceLock::new();
    SHARES.get_or_init(|| {
        let r = SHARE_RADIUS as i64;
        let k = PATCH_RADIUS;
        // The whole plane less the origin (a disc of the patch's radius).
        let plane = disc_less_origin(k);
        // A straight front: the half-plane y ≥ 0 less its edge element at the origin.
        let front: Vec<(i64, i64)> = (0..=k)
            .flat_map(|y| (-2 * k..=2 * k).map(move |x| (x, y)))
            .filter(|&(x, y)| (x, y) != (0, 0) && x * x + y * y <= 4 * k * k)
            .collect();
        let on_plane = balayage(&plane);
        let on_front = balayage(&front);
        let edge = |set: &[(i64, i64)], q: &[f64]| {
            set.iter().position(|&o| o == (1, 0)).map_or(0.0, |i| q[i])
        };
        let scale = edge(&front, &on_front) / edge(&plane, &on_plane);
        let side = 2 * r + 1;
        let mut w = vec![0.0; (side * side) as usize];
        for (&(x, y), &q) in plane.iter().zip(&on_plane) {
            if x.abs() <= r && y.abs() <= r {
                w[((y + r) * side + x + r) as usize] = scale * q;
            }
        }
        w
    })
}

/// The offsets (elements) of a disc of radius `k` elements about the origin, less the origin:
/// the whole plane less one element, as far as a balayage onto it needs.
pub(super) fn disc_less_origin(k: i64) -> Vec<(i64, i64)> {
    (-k..=k)
        .flat_map(|y| (-k..=k).map(move |x| (x, y)))
        .filter(|&(x, y)| (x, y) != (0, 0) && x * x + y * y <= k * k)
        .collect()
}

/// The shares q on the elements `set` (offsets, elements) of a unit pressure removed from
/// the origin: K_SS q = K_S0, the displacement on the set kept unchanged.
pub(super) fn balayage(set: &[(i64, i64)]) -> Vec<f64> {
    let n = set.len();
    let k =
        |a: (i64, i64), b: (i64, i64)| influence((a.0 - b.0) as f64, (a.1 - b.1) as f64, 1.0, 1.0);
    let mut a: Vec<f64> = set
        .iter()
        .flat_map(|&p| set.iter().map(move |&q| k(p, q)))
        .collect();
    let mut q: Vec<f64> = set.iter().map(|&p| k(p, (0, 0))).collect();
    cholesky_solve(&mut a, &mut q, n);
    q
}

/// Solve A x = b in place (A symmetric positive definite, n × n row-major, overwritten by its
/// Cholesky factor; b by x).
pub(super) fn cholesky_solve(a: &mut [f64], b: &mut [f64], n: usize) {
    for j in 0..n {
        let d = a[j * n + j] - (0..j).map(|k| a[j * n + k] * a[j * n + k]).sum::<f64>();
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let s = a[i * n + j] - (0..j).map(|k| a[i * n + k] * a[j * n + k]).sum::<f64>();
            a[i * n + j] = s / d;
        }
    }
    for i in 0..n {
        b[i] = (b[i] - (0..i).map(|k| a[i * n + k] * b[k]).sum::<f64>()) / a[i * n + i];
    }
    for i in (0..n).rev() {
        b[i] = (b[i] - (i + 1..n).map(|k| a[k * n + i] * b[k]).sum::<f64>()) / a[i * n + i];
    }
}

/// Twin of the GPU's `spread_detached` (shaders/spread.wgsl), on the host in f64: for every
/// element i of C, p_i += Σ_o w_o · before_{i+o} over the offsets o within [`SHARE_RADIUS`]
/// whose element i+o lies on the grid and off C (`before` is zero off the contact set it
/// was the pressure of, so only the elements just detached contribute).
pub fn spread_detached(c: &[bool], before: &[f64], p: &mut [f64], nx: usize, ny: usize) {
    let w = detachment_shares();
    let r = SHARE_RADIUS as i64;
    let side = 2 * r + 1;
    let detached: Vec<usize> = (0..nx * ny)
        .filter(|&j| !c[j] && before[j] != 0.0)
        .collect();
    for j in detached {
        let (jx, jy) = ((j % nx) as i64, (j / nx) as i64);
        for oy in -r..=r {
            let y = jy - oy;
            if y < 0 || y >= ny as i64 {
                continue;
            }
            for ox in -r..=r {
                let x = jx - ox;
                if x < 0 || x >= nx as i64 {
                    continue;
                }
                let i = y as usize * nx + x as usize;
                if c[i] {
                    p[i] += w[((oy + r) * side + ox + r) as usize] * before[j];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shares_are_the_plane_balayage_scaled_to_a_straight_front() {
        let w = detachment_shares();
        let r = SHARE_RADIUS;
        let side = 2 * r + 1;
        let at = |ox: i64, oy: i64| w[(oy + r as i64) as usize * side + (ox + r as i64) as usize];
        // The whole plane's edge and diagonal shares (0.15747, 0.04109) times the straight
        // front's edge share over the plane's (0.19193 / 0.15747).
        assert!((at(1, 0) - 0.19193).abs() < 2e-4, "edge {}", at(1, 0));
        assert!((at(1, 1) - 0.04109 * 0.19193 / 0.15747).abs() < 2e-4);
        assert_eq!(at(0, 0), 0.0);
        // Symmetric under the square's eight symmetries.
        for (x, y) in [(1, 0), (2, 1), (3, 2)] {
            for (a, b) in [(x, y), (-x, y), (x, -y), (y, x), (-y, -x)] {
                assert!((at(a, b) - at(x, y)).abs() < 1e-12);
            }
        }
    }
}
