//! Using the catalog: the tables are static (built at compile time,
//! `build.rs`), so a lookup is a binary search and nothing is read on first
//! use. `typical file` looks up the commands a contact study uses and finds
//! one keyword in each; `every command` walks every keyword tree (what a
//! listing or completion costs).

use aster_catalog::{catalog, Entry, Node};
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

fn count(entries: &[Entry]) -> usize {
    entries
        .iter()
        .map(|e| match &e.node {
            Node::Simple(_) => 1,
            Node::Factor(f) => 1 + count(f.keywords),
            Node::Block(b) => 1 + count(b.keywords),
        })
        .sum()
}

fn load(c: &mut Criterion) {
    c.bench_function("catalog: typical file", |b| {
        b.iter(|| {
            for n in TYPICAL {
                black_box(catalog().command(black_box(n)).and_then(|c| c.find("INFO")));
            }
        })
    });
    c.bench_function("catalog: every command", |b| {
        b.iter(|| {
            catalog()
                .commands()
                .iter()
                .map(|c| count(c.keywords))
                .sum::<usize>()
        })
    });
}

criterion_group!(benches, load);
criterion_main!(benches);
