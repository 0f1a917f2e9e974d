//! Re-checking a 2,000-line command file after a keystroke: the
//! incremental edit applied to the document, then the whole analysis the
//! server publishes diagnostics from (parse, evaluate, validate against the
//! catalog, `aster run`'s support table, the name index and outline). The
//! bar is 20 ms (docs/editors.md records the measure).
//!
//! Measured twice: wall-clock time, and the CPU time of the benchmark's
//! thread — on a shared machine the wall clock also counts the time other
//! processes hold the core, the CPU time only the work.
//!
//! `cargo bench -p aster-lsp --bench recheck`

use aster_lsp::analysis::analyse;
use aster_lsp::text::Document;
use criterion::measurement::{Measurement, ValueFormatter};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use lsp_types::{Position, Range, TextDocumentContentChangeEvent};
use std::time::Duration;

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

/// The CPU time of the calling thread (`CLOCK_THREAD_CPUTIME_ID`).
fn thread_cpu() -> Duration {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to write.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID)");
    Duration::new(t.tv_sec as u64, t.tv_nsec as u32)
}

/// Criterion's measurement of a thread's CPU time.
struct ThreadCpu;

/// Formats nanoseconds as milliseconds (the scale of this benchmark).
struct Millis;

impl ValueFormatter for Millis {
    fn scale_values(&self, _typical: f64, values: &mut [f64]) -> &'static str {
        for v in values {
            *v /= 1e6;
        }
        "ms (cpu)"
    }
    fn scale_throughputs(
        &self,
        _typical: f64,
        _t: &Throughput,
        values: &mut [f64],
    ) -> &'static str {
        self.scale_values(0.0, values)
    }
    fn scale_for_machines(&self, _values: &mut [f64]) -> &'static str {
        "ns"
    }
}

impl Measurement for ThreadCpu {
    type Intermediate = Duration;
    type Value = Duration;
    fn start(&self) -> Duration {
        thread_cpu()
    }
    fn end(&self, start: Duration) -> Duration {
        thread_cpu().saturating_sub(start)
    }
    fn add(&self, a: &Duration, b: &Duration) -> Duration {
        *a + *b
    }
    fn zero(&self) -> Duration {
        Duration::ZERO
    }
    fn to_f64(&self, v: &Duration) -> f64 {
        v.as_nanos() as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &Millis
    }
}

fn recheck<M: Measurement + 'static>(c: &mut Criterion<M>, name: &str) {
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
    c.bench_function(name, |b| {
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

fn wall(c: &mut Criterion) {
    recheck(c, "recheck/2000 lines after a keystroke");
}

fn cpu(c: &mut Criterion<ThreadCpu>) {
    recheck(c, "recheck/2000 lines after a keystroke (thread cpu)");
}

criterion_group!(wall_time, wall);
criterion_group! {
    name = cpu_time;
    config = Criterion::default().with_measurement(ThreadCpu);
    targets = cpu
}
criterion_main!(wall_time, cpu_time);
