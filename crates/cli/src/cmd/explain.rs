//! `aster explain CMD[/KEYWORD/...] [--all]`: the keyword tree of a command,
//! or the facts of one keyword (status, type, default, allowed values,
//! conditions in plain words), what `aster run` does with it, and — for a
//! code_aster 11–15 name — its code_aster 17 replacement.

use aster_catalog::explain::{explain_with, Options};

pub fn run(path: &str, all: bool) -> u8 {
    let options = Options { all };
    match explain_with(path, options) {
        Ok(text) => {
            print!("{text}");
            if let Some(line) = run_support(path) {
                println!("{line}");
            }
            0
        }
        Err(e) => match legacy(path) {
            Some((note, new_path)) => {
                println!("{note}\n");
                match explain_with(&new_path, options) {
                    Ok(text) => {
                        print!("{text}");
                        0
                    }
                    Err(_) => 0,
                }
            }
            None => {
                eprintln!("aster explain: {e}");
                1
            }
        },
    }
}

/// The path's parts, upper case, without occurrence indices.
fn parts(path: &str) -> Vec<String> {
    path.trim()
        .trim_matches('`')
        .split('/')
        .map(|p| p.split('[').next().unwrap_or(p).trim().to_uppercase())
        .filter(|p| !p.is_empty())
        .collect()
}

/// What `aster run` does with a command or keyword path.
fn run_support(path: &str) -> Option<String> {
    let parts = parts(path);
    let (cmd, kws) = parts.split_first()?;
    let text = aster_run::support::describe(cmd, &kws.join("/"));
    Some(format!("\naster run: {text}"))
}

/// A code_aster 11–15 name (a renamed or dropped keyword, a removed
/// command): a note, and the path to explain instead.
fn legacy(path: &str) -> Option<(String, String)> {
    let parts = parts(path);
    let (cmd, kws) = parts.split_first()?;
    let Some(last) = kws.last() else {
        let why = aster_eval::legacy::removed_command(cmd)?;
        return Some((
            format!("{cmd} is not a code_aster 17 command: {why}"),
            String::new(),
        ));
    };
    let renames = aster_eval::legacy::RENAMES
        .iter()
        .map(|(c, old, new, note)| (*c, *old, *new, *note))
        .chain(
            aster_eval::legacy::LEGACY_RENAMES
                .iter()
                .map(|(c, old, new)| (*c, *old, *new, "")),
        );
    for (c, old, new, note) in renames {
        if (c == "*" || c == cmd) && old == last {
            let mut new_parts = parts.clone();
            if let Some(l) = new_parts.last_mut() {
                *l = new.to_string();
            }
            let mut text = format!(
                "{last} is the code_aster 11–15 name of {new}: `aster migrate` rewrites it"
            );
            if !note.is_empty() {
                text.push_str(&format!(" ({note})"));
            }
            return Some((text, new_parts.join("/")));
        }
    }
    let dropped = aster_eval::legacy::DROPPED
        .iter()
        .chain(aster_eval::legacy::LEGACY_DROPPED.iter());
    for (c, _, name, why) in dropped {
        if (*c == "*" || c == cmd) && name == last {
            let parent = parts[..parts.len() - 1].join("/");
            return Some((
                format!("{last} is gone from code_aster 17 ({why}): `aster migrate` removes it"),
                parent,
            ));
        }
    }
    None
}
