//! The indenter flags of `jkrbem simulate` (`--indenter` and each shape's parameters), and
//! the shape they describe, a height map read from its file.

use super::super::{input, CliError};
use jkrbem::output::file::{read_regular, ReadError};
use jkrbem::scene::height_map::{HeightMap, HeightMapError};
use jkrbem::scene::{Indenter, MeasuredSurface};
use std::path::PathBuf;
use std::sync::Arc;

/// The largest height-map file read (bytes): the largest map, 16384², as text of up to 32
/// characters a value.
const MAX_MAP_BYTES: u64 = 16384 * 16384 * 32;

/// Memory reading a height map may take per byte of its file (dimensionless): the file's
/// bytes, the heights parsed from them (8 bytes for a text value of 2 characters or more, and
/// the list they grow in) and the map built from them.
const MAP_READ_BYTES_PER_BYTE: u64 = 6;

/// Refuse, before reading it, a map file whose reading would need more memory than the machine
/// has ([`jkrbem::plan::available_memory`]).
fn check_map_memory(path: &std::path::Path, name: &str) -> Result<(), CliError> {
    let Ok(meta) = std::fs::metadata(path) else {
        return Ok(()); // read_regular says why it cannot be read
    };
    let available = jkrbem::plan::available_memory().map_err(input)?;
    let need = meta.len().saturating_mul(MAP_READ_BYTES_PER_BYTE);
    match available {
        Some(a) if meta.is_file() && need > a => Err(input(format!(
            "--height-map {name}: reading this {} file needs up to {} of memory, more than the \
             {} this machine has available (free memory, control group and process limits): \
             save it as a .npy of float32 (4 bytes a height), or crop or subsample it",
            jkrbem::plan::bytes_text(meta.len()),
            jkrbem::plan::bytes_text(need),
            jkrbem::plan::bytes_text(a)
        ))),
        _ => Ok(()),
    }
}

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
    /// Flat punch: the face's radius a (length L, in [1e-30, 1e30]) [default: 1]. Forces are
    /// normalised by Kendall's pull-off force √(8π E* Δγ a³), lengths by a.
    #[arg(long)]
    pub radius: Option<f64>,
    /// Power law h = s·rⁿ: the exponent n (dimensionless, in [1.25, 64]; 2 is the sphere of
    /// radius 1/(2s)) [default: 2].
    #[arg(long)]
    pub exponent: Option<f64>,
    /// Power law h = s·rⁿ: the factor s (length^(1−n), in [1e-30, 1e30]) [default: 0.5: with
    /// n = 2, the sphere of radius 1].
    #[arg(long)]
    pub scale: Option<f64>,
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
                radius: self.radius.unwrap_or(1.0),
            },
            IndenterKind::PowerLaw => Indenter::PowerLaw {
                n: self.exponent.unwrap_or(2.0),
                scale: self.scale.unwrap_or(jkrbem::scene::DEFAULT_POWER_LAW_SCALE),
            },
            IndenterKind::HeightMap => self.height_map()?,
        }))
    }

    /// Refuse a shape's flag given with another `--indenter` (it would be ignored): `others`
    /// are `simulate`'s own shape flags, each with whether it was given and the shapes it is
    /// for.
    pub fn refuse_foreign(&self, others: &[(&str, bool, &[IndenterKind])]) -> Result<(), CliError> {
        use IndenterKind::*;
        let own: [(&str, bool, &[IndenterKind]); 5] = [
            ("--radius", self.radius.is_some(), &[FlatPunch]),
            ("--exponent", self.exponent.is_some(), &[PowerLaw]),
            ("--scale", self.scale.is_some(), &[PowerLaw]),
            ("--height-map", self.height_map.is_some(), &[HeightMap]),
            ("--spacing", self.spacing.is_some(), &[HeightMap]),
        ];
        let name = |k: IndenterKind| {
            clap::ValueEnum::to_possible_value(&k)
                .map(|v| v.get_name().to_string())
                .unwrap_or_default()
        };
        for &(flag, given, shapes) in others.iter().chain(own.iter()) {
            if given && !shapes.contains(&self.indenter) {
                let for_shapes: Vec<String> = shapes.iter().map(|&k| name(k)).collect();
                return Err(input(format!(
                    "{flag} is for --indenter {}, not {} (it would be ignored): leave it out, \
                     or give the indenter it is for",
                    for_shapes.join(" or "),
                    name(self.indenter)
                )));
            }
        }
        Ok(())
    }

    /// The measured surface of --height-map and --spacing, read and placed.
    fn height_map(&self) -> Result<Indenter, CliError> {
        let (Some(path), Some(spacing)) = (&self.height_map, self.spacing) else {
            return Err(input(
                "--indenter height-map needs --height-map FILE and --spacing (the nodes' \
                 spacing, length)",
            ));
        };
        let name = jkrbem::text::printable(&path.display().to_string(), 200);
        check_map_memory(path, &name)?;
        let bytes = read_regular(path, MAX_MAP_BYTES).map_err(|e| match e {
            ReadError::Absent => input(format!("--height-map {name}: no such file")),
            ReadError::Refused(why) => input(format!("--height-map {name}: {why}")),
        })?;
        let map = HeightMap::from_file_bytes(path, &bytes, spacing).map_err(|e| match e {
            HeightMapError::Spacing { .. } => input(format!("--spacing: {e}")),
            e => input(format!("--height-map: {e}")),
        })?;
        drop(bytes);
        let surface = MeasuredSurface::new(map, &name).map_err(input)?;
        Ok(Indenter::HeightMap(Arc::new(surface)))
    }
}
