//! The plate facets of code_aster's `DKT`, `DST` and `Q4G` modelisations
//! behind one interface ([`PlateTheory`]): stiffness, mass, generalised
//! efforts and strains, and the points where they are given, dispatched by
//! theory and cell type (TRIA3, QUAD4) to [`crate::dkt`], [`crate::dkq`],
//! [`crate::dst`] and [`crate::q4g`].

use crate::dkt::{Efforts, Generalised, ShellSection};
use crate::material::Elastic;
use crate::shape::GaussPoint;
use aster_mesh::CellType;
use nalgebra::{DMatrix, Matrix3};

/// Which plate element a `Shell` facet is (`AFFE_MODELE/MODELISATION`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PlateTheory {
    /// `DKT`: discrete Kirchhoff, no transverse shear strain (`MEDKTR3`,
    /// `MEDKQU4`).
    #[default]
    Dkt,
    /// `DST`: discrete shear (`MEDSTR3`, `MEDSQU4`).
    Dst,
    /// `Q4G`: assumed shear strains (`MET3TR3`, `MEQ4QU4`).
    Q4g,
}

impl PlateTheory {
    /// The modelisation's name.
    pub fn name(self) -> &'static str {
        match self {
            PlateTheory::Dkt => "DKT",
            PlateTheory::Dst => "DST",
            PlateTheory::Q4g => "Q4G",
        }
    }

    /// Whether the plate has a transverse shear strain (DST, Q4G): its
    /// stresses by layer carry SIXZ SIYZ.
    pub fn has_shear_strain(self) -> bool {
        self != PlateTheory::Dkt
    }
}

/// An offset section (`EXCENTREMENT`) is reproduced on the DKT and DKQ
/// facets only (`dktrig`, `dkqrig`, `dktmas`, `dkqmas`, `dktedg`,
/// `dkqedg`); DST's and Q4G's own coupling terms (`dstrig`, `dsqrig`,
/// `q4grig`, `t3grig`) are not.
pub fn check_offset(theory: PlateTheory, section: &ShellSection) -> Result<(), String> {
    if section.offset != 0. && theory != PlateTheory::Dkt {
        return Err(format!(
            "an offset section (EXCENTREMENT = {}) is reproduced on DKT/DKQ facets only, not on {}",
            section.offset,
            theory.name()
        ));
    }
    Ok(())
}

fn check_nodes(theory: PlateTheory, xyz: &[[f64; 3]]) -> Result<(), String> {
    if matches!(xyz.len(), 3 | 4) {
        Ok(())
    } else {
        Err(format!(
            "the {} plate exists on TRIA3 and QUAD4 cells only",
            theory.name()
        ))
    }
}

/// The frame `pgl` (rows x, y, z) of a facet with nodes at `xyz` (3 or 4):
/// `dxtpgl` on a triangle, `dxqpgl` on a quadrangle.
pub fn frame(xyz: &[[f64; 3]]) -> Result<Matrix3<f64>, String> {
    match xyz {
        [a, b, c] => Ok(crate::dkt::Facet::new(&[*a, *b, *c])?.pgl),
        [a, b, c, d] => Ok(crate::dkq::Quad::new(&[*a, *b, *c, *d])?.pgl),
        _ => Err("a plate facet has 3 or 4 nodes".into()),
    }
}

/// The section of a facet at `xyz` made of the plies of `laminate`
/// ([`crate::laminate`]), whose reference direction is `direction`
/// (`ANGL_REP`/`VECTEUR`): `base` with the stack's matrices in the facet's
/// frame and its total thickness.
pub fn layered_section(
    xyz: &[[f64; 3]],
    base: &ShellSection,
    laminate: std::sync::Arc<crate::laminate::Laminate>,
    direction: [f64; 3],
) -> Result<ShellSection, String> {
    let pgl = frame(xyz)?;
    let thickness = laminate.thickness;
    let layered = crate::laminate::LayeredSection::new(laminate, &pgl, direction)?;
    Ok(ShellSection {
        thickness,
        layered: Some(std::sync::Arc::new(layered)),
        ..base.clone()
    })
}

/// The global stiffness (node-major DX DY DZ DRX DRY DRZ) of a facet with
/// nodes at `xyz` (3 or 4).
pub fn stiffness(
    theory: PlateTheory,
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
) -> Result<DMatrix<f64>, String> {
    check_nodes(theory, xyz)?;
    check_offset(theory, section)?;
    match (theory, xyz) {
        (PlateTheory::Dkt, [a, b, c]) => crate::dkt::stiffness(&[*a, *b, *c], material, section),
        (PlateTheory::Dkt, [a, b, c, d]) => {
            crate::dkq::stiffness(&[*a, *b, *c, *d], material, section)
        }
        (PlateTheory::Dst, _) => crate::dst::stiffness(xyz, material, section),
        (_, _) => crate::q4g::stiffness(xyz, material, section),
    }
}

/// The global mass of a facet of density `rho` and its mass ρ·h·A
/// (`dialum`'s weight when lumped). `te0031`: DKT's `dktmas`/`dkqmas`,
/// DST's `dstmas`/`dsqmas`, Q4G's `q4gmas` on QUAD4 and the DKT's
/// `dktmas` on its TRIA3 — integrated there on the element's RIGI family,
/// FPG1.
pub fn mass(
    theory: PlateTheory,
    xyz: &[[f64; 3]],
    material: &Elastic,
    rho: f64,
    section: &ShellSection,
) -> Result<(DMatrix<f64>, f64), String> {
    check_nodes(theory, xyz)?;
    check_offset(theory, section)?;
    match (theory, xyz) {
        (PlateTheory::Dkt, [a, b, c]) => crate::dkt::mass(&[*a, *b, *c], rho, section),
        // `dktmas` on Q4G's triangle reads its RIGI family, FPG1.
        (PlateTheory::Q4g, [a, b, c]) => crate::dkt::mass_on(
            &[*a, *b, *c],
            rho,
            section,
            &rigi_scheme(theory, CellType::TRIA3),
        ),
        (PlateTheory::Dkt, [a, b, c, d]) => crate::dkq::mass(&[*a, *b, *c, *d], rho, section),
        (PlateTheory::Q4g, [a, b, c, d]) => crate::q4g::quad_mass(&[*a, *b, *c, *d], rho, section),
        (_, _) => crate::dst::mass(xyz, material, rho, section),
    }
}

/// The RIGI family of a facet (where `EFGE_ELGA` is given): FPG3 on the
/// DKT and DST triangles, FPG1 on Q4G's, FPG4 on the quadrangles.
pub fn rigi_scheme(theory: PlateTheory, ty: CellType) -> Vec<GaussPoint> {
    match (theory, ty) {
        (PlateTheory::Q4g, CellType::TRIA3) => crate::shape::rigi_scheme(CellType::TRIA3),
        (_, CellType::TRIA3) => crate::dkt::fpg3(),
        _ => crate::dkq::fpg4(),
    }
}

/// The cell's nodes in reference coordinates (the `NOEU` family).
pub fn nodes(ty: CellType) -> Vec<[f64; 2]> {
    match ty {
        CellType::TRIA3 => crate::dkt::NODES.to_vec(),
        _ => crate::dkq::NODES.to_vec(),
    }
}

/// Generalised efforts or strains at the reference `points` of a facet, in
/// its frame, with that frame `pgl` (rows x, y, z); `u` the global
/// displacements of its nodes (6 per node).
pub fn generalised_at(
    theory: PlateTheory,
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64],
    points: &[[f64; 2]],
    what: Generalised,
) -> Result<(Matrix3<f64>, Vec<Efforts>), String> {
    check_nodes(theory, xyz)?;
    check_offset(theory, section)?;
    match (theory, xyz) {
        (PlateTheory::Dkt, [a, b, c]) => {
            let xyz = [*a, *b, *c];
            let facet = crate::dkt::Facet::new(&xyz)?;
            let ue: [f64; 18] = std::array::from_fn(|i| u[i]);
            let e = crate::dkt::generalised_at(&xyz, material, section, &ue, points, what)?;
            Ok((facet.pgl, e))
        }
        (PlateTheory::Dkt, [a, b, c, d]) => {
            let xyz = [*a, *b, *c, *d];
            let quad = crate::dkq::Quad::new(&xyz)?;
            let ue: [f64; 24] = std::array::from_fn(|i| u[i]);
            let e = crate::dkq::generalised_at(&xyz, material, section, &ue, points, what)?;
            Ok((quad.pgl, e))
        }
        (PlateTheory::Dst, _) => {
            crate::dst::generalised_at(xyz, material, section, u, points, what)
        }
        (_, _) => crate::q4g::generalised_at(xyz, material, section, u, points, what),
    }
}
