//! The Hertz cylinder-on-plane scene (plane strain): a mesh generator and
//! the analytic solution.
//!
//! The mesh is the right half (x ≥ 0) of a cylinder of radius R centred at
//! (0, R), resting on the plane y = 0 at the origin. The cylinder is a
//! polar grid between a rigid hub of radius r₀ (where the load is imposed)
//! and the outer radius R; it is refined towards the contact point: uniform
//! fine angular steps over `contact_angle`, then geometric growth up to
//! π/2, and a geometric radial grading from R inwards whose first layer
//! matches the fine angular step (square cells at the contact). The plane
//! is one layer of QUAD4 cells under y = 0, meant to be held fixed (a rigid
//! foundation).
//!
//! Groups (cells): `CYL`, `PLAN`, `ESCL` (outer arc SEG2, slave), `MAIT`
//! (top of the plane SEG2, master). Groups (nodes): `SYME` (cylinder nodes
//! on x = 0), `HUB` (inner arc nodes), `PLAN` (plane nodes), `PC` (the
//! initial contact point (0, 0) of the cylinder), and node groups of every
//! cell group.

use aster_mesh::{Cell, CellId, CellType, Group, Mesh, NodeId};

use crate::error::ContactError;

/// Parameters of the generated mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct HertzMesh {
    pub radius: f64,
    /// Radius of the rigid hub (load application), a fraction of R is typical (0.2 R).
    pub hub_radius: f64,
    /// Angle (radians) of the uniformly refined sector from the contact point.
    pub contact_angle: f64,
    /// Angular cells in the refined sector.
    pub n_contact: usize,
    /// Angular cells from the refined sector to π/2.
    pub n_outer: usize,
    /// Radial cells from R to the hub.
    pub n_radial: usize,
    /// Number of plane cells along x, uniform over [-0.05 R, 1.05 R].
    pub n_plane: usize,
    /// Thickness of the plane layer.
    pub plane_thickness: f64,
}

impl HertzMesh {
    /// A mesh with `n` cells across the refined sector of angle
    /// `contact_angle` (choose about 2–3 × a/R).
    pub fn new(radius: f64, contact_angle: f64, n: usize) -> HertzMesh {
        HertzMesh {
            radius,
            hub_radius: 0.2 * radius,
            contact_angle,
            n_contact: n,
            n_outer: n.max(8),
            n_radial: (2 * n).max(10),
            n_plane: (4 * n).max(20),
            plane_thickness: 0.05 * radius,
        }
    }
}

/// The analytic Hertz solution for a cylinder on a plane in plane strain:
/// contact half-width a = √(4 P R / (π E*)) and peak pressure p₀ = 2P/(π a),
/// with P the load per unit length and E* the plane-strain modulus
/// (1/E* = (1−ν₁²)/E₁ + (1−ν₂²)/E₂).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HertzSolution {
    pub half_width: f64,
    pub peak_pressure: f64,
}

impl HertzSolution {
    pub fn new(load_per_length: f64, radius: f64, e_star: f64) -> HertzSolution {
        let a = (4.0 * load_per_length * radius / (std::f64::consts::PI * e_star)).sqrt();
        HertzSolution {
            half_width: a,
            peak_pressure: 2.0 * load_per_length / (std::f64::consts::PI * a),
        }
    }

    /// p(x) = p₀ √(1 − x²/a²) inside the contact, 0 outside.
    pub fn pressure(&self, x: f64) -> f64 {
        let r = x / self.half_width;
        if r.abs() < 1.0 {
            self.peak_pressure * (1.0 - r * r).sqrt()
        } else {
            0.0
        }
    }
}

/// Plane-strain modulus of two elastic bodies (E = ∞ for a rigid one).
pub fn plane_strain_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    let c = |e: f64, nu: f64| {
        if e.is_infinite() {
            0.0
        } else {
            (1.0 - nu * nu) / e
        }
    };
    1.0 / (c(e1, nu1) + c(e2, nu2))
}

/// Steps of a geometric progression of `n` terms starting at `h0` summing to `total`.
fn geometric(h0: f64, total: f64, n: usize) -> Vec<f64> {
    if n == 0 {
        return Vec::new();
    }
    let sum = |q: f64| {
        if (q - 1.0).abs() < 1e-12 {
            h0 * n as f64
        } else {
            h0 * (q.powi(n as i32) - 1.0) / (q - 1.0)
        }
    };
    // Bisection on the ratio q ∈ [1e-3, 10] (sum is increasing in q).
    let (mut lo, mut hi) = (1e-3, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if sum(mid) < total {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let q = 0.5 * (lo + hi);
    let mut steps: Vec<f64> = (0..n).map(|i| h0 * q.powi(i as i32)).collect();
    // Remove the bisection's residual so the steps sum exactly.
    let s: f64 = steps.iter().sum();
    for h in &mut steps {
        *h *= total / s;
    }
    steps
}

/// Generates the Hertz mesh.
pub fn hertz_mesh(p: &HertzMesh) -> Result<Mesh, ContactError> {
    let half_pi = std::f64::consts::FRAC_PI_2;
    let bad = |message: String| ContactError::Invalid {
        keyword: "HertzMesh",
        message,
    };
    if !(p.radius > 0.0 && p.hub_radius > 0.0 && p.hub_radius < p.radius) {
        return Err(bad(format!(
            "need 0 < hub radius ({}) < radius ({})",
            p.hub_radius, p.radius
        )));
    }
    if !(p.contact_angle > 0.0 && p.contact_angle < half_pi) {
        return Err(bad(format!(
            "contact angle {} must lie in (0, π/2)",
            p.contact_angle
        )));
    }
    if p.n_contact == 0
        || p.n_outer == 0
        || p.n_radial == 0
        || p.n_plane == 0
        || p.plane_thickness.is_nan()
        || p.plane_thickness <= 0.0
    {
        return Err(bad(
            "every cell count and the plane thickness must be positive".into(),
        ));
    }
    let h = p.contact_angle / p.n_contact as f64;
    let mut thetas = vec![0.0];
    for i in 1..=p.n_contact {
        thetas.push(h * i as f64);
    }
    for s in geometric(h, half_pi - p.contact_angle, p.n_outer) {
        let last = *thetas.last().unwrap_or(&0.0);
        thetas.push(last + s);
    }
    // Radii from R inwards, first step ≈ R h.
    let mut radii = vec![p.radius];
    for s in geometric(
        (p.radius * h).min((p.radius - p.hub_radius) / p.n_radial as f64),
        p.radius - p.hub_radius,
        p.n_radial,
    ) {
        let last = *radii.last().unwrap_or(&p.radius);
        radii.push(last - s);
    }

    let mut mesh = Mesh {
        dim: 2,
        ..Mesh::default()
    };
    let centre = [0.0, p.radius];
    let nt = thetas.len();
    let node_at = |ir: usize, it: usize| NodeId((ir * nt + it) as u32);
    for &r in &radii {
        for &t in &thetas {
            mesh.coords
                .push([centre[0] + r * t.sin(), centre[1] - r * t.cos(), 0.0]);
        }
    }
    let mut cyl = Vec::new();
    for ir in 0..radii.len() - 1 {
        for it in 0..nt - 1 {
            // Counter-clockwise: outer radius is lower (y smaller) near θ = 0.
            let quad = vec![
                node_at(ir, it),
                node_at(ir, it + 1),
                node_at(ir + 1, it + 1),
                node_at(ir + 1, it),
            ];
            cyl.push(push_cell(&mut mesh, CellType::QUAD4, quad));
        }
    }
    let mut escl = Vec::new();
    for it in 0..nt - 1 {
        escl.push(push_cell(
            &mut mesh,
            CellType::SEG2,
            vec![node_at(0, it), node_at(0, it + 1)],
        ));
    }
    let syme: Vec<NodeId> = (0..radii.len()).map(|ir| node_at(ir, 0)).collect();
    let hub: Vec<NodeId> = (0..nt).map(|it| node_at(radii.len() - 1, it)).collect();

    // The plane: two rows of nodes, y = 0 and y = −thickness.
    let first_plane = mesh.coords.len();
    let (x0, x1) = (-0.05 * p.radius, 1.05 * p.radius);
    let np = p.n_plane + 1;
    for row in 0..2 {
        for i in 0..np {
            let x = x0 + (x1 - x0) * i as f64 / p.n_plane as f64;
            mesh.coords
                .push([x, -(row as f64) * p.plane_thickness, 0.0]);
        }
    }
    let pn = |row: usize, i: usize| NodeId((first_plane + row * np + i) as u32);
    let mut plan = Vec::new();
    for i in 0..p.n_plane {
        plan.push(push_cell(
            &mut mesh,
            CellType::QUAD4,
            vec![pn(1, i), pn(1, i + 1), pn(0, i + 1), pn(0, i)],
        ));
    }
    let mut mait = Vec::new();
    for i in 0..p.n_plane {
        // Along the plane's counter-clockwise boundary: right to left on top.
        mait.push(push_cell(
            &mut mesh,
            CellType::SEG2,
            vec![pn(0, i + 1), pn(0, i)],
        ));
    }
    let plan_nodes: Vec<NodeId> = (first_plane..mesh.coords.len())
        .map(|i| NodeId(i as u32))
        .collect();

    mesh.node_names = (1..=mesh.coords.len()).map(|i| format!("N{i}")).collect();
    mesh.cell_names = (1..=mesh.cells.len()).map(|i| format!("M{i}")).collect();
    for (name, cells) in [("CYL", cyl), ("PLAN", plan), ("ESCL", escl), ("MAIT", mait)] {
        let nodes = cell_nodes(&mesh, &cells);
        mesh.groups_ma.push(Group {
            name: name.into(),
            members: cells,
        });
        if name != "PLAN" {
            mesh.groups_no.push(Group {
                name: name.into(),
                members: nodes,
            });
        }
    }
    mesh.groups_no.push(Group {
        name: "PLAN".into(),
        members: plan_nodes,
    });
    mesh.groups_no.push(Group {
        name: "SYME".into(),
        members: syme,
    });
    mesh.groups_no.push(Group {
        name: "HUB".into(),
        members: hub,
    });
    mesh.groups_no.push(Group {
        name: "PC".into(),
        members: vec![node_at(0, 0)],
    });
    Ok(mesh)
}

fn push_cell(mesh: &mut Mesh, ty: CellType, nodes: Vec<NodeId>) -> CellId {
    mesh.cells.push(Cell { ty, nodes });
    CellId((mesh.cells.len() - 1) as u32)
}

fn cell_nodes(mesh: &Mesh, cells: &[CellId]) -> Vec<NodeId> {
    let mut v: Vec<NodeId> = cells
        .iter()
        .flat_map(|c| mesh.cell(*c).nodes.iter().copied())
        .collect();
    v.sort();
    v.dedup();
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(mesh: &Mesh, c: &Cell) -> f64 {
        let p: Vec<[f64; 3]> = c.nodes.iter().map(|n| mesh.coord(*n)).collect();
        let mut a = 0.0;
        for i in 0..p.len() {
            let j = (i + 1) % p.len();
            a += p[i][0] * p[j][1] - p[j][0] * p[i][1];
        }
        a / 2.0
    }

    #[test]
    fn mesh_is_valid_and_covers_the_quarter_annulus() {
        let p = HertzMesh::new(50.0, 0.1, 10);
        let mesh = hertz_mesh(&p).unwrap();
        let cyl = mesh.group_ma("CYL").unwrap();
        let mut total = 0.0;
        for c in &cyl.members {
            let a = area(&mesh, mesh.cell(*c));
            assert!(a > 0.0, "cell {c:?} is clockwise or degenerate");
            total += a;
        }
        // Polygonal approximation of the quarter annulus (coarse far from
        // the contact): slightly less than exact.
        let exact = std::f64::consts::FRAC_PI_4 * (50.0f64.powi(2) - 10.0f64.powi(2));
        assert!(total < exact && total > 0.97 * exact, "{total} vs {exact}");
        for c in &mesh.group_ma("PLAN").unwrap().members {
            assert!(area(&mesh, mesh.cell(*c)) > 0.0);
        }
        // Contact point at the origin; cells at the contact are nearly square.
        let pc = mesh.group_no("PC").unwrap().members[0];
        assert_eq!(mesh.coord(pc), [0.0, 0.0, 0.0]);
        let first = mesh.cell(cyl.members[0]);
        let d = |a: usize, b: usize| {
            let (p, q) = (mesh.coord(first.nodes[a]), mesh.coord(first.nodes[b]));
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
        };
        let ratio = d(0, 1) / d(1, 2);
        assert!((0.7..1.4).contains(&ratio), "aspect ratio {ratio}");
    }

    #[test]
    fn analytic_solution_balances_the_load() {
        let s = HertzSolution::new(
            1000.0,
            50.0,
            plane_strain_modulus(2e5, 0.3, f64::INFINITY, 0.0),
        );
        // ∫ p dx over [−a, a] = π a p₀ / 2 = P.
        let n = 20000;
        let h = 2.0 * s.half_width / n as f64;
        let integral: f64 = (0..n)
            .map(|i| s.pressure(-s.half_width + (i as f64 + 0.5) * h) * h)
            .sum();
        assert!((integral - 1000.0).abs() < 1e-3 * 1000.0);
    }

    #[test]
    fn bad_parameters_are_errors() {
        let mut p = HertzMesh::new(50.0, 0.1, 10);
        p.hub_radius = 60.0;
        assert!(hertz_mesh(&p)
            .unwrap_err()
            .to_string()
            .contains("hub radius"));
    }
}
