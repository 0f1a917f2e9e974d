//! Smoothed master normals (`LISSAGE='OUI'`) on quadratic faces, checked
//! against code_aster's formula written out here independently:
//!
//! - at each master node, each face around it gives its own unit normal
//!   from its derivatives **at that node** (`aptgem` → `mmctan`: the node is
//!   projected on the face, the tangents taken there, all 8 functions of a
//!   QUAD8); the nodal normal is their plain mean, normalised (`aptgnn`);
//! - at a point of a face, the nodal normals of all the face's nodes are
//!   interpolated with the face's own functions (8 serendipity functions
//!   on a QUAD8: `copnor` → `mmcoor`) and normalised.
//!
//! Scene: one row of QUAD8 faces on the cylinder r = R around z, of unequal
//! angular spans. A face over [θc − α, θc + α] interpolates the arc with a
//! parabola in ξ; its tangent at the end ξ = −1 is ∝ (2 − 2 cos α, sin α) in
//! the frame of its centre, so its normal there is the radius at θc − α
//! turned by ε(α) = α − atan(2 tan(α/2)) towards the face's centre (and
//! symmetrically at ξ = +1). The geometry being the tensor product of that
//! parabola and a straight line in z (which QUAD8 reproduces), the mid
//! nodes of the axial edges see the same normal as their corners, and the
//! mid node of a circumferential edge the radius through it.

use aster_contact::*;
use aster_mesh::{Cell, CellId, CellType, Group, Mesh, NodeId};

const R: f64 = 2.0;
/// Face boundaries (degrees): spans 10°, 20°, 15°.
const THETA: [f64; 4] = [0.0, 10.0, 30.0, 45.0];

fn polar(theta: f64, z: f64) -> [f64; 3] {
    [R * theta.cos(), R * theta.sin(), z]
}

/// The master faces, their nodes' angles and heights by node, and a
/// slave node (moved by the tests) of the slave face in group "S".
struct Scene {
    mesh: Mesh,
    /// (θ, z) of each master node.
    at: Vec<(f64, f64)>,
    slave: NodeId,
}

fn scene() -> Scene {
    let mut mesh = Mesh {
        dim: 3,
        ..Mesh::default()
    };
    let mut at = Vec::new();
    let mut node = |mesh: &mut Mesh, th: f64, z: f64| {
        mesh.coords.push(polar(th, z));
        mesh.node_names.push(format!("N{}", mesh.coords.len()));
        at.push((th, z));
        NodeId(mesh.coords.len() as u32 - 1)
    };
    let t: Vec<f64> = THETA.iter().map(|d| d.to_radians()).collect();
    // Corners at z = 0 and 1 and axial mid nodes at z = ½ on every θᵢ.
    let bottom: Vec<NodeId> = t.iter().map(|&th| node(&mut mesh, th, 0.0)).collect();
    let top: Vec<NodeId> = t.iter().map(|&th| node(&mut mesh, th, 1.0)).collect();
    let side: Vec<NodeId> = t.iter().map(|&th| node(&mut mesh, th, 0.5)).collect();
    let mut faces = Vec::new();
    for i in 0..t.len() - 1 {
        let mid = 0.5 * (t[i] + t[i + 1]);
        let mb = node(&mut mesh, mid, 0.0);
        let mt = node(&mut mesh, mid, 1.0);
        // (θ increasing, z increasing): t₁ × t₂ = e_θ × e_z = e_r, outwards.
        let nodes = vec![
            bottom[i],
            bottom[i + 1],
            top[i + 1],
            top[i],
            mb,
            side[i + 1],
            mt,
            side[i],
        ];
        mesh.cells.push(Cell {
            ty: CellType::QUAD8,
            nodes,
        });
        mesh.cell_names.push(format!("M{}", mesh.cells.len()));
        faces.push(CellId(mesh.cells.len() as u32 - 1));
    }
    // A slave QUAD4 far away; its first node is moved by the tests.
    let first = mesh.coords.len() as u32;
    for (k, p) in [
        [9.0, 9.0, 9.0],
        [10.0, 9.0, 9.0],
        [10.0, 10.0, 9.0],
        [9.0, 10.0, 9.0],
    ]
    .into_iter()
    .enumerate()
    {
        mesh.coords.push(p);
        mesh.node_names.push(format!("S{k}"));
    }
    let slave = NodeId(first);
    mesh.cells.push(Cell {
        ty: CellType::QUAD4,
        nodes: (first..first + 4).map(NodeId).collect(),
    });
    mesh.cell_names.push("MS".into());
    let s = CellId(mesh.cells.len() as u32 - 1);
    mesh.groups_ma.push(Group {
        name: "MAIT".into(),
        members: faces,
    });
    mesh.groups_ma.push(Group {
        name: "S".into(),
        members: vec![s],
    });
    Scene { mesh, at, slave }
}

/// Turn of a face's normal at its ends towards its centre (half-span α).
fn eps(alpha: f64) -> f64 {
    alpha - (2.0 * (alpha / 2.0).tan()).atan()
}

/// code_aster's nodal normal at a node of angle `th` (unit, horizontal).
fn expected_nodal(th: f64) -> [f64; 3] {
    let t: Vec<f64> = THETA.iter().map(|d| d.to_radians()).collect();
    let mut sum = [0.0; 3];
    for i in 0..t.len() - 1 {
        let (a, b) = (t[i], t[i + 1]);
        let alpha = 0.5 * (b - a);
        let dir = if (th - a).abs() < 1e-12 {
            Some(a + eps(alpha))
        } else if (th - b).abs() < 1e-12 {
            Some(b - eps(alpha))
        } else if (th - 0.5 * (a + b)).abs() < 1e-12 {
            Some(th)
        } else {
            None
        };
        if let Some(phi) = dir {
            sum[0] += phi.cos();
            sum[1] += phi.sin();
        }
    }
    let l = (sum[0] * sum[0] + sum[1] * sum[1]).sqrt();
    [sum[0] / l, sum[1] / l, 0.0]
}

/// The 8 serendipity functions of a QUAD8 (code_aster's node order).
fn quad8(xi: [f64; 2]) -> [f64; 8] {
    let (x, y) = (xi[0], xi[1]);
    let c = |a: f64, b: f64| 0.25 * (1.0 + a * x) * (1.0 + b * y) * (a * x + b * y - 1.0);
    [
        c(-1.0, -1.0),
        c(1.0, -1.0),
        c(1.0, 1.0),
        c(-1.0, 1.0),
        0.5 * (1.0 - x * x) * (1.0 - y),
        0.5 * (1.0 + x) * (1.0 - y * y),
        0.5 * (1.0 - x * x) * (1.0 + y),
        0.5 * (1.0 - x) * (1.0 - y * y),
    ]
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

fn zone(mesh: &Mesh) -> ResolvedZone {
    let mut g = ZoneGeometry::new("MAIT", "S");
    g.lissage = true;
    ResolvedZone::new(0, &g, mesh).unwrap()
}

#[test]
fn nodal_normals_on_quad8_faces_are_code_asters_means() {
    let s = scene();
    let z = zone(&s.mesh);
    let mut turned = 0;
    for &n in &z.master_nodes {
        let (th, _) = s.at[n.0 as usize];
        let got = z.nodal_normal(n, true, &s.mesh.coords).unwrap();
        let want = expected_nodal(th);
        assert!(close(got, want, 1e-13), "node at {th}: {got:?} vs {want:?}");
        // The corners between faces of unequal spans and the two ends are
        // not radial: the test sees the cells' own derivatives.
        let radial = [th.cos(), th.sin(), 0.0];
        if !close(got, radial, 1e-6) {
            turned += 1;
        }
    }
    // θ = 0°, 10°, 30°, 45°: 3 nodes each (bottom, middle, top).
    assert_eq!(turned, 12);
}

#[test]
fn the_normal_at_a_point_interpolates_every_nodal_normal() {
    let s = scene();
    let z = zone(&s.mesh);
    // A slave node outside the middle face (10°–30°), off its centre.
    for (th_deg, h) in [(13.0_f64, 0.3), (24.0, 0.85), (29.5, 0.5)] {
        let mut x = s.mesh.coords.clone();
        let th = th_deg.to_radians();
        x[s.slave.0 as usize] = [(R + 0.01) * th.cos(), (R + 0.01) * th.sin(), h];
        let point = nodal_points(&z)
            .into_iter()
            .find(|p| p.node() == Some(s.slave))
            .unwrap();
        let pair = pair_point(&z, &point, &x).unwrap();
        let p = pair.pairing().unwrap();
        let (cell, xi) = p.master_cell.unwrap();
        assert_eq!(cell, CellId(1), "{th_deg}°");
        let nodes = &s.mesh.cells[1].nodes;
        let mut sum = [0.0; 3];
        for (n, w) in nodes.iter().zip(quad8(xi)) {
            let v = expected_nodal(s.at[n.0 as usize].0);
            for k in 0..3 {
                sum[k] += w * v[k];
            }
        }
        let l = (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt();
        let want = [sum[0] / l, sum[1] / l, sum[2] / l];
        assert!(
            close(p.normal, want, 1e-12),
            "{th_deg}°: {:?} vs {want:?}",
            p.normal
        );
        // The corner-only (bilinear) interpolation code_aster does not use
        // would differ visibly here.
        let mut lin = [0.0; 3];
        let q4 = |a: f64, b: f64| 0.25 * (1.0 + a * xi[0]) * (1.0 + b * xi[1]);
        for (i, (a, b)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .into_iter()
            .enumerate()
        {
            let v = expected_nodal(s.at[nodes[i].0 as usize].0);
            for k in 0..3 {
                lin[k] += q4(a, b) * v[k];
            }
        }
        let l = (lin[0] * lin[0] + lin[1] * lin[1]).sqrt();
        let lin = [lin[0] / l, lin[1] / l, 0.0];
        assert!(!close(want, lin, 1e-9), "{th_deg}°");
    }
}
