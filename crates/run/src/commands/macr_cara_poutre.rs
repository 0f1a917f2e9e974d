//! `MACR_CARA_POUTRE` (code_aster's `macr_cara_poutre_ops.py`) and
//! `POST_ELEM/CARA_GEOM`: the section properties of a beam from a 2D mesh
//! of its cross-section, as a table.
//!
//! The keywords become plain inputs of aster-fem's [`aster_fem::section`]
//! (which reproduces `te0285`/`pemica`/`pecag2`/`pecag3` and the Laplace
//! problems of `CARA_POUTRE`, solved by the thermal solver):
//!
//! - the mesh: `MAILLAGE`, or read from `UNITE` (default 20) in `FORMAT`;
//! - `CARA_GEOM` of the whole section (the row `LIEU` = `NOM`, `ENTITE` =
//!   `TOUT`) and of each `GROUP_MA` (one row each), with `SYME_Y`/`SYME_Z`
//!   (code_aster's `SYME_X`/`SYME_Y` of `CARA_GEOM`) and `ORIG_INER`;
//! - with `GROUP_MA_BORD` (one group, without `GROUP_MA`): the torsion
//!   constant `JX`, shear coefficients `AY`/`AZ`, shear centre `EY`/`EZ`,
//!   `PCTY`/`PCTZ`, `PCT_M_Y`/`PCT_M_Z`, warping constant `JG`, `KY`=`KZ`=0;
//!   `GROUP_NO` (one node) fixes the shear functions;
//! - `QUADRANT` (the macro's `TraiteQuadrant`), `TABLE_CARA='OUI'` (the
//!   columns `AFFE_CARA_ELEM` reads, the positivity check POUTRE0_11).
//!
//! Refused before the run: `GROUP_MA` with `GROUP_MA_BORD` (the per-group
//! torsion with `LONGUEUR`/`MATERIAU`/`LIAISON`), several `GROUP_MA_BORD`.
//! Not computed (the column is absent, so a file that reads it stops there
//! rather than read a number): the torsion radius `RT` (code_aster's
//! `MACR_LIGN_COUPE` of the normal flux of φ on the border), and `JX` of a
//! section with holes (`GROUP_MA_INTE`: φ uniform on each hole's border,
//! `LIAISON_UNIF`, with the flux `FLUX_REP/CARA_TORSION` 2·area/length).

use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::support::{Refusal, Support};
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use aster_fem::section::{self, CaraGeom, Symmetry};
use aster_mesh::{CellId, Mesh, NodeId};
use std::collections::BTreeSet;
use std::rc::Rc;

/// What MACR_CARA_POUTRE runs (`crate::support`).
pub(crate) const MACR_CARA_POUTRE: Support = Support {
    rules: Some(rules),
    ..Support::keywords(&[
        "MAILLAGE",
        "FORMAT",
        "UNITE",
        "ORIG_INER",
        "QUADRANT",
        "INFO",
        "TABLE_CARA",
        "SYME_Y",
        "SYME_Z",
        "GROUP_MA",
        "GROUP_MA_BORD",
        "GROUP_NO",
        "GROUP_MA_INTE",
        "NOM",
    ])
};

fn rules(call: &CommandCall, out: &mut Vec<Refusal>) {
    let kw = &call.keywords;
    if kw.contains("GROUP_MA_BORD") && kw.contains("GROUP_MA") {
        out.push(Refusal::at(
            "MACR_CARA_POUTRE/GROUP_MA with GROUP_MA_BORD (the torsion of each group, with LONGUEUR, MATERIAU, LIAISON, is not reproduced)".into(),
            kw,
            "GROUP_MA",
            call.span,
        ));
    }
    if kw.contains("QUADRANT") && !kw.contains("GROUP_MA_BORD") {
        out.push(Refusal::at(
            "MACR_CARA_POUTRE/QUADRANT without GROUP_MA_BORD (code_aster's TraiteQuadrant reads the shear columns)".into(),
            kw,
            "QUADRANT",
            call.span,
        ));
    }
    if kw.contains("GROUP_MA_BORD") && kw.simple("GROUP_MA_BORD").len() > 1 {
        out.push(Refusal::at(
            "MACR_CARA_POUTRE/GROUP_MA_BORD of several groups without GROUP_MA".into(),
            kw,
            "GROUP_MA_BORD",
            call.span,
        ));
    }
}

/// The columns of code_aster's `CARA_GEOM` table (`pecage`'s `noparr`),
/// with the torsion ones `MACR_CARA_POUTRE` adds.
const ALL_COLUMNS: &[&str] = &[
    "LIEU", "ENTITE", "A_M", "CDG_Y_M", "CDG_Z_M", "IY_G_M", "IZ_G_M", "IYZ_G_M", "PCT_M_Y",
    "PCT_M_Z", "Y_MAX", "Z_MAX", "Y_MIN", "Z_MIN", "R_MAX", "A", "CDG_Y", "CDG_Z", "IY_G", "IZ_G",
    "IYZ_G", "IY", "IZ", "ALPHA", "Y_P", "Z_P", "IY_P", "IZ_P", "IYZ_P", "JX", "AY", "AZ", "EY",
    "EZ", "PCTY", "PCTZ", "JG", "KY", "KZ", "IYR2_G", "IZR2_G", "IYR2", "IZR2", "IYR2_P", "IZR2_P",
    "RY", "RZ",
];

/// Columns of `TABLE_CARA='OUI'` (the macro's `CALC_TABLE/EXTR`).
const CARA_BORD: &[&str] = &[
    "LIEU", "A", "IY", "IZ", "AY", "AZ", "EY", "EZ", "JX", "JG", "IYR2", "IZR2", "RY", "RZ",
    "ALPHA", "CDG_Y", "CDG_Z",
];
const CARA_GEOM_ONLY: &[&str] = &[
    "LIEU", "A", "IY", "IZ", "IYR2", "IZR2", "RY", "RZ", "ALPHA", "CDG_Y", "CDG_Z",
];
const TORSION: &[&str] = &[
    "PCT_M_Y", "PCT_M_Z", "JX", "AY", "AZ", "EY", "EZ", "PCTY", "PCTZ", "JG", "KY", "KZ",
];

/// The surface cells of `mesh` (`cells`: all, or a group's).
fn surface_cells(mesh: &Mesh, cells: impl Iterator<Item = CellId>) -> Vec<CellId> {
    cells
        .filter(|&c| section::is_section_cell(mesh, c))
        .collect()
}

fn nodes_of(mesh: &Mesh, cells: &[CellId]) -> Vec<NodeId> {
    let set: BTreeSet<NodeId> = cells
        .iter()
        .flat_map(|&c| mesh.cell(c).nodes.iter().copied())
        .collect();
    set.into_iter().collect()
}

/// `CARA_GEOM` rows: the whole mesh (`lieu_all`) then each group.
pub(crate) fn cara_geom_rows(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    mesh: &Mesh,
    lieu_all: Option<&str>,
    groups: &[&str],
    (sym, origin): (Symmetry, Option<[f64; 2]>),
) -> Result<Vec<(String, &'static str, CaraGeom)>, ExecError> {
    let fem = |e: aster_fem::FemError| ExecError::new(format!("{cmd}: {e}"));
    let mut rows = Vec::new();
    if let Some(lieu) = lieu_all {
        let cells = surface_cells(mesh, (0..mesh.cells.len() as u32).map(CellId));
        if cells.is_empty() {
            return Err(ExecError::new(format!(
                "{cmd}: the mesh has no surface cell (TRIA3, TRIA6, QUAD4, QUAD8, QUAD9) to make a section of"
            )));
        }
        let all_nodes: Vec<NodeId> = (0..mesh.node_count() as u32).map(NodeId).collect();
        let g = section::cara_geom(mesh, &cells, &all_nodes, sym, origin).map_err(fem)?;
        rows.push((lieu.to_string(), "TOUT", g));
    }
    for name in groups {
        let group =
            crate::select::group_ma(mesh, name).map_err(|e| ex.kw_error(cmd, kw, "GROUP_MA", e))?;
        let cells = surface_cells(mesh, group.iter().copied());
        if cells.is_empty() {
            // code_aster's UTILITAI3_47: an alarm and no row.
            continue;
        }
        let nodes = nodes_of(mesh, group);
        let g = section::cara_geom(mesh, &cells, &nodes, sym, origin).map_err(fem)?;
        rows.push((name.to_string(), "GROUP_MA", g));
    }
    Ok(rows)
}

fn yes(kw: &Keywords, name: &str) -> bool {
    kw.str(name) == Some("OUI")
}

fn origin_of(kw: &Keywords) -> Option<[f64; 2]> {
    let v: Vec<f64> = kw
        .simple("ORIG_INER")
        .iter()
        .filter_map(|s| s.as_f64())
        .collect();
    match v[..] {
        [] => None,
        [x] => Some([x, 0.0]),
        [x, y, ..] => Some([x, y]),
    }
}

pub fn macr_cara_poutre(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "MACR_CARA_POUTRE";
    let kw = &call.keywords;
    let mesh = match kw.concept("MAILLAGE") {
        Some(m) => ex.mesh(m)?,
        None => {
            let format = kw.str("FORMAT").unwrap_or("MED").to_string();
            let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(20);
            super::mesh::read_unit(cmd, ex, unit, &format, false, &format)?
        }
    };
    let strs =
        |name: &str| -> Vec<&str> { kw.simple(name).iter().filter_map(|s| s.as_str()).collect() };
    let groups = strs("GROUP_MA");
    let border = strs("GROUP_MA_BORD");
    let table_cara = yes(kw, "TABLE_CARA");
    let nom = kw.str("NOM").unwrap_or("").to_string();
    let sym = Symmetry {
        x: yes(kw, "SYME_Y"),
        y: yes(kw, "SYME_Z"),
    };
    for g in &groups {
        if mesh.group_ma(g).is_none() {
            return Err(ex.kw_error(
                cmd,
                kw,
                "GROUP_MA",
                format!("no cell group `{g}` in the mesh (POUTRE0_20)"),
            ));
        }
    }
    let mut rows = cara_geom_rows(
        ex,
        cmd,
        kw,
        &mesh,
        Some(&nom),
        &groups,
        (sym, origin_of(kw)),
    )?;
    let mut extra: Vec<(&'static str, f64)> = Vec::new();
    if let Some(&bord) = border.first() {
        let Some(group) = mesh.group_ma(bord) else {
            return Err(ex.kw_error(
                cmd,
                kw,
                "GROUP_MA_BORD",
                format!("no cell group `{bord}` in the mesh (POUTRE0_20)"),
            ));
        };
        let segments: Vec<CellId> = group.members.to_vec();
        let inte = strs("GROUP_MA_INTE");
        for g in &inte {
            if mesh.group_ma(g).is_none() {
                return Err(ex.kw_error(
                    cmd,
                    kw,
                    "GROUP_MA_INTE",
                    format!("no cell group `{g}` in the mesh (POUTRE0_20)"),
                ));
            }
        }
        let border_nodes = nodes_of(&mesh, &segments);
        let grno = strs("GROUP_NO");
        let pinned = match grno[..] {
            [g] => {
                let nodes = crate::select::group_no(&mesh, g)
                    .map_err(|e| ex.kw_error(cmd, kw, "GROUP_NO", e))?;
                match nodes {
                    [n] => *n,
                    _ => {
                        return Err(ex.kw_error(
                            cmd,
                            kw,
                            "GROUP_NO",
                            format!("group `{g}` has {} nodes: one is needed (POUTRE0_3)", nodes.len()),
                        ))
                    }
                }
            }
            [] => {
                return Err(ex.unsupported(
                    "MACR_CARA_POUTRE/GROUP_MA_BORD without GROUP_NO (the shear problems are then singular: code_aster's result depends on its solver)",
                    kw.keyword("GROUP_MA_BORD").map(|k| k.span).unwrap_or(call.span),
                ))
            }
            _ => return Err(ex.kw_error(cmd, kw, "GROUP_NO", "one group of one node is needed (POUTRE0_3)")),
        };
        let cells = surface_cells(&mesh, (0..mesh.cells.len() as u32).map(CellId));
        let geom = &rows[0].2;
        let p = section::beam_properties(
            &mesh,
            geom,
            &section::SectionBorder {
                cells: &cells,
                border_nodes: &border_nodes,
                border_segments: &segments,
                pinned,
                holes: !inte.is_empty(),
            },
        )
        .map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
        extra = vec![
            ("PCT_M_Y", geom.get("CDG_Y_M") - p.pcty),
            ("PCT_M_Z", geom.get("CDG_Z_M") - p.pctz),
            ("AY", p.ay),
            ("AZ", p.az),
            ("EY", p.ey),
            ("EZ", p.ez),
            ("PCTY", p.pcty),
            ("PCTZ", p.pctz),
            ("JG", p.jg),
            ("KY", 0.0),
            ("KZ", 0.0),
        ];
        if let Some(jx) = p.jx {
            extra.push(("JX", jx));
        }
    }
    if table_cara && !groups.is_empty() {
        // The row of the whole mesh is removed.
        rows.remove(0);
    }
    let quadrant = kw.first("QUADRANT").and_then(|s| s.as_i64());
    let with_border = !border.is_empty();
    let columns: Vec<&str> = if table_cara {
        if with_border {
            CARA_BORD
        } else {
            CARA_GEOM_ONLY
        }
        .to_vec()
    } else {
        ALL_COLUMNS
            .iter()
            .copied()
            .filter(|c| with_border || !TORSION.contains(c))
            .collect()
    };
    let mut table = Table::new(
        columns
            .iter()
            .map(|c| Column {
                name: c.to_string(),
                ty: match *c {
                    "LIEU" => ColumnType::Text(24),
                    "ENTITE" => ColumnType::Text(8),
                    _ => ColumnType::Real,
                },
            })
            .collect(),
    );
    for (lieu, entite, geom) in &rows {
        let mut vals: Vec<(&'static str, f64)> = geom.values.clone();
        if *entite == "TOUT" {
            vals.extend(extra.iter().copied());
        }
        if let Some(q) = quadrant {
            quadrant_change(&mut vals, q);
        }
        if table_cara && lieu == &nom {
            for name in ["A", "IY", "IZ", "AY", "AZ", "JX", "JG"] {
                if let Some((_, v)) = vals.iter().find(|(n, _)| *n == name) {
                    if *v <= 0.0 {
                        return Err(ExecError::new(format!(
                            "{cmd}: {name} = {v:e} is not positive: the section is not usable by AFFE_CARA_ELEM (POUTRE0_10, POUTRE0_11)"
                        )));
                    }
                }
            }
        }
        let mut row = vec![("LIEU", Value::Text(lieu.clone()))];
        if columns.contains(&"ENTITE") {
            row.push(("ENTITE", Value::Text(entite.to_string())));
        }
        for (n, v) in vals {
            if columns.contains(&n) {
                row.push((n, Value::Real(v)));
            }
        }
        table.push_row(row);
    }
    store_result(ex, call, Concept::Table(Rc::new(table)))
}

/// The macro's `TraiteQuadrant`: the principal frame turned by quarter
/// turns so that `ALPHA` falls in quadrant `q` (1–4), the characteristics
/// following the axes.
fn quadrant_change(vals: &mut [(&'static str, f64)], q: i64) {
    let get = |vals: &[(&'static str, f64)], n: &str| {
        vals.iter()
            .find(|(k, _)| *k == n)
            .map(|(_, v)| *v)
            .unwrap_or(f64::NAN)
    };
    let mut alpha0 = get(vals, "ALPHA");
    if alpha0 < 0.0 {
        alpha0 += 360.0;
    }
    let quadrant = if alpha0 < 90.0 {
        1
    } else if alpha0 < 180.0 {
        2
    } else if alpha0 < 270.0 {
        3
    } else {
        4
    };
    let [iy0, iz0, ey0, ez0, ay0, az0, ry0, rz0, iyr20, izr20] = [
        "IY", "IZ", "EY", "EZ", "AY", "AZ", "RY", "RZ", "IYR2", "IZR2",
    ]
    .map(|n| get(vals, n));
    // (alpha, ay, az, ry, rz, iy, iz, ey, ez, iyr2, izr2) in quadrant 1.
    let q1 = match quadrant {
        1 => (alpha0, ay0, az0, ry0, rz0, iy0, iz0, ey0, ez0, iyr20, izr20),
        2 => (
            alpha0 - 90.0,
            az0,
            ay0,
            rz0,
            ry0,
            iz0,
            iy0,
            -ez0,
            ey0,
            -izr20,
            iyr20,
        ),
        3 => (
            alpha0 - 180.0,
            ay0,
            az0,
            ry0,
            rz0,
            iy0,
            iz0,
            -ey0,
            -ez0,
            -iyr20,
            -izr20,
        ),
        _ => (
            alpha0 - 270.0,
            az0,
            ay0,
            rz0,
            ry0,
            iz0,
            iy0,
            ez0,
            -ey0,
            izr20,
            -iyr20,
        ),
    };
    let (a1, ay1, az1, ry1, rz1, iy1, iz1, ey1, ez1, iyr21, izr21) = q1;
    let out = match q {
        1 => (a1, ay1, az1, ry1, rz1, iy1, iz1, ey1, ez1, iyr21, izr21),
        2 => (
            a1 + 90.0,
            az1,
            ay1,
            rz1,
            ry1,
            iz1,
            iy1,
            ez1,
            -ey1,
            izr21,
            -iyr21,
        ),
        3 => (
            a1 + 180.0,
            ay1,
            az1,
            ry1,
            rz1,
            iy1,
            iz1,
            -ey1,
            -ez1,
            -iyr21,
            -izr21,
        ),
        _ => (
            a1 + 270.0,
            az1,
            ay1,
            rz1,
            ry1,
            iz1,
            iy1,
            -ez1,
            ey1,
            -izr21,
            iyr21,
        ),
    };
    let (alpha, ay, az, ry, rz, iy, iz, ey, ez, iyr2, izr2) = out;
    for (k, v) in vals.iter_mut() {
        *v = match *k {
            "ALPHA" => alpha,
            "AY" => ay,
            "AZ" => az,
            "RY" => ry,
            "RZ" => rz,
            "IY" => iy,
            "IZ" => iz,
            "EY" => ey,
            "EZ" => ez,
            "IYR2" => iyr2,
            "IZR2" => izr2,
            _ => *v,
        };
    }
}
