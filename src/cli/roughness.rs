//! `jkrbem roughness`: a random self-affine rough surface (Fourier synthesis), written as a
//! NumPy `.npy` height map with a JSON sidecar of its parameters and statistics.

use super::parse::value;
use super::stdout::is_stdout;
use super::{input, CliError};
use jkrbem::output::roughness_npy;
use jkrbem::params::{
    words::flags, Spec, CUTOFF, HURST, LARGEST_WAVELENGTH, OUT, RMS_HEIGHT, RMS_SLOPE, ROLLOFF,
    ROUGHNESS_GRID, ROUGHNESS_GRID_Y, SEED, SPACING,
};
use jkrbem::scene::roughness::{self, RoughnessParams};
use jkrbem::session::claim::{write_error, Outputs};
use jkrbem::text::compact;
use std::path::PathBuf;

/// A roughness parameter's `--help`: the schema's text with its unit, range and default, in
/// flags.
fn help(spec: &Spec) -> String {
    let text = spec
        .help
        .strip_prefix("Roughness: the ")
        .unwrap_or(spec.help);
    flags(&format!("The {text} [{}]", spec.terms()))
}

/// Arguments of `jkrbem roughness`. Lengths are in the user's unit L (that of `--spacing`);
/// the heights come out in L.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The surface's heights as a NumPy .npy (float64, shape (ny, nx), row-major, as
    /// `simulate --height-map` reads it); its parameters and achieved statistics go to the
    /// same name with the extension .json. Each is written whole or not at all.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Nodes along x, nx (4 to 16384; any count, though a power of two transforms fastest).
    /// At most 67108864 nodes in all (8192², --grid × --grid-y), and within the memory
    /// available: about 32 bytes per node while the surface is generated (free memory, the
    /// control group's and the process's limits, or JKRBEM_MEMORY_LIMIT in bytes), checked
    /// before any work.
    #[arg(long, value_name = "N", value_parser = value::<usize>(ROUGHNESS_GRID))]
    pub grid: usize,
    /// Nodes along y, ny (4 to 16384; the total and the memory bound it as --grid says)
    /// [default: as --grid].
    #[arg(long, value_name = "N", value_parser = value::<usize>(ROUGHNESS_GRID_Y))]
    pub grid_y: Option<usize>,
    /// The spacing Δ of the nodes (length L, in [1e-30, 1e30]); the domain is grid × spacing
    /// along x and grid-y × spacing along y, and the surface is periodic over it.
    #[arg(long, value_name = "X", value_parser = value::<f64>(SPACING))]
    pub spacing: f64,
    #[arg(long, value_name = "X", help = help(HURST), value_parser = value::<f64>(HURST))]
    pub hurst: f64,
    #[arg(long, value_name = "X", help = help(RMS_HEIGHT), value_parser = value::<f64>(RMS_HEIGHT))]
    pub rms_height: Option<f64>,
    #[arg(long, value_name = "X", help = help(RMS_SLOPE), value_parser = value::<f64>(RMS_SLOPE))]
    pub rms_slope: Option<f64>,
    #[arg(long, value_name = "X", help = help(ROLLOFF), value_parser = value::<f64>(ROLLOFF))]
    pub rolloff: Option<f64>,
    #[arg(long, value_name = "X", help = help(CUTOFF), value_parser = value::<f64>(CUTOFF))]
    pub cutoff: Option<f64>,
    #[arg(long, value_name = "X", help = help(LARGEST_WAVELENGTH), value_parser = value::<f64>(LARGEST_WAVELENGTH))]
    pub largest_wavelength: Option<f64>,
    #[arg(long, value_name = "N", default_value_t = 0, hide_default_value = true, help = help(SEED), value_parser = value::<u64>(SEED))]
    pub seed: u64,
}

/// Run `jkrbem roughness`.
pub fn run(args: Args) -> Result<(), CliError> {
    let params = RoughnessParams {
        grid: args.grid,
        grid_y: args.grid_y,
        spacing: args.spacing,
        hurst: args.hurst,
        rms_height: args.rms_height,
        rms_slope: args.rms_slope,
        rolloff: args.rolloff,
        cutoff: args.cutoff,
        largest_wavelength: args.largest_wavelength,
        seed: args.seed,
    };
    if is_stdout(&args.out) {
        return Err(input(format!(
            "{OUT} -: the surface is a binary .npy beside a .json sidecar; give a file name"
        )));
    }
    let resolved = params.resolved().map_err(input)?;
    // Before any work: the surface must fit in the memory this machine can give it.
    jkrbem::plan::check_roughness_memory(&params).map_err(input)?;
    let sidecar = roughness_npy::sidecar_path(&args.out);
    let _claimed = Outputs::claim(&[(args.out.clone(), OUT.into()), (sidecar, OUT.into())])?;
    let map = roughness::generate(&params).map_err(input)?;
    let written = roughness_npy::save(&map, &params, &args.out).map_err(write_error(OUT))?;
    let s = roughness::statistics(&map);
    let (nx, ny) = (map.nx(), map.ny());
    let c = |v: Option<f64>| v.map_or_else(|| "-".into(), compact);
    outln!(
        "{nx} × {ny} nodes at spacing {} (H = {}, seed {}) written to {}; parameters and \
         statistics to {}",
        compact(params.spacing),
        compact(params.hurst),
        params.seed,
        args.out.display(),
        written.display()
    );
    outln!(
        "wavelengths: largest {}, roll-off {}, cut-off {} (length)",
        c(resolved.largest_wavelength),
        c(resolved.rolloff),
        c(resolved.cutoff)
    );
    outln!("rms height    {} (length)", compact(s.rms_height));
    outln!(
        "rms slope     {} (spectral rms of |∇h|)",
        compact(s.rms_slope)
    );
    outln!(
        "rms curvature {} (1/length, spectral rms of ½∇²h)",
        compact(s.rms_curvature)
    );
    Ok(())
}
