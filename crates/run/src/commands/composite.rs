//! `DEFI_COMPOSITE`: a stack of `ELAS_ORTH` plies (`COUCHE`: `EPAIS`,
//! `MATER`, `ORIENTATION`), homogenised as code_aster's `op0056` does
//! ([`aster_fem::laminate`]) into a material that `AFFE_MATERIAU` gives to
//! the plate cells (`DKT`, `DST`, `Q4G`). `IMPRESSION` (the homogenised
//! coefficients written to a file) is accepted and writes nothing.
//! Refused, located: a ply material other than `ELAS_ORTH` (code_aster
//! accepts nothing else either, `MODELISA8_71`), `THER_ORTH` plies (the
//! thermal composite), and `RHO` given for some plies only.

use crate::concept::{Concept, Material};
use crate::executor::{store_result, Executor};
use crate::support::Support;
use aster_eval::{CommandCall, CommandOutput, ExecError};
use aster_fem::laminate::{Laminate, Ply};
use std::rc::Rc;

/// What DEFI_COMPOSITE reads (`crate::support`).
pub(crate) const DEFI_COMPOSITE: Support = Support::keywords(&[
    "COUCHE",
    "COUCHE/EPAIS",
    "COUCHE/MATER",
    "COUCHE/ORIENTATION",
    "IMPRESSION",
    "IMPRESSION/UNITE",
]);

pub fn defi_composite(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let at = "DEFI_COMPOSITE/COUCHE";
    let mut plies = Vec::new();
    for occ in kw.factor("COUCHE") {
        let thickness = occ
            .f64("EPAIS")
            .ok_or_else(|| ex.kw_error(at, occ, "EPAIS", "EPAIS is required"))?;
        let mat = ex.required(at, occ, "MATER")?;
        let name = mat.name.clone();
        let mat = ex.material(mat)?;
        let Some(o) = mat.orthotropic else {
            return Err(ex.kw_error(
                at,
                occ,
                "MATER",
                format!(
                    "the material `{name}` of a layer must be defined by ELAS_ORTH (code_aster's MODELISA8_71)"
                ),
            ));
        };
        if mat.thermal.is_some() || mat.thermal_nl.is_some() {
            let span = occ.keyword("MATER").map(|k| k.span).unwrap_or(call.span);
            return Err(ex.unsupported(
                &format!("DEFI_COMPOSITE with the thermal properties of `{name}` (THER_ORTH: the thermal composite)"),
                span,
            ));
        }
        let given = |v: f64| v.is_finite().then_some(v);
        plies.push(Ply {
            thickness,
            orientation: occ.f64("ORIENTATION").unwrap_or(0.0),
            e_l: o.e_l,
            e_t: o.e_t,
            nu_lt: o.nu_lt,
            g_lt: o.g_lt,
            g_ln: given(o.g_ln),
            g_tn: given(o.g_tn),
            rho: mat.density,
        });
    }
    let laminate = Laminate::new(&plies).map_err(|e| {
        let span = kw.keyword("COUCHE").map(|k| k.span).unwrap_or(call.span);
        match ex.location(span) {
            Some(loc) => ExecError::new(format!("DEFI_COMPOSITE: {e} ({loc})")),
            None => ExecError::new(format!("DEFI_COMPOSITE: {e}")),
        }
    })?;
    let m = Material {
        elastic: true,
        density: laminate.density,
        composite: Some(std::sync::Arc::new(laminate)),
        ..super::define::without_elas(None)
    };
    store_result(ex, call, Concept::Material(Rc::new(m)))
}

/// The material and section of plate cell `cell` when its material is a
/// `DEFI_COMPOSITE` (`None` otherwise): the stack's matrices in the
/// facet's frame, from the reference direction of its `AFFE_CARA_ELEM/COQUE`
/// (code_aster's `dxmate`). Refused: a stack whose membrane and bending are
/// coupled (not symmetric about its mid-surface: code_aster's `coupmf`
/// terms are not reproduced) and a `COQUE_NCOU` other than the number of
/// plies (code_aster's stresses are by ply).
pub(crate) fn layered(
    mesh: &aster_mesh::Mesh,
    cell: aster_mesh::CellId,
    materials: &crate::concept::MaterialField,
    cara: Option<&crate::concept::CaraElem>,
    section: &aster_fem::ShellSection,
) -> Result<Option<(aster_fem::Elastic, aster_fem::ShellSection)>, ExecError> {
    let Some(laminate) = materials.cells.get(&cell).and_then(|m| m.composite.clone()) else {
        return Ok(None);
    };
    let name = crate::select::cell_name(mesh, cell);
    if !laminate.is_uncoupled() {
        return Err(ExecError::new(format!(
            "not supported yet: the DEFI_COMPOSITE of cell {name} couples membrane and bending (its plies are not symmetric about the mid-surface): code_aster's coupling terms (dxmate's coupmf) are not reproduced"
        )));
    }
    let occ = cara.and_then(|c| c.shells.iter().rev().find(|s| s.cells.contains(&cell)));
    let (direction, layers) = occ
        .map(|s| (s.direction, s.layers))
        .unwrap_or(([1., 0., 0.], 1));
    if layers as usize != laminate.layers.len() {
        return Err(ExecError::new(format!(
            "cell {name}: AFFE_CARA_ELEM/COQUE/COQUE_NCOU = {layers} but its DEFI_COMPOSITE has {} layers: give COQUE_NCOU equal to the number of layers (the stresses are by layer)",
            laminate.layers.len()
        )));
    }
    let c = mesh.cell(cell);
    let xyz: Vec<[f64; 3]> = c.nodes.iter().map(|&n| mesh.coord(n)).collect();
    let section = aster_fem::plate::layered_section(&xyz, section, laminate, direction)
        .map_err(|e| ExecError::new(format!("cell {name}: {e}")))?;
    // The elements read the stack's matrices only; the isotropic constants
    // are placeholders.
    let material = aster_fem::Elastic {
        e: f64::NAN,
        nu: f64::NAN,
        orthotropic: None,
    };
    Ok(Some((material, section)))
}
