//! The Python subset and command calls, through a recording sink.

use aster_eval::*;
use aster_syntax::CodeMap;

#[derive(Default)]
struct Recorder {
    calls: Vec<CommandCall>,
    printed: Vec<String>,
}

impl CommandSink for Recorder {
    fn execute(&mut self, call: &CommandCall) -> Result<CommandOutput, ExecError> {
        self.calls.push(call.clone());
        Ok(CommandOutput::Concept)
    }
    fn print(&mut self, line: &str) {
        self.printed.push(line.to_string());
    }
}

fn run(src: &str) -> Result<Recorder, String> {
    let map = CodeMap::new("t.comm", src);
    let module = aster_syntax::parse_module(src).map_err(|e| e.message)?;
    let mut rec = Recorder::default();
    run_program(&map, &module, &mut rec, RunOptions::default()).map_err(|d| d.render(&map))?;
    Ok(rec)
}

fn reals(k: &Keywords, name: &str) -> Vec<f64> {
    k.simple(name).iter().filter_map(Scalar::as_f64).collect()
}

#[test]
fn python_subset_computes_keyword_values() {
    let rec = run(r#"
from math import *
import math
E = 2.0e11
nu = 0.3
vals = [i * 0.5 for i in range(4) if i != 2]
d = {"a": 1, "b": 2}
total = sum(v for v in d.values())
def young(scale, shift=0.0):
    return E * scale + shift
name = "N%d" % 3 + f"_{total:02d}"
x, (y, z) = 1, (2.0, 3)
while x < 8:
    x *= 2
MAT = DEFI_MATERIAU(ELAS=_F(E=young(0.5, shift=1.0), NU=nu, RHO=sqrt(16.0) + math.pi * 0))
L = DEFI_LIST_REEL(VALE=vals + [max(x, 3), abs(-y), z ** 2, 7 // 2, -7 % 3])
print(name, len(vals), round(2.675, 2), str(1e-5), 10 / 4)
"#)
    .unwrap();
    let mat = &rec.calls[0];
    assert_eq!(mat.command, "DEFI_MATERIAU");
    let elas = &mat.keywords.factor("ELAS")[0];
    assert_eq!(elas.f64("E"), Some(1.0e11 + 1.0));
    assert_eq!(elas.f64("RHO"), Some(4.0));
    let l = &rec.calls[1];
    assert_eq!(
        reals(&l.keywords, "VALE"),
        vec![0.0, 0.5, 1.5, 8.0, 2.0, 9.0, 3.0, 2.0]
    );
    assert_eq!(rec.printed, vec!["N3_03 3 2.67 1e-05 2.5"]);
}

#[test]
fn commands_in_loops_and_functions_get_distinct_concepts() {
    let rec = run(r#"
MA = LIRE_MAILLAGE(FORMAT="MED")
def model(m, modelisation):
    return AFFE_MODELE(MAILLAGE=m, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION=modelisation))
models = {}
for mod in ("D_PLAN", "AXIS"):
    models[mod] = model(MA, mod)
MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU=_F(GROUP_MA_PEAU="AB"))
FIN()
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="3D"))
"#)
    .unwrap();
    // FIN stops the program: the last AFFE_MODELE is not run.
    let names: Vec<&str> = rec.calls.iter().map(|c| c.command.as_str()).collect();
    assert_eq!(
        names,
        [
            "LIRE_MAILLAGE",
            "AFFE_MODELE",
            "AFFE_MODELE",
            "MODI_MAILLAGE",
            "FIN"
        ]
    );
    let ma = rec.calls[0].result.clone().unwrap();
    assert_eq!(ma.typ, "maillage_sdaster");
    assert_eq!(rec.calls[1].keywords.concept("MAILLAGE"), Some(&ma));
    assert_ne!(
        rec.calls[1].result.as_ref().unwrap().id,
        rec.calls[2].result.as_ref().unwrap().id
    );
    let modi = &rec.calls[3];
    assert_eq!(modi.reuse.as_ref().map(|c| c.id), Some(ma.id));
    assert_eq!(modi.result.as_ref().map(|c| c.id), Some(ma.id));
}

#[test]
fn defaults_are_filled_and_blocks_follow_values() {
    let rec = run(r#"
MA = LIRE_MAILLAGE(FORMAT="MED")
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
C = DEFI_CONTACT(MODELE=MO, ZONE=_F(GROUP_MA_MAIT="A", GROUP_MA_ESCL="B"))
"#)
    .unwrap();
    let c = &rec.calls[2];
    assert_eq!(c.result.as_ref().unwrap().typ, "char_contact");
    let k = &c.keywords;
    assert_eq!(k.str("FORMULATION"), Some("DISCRETE"));
    assert!(k.keyword("FORMULATION").unwrap().defaulted);
    // REAC_GEOM='AUTOMATIQUE' by default opens the block of ITER_GEOM_MAXI.
    assert_eq!(k.str("REAC_GEOM"), Some("AUTOMATIQUE"));
    assert_eq!(k.first("ITER_GEOM_MAXI").and_then(Scalar::as_i64), Some(10));
    // No keyword of the continuous formulation.
    assert!(!k.contains("ALGO_RESO_CONT"));
    let zone = &k.factor("ZONE")[0];
    assert_eq!(zone.str("GROUP_MA_ESCL"), Some("B"));
    assert_eq!(zone.str("APPARIEMENT"), Some("MAIT_ESCL"));
}

#[test]
fn formule_is_kept_and_evaluated_later() {
    struct Keep(Vec<std::rc::Rc<Formula>>);
    impl CommandSink for Keep {
        fn execute(&mut self, _: &CommandCall) -> Result<CommandOutput, ExecError> {
            Ok(CommandOutput::Concept)
        }
        fn formula(&mut self, _: &ConceptRef, f: &std::rc::Rc<Formula>) {
            self.0.push(f.clone());
        }
    }
    let src = r#"
from math import sin, pi
A = 2.0
F = FORMULE(VALE="A * sin(pi * X / 2) + Y * B", NOM_PARA=("X", "Y"), B=10.0)
G = FORMULE(VALE="F(X, 0.0) ** 2", NOM_PARA="X")
v = G(1.0)
L = DEFI_LIST_REEL(VALE=v)
"#;
    let map = CodeMap::new("f.comm", src);
    let module = aster_syntax::parse_module(src).unwrap();
    let mut keep = Keep(Vec::new());
    run_program(&map, &module, &mut keep, RunOptions::default()).unwrap();
    let f = &keep.0[0];
    assert_eq!(f.params, ["X", "Y"]);
    assert!((f.eval(&[1.0, 0.5]).unwrap() - 7.0).abs() < 1e-12);
    assert!((f.eval_named(&[("Y", 1.0), ("X", 0.0)]).unwrap() - 10.0).abs() < 1e-12);
    assert!(f.eval(&[1.0]).is_err());
    assert!((keep.0[1].eval(&[1.0]).unwrap() - 4.0).abs() < 1e-12);
}

#[test]
fn runner_mode_stops_at_the_first_invalid_command() {
    let err = run(r#"
MAT = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, NUU=1))
L = DEFI_LIST_REEL(VALE=1.0)
"#)
    .err()
    .unwrap();
    assert!(err.contains("t.comm:2:"), "{err}");
    assert!(err.contains("DEFI_MATERIAU/ELAS[1]"), "{err}");
}

#[test]
fn detruire_unbinds_and_co_binds() {
    let err = run(r#"
L = DEFI_LIST_REEL(VALE=1.0)
DETRUIRE(NOM=L)
M = DEFI_LIST_REEL(VALE=L)
"#)
    .err()
    .unwrap();
    assert!(err.contains("name `L` is not defined"), "{err}");
}

#[test]
fn run_time_values_stop_control_flow_precisely() {
    let src = r#"
T = CREA_TABLE(LISTE=_F(PARA="X", LISTE_R=(1.0, 2.0)))
v = T["X", 1] * 2.0
L = DEFI_LIST_REEL(VALE=v)
if v > 1.0:
    pass
"#;
    let map = CodeMap::new("r.comm", src);
    let report = check_source(&map, true);
    let errs: Vec<_> = report.diagnostics.errors().collect();
    assert_eq!(errs.len(), 1, "{}", report.diagnostics.render(&map));
    assert_eq!(errs[0].kind, DiagKind::RunTimeValue);
    assert_eq!(map.location(errs[0].span), "r.comm:5:4");
    assert_eq!(report.calls.len(), 2);
}

#[test]
fn os_environment_and_path_arithmetic() {
    let rec = run(r#"
import os
import os.path as osp
from os.path import join as pj
name = osp.join("dir", "sub/", "case.json")
root = pj("rel", "/abs", "x.med")
stem, ext = osp.splitext(osp.basename("/a/b/mesh.tar.gz"))
os.environ["ASTER_TEST_FC"] = "gfortran"
seen = "ASTER_TEST_FC" in os.environ
print(name, root, stem, ext, os.environ["ASTER_TEST_FC"], seen, os.getenv("ASTER_SURELY_UNSET_ZZ", "dflt"))
"#)
    .unwrap();
    assert_eq!(
        rec.printed,
        vec!["dir/sub/case.json /abs/x.med mesh.tar .gz gfortran True dflt"]
    );
    let err = match run("import os\nos.system('rm -rf /')\n") {
        Ok(_) => panic!("os.system ran"),
        Err(e) => e,
    };
    assert!(
        err.contains("2:4") && err.contains("not supported: `os.system`"),
        "{err}"
    );
    // The file system is code_aster's work directory: not asked here.
    let err = match run("import os.path\nassert os.path.isfile('case.py')\n") {
        Ok(_) => panic!("os.path.isfile answered"),
        Err(e) => e,
    };
    assert!(
        err.contains("2:16") && err.contains("not supported: `os.path.isfile`"),
        "{err}"
    );
}

#[test]
fn trailing_blanks_of_mesh_names_are_not_part_of_them() {
    // code_aster's names are fixed-length Fortran strings: `'POUTRE    '`
    // names the group POUTRE (sdll127b); leading blanks and text keywords
    // are kept as written.
    let rec = run(r#"
MA = LIRE_MAILLAGE(FORMAT="MED")
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(GROUP_MA=("POUTRE    ", " B"), PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
G = DEFI_GROUP(MAILLAGE=MA, CREA_GROUP_NO=_F(GROUP_MA="C  ", NOM="N1  "))
"#)
    .unwrap();
    let affe = &rec.calls[1].keywords.factor("AFFE")[0];
    let groups: Vec<&str> = affe
        .simple("GROUP_MA")
        .iter()
        .filter_map(Scalar::as_str)
        .collect();
    assert_eq!(groups, vec!["POUTRE", " B"]);
    let crea = &rec.calls[2].keywords.factor("CREA_GROUP_NO")[0];
    assert_eq!(crea.str("GROUP_MA"), Some("C"));
}
