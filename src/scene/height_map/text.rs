//! Reading plain-text height maps: one row per line, values separated by
//! whitespace and/or commas, `#` comments.

use super::error::quote_limited;
use super::{Grid, HeightMapError, MAX_NODES};

/// Splits a plain-text map into its node counts and its heights (length,
/// row-major with x fastest); `name` identifies the text in error messages.
///
/// Checks the text's layout and refuses more than 16384 nodes along either
/// axis, but does not check the heights themselves: see
/// [`HeightMap::from_text`](super::HeightMap::from_text) for the syntax and
/// the errors.
pub(super) fn parse(text: &str, name: &str) -> Result<Grid, HeightMapError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut heights = Vec::new();
    let mut nx = 0;
    let mut ny = 0;
    let mut first_line = 0;
    for (index, raw_line) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw_line.split('#').next().unwrap_or_default();
        check_decimal_comma(content, line, name)?;
        let mut count = 0;
        for token in content
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|token| !token.is_empty())
        {
            count += 1;
            let value = token
                .parse::<f64>()
                .map_err(|_| HeightMapError::TextBadValue {
                    file: name.to_owned(),
                    line,
                    column: count,
                    token: quote_limited(token),
                })?;
            heights.push(value);
            if count > MAX_NODES {
                // Refused as soon as a row is too long: a one-line file is not read whole.
                return Err(HeightMapError::Dimensions {
                    file: name.to_owned(),
                    nx: count,
                    ny: ny + 1,
                });
            }
        }
        if count == 0 {
            continue;
        }
        if ny == 0 {
            nx = count;
            first_line = line;
        } else if count != nx {
            return Err(HeightMapError::TextRaggedRow {
                file: name.to_owned(),
                line,
                expected: nx,
                found: count,
                first_line,
            });
        }
        ny += 1;
        if nx > MAX_NODES || ny > MAX_NODES {
            return Err(HeightMapError::Dimensions {
                file: name.to_owned(),
                nx,
                ny,
            });
        }
    }
    if ny == 0 {
        return Err(HeightMapError::TextNoData {
            file: name.to_owned(),
        });
    }
    Ok(Grid { nx, ny, heights })
}

/// Refuse a row written with decimal commas: two or more values separated by whitespace, each
/// of them digits, one comma and digits ("1,5 2,5", "-0,25 3,0e-2"). A row of commas alone
/// ("1,2,3"), of commas and spaces ("1, 2, 3") or of both mixed ("5 6,7 8") is a list of values.
fn check_decimal_comma(content: &str, line: usize, name: &str) -> Result<(), HeightMapError> {
    let fields: Vec<&str> = content.split_whitespace().collect();
    let decimal_comma = |f: &str| match f.split_once(',') {
        Some((int, frac)) => {
            let int = int.strip_prefix(['-', '+']).unwrap_or(int);
            !int.is_empty()
                && int.bytes().all(|b| b.is_ascii_digit())
                && frac.starts_with(|c: char| c.is_ascii_digit())
                && !frac.contains(',')
        }
        None => false,
    };
    if fields.len() < 2 || !fields.iter().all(|f| decimal_comma(f)) {
        return Ok(());
    }
    Err(HeightMapError::TextDecimalComma {
        file: name.to_owned(),
        line,
        token: quote_limited(fields[0]),
    })
}

#[cfg(test)]
mod tests {
    use super::super::{HeightMap, HeightMapError};

    #[test]
    fn decimal_commas_are_named_and_lists_are_not() {
        let e = HeightMap::from_text("1,5 2,5 3,5 4,5\n", 1.0, "m.txt").unwrap_err();
        assert!(e.to_string().contains("decimal comma"), "{e}");
        for list in ["1,2,3,4\n", "1, 2, 3, 4\n", "1 2,3 4\n", "1,5\t2\n"] {
            if let Err(e) = HeightMap::from_text(list, 1.0, "m.txt") {
                assert!(!e.to_string().contains("decimal comma"), "{list:?}: {e}");
            }
        }
    }

    #[test]
    fn text_with_comments_commas_and_blank_lines() {
        let text = "\u{feff}# measured tip\n\n1, 2, 3, 4\r\n  5 6,7 8  # trailing note\n\
                    # another comment\n9,10,11,12,\n\n13 14 15 16\n";
        let map = HeightMap::from_text(text, 0.25, "tip.txt").unwrap();
        assert_eq!((map.nx(), map.ny(), map.spacing()), (4, 4, 0.25));
        let expected: Vec<f64> = (1..=16).map(f64::from).collect();
        assert_eq!(map.heights(), expected.as_slice());
        assert_eq!(map.min_height(), 1.0);
    }

    #[test]
    fn text_refuses_ragged_rows_and_bad_values() {
        let err = HeightMap::from_text("# c\n1 2 3 4\n\n5 6 7\n", 1.0, "r.txt").unwrap_err();
        assert_eq!(
            err,
            HeightMapError::TextRaggedRow {
                file: "r.txt".into(),
                line: 4,
                expected: 4,
                found: 3,
                first_line: 2
            }
        );
        let text = err.to_string();
        assert!(text.contains("line 4") && text.contains("3 values") && text.contains("has 4"));

        let err = HeightMap::from_text("1 2 3 4\n5 6 x7 8\n", 1.0, "r.txt").unwrap_err();
        assert_eq!(
            err,
            HeightMapError::TextBadValue {
                file: "r.txt".into(),
                line: 2,
                column: 3,
                token: "x7".into()
            }
        );
        assert!(err.to_string().contains("line 2, column 3"));
        assert!(matches!(
            HeightMap::from_text("# nothing\n\n", 1.0, "e"),
            Err(HeightMapError::TextNoData { .. })
        ));
    }
}
