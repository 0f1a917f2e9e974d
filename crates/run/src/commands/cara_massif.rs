//! `AFFE_CARA_ELEM/MASSIF`: the material frame of the continuum cells
//! (code_aster's `aceama`), used by the orthotropic materials
//! (`DEFI_MATERIAU/ELAS_ORTH`, [`aster_fem::orthotropic`]).
//!
//! - `ANGL_REP` (1 to 3 values, degrees): the nautical angles α, β, γ
//!   (missing ones 0);
//! - `ANGL_EULER` (3 values, degrees): Euler angles ψ, θ, φ turned into
//!   nautical ones by code_aster's `eulnau` (code_aster reads three values
//!   whatever is given: fewer are refused here);
//! - a later occurrence replaces an earlier one on a cell; a cell without
//!   occurrence keeps the global frame. In 2D only α counts (`rcangm`).
//!
//! `ORIG_AXE`/`ANGL_AXE` (cylindrical frames) and `CHAM_ORIE` are refused
//! before the run (not in [`KEYWORDS`]).

use crate::executor::Executor;
use crate::select;
use aster_eval::{ExecError, Keywords};
use aster_mesh::{CellId, Mesh};

/// One `MASSIF` occurrence resolved on the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct MassifFrame {
    pub cells: Vec<CellId>,
    /// Nautical angles α, β, γ in radians.
    pub angles: [f64; 3],
}

/// The `MASSIF` keywords AFFE_CARA_ELEM reads (`crate::support`).
pub(crate) const KEYWORDS: [&str; 5] = [
    "MASSIF",
    "MASSIF/GROUP_MA",
    "MASSIF/MAILLE",
    "MASSIF/ANGL_REP",
    "MASSIF/ANGL_EULER",
];

/// The `MASSIF` occurrences of an AFFE_CARA_ELEM call.
pub(crate) fn frames(
    ex: &Executor,
    kw: &Keywords,
    mesh: &Mesh,
) -> Result<Vec<MassifFrame>, ExecError> {
    let mut out = Vec::new();
    for occ in kw.factor("MASSIF") {
        let err = |key: &str, m: String| ex.kw_error("AFFE_CARA_ELEM/MASSIF", occ, key, m);
        let rep = super::define::reals(occ, "ANGL_REP");
        let euler = super::define::reals(occ, "ANGL_EULER");
        let degrees = match (rep.is_empty(), euler.is_empty()) {
            (false, true) => {
                if rep.len() > 3 {
                    return Err(err(
                        "ANGL_REP",
                        format!("ANGL_REP takes 1 to 3 angles, got {}", rep.len()),
                    ));
                }
                let mut a = [0.0; 3];
                a[..rep.len()].copy_from_slice(&rep);
                a
            }
            (true, false) => {
                if euler.len() != 3 {
                    return Err(err(
                        "ANGL_EULER",
                        format!(
                            "ANGL_EULER needs the three angles ψ, θ, φ here, got {} (code_aster reads three whatever is given)",
                            euler.len()
                        ),
                    ));
                }
                aster_fem::orthotropic::euler_to_nautical([euler[0], euler[1], euler[2]])
            }
            _ => {
                return Err(ex.kw_error(
                    "AFFE_CARA_ELEM",
                    occ,
                    "ANGL_REP",
                    "MASSIF needs one of ANGL_REP and ANGL_EULER",
                ))
            }
        };
        if let Some(a) = degrees.iter().find(|a| !a.is_finite()) {
            return Err(err("ANGL_REP", format!("the angle {a} is not finite")));
        }
        let cells = select::cells(occ, mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_CARA_ELEM/MASSIF: {e}")))?;
        out.push(MassifFrame {
            cells,
            angles: degrees.map(f64::to_radians),
        });
    }
    Ok(out)
}
