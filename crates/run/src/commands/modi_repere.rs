//! `MODI_REPERE` of a result's nodal fields (code_aster's `op0191` →
//! `modirepresu` → `chrpno`): the vectors (`VECT_2D`, `VECT_3D`: DX DY DZ
//! [DRX DRY DRZ], FLUX FLUY FLUZ) and symmetric tensors (`TENS_2D`,
//! `TENS_3D`: SIXX… or EPXX…) of `MODI_CHAM/NOM_CHAM` written in another
//! frame, node by node:
//!
//! - `REPERE='UTILISATEUR'`, `AFFE=_F(ANGL_NAUT)`: `matrot` of the nautical
//!   angles (degrees; one angle about z on a plane mesh, three in 3D), its
//!   rows the new axes: v' = P v, σ' = P σ Pᵀ.
//! - `REPERE='CYLINDRIQUE'`, `AFFE=_F(ORIGINE, AXE_Z)`: at each node the
//!   rows (e_r, e_z, e_θ), e_r the node's position from ORIGINE without
//!   its part along AXE_Z (z on a plane mesh), e_θ = e_z × e_r. The tensor
//!   is written in code_aster's order: SIXX = σ_rr, SIYY = σ_zz, SIZZ =
//!   σ_θθ, SIXY = σ_zr, SIXZ = σ_θr, SIYZ = σ_θz — on a plane mesh
//!   (`TENS_2D`) SIXY is σ_θr (`licmpu` 1 2 3 5), SIYY the out-of-plane
//!   σ_zz and SIZZ the hoop stress.
//!
//! The new field keeps the transformed components only (`selectCompN` +
//! `cnsred`); a node missing one of them gets none. The new result holds
//! the selected steps with the transformed fields only.
//!
//! Refused with their keyword: `CHAM_GD`, element fields (`chrpel`),
//! `COQUE_GENE`/`1D_GENE`, the shell frames (`COQUE*`, `GLOBAL_UTIL`),
//! `VECT_X`/`VECT_Y`, `AFFE` on groups, and `VECT_2D` in the cylindrical
//! frame; a node on the cylinder's axis (code_aster then takes the centre
//! of a cell around it) is an error.

use crate::concept::{Concept, EvolResult, Step};
use crate::executor::{store_result, Executor};
use crate::field::{Field, NodalField};
use crate::support::{joined, Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_mesh::{Mesh, NodeId};
use std::rc::Rc;

const KEYWORDS: &[&str] = &[
    "RESULTAT",
    "MODI_CHAM",
    "MODI_CHAM/NOM_CHAM",
    "MODI_CHAM/TYPE_CHAM",
    "MODI_CHAM/TOUT",
    "REPERE",
    "AFFE",
    "AFFE/TOUT",
    "AFFE/ANGL_NAUT",
    "AFFE/ORIGINE",
    "AFFE/AXE_Z",
    "INFO",
    "TITRE",
];

/// What MODI_REPERE reads (`crate::support`).
pub(crate) const MODI_REPERE: Support = Support {
    values: &[
        Values::listed("REPERE", &["UTILISATEUR", "CYLINDRIQUE"])
            .why("(the shell frames COQUE, COQUE_*, GLOBAL_UTIL are not implemented)"),
        Values::listed(
            "MODI_CHAM/TYPE_CHAM",
            &["VECT_2D", "VECT_3D", "TENS_2D", "TENS_3D"],
        )
        .why("(the generalised efforts and strains of shells and beams, COQUE_GENE and 1D_GENE, are not implemented)"),
    ],
    hints: &[
        ("CHAM_GD", "only the fields of a RESULTAT are turned"),
        (
            "AFFE/VECT_X",
            "give the frame by ANGL_NAUT (code_aster's angvxy is not reproduced)",
        ),
        ("AFFE/GROUP_MA", "only AFFE=_F(TOUT='OUI') is implemented"),
        ("AFFE/GROUP_NO", "only AFFE=_F(TOUT='OUI') is implemented"),
        ("MODI_CHAM/GROUP_MA", "only the whole field is turned"),
    ],
    reuse: false,
    rules: None,
    ..Support::keywords(&joined::<_, { KEYWORDS.len() + crate::commands::post::STEP_SELECTION.len() }>(
        KEYWORDS,
        crate::commands::post::STEP_SELECTION,
    ))
};

const CMD: &str = "MODI_REPERE";

/// The new frame at each node.
enum Frame {
    /// One rotation for every node (rows: the new axes).
    Fixed([[f64; 3]; 3]),
    /// Cylindrical: origin and unit axis.
    Cylinder { origin: [f64; 3], axis: [f64; 3] },
}

/// What a `MODI_CHAM` occurrence turns: the components (code_aster's
/// `selectCompN`) and whether they form a tensor.
struct Turned {
    name: String,
    tensor: bool,
    components: Vec<&'static str>,
}

const SIEF: [&str; 6] = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
const EPSI: [&str; 6] = ["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ"];
const DEPL: [&str; 6] = ["DX", "DY", "DZ", "DRX", "DRY", "DRZ"];
const FLUX: [&str; 3] = ["FLUX", "FLUY", "FLUZ"];

/// `selectCompN`: the components of a field a type turns, or why not.
fn components(f: &NodalField, type_cham: &str) -> Result<(bool, Vec<&'static str>), String> {
    let two = type_cham.ends_with("2D");
    let has = |c: &str| f.component_index(c).is_some();
    if type_cham.starts_with("TENS") {
        let n = if two { 4 } else { 6 };
        let names = if has("SIXX") {
            &SIEF
        } else if has("EPXX") {
            &EPSI
        } else {
            return Err(format!(
                "{type_cham} turns stress or strain fields (SIXX…, EPXX…)"
            ));
        };
        if let Some(m) = names[..n].iter().find(|c| !has(c)) {
            return Err(format!("the field has no {m} (ALGORITH2_12)"));
        }
        return Ok((true, names[..n].to_vec()));
    }
    let (names, required): (&[&'static str], usize) = if has("DX") {
        (&DEPL, if two { 2 } else { 3 })
    } else if has("FLUX") {
        (&FLUX, if two { 2 } else { 3 })
    } else {
        return Err(format!(
            "{type_cham} turns DX DY DZ or FLUX FLUY FLUZ fields"
        ));
    };
    if let Some(m) = names[..required].iter().find(|c| !has(c)) {
        return Err(format!("the field has no {m} (ALGORITH2_12)"));
    }
    // VECT_3D takes the rotations too when the field has them all.
    let n = if !two && names.len() == 6 && names[3..].iter().all(|c| has(c)) {
        6
    } else if two && names.len() == 3 {
        3.min(if has("FLUZ") { 3 } else { 2 })
    } else {
        required
    };
    Ok((false, names[..n].to_vec()))
}

fn unit(v: [f64; 3]) -> ([f64; 3], f64) {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n > 0.0 {
        (v.map(|c| c / n), n)
    } else {
        (v, 0.0)
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl Frame {
    /// The rows of the frame at a node (`None`: the node is on the axis).
    fn at(&self, x: [f64; 3], plane: bool) -> Option<[[f64; 3]; 3]> {
        match self {
            Frame::Fixed(p) => Some(*p),
            Frame::Cylinder { origin, axis } => {
                let mut r = [x[0] - origin[0], x[1] - origin[1], x[2] - origin[2]];
                if plane {
                    r[2] = 0.0;
                }
                let along = r[0] * axis[0] + r[1] * axis[1] + r[2] * axis[2];
                for k in 0..3 {
                    r[k] -= along * axis[k];
                }
                if plane {
                    r[2] = 0.0;
                }
                let (r, norm) = unit(r);
                if norm < 1e-6 {
                    return None;
                }
                let (t, _) = unit(cross(*axis, r));
                Some([r, *axis, t])
            }
        }
    }
}

/// σ' = P σ Pᵀ of (XX, YY, ZZ, XY, XZ, YZ), written back in the order
/// `order` of the pairs of new axes (code_aster's `utpsgl` and the
/// unpacking of `chrpno`).
fn turn_tensor(p: &[[f64; 3]; 3], s: [f64; 6], order: &[(usize, usize)]) -> Vec<f64> {
    let [xx, yy, zz, xy, xz, yz] = s;
    let m = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
    order
        .iter()
        .map(|&(a, b)| {
            let mut v = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    v += p[a][i] * m[i][j] * p[b][j];
                }
            }
            v
        })
        .collect()
}

/// v' = P v on each triple (`utpvgl`), or on the plane's two components
/// (`ut2vgl`: the upper-left 2 × 2 of P).
fn turn_vector(p: &[[f64; 3]; 3], v: &[f64], plane: bool) -> Vec<f64> {
    let mut out = v.to_vec();
    if plane {
        for i in 0..2 {
            out[i] = p[i][0] * v[0] + p[i][1] * v[1];
        }
        return out;
    }
    for start in (0..v.len()).step_by(3) {
        if start + 3 > v.len() {
            break;
        }
        for i in 0..3 {
            out[start + i] = (0..3).map(|k| p[i][k] * v[start + k]).sum();
        }
    }
    out
}

/// One field in the new frame (`chrpno`).
fn turn_field(
    f: &NodalField,
    what: &Turned,
    frame: &Frame,
    mesh: &Mesh,
    plane: bool,
) -> Result<NodalField, String> {
    let comps: Vec<String> = what.components.iter().map(|c| c.to_string()).collect();
    let idx: Vec<usize> = what
        .components
        .iter()
        .map(|c| f.component_index(c).unwrap_or(usize::MAX))
        .collect();
    let mut out = NodalField::with_node_count(comps, mesh.node_count());
    let cylinder = matches!(frame, Frame::Cylinder { .. });
    for (node, values) in f.iter() {
        let v: Option<Vec<f64>> = idx.iter().map(|&i| values.get(i)).collect();
        let Some(v) = v else { continue };
        let Some(p) = frame.at(mesh.coord(node), plane) else {
            return Err(format!(
                "node {} is on the cylinder's axis (code_aster then takes the centre of a cell around it: not reproduced)",
                mesh.node_name(node)
            ));
        };
        let new = if what.tensor {
            let mut s = [0.0; 6];
            s[..v.len()].copy_from_slice(&v);
            let order: &[(usize, usize)] = match (cylinder, v.len()) {
                (true, 4) => &[(0, 0), (1, 1), (2, 2), (2, 0)],
                (true, _) => &[(0, 0), (1, 1), (2, 2), (1, 0), (2, 0), (2, 1)],
                (false, 4) => &[(0, 0), (1, 1), (2, 2), (1, 0)],
                (false, _) => &[(0, 0), (1, 1), (2, 2), (1, 0), (2, 0), (2, 1)],
            };
            turn_tensor(&p, s, order)
        } else {
            turn_vector(&p, &v, plane)
        };
        insert(&mut out, node, new);
    }
    Ok(out)
}

fn insert(f: &mut NodalField, node: NodeId, values: Vec<f64>) {
    f.insert(node, values.into_iter().map(Some));
}

/// The frame of the `AFFE` occurrence (only one, on every node).
fn frame(ex: &Executor, kw: &Keywords, repere: &str, plane: bool) -> Result<Frame, ExecError> {
    let [occ] = kw.factor("AFFE") else {
        return Err(ex.kw_error(
            CMD,
            kw,
            "AFFE",
            "one AFFE occurrence with TOUT='OUI' is implemented",
        ));
    };
    if occ.str("TOUT") != Some("OUI") {
        return Err(ex.kw_error(CMD, occ, "AFFE", "only TOUT='OUI' is implemented"));
    }
    let reals =
        |name: &str| -> Vec<f64> { occ.simple(name).iter().filter_map(|s| s.as_f64()).collect() };
    if repere == "UTILISATEUR" {
        let a = reals("ANGL_NAUT");
        let angles = if plane {
            [a.first().copied().unwrap_or(0.0), 0.0, 0.0]
        } else {
            let [x, y, z] = a[..] else {
                return Err(ex.kw_error(
                    CMD,
                    occ,
                    "ANGL_NAUT",
                    "three nautical angles in 3D (ALGORITH2_7)",
                ));
            };
            [x, y, z]
        };
        return Ok(Frame::Fixed(aster_fem::orthotropic::matrot(
            angles.map(f64::to_radians),
        )));
    }
    let o = reals("ORIGINE");
    let (origin, axis) = if plane {
        let [x, y] = o[..] else {
            return Err(ex.kw_error(CMD, occ, "ORIGINE", "two coordinates on a plane mesh"));
        };
        ([x, y, 0.0], [0.0, 0.0, 1.0])
    } else {
        let [x, y, z] = o[..] else {
            return Err(ex.kw_error(CMD, occ, "ORIGINE", "three coordinates in 3D (ALGORITH2_8)"));
        };
        let Ok::<[f64; 3], _>(a) = reals("AXE_Z").try_into() else {
            return Err(ex.kw_error(
                CMD,
                occ,
                "AXE_Z",
                "the axis is required in 3D (ALGORITH2_9)",
            ));
        };
        let (a, n) = unit(a);
        if n == 0.0 {
            return Err(ex.kw_error(CMD, occ, "AXE_Z", "a zero axis"));
        }
        ([x, y, z], a)
    };
    Ok(Frame::Cylinder { origin, axis })
}

pub fn modi_repere(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let r = ex.required(CMD, kw, "RESULTAT")?.clone();
    let result = ex.result(&r)?;
    let mesh = ex.mesh_by_id(result.mesh)?;
    // code_aster's `Z_CST`: a mesh whose nodes share one z is plane.
    let plane = mesh
        .coords
        .first()
        .is_none_or(|c0| mesh.coords.iter().all(|c| c[2] == c0[2]));
    let repere = kw.str("REPERE").unwrap_or("UTILISATEUR");
    let frame = frame(ex, kw, repere, plane)?;
    let steps = crate::commands::post::select_steps(ex, CMD, kw, &result)?;
    if steps.is_empty() {
        return Err(ex.kw_error(CMD, kw, "RESULTAT", "no step selected"));
    }
    let mut out_steps: Vec<Step> = steps
        .iter()
        .map(|s| Step {
            nume_ordre: s.nume_ordre,
            inst: s.inst,
            fields: Default::default(),
        })
        .collect();
    for occ in kw.factor("MODI_CHAM") {
        let name = occ.str("NOM_CHAM").unwrap_or_default().to_string();
        let type_cham = occ.str("TYPE_CHAM").unwrap_or_default();
        let two = type_cham.ends_with("2D");
        if !plane && two {
            return Err(ex.kw_error(
                CMD,
                occ,
                "TYPE_CHAM",
                format!("{type_cham} on a 3D mesh (ALGORITH12_45)"),
            ));
        }
        // A 3D type on a plane mesh turns in 3D (code_aster's alarm
        // ALGORITH12_44).
        let plane_turn = plane && two;
        if repere == "CYLINDRIQUE" && !type_cham.starts_with("TENS") && plane_turn {
            let span = occ
                .keyword("TYPE_CHAM")
                .map(|k| k.span)
                .unwrap_or(call.span);
            return Err(ex.unsupported(
                "MODI_REPERE/TYPE_CHAM='VECT_2D' with REPERE='CYLINDRIQUE' (ut2vgl on the (r, z, θ) rows is not checked)",
                span,
            ));
        }
        for (s, out) in steps.iter().zip(out_steps.iter_mut()) {
            let Some(field) = s.fields.get(&name) else {
                return Err(ex.kw_error(
                    CMD,
                    occ,
                    "NOM_CHAM",
                    format!(
                        "the result has no field {name} at NUME_ORDRE {}",
                        s.nume_ordre
                    ),
                ));
            };
            let Field::Nodal(f) = field else {
                let span = occ.keyword("NOM_CHAM").map(|k| k.span).unwrap_or(call.span);
                return Err(ex.unsupported(
                    &format!("MODI_REPERE of the element field {name} (code_aster's chrpel)"),
                    span,
                ));
            };
            let (tensor, components) =
                components(f, type_cham).map_err(|e| ex.kw_error(CMD, occ, "TYPE_CHAM", e))?;
            let what = Turned {
                name: name.clone(),
                tensor,
                components,
            };
            let turned = turn_field(f, &what, &frame, &mesh, plane_turn)
                .map_err(|e| ex.kw_error(CMD, occ, "NOM_CHAM", e))?;
            out.fields.insert(what.name, Field::Nodal(turned));
        }
    }
    let turned = EvolResult {
        prep_varc: false,
        typ: result.typ.clone(),
        mesh: result.mesh,
        steps: out_steps,
        fem: None,
        tables: Vec::new(),
        modal: result.modal.clone(),
        cases: result.cases.clone(),
        thermal: None,
    };
    store_result(ex, call, Concept::Result(Rc::new(turned)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A uniaxial σ_xx = 1 at (0, 1) in the cylindrical frame about the
    /// origin: e_r = y, e_θ = z × y = −x, so σ_θθ (SIZZ) = 1, σ_rr = 0,
    /// and code_aster's SIXY is σ_θr = 0; at (1, 1)/√2: all ½, σ_θr −½.
    #[test]
    fn cylindrical_tensor_in_code_aster_order() {
        let f = Frame::Cylinder {
            origin: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
        };
        let order = [(0, 0), (1, 1), (2, 2), (2, 0)];
        let p = f.at([0.0, 1.0, 0.0], true).unwrap();
        let t = turn_tensor(&p, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0], &order);
        for (a, b) in t.iter().zip([0.0, 0.0, 1.0, 0.0]) {
            assert!((a - b).abs() < 1e-15, "{t:?}");
        }
        let p = f.at([1.0, 1.0, 0.0], true).unwrap();
        let t = turn_tensor(&p, [1.0, 0.0, 0.5, 0.0, 0.0, 0.0], &order);
        for (a, b) in t.iter().zip([0.5, 0.5, 0.5, -0.5]) {
            assert!((a - b).abs() < 1e-15, "{t:?}");
        }
        assert!(f.at([0.0, 0.0, 0.0], true).is_none());
    }

    /// matrot(α) about z: v' = (cos α vx + sin α vy, −sin α vx + cos α vy).
    #[test]
    fn user_frame_turns_a_plane_vector() {
        let p = aster_fem::orthotropic::matrot([30f64.to_radians(), 0.0, 0.0]);
        let v = turn_vector(&p, &[1.0, 0.0], true);
        assert!((v[0] - 30f64.to_radians().cos()).abs() < 1e-15);
        assert!((v[1] + 0.5).abs() < 1e-15, "{v:?}");
        let v = turn_vector(&p, &[0.0, 0.0, 1.0, 1.0, 0.0, 0.0], false);
        assert!(
            (v[2] - 1.0).abs() < 1e-15 && (v[4] + 0.5).abs() < 1e-15,
            "{v:?}"
        );
    }
}
