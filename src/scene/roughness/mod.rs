//! Self-affine random roughness by Fourier synthesis: a periodic surface on a grid of
//! `nx` × `ny` nodes whose power spectral density is isotropic,
//!
//! ```text
//! C(q) ∝ 1                      for q_L ≤ |q| < q_r   (the roll-off plateau)
//! C(q) ∝ (|q|/q_r)^(−2(1+H))    for q_r ≤ |q| ≤ q_s   (self-affine, Hurst exponent H)
//! C(q) = 0                      otherwise (and at q = 0: the mean is zero)
//! ```
//!
//! with `q_L = 2π/λ_L` (the largest wavelength, by default the domain's longer side),
//! `q_r = 2π/λ_r` (the roll-off) and `q_s = 2π/λ_s` (the short-wavelength cut-off), as
//! Tamaas' `SurfaceGeneratorFilter` with its isotropic power law and ContactMechanics'
//! `fourier_synthesis` define it. [`RoughnessParams`] holds the parameters, [`generate`] makes
//! the surface as a [`HeightMap`] (heights in the spacing's length unit, row-major, x
//! fastest, as every height map), and the statistics functions ([`statistics`],
//! [`rms_height`], [`rms_slope`], [`rms_curvature`], [`radial_psd`]) measure any map.
//!
//! # The algorithm (version [`GENERATOR_VERSION`])
//!
//! 1. The half spectrum (`kx` in `0..=nx/2`, every `ky`) is filled with complex Gaussian
//!    white noise `(g1 + i g2)/√2` (so `E|Z|² = 1`), one pair of normal numbers per
//!    coefficient, `ky` in the outer loop (`0..ny`) and `kx` in the inner one (`0..=nx/2`), in
//!    that fixed order, whatever the parameters but the grid (the normal numbers are those of
//!    [`noise`]: `pcg64` seeded with the seed, Box–Muller written here).
//! 2. Hermitian symmetry, so that the inverse real FFT is exact: in the self-conjugate
//!    columns `kx = 0` and (even `nx`) `kx = nx/2`, the coefficient at `ky > ny/2` is set to the
//!    conjugate of the one at `ny − ky`, and a self-conjugate coefficient (`ky = 0`, or
//!    `ky = ny/2` for even `ny`) to `√2·g1`, real, with the same variance.
//! 3. Each coefficient is multiplied by `√(C(|q|)/C(q_r))`, the mean's by 0. A mode on a band
//!    edge (within a relative 10⁻⁹ of it) is inside the band.
//! 4. The inverse 2-D FFT (realfft along x, rustfft along y) gives the heights; their mean
//!    is subtracted, and they are scaled so that the surface's rms height over the nodes (or
//!    its spectral rms slope, [`rms_slope`]) is exactly the value asked for (to rounding).
//!
//! The surface is periodic on the domain `nx·Δ × ny·Δ` by construction: its spectrum holds
//! the grid's own Fourier modes only, so it has no leakage.
//!
//! # Reproducibility
//!
//! The same parameters and seed give the same surface on every machine: the random numbers
//! are defined bit for bit by their algorithms (no distribution crate is involved), and only
//! the rounding of the transforms (rustfft chooses SIMD kernels for the processor it runs
//! on) and of the platform's `ln`, `sin` and `cos` may differ, by a relative 10⁻¹⁵ or so. On
//! one machine and build the heights are identical to the bit. A change of the algorithm
//! changes [`GENERATOR_VERSION`], which the saved sidecar records.

mod fft2;
pub mod noise;
mod stats;

pub use stats::{
    carrying_wavelength, radial_psd, rms_curvature, rms_height, rms_slope, shortest_wavelength,
    statistics, PsdBin, Statistics, CARRY_SHARE, SLOPE_TAIL,
};

use super::height_map::HeightMap;
use super::SceneError;
use crate::params::{
    Kind, Spec, CUTOFF, GRID, GRID_Y, HURST, LARGEST_WAVELENGTH, RMS_HEIGHT, RMS_SLOPE, ROLLOFF,
    SPACING,
};
use crate::text::{bytes_text, compact};
use fft2::{wavenumber, Fft2};
use noise::Normals;
use realfft::num_complex::Complex;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The generator's name and the version of its algorithm: the same version, parameters and
/// seed give the same surface.
pub const GENERATOR_VERSION: &str = "jkrbem-roughness/1";

pub use crate::params::limits::MAX_ROUGHNESS_NODES as MAX_NODES;
pub use crate::params::limits::MIN_ROUGHNESS_NODES as MIN_NODES;
/// Most nodes in all (a count): 8192², about 1.6 GB of heights and spectrum while generating.
pub const MAX_TOTAL_NODES: usize = 1 << 26;
/// Memory a surface takes per node while it is generated and written (bytes): the heights,
/// the half spectrum, the transforms' scratch and the scaled copy; measured at its peak 28
/// (`jkrbem roughness`, peak resident set at 4096² and 8192²), Python's copy into an array
/// within it.
pub const BYTES_PER_NODE: u64 = 32;
/// Memory besides the nodes (bytes): the program itself, 8 MB measured at 16².
pub const BASE_BYTES: u64 = 16 << 20;
/// The default cut-off λ_s in spacings: the shortest wave is sampled by 4 nodes.
pub const DEFAULT_CUTOFF_SPACINGS: f64 = 4.0;
/// Relative slack with which a Fourier mode on a band edge counts as inside it, and a
/// wavelength equal to a bound (the domain, 2 spacings) is accepted, for rounding.
const EDGE: f64 = 1e-9;

/// The parameters of a random self-affine surface. Lengths are in the user's unit (that of
/// the spacing); the JSON keys (serde) are the parameters' names, as Python's keywords.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughnessParams {
    /// Nodes along x, nx (a count, 4 to 16384).
    pub grid: usize,
    /// Nodes along y, ny (a count, 4 to 16384); `None`: as many as along x.
    #[serde(default)]
    pub grid_y: Option<usize>,
    /// The spacing Δ of the nodes (length).
    pub spacing: f64,
    /// The Hurst exponent H, in (0, 1] (dimensionless).
    pub hurst: f64,
    /// The rms height about the mean over the nodes (length). Exactly one of it and
    /// `rms_slope`.
    #[serde(default)]
    pub rms_height: Option<f64>,
    /// The spectral rms gradient magnitude √⟨|∇h|²⟩ (dimensionless). Exactly one of it and
    /// `rms_height`.
    #[serde(default)]
    pub rms_slope: Option<f64>,
    /// The roll-off wavelength λ_r (length): the spectrum is flat between it and the largest
    /// wavelength. `None`: the largest wavelength (no plateau).
    #[serde(default)]
    pub rolloff: Option<f64>,
    /// The short-wavelength cut-off λ_s (length), at least 2 Δ. `None`: 4 Δ
    /// ([`DEFAULT_CUTOFF_SPACINGS`]).
    #[serde(default)]
    pub cutoff: Option<f64>,
    /// The largest wavelength λ_L with power (length), at most the domain's longer side.
    /// `None`: the domain's longer side, max(nx, ny)·Δ.
    #[serde(default)]
    pub largest_wavelength: Option<f64>,
    /// The seed of the random numbers.
    #[serde(default)]
    pub seed: u64,
}

/// What the surface's amplitude is scaled to.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Target {
    /// The rms height (length).
    Height(f64),
    /// The spectral rms slope (dimensionless).
    Slope(f64),
}

/// Checked parameters with every default resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Band {
    /// Nodes along x and y (counts).
    nx: usize,
    ny: usize,
    /// Spacing (length).
    spacing: f64,
    /// Hurst exponent.
    hurst: f64,
    /// The amplitude's target.
    target: Target,
    /// λ_L, λ_r, λ_s (length).
    largest: f64,
    rolloff: f64,
    cutoff: f64,
}

impl Band {
    /// `√(C(q)/C(q_r))` for `|q| = q` (1/length): the filter of step 3.
    fn amplitude(&self, q: f64) -> f64 {
        let q_large = 2.0 * PI / self.largest;
        let q_rolloff = 2.0 * PI / self.rolloff;
        let q_cutoff = 2.0 * PI / self.cutoff;
        if q <= 0.0 || q < q_large * (1.0 - EDGE) || q > q_cutoff * (1.0 + EDGE) {
            0.0
        } else if q < q_rolloff {
            1.0
        } else {
            (q / q_rolloff).powf(-(1.0 + self.hurst))
        }
    }
}

impl RoughnessParams {
    /// A square grid of `grid` × `grid` nodes at `spacing` (length) with Hurst exponent
    /// `hurst` and rms height `rms_height` (length); seed 0 and the default wavelengths.
    pub fn with_rms_height(grid: usize, spacing: f64, hurst: f64, rms_height: f64) -> Self {
        RoughnessParams {
            grid,
            grid_y: None,
            spacing,
            hurst,
            rms_height: Some(rms_height),
            rms_slope: None,
            rolloff: None,
            cutoff: None,
            largest_wavelength: None,
            seed: 0,
        }
    }

    /// As [`RoughnessParams::with_rms_height`], scaled to the rms slope `rms_slope`
    /// (dimensionless) instead.
    pub fn with_rms_slope(grid: usize, spacing: f64, hurst: f64, rms_slope: f64) -> Self {
        RoughnessParams {
            rms_height: None,
            rms_slope: Some(rms_slope),
            ..Self::with_rms_height(grid, spacing, hurst, 1.0)
        }
    }

    /// Nodes along x (a count).
    pub fn nx(&self) -> usize {
        self.grid
    }

    /// Nodes along y (a count).
    pub fn ny(&self) -> usize {
        self.grid_y.unwrap_or(self.grid)
    }

    /// The memory generating this surface takes at its peak (bytes): [`memory_estimate`].
    pub fn memory_estimate(&self) -> u64 {
        memory_estimate(self.nx(), self.ny())
    }

    /// Refuses a surface whose generation needs more than `available` bytes (no check if
    /// `None`; the plan's memory check gives it what this machine has).
    ///
    /// # Errors
    ///
    /// [`SceneError::Invalid`] naming ⟨grid⟩ (and ⟨grid_y⟩) with the estimate, what is
    /// available and the largest surface of the same shape that fits.
    pub fn check_memory_within(&self, available: Option<u64>) -> Result<(), SceneError> {
        let (nx, ny) = (self.nx(), self.ny());
        let need = memory_estimate(nx, ny);
        let Some(available) = available.filter(|&a| need > a) else {
            return Ok(());
        };
        // The largest surface of the same aspect whose nodes fit in what is left.
        let nodes = available.saturating_sub(BASE_BYTES) / BYTES_PER_NODE;
        let scale = (nodes as f64 / (nx as f64 * ny as f64)).sqrt();
        let (fx, fy) = (
            (nx as f64 * scale).floor() as usize,
            (ny as f64 * scale).floor() as usize,
        );
        let fits = if fx < MIN_NODES || fy < MIN_NODES {
            "not even the smallest surface of this shape fits".to_string()
        } else if self.grid_y.is_some() {
            format!("the largest of this shape that fits is {GRID} {fx} {GRID_Y} {fy}")
        } else {
            format!("the largest that fits is {GRID} {fx}")
        };
        Err(SceneError::Invalid {
            param: GRID,
            value: nx as f64,
            expected: format!(
                "a surface of {GRID} × {GRID_Y} = {nx} × {ny} nodes needs about {} while it is \
                 generated ({BYTES_PER_NODE} bytes per node), more than the {} this machine has \
                 available (free memory, control group and process limits); {fits}",
                bytes_text(need),
                bytes_text(available)
            ),
        })
    }

    /// Checks the parameters, naming the first one that is wrong.
    ///
    /// # Errors
    ///
    /// [`SceneError::Invalid`] for a value out of its range: a grid side outside 4..=16384
    /// (or more than [`MAX_TOTAL_NODES`] nodes), a spacing, length or rms value outside
    /// [1e-30, 1e30], H outside (0, 1], λ_L longer than the domain, λ_r longer than λ_L, λ_s
    /// shorter than 2 spacings (the Nyquist wavelength) or not shorter than λ_r;
    /// [`SceneError::Refused`] for both or neither of the rms height and slope, and for a band
    /// that holds no Fourier mode of the grid.
    pub fn validate(&self) -> Result<(), SceneError> {
        let band = self.band()?;
        if band_modes(&band) == 0 {
            return Err(empty_band(&band));
        }
        Ok(())
    }

    /// The parameters with every default filled in (the grid's y side and the three
    /// wavelengths), as the sidecar records them.
    ///
    /// # Errors
    ///
    /// Those of [`RoughnessParams::validate`].
    pub fn resolved(&self) -> Result<RoughnessParams, SceneError> {
        self.validate()?;
        let b = self.band()?;
        Ok(RoughnessParams {
            grid_y: Some(b.ny),
            rolloff: Some(b.rolloff),
            cutoff: Some(b.cutoff),
            largest_wavelength: Some(b.largest),
            ..self.clone()
        })
    }

    /// The checked, resolved parameters.
    fn band(&self) -> Result<Band, SceneError> {
        let (nx, ny) = (self.nx(), self.ny());
        nodes(GRID, nx)?;
        nodes(GRID_Y, ny)?;
        if nx.saturating_mul(ny) > MAX_TOTAL_NODES {
            return Err(invalid(
                GRID,
                nx as f64,
                format!(
                    "{GRID} × {GRID_Y} = {nx} × {ny} nodes is more than the {MAX_TOTAL_NODES} \
                     the generator takes"
                ),
            ));
        }
        let spacing = in_range(SPACING, self.spacing)?;
        let hurst = in_range(HURST, self.hurst)?;
        let target = match (self.rms_height, self.rms_slope) {
            (Some(h), None) => Target::Height(in_range(RMS_HEIGHT, h)?),
            (None, Some(s)) => Target::Slope(in_range(RMS_SLOPE, s)?),
            (Some(_), Some(_)) => {
                return Err(SceneError::Refused {
                    param: RMS_SLOPE,
                    why: format!(
                        "is given with {RMS_HEIGHT}: give one of them, the surface is scaled \
                         to meet it"
                    ),
                })
            }
            (None, None) => {
                return Err(SceneError::Refused {
                    param: RMS_HEIGHT,
                    why: format!(
                        "or {RMS_SLOPE} is required: give one of them, the surface is scaled \
                         to meet it"
                    ),
                })
            }
        };
        let domain = nx.max(ny) as f64 * spacing;
        let largest = in_range(
            LARGEST_WAVELENGTH,
            self.largest_wavelength.unwrap_or(domain),
        )?;
        if largest > domain * (1.0 + EDGE) {
            return Err(invalid(
                LARGEST_WAVELENGTH,
                largest,
                format!(
                    "it must be at most the domain's longer side, max({GRID}, {GRID_Y}) × \
                     {SPACING} = {}: the surface is periodic over the domain",
                    compact(domain)
                ),
            ));
        }
        let cutoff = in_range(
            CUTOFF,
            self.cutoff.unwrap_or(DEFAULT_CUTOFF_SPACINGS * spacing),
        )?;
        if cutoff < 2.0 * spacing * (1.0 - EDGE) {
            return Err(invalid(
                CUTOFF,
                cutoff,
                format!(
                    "it must be at least 2 × {SPACING} = {}, the grid's Nyquist wavelength",
                    compact(2.0 * spacing)
                ),
            ));
        }
        let rolloff = in_range(ROLLOFF, self.rolloff.unwrap_or(largest))?;
        if rolloff > largest * (1.0 + EDGE) {
            return Err(invalid(
                ROLLOFF,
                rolloff,
                format!(
                    "it must be at most {LARGEST_WAVELENGTH} = {} (the domain's longer side \
                     unless given)",
                    compact(largest)
                ),
            ));
        }
        if cutoff >= rolloff {
            let (param, value) = if self.cutoff.is_some() || self.rolloff.is_none() {
                (CUTOFF, cutoff)
            } else {
                (ROLLOFF, rolloff)
            };
            return Err(invalid(
                param,
                value,
                format!(
                    "{CUTOFF} = {} must be shorter than {ROLLOFF} = {} (which is \
                     {LARGEST_WAVELENGTH}, the domain's longer side, unless given)",
                    compact(cutoff),
                    compact(rolloff)
                ),
            ));
        }
        Ok(Band {
            nx,
            ny,
            spacing,
            hurst,
            target,
            largest,
            rolloff,
            cutoff,
        })
    }
}

/// The memory generating a surface of `nx` × `ny` nodes takes at its peak (bytes):
/// [`BYTES_PER_NODE`] per node and [`BASE_BYTES`] besides.
pub fn memory_estimate(nx: usize, ny: usize) -> u64 {
    (nx as u64)
        .saturating_mul(ny as u64)
        .saturating_mul(BYTES_PER_NODE)
        .saturating_add(BASE_BYTES)
}

/// A [`SceneError::Invalid`].
fn invalid(param: &'static Spec, value: f64, expected: String) -> SceneError {
    SceneError::Invalid {
        param,
        value,
        expected,
    }
}

/// `n` nodes along the axis that `param` sets, checked.
fn nodes(param: &'static Spec, n: usize) -> Result<(), SceneError> {
    if (MIN_NODES..=MAX_NODES).contains(&n) {
        Ok(())
    } else {
        Err(invalid(
            param,
            n as f64,
            format!("a surface has from {MIN_NODES} to {MAX_NODES} nodes along each side"),
        ))
    }
}

/// `value` if it lies in `param`'s range (its [`Kind::Real`]).
fn in_range(param: &'static Spec, value: f64) -> Result<f64, SceneError> {
    match param.kind {
        Kind::Real(range) if !range.contains(value) => Err(invalid(
            param,
            value,
            format!("it must lie in {range}{}", unit(param)),
        )),
        _ => Ok(value),
    }
}

/// ` (unit)` for a parameter with a unit, else nothing.
fn unit(param: &Spec) -> String {
    if param.unit.is_empty() {
        String::new()
    } else {
        format!(" ({})", param.unit)
    }
}

/// How many coefficients of the half spectrum the band gives power.
fn band_modes(band: &Band) -> usize {
    let mut count = 0;
    for kx in 0..=band.nx / 2 {
        let qx = wavenumber(kx, band.nx, band.spacing);
        for ky in 0..band.ny {
            let q = qx.hypot(wavenumber(ky, band.ny, band.spacing));
            if band.amplitude(q) > 0.0 {
                count += 1;
            }
        }
    }
    count
}

/// The refusal of a band that holds no mode of the grid.
fn empty_band(band: &Band) -> SceneError {
    SceneError::Refused {
        param: CUTOFF,
        why: format!(
            "= {}: no Fourier mode of the grid has a wavelength from it to {LARGEST_WAVELENGTH} \
             = {} (the modes' wavelengths are the domain's sides divided by whole numbers, \
             combined along x and y): widen the band",
            compact(band.cutoff),
            compact(band.largest)
        ),
    }
}

/// The half spectrum of complex Gaussian white noise, Hermitian where it must be (steps 1
/// and 2 of the [module's algorithm](self)): coefficient `(kx, ky)` at `kx * ny + ky`.
fn white_noise(nx: usize, ny: usize, seed: u64) -> Vec<Complex<f64>> {
    let half = nx / 2 + 1;
    let mut normals = Normals::new(seed);
    let mut z = vec![Complex::new(0.0, 0.0); half * ny];
    let scale = std::f64::consts::FRAC_1_SQRT_2;
    for ky in 0..ny {
        for kx in 0..half {
            let (g1, g2) = normals.pair();
            z[kx * ny + ky] = Complex::new(g1 * scale, g2 * scale);
        }
    }
    for kx in (0..half).filter(|&kx| kx == 0 || 2 * kx == nx) {
        let column = &mut z[kx * ny..(kx + 1) * ny];
        for ky in 0..ny {
            let mirror = (ny - ky) % ny;
            if mirror == ky {
                column[ky] = Complex::new(column[ky].re * std::f64::consts::SQRT_2, 0.0);
            } else if ky > mirror {
                column[ky] = column[mirror].conj();
            }
        }
    }
    z
}

/// A random self-affine surface with the parameters `params` (see the [module](self)), as a
/// height map: heights in the spacing's unit, zero mean, row-major with x fastest.
///
/// # Errors
///
/// Those of [`RoughnessParams::validate`], and [`SceneError::Refused`] naming the rms
/// height or slope where the scaled heights leave a height map's range (|h| ≤ 1e30).
pub fn generate(params: &RoughnessParams) -> Result<HeightMap, SceneError> {
    let band = params.band()?;
    let (nx, ny, dx) = (band.nx, band.ny, band.spacing);
    let fft = Fft2::new(nx, ny);
    let mut spectrum = white_noise(nx, ny, params.seed);
    let mut modes = 0usize;
    for kx in 0..fft.half() {
        let qx = wavenumber(kx, nx, dx);
        for ky in 0..ny {
            let a = band.amplitude(qx.hypot(wavenumber(ky, ny, dx)));
            modes += usize::from(a > 0.0);
            spectrum[kx * ny + ky] *= a;
        }
    }
    if modes == 0 {
        return Err(empty_band(&band));
    }
    let mut heights = fft.inverse(spectrum);
    let mean = heights.iter().sum::<f64>() / heights.len() as f64;
    heights.iter_mut().for_each(|h| *h -= mean);
    let (param, target) = match band.target {
        Target::Height(v) => (RMS_HEIGHT, v),
        Target::Slope(v) => (RMS_SLOPE, v),
    };
    let too_large = |e: super::height_map::HeightMapError| SceneError::Refused {
        param,
        why: format!(
            "= {} gives heights out of a height map's range: {e}",
            compact(target)
        ),
    };
    let unscaled = HeightMap::new(nx, ny, dx, heights).map_err(too_large)?;
    let achieved = match band.target {
        Target::Height(_) => rms_height(&unscaled),
        Target::Slope(_) => rms_slope(&unscaled),
    };
    let factor = target / achieved;
    let heights = unscaled.heights().iter().map(|h| h * factor).collect();
    HeightMap::new(nx, ny, dx, heights).map_err(too_large)
}

#[cfg(test)]
mod tests;
