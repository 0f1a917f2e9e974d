//! One module per family of commands; [`dispatch`] maps a command name to
//! its implementation.

mod crea_maillage;
mod define;
mod elementary;
mod functions;
mod inspect;
mod loads;
mod loads_f;
mod mesh;
mod post;
mod post_elem;
mod pressure;
mod results;
mod tables;

use crate::executor::Executor;
use aster_eval::{CommandCall, CommandOutput, ExecError};

/// Runs one command.
pub fn dispatch(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    match call.command.as_str() {
        "DEBUT" | "POURSUITE" => Ok(CommandOutput::Nothing),
        "FIN" => {
            ex.finished = true;
            Ok(CommandOutput::Nothing)
        }
        "LIRE_MAILLAGE" => mesh::lire_maillage(ex, call),
        "PRE_GMSH" | "PRE_GIBI" => mesh::pre_convert(ex, call),
        "ASSE_MAILLAGE" => mesh::asse_maillage(ex, call),
        "DEFI_GROUP" => mesh::defi_group(ex, call),
        "MODI_MAILLAGE" => mesh::modi_maillage(ex, call),
        "CREA_MAILLAGE" => crea_maillage::crea_maillage(ex, call),
        "DEFI_MATERIAU" => define::defi_materiau(ex, call),
        "AFFE_MATERIAU" => define::affe_materiau(ex, call),
        "AFFE_MODELE" => define::affe_modele(ex, call),
        "AFFE_CARA_ELEM" => define::affe_cara_elem(ex, call),
        "DEFI_FONCTION" => define::defi_fonction(ex, call),
        "DEFI_CONSTANTE" => define::defi_constante(ex, call),
        "DEFI_LIST_REEL" => define::defi_list_reel(ex, call),
        "DEFI_LIST_INST" => define::defi_list_inst(ex, call),
        "AFFE_CHAR_CINE" => loads::affe_char_cine(ex, call),
        "AFFE_CHAR_MECA" => loads::affe_char_meca(ex, call),
        "AFFE_CHAR_MECA_F" => loads_f::affe_char_meca_f(ex, call),
        "AFFE_CHAR_CINE_F" => loads_f::affe_char_cine_f(ex, call),
        "DEFI_CONTACT" => loads::defi_contact(ex, call),
        "STAT_NON_LINE" => crate::solve::stat_non_line(ex, call),
        "MECA_STATIQUE" => crate::solve::meca_statique(ex, call),
        "CALC_CHAMP" => crate::solve::calc_champ(ex, call),
        "CREA_CHAMP" => post::crea_champ(ex, call),
        "POST_RELEVE_T" => post::post_releve_t(ex, call),
        "IMPR_TABLE" => post::impr_table(ex, call),
        "IMPR_RESU" => post::impr_resu(ex, call),
        "TEST_RESU" => inspect::test_resu(ex, call),
        "TEST_TABLE" => inspect::test_table(ex, call),
        "TEST_FONCTION" => inspect::test_fonction(ex, call),
        "CALCUL" => elementary::calcul(ex, call),
        "CALC_VECT_ELEM" => elementary::calc_vect_elem(ex, call),
        "EXTR_TABLE" => elementary::extr_table(ex, call),
        "NUME_DDL" => elementary::nume_ddl(ex, call),
        "ASSE_VECTEUR" => elementary::asse_vecteur(ex, call),
        "RECU_FONCTION" => functions::recu_fonction(ex, call),
        "CALC_FONC_INTERP" => functions::calc_fonc_interp(ex, call),
        "CALC_FONCTION" => functions::calc_fonction(ex, call),
        "IMPR_FONCTION" => functions::impr_fonction(ex, call),
        "DEFI_LIST_ENTI" => functions::defi_list_enti(ex, call),
        "DEFI_FICHIER" => functions::defi_fichier(ex, call),
        "CREA_TABLE" => tables::crea_table(ex, call),
        "CALC_TABLE" => tables::calc_table(ex, call),
        "CALC_PRESSION" => pressure::calc_pression(ex, call),
        "POST_ELEM" => post_elem::post_elem(ex, call),
        "CREA_RESU" => results::crea_resu(ex, call),
        "RECU_TABLE" => results::recu_table(ex, call),
        "MACR_ADAP_MAIL" => Err(ex.unsupported(
            "MACR_ADAP_MAIL (mesh adaptation runs the external HOMARD tool, which aster does not have)",
            call.span,
        )),
        "DETRUIRE" => Ok(CommandOutput::Nothing),
        // The formula itself arrives through `CommandSink::formula`.
        "FORMULE" => Ok(CommandOutput::Concept),
        other => Err(ex.unsupported(other, call.span)),
    }
}

/// NUME_ORDRE of the steps an occurrence designates.
pub fn select_steps_pub(
    ex: &Executor,
    cmd: &str,
    occ: &aster_eval::Keywords,
    result: &crate::concept::EvolResult,
) -> Result<Vec<u32>, ExecError> {
    Ok(post::select_steps(ex, cmd, occ, result)?
        .iter()
        .map(|s| s.nume_ordre)
        .collect())
}

/// Appends text to a file the program writes (IMPR_* on a unit).
pub fn append_file(path: &std::path::Path, text: &str) -> Result<(), ExecError> {
    post::append(path, text)
}
