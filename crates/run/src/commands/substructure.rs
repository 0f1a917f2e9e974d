//! Static substructuring: `MACR_ELEM_STAT`, `DEFI_MAILLAGE`,
//! `ASSE_MAILLAGE(OPERATION='SOUS_STR')`, `AFFE_MODELE/AFFE_SOUS_STRUC`
//! and `STAT_NON_LINE/SOUS_STRUC`.
//!
//! code_aster condenses a macro element on its exterior nodes (a Schur
//! complement of its linear elastic stiffness with the `CHAR_MACR_ELEM`
//! Dirichlet conditions held inside, and per `CAS_CHARGE` the load that
//! the case's loads give on the exterior with the exterior fixed), then
//! solves the assembled problem. aster does not condense: when the macro
//! element is defined on the mesh the super mesh is assembled onto
//! (`MAILLAGE_1`) and its exterior nodes are those nodes (`DEFI_NOEUD`
//! names them as `MAILLAGE_1` does), it keeps the macro element's cells,
//! linear elastic with the macro element's materials, in the solved model,
//! its `CHAR_MACR_ELEM` conditions held, and each `SOUS_STRUC` load case
//! applied with its `FONC_MULT`. Static condensation is exact: the
//! equations on the exterior nodes are the same, so is the answer, to
//! round-off. What differs is only what a result holds: the interior
//! nodes' displacements, which code_aster does not compute.

use crate::concept::{
    Concept, LoadCase, MacroElement, MaterialField, ModelDef, SuperCell, SuperMesh,
};
use crate::executor::{result_of, store_result, Executor};
use crate::function::Function;
use crate::solve::{BehaviourOcc, Excitation, LoadRef, Relation};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use std::rc::Rc;
use std::sync::Arc;

/// What MACR_ELEM_STAT reads (`crate::support`).
pub(crate) const MACR_ELEM_STAT: Support = Support::keywords(&[
    "DEFINITION",
    "DEFINITION/MODELE",
    "DEFINITION/CHAM_MATER",
    "DEFINITION/CHAR_MACR_ELEM",
    "EXTERIEUR",
    "EXTERIEUR/GROUP_NO",
    "EXTERIEUR/NOEUD",
    "RIGI_MECA",
    "CAS_CHARGE",
    "CAS_CHARGE/NOM_CAS",
    "CAS_CHARGE/SUIV",
    "CAS_CHARGE/CHARGE",
]);

/// What DEFI_MAILLAGE reads (`crate::support`).
pub(crate) const DEFI_MAILLAGE: Support = Support::keywords(&[
    "DEFI_SUPER_MAILLE",
    "DEFI_SUPER_MAILLE/MACR_ELEM",
    "DEFI_SUPER_MAILLE/SUPER_MAILLE",
    "DEFI_NOEUD",
    "DEFI_NOEUD/TOUT",
    "DEFI_NOEUD/PREFIXE",
    "DEFI_NOEUD/INDEX",
]);

/// The values of `ASSE_MAILLAGE/OPERATION` (`crate::commands::mesh`).
pub(crate) const ASSE_OPERATIONS: Values = Values::new("OPERATION", &["SUPERPOSE", "SOUS_STR"]);

fn loads_of(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    name: &str,
) -> Result<Vec<LoadRef>, ExecError> {
    kw.simple(name)
        .iter()
        .filter_map(|s| s.as_concept())
        .map(|c| crate::solve::load_ref(ex, &format!("{cmd}/{name}"), c))
        .collect()
}

pub fn macr_elem_stat(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    const CMD: &str = "MACR_ELEM_STAT";
    let kw = &call.keywords;
    let Some(def) = kw.factor("DEFINITION").first() else {
        return Err(ExecError::new(format!(
            "{CMD}: DEFINITION is required (continuing a macro element with MACR_ELEM is not supported)"
        )));
    };
    let model = ex.model(ex.required(&format!("{CMD}/DEFINITION"), def, "MODELE")?)?;
    let materials =
        ex.material_field(ex.required(&format!("{CMD}/DEFINITION"), def, "CHAM_MATER")?)?;
    // code_aster condenses the thermal strains of the material field's
    // AFFE_VARC into the load cases (zzzz104a: the macro element's half of
    // a heated beam); here a load case holds its CHARGE only.
    if let Some(t) = &materials.temperature {
        if model.cells.keys().any(|c| t.cells.contains(c)) {
            return Err(ex.kw_error(
                CMD,
                def,
                "CHAM_MATER",
                "not supported yet: a macro element whose CHAM_MATER gives its cells a temperature (AFFE_VARC): the thermal strains condensed into its load cases are not computed",
            ));
        }
    }
    let dirichlet = loads_of(ex, CMD, def, "CHAR_MACR_ELEM")?;
    let mesh = ex.mesh_by_id(model.mesh)?;
    let mut exterior = Vec::new();
    for occ in kw.factor("EXTERIEUR") {
        let nodes = crate::select::nodes(occ, &mesh, "")
            .map_err(|e| ExecError::new(format!("{CMD}/EXTERIEUR: {e}")))?;
        for n in nodes {
            if !exterior.contains(&n) {
                exterior.push(n);
            }
        }
    }
    if exterior.is_empty() {
        return Err(ExecError::new(format!(
            "{CMD}: EXTERIEUR names no node: a macro element is joined to the rest of the model by its exterior nodes"
        )));
    }
    let mut cases = Vec::new();
    for occ in kw.factor("CAS_CHARGE") {
        let name = occ.str("NOM_CAS").unwrap_or_default().to_string();
        if cases.iter().any(|c: &LoadCase| c.name == name) {
            return Err(ex.kw_error(
                CMD,
                occ,
                "NOM_CAS",
                format!("two load cases are named '{name}'"),
            ));
        }
        let loads = loads_of(ex, CMD, occ, "CHARGE")?;
        cases.push(LoadCase { name, loads });
    }
    let m = MacroElement {
        model,
        materials,
        dirichlet,
        exterior,
        cases,
    };
    store_result(ex, call, Concept::MacroElement(Rc::new(m)))
}

/// The name `DEFI_NOEUD(TOUT='OUI', INDEX=(i1, i2, i3, i4), PREFIXE)`
/// gives an exterior node of a super cell: the prefix, characters i1 to
/// i2 of the super cell's name, then characters i3 to i4 of the node's
/// (an empty range when the end is before the start), as code_aster's
/// `ssdmdn`.
fn indexed_name(prefix: &str, cell: &str, node: &str, index: [i64; 4]) -> String {
    let part = |s: &str, a: i64, b: i64| -> String {
        if b < a || a < 1 {
            return String::new();
        }
        s.chars()
            .skip((a - 1) as usize)
            .take((b - a + 1) as usize)
            .collect()
    };
    format!(
        "{prefix}{}{}",
        part(cell, index[0], index[1]),
        part(node, index[2], index[3])
    )
}

pub fn defi_maillage(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    const CMD: &str = "DEFI_MAILLAGE";
    let kw = &call.keywords;
    let mut cells: Vec<SuperCell> = Vec::new();
    for occ in kw.factor("DEFI_SUPER_MAILLE") {
        let macros: Vec<&aster_eval::ConceptRef> = occ
            .simple("MACR_ELEM")
            .iter()
            .filter_map(|s| s.as_concept())
            .collect();
        let names: Vec<String> = occ
            .simple("SUPER_MAILLE")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        if !names.is_empty() && names.len() != macros.len() {
            return Err(ex.kw_error(
                CMD,
                occ,
                "SUPER_MAILLE",
                format!(
                    "{} names for {} macro elements: give one name per MACR_ELEM",
                    names.len(),
                    macros.len()
                ),
            ));
        }
        for (i, c) in macros.iter().enumerate() {
            let macro_elem = ex.macro_element(c)?;
            // code_aster's default super cell name is the macro element's.
            let name = names.get(i).cloned().unwrap_or_else(|| c.name.clone());
            cells.push(SuperCell {
                name,
                macro_elem,
                node_names: Vec::new(),
            });
        }
    }
    let Some(defi) = kw.factor("DEFI_NOEUD").first() else {
        return Err(ExecError::new(format!(
            "{CMD}: give DEFI_NOEUD(TOUT='OUI', INDEX=…): aster names the exterior nodes of the super cells only so"
        )));
    };
    if defi.str("TOUT") != Some("OUI") {
        return Err(ex.kw_error(
            CMD,
            defi,
            "NOEUD_INIT",
            "not supported yet: DEFI_NOEUD by NOEUD_INIT (give TOUT='OUI' with INDEX)",
        ));
    }
    let index: Vec<i64> = defi
        .simple("INDEX")
        .iter()
        .filter_map(|s| s.as_i64())
        .collect();
    let [a, b, c, d] = index.as_slice() else {
        return Err(ex.kw_error(
            CMD,
            defi,
            "INDEX",
            format!("INDEX takes four integers (i1, i2 of the super cell's name, i3, i4 of the node's), got {}", index.len()),
        ));
    };
    let prefix = defi.str("PREFIXE").unwrap_or("");
    for cell in &mut cells {
        let mesh = ex.mesh_by_id(cell.macro_elem.model.mesh)?;
        cell.node_names = cell
            .macro_elem
            .exterior
            .iter()
            .map(|&n| indexed_name(prefix, &cell.name, &mesh.node_name(n), [*a, *b, *c, *d]))
            .collect();
    }
    store_result(ex, call, Concept::SuperMesh(Rc::new(SuperMesh { cells })))
}

/// `ASSE_MAILLAGE(OPERATION='SOUS_STR')`: `MAILLAGE_1` with the super
/// cells of `MAILLAGE_2` (a DEFI_MAILLAGE), whose nodes are `MAILLAGE_1`'s
/// nodes of the same name (code_aster's `asmael` merges them so).
pub fn asse_sous_str(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    const CMD: &str = "ASSE_MAILLAGE";
    let kw = &call.keywords;
    let base_ref = ex.required(CMD, kw, "MAILLAGE_1")?;
    let base_id = base_ref.id;
    let base = ex.mesh(base_ref)?;
    let super_ref = ex.required(CMD, kw, "MAILLAGE_2")?;
    let supers = ex.super_mesh(super_ref)?;
    for cell in &supers.cells {
        let own = cell.macro_elem.model.mesh;
        for (&n, name) in cell.macro_elem.exterior.iter().zip(&cell.node_names) {
            let found = crate::select::node_named(&base, name).ok();
            if own != base_id || found != Some(n) {
                return Err(ex.unsupported(
                    &format!(
                        "ASSE_MAILLAGE/OPERATION='SOUS_STR' with a super cell ({}) whose exterior node {name} is not the node of that name of MAILLAGE_1 (aster solves a macro element with the cells it was defined on: it must be defined on MAILLAGE_1 and DEFI_NOEUD must keep its nodes' names)",
                        cell.name
                    ),
                    kw.keyword("MAILLAGE_2").map(|k| k.span).unwrap_or(call.span),
                ));
            }
        }
    }
    let id = result_of(call)?.id;
    ex.substructured.insert(id, supers);
    store_result(ex, call, Concept::Mesh(Arc::new((*base).clone())))
}

/// `AFFE_MODELE/AFFE_SOUS_STRUC`: the super cells of the model's mesh it
/// names (`SUPER_MAILLE`, or `TOUT`).
pub(crate) fn affe_sous_struc(
    ex: &Executor,
    call: &CommandCall,
    mesh: u32,
) -> Result<Vec<SuperCell>, ExecError> {
    let Some(occ) = call.keywords.factor("AFFE_SOUS_STRUC").first() else {
        return Ok(Vec::new());
    };
    let Some(s) = ex.substructured.get(&mesh) else {
        return Err(ex.kw_error(
            "AFFE_MODELE",
            occ,
            "SUPER_MAILLE",
            "the mesh has no super cell: assemble it with ASSE_MAILLAGE(OPERATION='SOUS_STR')",
        ));
    };
    pick_super_cells(ex, "AFFE_MODELE/AFFE_SOUS_STRUC", occ, &s.cells)
        .map(|cells| cells.into_iter().cloned().collect())
}

/// The super cells an occurrence designates (`TOUT='OUI'` or
/// `SUPER_MAILLE`), an unknown name an error.
fn pick_super_cells<'c>(
    ex: &Executor,
    at: &str,
    occ: &Keywords,
    cells: &'c [SuperCell],
) -> Result<Vec<&'c SuperCell>, ExecError> {
    if occ.str("TOUT") == Some("OUI") {
        return Ok(cells.iter().collect());
    }
    let mut out = Vec::new();
    for name in occ.simple("SUPER_MAILLE").iter().filter_map(|s| s.as_str()) {
        let Some(c) = cells.iter().find(|c| c.name == name) else {
            let known: Vec<&str> = cells.iter().map(|c| c.name.as_str()).collect();
            return Err(ex.kw_error(
                at,
                occ,
                "SUPER_MAILLE",
                format!("no super cell '{name}' (there are: {})", known.join(", ")),
            ));
        };
        out.push(c);
    }
    Ok(out)
}

/// A solve's model, materials and loads with its super cells expanded:
/// each macro element's cells join the model with the macro element's
/// materials, its `CHAR_MACR_ELEM` conditions and the load cases of
/// `SOUS_STRUC` (with their `FONC_MULT`) join the loads. A model without
/// super cells comes back as it is. `behaviours` must leave the macro
/// elements' cells linear elastic under small strains (a macro element
/// is linear).
pub(crate) fn expand(
    ex: &Executor,
    call: &CommandCall,
    model: Rc<ModelDef>,
    materials: Rc<MaterialField>,
    excitations: &mut Vec<Excitation>,
) -> Result<(Rc<ModelDef>, Rc<MaterialField>), ExecError> {
    let cmd = call.command.as_str();
    let kw = &call.keywords;
    if model.substructures.is_empty() {
        if let Some(occ) = kw.factor("SOUS_STRUC").first() {
            return Err(ex.kw_error(
                cmd,
                occ,
                "CAS_CHARGE",
                "the model has no super cell (AFFE_MODELE/AFFE_SOUS_STRUC)",
            ));
        }
        return Ok((model, materials));
    }
    if cmd != "STAT_NON_LINE" {
        return Err(ex.unsupported(
            &format!("{cmd} on a model with super cells (AFFE_MODELE/AFFE_SOUS_STRUC): STAT_NON_LINE only"),
            call.span,
        ));
    }
    let mut m = (*model).clone();
    let mut mat = (*materials).clone();
    m.substructures.clear();
    // ASSE_MAILLAGE checked every macro element is defined on the mesh the
    // super mesh was assembled onto, with its node names: its cells are
    // the model's mesh's.
    for s in &model.substructures {
        for (&c, &md) in &s.macro_elem.model.cells {
            if m.cells.insert(c, md).is_some() {
                let mesh = ex.mesh_by_id(model.mesh)?;
                return Err(ExecError::new(format!(
                    "{cmd}: cell {} is both in the model and in the macro element of super cell {}",
                    crate::select::cell_name(&mesh, c),
                    s.name
                )));
            }
            if s.macro_elem.model.reduced.contains(&c) {
                m.reduced.insert(c);
            }
            if s.macro_elem.model.mixed.contains(&c) {
                m.mixed.insert(c);
            }
            if let Some(x) = s.macro_elem.materials.cells.get(&c) {
                mat.cells.insert(c, x.clone());
            }
        }
        for (r, &own) in m.rotations.iter_mut().zip(&s.macro_elem.model.rotations) {
            *r |= own;
        }
    }
    // The load cases asked, per super cell.
    let mut used: Vec<(String, Vec<LoadRef>)> = Vec::new();
    for occ in kw.factor("SOUS_STRUC") {
        let at = format!("{cmd}/SOUS_STRUC");
        let case = occ.str("CAS_CHARGE").unwrap_or_default();
        let multiplier = match occ.concept("FONC_MULT") {
            Some(f) => Some(ex.function(f)?),
            None => None,
        };
        for s in pick_super_cells(ex, &at, occ, &model.substructures)? {
            let Some(lc) = s.macro_elem.cases.iter().find(|c| c.name == case) else {
                let known: Vec<&str> = s.macro_elem.cases.iter().map(|c| c.name.as_str()).collect();
                return Err(ex.kw_error(
                    &at,
                    occ,
                    "CAS_CHARGE",
                    format!(
                        "the macro element of super cell {} has no load case '{case}' (it has: {})",
                        s.name,
                        known.join(", ")
                    ),
                ));
            };
            for l in &lc.loads {
                excitations.push(Excitation {
                    load: l.clone(),
                    multiplier: multiplier.clone(),
                    kind: Default::default(),
                });
            }
            used.push((s.name.clone(), lc.loads.clone()));
        }
    }
    // Each macro element's Dirichlet conditions hold inside it: a
    // CHAR_MACR_ELEM load that no applied case carries is imposed with
    // its values times zero (the interior held where it was condensed).
    let zero = Rc::new(Function::Constant {
        parameter: "INST".into(),
        value: 0.0,
    });
    for s in &model.substructures {
        let cases: Vec<&LoadRef> = used
            .iter()
            .filter(|(n, _)| *n == s.name)
            .flat_map(|(_, l)| l.iter())
            .collect();
        for d in &s.macro_elem.dirichlet {
            if !cases.iter().any(|l| same_load(l, d)) {
                excitations.push(Excitation {
                    load: d.clone(),
                    multiplier: Some(zero.clone()),
                    kind: Default::default(),
                });
            }
        }
    }
    Ok((Rc::new(m), Rc::new(mat)))
}

fn same_load(a: &LoadRef, b: &LoadRef) -> bool {
    match (a, b) {
        (LoadRef::Kinematic(x), LoadRef::Kinematic(y)) => Rc::ptr_eq(x, y),
        (LoadRef::Mechanical(x), LoadRef::Mechanical(y)) => Rc::ptr_eq(x, y),
        _ => false,
    }
}

/// A macro element is linear elastic: a `COMPORTEMENT` occurrence other
/// than `ELAS` under `PETIT` reaching one of its cells is refused (code_aster
/// applies no behaviour to a super cell).
pub(crate) fn check_behaviours(
    ex: &Executor,
    call: &CommandCall,
    model: &ModelDef,
    behaviours: &[BehaviourOcc],
) -> Result<(), ExecError> {
    for s in &model.substructures {
        for (b, occ) in behaviours.iter().zip(call.keywords.factor("COMPORTEMENT")) {
            if b.relation == Relation::Elas && b.kinematics == aster_fem::Kinematics::Small {
                continue;
            }
            let reaches = match &b.cells {
                None => true,
                Some(cells) => cells
                    .iter()
                    .any(|c| s.macro_elem.model.cells.contains_key(c)),
            };
            if reaches {
                return Err(ex.unsupported(
                    &format!(
                        "{}/COMPORTEMENT other than ELAS under PETIT on the cells of the macro element of super cell {} (a macro element is linear elastic: give the behaviour on the model's own cells, by GROUP_MA)",
                        call.command, s.name
                    ),
                    occ.entries.first().map(|k| k.span).unwrap_or(call.span),
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::indexed_name;

    #[test]
    fn defi_noeud_index_takes_character_ranges() {
        // ssnv193a's INDEX=(1, 0, 1, 8): the node's own name.
        assert_eq!(indexed_name("", "MAILLE1", "N12", [1, 0, 1, 8]), "N12");
        // Two characters of the super cell's name, then the node's.
        assert_eq!(indexed_name("", "S1", "N12", [1, 2, 1, 8]), "S1N12");
        assert_eq!(indexed_name("P", "ABC", "N12345", [2, 3, 2, 4]), "PBC123");
    }
}
