//! CALC_PRESSION: the pressure on a boundary from the nodal stresses, as
//! code_aster 17 computes it (a macro-command): at each node of the
//! `GROUP_MA` cells, with n the nodal normal (the normalised mean of the
//! unit normals of the group's cells at the node, each from the cell's
//! tangents at that node, on the initial or the deformed geometry) and σ
//! the `SIEF_NOEU` stress,
//!
//!   PRES = n·σ·n;  in 2D also V = σ·n − PRES·n (VX, VY) and CISA = |V|.
//!
//! The field `PRES_NOEU` is added to the result at each instant (`INST`, or
//! all with `TOUT_ORDRE`); `SIEF_NOEU` is computed first when the result
//! does not have it.

use crate::concept::{Concept, EvolResult, Step};
use crate::executor::{result_of, Executor};
use crate::field::{Field, NodalField};
use crate::select;
use crate::support::Support;
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_mesh::{CellId, Mesh, NodeId};
use std::collections::BTreeMap;
use std::rc::Rc;

const CMD: &str = "CALC_PRESSION";

/// Nodal normals of boundary cells (segments in 2D, faces in 3D) on the
/// coordinates `xyz`, as code_aster's `CREA_CHAMP(OPERATION='NORMALE')`
/// (`canort`): in each cell, the unit normal at the node from the cell's
/// own tangents there ((t_y, −t_x) for a segment, t₁ × t₂ for a face, so a
/// curved quadratic cell gives each node its own normal), summed over the
/// cells around the node, then normalised.
pub(crate) fn nodal_normals(
    mesh: &Mesh,
    cells: &[CellId],
    xyz: &dyn Fn(NodeId) -> [f64; 3],
) -> Result<BTreeMap<NodeId, [f64; 3]>, ExecError> {
    let mut sum: BTreeMap<NodeId, [f64; 3]> = BTreeMap::new();
    for &c in cells {
        let cell = mesh.cell(c);
        let dim = cell.ty.dim();
        if !(dim == 1 || dim == 2) || !aster_fem::shape::supported(cell.ty) {
            return Err(ExecError::new(format!(
                "GROUP_MA: cell {} is a {}; normals are computed on boundary cells (segments in 2D, faces in 3D)",
                select::cell_name(mesh, c),
                cell.ty.name()
            )));
        }
        let p: Vec<[f64; 3]> = cell.nodes.iter().map(|n| xyz(*n)).collect();
        let reference = aster_fem::shape::reference_nodes(cell.ty);
        for (i, &node) in cell.nodes.iter().enumerate() {
            let Some(&xi) = reference.get(i) else {
                continue;
            };
            let dn = aster_fem::shape::shape(cell.ty, xi).dn;
            let (mut t1, mut t2) = ([0.0; 3], [0.0; 3]);
            for (k, x) in p.iter().enumerate() {
                for d in 0..3 {
                    t1[d] += dn[k][0] * x[d];
                    t2[d] += dn[k][1] * x[d];
                }
            }
            let n = if dim == 1 {
                [t1[1], -t1[0], 0.0]
            } else {
                [
                    t1[1] * t2[2] - t1[2] * t2[1],
                    t1[2] * t2[0] - t1[0] * t2[2],
                    t1[0] * t2[1] - t1[1] * t2[0],
                ]
            };
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if l == 0.0 || !l.is_finite() {
                return Err(ExecError::new(format!(
                    "cell {} is degenerate (no normal)",
                    select::cell_name(mesh, c)
                )));
            }
            let s = sum.entry(node).or_insert([0.0; 3]);
            for d in 0..3 {
                s[d] += n[d] / l;
            }
        }
    }
    for v in sum.values_mut() {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if l > 0.0 {
            for x in v.iter_mut() {
                *x /= l;
            }
        }
    }
    Ok(sum)
}

/// PRES_NOEU of one step.
fn pressure_field(
    mesh: &Mesh,
    cells: &[CellId],
    step: &Step,
    deformed: bool,
) -> Result<NodalField, ExecError> {
    let Some(Field::Nodal(sigma)) = step.fields.get("SIEF_NOEU") else {
        return Err(ExecError::new(format!(
            "{CMD}: no SIEF_NOEU at INST={}",
            step.inst
        )));
    };
    let depl = match (deformed, step.fields.get("DEPL")) {
        (false, _) => None,
        (true, Some(Field::Nodal(d))) => Some(d),
        (true, _) => {
            return Err(ExecError::new(format!(
                "{CMD}: GEOMETRIE='DEFORMEE' needs DEPL at INST={}",
                step.inst
            )))
        }
    };
    let xyz = |n: NodeId| {
        let mut x = mesh.coord(n);
        if let Some(d) = depl {
            for (k, c) in ["DX", "DY", "DZ"].iter().enumerate() {
                x[k] += d.get(n, c).unwrap_or(0.0);
            }
        }
        x
    };
    let normals = nodal_normals(mesh, cells, &xyz)?;
    let plane = mesh.dim < 3;
    let comps: Vec<String> = if plane {
        ["PRES", "CISA", "VX", "VY"].map(String::from).to_vec()
    } else {
        vec!["PRES".to_string()]
    };
    let mut out = NodalField::new(comps);
    for (&node, n) in &normals {
        let s = |c: &str| sigma.get(node, c).unwrap_or(0.0);
        let (xx, yy, xy) = (s("SIXX"), s("SIYY"), s("SIXY"));
        if plane {
            let p = xx * n[0] * n[0] + yy * n[1] * n[1] + 2.0 * xy * n[0] * n[1];
            let vx = (xx - p) * n[0] + xy * n[1];
            let vy = (yy - p) * n[1] + xy * n[0];
            out.set(node, "PRES", p);
            out.set(node, "CISA", (vx * vx + vy * vy).sqrt());
            out.set(node, "VX", vx);
            out.set(node, "VY", vy);
        } else {
            let (zz, xz, yz) = (s("SIZZ"), s("SIXZ"), s("SIYZ"));
            let p = xx * n[0] * n[0]
                + yy * n[1] * n[1]
                + zz * n[2] * n[2]
                + 2.0 * (xy * n[0] * n[1] + xz * n[0] * n[2] + yz * n[1] * n[2]);
            out.set(node, "PRES", p);
        }
    }
    Ok(out)
}

const CALC_PRESSION_OWN: &[&str] = &[
    "MAILLAGE",
    "RESULTAT",
    "GROUP_MA",
    "GEOMETRIE",
    "INFO",
    "MODELE",
];

/// What CALC_PRESSION reads (`crate::support`): its own keywords and the step
/// selection ([`super::post::STEP_SELECTION`]).
pub(crate) const CALC_PRESSION: Support =
    Support::keywords(&crate::support::joined::<
        _,
        { super::post::STEP_SELECTION.len() + CALC_PRESSION_OWN.len() },
    >(super::post::STEP_SELECTION, CALC_PRESSION_OWN));

pub fn calc_pression(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let r = ex.required(CMD, kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let mesh = ex.mesh_by_id(result.mesh)?;
    let cells = select::cells(kw, &mesh, "").map_err(|e| ExecError::new(format!("{CMD}: {e}")))?;
    // Every step unless the step selection designates some.
    let steps: Vec<u32> = super::select_steps_pub(ex, CMD, kw, &result)?;
    let deformed = kw.str("GEOMETRIE").unwrap_or("DEFORMEE") == "DEFORMEE";
    let missing: Vec<u32> = steps
        .iter()
        .copied()
        .filter(|n| {
            result
                .step_numbered(*n)
                .is_some_and(|s| !s.fields.contains_key("SIEF_NOEU"))
        })
        .collect();
    let mut out: EvolResult = if missing.is_empty() {
        (*result).clone()
    } else {
        crate::fembridge::calc_champ(
            ex,
            call,
            &result,
            &["SIEF_NOEU".to_string()],
            &missing,
            None,
        )?
    };
    for step in out
        .steps
        .iter_mut()
        .filter(|s| steps.contains(&s.nume_ordre))
    {
        let field = pressure_field(&mesh, &cells, step, deformed)?;
        step.fields.insert("PRES_NOEU".into(), Field::Nodal(field));
    }
    let target = result_of(call)?.clone();
    ex.insert(&target, Concept::Result(Rc::new(out)));
    Ok(CommandOutput::Concept)
}

#[cfg(test)]
mod tests {
    use super::*;
    use aster_mesh::{Cell, CellType};

    #[test]
    fn pressure_and_shear_on_a_diagonal_edge() {
        let mesh = Mesh {
            dim: 2,
            coords: vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
            node_names: vec!["N1".into(), "N2".into()],
            cells: vec![Cell {
                ty: CellType::SEG2,
                nodes: vec![NodeId(0), NodeId(1)],
            }],
            cell_names: vec!["M1".into()],
            ..Mesh::default()
        };
        // Uniaxial σxx = 1 on the edge of normal (1, −1)/√2: the normal
        // stress is ½, the shear ½ (along (1, 1)/√2).
        let mut sigma = NodalField::new(vec!["SIXX".into(), "SIYY".into(), "SIXY".into()]);
        for n in [NodeId(0), NodeId(1)] {
            sigma.set(n, "SIXX", 1.0);
            sigma.set(n, "SIYY", 0.0);
            sigma.set(n, "SIXY", 0.0);
        }
        let step = Step {
            nume_ordre: 1,
            inst: 1.0,
            fields: [("SIEF_NOEU".to_string(), Field::Nodal(sigma))].into(),
        };
        let f = pressure_field(&mesh, &[CellId(0)], &step, false).unwrap();
        let h = 0.5 / 2f64.sqrt();
        for n in [NodeId(0), NodeId(1)] {
            assert!((f.get(n, "PRES").unwrap() - 0.5).abs() < 1e-15);
            assert!((f.get(n, "CISA").unwrap() - 0.5).abs() < 1e-15);
            assert!((f.get(n, "VX").unwrap() - h).abs() < 1e-15);
            assert!((f.get(n, "VY").unwrap() - h).abs() < 1e-15);
        }
        // The deformed geometry needs DEPL.
        let err = pressure_field(&mesh, &[CellId(0)], &step, true)
            .unwrap_err()
            .message;
        assert!(err.contains("needs DEPL"), "{err}");
    }
}
