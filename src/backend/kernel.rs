//! Love's influence coefficients for uniform pressure on square elements, laid out for
//! the zero-padded (non-periodic) FFT convolution; the same elements' influence on a surface
//! periodic over the domain ([`periodic_symbol`]); and the preconditioner's stiffness.
//!
//! # The periodic operator
//!
//! A surface periodic over the domain Lx × Ly = nx Δx × ny Δx (a nominally flat rough
//! surface, a wave) carries a periodic pressure, and its displacement at element i is the sum
//! over every image of every element: u_i = Σ_j Σ_n K(x_i − x_j − n∘L) p_j, with K Love's
//! element kernel ([`influence`]), the one the padded convolution sums over the domain alone.
//! On the periodic grid this is a circular convolution whose symbol (the DFT of the
//! image-summed kernel) follows from Poisson's summation: the element kernel is the point
//! load's Green function 1/(π E* r), of Fourier transform 2/(E*|q|), smeared over the square
//! element, of transform Δx² S(q) with S(q) = sinc(qx Δx/2)·sinc(qy Δx/2) (sinc t = sin t / t);
//! sampling it at the element centres (spacing Δx) aliases every wavenumber q + 2π m/Δx onto
//! q, so that
//!
//! K̃(q) = Σ_{m ∈ ℤ²} 2/(E*|q_m|) · S(q_m),   q_m = q + 2π m/Δx,
//!
//! at the lattice's wavenumbers q = 2π (kx/Lx, ky/Ly). This is exactly the padded operator's
//! element kernel with its images added: for a pressure confined to a patch far from the
//! domain's edges the two differ only by the images' displacement (and a constant, below).
//! The continuum symbol 2/(E*|q|) alone (Tamaas's choice) or times S(q) (the m = 0 term)
//! differ from it at the neighbours by 8 % and at the element itself by 17 % (measured on
//! 16², Δx = 1), and the Pohrt–Popov detachment stress σ_c is calibrated on Love's element
//! (physics §5): only the full sum keeps the criterion the padded runs use. For small q it
//! is 2/(E*|q|)·(1 − (qΔx)²/24 + O(|qΔx|³)) along an axis: a single Fourier mode of pressure
//! gets the continuum displacement within the element's discretisation error.
//!
//! The sum over m converges as an alternating series (the sincs change sign with m): it is
//! taken over |mx|, |my| ≤ M with the outermost terms halved (the end correction of an
//! alternating sum), whose error falls as M⁻⁴, and the results at M = [`ALIAS_REACH`] and
//! M/2 are extrapolated (Richardson): within 1e-7 relative of the converged symbol.
//!
//! The mean (q = 0). A periodic pressure of non-zero mean on a half-space has no finite
//! displacement (the images' loads add up without bound), so the q = 0 term is set to zero:
//! the displacement has zero mean over the domain, and the approach d is measured from the
//! mean plane of the elastic surface (Tamaas's convention): the gap g = h − d + u then has the
//! mean h̄ − d. The operator is positive semi-definite with the constants as its null space;
//! restricted to a contact set C short of the whole domain it is positive definite, so CG
//! solves it as it does the padded one. Full contact has a solution only at d = h̄.

use std::f64::consts::PI;

/// f(s, t) = s·ln(t + √(s²+t²)) + t·ln(s + √(s²+t²)), with 0·ln 0 taken as 0.
fn love_f(s: f64, t: f64) -> f64 {
    let r = (s * s + t * t).sqrt();
    let term = |a: f64, b: f64| if a == 0.0 { 0.0 } else { a * (b + r).ln() };
    term(s, t) + term(t, s)
}

/// Surface displacement (length) at offset (x, y) (length) from the centre of a square
/// element of side `dx` (length) under unit pressure, on a half-space of effective
/// modulus `e_star` (stress).
pub fn influence(x: f64, y: f64, dx: f64, e_star: f64) -> f64 {
    let a = 0.5 * dx;
    (love_f(x + a, y + a) - love_f(x + a, y - a) - love_f(x - a, y + a) + love_f(x - a, y - a))
        / (PI * e_star)
}

/// The influence kernel on the padded 2nx × 2ny grid (row-major, x fastest): offset
/// (i, j) element sizes, with negative offsets wrapped to the end. Units: length per
/// unit pressure.
pub fn padded_kernel(nx: usize, ny: usize, dx: f64, e_star: f64) -> Vec<f64> {
    let (px, py) = (2 * nx, 2 * ny);
    let offset = |k: usize, n: usize| {
        if k < n {
            k as f64
        } else {
            k as f64 - 2.0 * n as f64
        }
    };
    let mut out = vec![0.0; px * py];
    for j in 0..py {
        let y = offset(j, ny) * dx;
        for i in 0..px {
            out[j * px + i] = influence(offset(i, nx) * dx, y, dx, e_star);
        }
    }
    out
}

/// Direct O(N⁴) sum u_i = Σ_j K(x_i − x_j) p_j on an nx × ny grid: the oracle that the
/// FFT convolution is tested against.
pub fn direct_convolution(p: &[f64], nx: usize, ny: usize, dx: f64, e_star: f64) -> Vec<f64> {
    let mut u = vec![0.0; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            let mut s = 0.0;
            for l in 0..ny {
                for k in 0..nx {
                    let pk = p[l * nx + k];
                    if pk != 0.0 {
                        let x = (i as f64 - k as f64) * dx;
                        let y = (j as f64 - l as f64) * dx;
                        s += influence(x, y, dx, e_star) * pk;
                    }
                }
            }
            u[j * nx + i] = s;
        }
    }
    u
}

/// The reach M of the alias sum of [`periodic_symbol`] (see the module's notes).
pub const ALIAS_REACH: i64 = 16;

/// sin t / t, with 1 at t = 0.
fn sinc(t: f64) -> f64 {
    if t == 0.0 {
        1.0
    } else {
        t.sin() / t
    }
}

/// Σ over |mx|, |my| ≤ `reach` of 2/|q_m| · S(q_m) with the outermost terms halved, in units
/// of Δx (`tx`, `ty` = q Δx, the wavenumber times the element side; the result times Δx/E*
/// is the symbol).
fn alias_sum(tx: f64, ty: f64, reach: i64) -> f64 {
    let weight = |m: i64| if m.abs() == reach { 0.5 } else { 1.0 };
    let line = |t: f64| -> Vec<(f64, f64)> {
        (-reach..=reach)
            .map(|m| {
                let q = t + 2.0 * PI * m as f64;
                (q * q, weight(m) * sinc(0.5 * q))
            })
            .collect()
    };
    let (xs, ys) = (line(tx), line(ty));
    let mut sum = 0.0;
    for &(qy2, sy) in &ys {
        if sy == 0.0 {
            continue;
        }
        for &(qx2, sx) in &xs {
            if sx != 0.0 {
                sum += sx * sy / (qx2 + qy2).sqrt();
            }
        }
    }
    2.0 * sum
}

/// The symbol K̃(q) (length per unit pressure) of Love's element kernel summed over the
/// periodic images of an nx × ny domain of elements of side `dx` (length), for a half-space of
/// effective modulus `e_star` (stress), with K̃(0) = 0 (see the module's notes): laid out like
/// a real-to-complex spectrum, `(nx/2 + 1)` columns × `ny` rows, column-major (index
/// `kx * ny + ky`), unscaled (the filter divides by nx·ny).
pub fn periodic_symbol(nx: usize, ny: usize, dx: f64, e_star: f64) -> Vec<f64> {
    use rayon::prelude::*;
    let hx = nx / 2 + 1;
    let scale = dx / e_star;
    let mut s = vec![0.0; hx * ny];
    s.par_chunks_mut(ny).enumerate().for_each(|(kx, column)| {
        let tx = wavenumber(kx, nx, dx) * dx;
        // The symbol is even in qy: compute ky ≤ ny/2 and mirror.
        for ky in 0..=ny / 2 {
            if kx == 0 && ky == 0 {
                continue;
            }
            let ty = wavenumber(ky, ny, dx) * dx;
            let fine = alias_sum(tx, ty, ALIAS_REACH);
            let coarse = alias_sum(tx, ty, ALIAS_REACH / 2);
            let v = scale * (16.0 * fine - coarse) / 15.0;
            column[ky] = v;
            column[(ny - ky) % ny] = v;
        }
    });
    s
}

/// Wavenumber (1/length) of FFT bin `k` on a periodic grid of `n` points spaced `dx`.
pub fn wavenumber(k: usize, n: usize, dx: f64) -> f64 {
    let kk = if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    };
    2.0 * PI * kk / (n as f64 * dx)
}

/// Half-space stiffness symbol E*|q|/2 (stress per length) on the periodic nx × ny grid,
/// laid out like a real-to-complex spectrum: `(nx/2 + 1)` columns × `ny` rows, column-major
/// (index `kx * ny + ky`). The q = 0 mode takes the value of the smallest non-zero |q|.
pub fn stiffness_spectrum(nx: usize, ny: usize, dx: f64, e_star: f64) -> Vec<f64> {
    let hx = nx / 2 + 1;
    let qmin = wavenumber(1, nx, dx).min(wavenumber(1, ny, dx));
    let mut s = vec![0.0; hx * ny];
    for kx in 0..hx {
        let qx = wavenumber(kx, nx, dx);
        for ky in 0..ny {
            let qy = wavenumber(ky, ny, dx);
            let q = (qx * qx + qy * qy).sqrt().max(qmin);
            s[kx * ny + ky] = 0.5 * e_star * q;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn self_influence_matches_closed_form() {
        // (4/π)·ln(1+√2)·Δx/E* at the element's own centre.
        let (dx, e) = (0.3, 2.0);
        let expect = 4.0 / PI * (1.0 + 2f64.sqrt()).ln() * dx / e;
        assert!((influence(0.0, 0.0, dx, e) - expect).abs() < 1e-14);
    }

    /// The periodic symbol's kernel (real space, row-major nx × ny) by an inverse DFT.
    fn periodic_kernel_by_dft(nx: usize, ny: usize, dx: f64, e: f64) -> Vec<f64> {
        let sym = periodic_symbol(nx, ny, dx, e);
        // Real and even: K̃(kx, ky) = K̃(nx − kx, ky).
        let full = |kx: usize, ky: usize| sym[kx.min(nx - kx) * ny + ky];
        let mut out = vec![0.0; nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                let mut s = 0.0;
                for ky in 0..ny {
                    for kx in 0..nx {
                        let ph =
                            2.0 * PI * ((kx * i) as f64 / nx as f64 + (ky * j) as f64 / ny as f64);
                        s += full(kx, ky) * ph.cos();
                    }
                }
                out[j * nx + i] = s / (nx * ny) as f64;
            }
        }
        out
    }

    #[test]
    fn periodic_kernel_is_loves_summed_over_the_images() {
        // Brute force: Love's kernel summed over the images within R periods, less its mean.
        // That sum converges as 1/R; extrapolate R = 16, 32 to R → ∞.
        let (n, dx, e) = (8usize, 0.5, 2.0);
        let off = |k: usize| {
            if k <= n / 2 {
                k as f64
            } else {
                k as f64 - n as f64
            }
        };
        let images = |r: i64| {
            let mut k = vec![0.0; n * n];
            for j in 0..n {
                for i in 0..n {
                    let mut s = 0.0;
                    for a in -r..=r {
                        for b in -r..=r {
                            s += influence(
                                (off(i) + (a * n as i64) as f64) * dx,
                                (off(j) + (b * n as i64) as f64) * dx,
                                dx,
                                e,
                            );
                        }
                    }
                    k[j * n + i] = s;
                }
            }
            let mean = k.iter().sum::<f64>() / (n * n) as f64;
            k.iter().map(|v| v - mean).collect::<Vec<_>>()
        };
        let (k16, k32) = (images(16), images(32));
        let got = periodic_kernel_by_dft(n, n, dx, e);
        let self_term = influence(0.0, 0.0, dx, e);
        for i in 0..n * n {
            let extrapolated = 2.0 * k32[i] - k16[i];
            assert!(
                (got[i] - extrapolated).abs() < 2e-4 * self_term,
                "offset {i}: {} against the image sum {extrapolated} (R = 32: {})",
                got[i],
                k32[i]
            );
        }
        // Its mean is zero (the q = 0 convention).
        assert!(got.iter().sum::<f64>().abs() < 1e-12 * self_term);
    }

    #[test]
    fn periodic_symbol_is_the_continuum_one_for_long_waves() {
        // Along an axis K̃ = 2/(E*|q|)·(1 − (qΔx)²/24 + O(|qΔx|³)): the element's sinc.
        let (dx, e) = (0.1, 3.0);
        let mut last = f64::INFINITY;
        for n in [64usize, 128, 256, 512] {
            let sym = periodic_symbol(n, 4, dx, e);
            let q = wavenumber(1, n, dx);
            let ratio = sym[4] / (2.0 / (e * q));
            let c = (1.0 - ratio) / (q * dx).powi(2);
            let dev = (c - 1.0 / 24.0).abs();
            assert!(dev < 0.06 * q * dx, "n = {n}: (1 − K̃/K)/(qΔx)² = {c}");
            assert!(dev < last, "n = {n}: not converging to 1/24 ({c})");
            last = dev;
        }
    }

    #[test]
    fn periodic_symbol_alias_sum_has_converged() {
        // The extrapolated sum at the reach M against a far larger reach.
        for (tx, ty) in [(0.3, 0.0), (PI, PI), (1.0, 2.5), (0.01, PI)] {
            let reference = alias_sum(tx, ty, 256);
            let fine = alias_sum(tx, ty, ALIAS_REACH);
            let coarse = alias_sum(tx, ty, ALIAS_REACH / 2);
            let got = (16.0 * fine - coarse) / 15.0;
            assert!(
                (got / reference - 1.0).abs() < 2e-7,
                "q Δx = ({tx}, {ty}): {got} against {reference}"
            );
        }
    }

    #[test]
    fn far_field_is_point_load() {
        // Far away, uniform pressure on Δx² acts like a point load: u = Δx²/(π E* r).
        let (dx, e, r) = (1.0, 1.0, 200.0);
        let expect = dx * dx / (PI * e * r);
        assert!((influence(r, 0.0, dx, e) / expect - 1.0).abs() < 1e-5);
    }
}
