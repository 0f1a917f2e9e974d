//! First use of the catalog: what a process pays before checking its first
//! command. `typical file` reads the commands a contact study uses (the
//! command set of a real contact case); `every command` reads all of them
//! (what listing commands costs).

use aster_catalog::Catalog;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

const TYPICAL: [&str; 13] = [
    "DEBUT",
    "LIRE_MAILLAGE",
    "AFFE_MODELE",
    "DEFI_MATERIAU",
    "AFFE_MATERIAU",
    "AFFE_CHAR_MECA",
    "DEFI_CONTACT",
    "DEFI_FONCTION",
    "DEFI_LIST_REEL",
    "STAT_NON_LINE",
    "CALC_CHAMP",
    "TEST_RESU",
    "FIN",
];

fn load(c: &mut Criterion) {
    c.bench_function("catalog: typical file", |b| {
        b.iter(|| {
            let cat = Catalog::new();
            for n in TYPICAL {
                black_box(cat.command(n));
            }
        })
    });
    c.bench_function("catalog: one small command", |b| {
        b.iter(|| black_box(Catalog::new().command("DEBUT").is_some()))
    });
    c.bench_function("catalog: every command", |b| {
        b.iter(|| black_box(Catalog::new().commands().len()))
    });
}

criterion_group!(benches, load);
criterion_main!(benches);
