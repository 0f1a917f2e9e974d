//! POST_ELEM: quantities integrated over cells, as a table.
//!
//! - `ENER_POT` (code_aster's `peepot`): the potential energy of a
//!   displacement (`EPOT_ELEM`: ½ uₑᵀ Kₑ uₑ per cell, aster-fem
//!   `energy::potential_energy_by_cell`), summed over the whole model
//!   (`TOUT`, `LIEU` = the mesh's name) or per group (`GROUP_MA`), with
//!   `POUR_CENT` the share of the model's total. From a result
//!   (`RESULTAT`, every stored instant unless `NUME_ORDRE`/`INST`/
//!   `LIST_INST` choose) the table has `NUME_ORDRE`, `INST`, `LIEU` (K24),
//!   `ENTITE`, `TOTALE`, `POUR_CENT`; from a field (`CHAM_GD` with
//!   `MODELE`, `CHAM_MATER`, `CARA_ELEM`) `LIEU` (K8), `ENTITE`, `TOTALE`,
//!   `POUR_CENT`.
//! - `ENER_ELAS` (`peingl`, option `ENEL_ELEM`): the elastic energy of a
//!   result's stresses, per instant, with code_aster's columns `TOTALE`,
//!   `MEMBRANE`, `FLEXION`, `CISAILLE`, `COUPL_MF` (the last four are for
//!   plates: 0 for continuum cells). Elastic results only: there it is the
//!   same ½ σ:D⁻¹:σ = ½ ε:D:ε as `ENER_POT`.
//! - `ENER_TOTALE` (`peingl`, `te0491`) of a result: the same energy for
//!   elastic results (code_aster adds the plastic work of VMIS_ISOT cells
//!   and integrates other behaviours over the steps: plastic results are
//!   refused), columns `NUME_ORDRE`, `INST`, `LIEU`, `ENTITE`, `TOTALE`.
//!
//! - `ENER_CIN` (`peecin`, option `ECIN_ELEM`): the kinetic energy
//!   ½ vₑᵀ Mₑ vₑ of each continuum cell with the consistent mass
//!   (`MASS_MECA`, aster-fem `mass::kinetic_energy_by_cell`) and the
//!   velocity `VITE` of each stored instant of a result (code_aster takes
//!   `VITE` when the result has instants; an instant without `VITE` gives
//!   no row). Same columns as `ENER_POT`. Densities from `CHAM_MATER`
//!   when given, else those of the computation; discrete masses refused.
//!
//! - `NORME` (`penorm`, option `NORME_L2`) of a field (`CHAM_GD`, `MODELE`):
//!   see [`norme`].
//!
//! - `INTEGRALE` (`peeint`/`peecal`/`chpond`) of a result's field or of a
//!   field (`CHAM_GD`, `MODELE`; the sources in `integrale_field`): see
//!   [`integrale`].
//!
//! - `TRAV_EXT` (`pewext`): the work of the external forces of a result,
//!   from its `DEPL` and `FORC_NODA`: see [`trav_ext`].
//!
//! - `MINMAX` (`pemima`): the extrema of components of a field and where
//!   they are reached: see [`minmax`].
//!
//! - `MASS_INER` (`pemain`/`pemica`): mass, centre of gravity and inertia,
//!   see [`mass_iner`].
//!
//! - `CARA_GEOM` (`pecage`): the geometric properties of a plane section,
//!   see [`cara_geom`].
//!
//! Every other quantity (ENER_DISS, INTEGRALE/NOM_VARI…) is refused with
//! its location.

use crate::concept::{Concept, EvolResult};
use crate::executor::{store_result, Executor};
use crate::support::{Support, Values};
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_fem::Model;
use aster_mesh::{CellId, Mesh};
use std::collections::HashMap;
use std::rc::Rc;

mod cara_geom;
mod integrale_field;
mod mass_iner;
mod minmax;
mod trav_ext;

const POST_ELEM_OWN: &[&str] = &[
    "ENER_POT",
    "ENER_POT/TOUT",
    "ENER_POT/GROUP_MA",
    "ENER_ELAS",
    "ENER_ELAS/TOUT",
    "ENER_ELAS/GROUP_MA",
    "ENER_TOTALE",
    "ENER_TOTALE/TOUT",
    "ENER_TOTALE/GROUP_MA",
    "ENER_CIN",
    "ENER_CIN/TOUT",
    "ENER_CIN/GROUP_MA",
    "RESULTAT",
    "CHAM_GD",
    "MODELE",
    "CHAM_MATER",
    "CARA_ELEM",
    "TITRE",
    "NORME",
    "NORME/TOUT",
    "NORME/GROUP_MA",
    "NORME/TYPE_MAILLE",
    "NORME/TYPE_NORM",
    "NORME/CHAM_GD",
    "NORME/MODELE",
    "NORME/COEF_MULT",
    "INTEGRALE",
    "INTEGRALE/TOUT",
    "INTEGRALE/GROUP_MA",
    "INTEGRALE/NOM_CHAM",
    "INTEGRALE/NOM_CMP",
    "INTEGRALE/TYPE_MAILLE",
    "TRAV_EXT",
    "MINMAX",
    "MINMAX/TOUT",
    "MINMAX/GROUP_MA",
    "MINMAX/RESULTAT",
    "MINMAX/NOM_CHAM",
    "MINMAX/CHAM_GD",
    "MINMAX/MODELE",
    "MINMAX/NOM_CMP",
    "MINMAX/CRITERE",
    "MINMAX/PRECISION",
    "MINMAX/TOUT_ORDRE",
    "MINMAX/NUME_ORDRE",
    "MINMAX/LIST_ORDRE",
    "MINMAX/INST",
    "MINMAX/LIST_INST",
    "MASS_INER",
    "MASS_INER/TOUT",
    "MASS_INER/GROUP_MA",
    "MASS_INER/ORIG_INER",
    "GEOMETRIE",
    "CARA_GEOM",
    "CARA_GEOM/TOUT",
    "CARA_GEOM/GROUP_MA",
    "CARA_GEOM/SYME_X",
    "CARA_GEOM/SYME_Y",
    "CARA_GEOM/ORIG_INER",
];

/// What POST_ELEM computes (`crate::support`): its own keywords and the
/// step selection ([`super::post::STEP_SELECTION`]).
pub(crate) const POST_ELEM: Support = Support {
    values: &[
        Values::new("NORME/TYPE_NORM", &["L2"])
            .why("(the Frobenius norm is not reproduced): the L2 norm only"),
        Values::new("GEOMETRIE", &["INITIALE"])
            .why("(the deformed geometry is not reproduced): the mesh's own"),
    ],
    ..Support::keywords(&crate::support::joined::<
        _,
        { super::post::STEP_SELECTION.len() + POST_ELEM_OWN.len() },
    >(super::post::STEP_SELECTION, POST_ELEM_OWN))
};

pub fn post_elem(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    if kw.contains("ENER_CIN") {
        return ener_cin(ex, call);
    }
    if kw.contains("NORME") {
        return norme(ex, call);
    }
    if kw.contains("INTEGRALE") {
        return integrale(ex, call);
    }
    if kw.contains("TRAV_EXT") {
        return trav_ext::trav_ext(ex, call);
    }
    if kw.contains("MINMAX") {
        return minmax::minmax(ex, call);
    }
    if kw.contains("MASS_INER") {
        return mass_iner::mass_iner(ex, call);
    }
    if kw.contains("CARA_GEOM") {
        return cara_geom::cara_geom(ex, call);
    }
    let (factor, elastic) = if kw.contains("ENER_ELAS") {
        ("ENER_ELAS", true)
    } else if kw.contains("ENER_TOTALE") {
        // `peingl`'s ENER_TOTALE of an elastic result: its elastic energy
        // (`te0491`: enelas + eplast, eplast = 0 under ELAS), columns up to
        // TOTALE; code_aster requires RESULTAT.
        ex.required("POST_ELEM/ENER_TOTALE", kw, "RESULTAT")?;
        ("ENER_TOTALE", false)
    } else {
        ("ENER_POT", false)
    };
    let totale = factor == "ENER_TOTALE";
    let places = places(ex, kw, factor)?;
    let table = if let Some(r) = kw.concept("RESULTAT") {
        let result = ex.result(r)?;
        let steps = super::post::select_steps(ex, "POST_ELEM", kw, &result)?;
        let orders: Vec<(u32, f64)> = steps.iter().map(|s| (s.nume_ordre, s.inst)).collect();
        let (model, mesh_name) = result_model(ex, kw, r, &result)?;
        if let ModelRef::Run(run) = &*model {
            if run.plastic {
                return Err(ex.unsupported(
                    "POST_ELEM on a result with plastic cells (the energies of elastic results only)",
                    kw.keyword("RESULTAT").map(|k| k.span).unwrap_or_default(),
                ));
            }
            // code_aster's energies are those of the mechanical strain
            // ε − εth; ½uᵀKu is not (hplv103a: 2.7 times too large).
            if run.loads.items.iter().any(|i| {
                matches!(
                    i.load,
                    aster_fem::Load::FreeStrain { .. } | aster_fem::Load::ShellThermal { .. }
                )
            }) {
                return Err(ex.unsupported(
                    "POST_ELEM energies of a result with a thermal strain (AFFE_VARC TEMP: code_aster integrates ½(ε − εth):D:(ε − εth); not done)",
                    kw.keyword("RESULTAT").map(|k| k.span).unwrap_or_default(),
                ));
            }
        }
        let mut columns = vec![
            col("NUME_ORDRE", ColumnType::Int),
            col("INST", ColumnType::Real),
            col("LIEU", ColumnType::Text(24)),
            col("ENTITE", ColumnType::Text(8)),
            col("TOTALE", ColumnType::Real),
        ];
        if elastic {
            for c in ["MEMBRANE", "FLEXION", "CISAILLE", "COUPL_MF"] {
                columns.push(col(c, ColumnType::Real));
            }
        } else if !totale {
            columns.push(col("POUR_CENT", ColumnType::Real));
        }
        let mut table = Table::new(columns);
        for (order, inst) in orders {
            let u = displacement(ex, &result, &model, order, &r.name)?;
            let energies = energies(&model, &u)?;
            for place in &places {
                let (value, percent) = place.sum(&energies, &model);
                let mut row = vec![
                    ("NUME_ORDRE", Value::Int(order as i64)),
                    ("INST", Value::Real(inst)),
                    ("LIEU", Value::Text(place.lieu(&mesh_name))),
                    ("ENTITE", Value::Text(place.entite().into())),
                    ("TOTALE", Value::Real(value)),
                ];
                if elastic {
                    for c in ["MEMBRANE", "FLEXION", "CISAILLE", "COUPL_MF"] {
                        row.push((c, Value::Real(0.0)));
                    }
                } else if !totale {
                    row.push(("POUR_CENT", Value::Real(percent)));
                }
                table.push_row(row);
            }
        }
        table
    } else {
        let Some(f) = kw.concept("CHAM_GD") else {
            return Err(ExecError::new(format!(
                "POST_ELEM/{factor}: give RESULTAT, or CHAM_GD with MODELE and CHAM_MATER"
            )));
        };
        let field = ex.field(f)?;
        let crate::field::Field::Nodal(depl) = &*field else {
            return Err(ex.kw_error(
                "POST_ELEM",
                kw,
                "CHAM_GD",
                "ENER_POT of an element field (ENER_ELEM) is not supported: give the displacement (a NOEU_DEPL_R field)",
            ));
        };
        let (model, mesh_name) = model_from_keywords(ex, kw)?;
        let u = crate::fembridge::displacement_from(&model, depl);
        let energies = energies(&model, &u)?;
        let mut table = Table::new(vec![
            col("LIEU", ColumnType::Text(8)),
            col("ENTITE", ColumnType::Text(8)),
            col("TOTALE", ColumnType::Real),
            col("POUR_CENT", ColumnType::Real),
        ]);
        for place in &places {
            let (value, percent) = place.sum(&energies, &model);
            table.push_row(vec![
                ("LIEU", Value::Text(place.lieu(&mesh_name))),
                ("ENTITE", Value::Text(place.entite().into())),
                ("TOTALE", Value::Real(value)),
                ("POUR_CENT", Value::Real(percent)),
            ]);
        }
        table
    };
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// `POST_ELEM/ENER_CIN` of a result: one row per stored instant with a
/// velocity and per place.
fn ener_cin(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let cmd = "POST_ELEM/ENER_CIN";
    let places = places(ex, kw, "ENER_CIN")?;
    let Some(r) = kw.concept("RESULTAT") else {
        return Err(ex.unsupported(
            "POST_ELEM/ENER_CIN of a field (CHAM_GD): give RESULTAT",
            kw.keyword("CHAM_GD").map(|k| k.span).unwrap_or(call.span),
        ));
    };
    let result = ex.result(r)?;
    let steps = super::post::select_steps(ex, "POST_ELEM", kw, &result)?;
    let (model, mesh_name) = result_model(ex, kw, r, &result)?;
    let mass = match (kw.concept("CHAM_MATER"), &*model) {
        (Some(m), _) => {
            let materials = ex.material_field(m)?;
            let mut data = aster_fem::MassData::default();
            for el in model.elements() {
                let rho = match materials.cells.get(&el.cell) {
                    Some(m) => m.resolved_density().map_err(ExecError::new)?,
                    None => None,
                };
                if let Some(rho) = rho {
                    data.density.insert(el.cell, rho);
                }
            }
            if let Some(c) = kw.concept("CARA_ELEM") {
                if !ex.cara_elem(c)?.masses.is_empty() {
                    return Err(ex.unsupported(
                        "POST_ELEM/ENER_CIN with discrete masses (AFFE_CARA_ELEM M_T_D_N, M_T_N, M_T_L): the kinetic energy of continuum cells only",
                        kw.keyword("CARA_ELEM").map(|k| k.span).unwrap_or(call.span),
                    ));
                }
            }
            data
        }
        (None, ModelRef::Run(run)) => run.mass.clone().ok_or_else(|| {
            ExecError::new(format!(
                "{cmd}: the masses of `{}` could not be gathered",
                r.name
            ))
        })?,
        (None, ModelRef::Own(_)) => {
            return Err(ExecError::new(format!(
                "{cmd}: give CHAM_MATER with MODELE"
            )));
        }
    };
    if !mass.discrete.is_empty() {
        return Err(ex.unsupported(
            "POST_ELEM/ENER_CIN with discrete masses (AFFE_CARA_ELEM M_T_D_N, M_T_N, M_T_L): the kinetic energy of continuum cells only",
            kw.keyword("ENER_CIN").map(|k| k.span).unwrap_or(call.span),
        ));
    }
    // `peecin`: of modes (a MODE_MECA), the shape stands for the velocity
    // and the energy is multiplied by the mode's OMEGA2; the table gives
    // FREQ where a transient gives INST.
    let modal = result.modal.clone();
    let abscissa = if modal.is_some() { "FREQ" } else { "INST" };
    let mut table = Table::new(vec![
        col("NUME_ORDRE", ColumnType::Int),
        col(abscissa, ColumnType::Real),
        col("LIEU", ColumnType::Text(24)),
        col("ENTITE", ColumnType::Text(8)),
        col("TOTALE", ColumnType::Real),
        col("POUR_CENT", ColumnType::Real),
    ]);
    for step in steps {
        let param = |name: &str| {
            modal
                .as_ref()
                .and_then(|m| m.params.get(&step.nume_ordre))
                .and_then(|p| p.get(name))
                .copied()
                .ok_or_else(|| {
                    ExecError::new(format!("{cmd}: mode {} has no {name}", step.nume_ordre))
                })
        };
        let (field, factor, at) = match &modal {
            Some(_) => ("DEPL", param("OMEGA2")?, param("FREQ")?),
            None => ("VITE", 1.0, step.inst),
        };
        let Some(crate::field::Field::Nodal(vite)) = step.fields.get(field) else {
            continue;
        };
        let v = crate::fembridge::displacement_from(&model, vite);
        let energies: HashMap<CellId, f64> =
            aster_fem::mass::kinetic_energy_by_cell(&model, &mass, &v)
                .map_err(|e| ExecError::new(format!("{cmd}: {e}")))?
                .into_iter()
                .map(|(c, e)| (c, factor * e))
                .collect();
        for place in &places {
            let (value, percent) = place.sum(&energies, &model);
            table.push_row(vec![
                ("NUME_ORDRE", Value::Int(step.nume_ordre as i64)),
                (abscissa, Value::Real(at)),
                ("LIEU", Value::Text(place.lieu(&mesh_name))),
                ("ENTITE", Value::Text(place.entite().into())),
                ("TOTALE", Value::Real(value)),
                ("POUR_CENT", Value::Real(percent)),
            ]);
        }
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// `POST_ELEM/NORME` of a field (`CHAM_GD`, `MODELE`), code_aster's
/// `penorm`: the field at the Gauss points of the `NORME_L2` option (the
/// `RIGI` family, crate::commands::crea_champ_elga; a nodal field
/// interpolated there, a value it lacks 0) on the model's cells of `TOUT`
/// or `GROUP_MA` (of dimension `TYPE_MAILLE`), and √(Σ weight · Σ_c coef_c
/// v_c²) (aster-fem `elga::weighted_square_sum`, `COOR_ELGA` weights).
/// The coefficients follow the field's quantity (`calc_norm_coef`): DEPL
/// DX DY DZ; TEMP; FLUX FLUX FLUY FLUZ; SIEF and EPSI the diagonal 1, the
/// shears 2; NEUT_R `COEF_MULT` by component (none: 0). A field of another
/// quantity gives no row (as code_aster). 3D edge cells carry no norm.
fn norme(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "POST_ELEM/NORME";
    let kw = &call.keywords;
    let occ = kw
        .factor("NORME")
        .first()
        .ok_or_else(|| ExecError::new(format!("{cmd}: no occurrence")))?;
    let f = ex.required(cmd, occ, "CHAM_GD")?;
    let model = ex.model(ex.required(cmd, occ, "MODELE")?)?;
    let mesh = ex.model_mesh(&model)?;
    let at = occ.keyword("MODELE").map(|k| k.span).unwrap_or(call.span);
    let layout = super::crea_champ_elga::layout(ex, &model, &mesh, at)?;
    let mut table = Table::new(vec![
        col("CHAM_GD", ColumnType::Text(8)),
        col("GROUP_MA", ColumnType::Text(24)),
        col("TYPE_MAIL", ColumnType::Text(8)),
        col("TYPE_NORM", ColumnType::Text(8)),
        col("VALE_NORM", ColumnType::Real),
    ]);
    let Some(quantity) = ex.field_quantity.get(&f.id).cloned() else {
        return Err(ex.unsupported(
            "POST_ELEM/NORME of a field not made by CREA_CHAMP (its quantity, which sets the norm's components, is not known here)",
            occ.keyword("CHAM_GD").map(|k| k.span).unwrap_or(call.span),
        ));
    };
    let coef_mult: Vec<f64> = occ
        .simple("COEF_MULT")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    if !coef_mult.is_empty() && !quantity.starts_with("NEUT_R") {
        // code_aster's POSTELEM_2.
        return Err(ex.kw_error(
            cmd,
            occ,
            "COEF_MULT",
            format!("COEF_MULT is for NEUT_R fields, not {quantity}"),
        ));
    }
    let q4 = quantity.get(..4).unwrap_or("");
    let normed = quantity.ends_with("_R")
        && (matches!(q4, "DEPL" | "EPSI" | "TEMP" | "FLUX" | "SIEF") || quantity == "NEUT_R");
    if !normed {
        return store_result(ex, call, Concept::Table(Rc::new(table)));
    }
    let field = ex.field(f)?;
    let comps = field.components().to_vec();
    // Per component of the field, its coefficient.
    let coef: Vec<f64> = match q4 {
        "NEUT" => {
            // By position among the field's components: a cham_no holds
            // those it has, a cham_elem all of X1…X30 (here: by X index).
            let mut order: Vec<usize> = (0..comps.len()).collect();
            let index = |c: &str| c.strip_prefix('X').and_then(|n| n.parse::<usize>().ok());
            order.sort_by_key(|&i| index(&comps[i]).unwrap_or(usize::MAX));
            let mut out = vec![0.0; comps.len()];
            for (pos, &i) in order.iter().enumerate() {
                let k = match &*field {
                    crate::field::Field::Nodal(_) => Some(pos),
                    crate::field::Field::Elem(_) => index(&comps[i]).map(|x| x - 1),
                };
                out[i] = k.and_then(|k| coef_mult.get(k)).copied().unwrap_or(0.0);
            }
            out
        }
        _ => comps
            .iter()
            .map(|c| match c.as_str() {
                "DX" | "DY" | "DZ" if q4 == "DEPL" => 1.0,
                "TEMP" if q4 == "TEMP" => 1.0,
                "FLUX" | "FLUY" | "FLUZ" if q4 == "FLUX" => 1.0,
                "EPXX" | "EPYY" | "EPZZ" if q4 == "EPSI" => 1.0,
                "EPXY" | "EPXZ" | "EPYZ" if q4 == "EPSI" => 2.0,
                "SIXX" | "SIYY" | "SIZZ" if q4 == "SIEF" => 1.0,
                "SIXY" | "SIXZ" | "SIYZ" if q4 == "SIEF" => 2.0,
                _ => 0.0,
            })
            .collect(),
    };
    // The cells: the model's, of TOUT or the groups, of TYPE_MAILLE's
    // dimension; edges of a 3D model have no NORME_L2.
    let mut cells: Vec<CellId> = if occ.contains("TOUT") {
        model.cells.keys().copied().collect()
    } else {
        crate::select::cells(occ, &mesh, "")
            .map_err(|e| ex.kw_error(cmd, occ, "GROUP_MA", e))?
            .into_iter()
            .filter(|c| model.cells.contains_key(c))
            .collect()
    };
    let type_maille = occ.str("TYPE_MAILLE");
    if let Some(t) = type_maille {
        let dim = if t == "2D" { 2 } else { 3 };
        cells.retain(|&c| mesh.cell(c).ty.dim() as usize == dim);
        if cells.is_empty() {
            // code_aster's PREPOST2_6.
            return Err(ex.kw_error(cmd, occ, "TYPE_MAILLE", "no cell of that dimension"));
        }
    }
    cells.retain(|c| {
        layout
            .cells
            .get(c)
            .is_some_and(|g| g.role != aster_fem::elga::CellRole::Edge)
    });
    let values: std::collections::BTreeMap<CellId, Vec<Vec<f64>>> = match &*field {
        crate::field::Field::Nodal(n) => {
            super::crea_champ_elga::nodal_at_points(n, &mesh, &layout, &cells)
        }
        crate::field::Field::Elem(e) => {
            if e.location != crate::field::ElemLocation::Gauss {
                return Err(ex.unsupported(
                    "POST_ELEM/NORME of an element field not at Gauss points (ELNO, ELEM)",
                    occ.keyword("CHAM_GD").map(|k| k.span).unwrap_or(call.span),
                ));
            }
            let mut out = std::collections::BTreeMap::new();
            for c in &cells {
                let Some(points) = e.cell(*c) else {
                    continue;
                };
                let n = layout.cells[c].points.len();
                if points.len() != n {
                    return Err(ExecError::new(format!(
                        "{cmd}: cell {} has {} points in the field and {n} in the model's NORME_L2 family",
                        crate::select::cell_name(&mesh, *c),
                        points.len()
                    )));
                }
                let zeroed = points
                    .iter()
                    .map(|p| {
                        p.iter()
                            .map(|v| if v.is_nan() { 0.0 } else { *v })
                            .collect()
                    })
                    .collect();
                out.insert(*c, zeroed);
            }
            out
        }
    };
    let mut sum = 0.0;
    for (c, v) in &values {
        sum += aster_fem::elga::weighted_square_sum(&layout.cells[c].points, v, &coef);
    }
    let group = if occ.contains("TOUT") {
        "-".to_string()
    } else {
        occ.str("GROUP_MA").unwrap_or("-").to_string()
    };
    table.push_row(vec![
        ("CHAM_GD", Value::Text(f.name.clone())),
        ("GROUP_MA", Value::Text(group)),
        (
            "TYPE_MAIL",
            Value::Text(type_maille.unwrap_or("-").to_string()),
        ),
        ("TYPE_NORM", Value::Text("L2".into())),
        ("VALE_NORM", Value::Real(sum.sqrt())),
    ]);
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// `POST_ELEM/INTEGRALE` of a result's field (code_aster's `peeint` →
/// `peecal`, the weights of `chpond`): for each occurrence, each selected
/// step and each place (`TOUT`, each `GROUP_MA`, then their union
/// `UNION_GROUP_MA` when there are several), over the model's cells of the
/// place (of dimension `TYPE_MAILLE` when given) and for each `NOM_CMP`:
/// INTE = Σ v·w and VOL = Σ w over the points that carry the component,
/// MOYE = INTE/VOL. The weights: at Gauss points (`ELGA`) `COOR_ELGA`'s
/// w·|J| (·r on an axisymmetric model); at nodes (`ELNO`, and a nodal field
/// which code_aster first spreads to its cells' nodes) the cell's measure
/// (Σ of those weights) over its number of nodes — a cell's mean of nodal
/// values, not a quadrature. Columns: NOM_CHAM, NUME_ORDRE, INST, VOL, the
/// place's (`TOUT` or `GROUP_MA`), INTE_<cmp>… then MOYE_<cmp>…; of a field
/// (`CHAM_GD`), one row per place: CHAM_GD, VOL, the place's, INTE_, MOYE_.
fn integrale(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "POST_ELEM/INTEGRALE";
    let kw = &call.keywords;
    let (source, mesh, axis) = integrale_field::source(ex, call)?;
    let mut table = integrale_field::table(&source);
    for occ in kw.factor("INTEGRALE") {
        let at = |k: &str| occ.keyword(k).map(|k| k.span).unwrap_or(call.span);
        let nom_cham = match &source {
            integrale_field::Source::Field(name, ..) => name.clone(),
            integrale_field::Source::Result(..) => match occ.str("NOM_CHAM") {
                Some(n) => n.to_string(),
                // code_aster's POSTELEM_4.
                None => {
                    return Err(ExecError::new(format!(
                        "{cmd}: NOM_CHAM is needed with RESULTAT"
                    )))
                }
            },
        };
        if matches!(nom_cham.as_str(), "FORC_NODA" | "REAC_NODA") {
            // code_aster's POSTELEM_5.
            return Err(ex.kw_error(
                cmd,
                occ,
                "NOM_CHAM",
                "FORC_NODA and REAC_NODA cannot be integrated",
            ));
        }
        let cmps: Vec<String> = occ
            .simple("NOM_CMP")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        if cmps.is_empty() {
            return Err(ex.unsupported(
                "POST_ELEM/INTEGRALE without NOM_CMP (NOM_VARI: internal variables by name)",
                at("INTEGRALE"),
            ));
        }
        // The occurrence's cells (the reduced model of `exlim1`).
        let dim_filter = occ.str("TYPE_MAILLE").map(|t| match t {
            "1D" => 1,
            "2D" => 2,
            _ => 3,
        });
        let keep = |c: &CellId| {
            source.in_model(*c) && dim_filter.is_none_or(|d| mesh.cell(*c).ty.dim() as usize == d)
        };
        let mut places: Vec<(&str, String, Vec<CellId>)> = Vec::new();
        if occ.contains("TOUT") {
            let cells: Vec<CellId> = source.model_cells().into_iter().filter(keep).collect();
            places.push(("TOUT", "TOUT".into(), cells));
        }
        let groups: Vec<String> = occ
            .simple("GROUP_MA")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        let mut union: std::collections::BTreeSet<CellId> = Default::default();
        for g in &groups {
            let cells = crate::select::group_ma(&mesh, g)
                .map_err(|e| ex.kw_error(cmd, occ, "GROUP_MA", e))?;
            let cells: Vec<CellId> = cells.iter().copied().filter(keep).collect();
            union.extend(cells.iter().copied());
            places.push(("GROUP_MA", g.clone(), cells));
        }
        if groups.len() > 1 {
            places.push((
                "GROUP_MA",
                "UNION_GROUP_MA".into(),
                union.into_iter().collect(),
            ));
        }
        if dim_filter.is_some() && places.iter().all(|p| p.2.is_empty()) {
            // code_aster's PREPOST2_8.
            return Err(ex.kw_error(cmd, occ, "TYPE_MAILLE", "no cell of that dimension"));
        }
        // The points and weights of every cell used (COOR_ELGA).
        let mut weights: HashMap<CellId, Vec<f64>> = HashMap::new();
        for (_, _, cells) in &places {
            for &c in cells {
                if weights.contains_key(&c) {
                    continue;
                }
                let Some(w) = source.weights(ex, c, axis, at("INTEGRALE"))? else {
                    continue;
                };
                weights.insert(c, w);
            }
        }
        for (step, field) in source.fields(&nom_cham)? {
            let mut row_values: Vec<(String, f64, f64)> = Vec::new();
            for (lieu, name, cells) in &places {
                let mut vol0 = 0.0;
                row_values.clear();
                for (k, cmp) in cmps.iter().enumerate() {
                    let (mut val, mut vol, mut count) = (0.0, 0.0, 0usize);
                    for c in cells {
                        let Some(w) = weights.get(c) else { continue };
                        let measure: f64 = w.iter().sum();
                        match field {
                            crate::field::Field::Nodal(n) => {
                                let nodes = &mesh.cell(*c).nodes;
                                for node in nodes.iter() {
                                    if let Some(v) = n.get(*node, cmp).filter(|v| !v.is_nan()) {
                                        val += v * measure / nodes.len() as f64;
                                        vol += measure / nodes.len() as f64;
                                        count += 1;
                                    }
                                }
                            }
                            crate::field::Field::Elem(e) => {
                                let Some(ic) = e.components().iter().position(|x| x == cmp) else {
                                    continue;
                                };
                                let Some(points) = e.cell(*c) else { continue };
                                let gauss = e.location == crate::field::ElemLocation::Gauss;
                                if gauss && points.len() != w.len() {
                                    return Err(ExecError::new(format!(
                                        "{cmd}: cell {} has {} points in {nom_cham} and {} in its element's family",
                                        crate::select::cell_name(&mesh, *c),
                                        points.len(),
                                        w.len()
                                    )));
                                }
                                for (p, vals) in points.iter().enumerate() {
                                    let v = vals[ic];
                                    if v.is_nan() {
                                        continue;
                                    }
                                    let wt = if gauss {
                                        w[p]
                                    } else {
                                        measure / points.len() as f64
                                    };
                                    val += v * wt;
                                    vol += wt;
                                    count += 1;
                                }
                            }
                        }
                    }
                    if count == 0 && !cells.is_empty() {
                        // code_aster's UTILITAI7_12.
                        return Err(ex.kw_error(
                            cmd,
                            occ,
                            "NOM_CMP",
                            format!(
                                "field {nom_cham} has no component {cmp} on the cells of {name}"
                            ),
                        ));
                    }
                    if k == 0 {
                        vol0 = vol;
                    }
                    row_values.push((cmp.clone(), val, vol));
                }
                // `peecal`'s order: the place, the INTE_ then the MOYE_.
                table.ensure_column(lieu, ColumnType::Text(16));
                for prefix in ["INTE_", "MOYE_"] {
                    for (cmp, _, _) in &row_values {
                        table.ensure_column(&format!("{prefix}{cmp}"), ColumnType::Real);
                    }
                }
                let names: Vec<(String, String)> = row_values
                    .iter()
                    .map(|(c, _, _)| (format!("INTE_{c}"), format!("MOYE_{c}")))
                    .collect();
                let mut row: Vec<(&str, Value)> = match step {
                    Some((order, inst)) => vec![
                        ("NOM_CHAM", Value::Text(nom_cham.clone())),
                        ("NUME_ORDRE", Value::Int(order as i64)),
                        ("INST", Value::Real(inst)),
                    ],
                    None => vec![("CHAM_GD", Value::Text(nom_cham.clone()))],
                };
                row.push(("VOL", Value::Real(vol0)));
                row.push((lieu, Value::Text(name.clone())));
                for ((inte, moye), (_, val, vol)) in names.iter().zip(&row_values) {
                    row.push((inte.as_str(), Value::Real(*val)));
                    row.push((moye.as_str(), Value::Real(val / vol)));
                }
                table.push_row(row);
            }
        }
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

fn col(name: &str, ty: ColumnType) -> Column {
    Column {
        name: name.to_string(),
        ty,
    }
}

/// Where a row sums: the whole model, or a group of cells.
enum Place {
    All,
    Group(String, Vec<CellId>),
}

impl Place {
    fn lieu(&self, mesh_name: &str) -> String {
        match self {
            Place::All => mesh_name.to_string(),
            Place::Group(g, _) => g.clone(),
        }
    }

    fn entite(&self) -> &'static str {
        match self {
            Place::All => "TOUT",
            Place::Group(..) => "GROUP_MA",
        }
    }

    /// The sum over the place and its share of the total (`peenca`).
    fn sum(&self, energies: &HashMap<CellId, f64>, model: &Model) -> (f64, f64) {
        let total: f64 = model
            .elements()
            .iter()
            .filter_map(|e| energies.get(&e.cell))
            .sum();
        match self {
            Place::All => (total, 100.0),
            Place::Group(_, cells) => {
                let v: f64 = cells.iter().filter_map(|c| energies.get(c)).sum();
                let percent = if v < f64::EPSILON && total < f64::EPSILON {
                    0.0
                } else {
                    100.0 * v / total
                };
                (v, percent)
            }
        }
    }
}

/// The places of every occurrence of the factor keyword, in order.
fn places(ex: &Executor, kw: &Keywords, factor: &str) -> Result<Vec<Place>, ExecError> {
    let mut out = Vec::new();
    let mesh: Option<std::sync::Arc<Mesh>> = match (kw.concept("RESULTAT"), kw.concept("MODELE")) {
        (_, Some(m)) => Some(ex.mesh_by_id(ex.model(m)?.mesh)?),
        (Some(r), None) => Some(ex.mesh_by_id(ex.result(r)?.mesh)?),
        _ => None,
    };
    for occ in kw.factor(factor) {
        if occ.contains("TOUT") {
            out.push(Place::All);
        }
        for g in occ.simple("GROUP_MA").iter().filter_map(|s| s.as_str()) {
            let Some(mesh) = &mesh else {
                return Err(ExecError::new(format!(
                    "POST_ELEM/{factor}: no mesh to find group `{g}` in"
                )));
            };
            let group = crate::select::group_ma(mesh, g)
                .map_err(|e| ex.kw_error("POST_ELEM", occ, "GROUP_MA", e))?;
            out.push(Place::Group(g.to_string(), group.to_vec()));
        }
    }
    Ok(out)
}

/// The fem model a result was computed with, or the one `MODELE` +
/// `CHAM_MATER` (+ `CARA_ELEM`) describe; and the mesh's name.
fn result_model(
    ex: &Executor,
    kw: &Keywords,
    r: &aster_eval::ConceptRef,
    result: &EvolResult,
) -> Result<(Rc<ModelRef>, String), ExecError> {
    if kw.contains("MODELE") {
        let (m, name) = model_from_keywords(ex, kw)?;
        return Ok((Rc::new(ModelRef::Own(Box::new(m))), name));
    }
    let Some(run) = result.fem.clone() else {
        return Err(ExecError::new(format!(
            "POST_ELEM: result `{}` was not computed in this run: give MODELE and CHAM_MATER",
            r.name
        )));
    };
    let name = ex.internal_name(result.mesh);
    Ok((Rc::new(ModelRef::Run(run)), name))
}

/// A model owned here or the one of a computed result.
enum ModelRef {
    Own(Box<Model>),
    Run(Rc<crate::fembridge::FemRun>),
}

impl std::ops::Deref for ModelRef {
    type Target = Model;
    fn deref(&self) -> &Model {
        match self {
            ModelRef::Own(m) => m,
            ModelRef::Run(r) => &r.model,
        }
    }
}

fn model_from_keywords(ex: &Executor, kw: &Keywords) -> Result<(Model, String), ExecError> {
    let model = ex.model(ex.required("POST_ELEM", kw, "MODELE")?)?;
    let materials = ex.material_field(ex.required("POST_ELEM", kw, "CHAM_MATER")?)?;
    let cara = match kw.concept("CARA_ELEM") {
        Some(c) => Some(ex.cara_elem(c)?),
        None => None,
    };
    let mesh = ex.model_mesh(&model)?;
    let name = ex.internal_name(model.mesh);
    let m = crate::fembridge::build_model(&mesh, &model, &materials, cara.as_deref())?;
    Ok((m, name))
}

/// The displacement (per DOF of the model) of a result at a NUME_ORDRE.
fn displacement(
    ex: &Executor,
    result: &EvolResult,
    model: &ModelRef,
    order: u32,
    name: &str,
) -> Result<Vec<f64>, ExecError> {
    if let ModelRef::Run(run) = model {
        if let Some(step) = run.raw.by_order(order as usize) {
            return Ok(step.displacement.clone());
        }
    }
    let _ = ex;
    let step = result
        .step_numbered(order)
        .ok_or_else(|| ExecError::new(format!("POST_ELEM: no NUME_ORDRE {order} in `{name}`")))?;
    match super::post::step_field(step, "DEPL", name)? {
        crate::field::Field::Nodal(depl) => Ok(crate::fembridge::displacement_from(model, depl)),
        _ => Err(ExecError::new(format!(
            "POST_ELEM: DEPL of `{name}` is not a nodal field"
        ))),
    }
}

fn energies(model: &Model, u: &[f64]) -> Result<HashMap<CellId, f64>, ExecError> {
    Ok(aster_fem::energy::potential_energy_by_cell(model, u)
        .map_err(|e| ExecError::new(format!("POST_ELEM: {e}")))?
        .into_iter()
        .collect())
}
