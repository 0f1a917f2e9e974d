//! Links `aster` as a position-dependent executable (`-no-pie`).
//!
//! The catalog is static tables of the model's types (crates/catalog,
//! `build.rs`): 2.6 MB of data holding some 48,000 pointers (names,
//! keyword lists, literals). In a position-independent executable the
//! dynamic loader rewrites every one of them at each start — 66,000
//! relative relocations, every page of the tables touched: 3.2 ms and 630
//! page faults before `main`, more than the rest of `aster check` of a
//! small file. Linked at a fixed address, the linker resolves them once and
//! the loader maps the pages untouched (docs/performance.md).

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if os == "linux" {
        println!("cargo::rustc-link-arg-bin=aster=-no-pie");
    }
}
