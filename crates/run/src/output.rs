//! IMPR_RESU: writing meshes and results through the mesh crate's writers
//! (MED 4.1, ASTER `.mail`), into `--out` (`fort.<UNITE>` unless the
//! `.export` names the unit's file).

use crate::concept::{EvolResult, Step};
use crate::executor::Executor;
use crate::field::{ElemLocation, Field};
use crate::support::{Refusal, Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_mesh::{FieldLocation, Mesh, ResultStep};
use std::sync::Arc;

/// A stored field in the writer's form (every node / cell of the mesh;
/// entities the field does not cover get 0).
pub(crate) fn to_mesh_field(name: &str, field: &Field, mesh: &Mesh) -> aster_mesh::Field {
    match field {
        Field::Nodal(f) => {
            let nc = f.components().len();
            let mut values = vec![0.0; mesh.node_count() * nc];
            for (n, vals) in f.iter() {
                for (c, v) in vals.iter().enumerate() {
                    values[n.0 as usize * nc + c] = v.unwrap_or(0.0);
                }
            }
            aster_mesh::Field {
                name: name.to_string(),
                components: f.components().to_vec(),
                location: FieldLocation::Nodes,
                values,
            }
        }
        Field::Elem(f) => {
            let nc = f.components().len();
            let clean = |v: f64| if v.is_finite() { v } else { 0.0 };
            match f.location {
                ElemLocation::Cell => {
                    let mut values = vec![0.0; mesh.cells.len() * nc];
                    for (c, pts) in f.iter() {
                        if let Some(p) = pts.get(0) {
                            for (k, v) in p.iter().enumerate() {
                                values[c.0 as usize * nc + k] = clean(*v);
                            }
                        }
                    }
                    aster_mesh::Field {
                        name: name.to_string(),
                        components: f.components().to_vec(),
                        location: FieldLocation::Cells,
                        values,
                    }
                }
                ElemLocation::Gauss | ElemLocation::Nodes => {
                    let mut points = vec![0u32; mesh.cells.len()];
                    let mut values = Vec::new();
                    for (i, slot) in points.iter_mut().enumerate() {
                        if let Some(pts) = f.cell(aster_mesh::CellId(i as u32)) {
                            *slot = pts.len() as u32;
                            values.extend(pts.flat().iter().map(|v| clean(*v)));
                        }
                    }
                    aster_mesh::Field {
                        name: name.to_string(),
                        components: f.components().to_vec(),
                        location: FieldLocation::GaussPoints {
                            points_per_cell: points,
                        },
                        values,
                    }
                }
            }
        }
    }
}

/// A selected step and its selected fields, by name.
type StepFields<'r> = (&'r Step, Vec<(&'r str, &'r Field)>);

/// The steps an IMPR_RESU `RESU` occurrence selects (`NUME_ORDRE`/`INST`/…)
/// with, for each, its fields named in `NOM_CHAM` (all fields without it).
/// The MED, RESULTAT and GMSH writers all print this selection.
fn selected_fields<'r>(
    ex: &Executor,
    occ: &Keywords,
    result: &'r EvolResult,
) -> Result<Vec<StepFields<'r>>, ExecError> {
    let names: Vec<&str> = occ
        .simple("NOM_CHAM")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let steps = crate::commands::select_steps_pub(ex, "IMPR_RESU/RESU", occ, result)?;
    Ok(result
        .steps
        .iter()
        .filter(|s| steps.contains(&s.nume_ordre))
        .map(|s| {
            let fields = s
                .fields
                .iter()
                .filter(|(name, _)| names.is_empty() || names.contains(&name.as_str()))
                .map(|(name, f)| (name.as_str(), f))
                .collect();
            (s, fields)
        })
        .collect())
}

/// The nodes and cells a `RESU` occurrence restricts the MED fields to
/// (`irtopo`): the nodes of `GROUP_NO`/`NOEUD` and of the cells of
/// `GROUP_MA`/`MAILLE`; the cells of `GROUP_MA`/`MAILLE` (`None`: every
/// cell, as with `GROUP_NO` only). `None` without these keywords.
type Selection = (Vec<bool>, Option<Vec<bool>>);

fn selection(occ: &Keywords, mesh: &Mesh) -> Result<Option<Selection>, ExecError> {
    if !["GROUP_NO", "NOEUD", "GROUP_MA", "MAILLE"]
        .iter()
        .any(|k| occ.contains(k))
    {
        return Ok(None);
    }
    let err = |e: String| ExecError::new(format!("IMPR_RESU/RESU: {e}"));
    let mut nodes = vec![false; mesh.node_count()];
    for n in crate::select::nodes(occ, mesh, "").map_err(err)? {
        nodes[n.0 as usize] = true;
    }
    let cells = if occ.contains("GROUP_MA") || occ.contains("MAILLE") {
        let mut cells = vec![false; mesh.cells.len()];
        for c in crate::select::cells(occ, mesh, "").map_err(err)? {
            cells[c.0 as usize] = true;
        }
        Some(cells)
    } else {
        None
    };
    Ok(Some((nodes, cells)))
}

/// The entities code_aster writes a field on in MED (`ircmpn`, `ircmpe`):
/// a nodal field on the selected nodes that carry one of the written
/// components (`wanted`, all when empty); an element field, when cells are
/// selected, on those that carry it. `None`: every entity.
fn written_on(
    f: &Field,
    wanted: &[&str],
    mesh: &Mesh,
    sel: Option<&Selection>,
) -> Option<Vec<bool>> {
    match f {
        Field::Nodal(f) => {
            let cols: Vec<usize> = (0..f.components().len())
                .filter(|&c| wanted.is_empty() || wanted.contains(&f.components()[c].as_str()))
                .collect();
            let mut mask = vec![false; mesh.node_count()];
            for (n, vals) in f.iter() {
                let i = n.0 as usize;
                let selected = sel.is_none_or(|(nodes, _)| nodes.get(i).copied().unwrap_or(false));
                if selected && cols.iter().any(|&c| vals.get(c).is_some()) {
                    if let Some(m) = mask.get_mut(i) {
                        *m = true;
                    }
                }
            }
            Some(mask)
        }
        Field::Elem(f) => {
            let cells = sel?.1.as_ref()?;
            let mut mask = vec![false; mesh.cells.len()];
            for (c, pts) in f.iter() {
                let i = c.0 as usize;
                if !pts.is_empty() && cells.get(i).copied().unwrap_or(false) {
                    mask[i] = true;
                }
            }
            Some(mask)
        }
    }
}

/// The MED steps of a `RESU/RESULTAT` occurrence, with the entities each
/// field is written on (parallel to each step's fields).
type StepsOn = Vec<(ResultStep, Vec<Option<Vec<bool>>>)>;

fn result_steps(ex: &Executor, occ: &Keywords, result: &EvolResult) -> Result<StepsOn, ExecError> {
    let mesh = ex.mesh_by_id(result.mesh)?;
    let wanted: Vec<&str> = occ
        .simple("NOM_CMP")
        .iter()
        .filter_map(|v| v.as_str())
        .collect();
    let sel = selection(occ, &mesh)?;
    let mut out = Vec::new();
    for (s, selected) in selected_fields(ex, occ, result)? {
        let mut fields = Vec::new();
        let mut masks = Vec::new();
        for (name, f) in selected {
            // Fields without components (VARI_ELGA of ELAS) have nothing to write.
            if f.components().is_empty() {
                continue;
            }
            let field = to_mesh_field(name, f, &mesh);
            // NOM_CMP (FORMAT='MED'): only these components are written; a
            // field with none of them is left out, as code_aster does.
            match only_components(field, &wanted) {
                Some(field) => {
                    fields.push(field);
                    masks.push(written_on(f, &wanted, &mesh, sel.as_ref()));
                }
                None => continue,
            }
        }
        out.push((
            ResultStep {
                nume_ordre: s.nume_ordre as i32,
                inst: s.inst,
                fields,
            },
            masks,
        ));
    }
    Ok(out)
}

/// A field restricted to the components `wanted` (all when empty); `None`
/// when it has none of them.
fn only_components(field: aster_mesh::Field, wanted: &[&str]) -> Option<aster_mesh::Field> {
    if wanted.is_empty() {
        return Some(field);
    }
    let keep: Vec<usize> = (0..field.components.len())
        .filter(|&c| wanted.contains(&field.components[c].as_str()))
        .collect();
    if keep.is_empty() {
        return None;
    }
    let n = field.components.len();
    let values = field
        .values
        .chunks(n)
        .flat_map(|set| keep.iter().map(move |&c| set[c]))
        .collect();
    Some(aster_mesh::Field {
        components: keep.iter().map(|&c| field.components[c].clone()).collect(),
        values,
        ..field
    })
}

/// What IMPR_RESU reads (`crate::support`).
pub(crate) const IMPR_RESU: Support = Support {
    values: &[
        Values::new("FORMAT", &["MED", "ASTER", "RESULTAT", "GMSH"]),
        // 'OUI' is what no NOM_CHAM means: every field of the result.
        Values::new("RESU/TOUT_CHAM", &["OUI"]),
    ],
    rules: Some(impr_resu_rules),
    ..Support::keywords(&[
        "FORMAT",
        "UNITE",
        "INFO",
        "PROC0",
        "VERSION_MED",
        // The model code_aster uses to locate element fields: ours
        // carry their model with the result.
        "MODELE",
        "RESU",
        "RESU/MAILLAGE",
        "RESU/RESULTAT",
        "RESU/CHAM_GD",
        "RESU/NOM_CHAM",
        "RESU/TOUT_CHAM",
        "RESU/TOUT",
        "RESU/TOUT_ORDRE",
        "RESU/NUME_ORDRE",
        "RESU/NOM_CAS",
        "RESU/INST",
        "RESU/PRECISION",
        "RESU/CRITERE",
        "RESU/INFO_MAILLAGE",
        "RESU/IMPR_NOM_VARI",
        // FORMAT='RESULTAT' listing selections.
        "RESU/NOM_CMP",
        "RESU/GROUP_NO",
        "RESU/NOEUD",
        "RESU/GROUP_MA",
        "RESU/MAILLE",
        "RESU/FORMAT_R",
        "RESU/IMPR_COOR",
        "RESU/TYPE_CHAM",
        // code_aster reads it to describe the sub-points (layers) of a
        // field as MED structural elements; aster's results hold no
        // sub-point field (the layers are extracted by POST_CHAMP), so it
        // changes nothing written (ssls111a).
        "RESU/CARA_ELEM",
    ])
};

/// The selections of `RESU` each format prints, and the real formats.
fn impr_resu_rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    let format = kw.str("FORMAT").unwrap_or("RESULTAT");
    for occ in kw.factor("RESU") {
        for key in [
            "NOM_CMP",
            "GROUP_NO",
            "NOEUD",
            "GROUP_MA",
            "MAILLE",
            "IMPR_COOR",
            "TYPE_CHAM",
        ] {
            let allowed = match format {
                "RESULTAT" => key != "TYPE_CHAM",
                "GMSH" => key == "NOM_CMP" || key == "TYPE_CHAM",
                "MED" => matches!(
                    key,
                    "NOM_CMP" | "GROUP_NO" | "NOEUD" | "GROUP_MA" | "MAILLE"
                ),
                _ => false,
            };
            if !allowed && occ.keyword(key).is_some_and(|k| !k.defaulted) {
                out.push(Refusal::at(
                    format!("IMPR_RESU/RESU/{key} with FORMAT='{format}'"),
                    occ,
                    key,
                    call.span,
                ));
            }
        }
        if let Some(f) = occ.str("FORMAT_R").filter(|f| real_format(f).is_none()) {
            out.push(Refusal::at(
                format!("IMPR_RESU/RESU/FORMAT_R='{f}'"),
                occ,
                "FORMAT_R",
                call.span,
            ));
        }
    }
}

pub fn impr_resu(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let format = kw.str("FORMAT").unwrap_or("RESULTAT");
    if format == "GMSH" {
        let text = gmsh(ex, kw)?;
        let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(37);
        let path = ex.output_path(unit);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| {
                ExecError::new(format!("IMPR_RESU: cannot create {}: {e}", dir.display()))
            })?;
        }
        std::fs::write(&path, text).map_err(|e| {
            ExecError::new(format!("IMPR_RESU: cannot write {}: {e}", path.display()))
        })?;
        return Ok(CommandOutput::Nothing);
    }
    if format == "RESULTAT" {
        let text = listing(ex, kw)?;
        let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(8);
        if unit == 8 || unit == 6 {
            ex.write_report(&text)?;
        } else {
            ex.append_unit(unit, &text)?;
        }
        return Ok(CommandOutput::Nothing);
    }
    let default_unit = if format == "MED" { 80 } else { 8 };
    let unit = kw
        .first("UNITE")
        .and_then(|s| s.as_i64())
        .unwrap_or(default_unit);
    let path = ex.output_path(unit);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| {
            ExecError::new(format!("IMPR_RESU: cannot create {}: {e}", dir.display()))
        })?;
    }
    let mut mesh: Option<(Arc<Mesh>, String)> = None;
    let mut steps: Vec<ResultStep> = Vec::new();
    // The entities each written field covers (MED profiles).
    let mut entities = aster_mesh::Entities::new();
    // One MED file holds one mesh here: the mesh of every occurrence.
    let mut same_mesh = |m: &Arc<Mesh>, name: &str, at: &Keywords, key: &str| {
        match &mesh {
            None => {
                mesh = Some((m.clone(), name.to_string()));
                Ok(())
            }
            // DEFI_GROUP(reuse=) makes a new mesh concept with the same nodes.
            Some((first, _))
                if Arc::ptr_eq(first, m)
                    || (first.coords == m.coords && first.cells == m.cells) =>
            {
                Ok(())
            }
            Some(_) => Err(ex.unsupported(
                "IMPR_RESU/FORMAT='MED' with fields of several meshes in one file",
                at.keyword(key).map(|k| k.span).unwrap_or(call.span),
            )),
        }
    };
    for occ in kw.factor("RESU") {
        if let Some(m) = occ.concept("MAILLAGE") {
            same_mesh(&ex.mesh(m)?, &m.name, occ, "MAILLAGE")?;
        }
        if let Some(r) = occ.concept("RESULTAT") {
            let result = ex.result(r)?;
            same_mesh(&ex.mesh_by_id(result.mesh)?, &r.name, occ, "RESULTAT")?;
            let s = result_steps(ex, occ, &result)?;
            // Several results in one file: prefix field names with the result's.
            for (mut st, masks) in s {
                for (f, mask) in st.fields.iter_mut().zip(masks) {
                    f.name = format!("{}{}", r.name, f.name);
                    if let Some(mask) = mask {
                        entities.insert((st.nume_ordre, f.name.clone()), mask);
                    }
                }
                steps.push(st);
            }
        }
        if let Some(c) = occ.concept("CHAM_GD") {
            let m = ex.field_mesh(c)?;
            same_mesh(&m, &c.name, occ, "CHAM_GD")?;
            let f = ex.field(c)?;
            let field = to_mesh_field(&c.name, &f, &m);
            let cmps: Vec<&str> = occ
                .simple("NOM_CMP")
                .iter()
                .filter_map(|c| c.as_str())
                .collect();
            let sel = selection(occ, &m)?;
            if let Some(mask) = written_on(&f, &cmps, &m, sel.as_ref()) {
                entities.insert((0, c.name.clone()), mask);
            }
            let fields = only_components(field, &cmps).into_iter().collect();
            steps.push(ResultStep {
                nume_ordre: 0,
                inst: 0.0,
                fields,
            });
        }
    }
    let Some((mesh, name)) = mesh else {
        return Err(ExecError::new(
            "IMPR_RESU: nothing to print (give MAILLAGE, RESULTAT or CHAM_GD in RESU)",
        ));
    };
    match format {
        "MED" => {
            // One MED step per NUME_ORDRE, fields of all occurrences merged.
            let mut merged: Vec<ResultStep> = Vec::new();
            for s in steps {
                match merged.iter_mut().find(|m| m.nume_ordre == s.nume_ordre) {
                    Some(m) => m.fields.extend(s.fields),
                    None => merged.push(s),
                }
            }
            aster_mesh::write_med_on(&path, &mesh, &name, &merged, &entities)
                .map_err(|e| ExecError::new(format!("IMPR_RESU: {e}")))?;
            ex.med_written.insert(unit as u32, path.clone());
        }
        _ => {
            // code_aster's FORMAT='ASTER' prints the mesh only: result
            // fields are left out with an alarm (RESULT3_67), and without
            // MAILLAGE nothing can be printed (RESULT3_70).
            if !kw.factor("RESU").iter().any(|o| o.contains("MAILLAGE")) {
                return Err(ex.unsupported(
                    "IMPR_RESU/FORMAT='ASTER' without RESU/MAILLAGE (code_aster prints only a mesh in this format: RESULT3_70)",
                    call.span,
                ));
            }
            if !steps.is_empty() {
                ex.write_report(
                    "<A> IMPR_RESU: the ASTER format prints only the mesh; the fields are not printed (code_aster RESULT3_67: use FORMAT='RESULTAT')\n",
                )?;
            }
            aster_mesh::write_mail(&path, &mesh)
                .map_err(|e| ExecError::new(format!("IMPR_RESU: {e}")))?;
        }
    }
    Ok(CommandOutput::Nothing)
}

/// Width and precision of a Fortran `1PEw.p` format (`FORMAT_R`).
fn real_format(f: &str) -> Option<(usize, usize)> {
    let (w, p) = f.strip_prefix("1PE")?.split_once('.')?;
    Some((w.parse().ok()?, p.parse().ok()?))
}

/// `IMPR_RESU(FORMAT='RESULTAT')`: a text listing of nodal fields (one
/// line per node: its name, then the components as `%12.5E`), per field
/// and stored step, restricted to `GROUP_NO`/`NOEUD`/`GROUP_MA`/`MAILLE`
/// and `NOM_CMP` when given. Element fields are listed by their name only.
fn listing(ex: &Executor, kw: &Keywords) -> Result<String, ExecError> {
    use crate::pyfmt::c_exp;
    let mut out = String::new();
    fn print(
        out: &mut String,
        mesh: &Mesh,
        occ: &Keywords,
        title: String,
        f: &crate::field::Field,
    ) -> Result<(), ExecError> {
        use crate::field::Field as RunField;
        use crate::pyfmt::c_exp;
        *out += &format!("\n{title}\n");
        let RunField::Nodal(f) = f else {
            *out += " (element field: not listed in FORMAT='RESULTAT')\n";
            return Ok(());
        };
        let wanted: Vec<&str> = occ
            .simple("NOM_CMP")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        let cols: Vec<usize> = (0..f.components().len())
            .filter(|i| wanted.is_empty() || wanted.contains(&f.components()[*i].as_str()))
            .collect();
        let selected = ["GROUP_NO", "NOEUD", "GROUP_MA", "MAILLE"]
            .iter()
            .any(|k| occ.contains(k));
        let nodes: Option<std::collections::BTreeSet<aster_mesh::NodeId>> = if selected {
            Some(
                crate::select::nodes(occ, mesh, "")
                    .map_err(|e| ExecError::new(format!("IMPR_RESU/RESU: {e}")))?
                    .into_iter()
                    .collect(),
            )
        } else {
            None
        };
        let (w, p) = real_format(occ.str("FORMAT_R").unwrap_or("1PE21.14")).unwrap_or((21, 14));
        *out += &format!("{:<9}", "NOEUD");
        for &c in &cols {
            *out += &format!(" {:>w$}", f.components()[c]);
        }
        *out += "\n";
        for (node, vals) in f.iter() {
            if nodes.as_ref().is_some_and(|s| !s.contains(&node)) {
                continue;
            }
            *out += &format!("{:<9}", mesh.node_name(node));
            for &c in &cols {
                match vals.get(c) {
                    Some(v) => *out += &format!(" {}", c_exp(v, w, p)),
                    None => *out += &format!(" {:>w$}", "-"),
                }
            }
            *out += "\n";
        }
        Ok(())
    }
    for occ in kw.factor("RESU") {
        if let Some(r) = occ.concept("RESULTAT") {
            let result = ex.result(r)?;
            let mesh = ex.mesh_by_id(result.mesh)?;
            for (s, fields) in selected_fields(ex, occ, &result)? {
                for (name, f) in fields {
                    let title = format!(
                        "CHAMP AUX NOEUDS DE NOM SYMBOLIQUE  {name}\nNUMERO D'ORDRE: {} INST: {}",
                        s.nume_ordre,
                        c_exp(s.inst, 12, 5).trim()
                    );
                    print(&mut out, &mesh, occ, title, f)?;
                }
            }
        }
        if let Some(c) = occ.concept("CHAM_GD") {
            let mesh = ex.single_mesh()?;
            let f = ex.field(c)?;
            print(&mut out, &mesh, occ, format!("CHAMP {}", c.name), &f)?;
        }
        if occ.concept("MAILLAGE").is_some()
            && occ.concept("RESULTAT").is_none()
            && occ.concept("CHAM_GD").is_none()
        {
            let m = ex.mesh(
                occ.concept("MAILLAGE")
                    .ok_or_else(|| ExecError::new("IMPR_RESU: no mesh"))?,
            )?;
            out += &format!(
                "\nMAILLAGE: {} noeuds, {} mailles\n",
                m.node_count(),
                m.cells.len()
            );
        }
    }
    Ok(out)
}

/// gmsh element type of a cell and the nodes written (quadratic volumes are
/// written by their corners: the file is for viewing).
fn gmsh_cell(ty: aster_mesh::CellType) -> (u32, usize) {
    use aster_mesh::CellType as T;
    match ty {
        T::POI1 => (15, 1),
        T::SEG2 | T::SEG4 => (1, 2),
        T::SEG3 => (8, 3),
        T::TRIA3 | T::TRIA7 => (2, 3),
        T::TRIA6 => (9, 6),
        T::QUAD4 => (3, 4),
        T::QUAD8 => (16, 8),
        T::QUAD9 => (10, 9),
        T::TETRA4 | T::TETRA10 => (4, 4),
        T::HEXA8 | T::HEXA20 | T::HEXA27 => (5, 8),
        T::PENTA6 | T::PENTA15 | T::PENTA18 => (6, 6),
        T::PYRAM5 | T::PYRAM13 => (7, 5),
    }
}

/// `IMPR_RESU(FORMAT='GMSH')`: a gmsh 2.2 ASCII file with the mesh and, for
/// each nodal field, step and component (`NOM_CMP` when given), one
/// `$NodeData` view named `<result>_<field>_<component>`.
fn gmsh(ex: &Executor, kw: &Keywords) -> Result<String, ExecError> {
    let mut views = String::new();
    let mut mesh: Option<Arc<Mesh>> = None;
    for occ in kw.factor("RESU") {
        if let Some(m) = occ.concept("MAILLAGE") {
            mesh = Some(ex.mesh(m)?);
        }
        let Some(r) = occ.concept("RESULTAT") else {
            continue;
        };
        let result = ex.result(r)?;
        let m = ex.mesh_by_id(result.mesh)?;
        let cmps: Vec<&str> = occ
            .simple("NOM_CMP")
            .iter()
            .filter_map(|s| s.as_str())
            .collect();
        for (s, fields) in selected_fields(ex, occ, &result)? {
            for (name, f) in fields {
                let Field::Nodal(f) = f else { continue };
                for (c, comp) in f.components().iter().enumerate() {
                    if !cmps.is_empty() && !cmps.contains(&comp.as_str()) {
                        continue;
                    }
                    let values: Vec<(u32, f64)> = f
                        .iter()
                        .filter_map(|(n, v)| v.get(c).map(|v| (n.0 + 1, v)))
                        .collect();
                    views += &format!(
                        "$NodeData\n1\n\"{}_{}_{}\"\n1\n{}\n3\n{}\n1\n{}\n",
                        r.name,
                        name,
                        comp,
                        crate::pyfmt::py_repr(s.inst),
                        s.nume_ordre,
                        values.len()
                    );
                    for (n, v) in values {
                        views += &format!("{n} {}\n", crate::pyfmt::py_repr(v));
                    }
                    views += "$EndNodeData\n";
                }
            }
        }
        mesh.get_or_insert(m);
    }
    let mesh = match mesh {
        Some(m) => m,
        None => ex.single_mesh()?,
    };
    let mut out = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n");
    out += &format!("{}\n", mesh.node_count());
    for (i, x) in mesh.coords.iter().enumerate() {
        out += &format!(
            "{} {} {} {}\n",
            i + 1,
            crate::pyfmt::py_repr(x[0]),
            crate::pyfmt::py_repr(x[1]),
            crate::pyfmt::py_repr(x[2])
        );
    }
    out += &format!("$EndNodes\n$Elements\n{}\n", mesh.cells.len());
    for (i, cell) in mesh.cells.iter().enumerate() {
        let (ty, count) = gmsh_cell(cell.ty);
        out += &format!("{} {ty} 2 0 0", i + 1);
        for n in cell.nodes.iter().take(count) {
            out += &format!(" {}", n.0 + 1);
        }
        out += "\n";
    }
    out += "$EndElements\n";
    out += &views;
    Ok(out)
}
