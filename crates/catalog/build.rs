//! Splits the embedded catalog into one JSON text per command, with an
//! index by name, so that the program deserialises only the commands a file
//! uses (see `src/load.rs`).

use std::fmt::Write as _;
use std::path::PathBuf;

fn main() {
    let src = "data/catalog-v17.json";
    println!("cargo::rerun-if-changed={src}");
    let text = std::fs::read_to_string(src).expect("data/catalog-v17.json is readable");
    let commands: Vec<serde_json::Value> =
        serde_json::from_str(&text).expect("data/catalog-v17.json is a JSON array");
    let mut blob = String::with_capacity(text.len());
    // (name, start, end) in catalog order.
    let mut spans: Vec<(String, usize, usize)> = Vec::with_capacity(commands.len());
    for c in &commands {
        let name = c
            .get("name")
            .and_then(|n| n.as_str())
            .expect("every command has a name")
            .to_string();
        let start = blob.len();
        blob.push_str(&serde_json::to_string(c).expect("a JSON value serialises"));
        spans.push((name, start, blob.len()));
    }
    let mut sorted: Vec<usize> = (0..spans.len()).collect();
    sorted.sort_by(|&a, &b| spans[a].0.cmp(&spans[b].0));
    let mut index = String::new();
    writeln!(
        index,
        "/// Commands in catalog order: name, then the span of its JSON in `BLOB`."
    )
    .unwrap();
    writeln!(
        index,
        "pub static COMMANDS: [(&str, u32, u32); {}] = [",
        spans.len()
    )
    .unwrap();
    for (n, a, b) in &spans {
        writeln!(index, "    ({n:?}, {a}, {b}),").unwrap();
    }
    writeln!(index, "];").unwrap();
    writeln!(index, "/// Positions in `COMMANDS`, sorted by name.").unwrap();
    writeln!(
        index,
        "pub static BY_NAME: [u16; {}] = {sorted:?};",
        sorted.len()
    )
    .unwrap();
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::write(out.join("catalog-commands.json"), blob).expect("OUT_DIR is writable");
    std::fs::write(out.join("catalog-index.rs"), index).expect("OUT_DIR is writable");
}
