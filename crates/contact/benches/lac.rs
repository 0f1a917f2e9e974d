//! LAC pairing: the mortar integrals of every patch of the two-plates
//! interface (`scenes::two_plates_mesh(n, n - 1)`, QUAD4 slave edges cut in
//! three by DECOUPE_LAC, non-matching master edges) — one pairing, as the
//! geometric loop does it once per update.

use aster_contact::lac::{patch_integral, resolve_patches};
use aster_contact::scenes::two_plates_mesh;
use aster_contact::{Measure, ResolvedZone, ZoneGeometry};
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
        let Ok(refs) = resolve_patches(&zone, zp) else {
            return;
        };
        c.bench_function(&format!("lac_pairing_two_plates_{n}_patches"), |b| {
            b.iter(|| {
                let mut total = 0.0;
                for p in &refs {
                    if let Ok(i) = patch_integral(&mesh, &zone, p, &mesh.coords, Measure::Plane) {
                        total += i.paired;
                    }
                }
                assert!((total - 2.0).abs() < 1e-9, "{total}");
                total
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
