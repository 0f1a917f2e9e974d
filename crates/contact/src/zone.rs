//! What `DEFI_CONTACT` describes, as plain Rust values: the formulation,
//! its global loop settings and one [`Zone`] per `ZONE` occurrence.
//!
//! Types are shaped so that a discrete zone cannot carry a continuous
//! algorithm and vice versa. Defaults are code_aster 17's catalog defaults.

use std::fmt;
use std::sync::Arc;

use crate::error::ContactError;

/// `APPARIEMENT`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Appariement {
    /// `MAIT_ESCL`: orthogonal projection of slave points onto master cells.
    #[default]
    MaitEscl,
    /// `NODAL`: the nearest master node.
    Nodal,
}

/// `VECT_MAIT` / `VECT_ESCL`: how a side's normal is obtained.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum NormalSource {
    /// `AUTO`: from the cell geometry, oriented outwards of the body.
    #[default]
    Auto,
    /// `FIXE` with `MAIT_FIXE`/`ESCL_FIXE`: this (normalised) vector.
    Fixed([f64; 3]),
    /// `VECT_Y` with `MAIT_VECT_Y`/`ESCL_VECT_Y`: on a segment, the normal
    /// is its tangent crossed with this vector (beams in 3D); on a face, the
    /// face's normal without its component along this vector (code_aster's
    /// `aptgnn`), whatever the order of the face's nodes.
    VectY([f64; 3]),
}

/// `NORMALE`: which side's normal carries the contact direction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum NormalChoice {
    #[default]
    Mait,
    Escl,
    MaitEscl,
}

/// An extra gap (`DIST_MAIT`, `DIST_ESCL`): thickness of shells or beams
/// modelled by their mid-surface. A function of the point coordinates, or
/// of the time (`NOM_PARA='INST'`).
#[derive(Clone, Default)]
pub enum Offset {
    #[default]
    Zero,
    Constant(f64),
    Function(Arc<dyn Fn([f64; 3]) -> f64 + Send + Sync>),
    /// A function of the time of the pairing.
    OfTime(Arc<dyn Fn(f64) -> f64 + Send + Sync>),
}

impl Offset {
    /// The offset at a point (a function of time is taken at t = 0).
    pub fn at(&self, x: [f64; 3]) -> f64 {
        self.at_time(x, 0.0)
    }

    /// The offset at a point and time.
    pub fn at_time(&self, x: [f64; 3], t: f64) -> f64 {
        match self {
            Offset::Zero => 0.0,
            Offset::Constant(c) => *c,
            Offset::Function(f) => f(x),
            Offset::OfTime(f) => f(t),
        }
    }

    pub fn depends_on_time(&self) -> bool {
        matches!(self, Offset::OfTime(_))
    }
}

impl fmt::Debug for Offset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Offset::Zero => write!(f, "Zero"),
            Offset::Constant(c) => write!(f, "Constant({c})"),
            Offset::Function(_) => write!(f, "Function(..)"),
            Offset::OfTime(_) => write!(f, "OfTime(..)"),
        }
    }
}

/// The geometric part of a zone, shared by all formulations.
#[derive(Clone, Debug)]
pub struct ZoneGeometry {
    /// `GROUP_MA_MAIT`.
    pub master_group: String,
    /// `GROUP_MA_ESCL`.
    pub slave_group: String,
    /// `SANS_GROUP_NO`: slave nodes never paired.
    pub excluded_node_groups: Vec<String>,
    /// `SANS_GROUP_MA`: the nodes of these cells are never paired.
    pub excluded_cell_groups: Vec<String>,
    pub appariement: Appariement,
    pub vect_mait: NormalSource,
    pub vect_escl: NormalSource,
    pub normale: NormalChoice,
    /// `DIST_APPA` (legacy `TOLE_APPA`): a slave point is paired only if its
    /// nearest master node is within this distance. `None` = no limit
    /// (code_aster's default -1, and any value ≤ 0).
    pub dist_appa: Option<f64>,
    /// `TOLE_PROJ_EXT`: how far outside the master cell a projection is
    /// still accepted, in reference (parametric) coordinates. Negative =
    /// no limit.
    pub tole_proj_ext: f64,
    pub dist_mait: Offset,
    pub dist_escl: Offset,
    /// `RESOLUTION='NON'`: pair and report, never enforce.
    pub resolve: bool,
    /// `TOLE_INTERP` (with `RESOLUTION='NON'`): interpenetration allowed
    /// before the pairing-only zone reports it.
    pub tole_interp: f64,
    /// `STOP_INTERP='OUI'` (with `RESOLUTION='NON'`): a converged step
    /// whose slave nodes interpenetrate by more than `tole_interp` stops
    /// the analysis ([`aster_fem::FemError::Interpenetration`]).
    pub stop_interp: bool,
    /// `LISSAGE='OUI'`: smoothed master normals — the outward normals
    /// averaged at the master nodes, interpolated with the shape functions
    /// inside each cell, so the normal is continuous from cell to cell.
    /// Default (code_aster's `'NON'`): the normal of the cell the slave
    /// point projects on.
    pub lissage: bool,
    /// `GLISSIERE='OUI'`: bilateral sliding contact — links that never
    /// open. Discrete (code_aster's `cfinal` + `algogl`): every paired
    /// slave node is linked from the first pairing, whatever its gap.
    /// Continuous (`mmopti`, `mmglis`, `mm_cycl_algo`): a slave point is
    /// linked from the start as `contact_init` says, and once it has been
    /// in contact at a converged state it stays linked.
    pub glissiere: bool,
    /// `CONTACT_INIT` (continuous zones): which points start in contact.
    /// It only changes the path of the active set, except with
    /// `glissiere`, where it says which points are linked from the start.
    pub contact_init: ContactInit,
    /// `DIST_MAXI` (with `CONTACT_INIT='INTERPENETRE'`, code_aster 17):
    /// the initial gap below which a point starts in contact (default: 1e-6
    /// × the shortest edge of the mesh).
    pub dist_maxi: Option<f64>,
    /// `TYPE_PROJECTION='FIXE'` with `DIRE_APPA`: slave points are
    /// projected on the master cells along this (unit) direction instead
    /// of orthogonally (code_aster's `mmnewd`); the normal stays the master
    /// cell's.
    pub dire_appa: Option<[f64; 3]>,
    /// Continuous `ALGO_CONT='PENALISATION'` with `ADAPTATION='ADAPT_COEF'`
    /// or `'TOUT'`: code_aster raises the penalty coefficient at a point
    /// whose penetration exceeds this (`PENE_MAXI`, or 1 % of the shortest
    /// master cell). That adaptation (Bussetta's rule, `mm_cycl_algo`) is
    /// not reproduced: a converged step whose penetration stays below the
    /// limit is code_aster's; one that exceeds it is an error.
    pub pene_maxi: Option<f64>,
    /// `DIST_POUTRE='OUI'`: the radius of each slave beam cell's circular
    /// section (`CARA_ELEM`), added to the gap (code_aster's `capoco`,
    /// `cfdist`; at a node, the mean over its slave cells, `cfdism`).
    /// `None`: no such offset.
    pub beam_radius: Option<std::collections::BTreeMap<aster_mesh::CellId, f64>>,
    /// `DIST_COQUE='OUI'`: half the thickness of each slave shell cell
    /// (`CARA_ELEM`, `EPAIS`/2), added to the gap as the beams' radii are
    /// (code_aster's `cacoco`, `cfdist`: the slave side only, summed with
    /// `DIST_POUTRE`'s). `None`: no such offset.
    pub shell_half_thickness: Option<std::collections::BTreeMap<aster_mesh::CellId, f64>>,
    /// The QUAD9 and TRIA7 cells carrying code_aster's `COQUE_3D`: their
    /// centre node (rotations only) is no contact node (`cflecq`), and
    /// contact sees the face through its other nodes, as a QUAD8 / TRIA6
    /// (`mmtypm`: geometry, projection and the master coefficients of
    /// `cfreli` with the QU8 / TR6 functions), without the QUAD8
    /// middle-node treatment (`cfleqa` counts no middle node on a QUAD9).
    pub coque3d_cells: std::collections::BTreeSet<aster_mesh::CellId>,
}

/// `CONTACT_INIT` of a continuous zone.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ContactInit {
    /// `'OUI'`: every point.
    Oui,
    /// `'INTERPENETRE'` (default): the points whose initial gap is at most
    /// 1e-6 × the shortest edge of the mesh (code_aster's `epsint`).
    #[default]
    Interpenetre,
    /// `'NON'`: none.
    Non,
}

impl ZoneGeometry {
    /// A zone with code_aster's defaults.
    pub fn new(master_group: impl Into<String>, slave_group: impl Into<String>) -> Self {
        ZoneGeometry {
            master_group: master_group.into(),
            slave_group: slave_group.into(),
            excluded_node_groups: Vec::new(),
            excluded_cell_groups: Vec::new(),
            appariement: Appariement::MaitEscl,
            vect_mait: NormalSource::Auto,
            vect_escl: NormalSource::Auto,
            normale: NormalChoice::Mait,
            dist_appa: None,
            tole_proj_ext: 0.5,
            dist_mait: Offset::Zero,
            dist_escl: Offset::Zero,
            resolve: true,
            tole_interp: 0.0,
            stop_interp: false,
            lissage: false,
            glissiere: false,
            contact_init: ContactInit::Interpenetre,
            dist_maxi: None,
            dire_appa: None,
            pene_maxi: None,
            beam_radius: None,
            shell_half_thickness: None,
            coque3d_cells: Default::default(),
        }
    }

    /// Sets `DIST_APPA`/`TOLE_APPA` with code_aster's meaning: a value ≤ 0
    /// means "no limit".
    pub fn with_dist_appa(mut self, d: f64) -> Self {
        self.dist_appa = (d > 0.0).then_some(d);
        self
    }

    /// Sets `VECT_MAIT='FIXE'` with `MAIT_FIXE`; the vector must not be zero.
    pub fn with_fixed_master_normal(mut self, v: [f64; 3]) -> Result<Self, ContactError> {
        self.vect_mait = NormalSource::Fixed(normalised(v, "MAIT_FIXE")?);
        Ok(self)
    }
}

pub(crate) fn normalised(v: [f64; 3], keyword: &'static str) -> Result<[f64; 3], ContactError> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n.is_finite() && n > 0.0 {
        Ok([v[0] / n, v[1] / n, v[2] / n])
    } else {
        Err(ContactError::Invalid {
            keyword,
            message: format!("the vector {v:?} has no direction"),
        })
    }
}

/// `ALGO_CONT` of a discrete zone.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum DiscreteAlgo {
    /// `CONTRAINTE`: exact, active set on Lagrange multipliers.
    #[default]
    Contrainte,
    /// `PENALISATION` with `E_N` (force per unit interpenetration).
    Penalisation { e_n: f64 },
    /// `GCP`: projected conjugate gradient on the multipliers (MPRGP),
    /// matrix-free. `resi_abso`: tolerance on the projected gradient
    /// (an interpenetration), `None` = 1e-10 × the largest initial gap
    /// violation; `iter_maxi`: 0 = 10 × number of points (at least 100).
    Gcp {
        resi_abso: Option<f64>,
        iter_maxi: usize,
    },
}

/// `INTEGRATION` of a continuous zone (with `ORDRE_INT`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Integration {
    /// `AUTO`: at the nodes of the slave cells (Newton–Cotes weights).
    #[default]
    Auto,
    /// Gauss with code_aster's `ORDRE_INT` (`mmgaus`): on segments that
    /// many Gauss–Legendre points, on quadrangles their square, on
    /// triangles the rule of that rank (1, 3, 4, 6, 7, 12 points, exact
    /// to degree 1…6).
    Gauss(u8),
    /// Composite Simpson with the given number of sub-intervals pairs (segments).
    Simpson(u8),
    /// Newton–Cotes with `order + 1` equally spaced points (segments).
    NCotes(u8),
}

/// `ALGO_CONT` of a continuous zone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContinueAlgo {
    /// `STANDARD`: augmented Lagrangian with `COEF_CONT` (default 100).
    Standard { coef_cont: f64 },
    /// `PENALISATION` with `COEF_PENA_CONT` (pressure per unit interpenetration).
    Penalisation { coef_pena_cont: f64 },
    /// `LAC` (with `APPARIEMENT='MORTAR'`): one pressure per DECOUPE_LAC
    /// patch, mortar-integrated gap (module `lac`); the zone needs its
    /// patches (`ZoneContact::set_lac_patches`).
    Lac,
}

impl Default for ContinueAlgo {
    fn default() -> Self {
        ContinueAlgo::Standard { coef_cont: 100.0 }
    }
}

/// A zone: its geometry and the law of its formulation.
#[derive(Clone, Debug)]
pub struct Zone<L> {
    pub geometry: ZoneGeometry,
    pub law: L,
}

/// The law of a continuous zone.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContinueLaw {
    pub algo: ContinueAlgo,
    pub integration: Integration,
}

/// `ALGO_RESO_CONT` / `ALGO_RESO_GEOM`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Resolution {
    #[default]
    Newton,
    PointFixe,
}

/// `REAC_GEOM`: the geometric loop (pairing on the deformed geometry).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GeomLoop {
    /// Re-pair until the displacement change between two pairings is below
    /// `resi_geom` (relative), at most `iter_maxi` times.
    Automatique { iter_maxi: usize, resi_geom: f64 },
    /// Re-pair exactly `nb_iter` times per step.
    Controle { nb_iter: usize },
    /// Pair once, on the initial geometry.
    Sans,
}

impl Default for GeomLoop {
    fn default() -> Self {
        GeomLoop::Automatique {
            iter_maxi: 10,
            resi_geom: 0.01,
        }
    }
}

/// `FROTTEMENT`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Frottement {
    #[default]
    Sans,
    Coulomb,
}

/// The whole `DEFI_CONTACT` (formulations DISCRETE and CONTINUE;
/// LIAISON_UNIL is the fem crate's).
#[derive(Clone, Debug)]
pub enum ContactDefinition {
    Discrete(DiscreteDefinition),
    Continue(ContinueDefinition),
}

#[derive(Clone, Debug)]
pub struct DiscreteDefinition {
    pub zones: Vec<Zone<DiscreteAlgo>>,
    pub geom_loop: GeomLoop,
    /// `ITER_CONT_MULT`: the active set may change at most
    /// `ITER_CONT_MULT × number of points` times (default 4).
    pub iter_cont_mult: usize,
    /// `STOP_SINGULIER`: stop on a singular contact matrix (default yes);
    /// with `false` the redundant point is dropped.
    pub stop_singulier: bool,
    /// `FROTTEMENT='COULOMB'`: the zones' friction (module `friction`).
    pub friction: Option<crate::friction::DiscreteFrictionDef>,
}

#[derive(Clone, Debug)]
pub struct ContinueDefinition {
    pub zones: Vec<Zone<ContinueLaw>>,
    pub geom_loop: GeomLoop,
    pub algo_reso_cont: Resolution,
    pub algo_reso_geom: Resolution,
    /// `ITER_CONT_MAXI` (default 30) for the fixed-point contact loop.
    pub iter_cont_maxi: usize,
    /// `RESI_CONT`: relative change of the pressures that ends the
    /// contact loop; code_aster's default -1 means "active set stable".
    pub resi_cont: Option<f64>,
    /// `FROTTEMENT='COULOMB'`: the zones' friction (module `friction`).
    pub friction: Option<crate::friction::ContinueFriction>,
}

impl ContactDefinition {
    /// A discrete definition with code_aster's defaults. Refuses friction.
    pub fn discrete(
        zones: Vec<Zone<DiscreteAlgo>>,
        frottement: Frottement,
    ) -> Result<Self, ContactError> {
        refuse_friction(frottement)?;
        check_zones(&zones)?;
        for z in &zones {
            if let DiscreteAlgo::Penalisation { e_n } = z.law {
                positive("E_N", e_n)?;
            }
        }
        Ok(ContactDefinition::Discrete(DiscreteDefinition {
            zones,
            geom_loop: GeomLoop::default(),
            iter_cont_mult: 4,
            stop_singulier: true,
            friction: None,
        }))
    }

    /// A discrete definition with Coulomb friction (`ALGO_FROT=
    /// 'PENALISATION'`), one friction setting per zone.
    pub fn discrete_with_friction(
        zones: Vec<Zone<DiscreteAlgo>>,
        friction: crate::friction::DiscreteFrictionDef,
    ) -> Result<Self, ContactError> {
        friction.check(zones.len())?;
        let mut d = ContactDefinition::discrete(zones, Frottement::Sans)?;
        if let ContactDefinition::Discrete(dd) = &mut d {
            dd.friction = Some(friction);
        }
        Ok(d)
    }

    /// A continuous definition with Coulomb friction, one friction setting
    /// per zone.
    pub fn continuous_with_friction(
        zones: Vec<Zone<ContinueLaw>>,
        friction: crate::friction::ContinueFriction,
    ) -> Result<Self, ContactError> {
        friction.check(zones.len())?;
        for z in &zones {
            if z.law.algo == ContinueAlgo::Lac {
                return Err(ContactError::Unsupported {
                    feature: "ALGO_CONT='LAC' with FROTTEMENT='COULOMB'".into(),
                    hint: "code_aster's LAC method is frictionless".into(),
                });
            }
        }
        let mut d = ContactDefinition::continuous(zones, Frottement::Sans)?;
        if let ContactDefinition::Continue(c) = &mut d {
            c.friction = Some(friction);
        }
        Ok(d)
    }

    /// Whether the definition has Coulomb friction.
    pub fn has_friction(&self) -> bool {
        match self {
            ContactDefinition::Discrete(d) => d.friction.is_some(),
            ContactDefinition::Continue(c) => c.friction.is_some(),
        }
    }

    /// A continuous definition with code_aster's defaults. Refuses friction.
    pub fn continuous(
        zones: Vec<Zone<ContinueLaw>>,
        frottement: Frottement,
    ) -> Result<Self, ContactError> {
        refuse_friction(frottement)?;
        check_zones(&zones)?;
        for z in &zones {
            match z.law.algo {
                ContinueAlgo::Standard { coef_cont } => positive("COEF_CONT", coef_cont)?,
                ContinueAlgo::Penalisation { coef_pena_cont } => {
                    positive("COEF_PENA_CONT", coef_pena_cont)?
                }
                ContinueAlgo::Lac => {}
            }
        }
        Ok(ContactDefinition::Continue(ContinueDefinition {
            zones,
            geom_loop: GeomLoop::default(),
            algo_reso_cont: Resolution::Newton,
            algo_reso_geom: Resolution::PointFixe,
            iter_cont_maxi: 30,
            resi_cont: None,
            friction: None,
        }))
    }

    /// The geometric parts of all zones, in order.
    pub fn geometries(&self) -> Vec<&ZoneGeometry> {
        match self {
            ContactDefinition::Discrete(d) => d.zones.iter().map(|z| &z.geometry).collect(),
            ContactDefinition::Continue(c) => c.zones.iter().map(|z| &z.geometry).collect(),
        }
    }

    pub fn geom_loop(&self) -> GeomLoop {
        match self {
            ContactDefinition::Discrete(d) => d.geom_loop,
            ContactDefinition::Continue(c) => c.geom_loop,
        }
    }

    pub fn set_geom_loop(&mut self, g: GeomLoop) {
        match self {
            ContactDefinition::Discrete(d) => d.geom_loop = g,
            ContactDefinition::Continue(c) => c.geom_loop = g,
        }
    }
}

fn refuse_friction(f: Frottement) -> Result<(), ContactError> {
    match f {
        Frottement::Sans => Ok(()),
        Frottement::Coulomb => Err(ContactError::Unsupported {
            feature: "FROTTEMENT='COULOMB'".into(),
            hint: "give the zones' friction (ContactDefinition::discrete_with_friction / continuous_with_friction)".into(),
        }),
    }
}

fn check_zones<L>(zones: &[Zone<L>]) -> Result<(), ContactError> {
    if zones.is_empty() {
        return Err(ContactError::Invalid {
            keyword: "ZONE",
            message: "at least one contact zone is required".into(),
        });
    }
    for z in zones {
        if z.geometry.master_group == z.geometry.slave_group {
            return Err(ContactError::Invalid {
                keyword: "GROUP_MA_ESCL",
                message: format!(
                    "the slave group '{}' is also the master group; contact needs two distinct surfaces",
                    z.geometry.slave_group
                ),
            });
        }
    }
    Ok(())
}

fn positive(keyword: &'static str, v: f64) -> Result<(), ContactError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(ContactError::Invalid {
            keyword,
            message: format!("must be a positive number, got {v}"),
        })
    }
}
