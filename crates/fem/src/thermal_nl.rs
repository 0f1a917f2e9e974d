//! Non-linear heat conduction: code_aster's `THER_NON_LINE` numerics
//! (code_aster 17's Python solver: `ThermalOperators`, `NewtonSolver`,
//! `ConvergenceManager`; elements `te0243` RAPH_THER / RIGI_THER_TANG,
//! `te0252` MASS_THER_RESI, `te0246` MASS_THER_TANG; material functions
//! read by `rcfode`, the enthalpy built from ρCp by `create_enthalpy`).
//!
//! The material (`DEFI_MATERIAU/THER_NL`) gives the conductivity λ(T) and
//! the volumic enthalpy β(T) as piecewise-linear functions of the
//! temperature. At the Gauss points of each cell (the cell's `RIGI`
//! family, which is its `MASS` family for the thermal elements), with T
//! interpolated from the nodes:
//!
//! - conduction residual  Rλ(T) = ∫ λ(T) ∇T·∇Nᵢ, its tangent
//!   ∫ λ(T) ∇Nⱼ·∇Nᵢ + ∫ Nⱼ λ'(T) ∇T·∇Nᵢ (not symmetric);
//! - capacity residual  B(T) = ∫ β(T) Nᵢ, its tangent ∫ β'(T) Nᵢ Nⱼ;
//! - loads  F(t, T) = ∫ q Nᵢ + ∫ h (Tₑ − T) Nᵢ on the skin cells (the
//!   exchange's tangent ∫ h Nᵢ Nⱼ).
//!
//! A transient step from (tₙ, Tₙ) to tₙ₊₁ (Δt = tₙ₊₁ − tₙ, θ from
//! `SCHEMA_TEMPS`) solves for T (`ThermalOperators._getResidualTrans`):
//!
//! ```text
//! θ Rλ(T) + B(T)/Δt + L = θ F(tₙ₊₁, T) + (1−θ) F(tₙ, Tₙ) + B(Tₙ)/Δt − (1−θ) Rλ(Tₙ)
//! ```
//!
//! L the reactions of the imposed temperatures (code_aster dualises
//! `TEMP_IMPO`; here they are eliminated and the multipliers L carried
//! along, since they enter the residual and its norm). The stationary
//! problem (`ETAT_INIT/STAT`) is Rλ(T) + L = F(t₀, T).
//!
//! Newton as code_aster iterates it: iteration 0 starts from Tₙ with the
//! imposed temperatures' increment and is always solved; at iteration k
//! the residual at Tₖ is measured — `RESI_GLOB_MAXI` its largest
//! component, `RESI_GLOB_RELA` that divided by the largest
//! |L + B(T) − F| over the nodes (B counted in transient steps only) — and
//! from k ≥ 1, when every given criterion holds, Tₖ is the answer. The
//! Jacobian θ K(T) + M(T)/Δt (stationary: K(T)) is computed at iteration
//! 0 of a step when `REAC_INCR` asks (every step by default) and again
//! every `REAC_ITER` iterations (0, the default: never within a step).

use crate::error::FemError;
use crate::linalg;
use crate::thermal::{
    skin_points, volume_points, volume_scheme, SkinLoad, ThermalHypothesis, VolumePoint,
};
use aster_mesh::{CellId, Mesh, NodeId};

/// code_aster's zero of the Celsius scale in Kelvin (`r8t0`).
const T0_KELVIN: f64 = 273.15;

/// How a material function is prolonged beyond its abscissae (the
/// `PROL_GAUCHE`/`PROL_DROITE` letters `rcfode` reads).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveEnd {
    Excluded,
    Constant,
    Linear,
}

/// A material function of the temperature, evaluated as `rcfode` does:
/// linear between its points whatever its `INTERPOL`.
#[derive(Clone, Debug, PartialEq)]
pub enum Curve {
    /// `DEFI_CONSTANTE`: the value, a zero derivative.
    Constant(f64),
    Table {
        xs: Vec<f64>,
        ys: Vec<f64>,
        left: CurveEnd,
        right: CurveEnd,
    },
}

impl Curve {
    /// A tabulated function: at least two strictly increasing abscissae.
    pub fn table(
        xs: Vec<f64>,
        ys: Vec<f64>,
        left: CurveEnd,
        right: CurveEnd,
    ) -> Result<Curve, String> {
        if xs.len() < 2 || xs.len() != ys.len() {
            return Err(format!(
                "a material function needs at least two points, got {}",
                xs.len()
            ));
        }
        if xs.windows(2).any(|w| w[1] <= w[0]) {
            return Err("the abscissae of a material function must increase".into());
        }
        Ok(Curve::Table {
            xs,
            ys,
            left,
            right,
        })
    }

    /// The value and the derivative at `t` (`rcfode`). Below the first
    /// abscissa `rcfode` reads the right prolongation first: with
    /// `PROL_DROITE='CONSTANT'` the first value is kept whatever
    /// `PROL_GAUCHE` says; else `PROL_GAUCHE='LINEAIRE'` prolongs the
    /// first segment and `EXCLU` is an error. With `PROL_GAUCHE='CONSTANT'`
    /// and another right prolongation `rcfode` leaves the value unset:
    /// refused.
    pub fn value(&self, t: f64) -> Result<(f64, f64), FemError> {
        let (xs, ys, left, right) = match self {
            Curve::Constant(v) => return Ok((*v, 0.0)),
            Curve::Table {
                xs,
                ys,
                left,
                right,
            } => (xs, ys, *left, *right),
        };
        let n = xs.len();
        let seg = |j: usize| {
            let df = (ys[j] - ys[j - 1]) / (xs[j] - xs[j - 1]);
            (df * (t - xs[j - 1]) + ys[j - 1], df)
        };
        if t.is_nan() {
            return Err(FemError::Model(
                "a material function of the temperature is evaluated at NaN".into(),
            ));
        }
        if t < xs[0] {
            return match (right, left) {
                (CurveEnd::Constant, _) => Ok((ys[0], 0.0)),
                (_, CurveEnd::Linear) => Ok(seg(1)),
                (_, CurveEnd::Excluded) => Err(FemError::Model(format!(
                    "temperature {t} below the first abscissa {} of a material function prolonged EXCLU",
                    xs[0]
                ))),
                (_, CurveEnd::Constant) => Err(FemError::Model(format!(
                    "temperature {t} below the first abscissa {} of a material function with PROL_GAUCHE='CONSTANT' and PROL_DROITE not CONSTANT: code_aster's rcfode leaves its value unset",
                    xs[0]
                ))),
            };
        }
        if t > xs[n - 1] {
            return match right {
                CurveEnd::Constant => Ok((ys[n - 1], 0.0)),
                CurveEnd::Linear => Ok(seg(n - 1)),
                CurveEnd::Excluded => Err(FemError::Model(format!(
                    "temperature {t} beyond the last abscissa {} of a material function prolonged EXCLU",
                    xs[n - 1]
                ))),
            };
        }
        let j = xs.partition_point(|x| *x < t).clamp(1, n - 1);
        Ok(seg(j))
    }

    /// The enthalpy β of a volumic heat capacity ρCp, as code_aster's
    /// `DEFI_MATERIAU` makes it when `THER_NL` gives `RHO_CP` without
    /// `BETA` (`create_enthalpy`): the trapezoidal integral of ρCp at its
    /// abscissae (β linear between them, not the exact quadratic), from
    /// β(x₀) = ½(ρCp₀ + ρCp₁)(x₀ + 273.15); prolonged linearly on the left,
    /// and on the right when ρCp was prolonged by a constant. A constant
    /// ρCp = c gives β(T) = c (T + 273.15).
    pub fn enthalpy_of(rho_cp: &Curve) -> Curve {
        match rho_cp {
            Curve::Constant(c) => Curve::Table {
                xs: vec![1.0, 2.0],
                ys: vec![c * (1.0 + T0_KELVIN), c * (1.0 + T0_KELVIN) + c],
                left: CurveEnd::Linear,
                right: CurveEnd::Linear,
            },
            Curve::Table { xs, ys, right, .. } => {
                let mut b = Vec::with_capacity(xs.len());
                b.push(0.5 * (ys[0] + ys[1]) * (T0_KELVIN + xs[0]));
                for i in 1..xs.len() {
                    let prev = b[i - 1];
                    b.push(prev + 0.5 * (xs[i] - xs[i - 1]) * (ys[i] + ys[i - 1]));
                }
                Curve::Table {
                    xs: xs.clone(),
                    ys: b,
                    left: CurveEnd::Linear,
                    right: match right {
                        CurveEnd::Constant => CurveEnd::Linear,
                        r => *r,
                    },
                }
            }
        }
    }
}

/// `DEFI_MATERIAU/THER_NL`: λ(T) and the enthalpy β(T).
#[derive(Clone, Debug, PartialEq)]
pub struct NlConduction {
    pub lambda: Curve,
    pub beta: Curve,
}

/// A non-linear heat-conduction problem: its cells, the skin cells that
/// carry loads and the nodes whose temperature is imposed (the values
/// come from [`NlLoads`] at each instant).
#[derive(Clone, Debug)]
pub struct NlProblem<'m> {
    pub mesh: &'m Mesh,
    pub hypothesis: ThermalHypothesis,
    /// The conducting cells and the index of their material.
    pub cells: Vec<(CellId, usize)>,
    pub materials: Vec<NlConduction>,
    /// The skin cells some load may act on.
    pub skin: Vec<CellId>,
    /// The nodes of imposed temperature.
    pub imposed: Vec<NodeId>,
}

/// The loads of a problem at an instant (functions of time evaluated by
/// the caller).
pub trait NlLoads {
    /// The boundary loads at `t` (on cells of [`NlProblem::skin`]).
    fn skin(&self, t: f64) -> Result<Vec<(CellId, SkinLoad)>, FemError>;
    /// The temperature of each node of [`NlProblem::imposed`] at `t`.
    fn imposed(&self, t: f64) -> Result<Vec<f64>, FemError>;
}

/// The initial state of a transient computation.
#[derive(Clone, Debug, PartialEq)]
pub enum NlInitial {
    /// `ETAT_INIT/STAT='OUI'` (the default): the stationary solution at the
    /// first instant.
    Stationary,
    /// A temperature per mesh node.
    Field(Vec<f64>),
}

/// `THER_NON_LINE`'s time and Newton settings.
#[derive(Clone, Debug, PartialEq)]
pub struct NlSettings {
    /// `SCHEMA_TEMPS/THETA` (`PARM_THETA`).
    pub theta: f64,
    /// The instants, the first being the initial one.
    pub instants: Vec<f64>,
    pub initial: NlInitial,
    /// `NEWTON/REAC_ITER` (0: the Jacobian is kept within a step).
    pub reac_iter: usize,
    /// `NEWTON/REAC_INCR` (1: a new Jacobian at each step; 0: never).
    pub reac_incr: usize,
    /// `CONVERGENCE/ITER_GLOB_MAXI`.
    pub iter_glob_maxi: usize,
    pub resi_glob_rela: Option<f64>,
    pub resi_glob_maxi: Option<f64>,
}

/// Per cell: its unknowns and, per Gauss point, N, ∇N, the weight (with r
/// in axisymmetry).
struct CellGauss {
    dofs: Vec<usize>,
    mat: usize,
    points: Vec<VolumePoint>,
}

/// Per skin cell: its unknowns and, per Gauss point, N and the weight.
struct SkinGauss {
    cell: CellId,
    dofs: Vec<usize>,
    points: Vec<(Vec<f64>, f64)>,
}

struct Model<'p> {
    p: &'p NlProblem<'p>,
    dim: usize,
    unknown_of: Vec<usize>,
    n: usize,
    cells: Vec<CellGauss>,
    skin: Vec<SkinGauss>,
    /// The pattern (all unknowns): values set by [`Model::jacobian`].
    pattern: linalg::Csc,
    /// Unknown → free index (`usize::MAX` when imposed).
    free_of: Vec<usize>,
    n_free: usize,
    /// The imposed unknowns, in the order of [`NlProblem::imposed`].
    imposed: Vec<usize>,
}

fn model<'p>(p: &'p NlProblem<'p>) -> Result<Model<'p>, FemError> {
    let mesh = p.mesh;
    let dim = p.hypothesis.dim();
    let axis = p.hypothesis == ThermalHypothesis::Axisymmetric;
    let (unknown_of, n) = crate::thermal::number_unknowns(mesh, p.cells.iter().map(|(c, _)| *c));
    let dofs_of = |c: CellId| -> Result<Vec<usize>, FemError> {
        mesh.cell(c)
            .nodes
            .iter()
            .map(|node| match unknown_of[node.0 as usize] {
                usize::MAX => Err(FemError::Model(format!(
                    "cell {} carries a thermal load but node {} is in no cell of the thermal model",
                    mesh.cell_name(c),
                    mesh.node_name(*node)
                ))),
                u => Ok(u),
            })
            .collect()
    };
    let mut cells = Vec::with_capacity(p.cells.len());
    for &(cell, mat) in &p.cells {
        cells.push(CellGauss {
            dofs: dofs_of(cell)?,
            mat,
            points: volume_points(mesh, cell, dim, axis)?,
        });
    }
    let mut skin = Vec::with_capacity(p.skin.len());
    for &cell in &p.skin {
        skin.push(SkinGauss {
            cell,
            dofs: dofs_of(cell)?,
            points: skin_points(mesh, cell, axis)?,
        });
    }
    let mut cols: Vec<Vec<u32>> = vec![Vec::new(); n];
    for dofs in cells
        .iter()
        .map(|c| &c.dofs)
        .chain(skin.iter().map(|s| &s.dofs))
    {
        for &i in dofs {
            for &j in dofs {
                cols[j].push(i as u32);
            }
        }
    }
    let pattern = linalg::Csc::from_columns(n, cols);
    let mut imposed = Vec::with_capacity(p.imposed.len());
    let mut free_of = vec![0usize; n];
    for node in &p.imposed {
        let u = unknown_of
            .get(node.0 as usize)
            .copied()
            .unwrap_or(usize::MAX);
        if u == usize::MAX {
            return Err(FemError::Model(format!(
                "a temperature is imposed on node {}, in no cell of the thermal model",
                mesh.node_name(*node)
            )));
        }
        free_of[u] = usize::MAX;
        imposed.push(u);
    }
    let mut n_free = 0;
    for f in free_of.iter_mut() {
        if *f != usize::MAX {
            *f = n_free;
            n_free += 1;
        }
    }
    Ok(Model {
        p,
        dim,
        unknown_of,
        n,
        cells,
        skin,
        pattern,
        free_of,
        n_free,
        imposed,
    })
}

/// The temperature and its gradient at a Gauss point.
fn at_point(dofs: &[usize], nv: &[f64], dn: &[[f64; 3]], dim: usize, t: &[f64]) -> (f64, [f64; 3]) {
    let mut tg = 0.0;
    let mut grad = [0.0; 3];
    for (a, &i) in dofs.iter().enumerate() {
        tg += nv[a] * t[i];
        for d in 0..dim {
            grad[d] += dn[a][d] * t[i];
        }
    }
    (tg, grad)
}

impl Model<'_> {
    /// Rλ(T) = ∫ λ(T) ∇T·∇Nᵢ and B(T) = ∫ β(T) Nᵢ.
    fn internal(&self, t: &[f64]) -> Result<(Vec<f64>, Vec<f64>), FemError> {
        let mut r = vec![0.0; self.n];
        let mut b = vec![0.0; self.n];
        for c in &self.cells {
            let m = &self.p.materials[c.mat];
            for (nv, dn, w) in &c.points {
                let (tg, grad) = at_point(&c.dofs, nv, dn, self.dim, t);
                let (lambda, _) = m.lambda.value(tg)?;
                let (beta, _) = m.beta.value(tg)?;
                for (a, &i) in c.dofs.iter().enumerate() {
                    let g: f64 = (0..self.dim).map(|d| grad[d] * dn[a][d]).sum();
                    r[i] += w * lambda * g;
                    b[i] += w * beta * nv[a];
                }
            }
        }
        Ok((r, b))
    }

    /// F(t, T) = ∫ q Nᵢ + ∫ h (Tₑ − T) Nᵢ.
    fn external(&self, loads: &[(CellId, SkinLoad)], t: &[f64]) -> Result<Vec<f64>, FemError> {
        let mut f = vec![0.0; self.n];
        for (cell, load) in loads {
            let s = self.skin_of(*cell)?;
            for (nv, w) in &s.points {
                let tg: f64 = s.dofs.iter().enumerate().map(|(a, &i)| nv[a] * t[i]).sum();
                let v = match *load {
                    SkinLoad::Exchange { h, t_ext } => h * (t_ext - tg),
                    SkinLoad::NormalFlux { q } => q,
                };
                for (a, &i) in s.dofs.iter().enumerate() {
                    f[i] += w * v * nv[a];
                }
            }
        }
        Ok(f)
    }

    fn skin_of(&self, cell: CellId) -> Result<&SkinGauss, FemError> {
        self.skin.iter().find(|s| s.cell == cell).ok_or_else(|| {
            FemError::Model(format!(
                "cell {} carries a load but is not a skin cell of the problem",
                self.p.mesh.cell_name(cell)
            ))
        })
    }

    /// The Jacobian c_k (K(T) + H) + c_m M(T) on the full pattern.
    fn jacobian(
        &self,
        t: &[f64],
        loads: &[(CellId, SkinLoad)],
        c_k: f64,
        c_m: f64,
    ) -> Result<linalg::Csc, FemError> {
        let mut j = self.pattern.clone();
        j.values.iter_mut().for_each(|v| *v = 0.0);
        for c in &self.cells {
            let m = &self.p.materials[c.mat];
            for (nv, dn, w) in &c.points {
                let (tg, grad) = at_point(&c.dofs, nv, dn, self.dim, t);
                let (lambda, dlambda) = m.lambda.value(tg)?;
                let (_, dbeta) = m.beta.value(tg)?;
                for (a, &i) in c.dofs.iter().enumerate() {
                    let gi: f64 = (0..self.dim).map(|d| grad[d] * dn[a][d]).sum();
                    for (b, &k) in c.dofs.iter().enumerate() {
                        let gg: f64 = (0..self.dim).map(|d| dn[a][d] * dn[b][d]).sum();
                        let v = c_k * w * (lambda * gg + dlambda * gi * nv[b])
                            + c_m * w * dbeta * nv[a] * nv[b];
                        j.add(i, k, v);
                    }
                }
            }
        }
        for (cell, load) in loads {
            if let SkinLoad::Exchange { h, .. } = *load {
                let s = self.skin_of(*cell)?;
                for (nv, w) in &s.points {
                    for (a, &i) in s.dofs.iter().enumerate() {
                        for (b, &k) in s.dofs.iter().enumerate() {
                            j.add(i, k, c_k * w * h * nv[a] * nv[b]);
                        }
                    }
                }
            }
        }
        Ok(j)
    }

    /// Solves J ΔT = r with ΔT given on the imposed unknowns (`d_imposed`,
    /// over all unknowns, 0 on the free ones); returns ΔT and the
    /// multipliers' increment r − J ΔT on the imposed rows.
    fn solve(
        &self,
        j: &linalg::Csc,
        r: &[f64],
        d_imposed: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>), FemError> {
        let lift = j.mul(d_imposed);
        let mut cols: Vec<Vec<u32>> = vec![Vec::new(); self.n_free];
        for c in 0..self.n {
            let fc = self.free_of[c];
            if fc == usize::MAX {
                continue;
            }
            for p in j.col_ptr[c]..j.col_ptr[c + 1] {
                let fr = self.free_of[j.row_idx[p]];
                if fr != usize::MAX {
                    cols[fc].push(fr as u32);
                }
            }
        }
        let mut a = linalg::Csc::from_columns(self.n_free, cols);
        for c in 0..self.n {
            let fc = self.free_of[c];
            if fc == usize::MAX {
                continue;
            }
            for p in j.col_ptr[c]..j.col_ptr[c + 1] {
                let fr = self.free_of[j.row_idx[p]];
                if fr != usize::MAX {
                    a.add(fr, fc, j.values[p]);
                }
            }
        }
        let b: Vec<f64> = (0..self.n)
            .filter(|&u| self.free_of[u] != usize::MAX)
            .map(|u| r[u] - lift[u])
            .collect();
        let x = if self.n_free == 0 {
            Vec::new()
        } else {
            linalg::solve(&a, &b, self.n_free, false)
                .map_err(|f| {
                    linalg::failure_to_error(f, |i| {
                        let u = (0..self.n).find(|&u| self.free_of[u] == i);
                        let node = u.and_then(|u| self.unknown_of.iter().position(|&v| v == u));
                        node.map_or_else(
                            || format!("#{i}"),
                            |nd| format!("{} TEMP", self.p.mesh.node_name(NodeId(nd as u32))),
                        )
                    })
                })?
                .x
        };
        let dt: Vec<f64> = (0..self.n)
            .map(|u| match self.free_of[u] {
                usize::MAX => d_imposed[u],
                f => x[f],
            })
            .collect();
        let jd = j.mul(&dt);
        let mut dl = vec![0.0; self.n];
        for &u in &self.imposed {
            dl[u] = r[u] - jd[u];
        }
        Ok((dt, dl))
    }

    fn to_nodes(&self, t: &[f64]) -> Vec<f64> {
        self.unknown_of
            .iter()
            .map(|&u| if u == usize::MAX { f64::NAN } else { t[u] })
            .collect()
    }
}

/// What the previous converged state contributes to a transient step.
struct Previous {
    r: Vec<f64>,
    b: Vec<f64>,
    f: Vec<f64>,
}

/// One instant's solve: transient (`Some((θ, Δt, previous))`) or
/// stationary (`None`).
struct StepData<'a> {
    t: f64,
    transient: Option<(f64, f64, &'a Previous)>,
    loads: Vec<(CellId, SkinLoad)>,
    imposed: Vec<f64>,
}

/// The Newton loop of one instant (code_aster's `NewtonSolver.solve`),
/// from `temp` and the multipliers `lag`; `kept` the Jacobian carried from
/// the previous step (`None`: computed at iteration 0). Returns the last
/// Jacobian and the converged state's (Rλ, B, F).
fn newton(
    m: &Model,
    s: &NlSettings,
    step: &StepData,
    temp: &mut [f64],
    lag: &mut [f64],
    mut kept: Option<linalg::Csc>,
) -> Result<(Option<linalg::Csc>, Previous), FemError> {
    let mut k = 0usize;
    loop {
        if k > 0 && s.reac_iter > 0 && k.is_multiple_of(s.reac_iter) {
            kept = None;
        }
        let j = match kept.take() {
            Some(j) => j,
            None => match step.transient {
                Some((theta, dt, _)) => m.jacobian(temp, &step.loads, theta, 1.0 / dt)?,
                None => m.jacobian(temp, &step.loads, 1.0, 0.0)?,
            },
        };
        let (r, b) = m.internal(temp)?;
        let f = m.external(&step.loads, temp)?;
        // resi = F_ext − (R_int + L), and the scaling's terms.
        let (resi, f_ext) = match step.transient {
            Some((theta, dt, prev)) => {
                let fe: Vec<f64> = (0..m.n)
                    .map(|i| theta * f[i] + (1.0 - theta) * prev.f[i])
                    .collect();
                let resi: Vec<f64> = (0..m.n)
                    .map(|i| {
                        let int = theta * r[i] + b[i] / dt
                            - (prev.b[i] / dt - (1.0 - theta) * prev.r[i])
                            + lag[i];
                        fe[i] - int
                    })
                    .collect();
                (resi, fe)
            }
            None => {
                let resi: Vec<f64> = (0..m.n).map(|i| f[i] - r[i] - lag[i]).collect();
                (resi, f.clone())
            }
        };
        let maxi = resi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let scaling = (0..m.n).fold(0.0f64, |a, i| {
            let mass = if step.transient.is_some() { b[i] } else { 0.0 };
            a.max((lag[i] + mass - f_ext[i]).abs())
        });
        let rela = if scaling == 0.0 { -1.0 } else { maxi / scaling };
        let converged = k >= 1
            && s.resi_glob_rela
                .is_none_or(|tol| (0.0..=tol).contains(&rela))
            && s.resi_glob_maxi.is_none_or(|tol| maxi <= tol);
        if converged {
            // NewtonSolver.solve ends with _resetMatrix at k + 1.
            let keep = !(s.reac_iter > 0 && (k + 1).is_multiple_of(s.reac_iter));
            return Ok((keep.then_some(j), Previous { r, b, f }));
        }
        if k >= s.iter_glob_maxi {
            return Err(FemError::NoConvergence {
                time: step.t,
                iterations: k,
                resi_rela: rela,
                resi_maxi: maxi,
                cycling: None,
            });
        }
        let mut d_imposed = vec![0.0; m.n];
        for (&u, &v) in m.imposed.iter().zip(&step.imposed) {
            d_imposed[u] = v - temp[u];
        }
        let (dt, dl) = m.solve(&j, &resi, &d_imposed)?;
        for i in 0..m.n {
            temp[i] += dt[i];
            lag[i] += dl[i];
        }
        kept = Some(j);
        k += 1;
    }
}

/// `THER_NON_LINE` (transient): the temperature per mesh node (NaN off
/// the model) at every instant of `s`, the first being the initial state.
pub fn ther_non_line(
    p: &NlProblem,
    loads: &dyn NlLoads,
    s: &NlSettings,
) -> Result<Vec<Vec<f64>>, FemError> {
    if !(s.theta > 0.0 && s.theta <= 1.0) {
        return Err(FemError::Model(format!(
            "THETA = {} must be in (0, 1]",
            s.theta
        )));
    }
    let Some(&t0) = s.instants.first() else {
        return Err(FemError::Model("no instant to compute".into()));
    };
    let m = model(p)?;
    let mut temp = vec![0.0; m.n];
    let mut lag = vec![0.0; m.n];
    fn data<'a>(
        m: &Model,
        loads: &dyn NlLoads,
        t: f64,
        transient: Option<(f64, f64, &'a Previous)>,
    ) -> Result<StepData<'a>, FemError> {
        let imposed = loads.imposed(t)?;
        if imposed.len() != m.imposed.len() {
            return Err(FemError::Model(format!(
                "{} imposed temperatures for {} nodes",
                imposed.len(),
                m.imposed.len()
            )));
        }
        Ok(StepData {
            t,
            transient,
            loads: loads.skin(t)?,
            imposed,
        })
    }
    // The initial stationary solve's Jacobian stays in its own step solver:
    // the first step starts without one (NonLinearOperator.run_).
    let mut kept = None;
    let mut prev = match &s.initial {
        NlInitial::Stationary => {
            let step = data(&m, loads, t0, None)?;
            newton(&m, s, &step, &mut temp, &mut lag, None)?.1
        }
        NlInitial::Field(t_init) => {
            for (node, &u) in m.unknown_of.iter().enumerate() {
                if u != usize::MAX {
                    let v = t_init.get(node).copied().unwrap_or(f64::NAN);
                    if !v.is_finite() {
                        return Err(FemError::Model(format!(
                            "the initial temperature has no value at node {}",
                            p.mesh.node_name(NodeId(node as u32))
                        )));
                    }
                    temp[u] = v;
                }
            }
            let (r, b) = m.internal(&temp)?;
            let f = m.external(&loads.skin(t0)?, &temp)?;
            Previous { r, b, f }
        }
    };
    let mut out = vec![m.to_nodes(&temp)];
    for (idx, w) in s.instants.windows(2).enumerate() {
        let dt = w[1] - w[0];
        if dt <= 0.0 || !dt.is_finite() {
            return Err(FemError::Model(format!(
                "the instants must increase: {} then {}",
                w[0], w[1]
            )));
        }
        // NonLinearOperator.run_: REAC_INCR = 0 keeps the Jacobian,
        // otherwise a new one every REAC_INCR steps.
        if s.reac_incr != 0 && (idx + 1).is_multiple_of(s.reac_incr) {
            kept = None;
        }
        let step = data(&m, loads, w[1], Some((s.theta, dt, &prev)))?;
        let (j, next) = newton(&m, s, &step, &mut temp, &mut lag, kept.take())?;
        kept = j;
        prev = next;
        out.push(m.to_nodes(&temp));
    }
    Ok(out)
}

/// The heat flux −λ(T) ∇T at the Gauss points of each cell (code_aster's
/// `FLUX_ELGA`, `te0069`… for THER_NL the flux of `RAPH_THER`), per cell
/// of `p.cells` in order, per point: [FLUX, FLUY, FLUZ] (the first `dim`).
pub fn flux_elga(p: &NlProblem, temp_nodes: &[f64]) -> Result<Vec<Vec<[f64; 3]>>, FemError> {
    let m = model(p)?;
    let mut t = vec![0.0; m.n];
    for (node, &u) in m.unknown_of.iter().enumerate() {
        if u != usize::MAX {
            t[u] = temp_nodes.get(node).copied().unwrap_or(f64::NAN);
        }
    }
    m.cells
        .iter()
        .map(|c| {
            let mat = &p.materials[c.mat];
            c.points
                .iter()
                .map(|(nv, dn, _)| {
                    let (tg, grad) = at_point(&c.dofs, nv, dn, m.dim, &t);
                    let (lambda, _) = mat.lambda.value(tg)?;
                    Ok([-lambda * grad[0], -lambda * grad[1], -lambda * grad[2]])
                })
                .collect()
        })
        .collect()
}

/// The fluxes of [`flux_elga`] extrapolated to the nodes of each cell
/// (`FLUX_ELNO`, `te0004`: the cell's Gauss-to-node matrix, as the other
/// `*_ELNO` fields, [`crate::post::extrapolation`]), in the cell's node
/// order.
pub fn flux_elno(p: &NlProblem, elga: &[Vec<[f64; 3]>]) -> Result<Vec<Vec<[f64; 3]>>, FemError> {
    p.cells
        .iter()
        .zip(elga)
        .map(|((cell, _), pts)| {
            let ty = p.mesh.cell(*cell).ty;
            let scheme = volume_scheme(ty).ok_or_else(|| {
                FemError::Model(format!(
                    "cell {} is a {ty:?}: no thermal element for it",
                    p.mesh.cell_name(*cell)
                ))
            })?;
            let e = crate::post::extrapolation(ty, &scheme);
            Ok((0..e.nrows())
                .map(|n| {
                    let mut v = [0.0; 3];
                    for (k, q) in pts.iter().enumerate() {
                        for c in 0..3 {
                            v[c] += e[(n, k)] * q[c];
                        }
                    }
                    v
                })
                .collect())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rcfode_prolongations() {
        let c = Curve::table(
            vec![0.0, 10.0],
            vec![1.0, 2.0],
            CurveEnd::Linear,
            CurveEnd::Linear,
        )
        .unwrap();
        assert_eq!(c.value(5.0).unwrap(), (1.5, 0.1));
        assert_eq!(c.value(-10.0).unwrap(), (0.0, 0.1));
        assert_eq!(c.value(20.0).unwrap(), (3.0, 0.1));
        // rcfode reads the right prolongation below the first abscissa.
        let q = Curve::table(
            vec![0.0, 10.0],
            vec![1.0, 2.0],
            CurveEnd::Linear,
            CurveEnd::Constant,
        )
        .unwrap();
        assert_eq!(q.value(-10.0).unwrap(), (1.0, 0.0));
        let e = Curve::table(
            vec![0.0, 10.0],
            vec![1.0, 2.0],
            CurveEnd::Excluded,
            CurveEnd::Excluded,
        )
        .unwrap();
        assert!(e.value(11.0).is_err() && e.value(-1.0).is_err());
        let u = Curve::table(
            vec![0.0, 10.0],
            vec![1.0, 2.0],
            CurveEnd::Constant,
            CurveEnd::Linear,
        )
        .unwrap();
        assert!(u.value(-1.0).is_err());
    }

    #[test]
    fn enthalpy_is_the_trapezoidal_integral() {
        let b = Curve::enthalpy_of(&Curve::Constant(2.0));
        let (v, d) = b.value(100.0).unwrap();
        assert!((v - 2.0 * 373.15).abs() < 1e-9 && d == 2.0);
        let rho = Curve::table(
            vec![0.0, 100.0, 200.0],
            vec![1.0, 3.0, 3.0],
            CurveEnd::Constant,
            CurveEnd::Constant,
        )
        .unwrap();
        let b = Curve::enthalpy_of(&rho);
        let b0 = 0.5 * 4.0 * 273.15;
        assert!((b.value(0.0).unwrap().0 - b0).abs() < 1e-9);
        assert!((b.value(100.0).unwrap().0 - (b0 + 200.0)).abs() < 1e-9);
        // Linear between the points (not the quadratic integral), and
        // prolonged linearly on the right since ρCp was constant there.
        assert!((b.value(50.0).unwrap().0 - (b0 + 100.0)).abs() < 1e-9);
        assert!((b.value(300.0).unwrap().0 - (b0 + 200.0 + 300.0 + 300.0)).abs() < 1e-9);
    }
}
