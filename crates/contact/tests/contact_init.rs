//! code_aster's `CONTACT_INIT='INTERPENETRE'` threshold (`cazocc`,
//! `contSetInit`, `mmopti`): 1e-6 × `DIST_MAXI`, or without it 1e-6 × the
//! shortest edge of the zone's own slave and master cells — not the
//! mesh's.

use aster_contact::scenes::two_plates_mesh;
use aster_contact::{ResolvedZone, ZoneGeometry};

/// Upper plate 2 × 2 QUAD4 (bottom `AB`: edges 1.0), lower plate 4 × 4
/// (top `EF`: edges 0.5); the mesh's shortest edge is the lower plate's
/// vertical 0.25, which the zone's cells do not have.
fn zone(dist_maxi: Option<f64>) -> (aster_mesh::Mesh, ResolvedZone) {
    let mesh = two_plates_mesh(2, 4).expect("scene");
    let mut g = ZoneGeometry::new("AB", "EF");
    g.dist_maxi = dist_maxi;
    let z = ResolvedZone::new(0, &g, &mesh).expect("zone");
    (mesh, z)
}

#[test]
fn without_dist_maxi_the_zone_cells_shortest_edge() {
    let (mesh, z) = zone(None);
    // The whole mesh's shortest edge is 0.25 (what `armin` gives).
    let all: Vec<aster_mesh::CellId> = (0..mesh.cells.len() as u32)
        .map(aster_mesh::CellId)
        .collect();
    let (lo, _) = mesh.edge_length_range(&all).expect("edges");
    assert!((lo - 0.25).abs() < 1e-12);
    assert!((z.contact_init_distance(&mesh) - 0.5).abs() < 1e-12);
    assert!((z.contact_init_threshold(&mesh) - 5e-7).abs() < 1e-18);
}

#[test]
fn dist_maxi_is_scaled_by_1e_minus_6() {
    let (mesh, z) = zone(Some(0.3710167603714386));
    assert!((z.contact_init_distance(&mesh) - 0.3710167603714386).abs() < 1e-15);
    assert!((z.contact_init_threshold(&mesh) - 3.710167603714386e-7).abs() < 1e-20);
}

#[test]
fn a_negative_dist_maxi_means_absent() {
    // cazocc stores −1 when DIST_MAXI is absent, and contSetInit replaces
    // any negative value by the zone's shortest edge.
    let (mesh, z) = zone(Some(-1.0));
    assert!((z.contact_init_threshold(&mesh) - 5e-7).abs() < 1e-18);
}
