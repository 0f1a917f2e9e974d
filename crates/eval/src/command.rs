//! The evaluated form of a command call: plain data, no Python left in it.
//! This is the contract between the evaluator and whatever executes commands.

use aster_syntax::Span;
use serde::Serialize;

/// A named result of a command (`MA = LIRE_MAILLAGE(...)` makes concept `MA`
/// of type `maillage_sdaster`).
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct ConceptRef {
    /// The Python name it was bound to.
    pub name: String,
    /// Unique per concept creation in a run (a re-created name gets a new id;
    /// `reuse=` keeps the id).
    pub id: u32,
    /// The catalog type, e.g. `maillage_sdaster`, `evol_noli`, `char_meca`.
    pub typ: String,
}

/// One value of a simple keyword.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "t", content = "v")]
pub enum Scalar {
    Int(i64),
    Real(f64),
    Complex(f64, f64),
    Str(String),
    Concept(ConceptRef),
    /// A Python value that has no command-level meaning (a user function
    /// passed through, `None`...), kept as its repr for diagnostics.
    Opaque(String),
}

impl Scalar {
    /// The value as a real (integers widen).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Scalar::Int(i) => Some(*i as f64),
            Scalar::Real(r) => Some(*r),
            _ => None,
        }
    }

    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Scalar::Int(i) => Some(*i),
            _ => None,
        }
    }

    pub fn as_str(&self) -> Option<&str> {
        match self {
            Scalar::Str(s) => Some(s),
            _ => None,
        }
    }

    pub fn as_concept(&self) -> Option<&ConceptRef> {
        match self {
            Scalar::Concept(c) => Some(c),
            _ => None,
        }
    }
}

/// A keyword's value: a simple keyword holds a list of scalars (code_aster
/// treats `GROUP_MA='A'` and `GROUP_MA=('A',)` alike), a factor keyword holds
/// its occurrences (`ZONE=_F(...)` is one occurrence, `ZONE=(_F(), _F())` two).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", content = "value")]
pub enum KwValue {
    Simple(Vec<Scalar>),
    Factor(Vec<Keywords>),
}

/// One keyword of a call or of a factor occurrence.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Keyword {
    pub name: String,
    pub value: KwValue,
    /// Where it was written; for a default, the span of the enclosing call/_F.
    #[serde(skip)]
    pub span: Span,
    /// True when the value is the catalog default (not written by the user).
    pub defaulted: bool,
}

/// An ordered set of keywords (a call's arguments or one `_F(...)`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
#[serde(transparent)]
pub struct Keywords {
    pub entries: Vec<Keyword>,
}

impl Keywords {
    pub fn get(&self, name: &str) -> Option<&KwValue> {
        self.entries
            .iter()
            .find(|k| k.name == name)
            .map(|k| &k.value)
    }

    pub fn keyword(&self, name: &str) -> Option<&Keyword> {
        self.entries.iter().find(|k| k.name == name)
    }

    /// The scalars of a simple keyword (empty if absent or a factor keyword).
    pub fn simple(&self, name: &str) -> &[Scalar] {
        match self.get(name) {
            Some(KwValue::Simple(v)) => v,
            _ => &[],
        }
    }

    /// The first scalar of a simple keyword.
    pub fn first(&self, name: &str) -> Option<&Scalar> {
        self.simple(name).first()
    }

    pub fn str(&self, name: &str) -> Option<&str> {
        self.first(name).and_then(Scalar::as_str)
    }

    pub fn f64(&self, name: &str) -> Option<f64> {
        self.first(name).and_then(Scalar::as_f64)
    }

    pub fn concept(&self, name: &str) -> Option<&ConceptRef> {
        self.first(name).and_then(Scalar::as_concept)
    }

    /// The occurrences of a factor keyword (empty if absent).
    pub fn factor(&self, name: &str) -> &[Keywords] {
        match self.get(name) {
            Some(KwValue::Factor(v)) => v,
            _ => &[],
        }
    }

    pub fn contains(&self, name: &str) -> bool {
        self.get(name).is_some()
    }
}

/// A validated command call, ready to execute.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CommandCall {
    /// The command name, e.g. `STAT_NON_LINE`.
    pub command: String,
    /// The concept it produces (`RESU = STAT_NON_LINE(...)`), with its type.
    pub result: Option<ConceptRef>,
    /// `reuse=X`: the concept updated in place.
    pub reuse: Option<ConceptRef>,
    pub keywords: Keywords,
    /// The call expression in the source.
    #[serde(skip)]
    pub span: Span,
}

/// What executing a command gives back to the Python program.
#[derive(Clone, Debug, PartialEq)]
pub enum CommandOutput {
    /// Nothing (procedures such as `IMPR_TABLE`).
    Nothing,
    /// The produced concept (`result` of the call).
    Concept,
    /// A plain value (e.g. `EXTR_TABLE(TYPE_RESU='REEL')`).
    Value(Scalar),
}

/// An error raised while executing a command; the evaluator adds the
/// location of the call.
#[derive(Clone, Debug, PartialEq)]
pub struct ExecError {
    pub message: String,
    /// The id of the message code_aster raises for the same error with the
    /// same cause (`CONTACT_93`, `MECANONLINE9_7`), when aster knows it: a
    /// program's `except CA.AsterError as err` reads it as
    /// `err.id_message`. `None`: the error is aster's own.
    pub id_message: Option<&'static str>,
}

impl ExecError {
    pub fn new(message: impl Into<String>) -> ExecError {
        ExecError {
            message: message.into(),
            id_message: None,
        }
    }

    /// The error code_aster raises as message `id`.
    pub fn with_id(mut self, id: &'static str) -> ExecError {
        self.id_message = Some(id);
        self
    }
}

/// A plain Python value exchanged with a sink for methods and subscripts on
/// concepts (`TAB['DX', 1]`, `TAB.EXTR_TABLE()`, `RESU.LIST_PARA()`).
#[derive(Clone, Debug, PartialEq)]
pub enum HostValue {
    None,
    Scalar(Scalar),
    List(Vec<HostValue>),
    /// String-keyed mapping (`LIST_PARA()` gives `{'INST': [...], ...}`).
    Dict(Vec<(String, HostValue)>),
    /// Only known when the commands run (the checker's answer).
    Unknown,
    /// code_aster's `Table` object (`TAB.EXTR_TABLE()`); `None`: its
    /// contents are known only when the commands run (the static pass).
    Table(Option<HostTable>),
}

/// The contents of a table handed to the program (`TAB.EXTR_TABLE()`).
#[derive(Clone, Debug, PartialEq)]
pub struct HostTable {
    /// The parameters (column names), in order.
    pub para: Vec<String>,
    /// The rows, one cell per parameter (`HostValue::None`: empty).
    pub rows: Vec<Vec<HostValue>>,
    /// The table as `print` shows it (its `IMPR_TABLE` text).
    pub text: String,
}

/// A method of a concept that makes a new concept, as code_aster 17's
/// Python objects have them (`mesh = mesh.refine(2)`): the receiver's type,
/// the parameters with their defaults (in order, for positional arguments)
/// and the type of the concept made.
#[derive(Debug)]
pub struct MakingMethod {
    pub receiver: &'static str,
    pub name: &'static str,
    pub params: &'static [(&'static str, i64)],
    pub result: &'static str,
}

/// The concept-making methods the evaluator knows (code_aster 17's
/// `Mesh.refine(ntimes=1, info=1)`, `Mesh.convertToLinear(info=1)`,
/// `Mesh.convertToQuadratic(info=1)`); the sink says whether it runs them
/// ([`CommandSink::make`]).
pub const MAKING_METHODS: &[MakingMethod] = &[
    MakingMethod {
        receiver: "maillage_sdaster",
        name: "refine",
        params: &[("ntimes", 1), ("info", 1)],
        result: "maillage_sdaster",
    },
    MakingMethod {
        receiver: "maillage_sdaster",
        name: "convertToLinear",
        params: &[("info", 1)],
        result: "maillage_sdaster",
    },
    MakingMethod {
        receiver: "maillage_sdaster",
        name: "convertToQuadratic",
        params: &[("info", 1)],
        result: "maillage_sdaster",
    },
];

/// The concept-making method `name` of a concept of type `typ`.
pub fn making_method(typ: &str, name: &str) -> Option<&'static MakingMethod> {
    MAKING_METHODS
        .iter()
        .find(|m| m.receiver == typ && m.name == name)
}

/// Receives the validated commands of a program, in order.
///
/// Only `execute` is required; the other methods have defaults that say
/// "not supported" (or do nothing), so a sink implements what it can.
pub trait CommandSink {
    fn execute(&mut self, call: &CommandCall) -> Result<CommandOutput, ExecError>;

    /// A method called on a concept: `TAB.EXTR_TABLE()`, `RESU.LIST_PARA()`.
    fn method(
        &mut self,
        concept: &ConceptRef,
        name: &str,
        args: &[HostValue],
    ) -> Result<HostValue, ExecError> {
        let _ = args;
        Err(ExecError::new(format!(
            "not supported: method {name}() of concept {} ({})",
            concept.name, concept.typ
        )))
    }

    /// A method that makes a new concept ([`MAKING_METHODS`]:
    /// `mesh.refine(2)`), its arguments bound to the method's parameters
    /// (defaults filled in); `result` is the new concept (its id given by
    /// the evaluator).
    fn make(
        &mut self,
        concept: &ConceptRef,
        name: &str,
        args: &[(&'static str, HostValue)],
        result: &ConceptRef,
    ) -> Result<(), ExecError> {
        let _ = (args, result);
        Err(ExecError::new(format!(
            "not supported: method {name}() of concept {} ({})",
            concept.name, concept.typ
        )))
    }

    /// A subscript on a concept: `TAB['DX', 1]` gives `key = ['DX', 1]`.
    fn index(&mut self, concept: &ConceptRef, key: &[HostValue]) -> Result<HostValue, ExecError> {
        let _ = key;
        Err(ExecError::new(format!(
            "not supported: subscript of concept {} ({})",
            concept.name, concept.typ
        )))
    }

    /// A `FORMULE` was defined (after `execute` accepted its call): the
    /// runner keeps it to evaluate it later with [`crate::Formula::eval`].
    fn formula(&mut self, concept: &ConceptRef, formula: &std::rc::Rc<crate::Formula>) {
        let _ = (concept, formula);
    }

    /// Python `print` output (a whole line, without the newline).
    fn print(&mut self, line: &str) {
        println!("{line}");
    }
}
