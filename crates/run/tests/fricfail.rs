//! Continuous friction increments that failed where code_aster converges
//! (ssnv128m/x/z, ssnv504k): the scene comm/two_plates_friction_adapt.comm
//! (the settings of ssnv128m, whose sliding Newton matrix defeated the
//! symmetric equilibration of the linear solve) against Coulomb's law, and
//! the settings still not reproduced, refused before the solve at their
//! keyword.

mod scene;

/// comm/two_plates_friction_adapt.comm: COEF_CONT = COEF_FROT = 1 against
/// E = 1.3e11, a near-rigid base, ADAPTATION='ADAPT_COEF', SANS_GROUP_NO.
/// Before the two-sided equilibration fallback of `aster_fem::linalg` the
/// first sliding increment failed however cut; now the plates stick, then
/// slide with a friction resultant of μ = 0.3 times the normal one (1e-6).
#[test]
fn unit_coefficients_slide_with_mu_times_the_normal_force() {
    let (ok, nook, err) = scene::run_on(
        &scene::read("two_plates_friction_adapt.comm"),
        "comm/two_plates.mail",
        "fricfail-adapt",
    );
    assert_eq!((ok, nook, err), (8, 0, None));
}

/// A loose RESI_FROT with the generalised Newton friction (ssnv128x's
/// 0.01) is refused at RESI_FROT, before the solve.
#[test]
fn loose_resi_frot_with_newton_friction_is_refused_before_the_solve() {
    let msg = scene::refused_export(
        "two_plates_friction_adapt.comm",
        &["two_plates.mail"],
        &[(
            "    ALGO_RESO_FROT=\"NEWTON\",\n",
            "    ALGO_RESO_FROT=\"NEWTON\",\n    RESI_FROT=0.01,\n",
        )],
        "fricfail-resi-frot",
    );
    assert!(msg.contains("DEFI_CONTACT/RESI_FROT=1e-2"), "{msg}");
    assert!(msg.contains("not supported"), "{msg}");
}

/// COEF_FROT above 1e6 under the cycling treatment (ssnv128z's 1e8 with
/// ADAPTATION='CYCLAGE') is refused at COEF_FROT, before the solve; with
/// ADAPT_COEF (no treatment) the same coefficient is accepted.
#[test]
fn huge_coef_frot_under_the_cycling_treatment_is_refused_before_the_solve() {
    let msg = scene::refused_export(
        "two_plates_friction_adapt.comm",
        &["two_plates.mail"],
        &[
            ("COEF_FROT=1.0,", "COEF_FROT=1.0e8,"),
            ("ADAPTATION=\"ADAPT_COEF\"", "ADAPTATION=\"CYCLAGE\""),
        ],
        "fricfail-coef-frot",
    );
    assert!(msg.contains("DEFI_CONTACT/ZONE/COEF_FROT=1e8"), "{msg}");
    let text = scene::read("two_plates_friction_adapt.comm").replacen(
        "COEF_FROT=1.0,",
        "COEF_FROT=1.0e8,",
        1,
    );
    let (ok, nook, err) = scene::run_on(&text, "comm/two_plates.mail", "fricfail-coef-frot-adapt");
    assert!(
        err.as_deref().is_none_or(|e| !e.contains("COEF_FROT=1e8")),
        "{err:?}"
    );
    assert_eq!(nook, 0, "{ok} OK, {err:?}");
}

/// A penalised continuous zone beside a GLISSIERE zone (ssnv504k) is
/// refused at the penalised zone's ALGO_CONT, before the solve.
#[test]
fn penalised_zone_beside_a_sliding_zone_is_refused_before_the_solve() {
    let msg = scene::refused_export(
        "two_plates.comm",
        &["two_plates.mail"],
        &[
            ("    ZONE=_F(\n", "    ZONE=(_F(\n"),
            (
            "        ALGO_CONT=\"STANDARD\",\n        COEF_CONT=1000.0,\n    ),",
            "        ALGO_CONT=\"STANDARD\",\n        COEF_CONT=1000.0,\n        GLISSIERE=\"OUI\",\n    ),\n    _F(GROUP_MA_ESCL=\"CD\", GROUP_MA_MAIT=\"GH\", ALGO_CONT=\"PENALISATION\", COEF_PENA_CONT=1.0e6),\n    ),",
            ),
        ],
        "fricfail-glissiere",
    );
    assert!(
        msg.contains("ALGO_CONT='PENALISATION' beside a zone with GLISSIERE='OUI'"),
        "{msg}"
    );
}

/// The same plates with penalised friction beside augmented contact
/// (ssnv128p's U3M settings: ALGO_FROT='PENALISATION', GLIS_MAXI,
/// ADAPTATION='TOUT'): code_aster's coefficient 10 × arete_max / arete_min
/// / GLIS_MAXI at the slipping points in contact (`mm_cycl_algo`). With
/// GLIS_MAXI = 1e-6 the regularised law slides: the friction resultant is
/// μ = 0.3 times the normal one. Under the cycling treatment
/// (ADAPTATION='CYCLAGE') the same zone is refused before the solve.
#[test]
fn penalised_friction_beside_augmented_contact_slides_with_mu() {
    let edits = [
        (
            "ALGO_FROT=\"STANDARD\",\n        COEF_FROT=1.0,",
            "ALGO_FROT=\"PENALISATION\",\n        GLIS_MAXI=1.0e-6,",
        ),
        ("COEF_CONT=1.0,", "COEF_CONT=100.0,"),
    ];
    let mut text = scene::read("two_plates_friction_adapt.comm");
    for (from, to) in edits
        .iter()
        .chain(&[("ADAPTATION=\"ADAPT_COEF\"", "ADAPTATION=\"TOUT\"")])
    {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let (ok, nook, err) = scene::run_on(&text, "comm/two_plates.mail", "fricfail-pena-frot");
    assert_eq!((ok, nook, err), (8, 0, None));
    // With CYCLAGE the catalog asks COEF_PENA_FROT and has no GLIS_MAXI.
    let msg = scene::refused_export(
        "two_plates_friction_adapt.comm",
        &["two_plates.mail"],
        &[
            (
                "ALGO_FROT=\"STANDARD\",\n        COEF_FROT=1.0,",
                "ALGO_FROT=\"PENALISATION\",\n        COEF_PENA_FROT=1.0e6,",
            ),
            ("ADAPTATION=\"ADAPT_COEF\"", "ADAPTATION=\"CYCLAGE\""),
        ],
        "fricfail-pena-frot-cyclage",
    );
    assert!(
        msg.contains("ALGO_FROT='PENALISATION' with ALGO_CONT='STANDARD'"),
        "{msg}"
    );
}
