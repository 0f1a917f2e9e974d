//! Internal forces and tangent of a continuum cell under a finite-strain
//! kinematics (code_aster's `nmgr2d`/`nmgr3d` + `nmgrtg`, `nmdlog`,
//! `nmgpfi`, `nmpl2d`/`nmpl3d` with the reactualised geometry).
//!
//! Conventions: element DOFs are node-major (x, y[, z] per node); inside,
//! stresses and strains are in code_aster's Mandel notation (see
//! [`super::log`]), converted to the behaviours' convention (engineering
//! shear strains, tensor stresses) at the call.

use super::log::{from_mandel, mandel_factor, LogStrain, Mat6, PAIRS};
use super::Kinematics;
use crate::behaviour::simo_miehe::{self, SmState};
use crate::behaviour::vmis::{self, PointState, VonMises};
use crate::element::GaussData;
use crate::error::FemError;
use crate::material::{Elastic, Hypothesis};
use nalgebra::{DMatrix, Matrix2, Matrix3};

/// The state of a Gauss point of a cell with a behaviour.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GaussState {
    /// The behaviour's state; its stress is σ (PETIT, PETIT_REAC), the
    /// second Piola–Kirchhoff S (GREEN_LAGRANGE), the dual T of the log
    /// strain (GDEF_LOG) or the Kirchhoff τ (SIMO_MIEHE), tensor
    /// components.
    pub law: PointState,
    /// SIEF_ELGA: the Cauchy stress (tensor components).
    pub cauchy: [f64; 6],
    /// PETIT_REAC: the accumulated strain (engineering shears);
    /// SIMO_MIEHE: the elastic strain (I − bₑ)/2 (tensor components).
    pub extra: [f64; 6],
}

/// What is asked of a cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Phase {
    /// `FULL_MECA`: internal forces, states and tangent at the iterate.
    Correction,
    /// `RIGI_MECA_TANG` (`elastic`: `RIGI_MECA_ELAS`): the tangent at the
    /// converged state.
    Prediction { elastic: bool },
}

/// A Gauss point on the initial geometry: shape derivatives dN/dX, shape
/// values (AXIS), radius (AXIS) and weight × |det J₀| (× r₀ in AXIS).
pub(crate) struct PointGeom {
    dn: Vec<[f64; 3]>,
    n: Vec<f64>,
    r: f64,
    w0: f64,
}

/// The Gauss points of a cell, read from its small-strain data (the rows
/// of B are the shape derivatives, and N/r in AXIS).
pub(crate) fn point_geoms(gauss: &[GaussData], hyp: Hypothesis) -> Vec<PointGeom> {
    let dim = hyp.dim();
    gauss
        .iter()
        .map(|g| {
            let nn = g.b.ncols() / dim;
            let r = if hyp == Hypothesis::Axisymmetric {
                g.x[0]
            } else {
                0.0
            };
            let dn = (0..nn)
                .map(|a| {
                    let mut d = [0.0; 3];
                    for k in 0..dim {
                        d[k] = g.b[(k, dim * a + k)];
                    }
                    d
                })
                .collect();
            let n = (0..nn)
                .map(|a| {
                    if hyp == Hypothesis::Axisymmetric {
                        g.b[(2, dim * a)] * r
                    } else {
                        0.0
                    }
                })
                .collect();
            PointGeom { dn, n, r, w0: g.w }
        })
        .collect()
}

/// A cell's kinematics, law and Gauss points.
pub(crate) struct CellSetup<'a> {
    pub hyp: Hypothesis,
    pub elastic: &'a Elastic,
    /// `None`: `RELATION='ELAS'`.
    pub law: Option<&'a VonMises>,
    pub kinematics: Kinematics,
    pub geoms: &'a [PointGeom],
    /// The step's duration (the rate-dependent laws').
    pub dt: f64,
}

/// Internal forces (empty in prediction), tangent and new states of a cell.
pub(crate) struct CellResult {
    pub f: Vec<f64>,
    pub k: DMatrix<f64>,
    pub states: Vec<GaussState>,
}

/// H = ∇u at a point, the displacement gradient on the initial geometry
/// (AXIS: H₃₃ = u_r/r; D_PLAN and C_PLAN: H₃₃ = 0).
pub(crate) fn displacement_gradient(pg: &PointGeom, hyp: Hypothesis, ue: &[f64]) -> Matrix3<f64> {
    let dim = hyp.dim();
    let mut h = Matrix3::zeros();
    for (a, d) in pg.dn.iter().enumerate() {
        for i in 0..dim {
            for j in 0..dim {
                h[(i, j)] += d[j] * ue[dim * a + i];
            }
        }
    }
    if hyp == Hypothesis::Axisymmetric {
        let ur: f64 = pg.n.iter().enumerate().map(|(a, n)| n * ue[dim * a]).sum();
        h[(2, 2)] = ur / pg.r;
    }
    h
}

/// F = I + ∇ᵤ at a point (AXIS: F₃₃ = 1 + u_r/r).
pub(crate) fn gradient(pg: &PointGeom, hyp: Hypothesis, ue: &[f64]) -> Matrix3<f64> {
    let dim = hyp.dim();
    let mut f = Matrix3::identity();
    for (a, d) in pg.dn.iter().enumerate() {
        for i in 0..dim {
            for j in 0..dim {
                f[(i, j)] += d[j] * ue[dim * a + i];
            }
        }
    }
    if hyp == Hypothesis::Axisymmetric {
        let ur: f64 = pg.n.iter().enumerate().map(|(a, n)| n * ue[dim * a]).sum();
        f[(2, 2)] += ur / pg.r;
    }
    f
}

/// ΔF = I + ∂Δu/∂x₋ on the configuration of the converged step
/// (code_aster's `nmgpfi`: `nmepsi` of the increment on `geomPrev`), with
/// ∂N/∂x₋ = ∂N/∂X F₋⁻¹ (AXIS: ΔF₃₃ = 1 + Δu_r/r₋). From the increment,
/// not F(u) F₋⁻¹: a rigid translation then leaves ΔF = I to the round-off
/// of the increment, not of the total displacement.
fn increment_gradient(
    pg: &PointGeom,
    hyp: Hypothesis,
    u_prev: &[f64],
    u: &[f64],
    fm: &Matrix3<f64>,
    fm_inv: &Matrix3<f64>,
) -> Matrix3<f64> {
    let dim = hyp.dim();
    let du = |k: usize| u[k] - u_prev[k];
    let mut g = Matrix3::<f64>::zeros();
    for (a, d) in pg.dn.iter().enumerate() {
        for i in 0..dim {
            for k in 0..dim {
                g[(i, k)] += du(dim * a + i) * d[k];
            }
        }
    }
    let mut f = Matrix3::<f64>::identity();
    for i in 0..dim {
        for j in 0..dim {
            f[(i, j)] += (0..dim).map(|k| g[(i, k)] * fm_inv[(k, j)]).sum::<f64>();
        }
    }
    if hyp == Hypothesis::Axisymmetric {
        let dur: f64 = pg.n.iter().enumerate().map(|(a, n)| n * du(dim * a)).sum();
        f[(2, 2)] += dur / (pg.r * fm[(2, 2)]);
    }
    f
}

/// Hooke's matrix padded to 6×6 (engineering shears).
fn hooke6(el: &Elastic, hyp: Hypothesis) -> Mat6 {
    let d = el.hooke(hyp);
    let mut out = [[0.0; 6]; 6];
    for i in 0..d.nrows() {
        for j in 0..d.ncols() {
            out[i][j] = d[(i, j)];
        }
    }
    out
}

/// The small-strain behaviour on a strain measure `eps` (engineering
/// shears): the new state and the tangent (engineering convention).
pub(crate) fn behave(
    setup: &CellSetup,
    eps: &[f64; 6],
    prev: &PointState,
    phase: Phase,
) -> Result<(PointState, Mat6), FemError> {
    let hyp = setup.hyp;
    let n = hyp.ncomp();
    match (setup.law, phase) {
        (None, Phase::Prediction { .. }) => Ok((*prev, hooke6(setup.elastic, hyp))),
        (Some(law), Phase::Prediction { elastic: true }) => {
            Ok((*prev, hooke6(&law.elastic(setup.elastic), hyp)))
        }
        (None, Phase::Correction) => {
            let d = hooke6(setup.elastic, hyp);
            let mut state = *prev;
            for i in 0..6 {
                state.stress[i] = (0..n).map(|j| d[i][j] * eps[j]).sum();
            }
            if hyp == Hypothesis::PlaneStress {
                let nu = setup.elastic.nu;
                state.eps_zz = -nu / (1.0 - nu) * (eps[0] + eps[1]);
            }
            Ok((state, d))
        }
        (Some(law), Phase::Correction) => {
            vmis::integrate(law, setup.elastic, hyp, &eps[..n], prev, false, setup.dt)
        }
        (Some(law), Phase::Prediction { elastic: false }) => {
            vmis::integrate(law, setup.elastic, hyp, &eps[..n], prev, true, setup.dt)
        }
    }
}

/// Tensor stress → Mandel; engineering tangent → Mandel.
fn stress_to_mandel(s: &[f64; 6]) -> [f64; 6] {
    let mut m = [0.0; 6];
    for k in 0..6 {
        m[k] = s[k] * mandel_factor(k);
    }
    m
}

fn tangent_to_mandel(c: &Mat6) -> Mat6 {
    let mut m = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            m[i][j] = c[i][j] * mandel_factor(i) * mandel_factor(j);
        }
    }
    m
}

/// Cauchy stress F S Fᵀ / J (tensor components) of a Mandel PK2 stress.
fn pk2_to_cauchy(f: &Matrix3<f64>, s: &[f64; 6], j: f64) -> [f64; 6] {
    let sig = f * from_mandel(s) * f.transpose() / j;
    let mut out = [0.0; 6];
    for (k, &(a, b)) in PAIRS.iter().enumerate() {
        out[k] = sig[(a, b)];
    }
    out
}

fn det2(f: &Matrix3<f64>) -> f64 {
    f[(0, 0)] * f[(1, 1)] - f[(0, 1)] * f[(1, 0)]
}

/// Adds a total Lagrangian point (`nmgrtg`): ∫ def(F)ᵀ S, and
/// ∫ def(F)ᵀ D def(F) + geometric stiffness (S).
fn add_total_lagrangian(
    pg: &PointGeom,
    hyp: Hypothesis,
    f: &Matrix3<f64>,
    s: &[f64; 6],
    d: &Mat6,
    fe: Option<&mut [f64]>,
    ke: &mut DMatrix<f64>,
) {
    let dim = hyp.dim();
    let nn = pg.dn.len();
    let nc = hyp.ncomp();
    let r2 = std::f64::consts::FRAC_1_SQRT_2;
    // def[(a, i)][kl]: ∂E_kl (Mandel) / ∂u_{a,i}.
    let mut def = vec![[0.0; 6]; nn * dim];
    for a in 0..nn {
        let dn = pg.dn[a];
        for i in 0..dim {
            let v = &mut def[dim * a + i];
            v[0] = f[(i, 0)] * dn[0];
            v[1] = f[(i, 1)] * dn[1];
            v[3] = (f[(i, 0)] * dn[1] + f[(i, 1)] * dn[0]) * r2;
            if dim == 3 {
                v[2] = f[(i, 2)] * dn[2];
                v[4] = (f[(i, 0)] * dn[2] + f[(i, 2)] * dn[0]) * r2;
                v[5] = (f[(i, 1)] * dn[2] + f[(i, 2)] * dn[1]) * r2;
            } else if hyp == Hypothesis::Axisymmetric && i == 0 {
                v[2] = f[(2, 2)] * pg.n[a] / pg.r;
            }
        }
    }
    let w = pg.w0;
    if let Some(fe) = fe {
        for (p, v) in def.iter().enumerate() {
            fe[p] += w * (0..nc).map(|k| v[k] * s[k]).sum::<f64>();
        }
    }
    // The material part w·Bᵀ D B as one matrix product (faster than the
    // entry-by-entry sums on the 81 DOFs of a HEXA27): Bᵀ is nd × nc, D B
    // is nc × nd.
    let nd = nn * dim;
    let bt = DMatrix::from_fn(nd, nc, |p, k| def[p][k]);
    let db = DMatrix::from_fn(nc, nd, |k, q| (0..nc).map(|l| d[k][l] * def[q][l]).sum());
    ke.gemm(w, &bt, &db, 1.0);
    // The geometric part: (∇N_a · S ∇N_b) on each displacement component.
    for b in 0..nn {
        let db_ = pg.dn[b];
        for a in 0..nn {
            let da = pg.dn[a];
            let mut geo = da[0] * db_[0] * s[0]
                + da[1] * db_[1] * s[1]
                + (da[0] * db_[1] + da[1] * db_[0]) * r2 * s[3];
            if dim == 3 {
                geo += da[2] * db_[2] * s[2]
                    + (da[0] * db_[2] + da[2] * db_[0]) * r2 * s[4]
                    + (da[1] * db_[2] + da[2] * db_[1]) * r2 * s[5];
            }
            for i in 0..dim {
                let mut v = geo;
                if hyp == Hypothesis::Axisymmetric && i == 0 {
                    v += pg.n[a] * pg.n[b] / (pg.r * pg.r) * s[2];
                }
                ke[(dim * a + i, dim * b + i)] += w * v;
            }
        }
    }
}

/// The cell's forces, tangent and states for the converged displacement
/// `u_prev`, the iterate `u` (element DOFs) and the converged states.
/// Errors name the Gauss point (1-based) in their message.
pub(crate) fn compute(
    setup: &CellSetup,
    u_prev: &[f64],
    u: &[f64],
    prev: &[GaussState],
    phase: Phase,
) -> Result<CellResult, FemError> {
    let nd = u.len();
    let mut f = vec![0.0; nd];
    let mut k = DMatrix::zeros(nd, nd);
    let mut states = Vec::with_capacity(prev.len());
    for (g, (pg, st)) in setup.geoms.iter().zip(prev).enumerate() {
        let at = |e: FemError| match e {
            FemError::Integration(m) => {
                FemError::Integration(format!("Gauss point {}: {m}", g + 1))
            }
            FemError::Model(m) => FemError::Model(format!("Gauss point {}: {m}", g + 1)),
            other => other,
        };
        let new = match setup.kinematics {
            Kinematics::GreenLagrange | Kinematics::Logarithmic => {
                total_lagrangian(setup, pg, u_prev, u, st, phase, &mut f, &mut k).map_err(at)?
            }
            Kinematics::SimoMiehe => {
                simo_miehe_point(setup, pg, u_prev, u, st, phase, &mut f, &mut k).map_err(at)?
            }
            Kinematics::SmallUpdated => {
                updated_small(setup, pg, u_prev, u, st, phase, &mut f, &mut k).map_err(at)?
            }
            Kinematics::Small => {
                return Err(FemError::Model(
                    "small strains are not a finite-strain kinematics".into(),
                ))
            }
        };
        states.push(new);
    }
    Ok(CellResult { f, k, states })
}

/// GREEN_LAGRANGE and GDEF_LOG: total Lagrangian on S and ∂S/∂E.
#[allow(clippy::too_many_arguments)]
fn total_lagrangian(
    setup: &CellSetup,
    pg: &PointGeom,
    u_prev: &[f64],
    u: &[f64],
    prev: &GaussState,
    phase: Phase,
    fe: &mut [f64],
    ke: &mut DMatrix<f64>,
) -> Result<GaussState, FemError> {
    let hyp = setup.hyp;
    let correction = phase == Phase::Correction;
    let f = gradient(pg, hyp, if correction { u } else { u_prev });
    let mut state = *prev;
    let (s, d) = match setup.kinematics {
        Kinematics::GreenLagrange => {
            let e = to_engineering(&super::log::to_mandel(
                &(0.5 * (f.transpose() * f - Matrix3::identity())),
            ));
            let (law, c) = behave(setup, &e, &prev.law, phase)?;
            state.law = law;
            (stress_to_mandel(&law.stress), tangent_to_mandel(&c))
        }
        _ => {
            let log = LogStrain::new(&f, hyp.dim()).map_err(|c| {
                FemError::Integration(format!(
                    "the element is crushed (eigenvalue {:.3e} of FᵀF): no logarithmic strain",
                    c.smallest
                ))
            })?;
            let (law, c) = behave(setup, &to_engineering(&log.eps), &prev.law, phase)?;
            state.law = law;
            let t = stress_to_mandel(&law.stress);
            let p = log.p();
            let cm = tangent_to_mandel(&c);
            let mut s = [0.0; 6];
            for j in 0..6 {
                s[j] = (0..6).map(|i| t[i] * p[i][j]).sum();
            }
            // Pᵀ C P + T : ∂²ε/∂E².
            let mut d = log.t_l(&t);
            for a in 0..6 {
                for b in 0..6 {
                    let mut v = 0.0;
                    for i in 0..6 {
                        for j in 0..6 {
                            v += p[i][a] * cm[i][j] * p[j][b];
                        }
                    }
                    d[a][b] += v;
                }
            }
            (s, d)
        }
    };
    add_total_lagrangian(
        pg,
        hyp,
        &f,
        &s,
        &d,
        if correction { Some(fe) } else { None },
        ke,
    );
    if correction {
        let j = if setup.kinematics == Kinematics::Logarithmic && hyp == Hypothesis::PlaneStress {
            // code_aster's poslog: J = exp(tr εₑ) from the plane-stress
            // elastic strain of T (plastic flow is isochoric).
            let el = match setup.law {
                Some(law) => law.elastic(setup.elastic),
                None => *setup.elastic,
            };
            let t = &state.law.stress;
            ((1.0 - 2.0 * el.nu) / el.e * (t[0] + t[1])).exp()
        } else {
            f.determinant()
        };
        // code_aster's GREEN_LAGRANGE (nmgrla) never fails on det F: the
        // Saint-Venant–Kirchhoff energy is defined for any F, and pk2sig
        // divides by J whatever its sign. An iterate that goes through an
        // inverted element (a large prediction) carries on there as it
        // does; only J = 0 (no Cauchy stress) stops the integration.
        let tolerated = setup.kinematics == Kinematics::GreenLagrange && j != 0.0;
        if j.is_nan() || (j <= 0.0 && !tolerated) {
            return Err(FemError::Integration(format!(
                "the element is inverted (det F = {j:.3e})"
            )));
        }
        state.cauchy = pk2_to_cauchy(&f, &s, j);
    }
    Ok(state)
}

/// Mandel strain → engineering shears.
fn to_engineering(m: &[f64; 6]) -> [f64; 6] {
    let mut e = *m;
    for k in 3..6 {
        e[k] *= std::f64::consts::SQRT_2;
    }
    e
}

/// Shape derivatives on the configuration of gradient `f`: dN/dx = dN/dX F⁻¹.
fn spatial_derivatives(
    pg: &PointGeom,
    hyp: Hypothesis,
    f: &Matrix3<f64>,
) -> Result<Vec<[f64; 3]>, FemError> {
    let dim = hyp.dim();
    let inverted = |d: f64| {
        FemError::Integration(format!(
            "the element is inverted or crushed (det F = {d:.3e})"
        ))
    };
    let mut out = vec![[0.0; 3]; pg.dn.len()];
    if dim == 3 {
        let d = f.determinant();
        let inv = f
            .try_inverse()
            .filter(|_| d > 0.0)
            .ok_or_else(|| inverted(d))?;
        for (a, dn) in pg.dn.iter().enumerate() {
            for j in 0..3 {
                out[a][j] = (0..3).map(|k| dn[k] * inv[(k, j)]).sum();
            }
        }
    } else {
        let f2 = Matrix2::new(f[(0, 0)], f[(0, 1)], f[(1, 0)], f[(1, 1)]);
        let d = f2.determinant();
        let inv = f2
            .try_inverse()
            .filter(|_| d > 0.0)
            .ok_or_else(|| inverted(d))?;
        for (a, dn) in pg.dn.iter().enumerate() {
            for j in 0..2 {
                out[a][j] = (0..2).map(|k| dn[k] * inv[(k, j)]).sum();
            }
        }
    }
    Ok(out)
}

/// SIMO_MIEHE (`nmgpfi`): updated Lagrangian on the Kirchhoff stress.
#[allow(clippy::too_many_arguments)]
fn simo_miehe_point(
    setup: &CellSetup,
    pg: &PointGeom,
    u_prev: &[f64],
    u: &[f64],
    prev: &GaussState,
    phase: Phase,
    fe: &mut [f64],
    ke: &mut DMatrix<f64>,
) -> Result<GaussState, FemError> {
    let hyp = setup.hyp;
    let law = setup.law.ok_or_else(|| {
        FemError::Model("SIMO_MIEHE needs a plastic law (VMIS_ISOT_LINE/TRAC), not ELAS".into())
    })?;
    if hyp == Hypothesis::PlaneStress {
        return Err(FemError::Model(
            "SIMO_MIEHE is not available in plane stress (C_PLAN), as in code_aster".into(),
        ));
    }
    let correction = phase == Phase::Correction;
    let fm = gradient(pg, hyp, u_prev);
    let fm_inv = fm.try_inverse().ok_or_else(|| {
        FemError::Integration("the converged element is degenerate (det F = 0)".into())
    })?;
    let df = if correction {
        increment_gradient(pg, hyp, u_prev, u, &fm, &fm_inv)
    } else {
        Matrix3::identity()
    };
    let fp = df * fm;
    let dj = df.determinant();
    if correction && !(dj > 1e-2 && dj <= 1e2) {
        return Err(FemError::Integration(format!(
            "the volume change of the increment det ΔF = {dj:.3e} is out of [0.01, 100]"
        )));
    }
    let sm_prev = SmState {
        p: prev.law.p,
        plastic: prev.law.plastic,
        e: prev.extra,
    };
    let sm_phase = match phase {
        Phase::Correction => simo_miehe::Phase::Correction,
        Phase::Prediction { elastic } => simo_miehe::Phase::Prediction { elastic },
    };
    let out = simo_miehe::integrate(law, setup.elastic, &fm, &df, &sm_prev, sm_phase)?;
    let tau = if correction { out.tau } else { prev.law.stress };
    let dn = spatial_derivatives(pg, hyp, &fp)?;
    let axi = hyp == Hypothesis::Axisymmetric;
    let dim = hyp.dim();
    let ndu = if axi { 3 } else { dim };
    let r = if axi { pg.r * fp[(2, 2)] } else { 0.0 };
    // ∂N_a/∂x_j with code_aster's AXIS mapping (nmmalu): the hoop
    // direction pairs only with itself (N/r).
    let gr = |a: usize, i: usize, j: usize| -> f64 {
        if !axi || (i < 2 && j < 2) {
            dn[a][j]
        } else if i == 2 && j == 2 {
            pg.n[a] / r
        } else {
            0.0
        }
    };
    let dof = |a: usize, i: usize| dim * a + if i < dim { i } else { 0 };
    let t = |i: usize, j: usize| tau[super::log::MANDEL[i][j]];
    let w = pg.w0;
    let nn = pg.dn.len();
    // gr tabulated once per point (the tangent's inner loops read it
    // nn² · ndu⁴ times); the sums below keep their order, so the tangent
    // is bit for bit the same.
    let g_tab: Vec<[[f64; 3]; 3]> = (0..nn)
        .map(|a| {
            let mut m = [[0.0; 3]; 3];
            for (i, row) in m.iter_mut().enumerate().take(ndu) {
                for (j, v) in row.iter_mut().enumerate().take(ndu) {
                    *v = gr(a, i, j);
                }
            }
            m
        })
        .collect();
    if correction {
        for a in 0..nn {
            for i in 0..ndu {
                let v: f64 = (0..ndu).map(|j| t(i, j) * g_tab[a][i][j]).sum();
                fe[dof(a, i)] += w * v;
            }
        }
    }
    let mut t_tab = [[0.0; 3]; 3];
    for (i, row) in t_tab.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = t(i, j);
        }
    }
    for (a, ga) in g_tab.iter().enumerate() {
        for ia in 0..ndu {
            let row = dof(a, ia);
            for (b, gb) in g_tab.iter().enumerate() {
                for ib in 0..ndu {
                    let mut v = 0.0;
                    for ja in 0..ndu {
                        let g = ga[ia][ja];
                        if g == 0.0 {
                            continue;
                        }
                        let d = &out.dtau[super::log::MANDEL[ia][ja]][ib];
                        for jb in 0..ndu {
                            v += g * d[jb] * gb[ib][jb];
                        }
                    }
                    for jb in 0..ndu {
                        v -= ga[ia][ib] * gb[ib][jb] * t_tab[ia][jb];
                    }
                    ke[(row, dof(b, ib))] += w * v;
                }
            }
        }
    }
    let mut state = *prev;
    if correction {
        let j = fm.determinant() * dj; // jacoPrev·jacoIncr
        state.law.p = out.state.p;
        state.law.plastic = out.state.plastic;
        state.law.stress = out.tau;
        state.extra = out.state.e;
        for k in 0..6 {
            state.cauchy[k] = out.tau[k] / j;
        }
    }
    Ok(state)
}

/// PETIT_REAC (`nmpl2d`/`nmpl3d` on X + u): small strain increments and
/// B on the updated geometry, no geometric stiffness.
#[allow(clippy::too_many_arguments)]
fn updated_small(
    setup: &CellSetup,
    pg: &PointGeom,
    u_prev: &[f64],
    u: &[f64],
    prev: &GaussState,
    phase: Phase,
    fe: &mut [f64],
    ke: &mut DMatrix<f64>,
) -> Result<GaussState, FemError> {
    let hyp = setup.hyp;
    let dim = hyp.dim();
    let nc = hyp.ncomp();
    let correction = phase == Phase::Correction;
    let ucur = if correction { u } else { u_prev };
    let f = gradient(pg, hyp, ucur);
    let dn = spatial_derivatives(pg, hyp, &f)?;
    let axi = hyp == Hypothesis::Axisymmetric;
    let r = if axi { pg.r * f[(2, 2)] } else { 0.0 };
    if axi && (r.is_nan() || r <= 0.0) {
        return Err(FemError::Integration(format!(
            "a Gauss point reaches the axis (r = {r:.3e})"
        )));
    }
    let j = if dim == 3 {
        f.determinant()
    } else if axi {
        det2(&f) * f[(2, 2)]
    } else {
        det2(&f)
    };
    let w = pg.w0 * j;
    let nn = pg.dn.len();
    // B(x), engineering shears.
    let mut b = vec![[0.0; 6]; nn * dim];
    for a in 0..nn {
        let d = dn[a];
        if dim == 2 {
            b[2 * a][0] = d[0];
            b[2 * a + 1][1] = d[1];
            b[2 * a][3] = d[1];
            b[2 * a + 1][3] = d[0];
            if axi {
                b[2 * a][2] = pg.n[a] / r;
            }
        } else {
            b[3 * a][0] = d[0];
            b[3 * a + 1][1] = d[1];
            b[3 * a + 2][2] = d[2];
            b[3 * a][3] = d[1];
            b[3 * a + 1][3] = d[0];
            b[3 * a][4] = d[2];
            b[3 * a + 2][4] = d[0];
            b[3 * a + 1][5] = d[2];
            b[3 * a + 2][5] = d[1];
        }
    }
    let mut eps = prev.extra;
    if correction {
        for (p, bp) in b.iter().enumerate() {
            let du = u[p] - u_prev[p];
            for k in 0..nc {
                eps[k] += bp[k] * du;
            }
        }
    }
    let (law, c) = behave(setup, &eps, &prev.law, phase)?;
    let mut state = *prev;
    if correction {
        for (p, bp) in b.iter().enumerate() {
            fe[p] += w * (0..nc).map(|k| bp[k] * law.stress[k]).sum::<f64>();
        }
        state.law = law;
        state.extra = eps;
        state.cauchy = law.stress;
    }
    let cb: Vec<[f64; 6]> = b
        .iter()
        .map(|bq| {
            let mut o = [0.0; 6];
            for k in 0..nc {
                o[k] = (0..nc).map(|l| c[k][l] * bq[l]).sum();
            }
            o
        })
        .collect();
    for p in 0..b.len() {
        for q in 0..b.len() {
            ke[(p, q)] += w * (0..nc).map(|k| b[p][k] * cb[q][k]).sum::<f64>();
        }
    }
    Ok(state)
}

/// Forces Σ ∫ Bᵀ(x) σ dv of a cell on the geometry X + u (code_aster's
/// FORC_NODA for DEFORMATION ≠ PETIT), for its Cauchy stresses.
pub(crate) fn forces_on_deformed(
    geoms: &[PointGeom],
    hyp: Hypothesis,
    u: &[f64],
    stress: &[Vec<f64>],
) -> Result<Vec<f64>, FemError> {
    let dim = hyp.dim();
    let mut fe = vec![0.0; u.len()];
    for (pg, s) in geoms.iter().zip(stress) {
        let f = gradient(pg, hyp, u);
        let dn = spatial_derivatives(pg, hyp, &f)?;
        let axi = hyp == Hypothesis::Axisymmetric;
        let r = if axi { pg.r * f[(2, 2)] } else { 0.0 };
        let j = if dim == 3 {
            f.determinant()
        } else if axi {
            det2(&f) * f[(2, 2)]
        } else {
            det2(&f)
        };
        let w = pg.w0 * j;
        let sv = |k: usize| s.get(k).copied().unwrap_or(0.0);
        for (a, d) in dn.iter().enumerate() {
            if dim == 2 {
                fe[2 * a] += w * (d[0] * sv(0) + d[1] * sv(3));
                fe[2 * a + 1] += w * (d[1] * sv(1) + d[0] * sv(3));
                if axi {
                    fe[2 * a] += w * pg.n[a] / r * sv(2);
                }
            } else {
                fe[3 * a] += w * (d[0] * sv(0) + d[1] * sv(3) + d[2] * sv(4));
                fe[3 * a + 1] += w * (d[1] * sv(1) + d[0] * sv(3) + d[2] * sv(5));
                fe[3 * a + 2] += w * (d[2] * sv(2) + d[0] * sv(4) + d[1] * sv(5));
            }
        }
    }
    Ok(fe)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::behaviour::vmis::CurveEnd;
    use crate::shape;
    use aster_mesh::CellType;

    /// Gauss points of a distorted QUAD4 (2D) or HEXA8 (3D), computed from
    /// the reference shape functions.
    fn geoms(hyp: Hypothesis) -> Vec<PointGeom> {
        let (ty, nodes): (CellType, Vec<[f64; 3]>) = if hyp.dim() == 2 {
            (
                CellType::QUAD4,
                vec![
                    [1.0, 0.0, 0.0],
                    [2.1, 0.1, 0.0],
                    [2.0, 1.2, 0.0],
                    [0.9, 0.9, 0.0],
                ],
            )
        } else {
            let mut v = Vec::new();
            for z in [0.0, 1.1] {
                v.push([0.0, 0.0, z]);
                v.push([1.0, 0.1 * z, z]);
                v.push([1.1, 1.0, z + 0.1]);
                v.push([0.1, 0.9, z]);
            }
            (CellType::HEXA8, v)
        };
        let dim = hyp.dim();
        shape::rigi_scheme(ty)
            .iter()
            .map(|gp| {
                let s = shape::shape(ty, gp.xi);
                let mut j = nalgebra::DMatrix::<f64>::zeros(dim, dim);
                let mut x = [0.0; 3];
                for (a, p) in nodes.iter().enumerate() {
                    for r in 0..dim {
                        for c in 0..dim {
                            j[(r, c)] += s.dn[a][r] * p[c];
                        }
                        x[r] += s.n[a] * p[r];
                    }
                }
                let det = j.determinant();
                let inv = j.try_inverse().unwrap();
                let dn =
                    s.dn.iter()
                        .map(|d| {
                            let mut o = [0.0; 3];
                            for c in 0..dim {
                                o[c] = (0..dim).map(|r| inv[(c, r)] * d[r]).sum();
                            }
                            o
                        })
                        .collect();
                let axi = hyp == Hypothesis::Axisymmetric;
                PointGeom {
                    dn,
                    n: if axi {
                        s.n.clone()
                    } else {
                        vec![0.0; s.n.len()]
                    },
                    r: if axi { x[0] } else { 0.0 },
                    w0: gp.weight * det.abs() * if axi { x[0] } else { 1.0 },
                }
            })
            .collect()
    }

    fn disp(n: usize, scale: f64, seed: f64) -> Vec<f64> {
        (0..n)
            .map(|k| scale * ((k as f64 * 1.7 + seed).sin() + 0.3 * (k as f64 * 0.37).cos()))
            .collect()
    }

    /// The element tangent against centred finite differences of the
    /// internal forces, for every kinematics, hypothesis and law, from a
    /// converged state carrying stresses (and plastic strain).
    #[test]
    fn tangent_matches_finite_differences_of_the_forces() {
        let el = Elastic::new(1000.0, 0.3).unwrap();
        let linear = VonMises::linear(1000.0, 5.0, 100.0).unwrap();
        let curve =
            VonMises::traction_curve(&[0.005, 0.02, 0.1], &[5.0, 7.0, 9.0], CurveEnd::Linear)
                .unwrap();
        for kin in [
            Kinematics::GreenLagrange,
            Kinematics::Logarithmic,
            Kinematics::SimoMiehe,
            Kinematics::SmallUpdated,
        ] {
            for hyp in [
                Hypothesis::PlaneStrain,
                Hypothesis::Axisymmetric,
                Hypothesis::PlaneStress,
                Hypothesis::Solid3D,
            ] {
                for law in [None, Some(&linear), Some(&curve)] {
                    if kin == Kinematics::SimoMiehe
                        && (law.is_none() || hyp == Hypothesis::PlaneStress)
                    {
                        continue;
                    }
                    let g = geoms(hyp);
                    let setup = CellSetup {
                        hyp,
                        elastic: &el,
                        law,
                        kinematics: kin,
                        geoms: &g,
                        dt: 0.0,
                    };
                    let nd = g[0].dn.len() * hyp.dim();
                    // A converged first step, then the increment tested
                    // (PETIT_REAC: small, its matrix lacks the geometric
                    // terms, as code_aster's).
                    let small = kin == Kinematics::SmallUpdated;
                    let amp = if small { 1e-3 } else { 1.0 };
                    let u1 = disp(nd, 0.05 * amp, 0.0);
                    let zero = vec![0.0; nd];
                    let s0 = vec![GaussState::default(); g.len()];
                    let first = compute(&setup, &zero, &u1, &s0, Phase::Correction).unwrap();
                    let u2: Vec<f64> = u1
                        .iter()
                        .zip(disp(nd, 0.04 * amp, 1.0))
                        .map(|(a, b)| a + b)
                        .collect();
                    let at = compute(&setup, &u1, &u2, &first.states, Phase::Correction).unwrap();
                    let h = 1e-7 * amp;
                    let scale = at.k.amax();
                    for q in 0..nd {
                        let mut up = u2.clone();
                        let mut um = u2.clone();
                        up[q] += h;
                        um[q] -= h;
                        let fp = compute(&setup, &u1, &up, &first.states, Phase::Correction)
                            .unwrap()
                            .f;
                        let fm = compute(&setup, &u1, &um, &first.states, Phase::Correction)
                            .unwrap()
                            .f;
                        for p in 0..nd {
                            let fd = (fp[p] - fm[p]) / (2.0 * h);
                            let tol = if small { 2e-2 * scale } else { 2e-5 * scale };
                            assert!(
                                (fd - at.k[(p, q)]).abs() <= tol,
                                "{kin:?} {hyp:?} {}: K[{p}][{q}] = {} vs {fd}",
                                law.map(|_| "VMIS").unwrap_or("ELAS"),
                                at.k[(p, q)]
                            );
                        }
                    }
                }
            }
        }
    }
}
