//! code_aster's mixed incompressible elements of `MODELISATION='D_PLAN_INCO_UPG'`,
//! `'AXIS_INCO_UPG'` and `'3D_INCO_UPG'` in small strains (`te0590` → `nifipd`,
//! unknowns numbered by `niinit`): three fields, the displacement u
//! (quadratic, every node), the pressure p (`PRES`) and the swelling g
//! (`GONF`), both linear, at the vertices (code_aster's `MIPLTR6`/`MIPLQU8`,
//! `MIAXTR6`/`MIAXQU8`, `MINC_TETRA10`/`MINC_PENTA15`/`MINC_HEXA20`).
//!
//! At each Gauss point the behaviour receives the strain of u whose
//! volumetric part is replaced by g/3:
//! ε̃ = ε(u) − (tr ε(u) − g)/3 · 1, and returns σ(ε̃) with its tangent C
//! (the behaviours of [`crate::behaviour`], unchanged). The element's
//! stress is Σ = dev σ + p·1 and its residuals are
//!
//! - on u: ∫ B(δu) : Σ,
//! - on g: ∫ δg (tr σ/3 − p),
//! - on p: ∫ δp (div u − g),
//!
//! so p is the mean stress (positive in tension, code_aster's sign) and g
//! the volume change, both weakly. The tangent (`nifipd`'s `dddev`,
//! `devdi`, `iddev`, `iddid`) is K_uu = Bᵀ P C P B, K_ug = Bᵀ P C 1 Ng/3,
//! K_up = tr B Np, K_gg = Ng (1ᵀC1)/9 Ng, K_gp = −Ng Np, K_pp = 0, with P
//! the deviatoric projector: symmetric for a symmetric C, but indefinite
//! (the linear solve falls back to LU, [`crate::linalg`]).
//!
//! SIEF_ELGA holds Σ (SIXX … SIYZ) and `SIP` = tr σ/3 − p (code_aster's
//! `ECONTPG`), which vanishes at convergence in the weak sense only.
//!
//! Gauss families (the catalogue's RIGI): TRIA6 FPG3 (plane and AXIS),
//! QUAD8 FPG9 in D_PLAN but FPG4 in AXIS, HEXA20 FPG8, PENTA15 FPG21,
//! TETRA10 FPG4; p and g use the vertex element (TRIA3, QUAD4, HEXA8,
//! PENTA6, TETRA4) on the same points.

use crate::dof::Comp;
use crate::element::{element_dofs, model_gauss, GaussData};
use crate::material::{Elastic, Hypothesis};
use crate::model::Model;
use crate::shape::{self, GaussPoint};
use aster_mesh::{CellId, CellType};
use nalgebra::DMatrix;

/// The error for what is not computed on the mixed cell `cell` (`what`:
/// `FORC_NODA`, an energy…).
pub fn refused(model: &Model, cell: CellId, what: &str) -> crate::error::FemError {
    crate::error::FemError::Model(format!(
        "{what} on cell {}, a mixed incompressible element (_INCO_UPG), is not implemented",
        model.cell_name(cell)
    ))
}

/// An error when the model has mixed cells (what `what` does not
/// compute on them).
pub fn refuse_mixed(model: &Model, what: &str) -> Result<(), crate::error::FemError> {
    match model.elements().iter().find(|e| model.is_mixed(e.cell)) {
        Some(e) => Err(refused(model, e.cell, what)),
        None => Ok(()),
    }
}

/// The stress component names of SIEF_ELGA on a mixed element.
pub fn stress_names(hyp: Hypothesis) -> Vec<&'static str> {
    let mut v = hyp.stress_names().to_vec();
    v.push("SIP");
    v
}

/// Whether code_aster has a `*_INCO_UPG` element for a cell type under a
/// hypothesis.
pub fn has_element(ty: CellType, hyp: Hypothesis) -> bool {
    match hyp {
        Hypothesis::PlaneStrain | Hypothesis::Axisymmetric => {
            matches!(ty, CellType::TRIA6 | CellType::QUAD8)
        }
        Hypothesis::Solid3D => {
            matches!(ty, CellType::HEXA20 | CellType::PENTA15 | CellType::TETRA10)
        }
        Hypothesis::PlaneStress => false,
    }
}

/// The vertex (linear) cell of the pressure and swelling fields.
pub fn vertex_type(ty: CellType) -> CellType {
    match ty {
        CellType::TRIA6 => CellType::TRIA3,
        CellType::QUAD8 => CellType::QUAD4,
        CellType::HEXA20 => CellType::HEXA8,
        CellType::PENTA15 => CellType::PENTA6,
        CellType::TETRA10 => CellType::TETRA4,
        other => other,
    }
}

/// The RIGI Gauss family of the mixed element on `ty`.
pub fn scheme(ty: CellType, hyp: Hypothesis) -> Vec<GaussPoint> {
    match ty {
        CellType::QUAD8 if hyp == Hypothesis::Axisymmetric => shape::rigi_scheme(CellType::QUAD4),
        CellType::HEXA20 => crate::fpg::hexa(2),
        CellType::TETRA10 => crate::fpg::tetra4(),
        CellType::PENTA15 => crate::fpg::penta21(),
        other => shape::rigi_scheme(other),
    }
}

/// One mixed cell: its Gauss data (displacement), the vertex shape values
/// at its points, and its unknowns: the displacements (node-major), then
/// PRES at each vertex, then GONF at each vertex.
pub struct MixedCell {
    pub hypothesis: Hypothesis,
    pub gauss: Vec<GaussData>,
    /// `vertex[g][s]`: the vertex shape function s at point g.
    pub vertex: Vec<Vec<f64>>,
    /// Displacement unknowns.
    pub nu: usize,
    /// Vertices.
    pub nv: usize,
    pub dofs: Vec<usize>,
}

/// The unknowns of a mixed cell: its displacements (node-major), then
/// PRES at each vertex, then GONF at each vertex (a vertex without them
/// is skipped: [`MixedCell::new`] reports it).
pub fn mixed_dofs(model: &Model, cell: CellId) -> Vec<usize> {
    let mut dofs = element_dofs(model, cell);
    let c = model.mesh().cell(cell);
    let nv = shape::corner_count(c.ty);
    for comp in [Comp::PRES, Comp::GONF] {
        for &n in &c.nodes[..nv] {
            if let Some(i) = model.dofs().index(crate::dof::Dof::new(n, comp)) {
                dofs.push(i);
            }
        }
    }
    dofs
}

/// A 6×6 material tangent (engineering shears), as the behaviours give it.
pub type Tangent = [[f64; 6]; 6];

impl MixedCell {
    /// The cell's data; errors describe the cell (`is degenerate…`).
    pub fn new(model: &Model, cell: CellId, hyp: Hypothesis) -> Result<MixedCell, String> {
        let gauss = model_gauss(model, cell, hyp)?;
        let ty = model.mesh().cell(cell).ty;
        let lin = vertex_type(ty);
        let vertex = model
            .stiffness_scheme(cell)
            .iter()
            .map(|gp| shape::shape(lin, gp.xi).n.to_vec())
            .collect();
        let nu = element_dofs(model, cell).len();
        let nv = shape::corner_count(ty);
        let dofs = mixed_dofs(model, cell);
        if dofs.len() != nu + 2 * nv {
            return Err("without the PRES and GONF unknowns at its vertices".into());
        }
        Ok(MixedCell {
            hypothesis: hyp,
            gauss,
            vertex,
            nu,
            nv,
            dofs,
        })
    }

    fn ncomp(&self) -> usize {
        self.hypothesis.ncomp()
    }

    /// ε(u) (engineering shears), tr ε(u), p and g at point `g` for the
    /// cell unknowns `ue`.
    fn fields_at(&self, g: usize, ue: &[f64]) -> ([f64; 6], f64, f64, f64) {
        let gp = &self.gauss[g];
        let mut eps = [0.0; 6];
        for (k, e) in eps.iter_mut().enumerate().take(self.ncomp()) {
            *e = (0..self.nu).map(|a| gp.b[(k, a)] * ue[a]).sum();
        }
        let tr = eps[0] + eps[1] + eps[2];
        let nv = self.vertex[g].as_slice();
        let p: f64 = (0..self.nv).map(|s| nv[s] * ue[self.nu + s]).sum();
        let gf: f64 = (0..self.nv)
            .map(|s| nv[s] * ue[self.nu + self.nv + s])
            .sum();
        (eps, tr, p, gf)
    }

    /// The strain given to the behaviour at point `g`: ε(u) with its
    /// volumetric part replaced by g/3 (`nifipd`'s `epsm + (gm − divum)/3`).
    pub fn strain(&self, g: usize, ue: &[f64]) -> [f64; 6] {
        let (mut eps, tr, _, gf) = self.fields_at(g, ue);
        for e in eps.iter_mut().take(3) {
            *e += (gf - tr) / 3.0;
        }
        eps
    }

    /// The element stress at point `g` from the behaviour's σ: Σ = dev σ
    /// + p·1 (the stress components) and SIP = tr σ/3 − p.
    pub fn stress(&self, g: usize, sigma: &[f64; 6], ue: &[f64]) -> ([f64; 6], f64) {
        let (_, _, p, _) = self.fields_at(g, ue);
        let tr = sigma[0] + sigma[1] + sigma[2];
        let mut s = *sigma;
        for v in s.iter_mut().take(3) {
            *v += p - tr / 3.0;
        }
        (s, tr / 3.0 - p)
    }

    /// Adds point `g`'s residual to `f` (one value per cell unknown) for
    /// the behaviour's stress `sigma`.
    pub fn add_forces(&self, g: usize, sigma: &[f64; 6], ue: &[f64], f: &mut [f64]) {
        let gp = &self.gauss[g];
        let (_, tr_eps, _, gf) = self.fields_at(g, ue);
        let (s, sip) = self.stress(g, sigma, ue);
        let n = self.ncomp();
        for (a, fa) in f.iter_mut().enumerate().take(self.nu) {
            *fa += gp.w * (0..n).map(|k| gp.b[(k, a)] * s[k]).sum::<f64>();
        }
        for r in 0..self.nv {
            let nr = self.vertex[g][r];
            f[self.nu + self.nv + r] += gp.w * nr * sip;
            f[self.nu + r] += gp.w * nr * (tr_eps - gf);
        }
    }

    /// Adds point `g`'s tangent to `k` (square, one row per cell unknown)
    /// for the material tangent `c`; `shear` multiplies the shear rows of
    /// the strain operator (1, or 2 for `RIGI_MECA`'s, see
    /// [`MixedCell::elastic_matrix`]).
    pub fn add_tangent(&self, g: usize, c: &Tangent, k: &mut DMatrix<f64>) {
        self.add_tangent_scaled(g, c, 1.0, k)
    }

    fn add_tangent_scaled(&self, g: usize, c: &Tangent, shear: f64, k: &mut DMatrix<f64>) {
        let gp = &self.gauss[g];
        let (n, nu, nv, w) = (self.ncomp(), self.nu, self.nv, gp.w);
        // P B (deviatoric part of the strain of each displacement unknown)
        // and tr B.
        let mut pb = DMatrix::zeros(n, nu);
        let mut trb = vec![0.0; nu];
        for a in 0..nu {
            let tr = gp.b[(0, a)] + gp.b[(1, a)] + gp.b[(2, a)];
            trb[a] = tr;
            for kk in 0..n {
                pb[(kk, a)] = if kk < 3 {
                    gp.b[(kk, a)] - tr / 3.0
                } else {
                    shear * gp.b[(kk, a)]
                };
            }
        }
        let cm = DMatrix::from_fn(n, n, |i, j| c[i][j]);
        // C·1 (columns 1–3 summed) and 1ᵀ·C (rows summed), 1ᵀC1.
        let c1: Vec<f64> = (0..n)
            .map(|i| cm[(i, 0)] + cm[(i, 1)] + cm[(i, 2)])
            .collect();
        let c1t: Vec<f64> = (0..n)
            .map(|j| cm[(0, j)] + cm[(1, j)] + cm[(2, j)])
            .collect();
        let c11 = c1[0] + c1[1] + c1[2];
        // P·C·1 and 1ᵀ·C·P.
        let mut pc1 = c1.clone();
        let t1 = c11 / 3.0;
        for v in pc1.iter_mut().take(3) {
            *v -= t1;
        }
        let mut c1p = c1t.clone();
        let t2 = (c1t[0] + c1t[1] + c1t[2]) / 3.0;
        for v in c1p.iter_mut().take(3) {
            *v -= t2;
        }
        let cpb = &cm * &pb;
        let kuu = pb.transpose() * cpb;
        for a in 0..nu {
            for b in 0..nu {
                k[(a, b)] += w * kuu[(a, b)];
            }
        }
        let (po, go) = (nu, nu + nv);
        let ng = &self.vertex[g];
        for a in 0..nu {
            let ug: f64 = (0..n).map(|kk| pb[(kk, a)] * pc1[kk]).sum::<f64>() / 3.0;
            let gu: f64 = (0..n).map(|kk| c1p[kk] * pb[(kk, a)]).sum::<f64>() / 3.0;
            for r in 0..nv {
                k[(a, go + r)] += w * ug * ng[r];
                k[(go + r, a)] += w * gu * ng[r];
                k[(a, po + r)] += w * trb[a] * ng[r];
                k[(po + r, a)] += w * trb[a] * ng[r];
            }
        }
        for r in 0..nv {
            for s in 0..nv {
                k[(go + r, go + s)] += w * ng[r] * ng[s] * c11 / 9.0;
                k[(go + r, po + s)] -= w * ng[r] * ng[s];
                k[(po + r, go + s)] -= w * ng[r] * ng[s];
            }
        }
    }

    /// The linear elastic matrix of the cell: the tangent of ELAS
    /// (`nifipd`), or with `rigi_meca` code_aster's `RIGI_MECA` (`te0592`
    /// → `nirmtd`, the matrix of MECA_STATIQUE). The latter scales the
    /// engineering shear strains of `bmatmc` (γ) by √2 where the Mandel
    /// form wants 1/√2, against Hooke's matrix turned to Mandel's (2μ):
    /// its shear terms of K_uu are 4 times the tangent's (on an isotropic
    /// material). Reproduced as code_aster computes it (zzzz504r's
    /// reference values hold only with it).
    pub fn elastic_matrix(&self, material: &Elastic, rigi_meca: bool) -> DMatrix<f64> {
        let c = tangent_of(&material.hooke(self.hypothesis));
        let nd = self.dofs.len();
        let mut k = DMatrix::zeros(nd, nd);
        let shear = if rigi_meca { 2.0 } else { 1.0 };
        for g in 0..self.gauss.len() {
            self.add_tangent_scaled(g, &c, shear, &mut k);
        }
        k
    }

    /// SIEF_ELGA of a linear elastic cell as code_aster's `SIEF_ELGA`
    /// option computes it (`te0097`, MECA_STATIQUE and CALC_CHAMP): σ = D
    /// ε(u) from the displacement alone (not the strain with the
    /// swelling's volume change that the behaviour sees in STAT_NON_LINE),
    /// then Σ = dev σ + p·1 and SIP = tr σ/3 − p.
    pub fn elastic_stress(&self, material: &Elastic, ue: &[f64]) -> Vec<Vec<f64>> {
        let c = tangent_of(&material.hooke(self.hypothesis));
        let n = self.ncomp();
        (0..self.gauss.len())
            .map(|g| {
                let (eps, _, _, _) = self.fields_at(g, ue);
                let mut sigma = [0.0; 6];
                for (i, s) in sigma.iter_mut().enumerate().take(n) {
                    *s = (0..n).map(|j| c[i][j] * eps[j]).sum();
                }
                let (s, sip) = self.stress(g, &sigma, ue);
                let mut v = s[..n].to_vec();
                v.push(sip);
                v
            })
            .collect()
    }
}

/// A Hooke matrix (n × n) as a 6×6 tangent.
fn tangent_of(d: &DMatrix<f64>) -> Tangent {
    let mut c = [[0.0; 6]; 6];
    for i in 0..d.nrows().min(6) {
        for j in 0..d.ncols().min(6) {
            c[i][j] = d[(i, j)];
        }
    }
    c
}
