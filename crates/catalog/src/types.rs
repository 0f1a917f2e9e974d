//! Concept types: which type a command produces and which types a keyword
//! accepts (code_aster's data-structure class hierarchy, reduced to parents).

use crate::cond::CVal;

/// The parent class of a concept type, when it is a subclass of another
/// catalog type (so a `evol_noli` is accepted where `resultat_sdaster` is).
pub fn parent(typ: &str) -> Option<&'static str> {
    Some(match typ {
        "evol_elas" | "evol_noli" | "evol_ther" | "evol_char" | "evol_varc" | "evol_sech" => {
            "evol_sdaster"
        }
        // code_aster's DataStructure classes: mode_meca_c(mode_meca),
        // formule_c(formule), the *_dict containers are ds_dict.
        "mode_meca_c" => "mode_meca",
        "formule_c" => "formule",
        "evol_elas_dict" | "evol_ther_dict" | "evol_noli_dict" => "ds_dict",
        "evol_sdaster" | "dyna_trans" | "dyna_harmo" | "acou_harmo" | "mode_meca" | "mode_acou"
        | "mode_flamb" | "mode_empi" | "mult_elas" | "fourier_elas" | "fourier_ther"
        | "comb_fourier" | "mode_gene" | "tran_gene" | "harm_gene" | "dyna_phys" => {
            "resultat_sdaster"
        }
        "cham_no_sdaster" | "cham_elem" | "carte_sdaster" => "cham_gd_sdaster",
        "table_container" | "table_fonction" => "table_sdaster",
        "maillage_p" | "squelette" | "grille_sdaster" | "super_mesh" => "maillage_sdaster",
        "char_contact" => "char_meca",
        "vect_elem_depl_r" | "vect_elem_temp_r" | "vect_elem_pres_c" => "vect_elem",
        "matr_elem_depl_r" | "matr_elem_depl_c" | "matr_elem_temp_r" | "matr_elem_pres_c" => {
            "matr_elem"
        }
        _ => return None,
    })
}

/// Whether a concept of type `actual` is accepted where `expected` is required.
pub fn is_a(actual: &str, expected: &str) -> bool {
    let mut t = actual;
    loop {
        if t == expected {
            return true;
        }
        match parent(t) {
            Some(p) => t = p,
            None => return false,
        }
    }
}

/// The type of the concept a command really returns, where code_aster's
/// implementation (its `ops` function) returns something else than the
/// catalog's `sd_prod` says: the objects, not the catalog, are what later
/// commands are checked against. `None` for every other command.
pub fn actual_result(command: &str, type_of: &dyn Fn(&str) -> Option<String>) -> Option<String> {
    match command {
        // Declared `evol_ther`; the macro returns a ThermalResultDict, one
        // result per loading case (read back with EXTR_CONCEPT).
        "CALC_THER_MULT" => Some("evol_ther_dict".into()),
        // Declared `cham_gd_sdaster`; the macro projects RESULTAT onto the
        // cut lines and returns a result (or a dictionary of results) of
        // the same type.
        "EXTR_COUPE" => Some(type_of("RESULTAT").unwrap_or_else(|| UNKNOWN.into())),
        _ => None,
    }
}

/// A concept type not known until the command runs: accepted everywhere a
/// concept is (the checker cannot know better without executing).
pub const UNKNOWN: &str = "?";

/// The result type of a command whose `sd_prod` is computed, from its
/// (already validated) keyword values. `value(kw)` gives a top-level
/// keyword's value, `type_of(kw)` the type of a concept given there.
///
/// Returns [`UNKNOWN`] for the functions not modelled.
pub fn computed(
    function: &str,
    value: &dyn Fn(&str) -> Option<CVal>,
    type_of: &dyn Fn(&str) -> Option<String>,
) -> String {
    let text = |k: &str| match value(k) {
        Some(CVal::Str(s)) => Some(s),
        Some(CVal::Tuple(t)) => match t.first() {
            Some(CVal::Str(s)) => Some(s.clone()),
            _ => None,
        },
        _ => None,
    };
    let has = |k: &str| value(k).is_some();
    let t = match function {
        "crea_champ_prod" => match text("TYPE_CHAM") {
            Some(tc) if tc.starts_with("NOEU_") => "cham_no_sdaster",
            Some(tc) if tc.starts_with("CART_") => "carte_sdaster",
            Some(tc) if tc.starts_with("EL") => "cham_elem",
            _ => UNKNOWN,
        },
        "defi_fonction_prod" => {
            if has("VALE_C") {
                "fonction_c"
            } else {
                "fonction_sdaster"
            }
        }
        "formule_prod" => {
            if has("VALE_C") {
                "formule_c"
            } else {
                "formule"
            }
        }
        // code_aster 17's LIRE_MAILLAGE builds a ParallelMesh (maillage_p)
        // when a MED mesh is read with PARTITIONNEUR='PTSCOTCH' on several
        // processes (code_aster/Commands/lire_maillage.py), whatever the
        // catalog's sd_prod says; asking for the partitioner is asking for
        // that run (on one process code_aster reads a plain mesh, alarm
        // MED_18). maillage_p is a maillage_sdaster everywhere else.
        "lire_maillage_sdprod" => {
            if text("FORMAT").as_deref().unwrap_or("MED") == "MED"
                && text("PARTITIONNEUR").as_deref() == Some("PTSCOTCH")
            {
                "maillage_p"
            } else {
                "maillage_sdaster"
            }
        }
        "affe_char_cine_prod" => {
            if has("MECA_IMPO")
                || has("EVOL_IMPO") && type_of("EVOL_IMPO").as_deref() == Some("evol_noli")
            {
                "char_cine_meca"
            } else if has("THER_IMPO") {
                "char_cine_ther"
            } else if has("ACOU_IMPO") {
                "char_cine_acou"
            } else {
                "char_cine_meca"
            }
        }
        "affe_char_cine_f_prod" => {
            if has("THER_IMPO") {
                "char_cine_ther"
            } else {
                "char_cine_meca"
            }
        }
        "affe_cara_elem_prod" => "cara_elem",
        "calc_champ_prod" | "calc_erreur_prod" | "copier_prod" | "norm_mode_prod"
        | "extr_resu_prod" | "modi_repere_prod" => {
            // Same type as the input result / concept.
            return ["RESULTAT", "CONCEPT", "CHAM_GD"]
                .iter()
                .find_map(|k| type_of(k))
                .unwrap_or_else(|| UNKNOWN.to_string());
        }
        "crea_resu_prod" | "lire_resu_prod" => match text("TYPE_RESU") {
            Some(t) => return t.to_lowercase(),
            None => UNKNOWN,
        },
        // Real or complex, function or surface: depends on the inputs in
        // ways the checker does not follow; left open.
        "calc_fonction_prod" | "calc_fonc_interp_prod" | "recu_fonction_prod" => UNKNOWN,
        "lire_fonction_prod" => match text("TYPE").as_deref() {
            Some("NAPPE") => "nappe_sdaster",
            Some("FONCTION_C") => "fonction_c",
            Some("FONCTION") => "fonction_sdaster",
            _ => UNKNOWN,
        },
        "calc_table_prod" | "crea_table_prod" | "extr_table_prod" | "post_elem_prod" => {
            if function == "extr_table_prod" {
                return text("TYPE_RESU")
                    .map(|t| t.to_lowercase())
                    .unwrap_or_else(|| UNKNOWN.to_string());
            }
            // CREA_TABLE and CALC_TABLE: TYPE_TABLE when given; CALC_TABLE
            // otherwise keeps a table_fonction/table_container it works on.
            match text("TYPE_TABLE").as_deref() {
                Some("TABLE_FONCTION") => "table_fonction",
                Some("TABLE_CONTAINER") => "table_container",
                Some(_) => "table_sdaster",
                None if function == "calc_table_prod" => match type_of("TABLE").as_deref() {
                    Some("table_fonction") => "table_fonction",
                    Some("table_container") => "table_container",
                    _ => "table_sdaster",
                },
                None => "table_sdaster",
            }
        }
        "calc_vect_elem_prod" => "vect_elem_depl_r",
        "calc_matr_elem_prod" => match text("OPTION") {
            Some(o) if o.starts_with("RIGI_THER") || o.starts_with("MASS_THER") => {
                "matr_elem_temp_r"
            }
            Some(o) if o.ends_with("ACOU") => "matr_elem_pres_c",
            _ => "matr_elem_depl_r",
        },
        "asse_matrice_prod" => match type_of("MATR_ELEM").as_deref() {
            Some("matr_elem_temp_r") => "matr_asse_temp_r",
            Some("matr_elem_pres_c") => "matr_asse_pres_c",
            Some("matr_elem_depl_c") => "matr_asse_depl_c",
            _ => "matr_asse_depl_r",
        },
        "defi_list_freq_prod" => "listr8_sdaster",
        "proj_champ_prod" => match (text("METHODE").as_deref(), type_of("RESULTAT")) {
            (_, Some(t)) => return t,
            // Projection onto sub-points gives an element field.
            (Some("SOUS_POINT"), None) => "cham_elem",
            (_, None) if has("CHAM_GD") => {
                return type_of("CHAM_GD").unwrap_or_else(|| UNKNOWN.into())
            }
            _ => "corresp_2_mailla",
        },
        "calc_modes_prod" => match type_of("MATR_RIGI").as_deref() {
            Some(t) if t.starts_with("matr_asse_gene") => "mode_gene",
            Some(t) if t.starts_with("matr_asse_pres") => "mode_acou",
            Some(t) if t.starts_with("matr_asse_depl") => "mode_meca",
            _ => UNKNOWN,
        },
        "defi_group_prod" => {
            return type_of("MAILLAGE")
                .or_else(|| type_of("GRILLE"))
                .unwrap_or_else(|| "maillage_sdaster".into())
        }
        "asse_maillage_prod" | "cream_prod" | "macr_adap_mail_prod" => "maillage_sdaster",
        "post_champ_prod" => return type_of("RESULTAT").unwrap_or_else(|| UNKNOWN.into()),
        "dyna_vibra_sdprod" => match (
            text("BASE_CALCUL").as_deref(),
            text("TYPE_CALCUL").as_deref(),
        ) {
            (Some("PHYS"), Some("TRAN")) => "dyna_trans",
            (Some("PHYS"), Some("HARM")) => "dyna_harmo",
            (Some("GENE"), Some("TRAN")) => "tran_gene",
            (Some("GENE"), Some("HARM")) => "harm_gene",
            _ => UNKNOWN,
        },

        _ => UNKNOWN,
    };
    t.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hierarchy() {
        assert!(is_a("evol_noli", "resultat_sdaster"));
        assert!(is_a("evol_noli", "evol_sdaster"));
        assert!(!is_a("char_cine_meca", "char_meca"));
        assert!(is_a("table_container", "table_sdaster"));
        assert!(is_a("formule_c", "formule"));
        assert!(!is_a("formule", "formule_c"));
        assert!(is_a("evol_ther_dict", "ds_dict"));
        assert!(is_a("mode_meca_c", "resultat_sdaster"));
    }

    #[test]
    fn results_that_differ_from_the_catalog() {
        let ty = |k: &str| (k == "RESULTAT").then(|| "evol_elas".to_string());
        assert_eq!(
            actual_result("EXTR_COUPE", &ty).as_deref(),
            Some("evol_elas")
        );
        assert_eq!(
            actual_result("EXTR_COUPE", &|_| None).as_deref(),
            Some(UNKNOWN)
        );
        assert_eq!(
            actual_result("CALC_THER_MULT", &|_| None).as_deref(),
            Some("evol_ther_dict")
        );
        assert_eq!(actual_result("MECA_STATIQUE", &ty), None);
    }

    #[test]
    fn a_partitioned_med_mesh_is_a_parallel_mesh() {
        let read = |part: Option<&str>| {
            let value = move |k: &str| match (k, part) {
                ("FORMAT", _) => Some(CVal::Str("MED".into())),
                ("PARTITIONNEUR", Some(p)) => Some(CVal::Str(p.into())),
                _ => None,
            };
            computed("lire_maillage_sdprod", &value, &|_| None)
        };
        assert_eq!(read(Some("PTSCOTCH")), "maillage_p");
        assert_eq!(read(Some("SANS")), "maillage_sdaster");
        assert_eq!(read(None), "maillage_sdaster");
        assert!(is_a("maillage_p", "maillage_sdaster"));
    }

    #[test]
    fn crea_champ_by_type_cham() {
        let v = |k: &str| (k == "TYPE_CHAM").then(|| CVal::Str("NOEU_DEPL_R".into()));
        assert_eq!(
            computed("crea_champ_prod", &v, &|_| None),
            "cham_no_sdaster"
        );
        let v = |k: &str| (k == "TYPE_CHAM").then(|| CVal::Str("ELGA_SIEF_R".into()));
        assert_eq!(computed("crea_champ_prod", &v, &|_| None), "cham_elem");
        assert_eq!(computed("no_such_prod", &|_| None, &|_| None), UNKNOWN);
    }
}
