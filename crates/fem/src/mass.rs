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
//! - POU_D_E beams: code_aster's `ptma01` ([`crate::beam::local_mass`]:
//!   no rotary inertia of bending, torsion with Iy + Iz), its diagonal
//!   variant when lumped.
//! - Discrete cells: `M_T_D_N` (a mass on each translation of a POI1
//!   node), `M_TR_D_N` (mass, inertia tensor and offset of a `DIS_TR` POI1,
//!   [`DiscreteMass::node_with_inertia`]), `M_TR_D_L`
//!   ([`DiscreteMass::segment_with_inertia`]) and `M_T_N`/`M_T_L`/`M_TR_N`/
//!   `M_TR_L` (a full symmetric matrix over the cell's DOFs, given as
//!   code_aster's upper triangle by columns).
//! - DKT shells: code_aster's `dktmas` on triangles
//!   ([`crate::dkt::local_mass`]) and `dkqmas` on quadrangles
//!   ([`crate::dkq::local_mass`]), lumped by `dialum` ([`lump_shell`]);
//!   COQUE_3D: no mass yet (an error naming the cell).
//! - Rayleigh damping (`ELAS/AMOR_ALPHA`, `AMOR_BETA`): C = Σ αₑ Kₑ + βₑ Mₑ
//!   per cell, with the elastic stiffness (`AMOR_RAYL_RIGI='ELASTIQUE'`).
//!
//! The matrices share the stiffness pattern ([`assembly::stiffness_pattern`])
//! so that K + c·M is a sum of value arrays.

use crate::assembly::stiffness_pattern;
use crate::element::{
    beam_coords, element_dofs_into, element_stiffness, physical_derivatives, spring_rotation,
};
use crate::error::FemError;
use crate::linalg::Csc;
use crate::material::Hypothesis;
use crate::model::{Element, ElementKind, Frame, Model};
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

/// The mass matrix of one discrete cell over its DOFs (global frame), or
/// an error naming the cell when the values do not fit it.
/// code_aster's `dialum` (`MASS_MECA_DIAG` of the DKT shells): the
/// diagonal of the global consistent matrix `m` (six DOFs a node) scaled so
/// that each translation's terms sum to the facet's mass `weight`; each
/// rotation's terms by the factor of the translation of the same axis
/// (DRX by DX's…); a zero diagonal term becomes 1e-5 × DX's factor × the
/// least non-zero diagonal term. Off-diagonal terms are dropped.
pub fn lump_shell(m: &DMatrix<f64>, weight: f64) -> DMatrix<f64> {
    let n = m.nrows();
    let nodes = n / 6;
    let mut sums = [0.0; 3];
    for k in 0..nodes {
        for (d, s) in sums.iter_mut().enumerate() {
            *s += m[(6 * k + d, 6 * k + d)];
        }
    }
    let alpha = sums.map(|s| weight / s);
    let mut out = DMatrix::zeros(n, n);
    let mut least = m[(0, 0)];
    let mut zeros = Vec::new();
    for i in 0..n {
        let d = m[(i, i)];
        if d == 0.0 {
            zeros.push(i);
        } else {
            least = least.min(d);
            out[(i, i)] = alpha[(i % 6) % 3] * d;
        }
    }
    for i in zeros {
        out[(i, i)] = 1e-5 * alpha[0] * least;
    }
    out
}

fn discrete_mass(model: &Model, d: &DiscreteMass) -> Result<(CellId, DMatrix<f64>), FemError> {
    let dim = model.dim();
    let cell = d.cell();
    if !model.elements().iter().any(|e| e.cell == cell) {
        return Err(FemError::Model(format!(
            "a discrete mass on cell {}, which carries no element of the model",
            model.cell_name(cell)
        )));
    }
    let nn = model.mesh().cell(cell).nodes.len();
    let mut dofs = Vec::new();
    element_dofs_into(model, cell, &mut dofs);
    let n = dofs.len();
    match d {
        DiscreteMass::Node { mass, .. } => {
            if nn != 1 {
                return Err(FemError::Model(format!(
                    "a node mass (M_T_D_N) on cell {}, which has {nn} nodes: it needs a POI1",
                    model.cell_name(cell)
                )));
            }
            if n != dim {
                // code_aster stops too (te0041, DISCRETS_25): the mass's
                // type must be the element's.
                return Err(FemError::Model(format!(
                    "a translational node mass (M_T_D_N) on cell {}, whose element has {n} DOFs (DIS_TR): give it M_TR_D_N",
                    model.cell_name(cell)
                )));
            }
            Ok((cell, DMatrix::identity(dim, dim) * *mass))
        }
        DiscreteMass::Matrix { upper, frame, .. } => {
            if upper.len() != n * (n + 1) / 2 {
                return Err(FemError::Model(format!(
                    "the mass matrix of cell {} has {} values; its element's {n} DOFs need {} (M_T_* for DIS_T, M_TR_* for DIS_TR)",
                    model.cell_name(cell),
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
            // The frame turns each block of `dim` components (translations,
            // then rotations, node by node: code_aster's `utpslg`).
            let r = spring_rotation(model.mesh(), cell, dim, *frame);
            let mut t = DMatrix::zeros(n, n);
            for b in 0..n / dim {
                t.view_mut((b * dim, b * dim), (dim, dim)).copy_from(&r);
            }
            Ok((cell, t.transpose() * m * t))
        }
    }
}

impl DiscreteMass {
    /// The cell the mass is on.
    pub fn cell(&self) -> CellId {
        match self {
            DiscreteMass::Node { cell, .. } | DiscreteMass::Matrix { cell, .. } => *cell,
        }
    }

    /// `M_TR_D_N` on a POI1 of `DIS_TR`: `v` = (m, Ixx, Iyy, Izz, Ixy,
    /// Iyz, Ixz, ex, ey, ez), the mass, its inertia tensor about its
    /// centre and the centre's offset from the node. The 6×6 matrix is
    /// code_aster's (`afdi3d`): m on the translations, the coupling m·e×
    /// between translations and rotations, the inertia moved to the node
    /// by Huygens (Ixx + m(ey² + ez²)…, Ixy − m·ex·ey…; the products as
    /// given, code_aster adds them without a sign change).
    pub fn node_with_inertia(cell: CellId, v: &[f64; 10]) -> DiscreteMass {
        let m = v[0];
        let (ex, ey, ez) = (v[7], v[8], v[9]);
        let mut upper = vec![0.0; 21];
        upper[0] = m;
        upper[2] = m;
        upper[5] = m;
        upper[7] = -m * ez;
        upper[8] = m * ey;
        upper[10] = m * ez;
        upper[12] = -m * ex;
        upper[15] = -m * ey;
        upper[16] = m * ex;
        upper[9] = v[1] + m * (ez * ez + ey * ey);
        upper[14] = v[2] + m * (ex * ex + ez * ez);
        upper[20] = v[3] + m * (ey * ey + ex * ex);
        upper[13] = v[4] - m * ex * ey;
        upper[19] = v[5] - m * ey * ez;
        upper[18] = v[6] - m * ex * ez;
        DiscreteMass::Matrix {
            cell,
            upper,
            frame: Frame::Global,
        }
    }

    /// `M_TR_D_L` on a SEG2 of `DIS_TR`: `v` = (m, Ixx, Iyy, Izz), the
    /// same mass and inertia at each of the two nodes (`afdi3d`: the
    /// diagonal of the 12×12 matrix, nothing split), in `frame`.
    pub fn segment_with_inertia(cell: CellId, v: &[f64; 4], frame: Frame) -> DiscreteMass {
        let mut upper = vec![0.0; 78];
        for j in 0..12 {
            upper[j * (j + 1) / 2 + j] = if j % 6 < 3 { v[0] } else { v[1 + j % 6 - 3] };
        }
        DiscreteMass::Matrix { cell, upper, frame }
    }
}

/// The mass of one element of density `rho` over its DOFs (node-major):
/// continuum cells ([`continuum_mass`], lumped by [`lump`]), POU_D_E beams
/// ([`crate::beam::mass`], code_aster's `ptma01`), DKT shells
/// ([`crate::dkt::mass`], `dktmas`; [`crate::dkq::mass`], `dkqmas`; lumped
/// by [`lump_shell`], `dialum`); `None` for the elements without a mass of
/// their own (springs carry the discrete masses, boundary cells nothing).
/// COQUE_3D: an error naming the cell.
pub fn element_mass(
    model: &Model,
    el: &Element,
    rho: f64,
    lumping: Lumping,
) -> Result<Option<DMatrix<f64>>, FemError> {
    let lumped = lumping == Lumping::Diagonal;
    match &el.kind {
        ElementKind::Continuum { hypothesis, .. } => {
            let m = continuum_mass(model, el.cell, *hypothesis, rho)?;
            Ok(Some(if lumped {
                lump(&m, hypothesis.dim())
            } else {
                m
            }))
        }
        ElementKind::Beam { material, section } => beam_coords(model.mesh(), el.cell)
            .and_then(|xyz| crate::beam::mass(&xyz, rho, material, section, lumped))
            .map(Some)
            .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))),
        ElementKind::Bar { area, .. } => beam_coords(model.mesh(), el.cell)
            .and_then(|xyz| crate::bar::mass(&xyz, rho, *area, lumped))
            .map(Some)
            .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell)))),
        ElementKind::Shell {
            material,
            section,
            theory,
        } => {
            let c = model.mesh().cell(el.cell);
            let xyz: Vec<[f64; 3]> = c.nodes.iter().map(|&n| model.mesh().coord(n)).collect();
            let built = crate::plate::mass(*theory, &xyz, material, rho, section);
            let (m, weight) = built
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))?;
            Ok(Some(if lumped { lump_shell(&m, weight) } else { m }))
        }
        ElementKind::Coque3d { .. } if lumped => Err(FemError::Model(format!(
            "cell {} is a COQUE_3D shell: its lumped mass is not implemented (its consistent one, te0406, is)",
            model.cell_name(el.cell),
        ))),
        ElementKind::Coque3d { section, .. } => {
            crate::element::coque3d_coords(model.mesh(), el.cell)
                .and_then(|xyz| {
                    let n = 6 * xyz.len() + 3;
                    crate::coque3d::mass(&xyz, rho, section)
                        .map(|m| DMatrix::from_row_slice(n, n, &m))
                })
                .map(Some)
                .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(el.cell))))
        }
        ElementKind::Grid { .. } => Err(FemError::Model(format!(
            "cell {} is a reinforcement grid (GRILLE_*): its mass (te0432) is not implemented",
            model.cell_name(el.cell),
        ))),
        ElementKind::Spring { .. } | ElementKind::Boundary => Ok(None),
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
        let Some(&rho) = data.density.get(&el.cell) else {
            continue;
        };
        if rho == 0.0 {
            continue;
        }
        if let Some(m) = element_mass(model, el, rho, lumping)? {
            scatter(model, &mut out, el.cell, &m, &mut dofs);
        }
    }
    for d in &data.discrete {
        let (cell, mut m) = discrete_mass(model, d)?;
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
        // Discrete elements damp through their own A_* characteristics
        // (code_aster's te0041), not through a material's Rayleigh terms.
        if matches!(el.kind, ElementKind::Spring { .. } | ElementKind::Boundary) {
            continue;
        }
        let mut c = DMatrix::zeros(0, 0);
        if r.alpha != 0.0 {
            if let Some(k) = element_stiffness(model, index)? {
                c = k * r.alpha;
            }
        }
        if r.beta != 0.0 {
            let rho = data.density.get(&el.cell).copied().unwrap_or(0.0);
            if rho != 0.0 {
                if let Some(m) = element_mass(model, el, rho, Lumping::Consistent)? {
                    let m = m * r.beta;
                    c = if c.is_empty() { m } else { c + m };
                }
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

/// The kinetic energy ½ vₑᵀ Mₑ vₑ of every continuum or beam cell with a
/// density (code_aster's `ECIN_ELEM`, consistent mass: `te0151` takes the
/// beams' `pomass` as `MASS_MECA` does), in element order: what
/// `POST_ELEM/ENER_CIN` sums over the cells it is asked for.
pub fn kinetic_energy_by_cell(
    model: &Model,
    data: &MassData,
    velocity: &[f64],
) -> Result<Vec<(CellId, f64)>, FemError> {
    let mut out = Vec::new();
    let mut dofs = Vec::new();
    for el in model.elements() {
        let Some(&rho) = data.density.get(&el.cell) else {
            continue;
        };
        let Some(m) = element_mass(model, el, rho, Lumping::Consistent)? else {
            continue;
        };
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

/// code_aster's `ECIN_ELEM` of a mode (`CALC_CHAMP/ENERGIE` on a
/// `MODE_MECA`): the mode's shape `u` stands for the velocity and the
/// energies are multiplied by its ω² (`POMEGA2`), per cell with a density,
/// with the components code_aster's elements write:
/// - continuum cells, beams, bars: `TOTALE` = ½ ω² uₑᵀ Mₑ uₑ (te0151
///   and the continuum `te` also write per-direction shares, not given);
/// - DKT/DKQ/DST/Q4G plates (`te0031` → `dxtloe`): `TOTALE` as above,
///   `MEMBRANE` and `FLEXION` are ω² × the *share* of the total that the
///   membrane (in-plane translations) and bending (normal translation and
///   in-plane rotations) DOFs of the facet's frame carry alone — code_aster
///   multiplies the fractions by ω² too (`te0031`: `zr(jfreq)*ener(i)` for
///   the three);
/// - COQUE_3D (`te0406`): `MEMBRANE` = `FLEXION` = `TOTALE` (it copies the
///   total into both).
///
/// Consistent masses, as code_aster's option computes them whatever the
/// modes' mass matrix was.
pub fn modal_kinetic_energy_by_cell(
    model: &Model,
    data: &MassData,
    u: &[f64],
    omega2: f64,
) -> Result<Vec<crate::post::CellValues>, FemError> {
    let mut out = Vec::new();
    let mut dofs = Vec::new();
    let quad = |m: &DMatrix<f64>, v: &[f64]| -> f64 {
        let mut e = 0.0;
        for a in 0..v.len() {
            if v[a] == 0.0 {
                continue;
            }
            for b in 0..v.len() {
                e += v[a] * m[(a, b)] * v[b];
            }
        }
        0.5 * e
    };
    for el in model.elements() {
        let Some(&rho) = data.density.get(&el.cell) else {
            continue;
        };
        let Some(m) = element_mass(model, el, rho, Lumping::Consistent)? else {
            continue;
        };
        dofs.clear();
        element_dofs_into(model, el.cell, &mut dofs);
        if dofs.len() != m.nrows() {
            return Err(FemError::Model(format!(
                "cell {}: {} DOFs for a {}×{} mass",
                model.cell_name(el.cell),
                dofs.len(),
                m.nrows(),
                m.ncols()
            )));
        }
        let v: Vec<f64> = dofs
            .iter()
            .map(|&i| u.get(i).copied().unwrap_or(0.0))
            .collect();
        let total = quad(&m, &v);
        let (names, values): (Vec<&'static str>, Vec<f64>) = match &el.kind {
            ElementKind::Shell { .. } => {
                let mesh = model.mesh();
                let xyz: Vec<[f64; 3]> = mesh
                    .cell(el.cell)
                    .nodes
                    .iter()
                    .map(|&n| mesh.coord(n))
                    .collect();
                let n = facet_normal(&xyz).ok_or_else(|| {
                    FemError::Model(format!(
                        "cell {}: a degenerate facet has no normal",
                        model.cell_name(el.cell)
                    ))
                })?;
                if v.len() != 6 * xyz.len() {
                    return Err(FemError::Model(format!(
                        "cell {}: {} DOFs for a facet of {} nodes",
                        model.cell_name(el.cell),
                        v.len(),
                        xyz.len()
                    )));
                }
                // The membrane and bending parts of the facet's local
                // DOFs, back in the global frame: uₘ = the in-plane
                // translations, u_f = the normal translation and the
                // in-plane rotations (vᵀ Mₗₒ꜀ v = (Tᵀv)ᵀ M (Tᵀv)).
                let dot = |a: &[f64], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                let mut vm = vec![0.0; v.len()];
                let mut vf = vec![0.0; v.len()];
                for node in 0..xyz.len() {
                    let t = &v[6 * node..6 * node + 3];
                    let r = &v[6 * node + 3..6 * node + 6];
                    let tn = dot(t, &n);
                    let rn = dot(r, &n);
                    for k in 0..3 {
                        vm[6 * node + k] = t[k] - tn * n[k];
                        vf[6 * node + k] = tn * n[k];
                        vf[6 * node + 3 + k] = r[k] - rn * n[k];
                    }
                }
                let (memb, flex) = if total.abs() > 1e-6 {
                    (quad(&m, &vm) / total, quad(&m, &vf) / total)
                } else {
                    (0.0, 0.0)
                };
                (
                    vec!["TOTALE", "MEMBRANE", "FLEXION"],
                    vec![omega2 * total, omega2 * memb, omega2 * flex],
                )
            }
            ElementKind::Coque3d { .. } => (
                vec!["TOTALE", "MEMBRANE", "FLEXION"],
                vec![omega2 * total; 3],
            ),
            _ => (vec!["TOTALE"], vec![omega2 * total]),
        };
        out.push(crate::post::CellValues {
            cell: el.cell,
            names,
            points: vec![values],
        });
    }
    Ok(out)
}

/// The unit normal of a plate facet: (x₂ − x₁) × (x₃ − x₁) on a triangle,
/// the product of the diagonals on a quadrangle.
fn facet_normal(xyz: &[[f64; 3]]) -> Option<[f64; 3]> {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let (a, b) = match xyz {
        [p1, p2, p3] => (sub(*p2, *p1), sub(*p3, *p1)),
        [p1, p2, p3, p4] => (sub(*p3, *p1), sub(*p4, *p2)),
        _ => return None,
    };
    let n = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (l > 0.0).then(|| [n[0] / l, n[1] / l, n[2] / l])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Elastic;
    use crate::model::Element;
    use aster_mesh::{CellType, Mesh};

    fn one_cell(ty: CellType, coords: Vec<[f64; 3]>, hyp: Hypothesis) -> Model {
        let kind = ElementKind::Continuum {
            hypothesis: hyp,
            material: Elastic::new(1.0, 0.3).unwrap(),
        };
        single(ty, coords, hyp.dim().max(2) as u8, kind)
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

    /// A model of one cell with `kind` on nodes `coords`, in `dim` dimensions.
    fn single(ty: CellType, coords: Vec<[f64; 3]>, dim: u8, kind: ElementKind) -> Model {
        let n = coords.len();
        let mut mesh = Mesh {
            dim,
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
                kind,
            }],
        )
        .unwrap()
    }

    fn structural(ty: CellType, coords: Vec<[f64; 3]>, kind: ElementKind) -> Model {
        single(ty, coords, 3, kind)
    }

    fn quad(m: &DMatrix<f64>, v: &[f64]) -> f64 {
        let v = nalgebra::DVector::from_column_slice(v);
        (v.transpose() * m * &v)[(0, 0)]
    }

    use aster_mesh::vec3::{cross, dot};

    /// Velocities of a rigid motion (v0 + ω × x, ω) at the nodes.
    fn rigid(coords: &[[f64; 3]], v0: [f64; 3], w: [f64; 3]) -> Vec<f64> {
        let mut v = Vec::new();
        for &x in coords {
            let r = cross(w, x);
            v.extend([v0[0] + r[0], v0[1] + r[1], v0[2] + r[2], w[0], w[1], w[2]]);
        }
        v
    }

    #[test]
    fn beam_mass_moves_rigidly_as_code_aster_s() {
        let s = crate::beam::BeamSection::rectangle(0.1, 0.05, None);
        let (a, b) = ([0.3, -0.2, 0.5], [1.9, 0.7, -0.4]);
        let kind = ElementKind::Beam {
            material: Elastic::new(2e11, 0.3).unwrap(),
            section: s,
        };
        let model = structural(CellType::SEG2, vec![a, b], kind);
        let rho = 7800.0;
        let el = &model.elements()[0];
        let m = element_mass(&model, el, rho, Lumping::Consistent)
            .unwrap()
            .unwrap();
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let l = dot(d, d).sqrt();
        // A translation carries the mass ρAL.
        for v0 in [[1., 0., 0.], [0.3, -0.7, 0.2]] {
            let v = rigid(&[a, b], v0, [0.; 3]);
            let e = quad(&m, &v);
            assert!((e - rho * s.area * l * dot(v0, v0)).abs() < 1e-10 * e);
        }
        // A rotation ω about the origin: the centre line's ρA∫|ω×x|² ds
        // (Simpson is exact on the quadratic) plus the torsion inertia
        // ρ(Iy+Iz)L(ω·x̂)², and no rotary inertia of bending (ptma01 for
        // POU_D_E).
        let w = [0.4, -1.3, 0.8];
        let f = |t: f64| {
            let x = [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]];
            let r = cross(w, x);
            dot(r, r)
        };
        let line = l * (f(0.) + 4. * f(0.5) + f(1.)) / 6.;
        let axial = dot(w, d) / l;
        let exact = rho * s.area * line + rho * (s.iy + s.iz) * l * axial * axial;
        let e = quad(&m, &rigid(&[a, b], [0.; 3], w));
        assert!((e - exact).abs() < 1e-10 * exact, "{e} vs {exact}");
        // Lumped: the same translational mass, ρ(Iy+Iz)L on the torsion.
        let d2 = element_mass(&model, el, rho, Lumping::Diagonal)
            .unwrap()
            .unwrap();
        let v = rigid(&[a, b], [0.3, -0.7, 0.2], [0.; 3]);
        assert!((quad(&d2, &v) - quad(&m, &v)).abs() < 1e-10 * quad(&m, &v));
        let loc = crate::beam::local_mass(rho, &Elastic::new(2e11, 0.3).unwrap(), &s, l, true);
        assert!((loc[(3, 3)] + loc[(9, 9)] - rho * (s.iy + s.iz) * l).abs() < 1e-9);
        assert!(
            (loc[(4, 4)] - rho * s.area * l.powi(3) / 105. - 2. * rho * s.iy * l / 15.).abs()
                < 1e-9
        );
        // The assembled matrix is the element's.
        let data = MassData {
            density: HashMap::from([(CellId(0), rho)]),
            discrete: vec![],
        };
        let g = assemble_mass(&model, &data, Lumping::Consistent).unwrap();
        let v = rigid(&[a, b], [0.1, 0.2, 0.3], w);
        assert!((2. * kinetic_energy(&g, &v) - quad(&m, &v)).abs() < 1e-9 * quad(&m, &v));
        let by_cell = kinetic_energy_by_cell(&model, &data, &v).unwrap();
        assert!((by_cell[0].1 - kinetic_energy(&g, &v)).abs() < 1e-9 * by_cell[0].1);
    }

    #[test]
    fn rotational_node_mass_is_a_rigid_body_s() {
        // M_TR_D_N: m, Ixx, Iyy, Izz, Ixy, Iyz, Ixz, ex, ey, ez.
        let vals = [3.0, 0.7, 0.9, 1.1, 0.05, -0.08, 0.03, 0.2, -0.4, 0.6];
        let kind = ElementKind::Spring {
            stiffness: vec![0.0; 6],
            frame: Frame::Global,
        };
        let x = [1.0, 2.0, 3.0];
        let model = structural(CellType::POI1, vec![x], kind);
        let data = MassData {
            density: HashMap::new(),
            discrete: vec![DiscreteMass::node_with_inertia(CellId(0), &vals)],
        };
        let g = assemble_mass(&model, &data, Lumping::Consistent).unwrap();
        // ½ (m |v + ω×e|² + ω·I·ω): the body's centre is at node + e.
        let (v, w) = ([0.3, -0.5, 0.9], [1.2, -0.4, 0.7]);
        let e = [vals[7], vals[8], vals[9]];
        let vc = {
            let r = cross(w, e);
            [v[0] + r[0], v[1] + r[1], v[2] + r[2]]
        };
        let i = [
            [vals[1], vals[4], vals[6]],
            [vals[4], vals[2], vals[5]],
            [vals[6], vals[5], vals[3]],
        ];
        let iw = [dot(i[0], w), dot(i[1], w), dot(i[2], w)];
        let exact = 0.5 * (vals[0] * dot(vc, vc) + dot(w, iw));
        let got = kinetic_energy(&g, &[v[0], v[1], v[2], w[0], w[1], w[2]]);
        assert!((got - exact).abs() < 1e-12 * exact, "{got} vs {exact}");
        // A translational M_T_D_N on this DIS_TR cell stops, as code_aster.
        let bad = MassData {
            density: HashMap::new(),
            discrete: vec![DiscreteMass::Node {
                cell: CellId(0),
                mass: 1.0,
            }],
        };
        assert!(assemble_mass(&model, &bad, Lumping::Consistent).is_err());
        // M_TR_D_L: the mass and inertias at each node of the segment.
        let kind = ElementKind::Spring {
            stiffness: vec![0.0; 6],
            frame: Frame::Global,
        };
        let model = structural(CellType::SEG2, vec![[0.; 3], [1., 0., 0.]], kind);
        let data = MassData {
            density: HashMap::new(),
            discrete: vec![DiscreteMass::segment_with_inertia(
                CellId(0),
                &[2.0, 0.1, 0.2, 0.3],
                Frame::Local,
            )],
        };
        let g = assemble_mass(&model, &data, Lumping::Consistent).unwrap();
        let v = [1., 0., 0., 0., 0., 1., 1., 0., 0., 0., 0., 1.];
        assert!((kinetic_energy(&g, &v) - 0.5 * 2. * (2. + 0.3)).abs() < 1e-14);
    }

    #[test]
    fn dkt_triangle_mass_moves_rigidly_as_code_aster_s() {
        let xyz = [[0.2, -0.1, 0.3], [1.4, 0.3, -0.2], [0.5, 1.1, 0.6]];
        let (h, rho) = (0.02, 2700.0);
        let kind = ElementKind::Shell {
            material: Elastic::new(7e10, 0.3).unwrap(),
            section: crate::dkt::ShellSection::new(h),
            theory: crate::plate::PlateTheory::Dkt,
        };
        let model = structural(CellType::TRIA3, xyz.to_vec(), kind);
        let facet = crate::dkt::Facet::new(&xyz).unwrap();
        let sec = crate::dkt::ShellSection::new(h);
        let loc = crate::dkt::local_mass(&facet, rho, &sec);
        let m = element_mass(&model, &model.elements()[0], rho, Lumping::Consistent)
            .unwrap()
            .unwrap();
        let e1 = [
            xyz[1][0] - xyz[0][0],
            xyz[1][1] - xyz[0][1],
            xyz[1][2] - xyz[0][2],
        ];
        let e2 = [
            xyz[2][0] - xyz[0][0],
            xyz[2][1] - xyz[0][1],
            xyz[2][2] - xyz[0][2],
        ];
        let n = cross(e1, e2);
        let area = 0.5 * dot(n, n).sqrt();
        // Translations: ρhA.
        let v0 = [0.3, -0.7, 0.2];
        let e = quad(&m, &rigid(&xyz, v0, [0.; 3]));
        assert!((e - rho * h * area * dot(v0, v0)).abs() < 1e-12 * e);
        // A rotation about the origin: ρh ∫|ω×x|² dA (the cubic w of a
        // linear field is that field; the mid-edge rule is exact on the
        // quadratic), no rotary inertia (no INER_ROTA); the drilling term
        // on each node's rotation about the normal.
        let w = [0.4, -1.3, 0.8];
        let f = |x: [f64; 3]| {
            let r = cross(w, x);
            dot(r, r)
        };
        let mid = |a: usize, b: usize| [0, 1, 2].map(|k| 0.5 * (xyz[a][k] + xyz[b][k]));
        let wn = (0..3).map(|k| facet.pgl[(2, k)] * w[k]).sum::<f64>();
        let exact = rho * h * area / 3. * (f(mid(0, 1)) + f(mid(1, 2)) + f(mid(2, 0)))
            + 3. * loc[(5, 5)] * wn * wn;
        let e = quad(&m, &rigid(&xyz, [0.; 3], w));
        assert!((e - exact).abs() < 1e-10 * exact, "{e} vs {exact}");
        // The drilling term: COEF_RIGI_DRZ × the least bending-rotation
        // diagonal, on DRZ of the facet's frame.
        let least = [3, 4, 9, 10, 15, 16]
            .iter()
            .map(|&i| loc[(i, i)])
            .fold(f64::INFINITY, f64::min);
        assert!((loc[(5, 5)] - 1e-5 * least).abs() < 1e-20 && loc[(5, 5)] > 0.);
        rotary_inertia_adds_rho_h3_over_12(&model, &xyz, w, area, rho, h);
    }

    /// ECIN_ELEM of a mode on a tilted DKT facet, as `te0031`/`dxtloe`
    /// compute it in the facet's frame: TOTALE = ω² · ½ uₗᵀ Mₗ uₗ; MEMBRANE
    /// and FLEXION = ω² × the shares of the local membrane (u, v) and
    /// bending (w, θx, θy) blocks of the local mass in that total.
    #[test]
    fn dkt_modal_kinetic_energy_splits_as_dxtloe() {
        let xyz = [[0.2, -0.1, 0.3], [1.4, 0.3, -0.2], [0.5, 1.1, 0.6]];
        let (h, rho, omega2) = (0.02, 2700.0, 3.7e4);
        let kind = ElementKind::Shell {
            material: Elastic::new(7e10, 0.3).unwrap(),
            section: crate::dkt::ShellSection::new(h),
            theory: crate::plate::PlateTheory::Dkt,
        };
        let model = structural(CellType::TRIA3, xyz.to_vec(), kind);
        let facet = crate::dkt::Facet::new(&xyz).unwrap();
        let loc = crate::dkt::local_mass(&facet, rho, &crate::dkt::ShellSection::new(h));
        let loc = DMatrix::from_fn(18, 18, |i, j| loc[(i, j)]);
        let u: Vec<f64> = (0..18)
            .map(|i| ((i * 7 + 3) % 11) as f64 / 11.0 - 0.4)
            .collect();
        // The local DOFs: pgl × (DX DY DZ), pgl × (DRX DRY DRZ).
        let mut ul = [0.0; 18];
        for node in 0..3 {
            for half in 0..2 {
                for a in 0..3 {
                    ul[6 * node + 3 * half + a] = (0..3)
                        .map(|b| facet.pgl[(a, b)] * u[6 * node + 3 * half + b])
                        .sum();
                }
            }
        }
        let part = |keep: &[usize]| {
            let v: Vec<f64> = (0..18)
                .map(|i| if keep.contains(&(i % 6)) { ul[i] } else { 0.0 })
                .collect();
            0.5 * quad(&loc, &v)
        };
        let total = part(&[0, 1, 2, 3, 4, 5]);
        let (memb, flex) = (part(&[0, 1]), part(&[2, 3, 4]));
        let data = MassData {
            density: HashMap::from([(CellId(0), rho)]),
            discrete: Vec::new(),
        };
        let out = modal_kinetic_energy_by_cell(&model, &data, &u, omega2).unwrap();
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].names, ["TOTALE", "MEMBRANE", "FLEXION"]);
        let got = &out[0].points[0];
        for (g, want) in
            got.iter()
                .zip([omega2 * total, omega2 * memb / total, omega2 * flex / total])
        {
            assert!(
                (g - want).abs() <= 1e-10 * want.abs(),
                "{got:?}: {g} vs {want}"
            );
        }
        // The total is the global ½ uᵀ M u (the frame is a rotation).
        let m = element_mass(&model, &model.elements()[0], rho, Lumping::Consistent)
            .unwrap()
            .unwrap();
        assert!((got[0] - omega2 * 0.5 * quad(&m, &u)).abs() <= 1e-10 * got[0]);
        // A field in the facet's plane is all membrane.
        let n = [0, 1, 2].map(|k| facet.pgl[(2, k)]);
        let inplane: Vec<f64> = (0..3)
            .flat_map(|node| {
                let t = [0.3 + node as f64, -0.2, 0.5];
                let tn = dot(t, n);
                let t = [0, 1, 2].map(|k| t[k] - tn * n[k]);
                [t[0], t[1], t[2], 0.0, 0.0, 0.0]
            })
            .collect();
        let e =
            &modal_kinetic_energy_by_cell(&model, &data, &inplane, omega2).unwrap()[0].points[0];
        assert!(
            (e[1] - omega2).abs() < 1e-9 * omega2 && e[2].abs() < 1e-9 * omega2,
            "{e:?}"
        );
    }

    /// Beams: TOTALE only, ½ ω² uᵀ M u (te0151's ptenci).
    #[test]
    fn beam_modal_kinetic_energy_is_half_omega2_u_m_u() {
        let xyz = vec![[0.0, 0.0, 0.0], [0.7, 0.2, -0.1]];
        let section = crate::beam::BeamSection::rectangle(0.02, 0.01, None);
        let kind = ElementKind::Beam {
            material: Elastic::new(2.1e11, 0.3).unwrap(),
            section,
        };
        let model = structural(CellType::SEG2, xyz, kind);
        let rho = 7800.0;
        let data = MassData {
            density: HashMap::from([(CellId(0), rho)]),
            discrete: Vec::new(),
        };
        let u: Vec<f64> = (0..12).map(|i| (i as f64 * 0.37).sin()).collect();
        let m = element_mass(&model, &model.elements()[0], rho, Lumping::Consistent)
            .unwrap()
            .unwrap();
        let out = modal_kinetic_energy_by_cell(&model, &data, &u, 2.0).unwrap();
        assert_eq!(out[0].names, ["TOTALE"]);
        let want = quad(&m, &u);
        assert!((out[0].points[0][0] - want).abs() < 1e-12 * want.abs());
    }

    /// With `INER_ROTA='OUI'` a rigid rotation ω gains ρh³/12 · A · |ω in
    /// the plane|² (the DKT/DKQ rotations of a rigid motion are constant:
    /// `dktnib`/`dkqnib` reproduce them, the rule is exact).
    #[allow(clippy::too_many_arguments)]
    fn rotary_inertia_adds_rho_h3_over_12(
        model: &Model,
        xyz: &[[f64; 3]],
        w: [f64; 3],
        area: f64,
        rho: f64,
        h: f64,
    ) {
        // With a negligible drilling spring (it follows the bending
        // diagonal, which the rotary inertia changes).
        let ty = model.mesh().cell(model.elements()[0].cell).ty;
        let mass = |rotary_inertia: bool| {
            let section = crate::dkt::ShellSection {
                drilling: 1e-20,
                rotary_inertia,
                ..crate::dkt::ShellSection::new(h)
            };
            let kind = ElementKind::Shell {
                material: Elastic::new(7e10, 0.3).unwrap(),
                section,
                theory: crate::plate::PlateTheory::Dkt,
            };
            let one = structural(ty, xyz.to_vec(), kind);
            element_mass(&one, &one.elements()[0], rho, Lumping::Consistent)
                .unwrap()
                .unwrap()
        };
        let (m, without) = (mass(true), mass(false));
        let without = &without;
        let e1 = [0, 1, 2].map(|k| xyz[1][k] - xyz[0][k]);
        let e2 = [0, 1, 2].map(|k| xyz[2][k] - xyz[0][k]);
        let n = cross(e1, e2);
        let n = n.map(|x| x / dot(n, n).sqrt());
        let wn = dot(w, n);
        let in_plane = dot(w, w) - wn * wn;
        let v = rigid(xyz, [0.; 3], w);
        let gained = quad(&m, &v) - quad(without, &v);
        let exact = rho * h.powi(3) / 12. * area * in_plane;
        assert!(
            (gained - exact).abs() < 1e-10 * exact,
            "{gained} vs {exact}"
        );
        // Translations are unchanged.
        let t = rigid(xyz, [0.3, -0.7, 0.2], [0.; 3]);
        assert!((quad(&m, &t) - quad(without, &t)).abs() < 1e-12 * quad(&m, &t));
    }

    #[test]
    fn coque3d_mass_moves_rigidly_as_code_aster_s() {
        // A flat rectangle a × b turned in space, meshed by one QUAD9:
        // the serendipity translations and 3 × 3 normal points integrate
        // a rigid motion's square exactly, the two points through the
        // thickness the rotary term ρh³/12 |ω × n|².
        let (o, e1, e2) = ([0.2, -0.1, 0.3], [0.8, 0.6, 0.0], [0.0, 0.0, 1.0]);
        let (a, b) = (1.5, 0.7);
        let p = |s: f64, t: f64| [0, 1, 2].map(|k| o[k] + s * a * e1[k] + t * b * e2[k]);
        let ref9 = [
            (0., 0.),
            (1., 0.),
            (1., 1.),
            (0., 1.),
            (0.5, 0.),
            (1., 0.5),
            (0.5, 1.),
            (0., 0.5),
            (0.5, 0.5),
        ];
        let xyz: Vec<[f64; 3]> = ref9.iter().map(|&(s, t)| p(s, t)).collect();
        let (h, rho) = (0.05, 7800.0);
        let kind = ElementKind::Coque3d {
            material: Elastic::new(2e11, 0.3).unwrap(),
            section: crate::coque3d::Coque3dSection::new(h),
        };
        let model = structural(CellType::QUAD9, xyz.clone(), kind);
        let m = element_mass(&model, &model.elements()[0], rho, Lumping::Consistent)
            .unwrap()
            .unwrap();
        let area = a * b;
        let v0 = [0.3, -0.7, 0.2];
        // The central node carries rotations only.
        let rigid9 = |v0: [f64; 3], w: [f64; 3]| {
            let mut v = rigid(&xyz[..8], v0, w);
            v.extend(w);
            v
        };
        let e = quad(&m, &rigid9(v0, [0.; 3]));
        assert!((e - rho * h * area * dot(v0, v0)).abs() < 1e-12 * e, "{e}");
        // An in-plane ω (no drilling): ρh ∫|ω×x|² dA + ρh³/12 A |ω×n|².
        let n = cross(e1, e2);
        let w = [0, 1, 2].map(|k| 0.4 * e1[k] - 1.3 * e2[k]);
        let g = 0.5 * (0.6f64).sqrt();
        let (wg, w0) = (5. / 18., 8. / 18.);
        let mut integral = 0.;
        for (s, ws) in [(0.5 - g, wg), (0.5, w0), (0.5 + g, wg)] {
            for (t, wt) in [(0.5 - g, wg), (0.5, w0), (0.5 + g, wg)] {
                let r = cross(w, p(s, t));
                integral += dot(r, r) * area * ws * wt;
            }
        }
        let wn = cross(w, n);
        let exact = rho * h * integral + rho * h.powi(3) / 12. * area * dot(wn, wn);
        let e = quad(&m, &rigid9([0.; 3], w));
        assert!((e - exact).abs() < 1e-10 * exact, "{e} vs {exact}");
        // Lumped: not implemented, an error naming the cell.
        let err = element_mass(&model, &model.elements()[0], rho, Lumping::Diagonal)
            .unwrap_err()
            .to_string();
        assert!(err.contains("M1") && err.contains("lumped"), "{err}");
    }

    #[test]
    fn dkq_quadrangle_mass_moves_rigidly_as_code_aster_s() {
        // A planar parallelogram turned in space: its Jacobian is constant,
        // the membrane's literal pattern is the bilinear consistent mass and
        // FPG4 integrates the squares of linear fields exactly.
        let (o, a, b) = ([0.2, -0.1, 0.3], [1.1, 0.4, -0.2], [-0.3, 0.8, 0.5]);
        let p = |s: f64, t: f64| [0, 1, 2].map(|k| o[k] + s * a[k] + t * b[k]);
        let xyz = [p(0., 0.), p(1., 0.), p(1., 1.), p(0., 1.)];
        let (h, rho) = (0.02, 2700.0);
        let sec = crate::dkt::ShellSection::new(h);
        let kind = ElementKind::Shell {
            material: Elastic::new(7e10, 0.3).unwrap(),
            section: sec.clone(),
            theory: crate::plate::PlateTheory::Dkt,
        };
        let model = structural(CellType::QUAD4, xyz.to_vec(), kind);
        let facet = crate::dkq::Quad::new(&xyz).unwrap();
        let loc = crate::dkq::local_mass(&facet, rho, &sec);
        let m = element_mass(&model, &model.elements()[0], rho, Lumping::Consistent)
            .unwrap()
            .unwrap();
        let n = cross(a, b);
        let area = dot(n, n).sqrt();
        // Translations: ρhA.
        let v0 = [0.3, -0.7, 0.2];
        let e = quad(&m, &rigid(&xyz, v0, [0.; 3]));
        assert!((e - rho * h * area * dot(v0, v0)).abs() < 1e-12 * e);
        // A rotation about the origin: ρh ∫|ω×x|² dA (2 × 2 Gauss points
        // on the parallelogram: exact), no rotary inertia, and the drilling
        // term on each node's rotation about the normal.
        let w = [0.4, -1.3, 0.8];
        let g = 0.5 / 3f64.sqrt();
        let mut integral = 0.;
        for s in [0.5 - g, 0.5 + g] {
            for t in [0.5 - g, 0.5 + g] {
                let r = cross(w, p(s, t));
                integral += dot(r, r) * area / 4.;
            }
        }
        let wn = (0..3).map(|k| facet.pgl[(2, k)] * w[k]).sum::<f64>();
        let exact = rho * h * integral + 4. * loc[(5, 5)] * wn * wn;
        let e = quad(&m, &rigid(&xyz, [0.; 3], w));
        assert!((e - exact).abs() < 1e-10 * exact, "{e} vs {exact}");
        let least = [3, 4, 9, 10, 15, 16, 21, 22]
            .iter()
            .map(|&i| loc[(i, i)])
            .fold(f64::INFINITY, f64::min);
        assert!((loc[(5, 5)] - 1e-5 * least).abs() < 1e-20 && loc[(5, 5)] > 0.);
        rotary_inertia_adds_rho_h3_over_12(&model, &xyz, w, area, rho, h);
        // Lumped (dialum): diagonal, each translation's terms summing to
        // ρhA, the rotations scaled by the same factors.
        let d = element_mass(&model, &model.elements()[0], rho, Lumping::Diagonal)
            .unwrap()
            .unwrap();
        for axis in 0..3 {
            let sum: f64 = (0..4).map(|k| d[(6 * k + axis, 6 * k + axis)]).sum();
            assert!((sum - rho * h * area).abs() < 1e-12 * sum, "{axis}: {sum}");
            let alpha = d[(axis, axis)] / m[(axis, axis)];
            let r = 3 + axis;
            assert!((d[(r, r)] - alpha * m[(r, r)]).abs() <= 1e-12 * d[(r, r)]);
        }
        assert_eq!(
            (d.clone() - DMatrix::from_diagonal(&d.diagonal())).norm(),
            0.
        );
    }
}
