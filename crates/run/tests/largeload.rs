//! Distributed loads given by functions of the coordinates under large
//! strains (AFFE_CHAR_MECA_F FORCE_CONTOUR / FORCE_FACE / FORCE_INTERNE with
//! DEFORMATION='GREEN_LAGRANGE'), dead loads on the initial geometry as in
//! code_aster, on the project's manufactured solutions:
//! comm/largeload_quad8.comm (plane strain, exact in the QUAD8 space: to
//! round-off) and comm/largeload_blocks.export (a HEXA20 base under a cube,
//! DEFI_CONT mortar contact, MECA_NON_LINE: the error decreasing with the
//! mesh), comm/largeload_chain.export (cont006c's chain: ASSE_MAILLAGE,
//! L2 error norms, convergence rates); and the refusal, before solving, of what does not reproduce
//! code_aster (DEFI_CONTACT with these loads under large strains).

use aster_run::preflight;
use aster_run::RunOptions;
use aster_syntax::CodeMap;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster-largeload-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs a case (a `.comm` with its mesh, or an `.export`); the outcome and
/// the report text.
fn run(case: &Path, mesh: Option<&Path>, name: &str) -> (aster_run::program::Outcome, String) {
    let out = temp(name);
    let prepared = aster_run::program::prepare(case, mesh, &out).unwrap();
    let report = out.join("report.txt");
    let file = std::fs::File::create(&report).unwrap();
    let outcome = aster_run::program::run(&prepared, Box::new(file));
    let text = std::fs::read_to_string(&report).unwrap_or_default();
    let _ = std::fs::remove_dir_all(&out);
    (outcome, text)
}

fn quad8_scene(edits: &[(&str, &str)], name: &str) -> (aster_run::program::Outcome, String) {
    let dir = temp(&format!("{name}-src"));
    let mut text = std::fs::read_to_string(root().join("comm/largeload_quad8.comm")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    let comm = dir.join("case.comm");
    std::fs::write(&comm, text).unwrap();
    let r = run(&comm, Some(&root().join("comm/largeload_quad8.mail")), name);
    let _ = std::fs::remove_dir_all(dir);
    r
}

#[test]
fn green_lagrange_with_coordinate_loads_is_exact_in_the_quad8_space() {
    let (outcome, report) = quad8_scene(&[], "quad8");
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (12, 0), "{report}");
}

#[test]
fn the_same_loads_under_small_strains_miss_the_large_strain_solution() {
    // The check sees the kinematics: the SVK body force and tractions in
    // PETIT give another field (every analytic check but the Dirichlet-free
    // ones fails).
    let (outcome, report) = quad8_scene(&[("\"GREEN_LAGRANGE\"", "\"PETIT\"")], "petit");
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    assert!(outcome.tally.nook >= 6, "{report}");
}

#[test]
fn a_base_under_a_cube_with_mortar_contact_converges_to_the_analytic_field() {
    let (outcome, report) = run(&root().join("comm/largeload_blocks.export"), None, "blocks");
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (24, 0), "{report}");
}

#[test]
fn the_chain_of_cont006c_converges_at_the_expected_rates() {
    // ASSE_MAILLAGE of a HEXA20 base and HEXA8 cubes, MECA_NON_LINE +
    // DEFI_CONT + GREEN_LAGRANGE, L2 error norms at the Gauss points and
    // their rates (TEST_TABLE).
    let (outcome, report) = run(&root().join("comm/largeload_chain.export"), None, "chain");
    assert!(outcome.error.is_none(), "{:?}\n{report}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (4, 0), "{report}");
}

#[test]
fn defi_contact_with_coordinate_loads_under_large_strains_is_refused_before_solving() {
    let src = r#"DEBUT()
mesh = LIRE_MAILLAGE(FORMAT="ASTER")
model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
mat = DEFI_MATERIAU(ELAS=_F(E=1000.0, NU=0.3))
chmat = AFFE_MATERIAU(MAILLAGE=mesh, AFFE=_F(TOUT="OUI", MATER=mat))
times = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))
fx = FORMULE(VALE="10.0 * Y", NOM_PARA=("X", "Y"))
load = AFFE_CHAR_MECA_F(MODELE=model, FORCE_CONTOUR=_F(GROUP_MA="DROITE", FX=fx))
held = AFFE_CHAR_MECA(MODELE=model, DDL_IMPO=_F(GROUP_MA="BAS", DX=0.0, DY=0.0))
contact = DEFI_CONTACT(MODELE=model, FORMULATION="DISCRETE", ZONE=_F(GROUP_MA_MAIT="GAUCHE", GROUP_MA_ESCL="HAUT"))
resu = STAT_NON_LINE(
    MODELE=model,
    CHAM_MATER=chmat,
    EXCIT=(_F(CHARGE=held), _F(CHARGE=load)),
    CONTACT=contact,
    COMPORTEMENT=_F(RELATION="ELAS", DEFORMATION=KIN),
    INCREMENT=_F(LIST_INST=times),
)
FIN()
"#;
    let findings = |edits: &[(&str, &str)]| {
        let mut src = src.to_string();
        for (from, to) in edits {
            assert!(src.contains(from), "{from}");
            src = src.replace(from, to);
        }
        let map = CodeMap::new("case.comm".to_string(), &src);
        let module = aster_syntax::parse_module(&src).expect("parses");
        let mut options = RunOptions::default();
        options
            .units
            .insert(20, root().join("comm/largeload_quad8.mail"));
        let p = preflight::check(&map, &module, &options);
        p.findings
            .0
            .iter()
            .map(|d| d.headline(&map))
            .collect::<Vec<_>>()
    };
    let large = findings(&[("KIN", "\"GREEN_LAGRANGE\"")]);
    assert_eq!(large.len(), 1, "{large:?}");
    assert!(
        large[0].contains("case.comm:15:")
            && large[0].contains("STAT_NON_LINE/CONTACT (DEFI_CONTACT)")
            && large[0].contains("EXCIT/CHARGE=load"),
        "{large:?}"
    );
    // Under small strains, or with a load of the time only, nothing.
    assert_eq!(findings(&[("KIN", "\"PETIT\"")]), Vec::<String>::new());
    let of_time = findings(&[
        ("KIN", "\"GREEN_LAGRANGE\""),
        (
            "\"10.0 * Y\", NOM_PARA=(\"X\", \"Y\")",
            "\"10.0 * INST\", NOM_PARA=\"INST\"",
        ),
    ]);
    assert_eq!(of_time, Vec::<String>::new());
}
