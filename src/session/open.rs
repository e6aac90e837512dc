//! Opening the backend a request asks for, for one model: its kind, its convolution, the
//! check that the model's scales fit the backend's arithmetic, and the backend's own interval
//! between CG residual reads.

use super::{failed, input, RunError};
use crate::backend::select::{self, AnyBackend, BackendKind, Precision};
use crate::backend::BackendError;
use crate::model::Model;

/// How the displacements u = K ∗ p are convolved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Convolution {
    /// Zero-padded to 2Nx × 2Ny: the exact non-periodic sum (physics §4), for an isolated
    /// contact.
    #[default]
    Padded,
    /// Unpadded Nx × Ny, Love's kernel summed over the periodic images with a zero-mean
    /// displacement (`backend::kernel`): for a surface periodic over the domain (a nominally
    /// flat rough surface, a wave). Wrong for an isolated contact, which then feels its images.
    Periodic,
}

/// Which backend a request runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BackendRequest {
    /// cpu, gpu or auto.
    pub kind: BackendKind,
    /// The convolution's arithmetic: auto (the backend's own), f64 (the CPU) or f32.
    pub precision: Precision,
    /// Padded (an isolated contact) or periodic (a surface periodic over the domain).
    pub convolution: Convolution,
    /// CG residual reads every this many iterations; `None`: the backend's own interval.
    pub check_every: Option<usize>,
}

impl BackendRequest {
    /// Refuse a combination no backend offers (checked before any output is claimed): f64
    /// on the GPU ([`Precision::refusal`]). Every backend offers both convolutions (whether a
    /// scene is periodic is the scene's to check).
    pub fn check(&self) -> Result<(), RunError> {
        match self.precision.refusal(self.kind) {
            Some(why) => Err(input(why)),
            None => Ok(()),
        }
    }

    /// Whether the convolution asked for is the periodic one.
    pub fn periodic(&self) -> bool {
        self.convolution == Convolution::Periodic
    }
}

/// A backend opened for one model, with a line saying what was chosen and why.
pub struct OpenedFor {
    /// The backend.
    pub backend: AnyBackend,
    /// E.g. "gpu (f32, wgpu) on NVIDIA H100 …" or "cpu (f64, rustfft) (auto: …)".
    pub note: String,
}

/// A backend error as the request's error: a refused grid or a missing device is bad input,
/// a device that failed is a failure.
pub fn backend_error(e: BackendError) -> RunError {
    match e {
        BackendError::GridTooLarge { .. } | BackendError::Unavailable(_) => input(e),
        BackendError::DeviceLost { .. } => failed(e),
    }
}

/// Open `request`'s backend for `model`, refuse a model whose scales its arithmetic cannot
/// hold, and set the model's CG check interval (the request's, else the backend's own).
pub fn open_for(request: &BackendRequest, model: &mut Model) -> Result<OpenedFor, RunError> {
    request.check()?;
    let setup = model.grid_setup();
    let opened = select::open_in(request.kind, request.precision, &setup, request.periodic())
        .map_err(backend_error)?;
    let backend = opened.backend;
    let note = if request.periodic() {
        format!(
            "{} with a PERIODIC convolution (the surface repeats over the domain)",
            opened.note
        )
    } else {
        opened.note
    };
    // Refuse a model whose scales the backend's arithmetic (f32, the GPU's or the CPU's FFT
    // passes) cannot hold.
    if backend.precision() == "f32" {
        model
            .check_scales("f32", crate::model::F32_SAFE_RANGE)
            .map_err(input)?;
    }
    model.cg.check_every = request.check_every.unwrap_or(backend.check_every());
    Ok(OpenedFor { backend, note })
}
