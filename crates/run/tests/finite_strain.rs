//! The project's finite-strain scenes (comm/finite_strain_3d.comm on
//! comm/finite_strain.mail, comm/finite_strain_2d.comm on
//! comm/finite_strain_2d.mail): homogeneous deformations — uniaxial stretch
//! to 1.5, stretch then a rigid rotation of 90 degrees, simple shear,
//! plane stress, axisymmetric growth, a block compressed by 25 % through
//! discrete and continuous contact — under GREEN_LAGRANGE, GDEF_LOG,
//! SIMO_MIEHE and PETIT_REAC, every TEST_RESU against the closed-form
//! answer of its formulation to 1e-9.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs a scene and returns (OK, NOOK, error).
fn run(comm: &str, mesh: &str, tag: &str) -> (usize, usize, Option<String>) {
    let out = std::env::temp_dir().join(format!("aster-finite-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let case =
        aster_run::program::prepare(&root().join(comm), Some(&root().join(mesh)), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(&out);
    (
        outcome.tally.ok,
        outcome.tally.nook,
        outcome.error.map(|e| format!("{e:?}")),
    )
}

#[test]
fn uniaxial_stretch_of_a_cube_under_every_kinematics() {
    assert_eq!(
        run(
            "comm/finite_strain_3d.comm",
            "comm/finite_strain.mail",
            "3d"
        ),
        (40, 0, None)
    );
}

#[test]
fn rotation_shear_plane_stress_and_axis_match_the_closed_forms() {
    assert_eq!(
        run(
            "comm/finite_strain_2d.comm",
            "comm/finite_strain_2d.mail",
            "2d"
        ),
        (94, 0, None)
    );
}

#[test]
fn contact_is_paired_on_the_deformed_geometry() {
    assert_eq!(
        run(
            "comm/finite_strain_contact.comm",
            "comm/plastic_block.mail",
            "contact"
        ),
        (24, 0, None)
    );
}
