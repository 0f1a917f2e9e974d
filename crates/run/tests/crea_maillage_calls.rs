//! CREA_MAILLAGE driven through the executor with hand-built commands:
//! the legacy COPIE, the refusal of DECOUPE_LAC with its reason, and a call
//! without an operation.

mod common;

use aster_eval::CommandSink;
use aster_run::concept::Concept;
use aster_run::{Executor, RunOptions};
use common::*;
use std::path::PathBuf;

fn executor() -> (Executor, Program, aster_eval::ConceptRef) {
    let mut options = RunOptions::default();
    options.units.insert(
        20,
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../comm/strip.mail"),
    );
    let mut ex = Executor::new(options, Box::new(std::io::sink()));
    let mut p = Program::default();
    let ma = p.concept("MA", "maillage_sdaster");
    ex.execute(&call(
        "LIRE_MAILLAGE",
        Some(&ma),
        vec![("FORMAT", V::S("ASTER"))],
    ))
    .unwrap();
    (ex, p, ma)
}

#[test]
fn copie_copies_the_mesh() {
    let (mut ex, mut p, ma) = executor();
    let copy = p.concept("MB", "maillage_sdaster");
    ex.execute(&call(
        "CREA_MAILLAGE",
        Some(&copy),
        vec![
            ("MAILLAGE", V::C(ma.clone())),
            ("COPIE", V::F(vec![vec![]])),
        ],
    ))
    .unwrap();
    let (Concept::Mesh(a), Concept::Mesh(b)) =
        (ex.concept(&ma).unwrap(), ex.concept(&copy).unwrap())
    else {
        panic!("meshes expected");
    };
    assert_eq!(**a, **b);
    assert_eq!(b.node_count(), 8);
}

#[test]
fn decoupe_lac_is_refused_with_its_reason() {
    let (mut ex, mut p, ma) = executor();
    let out = p.concept("MB", "maillage_sdaster");
    let err = ex
        .execute(&call(
            "CREA_MAILLAGE",
            Some(&out),
            vec![
                ("MAILLAGE", V::C(ma)),
                (
                    "DECOUPE_LAC",
                    V::F(vec![vec![("GROUP_MA_ESCL", V::S("LEFT"))]]),
                ),
            ],
        ))
        .unwrap_err()
        .message;
    assert!(
        err.starts_with("not supported yet: CREA_MAILLAGE/DECOUPE_LAC"),
        "{err}"
    );
    assert!(err.contains("LAC contact algorithm"), "{err}");
}

#[test]
fn an_operation_is_required() {
    let (mut ex, mut p, ma) = executor();
    let out = p.concept("MB", "maillage_sdaster");
    let err = ex
        .execute(&call(
            "CREA_MAILLAGE",
            Some(&out),
            vec![("MAILLAGE", V::C(ma))],
        ))
        .unwrap_err()
        .message;
    assert!(
        err.contains("give exactly one operation among RESTREINT"),
        "{err}"
    );
}
