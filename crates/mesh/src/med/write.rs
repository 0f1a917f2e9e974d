//! Writing a mesh and result fields as a MED 4.0 file (checked with the
//! MED 4.2 library through MEDCoupling 9.15: mesh, groups, nodal and cell
//! fields with their steps read back).
//!
//! Layout written (MED ≥ 3 conventions):
//! - `INFOS_GENERALES` {MAJ, MIN, REL};
//! - `ENS_MAA/<mesh>` {DIM, ESP, TYP, …} / `-0000000000000000001-0000000000000000001`
//!   (the "no step" computation step) / `NOE/{COO,FAM[,NOM]}`, `MAI/<type>/{NOD,FAM[,NOM]}`;
//! - `FAS/<mesh>/{FAMILLE_ZERO, NOEUD/FAM_<n>_…, ELEME/FAM_-<n>_…}`;
//! - `CHA/<field>` {MAI, NCO, NOM, TYP, UNI, UNT} / `<dt><it>` {NDT, NOR, PDT, RDT, ROR}
//!   / `NOE` or `MAI.<type>` {PFL} / `MED_NO_PROFILE_INTERNAL` or the profile {GAU, NBR, NGA} / `CO`;
//! - `PROFILS/PROFIL__<n>` {NBR} / `PFL`: the entities (1-based) a field
//!   written on some entities only covers ([`write_med_on`]).
//!
//! Families: one family per distinct combination of groups. Families
//! 1…G (and −1…−G) come first, each naming one group and holding no
//! entity, so that a reader walking families in number order meets the
//! groups in the mesh's order; the real combinations follow.
//!
//! Gauss-point fields are written averaged per cell (MED cell fields),
//! since writing integration-point localisations is not supported yet.

use super::celltypes::{aster_from_med, med_geo, med_name, MED_TYPES};
use crate::error::MeshError;
use crate::field::{FieldLocation, ResultStep};
use crate::hdf5::write::{to_bytes, Node, WAttr};
use crate::{CellType, Mesh};
use std::collections::HashMap;
use std::path::Path;

const NO_STEP: &str = "-0000000000000000001-0000000000000000001";
const NO_PROFILE: &str = "MED_NO_PROFILE_INTERNAL";

/// Write `mesh` (named `mesh_name` in the file) and the fields of `steps`.
pub fn write_med(
    path: &Path,
    mesh: &Mesh,
    mesh_name: &str,
    steps: &[ResultStep],
) -> Result<(), MeshError> {
    write_med_on(path, mesh, mesh_name, steps, &Entities::new())
}

/// The entities each field is written on, by (NUME_ORDRE, field name):
/// `true` for a node (nodal fields) or cell (cell and Gauss-point fields)
/// written. A field not listed is written on every entity.
pub type Entities = HashMap<(i32, String), Vec<bool>>;

/// [`write_med`] with fields written on some entities only, through MED
/// profiles as code_aster's `IMPR_RESU` writes them (`ircmpn`/`ircmpf`):
/// a field on fewer entities than the support has gets a profile
/// `PROFIL__00000001`, `PROFIL__00000002`… (1-based entity numbers, per
/// cell type for cells), an identical list reusing the profile already
/// written; a field on no entity of a cell type is not written there.
pub fn write_med_on(
    path: &Path,
    mesh: &Mesh,
    mesh_name: &str,
    steps: &[ResultStep],
    entities: &Entities,
) -> Result<(), MeshError> {
    let bytes = med_bytes_on(mesh, mesh_name, steps, entities)?;
    std::fs::write(path, bytes).map_err(|e| MeshError::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// The MED file image of a mesh and fields.
pub fn med_bytes(mesh: &Mesh, mesh_name: &str, steps: &[ResultStep]) -> Result<Vec<u8>, MeshError> {
    med_bytes_on(mesh, mesh_name, steps, &Entities::new())
}

/// [`med_bytes`] with the entities of [`write_med_on`].
pub fn med_bytes_on(
    mesh: &Mesh,
    mesh_name: &str,
    steps: &[ResultStep],
    entities: &Entities,
) -> Result<Vec<u8>, MeshError> {
    if mesh_name.is_empty() || mesh_name.len() > 64 {
        return Err(MeshError::Operation(format!(
            "MED mesh name `{mesh_name}` must have 1 to 64 characters"
        )));
    }
    for step in steps {
        for f in &step.fields {
            f.check(mesh)?;
        }
    }
    let dim = mesh.dim.clamp(1, 3) as usize;
    let n = mesh.node_count();
    let mesh_dim = mesh
        .cells
        .iter()
        .map(|c| c.ty.dim())
        .max()
        .unwrap_or(0)
        .max(1);

    // Cells by MED type, in file order within each type.
    let mut by_type: Vec<(CellType, Vec<usize>)> =
        MED_TYPES.iter().map(|t| (t.2, Vec::new())).collect();
    for (i, c) in mesh.cells.iter().enumerate() {
        if let Some(slot) = by_type.iter_mut().find(|(t, _)| *t == c.ty) {
            slot.1.push(i);
        }
    }
    by_type.retain(|(_, cells)| !cells.is_empty());

    let (node_fam, node_families) = families(
        n,
        mesh.groups_no
            .iter()
            .map(|g| (&g.name, g.members.iter().map(|m| m.0 as usize))),
        1,
    );
    let (cell_fam, cell_families) = families(
        mesh.cells.len(),
        mesh.groups_ma
            .iter()
            .map(|g| (&g.name, g.members.iter().map(|m| m.0 as usize))),
        -1,
    );

    // Nodes: coordinates "no interlace" (all x, all y, all z).
    let mut coo = Vec::with_capacity(n * dim);
    for d in 0..dim {
        coo.extend(mesh.coords.iter().map(|c| c[d]));
    }
    let nbr = |k: usize| vec![WAttr::int("CGT", 1), WAttr::int("NBR", k as i32)];
    let mut noe = vec![
        Node::f64s("COO", nbr(n), &coo),
        Node::i32s("FAM", nbr(n), &node_fam),
    ];
    if !default_names(&mesh.node_names, 'N') {
        noe.push(Node::names("NOM", nbr(n), &mesh.node_names, 16));
    }
    let mut mai = Vec::new();
    for (ty, cells) in &by_type {
        let nn = ty.node_count();
        let count = cells.len();
        let mut nod = vec![0i32; count * nn];
        let perm = aster_from_med(*ty);
        for (i, &c) in cells.iter().enumerate() {
            for (j, node) in mesh.cells[c].nodes.iter().enumerate() {
                let k = perm.map_or(j, |p| p[j]);
                nod[k * count + i] = node.0 as i32 + 1;
            }
        }
        let fam: Vec<i32> = cells.iter().map(|&c| cell_fam[c]).collect();
        let mut children = vec![
            Node::i32s("NOD", nbr(count), &nod),
            Node::i32s("FAM", nbr(count), &fam),
        ];
        if !default_names(&mesh.cell_names, 'M') {
            let names: Vec<String> = cells.iter().map(|&c| mesh.cell_names[c].clone()).collect();
            children.push(Node::names("NOM", nbr(count), &names, 16));
        }
        mai.push(Node::group(
            med_name(*ty),
            vec![
                WAttr::int("CGS", 1),
                WAttr::int("CGT", 1),
                WAttr::int("GEO", med_geo(*ty)),
                WAttr::string("PFL", NO_PROFILE),
            ],
            children,
        ));
    }
    let step = Node::group(
        NO_STEP,
        vec![
            WAttr::int("CGT", 1),
            WAttr::int("NDT", -1),
            WAttr::int("NOR", -1),
            WAttr::int("NXI", -1),
            WAttr::int("NXT", -1),
            WAttr::float("PDT", -1.0),
            WAttr::int("PVI", -1),
            WAttr::int("PVT", -1),
        ],
        vec![
            Node::group(
                "NOE",
                vec![
                    WAttr::int("CGS", 1),
                    WAttr::int("CGT", 1),
                    WAttr::string("PFL", NO_PROFILE),
                ],
                noe,
            ),
            Node::group("MAI", vec![WAttr::int("CGT", 1)], mai),
        ],
    );
    let axes = ["X", "Y", "Z"];
    let axis_names: String = axes[..dim].iter().map(|a| format!("{a:<16}")).collect();
    let units: String = " ".repeat(16 * dim);
    let mesh_group = Node::group(
        mesh_name,
        vec![
            WAttr::string("DES", "written by aster"),
            WAttr::int("DIM", mesh_dim as i32),
            WAttr::int("ESP", dim as i32),
            WAttr::string("NOM", &axis_names),
            WAttr::int("NXI", -1),
            WAttr::int("NXT", -1),
            WAttr::int("REP", 0),
            WAttr::int("SRT", 0),
            WAttr::int("TYP", 0),
            WAttr::string("UNI", &units),
            WAttr::string("UNT", ""),
        ],
        vec![step],
    );

    let family_group = |num: i32, groups: &[String]| {
        let label = groups.join("_");
        let mut name = format!("FAM_{num}_{label}");
        name.truncate(64);
        Node::group(
            &name,
            vec![WAttr::int("NUM", num)],
            vec![Node::group(
                "GRO",
                vec![WAttr::int("NBR", groups.len() as i32)],
                vec![Node::names("NOM", vec![], groups, 80)],
            )],
        )
    };
    let fas_mesh = Node::group(
        mesh_name,
        vec![],
        vec![
            Node::group("FAMILLE_ZERO", vec![WAttr::int("NUM", 0)], vec![]),
            Node::group(
                "NOEUD",
                vec![],
                node_families
                    .iter()
                    .map(|(num, g)| family_group(*num, g))
                    .collect(),
            ),
            Node::group(
                "ELEME",
                vec![],
                cell_families
                    .iter()
                    .map(|(num, g)| family_group(*num, g))
                    .collect(),
            ),
        ],
    );

    let mut root = vec![
        Node::group(
            "INFOS_GENERALES",
            vec![
                WAttr::int("MAJ", 4),
                WAttr::int("MIN", 0),
                WAttr::int("REL", 0),
            ],
            vec![],
        ),
        Node::group("ENS_MAA", vec![], vec![mesh_group]),
        Node::group("FAS", vec![], vec![fas_mesh]),
    ];
    if !steps.is_empty() {
        let mut profiles = Vec::new();
        root.push(Node::group(
            "CHA",
            vec![],
            fields(mesh, mesh_name, &by_type, steps, entities, &mut profiles)?,
        ));
        if !profiles.is_empty() {
            root.push(Node::group(
                "PROFILS",
                vec![],
                profiles
                    .iter()
                    .map(|(name, ids)| {
                        Node::group(
                            name,
                            vec![WAttr::int("NBR", ids.len() as i32)],
                            vec![Node::i32s("PFL", vec![], ids)],
                        )
                    })
                    .collect(),
            ));
        }
    }
    Ok(to_bytes(&Node::group("", vec![], root)))
}

/// Whether names are code_aster's defaults (`N1`, `N2`… or `M1`…), which need not be stored.
fn default_names(names: &[String], prefix: char) -> bool {
    // `N12` or, for the nodes of a MED file read without names, `12`.
    names
        .iter()
        .enumerate()
        .all(|(i, s)| s.strip_prefix(prefix).unwrap_or(s).parse::<usize>().ok() == Some(i + 1))
}

/// Family number of each entity, and the families (number, group names).
fn families<'a>(
    count: usize,
    groups: impl Iterator<Item = (&'a String, impl Iterator<Item = usize>)>,
    sign: i32,
) -> (Vec<i32>, Vec<(i32, Vec<String>)>) {
    let mut of_entity: Vec<Vec<u32>> = vec![Vec::new(); count];
    let mut names = Vec::new();
    for (g, (name, members)) in groups.enumerate() {
        names.push(name.clone());
        for m in members {
            if let Some(e) = of_entity.get_mut(m) {
                if e.last() != Some(&(g as u32)) {
                    e.push(g as u32);
                }
            }
        }
    }
    let mut fams: Vec<(i32, Vec<String>)> = names
        .iter()
        .enumerate()
        .map(|(g, name)| (sign * (g as i32 + 1), vec![name.clone()]))
        .collect();
    let mut index: HashMap<Vec<u32>, i32> = HashMap::new();
    let mut next = names.len() as i32 + 1;
    let mut numbers = vec![0i32; count];
    for (e, key) in of_entity.into_iter().enumerate() {
        if key.is_empty() {
            continue;
        }
        if let [g] = key[..] {
            numbers[e] = sign * (g as i32 + 1);
            continue;
        }
        let num = *index.entry(key.clone()).or_insert_with(|| {
            let num = sign * next;
            next += 1;
            fams.push((
                num,
                key.iter().map(|&g| names[g as usize].clone()).collect(),
            ));
            num
        });
        numbers[e] = num;
    }
    (numbers, fams)
}

/// The profile of a list of 1-based entity numbers: an identical one
/// already written, else a new `PROFIL__<8 digits>` (`ircmpf`).
fn profile_name(profiles: &mut Vec<(String, Vec<i32>)>, ids: Vec<i32>) -> String {
    if let Some((name, _)) = profiles.iter().find(|(_, p)| *p == ids) {
        return name.clone();
    }
    let name = format!("PROFIL__{:08}", profiles.len() + 1);
    profiles.push((name.clone(), ids));
    name
}

fn fields(
    mesh: &Mesh,
    mesh_name: &str,
    by_type: &[(CellType, Vec<usize>)],
    steps: &[ResultStep],
    entities: &Entities,
    profiles: &mut Vec<(String, Vec<i32>)>,
) -> Result<Vec<Node>, MeshError> {
    // Field name → its steps.
    let mut order: Vec<&str> = Vec::new();
    for s in steps {
        for f in &s.fields {
            if !order.contains(&f.name.as_str()) {
                order.push(&f.name);
            }
        }
    }
    let mut out = Vec::new();
    for name in order {
        let mut step_nodes = Vec::new();
        let mut components: Vec<String> = Vec::new();
        for s in steps {
            let Some(f) = s.fields.iter().find(|f| f.name == name) else {
                continue;
            };
            if components.is_empty() {
                components = f.components.clone();
            } else if components != f.components {
                return Err(MeshError::Operation(format!(
                    "field `{name}` changes components between steps"
                )));
            }
            let nc = components.len();
            let mut supports = Vec::new();
            let profile_attrs = |count: usize| {
                vec![
                    WAttr::string("GAU", ""),
                    WAttr::int("NBR", count as i32),
                    WAttr::int("NGA", 1),
                ]
            };
            let written = entities.get(&(s.nume_ordre, name.to_string()));
            let kept = |e: usize| written.is_none_or(|w| w.get(e).copied().unwrap_or(false));
            // Values "no interlace": component after component.
            let no_interlace = |values: &[f64], entities: &mut dyn Iterator<Item = usize>| {
                let ids: Vec<usize> = entities.collect();
                let mut co = Vec::with_capacity(ids.len() * nc);
                for c in 0..nc {
                    co.extend(ids.iter().map(|&e| values[e * nc + c]));
                }
                (ids.len(), co)
            };
            match f.location {
                FieldLocation::Nodes => {
                    let (count, co) =
                        no_interlace(&f.values, &mut (0..mesh.node_count()).filter(|&e| kept(e)));
                    if count > 0 {
                        let pfl = if count == mesh.node_count() {
                            NO_PROFILE.to_string()
                        } else {
                            let ids = (0..mesh.node_count())
                                .filter(|&e| kept(e))
                                .map(|e| e as i32 + 1)
                                .collect();
                            profile_name(profiles, ids)
                        };
                        supports.push(Node::group(
                            "NOE",
                            vec![WAttr::string("GAU", ""), WAttr::string("PFL", &pfl)],
                            vec![Node::group(
                                &pfl,
                                profile_attrs(count),
                                vec![Node::f64s("CO", vec![], &co)],
                            )],
                        ));
                    }
                }
                _ => {
                    let values = f.cell_values().unwrap_or_default();
                    for (ty, cells) in by_type {
                        // A Gauss field lives only on the cell types that have points.
                        if let FieldLocation::GaussPoints { points_per_cell } = &f.location {
                            if cells.iter().all(|&c| points_per_cell[c] == 0) {
                                continue;
                            }
                        }
                        let local: Vec<usize> =
                            (0..cells.len()).filter(|&i| kept(cells[i])).collect();
                        if local.is_empty() {
                            continue;
                        }
                        let (count, co) =
                            no_interlace(&values, &mut local.iter().map(|&i| cells[i]));
                        let pfl = if count == cells.len() {
                            NO_PROFILE.to_string()
                        } else {
                            let ids = local.iter().map(|&i| i as i32 + 1).collect();
                            profile_name(profiles, ids)
                        };
                        supports.push(Node::group(
                            &format!("MAI.{}", med_name(*ty)),
                            vec![WAttr::string("GAU", ""), WAttr::string("PFL", &pfl)],
                            vec![Node::group(
                                &pfl,
                                profile_attrs(count),
                                vec![Node::f64s("CO", vec![], &co)],
                            )],
                        ));
                    }
                }
            }
            step_nodes.push(Node::group(
                &format!("{:020}{:020}", s.nume_ordre, -1),
                vec![
                    WAttr::int("NDT", s.nume_ordre),
                    WAttr::int("NOR", -1),
                    WAttr::float("PDT", s.inst),
                    WAttr::int("RDT", -1),
                    WAttr::int("ROR", -1),
                ],
                supports,
            ));
        }
        let names: String = components.iter().map(|c| format!("{c:<16.16}")).collect();
        out.push(Node::group(
            name,
            vec![
                WAttr::string("MAI", mesh_name),
                WAttr::int("NCO", components.len() as i32),
                WAttr::string("NOM", &names),
                WAttr::int("TYP", 6),
                WAttr::string("UNI", &" ".repeat(16 * components.len())),
                WAttr::string("UNT", ""),
            ],
            step_nodes,
        ));
    }
    Ok(out)
}
