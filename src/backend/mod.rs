//! Backends: where the grid fields live and where the elastic operator and the
//! vector operations of conjugate gradients run.
//!
//! The contract is split by job, in the manner of rustfft's `Fft: Length + Direction`, so
//! that each part of the solver states what it needs:
//! - [`Device`]: fields resident on the device (allocate, upload, download, copy), the grid
//!   shape, the work counters, a sibling for another grid;
//! - [`Scalars`]: scalar registers on the device ([`Slot`] handles the backend hands out);
//! - [`ElasticOperator`]: the half-space's influence operator u = K p and its preconditioner
//!   (the separation Tamaas and ContactMechanics make between the elastic operator and the
//!   contact solver);
//! - [`CgKernels`]: the vector operations of conjugate gradients, fused where a device
//!   benefits;
//! - [`ContactKernels`]: the contact set and the per-state operations on it;
//! - [`Backend`]: all of them (what the pull-off protocol needs).
//!
//! A GPU can run every operation on the device: grid fields stay resident, CG's scalars live
//! in device-side [`Slot`]s, and the host reads back only a handful of scalars (when it
//! chooses to test convergence, a state's measurement) and whole fields only where a caller
//! asks for them (contour snapshots, re-gridding).
//!
//! Conventions shared by every backend (all fields are `nx × ny`, row-major, x fastest):
//! - the *contact set* C is a mask held by the backend; masked operations act on C only;
//! - the *profile* h (length) and the element size Δx (length) are given at creation
//!   ([`GridSetup`]);
//! - pressure p has units of stress, displacement u and gap g of length.

pub mod certify;
pub mod cpu;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod kernel;
pub mod measure;
pub mod rules;
pub mod select;
pub mod shares;

pub use crate::setup::{ChordAxes, GridSetup, Preconditioner};
pub use measure::ContactMeasure;

/// Every part of the backend contract, for code that calls backends' operations.
pub mod prelude {
    pub use super::{
        Backend, CgKernels, ContactKernels, Device, ElasticOperator, FieldStore, MaskStore, Scalars,
    };
}

use thiserror::Error;

/// Errors a backend can raise.
#[derive(Debug, Error)]
pub enum BackendError {
    /// The requested grid cannot be held by this backend.
    #[error("grid {nx}×{ny} does not fit the {backend} backend: {reason}")]
    GridTooLarge {
        /// Elements along x.
        nx: usize,
        /// Elements along y.
        ny: usize,
        /// Backend name.
        backend: &'static str,
        /// Which limit, and what would fit.
        reason: String,
    },
    /// The device went away or failed during the run.
    #[error("the {backend} device failed: {reason}")]
    DeviceLost {
        /// Backend name.
        backend: &'static str,
        /// What the driver said.
        reason: String,
    },
    /// A backend that is not available on this machine was requested.
    #[error("{0}")]
    Unavailable(String),
}

/// A scalar register on the backend's device (CG's α, β, residual norms), handed out by
/// [`Scalars::slot`]; only the backend that made it reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Slot(usize);

impl Slot {
    /// The register's index on its device (for the backends).
    pub fn index(self) -> usize {
        self.0
    }

    /// A handle for register `index`: for the backends that hand them out, and for tests of
    /// device kernels that own their registers. The solver takes its own from
    /// [`Scalars::slot`].
    pub fn new(index: usize) -> Slot {
        Slot(index)
    }
}

/// When a guarded batch of CG iterations stops on the device (see [`CgKernels::guard_cg`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CgStop {
    /// The slot the CG update writes r·r to.
    pub rr: Slot,
    /// The slot holding ‖(d − h)_C‖², the scale of the relative residual.
    pub bb: Slot,
    /// Stop once √(r·r) ≤ tolerance · √bb (dimensionless), or r·r is not finite.
    pub tolerance: f64,
}

/// Changes made by one detachment/attachment sweep of the contact set.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ContactChange {
    /// Elements removed from C because their tensile stress exceeded σ_c.
    pub detached: usize,
    /// Elements added to C because their gap was negative.
    pub attached: usize,
    /// Elements in C after the sweep.
    pub n_contact: usize,
    /// Elements in C that touch the domain's outer ring of elements.
    pub at_edge: usize,
}

/// Work a backend has done since it was created, for benchmarks and reports.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Compute kernels launched on the device (0 for the CPU backend).
    pub dispatches: u64,
    /// Blocking reads of device memory by the host (scalars or fields).
    pub readbacks: u64,
    /// Bytes those reads brought back to the host (0 for the CPU backend).
    pub readback_bytes: u64,
    /// Command submissions to the device queue.
    pub submits: u64,
    /// Bytes the launched kernels read and wrote in device memory, as counted from their
    /// code (`gpu::traffic`; 0 for the CPU backend).
    pub bytes: u64,
    /// Host wall time blocked in those reads (ns): the work queued before each read and the
    /// round trip to the device (0 for the CPU backend). Not device-independent: for profiles.
    pub wait_ns: u64,
    /// Host wall time spent finishing and submitting command buffers (ns; 0 for the CPU
    /// backend). For profiles.
    pub submit_ns: u64,
}

/// A device and what lives on it: the part of the contract every other part builds on (the
/// types of its fields and contact sets, its name and precision, its grid, its counters, and
/// a sibling for another grid). Making, moving and copying them is [`FieldStore`] and [`MaskStore`].
pub trait Device {
    /// A real field of nx × ny values resident on the backend's device.
    type Field;
    /// A contact set C on the device: one flag per element (in contact or not). Every
    /// operation "on C" takes the set it works on explicitly; a backend holds none.
    type Mask;

    /// Short name for reports ("cpu", "gpu"; "cpu-periodic" for the unpadded CPU one).
    fn name(&self) -> &'static str;
    /// Arithmetic precision of the convolution ("f64", "f32"): the device fields' on the
    /// GPU, the FFT passes' on the CPU (its fields are f64).
    fn precision(&self) -> &'static str;
    /// Grid shape (nx, ny).
    fn shape(&self) -> (usize, usize);
    /// Work done since creation (zeros where a backend does not count).
    fn counters(&self) -> Counters {
        Counters::default()
    }
    /// A new backend of the same kind, on the same device, for another grid (the solver
    /// re-grids a shrinking contact with it).
    fn sibling(&self, setup: &GridSetup) -> Result<Self, BackendError>
    where
        Self: Sized;
}

/// Real fields on the device: made, uploaded, read back and copied.
pub trait FieldStore: Device {
    /// A new field, zero everywhere.
    fn field(&mut self) -> Result<Self::Field, BackendError>;
    /// Copy host values (row-major, length nx·ny) into a field.
    fn upload(&mut self, dst: &mut Self::Field, host: &[f64]) -> Result<(), BackendError>;
    /// Copy a field back to the host (row-major, length nx·ny).
    fn download(&mut self, src: &Self::Field, host: &mut [f64]) -> Result<(), BackendError>;
    /// dst = src on the whole grid.
    fn copy(&mut self, src: &Self::Field, dst: &mut Self::Field) -> Result<(), BackendError>;
}

/// Contact sets on the device: made, uploaded, read back and copied.
pub trait MaskStore: Device {
    /// A new contact set, empty.
    fn mask(&mut self) -> Result<Self::Mask, BackendError>;
    /// Copy host flags (row-major, length nx·ny, true = in contact) into a contact set.
    fn upload_mask(&mut self, dst: &mut Self::Mask, host: &[bool]) -> Result<(), BackendError>;
    /// Copy a contact set back to the host (row-major, length nx·ny).
    fn download_mask(&mut self, src: &Self::Mask, host: &mut [bool]) -> Result<(), BackendError>;
    /// dst = src (on the device).
    fn copy_mask(&mut self, src: &Self::Mask, dst: &mut Self::Mask) -> Result<(), BackendError>;
}

/// Scalar registers on the device.
pub trait Scalars: Device {
    /// A new register, holding 0 until written. Fails when the device has no more.
    fn slot(&mut self) -> Result<Slot, BackendError>;
    /// Read registers back to the host.
    fn read_slots(&mut self, slots: &[Slot], out: &mut [f64]) -> Result<(), BackendError>;
    /// slots\[dst\] = slots\[src\] (on the device).
    fn copy_slot(&mut self, src: Slot, dst: Slot) -> Result<(), BackendError>;
}

/// The elastic half-space's influence operator and an approximate inverse of it.
pub trait ElasticOperator: FieldStore {
    /// dst = K ∗ src, the non-periodic convolution with the influence kernel
    /// (src a pressure, dst a displacement); evaluated on the whole grid.
    fn convolve(&mut self, src: &Self::Field, dst: &mut Self::Field) -> Result<(), BackendError>;
    /// dst = M r, the preconditioner applied to a residual (zero off C), zero off C.
    fn precondition(
        &mut self,
        c: &Self::Mask,
        src: &Self::Field,
        dst: &mut Self::Field,
    ) -> Result<(), BackendError>;
}

/// The vector operations of conjugate gradients on a contact set C (each takes it as `c`).
pub trait CgKernels: ElasticOperator + Scalars {
    /// The relative residual below which this backend's arithmetic cannot bring CG's true
    /// residual (dimensionless): the solver stops there even if the tolerance asked is lower
    /// (0: no floor above the tolerances accepted, as in f64).
    fn residual_floor(&self) -> f64 {
        0.0
    }
    /// How often (iterations) the solver should read CG's residual back by default: 1 where
    /// each operation runs when called, more on a device that queues work ahead of the host
    /// and stops it itself ([`CgKernels::guard_cg`]).
    fn check_every(&self) -> usize {
        1
    }
    /// r = d − h − u on C, 0 off C (the residual of (K p)_C = (d − h)_C given u = K p; h is
    /// the profile the backend was built with).
    fn residual(
        &mut self,
        c: &Self::Mask,
        u: &Self::Field,
        d: f64,
        r: &mut Self::Field,
    ) -> Result<(), BackendError>;
    /// slots\[out\] = Σ_C a·b.
    fn dot(
        &mut self,
        c: &Self::Mask,
        a: &Self::Field,
        b: &Self::Field,
        out: Slot,
    ) -> Result<(), BackendError>;
    /// y += sign · (slots\[num\] / slots\[den\]) · x on C (a zero denominator gives a zero step).
    fn axpy_ratio(
        &mut self,
        c: &Self::Mask,
        y: &mut Self::Field,
        x: &Self::Field,
        num: Slot,
        den: Slot,
        sign: f64,
    ) -> Result<(), BackendError>;
    /// y = x + (slots\[num\] / slots\[den\]) · y on C, 0 off C.
    fn xpay_ratio(
        &mut self,
        c: &Self::Mask,
        y: &mut Self::Field,
        x: &Self::Field,
        num: Slot,
        den: Slot,
    ) -> Result<(), BackendError>;
    /// dst = K src and slots\[out\] = Σ_C src·dst (CG's curvature s·Ks). A device backend
    /// fuses the dot product into the convolution's last pass.
    fn convolve_dot(
        &mut self,
        c: &Self::Mask,
        src: &Self::Field,
        dst: &mut Self::Field,
        out: Slot,
    ) -> Result<(), BackendError> {
        self.convolve(src, dst)?;
        self.dot(c, src, dst, out)
    }
    /// dst = M src and slots\[out\] = Σ_C src·dst (CG's r·z). A device backend fuses the dot
    /// product into the preconditioner's last pass.
    fn precondition_dot(
        &mut self,
        c: &Self::Mask,
        src: &Self::Field,
        dst: &mut Self::Field,
        out: Slot,
    ) -> Result<(), BackendError> {
        self.precondition(c, src, dst)?;
        self.dot(c, src, dst, out)
    }
    /// One CG step's updates with α = slots\[num\] / slots\[den\] (0 for a zero
    /// denominator): x += α·s and r −= α·q on C; then slots\[rr\] = Σ_C r·r. A device backend
    /// does all of it in one pass.
    #[allow(clippy::too_many_arguments)]
    fn cg_update(
        &mut self,
        c: &Self::Mask,
        x: &mut Self::Field,
        r: &mut Self::Field,
        s: &Self::Field,
        q: &Self::Field,
        num: Slot,
        den: Slot,
        rr: Slot,
    ) -> Result<(), BackendError> {
        self.axpy_ratio(c, x, s, num, den, 1.0)?;
        self.axpy_ratio(c, r, q, num, den, -1.0)?;
        self.dot(c, r, r, rr)
    }

    /// Guard the CG iterations recorded from now on (`Some`) or end the guard (`None`). A
    /// device backend that queues iterations ahead of the host stops them on the device once
    /// the stop condition holds after a step: the steps recorded after that change nothing,
    /// and [`CgKernels::read_cg_status`] tells how many steps were made. The guarded
    /// iterations are: `convolve_dot`, `cg_update` (one step each), `precondition_dot` and
    /// `xpay_ratio` (which tests the condition). The default does nothing: a backend that
    /// runs each operation when called makes every step the solver asks for.
    fn guard_cg(&mut self, stop: Option<CgStop>) -> Result<(), BackendError> {
        let _ = stop;
        Ok(())
    }
    /// slots\[out\] = max over C of |f| (0 if C is empty), left on the device: CG's error
    /// estimate of a solve (max |M r|), read with the solve's last read where the backend
    /// defers its reads ([`CgKernels::defers_cg_start`]).
    fn max_abs_to(
        &mut self,
        c: &Self::Mask,
        f: &Self::Field,
        out: Slot,
    ) -> Result<(), BackendError>;
    /// Whether CG's start may be left unread until its first progress read
    /// ([`CgKernels::read_cg_status`]): a backend that guards the iterations it queues
    /// ([`CgKernels::guard_cg`]) makes no step where the warm start already meets the
    /// tolerance, so the solver need not wait for the start's residual before recording them.
    /// The default (false): the solver reads the start at once.
    fn defers_cg_start(&self) -> bool {
        false
    }
    /// `slots` read back together (into `out`), and under a guard the CG steps made since it
    /// began (`None`: every step recorded was made): one read for CG's progress and, where
    /// deferred, its start.
    fn read_cg_status(
        &mut self,
        slots: &[Slot],
        out: &mut [f64],
    ) -> Result<Option<usize>, BackendError> {
        self.read_slots(slots, out)?;
        Ok(None)
    }
}

/// The operations of the pull-off protocol on a contact set C (each takes it as `c`).
pub trait ContactKernels: FieldStore + MaskStore {
    /// One sweep of the Pohrt–Popov rule: detach elements of C with p < −σ_c and, with
    /// `attach_at` = Some(d), attach elements off C whose gap g = h − d + u at approach d
    /// (length) is negative; then p = 0 off C. With `attach_at` = None the sweep only
    /// detaches (`u` is not read): what a cascade round solved only approximately may do.
    /// σ_c is a stress; σ_c = 0 gives the non-adhesive (Signorini) rule.
    fn update_contact(
        &mut self,
        c: &mut Self::Mask,
        p: &mut Self::Field,
        u: &Self::Field,
        attach_at: Option<f64>,
        sigma_c: f64,
    ) -> Result<ContactChange, BackendError>;
    /// A cascade round's predicted start: p += Σ_o w_o · before_{i+o} on C, over the offsets
    /// o within [`shares::SHARE_RADIUS`] whose element lies off C, w being
    /// [`shares::detachment_shares`]. `before` is p as it was before the sweep (zero off the
    /// contact set it was on), so only the elements that sweep detached hand on their load.
    fn spread_detached(
        &mut self,
        c: &Self::Mask,
        before: &Self::Field,
        p: &mut Self::Field,
    ) -> Result<(), BackendError>;
    /// After a sweep that only detached: detach the elements of C certainly over `sigma_c`
    /// (stress) once the elements just detached hand on their load, zero p on them, set p on
    /// the candidates kept to the round's predicted start, and return how many were
    /// certified ([`certify::certify_detached`] is the definition and the host twin of
    /// shaders/certify.wgsl). `before` is p before the sweep, `eps` (stress) the error
    /// estimate of the solve it came from. `None`: not taken (the periodic backend, whose
    /// convolution is not the plane's), p untouched; the states are the same, only the
    /// solves more.
    fn certify_detached(
        &mut self,
        c: &mut Self::Mask,
        before: &Self::Field,
        p: &mut Self::Field,
        sigma_c: f64,
        eps: f64,
    ) -> Result<Option<usize>, BackendError>;
    /// The fraction t ∈ [0, 1] of a load step at which the first element of C reaches the
    /// detachment stress, with p moving linearly from `p_old` (t = 0, all p ≥ −σ_c) to
    /// `p_new` (t = 1) on a fixed contact set: min over C of (−σ_c − p_old)/(p_new − p_old)
    /// where p_new < −σ_c; 1 if no element crosses.
    fn first_crossing(
        &mut self,
        c: &Self::Mask,
        p_old: &Self::Field,
        p_new: &Self::Field,
        sigma_c: f64,
    ) -> Result<f64, BackendError>;
    /// max over C of |f| (0 if C is empty), reduced on the device.
    fn max_abs(&mut self, c: &Self::Mask, f: &Self::Field) -> Result<f64, BackendError>;
    /// dst = a + t·(b − a) on C, 0 off C.
    fn lerp(
        &mut self,
        c: &Self::Mask,
        a: &Self::Field,
        b: &Self::Field,
        t: f64,
        dst: &mut Self::Field,
    ) -> Result<(), BackendError>;
    /// A state's measurement of C with pressure `p` on it, reduced where the fields live (a
    /// few numbers come back, never the mask): Σ_C p (stress; multiply by Δx² for force),
    /// |C|, the chords along `axes` through the grid centre and the index box of C
    /// ([`measure::measure_mask`] defines them).
    fn measure(
        &mut self,
        c: &Self::Mask,
        p: &Self::Field,
        axes: ChordAxes,
    ) -> Result<ContactMeasure, BackendError>;
}

/// Everything the pull-off protocol needs of a backend.
pub trait Backend: CgKernels + ContactKernels {}

impl<B: CgKernels + ContactKernels> Backend for B {}

/// Refuse a setup whose profile is not one value per element.
pub(crate) fn check_profile(setup: &crate::setup::GridSetup) -> Result<(), BackendError> {
    let (nx, ny) = (setup.nx, setup.ny);
    if setup.profile.len() != nx * ny {
        return Err(BackendError::Unavailable(format!(
            "profile has {} values, grid needs {}",
            setup.profile.len(),
            nx * ny
        )));
    }
    Ok(())
}
