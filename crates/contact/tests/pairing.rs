//! Pairing on hand-built meshes: 2D projection and normals (orientation
//! from the parent cell), NODAL pairing, NORMALE, TOLE_PROJ_EXT, SANS_GROUP_NO,
//! 3D faces (TRIA3, QUAD4, QUAD8), and the errors a user can provoke.

use aster_contact::*;
use aster_mesh::{Cell, CellId, CellType, Group, Mesh, NodeId};

struct Builder {
    mesh: Mesh,
}

impl Builder {
    fn new(dim: u8) -> Self {
        Builder {
            mesh: Mesh {
                dim,
                ..Mesh::default()
            },
        }
    }
    fn node(&mut self, p: [f64; 3]) -> NodeId {
        self.mesh.coords.push(p);
        self.mesh
            .node_names
            .push(format!("N{}", self.mesh.coords.len()));
        NodeId(self.mesh.coords.len() as u32 - 1)
    }
    fn cell(&mut self, ty: CellType, nodes: &[NodeId]) -> CellId {
        self.mesh.cells.push(Cell {
            ty,
            nodes: nodes.to_vec(),
        });
        self.mesh
            .cell_names
            .push(format!("M{}", self.mesh.cells.len()));
        CellId(self.mesh.cells.len() as u32 - 1)
    }
    fn group_ma(&mut self, name: &str, members: Vec<CellId>) {
        self.mesh.groups_ma.push(Group {
            name: name.into(),
            members,
        });
    }
    fn group_no(&mut self, name: &str, members: Vec<NodeId>) {
        self.mesh.groups_no.push(Group {
            name: name.into(),
            members,
        });
    }
}

/// A block [0,4]×[-1,0] whose top edge (two SEG2, deliberately oriented
/// left to right, i.e. with the geometric normal pointing into the block)
/// is the master; slave nodes above it.
fn plane_2d(slaves: &[[f64; 3]]) -> Mesh {
    let mut b = Builder::new(2);
    let p = [
        b.node([0.0, -1.0, 0.0]),
        b.node([4.0, -1.0, 0.0]),
        b.node([4.0, 0.0, 0.0]),
        b.node([2.0, 0.0, 0.0]),
        b.node([0.0, 0.0, 0.0]),
    ];
    let m1 = b.cell(CellType::SEG2, &[p[4], p[3]]);
    let m2 = b.cell(CellType::SEG2, &[p[3], p[2]]);
    // The block: two quads under the master edges (their parents).
    let bottom_mid = b.node([2.0, -1.0, 0.0]);
    let qa = b.cell(CellType::QUAD4, &[p[0], bottom_mid, p[3], p[4]]);
    let qb = b.cell(CellType::QUAD4, &[bottom_mid, p[1], p[2], p[3]]);
    b.group_ma("MAIT", vec![m1, m2]);
    b.group_ma("BLOC", vec![qa, qb]);
    let mut slave_cells = Vec::new();
    let nodes: Vec<NodeId> = slaves.iter().map(|s| b.node(*s)).collect();
    for w in nodes.windows(2) {
        slave_cells.push(b.cell(CellType::SEG2, &[w[0], w[1]]));
    }
    // A parent for the slave side too, above it.
    if nodes.len() >= 2 {
        let top_r = b.node([slaves[slaves.len() - 1][0], 5.0, 0.0]);
        let top_l = b.node([slaves[0][0], 5.0, 0.0]);
        b.cell(
            CellType::QUAD4,
            &[nodes[0], nodes[nodes.len() - 1], top_r, top_l],
        );
    }
    b.group_ma("ESCL", slave_cells);
    b.group_no("S1", vec![nodes[0]]);
    b.mesh
}

fn pairs(mesh: &Mesh, geometry: ZoneGeometry) -> Vec<ContactPair> {
    let zone = ResolvedZone::new(0, &geometry, mesh).unwrap();
    nodal_points(&zone)
        .iter()
        .map(|p| pair_point(&zone, p, &mesh.coords).unwrap())
        .collect()
}

#[test]
fn projection_gap_and_outward_normal_in_2d() {
    let mesh = plane_2d(&[[1.0, 0.5, 0.0], [3.0, -0.25, 0.0]]);
    let ps = pairs(&mesh, ZoneGeometry::new("MAIT", "ESCL"));
    let gaps: Vec<f64> = ps.iter().map(|p| p.pairing().unwrap().gap).collect();
    assert!(
        (gaps[0] - 0.5).abs() < 1e-14 && (gaps[1] + 0.25).abs() < 1e-14,
        "{gaps:?}"
    );
    for p in &ps {
        let pr = p.pairing().unwrap();
        // Outward from the block although the cells point inwards.
        assert!((pr.normal[1] - 1.0).abs() < 1e-14, "{:?}", pr.normal);
        let w: f64 = pr.master.iter().map(|m| m.1).sum();
        assert!((w - 1.0).abs() < 1e-14);
    }
    // Slave at x = 1 projects at the middle of the first master cell.
    let first = ps[0].pairing().unwrap();
    assert!(first.master.iter().all(|m| (m.1 - 0.5).abs() < 1e-14));
}

#[test]
fn nodal_pairing_and_slave_normal() {
    let mesh = plane_2d(&[[1.9, 0.5, 0.0], [3.0, 0.3, 0.0]]);
    let mut g = ZoneGeometry::new("MAIT", "ESCL");
    g.appariement = Appariement::Nodal;
    let ps = pairs(&mesh, g.clone());
    let pr = ps[0].pairing().unwrap();
    assert_eq!(pr.master.len(), 1);
    assert_eq!(pr.master_x, [2.0, 0.0, 0.0]);
    assert!((pr.gap - 0.5).abs() < 1e-14);
    // NORMALE='ESCL': minus the slave outward normal (the slave edge is
    // inclined, so the normal differs from the master's).
    g.appariement = Appariement::MaitEscl;
    g.normale = NormalChoice::Escl;
    let ps = pairs(&mesh, g);
    let n = ps[0].pairing().unwrap().normal;
    let (dx, dy): (f64, f64) = (3.0 - 1.9, 0.3 - 0.5);
    let l = (dx * dx + dy * dy).sqrt();
    // Slave outward normal points down-left of the edge: (dy, -dx)/l; the contact normal is its opposite.
    assert!(
        (n[0] - -dy / l).abs() < 1e-12 && (n[1] - dx / l).abs() < 1e-12,
        "{n:?}"
    );
}

/// Continuous elements integrated at the nodes (`INTEGRATION='AUTO'`) put
/// one point on a slave node per slave cell around it. With the slave's
/// normal (`NORMALE='ESCL'`, `'MAIT_ESCL'`) code_aster takes the node's
/// normal averaged over those cells (`cftanr`: `APPARI_NOEUD_TAU1/2`,
/// smoothed by `aptgnn`) for both points, not each cell's own normal.
#[test]
fn points_on_a_slave_node_take_the_averaged_nodal_normal() {
    // A slave kinked at (2, 0.3): its two cells' outward normals are
    // (∓0.2, −1)/√1.04, their average (0, −1).
    let mesh = plane_2d(&[[1.0, 0.5, 0.0], [2.0, 0.3, 0.0], [3.0, 0.5, 0.0]]);
    let middle = NodeId(
        mesh.coords
            .iter()
            .position(|c| *c == [2.0, 0.3, 0.0])
            .unwrap() as u32,
    );
    for normale in [NormalChoice::Escl, NormalChoice::MaitEscl] {
        let mut g = ZoneGeometry::new("MAIT", "ESCL");
        g.normale = normale;
        let zone = ResolvedZone::new(0, &g, &mesh).unwrap();
        let cell_of = |ci: usize| {
            zone.slave
                .iter()
                .position(|c| c.nodes.contains(&middle) && c.nodes[ci] == middle)
                .unwrap()
        };
        // The point ending the first cell and the one starting the second.
        for (ci, xi) in [(cell_of(1), [1.0, 0.0]), (cell_of(0), [-1.0, 0.0])] {
            let point = SlavePoint {
                zone: 0,
                nodes: vec![(middle, 1.0)],
                weight: 1.0,
                cell: Some((ci, xi)),
            };
            let pr = pair_point(&zone, &point, &mesh.coords).unwrap();
            let pr = pr.pairing().unwrap();
            assert!(
                pr.normal[0].abs() < 1e-14 && (pr.normal[1] - 1.0).abs() < 1e-14,
                "{normale:?}, cell {ci}: {:?}",
                pr.normal
            );
            assert!((pr.gap - 0.3).abs() < 1e-14, "{}", pr.gap);
        }
        // A point inside a cell keeps that cell's normal.
        let inside = SlavePoint {
            zone: 0,
            nodes: vec![(middle, 0.5), (NodeId(middle.0 + 1), 0.5)],
            weight: 1.0,
            cell: Some((cell_of(0), [0.0, 0.0])),
        };
        let pr = pair_point(&zone, &inside, &mesh.coords).unwrap();
        let n = pr.pairing().unwrap().normal;
        if normale == NormalChoice::Escl {
            let l = 1.04f64.sqrt();
            assert!(
                (n[0] + 0.2 / l).abs() < 1e-12 && (n[1] - 1.0 / l).abs() < 1e-12,
                "{n:?}"
            );
        }
    }
}

#[test]
fn tole_proj_ext_and_dist_appa() {
    // Master spans x ∈ [0, 4]: a slave at x = 4.5 projects 0.5 outside the
    // second cell (length 2), i.e. 0.5 in reference coordinates.
    let mesh = plane_2d(&[[4.5, 0.1, 0.0], [6.0, 0.1, 0.0]]);
    let mut g = ZoneGeometry::new("MAIT", "ESCL");
    let ps = pairs(&mesh, g.clone());
    assert!(
        ps[0].pairing().is_some(),
        "within the default TOLE_PROJ_EXT = 0.5"
    );
    assert_eq!(
        ps[0].pairing().unwrap().master_x,
        [4.0, 0.0, 0.0],
        "clamped on the cell"
    );
    assert!(matches!(
        ps[1].status,
        PairStatus::Excluded(Exclusion::OutsideMaster { .. })
    ));
    g.tole_proj_ext = 0.1;
    assert!(pairs(&mesh, g.clone())[0].pairing().is_none());
    g.tole_proj_ext = -1.0;
    assert!(
        pairs(&mesh, g.clone())[1].pairing().is_some(),
        "negative = unlimited"
    );
    let g = ZoneGeometry::new("MAIT", "ESCL").with_dist_appa(0.4);
    assert!(matches!(
        pairs(&mesh, g)[0].status,
        PairStatus::Excluded(Exclusion::DistAppa { .. })
    ));
}

#[test]
fn sans_group_no_removes_slave_nodes() {
    let mesh = plane_2d(&[[1.0, 0.5, 0.0], [3.0, 0.5, 0.0]]);
    let mut g = ZoneGeometry::new("MAIT", "ESCL");
    g.excluded_node_groups = vec!["S1".into()];
    let zone = ResolvedZone::new(0, &g, &mesh).unwrap();
    assert_eq!(zone.slave_nodes.len(), 1);
    assert_eq!(mesh.coord(zone.slave_nodes[0])[0], 3.0);
}

#[test]
fn user_errors_are_explained() {
    let mesh = plane_2d(&[[1.0, 0.5, 0.0], [3.0, 0.5, 0.0]]);
    let err = ResolvedZone::new(0, &ZoneGeometry::new("MAITT", "ESCL"), &mesh).unwrap_err();
    assert_eq!(
        err.to_string(),
        "GROUP_MA_MAIT: the mesh has no group 'MAITT' (did you mean 'MAIT'?)"
    );
    let err = ResolvedZone::new(0, &ZoneGeometry::new("BLOC", "ESCL"), &mesh).unwrap_err();
    assert!(
        err.to_string()
            .contains("is a QUAD4; expected SEG2 or SEG3"),
        "{err}"
    );
    let err = ContactDefinition::discrete(
        vec![Zone {
            geometry: ZoneGeometry::new("MAIT", "ESCL"),
            law: DiscreteAlgo::Contrainte,
        }],
        Frottement::Coulomb,
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "FROTTEMENT='COULOMB' is not supported yet: give the zones' friction (ContactDefinition::discrete_with_friction / continuous_with_friction)"
    );
    let err = ContactDefinition::discrete(
        vec![Zone {
            geometry: ZoneGeometry::new("MAIT", "ESCL"),
            law: DiscreteAlgo::Penalisation { e_n: -1.0 },
        }],
        Frottement::Sans,
    )
    .unwrap_err();
    assert_eq!(err.to_string(), "E_N: must be a positive number, got -1");
}

/// A HEXA8 [0,2]×[0,2]×[-1,0] whose top face is split into master faces of
/// the given type; slave POI-like nodes carried by a slave QUAD4 above.
fn block_3d(top: CellType) -> Mesh {
    let mut b = Builder::new(3);
    let mut id = |x: f64, y: f64, z: f64| b.node([x, y, z]);
    let c: Vec<NodeId> = vec![
        id(0.0, 0.0, -1.0),
        id(2.0, 0.0, -1.0),
        id(2.0, 2.0, -1.0),
        id(0.0, 2.0, -1.0),
        id(0.0, 0.0, 0.0),
        id(2.0, 0.0, 0.0),
        id(2.0, 2.0, 0.0),
        id(0.0, 2.0, 0.0),
    ];
    let hexa = b.cell(CellType::HEXA8, &c);
    let faces = match top {
        CellType::TRIA3 => vec![
            b.cell(CellType::TRIA3, &[c[4], c[5], c[6]]),
            b.cell(CellType::TRIA3, &[c[4], c[6], c[7]]),
        ],
        CellType::QUAD4 => vec![b.cell(CellType::QUAD4, &[c[4], c[5], c[6], c[7]])],
        _ => {
            let m: Vec<NodeId> = [[1.0, 0.0], [2.0, 1.0], [1.0, 2.0], [0.0, 1.0]]
                .iter()
                .map(|p| b.node([p[0], p[1], 0.0]))
                .collect();
            vec![b.cell(
                CellType::QUAD8,
                &[c[4], c[5], c[6], c[7], m[0], m[1], m[2], m[3]],
            )]
        }
    };
    b.group_ma("BLOC", vec![hexa]);
    b.group_ma("MAIT", faces);
    let s: Vec<NodeId> = [[0.5, 0.5], [1.5, 0.4], [1.6, 1.7], [0.3, 1.5]]
        .iter()
        .map(|p| b.node([p[0], p[1], 0.2 + 0.1 * p[0]]))
        .collect();
    let sf = b.cell(CellType::QUAD4, &s);
    b.group_ma("ESCL", vec![sf]);
    b.mesh
}

#[test]
fn pairing_on_3d_faces() {
    for ty in [CellType::TRIA3, CellType::QUAD4, CellType::QUAD8] {
        let mesh = block_3d(ty);
        let ps = pairs(&mesh, ZoneGeometry::new("MAIT", "ESCL"));
        assert_eq!(ps.len(), 4);
        for p in &ps {
            let pr = p
                .pairing()
                .unwrap_or_else(|| panic!("{ty:?}: {:?}", p.status));
            let s = pr.slave_x;
            assert!(
                (pr.gap - s[2]).abs() < 1e-12,
                "{ty:?} gap {} vs {}",
                pr.gap,
                s[2]
            );
            assert!(
                (pr.normal[2] - 1.0).abs() < 1e-12,
                "{ty:?} normal {:?}",
                pr.normal
            );
            assert!((pr.master_x[0] - s[0]).abs() < 1e-12 && (pr.master_x[1] - s[1]).abs() < 1e-12);
        }
    }
}

#[test]
fn rows_linearise_the_gap() {
    // A slave node 0.5 above the middle of a master cell: row
    // −u_s,y + ½ u_m1,y + ½ u_m2,y ≤ 0.5.
    let mesh = plane_2d(&[[1.0, 0.5, 0.0], [3.0, 0.5, 0.0]]);
    let zone = ResolvedZone::new(0, &ZoneGeometry::new("MAIT", "ESCL"), &mesh).unwrap();
    let pts = nodal_points(&zone);
    let pair = pair_point(&zone, &pts[0], &mesh.coords).unwrap();
    let row = contact_row(
        &mesh,
        &mesh.coords,
        &pts[0].nodes,
        pair.pairing().unwrap(),
        2,
        1.0,
        7,
    );
    assert_eq!(row.id, 7);
    assert!((row.rhs - 0.5).abs() < 1e-14);
    let mut coefs: Vec<f64> = row.terms.iter().map(|t| t.1).collect();
    coefs.sort_by(f64::total_cmp);
    assert_eq!(coefs, vec![-1.0, 0.5, 0.5]);
    assert!(row.terms.iter().all(|t| t.0.comp == aster_fem::Comp::DY));
}

/// MAIT_ESCL projects only on the master cells around the nearest master
/// node (code_aster's approj): a slave point whose nearest master node ends
/// a cell it projects far outside of is not paired, even though another
/// master cell lies right under it.
#[test]
fn projection_only_on_the_cells_of_the_nearest_master_node() {
    let mut b = Builder::new(2);
    let a = b.node([0.0, 0.0, 0.0]);
    let bb = b.node([10.0, 0.0, 0.0]);
    let c = b.node([5.0, 2.0, 0.0]);
    let d = b.node([5.0, 4.0, 0.0]);
    let m1 = b.cell(CellType::SEG2, &[a, bb]);
    let m2 = b.cell(CellType::SEG2, &[c, d]);
    b.group_ma("MAIT", vec![m1, m2]);
    let s1 = b.node([5.0, 1.2, 0.0]);
    let s2 = b.node([20.0, 1.2, 0.0]);
    let e = b.cell(CellType::SEG2, &[s1, s2]);
    b.group_ma("ESCL", vec![e]);
    let mesh = b.mesh;
    // Nearest master node of (5, 1.2): C at 0.8 (A and B are 5.1 away);
    // C's only cell is CD, projected 0.8 beyond C (half-length 1) > 0.5.
    let ps = pairs(&mesh, ZoneGeometry::new("MAIT", "ESCL"));
    match &ps[0].status {
        PairStatus::Excluded(Exclusion::OutsideMaster { outside }) => {
            assert!((outside - 0.8).abs() < 1e-12, "{outside}")
        }
        other => panic!("{other:?}"),
    }
    // Tolerated (TOLE_PROJ_EXT = 1): brought back onto C, the gap is
    // measured along CD's normal, not on AB right below.
    let mut g = ZoneGeometry::new("MAIT", "ESCL");
    g.tole_proj_ext = 1.0;
    let pr = pairs(&mesh, g)[0].pairing().cloned().unwrap();
    assert_eq!(pr.master_x, [5.0, 2.0, 0.0]);
    assert_eq!(pr.nearest_master_node, c);
    assert!(pr.gap.abs() < 1e-14, "{}", pr.gap);
}

/// CONT_NOEU of a RESOLUTION='NON' zone: code_aster's verification status
/// (0 apart or within TOLE_INTERP, 3 beyond) and the gap.
#[test]
fn verification_zone_status_in_cont_noeu() {
    let mesh = plane_2d(&[[1.0, 0.5, 0.0], [2.5, -0.2, 0.0], [3.5, -0.4, 0.0]]);
    let mut g = ZoneGeometry::new("MAIT", "ESCL");
    g.resolve = false;
    g.tole_interp = 0.3;
    let zone = ResolvedZone::new(0, &g, &mesh).unwrap();
    let mut zc = ZoneContact::new(
        zone,
        ZoneLaw::Discrete(DiscreteAlgo::Contrainte),
        GeomLoop::default(),
    );
    assert!(zc.pair(&mesh, &mesh.coords).unwrap().is_empty(), "no rows");
    let cn = ContNoeu::from_zones(&[zc], &mesh.coords, &mesh).unwrap();
    let got: Vec<(f64, f64)> = cn
        .nodes
        .iter()
        .map(|&n| (cn.value(n, "CONT").unwrap(), cn.value(n, "JEU").unwrap()))
        .collect();
    let want = [(0.0, 0.5), (0.0, -0.2), (3.0, -0.4)];
    for ((c, j), (wc, wj)) in got.iter().zip(want) {
        assert_eq!(*c, wc, "{got:?}");
        assert!((j - wj).abs() < 1e-14, "{got:?}");
    }
}

/// CONT_NOEU of a RESOLUTION='NON' zone at a stored step reports the gaps
/// of the pairing that step ended with (code_aster's `cfveri`), not a new
/// pairing on the step's final geometry.
#[test]
fn verification_zone_reports_the_last_pairing_of_the_step() {
    use aster_fem::{
        Comp, Dof, Elastic, Element, ElementKind, Hypothesis, Model, State, UnilateralSource,
    };
    let mesh = plane_2d(&[[1.0, 0.5, 0.0], [3.0, 0.5, 0.0]]);
    let material = Elastic::new(1000.0, 0.3).unwrap();
    let elements = (0..mesh.cells.len())
        .map(|i| Element {
            cell: CellId(i as u32),
            kind: if mesh.cells[i].ty == CellType::QUAD4 {
                ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material,
                }
            } else {
                ElementKind::Boundary
            },
        })
        .collect();
    let model = Model::new(mesh.clone(), elements).unwrap();
    let mut g = ZoneGeometry::new("MAIT", "ESCL");
    g.resolve = false;
    let zone = ResolvedZone::new(0, &g, &mesh).unwrap();
    let slaves = zone.slave_nodes.clone();
    let mut zc = ZoneContact::new(
        zone,
        ZoneLaw::Discrete(DiscreteAlgo::Contrainte),
        GeomLoop::default(),
    );
    // The slave side lowered by 0.1 when last paired, by 0.3 at the end.
    let lowered = |dy: f64| {
        let mut u = vec![0.0; model.dofs().len()];
        for &n in &slaves {
            u[model.dofs().index(Dof::new(n, Comp::DY)).unwrap()] = -dy;
        }
        u
    };
    let (u1, u_end) = (lowered(0.1), lowered(0.3));
    let state = |u| State {
        mesh: model.mesh(),
        dofs: model.dofs(),
        displacement: u,
        time: 2.0,
    };
    assert!(zc.rows(&state(&u1)).unwrap().is_empty());
    zc.converged(&state(&u_end), &[]).unwrap();
    let x_end = positions(model.mesh(), model.dofs(), &u_end);
    let mut zones = [zc];
    let reported = ContNoeu::at_step_time(&mut zones, &mesh, &x_end, &[vec![]], 2.0).unwrap();
    let repaired = ContNoeu::at_step(&mut zones, &mesh, &x_end, &[vec![]]).unwrap();
    for &n in &slaves {
        let jeu = reported.value(n, "JEU").unwrap();
        assert!((jeu - 0.4).abs() < 1e-14, "{jeu}");
        let jeu_end = repaired.value(n, "JEU").unwrap();
        assert!((jeu_end - 0.2).abs() < 1e-14, "{jeu_end}");
    }
}

/// TYPE_PROJECTION='FIXE' with DIRE_APPA (code_aster's `mmnewd`): the
/// master point is where the line through the slave node along the
/// direction meets the master, not its foot; on a flat master the gap
/// (measured along the master normal) is the same, the master weights are
/// not.
#[test]
fn a_fixed_projection_direction_moves_the_master_point() {
    // Slave node at (1, 0.5) above the first master cell [0, 2] × {0}.
    let mesh = plane_2d(&[[1.0, 0.5, 0.0], [3.0, 0.5, 0.0]]);
    let orth = pairs(&mesh, ZoneGeometry::new("MAIT", "ESCL"));
    let o = orth[0].pairing().unwrap();
    assert_eq!(o.master_x, [1.0, 0.0, 0.0]);
    let mut g = ZoneGeometry::new("MAIT", "ESCL");
    let s = 0.5f64.sqrt();
    g.dire_appa = Some([s, -s, 0.0]);
    let fixed = pairs(&mesh, g);
    let f = fixed[0].pairing().unwrap();
    // Down and to the right at 45°: the master at x = 1.5.
    assert!(
        (f.master_x[0] - 1.5).abs() < 1e-12 && f.master_x[1].abs() < 1e-12,
        "{:?}",
        f.master_x
    );
    assert!((f.gap - o.gap).abs() < 1e-14 && (f.gap - 0.5).abs() < 1e-14);
    // Weights of the master cell's nodes (x = 0 and x = 2): 1/4 and 3/4.
    let mut w: Vec<f64> = f.master.iter().map(|m| m.1).collect();
    w.sort_by(f64::total_cmp);
    assert!(
        (w[0] - 0.25).abs() < 1e-12 && (w[1] - 0.75).abs() < 1e-12,
        "{w:?}"
    );
    assert_eq!(f.normal, o.normal);
}

/// `VECT_MAIT='VECT_Y'` on a face (code_aster's `aptgnn`): the face's
/// outward normal without its component along VECT_Y, whichever node the
/// face starts with (an edge parallel to VECT_Y must not matter).
#[test]
fn vect_y_on_a_face_projects_the_face_normal() {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    for rotate in 0..4 {
        let mut mesh = block_3d(CellType::QUAD4);
        let face = mesh.group_ma("MAIT").unwrap().members[0];
        mesh.cells[face.0 as usize].nodes.rotate_left(rotate);
        for (v, expected) in [
            ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 2.0, 2.0], [0.0, -w, w]),
        ] {
            let mut g = ZoneGeometry::new("MAIT", "ESCL");
            g.vect_mait = NormalSource::VectY(v);
            for p in pairs(&mesh, g) {
                let n = p.pairing().unwrap().normal;
                for k in 0..3 {
                    assert!(
                        (n[k] - expected[k]).abs() < 1e-12,
                        "rotation {rotate}, VECT_Y {v:?}: normal {n:?}"
                    );
                }
            }
        }
    }
}
