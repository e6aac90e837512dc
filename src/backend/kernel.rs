//! Love's influence coefficients for uniform pressure on square elements, laid out for
//! the zero-padded (non-periodic) FFT convolution, and the preconditioner's stiffness.

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

    #[test]
    fn far_field_is_point_load() {
        // Far away, uniform pressure on Δx² acts like a point load: u = Δx²/(π E* r).
        let (dx, e, r) = (1.0, 1.0, 200.0);
        let expect = dx * dx / (PI * e * r);
        assert!((influence(r, 0.0, dx, e) / expect - 1.0).abs() < 1e-5);
    }
}
