//! Pairing (APPARIEMENT): each slave point gets a master point, a normal and
//! a gap on the current geometry — or the reason it is not paired.

use aster_mesh::{CellId, NodeId};

use crate::error::ContactError;
use crate::shape::{dot, norm, project_along, project_mmnewt, scale, sub, SurfaceKind};
use crate::surface::ResolvedZone;
use crate::zone::{Appariement, NormalChoice};

/// A point of the slave surface where contact is enforced: a slave node
/// (discrete contact, continuous with nodal integration) or an integration
/// point of a slave cell.
#[derive(Clone, Debug, PartialEq)]
pub struct SlavePoint {
    pub zone: usize,
    /// Slave nodes and their interpolation weights (one node with weight 1
    /// for a nodal point).
    pub nodes: Vec<(NodeId, f64)>,
    /// Integration weight (length or area); 1 for discrete nodal points.
    pub weight: f64,
    /// The slave cell and reference coordinates of an integration point.
    pub cell: Option<(usize, [f64; 2])>,
}

impl SlavePoint {
    /// The slave node of a nodal point.
    pub fn node(&self) -> Option<NodeId> {
        match (self.cell, self.nodes.as_slice()) {
            (None, [(n, _)]) => Some(*n),
            _ => None,
        }
    }
}

/// Why a slave point takes no part in contact (CONT = -1 in CONT_NOEU).
#[derive(Clone, Debug, PartialEq)]
pub enum Exclusion {
    /// Its nearest master node is farther than DIST_APPA.
    DistAppa { distance: f64, limit: f64 },
    /// Its projection falls outside every master cell by more than TOLE_PROJ_EXT.
    OutsideMaster { outside: f64 },
}

/// A successful pairing.
#[derive(Clone, Debug, PartialEq)]
pub struct Pairing {
    /// The master cell and the reference coordinates of the projection
    /// (`None` for NODAL pairing).
    pub master_cell: Option<(CellId, [f64; 2])>,
    /// Master nodes and their weights at the master point.
    pub master: Vec<(NodeId, f64)>,
    /// Unit contact normal, pointing from the master body towards the slave.
    pub normal: [f64; 3],
    /// Signed gap g = (x_s − x_m)·n − DIST_MAIT − DIST_ESCL; negative means
    /// interpenetration.
    pub gap: f64,
    pub slave_x: [f64; 3],
    pub master_x: [f64; 3],
    pub nearest_master_node: NodeId,
}

#[derive(Clone, Debug, PartialEq)]
pub enum PairStatus {
    Paired(Pairing),
    Excluded(Exclusion),
}

/// A slave point and what pairing made of it.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactPair {
    pub point: SlavePoint,
    pub status: PairStatus,
}

impl ContactPair {
    pub fn pairing(&self) -> Option<&Pairing> {
        match &self.status {
            PairStatus::Paired(p) => Some(p),
            PairStatus::Excluded(_) => None,
        }
    }
}

/// Pairs one slave point of `zone` on the geometry `x` (current positions
/// of all mesh nodes).
pub fn pair_point(
    zone: &ResolvedZone,
    point: &SlavePoint,
    x: &[[f64; 3]],
) -> Result<ContactPair, ContactError> {
    let g = &zone.geometry;
    let mut xs = [0.0; 3];
    for (n, w) in &point.nodes {
        let p = x[n.0 as usize];
        xs = [xs[0] + w * p[0], xs[1] + w * p[1], xs[2] + w * p[2]];
    }

    if xs.iter().any(|c| !c.is_finite()) {
        return Err(ContactError::Invalid {
            keyword: "GROUP_MA_ESCL",
            message: format!(
                "a slave point of group '{}' has no finite position: the previous solve diverged",
                g.slave_group
            ),
        });
    }
    // Nearest master node: DIST_APPA is measured to it, NODAL pairs on it.
    let mut nearest = None;
    let mut best = f64::INFINITY;
    for &m in &zone.master_nodes {
        let d = norm(sub(xs, x[m.0 as usize]));
        if d < best {
            best = d;
            nearest = Some(m);
        }
    }
    let Some(nearest) = nearest else {
        return Err(ContactError::Invalid {
            keyword: "GROUP_MA_MAIT",
            message: format!("group '{}' has no node", g.master_group),
        });
    };
    if let Some(limit) = g.dist_appa {
        if best > limit {
            return Ok(ContactPair {
                point: point.clone(),
                status: PairStatus::Excluded(Exclusion::DistAppa {
                    distance: best,
                    limit,
                }),
            });
        }
    }

    let (master_cell, master, xm, master_normal_opt) = match g.appariement {
        Appariement::Nodal => {
            // With NORMALE='ESCL' the master normal is not used (and a
            // master point, POI1, has none).
            let n = if g.normale == NormalChoice::Escl {
                None
            } else {
                Some(zone.nodal_normal(nearest, true, x)?)
            };
            (None, vec![(nearest, 1.0)], x[nearest.0 as usize], n)
        }
        Appariement::MaitEscl => {
            // As code_aster (approj/apchoi): project on the master cells
            // around the nearest master node only, each projection brought
            // back onto its cell; a projection inside a cell beats any
            // outside one, then the nearest wins (ties keep the first cell).
            // The chosen projection outside by more than TOLE_PROJ_EXT
            // excludes the point.
            let mut chosen: Option<Candidate> = None;
            let near: &[usize] = zone
                .master_cells_of_node
                .get(&nearest)
                .map(|v| v.as_slice())
                .unwrap_or(&[]);
            for &ci in near {
                let cell = &zone.master[ci];
                let nodes: Vec<[f64; 3]> = cell.nodes.iter().map(|n| x[n.0 as usize]).collect();
                let projected = match g.dire_appa {
                    Some(d) => project_along(cell.kind, &nodes, xs, d),
                    None => project_mmnewt(cell.kind, &nodes, xs),
                };
                let Some(p) = projected else {
                    continue;
                };
                let outside = cell.kind.outside_distance(p.xi);
                let status = if outside <= 0.0 {
                    ProjStatus::Inside
                } else if g.tole_proj_ext < 0.0 || outside <= g.tole_proj_ext {
                    ProjStatus::Tolerated
                } else {
                    ProjStatus::Outside
                };
                let xi = cell.kind.clamp(p.xi);
                let p = crate::shape::interpolate(cell.kind, &nodes, xi);
                let d = norm(sub(xs, p.x));
                let better = match &chosen {
                    None => true,
                    Some(c) if c.status != ProjStatus::Inside => {
                        status == ProjStatus::Inside || d < c.distance
                    }
                    Some(c) => {
                        let relative = if c.distance == 0.0 || d == c.distance {
                            0.0
                        } else {
                            ((d - c.distance) / c.distance).abs()
                        };
                        status == ProjStatus::Inside && d < c.distance && relative > f64::EPSILON
                    }
                };
                if better {
                    chosen = Some(Candidate {
                        cell: ci,
                        xi,
                        shape: p.shape,
                        point: p.x,
                        distance: d,
                        outside,
                        status,
                    });
                }
            }
            let Some(c) = chosen else {
                return Ok(ContactPair {
                    point: point.clone(),
                    status: PairStatus::Excluded(Exclusion::OutsideMaster {
                        outside: f64::INFINITY,
                    }),
                });
            };
            if c.status == ProjStatus::Outside {
                return Ok(ContactPair {
                    point: point.clone(),
                    status: PairStatus::Excluded(Exclusion::OutsideMaster { outside: c.outside }),
                });
            }
            let cell = &zone.master[c.cell];
            let n = master_normal_at(zone, cell, c.xi, x)?;
            let master = cell.nodes.iter().copied().zip(c.shape).collect();
            (Some((cell.id, c.xi)), master, c.point, Some(n))
        }
    };

    let master_normal = |m: Option<[f64; 3]>| match m {
        Some(n) => Ok(n),
        None => zone.nodal_normal(nearest, true, x),
    };
    let normal = match g.normale {
        NormalChoice::Mait => master_normal(master_normal_opt)?,
        NormalChoice::Escl | NormalChoice::MaitEscl => {
            let ns = slave_normal(zone, point, x)?;
            let v = if g.normale == NormalChoice::Escl {
                scale(ns, -1.0)
            } else {
                sub(master_normal(master_normal_opt)?, ns)
            };
            let l = norm(v);
            if l > 0.0 {
                scale(v, 1.0 / l)
            } else {
                master_normal(master_normal_opt)?
            }
        }
    };
    let gap = dot(sub(xs, xm), normal)
        - g.dist_mait.at_time(xm, zone.time)
        - g.dist_escl.at_time(xs, zone.time)
        - zone.structural_gap(point);
    Ok(ContactPair {
        point: point.clone(),
        status: PairStatus::Paired(Pairing {
            master_cell,
            master,
            normal,
            gap,
            slave_x: xs,
            master_x: xm,
            nearest_master_node: nearest,
        }),
    })
}

/// Where a projection falls with respect to its master cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ProjStatus {
    Inside,
    /// Outside, within TOLE_PROJ_EXT (brought back onto the cell).
    Tolerated,
    /// Outside by more than TOLE_PROJ_EXT.
    Outside,
}

/// The master normal at the reference coordinates `xi` of a master cell.
///
/// With `VECT_MAIT='AUTO'`: with `LISSAGE`, the nodal normals (averaged over
/// the cells around each node) interpolated inside the cell; without it,
/// the cell's own normal — except on a master node itself, where the cells
/// around the node meet and their normals differ: there the averaged nodal
/// normal is used, so that the answer does not depend on which of those
/// cells the projection was attributed to.
fn master_normal_at(
    zone: &ResolvedZone,
    cell: &crate::surface::SurfaceCell,
    xi: [f64; 2],
    x: &[[f64; 3]],
) -> Result<[f64; 3], ContactError> {
    let source = zone.geometry.vect_mait;
    if !matches!(source, crate::zone::NormalSource::Auto) {
        return zone.cell_normal(cell, xi, x, source);
    }
    if zone.geometry.lissage {
        let (shape, _) = cell.kind.eval(xi);
        let mut sum = [0.0; 3];
        for (node, w) in cell.nodes.iter().zip(shape) {
            let n = zone.nodal_normal(*node, true, x)?;
            for c in 0..3 {
                sum[c] += w * n[c];
            }
        }
        let l = norm(sum);
        // Nodal normals of a sane surface never cancel inside one cell;
        // if they do, the cell's own normal is the only meaningful one.
        return if l > 1e-12 {
            Ok(scale(sum, 1.0 / l))
        } else {
            zone.cell_normal(cell, xi, x, source)
        };
    }
    // On a master node (within 1e-6 of the cell in reference coordinates)
    // the cells around the node meet. code_aster keeps the normal of the
    // cell the projection was attributed to, and on a curved master that
    // choice matters (SSNV104B's values depend on it at 1e-6): keep it.
    // But where those cells are flat to within ~1e-6 rad, the choice cannot
    // matter physically while its noise can: a slave node sitting on a
    // master node by symmetry drifts off it by the solver's round-off
    // (~1e-8 of the cell on ZZZZ237, whose square is held sideways by
    // 10 N/m against 1e10 N of contact force), and switching between the
    // cells' normals pushes it sideways by metres, so the geometric loop
    // never settles. There the averaged nodal normal is used.
    const ON_NODE: f64 = 1e-6;
    const FLAT: f64 = 1e-12; // 1 − cos θ, θ ≈ 1.4e-6 rad
    let own = zone.cell_normal(cell, xi, x, source)?;
    for (i, c) in cell.kind.node_coords().iter().enumerate() {
        if (xi[0] - c[0]).abs() <= ON_NODE && (xi[1] - c[1]).abs() <= ON_NODE {
            // Where the cells around the node fold back on each other
            // (their normals cancel out: a master line that turns by
            // 180°), no average exists and the cells are anything but
            // flat: the attributed cell's normal, as code_aster.
            if let Ok(averaged) = zone.nodal_normal(cell.nodes[i], true, x) {
                if 1.0 - crate::shape::dot(own, averaged) <= FLAT {
                    return Ok(averaged);
                }
            }
            return Ok(own);
        }
    }
    Ok(own)
}

/// A projection candidate on one master cell.
struct Candidate {
    cell: usize,
    /// Reference coordinates, brought back onto the cell.
    xi: [f64; 2],
    shape: Vec<f64>,
    point: [f64; 3],
    distance: f64,
    /// Distance outside the cell before being brought back (reference coordinates).
    outside: f64,
    status: ProjStatus,
}

fn slave_normal(
    zone: &ResolvedZone,
    point: &SlavePoint,
    x: &[[f64; 3]],
) -> Result<[f64; 3], ContactError> {
    // A point on a slave node (nodal integration) takes the node's normal,
    // averaged over the slave cells around it, as code_aster's `cftanr`
    // (`APPARI_NOEUD_TAU1/2`, smoothed by `aptgnn`), whichever cell the
    // point belongs to.
    if let [(n, w)] = point.nodes.as_slice() {
        if *w == 1.0 {
            return zone.nodal_normal(*n, false, x);
        }
    }
    match (point.cell, point.node()) {
        (Some((ci, xi)), _) => zone.cell_normal(&zone.slave[ci], xi, x, zone.geometry.vect_escl),
        (None, Some(n)) => zone.nodal_normal(n, false, x),
        (None, None) => Err(ContactError::Invalid {
            keyword: "GROUP_MA_ESCL",
            message: "a slave point has neither a cell nor a node".into(),
        }),
    }
}

/// The nodal slave points of a zone (discrete contact).
pub fn nodal_points(zone: &ResolvedZone) -> Vec<SlavePoint> {
    zone.slave_nodes
        .iter()
        .map(|n| SlavePoint {
            zone: zone.index,
            nodes: vec![(*n, 1.0)],
            weight: 1.0,
            cell: None,
        })
        .collect()
}

/// Surface measure element |∂x/∂ξ| (or |t₁×t₂|) of a cell at `xi`.
pub(crate) fn jacobian(kind: SurfaceKind, nodes: &[[f64; 3]], xi: [f64; 2]) -> f64 {
    let p = crate::shape::interpolate(kind, nodes, xi);
    if kind.dim() == 1 {
        norm(p.tangents[0])
    } else {
        norm(crate::shape::cross(p.tangents[0], p.tangents[1]))
    }
}
