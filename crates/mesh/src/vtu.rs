//! Writing a mesh and result fields as a VTK XML unstructured grid (`.vtu`,
//! ASCII), which every ParaView opens.
//!
//! Node order: code_aster and VTK agree on corners and on most mid-edge
//! nodes; HEXA20/27 and PENTA15/18 list their mid-edge nodes edge ring by
//! edge ring in a different order, remapped below. Gauss-point fields are
//! written averaged per cell.

use crate::error::MeshError;
use crate::field::{FieldLocation, ResultStep};
use crate::{CellType, Mesh};
use std::fmt::Write as _;
use std::path::Path;

/// VTK cell type number and, when they differ, the code_aster node index for each VTK position.
fn vtk_type(ty: CellType) -> (u8, Option<&'static [usize]>) {
    const HEXA20: [usize; 20] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15,
    ];
    const HEXA27: [usize; 27] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15, 24, 22, 21, 23, 20,
        25, 26,
    ];
    const PENTA15: [usize; 15] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 13, 14, 9, 10, 11];
    const PENTA18: [usize; 18] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 13, 14, 9, 10, 11, 15, 16, 17];
    match ty {
        CellType::POI1 => (1, None),
        CellType::SEG2 => (3, None),
        CellType::SEG3 => (21, None),
        CellType::SEG4 => (35, None),
        CellType::TRIA3 => (5, None),
        CellType::TRIA6 => (22, None),
        CellType::TRIA7 => (34, None),
        CellType::QUAD4 => (9, None),
        CellType::QUAD8 => (23, None),
        CellType::QUAD9 => (28, None),
        CellType::TETRA4 => (10, None),
        CellType::TETRA10 => (24, None),
        CellType::PENTA6 => (13, None),
        CellType::PENTA15 => (26, Some(&PENTA15)),
        CellType::PENTA18 => (32, Some(&PENTA18)),
        CellType::HEXA8 => (12, None),
        CellType::HEXA20 => (25, Some(&HEXA20)),
        CellType::HEXA27 => (29, Some(&HEXA27)),
        CellType::PYRAM5 => (14, None),
        CellType::PYRAM13 => (27, None),
    }
}

/// Write the mesh and, if given, one step's fields.
pub fn write_vtu(path: &Path, mesh: &Mesh, step: Option<&ResultStep>) -> Result<(), MeshError> {
    let text = vtu_string(mesh, step)?;
    std::fs::write(path, text).map_err(|e| MeshError::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// Write every step of a result as `<dir>/<stem>_<NUME_ORDRE>.vtu` and a
/// ParaView collection `<dir>/<stem>.pvd` listing them by INST (ParaView's
/// time). Returns the files written, the `.pvd` first.
pub fn write_vtu_series(
    dir: &Path,
    stem: &str,
    mesh: &Mesh,
    steps: &[ResultStep],
) -> Result<Vec<std::path::PathBuf>, MeshError> {
    let write = |path: &Path, text: &str| {
        std::fs::write(path, text).map_err(|e| MeshError::Write {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    };
    std::fs::create_dir_all(dir).map_err(|e| MeshError::Write {
        path: dir.to_path_buf(),
        message: e.to_string(),
    })?;
    let mut pvd = String::new();
    let _ = writeln!(pvd, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        pvd,
        "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">"
    );
    let _ = writeln!(pvd, "<Collection>");
    let mut written = vec![dir.join(format!("{stem}.pvd"))];
    for step in steps {
        let name = format!("{stem}_{:06}.vtu", step.nume_ordre);
        write(&dir.join(&name), &vtu_string(mesh, Some(step))?)?;
        let _ = writeln!(
            pvd,
            "<DataSet timestep=\"{:e}\" part=\"0\" file=\"{}\"/>",
            step.inst,
            escape(&name)
        );
        written.push(dir.join(name));
    }
    let _ = writeln!(pvd, "</Collection>");
    let _ = writeln!(pvd, "</VTKFile>");
    write(&written[0], &pvd)?;
    Ok(written)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

pub fn vtu_string(mesh: &Mesh, step: Option<&ResultStep>) -> Result<String, MeshError> {
    if let Some(s) = step {
        for f in &s.fields {
            f.check(mesh)?;
        }
    }
    let mut o = String::new();
    let _ = writeln!(o, "<?xml version=\"1.0\"?>");
    let _ = writeln!(o, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">");
    let _ = writeln!(o, "<UnstructuredGrid>");
    if let Some(s) = step {
        let _ = writeln!(o, "<FieldData><DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{:e}</DataArray><DataArray type=\"Int32\" Name=\"NUME_ORDRE\" NumberOfTuples=\"1\" format=\"ascii\">{}</DataArray></FieldData>", s.inst, s.nume_ordre);
    }
    let _ = writeln!(
        o,
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        mesh.node_count(),
        mesh.cells.len()
    );
    let array_header = |o: &mut String, name: &str, comps: &[String]| {
        let _ = write!(
            o,
            "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\"",
            escape(name),
            comps.len()
        );
        for (i, c) in comps.iter().enumerate() {
            let _ = write!(o, " ComponentName{i}=\"{}\"", escape(c));
        }
        let _ = writeln!(o, " format=\"ascii\">");
    };
    let write_values = |o: &mut String, values: &[f64], nc: usize| {
        for row in values.chunks(nc.max(1)) {
            let line: Vec<String> = row.iter().map(|v| format!("{v:e}")).collect();
            let _ = writeln!(o, "{}", line.join(" "));
        }
        let _ = writeln!(o, "</DataArray>");
    };
    if let Some(s) = step {
        let _ = writeln!(o, "<PointData>");
        for f in s
            .fields
            .iter()
            .filter(|f| f.location == FieldLocation::Nodes)
        {
            array_header(&mut o, &f.name, &f.components);
            write_values(&mut o, &f.values, f.components.len());
        }
        let _ = writeln!(o, "</PointData>");
        let _ = writeln!(o, "<CellData>");
        for f in &s.fields {
            if let Some(values) = f.cell_values() {
                array_header(&mut o, &f.name, &f.components);
                write_values(&mut o, &values, f.components.len());
            }
        }
        let _ = writeln!(o, "</CellData>");
    }
    let _ = writeln!(
        o,
        "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
    );
    for c in &mesh.coords {
        let _ = writeln!(o, "{:e} {:e} {:e}", c[0], c[1], c[2]);
    }
    let _ = writeln!(o, "</DataArray></Points>");
    let _ = writeln!(
        o,
        "<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
    );
    let mut offsets = Vec::with_capacity(mesh.cells.len());
    let mut total = 0usize;
    for c in &mesh.cells {
        let (_, perm) = vtk_type(c.ty);
        let ids: Vec<String> = (0..c.nodes.len())
            .map(|k| c.nodes[perm.map_or(k, |p| p[k])].0.to_string())
            .collect();
        let _ = writeln!(o, "{}", ids.join(" "));
        total += c.nodes.len();
        offsets.push(total);
    }
    let _ = writeln!(
        o,
        "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
    );
    for chunk in offsets.chunks(16) {
        let s: Vec<String> = chunk.iter().map(|v| v.to_string()).collect();
        let _ = writeln!(o, "{}", s.join(" "));
    }
    let _ = writeln!(
        o,
        "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"
    );
    for chunk in mesh.cells.chunks(32) {
        let s: Vec<String> = chunk.iter().map(|c| vtk_type(c.ty).0.to_string()).collect();
        let _ = writeln!(o, "{}", s.join(" "));
    }
    let _ = writeln!(o, "</DataArray></Cells>");
    let _ = writeln!(o, "</Piece>");
    let _ = writeln!(o, "</UnstructuredGrid>");
    let _ = writeln!(o, "</VTKFile>");
    Ok(o)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn remaps_are_permutations() {
        for ty in CellType::ALL {
            if let (_, Some(p)) = vtk_type(ty) {
                let mut s = p.to_vec();
                s.sort_unstable();
                assert_eq!(s, (0..ty.node_count()).collect::<Vec<_>>(), "{ty:?}");
            }
        }
    }
}
