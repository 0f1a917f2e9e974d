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

/// code_aster's `ENEL_ELGA` in small strains (`enelpg`, `PETIT`): the
/// elastic energy density ½ σ : D⁻¹ : σ at each point of a stress field
/// (SIEF_ELGA), component `TOTALE`, with the isotropic compliance of the
/// cell's material (εᵢᵢ = ((1+ν)σᵢᵢ − ν tr σ)/E, γᵢⱼ = σᵢⱼ/G). Cells that
/// are not continuum elements are skipped; an orthotropic material is
/// refused.
pub fn elastic_energy_density(
    model: &Model,
    stress: &[crate::post::CellValues],
) -> Result<Vec<crate::post::CellValues>, FemError> {
    let mut out = Vec::with_capacity(stress.len());
    for cv in stress {
        let Some(crate::model::ElementKind::Continuum { material, .. }) =
            model.element_kind(cv.cell)
        else {
            continue;
        };
        if !material.is_isotropic() {
            return Err(FemError::Model(format!(
                "cell {}: the elastic energy of an orthotropic material (ELAS_ORTH) is not computed",
                model.cell_name(cv.cell)
            )));
        }
        let (e, nu) = (material.e, material.nu);
        let g = e / (2.0 * (1.0 + nu));
        let points = (0..cv.points.len())
            .map(|p| {
                let s = |n: &str| cv.get(p, n).unwrap_or(0.0);
                let d = [s("SIXX"), s("SIYY"), s("SIZZ")];
                let tr = d[0] + d[1] + d[2];
                let normal: f64 = d.iter().map(|&x| x * ((1.0 + nu) * x - nu * tr) / e).sum();
                let shear: f64 = ["SIXY", "SIXZ", "SIYZ"]
                    .iter()
                    .map(|n| s(n) * s(n) / g)
                    .sum();
                vec![0.5 * (normal + shear)]
            })
            .collect();
        out.push(crate::post::CellValues {
            cell: cv.cell,
            names: vec!["TOTALE"],
            points,
        });
    }
    Ok(out)
}

/// The elastic energy of the plate facets of `model` (DKT, DST, Q4G and
/// their G variants) for the displacement `u`: the density at the points
/// of each facet's RIGI family and its integral over the facet, with the
/// components [`crate::plate::ENERGY_NAMES`] (`ENEL_ELGA`, `ENEL_ELEM`:
/// [`crate::plate::elastic_energy`], by code_aster's path for a linear or
/// a non-linear result).
pub fn plate_elastic_energy(
    model: &Model,
    u: &[f64],
    linear: bool,
) -> Result<(Vec<crate::post::CellValues>, Vec<crate::post::CellValues>), FemError> {
    let mut density = Vec::new();
    let mut totals = Vec::new();
    for el in model.elements() {
        let crate::model::ElementKind::Shell {
            material,
            section,
            theory,
        } = &el.kind
        else {
            continue;
        };
        let xyz = crate::element::cell_coords(model.mesh(), el.cell);
        let ue: Vec<f64> = crate::element::element_dofs(model, el.cell)
            .iter()
            .map(|&i| u[i])
            .collect();
        let (values, weights) =
            crate::plate::elastic_energy(*theory, &xyz, material, section, &ue, linear)
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))?;
        let mut sum = vec![0.0; 5];
        for (v, w) in values.iter().zip(&weights) {
            for (acc, x) in sum.iter_mut().zip(v) {
                *acc += w * x;
            }
        }
        let names = crate::plate::ENERGY_NAMES.to_vec();
        density.push(crate::post::CellValues {
            cell: el.cell,
            names: names.clone(),
            points: values.iter().map(|v| v.to_vec()).collect(),
        });
        totals.push(crate::post::CellValues {
            cell: el.cell,
            names,
            points: vec![sum],
        });
    }
    Ok((density, totals))
}

/// The integral over each cell of a field at the points of its stiffness
/// family (code_aster's `_ELEM` options from their `_ELGA` densities, e.g.
/// `ENEL_ELEM`): Σ value × weight (AXIS: per radian, weight × r), one
/// point per cell with the field's components.
pub fn cell_integrals(
    model: &Model,
    density: &[crate::post::CellValues],
) -> Result<Vec<crate::post::CellValues>, FemError> {
    let axis = model.hypothesis() == Some(crate::material::Hypothesis::Axisymmetric);
    let mesh = model.mesh();
    let mut out = Vec::with_capacity(density.len());
    for cv in density {
        let scheme = model.stiffness_scheme(cv.cell);
        let points = crate::elga::points(mesh, cv.cell, &scheme, axis);
        if points.len() != cv.points.len() {
            return Err(FemError::Model(format!(
                "cell {}: {} values for {} integration points",
                model.cell_name(cv.cell),
                cv.points.len(),
                points.len()
            )));
        }
        let mut sum = vec![0.0; cv.names.len()];
        for (p, v) in points.iter().zip(&cv.points) {
            for (acc, x) in sum.iter_mut().zip(v) {
                *acc += p.weight * x;
            }
        }
        out.push(crate::post::CellValues {
            cell: cv.cell,
            names: cv.names.clone(),
            points: vec![sum],
        });
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

    /// A general displacement (not uniform): the density ½ σ:D⁻¹:σ of the
    /// element stresses, integrated over each cell, is ½ uₑᵀ Kₑ uₑ (same
    /// Gauss family) — ENEL_ELEM of an elastic result.
    #[test]
    fn integrated_energy_density_is_half_u_k_u() {
        let (model, _) = crate::scenes::quad4_grid(3).unwrap();
        let mut u = vec![0.0; model.dofs().len()];
        for (k, v) in u.iter_mut().enumerate() {
            let d = model.dofs().dof(k);
            let x = model.mesh().coord(d.node);
            *v = 1e-3
                * (x[0] * x[1] + 0.3 * x[1] * x[1] - 0.2 * x[0])
                * if d.comp == crate::Comp::DX { 1.0 } else { -0.7 };
        }
        let stress = crate::post::sief_elga(&model, &u).unwrap();
        let density = elastic_energy_density(&model, &stress).unwrap();
        assert_eq!(density[0].names, vec!["TOTALE"]);
        let elem = cell_integrals(&model, &density).unwrap();
        let reference = potential_energy_by_cell(&model, &u).unwrap();
        assert_eq!(elem.len(), reference.len());
        for (got, (cell, want)) in elem.iter().zip(&reference) {
            assert_eq!(got.cell, *cell);
            assert!(
                (got.points[0][0] - want).abs() < 1e-10 * want.abs().max(1e-30),
                "{} vs {want}",
                got.points[0][0]
            );
        }
    }
}
