//! docs/supported.md documents exactly the commands `aster run` executes
//! (`aster_run::commands::COMMANDS`, the support table): a command added to
//! the table needs its section, and a section needs its command.

use std::collections::BTreeSet;

#[test]
fn supported_md_has_a_section_per_executed_command() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/supported.md");
    let text = std::fs::read_to_string(path).expect("docs/supported.md");
    let documented: BTreeSet<&str> = text
        .lines()
        .filter_map(|l| l.strip_prefix("## "))
        .flat_map(|h| h.split(" / "))
        .map(str::trim)
        .filter(|w| {
            !w.is_empty()
                && w.chars()
                    .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
        })
        .collect();
    let executed: BTreeSet<&str> = aster_run::commands::COMMANDS
        .iter()
        .map(|c| c.name)
        .collect();
    let undocumented: Vec<_> = executed.difference(&documented).collect();
    let unexecuted: Vec<_> = documented.difference(&executed).collect();
    assert!(
        undocumented.is_empty() && unexecuted.is_empty(),
        "executed but without a section in docs/supported.md: {undocumented:?}; \
         a section but not executed: {unexecuted:?}"
    );
}
