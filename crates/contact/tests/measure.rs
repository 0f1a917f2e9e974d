//! Integration weights of the continuous formulation: measured on the
//! reference slave geometry, times the radius under AXIS (code_aster's
//! `mmmjac`), whatever the current positions.

use aster_contact::scenes::two_plates_mesh;
use aster_contact::*;

fn zone() -> (aster_mesh::Mesh, ResolvedZone) {
    // Slave AB: two SEG2 along y = 0, x ∈ [−1, 0] and [0, 1].
    let mesh = two_plates_mesh(2, 2).unwrap();
    let zone = ResolvedZone::new(0, &ZoneGeometry::new("EF", "AB"), &mesh).unwrap();
    (mesh, zone)
}

fn total(points: &[SlavePoint]) -> f64 {
    points.iter().map(|p| p.weight).sum()
}

fn nodal(points: &[SlavePoint], mesh: &aster_mesh::Mesh, x: f64) -> f64 {
    let p = points
        .iter()
        .find(|p| p.nodes.len() == 1 && (mesh.coord(p.nodes[0].0)[0] - x).abs() < 1e-12)
        .unwrap();
    p.weight
}

#[test]
fn plane_weights_are_lengths() {
    let (mesh, zone) = zone();
    let g = integration_points_measured(&zone, Integration::Gauss(3), &mesh.coords, Measure::Plane);
    assert!((total(&g) - 2.0).abs() < 1e-14, "{}", total(&g));
    let n = integration_points_measured(&zone, Integration::Auto, &mesh.coords, Measure::Plane);
    assert!((nodal(&n, &mesh, 0.0) - 1.0).abs() < 1e-14);
    assert!((nodal(&n, &mesh, 1.0) - 0.5).abs() < 1e-14);
}

#[test]
fn axisymmetric_weights_carry_the_radius() {
    let (mesh, zone) = zone();
    // ∫ |x| ds over [−1, 1] = 1 (two Gauss points per cell are exact).
    let g = integration_points_measured(
        &zone,
        Integration::Gauss(3),
        &mesh.coords,
        Measure::Axisymmetric,
    );
    assert!((total(&g) - 1.0).abs() < 1e-14, "{}", total(&g));
    // Nodal rule: the node at x = 1 weighs (L/2)·r = 0.5; the node on the
    // axis counts with code_aster's radius 1e-7 (once per cell).
    let n = integration_points_measured(
        &zone,
        Integration::Auto,
        &mesh.coords,
        Measure::Axisymmetric,
    );
    assert!((nodal(&n, &mesh, 1.0) - 0.5).abs() < 1e-14);
    assert!((nodal(&n, &mesh, 0.0) - 1e-7).abs() < 1e-20);
}

#[test]
fn weights_follow_the_geometry_they_are_given() {
    // integration_points measures on the positions it is handed; the zone
    // hands the mesh's reference coordinates (see ssnp121.rs for the real
    // case this decides).
    let (mesh, zone) = zone();
    let stretched: Vec<[f64; 3]> = mesh
        .coords
        .iter()
        .map(|c| [2.0 * c[0], c[1], c[2]])
        .collect();
    let g = integration_points(&zone, Integration::Gauss(3), &stretched);
    assert!((total(&g) - 4.0).abs() < 1e-14);
}
