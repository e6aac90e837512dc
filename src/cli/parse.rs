//! Values the commands share, parsed by the schema: each flag's value is checked against the
//! kind and range of its parameter ([`Spec`]) as clap reads it, so that a value past the range
//! is refused (exit 2) naming the flag, by every command alike.

use jkrbem::params::{values, words, Kind, Spec};
use serde::de::DeserializeOwned;

/// A clap value parser of one value of `spec` (one item of a comma-separated list), checked
/// against its kind and range ([`values::from_text`]): a percentage with its `%` for a
/// fraction, a whole number for a count (exactly, up to 2⁶⁴ − 1), a number in range for a
/// real. Its error says what the parameter takes, in flags.
pub fn value<T>(
    spec: &'static Spec,
) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: DeserializeOwned + 'static,
{
    move |text: &str| {
        let checked = match spec.kind {
            Kind::Count(lo, hi) | Kind::PowerOfTwo(lo, hi) => whole(spec, text, lo, hi),
            _ => values::from_text(spec, text),
        };
        let value = checked.map_err(|e| {
            // "⟨p⟩ = "x" is invalid: what it takes": clap names the flag and the value.
            let prefix = format!("{spec} = {} is invalid: ", values::shown(text));
            words::flags(e.strip_prefix(&prefix).unwrap_or(&e))
        })?;
        serde_json::from_value(value).map_err(|e| e.to_string())
    }
}

/// A whole number written with digits only, read exactly (a `u64`, not through an `f64`,
/// which rounds past 2⁵³), in [lo, hi] (a power of two where `spec` takes one); any other text
/// (`1e3`, `-1`, `NaN`) as [`values::from_text`] reads it.
fn whole(spec: &Spec, text: &str, lo: u64, hi: u64) -> Result<serde_json::Value, String> {
    let t = text.trim();
    if t.is_empty() || !t.bytes().all(|b| b.is_ascii_digit()) {
        return values::from_text(spec, text);
    }
    let power = matches!(spec.kind, Kind::PowerOfTwo(..));
    match t.parse::<u64>() {
        Ok(n) if (lo..=hi).contains(&n) && (!power || n.is_power_of_two()) => Ok(n.into()),
        _ => Err(format!(
            "{spec} = {} is invalid: {}",
            values::shown(text),
            values::expected(spec)
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use jkrbem::params::{ACCURACY, JOBS, RATIO, SEEDS, TARGET};

    #[test]
    fn values_are_checked_against_their_parameter() {
        assert_eq!(value::<f64>(ACCURACY)("5%"), Ok(0.05));
        assert!(value::<f64>(ACCURACY)("0.05")
            .unwrap_err()
            .contains("write the unit"));
        for bad in ["0%", "60%", "-5%", "NaN%", "1e300%"] {
            let e = value::<f64>(TARGET)(bad).unwrap_err();
            assert!(e.contains("[0.1, 50]") || e.contains("percentage"), "{e}");
            assert!(e.len() < 120, "{e}");
        }
        assert_eq!(value::<usize>(JOBS)("8"), Ok(8));
        assert_eq!(value::<usize>(JOBS)("1e2"), Ok(100));
        for bad in ["0", "257", "-1", "NaN", "2.5", ""] {
            let e = value::<usize>(JOBS)(bad).unwrap_err();
            assert_eq!(e, "a whole number from 1 to 256", "{bad}");
        }
        assert_eq!(value::<f64>(RATIO)("2"), Ok(2.0));
        assert!(value::<f64>(RATIO)("inf").is_err());
        // Seeds are read exactly, to the last of 2⁶⁴ − 1, and no further.
        assert_eq!(
            value::<u64>(SEEDS)("9007199254740993"),
            Ok(9_007_199_254_740_993)
        );
        assert_eq!(value::<u64>(SEEDS)("18446744073709551615"), Ok(u64::MAX));
        assert!(value::<u64>(SEEDS)("18446744073709551616").is_err());
        assert!(value::<u64>(SEEDS)("-1").is_err());
    }
}
