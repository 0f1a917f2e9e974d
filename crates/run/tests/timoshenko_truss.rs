//! The project's Timoshenko-beam and truss scene (comm/timoshenko_truss.comm
//! on comm/timoshenko_truss.mail): POU_D_T cantilevers of a solid
//! rectangle, a tube and a hollow rectangle (code_aster's shear
//! coefficients AY, AZ, interpolated in its tables) against the closed-form
//! Timoshenko deflection PL³/3EI + PL·AY/(GA), and a BARRE triangle against
//! its statics and virtual work — all within 1e-9. What they cannot run is
//! refused at its keyword.

mod scene;

fn run(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    scene::run_on(text, "comm/timoshenko_truss.mail", &format!("timo-{tag}"))
}

fn text() -> String {
    scene::read("timoshenko_truss.comm")
}

#[test]
fn timoshenko_cantilevers_and_truss_match_closed_forms() {
    assert_eq!(run(&text(), "scene"), (32, 0, None));
}

/// The same beams as POU_D_E lose their shear deflection: the five tip
/// deflections (T1 DY DZ, T2 DY, T3 DY DZ) miss the analytic Timoshenko
/// values (each checked twice, NON_REGRESSION and ANALYTIQUE), while the
/// rotations, the efforts and the truss do not change.
#[test]
fn euler_beams_miss_exactly_the_shear_deflections() {
    let t = text().replace("MODELISATION=\"POU_D_T\"", "MODELISATION=\"POU_D_E\"");
    assert!(t.contains("POU_D_E"));
    assert_eq!(run(&t, "euler"), (22, 10, None));
}

/// A GENERALE section with the rectangle's A, IY, IZ, JX and AY = AZ = 1.2
/// is the same Timoshenko beam.
#[test]
fn generale_section_with_shear_coefficients_is_the_same_beam() {
    let t = text().replace(
        "_F(GROUP_MA=\"T1\", SECTION=\"RECTANGLE\", CARA=(\"HY\", \"HZ\"), VALE=(0.1, 0.05))",
        "_F(GROUP_MA=\"T1\", SECTION=\"GENERALE\", CARA=(\"A\", \"IY\", \"IZ\", \"JX\", \"AY\", \"AZ\"), \
         VALE=(5.0e-3, 1.0416666666666667e-06, 4.166666666666667e-06, 2.8610026041666676e-06, 1.2, 1.2))",
    );
    assert!(t.contains("GENERALE\", CARA=(\"A\""));
    assert_eq!(run(&t, "generale"), (32, 0, None));
}

#[test]
fn a_timoshenko_beam_without_shear_coefficients_is_refused() {
    let t = text().replace(
        "_F(GROUP_MA=\"T1\", SECTION=\"RECTANGLE\", CARA=(\"HY\", \"HZ\"), VALE=(0.1, 0.05))",
        "_F(GROUP_MA=\"T1\", SECTION=\"GENERALE\", CARA=(\"A\", \"IY\", \"IZ\", \"JX\"), \
         VALE=(5.0e-3, 1.0416666666666667e-06, 4.166666666666667e-06, 2.8610026041666676e-06))",
    );
    let (ok, nook, err) = run(&t, "no-ay");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("POU_D_T") && err.contains("'AY'"), "{err}");
}

#[test]
fn a_hollow_rectangle_beyond_code_aster_s_table_is_an_error() {
    let t = text().replace(
        "CARA=(\"HY\", \"HZ\", \"EP\"), VALE=(0.1, 0.08, 0.01)",
        "CARA=(\"HY\", \"HZ\", \"EP\"), VALE=(0.1, 0.08, 0.001)",
    );
    let (ok, nook, err) = run(&t, "thin");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("0.95") && err.contains("VALE"), "{err}");
}

/// The bars' thermal strain is not reproduced: a temperature on them is
/// refused, not ignored.
#[test]
fn a_temperature_on_the_bars_is_refused() {
    let t = text()
        .replace(
            "ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, RHO=7800.0))",
            "ACIER = DEFI_MATERIAU(ELAS=_F(E=2.0e11, NU=0.3, RHO=7800.0, ALPHA=1.0e-5))\n\
             TEMP = CREA_CHAMP(OPERATION=\"AFFE\", TYPE_CHAM=\"NOEU_TEMP_R\", MAILLAGE=MA, \
             AFFE=_F(TOUT=\"OUI\", NOM_CMP=\"TEMP\", VALE=30.0))",
        )
        .replace(
            "MAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=ACIER))",
            "MAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT=\"OUI\", MATER=ACIER), \
             AFFE_VARC=_F(GROUP_MA=\"TRI\", NOM_VARC=\"TEMP\", VALE_REF=0.0, CHAM_GD=TEMP))",
        );
    assert!(t.contains("AFFE_VARC"));
    let (ok, nook, err) = run(&t, "thermal");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(
        err.contains("not supported yet") && err.contains("TEMP") && err.contains("BARRE"),
        "{err}"
    );
    // Located at the AFFE_VARC keyword of AFFE_MATERIAU.
    assert!(
        err.contains(".comm:") && err.contains("their thermal strain is not reproduced ("),
        "{err}"
    );
}

#[test]
fn a_bar_section_needs_its_area() {
    let t = text().replace(
        "BARRE=_F(GROUP_MA=\"TRI\", SECTION=\"GENERALE\", CARA=\"A\", VALE=1.0e-4)",
        "BARRE=_F(GROUP_MA=\"TRI\", SECTION=\"CERCLE\", CARA=\"EP\", VALE=1.0e-3)",
    );
    let (ok, nook, err) = run(&t, "bar-r");
    assert_eq!((ok, nook), (0, 0));
    let err = err.expect("refused");
    assert!(err.contains("CERCLE") && err.contains("needs R"), "{err}");
}
