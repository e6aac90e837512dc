//! Values the commands share: percentages (`2%`), with the unit required and the range checked.

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

#[cfg(test)]
mod tests {
    use super::*;

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
