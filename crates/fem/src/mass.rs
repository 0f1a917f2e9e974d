//! Mass and damping matrices, and the kinetic energy (code_aster's
//! `MASS_MECA`, `MASS_MECA_DIAG`, `AMOR_MECA`, `ECIN_ELEM`).
//!
//! - Continuum cells: M = Σ ρ N·Nᵀ w |det J| (× r in AXIS, per radian as
//!   the stiffness) on each displacement component, integrated with
//!   code_aster's `MASS` Gauss family ([`shape::mass_scheme`]).
//! - Lumped (`MASS_MECA_DIAG`, `te0012`/`te0082`): each diagonal term of
//!   the consistent matrix scaled by the cell's mass over the trace of
//!   one component's block (the diagonal keeps the cell's total mass and
//!   the consistent matrix's proportions; HRZ lumping).
//! - Discrete cells: `M_T_D_N` (a mass on each translation of a POI1
//!   node) and `M_T_N`/`M_T_L` (a full symmetric matrix over the cell's
//!   translations, given as code_aster's upper triangle by columns).
//! - Rayleigh damping (`ELAS/AMOR_ALPHA`, `AMOR_BETA`): C = Σ αₑ Kₑ + βₑ Mₑ
//!   per cell, with the elastic stiffness (`AMOR_RAYL_RIGI='ELASTIQUE'`).
//!
//! The matrices share the stiffness pattern ([`assembly::stiffness_pattern`])
//! so that K + c·M is a sum of value arrays.

use crate::assembly::stiffness_pattern;
use crate::element::{element_dofs_into, element_stiffness, physical_derivatives, spring_rotation};
use crate::error::FemError;
use crate::linalg::Csc;
use crate::material::Hypothesis;
use crate::model::{ElementKind, Frame, Model};
use crate::shape;
use aster_mesh::CellId;
use nalgebra::DMatrix;
use std::collections::HashMap;

/// A mass given on a discrete cell (`AFFE_CARA_ELEM/DISCRET(_2D)`).
#[derive(Clone, Debug, PartialEq)]
pub enum DiscreteMass {
    /// `M_T_D_N`: the same mass on every translation of the POI1 node.
    Node { cell: CellId, mass: f64 },
    /// `M_T_N` (POI1) / `M_T_L` (SEG2): the symmetric matrix over the cell's
    /// translations, upper triangle by columns ((1,1), (1,2), (2,2), (1,3)…),
    /// in the global frame or the cell's local one.
    Matrix {
        cell: CellId,
        upper: Vec<f64>,
        frame: Frame,
    },
}

/// Everything the mass of a model needs besides the model: the density of
/// each continuum cell (`ELAS/RHO`; absent: no mass) and the discrete masses.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MassData {
    pub density: HashMap<CellId, f64>,
    pub discrete: Vec<DiscreteMass>,
}

/// Rayleigh coefficients of a cell: C = alpha·K + beta·M (`AMOR_ALPHA`,
/// `AMOR_BETA`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rayleigh {
    pub alpha: f64,
    pub beta: f64,
}

/// Consistent or lumped (`MASS_DIAG='OUI'`) mass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Lumping {
    #[default]
    Consistent,
    Diagonal,
}

/// The consistent mass of one continuum cell over its DOFs (node-major),
/// with the `MASS` Gauss family.
pub fn continuum_mass(
    model: &Model,
    cell: CellId,
    hyp: Hypothesis,
    rho: f64,
) -> Result<DMatrix<f64>, FemError> {
    let mesh = model.mesh();
    let c = mesh.cell(cell);
    let nn = c.nodes.len();
    let dim = hyp.dim();
    // One component's block a(i, j) = Σ ρ w Nᵢ Nⱼ.
    let mut a = DMatrix::<f64>::zeros(nn, nn);
    for gp in &shape::mass_scheme(c.ty) {
        let (n, _, det, x) = physical_derivatives(mesh, cell, dim, gp)
            .map_err(|m| FemError::Model(format!("cell {} is {m}", model.cell_name(cell))))?;
        let mut w = rho * gp.weight * det.abs();
        if hyp == Hypothesis::Axisymmetric {
            w *= x[0];
        }
        for i in 0..nn {
            for j in 0..nn {
                a[(i, j)] += w * n[i] * n[j];
            }
        }
    }
    let mut m = DMatrix::zeros(nn * dim, nn * dim);
    for i in 0..nn {
        for j in 0..nn {
            for k in 0..dim {
                m[(i * dim + k, j * dim + k)] = a[(i, j)];
            }
        }
    }
    Ok(m)
}

/// code_aster's diagonal mass of a cell: the consistent diagonal scaled by
/// (cell mass) / (trace of one component's block).
pub fn lump(m: &DMatrix<f64>, dim: usize) -> DMatrix<f64> {
    let nn = m.nrows() / dim.max(1);
    let mut total = 0.0;
    let mut trace = 0.0;
    for i in 0..nn {
        for j in 0..nn {
            total += m[(i * dim, j * dim)];
        }
        trace += m[(i * dim, i * dim)];
    }
    let alpha = if trace != 0.0 { total / trace } else { 0.0 };
    DMatrix::from_diagonal(&(m.diagonal() * alpha))
}

/// The mass matrix of one discrete cell over its translations (global
/// frame), or an error naming the cell when the values do not fit it.
fn discrete_mass(model: &Model, d: &DiscreteMass) -> Result<(CellId, DMatrix<f64>), FemError> {
    let dim = model.dim();
    match d {
        DiscreteMass::Node { cell, mass } => {
            let nn = model.mesh().cell(*cell).nodes.len();
            if nn != 1 {
                return Err(FemError::Model(format!(
                    "a node mass (M_T_D_N) on cell {}, which has {nn} nodes: it needs a POI1",
                    model.cell_name(*cell)
                )));
            }
            Ok((*cell, DMatrix::identity(dim, dim) * *mass))
        }
        DiscreteMass::Matrix { cell, upper, frame } => {
            let nn = model.mesh().cell(*cell).nodes.len();
            let n = nn * dim;
            if upper.len() != n * (n + 1) / 2 {
                return Err(FemError::Model(format!(
                    "the mass matrix of cell {} has {} values; its {n} translations need {}",
                    model.cell_name(*cell),
                    upper.len(),
                    n * (n + 1) / 2
                )));
            }
            let mut m = DMatrix::zeros(n, n);
            let mut k = 0;
            for j in 0..n {
                for i in 0..=j {
                    m[(i, j)] = upper[k];
                    m[(j, i)] = upper[k];
                    k += 1;
                }
            }
            let r = spring_rotation(model.mesh(), *cell, dim, *frame);
            let mut t = DMatrix::zeros(n, n);
            for b in 0..nn {
                t.view_mut((b * dim, b * dim), (dim, dim)).copy_from(&r);
            }
            Ok((*cell, t.transpose() * m * t))
        }
    }
}

fn scatter(model: &Model, out: &mut Csc, cell: CellId, m: &DMatrix<f64>, dofs: &mut Vec<usize>) {
    dofs.clear();
    element_dofs_into(model, cell, dofs);
    for (a, &i) in dofs.iter().enumerate() {
        for (b, &j) in dofs.iter().enumerate() {
            let v = m[(a, b)];
            if v != 0.0 {
                // Same cell, same pattern: the entry exists.
                out.add(i, j, v);
            }
        }
    }
}

/// The mass matrix over all DOFs of the model, in the stiffness pattern.
/// Continuum cells without a density and boundary cells carry no mass.
pub fn assemble_mass(model: &Model, data: &MassData, lumping: Lumping) -> Result<Csc, FemError> {
    let mut out = stiffness_pattern(model);
    let mut dofs = Vec::new();
    for el in model.elements() {
        let ElementKind::Continuum { hypothesis, .. } = &el.kind else {
            continue;
        };
        let Some(&rho) = data.density.get(&el.cell) else {
            continue;
        };
        if rho == 0.0 {
            continue;
        }
        let mut m = continuum_mass(model, el.cell, *hypothesis, rho)?;
        if lumping == Lumping::Diagonal {
            m = lump(&m, hypothesis.dim());
        }
        scatter(model, &mut out, el.cell, &m, &mut dofs);
    }
    for d in &data.discrete {
        let (cell, mut m) = discrete_mass(model, d)?;
        if !model.elements().iter().any(|e| e.cell == cell) {
            return Err(FemError::Model(format!(
                "a discrete mass on cell {}, which carries no element of the model",
                model.cell_name(cell)
            )));
        }
        if lumping == Lumping::Diagonal {
            m = DMatrix::from_diagonal(&m.diagonal());
        }
        scatter(model, &mut out, cell, &m, &mut dofs);
    }
    Ok(out)
}

/// Rayleigh damping C = Σ αₑ Kₑ + βₑ Mₑ (consistent Mₑ), in the stiffness
/// pattern. `None` when every coefficient is zero.
pub fn assemble_rayleigh(
    model: &Model,
    data: &MassData,
    coefficients: &HashMap<CellId, Rayleigh>,
) -> Result<Option<Csc>, FemError> {
    if coefficients
        .values()
        .all(|r| r.alpha == 0.0 && r.beta == 0.0)
    {
        return Ok(None);
    }
    let mut out = stiffness_pattern(model);
    let mut dofs = Vec::new();
    for (index, el) in model.elements().iter().enumerate() {
        let Some(r) = coefficients.get(&el.cell) else {
            continue;
        };
        let ElementKind::Continuum { hypothesis, .. } = &el.kind else {
            continue;
        };
        let mut c = DMatrix::zeros(0, 0);
        if r.alpha != 0.0 {
            if let Some(k) = element_stiffness(model, index)? {
                c = k * r.alpha;
            }
        }
        if r.beta != 0.0 {
            let rho = data.density.get(&el.cell).copied().unwrap_or(0.0);
            if rho != 0.0 {
                let m = continuum_mass(model, el.cell, *hypothesis, rho)? * r.beta;
                c = if c.is_empty() { m } else { c + m };
            }
        }
        if !c.is_empty() {
            scatter(model, &mut out, el.cell, &c, &mut dofs);
        }
    }
    Ok(Some(out))
}

/// ½ vᵀ M v.
pub fn kinetic_energy(mass: &Csc, velocity: &[f64]) -> f64 {
    0.5 * mass
        .mul(velocity)
        .iter()
        .zip(velocity)
        .map(|(a, b)| a * b)
        .sum::<f64>()
}

/// The kinetic energy ½ vₑᵀ Mₑ vₑ of every continuum cell with a density
/// (code_aster's `ECIN_ELEM`, consistent mass), in element order: what
/// `POST_ELEM/ENER_CIN` sums over the cells it is asked for.
pub fn kinetic_energy_by_cell(
    model: &Model,
    data: &MassData,
    velocity: &[f64],
) -> Result<Vec<(CellId, f64)>, FemError> {
    let mut out = Vec::new();
    let mut dofs = Vec::new();
    for el in model.elements() {
        let ElementKind::Continuum { hypothesis, .. } = &el.kind else {
            continue;
        };
        let Some(&rho) = data.density.get(&el.cell) else {
            continue;
        };
        let m = continuum_mass(model, el.cell, *hypothesis, rho)?;
        dofs.clear();
        element_dofs_into(model, el.cell, &mut dofs);
        let v: Vec<f64> = dofs.iter().map(|&i| velocity[i]).collect();
        let mut e = 0.0;
        for a in 0..v.len() {
            for b in 0..v.len() {
                e += v[a] * m[(a, b)] * v[b];
            }
        }
        out.push((el.cell, 0.5 * e));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Elastic;
    use crate::model::Element;
    use aster_mesh::{CellType, Mesh};

    fn one_cell(ty: CellType, coords: Vec<[f64; 3]>, hyp: Hypothesis) -> Model {
        let n = coords.len();
        let mut mesh = Mesh {
            dim: if hyp == Hypothesis::Solid3D { 3 } else { 2 },
            node_names: (0..n).map(|i| format!("N{i}")).collect(),
            coords,
            ..Mesh::default()
        };
        let nodes: Vec<_> = (0..n).map(|i| aster_mesh::NodeId(i as u32)).collect();
        mesh.cells.push(aster_mesh::Cell { ty, nodes });
        mesh.cell_names.push("M1".into());
        Model::new(
            mesh,
            vec![Element {
                cell: CellId(0),
                kind: ElementKind::Continuum {
                    hypothesis: hyp,
                    material: Elastic::new(1.0, 0.3).unwrap(),
                },
            }],
        )
        .unwrap()
    }

    fn total(m: &DMatrix<f64>, dim: usize) -> f64 {
        // Σ over one component's block = the cell's mass.
        let nn = m.nrows() / dim;
        (0..nn)
            .flat_map(|i| (0..nn).map(move |j| (i, j)))
            .map(|(i, j)| m[(i * dim, j * dim)])
            .sum()
    }

    #[test]
    fn masses_are_density_times_measure() {
        let hexa = one_cell(
            CellType::HEXA8,
            vec![
                [0., 0., 0.],
                [2., 0., 0.],
                [2., 1., 0.],
                [0., 1., 0.],
                [0., 0., 3.],
                [2., 0., 3.],
                [2., 1., 3.],
                [0., 1., 3.],
            ],
            Hypothesis::Solid3D,
        );
        let m = continuum_mass(&hexa, CellId(0), Hypothesis::Solid3D, 7.0).unwrap();
        assert!((total(&m, 3) - 42.0).abs() < 1e-12);
        // Lumped: the same mass, a diagonal, equal corners on a brick.
        let l = lump(&m, 3);
        assert!((l.trace() / 3.0 - 42.0).abs() < 1e-12);
        assert!((l[(0, 0)] - 42.0 / 8.0).abs() < 1e-12);
        // TRIA3 in AXIS: ρ ∫ r dr dz = ρ · area · r̄ (per radian).
        let tri = one_cell(
            CellType::TRIA3,
            vec![[1., 0., 0.], [3., 0., 0.], [1., 2., 0.]],
            Hypothesis::Axisymmetric,
        );
        let m = continuum_mass(&tri, CellId(0), Hypothesis::Axisymmetric, 2.0).unwrap();
        let rbar = (1. + 3. + 1.) / 3.;
        assert!((total(&m, 2) - 2.0 * 2.0 * rbar).abs() < 1e-12);
        // The consistent TRIA3 mass is ρA/12 (2 on the diagonal, 1 off it)
        // in plane strain: FPG3 integrates it exactly.
        let tri = one_cell(
            CellType::TRIA3,
            vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]],
            Hypothesis::PlaneStrain,
        );
        let m = continuum_mass(&tri, CellId(0), Hypothesis::PlaneStrain, 12.0).unwrap();
        assert!((m[(0, 0)] - 1.0).abs() < 1e-14 && (m[(0, 2)] - 0.5).abs() < 1e-14);
        // TETRA10's FPG15 weights sum to the reference volume 1/6.
        let w: f64 = crate::fpg::tetra15().iter().map(|g| g.weight).sum();
        assert!((w - 1. / 6.).abs() < 1e-15);
    }
}
