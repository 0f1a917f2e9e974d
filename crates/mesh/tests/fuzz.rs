//! Random and mutated input never panics the readers: they return a mesh
//! or an error.

use aster_mesh::med::read_med_bytes;
use aster_mesh::{ideas_to_mail, med_bytes, parse_mail};
use proptest::prelude::*;
use std::path::Path;

const VALID: &str = "TITRE\nt\nFINSF\nCOOR_2D\nN1 0 0\nN2 1 0\nN3 1 1\nN4 0 1\nFINSF\n\
    QUAD4\nM1 N1 N2 N3 N4\nFINSF\nSEG2\nS1 N1 N2\nS2 N2 N3\nFINSF\n\
    GROUP_MA\nG S1 S2\nFINSF\nGROUP_NO NOM=P\nN1 N3\nFINSF\nFIN\n";

/// Words the format uses, to build plausible-looking garbage.
fn word() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("COOR_2D".to_string()),
        Just("COOR_3D".to_string()),
        Just("SEG2".to_string()),
        Just("QUAD4".to_string()),
        Just("HEXA8".to_string()),
        Just("GROUP_MA".to_string()),
        Just("GROUP_NO".to_string()),
        Just("NOM=".to_string()),
        Just("FINSF".to_string()),
        Just("FIN".to_string()),
        Just("TITRE".to_string()),
        Just("%".to_string()),
        Just("\n".to_string()),
        "N[0-9]{1,2}",
        "M[0-9]",
        "-?[0-9]{1,3}(\\.[0-9]*)?([ED][+-]?[0-9]{1,3})?",
        "[ -~]{0,6}",
    ]
}

/// The project's I-DEAS universal file (comm/ideas_bar.unv).
const UNV: &str = include_str!("../../../comm/ideas_bar.unv");

/// Lines an I-DEAS file is made of, to build plausible-looking garbage.
fn unv_line() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("    -1".to_string()),
        Just("  2411".to_string()),
        Just("  2412".to_string()),
        Just("  2467".to_string()),
        Just("  2420".to_string()),
        Just("   752".to_string()),
        "( *-?[0-9]{1,10}){1,8}",
        "( *-?[0-9]\\.[0-9]{1,16}D[+-][0-9]{2}){1,3}",
        "[ -~]{0,20}",
    ]
}

/// The I-DEAS converter then the ASTER reader, as LIRE_MAILLAGE does.
fn read_unv(text: &str) {
    if let Ok(mail) = ideas_to_mail(text, Path::new("fuzz.unv"), true) {
        let _ = parse_mail(&mail, Path::new("fuzz.unv"));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn ideas_reader_never_panics_on_mutations(pos in 0usize..UNV.len(), len in 0usize..40, insert in "[ -~\n]{0,12}") {
        let mut text = UNV.to_string();
        let start = pos.min(text.len());
        let end = (start + len).min(text.len());
        text.replace_range(start..end, &insert);
        read_unv(&text);
    }

    #[test]
    fn ideas_reader_never_panics_on_line_soup(lines in prop::collection::vec(unv_line(), 0..60)) {
        read_unv(&lines.join("\n"));
    }

    #[test]
    fn ideas_reader_never_panics_on_arbitrary_text(text in "\\PC{0,300}") {
        read_unv(&text);
    }

    #[test]
    fn mail_reader_never_panics_on_word_soup(words in prop::collection::vec(word(), 0..60)) {
        let text = words.join(" ");
        let _ = parse_mail(&text, Path::new("fuzz.mail"));
    }

    #[test]
    fn mail_reader_never_panics_on_mutations(pos in 0usize..VALID.len(), len in 0usize..20, insert in "[ -~\n]{0,10}") {
        let mut text = VALID.to_string();
        let start = pos.min(text.len());
        let end = (start + len).min(text.len());
        text.replace_range(start..end, &insert);
        let _ = parse_mail(&text, Path::new("fuzz.mail"));
    }

    #[test]
    fn mail_reader_never_panics_on_arbitrary_text(text in "\\PC{0,300}") {
        let _ = parse_mail(&text, Path::new("fuzz.mail"));
    }

    #[test]
    fn med_reader_never_panics_on_corrupted_bytes(flips in prop::collection::vec((0usize..100_000, any::<u8>()), 1..8), cut in 0usize..100_000) {
        let mesh = parse_mail(VALID, Path::new("v.mail")).unwrap();
        let mut bytes = med_bytes(&mesh, "V", &[]).unwrap();
        for (at, b) in flips {
            let i = at % bytes.len();
            bytes[i] = b;
        }
        let keep = bytes.len() - cut % bytes.len();
        bytes.truncate(keep);
        let _ = read_med_bytes(bytes, Path::new("fuzz.med"), None);
    }

    #[test]
    fn export_reader_never_panics(lines in prop::collection::vec(prop_oneof![
        "F (comm|mmed|mail|rmed) [a-z./]{0,12} (D|R|DR|X) -?[0-9]{0,12}",
        "[FPA] [ -~]{0,30}",
        "\\PC{0,40}",
    ], 0..8), unit in 0u32..100) {
        static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let k = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!("aster-fuzz-{}-{k}.export", std::process::id()));
        std::fs::write(&path, lines.join("\n")).unwrap();
        if let Ok(files) = aster_mesh::read_export(&path) {
            prop_assert!(files.iter().all(|f| !f.kind.is_empty()));
        }
        let _ = aster_mesh::unit_path(&path, unit);
        let _ = std::fs::remove_file(&path);
    }
}

#[test]
fn valid_input_of_the_fuzzers_reads() {
    let unv = parse_mail(
        &ideas_to_mail(UNV, Path::new("v.unv"), true).unwrap(),
        Path::new("v.unv"),
    )
    .unwrap();
    // With CREA_GROUP_COUL='OUI': COUL_11 (nodes) and COUL_7 (cells) too.
    assert_eq!((unv.node_count(), unv.cells.len()), (32, 4));
    assert_eq!(unv.group_no("COUL_11").unwrap().members.len(), 32);
    assert_eq!(unv.group_ma("COUL_7").unwrap().members.len(), 4);
    let m = parse_mail(VALID, Path::new("v.mail")).unwrap();
    assert_eq!(
        (
            m.node_count(),
            m.cells.len(),
            m.groups_ma.len(),
            m.groups_no.len()
        ),
        (4, 3, 1, 1)
    );
    let back = read_med_bytes(med_bytes(&m, "V", &[]).unwrap(), Path::new("v.med"), None)
        .unwrap()
        .0;
    assert_eq!(back.node_count(), 4);
}
