//! Python integers: exact and unbounded.
//!
//! Most integers of a command file fit an `i64` ([`Value::Int`], no
//! allocation); a result that does not (`1 << 64`, `-(-2**63)`,
//! `abs(-2**63)`, `int(1e300)`) becomes a [`Value::Big`] (`num_bigint`),
//! and any result that fits again is an `Int` again, so each integer has one
//! representation. Integers are bounded only by [`MAX_INT_BITS`] (a result
//! beyond it is refused as too large, as Python refuses to print more than
//! 4,300 digits).

use crate::limits::{MAX_INT_BITS, MAX_INT_DIGITS};
use crate::value::Value;
use aster_syntax::ast::BinOp;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{FromPrimitive, One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::rc::Rc;

/// The value of an exact integer (one representation: `Int` when it fits).
pub fn norm(b: BigInt) -> Value {
    match b.to_i64() {
        Some(i) => Value::Int(i),
        None => Value::Big(Rc::new(b)),
    }
}

/// The integer value of `v` (`bool` included), if it is one.
pub fn big(v: &Value) -> Option<BigInt> {
    match v {
        Value::Int(i) => Some(BigInt::from(*i)),
        Value::Bool(b) => Some(BigInt::from(*b as i64)),
        Value::Big(b) => Some((**b).clone()),
        _ => None,
    }
}

pub fn is_int(v: &Value) -> bool {
    matches!(v, Value::Int(_) | Value::Bool(_) | Value::Big(_))
}

/// A result checked against [`MAX_INT_BITS`].
fn sized(b: BigInt) -> Result<Value, String> {
    if b.bits() > MAX_INT_BITS {
        return Err(too_large());
    }
    Ok(norm(b))
}

pub fn too_large() -> String {
    format!("integer result too large (more than {MAX_INT_BITS} bits)")
}

/// Python's `float(n)`: an error when the integer is beyond a float's range.
pub fn to_f64(b: &BigInt) -> Result<f64, String> {
    match b.to_f64() {
        Some(f) if f.is_finite() => Ok(f),
        _ => Err("int too large to convert to float".into()),
    }
}

/// Python's `int(x)` of a float: truncated, exact.
pub fn from_f64(f: f64) -> Result<Value, String> {
    if f.is_nan() {
        return Err("cannot convert float NaN to integer".into());
    }
    if f.is_infinite() {
        return Err("cannot convert float infinity to integer".into());
    }
    let t = f.trunc();
    if t.abs() < 9.0e18 {
        return Ok(Value::Int(t as i64));
    }
    BigInt::from_f64(t)
        .map(norm)
        .ok_or_else(|| "cannot convert float to integer".into())
}

/// Python's `int(text)`: optional sign, digits with `_` separators, blanks around.
pub fn parse(text: &str) -> Option<Value> {
    let t = text.trim();
    let (neg, digits) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t),
    };
    if digits.is_empty()
        || digits.starts_with('_')
        || digits.ends_with('_')
        || digits.contains("__")
        || !digits.bytes().all(|b| b.is_ascii_digit() || b == b'_')
    {
        return None;
    }
    let clean: String = digits.chars().filter(|c| *c != '_').collect();
    if clean.len() > MAX_INT_DIGITS {
        return None;
    }
    let b: BigInt = clean.parse().ok()?;
    Some(norm(if neg { -b } else { b }))
}

pub fn neg(v: &Value) -> Value {
    match v {
        Value::Int(i) => match i.checked_neg() {
            Some(n) => Value::Int(n),
            None => norm(-BigInt::from(*i)),
        },
        Value::Bool(b) => Value::Int(-(*b as i64)),
        Value::Big(b) => norm(-(**b).clone()),
        other => other.clone(),
    }
}

pub fn abs(v: &Value) -> Value {
    match v {
        Value::Int(i) => match i.checked_abs() {
            Some(n) => Value::Int(n),
            None => norm(BigInt::from(*i).abs()),
        },
        Value::Bool(b) => Value::Int(*b as i64),
        Value::Big(b) => norm(b.abs()),
        other => other.clone(),
    }
}

pub fn invert(v: &Value) -> Value {
    match v {
        Value::Int(i) => Value::Int(!i),
        Value::Bool(b) => Value::Int(!(*b as i64)),
        Value::Big(b) => norm(-(**b).clone() - 1),
        other => other.clone(),
    }
}

/// `l op r` for two integers, exactly as Python computes it.
pub fn binop(op: BinOp, l: &Value, r: &Value) -> Result<Value, String> {
    if let (Value::Int(a), Value::Int(b)) = (l, r) {
        if let Some(v) = small(op, *a, *b)? {
            return Ok(v);
        }
    }
    let (Some(a), Some(b)) = (big(l), big(r)) else {
        return Err("internal: integer operation on non-integers".into());
    };
    Ok(match op {
        BinOp::Add => norm(a + b),
        BinOp::Sub => norm(a - b),
        BinOp::Mul => {
            if a.bits() + b.bits() > MAX_INT_BITS + 1 {
                return Err(too_large());
            }
            sized(a * b)?
        }
        BinOp::Div => {
            if b.is_zero() {
                return Err("division by zero".into());
            }
            Value::Float(true_div(&a, &b)?)
        }
        BinOp::FloorDiv => {
            if b.is_zero() {
                return Err("integer division or modulo by zero".into());
            }
            norm(a.div_floor(&b))
        }
        BinOp::Mod => {
            if b.is_zero() {
                return Err("integer division or modulo by zero".into());
            }
            norm(a.mod_floor(&b))
        }
        BinOp::Pow => pow(&a, &b)?,
        BinOp::LShift => {
            let n = shift_count(&b)?;
            if a.is_zero() {
                Value::Int(0)
            } else if a.bits() + n > MAX_INT_BITS {
                return Err(too_large());
            } else {
                norm(a << n)
            }
        }
        BinOp::RShift => {
            let n = shift_count(&b)?;
            if n >= a.bits() {
                Value::Int(if a.is_negative() { -1 } else { 0 })
            } else {
                // num-bigint shifts negative numbers toward -infinity, like Python.
                norm(a >> n)
            }
        }
        BinOp::BitAnd => norm(a & b),
        BinOp::BitOr => norm(a | b),
        BinOp::BitXor => norm(a ^ b),
        BinOp::MatMul => return Err("unsupported operand types for @: 'int' and 'int'".into()),
    })
}

/// The `i64` fast path; `None` when the exact result needs more bits.
fn small(op: BinOp, a: i64, b: i64) -> Result<Option<Value>, String> {
    Ok(match op {
        BinOp::Add => a.checked_add(b).map(Value::Int),
        BinOp::Sub => a.checked_sub(b).map(Value::Int),
        BinOp::Mul => a.checked_mul(b).map(Value::Int),
        BinOp::FloorDiv | BinOp::Mod => {
            if b == 0 {
                return Err("integer division or modulo by zero".into());
            }
            // i64::MIN // -1 overflows: the big path answers.
            match (a.checked_div(b), a.checked_rem(b)) {
                (Some(q), Some(r)) => {
                    let adjust = r != 0 && ((r < 0) != (b < 0));
                    Some(Value::Int(if op == BinOp::FloorDiv {
                        q - adjust as i64
                    } else if adjust {
                        r + b
                    } else {
                        r
                    }))
                }
                _ => None,
            }
        }
        BinOp::Div => {
            if b == 0 {
                return Err("division by zero".into());
            }
            // Both exact as floats: one correctly rounded division.
            if a.unsigned_abs() <= 1 << 53 && b.unsigned_abs() <= 1 << 53 {
                Some(Value::Float(a as f64 / b as f64))
            } else {
                None
            }
        }
        BinOp::Pow => {
            if b < 0 {
                if a == 0 {
                    return Err("0.0 cannot be raised to a negative power".into());
                }
                Some(Value::Float((a as f64).powf(b as f64)))
            } else {
                u32::try_from(b)
                    .ok()
                    .and_then(|e| a.checked_pow(e))
                    .map(Value::Int)
            }
        }
        BinOp::LShift => {
            if b < 0 {
                return Err("negative shift count".into());
            }
            if b < 64 && a.unsigned_abs().leading_zeros() as i64 > b {
                Some(Value::Int(a << b))
            } else if a == 0 {
                Some(Value::Int(0))
            } else {
                None
            }
        }
        BinOp::RShift => {
            if b < 0 {
                return Err("negative shift count".into());
            }
            Some(Value::Int(a >> b.min(63)))
        }
        BinOp::BitAnd => Some(Value::Int(a & b)),
        BinOp::BitOr => Some(Value::Int(a | b)),
        BinOp::BitXor => Some(Value::Int(a ^ b)),
        BinOp::MatMul => None,
    })
}

fn shift_count(b: &BigInt) -> Result<u64, String> {
    if b.is_negative() {
        return Err("negative shift count".into());
    }
    Ok(b.to_u64().unwrap_or(u64::MAX))
}

/// `a / b` of two integers as a float (Python rounds the exact quotient;
/// here each operand is rounded first, which differs in the last bit at
/// most, and only beyond 2^53).
fn true_div(a: &BigInt, b: &BigInt) -> Result<f64, String> {
    let (x, y) = (a.to_f64(), b.to_f64());
    match (x, y) {
        (Some(x), Some(y)) if x.is_finite() && y.is_finite() => Ok(x / y),
        _ => {
            // Scale both down to the float range.
            let shift = a.bits().max(b.bits()).saturating_sub(1000);
            let (x, y) = ((a >> shift).to_f64(), (b >> shift).to_f64());
            match (x, y) {
                (Some(x), Some(y)) if (x / y).is_finite() => Ok(x / y),
                _ => Err("integer division result too large for a float".into()),
            }
        }
    }
}

fn pow(a: &BigInt, b: &BigInt) -> Result<Value, String> {
    if b.is_negative() {
        if a.is_zero() {
            return Err("0.0 cannot be raised to a negative power".into());
        }
        let (x, y) = (to_f64(a)?, b.to_f64().unwrap_or(f64::NEG_INFINITY));
        return Ok(Value::Float(x.powf(y)));
    }
    // 0, 1 and -1 stay small whatever the exponent.
    if a.is_zero() {
        return Ok(Value::Int(if b.is_zero() { 1 } else { 0 }));
    }
    if a.is_one() {
        return Ok(Value::Int(1));
    }
    if *a == BigInt::from(-1) {
        return Ok(Value::Int(if b.is_even() { 1 } else { -1 }));
    }
    let e = match b.to_u64() {
        Some(e) if (a.bits() - 1).saturating_mul(e) <= MAX_INT_BITS => e,
        _ => return Err(too_large()),
    };
    sized(num_traits::pow::Pow::pow(a, e))
}

/// Python's three-argument `pow(base, exp, mod)`.
pub fn pow_mod(base: &Value, exp: &Value, m: &Value) -> Result<Value, String> {
    let (Some(a), Some(e), Some(m)) = (big(base), big(exp), big(m)) else {
        return Err("pow() 3rd argument not allowed unless all arguments are integers".into());
    };
    if m.is_zero() {
        return Err("pow() 3rd argument cannot be 0".into());
    }
    if e.is_negative() {
        return Err("pow() with a negative exponent and a modulus is not supported".into());
    }
    // Python's result has the sign of the modulus.
    let r = a.modpow(&e, &m.abs());
    let r = if m.is_negative() && !r.is_zero() {
        r + &m
    } else {
        r
    };
    Ok(norm(r))
}

/// The exact order of an integer and a float (`None` for NaN).
pub fn cmp_float(a: &BigInt, f: f64) -> Option<Ordering> {
    if f.is_nan() {
        return None;
    }
    if f.is_infinite() {
        return Some(if f > 0.0 {
            Ordering::Less
        } else {
            Ordering::Greater
        });
    }
    let fl = f.floor();
    let bf = BigInt::from_f64(fl)?;
    Some(match a.cmp(&bf) {
        Ordering::Equal if f > fl => Ordering::Less,
        o => o,
    })
}

/// The number of bits of an integer value (0 for non-integers).
pub fn bits(v: &Value) -> u64 {
    big(v).map(|b| b.bits()).unwrap_or(0)
}

/// An integer as a count (repetitions, widths): a big integer saturates,
/// so that it is refused as too large (or gives an empty result when
/// negative), as in Python.
pub fn as_count(v: &Value) -> Option<i128> {
    match v {
        Value::Int(i) => Some(*i as i128),
        Value::Bool(b) => Some(*b as i128),
        Value::Big(b) => Some(if b.is_negative() {
            i128::MIN
        } else {
            i128::MAX
        }),
        _ => None,
    }
}

/// An integer value as an `int` (a `bool` becomes 0 or 1).
pub fn plain(v: &Value) -> Value {
    match v {
        Value::Bool(b) => Value::Int(*b as i64),
        other => other.clone(),
    }
}

/// Python's `round(n, -k)` for an integer: the nearest multiple of 10^k,
/// ties to even.
pub fn round_int(v: &Value, k: u32) -> Result<Value, String> {
    let Some(a) = big(v) else {
        return Err("round(): not an integer".into());
    };
    if (k as u64) * 4 > a.bits() + 4 {
        // 10^k is beyond the number: it rounds to 0.
        return Ok(Value::Int(0));
    }
    let p = num_traits::pow::Pow::pow(&BigInt::from(10), k);
    let (q, r) = a.div_mod_floor(&p);
    let twice: BigInt = &r * 2;
    let q = match twice.cmp(&p) {
        Ordering::Greater => q + 1,
        Ordering::Equal if q.is_odd() => q + 1,
        _ => q,
    };
    sized(q * p)
}

/// `math.factorial(n)`, exact.
pub fn factorial(v: &Value) -> Result<Value, String> {
    let Some(n) = big(v).and_then(|b| b.to_u64()) else {
        return Err("factorial() not defined for negative values".into());
    };
    let mut acc = BigInt::one();
    for k in 2..=n {
        acc *= k;
        if acc.bits() > MAX_INT_BITS {
            return Err(too_large());
        }
    }
    Ok(norm(acc))
}
