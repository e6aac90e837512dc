//! Statistics of a surface on a periodic grid: rms height, and, spectrally, rms slope, rms
//! curvature and the radially averaged power spectral density.
//!
//! The spectral ones are those of the band-limited periodic surface through the nodes: with
//! `H(k)` the unnormalised DFT of the heights on `N = nx·ny` nodes and `q(k)` the wavevector
//! of index `k` (the FFT's symmetric convention, `|k| ≤ n/2` per axis),
//! `⟨h²⟩ = Σ |H|² / N²`, `⟨|∇h|²⟩ = Σ |q|² |H|² / N²` and
//! `⟨(½∇²h)²⟩ = Σ (|q|²/2)² |H|² / N²`. The power spectral density is
//! `C(q) = Δ² |H|² / N` (length⁴, Δ the spacing), normalised so that
//! `⟨h²⟩ = (1/A) Σ_q C(q)` over the domain's area `A = N Δ²`, i.e. `∫ C d²q / (2π)²` in the
//! continuum limit.

use super::fft2::{wavenumber, weight, Fft2};
use crate::scene::height_map::HeightMap;
use serde::{Deserialize, Serialize};

/// A surface's statistics (every one about its mean).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Statistics {
    /// The mean height (length).
    pub mean: f64,
    /// The root-mean-square height about the mean over the nodes (length).
    pub rms_height: f64,
    /// The root-mean-square gradient magnitude `√⟨|∇h|²⟩`, spectral (dimensionless).
    pub rms_slope: f64,
    /// The root-mean-square mean curvature `√⟨(½∇²h)²⟩`, spectral (1/length).
    pub rms_curvature: f64,
}

/// One bin of a radially averaged power spectral density.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PsdBin {
    /// The mean wavenumber `|q|` of the bin's Fourier modes (1/length).
    pub q: f64,
    /// The mean power spectral density `C(q)` of those modes (length⁴).
    pub psd: f64,
    /// How many modes of the full spectrum the bin holds (a count).
    pub modes: usize,
}

/// One Fourier mode of the half spectrum: `|q|` (1/length), `C(q)` (length⁴) and how many
/// modes of the full spectrum it stands for (1 or 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Mode {
    /// `|q|` (1/length).
    pub q: f64,
    /// `C(q)` (length⁴).
    pub psd: f64,
    /// Modes of the full spectrum it stands for.
    pub weight: f64,
}

/// Every mode of the map's half spectrum but the mean (`q = 0`), with its PSD.
pub(super) fn modes(map: &HeightMap) -> Vec<Mode> {
    let (nx, ny, dx) = (map.nx(), map.ny(), map.spacing());
    let fft = Fft2::new(nx, ny);
    let spectrum = fft.forward(map.heights());
    let n = (nx * ny) as f64;
    let mut modes = Vec::with_capacity(spectrum.len());
    for kx in 0..fft.half() {
        let qx = wavenumber(kx, nx, dx);
        for ky in 0..ny {
            if kx == 0 && ky == 0 {
                continue;
            }
            let qy = wavenumber(ky, ny, dx);
            modes.push(Mode {
                q: qx.hypot(qy),
                psd: dx * dx * spectrum[kx * ny + ky].norm_sqr() / n,
                weight: weight(kx, nx),
            });
        }
    }
    modes
}

/// The fraction of a map's mean-square slope that its modes beyond its shortest wavelength
/// may hold ([`shortest_wavelength`]): a hundredth, so that bilinear interpolation on a grid
/// resolving that wavelength misses at most a tenth of the rms slope.
pub const SLOPE_TAIL: f64 = 0.01;

/// The shortest wavelength `map` holds (length): 2π/q_s, with q_s the smallest |q| beyond which
/// the modes hold at most [`SLOPE_TAIL`] of the mean-square slope. The map, less its mean, is
/// first multiplied by a Hann window along x and y, so that the jump between opposite edges
/// of a map that is not periodic adds no spurious power at short wavelengths. At least two
/// spacings (the shortest a lattice holds).
pub fn shortest_wavelength(map: &HeightMap) -> f64 {
    let floor = 2.0 * map.spacing();
    let mean = mean_and_rms(map.heights()).0;
    let centred: Vec<f64> = map.heights().iter().map(|h| h - mean).collect();
    let Some(windowed) = hann_windowed(map, centred) else {
        // A map flat after the window (e.g. a single sloped plane of two nodes): nothing short.
        return floor;
    };
    let mut slope: Vec<(f64, f64)> = modes(&windowed)
        .into_iter()
        .map(|m| (m.q, m.weight * m.q * m.q * m.psd))
        .collect();
    let total: f64 = slope.iter().map(|s| s.1).sum();
    if total.is_nan() || total <= 0.0 {
        return floor;
    }
    slope.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut tail = 0.0;
    let mut q_s = slope[0].0;
    for &(q, s) in &slope {
        if tail + s > SLOPE_TAIL * total {
            q_s = q;
            break;
        }
        tail += s;
    }
    (2.0 * std::f64::consts::PI / q_s).max(floor)
}

/// The share of the mean-square height, or of the mean-square slope, of a map's surface less
/// its smooth shape that one ring of wavenumbers (|q| within half a ring's width
/// 2π/(max(n, m)·s) of its centre) must hold for its wavelength to be one the surface carries
/// ([`carrying_wavelength`]): a tenth. A waviness puts most of both in one or two rings; a
/// band of roughness spreads its slope over its many rings, so that only its long wavelengths,
/// which hold its height, count.
pub const CARRY_SHARE: f64 = 0.1;

/// A residual (the map less its quadratic) whose rms height is below this fraction of the
/// map's rms height about its mean is the map's round-off, not a surface it carries
/// (dimensionless): a float32 map's round-off is ~1e-7.
const SMOOTH_RESIDUAL: f64 = 1e-6;

/// The shortest wavelength (length) that carries a share of the map's surface less its
/// smooth shape: the map less its least-squares quadratic `c + a·x + b·y + p·x² + q·y² + r·xy`
/// (the apex of a sphere or ellipsoid, a tilt), Hann-windowed as in [`shortest_wavelength`],
/// split into rings of |q|; the ring of largest |q| holding at least [`CARRY_SHARE`] of the
/// residual's mean-square height or of its mean-square slope. A wavy sphere's waviness (its
/// wavelength holds nearly all the residual), where the slope of the sphere hides it from
/// [`shortest_wavelength`]. `None` for a map that is its quadratic up to round-off.
pub fn carrying_wavelength(map: &HeightMap) -> Option<f64> {
    let residual = less_quadratic(map);
    let (r, whole) = (mean_and_rms(&residual).1, mean_and_rms(map.heights()).1);
    if !(r.is_finite() && r > SMOOTH_RESIDUAL * whole) {
        return None;
    }
    let windowed = hann_windowed(map, residual)?;
    let ring_width = 2.0 * std::f64::consts::PI / (map.nx().max(map.ny()) as f64 * map.spacing());
    let mut rings: Vec<(f64, f64)> = Vec::new();
    for m in modes(&windowed) {
        let k = (m.q / ring_width).round() as usize;
        if rings.len() <= k {
            rings.resize(k + 1, (0.0, 0.0));
        }
        rings[k].0 += m.weight * m.psd;
        rings[k].1 += m.weight * m.q * m.q * m.psd;
    }
    let (height, slope) = rings
        .iter()
        .fold((0.0, 0.0), |(h, s), r| (h + r.0, s + r.1));
    if !(height > 0.0 && slope > 0.0) {
        return None;
    }
    let k = rings
        .iter()
        .rposition(|r| r.0 >= CARRY_SHARE * height || r.1 >= CARRY_SHARE * slope)?;
    Some((2.0 * std::f64::consts::PI / (k.max(1) as f64 * ring_width)).max(2.0 * map.spacing()))
}

/// The heights of `map` less their least-squares quadratic in the node coordinates (length).
/// About the lattice's centre the six monomials 1, x, y, x² − ⟨x²⟩, y² − ⟨y²⟩, xy are
/// orthogonal over the nodes, so each coefficient is one projection.
fn less_quadratic(map: &HeightMap) -> Vec<f64> {
    let (nx, ny) = (map.nx(), map.ny());
    let centre = |i: usize, n: usize| i as f64 - 0.5 * (n as f64 - 1.0);
    let mean_sq = |n: usize| (0..n).map(|i| centre(i, n).powi(2)).sum::<f64>() / n as f64;
    let (mx, my) = (mean_sq(nx), mean_sq(ny));
    let basis = |i: usize, j: usize| {
        let (x, y) = (centre(i, nx), centre(j, ny));
        [1.0, x, y, x * x - mx, y * y - my, x * y]
    };
    let (mut dot, mut norm) = ([0.0; 6], [0.0; 6]);
    for (k, &h) in map.heights().iter().enumerate() {
        let b = basis(k % nx, k / nx);
        for t in 0..6 {
            dot[t] += h * b[t];
            norm[t] += b[t] * b[t];
        }
    }
    let coef: Vec<f64> = (0..6)
        .map(|t| if norm[t] > 0.0 { dot[t] / norm[t] } else { 0.0 })
        .collect();
    map.heights()
        .iter()
        .enumerate()
        .map(|(k, &h)| {
            let b = basis(k % nx, k / nx);
            h - (0..6).map(|t| coef[t] * b[t]).sum::<f64>()
        })
        .collect()
}

/// `values` (length, one per node of `map`, row-major) multiplied by a Hann window along x
/// and y, as a map of the same lattice; `None` where the window leaves nothing (a map of a
/// node or two along an axis).
fn hann_windowed(map: &HeightMap, values: Vec<f64>) -> Option<HeightMap> {
    let (nx, ny, dx) = (map.nx(), map.ny(), map.spacing());
    let hann = |i: usize, n: usize| {
        (std::f64::consts::PI * (i as f64 + 0.5) / n as f64)
            .sin()
            .powi(2)
    };
    let wx: Vec<f64> = (0..nx).map(|i| hann(i, nx)).collect();
    let wy: Vec<f64> = (0..ny).map(|j| hann(j, ny)).collect();
    let windowed = values
        .into_iter()
        .enumerate()
        .map(|(k, h)| h * wx[k % nx] * wy[k / nx])
        .collect();
    HeightMap::new(nx, ny, dx, windowed).ok()
}

/// The map's statistics, treating it as one period of a periodic surface.
pub fn statistics(map: &HeightMap) -> Statistics {
    let (mean, rms_height) = mean_and_rms(map.heights());
    // ⟨q^p⟩-weighted sums: Σ w |q|^p C / A, with A = N Δ².
    let area = map.heights().len() as f64 * map.spacing() * map.spacing();
    let (mut slope, mut curvature) = (0.0, 0.0);
    for m in modes(map) {
        let q2 = m.q * m.q;
        slope += m.weight * q2 * m.psd;
        curvature += m.weight * 0.25 * q2 * q2 * m.psd;
    }
    Statistics {
        mean,
        rms_height,
        rms_slope: (slope / area).sqrt(),
        rms_curvature: (curvature / area).sqrt(),
    }
}

/// The rms height about the mean over the map's nodes (length).
pub fn rms_height(map: &HeightMap) -> f64 {
    mean_and_rms(map.heights()).1
}

/// The mean of `h` and the rms of `h` about it.
fn mean_and_rms(h: &[f64]) -> (f64, f64) {
    let n = h.len() as f64;
    let mean = h.iter().sum::<f64>() / n;
    let rms = (h.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n).sqrt();
    (mean, rms)
}

/// The rms gradient magnitude `√⟨|∇h|²⟩` of the periodic band-limited surface through the
/// nodes, computed spectrally (dimensionless).
pub fn rms_slope(map: &HeightMap) -> f64 {
    statistics(map).rms_slope
}

/// The rms mean curvature `√⟨(½∇²h)²⟩` of the periodic band-limited surface through the
/// nodes, computed spectrally (1/length).
pub fn rms_curvature(map: &HeightMap) -> f64 {
    statistics(map).rms_curvature
}

/// The radially averaged power spectral density `C(|q|)` of the map (periodic): the modes
/// (all but the mean) in `bins` bins of `|q|` equally spaced in log |q| from the smallest
/// nonzero `|q|` to the largest (the corner of the spectrum); empty bins are left out. Each
/// bin holds the mean `|q|` and the mean `C` of its modes, each mode of the full spectrum
/// counted once. No bins for `bins = 0`.
pub fn radial_psd(map: &HeightMap, bins: usize) -> Vec<PsdBin> {
    let modes = modes(map);
    let lo = modes.iter().map(|m| m.q).fold(f64::INFINITY, f64::min);
    let hi = modes.iter().map(|m| m.q).fold(0.0, f64::max);
    if bins == 0 || !(lo > 0.0 && hi >= lo) {
        return Vec::new();
    }
    let width = (hi / lo).ln() / bins as f64;
    let mut sums = vec![(0.0, 0.0, 0.0); bins];
    for m in &modes {
        let at = if width > 0.0 {
            ((m.q / lo).ln() / width) as usize
        } else {
            0
        };
        let s = &mut sums[at.min(bins - 1)];
        s.0 += m.weight * m.q;
        s.1 += m.weight * m.psd;
        s.2 += m.weight;
    }
    sums.into_iter()
        .filter(|s| s.2 > 0.0)
        .map(|(q, psd, w)| PsdBin {
            q: q / w,
            psd: psd / w,
            modes: w as usize,
        })
        .collect()
}
