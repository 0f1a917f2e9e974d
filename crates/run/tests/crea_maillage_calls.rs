//! CREA_MAILLAGE driven through the executor with hand-built commands:
//! the legacy COPIE, DECOUPE_LAC (a cut and a refusal with its reason), and a call
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
fn decoupe_lac_cuts_a_quad4_edge_and_refuses_a_body_group() {
    let (mut ex, mut p, ma) = executor();
    let out = p.concept("MB", "maillage_sdaster");
    ex.execute(&call(
        "CREA_MAILLAGE",
        Some(&out),
        vec![
            ("MAILLAGE", V::C(ma.clone())),
            (
                "DECOUPE_LAC",
                V::F(vec![vec![("GROUP_MA_ESCL", V::S("LEFT"))]]),
            ),
        ],
    ))
    .unwrap();
    let Concept::Mesh(m) = ex.concept(&out).unwrap() else {
        panic!("mesh expected");
    };
    // LEFT is the SEG2 side of M1 (QUAD4): +4 nodes, 3 edges, 4 quadrangles.
    assert_eq!((m.node_count(), m.cells.len()), (8 + 4, 6 + 5));
    assert_eq!(m.group_ma("LEFT").unwrap().members.len(), 3);
    assert_eq!(m.group_ma("PLATE").unwrap().members.len(), 2 + 3);

    let bad = p.concept("MC", "maillage_sdaster");
    let err = ex
        .execute(&call(
            "CREA_MAILLAGE",
            Some(&bad),
            vec![
                ("MAILLAGE", V::C(ma)),
                (
                    "DECOUPE_LAC",
                    V::F(vec![vec![("GROUP_MA_ESCL", V::S("PLATE"))]]),
                ),
            ],
        ))
        .unwrap_err()
        .message;
    assert!(err.starts_with("CREA_MAILLAGE/GROUP_MA_ESCL:"), "{err}");
    assert!(
        err.contains("cell M1 (QUAD4) of GROUP_MA_ESCL 'PLATE'"),
        "{err}"
    );
    assert!(err.contains("give the group of its contact edges"), "{err}");
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
