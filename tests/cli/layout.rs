//! docs/layout.md stays in step with the tree (issue 56, item 8): its table of files has one
//! row per `*.rs` under `src/` and per `*.wgsl` under `shaders/`, each naming a file that
//! exists and saying what it is for in 1 to 12 words; its table of rooms has one row per
//! top-level entry of `src/` (each `src/X.rs` and each `src/X/`).

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

/// Most words a file's purpose may take.
const MAX_PURPOSE_WORDS: usize = 12;

/// The header row of the table of files.
const FILES_HEADER: &str = "| file | purpose |";

/// The header row of the table of rooms.
const ROOMS_HEADER: &str = "| room | owns | must not import |";

/// The rows of the table under `header` in `doc`, each as its cells (trimmed, outer pipes
/// dropped), with its line number; the separator row is skipped and the table ends at the first
/// line that does not start with `|`.
fn table_rows(doc: &str, header: &str) -> Vec<(usize, Vec<String>)> {
    let mut lines = doc.lines().enumerate();
    let found = lines.by_ref().any(|(_, line)| line.trim() == header);
    assert!(
        found,
        "docs/layout.md has no table with the header row `{header}`"
    );
    let mut rows = Vec::new();
    for (i, line) in lines {
        let line = line.trim();
        if !line.starts_with('|') {
            break;
        }
        let inner = line.trim_start_matches('|').trim_end_matches('|');
        let cells: Vec<String> = inner.split('|').map(|c| c.trim().to_string()).collect();
        if cells
            .iter()
            .all(|c| !c.is_empty() && c.chars().all(|ch| ch == '-' || ch == ':'))
        {
            continue;
        }
        rows.push((i + 1, cells));
    }
    rows
}

/// The first `code` span of a cell, or the whole cell where it has none.
fn first_code(cell: &str) -> &str {
    let mut parts = cell.split('`');
    match (parts.next(), parts.next()) {
        (Some(_), Some(code)) => code,
        _ => cell,
    }
}

/// Every file under `dir` (relative to `root`) whose name ends in `ext`, as a path relative to
/// `root` with `/` separators.
fn files_under(root: &Path, dir: &str, ext: &str, found: &mut Vec<String>) {
    let entries = fs::read_dir(root.join(dir)).unwrap_or_else(|e| panic!("reading {dir}: {e}"));
    for entry in entries {
        let entry = entry.unwrap();
        let name = entry
            .file_name()
            .into_string()
            .expect("a file name that is UTF-8");
        let path = format!("{dir}/{name}");
        if entry.file_type().unwrap().is_dir() {
            files_under(root, &path, ext, found);
        } else if name.ends_with(ext) {
            found.push(path);
        }
    }
}

#[test]
fn layout_doc_lists_every_source_file_and_every_room() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = fs::read_to_string(root.join("docs/layout.md")).expect("docs/layout.md");
    let mut problems = Vec::new();

    // The table of files.
    let mut rows: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (line, cells) in table_rows(&doc, FILES_HEADER) {
        if cells.len() != 2 {
            problems.push(format!(
                "line {line}: a file's row has {} cells, not 2 (a `|` in its purpose?)",
                cells.len()
            ));
            continue;
        }
        let file = first_code(&cells[0]).to_string();
        let words = cells[1].split_whitespace().count();
        if !(1..=MAX_PURPOSE_WORDS).contains(&words) {
            problems.push(format!(
                "line {line}: the purpose of {file} has {words} words, not 1 to {MAX_PURPOSE_WORDS}"
            ));
        }
        rows.entry(file).or_default().push(line);
    }
    let mut sources = Vec::new();
    files_under(root, "src", ".rs", &mut sources);
    files_under(root, "shaders", ".wgsl", &mut sources);
    sources.sort();
    for source in &sources {
        match rows.get(source).map(Vec::len) {
            None => problems.push(format!("{source} has no row in the table of files")),
            Some(1) => {}
            Some(n) => problems.push(format!(
                "{source} has {n} rows in the table of files (lines {:?})",
                rows[source]
            )),
        }
    }
    for (file, lines) in &rows {
        if !sources.contains(file) {
            problems.push(format!(
                "line {}: the table of files names {file}, which is no `*.rs` under src/ or \
                 `*.wgsl` under shaders/",
                lines[0]
            ));
        }
    }

    // The table of rooms.
    let mut rooms: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (line, cells) in table_rows(&doc, ROOMS_HEADER) {
        if cells.len() != 3 {
            problems.push(format!(
                "line {line}: a room's row has {} cells, not 3",
                cells.len()
            ));
            continue;
        }
        rooms
            .entry(first_code(&cells[0]).to_string())
            .or_default()
            .push(line);
    }
    let mut top = Vec::new();
    for entry in fs::read_dir(root.join("src")).unwrap() {
        let entry = entry.unwrap();
        let name = entry
            .file_name()
            .into_string()
            .expect("a file name that is UTF-8");
        if entry.file_type().unwrap().is_dir() {
            top.push(format!("src/{name}/"));
        } else if name.ends_with(".rs") {
            top.push(format!("src/{name}"));
        }
    }
    top.sort();
    for room in &top {
        match rooms.get(room).map(Vec::len) {
            None => problems.push(format!("{room} has no row in the table of rooms")),
            Some(1) => {}
            Some(n) => problems.push(format!(
                "{room} has {n} rows in the table of rooms (lines {:?})",
                rooms[room]
            )),
        }
    }
    for (room, lines) in &rooms {
        let stale = if room.starts_with("src/") {
            !top.contains(room)
        } else {
            !root.join(room).exists()
        };
        if stale {
            problems.push(format!(
                "line {}: the table of rooms names {room}, which does not exist",
                lines[0]
            ));
        }
    }

    assert!(
        problems.is_empty(),
        "docs/layout.md is out of step with the tree:\n  {}",
        problems.join("\n  ")
    );
}
