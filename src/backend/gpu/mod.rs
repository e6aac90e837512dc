//! The GPU backend (wgpu): device selection and the compute kernels of `shaders/`.
//!
//! Every WGSL kernel has a CPU twin in this module, and a test runs both on the same input.

pub mod backend;
pub mod context;
pub mod fft;
pub mod recorder;
pub mod spectral;
pub mod traffic;

pub use backend::{GpuBackend, GpuField};
pub use context::{list_adapters, test_context, AdapterInfoLine, AdapterPreference, GpuContext};
pub use fft::GpuFft;
