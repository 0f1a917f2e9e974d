//! code_aster 17's mesh methods (comm/mesh_refine.export, written for the
//! project): `mesh.refine(ntimes)`, `convertToQuadratic()`,
//! `convertToLinear()` against closed-form counts, exact linear and
//! uniform-stress solutions on refined meshes and the h**2 convergence of
//! an L2 error; and the static pass refusing, located, every method call
//! aster does not run and a refinement of cells code_aster cannot refine
//! (a quadratic pyramid).

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
    // 73 checks, each against VALE_CALC and the closed form: 46 + 4
    // counts, 2 nodal values and 1 zero error of the linear field, 3 x (5
    // values and 1 zero error) of the uniform stress (HEXA8 refined once
    // and twice, HEXA20 refined once), 1 zero error of the quadratic field
    // on refined QUAD8/TRIA6 cells, 1 convergence slope.
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (146, 0), "{report}");
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
fn quadratic_cells_are_refined_and_what_refine_cannot_place_is_refused() {
    let src = r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
mesh = mesh.refine()
FIN()
"#;
    // QUAD8 (and SEG3) cells are refined, kept quadratic.
    let (p, map) = pass(src, "quad8_punch.mail");
    assert!(p.findings.0.is_empty(), "{:?}", messages(&p, &map));
    // convertToQuadratic still takes linear cells only.
    let again = src.replace("mesh.refine()", "mesh.convertToQuadratic()");
    let (p, map) = pass(&again, "quad8_punch.mail");
    let got = messages(&p, &map);
    assert!(
        got.len() == 1
            && got[0].starts_with(
                "case.comm:3:8: error: not supported: convertToQuadratic() of mesh mesh: cell "
            )
            && got[0].contains("convertToLinear() first"),
        "{got:?}"
    );
    // A quadratic pyramid: code_aster cannot place its sub-pyramids' nodes.
    let dir = std::env::temp_dir().join(format!("aster-refine-pyram-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let mut mail = String::from("COOR_3D\n");
    let corners = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.5, 0.5, 1.0],
    ];
    let mut pts: Vec<[f64; 3]> = corners.to_vec();
    for &[a, b] in aster_mesh::CellType::PYRAM13.corner_edges() {
        pts.push([0, 1, 2].map(|k| 0.5 * (corners[a][k] + corners[b][k])));
    }
    for (i, p) in pts.iter().enumerate() {
        mail += &format!("N{} {} {} {}\n", i + 1, p[0], p[1], p[2]);
    }
    mail += "FINSF\nPYRAM13\nP1";
    for i in 1..=13 {
        mail += &format!(" N{i}");
    }
    mail += "\nFINSF\nFIN\n";
    let path = dir.join("pyram13.mail");
    std::fs::write(&path, mail).expect("the mesh is written");
    let map = CodeMap::new("case.comm".to_string(), src);
    let module = aster_syntax::parse_module(src).expect("the scene parses");
    let mut options = RunOptions::default();
    options.units.insert(20, path);
    let p = preflight::check(&map, &module, &options);
    let got = messages(&p, &map);
    assert!(
        got.len() == 1
            && got[0].starts_with(
                "case.comm:3:8: error: not supported: refine() of mesh mesh: cell P1 is a PYRAM13: aster refines "
            ),
        "{got:?}"
    );
    // CREA_MAILLAGE/RAFFINEMENT (what refine() runs in code_aster) too.
    let command = src.replace(
        "mesh.refine()",
        "CREA_MAILLAGE(MAILLAGE=mesh, RAFFINEMENT=_F(NIVEAU=1))",
    );
    let module = aster_syntax::parse_module(&command).expect("the scene parses");
    let map = CodeMap::new("case.comm".to_string(), &command);
    let p = preflight::check(&map, &module, &options);
    let got = messages(&p, &map);
    assert!(
        got.len() == 1
            && got[0].starts_with(
                "case.comm:3:37: error: not supported yet: CREA_MAILLAGE/RAFFINEMENT: cell P1 is a PYRAM13"
            ),
        "{got:?}"
    );
    let _ = std::fs::remove_dir_all(dir);
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
