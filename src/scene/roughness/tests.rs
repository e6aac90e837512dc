use super::stats::modes;
use super::*;
use crate::params::SEED;
use std::f64::consts::PI;

/// Relative difference of `a` from `b`.
fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// A 256² surface at unit spacing with H = `hurst`, roll-off 32 and cut-off 4 (spacings).
fn band_256(hurst: f64, seed: u64) -> RoughnessParams {
    RoughnessParams {
        rolloff: Some(32.0),
        cutoff: Some(4.0),
        seed,
        ..RoughnessParams::with_rms_height(256, 1.0, hurst, 1.0)
    }
}

#[test]
fn rms_height_and_slope_are_met_exactly_and_the_mean_is_zero() {
    // Square, non-square, odd and even sides: the rescaling is exact, so only rounding is left.
    for (nx, ny, hurst, seed) in [(64, 64, 0.8, 1), (64, 32, 0.3, 2), (45, 30, 1.0, 3)] {
        let height = RoughnessParams {
            grid_y: Some(ny),
            seed,
            ..RoughnessParams::with_rms_height(nx, 0.5, hurst, 0.37)
        };
        let map = generate(&height).unwrap();
        assert_eq!((map.nx(), map.ny()), (nx, ny));
        let s = statistics(&map);
        assert!(rel(s.rms_height, 0.37) < 1e-9, "{s:?}");
        assert!(s.mean.abs() < 1e-12 * s.rms_height, "{s:?}");
        let slope = RoughnessParams {
            rms_height: None,
            rms_slope: Some(0.2),
            ..height
        };
        let map = generate(&slope).unwrap();
        let s = statistics(&map);
        assert!(rel(s.rms_slope, 0.2) < 1e-9, "{s:?}");
        assert!(rel(rms_slope(&map), 0.2) < 1e-9);
        assert!(s.mean.abs() < 1e-12 * s.rms_height, "{s:?}");
    }
}

/// The least-squares slope of ln C against ln q over the independent modes (kx > 0 and
/// below the Nyquist column: their conjugates are not counted again) with `lo ≤ q ≤ hi`, and
/// its standard error. For a Gaussian surface |Z|² is exponential, so ln C scatters about
/// its mean law with variance π²/6 whatever the level: the error is √(π²/6 / Σ(x − x̄)²).
fn fitted_slope(map: &HeightMap, lo: f64, hi: f64) -> (f64, f64, usize) {
    let points: Vec<(f64, f64)> = modes(map)
        .into_iter()
        .filter(|m| m.weight == 2.0 && m.q >= lo && m.q <= hi)
        .map(|m| (m.q.ln(), m.psd.ln()))
        .collect();
    let n = points.len() as f64;
    let xm = points.iter().map(|p| p.0).sum::<f64>() / n;
    let ym = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - xm).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - xm) * (p.1 - ym)).sum();
    (sxy / sxx, (PI * PI / 6.0 / sxx).sqrt(), points.len())
}

#[test]
fn the_spectrum_falls_as_q_to_minus_two_one_plus_h_and_is_flat_below_the_rolloff() {
    for (hurst, seed) in [(0.3, 11), (0.8, 12), (1.0, 13)] {
        let map = generate(&band_256(hurst, seed)).unwrap();
        let (q_r, q_s) = (2.0 * PI / 32.0, 2.0 * PI / 4.0);
        // Thousands of modes: the standard error is about 0.03; 5 of them bound a chance miss
        // at 6e-7.
        let (slope, se, n) = fitted_slope(&map, q_r, q_s);
        assert!(n > 5000, "{n} modes");
        let expected = -2.0 * (1.0 + hurst);
        assert!(
            (slope - expected).abs() < 5.0 * se,
            "H = {hurst}: slope {slope} ± {se} over {n} modes, expected {expected}"
        );
        // The plateau from the domain's fundamental to the roll-off: flat.
        let (flat, se, n) = fitted_slope(&map, 2.0 * PI / 256.0, q_r * (1.0 - 1e-9));
        assert!(n > 80, "{n} modes");
        assert!(
            flat.abs() < 5.0 * se,
            "plateau slope {flat} ± {se} ({n} modes)"
        );
    }
}

#[test]
fn there_is_no_power_outside_the_band_so_no_leakage() {
    // λ_L half the domain: the fundamentals lie below q_L and must stay empty.
    let params = RoughnessParams {
        largest_wavelength: Some(128.0),
        rolloff: Some(64.0),
        cutoff: Some(8.0),
        ..band_256(0.7, 5)
    };
    let map = generate(&params).unwrap();
    let (q_l, q_s) = (2.0 * PI / 128.0, 2.0 * PI / 8.0);
    let all = modes(&map);
    let top = all.iter().map(|m| m.psd).fold(0.0, f64::max);
    let mut inside = 0;
    for m in &all {
        if m.q < q_l * (1.0 - 1e-6) || m.q > q_s * (1.0 + 1e-6) {
            // Only the rounding of two transforms is left there.
            assert!(m.psd < 1e-20 * top, "q = {}: C = {} of {top}", m.q, m.psd);
        } else {
            inside += 1;
            assert!(
                m.psd > 1e-20 * top,
                "an empty mode inside the band, q = {}",
                m.q
            );
        }
    }
    assert!(inside > 1000, "{inside}");
    // The band's edges are inside it: the modes at exactly q_L and q_s have power.
    for edge in [q_l, q_s] {
        assert!(all
            .iter()
            .any(|m| rel(m.q, edge) < 1e-12 && m.psd > 1e-20 * top));
    }
}

#[test]
fn the_same_seed_gives_the_same_surface_and_another_seed_another() {
    let a = generate(&band_256(0.5, 7)).unwrap();
    let b = generate(&band_256(0.5, 7)).unwrap();
    assert_eq!(a.heights(), b.heights(), "bit for bit on one machine");
    let c = generate(&band_256(0.5, 8)).unwrap();
    let largest = a
        .heights()
        .iter()
        .zip(c.heights())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(largest > 0.5, "seeds 7 and 8 differ by at most {largest}");
    // Independent surfaces: their correlation over the nodes is of order 1/√(modes), far
    // below 0.5 with the band's thousands of modes.
    let rho: f64 = a
        .heights()
        .iter()
        .zip(c.heights())
        .map(|(x, y)| x * y)
        .sum::<f64>()
        / (256.0 * 256.0);
    assert!(rho.abs() < 0.5, "correlation {rho}");
}

/// Golden values, computed once with this generator and stored: the generator is defined by
/// its algorithm (pcg64 from the seed, Box–Muller, the fill order, the filter, the FFT), so
/// these numbers are what it must give on every machine, to the rounding of the transforms
/// and of `ln`/`sin`/`cos` (a relative 1e-15 or so, checked to 1e-12 of the rms height). A
/// change here is a change of the generator: bump [`GENERATOR_VERSION`].
#[test]
fn golden_values_pin_the_algorithm() {
    // The uniform stream is pcg64's, exactly (integers: no rounding).
    let mut n = noise::Normals::new(0);
    assert_eq!(n.next_u64(), GOLDEN_U64[0]);
    assert_eq!(n.next_u64(), GOLDEN_U64[1]);
    let (g1, g2) = noise::Normals::new(42).pair();
    assert!((g1 - GOLDEN_NORMALS[0]).abs() < 1e-14, "{g1}");
    assert!((g2 - GOLDEN_NORMALS[1]).abs() < 1e-14, "{g2}");
    let params = RoughnessParams {
        grid_y: Some(8),
        seed: 2024,
        cutoff: Some(2.0),
        ..RoughnessParams::with_rms_height(16, 1.0, 0.7, 1.0)
    };
    let map = generate(&params).unwrap();
    for (k, expected) in GOLDEN_HEIGHTS {
        let h = map.heights()[k];
        assert!(
            (h - expected).abs() < 1e-12,
            "node {k}: {h:.17} against {expected:.17}"
        );
    }
}

/// The first two outputs of pcg64 seeded with 0.
/// (PCG's reference `pcg64` with state 0 and its default stream gives the same two.)
const GOLDEN_U64: [u64; 2] = [14734495297819468440, 10563326859733236824];
/// The first Box–Muller pair of seed 42.
const GOLDEN_NORMALS: [f64; 2] = [-1.111298573894142, -0.4020967870375027];
/// Heights (index, value) of the 16 × 8 surface of the golden test.
const GOLDEN_HEIGHTS: [(usize, f64); 4] = [
    (0, 0.5074889035262419),
    (5, 1.964089138992731),
    (37, 1.3698270743114445),
    (127, 1.1972805553682004),
];

/// Periodic central differences of the map: ⟨|∇h|²⟩ and ⟨(½∇²h)²⟩ (five-point Laplacian).
fn finite_differences(map: &HeightMap) -> (f64, f64) {
    let (nx, ny, dx) = (map.nx(), map.ny(), map.spacing());
    let h = |i: usize, j: usize| map.heights()[(j % ny) * nx + i % nx];
    let (mut g2, mut c2) = (0.0, 0.0);
    for j in 0..ny {
        for i in 0..nx {
            let gx = (h(i + 1, j) - h(i + nx - 1, j)) / (2.0 * dx);
            let gy = (h(i, j + 1) - h(i, j + ny - 1)) / (2.0 * dx);
            g2 += gx * gx + gy * gy;
            let lap = (h(i + 1, j) + h(i + nx - 1, j) + h(i, j + 1) + h(i, j + ny - 1)
                - 4.0 * h(i, j))
                / (dx * dx);
            c2 += 0.25 * lap * lap;
        }
    }
    let n = (nx * ny) as f64;
    (g2 / n, c2 / n)
}

#[test]
fn spectral_slope_and_curvature_agree_with_finite_differences_on_a_fine_grid() {
    // The shortest wave spans 32 spacings. A central difference sees a mode of wavenumber q
    // along an axis as sin(qΔ)/Δ, so the finite-difference rms slope lies between
    // √(1 − (q_s Δ)²/3) and 1 times the spectral one (sin²x/x² ≥ 1 − x²/3); the five-point
    // Laplacian sees q² as (2 sin(qΔ/2)/Δ)², so its rms curvature lies between
    // 1 − (q_s Δ)²/12 and 1 times the spectral one. Here q_s Δ = 2π/32.
    let params = RoughnessParams {
        rolloff: Some(128.0),
        cutoff: Some(32.0),
        rms_height: None,
        rms_slope: Some(0.1),
        ..band_256(0.5, 21)
    };
    let map = generate(&params).unwrap();
    let s = statistics(&map);
    let (g2, c2) = finite_differences(&map);
    let x = 2.0 * PI / 32.0;
    let slope = g2.sqrt() / s.rms_slope;
    assert!(
        slope <= 1.0 + 1e-12 && slope >= (1.0 - x * x / 3.0).sqrt(),
        "finite-difference rms slope {} against spectral {}",
        g2.sqrt(),
        s.rms_slope
    );
    let curvature = c2.sqrt() / s.rms_curvature;
    assert!(
        curvature <= 1.0 + 1e-12 && curvature >= 1.0 - x * x / 12.0,
        "finite-difference rms curvature {} against spectral {}",
        c2.sqrt(),
        s.rms_curvature
    );
}

#[test]
fn the_radial_psd_adds_up_to_the_variance() {
    // Parseval: ⟨h²⟩ = (1/A) Σ C over every mode, which the bins hold with their counts.
    let map = generate(&band_256(0.6, 3)).unwrap();
    let bins = radial_psd(&map, 40);
    assert!(bins.len() > 20 && bins.len() <= 40);
    let area = 256.0 * 256.0;
    let total: f64 = bins.iter().map(|b| b.psd * b.modes as f64).sum::<f64>() / area;
    assert!(rel(total, rms_height(&map).powi(2)) < 1e-9, "{total}");
    assert_eq!(bins.iter().map(|b| b.modes).sum::<usize>(), 256 * 256 - 1);
    assert!(bins.windows(2).all(|w| w[0].q < w[1].q));
    assert!(radial_psd(&map, 0).is_empty());
}

#[test]
fn bad_parameters_are_refused_naming_them() {
    let good = RoughnessParams::with_rms_height(64, 1.0, 0.8, 1.0);
    assert!(good.validate().is_ok());
    let cases: Vec<(RoughnessParams, &Spec)> = vec![
        (
            RoughnessParams {
                grid: 3,
                ..good.clone()
            },
            GRID,
        ),
        (
            RoughnessParams {
                grid_y: Some(20000),
                ..good.clone()
            },
            GRID_Y,
        ),
        (
            RoughnessParams {
                grid: 16384,
                grid_y: Some(16384),
                ..good.clone()
            },
            GRID,
        ),
        (
            RoughnessParams {
                spacing: 0.0,
                ..good.clone()
            },
            SPACING,
        ),
        (
            RoughnessParams {
                spacing: f64::NAN,
                ..good.clone()
            },
            SPACING,
        ),
        (
            RoughnessParams {
                hurst: 0.0,
                ..good.clone()
            },
            HURST,
        ),
        (
            RoughnessParams {
                hurst: 1.2,
                ..good.clone()
            },
            HURST,
        ),
        (
            RoughnessParams {
                hurst: f64::NAN,
                ..good.clone()
            },
            HURST,
        ),
        (
            RoughnessParams {
                rms_height: Some(-1.0),
                ..good.clone()
            },
            RMS_HEIGHT,
        ),
        (
            RoughnessParams {
                rms_height: None,
                ..good.clone()
            },
            RMS_HEIGHT,
        ),
        (
            RoughnessParams {
                rms_slope: Some(0.1),
                ..good.clone()
            },
            RMS_SLOPE,
        ),
        (
            RoughnessParams {
                rms_height: None,
                rms_slope: Some(f64::INFINITY),
                ..good.clone()
            },
            RMS_SLOPE,
        ),
        (
            RoughnessParams {
                cutoff: Some(1.5),
                ..good.clone()
            },
            CUTOFF,
        ),
        (
            RoughnessParams {
                cutoff: Some(64.0),
                ..good.clone()
            },
            CUTOFF,
        ),
        (
            RoughnessParams {
                rolloff: Some(65.0),
                ..good.clone()
            },
            ROLLOFF,
        ),
        (
            RoughnessParams {
                rolloff: Some(3.0),
                ..good.clone()
            },
            ROLLOFF,
        ),
        (
            RoughnessParams {
                largest_wavelength: Some(100.0),
                ..good.clone()
            },
            LARGEST_WAVELENGTH,
        ),
        // A band between two of the grid's modes: wavelengths from 58 to 60 on a domain of 64.
        (
            RoughnessParams {
                largest_wavelength: Some(60.0),
                cutoff: Some(58.0),
                ..good.clone()
            },
            CUTOFF,
        ),
    ];
    for (params, spec) in cases {
        let e = params.validate().unwrap_err();
        assert_eq!(e.param(), spec, "{params:?}: {e}");
        assert!(e.to_string().contains(&spec.to_string()), "{e}");
        assert!(e.to_string().len() < 400, "{e}");
        assert_eq!(generate(&params).unwrap_err().to_string(), e.to_string());
    }
    // The Nyquist wavelength itself is accepted, and the seed takes any u64.
    let nyquist = RoughnessParams {
        cutoff: Some(2.0),
        seed: u64::MAX,
        ..good.clone()
    };
    assert!(generate(&nyquist).is_ok());
    assert_eq!(SEED.name, "seed");
}

#[test]
fn the_shortest_wavelength_is_the_cut_off_of_a_band_and_long_for_a_smooth_tip() {
    // Band-limited surfaces: their cut-off within a tenth (the window spreads each mode over
    // a few neighbours, so a band's edge blurs by that much), whatever H.
    for (hurst, cutoff) in [(0.8, 4.0), (0.8, 16.0), (0.3, 8.0), (1.0, 8.0)] {
        let params = RoughnessParams {
            cutoff: Some(cutoff),
            seed: 5,
            ..band_256(hurst, 5)
        };
        let l = shortest_wavelength(&generate(&params).unwrap());
        assert!(
            (0.9 * cutoff..=1.1 * cutoff).contains(&l),
            "H = {hurst}, cut-off {cutoff}: shortest wavelength {l}"
        );
    }
    // A paraboloid sampled as a map (not periodic: its edges jump) holds nothing short: the
    // window keeps the jump out of the spectrum.
    let n = 129;
    let h: Vec<f64> = (0..n * n)
        .map(|k| {
            let (x, y) = ((k % n) as f64 - 64.0, (k / n) as f64 - 64.0);
            (x * x + 2.0 * y * y) / 200.0
        })
        .collect();
    let tip = HeightMap::new(n, n, 1.0, h).unwrap();
    let l = tip.shortest_wavelength();
    assert!(l > 20.0, "paraboloid: shortest wavelength {l} spacings");
    // Noise on every node: two spacings.
    let mut noise = super::noise::Normals::new(3);
    let h: Vec<f64> = (0..64 * 64).map(|_| noise.pair().0).collect();
    let l = shortest_wavelength(&HeightMap::new(64, 64, 0.5, h).unwrap());
    assert!((1.0..1.5).contains(&l), "white noise: {l}");
}

#[test]
fn the_carrying_wavelength_is_a_wavy_spheres_waviness_and_absent_for_a_smooth_tip() {
    // R = 1 with waviness 0.02·cos(2πx/0.3)·cos(2πy/0.3) on 901² nodes 0.01 apart (issue 55,
    // item 13): the sphere's slope hides the waviness from the shortest wavelength; the
    // surface less its quadratic carries it (its ring blurs by a ring width, 1/9.01).
    let n = 901;
    let wavy = |amplitude: f64| {
        let h: Vec<f64> = (0..n * n)
            .map(|k| {
                let (x, y) = (
                    ((k % n) as f64 - 450.0) * 0.01,
                    ((k / n) as f64 - 450.0) * 0.01,
                );
                0.5 * (x * x + y * y)
                    + amplitude * (2.0 * PI * x / 0.3).cos() * (2.0 * PI * y / 0.3).cos()
            })
            .collect();
        HeightMap::new(n, n, 0.01, h).unwrap()
    };
    let map = wavy(0.02);
    let l = map.carrying_wavelength().expect("a waviness");
    // cos·cos holds the wavevector (±1, ±1)·2π/0.3: |q| = √2·2π/0.3, a wavelength 0.3/√2.
    let expected = 0.3 / 2f64.sqrt();
    assert!(
        rel(l, expected) < 0.1,
        "carrying wavelength {l}, not {expected}"
    );
    assert!(
        map.shortest_wavelength() > 1.5 * l,
        "the shortest-wavelength rule already saw it: {}",
        map.shortest_wavelength()
    );
    // The sphere alone (and a tilted ellipsoid) is its quadratic: nothing carried.
    assert_eq!(wavy(0.0).carrying_wavelength(), None);
    let h: Vec<f64> = (0..64 * 64)
        .map(|k| {
            let (x, y) = ((k % 64) as f64, (k / 64) as f64);
            0.01 * x * x + 0.03 * y * y + 0.002 * x * y + 0.1 * x + 3.0
        })
        .collect();
    assert_eq!(
        HeightMap::new(64, 64, 1.0, h)
            .unwrap()
            .carrying_wavelength(),
        None
    );
    // A band of roughness: its slope spreads over many rings, so only its long wavelengths
    // (which hold its height) count: at least a sixteenth of the map, far above its cut-off.
    let params = RoughnessParams {
        cutoff: Some(4.0),
        seed: 5,
        ..band_256(0.8, 5)
    };
    let rough = generate(&params).unwrap();
    let l = rough.carrying_wavelength().expect("roughness");
    assert!(l >= 16.0 * rough.spacing(), "rough band: {l}");
}

/// The memory check refuses a surface past what is available, naming ⟨grid⟩ (and ⟨grid_y⟩
/// where given) with the largest surface of the same shape that fits, which itself fits.
#[test]
fn the_memory_check_names_the_grid_and_the_largest_that_fits() {
    let big = RoughnessParams::with_rms_height(4096, 1.0, 0.8, 1.0);
    assert_eq!(big.memory_estimate(), 4096 * 4096 * 32 + (16 << 20));
    assert!(big.check_memory_within(None).is_ok());
    assert!(big.check_memory_within(Some(big.memory_estimate())).is_ok());
    let e = big
        .check_memory_within(Some(100_000_000))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with(&format!("{GRID} = 4096 is invalid")), "{e}");
    assert!(
        e.contains(&format!("the largest that fits is {GRID} 1612")),
        "{e}"
    );
    assert!(memory_estimate(1612, 1612) <= 100_000_000);
    assert!(memory_estimate(1613, 1613) > 100_000_000);
    let wide = RoughnessParams {
        grid_y: Some(1024),
        ..big.clone()
    };
    let e = wide
        .check_memory_within(Some(100_000_000))
        .unwrap_err()
        .to_string();
    assert!(e.contains(&format!("{GRID} 3225 {GRID_Y} 806")), "{e}");
    let e = big
        .check_memory_within(Some(1 << 20))
        .unwrap_err()
        .to_string();
    assert!(e.contains("not even the smallest surface"), "{e}");
}
