//! `AFFE_CARA_ELEM/GRILLE`: the sections of the reinforcement grids
//! (`GRILLE_MEMBRANE`, `GRILLE_EXCENTRE`) — the area per unit width
//! `SECTION`, the bars' direction (`ANGL_REP_1` α, β; `VECT_1`; or across
//! `VECT_2` / `ANGL_REP_2`, cell by cell, as code_aster's `aceagb`) and
//! the offset `EXCENTREMENT` of `GRILLE_EXCENTRE`.
//!
//! Read here, handed to aster-fem as [`aster_fem::grid::GridSection`] per
//! cell. Refused by the support table: `SECTION_FO`, `EXCENTREMENT_FO`,
//! `REPERE='CYLINDRIQUE'`. `COEF_RIGI_DRZ` is read by no grid element of
//! code_aster (`te0430`–`te0433` ignore `CTOR`): accepted.

use crate::executor::Executor;
use crate::select;
use aster_eval::{ExecError, Keywords};
use aster_fem::grid::{self, GridSection};
use aster_mesh::{CellId, CellType, Mesh};

/// One cell's grid data: its section and direction, and the offset
/// `EXCENTREMENT` (read by `GRILLE_EXCENTRE` cells only).
#[derive(Clone, Debug, PartialEq)]
pub struct GridCara {
    pub cell: CellId,
    pub section: f64,
    pub direction: [f64; 3],
    pub offset: f64,
}

impl GridCara {
    /// The fem section: with its offset when the cell is `GRILLE_EXCENTRE`.
    pub fn section(&self, excentre: bool) -> GridSection {
        GridSection {
            section: self.section,
            direction: self.direction,
            offset: excentre.then_some(self.offset),
        }
    }
}

/// The `GRILLE` keywords AFFE_CARA_ELEM reads (`crate::support`).
pub(crate) const KEYWORDS: [&str; 10] = [
    "GRILLE",
    "GRILLE/GROUP_MA",
    "GRILLE/SECTION",
    "GRILLE/ANGL_REP_1",
    "GRILLE/ANGL_REP_2",
    "GRILLE/VECT_1",
    "GRILLE/VECT_2",
    "GRILLE/EXCENTREMENT",
    "GRILLE/COEF_RIGI_DRZ",
    "GRILLE/REPERE",
];

/// `REPERE='CYLINDRIQUE'` is not reproduced.
pub(crate) const VALUES: [crate::support::Values; 1] =
    [crate::support::Values::new("GRILLE/REPERE", &["GLOBAL"])];

fn reals(kw: &Keywords, name: &str) -> Vec<f64> {
    kw.simple(name).iter().filter_map(|s| s.as_f64()).collect()
}

/// The `GRILLE` occurrences of an AFFE_CARA_ELEM call, cell by cell (a
/// later occurrence replaces an earlier one on the same cell).
pub(crate) fn grids(ex: &Executor, kw: &Keywords, mesh: &Mesh) -> Result<Vec<GridCara>, ExecError> {
    let mut out = Vec::new();
    for occ in kw.factor("GRILLE") {
        let err = |key: &str, m: String| ex.kw_error("AFFE_CARA_ELEM", occ, key, m);
        let Some(section) = occ.f64("SECTION") else {
            return Err(err(
                "SECTION",
                "GRILLE needs SECTION (SECTION_FO is not supported)".into(),
            ));
        };
        if !(section >= 0. && section.is_finite()) {
            return Err(err(
                "SECTION",
                format!("SECTION = {section}: an area per unit width must be positive"),
            ));
        }
        let offset = occ.f64("EXCENTREMENT").unwrap_or(0.);
        let cells = select::cells(occ, mesh, "")
            .map_err(|e| ExecError::new(format!("AFFE_CARA_ELEM/GRILLE: {e}")))?;
        let surface = |ty: CellType| {
            matches!(
                ty,
                CellType::TRIA3 | CellType::TRIA6 | CellType::QUAD4 | CellType::QUAD8
            )
        };
        if let Some(bad) = select::misfit(mesh, &cells, |c| surface(c.ty)) {
            return Err(err(
                "GROUP_MA",
                format!("GRILLE applies to TRIA3, TRIA6, QUAD4 and QUAD8 cells: {bad}"),
            ));
        }
        // A constant direction (ANGL_REP_1, VECT_1), or one per cell
        // across VECT_2 / ANGL_REP_2 (aceagb).
        let two = |name: &str| -> Result<Option<[f64; 2]>, ExecError> {
            if occ.keyword(name).is_none() {
                return Ok(None);
            }
            match reals(occ, name).as_slice() {
                [a, b] => Ok(Some([*a, *b])),
                _ => Err(err(name, format!("{name} needs two angles (α, β)"))),
            }
        };
        let three = |name: &str| -> Result<Option<[f64; 3]>, ExecError> {
            if occ.keyword(name).is_none() {
                return Ok(None);
            }
            match reals(occ, name).as_slice() {
                [a, b, c] if (a * a + b * b + c * c).sqrt() >= 1e-6 => Ok(Some([*a, *b, *c])),
                _ => Err(err(
                    name,
                    format!("{name} needs three components, not all zero (MODELISA_10)"),
                )),
            }
        };
        let constant = if let Some([a, b]) = two("ANGL_REP_1")? {
            Some(grid::direction(a, b))
        } else if let Some(v) = three("VECT_1")? {
            let (a, b) = grid::angles_of(v).map_err(|m| err("VECT_1", m))?;
            Some(grid::direction(a, b))
        } else {
            None
        };
        let across = if let Some([a, b]) = two("ANGL_REP_2")? {
            let (a, b) = (a.to_radians(), b.to_radians());
            Some((
                "ANGL_REP_2",
                [a.cos() * b.cos(), a.sin() * b.cos(), b.sin()],
            ))
        } else {
            three("VECT_2")?.map(|v| ("VECT_2", v))
        };
        for &cell in &cells {
            let direction = match (constant, across) {
                (Some(d), _) => d,
                (None, Some((name, y))) => {
                    let c = mesh.cell(cell);
                    let corners: Vec<[f64; 3]> = c
                        .nodes
                        .iter()
                        .take(aster_fem::shape::corner_count(c.ty))
                        .map(|&n| mesh.coord(n))
                        .collect();
                    let x = grid::direction_across(&corners, y).map_err(|m| {
                        err(
                            name,
                            format!("cell {}: {m} (MODELISA_11)", mesh.cell_name(cell)),
                        )
                    })?;
                    // Stored as angles, as code_aster's carte.
                    let (a, b) = grid::angles_of(x).map_err(|m| err(name, m))?;
                    grid::direction(a, b)
                }
                (None, None) => {
                    return Err(err(
                        "GROUP_MA",
                        "GRILLE needs one of ANGL_REP_1, ANGL_REP_2, VECT_1, VECT_2".into(),
                    ))
                }
            };
            out.push(GridCara {
                cell,
                section,
                direction,
                offset,
            });
        }
    }
    Ok(out)
}
