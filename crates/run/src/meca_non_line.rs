//! MECA_NON_LINE, code_aster 17's Python non-linear operator: mapped onto
//! the machinery of STAT_NON_LINE (the same equations, Newton loop,
//! conditions, behaviours, time list and step cutting; the converged steps
//! are those of STAT_NON_LINE within the Newton tolerance).
//!
//! Its own keywords: `CONTACT` is a factor keyword whose `DEFINITION` is a
//! `DEFI_CONT` (code_aster 17's mortar augmented-Lagrangian contact,
//! `crate::defi_cont`), paired again before every Newton iteration
//! (`ALGO_RESO_GEOM='NEWTON'`, the only value reproduced); `RESI_GEOM` is
//! accepted (the Newton tolerance decides the converged state).
//! `METHODE='SNES'`/`'RASPEN'` (PETSc solvers) and `RECH_LINEAIRE` are
//! refused; `ARCHIVAGE`, `SOLVEUR` and `INFO` are accepted as in
//! STAT_NON_LINE.

use crate::executor::Executor;
use crate::solve::{kinematics_rules, parse_setup, store_solution, SNL_VALUES};
use crate::support::{Support, Values};
use aster_eval::{CommandCall, CommandOutput, ExecError};

/// What MECA_NON_LINE reads (`crate::support`): STAT_NON_LINE's set-up
/// without the keywords code_aster 17's operator does not have.
pub(crate) const MECA_NON_LINE: Support = Support {
    keywords: KEYWORDS,
    values: &MECA_VALUES,
    hints: &[],
    reuse: false,
    rules: Some(kinematics_rules),
};

const MECA_VALUES: [Values; SNL_VALUES.len() + 2] = crate::support::joined(
    SNL_VALUES,
    &[
        Values::new("METHODE", &["NEWTON"]).why("(the PETSc solvers SNES and RASPEN)"),
        Values::new("CONTACT/ALGO_RESO_GEOM", &["NEWTON"])
            .why("(the fixed-point geometric loop of code_aster 17's mortar contact)"),
    ],
);

const KEYWORDS: &[&str] = &[
    "MODELE",
    "CHAM_MATER",
    "CARA_ELEM",
    "EXCIT",
    "EXCIT/CHARGE",
    "EXCIT/FONC_MULT",
    "EXCIT/TYPE_CHARGE",
    "CONTACT",
    "CONTACT/DEFINITION",
    "CONTACT/ALGO_RESO_GEOM",
    "CONTACT/RESI_GEOM",
    "COMPORTEMENT",
    "COMPORTEMENT/RELATION",
    "COMPORTEMENT/DEFORMATION",
    "COMPORTEMENT/TOUT",
    "COMPORTEMENT/GROUP_MA",
    "COMPORTEMENT/MAILLE",
    "COMPORTEMENT/RESI_INTE_RELA",
    "COMPORTEMENT/RESI_INTE",
    "COMPORTEMENT/ITER_INTE_MAXI",
    "COMPORTEMENT/ITER_INTE_PAS",
    "COMPORTEMENT/ALGO_INTE",
    "INCREMENT",
    "INCREMENT/LIST_INST",
    "INCREMENT/INST_INIT",
    "INCREMENT/INST_FIN",
    "INCREMENT/NUME_INST_INIT",
    "INCREMENT/NUME_INST_FIN",
    "INCREMENT/PRECISION",
    "METHODE",
    "NEWTON",
    "NEWTON/PREDICTION",
    "NEWTON/MATRICE",
    "NEWTON/REAC_ITER",
    "NEWTON/REAC_INCR",
    "NEWTON/MATR_RIGI_SYME",
    "NEWTON/REAC_ITER_ELAS",
    "CONVERGENCE",
    "CONVERGENCE/RESI_GLOB_RELA",
    "CONVERGENCE/RESI_GLOB_MAXI",
    "CONVERGENCE/ITER_GLOB_MAXI",
    "CONVERGENCE/ITER_GLOB_ELAS",
    "CONVERGENCE/ARRET",
    "SOLVEUR",
    "SOLVEUR/*",
    "ETAT_INIT",
    "ETAT_INIT/EVOL_NOLI",
    "ETAT_INIT/INST",
    "ETAT_INIT/NUME_ORDRE",
    "ETAT_INIT/PRECISION",
    "ETAT_INIT/CRITERE",
    "INFO",
    "TITRE",
    "ARCHIVAGE",
    "ARCHIVAGE/*",
];

pub fn meca_non_line(ex: &mut Executor, call: &CommandCall) -> Result<CommandOutput, ExecError> {
    let setup = parse_setup(ex, call, false)?;
    store_solution(ex, call, &setup, false)
}
