//! A command call in the program: keywords validated against the catalog,
//! the result concept typed, the call handed to the sink, and the special
//! commands (`FORMULE`, `DETRUIRE`, `FIN`, `CO`) handled.

use crate::command::*;
use crate::diag::{DiagKind, Diagnostic};
use crate::interp::{
    exec_diag, from_scalar, new_formula, py_err, unsupported, CallArg, Halt, Interp, R,
};
use crate::validate::{Given, Validator};
use crate::value::Value;
use aster_catalog::cond::CVal;
use aster_catalog::{catalog, types, Produces, Reentrant};
use aster_syntax::Span;
use std::rc::Rc;

fn kw_cval(k: &Keywords, name: &str) -> Option<CVal> {
    let conv = |s: &Scalar| match s {
        Scalar::Int(i) => CVal::Int(*i),
        Scalar::Real(r) => CVal::Real(*r),
        Scalar::Str(s) => CVal::Str(s.clone()),
        Scalar::Concept(c) => CVal::Str(c.name.clone()),
        Scalar::Complex(..) | Scalar::Opaque(_) => CVal::None,
    };
    match k.get(name)? {
        KwValue::Simple(v) if v.len() == 1 => Some(conv(&v[0])),
        KwValue::Simple(v) => Some(CVal::Tuple(v.iter().map(conv).collect())),
        KwValue::Factor(_) => Some(CVal::Bool(true)),
    }
}

pub(crate) fn call_command(
    me: &mut Interp,
    name: &str,
    args: Vec<CallArg>,
    span: Span,
    target: Option<&str>,
) -> R<Value> {
    // A code_aster 11 command replaced by another (`MODE_ITER_SIMULT` →
    // `CALC_MODES`...): its keywords are translated below.
    let replaced = if me.legacy {
        crate::legacy_commands::replacement(name)
    } else {
        None
    };
    let Some(mut cmd) = catalog().command(replaced.unwrap_or(name)).or_else(|| {
        // code_aster 17: `POURSUITE(...)` is `DEBUT(MODE='POURSUITE', ...)`.
        (name == "POURSUITE")
            .then(|| catalog().command("DEBUT"))
            .flatten()
    }) else {
        return err_unknown(name, span);
    };
    if name == "INCLUDE" {
        // What the included file defines is not known (`recover`).
        me.recovery.names_unknown = true;
        return unsupported(span, "INCLUDE (reading another command file)");
    }
    let mut given = Vec::with_capacity(args.len());
    let mut reuse: Option<(Value, Span)> = None;
    let mut formula_context = Vec::new();
    for a in args {
        let Some((kw, _)) = a.name else {
            return py_err(
                a.span,
                format!("{name}: commands take keyword arguments only (KEYWORD=value)"),
            );
        };
        if kw == "reuse" {
            reuse = Some((a.value, a.span));
            continue;
        }
        if name == "FORMULE" && !matches!(kw.as_str(), "VALE" | "VALE_C" | "NOM_PARA") {
            // Extra FORMULE arguments are names the expression may use.
            formula_context.push((kw, a.value));
            continue;
        }
        given.push(Given {
            name: kw,
            span: a.span,
            value: a.value,
        });
    }

    let mut early = Vec::new();
    let old_name = name;
    let replaced = replaced.or_else(|| {
        me.legacy
            .then(|| crate::legacy_commands::replacement_by_keywords(name, &given))
            .flatten()
    });
    let name = match replaced {
        Some(new) => {
            if let Some(c) = catalog().command(new) {
                cmd = c;
            }
            crate::legacy_commands::translate(old_name, span, &mut given, &mut early)
                .unwrap_or(old_name)
        }
        None => name,
    };
    let mut v = Validator {
        reuse_given: reuse.is_some(),
        command: name.to_string(),
        diags: early,
        created: Vec::new(),
        next_id: &mut me.next_id,
        legacy: me.legacy,
        synthesized: Vec::new(),
    };
    let cmd = match crate::legacy::legacy_command(name, &given) {
        Some((legacy, why)) => {
            v.diags
                .push(Diagnostic::warning(DiagKind::Legacy, span, why));
            legacy
        }
        None => cmd,
    };
    // The static pass of `aster run` validated this call already when its
    // inputs are the same (`memo`).
    let key = me.memo.as_ref().and_then(|_| {
        crate::memo::Key::new(cmd, &given, span, *v.next_id, v.legacy, v.reuse_given)
    });
    let known = match (&key, me.memo.as_mut()) {
        (Some(k), Some(m)) => m.get(k),
        (None, Some(m)) => {
            m.unkeyed();
            None
        }
        _ => None,
    };
    let (keywords, mut diags, created, synthesized) = match known {
        Some(done) => {
            *v.next_id = done.next_id;
            let mut diags = v.diags;
            diags.extend(done.diags);
            (done.keywords, diags, done.created, done.synthesized)
        }
        None => {
            let early = v.diags.len();
            let keywords = v.validate(cmd, given, span);
            if let (Some(k), Some(m)) = (key, me.memo.as_mut().filter(|m| m.records())) {
                m.put(
                    k,
                    crate::memo::Validated {
                        keywords: keywords.clone(),
                        diags: v.diags[early..].to_vec(),
                        created: v.created.clone(),
                        synthesized: v.synthesized.clone(),
                        next_id: *v.next_id,
                    },
                );
            }
            (keywords, v.diags, v.created, v.synthesized)
        }
    };

    // reuse=
    let mut reused: Option<ConceptRef> = None;
    if let Some((rv, rspan)) = &reuse {
        match (rv, &cmd.reentrant) {
            (_, Reentrant::No) => diags.push(Diagnostic::error(
                DiagKind::Reuse,
                *rspan,
                format!("{name} does not accept reuse=: it always creates a new concept"),
            )),
            (Value::Concept(c), _) | (Value::Formula(c, _), _) => reused = Some(c.clone()),
            (Value::Unknown, _) => {}
            (other, _) => diags.push(Diagnostic::error(
                DiagKind::Reuse,
                *rspan,
                format!("reuse= expects a concept, found {}", other.repr()),
            )),
        }
    } else if let Reentrant::Yes {
        mandatory: true,
        keywords: kws,
    } = &cmd.reentrant
    {
        // code_aster 17 modifies the concept in place anyway.
        diags.push(Diagnostic::warning(
            DiagKind::Reuse,
            span,
            format!(
                "{name} modifies the concept given under {} in place: write reuse=",
                kws.join(" or ")
            ),
        ));
    }

    let has_error = diags.iter().any(|d| d.is_error());
    me.diags.extend(diags);
    if has_error && !me.keep_going {
        return Err(Halt::Reported);
    }

    // Concepts the legacy layer added (constant functions, time lists):
    // defined first.
    if !has_error {
        for s in synthesized {
            define_synthesized(me, s)?;
        }
    }

    // The result concept.
    let actual = types::actual_result(name, &|k: &str| keywords.concept(k).map(|c| c.typ.clone()));
    let typ = match &cmd.produces {
        _ if actual.is_some() => actual,
        Produces::Nothing => None,
        Produces::Type(t) => Some(t.to_string()),
        Produces::Computed(f) => {
            let value = |k: &str| kw_cval(&keywords, k);
            let type_of = |k: &str| keywords.concept(k).map(|c| c.typ.clone());
            let t = types::computed(f, &value, &type_of);
            match (&reused, t.as_str()) {
                (Some(r), types::UNKNOWN) => Some(r.typ.clone()),
                _ => Some(t),
            }
        }
    };
    let result = typ.map(|typ| match &reused {
        Some(r) => ConceptRef {
            name: target.map(str::to_string).unwrap_or_else(|| r.name.clone()),
            id: r.id,
            typ,
        },
        None => {
            let id = me.next_id;
            me.next_id += 1;
            ConceptRef {
                name: target
                    .map(str::to_string)
                    .unwrap_or_else(|| format!("_{name}_{id}")),
                id,
                typ,
            }
        }
    });

    let formula = if name == "FORMULE" {
        let params: Vec<String> = keywords
            .simple("NOM_PARA")
            .iter()
            .filter_map(|s| s.as_str().map(str::to_string))
            .collect();
        let src = keywords
            .str("VALE")
            .or(keywords.str("VALE_C"))
            .unwrap_or("");
        match new_formula(me, params, src, formula_context, span) {
            Ok(f) => Some(Rc::new(f)),
            Err(Halt::Diag(d)) if me.keep_going => {
                me.diags.push(*d);
                None
            }
            Err(e) => return Err(e),
        }
    } else {
        None
    };

    let call = CommandCall {
        command: name.to_string(),
        result: result.clone(),
        reuse: reused,
        keywords,
        span,
    };

    let output = if has_error {
        CommandOutput::Concept
    } else {
        me.commands += 1;
        match me.sink.execute(&call) {
            Ok(o) => o,
            Err(e) => return Err(exec_diag(span, e).into()),
        }
    };

    // Concepts created by the macro through CO('name').
    for c in created {
        me.set_var(&c.name.clone(), Value::Concept(c.clone()));
        me.resolve_co(&c);
    }
    if name == "DETRUIRE" {
        destroy(me, &call.keywords);
    }
    if name == "FIN" {
        me.finished = true;
    }
    let restart = name == "POURSUITE"
        || (name == "DEBUT"
            && matches!(call.keywords.get("MODE"), Some(KwValue::Simple(v))
                if matches!(v.as_slice(), [Scalar::Str(m)] if m == "POURSUITE")));
    if restart {
        if me.study.several_files {
            me.restore_context();
        } else {
            me.continued = true;
        }
    }

    Ok(match (output, result, formula) {
        (_, Some(c), Some(f)) => {
            if !has_error {
                me.sink.formula(&c, &f);
            }
            Value::Formula(c, f)
        }
        (CommandOutput::Value(s), _, _) => from_scalar(s),
        // `EXTR_TABLE(TYPE_RESU='ENTIER'|'REEL')` gives a plain number
        // (code_aster's AsInteger/AsFloat): known when the commands run.
        (CommandOutput::Concept, Some(c), None) if matches!(c.typ.as_str(), "entier" | "reel") => {
            Value::Unknown
        }
        (_, Some(c), None) => Value::Concept(c),
        (_, None, _) => Value::None,
    })
}

/// A command the legacy layer added (see `Validator::synthesized`), handed
/// to the sink like a command of the file.
fn define_synthesized(me: &mut Interp, s: crate::validate::Synthesized) -> R<()> {
    let Some(cmd) = catalog().command(s.command) else {
        return Ok(());
    };
    let mut v = Validator {
        reuse_given: false,
        command: cmd.name.to_string(),
        diags: Vec::new(),
        created: Vec::new(),
        next_id: &mut me.next_id,
        legacy: false,
        synthesized: Vec::new(),
    };
    let keywords = v.validate(cmd, s.keywords, s.span);
    let call = CommandCall {
        command: cmd.name.to_string(),
        result: Some(s.result),
        reuse: None,
        keywords,
        span: s.span,
    };
    me.commands += 1;
    me.sink
        .execute(&call)
        .map_err(|e| Halt::from(exec_diag(s.span, e)))?;
    Ok(())
}

fn destroy(me: &mut Interp, k: &Keywords) {
    let mut ids = Vec::new();
    fn collect(k: &Keywords, ids: &mut Vec<u32>) {
        for e in &k.entries {
            match &e.value {
                KwValue::Simple(v) => {
                    ids.extend(v.iter().filter_map(|s| s.as_concept().map(|c| c.id)))
                }
                KwValue::Factor(occ) => occ.iter().for_each(|o| collect(o, ids)),
            }
        }
    }
    collect(k, &mut ids);
    me.globals.retain(|_, v| match v {
        Value::Concept(c) | Value::Formula(c, _) => !ids.contains(&c.id),
        _ => true,
    });
}

fn err_unknown<T>(name: &str, span: Span) -> R<T> {
    Err(Diagnostic::error(
        DiagKind::UnknownCommand,
        span,
        format!("`{name}` is not a code_aster 17 command"),
    )
    .into())
}

#[cfg(test)]
mod tests {
    //! Command calls built from values (no parser needed).
    use super::*;
    use crate::value::Dict;
    use crate::CheckSink;
    use aster_syntax::CodeMap;
    use std::cell::RefCell;

    fn kw(name: &str, value: Value) -> CallArg {
        CallArg {
            name: Some((name.to_string(), Span::default())),
            value,
            span: Span::default(),
        }
    }

    fn f(entries: Vec<(&str, Value)>) -> Value {
        let mut d = Dict::default();
        for (k, v) in entries {
            d.insert(Value::str(k), v, Span::default());
        }
        Value::Dict(Rc::new(RefCell::new(d)))
    }

    fn s(x: &str) -> Value {
        Value::str(x)
    }

    fn call(me: &mut Interp, cmd: &str, args: Vec<CallArg>, target: &str) -> R<Value> {
        call_command(me, cmd, args, Span::default(), Some(target))
    }

    #[test]
    fn typed_results_and_concept_checks() {
        let map = CodeMap::new("t", "");
        let mut sink = CheckSink {
            calls: Vec::new(),
            record: true,
        };
        let mut me = Interp::new(&map, &mut sink, true);
        let ma = call(&mut me, "LIRE_MAILLAGE", vec![kw("FORMAT", s("MED"))], "MA")
            .ok()
            .unwrap();
        let Value::Concept(c) = &ma else { panic!() };
        assert_eq!(c.typ, "maillage_sdaster");
        let mo = call(
            &mut me,
            "AFFE_MODELE",
            vec![
                kw("MAILLAGE", ma.clone()),
                kw(
                    "AFFE",
                    f(vec![
                        ("TOUT", s("OUI")),
                        ("PHENOMENE", s("MECANIQUE")),
                        ("MODELISATION", s("D_PLAN")),
                    ]),
                ),
            ],
            "MO",
        )
        .ok()
        .unwrap();
        assert!(me.diags.is_empty(), "{:?}", me.diags);
        let cine = call(
            &mut me,
            "AFFE_CHAR_CINE",
            vec![
                kw("MODELE", mo.clone()),
                kw(
                    "MECA_IMPO",
                    f(vec![("GROUP_NO", s("A")), ("DX", Value::Int(0))]),
                ),
            ],
            "BLOC",
        )
        .ok()
        .unwrap();
        let Value::Concept(cc) = &cine else { panic!() };
        assert_eq!(cc.typ, "char_cine_meca");
        // DX=0 (an int) became a real, as the keyword is typed R.
        let _ = call(
            &mut me,
            "CALC_VECT_ELEM",
            vec![kw("OPTION", s("CHAR_MECA")), kw("CHARGE", cine)],
            "VE",
        );
        let wrong: Vec<_> = me
            .diags
            .iter()
            .filter(|d| d.kind == DiagKind::WrongType)
            .collect();
        assert_eq!(wrong.len(), 1, "{:?}", me.diags);
        assert!(
            wrong[0].message.contains("char_cine_meca"),
            "{}",
            wrong[0].message
        );
        drop(me);
        let dx = sink.calls[2].keywords.factor("MECA_IMPO")[0]
            .first("DX")
            .cloned();
        assert_eq!(dx, Some(Scalar::Real(0.0)));
    }

    #[test]
    fn crea_champ_type_follows_type_cham() {
        let map = CodeMap::new("t", "");
        let mut sink = CheckSink::default();
        let mut me = Interp::new(&map, &mut sink, true);
        let ma = call(&mut me, "LIRE_MAILLAGE", vec![], "MA").ok().unwrap();
        let ch = call(
            &mut me,
            "CREA_CHAMP",
            vec![
                kw("TYPE_CHAM", s("NOEU_DEPL_R")),
                kw("OPERATION", s("AFFE")),
                kw("MAILLAGE", ma),
                kw(
                    "AFFE",
                    f(vec![
                        ("TOUT", s("OUI")),
                        ("NOM_CMP", s("DX")),
                        ("VALE", Value::Float(0.0)),
                    ]),
                ),
            ],
            "CH",
        )
        .ok()
        .unwrap();
        let Value::Concept(c) = ch else { panic!() };
        assert_eq!(c.typ, "cham_no_sdaster", "{:?}", me.diags);
    }

    #[test]
    fn unknown_keyword_suggests_and_names_the_path() {
        let map = CodeMap::new("t", "");
        let mut sink = CheckSink::default();
        let mut me = Interp::new(&map, &mut sink, true);
        let _ = call(
            &mut me,
            "DEFI_MATERIAU",
            vec![kw(
                "ELAS",
                Value::tuple(vec![f(vec![
                    ("E", Value::Float(1.0)),
                    ("NUE", Value::Float(0.3)),
                ])]),
            )],
            "M",
        );
        let d = &me.diags[0];
        assert_eq!(d.kind, DiagKind::UnknownKeyword);
        assert!(d.message.contains("DEFI_MATERIAU/ELAS[1]"), "{}", d.message);
        assert!(d.notes.iter().any(|n| n.contains("`NU`")), "{:?}", d.notes);
    }
}
