//! `--backend` and `--precision` of the studies that run many pull-offs (`sweep`, `crossed`,
//! `reproduce`): one backend request for every run of the study.

use jkrbem::backend::select::{BackendKind, Precision};
use jkrbem::session::open::BackendRequest;

/// The backend every run of a study uses, and the arithmetic of its FFT passes.
#[derive(Debug, Clone, clap::Args)]
pub struct StudyBackendArgs {
    /// Backend: `auto` (a hardware GPU if present, else the CPU), `cpu` or `gpu`.
    #[arg(long, value_enum, default_value_t = BackendKind::Auto)]
    pub backend: BackendKind,
    /// Arithmetic of the convolution's FFT passes: `auto` (the backend's own: f64 on the CPU,
    /// f32 on the GPU), `f64` (the CPU only) or `f32` (the GPU, or the CPU's FFT passes at
    /// twice the SIMD width; CG's tolerance is then raised to f32's floor, 2e-7).
    #[arg(long, value_enum, default_value_t = Precision::Auto)]
    pub precision: Precision,
}

impl StudyBackendArgs {
    /// The request every run of the study opens its backend with.
    pub fn request(&self) -> BackendRequest {
        BackendRequest {
            kind: self.backend,
            precision: self.precision,
            ..BackendRequest::default()
        }
    }
}
