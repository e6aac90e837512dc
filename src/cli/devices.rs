//! `jkrbem devices`: the GPU adapters wgpu sees, best first, with the limits that decide
//! which grids the GPU backend can hold.

use super::CliError;

/// Arguments of `jkrbem devices` (none).
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `jkrbem devices`.
#[cfg(not(feature = "gpu"))]
pub fn run(_args: Args) -> Result<(), CliError> {
    outln!(
        "this jkrbem was built without the `gpu` feature: no GPU adapter is looked for, and \
         every run uses the CPU backend"
    );
    Ok(())
}

/// Run `jkrbem devices`.
#[cfg(feature = "gpu")]
pub fn run(_args: Args) -> Result<(), CliError> {
    use jkrbem::backend::gpu::list_adapters;
    let adapters = list_adapters();
    if adapters.is_empty() {
        outln!(
            "no GPU adapter with compute shaders was found; `--backend auto` will use the CPU \
             (on Linux without a GPU, Mesa's lavapipe gives a software adapter: \
             apt-get install mesa-vulkan-drivers libvulkan1)"
        );
        return Ok(());
    }
    outln!("GPU adapters, best first (`--backend gpu` takes the first):");
    for (i, a) in adapters.iter().enumerate() {
        let software = if a.device_type == "Cpu" {
            "  [software: `--backend auto` skips it]"
        } else {
            ""
        };
        outln!("{}. {a}{software}", i + 1);
    }
    Ok(())
}
