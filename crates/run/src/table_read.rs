//! Reading back the text that `IMPR_TABLE` and `IMPR_FONCTION` write — the
//! `TABLEAU` and `AGRAF` tables (`#` title lines, a header of column names,
//! one row per line, `-` for an empty cell) and `XMGRACE` projects (one
//! `xy` set per curve) — as named columns of cells, for `aster plot`.
//!
//! The same reader takes code_aster's own files: its `TABLEAU` layout is
//! the one `table::Table::render_as` reproduces.

use std::fmt;

/// One table read from a text file: its title lines, its column names and
/// its rows of cells (`None` for an empty cell).
#[derive(Clone, Debug, PartialEq)]
pub struct TextTable {
    pub title: Vec<String>,
    pub columns: Vec<String>,
    pub rows: Vec<Vec<Option<String>>>,
}

/// Why a file could not be read as tables.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadError {
    /// 1-based line of the file.
    pub line: usize,
    pub message: String,
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl TextTable {
    pub fn column_index(&self, name: &str) -> Option<usize> {
        self.columns
            .iter()
            .position(|c| c.eq_ignore_ascii_case(name))
    }

    /// The number in a cell, Fortran `D` exponents included.
    pub fn number(&self, row: usize, column: usize) -> Option<f64> {
        let cell = self.rows.get(row)?.get(column)?.as_deref()?;
        parse_number(cell)
    }

    /// True when every non-empty cell of the column is a number and at
    /// least one is.
    pub fn is_numeric(&self, column: usize) -> bool {
        let mut any = false;
        for r in 0..self.rows.len() {
            match self.rows[r].get(column).and_then(Option::as_deref) {
                None => {}
                Some(_) if self.number(r, column).is_some() => any = true,
                Some(_) => return false,
            }
        }
        any
    }

    /// The text of a cell, for row filters (`NOEUD=N1`).
    pub fn text(&self, row: usize, column: usize) -> Option<&str> {
        self.rows.get(row)?.get(column)?.as_deref()
    }
}

fn parse_number(cell: &str) -> Option<f64> {
    let s = cell.trim();
    if s.is_empty() {
        return None;
    }
    let v = s
        .parse::<f64>()
        .ok()
        .or_else(|| s.replace(['D', 'd'], "E").parse::<f64>().ok())?;
    v.is_finite().then_some(v)
}

/// Reads every table of a file: XMGRACE when the text has `@` directives
/// and `&` set ends, TABLEAU/AGRAF otherwise.
pub fn read_tables(text: &str) -> Result<Vec<TextTable>, ReadError> {
    let grace = text.lines().any(|l| l.starts_with('@')) && text.lines().any(|l| l.trim() == "&");
    let tables = if grace {
        read_xmgrace(text)?
    } else {
        read_tableau(text)
    };
    if tables.is_empty() {
        return Err(ReadError {
            line: 1,
            message: "no table found (expected IMPR_TABLE / IMPR_FONCTION text: \
                      a header of column names, then rows; or an XMGRACE project)"
                .into(),
        });
    }
    Ok(tables)
}

/// TABLEAU (and AGRAF, whose empty cells are `\-`): `#` lines open a table
/// and carry its title, the first other line is the header, then rows until
/// a blank line or the next `#` block.
fn read_tableau(text: &str) -> Vec<TextTable> {
    let mut tables = Vec::new();
    let mut title: Vec<String> = Vec::new();
    // The header's names and the character position where each starts.
    let mut header: Option<(Vec<String>, Vec<usize>)> = None;
    let mut rows: Vec<Vec<Option<String>>> = Vec::new();
    let finish = |title: &mut Vec<String>,
                  header: &mut Option<(Vec<String>, Vec<usize>)>,
                  rows: &mut Vec<Vec<Option<String>>>,
                  tables: &mut Vec<TextTable>| {
        if let Some((columns, _)) = header.take() {
            tables.push(TextTable {
                title: std::mem::take(title),
                columns,
                rows: std::mem::take(rows),
            });
        }
    };
    for raw in text.lines() {
        let line = raw.trim_end();
        if let Some(rest) = line.strip_prefix('#') {
            if header.is_some() {
                finish(&mut title, &mut header, &mut rows, &mut tables);
            }
            let t = rest.trim();
            if !t.is_empty() && !t.chars().all(|c| c == '-') {
                title.push(t.to_string());
            }
            continue;
        }
        if line.trim().is_empty() {
            finish(&mut title, &mut header, &mut rows, &mut tables);
            continue;
        }
        let Some((names, starts)) = &header else {
            let (names, starts) = tokens(line);
            header = Some((names, starts));
            continue;
        };
        let row = split_row(line, names.len(), starts);
        rows.push(row);
    }
    finish(&mut title, &mut header, &mut rows, &mut tables);
    tables
}

/// The whitespace-separated words of a line and the character position of
/// each.
fn tokens(line: &str) -> (Vec<String>, Vec<usize>) {
    let mut words = Vec::new();
    let mut starts = Vec::new();
    let mut current = String::new();
    for (pos, c) in line.chars().enumerate() {
        if c.is_whitespace() {
            if !current.is_empty() {
                words.push(std::mem::take(&mut current));
            }
        } else {
            if current.is_empty() {
                starts.push(pos);
            }
            current.push(c);
        }
    }
    if !current.is_empty() {
        words.push(current);
    }
    (words, starts)
}

/// A row's cells: its words when there are as many as columns, else the
/// text under each header name (code_aster aligns each column's cells under
/// its name, so a text cell holding blanks still lands in its column).
fn split_row(line: &str, n: usize, starts: &[usize]) -> Vec<Option<String>> {
    let (words, _) = tokens(line);
    let cells: Vec<String> = if words.len() == n {
        words
    } else {
        let chars: Vec<char> = line.chars().collect();
        (0..n)
            .map(|k| {
                let a = starts[k].min(chars.len());
                let b = starts
                    .get(k + 1)
                    .copied()
                    .unwrap_or(chars.len())
                    .min(chars.len());
                chars[a..b.max(a)]
                    .iter()
                    .collect::<String>()
                    .trim()
                    .to_string()
            })
            .collect()
    };
    cells
        .into_iter()
        .map(|c| {
            let c = c.trim_start_matches('\\').trim();
            (!(c.is_empty() || c == "-")).then(|| c.to_string())
        })
        .collect()
}

/// XMGRACE: each `xy` set (data lines up to `&`) is a table of two
/// columns, named by the x axis label (else `X`) and the set's legend (else
/// `S<n>`); the project's title is each table's title.
fn read_xmgrace(text: &str) -> Result<Vec<TextTable>, ReadError> {
    let mut title = Vec::new();
    let mut x_label = "X".to_string();
    let mut legends: Vec<(usize, String)> = Vec::new();
    let mut sets: Vec<(usize, Vec<Vec<Option<String>>>)> = Vec::new();
    let mut current: Option<(usize, Vec<Vec<Option<String>>>)> = None;
    let mut next_set = 0usize;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if let Some(d) = line.strip_prefix('@') {
            let d = d.trim();
            if let Some(t) = d.strip_prefix("title ") {
                title.push(unquote(t));
            } else if let Some(l) = d.strip_prefix("xaxis label ") {
                x_label = unquote(l);
            } else if let Some(rest) = d.strip_prefix('s') {
                if let Some((n, l)) = rest.split_once(" legend ") {
                    if let Ok(n) = n.trim().parse::<usize>() {
                        legends.push((n, unquote(l)));
                    }
                }
            } else if let Some(t) = d.strip_prefix("target ") {
                // `G0.S3`
                if let Some(n) = t.rsplit_once(".S").and_then(|(_, n)| n.trim().parse().ok()) {
                    next_set = n;
                }
            }
            continue;
        }
        if line == "&" {
            if let Some(set) = current.take() {
                sets.push(set);
            }
            next_set += 1;
            continue;
        }
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.len() < 2 || words.iter().take(2).any(|w| parse_number(w).is_none()) {
            return Err(ReadError {
                line: i + 1,
                message: format!("expected a point `x y` of an XMGRACE set, found `{line}`"),
            });
        }
        current
            .get_or_insert_with(|| (next_set, Vec::new()))
            .1
            .push(words[..2].iter().map(|w| Some(w.to_string())).collect());
    }
    if let Some(set) = current.take() {
        sets.push(set);
    }
    Ok(sets
        .into_iter()
        .map(|(n, rows)| {
            let legend = legends
                .iter()
                .rev()
                .find(|(k, _)| *k == n)
                .map(|(_, l)| l.clone())
                .filter(|l| !l.is_empty())
                .unwrap_or_else(|| format!("S{n}"));
            TextTable {
                title: title.clone(),
                columns: vec![x_label.clone(), legend],
                rows,
            }
        })
        .collect())
}

fn unquote(s: &str) -> String {
    s.trim().trim_matches('"').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::{Column, ColumnType, Table, TableFormat, Value};

    fn sample() -> Table {
        let mut t = Table::new(vec![
            Column {
                name: "NOEUD".into(),
                ty: ColumnType::Text(8),
            },
            Column {
                name: "NUME_ORDRE".into(),
                ty: ColumnType::Int,
            },
            Column {
                name: "INST".into(),
                ty: ColumnType::Real,
            },
            Column {
                name: "DX".into(),
                ty: ColumnType::Real,
            },
        ]);
        t.title.push("ASTER CONCEPT T DE TYPE TABLE_SDASTER".into());
        for k in 0..3 {
            t.push_row(vec![
                ("NOEUD", Value::Text("N1".into())),
                ("NUME_ORDRE", Value::Int(k)),
                ("INST", Value::Real(0.5 * k as f64)),
                ("DX", Value::Real(-1.25e-3 * k as f64)),
            ]);
        }
        // A row with empty cells.
        t.push_row(vec![("NOEUD", Value::Text("N2".into()))]);
        t
    }

    #[test]
    fn reads_back_what_impr_table_writes() {
        for format in [
            TableFormat::default(),
            TableFormat {
                agraf: true,
                ..TableFormat::default()
            },
            TableFormat {
                real_lead: 1,
                real_width: 12,
                real_precision: 7,
                agraf: false,
            },
        ] {
            let text = sample().render_as(&format);
            let tables = read_tables(&text).expect("reads");
            assert_eq!(tables.len(), 1, "{text}");
            let t = &tables[0];
            assert_eq!(t.columns, ["NOEUD", "NUME_ORDRE", "INST", "DX"]);
            assert_eq!(t.title, ["ASTER CONCEPT T DE TYPE TABLE_SDASTER"]);
            assert_eq!(t.rows.len(), 4);
            let dx = t.column_index("dx").expect("DX");
            assert!((t.number(2, dx).expect("a number") + 2.5e-3).abs() < 1e-15);
            assert_eq!(t.number(3, dx), None, "empty cell: {text}");
            assert_eq!(t.text(3, 0), Some("N2"));
            assert!(t.is_numeric(dx) && t.is_numeric(1) && !t.is_numeric(0));
        }
    }

    #[test]
    fn several_tables_and_fortran_exponents() {
        let text = "#\n# first\nINST DY\n0.0 1.0D-3\n1.0 2.0D-3\n\n#\n# second\nX Y Z\n1 2 3\n";
        let tables = read_tables(text).expect("reads");
        assert_eq!(tables.len(), 2);
        assert_eq!(tables[0].number(1, 1), Some(2.0e-3));
        assert_eq!(tables[1].title, ["second"]);
        assert_eq!(tables[1].columns, ["X", "Y", "Z"]);
    }

    #[test]
    fn a_text_cell_with_blanks_stays_in_its_column() {
        let text =
            "#\nINTITULE         INST         DY\nmy label         1.00000E+00  3.00000E+00\n";
        let t = &read_tables(text).expect("reads")[0];
        assert_eq!(t.text(0, 0), Some("my label"));
        assert_eq!(t.number(0, 2), Some(3.0));
    }

    #[test]
    fn reads_xmgrace_sets_with_their_legends() {
        let text = "# Grace project file written by aster\n@version 50100\n@title \"F(U)\"\n\
                    @xaxis label \"U\"\n@s0 legend \"force\"\n@target G0.S0\n@type xy\n0 0\n1 2.5\n&\n\
                    @s1 legend \"\"\n@target G0.S1\n@type xy\n0 1\n2 3\n&\n";
        let tables = read_tables(text).expect("reads");
        assert_eq!(tables.len(), 2);
        assert_eq!(tables[0].columns, ["U", "force"]);
        assert_eq!(tables[0].title, ["F(U)"]);
        assert_eq!(tables[0].number(1, 1), Some(2.5));
        assert_eq!(tables[1].columns, ["U", "S1"]);
    }

    #[test]
    fn errors_say_where() {
        let e = read_tables("").expect_err("empty");
        assert!(e.message.contains("no table found"), "{e}");
        let e = read_tables("@type xy\n1 x\n&\n").expect_err("bad point");
        assert_eq!(e.line, 2);
    }
}
