//! Opening the backend a user asked for: `cpu`, `gpu` (the best adapter) or `auto` (a
//! hardware GPU if there is one, else the CPU), behind one enum the solver is dispatched on.

use super::cpu::CpuBackend;
#[cfg(feature = "gpu")]
use super::gpu::{AdapterPreference, GpuBackend, GpuContext};
use super::{BackendError, GridSetup};

/// Which backend to open.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Default,
    clap::ValueEnum,
    serde::Serialize,
    serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum BackendKind {
    /// A hardware GPU if there is one, else the CPU.
    #[default]
    Auto,
    /// The rustfft CPU backend (f64).
    Cpu,
    /// The wgpu GPU backend (f32) on the best adapter, software adapters included.
    Gpu,
}

/// An opened backend of either kind.
pub enum AnyBackend {
    /// The CPU backend.
    Cpu(Box<CpuBackend>),
    /// The GPU backend.
    #[cfg(feature = "gpu")]
    Gpu(Box<GpuBackend>),
}

/// A backend and a line saying what was chosen and why (for the user).
pub struct Opened {
    /// The backend.
    pub backend: AnyBackend,
    /// E.g. "gpu: NVIDIA H100 [discrete GPU, Vulkan, …]" or "cpu (auto: no hardware GPU: …)".
    pub note: String,
}

/// Open the backend `kind` for `setup`.
///
/// `gpu` takes the best adapter (discrete, integrated, virtual, then software such as
/// lavapipe, saying so) and fails if there is none or the grid does not fit; `auto` takes a
/// hardware GPU whose limits hold the grid, and otherwise the CPU backend, saying why.
pub fn open(kind: BackendKind, setup: &GridSetup) -> Result<Opened, BackendError> {
    open_with(kind, setup, false)
}

/// [`open`] with the padded convolution (`periodic` false: an isolated contact) or the
/// periodic one (a surface periodic over the domain: [`crate::backend::kernel`]'s notes):
/// [`CpuBackend::new_periodic`] or `GpuBackend::new_periodic`, chosen as [`open`] chooses.
pub fn open_with(
    kind: BackendKind,
    setup: &GridSetup,
    periodic: bool,
) -> Result<Opened, BackendError> {
    let cpu = |why: String| -> Result<Opened, BackendError> {
        let backend = if periodic {
            CpuBackend::new_periodic(setup)?
        } else {
            CpuBackend::new(setup)?
        };
        Ok(Opened {
            backend: AnyBackend::Cpu(Box::new(backend)),
            note: why,
        })
    };
    #[cfg(feature = "gpu")]
    let gpu = |ctx: GpuContext| {
        if periodic {
            GpuBackend::new_periodic(ctx, setup)
        } else {
            GpuBackend::new(ctx, setup)
        }
    };
    match kind {
        BackendKind::Cpu => cpu("cpu (f64, rustfft)".into()),
        #[cfg(not(feature = "gpu"))]
        BackendKind::Gpu => Err(BackendError::Unavailable(format!(
            "this jkrbem was built without the `gpu` feature: use {} cpu, or rebuild with the \
             default features",
            crate::run::schema::BACKEND
        ))),
        #[cfg(not(feature = "gpu"))]
        BackendKind::Auto => cpu("cpu (f64, rustfft) (auto: built without the gpu feature)".into()),
        #[cfg(feature = "gpu")]
        BackendKind::Gpu => {
            let ctx = GpuContext::new(AdapterPreference::Best)?;
            let mut note = format!("gpu (f32, wgpu) on {}", ctx.adapter_summary());
            if !ctx.is_hardware() {
                note.push_str(&format!(
                    " — a software adapter: expect it to be slower than {} cpu",
                    crate::run::schema::BACKEND
                ));
            }
            let backend = gpu(ctx)?;
            Ok(Opened {
                backend: AnyBackend::Gpu(Box::new(backend)),
                note,
            })
        }
        #[cfg(feature = "gpu")]
        BackendKind::Auto => match GpuContext::new(AdapterPreference::Best) {
            Ok(ctx) if ctx.is_hardware() => {
                let summary = ctx.adapter_summary();
                match gpu(ctx) {
                    Ok(b) => Ok(Opened {
                        backend: AnyBackend::Gpu(Box::new(b)),
                        note: format!("gpu (f32, wgpu) on {summary} (auto: hardware GPU found)"),
                    }),
                    Err(e) => cpu(format!("cpu (f64, rustfft) (auto: {summary} refused: {e})")),
                }
            }
            Ok(ctx) => cpu(format!(
                "cpu (f64, rustfft) (auto: the only GPU adapter is software: {})",
                ctx.adapter_summary()
            )),
            Err(e) => cpu(format!("cpu (f64, rustfft) (auto: {e})")),
        },
    }
}

/// Run `$body` with `$b` bound to `&mut` the concrete backend inside an [`AnyBackend`], so
/// generic solver code is monomorphised for each backend.
#[macro_export]
macro_rules! with_backend {
    ($any:expr, $b:ident => $body:expr) => {
        match $any {
            $crate::backend::select::AnyBackend::Cpu(cpu) => {
                let $b = &mut **cpu;
                $body
            }
            #[cfg(feature = "gpu")]
            $crate::backend::select::AnyBackend::Gpu(gpu) => {
                let $b = &mut **gpu;
                $body
            }
        }
    };
}

impl AnyBackend {
    /// Short name of the backend ("cpu", "gpu", "cpu-periodic", "gpu-periodic").
    pub fn name(&self) -> &'static str {
        use super::Device;
        match self {
            AnyBackend::Cpu(b) => b.name(),
            #[cfg(feature = "gpu")]
            AnyBackend::Gpu(b) => b.name(),
        }
    }

    /// The backend's own interval between CG residual reads (iterations): 1 on the CPU,
    /// more on a device that queues work ahead of the host.
    pub fn check_every(&self) -> usize {
        use super::CgKernels;
        match self {
            AnyBackend::Cpu(b) => b.check_every(),
            #[cfg(feature = "gpu")]
            AnyBackend::Gpu(b) => b.check_every(),
        }
    }

    /// The device in words: the CPU model and its threads, or the GPU adapter.
    pub fn device_summary(&self) -> String {
        match self {
            AnyBackend::Cpu(_) => {
                let model = std::fs::read_to_string("/proc/cpuinfo")
                    .ok()
                    .and_then(|s| {
                        s.lines()
                            .find(|l| l.starts_with("model name"))
                            .and_then(|l| l.split_once(':'))
                            .map(|(_, v)| v.trim().to_string())
                    })
                    .unwrap_or_else(|| std::env::consts::ARCH.to_string());
                format!("{model} ({} threads)", rayon::current_num_threads())
            }
            #[cfg(feature = "gpu")]
            AnyBackend::Gpu(g) => g.adapter_summary(),
        }
    }

    /// The arithmetic of the device fields ("f64", "f32").
    pub fn precision(&self) -> &'static str {
        use super::Device;
        match self {
            AnyBackend::Cpu(b) => b.precision(),
            #[cfg(feature = "gpu")]
            AnyBackend::Gpu(b) => b.precision(),
        }
    }
}
