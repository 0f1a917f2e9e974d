//! A contact zone as a producer of inequality rows for fem's solver
//! ([`UnilateralSource`]), with the state CONT_NOEU is built from.

use std::collections::BTreeMap;

use aster_fem::{
    AugmentedTerm, Dof, FemError, GeometryUpdate, InequalityRow, OuterLoops, RowOutcome, State,
    UnilateralMethod, UnilateralSource,
};
use aster_mesh::{CellId, LacZonePatches, Mesh, NodeId};

use crate::error::ContactError;
use crate::geomloop::{GeomDecision, GeomLoopState};
use crate::glissiere::Glissiere;
use crate::integration::{integration_points_measured, Measure};
use crate::lac::{LacOptions, LacZone};
use crate::pairing::{nodal_points, pair_point, ContactPair, PairStatus, SlavePoint};
use crate::post::interpenetrates;
use crate::rows::contact_row;
use crate::surface::ResolvedZone;
use crate::zone::{
    ContactDefinition, ContinueAlgo, ContinueLaw, DiscreteAlgo, GeomLoop, Resolution,
};

/// The law a zone enforces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ZoneLaw {
    Discrete(DiscreteAlgo),
    Continue(ContinueLaw),
}

/// Per paired point: the row it produced and the row scale (the nodal
/// normal force is `multiplier × scale`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct RowLink {
    row: usize,
    scale: f64,
}

impl ZoneContact {
    /// The slave node a continuous row id stands for.
    fn row_node(&self, id: usize) -> Option<NodeId> {
        match self.carriers.get(id).map(Vec::as_slice) {
            Some([(n, _)]) => Some(*n),
            _ => None,
        }
    }
}

/// One contact zone at work: pairing, rows, and the last converged outcome.
#[derive(Clone, Debug)]
pub struct ZoneContact {
    pub zone: ResolvedZone,
    pub law: ZoneLaw,
    pub geom_loop: GeomLoop,
    pairs: Vec<ContactPair>,
    links: Vec<Option<RowLink>>,
    /// Normal force carried by each pair at the last converged step (≥ 0).
    forces: Vec<f64>,
    /// Whether pairing was done once (REAC_GEOM='SANS' keeps it).
    paired_once: bool,
    /// The geometric loop of fem's steps (when to pair again).
    geom: GeomLoopState,
    /// The rows last handed to fem, kept while new ones differ only by
    /// round-off (fem compares rows exactly to decide that the geometric
    /// loop has settled).
    last_rows: Vec<InequalityRow>,
    /// Length scale of the zone (bounding box diagonal), for tolerances.
    length: f64,
    /// With REAC_GEOM='SANS': the rows of the first pairing.
    frozen_rows: Vec<InequalityRow>,
    /// What each force acts on: slave nodes and weights (one entry per
    /// pair in discrete, per slave node row in continuous).
    carriers: Vec<Vec<(NodeId, f64)>>,
    /// RESOLUTION='NON': the pairing each converged step ended with, by
    /// step time (code_aster reports these zones' gaps as paired last, not
    /// on the final geometry).
    step_pairings: Vec<(f64, Vec<ContactPair>)>,
    /// Per carrier, the measure its force is spread over: Wⱼ = Σₚ wₚ Nⱼ(p)
    /// for a continuous slave-node row (force / Wⱼ is the contact pressure),
    /// 1 for a discrete pair.
    measures: Vec<f64>,
    /// How continuous integration weights measure the slave surface
    /// (AXIS multiplies by the radius).
    measure: Measure,
    /// ALGO_CONT='LAC': the zone's patches, pairs and pressures (one
    /// carrier and at most one row per patch, in this order).
    lac: Option<LacZone>,
    lac_options: LacOptions,
    /// GLISSIERE='OUI': which rows are bilateral links.
    glissiere: Glissiere,
    /// Continuous zones' ALGO_RESO_GEOM / ALGO_RESO_CONT = 'POINT_FIXE':
    /// loops outside Newton (its iteration count restarts with each pass).
    outer: OuterLoops,
    /// ALGO_CONT='STANDARD': the augmented term ρ·g of each paired
    /// integration point (module `augmented`), for the rows of the last
    /// pairing.
    augmented: Vec<AugmentedTerm>,
}

impl ZoneContact {
    /// Resolves every zone of a definition against the mesh.
    pub fn build_all(
        def: &ContactDefinition,
        mesh: &Mesh,
    ) -> Result<Vec<ZoneContact>, ContactError> {
        let dim = if mesh.dim >= 3 { 3 } else { 2 };
        Self::build_all_in(def, mesh, dim)
    }

    /// [`ZoneContact::build_all`] for a model of dimension `space_dim`
    /// (2 for plane and axisymmetric models, whatever the mesh's number of
    /// coordinates).
    pub fn build_all_in(
        def: &ContactDefinition,
        mesh: &Mesh,
        space_dim: usize,
    ) -> Result<Vec<ZoneContact>, ContactError> {
        let geom_loop = def.geom_loop();
        let mut out = Vec::new();
        match def {
            ContactDefinition::Discrete(d) => {
                for (i, z) in d.zones.iter().enumerate() {
                    out.push(ZoneContact::new(
                        ResolvedZone::new_in(i, &z.geometry, mesh, space_dim)?,
                        ZoneLaw::Discrete(z.law),
                        geom_loop,
                    ));
                }
            }
            ContactDefinition::Continue(c) => {
                let outer = OuterLoops {
                    pairing_restarts: c.algo_reso_geom == Resolution::PointFixe,
                    status_restarts: c.algo_reso_cont == Resolution::PointFixe,
                };
                for (i, z) in c.zones.iter().enumerate() {
                    let mut zc = ZoneContact::new(
                        ResolvedZone::new_in(i, &z.geometry, mesh, space_dim)?,
                        ZoneLaw::Continue(z.law),
                        geom_loop,
                    );
                    zc.outer = outer;
                    out.push(zc);
                }
            }
        }
        crate::quad8::remove_middle_nodes(&mut out);
        Ok(out)
    }

    pub fn new(zone: ResolvedZone, law: ZoneLaw, geom_loop: GeomLoop) -> Self {
        let g = &zone.geometry;
        let glissiere = Glissiere::new(
            g.glissiere,
            matches!(law, ZoneLaw::Discrete(_)),
            g.contact_init,
        );
        ZoneContact {
            glissiere,
            outer: OuterLoops::default(),
            last_rows: Vec::new(),
            length: 0.0,
            frozen_rows: Vec::new(),
            carriers: Vec::new(),
            step_pairings: Vec::new(),
            measures: Vec::new(),
            measure: Measure::Plane,
            lac: None,
            lac_options: LacOptions::default(),
            augmented: Vec::new(),
            zone,
            law,
            geom_loop,
            pairs: Vec::new(),
            links: Vec::new(),
            forces: Vec::new(),
            paired_once: false,
            geom: GeomLoopState::new(geom_loop),
        }
    }

    /// Declares the model axisymmetric (AXIS): continuous integration
    /// weights then carry the radius, as fem's nodal forces (per radian).
    pub fn set_measure(&mut self, measure: Measure) {
        self.measure = measure;
        if let Some(l) = &mut self.lac {
            l.axis = measure == Measure::Axisymmetric;
        }
    }

    /// Whether the zone is a continuous `ALGO_CONT='PENALISATION'` zone.
    fn is_penalised_continue(&self) -> bool {
        matches!(
            self.law,
            ZoneLaw::Continue(ContinueLaw {
                algo: ContinueAlgo::Penalisation { .. },
                ..
            })
        )
    }

    /// Whether the zone is an `ALGO_CONT='LAC'` zone.
    pub fn is_lac(&self) -> bool {
        matches!(
            self.law,
            ZoneLaw::Continue(ContinueLaw {
                algo: ContinueAlgo::Lac,
                ..
            })
        )
    }

    /// Gives a LAC zone the patches DECOUPE_LAC made on its slave group.
    pub fn set_lac_patches(&mut self, patches: &LacZonePatches) -> Result<(), ContactError> {
        let mut lac = LacZone::new(&self.zone, patches)?;
        lac.axis = self.measure == Measure::Axisymmetric;
        lac.updated_jacobian = self.lac_options.updated_jacobian;
        lac.tole = self.lac_options.resi_appa;
        self.lac = Some(lac);
        Ok(())
    }

    /// The LAC state of the zone (patches, last pairing, pressures).
    pub fn lac(&self) -> Option<&LacZone> {
        self.lac.as_ref()
    }

    /// LAC's zone keywords (`TYPE_JACOBIEN`, `RESI_APPA`).
    pub fn set_lac_options(&mut self, options: LacOptions) {
        self.lac_options = options;
        if let Some(l) = &mut self.lac {
            l.updated_jacobian = options.updated_jacobian;
            l.tole = options.resi_appa;
        }
    }

    /// Replaces the geometric loop (and restarts its state).
    pub fn set_geom_loop(&mut self, geom_loop: GeomLoop) {
        self.geom_loop = geom_loop;
        self.geom = GeomLoopState::new(geom_loop);
    }

    /// `CONT_ELEM` of a LAC zone: per slave cell, the values of its patch
    /// (components `lac::CONT_ELEM_COMPONENTS`) at the last pairing and
    /// outcome. `None` for other zones.
    pub fn cont_elem(&self) -> Option<Vec<(CellId, [f64; 5])>> {
        Some(self.lac.as_ref()?.cont_elem(&self.zone))
    }

    /// ALGO_CONT='LAC': pairs the zone (module `lac`) and returns one row
    /// per patch that may touch; the multiplier is the patch pressure.
    fn lac_rows(
        &mut self,
        mesh: &Mesh,
        x: &[[f64; 3]],
    ) -> Result<Vec<InequalityRow>, ContactError> {
        let smooth = if self.zone.geometry.lissage {
            let mut map = BTreeMap::new();
            for c in self.zone.slave.iter().chain(&self.zone.master) {
                for n in &c.nodes {
                    if !map.contains_key(n) {
                        let master = self.zone.master_cells_of_node.contains_key(n)
                            && !self.zone.slave_cells_of_node.contains_key(n);
                        map.insert(*n, self.zone.nodal_normal(*n, master, x)?);
                    }
                }
            }
            Some(map)
        } else {
            None
        };
        let Some(lac) = self.lac.as_mut() else {
            return Err(ContactError::Invalid {
                keyword: "ALGO_CONT",
                message: format!(
                    "ALGO_CONT='LAC' needs the patches of CREA_MAILLAGE/DECOUPE_LAC on '{}': \
                     cut the mesh with CREA_MAILLAGE(DECOUPE_LAC=_F(GROUP_MA_ESCL=...)) and \
                     build the model on the new mesh",
                    self.zone.geometry.slave_group
                ),
            });
        };
        lac.pair(&self.zone, x);
        let rows = lac.rows(mesh, &self.zone, x, smooth.as_ref());
        for (k, p) in lac.patches.iter().enumerate() {
            let n = p.pressure_nodes.len().max(1) as f64;
            self.carriers
                .push(p.pressure_nodes.iter().map(|m| (*m, 1.0 / n)).collect());
            self.measures.push(lac.state[k].paired);
            self.links.push(None);
        }
        for (r, row) in rows.iter().enumerate() {
            self.links[row.id] = Some(RowLink {
                row: r,
                scale: lac.state[row.id].paired,
            });
        }
        Ok(rows)
    }

    /// The measure continuous integration weights are taken with.
    pub fn measure(&self) -> Measure {
        self.measure
    }

    /// The slave points of this zone; continuous weights are measured on
    /// the mesh's reference geometry, as code_aster's contact elements.
    fn points(&self, mesh: &Mesh) -> Vec<SlavePoint> {
        match self.law {
            ZoneLaw::Discrete(_) => nodal_points(&self.zone),
            // LAC integrates on its own mortar pieces.
            ZoneLaw::Continue(ContinueLaw {
                algo: ContinueAlgo::Lac,
                ..
            }) => Vec::new(),
            ZoneLaw::Continue(l) => {
                integration_points_measured(&self.zone, l.integration, &mesh.coords, self.measure)
            }
        }
    }

    /// Pairs the zone on the current positions `x` of all mesh nodes and
    /// returns its rows (none with RESOLUTION='NON'). With REAC_GEOM='SANS'
    /// the rows of the first pairing are returned unchanged.
    pub fn pair(
        &mut self,
        mesh: &Mesh,
        x: &[[f64; 3]],
    ) -> Result<Vec<InequalityRow>, ContactError> {
        if x.len() != mesh.coords.len() {
            return Err(ContactError::Invalid {
                keyword: "GROUP_MA_ESCL",
                message: format!(
                    "geometry of {} nodes for a mesh of {}",
                    x.len(),
                    mesh.coords.len()
                ),
            });
        }
        let frozen = self.geom_loop == GeomLoop::Sans && self.paired_once;
        if frozen {
            // REAC_GEOM='SANS': the rows of the initial pairing, as they were
            // (links made since then included).
            let mut rows = self.frozen_rows.clone();
            self.glissiere.mark(&mut rows, |id| self.row_node(id));
            return Ok(rows);
        }
        let points = self.points(mesh);
        self.pairs = points
            .iter()
            .map(|p| pair_point(&self.zone, p, x))
            .collect::<Result<_, _>>()?;
        self.paired_once = true;
        let mut rows = Vec::new();
        self.carriers.clear();
        self.measures.clear();
        self.links.clear();
        if self.zone.geometry.resolve {
            match self.law {
                ZoneLaw::Discrete(_) => {
                    for (i, pair) in self.pairs.iter().enumerate() {
                        self.carriers.push(pair.point.nodes.clone());
                        self.measures.push(1.0);
                        self.links.push(None);
                        let Some(p) = pair.pairing() else { continue };
                        let row =
                            contact_row(mesh, x, &pair.point.nodes, p, self.zone.space_dim, 1.0, i);
                        if !row.terms.is_empty() {
                            self.links[i] = Some(RowLink {
                                row: rows.len(),
                                scale: 1.0,
                            });
                            rows.push(row);
                        }
                    }
                }
                ZoneLaw::Continue(ContinueLaw {
                    algo: ContinueAlgo::Lac,
                    ..
                }) => rows = self.lac_rows(mesh, x)?,
                ZoneLaw::Continue(ContinueLaw {
                    algo: ContinueAlgo::Penalisation { .. },
                    ..
                }) => {
                    // Pointwise penalty (module `penalty`): one row and one
                    // carrier per integration point.
                    let point_rows = crate::penalty::point_rows(&self.zone, &self.pairs, mesh, x);
                    for (pair, r) in self.pairs.iter().zip(point_rows) {
                        self.carriers.push(pair.point.nodes.clone());
                        self.measures.push(pair.point.weight);
                        self.links.push(r.as_ref().map(|(_, scale)| RowLink {
                            row: rows.len(),
                            scale: *scale,
                        }));
                        if let Some((row, _)) = r {
                            rows.push(row);
                        }
                    }
                }
                ZoneLaw::Continue(_) => rows = self.weighted_node_rows(mesh, x),
            }
        }
        self.augmented = match self.law {
            ZoneLaw::Continue(ContinueLaw {
                algo: ContinueAlgo::Standard { coef_cont },
                ..
            }) if self.zone.geometry.resolve => crate::augmented::terms(
                &self.zone,
                &self.pairs,
                &self.node_rows(),
                coef_cont,
                mesh,
                x,
            ),
            _ => Vec::new(),
        };
        self.forces = vec![0.0; self.carriers.len()];
        if self.geom_loop == GeomLoop::Sans {
            self.frozen_rows = rows.clone();
        }
        self.glissiere.mark(&mut rows, |id| self.row_node(id));
        Ok(rows)
    }

    /// Continuous formulation: one row per slave node j, the weighted gap
    /// Σₚ wₚ Nⱼ(p) gₚ / Wⱼ (Wⱼ = Σₚ wₚ Nⱼ(p)) over the paired integration
    /// points — the contact pressure is a nodal field, as code_aster's
    /// LAGS_C, and several points on one cell never make redundant rows.
    /// The row is scaled by Wⱼ (λ is then the pressure). (PENALISATION is
    /// pointwise: module `penalty`.)
    fn weighted_node_rows(&mut self, mesh: &Mesh, x: &[[f64; 3]]) -> Vec<InequalityRow> {
        type Acc = (f64, BTreeMap<Dof, f64>, f64, f64);
        let mut acc: BTreeMap<NodeId, Acc> = BTreeMap::new();
        for pair in &self.pairs {
            let Some(p) = pair.pairing() else { continue };
            let r = contact_row(mesh, x, &pair.point.nodes, p, self.zone.space_dim, 1.0, 0);
            // The pressure's functions weigh the gap (the corners' only on
            // TRIA6/QUAD8 faces: SurfaceKind::linear_pressure).
            let pressure: Vec<(NodeId, f64)> = match pair.point.cell {
                Some((ci, xi)) => {
                    let c = &self.zone.slave[ci];
                    c.nodes
                        .iter()
                        .copied()
                        .zip(c.kind.pressure_eval(xi))
                        .collect()
                }
                None => pair.point.nodes.clone(),
            };
            for &(j, nj) in &pressure {
                let w = pair.point.weight * nj;
                if w == 0.0 || self.zone.slave_nodes.binary_search(&j).is_err() {
                    continue;
                }
                let e = acc
                    .entry(j)
                    .or_insert_with(|| (0.0, BTreeMap::new(), 0.0, 0.0));
                e.0 += w;
                for &(d, c) in &r.terms {
                    *e.1.entry(d).or_default() += w * c;
                }
                e.2 += w * r.rhs;
                e.3 += w * p.gap;
            }
        }
        if self.glissiere.is_on() {
            let gaps: Vec<(NodeId, f64)> = acc
                .iter()
                .filter(|(_, a)| a.0 > 0.0)
                .map(|(j, a)| (*j, a.3 / a.0))
                .collect();
            let eps = self.zone.contact_init_threshold(mesh);
            self.glissiere.start(eps, &gaps);
        }
        let mut rows = Vec::new();
        for (j, (weight, terms, rhs, _)) in acc {
            if weight <= 0.0 {
                continue;
            }
            let terms: Vec<(Dof, f64)> = terms.into_iter().filter(|t| t.1 != 0.0).collect();
            if terms.is_empty() {
                continue;
            }
            let id = self.carriers.len();
            self.carriers.push(vec![(j, 1.0)]);
            self.measures.push(weight);
            self.links.push(Some(RowLink {
                row: rows.len(),
                scale: weight,
            }));
            rows.push(InequalityRow::new(terms, rhs, id));
        }
        rows
    }

    /// For each slave node that carries a continuous row: the row's index
    /// in the rows of the last pairing.
    fn node_rows(&self) -> BTreeMap<NodeId, usize> {
        self.carriers
            .iter()
            .zip(&self.links)
            .filter_map(|(nodes, link)| match (nodes.as_slice(), link) {
                ([(n, _)], Some(l)) => Some((*n, l.row)),
                _ => None,
            })
            .collect()
    }

    /// Penalty of each row for the dual algorithms (ε = 1/penalty, 0 = exact).
    pub fn row_penalties(&self) -> Vec<f64> {
        let eps = match self.law {
            ZoneLaw::Discrete(DiscreteAlgo::Penalisation { e_n }) => 1.0 / e_n,
            ZoneLaw::Continue(ContinueLaw {
                algo: ContinueAlgo::Penalisation { coef_pena_cont },
                ..
            }) => 1.0 / coef_pena_cont,
            _ => 0.0,
        };
        vec![eps; self.links.iter().flatten().count()]
    }

    /// Records the multipliers of this zone's rows (in row order).
    pub fn set_multipliers(&mut self, multipliers: &[f64]) {
        self.forces = vec![0.0; self.carriers.len()];
        if let Some(z) = self.lac.as_mut() {
            z.pressures.iter_mut().for_each(|p| *p = 0.0);
        }
        for (i, link) in self.links.iter().enumerate() {
            if let Some(l) = link {
                if let Some(&m) = multipliers.get(l.row) {
                    // A bilateral link (GLISSIERE) may pull.
                    let m = if self.glissiere.links(self.row_node(i)) {
                        m
                    } else {
                        m.max(0.0)
                    };
                    self.forces[i] = m * l.scale;
                    if let Some(p) = self.lac.as_mut().and_then(|z| z.pressures.get_mut(i)) {
                        *p = m;
                    }
                }
            }
        }
    }

    /// Records fem's outcomes of this zone's rows (matched by row id, which
    /// is the carrier index: the pair in discrete, the slave node row in
    /// continuous).
    pub fn set_outcomes(&mut self, outcomes: &[RowOutcome]) {
        self.forces = vec![0.0; self.carriers.len()];
        if let Some(z) = self.lac.as_mut() {
            z.pressures.iter_mut().for_each(|p| *p = 0.0);
        }
        for o in outcomes {
            if let Some(Some(l)) = self.links.get(o.id) {
                // A bilateral link (GLISSIERE) may pull.
                let m = if self.glissiere.links(self.row_node(o.id)) {
                    o.multiplier
                } else {
                    o.multiplier.max(0.0)
                };
                self.forces[o.id] = m * l.scale;
                if let Some(p) = self.lac.as_mut().and_then(|z| z.pressures.get_mut(o.id)) {
                    *p = m;
                }
            }
        }
    }

    /// RESOLUTION='NON' zone: the pairing the converged step at `time`
    /// ended with (as recorded during fem's solve).
    pub fn verification_pairing(&self, time: f64) -> Option<&[ContactPair]> {
        self.step_pairings
            .iter()
            .rev()
            .find(|(t, _)| (t - time).abs() <= 1e-9 * time.abs().max(1.0))
            .map(|(_, p)| p.as_slice())
    }

    /// Pairings done in the current (last) step of fem's geometric loop.
    pub fn geom_pairings(&self) -> usize {
        self.geom.pairings()
    }

    /// The last geometric residual of `REAC_GEOM='AUTOMATIQUE'`
    /// (max‖uₖ − uₖ₋₁‖ / max‖uₖ₋₁ − u₀‖), if one was computed.
    pub fn geom_residual(&self) -> Option<f64> {
        self.geom.last_residual
    }

    /// The pairs of the last pairing.
    pub fn pairs(&self) -> &[ContactPair] {
        &self.pairs
    }

    /// Normal force (≥ 0) of each row carrier at the last converged step
    /// (pairs in discrete, slave nodes in continuous).
    pub fn forces(&self) -> &[f64] {
        &self.forces
    }

    /// Nodal normal forces on the slave nodes.
    pub fn nodal_forces(&self) -> Vec<(NodeId, f64)> {
        let mut out: Vec<(NodeId, f64)> = Vec::new();
        for (nodes, f) in self.carriers.iter().zip(&self.forces) {
            for (n, w) in nodes {
                match out.iter_mut().find(|(m, _)| m == n) {
                    Some(e) => e.1 += w * f,
                    None => out.push((*n, w * f)),
                }
            }
        }
        out
    }

    /// code_aster's `LAGS_C` (the contact multiplier component of DEPL in
    /// the continuous formulation) on every slave node of the zone: minus
    /// the contact pressure, force / Wⱼ (R5.03.52: the multiplier is the
    /// normal stress on the slave surface, negative in compression); 0 on
    /// slave nodes without contact. `None` for a discrete zone, whose
    /// multipliers are not part of DEPL.
    pub fn lags_c(&self) -> Option<Vec<(NodeId, f64)>> {
        if !matches!(self.law, ZoneLaw::Continue(_)) {
            return None;
        }
        if let Some(lac) = &self.lac {
            // LAC: the patch pressure on its pressure nodes only.
            return Some(lac.lags_c());
        }
        let mut out: BTreeMap<NodeId, f64> =
            self.zone.slave_nodes.iter().map(|n| (*n, 0.0)).collect();
        if self.is_penalised_continue() {
            // The L² projection of the pointwise pressure (module `penalty`).
            out.extend(crate::penalty::lags_c(
                &self.zone,
                &self.pairs,
                &self.forces,
            ));
        } else {
            for ((nodes, f), w) in self.carriers.iter().zip(&self.forces).zip(&self.measures) {
                if let [(n, _)] = nodes.as_slice() {
                    if *w > 0.0 {
                        if let Some(v) = out.get_mut(n) {
                            *v = -f / w;
                        }
                    }
                }
            }
        }
        // Nodes without a pressure of their own (mid-sides of TRIA6/QUAD8
        // faces): the mean of the corners they lie between.
        for cell in &self.zone.slave {
            for (local, n) in cell.nodes.iter().enumerate() {
                let support = cell.kind.pressure_support(local);
                if support == [local] || !out.contains_key(n) {
                    continue;
                }
                let vals: Vec<f64> = support
                    .iter()
                    .filter_map(|&k| out.get(&cell.nodes[k]).copied())
                    .collect();
                if vals.len() == support.len() {
                    out.insert(*n, vals.iter().sum::<f64>() / vals.len() as f64);
                }
            }
        }
        Some(out.into_iter().collect())
    }

    /// Penalised continuous zone with code_aster's adaptive coefficient
    /// (`ZoneGeometry::pene_maxi`): the converged penetrations (weighted
    /// mean per slave node) must stay within the limit, where code_aster
    /// leaves the coefficient as it is.
    /// A verification zone (`RESOLUTION='NON'`) with `STOP_INTERP='OUI'`
    /// at a converged step: stops when slave nodes interpenetrate, counted
    /// as code_aster's `cfsans` does (a gap ≤ ε beyond `TOLE_INTERP`, the
    /// gaps of the step's last pairing, those `CONT` reports).
    fn stop_on_interpenetration(&self, time: f64) -> Result<(), FemError> {
        let g = &self.zone.geometry;
        if !g.stop_interp {
            return Ok(());
        }
        let nodes = self
            .pairs
            .iter()
            .filter(|p| match &p.status {
                PairStatus::Paired(p) => interpenetrates(p.gap, g.tole_interp),
                PairStatus::Excluded(_) => false,
            })
            .count();
        if nodes > 0 {
            return Err(FemError::Interpenetration { time, nodes });
        }
        Ok(())
    }

    fn check_penetration(&self, time: f64, outcomes: &[RowOutcome]) -> Result<(), FemError> {
        let Some(limit) = self.zone.geometry.pene_maxi else {
            return Ok(());
        };
        for o in outcomes.iter().filter(|o| o.active) {
            let Some(Some(l)) = self.links.get(o.id) else {
                continue;
            };
            let penetration = o.violation / l.scale.max(f64::MIN_POSITIVE);
            if penetration > limit {
                let node = self
                    .row_node(o.id)
                    .map(|n| format!(" at slave node #{}", n.0 + 1))
                    .unwrap_or_default();
                return Err(FemError::Source(format!(
                    "{}: at time {time} the penetration{node} is {penetration:.4e}, beyond \
                     {limit:.4e} (PENE_MAXI, or 1 % of the shortest master cell): code_aster \
                     would raise COEF_PENA_CONT there (ADAPTATION='ADAPT_COEF'/'TOUT', \
                     Bussetta's rule), which is not reproduced; give ADAPTATION='NON' with \
                     COEF_PENA_CONT, or use ALGO_CONT='STANDARD'",
                    self.describe()
                )));
            }
        }
        Ok(())
    }

    fn describe(&self) -> String {
        format!(
            "contact zone {} ({} on {})",
            self.zone.index + 1,
            self.zone.geometry.slave_group,
            self.zone.geometry.master_group
        )
    }
}

fn zone_length(zone: &ResolvedZone, coords: &[[f64; 3]]) -> f64 {
    let d = aster_mesh::box_diagonal(aster_mesh::bounding_box(
        zone.master_nodes
            .iter()
            .chain(&zone.slave_nodes)
            .map(|n| coords[n.0 as usize]),
    ));
    if d.is_finite() && d > 0.0 {
        d
    } else {
        1.0
    }
}

fn same_rows(a: &[InequalityRow], b: &[InequalityRow], tol_coef: f64, tol_rhs: f64) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(r, s)| {
            r.id == s.id
                && r.bilateral == s.bilateral
                && (r.rhs - s.rhs).abs() <= tol_rhs
                && r.terms.len() == s.terms.len()
                && r.terms
                    .iter()
                    .zip(&s.terms)
                    .all(|(x, y)| x.0 == y.0 && (x.1 - y.1).abs() <= tol_coef * x.1.abs().max(1.0))
        })
}

/// Nodal translations of a fem state.
fn nodal_displacements(state: &State) -> Vec<[f64; 3]> {
    (0..state.mesh.coords.len())
        .map(|i| state.node_displacement(NodeId(i as u32)))
        .collect()
}

/// Current node positions of a fem state.
pub fn current_positions(state: &State) -> Vec<[f64; 3]> {
    (0..state.mesh.coords.len())
        .map(|i| state.current_coord(NodeId(i as u32)))
        .collect()
}

impl UnilateralSource for ZoneContact {
    fn name(&self) -> String {
        self.describe()
    }

    fn method(&self) -> UnilateralMethod {
        match self.law {
            ZoneLaw::Discrete(DiscreteAlgo::Penalisation { e_n }) => {
                UnilateralMethod::Penalty { coef: e_n }
            }
            ZoneLaw::Continue(ContinueLaw {
                algo: ContinueAlgo::Penalisation { coef_pena_cont },
                ..
            }) => UnilateralMethod::Penalty {
                coef: coef_pena_cont,
            },
            // CONTRAINTE, GCP and STANDARD converge to the exact solution:
            // fem's active set computes that solution directly.
            _ => UnilateralMethod::ActiveSet,
        }
    }

    fn outer_loops(&self) -> OuterLoops {
        self.outer
    }

    fn geometry_update(&self) -> GeometryUpdate {
        match self.geom_loop {
            GeomLoop::Sans => GeometryUpdate::Once,
            // The loop (GeomLoopState) decides at each request whether to
            // pair again; fem asks at every stable active set.
            GeomLoop::Controle { .. } | GeomLoop::Automatique { .. } => {
                GeometryUpdate::EachIteration
            }
        }
    }

    fn rows(&mut self, state: &State) -> Result<Vec<InequalityRow>, FemError> {
        let x = current_positions(state);
        if self.length == 0.0 {
            self.length = zone_length(&self.zone, &state.mesh.coords);
        }
        let u = nodal_displacements(state);
        // Discrete AUTOMATIQUE: fem's loop applies code_aster's RESI_GEOM
        // test (`geometry_criterion`) and asks for rows exactly when it wants
        // a new pairing; the zone's own loop state decides for the others.
        let decision = self.geom.decide(state.time, &u);
        match decision {
            GeomDecision::Keep if self.paired_once => return Ok(self.last_rows.clone()),
            GeomDecision::Keep | GeomDecision::Pair => {}
            GeomDecision::Diverged { pairings, residual } => {
                let (iter_maxi, resi_geom) = match self.geom_loop {
                    GeomLoop::Automatique {
                        iter_maxi,
                        resi_geom,
                    } => (iter_maxi, resi_geom),
                    _ => (pairings, 0.0),
                };
                let message = format!(
                    "{}: the geometric loop (REAC_GEOM='AUTOMATIQUE') did not converge at time {}: \
                     after ITER_GEOM_MAXI={iter_maxi} pairings the displacement still changes by \
                     {:.3e} of the step's displacement (RESI_GEOM={resi_geom}); raise \
                     ITER_GEOM_MAXI, cut the step, or fix the number of updates with \
                     REAC_GEOM='CONTROLE'",
                    self.describe(),
                    state.time,
                    residual
                );
                // A continuous zone with ALGO_RESO_GEOM='NEWTON' (or LAC)
                // has no geometric loop in code_aster: the geometry moves
                // inside its Newton. The loop here stands in for it, so its
                // failure is not code_aster's event ERRE_CTCG: stop rather
                // than cut (cutting does not help a loop whose criterion is
                // relative to the step's displacement: ssnv505l cut to
                // 1/64 steps for 100 s, still failing).
                let stand_in =
                    matches!(self.law, ZoneLaw::Continue(_)) && !self.outer.pairing_restarts;
                return Err(if stand_in {
                    FemError::Source(format!(
                        "{message} (ALGO_RESO_GEOM='NEWTON': code_aster updates the geometry \
                         inside Newton; this loop stands in for it and is not cut)"
                    ))
                } else {
                    FemError::SourceLoop(message)
                });
            }
        }
        self.zone.time = state.time;
        let rows = self
            .pair(state.mesh, &x)
            .map_err(|e| FemError::Source(format!("{}: {e}", self.describe())))?;
        // Rows that moved by round-off only are the same rows (coefficients
        // to 1e-9, right-hand sides to 1e-9 × the zone size): fem compares
        // rows exactly.
        if same_rows(&rows, &self.last_rows, 1e-9, 1e-9 * self.length) {
            return Ok(self.last_rows.clone());
        }
        self.last_rows = rows.clone();
        Ok(rows)
    }

    fn augmented_terms(&self) -> Vec<AugmentedTerm> {
        self.augmented.clone()
    }

    fn converged(&mut self, state: &State, outcomes: &[RowOutcome]) -> Result<(), FemError> {
        self.check_penetration(state.time, outcomes)?;
        if !self.zone.geometry.resolve {
            self.stop_on_interpenetration(state.time)?;
            self.step_pairings.push((state.time, self.pairs.clone()));
        }
        self.set_outcomes(outcomes);
        let carriers = &self.carriers;
        let node_of = |id: usize| match carriers.get(id).map(Vec::as_slice) {
            Some([(n, _)]) => Some(*n),
            _ => None,
        };
        self.glissiere.converged(outcomes, node_of);
        // The rows kept for the next requests carry the new links.
        self.glissiere.mark(&mut self.last_rows, node_of);
        self.refuse_mixed_statuses(state, outcomes)?;
        if let Some(lac) = self.lac.as_mut() {
            // CONT_ELEM reports the patches on the converged geometry.
            lac.pair(&self.zone, &current_positions(state));
        }
        self.geom.step_converged(nodal_displacements(state));
        Ok(())
    }
}

impl ZoneContact {
    /// Continuous STANDARD: stops when a slave node's integration points
    /// end the step with different contact statuses and code_aster's
    /// multiplier equation for it (module `augmented`: the points out of
    /// contact enter with ∫ λ Nⱼ / ρ instead of their gaps) would not hold
    /// to 1e-8 of the zone size. The answer here is then not code_aster's
    /// (ssnp154b: SIEF_NOEU at the Hertz contact's centre 2.2e-6 off).
    fn refuse_mixed_statuses(
        &self,
        state: &State,
        outcomes: &[RowOutcome],
    ) -> Result<(), FemError> {
        if self.augmented.is_empty() {
            return Ok(());
        }
        let multipliers: Vec<f64> = outcomes.iter().map(|o| o.multiplier).collect();
        let value = |d| state.value(d).unwrap_or(0.0);
        let Some(m) = crate::augmented::worst_mixed_node(&self.augmented, &multipliers, value)
        else {
            return Ok(());
        };
        if m.misfit <= 1e-8 * self.length {
            return Ok(());
        }
        let node = self
            .links
            .iter()
            .position(|l| l.is_some_and(|l| l.row == m.row))
            .and_then(|c| self.carriers.get(c))
            .and_then(|c| c.first())
            .and_then(|(n, _)| state.mesh.node_names.get(n.0 as usize))
            .cloned()
            .unwrap_or_else(|| "?".to_string());
        Err(FemError::Source(format!(
            "{}: not supported yet: at time {} the contact front crosses the slave cells \
             around node {node} (its integration points are partly in contact); code_aster's \
             continuous STANDARD formulation then weighs the points out of contact by \
             1/COEF_CONT in the node's equation, which is not reproduced (its equation is \
             missed by {:.3e}, the zone measures {:.3e}); ALGO_CONT='PENALISATION' or the \
             DISCRETE formulation are reproduced",
            self.describe(),
            state.time,
            m.misfit,
            self.length
        )))
    }
}

// `&mut ZoneContact` is a source through fem's blanket impl for `&mut T`
// (the caller keeps the zone for CONT_NOEU while the solver borrows it).
