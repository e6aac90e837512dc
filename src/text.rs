//! Numbers as people read them, in messages, summaries and chart labels: short (never 300
//! digits echoed back), with no "−0.0000", and with signs written as an operator ("− 1.010",
//! not "+ -1.010").

/// Items as text, the first [`SHOWN_ITEMS`] of them: "a, b, c", or "a, b, … and 3 more" (a
/// message names a few thousand shards or scenes no better than twenty).
pub fn listed<T: std::fmt::Display>(items: &[T]) -> String {
    let mut text = items
        .iter()
        .take(SHOWN_ITEMS)
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ");
    if items.len() > SHOWN_ITEMS {
        text.push_str(&format!(" and {} more", items.len() - SHOWN_ITEMS));
    }
    text
}

/// The most items [`listed`] shows.
pub const SHOWN_ITEMS: usize = 20;

/// A value in at most `digits` significant digits, in scientific notation outside
/// [10⁻⁴, 10⁶): "1e300", "2.5e-12", "0.08", "1048576". Non-finite values as Rust writes them.
pub fn compact(v: f64) -> String {
    compact_digits(v, 6)
}

/// [`compact`] with `digits` (≥ 1) significant digits.
pub fn compact_digits(v: f64, digits: usize) -> String {
    if !v.is_finite() || v == 0.0 {
        return format!("{}", if v == 0.0 { 0.0 } else { v });
    }
    let digits = digits.max(1);
    let e = v.abs().log10().floor() as i32;
    if (-4..6).contains(&e) {
        let decimals = (digits as i32 - 1 - e).max(0) as usize;
        let s = format!("{v:.decimals$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    } else {
        let s = format!("{v:.*e}", digits - 1);
        match s.split_once('e') {
            Some((m, x)) if m.contains('.') => {
                format!("{}e{x}", m.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => s,
        }
    }
}

/// A duration in seconds as `--time-limit` takes it: "90s", "10min", "1.5h" (three
/// significant digits; minutes from 2 min, hours from 2 h).
pub fn duration(seconds: f64) -> String {
    if seconds < 120.0 {
        format!("{}s", compact_digits(seconds, 3))
    } else if seconds < 7200.0 {
        format!("{}min", compact_digits(seconds / 60.0, 3))
    } else {
        format!("{}h", compact_digits(seconds / 3600.0, 3))
    }
}

/// `v` with `decimals` decimals, without the sign of a value that rounds to zero
/// ("0.0000", not "-0.0000").
pub fn fixed(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

/// A term added to an expression: "+ 1.010" or "− 1.010" (U+2212), with `decimals` decimals.
pub fn signed_term(v: f64, decimals: usize) -> String {
    let s = fixed(v, decimals);
    match s.strip_prefix('-') {
        Some(rest) => format!("− {rest}"),
        None => format!("+ {s}"),
    }
}

/// A number with a typographic minus (U+2212) for negative values: "−1.492".
pub fn minus(v: f64, decimals: usize) -> String {
    fixed(v, decimals).replacen('-', "−", 1)
}

/// The law k1·(R1/R2)^k2 + k3 as text with proper signs:
/// "0.018·(R1/R2)^−1.492 − 1.010".
pub fn power_law(k1: f64, k2: f64, k3: f64) -> String {
    format!(
        "{}·(R1/R2)^{} {}",
        minus(k1, 3),
        minus(k2, 3),
        signed_term(k3, 3)
    )
}

/// User text (a file's name or contents, a value given) made safe to echo to a terminal:
/// control characters written as escapes (`\u{1b}`, `\n`, `\0`), so that no escape sequence
/// from a file or a name reaches the terminal, and at most `max` characters, "..." beyond.
pub fn printable(text: &str, max: usize) -> String {
    let mut out = String::new();
    for (i, c) in text.chars().enumerate() {
        if i == max {
            out.push_str("...");
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// Bytes in words: "8.8 TB", "420 MB".
pub fn bytes_text(b: u64) -> String {
    let b = b as f64;
    let (v, unit) = if b >= 1e12 {
        (b / 1e12, "TB")
    } else if b >= 1e9 {
        (b / 1e9, "GB")
    } else {
        (b / 1e6, "MB")
    };
    format!("{} {unit}", compact(((v * 10.0).round() / 10.0).max(0.1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn printable_escapes_control_characters_and_clips() {
        assert_eq!(printable("a\u{1b}]0;x\u{7}b", 80), "a\\u{1b}]0;x\\u{7}b");
        assert_eq!(printable("x\0\n", 80), "x\\u{0}\\n");
        assert_eq!(printable("abcdef", 3), "abc...");
        assert_eq!(printable("Δγ é", 80), "Δγ é");
    }

    #[test]
    fn huge_and_tiny_values_are_short() {
        assert_eq!(compact(1e300), "1e300");
        assert_eq!(compact(-1e-300), "-1e-300");
        assert_eq!(compact(2.5e-12), "2.5e-12");
        assert_eq!(compact(0.08), "0.08");
        assert_eq!(compact(1048576.0), "1.04858e6");
        assert_eq!(compact(64.0), "64");
        assert_eq!(compact(-5.0), "-5");
        assert_eq!(compact(f64::INFINITY), "inf");
        assert_eq!(compact(-0.0), "0");
        assert!(compact(1e300).len() < 10);
    }

    #[test]
    fn no_negative_zero_and_signs_as_operators() {
        assert_eq!(fixed(-0.0, 4), "0.0000");
        assert_eq!(fixed(-0.00001, 4), "0.0000");
        assert_eq!(fixed(-0.4898, 4), "-0.4898");
        assert_eq!(signed_term(-1.0104, 3), "− 1.010");
        assert_eq!(signed_term(0.737, 3), "+ 0.737");
        assert_eq!(
            power_law(0.018, -1.492, -1.010),
            "0.018·(R1/R2)^−1.492 − 1.010"
        );
        assert!(!power_law(0.018, -1.492, -1.010).contains("+ -"));
    }
}
