//! `aster fmt FILE... [--check | --write]` over several files, and the shell
//! completions of `aster completions SHELL`. The scenes are written here.

mod cli;

use cli::aster;
use std::path::PathBuf;

/// Not canonical: single quotes, a call on one long line, spacing.
const RAGGED: &str = "\
# kept comment
DEBUT( CODE='OUI' )
MA=LIRE_MAILLAGE(FORMAT='ASTER',UNITE=20)
FIN()
";

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-fmt-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A ragged file and its canonical form (`aster fmt` of it), both on disk.
fn pair(tag: &str) -> (PathBuf, PathBuf) {
    let d = dir(tag);
    let ragged = d.join("ragged.comm");
    std::fs::write(&ragged, RAGGED).unwrap();
    let (code, canonical, err) = aster(&["fmt", ragged.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let clean = d.join("clean.comm");
    std::fs::write(&clean, &canonical).unwrap();
    (ragged, clean)
}

#[test]
fn fmt_prints_the_canonical_form() {
    let (ragged, _) = pair("print");
    let (_, text, _) = aster(&["fmt", ragged.to_str().unwrap()]);
    insta::assert_snapshot!("fmt_canonical", text);
}

#[test]
fn fmt_check_names_what_would_change_and_changes_nothing() {
    let (ragged, clean) = pair("check");
    let (r, c) = (ragged.to_str().unwrap(), clean.to_str().unwrap());
    // A canonical file alone: exit 0, no diff.
    let (code, out, err) = aster(&["fmt", "--check", c]);
    assert_eq!((code, out.as_str()), (0, ""), "{err}");
    assert!(
        err.contains("0 file(s) would be reformatted, 1 already canonical"),
        "{err}"
    );
    // With the ragged one: exit 1, its diff and its name, the file untouched.
    let (code, diff, err) = aster(&["fmt", "--check", c, r]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains(&format!("would reformat: {r}")), "{err}");
    assert!(!err.contains(&format!("would reformat: {c}")), "{err}");
    assert!(
        err.contains("1 file(s) would be reformatted, 1 already canonical"),
        "{err}"
    );
    insta::assert_snapshot!("fmt_check_diff", diff.replace(r, "ragged.comm"));
    assert_eq!(std::fs::read_to_string(&ragged).unwrap(), RAGGED);
}

#[test]
fn fmt_write_rewrites_in_place_and_is_idempotent() {
    let (ragged, clean) = pair("write");
    let (r, c) = (ragged.to_str().unwrap(), clean.to_str().unwrap());
    let (code, _, err) = aster(&["fmt", "--write", r, c]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("1 file(s) reformatted, 1 left unchanged"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(&ragged).unwrap(),
        std::fs::read_to_string(&clean).unwrap()
    );
    let (code, _, _) = aster(&["fmt", "--check", r, c]);
    assert_eq!(code, 0);
}

#[test]
fn fmt_write_keeps_a_latin1_file_latin1() {
    let d = dir("latin1");
    let p = d.join("old.comm");
    // "# déplacement" in Latin-1 (é = 0xE9), then a non-canonical call.
    let mut bytes = b"# d\xe9placement\nDEBUT( )\n".to_vec();
    bytes.extend_from_slice(b"FIN()\n");
    std::fs::write(&p, &bytes).unwrap();
    let (code, _, err) = aster(&["fmt", "--write", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let out = std::fs::read(&p).unwrap();
    assert!(std::str::from_utf8(&out).is_err(), "still Latin-1");
    assert!(out.starts_with(b"# d\xe9placement\n"));
    assert!(out.windows(7).any(|w| w == b"DEBUT()"));
}

#[test]
fn fmt_reports_a_file_that_does_not_parse_and_goes_on() {
    let d = dir("broken");
    let broken = d.join("broken.comm");
    std::fs::write(&broken, "DEBUT(\n").unwrap();
    let (_, clean) = pair("broken-pair");
    let (code, _, err) = aster(&[
        "fmt",
        "--check",
        broken.to_str().unwrap(),
        clean.to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("broken.comm:"), "{err}");
    assert!(
        err.contains("0 file(s) would be reformatted, 1 already canonical"),
        "{err}"
    );
    let (code, _, err) = aster(&["fmt", "--check", d.join("missing.comm").to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn completions_are_generated_for_each_shell() {
    for (shell, marker, flag) in [
        ("bash", "_aster()", "--write"),
        ("zsh", "#compdef aster", "--write"),
        ("fish", "complete -c aster", "-l write"),
    ] {
        let (code, script, err) = aster(&["completions", shell]);
        assert_eq!(code, 0, "{err}");
        assert!(script.contains(marker), "{shell}: {script}");
        // Every subcommand and the fmt flags are offered.
        for word in ["run", "check", "explain", "migrate", "completions", flag] {
            assert!(script.contains(word), "{shell} lacks {word}");
        }
    }
    let (code, _, err) = aster(&["completions", "tcsh"]);
    assert_eq!(code, 2);
    assert!(err.contains("possible values"), "{err}");
}

#[test]
fn every_subcommand_help_has_examples() {
    for sub in [
        "parse",
        "fmt",
        "check",
        "explain",
        "migrate",
        "mesh",
        "run",
        "study",
        "lsp",
        "completions",
    ] {
        let (code, help, err) = aster(&[sub, "--help"]);
        assert_eq!(code, 0, "{sub}: {err}");
        assert!(
            help.contains("Example"),
            "{sub} --help has no example:\n{help}"
        );
        assert!(help.contains(&format!("aster {sub} ")), "{sub}:\n{help}");
    }
}

/// A reader that stops early (`aster explain X | head -1`): a quiet stop
/// with the SIGPIPE status, no panic message.
#[test]
fn a_closed_stdout_stops_quietly() {
    use std::io::Read;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(["explain", "--all", "DEFI_MATERIAU"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    drop(child.stdout.take());
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    let status = child.wait().unwrap();
    assert!(!err.contains("panicked"), "{err}");
    assert!(matches!(status.code(), Some(141) | Some(0)), "{status:?}");
}
