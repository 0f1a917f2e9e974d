//! `DEFI_MATERIAU/ELAS_FO`: the elastic constants as functions (of `TEMP`,
//! `X`, `Y`, `Z`), resolved per cell by `AFFE_MATERIAU` into the constants
//! the elements take, and ALPHA converted to the reference temperature as
//! code_aster's `alfint` does.
//!
//! code_aster evaluates the functions at each integration point with the
//! command variables there (`rcvalb` → `rcvarc`). aster's elements take one
//! E, NU (and RHO) per cell, constant in time: a function is resolved when
//! it takes one value over everything the cell sees — its nodes'
//! coordinates, its nodes' temperatures at every instant of the
//! `AFFE_VARC` field —, which covers constant functions
//! (`DEFI_CONSTANTE`) and functions of a temperature uniform over the cell
//! and in time; otherwise the cell's material is marked unresolved and a
//! mechanical computation on it is refused at the ELAS_FO keyword.
//!
//! The thermal strain takes ALPHA per node (`Material::thermal_strain`),
//! a function of the node's temperature: code_aster's, α(T)(T − T_ref)
//! with T at the Gauss point, is the same where the temperature is
//! uniform over the cell; where it is not, the two differ by the
//! curvature of α(T)(T − T_ref) over the cell, and a cell with a
//! non-constant ALPHA and a temperature not uniform over it is marked
//! unresolved (docs/fem.md).

use crate::concept::{LoadFunction, Material};
use crate::function::{Function, Tabulated};
use aster_syntax::Span;
use std::rc::Rc;

/// One function of ELAS_FO: the keyword, the function's name and where
/// it was given.
#[derive(Clone, Debug, PartialEq)]
pub struct FoArg {
    pub keyword: &'static str,
    pub name: String,
    pub function: LoadFunction,
    pub span: Span,
}

/// `ELAS_FO=_F(E, NU, RHO, ALPHA, TEMP_DEF_ALPHA, PRECISION, AMOR_ALPHA,
/// AMOR_BETA)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ElasFo {
    pub e: FoArg,
    pub nu: FoArg,
    pub rho: Option<FoArg>,
    pub alpha: Option<FoArg>,
    pub amor_alpha: Option<FoArg>,
    pub amor_beta: Option<FoArg>,
    pub temp_def_alpha: Option<f64>,
    /// `PRECISION`: how close to T_ref an abscissa of ALPHA takes the
    /// derivative rule of `alfint`.
    pub precision: f64,
}

/// The value of a function that depends on nothing (`DEFI_CONSTANTE`, a
/// formula of no parameter).
pub fn constant(f: &Function) -> Option<f64> {
    if f.parameters().is_empty() {
        f.eval_named(&[]).ok()
    } else {
        None
    }
}

impl ElasFo {
    /// Whether every function is a constant (then DEFI_MATERIAU gives the
    /// values and AFFE_MATERIAU has nothing to resolve).
    pub fn is_constant(&self) -> bool {
        [
            Some(&self.e),
            Some(&self.nu),
            self.rho.as_ref(),
            self.alpha.as_ref(),
            self.amor_alpha.as_ref(),
            self.amor_beta.as_ref(),
        ]
        .into_iter()
        .flatten()
        .all(|a| constant(&a.function.0).is_some())
    }
}

/// code_aster's `alfint` (bibfor/mate_util/alfint.F90): the coefficient of
/// thermal expansion given from `TEMP_DEF_ALPHA` (α, with
/// ε_th = α(T)(T − T_def)) turned into one from the reference temperature
/// T_ref of AFFE_VARC (ε_th = α'(T)(T − T_ref)), at each abscissa Tᵢ of
/// the tabulated function:
///
/// α'(Tᵢ) = [α(Tᵢ)(Tᵢ − T_def) − α(T_ref)(T_ref − T_def)] / (Tᵢ − T_ref)
///
/// and, where |Tᵢ − T_ref| < PRECISION, α'(Tᵢ) = α(T_ref) + dα(T_ref)
/// (T_ref − T_def), dα the mean of the slopes to the neighbouring
/// abscissae (one-sided at the ends). The result keeps the abscissae,
/// interpolation and prolongations: between the abscissae α' is
/// interpolated, not computed by the formula. A constant (`DEFI_CONSTANTE`)
/// is kept; a one-point function is kept when |T_ref − T_def| < 1 and
/// refused otherwise (MATERIAL1_42); a formula is refused (MATERIAL1_1).
/// `Ok(None)`: α is kept as given.
pub fn alfint(
    alpha: &Function,
    tref: f64,
    tdef: f64,
    prec: f64,
) -> Result<Option<Tabulated>, String> {
    let t = match alpha {
        Function::Constant { .. } => return Ok(None),
        Function::Tabulated(t) => t,
        Function::Formula { .. } | Function::Nappe(_) => {
            return Err(
                "with TEMP_DEF_ALPHA, ALPHA must be a function of TEMP given by DEFI_FONCTION (code_aster's MATERIAL1_1)"
                    .into(),
            )
        }
    };
    let (xs, ys) = (t.abscissae(), t.values());
    let n = xs.len();
    if n == 1 {
        if (tref - tdef).abs() < 1.0 {
            return Ok(None);
        }
        return Err(format!(
            "ALPHA, a one-point function, cannot be converted from TEMP_DEF_ALPHA={tdef} to the reference temperature {tref} (code_aster's MATERIAL1_42)"
        ));
    }
    let alfref = t
        .eval(tref)
        .map_err(|e| format!("ALPHA at the reference temperature: {e}"))?;
    let coincide = || {
        format!(
            "ALPHA has two abscissae within PRECISION={prec} of the reference temperature {tref} (code_aster's MATERIAL1_3)"
        )
    };
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let (ti, ai) = (xs[i], ys[i]);
        if (ti - tref).abs() >= prec {
            out.push((ai * (ti - tdef) - alfref * (tref - tdef)) / (ti - tref));
            continue;
        }
        let dalref = if i > 0 && i + 1 < n {
            let (tim1, tip1) = (xs[i - 1], xs[i + 1]);
            if tip1 == tref || tim1 == tref {
                return Err(coincide());
            }
            0.5 * ((ys[i + 1] - alfref) / (tip1 - tref) + (alfref - ys[i - 1]) / (tref - tim1))
        } else if i + 1 == n {
            let tim1 = xs[i - 1];
            if tim1 == tref {
                return Err(coincide());
            }
            (alfref - ys[i - 1]) / (tref - tim1)
        } else {
            let tip1 = xs[i + 1];
            if tip1 == tref {
                return Err(coincide());
            }
            (ys[i + 1] - alfref) / (tip1 - tref)
        };
        out.push(dalref * (tref - tdef) + alfref);
    }
    Ok(Some(t.with_values(out)))
}

/// What a cell gives the functions of its material: its nodes'
/// coordinates and, with AFFE_VARC, its nodes' temperatures at each
/// instant of the field and the reference temperature.
pub struct CellVars<'a> {
    pub coords: Vec<[f64; 3]>,
    /// Per instant of the temperature field, per node of the cell.
    pub temps: Option<Vec<Vec<f64>>>,
    pub tref: Option<f64>,
    pub cell_name: &'a str,
    /// The temperature is through the thickness of shells
    /// (`CREA_RESU/PREP_VARC`): no TEMP at the nodes.
    pub through_thickness: bool,
}

/// The one value of `arg`'s function over what the cell gives it, or why
/// there is none.
fn one_value(arg: &FoArg, vars: &CellVars) -> Result<f64, String> {
    let f = &arg.function.0;
    if let Some(c) = constant(f) {
        return Ok(c);
    }
    let params = f.parameters();
    let cell = vars.cell_name;
    for p in &params {
        match *p {
            "TEMP" if vars.temps.is_none() => {
                return Err(format!(
                    "`{}` is a function of TEMP and cell {cell} has no temperature (AFFE_MATERIAU/AFFE_VARC)",
                    arg.name
                ))
            }
            "TEMP" | "X" | "Y" | "Z" => {}
            other => {
                return Err(format!(
                    "`{}` is a function of {other}: aster gives ELAS_FO the temperature (TEMP, from AFFE_VARC) and the coordinates X, Y, Z",
                    arg.name
                ))
            }
        }
    }
    let mut values = Vec::new();
    let mut eval = |args: &[(&str, f64)]| -> Result<(), String> {
        let v = f
            .eval_named(args)
            .map_err(|e| format!("`{}`: {e}", arg.name))?;
        values.push(v);
        Ok(())
    };
    for (n, x) in vars.coords.iter().enumerate() {
        let xyz = [("X", x[0]), ("Y", x[1]), ("Z", x[2])];
        match &vars.temps {
            Some(fields) if params.contains(&"TEMP") => {
                for field in fields {
                    let t = field[n];
                    if vars.through_thickness {
                        return Err(format!(
                            "a function of TEMP on shell cell {cell}, heated through its thickness (CREA_RESU/PREP_VARC): code_aster evaluates it at each sub-point of the thickness (the behaviour integrated layer by layer in STAT_NON_LINE, dxmate's mean temperature in MECA_STATIQUE), not reproduced"
                        ));
                    }
                    if t.is_nan() {
                        return Err(format!(
                            "the temperature field has no value at a node of cell {cell}"
                        ));
                    }
                    eval(&[("TEMP", t), xyz[0], xyz[1], xyz[2]])?;
                }
            }
            _ => eval(&xyz)?,
        }
    }
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if hi - lo > 1e-12 * lo.abs().max(hi.abs()) {
        return Err(format!(
            "`{}` ({}) takes values from {lo} to {hi} over cell {cell} (its nodes, every instant of the temperature): aster's elements take one {} per cell, constant in time",
            arg.name,
            params.join(", "),
            arg.keyword
        ));
    }
    Ok(values.first().copied().unwrap_or(f64::NAN))
}

/// The material of one cell with ELAS_FO: E, NU, RHO, AMOR_ALPHA,
/// AMOR_BETA as constants and ALPHA converted (`alfint`), or marked
/// unresolved with the reason, located by `locate`.
pub fn resolve(
    base: &Material,
    fo: &ElasFo,
    vars: &CellVars,
    locate: &dyn Fn(Span) -> String,
) -> Material {
    let mut m = base.clone();
    let fail = |arg: &FoArg, why: String| {
        format!(
            "not supported yet: DEFI_MATERIAU/ELAS_FO/{}: {why} ({})",
            arg.keyword,
            locate(arg.span)
        )
    };
    let get = |arg: &FoArg| one_value(arg, vars).map_err(|why| fail(arg, why));
    let resolved = (|| -> Result<(), String> {
        m.young = get(&fo.e)?;
        m.poisson = get(&fo.nu)?;
        if !(m.young.is_finite() && m.young > 0.0) {
            return Err(fail(
                &fo.e,
                format!(
                    "E must be positive, got {} on cell {}",
                    m.young, vars.cell_name
                ),
            ));
        }
        if !(-1.0 < m.poisson && m.poisson < 0.5) {
            return Err(fail(
                &fo.nu,
                format!(
                    "NU must be in (-1, 0.5), got {} on cell {}",
                    m.poisson, vars.cell_name
                ),
            ));
        }
        m.density = fo.rho.as_ref().map(get).transpose()?;
        m.amor_alpha = fo.amor_alpha.as_ref().map(get).transpose()?;
        m.amor_beta = fo.amor_beta.as_ref().map(get).transpose()?;
        m.alpha = None;
        m.alpha_fo = None;
        if let Some(a) = &fo.alpha {
            let f = &a.function.0;
            if let Some(c) = constant(f) {
                m.alpha = Some(c);
            } else if let Some(tref) = vars.tref {
                if f.parameters() != ["TEMP"] {
                    return Err(fail(
                        a,
                        format!(
                            "`{}` is a function of {}: ALPHA is a function of TEMP",
                            a.name,
                            f.parameters().join(", ")
                        ),
                    ));
                }
                let converted = match fo.temp_def_alpha {
                    Some(tdef) => alfint(f, tref, tdef, fo.precision)
                        .map_err(|why| fail(a, format!("`{}`: {why}", a.name)))?,
                    None => None,
                };
                // code_aster takes α(T) (T − T_ref) at each Gauss point
                // with T interpolated there; aster's free strain is
                // nodal, interpolated: the same only where T is uniform
                // over the cell (at every instant of the field, hence
                // between them).
                for field in vars.temps.iter().flatten() {
                    let lo = field.iter().copied().fold(f64::INFINITY, f64::min);
                    let hi = field.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    if hi - lo > 1e-12 * lo.abs().max(hi.abs()).max(1.0) {
                        return Err(fail(
                            a,
                            format!(
                                "`{}` (a function of TEMP) on cell {}, whose temperature is not uniform (from {lo} to {hi}): code_aster takes α(T)(T − T_ref) at each Gauss point, aster's thermal strain is interpolated from the nodes",
                                a.name, vars.cell_name
                            ),
                        ));
                    }
                }
                m.alpha_fo = Some(LoadFunction(match converted {
                    Some(t) => Rc::new(Function::Tabulated(t)),
                    None => a.function.0.clone(),
                }));
            }
        }
        Ok(())
    })();
    if let Err(why) = resolved {
        m.young = f64::NAN;
        m.poisson = f64::NAN;
        m.density = None;
        m.unresolved = Some(why);
    }
    m
}

/// AFFE_MATERIAU's cells with their ELAS_FO resolved ([`resolve`]): one
/// material per distinct set of values (cells of equal values share it).
pub fn resolve_cells(
    mesh: &aster_mesh::Mesh,
    cells: std::collections::BTreeMap<aster_mesh::CellId, Rc<Material>>,
    temperature: Option<&crate::concept::Temperature>,
    locate: &dyn Fn(Span) -> String,
) -> std::collections::BTreeMap<aster_mesh::CellId, Rc<Material>> {
    type Key = (usize, Vec<u64>, Option<String>);
    let mut shared: std::collections::HashMap<Key, Rc<Material>> = Default::default();
    let bits = |v: Option<f64>| v.map_or(u64::MAX, f64::to_bits);
    cells
        .into_iter()
        .map(|(cell, mat)| {
            let Some(fo) = mat.elas_fo.as_ref().filter(|fo| !fo.is_constant()) else {
                return (cell, mat);
            };
            let c = mesh.cell(cell);
            let heated = temperature.filter(|t| t.cells.contains(&cell) && !t.fields.is_empty());
            let name = mesh.cell_name(cell);
            let vars = CellVars {
                coords: c.nodes.iter().map(|&n| mesh.coord(n)).collect(),
                temps: heated.map(|t| {
                    t.fields
                        .iter()
                        .map(|(_, v)| c.nodes.iter().map(|n| v[n.0 as usize]).collect())
                        .collect()
                }),
                tref: heated.map(|t| t.tref),
                cell_name: &name,
                through_thickness: heated.is_some_and(|t| t.shell.is_some()),
            };
            let m = resolve(&mat, fo, &vars, locate);
            let key = (
                Rc::as_ptr(&mat) as usize,
                vec![
                    m.young.to_bits(),
                    m.poisson.to_bits(),
                    bits(m.density),
                    bits(m.alpha),
                    bits(m.amor_alpha),
                    bits(m.amor_beta),
                    m.alpha_fo.is_some() as u64,
                ],
                m.unresolved.clone(),
            );
            let m = shared.entry(key).or_insert_with(|| Rc::new(m)).clone();
            (cell, m)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(vale: &[f64]) -> Function {
        Function::Tabulated(Tabulated::from_pairs("TEMP", vale).unwrap())
    }

    /// Away from T_ref, each abscissa takes the exact conversion; between
    /// abscissae the converted values are interpolated (not the formula).
    #[test]
    fn alfint_converts_at_the_abscissae_and_interpolates_between() {
        let a = table(&[0.0, 1.0e-5, 100.0, 1.2e-5, 200.0, 1.6e-5]);
        let (tref, tdef) = (20.0, 0.0);
        let conv = alfint(&a, tref, tdef, 1.0).unwrap().unwrap();
        let aref = 1.04e-5;
        let exact = |t: f64, at: f64| (at * (t - tdef) - aref * (tref - tdef)) / (t - tref);
        for (t, at) in [(0.0, 1.0e-5), (100.0, 1.2e-5), (200.0, 1.6e-5)] {
            let got = conv.eval(t).unwrap();
            assert!((got - exact(t, at)).abs() < 1e-18, "{t}: {got}");
        }
        let mid = conv.eval(150.0).unwrap();
        assert!((mid - 0.5 * (exact(100.0, 1.2e-5) + exact(200.0, 1.6e-5))).abs() < 1e-18);
        // The formula itself at 150 differs: code_aster interpolates.
        let a150 = 1.4e-5;
        assert!((mid - exact(150.0, a150)).abs() > 1e-8);
    }

    /// An abscissa within PRECISION of T_ref takes α(T_ref) + dα (T_ref −
    /// T_def), dα the mean of the slopes to its neighbours (one-sided at
    /// the ends).
    #[test]
    fn alfint_uses_the_slope_near_the_reference_temperature() {
        let a = table(&[0.0, 1.0e-5, 20.0, 1.1e-5, 100.0, 1.5e-5]);
        let (tref, tdef) = (20.5, 10.0);
        let conv = alfint(&a, tref, tdef, 1.0).unwrap().unwrap();
        let aref = 1.1e-5 + 0.5 * (0.4e-5 / 80.0);
        let d = 0.5 * ((1.5e-5 - aref) / (100.0 - tref) + (aref - 1.0e-5) / (tref - 0.0));
        let got = conv.values()[1];
        assert!((got - (aref + d * (tref - tdef))).abs() < 1e-18, "{got}");
        // The first abscissa (20 away) takes the formula.
        let exact0 = (1.0e-5 * (0.0 - tdef) - aref * (tref - tdef)) / (0.0 - tref);
        assert!((conv.values()[0] - exact0).abs() < 1e-18);
        // At an end: the one-sided slope.
        let b = table(&[0.0, 1.0e-5, 100.0, 1.5e-5]);
        let conv = alfint(&b, 99.5, tdef, 1.0).unwrap().unwrap();
        let aref = b.eval(99.5).unwrap();
        let d = (aref - 1.0e-5) / (99.5 - 0.0);
        assert!((conv.values()[1] - (aref + d * (99.5 - tdef))).abs() < 1e-18);
    }

    #[test]
    fn alfint_keeps_constants_and_refuses_formulas_and_far_one_point_tables() {
        let c = Function::Constant {
            parameter: "TOUTPARA".into(),
            value: 1e-5,
        };
        assert_eq!(alfint(&c, 20.0, 0.0, 1.0), Ok(None));
        let one = table(&[20.0, 1e-5]);
        assert_eq!(alfint(&one, 20.0, 20.5, 1.0), Ok(None));
        let err = alfint(&one, 20.0, 0.0, 1.0).unwrap_err();
        assert!(err.contains("MATERIAL1_42"), "{err}");
        let f = Function::Formula {
            parameters: vec!["TEMP".into()],
            eval: Rc::new(|_: &[(String, f64)]| Ok(1e-5)),
        };
        let err = alfint(&f, 20.0, 0.0, 1.0).unwrap_err();
        assert!(err.contains("DEFI_FONCTION"), "{err}");
    }
}
