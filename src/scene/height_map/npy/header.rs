//! Parsing the header of a `.npy` file: the Python dictionary literal that
//! gives the array's dtype, memory order and shape.

use super::super::error::quote_limited;

/// Deepest bracket nesting accepted in a `.npy` header (dimensionless count).
const MAX_HEADER_DEPTH: usize = 16;

/// The parts of a `.npy` header the reader uses.
#[derive(Debug)]
pub(super) struct NpyHeaderInfo {
    /// The `'descr'` value (a string for plain dtypes, a list for records).
    pub(super) descr: PyValue,
    /// The `'fortran_order'` flag.
    pub(super) fortran_order: bool,
    /// The `'shape'` tuple (counts).
    pub(super) shape: Vec<u64>,
}

/// A Python literal as found in a `.npy` header.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum PyValue {
    /// A quoted string.
    Str(String),
    /// An integer.
    Int(i64),
    /// `True` or `False`.
    Bool(bool),
    /// `None`.
    NoneValue,
    /// A parenthesised tuple.
    Tuple(Vec<PyValue>),
    /// A bracketed list.
    List(Vec<PyValue>),
    /// A braced dictionary, in source order.
    Dict(Vec<(PyValue, PyValue)>),
}

impl PyValue {
    /// Renders the value as Python would print it.
    pub(super) fn render(&self) -> String {
        let join = |items: &[PyValue]| {
            items
                .iter()
                .map(PyValue::render)
                .collect::<Vec<_>>()
                .join(", ")
        };
        match self {
            Self::Str(s) => format!("'{s}'"),
            Self::Int(n) => n.to_string(),
            Self::Bool(true) => "True".to_owned(),
            Self::Bool(false) => "False".to_owned(),
            Self::NoneValue => "None".to_owned(),
            Self::Tuple(items) if items.len() == 1 => format!("({},)", join(items)),
            Self::Tuple(items) => format!("({})", join(items)),
            Self::List(items) => format!("[{}]", join(items)),
            Self::Dict(entries) => {
                let inner = entries
                    .iter()
                    .map(|(k, v)| format!("{}: {}", k.render(), v.render()))
                    .collect::<Vec<_>>()
                    .join(", ");
                format!("{{{inner}}}")
            }
        }
    }
}

/// A recursive-descent parser for the Python literals in `.npy` headers.
struct PyParser {
    /// The header text.
    chars: Vec<char>,
    /// Index of the next unread char.
    pos: usize,
}

impl PyParser {
    /// The next unread char, if any.
    fn peek(&self) -> Option<char> {
        self.chars.get(self.pos).copied()
    }

    /// Skips whitespace.
    fn skip_whitespace(&mut self) {
        while self.peek().is_some_and(char::is_whitespace) {
            self.pos += 1;
        }
    }

    /// Parses one value nested `depth` brackets deep.
    fn value(&mut self, depth: usize) -> Result<PyValue, String> {
        if depth > MAX_HEADER_DEPTH {
            return Err("brackets are nested too deeply".to_owned());
        }
        self.skip_whitespace();
        let Some(c) = self.peek() else {
            return Err("the header ends where a value was expected".to_owned());
        };
        match c {
            '{' => {
                self.pos += 1;
                self.dict(depth)
            }
            '(' => {
                self.pos += 1;
                self.items(')', depth).map(PyValue::Tuple)
            }
            '[' => {
                self.pos += 1;
                self.items(']', depth).map(PyValue::List)
            }
            '\'' | '"' => self.string(c),
            '0'..='9' | '-' | '+' => self.int(),
            c if c.is_alphabetic() || c == '_' => self.word(),
            other => Err(format!(
                "unexpected character '{}' at position {}",
                other.escape_debug(),
                self.pos + 1
            )),
        }
    }

    /// After an item, consumes `,` or `close`; `Ok(true)` once `close` is read.
    fn separator(&mut self, close: char) -> Result<bool, String> {
        self.skip_whitespace();
        match self.peek() {
            Some(',') => {
                self.pos += 1;
                Ok(false)
            }
            Some(c) if c == close => {
                self.pos += 1;
                Ok(true)
            }
            Some(c) => Err(format!(
                "expected ',' or '{close}' but found '{}' at position {}",
                c.escape_debug(),
                self.pos + 1
            )),
            None => Err(format!("the header ends before the closing '{close}'")),
        }
    }

    /// Parses tuple or list items up to `close` (already past the opener).
    fn items(&mut self, close: char, depth: usize) -> Result<Vec<PyValue>, String> {
        let mut out = Vec::new();
        loop {
            self.skip_whitespace();
            if self.peek() == Some(close) {
                self.pos += 1;
                return Ok(out);
            }
            out.push(self.value(depth + 1)?);
            if self.separator(close)? {
                return Ok(out);
            }
        }
    }

    /// Parses dictionary entries up to `}` (already past the `{`).
    fn dict(&mut self, depth: usize) -> Result<PyValue, String> {
        let mut entries = Vec::new();
        loop {
            self.skip_whitespace();
            if self.peek() == Some('}') {
                self.pos += 1;
                return Ok(PyValue::Dict(entries));
            }
            let key = self.value(depth + 1)?;
            self.skip_whitespace();
            if self.peek() != Some(':') {
                return Err(format!(
                    "expected ':' after the key {} at position {}",
                    quote_limited(&key.render()),
                    self.pos + 1
                ));
            }
            self.pos += 1;
            let value = self.value(depth + 1)?;
            entries.push((key, value));
            if self.separator('}')? {
                return Ok(PyValue::Dict(entries));
            }
        }
    }

    /// Parses a string quoted with `quote` (the parser is at the quote).
    fn string(&mut self, quote: char) -> Result<PyValue, String> {
        let start = self.pos + 1;
        self.pos += 1;
        let mut out = String::new();
        loop {
            let Some(c) = self.peek() else {
                return Err(format!(
                    "the string starting at position {start} is not closed"
                ));
            };
            self.pos += 1;
            if c == quote {
                return Ok(PyValue::Str(out));
            }
            if c != '\\' {
                out.push(c);
                continue;
            }
            let Some(escaped) = self.peek() else {
                return Err(format!(
                    "the string starting at position {start} is not closed"
                ));
            };
            self.pos += 1;
            match escaped {
                'n' => out.push('\n'),
                't' => out.push('\t'),
                '\\' | '\'' | '"' => out.push(escaped),
                other => {
                    out.push('\\');
                    out.push(other);
                }
            }
        }
    }

    /// Parses an optionally signed decimal integer (a Python 2 `L` suffix is
    /// accepted).
    fn int(&mut self) -> Result<PyValue, String> {
        let start = self.pos + 1;
        let negative = match self.peek() {
            Some('-') => {
                self.pos += 1;
                true
            }
            Some('+') => {
                self.pos += 1;
                false
            }
            _ => false,
        };
        let mut value: i64 = 0;
        let mut digits = 0;
        while let Some(digit) = self.peek().and_then(|c| c.to_digit(10)) {
            value = value
                .checked_mul(10)
                .and_then(|v| v.checked_add(i64::from(digit)))
                .ok_or_else(|| format!("the integer at position {start} is too large"))?;
            digits += 1;
            self.pos += 1;
        }
        if digits == 0 {
            return Err(format!("expected a digit at position {}", self.pos + 1));
        }
        if matches!(self.peek(), Some('L' | 'l')) {
            self.pos += 1;
        }
        if matches!(self.peek(), Some('.' | 'e' | 'E' | 'j' | 'J')) {
            return Err(format!(
                "expected an integer at position {start} but found a non-integer number"
            ));
        }
        Ok(PyValue::Int(if negative { -value } else { value }))
    }

    /// Parses `True`, `False` or `None`.
    fn word(&mut self) -> Result<PyValue, String> {
        let start = self.pos;
        while self.peek().is_some_and(|c| c.is_alphanumeric() || c == '_') {
            self.pos += 1;
        }
        let word: String = self
            .chars
            .get(start..self.pos)
            .unwrap_or_default()
            .iter()
            .collect();
        match word.as_str() {
            "True" => Ok(PyValue::Bool(true)),
            "False" => Ok(PyValue::Bool(false)),
            "None" => Ok(PyValue::NoneValue),
            _ => Err(format!(
                "unknown name '{}' at position {}",
                quote_limited(&word),
                start + 1
            )),
        }
    }
}

/// Parses a `.npy` header dictionary and extracts `descr`, `fortran_order`
/// and `shape`; other keys are ignored, and a repeated key's last value wins.
pub(super) fn parse_npy_header(text: &str) -> Result<NpyHeaderInfo, String> {
    let mut parser = PyParser {
        chars: text.chars().collect(),
        pos: 0,
    };
    let value = parser.value(0)?;
    let rest = parser.chars.get(parser.pos..).unwrap_or_default();
    if !rest.iter().all(|c| c.is_whitespace() || *c == '\0') {
        return Err(format!(
            "unexpected text after the dictionary at position {}",
            parser.pos + 1
        ));
    }
    let PyValue::Dict(entries) = value else {
        return Err(format!(
            "expected a dictionary but found {}",
            quote_limited(&value.render())
        ));
    };
    let lookup = |key: &str| {
        entries
            .iter()
            .rev()
            .find(|(k, _)| matches!(k, PyValue::Str(s) if s == key))
            .map(|(_, v)| v)
    };
    let missing = |key: &str| format!("the header has no '{key}' entry");
    let descr = lookup("descr").ok_or_else(|| missing("descr"))?.clone();
    let fortran_order = match lookup("fortran_order") {
        Some(PyValue::Bool(flag)) => *flag,
        Some(other) => {
            return Err(format!(
                "'fortran_order' must be True or False, not {}",
                quote_limited(&other.render())
            ))
        }
        None => return Err(missing("fortran_order")),
    };
    let shape = match lookup("shape") {
        Some(PyValue::Tuple(items) | PyValue::List(items)) => items
            .iter()
            .map(|item| match item {
                PyValue::Int(n) => {
                    u64::try_from(*n).map_err(|_| format!("the shape has a negative size {n}"))
                }
                other => Err(format!(
                    "the shape must hold integers, not {}",
                    quote_limited(&other.render())
                )),
            })
            .collect::<Result<Vec<u64>, String>>()?,
        Some(other) => {
            return Err(format!(
                "'shape' must be a tuple of integers, not {}",
                quote_limited(&other.render())
            ))
        }
        None => return Err(missing("shape")),
    };
    Ok(NpyHeaderInfo {
        descr,
        fortran_order,
        shape,
    })
}

#[cfg(test)]
mod tests {
    use super::super::super::HeightMap;
    use super::super::tests::{le8, sample_values};
    use super::super::NPY_MAGIC;

    #[test]
    fn npy_header_tolerates_quotes_spaces_and_commas() {
        let (_, _, values) = sample_values();
        let header = "{ \"shape\" : ( 4 , 5 , ) ,\"fortran_order\":False,'descr':\"=f8\" }  \n";
        let mut bytes = NPY_MAGIC.to_vec();
        bytes.extend_from_slice(&[1, 0]);
        bytes.extend_from_slice(&u16::try_from(header.len()).unwrap().to_le_bytes());
        bytes.extend_from_slice(header.as_bytes());
        let data: Vec<u8> = if cfg!(target_endian = "big") {
            values.iter().flat_map(|v| v.to_be_bytes()).collect()
        } else {
            le8(&values)
        };
        bytes.extend_from_slice(&data);
        let map = HeightMap::from_npy_bytes(&bytes, 1.0, "q").unwrap();
        assert_eq!(map.heights(), values.as_slice());
    }
}
