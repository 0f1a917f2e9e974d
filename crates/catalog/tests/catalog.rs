use aster_catalog::{catalog, find_in, Node, Produces, Reentrant, Status, ValueType};

/// code_aster 17's 267 catalog commands and `DEFI_CONT`, the macro of
/// `code_aster.MacroCommands.defi_cont` (its catalog `DEFI_CONT_CATA`).
#[test]
fn has_all_268_commands() {
    assert_eq!(catalog().commands().len(), 268);
    assert!(catalog().command("DEFI_CONT").is_some());
    assert!(catalog().command("STAT_NON_LINE").is_some());
    assert!(catalog().command("NO_SUCH").is_none());
}

#[test]
fn a_command_is_read_on_its_first_use_and_alone() {
    let cat = aster_catalog::Catalog::new();
    assert_eq!(cat.read_count(), 0);
    assert_eq!(cat.names().count(), 268, "names need no read");
    let debut = cat.command("DEBUT").expect("DEBUT exists");
    assert_eq!(debut.name, "DEBUT");
    assert_eq!(cat.read_count(), 1);
    assert!(cat.command("DEBUT").is_some());
    assert!(cat.command("NO_SUCH").is_none());
    assert_eq!(cat.read_count(), 1);
    // Read one by one or all at once, a command is the same.
    let lazy = aster_catalog::Catalog::new();
    for (c, name) in cat.commands().iter().zip(cat.names()) {
        assert_eq!(c.name, name);
        assert_eq!(lazy.command(name), Some(c), "{name}");
    }
    assert_eq!(cat.read_count(), 268);
}

#[test]
fn every_condition_parses() {
    fn walk(entries: &[aster_catalog::Entry], bad: &mut Vec<String>) {
        for e in entries {
            match &e.node {
                Node::Block(b) => {
                    if let Err(err) = catalog().condition(&b.condition) {
                        bad.push(format!("{}: {err}", b.condition));
                    }
                    walk(&b.keywords, bad);
                }
                Node::Factor(f) => walk(&f.keywords, bad),
                Node::Simple(_) => {}
            }
        }
    }
    let mut bad = Vec::new();
    for c in catalog().commands() {
        walk(&c.keywords, &mut bad);
    }
    assert!(bad.is_empty(), "{bad:#?}");
}

#[test]
fn keyword_facts_survive_generation() {
    let dc = catalog().command("DEFI_CONTACT").unwrap();
    let Some(Node::Simple(f)) = dc.find("FORMULATION").map(|e| &e.node) else {
        panic!("FORMULATION missing");
    };
    assert_eq!(f.status, Status::Optional);
    assert_eq!(f.types, vec![ValueType::Text]);
    assert_eq!(
        f.default.as_ref().map(|d| d[0].to_string()),
        Some("'DISCRETE'".to_string())
    );
    let Some(Node::Factor(zone)) = dc.find("ZONE").map(|e| &e.node) else {
        panic!("ZONE missing");
    };
    assert!(
        find_in(&zone.keywords, "NOM_CMP").is_some(),
        "first ZONE is the LIAISON_UNIL one"
    );

    let lm = catalog().command("LIRE_MAILLAGE").unwrap();
    assert_eq!(
        lm.produces,
        Produces::Computed("lire_maillage_sdprod".into())
    );
    let snl = catalog().command("STAT_NON_LINE").unwrap();
    assert_eq!(snl.produces, Produces::Type("evol_noli".into()));
    assert!(matches!(snl.reentrant, Reentrant::Yes { .. }));
    let Some(Node::Factor(newton)) = snl.find("NEWTON").map(|e| &e.node) else {
        panic!("NEWTON missing");
    };
    assert_eq!(newton.status, Status::Defaulted);
}
