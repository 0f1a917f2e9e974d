//! code_aster's discrete penalised friction (`FORMULATION='DISCRETE'`,
//! `ALGO_CONT='PENALISATION'`, `ALGO_FROT='PENALISATION'`: `frogdp` and
//! the routines it calls, `cfcpes`, `cffpfo`, `cffpm1`, `cffpm2`, `cfjein`,
//! `cfresu`), as a fem force source without own unknowns.
//!
//! Per paired slave node (a link, code_aster's `iliai`), on the pairing of
//! the zone (shared with the frictionless formulation: [`ZoneContact`]),
//! with the linearised gap g(u) = b − a·u of the contact row a·u ≤ b and
//! the tangents τ₁ (2D) or τ₁, τ₂ (3D) of the master normal:
//!
//! - contact when g < ε: normal force λ = −E_N g (`cfcpes`), on the
//!   internal-force side λ aᵀ, tangent E_N a aᵀ (`cfcpem`);
//! - slip of the step s = T (u − u₀), u₀ the converged state of the
//!   previous step, T the tangential rows (slave minus master along τₖ:
//!   code_aster's `APCOFR` applied to the cumulated increment, `cfjein`);
//!   re-pairing inside a step measures s again from u₀ with the new
//!   tangents (`JEUITE` 2:3 are zeroed at pairing, `cfaddm`);
//! - friction: k = E_T when |s| ≤ μλ/E_T (stick), k = μλ/|s| otherwise
//!   (slip, force exactly μλ), force k Tᵀ s (`cffpfo`, `cffpm1`: the
//!   friction matrix (√k T)ᵀ(√k T) times the step's displacement);
//! - tangent: E_N a aᵀ + k TᵀT, and when slipping the derivative of the
//!   sliding force μλ Tᵀŝ (ŝ = s/|s|): −k (Tᵀŝ)(Tᵀŝ)ᵀ + μ E_N (Tᵀŝ) aᵀ.
//!   code_aster (`cffpm2`) subtracts the first term weighted by
//!   `COEF_MATR_FROT` while RESI_GLOB_RELA ≥ 1e-3 and fully afterwards,
//!   and omits the second (its matrix stays symmetric; its cases allow up
//!   to 1500 Newton iterations). The tangent changes the iterates, not the
//!   converged state: the full derivative converges in a few iterations
//!   (fem's LU takes the unsymmetric matrix), and a node whose slip
//!   reverses between two iterates (the stick/slip boundary) takes the
//!   sticking tangent E_T TᵀT for that iteration. `COEF_MATR_FROT` is read
//!   and checked but does not change the answer.
//!
//! The friction force has no memory across steps: it is E_T times the
//! step's slip, capped at μλ. So a node that sticks through a step after a
//! slipping one carries only the friction of that step's motion — this is
//! code_aster's law, not an elastoplastic regularisation.
//!
//! code_aster switches a link's friction on one iteration after it comes
//! into contact (`MU(2·nbliai + i)`, set in `cffpm2`): the converged state
//! is the same, since an iteration with the friction missing does not
//! balance a frictional load.
//!
//! CONT_NOEU (`cfresu`): CONT is 1 for a link whose friction coefficient
//! is not √E_T (sliding) and 2 for a sticking one — code_aster's own
//! numbering for the discrete formulation, the reverse of the continuous
//! one; RTAX… holds the friction force of a status-1 node, RTGX… that of a
//! status-2 node.

use aster_fem::{Contribution, Dof, FemError, ForceSource, LoopVerdict, State, Unknown};
use aster_mesh::{Mesh, NodeId};

use super::continuous::tangents;
use super::DiscreteZoneFriction;
use crate::error::ContactError;
use crate::geomloop::{GeomDecision, GeomLoopState};
use crate::pairing::Pairing;
use crate::post::ContNoeu;
use crate::rows::contact_row;
use crate::source::{current_positions, ZoneContact};
use crate::zone::{ContactDefinition, DiscreteAlgo};

/// One zone: its pairing and its penalties.
#[derive(Clone, Debug)]
struct DZone {
    contact: ZoneContact,
    e_n: f64,
    friction: DiscreteZoneFriction,
}

/// A paired slave node (code_aster's link).
#[derive(Clone, Debug)]
struct Link {
    zone: usize,
    node: NodeId,
    /// Unit normal from the master towards the slave.
    normal: [f64; 3],
    /// The contact row a·u ≤ b on DOF indices.
    row: Vec<(usize, f64)>,
    rhs: f64,
    /// The tangential rows (one in 2D, two in 3D) on DOF indices.
    tangents: Vec<Vec<(usize, f64)>>,
    /// The slave node's translation DOFs (for its forces in CONT_NOEU).
    slave_dofs: [Option<usize>; 3],
}

/// The state of a link at an iterate.
#[derive(Clone, Copy, Debug, Default)]
struct LinkState {
    gap: f64,
    lambda: f64,
    slip: [f64; 2],
    glis: f64,
    /// Friction coefficient k (force per unit slip); 0 without friction.
    k: f64,
    stick: bool,
}

/// Friction CONT_NOEU snapshots, by step time.
type Snapshots = Vec<(f64, ContNoeu)>;

/// The discrete penalised contact with Coulomb friction of a
/// `DEFI_CONTACT`, as a fem force source (module docs).
#[derive(Clone, Debug)]
pub struct DiscreteFriction {
    zones: Vec<DZone>,
    links: Vec<Link>,
    /// Slave nodes that were not paired by the last pairing, per zone.
    unpaired: Vec<(usize, NodeId)>,
    dim: usize,
    geom: GeomLoopState,
    /// Displacement per DOF index at the start of the step.
    u_start: Vec<f64>,
    first_increment: bool,
    snapshots: Snapshots,
    /// Per link, the slip of the previous evaluation (a reversal between
    /// two iterates takes the sticking tangent: see `evaluate`).
    last_slip: Vec<Option<[f64; 2]>>,
}

impl DiscreteFriction {
    /// The source of a discrete definition with friction: every zone must
    /// be `ALGO_CONT='PENALISATION'` (code_aster's only discrete friction,
    /// `cfalgo`: `frogdp`).
    pub fn new(def: &ContactDefinition, mesh: &Mesh) -> Result<Self, ContactError> {
        let ContactDefinition::Discrete(d) = def else {
            return Err(ContactError::Unsupported {
                feature: "discrete friction on a continuous definition".into(),
                hint: "use friction::ContinuousFriction".into(),
            });
        };
        let Some(friction) = &d.friction else {
            return Err(ContactError::Invalid {
                keyword: "FROTTEMENT",
                message: "the definition has no friction".into(),
            });
        };
        friction.check(d.zones.len())?;
        let contacts = ZoneContact::build_all(def, mesh)?;
        let mut zones = Vec::new();
        for ((c, z), f) in contacts.into_iter().zip(&d.zones).zip(&friction.zones) {
            let DiscreteAlgo::Penalisation { e_n } = z.law else {
                return Err(ContactError::Unsupported {
                    feature: "discrete friction with ALGO_CONT other than 'PENALISATION'".into(),
                    hint: "code_aster's discrete friction is penalised (ALGO_CONT='PENALISATION', ALGO_FROT='PENALISATION')".into(),
                });
            };
            zones.push(DZone {
                contact: c,
                e_n,
                friction: *f,
            });
        }
        let dim = zones.first().map(|z| z.contact.zone.space_dim).unwrap_or(2);
        Ok(DiscreteFriction {
            zones,
            links: Vec::new(),
            unpaired: Vec::new(),
            dim,
            geom: GeomLoopState::new(def.geom_loop()),
            u_start: Vec::new(),
            first_increment: true,
            snapshots: Vec::new(),
            last_slip: Vec::new(),
        })
    }

    /// The contact zones (their pairing), e.g. for the QUAD8 middle-node
    /// relations.
    pub fn zones(&self) -> Vec<&ZoneContact> {
        self.zones.iter().map(|z| &z.contact).collect()
    }

    /// CONT_NOEU of the converged step at `time`.
    pub fn cont_noeu_at(&self, time: f64) -> Option<&ContNoeu> {
        self.snapshots
            .iter()
            .rev()
            .find(|(t, _)| (t - time).abs() <= 1e-12 * time.abs().max(1.0))
            .map(|(_, c)| c)
    }

    fn describe(&self) -> String {
        let groups: Vec<String> = self
            .zones
            .iter()
            .map(|z| {
                format!(
                    "{} on {}",
                    z.contact.zone.geometry.slave_group, z.contact.zone.geometry.master_group
                )
            })
            .collect();
        format!("discrete contact with friction ({})", groups.join(", "))
    }

    fn err(&self, e: ContactError) -> FemError {
        FemError::Source(format!("{}: {e}", self.describe()))
    }

    /// Pairs every zone on the current geometry and rebuilds the links.
    fn pair_all(&mut self, state: &State) -> Result<(), ContactError> {
        let x = current_positions(state);
        let mesh = state.mesh;
        let dim = self.dim;
        let index = |d: Dof| state.dofs.index(d);
        let mut links = Vec::new();
        let mut unpaired = Vec::new();
        for (zi, z) in self.zones.iter_mut().enumerate() {
            let rows = z.contact.pair(mesh, &x)?;
            let pairs = z.contact.pairs();
            for pair in pairs {
                if pair.pairing().is_none() {
                    if let Some(n) = pair.point.node() {
                        unpaired.push((zi, n));
                    }
                }
            }
            for row in rows {
                let Some(pair) = pairs.get(row.id) else {
                    continue;
                };
                let (Some(p), Some(node)) = (pair.pairing(), pair.point.node()) else {
                    continue;
                };
                let tau = tangents(dim, p.normal);
                let mut trows = Vec::new();
                for t in tau.iter().take(dim - 1) {
                    let tp = Pairing {
                        normal: *t,
                        ..p.clone()
                    };
                    let r = contact_row(mesh, &x, &pair.point.nodes, &tp, dim, 1.0, row.id);
                    trows.push(
                        r.terms
                            .iter()
                            .filter_map(|&(d, c)| index(d).map(|i| (i, c)))
                            .collect(),
                    );
                }
                let comps = aster_fem::Comp::translations(dim);
                let mut slave_dofs = [None; 3];
                for (c, comp) in comps.iter().enumerate() {
                    slave_dofs[c] = index(Dof::new(node, *comp));
                }
                links.push(Link {
                    zone: zi,
                    node,
                    normal: p.normal,
                    row: row
                        .terms
                        .iter()
                        .filter_map(|&(d, c)| index(d).map(|i| (i, c)))
                        .collect(),
                    rhs: row.rhs,
                    tangents: trows,
                    slave_dofs,
                });
            }
        }
        self.last_slip = vec![None; links.len()];
        self.links = links;
        self.unpaired = unpaired;
        Ok(())
    }

    /// The state of a link at the displacement `u`.
    fn link_state(&self, l: &Link, u: &[f64]) -> LinkState {
        let z = &self.zones[l.zone];
        let au: f64 = l.row.iter().map(|&(i, c)| c * u[i]).sum();
        let gap = l.rhs - au;
        let mut st = LinkState {
            gap,
            ..LinkState::default()
        };
        // code_aster: contact when the gap is below r8prem (cfcpes).
        if gap >= f64::EPSILON {
            return st;
        }
        st.lambda = -z.e_n * gap;
        for (k, t) in l.tangents.iter().enumerate() {
            st.slip[k] = t
                .iter()
                .map(|&(i, c)| c * (u[i] - self.u_start.get(i).copied().unwrap_or(0.0)))
                .sum();
        }
        st.glis = (st.slip[0] * st.slip[0] + st.slip[1] * st.slip[1]).sqrt();
        let f = &z.friction;
        let threshold = if st.lambda > 0.0 {
            f.coulomb * st.lambda
        } else {
            0.0
        };
        if threshold > 0.0 {
            if st.glis <= threshold / f.e_t {
                st.k = f.e_t;
                st.stick = true;
            } else {
                st.k = threshold / st.glis;
            }
        }
        st
    }

    /// The forces a link exerts on its slave node (on the slave's side:
    /// the master pushes it along +n), normal and friction parts.
    fn slave_forces(&self, l: &Link, st: &LinkState) -> ([f64; 3], [f64; 3]) {
        let mut rn = [0.0; 3];
        let mut rt = [0.0; 3];
        if st.gap >= f64::EPSILON {
            return (rn, rt);
        }
        for c in 0..3 {
            rn[c] = st.lambda * l.normal[c];
        }
        // The internal-force side carries k Tᵀ s; the force the master
        // exerts on the slave node is its opposite on the slave's DOFs.
        for (k, t) in l.tangents.iter().enumerate() {
            for (c, dof) in l.slave_dofs.iter().enumerate() {
                let Some(dof) = dof else { continue };
                let coef: f64 = t.iter().filter(|(i, _)| i == dof).map(|(_, v)| v).sum();
                rt[c] -= st.k * st.slip[k] * coef;
            }
        }
        (rn, rt)
    }

    fn cont_noeu(&self, state: &State) -> ContNoeu {
        let mut out = ContNoeu {
            nodes: Vec::new(),
            values: Vec::new(),
        };
        let mut put = |node: NodeId, v: [f64; 19]| match out.nodes.iter().position(|n| *n == node) {
            Some(k) => out.values[k] = v,
            None => {
                out.nodes.push(node);
                out.values.push(v);
            }
        };
        for &(_, n) in &self.unpaired {
            let mut v = [0.0; 19];
            v[0] = -1.0;
            put(n, v);
        }
        for l in &self.links {
            let st = self.link_state(l, state.displacement);
            let mut v = [0.0; 19];
            v[1] = st.gap;
            if st.gap < f64::EPSILON {
                let (rn, rt) = self.slave_forces(l, &st);
                v[2] = st.lambda.abs();
                v[3..6].copy_from_slice(&rn);
                // GLIX, GLIY: the step's slip along the tangents.
                v[6] = st.slip[0];
                v[7] = st.slip[1];
                v[8] = st.glis;
                let frictional = self.zones[l.zone].friction.e_t > 0.0;
                if frictional && !st.stick {
                    v[0] = 1.0;
                    v[9..12].copy_from_slice(&rt);
                } else {
                    v[0] = 2.0;
                    v[12..15].copy_from_slice(&rt);
                }
                for c in 0..3 {
                    v[15 + c] = rn[c] + rt[c];
                }
                v[18] = (v[15] * v[15] + v[16] * v[16] + v[17] * v[17]).sqrt();
            }
            put(l.node, v);
        }
        out
    }

    fn nodal(state: &State) -> Vec<[f64; 3]> {
        (0..state.mesh.coords.len())
            .map(|i| state.node_displacement(NodeId(i as u32)))
            .collect()
    }
}

impl ForceSource for DiscreteFriction {
    fn name(&self) -> String {
        self.describe()
    }

    fn unknowns(&self) -> usize {
        0
    }

    fn begin_increment(&mut self, state: &State, _own: &mut [f64]) -> Result<(), FemError> {
        self.u_start = state.displacement.to_vec();
        let pair = match self.geom.decide(state.time, &Self::nodal(state)) {
            GeomDecision::Pair => true,
            GeomDecision::Keep => self.first_increment,
            GeomDecision::Diverged { .. } => true,
        };
        if pair {
            self.pair_all(state).map_err(|e| self.err(e))?;
        }
        Ok(())
    }

    fn evaluate(&mut self, state: &State, _own: &[f64]) -> Result<Contribution, FemError> {
        let u = state.displacement;
        let mut c = Contribution::default();
        for (li, l) in self.links.iter().enumerate() {
            let st = self.link_state(l, u);
            // A node whose slip reversed since the previous iterate sits at
            // the stick/slip boundary: the sliding tangent (1 − c) μλ/|s|
            // sends it across by (1 + c)… times its slip, back and forth
            // (a corner of a pressed plate does so for ever with c = 0.5).
            // The sticking tangent E_T brings it back to the boundary. The
            // tangent only changes the iterates, not the converged state.
            let reversed = match self.last_slip.get(li).copied().flatten() {
                Some(p) => p[0] * st.slip[0] + p[1] * st.slip[1] < 0.0,
                None => false,
            };
            if let Some(ls) = self.last_slip.get_mut(li) {
                *ls = (st.glis > 0.0).then_some(st.slip);
            }
            if std::env::var_os("ASTER_FRICTION_TRACE").is_some() {
                eprintln!("[discrete friction] node {:?} {:?}", l.node, st);
            }
            if st.gap >= f64::EPSILON {
                continue;
            }
            let e_n = self.zones[l.zone].e_n;
            for &(i, a) in &l.row {
                c.forces.push((i, st.lambda * a));
                for &(j, b) in &l.row {
                    c.tangent
                        .push((Unknown::Dof(i), Unknown::Dof(j), e_n * a * b));
                }
            }
            if st.k == 0.0 {
                continue;
            }
            let e_t = self.zones[l.zone].friction.e_t;
            let kt = if reversed && !st.stick { e_t } else { st.k };
            for (k, t) in l.tangents.iter().enumerate() {
                for &(i, a) in t {
                    c.forces.push((i, st.k * st.slip[k] * a));
                    for &(j, b) in t {
                        c.tangent
                            .push((Unknown::Dof(i), Unknown::Dof(j), kt * a * b));
                    }
                }
            }
            // Near the stick/slip boundary (|s| < 2 μλ/E_T) the full
            // derivative sends the node back and forth across it: the
            // secant k TᵀT alone there.
            let deep = e_t > 2.0 * st.k;
            if !st.stick && !reversed && st.glis > 0.0 && deep {
                // The sliding force μλ Tᵀŝ: −k (Tᵀŝ)(Tᵀŝ)ᵀ (what code_aster's
                // `cffpm2` subtracts, weighted by COEF_MATR_FROT far from
                // convergence and fully near it) and its dependence on the
                // normal force, μ E_N (Tᵀŝ) aᵀ (code_aster omits it).
                let mut v: Vec<(usize, f64)> = Vec::new();
                for (k, t) in l.tangents.iter().enumerate() {
                    let sk = st.slip[k] / st.glis;
                    v.extend(t.iter().map(|&(i, a)| (i, a * sk)));
                }
                let mu = self.zones[l.zone].friction.coulomb;
                for &(i, a) in &v {
                    for &(j, b) in &v {
                        c.tangent
                            .push((Unknown::Dof(i), Unknown::Dof(j), -st.k * a * b));
                    }
                    for &(j, b) in &l.row {
                        c.tangent
                            .push((Unknown::Dof(i), Unknown::Dof(j), mu * e_n * a * b));
                    }
                }
            }
        }
        Ok(c)
    }

    fn after_iteration(&mut self, _state: &State, _own: &mut [f64]) -> Result<bool, FemError> {
        // Penalised contact and friction: no status to settle, the residual
        // decides (code_aster's `frogdp` reports no contact divergence).
        Ok(true)
    }

    fn after_convergence(&mut self, state: &State, _own: &[f64]) -> Result<LoopVerdict, FemError> {
        match self.geom.decide(state.time, &Self::nodal(state)) {
            GeomDecision::Keep => Ok(LoopVerdict::Done),
            GeomDecision::Pair => {
                self.pair_all(state).map_err(|e| self.err(e))?;
                Ok(LoopVerdict::Again)
            }
            GeomDecision::Diverged { pairings, residual } => Err(FemError::Source(format!(
                "{}: the geometric loop (REAC_GEOM='AUTOMATIQUE') did not converge at time {}: after {pairings} pairings the displacement still changes by {residual:.3e} of the step's displacement (raise ITER_GEOM_MAXI or RESI_GEOM, or fix the number of updates with REAC_GEOM='CONTROLE')",
                self.describe(),
                state.time
            ))),
        }
    }

    fn converged(&mut self, state: &State, _own: &[f64]) -> Result<(), FemError> {
        let cn = self.cont_noeu(state);
        self.snapshots.push((state.time, cn));
        self.geom.step_converged(Self::nodal(state));
        self.first_increment = false;
        Ok(())
    }
}
