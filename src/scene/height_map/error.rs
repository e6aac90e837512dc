//! Why a height map could not be built or read: [`HeightMapError`], its
//! messages, and the helpers that format them.

use std::fmt;

use super::npy::ACCEPTED_DTYPES;
use super::{MAX_ABS_HEIGHT, MAX_NODES, MAX_SPACING, MIN_NODES, MIN_SPACING};

/// Longest piece of user text quoted back in an error message (characters).
const MAX_QUOTED_CHARS: usize = 80;

/// Why a height map could not be built or read.
///
/// Every variant that can come from a file carries `file`, the name the map
/// was read from (the path for [`HeightMap::read`], the `name` argument for
/// [`HeightMap::from_npy_bytes`] and [`HeightMap::from_text`], or an empty
/// string for [`HeightMap::new`]). Rows, columns and lines are 1-based.
///
/// [`HeightMap::read`]: super::HeightMap::read
/// [`HeightMap::from_npy_bytes`]: super::HeightMap::from_npy_bytes
/// [`HeightMap::from_text`]: super::HeightMap::from_text
/// [`HeightMap::new`]: super::HeightMap::new
#[derive(Debug, Clone, PartialEq)]
pub enum HeightMapError {
    /// The file could not be read from disk.
    Io {
        /// The file's path as given.
        file: String,
        /// The operating system's description of the failure.
        message: String,
    },
    /// The number of nodes along x or y is outside `4..=16384`.
    Dimensions {
        /// Where the map came from (empty for [`HeightMap::new`](super::HeightMap::new)).
        file: String,
        /// Nodes along x (columns), a count.
        nx: usize,
        /// Nodes along y (rows), a count.
        ny: usize,
    },
    /// The number of heights is not `nx * ny`.
    LengthMismatch {
        /// Where the map came from (empty for [`HeightMap::new`](super::HeightMap::new)).
        file: String,
        /// `nx * ny`, a count.
        expected: usize,
        /// The number of heights supplied, a count.
        found: usize,
    },
    /// The lattice spacing is not a finite length in `[1e-30, 1e30]`.
    Spacing {
        /// Where the map came from (empty for [`HeightMap::new`](super::HeightMap::new)).
        file: String,
        /// The spacing supplied (length).
        spacing: f64,
    },
    /// A height is NaN or infinite.
    NonFiniteHeight {
        /// Where the map came from (empty for [`HeightMap::new`](super::HeightMap::new)).
        file: String,
        /// 1-based row (`j + 1`, along y) of the first bad height.
        row: usize,
        /// 1-based column (`i + 1`, along x) of the first bad height.
        column: usize,
        /// The offending value (NaN, +inf or -inf).
        value: f64,
    },
    /// A height's magnitude exceeds `1e30`.
    HeightOutOfRange {
        /// Where the map came from (empty for [`HeightMap::new`](super::HeightMap::new)).
        file: String,
        /// 1-based row (`j + 1`, along y) of the first bad height.
        row: usize,
        /// 1-based column (`i + 1`, along x) of the first bad height.
        column: usize,
        /// The offending height (length).
        value: f64,
    },
    /// Every height is the same, so the map has no lowest point.
    Flat {
        /// Where the map came from (empty for [`HeightMap::new`](super::HeightMap::new)).
        file: String,
        /// The common height (length).
        height: f64,
    },
    /// The data does not start with the `.npy` magic bytes `\x93NUMPY`.
    NpyBadMagic {
        /// Where the map came from.
        file: String,
    },
    /// The `.npy` format version is not 1.0, 2.0 or 3.0.
    NpyVersion {
        /// Where the map came from.
        file: String,
        /// Major version byte found.
        major: u8,
        /// Minor version byte found.
        minor: u8,
    },
    /// The `.npy` data ends before its header or its array data does.
    NpyTruncated {
        /// Where the map came from.
        file: String,
        /// Which part is cut short: `"header"` or `"data"`.
        part: &'static str,
        /// Bytes that part needs (for `"header"`: counted from the start of
        /// the file; for `"data"`: counted from the end of the header).
        expected: usize,
        /// Bytes actually present, counted the same way.
        found: usize,
    },
    /// The `.npy` header dictionary could not be understood.
    NpyHeader {
        /// Where the map came from.
        file: String,
        /// What is wrong with it.
        message: String,
    },
    /// The `.npy` array's dtype is not float64 or float32.
    NpyDtype {
        /// Where the map came from.
        file: String,
        /// The dtype description found in the header.
        descr: String,
    },
    /// The `.npy` array is not 2-D.
    NpyShape {
        /// Where the map came from.
        file: String,
        /// The shape found in the header (counts).
        shape: Vec<u64>,
    },
    /// The `.npy` file holds more data than its shape and dtype describe.
    NpyTrailingData {
        /// Where the map came from.
        file: String,
        /// Data bytes the shape and dtype call for.
        expected: usize,
        /// Data bytes present after the header.
        found: usize,
    },
    /// A text map has no data rows at all.
    TextNoData {
        /// Where the map came from.
        file: String,
    },
    /// A text row has a different number of values from the first row.
    TextRaggedRow {
        /// Where the map came from.
        file: String,
        /// 1-based line number of the offending row.
        line: usize,
        /// Values on the first data row, a count.
        expected: usize,
        /// Values on the offending row, a count.
        found: usize,
        /// 1-based line number of the first data row.
        first_line: usize,
    },
    /// A text row that looks written with decimal commas ("1,5 2,5"): its values would be
    /// read as twice as many columns.
    TextDecimalComma {
        /// Where the map came from.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The first value that holds a comma between digits (shortened if very long).
        token: String,
    },
    /// The file is a zip archive (NumPy's `.npz`), not one array.
    Archive {
        /// Where the map came from.
        file: String,
    },
    /// A text value is not a number.
    TextBadValue {
        /// Where the map came from.
        file: String,
        /// 1-based line number.
        line: usize,
        /// 1-based position of the value within its line (the map column).
        column: usize,
        /// The text that failed to parse (shortened if very long).
        token: String,
    },
}

/// Formats "height map" or "height map 'name'" at the start of messages.
struct Origin<'a>(&'a str);

impl fmt::Display for Origin<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            f.write_str("height map")
        } else {
            write!(f, "height map '{}'", crate::text::printable(self.0, 200))
        }
    }
}

/// Formats a shape the way Python prints a tuple: `()`, `(3,)`, `(2, 3, 4)`.
struct ShapeText<'a>(&'a [u64]);

impl fmt::Display for ShapeText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("(")?;
        for (k, dim) in self.0.iter().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{dim}")?;
        }
        if self.0.len() == 1 {
            f.write_str(",")?;
        }
        f.write_str(")")
    }
}

/// Names the kind of a NumPy dtype description, for error messages.
fn dtype_kind(descr: &str) -> &'static str {
    let body = descr.trim_start_matches(['\'', '"', '<', '>', '=', '|']);
    match body.chars().next() {
        Some('f') => "floating point of an unsupported width or byte order",
        Some('i') => "signed integer",
        Some('u') => "unsigned integer",
        Some('b' | '?') => "boolean",
        Some('c') => "complex",
        Some('O') => "Python object",
        Some('S' | 'a' | 'U') => "string",
        Some('V' | '[' | '{' | '(') => "structured record",
        Some('M' | 'm') => "date/time",
        _ => "unrecognised",
    }
}

impl fmt::Display for HeightMapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { file, message } => {
                write!(f, "{}: cannot read the file: {message}", Origin(file))
            }
            Self::Dimensions { file, nx, ny } => write!(
                f,
                "{}: the map has {nx} columns (x) and {ny} rows (y); each must be \
                 between {MIN_NODES} and {MAX_NODES}",
                Origin(file)
            ),
            Self::LengthMismatch {
                file,
                expected,
                found,
            } => write!(
                f,
                "{}: {found} heights were given but nx * ny = {expected} were expected",
                Origin(file)
            ),
            Self::Spacing { file, spacing } => write!(
                f,
                "{}: the lattice spacing {} cannot be used; it must be a finite \
                 length between {MIN_SPACING:e} and {MAX_SPACING:e}, in the same unit as \
                 the heights",
                Origin(file),
                crate::text::compact(*spacing)
            ),
            Self::NonFiniteHeight {
                file,
                row,
                column,
                value,
            } => {
                let what = if value.is_nan() {
                    "NaN"
                } else if *value > 0.0 {
                    "infinite (+inf)"
                } else {
                    "infinite (-inf)"
                };
                write!(
                    f,
                    "{}: the height at row {row}, column {column} (1-based; row counts \
                     along y, column along x) is {what}; every height must be a finite \
                     number",
                    Origin(file)
                )
            }
            Self::HeightOutOfRange {
                file,
                row,
                column,
                value,
            } => write!(
                f,
                "{}: the height at row {row}, column {column} (1-based) is {value:e}, \
                 beyond the accepted magnitude {MAX_ABS_HEIGHT:e}; check the map's units",
                Origin(file)
            ),
            Self::Flat { file, height } => write!(
                f,
                "{}: every height equals {height}; a flat map has no lowest point to \
                 indent with (check that the intended data was loaded)",
                Origin(file)
            ),
            Self::NpyBadMagic { file } => write!(
                f,
                "{}: not a NumPy .npy file: it does not start with the bytes \
                 \\x93NUMPY (a .npz archive must be unpacked first; a text map needs \
                 an extension other than .npy)",
                Origin(file)
            ),
            Self::NpyVersion { file, major, minor } => write!(
                f,
                "{}: .npy format version {major}.{minor} is not supported; versions \
                 1.0, 2.0 and 3.0 are",
                Origin(file)
            ),
            Self::NpyTruncated {
                file,
                part,
                expected,
                found,
            } => write!(
                f,
                "{}: the .npy file is truncated: its {part} needs {expected} bytes but \
                 only {found} are present",
                Origin(file)
            ),
            Self::NpyHeader { file, message } => {
                write!(f, "{}: malformed .npy header: {message}", Origin(file))
            }
            Self::NpyDtype { file, descr } => write!(
                f,
                "{}: the array's dtype {descr} ({}) is not supported; accepted dtypes \
                 are {ACCEPTED_DTYPES} (float64 or float32); convert it in NumPy with \
                 a.astype(numpy.float64)",
                Origin(file),
                dtype_kind(descr)
            ),
            Self::NpyShape { file, shape } => write!(
                f,
                "{}: the array has shape {} but a height map must be 2-D, shape \
                 (rows = ny, columns = nx)",
                Origin(file),
                ShapeText(shape)
            ),
            Self::NpyTrailingData {
                file,
                expected,
                found,
            } => write!(
                f,
                "{}: the .npy file holds {found} data bytes but its shape and dtype call \
                 for exactly {expected}; refusing a file with extra data after the array",
                Origin(file)
            ),
            Self::TextNoData { file } => write!(
                f,
                "{}: no data rows found (only blank lines and '#' comments)",
                Origin(file)
            ),
            Self::TextRaggedRow {
                file,
                line,
                expected,
                found,
                first_line,
            } => write!(
                f,
                "{}: line {line} has {found} values but the first data row (line \
                 {first_line}) has {expected}; every row must have the same number of \
                 values",
                Origin(file)
            ),
            Self::TextDecimalComma { file, line, token } => write!(
                f,
                "{}: line {line}: '{token}' looks like a decimal comma (values are separated \
                 by spaces or commas, so it would be read as two values): write decimal points",
                Origin(file)
            ),
            Self::Archive { file } => write!(
                f,
                "{}: the file is a zip archive (a NumPy .npz), not one array: save the heights \
                 with numpy.save as a .npy, or as a text grid",
                Origin(file)
            ),
            Self::TextBadValue {
                file,
                line,
                column,
                token,
            } => write!(
                f,
                "{}: line {line}, column {column}: '{token}' is not a number",
                Origin(file)
            ),
        }
    }
}

impl std::error::Error for HeightMapError {}

/// Shortens user text quoted in an error message to [`MAX_QUOTED_CHARS`], its control
/// characters escaped ([`crate::text::printable`]).
pub(super) fn quote_limited(text: &str) -> String {
    crate::text::printable(text, MAX_QUOTED_CHARS)
}
