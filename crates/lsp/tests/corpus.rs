//! No false diagnostic on the real corpus: every code_aster 17 file of
//! `../shared/corpus/v17` that `aster check` finds clean is opened in the
//! server (an in-memory connection, real LSP messages) and must get no
//! error, and exactly the warnings `aster check` gives. Skipped when the
//! shared material is absent (a fresh clone).

use lsp_server::{Connection, Message, Notification, Request, RequestId};
use serde_json::json;
use std::path::Path;

#[test]
fn clean_v17_files_get_no_false_diagnostic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/v17");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("{}: absent, test skipped", dir.display());
        return;
    };
    let mut files: Vec<_> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "comm"))
        .collect();
    files.sort();
    let (client, server) = Connection::memory();
    let thread = std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(move || aster_lsp::serve(server).map_err(|e| e.to_string()))
        .unwrap();
    client
        .sender
        .send(Message::Request(Request::new(
            RequestId::from(1),
            "initialize".into(),
            json!({"capabilities": {}, "initializationOptions": {"debounceMs": 0}}),
        )))
        .unwrap();
    let _ = client.receiver.recv().unwrap();
    client
        .sender
        .send(Message::Notification(Notification::new(
            "initialized".into(),
            json!({}),
        )))
        .unwrap();
    let (mut clean, mut opened) = (0, 0);
    let mut false_diags = Vec::new();
    for f in &files {
        let text = aster_syntax::read_source(f).unwrap();
        let map = aster_syntax::CodeMap::new(f.display().to_string(), text.clone());
        let report = aster_eval::check_source(&map, false);
        if !report.ok() {
            continue;
        }
        clean += 1;
        let warnings = report.diagnostics.0.len();
        let uri = format!(
            "file:///corpus/{}",
            f.file_name().unwrap().to_string_lossy()
        );
        for (method, params) in [
            (
                "textDocument/didOpen",
                json!({"textDocument": {"uri": uri, "languageId": "comm", "version": 1, "text": text}}),
            ),
            (
                "textDocument/didClose",
                json!({"textDocument": {"uri": uri}}),
            ),
        ] {
            client
                .sender
                .send(Message::Notification(Notification::new(
                    method.into(),
                    params,
                )))
                .unwrap();
            let Message::Notification(n) = client.receiver.recv().unwrap() else {
                panic!("expected a notification");
            };
            if method == "textDocument/didOpen" {
                opened += 1;
                let diags = n.params["diagnostics"].as_array().unwrap();
                let errors = diags.iter().filter(|d| d["severity"] == 1).count();
                let warns = diags.iter().filter(|d| d["severity"] == 2).count();
                if errors > 0 || warns != warnings {
                    false_diags.push(format!(
                        "{}: {errors} errors, {warns} warnings (check: {warnings})",
                        f.display()
                    ));
                }
            }
        }
    }
    client
        .sender
        .send(Message::Request(Request::new(
            RequestId::from(2),
            "shutdown".into(),
            json!(null),
        )))
        .unwrap();
    let _ = client.receiver.recv().unwrap();
    client
        .sender
        .send(Message::Notification(Notification::new(
            "exit".into(),
            json!(null),
        )))
        .unwrap();
    thread.join().unwrap().unwrap();
    eprintln!(
        "{opened} clean files opened in the server ({} files)",
        files.len()
    );
    assert_eq!(opened, clean);
    assert!(false_diags.is_empty(), "{}", false_diags.join("\n"));
}
