//! CREA_CHAMP's element fields at Gauss points (`TYPE_CHAM='ELGA_GEOM_R'`,
//! `'ELGA_DEPL_R'`, `'ELGA_NEUT_R'`, `'ELGA_NEUT_F'`), as code_aster 17
//! builds them (`op0195`, `chpchd`, `cnsces`, `caraff`, `chpass`,
//! `ceseva`, `cescel`), and the same points for `POST_ELEM/NORME`.
//!
//! The field lives on every cell of the `MODELE` whose element has the
//! option `TOU_INI_ELGA` for the quantity, at the points of its `RIGI`
//! family (aster-fem `elga`: continuum, skin and — in a 3D model — edge
//! elements), with the element's components: `GEOM_R` X Y (plane) or
//! X Y Z; `DEPL_R` DX DY on plane continuum cells, DX DY DZ elsewhere
//! (plane skin cells included, code_aster's `EGDEP3D`); `NEUT_R`/`NEUT_F`
//! X1…X30.
//!
//! - `OPERATION='DISC'` (a nodal field in `CHAM_GD`): at each point the
//!   cell's shape functions times its nodes' values, for each component
//!   every node of the cell carries (`cnsces` with `manopg`).
//! - `OPERATION='AFFE'`, `TYPE_CHAM='ELGA_NEUT_F'`: one function per
//!   component on the cells of each occurrence (later ones overwrite).
//! - `OPERATION='EVAL'` (`CHAM_F` of functions at Gauss points,
//!   `CHAM_PARA` `ELGA` fields): at each point each function of the point
//!   evaluated with the parameters' components there, by name (`ceseva`).
//! - `OPERATION='ASSE'` (`ELGA` fields in `ASSE/CHAM_GD` on `TOUT`,
//!   `GROUP_MA` or `MAILLE`, `NOM_CMP`, `NOM_CMP_RESU`, `COEF_R`, `CUMUL`):
//!   the first occurrence times its `COEF_R`, each next one added
//!   (`CUMUL='OUI'`) or overwriting where it has values (`chpass`,
//!   `chsfus`).
//!
//! `PROL_ZERO='OUI'`: a component of a cell's element the operation gave no
//! value is 0 (the zero function `&FOZERO` for `ELGA_NEUT_F`). Without it
//! code_aster fills such values with NaN (`cescel` with `'NAN'`) for a field
//! of reals, and stops for a field of functions: both are refused here
//! (a NaN is not a result).
//!
//! aster's 3D models carry no edge elements (AFFE_MODELE leaves segments
//! out), so their fields lack the points code_aster's `MECA_ARETE2/3` give
//! the segments of a 3D model: no norm counts them (they have no
//! `NORME_L2`), a `TEST_RESU/CHAM_ELEM` of such a cell would (an error:
//! the cell has no value) or a `TYPE_TEST` over the whole field (refused
//! at `TYPE_TEST` on a mesh with volumes and segments,
//! `commands::inspect`).
//!
//! Refused: cells of other modelisations (discrete, beams, shells) and the
//! under-integrated ones (`_SI`), other quantities and locations (`ELNO`,
//! `ELEM`, `CART`), `ASSE` from fields that are not `ELGA`.

use crate::concept::{GaussFunctionField, ModelDef, Modelisation};
use crate::executor::Executor;
use crate::field::{ElemField, ElemLocation, Field};
use crate::select;
use crate::support::Refusal;
use aster_eval::{CommandCall, ExecError, Keywords};
use aster_fem::elga::{self, CellRole, ElgaPoint};
use aster_mesh::{CellId, Mesh};
use aster_syntax::Span;
use std::collections::BTreeMap;
use std::rc::Rc;

/// The quantities of `ELGA` fields made here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Quantity {
    Geom,
    Depl,
    Neut,
}

/// The `TYPE_CHAM` values made here (CREA_CHAMP's static rules).
pub(crate) const ELGA_TYPES: &[&str] = &["ELGA_GEOM_R", "ELGA_DEPL_R", "ELGA_NEUT_R"];

impl Quantity {
    /// The quantity of an `ELGA_*` `TYPE_CHAM` (`ELGA_NEUT_F` is `Neut`).
    pub(crate) fn of_type(ty: &str) -> Option<Quantity> {
        match ty {
            "ELGA_GEOM_R" => Some(Quantity::Geom),
            "ELGA_DEPL_R" => Some(Quantity::Depl),
            "ELGA_NEUT_R" | "ELGA_NEUT_F" => Some(Quantity::Neut),
            _ => None,
        }
    }

    /// Every component of the quantity, in code_aster's catalog order.
    fn catalog(self) -> Vec<String> {
        match self {
            Quantity::Geom => ["X", "Y", "Z"].map(String::from).to_vec(),
            Quantity::Depl => ["DX", "DY", "DZ"].map(String::from).to_vec(),
            Quantity::Neut => (1..=30).map(|i| format!("X{i}")).collect(),
        }
    }

    /// Whether the element of a cell (its role in a plane or 3D model)
    /// carries the component (`TOU_INI_ELGA`'s located components).
    fn carries(self, comp: &str, role: CellRole, plane: bool) -> bool {
        match self {
            Quantity::Geom => comp != "Z" || !plane,
            Quantity::Depl => comp != "DZ" || !plane || role != CellRole::Continuum,
            Quantity::Neut => true,
        }
    }
}

/// One cell of a model's `ELGA` layout.
pub(crate) struct GaussCell {
    pub role: CellRole,
    pub points: Vec<ElgaPoint>,
}

/// The cells of a model that carry `ELGA` fields, with their points.
pub(crate) struct Layout {
    pub cells: BTreeMap<CellId, GaussCell>,
    /// A plane model (D_PLAN, C_PLAN, AXIS).
    pub plane: bool,
}

/// The `ELGA` layout of a model; what it cannot place is refused at `at`.
pub(crate) fn layout(
    ex: &Executor,
    model: &ModelDef,
    mesh: &Mesh,
    at: Span,
) -> Result<Layout, ExecError> {
    let mut cells = BTreeMap::new();
    let plane = model.dim() == 2;
    for (&cell, &m) in &model.cells {
        let axis = match m {
            Modelisation::PlaneStrain | Modelisation::PlaneStress | Modelisation::Solid3D => false,
            Modelisation::Axisymmetric => true,
            other => {
                return Err(ex.unsupported(
                    &format!("fields at Gauss points (ELGA) on a model with {other:?} cells: continuum models (D_PLAN, C_PLAN, AXIS, 3D) only"),
                    at,
                ))
            }
        };
        if model.reduced.contains(&cell) {
            return Err(ex.unsupported(
                "fields at Gauss points (ELGA) on under-integrated cells (MODELISATION '…_SI')",
                at,
            ));
        }
        let ty = mesh.cell(cell).ty;
        let Some(role) = CellRole::of(ty.dim() as usize, m.dim()) else {
            continue;
        };
        let family = elga::family(ty, role, axis).ok_or_else(|| {
            ex.unsupported(
                &format!(
                    "fields at Gauss points (ELGA) on cell {} ({}): no element family",
                    select::cell_name(mesh, cell),
                    ty.name()
                ),
                at,
            )
        })?;
        let points = elga::points(mesh, cell, &family, axis);
        cells.insert(cell, GaussCell { role, points });
    }
    Ok(Layout { cells, plane })
}

/// Values being built: per cell, per point, per component; `None` where
/// the operation gave nothing, NaN for a component the element does not
/// carry.
type Building = BTreeMap<CellId, Vec<Vec<Option<f64>>>>;

/// Turns values being built into the field: a value not given is 0 with
/// `PROL_ZERO='OUI'`, refused otherwise (code_aster's NaN).
fn settle(
    ex: &Executor,
    call: &CommandCall,
    components: Vec<String>,
    values: Building,
    mesh: &Mesh,
) -> Result<ElemField, ExecError> {
    let prol = prol_zero(&call.keywords);
    let mut out = ElemField::new(ElemLocation::Gauss, components.clone());
    for (cell, points) in values {
        let mut settled = Vec::with_capacity(points.len());
        for p in points {
            let mut row = Vec::with_capacity(p.len());
            for (c, v) in p.into_iter().enumerate() {
                match v {
                    Some(v) => row.push(v),
                    None if prol => row.push(0.0),
                    None => {
                        let kw = &call.keywords;
                        let span = written(kw, "PROL_ZERO")
                            .or(kw.keyword("TYPE_CHAM"))
                            .map(|k| k.span)
                            .unwrap_or(call.span);
                        return Err(ex.unsupported(
                            &format!(
                                "CREA_CHAMP: component {} of cell {} has no value, which code_aster fills with NaN without PROL_ZERO='OUI'",
                                components[c],
                                select::cell_name(mesh, cell)
                            ),
                            span,
                        ));
                    }
                }
            }
            settled.push(row);
        }
        out.insert(cell, settled);
    }
    Ok(out)
}

/// A keyword the user wrote (not a catalog default).
fn written<'k>(kw: &'k Keywords, name: &str) -> Option<&'k aster_eval::Keyword> {
    kw.keyword(name).filter(|k| !k.defaulted)
}

/// `PROL_ZERO='OUI'`.
fn prol_zero(kw: &Keywords) -> bool {
    kw.str("PROL_ZERO") == Some("OUI")
}

/// The quantity of the call's `TYPE_CHAM` (the static rules let only
/// [`ELGA_TYPES`] and `ELGA_NEUT_F` through).
fn quantity(ex: &Executor, call: &CommandCall) -> Result<Quantity, ExecError> {
    let kw = &call.keywords;
    let ty = kw.str("TYPE_CHAM").unwrap_or("");
    Quantity::of_type(ty).ok_or_else(|| {
        ex.unsupported(
            &format!("CREA_CHAMP with TYPE_CHAM='{ty}'"),
            kw.keyword("TYPE_CHAM").map(|k| k.span).unwrap_or(call.span),
        )
    })
}

/// The model (and its mesh and layout) of an `ELGA` CREA_CHAMP: `MODELE`
/// is required (code_aster's UTILITAI3_22).
fn model_layout(
    ex: &Executor,
    call: &CommandCall,
) -> Result<(Rc<ModelDef>, std::sync::Arc<Mesh>, Layout), ExecError> {
    let kw = &call.keywords;
    let model = ex.model(ex.required("CREA_CHAMP", kw, "MODELE")?)?;
    let mesh = ex.model_mesh(&model)?;
    let at = kw.keyword("MODELE").map(|k| k.span).unwrap_or(call.span);
    let layout = layout(ex, &model, &mesh, at)?;
    Ok((model, mesh, layout))
}

/// The components a new field stores: the quantity's catalog for GEOM and
/// DEPL (what the operation did not give is a hole), and for NEUT those
/// the operation gave (`present`), in catalog order.
fn stored_components(q: Quantity, present: &[String]) -> Vec<String> {
    let all = q.catalog();
    match q {
        Quantity::Neut => all.into_iter().filter(|c| present.contains(c)).collect(),
        _ => all,
    }
}

/// `OPERATION='DISC'` of a nodal field onto the model's Gauss points.
pub(crate) fn disc(ex: &Executor, call: &CommandCall) -> Result<ElemField, ExecError> {
    let kw = &call.keywords;
    let q = quantity(ex, call)?;
    let src = ex.field(ex.required("CREA_CHAMP", kw, "CHAM_GD")?)?;
    let Field::Nodal(src) = &*src else {
        return Err(ex.unsupported(
            "CREA_CHAMP/OPERATION='DISC' of an element field (a nodal field to Gauss points only)",
            kw.keyword("CHAM_GD").map(|k| k.span).unwrap_or(call.span),
        ));
    };
    let (_, mesh, layout) = model_layout(ex, call)?;
    let components = stored_components(q, src.components());
    let mut values = Building::new();
    for (&cell, gc) in &layout.cells {
        let nodes = &mesh.cell(cell).nodes;
        let mut per_point = vec![vec![None; components.len()]; gc.points.len()];
        for (ci, comp) in components.iter().enumerate() {
            if !q.carries(comp, gc.role, layout.plane) {
                per_point.iter_mut().for_each(|p| p[ci] = Some(f64::NAN));
                continue;
            }
            let nodal: Option<Vec<f64>> = nodes.iter().map(|&n| src.get(n, comp)).collect();
            let Some(nodal) = nodal else { continue };
            for (p, point) in gc.points.iter().enumerate() {
                per_point[p][ci] = Some(point.shape.iter().zip(&nodal).map(|(s, v)| s * v).sum());
            }
        }
        values.insert(cell, per_point);
    }
    settle(ex, call, components, values, &mesh)
}

/// `OPERATION='AFFE'`, `TYPE_CHAM='ELGA_NEUT_F'`: functions per component
/// on the cells of each occurrence, the zero function elsewhere.
pub(crate) fn affe_functions(
    ex: &Executor,
    call: &CommandCall,
) -> Result<GaussFunctionField, ExecError> {
    let kw = &call.keywords;
    let cmd = "CREA_CHAMP/AFFE";
    let (_, mesh, layout) = model_layout(ex, call)?;
    let mut given: BTreeMap<CellId, BTreeMap<String, Rc<crate::function::Function>>> =
        BTreeMap::new();
    let mut present = Vec::new();
    for occ in kw.factor("AFFE") {
        let (cmps, functions) = super::post::affe_functions(ex, cmd, occ)?;
        if let Some(bad) = cmps.iter().find(|c| !Quantity::Neut.catalog().contains(c)) {
            return Err(ex.kw_error(
                cmd,
                occ,
                "NOM_CMP",
                format!("{bad} is not a component of NEUT_F (X1 … X30)"),
            ));
        }
        let cells = select::cells(occ, &mesh, "").map_err(|e| ex.kw_error(cmd, occ, "AFFE", e))?;
        for c in &cmps {
            if !present.contains(c) {
                present.push(c.clone());
            }
        }
        for cell in cells {
            let slot = given.entry(cell).or_default();
            for (c, f) in cmps.iter().zip(&functions) {
                slot.insert(c.clone(), f.clone());
            }
        }
    }
    let components = stored_components(Quantity::Neut, &present);
    let mut out = GaussFunctionField {
        components: components.clone(),
        values: BTreeMap::new(),
    };
    for (&cell, gc) in &layout.cells {
        let at = given.get(&cell);
        let funcs = components
            .iter()
            .map(|c| at.and_then(|m| m.get(c)).cloned())
            .collect();
        out.values.insert(cell, (gc.points.len(), funcs));
    }
    Ok(out)
}

/// `OPERATION='EVAL'` of a field of functions at Gauss points.
pub(crate) fn eval(
    ex: &Executor,
    call: &CommandCall,
    functions: &GaussFunctionField,
) -> Result<ElemField, ExecError> {
    let kw = &call.keywords;
    let cmd = "CREA_CHAMP/EVAL";
    let mut params: Vec<Rc<Field>> = Vec::new();
    for s in kw.simple("CHAM_PARA") {
        let Some(c) = s.as_concept() else { continue };
        let f = ex.field(c)?;
        if !matches!(&*f, Field::Elem(e) if e.location == ElemLocation::Gauss) {
            // code_aster's MODELISA4_14: the parameters are discretised as
            // the functions.
            return Err(ex.kw_error(
                cmd,
                kw,
                "CHAM_PARA",
                "the parameter fields must be at Gauss points (ELGA) as CHAM_F is",
            ));
        }
        params.push(f);
    }
    let mut values = ElemField::new(ElemLocation::Gauss, functions.components.clone());
    for (&cell, (npts, funcs)) in &functions.values {
        let mut rows = Vec::with_capacity(*npts);
        for p in 0..*npts {
            let mut args: Vec<(&str, f64)> = Vec::new();
            for f in &params {
                let Field::Elem(e) = &**f else { continue };
                let Some(points) = e.cell(cell) else {
                    continue;
                };
                if points.len() != *npts {
                    return Err(ex.kw_error(
                        cmd,
                        kw,
                        "CHAM_PARA",
                        format!(
                            "cell {} has {} points in CHAM_PARA and {npts} in CHAM_F",
                            cell.0 + 1,
                            points.len()
                        ),
                    ));
                }
                for (name, &v) in e.components().iter().zip(&points[p]) {
                    if v.is_nan() {
                        continue;
                    }
                    if args.iter().any(|(n, _)| *n == name) {
                        // code_aster's CALCULEL2_78.
                        return Err(ex.kw_error(
                            cmd,
                            kw,
                            "CHAM_PARA",
                            format!("parameter {name} is given by two fields of CHAM_PARA"),
                        ));
                    }
                    args.push((name, v));
                }
            }
            let mut row = Vec::with_capacity(funcs.len());
            for f in funcs {
                row.push(match f {
                    None => 0.0,
                    Some(f) => f
                        .eval_named(&args)
                        .map_err(|e| ExecError::new(format!("{cmd}: {e}")))?,
                });
            }
            rows.push(row);
        }
        values.insert(cell, rows);
    }
    Ok(values)
}

/// `OPERATION='ASSE'` of `ELGA` fields onto the model's Gauss points.
pub(crate) fn asse(ex: &Executor, call: &CommandCall) -> Result<ElemField, ExecError> {
    let kw = &call.keywords;
    let cmd = "CREA_CHAMP/ASSE";
    let q = quantity(ex, call)?;
    let (_, mesh, layout) = model_layout(ex, call)?;
    // Per cell, per component, per point.
    let mut acc: BTreeMap<CellId, BTreeMap<String, Vec<Option<f64>>>> = BTreeMap::new();
    let mut first = true;
    for occ in kw.factor("ASSE") {
        let src = ex.field(ex.required(cmd, occ, "CHAM_GD")?)?;
        let src = match &*src {
            Field::Elem(e) if e.location == ElemLocation::Gauss => e,
            _ => {
                return Err(ex.unsupported(
                    "CREA_CHAMP/ASSE of a field that is not at Gauss points into an ELGA field",
                    occ.keyword("CHAM_GD").map(|k| k.span).unwrap_or(call.span),
                ))
            }
        };
        let cells = select::cells(occ, &mesh, "").map_err(|e| ex.kw_error(cmd, occ, "ASSE", e))?;
        if cells.is_empty() {
            continue;
        }
        let cmps: Vec<String> = occ
            .simple("NOM_CMP")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        if let Some(bad) = cmps.iter().find(|c| !src.components().contains(c)) {
            // code_aster's UTILITAI_43.
            return Err(ex.kw_error(
                cmd,
                occ,
                "NOM_CMP",
                format!(
                    "the field has no component {bad} (components: {})",
                    src.components().join(", ")
                ),
            ));
        }
        let renamed: Vec<String> = occ
            .simple("NOM_CMP_RESU")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        if !renamed.is_empty() && renamed.len() != cmps.len() {
            return Err(ex.kw_error(
                cmd,
                occ,
                "NOM_CMP_RESU",
                format!(
                    "{} names for the {} components of NOM_CMP: give one per component",
                    renamed.len(),
                    cmps.len()
                ),
            ));
        }
        let coef = occ.f64("COEF_R").unwrap_or(1.0);
        let cumul = occ.str("CUMUL") == Some("OUI");
        let taken: Vec<(usize, String)> = src
            .components()
            .iter()
            .enumerate()
            .filter_map(|(i, c)| {
                if cmps.is_empty() {
                    return Some((i, c.clone()));
                }
                let k = cmps.iter().position(|x| x == c)?;
                Some((i, renamed.get(k).cloned().unwrap_or_else(|| c.clone())))
            })
            .collect();
        for cell in cells {
            let Some(points) = src.cell(cell) else {
                continue;
            };
            let slot = acc.entry(cell).or_default();
            for (i, target) in &taken {
                let column = slot
                    .entry(target.clone())
                    .or_insert_with(|| vec![None; points.len()]);
                if column.len() != points.len() {
                    return Err(ex.kw_error(
                        cmd,
                        occ,
                        "CHAM_GD",
                        format!(
                            "cell {} has {} points here and {} in an earlier occurrence",
                            select::cell_name(&mesh, cell),
                            points.len(),
                            column.len()
                        ),
                    ));
                }
                for (p, row) in points.iter().enumerate() {
                    let v = row[*i];
                    if v.is_nan() {
                        continue;
                    }
                    column[p] = Some(match column[p] {
                        Some(old) if cumul && !first => old + coef * v,
                        _ => coef * v,
                    });
                }
            }
        }
        first = false;
    }
    let present: Vec<String> = acc
        .values()
        .flat_map(|m| m.keys().cloned())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let components = stored_components(q, &present);
    let mut values = Building::new();
    for (&cell, gc) in &layout.cells {
        let n = gc.points.len();
        let at = acc.get(&cell);
        let mut rows = vec![vec![None; components.len()]; n];
        for (ci, comp) in components.iter().enumerate() {
            if !q.carries(comp, gc.role, layout.plane) {
                rows.iter_mut().for_each(|r| r[ci] = Some(f64::NAN));
                continue;
            }
            let Some(column) = at.and_then(|m| m.get(comp)) else {
                continue;
            };
            if column.len() != n {
                // code_aster's CALCULEL_57.
                return Err(ExecError::new(format!(
                    "{cmd}: cell {} has {} Gauss points in the model and {} in the assembled fields",
                    select::cell_name(&mesh, cell),
                    n,
                    column.len()
                )));
            }
            for (r, v) in rows.iter_mut().zip(column) {
                r[ci] = *v;
            }
        }
        values.insert(cell, rows);
    }
    settle(ex, call, components, values, &mesh)
}

/// The nodal field `src` at the Gauss points of `cells` of a layout (the
/// components every node of a cell carries; 0 elsewhere): `POST_ELEM/NORME`
/// of a nodal field (code_aster's `chpchd` onto `NORME_L2` with
/// `PROL_ZERO='OUI'`). Per cell, per point, per component of `src`.
pub(crate) fn nodal_at_points(
    src: &crate::field::NodalField,
    mesh: &Mesh,
    layout: &Layout,
    cells: &[CellId],
) -> BTreeMap<CellId, Vec<Vec<f64>>> {
    let mut out = BTreeMap::new();
    for cell in cells {
        let Some(gc) = layout.cells.get(cell) else {
            continue;
        };
        let nodes = &mesh.cell(*cell).nodes;
        let mut rows = vec![vec![0.0; src.components().len()]; gc.points.len()];
        for (ci, comp) in src.components().iter().enumerate() {
            let nodal: Option<Vec<f64>> = nodes.iter().map(|&n| src.get(n, comp)).collect();
            let Some(nodal) = nodal else { continue };
            for (row, point) in rows.iter_mut().zip(&gc.points) {
                row[ci] = point.shape.iter().zip(&nodal).map(|(s, v)| s * v).sum();
            }
        }
        out.insert(*cell, rows);
    }
    out
}

/// CREA_CHAMP's static rules for element fields: which `OPERATION` and
/// `TYPE_CHAM` go together here (`crate::support`).
pub(crate) fn rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    let op = kw.str("OPERATION").unwrap_or("");
    let ty = kw.str("TYPE_CHAM").unwrap_or("");
    let el = ty.starts_with("EL");
    let made = ELGA_TYPES.contains(&ty);
    let mut refuse = |why: &str| {
        out.push(Refusal::at(
            format!("CREA_CHAMP/OPERATION='{op}' with TYPE_CHAM='{ty}' ({why})"),
            kw,
            "TYPE_CHAM",
            call.span,
        ))
    };
    match op {
        "DISC" if !made => {
            refuse("a nodal field onto Gauss points only: ELGA_GEOM_R, ELGA_DEPL_R, ELGA_NEUT_R")
        }
        "AFFE" if el && ty != "ELGA_NEUT_F" => {
            refuse("element fields: ELGA_NEUT_F (functions at Gauss points) only")
        }
        "EVAL" if el && ty != "ELGA_NEUT_R" => {
            refuse("element fields: ELGA_NEUT_R from ELGA_NEUT_F only")
        }
        "ASSE" if el && !made => {
            refuse("element fields: ELGA_GEOM_R, ELGA_DEPL_R, ELGA_NEUT_R only")
        }
        "COMB" | "NORMALE" if el => refuse("nodal fields only"),
        _ => {}
    }
    if op == "AFFE" && ty == "ELGA_NEUT_F" && !prol_zero(kw) {
        out.push(Refusal {
            what: "CREA_CHAMP/TYPE_CHAM='ELGA_NEUT_F' without PROL_ZERO='OUI' (code_aster stops on the components X1…X30 and the cells no occurrence gives a function)".into(),
            span: written(kw, "PROL_ZERO")
                .or(kw.keyword("TYPE_CHAM"))
                .map(|k| k.span)
                .unwrap_or(call.span),
        });
    }
    if el && matches!(op, "AFFE" | "ASSE") {
        for occ in kw.factor(op) {
            for name in ["GROUP_NO", "NOEUD"] {
                if occ.contains(name) {
                    out.push(Refusal::at(
                        format!("CREA_CHAMP/{op}/{name} for an element field (cells only: TOUT, GROUP_MA, MAILLE)"),
                        occ,
                        name,
                        call.span,
                    ));
                }
            }
        }
    }
}
