//! The real meshes of `../shared` (code_aster's test meshes, not part of
//! the repository): every one reads, with facts checked against the files.
//! Each test returns early, saying why, when `../shared` is absent.

use aster_mesh::{read_mesh, CellType, Mesh};
use std::path::{Path, PathBuf};

fn shared() -> Option<PathBuf> {
    let p = std::env::var_os("ASTER_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared"));
    if p.join("meshes").is_dir() {
        Some(p)
    } else {
        eprintln!("skipped: no shared data at {}", p.display());
        None
    }
}

fn mesh_files(shared: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut dirs = vec![shared.join("meshes")];
    if let Ok(cases) = std::fs::read_dir(shared.join("cases")) {
        dirs.extend(cases.flatten().map(|e| e.path()));
    }
    for d in dirs {
        if let Ok(entries) = std::fs::read_dir(&d) {
            for e in entries.flatten() {
                let p = e.path();
                if matches!(
                    p.extension().and_then(|x| x.to_str()),
                    Some("mmed" | "med" | "mail" | "msh" | "mgib")
                ) {
                    files.push(p);
                }
            }
        }
    }
    files.sort();
    files
}

/// Signed volume measure of a cell's first corner tetrahedron, code_aster order.
fn corner_volume(
    m: &Mesh,
    nodes: &[aster_mesh::NodeId],
    a: usize,
    b: usize,
    c: usize,
    d: usize,
) -> f64 {
    let p = |i: usize| m.coord(nodes[i]);
    let (o, u, v, w) = (p(a), p(b), p(c), p(d));
    let s = |x: [f64; 3]| [x[0] - o[0], x[1] - o[1], x[2] - o[2]];
    let (u, v, w) = (s(u), s(v), s(w));
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

#[test]
fn every_shared_mesh_reads_consistently() {
    let Some(shared) = shared() else { return };
    let files = mesh_files(&shared);
    assert!(
        files.len() >= 120,
        "expected the 116 sample meshes and the case meshes, found {}",
        files.len()
    );
    let mut failures = Vec::new();
    // Volume cells, and those whose corner trihedra disagree in sign.
    let (mut volumes, mut twisted, mut first_twisted) = (0usize, 0usize, None);
    let (mut with_volumes, mut inverted_files) = (0usize, 0usize);
    for f in &files {
        match read_mesh(f) {
            Ok(m) => {
                assert!(m.node_count() > 0, "{}: no nodes", f.display());
                assert_eq!(m.node_names.len(), m.node_count());
                assert_eq!(m.cell_names.len(), m.cells.len());
                let (mut file_volumes, mut file_negative) = (0usize, 0usize);
                for c in &m.cells {
                    assert_eq!(c.nodes.len(), c.ty.node_count());
                    assert!(c.nodes.iter().all(|n| (n.0 as usize) < m.node_count()));
                    let Some(signs) = corner_signs(&m, c.ty, &c.nodes) else {
                        continue;
                    };
                    volumes += 1;
                    file_volumes += 1;
                    // A wrong node permutation (MED to code_aster order)
                    // turns a hexahedron or a prism into a twisted cell whose
                    // corners disagree; a whole cell inverted on purpose (or
                    // by the mesher: code_aster integrates with |J|) keeps
                    // every corner of one sign.
                    if signs.iter().all(|&s| s < 0.0) {
                        file_negative += 1;
                    } else if !signs.iter().all(|&s| s > 0.0) {
                        twisted += 1;
                        first_twisted.get_or_insert_with(|| {
                            format!("{}: {} {:?}", f.display(), c.ty.name(), signs)
                        });
                    }
                }
                for g in &m.groups_ma {
                    assert!(
                        !g.members.is_empty(),
                        "{}: empty group {}",
                        f.display(),
                        g.name
                    );
                }
                if file_volumes > 0 {
                    with_volumes += 1;
                    inverted_files += (2 * file_negative > file_volumes) as usize;
                }
            }
            Err(e) => failures.push(e.to_string()),
        }
    }
    assert!(
        failures.is_empty(),
        "{} meshes failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    eprintln!(
        "{} meshes read; {with_volumes} with volumes ({inverted_files} mostly inverted), \
         {volumes} volume cells, {twisted} twisted",
        files.len()
    );
    assert!(with_volumes >= 30);
    // A few real cells are degenerate (a collapsed corner gives a zero
    // trihedron); a wrong permutation would twist every cell of its type.
    assert!(
        twisted * 1000 < volumes,
        "{twisted} of {volumes} volume cells have corners of both signs \
         (wrong MED node permutation?), first: {first_twisted:?}"
    );
    // Tetrahedra cannot twist: a wrong permutation inverts all of them in
    // every file, so most files must still read direct.
    assert!(
        inverted_files * 4 < with_volumes,
        "{inverted_files} of {with_volumes} meshes have mostly inverted volumes"
    );
}

/// Signed volumes of the corner trihedra of a volume cell (code_aster
/// order: each corner with its three edge neighbours, ordered so that the
/// reference element gives positive values); `None` for other cells.
fn corner_signs(m: &Mesh, ty: CellType, nodes: &[aster_mesh::NodeId]) -> Option<Vec<f64>> {
    let corners: Vec<[usize; 4]> = match ty {
        CellType::TETRA4 | CellType::TETRA10 => vec![[0, 1, 2, 3]],
        CellType::HEXA8 | CellType::HEXA20 | CellType::HEXA27 => (0..4)
            .flat_map(|k| {
                let (prev, next) = ((k + 3) % 4, (k + 1) % 4);
                [[k, next, prev, k + 4], [k + 4, prev + 4, next + 4, k]]
            })
            .collect(),
        CellType::PENTA6 | CellType::PENTA15 | CellType::PENTA18 => (0..3)
            .flat_map(|k| {
                let (prev, next) = ((k + 2) % 3, (k + 1) % 3);
                [[k, next, prev, k + 3], [k + 3, prev + 3, next + 3, k]]
            })
            .collect(),
        _ => return None,
    };
    Some(
        corners
            .iter()
            .map(|&[a, b, c, d]| corner_volume(m, nodes, a, b, c, d))
            .collect(),
    )
}

#[test]
fn seed_mesh_matches_its_description() {
    let Some(shared) = shared() else { return };
    let m = read_mesh(&shared.join("cases/zzzz237/zzzz237a.mmed")).unwrap();
    let s = serde_json::to_string(&m.summary()).unwrap();
    assert_eq!(
        s,
        r#"{"nodes":10,"cells":{"SEG2":10,"QUAD4":2},"groups_ma":["AB","BC","CD","DA","ABCD","K1","K2","EF","FG","GH","HE","EFGH"],"groups_no":["A","B","C","D","R1","R2","E","F","G","H"]}"#
    );
    assert_eq!(m.dim, 2);
    // Node 2 is B (100, 0); node 5 is E (0, 100).
    assert_eq!(m.coords[1], [100.0, 0.0, 0.0]);
    assert_eq!(m.coords[4], [0.0, 200.0, 0.0]);
    // The square ABCD: nodes stored "no interlace" in the file.
    let abcd = m.group_ma("ABCD").unwrap().members[0];
    let nodes: Vec<u32> = m.cell(abcd).nodes.iter().map(|n| n.0 + 1).collect();
    assert_eq!(nodes, [2, 1, 4, 3]);
    assert_eq!(m.group_no("R1").unwrap().members.len(), 1);
    assert_eq!(m.cell_names[0], "M1");
}

#[test]
fn med_versions_and_layouts_are_all_covered() {
    let Some(shared) = shared() else { return };
    let mut versions = std::collections::BTreeSet::new();
    for f in mesh_files(&shared) {
        if !matches!(f.extension().and_then(|x| x.to_str()), Some("med" | "mmed")) {
            continue;
        }
        let (_, info) = aster_mesh::read_med_named(&f, None).unwrap();
        if let Some((a, b, _)) = info.version {
            versions.insert((a, b));
        }
    }
    for v in [(2, 2), (2, 3), (3, 0), (3, 2), (3, 3), (4, 0), (4, 1)] {
        assert!(
            versions.contains(&v),
            "no MED {v:?} file read: {versions:?}"
        );
    }
}

#[test]
fn corrupted_real_files_give_errors_not_panics() {
    let Some(shared) = shared() else { return };
    // The HDF5 1.6 seed (layout v2, old headers) and MED 3 / 4 files (dense attributes).
    for name in [
        "cases/zzzz237/zzzz237a.mmed",
        "meshes/zzzz504z.mmed",
        "meshes/ssnv263c.mmed",
        "meshes/tpna01b.mmed",
    ] {
        let Ok(original) = std::fs::read(shared.join(name)) else {
            continue;
        };
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let iterations: usize = std::env::var("ASTER_FUZZ_ITERS")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(300);
        for _ in 0..iterations {
            let mut bytes = original.clone();
            // Corrupt the metadata-heavy start more often than the raw data.
            for _ in 0..1 + next() % 6 {
                let span = if next() % 2 == 0 {
                    4096.min(bytes.len())
                } else {
                    bytes.len()
                };
                let i = (next() as usize) % span;
                bytes[i] = next() as u8;
            }
            if next() % 4 == 0 {
                let keep = (next() as usize) % bytes.len();
                bytes.truncate(keep);
            }
            let _ = aster_mesh::med::read_med_bytes(bytes, Path::new(name), None);
        }
    }
}

#[test]
fn seed_scene_operations() {
    let Some(shared) = shared() else { return };
    let mut m = read_mesh(&shared.join("cases/zzzz237/zzzz237a.mmed")).unwrap();
    // MODI_MAILLAGE(ORIE_PEAU=_F(GROUP_MA_PEAU=(AB, BC, CD, DA, EF, FG, GH, HE)))
    let skin = ["AB", "BC", "CD", "DA", "EF", "FG", "GH", "HE"];
    let r = m.orient_skin(&skin).unwrap();
    assert_eq!(r.cells, 8);
    for name in skin {
        let cell = m.cell(m.group_ma(name).unwrap().members[0]);
        let n = m.skin_normal(cell);
        let mid = {
            let (a, b) = (m.coord(cell.nodes[0]), m.coord(cell.nodes[1]));
            [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
        };
        // Squares ABCD = [0,100]², EFGH = [-50,150]×[-100,0]: the normal points away from the centre.
        let centre = if ["AB", "BC", "CD", "DA"].contains(&name) {
            [50.0, 50.0]
        } else {
            [50.0, -50.0]
        };
        assert!(
            n[0] * (mid[0] - centre[0]) + n[1] * (mid[1] - centre[1]) > 0.0,
            "{name}: {n:?}"
        );
    }
    // DEFI_GROUP(CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI'))
    assert!(m.crea_group_no_tout_group_ma().is_empty());
    assert_eq!(m.group_no("ABCD").unwrap().members.len(), 4);
    assert_eq!(m.group_no("CD").unwrap().members.len(), 2);
    assert_eq!(m.groups_no.len(), 22);
}

/// code_aster's mid-edge nodes (0-based) and the corners they lie between.
fn mid_edges(ty: CellType) -> &'static [(usize, usize, usize)] {
    match ty {
        CellType::SEG3 => &[(2, 0, 1)],
        CellType::TRIA6 | CellType::TRIA7 => &[(3, 0, 1), (4, 1, 2), (5, 2, 0)],
        CellType::QUAD8 | CellType::QUAD9 => &[(4, 0, 1), (5, 1, 2), (6, 2, 3), (7, 3, 0)],
        CellType::TETRA10 => &[
            (4, 0, 1),
            (5, 1, 2),
            (6, 2, 0),
            (7, 0, 3),
            (8, 1, 3),
            (9, 2, 3),
        ],
        CellType::PENTA15 | CellType::PENTA18 => &[
            (6, 0, 1),
            (7, 1, 2),
            (8, 2, 0),
            (9, 0, 3),
            (10, 1, 4),
            (11, 2, 5),
            (12, 3, 4),
            (13, 4, 5),
            (14, 5, 3),
        ],
        CellType::PYRAM13 => &[
            (5, 0, 1),
            (6, 1, 2),
            (7, 2, 3),
            (8, 3, 0),
            (9, 0, 4),
            (10, 1, 4),
            (11, 2, 4),
            (12, 3, 4),
        ],
        CellType::HEXA20 | CellType::HEXA27 => &[
            (8, 0, 1),
            (9, 1, 2),
            (10, 2, 3),
            (11, 3, 0),
            (12, 0, 4),
            (13, 1, 5),
            (14, 2, 6),
            (15, 3, 7),
            (16, 4, 5),
            (17, 5, 6),
            (18, 6, 7),
            (19, 7, 4),
        ],
        _ => &[],
    }
}

#[test]
fn quadratic_nodes_sit_on_their_edges() {
    let Some(shared) = shared() else { return };
    // With a wrong permutation a mid node lands on another edge (error ≳ 0.5).
    let mut checked = std::collections::BTreeMap::new();
    for f in mesh_files(&shared) {
        let Ok(m) = read_mesh(&f) else { continue };
        for c in &m.cells {
            for &(mid, a, b) in mid_edges(c.ty) {
                let (p, q, r) = (
                    m.coord(c.nodes[a]),
                    m.coord(c.nodes[b]),
                    m.coord(c.nodes[mid]),
                );
                let len =
                    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                let off = ((r[0] - (p[0] + q[0]) / 2.0).powi(2)
                    + (r[1] - (p[1] + q[1]) / 2.0).powi(2)
                    + (r[2] - (p[2] + q[2]) / 2.0).powi(2))
                .sqrt();
                let e = checked.entry(c.ty.name()).or_insert((0usize, 0usize));
                e.0 += 1;
                e.1 += (off > 0.25 * len) as usize;
            }
        }
    }
    eprintln!("mid-edge nodes checked (total, off their edge): {checked:?}");
    for ty in ["TETRA10", "HEXA20", "PENTA15", "PYRAM13", "QUAD8", "TRIA6"] {
        let (n, bad) = checked.get(ty).copied().unwrap_or((0, 0));
        assert!(n > 0, "no {ty} in the corpus");
        assert!(
            bad * 100 <= n,
            "{ty}: {bad} of {n} mid-edge nodes are off their edge"
        );
    }
}
