//! `AFFE_CARA_ELEM/POUTRE`: the sections of the beam (`POU_D_E`,
//! `POU_D_T`) cells, A, IY, IZ, JX and the shear coefficients AY, AZ as
//! code_aster's `affgen` computes them (`coecis`'s tables for the tubes and
//! the hollow rectangles, 1.2 for a solid rectangle).
//!
//! - `SECTION='CERCLE'`: `R` and `EP` (a tube; `EP` absent: solid);
//! - `SECTION='RECTANGLE'`: `HY`/`HZ` or `H` (square), `EPY`/`EPZ` or `EP`
//!   (hollow; absent: solid);
//! - `SECTION='GENERALE'`: `A`, `IY`, `IZ`, `JX` given, `AY`/`AZ` for a
//!   Timoshenko beam (the other characteristics — warping, radii of the
//!   stresses — do not enter these elements; a non-zero `EY`/`EZ` is
//!   refused);
//! - `VARI_SECT='HOMOTHETIQUE'` is accepted when both ends are equal (a
//!   constant section); a varying section is refused at `VARI_SECT`.
//!
//! `AFFE_CARA_ELEM/BARRE`: the cross-section area A of the truss (`BARRE`)
//! cells, from `SECTION='GENERALE'` (`A`), `'CERCLE'` (`R`, `EP`) or
//! `'RECTANGLE'` (`HY`/`HZ` or `H`, `EPY`/`EPZ` or `EP`), the areas of the
//! beams' sections.
//!
//! Read here, handed to aster-fem as [`aster_fem::BeamSection`] and the
//! bars' areas.

use crate::executor::Executor;
use crate::select;
use aster_eval::{ExecError, Keywords};
use aster_fem::BeamSection;
use aster_mesh::{CellId, CellType, Mesh};

/// One `POUTRE` occurrence resolved on the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamCara {
    pub cells: Vec<CellId>,
    pub section: BeamSection,
    /// The outer radius of a circular section (`DEFI_CONTACT/ZONE/
    /// DIST_POUTRE`).
    pub radius: Option<f64>,
}

/// One `BARRE` occurrence resolved on the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct BarCara {
    pub cells: Vec<CellId>,
    pub area: f64,
}

/// The `POUTRE` and `BARRE` keywords AFFE_CARA_ELEM reads (`crate::support`).
pub(crate) const KEYWORDS: [&str; 14] = [
    "BARRE",
    "BARRE/GROUP_MA",
    "BARRE/SECTION",
    "BARRE/CARA",
    "BARRE/VALE",
    "POUTRE",
    "POUTRE/GROUP_MA",
    "POUTRE/SECTION",
    "POUTRE/VARI_SECT",
    "POUTRE/CARA",
    "POUTRE/VALE",
    "POUTRE/MODI_METRIQUE",
    "POUTRE/TUYAU_NSEC",
    "POUTRE/TUYAU_NCOU",
];

/// The sections reproduced; `MODI_METRIQUE='OUI'` is the pipes'.
pub(crate) const VALUES: [crate::support::Values; 4] = [
    crate::support::Values::listed("BARRE/SECTION", &["CERCLE", "RECTANGLE", "GENERALE"]),
    crate::support::Values::listed("POUTRE/SECTION", &["CERCLE", "RECTANGLE", "GENERALE"]),
    crate::support::Values::listed("POUTRE/VARI_SECT", &["CONSTANT", "HOMOTHETIQUE"]),
    crate::support::Values::new("POUTRE/MODI_METRIQUE", &["NON"]),
];

/// The `CARA` names and `VALE` values of a `POUTRE` or `BARRE`
/// occurrence, one to one (an error at `VALE` otherwise).
fn cara_vale<'k>(
    ex: &Executor,
    occ: &'k Keywords,
    factor: &str,
) -> Result<(Vec<&'k str>, Vec<f64>), ExecError> {
    let names: Vec<&str> = occ
        .simple("CARA")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let values: Vec<f64> = occ
        .simple("VALE")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    if names.len() != values.len() {
        return Err(ex.kw_error(
            "AFFE_CARA_ELEM",
            occ,
            "VALE",
            format!(
                "{factor} gives {} characteristics (CARA) and {} values (VALE)",
                names.len(),
                values.len()
            ),
        ));
    }
    Ok((names, values))
}

/// HY, HZ and the walls (EPY, EPZ) of a RECTANGLE section.
type RectangleDims = (f64, f64, Option<(f64, f64)>);

/// A RECTANGLE section's HY, HZ (or H) and walls EPY, EPZ (or EP; none:
/// solid) from its `CARA` values, or the keyword and message of what is
/// missing or wrong.
fn rectangle_dims(
    get: &dyn Fn(&str) -> Option<f64>,
) -> Result<RectangleDims, (&'static str, String)> {
    let h = get("H");
    let (Some(hy), Some(hz)) = (get("HY").or(h), get("HZ").or(h)) else {
        return Err(("CARA", "SECTION='RECTANGLE' needs HY and HZ, or H".into()));
    };
    let ep = get("EP");
    let walls = match (get("EPY").or(ep), get("EPZ").or(ep)) {
        (None, None) => None,
        (Some(a), Some(b)) => Some((a, b)),
        _ => {
            return Err((
                "CARA",
                "a hollow RECTANGLE needs both EPY and EPZ, or EP".into(),
            ))
        }
    };
    if !(hy > 0. && hz > 0.) {
        return Err(("VALE", format!("RECTANGLE with HY = {hy}, HZ = {hz}")));
    }
    Ok((hy, hz, walls))
}

/// The `POUTRE` occurrences of an AFFE_CARA_ELEM call.
pub(crate) fn beams(ex: &Executor, kw: &Keywords, mesh: &Mesh) -> Result<Vec<BeamCara>, ExecError> {
    let mut out = Vec::new();
    for occ in kw.factor("POUTRE") {
        let err = |key: &str, m: String| ex.kw_error("AFFE_CARA_ELEM", occ, key, m);
        let (names, values) = cara_vale(ex, occ, "POUTRE")?;
        let get = |n: &str| names.iter().position(|&c| c == n).map(|k| values[k]);
        let section_kind = occ.str("SECTION").unwrap_or("GENERALE");
        let homothetic = occ.str("VARI_SECT") == Some("HOMOTHETIQUE");
        // A homothetic section equal at both ends is a constant one.
        let end = |base: &str, first: &str, last: &str| -> Result<Option<f64>, ExecError> {
            if !homothetic {
                return Ok(get(base));
            }
            match (get(first), get(last)) {
                (None, None) => Ok(None),
                (Some(a), Some(b)) if a == b => Ok(Some(a)),
                (a, b) => Err(ex.unsupported(
                    &format!(
                        "AFFE_CARA_ELEM/POUTRE/VARI_SECT='HOMOTHETIQUE' with {first}={} and {last}={} (a section varying along the beam is not reproduced; equal ends are)",
                        a.map_or("-".into(), |v| v.to_string()),
                        b.map_or("-".into(), |v| v.to_string())
                    ),
                    occ.keyword("VARI_SECT").map(|k| k.span).unwrap_or_default(),
                )),
            }
        };
        let mut radius = None;
        let section = match section_kind {
            "CERCLE" => {
                let Some(r) = end("R", "R_DEBUT", "R_FIN")? else {
                    return Err(err("CARA", "SECTION='CERCLE' needs R".into()));
                };
                let ep = end("EP", "EP_DEBUT", "EP_FIN")?.unwrap_or(r);
                if !(r > 0. && ep > 0. && ep <= r) {
                    return Err(err(
                        "VALE",
                        format!("CERCLE with R = {r}, EP = {ep}: needs 0 < EP ≤ R"),
                    ));
                }
                radius = Some(r);
                BeamSection {
                    shear: Some(BeamSection::circle_shear(r, ep)),
                    ..BeamSection::circle(r, ep)
                }
            }
            "RECTANGLE" => {
                if homothetic {
                    return Err(ex.unsupported(
                        "AFFE_CARA_ELEM/POUTRE/VARI_SECT='HOMOTHETIQUE' on a RECTANGLE (a section varying along the beam is not reproduced)",
                        occ.keyword("VARI_SECT").map(|k| k.span).unwrap_or_default(),
                    ));
                }
                let (hy, hz, walls) = rectangle_dims(&get).map_err(|(k, m)| err(k, m))?;
                let shear =
                    BeamSection::rectangle_shear(hy, hz, walls).map_err(|m| err("VALE", m))?;
                BeamSection {
                    shear: Some(shear),
                    ..BeamSection::rectangle(hy, hz, walls)
                }
            }
            _ => {
                if homothetic {
                    return Err(ex.unsupported(
                        "AFFE_CARA_ELEM/POUTRE/VARI_SECT='HOMOTHETIQUE' on a GENERALE section (a section varying along the beam is not reproduced)",
                        occ.keyword("VARI_SECT").map(|k| k.span).unwrap_or_default(),
                    ));
                }
                for off in ["EY", "EZ"] {
                    if get(off).is_some_and(|v| v != 0.) {
                        return Err(ex.unsupported(
                            &format!(
                                "AFFE_CARA_ELEM/POUTRE/CARA='{off}' non-zero (a shear centre offset from the centroid couples torsion and bending: not reproduced)"
                            ),
                            occ.keyword("CARA").map(|k| k.span).unwrap_or_default(),
                        ));
                    }
                }
                let (Some(area), Some(iy), Some(iz), Some(jx)) =
                    (get("A"), get("IY"), get("IZ"), get("JX"))
                else {
                    return Err(err(
                        "CARA",
                        "SECTION='GENERALE' needs A, IY, IZ and JX".into(),
                    ));
                };
                // AY, AZ: a Timoshenko beam's shear coefficients (no
                // default in code_aster's `affdef`: a POU_D_T cell without
                // them is refused when the model is built).
                let shear = match (get("AY"), get("AZ")) {
                    (Some(ay), Some(az)) => Some([ay, az]),
                    _ => None,
                };
                BeamSection {
                    area,
                    iy,
                    iz,
                    jx,
                    shear,
                }
            }
        };
        section.check().map_err(|m| err("VALE", m))?;
        let cells = select::cells(occ, mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_CARA_ELEM/POUTRE: {e}")))?;
        if let Some(bad) = select::misfit(mesh, &cells, |c| c.ty == CellType::SEG2) {
            return Err(err(
                "GROUP_MA",
                format!("POUTRE applies to the beam cells (SEG2), but {bad}"),
            ));
        }
        out.push(BeamCara {
            cells,
            section,
            radius,
        });
    }
    Ok(out)
}

/// The `BARRE` occurrences of an AFFE_CARA_ELEM call: the area of each
/// (code_aster's `aceaba`: `A` given, or the area of the circle or
/// rectangle, as the beams' sections compute it).
pub(crate) fn bars(ex: &Executor, kw: &Keywords, mesh: &Mesh) -> Result<Vec<BarCara>, ExecError> {
    let mut out = Vec::new();
    for occ in kw.factor("BARRE") {
        let err = |key: &str, m: String| ex.kw_error("AFFE_CARA_ELEM", occ, key, m);
        let (names, values) = cara_vale(ex, occ, "BARRE")?;
        let get = |n: &str| names.iter().position(|&c| c == n).map(|k| values[k]);
        let area = match occ.str("SECTION").unwrap_or("GENERALE") {
            "CERCLE" => {
                let Some(r) = get("R") else {
                    return Err(err("CARA", "SECTION='CERCLE' needs R".into()));
                };
                let ep = get("EP").unwrap_or(r);
                if !(r > 0. && ep > 0. && ep <= r) {
                    return Err(err(
                        "VALE",
                        format!("CERCLE with R = {r}, EP = {ep}: needs 0 < EP ≤ R"),
                    ));
                }
                BeamSection::circle(r, ep).area
            }
            "RECTANGLE" => {
                let (hy, hz, walls) = rectangle_dims(&get).map_err(|(k, m)| err(k, m))?;
                BeamSection::rectangle(hy, hz, walls).area
            }
            _ => {
                let Some(a) = get("A") else {
                    return Err(err("CARA", "SECTION='GENERALE' needs A".into()));
                };
                a
            }
        };
        aster_fem::bar::check_area(area).map_err(|m| err("VALE", m))?;
        let cells = select::cells(occ, mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_CARA_ELEM/BARRE: {e}")))?;
        if let Some(bad) = select::misfit(mesh, &cells, |c| c.ty == CellType::SEG2) {
            return Err(err(
                "GROUP_MA",
                format!("BARRE applies to the truss cells (SEG2), but {bad}"),
            ));
        }
        out.push(BarCara { cells, area });
    }
    Ok(out)
}
