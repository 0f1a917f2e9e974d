use aster_catalog::explain::explain;

#[test]
fn explain_commands() {
    insta::assert_snapshot!(
        "defi_materiau_head",
        explain("DEFI_MATERIAU")
            .unwrap()
            .lines()
            .take(40)
            .collect::<Vec<_>>()
            .join("\n")
    );
    insta::assert_snapshot!("affe_modele", explain("AFFE_MODELE").unwrap());
    insta::assert_snapshot!("defi_contact", explain("DEFI_CONTACT").unwrap());
    insta::assert_snapshot!("stat_non_line", explain("STAT_NON_LINE").unwrap());
}

#[test]
fn explain_keywords() {
    insta::assert_snapshot!(
        "defi_contact_zone_escl",
        explain("DEFI_CONTACT/ZONE/GROUP_MA_ESCL").unwrap()
    );
    insta::assert_snapshot!(
        "affe_modele_affe_phenomene",
        explain("affe_modele/AFFE/PHENOMENE").unwrap()
    );
    insta::assert_snapshot!(
        "stat_non_line_newton",
        explain("STAT_NON_LINE/NEWTON").unwrap()
    );
}

#[test]
fn explain_suggests() {
    let e = explain("STAT_NON_LIN").unwrap_err();
    assert!(e.contains("`STAT_NON_LINE`"), "{e}");
    let e = explain("DEFI_CONTACT/ZONE/GROUP_MA_ESC").unwrap_err();
    assert!(e.contains("`GROUP_MA_ESCL`"), "{e}");
}
