//! Syntax errors: turning pest's failure (the furthest position reached and
//! the rules it tried there) into a message that says what was expected and
//! what was found, and rendering it as `file:line:col: message` with the
//! source line and a caret.

use crate::codemap::{CodeMap, Span};
use crate::parser::Rule;
use crate::ParseError;
use pest::error::{ErrorVariant, InputLocation};
use std::collections::BTreeSet;

/// Convert a pest error into a [`ParseError`] at the same position.
pub fn from_pest(e: &pest::error::Error<Rule>, source: &str) -> ParseError {
    let pos = match e.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    };
    let message = match &e.variant {
        ErrorVariant::ParsingError { positives, .. } => expected_message(positives, source, pos),
        ErrorVariant::CustomError { message } => message.clone(),
    };
    ParseError {
        span: Span::new(pos, (pos + char_len_at(source, pos)).min(source.len())),
        message,
    }
}

fn char_len_at(source: &str, pos: usize) -> usize {
    source
        .get(pos..)
        .and_then(|s| s.chars().next())
        .map(|c| c.len_utf8())
        .unwrap_or(0)
}

/// What the token at `pos` is, for "found …".
pub fn found_at(source: &str, pos: usize) -> String {
    let rest = source.get(pos..).unwrap_or("");
    match rest.chars().next() {
        None => "end of file".into(),
        Some('\n' | '\r') => "end of line".into(),
        Some(c) if c.is_alphanumeric() || c == '_' => {
            let word: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '.')
                .take(30)
                .collect();
            format!("`{word}`")
        }
        Some(' ' | '\t') => "indentation".into(),
        Some(c) => format!("`{c}`"),
    }
}

/// A human name for a rule pest expected.
fn describe(rule: Rule) -> Option<&'static str> {
    use Rule::*;
    Some(match rule {
        test | test_nocond | or_expr | testlist_star | exprlist | primary | star_expr
        | comp_body | yield_expr | lambdef | lambdef_nocond | namedexpr | paren | list | brace
        | string | string_body | number | name | none | true_ | false_ | ellipsis | backquote
        | subscript_list | slice | slice_bound | dict_body | set_body | dict_item | comp_arg
        | kwarg | kwarg_name | star_arg | dstar_arg | arglist | neg | pos | invert | not => {
            "an expression"
        }
        target_list | target | star_target => "an assignment target",
        pow | mul | matmul | floordiv | div | modulo | add | sub | lshift | rshift | bitand
        | bitxor | bitor | le | ge | ne_py2 | lt | gt | eq | ne | not_in | in_ | is_not | is_
        | and | or | ternary => "an operator",
        call => "`(`",
        subscript => "`[`",
        attribute => "`.`",
        comma => "`,`",
        assign_rhs => "`=`",
        augassign | aug_op => "an augmented assignment",
        annassign => "`:`",
        comp_for => "`for`",
        comp_if => "`if`",
        block => "an indented block",
        simple_stmts | pass_stmt | break_stmt | continue_stmt | return_stmt | import_stmt
        | from_stmt | global_stmt | nonlocal_stmt | del_stmt | assert_stmt | raise_stmt
        | print_stmt | exec_stmt | expr_stmt | if_stmt | for_stmt | while_stmt | def_stmt
        | class_stmt | try_stmt | with_stmt | decorated | decorator => "a statement",
        elif_clause => "`elif`",
        else_clause => "`else`",
        except_clause => "`except`",
        finally_clause => "`finally`",
        params | param | plain_param | lambda_params | lambda_param => "a parameter",
        kw_in => "`in`",
        kw_import => "`import`",
        kw_as => "`as`",
        kw_else => "`else`",
        kw_for => "`for`",
        kw_if => "`if`",
        EOI => "end of file",
        default => "`=`",
        annotation => "`:`",
        returns => "`->`",
        dotted_name | dotted_as_name | import_names | import_as_name => "a module name",
        import_star => "`*`",
        _ => return None,
    })
}

fn expected_message(positives: &[Rule], source: &str, pos: usize) -> String {
    let mut seen = BTreeSet::new();
    let mut items: Vec<&'static str> = Vec::new();
    for &r in positives {
        if let Some(d) = describe(r) {
            if seen.insert(d) {
                items.push(d);
            }
        }
    }
    // Operators and trailers are always possible after an operand; mention
    // them only when nothing more specific was expected.
    let specific: Vec<&str> = items
        .iter()
        .copied()
        .filter(|d| {
            !matches!(
                *d,
                "an operator" | "`(`" | "`[`" | "`.`" | "an augmented assignment"
            )
        })
        .collect();
    let chosen = if specific.is_empty() { items } else { specific };
    let found = found_at(source, pos);
    if chosen.is_empty() {
        return format!("unexpected {found}");
    }
    format!("expected {}, found {found}", join_or(&chosen))
}

/// "a", "a or b", "a, b or c".
pub fn join_or(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => (*one).to_string(),
        [init @ .., last] => format!("{} or {}", init.join(", "), last),
    }
}

/// Render an error as `file:line:col: message`, then the source line and a caret.
pub fn render(map: &CodeMap, error: &ParseError) -> String {
    let lc = map.line_col(error.span.start as usize);
    let line = map.line_text_at(lc);
    let number = lc.line.to_string();
    let gutter = " ".repeat(number.len());
    // The caret goes under the character, counting tabs as one column each
    // but reproducing them so the caret lines up in a terminal.
    let pad: String = line
        .chars()
        .take(lc.column.saturating_sub(1))
        .map(|c| if c == '\t' { '\t' } else { ' ' })
        .collect();
    format!(
        "{}: {}\n{gutter} |\n{number} | {line}\n{gutter} | {pad}^\n",
        map.location(error.span),
        error.message
    )
}
