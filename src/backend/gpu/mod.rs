//! The GPU backend (wgpu): device selection and the compute kernels of `shaders/`.
//!
//! Every WGSL kernel has a CPU twin in this module, and a test runs both on the same input.

pub mod backend;
pub mod context;
pub mod headless;
pub mod profile;
pub mod recorder;
pub mod shaders;
pub mod slots;
pub mod spectral;
pub mod traffic;
pub mod twin;

pub use backend::{GpuBackend, GpuField, F32_RESIDUAL_FLOOR};
pub use context::{list_adapters, test_context, AdapterInfoLine, AdapterPreference, GpuContext};
