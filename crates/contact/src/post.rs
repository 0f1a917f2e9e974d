//! CONT_NOEU (legacy VALE_CONT): the contact state per slave node.
//!
//! Components, as code_aster names them for frictionless contact:
//! `CONT` (-1 not paired, 0 no contact, 1 contact; in a RESOLUTION='NON'
//! zone 3 for an interpenetration beyond TOLE_INTERP), `JEU` (gap on the
//! current geometry; in a RESOLUTION='NON' zone on the last pairing's), `RN` (normal nodal force ≥ 0), `RNX RNY RNZ` (that
//! force along the contact normal, with the contact vector's sign: against
//! the force the master exerts on the slave node, in both formulations), the friction
//! components `GLIX GLIY GLI RTAX RTAY RTAZ RTGX RTGY RTGZ` (all 0 without
//! friction), `RX RY RZ` (total contact force = normal force here) and `R`
//! (its norm).

use aster_fem::RowOutcome;
use aster_mesh::{Mesh, NodeId};

use crate::error::ContactError;
use crate::pairing::{nodal_points, pair_point, PairStatus};
use crate::source::{ZoneContact, ZoneLaw};

/// The component names, in field order.
pub const CONT_NOEU_COMPONENTS: [&str; 19] = [
    "CONT", "JEU", "RN", "RNX", "RNY", "RNZ", "GLIX", "GLIY", "GLI", "RTAX", "RTAY", "RTAZ",
    "RTGX", "RTGY", "RTGZ", "RX", "RY", "RZ", "R",
];

/// The projection components of the discrete formulation's CONT_NOEU
/// (`cfresu`: the master point a slave node in contact is paired with).
pub const CONT_NOEU_PROJ_COMPONENTS: [&str; 3] = ["PROJ_X", "PROJ_Y", "PROJ_Z"];

/// A nodal field on the slave nodes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContNoeu {
    pub nodes: Vec<NodeId>,
    /// `values[k][c]`: node `nodes[k]`, component `CONT_NOEU_COMPONENTS[c]`.
    pub values: Vec<[f64; 19]>,
    /// `proj[k]`: PROJ_X, PROJ_Y, PROJ_Z of node `nodes[k]`, when the
    /// formulation writes them (discrete friction; continuous friction at
    /// its paired nodes, NaN where a component is not written); empty otherwise.
    pub proj: Vec<[f64; 3]>,
}

impl ContNoeu {
    /// Index of a component name.
    pub fn component(name: &str) -> Option<usize> {
        CONT_NOEU_COMPONENTS.iter().position(|c| *c == name)
    }

    /// The value of a component at a node (`None` if the node is not a
    /// slave node or the component unknown).
    pub fn value(&self, node: NodeId, component: &str) -> Option<f64> {
        let k = self.nodes.iter().position(|n| *n == node)?;
        if let Some(c) = CONT_NOEU_PROJ_COMPONENTS
            .iter()
            .position(|c| *c == component)
        {
            return self.proj.get(k).map(|p| p[c]).filter(|v| v.is_finite());
        }
        Some(self.values[k][Self::component(component)?])
    }

    /// The field of a stored step of fem's solver: the zones are re-paired
    /// on that step's geometry `x` and given its row outcomes
    /// (`outcomes[k]` for `zones[k]`, as in `Step::unilateral`).
    pub fn at_step(
        zones: &mut [ZoneContact],
        mesh: &Mesh,
        x: &[[f64; 3]],
        outcomes: &[Vec<RowOutcome>],
    ) -> Result<ContNoeu, ContactError> {
        for (z, o) in zones.iter_mut().zip(outcomes) {
            z.pair(mesh, x)?;
            z.set_outcomes(o);
        }
        Self::from_zones(zones, x, mesh)
    }

    /// As [`ContNoeu::at_step`], for the step at `time` of a solve the zones
    /// took part in: a RESOLUTION='NON' zone reports the pairing that step
    /// ended with (its gaps on the geometry of the last pairing, as
    /// code_aster's `cfveri`), when recorded.
    pub fn at_step_time(
        zones: &mut [ZoneContact],
        mesh: &Mesh,
        x: &[[f64; 3]],
        outcomes: &[Vec<RowOutcome>],
        time: f64,
    ) -> Result<ContNoeu, ContactError> {
        for (z, o) in zones.iter_mut().zip(outcomes) {
            z.pair(mesh, x)?;
            z.set_outcomes(o);
        }
        Self::build(zones, x, mesh, Some(time))
    }

    /// Builds the field from the zones' last converged state, on the
    /// converged geometry `x` (current positions of all nodes). A node is
    /// in contact when it carries a positive force.
    pub fn from_zones(
        zones: &[ZoneContact],
        x: &[[f64; 3]],
        mesh: &Mesh,
    ) -> Result<ContNoeu, ContactError> {
        Self::build(zones, x, mesh, None)
    }

    fn build(
        zones: &[ZoneContact],
        x: &[[f64; 3]],
        mesh: &Mesh,
        time: Option<f64>,
    ) -> Result<ContNoeu, ContactError> {
        let mut out = ContNoeu::default();
        if x.len() != mesh.coords.len() {
            return Err(ContactError::Invalid {
                keyword: "CONT_NOEU",
                message: format!(
                    "geometry of {} nodes for a mesh of {}",
                    x.len(),
                    mesh.coords.len()
                ),
            });
        }
        for z in zones {
            let forces = z.nodal_forces();
            let recorded = match time {
                Some(t) if !z.zone.geometry.resolve => z.verification_pairing(t),
                _ => None,
            };
            // Offsets that vary in time are taken at the step's time.
            let timed = match time {
                Some(t)
                    if z.zone.time != t
                        && (z.zone.geometry.dist_mait.depends_on_time()
                            || z.zone.geometry.dist_escl.depends_on_time()) =>
                {
                    let mut c = z.zone.clone();
                    c.time = t;
                    Some(c)
                }
                _ => None,
            };
            let zone = timed.as_ref().unwrap_or(&z.zone);
            for point in nodal_points(zone) {
                let Some(node) = point.node() else { continue };
                let mut v = [0.0; 19];
                let pair =
                    match recorded.and_then(|r| r.iter().find(|p| p.point.node() == Some(node))) {
                        Some(p) => p.clone(),
                        None => pair_point(zone, &point, x)?,
                    };
                match &pair.status {
                    PairStatus::Excluded(_) => v[0] = -1.0,
                    PairStatus::Paired(p) => {
                        let rn = forces
                            .iter()
                            .find(|(n, _)| *n == node)
                            .map(|e| e.1)
                            .unwrap_or(0.0);
                        // In contact: a positive force, or any force of a
                        // bilateral link (GLISSIERE), which may pull. A
                        // frictionless continuous node in contact is
                        // "sliding", 2 (code_aster's `mmmres`); discrete, 1.
                        v[0] = if !z.zone.geometry.resolve {
                            verification_status(p.gap, z.zone.geometry.tole_interp)
                        } else if rn != 0.0 {
                            match z.law {
                                ZoneLaw::Continue(_) => 2.0,
                                ZoneLaw::Discrete(_) => 1.0,
                            }
                        } else {
                            0.0
                        };
                        v[1] = p.gap;
                        v[2] = rn.abs();
                        // The vector components: code_aster reads them from
                        // the contact forces on the internal-force side of
                        // the balance (continuous: the assembled CNELTC;
                        // discrete: Aᵀμ at the slave node's DOFs, `cfresa`),
                        // so they point against the force the master exerts
                        // on the slave node, in both formulations: SSNV193A
                        // tests RZ < 0 on a slave face pressed down onto its
                        // master, continuous (UCTCC) and discrete (UMCTCD).
                        for c in 0..3 {
                            v[3 + c] = -rn * p.normal[c];
                            v[15 + c] = -rn * p.normal[c];
                        }
                        v[18] = rn.abs();
                    }
                }
                // A node slave in several zones reports the last one, as
                // code_aster fills the field zone after zone.
                match out.nodes.iter().position(|n| *n == node) {
                    Some(k) => out.values[k] = v,
                    None => {
                        out.nodes.push(node);
                        out.values.push(v);
                    }
                }
            }
            // Discrete zones: code_aster's field is initialised to zero at
            // every slave node of the zone, `SANS_GROUP_NO` ones included
            // (`cfmxr0`), and `cfresu` fills only the contact links; so an
            // excluded slave node carries every component, at 0.
            if matches!(z.law, ZoneLaw::Discrete(_)) {
                for node in &zone.excluded_nodes {
                    if zone.slave_cells_of_node.contains_key(node) && !out.nodes.contains(node) {
                        out.nodes.push(*node);
                        out.values.push([0.0; 19]);
                    }
                }
            }
        }
        Ok(out)
    }
}

/// CONT of a RESOLUTION='NON' zone (code_aster's verification status):
/// 0 apart or interpenetrating by at most `TOLE_INTERP`, 3 interpenetrating
/// by more.
fn verification_status(gap: f64, tole_interp: f64) -> f64 {
    if interpenetrates(gap, tole_interp) {
        3.0
    } else {
        0.0
    }
}

/// Whether a verification zone's gap is an interpenetration beyond
/// `TOLE_INTERP` (code_aster's `cfsans`, `mmveri`: gap ≤ ε and |gap| >
/// TOLE_INTERP).
pub(crate) fn interpenetrates(gap: f64, tole_interp: f64) -> bool {
    !(gap > f64::EPSILON || gap.abs() <= tole_interp)
}
