//! The GPU backend: f32 fields in wgpu storage buffers, the padded FFT convolution and CG's
//! vector operations as WGSL kernels, CG's scalars in a device-side slot buffer.

use super::context::GpuContext;
use crate::backend::cpu::GridSetup;
use crate::backend::{Backend, BackendError, ContactChange, Counters, Slot};

/// A real field of nx × ny f32 values in a storage buffer.
pub struct GpuField {
    buffer: wgpu::Buffer,
}

/// The wgpu backend (f32 on the device).
pub struct GpuBackend {
    ctx: GpuContext,
    nx: usize,
    ny: usize,
    counters: Counters,
}

impl GpuBackend {
    /// Build the backend on an opened device: compile the kernels, upload the profile and
    /// the kernel spectra. Refuses a grid whose buffers exceed the adapter's limits.
    pub fn new(ctx: GpuContext, setup: &GridSetup) -> Result<Self, BackendError> {
        let _ = &setup.profile;
        Ok(GpuBackend {
            ctx,
            nx: setup.nx,
            ny: setup.ny,
            counters: Counters::default(),
        })
    }

    /// The adapter in use, in words.
    pub fn adapter_summary(&self) -> String {
        self.ctx.adapter_summary()
    }
}

impl Backend for GpuBackend {
    type Field = GpuField;
    fn name(&self) -> &'static str {
        "gpu"
    }
    fn precision(&self) -> &'static str {
        "f32"
    }
    fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
    fn field(&mut self) -> Result<GpuField, BackendError> {
        todo!()
    }
    fn upload(&mut self, _dst: &mut GpuField, _host: &[f64]) -> Result<(), BackendError> {
        todo!()
    }
    fn download(&mut self, _src: &GpuField, _host: &mut [f64]) -> Result<(), BackendError> {
        todo!()
    }
    fn set_contact(&mut self, _mask: &[bool]) -> Result<(), BackendError> {
        todo!()
    }
    fn contact(&mut self, _mask: &mut [bool]) -> Result<(), BackendError> {
        todo!()
    }
    fn convolve(&mut self, _src: &GpuField, _dst: &mut GpuField) -> Result<(), BackendError> {
        todo!()
    }
    fn precondition(&mut self, _src: &GpuField, _dst: &mut GpuField) -> Result<(), BackendError> {
        todo!()
    }
    fn residual(&mut self, _u: &GpuField, _d: f64, _r: &mut GpuField) -> Result<(), BackendError> {
        todo!()
    }
    fn dot(&mut self, _a: &GpuField, _b: &GpuField, _out: Slot) -> Result<(), BackendError> {
        todo!()
    }
    fn axpy_ratio(
        &mut self,
        _y: &mut GpuField,
        _x: &GpuField,
        _num: Slot,
        _den: Slot,
        _sign: f64,
    ) -> Result<(), BackendError> {
        todo!()
    }
    fn xpay_ratio(
        &mut self,
        _y: &mut GpuField,
        _x: &GpuField,
        _num: Slot,
        _den: Slot,
    ) -> Result<(), BackendError> {
        todo!()
    }
    fn copy_slot(&mut self, _src: Slot, _dst: Slot) -> Result<(), BackendError> {
        todo!()
    }
    fn read_slots(&mut self, _slots: &[Slot], _out: &mut [f64]) -> Result<(), BackendError> {
        todo!()
    }
    fn update_contact(
        &mut self,
        _p: &mut GpuField,
        _u: &GpuField,
        _d: f64,
        _sigma_c: f64,
    ) -> Result<ContactChange, BackendError> {
        todo!()
    }
    fn first_crossing(
        &mut self,
        _p_old: &GpuField,
        _p_new: &GpuField,
        _sigma_c: f64,
    ) -> Result<f64, BackendError> {
        todo!()
    }
    fn lerp(
        &mut self,
        _a: &GpuField,
        _b: &GpuField,
        _t: f64,
        _dst: &mut GpuField,
    ) -> Result<(), BackendError> {
        todo!()
    }
    fn copy(&mut self, _src: &GpuField, _dst: &mut GpuField) -> Result<(), BackendError> {
        todo!()
    }
    fn sum_and_count(&mut self, _p: &GpuField) -> Result<(f64, usize), BackendError> {
        todo!()
    }
    fn counters(&self) -> Counters {
        self.counters
    }
}
