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
//! Only the solve's count changes, never a state: 5:1 at 512×256, adhesive force, 2 148 →
//! 1 301 cascade rounds and 11 230 → 7 560 CG iterations, every contact set equal.

use super::shares;
use rayon::prelude::*;
use std::collections::HashMap;
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
const DISC_SAFETY: f64 = 0.98;

/// Radius (elements) of the disc on which G's entries are computed.
const DISC_RADIUS: i64 = 16;

/// G / G(0) on the offsets within [`TRUNCATION`], row-major over (2T+1)², centre 1
/// (dimensionless).
fn inverse_influence() -> &'static [f64] {
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

/// A cluster's local frame: a box on the grid, and the hole's index of each of its cells.
struct Frame {
    x0: i64,
    y0: i64,
    x1: i64,
    y1: i64,
    /// Index into the hole of the cell (x, y), or `u32::MAX`.
    index: Vec<u32>,
}

impl Frame {
    /// The hole's index of element (x, y), if it lies in the box and in the hole.
    fn hole_at(&self, x: i64, y: i64) -> Option<usize> {
        if x < self.x0 || x > self.x1 || y < self.y0 || y > self.y1 {
            return None;
        }
        let w = self.x1 - self.x0 + 1;
        let k = self.index[((y - self.y0) * w + x - self.x0) as usize];
        (k != u32::MAX).then_some(k as usize)
    }
}

/// Detach the elements of C (`c`) that are certainly over `sigma_c` (stress) once the
/// elements just detached hand on their load; return how many. `before` is p before the
/// sweep (the detached elements are those off C with `before` ≠ 0); `p` is zeroed on the
/// elements certified. `eps` (stress) is the error estimate of `before`. Nothing is done if
/// a detached element was not tensile. Grid nx × ny, row-major, x fastest.
pub fn certify_detached(
    c: &mut [bool],
    before: &[f64],
    p: &mut [f64],
    nx: usize,
    ny: usize,
    sigma_c: f64,
    eps: f64,
) -> usize {
    let n = nx * ny;
    let mut removed: Vec<usize> = (0..n).filter(|&j| !c[j] && before[j] != 0.0).collect();
    if removed.is_empty() || removed.iter().any(|&j| before[j] >= 0.0) {
        return 0;
    }
    let first = removed.len();
    // The generation (from 1) in which each element was removed; 0 for one still in C.
    let mut removed_in = vec![0u32; n];
    for &j in &removed {
        removed_in[j] = 1;
    }
    // The hole's solution of the last generation by element: the next one starts from it.
    let mut warm: HashMap<usize, f64> = HashMap::new();
    let mut label = vec![u32::MAX; n];
    let limit = -sigma_c - ERROR_MARGIN * eps;
    for generation in 1.. {
        let groups = clusters(&removed, nx, ny, &mut label);
        let (cm, rm, wm): (&[bool], &[u32], &HashMap<usize, f64>) = (c, &removed_in, &warm);
        // Only the groups that gained elements in the last generation have a new bound.
        let found: Vec<GroupBound> = groups
            .par_iter()
            .filter(|g| g.iter().any(|&j| rm[j] == generation))
            .map(|members| bound_cluster(members, cm, rm, before, wm, nx, ny))
            .collect();
        let mut certain = Vec::new();
        for (deltas, hole) in found {
            // Groups' candidates are disjoint: each Δ is the whole bound's change.
            certain.extend(
                deltas
                    .into_iter()
                    .filter(|&(i, d)| before[i] < 0.0 && before[i] + DISC_SAFETY * d < limit)
                    .map(|(i, _)| i),
            );
            warm.extend(hole);
        }
        if certain.is_empty() {
            break;
        }
        certain.sort_unstable();
        for &i in &certain {
            c[i] = false;
            p[i] = 0.0;
            removed_in[i] = generation + 1;
        }
        removed.extend(certain);
    }
    removed.len() - first
}

/// The removed elements in groups whose holes and candidates do not overlap: linked when
/// within 2·max(reach) of each other. Each group's bound is taken on its own; leaving out
/// the other groups' (negative) contributions only loosens it.
fn clusters(removed: &[usize], nx: usize, ny: usize, label: &mut [u32]) -> Vec<Vec<usize>> {
    const UNSEEN: u32 = u32::MAX - 1;
    let link = 2 * CANDIDATE_REACH.max(HOLE_REACH);
    for &j in removed {
        label[j] = UNSEEN;
    }
    let mut out: Vec<Vec<usize>> = Vec::new();
    for &j0 in removed {
        if label[j0] != UNSEEN {
            continue;
        }
        let id = out.len() as u32;
        label[j0] = id;
        let mut stack = vec![j0];
        let mut group = Vec::new();
        while let Some(j) = stack.pop() {
            group.push(j);
            let (jx, jy) = ((j % nx) as i64, (j / nx) as i64);
            for y in (jy - link).max(0)..=(jy + link).min(ny as i64 - 1) {
                for x in (jx - link).max(0)..=(jx + link).min(nx as i64 - 1) {
                    let i = y as usize * nx + x as usize;
                    if label[i] == UNSEEN {
                        label[i] = id;
                        stack.push(i);
                    }
                }
            }
        }
        group.sort_unstable();
        out.push(group);
    }
    for &j in removed {
        label[j] = u32::MAX;
    }
    out
}

/// One group's bound: Δ (stress) on each candidate, and the hole's solution v by element.
type GroupBound = (Vec<(usize, f64)>, Vec<(usize, f64)>);

/// The bound of the group `members` ([`GroupBound`]); `removed_in` is non-zero on the
/// elements removed so far.
fn bound_cluster(
    members: &[usize],
    c: &[bool],
    removed_in: &[u32],
    before: &[f64],
    warm: &HashMap<usize, f64>,
    nx: usize,
    ny: usize,
) -> GroupBound {
    let g = inverse_influence();
    let t = TRUNCATION;
    let reach = CANDIDATE_REACH.max(HOLE_REACH);
    let xy = |j: usize| ((j % nx) as i64, (j / nx) as i64);
    let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
    for &j in members {
        let (x, y) = xy(j);
        (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
    }
    let mut frame = Frame {
        x0: (x0 - reach).max(0),
        y0: (y0 - reach).max(0),
        x1: (x1 + reach).min(nx as i64 - 1),
        y1: (y1 + reach).min(ny as i64 - 1),
        index: Vec::new(),
    };
    let w = frame.x1 - frame.x0 + 1;
    frame.index = vec![u32::MAX; (w * (frame.y1 - frame.y0 + 1)) as usize];
    let mut candidate = vec![false; frame.index.len()];
    let (mut hole, mut cands) = (Vec::new(), Vec::new());
    for &j in members {
        let (jx, jy) = xy(j);
        for y in (jy - reach).max(frame.y0)..=(jy + reach).min(frame.y1) {
            for x in (jx - reach).max(frame.x0)..=(jx + reach).min(frame.x1) {
                let local = ((y - frame.y0) * w + x - frame.x0) as usize;
                let i = y as usize * nx + x as usize;
                let dist = (x - jx).abs().max((y - jy).abs());
                if c[i] {
                    if dist <= CANDIDATE_REACH && !candidate[local] {
                        candidate[local] = true;
                        cands.push(i);
                    }
                } else if frame.index[local] == u32::MAX
                    && (dist <= HOLE_REACH || removed_in[i] > 0)
                {
                    frame.index[local] = hole.len() as u32;
                    hole.push(i);
                }
            }
        }
    }
    // G_HH's rows within the truncation, compressed (row k: entries start[k]..start[k+1]).
    let mut rows = Rows::default();
    for &h in &hole {
        let (hx, hy) = xy(h);
        for oy in -t..=t {
            for ox in -t..=t {
                if let Some(k) = frame.hole_at(hx + ox, hy + oy) {
                    rows.col.push(k as u32);
                    rows.val.push(g_at(g, ox, oy));
                }
            }
        }
        rows.start.push(rows.col.len());
    }
    let b: Vec<f64> = hole.iter().map(|&h| -before[h]).collect();
    let mut v: Vec<f64> = hole
        .iter()
        .map(|h| warm.get(h).copied().unwrap_or(0.0))
        .collect();
    solve_stieltjes(&rows, &b, &mut v);
    let deltas = cands
        .iter()
        .map(|&i| {
            let (ix, iy) = xy(i);
            let mut d = 0.0;
            for oy in -t..=t {
                for ox in -t..=t {
                    if let Some(k) = frame.hole_at(ix + ox, iy + oy) {
                        d += g_at(g, -ox, -oy) * v[k];
                    }
                }
            }
            (i, d.min(0.0))
        })
        .collect();
    (deltas, hole.into_iter().zip(v).collect())
}

/// Relative residual to which the hole's system is solved.
const HOLE_TOLERANCE: f64 = 1e-6;

/// A sparse matrix by compressed rows.
struct Rows {
    /// Where each row's entries start, and (last) where the entries end.
    start: Vec<usize>,
    /// Column of each entry.
    col: Vec<u32>,
    /// Value of each entry.
    val: Vec<f64>,
}

impl Default for Rows {
    fn default() -> Self {
        Rows {
            start: vec![0],
            col: Vec::new(),
            val: Vec::new(),
        }
    }
}

/// Solve A v = b by CG from the `v` given, A symmetric positive definite.
fn solve_stieltjes(rows: &Rows, b: &[f64], v: &mut [f64]) {
    let m = b.len();
    let apply = |x: &[f64], out: &mut [f64]| {
        for (k, o) in out.iter_mut().enumerate() {
            let (a, e) = (rows.start[k], rows.start[k + 1]);
            *o = rows.col[a..e]
                .iter()
                .zip(&rows.val[a..e])
                .map(|(&j, &g)| g * x[j as usize])
                .sum();
        }
    };
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut q = vec![0.0; m];
    apply(v, &mut q);
    let mut r: Vec<f64> = b.iter().zip(&q).map(|(b, q)| b - q).collect();
    let mut d = r.clone();
    let target = HOLE_TOLERANCE * dot(b, b).sqrt();
    let mut rr = dot(&r, &r);
    for _ in 0..m.max(1) * 2 {
        if rr.sqrt() <= target {
            break;
        }
        apply(&d, &mut q);
        let alpha = rr / dot(&d, &q);
        for k in 0..m {
            v[k] += alpha * d[k];
            r[k] -= alpha * q[k];
        }
        let next = dot(&r, &r);
        let beta = next / rr;
        rr = next;
        for k in 0..m {
            d[k] = r[k] + beta * d[k];
        }
    }
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
        let (deltas, _) = bound_cluster(&members, &swept, &removed, &before, &HashMap::new(), n, n);
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
        let count = certify_detached(&mut certified, &before, &mut p, n, n, sigma_c, 0.0);
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
