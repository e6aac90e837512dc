//! Measured indenter topography: a height map on a square lattice.
//!
//! A [`HeightMap`] holds the heights `h[j][i]` of an indenter surface, in the
//! caller's length unit, on a square lattice whose spacing `spacing` is in the
//! same length unit. A larger `h` is further from the elastic half-space, so
//! the part of the indenter that touches first is the map's minimum. The
//! heights are stored row-major: index `i` runs along a row (x, fastest) and
//! index `j` picks the row (y).
//!
//! # Coordinates
//!
//! The map is centred on the origin. Node `(i, j)` lies at
//! `x = (i - (nx - 1) / 2) * spacing` and `y = (j - (ny - 1) / 2) * spacing`,
//! both in length units. [`HeightMap::sample`] interpolates in these
//! coordinates and measures heights from the map's minimum.
//!
//! # Input formats
//!
//! * **NumPy `.npy`** (format versions 1.0, 2.0 and 3.0): a 2-D array of
//!   float64 or float32 (`'<f8'`, `'<f4'`, `'=f8'`, `'=f4'`, `'>f8'`,
//!   `'>f4'`). Shape `(rows, cols)` gives `ny = rows`, `nx = cols`. Arrays
//!   written with `fortran_order: True` are transposed to row-major on load,
//!   so `a[j, i]` in NumPy always becomes node `(i, j)`.
//! * **Plain text**: one map row per non-empty line, values separated by
//!   whitespace and/or commas. Everything from a `#` to the end of its line is
//!   a comment. The first data line is row `j = 0` (the most negative y).
//!
//! # Limits
//!
//! Each axis must have between 4 and 16384 nodes. The spacing must be a
//! finite length in `[1e-30, 1e30]`. Every height must be finite with
//! magnitude at most `1e30`, and the map must not be flat. No function in
//! this module panics, whatever its input: every problem comes back as a
//! [`HeightMapError`] or, for queries, as `None`.

use std::path::Path;
use std::sync::Arc;

mod error;
mod fit;
mod npy;
mod text;

pub use error::HeightMapError;
pub use fit::QuadraticFit;

/// Fewest nodes accepted along either axis (dimensionless count).
const MIN_NODES: usize = 4;
/// Most nodes accepted along either axis (dimensionless count).
const MAX_NODES: usize = 16384;
/// Smallest accepted lattice spacing (length).
const MIN_SPACING: f64 = 1e-30;
/// Largest accepted lattice spacing (length).
const MAX_SPACING: f64 = 1e30;
/// Largest accepted height magnitude (length).
const MAX_ABS_HEIGHT: f64 = 1e30;
/// How far outside the nodes' hull a sample point may lie and still be
/// clamped onto it, in lattice units (multiples of the spacing). This absorbs
/// round-off when sampling exactly on the boundary.
const SAMPLE_SLACK: f64 = 1e-9;

/// Checks that both node counts lie in `MIN_NODES..=MAX_NODES`.
fn check_dims(file: &str, nx: usize, ny: usize) -> Result<(), HeightMapError> {
    let range = MIN_NODES..=MAX_NODES;
    if range.contains(&nx) && range.contains(&ny) {
        Ok(())
    } else {
        Err(HeightMapError::Dimensions {
            file: file.to_owned(),
            nx,
            ny,
        })
    }
}

/// Checks that the spacing (length) is finite and in `[1e-30, 1e30]`.
fn check_spacing(file: &str, spacing: f64) -> Result<(), HeightMapError> {
    if (MIN_SPACING..=MAX_SPACING).contains(&spacing) {
        Ok(())
    } else {
        Err(HeightMapError::Spacing {
            file: file.to_owned(),
            spacing,
        })
    }
}

/// Node counts and heights decoded from a file, before `HeightMap::build`
/// validates them.
struct Grid {
    /// Nodes along x (values per row), a count.
    nx: usize,
    /// Nodes along y (rows), a count.
    ny: usize,
    /// Heights, row-major with x fastest (length).
    heights: Vec<f64>,
}

/// A measured indenter topography on a square lattice, centred on the origin.
///
/// See the [module documentation](self) for the layout and coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    /// Nodes along x (per row), a count.
    nx: usize,
    /// Nodes along y (rows), a count.
    ny: usize,
    /// Lattice spacing (length).
    spacing: f64,
    /// Heights, row-major with x fastest (length), shared by the map's clones (a batch's rows
    /// that name one file hold one copy of its heights).
    heights: Arc<Vec<f64>>,
    /// The smallest height (length), cached at construction.
    min: f64,
    /// Row-major index of the first node holding `min`.
    lowest: usize,
    /// The shortest wavelength the map holds (length), computed on first use
    /// ([`HeightMap::shortest_wavelength`]).
    shortest: std::sync::OnceLock<f64>,
    /// The shortest wavelength carrying a share of the surface less its smooth shape (length),
    /// computed on first use ([`HeightMap::carrying_wavelength`]).
    carrying: std::sync::OnceLock<Option<f64>>,
}

impl HeightMap {
    /// Builds a map of `nx` × `ny` nodes (counts) with lattice spacing
    /// `spacing` (length) from `heights` (length), stored row-major with x
    /// (index `i`) fastest.
    ///
    /// # Errors
    ///
    /// Refuses, in this order: `nx` or `ny` outside `4..=16384`
    /// ([`HeightMapError::Dimensions`]); `heights.len() != nx * ny`
    /// ([`HeightMapError::LengthMismatch`]); a spacing that is not a finite
    /// length in `[1e-30, 1e30]` ([`HeightMapError::Spacing`]); the first height,
    /// in storage order, that is NaN or infinite
    /// ([`HeightMapError::NonFiniteHeight`]) or of magnitude above `1e30`
    /// ([`HeightMapError::HeightOutOfRange`]), named by its 1-based row and
    /// column; and a flat map ([`HeightMapError::Flat`]).
    pub fn new(
        nx: usize,
        ny: usize,
        spacing: f64,
        heights: Vec<f64>,
    ) -> Result<Self, HeightMapError> {
        Self::build("", nx, ny, spacing, heights)
    }

    /// [`HeightMap::new`] with `file` recorded in any error.
    fn build(
        file: &str,
        nx: usize,
        ny: usize,
        spacing: f64,
        heights: Vec<f64>,
    ) -> Result<Self, HeightMapError> {
        check_dims(file, nx, ny)?;
        let expected = nx
            .checked_mul(ny)
            .ok_or_else(|| HeightMapError::Dimensions {
                file: file.to_owned(),
                nx,
                ny,
            })?;
        if heights.len() != expected {
            return Err(HeightMapError::LengthMismatch {
                file: file.to_owned(),
                expected,
                found: heights.len(),
            });
        }
        check_spacing(file, spacing)?;
        let mut min = f64::INFINITY;
        let mut max = f64::NEG_INFINITY;
        let mut lowest = 0;
        for (k, &h) in heights.iter().enumerate() {
            if !h.is_finite() {
                return Err(HeightMapError::NonFiniteHeight {
                    file: file.to_owned(),
                    row: k / nx + 1,
                    column: k % nx + 1,
                    value: h,
                });
            }
            if h.abs() > MAX_ABS_HEIGHT {
                return Err(HeightMapError::HeightOutOfRange {
                    file: file.to_owned(),
                    row: k / nx + 1,
                    column: k % nx + 1,
                    value: h,
                });
            }
            if h < min {
                min = h;
                lowest = k;
            }
            if h > max {
                max = h;
            }
        }
        if max <= min {
            return Err(HeightMapError::Flat {
                file: file.to_owned(),
                height: min,
            });
        }
        Ok(Self {
            nx,
            ny,
            spacing,
            heights: Arc::new(heights),
            min,
            lowest,
            shortest: std::sync::OnceLock::new(),
            carrying: std::sync::OnceLock::new(),
        })
    }

    /// The same heights with nodes `spacing` apart (length), sharing them (no copy); `name`
    /// identifies the map in an error.
    ///
    /// # Errors
    ///
    /// [`HeightMapError::Spacing`] outside the spacings a map may have.
    pub fn with_spacing(&self, spacing: f64, name: &str) -> Result<Self, HeightMapError> {
        check_spacing(name, spacing)?;
        Ok(Self {
            spacing,
            heights: Arc::clone(&self.heights),
            shortest: std::sync::OnceLock::new(),
            carrying: std::sync::OnceLock::new(),
            ..*self
        })
    }

    /// The shortest wavelength the map holds (length): that of the smallest |q| beyond which
    /// the map's spectrum holds at most [`crate::scene::roughness::SLOPE_TAIL`] of its
    /// mean-square slope, the map windowed so that its edges add no power
    /// ([`crate::scene::roughness::shortest_wavelength`]). Two spacings for a map
    /// rough down to its nodes; the cut-off of a band-limited one. Computed once.
    pub fn shortest_wavelength(&self) -> f64 {
        *self
            .shortest
            .get_or_init(|| crate::scene::roughness::shortest_wavelength(self))
    }

    /// The shortest wavelength that carries a share of the map's surface less its smooth
    /// shape (length; [`crate::scene::roughness::carrying_wavelength`]): a wavy sphere's
    /// waviness. `None` for a map that is its quadratic. Computed once.
    pub fn carrying_wavelength(&self) -> Option<f64> {
        *self
            .carrying
            .get_or_init(|| crate::scene::roughness::carrying_wavelength(self))
    }

    /// Reads a map from `path`, with lattice spacing `spacing` (length, the
    /// unit of the heights in the file).
    ///
    /// A file whose extension is `.npy` (any letter case) is read as NumPy;
    /// any other file is read as plain text, unless it begins with the `.npy`
    /// magic bytes (which no UTF-8 text can), in which case it is read as
    /// NumPy too. Errors name the file by its path.
    ///
    /// # Errors
    ///
    /// [`HeightMapError::Io`] if the file cannot be read, and otherwise any
    /// error of [`HeightMap::from_npy_bytes`] or [`HeightMap::from_text`].
    pub fn read(path: &Path, spacing: f64) -> Result<Self, HeightMapError> {
        let name = path.display().to_string();
        check_spacing(&name, spacing)?;
        let bytes = std::fs::read(path).map_err(|err| HeightMapError::Io {
            file: name.clone(),
            message: err.to_string(),
        })?;
        Self::from_file_bytes(path, &bytes, spacing)
    }

    /// Parses the bytes read from the file `path` as [`HeightMap::read`] does: NumPy when its
    /// name ends in `.npy` or the bytes start with the NumPy magic, text otherwise.
    pub fn from_file_bytes(
        path: &Path,
        bytes: &[u8],
        spacing: f64,
    ) -> Result<Self, HeightMapError> {
        let name = path.display().to_string();
        let is_npy = path
            .extension()
            .is_some_and(|ext| ext.eq_ignore_ascii_case("npy"));
        let is_npz = path
            .extension()
            .is_some_and(|ext| ext.eq_ignore_ascii_case("npz"));
        if is_npz || bytes.starts_with(b"PK\x03\x04") {
            return Err(HeightMapError::Archive { file: name });
        }
        if is_npy || bytes.starts_with(npy::NPY_MAGIC) {
            Self::from_npy_bytes(bytes, spacing, &name)
        } else {
            Self::from_text(&String::from_utf8_lossy(bytes), spacing, &name)
        }
    }

    /// Refuse a `.npy` file whose header (in `prefix`, the file's first bytes) states a shape
    /// outside the limits, before its data is read: a 20000² map would otherwise be read in
    /// full (gigabytes) first. Only the shape's refusal is final here; any other fault of the
    /// file is found when the whole of it is read (`Ok` then).
    pub fn refuse_npy_shape(prefix: &[u8], name: &str) -> Result<(), HeightMapError> {
        match npy::header(prefix, name) {
            Err(e @ (HeightMapError::Dimensions { .. } | HeightMapError::NpyShape { .. })) => {
                Err(e)
            }
            _ => Ok(()),
        }
    }

    /// Parses the contents of a NumPy `.npy` file, with lattice spacing
    /// `spacing` (length); `name` identifies the data in error messages.
    ///
    /// Accepts format versions 1.0, 2.0 and 3.0 and dtypes `'<f8'`, `'<f4'`,
    /// `'=f8'`, `'=f4'`, `'>f8'` and `'>f4'` (big-endian data is byte-swapped,
    /// float32 is widened to float64). The array must be 2-D with shape
    /// `(ny, nx)`. An array stored with `fortran_order: True` is transposed, so
    /// element `a[j, i]` always becomes node `(i, j)`.
    ///
    /// # Errors
    ///
    /// [`HeightMapError::NpyBadMagic`], [`HeightMapError::NpyVersion`],
    /// [`HeightMapError::NpyTruncated`] (header or data shorter than needed),
    /// [`HeightMapError::NpyHeader`] (the header dictionary cannot be parsed
    /// or lacks a key), [`HeightMapError::NpyDtype`] (integers, booleans,
    /// complex, objects, strings, records, half or extended precision),
    /// [`HeightMapError::NpyShape`] (not 2-D),
    /// [`HeightMapError::NpyTrailingData`] (more data than the shape), and
    /// any error of [`HeightMap::new`].
    pub fn from_npy_bytes(bytes: &[u8], spacing: f64, name: &str) -> Result<Self, HeightMapError> {
        check_spacing(name, spacing)?;
        let grid = npy::parse(bytes, name)?;
        Self::build(name, grid.nx, grid.ny, spacing, grid.heights)
    }

    /// Parses a plain-text map, with lattice spacing `spacing` (length);
    /// `name` identifies the text in error messages.
    ///
    /// Each non-empty line is one row of the map (the first is `j = 0`), its
    /// values separated by whitespace and/or commas (empty fields between
    /// commas are skipped). A `#` starts a comment that runs to the end of the
    /// line; lines holding only comments or separators are skipped. A leading
    /// byte-order mark is ignored. Values use Rust's `f64` syntax, which also
    /// reads `nan` and `inf`; those are then refused as in [`HeightMap::new`].
    ///
    /// # Errors
    ///
    /// [`HeightMapError::TextBadValue`] (names the line and column),
    /// [`HeightMapError::TextRaggedRow`] (names the line and both counts),
    /// [`HeightMapError::TextNoData`], and any error of [`HeightMap::new`].
    pub fn from_text(text: &str, spacing: f64, name: &str) -> Result<Self, HeightMapError> {
        check_spacing(name, spacing)?;
        let grid = text::parse(text, name)?;
        Self::build(name, grid.nx, grid.ny, spacing, grid.heights)
    }

    /// Nodes along x (values per row), a count.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Nodes along y (rows), a count.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Lattice spacing (length).
    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// The heights as stored (length), row-major with x (index `i`) fastest:
    /// node `(i, j)` is element `j * nx + i`.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// The smallest stored height (length): the indenter's first point of
    /// contact.
    pub fn min_height(&self) -> f64 {
        self.min
    }

    /// `(x, y)` (length) of the lowest node in the map's coordinates. When
    /// several nodes share the minimum, the first in storage order is used.
    pub fn lowest_point(&self) -> (f64, f64) {
        let (i, j) = self.lowest_node();
        (self.node_x(i), self.node_y(j))
    }

    /// Half-widths `(along x, along y)` (length) of the nodes' hull:
    /// `((nx - 1) * spacing / 2, (ny - 1) * spacing / 2)`.
    pub fn extent(&self) -> (f64, f64) {
        (
            Self::half_span(self.nx) * self.spacing,
            Self::half_span(self.ny) * self.spacing,
        )
    }

    /// Bilinear interpolation of the height (length) at `(x, y)` (length) in
    /// the map's coordinates, measured from the map's minimum, so the result
    /// is never negative and is zero at the lowest node.
    ///
    /// Returns `None` for points outside the nodes' hull
    /// `[-extent().0, extent().0] × [-extent().1, extent().1]` and for
    /// non-finite coordinates. Points within `1e-9` spacings outside the hull
    /// are clamped onto it, to absorb round-off on the boundary.
    pub fn sample(&self, x: f64, y: f64) -> Option<f64> {
        let u = Self::lattice_coordinate(x, self.spacing, self.nx)?;
        let v = Self::lattice_coordinate(y, self.spacing, self.ny)?;
        // u, v are finite and within [0, n - 1], so the casts are exact floors.
        let i0 = (u.floor() as usize).min(self.nx.saturating_sub(2));
        let j0 = (v.floor() as usize).min(self.ny.saturating_sub(2));
        let t = u - i0 as f64;
        let s = v - j0 as f64;
        let node = |i: usize, j: usize| self.heights.get(j * self.nx + i).map(|&h| h - self.min);
        let h00 = node(i0, j0)?;
        let h10 = node(i0 + 1, j0)?;
        let h01 = node(i0, j0 + 1)?;
        let h11 = node(i0 + 1, j0 + 1)?;
        let bottom = (1.0 - t) * h00 + t * h10;
        let top = (1.0 - t) * h01 + t * h11;
        Some((1.0 - s) * bottom + s * top)
    }

    /// Least-squares fit of
    /// `h ≈ c0 + gx x + gy y + ½ (kxx x² + 2 kxy x y + kyy y²)` to the nodes
    /// whose distance from [`HeightMap::lowest_point`] is at most `radius`
    /// (length).
    ///
    /// In the fit, `x` and `y` (length) are measured from the lowest point, so
    /// `(gx, gy)` is the slope there and `c0` (length) the fitted height
    /// there, on the stored (unshifted) height scale. The curvatures do not
    /// depend on that choice of origin. `radius = +inf` uses every node.
    ///
    /// Returns `None` when `radius` is NaN or not positive, fewer than 6 nodes
    /// lie within it, or the nodes do not determine the six coefficients
    /// (singular normal equations). The fit uses an orthogonal (Givens QR)
    /// factorisation rather than forming the normal equations, for accuracy.
    pub fn curvature_fit(&self, radius: f64) -> Option<QuadraticFit> {
        fit::curvature_fit(self, radius)
    }

    /// `(i, j)` of the lowest node.
    fn lowest_node(&self) -> (usize, usize) {
        (self.lowest % self.nx, self.lowest / self.nx)
    }

    /// `(n - 1) / 2`, in lattice units.
    fn half_span(n: usize) -> f64 {
        (n as f64 - 1.0) * 0.5
    }

    /// x (length) of column `i`.
    fn node_x(&self, i: usize) -> f64 {
        (i as f64 - Self::half_span(self.nx)) * self.spacing
    }

    /// y (length) of row `j`.
    fn node_y(&self, j: usize) -> f64 {
        (j as f64 - Self::half_span(self.ny)) * self.spacing
    }

    /// Converts a coordinate (length) to a fractional node index in
    /// `[0, n - 1]`, or `None` if it lies outside the hull.
    fn lattice_coordinate(coordinate: f64, spacing: f64, n: usize) -> Option<f64> {
        let last = n as f64 - 1.0;
        let index = coordinate / spacing + 0.5 * last;
        (-SAMPLE_SLACK..=last + SAMPLE_SLACK)
            .contains(&index)
            .then(|| index.clamp(0.0, last))
    }
}

#[cfg(test)]
mod tests;
