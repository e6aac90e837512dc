//! The backends without a GPU adapter: the FFT convolution against the direct sum, the CG
//! solver's stops and their reports on the CPU, and the GPU backend's WGSL shaders (validated
//! with naga, no adapter needed). The checks that need an adapter, and the backend contract on
//! every backend, are in `tests/gpu/` (on libtest-mimic). One test binary; each former file is
//! a module.

#[path = "../common/mod.rs"]
mod common;

mod convolution;
mod failure_cg;
mod periodic;
#[cfg(feature = "gpu")]
mod shaders;
