//! Linear heat conduction (comm/heat_strip.comm): THER_LINEAIRE on the
//! project's QUAD8 strip, stationary (a hollow cylinder in AXIS with an
//! imposed temperature and an exchange; a plane slab with an imposed flux
//! and an exchange) and transient (the first mode of a slab decaying under
//! the θ-scheme), each against its closed-form answer; imposed
//! temperatures given by functions of INST and X (AFFE_CHAR_THER_F), scaled
//! by FONC_MULT, and constant functions for a flux and an exchange; then
//! the refusals and errors a user meets.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/heat_strip.mail", &format!("heat-{tag}"))
}

fn text() -> String {
    scene::read("heat_strip.comm")
}

#[test]
fn stationary_and_transient_temperatures_match_their_closed_forms() {
    assert_eq!(run(&text(), "scene"), (22, 0, None));
}

#[test]
fn fluxes_varying_in_space_and_exchanges_scaled_in_time_are_refused_at_their_keyword() {
    let t = text().replace(
        "FLUX_REP=_F(GROUP_MA=\"LEFT\", FLUN=q_f)",
        "FLUX_REP=_F(GROUP_MA=\"LEFT\", FLUN=t_right)",
    );
    assert!(t.contains("FLUN=t_right"));
    let (_, nook, err) = run(&t, "flux-x");
    assert_eq!(nook, 0);
    let err = err.expect("a refusal");
    assert!(
        err.contains("not supported yet: AFFE_CHAR_THER_F/FLUX_REP/FLUN as a function of X"),
        "{err}"
    );
    let t = text().replace(
        "EXCIT=_F(CHARGE=bc_flux_f)",
        "EXCIT=_F(CHARGE=bc_flux_f, FONC_MULT=scale)",
    );
    assert!(t.contains("FONC_MULT=scale)"));
    let (_, nook, err) = run(&t, "flux-mult");
    assert_eq!(nook, 0);
    let err = err.expect("a refusal");
    assert!(
        err.contains("THER_LINEAIRE/EXCIT: an ECHANGE varying in time"),
        "{err}"
    );
}

#[test]
fn a_thermal_material_in_a_mechanical_model_is_an_error() {
    let t = text();
    let cut = t.find("# 2. The slab").expect("the scene changed");
    let mut variant = t[..cut].to_string();
    variant.push_str(
        "mech = AFFE_MODELE(MAILLAGE=mesh, AFFE=_F(TOUT=\"OUI\", PHENOMENE=\"MECANIQUE\", \
         MODELISATION=\"D_PLAN\"))\n\
         fix = AFFE_CHAR_MECA(MODELE=mech, DDL_IMPO=_F(GROUP_MA=\"LEFT\", DX=0.0, DY=0.0))\n\
         r = MECA_STATIQUE(MODELE=mech, CHAM_MATER=mat_axis, EXCIT=_F(CHARGE=fix))\nFIN()\n",
    );
    let (_, nook, err) = run(&variant, "mech");
    assert_eq!(nook, 0);
    let err = err.expect("an error");
    assert!(
        err.contains("has no ELAS (a thermal material, THER alone)"),
        "{err}"
    );
}

#[test]
fn an_exchange_on_volume_cells_is_located() {
    let t = text().replace(
        "ECHANGE=_F(GROUP_MA=\"RIGHT\", COEF_H=H, TEMP_EXT=0.0)",
        "ECHANGE=_F(GROUP_MA=\"STRIP\", COEF_H=H, TEMP_EXT=0.0)",
    );
    assert!(t.contains("GROUP_MA=\"STRIP\", COEF_H"));
    let (ok, nook, err) = run(&t, "exchange");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("an error");
    assert!(
        err.contains(
            "ECHANGE applies to the edges (segments) of the model, but cell Q1 is a QUAD8"
        ),
        "{err}"
    );
}

#[test]
fn an_initial_state_from_a_result_is_refused_before_solving() {
    let t = text().replace("ETAT_INIT=_F(CHAM_NO=t0)", "ETAT_INIT=_F(EVOL_THER=cyl)");
    assert!(t.contains("EVOL_THER=cyl"));
    let (ok, nook, err) = run(&t, "evol");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("a refusal");
    assert!(err.contains("THER_LINEAIRE/ETAT_INIT/EVOL_THER"), "{err}");
}

#[test]
fn a_zero_heat_capacity_is_the_stationary_default_and_a_negative_one_is_refused() {
    // RHO_CP=0.0 written out is code_aster's default (hsnv100f): the
    // stationary cylinder gives the same temperatures.
    let t = text().replace("RHO_CP=4.0e6", "RHO_CP=0.0");
    assert!(t.contains("RHO_CP=0.0"));
    assert_eq!(run(&t, "rhocp0"), (22, 0, None));
    let t = text().replace("RHO_CP=4.0e6", "RHO_CP=-1.0");
    let (_, nook, err) = run(&t, "rhocp-neg");
    assert_eq!(nook, 0);
    let err = err.expect("an error");
    assert!(err.contains("RHO_CP must be positive, got -1"), "{err}");
}

fn source_scene() -> String {
    scene::read("heat_source.comm")
}

/// comm/heat_source.comm: a volume source in a slab (exact quadratic
/// profile), a hollow cylinder (closed form, 1e-5) and the slab's
/// transient reaching its stationary profile.
#[test]
fn a_volume_source_gives_the_closed_form_temperatures() {
    assert_eq!(run(&source_scene(), "source"), (6, 0, None));
}

/// A source scaled by FONC_MULT, or in THER_NON_LINE, is refused at its
/// keyword rather than ignored.
#[test]
fn a_source_with_fonc_mult_or_in_ther_non_line_is_refused() {
    let t = source_scene().replacen(
        "EXCIT=_F(CHARGE=heat_plane),\n    TYPE_CALCUL",
        "EXCIT=_F(CHARGE=heat_plane, FONC_MULT=DEFI_CONSTANTE(VALE=2.0)),\n    TYPE_CALCUL",
        1,
    );
    assert!(t.contains("FONC_MULT"), "the edit applies");
    let (_, nook, err) = run(&t, "source-mult");
    assert_eq!(nook, 0);
    let err = err.expect("a refusal");
    assert!(
        err.contains("not supported yet: THER_LINEAIRE/EXCIT/FONC_MULT on a load with SOURCE"),
        "{err}"
    );
    // The slab alone, with a THER_NL material, in THER_NON_LINE.
    let full = source_scene();
    let head = &full[..full
        .find("slab = THER_LINEAIRE(")
        .expect("the scene changed")];
    let t = format!(
        "{}\nwarming = THER_NON_LINE(MODELE=plane, CHAM_MATER=mat, \
         EXCIT=_F(CHARGE=heat_plane), ETAT_INIT=_F(VALE=0.0), \
         INCREMENT=_F(LIST_INST=DEFI_LIST_REEL(VALE=(0.0, 1.0))))\nFIN()\n",
        head.replacen(
            "THER=_F(LAMBDA=LAMBDA, RHO_CP=1.0e4)",
            "THER_NL=_F(LAMBDA=DEFI_CONSTANTE(VALE=LAMBDA), RHO_CP=DEFI_CONSTANTE(VALE=1.0e4))",
            1,
        )
    );
    assert!(t.contains("THER_NL="), "the edit applies");
    let (_, nook, err) = run(&t, "source-nl");
    assert_eq!(nook, 0);
    let err = err.expect("a refusal");
    assert!(
        err.contains("THER_NON_LINE with a SOURCE in the load"),
        "{err}"
    );
}
