//! The CPU backend: f64 fields in host memory, `rustfft`/`realfft` transforms, rayon
//! across the cores. It is also the reference ("CPU twin") for every GPU kernel.
//!
//! Its convolution is the padded one (an isolated contact) or the periodic one (a surface
//! periodic over the domain: [`crate::backend::kernel`] derives it). On the periodic one the
//! preconditioner is the same stiffness E*|q|/2 (there the exact inverse of the continuum
//! symbol, a positive multiplier at q = 0), the residual floor is f64's as for the padded
//! one, the certified detachments are off (their bound is the plane's) and no contact is
//! reported at the edge (the domain has none).
//!
//! Its convolution's FFT passes (the symbol's multiply included) run in f64, or in f32 where
//! asked ([`CpuBackend::new_f32`]: twice the SIMD width); the fields, CG's vectors, every
//! reduction and the preconditioner stay f64 either way, the pressure rounded to f32 on its
//! way into the convolution and the displacement widened on its way out. The f32 convolution
//! puts a floor under CG's true residual ([`F32_CONVOLUTION_FLOOR`]).

pub mod spectral;

use super::kernel::stiffness_spectrum;
use super::measure::{self, ChordAxes, ContactMeasure};
use super::rules::{self, Flip};
use super::{
    BackendError, CgKernels, ContactChange, ContactKernels, Device, ElasticOperator, FieldStore,
    GridSetup, MaskStore, Preconditioner, Scalars, Slot,
};
use rayon::prelude::*;
use spectral::SpectralFilter;

/// Fields shorter than this are processed on one thread.
const PAR_MIN: usize = 1 << 14;

/// The relative CG residual below which the f32 convolution cannot bring the true residual
/// (dimensionless): the solver's tolerance is raised to it on an f32 CPU backend, as on the
/// GPU (whose floor, 2e-7, is the same arithmetic's). Measured on the 64² sphere's whole
/// curve: with no floor (the 1e-8 tolerance) the worst true residual is 1.4e-7 and CG makes
/// 1893 iterations against f64's 1540, with 1e-7 1538, with 2e-7 1420; |min F̄| within 8e-7
/// of f64's at each (docs/speed.md).
pub const F32_CONVOLUTION_FLOOR: f64 = 2e-7;

/// The convolution's filter in the arithmetic asked for.
enum Convolution {
    /// FFT passes in f64 (the reference).
    F64(SpectralFilter<f64>),
    /// FFT passes in f32.
    F32(SpectralFilter<f32>),
}

impl Convolution {
    /// The influence filter of `setup` ([`SpectralFilter::influence`]) in f32 or f64.
    fn of(setup: &GridSetup, periodic: bool, f32: bool) -> Self {
        let (nx, ny, dx, e) = (setup.nx, setup.ny, setup.dx, setup.e_star);
        if f32 {
            Convolution::F32(SpectralFilter::influence(nx, ny, dx, e, periodic))
        } else {
            Convolution::F64(SpectralFilter::influence(nx, ny, dx, e, periodic))
        }
    }

    /// dst = K src.
    fn apply(&mut self, src: &[f64], dst: &mut [f64]) {
        match self {
            Convolution::F64(f) => f.apply(src, dst),
            Convolution::F32(f) => f.apply(src, dst),
        }
    }

    /// Whether the passes run in f32.
    fn is_f32(&self) -> bool {
        matches!(self, Convolution::F32(_))
    }
}

/// The CPU backend (f64; its convolution's FFT passes in f64 or f32).
pub struct CpuBackend {
    nx: usize,
    ny: usize,
    convolution: Convolution,
    preconditioner: Option<SpectralFilter>,
    profile: Vec<f64>,
    /// Whether the convolution is the unpadded, periodic one.
    periodic: bool,
    /// Scratch for the masked preconditioner input.
    scratch: Vec<f64>,
    /// The scalar registers handed out so far.
    slots: Vec<f64>,
    /// The certification's workspace, made at its first use.
    certifier: Option<super::certify::Certifier>,
}

impl CpuBackend {
    /// Build the backend: plan the transforms and compute the kernel spectrum once.
    pub fn new(setup: &GridSetup) -> Result<Self, BackendError> {
        Self::build(setup, false, false)
    }

    /// Like [`CpuBackend::new`] but with the periodic convolution: Love's element kernel
    /// summed over the domain's periodic images, unpadded (nx × ny), with a zero-mean
    /// displacement ([`crate::backend::kernel::periodic_symbol`]), for a surface periodic over
    /// the domain (a nominally flat rough surface, a wave). The detachments certified before a
    /// solve are not taken on it (their bound is the plane's), and a contact at the domain's
    /// edges meets its images, not the edge: such a backend reports none at the edge.
    pub fn new_periodic(setup: &GridSetup) -> Result<Self, BackendError> {
        Self::build(setup, true, false)
    }

    /// [`CpuBackend::new`] (or [`CpuBackend::new_periodic`], `periodic`) with the
    /// convolution's FFT passes in f32: the pressure is rounded to f32 on its way in and the
    /// displacement widened to f64 on its way out; everything else stays f64. Its
    /// [`Device::precision`] is "f32", and CG's tolerance is raised to
    /// [`F32_CONVOLUTION_FLOOR`].
    pub fn new_f32(setup: &GridSetup, periodic: bool) -> Result<Self, BackendError> {
        Self::build(setup, periodic, true)
    }

    fn build(setup: &GridSetup, periodic: bool, f32: bool) -> Result<Self, BackendError> {
        super::check_profile(setup)?;
        if periodic && (setup.nx < 2 || setup.ny < 1) {
            return Err(BackendError::Unavailable(format!(
                "a periodic convolution needs at least 2 × 1 elements, not {} × {}",
                setup.nx, setup.ny
            )));
        }
        let (nx, ny, dx, e) = (setup.nx, setup.ny, setup.dx, setup.e_star);
        let convolution = Convolution::of(setup, periodic, f32);
        let preconditioner = match setup.preconditioner {
            Preconditioner::None => None,
            Preconditioner::Stiffness => {
                let mut f = SpectralFilter::new(nx, ny, nx, ny);
                f.set_symbol(&stiffness_spectrum(nx, ny, dx, e));
                Some(f)
            }
        };
        Ok(CpuBackend {
            nx,
            ny,
            convolution,
            preconditioner,
            profile: setup.profile.clone(),
            periodic,
            scratch: vec![0.0; nx * ny],
            slots: Vec::new(),
            certifier: None,
        })
    }

    /// Whether the convolution is the periodic one.
    pub fn is_periodic(&self) -> bool {
        self.periodic
    }

    fn ratio(&self, num: Slot, den: Slot) -> f64 {
        let d = self.slots[den.index()];
        if d == 0.0 {
            0.0
        } else {
            self.slots[num.index()] / d
        }
    }
}

impl Device for CpuBackend {
    type Field = Vec<f64>;
    type Mask = Vec<bool>;
    fn name(&self) -> &'static str {
        if self.periodic {
            "cpu-periodic"
        } else {
            "cpu"
        }
    }
    fn precision(&self) -> &'static str {
        if self.convolution.is_f32() {
            "f32"
        } else {
            "f64"
        }
    }
    fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
    fn sibling(&self, setup: &GridSetup) -> Result<Self, BackendError> {
        Self::build(setup, self.periodic, self.convolution.is_f32())
    }
}

impl FieldStore for CpuBackend {
    fn field(&mut self) -> Result<Vec<f64>, BackendError> {
        Ok(vec![0.0; self.nx * self.ny])
    }
    fn upload(&mut self, dst: &mut Vec<f64>, host: &[f64]) -> Result<(), BackendError> {
        dst.copy_from_slice(host);
        Ok(())
    }
    fn download(&mut self, src: &Vec<f64>, host: &mut [f64]) -> Result<(), BackendError> {
        host.copy_from_slice(src);
        Ok(())
    }
    fn copy(&mut self, src: &Vec<f64>, dst: &mut Vec<f64>) -> Result<(), BackendError> {
        dst.copy_from_slice(src);
        Ok(())
    }
}

impl MaskStore for CpuBackend {
    fn mask(&mut self) -> Result<Vec<bool>, BackendError> {
        Ok(vec![false; self.nx * self.ny])
    }
    fn upload_mask(&mut self, dst: &mut Vec<bool>, host: &[bool]) -> Result<(), BackendError> {
        dst.copy_from_slice(host);
        Ok(())
    }
    fn download_mask(&mut self, src: &Vec<bool>, host: &mut [bool]) -> Result<(), BackendError> {
        host.copy_from_slice(src);
        Ok(())
    }
    fn copy_mask(&mut self, src: &Vec<bool>, dst: &mut Vec<bool>) -> Result<(), BackendError> {
        dst.copy_from_slice(src);
        Ok(())
    }
}

impl Scalars for CpuBackend {
    fn slot(&mut self) -> Result<Slot, BackendError> {
        self.slots.push(0.0);
        Ok(Slot::new(self.slots.len() - 1))
    }
    fn copy_slot(&mut self, src: Slot, dst: Slot) -> Result<(), BackendError> {
        self.slots[dst.index()] = self.slots[src.index()];
        Ok(())
    }
    fn read_slots(&mut self, slots: &[Slot], out: &mut [f64]) -> Result<(), BackendError> {
        for (o, s) in out.iter_mut().zip(slots) {
            *o = self.slots[s.index()];
        }
        Ok(())
    }
}

impl ElasticOperator for CpuBackend {
    fn convolve(&mut self, src: &Vec<f64>, dst: &mut Vec<f64>) -> Result<(), BackendError> {
        self.convolution.apply(src, dst);
        Ok(())
    }
    fn precondition(
        &mut self,
        mask: &Vec<bool>,
        src: &Vec<f64>,
        dst: &mut Vec<f64>,
    ) -> Result<(), BackendError> {
        match &mut self.preconditioner {
            None => dst.copy_from_slice(src),
            Some(f) => {
                self.scratch
                    .par_iter_mut()
                    .with_min_len(PAR_MIN)
                    .zip(src.par_iter().zip(mask.par_iter()))
                    .for_each(|(s, (v, &m))| *s = if m { *v } else { 0.0 });
                f.apply(&self.scratch, dst);
                dst.par_iter_mut()
                    .with_min_len(PAR_MIN)
                    .zip(mask.par_iter())
                    .for_each(|(v, &m)| {
                        if !m {
                            *v = 0.0
                        }
                    });
            }
        }
        Ok(())
    }
}

/// max over the mask of |f| (0 for an empty mask).
fn max_abs_on(mask: &[bool], f: &[f64]) -> f64 {
    f.par_iter()
        .with_min_len(PAR_MIN)
        .zip(mask.par_iter())
        .map(|(v, &m)| if m { v.abs() } else { 0.0 })
        .reduce(|| 0.0, f64::max)
}

impl CgKernels for CpuBackend {
    fn max_abs_to(
        &mut self,
        mask: &Vec<bool>,
        f: &Vec<f64>,
        out: Slot,
    ) -> Result<(), BackendError> {
        self.slots[out.index()] = max_abs_on(mask, f);
        Ok(())
    }
    /// 0 in f64; [`F32_CONVOLUTION_FLOOR`] with the f32 convolution.
    fn residual_floor(&self) -> f64 {
        if self.convolution.is_f32() {
            F32_CONVOLUTION_FLOOR
        } else {
            0.0
        }
    }
    fn residual(
        &mut self,
        mask: &Vec<bool>,
        u: &Vec<f64>,
        d: f64,
        r: &mut Vec<f64>,
    ) -> Result<(), BackendError> {
        let h = &self.profile;
        r.par_iter_mut()
            .with_min_len(PAR_MIN)
            .enumerate()
            .for_each(|(i, ri)| *ri = if mask[i] { d - h[i] - u[i] } else { 0.0 });
        Ok(())
    }
    fn dot(
        &mut self,
        mask: &Vec<bool>,
        a: &Vec<f64>,
        b: &Vec<f64>,
        out: Slot,
    ) -> Result<(), BackendError> {
        self.slots[out.index()] = a
            .par_iter()
            .with_min_len(PAR_MIN)
            .zip(b.par_iter())
            .zip(mask.par_iter())
            .map(|((x, y), &m)| if m { x * y } else { 0.0 })
            .sum();
        Ok(())
    }
    fn axpy_ratio(
        &mut self,
        mask: &Vec<bool>,
        y: &mut Vec<f64>,
        x: &Vec<f64>,
        num: Slot,
        den: Slot,
        sign: f64,
    ) -> Result<(), BackendError> {
        let a = sign * self.ratio(num, den);
        y.par_iter_mut()
            .with_min_len(PAR_MIN)
            .zip(x.par_iter().zip(mask.par_iter()))
            .for_each(|(yi, (xi, &m))| {
                if m {
                    *yi += a * xi
                }
            });
        Ok(())
    }
    fn xpay_ratio(
        &mut self,
        mask: &Vec<bool>,
        y: &mut Vec<f64>,
        x: &Vec<f64>,
        num: Slot,
        den: Slot,
    ) -> Result<(), BackendError> {
        let b = self.ratio(num, den);
        y.par_iter_mut()
            .with_min_len(PAR_MIN)
            .zip(x.par_iter().zip(mask.par_iter()))
            .for_each(|(yi, (xi, &m))| *yi = if m { xi + b * *yi } else { 0.0 });
        Ok(())
    }
}

impl ContactKernels for CpuBackend {
    fn certify_detached(
        &mut self,
        mask: &mut Vec<bool>,
        before: &Vec<f64>,
        p: &mut Vec<f64>,
        sigma_c: f64,
        eps: f64,
    ) -> Result<Option<usize>, BackendError> {
        if self.periodic {
            // The bound is the balayage onto the plane less a hole, in the plane's inverse
            // influence (backend::certify): not proven for the periodic operator, whose
            // inverse differs (its images, its zero mean). Not taken: the states are the same,
            // only the solves more.
            return Ok(None);
        }
        let (nx, ny) = (self.nx, self.ny);
        let certifier = self
            .certifier
            .get_or_insert_with(|| super::certify::Certifier::new(nx, ny));
        Ok(certifier.certify(mask, before, p, sigma_c, eps))
    }
    fn spread_detached(
        &mut self,
        mask: &Vec<bool>,
        before: &Vec<f64>,
        p: &mut Vec<f64>,
    ) -> Result<(), BackendError> {
        super::shares::spread_detached(mask, before, p, self.nx, self.ny);
        Ok(())
    }
    fn update_contact(
        &mut self,
        mask: &mut Vec<bool>,
        p: &mut Vec<f64>,
        u: &Vec<f64>,
        attach_at: Option<f64>,
        sigma_c: f64,
    ) -> Result<ContactChange, BackendError> {
        let (nx, ny) = (self.nx, self.ny);
        let h = &self.profile;
        let (attach, d) = (attach_at.is_some(), attach_at.unwrap_or(0.0));
        let (detached, attached) = mask
            .par_iter_mut()
            .with_min_len(PAR_MIN)
            .zip(p.par_iter_mut())
            .enumerate()
            .map(|(i, (m, pi))| {
                let gap = attach.then(|| h[i] - d + u[i]);
                let out = match rules::sweep_element(*m, *pi, gap, sigma_c) {
                    Flip::Detach => (1, 0),
                    Flip::Attach => (0, 1),
                    Flip::Keep => (0, 0),
                };
                if out != (0, 0) {
                    *m = !*m;
                }
                if !*m {
                    *pi = 0.0;
                }
                out
            })
            .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
        let n_contact = mask.par_iter().filter(|&&m| m).count();
        let on = |x: usize, y: usize| mask[y * nx + x] as usize;
        let rows_edge: usize = (0..nx).map(|x| on(x, 0) + on(x, ny - 1)).sum();
        let cols_edge: usize = (1..ny - 1).map(|y| on(0, y) + on(nx - 1, y)).sum();
        // A periodic domain has no edge: a contact there meets its own images.
        let at_edge = if self.periodic {
            0
        } else {
            rows_edge + cols_edge
        };
        Ok(ContactChange {
            detached,
            attached,
            n_contact,
            at_edge,
        })
    }
    fn first_crossing(
        &mut self,
        mask: &Vec<bool>,
        p_old: &Vec<f64>,
        p_new: &Vec<f64>,
        sigma_c: f64,
    ) -> Result<f64, BackendError> {
        Ok(p_old
            .par_iter()
            .with_min_len(PAR_MIN)
            .zip(p_new.par_iter().zip(mask.par_iter()))
            .map(|(&a, (&b, &m))| {
                if m {
                    rules::crossing_fraction(a, b, sigma_c)
                } else {
                    1.0
                }
            })
            .reduce(|| 1.0, f64::min))
    }
    fn max_abs(&mut self, mask: &Vec<bool>, f: &Vec<f64>) -> Result<f64, BackendError> {
        Ok(max_abs_on(mask, f))
    }
    fn lerp(
        &mut self,
        mask: &Vec<bool>,
        a: &Vec<f64>,
        b: &Vec<f64>,
        t: f64,
        dst: &mut Vec<f64>,
    ) -> Result<(), BackendError> {
        dst.par_iter_mut()
            .with_min_len(PAR_MIN)
            .enumerate()
            .for_each(|(i, v)| {
                *v = if mask[i] {
                    a[i] + t * (b[i] - a[i])
                } else {
                    0.0
                }
            });
        Ok(())
    }
    fn measure(
        &mut self,
        mask: &Vec<bool>,
        p: &Vec<f64>,
        axes: ChordAxes,
    ) -> Result<ContactMeasure, BackendError> {
        let (sum, count) = p
            .par_iter()
            .with_min_len(PAR_MIN)
            .zip(mask.par_iter())
            .map(|(v, &m)| if m { (*v, 1usize) } else { (0.0, 0) })
            .reduce(|| (0.0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
        Ok(measure::with_shape(
            sum, count, mask, self.nx, self.ny, axes,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::Device;

    /// A grid's setup: flat profile, element side `dx`, E* = 1.
    fn setup(nx: usize, ny: usize, dx: f64) -> GridSetup {
        GridSetup {
            nx,
            ny,
            dx,
            e_star: 1.0,
            profile: vec![0.0; nx * ny],
            preconditioner: Preconditioner::Stiffness,
        }
    }

    /// A JKR-like pressure on an elliptic contact: Hertz's compressive dome less a tensile
    /// 1/√ rim, 0 outside, with a little noise so that every wavenumber is occupied.
    fn pressure(nx: usize, ny: usize) -> Vec<f64> {
        let (a, b) = (0.4 * nx as f64, 0.4 * ny as f64);
        (0..nx * ny)
            .map(|i| {
                let (x, y) = ((i % nx) as f64 + 0.5, (i / nx) as f64 + 0.5);
                let r2 = ((x - 0.5 * nx as f64) / a).powi(2) + ((y - 0.5 * ny as f64) / b).powi(2);
                if r2 < 1.0 {
                    2.0 * (1.0 - r2).sqrt() - 0.6 / (1.0 - r2 + 1e-3).sqrt()
                        + 1e-3 * (i as f64 * 0.7).sin()
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// The f32 FFT passes give the f64 convolution's u = K p to a relative max difference
    /// below 1e-5, padded and periodic, on a square and a rectangular grid; the backend then
    /// says f32 and raises CG's tolerance to its floor, as its sibling on another grid does.
    #[test]
    fn the_f32_convolution_matches_the_f64_one() {
        for (nx, ny) in [(64, 64), (128, 32)] {
            for periodic in [false, true] {
                let s = setup(nx, ny, 0.05);
                let mut b64 = CpuBackend::build(&s, periodic, false).unwrap();
                let mut b32 = CpuBackend::new_f32(&s, periodic).unwrap();
                assert_eq!((b64.precision(), b32.precision()), ("f64", "f32"));
                assert_eq!(b64.residual_floor(), 0.0);
                assert_eq!(b32.residual_floor(), F32_CONVOLUTION_FLOOR);
                let sibling = b32.sibling(&setup(2 * nx, 2 * ny, 0.025)).unwrap();
                assert_eq!(sibling.precision(), "f32");
                assert_eq!(sibling.is_periodic(), periodic);
                let p = pressure(nx, ny);
                let (mut u64, mut u32) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
                b64.convolve(&p, &mut u64).unwrap();
                b32.convolve(&p, &mut u32).unwrap();
                let scale = u64.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let diff = u64
                    .iter()
                    .zip(&u32)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                let rel = diff / scale;
                println!("{nx}×{ny} periodic {periodic}: relative max difference {rel:.2e}");
                assert!(
                    scale > 0.0 && rel < 1e-5,
                    "{nx}×{ny} periodic {periodic}: {rel:e}"
                );
                // Not the f64 answer itself: the passes did run in f32.
                assert!(diff > 0.0);
            }
        }
    }
}
