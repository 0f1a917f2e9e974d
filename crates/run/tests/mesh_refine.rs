//! code_aster 17's mesh methods (comm/mesh_refine.export, written for the
//! project): `mesh.refine(ntimes)`, `convertToQuadratic()`,
//! `convertToLinear()` against closed-form counts, exact linear and
//! uniform-stress solutions on refined meshes and the h**2 convergence of
//! an L2 error; and the static pass refusing, located, every method call
//! aster does not run and a refinement of quadratic cells.

use aster_run::preflight::{self, Preflight};
use aster_run::RunOptions;
use aster_syntax::CodeMap;

mod scene;

use scene::{root, run_case as run};

#[test]
fn refined_meshes_counts_exact_solutions_and_convergence() {
    let out = std::env::temp_dir().join(format!("aster-mesh-refine-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let (outcome, report) = run(&root().join("comm/mesh_refine.export"), &out);
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    // 62 checks, each against VALE_CALC and the closed form: 46 counts,
    // 2 nodal values and 1 zero error of the linear field, 2 x (5 values
    // and 1 zero error) of the uniform stress, 1 convergence slope.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (124, 0), "{report}");
    assert!(report.contains("L2 errors [0.1367"), "{report}");
    let _ = std::fs::remove_dir_all(out);
}

fn pass(source: &str, mesh: &str) -> (Preflight, CodeMap) {
    let map = CodeMap::new("case.comm".to_string(), source);
    let module = aster_syntax::parse_module(source).expect("the scene parses");
    let mut options = RunOptions::default();
    options.units.insert(20, root().join("comm").join(mesh));
    (preflight::check(&map, &module, &options), map)
}

fn messages(p: &Preflight, map: &CodeMap) -> Vec<String> {
    p.findings.0.iter().map(|d| d.headline(map)).collect()
}

#[test]
fn a_method_aster_does_not_run_is_refused_before_anything_runs() {
    let src = r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
fine = mesh.refine(2)
x = fine.getCoordinates()
model = AFFE_MODELE(MAILLAGE=fine, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
FIN()
"#;
    let (p, map) = pass(src, "refine_plate.mail");
    assert_eq!(
        messages(&p, &map),
        vec!["case.comm:4:5: error: not supported: method getCoordinates() of concept fine (maillage_sdaster); aster runs getName, getMinMaxEdgeSizes, getNumberOfNodes, getNumberOfCells, getCells, refine, convertToLinear, convertToQuadratic"]
    );
    // The methods aster runs pass.
    let ok = src.replace("x = fine.getCoordinates()", "x = fine.getNumberOfNodes()");
    let (p, map) = pass(&ok, "refine_plate.mail");
    assert!(p.findings.0.is_empty(), "{:?}", messages(&p, &map));
}

#[test]
fn refining_quadratic_cells_is_refused_at_the_call() {
    let src = r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
mesh = mesh.refine()
FIN()
"#;
    let (p, map) = pass(src, "quad8_punch.mail");
    let got = messages(&p, &map);
    assert_eq!(got.len(), 1, "{got:?}");
    assert!(
        got[0].starts_with("case.comm:3:8: error: not supported: refine() of mesh mesh: cell ")
            && got[0].contains("convertToLinear() first"),
        "{got:?}"
    );
    // Made linear first, it is refined; made quadratic again, it is not.
    let linear = src.replace("mesh.refine()", "mesh.convertToLinear().refine()");
    let (p, map) = pass(&linear, "quad8_punch.mail");
    assert!(p.findings.0.is_empty(), "{:?}", messages(&p, &map));
    let again = src.replace(
        "mesh.refine()",
        "mesh.convertToLinear().convertToQuadratic().refine()",
    );
    let (p, map) = pass(&again, "quad8_punch.mail");
    assert_eq!(p.findings.0.len(), 1, "{:?}", messages(&p, &map));
    // CREA_MAILLAGE/RAFFINEMENT (what refine() runs in code_aster) too.
    let command = src.replace(
        "mesh.refine()",
        "CREA_MAILLAGE(MAILLAGE=mesh, RAFFINEMENT=_F(NIVEAU=1))",
    );
    let (p, map) = pass(&command, "quad8_punch.mail");
    let got = messages(&p, &map);
    assert!(
        got.len() == 1
            && got[0].starts_with("case.comm:3:37: error: not supported yet: CREA_MAILLAGE/RAFFINEMENT of a mesh whose cell "),
        "{got:?}"
    );
}

#[test]
fn method_arguments_are_bound_as_python_binds_them() {
    for (call, expected) in [
        (
            "mesh.refine(1, 1, 1)",
            "refine() takes at most 2 positional argument(s)",
        ),
        (
            "mesh.refine(level=2)",
            "refine() got an unexpected keyword argument 'level'",
        ),
        (
            "mesh.refine(2, ntimes=2)",
            "refine() got multiple values for argument 'ntimes'",
        ),
    ] {
        let src =
            format!("DEBUT()\nmesh = LIRE_MAILLAGE(FORMAT=\"ASTER\")\nfine = {call}\nFIN()\n");
        let (p, map) = pass(&src, "refine_plate.mail");
        let got = messages(&p, &map);
        assert!(
            got.len() == 1 && got[0].contains(expected),
            "{call}: {got:?}"
        );
    }
}
