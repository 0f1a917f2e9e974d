//! Re-checking a 2,000-line command file after a keystroke: the
//! incremental edit applied to the document, then the whole analysis the
//! server publishes diagnostics from (parse, evaluate, validate against the
//! catalog, `aster run`'s support table, the name index and outline). The
//! bar is 20 ms (docs/editors.md records the measure).
//!
//! `cargo bench -p aster-lsp --bench recheck`

use aster_lsp::analysis::analyse;
use aster_lsp::text::Document;
use criterion::{criterion_group, criterion_main, Criterion};
use lsp_types::{Position, Range, TextDocumentContentChangeEvent};

/// A program of about `lines` lines: a mesh and a model, then blocks of
/// materials, loads, functions and time lists, each command over several
/// lines as people write them.
pub fn program(lines: usize) -> String {
    let mut s = String::from(
        "DEBUT()\nmesh = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\n\
         model = AFFE_MODELE(\n    MAILLAGE=mesh,\n    AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'),\n)\n",
    );
    let mut i = 0;
    while s.lines().count() < lines - 1 {
        s.push_str(&format!(
            "mat{i} = DEFI_MATERIAU(\n    ELAS=_F(E=2.0e9 + {i}, NU=0.3),\n)\n\
             cm{i} = AFFE_MATERIAU(\n    MAILLAGE=mesh,\n    AFFE=_F(TOUT='OUI', MATER=mat{i}),\n)\n\
             ch{i} = AFFE_CHAR_MECA(\n    MODELE=model,\n    DDL_IMPO=_F(GROUP_NO='CD', DY=-{i}.0),\n)\n\
             f{i} = DEFI_FONCTION(NOM_PARA='INST', VALE=(0.0, 0.0, 1.0, {i}.0))\n\
             l{i} = DEFI_LIST_REEL(\n    DEBUT=0.0,\n    INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=2),\n)\n"
        ));
        i += 1;
    }
    s.push_str("FIN()\n");
    s
}

fn recheck(c: &mut Criterion) {
    let text = program(2000);
    assert!(text.lines().count() >= 2000);
    let clean = analyse("bench.comm", &text);
    assert!(
        clean
            .findings
            .iter()
            .all(|f| f.code == "not_supported_by_run"),
        "{:?}",
        clean.findings
    );
    let mut doc = Document::new(text, 1);
    // The keystroke: a digit typed into a value in the middle of the file
    // (`NU=0.3` becomes `NU=0.33`, and back).
    let mid = doc.text.len() / 2;
    let at_byte = mid + doc.text[mid..].find("NU=0.3").expect("a material") + "NU=0.3".len();
    let at = doc.position(at_byte);
    let after = Position::new(at.line, at.character + 1);
    let mut version = 1;
    c.bench_function("recheck/2000 lines after a keystroke", |b| {
        b.iter(|| {
            version += 1;
            doc.apply(
                vec![TextDocumentContentChangeEvent {
                    range: Some(Range::new(at, at)),
                    range_length: None,
                    text: "3".into(),
                }],
                version,
            );
            let a = analyse("bench.comm", &doc.text);
            doc.apply(
                vec![TextDocumentContentChangeEvent {
                    range: Some(Range::new(at, after)),
                    range_length: None,
                    text: String::new(),
                }],
                version,
            );
            assert!(a.findings.iter().all(|f| f.code == "not_supported_by_run"));
            a
        })
    });
}

criterion_group!(benches, recheck);
criterion_main!(benches);
