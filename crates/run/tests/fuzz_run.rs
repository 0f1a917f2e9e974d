//! Fuzzing `aster run` (issue 15): the project's scenes on comm/strip.mail
//! with one value replaced by a hostile one (zero, negative, huge, tiny,
//! subnormal, non-finite, wrong type, a missing group, an empty string) or a
//! line of the mesh damaged. Every run must end with a result or an error
//! value — never a panic, a stack overflow or a hang. proptest runs on
//! stable in `cargo test`, with a fixed number of cases (see
//! crates/eval/tests/fuzz_check.rs for why not `cargo fuzz`).

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

const SCENES: [&str; 5] = [
    "comm/pressure.comm",
    "comm/functions.comm",
    "comm/groups.comm",
    "comm/loads_f.comm",
    "comm/crea_maillage.comm",
];

/// Byte ranges of the numeric and string literals of `src` (outside
/// comments).
fn literals(src: &str) -> Vec<(usize, usize)> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'#' => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b'"' | b'\'' => {
                let q = b[i];
                let s = i;
                i += 1;
                while i < b.len() && b[i] != q && b[i] != b'\n' {
                    i += 1;
                }
                out.push((s, (i + 1).min(b.len())));
                i += 1;
            }
            c if c.is_ascii_digit()
                && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_')) =>
            {
                let s = i;
                while i < b.len()
                    && (b[i].is_ascii_alphanumeric()
                        || b[i] == b'.'
                        || ((b[i] == b'-' || b[i] == b'+') && matches!(b[i - 1], b'e' | b'E')))
                {
                    i += 1;
                }
                out.push((s, i));
            }
            _ => i += 1,
        }
    }
    out
}

const HOSTILE: [&str; 20] = [
    "0",
    "0.0",
    "-1.0",
    "-1",
    "1e308",
    "-1e308",
    "1e-310",
    "float('inf')",
    "float('nan')",
    "10**9",
    "10**30",
    "2**63",
    "1e-9",
    "'NOPE'",
    "''",
    "None",
    "()",
    "(1.0, 2.0)",
    "'X' * 5",
    "-0.0",
];

/// Runs `comm` on `mesh` in a fresh directory on a thread with an 8 MB
/// stack: no panic, within `budget`.
fn exercise(comm: String, mesh: String, budget: Duration) {
    static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("aster-fuzz-run-{}-{k}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let shown = comm.clone();
    let d = dir.clone();
    let handle = std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let t = Instant::now();
            let _ = run_in(&d, &comm, &mesh);
            t.elapsed()
        })
        .expect("thread");
    let r = handle.join();
    let _ = std::fs::remove_dir_all(&dir);
    match r {
        Ok(took) => assert!(took < budget, "{took:?} for:\n{shown}"),
        Err(_) => panic!("panicked on:\n{shown}"),
    }
}

/// Runs `comm` on `mesh` in `dir`: the outcome, or `None` when the case
/// cannot be prepared.
fn run_in(dir: &Path, comm: &str, mesh: &str) -> Option<aster_run::program::Outcome> {
    std::fs::write(dir.join("f.comm"), comm).expect("write");
    std::fs::write(dir.join("f.mail"), mesh).expect("write");
    let case = aster_run::program::prepare(
        &dir.join("f.comm"),
        Some(&dir.join("f.mail")),
        &dir.join("out"),
    )
    .ok()?;
    Some(aster_run::program::run(&case, Box::new(std::io::sink())))
}

fn read(p: &str) -> String {
    std::fs::read_to_string(root().join(p)).expect("scene")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn a_scene_with_a_hostile_value_ends_in_a_result_or_an_error(
        scene in 0usize..SCENES.len(),
        pick in any::<prop::sample::Index>(),
        value in prop::sample::select(HOSTILE.to_vec()),
    ) {
        let src = read(SCENES[scene]);
        let lits = literals(&src);
        let (s, e) = lits[pick.index(lits.len())];
        let comm = format!("{}{}{}", &src[..s], value, &src[e..]);
        exercise(comm, read("comm/strip.mail"), Duration::from_secs(20));
    }

    #[test]
    fn a_scene_on_a_damaged_mesh_ends_in_a_result_or_an_error(
        scene in 0usize..SCENES.len(),
        line in any::<prop::sample::Index>(),
        edit in prop::sample::select(vec!["", "N1 1e308 -1e308", "N99 0 0", "M1 N1 N1 N1 N1", "FINSF", "GROUP_MA NOM=PLATE", "nan nan", "M9 N1"]),
    ) {
        let mesh = read("comm/strip.mail");
        let mut lines: Vec<&str> = mesh.lines().collect();
        let i = line.index(lines.len());
        lines[i] = edit;
        exercise(read(SCENES[scene]), lines.join("\n") + "\n", Duration::from_secs(20));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// The `.export` reader of `aster run`: any text gives an export or an
    /// error, and what it lists is consistent.
    #[test]
    fn export_text_ends_in_an_export_or_an_error(lines in prop::collection::vec(prop_oneof![
        "F (comm|mmed|mail|rmed|libr) [a-z./]{0,12} (D|R|DR|X) -?[0-9]{0,12}",
        "P [a-z_]{0,12} [ -~]{0,20}",
        "[FPAR] [ -~]{0,30}",
        "\\PC{0,40}",
    ], 0..10)) {
        if let Ok(e) = aster_run::export::Export::parse(&lines.join("\n"), Path::new("/cases/x")) {
            let _ = e.comm_files();
            let _ = e.data_units();
        }
    }
}

#[test]
fn the_literal_scanner_finds_the_values() {
    let src = "# 1 2\nx = F(A=1.5e-3, B='G1')\n";
    let found: Vec<&str> = literals(src).iter().map(|&(s, e)| &src[s..e]).collect();
    assert_eq!(found, ["1.5e-3", "'G1'"]);
}

/// The harness runs the scenes for real: unmodified, each passes its checks.
#[test]
fn the_unmodified_scenes_pass_in_the_harness() {
    let dir = std::env::temp_dir().join(format!("aster-fuzz-run-{}-plain", std::process::id()));
    for scene in SCENES {
        let _ = std::fs::create_dir_all(&dir);
        let outcome = run_in(&dir, &read(scene), &read("comm/strip.mail")).expect(scene);
        assert!(outcome.error.is_none(), "{scene}: {:?}", outcome.error);
        assert!(outcome.tally.ok > 0 && outcome.tally.nook == 0, "{scene}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// MODELISATION='3D' on a 2D mesh: said at AFFE_MODELE, not as a singular
/// system at the solve.
#[test]
fn a_3d_model_on_a_2d_mesh_is_refused_at_its_modelisation() {
    let dir = std::env::temp_dir().join(format!("aster-fuzz-run-{}-3d", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let comm = read("comm/pressure.comm").replace("MODELISATION=\"C_PLAN\"", "MODELISATION=\"3D\"");
    let outcome = run_in(&dir, &comm, &read("comm/strip.mail")).expect("prepared");
    let e = outcome.error.expect("refused").message;
    assert!(e.contains("MODELISATION='3D' needs volume cells"), "{e}");
    assert!(e.contains("f.comm:13:"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
