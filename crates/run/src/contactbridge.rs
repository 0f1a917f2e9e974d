//! The bridge to aster-contact: DEFI_CONTACT zones (DISCRETE/CONTINUE).

use crate::executor::Executor;
use aster_eval::{ExecError, Keywords};
use aster_fem::UnilateralSource;
use aster_mesh::Mesh;

pub fn sources(ex: &Executor, mesh: &Mesh, kw: &Keywords) -> Result<Vec<Box<dyn UnilateralSource>>, ExecError> {
    let _ = mesh;
    let span = kw.keyword("FORMULATION").map(|k| k.span).unwrap_or_default();
    let f = kw.str("FORMULATION").unwrap_or("DISCRETE");
    Err(ex.unsupported(&format!("DEFI_CONTACT/FORMULATION='{f}' (contact zones)"), span))
}
