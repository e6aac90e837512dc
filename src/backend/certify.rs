//! Detachments certain before a solve: after a cascade round's sweep detaches elements, the
//! contact elements around them that are sure to be over σ_c once the detached load is
//! handed on are detached at once, without solving for it, in generations.
//!
//! The bound. Removing a set S of tensile elements (p_S < 0) from a contact set C at a fixed
//! approach changes the pressure on the elements left by the balayage of p_S onto C \ S:
//! p'_i = p_i + Σ_j W_ij p_j, with W ≥ 0. Onto a larger set the shares are smaller (each
//! element of the larger set takes at most what it takes of the smaller one), so the
//! balayage onto any superset Y ⊇ C \ S bounds the change from above: p'_i ≤ p_i + Δ_i with
//! Δ the balayage onto Y. Here Y is the whole plane less a local hole H: S and the elements
//! off C within [`HOLE_REACH`] of it. On the plane less a finite hole the balayage has a
//! closed form in the plane's inverse influence G = K⁻¹: solve G_HH v = −p_H (with p zero on
//! H \ S) and Δ = G_YH v. G's off-diagonal entries are negative (−G(o)/G(0) is the balayage
//! of one element onto the plane less it, [`super::shares`]), so G_HH is a Stieltjes matrix,
//! v ≥ 0 and Δ ≤ 0; leaving out G's entries beyond [`TRUNCATION`] makes v smaller and drops
//! negative terms from Δ, so the truncated bound is still a bound.
//!
//! An element i with p_i + Δ_i < −σ_c − [`ERROR_MARGIN`] ε is over σ_c on C \ S, so the
//! exact cascade detaches it too, whatever else it detaches first (the rule is monotone and
//! the set it ends on is the greatest stable subset). Certified elements join S and the
//! bound is taken again (for removing all of S from C at once, each element with its
//! tensile p from before the sweep), until a generation certifies nothing. ε is the error estimate of
//! the p the sweep used (the loose rounds' one): p and the detached loads are each within
//! about ε of the exact solve's, and the shares sum to at most 1.
//!
//! The hole's system is solved by [`JACOBI_STEPS`] Jacobi sweeps per generation, on the whole
//! set S removed so far at once (its hole grows with it), each generation starting from the
//! last one's v. That keeps it a bound at every step: G_HH is strictly diagonally dominant
//! (the one-element shares within the truncation sum to 0.915), so Jacobi's iterates
//! from a subsolution (G_HH v ≤ b; zero is one, and the last generation's v extended by zero
//! is one of the grown hole's system, whose new rows have b ≥ 0 and non-positive couplings)
//! rise towards the solution and stay below it: v smaller, Δ less negative, the bound looser,
//! never wrong. Sixteen sweeps certify what a converged solve does (5:1 at 256×128: 10 056
//! elements against 10 060 with 32 sweeps). Jacobi is the same on the host and on a device:
//! shaders/certify.wgsl runs these steps over the whole grid (this module is its twin), so
//! the GPU backend certifies what the CPU backend does without its fields leaving the device.
//!
//! The last generation's bound, which certifies nothing more, is also the round's predicted
//! start: p + Δ on the candidates kept (unscaled), the load they take from S onto the plane
//! less the actual hole, which CG corrects (in place of the fixed shares of
//! [`super::shares`], which know no hole).
//!
//! Only the solve's count changes, never a state: 5:1 at 512×256, adhesive force, 2 148 →
//! 1 258 cascade rounds and 11 230 → 7 023 CG iterations (with the predicted start), every
//! contact set equal.

use super::shares;
use rayon::prelude::*;
use std::sync::OnceLock;

/// Contact elements within this many elements (along x and y) of a removed one are tested.
pub const CANDIDATE_REACH: i64 = 4;

/// Elements off C within this many elements of a removed one belong to the hole H.
pub const HOLE_REACH: i64 = 4;

/// Entries of G beyond this many elements (along x or y) are left out (see the module).
pub const TRUNCATION: i64 = 4;

/// An element is certified only below −σ_c − this × ε (ε: the solve's error estimate).
pub const ERROR_MARGIN: f64 = 3.0;

/// The computed change Δ is scaled by this before the test: G is computed on a disc of
/// radius [`DISC_RADIUS`], whose balayage weights exceed the whole plane's by less than 1 %
/// within [`TRUNCATION`] (the sign that would loosen the bound).
pub const DISC_SAFETY: f64 = 0.98;

/// Radius (elements) of the disc on which G's entries are computed.
pub const DISC_RADIUS: i64 = 16;

/// G / G(0) on the offsets within [`TRUNCATION`], row-major over (2T+1)², centre 1
/// (dimensionless).
pub fn inverse_influence() -> &'static [f64] {
    static G: OnceLock<Vec<f64>> = OnceLock::new();
    G.get_or_init(|| {
        let k = DISC_RADIUS;
        let t = TRUNCATION;
        let disc = shares::disc_less_origin(k);
        let w = shares::balayage(&disc);
        let side = (2 * t + 1) as usize;
        let mut g = vec![0.0; side * side];
        for (&(x, y), &wi) in disc.iter().zip(&w) {
            if x.abs() <= t && y.abs() <= t {
                g[((y + t) as usize) * side + (x + t) as usize] = -wi;
            }
        }
        g[(t as usize) * side + t as usize] = 1.0;
        g
    })
}

/// G / G(0) at offset (ox, oy), |ox|, |oy| ≤ [`TRUNCATION`].
fn g_at(g: &[f64], ox: i64, oy: i64) -> f64 {
    let t = TRUNCATION;
    g[((oy + t) * (2 * t + 1) + ox + t) as usize]
}

/// Jacobi sweeps of the hole's system per generation. From zero (or from the last
/// generation's v, which is a subsolution of the grown hole's system) Jacobi's iterates rise
/// towards the solution and stay below it (G_HH is a strictly diagonally dominant Stieltjes
/// matrix), so every iterate gives a bound: more sweeps only tighten it.
pub const JACOBI_STEPS: usize = 16;

/// One row of G_HH off the diagonal: (hole index, G/G(0)).
type Row = Vec<(u32, f64)>;

/// The hole H, the candidates and v on the grid, grown generation by generation.
struct Hole {
    /// The hole's index of each element, or `u32::MAX` (n, row-major).
    slot: Vec<u32>,
    /// The hole's elements.
    cells: Vec<usize>,
    /// −p before the sweep on the removed elements, 0 on the others (stress).
    b: Vec<f64>,
    /// The hole's Jacobi iterate (stress).
    v: Vec<f64>,
    /// G_HH's off-diagonal entries within the truncation by row (hole index, value), built
    /// when a cell joins and extended when its neighbours join later.
    rows: Vec<Row>,
    /// Whether an element of C is a candidate (n).
    is_candidate: Vec<bool>,
    /// The candidates, in the order found (some may have been certified since).
    candidates: Vec<usize>,
}

impl Hole {
    fn new(n: usize) -> Hole {
        Hole {
            slot: vec![u32::MAX; n],
            cells: Vec::new(),
            b: Vec::new(),
            v: Vec::new(),
            rows: Vec::new(),
            is_candidate: vec![false; n],
            candidates: Vec::new(),
        }
    }

    /// Grow the hole and the candidates around the elements `fresh` just removed.
    fn grow(
        &mut self,
        fresh: &[usize],
        c: &[bool],
        before: &[f64],
        removed_in: &[u32],
        nx: usize,
        ny: usize,
    ) {
        let reach = CANDIDATE_REACH.max(HOLE_REACH);
        for &j in fresh {
            let (jx, jy) = ((j % nx) as i64, (j / nx) as i64);
            for y in (jy - reach).max(0)..=(jy + reach).min(ny as i64 - 1) {
                for x in (jx - reach).max(0)..=(jx + reach).min(nx as i64 - 1) {
                    let i = y as usize * nx + x as usize;
                    let dist = (x - jx).abs().max((y - jy).abs());
                    if c[i] {
                        if dist <= CANDIDATE_REACH && !self.is_candidate[i] {
                            self.is_candidate[i] = true;
                            self.candidates.push(i);
                        }
                    } else if dist <= HOLE_REACH && self.slot[i] == u32::MAX {
                        self.join(i, before, removed_in, nx, ny);
                    }
                }
            }
        }
    }

    /// Element i joins the hole: its row of G_HH, and its entry in its neighbours' rows.
    fn join(&mut self, i: usize, before: &[f64], removed_in: &[u32], nx: usize, ny: usize) {
        let g = inverse_influence();
        let t = TRUNCATION;
        let k = self.cells.len() as u32;
        self.slot[i] = k;
        self.cells.push(i);
        self.b
            .push(if removed_in[i] > 0 { -before[i] } else { 0.0 });
        self.v.push(0.0);
        let (ix, iy) = ((i % nx) as i64, (i / nx) as i64);
        let mut row = Vec::new();
        for y in (iy - t).max(0)..=(iy + t).min(ny as i64 - 1) {
            for x in (ix - t).max(0)..=(ix + t).min(nx as i64 - 1) {
                let m = self.slot[y as usize * nx + x as usize];
                if m != u32::MAX && m != k {
                    let w = g_at(g, x - ix, y - iy);
                    row.push((m, w));
                    self.rows[m as usize].push((k, w));
                }
            }
        }
        self.rows.push(row);
    }

    /// Σ_o g(o) v(i + o) over the offsets within the truncation (stress).
    fn g_times_v(&self, g: &[f64], i: usize, nx: usize, ny: usize) -> f64 {
        let t = TRUNCATION;
        let (ix, iy) = ((i % nx) as i64, (i / nx) as i64);
        let mut acc = 0.0;
        for y in (iy - t).max(0)..=(iy + t).min(ny as i64 - 1) {
            for x in (ix - t).max(0)..=(ix + t).min(nx as i64 - 1) {
                let k = self.slot[y as usize * nx + x as usize];
                if k != u32::MAX {
                    acc += g_at(g, x - ix, y - iy) * self.v[k as usize];
                }
            }
        }
        acc
    }

    /// [`JACOBI_STEPS`] Jacobi sweeps of G_HH v = b (G's diagonal is 1).
    fn jacobi(&mut self) {
        let mut next = vec![0.0; self.v.len()];
        let parallel = self.cells.len() >= PARALLEL_FROM;
        for _ in 0..JACOBI_STEPS {
            let v = &self.v;
            let sweep = |(o, (row, &b)): (&mut f64, (&Row, &f64))| {
                *o = b - row.iter().map(|&(m, w)| w * v[m as usize]).sum::<f64>();
            };
            if parallel {
                next.par_iter_mut()
                    .zip(self.rows.par_iter().zip(&self.b))
                    .with_min_len(PARALLEL_FROM / 4)
                    .for_each(sweep);
            } else {
                next.iter_mut()
                    .zip(self.rows.iter().zip(&self.b))
                    .for_each(sweep);
            }
            std::mem::swap(&mut self.v, &mut next);
        }
    }

    /// Δ (stress, ≤ 0) on every candidate still in C.
    fn deltas(&self, c: &[bool], nx: usize, ny: usize) -> Vec<(usize, f64)> {
        let g = inverse_influence();
        let delta = |&i: &usize| (i, self.g_times_v(g, i, nx, ny).min(0.0));
        if self.candidates.len() >= PARALLEL_FROM {
            self.candidates
                .par_iter()
                .with_min_len(PARALLEL_FROM / 4)
                .filter(|&&i| c[i])
                .map(delta)
                .collect()
        } else {
            self.candidates
                .iter()
                .filter(|&&i| c[i])
                .map(delta)
                .collect()
        }
    }
}

/// Holes and candidate lists shorter than this are swept on one thread (elements): waking
/// the pool for a few hundred stencils costs more than it saves.
const PARALLEL_FROM: usize = 2048;

/// Detach the elements of C (`c`) that are certainly over `sigma_c` (stress) once the
/// elements just detached hand on their load; return how many. `before` is p before the
/// sweep (the detached elements are those off C with `before` ≠ 0); `p` is zeroed on the
/// elements certified and, on the candidates kept, set to the round's predicted start
/// before + Δ (the balayage onto the plane less the last hole: nearly the load they take,
/// which CG corrects). `eps` (stress) is the error estimate of `before`. `None` (nothing
/// done) if a detached element was not tensile or none was. Grid nx × ny, row-major, x
/// fastest.
pub fn certify_detached(
    c: &mut [bool],
    before: &[f64],
    p: &mut [f64],
    nx: usize,
    ny: usize,
    sigma_c: f64,
    eps: f64,
) -> Option<usize> {
    let n = nx * ny;
    let mut fresh: Vec<usize> = (0..n).filter(|&j| !c[j] && before[j] != 0.0).collect();
    if fresh.is_empty() || fresh.iter().any(|&j| before[j] >= 0.0) {
        return None;
    }
    // The generation (from 1) in which each element was removed; 0 for one still in C.
    let mut removed_in = vec![0u32; n];
    for &j in &fresh {
        removed_in[j] = 1;
    }
    let mut hole = Hole::new(n);
    let limit = -sigma_c - ERROR_MARGIN * eps;
    let mut certified = 0;
    for generation in 1.. {
        hole.grow(&fresh, c, before, &removed_in, nx, ny);
        hole.jacobi();
        let deltas = hole.deltas(c, nx, ny);
        let mut certain: Vec<usize> = deltas
            .iter()
            .filter(|&&(i, d)| before[i] < 0.0 && before[i] + DISC_SAFETY * d < limit)
            .map(|&(i, _)| i)
            .collect();
        if certain.is_empty() {
            // The last bound, unscaled, is the round's predicted start.
            for (i, d) in deltas {
                p[i] = before[i] + d;
            }
            break;
        }
        certain.sort_unstable();
        for &i in &certain {
            c[i] = false;
            p[i] = 0.0;
            removed_in[i] = generation + 1;
        }
        certified += certain.len();
        fresh = certain;
    }
    Some(certified)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::kernel::influence;

    #[test]
    fn the_inverse_influence_is_a_stieltjes_kernel() {
        let g = inverse_influence();
        let t = TRUNCATION;
        assert_eq!(g_at(g, 0, 0), 1.0);
        // The edge neighbour's balayage share on the whole plane, negated.
        assert!((g_at(g, 1, 0) + 0.15746).abs() < 1e-4, "{}", g_at(g, 1, 0));
        for oy in -t..=t {
            for ox in -t..=t {
                if (ox, oy) != (0, 0) {
                    assert!(g_at(g, ox, oy) < 0.0, "({ox}, {oy})");
                    assert!((g_at(g, ox, oy) - g_at(g, oy, -ox)).abs() < 1e-9);
                }
            }
        }
        // Strictly diagonally dominant, so Jacobi converges and its iterates bound (see the
        // module).
        let off: f64 = g.iter().map(|w| w.abs()).sum::<f64>() - 1.0;
        assert!(off < 0.95, "the shares within the truncation sum to {off}");
    }

    #[test]
    fn jacobi_iterates_rise_and_stay_below_the_hole_solution() {
        // A band of contact whose lower edge partly detached, then a second generation.
        let (nx, ny) = (40, 24);
        let mut c: Vec<bool> = (0..nx * ny).map(|i| (6..18).contains(&(i / nx))).collect();
        let before: Vec<f64> = (0..nx * ny)
            .map(|i| {
                if c[i] {
                    -1.0 + 0.03 * ((i * 7919) % 13) as f64
                } else {
                    0.0
                }
            })
            .collect();
        let mut removed_in = vec![0u32; nx * ny];
        let first: Vec<usize> = (10..30).map(|x| 6 * nx + x).collect();
        let second: Vec<usize> = (12..28).map(|x| 7 * nx + x).collect();
        let mut hole = Hole::new(nx * ny);
        for (generation, fresh) in [&first, &second].into_iter().enumerate() {
            for &j in fresh {
                c[j] = false;
                removed_in[j] = generation as u32 + 1;
            }
            hole.grow(fresh, &c, &before, &removed_in, nx, ny);
            // The solution, from far more sweeps than needed.
            let mut exact = Hole {
                v: hole.v.clone(),
                rows: hole.rows.clone(),
                b: hole.b.clone(),
                ..Hole::new(0)
            };
            for _ in 0..50 {
                exact.jacobi();
            }
            let mut last = hole.v.clone();
            for _ in 0..4 {
                hole.jacobi();
                for (k, (&v, &was)) in hole.v.iter().zip(&last).enumerate() {
                    assert!(v >= was - 1e-12, "generation {generation}: v fell at {k}");
                    assert!(
                        v <= exact.v[k] + 1e-12,
                        "generation {generation}: v above the solution at {k}"
                    );
                }
                last = hole.v.clone();
            }
            assert!(hole.v.iter().any(|&v| v > 0.0));
        }
    }

    /// p on the contact set `c` (grid n × n, unit Δx and E*) of a rigid sphere of radius 30
    /// at approach 2.7 (its Hertz contact has radius 9), centred on the grid: K_CC p = d − h
    /// on C, solved densely.
    fn sphere_pressure(c: &[bool], n: usize) -> Vec<f64> {
        let set: Vec<usize> = (0..n * n).filter(|&i| c[i]).collect();
        let at = |i: usize| ((i % n) as f64, (i / n) as f64);
        let mut a: Vec<f64> = set
            .iter()
            .flat_map(|&i| {
                set.iter().map(move |&j| {
                    let ((xi, yi), (xj, yj)) = (at(i), at(j));
                    influence(xi - xj, yi - yj, 1.0, 1.0)
                })
            })
            .collect();
        let centre = (n as f64 - 1.0) / 2.0;
        let mut b: Vec<f64> = set
            .iter()
            .map(|&i| {
                let (x, y) = at(i);
                let r2 = (x - centre).powi(2) + (y - centre).powi(2);
                2.7 - r2 / 60.0
            })
            .collect();
        shares::cholesky_solve(&mut a, &mut b, set.len());
        let mut p = vec![0.0; n * n];
        for (&i, &pi) in set.iter().zip(&b) {
            p[i] = pi;
        }
        p
    }

    /// The bound on a sphere's adhesive contact of radius 12.5 whose most tensile edge
    /// elements are detached: the
    /// largest amount by which an exact pressure on C \ S lies above its bound (≤ 0 when the
    /// bound holds), and how many elements it certifies. `scale` multiplies Δ (1 as built).
    fn punch_bound(scale: f64) -> (f64, usize, Vec<bool>) {
        let n = 36;
        let c: Vec<bool> = (0..n * n)
            .map(|i| {
                let (x, y) = ((i % n) as f64 - 17.5, (i / n) as f64 - 17.5);
                x * x + y * y <= 12.5 * 12.5
            })
            .collect();
        let before = sphere_pressure(&c, n);
        let most = before.iter().cloned().fold(0.0, f64::min);
        let sigma_c = 0.8 * most.abs();
        let swept: Vec<bool> = c
            .iter()
            .zip(&before)
            .map(|(&m, &p)| m && p >= -sigma_c)
            .collect();
        let exact = sphere_pressure(&swept, n);
        let members: Vec<usize> = (0..n * n).filter(|&i| c[i] && !swept[i]).collect();
        let removed: Vec<u32> = (0..n * n).map(|i| (c[i] && !swept[i]) as u32).collect();
        let mut hole = Hole::new(n * n);
        hole.grow(&members, &swept, &before, &removed, n, n);
        hole.jacobi();
        let deltas = hole.deltas(&swept, n, n);
        let worst = deltas
            .iter()
            .map(|&(i, d)| exact[i] - (before[i] + scale * DISC_SAFETY * d))
            .fold(f64::NEG_INFINITY, f64::max);
        let mut certified = swept.clone();
        let mut p = before.clone();
        for (pi, &m) in p.iter_mut().zip(&swept) {
            if !m {
                *pi = 0.0;
            }
        }
        let count = certify_detached(&mut certified, &before, &mut p, n, n, sigma_c, 0.0).unwrap();
        // The exact cascade (solve, sweep, until nothing changes) keeps every element that
        // the certification kept.
        let mut stable = swept.clone();
        loop {
            let q = sphere_pressure(&stable, n);
            let next: Vec<bool> = stable
                .iter()
                .zip(&q)
                .map(|(&m, &p)| m && p >= -sigma_c)
                .collect();
            if next == stable {
                break;
            }
            stable = next;
        }
        for i in 0..n * n {
            assert!(
                !stable[i] || certified[i],
                "element {i} certified but kept by the cascade"
            );
        }
        assert!(stable.contains(&true), "the cascade keeps nothing: no test");
        (worst, count, certified)
    }

    #[test]
    fn the_bound_holds_on_a_sphere_contact_and_fails_when_inflated() {
        let (worst, count, _) = punch_bound(1.0);
        assert!(
            worst <= 1e-9,
            "an exact pressure lies {worst:e} above its bound"
        );
        assert!(count > 0, "nothing certified");
        // The rule broken on purpose: shares half as large again overstate the change.
        let (broken, _, _) = punch_bound(1.5);
        assert!(
            broken > 0.0,
            "an inflated bound went unnoticed ({broken:e})"
        );
    }
}
