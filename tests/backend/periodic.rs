//! The periodic convolution (`backend::kernel`'s notes): a single Fourier mode of pressure
//! gets the continuum displacement 2/(E*|q|) within the element's discretisation error, and a
//! compact patch far from the edges the padded (isolated) displacement plus its images'.

use crate::common::flat_setup as setup;
use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::prelude::*;
use std::f64::consts::PI;

fn convolve(b: &mut CpuBackend, p: &[f64]) -> Vec<f64> {
    let mut f = b.field().unwrap();
    b.upload(&mut f, p).unwrap();
    let mut u = b.field().unwrap();
    b.convolve(&f, &mut u).unwrap();
    let mut out = vec![0.0; p.len()];
    b.download(&u, &mut out).unwrap();
    out
}

#[test]
fn a_single_fourier_mode_gets_the_continuum_displacement() {
    let (nx, ny, dx, e) = (64, 32, 0.2, 2.5);
    let mut b = CpuBackend::new_periodic(&setup(nx, ny, dx, e)).unwrap();
    for (kx, ky) in [(1, 0), (0, 1), (2, 1), (3, 5), (8, 0)] {
        let q = [
            2.0 * PI * kx as f64 / (nx as f64 * dx),
            2.0 * PI * ky as f64 / (ny as f64 * dx),
        ];
        let qn = (q[0] * q[0] + q[1] * q[1]).sqrt();
        let p: Vec<f64> = (0..nx * ny)
            .map(|i| {
                let (x, y) = ((i % nx) as f64 * dx, (i / nx) as f64 * dx);
                (q[0] * x + q[1] * y + 0.3).cos()
            })
            .collect();
        let u = convolve(&mut b, &p);
        let continuum = 2.0 / (e * qn);
        // The mode is an eigenvector: u = K̃ p everywhere, with K̃ the continuum's within the
        // element's error, (qΔx)²/24 along an axis (the sinc of uniform pressure on Δx).
        let ratio = u.iter().zip(&p).map(|(a, b)| a * b).sum::<f64>()
            / p.iter().map(|v| v * v).sum::<f64>();
        let off = u
            .iter()
            .zip(&p)
            .fold(0.0f64, |m, (a, b)| m.max((a - ratio * b).abs()));
        assert!(
            off < 1e-12 * continuum,
            "({kx}, {ky}): not an eigenvector, {off}"
        );
        let dev = 1.0 - ratio / continuum;
        let element = (qn * dx).powi(2) / 24.0;
        println!(
            "mode ({kx}, {ky}), qΔx = {:.4}: K̃/(2/(E*|q|)) − 1 = {:+.3e} (element term \
             −(qΔx)²/24 = {:+.3e})",
            qn * dx,
            -dev,
            -element
        );
        assert!(
            dev > 0.0 && dev < 1.5 * element,
            "({kx}, {ky}): {dev} vs {element}"
        );
    }
}

#[test]
fn a_compact_patch_gets_the_padded_displacement_plus_its_images() {
    // Uniform pressure on a 4 × 4 patch in the middle of a 128² periodic domain: its
    // displacement is the isolated (padded) one plus that of its images, less the mean. Near
    // the patch the images add (P/(πE*))·Σ'_n 1/|x − nL| ≈ const + P S₃ |x − x₀|²/(4πE* L³),
    // S₃ = Σ' 1/|n|³ = 4ζ(3/2)β(3/2) over the square lattice (the images' Hessian summed:
    // Σ' ∂²(1/r)/∂x² = S₃/(2L³)).
    let (n, dx, e) = (128usize, 0.5, 1.3);
    let l = n as f64 * dx;
    let side = 4;
    let lo = n / 2 - side / 2;
    let mut p = vec![0.0; n * n];
    for j in lo..lo + side {
        for i in lo..lo + side {
            p[j * n + i] = 1.0;
        }
    }
    let force = (side * side) as f64 * dx * dx;
    let padded = convolve(&mut CpuBackend::new(&setup(n, n, dx, e)).unwrap(), &p);
    let periodic = convolve(
        &mut CpuBackend::new_periodic(&setup(n, n, dx, e)).unwrap(),
        &p,
    );
    let scale = padded.iter().fold(0.0f64, |m, v| m.max(*v));
    let mean = periodic.iter().sum::<f64>() / (n * n) as f64;
    assert!(
        mean.abs() < 1e-12 * scale,
        "the periodic displacement's mean is {mean}"
    );
    let s3 = 4.0 * 2.612_375_348_685_488 * 0.864_502_653_461_202;
    // The patch's centre is the corner shared by the four middle elements.
    let centre = n / 2;
    let diff = |i: usize, j: usize| periodic[j * n + i] - padded[j * n + i];
    let at_centre = 0.25
        * (diff(centre, centre)
            + diff(centre - 1, centre)
            + diff(centre, centre - 1)
            + diff(centre - 1, centre - 1));
    let r2_centre = 0.5 * dx * dx; // the four middle elements lie Δx/√2 from it
    let images = |r2: f64| force * s3 * r2 / (4.0 * PI * e * l.powi(3));
    let mut worst: f64 = 0.0;
    let mut largest: f64 = 0.0;
    for j in lo - 12..lo + side + 12 {
        for i in lo - 12..lo + side + 12 {
            let (x, y) = (
                (i as f64 + 0.5 - centre as f64) * dx,
                (j as f64 + 0.5 - centre as f64) * dx,
            );
            let want = images(x * x + y * y) - images(r2_centre);
            let got = diff(i, j) - at_centre;
            worst = worst.max((got - want).abs());
            largest = largest.max(want.abs());
        }
    }
    // Within 20 elements of the centre (r ≤ L/6) the next terms, O((r/L)⁴), are below 5 %
    // of the quadratic one; the images' variation itself is small against the displacement.
    println!(
        "patch in 128²: images' variation up to {:.3e} (of a peak displacement {:.3e}); the \
         quadratic estimate misses by {:.3e} ({:.2} %)",
        largest,
        scale,
        worst,
        100.0 * worst / largest
    );
    assert!(worst < 0.05 * largest, "{worst} vs {largest}");
    assert!(
        largest > 1e-4 * scale,
        "the images' effect should show: {largest}"
    );
}
