//! code_aster 17's Python methods of concepts that `aster run` answers, the
//! mesh's counts (`getNumberOfNodes()`, `getNumberOfCells()`,
//! `getCells(groups)`), and the mesh methods that make a new mesh:
//! `mesh.refine(ntimes=1)`,
//! `mesh.convertToLinear()`, `mesh.convertToQuadratic()` (their arguments
//! checked here, the meshes made by aster-mesh's `Mesh::refine`,
//! `convert_to_linear`, `convert_to_quadratic`).

use aster_eval::{ExecError, HostValue, Scalar};
use aster_mesh::Mesh;

/// The methods `aster run` answers, as (the concept type's prefix, name);
/// an empty prefix: any concept. The static pass refuses any other method
/// call on a concept, located at the call, before anything runs
/// ([`crate::executor::Executor`]'s `method` and `make` answer exactly
/// these).
pub const METHODS: &[(&str, &str)] = &[
    ("", "getName"),
    ("table", "EXTR_TABLE"),
    ("table", "get_nom_para"),
    ("fonction", "__call__"),
    ("nappe", "__call__"),
    ("formule", "__call__"),
    ("maillage", "getMinMaxEdgeSizes"),
    ("maillage", "getNumberOfNodes"),
    ("maillage", "getNumberOfCells"),
    ("maillage", "getCells"),
    ("maillage_sdaster", "refine"),
    ("maillage_sdaster", "convertToLinear"),
    ("maillage_sdaster", "convertToQuadratic"),
];

/// `aster run` answers the method `name` of a concept of type `typ` (a
/// type known only at run time passes).
pub fn runs(typ: &str, name: &str) -> bool {
    // `?`: the catalog's type of a concept known only at run time.
    typ == "?"
        || METHODS
            .iter()
            .any(|(prefix, m)| *m == name && typ.starts_with(prefix))
}

/// Why a method is not run: the message of the refusal.
pub fn refusal(concept: &str, typ: &str, name: &str) -> String {
    let known: Vec<&str> = METHODS
        .iter()
        .filter(|(prefix, _)| typ.starts_with(prefix))
        .map(|(_, m)| *m)
        .collect();
    format!(
        "not supported: method {name}() of concept {concept} ({typ}); aster runs {}",
        if known.is_empty() {
            "no method of this concept".to_string()
        } else {
            known.join(", ")
        }
    )
}

/// Most cells a refinement may make (each level multiplies a volume's
/// cells by 8).
pub const MAX_REFINED_CELLS: usize = 20_000_000;

/// The mesh a concept-making mesh method gives.
pub fn make(
    mesh: &Mesh,
    name: &str,
    args: &[(&'static str, HostValue)],
) -> Result<Mesh, ExecError> {
    let arg = |p: &str| args.iter().find(|(n, _)| *n == p).map(|(_, v)| v);
    if let Some(info) = arg("info") {
        if !matches!(info, HostValue::Scalar(Scalar::Int(1 | 2))) {
            return Err(ExecError::new(format!(
                "{name}(): info takes 1 or 2 (code_aster's verbosity), not {info:?}"
            )));
        }
    }
    match name {
        "refine" => {
            let ntimes = match arg("ntimes") {
                // code_aster's loop over the levels runs no time for n ≤ 0.
                Some(HostValue::Scalar(Scalar::Int(n))) => *n,
                other => {
                    return Err(ExecError::new(format!(
                        "refine(): ntimes takes an integer, not {other:?}"
                    )))
                }
            };
            refined(mesh, ntimes)
        }
        "convertToLinear" => Ok(mesh.convert_to_linear()),
        "convertToQuadratic" => mesh
            .convert_to_quadratic()
            .map_err(|e| ExecError::new(format!("not supported: {e}"))),
        _ => Err(ExecError::new(format!(
            "not supported: method {name}() of a mesh"
        ))),
    }
}

/// `getNumberOfNodes()`, `getNumberOfCells()`, `getCells(group_name)`
/// (code_aster's `Mesh::getCells`: the 0-based indexes of the cells of the
/// groups, sorted, each once; a group the mesh does not have adds none; no
/// group: every cell); `None` for another method.
pub fn query(mesh: &Mesh, name: &str, args: &[HostValue]) -> Option<Result<HostValue, ExecError>> {
    let int = |n: usize| HostValue::Scalar(Scalar::Int(n as i64));
    Some(match (name, args) {
        ("getNumberOfNodes", []) => Ok(int(mesh.node_count())),
        ("getNumberOfCells", []) => Ok(int(mesh.cells.len())),
        ("getCells", _) => {
            let names: Option<Vec<&str>> = match args {
                [] => Some(Vec::new()),
                [HostValue::Scalar(Scalar::Str(g))] => Some(vec![g.as_str()]),
                [HostValue::List(l)] => l
                    .iter()
                    .map(|v| match v {
                        HostValue::Scalar(Scalar::Str(g)) => Some(g.as_str()),
                        _ => None,
                    })
                    .collect(),
                _ => None,
            };
            match names {
                None => Err(ExecError::new(
                    "getCells takes a group name or a list of group names",
                )),
                Some(names) if names.is_empty() => {
                    Ok(HostValue::List((0..mesh.cells.len()).map(int).collect()))
                }
                Some(names) => {
                    let mut cells: Vec<usize> = names
                        .iter()
                        .filter_map(|g| mesh.group_ma(g))
                        .flat_map(|g| g.members.iter().map(|c| c.0 as usize))
                        .collect();
                    cells.sort_unstable();
                    cells.dedup();
                    Ok(HostValue::List(cells.into_iter().map(int).collect()))
                }
            }
        }
        ("getNumberOfNodes" | "getNumberOfCells", _) => {
            Err(ExecError::new(format!("{name}() takes no argument")))
        }
        _ => return None,
    })
}

/// The first cell of a mesh that `convertToQuadratic()` does not take (a
/// cell that is not linear), described.
pub fn non_linear_cell(mesh: &Mesh) -> Option<String> {
    use aster_mesh::CellType::*;
    mesh.cells.iter().enumerate().find_map(|(i, c)| {
        (!matches!(
            c.ty,
            POI1 | SEG2 | TRIA3 | QUAD4 | TETRA4 | HEXA8 | PENTA6 | PYRAM5
        ))
        .then(|| {
            format!(
                "cell {} is a {}",
                mesh.cell_name(aster_mesh::CellId(i as u32)),
                c.ty.name()
            )
        })
    })
}

/// What `refine()` and `CREA_MAILLAGE/RAFFINEMENT` know of a mesh's cells,
/// for the static pass: the first cell that is not linear (which
/// `convertToQuadratic()` refuses) and why `refine()` would refuse the mesh
/// (a SEG4 or PYRAM13 cell, a PYRAM5 beside quadratic cells).
#[derive(Clone, Debug, Default)]
pub struct MeshCells {
    pub non_linear: Option<String>,
    pub unrefinable: Option<String>,
}

impl MeshCells {
    pub fn of(mesh: &Mesh) -> MeshCells {
        MeshCells {
            non_linear: non_linear_cell(mesh),
            unrefinable: mesh.refine_refusal(),
        }
    }
}

/// `mesh.refine(ntimes)` and `CREA_MAILLAGE/RAFFINEMENT/NIVEAU`: the mesh
/// refined `ntimes` times (code_aster's loop over the levels runs no time
/// for ntimes ≤ 0), refused when it would make more than
/// [`MAX_REFINED_CELLS`] cells or when `Mesh::refine` does not take a cell.
pub fn refined(mesh: &Mesh, ntimes: i64) -> Result<Mesh, ExecError> {
    let ntimes = ntimes.max(0) as usize;
    let per_level = mesh
        .cells
        .iter()
        .map(|c| match c.ty.dim() {
            0 => 1usize,
            1 => 2,
            2 => 4,
            _ => 10,
        })
        .max()
        .unwrap_or(1);
    let bound = (0..ntimes).try_fold(mesh.cells.len(), |n, _| n.checked_mul(per_level));
    if bound.is_none_or(|n| n > MAX_REFINED_CELLS) {
        return Err(ExecError::new(format!(
            "not supported: refining {ntimes} times a mesh of {} cells would make more than {MAX_REFINED_CELLS} cells",
            mesh.cells.len()
        )));
    }
    mesh.refine(ntimes)
        .map_err(|e| ExecError::new(format!("not supported: {e}")))
}
