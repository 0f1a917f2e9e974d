//! code_aster's mixed incompressible elements (`*_INCO_UPG`,
//! `aster_fem::mixed_upg`): the PRES and GONF unknowns at the vertices, the
//! patch test (a homogeneous strain reproduced exactly, PRES the mean
//! stress and GONF the volume change), rigid modes in the kernel of the
//! element matrix, and the absence of volumetric locking where the
//! displacement element locks.
#![allow(clippy::needless_range_loop)]

mod common;

use aster_fem::*;
use aster_mesh::{CellId, CellType, Mesh, NodeId};
use common::MeshBuilder;

/// An `nx × ny` grid of QUAD8 (or TRIA6 pairs) on [0, lx] × [0, ly], the
/// interior vertices moved to distort the cells.
fn grid(nx: usize, ny: usize, lx: f64, ly: f64, tria: bool, distort: bool) -> Mesh {
    let mut mb = MeshBuilder::new(2);
    let (mx, my) = (2 * nx + 1, 2 * ny + 1);
    let mut ids = vec![vec![NodeId(0); my]; mx];
    for i in 0..mx {
        for j in 0..my {
            let mut x = lx * i as f64 / (mx - 1) as f64;
            let mut y = ly * j as f64 / (my - 1) as f64;
            let interior = i > 0 && i < mx - 1 && j > 0 && j < my - 1;
            if distort && interior && i % 2 == 0 && j % 2 == 0 {
                x += 0.13 * lx / nx as f64 * ((i + 2 * j) as f64).sin();
                y += 0.11 * ly / ny as f64 * ((3 * i + j) as f64).cos();
            }
            ids[i][j] = mb.node(&format!("N{i}_{j}"), [x, y, 0.]);
        }
    }
    // Mid-edge nodes on the straight segments between moved vertices.
    for i in 0..mx {
        for j in 0..my {
            if i % 2 == 1 || j % 2 == 1 {
                let (i0, i1) = if i % 2 == 1 { (i - 1, i + 1) } else { (i, i) };
                let (j0, j1) = if j % 2 == 1 { (j - 1, j + 1) } else { (j, j) };
                let a = mb.mesh.coords[ids[i0][j0].0 as usize];
                let b = mb.mesh.coords[ids[i1][j1].0 as usize];
                if i % 2 == 1 && j % 2 == 1 {
                    continue;
                }
                mb.mesh.coords[ids[i][j].0 as usize] = [(a[0] + b[0]) / 2., (a[1] + b[1]) / 2., 0.];
            }
        }
    }
    for ci in 0..nx {
        for cj in 0..ny {
            let (i, j) = (2 * ci, 2 * cj);
            let n = |a: usize, b: usize| ids[i + a][j + b];
            if tria {
                let t1 = [n(0, 0), n(2, 0), n(2, 2), n(1, 0), n(2, 1), n(1, 1)];
                let t2 = [n(0, 0), n(2, 2), n(0, 2), n(1, 1), n(1, 2), n(0, 1)];
                mb.cell(&format!("T{ci}_{cj}a"), CellType::TRIA6, &t1);
                mb.cell(&format!("T{ci}_{cj}b"), CellType::TRIA6, &t2);
            } else {
                let q = [
                    n(0, 0),
                    n(2, 0),
                    n(2, 2),
                    n(0, 2),
                    n(1, 0),
                    n(2, 1),
                    n(1, 2),
                    n(0, 1),
                ];
                mb.cell(&format!("Q{ci}_{cj}"), CellType::QUAD8, &q);
            }
        }
    }
    // The diagonal mid-nodes of the triangles.
    if tria {
        for ci in 0..nx {
            for cj in 0..ny {
                let (i, j) = (2 * ci + 1, 2 * cj + 1);
                let a = mb.mesh.coords[ids[i - 1][j - 1].0 as usize];
                let b = mb.mesh.coords[ids[i + 1][j + 1].0 as usize];
                mb.mesh.coords[ids[i][j].0 as usize] = [(a[0] + b[0]) / 2., (a[1] + b[1]) / 2., 0.];
            }
        }
    }
    mb.mesh
}

fn model(mesh: Mesh, hyp: Hypothesis, e: f64, nu: f64, mixed: bool) -> Model {
    let material = Elastic::new(e, nu).unwrap();
    let n = mesh.cells.len();
    let elements = (0..n)
        .map(|c| Element {
            cell: CellId(c as u32),
            kind: ElementKind::Continuum {
                hypothesis: hyp,
                material,
            },
        })
        .collect();
    let m = Model::new(mesh, elements).unwrap();
    if mixed {
        m.with_mixed((0..n as u32).map(CellId)).unwrap()
    } else {
        m
    }
}

#[test]
fn vertices_carry_pres_and_gonf_mid_nodes_do_not() {
    let m = model(
        grid(1, 1, 1., 1., false, false),
        Hypothesis::PlaneStrain,
        1.,
        0.3,
        true,
    );
    let cell = &m.mesh().cells[0];
    for (k, n) in cell.nodes.iter().enumerate() {
        let comps = m.dofs().node_comps(*n);
        if k < 4 {
            assert_eq!(comps, &[Comp::DX, Comp::DY, Comp::PRES, Comp::GONF]);
        } else {
            assert_eq!(comps, &[Comp::DX, Comp::DY]);
        }
    }
    assert_eq!(m.dofs().len(), 8 * 2 + 4 * 2);
}

#[test]
fn mixed_cells_refused_on_linear_cells_and_in_plane_stress() {
    let mut mb = MeshBuilder::new(2);
    let n: Vec<NodeId> = [[0., 0.], [1., 0.], [1., 1.], [0., 1.]]
        .iter()
        .map(|p| mb.node("N", [p[0], p[1], 0.]))
        .collect();
    mb.cell("Q", CellType::QUAD4, &n);
    let mesh = mb.mesh;
    let quad4 = model(mesh, Hypothesis::PlaneStrain, 1., 0.3, false);
    let err = quad4.with_mixed([CellId(0)]).unwrap_err().to_string();
    assert!(err.contains("QUAD4"), "{err}");
    let cp = model(
        grid(1, 1, 1., 1., false, false),
        Hypothesis::PlaneStress,
        1.,
        0.3,
        false,
    );
    assert!(cp.with_mixed([CellId(0)]).is_err());
}

/// A homogeneous strain imposed on the boundary is reproduced inside:
/// displacements, PRES = tr σ/3, GONF = tr ε at every vertex, SIEF_ELGA
/// = σ and SIP = 0, on distorted QUAD8 and TRIA6 meshes, plane strain and
/// axisymmetric, nearly incompressible.
#[test]
fn patch_test_plane_strain_and_axis() {
    for tria in [false, true] {
        for hyp in [Hypothesis::PlaneStrain, Hypothesis::Axisymmetric] {
            let (e, nu) = (200.0, 0.4999);
            let mesh = grid(3, 2, 2., 1., tria, true);
            // A field affine in x, y; in AXIS u_r = a r keeps it
            // homogeneous (εθθ = a).
            let g = [[1e-3, 4e-4], [-2e-4, -5e-4]];
            let g = if hyp == Hypothesis::Axisymmetric {
                [[1e-3, 0.], [0., -5e-4]]
            } else {
                g
            };
            let field = |p: [f64; 3]| {
                [
                    g[0][0] * p[0] + g[0][1] * p[1],
                    g[1][0] * p[0] + g[1][1] * p[1],
                ]
            };
            let x0 = if hyp == Hypothesis::Axisymmetric {
                1.0
            } else {
                0.0
            };
            let mut mesh = mesh;
            for c in &mut mesh.coords {
                c[0] += x0;
            }
            let m = model(mesh, hyp, e, nu, true);
            let mesh = m.mesh().clone();
            let (lo, hi) = ([x0, 0.], [x0 + 2., 1.]);
            let boundary = |p: [f64; 3]| {
                (0..2).any(|k| (p[k] - lo[k]).abs() < 1e-12 || (p[k] - hi[k]).abs() < 1e-12)
            };
            let mut loads = Loads::new();
            for (n, &p) in mesh.coords.iter().enumerate() {
                if !m.dofs().has_node(NodeId(n as u32)) {
                    continue; // the QUAD8 grid's centres
                }
                if boundary(p) {
                    let u = field(p);
                    for (k, comp) in [Comp::DX, Comp::DY].into_iter().enumerate() {
                        loads.push(Load::Eliminated {
                            dof: Dof::new(NodeId(n as u32), comp),
                            value: u[k],
                        });
                    }
                }
            }
            let res = meca_statique(&m, &loads, &[]).unwrap();
            let u = &res.steps[0].displacement;
            let ezz = if hyp == Hypothesis::Axisymmetric {
                g[0][0]
            } else {
                0.
            };
            let eps = [g[0][0], g[1][1], ezz, g[0][1] + g[1][0]];
            let d = Elastic::new(e, nu).unwrap().hooke(hyp);
            let sig: Vec<f64> = (0..4)
                .map(|i| (0..4).map(|j| d[(i, j)] * eps[j]).sum())
                .collect();
            let mean = (sig[0] + sig[1] + sig[2]) / 3.;
            let scale = sig.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            for (n, &p) in mesh.coords.iter().enumerate() {
                let node = NodeId(n as u32);
                if !m.dofs().has_node(node) {
                    continue;
                }
                let want = field(p);
                for (k, comp) in [Comp::DX, Comp::DY].into_iter().enumerate() {
                    let got = u[m.dofs().index(Dof::new(node, comp)).unwrap()];
                    assert!(
                        (got - want[k]).abs() < 1e-10,
                        "{hyp:?} tria={tria} {comp:?}: {got} vs {}",
                        want[k]
                    );
                }
                if let Some(i) = m.dofs().index(Dof::new(node, Comp::PRES)) {
                    assert!(
                        (u[i] - mean).abs() < 1e-7 * scale,
                        "{hyp:?} tria={tria} PRES {} vs {mean}",
                        u[i]
                    );
                    let gonf = u[m.dofs().index(Dof::new(node, Comp::GONF)).unwrap()];
                    let tr = eps[0] + eps[1] + eps[2];
                    assert!((gonf - tr).abs() < 1e-12, "GONF {gonf} vs {tr}");
                }
            }
            for cv in &res.steps[0].stress {
                assert_eq!(cv.names, ["SIXX", "SIYY", "SIZZ", "SIXY", "SIP"]);
                for p in &cv.points {
                    for c in 0..4 {
                        assert!(
                            (p[c] - sig[c]).abs() < 1e-7 * scale,
                            "{hyp:?} {}: {} vs {}",
                            cv.names[c],
                            p[c],
                            sig[c]
                        );
                    }
                    assert!(p[4].abs() < 1e-7 * scale, "SIP {}", p[4]);
                }
            }
        }
    }
}

/// The rigid modes (two translations, the rotation in the plane) with
/// PRES = GONF = 0 are in the kernel of the element matrix, of the
/// tangent (STAT_NON_LINE) as of RIGI_MECA (MECA_STATIQUE).
#[test]
fn rigid_modes_are_in_the_kernel() {
    for rigi in [false, true] {
        for tria in [false, true] {
            let mut m = model(
                grid(1, 1, 1.3, 0.7, tria, false),
                Hypothesis::PlaneStrain,
                1e3,
                0.45,
                true,
            );
            m.set_mixed_rigi_meca(rigi);
            let k = assembly::assemble_stiffness(&m).unwrap();
            let kmax = k.norm_inf();
            for mode in 0..3 {
                let x: Vec<f64> = m
                    .dofs()
                    .dofs()
                    .iter()
                    .map(|d| {
                        let p = m.mesh().coord(d.node);
                        match (mode, d.comp) {
                            (0, Comp::DX) | (1, Comp::DY) => 1.0,
                            (2, Comp::DX) => -p[1],
                            (2, Comp::DY) => p[0],
                            _ => 0.0,
                        }
                    })
                    .collect();
                let kx = k.mul(&x);
                let r = kx.iter().fold(0.0f64, |a, v| a.max(v.abs()));
                assert!(r < 1e-12 * kmax, "mode {mode} rigi={rigi} tria={tria}: {r}");
            }
        }
    }
}

/// Nearly incompressible plane-strain cantilever (ν = 0.49999) under an
/// end shear, 10 × 2 QUAD8: the displacement element is stiffened by the
/// incompressibility (measured: 9 % under the beam's deflection), the
/// mixed element much less (3.4 % under, the bending of two cells through
/// the depth).
#[test]
fn no_volumetric_locking_on_a_cantilever() {
    let (l, h, e, nu, f) = (10.0, 1.0, 1000.0, 0.4999999, 1e-3);
    let tip = |mixed: bool| -> f64 {
        let m = model(
            grid(10, 2, l, h, false, false),
            Hypothesis::PlaneStrain,
            e,
            nu,
            mixed,
        );
        let mesh = m.mesh().clone();
        let mut loads = Loads::new();
        let right: Vec<usize> = (0..mesh.coords.len())
            .filter(|&n| (mesh.coords[n][0] - l).abs() < 1e-12)
            .collect();
        for (n, p) in mesh.coords.iter().enumerate() {
            if p[0].abs() < 1e-12 {
                for comp in [Comp::DX, Comp::DY] {
                    loads.push(Load::Eliminated {
                        dof: Dof::new(NodeId(n as u32), comp),
                        value: 0.0,
                    });
                }
            }
        }
        // The end shear as consistent nodal forces of SEG3 edges (1/6,
        // 4/6, 1/6 of each edge's share).
        let ne = 2.0;
        for &n in &right {
            let y = mesh.coords[n][1];
            let k = (y / (h / (2.0 * ne))).round() as usize;
            let w = if k % 2 == 1 {
                4.0
            } else if k == 0 || k == 4 {
                1.0
            } else {
                2.0
            } / (6.0 * ne);
            loads.push(Load::NodalForce {
                dof: Dof::new(NodeId(n as u32), Comp::DY),
                value: -f * w,
            });
        }
        let res = meca_statique(&m, &loads, &[]).unwrap();
        let u = &res.steps[0].displacement;
        let top = right
            .iter()
            .find(|&&n| (mesh.coords[n][1] - h / 2.).abs() < 1e-12)
            .copied()
            .unwrap();
        u[m.dofs()
            .index(Dof::new(NodeId(top as u32), Comp::DY))
            .unwrap()]
    };
    // Plane-strain beam: E' = E/(1−ν²), bending + shear (κ = 5/6).
    let ep = e / (1. - nu * nu);
    let inertia = h * h * h / 12.;
    let mu = e / (2. * (1. + nu));
    let beam = f * l.powi(3) / (3. * ep * inertia) + f * l / (5. / 6. * mu * h);
    let mixed = -tip(true);
    let displacement = -tip(false);
    assert!(
        (mixed - beam).abs() < 0.05 * beam,
        "mixed {mixed} vs beam {beam}"
    );
    assert!(
        displacement < 0.95 * mixed,
        "the displacement element should lock: {displacement} vs mixed {mixed}"
    );
}
