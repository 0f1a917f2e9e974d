//! `aster plot FILE…`: draw the tables and functions a case wrote
//! (`IMPR_TABLE`, `IMPR_FONCTION`: TABLEAU, AGRAF or XMGRACE text, code_aster's
//! own files as well as aster's) as an SVG or PNG line chart.

use aster_run::table_read::{read_tables, TextTable};
use aster_study::charts::{write_line_chart, LineChart, Series};
use std::path::{Path, PathBuf};

/// What to draw: which columns, which rows, where and how.
pub struct Options<'a> {
    pub x: Option<&'a str>,
    pub y: &'a [String],
    /// `COLUMN=VALUE` row filters, all of which a row must pass.
    pub filters: &'a [String],
    pub out: Option<&'a Path>,
    pub title: Option<&'a str>,
    pub log_x: bool,
    pub log_y: bool,
}

/// Abscissae chosen before the first numeric column when no `--x` is given.
const PREFERRED_X: [&str; 4] = ["INST", "ABSC_CURV", "ABSCISSE", "FREQ"];
/// Numeric columns that are counters, not values: never drawn by default.
const COUNTERS: [&str; 2] = ["NUME_ORDRE", "NUME_INST"];

/// Exit 0 when the chart is written, 2 otherwise (with the reason).
pub fn run(files: &[PathBuf], opts: &Options) -> u8 {
    match plot(files, opts) {
        Ok((path, n)) => {
            println!(
                "wrote {} ({n} curve{})",
                path.display(),
                if n == 1 { "" } else { "s" }
            );
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            2
        }
    }
}

fn plot(files: &[PathBuf], opts: &Options) -> Result<(PathBuf, usize), String> {
    let filters = opts
        .filters
        .iter()
        .map(|f| {
            f.split_once('=')
                .map(|(c, v)| (c.trim().to_string(), v.trim().to_string()))
                .ok_or_else(|| format!("--where `{f}`: expected COLUMN=VALUE (e.g. NOEUD=N1)"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut curves: Vec<(String, Series)> = Vec::new();
    let mut x_name = None;
    for file in files {
        let text = std::fs::read(file).map_err(|e| format!("{}: {e}", file.display()))?;
        let text = String::from_utf8_lossy(&text);
        let tables = read_tables(&text)
            .map_err(|e| format!("{}:{}: {}", file.display(), e.line, e.message))?;
        let several = tables.len() > 1;
        let stem = file
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        for (k, t) in tables.iter().enumerate() {
            let place = if several {
                format!("{} (table {})", file.display(), k + 1)
            } else {
                file.display().to_string()
            };
            let label = if several {
                format!("{stem} #{}", k + 1)
            } else {
                stem.clone()
            };
            let (x, ys) = columns(t, opts, &place)?;
            let rows = selected_rows(t, &filters, &place)?;
            x_name.get_or_insert_with(|| t.columns[x].clone());
            for y in ys {
                let points = rows
                    .iter()
                    .filter_map(|&r| Some((t.number(r, x)?, t.number(r, y)?)))
                    .collect();
                curves.push((
                    label.clone(),
                    Series {
                        name: t.columns[y].clone(),
                        points,
                    },
                ));
            }
        }
    }
    // Legends say which file or table a curve comes from only where two
    // curves would otherwise share one.
    let names: Vec<String> = curves.iter().map(|(_, s)| s.name.clone()).collect();
    let series: Vec<Series> = curves
        .into_iter()
        .map(|(label, mut s)| {
            if names.iter().filter(|n| **n == s.name).count() > 1 {
                s.name = format!("{} — {label}", s.name);
            }
            s
        })
        .collect();
    if series.iter().all(|s| s.points.is_empty()) {
        return Err(match filters.is_empty() {
            true => "no numeric point to draw".into(),
            false => "no row passes the --where filters with numbers in the drawn columns".into(),
        });
    }
    let y_label = match series.as_slice() {
        [one] => one.name.clone(),
        _ => "value".into(),
    };
    let out = match opts.out {
        Some(p) => p.to_path_buf(),
        None => {
            let stem = files[0]
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned());
            PathBuf::from(format!("{}.svg", stem.unwrap_or_else(|| "plot".into())))
        }
    };
    let title = opts.title.map(str::to_string).unwrap_or_else(|| {
        files
            .iter()
            .map(|f| {
                f.file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default()
            })
            .collect::<Vec<_>>()
            .join(", ")
    });
    let n = series.len();
    let chart = LineChart {
        title,
        x_label: x_name.unwrap_or_default(),
        y_label,
        series,
        log_x: opts.log_x,
        log_y: opts.log_y,
    };
    write_line_chart(&chart, &out).map_err(|e| e.to_string())?;
    Ok((out, n))
}

fn find(t: &TextTable, name: &str, place: &str) -> Result<usize, String> {
    t.column_index(name).ok_or_else(|| {
        format!(
            "{place}: no column `{name}` (columns: {})",
            t.columns.join(", ")
        )
    })
}

/// The abscissa and ordinate columns of a table: as given, or INST (or
/// another usual abscissa) else the first numeric column, against every
/// other numeric column but counters.
fn columns(t: &TextTable, opts: &Options, place: &str) -> Result<(usize, Vec<usize>), String> {
    let numeric = |c: usize| t.is_numeric(c);
    let x = match opts.x {
        Some(name) => find(t, name, place)?,
        None => PREFERRED_X
            .iter()
            .filter_map(|n| t.column_index(n))
            .find(|&c| numeric(c))
            .or_else(|| (0..t.columns.len()).find(|&c| numeric(c)))
            .ok_or_else(|| {
                format!(
                    "{place}: no numeric column to draw (columns: {})",
                    t.columns.join(", ")
                )
            })?,
    };
    let ys: Vec<usize> = if opts.y.is_empty() {
        (0..t.columns.len())
            .filter(|&c| c != x && numeric(c))
            .filter(|&c| {
                !COUNTERS
                    .iter()
                    .any(|k| t.columns[c].eq_ignore_ascii_case(k))
            })
            .collect()
    } else {
        opts.y
            .iter()
            .map(|name| find(t, name, place))
            .collect::<Result<_, _>>()?
    };
    if ys.is_empty() {
        return Err(format!(
            "{place}: no numeric column to draw against `{}` (columns: {}); name one with --y",
            t.columns[x],
            t.columns.join(", ")
        ));
    }
    Ok((x, ys))
}

/// The rows passing every `COLUMN=VALUE` filter: equal text (case
/// ignored), or equal numbers when both sides are numbers.
fn selected_rows(
    t: &TextTable,
    filters: &[(String, String)],
    place: &str,
) -> Result<Vec<usize>, String> {
    let mut cols = Vec::new();
    for (c, v) in filters {
        cols.push((find(t, c, place)?, v.as_str()));
    }
    Ok((0..t.rows.len())
        .filter(|&r| {
            cols.iter()
                .all(|&(c, v)| match (t.number(r, c), v.parse::<f64>()) {
                    (Some(a), Ok(b)) => a == b,
                    _ => t.text(r, c).is_some_and(|s| s.eq_ignore_ascii_case(v)),
                })
        })
        .collect())
}
