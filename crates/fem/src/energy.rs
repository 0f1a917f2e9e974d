//! Energies of a displacement field, per cell (code_aster's `EPOT_ELEM`,
//! the potential energy `POST_ELEM/ENER_POT` sums, and `ENEL_ELEM` for
//! elastic cells, which `ENER_ELAS` sums).
//!
//! For an elastic continuum cell the strain energy is
//! ½ ∫ ε(u):D:ε(u) dΩ = ½ uₑᵀ Kₑ uₑ, integrated with the stiffness Gauss
//! family (AXIS: per radian, as the stiffness); for a discrete spring it is
//! ½ uₑᵀ Kₑ uₑ with the spring's matrix. Boundary cells carry none. The
//! kinetic energy lives with the mass matrices (dynamics).

use crate::element::{element_dofs_into, element_stiffness};
use crate::error::FemError;
use crate::model::Model;
use aster_mesh::CellId;

/// ½ uₑᵀ Kₑ uₑ for each element that has a stiffness, in element order.
pub fn potential_energy_by_cell(model: &Model, u: &[f64]) -> Result<Vec<(CellId, f64)>, FemError> {
    crate::post::refuse_stabilised(model, "elastic energies (½ uᵀ K u)")?;
    let mut out = Vec::with_capacity(model.elements().len());
    let mut dofs = Vec::new();
    for (i, el) in model.elements().iter().enumerate() {
        let Some(k) = element_stiffness(model, i)? else {
            continue;
        };
        dofs.clear();
        element_dofs_into(model, el.cell, &mut dofs);
        if dofs.len() != k.nrows() {
            return Err(FemError::Model(format!(
                "cell {}: {} DOFs for a {}×{} stiffness",
                model.cell_name(el.cell),
                dofs.len(),
                k.nrows(),
                k.ncols()
            )));
        }
        let mut e = 0.0;
        for (a, &da) in dofs.iter().enumerate() {
            let ua = u.get(da).copied().unwrap_or(0.0);
            if ua == 0.0 {
                continue;
            }
            let mut row = 0.0;
            for (b, &db) in dofs.iter().enumerate() {
                row += k[(a, b)] * u.get(db).copied().unwrap_or(0.0);
            }
            e += ua * row;
        }
        out.push((el.cell, 0.5 * e));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// u = (a·x, 0) on the unit square in plane strain: ε_xx = a, so the
    /// energy density is ½ (λ + 2μ) a², over an area of 1, shared by the cells
    /// in proportion to their areas.
    #[test]
    fn uniform_strain_energy_is_half_lambda_two_mu_a_squared() {
        let (model, _) = crate::scenes::quad4_grid(3).unwrap();
        let a = 1e-3;
        let mut u = vec![0.0; model.dofs().len()];
        for k in 0..u.len() {
            let d = model.dofs().dof(k);
            if d.comp == crate::Comp::DX {
                u[k] = a * model.mesh().coord(d.node)[0];
            }
        }
        let (e, nu) = (2e11, 0.3);
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        let exact = 0.5 * (lambda + 2.0 * mu) * a * a;
        let by_cell = potential_energy_by_cell(&model, &u).unwrap();
        assert_eq!(by_cell.len(), 9);
        let total: f64 = by_cell.iter().map(|(_, e)| e).sum();
        assert!((total - exact).abs() < 1e-12 * exact, "{total} vs {exact}");
        for (_, ec) in &by_cell {
            assert!((ec - exact / 9.0).abs() < 1e-12 * exact);
        }
    }
}
