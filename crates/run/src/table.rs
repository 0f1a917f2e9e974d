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

    /// The width of one formatted value (code_aster: 12 for numbers).
    fn value_width(self) -> usize {
        match self {
            ColumnType::Int | ColumnType::Real => 12,
            ColumnType::Text(n) => n,
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

    pub fn value(&self, row: usize, column: &str) -> Option<&Value> {
        let c = self.column_index(column)?;
        self.rows.get(row)?.get(c)?.as_ref()
    }

    /// The `IMPR_TABLE` text (FORMAT='TABLEAU').
    pub fn render(&self) -> String {
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
            .map(|c| c.ty.value_width().max(c.name.len()))
            .collect();
        let header: Vec<String> = self
            .columns
            .iter()
            .zip(&widths)
            .map(|(c, &w)| format!("{:<w$}", c.name))
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
                .map(|((c, &w), v)| format_cell(c.ty, w, v.as_ref()))
                .collect();
            out.push_str(&cells.join(" "));
            out.push('\n');
        }
        out
    }
}

fn format_cell(ty: ColumnType, width: usize, value: Option<&Value>) -> String {
    // Numbers are right-aligned in their 12 characters, then the column is
    // padded on the left when its name is wider (code_aster's FMT rule).
    let pad = width - ty.value_width().min(width);
    match value {
        None => format!("{:<width$}", "-"),
        Some(Value::Real(r)) => format!("{}{}", " ".repeat(pad), c_exp(*r, 12, 5)),
        Some(Value::Int(i)) => format!("{}{:>12}", " ".repeat(pad), i),
        Some(Value::Text(s)) => format!("{s:<width$}"),
    }
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
}
