//! Validation of a command call against the catalog, as code_aster does it:
//! blocks activated by their conditions (with defaults visible), unknown
//! and missing keywords, types, allowed values, counts, ranges, rules.
//! The result is a [`Keywords`] tree with every default filled in.

use crate::command::{ConceptRef, Keyword, Keywords, KwValue, Scalar};
use crate::diag::{allowed_list, did_you_mean, DiagKind, Diagnostic};
use crate::legacy;
use crate::value::Value;
use aster_catalog::cond::{CVal, CondEnv};
use aster_catalog::{
    find_in, same_name, types, Block, Command, Entry, Lit, Node, Rule, RuleKind, SimpleKw, Status,
    ValueType,
};
use aster_syntax::Span;
use std::borrow::Cow;

/// A keyword as written by the user.
#[derive(Clone, Debug)]
pub(crate) struct Given {
    pub name: String,
    pub span: Span,
    pub value: Value,
}

/// Keyword values seen by block conditions: this level, then the enclosing
/// ones. A level has a few dozen keywords at most: a vector scanned by name
/// beats hashing here.
struct Ctx<'p> {
    /// Name, value (defaults borrowed from the catalog), concept type.
    vals: Vec<(&'p str, Cow<'p, CVal>, Option<String>)>,
    parent: Option<&'p Ctx<'p>>,
}

type CtxEntry<'p> = (&'p str, Cow<'p, CVal>, Option<String>);

impl<'p> Ctx<'p> {
    fn get(&self, k: &str) -> Option<&CtxEntry<'p>> {
        self.vals.iter().find(|(n, _, _)| same_name(n, k))
    }

    fn contains(&self, k: &str) -> bool {
        self.get(k).is_some()
    }

    fn insert(&mut self, k: &'p str, v: Cow<'p, CVal>) {
        if !self.contains(k) {
            self.vals.push((k, v, None));
        }
    }
}

/// What a condition sees for a keyword known only at run time.
static RUN_TIME_NONE: CVal = CVal::None;

/// The condition value of a keyword whose value is only known at run time.
const RUN_TIME: &str = "\u{0}run-time value";

thread_local! {
    /// Set when a condition read something unknown to the checker (a
    /// run-time value, a concept of a type not computed): its answer is a
    /// guess, and the checker must not report errors that depend on it.
    static UNCERTAIN: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

impl CondEnv for Ctx<'_> {
    fn value(&self, k: &str) -> Option<&CVal> {
        match self.get(k) {
            Some((_, v, _)) if matches!(v.as_ref(), CVal::Str(s) if s == RUN_TIME) => {
                UNCERTAIN.with(|u| u.set(true));
                Some(&RUN_TIME_NONE)
            }
            Some((_, v, _)) => Some(v.as_ref()),
            None => self.parent.and_then(|p| p.value(k)),
        }
    }
    fn type_of(&self, k: &str) -> Option<&str> {
        match self.get(k) {
            Some((_, _, Some(t))) if t == types::UNKNOWN => {
                UNCERTAIN.with(|u| u.set(true));
                None
            }
            Some((_, _, t)) => t.as_deref(),
            None => self.parent.and_then(|p| p.type_of(k)),
        }
    }
}

fn lit_scalar(l: &Lit) -> Scalar {
    match l {
        Lit::Int(i) => Scalar::Int(*i),
        Lit::Real(r) => Scalar::Real(*r),
        Lit::Str(s) => Scalar::Str(s.to_string()),
    }
}

/// A user value as a condition sees it (and its concept type).
fn value_cval(v: &Value) -> (CVal, Option<String>) {
    match v {
        Value::Int(i) => (CVal::Int(*i), None),
        Value::Bool(b) => (CVal::Int(*b as i64), None),
        Value::Float(f) => (CVal::Real(*f), None),
        Value::Str(s) => (CVal::Str(s.to_string()), None),
        Value::Concept(c) | Value::Formula(c, _) => {
            (CVal::Str(c.name.clone()), Some(c.typ.clone()))
        }
        Value::List(_) | Value::Tuple(_) => {
            let items = flatten(v);
            let ty = items.first().and_then(|x| value_cval(x).1);
            match items.as_slice() {
                [one] => (value_cval(one).0, ty),
                many => (
                    CVal::Tuple(many.iter().map(|x| value_cval(x).0).collect()),
                    ty,
                ),
            }
        }
        Value::Dict(_) => (CVal::Bool(true), None),
        // Possibly a concept (`R.copy()`), of a type nobody knows yet.
        Value::Unknown => (CVal::Str(RUN_TIME.into()), Some(types::UNKNOWN.into())),
        _ => (CVal::Str(v.to_string()), None),
    }
}

/// The real a code_aster 11 file gave for a keyword that code_aster 17
/// types as a function only (`DEFI_MATERIAU/THM_LIQU/ALPHA`,
/// `ELAS_FO/RHO`...): it stands for a constant function.
fn constant_function_wanted(kw: &SimpleKw, item: &Value) -> Option<f64> {
    let x = match item {
        Value::Float(f) => *f,
        Value::Int(i) => *i as f64,
        _ => return None,
    };
    let function = kw
        .types
        .iter()
        .any(|t| matches!(t, ValueType::Concept(c) if *c == "fonction_sdaster"));
    let number = kw
        .types
        .iter()
        .any(|t| matches!(t, ValueType::Real | ValueType::Int | ValueType::Any));
    (function && !number).then_some(x)
}

pub(crate) fn flatten(v: &Value) -> Vec<Value> {
    match v {
        Value::List(l) => l.borrow().iter().flat_map(flatten).collect(),
        Value::Tuple(t) => t.iter().flat_map(flatten).collect(),
        // An attribute of a concept (`getattr(resu, 'CHAMP_1')`, a result
        // of a macro): known only when the commands run.
        Value::Method(r, _) if matches!(**r, Value::Concept(_) | Value::Formula(..)) => {
            vec![Value::Unknown]
        }
        other => vec![other.clone()],
    }
}

pub(crate) struct Validator<'n> {
    /// `reuse=` was written (some rules name it).
    pub reuse_given: bool,
    pub command: String,
    pub diags: Vec<Diagnostic>,
    /// Concepts announced with `CO('name')`.
    pub created: Vec<ConceptRef>,
    pub next_id: &'n mut u32,
    /// The file was written for an older code_aster: its spellings that
    /// code_aster 17 dropped are translated (see `legacy`).
    pub legacy: bool,
    /// Concepts that code_aster 17 needs where a code_aster 11 file wrote
    /// none (a real where a function is wanted, no time list for a
    /// stationary computation): the caller defines each, in order, before
    /// the command runs.
    pub synthesized: Vec<Synthesized>,
}

/// A command the legacy layer adds before the one being validated.
#[derive(Clone, Debug)]
pub(crate) struct Synthesized {
    pub command: &'static str,
    pub keywords: Vec<Given>,
    pub result: ConceptRef,
    pub span: Span,
}

impl Validator<'_> {
    /// A new concept of type `typ` made by `command(keywords)`, defined
    /// before the command being validated.
    fn synthesize(
        &mut self,
        command: &'static str,
        typ: &str,
        keywords: Vec<(&str, Value)>,
        span: Span,
    ) -> ConceptRef {
        let id = *self.next_id;
        *self.next_id += 1;
        let result = ConceptRef {
            name: format!("_{command}_{id}"),
            id,
            typ: typ.into(),
        };
        self.synthesized.push(Synthesized {
            command,
            keywords: keywords
                .into_iter()
                .map(|(name, value)| Given {
                    name: name.into(),
                    span,
                    value,
                })
                .collect(),
            result: result.clone(),
            span,
        });
        result
    }

    /// code_aster 11's stationary thermal computation: no `INCREMENT`.
    /// code_aster 17 writes it `TYPE_CALCUL='STAT',
    /// INCREMENT=_F(LIST_INST=DEFI_LIST_REEL(VALE=0.0))`.
    fn stationary_thermal(&mut self, path: &str, given: &mut Vec<Given>, span: Span) {
        if given
            .iter()
            .any(|g| g.name == "INCREMENT" || g.name == "TYPE_CALCUL")
        {
            return;
        }
        let list = self.synthesize(
            "DEFI_LIST_REEL",
            "listr8_sdaster",
            vec![("VALE", Value::Float(0.0))],
            span,
        );
        self.diags.push(Diagnostic::warning(
            DiagKind::Legacy,
            span,
            format!("`{path}` without INCREMENT is code_aster 11's stationary computation: now TYPE_CALCUL='STAT', INCREMENT=_F(LIST_INST=DEFI_LIST_REEL(VALE=0.0))"),
        ));
        let mut d = crate::value::Dict::default();
        d.insert(Value::str("LIST_INST"), Value::Concept(list), span);
        given.push(Given {
            name: "TYPE_CALCUL".into(),
            span,
            value: Value::str("STAT"),
        });
        given.push(Given {
            name: "INCREMENT".into(),
            span,
            value: Value::Dict(std::rc::Rc::new(std::cell::RefCell::new(d))),
        });
    }
}

impl Validator<'_> {
    pub fn validate(&mut self, cmd: &Command, given: Vec<Given>, span: Span) -> Keywords {
        self.level(cmd.keywords, cmd.rules, given, cmd.name, None, span)
    }

    fn error(&mut self, kind: DiagKind, span: Span, msg: String) -> &mut Diagnostic {
        self.diags.push(Diagnostic::error(kind, span, msg));
        let n = self.diags.len();
        &mut self.diags[n - 1]
    }

    #[allow(clippy::too_many_arguments)]
    fn activate<'e>(
        &self,
        entries: &'e [Entry],
        ctx: &mut Ctx<'e>,
        active: &mut Vec<&'e Entry>,
        rules: &mut Vec<&'e Rule>,
        maybe: bool,
        guessed: &mut Vec<&'e str>,
    ) {
        // The direct entries of a level are distinct (a Python dict in the
        // catalog): only the keywords of blocks can repeat a name already
        // active. Not scanning for the others keeps this linear for the
        // levels with hundreds of keywords (DEFI_MATERIAU).
        let top = active.is_empty();
        for e in entries {
            match &e.node {
                Node::Block(_) => {}
                Node::Simple(s) => {
                    if !top && active.iter().any(|a| same_name(a.name, e.name)) {
                        continue;
                    }
                    active.push(e);
                    if maybe {
                        guessed.push(e.name);
                        continue;
                    }
                    if s.default.is_some() && !ctx.contains(e.name) {
                        if let Some(d) = s.default_cval() {
                            ctx.insert(e.name, Cow::Borrowed(d));
                        }
                    }
                }
                Node::Factor(f) => {
                    if !top && active.iter().any(|a| same_name(a.name, e.name)) {
                        continue;
                    }
                    active.push(e);
                    if maybe {
                        guessed.push(e.name);
                        continue;
                    }
                    if f.status == Status::Defaulted {
                        ctx.insert(e.name, Cow::Owned(CVal::Bool(true)));
                    }
                }
            }
        }
        for e in entries {
            if let Node::Block(b) = &e.node {
                // A condition that cannot be evaluated (e.g. comparing an
                // absent keyword) does not hold: no false errors from it.
                UNCERTAIN.with(|u| u.set(false));
                let holds = match b.cond().as_ref() {
                    Ok(c) => aster_catalog::cond::holds(c, ctx).unwrap_or(false),
                    Err(_) => false,
                };
                let unsure = UNCERTAIN.with(|u| u.replace(false));
                if holds && !maybe && !unsure {
                    rules.extend(b.rules.iter());
                    self.activate(b.keywords, ctx, active, rules, false, guessed);
                } else if holds || unsure {
                    // Accept the block's keywords without requiring or
                    // defaulting any: the checker cannot know.
                    self.activate(b.keywords, ctx, active, rules, true, guessed);
                }
            }
        }
    }

    fn level(
        &mut self,
        entries: &[Entry],
        level_rules: &[Rule],
        mut given: Vec<Given>,
        path: &str,
        parent: Option<&Ctx>,
        span: Span,
    ) -> Keywords {
        // `KW=None` means "not given" in code_aster.
        // An empty list or tuple is "nothing" too (lists built by loops).
        given.retain(|g| match &g.value {
            Value::None => false,
            Value::List(l) => !l.borrow().is_empty(),
            Value::Tuple(t) => !t.is_empty(),
            _ => true,
        });
        let level_start = self.diags.len();
        if self.legacy
            && parent.is_none()
            && matches!(self.command.as_str(), "THER_LINEAIRE" | "THER_NON_LINE")
        {
            self.stationary_thermal(path, &mut given, span);
        }
        legacy::transform_level(
            &self.command,
            path,
            entries,
            &mut given,
            &mut self.diags,
            self.legacy,
        );

        let mut ctx = Ctx {
            vals: Vec::with_capacity(given.len() + 8),
            parent,
        };
        for g in &given {
            let (mut v, t) = value_cval(&g.value);
            // A keyword that takes several values is a tuple for the
            // conditions (`len(CARA) == 1`), as in code_aster.
            let multi = matches!(
                find_in(entries, &g.name).map(|e| &e.node),
                Some(Node::Simple(s)) if s.max != aster_catalog::Max::Count(1)
            );
            if multi && !matches!(v, CVal::Tuple(_)) {
                v = CVal::Tuple(vec![v]);
            }
            // Python keeps the last of repeated keys: so does a dict here.
            match ctx.vals.iter_mut().find(|(n, _, _)| *n == g.name) {
                Some(slot) => *slot = (&g.name, Cow::Owned(v), t),
                None => ctx.vals.push((&g.name, Cow::Owned(v), t)),
            }
        }
        let mut active: Vec<&Entry> = Vec::new();
        let mut rules: Vec<&Rule> = level_rules.iter().collect();
        let mut guessed: Vec<&str> = Vec::new();
        self.activate(
            entries,
            &mut ctx,
            &mut active,
            &mut rules,
            false,
            &mut guessed,
        );

        // The validated value of each active entry, by position in `active`.
        // The validated given keywords, with their position in `active`
        // (few: a level with hundreds of possible keywords gets a handful).
        let mut values: Vec<(usize, Keyword)> = Vec::with_capacity(given.len());
        let errors_before = self.diags.iter().filter(|d| d.is_error()).count();
        let diags_before = self.diags.len();
        let mut inactive = Vec::new();
        for g in &given {
            let Some(slot) = active.iter().position(|a| same_name(a.name, &g.name)) else {
                inactive.push(g);
                continue;
            };
            let entry = active[slot];
            let value = match &entry.node {
                Node::Simple(s) if guessed.contains(&g.name.as_str()) => {
                    // Its block may or may not apply (the checker cannot
                    // know): take the value without judging it.
                    let n = self.diags.len();
                    let v = self.simple(s, g, path);
                    self.diags.truncate(n);
                    Some(KwValue::Simple(v.unwrap_or_else(|| lenient(&g.value))))
                }
                Node::Simple(s) => self.simple(s, g, path).map(KwValue::Simple),
                Node::Factor(f) => {
                    let kpath = format!("{path}/{}", g.name);
                    let occs: Vec<Value> = match &g.value {
                        Value::Dict(_) => vec![g.value.clone()],
                        Value::List(_) | Value::Tuple(_) => flatten(&g.value),
                        _ => vec![g.value.clone()],
                    };
                    let mut out = Vec::new();
                    let mut ok = true;
                    for (i, occ) in occs.iter().enumerate() {
                        let Value::Dict(d) = occ else {
                            self.error(
                                DiagKind::WrongType,
                                g.span,
                                format!(
                                    "`{kpath}` is a factor keyword: expected _F(...), found {}",
                                    occ.repr()
                                ),
                            );
                            ok = false;
                            continue;
                        };
                        let mut inner = Vec::new();
                        for en in d.borrow().entries.iter() {
                            match &en.key {
                                Value::Str(k) => inner.push(Given {
                                    name: k.to_string(),
                                    span: if en.span == Span::default() {
                                        g.span
                                    } else {
                                        en.span
                                    },
                                    value: en.value.clone(),
                                }),
                                other => {
                                    self.error(
                                        DiagKind::WrongType,
                                        g.span,
                                        format!(
                                            "`{kpath}`: keyword names must be strings, found {}",
                                            other.repr()
                                        ),
                                    );
                                }
                            }
                        }
                        let occ_span = d.borrow().entries.first().map(|e| e.span).unwrap_or(g.span);
                        let occ_path = format!("{kpath}[{}]", i + 1);
                        out.push(self.level(
                            f.keywords,
                            f.rules,
                            inner,
                            &occ_path,
                            Some(&ctx),
                            if occ_span == Span::default() {
                                g.span
                            } else {
                                occ_span
                            },
                        ));
                    }
                    if ok && (occs.len() < f.min as usize || !f.max.allows(occs.len())) {
                        self.error(
                            DiagKind::Count,
                            g.span,
                            format!(
                                "`{kpath}` accepts between {} and {} occurrence(s), {} given",
                                f.min,
                                f.max.describe(),
                                occs.len()
                            ),
                        );
                    }
                    Some(KwValue::Factor(out))
                }
                Node::Block(_) => None,
            };
            if let Some(v) = value {
                values.push((
                    slot,
                    Keyword {
                        name: g.name.clone(),
                        value: v,
                        span: g.span,
                        defaulted: false,
                    },
                ));
            }
        }

        // A wrong value at this level may have closed the block a keyword
        // belongs to: then only truly unknown keywords are reported.
        let level_failed = self.diags.iter().filter(|d| d.is_error()).count() > errors_before;
        // A value refused as unsupported (a code_aster 11 method with no
        // current form) leaves the level's meaning unknown: the keywords
        // code_aster 17 would require with it are not reported missing, nor
        // its rules checked.
        let refused = self.diags[level_start.min(diags_before)..]
            .iter()
            .any(|d| d.is_error() && d.kind.is_not_supported());
        // A did-you-mean never proposes a keyword written beside it.
        let written_here: Vec<&str> = given.iter().map(|g| g.name.as_str()).collect();
        for g in inactive {
            self.not_active(entries, &active, g, &written_here, path, level_failed);
        }

        // Missing keywords and defaults, in catalog order.
        let mut out = Keywords {
            entries: Vec::with_capacity(active.len()),
        };
        values.sort_by_key(|(slot, _)| *slot);
        let mut values = values.into_iter().peekable();
        for (i, e) in active.iter().enumerate() {
            if let Some((_, k)) = values.next_if(|(slot, _)| *slot == i) {
                out.entries.push(k);
                continue;
            }
            // Most entries of a large level are optional and absent:
            // settle them before comparing names.
            let needs_something = match &e.node {
                Node::Simple(s) => s.default.is_some() || s.status == Status::Mandatory,
                Node::Factor(f) => matches!(f.status, Status::Mandatory | Status::Defaulted),
                Node::Block(_) => false,
            };
            if !needs_something
                || given.iter().any(|g| same_name(&g.name, e.name))
                || guessed.contains(&e.name)
            {
                continue; // nothing to fill, given but invalid (already reported), or unsure
            }
            match &e.node {
                Node::Simple(s) => match (&s.default, s.status) {
                    (Some(d), _) => out.entries.push(Keyword {
                        name: e.name.to_string(),
                        value: KwValue::Simple(d.iter().map(|l| default_scalar(l, s)).collect()),
                        span,
                        defaulted: true,
                    }),
                    (None, Status::Mandatory) if refused => {}
                    (None, Status::Mandatory) => {
                        let expected = s
                            .types
                            .iter()
                            .map(|t| t.describe())
                            .collect::<Vec<_>>()
                            .join(" or ");
                        let mut d = Diagnostic::error(
                            DiagKind::MissingKeyword,
                            span,
                            format!(
                                "`{path}`: missing mandatory keyword {} ({expected})",
                                e.name
                            ),
                        );
                        if let Some(into) = &s.into {
                            d = d.note(format!("note: allowed values: {}", allowed_list(into)));
                        }
                        self.diags.push(d);
                    }
                    _ => {}
                },
                Node::Factor(f) => match f.status {
                    Status::Mandatory => {
                        self.error(
                            DiagKind::MissingKeyword,
                            span,
                            format!(
                                "`{path}`: missing mandatory factor keyword {}=_F(...)",
                                e.name
                            ),
                        );
                    }
                    Status::Defaulted => {
                        let occ = self.level(
                            f.keywords,
                            f.rules,
                            Vec::new(),
                            &format!("{path}/{}[1]", e.name),
                            Some(&ctx),
                            span,
                        );
                        out.entries.push(Keyword {
                            name: e.name.to_string(),
                            value: KwValue::Factor(vec![occ]),
                            span,
                            defaulted: true,
                        });
                    }
                    _ => {}
                },
                Node::Block(_) => {}
            }
        }

        let mut written: Vec<&str> = given.iter().map(|g| g.name.as_str()).collect();
        if parent.is_none() && self.reuse_given {
            written.push("reuse");
        }
        // code_aster does not hold `reuse` to the catalog rules that name it
        // (THER_NON_LINE(reuse=R) without RESULTAT is valid).
        let rules: Vec<&Rule> = rules
            .into_iter()
            .filter(|r| !r.args.contains(&"reuse"))
            .collect();
        let defaulted: Vec<&str> = out
            .entries
            .iter()
            .filter(|k| k.defaulted)
            .map(|k| k.name.as_str())
            .collect();
        let mut drop: Vec<String> = Vec::new();
        // An occurrence nobody wrote (a factor keyword present by default)
        // is not held to the "at least one" rules: code_aster fills those
        // values when the command runs.
        let mut implied: Vec<Keyword> = Vec::new();
        let check_rules = (!given.is_empty() || parent.is_none()) && !refused;
        for r in rules {
            if let Some(k) = implicit_default(path, r, &written, span) {
                implied.extend(k);
                continue;
            }
            if check_rules {
                if r.args.is_empty() {
                    // `NotEmpty` without names: the occurrence says something.
                    if given.is_empty() && out.entries.is_empty() {
                        self.error(DiagKind::Rule, span, format!("`{path}` must not be empty"));
                    }
                    continue;
                }
                self.rule(r, &written, &defaulted, &mut drop, path, span);
            }
        }
        drop_names(&mut out, &drop);
        out.entries.extend(implied);
        out
    }

    fn not_active(
        &mut self,
        entries: &[Entry],
        active: &[&Entry],
        g: &Given,
        written: &[&str],
        path: &str,
        quiet: bool,
    ) {
        let unwritten = |name: &&str| !written.contains(name);
        if let Some(b) = block_of(entries, &g.name) {
            if quiet {
                return;
            }
            let mut d = Diagnostic::error(
                DiagKind::KeywordNotApplicable,
                g.span,
                format!(
                    "`{path}/{}` is not allowed here: it applies only when {}",
                    g.name,
                    aster_catalog::explain::plain_condition(b.condition)
                ),
            );
            if let Some(h) = did_you_mean(&g.name, active.iter().map(|a| a.name).filter(unwritten))
            {
                d = d.note(h);
            }
            self.diags.push(d);
            return;
        }
        let names: Vec<&str> = active
            .iter()
            .map(|a| a.name)
            .filter(|n| *n != "reuse")
            .collect();
        let candidates: Vec<&str> = names.iter().copied().filter(unwritten).collect();
        let mut d = Diagnostic::error(
            DiagKind::UnknownKeyword,
            g.span,
            format!("`{path}`: unknown keyword {}", g.name),
        );
        match did_you_mean(&g.name, candidates.iter().copied()) {
            Some(h) => d = d.note(h),
            None => {
                d = d.note(format!(
                    "note: keywords accepted here: {}",
                    allowed_list(&names)
                ))
            }
        }
        self.diags.push(d);
    }

    /// Validates a simple keyword given at level `parent` (its path, for
    /// messages, is only built when there is something to report).
    fn simple(&mut self, kw: &SimpleKw, g: &Given, parent: &str) -> Option<Vec<Scalar>> {
        let kpath = || format!("{parent}/{}", g.name);
        let items = flatten(&g.value);
        let items = group_complex(kw, items);
        let mut out = Vec::with_capacity(items.len());
        let mut failed = false;
        for item in &items {
            let constant = if self.legacy {
                constant_function_wanted(kw, item)
            } else {
                None
            };
            match (self.scalar(kw, item), constant) {
                (Some(s), _) => out.push(s),
                (None, Some(x)) => {
                    self.diags.push(Diagnostic::warning(
                        DiagKind::Legacy,
                        g.span,
                        format!(
                            "`{}`: a real is code_aster 11 syntax here: now a function, DEFI_CONSTANTE(VALE={})",
                            kpath(),
                            item.repr()
                        ),
                    ));
                    let c = self.synthesize(
                        "DEFI_CONSTANTE",
                        "fonction_sdaster",
                        vec![("VALE", Value::Float(x))],
                        g.span,
                    );
                    out.push(Scalar::Concept(c));
                }
                (None, None) => {
                    let expected = kw
                        .types
                        .iter()
                        .map(|t| t.describe())
                        .collect::<Vec<_>>()
                        .join(" or ");
                    let found = match item {
                        Value::Concept(c) | Value::Formula(c, _) => {
                            format!("concept {} of type {}", c.name, c.typ)
                        }
                        other => format!("{} ({})", other.repr(), other.type_name()),
                    };
                    self.error(
                        DiagKind::WrongType,
                        g.span,
                        format!("`{}`: expected {expected}, found {found}", kpath()),
                    );
                    failed = true;
                }
            }
        }
        if failed {
            return None;
        }
        if let Some(into) = &kw.into {
            for s in out.iter_mut() {
                if matches!(s, Scalar::Opaque(_)) || into_contains(into, s) {
                    continue;
                }
                match legacy::value(&kpath(), s, into, kw.default, self.legacy) {
                    Some(legacy::ValueFix::Renamed(new, why)) => {
                        let d = Diagnostic::warning(
                            DiagKind::Legacy,
                            g.span,
                            format!(
                                "`{}`: legacy value {} is now {}",
                                kpath(),
                                scalar_repr(s),
                                scalar_repr(&new)
                            ),
                        );
                        self.diags.push(match why {
                            Some(w) => d.note(format!("note: {w}")),
                            None => d,
                        });
                        *s = new;
                        continue;
                    }
                    Some(legacy::ValueFix::Unsupported(msg)) => {
                        self.diags
                            .push(Diagnostic::error(DiagKind::NotSupported, g.span, msg));
                        failed = true;
                        continue;
                    }
                    None => {}
                }
                let shown = scalar_repr(s);
                let strs: Vec<String> = into
                    .iter()
                    .map(|l| match l {
                        Lit::Str(x) => x.to_string(),
                        other => other.to_string(),
                    })
                    .collect();
                let mut d = Diagnostic::error(
                    DiagKind::NotInto,
                    g.span,
                    format!("`{}`: value {shown} is not allowed", kpath()),
                );
                if let Scalar::Str(x) = s {
                    if let Some(h) = did_you_mean(x, strs.iter().map(|s| s.as_str())) {
                        d = d.note(h);
                    }
                }
                d = d.note(format!("note: allowed values: {}", allowed_list(into)));
                self.diags.push(d);
                failed = true;
            }
        }
        for s in &out {
            if let Some(x) = s.as_f64() {
                // No keyword of code_aster takes an infinity or a NaN: caught
                // here, at the keyword, rather than as a singular system or
                // a degenerate cell later.
                if !x.is_finite() {
                    self.error(
                        DiagKind::OutOfRange,
                        g.span,
                        format!(
                            "`{}`: value {} is not a finite number",
                            kpath(),
                            scalar_repr(s)
                        ),
                    );
                    failed = true;
                    continue;
                }
                let lo = kw.val_min.is_some_and(|m| x < m);
                let hi = kw.val_max.is_some_and(|m| x > m);
                if lo || hi {
                    let range = match (kw.val_min, kw.val_max) {
                        (Some(a), Some(b)) => format!("between {a} and {b}"),
                        (Some(a), None) => format!("at least {a}"),
                        (None, Some(b)) => format!("at most {b}"),
                        _ => String::new(),
                    };
                    self.error(
                        DiagKind::OutOfRange,
                        g.span,
                        format!(
                            "`{}`: value {} out of range: must be {range}",
                            kpath(),
                            scalar_repr(s)
                        ),
                    );
                    failed = true;
                }
            }
        }
        let n = out.len();
        // A run-time value may stand for any number of values.
        let count_known = !items.iter().any(|v| matches!(v, Value::Unknown));
        if count_known && (n < kw.min as usize || !kw.max.allows(n)) {
            let expect = if kw.min as usize == 1 && kw.max == aster_catalog::Max::Count(1) {
                "exactly one value".to_string()
            } else {
                format!("between {} and {} values", kw.min, kw.max.describe())
            };
            self.error(
                DiagKind::Count,
                g.span,
                format!("`{}` expects {expect}, {n} given", kpath()),
            );
            failed = true;
        }
        (!failed).then_some(out)
    }

    fn scalar(&mut self, kw: &SimpleKw, v: &Value) -> Option<Scalar> {
        let types = &kw.types;
        let has = |t: &ValueType| types.contains(t);
        if types.is_empty() || has(&ValueType::Any) {
            return Some(match v {
                Value::Int(i) => Scalar::Int(*i),
                Value::Float(f) => Scalar::Real(*f),
                Value::Str(s) => Scalar::Str(s.to_string()),
                Value::Concept(c) | Value::Formula(c, _) => Scalar::Concept(c.clone()),
                other => Scalar::Opaque(other.to_string()),
            });
        }
        match v {
            Value::Unknown => Some(Scalar::Opaque("<run-time value>".into())),
            // An integer beyond 64 bits: a real keyword takes it as code_aster
            // does (`float()`); an integer keyword cannot hold it.
            Value::Big(_) => {
                let f = v.as_f64().filter(|f| f.is_finite())?;
                if has(&ValueType::Real) {
                    Some(Scalar::Real(f))
                } else if has(&ValueType::Complex) {
                    Some(Scalar::Complex(f, 0.0))
                } else {
                    None
                }
            }
            Value::Int(_) | Value::Bool(_) => {
                let i = match v {
                    Value::Bool(b) => *b as i64,
                    Value::Int(i) => *i,
                    _ => 0,
                };
                if has(&ValueType::Int) || has(&ValueType::Unit) {
                    Some(Scalar::Int(i))
                } else if has(&ValueType::Real) {
                    Some(Scalar::Real(i as f64))
                } else if has(&ValueType::Complex) {
                    Some(Scalar::Complex(i as f64, 0.0))
                } else {
                    None
                }
            }
            Value::Float(f) => {
                if has(&ValueType::Real) {
                    Some(Scalar::Real(*f))
                } else if (has(&ValueType::Int) || has(&ValueType::Unit))
                    && f.fract() == 0.0
                    && f.abs() < 9.0e15
                {
                    // code_aster accepts an integral real for an integer.
                    Some(Scalar::Int(*f as i64))
                } else if has(&ValueType::Complex) {
                    Some(Scalar::Complex(*f, 0.0))
                } else {
                    None
                }
            }
            Value::Complex(a, b) => has(&ValueType::Complex).then_some(Scalar::Complex(*a, *b)),
            Value::Str(s) => {
                let name = types.iter().any(|t| {
                    matches!(
                        t,
                        ValueType::GroupMa | ValueType::GroupNo | ValueType::Cell | ValueType::Node
                    )
                });
                if name {
                    // Names of the mesh are fixed-length Fortran strings in
                    // code_aster: trailing blanks are not part of the name
                    // (`GROUP_MA='POUTRE    '` is the group POUTRE).
                    Some(Scalar::Str(s.trim_end_matches(' ').to_string()))
                } else {
                    has(&ValueType::Text).then(|| Scalar::Str(s.to_string()))
                }
            }
            Value::Concept(c) | Value::Formula(c, _) => {
                let ok = c.typ == types::UNKNOWN
                    || types.iter().any(|t| match t {
                        ValueType::Concept(e) => types::is_a(&c.typ, e),
                        ValueType::Co => true,
                        _ => false,
                    });
                ok.then(|| Scalar::Concept(c.clone()))
            }
            Value::Co(name) => {
                if !has(&ValueType::Co) {
                    return None;
                }
                let c = ConceptRef {
                    name: name.to_string(),
                    id: *self.next_id,
                    typ: types::UNKNOWN.to_string(),
                };
                *self.next_id += 1;
                self.created.push(c.clone());
                Some(Scalar::Concept(c))
            }
            _ => None,
        }
    }

    /// Checks a rule the way code_aster reads its catalog: a default counts
    /// as present when nothing written competes with it (`TOUT='OUI'` by
    /// default, unless a `GROUP_MA` is given — then the default is dropped,
    /// listed in `drop`).
    fn rule(
        &mut self,
        r: &Rule,
        written: &[&str],
        defaulted: &[&str],
        drop: &mut Vec<String>,
        path: &str,
        span: Span,
    ) {
        let w = |k: &str| written.contains(&k);
        // `TOUT` competing with groups means "everywhere" when no group is
        // given (code_aster's implicit `TOUT='OUI'`).
        let d = |k: &str| defaulted.contains(&k) || (k == "TOUT" && nw_of(r, written) == 0);
        let nw = r.args.iter().filter(|a| w(a)).count();
        let nd = r.args.iter().filter(|a| d(a)).count();
        // Message parts, built only when a rule fails.
        let list = || r.args.join(", ");
        let first = r.args.first().copied().unwrap_or("");
        let others = || r.args.get(1..).unwrap_or(&[]).join(", ");
        let drop_defaults = |drop: &mut Vec<String>| {
            drop.extend(r.args.iter().filter(|a| d(a)).map(|a| a.to_string()));
        };
        let msg = match r.kind {
            RuleKind::ExactlyOne => {
                if nw == 1 {
                    drop_defaults(drop);
                    None
                } else if nw > 1 {
                    Some(format!(
                        "exactly one of {} is required ({nw} given)",
                        list()
                    ))
                } else if nd == 1 {
                    None
                } else {
                    Some(format!(
                        "exactly one of {} is required (none given)",
                        list()
                    ))
                }
            }
            RuleKind::AtMostOne => {
                if nw > 1 {
                    Some(format!("at most one of {} is allowed ({nw} given)", list()))
                } else {
                    if nw == 1 {
                        drop_defaults(drop);
                    }
                    None
                }
            }
            RuleKind::AtLeastOne | RuleKind::NotEmpty => {
                (nw + nd == 0).then(|| format!("at least one of {} is required", list()))
            }
            RuleKind::AllTogether => {
                let n = r.args.iter().filter(|a| w(a) || d(a)).count();
                (nw > 0 && n != r.args.len())
                    .then(|| format!("{} go together: give all of them or none", list()))
            }
            RuleKind::OnlyFirstPresent => {
                let others_written = r.args[1.min(r.args.len())..].iter().any(|a| w(a));
                if w(first) && others_written {
                    Some(format!("when {first} is given, {} must not be", others()))
                } else {
                    if w(first) {
                        drop.extend(r.args[1..].iter().filter(|a| d(a)).map(|a| a.to_string()));
                    } else if others_written && d(first) {
                        drop.push(first.to_string());
                    }
                    None
                }
            }
            RuleKind::IfFirstAllPresent => {
                let all = r.args[1.min(r.args.len())..].iter().all(|a| w(a) || d(a));
                (w(first) && !all)
                    .then(|| format!("when {first} is given, {} must be given too", others()))
            }
        };
        if let Some(m) = msg {
            self.error(DiagKind::Rule, span, format!("`{path}`: {m}"));
        }
    }
}

/// Removes the defaults that a written keyword displaced (see `rule`).
fn drop_names(out: &mut Keywords, drop: &[String]) {
    if !drop.is_empty() {
        out.entries
            .retain(|k| !(k.defaulted && drop.contains(&k.name)));
    }
}

/// Rules that code_aster satisfies when the command runs, with the value
/// it then uses: "exactly one of INST, LIST_INST" in MECA_STATIQUE means
/// INST=0.0 when neither is given; CONVERGENCE gets RESI_GLOB_RELA=1e-6;
/// ARCHIVAGE archives every step. `Some(keywords to add)` when the rule
/// is one of these and nothing was written.
fn implicit_default(path: &str, r: &Rule, written: &[&str], span: Span) -> Option<Option<Keyword>> {
    if nw_of(r, written) > 0 || !matches!(r.kind, RuleKind::ExactlyOne | RuleKind::AtLeastOne) {
        return None;
    }
    let last = path.rsplit('/').next().unwrap_or(path);
    let last = last.split('[').next().unwrap_or(last);
    let has = |k: &str| r.args.contains(&k);
    let add = |name: &str, v: Scalar| {
        Some(Some(Keyword {
            name: name.to_string(),
            value: KwValue::Simple(vec![v]),
            span,
            defaulted: true,
        }))
    };
    match last {
        "CONVERGENCE" if has("RESI_GLOB_RELA") => add("RESI_GLOB_RELA", Scalar::Real(1e-6)),
        "MECA_STATIQUE" if has("INST") && has("LIST_INST") => add("INST", Scalar::Real(0.0)),
        "ARCHIVAGE" => Some(None),
        _ => None,
    }
}

/// A value taken as written, without a catalog type to convert it to.
fn lenient(v: &Value) -> Vec<Scalar> {
    flatten(v)
        .into_iter()
        .map(|x| match x {
            Value::Int(i) => Scalar::Int(i),
            Value::Float(f) => Scalar::Real(f),
            Value::Complex(a, b) => Scalar::Complex(a, b),
            Value::Str(s) => Scalar::Str(s.to_string()),
            Value::Concept(c) | Value::Formula(c, _) => Scalar::Concept(c),
            other => Scalar::Opaque(other.to_string()),
        })
        .collect()
}

fn nw_of(r: &Rule, written: &[&str]) -> usize {
    r.args.iter().filter(|a| written.contains(a)).count()
}

/// `('RI', re, im)` / `('MP', mod, phase)` given to a complex keyword.
fn group_complex(kw: &SimpleKw, items: Vec<Value>) -> Vec<Value> {
    if !kw.types.contains(&ValueType::Complex) {
        return items;
    }
    let mut out = Vec::new();
    let mut i = 0;
    while i < items.len() {
        match (
            &items[i],
            items.get(i + 1).and_then(Value::as_f64),
            items.get(i + 2).and_then(Value::as_f64),
        ) {
            (Value::Str(s), Some(a), Some(b)) if &**s == "RI" => {
                out.push(Value::Complex(a, b));
                i += 3;
            }
            (Value::Str(s), Some(m), Some(p)) if &**s == "MP" => {
                let p = p.to_radians();
                out.push(Value::Complex(m * p.cos(), m * p.sin()));
                i += 3;
            }
            (v, _, _) => {
                out.push(v.clone());
                i += 1;
            }
        }
    }
    out
}

fn default_scalar(l: &Lit, kw: &SimpleKw) -> Scalar {
    match l {
        Lit::Int(i)
            if kw.types.contains(&ValueType::Real) && !kw.types.contains(&ValueType::Int) =>
        {
            Scalar::Real(*i as f64)
        }
        other => lit_scalar(other),
    }
}

fn into_contains(into: &[Lit], s: &Scalar) -> bool {
    into.iter().any(|l| match (l, s) {
        (Lit::Str(a), Scalar::Str(b)) => a == b,
        (Lit::Int(a), Scalar::Int(b)) => a == b,
        (l, s) => match (l, s.as_f64()) {
            (Lit::Int(a), Some(b)) => *a as f64 == b,
            (Lit::Real(a), Some(b)) => *a == b,
            _ => false,
        },
    })
}

pub(crate) fn scalar_repr(s: &Scalar) -> String {
    match s {
        Scalar::Int(i) => i.to_string(),
        Scalar::Real(r) => crate::value::float_str(*r),
        Scalar::Complex(a, b) => format!("({a}{b:+}j)"),
        Scalar::Str(s) => format!("'{s}'"),
        Scalar::Concept(c) => c.name.clone(),
        Scalar::Opaque(o) => o.clone(),
    }
}

/// The innermost block of a level that declares `name`.
fn block_of<'e>(entries: &'e [Entry], name: &str) -> Option<&'e Block> {
    for e in entries {
        if let Node::Block(b) = &e.node {
            if let Some(inner) = block_of(b.keywords, name) {
                return Some(inner);
            }
            if b.keywords
                .iter()
                .any(|k| k.name == name && !matches!(k.node, Node::Block(_)))
            {
                return Some(b);
            }
        }
    }
    None
}
