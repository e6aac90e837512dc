//! A batch's table (`scenes.csv`): one scene per row, one column per parameter of the schema
//! (by its name, `mesh_angle`, or its flag, `--mesh-angle` or `mesh-angle`), and an optional
//! `id` column naming each scene (else its 1-based row number). An empty cell is a parameter
//! not given (the schema's default). Every cell is checked here, before any work: a refusal
//! names the row and the column, and the parameter in the table's words (its name).

use crate::output::file::{read_regular, ReadError};
use crate::params::{self, values, words, Fronts, Spec, SPECS};
use crate::session::request::Request;
use crate::session::{input, RunError};
use std::collections::HashMap;
use std::path::Path;

/// The most scenes a batch holds.
pub const MAX_SCENES: usize = 10_000;

/// The largest table read (bytes).
pub const MAX_TABLE_BYTES: u64 = 64 << 20;

/// The longest id (characters): it goes into file names.
pub const MAX_ID_CHARS: usize = 100;

/// One scene of the table.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Its place in the table, from 0 (the shards split by it).
    pub index: usize,
    /// Its line in the file (the header is line 1).
    pub line: u64,
    /// Its id (given, or its 1-based row number).
    pub id: String,
    /// Its request, every cell checked, the defaults filled.
    pub request: Request,
}

/// A table read: its rows, and the header each parameter was given under.
#[derive(Debug, Clone)]
pub struct Table {
    /// The file, as given (for messages).
    pub source: String,
    /// Every scene, in order.
    pub rows: Vec<Row>,
    /// Each parameter's column as the header spells it.
    pub columns: Vec<(&'static Spec, String)>,
}

impl Table {
    /// "scenes.csv row 3 (line 4, id a1)": where a row is, for a message.
    pub fn place(&self, row: &Row) -> String {
        let id = if row.id == (row.index + 1).to_string() {
            String::new()
        } else {
            format!(", id {}", row.id)
        };
        format!(
            "{} row {} (line {}{id})",
            self.source,
            row.index + 1,
            row.line
        )
    }

    /// A refusal of `row`: `message` (from the library, parameters as markers) in the table's
    /// words, with the row and, where the message names one of the table's parameters first,
    /// its column.
    pub fn refusal(&self, row: &Row, message: &str) -> RunError {
        let column = words::named(message).first().map(|spec| {
            let header = self
                .columns
                .iter()
                .find(|(s, _)| std::ptr::eq(*s, *spec))
                .map_or(spec.name, |(_, h)| h.as_str());
            format!(", column {header}")
        });
        input(format!(
            "{}{}: {}",
            self.place(row),
            column.unwrap_or_default(),
            words::keywords(message)
        ))
    }
}

/// What a column holds.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Column {
    /// The scene's id.
    Id,
    /// A parameter.
    Parameter(&'static Spec),
}

/// Read and check the table at `path`.
pub fn read(path: &Path) -> Result<Table, RunError> {
    let source = path.display().to_string();
    let bytes = read_regular(path, MAX_TABLE_BYTES).map_err(|e| match e {
        ReadError::Absent => input(format!("{source}: no such file (the table of scenes)")),
        ReadError::Refused(why) => input(format!("{source}: {why}")),
    })?;
    let text = String::from_utf8(bytes).map_err(|_| {
        input(format!(
            "{source}: not UTF-8 text (a CSV table is expected)"
        ))
    })?;
    parse(&text, &source)
}

/// The columns of a header, every name checked.
fn columns(header: &csv::StringRecord, source: &str) -> Result<Vec<Column>, RunError> {
    let mut out: Vec<Column> = Vec::new();
    for (i, name) in header.iter().enumerate() {
        let at = format!("{source} column {} ({})", i + 1, values::shown(name));
        let column = match name.trim() {
            "id" => Column::Id,
            "" => return Err(input(format!("{at}: a column without a name"))),
            n => match params::by_column(n) {
                Some(spec) if spec.fronts == Fronts::Cli => {
                    return Err(input(format!(
                        "{at}: a batch chooses each scene's files itself (DIR/scene-<id>.csv \
                         for the states, DIR/scene-<id>.json for the summary): leave the \
                         column out"
                    )))
                }
                Some(spec) => Column::Parameter(spec),
                None => {
                    return Err(input(format!(
                        "{at}: {}",
                        words::keywords(&values::unknown(SPECS, n))
                    )))
                }
            },
        };
        if let Some(j) = out.iter().position(|c| *c == column) {
            return Err(input(format!(
                "{at} repeats column {} ({}): give each parameter one column",
                j + 1,
                values::shown(&header[j])
            )));
        }
        out.push(column);
    }
    Ok(out)
}

/// Whether `id` may name a scene's files: 1 to [`MAX_ID_CHARS`] letters, digits, `.`, `_` or
/// `-`.
fn valid_id(id: &str) -> bool {
    !id.is_empty()
        && id.chars().count() <= MAX_ID_CHARS
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'))
}

/// Parse and check a table's text (`source`: its name, for messages).
pub fn parse(text: &str, source: &str) -> Result<Table, RunError> {
    // A spreadsheet's byte-order mark is no part of the first column's name.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(false)
        .from_reader(text.as_bytes());
    let header = reader
        .headers()
        .map_err(|e| input(format!("{source}: {e}")))?
        .clone();
    if header.iter().all(|h| h.trim().is_empty()) {
        return Err(input(format!(
            "{source}: no header (the first line names the columns: id and parameters, e.g. \
             id,ratio,grid)"
        )));
    }
    let kinds = columns(&header, source)?;
    let table_columns: Vec<(&'static Spec, String)> = kinds
        .iter()
        .zip(header.iter())
        .filter_map(|(c, h)| match c {
            Column::Parameter(spec) => Some((*spec, h.trim().to_string())),
            Column::Id => None,
        })
        .collect();
    let mut table = Table {
        source: source.to_string(),
        rows: Vec::new(),
        columns: table_columns,
    };
    // Each id by its lower case: ids that differ only in case name one file on a file system
    // that ignores case (macOS's, Windows').
    let mut ids: HashMap<String, (usize, String)> = HashMap::new();
    for (index, record) in reader.records().enumerate() {
        if index >= MAX_SCENES {
            return Err(input(format!(
                "{source}: more than {MAX_SCENES} scenes; split the table"
            )));
        }
        let record = record.map_err(|e| input(format!("{source} row {}: {e}", index + 1)))?;
        let line = record.position().map_or(index as u64 + 2, |p| p.line());
        let mut id = (index + 1).to_string();
        let mut given: Vec<(&'static Spec, &str)> = Vec::new();
        for (column, cell) in kinds.iter().zip(record.iter()) {
            let cell = cell.trim();
            if cell.is_empty() {
                continue;
            }
            match column {
                Column::Id if valid_id(cell) => id = cell.to_string(),
                Column::Id => {
                    return Err(input(format!(
                        "{source} row {} (line {line}), column id: {} is invalid: 1 to \
                         {MAX_ID_CHARS} letters, digits, '.', '_' or '-' (it names the scene's \
                         files)",
                        index + 1,
                        values::shown(cell)
                    )))
                }
                Column::Parameter(spec) => given.push((spec, cell)),
            }
        }
        // A placeholder row for messages until its request is built.
        let mut row = Row {
            index,
            line,
            id,
            request: Request::from_values(Default::default())?,
        };
        for &(spec, cell) in &given {
            values::from_text(spec, cell).map_err(|e| table.refusal(&row, &e))?;
        }
        row.request = Request::from_texts(given.iter().map(|(s, c)| (s.name, *c)))
            .map_err(|e| table.refusal(&row, &e.to_string()))?;
        if let Some((first, other)) = ids.insert(row.id.to_lowercase(), (index, row.id.clone())) {
            return Err(input(if other == row.id {
                format!(
                    "{source} rows {} and {} have the same id {}: each scene needs its own (it \
                     names the scene's files)",
                    first + 1,
                    index + 1,
                    values::shown(&row.id)
                )
            } else {
                format!(
                    "{source} rows {} and {} have the ids {} and {}, which differ only in \
                     case: on a file system that ignores case (macOS, Windows) they name the \
                     same files; give ids that differ in more than case",
                    first + 1,
                    index + 1,
                    values::shown(&other),
                    values::shown(&row.id)
                )
            }));
        }
        table.rows.push(row);
    }
    if table.rows.is_empty() {
        return Err(input(format!(
            "{source}: no scenes (a header and one row per scene are expected)"
        )));
    }
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(text: &str) -> String {
        parse(text, "t.csv").unwrap_err().to_string()
    }

    #[test]
    fn cells_become_requests_with_the_defaults_filled() {
        let t = parse(
            "id,ratio,--mesh-angle,grid,accuracy\na,2,,32,\n,,30,,1%\n",
            "t.csv",
        )
        .unwrap();
        assert_eq!(t.rows.len(), 2);
        assert_eq!(t.rows[0].id, "a");
        assert_eq!(t.rows[0].request.ratio, Some(2.0));
        assert_eq!(t.rows[0].request.grid, Some(32));
        assert_eq!(t.rows[0].request.mesh_angle, 0.0);
        assert_eq!(t.rows[1].id, "2");
        assert_eq!(t.rows[1].request.mesh_angle, 30.0);
        assert_eq!(t.rows[1].request.accuracy, Some(0.01));
        assert_eq!(t.rows[1].line, 3);
    }

    #[test]
    fn a_bad_cell_is_refused_naming_its_row_and_column() {
        let e = refused("id,ratio,mesh-angle\na,2,0\nb,0.5,0\n");
        assert!(
            e.starts_with("t.csv row 2 (line 3, id b), column ratio: ratio = "),
            "{e}"
        );
        let e = refused("ratio,mesh-angle\n2,0\n3,500\n");
        assert!(
            e.starts_with("t.csv row 2 (line 3), column mesh-angle: mesh_angle = "),
            "{e}"
        );
        assert!(!e.contains('⟨'), "{e}");
    }

    #[test]
    fn bad_columns_and_ids_are_refused() {
        let e = refused("id,ratoi\na,2\n");
        assert!(
            e.contains("column 2") && e.contains("did you mean ratio"),
            "{e}"
        );
        let e = refused("ratio,out\n2,x.csv\n");
        assert!(
            e.contains("column 2") && e.contains("leave the column out"),
            "{e}"
        );
        let e = refused("summary\nx.json\n");
        assert!(e.contains("leave the column out"), "{e}");
        let e = refused("mesh_angle,--mesh-angle\n1,2\n");
        assert!(e.contains("repeats column 1"), "{e}");
        let e = refused("id,ratio\na,2\na,3\n");
        assert!(e.contains("rows 1 and 2 have the same id"), "{e}");
        let e = refused("id,ratio\nb,2\nAb-1,2\naB-1,3\n");
        assert!(
            e.contains(
                "rows 2 and 3 have the ids \"Ab-1\" and \"aB-1\", which differ only in case"
            ),
            "{e}"
        );
        let e = refused("id,ratio\n../x,2\n");
        assert!(e.contains("row 1 (line 2), column id"), "{e}");
        let e = refused("id,ratio\na,2,3\n");
        assert!(e.contains("row 1"), "{e}");
        assert!(refused("id,ratio\n").contains("no scenes"));
    }
}
