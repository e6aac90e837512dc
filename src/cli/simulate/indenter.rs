//! The indenter flags of `jkrbem simulate` (`--indenter` and each shape's parameters), and
//! the shape they describe, a height map read from its file.

use super::super::{input, CliError};
use jkrbem::output::file::{read_regular, ReadError};
use jkrbem::scene::height_map::HeightMap;
use jkrbem::scene::{Indenter, MeasuredSurface};
use std::path::PathBuf;
use std::sync::Arc;

/// The largest height-map file read (bytes): the largest map, 16384², as text of up to 32
/// characters a value.
const MAX_MAP_BYTES: u64 = 16384 * 16384 * 32;

/// The indenter shapes `--indenter` takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum IndenterKind {
    /// h = x²/(2 R1) + y²/(2 R2): --ratio or --r1, --r2.
    Ellipsoid,
    /// A flat cylindrical punch of radius --radius.
    FlatPunch,
    /// A measured topography: --height-map FILE, --spacing.
    HeightMap,
    /// Axisymmetric h = s·rⁿ: --exponent n, --scale s.
    PowerLaw,
}

/// The indenter's flags (the ellipsoid's radii are `simulate`'s own --ratio, --r1, --r2).
#[derive(Debug, clap::Args)]
pub struct IndenterArgs {
    /// The indenter's shape: `ellipsoid` (--ratio or --r1, --r2), `flat-punch` (--radius),
    /// `power-law` (h = s·rⁿ: --exponent, --scale) or `height-map` (--height-map,
    /// --spacing). The ellipsoid has a convergence law (--accuracy, --extrapolate); the
    /// others run one grid, set beside the closed form of their Δx → 0 limit where one
    /// exists (Kendall; the power law's JKR solution) [default: ellipsoid].
    #[arg(long, value_enum, default_value_t = IndenterKind::Ellipsoid)]
    pub indenter: IndenterKind,
    /// Flat punch: the face's radius a (length L, in [1e-30, 1e30]). Forces are normalised
    /// by Kendall's pull-off force √(8π E* Δγ a³), lengths by a.
    #[arg(long, default_value_t = 1.0)]
    pub radius: f64,
    /// Power law h = s·rⁿ: the exponent n (dimensionless, in [1.25, 64]; 2 is the sphere of
    /// radius 1/(2s)).
    #[arg(long, default_value_t = 2.0)]
    pub exponent: f64,
    /// Power law h = s·rⁿ: the factor s (length^(1−n), in [1e-30, 1e30]).
    #[arg(long, default_value_t = 0.5)]
    pub scale: f64,
    /// Height map: the file of heights (length L; larger is further from the half-space), a
    /// NumPy .npy of float64/float32 (rows along y) or a text grid (one row per line, values
    /// separated by spaces or commas, # comments). Its apex (where a quadratic fitted around
    /// the lowest node is lowest) is placed at the domain's centre; the fit's principal radii
    /// size the domain and normalise the results like an ellipsoid's.
    #[arg(long)]
    pub height_map: Option<PathBuf>,
    /// Height map: the spacing of its nodes (length L, in [1e-30, 1e30]).
    #[arg(long)]
    pub spacing: Option<f64>,
}

impl IndenterArgs {
    /// The shape other than the ellipsoid these flags describe (`None` for the ellipsoid,
    /// whose radii `simulate` reads itself); a height map is read and placed.
    pub fn other_shape(&self) -> Result<Option<Indenter>, CliError> {
        Ok(Some(match self.indenter {
            IndenterKind::Ellipsoid => return Ok(None),
            IndenterKind::FlatPunch => Indenter::FlatPunch {
                radius: self.radius,
            },
            IndenterKind::PowerLaw => Indenter::PowerLaw {
                n: self.exponent,
                scale: self.scale,
            },
            IndenterKind::HeightMap => self.height_map()?,
        }))
    }

    /// The measured surface of --height-map and --spacing, read and placed.
    fn height_map(&self) -> Result<Indenter, CliError> {
        let (Some(path), Some(spacing)) = (&self.height_map, self.spacing) else {
            return Err(input(
                "--indenter height-map needs --height-map FILE and --spacing (the nodes' \
                 spacing, length)",
            ));
        };
        let name = path.display().to_string();
        let bytes = read_regular(path, MAX_MAP_BYTES).map_err(|e| match e {
            ReadError::Absent => input(format!("--height-map {name}: no such file")),
            ReadError::Refused(why) => input(format!("--height-map {name}: {why}")),
        })?;
        let map = HeightMap::from_file_bytes(path, &bytes, spacing)
            .map_err(|e| input(format!("--height-map: {e}")))?;
        let surface = MeasuredSurface::new(map, &name).map_err(input)?;
        Ok(Indenter::HeightMap(Arc::new(surface)))
    }
}
