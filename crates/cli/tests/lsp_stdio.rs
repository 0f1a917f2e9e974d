//! `aster lsp` driven over stdio with real JSON-RPC messages, as an editor
//! does: initialize, didOpen, didChange (incremental), hover, completion,
//! signature help, definition, references, document symbols, codeAction,
//! shutdown and exit — on a `comm/` scene and on a broken variant of it
//! (`tests/lsp_data/broken.comm`, whose mesh sits beside it). Positions and
//! contents are insta snapshots.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

struct Client {
    child: Child,
    stdin: ChildStdin,
    stdout: BufReader<ChildStdout>,
    next_id: i64,
    /// Notifications read while waiting for a response.
    pending: Vec<Value>,
}

impl Client {
    fn start() -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_aster"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start aster lsp");
        let stdin = child.stdin.take().unwrap();
        let stdout = BufReader::new(child.stdout.take().unwrap());
        Client {
            child,
            stdin,
            stdout,
            next_id: 0,
            pending: Vec::new(),
        }
    }

    fn send(&mut self, msg: Value) {
        let body = msg.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        self.stdin.flush().unwrap();
    }

    fn read(&mut self) -> Value {
        let mut len = 0usize;
        loop {
            let mut line = String::new();
            assert!(
                self.stdout.read_line(&mut line).unwrap() > 0,
                "server closed"
            );
            let line = line.trim_end();
            if line.is_empty() {
                break;
            }
            if let Some(v) = line.strip_prefix("Content-Length: ") {
                len = v.parse().unwrap();
            }
        }
        let mut body = vec![0; len];
        self.stdout.read_exact(&mut body).unwrap();
        serde_json::from_slice(&body).unwrap()
    }

    fn request(&mut self, method: &str, params: Value) -> Value {
        self.next_id += 1;
        let id = self.next_id;
        self.send(json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        loop {
            let msg = self.read();
            if msg.get("id") == Some(&json!(id)) {
                assert!(msg.get("error").is_none(), "{method}: {msg}");
                return msg["result"].clone();
            }
            self.pending.push(msg);
        }
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// The next diagnostics published for `uri`.
    fn diagnostics(&mut self, uri: &str) -> Vec<Value> {
        loop {
            let msg = match self
                .pending
                .iter()
                .position(|m| m["method"] == "textDocument/publishDiagnostics")
            {
                Some(i) => self.pending.remove(i),
                None => self.read(),
            };
            if msg["method"] == "textDocument/publishDiagnostics" && msg["params"]["uri"] == uri {
                return msg["params"]["diagnostics"]
                    .as_array()
                    .cloned()
                    .unwrap_or_default();
            }
        }
    }
}

fn uri(path: &Path) -> String {
    format!("file://{}", path.canonicalize().unwrap().display())
}

fn pos(l: u64, c: u64) -> Value {
    json!({"line": l, "character": c})
}

fn at(u: &str, l: u64, c: u64) -> Value {
    json!({"textDocument": {"uri": u}, "position": pos(l, c)})
}

/// `line:col-line:col` (0-based, UTF-16 columns, as the protocol says).
fn range(r: &Value) -> String {
    format!(
        "{}:{}-{}:{}",
        r["start"]["line"], r["start"]["character"], r["end"]["line"], r["end"]["character"]
    )
}

fn show_diagnostics(d: &[Value]) -> String {
    d.iter()
        .map(|d| {
            let mut s = format!(
                "{} sev{} {}: {}",
                range(&d["range"]),
                d["severity"],
                d["code"].as_str().unwrap_or(""),
                d["message"].as_str().unwrap_or("")
            );
            for r in d["relatedInformation"].as_array().into_iter().flatten() {
                s.push_str(&format!(
                    "\n    related {}: {}",
                    range(&r["location"]["range"]),
                    r["message"].as_str().unwrap_or("")
                ));
            }
            s
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn labels(completion: &Value) -> Vec<String> {
    completion["items"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| {
            format!(
                "{} [{}]",
                i["label"].as_str().unwrap(),
                i["detail"].as_str().unwrap_or("")
            )
        })
        .collect()
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/lsp_data")
        .join(name)
}

fn open(c: &mut Client, path: &Path) -> (String, String) {
    let text = std::fs::read_to_string(path).unwrap();
    let u = uri(path);
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": u, "languageId": "comm", "version": 1, "text": text}}),
    );
    (u, text)
}

fn start() -> Client {
    let mut c = Client::start();
    let init = c.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {},
               "initializationOptions": {"debounceMs": 0}}),
    );
    assert_eq!(init["capabilities"]["textDocumentSync"]["change"], 2);
    assert_eq!(init["serverInfo"]["name"], "aster");
    c.notify("initialized", json!({}));
    c
}

fn stop(mut c: Client) {
    assert_eq!(c.request("shutdown", Value::Null), Value::Null);
    c.notify("exit", Value::Null);
    let status = c.child.wait().unwrap();
    assert!(status.success(), "aster lsp exited with {status}");
}

/// The line and UTF-16 column of the first `needle` after `after` in `text`.
fn find(text: &str, after: &str, needle: &str) -> (u64, u64) {
    let base = text.find(after).expect(after);
    let off = base + text[base..].find(needle).expect(needle);
    let line = text[..off].matches('\n').count() as u64;
    let start = text[..off].rfind('\n').map(|i| i + 1).unwrap_or(0);
    (line, text[start..off].encode_utf16().count() as u64)
}

#[test]
fn a_clean_scene_has_no_diagnostic_and_an_outline() {
    let mut c = start();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../comm/zzzz237b.comm");
    let (u, text) = open(&mut c, &path);
    let d = c.diagnostics(&u);
    assert!(d.is_empty(), "{}", show_diagnostics(&d));
    let symbols = c.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": u}}),
    );
    let outline: Vec<String> = symbols
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let children: Vec<&str> = s["children"]
                .as_array()
                .into_iter()
                .flatten()
                .map(|c| c["name"].as_str().unwrap())
                .collect();
            format!(
                "{} {} {:?}",
                range(&s["range"]),
                s["name"].as_str().unwrap(),
                children
            )
        })
        .collect();
    insta::assert_snapshot!("lsp_outline_zzzz237b", outline.join("\n"));
    // Definition of `model` from its use in STAT_NON_LINE, and its references.
    let (l, col) = find(&text, "STAT_NON_LINE(", "model");
    let def = c.request("textDocument/definition", at(&u, l, col + 2));
    assert_eq!(range(&def["range"]), "22:0-22:5");
    let refs = c.request(
        "textDocument/references",
        json!({"textDocument": {"uri": u}, "position": pos(l, col), "context": {"includeDeclaration": true}}),
    );
    let refs: Vec<String> = refs
        .as_array()
        .unwrap()
        .iter()
        .map(|r| range(&r["range"]))
        .collect();
    insta::assert_snapshot!("lsp_references_model", refs.join("\n"));
    // Hover on the concept and on a keyword.
    let h = c.request("textDocument/hover", at(&u, l, col));
    insta::assert_snapshot!(
        "lsp_hover_concept",
        h["contents"]["value"].as_str().unwrap()
    );
    let (l, col) = find(&text, "DEFI_CONTACT(", "FORMULATION");
    let h = c.request("textDocument/hover", at(&u, l, col + 3));
    assert_eq!(range(&h["range"]), format!("{l}:{col}-{l}:{}", col + 11));
    insta::assert_snapshot!(
        "lsp_hover_keyword",
        h["contents"]["value"].as_str().unwrap()
    );
    stop(c);
}

#[test]
fn a_broken_file_its_fixes_and_edits() {
    let mut c = start();
    let (u, text) = open(&mut c, &data("broken.comm"));
    let d = c.diagnostics(&u);
    insta::assert_snapshot!("lsp_broken_diagnostics", show_diagnostics(&d));

    // Quick fixes: the did-you-mean of the value after a non-BMP string on
    // the same line (UTF-16 columns), the unknown keyword, the legacy one.
    let mut actions = Vec::new();
    for (after, needle) in [
        ("label", "MECANIQE"),
        ("ZONE=", "GROUP_MA_ESC="),
        ("DDL_IMPO", "MAILLE"),
        ("IMPR_RESU", "NOM_CHAM"),
    ] {
        let (l, col) = find(&text, after, needle);
        let a = c.request(
            "textDocument/codeAction",
            json!({"textDocument": {"uri": u}, "range": {"start": pos(l, col), "end": pos(l, col)},
                   "context": {"diagnostics": []}}),
        );
        for a in a.as_array().unwrap() {
            let edits = &a["edit"]["changes"][&u];
            for e in edits.as_array().unwrap() {
                actions.push(format!(
                    "{}: {} -> {}",
                    a["title"].as_str().unwrap(),
                    range(&e["range"]),
                    e["newText"].as_str().unwrap()
                ));
            }
        }
    }
    insta::assert_snapshot!("lsp_broken_code_actions", actions.join("\n"));

    // Apply the first fix as an incremental change: its diagnostic goes.
    let (l, col) = find(&text, "label", "MECANIQE");
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": u, "version": 2},
               "contentChanges": [{"range": {"start": pos(l, col), "end": pos(l, col + 8)}, "text": "MECANIQUE"}]}),
    );
    let after = c.diagnostics(&u);
    assert_eq!(after.len() + 1, d.len(), "{}", show_diagnostics(&after));
    assert!(!show_diagnostics(&after).contains("MECANIQE"));

    // Completion of the keywords of DEFI_CONTACT/ZONE after FORMULATION
    // 'DISCRETE', without those written.
    let (l, col) = find(&text, "ZONE=_F(", "GROUP_MA_MAIT");
    let comp = c.request("textDocument/completion", at(&u, l, col));
    let kws = labels(&comp);
    assert!(
        kws.iter().any(|k| k.starts_with("GROUP_MA_ESCL ")),
        "{kws:?}"
    );
    assert!(
        !kws.iter().any(|k| k.starts_with("GROUP_MA_MAIT ")),
        "{kws:?}"
    );
    insta::assert_snapshot!("lsp_completion_zone_discrete", kws.join("\n"));
    stop(c);
}

#[test]
fn completion_while_typing() {
    let mut c = start();
    let dir = std::env::temp_dir().join(format!("aster-lsp-typing-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(data("broken.mail"), dir.join("typing.mail")).unwrap();
    let head = "DEBUT()\nmesh = LIRE_MAILLAGE(FORMAT='ASTER')\nsoft = DEFI_MATERIAU(ELAS=_F(E=1.0, NU=0.3))\n";
    let path = dir.join("typing.comm");
    std::fs::write(&path, head).unwrap();
    let (u, _) = open(&mut c, &path);
    c.diagnostics(&u);
    let mut text = head.to_string();
    let mut version = 1;
    // Types at the end of the file, as an editor sends keystrokes.
    let mut typed = |c: &mut Client, s: &str| -> (u64, u64) {
        let line = text.matches('\n').count() as u64;
        let col = text[text.rfind('\n').map(|i| i + 1).unwrap_or(0)..]
            .encode_utf16()
            .count() as u64;
        version += 1;
        c.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": u, "version": version},
                   "contentChanges": [{"range": {"start": pos(line, col), "end": pos(line, col)}, "text": s}]}),
        );
        text.push_str(s);
        c.diagnostics(&u);
        let line = text.matches('\n').count() as u64;
        let col = text[text.rfind('\n').map(|i| i + 1).unwrap_or(0)..]
            .encode_utf16()
            .count() as u64;
        (line, col)
    };
    let mut out = Vec::new();
    let (l, col) = typed(&mut c, "mo = AFFE_MO");
    out.push((
        "commands `AFFE_MO`",
        c.request("textDocument/completion", at(&u, l, col)),
    ));
    let (l, col) = typed(&mut c, "DELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA='");
    out.push((
        "cell groups of the mesh",
        c.request("textDocument/completion", at(&u, l, col)),
    ));
    let (l, col) = typed(&mut c, "ABCD', PHENOMENE='");
    out.push((
        "values of PHENOMENE",
        c.request("textDocument/completion", at(&u, l, col)),
    ));
    let (l, col) = typed(&mut c, "MECANIQUE', ");
    out.push((
        "keywords of AFFE after PHENOMENE",
        c.request("textDocument/completion", at(&u, l, col)),
    ));
    let sig = c.request("textDocument/signatureHelp", at(&u, l, col));
    let (l, col) = typed(
        &mut c,
        "MODELISATION='D_PLAN'))\nmat = AFFE_MATERIAU(MAILLAGE=mesh, AFFE=_F(TOUT='OUI', MATER=",
    );
    out.push((
        "concepts of type mater_sdaster",
        c.request("textDocument/completion", at(&u, l, col)),
    ));
    let shown: Vec<String> = out
        .iter()
        .map(|(what, comp)| format!("== {what}\n{}", labels(comp).join("\n")))
        .collect();
    insta::assert_snapshot!("lsp_completion_typing", shown.join("\n"));
    let s = &sig["signatures"][0];
    let active = sig["activeParameter"].clone();
    insta::assert_snapshot!(
        "lsp_signature_affe",
        format!("{}\nactive: {active}", s["label"].as_str().unwrap())
    );
    stop(c);
    let _ = std::fs::remove_dir_all(&dir);
}
