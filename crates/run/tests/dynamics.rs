//! The project's dynamics scenes (DYNA_NON_LINE) and MECA_NON_LINE:
//! - comm/dyna_oscillator.comm: a mass-spring oscillator, Newmark's average
//!   acceleration against its exact discrete solution (period elongation),
//!   HHT (MODI_EQUI 'NON' and 'OUI') against the schemes' recursions;
//! - comm/dyna_bar.comm: a bar with an initial velocity, in free flight
//!   (exact rigid translation) and thrown against a wall (discrete contact:
//!   the end held at the wall during 2L/c, the wave solution);
//! - comm/dyna_impact.comm: a point mass on a rigid wall (LIAISON_UNIL),
//!   the elastic impact of the average acceleration and the dissipation of
//!   GAMMA > 1/2;
//! - comm/dyna_energy.comm: ENERGIE's PARA_CALC table against the exact
//!   works of a spring, a constant force and a reaction;
//! - comm/beam_vibration.comm: a POU_D_E cantilever launched in its
//!   first Euler–Bernoulli mode (tip against the trapezoidal rule's
//!   rotation of that mode, the energy conserved) and a DIS_TR mass with
//!   rotational inertia (M_TR_D_N) on springs, exact;
//! - comm/dkt_vibration.comm, comm/dkq_vibration.comm: strips of DKT
//!   triangles and quadrangles in their first mode (code_aster's `dktmas`,
//!   `dkqmas`), within their measured discretisation;
//! - comm/continued_plastic.comm: MECA_NON_LINE continued by reuse= from
//!   its last plastic state gives the values of one run;
//! - error cases: located refusals and errors;
//! - MECA_NON_LINE on the step-cutting scene gives STAT_NON_LINE's values.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs a command file's text on a mesh: (OK, NOOK, error).
fn run_text(text: &str, mesh: &Path, tag: &str) -> (usize, usize, Option<String>) {
    let out = std::env::temp_dir().join(format!("aster-dyna-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let comm = out.join("case.comm");
    std::fs::write(&comm, text).unwrap();
    let case = aster_run::program::prepare(&comm, Some(mesh), &out).unwrap();
    let outcome = aster_run::program::run(&case, Box::new(std::io::sink()));
    let _ = std::fs::remove_dir_all(&out);
    (
        outcome.tally.ok,
        outcome.tally.nook,
        outcome.error.map(|e| format!("{e:?}")),
    )
}

fn scene(name: &str) -> String {
    std::fs::read_to_string(root().join("comm").join(name)).unwrap()
}

fn edited(name: &str, pairs: &[(&str, &str)]) -> String {
    let mut text = scene(name);
    for (from, to) in pairs {
        assert!(text.contains(from), "{name} no longer has `{from}`");
        text = text.replacen(from, to, 1);
    }
    text
}

fn oscillator_mesh() -> PathBuf {
    root().join("comm/dyna_oscillator.mail")
}

/// A POU_D_E cantilever in its first mode and a DIS_TR point mass with
/// rotational inertia (code_aster's `ptma01` and `afdi3d` masses).
#[test]
fn beam_and_rotational_mass_vibrate_at_their_frequencies() {
    let mesh = root().join("comm/beam_vibration.mail");
    let r = run_text(&scene("beam_vibration.comm"), &mesh, "beam");
    assert_eq!(r, (44, 0, None));
    // Without the beam's mass the tip no longer follows the mode: the
    // Euler–Bernoulli period holds only with ρ on the beam.
    let light = edited(
        "beam_vibration.comm",
        &[(
            "MAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=STEEL))",
            "LIGHT = DEFI_MATERIAU(ELAS=_F(E=E, NU=0.3, RHO=RHO / 2.0))\n\
             MAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=LIGHT))",
        )],
    );
    let (ok, nook, err) = run_text(&light, &mesh, "beam-light");
    assert!(
        err.is_none() && nook >= 10 && ok + nook == 44,
        "{ok} {nook} {err:?}"
    );
    // A translational mass on a DIS_TR cell stops, as code_aster's te0041.
    let wrong = edited(
        "beam_vibration.comm",
        &[(
            "CARA=\"M_TR_D_N\",\n            VALE=(MASS, INER, INER, INER, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),",
            "CARA=\"M_T_D_N\",\n            VALE=MASS,",
        )],
    );
    let (_, _, err) = run_text(&wrong, &mesh, "beam-wrong");
    let err = err.expect("an error");
    assert!(err.contains("M_T_D_N") && err.contains("R1"), "{err}");
}

/// A strip of DKT triangles launched in its first beam mode.
#[test]
fn dkt_strip_vibrates_at_its_beam_frequency() {
    let mesh = root().join("comm/dkt_strips.mail");
    let r = run_text(&scene("dkt_vibration.comm"), &mesh, "dkt");
    assert_eq!(r, (26, 0, None));
}

/// The same on a strip of DKT quadrangles (DKQ, `dkqmas`), and with
/// `INER_ROTA='OUI'` at the Rayleigh beam's frequency.
#[test]
fn dkq_strip_vibrates_at_its_beam_frequency() {
    let mesh = root().join("comm/dkt_strips.mail");
    let r = run_text(&scene("dkq_vibration.comm"), &mesh, "dkq");
    assert_eq!(r, (36, 0, None));
}

#[test]
fn oscillator_matches_newmark_and_hht_references() {
    let r = run_text(&scene("dyna_oscillator.comm"), &oscillator_mesh(), "osc");
    assert_eq!(r, (26, 0, None));
}

/// ENERGIE's PARA_CALC table against the exact trapezoidal works of a
/// spring and a constant force: Newmark conserves (DISS_SCH = 0), HHT
/// dissipates, a driven DOF's reaction works.
#[test]
fn energy_balance_of_the_oscillator() {
    let r = run_text(&scene("dyna_energy.comm"), &oscillator_mesh(), "energy");
    assert_eq!(r, (102, 0, None));
    // The weighted equilibrium's balance is refused at ENERGIE.
    let text = scene("dyna_energy.comm").replace(r#"MODI_EQUI="NON""#, r#"MODI_EQUI="OUI""#);
    let (_, nook, err) = run_text(&text, &oscillator_mesh(), "energy-oui");
    let err = err.expect("an error");
    assert_eq!(nook, 0);
    assert!(
        err.contains("DYNA_NON_LINE/ENERGIE with HHT MODI_EQUI='OUI'")
            && err.contains("case.comm:"),
        "{err}"
    );
}

#[test]
fn bar_in_flight_and_against_a_wall() {
    let r = run_text(
        &scene("dyna_bar.comm"),
        &root().join("comm/dyna_bar.mail"),
        "bar",
    );
    assert_eq!(r, (26, 0, None));
}

#[test]
fn point_mass_impacts_a_rigid_wall() {
    let r = run_text(&scene("dyna_impact.comm"), &oscillator_mesh(), "impact");
    assert_eq!(r, (30, 0, None));
}

#[test]
fn archivage_keeps_the_listed_instants_and_renumbers() {
    // Only t = 5dt and 17dt are archived (with the initial state and the
    // last step, always kept): NUME_ORDRE 1, 2, 3 are steps 5, 17, 40.
    let text = edited(
        "dyna_oscillator.comm",
        &[
            (
                "times = DEFI_LIST_REEL",
                "archived = DEFI_LIST_REEL(VALE=(5 * dt, 17 * dt))\ntimes = DEFI_LIST_REEL",
            ),
            (
                "INCREMENT=_F(LIST_INST=times),",
                "INCREMENT=_F(LIST_INST=times),\n    ARCHIVAGE=_F(LIST_INST=archived),",
            ),
            (
                "for n in (5, 17, 40):",
                "for n, no in ((5, 1), (17, 2), (40, 3)):",
            ),
            (
                "NUME_ORDRE=n, NOM_CHAM=\"DEPL\"",
                "NUME_ORDRE=no, NOM_CHAM=\"DEPL\"",
            ),
            (
                "NUME_ORDRE=n, NOM_CHAM=\"VITE\"",
                "NUME_ORDRE=no, NOM_CHAM=\"VITE\"",
            ),
            (
                "NUME_ORDRE=n, NOM_CHAM=\"ACCE\"",
                "NUME_ORDRE=no, NOM_CHAM=\"ACCE\"",
            ),
        ],
    );
    assert_eq!(
        run_text(&text, &oscillator_mesh(), "archive"),
        (26, 0, None)
    );
}

const NEWMARK: &str =
    r#"SCHEMA_TEMPS=_F(SCHEMA="NEWMARK", FORMULATION="DEPLACEMENT", BETA=0.25, GAMMA=0.5),"#;

fn oscillator_error(pairs: &[(&str, &str)], tag: &str) -> String {
    let text = edited("dyna_oscillator.comm", pairs);
    let (_, nook, err) = run_text(&text, &oscillator_mesh(), tag);
    assert_eq!(nook, 0);
    err.expect("an error")
}

#[test]
fn unsupported_schemes_and_settings_are_refused_where_written() {
    let err = oscillator_error(
        &[(
            NEWMARK,
            r#"SCHEMA_TEMPS=_F(SCHEMA="DIFF_CENT", FORMULATION="ACCELERATION"),"#,
        )],
        "diffcent",
    );
    assert!(
        err.contains("not supported yet: DYNA_NON_LINE/SCHEMA_TEMPS/SCHEMA='DIFF_CENT'")
            && err.contains("case.comm:"),
        "{err}"
    );
    let err = oscillator_error(
        &[(
            NEWMARK,
            r#"SCHEMA_TEMPS=_F(SCHEMA="NEWMARK", FORMULATION="DEPLACEMENT"), MASS_DIAG="OUI","#,
        )],
        "massdiag",
    );
    assert!(
        err.contains("MASS_DIAG") && err.contains("explicit schemes"),
        "{err}"
    );
    // A stress-free initial displacement (DEPL without SIGM) that strains
    // the spring is refused.
    let err = oscillator_error(
        &[
            (
                "times = DEFI_LIST_REEL",
                "shifted = CREA_CHAMP(TYPE_CHAM=\"NOEU_DEPL_R\", OPERATION=\"AFFE\", MAILLAGE=mesh, AFFE=_F(GROUP_NO=\"A\", NOM_CMP=(\"DX\", \"DY\"), VALE=(0.5, 0.0)))\ntimes = DEFI_LIST_REEL",
            ),
            ("ETAT_INIT=_F(VITE=launch),", "ETAT_INIT=_F(VITE=launch, DEPL=shifted),"),
        ],
        "depl",
    );
    assert!(
        err.contains("ETAT_INIT/DEPL with a displacement that strains the structure"),
        "{err}"
    );
    // BETA = 0 is an explicit scheme.
    let err = oscillator_error(
        &[(
            NEWMARK,
            r#"SCHEMA_TEMPS=_F(SCHEMA="NEWMARK", FORMULATION="DEPLACEMENT", BETA=0.0, GAMMA=0.5),"#,
        )],
        "beta0",
    );
    assert!(err.contains("BETA must be positive"), "{err}");
}

#[test]
fn a_massless_unheld_dof_is_a_located_singular_system() {
    // Without the mass the free node has nothing holding it along x.
    let err = oscillator_error(
        &[
            (
                r#"_F(GROUP_MA="MASS", CARA="K_T_D_N", VALE=(k, k)),"#,
                r#"_F(GROUP_MA="MASS", CARA="K_T_D_N", VALE=(0.0, 0.0)),"#,
            ),
            (
                r#"_F(GROUP_MA="MASS", CARA="M_T_D_N", VALE=m),"#,
                r#"_F(GROUP_MA="MASS", CARA="M_T_D_N", VALE=0.0),"#,
            ),
        ],
        "massless",
    );
    assert!(
        err.contains("singular system") && err.contains("N1 DX"),
        "{err}"
    );
}

fn cutting_mesh() -> PathBuf {
    root().join("comm/plastic3d_cutting.mail")
}

/// reuse= continues a plastic analysis from its last state (stresses,
/// internal variables, finite-strain state): the same values as one run;
/// from an earlier state, whose behaviour state is not kept, refused.
#[test]
fn meca_non_line_continues_a_plastic_result() {
    let text = scene("continued_plastic.comm");
    let r = run_text(&text, &cutting_mesh(), "continued");
    assert_eq!(r, (24, 0, None));
    let text = text.replace(
        "ETAT_INIT=_F(EVOL_NOLI=part),",
        "ETAT_INIT=_F(EVOL_NOLI=part, INST=0.25),",
    );
    let (_, nook, err) = run_text(&text, &cutting_mesh(), "continued-early");
    let err = err.expect("an error");
    assert_eq!(nook, 0);
    assert!(
        err.contains("needs its stresses and internal variables"),
        "{err}"
    );
}

#[test]
fn meca_non_line_gives_stat_non_line_steps() {
    let text =
        scene("plastic3d_cutting.comm").replace("resu = STAT_NON_LINE(", "resu = MECA_NON_LINE(");
    assert!(text.contains("MECA_NON_LINE("));
    assert_eq!(run_text(&text, &cutting_mesh(), "meca"), (3, 0, None));
}

/// The edits that make comm/dyna_sliding_block.comm discrete (penalised
/// friction).
fn discrete_pairs() -> Vec<(&'static str, &'static str)> {
    vec![
        (r#"FORMULATION="CONTINUE","#, r#"FORMULATION="DISCRETE","#),
        (r#"    ALGO_RESO_CONT="NEWTON","#, ""),
        (r#"    ALGO_RESO_GEOM="NEWTON","#, ""),
        (r#"    ALGO_RESO_FROT="NEWTON","#, ""),
        (
            r#"ALGO_CONT="STANDARD","#,
            r#"ALGO_CONT="PENALISATION", E_N=1.0e12,"#,
        ),
        (r#"COEF_CONT=1.0e4,"#, ""),
        (
            r#"ALGO_FROT="STANDARD","#,
            r#"ALGO_FROT="PENALISATION", E_T=1.0e12,"#,
        ),
        (r#"COEF_FROT=1.0e4,"#, ""),
    ]
}

/// comm/dyna_sliding_block.comm made discrete (penalised friction), with
/// more edits; the error it stops with.
fn discrete_sliding_block(extra: &[(&str, &str)], tag: &str) -> String {
    let mut pairs = discrete_pairs();
    pairs.extend_from_slice(extra);
    let text = edited("dyna_sliding_block.comm", &pairs);
    let (_, nook, err) = run_text(&text, &root().join("comm/two_plates.mail"), tag);
    assert_eq!(nook, 0);
    err.expect("an error")
}

#[test]
fn discrete_friction_in_dynamics_is_refused_with_weighted_hht() {
    let schema = r#"SCHEMA_TEMPS=_F(SCHEMA="HHT", FORMULATION="DEPLACEMENT"),"#;
    let err = discrete_sliding_block(
        &[(
            r#"SCHEMA_TEMPS=_F(SCHEMA="NEWMARK", FORMULATION="DEPLACEMENT", BETA=0.49, GAMMA=0.9),"#,
            schema,
        )],
        "hhtfrot",
    );
    assert!(
        err.contains("HHT with MODI_EQUI='OUI' and discrete friction")
            && err.contains("case.comm:"),
        "{err}"
    );
}

/// Discrete friction with a plastic behaviour in dynamics runs, but an
/// increment that fails is not cut: the analysis stops, refused, naming
/// the behaviour's location (which increments code_aster cuts is not
/// reproduced; sdnv103d, with no cut, is all OK).
#[test]
fn discrete_friction_with_plasticity_refuses_to_cut() {
    let plastic = [
        (
            "steel = DEFI_MATERIAU(ELAS=_F(E=2.0e8, NU=0.0, RHO=1.0e4))",
            "steel = DEFI_MATERIAU(ELAS=_F(E=2.0e8, NU=0.0, RHO=1.0e4), ECRO_LINE=_F(D_SIGM_EPSI=1.0e7, SY=1.0e9))",
        ),
        (
            r#"COMPORTEMENT=_F(RELATION="ELAS"),"#,
            r#"COMPORTEMENT=_F(RELATION="VMIS_ISOT_LINE"),"#,
        ),
    ];
    let mut failing = plastic.to_vec();
    failing.push((
        "CONVERGENCE=_F(ITER_GLOB_MAXI=50, RESI_GLOB_RELA=1.0e-8),",
        "CONVERGENCE=_F(ITER_GLOB_MAXI=1, RESI_GLOB_RELA=1.0e-14),",
    ));
    let err = discrete_sliding_block(&failing, "plasfrotcut");
    assert!(
        err.contains("is not cut")
            && err.contains("COMPORTEMENT/RELATION='VMIS_ISOT_LINE' (")
            && err.contains("case.comm:"),
        "{err}"
    );
}
