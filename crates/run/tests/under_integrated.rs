//! Under-integrated modelisations (`3D_SI`, `AXIS_SI`, `C_PLAN_SI`,
//! `D_PLAN_SI`) on the project's scenes, and the refusal of SIMO_MIEHE
//! nodal forces with contact. code_aster's `_SI` QUAD8, HEXA20 and TETRA10
//! elements integrate their stiffness with 2×2, 2×2×2 and 4 points (their
//! mass keeps the full family); validated against code_aster on ssna303a
//! (AXIS_SI, GDEF_LOG and SIMO_MIEHE, 24 TEST_RESU, `.ci/devset`). The
//! HEXA8 of 3D_SI is code_aster's one-point element with hourglass
//! stabilisation (aster-fem's `hexs8`).

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(comm: &str, mesh: &str, name: &str) -> aster_run::program::Outcome {
    let dir = std::env::temp_dir().join(format!("aster-si-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.comm"));
    std::fs::write(&file, comm).unwrap();
    let case = aster_run::program::prepare(&file, Some(&root().join(mesh)), &dir).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(dir);
    outcome
}

fn punch(modelisation: &str, extra: &str) -> String {
    let comm = std::fs::read_to_string(root().join("comm/quad8_punch.comm")).unwrap();
    assert!(comm.contains("MODELISATION=\"3D\""));
    comm.replace(
        "MODELISATION=\"3D\"",
        &format!("MODELISATION=\"{modelisation}\""),
    )
    .replace("\nFIN()", &format!("\n{extra}\nFIN()"))
}

/// σzz at a Gauss point of an upper block cell (the uniform −F).
fn sizz_at(point: usize) -> String {
    format!(
        "mesh = DEFI_GROUP(reuse=mesh, MAILLAGE=mesh, CREA_GROUP_MA=_F(NOM=\"C1\", MAILLE=\"M1\"))\n\
         TEST_RESU(RESU=_F(INST=1.0, RESULTAT=result, NOM_CHAM=\"SIEF_ELGA\", GROUP_MA=\"C1\", \
         POINT={point}, NOM_CMP=\"SIZZ\", VALE_CALC=-20000.0, VALE_REFE=-20000.0, \
         REFERENCE=\"ANALYTIQUE\", PRECISION=1.0e-8))"
    )
}

/// The HEXA20 punch under 3D_SI: the homogeneous answer (DZ = −0.1 on the
/// interface, the consistent QUAD8 reactions, σzz = −20000) is exact with
/// 8 points as with 27, and the cells have 8 points.
#[test]
fn hexa20_punch_under_3d_si_is_exact_with_eight_points() {
    let outcome = run(
        &punch("3D_SI", &sizz_at(8)),
        "comm/quad8_punch.mail",
        "punch8",
    );
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (34, 0));
    // A ninth point exists with 3D (27 points), not with 3D_SI.
    let full = run(&punch("3D", &sizz_at(9)), "comm/quad8_punch.mail", "full9");
    assert!(full.error.is_none(), "{:?}", full.error);
    assert_eq!((full.tally.ok, full.tally.nook), (34, 0));
    let reduced = run(
        &punch("3D_SI", &sizz_at(9)),
        "comm/quad8_punch.mail",
        "punch9",
    );
    let err = format!("{:?}", reduced.error.expect("POINT=9 of an 8-point cell"));
    assert!(err.contains("POINT"), "{err}");
}

/// code_aster's QUAD4 `_SI` elements (`MEDPQS4`, `MECPQS4`: one point,
/// hourglass stabilisation in 2D) are refused at AFFE_MODELE, located.
#[test]
fn stabilised_quad4_si_elements_are_refused_at_affe_modele() {
    let comm = std::fs::read_to_string(root().join("comm/dyna_sliding_block.comm"))
        .unwrap()
        .replace("MODELISATION=\"D_PLAN\"", "MODELISATION=\"D_PLAN_SI\"");
    let outcome = run(&comm, "comm/two_plates.mail", "quad4");
    let err = format!("{:?}", outcome.error.expect("QUAD4 under D_PLAN_SI"));
    assert!(
        err.contains("MODELISATION='D_PLAN_SI' on QUAD4 cells") && err.contains("quad4.comm"),
        "{err}"
    );
}

fn hexs8_scene(name: &str) -> aster_run::program::Outcome {
    let comm = std::fs::read_to_string(root().join(format!("comm/{name}.comm"))).unwrap();
    run(&comm, "comm/hexs8_beam.mail", name)
}

/// The stabilised one-point HEXA8 of 3D_SI (`MECA_HEXS8`, ELAS: ASQBI) is
/// exact in pure bending of a rectangular beam with one element through
/// the section (tip and mid-span deflections and the tip's axial
/// displacement against the closed form to 1e-8); the fully integrated
/// HEXA8 locks (35 % short).
#[test]
fn hexa8_under_3d_si_is_exact_in_pure_bending() {
    let outcome = hexs8_scene("hexs8_bending");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (6, 0));
    let comm = std::fs::read_to_string(root().join("comm/hexs8_bending.comm"))
        .unwrap()
        .replace("MODELISATION=\"3D_SI\"", "MODELISATION=\"3D\"");
    let full = run(&comm, "comm/hexs8_beam.mail", "hexs8_full");
    assert!(full.error.is_none(), "{:?}", full.error);
    assert_eq!((full.tally.ok, full.tally.nook), (0, 6));
}

/// A plastic bar of stabilised HEXA8 (VMIS_ISOT_LINE: ADS) under
/// PETIT_REAC: the one-point SIEF_ELGA and VARI_ELGA against the closed
/// form of the updated-geometry strain sum (1e-8).
#[test]
fn hexa8_under_3d_si_plastic_bar_under_petit_reac() {
    let outcome = hexs8_scene("hexs8_tension");
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (6, 0));
    // No second point: code_aster's RIGI family of MECA_HEXS8 is FPG1.
    let comm = std::fs::read_to_string(root().join("comm/hexs8_tension.comm"))
        .unwrap()
        .replacen("POINT=1,", "POINT=2,", 1);
    let two = run(&comm, "comm/hexs8_beam.mail", "hexs8_p2");
    let err = format!("{:?}", two.error.expect("POINT=2 of a one-point cell"));
    assert!(err.contains("no component SIXX at point 2"), "{err}");
}

/// What the stabilised HEXA8 does not compute is refused: the linear
/// stiffness of MECA_STATIQUE (code_aster's te0392) and nodal forces.
#[test]
fn hexa8_under_3d_si_refuses_what_it_does_not_compute() {
    let comm = std::fs::read_to_string(root().join("comm/hexs8_bending.comm"))
        .unwrap()
        .replace("COMPORTEMENT=_F(RELATION=\"ELAS\", TOUT=\"OUI\"),", "")
        .replace("INCREMENT=_F(LIST_INST=times),", "LIST_INST=times,")
        .replace("CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10),", "")
        .replace("STAT_NON_LINE(", "MECA_STATIQUE(");
    let outcome = run(&comm, "comm/hexs8_beam.mail", "hexs8_lin");
    let err = format!("{:?}", outcome.error.expect("MECA_STATIQUE refused"));
    assert!(err.contains("te0392"), "{err}");
    let comm = std::fs::read_to_string(root().join("comm/hexs8_bending.comm"))
        .unwrap()
        .replace(
            "\nTEST_RESU(",
            "\nresult = CALC_CHAMP(reuse=result, RESULTAT=result, FORCE=\"FORC_NODA\")\nTEST_RESU(",
        );
    let outcome = run(&comm, "comm/hexs8_beam.mail", "hexs8_forc");
    let err = format!("{:?}", outcome.error.expect("FORC_NODA refused"));
    assert!(err.contains("nodal forces"), "{err}");
}

/// Nodal forces of a SIMO_MIEHE result with the discrete contact are
/// refused before the run (ssna111a's cone-tip reaction is 4.85e-5 off
/// code_aster 17's, docs/contact.md); the continuous one is accepted
/// (comm/simo_miehe_contact_forces.comm).
#[test]
fn simo_miehe_nodal_forces_with_contact_are_refused() {
    let comm = std::fs::read_to_string(root().join("comm/finite_strain_contact.comm"))
        .unwrap()
        .replace("DEFORMATION=\"GDEF_LOG\"", "DEFORMATION=\"SIMO_MIEHE\"");
    let outcome = run(&comm, "comm/plastic_block.mail", "simo");
    let err = format!("{:?}", outcome.error.expect("refused"));
    assert!(
        err.contains(
            "FORCE='REAC_NODA' of a result computed with DEFORMATION='SIMO_MIEHE' and the discrete contact"
        ),
        "{err}"
    );
    assert_eq!(outcome.tally.ok, 0);
}
