//! DEFI_NAPPE (comm/nappe.comm): functions of two parameters given by
//! function concepts or DEFI_FONCTION occurrences, evaluated as code_aster's
//! nappe inside the range, at tabulated values, prolonged on each side,
//! with LOG interpolation across the functions, from a FORMULE and from
//! TEST_FONCTION; and the errors a wrong nappe gets.

mod scene;

use scene::{read, root, run_case, temp};

fn run_text(text: &str, tag: &str) -> (usize, usize, Option<String>) {
    let dir = temp(tag);
    let comm = dir.join("nappe.comm");
    std::fs::write(&comm, text).unwrap();
    let (outcome, _) = run_case(&comm, &dir.join("out"));
    let _ = std::fs::remove_dir_all(&dir);
    (
        outcome.tally.ok,
        outcome.tally.nook,
        outcome.error.map(|e| e.message),
    )
}

#[test]
fn the_nappe_scene_passes() {
    let dir = temp("nappe");
    let (outcome, _) = run_case(&root().join("comm/nappe.comm"), &dir.join("out"));
    let _ = std::fs::remove_dir_all(&dir);
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    assert_eq!((outcome.tally.ok, outcome.tally.nook), (16, 0));
}

#[test]
fn a_value_outside_an_excluded_side_names_the_fix() {
    let text = read("nappe.comm").replacen("PROL_GAUCHE=\"CONSTANT\",", "", 1);
    let (_, _, error) = run_text(&text, "nappe-excluded");
    let e = error.expect("N(0.5, 5) is outside the nappe");
    assert!(e.contains("AMOR=0.5") && e.contains("PROL_GAUCHE"), "{e}");
}

#[test]
fn para_out_of_order_with_verif_croissant_is_an_error() {
    let text = read("nappe.comm").replacen("PARA=(1.0, 2.0, 4.0),", "PARA=(2.0, 1.0, 4.0),", 1);
    let (_, _, error) = run_text(&text, "nappe-verif");
    let e = error.expect("VERIF='CROISSANT' with PARA out of order");
    assert!(e.contains("PARA must increase strictly"), "{e}");
}

#[test]
fn as_many_functions_as_parameter_values() {
    let text = read("nappe.comm").replacen("FONCTION=(F1, F2, F4),", "FONCTION=(F1, F2),", 1);
    let (_, _, error) = run_text(&text, "nappe-count");
    let e = error.expect("three values, two functions");
    assert!(e.contains("3 parameter values for 2 functions"), "{e}");
}

#[test]
fn a_nappe_takes_two_values() {
    let text = read("nappe.comm").replacen(
        "values = CREA_TABLE(",
        "x = N(1.0)\nvalues = CREA_TABLE(",
        1,
    );
    let (_, _, error) = run_text(&text, "nappe-one");
    let e = error.expect("a nappe called with one value");
    assert!(e.contains("takes 2 argument(s)"), "{e}");
}
