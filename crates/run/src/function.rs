//! Real functions: `DEFI_FONCTION` (tabulated, with interpolation and
//! extension rules), `DEFI_CONSTANTE`, `FORMULE`, and `DEFI_NAPPE`'s
//! functions of two parameters ([`Nappe`]).

use std::fmt;

/// How a tabulated function is extended outside its abscissae
/// (`PROL_GAUCHE` / `PROL_DROITE`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extension {
    /// Outside the table is an error (code_aster's default).
    Excluded,
    /// The end value is kept.
    Constant,
    /// The end segment is prolonged.
    Linear,
}

impl Extension {
    pub fn from_keyword(value: &str) -> Option<Extension> {
        match value {
            "EXCLU" => Some(Extension::Excluded),
            "CONSTANT" => Some(Extension::Constant),
            "LINEAIRE" => Some(Extension::Linear),
            _ => None,
        }
    }

    pub fn keyword(self) -> &'static str {
        match self {
            Extension::Excluded => "EXCLU",
            Extension::Constant => "CONSTANT",
            Extension::Linear => "LINEAIRE",
        }
    }
}

/// Interpolation scale of one axis (`INTERPOL`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    Linear,
    Log,
}

impl Scale {
    pub fn from_keyword(value: &str) -> Option<Scale> {
        match value {
            "LIN" => Some(Scale::Linear),
            "LOG" => Some(Scale::Log),
            _ => None,
        }
    }

    fn forward(self, v: f64) -> f64 {
        match self {
            Scale::Linear => v,
            Scale::Log => v.ln(),
        }
    }

    fn backward(self, v: f64) -> f64 {
        match self {
            Scale::Linear => v,
            Scale::Log => v.exp(),
        }
    }
}

/// A tabulated function: strictly increasing abscissae and their values.
#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated {
    pub parameter: String,
    /// `NOM_RESU`, the name of the values (`None`: code_aster's default
    /// `TOUTRESU`); RECU_FONCTION names them after the component or the
    /// table column it read.
    pub result: Option<String>,
    xs: Vec<f64>,
    ys: Vec<f64>,
    pub scale_x: Scale,
    pub scale_y: Scale,
    pub left: Extension,
    pub right: Extension,
}

/// Why a function could not be built or evaluated.
#[derive(Clone, Debug, PartialEq)]
pub enum FunctionError {
    Empty,
    OddValueCount(usize),
    NotIncreasing {
        index: usize,
        previous: f64,
        next: f64,
    },
    LogOfNonPositive {
        axis: &'static str,
        value: f64,
    },
    OutOfRange {
        parameter: String,
        at: f64,
        min: f64,
        max: f64,
        side: &'static str,
    },
    Formula(String),
}

impl fmt::Display for FunctionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FunctionError::Empty => write!(f, "a function needs at least one point (VALE is empty)"),
            FunctionError::OddValueCount(n) => write!(
                f,
                "VALE must hold (abscissa, value) pairs, but it has {n} numbers (an odd count)"
            ),
            FunctionError::NotIncreasing { index, previous, next } => write!(
                f,
                "abscissae must be strictly increasing: point {} has {} after {}",
                index + 1,
                next,
                previous
            ),
            FunctionError::LogOfNonPositive { axis, value } => write!(
                f,
                "INTERPOL='LOG' on the {axis} axis needs positive values, found {value}"
            ),
            FunctionError::OutOfRange { parameter, at, min, max, side } => write!(
                f,
                "function evaluated at {parameter}={at}, outside its definition range [{min}, {max}] \
                 (PROL_{side}='EXCLU'; set PROL_{side}='CONSTANT' or 'LINEAIRE' to extend it)"
            ),
            FunctionError::Formula(message) => write!(f, "{message}"),
        }
    }
}

impl Tabulated {
    /// Builds a function from `VALE=(x1, y1, x2, y2, …)`.
    pub fn from_pairs(parameter: &str, vale: &[f64]) -> Result<Tabulated, FunctionError> {
        if vale.is_empty() {
            return Err(FunctionError::Empty);
        }
        if !vale.len().is_multiple_of(2) {
            return Err(FunctionError::OddValueCount(vale.len()));
        }
        let xs: Vec<f64> = vale.iter().step_by(2).copied().collect();
        let ys: Vec<f64> = vale.iter().skip(1).step_by(2).copied().collect();
        Tabulated::new(parameter, xs, ys)
    }

    pub fn new(parameter: &str, xs: Vec<f64>, ys: Vec<f64>) -> Result<Tabulated, FunctionError> {
        if xs.is_empty() {
            return Err(FunctionError::Empty);
        }
        for (i, w) in xs.windows(2).enumerate() {
            if w[1] <= w[0] {
                return Err(FunctionError::NotIncreasing {
                    index: i + 1,
                    previous: w[0],
                    next: w[1],
                });
            }
        }
        Ok(Tabulated {
            parameter: parameter.to_string(),
            result: None,
            xs,
            ys,
            scale_x: Scale::Linear,
            scale_y: Scale::Linear,
            left: Extension::Excluded,
            right: Extension::Excluded,
        })
    }

    /// The same function (abscissae, interpolation, prolongations) with
    /// other values, one per abscissa.
    pub fn with_values(&self, ys: Vec<f64>) -> Tabulated {
        debug_assert_eq!(ys.len(), self.xs.len());
        Tabulated { ys, ..self.clone() }
    }

    pub fn abscissae(&self) -> &[f64] {
        &self.xs
    }

    pub fn values(&self) -> &[f64] {
        &self.ys
    }

    /// Interpolates between points `i` and `i + 1` (also used to prolong).
    fn on_segment(&self, i: usize, x: f64) -> Result<f64, FunctionError> {
        let check = |axis: &'static str, scale: Scale, v: f64| {
            if scale == Scale::Log && v <= 0.0 {
                Err(FunctionError::LogOfNonPositive { axis, value: v })
            } else {
                Ok(scale.forward(v))
            }
        };
        let x0 = check("abscissa", self.scale_x, self.xs[i])?;
        let x1 = check("abscissa", self.scale_x, self.xs[i + 1])?;
        let y0 = check("ordinate", self.scale_y, self.ys[i])?;
        let y1 = check("ordinate", self.scale_y, self.ys[i + 1])?;
        let xx = check("abscissa", self.scale_x, x)?;
        let y = y0 + (y1 - y0) * (xx - x0) / (x1 - x0);
        Ok(self.scale_y.backward(y))
    }

    pub fn eval(&self, x: f64) -> Result<f64, FunctionError> {
        let n = self.xs.len();
        let (first, last) = (self.xs[0], self.xs[n - 1]);
        let out_of_range = |side: &'static str| FunctionError::OutOfRange {
            parameter: self.parameter.clone(),
            at: x,
            min: first,
            max: last,
            side,
        };
        // code_aster (fointe, folocx): with PROL_*='EXCLU', an abscissa
        // beyond an end by at most √ε times the end interval takes the end
        // value (a list's last instant and a parameter typed apart often
        // differ by an ulp).
        let near = |end: usize, other: usize| {
            n > 1
                && (x - self.xs[end]).abs()
                    <= f64::EPSILON.sqrt() * (self.xs[end] - self.xs[other]).abs()
        };
        if x < first {
            return match self.left {
                Extension::Excluded if near(0, 1) => Ok(self.ys[0]),
                Extension::Excluded => Err(out_of_range("GAUCHE")),
                Extension::Constant => Ok(self.ys[0]),
                Extension::Linear if n == 1 => Ok(self.ys[0]),
                Extension::Linear => self.on_segment(0, x),
            };
        }
        if x > last {
            return match self.right {
                Extension::Excluded if near(n - 1, n - 2) => Ok(self.ys[n - 1]),
                Extension::Excluded => Err(out_of_range("DROITE")),
                Extension::Constant => Ok(self.ys[n - 1]),
                Extension::Linear if n == 1 => Ok(self.ys[0]),
                Extension::Linear => self.on_segment(n - 2, x),
            };
        }
        if n == 1 {
            return Ok(self.ys[0]);
        }
        if x.is_nan() {
            return Err(FunctionError::Formula(format!(
                "the function of {} is evaluated at NaN",
                self.parameter
            )));
        }
        // first <= x <= last here (−0.0 equals 0.0: compared as numbers,
        // not by their bits). Exact abscissae return the tabulated value
        // (no rounding).
        let i = self.xs.partition_point(|v| *v < x);
        if self.xs.get(i) == Some(&x) {
            return Ok(self.ys[i]);
        }
        self.on_segment(i.saturating_sub(1).min(n - 2), x)
    }
}

/// Evaluates a `FORMULE` for given parameter values (provided by the
/// evaluator, which owns the Python expression).
pub type FormulaFn = dyn Fn(&[(String, f64)]) -> Result<f64, String>;

/// Any real function of the command language.
#[derive(Clone)]
pub enum Function {
    /// `DEFI_CONSTANTE(VALE=c)`.
    Constant {
        parameter: String,
        value: f64,
    },
    Tabulated(Tabulated),
    /// `FORMULE(NOM_PARA=…, VALE='…')`.
    Formula {
        parameters: Vec<String>,
        eval: std::rc::Rc<FormulaFn>,
    },
    /// `DEFI_NAPPE`: a function of two parameters.
    Nappe(Nappe),
}

/// `DEFI_NAPPE`: one function of `parameter_fonc` per value of
/// `parameter`, evaluated as code_aster's `t_nappe.__call__`
/// (`code_aster/Objects/function_py.py`): the two functions around the
/// first parameter's value, each at the second, interpolated between
/// (`INTERPOL`) or prolonged beyond the ends (`PROL_GAUCHE`,
/// `PROL_DROITE`); within 1e-6 of an interval's length of a tabulated
/// parameter, that parameter's function.
#[derive(Clone, Debug)]
pub struct Nappe {
    /// `NOM_PARA`.
    pub parameter: String,
    /// `NOM_PARA_FONC`, or the functions' own parameter.
    pub parameter_fonc: String,
    /// `PARA`, increasing.
    pub para: Vec<f64>,
    /// The function of each `PARA` value.
    pub functions: Vec<Function>,
    pub scale_x: Scale,
    pub scale_y: Scale,
    pub left: Extension,
    pub right: Extension,
}

/// code_aster's `interp` (function_py.py): between (x1, y1) and (x2, y2),
/// the end value within `tol` × the interval of an end.
fn interp_pair(
    (sx, sy): (Scale, Scale),
    val: f64,
    (x1, x2): (f64, f64),
    (y1, y2): (f64, f64),
) -> Result<f64, FunctionError> {
    let tol = 1.0e-6;
    if (val - x1).abs() < tol * (x2 - x1).abs() {
        return Ok(y1);
    }
    if (val - x2).abs() < tol * (x2 - x1).abs() {
        return Ok(y2);
    }
    if sx == Scale::Log && (x1 <= 0.0 || x2 <= 0.0 || val <= 0.0) {
        return Err(FunctionError::LogOfNonPositive {
            axis: "parameter",
            value: x1.min(x2).min(val),
        });
    }
    if sy == Scale::Log && (y1 <= 0.0 || y2 <= 0.0) {
        return Err(FunctionError::LogOfNonPositive {
            axis: "value",
            value: y1.min(y2),
        });
    }
    let t = (sx.forward(val) - sx.forward(x1)) / (sx.forward(x2) - sx.forward(x1));
    Ok(sy.backward(sy.forward(y1) + t * (sy.forward(y2) - sy.forward(y1))))
}

impl Nappe {
    /// The value at `p` (`NOM_PARA`) and `x` (`NOM_PARA_FONC`).
    pub fn eval(&self, p: f64, x: f64) -> Result<f64, FunctionError> {
        let n = self.para.len();
        let tol = 1.0e-6;
        let out = |side: &'static str| FunctionError::OutOfRange {
            parameter: self.parameter.clone(),
            at: p,
            min: self.para[0],
            max: self.para[n - 1],
            side,
        };
        let f = |i: usize| self.functions[i].eval(x);
        let scales = (self.scale_x, self.scale_y);
        if n == 1 {
            let p0 = self.para[0];
            let prolonged = |e: Extension| matches!(e, Extension::Constant | Extension::Linear);
            return if (p - p0).abs() <= tol * p0.abs()
                || (p > p0 && prolonged(self.right))
                || (p < p0 && prolonged(self.left))
            {
                f(0)
            } else {
                Err(out(if p > p0 { "DROITE" } else { "GAUCHE" }))
            };
        }
        if p.is_nan() {
            return Err(FunctionError::Formula(format!(
                "the nappe of {} is evaluated at NaN",
                self.parameter
            )));
        }
        // numpy's searchsorted (side='left').
        let i = self.para.partition_point(|v| *v < p);
        if i == 0 {
            let (p0, p1) = (self.para[0], self.para[1]);
            if ((p - p0) / (p1 - p0)).abs() <= tol {
                return f(0);
            }
            return match self.left {
                Extension::Excluded => Err(out("GAUCHE")),
                Extension::Constant => f(0),
                Extension::Linear => interp_pair(scales, p, (p0, p1), (f(0)?, f(1)?)),
            };
        }
        if i == n {
            let (pn, pm) = (self.para[n - 1], self.para[n - 2]);
            if ((p - pn) / (pn - pm)).abs() <= tol {
                return f(n - 1);
            }
            return match self.right {
                Extension::Excluded => Err(out("DROITE")),
                Extension::Constant => f(n - 1),
                Extension::Linear => interp_pair(scales, p, (pn, pm), (f(n - 1)?, f(n - 2)?)),
            };
        }
        interp_pair(
            scales,
            p,
            (self.para[i - 1], self.para[i]),
            (f(i - 1)?, f(i)?),
        )
    }
}

impl fmt::Debug for Function {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Function::Constant { parameter, value } => {
                write!(f, "Constant({parameter}: {value})")
            }
            Function::Tabulated(t) => write!(f, "{t:?}"),
            Function::Formula { parameters, .. } => write!(f, "Formula({parameters:?})"),
            Function::Nappe(n) => write!(
                f,
                "Nappe({}, {}: {:?})",
                n.parameter, n.parameter_fonc, n.para
            ),
        }
    }
}

impl Function {
    /// The value for a one-parameter call (`f(t)`); a formula with several
    /// parameters gets the value for its first one.
    pub fn eval(&self, x: f64) -> Result<f64, FunctionError> {
        match self {
            Function::Constant { value, .. } => Ok(*value),
            Function::Tabulated(t) => t.eval(x),
            Function::Formula { parameters, eval } => {
                let args: Vec<(String, f64)> = parameters.iter().map(|p| (p.clone(), x)).collect();
                eval(&args).map_err(FunctionError::Formula)
            }
            Function::Nappe(n) => Err(FunctionError::Formula(format!(
                "a nappe is a function of two parameters ({}, {}): one value given",
                n.parameter, n.parameter_fonc
            ))),
        }
    }
}

impl Function {
    /// The parameters it depends on (`NOM_PARA`).
    pub fn parameters(&self) -> Vec<&str> {
        match self {
            Function::Constant { .. } => Vec::new(),
            Function::Tabulated(t) => vec![t.parameter.as_str()],
            Function::Formula { parameters, .. } => parameters.iter().map(String::as_str).collect(),
            Function::Nappe(n) => vec![n.parameter.as_str(), n.parameter_fonc.as_str()],
        }
    }

    /// The value for named parameter values (`INST`, `X`, `Y`, `Z`…), as
    /// code_aster evaluates the functions of `AFFE_CHAR_MECA_F`: each
    /// parameter the function names must be among `args`.
    pub fn eval_named(&self, args: &[(&str, f64)]) -> Result<f64, FunctionError> {
        let value_of = |p: &str| {
            args.iter()
                .find(|(n, _)| *n == p)
                .map(|(_, v)| *v)
                .ok_or_else(|| {
                    let known: Vec<&str> = args.iter().map(|(n, _)| *n).collect();
                    FunctionError::Formula(format!(
                        "the function depends on {p}, but only {} are known here",
                        known.join(", ")
                    ))
                })
        };
        match self {
            Function::Constant { value, .. } => Ok(*value),
            Function::Tabulated(t) => t.eval(value_of(&t.parameter)?),
            Function::Formula { parameters, eval } => {
                let named: Vec<(String, f64)> = parameters
                    .iter()
                    .map(|p| value_of(p).map(|v| (p.clone(), v)))
                    .collect::<Result<_, _>>()?;
                eval(&named).map_err(FunctionError::Formula)
            }
            Function::Nappe(n) => n.eval(value_of(&n.parameter)?, value_of(&n.parameter_fonc)?),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Tabulated {
        let mut f = Tabulated::from_pairs("INST", &[0.0, 0.0, 1.0, 1.0]).unwrap();
        f.right = Extension::Linear;
        f
    }

    #[test]
    fn interpolates_and_prolongs_linearly() {
        let f = ramp();
        assert_eq!(f.eval(0.5).unwrap(), 0.5);
        assert_eq!(f.eval(1.0).unwrap(), 1.0);
        assert!((f.eval(20.0).unwrap() - 20.0).abs() < 1e-12);
    }

    /// −0.0 is the first abscissa 0.0 (found by fuzz_run: the bitwise
    /// order put it before the table); NaN is an error, not a value.
    #[test]
    fn minus_zero_is_zero_and_nan_is_an_error() {
        let f = ramp();
        assert_eq!(f.eval(-0.0).unwrap(), 0.0);
        let g = Tabulated::from_pairs("INST", &[0.0, 3.0, 1.0, 5.0, 2.0, 9.0]).unwrap();
        assert_eq!(g.eval(-0.0).unwrap(), 3.0);
        assert_eq!(g.eval(1.5).unwrap(), 7.0);
        assert_eq!(g.eval(2.0).unwrap(), 9.0);
        assert!(f.eval(f64::NAN).is_err());
    }

    #[test]
    fn excluded_side_is_an_error_that_names_the_fix() {
        let f = ramp();
        let err = f.eval(-1.0).unwrap_err().to_string();
        assert!(err.contains("INST=-1"), "{err}");
        assert!(err.contains("PROL_GAUCHE='EXCLU'"), "{err}");
    }

    #[test]
    fn constant_extension_keeps_end_values() {
        let mut f = Tabulated::from_pairs("X", &[1.0, 2.0, 3.0, 6.0]).unwrap();
        f.left = Extension::Constant;
        f.right = Extension::Constant;
        assert_eq!(f.eval(0.0).unwrap(), 2.0);
        assert_eq!(f.eval(9.0).unwrap(), 6.0);
        assert_eq!(f.eval(2.0).unwrap(), 4.0);
    }

    #[test]
    fn log_interpolation() {
        let mut f = Tabulated::from_pairs("X", &[1.0, 1.0, 100.0, 10000.0]).unwrap();
        f.scale_x = Scale::Log;
        f.scale_y = Scale::Log;
        // log-log: y = x^2
        assert!((f.eval(10.0).unwrap() - 100.0).abs() < 1e-9);
    }

    #[test]
    fn rejects_bad_tables() {
        assert_eq!(
            Tabulated::from_pairs("X", &[0.0, 1.0, 2.0]).unwrap_err(),
            FunctionError::OddValueCount(3)
        );
        assert!(matches!(
            Tabulated::from_pairs("X", &[0.0, 1.0, 0.0, 2.0]),
            Err(FunctionError::NotIncreasing { .. })
        ));
    }

    /// A nappe of AMOR with a function of FREQ per value: f_a(x) = a x.
    fn nappe(left: Extension, right: Extension) -> Nappe {
        let line = |a: f64| {
            Function::Tabulated(Tabulated::from_pairs("FREQ", &[0.0, 0.0, 10.0, 10.0 * a]).unwrap())
        };
        Nappe {
            parameter: "AMOR".into(),
            parameter_fonc: "FREQ".into(),
            para: vec![1.0, 2.0, 4.0],
            functions: vec![line(1.0), line(2.0), line(4.0)],
            scale_x: Scale::Linear,
            scale_y: Scale::Linear,
            left,
            right,
        }
    }

    #[test]
    fn nappe_interpolates_between_its_functions() {
        let n = nappe(Extension::Excluded, Extension::Excluded);
        // f_a(x) = a x, linear in a between the tabulated values.
        assert_eq!(n.eval(2.0, 5.0).unwrap(), 10.0);
        assert!((n.eval(3.0, 5.0).unwrap() - 15.0).abs() < 1e-12);
        assert!((n.eval(1.5, 2.0).unwrap() - 3.0).abs() < 1e-12);
        // within 1e-6 of the interval of an end: that end's function.
        assert_eq!(n.eval(1.0 - 1e-7, 5.0).unwrap(), 5.0);
        let err = n.eval(0.5, 5.0).unwrap_err().to_string();
        assert!(
            err.contains("AMOR=0.5") && err.contains("PROL_GAUCHE"),
            "{err}"
        );
        assert!(n
            .eval(5.0, 5.0)
            .unwrap_err()
            .to_string()
            .contains("PROL_DROITE"));
        let m = nappe(Extension::Constant, Extension::Linear);
        assert_eq!(m.eval(0.5, 5.0).unwrap(), 5.0);
        // prolonged along the last interval: 5 x at AMOR = 5.
        assert!((m.eval(5.0, 5.0).unwrap() - 25.0).abs() < 1e-12);
        let f = Function::Nappe(m);
        assert_eq!(f.parameters(), vec!["AMOR", "FREQ"]);
        assert!((f.eval_named(&[("FREQ", 2.0), ("AMOR", 3.0)]).unwrap() - 6.0).abs() < 1e-12);
        assert!(f.eval(1.0).is_err());
    }

    #[test]
    fn nappe_log_interpolation_between_functions() {
        let mut n = nappe(Extension::Excluded, Extension::Excluded);
        n.scale_x = Scale::Log;
        n.scale_y = Scale::Log;
        // log-log between (1, 5) and (2, 10) at FREQ = 5: y = 5 a.
        assert!((n.eval(1.5, 5.0).unwrap() - 7.5).abs() < 1e-12);
    }

    #[test]
    fn named_evaluation_picks_the_parameter() {
        let f = Function::Tabulated(Tabulated::from_pairs("Y", &[0.0, 0.0, 2.0, 4.0]).unwrap());
        assert_eq!(
            f.eval_named(&[("INST", 9.0), ("X", 7.0), ("Y", 1.0)])
                .unwrap(),
            2.0
        );
        let err = f.eval_named(&[("INST", 1.0)]).unwrap_err().to_string();
        assert!(err.contains("depends on Y"), "{err}");
        let g = Function::Formula {
            parameters: vec!["X".into(), "INST".into()],
            eval: std::rc::Rc::new(|a: &[(String, f64)]| Ok(a[0].1 * 10.0 + a[1].1)),
        };
        assert_eq!(
            g.eval_named(&[("INST", 2.0), ("X", 3.0), ("Y", 5.0)])
                .unwrap(),
            32.0
        );
        assert_eq!(g.parameters(), vec!["X", "INST"]);
    }
}
