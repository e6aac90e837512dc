//! Choosing a wgpu adapter and opening a device on it.

use crate::backend::BackendError;
use std::sync::{Arc, Mutex};

/// Which kind of adapter [`GpuContext::new`] should open.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AdapterPreference {
    /// The best adapter present: a discrete GPU, else an integrated one, else a virtual
    /// one, else a software (CPU) implementation such as Mesa's lavapipe.
    #[default]
    Best,
    /// Only a discrete GPU.
    Discrete,
    /// Only an integrated GPU.
    Integrated,
    /// Only a software (CPU) implementation such as lavapipe or SwiftShader.
    Software,
}

/// One adapter as `jkrbem devices` reports it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AdapterInfoLine {
    /// Adapter name as the driver gives it (e.g. "llvmpipe (LLVM 19.1.7, 256 bits)").
    pub name: String,
    /// Device type ("DiscreteGpu", "IntegratedGpu", "VirtualGpu", "Cpu", "Other").
    pub device_type: String,
    /// Graphics API wgpu reaches it through ("Vulkan", "Metal", "Dx12", "Gl").
    pub backend: String,
    /// Largest storage buffer one binding can see (bytes).
    pub max_storage_buffer_binding_size: u64,
    /// Largest buffer that can be created (bytes).
    pub max_buffer_size: u64,
    /// Workgroup (shared) memory available to one compute workgroup (bytes).
    pub max_compute_workgroup_storage_size: u32,
    /// The largest square grid N × N the GPU backend can hold on this adapter (elements).
    pub largest_grid: usize,
}

impl std::fmt::Display for AdapterInfoLine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} ({}, {}): storage binding {} MiB, buffer {} MiB, workgroup memory {} KiB, \
             grids up to {}×{}",
            self.name,
            self.device_type,
            self.backend,
            self.max_storage_buffer_binding_size >> 20,
            self.max_buffer_size >> 20,
            self.max_compute_workgroup_storage_size >> 10,
            self.largest_grid,
            self.largest_grid
        )
    }
}

/// An open wgpu device and its queue, with what was learnt about the adapter. Clones share
/// the device.
#[derive(Clone)]
pub struct GpuContext {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    limits: wgpu::Limits,
    /// The first validation error, out-of-memory or device loss the driver reported.
    failure: Arc<Mutex<Option<String>>>,
}

impl std::fmt::Debug for GpuContext {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuContext")
            .field("adapter", &self.adapter_summary())
            .finish_non_exhaustive()
    }
}

/// Rank of a device type when choosing the best adapter (higher is better).
fn type_rank(t: wgpu::DeviceType) -> u32 {
    match t {
        wgpu::DeviceType::DiscreteGpu => 4,
        wgpu::DeviceType::IntegratedGpu => 3,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Cpu => 1,
        wgpu::DeviceType::Other => 0,
    }
}

/// Rank of a graphics API for the same device (native compute APIs before OpenGL).
fn backend_rank(b: wgpu::Backend) -> u32 {
    match b {
        wgpu::Backend::Vulkan | wgpu::Backend::Metal | wgpu::Backend::Dx12 => 2,
        wgpu::Backend::Gl => 1,
        _ => 0,
    }
}

fn accepts(preference: AdapterPreference, t: wgpu::DeviceType) -> bool {
    match preference {
        AdapterPreference::Best => true,
        AdapterPreference::Discrete => t == wgpu::DeviceType::DiscreteGpu,
        AdapterPreference::Integrated => t == wgpu::DeviceType::IntegratedGpu,
        AdapterPreference::Software => t == wgpu::DeviceType::Cpu,
    }
}

/// Every adapter wgpu can see, with the backends allowed by `WGPU_BACKEND` (default: all).
fn adapters() -> Vec<wgpu::Adapter> {
    let desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    let backends = desc.backends;
    let instance = wgpu::Instance::new(desc);
    pollster::block_on(instance.enumerate_adapters(backends))
        .into_iter()
        // Compute shaders are required; WebGL-class OpenGL adapters lack them.
        .filter(|a| {
            a.get_downlevel_capabilities()
                .flags
                .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
        })
        .collect()
}

fn info_line(adapter: &wgpu::Adapter) -> AdapterInfoLine {
    let info = adapter.get_info();
    let limits = adapter.limits();
    AdapterInfoLine {
        name: info.name,
        device_type: format!("{:?}", info.device_type),
        backend: format!("{:?}", info.backend),
        max_storage_buffer_binding_size: limits.max_storage_buffer_binding_size,
        max_buffer_size: limits.max_buffer_size,
        max_compute_workgroup_storage_size: limits.max_compute_workgroup_storage_size,
        largest_grid: super::backend::largest_square_grid(&limits),
    }
}

/// Every compute-capable adapter on this machine, best first (for `jkrbem devices`).
pub fn list_adapters() -> Vec<AdapterInfoLine> {
    let mut all = adapters();
    sort_best_first(&mut all);
    all.iter().map(info_line).collect()
}

fn sort_best_first(adapters: &mut [wgpu::Adapter]) {
    adapters.sort_by_key(|a| {
        let info = a.get_info();
        std::cmp::Reverse((type_rank(info.device_type), backend_rank(info.backend)))
    });
}

impl GpuContext {
    /// Opens a device on the best adapter that `preference` accepts, with the adapter's own
    /// limits (so storage buffers as large as the hardware allows can be bound).
    ///
    /// Fails with [`BackendError::Unavailable`] when no adapter fits, saying which exist.
    pub fn new(preference: AdapterPreference) -> Result<GpuContext, BackendError> {
        let mut all = adapters();
        sort_best_first(&mut all);
        let seen: Vec<String> = all.iter().map(|a| info_line(a).to_string()).collect();
        let Some(adapter) = all
            .into_iter()
            .find(|a| accepts(preference, a.get_info().device_type))
        else {
            let msg = if seen.is_empty() {
                format!(
                    "no GPU adapter with compute shaders was found: install a Vulkan, Metal or \
                     DX12 driver (on Linux without a GPU, Mesa's lavapipe gives a software one), \
                     or run with `{} cpu`",
                    crate::params::BACKEND
                )
            } else {
                format!(
                    "no {preference:?} GPU adapter was found; available: {}",
                    seen.join("; ")
                )
            };
            return Err(BackendError::Unavailable(msg));
        };
        let info = adapter.get_info();
        let limits = adapter.limits();
        // Timestamp queries feed `jkrbem bench --profile`; asked for only where they exist.
        let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("jkrbem"),
            required_features: features,
            required_limits: limits.clone(),
            ..Default::default()
        }))
        .map_err(|e| BackendError::Unavailable(format!("{}: {e}", info.name)))?;
        let failure: Arc<Mutex<Option<String>>> = Arc::default();
        let sink = failure.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            record_failure(&sink, e.to_string());
        }));
        let sink = failure.clone();
        device.set_device_lost_callback(move |reason, message| {
            record_failure(&sink, format!("device lost ({reason:?}): {message}"));
        });
        Ok(GpuContext {
            device,
            queue,
            info,
            limits,
            failure,
        })
    }

    /// The wgpu device.
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The device's command queue.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }

    /// Whether the device can write timestamps around compute passes (for the profiler).
    pub fn has_timestamps(&self) -> bool {
        self.device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
    }

    /// The limits the device was opened with (the adapter's own).
    pub fn limits(&self) -> &wgpu::Limits {
        &self.limits
    }

    /// Name, type and backend of the adapter in use, e.g.
    /// "llvmpipe (LLVM 19.1.7, 256 bits) [Cpu, Vulkan, software]".
    pub fn adapter_summary(&self) -> String {
        let kind = match self.info.device_type {
            wgpu::DeviceType::DiscreteGpu => "discrete GPU",
            wgpu::DeviceType::IntegratedGpu => "integrated GPU",
            wgpu::DeviceType::VirtualGpu => "virtual GPU",
            wgpu::DeviceType::Cpu => "software (CPU) adapter",
            wgpu::DeviceType::Other => "unknown adapter type",
        };
        format!(
            "{} [{kind}, {:?}, driver {} {}]",
            self.info.name, self.info.backend, self.info.driver, self.info.driver_info
        )
    }

    /// Whether the adapter is real GPU hardware (discrete, integrated or virtual), not a
    /// software implementation such as lavapipe.
    pub fn is_hardware(&self) -> bool {
        matches!(
            self.info.device_type,
            wgpu::DeviceType::DiscreteGpu
                | wgpu::DeviceType::IntegratedGpu
                | wgpu::DeviceType::VirtualGpu
        )
    }

    /// Blocks until all submitted work has finished; fails if the device reported an error.
    pub fn wait(&self) -> Result<(), BackendError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| BackendError::DeviceLost {
                backend: "gpu",
                reason: e.to_string(),
            })?;
        self.check()
    }

    /// Fails with [`BackendError::DeviceLost`] if the driver has reported a lost device, an
    /// out-of-memory or a validation error since the device was opened.
    pub fn check(&self) -> Result<(), BackendError> {
        match self.failure.lock().map(|f| f.clone()) {
            Ok(None) => Ok(()),
            Ok(Some(reason)) => Err(BackendError::DeviceLost {
                backend: "gpu",
                reason,
            }),
            Err(_) => Err(BackendError::DeviceLost {
                backend: "gpu",
                reason: "the error record was poisoned".into(),
            }),
        }
    }

    /// Destroys the device, as a driver reset would: every later operation fails with
    /// [`BackendError::DeviceLost`]. For tests of the device-loss path.
    pub fn lose_device(&self) {
        self.device.destroy();
    }
}

fn record_failure(sink: &Mutex<Option<String>>, message: String) {
    if let Ok(mut f) = sink.lock() {
        f.get_or_insert(message);
    }
}

/// Name of the environment variable that turns a missing adapter into a test failure.
pub const REQUIRE_GPU_ENV: &str = "JKRBEM_REQUIRE_GPU";

/// A context for GPU tests: `Some` when an adapter exists; otherwise prints why the test is
/// skipped and returns `None`, unless `JKRBEM_REQUIRE_GPU=1`, in which case it panics.
pub fn test_context() -> Option<GpuContext> {
    match GpuContext::new(AdapterPreference::Best) {
        Ok(ctx) => Some(ctx),
        Err(e) => {
            if std::env::var(REQUIRE_GPU_ENV).as_deref() == Ok("1") {
                panic!("{REQUIRE_GPU_ENV}=1 but no GPU adapter is usable: {e}");
            }
            eprintln!("skipping GPU test: {e} (set {REQUIRE_GPU_ENV}=1 to make this a failure)");
            None
        }
    }
}
