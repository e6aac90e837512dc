//! Reading NumPy `.npy` data: the magic bytes, format version, dtype, shape
//! and memory order, and decoding the array into heights.

mod header;

use self::header::{parse_npy_header, PyValue};
use super::error::quote_limited;
use super::{check_dims, Grid, HeightMapError};

/// The first six bytes of every `.npy` file.
pub(super) const NPY_MAGIC: &[u8; 6] = b"\x93NUMPY";
/// Bytes before the header length field ends in a version 1.0 `.npy` file.
const NPY_V1_PREFIX: usize = 10;
/// Bytes before the header length field ends in a version 2.0/3.0 `.npy` file.
const NPY_V2_PREFIX: usize = 12;
/// The NumPy dtypes this module reads, as listed in error messages.
pub(super) const ACCEPTED_DTYPES: &str = "'<f8', '<f4', '=f8', '=f4', '>f8', '>f4'";

/// Decodes the contents of a NumPy `.npy` file into its node counts and its
/// heights (length, row-major with x fastest); `name` identifies the data in
/// error messages.
///
/// Checks the file's structure and its node counts, but not the heights
/// themselves: see [`HeightMap::from_npy_bytes`](super::HeightMap::from_npy_bytes)
/// for the accepted formats and the errors.
pub(super) fn parse(bytes: &[u8], name: &str) -> Result<Grid, HeightMapError> {
    let Header {
        nx,
        ny,
        item_size,
        big_endian,
        fortran_order,
        end: header_end,
    } = header(bytes, name)?;
    let file = || name.to_owned();
    let expected = nx
        .checked_mul(ny)
        .and_then(|count| count.checked_mul(item_size))
        .ok_or_else(|| HeightMapError::Dimensions {
            file: file(),
            nx,
            ny,
        })?;
    let data = bytes.get(header_end..).unwrap_or_default();
    if data.len() < expected {
        return Err(HeightMapError::NpyTruncated {
            file: file(),
            part: "data",
            expected,
            found: data.len(),
        });
    }
    if data.len() > expected {
        return Err(HeightMapError::NpyTrailingData {
            file: file(),
            expected,
            found: data.len(),
        });
    }
    let values = decode_floats(data, item_size, big_endian);
    let heights = if fortran_order {
        // Column-major (ny, nx): element [j, i] sits at i * ny + j.
        (0..ny)
            .flat_map(|j| (0..nx).map(move |i| i * ny + j))
            .map(|k| values.get(k).copied().unwrap_or(f64::NAN))
            .collect()
    } else {
        values
    };
    Ok(Grid { nx, ny, heights })
}

/// What a `.npy` file's header says: the node counts (checked against the limits), the item
/// size (bytes), the byte order, the memory order, and where the data starts (bytes).
pub(super) struct Header {
    pub(super) nx: usize,
    pub(super) ny: usize,
    item_size: usize,
    big_endian: bool,
    fortran_order: bool,
    end: usize,
}

/// The header of the `.npy` data `bytes` (the data itself need not follow): its magic,
/// version, dtype and shape checked; `name` identifies the data in error messages.
pub(super) fn header(bytes: &[u8], name: &str) -> Result<Header, HeightMapError> {
    let file = || name.to_owned();
    let truncated_header = |expected: usize| HeightMapError::NpyTruncated {
        file: file(),
        part: "header",
        expected,
        found: bytes.len(),
    };
    if !bytes.starts_with(NPY_MAGIC) {
        if bytes.len() < NPY_MAGIC.len() && NPY_MAGIC.starts_with(bytes) {
            return Err(truncated_header(NPY_V1_PREFIX));
        }
        return Err(HeightMapError::NpyBadMagic { file: file() });
    }
    let (major, minor) = match (bytes.get(6), bytes.get(7)) {
        (Some(&major), Some(&minor)) => (major, minor),
        _ => return Err(truncated_header(NPY_V1_PREFIX)),
    };
    let prefix = match (major, minor) {
        (1, 0) => NPY_V1_PREFIX,
        (2 | 3, 0) => NPY_V2_PREFIX,
        _ => {
            return Err(HeightMapError::NpyVersion {
                file: file(),
                major,
                minor,
            })
        }
    };
    let Some(length_field) = bytes.get(8..prefix) else {
        return Err(truncated_header(prefix));
    };
    let header_len = length_field
        .iter()
        .rev()
        .fold(0_usize, |acc, &b| (acc << 8) | usize::from(b));
    let header_end = prefix.saturating_add(header_len);
    let Some(header_bytes) = bytes.get(prefix..header_end) else {
        return Err(truncated_header(header_end));
    };
    let header_text: String = if major == 3 {
        match std::str::from_utf8(header_bytes) {
            Ok(text) => text.to_owned(),
            Err(_) => {
                return Err(HeightMapError::NpyHeader {
                    file: file(),
                    message: "a version 3.0 header must be valid UTF-8".to_owned(),
                })
            }
        }
    } else {
        // Versions 1.0 and 2.0 use Latin-1, which maps bytes to chars 1:1.
        header_bytes.iter().map(|&b| char::from(b)).collect()
    };
    let header = parse_npy_header(&header_text).map_err(|message| HeightMapError::NpyHeader {
        file: file(),
        message,
    })?;
    let (item_size, big_endian) = match &header.descr {
        PyValue::Str(descr) => parse_descr(descr).ok_or_else(|| HeightMapError::NpyDtype {
            file: file(),
            descr: format!("'{}'", quote_limited(descr)),
        })?,
        other => {
            return Err(HeightMapError::NpyDtype {
                file: file(),
                descr: quote_limited(&other.render()),
            })
        }
    };
    let &[rows, cols] = header.shape.as_slice() else {
        return Err(HeightMapError::NpyShape {
            file: file(),
            shape: header.shape,
        });
    };
    let ny = usize::try_from(rows).unwrap_or(usize::MAX);
    let nx = usize::try_from(cols).unwrap_or(usize::MAX);
    check_dims(name, nx, ny)?;
    Ok(Header {
        nx,
        ny,
        item_size,
        big_endian,
        fortran_order: header.fortran_order,
        end: header_end,
    })
}

/// Decodes little- or big-endian float64 (`size == 8`) or float32
/// (`size == 4`) values; any incomplete trailing bytes are ignored.
fn decode_floats(data: &[u8], size: usize, big_endian: bool) -> Vec<f64> {
    fn bytes<const N: usize>(chunk: &[u8]) -> [u8; N] {
        let mut out = [0_u8; N];
        for (dst, src) in out.iter_mut().zip(chunk) {
            *dst = *src;
        }
        out
    }
    match (size, big_endian) {
        (8, false) => data
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(bytes(c)))
            .collect(),
        (8, true) => data
            .chunks_exact(8)
            .map(|c| f64::from_be_bytes(bytes(c)))
            .collect(),
        (4, false) => data
            .chunks_exact(4)
            .map(|c| f64::from(f32::from_le_bytes(bytes(c))))
            .collect(),
        (4, true) => data
            .chunks_exact(4)
            .map(|c| f64::from(f32::from_be_bytes(bytes(c))))
            .collect(),
        _ => Vec::new(),
    }
}

/// Maps an accepted dtype description to `(bytes per value, big-endian?)`.
fn parse_descr(descr: &str) -> Option<(usize, bool)> {
    let native_big = cfg!(target_endian = "big");
    match descr {
        "<f8" => Some((8, false)),
        "<f4" => Some((4, false)),
        ">f8" => Some((8, true)),
        ">f4" => Some((4, true)),
        "=f8" => Some((8, native_big)),
        "=f4" => Some((4, native_big)),
        _ => None,
    }
}

#[cfg(test)]
pub(super) mod tests {
    //! Tests of the `.npy` reader, and the `.npy` fixtures that the other
    //! height-map tests share.

    use super::super::{HeightMap, HeightMapError};
    use super::NPY_MAGIC;

    /// Builds a `.npy` file with the given header fields and raw data.
    pub(crate) fn npy(descr: &str, shape: &str, fortran: bool, major: u8, data: &[u8]) -> Vec<u8> {
        let order = if fortran { "True" } else { "False" };
        let mut header =
            format!("{{'descr': '{descr}', 'fortran_order': {order}, 'shape': {shape}, }}");
        let prefix = if major == 1 { 10 } else { 12 };
        while (prefix + header.len() + 1) % 64 != 0 {
            header.push(' ');
        }
        header.push('\n');
        let mut out = NPY_MAGIC.to_vec();
        out.push(major);
        out.push(0);
        if major == 1 {
            out.extend_from_slice(&u16::try_from(header.len()).unwrap().to_le_bytes());
        } else {
            out.extend_from_slice(&u32::try_from(header.len()).unwrap().to_le_bytes());
        }
        out.extend_from_slice(header.as_bytes());
        out.extend_from_slice(data);
        out
    }

    /// The little-endian float64 bytes of `values`, as `'<f8'` data.
    pub(crate) fn le8(values: &[f64]) -> Vec<u8> {
        values.iter().flat_map(|v| v.to_le_bytes()).collect()
    }

    /// A 5 × 4 (nx × ny) test map; every value is exact in float32.
    pub(crate) fn sample_values() -> (usize, usize, Vec<f64>) {
        let (nx, ny) = (5, 4);
        let values = (0..ny)
            .flat_map(|j| {
                (0..nx).map(move |i| 0.5 * i as f64 + 1.25 * j as f64 - 0.125 * (i * j) as f64)
            })
            .collect();
        (nx, ny, values)
    }

    #[test]
    fn npy_round_trip_f8_little_endian() {
        let (nx, ny, values) = sample_values();
        let bytes = npy("<f8", "(4, 5)", false, 1, &le8(&values));
        let map = HeightMap::from_npy_bytes(&bytes, 0.5, "a.npy").unwrap();
        assert_eq!((map.nx(), map.ny(), map.spacing()), (nx, ny, 0.5));
        assert_eq!(map.heights(), values.as_slice());
    }

    #[test]
    fn npy_round_trip_f4_little_endian() {
        let (_, _, values) = sample_values();
        let data: Vec<u8> = values
            .iter()
            .flat_map(|v| (*v as f32).to_le_bytes())
            .collect();
        let map =
            HeightMap::from_npy_bytes(&npy("<f4", "(4, 5)", false, 1, &data), 1.0, "b").unwrap();
        assert_eq!(map.heights(), values.as_slice());
    }

    #[test]
    fn npy_round_trip_big_endian() {
        let (_, _, values) = sample_values();
        let data: Vec<u8> = values.iter().flat_map(|v| v.to_be_bytes()).collect();
        let map =
            HeightMap::from_npy_bytes(&npy(">f8", "(4, 5)", false, 1, &data), 1.0, "c").unwrap();
        assert_eq!(map.heights(), values.as_slice());
        let data4: Vec<u8> = values
            .iter()
            .flat_map(|v| (*v as f32).to_be_bytes())
            .collect();
        let map4 =
            HeightMap::from_npy_bytes(&npy(">f4", "(4, 5)", false, 1, &data4), 1.0, "d").unwrap();
        assert_eq!(map4.heights(), values.as_slice());
    }

    #[test]
    fn npy_round_trip_v2_and_v3_headers() {
        let (nx, ny, values) = sample_values();
        for major in [2, 3] {
            let bytes = npy("<f8", "(4, 5)", false, major, &le8(&values));
            assert_eq!(bytes.get(6), Some(&major));
            let map = HeightMap::from_npy_bytes(&bytes, 1.0, "v").unwrap();
            assert_eq!((map.nx(), map.ny()), (nx, ny));
            assert_eq!(map.heights(), values.as_slice());
        }
    }

    #[test]
    fn npy_fortran_order_is_transposed() {
        let (nx, ny, values) = sample_values();
        // Column-major storage of the same (ny, nx) array.
        let column_major: Vec<f64> = (0..nx)
            .flat_map(|i| (0..ny).map(move |j| (i, j)))
            .map(|(i, j)| values[j * nx + i])
            .collect();
        let bytes = npy("<f8", "(4, 5)", true, 1, &le8(&column_major));
        let map = HeightMap::from_npy_bytes(&bytes, 1.0, "f").unwrap();
        assert_eq!(map.heights(), values.as_slice());
    }

    #[test]
    fn npy_refuses_bad_magic() {
        let err = HeightMap::from_npy_bytes(b"1 2 3 4\n5 6 7 8\n", 1.0, "x.npy").unwrap_err();
        assert_eq!(
            err,
            HeightMapError::NpyBadMagic {
                file: "x.npy".into()
            }
        );
        assert!(err.to_string().contains("x.npy"));
        assert!(err.to_string().contains("NUMPY"));
    }

    #[test]
    fn npy_refuses_truncated_data_and_header() {
        let (_, _, values) = sample_values();
        let mut bytes = npy("<f8", "(4, 5)", false, 1, &le8(&values));
        bytes.truncate(bytes.len() - 3);
        let err = HeightMap::from_npy_bytes(&bytes, 1.0, "t.npy").unwrap_err();
        assert_eq!(
            err,
            HeightMapError::NpyTruncated {
                file: "t.npy".into(),
                part: "data",
                expected: 160,
                found: 157
            }
        );
        let text = err.to_string();
        assert!(text.contains("160") && text.contains("157") && text.contains("t.npy"));

        let err = HeightMap::from_npy_bytes(&bytes[..40], 1.0, "t.npy").unwrap_err();
        assert!(matches!(
            err,
            HeightMapError::NpyTruncated {
                part: "header",
                expected: 128,
                found: 40,
                ..
            }
        ));
    }

    #[test]
    fn npy_never_panics_on_any_prefix_or_corruption() {
        let (_, _, values) = sample_values();
        let bytes = npy("<f8", "(4, 5)", false, 1, &le8(&values));
        for cut in 0..bytes.len() {
            assert!(HeightMap::from_npy_bytes(&bytes[..cut], 1.0, "p").is_err());
        }
        // Flip every byte of the header in turn; any outcome but a panic is fine.
        for k in 0..128 {
            let mut corrupt = bytes.clone();
            corrupt[k] ^= 0xA5;
            let _ = HeightMap::from_npy_bytes(&corrupt, 1.0, "p");
        }
    }

    #[test]
    fn npy_refuses_unsupported_dtypes() {
        let data = vec![0_u8; 8 * 20];
        for (descr, kind) in [
            ("<i8", "integer"),
            ("<u4", "integer"),
            ("<c16", "complex"),
            ("|O", "object"),
            ("<f2", "floating"),
            ("|f8", "floating"),
        ] {
            let err = HeightMap::from_npy_bytes(&npy(descr, "(4, 5)", false, 1, &data), 1.0, "i")
                .unwrap_err();
            assert_eq!(
                err,
                HeightMapError::NpyDtype {
                    file: "i".into(),
                    descr: format!("'{descr}'")
                }
            );
            let text = err.to_string();
            assert!(text.contains(descr) && text.contains(kind), "{text}");
            assert!(text.contains("'<f8'") && text.contains("'>f4'"), "{text}");
        }
    }

    #[test]
    fn npy_refuses_non_2d_shapes_and_extra_data() {
        let data = le8(&[1.0; 24]);
        let err = HeightMap::from_npy_bytes(&npy("<f8", "(2, 3, 4)", false, 1, &data), 1.0, "s")
            .unwrap_err();
        assert_eq!(
            err,
            HeightMapError::NpyShape {
                file: "s".into(),
                shape: vec![2, 3, 4]
            }
        );
        assert!(err.to_string().contains("(2, 3, 4)"));
        let err =
            HeightMap::from_npy_bytes(&npy("<f8", "(24,)", false, 1, &data), 1.0, "s").unwrap_err();
        assert!(err.to_string().contains("(24,)"));

        let (_, _, values) = sample_values();
        let mut long = le8(&values);
        long.extend_from_slice(&[0; 8]);
        let err = HeightMap::from_npy_bytes(&npy("<f8", "(4, 5)", false, 1, &long), 1.0, "s")
            .unwrap_err();
        assert_eq!(
            err,
            HeightMapError::NpyTrailingData {
                file: "s".into(),
                expected: 160,
                found: 168
            }
        );
    }

    #[test]
    fn npy_refuses_bad_versions_headers_and_huge_shapes() {
        let (_, _, values) = sample_values();
        let mut bytes = npy("<f8", "(4, 5)", false, 1, &le8(&values));
        bytes[6] = 4;
        assert!(matches!(
            HeightMap::from_npy_bytes(&bytes, 1.0, "h"),
            Err(HeightMapError::NpyVersion {
                major: 4,
                minor: 0,
                ..
            })
        ));
        let no_shape = "{'descr': '<f8', 'fortran_order': False}\n";
        let mut bytes = NPY_MAGIC.to_vec();
        bytes.extend_from_slice(&[1, 0, u8::try_from(no_shape.len()).unwrap(), 0]);
        bytes.extend_from_slice(no_shape.as_bytes());
        let err = HeightMap::from_npy_bytes(&bytes, 1.0, "h").unwrap_err();
        assert!(err.to_string().contains("'shape'"), "{err}");
        // A header claiming an enormous array is refused before allocating.
        let bytes = npy("<f8", "(100000000, 100000000)", false, 1, &[]);
        assert!(matches!(
            HeightMap::from_npy_bytes(&bytes, 1.0, "h"),
            Err(HeightMapError::Dimensions { .. })
        ));
    }
}
