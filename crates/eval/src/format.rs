//! String formatting: `%`-formatting, `str.format` and f-string format specs.

use crate::limits::{too_large, MAX_STR_BYTES};
use crate::value::{float_str, Value};

/// A width or precision read from a format: digits, saturating (a huge
/// one is refused by [`check_len`] rather than overflowing).
fn digits_value(acc: usize, d: u32) -> usize {
    acc.saturating_mul(10).saturating_add(d as usize)
}

/// A width or precision within what one string may hold.
fn check_len(n: usize) -> Result<(), String> {
    if n > MAX_STR_BYTES {
        return Err(too_large(n as u128, MAX_STR_BYTES, "characters"));
    }
    Ok(())
}

/// Digits after the point beyond which a float's exact decimal expansion
/// has only zeros (2^-1074 has 1,074 of them): Rust's formatting takes at
/// most 65,535, so longer precisions are these digits and zeros.
const EXACT_FRACTION_DIGITS: usize = 1_100;

/// `x` with `p` digits after the point (Python's `%.pf`), for any `p`.
fn fixed(x: f64, p: usize) -> String {
    if !x.is_finite() {
        // `inf`, `nan`: no digits (Rust's formatting would refuse p > 65,535).
        return format!("{x}");
    }
    if p <= EXACT_FRACTION_DIGITS {
        return format!("{x:.p$}");
    }
    let mut s = format!("{x:.EXACT_FRACTION_DIGITS$}");
    s.push_str(&"0".repeat(p - EXACT_FRACTION_DIGITS));
    s
}

/// Formats one value with a format-spec of the mini-language
/// (`[[fill]align][sign][0][width][,][.precision][type]`).
pub fn format_spec(v: &Value, spec: &str) -> Result<String, String> {
    if spec.is_empty() {
        return v.try_str();
    }
    let chars: Vec<char> = spec.chars().collect();
    let mut i = 0;
    let (mut fill, mut align) = (' ', None);
    if chars.len() >= 2 && matches!(chars[1], '<' | '>' | '^' | '=') {
        fill = chars[0];
        align = Some(chars[1]);
        i = 2;
    } else if matches!(chars[0], '<' | '>' | '^' | '=') {
        align = Some(chars[0]);
        i = 1;
    }
    let mut sign = '-';
    if i < chars.len() && matches!(chars[i], '+' | '-' | ' ') {
        sign = chars[i];
        i += 1;
    }
    if i < chars.len() && chars[i] == '#' {
        i += 1;
    }
    if i < chars.len() && chars[i] == '0' {
        fill = '0';
        align = align.or(Some('='));
        i += 1;
    }
    let mut width = 0usize;
    while i < chars.len() && chars[i].is_ascii_digit() {
        width = digits_value(width, chars[i].to_digit(10).unwrap_or(0));
        i += 1;
    }
    check_len(width)?;
    if i < chars.len() && (chars[i] == ',' || chars[i] == '_') {
        i += 1;
    }
    let mut prec = None;
    if i < chars.len() && chars[i] == '.' {
        i += 1;
        let mut p = 0usize;
        while i < chars.len() && chars[i].is_ascii_digit() {
            p = digits_value(p, chars[i].to_digit(10).unwrap_or(0));
            i += 1;
        }
        check_len(p)?;
        prec = Some(p);
    }
    let ty = chars.get(i).copied();
    if i + 1 < chars.len() {
        return Err(format!("invalid format specifier `{spec}`"));
    }
    let body = format_one(v, ty, prec, sign)?;
    let numeric = v.as_f64().is_some();
    pad(
        &body,
        width,
        fill,
        align.unwrap_or(if numeric { '>' } else { '<' }),
    )
}

fn pad(body: &str, width: usize, fill: char, align: char) -> Result<String, String> {
    check_len(width)?;
    let n = body.chars().count();
    if n >= width {
        return Ok(body.to_string());
    }
    let k = width - n;
    let f = |m: usize| fill.to_string().repeat(m);
    Ok(match align {
        '<' => format!("{body}{}", f(k)),
        '^' => format!("{}{body}{}", f(k / 2), f(k - k / 2)),
        '=' => {
            if let Some(rest) = body.strip_prefix('-') {
                format!("-{}{rest}", f(k))
            } else if let Some(rest) = body.strip_prefix('+') {
                format!("+{}{rest}", f(k))
            } else {
                format!("{}{body}", f(k))
            }
        }
        _ => format!("{}{body}", f(k)),
    })
}

/// Significant digits beyond which a float's exact decimal expansion has
/// only zeros (at most 767 significant digits).
const EXACT_SIGNIFICANT_DIGITS: usize = 800;

fn exp_form(x: f64, prec: usize, upper: bool) -> String {
    let shown = prec.min(EXACT_SIGNIFICANT_DIGITS);
    let s = format!("{x:.shown$e}");
    let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
    let zeros;
    let m = if prec > shown && x.is_finite() {
        zeros = format!("{m}{}", "0".repeat(prec - shown));
        zeros.as_str()
    } else {
        m
    };
    let e: i32 = e.parse().unwrap_or(0);
    let out = format!("{m}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs());
    if upper {
        out.to_uppercase()
    } else {
        out
    }
}

fn general(x: f64, prec: usize, upper: bool, strip: bool) -> String {
    let p = prec.max(1);
    if x == 0.0 {
        return "0".into();
    }
    let exp = x.abs().log10().floor() as i32;
    let s = if exp < -4 || exp as i64 >= p as i64 {
        let s = exp_form(x, p - 1, upper);
        if strip {
            let (m, e) = s
                .split_once(if upper { 'E' } else { 'e' })
                .unwrap_or((&s, ""));
            let m = if m.contains('.') {
                m.trim_end_matches('0').trim_end_matches('.')
            } else {
                m
            };
            format!("{m}{}{e}", if upper { 'E' } else { 'e' })
        } else {
            s
        }
    } else {
        let decimals = (p as i64 - 1 - exp as i64).max(0) as usize;
        let s = fixed(x, decimals);
        if strip && s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    s
}

fn format_one(
    v: &Value,
    ty: Option<char>,
    prec: Option<usize>,
    sign: char,
) -> Result<String, String> {
    let signed = |s: String, neg: bool| -> String {
        if neg || s.starts_with('-') {
            s
        } else if sign == '+' {
            format!("+{s}")
        } else if sign == ' ' {
            format!(" {s}")
        } else {
            s
        }
    };
    match ty {
        Some('s') | None
            if !matches!(v, Value::Float(_) | Value::Int(_) | Value::Big(_)) || ty == Some('s') =>
        {
            let s = v.try_str()?;
            Ok(match prec {
                Some(p) => s.chars().take(p).collect(),
                None => s,
            })
        }
        Some('d') | Some('i') => match v {
            Value::Int(i) => Ok(signed(i.to_string(), *i < 0)),
            Value::Big(b) => Ok(signed(b.to_string(), b.sign() == num_bigint::Sign::Minus)),
            Value::Bool(b) => Ok((*b as i64).to_string()),
            Value::Float(f) if ty == Some('i') || f.fract() == 0.0 => {
                Ok(signed(crate::int::from_f64(*f)?.to_string(), *f < 0.0))
            }
            other => Err(format!("format code 'd' for {}", other.type_name())),
        },
        Some(c @ ('f' | 'F' | 'e' | 'E' | 'g' | 'G' | '%')) | Some(c @ 'n') => {
            let x = v
                .as_f64()
                .ok_or_else(|| format!("format code '{c}' for {}", v.type_name()))?;
            if x.is_infinite() && matches!(v, Value::Big(_)) {
                return Err("int too large to convert to float".into());
            }
            let p = prec.unwrap_or(6);
            let s = match c {
                'f' | 'F' => fixed(x, p),
                'e' | 'E' => exp_form(x, p, c == 'E'),
                '%' => format!("{}%", fixed(x * 100.0, p)),
                _ => general(x, p, c == 'G', true),
            };
            Ok(signed(s, x < 0.0))
        }
        None => match v {
            Value::Float(f) => match prec {
                Some(p) => Ok(signed(general(*f, p, false, true), *f < 0.0)),
                None => Ok(signed(float_str(*f), *f < 0.0)),
            },
            other => Ok(signed(other.try_str()?, false)),
        },
        Some('r') => v.try_repr(),
        Some(c) => Err(format!("unknown format code '{c}'")),
    }
}

/// Python's `fmt % args`.
pub fn percent(fmt: &str, args: &Value) -> Result<String, String> {
    let items: Vec<Value> = match args {
        Value::Tuple(t) => t.to_vec(),
        other => vec![other.clone()],
    };
    let dict = match args {
        Value::Dict(d) => Some(d.clone()),
        _ => None,
    };
    let mut next = 0usize;
    let mut out = String::new();
    let chars: Vec<char> = fmt.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c != '%' {
            out.push(c);
            i += 1;
            continue;
        }
        i += 1;
        if i < chars.len() && chars[i] == '%' {
            out.push('%');
            i += 1;
            continue;
        }
        let mut key = None;
        if i < chars.len() && chars[i] == '(' {
            let s = i + 1;
            while i < chars.len() && chars[i] != ')' {
                i += 1;
            }
            key = Some(chars[s..i.min(chars.len())].iter().collect::<String>());
            i += 1;
        }
        let mut flags = String::new();
        while i < chars.len() && matches!(chars[i], '-' | '+' | ' ' | '0' | '#') {
            flags.push(chars[i]);
            i += 1;
        }
        let mut width = String::new();
        let take_arg = |out_next: &mut usize| -> Result<Value, String> {
            let v = items
                .get(*out_next)
                .cloned()
                .ok_or("not enough arguments for format string")?;
            *out_next += 1;
            Ok(v)
        };
        if i < chars.len() && chars[i] == '*' {
            width = take_arg(&mut next)?.try_str()?;
            i += 1;
        }
        while i < chars.len() && chars[i].is_ascii_digit() {
            width.push(chars[i]);
            i += 1;
        }
        let mut prec = None;
        if i < chars.len() && chars[i] == '.' {
            i += 1;
            let mut p = String::new();
            while i < chars.len() && chars[i].is_ascii_digit() {
                p.push(chars[i]);
                i += 1;
            }
            let p = p
                .bytes()
                .fold(0usize, |acc, d| digits_value(acc, (d - b'0') as u32));
            check_len(p)?;
            prec = Some(p);
        }
        let Some(&ty) = chars.get(i) else {
            return Err("incomplete format".into());
        };
        i += 1;
        let v = match &key {
            Some(k) => dict
                .as_ref()
                .and_then(|d| d.borrow().get(&Value::str(k)).cloned())
                .ok_or_else(|| format!("format key '{k}' not found"))?,
            None => take_arg(&mut next)?,
        };
        let ty = match ty {
            'u' => 'd',
            c => c,
        };
        let sign = if flags.contains('+') {
            '+'
        } else if flags.contains(' ') {
            ' '
        } else {
            '-'
        };
        let body = match ty {
            's' => v.try_str()?,
            'r' | 'a' => v.try_repr()?,
            'c' => v.try_str()?,
            'd' | 'i' => match &v {
                Value::Float(f) => format_one(&crate::int::from_f64(*f)?, Some('d'), None, sign)?,
                other => format_one(other, Some('d'), None, sign)?,
            },
            t => format_one(&v, Some(t), prec.or(Some(6)), sign)?,
        };
        let body = if ty == 's' {
            match prec {
                Some(p) => body.chars().take(p).collect(),
                None => body,
            }
        } else {
            body
        };
        let w: usize = width
            .trim_start_matches('-')
            .bytes()
            .filter(u8::is_ascii_digit)
            .fold(0usize, |acc, d| digits_value(acc, (d - b'0') as u32));
        let (fill, align) = if flags.contains('-') {
            (' ', '<')
        } else if flags.contains('0') && ty != 's' {
            ('0', '=')
        } else {
            (' ', '>')
        };
        out.push_str(&pad(&body, w, fill, align)?);
        check_len(out.len())?;
    }
    if key_free(&dict) && next < items.len() && !matches!(args, Value::Dict(_)) {
        return Err("not all arguments converted during string formatting".into());
    }
    Ok(out)
}

fn key_free(d: &Option<std::rc::Rc<std::cell::RefCell<crate::value::Dict>>>) -> bool {
    d.is_none()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_forms() {
        let t = Value::tuple(vec![Value::Int(3), Value::Float(1.5), Value::str("ab")]);
        assert_eq!(percent("N%d x=%.3f %s", &t).unwrap(), "N3 x=1.500 ab");
        assert_eq!(
            percent(
                "%5.2e|%-4d|%04d",
                &Value::tuple(vec![Value::Float(12345.0), Value::Int(7), Value::Int(-7)])
            )
            .unwrap(),
            "1.23e+04|7   |-007"
        );
        assert_eq!(percent("%g", &Value::Float(0.0001)).unwrap(), "0.0001");
        assert_eq!(percent("%g", &Value::Float(1e-5)).unwrap(), "1e-05");
        assert!(percent("%d %d", &Value::Int(1)).is_err());
    }

    #[test]
    fn spec_forms() {
        assert_eq!(format_spec(&Value::Float(1.23456), ".2f").unwrap(), "1.23");
        assert_eq!(format_spec(&Value::Int(5), "03d").unwrap(), "005");
        assert_eq!(format_spec(&Value::str("a"), ">3").unwrap(), "  a");
        assert_eq!(
            format_spec(&Value::Float(1234.5), ".3e").unwrap(),
            "1.234e+03"
        );
    }
}
