//! Tables (`table_sdaster`): typed columns, rows with possibly empty cells,
//! and their text form as `IMPR_TABLE` prints it (code_aster's `TABLEAU`
//! format: `#` title lines, a header, reals as `%12.5E`, integers as `%12d`,
//! strings left-aligned in their declared width `K8`/`K16`/`K24`).

use crate::pyfmt::c_exp;

/// The type of a column, as code_aster declares it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColumnType {
    Int,
    Real,
    /// A string of at most n characters (`K8`, `K16`, `K24`…).
    Text(usize),
}

impl ColumnType {
    pub fn name(self) -> String {
        match self {
            ColumnType::Int => "I".into(),
            ColumnType::Real => "R".into(),
            ColumnType::Text(n) => format!("K{n}"),
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Int(i64),
    Real(f64),
    Text(String),
}

impl Value {
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Int(i) => Some(*i as f64),
            Value::Real(r) => Some(*r),
            Value::Text(_) => None,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    pub name: String,
    pub ty: ColumnType,
}

/// A table: its title lines, columns, and rows (`None` = empty cell).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    pub title: Vec<String>,
    pub columns: Vec<Column>,
    pub rows: Vec<Vec<Option<Value>>>,
}

impl Table {
    pub fn new(columns: Vec<Column>) -> Table {
        Table {
            title: Vec::new(),
            columns,
            rows: Vec::new(),
        }
    }

    pub fn column_index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c.name == name)
    }

    /// Adds a column if absent; returns its index.
    pub fn ensure_column(&mut self, name: &str, ty: ColumnType) -> usize {
        if let Some(i) = self.column_index(name) {
            return i;
        }
        self.columns.push(Column {
            name: name.to_string(),
            ty,
        });
        for row in &mut self.rows {
            row.push(None);
        }
        self.columns.len() - 1
    }

    /// Appends a row given as (column, value) pairs; unknown columns are
    /// added with the type of their value.
    pub fn push_row(&mut self, cells: Vec<(&str, Value)>) {
        let mut row = vec![None; self.columns.len()];
        for (name, value) in cells {
            let ty = match &value {
                Value::Int(_) => ColumnType::Int,
                Value::Real(_) => ColumnType::Real,
                Value::Text(s) => ColumnType::Text(if s.len() <= 8 {
                    8
                } else if s.len() <= 16 {
                    16
                } else {
                    24
                }),
            };
            let i = self.ensure_column(name, ty);
            if row.len() < self.columns.len() {
                row.resize(self.columns.len(), None);
            }
            row[i] = Some(value);
        }
        self.rows.push(row);
    }

    /// Keeps the columns at `keep`, in that order.
    pub fn keep_columns(&mut self, keep: &[usize]) {
        self.columns = keep.iter().map(|&c| self.columns[c].clone()).collect();
        for row in &mut self.rows {
            *row = keep
                .iter()
                .map(|&c| row.get(c).cloned().flatten())
                .collect();
        }
    }

    pub fn value(&self, row: usize, column: &str) -> Option<&Value> {
        let c = self.column_index(column)?;
        self.rows.get(row)?.get(c)?.as_ref()
    }

    /// The `IMPR_TABLE` text (FORMAT='TABLEAU', reals as `%12.5E`).
    pub fn render(&self) -> String {
        self.render_as(&TableFormat::default())
    }

    /// The `IMPR_TABLE` text in a given format: code_aster's
    /// `TableBase.ReprTable` (code_aster/Objects/table_py.py), the widths
    /// and paddings of its `FMT` rule included.
    pub fn render_as(&self, format: &TableFormat) -> String {
        let mut out = String::new();
        out.push_str("#\n#");
        out.push_str(&"-".repeat(80));
        // The third line of the banner carries the first title line.
        out.push_str("\n#");
        if self.title.is_empty() {
            out.push('\n');
        }
        for (i, line) in self.title.iter().enumerate() {
            if i > 0 {
                out.push('#');
            }
            out.push_str(line);
            out.push('\n');
        }
        // Each column is as wide as its values or its name, whichever is wider.
        let widths: Vec<usize> = self
            .columns
            .iter()
            .map(|c| format.value_width(c.ty).max(c.name.len()))
            .collect();
        let header: Vec<String> = self
            .columns
            .iter()
            .zip(&widths)
            .map(|(c, &w)| format.string_cell(c.ty, w, &c.name))
            .collect();
        out.push_str(&header.join(" "));
        out.push('\n');
        for row in &self.rows {
            if row.iter().all(Option::is_none) {
                continue;
            }
            let cells: Vec<String> = self
                .columns
                .iter()
                .zip(&widths)
                .zip(row)
                .map(|((c, &w), v)| format.cell(c.ty, w, v.as_ref()))
                .collect();
            out.push_str(&cells.join(" "));
            out.push('\n');
        }
        out
    }
}

/// How `IMPR_TABLE` writes a table: the real format (`FORMAT_R`, a Fortran
/// edit descriptor such as `E12.5` or `1PE12.7`) and the AGRAF flavour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableFormat {
    /// Blanks before each real: code_aster turns a Fortran scale factor
    /// `nP` into n leading blanks (`fmtF2PY`: `1PE12.7` → `' %12.7E'`).
    pub real_lead: usize,
    pub real_width: usize,
    pub real_precision: usize,
    /// FORMAT='AGRAF': the TABLEAU text with a `\\` before each empty cell.
    pub agraf: bool,
}

impl Default for TableFormat {
    fn default() -> TableFormat {
        TableFormat {
            real_lead: 0,
            real_width: 12,
            real_precision: 5,
            agraf: false,
        }
    }
}

impl TableFormat {
    /// The format of reals from a Fortran edit descriptor `[nP]Ew.d` (or
    /// `D`), as code_aster's `fmtF2PY` reads it; `None` for any other.
    pub fn real_from_fortran(descriptor: &str) -> Option<(usize, usize, usize)> {
        let d = descriptor.trim().to_ascii_uppercase();
        let (lead, rest) = match d.split_once('P') {
            Some((n, rest)) => (n.parse::<usize>().ok()?, rest),
            None => (0, d.as_str()),
        };
        let rest = rest.strip_prefix('E').or_else(|| rest.strip_prefix('D'))?;
        let (w, p) = rest.split_once('.')?;
        let (w, p) = (w.parse::<usize>().ok()?, p.parse::<usize>().ok()?);
        (w > p && w <= 40).then_some((lead, w, p))
    }

    /// `len(formR % 0)`: the real format's width, or more when the digits
    /// overflow it (`%12.7E` writes 13 characters), after its blanks.
    fn real_len(&self) -> usize {
        let digits = if self.real_precision == 0 {
            5
        } else {
            self.real_precision + 6
        };
        self.real_lead + self.real_width.max(digits)
    }

    /// The string format of a column's type (`FMT(…, 'formK', type)`):
    /// (leading blanks, width of `%-ws`). For reals and integers code_aster
    /// derives it from their number format (`%12.5E` → `%-12s`).
    fn string_format(&self, ty: ColumnType) -> (usize, usize) {
        match ty {
            ColumnType::Real => (self.real_lead, self.real_width),
            ColumnType::Int => (0, 12),
            ColumnType::Text(n) => (0, n),
        }
    }

    /// The width of a column before its name is counted: the longest of
    /// its string, real and integer formats applied to 0 (code_aster's
    /// `ReprTable`: an integer column is as wide as a real one).
    fn value_width(&self, ty: ColumnType) -> usize {
        let (lead, w) = self.string_format(ty);
        match ty {
            ColumnType::Text(n) => n,
            _ => (lead + w).max(self.real_len()).max(12),
        }
    }

    /// A string in a column of `width` (a header, the `-` of an empty
    /// cell, a text value): the column's string format, shifted right when
    /// the column is wider than that format and than the string.
    fn string_cell(&self, ty: ColumnType, width: usize, s: &str) -> String {
        let (lead, w) = self.string_format(ty);
        let shift = width
            .saturating_sub(s.len())
            .min(width.saturating_sub(lead + w));
        format!("{}{}{s:<w$}", " ".repeat(shift), " ".repeat(lead))
    }

    fn cell(&self, ty: ColumnType, width: usize, value: Option<&Value>) -> String {
        match value {
            None => {
                // The empty cell's format is the string one, shifted as for
                // an empty string.
                let (lead, w) = self.string_format(ty);
                let shift = width.saturating_sub(lead + w);
                let s = format!("{}{}{:<w$}", " ".repeat(shift), " ".repeat(lead), "-");
                if self.agraf {
                    format!("\\{s}")
                } else {
                    s
                }
            }
            Some(Value::Real(r)) => format!(
                "{}{}{}",
                " ".repeat(width.saturating_sub(self.real_len())),
                " ".repeat(self.real_lead),
                c_exp(*r, self.real_width, self.real_precision)
            ),
            Some(Value::Int(i)) => format!("{}{:>12}", " ".repeat(width.saturating_sub(12)), i),
            Some(Value::Text(s)) => {
                let n = self.value_width(ty);
                format!("{}{s:<n$}", " ".repeat(width.saturating_sub(n)))
            }
        }
    }
}

/// code_aster's `PARA_CALC` table of `ENERGIE` (`nonlinDSEnergyCreate`):
/// NUME_REUSE, INST and the cumulated energies, one row per converged
/// increment after the initial state's.
pub fn energy_table(rows: &[aster_fem::energy_balance::EnergyRow]) -> Table {
    let mut t = Table::new(
        [
            ("NUME_REUSE", ColumnType::Int),
            ("INST", ColumnType::Real),
            ("TRAV_EXT", ColumnType::Real),
            ("ENER_CIN", ColumnType::Real),
            ("ENER_TOT", ColumnType::Real),
            ("TRAV_AMOR", ColumnType::Real),
            ("TRAV_LIAI", ColumnType::Real),
            ("DISS_SCH", ColumnType::Real),
        ]
        .into_iter()
        .map(|(name, ty)| Column {
            name: name.into(),
            ty,
        })
        .collect(),
    );
    for r in rows {
        t.push_row(vec![
            ("NUME_REUSE", Value::Int(0)),
            ("INST", Value::Real(r.time)),
            ("TRAV_EXT", Value::Real(r.trav_ext)),
            ("ENER_CIN", Value::Real(r.ener_cin)),
            ("ENER_TOT", Value::Real(r.ener_tot)),
            ("TRAV_AMOR", Value::Real(r.trav_amor)),
            ("TRAV_LIAI", Value::Real(r.trav_liai)),
            ("DISS_SCH", Value::Real(r.diss_sch)),
        ]);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_like_impr_table() {
        let mut t = Table::new(vec![
            Column {
                name: "INTITULE".into(),
                ty: ColumnType::Text(16),
            },
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
        t.push_row(vec![
            ("INTITULE", Value::Text("Depl".into())),
            ("NOEUD", Value::Text("N1".into())),
            ("NUME_ORDRE", Value::Int(20)),
            ("INST", Value::Real(20.0)),
            ("DX", Value::Real(-4.285714318)),
        ]);
        t.push_row(vec![
            ("NOEUD", Value::Text("N2".into())),
            ("DX", Value::Real(1.0)),
        ]);
        insta::assert_snapshot!(t.render());
    }

    /// Rows as code_aster's `ReprTable` writes them (its Python run on the
    /// same table gave these lines): `FORMAT_R='1PE12.7'` is `' %12.7E'`,
    /// AGRAF puts `\\` before empty cells, and a column whose name is wider
    /// than its values shifts them right.
    #[test]
    fn agraf_and_fortran_real_format_as_repr_table() {
        let mut t = Table::new(vec![
            Column {
                name: "NOEUD".into(),
                ty: ColumnType::Text(8),
            },
            Column {
                name: "INST".into(),
                ty: ColumnType::Real,
            },
            Column {
                name: "COOR_X".into(),
                ty: ColumnType::Real,
            },
            Column {
                name: "LAGS_C".into(),
                ty: ColumnType::Real,
            },
            Column {
                name: "A_LONG_COLUMN_NAME".into(),
                ty: ColumnType::Real,
            },
        ]);
        t.push_row(vec![
            ("NOEUD", Value::Text("N1".into())),
            ("INST", Value::Real(0.25)),
            ("COOR_X", Value::Real(-1.5)),
            ("A_LONG_COLUMN_NAME", Value::Real(3.0)),
        ]);
        t.push_row(vec![
            ("NOEUD", Value::Text("N12".into())),
            ("INST", Value::Real(1.0)),
            ("COOR_X", Value::Real(2.0e-3)),
            ("LAGS_C", Value::Real(-8105.9650734574)),
        ]);
        let (lead, width, precision) = TableFormat::real_from_fortran("1PE12.7").unwrap();
        let agraf = TableFormat {
            real_lead: lead,
            real_width: width,
            real_precision: precision,
            agraf: true,
        };
        let text = t.render_as(&agraf);
        let lines: Vec<&str> = text.lines().skip(3).collect();
        assert_eq!(
            lines,
            [
                "NOEUD      INST           COOR_X         LAGS_C        A_LONG_COLUMN_NAME",
                "N1        2.5000000E-01  -1.5000000E+00 \\  -                 3.0000000E+00",
                "N12       1.0000000E+00  2.0000000E-03  -8.1059651E+03 \\      -           ",
            ]
        );
        let text = t.render();
        let lines: Vec<&str> = text.lines().skip(3).collect();
        assert_eq!(
            lines,
            [
                "NOEUD    INST         COOR_X       LAGS_C       A_LONG_COLUMN_NAME",
                "N1        2.50000E-01 -1.50000E+00 -                   3.00000E+00",
                "N12       1.00000E+00  2.00000E-03 -8.10597E+03       -           ",
            ]
        );
        assert_eq!(TableFormat::real_from_fortran("E12.5"), Some((0, 12, 5)));
        assert_eq!(TableFormat::real_from_fortran("F8.3"), None);
    }
}
