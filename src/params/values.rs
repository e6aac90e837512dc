//! A parameter's value checked against its [`Spec`]: from text (the command line, a batch's
//! table) or from JSON (Python, a request file), into one canonical JSON value. Every refusal
//! names the parameter by its marker and says what it takes.

use super::{Kind, Range, Spec};
use crate::text::compact;
use serde_json::{Map, Value};

/// Longest part of a refused text that a message repeats (characters).
const SHOWN_CHARS: usize = 40;

/// `text` quoted for a message, cut to `SHOWN_CHARS` (40) characters and made printable.
pub fn shown(text: &str) -> String {
    let printable = crate::text::printable(text, SHOWN_CHARS);
    format!("\"{printable}\"")
}

/// "⟨name⟩ = value is invalid: what it takes".
fn invalid(spec: &Spec, value: &str, expected: &str) -> String {
    format!("{spec} = {value} is invalid: {expected}")
}

/// What a parameter takes, in words (its unit, range and form).
pub fn expected(spec: &Spec) -> String {
    let unit = if spec.unit.is_empty() {
        String::new()
    } else {
        format!(" ({})", spec.unit)
    };
    match spec.kind {
        Kind::Real(r) => format!("a number in {r}{unit}"),
        Kind::Count(lo, hi) => format!("a whole number from {lo} to {hi}"),
        Kind::PowerOfTwo(lo, hi) => format!("a power of two from {lo} to {hi}"),
        Kind::Switch => "true or false".to_string(),
        Kind::Choice(names) => format!("one of {}", names.join(", ")),
        Kind::Choices(names) => format!(
            "one or more of {}, comma-separated, none repeated (e.g. {})",
            names.join(", "),
            names[..names.len().min(2)].join(",")
        ),
        Kind::File => "a file's path".to_string(),
        Kind::Fraction(lo, hi) => format!(
            "a percentage in [{}, {}] (e.g. 2%{})",
            compact(lo * 100.0),
            compact(hi * 100.0),
            match spec.fronts {
                super::Fronts::Both => " on the command line, 0.02 from Python",
                super::Fronts::Cli => "",
            }
        ),
        Kind::Seconds(..) => {
            "a duration in [1 s, 30 days] (e.g. 90s, 20min or 2h on the command line; seconds \
             from Python)"
                .to_string()
        }
        Kind::Pair(r) => format!("two numbers, each in {r}{unit}, e.g. 0.25,-0.5"),
        Kind::Grids(lo, hi) => {
            format!("2 to 8 increasing powers of two from {lo} to {hi}, e.g. 64,128,256")
        }
        Kind::States => {
            "\"none\", \"minimum\", \"every:K\" (every K-th state, K ≥ 1) or \"states:I,J\" \
             (those states, counted from 0)"
                .to_string()
        }
    }
}

/// A real number in `r`, or why not.
fn real_in(spec: &Spec, v: f64, r: Range, shown_as: &str) -> Result<Value, String> {
    if r.contains(v) {
        Ok(Value::from(v))
    } else {
        Err(invalid(spec, shown_as, &expected(spec)))
    }
}

/// A whole number in [lo, hi] (and a power of two where asked), or why not.
fn whole_in(
    spec: &Spec,
    v: f64,
    lo: u64,
    hi: u64,
    power: bool,
    shown_as: &str,
) -> Result<Value, String> {
    let ok = v.fract() == 0.0 && v >= lo as f64 && v <= hi as f64;
    let n = v as u64;
    if ok && (!power || n.is_power_of_two()) {
        Ok(Value::from(n))
    } else {
        Err(invalid(spec, shown_as, &expected(spec)))
    }
}

/// Powers of two, 2 to 8 of them, increasing.
fn grids_in(
    spec: &Spec,
    values: &[f64],
    lo: u64,
    hi: u64,
    shown_as: &str,
) -> Result<Value, String> {
    let bad = || invalid(spec, shown_as, &expected(spec));
    if !(2..=8).contains(&values.len()) {
        return Err(bad());
    }
    let mut out: Vec<u64> = Vec::new();
    for &v in values {
        let n = whole_in(spec, v, lo, hi, true, shown_as)?;
        let n = n.as_u64().ok_or_else(bad)?;
        if out.last().is_some_and(|&last| n <= last) {
            return Err(bad());
        }
        out.push(n);
    }
    Ok(Value::from(out))
}

/// A choice's name as the library spells it (hyphens), if it is one of `names`.
fn choice(names: &[&str], given: &str) -> Option<String> {
    let canonical = given.trim().replace('_', "-");
    names
        .iter()
        .find(|n| **n == canonical)
        .map(|n| n.to_string())
}

/// One or more of `names`, none repeated, in the order given; or why not (naming the name
/// that is none of them, or the repeat).
fn choices_in(
    spec: &Spec,
    names: &[&str],
    given: &[&str],
    shown_as: &str,
) -> Result<Value, String> {
    if given.is_empty() || given.iter().all(|g| g.trim().is_empty()) {
        return Err(invalid(spec, shown_as, &expected(spec)));
    }
    let mut out: Vec<String> = Vec::new();
    for g in given {
        let Some(name) = choice(names, g) else {
            return Err(invalid(
                spec,
                shown_as,
                &format!("{} is not one of {}", shown(g.trim()), names.join(", ")),
            ));
        };
        if out.contains(&name) {
            return Err(invalid(
                spec,
                shown_as,
                &format!("{name} is given more than once; give each once"),
            ));
        }
        out.push(name);
    }
    Ok(Value::from(out))
}

/// A number written as text, or `None`.
fn number(text: &str) -> Option<f64> {
    text.trim().parse::<f64>().ok().filter(|v| v.is_finite())
}

/// Parse the text the command line (or a batch's table) gives for `spec`.
pub fn from_text(spec: &Spec, text: &str) -> Result<Value, String> {
    let s = shown(text);
    let bad = || invalid(spec, &s, &expected(spec));
    match spec.kind {
        Kind::Real(r) => real_in(spec, number(text).ok_or_else(bad)?, r, &s),
        Kind::Count(lo, hi) => whole_in(spec, number(text).ok_or_else(bad)?, lo, hi, false, &s),
        Kind::PowerOfTwo(lo, hi) => whole_in(spec, number(text).ok_or_else(bad)?, lo, hi, true, &s),
        Kind::Switch => match text.trim().to_ascii_lowercase().as_str() {
            "true" | "yes" | "1" | "on" => Ok(Value::Bool(true)),
            "false" | "no" | "0" | "off" | "" => Ok(Value::Bool(false)),
            _ => Err(bad()),
        },
        Kind::Choice(names) => choice(names, text).map(Value::from).ok_or_else(bad),
        Kind::File => {
            if text.is_empty() {
                Err(bad())
            } else {
                Ok(Value::from(text))
            }
        }
        Kind::Fraction(lo, hi) => {
            let Some(p) = text.trim().strip_suffix('%') else {
                return Err(format!(
                    "{spec} = {s} is invalid: write the unit, e.g. 5% or 1% (a bare number \
                     could mean a fraction or a per cent)"
                ));
            };
            let v = number(p).ok_or_else(bad)? / 100.0;
            real_in(spec, v, Range::closed(lo, hi), &s)
        }
        Kind::Seconds(lo, hi) => {
            let t = text.trim();
            let (n, scale) = [("min", 60.0), ("h", 3600.0), ("s", 1.0)]
                .iter()
                .find_map(|&(u, scale)| t.strip_suffix(u).map(|n| (n, scale)))
                .ok_or_else(|| {
                    format!("{spec} = {s} is invalid: write the unit, e.g. 90s, 20min or 2h")
                })?;
            let v = number(n).ok_or_else(bad)? * scale;
            real_in(spec, v, Range::closed(lo, hi), &s)
        }
        Kind::Pair(r) => {
            let parts: Vec<Option<f64>> = text.split(',').map(number).collect();
            match parts[..] {
                [Some(x), Some(y)] if r.contains(x) && r.contains(y) => Ok(Value::from(vec![x, y])),
                _ => Err(bad()),
            }
        }
        Kind::Grids(lo, hi) => {
            let parts: Option<Vec<f64>> = text.split(',').map(number).collect();
            grids_in(spec, &parts.ok_or_else(bad)?, lo, hi, &s)
        }
        Kind::States => super::FieldChoice::parse(text)
            .map(|_| Value::from(text.trim()))
            .map_err(|_| bad()),
        Kind::Choices(names) => {
            let given: Vec<&str> = text.split(',').collect();
            choices_in(spec, names, &given, &s)
        }
    }
}

/// A real number as text that reads back as the same number: Rust's shortest round-trip
/// form, in exponent form where that is shorter than a long run of digits.
fn real_text(v: f64) -> String {
    let plain = format!("{v}");
    if plain.len() > 20 {
        format!("{v:e}")
    } else {
        plain
    }
}

/// A JSON number as text: a whole number as one, a real by [`real_text`].
fn number_text(n: &serde_json::Number) -> String {
    match (n.as_u64(), n.as_i64(), n.as_f64()) {
        (Some(u), _, _) => u.to_string(),
        (_, Some(i), _) => i.to_string(),
        (_, _, Some(v)) => real_text(v),
        _ => n.to_string(),
    }
}

/// A checked value (the canonical form [`from_text`] and [`from_json`] give, as a request
/// records it) written as the command line and a batch's table write it, so that
/// [`from_text`] reads it back as the same value: an accuracy as a percentage ("2%"), a
/// duration in seconds with its unit ("90s"), a pair or grids joined by commas, a switch as
/// true or false. Empty for `null` (a parameter chosen for the scene).
pub fn to_text(spec: &Spec, value: &Value) -> String {
    match (spec.kind, value) {
        (_, Value::Null) => String::new(),
        (Kind::Fraction(..), Value::Number(n)) => n
            .as_f64()
            .map_or_else(|| n.to_string(), |v| format!("{}%", real_text(100.0 * v))),
        (Kind::Seconds(..), Value::Number(n)) => format!("{}s", number_text(n)),
        (_, Value::Number(n)) => number_text(n),
        (_, Value::Bool(b)) => b.to_string(),
        (_, Value::String(s)) => s.clone(),
        (_, Value::Array(items)) => items
            .iter()
            .map(|v| match v {
                Value::Number(n) => number_text(n),
                Value::String(s) => s.clone(),
                other => other.to_string(),
            })
            .collect::<Vec<_>>()
            .join(","),
        (_, other) => other.to_string(),
    }
}

/// `value` (from JSON) shown in a message: a string quoted and cut, anything else compact.
fn shown_json(value: &Value) -> String {
    match value {
        Value::String(s) => shown(s),
        Value::Number(n) => n.as_f64().map(compact).unwrap_or_else(|| n.to_string()),
        other => {
            let text = other.to_string();
            crate::text::printable(&text, SHOWN_CHARS)
        }
    }
}

/// A value refused: the message (naming the parameter by its marker), and whether the value
/// was of the wrong type (a string where a number is meant, 32.0 where a whole number is, a
/// bool where a number is …) rather than out of range.
#[derive(Debug, Clone, PartialEq)]
pub struct Refusal {
    /// What is wrong, naming the parameter.
    pub message: String,
    /// Whether the value was of the wrong type.
    pub wrong_type: bool,
    /// The parameter whose value was refused (`None` for a name that is no parameter).
    pub param: Option<&'static Spec>,
}

impl From<String> for Refusal {
    fn from(message: String) -> Self {
        Refusal {
            message,
            wrong_type: false,
            param: None,
        }
    }
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// The JSON type of `value`, in words.
fn json_type(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a bool",
        Value::Number(n) if n.is_f64() => "a float",
        Value::Number(_) => "an integer",
        Value::String(_) => "a string",
        Value::Array(_) => "a list",
        Value::Object(_) => "a dict",
    }
}

/// Check the JSON value a Python caller (or a request file) gives for `spec`. Numbers where
/// numbers are asked (whole numbers written as such: 32, not 32.0), `true`/`false` for a
/// switch, a fraction for an accuracy, seconds for a duration, a list for a pair or grids; a
/// string in the command line's form is also taken for an accuracy ("2%") and a duration
/// ("90s").
pub fn from_json(spec: &Spec, value: &Value) -> Result<Value, Refusal> {
    let s = shown_json(value);
    let wrong = || Refusal {
        message: format!(
            "{spec} = {s} is invalid: {} is expected, not {}",
            expected(spec),
            json_type(value)
        ),
        wrong_type: true,
        param: None,
    };
    let is_num = |v: &Value| v.is_number();
    // A whole number must be written as one (32, not 32.0); one beyond 64 bits comes as a
    // float (and is then out of range).
    let whole = |v: &Value| {
        v.is_i64()
            || v.is_u64()
            || v.as_f64()
                .is_some_and(|x| x.abs() >= 9.2e18 && x.fract() == 0.0)
    };
    let num = |v: &Value| v.as_f64().unwrap_or(f64::NAN);
    let nums = |a: &[Value]| a.iter().map(num).collect::<Vec<f64>>();
    let out = match (spec.kind, value) {
        (Kind::Real(r), v) if is_num(v) => real_in(spec, num(v), r, &s),
        (Kind::Count(lo, hi), v) if whole(v) => whole_in(spec, num(v), lo, hi, false, &s),
        (Kind::PowerOfTwo(lo, hi), v) if whole(v) => whole_in(spec, num(v), lo, hi, true, &s),
        (Kind::Switch, Value::Bool(b)) => Ok(Value::Bool(*b)),
        (Kind::Choice(names), Value::String(t)) => choice(names, t)
            .map(Value::from)
            .ok_or_else(|| invalid(spec, &s, &expected(spec))),
        (Kind::File, Value::String(t)) if !t.is_empty() => Ok(Value::from(t.as_str())),
        (Kind::File, Value::String(_)) => Err(invalid(spec, &s, &expected(spec))),
        (Kind::Fraction(..) | Kind::Seconds(..) | Kind::States, Value::String(t)) => {
            from_text(spec, t)
        }
        (Kind::Fraction(lo, hi) | Kind::Seconds(lo, hi), v) if is_num(v) => {
            real_in(spec, num(v), Range::closed(lo, hi), &s)
        }
        (Kind::Pair(r), Value::Array(a)) if a.iter().all(is_num) => match nums(a)[..] {
            [x, y] if r.contains(x) && r.contains(y) => Ok(Value::from(vec![x, y])),
            _ => Err(invalid(spec, &s, &expected(spec))),
        },
        (Kind::Grids(lo, hi), Value::Array(a)) if a.iter().all(whole) => {
            grids_in(spec, &nums(a), lo, hi, &s)
        }
        (Kind::Choices(_), Value::String(t)) => from_text(spec, t),
        (Kind::Choices(names), Value::Array(a)) if a.iter().all(Value::is_string) => {
            let given: Vec<&str> = a.iter().filter_map(Value::as_str).collect();
            choices_in(spec, names, &given, &s)
        }
        _ => return Err(wrong()),
    };
    out.map_err(Refusal::from)
}

/// A request's values, checked: every name a parameter of `specs` (else the names it could
/// be), every value of its kind and range. `from` reads one value for its spec.
pub fn checked<'a, T: 'a, E: Into<Refusal>>(
    specs: &[&'static Spec],
    given: impl IntoIterator<Item = (&'a str, T)>,
    from: impl Fn(&Spec, T) -> Result<Value, E>,
) -> Result<Map<String, Value>, Refusal> {
    let mut out = Map::new();
    for (name, raw) in given {
        let Some(spec) = specs.iter().copied().find(|s| s.name == name) else {
            return Err(Refusal {
                message: unknown(specs, name),
                wrong_type: true,
                param: None,
            });
        };
        let naming = |e: E| Refusal {
            param: Some(spec),
            ..e.into()
        };
        let v = from(spec, raw).map_err(naming)?;
        if out.insert(spec.name.to_string(), v).is_some() {
            return Err(Refusal {
                param: Some(spec),
                ..format!("{spec} is given more than once").into()
            });
        }
    }
    Ok(out)
}

/// The refusal of a name that is no parameter, with the closest names.
pub fn unknown(specs: &[&'static Spec], name: &str) -> String {
    let canonical = name.trim_start_matches('-').replace('-', "_");
    let mut near: Vec<&Spec> = specs
        .iter()
        .copied()
        .filter(|s| {
            s.name.contains(canonical.as_str())
                || canonical.contains(s.name)
                || edit_distance(s.name, &canonical) <= 2
        })
        .collect();
    near.truncate(3);
    let hint = if near.is_empty() {
        String::new()
    } else {
        let names: Vec<String> = near.iter().map(|s| s.to_string()).collect();
        format!(" (did you mean {}?)", names.join(" or "))
    };
    format!("{} is not a parameter{hint}", shown(name))
}

/// Levenshtein distance of two short names.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}
