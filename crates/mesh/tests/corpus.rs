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
    // Files with volume cells, and those whose volumes are mostly inverted.
    let (mut with_volumes, mut mostly_inverted) = (0usize, Vec::new());
    for f in &files {
        let (mut volumes, mut negative) = (0usize, 0usize);
        match read_mesh(f) {
            Ok(m) => {
                assert!(m.node_count() > 0, "{}: no nodes", f.display());
                assert_eq!(m.node_names.len(), m.node_count());
                assert_eq!(m.cell_names.len(), m.cells.len());
                for c in &m.cells {
                    assert_eq!(c.nodes.len(), c.ty.node_count());
                    assert!(c.nodes.iter().all(|n| (n.0 as usize) < m.node_count()));
                    // code_aster orders volumes so that the corner trihedron is direct.
                    let v = match c.ty {
                        CellType::TETRA4 | CellType::TETRA10 => {
                            Some(corner_volume(&m, &c.nodes, 0, 1, 2, 3))
                        }
                        CellType::HEXA8 | CellType::HEXA20 | CellType::HEXA27 => {
                            Some(corner_volume(&m, &c.nodes, 0, 1, 3, 4))
                        }
                        CellType::PENTA6 | CellType::PENTA15 | CellType::PENTA18 => {
                            Some(corner_volume(&m, &c.nodes, 0, 1, 2, 3))
                        }
                        _ => None,
                    };
                    if let Some(v) = v {
                        volumes += 1;
                        negative += (v < 0.0) as usize;
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
                if volumes > 0 {
                    with_volumes += 1;
                    if 2 * negative > volumes {
                        mostly_inverted.push(f.display().to_string());
                    }
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
        "{} meshes read; {with_volumes} with volumes, {} of them mostly inverted: {mostly_inverted:?}",
        files.len(),
        mostly_inverted.len()
    );
    // A few test meshes are inverted on purpose (reorientation tests); a
    // wrong MED permutation would invert nearly all of them.
    assert!(with_volumes >= 30);
    assert!(
        mostly_inverted.len() * 8 < with_volumes,
        "{} of {with_volumes} meshes have mostly inverted volumes: wrong MED node permutation?",
        mostly_inverted.len()
    );
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
        if f.extension().and_then(|x| x.to_str()) == Some("mail") {
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
