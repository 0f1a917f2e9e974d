//! Number formatting as code_aster prints it. Its printers are Python, so a
//! real is shown with Python's `repr` (shortest round-trip digits, exponent
//! outside 1e-4..1e16) and tables use C's `%12.5E` (signed, two-digit
//! exponent). Rust's own `{}`/`{:e}` differ from both, hence these helpers.

/// Python's `repr(float)`, with the exponent marker upper-cased as
/// code_aster's TEST_RESU printer does (`-1.55431223E-15`, `21978000000.0`).
pub fn py_repr(x: f64) -> String {
    if x.is_nan() {
        return "NAN".to_string();
    }
    if x.is_infinite() {
        return if x > 0.0 { "INF" } else { "-INF" }.to_string();
    }
    if x == 0.0 {
        return if x.is_sign_negative() { "-0.0" } else { "0.0" }.to_string();
    }
    // `{:e}` gives the shortest round-trip digits: "d.ddde±x".
    let sci = format!("{x:e}");
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let negative = mantissa.starts_with('-');
    let digits: String = mantissa.chars().filter(|c| c.is_ascii_digit()).collect();
    let sign = if negative { "-" } else { "" };
    if (-4..16).contains(&exp) {
        // Fixed notation with the same digits.
        let point = exp + 1; // position of the decimal point in `digits`
        let text = if point <= 0 {
            format!("0.{}{}", "0".repeat((-point) as usize), digits)
        } else if point as usize >= digits.len() {
            format!("{}{}.0", digits, "0".repeat(point as usize - digits.len()))
        } else {
            let (a, b) = digits.split_at(point as usize);
            format!("{a}.{b}")
        };
        format!("{sign}{text}")
    } else {
        let (first, rest) = digits.split_at(1);
        let mant = if rest.is_empty() {
            first.to_string()
        } else {
            format!("{first}.{rest}")
        };
        let esign = if exp < 0 { '-' } else { '+' };
        format!("{sign}{mant}E{esign}{:02}", exp.abs())
    }
}

/// C's `%W.PE`: `-4.28571E+00` right-aligned in `width`.
pub fn c_exp(x: f64, width: usize, precision: usize) -> String {
    let body = if x.is_finite() {
        let s = format!("{:.*e}", precision, x);
        let (mant, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let exp: i32 = exp.parse().unwrap_or(0);
        let esign = if exp < 0 { '-' } else { '+' };
        format!("{mant}E{esign}{:02}", exp.abs())
    } else if x.is_nan() {
        "NAN".to_string()
    } else if x > 0.0 {
        "INF".to_string()
    } else {
        "-INF".to_string()
    };
    format!("{body:>width$}")
}

/// C's `%13.6e` used by TEST_RESU for long error strings, upper-cased.
pub fn c_exp_lower_width(x: f64) -> String {
    c_exp(x, 13, 6)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repr_matches_python() {
        assert_eq!(py_repr(-1.55431223e-15), "-1.55431223E-15");
        assert_eq!(py_repr(2.1978e10), "21978000000.0");
        assert_eq!(py_repr(-4.2857143183057), "-4.2857143183057");
        assert_eq!(py_repr(0.0), "0.0");
        assert_eq!(py_repr(1e16), "1E+16");
        assert_eq!(py_repr(1.5e-5), "1.5E-05");
        assert_eq!(py_repr(0.0001), "0.0001");
        assert_eq!(py_repr(20.0), "20.0");
        assert_eq!(py_repr(0.1), "0.1");
        assert_eq!(py_repr(123.456), "123.456");
    }

    #[test]
    fn c_exponent_format() {
        assert_eq!(c_exp(-4.285714, 12, 5), "-4.28571E+00");
        assert_eq!(c_exp(20.0, 12, 5), " 2.00000E+01");
        assert_eq!(c_exp(2.1978e10, 12, 5), " 2.19780E+10");
        assert_eq!(c_exp(1.5e-120, 12, 5), "1.50000E-120");
        assert_eq!(c_exp(0.0, 12, 5), " 0.00000E+00");
    }
}
