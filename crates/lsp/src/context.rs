//! Where a position is, in catalog terms: inside which command call and
//! which factor keywords (`DEFI_CONTACT(ZONE=_F(|`), with the keywords
//! already written at each level and their literal values — read from the
//! tolerant token stream ([`crate::lex`]), so that it works on a file being
//! typed. From it: the keywords valid at that point (the blocks whose
//! condition holds given what is written, defaults visible, as the
//! validator opens them).

use crate::lex::{self, Kind, Token};
use aster_catalog::cond::{CVal, CondEnv};
use aster_catalog::{catalog, Command, Entry, Node, Rule, RuleKind, SimpleKw};
use std::collections::HashMap;

/// A keyword written at one level.
#[derive(Clone, Debug)]
pub struct Written {
    pub name: String,
    /// The byte range of the name.
    pub start: usize,
    pub end: usize,
    /// Its literal values (strings, numbers) as block conditions see them;
    /// a name's value is kept as the name (its type is looked up).
    pub values: Vec<CVal>,
    /// Names (concepts, variables) in its value.
    pub names: Vec<String>,
}

/// One open bracket.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The open bracket's token.
    pub open: usize,
    /// The called name (last part of a dotted name), when `(` follows a name.
    pub callee: Option<String>,
    /// The keyword this bracket is the value of (`ZONE=_F(` and `ZONE=(`
    /// give `ZONE`; an `_F(` inside `ZONE=(…` inherits it).
    pub kw: Option<String>,
    /// Keywords written at this level.
    pub written: Vec<Written>,
    /// The keyword whose value is being written (after `=`, before `,`).
    pub pending: Option<usize>,
}

/// What the token before a position says the position is.
#[derive(Clone, Debug, PartialEq)]
pub enum Slot {
    /// Where a keyword name goes (after `(` or `,` of a call).
    Keyword,
    /// The value of a keyword (after `KW=`, or inside its tuple).
    Value { keyword: String },
    /// Anywhere else.
    Other,
}

/// The chain of catalog levels a position is in.
#[derive(Clone, Debug)]
pub struct CatalogPath {
    pub command: String,
    /// The factor keywords from the command down (`["ZONE"]`).
    pub factors: Vec<String>,
    /// For each level (command first), the frame holding its keywords.
    pub frames: Vec<usize>,
}

/// The context of one position.
#[derive(Clone, Debug)]
pub struct Context {
    pub tokens: Vec<Token>,
    pub frames: Vec<Frame>,
    pub slot: Slot,
    /// The word being typed (a name prefix or the content of a string
    /// before the position) and where it starts.
    pub prefix: String,
    pub prefix_start: usize,
    /// The position is inside a string literal.
    pub in_string: bool,
    pub path: Option<CatalogPath>,
}

fn literal(src: &str, t: &Token) -> Option<CVal> {
    match t.kind {
        Kind::Str { .. } => Some(CVal::Str(lex::str_content(src, t).to_string())),
        Kind::Number => {
            let s = t.text(src).replace('_', "");
            if let Ok(i) = s.parse::<i64>() {
                Some(CVal::Int(i))
            } else {
                s.parse::<f64>().ok().map(CVal::Real)
            }
        }
        _ => None,
    }
}

/// Reads the frames open at `offset`. Tokens at or after `offset` are not
/// read, except that a name or string the position is inside is the
/// prefix being typed.
pub fn at(src: &str, offset: usize) -> Context {
    let tokens = lex::tokens(src);
    let mut frames: Vec<Frame> = Vec::new();
    let mut prefix = String::new();
    let mut prefix_start = offset;
    let mut in_string = false;
    let mut last: Option<usize> = None;
    // Where the reading stopped, and whether at a word being typed.
    let mut stop = tokens.len();
    let mut typing = false;
    for (i, t) in tokens.iter().enumerate() {
        if t.start >= offset {
            stop = i;
            break;
        }
        if t.end >= offset && matches!(t.kind, Kind::Name) {
            prefix = src[t.start..offset].to_string();
            prefix_start = t.start;
            stop = i;
            typing = true;
            break;
        }
        if let Kind::Str { closed } = t.kind {
            let (cs, ce) = lex::str_content_range(src, t);
            if offset >= cs && (offset <= ce && (!closed || offset < t.end)) {
                in_string = true;
                prefix = src[cs..offset].to_string();
                prefix_start = cs;
                stop = i;
                typing = true;
                break;
            }
        }
        step(src, &tokens, i, &mut frames);
        last = Some(i);
    }
    let slot = slot_of(&tokens, &frames, last, in_string);
    let path = catalog_path(&frames);
    written_after(src, &tokens, stop, typing, &mut frames);
    Context {
        tokens,
        frames,
        slot,
        prefix,
        prefix_start,
        in_string,
        path,
    }
}

/// Adds to the open levels the keywords written after the position, up to
/// the end of each level (they are "already present" too: a keyword
/// written further in the same `_F(` or call is not offered again, and the
/// block conditions read it). The word being typed, and its value, are not
/// counted; nor are the keywords of calls and `_F(` opened after the
/// position (a sibling occurrence of a factor keyword is another level).
fn written_after(src: &str, tokens: &[Token], stop: usize, typing: bool, frames: &mut [Frame]) {
    if frames.is_empty() {
        return;
    }
    // The open levels are a prefix of `more`; a frame is one of them when
    // its bracket was opened before the position.
    let mut more: Vec<Frame> = frames.to_vec();
    for f in &mut more {
        f.pending = None;
    }
    let merge = |frames: &mut [Frame], k: usize, m: Frame| {
        for w in m.written {
            if !frames[k].written.iter().any(|x| x.start == w.start) {
                frames[k].written.push(w);
            }
        }
    };
    let depth = frames.len();
    let mut skipping = typing;
    let mut i = stop + usize::from(typing);
    while i < tokens.len() && !more.is_empty() {
        let t = tokens[i];
        i += 1;
        match t.kind {
            Kind::Newline => break,
            Kind::Close if more.last().is_some_and(|f| f.open < stop) => {
                // An open level ends: what it holds is final.
                let k = more.len() - 1;
                if let Some(m) = more.pop() {
                    merge(frames, k, m);
                }
                skipping = false;
                continue;
            }
            _ => {}
        }
        if skipping {
            // The rest of the item being typed, to the next comma of its level.
            match t.kind {
                Kind::Open => more.push(Frame {
                    open: i - 1,
                    callee: None,
                    kw: None,
                    written: Vec::new(),
                    pending: None,
                }),
                Kind::Close => {
                    more.pop();
                }
                Kind::Comma if more.len() == depth => skipping = false,
                _ => {}
            }
            continue;
        }
        step(src, tokens, i - 1, &mut more);
    }
    for (k, m) in more.into_iter().enumerate() {
        if m.open < stop {
            merge(frames, k, m);
        }
    }
}

/// Reads token `i` into the frame stack.
fn step(src: &str, tokens: &[Token], i: usize, frames: &mut Vec<Frame>) {
    let t = tokens[i];
    let prev = i.checked_sub(1).map(|p| tokens[p]);
    match t.kind {
        Kind::Open => {
            let callee = match prev {
                Some(p) if p.kind == Kind::Name && src.as_bytes()[t.start] == b'(' => {
                    Some(p.text(src).to_string())
                }
                _ => None,
            };
            let parent_kw = frames.last().and_then(|f| {
                f.pending
                    .map(|w| f.written[w].name.clone())
                    .or_else(|| f.callee.is_none().then(|| f.kw.clone()).flatten())
            });
            frames.push(Frame {
                open: i,
                callee,
                kw: parent_kw,
                written: Vec::new(),
                pending: None,
            });
        }
        Kind::Close => {
            frames.pop();
        }
        Kind::Comma => {
            if let Some(f) = frames.last_mut() {
                f.pending = None;
            }
        }
        Kind::Newline => frames.clear(),
        Kind::Assign => {
            let Some(f) = frames.last_mut() else { return };
            if f.callee.is_none() || f.pending.is_some() {
                return;
            }
            if let Some(p) = prev.filter(|p| p.kind == Kind::Name) {
                f.written.push(Written {
                    name: p.text(src).to_string(),
                    start: p.start,
                    end: p.end,
                    values: Vec::new(),
                    names: Vec::new(),
                });
                f.pending = Some(f.written.len() - 1);
            }
        }
        _ => {
            // A value of the keyword pending in this frame, or in the
            // frame of the tuple this one is (`GROUP_MA=('A', 'B')`).
            let n = frames.len();
            let target = match frames.last() {
                Some(f) if f.pending.is_some() => Some(n - 1),
                Some(f) if f.callee.is_none() && n >= 2 && frames[n - 2].pending.is_some() => {
                    Some(n - 2)
                }
                _ => None,
            };
            let Some(fi) = target else { return };
            let f = &mut frames[fi];
            let Some(w) = f.pending else { return };
            let after_dot = prev.is_some_and(|p| p.kind == Kind::Dot);
            let w = &mut f.written[w];
            if let Some(v) = literal(src, &t) {
                w.values.push(v);
            } else if t.kind == Kind::Name && !after_dot {
                w.names.push(t.text(src).to_string());
            }
        }
    }
}

fn slot_of(tokens: &[Token], frames: &[Frame], last: Option<usize>, in_string: bool) -> Slot {
    let Some(f) = frames.last() else {
        return Slot::Other;
    };
    let value = |frame: &Frame| {
        frame.pending.map(|w| Slot::Value {
            keyword: frame.written[w].name.clone(),
        })
    };
    if let Some(v) = value(f) {
        return v;
    }
    // Inside a tuple that is a keyword's value.
    if f.callee.is_none() {
        if let Some(kw) = &f.kw {
            let n = frames.len();
            if n >= 2 && frames[n - 2].pending.is_some() {
                return Slot::Value {
                    keyword: kw.clone(),
                };
            }
        }
        return Slot::Other;
    }
    if in_string {
        return Slot::Other;
    }
    match last.map(|l| tokens[l].kind) {
        Some(Kind::Open) | Some(Kind::Comma) => Slot::Keyword,
        _ => Slot::Other,
    }
}

/// The innermost command call and the factor keywords down to the
/// position, when every frame between is a `_F(` or a tuple.
fn catalog_path(frames: &[Frame]) -> Option<CatalogPath> {
    let cat = catalog();
    let mut factors = Vec::new();
    let mut levels = Vec::new();
    for (i, f) in frames.iter().enumerate().rev() {
        match f.callee.as_deref() {
            Some("_F") => {
                factors.push(f.kw.clone()?);
                levels.push(i);
            }
            Some(name) if cat.command(name).is_some() => {
                levels.push(i);
                factors.reverse();
                levels.reverse();
                return Some(CatalogPath {
                    command: name.to_string(),
                    factors,
                    frames: levels,
                });
            }
            Some(_) => return None,
            None => {}
        }
    }
    None
}

/// What is valid at one catalog level given what is written: its entries
/// (direct keywords and those of the open blocks) and the rules of the
/// level and of those blocks.
pub struct Level<'c> {
    pub entries: Vec<&'c Entry>,
    pub rules: Vec<&'c Rule>,
}

impl Level<'_> {
    /// Whether a rule of the level forbids writing `name` next to the
    /// keywords already `written`: `UN_PARMI`/`EXCLUS` once one of their
    /// keywords is written, `PRESENT_ABSENT` (the first excludes the
    /// others, any other the first).
    pub fn excluded(&self, name: &str, written: &[String]) -> bool {
        let w = |k: &&str| *k != name && written.iter().any(|x| x == k);
        self.rules.iter().any(|r| {
            let mine = r.args.contains(&name);
            match r.kind {
                RuleKind::ExactlyOne | RuleKind::AtMostOne => mine && r.args.iter().any(w),
                RuleKind::OnlyFirstPresent => match r.args.split_first() {
                    Some((first, others)) if *first == name => others.iter().any(w),
                    Some((first, _)) => mine && w(first),
                    None => false,
                },
                _ => false,
            }
        })
    }
}

/// The entries valid at the level a path ends in: at each level down, the
/// factor keyword of the path is taken among the entries valid there (a
/// factor such as `DEFI_CONTACT/ZONE` has one definition per block).
/// `None` when a factor keyword of the path is not valid.
pub fn level_active<'c>(
    cmd: &'c Command,
    factors: &[String],
    env: &mut Env<'_>,
) -> Option<Level<'c>> {
    let mut entries: &[Entry] = cmd.keywords;
    let mut rules: &[Rule] = cmd.rules;
    for f in factors {
        let mut act = Vec::new();
        active(entries, env, &mut act, &mut Vec::new());
        match &act.iter().find(|e| e.name == f)?.node {
            Node::Factor(fk) => {
                entries = fk.keywords;
                rules = fk.rules;
            }
            _ => return None,
        }
    }
    let mut level = Level {
        entries: Vec::new(),
        rules: rules.iter().collect(),
    };
    active(entries, env, &mut level.entries, &mut level.rules);
    Some(level)
}

/// Keyword values as block conditions read them: what is written (this
/// level first, then the enclosing ones), else the defaults.
pub struct Env<'a> {
    values: HashMap<String, CVal>,
    types: HashMap<String, String>,
    concept_type: &'a dyn Fn(&str) -> Option<String>,
}

impl CondEnv for Env<'_> {
    fn value(&self, keyword: &str) -> Option<&CVal> {
        self.values.get(keyword)
    }
    fn type_of(&self, keyword: &str) -> Option<&str> {
        self.types.get(keyword).map(String::as_str)
    }
}

impl<'a> Env<'a> {
    /// The environment of the innermost level of `ctx`'s path.
    pub fn new(ctx: &Context, concept_type: &'a dyn Fn(&str) -> Option<String>) -> Env<'a> {
        let mut env = Env {
            values: HashMap::new(),
            types: HashMap::new(),
            concept_type,
        };
        if let Some(path) = &ctx.path {
            for &fi in &path.frames {
                for w in &ctx.frames[fi].written {
                    env.insert(w);
                }
            }
        }
        env
    }

    fn insert(&mut self, w: &Written) {
        let v = match (w.values.as_slice(), w.names.first()) {
            ([one], _) => one.clone(),
            ([], Some(n)) => CVal::Str(n.clone()),
            ([], None) => CVal::None,
            (many, _) => CVal::Tuple(many.to_vec()),
        };
        if let Some(t) = w.names.first().and_then(|n| (self.concept_type)(n)) {
            self.types.insert(w.name.clone(), t);
        }
        self.values.insert(w.name.clone(), v);
    }
}

/// The entries valid at a level given `env`: its direct keywords, and
/// those of the blocks whose condition holds (or cannot be decided yet:
/// completion offers rather than hides), with the rules of those blocks.
/// Defaults of the open keywords become visible to the blocks after them,
/// as in the validator.
pub fn active<'c>(
    entries: &'c [Entry],
    env: &mut Env<'_>,
    out: &mut Vec<&'c Entry>,
    rules: &mut Vec<&'c Rule>,
) {
    for e in entries {
        match &e.node {
            Node::Block(_) => {}
            Node::Simple(s) => {
                if !out.iter().any(|a| a.name == e.name) {
                    out.push(e);
                }
                default_into(env, e.name, s);
            }
            Node::Factor(_) => {
                if !out.iter().any(|a| a.name == e.name) {
                    out.push(e);
                }
            }
        }
    }
    for e in entries {
        if let Node::Block(b) = &e.node {
            let open = match b.cond().as_ref() {
                Ok(c) => aster_catalog::cond::holds(c, env).unwrap_or(true),
                Err(_) => true,
            };
            if open {
                rules.extend(b.rules.iter());
                active(b.keywords, env, out, rules);
            }
        }
    }
}

fn default_into(env: &mut Env<'_>, name: &str, s: &SimpleKw) {
    if !env.values.contains_key(name) {
        if let Some(d) = s.default_cval() {
            env.values.insert(name.to_string(), d.clone());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_a_factor_keyword_of_a_tuple() {
        let src = "C = DEFI_CONTACT(MODELE=MO, FORMULATION='CONTINUE',\n  ZONE=(_F(GROUP_MA_MAIT='A'), _F(";
        let ctx = at(src, src.len());
        let path = ctx.path.expect("a catalog path");
        assert_eq!(path.command, "DEFI_CONTACT");
        assert_eq!(path.factors, vec!["ZONE".to_string()]);
        assert_eq!(ctx.slot, Slot::Keyword);
        let top = &ctx.frames[path.frames[0]];
        assert_eq!(top.written[1].name, "FORMULATION");
        assert_eq!(top.written[1].values, vec![CVal::Str("CONTINUE".into())]);
    }

    #[test]
    fn keywords_written_after_the_position_count_to_the_end_of_each_level() {
        let src = "C = DEFI_CONTACT(MODELE=MO,\n  ZONE=(_F(GROUP_MA_MAIT='A', ), _F(GROUP_MA_ESCL='B')),\n  FORMULATION='CONTINUE')\nX = 1\n";
        // Before GROUP_MA_MAIT, in the first ZONE occurrence.
        let at_kw = src.find("GROUP_MA_MAIT").unwrap();
        let ctx = at(src, at_kw);
        let path = ctx.path.clone().expect("a catalog path");
        let names = |fi: usize| -> Vec<String> {
            ctx.frames[fi]
                .written
                .iter()
                .map(|w| w.name.clone())
                .collect()
        };
        // The occurrence holds GROUP_MA_MAIT, not its sibling's GROUP_MA_ESCL.
        assert_eq!(names(path.frames[1]), vec!["GROUP_MA_MAIT".to_string()]);
        // The command level sees FORMULATION, written after the factor.
        assert_eq!(names(path.frames[0]), vec!["MODELE", "ZONE", "FORMULATION"]);
        let top = &ctx.frames[path.frames[0]];
        assert_eq!(top.written[2].values, vec![CVal::Str("CONTINUE".into())]);
        // Typing a keyword: the word being typed is not counted.
        let ctx = at(src, at_kw + 5);
        assert_eq!(ctx.prefix, "GROUP");
        let path = ctx.path.clone().unwrap();
        assert!(ctx.frames[path.frames[1]].written.is_empty());
        // Typing a string value: the keyword it is the value of is written
        // before the position; nothing after it in the occurrence.
        let ctx = at(src, src.find("'A'").unwrap() + 1);
        assert!(ctx.in_string);
        let path = ctx.path.unwrap();
        assert_eq!(ctx.frames[path.frames[1]].written.len(), 1);
    }

    #[test]
    fn value_slots_and_prefixes() {
        let src = "M = AFFE_MODELE(AFFE=_F(PHENOMENE='MECA";
        let ctx = at(src, src.len());
        assert!(ctx.in_string);
        assert_eq!(ctx.prefix, "MECA");
        assert_eq!(
            ctx.slot,
            Slot::Value {
                keyword: "PHENOMENE".into()
            }
        );
        let src = "M = AFFE_MODELE(MAIL";
        let ctx = at(src, src.len());
        assert_eq!(ctx.prefix, "MAIL");
        assert_eq!(ctx.slot, Slot::Keyword);
    }
}
