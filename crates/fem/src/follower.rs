//! Follower pressures (code_aster's `EXCIT=_F(TYPE_CHARGE='SUIV')` on a
//! `PRES_REP`): a pressure on a boundary face (3D) or edge (2D plane) of
//! continuum cells that acts on the *current* configuration x = X + u,
//! recomputed at every Newton iteration, with its derivative added to the
//! tangent (non-symmetric), as code_aster's options `CHAR_MECA_PRSU_R/F`
//! and `RIGI_MECA_PRSU_R/F` compute them (te0424 → `nmpr3d_vect`,
//! `nmpr3d_matr`; te0573 → `nmpr2d`).
//!
//! At each point of the boundary cell's stiffness scheme
//! ([`shape::skin_scheme`], code_aster's `RIGI` family of the skin
//! element), with a = ∂x/∂ξ, b = ∂x/∂η the tangents of the current
//! geometry, the external force on node i is
//!
//! ```text
//! 3D: Fᵢ = −Σ_g w_g p_g Nᵢ (a × b)        2D: Fᵢ = −Σ_g w_g p_g Nᵢ (a_y, −a_x)
//! ```
//!
//! (code_aster's `jac · cova(:,3)`), oriented outward from the volume the
//! face bounds as aster's dead pressure is ([`crate::loads`]). The
//! tangent is the exact derivative of F with p held fixed: code_aster's
//! `RIGI_MECA_PRSU` does not differentiate a pressure given as a function
//! of the current coordinates (`XF`, `YF`, `ZF`), and neither does this
//! module. The load does not depend on the kinematics of the cells
//! (`DEFORMATION='PETIT'` included): code_aster updates the geometry of
//! the follower load whatever the behaviour's kinematics.
//!
//! The loads enter the Newton loop as a [`ForceSource`] without unknowns
//! of its own ([`FollowerSource`]): the generalised Newton method of
//! [`crate::force_source`] factorises the non-symmetric tangent by sparse
//! LU.

use crate::error::FemError;
use crate::force_source::{Contribution, ForceSource, Unknown};
use crate::loads::Multiplier;
use crate::material::Hypothesis;
use crate::model::Model;
use crate::shape;
use crate::unilateral::State;
use aster_mesh::{CellId, Mesh, NodeId};
use std::fmt;
use std::rc::Rc;

/// A pressure's value at a point from its initial and current coordinates
/// (code_aster's `X`, `Y`, `Z` and `XF`, `YF`, `ZF`) and the time.
pub type PointPressure = dyn Fn([f64; 3], [f64; 3], f64) -> Result<f64, String>;

/// The value of a follower pressure before its time multiplier.
#[derive(Clone)]
pub enum FollowerValue {
    Constant(f64),
    /// A function of the point's initial and current coordinates and of
    /// the time.
    At(Rc<PointPressure>),
}

impl fmt::Debug for FollowerValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FollowerValue::Constant(p) => write!(f, "Constant({p})"),
            FollowerValue::At(_) => write!(f, "At(fn)"),
        }
    }
}

/// One follower pressure on a boundary cell.
#[derive(Clone, Debug)]
pub struct FollowerPressure {
    pub cell: CellId,
    pub value: FollowerValue,
    pub mult: Multiplier,
    /// −1 when the cell's own normal points into the volume it bounds.
    sign: f64,
}

/// The follower pressures of an analysis.
#[derive(Clone, Debug, Default)]
pub struct FollowerPressures {
    pub items: Vec<FollowerPressure>,
    /// 2 (plane) or 3.
    dim: usize,
}

impl FollowerPressures {
    /// The pressures `(cell, value, multiplier)` on boundary cells of the
    /// continuum elements of `model`; an error for an axisymmetric model
    /// (code_aster's extra hoop term of `nmpr2d` is not written) or a cell
    /// that is not a boundary segment (2D) or face (3D).
    pub fn new(
        model: &Model,
        items: Vec<(CellId, FollowerValue, Multiplier)>,
    ) -> Result<FollowerPressures, FemError> {
        if items.is_empty() {
            return Ok(FollowerPressures::default());
        }
        if model.hypothesis() == Some(Hypothesis::Axisymmetric) {
            return Err(FemError::Model(
                "a follower pressure on an axisymmetric model (the hoop term of code_aster's nmpr2d is not implemented)".into(),
            ));
        }
        let dim = model.dim();
        let mesh = model.mesh();
        let inner = crate::loads::inner_points(model);
        let mut out = Vec::with_capacity(items.len());
        for (cell, value, mult) in items {
            let c = mesh.cell(cell);
            if c.ty.dim() as usize + 1 != dim || shape::skin_scheme(c.ty).is_empty() {
                return Err(FemError::Model(format!(
                    "follower pressure on cell {} ({}): expected a boundary {} of the {dim}D model",
                    model.cell_name(cell),
                    c.ty.name(),
                    if dim == 2 { "segment" } else { "face" }
                )));
            }
            if c.nodes
                .iter()
                .any(|&n| model.dofs().node_first(n).is_none())
            {
                return Err(FemError::Model(format!(
                    "follower pressure on cell {}: a node carries no element of the model",
                    model.cell_name(cell)
                )));
            }
            let mut key: Vec<NodeId> = c
                .nodes
                .iter()
                .take(shape::corner_count(c.ty))
                .copied()
                .collect();
            key.sort();
            let flip = inner
                .get(&key)
                .is_some_and(|inside| crate::loads::points_inward(mesh, cell, *inside));
            out.push(FollowerPressure {
                cell,
                value,
                mult,
                sign: if flip { -1.0 } else { 1.0 },
            });
        }
        Ok(FollowerPressures { items: out, dim })
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// The external forces of the pressures at displacement `u` (indexed
    /// like the DOFs of `dofs`) and time `t`, and with `tangent` their
    /// derivatives (row, column, ∂F_row/∂u_col) in DOF indices.
    pub fn evaluate(
        &self,
        mesh: &Mesh,
        dofs: &crate::dof::DofNumbering,
        u: &[f64],
        t: f64,
        tangent: Option<&mut Vec<(usize, usize, f64)>>,
    ) -> Result<Vec<f64>, FemError> {
        let mut f = vec![0.0; u.len()];
        let mut tangent = tangent;
        let dim = self.dim;
        for item in &self.items {
            let m = item.mult.eval(t)?;
            if m == 0.0 {
                continue;
            }
            let c = mesh.cell(item.cell);
            let nn = c.nodes.len();
            let mut first = Vec::with_capacity(nn);
            let mut x0 = Vec::with_capacity(nn);
            let mut x = Vec::with_capacity(nn);
            for &n in &c.nodes {
                let i0 = dofs.node_first(n).ok_or_else(|| {
                    FemError::Model(format!("follower pressure: node {} has no DOF", n.0))
                })?;
                let p = mesh.coord(n);
                let mut cur = p;
                for k in 0..dim {
                    cur[k] += u[i0 + k];
                }
                first.push(i0);
                x0.push(p);
                x.push(cur);
            }
            for gp in shape::skin_scheme(c.ty) {
                let s = shape::shape(c.ty, gp.xi);
                let mut p0 = [0.0; 3];
                let mut pc = [0.0; 3];
                let mut a = [0.0; 3];
                let mut b = [0.0; 3];
                for i in 0..nn {
                    for k in 0..3 {
                        p0[k] += s.n[i] * x0[i][k];
                        pc[k] += s.n[i] * x[i][k];
                        a[k] += s.dn[i][0] * x[i][k];
                        b[k] += s.dn[i][1] * x[i][k];
                    }
                }
                let value = match &item.value {
                    FollowerValue::Constant(p) => *p,
                    FollowerValue::At(f) => f(p0, pc, t).map_err(|e| {
                        FemError::Model(format!(
                            "follower pressure on cell {} at ({}, {}, {}): {e}",
                            mesh.cell_name(item.cell),
                            pc[0],
                            pc[1],
                            pc[2]
                        ))
                    })?,
                };
                // The force per unit reference parameter: −c n, n = a × b
                // (3D) or (a_y, −a_x) (2D).
                let coef = gp.weight * value * m * item.sign;
                if coef == 0.0 {
                    continue;
                }
                let n = if dim == 2 {
                    [a[1], -a[0], 0.0]
                } else {
                    cross(a, b)
                };
                for i in 0..nn {
                    for k in 0..dim {
                        f[first[i] + k] -= coef * s.n[i] * n[k];
                    }
                }
                let Some(tg) = tangent.as_mut() else { continue };
                // ∂n/∂u_{j,l}: 2D, ∂a/∂u_{j,l} = N'_j e_l; 3D, N_{j,ξ} e_l × b
                // + N_{j,η} a × e_l.
                for j in 0..nn {
                    for l in 0..dim {
                        let dn = if dim == 2 {
                            let d = s.dn[j][0];
                            if l == 0 {
                                [0.0, -d, 0.0]
                            } else {
                                [d, 0.0, 0.0]
                            }
                        } else {
                            let mut e = [0.0; 3];
                            e[l] = 1.0;
                            let t1 = cross(e, b);
                            let t2 = cross(a, e);
                            [
                                s.dn[j][0] * t1[0] + s.dn[j][1] * t2[0],
                                s.dn[j][0] * t1[1] + s.dn[j][1] * t2[1],
                                s.dn[j][0] * t1[2] + s.dn[j][1] * t2[2],
                            ]
                        };
                        for i in 0..nn {
                            for k in 0..dim {
                                let v = -coef * s.n[i] * dn[k];
                                if v != 0.0 {
                                    tg.push((first[i] + k, first[j] + l, v));
                                }
                            }
                        }
                    }
                }
            }
        }
        Ok(f)
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The follower pressures as a force source of the Newton loop: forces
/// −F(u) on the internal-force side, tangent −∂F/∂u, no unknowns.
pub struct FollowerSource<'a> {
    pub loads: &'a FollowerPressures,
}

impl ForceSource for FollowerSource<'_> {
    fn name(&self) -> String {
        "a follower pressure (TYPE_CHARGE='SUIV')".into()
    }

    fn unknowns(&self) -> usize {
        0
    }

    fn begin_increment(&mut self, _state: &State, _own: &mut [f64]) -> Result<(), FemError> {
        Ok(())
    }

    fn evaluate(&mut self, state: &State, _own: &[f64]) -> Result<Contribution, FemError> {
        let mut tangent = Vec::new();
        let f = self.loads.evaluate(
            state.mesh,
            state.dofs,
            state.displacement,
            state.time,
            Some(&mut tangent),
        )?;
        Ok(Contribution {
            forces: f
                .iter()
                .enumerate()
                .filter(|(_, v)| **v != 0.0)
                .map(|(i, v)| (i, -v))
                .collect(),
            own_residual: Vec::new(),
            tangent: tangent
                .into_iter()
                .map(|(i, j, v)| (Unknown::Dof(i), Unknown::Dof(j), -v))
                .collect(),
        })
    }

    /// A trial of STAT_NON_LINE's line search: the follower forces stay
    /// those of the iteration's start `pairing`, as code_aster's `nmrelp`
    /// keeps `CNFEXT` (the follower loads of the iterate) and recomputes
    /// only the internal forces at each ρ (`nmrecz`).
    fn evaluate_on_pairing(
        &mut self,
        pairing: &State,
        _state: &State,
        own: &[f64],
    ) -> Result<Contribution, FemError> {
        self.evaluate(pairing, own)
    }

    fn after_iteration(&mut self, _state: &State, _own: &mut [f64]) -> Result<bool, FemError> {
        Ok(true)
    }

    fn converged(&mut self, _state: &State, _own: &[f64]) -> Result<(), FemError> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Elastic;
    use crate::model::{Element, ElementKind};
    use aster_mesh::CellType;

    /// A unit cube HEXA8 with its top face QUAD4, or a unit square QUAD4
    /// with its top edge SEG2; the boundary cell is ordered so that its
    /// own normal points into the volume (the orientation is corrected
    /// from the volume, as for the dead pressure).
    fn block(dim: usize) -> (Model, CellId) {
        use aster_mesh::Cell;
        type Cells = Vec<(CellType, Vec<u32>)>;
        let (coords, cells): (Vec<[f64; 3]>, Cells) = if dim == 3 {
            (
                vec![
                    [0., 0., 0.],
                    [1., 0., 0.],
                    [1., 1., 0.],
                    [0., 1., 0.],
                    [0., 0., 1.],
                    [1., 0., 1.],
                    [1., 1., 1.],
                    [0., 1., 1.],
                ],
                vec![
                    (CellType::HEXA8, vec![0, 1, 2, 3, 4, 5, 6, 7]),
                    (CellType::QUAD4, vec![4, 7, 6, 5]),
                ],
            )
        } else {
            (
                vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]],
                vec![
                    (CellType::QUAD4, vec![0, 1, 2, 3]),
                    (CellType::SEG2, vec![3, 2]),
                ],
            )
        };
        let mesh = Mesh {
            dim: dim as u8,
            node_names: (0..coords.len()).map(|i| format!("N{i}")).collect(),
            coords,
            cell_names: vec!["V".into(), "T".into()],
            cells: cells
                .into_iter()
                .map(|(ty, n)| Cell {
                    ty,
                    nodes: n.into_iter().map(NodeId).collect(),
                })
                .collect(),
            ..Mesh::default()
        };
        let hypothesis = if dim == 3 {
            Hypothesis::Solid3D
        } else {
            Hypothesis::PlaneStrain
        };
        let material = Elastic::new(1.0, 0.3).unwrap();
        let model = Model::new(
            std::sync::Arc::new(mesh),
            vec![Element {
                cell: CellId(0),
                kind: ElementKind::Continuum {
                    hypothesis,
                    material,
                },
            }],
        )
        .expect("model");
        (model, CellId(1))
    }

    fn perturbed(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| 0.1 * ((i as f64 * 1.7).sin() + 0.3 * (i as f64).cos()))
            .collect()
    }

    /// The tangent against central finite differences of the force, at a
    /// distorted configuration, in 2D and 3D.
    #[test]
    fn tangent_matches_finite_differences() {
        for dim in [2, 3] {
            let (model, top) = block(dim);
            let loads = FollowerPressures::new(
                &model,
                vec![(top, FollowerValue::Constant(2.5), Multiplier::constant(0.8))],
            )
            .expect("loads");
            let nd = model.dofs().len();
            let u = perturbed(nd);
            let mut tg = Vec::new();
            loads
                .evaluate(model.mesh(), model.dofs(), &u, 0.0, Some(&mut tg))
                .expect("evaluate");
            let mut k = vec![vec![0.0; nd]; nd];
            for (i, j, v) in tg {
                k[i][j] += v;
            }
            let h = 1e-6;
            let mut worst = 0.0f64;
            let mut scale = 0.0f64;
            for j in 0..nd {
                let mut up = u.clone();
                up[j] += h;
                let mut um = u.clone();
                um[j] -= h;
                let fp = loads
                    .evaluate(model.mesh(), model.dofs(), &up, 0.0, None)
                    .unwrap();
                let fm = loads
                    .evaluate(model.mesh(), model.dofs(), &um, 0.0, None)
                    .unwrap();
                for i in 0..nd {
                    let fd = (fp[i] - fm[i]) / (2.0 * h);
                    worst = worst.max((fd - k[i][j]).abs());
                    scale = scale.max(fd.abs());
                }
            }
            assert!(scale > 0.1, "{dim}D: a tangent that does not vanish");
            assert!(
                worst < 1e-8 * scale.max(1.0),
                "{dim}D: tangent off by {worst}"
            );
        }
    }

    /// Undeformed, the follower pressure is the dead one: total −p·A along
    /// the outward normal (+z / +y), whatever the face's own orientation.
    #[test]
    fn undeformed_equals_dead_pressure() {
        for dim in [2, 3] {
            let (model, top) = block(dim);
            let loads = FollowerPressures::new(
                &model,
                vec![(top, FollowerValue::Constant(3.0), Multiplier::one())],
            )
            .unwrap();
            let u = vec![0.0; model.dofs().len()];
            let f = loads
                .evaluate(model.mesh(), model.dofs(), &u, 0.0, None)
                .unwrap();
            let mut dead = crate::loads::Loads::new();
            dead.push(crate::loads::Load::Pressure {
                cell: top,
                pressure: 3.0,
            });
            let fd = dead.external_forces(&model, 0.0).unwrap();
            for (a, b) in f.iter().zip(&fd) {
                assert!((a - b).abs() < 1e-12, "{dim}D: {a} against dead {b}");
            }
            let total: f64 = (0..model.dofs().len())
                .filter(|&i| model.dofs().dof(i).comp == crate::dof::Comp::ALL[dim - 1])
                .map(|i| f[i])
                .sum();
            assert!((total + 3.0).abs() < 1e-12, "{dim}D: resultant {total}");
        }
    }

    /// A rigid rotation of the block by θ turns the follower force with it
    /// (a dead load would not turn), and stretches with the face.
    #[test]
    fn force_follows_a_rigid_rotation() {
        let (model, top) = block(2);
        let loads = FollowerPressures::new(
            &model,
            vec![(top, FollowerValue::Constant(1.0), Multiplier::one())],
        )
        .unwrap();
        let th = 0.4f64;
        let stretch = 1.5;
        let mesh = model.mesh();
        let mut u = vec![0.0; model.dofs().len()];
        for id in (0..mesh.coords.len() as u32).map(NodeId) {
            let p = mesh.coord(id);
            let first = model.dofs().node_first(id).unwrap();
            let (x, y) = (stretch * p[0], p[1]);
            u[first] = th.cos() * x - th.sin() * y - p[0];
            u[first + 1] = th.sin() * x + th.cos() * y - p[1];
        }
        let f = loads.evaluate(mesh, model.dofs(), &u, 0.0, None).unwrap();
        let (fx, fy) = (0..f.len()).fold((0.0, 0.0), |(a, b), i| {
            if model.dofs().dof(i).comp == crate::dof::Comp::DX {
                (a + f[i], b)
            } else {
                (a, b + f[i])
            }
        });
        // −p · length · the rotated outward normal (0, 1).
        assert!((fx - stretch * th.sin()).abs() < 1e-12, "{fx}");
        assert!((fy + stretch * th.cos()).abs() < 1e-12, "{fy}");
    }
}
