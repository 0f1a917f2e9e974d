//! Loads and kinematic conditions, each scaled by its own time multiplier
//! (code_aster's `EXCIT=_F(CHARGE=…, FONC_MULT=…)`).

use crate::dof::Dof;
use crate::error::FemError;
use crate::material::Hypothesis;
use crate::model::{ElementKind, Model};
use crate::shape;
use aster_mesh::{CellId, CellType, NodeId};
use std::collections::HashMap;
use std::fmt;
use std::sync::Arc;

type TimeFn = dyn Fn(f64) -> Result<f64, String> + Send + Sync;

/// A time multiplier f(t) (`FONC_MULT`); the default is f ≡ 1.
#[derive(Clone, Default)]
pub struct Multiplier(Option<Arc<TimeFn>>);

impl Multiplier {
    /// f ≡ 1.
    pub fn one() -> Multiplier {
        Multiplier(None)
    }

    /// f(t) = c.
    pub fn constant(c: f64) -> Multiplier {
        Multiplier(Some(Arc::new(move |_| Ok(c))))
    }

    /// Any function; an `Err` (e.g. evaluation outside an `EXCLU` range) is
    /// reported with the time and the load.
    pub fn from_fn(f: impl Fn(f64) -> Result<f64, String> + Send + Sync + 'static) -> Multiplier {
        Multiplier(Some(Arc::new(f)))
    }

    pub fn eval(&self, t: f64) -> Result<f64, FemError> {
        match &self.0 {
            None => Ok(1.0),
            Some(f) => {
                f(t).map_err(|m| FemError::Model(format!("load multiplier at time {t}: {m}")))
            }
        }
    }
}

impl fmt::Debug for Multiplier {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            None => write!(f, "Multiplier(1)"),
            Some(_) => write!(f, "Multiplier(fn)"),
        }
    }
}

/// One load or condition (its value is multiplied by f(t)).
#[derive(Clone, Debug, PartialEq)]
pub enum Load {
    /// Imposed value by elimination (`AFFE_CHAR_CINE/MECA_IMPO`).
    Eliminated { dof: Dof, value: f64 },
    /// Imposed value dualised with a Lagrange multiplier (`DDL_IMPO`); the
    /// multiplier is the reaction.
    Imposed { dof: Dof, value: f64 },
    /// Dualised linear relation Σ cᵢ uᵢ = rhs (`LIAISON_DDL`).
    Relation { terms: Vec<(Dof, f64)>, rhs: f64 },
    /// Nodal force (`FORCE_NODALE`).
    NodalForce { dof: Dof, value: f64 },
    /// Distributed force per unit length (2D edge) or area (3D face)
    /// (`FORCE_CONTOUR`, `FORCE_FACE`), global components.
    SurfaceForce { cell: CellId, force: [f64; 3] },
    /// Pressure (`PRES_REP`): traction −p·n with n the outward normal.
    Pressure { cell: CellId, pressure: f64 },
    /// Force per unit volume (per unit area in 2D) on a continuum cell
    /// (`FORCE_INTERNE`), global components.
    VolumeForce { cell: CellId, force: [f64; 3] },
    /// A surface force given point by point: its value at each point of
    /// [`shape::skin_scheme`] (a function of the coordinates evaluated
    /// there, as code_aster does for `AFFE_CHAR_MECA_F`); see
    /// [`Loads::skin_points`].
    SurfaceForceAt { cell: CellId, forces: Vec<[f64; 3]> },
    /// A pressure given at each point of [`shape::skin_scheme`].
    PressureAt { cell: CellId, pressures: Vec<f64> },
    /// A force per unit volume given at each point of the cell's stiffness
    /// scheme ([`shape::rigi_scheme`]); see [`Loads::volume_points`].
    VolumeForceAt { cell: CellId, forces: Vec<[f64; 3]> },
    /// Force and moment per unit length on an edge (`FORCE_ARETE`): a
    /// SEG2/SEG3 cell of a 3D model, bordering solids or shells; global
    /// components FX FY FZ MX MY MZ, integrated as ∫ Nᵢ f dl with the
    /// Gauss family of the element code_aster puts on the segment
    /// ([`EdgeRule`]: te0469, te0034, te0418). Moments need the rotations
    /// of shell nodes.
    EdgeForce {
        cell: CellId,
        force: [f64; 6],
        rule: EdgeRule,
    },
    /// A force and moment per unit area on a shell cell (`FORCE_COQUE`
    /// with global components or a pressure, `PESANTEUR` on shells:
    /// ρ h g d): the value at each node of the cell (global FX FY FZ MX MY
    /// MZ, then a pressure p adding −p n to the force, n the facet's normal
    /// on a DKT, the node's on a COQUE_3D), acting in the plane at `offset` from the mid-surface along the
    /// facet's normal n (`PLAN`: the moment offset·n × F added, te0032).
    /// DKT/DKQ (te0032 → dxtfor, dxqfor; [`shell_nodal_load`]): a
    /// triangle's node receives its value × A/3, a quadrangle's node half
    /// the sum, over the three corner triangles it belongs to, of
    /// (its value/6 + the two others'/12) × the triangle's area.
    /// COQUE_3D (te0403 → fsurf): the forces interpolated at the normal
    /// points ([`crate::coque3d::surface_load`]); moments and offsets are
    /// errors there.
    ShellForce {
        cell: CellId,
        nodal: Vec<[f64; 7]>,
        offset: f64,
    },
    /// An isotropic free strain ε_th = α (T − T_ref) on a continuum cell
    /// (a temperature given by `AFFE_VARC`), its value at each node of the
    /// cell, interpolated at the Gauss points with the shape functions:
    /// the load ∫ Bᵀ D ε_th (ε_th on xx, yy, zz) and the stresses
    /// σ = D (B u − ε_th) ([`Loads::subtract_free_strain`]).
    FreeStrain { cell: CellId, nodal: Vec<f64> },
    /// A free strain through the thickness of a plate facet (DKT, DST,
    /// Q4G), ε_th(z) = p₀ + p₁ z + p₂ z² on xx and yy, constant over the
    /// facet (a temperature of `CREA_RESU/PREP_VARC`): the load ∫ Bᵀ (N, M)
    /// of its generalised efforts ([`crate::plate::thermal_load`]); the
    /// efforts and stresses of the facet are its mechanical ones minus
    /// [`crate::plate::thermal_efforts`] and
    /// [`crate::plate::thermal_stress`] ([`Loads::shell_thermal_at`]).
    ShellThermal {
        cell: CellId,
        profile: crate::plate::ThicknessProfile,
    },
}

/// A load with its multiplier.
#[derive(Clone, Debug)]
pub struct LoadItem {
    pub load: Load,
    pub mult: Multiplier,
}

/// All loads and conditions of an analysis.
#[derive(Clone, Debug, Default)]
pub struct Loads {
    pub items: Vec<LoadItem>,
}

/// A dualised equality row Σ cᵢ u[i] = rhs over DOF indices.
#[derive(Clone, Debug, PartialEq)]
pub struct EqualityRow {
    pub terms: Vec<(usize, f64)>,
    pub rhs: f64,
    /// Index of the load item that produced it.
    pub item: usize,
}

impl Loads {
    pub fn new() -> Loads {
        Loads::default()
    }

    /// Adds a load with a multiplier.
    pub fn add(&mut self, load: Load, mult: Multiplier) -> &mut Loads {
        self.items.push(LoadItem { load, mult });
        self
    }

    /// Adds a load with f ≡ 1.
    pub fn push(&mut self, load: Load) -> &mut Loads {
        self.add(load, Multiplier::one())
    }

    /// Checks that every DOF and cell a load refers to exists in the model.
    pub fn validate(&self, model: &Model) -> Result<(), FemError> {
        let check = |dof: Dof, what: &str| -> Result<(), FemError> {
            if model.dofs().index(dof).is_some() {
                return Ok(());
            }
            let mesh = model.mesh();
            if dof.node.0 as usize >= mesh.node_count() {
                return Err(FemError::Model(format!(
                    "{what} on node #{} which the mesh does not have",
                    dof.node.0 + 1
                )));
            }
            if !model.dofs().has_node(dof.node) {
                return Err(FemError::Model(format!(
                    "{what} on {}: node {} carries no element of the model, so it has no degrees of freedom",
                    dof.describe(mesh),
                    mesh.node_names.get(dof.node.0 as usize).map(String::as_str).unwrap_or("?")
                )));
            }
            let comps: Vec<&str> = model
                .dofs()
                .node_comps(dof.node)
                .iter()
                .map(|c| c.name())
                .collect();
            Err(FemError::Model(format!(
                "{what} on {}: this node of the model carries only {}",
                dof.describe(mesh),
                comps.join(", ")
            )))
        };
        for item in &self.items {
            match &item.load {
                Load::Eliminated { dof, .. } => check(*dof, "imposed value (MECA_IMPO)")?,
                Load::Imposed { dof, .. } => check(*dof, "imposed value (DDL_IMPO)")?,
                Load::NodalForce { dof, .. } => check(*dof, "nodal force")?,
                Load::Relation { terms, .. } => {
                    for (d, _) in terms {
                        check(*d, "linear relation (LIAISON_DDL)")?;
                    }
                }
                Load::VolumeForce { cell, .. }
                | Load::VolumeForceAt { cell, .. }
                | Load::FreeStrain { cell, .. } => {
                    let continuum = model.elements().iter().any(|e| {
                        e.cell == *cell && matches!(e.kind, ElementKind::Continuum { .. })
                    });
                    if !continuum {
                        return Err(FemError::Model(format!(
                            "volume force (FORCE_INTERNE) on cell {}, which carries no continuum element of the model",
                            model.cell_name(*cell)
                        )));
                    }
                }
                Load::ShellThermal { cell, .. } => {
                    if !matches!(model.element_kind(*cell), Some(ElementKind::Shell { .. })) {
                        return Err(FemError::Model(format!(
                            "thermal strain through the thickness on cell {}, which carries no DKT, DST or Q4G plate element of the model",
                            model.cell_name(*cell)
                        )));
                    }
                }
                Load::EdgeForce { cell, force, .. } => edge_check(model, *cell, force)?,
                Load::ShellForce {
                    cell,
                    nodal,
                    offset,
                } => {
                    let n = model
                        .mesh()
                        .cells
                        .get(cell.0 as usize)
                        .map(|c| c.nodes.len());
                    let coque3d = model.is_coque3d(*cell);
                    let what = if coque3d {
                        (nodal.iter().any(|v| v[3..6].iter().any(|m| *m != 0.0)) || *offset != 0.0)
                            .then_some(
                            "a COQUE_3D cell takes forces only (no moment, no PLAN offset: te0403)",
                        )
                    } else if !matches!(model.element_kind(*cell), Some(ElementKind::Shell { .. }))
                    {
                        Some("the cell carries no DKT/DKQ or COQUE_3D shell element")
                    } else {
                        None
                    };
                    let what = what.or((n != Some(nodal.len()))
                        .then_some("one value per node of the cell is needed"));
                    if let Some(what) = what {
                        return Err(FemError::Model(format!(
                            "shell force on cell {}: {what}",
                            model.cell_name(*cell)
                        )));
                    }
                }
                Load::SurfaceForce { cell, .. }
                | Load::Pressure { cell, .. }
                | Load::SurfaceForceAt { cell, .. }
                | Load::PressureAt { cell, .. } => {
                    let mesh = model.mesh();
                    let Some(c) = mesh.cells.get(cell.0 as usize) else {
                        return Err(FemError::Model(format!(
                            "distributed load on cell #{} which the mesh does not have",
                            cell.0 + 1
                        )));
                    };
                    if model.element_comps(*cell) == 6 {
                        // A constant pressure on a shell facet acts along
                        // its normal (`shell_load`); forces and
                        // pressures given point by point are not reproduced.
                        let constant_pressure = matches!(item.load, Load::Pressure { .. });
                        let facet = matches!(c.ty, CellType::TRIA3 | CellType::QUAD4)
                            || model.is_coque3d(*cell);
                        if !(constant_pressure && facet) {
                            return Err(FemError::Model(format!(
                                "distributed load on shell cell {}: only a constant pressure (PRES_REP) on TRIA3/QUAD4 (DKT) and QUAD9/TRIA7 (COQUE_3D) shells is supported",
                                model.cell_name(*cell)
                            )));
                        }
                        continue;
                    }
                    let expected_dim = model.dim() - 1;
                    if c.ty.dim() as usize != expected_dim || !shape::supported(c.ty) {
                        return Err(FemError::Model(format!(
                            "distributed load on cell {} ({}): expected a boundary {} of the {}D model",
                            model.cell_name(*cell),
                            c.ty.name(),
                            if expected_dim == 1 { "segment (SEG2, SEG3)" } else { "face (TRIA3, TRIA6, TRIA7, QUAD4, QUAD8, QUAD9)" },
                            model.dim()
                        )));
                    }
                    for &n in &c.nodes {
                        if !model.dofs().has_node(n) {
                            return Err(FemError::Model(format!(
                                "distributed load on cell {}: its node {} carries no element of the model",
                                model.cell_name(*cell),
                                mesh.node_names.get(n.0 as usize).map(String::as_str).unwrap_or("?")
                            )));
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// Eliminated DOFs and their values at time t (index → value). Two
    /// conditions imposing different values on one DOF are an error.
    pub fn eliminated(&self, model: &Model, t: f64) -> Result<HashMap<usize, f64>, FemError> {
        let mut out: HashMap<usize, f64> = HashMap::new();
        for item in &self.items {
            if let Load::Eliminated { dof, value } = item.load {
                let i = index(model, dof)?;
                let v = value * item.mult.eval(t)?;
                if let Some(prev) = out.insert(i, v) {
                    if (prev - v).abs() > 1e-12 * prev.abs().max(v.abs()) {
                        return Err(FemError::Model(format!(
                            "{} is imposed twice by elimination with different values ({prev} and {v})",
                            dof.describe(model.mesh())
                        )));
                    }
                }
            }
        }
        Ok(out)
    }

    /// Dualised equality rows at time t.
    pub fn equality_rows(&self, model: &Model, t: f64) -> Result<Vec<EqualityRow>, FemError> {
        let mut rows = Vec::new();
        for (k, item) in self.items.iter().enumerate() {
            match &item.load {
                Load::Imposed { dof, value } => rows.push(EqualityRow {
                    terms: vec![(index(model, *dof)?, 1.0)],
                    rhs: value * item.mult.eval(t)?,
                    item: k,
                }),
                Load::Relation { terms, rhs } => {
                    let mut ts = Vec::with_capacity(terms.len());
                    for (d, c) in terms {
                        ts.push((index(model, *d)?, *c));
                    }
                    rows.push(EqualityRow {
                        terms: ts,
                        rhs: rhs * item.mult.eval(t)?,
                        item: k,
                    })
                }
                _ => {}
            }
        }
        Ok(rows)
    }

    /// The applied external force vector at time t (nodal forces, surface
    /// forces and pressures; not reactions).
    pub fn external_forces(&self, model: &Model, t: f64) -> Result<Vec<f64>, FemError> {
        let mut f = vec![0.0; model.dofs().len()];
        let mut faces: Option<HashMap<Vec<NodeId>, [f64; 3]>> = None;
        for item in &self.items {
            match &item.load {
                Load::NodalForce { dof, value } => {
                    f[index(model, *dof)?] += value * item.mult.eval(t)?;
                }
                Load::SurfaceForce { cell, force } => {
                    let m = item.mult.eval(t)?;
                    let tr = [force[0] * m, force[1] * m, force[2] * m];
                    let scheme = shape::load_scheme(model.mesh().cell(*cell).ty);
                    surface_load(model, *cell, &scheme, |_, _, _| tr, &mut f)?;
                }
                Load::SurfaceForceAt { cell, forces } => {
                    let m = item.mult.eval(t)?;
                    let scheme = point_scheme(model, *cell, forces.len(), true)?;
                    surface_load(
                        model,
                        *cell,
                        &scheme,
                        |k, _, _| [forces[k][0] * m, forces[k][1] * m, forces[k][2] * m],
                        &mut f,
                    )?;
                }
                Load::EdgeForce { cell, force, rule } => {
                    let m = item.mult.eval(t)?;
                    if m != 0.0 {
                        edge_load(model, *cell, &force.map(|v| v * m), *rule, &mut f)?;
                    }
                }
                Load::ShellForce {
                    cell,
                    nodal,
                    offset,
                } => {
                    let m = item.mult.eval(t)?;
                    if m == 0.0 {
                        continue;
                    }
                    let scaled: Vec<[f64; 7]> = nodal.iter().map(|v| v.map(|x| x * m)).collect();
                    shell_load(model, *cell, &scaled, *offset, &mut f)?;
                }
                Load::VolumeForce { cell, force } => {
                    let m = item.mult.eval(t)?;
                    let b = [force[0] * m, force[1] * m, force[2] * m];
                    volume_load(model, *cell, |_| b, &mut f)?;
                }
                Load::FreeStrain { cell, nodal } => {
                    let m = item.mult.eval(t)?;
                    if m != 0.0 {
                        free_strain_load(model, *cell, nodal, m, &mut f)?;
                    }
                }
                Load::ShellThermal { cell, profile } => {
                    let m = item.mult.eval(t)?;
                    if m != 0.0 {
                        shell_thermal_load(model, *cell, profile.map(|v| v * m), &mut f)?;
                    }
                }
                Load::VolumeForceAt { cell, forces } => {
                    let m = item.mult.eval(t)?;
                    point_scheme(model, *cell, forces.len(), false)?;
                    volume_load(
                        model,
                        *cell,
                        |k| [forces[k][0] * m, forces[k][1] * m, forces[k][2] * m],
                        &mut f,
                    )?;
                }
                Load::Pressure { cell, pressure } if model.element_comps(*cell) == 6 => {
                    // A pressure on a shell: −p n at each node, n the
                    // facet's normal (DKT, te0032) or each node's
                    // (COQUE_3D, te0403 → fpres).
                    let p = pressure * item.mult.eval(t)?;
                    let n = model.mesh().cell(*cell).nodes.len();
                    let nodal = vec![[0., 0., 0., 0., 0., 0., p]; n];
                    shell_load(model, *cell, &nodal, 0.0, &mut f)?;
                }
                Load::Pressure { cell, .. } | Load::PressureAt { cell, .. } => {
                    let m = item.mult.eval(t)?;
                    let (scheme, values): (Vec<shape::GaussPoint>, Vec<f64>) = match &item.load {
                        Load::PressureAt { pressures, .. } => (
                            point_scheme(model, *cell, pressures.len(), true)?,
                            pressures.iter().map(|p| p * m).collect(),
                        ),
                        Load::Pressure { pressure, .. } => {
                            let scheme = shape::load_scheme(model.mesh().cell(*cell).ty);
                            let n = scheme.len();
                            (scheme, vec![pressure * m; n])
                        }
                        _ => unreachable!("matched above"),
                    };
                    let adj = faces.get_or_insert_with(|| inner_points(model));
                    let c = model.mesh().cell(*cell);
                    let mut key: Vec<NodeId> = c
                        .nodes
                        .iter()
                        .take(shape::corner_count(c.ty))
                        .copied()
                        .collect();
                    key.sort();
                    // One orientation for the whole face: outward from the
                    // volume cell it bounds (code_aster asks the mesh for
                    // outward faces, ORIE_PEAU and VERI_NORM).
                    let flip = adj
                        .get(&key)
                        .is_some_and(|inside| points_inward(model.mesh(), *cell, *inside));
                    surface_load(
                        model,
                        *cell,
                        &scheme,
                        |k, _, n| {
                            let p = if flip { -values[k] } else { values[k] };
                            [-p * n[0], -p * n[1], -p * n[2]]
                        },
                        &mut f,
                    )?;
                }
                _ => {}
            }
        }
        Ok(f)
    }
}

impl Loads {
    /// Where a load given point by point on a boundary cell takes its
    /// values ([`Load::SurfaceForceAt`], [`Load::PressureAt`]): the
    /// physical coordinates of the points of [`shape::skin_scheme`].
    pub fn skin_points(mesh: &aster_mesh::Mesh, cell: CellId) -> Vec<[f64; 3]> {
        shape::scheme_points(mesh, cell, &shape::skin_scheme(mesh.cell(cell).ty))
    }

    /// The free strain of a cell at time t at each node (Σ of its
    /// [`Load::FreeStrain`] items times their multipliers), `None` when
    /// no item acts on it.
    pub fn free_strain_at(&self, cell: CellId, t: f64) -> Result<Option<Vec<f64>>, FemError> {
        let mut out: Option<Vec<f64>> = None;
        for item in &self.items {
            if let Load::FreeStrain { cell: c, nodal } = &item.load {
                if *c != cell {
                    continue;
                }
                let m = item.mult.eval(t)?;
                let acc = out.get_or_insert_with(|| vec![0.0; nodal.len()]);
                for (a, v) in acc.iter_mut().zip(nodal) {
                    *a += m * v;
                }
            }
        }
        Ok(out)
    }

    /// Whether any load is a free strain (a temperature), of continuum
    /// cells or through the thickness of plates.
    pub fn has_free_strain(&self) -> bool {
        self.items
            .iter()
            .any(|i| matches!(i.load, Load::FreeStrain { .. } | Load::ShellThermal { .. }))
    }

    /// The free strain through the thickness of a plate facet at time t
    /// (Σ of its [`Load::ShellThermal`] profiles times their multipliers),
    /// `None` when no item acts on it.
    pub fn shell_thermal_at(
        &self,
        cell: CellId,
        t: f64,
    ) -> Result<Option<crate::plate::ThicknessProfile>, FemError> {
        let mut out: Option<crate::plate::ThicknessProfile> = None;
        for item in &self.items {
            if let Load::ShellThermal { cell: c, profile } = &item.load {
                if *c != cell {
                    continue;
                }
                let m = item.mult.eval(t)?;
                let acc = out.get_or_insert([0.0; 3]);
                for (a, v) in acc.iter_mut().zip(profile) {
                    *a += m * v;
                }
            }
        }
        Ok(out)
    }

    /// The nodal forces of the plates' free strains at time t alone
    /// ([`Load::ShellThermal`]), per DOF: what the elements' internal
    /// forces ∫ Bᵀ σ lose to the thermal strain (code_aster's FORC_NODA
    /// of a heated plate is K u minus these).
    pub fn shell_thermal_forces(&self, model: &Model, t: f64) -> Result<Vec<f64>, FemError> {
        let mut f = vec![0.0; model.dofs().len()];
        for item in &self.items {
            if let Load::ShellThermal { cell, profile } = &item.load {
                let m = item.mult.eval(t)?;
                if m != 0.0 {
                    shell_thermal_load(model, *cell, profile.map(|v| v * m), &mut f)?;
                }
            }
        }
        Ok(f)
    }

    /// σ = D (B u − ε_th): removes D ε_th from the stresses `D B u` of the
    /// cells with a free strain at time t (in place; `stress` as
    /// [`crate::post::sief_elga`] gives it).
    pub fn subtract_free_strain(
        &self,
        model: &Model,
        t: f64,
        stress: &mut [crate::post::CellValues],
    ) -> Result<(), FemError> {
        if !self.has_free_strain() {
            return Ok(());
        }
        for cv in stress.iter_mut() {
            let Some(nodal) = self.free_strain_at(cv.cell, t)? else {
                continue;
            };
            let Some(ElementKind::Continuum {
                hypothesis,
                material,
            }) = model.element_kind(cv.cell)
            else {
                continue;
            };
            let d = material.hooke(*hypothesis);
            let ty = model.mesh().cell(cv.cell).ty;
            let scheme = model.stiffness_scheme(cv.cell);
            for (gp, point) in scheme.iter().zip(cv.points.iter_mut()) {
                let s = shape::shape(ty, gp.xi);
                let e: f64 = s.n.iter().zip(nodal.iter()).map(|(n, v)| n * v).sum();
                for (a, p) in point.iter_mut().enumerate().take(d.nrows()) {
                    let de: f64 = (0..3.min(d.ncols())).map(|b| d[(a, b)] * e).sum();
                    *p -= de;
                }
            }
        }
        Ok(())
    }

    /// Where [`Load::VolumeForceAt`] takes its values: the points of the
    /// cell's stiffness scheme.
    pub fn volume_points(mesh: &aster_mesh::Mesh, cell: CellId) -> Vec<[f64; 3]> {
        shape::scheme_points(mesh, cell, &shape::rigi_scheme(mesh.cell(cell).ty))
    }

    /// [`Loads::volume_points`] of a model's cell: the reduced family of an
    /// under-integrated (`_SI`) cell, where code_aster's RIGI family is.
    pub fn model_volume_points(model: &Model, cell: CellId) -> Vec<[f64; 3]> {
        shape::scheme_points(model.mesh(), cell, &volume_scheme(model, cell))
    }
}

/// The points a volume load is integrated on: the cell's stiffness family
/// ([`Model::stiffness_scheme`]: code_aster's RIGI, the reduced family of
/// an `_SI` cell, FPG6 on an axisymmetric TRIA6), the one
/// [`volume_load`] integrates on.
fn volume_scheme(model: &Model, cell: CellId) -> Vec<shape::GaussPoint> {
    model.stiffness_scheme(cell)
}

/// The scheme of a load given at `count` points (skin or stiffness),
/// checked against the count.
fn point_scheme(
    model: &Model,
    cell: CellId,
    count: usize,
    skin: bool,
) -> Result<Vec<shape::GaussPoint>, FemError> {
    let ty = model.mesh().cell(cell).ty;
    let scheme = if skin {
        shape::skin_scheme(ty)
    } else {
        volume_scheme(model, cell)
    };
    if scheme.len() != count {
        return Err(FemError::Model(format!(
            "load on cell {} given at {count} points; its {} scheme has {}",
            model.cell_name(cell),
            ty.name(),
            scheme.len()
        )));
    }
    Ok(scheme)
}

fn index(model: &Model, dof: Dof) -> Result<usize, FemError> {
    model.dofs().index(dof).ok_or_else(|| {
        FemError::Model(format!(
            "{} is not a degree of freedom of the model",
            dof.describe(model.mesh())
        ))
    })
}

/// Boundary facets of continuum elements (sorted corner nodes) → a point
/// inside the element they bound (the centroid of its corners off the
/// facet), to orient pressure normals outward ([`points_inward`]).
pub(crate) fn inner_points(model: &Model) -> HashMap<Vec<NodeId>, [f64; 3]> {
    let mesh = model.mesh();
    let mut map = HashMap::new();
    for el in model.elements() {
        if !matches!(el.kind, ElementKind::Continuum { .. }) {
            continue;
        }
        let c = mesh.cell(el.cell);
        let nc = shape::corner_count(c.ty);
        for f in shape::facet_corners(c.ty) {
            // The centroid of the cell's corners off the face: on the
            // inner side whatever the cell's curvature or thickness (the
            // corners' centroid of a thin curved cell can lie beyond the
            // face's own points).
            let mut ctr = [0.0; 3];
            let off: Vec<NodeId> = (0..nc)
                .filter(|i| !f.contains(i))
                .map(|i| c.nodes[i])
                .collect();
            for &n in &off {
                let p = mesh.coord(n);
                for k in 0..3 {
                    ctr[k] += p[k] / off.len() as f64;
                }
            }
            let mut key: Vec<NodeId> = f.iter().map(|&i| c.nodes[i]).collect();
            key.sort();
            map.insert(key, ctr);
        }
    }
    map
}

/// Whether the normal of boundary cell `cell` (∂x/∂ξ × ∂x/∂η in 3D, the
/// tangent turned in 2D, as [`surface_load`] takes it), at its parametric
/// centre, points towards `inside` (a point inside the volume it bounds).
pub(crate) fn points_inward(mesh: &aster_mesh::Mesh, cell: CellId, inside: [f64; 3]) -> bool {
    let c = mesh.cell(cell);
    let refs = shape::reference_nodes(c.ty);
    let nc = shape::corner_count(c.ty).min(refs.len());
    if nc == 0 {
        return false;
    }
    let mut xi = [0.0; 3];
    for r in &refs[..nc] {
        for k in 0..3 {
            xi[k] += r[k] / nc as f64;
        }
    }
    let s = shape::shape(c.ty, xi);
    let [x, t1, t2] = shape::point_and_tangents(mesh, c, &s);
    let n = boundary_normal(c.ty.dim() as usize + 1, t1, t2);
    (0..3).map(|k| (inside[k] - x[k]) * n[k]).sum::<f64>() > 0.0
}

/// The (unnormalised) normal of a boundary cell from its tangents at a
/// point, in a model of dimension `dim`: (t_y, −t_x) of the tangent in 2D,
/// ∂x/∂ξ × ∂x/∂η in 3D.
fn boundary_normal(dim: usize, t1: [f64; 3], t2: [f64; 3]) -> [f64; 3] {
    if dim == 2 {
        [t1[1], -t1[0], 0.]
    } else {
        [
            t1[1] * t2[2] - t1[2] * t2[1],
            t1[2] * t2[0] - t1[0] * t2[2],
            t1[0] * t2[1] - t1[1] * t2[0],
        ]
    }
}

/// Adds a shell load (force, moment and pressure per unit area at each
/// node of the cell, global components) to `f`: see [`Load::ShellForce`].
fn shell_load(
    model: &Model,
    cell: CellId,
    nodal: &[[f64; 7]],
    offset: f64,
    f: &mut [f64],
) -> Result<(), FemError> {
    if model.is_coque3d(cell) {
        let err = |m: String| {
            FemError::Model(format!(
                "load on COQUE_3D cell {}: {m}",
                model.cell_name(cell)
            ))
        };
        let xyz = crate::element::coque3d_coords(model.mesh(), cell).map_err(err)?;
        let normals = crate::coque3d::node_normals(&xyz).map_err(err)?;
        // The edge nodes (the centre, last, takes no surface load).
        let forces: Vec<[f64; 3]> = nodal
            .iter()
            .zip(&normals)
            .map(|(v, n)| [0, 1, 2].map(|k| v[k] - v[6] * n[k]))
            .collect();
        let fe = crate::coque3d::surface_load(&xyz, &forces).map_err(err)?;
        let dofs = crate::element::element_dofs(model, cell);
        for (&i, v) in dofs.iter().zip(fe) {
            f[i] += v;
        }
        return Ok(());
    }
    let (n, facet) = shell_facet(model.mesh(), cell)?;
    let values: Vec<[f64; 6]> = nodal
        .iter()
        .map(|v| {
            let force = [0, 1, 2].map(|k| v[k] - v[6] * n[k]);
            // te0032's PLAN: the moment d (e_z × F) in the facet's frame.
            let nf = [
                n[1] * force[2] - n[2] * force[1],
                n[2] * force[0] - n[0] * force[2],
                n[0] * force[1] - n[1] * force[0],
            ];
            let [a, b, c] = force;
            [
                a,
                b,
                c,
                v[3] + offset * nf[0],
                v[4] + offset * nf[1],
                v[5] + offset * nf[2],
            ]
        })
        .collect();
    let c = model.mesh().cell(cell);
    for (&node, v) in c.nodes.iter().zip(shell_nodal_load(&facet, &values)) {
        let first = model.dofs().node_first(node).ok_or_else(|| {
            FemError::Model(format!(
                "load on shell cell {}: a node carries no element of the model",
                model.cell_name(cell)
            ))
        })?;
        for (k, x) in v.iter().enumerate() {
            f[first + k] += x;
        }
    }
    Ok(())
}

/// A DKT/DKQ facet's areas as its loads use them.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Facet {
    /// A triangle's area (`gtria3`).
    Triangle(f64),
    /// A quadrangle's corner triangles (i, i+1, i−1), their areas in the
    /// facet's plane (`gquad4`'s `airetr`).
    Quadrangle([f64; 4]),
}

impl Facet {
    #[cfg(test)]
    fn nodes(&self) -> usize {
        match self {
            Facet::Triangle(_) => 3,
            Facet::Quadrangle(_) => 4,
        }
    }
}

/// The nodal loads of values per unit area given at the nodes of a
/// DKT/DKQ facet (code_aster's dxtfor, dxqfor; the same in any frame, the
/// rule being linear and the same for every component): a triangle's node
/// gets its value × A/3; a quadrangle's node half the sum, over the corner
/// triangles it belongs to, of (its value/6 + the two others'/12) × the
/// triangle's area (a constant value: a sixth of those three areas).
fn shell_nodal_load(facet: &Facet, values: &[[f64; 6]]) -> Vec<[f64; 6]> {
    match facet {
        Facet::Triangle(area) => values.iter().map(|v| v.map(|x| x * area / 3.0)).collect(),
        Facet::Quadrangle(areas) => {
            let mut out = vec![[0.0; 6]; 4];
            for (t, a) in areas.iter().enumerate() {
                let tri = [t, (t + 1) % 4, (t + 3) % 4];
                for &j in &tri {
                    for k in 0..6 {
                        let others: f64 =
                            tri.iter().filter(|&&o| o != j).map(|&o| values[o][k]).sum();
                        out[j][k] += 0.5 * a * (values[j][k] / 6.0 + others / 12.0);
                    }
                }
            }
            out
        }
    }
}

/// A DKT/DKQ facet's normal (its local z axis: `dxtpgl`: (P2−P1)×(P3−P1);
/// `dxqpgl`: the cross product of the lines joining the mid-points of
/// opposite edges) and areas.
fn shell_facet(mesh: &aster_mesh::Mesh, cell: CellId) -> Result<([f64; 3], Facet), FemError> {
    let c = mesh.cell(cell);
    let x: Vec<[f64; 3]> = c.nodes.iter().map(|&n| mesh.coord(n)).collect();
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let unit = |a: [f64; 3]| {
        let l = dot(a, a).sqrt();
        if l > 0.0 && l.is_finite() {
            Ok([a[0] / l, a[1] / l, a[2] / l])
        } else {
            Err(FemError::Model(format!(
                "load on degenerate shell cell {}",
                mesh.cell_name(cell)
            )))
        }
    };
    match x.len() {
        3 => {
            let n = cross(sub(x[1], x[0]), sub(x[2], x[0]));
            let area = 0.5 * dot(n, n).sqrt();
            Ok((unit(n)?, Facet::Triangle(area)))
        }
        4 => {
            let mid = |a: usize, b: usize| {
                [
                    0.5 * (x[a][0] + x[b][0]),
                    0.5 * (x[a][1] + x[b][1]),
                    0.5 * (x[a][2] + x[b][2]),
                ]
            };
            let ex = unit(sub(mid(2, 1), mid(0, 3)))?;
            let n = unit(cross(ex, sub(mid(3, 2), mid(1, 0))))?;
            let ey = cross(n, ex);
            // Corner triangle areas in the facet's plane (`gquad4`).
            let local: Vec<[f64; 2]> = x.iter().map(|p| [dot(*p, ex), dot(*p, ey)]).collect();
            let corner = |i: usize| {
                let (prev, here, next) = (local[(i + 3) % 4], local[i], local[(i + 1) % 4]);
                let (a, b) = (
                    [next[0] - here[0], next[1] - here[1]],
                    [prev[0] - here[0], prev[1] - here[1]],
                );
                0.5 * (a[0] * b[1] - a[1] * b[0])
            };
            Ok((
                n,
                Facet::Quadrangle([corner(0), corner(1), corner(2), corner(3)]),
            ))
        }
        k => Err(FemError::Model(format!(
            "load on shell cell {}: a DKT facet has 3 or 4 nodes, not {k}",
            mesh.cell_name(cell)
        ))),
    }
}

/// Integrates a traction t(x, n) over a boundary cell into `f`. In 2D the
/// normal is (t_y, −t_x) of the tangent (node 1 → node 2); in 3D it is
/// ∂x/∂ξ × ∂x/∂η. Callers re-orient it when they need the outward one.
fn surface_load(
    model: &Model,
    cell: CellId,
    scheme: &[shape::GaussPoint],
    traction: impl Fn(usize, &[f64; 3], &[f64; 3]) -> [f64; 3],
    f: &mut [f64],
) -> Result<(), FemError> {
    let mesh = model.mesh();
    let c = mesh.cell(cell);
    let dim = model.dim();
    let axis = model.hypothesis() == Some(Hypothesis::Axisymmetric);
    for (k, gp) in scheme.iter().enumerate() {
        let s = shape::shape(c.ty, gp.xi);
        let [x, t1, t2] = shape::point_and_tangents(mesh, c, &s);
        let n = boundary_normal(dim, t1, t2);
        let jac = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let normal = [n[0] / jac, n[1] / jac, n[2] / jac];
        if jac.is_nan() || jac <= 0. {
            return Err(FemError::Model(format!(
                "distributed load on degenerate cell {}",
                model.cell_name(cell)
            )));
        }
        let mut w = gp.weight * jac;
        if axis {
            w *= x[0];
        }
        let tr = traction(k, &x, &normal);
        for (i, &n) in c.nodes.iter().enumerate() {
            let first = model.dofs().node_first(n).ok_or_else(|| {
                FemError::Model(format!(
                    "distributed load on cell {}: a node carries no element of the model",
                    model.cell_name(cell)
                ))
            })?;
            for k in 0..dim {
                f[first + k] += w * s.n[i] * tr[k];
            }
        }
    }
    Ok(())
}

/// The DOF of each component an edge force gives (zero components skipped):
/// checks that the cell is a segment of a 3D model whose nodes carry them.
fn edge_dofs(
    model: &Model,
    cell: CellId,
    force: &[f64; 6],
) -> Result<Vec<Vec<(usize, usize)>>, FemError> {
    let mesh = model.mesh();
    let Some(c) = mesh.cells.get(cell.0 as usize) else {
        return Err(FemError::Model(format!(
            "edge force on cell #{} which the mesh does not have",
            cell.0 + 1
        )));
    };
    if !matches!(c.ty, CellType::SEG2 | CellType::SEG3) || model.dim() != 3 {
        return Err(FemError::Model(format!(
            "edge force (FORCE_ARETE) on cell {} ({}): expected a segment (SEG2, SEG3) of a 3D model",
            model.cell_name(cell),
            c.ty.name()
        )));
    }
    let mut out = Vec::with_capacity(c.nodes.len());
    for &n in &c.nodes {
        let mut dofs = Vec::new();
        for (k, comp) in crate::dof::Comp::ALL.iter().enumerate() {
            if force[k] == 0.0 {
                continue;
            }
            let i = model.dofs().index(Dof::new(n, *comp)).ok_or_else(|| {
                FemError::Model(format!(
                    "edge force (FORCE_ARETE) on cell {}: node {} has no {} (moments need the rotations of shell nodes; every node must carry an element of the model)",
                    model.cell_name(cell),
                    mesh.node_names.get(n.0 as usize).map(String::as_str).unwrap_or("?"),
                    comp.name()
                ))
            })?;
            dofs.push((k, i));
        }
        out.push(dofs);
    }
    Ok(out)
}

/// The Gauss family an edge load (`FORCE_ARETE`) is integrated with: the
/// `RIGI` family of the element code_aster puts on the segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeRule {
    /// The segment's own stiffness family, 2 points on SEG2 and 3 on SEG3:
    /// `MECA_ARETE2`/`MECA_ARETE3` on the edges of solids (te0469) and
    /// `MEBODKT` on those of DKT/DST/Q4G plates (te0034, whose f·L/2 per
    /// node is the same on a straight SEG2).
    Segment,
    /// `MEBOCQ3`, the SEG3 edge of COQUE_3D cells (te0418): `FPG4`, Gauss
    /// with 4 points (±√(3/7 ∓ 2/7·√(6/5)), weights (18 ± √30)/36), in
    /// `elraga`'s order.
    Gauss4,
}

impl EdgeRule {
    /// The points and weights on the reference segment [−1, 1].
    pub fn scheme(self, ty: CellType) -> Vec<shape::GaussPoint> {
        match self {
            EdgeRule::Segment => shape::rigi_scheme(ty),
            EdgeRule::Gauss4 => {
                let a = (3.0 / 7.0 - 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
                let b = (3.0 / 7.0 + 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
                let (wa, wb) = ((18.0 + 30f64.sqrt()) / 36.0, (18.0 - 30f64.sqrt()) / 36.0);
                [(a, wa), (-a, wa), (b, wb), (-b, wb)]
                    .into_iter()
                    .map(|(x, weight)| shape::GaussPoint {
                        xi: [x, 0.0, 0.0],
                        weight,
                    })
                    .collect()
            }
        }
    }
}

fn edge_check(model: &Model, cell: CellId, force: &[f64; 6]) -> Result<(), FemError> {
    edge_dofs(model, cell, force).map(|_| ())
}

/// ∫ Nᵢ f dl over a segment with the Gauss family of its edge element
/// ([`EdgeRule`]), f constant along it.
fn edge_load(
    model: &Model,
    cell: CellId,
    force: &[f64; 6],
    rule: EdgeRule,
    f: &mut [f64],
) -> Result<(), FemError> {
    let dofs = edge_dofs(model, cell, force)?;
    let mesh = model.mesh();
    let c = mesh.cell(cell);
    for gp in rule.scheme(c.ty) {
        let s = shape::shape(c.ty, gp.xi);
        let [_, t, _] = shape::point_and_tangents(mesh, c, &s);
        let jac = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
        if !(jac > 0.0 && jac.is_finite()) {
            return Err(FemError::Model(format!(
                "edge force on degenerate cell {}",
                model.cell_name(cell)
            )));
        }
        let w = gp.weight * jac;
        for (i, node_dofs) in dofs.iter().enumerate() {
            for &(k, idx) in node_dofs {
                f[idx] += w * s.n[i] * force[k];
            }
        }
    }
    Ok(())
}

/// ∫ Bᵀ (N, M) of a free strain through a plate facet's thickness
/// ([`crate::plate::thermal_load`]) added into `f`.
fn shell_thermal_load(
    model: &Model,
    cell: CellId,
    profile: crate::plate::ThicknessProfile,
    f: &mut [f64],
) -> Result<(), FemError> {
    let Some(ElementKind::Shell {
        material,
        section,
        theory,
    }) = model.element_kind(cell)
    else {
        return Err(FemError::Model(format!(
            "thermal strain through the thickness on cell {}, which carries no plate element",
            model.cell_name(cell)
        )));
    };
    let c = model.mesh().cell(cell);
    let xyz: Vec<[f64; 3]> = c.nodes.iter().map(|&n| model.mesh().coord(n)).collect();
    let fe = crate::plate::thermal_load(*theory, &xyz, material, section, profile)
        .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(cell))))?;
    let dofs = crate::element::element_dofs(model, cell);
    for (j, &dof) in dofs.iter().enumerate() {
        f[dof] += fe[j];
    }
    Ok(())
}

/// Integrates a constant body force b over a continuum cell into `f`
/// (∫ Nᵢ b dV with the stiffness Gauss scheme; ×r in axisymmetry, as the
/// stiffness is).
/// ∫ Bᵀ D ε_th over a continuum cell, ε_th = m Σ Nᵢ εᵢ on xx, yy, zz.
fn free_strain_load(
    model: &Model,
    cell: CellId,
    nodal: &[f64],
    m: f64,
    f: &mut [f64],
) -> Result<(), FemError> {
    let Some(ElementKind::Continuum {
        hypothesis,
        material,
    }) = model.element_kind(cell)
    else {
        return Err(FemError::Model(format!(
            "thermal strain on cell {}, which carries no continuum element",
            model.cell_name(cell)
        )));
    };
    if model.is_stabilised(cell) || model.is_reduced(cell) {
        return Err(FemError::Model(format!(
            "thermal strain on the under-integrated cell {} is not implemented",
            model.cell_name(cell)
        )));
    }
    let d = material.hooke(*hypothesis);
    let ty = model.mesh().cell(cell).ty;
    let gauss = crate::element::model_gauss(model, cell, *hypothesis)
        .map_err(|m| FemError::Model(format!("cell {}: {m}", model.cell_name(cell))))?;
    let scheme = model.stiffness_scheme(cell);
    let dofs = crate::element::element_dofs(model, cell);
    for (gp, g) in scheme.iter().zip(gauss.iter()) {
        let s = shape::shape(ty, gp.xi);
        let e: f64 = m * s
            .n
            .iter()
            .zip(nodal.iter())
            .map(|(n, v)| n * v)
            .sum::<f64>();
        let mut sig = vec![0.0; d.nrows()];
        for (a, sa) in sig.iter_mut().enumerate() {
            *sa = (0..3.min(d.ncols())).map(|b| d[(a, b)] * e).sum();
        }
        for (j, &dof) in dofs.iter().enumerate() {
            let mut v = 0.0;
            for (a, sa) in sig.iter().enumerate() {
                v += g.b[(a, j)] * sa;
            }
            f[dof] += g.w * v;
        }
    }
    Ok(())
}

fn volume_load(
    model: &Model,
    cell: CellId,
    force: impl Fn(usize) -> [f64; 3],
    f: &mut [f64],
) -> Result<(), FemError> {
    if model.is_stabilised(cell) {
        return Err(FemError::Model(format!(
            "volume loads on the under-integrated HEXA8 of 3D_SI (cell {}) are not implemented",
            model.cell_name(cell)
        )));
    }
    let mesh = model.mesh();
    let c = mesh.cell(cell);
    let dim = model.dim();
    let axis = model.hypothesis() == Some(Hypothesis::Axisymmetric);
    for (g, gp) in model.stiffness_scheme(cell).into_iter().enumerate() {
        let b = force(g);
        let s = shape::shape(c.ty, gp.xi);
        // Jacobian J[k][l] = ∂x_k/∂ξ_l.
        let mut jac = [[0.0; 3]; 3];
        let mut x = [0.0; 3];
        for (i, &n) in c.nodes.iter().enumerate() {
            let p = mesh.coord(n);
            for k in 0..3 {
                x[k] += s.n[i] * p[k];
                for l in 0..3 {
                    jac[k][l] += s.dn[i][l] * p[k];
                }
            }
        }
        let det = if dim == 2 {
            jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0]
        } else {
            jac[0][0] * (jac[1][1] * jac[2][2] - jac[1][2] * jac[2][1])
                - jac[0][1] * (jac[1][0] * jac[2][2] - jac[1][2] * jac[2][0])
                + jac[0][2] * (jac[1][0] * jac[2][1] - jac[1][1] * jac[2][0])
        };
        // An inverted cell integrates with |J|, as its stiffness does
        // (code_aster's dfdm2d/dfdm3d); a degenerate one is an error.
        if det.is_nan() || det == 0.0 {
            return Err(FemError::Model(format!(
                "volume force on cell {}: its Jacobian is zero (a degenerate cell)",
                model.cell_name(cell)
            )));
        }
        let mut w = gp.weight * det.abs();
        if axis {
            w *= x[0];
        }
        for (i, &n) in c.nodes.iter().enumerate() {
            let first = model.dofs().node_first(n).ok_or_else(|| {
                FemError::Model(format!(
                    "volume force on cell {}: a node carries no element of the model",
                    model.cell_name(cell)
                ))
            })?;
            for k in 0..dim {
                f[first + k] += w * s.n[i] * b[k];
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod shell_load_tests {
    use super::{shell_facet, shell_nodal_load};
    use aster_mesh::{Cell, CellId, CellType, Mesh, NodeId};

    /// The nodal weights of a constant unit value and the facet's normal.
    fn weights(m: &Mesh) -> ([f64; 3], Vec<f64>) {
        let (n, facet) = shell_facet(m, CellId(0)).unwrap();
        let ones = vec![[1.0; 6]; facet.nodes()];
        (
            n,
            shell_nodal_load(&facet, &ones)
                .iter()
                .map(|v| v[0])
                .collect(),
        )
    }

    fn mesh(points: &[[f64; 3]], ty: CellType) -> Mesh {
        Mesh {
            dim: 3,
            coords: points.to_vec(),
            node_names: (0..points.len()).map(|i| format!("N{i}")).collect(),
            cells: vec![Cell {
                ty,
                nodes: (0..points.len() as u32).map(NodeId).collect(),
            }],
            cell_names: vec!["M1".into()],
            ..Mesh::default()
        }
    }

    /// A parallelogram gives A/4 per node, a triangle A/3; the normal is the
    /// facet's local z (right-handed with the node order).
    #[test]
    fn parallelogram_and_triangle_weights() {
        let q = mesh(
            &[[0., 0., 0.], [2., 0., 0.], [3., 1., 0.], [1., 1., 0.]],
            CellType::QUAD4,
        );
        let (n, w) = weights(&q);
        assert!((n[2] - 1.0).abs() < 1e-15 && n[0].abs() < 1e-15);
        for x in &w {
            assert!((x - 0.5).abs() < 1e-14, "{w:?}");
        }
        let t = mesh(&[[0., 0., 0.], [0., 0., 3.], [0., 2., 0.]], CellType::TRIA3);
        let (n, w) = weights(&t);
        assert!((n[0] + 1.0).abs() < 1e-15, "{n:?}"); // (0,0,3)×(0,2,0) = (−6,0,0)
        for x in &w {
            assert!((x - 1.0).abs() < 1e-14, "{w:?}");
        }
    }

    /// A trapezoid: each node receives a sixth of the three corner
    /// triangles it belongs to (code_aster's dxqfor), not the bilinear
    /// ∫N dA; the weights still sum to the area.
    #[test]
    fn trapezoid_weights_are_code_aster_corner_triangles() {
        let q = mesh(
            &[[0., 0., 0.], [4., 0., 0.], [3., 1., 0.], [1., 1., 0.]],
            CellType::QUAD4,
        );
        let (_, w) = weights(&q);
        // Corner triangle areas: at node 1: 2, 2: 2, 3: 1, 4: 1.
        let t = [2.0, 2.0, 1.0, 1.0];
        let expect: Vec<f64> = (0..4).map(|i| (6.0 - t[(i + 2) % 4]) / 6.0).collect();
        for (a, b) in w.iter().zip(&expect) {
            assert!((a - b).abs() < 1e-14, "{w:?} vs {expect:?}");
        }
        assert!((w.iter().sum::<f64>() - 3.0).abs() < 1e-14);
        assert!((w[0] - 5.0 / 6.0).abs() < 1e-14 && (w[2] - 2.0 / 3.0).abs() < 1e-14);
    }
}

#[cfg(test)]
mod shell_nodal_tests {
    use super::{shell_nodal_load, Facet};

    /// dxqfor with values varying over the nodes: each corner triangle
    /// (i, i+1, i−1) gives its node (f_i/6 + (f_j + f_k)/12)·A, halved;
    /// the total is the mean over the four triangles of A·(f_i+f_j+f_k)/3
    /// summed, i.e. half of Σ_t A_t·mean_t.
    #[test]
    fn quadrangle_of_varying_values_follows_dxqfor() {
        let areas = [2.0, 2.0, 1.0, 1.0];
        let f = [1.0, 2.0, 3.0, 4.0];
        let values: Vec<[f64; 6]> = f.iter().map(|&x| [x, 0., 0., 0., 0., 0.]).collect();
        let out = shell_nodal_load(&Facet::Quadrangle(areas), &values);
        // Node 1 (index 0) is in triangles 0 (0,1,3), 1 (1,2,0), 3 (3,0,2).
        let node0 = 0.5
            * (areas[0] * (f[0] / 6.0 + (f[1] + f[3]) / 12.0)
                + areas[1] * (f[0] / 6.0 + (f[1] + f[2]) / 12.0)
                + areas[3] * (f[0] / 6.0 + (f[3] + f[2]) / 12.0));
        assert!((out[0][0] - node0).abs() < 1e-14, "{out:?}");
        let total: f64 = out.iter().map(|v| v[0]).sum();
        let expect: f64 = 0.5
            * (0..4)
                .map(|t| areas[t] * (f[t] + f[(t + 1) % 4] + f[(t + 3) % 4]) / 3.0)
                .sum::<f64>();
        assert!((total - expect).abs() < 1e-13, "{total} vs {expect}");
        // A triangle: each node its own value × A/3, no mixing (dxtfor).
        let tri = shell_nodal_load(&Facet::Triangle(3.0), &values[..3]);
        assert_eq!(
            tri.iter().map(|v| v[0]).collect::<Vec<_>>(),
            vec![1.0, 2.0, 3.0]
        );
    }
}

#[cfg(test)]
mod edge_rule_tests {
    use super::EdgeRule;
    use aster_mesh::CellType;

    fn integral(rule: EdgeRule, p: impl Fn(f64) -> f64) -> f64 {
        rule.scheme(CellType::SEG3)
            .iter()
            .map(|g| g.weight * p(g.xi[0]))
            .sum()
    }

    /// te0418's FPG4 (elraga): 4 points, ±0.3399810… and ±0.8611363…,
    /// exact up to degree 7 where the SEG3's own FPG3 stops at 5.
    #[test]
    fn gauss4_is_code_aster_fpg4_and_exact_to_degree_7() {
        let s = EdgeRule::Gauss4.scheme(CellType::SEG3);
        assert_eq!(s.len(), 4);
        assert!((s[0].xi[0] - 0.339_981_043_584_856).abs() < 1e-14);
        assert!((s[2].xi[0] - 0.861_136_311_594_053).abs() < 1e-14);
        assert!((s[0].weight - 0.652_145_154_862_546).abs() < 1e-14);
        for k in 0..=7 {
            let exact = if k % 2 == 0 {
                2.0 / (k as f64 + 1.0)
            } else {
                0.0
            };
            let got = integral(EdgeRule::Gauss4, |x| x.powi(k));
            assert!((got - exact).abs() < 1e-14, "degree {k}: {got} vs {exact}");
        }
        // x^6 tells the two families apart.
        let fpg3 = integral(EdgeRule::Segment, |x| x.powi(6));
        assert!((fpg3 - 2.0 / 7.0).abs() > 1e-3, "{fpg3}");
        assert_eq!(EdgeRule::Segment.scheme(CellType::SEG2).len(), 2);
    }
}
