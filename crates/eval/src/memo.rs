//! Validation done once: `aster run` evaluates a program twice — the static
//! pass (`preflight`, every call checked before anything runs) and the run
//! itself — and validating a call against the catalog (blocks, defaults,
//! rules) is most of an evaluation's cost. The first pass records each
//! validation's outcome; the second reuses it when the call is the same
//! one with the same inputs.
//!
//! Validation is a function of the command, the keywords as written (names,
//! values, positions), the call's position, the next concept id (`CO()`
//! and legacy-synthesised concepts take ids), the dialect and whether
//! `reuse=` was written: all of them are the key (the values through a
//! 64-bit hash of their whole structure, beside the call's position and
//! the id, so that two different inputs would have to collide at the same
//! call site and id). A call whose inputs hold a value that cannot be
//! compared across passes (a function, a module, a value known only at run
//! time) is validated afresh; so is any call the first pass did not see the
//! same (a loop that took another turn). A hit gives exactly what
//! validating again would.

use crate::command::{ConceptRef, Keywords};
use crate::diag::Diagnostic;
use crate::validate::{Given, Synthesized};
use crate::value::Value;
use aster_syntax::Span;
use std::collections::HashMap;
use std::hash::{Hash, Hasher};

/// What one validation gave.
#[derive(Clone, Debug)]
pub(crate) struct Validated {
    pub keywords: Keywords,
    /// The diagnostics validation added (after those of the legacy layer).
    pub diags: Vec<Diagnostic>,
    pub created: Vec<ConceptRef>,
    pub synthesized: Vec<Synthesized>,
    /// The next concept id after validation.
    pub next_id: u32,
}

/// The key of one validation (see the module's doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Key {
    span: Span,
    next_id: u32,
    inputs: u64,
}

impl Key {
    /// The key of validating `command`'s `given` keywords at `span`, or
    /// `None` when a value cannot be compared across passes.
    pub fn new(
        command: &aster_catalog::Command,
        given: &[Given],
        span: Span,
        next_id: u32,
        legacy: bool,
        reuse_given: bool,
    ) -> Option<Key> {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        // The definition itself (a legacy variant may share its name).
        (command as *const aster_catalog::Command as usize).hash(&mut h);
        legacy.hash(&mut h);
        reuse_given.hash(&mut h);
        given.len().hash(&mut h);
        for g in given {
            g.name.hash(&mut h);
            g.span.hash(&mut h);
            if !hash_value(&g.value, &mut h, 0) {
                return None;
            }
        }
        Some(Key {
            span,
            next_id,
            inputs: h.finish(),
        })
    }
}

/// Values nested deeper than this are not keyed (validated afresh).
const MAX_DEPTH: usize = 32;

/// Hashes a value's whole structure; false for a value that is not plain
/// data or not the same in both passes.
fn hash_value(v: &Value, h: &mut impl Hasher, depth: usize) -> bool {
    if depth > MAX_DEPTH {
        return false;
    }
    std::mem::discriminant(v).hash(h);
    match v {
        Value::None => true,
        Value::Bool(b) => {
            b.hash(h);
            true
        }
        Value::Int(i) => {
            i.hash(h);
            true
        }
        Value::Big(b) => {
            b.hash(h);
            true
        }
        Value::Float(f) => {
            f.to_bits().hash(h);
            true
        }
        Value::Complex(re, im) => {
            re.to_bits().hash(h);
            im.to_bits().hash(h);
            true
        }
        Value::Str(s) | Value::Command(s) | Value::Co(s) => {
            s.hash(h);
            true
        }
        Value::List(items) => hash_items(&items.borrow(), h, depth),
        Value::Tuple(items) => hash_items(items, h, depth),
        Value::Dict(d) => {
            let d = d.borrow();
            d.entries.len().hash(h);
            d.entries.iter().all(|e| {
                e.span.hash(h);
                hash_value(&e.key, h, depth + 1) && hash_value(&e.value, h, depth + 1)
            })
        }
        Value::Concept(c) | Value::Formula(c, _) => {
            c.name.hash(h);
            c.id.hash(h);
            c.typ.hash(h);
            true
        }
        Value::Func(_)
        | Value::Builtin(_)
        | Value::Method(..)
        | Value::Module(_)
        | Value::Unknown
        | Value::Raised(_)
        | Value::Table(_)
        | Value::Column(_) => false,
    }
}

fn hash_items(items: &[Value], h: &mut impl Hasher, depth: usize) -> bool {
    items.len().hash(h);
    items.iter().all(|v| hash_value(v, h, depth + 1))
}

/// The validations of a first pass, for a second to reuse.
#[derive(Debug, Default)]
pub struct ValidationMemo {
    entries: HashMap<Key, Validated>,
    /// Record (first pass) or reuse (second pass).
    recording: bool,
    /// Validations reused (for tests and measurements).
    pub hits: usize,
    /// Validations done afresh by the second pass.
    pub misses: usize,
}

impl ValidationMemo {
    /// A memo the next pass fills.
    pub fn recording() -> ValidationMemo {
        ValidationMemo {
            recording: true,
            ..ValidationMemo::default()
        }
    }

    /// From now on the memo is only read.
    pub fn freeze(&mut self) {
        self.recording = false;
    }

    pub(crate) fn get(&mut self, key: &Key) -> Option<Validated> {
        if self.recording {
            return None;
        }
        match self.entries.remove(key) {
            Some(v) => {
                self.hits += 1;
                Some(v)
            }
            None => {
                self.misses += 1;
                None
            }
        }
    }

    /// A call whose inputs cannot be keyed was validated afresh.
    pub(crate) fn unkeyed(&mut self) {
        if !self.recording {
            self.misses += 1;
        }
    }

    /// The memo records (the first pass).
    pub(crate) fn records(&self) -> bool {
        self.recording
    }

    pub(crate) fn put(&mut self, key: Key, v: Validated) {
        if self.recording {
            self.entries.insert(key, v);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{run_study_memo, CheckSink, RunOptions, Study, ValidationMemo};
    use aster_syntax::CodeMap;

    /// Runs `src` twice as `aster run` does (a recording pass, then a pass
    /// reading the memo); returns both passes' calls and the memo.
    fn twice(src: &str) -> (CheckSink, CheckSink, ValidationMemo) {
        let map = CodeMap::new("t.comm", src);
        let module = aster_syntax::parse_module(map.source()).expect("parses");
        let study = Study {
            files: vec![&module],
            modules: Vec::new(),
            declared: false,
        };
        let mut memo = ValidationMemo::recording();
        let mut first = CheckSink {
            calls: Vec::new(),
            record: true,
        };
        let opts = RunOptions { keep_going: true };
        let _ = run_study_memo(&map, &study, &mut first, opts, Some(&mut memo));
        memo.freeze();
        let mut second = CheckSink {
            calls: Vec::new(),
            record: true,
        };
        let _ = run_study_memo(&map, &study, &mut second, opts, Some(&mut memo));
        (first, second, memo)
    }

    #[test]
    fn the_second_pass_reuses_every_validation_and_gets_the_same_calls() {
        let src = "\
DEBUT()
MA = LIRE_MAILLAGE(FORMAT='MED')
MAT = [None] * 3
for i in range(3):
    MAT[i] = DEFI_MATERIAU(ELAS=_F(E=2.0e11 * (i + 1), NU=0.3))
L = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=4))
FIN()
";
        let (first, second, memo) = twice(src);
        assert_eq!(first.calls.len(), 7);
        assert_eq!(first.calls, second.calls);
        assert_eq!((memo.hits, memo.misses), (7, 0));
    }

    #[test]
    fn a_value_known_only_at_run_time_is_validated_again() {
        // A user function as a keyword value is not keyed: validated
        // afresh, with the same outcome.
        let src = "\
def f(x):
    return x
MA = LIRE_MAILLAGE(FORMAT='MED')
MAT = DEFI_MATERIAU(ELAS=_F(E=f, NU=0.3))
";
        let (first, second, memo) = twice(src);
        assert_eq!(first.calls, second.calls);
        assert_eq!(memo.misses, 1);
        assert_eq!(memo.hits, 1);
    }
}
