//! The server loop: one thread, no async runtime. Messages are read from
//! the connection; edits mark a document dirty and it is re-checked once no
//! edit has come for the debounce delay (a burst of keystrokes is checked
//! once), then its diagnostics are published. A request on a dirty document
//! checks it first, so every answer reflects the current text.

use crate::analysis::{self, Analysis};
use crate::features;
use crate::text::Document;
use crossbeam_channel::RecvTimeoutError;
use lsp_server::{Connection, ErrorCode, Message, Notification, Request, Response};
use lsp_types::notification::Notification as _;
use lsp_types::request::Request as _;
use lsp_types::*;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime};

type Error = Box<dyn std::error::Error + Send + Sync>;

/// The default delay between the last edit and the check.
pub const DEFAULT_DEBOUNCE: Duration = Duration::from_millis(150);

struct DocState {
    doc: Document,
    analysis: Analysis,
    /// When set, the text changed since the analysis: check at this time.
    due: Option<Instant>,
}

/// The group names of one mesh file, as read at a modification time.
struct MeshGroups {
    modified: Option<SystemTime>,
    cells: Vec<String>,
    nodes: Vec<String>,
}

pub struct Server {
    conn: Connection,
    docs: HashMap<Uri, DocState>,
    debounce: Duration,
    meshes: HashMap<PathBuf, MeshGroups>,
}

/// What the server offers.
pub fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Options(
            TextDocumentSyncOptions {
                open_close: Some(true),
                change: Some(TextDocumentSyncKind::INCREMENTAL),
                ..TextDocumentSyncOptions::default()
            },
        )),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(
                ["(", ",", "=", "'", "\""]
                    .iter()
                    .map(|s| s.to_string())
                    .collect(),
            ),
            ..CompletionOptions::default()
        }),
        signature_help_provider: Some(SignatureHelpOptions {
            trigger_characters: Some(vec!["(".into(), ",".into()]),
            retrigger_characters: Some(vec!["=".into()]),
            ..SignatureHelpOptions::default()
        }),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        code_action_provider: Some(CodeActionProviderCapability::Options(CodeActionOptions {
            code_action_kinds: Some(vec![CodeActionKind::QUICKFIX]),
            ..CodeActionOptions::default()
        })),
        ..ServerCapabilities::default()
    }
}

/// Runs the server on stdin/stdout until the client says `exit`.
pub fn run_stdio() -> Result<(), Error> {
    let (conn, io) = Connection::stdio();
    serve(conn)?;
    io.join()?;
    Ok(())
}

/// Runs the server on a connection: the `initialize` handshake, then the
/// loop until `shutdown` and `exit`.
pub fn serve(conn: Connection) -> Result<(), Error> {
    let (id, params) = conn.initialize_start()?;
    let params: InitializeParams = serde_json::from_value(params)?;
    let debounce = params
        .initialization_options
        .as_ref()
        .and_then(|o| o.get("debounceMs"))
        .and_then(|v| v.as_u64())
        .map(Duration::from_millis)
        .unwrap_or(DEFAULT_DEBOUNCE);
    let result = InitializeResult {
        capabilities: capabilities(),
        server_info: Some(ServerInfo {
            name: "aster".into(),
            version: Some(env!("CARGO_PKG_VERSION").into()),
        }),
    };
    conn.initialize_finish(id, serde_json::to_value(result)?)?;
    let mut server = Server {
        conn,
        docs: HashMap::new(),
        debounce,
        meshes: HashMap::new(),
    };
    server.main_loop()
}

impl Server {
    fn main_loop(&mut self) -> Result<(), Error> {
        loop {
            let due = self.docs.values().filter_map(|d| d.due).min();
            let msg = match due {
                Some(t) => match self
                    .conn
                    .receiver
                    .recv_timeout(t.saturating_duration_since(Instant::now()))
                {
                    Ok(m) => Some(m),
                    Err(RecvTimeoutError::Timeout) => None,
                    Err(RecvTimeoutError::Disconnected) => return Ok(()),
                },
                None => match self.conn.receiver.recv() {
                    Ok(m) => Some(m),
                    Err(_) => return Ok(()),
                },
            };
            match msg {
                Some(Message::Request(req)) => {
                    if self.conn.handle_shutdown(&req)? {
                        return Ok(());
                    }
                    let resp = self.request(req);
                    self.conn.sender.send(Message::Response(resp))?;
                }
                Some(Message::Notification(n)) => {
                    if n.method == notification::Exit::METHOD {
                        return Ok(());
                    }
                    self.notification(n)?;
                }
                Some(Message::Response(_)) => {}
                None => {}
            }
            let now = Instant::now();
            let ready: Vec<Uri> = self
                .docs
                .iter()
                .filter(|(_, d)| d.due.is_some_and(|t| t <= now))
                .map(|(u, _)| u.clone())
                .collect();
            for uri in ready {
                self.refresh(&uri)?;
            }
        }
    }

    /// Checks a dirty document now and publishes its diagnostics.
    fn refresh(&mut self, uri: &Uri) -> Result<(), Error> {
        let Some(state) = self.docs.get_mut(uri) else {
            return Ok(());
        };
        if state.due.take().is_none() {
            return Ok(());
        }
        let mut fresh = analysis::analyse(&file_name(uri), &state.doc.text);
        if fresh.findings.iter().any(|f| f.code == "syntax") {
            // A file being typed does not parse: the concepts and meshes of
            // its last parsed version still serve completion and hover.
            fresh.concepts = std::mem::take(&mut state.analysis.concepts);
            fresh.meshes = std::mem::take(&mut state.analysis.meshes);
        }
        state.analysis = fresh;
        let params = PublishDiagnosticsParams {
            uri: uri.clone(),
            diagnostics: features::diagnostics(&state.doc, uri, &state.analysis),
            version: Some(state.doc.version),
        };
        self.conn
            .sender
            .send(Message::Notification(Notification::new(
                notification::PublishDiagnostics::METHOD.into(),
                params,
            )))?;
        Ok(())
    }

    fn notification(&mut self, n: Notification) -> Result<(), Error> {
        match n.method.as_str() {
            notification::DidOpenTextDocument::METHOD => {
                let p: DidOpenTextDocumentParams = serde_json::from_value(n.params)?;
                let doc = Document::new(p.text_document.text, p.text_document.version);
                self.docs.insert(
                    p.text_document.uri,
                    DocState {
                        doc,
                        analysis: Analysis::default(),
                        due: Some(Instant::now()),
                    },
                );
            }
            notification::DidChangeTextDocument::METHOD => {
                let p: DidChangeTextDocumentParams = serde_json::from_value(n.params)?;
                if let Some(s) = self.docs.get_mut(&p.text_document.uri) {
                    s.doc.apply(p.content_changes, p.text_document.version);
                    s.due = Some(Instant::now() + self.debounce);
                }
            }
            notification::DidCloseTextDocument::METHOD => {
                let p: DidCloseTextDocumentParams = serde_json::from_value(n.params)?;
                if self.docs.remove(&p.text_document.uri).is_some() {
                    // Clear what the editor shows for it.
                    self.conn
                        .sender
                        .send(Message::Notification(Notification::new(
                            notification::PublishDiagnostics::METHOD.into(),
                            PublishDiagnosticsParams {
                                uri: p.text_document.uri,
                                diagnostics: Vec::new(),
                                version: None,
                            },
                        )))?;
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// The document of a request, checked if dirty.
    fn current(&mut self, uri: &Uri) -> Result<Option<&DocState>, Error> {
        self.refresh(uri)?;
        Ok(self.docs.get(uri))
    }

    fn request(&mut self, req: Request) -> Response {
        let id = req.id.clone();
        match self.dispatch(req) {
            Ok(Some(v)) => Response {
                id,
                result: Some(v),
                error: None,
            },
            Ok(None) => Response::new_err(
                id,
                ErrorCode::MethodNotFound as i32,
                "method not supported by aster lsp".into(),
            ),
            Err(e) => Response::new_err(id, ErrorCode::InvalidParams as i32, e.to_string()),
        }
    }

    fn dispatch(&mut self, req: Request) -> Result<Option<serde_json::Value>, Error> {
        fn json<T: serde::Serialize>(v: T) -> Result<Option<serde_json::Value>, Error> {
            Ok(Some(serde_json::to_value(v)?))
        }
        let Request { method, params, .. } = req;
        match method.as_str() {
            request::HoverRequest::METHOD => {
                let p: HoverParams = serde_json::from_value(params)?;
                let td = p.text_document_position_params;
                let Some(s) = self.current(&td.text_document.uri)? else {
                    return json(None::<Hover>);
                };
                json(features::hover(&s.doc, &s.analysis, td.position))
            }
            request::Completion::METHOD => {
                let p: CompletionParams = serde_json::from_value(params)?;
                let td = p.text_document_position;
                let uri = td.text_document.uri;
                self.refresh(&uri)?;
                let Some(s) = self.docs.get(&uri) else {
                    return json(None::<CompletionResponse>);
                };
                let meshes = &mut self.meshes;
                let cell = std::cell::RefCell::new(meshes);
                let groups = || group_names(&mut cell.borrow_mut(), &uri, &s.analysis);
                let items = features::completion(&s.doc, &s.analysis, td.position, &groups);
                json(CompletionResponse::List(CompletionList {
                    is_incomplete: false,
                    items,
                }))
            }
            request::SignatureHelpRequest::METHOD => {
                let p: SignatureHelpParams = serde_json::from_value(params)?;
                let td = p.text_document_position_params;
                let Some(s) = self.current(&td.text_document.uri)? else {
                    return json(None::<SignatureHelp>);
                };
                json(features::signature_help(&s.doc, &s.analysis, td.position))
            }
            request::GotoDefinition::METHOD => {
                let p: GotoDefinitionParams = serde_json::from_value(params)?;
                let td = p.text_document_position_params;
                let uri = td.text_document.uri;
                let Some(s) = self.current(&uri)? else {
                    return json(None::<Location>);
                };
                json(features::definition(&s.doc, &s.analysis, &uri, td.position))
            }
            request::References::METHOD => {
                let p: ReferenceParams = serde_json::from_value(params)?;
                let td = p.text_document_position;
                let uri = td.text_document.uri;
                let Some(s) = self.current(&uri)? else {
                    return json(Vec::<Location>::new());
                };
                json(features::references(
                    &s.doc,
                    &s.analysis,
                    &uri,
                    td.position,
                    p.context.include_declaration,
                ))
            }
            request::DocumentSymbolRequest::METHOD => {
                let p: DocumentSymbolParams = serde_json::from_value(params)?;
                let Some(s) = self.current(&p.text_document.uri)? else {
                    return json(None::<DocumentSymbolResponse>);
                };
                json(DocumentSymbolResponse::Nested(features::symbols(
                    &s.doc,
                    &s.analysis,
                )))
            }
            request::CodeActionRequest::METHOD => {
                let p: CodeActionParams = serde_json::from_value(params)?;
                let uri = p.text_document.uri;
                let Some(s) = self.current(&uri)? else {
                    return json(Vec::<CodeAction>::new());
                };
                json(features::code_actions(&s.doc, &uri, &s.analysis, p.range))
            }
            _ => Ok(None),
        }
    }
}

/// The file path of a `file:` URI (percent-decoded), else the URI itself.
pub fn uri_path(uri: &Uri) -> Option<PathBuf> {
    let s = uri.as_str().strip_prefix("file://")?;
    let mut bytes = Vec::with_capacity(s.len());
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' && i + 2 < b.len() {
            if let Ok(v) = u8::from_str_radix(&s[i + 1..i + 3], 16) {
                bytes.push(v);
                i += 3;
                continue;
            }
        }
        bytes.push(b[i]);
        i += 1;
    }
    let path = String::from_utf8(bytes).ok()?;
    // `file:///C:/x` on Windows.
    let path = match path.as_bytes() {
        [b'/', d, b':', ..] if d.is_ascii_alphabetic() => path[1..].to_string(),
        _ => path,
    };
    Some(PathBuf::from(path))
}

/// How diagnostics name the file.
fn file_name(uri: &Uri) -> String {
    uri_path(uri)
        .map(|p| p.display().to_string())
        .unwrap_or_else(|| uri.as_str().to_string())
}

/// The logical units of a command file, as `aster run` resolves them: an
/// `.export` beside it that names it as a command file, else
/// `<stem>.mmed|.med|.mail` for unit 20.
pub fn units_of(comm: &Path) -> BTreeMap<u32, PathBuf> {
    let dir = comm.parent().unwrap_or(Path::new("."));
    let me = std::fs::canonicalize(comm).ok();
    if let Ok(entries) = std::fs::read_dir(dir) {
        let mut exports: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "export"))
            .collect();
        exports.sort();
        for e in exports {
            let Ok(export) = aster_run::export::Export::read(&e) else {
                continue;
            };
            let names_me = export
                .comm_files()
                .iter()
                .any(|c| me.is_some() && std::fs::canonicalize(c).ok() == me);
            if names_me {
                return export.data_units();
            }
        }
    }
    let mut units = BTreeMap::new();
    if let Some(m) = ["mmed", "med", "mail"]
        .iter()
        .map(|ext| comm.with_extension(ext))
        .find(|p| p.exists())
    {
        units.insert(20, m);
    }
    units
}

/// The cell and node group names of the meshes the program reads, when
/// their units resolve to files (read once per file and modification).
fn group_names(
    cache: &mut HashMap<PathBuf, MeshGroups>,
    uri: &Uri,
    a: &Analysis,
) -> (Vec<String>, Vec<String>) {
    let (mut cells, mut nodes) = (Vec::new(), Vec::new());
    let Some(comm) = uri_path(uri) else {
        return (cells, nodes);
    };
    let units = units_of(&comm);
    for m in &a.meshes {
        let Some(path) = u32::try_from(m.unit).ok().and_then(|u| units.get(&u)) else {
            continue;
        };
        let modified = std::fs::metadata(path).and_then(|m| m.modified()).ok();
        let fresh = cache.get(path).is_some_and(|g| g.modified == modified);
        if !fresh {
            let Ok(mesh) = aster_mesh::read_mesh(path) else {
                continue;
            };
            cache.insert(
                path.clone(),
                MeshGroups {
                    modified,
                    cells: mesh.groups_ma.iter().map(|g| g.name.clone()).collect(),
                    nodes: mesh.groups_no.iter().map(|g| g.name.clone()).collect(),
                },
            );
        }
        if let Some(g) = cache.get(path) {
            cells.extend(
                g.cells
                    .iter()
                    .filter(|c| !cells.contains(c))
                    .cloned()
                    .collect::<Vec<_>>(),
            );
            nodes.extend(
                g.nodes
                    .iter()
                    .filter(|c| !nodes.contains(c))
                    .cloned()
                    .collect::<Vec<_>>(),
            );
        }
    }
    (cells, nodes)
}
