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
//!   friction matrix (√k T)ᵀ(√k T) times the step's displacement).
//!
//! The answer is where code_aster's Newton stops, not the exact solution
//! of this law: code_aster's tangent is symmetric and misses the μ E_N
//! coupling of the sliding force with the normal one, so its Newton
//! converges linearly (a factor 0.5–0.75 per iteration on ssnv128) and
//! stops at RESI_GLOB_RELA with the friction still a few 1e-6 from its
//! limit. The converged solution is 1.6–3.4 % off code_aster's numbers on
//! ssnv128c: the iterates are reproduced instead, pass for pass
//! (`DiscreteFriction::frogdp`):
//!
//! - the prediction (`nmprta`) solves with the matrix without contact
//!   terms (`nmmatr` adds them in the correction phase only) and the
//!   forces of the last evaluation (`CNCTDF`) held fixed;
//! - each evaluation computes the forces and the next matrix at the
//!   iterate: E_N a aᵀ (`cfcpem`) + k TᵀT (`cffpm1`) − β² f fᵀ per sliding
//!   link (`cffpm2`), f the friction forces `AFMU` on the link's DOFs and
//!   β² = 1/(μλ|s|), times `COEF_MATR_FROT` while the previous
//!   RESI_GLOB_RELA is ≥ 1e-3 (infinite at the start of a step);
//! - the friction of a link is switched on one evaluation after it comes
//!   into contact, and off for every link at the start of a step
//!   (`MU(2·nbliai + i)`, `cfprep`, `cffpm2`);
//! - a geometric iteration (`cfconv` → `cfcgeo`) does not restart Newton:
//!   the next iteration solves with the current matrix and residual, then
//!   pairs on the geometry before that solve (`nmcofr` → `cfgeom`).
//!
//! The friction force has no memory across steps: it is E_T times the
//! step's slip, capped at μλ (`cfjein`: `JEUX(2:3)` is `APCOFR` applied to
//! the step's cumulated increment). So a node that sticks through a step
//! after a slipping one carries only the friction of that step's motion —
//! this is code_aster's law, not an elastoplastic regularisation.
//!
//! CONT_NOEU (`cfresu`): CONT is 1 for a link whose friction coefficient
//! is not √E_T (sliding) and 2 for a sticking one — code_aster's own
//! numbering for the discrete formulation, the reverse of the continuous
//! one; RTAX… holds the friction force of a status-1 node, RTGX… that of a
//! status-2 node.

use aster_fem::{
    Contribution, Dof, FemError, ForceSource, LoopVerdict, PenaltyAdaptation, PenaltyVerdict,
    State, Unknown,
};
use aster_mesh::{Mesh, NodeId};
use std::collections::HashMap;

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
    /// The master point it is paired with (`APPROJ`: CONT_NOEU's PROJ_X…).
    proj: [f64; 3],
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
    /// code_aster's `MU(2·nbliai + i)` per slave node: the friction of a
    /// link is switched on one evaluation after it comes into contact, and
    /// off for every link at the start of a step (`cfprep`, `cffpm2`).
    friction_on: HashMap<NodeId, bool>,
    /// RESI_GLOB_RELA of the previous iterate (`cffpm2` weights the
    /// sliding tangent by COEF_MATR_FROT while it is ≥ 1e-3); infinite at
    /// the start of a step (`nmnpas`: r8vide).
    resigr: f64,
    /// The next evaluation is the step's prediction (see `evaluate`).
    prediction: bool,
    /// The contact and friction forces of the last evaluation (code_aster's
    /// `CNCTDF`), which the prediction of the next step takes as given.
    last_forces: Vec<(usize, f64)>,
    /// The last evaluation, replayed once when a geometric iteration
    /// restarts Newton from the same iterate.
    replay: Option<Contribution>,
    /// Displacement at which to pair before the next evaluation (the
    /// geometry before the solve, as `cfgeom` in `nmcofr`).
    pending_pair: Option<Vec<f64>>,
    /// The link states of the last evaluation (CONT_NOEU of the converged
    /// state: code_aster's `cfresu` reads the coefficients of that pass).
    last_states: Vec<LinkState>,
    /// The contribution of the last evaluation.
    last_eval: Option<Contribution>,
}

impl DiscreteFriction {
    /// The source of a discrete definition with friction: every zone must
    /// be `ALGO_CONT='PENALISATION'` (code_aster's only discrete friction,
    /// `cfalgo`: `frogdp`).
    pub fn new(def: &ContactDefinition, mesh: &Mesh) -> Result<Self, ContactError> {
        Self::new_in(def, mesh, if mesh.dim >= 3 { 3 } else { 2 })
    }

    /// As [`DiscreteFriction::new`] in a problem of dimension `space_dim`
    /// (the model's: a plane model on a mesh with three coordinates is 2D).
    pub fn new_in(
        def: &ContactDefinition,
        mesh: &Mesh,
        space_dim: usize,
    ) -> Result<Self, ContactError> {
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
        let contacts = ZoneContact::build_all_in(def, mesh, space_dim)?;
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
            friction_on: HashMap::new(),
            resigr: f64::INFINITY,
            prediction: false,
            last_forces: Vec::new(),
            replay: None,
            pending_pair: None,
            last_states: Vec::new(),
            last_eval: None,
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

    /// CONT_NOEU of the initial state: code_aster creates the field with
    /// zeros (`nmetcc`, not read from an initial state: `l_read_init`
    /// false in `CreateInOutDS_M`) and only a resolution fills it
    /// (`cfresu`), so the initial state archived carries zeros on the
    /// slave nodes — JEU = 0 included.
    pub fn cont_noeu_initial(&self) -> ContNoeu {
        let mut nodes: Vec<NodeId> = self.links.iter().map(|l| l.node).collect();
        nodes.extend(self.unpaired.iter().map(|&(_, n)| n));
        nodes.sort_unstable();
        nodes.dedup();
        ContNoeu {
            values: vec![[0.0; 19]; nodes.len()],
            proj: vec![[0.0; 3]; nodes.len()],
            nodes,
        }
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
                    proj: p.master_x,
                });
            }
        }
        self.links = links;
        self.unpaired = unpaired;
        Ok(())
    }

    /// The state of a link at the displacement `u`, its friction switched
    /// on (`cffpfo` with `MU(2·nbliai + i)` ≠ 0).
    fn link_state(&self, l: &Link, u: &[f64]) -> LinkState {
        self.link_state_with(l, u, true)
    }

    fn link_state_with(&self, l: &Link, u: &[f64], friction_on: bool) -> LinkState {
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
        if threshold > 0.0 && friction_on {
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
        let mut out = ContNoeu::default();
        let mut put = |node: NodeId, v: [f64; 19], proj: [f64; 3]| match out
            .nodes
            .iter()
            .position(|n| *n == node)
        {
            Some(k) => {
                out.values[k] = v;
                out.proj[k] = proj;
            }
            None => {
                out.nodes.push(node);
                out.values.push(v);
                out.proj.push(proj);
            }
        };
        for &(_, n) in &self.unpaired {
            let mut v = [0.0; 19];
            v[0] = -1.0;
            put(n, v, [0.0; 3]);
        }
        for (li, l) in self.links.iter().enumerate() {
            let st = match self.last_states.get(li) {
                Some(st) if self.last_states.len() == self.links.len() => *st,
                _ => self.link_state(l, state.displacement),
            };
            let mut v = [0.0; 19];
            v[1] = st.gap;
            if st.gap < f64::EPSILON {
                // code_aster's `cfresu` reads the vector components from
                // Aᵀμ and the friction forces on the internal-force side
                // (`cfresa`, `cfresb`): against the forces on the slave.
                let (on_slave_n, on_slave_t) = self.slave_forces(l, &st);
                let rn = on_slave_n.map(|x| -x);
                let rt = on_slave_t.map(|x| -x);
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
            // cfresu: PROJ_X… of the links in contact, zero elsewhere.
            let proj = if st.gap < f64::EPSILON {
                l.proj
            } else {
                [0.0; 3]
            };
            put(l.node, v, proj);
        }
        out
    }

    /// One pass of code_aster's `frogdp` at the displacement `u`: the
    /// contact forces (`cfcpes`), the friction coefficients (`cffpfo`),
    /// the friction forces `AFMU` = Σ k TᵀT Δu (`cffpm1`), and the matrix
    /// `MACT + MAF1 − MAF2` (`cfcpem`, `cffpm1`, `cffpm2`), where MAF2
    /// subtracts, per sliding link, β² (AFMU on its DOFs)(…)ᵀ with
    /// β² = 1/(μλ|s|), times COEF_MATR_FROT while the previous
    /// RESI_GLOB_RELA is ≥ 1e-3. The friction flags then switch on the
    /// links in contact and off the others (`cffpm2`).
    fn frogdp(&mut self, u: &[f64]) -> Contribution {
        let mut c = Contribution::default();
        let states: Vec<LinkState> = self
            .links
            .iter()
            .map(|l| {
                let on = self.friction_on.get(&l.node).copied().unwrap_or(false);
                self.link_state_with(l, u, on)
            })
            .collect();
        // AFMU: the friction forces, on every DOF.
        let mut afmu: HashMap<usize, f64> = HashMap::new();
        for (l, st) in self.links.iter().zip(&states) {
            if st.k == 0.0 {
                continue;
            }
            for (k, t) in l.tangents.iter().enumerate() {
                for &(i, a) in t {
                    *afmu.entry(i).or_insert(0.0) += st.k * st.slip[k] * a;
                }
            }
        }
        let trace = std::env::var_os("ASTER_FRICTION_TRACE").is_some();
        for (l, st) in self.links.iter().zip(&states) {
            if trace {
                eprintln!("[discrete friction] node {:?} {:?}", l.node, st);
            }
            if st.gap >= f64::EPSILON {
                continue;
            }
            let z = &self.zones[l.zone];
            for &(i, a) in &l.row {
                c.forces.push((i, st.lambda * a));
                for &(j, b) in &l.row {
                    c.tangent
                        .push((Unknown::Dof(i), Unknown::Dof(j), z.e_n * a * b));
                }
            }
            for t in &l.tangents {
                for &(i, a) in t {
                    for &(j, b) in t {
                        c.tangent
                            .push((Unknown::Dof(i), Unknown::Dof(j), st.k * a * b));
                    }
                }
            }
            let lambdf = z.friction.coulomb * st.lambda.max(0.0);
            let on = self.friction_on.get(&l.node).copied().unwrap_or(false);
            if lambdf != 0.0 && on && st.glis > lambdf / z.friction.e_t {
                let mut beta2 = 1.0 / (lambdf * st.glis);
                if self.resigr >= 1e-3 {
                    beta2 *= z.friction.coef_matr_frot;
                }
                let mut dofs: Vec<usize> = l.row.iter().map(|&(i, _)| i).collect();
                dofs.sort_unstable();
                dofs.dedup();
                let v: Vec<(usize, f64)> = dofs
                    .iter()
                    .map(|&i| (i, afmu.get(&i).copied().unwrap_or(0.0)))
                    .collect();
                for &(i, a) in &v {
                    for &(j, b) in &v {
                        c.tangent
                            .push((Unknown::Dof(i), Unknown::Dof(j), -beta2 * a * b));
                    }
                }
            }
        }
        for (i, f) in afmu {
            c.forces.push((i, f));
        }
        // cffpm2: the flags of the next evaluation.
        for (l, st) in self.links.iter().zip(&states) {
            let z = &self.zones[l.zone];
            if st.gap < 0.0 {
                if z.friction.coulomb * st.lambda > 0.0 {
                    self.friction_on.insert(l.node, true);
                }
            } else {
                self.friction_on.insert(l.node, false);
            }
        }
        self.last_states = states;
        c
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
            // cfprep: the friction flags start off with each step's first
            // pairing (l_first_geom).
            self.friction_on.clear();
        }
        self.resigr = f64::INFINITY;
        self.prediction = true;
        self.replay = None;
        self.pending_pair = None;
        Ok(())
    }

    fn evaluate(&mut self, state: &State, _own: &[f64]) -> Result<Contribution, FemError> {
        // code_aster's prediction (`nmprta`): the matrix without the
        // contact and friction terms (`nmmatr` adds them in the correction
        // phase only) and the forces of the last evaluation (`CNCTDF`,
        // those of the previous step's converged state) held fixed.
        if self.prediction {
            self.prediction = false;
            return Ok(Contribution {
                forces: self.last_forces.clone(),
                ..Contribution::default()
            });
        }
        if let Some(c) = self.replay.take() {
            return Ok(c);
        }
        if let Some(u) = self.pending_pair.take() {
            let at = State {
                displacement: &u,
                ..*state
            };
            self.pair_all(&at).map_err(|e| self.err(e))?;
        }
        let c = self.frogdp(state.displacement);
        self.last_forces = c.forces.clone();
        self.last_eval = Some(c.clone());
        Ok(c)
    }

    fn observe_residual(&mut self, resi_glob_rela: f64) {
        self.resigr = resi_glob_rela;
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
                // code_aster's discrete geometric loop (`cfconv` →
                // `cfcgeo`) does not restart Newton: the next iteration
                // solves with the current matrix and residual, then pairs
                // on the geometry before that solve (`nmcofr` → `cfgeom`).
                self.replay = self.last_eval.clone();
                self.pending_pair = Some(state.displacement.to_vec());
                Ok(LoopVerdict::Again)
            }
            GeomDecision::Diverged { pairings, residual } => Err(FemError::Source(format!(
                "{}: the geometric loop (REAC_GEOM='AUTOMATIQUE') did not converge at time {}: after {pairings} pairings the displacement still changes by {residual:.3e} of the step's displacement (raise ITER_GEOM_MAXI or RESI_GEOM, or fix the number of updates with REAC_GEOM='CONTROLE')",
                self.describe(),
                state.time
            ))),
        }
    }

    fn again_continues_newton(&self) -> bool {
        true
    }

    /// code_aster's `nmevin` and `nmadcp`: the event fires when a link's
    /// final gap (`JEUITE(1)`) is a penetration beyond PENE_MAXI; every
    /// zone's E_N is then doubled, at most COEF_MAXI (reaching it fails
    /// the action). code_aster doubles a zone when the largest
    /// penetration recorded so far (`EVENPE`, never reset) exceeds
    /// PENE_MAXI, which the event itself guarantees with one zone; with
    /// several it reads that record of the last link's zone for all.
    fn adapt_penalty(
        &mut self,
        state: &State,
        adaptation: PenaltyAdaptation,
    ) -> Result<PenaltyVerdict, FemError> {
        let u = state.displacement;
        let penetration = self
            .links
            .iter()
            .map(|l| self.link_state(l, u).gap)
            .filter(|&g| g <= 0.0)
            .fold(0.0f64, |m, g| m.max(-g));
        if penetration <= adaptation.pene_maxi {
            return Ok(PenaltyVerdict::Accepted);
        }
        let mut capped = false;
        for z in &mut self.zones {
            let mut e_n = 2.0 * z.e_n;
            if e_n > adaptation.coef_maxi {
                e_n = adaptation.coef_maxi;
                capped = true;
            }
            z.e_n = e_n;
        }
        Ok(if capped {
            PenaltyVerdict::Capped { penetration }
        } else {
            PenaltyVerdict::Raised { penetration }
        })
    }

    fn converged(&mut self, state: &State, _own: &[f64]) -> Result<(), FemError> {
        let cn = self.cont_noeu(state);
        self.snapshots.push((state.time, cn));
        self.geom.step_converged(Self::nodal(state));
        self.first_increment = false;
        Ok(())
    }
}
