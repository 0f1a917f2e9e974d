//! POST_ELEM/TRAV_EXT: the work of the external forces of a result,
//! code_aster's `pewext`.
//!
//! For each stored step `i` (every step, or those `TOUT_ORDRE`/`NUME_ORDRE`/
//! `INST`… designate) with its displacement `DEPL` uᵢ and its nodal forces
//! `FORC_NODA` fᵢ (computed before by CALC_CHAMP; code_aster stops when a
//! step lacks either), both reduced to the components DX DY DZ DRX DRY DRZ
//! (`cnsreddepl`; no Lagrange multipliers):
//! - `TRAV_ELAS` = ½ fᵢ·uᵢ, the work of a load applied proportionally;
//! - `TRAV_REEL` = Σ ½ (fᵢ₋₁ + fᵢ)·(uᵢ − uᵢ₋₁), the trapezoidal rule over
//!   the steps (0 at the first step listed, whatever its load: code_aster
//!   starts there, not from an unloaded state).
//!
//! Columns `NUME_ORDRE`, `INST`, `TRAV_ELAS`, `TRAV_REEL`.

use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::field::{Field, NodalField};
use crate::table::{ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError};
use std::rc::Rc;

/// The components `cnsreddepl` keeps.
const WORK_COMPONENTS: [&str; 6] = ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"];

pub(super) fn trav_ext(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "POST_ELEM/TRAV_EXT";
    let kw = &call.keywords;
    let r = ex.required(cmd, kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let steps = super::super::post::select_steps(ex, "POST_ELEM", kw, &result)?;
    let mut table = Table::new(
        [
            ("NUME_ORDRE", ColumnType::Int),
            ("INST", ColumnType::Real),
            ("TRAV_ELAS", ColumnType::Real),
            ("TRAV_REEL", ColumnType::Real),
        ]
        .into_iter()
        .map(|(n, ty)| super::col(n, ty))
        .collect(),
    );
    let mut work = ExternalWork::default();
    for step in steps {
        let nodal = |name: &str| -> Result<&NodalField, ExecError> {
            match super::super::post::step_field(step, name, &r.name)? {
                Field::Nodal(n) => Ok(n),
                Field::Elem(_) => Err(ExecError::new(format!(
                    "{cmd}: {name} of `{}` at NUME_ORDRE {} is not a nodal field",
                    r.name, step.nume_ordre
                ))),
            }
        };
        let u = nodal("DEPL")?;
        let f = nodal("FORC_NODA")?;
        let (u, f) = (work_vector(u), work_vector(f));
        let (elastic, real) = work.add(&u, &f).map_err(|(node, c)| {
            // code_aster's assertion in `cnsdot`: both fields must carry
            // the same components at the same nodes.
            ExecError::new(format!(
                "{cmd}: at NUME_ORDRE {} of `{}`, DEPL and FORC_NODA differ at node {} component {c} (one has it, the other not)",
                step.nume_ordre,
                r.name,
                node + 1
            ))
        })?;
        table.push_row(vec![
            ("NUME_ORDRE", Value::Int(step.nume_ordre as i64)),
            ("INST", Value::Real(step.inst)),
            ("TRAV_ELAS", Value::Real(elastic)),
            ("TRAV_REEL", Value::Real(real)),
        ]);
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// A node's number (0-based) and its DX…DRZ values.
type NodeWork = (u32, [Option<f64>; 6]);

/// A nodal field's DX…DRZ values, by node (ascending) then component of
/// [`WORK_COMPONENTS`]; `None` where the node lacks the component.
fn work_vector(field: &NodalField) -> Vec<NodeWork> {
    let index: Vec<Option<usize>> = WORK_COMPONENTS
        .iter()
        .map(|c| field.component_index(c))
        .collect();
    field
        .iter()
        .map(|(node, values)| {
            let mut v = [None; 6];
            for (k, i) in index.iter().enumerate() {
                v[k] = i.and_then(|i| values.get(i)).filter(|x| !x.is_nan());
            }
            (node.0, v)
        })
        .collect()
}

/// `pewext`'s running sums: the previous step's displacement and forces
/// and the accumulated work.
#[derive(Default)]
struct ExternalWork {
    previous: Option<(Vec<NodeWork>, Vec<NodeWork>)>,
    real: f64,
}

impl ExternalWork {
    /// Adds a step; returns (`TRAV_ELAS`, `TRAV_REEL`) of it, or the node
    /// and component where one field has a value and the other not.
    fn add(&mut self, u: &[NodeWork], f: &[NodeWork]) -> Result<(f64, f64), (u32, &'static str)> {
        let f1u1 = dot(u, f)?;
        match &self.previous {
            None => self.real = 0.0,
            Some((u0, f0)) => {
                let f0u0 = dot(u0, f0)?;
                let f1u0 = dot(u0, f)?;
                let f0u1 = dot(u, f0)?;
                self.real += 0.5 * (f0u1 - f1u0 + f1u1 - f0u0);
            }
        }
        self.previous = Some((u.to_vec(), f.to_vec()));
        Ok((f1u1 / 2.0, self.real))
    }
}

/// `cnsdot`: Σ aᵢ bᵢ over the values both carry; a value in one and not
/// in the other is an error (its node and component).
fn dot(a: &[NodeWork], b: &[NodeWork]) -> Result<f64, (u32, &'static str)> {
    let mut sum = 0.0;
    let (mut i, mut j) = (0, 0);
    let missing = |node: u32, v: &[Option<f64>; 6]| {
        v.iter()
            .position(Option::is_some)
            .map_or(Ok(()), |k| Err((node, WORK_COMPONENTS[k])))
    };
    while i < a.len() || j < b.len() {
        match (a.get(i), b.get(j)) {
            (Some((na, va)), Some((nb, vb))) if na == nb => {
                for k in 0..6 {
                    match (va[k], vb[k]) {
                        (Some(x), Some(y)) => sum += x * y,
                        (None, None) => {}
                        _ => return Err((*na, WORK_COMPONENTS[k])),
                    }
                }
                i += 1;
                j += 1;
            }
            (Some((na, va)), Some((nb, _))) if na < nb => {
                missing(*na, va)?;
                i += 1;
            }
            (Some((na, va)), None) => {
                missing(*na, va)?;
                i += 1;
            }
            (_, Some((nb, vb))) => {
                missing(*nb, vb)?;
                j += 1;
            }
            (None, None) => break,
        }
    }
    Ok(sum)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(node: u32, x: f64) -> NodeWork {
        (node, [Some(x), None, None, None, None, None])
    }

    /// A linear spring loaded in two equal steps, then unloaded: the
    /// trapezoidal rule is exact for a linear path (½ F u at the top, 0
    /// back at the start), `TRAV_ELAS` is ½ fᵢ·uᵢ of each step, and the
    /// first step's real work is 0 whatever its load.
    #[test]
    fn trapezoidal_work_of_a_linear_path() {
        let k = 4.0;
        let mut w = ExternalWork::default();
        let mut rows = Vec::new();
        for u in [0.5, 1.0, 2.0, 0.0] {
            rows.push(w.add(&[one(0, u)], &[one(0, k * u)]).unwrap());
        }
        assert_eq!(rows[0], (0.5 * k * 0.25, 0.0));
        assert_eq!(rows[1].0, 0.5 * k);
        assert!((rows[1].1 - 0.5 * k * (1.0 - 0.25)).abs() < 1e-15);
        assert!((rows[2].1 - 0.5 * k * (4.0 - 0.25)).abs() < 1e-15);
        assert!((rows[3].1 - 0.5 * k * (0.0 - 0.25)).abs() < 1e-15);
    }

    /// A component in one field and not in the other is `cnsdot`'s error.
    #[test]
    fn mismatched_components_are_an_error() {
        let u = [(3, [Some(1.0), Some(2.0), None, None, None, None])];
        let f = [one(3, 1.0)];
        assert_eq!(dot(&u, &f), Err((3, "DY")));
        assert_eq!(dot(&[one(1, 1.0)], &[one(2, 1.0)]), Err((1, "DX")));
        assert_eq!(dot(&[one(2, 3.0)], &[one(2, 5.0)]), Ok(15.0));
    }
}
