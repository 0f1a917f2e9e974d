//! Linear heat conduction: code_aster's `THER_LINEAIRE` numerics.
//!
//! Unknown: the temperature at the nodes of the thermal cells (one per
//! node). Matrices, as code_aster's thermal elements (`te0076` RIGI_THER,
//! `te0077` MASS_THER, `te0070` RIGI_THER_COEH_R, `te0072`
//! CHAR_THER_TEXT_R), per radian in axisymmetry (weight r):
//!
//! - conductivity K = ∫ λ ∇Nᵢ·∇Nⱼ, capacity M = ∫ ρCp Nᵢ Nⱼ, both with
//!   the cell's `RIGI`/`MASS` families (2D: QUAD4 FPG4, QUAD8/QUAD9 FPG9,
//!   TRIA3 FPG3, TRIA6 FPG6; 3D: HEXA8 FPG8, HEXA20/27 FPG27, TETRA4 FPG4,
//!   TETRA10 FPG15, PENTA6 FPG6, PENTA15 FPG21, PYRAM5 FPG5);
//! - exchange (`ECHANGE`, `COEF_H` h, `TEMP_EXT` Tₑ) on skin cells:
//!   H = ∫ h Nᵢ Nⱼ and the load ∫ h Tₑ Nᵢ (segments FPG4, faces their
//!   `RIGI` family);
//! - imposed normal flux (`FLUX_REP`, `FLUN` q): the load ∫ q Nᵢ.
//!
//! Time integration is code_aster's θ-scheme (`SCHEMA_TEMPS/THETA`, 0.57
//! by default), for Δt = tₙ₊₁ − tₙ:
//!
//! ```text
//! (M/Δt + θ(K + H)) Tₙ₊₁ = (M/Δt − (1−θ)(K + H)) Tₙ + F
//! ```
//!
//! with F = θF(tₙ₊₁) + (1−θ)F(tₙ) the loads (code_aster's
//! `ther_lineaire_ops._computeRhs`; only the normal fluxes of
//! [`ThermalProblem::varying_flux`] vary in time here). The
//! stationary problem (the initial state when `ETAT_INIT` is absent or
//! `STATIONNAIRE='OUI'`) is (K + H) T = F. Imposed temperatures
//! (`TEMP_IMPO`) are eliminated. The system matrix is symmetric positive
//! definite and factorised once per time step size.

use crate::element::physical_derivatives;
use crate::error::FemError;
use crate::shape::{self, GaussPoint};
use crate::{fpg, linalg};
use aster_mesh::vec3::{cross, norm};
use aster_mesh::{CellId, CellType, Mesh, NodeId};
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Col, Side};

/// The geometry of a thermal model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ThermalHypothesis {
    /// `PLAN`: per unit thickness.
    Plane,
    /// `AXIS`: x is the radius; integrals per radian (weight r).
    Axisymmetric,
    /// `3D`.
    Solid,
}

impl ThermalHypothesis {
    pub(crate) fn dim(self) -> usize {
        match self {
            ThermalHypothesis::Solid => 3,
            _ => 2,
        }
    }
}

/// `DEFI_MATERIAU/THER`: conductivity λ and volumic heat capacity ρCp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conduction {
    pub lambda: f64,
    pub rho_cp: f64,
}

/// A boundary condition on a skin cell (a segment in 2D, a face in 3D).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkinLoad {
    /// `ECHANGE`: flux h (Tₑ − T) entering the body.
    Exchange { h: f64, t_ext: f64 },
    /// `FLUX_REP/FLUN`: a flux q entering the body.
    NormalFlux { q: f64 },
}

/// A linear heat-conduction problem.
#[derive(Clone, Debug)]
pub struct ThermalProblem<'m> {
    pub mesh: &'m Mesh,
    pub hypothesis: ThermalHypothesis,
    /// The conducting cells and their material.
    pub cells: Vec<(CellId, Conduction)>,
    pub skin: Vec<(CellId, SkinLoad)>,
    /// Imposed temperatures (`TEMP_IMPO`).
    pub imposed: Vec<(NodeId, Imposed)>,
    /// Normal fluxes varying in time (`FLUX_REP` given by a function of
    /// `INST`, or scaled by `EXCIT/FONC_MULT`): q at each instant of the
    /// computation, as [`Imposed::PerInstant`].
    pub varying_flux: Vec<(CellId, Vec<f64>)>,
    /// Constant volume heat sources (`SOURCE/SOUR`, W/m³) per conducting
    /// cell, integrated on the cell's `RIGI` family as code_aster's
    /// `te0080` does.
    pub sources: Vec<(CellId, f64)>,
}

/// An imposed temperature (`TEMP_IMPO`; dualised in code_aster, so the
/// node takes exactly its value at each instant).
#[derive(Clone, Debug, PartialEq)]
pub enum Imposed {
    Constant(f64),
    /// Its value at each instant of the computation (a function of time
    /// evaluated by the caller): [`Transient::instants`], or the instants
    /// [`stationary`] is asked for.
    PerInstant(Vec<f64>),
}

/// The time discretisation of a transient computation.
#[derive(Clone, Debug, PartialEq)]
pub struct Transient {
    /// `SCHEMA_TEMPS/THETA`.
    pub theta: f64,
    /// The instants, the first being the initial one.
    pub instants: Vec<f64>,
    /// The initial temperature per mesh node; `None`: the stationary
    /// solution at the first instant (code_aster's default).
    pub initial: Option<Vec<f64>>,
}

/// code_aster's `RIGI`/`MASS` family of a thermal cell (they coincide).
pub(crate) fn volume_scheme(ty: CellType) -> Option<Vec<GaussPoint>> {
    Some(match ty {
        CellType::TRIA3 | CellType::TRIA6 | CellType::QUAD4 | CellType::QUAD8 => {
            shape::mass_scheme(ty)
        }
        CellType::QUAD9 => shape::rigi_scheme(ty),
        CellType::HEXA8 => fpg::hexa(2),
        CellType::HEXA20 | CellType::HEXA27 => fpg::hexa(3),
        CellType::TETRA4 => fpg::tetra4(),
        CellType::TETRA10 => fpg::tetra15(),
        CellType::PENTA6 => fpg::penta6(),
        CellType::PENTA15 => fpg::penta21(),
        CellType::PYRAM5 => fpg::pyram5(),
        _ => return None,
    })
}

/// The family of a skin cell: segments FPG4 (`THPLSE2`, `THAXSE3`…),
/// faces their `RIGI` family.
pub(crate) fn skin_scheme(ty: CellType) -> Option<Vec<GaussPoint>> {
    match ty {
        CellType::SEG2 | CellType::SEG3 => Some(shape::skin_scheme(CellType::SEG3)),
        CellType::TRIA3 | CellType::TRIA6 | CellType::QUAD4 | CellType::QUAD8 | CellType::QUAD9 => {
            Some(shape::skin_scheme(ty))
        }
        _ => None,
    }
}

/// Whether a cell type can carry the conduction elements.
pub fn conducting_cell(ty: CellType, hypothesis: ThermalHypothesis) -> bool {
    let dim = ty.dim();
    volume_scheme(ty).is_some() && usize::from(dim) == hypothesis.dim()
}

/// The assembled matrices over the model's nodes.
struct Assembled {
    /// Mesh node → unknown (`usize::MAX`: not in the model).
    unknown_of: Vec<usize>,
    n: usize,
    /// Conductivity + exchange (K + H), symmetric, full pattern.
    k: linalg::Csc,
    /// Capacity M on the same pattern.
    m: linalg::Csc,
    /// Constant loads F.
    f: Vec<f64>,
}

/// The thermal unknowns: one per node of `cells`, numbered in the order
/// the nodes first appear; `usize::MAX` for the other nodes of the mesh.
/// Returns that map (indexed by node) and the number of unknowns.
pub(crate) fn number_unknowns(
    mesh: &Mesh,
    cells: impl Iterator<Item = CellId>,
) -> (Vec<usize>, usize) {
    let mut unknown_of = vec![usize::MAX; mesh.node_count()];
    let mut n = 0;
    for c in cells {
        for &node in &mesh.cell(c).nodes {
            let u = &mut unknown_of[node.0 as usize];
            if *u == usize::MAX {
                *u = n;
                n += 1;
            }
        }
    }
    (unknown_of, n)
}

fn assemble(p: &ThermalProblem) -> Result<Assembled, FemError> {
    let mesh = p.mesh;
    let dim = p.hypothesis.dim();
    let axis = p.hypothesis == ThermalHypothesis::Axisymmetric;
    let (unknown_of, n) = number_unknowns(mesh, p.cells.iter().map(|(c, _)| *c));
    let mut cols: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut cell_unknowns = Vec::new();
    for c in p
        .cells
        .iter()
        .map(|(c, _)| c)
        .chain(p.skin.iter().map(|(c, _)| c))
    {
        cell_unknowns.clear();
        for &node in &mesh.cell(*c).nodes {
            let u = unknown_of[node.0 as usize];
            if u == usize::MAX {
                return Err(FemError::Model(format!(
                    "cell {} carries a thermal load but node {} is in no cell of the thermal model",
                    mesh.cell_name(*c),
                    mesh.node_name(node)
                )));
            }
            cell_unknowns.push(u);
        }
        for &i in &cell_unknowns {
            for &j in &cell_unknowns {
                cols[j].push(i as u32);
            }
        }
    }
    let mut k = linalg::Csc::from_columns(n, cols);
    let mut m = k.clone();
    let mut f = vec![0.0; n];
    for (cell, mat) in &p.cells {
        let c = mesh.cell(*cell);
        let dofs: Vec<usize> = c.nodes.iter().map(|n| unknown_of[n.0 as usize]).collect();
        for (nv, dn, w) in volume_points(mesh, *cell, dim, axis)? {
            for (a, &i) in dofs.iter().enumerate() {
                for (b, &j) in dofs.iter().enumerate() {
                    let grad: f64 = (0..dim).map(|d| dn[a][d] * dn[b][d]).sum();
                    k.add(i, j, w * mat.lambda * grad);
                    m.add(i, j, w * mat.rho_cp * nv[a] * nv[b]);
                }
            }
        }
    }
    for (cell, q) in &p.sources {
        let c = mesh.cell(*cell);
        let dofs: Vec<usize> = c.nodes.iter().map(|n| unknown_of[n.0 as usize]).collect();
        if dofs.contains(&usize::MAX) {
            return Err(FemError::Model(format!(
                "cell {} carries a heat source but is not a conducting cell of the model",
                mesh.cell_name(*cell)
            )));
        }
        for (nv, _, w) in volume_points(mesh, *cell, dim, axis)? {
            for (a, &i) in dofs.iter().enumerate() {
                f[i] += w * q * nv[a];
            }
        }
    }
    for (cell, load) in &p.skin {
        let c = mesh.cell(*cell);
        let dofs: Vec<usize> = c.nodes.iter().map(|n| unknown_of[n.0 as usize]).collect();
        for (n, w) in skin_points(mesh, *cell, axis)? {
            match *load {
                SkinLoad::Exchange { h, t_ext } => {
                    for (a, &i) in dofs.iter().enumerate() {
                        f[i] += w * h * t_ext * n[a];
                        for (b, &j) in dofs.iter().enumerate() {
                            k.add(i, j, w * h * n[a] * n[b]);
                        }
                    }
                }
                SkinLoad::NormalFlux { q } => {
                    for (a, &i) in dofs.iter().enumerate() {
                        f[i] += w * q * n[a];
                    }
                }
            }
        }
    }
    Ok(Assembled {
        unknown_of,
        n,
        k,
        m,
        f,
    })
}

/// Per Gauss point of a volume cell of a thermal model: the shape
/// functions, their physical gradients and the weight (times r in
/// axisymmetry).
pub(crate) type VolumePoint = (Vec<f64>, Vec<[f64; 3]>, f64);

/// The Gauss points of a volume cell of a thermal model.
pub(crate) fn volume_points(
    mesh: &Mesh,
    cell: CellId,
    dim: usize,
    axis: bool,
) -> Result<Vec<VolumePoint>, FemError> {
    let c = mesh.cell(cell);
    let scheme = volume_scheme(c.ty).ok_or_else(|| {
        FemError::Model(format!(
            "cell {} is a {:?}: no thermal element for it",
            mesh.cell_name(cell),
            c.ty
        ))
    })?;
    let mut points = Vec::with_capacity(scheme.len());
    for gp in &scheme {
        let (nv, dn, det, x) = physical_derivatives(mesh, cell, dim, gp)
            .map_err(|e| FemError::Model(format!("cell {} is {e}", mesh.cell_name(cell))))?;
        let mut w = gp.weight * det.abs();
        if axis {
            w *= x[0];
        }
        points.push((nv, dn, w));
    }
    Ok(points)
}

/// The Gauss points of a skin cell (edge or face) of a thermal model: the
/// shape functions and the weight (times r in axisymmetry).
pub(crate) fn skin_points(
    mesh: &Mesh,
    cell: CellId,
    axis: bool,
) -> Result<Vec<(Vec<f64>, f64)>, FemError> {
    let c = mesh.cell(cell);
    let scheme = skin_scheme(c.ty).ok_or_else(|| {
        FemError::Model(format!(
            "cell {} is a {:?}: no thermal boundary element for it",
            mesh.cell_name(cell),
            c.ty
        ))
    })?;
    let mut points = Vec::with_capacity(scheme.len());
    for gp in &scheme {
        let s = shape::shape(c.ty, gp.xi);
        let [x, t1, t2] = shape::point_and_tangents(mesh, c, &s);
        let measure = if c.ty.dim() == 1 {
            norm(t1)
        } else {
            norm(cross(t1, t2))
        };
        let mut w = gp.weight * measure;
        if axis {
            w *= x[0];
        }
        points.push((s.n, w));
    }
    Ok(points)
}

/// The loads F(tₖ) at instant `k`: the constant ones and the normal
/// fluxes of that instant.
fn loads_at(p: &ThermalProblem, a: &Assembled, k: usize) -> Result<Vec<f64>, FemError> {
    let mut f = a.f.clone();
    let axis = p.hypothesis == ThermalHypothesis::Axisymmetric;
    for (cell, qs) in &p.varying_flux {
        let q = *qs.get(k).ok_or_else(|| {
            FemError::Model(format!(
                "a varying flux has {} values, none for instant #{k}",
                qs.len()
            ))
        })?;
        let c = p.mesh.cell(*cell);
        for (n, w) in skin_points(p.mesh, *cell, axis)? {
            for (i, node) in c.nodes.iter().enumerate() {
                let u = a.unknown_of[node.0 as usize];
                if u == usize::MAX {
                    return Err(FemError::Model(format!(
                        "cell {} carries a thermal load but node {} is in no cell of the thermal model",
                        p.mesh.cell_name(*cell),
                        p.mesh.node_name(*node)
                    )));
                }
                f[u] += w * q * n[i];
            }
        }
    }
    Ok(f)
}

/// The free-free block of `c_m·M + c_k·K` (lower triangle, free indexing)
/// factorised by Cholesky.
struct Factorised {
    c_m: f64,
    c_k: f64,
    llt: Llt<usize, f64>,
}

/// Free unknowns and the imposed temperatures of the others.
struct Split<'p> {
    /// Unknown → free index (`usize::MAX` when imposed).
    free_of: Vec<usize>,
    n_free: usize,
    /// The imposed unknowns and their temperatures.
    imposed: Vec<(usize, &'p Imposed)>,
}

impl Split<'_> {
    /// Unknown → imposed value at instant `k` (0 when free).
    fn values_at(&self, n: usize, k: usize) -> Result<Vec<f64>, FemError> {
        let mut v = vec![0.0; n];
        for &(u, imp) in &self.imposed {
            v[u] = match imp {
                Imposed::Constant(t) => *t,
                Imposed::PerInstant(ts) => *ts.get(k).ok_or_else(|| {
                    FemError::Model(format!(
                        "an imposed temperature has {} values, none for instant #{k}",
                        ts.len()
                    ))
                })?,
            };
        }
        Ok(v)
    }
}

fn split<'p>(a: &Assembled, p: &'p ThermalProblem) -> Result<Split<'p>, FemError> {
    let mut value = vec![f64::NAN; a.n];
    let mut imposed = Vec::with_capacity(p.imposed.len());
    for (node, t) in &p.imposed {
        let node = *node;
        let u = a
            .unknown_of
            .get(node.0 as usize)
            .copied()
            .unwrap_or(usize::MAX);
        if u == usize::MAX {
            return Err(FemError::Model(format!(
                "a temperature is imposed on node {}, in no cell of the thermal model",
                p.mesh.node_name(node)
            )));
        }
        value[u] = 0.0;
        imposed.push((u, t));
    }
    let mut free_of = vec![usize::MAX; a.n];
    let mut n_free = 0;
    for (u, v) in value.iter_mut().enumerate() {
        if v.is_nan() {
            free_of[u] = n_free;
            n_free += 1;
            *v = 0.0;
        }
    }
    Ok(Split {
        free_of,
        n_free,
        imposed,
    })
}

/// The free-free block's symbolic Cholesky (the pattern is the same for
/// every c_m, c_k: it is computed once).
type Symbolic = Option<SymbolicLlt<usize>>;

fn factorise(
    a: &Assembled,
    sp: &Split,
    c_m: f64,
    c_k: f64,
    symbolic_kept: &mut Symbolic,
) -> Result<Factorised, FemError> {
    let mut col_ptr = vec![0usize];
    let mut row_idx = Vec::new();
    let mut values = Vec::new();
    for j in 0..a.n {
        if sp.free_of[j] == usize::MAX {
            continue;
        }
        for p in a.k.col_ptr[j]..a.k.col_ptr[j + 1] {
            let i = a.k.row_idx[p];
            let fi = sp.free_of[i];
            if fi != usize::MAX && fi >= sp.free_of[j] {
                row_idx.push(fi);
                values.push(c_m * a.m.values[p] + c_k * a.k.values[p]);
            }
        }
        col_ptr.push(row_idx.len());
    }
    let n = sp.n_free;
    let symbolic = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
    let mat = SparseColMatRef::new(symbolic, &values);
    // faer does not say which pivot failed (every unknown has its
    // diagonal: no node is left out of the pattern to name).
    let singular = || FemError::Singular { free_dofs: vec![] };
    let sym = match symbolic_kept {
        Some(s) => s.clone(),
        None => {
            let s = SymbolicLlt::try_new(mat.symbolic(), Side::Lower).map_err(|_| singular())?;
            *symbolic_kept = Some(s.clone());
            s
        }
    };
    let llt = Llt::try_new_with_symbolic(sym, mat, Side::Lower).map_err(|_| singular())?;
    Ok(Factorised { c_m, c_k, llt })
}

impl Factorised {
    fn solve(&self, b: &[f64]) -> Vec<f64> {
        let mut c = Col::<f64>::from_fn(b.len(), |i| b[i]);
        use faer::linalg::solvers::Solve;
        self.llt.solve_in_place(c.as_mat_mut());
        (0..b.len()).map(|i| c[i]).collect()
    }
}

/// Solves (c_m M + c_k K) T = rhs for the free unknowns (the factor's
/// c_m, c_k), the imposed ones at their value (`imposed`, over all
/// unknowns, 0 on the free ones); `rhs` and the result over all unknowns.
fn solve_step(
    a: &Assembled,
    sp: &Split,
    factor: &Factorised,
    rhs: &[f64],
    imposed: &[f64],
) -> Result<Vec<f64>, FemError> {
    // What the imposed temperatures give on the free rows.
    let mut lift = vec![0.0; a.n];
    a.m.mul_add(factor.c_m, imposed, &mut lift);
    a.k.mul_add(factor.c_k, imposed, &mut lift);
    let b: Vec<f64> = (0..a.n)
        .filter(|&u| sp.free_of[u] != usize::MAX)
        .map(|u| rhs[u] - lift[u])
        .collect();
    let x = factor.solve(&b);
    if x.iter().any(|v| !v.is_finite()) {
        return Err(FemError::Singular { free_dofs: vec![] });
    }
    Ok((0..a.n)
        .map(|u| match sp.free_of[u] {
            usize::MAX => imposed[u],
            f => x[f],
        })
        .collect())
}

/// Temperature per mesh node (NaN off the model) from the unknowns.
fn to_nodes(a: &Assembled, t: &[f64]) -> Vec<f64> {
    a.unknown_of
        .iter()
        .map(|&u| if u == usize::MAX { f64::NAN } else { t[u] })
        .collect()
}

/// The stationary temperature (K + H) T = F at each of `instants`
/// instants (the imposed temperatures [`Imposed::PerInstant`] give one
/// value per instant; the other loads are constant).
pub fn stationary(p: &ThermalProblem, instants: usize) -> Result<Vec<Vec<f64>>, FemError> {
    let a = assemble(p)?;
    let sp = split(&a, p)?;
    let factor = factorise(&a, &sp, 0.0, 1.0, &mut None)?;
    (0..instants)
        .map(|k| {
            let f = loads_at(p, &a, k)?;
            let t = solve_step(&a, &sp, &factor, &f, &sp.values_at(a.n, k)?)?;
            Ok(to_nodes(&a, &t))
        })
        .collect()
}

/// The stationary temperature K T = F + `extra` (the problem's own loads
/// plus nodal loads `extra`, indexed by mesh node, that the caller
/// integrated itself: a source or a flux given by a function of the
/// coordinates). Per mesh node, NaN off the model. `aster_fem::section`
/// solves the Laplace problems of a beam section with it.
pub fn stationary_with(p: &ThermalProblem, extra: &[f64]) -> Result<Vec<f64>, FemError> {
    let a = assemble(p)?;
    let sp = split(&a, p)?;
    let factor = factorise(&a, &sp, 0.0, 1.0, &mut None)?;
    let mut f = loads_at(p, &a, 0)?;
    for (node, &u) in a.unknown_of.iter().enumerate() {
        if u != usize::MAX {
            f[u] += extra.get(node).copied().unwrap_or(0.0);
        }
    }
    let t = solve_step(&a, &sp, &factor, &f, &sp.values_at(a.n, 0)?)?;
    Ok(to_nodes(&a, &t))
}

/// The transient temperature at every instant of `tr` (per mesh node, NaN
/// off the model), the first being the initial state.
pub fn transient(p: &ThermalProblem, tr: &Transient) -> Result<Vec<Vec<f64>>, FemError> {
    if !(0.0..=1.0).contains(&tr.theta) || tr.theta == 0.0 {
        return Err(FemError::Model(format!(
            "THETA = {} must be in (0, 1]",
            tr.theta
        )));
    }
    let a = assemble(p)?;
    let sp = split(&a, p)?;
    let mut symbolic = None;
    let mut t = match &tr.initial {
        Some(t0) => {
            let mut t = vec![0.0; a.n];
            for (node, &u) in a.unknown_of.iter().enumerate() {
                if u != usize::MAX {
                    let v = t0.get(node).copied().unwrap_or(f64::NAN);
                    if !v.is_finite() {
                        return Err(FemError::Model(format!(
                            "the initial temperature has no value at node {}",
                            p.mesh.node_name(NodeId(node as u32))
                        )));
                    }
                    t[u] = v;
                }
            }
            t
        }
        None => {
            let factor = factorise(&a, &sp, 0.0, 1.0, &mut symbolic)?;
            solve_step(
                &a,
                &sp,
                &factor,
                &loads_at(p, &a, 0)?,
                &sp.values_at(a.n, 0)?,
            )?
        }
    };
    let mut out = vec![to_nodes(&a, &t)];
    let mut kept: Option<(f64, Factorised)> = None;
    for (k, w) in tr.instants.windows(2).enumerate() {
        let dt = w[1] - w[0];
        if dt <= 0.0 || !dt.is_finite() {
            return Err(FemError::Model(format!(
                "the instants must increase: {} then {}",
                w[0], w[1]
            )));
        }
        // code_aster refactorises when Δt changes (op0025: deltam ≠
        // deltat). The instants of a DEFI_LIST_REEL interval give steps
        // equal to rounding only: a step within 1e-12 (relative) of the
        // factorised one is taken equal to it (the scheme then advances
        // by that Δt, a change of 1e-12 relative in the capacity term).
        let (dt, factor) = match kept.take() {
            Some((d, f)) if (d - dt).abs() <= 1e-12 * dt => (d, f),
            _ => (dt, factorise(&a, &sp, 1.0 / dt, tr.theta, &mut symbolic)?),
        };
        let (f0, f1) = (loads_at(p, &a, k)?, loads_at(p, &a, k + 1)?);
        let mut rhs: Vec<f64> = (0..a.n)
            .map(|i| tr.theta * f1[i] + (1.0 - tr.theta) * f0[i])
            .collect();
        a.m.mul_add(factor.c_m, &t, &mut rhs);
        a.k.mul_add(-(1.0 - tr.theta), &t, &mut rhs);
        t = solve_step(&a, &sp, &factor, &rhs, &sp.values_at(a.n, k + 1)?)?;
        out.push(to_nodes(&a, &t));
        kept = Some((dt, factor));
    }
    Ok(out)
}
