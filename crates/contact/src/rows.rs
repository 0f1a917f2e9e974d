//! Linearised non-penetration rows.
//!
//! For a paired point with normal n, slave weights Mⱼ and master weights Nᵢ,
//! the gap on the current geometry is linearised around the current
//! displacement u⁰ (n and the reference coordinates held fixed):
//!
//! g(u) ≈ g⁰ + n·(Σ Mⱼ (uⱼ − uⱼ⁰) − Σ Nᵢ (uᵢ − uᵢ⁰)) ≥ 0
//!
//! which is the row `a·u ≤ b` with a = −Mⱼ n on the slave DOFs, +Nᵢ n on the
//! master DOFs, and b = g⁰ + a·u⁰ (fem's rows are on the total displacement).

use std::collections::BTreeMap;

use aster_fem::{Comp, Dof, InequalityRow};
use aster_mesh::{Mesh, NodeId};

use crate::pairing::Pairing;

/// The row of one paired point; `scale` multiplies the whole row (used to
/// weight continuous integration points). `x` holds the current node
/// positions, so that u⁰ = x − X.
pub fn contact_row(
    mesh: &Mesh,
    x: &[[f64; 3]],
    slave: &[(NodeId, f64)],
    pairing: &Pairing,
    space_dim: usize,
    scale: f64,
    id: usize,
) -> InequalityRow {
    let comps = Comp::translations(space_dim);
    // Round-off leaves components of ~1e-18 in normals that are exactly
    // axis-aligned; they add or drop terms from one pass to the next, so the
    // geometric loop would see "new rows" forever. A unit normal's component
    // below 1e-12 (an angle of 1e-12 rad) is zero.
    let normal = pairing
        .normal
        .map(|v| if v.abs() < 1e-12 { 0.0 } else { v });
    let mut terms: BTreeMap<Dof, f64> = BTreeMap::new();
    let mut add = |node: NodeId, w: f64| {
        for (c, comp) in comps.iter().enumerate() {
            let coef = w * normal[c] * scale;
            if coef != 0.0 {
                *terms.entry(Dof::new(node, *comp)).or_default() += coef;
            }
        }
    };
    for &(n, w) in slave {
        add(n, -w);
    }
    for &(n, w) in &pairing.master {
        add(n, w);
    }
    let mut au0 = 0.0;
    for (d, coef) in &terms {
        let i = d.node.0 as usize;
        let c = match d.comp {
            Comp::DX => 0,
            Comp::DY => 1,
            _ => 2,
        };
        au0 += coef * (x[i][c] - mesh.coords[i][c]);
    }
    InequalityRow::new(
        terms.into_iter().filter(|(_, c)| *c != 0.0).collect(),
        pairing.gap * scale + au0,
        id,
    )
}
