//! LIAISON_MAIL (TYPE_RACCORD='MASSIF'): comm/liaison_mail.comm glues two
//! blocks that share no node; the uniform tension is exact across the glue
//! (the patch test within 1e-9, the glued node in the middle of the master
//! edge included). Without the glue the right block floats; what is not
//! reproduced is refused at its keyword.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(
        text,
        "comm/liaison_mail.mail",
        &format!("liaison-mail-{tag}"),
    )
}

fn glued() -> String {
    scene::read("liaison_mail.comm")
}

#[test]
fn glued_blocks_pass_the_patch_test() {
    assert_eq!(run(&glued(), "scene"), (10, 0, None));
}

/// Only DX glued: the right block has no DY link but its bottom node is
/// held, so the answer is the same (the uniform state needs no DY force at
/// the interface).
#[test]
fn ddl_restricts_the_glued_components() {
    let text = glued().replace(
        "GROUP_MA_ESCL=\"ESCL\")",
        "GROUP_MA_ESCL=\"ESCL\", DDL=\"DX\")",
    );
    assert!(text.contains("DDL=\"DX\""));
    assert_eq!(run(&text, "ddl"), (10, 0, None));
}

#[test]
fn without_the_glue_the_right_block_floats() {
    let text = glued().replace(", _F(CHARGE=glue)", "");
    let (ok, nook, err) = run(&text, "free");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("a singular system");
    assert!(err.contains("DX"), "{err}");
}

/// Every slave node already glued by the first occurrence: code_aster's
/// CHARGES7_48.
#[test]
fn a_second_occurrence_with_no_new_slave_is_an_error() {
    let text = glued().replace(
        "LIAISON_MAIL=_F(GROUP_MA_MAIT=\"LEFT\", GROUP_MA_ESCL=\"ESCL\")",
        "LIAISON_MAIL=(_F(GROUP_MA_MAIT=\"LEFT\", GROUP_MA_ESCL=\"ESCL\"), _F(GROUP_MA_MAIT=\"LEFT\", GROUP_NO_ESCL=\"MID\"))",
    );
    let (_, _, err) = run(&text, "elim");
    let err = err.expect("an error");
    assert!(
        err.contains("CHARGES7_48") && err.contains("occurrence 2"),
        "{err}"
    );
}

#[test]
fn shells_and_rigid_transforms_are_refused_at_the_keyword() {
    for (from, to, what) in [
        (
            "GROUP_MA_ESCL=\"ESCL\")",
            "GROUP_MA_ESCL=\"ESCL\", TYPE_RACCORD=\"COQUE\")",
            "LIAISON_MAIL/TYPE_RACCORD",
        ),
        (
            "GROUP_MA_ESCL=\"ESCL\")",
            "GROUP_MA_ESCL=\"ESCL\", TRAN=(0.0, 0.0))",
            "LIAISON_MAIL/TRAN",
        ),
    ] {
        let text = glued().replace(from, to);
        assert!(text.contains(to));
        let (ok, nook, err) = run(&text, "refused");
        assert_eq!((ok, nook), (0, 0));
        let err = err.expect("refused");
        assert!(err.contains("not supported") && err.contains(what), "{err}");
    }
}
