//! One module per family of commands; [`dispatch`] maps a command name to
//! its implementation.

pub(crate) mod calc_erreur;
pub(crate) mod cara_coque;
pub(crate) mod cara_grille;
pub(crate) mod cara_massif;
pub(crate) mod cara_poutre;
pub(crate) mod composite;
pub(crate) mod crea_champ_elga;
pub(crate) mod crea_maillage;
pub(crate) mod define;
pub(crate) mod elas_mult;
pub(crate) mod elementary;
pub(crate) mod fracture;
pub(crate) mod functions;
pub(crate) mod inspect;
pub(crate) mod liaison_mail;
pub(crate) mod lire_fonction;
pub(crate) mod lire_resu;
pub(crate) mod loads;
pub(crate) mod loads_f;
pub(crate) mod loads_more;
pub(crate) mod macr_cara_poutre;
pub(crate) mod macr_lign_coupe;
pub(crate) mod mesh;
pub(crate) mod modal;
pub(crate) mod modi_repere;
pub(crate) mod post;
pub(crate) mod post_elem;
pub(crate) mod post_erreur;
pub(crate) mod pressure;
pub(crate) mod proj_champ;
pub(crate) mod results;
pub(crate) mod substructure;
pub(crate) mod tables;
pub(crate) mod thermal;
pub(crate) mod thermal_nl;

use crate::executor::Executor;
use crate::support::Support;
use aster_eval::{CommandCall, CommandOutput, ExecError};

/// The implementation of one command.
type Handler = fn(&mut Executor, &CommandCall) -> Result<CommandOutput, ExecError>;

/// A command `aster run` executes: its implementation and what it supports.
pub struct Command {
    pub name: &'static str,
    run: Handler,
    pub support: Support,
}

/// Every command `aster run` executes. Any other is refused (before the run,
/// by `crate::preflight`).
pub static COMMANDS: &[Command] = &[
    Command {
        name: "DEBUT",
        run: nothing,
        support: Support::keywords(&["*"]),
    },
    Command {
        name: "POURSUITE",
        run: nothing,
        support: Support::keywords(&["*"]),
    },
    Command {
        name: "FIN",
        run: fin,
        support: Support::keywords(&["*"]),
    },
    Command {
        name: "DETRUIRE",
        run: nothing,
        support: Support::keywords(&["*"]),
    },
    // The formula itself arrives through `CommandSink::formula`.
    Command {
        name: "FORMULE",
        run: concept,
        support: Support::keywords(&["*"]),
    },
    Command {
        name: "LIRE_MAILLAGE",
        run: mesh::lire_maillage,
        support: mesh::LIRE_MAILLAGE,
    },
    Command {
        name: "PRE_GMSH",
        run: mesh::pre_convert,
        support: mesh::PRE_GMSH,
    },
    Command {
        name: "PRE_GIBI",
        run: mesh::pre_convert,
        support: mesh::PRE_GIBI,
    },
    Command {
        name: "PRE_IDEAS",
        run: mesh::pre_convert,
        support: mesh::PRE_IDEAS,
    },
    Command {
        name: "ASSE_MAILLAGE",
        run: mesh::asse_maillage,
        support: mesh::ASSE_MAILLAGE,
    },
    Command {
        name: "MACR_ELEM_STAT",
        run: substructure::macr_elem_stat,
        support: substructure::MACR_ELEM_STAT,
    },
    Command {
        name: "DEFI_MAILLAGE",
        run: substructure::defi_maillage,
        support: substructure::DEFI_MAILLAGE,
    },
    Command {
        name: "DEFI_GROUP",
        run: mesh::defi_group,
        support: mesh::DEFI_GROUP,
    },
    Command {
        name: "MODI_MAILLAGE",
        run: mesh::modi_maillage,
        support: mesh::MODI_MAILLAGE,
    },
    Command {
        name: "CREA_MAILLAGE",
        run: crea_maillage::crea_maillage,
        support: crea_maillage::CREA_MAILLAGE,
    },
    Command {
        name: "AFFE_CHAR_THER",
        run: thermal::affe_char_ther,
        support: thermal::AFFE_CHAR_THER,
    },
    Command {
        name: "AFFE_CHAR_THER_F",
        run: thermal::affe_char_ther_f,
        support: thermal::AFFE_CHAR_THER_F,
    },
    Command {
        name: "THER_LINEAIRE",
        run: thermal::ther_lineaire,
        support: thermal::THER_LINEAIRE,
    },
    Command {
        name: "THER_NON_LINE",
        run: thermal_nl::ther_non_line,
        support: thermal_nl::THER_NON_LINE,
    },
    Command {
        name: "DEFI_MATERIAU",
        run: define::defi_materiau,
        support: define::DEFI_MATERIAU,
    },
    Command {
        name: "DEFI_COMPOSITE",
        run: composite::defi_composite,
        support: composite::DEFI_COMPOSITE,
    },
    Command {
        name: "AFFE_MATERIAU",
        run: define::affe_materiau,
        support: define::AFFE_MATERIAU,
    },
    Command {
        name: "AFFE_MODELE",
        run: define::affe_modele,
        support: define::AFFE_MODELE,
    },
    Command {
        name: "AFFE_CARA_ELEM",
        run: define::affe_cara_elem,
        support: define::AFFE_CARA_ELEM,
    },
    Command {
        name: "DEFI_FONCTION",
        run: define::defi_fonction,
        support: define::DEFI_FONCTION,
    },
    Command {
        name: "DEFI_NAPPE",
        run: define::defi_nappe,
        support: define::DEFI_NAPPE,
    },
    Command {
        name: "DEFI_CONSTANTE",
        run: define::defi_constante,
        support: define::DEFI_CONSTANTE,
    },
    Command {
        name: "DEFI_LIST_REEL",
        run: define::defi_list_reel,
        support: define::DEFI_LIST_REEL,
    },
    Command {
        name: "DEFI_LIST_INST",
        run: define::defi_list_inst,
        support: define::DEFI_LIST_INST,
    },
    Command {
        name: "AFFE_CHAR_CINE",
        run: loads::affe_char_cine,
        support: loads::AFFE_CHAR_CINE,
    },
    Command {
        name: "AFFE_CHAR_MECA",
        run: loads::affe_char_meca,
        support: loads::AFFE_CHAR_MECA,
    },
    Command {
        name: "AFFE_CHAR_MECA_F",
        run: loads_f::affe_char_meca_f,
        support: loads_f::AFFE_CHAR_MECA_F,
    },
    Command {
        name: "AFFE_CHAR_CINE_F",
        run: loads_f::affe_char_cine_f,
        support: loads_f::AFFE_CHAR_CINE_F,
    },
    Command {
        name: "DEFI_CONT",
        run: crate::defi_cont::defi_cont,
        support: crate::defi_cont::DEFI_CONT,
    },
    Command {
        name: "DEFI_CONTACT",
        run: loads::defi_contact,
        support: crate::contactbridge::DEFI_CONTACT,
    },
    Command {
        name: "STAT_NON_LINE",
        run: crate::solve::stat_non_line,
        support: crate::solve::STAT_NON_LINE,
    },
    Command {
        name: "DYNA_NON_LINE",
        run: crate::dyna::dyna_non_line,
        support: crate::dyna::DYNA_NON_LINE,
    },
    Command {
        name: "MECA_NON_LINE",
        run: crate::meca_non_line::meca_non_line,
        support: crate::meca_non_line::MECA_NON_LINE,
    },
    Command {
        name: "MECA_STATIQUE",
        run: crate::solve::meca_statique,
        support: crate::solve::MECA_STATIQUE,
    },
    Command {
        name: "MACRO_ELAS_MULT",
        run: elas_mult::macro_elas_mult,
        support: elas_mult::MACRO_ELAS_MULT,
    },
    Command {
        name: "CALC_CHAMP",
        run: crate::solve::calc_champ,
        support: crate::solve::CALC_CHAMP,
    },
    Command {
        name: "POST_CHAMP",
        run: results::post_champ,
        support: results::POST_CHAMP,
    },
    Command {
        name: "CREA_CHAMP",
        run: post::crea_champ,
        support: post::CREA_CHAMP,
    },
    Command {
        name: "POST_RELEVE_T",
        run: post::post_releve_t,
        support: post::POST_RELEVE_T,
    },
    Command {
        name: "MACR_CARA_POUTRE",
        run: macr_cara_poutre::macr_cara_poutre,
        support: macr_cara_poutre::MACR_CARA_POUTRE,
    },
    Command {
        name: "MACR_LIGN_COUPE",
        run: macr_lign_coupe::macr_lign_coupe,
        support: macr_lign_coupe::MACR_LIGN_COUPE,
    },
    Command {
        name: "MODI_REPERE",
        run: modi_repere::modi_repere,
        support: modi_repere::MODI_REPERE,
    },
    Command {
        name: "PROJ_CHAMP",
        run: proj_champ::proj_champ,
        support: proj_champ::PROJ_CHAMP,
    },
    Command {
        name: "IMPR_TABLE",
        run: post::impr_table,
        support: post::IMPR_TABLE,
    },
    Command {
        name: "IMPR_RESU",
        run: post::impr_resu,
        support: crate::output::IMPR_RESU,
    },
    Command {
        name: "TEST_RESU",
        run: inspect::test_resu,
        support: inspect::TEST_RESU,
    },
    Command {
        name: "TEST_TABLE",
        run: inspect::test_table,
        support: inspect::TEST_TABLE,
    },
    Command {
        name: "TEST_FONCTION",
        run: inspect::test_fonction,
        support: inspect::TEST_FONCTION,
    },
    Command {
        name: "CALCUL",
        run: elementary::calcul,
        support: elementary::CALCUL,
    },
    Command {
        name: "CALC_VECT_ELEM",
        run: elementary::calc_vect_elem,
        support: elementary::CALC_VECT_ELEM,
    },
    Command {
        name: "EXTR_TABLE",
        run: elementary::extr_table,
        support: elementary::EXTR_TABLE,
    },
    Command {
        name: "NUME_DDL",
        run: elementary::nume_ddl,
        support: elementary::NUME_DDL,
    },
    Command {
        name: "CALC_MATR_ELEM",
        run: modal::calc_matr_elem,
        support: modal::CALC_MATR_ELEM,
    },
    Command {
        name: "ASSE_MATRICE",
        run: modal::asse_matrice,
        support: modal::ASSE_MATRICE,
    },
    Command {
        name: "ASSEMBLAGE",
        run: modal::assemblage,
        support: modal::ASSEMBLAGE,
    },
    Command {
        name: "CALC_MODES",
        run: modal::calc_modes,
        support: modal::CALC_MODES,
    },
    Command {
        name: "NORM_MODE",
        run: modal::norm_mode,
        support: modal::NORM_MODE,
    },
    Command {
        name: "ASSE_VECTEUR",
        run: elementary::asse_vecteur,
        support: elementary::ASSE_VECTEUR,
    },
    Command {
        name: "RECU_FONCTION",
        run: functions::recu_fonction,
        support: functions::RECU_FONCTION,
    },
    Command {
        name: "CALC_FONC_INTERP",
        run: functions::calc_fonc_interp,
        support: functions::CALC_FONC_INTERP,
    },
    Command {
        name: "CALC_FONCTION",
        run: functions::calc_fonction,
        support: functions::CALC_FONCTION,
    },
    Command {
        name: "IMPR_FONCTION",
        run: functions::impr_fonction,
        support: functions::IMPR_FONCTION,
    },
    Command {
        name: "DEFI_LIST_ENTI",
        run: functions::defi_list_enti,
        support: functions::DEFI_LIST_ENTI,
    },
    Command {
        name: "DEFI_FICHIER",
        run: functions::defi_fichier,
        support: functions::DEFI_FICHIER,
    },
    Command {
        name: "CREA_TABLE",
        run: tables::crea_table,
        support: tables::CREA_TABLE,
    },
    Command {
        name: "CALC_TABLE",
        run: tables::calc_table,
        support: tables::CALC_TABLE,
    },
    Command {
        name: "LIRE_FONCTION",
        run: lire_fonction::lire_fonction,
        support: lire_fonction::LIRE_FONCTION,
    },
    Command {
        name: "LIRE_RESU",
        run: lire_resu::lire_resu,
        support: lire_resu::LIRE_RESU,
    },
    Command {
        name: "RECU_TABLE",
        run: tables::recu_table,
        support: tables::RECU_TABLE,
    },
    Command {
        name: "CALC_PRESSION",
        run: pressure::calc_pression,
        support: pressure::CALC_PRESSION,
    },
    Command {
        name: "POST_ELEM",
        run: post_elem::post_elem,
        support: post_elem::POST_ELEM,
    },
    Command {
        name: "CALC_ERREUR",
        run: calc_erreur::calc_erreur,
        support: calc_erreur::CALC_ERREUR,
    },
    Command {
        name: "POST_ERREUR",
        run: post_erreur::post_erreur,
        support: post_erreur::POST_ERREUR,
    },
    Command {
        name: "DEFI_FOND_FISS",
        run: fracture::defi_fond_fiss,
        support: fracture::DEFI_FOND_FISS,
    },
    Command {
        name: "CALC_G",
        run: fracture::calc_g,
        support: fracture::CALC_G,
    },
    Command {
        name: "POST_K1_K2_K3",
        run: fracture::post_k1_k2_k3,
        support: fracture::POST_K1_K2_K3,
    },
    Command {
        name: "CREA_RESU",
        run: results::crea_resu,
        support: results::CREA_RESU,
    },
];

fn nothing(_: &mut Executor, _: &CommandCall) -> Result<CommandOutput, ExecError> {
    Ok(CommandOutput::Nothing)
}

fn concept(_: &mut Executor, _: &CommandCall) -> Result<CommandOutput, ExecError> {
    Ok(CommandOutput::Concept)
}

fn fin(ex: &mut Executor, _: &CommandCall) -> Result<CommandOutput, ExecError> {
    ex.finished = true;
    Ok(CommandOutput::Nothing)
}

/// The command of that name, if `aster run` executes it.
pub fn find(name: &str) -> Option<&'static Command> {
    COMMANDS.iter().find(|c| c.name == name)
}

/// Runs one command, after checking it against its support entry (the
/// same check the static pass made: a refusal here is located the same way).
pub fn dispatch(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let command = find(&call.command);
    let support = command.map(|c| &c.support);
    if let Some(r) = crate::support::check_call(support, call).into_iter().next() {
        return Err(ex.unsupported(&r.what, r.span));
    }
    match command {
        Some(c) => (c.run)(ex, call),
        None => Err(ex.unsupported(&call.command, call.span)),
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
