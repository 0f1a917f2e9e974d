//! The executing [`CommandSink`]: keeps the concept store and dispatches
//! each command to its implementation.

use crate::concept::*;
use crate::field::Field;
use crate::function::Function;
use crate::table::Table;
use crate::test_resu::Tally;
use aster_eval::{CommandCall, CommandOutput, CommandSink, ConceptRef, ExecError, Keywords};
use aster_mesh::Mesh;
use aster_syntax::{CodeMap, Span};
use std::collections::{BTreeMap, HashMap};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Arc;

/// Where the run reads and writes files.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Logical units read by the program (20 → the mesh…).
    pub units: BTreeMap<u32, PathBuf>,
    /// Files named for result units by the `.export` (`R` lines).
    pub result_units: BTreeMap<u32, PathBuf>,
    /// Directory for the files the program writes.
    pub out_dir: PathBuf,
}

/// Executes validated commands.
pub struct Executor {
    store: HashMap<u32, Concept>,
    /// The name each stored concept was given (`LIEU` of POST_ELEM tables…).
    names: HashMap<u32, String>,
    /// Objects tables refer to by name (`NOM_SD` of CALCUL's table).
    pub(crate) objects: HashMap<String, Concept>,
    /// Fields extracted from a result step (`CREA_CHAMP(OPERATION='EXTR')`),
    /// by concept id: the result and the NUME_ORDRE they come from.
    pub(crate) field_origin: HashMap<u32, (Rc<EvolResult>, u32)>,
    /// The mesh (id) a field made by CREA_CHAMP lives on, when the command
    /// tells it (MAILLAGE, MODELE, or the fields it was made from).
    pub(crate) field_meshes: HashMap<u32, u32>,
    /// The quantity of a field made by CREA_CHAMP (its `TYPE_CHAM` without
    /// the location: `DEPL_R`, `NEUT_R`…), by concept id.
    pub(crate) field_quantity: HashMap<u32, String>,
    pub(crate) options: RunOptions,
    out: Box<dyn Write>,
    pub tally: Tally,
    codemap: Option<Rc<CodeMap>>,
    /// Set by `FIN`.
    pub finished: bool,
    /// LAC patches recorded by `CREA_MAILLAGE/DECOUPE_LAC`, with the mesh
    /// they belong to (the Arc is kept so the pointer stays unique).
    pub(crate) lac_patches: Vec<(Arc<Mesh>, Arc<aster_mesh::LacPatches>)>,
    /// Meshes assembled with super cells (`ASSE_MAILLAGE(OPERATION=
    /// 'SOUS_STR')`), by concept id.
    pub(crate) substructured: HashMap<u32, Rc<crate::concept::SuperMesh>>,
    /// Meshes the static pass already read (`LIRE_MAILLAGE` takes them).
    pub(crate) read_meshes: Vec<crate::preflight::ReadMesh>,
    /// Text files this run has written on a unit: the first write of a run
    /// truncates what an earlier run left there (code_aster starts each run
    /// with fresh `fort.<UNITE>` files), later ones append.
    written_units: std::collections::HashSet<PathBuf>,
    /// MED files this run wrote (`IMPR_RESU(FORMAT='MED')`), by unit: a
    /// later command that reads a mesh from that unit reads them
    /// (`MACR_CARA_POUTRE(UNITE=…)`).
    pub(crate) med_written: HashMap<u32, PathBuf>,
    /// Each command and each TEST_* comparison as they ran (reports).
    pub journal: crate::journal::Journal,
    /// Where live progress goes (nowhere unless set).
    pub progress: crate::progress::Progress,
    /// The command running now (named in the journal's checks).
    current: String,
}

impl Executor {
    /// An executor writing its report (TEST_RESU lines, tables) to `out`.
    pub fn new(options: RunOptions, out: Box<dyn Write>) -> Executor {
        Executor {
            store: HashMap::new(),
            names: HashMap::new(),
            objects: HashMap::new(),
            field_origin: HashMap::new(),
            field_meshes: HashMap::new(),
            field_quantity: HashMap::new(),
            options,
            out,
            tally: Tally::default(),
            codemap: None,
            finished: false,
            lac_patches: Vec::new(),
            substructured: HashMap::new(),
            read_meshes: Vec::new(),
            written_units: Default::default(),
            med_written: Default::default(),
            journal: Default::default(),
            progress: Default::default(),
            current: String::new(),
        }
    }

    /// Appends `text` to the file of logical unit `unit`, emptied first if
    /// this run has not written it yet.
    pub(crate) fn append_unit(&mut self, unit: i64, text: &str) -> Result<(), ExecError> {
        let path = self.output_path(unit);
        if self.written_units.insert(path.clone()) && path.exists() {
            std::fs::write(&path, b"")
                .map_err(|e| ExecError::new(format!("cannot write {}: {e}", path.display())))?;
        }
        crate::commands::append_file(&path, text)
    }

    /// Lets messages give `file:line:col` of keywords.
    pub fn set_codemap(&mut self, codemap: Rc<CodeMap>) {
        self.codemap = Some(codemap);
    }

    pub(crate) fn write_report(&mut self, text: &str) -> Result<(), ExecError> {
        self.out
            .write_all(text.as_bytes())
            .and_then(|_| self.out.flush())
            .map_err(|e| ExecError::new(format!("cannot write the report: {e}")))
    }

    /// Writes out what the report still holds (a last line without its
    /// newline); errors are the report's own, as at its drop.
    pub(crate) fn flush_report(&mut self) {
        let _ = self.out.flush();
    }

    /// `file:line:col` of a span, when the source is known.
    pub(crate) fn location(&self, span: Span) -> Option<String> {
        self.codemap.as_ref().map(|cm| cm.location(span))
    }

    /// File, line and column of a span, when the source is known.
    pub(crate) fn position(&self, span: Span) -> crate::journal::Position {
        match &self.codemap {
            Some(cm) => {
                let lc = cm.line_col(span.start as usize);
                crate::journal::Position {
                    file: cm.file_name(lc.file).to_string(),
                    line: lc.line,
                    column: lc.column,
                }
            }
            None => Default::default(),
        }
    }

    /// The command running now.
    pub(crate) fn current_command(&self) -> &str {
        &self.current
    }

    /// "not supported yet: CMD/KEYWORD (file:line:col)".
    pub(crate) fn unsupported(&self, what: &str, span: Span) -> ExecError {
        match self.location(span) {
            Some(loc) => ExecError::new(format!("not supported yet: {what} ({loc})")),
            None => ExecError::new(format!("not supported yet: {what}")),
        }
    }

    /// An error about one keyword, located at it.
    pub(crate) fn kw_error(
        &self,
        cmd: &str,
        kw: &Keywords,
        name: &str,
        msg: impl AsRef<str>,
    ) -> ExecError {
        let span = kw.keyword(name).map(|k| k.span).unwrap_or_default();
        let loc = self
            .location(span)
            .filter(|_| kw.keyword(name).is_some())
            .map(|l| format!(" ({l})"))
            .unwrap_or_default();
        ExecError::new(format!("{cmd}/{name}: {}{loc}", msg.as_ref()))
    }

    pub(crate) fn insert(&mut self, c: &ConceptRef, concept: Concept) {
        self.store.insert(c.id, concept);
        self.names.insert(c.id, c.name.clone());
    }

    /// Forgets a concept (a macro's temporaries).
    pub(crate) fn remove(&mut self, id: u32) {
        self.store.remove(&id);
        self.names.remove(&id);
    }

    /// Every result the program holds now, by creation order, with its name.
    pub(crate) fn results(&self) -> Vec<(u32, &str, Rc<EvolResult>)> {
        let mut out: Vec<(u32, &str, Rc<EvolResult>)> = self
            .store
            .iter()
            .filter_map(|(id, c)| match c {
                Concept::Result(r) => {
                    Some((*id, self.concept_name(*id).unwrap_or("RESU"), r.clone()))
                }
                _ => None,
            })
            .collect();
        out.sort_by_key(|r| r.0);
        out
    }

    /// The name a concept was given (`None` for one made without a name).
    pub(crate) fn concept_name(&self, id: u32) -> Option<&str> {
        self.names.get(&id).map(String::as_str)
    }

    /// code_aster's own name of a concept (its JEVEUX name): since
    /// version 15 every data structure is named by a counter of the
    /// concepts created, on 8 digits ("00000001" the first) — what
    /// `POST_ELEM` writes in `LIEU` for `TOUT='OUI'` (the mesh's name).
    /// Concept ids count the new concepts of the commands in program order
    /// the same way (a `reuse` makes none); the concepts code_aster's
    /// macros create for themselves are not counted.
    pub(crate) fn internal_name(&self, id: u32) -> String {
        format!("{id:08}")
    }

    pub fn concept(&self, c: &ConceptRef) -> Result<&Concept, ExecError> {
        self.store.get(&c.id).ok_or_else(|| {
            ExecError::new(format!(
                "concept `{}` ({}) was not produced by an executed command",
                c.name, c.typ
            ))
        })
    }

    fn wrong(&self, c: &ConceptRef, got: &Concept, want: &str) -> ExecError {
        ExecError::new(format!("`{}` is {}, expected {want}", c.name, got.kind()))
    }

    /// The LAC patches of a mesh made by `CREA_MAILLAGE/DECOUPE_LAC` — the
    /// mesh itself or a copy with the same nodes and cells (DEFI_GROUP
    /// with `reuse` only adds groups).
    pub(crate) fn lac_patches_of(&self, mesh: &Mesh) -> Option<Arc<aster_mesh::LacPatches>> {
        self.lac_patches
            .iter()
            .rev()
            .find(|(m, _)| {
                std::ptr::eq(Arc::as_ptr(m), mesh)
                    || (m.coords == mesh.coords && m.cells == mesh.cells)
            })
            .map(|(_, p)| p.clone())
    }

    pub(crate) fn mesh_by_id(&self, id: u32) -> Result<Arc<Mesh>, ExecError> {
        match self.store.get(&id) {
            Some(Concept::Mesh(m)) => Ok(m.clone()),
            _ => Err(ExecError::new(
                "the mesh of this concept is no longer available",
            )),
        }
    }

    /// The mesh a model is solved on. code_aster takes the problem's
    /// dimension from the model's elements (`DIM_GEOM`), so a plane model
    /// on a mesh written with three coordinates (`COOR_3D`, as `PRE_GMSH`
    /// writes every mesh) works in the (x, y) plane; seeing such meshes in
    /// the plane here gave wrong contact results (ssnp167a–c, ssnp152g), so
    /// the mesh is kept as written (and such a contact is refused by the
    /// contact bridge) until that is understood.
    pub(crate) fn model_mesh(&self, model: &ModelDef) -> Result<Arc<Mesh>, ExecError> {
        self.mesh_by_id(model.mesh)
    }

    /// The concept behind a keyword, typed.
    pub(crate) fn required<'k>(
        &self,
        cmd: &str,
        kw: &'k Keywords,
        name: &str,
    ) -> Result<&'k ConceptRef, ExecError> {
        kw.concept(name)
            .ok_or_else(|| self.kw_error(cmd, kw, name, "a concept is required here"))
    }
}

macro_rules! getter {
    ($fn:ident, $variant:ident, $ty:ty, $want:expr) => {
        impl Executor {
            pub(crate) fn $fn(&self, c: &ConceptRef) -> Result<Rc<$ty>, ExecError> {
                match self.concept(c)? {
                    Concept::$variant(x) => Ok(x.clone()),
                    other => Err(self.wrong(c, other, $want)),
                }
            }
        }
    };
}

getter!(model, Model, ModelDef, "a model (AFFE_MODELE)");
getter!(
    thermal_model,
    ThermalModel,
    crate::commands::thermal::ThermalModel,
    "a thermal model (AFFE_MODELE with PHENOMENE='THERMIQUE')"
);
getter!(
    thermal_load,
    ThermalLoad,
    crate::commands::thermal::ThermalLoad,
    "a thermal load (AFFE_CHAR_THER, AFFE_CHAR_THER_F)"
);
getter!(
    macro_element,
    MacroElement,
    MacroElement,
    "a static macro element (MACR_ELEM_STAT)"
);
getter!(
    super_mesh,
    SuperMesh,
    SuperMesh,
    "a super mesh (DEFI_MAILLAGE)"
);
getter!(material, Material, Material, "a material (DEFI_MATERIAU)");
getter!(
    material_field,
    MaterialField,
    MaterialField,
    "a material field (AFFE_MATERIAU)"
);
getter!(
    cara_elem,
    CaraElem,
    CaraElem,
    "element characteristics (AFFE_CARA_ELEM)"
);
getter!(function, Function, Function, "a function");
getter!(result, Result, EvolResult, "a result");
getter!(table, Table, Table, "a table");
getter!(field, Field, Field, "a field");
getter!(
    contact,
    Contact,
    ContactDef,
    "a contact definition (DEFI_CONTACT)"
);

getter!(
    crack_front,
    CrackFront,
    crate::commands::fracture::CrackFront,
    "a crack front (DEFI_FOND_FISS)"
);

impl Executor {
    pub(crate) fn mesh(&self, c: &ConceptRef) -> Result<Arc<Mesh>, ExecError> {
        match self.concept(c)? {
            Concept::Mesh(x) => Ok(x.clone()),
            other => Err(self.wrong(c, other, "a mesh")),
        }
    }

    pub(crate) fn real_list(&self, c: &ConceptRef) -> Result<Rc<Vec<f64>>, ExecError> {
        match self.concept(c)? {
            Concept::RealList(l) => Ok(l.clone()),
            Concept::TimeList(l) => Ok(l.instants.clone()),
            other => Err(self.wrong(
                c,
                other,
                "a list of instants (DEFI_LIST_REEL/DEFI_LIST_INST)",
            )),
        }
    }

    /// The mesh a field concept lives on: that of the result it was
    /// extracted from (`CREA_CHAMP(OPERATION='EXTR')`), else the program's
    /// only mesh. Programs with `CREA_MAILLAGE` (DECOUPE_LAC…) have several.
    pub(crate) fn field_mesh(&self, field: &ConceptRef) -> Result<Arc<Mesh>, ExecError> {
        self.mesh_by_id(self.field_mesh_id(field)?)
    }

    /// The id of the mesh concept a field lives on ([`Executor::field_mesh`]).
    pub(crate) fn field_mesh_id(&self, field: &ConceptRef) -> Result<u32, ExecError> {
        match (
            self.field_origin.get(&field.id),
            self.field_meshes.get(&field.id),
        ) {
            (Some((result, _)), _) => Ok(result.mesh),
            (None, Some(&m)) => Ok(m),
            (None, None) => self.single_mesh_id(),
        }
    }

    /// The failure handling of a list of instants: a DEFI_LIST_INST's
    /// `ECHEC` with where it was defined, code_aster's default (DECOUPE,
    /// SUBD_PAS=4, SUBD_NIVEAU=3) for a plain list of reals.
    pub(crate) fn time_stepping(
        &self,
        c: &ConceptRef,
    ) -> Result<(Option<aster_fem::Subdivision>, Option<String>), ExecError> {
        Ok(match self.concept(c)? {
            Concept::TimeList(l) => (l.subdivision, l.location.clone()),
            _ => (Some(aster_fem::Subdivision::default()), None),
        })
    }

    /// A DEFI_LIST_INST's `ECHEC/EVENEMENT='INTERPENETRATION'` (with
    /// `ACTION='ADAPT_COEF_PENA'`), if any.
    pub(crate) fn penalty_adaptation(
        &self,
        c: &ConceptRef,
    ) -> Result<Option<aster_fem::PenaltyAdaptation>, ExecError> {
        Ok(match self.concept(c)? {
            Concept::TimeList(l) => l.penalty_adaptation,
            _ => None,
        })
    }

    /// The program's mesh when there is exactly one (fields do not record
    /// their mesh).
    pub(crate) fn single_mesh(&self) -> Result<Arc<Mesh>, ExecError> {
        self.mesh_by_id(self.single_mesh_id()?)
    }

    /// The id of the program's only mesh.
    pub(crate) fn single_mesh_id(&self) -> Result<u32, ExecError> {
        let meshes: Vec<u32> = self
            .store
            .iter()
            .filter_map(|(id, c)| matches!(c, Concept::Mesh(_)).then_some(*id))
            .collect();
        match meshes.as_slice() {
            [m] => Ok(*m),
            [] => Err(ExecError::new("no mesh has been read")),
            _ => Err(ExecError::new(
                "several meshes exist: this command cannot tell which one a field lives on",
            )),
        }
    }

    /// Path of a file the program writes on a logical unit.
    pub(crate) fn output_path(&self, unit: i64) -> PathBuf {
        let name = self
            .options
            .result_units
            .get(&(unit as u32))
            .and_then(|p| p.file_name())
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(format!("fort.{unit}")));
        self.options.out_dir.join(name)
    }

    pub(crate) fn input_path(&self, unit: u32) -> Option<&Path> {
        self.options.units.get(&unit).map(PathBuf::as_path)
    }
}

impl CommandSink for Executor {
    fn execute(&mut self, call: &CommandCall) -> Result<CommandOutput, ExecError> {
        if self.finished {
            // The next command file of a study starts again.
            if call.command == "POURSUITE" {
                self.finished = false;
            } else {
                return Ok(CommandOutput::Nothing);
            }
        }
        self.current = call.command.clone();
        let started = std::time::Instant::now();
        let outcome = crate::commands::dispatch(self, call);
        let seconds = started.elapsed().as_secs_f64();
        let at = self.position(call.span);
        let result = call
            .result
            .as_ref()
            .or(call.reuse.as_ref())
            .map(|c| c.name.clone());
        if self.progress.is_on() {
            let loc = format!("{}:{}:{}", at.file, at.line, at.column);
            self.progress.line(&crate::progress::command_line(
                &call.command,
                result.as_deref(),
                seconds,
                &loc,
            ));
        }
        self.journal.commands.push(crate::journal::CommandRecord {
            command: call.command.clone(),
            result,
            at,
            seconds,
            error: outcome.as_ref().err().map(|e| e.message.clone()),
        });
        outcome
    }

    fn formula(&mut self, concept: &ConceptRef, formula: &Rc<aster_eval::Formula>) {
        let f = formula.clone();
        // The function concepts the expression may call (`F(INST)`), as
        // they are now: a formula sees the values of its definition.
        let functions: Vec<(u32, Rc<Function>)> = formula
            .concepts()
            .iter()
            .filter_map(|c| match self.store.get(&c.id) {
                Some(Concept::Function(g)) => Some((c.id, g.clone())),
                _ => None,
            })
            .collect();
        let function = Function::Formula {
            parameters: formula.params.clone(),
            eval: Rc::new(move |args: &[(String, f64)]| {
                let named: Vec<(&str, f64)> = args.iter().map(|(n, v)| (n.as_str(), *v)).collect();
                f.eval_named_in(&named, &mut FunctionCalls(&functions))
            }),
        };
        self.insert(concept, Concept::Function(Rc::new(function)));
    }

    /// Methods of concepts: `TAB.EXTR_TABLE()` (the table's text, as `print`
    /// shows a code_aster `Table`, its `IMPR_TABLE` form),
    /// `mesh.getMinMaxEdgeSizes(group)` (`'TOUT'`: every cell), the mesh's
    /// counts ([`crate::mesh_methods::query`]) and `getName()` of any
    /// concept; the list is [`crate::mesh_methods::METHODS`].
    fn method(
        &mut self,
        concept: &ConceptRef,
        name: &str,
        args: &[aster_eval::HostValue],
    ) -> Result<aster_eval::HostValue, ExecError> {
        use aster_eval::{HostValue, Scalar};
        // The name code_aster stores the object under, which its tables
        // show (POST_ELEM's LIEU of a whole mesh): its internal name.
        if let ("getName", []) = (name, args) {
            return Ok(HostValue::Scalar(Scalar::Str(
                self.internal_name(concept.id),
            )));
        }
        if let ("EXTR_TABLE", []) = (name, args) {
            let table = self.table(concept)?;
            let cell = |v: &Option<crate::table::Value>| match v {
                None => HostValue::None,
                Some(crate::table::Value::Int(i)) => HostValue::Scalar(Scalar::Int(*i)),
                Some(crate::table::Value::Real(r)) => HostValue::Scalar(Scalar::Real(*r)),
                Some(crate::table::Value::Text(t)) => {
                    HostValue::Scalar(Scalar::Str(t.trim().to_string()))
                }
            };
            return Ok(HostValue::Table(Some(aster_eval::HostTable {
                para: table.columns.iter().map(|c| c.name.clone()).collect(),
                rows: table
                    .rows
                    .iter()
                    .map(|r| {
                        (0..table.columns.len())
                            .map(|k| cell(r.get(k).unwrap_or(&None)))
                            .collect()
                    })
                    .collect(),
                text: table.render().trim_end().to_string(),
            })));
        }
        if let ("get_nom_para", []) = (name, args) {
            let table = self.table(concept)?;
            return Ok(HostValue::List(
                table
                    .columns
                    .iter()
                    .map(|c| HostValue::Scalar(Scalar::Str(c.name.clone())))
                    .collect(),
            ));
        }
        match (self.concept(concept)?, name) {
            // A function concept called in a formula (`F(INST)`): its value,
            // the arguments taken in the order of its parameters.
            (Concept::Function(f), "__call__") => call_function(f, &concept.name, args),
            (Concept::Mesh(mesh), "getNumberOfNodes" | "getNumberOfCells" | "getCells") => {
                crate::mesh_methods::query(mesh, name, args).unwrap_or_else(|| {
                    Err(ExecError::new(crate::mesh_methods::refusal(
                        &concept.name,
                        &concept.typ,
                        name,
                    )))
                })
            }
            (Concept::Mesh(mesh), "getMinMaxEdgeSizes") => {
                let cells: Vec<aster_mesh::CellId> = match args {
                    [] => (0..mesh.cells.len() as u32)
                        .map(aster_mesh::CellId)
                        .collect(),
                    [HostValue::Scalar(Scalar::Str(g))] if g == "TOUT" => (0..mesh.cells.len()
                        as u32)
                        .map(aster_mesh::CellId)
                        .collect(),
                    [HostValue::Scalar(Scalar::Str(g))] => crate::select::group_ma(mesh, g)
                        .map_err(|e| ExecError::new(format!("getMinMaxEdgeSizes: {e}")))?
                        .to_vec(),
                    _ => {
                        return Err(ExecError::new(
                            "getMinMaxEdgeSizes takes a group name or 'TOUT'",
                        ))
                    }
                };
                let (lo, hi) = mesh
                    .edge_length_range(&cells)
                    .ok_or_else(|| ExecError::new("getMinMaxEdgeSizes: the cells have no edge"))?;
                Ok(HostValue::List(vec![
                    HostValue::Scalar(Scalar::Real(lo)),
                    HostValue::Scalar(Scalar::Real(hi)),
                ]))
            }
            _ => Err(ExecError::new(crate::mesh_methods::refusal(
                &concept.name,
                &concept.typ,
                name,
            ))),
        }
    }

    /// The mesh methods that make a mesh (`mesh.refine(2)`,
    /// `convertToLinear()`, `convertToQuadratic()`: [`crate::mesh_methods`]).
    fn make(
        &mut self,
        concept: &ConceptRef,
        name: &str,
        args: &[(&'static str, aster_eval::HostValue)],
        result: &ConceptRef,
    ) -> Result<(), ExecError> {
        let mesh = match self.concept(concept)? {
            Concept::Mesh(mesh) => mesh.clone(),
            _ => {
                return Err(ExecError::new(crate::mesh_methods::refusal(
                    &concept.name,
                    &concept.typ,
                    name,
                )))
            }
        };
        let made = crate::mesh_methods::make(&mesh, name, args)?;
        self.insert(result, Concept::Mesh(Arc::new(made)));
        Ok(())
    }

    fn index(
        &mut self,
        concept: &ConceptRef,
        key: &[aster_eval::HostValue],
    ) -> Result<aster_eval::HostValue, ExecError> {
        use aster_eval::{HostValue, Scalar};
        let table = self.table(concept)?;
        // TAB['PARA', row] with a 1-based row, as code_aster's tables.
        let (para, row) = match key {
            [HostValue::Scalar(Scalar::Str(p)), HostValue::Scalar(Scalar::Int(r))] => {
                (p.as_str(), *r)
            }
            _ => {
                return Err(ExecError::new(format!(
                    "table `{}`: subscript must be ['PARAMETER', row]",
                    concept.name
                )))
            }
        };
        let Some(col) = table.column_index(para) else {
            return Err(ExecError::new(format!(
                "table `{}` has no column {para}{}",
                concept.name,
                crate::select::did_you_mean(para, table.columns.iter().map(|c| c.name.as_str()))
            )));
        };
        let cell = usize::try_from(row - 1)
            .ok()
            .and_then(|r| table.rows.get(r))
            .ok_or_else(|| {
                ExecError::new(format!(
                    "table `{}` has {} rows, row {row} asked",
                    concept.name,
                    table.rows.len()
                ))
            })?;
        Ok(match &cell[col] {
            None => HostValue::None,
            Some(crate::table::Value::Int(i)) => HostValue::Scalar(Scalar::Int(*i)),
            Some(crate::table::Value::Real(r)) => HostValue::Scalar(Scalar::Real(*r)),
            Some(crate::table::Value::Text(t)) => HostValue::Scalar(Scalar::Str(t.clone())),
        })
    }

    fn print(&mut self, line: &str) {
        let _ = self.write_report(&format!("{line}\n"));
    }
}

/// Helpers on a command's result.
pub(crate) fn result_of(call: &CommandCall) -> Result<&ConceptRef, ExecError> {
    call.result.as_ref().or(call.reuse.as_ref()).ok_or_else(|| {
        ExecError::new(format!(
            "{} produces a concept: assign it (`X = {}(...)`)",
            call.command, call.command
        ))
    })
}

pub(crate) fn store_result(
    ex: &mut Executor,
    call: &CommandCall,
    concept: Concept,
) -> Result<CommandOutput, ExecError> {
    let r = result_of(call)?.clone();
    ex.insert(&r, concept);
    Ok(CommandOutput::Concept)
}

/// The value of a function concept called with numbers (`F(0.5)`, in the
/// command file or in a formula), the arguments taken in the order of its
/// parameters.
fn call_function(
    f: &Function,
    name: &str,
    args: &[aster_eval::HostValue],
) -> Result<aster_eval::HostValue, ExecError> {
    use aster_eval::{HostValue, Scalar};
    let xs: Vec<f64> = args
        .iter()
        .map(|a| match a {
            HostValue::Scalar(Scalar::Real(x)) => Some(*x),
            HostValue::Scalar(Scalar::Int(i)) => Some(*i as f64),
            _ => None,
        })
        .collect::<Option<_>>()
        .ok_or_else(|| ExecError::new(format!("function {name} takes numbers")))?;
    let params = f.parameters();
    let value = match xs.as_slice() {
        [x] if params.len() <= 1 => f.eval(*x),
        _ if xs.len() == params.len() => {
            let named: Vec<(&str, f64)> = params.iter().copied().zip(xs.iter().copied()).collect();
            f.eval_named(&named)
        }
        _ => {
            return Err(ExecError::new(format!(
                "function {name} takes {} argument(s) ({}), {} given",
                params.len().max(1),
                params.join(", "),
                xs.len()
            )))
        }
    };
    value
        .map(|v| HostValue::Scalar(Scalar::Real(v)))
        .map_err(|e| ExecError::new(format!("function {name}: {e}")))
}

/// What a formula's evaluation may ask of concepts: the calls of the
/// function concepts it refers to; it runs no command.
struct FunctionCalls<'f>(&'f [(u32, Rc<Function>)]);

impl CommandSink for FunctionCalls<'_> {
    fn execute(&mut self, call: &CommandCall) -> Result<CommandOutput, ExecError> {
        Err(ExecError::new(format!(
            "a formula cannot run the command {}",
            call.command
        )))
    }

    fn method(
        &mut self,
        concept: &ConceptRef,
        name: &str,
        args: &[aster_eval::HostValue],
    ) -> Result<aster_eval::HostValue, ExecError> {
        match self.0.iter().find(|(id, _)| *id == concept.id) {
            Some((_, f)) if name == "__call__" => call_function(f, &concept.name, args),
            _ => Err(ExecError::new(format!(
                "not supported: method {name}() of concept {} ({}) in a formula",
                concept.name, concept.typ
            ))),
        }
    }
}
