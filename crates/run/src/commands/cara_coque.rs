//! `AFFE_CARA_ELEM/COQUE`: the sections of the shell cells (`DKT`,
//! `COQUE_3D`) — thickness `EPAIS`, drilling coefficient `COEF_RIGI_DRZ`,
//! COQUE_3D's `A_CIS` and `COQUE_NCOU` — and the
//! reference direction of their efforts (`ANGL_REP` or `VECTEUR`: the x
//! axis of the user's frame is its projection on each facet, code_aster's
//! `coqrep`).
//!
//! Read here, handed to aster-fem as [`aster_fem::ShellSection`] and a
//! direction per cell. `EXCENTREMENT` (the offset e of the section's
//! mid-surface from the cells' plane, along their normal) couples
//! membrane and bending as `dxmate` does (B = e·A, D + e²·A) on the DKT
//! and DKQ facets; on DST, Q4G (their own coupling terms, `dstrig`,
//! `q4grig`, are not reproduced) and COQUE_3D cells (code_aster refuses
//! it there, te0119) it is refused at the keyword. Not reproduced, so
//! refused by the support table: `EPAIS_FO`, `EXCENTREMENT_FO`,
//! `MODI_METRIQUE='OUI'` (COQUE_3D only). `INER_ROTA='OUI'`
//! adds the rotary inertia ρh³/12 to the DKT masses (`dktmas`, `dkqmas`)
//! and changes no stiffness (COQUE_3D has no mass here: no effect).
//! `COQUE_NCOU` (the layers of the stresses through the thickness) and
//! `A_CIS` (the shear coefficient of DST/Q4G) do not change a DKT's
//! stiffness: accepted; a COQUE_3D integrates its stiffness layer by
//! layer and uses `A_CIS` for its transverse shears.

use crate::concept::{ModelDef, Modelisation};
use crate::executor::Executor;
use crate::select;
use aster_eval::{ExecError, Keywords};
use aster_fem::ShellSection;
use aster_mesh::{CellId, CellType, Mesh};

/// One `COQUE` occurrence resolved on the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct ShellCara {
    pub cells: Vec<CellId>,
    pub section: ShellSection,
    /// The global direction whose projection on a facet is the x axis of
    /// its efforts' frame (`ANGL_REP` α, β: (cos β cos α, cos β sin α,
    /// −sin β); `VECTEUR` as given; by default global X).
    pub direction: [f64; 3],
    /// `COQUE_NCOU`: the layers of the stresses through the thickness
    /// (sub-points of `SIGM_ELNO`, `POST_CHAMP/EXTR_COQUE`); default 1.
    /// COQUE_3D also integrates its stiffness layer by layer.
    pub layers: u32,
    /// `A_CIS`: the transverse shear factor of COQUE_3D (code_aster's
    /// default `0.8333333`); a DKT's stiffness does not use it.
    pub shear_factor: f64,
}

impl ShellCara {
    /// The section of a COQUE_3D cell of this occurrence.
    pub fn coque3d_section(&self) -> aster_fem::coque3d::Coque3dSection {
        aster_fem::coque3d::Coque3dSection {
            thickness: self.section.thickness,
            drilling: self.section.drilling,
            shear_factor: self.shear_factor,
            layers: self.layers,
            rule: aster_fem::coque3d::ThicknessRule::Simpson,
        }
    }
}

/// The `COQUE` keywords AFFE_CARA_ELEM reads (`crate::support`).
pub(crate) const KEYWORDS: [&str; 11] = [
    "COQUE",
    "COQUE/GROUP_MA",
    "COQUE/EPAIS",
    "COQUE/COEF_RIGI_DRZ",
    "COQUE/COQUE_NCOU",
    "COQUE/ANGL_REP",
    "COQUE/VECTEUR",
    "COQUE/A_CIS",
    "COQUE/MODI_METRIQUE",
    "COQUE/INER_ROTA",
    "COQUE/EXCENTREMENT",
];

/// `MODI_METRIQUE='OUI'` is COQUE_3D's.
pub(crate) const VALUES: [crate::support::Values; 1] =
    [crate::support::Values::new("COQUE/MODI_METRIQUE", &["NON"])];

fn reals(kw: &Keywords, name: &str) -> Vec<f64> {
    kw.simple(name).iter().filter_map(|s| s.as_f64()).collect()
}

/// The `COQUE` occurrences of an AFFE_CARA_ELEM call.
pub(crate) fn shells(
    ex: &Executor,
    kw: &Keywords,
    mesh: &Mesh,
    model: &ModelDef,
) -> Result<Vec<ShellCara>, ExecError> {
    let mut out = Vec::new();
    let mut empty: Option<ExecError> = None;
    for occ in kw.factor("COQUE") {
        let err = |key: &str, m: String| ex.kw_error("AFFE_CARA_ELEM", occ, key, m);
        let Some(thickness) = occ.f64("EPAIS") else {
            return Err(err(
                "EPAIS",
                "COQUE needs EPAIS (EPAIS_FO is not supported)".into(),
            ));
        };
        if !(thickness > 0. && thickness.is_finite()) {
            return Err(err(
                "EPAIS",
                format!("EPAIS = {thickness}: a thickness must be positive"),
            ));
        }
        let drilling = occ.f64("COEF_RIGI_DRZ").unwrap_or(1e-5);
        if !(drilling > 0. && drilling.is_finite()) {
            return Err(ex.unsupported(
                &format!(
                    "AFFE_CARA_ELEM/COQUE/COEF_RIGI_DRZ={drilling} (a negative coefficient selects code_aster's other drilling formulation; only the positive spring is reproduced)"
                ),
                occ.keyword("COEF_RIGI_DRZ").map(|k| k.span).unwrap_or_default(),
            ));
        }
        let direction = if occ.keyword("VECTEUR").is_some() {
            let v = reals(occ, "VECTEUR");
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if v.len() != 3 || norm.is_nan() || norm <= 0. {
                return Err(err(
                    "VECTEUR",
                    "VECTEUR needs three components, not all zero".into(),
                ));
            }
            [v[0] / norm, v[1] / norm, v[2] / norm]
        } else {
            let a = reals(occ, "ANGL_REP");
            let (alpha, beta) = match a.as_slice() {
                [] => (0., 0.),
                [a, b] => (a.to_radians(), b.to_radians()),
                _ => return Err(err("ANGL_REP", "ANGL_REP needs two angles (α, β)".into())),
            };
            [
                beta.cos() * alpha.cos(),
                beta.cos() * alpha.sin(),
                -beta.sin(),
            ]
        };
        let layers = match occ.first("COQUE_NCOU").and_then(|v| v.as_i64()) {
            None => 1,
            Some(n) if (1..=i64::from(u16::MAX)).contains(&n) => n as u32,
            Some(n) => {
                return Err(err(
                    "COQUE_NCOU",
                    format!("COQUE_NCOU = {n}: a number of layers must be at least 1"),
                ))
            }
        };
        let given = select::cells(occ, mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_CARA_ELEM/COQUE: {e}")))?;
        // code_aster's COQUE is a field on the given cells that only shell
        // elements read: the others of the group (the SEG2 edges of a
        // `TOUT` group, ssnv115b) are left out; a group without any shell
        // cell is an error.
        let is_shell = |ty: CellType| {
            matches!(
                ty,
                CellType::TRIA3 | CellType::QUAD4 | CellType::QUAD9 | CellType::TRIA7
            )
        };
        let cells: Vec<CellId> = given
            .iter()
            .copied()
            .filter(|&c| is_shell(mesh.cell(c).ty))
            .collect();
        if cells.is_empty() {
            if let Some(bad) = select::misfit(mesh, &given, |c| is_shell(c.ty)) {
                // An occurrence on edges only beside ones on shells reads
                // nothing (ssls504a gives EPAIS on its SEG2 sides too); on
                // its own it is an error.
                empty.get_or_insert(err(
                    "GROUP_MA",
                    format!(
                        "COQUE applies to the DKT cells (TRIA3, QUAD4) and the COQUE_3D cells (QUAD9, TRIA7), but none is given: {bad}"
                    ),
                ));
                continue;
            }
        }
        let shear_factor = occ
            .f64("A_CIS")
            .unwrap_or(aster_fem::coque3d::DEFAULT_SHEAR_FACTOR);
        if !(shear_factor > 0. && shear_factor.is_finite()) {
            return Err(err(
                "A_CIS",
                format!("A_CIS = {shear_factor}: a shear factor must be positive"),
            ));
        }
        let offset = occ.f64("EXCENTREMENT").unwrap_or(0.);
        if !offset.is_finite() {
            return Err(err(
                "EXCENTREMENT",
                format!("EXCENTREMENT = {offset}: an offset must be finite"),
            ));
        }
        if offset != 0. {
            // The offset is reproduced on DKT/DKQ facets and on the
            // DKTG/Q4GG ones (te0409's coupling; an offset Q4GG's mass is
            // refused where it is assembled).
            let other = cells.iter().find_map(|c| match model.cells.get(c) {
                Some(Modelisation::Plate(t))
                    if matches!(t.base(), aster_fem::plate::PlateTheory::Dkt) || t.is_global() =>
                {
                    None
                }
                None => None,
                Some(Modelisation::Plate(t)) => Some((*c, t.name())),
                Some(Modelisation::Coque3d) => Some((*c, "COQUE_3D")),
                Some(_) => None,
            });
            if let Some((c, name)) = other {
                let why = if name == "COQUE_3D" {
                    "code_aster refuses an offset on COQUE_3D (te0119)"
                } else {
                    "its membrane-bending coupling terms (dstrig, dsqrig, q4grig, t3grig) are not reproduced; DKT/DKQ's are"
                };
                return Err(ex.unsupported(
                    &format!(
                        "AFFE_CARA_ELEM/COQUE/EXCENTREMENT on the {name} cell {} ({why})",
                        select::cell_name(mesh, c)
                    ),
                    occ.keyword("EXCENTREMENT")
                        .map(|k| k.span)
                        .unwrap_or_default(),
                ));
            }
        }
        out.push(ShellCara {
            cells,
            section: ShellSection {
                thickness,
                drilling,
                // INER_ROTA='OUI' (its only value): the rotary inertia of
                // the DKT masses (`dktmas`, `dkqmas`); no effect on stiffness.
                rotary_inertia: occ.str("INER_ROTA") == Some("OUI"),
                layered: None,
                offset,
            },
            direction,
            layers,
            shear_factor,
        });
    }
    match empty {
        Some(e) if out.iter().all(|s| s.cells.is_empty()) => Err(e),
        _ => Ok(out),
    }
}
