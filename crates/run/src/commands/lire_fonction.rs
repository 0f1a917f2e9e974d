//! LIRE_FONCTION: a function or a nappe read from a text file of columns
//! (code_aster's `lire_fonction_ops.py`, format `LIBRE`).
//!
//! The file is cut into blocks: a line that is not a sequence of reals
//! (an empty line, a title, a header) ends the current block; every line
//! of a block has the same number of fields (code_aster's FONCT0_42
//! otherwise). `INDIC_PARA`, `INDIC_RESU`, `INDIC_ABSCISSE` are
//! (block, column) pairs counted from 1. The function is then made as
//! DEFI_FONCTION (`NOM_PARA`, `NOM_RESU`, `INTERPOL`, `PROL_*`) or, with
//! `TYPE='NAPPE'`, as DEFI_NAPPE: one function per `DEFI_FONCTION`
//! occurrence (`INDIC_ABSCISSE` against its `INDIC_RESU`, with
//! `INTERPOL_FONC`, `PROL_*_FONC`), the nappe's parameter values the
//! column `INDIC_PARA`.

use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::function::{Function, Tabulated};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use std::rc::Rc;

const CMD: &str = "LIRE_FONCTION";

/// What LIRE_FONCTION reads (`crate::support`).
pub(crate) const LIRE_FONCTION: Support = Support {
    values: &[
        Values::new("FORMAT", &["LIBRE"]).why("(a NumPy binary file): the text format LIBRE only"),
        Values::new("TYPE", &["FONCTION", "NAPPE"]).why("(complex functions are not implemented)"),
    ],
    ..Support::keywords(&[
        "FORMAT",
        "TYPE",
        "SEPARATEUR",
        "INDIC_PARA",
        "INDIC_RESU",
        "NOM_PARA_FONC",
        "INDIC_ABSCISSE",
        "INTERPOL_FONC",
        "PROL_DROITE_FONC",
        "PROL_GAUCHE_FONC",
        "DEFI_FONCTION",
        "DEFI_FONCTION/INDIC_RESU",
        "UNITE",
        "NOM_PARA",
        "NOM_RESU",
        "INTERPOL",
        "PROL_DROITE",
        "PROL_GAUCHE",
        "VERIF",
        "INFO",
        "TITRE",
    ])
};

/// The blocks of a text file of real columns (code_aster's `lire_blocs`):
/// rows of reals, split at every line that is not one; `separator` `None`
/// splits at white space, else at that string (empty fields dropped).
pub(crate) fn blocks(text: &str, separator: Option<&str>) -> Result<Vec<Vec<Vec<f64>>>, String> {
    let mut blocks = Vec::new();
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line = line.trim();
        let fields: Vec<&str> = match separator {
            None => line.split_whitespace().collect(),
            Some(sep) => line.split(sep).filter(|f| !f.is_empty()).collect(),
        };
        let values: Option<Vec<f64>> = if line.is_empty() {
            None
        } else {
            fields
                .iter()
                .map(|f| f.trim().parse::<f64>().ok())
                .collect()
        };
        match values {
            Some(values) => {
                if let Some(first) = rows.first() {
                    if first.len() != values.len() {
                        return Err(format!(
                            "line {}: {} fields where the block's first line has {}",
                            index + 1,
                            values.len(),
                            first.len()
                        ));
                    }
                }
                rows.push(values);
            }
            None => {
                if !rows.is_empty() {
                    blocks.push(std::mem::take(&mut rows));
                }
            }
        }
    }
    if !rows.is_empty() {
        blocks.push(rows);
    }
    Ok(blocks)
}

/// Column `indic` = (block, column), from 1, of `blocks`.
fn column(blocks: &[Vec<Vec<f64>>], indic: (usize, usize), name: &str) -> Result<Vec<f64>, String> {
    let (b, c) = indic;
    let block = b
        .checked_sub(1)
        .and_then(|b| blocks.get(b))
        .ok_or_else(|| {
            format!(
                "the file has {} block(s), but {name} = ({b}, {c})",
                blocks.len()
            )
        })?;
    let width = block.first().map_or(0, Vec::len);
    if c == 0 || c > width {
        return Err(format!(
            "block {b} has {width} column(s), but {name} = ({b}, {c})"
        ));
    }
    Ok(block.iter().map(|row| row[c - 1]).collect())
}

/// A (block, column) pair keyword, or its catalog default.
fn indic(kw: &Keywords, name: &str, default: (usize, usize)) -> Result<(usize, usize), String> {
    let v: Vec<i64> = kw.simple(name).iter().filter_map(|s| s.as_i64()).collect();
    match v.as_slice() {
        [] => Ok(default),
        [b, c] if *b >= 1 && *c >= 1 => Ok((*b as usize, *c as usize)),
        _ => Err(format!(
            "{name} takes two positive integers (block, column)"
        )),
    }
}

/// The tabulated function of columns `x` and `y` (the same length).
fn pairs(
    blocks: &[Vec<Vec<f64>>],
    x: (usize, usize),
    y: (usize, usize),
    x_name: &str,
    y_name: &str,
) -> Result<(Vec<f64>, Vec<f64>), String> {
    let xs = column(blocks, x, x_name)?;
    let ys = column(blocks, y, y_name)?;
    if xs.len() != ys.len() {
        return Err(format!(
            "the two columns differ in length: {} lines for {x_name}, {} for {y_name}",
            xs.len(),
            ys.len()
        ));
    }
    Ok((xs, ys))
}

pub fn lire_fonction(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(0);
    let path = ex
        .input_path(unit as u32)
        .map(std::path::Path::to_path_buf)
        .ok_or_else(|| {
            ex.kw_error(
                CMD,
                kw,
                "UNITE",
                format!("no file for unit {unit} (a .export line `F libr <file> D {unit}`)"),
            )
        })?;
    let text = std::fs::read(&path)
        .map(|b| String::from_utf8_lossy(&b).into_owned())
        .map_err(|e| ExecError::new(format!("{CMD}: {}: {e}", path.display())))?;
    let separator = kw.str("SEPARATEUR").filter(|s| *s != "None");
    // code_aster's FONCT0_42: the file does not have the columns asked.
    let fault =
        |key: &str, msg: String| ex.kw_error(CMD, kw, key, format!("{}: {msg}", path.display()));
    let blocks = blocks(&text, separator).map_err(|m| fault("UNITE", m))?;
    let para = kw.str("NOM_PARA").unwrap_or("TOUTPARA");
    let para_indic = indic(kw, "INDIC_PARA", (1, 1)).map_err(|m| fault("INDIC_PARA", m))?;
    let function = if kw.str("TYPE") == Some("NAPPE") {
        let abscissa =
            indic(kw, "INDIC_ABSCISSE", (1, 1)).map_err(|m| fault("INDIC_ABSCISSE", m))?;
        let parameter_fonc = kw.str("NOM_PARA_FONC").unwrap_or("TOUTPARA").to_string();
        // The functions' options: INTERPOL_FONC, PROL_*_FONC under the
        // names DEFI_FONCTION's options read.
        let (scale_x, scale_y, left, right) = fonc_options(ex, kw)?;
        let mut functions = Vec::new();
        for occ in kw.factor("DEFI_FONCTION") {
            let resu = indic(occ, "INDIC_RESU", (1, 2)).map_err(|m| fault("DEFI_FONCTION", m))?;
            let (xs, ys) = pairs(&blocks, abscissa, resu, "INDIC_ABSCISSE", "INDIC_RESU")
                .map_err(|m| fault("DEFI_FONCTION", m))?;
            let mut t = Tabulated::new(&parameter_fonc, xs, ys)
                .map_err(|e| fault("DEFI_FONCTION", e.to_string()))?;
            (t.scale_x, t.scale_y, t.left, t.right) = (scale_x, scale_y, left, right);
            functions.push(Function::Tabulated(t));
        }
        let values =
            column(&blocks, para_indic, "INDIC_PARA").map_err(|m| fault("INDIC_PARA", m))?;
        let mut nappe = super::define::nappe(ex, CMD, kw, values, functions, parameter_fonc)?;
        nappe.parameter = para.to_string();
        Function::Nappe(nappe)
    } else {
        let resu = indic(kw, "INDIC_RESU", (1, 2)).map_err(|m| fault("INDIC_RESU", m))?;
        let (xs, ys) = pairs(&blocks, para_indic, resu, "INDIC_PARA", "INDIC_RESU")
            .map_err(|m| fault("INDIC_RESU", m))?;
        let mut t = Tabulated::new(para, xs, ys).map_err(|e| fault("UNITE", e.to_string()))?;
        t.result = Some(kw.str("NOM_RESU").unwrap_or("TOUTRESU").to_string());
        super::functions::apply_options(ex, CMD, kw, &mut t)?;
        Function::Tabulated(t)
    };
    store_result(ex, call, Concept::Function(Rc::new(function)))
}

/// `INTERPOL_FONC`, `PROL_GAUCHE_FONC`, `PROL_DROITE_FONC` of a nappe's
/// functions (defaults `LIN`, `EXCLU`).
fn fonc_options(ex: &Executor, kw: &Keywords) -> Result<super::functions::Options, ExecError> {
    use crate::function::{Extension, Scale};
    let mut out = (
        Scale::Linear,
        Scale::Linear,
        Extension::Excluded,
        Extension::Excluded,
    );
    for (key, slot) in [
        ("PROL_GAUCHE_FONC", &mut out.2),
        ("PROL_DROITE_FONC", &mut out.3),
    ] {
        if let Some(v) = kw.str(key) {
            *slot = Extension::from_keyword(v)
                .ok_or_else(|| ex.kw_error(CMD, kw, key, format!("unknown extension `{v}`")))?;
        }
    }
    let interp: Vec<&str> = kw
        .simple("INTERPOL_FONC")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let scale = |name: &str| {
        Scale::from_keyword(name)
            .ok_or_else(|| ex.kw_error(CMD, kw, "INTERPOL_FONC", format!("unknown scale `{name}`")))
    };
    match interp.as_slice() {
        [] => {}
        [one] => {
            out.0 = scale(one)?;
            out.1 = out.0;
        }
        [x, y, ..] => {
            out.0 = scale(x)?;
            out.1 = scale(y)?;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_split_at_lines_that_are_not_reals() {
        let text = "# title\n1 2\n3 4\n\nX Y\n5 6 7\n8 9 10\n";
        let b = blocks(text, None).unwrap();
        assert_eq!(b.len(), 2);
        assert_eq!(b[0], vec![vec![1.0, 2.0], vec![3.0, 4.0]]);
        assert_eq!(b[1][1], vec![8.0, 9.0, 10.0]);
        assert_eq!(column(&b, (2, 3), "INDIC_RESU").unwrap(), vec![7.0, 10.0]);
    }

    #[test]
    fn a_separator_and_ragged_rows() {
        let b = blocks("1;2\n3;;4\n", Some(";")).unwrap();
        assert_eq!(b[0], vec![vec![1.0, 2.0], vec![3.0, 4.0]]);
        let err = blocks("1 2\n3\n", None).unwrap_err();
        assert!(err.contains("line 2: 1 fields"), "{err}");
    }

    #[test]
    fn a_missing_block_or_column_is_named() {
        let b = blocks("1 2\n", None).unwrap();
        let err = column(&b, (2, 1), "INDIC_PARA").unwrap_err();
        assert!(err.contains("1 block(s), but INDIC_PARA = (2, 1)"), "{err}");
        let err = column(&b, (1, 3), "INDIC_RESU").unwrap_err();
        assert!(err.contains("block 1 has 2 column(s)"), "{err}");
    }
}
