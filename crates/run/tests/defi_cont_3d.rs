//! code_aster 17's mortar contact in 3D (DEFI_CONT + MECA_NON_LINE) on the
//! project's scenes: comm/dc3d_blocks.comm (two blocks pressed by a
//! pressure, non-matching QUAD4/QUAD4 or QUAD4/TRIA3 faces, slave on
//! either side, linear and quadratic meshes) and comm/dc3d_tilted.comm
//! (the same blocks turned so that no face is parallel to a coordinate
//! plane, pressed by an imposed displacement): every TEST_RESU against the
//! analytic state at 1e-6. The penalised method (ALGO_CONT='PENALISATION')
//! on the same blocks and tilted blocks (comm/dc3d_penalised.comm,
//! comm/dc3d_tilted_penalised.comm: the interpenetration p h_F / COEF_CONT,
//! also under GREEN_LAGRANGE). And the refusals of what is not reproduced
//! in 3D, located before anything is solved. And the Lagrangian and
//! penalised friction on faces (comm/dc3d_friction.comm,
//! comm/dc3d_penalised_friction.comm).

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &str, name: &str, mesh: &Path) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-dc3d-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.comm"));
    std::fs::write(&file, comm).unwrap();
    let case = aster_run::program::prepare(&file, Some(mesh), &dir).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

fn scene(name: &str) -> String {
    std::fs::read_to_string(root().join("comm").join(name)).unwrap()
}

#[test]
fn blocks_pass_the_patch_test_on_hexa_and_tetra_meshes() {
    for mesh in ["dc3d_blocks.mail", "lac3d_patch.mail"] {
        let outcome = run(
            &scene("dc3d_blocks.comm"),
            "blocks",
            &root().join("comm").join(mesh),
        );
        assert!(outcome.error.is_none(), "{mesh}: {:?}", outcome.error);
        // 2 meshes (linear, quadratic) × 2 slave sides × 8 values × 2
        // (non-regression and analytic).
        assert_eq!((outcome.tally.ok, outcome.tally.nook), (64, 0), "{mesh}");
    }
}

/// Runs `comm/dc3d_tilted.comm` with its progress written to a `.mess`
/// file; gives the outcome and the Newton iterations of each MECA_NON_LINE
/// (one instant each).
fn run_tilted() -> (aster_run::program::Outcome, Vec<usize>) {
    let dir = std::env::temp_dir().join(format!("aster-dc3d-tilted-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut case = aster_run::program::prepare(
        &root().join("comm/dc3d_tilted.comm"),
        Some(&root().join("comm/dc3d_tilted.mail")),
        &dir,
    )
    .unwrap();
    let mess = dir.join("tilted.mess");
    case.report_files.push(mess.clone());
    case.mess = Some(mess.clone());
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let text = std::fs::read_to_string(&mess).unwrap_or_default();
    let _ = std::fs::remove_dir_all(dir);
    let iterations = text
        .lines()
        .filter_map(|l| l.split("converged in ").nth(1))
        .map(|rest| rest.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    (outcome, iterations)
}

/// At MECA_NON_LINE's default RESI_GLOB_RELA (1e-6) every value is within
/// 1e-6 of the analytic one: the Lagrangian tangent on faces is
/// code_aster's analytic one (the slave normal turning, the master point
/// sliding). With the normals frozen over an iteration (before) Newton
/// converged linearly: 9, 7, 5 and 5 iterations, and the values stopped
/// 2e-6 to 1e-5 off.
#[test]
fn a_tilted_interface_passes_the_patch_test() {
    let (outcome, iterations) = run_tilted();
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (48, 0));
    // Linear mesh (slave up, slave down), then quadratic.
    assert_eq!(iterations.len(), 4, "{iterations:?}");
    assert!(iterations[..2].iter().all(|&n| n <= 7), "{iterations:?}");
    assert!(iterations[2..].iter().all(|&n| n <= 4), "{iterations:?}");
}

/// VARIANTE='CLASSIQUE' on faces (frictionless; code_aster's
/// finite-difference matrix, `laMatr_diff`): the blocks' and the tilted
/// blocks' patch tests, every value within 1e-6 of the analytic one, in
/// at most 3 Newton iterations per step.
#[test]
fn classique_blocks_pass_the_patch_tests_in_3d() {
    let classique = |comm: &str, anchor: &str| {
        let edited = comm.replace(
            anchor,
            &anchor.replace("ZONE=_F(", "ZONE=_F(VARIANTE=\"CLASSIQUE\", "),
        );
        assert_ne!(edited, comm, "the scene's ZONE moved");
        edited
    };
    for mesh in ["dc3d_blocks.mail", "lac3d_patch.mail"] {
        let outcome = run(
            &classique(
                &scene("dc3d_blocks.comm"),
                "ZONE=_F(GROUP_MA_ESCL=slaves[j]",
            ),
            "classique",
            &root().join("comm").join(mesh),
        );
        assert!(outcome.error.is_none(), "{mesh}: {:?}", outcome.error);
        assert_eq!((outcome.tally.ok, outcome.tally.nook), (64, 0), "{mesh}");
    }
    let outcome = run(
        &classique(
            &scene("dc3d_tilted.comm"),
            "ZONE=_F(GROUP_MA_ESCL=slaves[j]",
        ),
        "classique_tilted",
        &root().join("comm/dc3d_tilted.mail"),
    );
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (48, 0));
}

#[test]
fn penalised_blocks_interpenetrate_by_the_analytic_amount() {
    for mesh in ["dc3d_blocks.mail", "lac3d_patch.mail"] {
        let outcome = run(
            &scene("dc3d_penalised.comm"),
            "penalised",
            &root().join("comm").join(mesh),
        );
        assert!(outcome.error.is_none(), "{mesh}: {:?}", outcome.error);
        // 2 meshes × 2 slave sides × 6 values, and 3 values under
        // GREEN_LAGRANGE, × 2 (non-regression and analytic).
        assert_eq!((outcome.tally.ok, outcome.tally.nook), (54, 0), "{mesh}");
    }
}

#[test]
fn a_tilted_penalised_interface_interpenetrates_by_the_analytic_amount() {
    let outcome = run(
        &scene("dc3d_tilted_penalised.comm"),
        "tilted_penalised",
        &root().join("comm/dc3d_tilted.mail"),
    );
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (48, 0));
}

/// comm/dc3d_friction.comm: a block pressed on a wider clamped block with
/// Coulomb friction (ALGO_CONT='LAGRANGIEN', LAGS_C, LAGS_F1, LAGS_F2 the
/// global components of the contact force): under a uniform shear below
/// μ p it sticks, the exact uniform state (multipliers (−τ, 0, p), the
/// slave nodes still); dragged far, every slave node is on the cone
/// LAGS_C = −μ LAGS_F2 and the reactions' DX/DZ = −μ, to 1e-8.
#[test]
fn a_block_sticks_below_mu_p_and_slides_at_mu_p_in_3d() {
    let outcome = run(
        &scene("dc3d_friction.comm"),
        "friction",
        &root().join("comm/dc3d_friction.mail"),
    );
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (38, 0));
    // On quadratic faces (the mesh made quadratic) the sliding does not
    // converge: refused at the zone, before anything is solved.
    let comm = scene("dc3d_friction.comm").replace(
        "mesh = LIRE_MAILLAGE(FORMAT=\"ASTER\", UNITE=20)",
        "mesh = LIRE_MAILLAGE(FORMAT=\"ASTER\", UNITE=20)\n\
         mesh = CREA_MAILLAGE(MAILLAGE=mesh, LINE_QUAD=_F(TOUT=\"OUI\"))",
    );
    let outcome = run(
        &comm,
        "friction_quad",
        &root().join("comm/dc3d_friction.mail"),
    );
    let e = outcome.error.expect("must be refused").to_string();
    assert!(
        e.contains("quadratic faces (Quad8) of GROUP_MA_ESCL AB")
            && e.contains("friction_quad.comm:"),
        "{e}"
    );
    assert_eq!(outcome.tally.ok + outcome.tally.nook, 0, "nothing ran: {e}");
}

/// comm/dc3d_penalised_friction.comm: the same block with the penalised
/// friction (no multipliers: p = γ(−g), the friction force γ times the
/// step's slip up to μp): pressed, the slave face sinks by p/γ; under a
/// uniform shear below μp it slips by τ/γ in the step; dragged with the
/// sides loaded by μp, every point slides (DX = 0.1 − μp/G, the reactions'
/// DX/DZ = −μ), each the exact uniform state, at 1e-6 (measured ≤ 1e-12);
/// the same on the mesh made quadratic (QUAD8 faces).
#[test]
fn a_penalised_block_sticks_and_slides_in_3d() {
    let mesh = root().join("comm/dc3d_friction.mail");
    let outcome = run(
        &scene("dc3d_penalised_friction.comm"),
        "pena_friction",
        &mesh,
    );
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (24, 0));
    // On the mesh made quadratic (QUAD8 faces, FPG7 on the polygons) the
    // same exact states.
    let comm = scene("dc3d_penalised_friction.comm").replace(
        "mesh = LIRE_MAILLAGE(FORMAT=\"ASTER\", UNITE=20)",
        "mesh = LIRE_MAILLAGE(FORMAT=\"ASTER\", UNITE=20)\n\
         mesh = CREA_MAILLAGE(MAILLAGE=mesh, LINE_QUAD=_F(TOUT=\"OUI\"))",
    );
    let outcome = run(&comm, "pena_friction_quad", &mesh);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (24, 0));
}

#[test]
fn what_is_not_reproduced_in_3d_is_refused_at_its_keyword() {
    let mesh = root().join("comm/dc3d_blocks.mail");
    for (edit, expected) in [
        // code_aster 2025 has no 3D Nitsche contact element.
        (
            "ALGO_CONT=\"NITSCHE\", ",
            "no contact element in code_aster 17",
        ),
        // The CLASSIQUE variant's friction (laVect_cf_std on faces).
        (
            "VARIANTE=\"CLASSIQUE\", FROTTEMENT=\"OUI\", TYPE_FROT=\"COULOMB\", COULOMB=0.3, ",
            "friction of code_aster 17's CLASSIQUE mortar contact in 3D",
        ),
    ] {
        let comm = scene("dc3d_blocks.comm").replace(
            "ZONE=_F(GROUP_MA_ESCL=slaves[j]",
            &format!("ZONE=_F({edit}GROUP_MA_ESCL=slaves[j]"),
        );
        let outcome = run(&comm, "refused", &mesh);
        let e = outcome.error.expect("must be refused").to_string();
        assert!(e.contains(expected) && e.contains("refused.comm:"), "{e}");
        assert_eq!(outcome.tally.ok + outcome.tally.nook, 0, "nothing ran: {e}");
    }
    // Shells: code_aster's shell contact (thicknesses of CARA_ELEM).
    let comm = "from code_aster.MacroCommands.defi_cont import DEFI_CONT\n\
        DEBUT(CODE='OUI')\n\
        mesh = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\n\
        model = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(GROUP_MA=('ESCH', 'ESCB'), \
        PHENOMENE='MECANIQUE', MODELISATION='DKT'))\n\
        contact = DEFI_CONT(MODELE=model, ZONE=_F(GROUP_MA_ESCL='ESCH', GROUP_MA_MAIT='ESCB'))\n\
        FIN()\n";
    let e = run(comm, "shells", &mesh)
        .error
        .expect("must be refused")
        .to_string();
    assert!(
        e.contains("shells (DKT, COQUE_3D)") && e.contains("shells.comm:5:"),
        "{e}"
    );
    // TRIA7 faces: code_aster's pairing has none (`cellSetType`).
    let comm = scene("dc3d_blocks.comm").replace(
        "quad = CREA_MAILLAGE(MAILLAGE=mesh, LINE_QUAD=_F(TOUT=\"OUI\"))",
        "quad = CREA_MAILLAGE(MAILLAGE=mesh, LINE_QUAD=_F(TOUT=\"OUI\"))\n\
         quad = CREA_MAILLAGE(MAILLAGE=quad, MODI_MAILLE=_F(TOUT=\"OUI\", OPTION=\"TRIA6_7\"))",
    );
    let outcome = run(&comm, "tria7", &root().join("comm/lac3d_patch.mail"));
    let e = outcome.error.expect("must be refused").to_string();
    assert!(
        e.contains("TRIA7 cells in GROUP_MA_") && e.contains("tria7.comm:"),
        "{e}"
    );
}
