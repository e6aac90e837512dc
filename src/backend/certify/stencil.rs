//! G's off-diagonal part applied to v at many cells at once: the host's side of the hole's
//! Jacobi step and of Δ (`g_times_v` in shaders/certify.wgsl), eight cells of a grid row at
//! a time.
//!
//! v lives on the grid padded by the truncation T on every side ([`Padded`], zero outside
//! the hole), so that no stencil leaves it and none needs a bound check. The cells to evaluate
//! are grouped into runs along x ([`runs`]); each output lane sums the (2T+1)² products of its
//! cell a stencil row at a time, every row into a partial sum of its own that is then added
//! to the total (so no chain of roundings is longer than 2(2T+1) terms: the rounding that
//! [`super::ROUNDING_SAFETY`] covers). The stencil's weight is broadcast and the eight cells'
//! v read as one vector: one fused multiply–add per weight for eight cells, where a cell at a
//! time needs a horizontal sum per cell.

use super::{off_diagonal, TRUNCATION};
use rayon::prelude::*;

/// Cells evaluated together (one 256-bit vector of f32).
const LANES: usize = 8;

/// The stencil's side, 2T + 1 (elements).
const SIDE: usize = 2 * TRUNCATION as usize + 1;

/// The values one lane group reads of a stencil row: its side plus the other lanes.
const SPAN: usize = SIDE + LANES - 1;

/// Runs holding fewer cells than this are evaluated on one thread: waking the pool for a
/// few hundred stencils costs more than it saves.
const PARALLEL_FROM: usize = 2048;

/// An nx × ny grid of f32 padded by T zeros on every side (row-major, x fastest), with
/// [`LANES`] values of slack at the end for the last lanes of the last row.
#[derive(Clone)]
pub(super) struct Padded {
    nx: usize,
    width: usize,
    data: Vec<f32>,
}

impl Padded {
    /// A zero grid for nx × ny cells.
    pub(super) fn new(nx: usize, ny: usize) -> Padded {
        let t = TRUNCATION as usize;
        let width = nx + 2 * t;
        Padded {
            nx,
            width,
            data: vec![0.0; width * (ny + 2 * t) + LANES],
        }
    }

    /// The index in `data` of cell `i` (row-major on the nx × ny grid).
    #[inline(always)]
    fn at(&self, i: usize) -> usize {
        let t = TRUNCATION as usize;
        (i / self.nx + t) * self.width + i % self.nx + t
    }

    /// The value at cell `i`.
    #[cfg(test)]
    pub(super) fn get(&self, i: usize) -> f32 {
        self.data[self.at(i)]
    }

    /// Set the value at cell `i`.
    pub(super) fn set(&mut self, i: usize, value: f32) {
        let k = self.at(i);
        self.data[k] = value;
    }
}

/// A run of cells along x: row `y`, columns `x0 .. x0 + len`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Run {
    y: usize,
    x0: usize,
    len: usize,
}

/// The runs of `cells` (sorted, row-major cell indices on a grid nx wide), in order.
pub(super) fn runs(cells: &[usize], nx: usize) -> Vec<Run> {
    let mut out: Vec<Run> = Vec::new();
    for &i in cells {
        let (x, y) = (i % nx, i / nx);
        match out.last_mut() {
            Some(r) if r.y == y && r.x0 + r.len == x => r.len += 1,
            _ => out.push(Run { y, x0: x, len: 1 }),
        }
    }
    out
}

/// `out[k]` = Σ_{o ≠ 0, |o| ≤ T} g(o) v(cell_k + o) for the k-th cell of `runs` in order
/// (stress; G/G(0) off the diagonal, [`off_diagonal`]), on the pool's threads when there are
/// many cells.
pub(super) fn apply(v: &Padded, runs: &[Run], out: &mut [f32]) {
    let total: usize = runs.iter().map(|r| r.len).sum();
    assert_eq!(out.len(), total, "one output per cell of the runs");
    if total < PARALLEL_FROM {
        apply_here(v, runs, out);
        return;
    }
    // Pieces of about PARALLEL_FROM / 4 cells, each with its own part of `out`.
    let mut pieces: Vec<(&[Run], &mut [f32])> = Vec::new();
    let (mut rest_runs, mut rest_out) = (runs, out);
    while !rest_runs.is_empty() {
        let mut count = 0;
        let mut k = 0;
        while k < rest_runs.len() && count < PARALLEL_FROM / 4 {
            count += rest_runs[k].len;
            k += 1;
        }
        let (r, rr) = rest_runs.split_at(k);
        let (o, ro) = std::mem::take(&mut rest_out).split_at_mut(count);
        pieces.push((r, o));
        (rest_runs, rest_out) = (rr, ro);
    }
    pieces
        .into_par_iter()
        .for_each(|(r, o)| apply_here(v, r, o));
}

/// [`apply`] on this thread: in 256-bit vectors with fused multiply–adds where the CPU has
/// them, else in plain arithmetic.
fn apply_here(v: &Padded, runs: &[Run], out: &mut [f32]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has AVX2 and FMA, checked just above.
        unsafe {
            each_lane_group(v, runs, out, |corner| {
                avx2::lane_sums(&v.data, v.width, corner)
            })
        };
        return;
    }
    each_lane_group(v, runs, out, |corner| lane_sums(&v.data, v.width, corner));
}

/// Fill `out` for the cells of `runs`, [`LANES`] at a time, by `sums(corner)`: the sums of
/// the cells whose stencils' top-left corners are at `corner`, `corner + 1`, … in `v.data`.
#[inline(always)]
fn each_lane_group(
    v: &Padded,
    runs: &[Run],
    out: &mut [f32],
    sums: impl Fn(usize) -> [f32; LANES],
) {
    let mut k = 0;
    for run in runs {
        let corner = run.y * v.width + run.x0;
        let mut done = 0;
        while done < run.len {
            let lanes = sums(corner + done);
            let take = (run.len - done).min(LANES);
            out[k..k + take].copy_from_slice(&lanes[..take]);
            k += take;
            done += take;
        }
    }
}

/// The sums for the [`LANES`] cells whose stencils' top-left corners are at `corner`,
/// `corner + 1`, … in `data` (a padded grid `width` wide), in plain arithmetic.
fn lane_sums(data: &[f32], width: usize, corner: usize) -> [f32; LANES] {
    let g = off_diagonal();
    let mut total = [0.0f32; LANES];
    for dy in 0..SIDE {
        let row = &data[corner + dy * width..][..SPAN];
        let weights = &g[dy * SIDE..][..SIDE];
        let mut part = [0.0f32; LANES];
        for (dx, &w) in weights.iter().enumerate() {
            for (lane, p) in part.iter_mut().enumerate() {
                *p += w * row[dx + lane];
            }
        }
        for (t, p) in total.iter_mut().zip(part) {
            *t += p;
        }
    }
    total
}

/// [`lane_sums`] in AVX2 with fused multiply–adds: each weight broadcast and multiplied into
/// the eight cells' values at once, over four independent partial sums per stencil row (so
/// that the additions do not wait on one another).
#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::{off_diagonal, LANES, SIDE, SPAN};
    use std::arch::x86_64::*;

    #[target_feature(enable = "avx2,fma")]
    pub(super) fn lane_sums(data: &[f32], width: usize, corner: usize) -> [f32; LANES] {
        let g = off_diagonal();
        assert!(g.len() == SIDE * SIDE && corner + (SIDE - 1) * width + SPAN <= data.len());
        let mut out = [0.0f32; LANES];
        // SAFETY: every read lies within `data` and `g` (asserted above: the last row read
        // ends at corner + (SIDE − 1)·width + SPAN); `out` holds LANES values.
        unsafe {
            let mut total = _mm256_setzero_ps();
            for dy in 0..SIDE {
                let row = data.as_ptr().add(corner + dy * width);
                let w = g.as_ptr().add(dy * SIDE);
                let mut acc = [_mm256_setzero_ps(); 4];
                let mut dx = 0;
                while dx + 4 <= SIDE {
                    for (j, a) in acc.iter_mut().enumerate() {
                        let weight = _mm256_broadcast_ss(&*w.add(dx + j));
                        *a = _mm256_fmadd_ps(weight, _mm256_loadu_ps(row.add(dx + j)), *a);
                    }
                    dx += 4;
                }
                while dx < SIDE {
                    let weight = _mm256_broadcast_ss(&*w.add(dx));
                    acc[0] = _mm256_fmadd_ps(weight, _mm256_loadu_ps(row.add(dx)), acc[0]);
                    dx += 1;
                }
                let part =
                    _mm256_add_ps(_mm256_add_ps(acc[0], acc[1]), _mm256_add_ps(acc[2], acc[3]));
                total = _mm256_add_ps(total, part);
            }
            _mm256_storeu_ps(out.as_mut_ptr(), total);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plain sum, a cell at a time, on the unpadded grid (f64).
    fn naive(v: &[f64], nx: usize, ny: usize, i: usize) -> f64 {
        let g = off_diagonal();
        let t = TRUNCATION;
        let (ix, iy) = ((i % nx) as i64, (i / nx) as i64);
        let mut acc = 0.0;
        for oy in -t..=t {
            for ox in -t..=t {
                let (x, y) = (ix + ox, iy + oy);
                if x >= 0 && y >= 0 && x < nx as i64 && y < ny as i64 {
                    let w = g[((oy + t) * (2 * t + 1) + ox + t) as usize] as f64;
                    acc += w * v[y as usize * nx + x as usize];
                }
            }
        }
        acc
    }

    #[test]
    fn runs_group_consecutive_cells_of_a_row() {
        let nx = 10;
        let cells = [3, 4, 5, 9, 10, 11, 25, 27];
        assert_eq!(
            runs(&cells, nx),
            vec![
                Run {
                    y: 0,
                    x0: 3,
                    len: 3
                },
                Run {
                    y: 0,
                    x0: 9,
                    len: 1
                },
                Run {
                    y: 1,
                    x0: 0,
                    len: 2
                },
                Run {
                    y: 2,
                    x0: 5,
                    len: 1
                },
                Run {
                    y: 2,
                    x0: 7,
                    len: 1
                },
            ]
        );
    }

    /// v on an nx × ny grid (a third of it zero), the cells all but most of every fifth,
    /// and the largest difference of `sums` from the plain sums, relative to 1 + |sum|.
    fn worst_difference(nx: usize, ny: usize, sums: impl Fn(&Padded, &[Run], &mut [f32])) -> f64 {
        let n = nx * ny;
        let values: Vec<f64> = (0..n)
            .map(|i| ((i * 7919 % 101) as f64 / 101.0) * if i % 3 == 0 { 0.0 } else { 1.0 })
            .collect();
        let mut v = Padded::new(nx, ny);
        for (i, &x) in values.iter().enumerate() {
            v.set(i, x as f32);
        }
        let cells: Vec<usize> = (0..n).filter(|i| i % 5 != 0 || i % 7 == 0).collect();
        let r = runs(&cells, nx);
        let mut out = vec![0.0; cells.len()];
        sums(&v, &r, &mut out);
        cells
            .iter()
            .zip(&out)
            .map(|(&i, &got)| {
                let want = naive(&values, nx, ny, i);
                (got as f64 - want).abs() / (1.0 + want.abs())
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn the_vector_sums_equal_the_plain_ones_at_every_cell_edges_included() {
        // A grid lower than a stencil and wider than one, so that cells see every edge; runs
        // of every length; then one large enough for the pool's threads.
        for (nx, ny) in [(45, 13), (120, 50)] {
            let fastest = worst_difference(nx, ny, apply);
            // The plain arithmetic, as on a CPU without AVX2 and FMA.
            let plain = worst_difference(nx, ny, |v, r, o| {
                each_lane_group(v, r, o, |corner| lane_sums(&v.data, v.width, corner))
            });
            for (what, d) in [("fastest", fastest), ("plain", plain)] {
                assert!(d < 1e-6, "{nx}×{ny}, {what}: differs by {d:e}");
            }
        }
    }
}
