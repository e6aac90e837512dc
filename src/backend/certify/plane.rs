//! The plane's inverse influence G = K⁻¹ within the truncation: the table the certification's
//! bound is built from, and how it is made.
//!
//! −G(o)/G(0) is the share of a unit load removed from one element that the element at offset
//! o takes when the load is handed to the whole plane less that element (the balayage onto
//! it). On the infinite lattice G has a closed form in Fourier space: K's symbol K̂(θ) (the
//! lattice sum of Love's coefficients, singular as 1/|θ| at θ = 0) inverted, G = F⁻¹(1/K̂).
//! [`plane_shares_on_lattice`] evaluates it on the m × m periodic lattice (K laid out on
//! offsets −m/2 … m/2 − 1, transformed, inverted, transformed back): the shares converge
//! to the plane's as m⁻³ (against m = 4096, within 2.8e-4 at m = 512, 3.6e-5 at 1024 and
//! 5.0e-6 at 2048, every one of them from below at 2048), and within 8 elements they equal
//! the extrapolation from dense solves on discs of radius 40 and 56 to 5e-7.
//!
//! [`PLANE_SHARES`] is the m = 4096 lattice's, less [`TABLE_MARGIN`] (1e-5, ten times the
//! distance left to the plane): no larger than the plane's, so that the hole's system gives a
//! v no larger than the plane's (comparison of M-matrices), what makes the bound a bound.
//! `cargo run --release --example plane_shares` makes it again and checks it (seconds); the
//! tests check it against the m = 2048 lattice.

use super::TRUNCATION;
use crate::backend::kernel::padded_kernel;
use rayon::prelude::*;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::OnceLock;

/// The side of the periodic lattice [`PLANE_SHARES`] was made on (elements).
pub const TABLE_LATTICE: usize = 4096;

/// The fraction taken off the lattice's shares in [`PLANE_SHARES`] (dimensionless): ten
/// times the distance left from the m = 4096 lattice's to the plane's.
pub const TABLE_MARGIN: f64 = 1e-5;

/// −G(o)/G(0) on the m × m periodic lattice at the offsets (x, y), 1 ≤ x ≤ [`TRUNCATION`],
/// 0 ≤ y ≤ x, in that order (dimensionless; `m` a power of two, at least 4 T). A few seconds
/// at m = 4096 on 2 cores.
pub fn plane_shares_on_lattice(m: usize) -> Vec<(i64, i64, f64)> {
    assert!(m.is_power_of_two() && m >= 4 * TRUNCATION as usize);
    // K on the lattice, negative offsets wrapped (unit Δx and E*: the shares depend on
    // neither): the padded convolution's kernel of an (m/2)² grid is laid out the same way.
    let mut a: Vec<Complex<f64>> = padded_kernel(m / 2, m / 2, 1.0, 1.0)
        .into_iter()
        .map(|k| Complex::new(k, 0.0))
        .collect();
    let mut planner = FftPlanner::new();
    transform(&mut a, m, planner.plan_fft_forward(m).as_ref());
    // K is real and even, so is its symbol: invert its real part.
    a.par_iter_mut()
        .for_each(|z| *z = Complex::new(1.0 / z.re, 0.0));
    transform(&mut a, m, planner.plan_fft_inverse(m).as_ref());
    let g0 = a[0].re;
    let t = TRUNCATION;
    (1..=t)
        .flat_map(|x| (0..=x).map(move |y| (x, y)))
        .map(|(x, y)| (x, y, -a[y as usize * m + x as usize].re / g0))
        .collect()
}

/// The 2-D transform of the m × m array `a` (row-major) by `fft` along both axes.
fn transform(a: &mut Vec<Complex<f64>>, m: usize, fft: &dyn Fft<f64>) {
    let mut out = vec![Complex::new(0.0, 0.0); m * m];
    for _ in 0..2 {
        a.par_chunks_mut(m).for_each(|row| fft.process(row));
        transpose::transpose(a, &mut out, m, m);
        std::mem::swap(a, &mut out);
    }
}

/// −G/G(0) at the offsets (x, y), 1 ≤ x ≤ [`TRUNCATION`], 0 ≤ y ≤ x (the other offsets by
/// symmetry): the share of a unit load removed from one element that each element of the plane less it
/// takes (dimensionless). The m = [`TABLE_LATTICE`] lattice's ([`plane_shares_on_lattice`])
/// less [`TABLE_MARGIN`]: see the module.
pub const PLANE_SHARES: [(i64, i64, f64); 90] = [
    (1, 0, 0.15745931171629762),
    (1, 1, 0.04108878428579769),
    (2, 0, 0.0022949709697885267),
    (2, 1, 0.0042125082186830025),
    (2, 2, 0.0027031745339056563),
    (3, 0, 0.002712375755639528),
    (3, 1, 0.0021948803552647757),
    (3, 2, 0.0014357735535567304),
    (3, 3, 0.000879062604699588),
    (4, 0, 0.0010307973195308846),
    (4, 1, 0.0009486822092839736),
    (4, 2, 0.0007494291097014502),
    (4, 3, 0.0005391902200105157),
    (4, 4, 0.00037366032309815543),
    (5, 0, 0.0005402765896963544),
    (5, 1, 0.0005093772749944337),
    (5, 2, 0.0004327748644424016),
    (5, 3, 0.0003414565623277715),
    (5, 4, 0.0002583196236410559),
    (5, 5, 0.0001921258177463814),
    (6, 0, 0.0003135621678007632),
    (6, 1, 0.00030102920047645246),
    (6, 2, 0.00026801197876398064),
    (6, 3, 0.00022483845756336108),
    (6, 4, 0.00018120230007638986),
    (6, 5, 0.0001427681677675823),
    (6, 6, 0.00011143792427304391),
    (7, 0, 0.0001980228568994546),
    (7, 1, 0.0001921390622884514),
    (7, 2, 0.00017612881321000764),
    (7, 3, 0.00015394183021307087),
    (7, 4, 0.00012984451074683195),
    (7, 5, 0.00010696617040185699),
    (7, 6, 8.694571068786148e-5),
    (7, 7, 7.027330952516862e-5),
    (8, 0, 0.00013289151306633768),
    (8, 1, 0.00012984784034938824),
    (8, 2, 0.00012138017814276687),
    (8, 3, 0.00010916561946318882),
    (8, 4, 9.519761242819621e-5),
    (8, 5, 8.116687231988987e-5),
    (8, 6, 6.818097268206628e-5),
    (8, 7, 5.678475694516871e-5),
    (8, 8, 4.711972257372605e-5),
    (9, 0, 9.344700478730573e-5),
    (9, 1, 9.174783117027144e-5),
    (9, 2, 8.694728294198632e-5),
    (9, 3, 7.982229437713121e-5),
    (9, 4, 7.136055819271303e-5),
    (9, 5, 6.24881195556619e-5),
    (9, 6, 5.390392865943988e-5),
    (9, 7, 4.60386327442895e-5),
    (9, 8, 3.909438980161461e-5),
    (9, 9, 3.3113981708326155e-5),
    (10, 0, 6.818199079703234e-5),
    (10, 1, 6.717432528836935e-5),
    (10, 2, 6.429550616448063e-5),
    (10, 3, 5.99323129649936e-5),
    (10, 4, 5.460120931681059e-5),
    (10, 5, 4.88229313694443e-5),
    (10, 6, 4.303133053507162e-5),
    (10, 7, 3.7533358847052796e-5),
    (10, 8, 3.251101340798645e-5),
    (10, 9, 2.8046026434602e-5),
    (10, 10, 2.4150684947586206e-5),
    (11, 0, 5.1259105571959844e-5),
    (11, 1, 5.0631425012151975e-5),
    (11, 2, 4.8823193159872927e-5),
    (11, 3, 4.603893478082621e-5),
    (11, 4, 4.256203309213081e-5),
    (11, 5, 3.869423056115204e-5),
    (11, 6, 3.4705903822694984e-5),
    (11, 7, 3.080762102294318e-5),
    (11, 8, 2.714258371058625e-5),
    (11, 9, 2.379334503091453e-5),
    (11, 10, 2.07952068985969e-5),
    (11, 11, 1.815065917606121e-5),
    (12, 0, 3.950191971850851e-5),
    (12, 1, 3.909467856066336e-5),
    (12, 2, 3.791398175244219e-5),
    (12, 3, 3.607365524499224e-5),
    (12, 4, 3.373596838078466e-5),
    (12, 5, 3.1081117091193305e-5),
    (12, 6, 2.827979230877304e-5),
    (12, 7, 2.547472336523766e-5),
    (12, 8, 2.2772511413517103e-5),
    (12, 9, 2.024375375517562e-5),
    (12, 10, 1.792818205849567e-5),
    (12, 11, 1.5841814888105927e-5),
    (12, 12, 1.3984082823232261e-5),
];

/// The plane's share at offset (x, y), 0 ≤ y ≤ x ≤ [`TRUNCATION`], from [`PLANE_SHARES`] (dimensionless).
fn plane_share(x: i64, y: i64) -> f64 {
    PLANE_SHARES
        .iter()
        .find(|&&(a, b, _)| (a, b) == (x, y))
        .expect("an offset within the table")
        .2
}

/// G / G(0) on the offsets within [`TRUNCATION`], row-major over (2T+1)², centre 1
/// (dimensionless).
pub fn inverse_influence() -> &'static [f64] {
    static G: OnceLock<Vec<f64>> = OnceLock::new();
    G.get_or_init(|| {
        let t = TRUNCATION;
        let side = (2 * t + 1) as usize;
        let mut g = vec![0.0; side * side];
        for oy in -t..=t {
            for ox in -t..=t {
                let (x, y) = (ox.abs().max(oy.abs()), ox.abs().min(oy.abs()));
                g[((oy + t) as usize) * side + (ox + t) as usize] = match (x, y) {
                    (0, 0) => 1.0,
                    _ => -plane_share(x, y),
                };
            }
        }
        g
    })
}

/// G / G(0) at offset (ox, oy), |ox|, |oy| ≤ [`TRUNCATION`].
#[cfg(test)]
fn g_at(g: &[f64], ox: i64, oy: i64) -> f64 {
    let t = TRUNCATION;
    g[((oy + t) * (2 * t + 1) + ox + t) as usize]
}

/// G / G(0) off the diagonal (the centre zero), row-major over (2T+1)², in f32
/// (dimensionless): the stencil of the hole's Jacobi step and of Δ, on the host and (the same
/// table uploaded) on a device.
pub fn off_diagonal() -> &'static [f32] {
    static G: OnceLock<Vec<f32>> = OnceLock::new();
    G.get_or_init(|| {
        let mut g: Vec<f32> = inverse_influence().iter().map(|&w| w as f32).collect();
        let t = TRUNCATION as usize;
        g[t * (2 * t + 1) + t] = 0.0;
        g
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::shares::{balayage, disc_less_origin};

    #[test]
    fn the_inverse_influence_is_a_stieltjes_kernel() {
        let g = inverse_influence();
        let t = TRUNCATION;
        assert_eq!(g_at(g, 0, 0), 1.0);
        // The edge neighbour's balayage share on the whole plane, negated.
        assert!((g_at(g, 1, 0) + 0.15746).abs() < 1e-5, "{}", g_at(g, 1, 0));
        for oy in -t..=t {
            for ox in -t..=t {
                if (ox, oy) != (0, 0) {
                    assert!(g_at(g, ox, oy) < 0.0, "({ox}, {oy})");
                    assert!((g_at(g, ox, oy) - g_at(g, oy, -ox)).abs() < 1e-9);
                }
            }
        }
        // Strictly diagonally dominant, so Jacobi converges and its iterates bound (see the
        // certification's notes): the shares within the truncation sum to 0.969 (within 8
        // to 0.955, within 16 to 0.977; the plane's, all of them, to 1).
        let off: f64 = g.iter().map(|w| w.abs()).sum::<f64>() - 1.0;
        assert!(
            (off - 0.969).abs() < 1e-3,
            "the shares within the truncation sum to {off}"
        );
    }

    #[test]
    fn the_table_lies_just_below_the_lattice_shares_that_converge_to_the_planes() {
        // The m = 2048 lattice is within 5e-6 of the m = 4096 one the table was made on (less
        // 1e-5), and the lattices converge as m⁻³: 512 and 1024 differ by eight times more
        // than 1024 and 2048.
        let at = |m| plane_shares_on_lattice(m);
        let (w512, w1024, w2048) = (at(512), at(1024), at(2048));
        let worst = |a: &[(i64, i64, f64)], b: &[(i64, i64, f64)]| {
            a.iter()
                .zip(b)
                .map(|(p, q)| (p.2 / q.2 - 1.0).abs())
                .fold(0.0, f64::max)
        };
        let (coarse, fine) = (worst(&w512, &w1024), worst(&w1024, &w2048));
        assert!(
            coarse > 4.0 * fine && fine < 5e-5,
            "512 → 1024: {coarse:e}, 1024 → 2048: {fine:e}"
        );
        assert_eq!(w2048.len(), PLANE_SHARES.len());
        for (&(x, y, table), &(a, b, lattice)) in PLANE_SHARES.iter().zip(&w2048) {
            assert_eq!((x, y), (a, b));
            let below = 1.0 - table / lattice;
            assert!(
                below > 0.0 && below < 2e-5,
                "({x}, {y}): the table is {below:e} below the 2048 lattice"
            );
        }
    }

    #[test]
    fn a_disc_exceeds_the_table_everywhere_as_it_exceeds_the_plane() {
        // A disc less its centre is a part of the plane less it, so its balayage weights lie
        // above the plane's; within 8 elements, radius 24's by at most 3 %.
        let disc = disc_less_origin(24);
        let w = balayage(&disc);
        for (&(x, y), &w) in disc.iter().zip(&w) {
            if 0 <= y && y <= x && x <= TRUNCATION && x > 0 {
                let excess = w / plane_share(x, y) - 1.0;
                assert!(excess > 0.0, "({x}, {y}): radius 24 lies {excess} above");
                if x <= 8 {
                    assert!(excess < 0.031, "({x}, {y}): radius 24 exceeds by {excess}");
                }
            }
        }
    }
}
