//! Values the commands share: percentages (`2%`) and durations (`90s`, `20min`, `2h`), each
//! with its unit required and its range checked.

use std::time::Duration;

/// A percentage such as `5%` as a fraction (0.05). The `%` is required: a bare `0.05` could
/// mean 5 % or 0.05 %.
pub fn percentage(text: &str) -> Result<f64, String> {
    let Some(number) = text.trim().strip_suffix('%') else {
        return Err(format!(
            "{text:?} is not a percentage: write the unit, e.g. 5% or 1% (a bare number could \
             mean a fraction or a per cent)"
        ));
    };
    let v: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a percentage (e.g. 5% or 1%)"))?;
    if (0.1..=50.0).contains(&v) {
        Ok(v / 100.0)
    } else {
        Err(format!(
            "{}: give a percentage in [0.1, 50], e.g. 5% or 1%",
            jkrbem::text::compact(v)
        ))
    }
}

/// A duration such as `90s`, `20min` or `2h`. The unit is required (s, min, h); the value
/// lies in [1 s, 30 days].
pub fn duration(text: &str) -> Result<Duration, String> {
    let t = text.trim();
    let (number, unit) = [("min", 60.0), ("h", 3600.0), ("s", 1.0)]
        .iter()
        .find_map(|&(u, scale)| t.strip_suffix(u).map(|n| (n, scale)))
        .ok_or_else(|| {
            format!("{text:?} is not a duration: write the unit, e.g. 90s, 20min or 2h")
        })?;
    let v: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a duration (e.g. 90s, 20min or 2h)"))?;
    let seconds = v * unit;
    if (1.0..=jkrbem::run::simulate::MAX_TIME_LIMIT_S).contains(&seconds) {
        Ok(Duration::from_secs_f64(seconds))
    } else {
        Err(format!(
            "{}: give a duration in [1 s, 30 days], e.g. 90s, 20min or 2h",
            jkrbem::text::compact(v)
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_need_a_unit_and_are_bounded() {
        assert_eq!(duration("90s"), Ok(Duration::from_secs(90)));
        assert_eq!(duration("20min"), Ok(Duration::from_secs(1200)));
        assert_eq!(duration("1.5h"), Ok(Duration::from_secs(5400)));
        assert!(duration("90").unwrap_err().contains("write the unit"));
        for bad in ["0s", "0.5s", "31h0", "-5min", "NaNs", "1e300h", "800h"] {
            let e = duration(bad).unwrap_err();
            assert!(
                e.contains("[1 s, 30 days]") || e.contains("not a duration"),
                "{bad}: {e}"
            );
            assert!(e.len() < 100, "{e}");
        }
    }

    #[test]
    fn percentages_are_bounded() {
        assert_eq!(percentage("5%"), Ok(0.05));
        assert!(percentage("0.05").unwrap_err().contains("write the unit"));
        for bad in ["0%", "60%", "-5%", "NaN%", "1e300%"] {
            let e = percentage(bad).unwrap_err();
            assert!(
                e.contains("[0.1, 50]") || e.contains("not a percentage"),
                "{e}"
            );
            assert!(e.len() < 100, "{e}");
        }
    }
}
