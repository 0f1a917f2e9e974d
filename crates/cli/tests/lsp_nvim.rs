//! `aster lsp` in a real editor: Neovim, headless, with its built-in LSP
//! client (tests/lsp_nvim/check.lua), opens the broken command file of
//! the LSP tests and must report the server's diagnostics. Skipped when
//! `nvim` is not installed (`apt-get install neovim`).

use std::path::Path;
use std::process::Command;

#[test]
fn neovim_reports_the_diagnostics_of_a_broken_file() {
    if Command::new("nvim").arg("--version").output().is_err() {
        eprintln!("nvim not found: test skipped");
        return;
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let out = std::env::temp_dir().join(format!("aster-lsp-nvim-{}.txt", std::process::id()));
    let status = Command::new("nvim")
        .args(["--headless", "-u", "NONE", "-i", "NONE", "-n"])
        .arg("-c")
        .arg(format!(
            "luafile {}",
            dir.join("lsp_nvim/check.lua").display()
        ))
        .env("ASTER_LSP_FILE", dir.join("lsp_data/broken.comm"))
        .env("ASTER_LSP_OUT", &out)
        .env("ASTER_BIN", env!("CARGO_BIN_EXE_aster"))
        .status()
        .expect("run nvim");
    assert!(status.success(), "nvim exited with {status}");
    let seen = std::fs::read_to_string(&out).expect("nvim wrote the diagnostics");
    let _ = std::fs::remove_file(&out);
    insta::assert_snapshot!("nvim_broken_diagnostics", seen);
}
