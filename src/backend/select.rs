//! Opening the backend a user asked for: `cpu`, `gpu` (the best adapter) or `auto` (a
//! hardware GPU if there is one, else the CPU), in the arithmetic asked for ([`Precision`]),
//! behind one enum the solver is dispatched on.

use super::cpu::CpuBackend;
#[cfg(feature = "gpu")]
use super::gpu::{AdapterPreference, GpuBackend, GpuContext};
use super::{BackendError, GridSetup};

/// Which backend to open.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum BackendKind {
    /// A hardware GPU if there is one, else the CPU.
    #[default]
    Auto,
    /// The rustfft CPU backend (f64; its FFT passes in f32 where asked).
    Cpu,
    /// The wgpu GPU backend (f32) on the best adapter, software adapters included.
    Gpu,
}

/// The arithmetic of the convolution's FFT passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Precision {
    /// The backend's own: f64 on the CPU, f32 on the GPU.
    #[default]
    Auto,
    /// f64 (the CPU only: the reference).
    F64,
    /// f32: the GPU, or the CPU's FFT passes at twice the SIMD width (its vectors and
    /// reductions stay f64).
    F32,
}

impl Precision {
    /// Why `kind` cannot run in this precision, if it cannot: the GPU has no f64.
    pub fn refusal(self, kind: BackendKind) -> Option<String> {
        (kind == BackendKind::Gpu && self == Precision::F64).then(|| {
            format!(
                "{} f64 is not offered by {} gpu, which computes in f32 only: use {} cpu for \
                 f64, or {} f32 (or auto) on the GPU",
                crate::params::PRECISION,
                crate::params::BACKEND,
                crate::params::BACKEND,
                crate::params::PRECISION
            )
        })
    }
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
    open_in(kind, Precision::Auto, setup, periodic)
}

/// [`open_with`] in the arithmetic `precision`: `f32` on the CPU runs its convolution's FFT
/// passes in f32 ([`CpuBackend::new_f32`]); `f64` is refused on `gpu` ([`Precision::refusal`])
/// and takes the CPU under `auto`; `auto` is the backend's own.
pub fn open_in(
    kind: BackendKind,
    precision: Precision,
    setup: &GridSetup,
    periodic: bool,
) -> Result<Opened, BackendError> {
    if let Some(why) = precision.refusal(kind) {
        return Err(BackendError::Unavailable(why));
    }
    let f32 = precision == Precision::F32;
    let arithmetic = if f32 { "f32 FFT passes" } else { "f64" };
    let cpu = |why: String| -> Result<Opened, BackendError> {
        let backend = if f32 {
            CpuBackend::new_f32(setup, periodic)?
        } else if periodic {
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
        BackendKind::Cpu => cpu(format!("cpu ({arithmetic}, rustfft)")),
        #[cfg(not(feature = "gpu"))]
        BackendKind::Gpu => Err(BackendError::Unavailable(format!(
            "this jkrbem was built without the `gpu` feature: use {} cpu, or rebuild with the \
             default features",
            crate::params::BACKEND
        ))),
        #[cfg(not(feature = "gpu"))]
        BackendKind::Auto => cpu(format!(
            "cpu ({arithmetic}, rustfft) (auto: built without the gpu feature)"
        )),
        #[cfg(feature = "gpu")]
        BackendKind::Gpu => {
            let ctx = GpuContext::new(AdapterPreference::Best)?;
            let mut note = format!("gpu (f32, wgpu) on {}", ctx.adapter_summary());
            if !ctx.is_hardware() {
                note.push_str(&format!(
                    " — a software adapter: expect it to be slower than {} cpu",
                    crate::params::BACKEND
                ));
            }
            let backend = gpu(ctx)?;
            Ok(Opened {
                backend: AnyBackend::Gpu(Box::new(backend)),
                note,
            })
        }
        #[cfg(feature = "gpu")]
        BackendKind::Auto if precision == Precision::F64 => cpu(format!(
            "cpu (f64, rustfft) (auto: {} f64, which only the CPU offers)",
            crate::params::PRECISION
        )),
        #[cfg(feature = "gpu")]
        BackendKind::Auto => match GpuContext::new(AdapterPreference::Best) {
            Ok(ctx) if ctx.is_hardware() => {
                let summary = ctx.adapter_summary();
                match gpu(ctx) {
                    Ok(b) => Ok(Opened {
                        backend: AnyBackend::Gpu(Box::new(b)),
                        note: format!("gpu (f32, wgpu) on {summary} (auto: hardware GPU found)"),
                    }),
                    Err(e) => cpu(format!(
                        "cpu ({arithmetic}, rustfft) (auto: {summary} refused: {e})"
                    )),
                }
            }
            Ok(ctx) => cpu(format!(
                "cpu ({arithmetic}, rustfft) (auto: the only GPU adapter is software: {})",
                ctx.adapter_summary()
            )),
            Err(e) => cpu(format!("cpu ({arithmetic}, rustfft) (auto: {e})")),
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

    /// The arithmetic of the convolution ("f64", "f32"): the GPU's fields, the CPU's FFT
    /// passes.
    pub fn precision(&self) -> &'static str {
        use super::Device;
        match self {
            AnyBackend::Cpu(b) => b.precision(),
            #[cfg(feature = "gpu")]
            AnyBackend::Gpu(b) => b.precision(),
        }
    }
}
