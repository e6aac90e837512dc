//! The tests on libtest-mimic (`harness = false`): the backend contract on every backend
//! (`conformance`: cpu, cpu-periodic, gpu and gpu-periodic) and the tests that need a GPU adapter. Where no
//! adapter exists, those are reported as ignored with the reason, never as passed; with
//! `JKRBEM_REQUIRE_GPU=1` that is a failure instead. Without the `gpu` feature only the CPU
//! backends' conformance runs; without the `cli` feature none of the tests that run the binary
//! does. One test binary; each former file is a module, its tests named
//! `<module>::<test>`.

#[path = "../common/mod.rs"]
mod common;

// The tests that run the binary need the `cli` feature too, which builds it.
#[cfg(all(feature = "gpu", feature = "cli"))]
mod cli_gpu;
mod conformance;
#[cfg(all(feature = "gpu", feature = "cli"))]
mod device_session;
#[cfg(feature = "gpu")]
mod failure_cg_gpu;
#[cfg(feature = "gpu")]
mod gpu_backend;
#[cfg(feature = "gpu")]
mod gpu_fft;
#[cfg(feature = "gpu")]
mod gpu_periodic;
#[cfg(feature = "gpu")]
mod gpu_pulloff;
#[cfg(feature = "gpu")]
mod gpu_rough;
#[cfg(feature = "gpu")]
mod gpu_traffic;

fn main() {
    // Before any thread or adapter: no "XDG_RUNTIME_DIR is invalid" lines from the Vulkan
    // device-select layer on a machine without a display (the command does the same).
    #[cfg(feature = "gpu")]
    jkrbem::backend::gpu::headless::quiet_display_probe();
    let args = libtest_mimic::Arguments::from_args();
    #[cfg(feature = "gpu")]
    let missing = common::gpu_missing();
    #[cfg(not(feature = "gpu"))]
    let missing: Option<String> = None;
    #[cfg_attr(not(feature = "gpu"), allow(unused_mut))]
    let mut all = conformance::all(missing.as_ref().map(|_| "no GPU adapter"));
    #[cfg(feature = "gpu")]
    {
        let missing = missing.as_deref();
        #[cfg(feature = "cli")]
        all.extend(cli_gpu::trials(missing));
        #[cfg(feature = "cli")]
        all.extend(device_session::trials(missing));
        all.extend(failure_cg_gpu::trials(missing));
        all.extend(gpu_backend::trials(missing));
        all.extend(gpu_fft::trials(missing));
        all.extend(gpu_periodic::trials(missing));
        all.extend(gpu_pulloff::trials(missing));
        all.extend(gpu_rough::trials(missing));
        all.extend(gpu_traffic::trials(missing));
    }
    let conclusion = libtest_mimic::run(&args, all);
    exit_without_driver_teardown(if conclusion.has_failed() { 101 } else { 0 })
}

/// Ends the process once every result is printed, without the C exit handlers. Mesa's software
/// Vulkan device (lavapipe, Mesa 22.3 in CI) once aborted with "double free or corruption" in
/// its own teardown after this binary had printed "100 passed; 0 failed": the verdict was in,
/// the crash was the driver's clean-up at exit. `_exit` skips that clean-up (the kernel frees
/// the process) and keeps the verdict; a failure still exits with libtest's 101.
fn exit_without_driver_teardown(code: i32) -> ! {
    use std::io::Write;
    let _ = std::io::stdout().flush();
    let _ = std::io::stderr().flush();
    // SAFETY: `_exit` ends the process at once; nothing runs after it, and the test threads
    // have all been joined by `libtest_mimic::run`.
    unsafe { libc::_exit(code) }
}
