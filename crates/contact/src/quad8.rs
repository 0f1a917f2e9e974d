//! Discrete contact on QUAD8 faces, as code_aster does it (`quadco`,
//! `cfleq8`/`cfleqa`/`cfleqb`/`cfleqc`, `cacoeq` in `bibfor/cont_defi`).
//!
//! The serendipity QUAD8 face has nodal integrals of a uniform pressure
//! of −1/12 at the corners and +1/3 at the middles: a nodal (discrete)
//! contact force cannot reproduce a uniform pressure with non-negative
//! nodal forces. code_aster therefore, in the DISCRETE formulation with
//! `ALGO_CONT` other than `PENALISATION` (and without `GLISSIERE`, and
//! unless every zone is `RESOLUTION='NON'`):
//!
//! - removes the middle nodes of the QUAD8 cells of both surfaces of every
//!   resolved zone from the zone's contact nodes (they are neither slave
//!   points nor candidates of the nearest-master-node search);
//! - ties each such middle node to its edge: u_m − ½ u_a − ½ u_b = 0 on
//!   DX, DY and DZ (dualised linear relations, duplicates dropped);
//!   a relation one of whose three nodes is in the `SANS_GROUP_NO` of a
//!   zone is skipped — and, as code_aster's `cacoeq` keeps only the status
//!   of the **last** middle node it examined, when that last one is
//!   skipped no relation is applied at all.
//!
//! The faces then behave as bilinear ones in contact: a flat punch on
//! HEXA20 blocks is exact (SSNV167B: DZ = −0.1, corner and middle
//! reactions −F/12 and F/3).

use std::collections::BTreeSet;

use aster_mesh::NodeId;

use crate::shape::SurfaceKind;
use crate::source::{ZoneContact, ZoneLaw};
use crate::zone::DiscreteAlgo;

/// One middle node tied to the two corners of its edge:
/// u(middle) = ½ u(ends[0]) + ½ u(ends[1]) on every translation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct MiddleLink {
    pub middle: NodeId,
    pub ends: [NodeId; 2],
}

/// Whether code_aster's QUAD8 treatment applies to these zones (`quadco`):
/// a discrete formulation, not penalised, with at least one resolved zone.
fn applies(zones: &[ZoneContact]) -> bool {
    let discrete = zones.iter().all(|z| match z.law {
        ZoneLaw::Discrete(DiscreteAlgo::Penalisation { .. }) => false,
        ZoneLaw::Discrete(_) => true,
        ZoneLaw::Continue(_) => false,
    });
    discrete && zones.iter().any(|z| z.zone.geometry.resolve)
}

/// A QUAD8 cell (not a COQUE_3D QUAD9 seen as one: `cfleqa` counts no
/// middle node on a QUAD9).
fn is_quad8(c: &crate::surface::SurfaceCell) -> bool {
    c.kind == SurfaceKind::Quad8 && !c.centre_dropped
}

/// The (middle, corner, corner) triples of the QUAD8 cells of the resolved
/// zones, in code_aster's order (`liexco`: zone, master then slave
/// surface, cell, edge).
fn triples(zones: &[ZoneContact]) -> Vec<MiddleLink> {
    let mut out = Vec::new();
    for z in zones.iter().filter(|z| z.zone.geometry.resolve) {
        for cells in [&z.zone.master, &z.zone.slave] {
            for c in cells.iter().filter(|c| is_quad8(c)) {
                for k in 0..4 {
                    out.push(MiddleLink {
                        middle: c.nodes[4 + k],
                        ends: [c.nodes[k], c.nodes[(k + 1) % 4]],
                    });
                }
            }
        }
    }
    out
}

/// The middle-node relations code_aster adds for discrete contact on
/// QUAD8 faces (none when the treatment does not apply), without
/// duplicates.
pub fn middle_links(zones: &[ZoneContact]) -> Vec<MiddleLink> {
    if !applies(zones) {
        return Vec::new();
    }
    let excluded: BTreeSet<NodeId> = zones
        .iter()
        .flat_map(|z| z.zone.excluded_nodes.iter().copied())
        .collect();
    let all = triples(zones);
    let skipped = |l: &MiddleLink| {
        [l.middle, l.ends[0], l.ends[1]]
            .iter()
            .any(|n| excluded.contains(n))
    };
    // cacoeq decides on the whole list from its last entry.
    if all.last().is_some_and(skipped) {
        return Vec::new();
    }
    let mut seen = BTreeSet::new();
    all.into_iter()
        .filter(|l| !skipped(l))
        .filter(|l| {
            let mut ends = l.ends;
            ends.sort();
            seen.insert((l.middle, ends))
        })
        .collect()
}

/// Removes the QUAD8 middle nodes from the contact nodes of every resolved
/// zone (slave points and the nearest-master-node search), when the
/// treatment applies.
pub(crate) fn remove_middle_nodes(zones: &mut [ZoneContact]) {
    if !applies(zones) {
        return;
    }
    for z in zones.iter_mut().filter(|z| z.zone.geometry.resolve) {
        let middles: BTreeSet<NodeId> = z
            .zone
            .slave
            .iter()
            .chain(&z.zone.master)
            .filter(|c| is_quad8(c))
            .flat_map(|c| c.nodes[4..8].iter().copied())
            .collect();
        z.zone.slave_nodes.retain(|n| !middles.contains(n));
        z.zone.master_nodes.retain(|n| !middles.contains(n));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{ResolvedZone, SurfaceCell};
    use crate::zone::{GeomLoop, ZoneGeometry};
    use aster_mesh::CellId;
    use std::collections::HashMap;

    fn quad8(first: u32) -> SurfaceCell {
        SurfaceCell {
            id: CellId(first),
            kind: SurfaceKind::Quad8,
            nodes: (first..first + 8).map(NodeId).collect(),
            sign: 1.0,
            centre_dropped: false,
        }
    }

    fn zone(law: DiscreteAlgo, excluded: Vec<NodeId>) -> ZoneContact {
        let slave = vec![quad8(0)];
        let master = vec![quad8(8)];
        let resolved = ResolvedZone {
            index: 0,
            geometry: ZoneGeometry::new("M", "S"),
            slave_nodes: (0..8).map(NodeId).collect(),
            master_nodes: (8..16).map(NodeId).collect(),
            excluded_nodes: excluded,
            master,
            slave,
            master_cells_of_node: HashMap::new(),
            slave_cells_of_node: HashMap::new(),
            space_dim: 3,
            time: 0.0,
        };
        ZoneContact::new(resolved, ZoneLaw::Discrete(law), GeomLoop::Sans)
    }

    #[test]
    fn middles_are_tied_and_removed_from_both_surfaces() {
        let mut zones = vec![zone(DiscreteAlgo::Contrainte, vec![])];
        let links = middle_links(&zones);
        assert_eq!(links.len(), 8);
        assert_eq!(
            links[0],
            MiddleLink {
                middle: NodeId(12),
                ends: [NodeId(8), NodeId(9)]
            }
        );
        assert_eq!(
            links[7],
            MiddleLink {
                middle: NodeId(7),
                ends: [NodeId(3), NodeId(0)]
            }
        );
        remove_middle_nodes(&mut zones);
        assert_eq!(
            zones[0].zone.slave_nodes,
            (0..4).map(NodeId).collect::<Vec<_>>()
        );
        assert_eq!(
            zones[0].zone.master_nodes,
            (8..12).map(NodeId).collect::<Vec<_>>()
        );
    }

    /// COQUE_3D QUAD9 faces seen as QUAD8 (`centre_dropped`) keep their
    /// middles: code_aster's `cfleqa` counts none on a QUAD9.
    #[test]
    fn coque3d_faces_keep_their_middles() {
        let mut z = zone(DiscreteAlgo::Contrainte, vec![]);
        for c in z.zone.slave.iter_mut().chain(z.zone.master.iter_mut()) {
            c.centre_dropped = true;
        }
        let mut zones = vec![z];
        assert!(middle_links(&zones).is_empty());
        remove_middle_nodes(&mut zones);
        assert_eq!(zones[0].zone.slave_nodes.len(), 8);
        assert_eq!(zones[0].zone.master_nodes.len(), 8);
    }

    #[test]
    fn penalisation_and_verification_keep_the_middles() {
        let mut zones = vec![zone(DiscreteAlgo::Penalisation { e_n: 1e6 }, vec![])];
        assert!(middle_links(&zones).is_empty());
        remove_middle_nodes(&mut zones);
        assert_eq!(zones[0].zone.slave_nodes.len(), 8);
        let mut z = zone(DiscreteAlgo::Contrainte, vec![]);
        z.zone.geometry.resolve = false;
        assert!(middle_links(&[z]).is_empty());
    }

    #[test]
    fn excluded_nodes_drop_their_ties_and_the_last_one_drops_all() {
        // Node 5 (the slave middle of edge 1-2) excluded: its tie goes.
        let zones = vec![zone(DiscreteAlgo::Contrainte, vec![NodeId(5)])];
        let links = middle_links(&zones);
        assert_eq!(links.len(), 7);
        assert!(links.iter().all(|l| l.middle != NodeId(5)));
        // The last tie examined (slave middle 7 between 3 and 0) excluded:
        // code_aster's cacoeq then applies none.
        let zones = vec![zone(DiscreteAlgo::Contrainte, vec![NodeId(0)])];
        assert!(middle_links(&zones).is_empty());
    }
}
