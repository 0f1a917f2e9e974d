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

#[test]
fn conditions_read_in_plain_words() {
    use aster_catalog::explain::plain_condition;
    assert_eq!(
        plain_condition(r#"equal_to("FORMULATION", 'CONTINUE')"#),
        "FORMULATION='CONTINUE'"
    );
    assert_eq!(
        plain_condition(
            r#"equal_to("FORMULATION", 'CONTINUE') and not equal_to("FROTTEMENT", 'COULOMB')"#
        ),
        "FORMULATION='CONTINUE' and FROTTEMENT≠'COULOMB'"
    );
    assert_eq!(
        plain_condition(r#"is_in("OPTION", ('SEPARE','AJUSTE')) and not exists("MATR_AMOR")"#),
        "OPTION one of 'SEPARE', 'AJUSTE' and MATR_AMOR is not given"
    );
    assert_eq!(
        plain_condition(r#"((equal_to("CARA", 'K_T_D_N')or(equal_to("CARA", 'A_T_D_N'))))"#),
        "((CARA='K_T_D_N' or (CARA='A_T_D_N')))"
    );
    // A tuple compared with equal_to: one of its values.
    assert_eq!(
        plain_condition(r#"equal_to('MODELISATION', ('D_PLAN_DIL', '3D_DIL', ))"#),
        "MODELISATION one of 'D_PLAN_DIL', '3D_DIL'"
    );
    // What is not one of the catalog's helpers stays as written.
    assert_eq!(
        plain_condition(r#"exists("TYPE_COEUR") and TYPE_COEUR.startswith('MONO')"#),
        "TYPE_COEUR is given and TYPE_COEUR.startswith('MONO')"
    );
    // A name that merely ends like a helper is left alone.
    assert_eq!(plain_condition("not_exists(X)"), "not_exists(X)");
}

#[test]
fn paths_from_diagnostics_are_accepted() {
    let from_diag = explain("`DEFI_CONTACT/ZONE[1]/GROUP_MA_ESCL`").unwrap();
    assert_eq!(
        from_diag,
        explain("DEFI_CONTACT/ZONE/GROUP_MA_ESCL").unwrap()
    );
}

#[test]
fn a_keyword_at_another_place_is_pointed_at() {
    let e = explain("STAT_NON_LINE/RESI_GLOB_RELA").unwrap_err();
    assert_eq!(
        e,
        "STAT_NON_LINE has no keyword `RESI_GLOB_RELA` there; RESI_GLOB_RELA exists as `STAT_NON_LINE/CONVERGENCE/RESI_GLOB_RELA`"
    );
    let e = explain("DEFI_CONTACT/COEF_PENA_CONT").unwrap_err();
    assert!(
        e.contains("exists as `DEFI_CONTACT/ZONE/COEF_PENA_CONT` (under"),
        "{e}"
    );
}

#[test]
fn all_lists_every_value() {
    use aster_catalog::explain::{explain_with, Options};
    let short = explain("AFFE_MODELE/AFFE/MODELISATION").unwrap();
    let all = explain_with("AFFE_MODELE/AFFE/MODELISATION", Options { all: true }).unwrap();
    assert!(short.contains("… ("), "{short}");
    assert!(!all.contains("… ("), "{all}");
    assert!(all.contains("'DKT'") && all.len() > short.len());
}
