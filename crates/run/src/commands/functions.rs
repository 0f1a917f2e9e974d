//! Commands that make or print functions: RECU_FONCTION, CALC_FONC_INTERP,
//! CALC_FONCTION, IMPR_FONCTION; and the small ones around them:
//! DEFI_LIST_ENTI, DEFI_FICHIER.

use super::inspect::filter_rows;
use super::post::select_steps;
use crate::concept::Concept;
use crate::executor::{store_result, Executor};
use crate::field::Field;
use crate::function::{Extension, Function, Scale, Tabulated};
use crate::select;
use crate::support::{Support, Values};
use crate::table::{Column, ColumnType, Table, Value};
use aster_eval::{CommandCall, CommandOutput, ExecError, Keywords};
use std::path::PathBuf;
use std::rc::Rc;

fn reals(kw: &Keywords, name: &str) -> Vec<f64> {
    kw.simple(name).iter().filter_map(|s| s.as_f64()).collect()
}

/// The interpolation and extensions of a function: (x scale, y scale,
/// left, right).
pub(crate) type Options = (Scale, Scale, Extension, Extension);

/// `INTERPOL` (one value: both axes), `PROL_GAUCHE`, `PROL_DROITE` of the
/// keywords `kw`, each absent one left as in `current`.
pub(crate) fn options(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    current: Options,
) -> Result<Options, ExecError> {
    let (mut sx, mut sy, mut left, mut right) = current;
    for (key, slot) in [("PROL_GAUCHE", &mut left), ("PROL_DROITE", &mut right)] {
        if let Some(v) = kw.str(key) {
            *slot = Extension::from_keyword(v).ok_or_else(|| {
                ex.kw_error(
                    cmd,
                    kw,
                    key,
                    format!("unknown extension `{v}` (EXCLU, CONSTANT, LINEAIRE)"),
                )
            })?;
        }
    }
    let interp: Vec<&str> = kw
        .simple("INTERPOL")
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    let scale = |name: &str| {
        Scale::from_keyword(name).ok_or_else(|| {
            let span = kw.keyword("INTERPOL").map(|k| k.span).unwrap_or_default();
            ex.unsupported(&format!("{cmd}/INTERPOL='{name}'"), span)
        })
    };
    match interp.as_slice() {
        [] => {}
        [one] => {
            sx = scale(one)?;
            sy = sx;
        }
        [x, y, ..] => {
            sx = scale(x)?;
            sy = scale(y)?;
        }
    }
    Ok((sx, sy, left, right))
}

/// `PROL_GAUCHE`, `PROL_DROITE`, `INTERPOL` of the command (defaults: the
/// function's own, i.e. `EXCLU` and `LIN` for a new one).
pub(crate) fn apply_options(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    f: &mut Tabulated,
) -> Result<(), ExecError> {
    (f.scale_x, f.scale_y, f.left, f.right) =
        options(ex, cmd, kw, (f.scale_x, f.scale_y, f.left, f.right))?;
    Ok(())
}

fn tabulated(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    para: &str,
    result: Option<&str>,
    xs: Vec<f64>,
    ys: Vec<f64>,
) -> Result<Rc<Function>, ExecError> {
    let mut f = Tabulated::new(para, xs, ys).map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
    f.result = result.map(str::to_string);
    apply_options(ex, cmd, kw, &mut f)?;
    Ok(Rc::new(Function::Tabulated(f)))
}

/// A real list given by concept (`LIST_PARA=…`).
fn list_of(
    ex: &Executor,
    cmd: &str,
    kw: &Keywords,
    key: &str,
) -> Result<Option<Vec<f64>>, ExecError> {
    match kw.concept(key) {
        Some(c) => Ok(Some((*ex.real_list(c)?).clone())),
        None if kw.contains(key) => {
            Err(ex.kw_error(cmd, kw, key, "a list of reals (DEFI_LIST_REEL) is required"))
        }
        None => Ok(None),
    }
}

const RECU_FONCTION_OWN: &[&str] = &[
    "RESULTAT",
    "NOM_CHAM",
    "NOM_CMP",
    "GROUP_NO",
    "NOEUD",
    "TABLE",
    "PARA_X",
    "PARA_Y",
    "FILTRE",
    "FILTRE/NOM_PARA",
    "FILTRE/CRIT_COMP",
    "FILTRE/VALE",
    "FILTRE/VALE_I",
    "FILTRE/VALE_K",
    "FILTRE/CRITERE",
    "FILTRE/PRECISION",
    "NOM_PARA",
    "NOM_RESU",
    "INTERPOL",
    "PROL_GAUCHE",
    "PROL_DROITE",
    "TITRE",
    "INFO",
];

/// What RECU_FONCTION reads (`crate::support`): its own keywords and the step
/// selection ([`super::post::STEP_SELECTION`]).
pub(crate) const RECU_FONCTION: Support =
    Support::keywords(&crate::support::joined::<
        _,
        { super::post::STEP_SELECTION.len() + RECU_FONCTION_OWN.len() },
    >(super::post::STEP_SELECTION, RECU_FONCTION_OWN));

pub fn recu_fonction(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "RECU_FONCTION";
    let kw = &call.keywords;
    if let Some(t) = kw.concept("TABLE") {
        let table = ex.table(t)?;
        let para = |k: &str| {
            kw.str(k)
                .ok_or_else(|| ExecError::new(format!("{cmd}: TABLE needs {k}")))
        };
        let (px, py) = (para("PARA_X")?, para("PARA_Y")?);
        let column = |p: &str| {
            table.column_index(p).ok_or_else(|| {
                ExecError::new(format!(
                    "{cmd}: table `{}` has no column {p}{}",
                    t.name,
                    select::did_you_mean(p, table.columns.iter().map(|c| c.name.as_str()))
                ))
            })
        };
        let (cx, cy) = (column(px)?, column(py)?);
        let rows = filter_rows(&table, kw.factor("FILTRE"))
            .map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
        let mut xs = Vec::new();
        let mut ys = Vec::new();
        for r in rows {
            let get = |c: usize| {
                table.rows[r]
                    .get(c)
                    .and_then(|v| v.as_ref())
                    .and_then(Value::as_f64)
            };
            if let (Some(x), Some(y)) = (get(cx), get(cy)) {
                xs.push(x);
                ys.push(y);
            }
        }
        let f = tabulated(
            ex,
            cmd,
            kw,
            px,
            Some(kw.str("NOM_RESU").unwrap_or(py)),
            xs,
            ys,
        )?;
        return store_result(ex, call, Concept::Function(f));
    }
    let r = ex.required(cmd, kw, "RESULTAT")?;
    let result = ex.result(r)?;
    let mesh = ex.mesh_by_id(result.mesh)?;
    let cham = kw
        .str("NOM_CHAM")
        .ok_or_else(|| ExecError::new(format!("{cmd}: RESULTAT needs NOM_CHAM")))?;
    let cmp = kw
        .str("NOM_CMP")
        .ok_or_else(|| ExecError::new(format!("{cmd}: RESULTAT needs NOM_CMP")))?;
    let node = select::first_node(kw, &mesh).map_err(|e| ExecError::new(format!("{cmd}: {e}")))?;
    let steps: Vec<&crate::concept::Step> = match list_of(ex, cmd, kw, "LIST_INST")? {
        Some(list) => list
            .iter()
            .map(|&t| {
                result
                    .step_at(
                        t,
                        kw.f64("PRECISION").unwrap_or(1e-6),
                        kw.str("CRITERE") == Some("ABSOLU"),
                    )
                    .ok_or_else(|| {
                        ex.kw_error(
                            cmd,
                            kw,
                            "LIST_INST",
                            format!("the result has no instant {t}"),
                        )
                    })
            })
            .collect::<Result<_, _>>()?,
        None => select_steps(ex, cmd, kw, &result)?,
    };
    let mut xs = Vec::new();
    let mut ys = Vec::new();
    for s in steps {
        let field = s.fields.get(cham).ok_or_else(|| {
            ExecError::new(format!(
                "{cmd}: the result has no field {cham} at INST={} (compute it with CALC_CHAMP; it has {})",
                s.inst,
                s.fields.keys().cloned().collect::<Vec<_>>().join(", ")
            ))
        })?;
        let Field::Nodal(f) = field else {
            return Err(ExecError::new(format!(
                "{cmd}: {cham} is an element field; only nodal fields (GROUP_NO/NOEUD) are read here"
            )));
        };
        let v = f.get(node, cmp).ok_or_else(|| {
            ExecError::new(format!(
                "{cmd}: {cham} has no component {cmp} at node {} (components: {})",
                mesh.node_name(node),
                f.components().join(", ")
            ))
        })?;
        xs.push(s.inst);
        ys.push(v);
    }
    let f = tabulated(
        ex,
        cmd,
        kw,
        "INST",
        Some(kw.str("NOM_RESU").unwrap_or(cmp)),
        xs,
        ys,
    )?;
    store_result(ex, call, Concept::Function(f))
}

/// What CALC_FONC_INTERP reads (`crate::support`).
pub(crate) const CALC_FONC_INTERP: Support = Support::keywords(&[
    "FONCTION",
    "LIST_PARA",
    "VALE_PARA",
    "NOM_PARA",
    "NOM_RESU",
    "INTERPOL",
    "PROL_GAUCHE",
    "PROL_DROITE",
    "TITRE",
    "INFO",
]);

pub fn calc_fonc_interp(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "CALC_FONC_INTERP";
    let kw = &call.keywords;
    let f = ex.function(ex.required(cmd, kw, "FONCTION")?)?;
    let xs = match list_of(ex, cmd, kw, "LIST_PARA")? {
        Some(l) => l,
        None => reals(kw, "VALE_PARA"),
    };
    if xs.is_empty() {
        return Err(ExecError::new(format!(
            "{cmd}: give the abscissae (LIST_PARA or VALE_PARA)"
        )));
    }
    let para = kw
        .str("NOM_PARA")
        .map(str::to_string)
        .or_else(|| f.parameters().first().map(|p| p.to_string()))
        .unwrap_or_else(|| "INST".into());
    let ys = xs
        .iter()
        .map(|&x| {
            f.eval(x)
                .map_err(|e| ExecError::new(format!("{cmd}: at {para}={x}: {e}")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let g = tabulated(ex, cmd, kw, &para, kw.str("NOM_RESU"), xs, ys)?;
    store_result(ex, call, Concept::Function(g))
}

/// The abscissae of a function (tabulated: its points; others: none).
fn abscissae(f: &Function) -> Vec<f64> {
    match f {
        Function::Tabulated(t) => t.abscissae().to_vec(),
        _ => Vec::new(),
    }
}

fn sorted_union(mut xs: Vec<f64>) -> Vec<f64> {
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    xs
}

/// What CALC_FONCTION reads (`crate::support`).
pub(crate) const CALC_FONCTION: Support = Support {
    values: &[Values::new("INTEGRE/METHODE", &["TRAPEZE"])],
    ..Support::keywords(&[
        "COMB",
        "COMB/FONCTION",
        "COMB/COEF",
        "INTEGRE",
        "INTEGRE/FONCTION",
        "INTEGRE/METHODE",
        "INTEGRE/COEF",
        "ABS",
        "ABS/FONCTION",
        "LIST_PARA",
        "NOM_PARA",
        "NOM_RESU",
        "INTERPOL",
        "PROL_GAUCHE",
        "PROL_DROITE",
        "TITRE",
        "INFO",
    ])
};

pub fn calc_fonction(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "CALC_FONCTION";
    let kw = &call.keywords;
    let list = list_of(ex, cmd, kw, "LIST_PARA")?;
    let eval = |f: &Function, x: f64| f.eval(x).map_err(|e| ExecError::new(format!("{cmd}: {e}")));
    let param = |f: &Function| {
        f.parameters()
            .first()
            .map(|p| p.to_string())
            .unwrap_or_else(|| "INST".into())
    };
    let (para, xs, ys) = if !kw.factor("COMB").is_empty() {
        let mut terms = Vec::new();
        for occ in kw.factor("COMB") {
            let f = ex.function(ex.required(cmd, occ, "FONCTION")?)?;
            let c = occ
                .f64("COEF")
                .ok_or_else(|| ex.kw_error(cmd, occ, "COEF", "a real coefficient is required"))?;
            terms.push((f, c));
        }
        let xs = match &list {
            Some(l) => l.clone(),
            None => sorted_union(terms.iter().flat_map(|(f, _)| abscissae(f)).collect()),
        };
        if xs.is_empty() {
            return Err(ExecError::new(format!(
                "{cmd}/COMB: formulas have no points of their own; give LIST_PARA"
            )));
        }
        let mut ys = vec![0.0; xs.len()];
        for (f, c) in &terms {
            for (y, &x) in ys.iter_mut().zip(&xs) {
                *y += c * eval(f, x)?;
            }
        }
        (param(&terms[0].0), xs, ys)
    } else if let Some(occ) = kw.factor("INTEGRE").first() {
        let f = ex.function(ex.required(cmd, occ, "FONCTION")?)?;
        let xs = list.clone().unwrap_or_else(|| abscissae(&f));
        let mut ys = Vec::with_capacity(xs.len());
        let mut acc = occ.f64("COEF").unwrap_or(0.0);
        let mut prev: Option<(f64, f64)> = None;
        for &x in &xs {
            let y = eval(&f, x)?;
            if let Some((x0, y0)) = prev {
                acc += 0.5 * (x - x0) * (y + y0);
            }
            ys.push(acc);
            prev = Some((x, y));
        }
        (param(&f), xs, ys)
    } else if let Some(occ) = kw.factor("ABS").first() {
        let f = ex.function(ex.required(cmd, occ, "FONCTION")?)?;
        let xs = list.clone().unwrap_or_else(|| abscissae(&f));
        let ys = xs
            .iter()
            .map(|&x| eval(&f, x).map(f64::abs))
            .collect::<Result<_, _>>()?;
        (param(&f), xs, ys)
    } else {
        return Err(ExecError::new(format!(
            "{cmd}: give COMB, INTEGRE or ABS (the operations supported yet)"
        )));
    };
    let para = kw.str("NOM_PARA").map(str::to_string).unwrap_or(para);
    let g = tabulated(ex, cmd, kw, &para, kw.str("NOM_RESU"), xs, ys)?;
    store_result(ex, call, Concept::Function(g))
}

/// One curve of IMPR_FONCTION: its points and its names.
pub(crate) struct Curve {
    pub(crate) x_name: String,
    pub(crate) y_name: String,
    /// code_aster's legend: LEGENDE, else the name of the function
    /// (FONCTION, FONC_X) the curve comes from.
    pub(crate) legend: Option<String>,
    pub(crate) points: Vec<(f64, f64)>,
}

fn curve(ex: &Executor, occ: &Keywords) -> Result<Curve, ExecError> {
    let cmd = "IMPR_FONCTION/COURBE";
    let list = list_of(ex, cmd, occ, "LIST_PARA")?;
    let legend = occ.str("LEGENDE").map(str::to_string);
    let eval = |f: &Function, x: f64| f.eval(x).map_err(|e| ExecError::new(format!("{cmd}: {e}")));
    if let Some(c) = occ.concept("FONCTION") {
        let f = ex.function(c)?;
        let xs = match (&list, &*f) {
            (Some(l), _) => l.clone(),
            (None, Function::Tabulated(t)) => t.abscissae().to_vec(),
            (None, _) => {
                return Err(ex.kw_error(
                    cmd,
                    occ,
                    "FONCTION",
                    "a formula or constant has no points of its own: give LIST_PARA",
                ))
            }
        };
        let points = xs
            .iter()
            .map(|&x| Ok((x, eval(&f, x)?)))
            .collect::<Result<_, ExecError>>()?;
        return Ok(Curve {
            legend: legend.clone().or_else(|| Some(c.name.clone())),
            x_name: f
                .parameters()
                .first()
                .map(|p| p.to_string())
                .unwrap_or_else(|| "INST".into()),
            y_name: legend.unwrap_or_else(|| c.name.clone()),
            points,
        });
    }
    if let (Some(fx), Some(fy)) = (occ.concept("FONC_X"), occ.concept("FONC_Y")) {
        let (gx, gy) = (ex.function(fx)?, ex.function(fy)?);
        let ts = list.clone().unwrap_or_else(|| abscissae(&gx));
        let points = ts
            .iter()
            .map(|&t| Ok((eval(&gx, t)?, eval(&gy, t)?)))
            .collect::<Result<_, ExecError>>()?;
        return Ok(Curve {
            legend: legend.clone().or_else(|| Some(fx.name.clone())),
            x_name: fx.name.clone(),
            y_name: legend.unwrap_or_else(|| fy.name.clone()),
            points,
        });
    }
    let (xs, ys) = if occ.contains("ABSCISSE") {
        (reals(occ, "ABSCISSE"), reals(occ, "ORDONNEE"))
    } else if let Some(r) = occ.concept("LIST_RESU") {
        let xs = list
            .clone()
            .ok_or_else(|| ex.kw_error(cmd, occ, "LIST_PARA", "LIST_RESU needs LIST_PARA"))?;
        (xs, (*ex.real_list(r)?).clone())
    } else {
        return Err(ExecError::new(format!(
            "{cmd}: give FONCTION, FONC_X/FONC_Y, ABSCISSE/ORDONNEE or LIST_RESU"
        )));
    };
    if xs.len() != ys.len() {
        return Err(ExecError::new(format!(
            "{cmd}: {} abscissae for {} ordinates",
            xs.len(),
            ys.len()
        )));
    }
    Ok(Curve {
        legend: legend.clone(),
        x_name: "ABSCISSE".into(),
        y_name: legend.unwrap_or_else(|| "ORDONNEE".into()),
        points: xs.into_iter().zip(ys).collect(),
    })
}

/// The curves as code_aster's TABLEAU text: one table per curve.
fn tableau(title: Option<&str>, curves: &[Curve]) -> String {
    let mut out = String::new();
    for c in curves {
        let mut t = Table::new(vec![
            Column {
                name: truncate(&c.x_name),
                ty: ColumnType::Real,
            },
            Column {
                name: truncate(&c.y_name),
                ty: ColumnType::Real,
            },
        ]);
        if let Some(title) = title {
            t.title = title.lines().map(str::to_string).collect();
        }
        for &(x, y) in &c.points {
            t.rows
                .push(vec![Some(Value::Real(x)), Some(Value::Real(y))]);
        }
        out.push_str(&t.render());
        out.push('\n');
    }
    out
}

fn truncate(s: &str) -> String {
    s.chars().take(16).collect()
}

/// The curves as an XMGRACE (`.agr`) project: axes, legends, one xy set per
/// curve.
pub(crate) fn xmgrace(kw: &Keywords, curves: &[Curve]) -> String {
    let quoted = |k: &str| kw.str(k).map(|s| s.replace('"', "'"));
    let mut out = String::from("# Grace project file written by aster\n@version 50100\n");
    if let Some(t) = quoted("TITRE") {
        out += &format!("@title \"{t}\"\n");
    }
    if let Some(t) = quoted("SOUS_TITRE") {
        out += &format!("@subtitle \"{t}\"\n");
    }
    for (axis, k) in [("xaxis", "X"), ("yaxis", "Y")] {
        if let Some(l) = quoted(&format!("LEGENDE_{k}")) {
            out += &format!("@{axis} label \"{l}\"\n");
        }
        if kw.str(&format!("ECHELLE_{k}")) == Some("LOG") {
            out += &format!("@{axis}es scale Logarithmic\n");
        }
        let b = reals(kw, &format!("BORNE_{k}"));
        if let [lo, hi] = b.as_slice() {
            out += &format!(
                "@world {}min {}\n@world {}max {}\n",
                k.to_lowercase(),
                crate::pyfmt::py_repr(*lo),
                k.to_lowercase(),
                crate::pyfmt::py_repr(*hi)
            );
        }
    }
    for (i, c) in curves.iter().enumerate() {
        out += &format!(
            "@s{i} legend \"{}\"\n@target G0.S{i}\n@type xy\n",
            c.y_name.replace('"', "'")
        );
        for &(x, y) in &c.points {
            out += &format!(
                "{} {}\n",
                crate::pyfmt::py_repr(x),
                crate::pyfmt::py_repr(y)
            );
        }
        out += "&\n";
    }
    out
}

/// The curves in AGRAF form: the directives (`.digr`: the graph's
/// aspect, then one COURBE block per curve) and the data (`.dogr`: one
/// block of `%12.5E` columns per curve), as code_aster's `TraceAgraf`
/// (code_aster/Objects/table_graph.py) writes them. The plot bounds not
/// given by BORNE_X/BORNE_Y are the curves' bounding box widened by 2.5 %
/// of its size on each side (`SetExtrema(marge=0.05)`).
fn agraf(kw: &Keywords, curves: &[Curve]) -> (String, String) {
    let mut digr = String::new();
    let mut dogr = String::new();
    if curves.is_empty() {
        return (digr, dogr);
    }
    let py = |x: f64| crate::pyfmt::py_repr(x).to_lowercase();
    let log = |k: &str| kw.str(&format!("ECHELLE_{k}")) == Some("LOG");
    // Bounding box of all curves; MinP: the smallest positive value (the
    // lower bound of a LOG axis).
    let (mut x0, mut x1, mut y0, mut y1) = (1e99f64, -1e99f64, 1e99f64, -1e99f64);
    let (mut minp_x, mut minp_y) = (1e99f64, 1e99f64);
    for c in curves {
        for &(x, y) in &c.points {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
            if x > 0.0 {
                minp_x = minp_x.min(x);
            }
            if y > 0.0 {
                minp_y = minp_y.min(y);
            }
        }
    }
    let bounds = |k: &str, lo: f64, hi: f64, minp: f64| -> (f64, f64) {
        let given = reals(kw, &format!("BORNE_{k}"));
        let (mut a, b) = match given.as_slice() {
            [a, b] if a <= b => (*a, *b),
            _ => {
                let mut d = (hi - lo).max(0.01 * hi);
                if d == 0.0 {
                    d = 1e-6;
                }
                (lo - 0.05 * d / 2.0, hi + 0.05 * d / 2.0)
            }
        };
        if log(k) && a < 0.0 {
            a = minp;
        }
        (a, b)
    };
    let (min_x, max_x) = bounds("X", x0, x1, minp_x);
    let (min_y, max_y) = bounds("Y", y0, y1, minp_y);
    // A LOG axis has a grid every 10; a grid not given on either axis
    // leaves both without one.
    let grid = |k: &str| -> i64 {
        if log(k) {
            10
        } else {
            kw.first(&format!("GRILLE_{k}"))
                .and_then(|s| s.as_f64())
                .map_or(-1, |g| g as i64)
        }
    };
    let (grid_x, grid_y) = match (grid("X"), grid("Y")) {
        (x, y) if x < 0 || y < 0 => (0, 0),
        xy => xy,
    };
    digr.push_str(AGRAF_ASPECT);
    let title = kw
        .simple("TITRE")
        .iter()
        .filter_map(|s| s.as_str())
        .collect::<Vec<_>>()
        .join(" ");
    let title = if title.is_empty() {
        "GRAPHIQUE CODE_ASTER".to_string()
    } else {
        title
    };
    digr += &format!("Titre :{title}\n");
    if let Some(t) = kw.str("SOUS_TITRE").filter(|t| !t.is_empty()) {
        digr += &format!("Commentaire :{t}\n");
    }
    digr += &format!("Frequence Grille X :{grid_x}\nFrequence Grille Y :{grid_y}\n");
    for k in ["X", "Y"] {
        digr += &format!("Echelle {k} :{}\n", if log(k) { 1 } else { 0 });
    }
    for k in ["X", "Y"] {
        if let Some(l) = kw.str(&format!("LEGENDE_{k}")).filter(|l| !l.is_empty()) {
            digr += &format!("Legende {k} :{l}\n");
        }
    }
    digr += &format!("Min X : {}\nMax X : {}\n", py(min_x), py(max_x));
    digr += &format!("Min Y : {}\nMax Y : {}\n", py(min_y), py(max_y));
    for (i, c) in curves.iter().enumerate() {
        digr += "  COURBE:\n     Trait :0\n";
        digr += &format!("     Couleur :{}\n     Marqueur :{}\n", i % 13, i % 13);
        digr += "     Frequence Marqueur :0\n";
        if let Some(l) = c.legend.as_deref().filter(|l| !l.is_empty()) {
            digr += &format!("     Legende :{l}\n");
        }
        digr += "     Tri :N\n";
        digr += &format!("     Abscisses : [ {}, 1]\n", i + 1);
        digr += &format!("     Ordonnees : [ {}, 2]\n", i + 1);
        let name = match c.legend.as_deref().filter(|l| !l.is_empty()) {
            Some(l) => l.to_string(),
            None => format!("COURBE_{i}"),
        };
        dogr += &format!("#NOM DE LA FONCTION: {name}\n");
        for &(x, y) in &c.points {
            dogr += &format!(
                " {} {}\n",
                crate::pyfmt::c_exp(x, 12, 5),
                crate::pyfmt::c_exp(y, 12, 5)
            );
        }
        dogr.push('\n');
    }
    (digr, dogr)
}

/// The fixed aspect block that opens AGRAF directives.
const AGRAF_ASPECT: &str = "
ASPECT_GRAPHIQUE:
  En-tete :Departement Analyses Mecaniques et Acoustique
  Aspect :0
  Nombre de vues :1
  Cesure commentaire :40
  MinMax :0
  Fonte Titre :%helvetica-14
  Fonte Axes :%courier-12
  Fonte Autre :%times-12

  DEFAUT_COURBE:
    Couleur (rvb) :     0     0     0

  DEFAUT_COURBE:
    Couleur (rvb) : 65535     0     0

  DEFAUT_COURBE:
    Couleur (rvb) : 11822 35723 22359

  DEFAUT_COURBE:
    Couleur (rvb) :     0     0 65535

  DEFAUT_COURBE:
    Couleur (rvb) : 65535     0 65535

  DEFAUT_COURBE:
    Couleur (rvb) :     0 65535 65535

  DEFAUT_COURBE:
    Couleur (rvb) :     0 65535     0

  DEFAUT_COURBE:
    Couleur (rvb) : 41120 21074 11565

  DEFAUT_COURBE:
    Couleur (rvb) : 65535 42405     0

  DEFAUT_COURBE:
    Couleur (rvb) : 41120  8224 61680

  DEFAUT_COURBE:
    Couleur (rvb) : 65535 65535     0

  DEFAUT_COURBE:
    Couleur (rvb) : 53970 46260 35980

GRAPHIQUE:
";

/// What IMPR_FONCTION reads (`crate::support`).
pub(crate) const IMPR_FONCTION: Support = Support {
    values: &[Values::new("FORMAT", &["TABLEAU", "XMGRACE", "AGRAF"])],
    ..Support::keywords(&[
        "FORMAT",
        "UNITE",
        "UNITE_DIGR",
        "COURBE",
        "COURBE/*",
        "TITRE",
        "SOUS_TITRE",
        "LEGENDE_X",
        "LEGENDE_Y",
        "BORNE_X",
        "BORNE_Y",
        "ECHELLE_X",
        "ECHELLE_Y",
        "GRILLE_X",
        "GRILLE_Y",
        "PILOTE",
        "SEPARATEUR",
        "COMMENTAIRE",
        "COMM_PARA",
        "DEBUT_LIGNE",
        "FIN_LIGNE",
        "FORMAT_R",
        "INFO",
    ])
};

pub fn impr_fonction(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let format = kw.str("FORMAT").unwrap_or("TABLEAU");
    let curves = kw
        .factor("COURBE")
        .iter()
        .map(|occ| curve(ex, occ))
        .collect::<Result<Vec<_>, _>>()?;
    if format == "AGRAF" {
        let (digr, dogr) = agraf(kw, &curves);
        let unit = |k: &str, default: i64| kw.first(k).and_then(|s| s.as_i64()).unwrap_or(default);
        for (u, text) in [(unit("UNITE", 25), dogr), (unit("UNITE_DIGR", 26), digr)] {
            if u == 8 || u == 6 {
                ex.write_report(&text)?;
            } else {
                ex.append_unit(u, &text)?;
            }
        }
        return Ok(CommandOutput::Nothing);
    }
    if format == "XMGRACE" {
        write_xmgrace(ex, kw, "IMPR_FONCTION", &xmgrace(kw, &curves))?;
        return Ok(CommandOutput::Nothing);
    }
    let text = tableau(kw.str("TITRE"), &curves);
    let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(8);
    if unit == 8 || unit == 6 {
        ex.write_report(&text)?;
    } else {
        ex.append_unit(unit, &text)?;
    }
    Ok(CommandOutput::Nothing)
}

/// Writes an xmgrace graph (IMPR_FONCTION, IMPR_TABLE with
/// `FORMAT='XMGRACE'`) to `UNITE` (29 by default) as code_aster's
/// `TraceXmgrace` does, for each `PILOTE`:
/// - `''`: xmgrace's text format (`.agr`);
/// - an image driver (`PNG`, `POSTSCRIPT`, `EPS`, `SVG`…): code_aster runs
///   xmgrace's `gracebat` to draw it; aster draws no images and does what
///   code_aster does when that filter fails (alarm `GRAPH0_9`): the unit
///   holds the text format, and the report says so;
/// - `INTERACTIF`/`INTERACTIF_BG`: code_aster opens xmgrace on a display
///   and deletes the file afterwards: nothing is written, the report says
///   the graph was not shown.
pub(crate) fn write_xmgrace(
    ex: &mut Executor,
    kw: &Keywords,
    command: &str,
    text: &str,
) -> Result<(), ExecError> {
    let pilote = kw.str("PILOTE").unwrap_or("");
    let unit = kw.first("UNITE").and_then(|s| s.as_i64()).unwrap_or(29);
    if pilote.starts_with("INTERACTIF") {
        return ex.write_report(&format!(
            "<A> {command}: PILOTE='{pilote}': the graph is not shown (aster opens no display); unit {unit} is not written\n"
        ));
    }
    if unit == 8 || unit == 6 {
        ex.write_report(text)?;
    } else {
        ex.append_unit(unit, text)?;
    }
    if !pilote.is_empty() {
        ex.write_report(&format!(
            "<A> {command}: PILOTE='{pilote}': the image is not drawn (aster does not run xmgrace); unit {unit} holds xmgrace's text format, as code_aster writes it when its filter fails (GRAPH0_9)\n"
        ))?;
    }
    Ok(())
}

/// What DEFI_LIST_ENTI reads (`crate::support`).
pub(crate) const DEFI_LIST_ENTI: Support = Support {
    values: &[Values::new("OPERATION", &["DEFI"])],
    ..Support::keywords(&[
        "OPERATION",
        "DEBUT",
        "INTERVALLE",
        "INTERVALLE/JUSQU_A",
        "INTERVALLE/PAS",
        "INTERVALLE/NOMBRE",
        "VALE",
        "INFO",
        "TITRE",
    ])
};

pub fn defi_list_enti(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let cmd = "DEFI_LIST_ENTI";
    let kw = &call.keywords;
    let ints = |k: &Keywords, n: &str| -> Vec<i64> {
        k.simple(n).iter().filter_map(|s| s.as_i64()).collect()
    };
    let values: Vec<i64> = if kw.contains("VALE") {
        ints(kw, "VALE")
    } else {
        let mut v = vec![kw
            .first("DEBUT")
            .and_then(|s| s.as_i64())
            .ok_or_else(|| ExecError::new(format!("{cmd}: give VALE or DEBUT + INTERVALLE")))?];
        for occ in kw.factor("INTERVALLE") {
            let last = *v.last().unwrap_or(&0);
            let end = occ
                .first("JUSQU_A")
                .and_then(|s| s.as_i64())
                .ok_or_else(|| ex.kw_error(cmd, occ, "JUSQU_A", "an integer is required"))?;
            let step = if let Some(p) = occ.first("PAS").and_then(|s| s.as_i64()) {
                p
            } else if let Some(n) = occ
                .first("NOMBRE")
                .and_then(|s| s.as_i64())
                .filter(|n| *n > 0)
            {
                if (end - last) % n != 0 {
                    return Err(ex.kw_error(
                        cmd,
                        occ,
                        "NOMBRE",
                        format!("{n} steps do not divide {last}..{end} into integers"),
                    ));
                }
                (end - last) / n
            } else {
                return Err(ex.kw_error(cmd, occ, "PAS", "give PAS or NOMBRE"));
            };
            if step <= 0 || end <= last {
                return Err(ex.kw_error(
                    cmd,
                    occ,
                    "JUSQU_A",
                    format!("the interval {last}..{end} with step {step} does not increase"),
                ));
            }
            let mut x = last + step;
            while x <= end {
                v.push(x);
                x += step;
            }
        }
        v
    };
    // Integer lists are kept as reals: every consumer (NUME_ORDRE lists)
    // reads them through `real_list`.
    let as_reals: Vec<f64> = values.iter().map(|&i| i as f64).collect();
    store_result(ex, call, Concept::RealList(Rc::new(as_reals)))
}

/// What DEFI_FICHIER reads (`crate::support`).
pub(crate) const DEFI_FICHIER: Support = Support {
    values: &[Values::new("ACTION", &["ASSOCIER", "LIBERER", "RESERVER"])],
    ..Support::keywords(&["ACTION", "UNITE", "FICHIER", "TYPE", "ACCES", "INFO"])
};

pub fn defi_fichier(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let kw = &call.keywords;
    let action = kw.str("ACTION").unwrap_or("ASSOCIER");
    let unit = kw.first("UNITE").and_then(|s| s.as_i64());
    match (action, unit, kw.str("FICHIER")) {
        ("ASSOCIER", Some(u), Some(file)) => {
            // Written files land in --out under the file's own name.
            let name = PathBuf::from(file)
                .file_name()
                .map(PathBuf::from)
                .unwrap_or_else(|| PathBuf::from(format!("fort.{u}")));
            ex.options.result_units.insert(u as u32, name);
            Ok(CommandOutput::Nothing)
        }
        ("ASSOCIER", None, file) => {
            // A free unit is asked for: the highest one not in use (as
            // code_aster, which counts down from 99).
            let free = (20..=99u32)
                .rev()
                .find(|u| {
                    !ex.options.result_units.contains_key(u) && !ex.options.units.contains_key(u)
                })
                .ok_or_else(|| ExecError::new("DEFI_FICHIER: no free unit left"))?;
            let name = file
                .and_then(|f| PathBuf::from(f).file_name().map(PathBuf::from))
                .unwrap_or_else(|| PathBuf::from(format!("fort.{free}")));
            ex.options.result_units.insert(free, name);
            Ok(CommandOutput::Value(aster_eval::Scalar::Int(free as i64)))
        }
        _ => Ok(CommandOutput::Nothing),
    }
}
