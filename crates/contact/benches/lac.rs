//! LAC pairing: code_aster's mortar pairing and gap integrals of every
//! patch of the two-plates interface (`scenes::two_plates_mesh(n, n - 1)`,
//! QUAD4 slave edges cut in three by DECOUPE_LAC, non-matching master
//! edges) — one pairing, as the geometric loop does it once per update.

use aster_contact::lac::LacZone;
use aster_contact::scenes::two_plates_mesh;
use aster_contact::{ResolvedZone, ZoneGeometry};
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    for n in [20usize, 80] {
        let Ok(mesh) = two_plates_mesh(n, n - 1) else {
            return;
        };
        let Ok((mesh, patches)) = aster_mesh::decoupe_lac(&mesh, &["AB"]) else {
            return;
        };
        let Ok(zone) = ResolvedZone::new(0, &ZoneGeometry::new("EF", "AB"), &mesh) else {
            return;
        };
        let Some(zp) = patches.zone("AB") else { return };
        let Ok(mut lac) = LacZone::new(&zone, zp) else {
            return;
        };
        c.bench_function(&format!("lac_pairing_two_plates_{n}_patches"), |b| {
            b.iter(|| {
                lac.pair(&zone, &mesh.coords);
                let total: f64 = lac.state.iter().map(|s| s.paired).sum();
                assert!((total - 2.0).abs() < 1e-9, "{total}");
                total
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
