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
//! tensile p from before the sweep), until a generation certifies nothing. ε is the error
//! estimate of the p the sweep used (the loose rounds' one): p and the detached loads are each
//! within about ε of the exact solve's, and the shares sum to at most 1.
//!
//! The hole's system is solved by [`JACOBI_STEPS`] Jacobi sweeps per generation, on the whole
//! set S removed so far at once (its hole grows with it), each generation starting from the
//! last one's v. That keeps it a bound at every step: G_HH is strictly diagonally dominant
//! (the one-element shares within the truncation sum to 0.969), so Jacobi's iterates
//! from a subsolution (G_HH v ≤ b; zero is one, and the last generation's v extended by zero
//! is one of the grown hole's system, whose new rows have b ≥ 0 and non-positive couplings)
//! rise towards the solution and stay below it: v smaller, Δ less negative, the bound looser,
//! never wrong. Jacobi is the same on the host and on a device, in f32 on both:
//! shaders/certify.wgsl runs these steps over the tiles the hole touches (this module is its
//! twin), so the GPU backend certifies what the CPU backend does without its fields leaving
//! the device.
//! On the host, v lives on the grid padded by the truncation, and eight cells of a row are
//! summed at once, each weight of the stencil broadcast and multiplied into the eight in one
//! vector instruction (the `stencil` module; AVX2 and FMA where the CPU has them); the
//! workspace ([`Certifier`]) is kept between rounds and only its touched cells are cleared.
//!
//! The reaches. The bound is only as tight as the hole is large and G is wide. Measured at
//! 5:1 (adhesive force, CPU, CG iterations at 256×128 / 512×256 / 1024×512): within 8
//! elements (17×17 stencils), 1 854 / 4 394 / 8 837; within 12 (25×25), 1 686 / 3 839 /
//! 7 538; within 16 (33×33), 1 604 / 3 592 / 6 945. The share a reach leaves out falls only as
//! 1/reach (G decays as r⁻³), and the host's work grows as the stencil's area times the
//! hole's: 12 is where the host's wall time stops falling at 1024×512 (268 s against 277 s
//! within 8 and 327 s within 16, 2 cores). More sweeps tighten the bound a little for more
//! host time than they save.
//!
//! The last generation's bound, which certifies nothing more, is also the round's predicted
//! start: p + Δ on the candidates kept (unscaled), the load they take from S onto the plane
//! less the actual hole, which CG corrects (in place of the fixed shares of
//! [`super::shares`], which know no hole).
//!
//! Only the solve's count changes, never a state: 5:1 at 512×256, adhesive force, 2 148 →
//! 912 cascade rounds and 11 230 → 5 213 CG iterations (with the predicted start, reaches of
//! 8), every contact set equal; with reaches of 12, 675 rounds and 3 839 CG iterations.

mod plane;
mod stencil;

pub use plane::{
    inverse_influence, off_diagonal, plane_shares_on_lattice, PLANE_SHARES, TABLE_LATTICE,
    TABLE_MARGIN,
};

use stencil::Padded;

/// Contact elements within this many elements (along x and y) of a removed one are tested.
pub const CANDIDATE_REACH: i64 = 12;

/// Elements off C within this many elements of a removed one belong to the hole H.
pub const HOLE_REACH: i64 = 12;

/// Entries of G beyond this many elements (along x or y) are left out (see the module).
pub const TRUNCATION: i64 = 12;

/// An element is certified only below −σ_c − this × ε (ε: the solve's error estimate).
pub const ERROR_MARGIN: f64 = 3.0;

/// The computed change Δ is scaled by this before the test: a margin for the rounding of
/// the hole's system, solved in f32 on the host and on a device alike (sums whose terms all
/// have one sign, each stencil row summed apart: chains of at most 2 × 25 roundings).
pub const ROUNDING_SAFETY: f64 = 0.99;

/// Jacobi sweeps of the hole's system per generation. From zero (or from the last
/// generation's v, which is a subsolution of the grown hole's system) Jacobi's iterates rise
/// towards the solution and stay below it (G_HH is a strictly diagonally dominant Stieltjes
/// matrix), so every iterate gives a bound: more sweeps only tighten it.
pub const JACOBI_STEPS: usize = 16;

/// The hole H, the candidates and v, grown generation by generation; kept between calls
/// (a workspace as large as the grid, whose touched cells are cleared after each call).
#[derive(Clone)]
pub struct Certifier {
    nx: usize,
    ny: usize,
    /// Whether each element belongs to the hole (n, row-major).
    in_hole: Vec<bool>,
    /// The hole's elements.
    cells: Vec<usize>,
    /// −p before the sweep on the removed elements, 0 elsewhere (stress, n).
    b: Vec<f32>,
    /// The hole's Jacobi iterate, zero off the hole (stress, on the padded grid).
    v: Padded,
    /// Whether an element of C is a candidate (n).
    is_candidate: Vec<bool>,
    /// The candidates, in the order found (some may have been certified since).
    candidates: Vec<usize>,
    /// The generation (from 1) in which each element was removed; 0 for one still in C (n).
    removed_in: Vec<u32>,
}

impl Certifier {
    /// A workspace for an nx × ny grid.
    pub fn new(nx: usize, ny: usize) -> Certifier {
        let n = nx * ny;
        Certifier {
            nx,
            ny,
            in_hole: vec![false; n],
            cells: Vec::new(),
            b: vec![0.0; n],
            v: Padded::new(nx, ny),
            is_candidate: vec![false; n],
            candidates: Vec::new(),
            removed_in: vec![0; n],
        }
    }

    /// Mark `fresh` removed in `generation`.
    fn remove(&mut self, fresh: &[usize], generation: u32) {
        for &j in fresh {
            self.removed_in[j] = generation;
        }
    }

    /// Grow the hole and the candidates around the elements `fresh` just removed.
    fn grow(&mut self, fresh: &[usize], c: &[bool], before: &[f64]) {
        let (nx, ny) = (self.nx, self.ny);
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
                    } else if dist <= HOLE_REACH && !self.in_hole[i] {
                        self.in_hole[i] = true;
                        self.cells.push(i);
                        if self.removed_in[i] > 0 {
                            self.b[i] = -before[i] as f32;
                        }
                    }
                }
            }
        }
    }

    /// [`JACOBI_STEPS`] Jacobi sweeps of G_HH v = b (G's diagonal is 1) over the hole.
    fn jacobi(&mut self) {
        self.cells.sort_unstable();
        let runs = stencil::runs(&self.cells, self.nx);
        let mut next = vec![0.0; self.cells.len()];
        for _ in 0..JACOBI_STEPS {
            stencil::apply(&self.v, &runs, &mut next);
            for (&i, &x) in self.cells.iter().zip(&next) {
                self.v.set(i, self.b[i] - x);
            }
        }
    }

    /// Δ (stress, ≤ 0) on every candidate still in C, in order.
    fn deltas(&self, c: &[bool]) -> Vec<(usize, f64)> {
        let mut kept: Vec<usize> = self.candidates.iter().copied().filter(|&i| c[i]).collect();
        kept.sort_unstable();
        let mut sums = vec![0.0; kept.len()];
        stencil::apply(&self.v, &stencil::runs(&kept, self.nx), &mut sums);
        kept.into_iter()
            .zip(sums)
            .map(|(i, s)| (i, f64::from(s).min(0.0)))
            .collect()
    }

    /// Clear what this call touched, for the next.
    fn clear(&mut self) {
        for &i in &self.cells {
            self.in_hole[i] = false;
            self.b[i] = 0.0;
            self.removed_in[i] = 0;
            self.v.set(i, 0.0);
        }
        for &i in &self.candidates {
            self.is_candidate[i] = false;
            self.removed_in[i] = 0;
        }
        self.cells.clear();
        self.candidates.clear();
    }

    /// Detach the elements of C (`c`) that are certainly over `sigma_c` (stress) once the
    /// elements just detached hand on their load; return how many. `before` is p before the
    /// sweep (the detached elements are those off C with `before` ≠ 0); `p` is zeroed on the
    /// elements certified and, on the candidates kept, set to the round's predicted start
    /// before + Δ (the balayage onto the plane less the last hole: nearly the load they
    /// take, which CG corrects). `eps` (stress) is the error estimate of `before`. `None`
    /// (nothing done) if a detached element was not tensile or none was. Grid nx × ny,
    /// row-major, x fastest.
    pub fn certify(
        &mut self,
        c: &mut [bool],
        before: &[f64],
        p: &mut [f64],
        sigma_c: f64,
        eps: f64,
    ) -> Option<usize> {
        let n = self.nx * self.ny;
        assert!(c.len() == n && before.len() == n && p.len() == n);
        let mut fresh: Vec<usize> = (0..n).filter(|&j| !c[j] && before[j] != 0.0).collect();
        if fresh.is_empty() || fresh.iter().any(|&j| before[j] >= 0.0) {
            return None;
        }
        self.remove(&fresh, 1);
        let limit = -sigma_c - ERROR_MARGIN * eps;
        let mut certified = 0;
        for generation in 1.. {
            self.grow(&fresh, c, before);
            self.jacobi();
            let deltas = self.deltas(c);
            let certain: Vec<usize> = deltas
                .iter()
                .filter(|&&(i, d)| before[i] < 0.0 && before[i] + ROUNDING_SAFETY * d < limit)
                .map(|&(i, _)| i)
                .collect();
            if certain.is_empty() {
                // The last bound, unscaled, is the round's predicted start.
                for (i, d) in deltas {
                    p[i] = before[i] + d;
                }
                break;
            }
            for &i in &certain {
                c[i] = false;
                p[i] = 0.0;
            }
            self.remove(&certain, generation + 1);
            certified += certain.len();
            fresh = certain;
        }
        self.clear();
        Some(certified)
    }
}

/// [`Certifier::certify`] with a workspace of its own (grid nx × ny).
pub fn certify_detached(
    c: &mut [bool],
    before: &[f64],
    p: &mut [f64],
    nx: usize,
    ny: usize,
    sigma_c: f64,
    eps: f64,
) -> Option<usize> {
    Certifier::new(nx, ny).certify(c, before, p, sigma_c, eps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::kernel::influence;
    use crate::backend::shares;

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
        let first: Vec<usize> = (10..30).map(|x| 6 * nx + x).collect();
        let second: Vec<usize> = (12..28).map(|x| 7 * nx + x).collect();
        let mut hole = Certifier::new(nx, ny);
        let on_grid = |h: &Certifier| (0..nx * ny).map(|i| h.v.get(i)).collect::<Vec<f32>>();
        for (generation, fresh) in [&first, &second].into_iter().enumerate() {
            for &j in fresh {
                c[j] = false;
            }
            hole.remove(fresh, generation as u32 + 1);
            hole.grow(fresh, &c, &before);
            // The solution, from far more sweeps than needed.
            let mut exact = hole.clone();
            for _ in 0..50 {
                exact.jacobi();
            }
            let exact = on_grid(&exact);
            let mut last = on_grid(&hole);
            for _ in 0..4 {
                hole.jacobi();
                let now = on_grid(&hole);
                for (k, (&v, &was)) in now.iter().zip(&last).enumerate() {
                    assert!(v >= was - 1e-12, "generation {generation}: v fell at {k}");
                    assert!(
                        v <= exact[k] + 1e-12,
                        "generation {generation}: v above the solution at {k}"
                    );
                }
                last = now;
            }
            assert!(last.iter().any(|&v| v > 0.0));
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
        let mut hole = Certifier::new(n, n);
        hole.remove(&members, 1);
        hole.grow(&members, &swept, &before);
        hole.jacobi();
        let deltas = hole.deltas(&swept);
        let worst = deltas
            .iter()
            .map(|&(i, d)| exact[i] - (before[i] + scale * ROUNDING_SAFETY * d))
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
