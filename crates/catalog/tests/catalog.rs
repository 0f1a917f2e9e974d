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
fn the_static_tables_are_the_catalog_json() {
    // The build script wrote the tables from this JSON; written back, they
    // must give it again, value for value (every keyword, literal, bound,
    // rule and condition, in order).
    let text = include_str!("../data/catalog-v17.json");
    let json: serde_json::Value = serde_json::from_str(text).unwrap();
    let tables = serde_json::to_value(aster_catalog::catalog().commands()).unwrap();
    let (serde_json::Value::Array(want), serde_json::Value::Array(got)) = (&json, &tables) else {
        panic!("both are arrays");
    };
    assert_eq!(want.len(), got.len());
    for (w, g) in want.iter().zip(got) {
        assert!(w == g, "{} differs from its JSON", w["name"]);
    }
}

#[test]
fn every_command_is_found_by_its_name() {
    let cat = catalog();
    assert_eq!(cat.names().count(), 268);
    for (c, name) in cat.commands().iter().zip(cat.names()) {
        assert_eq!(c.name, name);
        assert!(std::ptr::eq(cat.command(name).unwrap(), c), "{name}");
    }
    assert!(cat.command("").is_none());
    assert!(cat.command("stat_non_line").is_none());
}

#[test]
fn every_condition_parses() {
    fn walk(entries: &[aster_catalog::Entry], bad: &mut Vec<String>) {
        for e in entries {
            match &e.node {
                Node::Block(b) => {
                    if let Err(err) = catalog().condition(b.condition) {
                        bad.push(format!("{}: {err}", b.condition));
                    }
                    walk(b.keywords, bad);
                }
                Node::Factor(f) => walk(f.keywords, bad),
                Node::Simple(_) => {}
            }
        }
    }
    let mut bad = Vec::new();
    for c in catalog().commands() {
        walk(c.keywords, &mut bad);
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
        find_in(zone.keywords, "NOM_CMP").is_some(),
        "first ZONE is the LIAISON_UNIL one"
    );

    let lm = catalog().command("LIRE_MAILLAGE").unwrap();
    assert_eq!(lm.produces, Produces::Computed("lire_maillage_sdprod"));
    let snl = catalog().command("STAT_NON_LINE").unwrap();
    assert_eq!(snl.produces, Produces::Type("evol_noli"));
    assert!(matches!(snl.reentrant, Reentrant::Yes { .. }));
    let Some(Node::Factor(newton)) = snl.find("NEWTON").map(|e| &e.node) else {
        panic!("NEWTON missing");
    };
    assert_eq!(newton.status, Status::Defaulted);
}
