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
    /// `DKTG`: the DKT/DKQ facets with a behaviour integrated on the
    /// generalised strains (`MEDKTG3`, `MEDKQG4`, `te0409`): with `ELAS`
    /// the DKT's stiffness, mass and linear efforts; a non-linear result's
    /// efforts are the Gauss points' N and M, without shear forces
    /// (`ef0409`: QX = QY = 0).
    Dktg,
    /// `Q4GG`: the Q4G facets with a behaviour integrated on the
    /// generalised strains (`MET3GG3`, `MEQ4GG4`, `te0409`): with `ELAS`
    /// the Q4G's stiffness, plus, with an offset, the membrane–bending
    /// coupling ∫ Bmᵀ·Dmf·Bf that `te0409` adds for every facet.
    Q4gg,
}

impl PlateTheory {
    /// The modelisation's name.
    pub fn name(self) -> &'static str {
        match self {
            PlateTheory::Dkt => "DKT",
            PlateTheory::Dst => "DST",
            PlateTheory::Q4g => "Q4G",
            PlateTheory::Dktg => "DKTG",
            PlateTheory::Q4gg => "Q4GG",
        }
    }

    /// The facet whose stiffness, mass and linear efforts this one has:
    /// `DKTG` is the DKT's, `Q4GG` the Q4G's.
    pub fn base(self) -> PlateTheory {
        match self {
            PlateTheory::Dktg => PlateTheory::Dkt,
            PlateTheory::Q4gg => PlateTheory::Q4g,
            t => t,
        }
    }

    /// `DKTG`, `Q4GG`: the behaviour is integrated on the generalised
    /// strains (`te0409`), so the element runs in `STAT_NON_LINE`.
    pub fn is_global(self) -> bool {
        matches!(self, PlateTheory::Dktg | PlateTheory::Q4gg)
    }

    /// Whether the plate has a transverse shear strain (DST, Q4G): its
    /// stresses by layer carry SIXZ SIYZ.
    pub fn has_shear_strain(self) -> bool {
        self.base() != PlateTheory::Dkt
    }
}

/// An offset section (`EXCENTREMENT`) is reproduced on the DKT and DKQ
/// facets (`dktrig`, `dkqrig`, `dktmas`, `dkqmas`, `dktedg`, `dkqedg`),
/// and in the stiffness and efforts of the `DKTG` and `Q4GG` ones
/// (`te0409`'s coupling, `q4gedg`); DST's and Q4G's own coupling terms
/// (`dstrig`, `dsqrig`, `q4grig`, `t3grig`) are not, nor the mass of an
/// offset Q4GG.
pub fn check_offset(theory: PlateTheory, section: &ShellSection) -> Result<(), String> {
    if section.offset != 0.
        && !matches!(
            theory,
            PlateTheory::Dkt | PlateTheory::Dktg | PlateTheory::Q4gg
        )
    {
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
    match (theory.base(), xyz) {
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
/// FPG1; `te0444`: DKTG's and Q4GG's the DKT's `dktmas`/`dkqmas` (Q4GG's
/// triangle on its FPG1).
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
        (PlateTheory::Dkt | PlateTheory::Dktg, [a, b, c]) => {
            crate::dkt::mass(&[*a, *b, *c], rho, section)
        }
        // `dktmas` on Q4G's and Q4GG's triangle reads its RIGI family,
        // FPG1.
        (PlateTheory::Q4g | PlateTheory::Q4gg, [a, b, c]) => crate::dkt::mass_on(
            &[*a, *b, *c],
            rho,
            section,
            &rigi_scheme(PlateTheory::Q4g, CellType::TRIA3),
        ),
        // `te0444`: the DKTG and Q4GG quadrangles both take the DKQ's
        // `dkqmas` (offset included).
        (PlateTheory::Dkt | PlateTheory::Dktg | PlateTheory::Q4gg, [a, b, c, d]) => {
            crate::dkq::mass(&[*a, *b, *c, *d], rho, section)
        }
        (PlateTheory::Q4g, [a, b, c, d]) => crate::q4g::quad_mass(&[*a, *b, *c, *d], rho, section),
        (_, _) => crate::dst::mass(xyz, material, rho, section),
    }
}

/// The RIGI family of a facet (where `EFGE_ELGA` is given): FPG3 on the
/// DKT and DST triangles, FPG1 on Q4G's, FPG4 on the quadrangles.
pub fn rigi_scheme(theory: PlateTheory, ty: CellType) -> Vec<GaussPoint> {
    match (theory.base(), ty) {
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
    match (theory.base(), xyz) {
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

/// The points (ξ, η) of a facet's RIGI family and their weights w·area
/// (triangle) or w·det J (quadrangle).
fn rigi_points(theory: PlateTheory, xyz: &[[f64; 3]]) -> Result<(Vec<[f64; 2]>, Vec<f64>), String> {
    let ty = if xyz.len() == 3 {
        CellType::TRIA3
    } else {
        CellType::QUAD4
    };
    let scheme = rigi_scheme(theory, ty);
    let points: Vec<[f64; 2]> = scheme.iter().map(|g| [g.xi[0], g.xi[1]]).collect();
    let weights: Vec<f64> = match xyz {
        [a, b, c] => {
            let facet = crate::dkt::Facet::new(&[*a, *b, *c])?;
            scheme.iter().map(|g| g.weight * facet.c[6]).collect()
        }
        [a, b, c, d] => {
            let quad = crate::dkq::Quad::new(&[*a, *b, *c, *d])?;
            scheme
                .iter()
                .map(|g| g.weight * quad.jacobian(g.xi[0], g.xi[1]).0)
                .collect()
        }
        _ => return Err("a plate facet has 3 or 4 nodes".into()),
    };
    Ok((points, weights))
}

/// The components of a plate's elastic energy (`ENEL_ELGA`,
/// `ENEL_ELEM`: `te0412`).
pub const ENERGY_NAMES: [&str; 5] = ["TOTALE", "MEMBRANE", "FLEXION", "CISAILLE", "COUPL_MF"];

/// The elastic energy density of a facet at the points of its RIGI family
/// ([`ENERGY_NAMES`]) and the points' weights (w·area or w·det J), as
/// code_aster's `te0412` computes it for an elastic facet:
/// - a non-linear result (`linear` false, a behaviour given): ½ N·ε and
///   ½ M·κ with the efforts (N, M) of the facet's own element and the
///   strains of the DKT's operators (`dxtbm`/`dktbf`, `dxqbm`/`dkqbf`),
///   whatever the facet — so a Q4GG reads the DKQ's curvatures against
///   its own moments; no shear or coupling term;
/// - a linear result: the generalised strains of `*edg` (DEGE) with
///   `dxmate`'s matrices, ½ ε·Dm·ε, ½ κ·Df·κ, ½ γ·Dc·γ — γ being DEGE's
///   GAX GAY, half the engineering shear, as `te0412` reads them — and
///   with an offset the coupling ½ (ε·Dmf·κ + κ·Dmf·ε).
///
/// Layered (`DEFI_COMPOSITE`) sections are errors.
pub fn elastic_energy(
    theory: PlateTheory,
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
    u: &[f64],
    linear: bool,
) -> Result<(Vec<[f64; 5]>, Vec<f64>), String> {
    check_nodes(theory, xyz)?;
    if section.layered.is_some() {
        return Err(
            "the elastic energy of a layered (DEFI_COMPOSITE) plate is not implemented".into(),
        );
    }
    let (points, weights) = rigi_points(theory, xyz)?;
    let dot3 = |a: &[f64], b: &[f64]| (0..3).map(|i| a[i] * b[i]).sum::<f64>();
    let mat3 = |m: &[[f64; 3]; 3], v: &[f64]| -> [f64; 3] {
        std::array::from_fn(|i| (0..3).map(|j| m[i][j] * v[j]).sum())
    };
    // DEGE's tensor shears back to engineering ones (εxy → γxy, κxy).
    let engineering = |e: &Efforts| ([e[0], e[1], 2. * e[2]], [e[3], e[4], 2. * e[5]]);
    let values = if linear {
        let (_, strains) = generalised_at(
            theory,
            xyz,
            material,
            section,
            u,
            &points,
            Generalised::Strains,
        )?;
        let (dm, df) = crate::dkt::section_matrices(material, section);
        let dc = crate::q4g::shear_stiffness(material, section);
        let dmf = crate::dkt::coupling(material, section);
        strains
            .iter()
            .map(|e| {
                let (eps, khi) = engineering(e);
                let gam = [e[6], e[7]];
                let membrane = 0.5 * dot3(&eps, &mat3(&dm, &eps));
                let bending = 0.5 * dot3(&khi, &mat3(&df, &khi));
                let shear = 0.5
                    * (0..2)
                        .map(|i| gam[i] * (0..2).map(|j| dc[i][j] * gam[j]).sum::<f64>())
                        .sum::<f64>();
                let coupled = dmf.as_ref().map_or(0., |d| {
                    0.5 * (dot3(&eps, &mat3(d, &khi)) + dot3(&khi, &mat3(d, &eps)))
                });
                [
                    membrane + bending + shear + coupled,
                    membrane,
                    bending,
                    shear,
                    coupled,
                ]
            })
            .collect()
    } else {
        let (_, efforts) = generalised_at(
            theory,
            xyz,
            material,
            section,
            u,
            &points,
            Generalised::Efforts,
        )?;
        let (_, strains) = generalised_at(
            PlateTheory::Dkt,
            xyz,
            material,
            section,
            u,
            &points,
            Generalised::Strains,
        )?;
        efforts
            .iter()
            .zip(&strains)
            .map(|(f, e)| {
                let (eps, khi) = engineering(e);
                let membrane = 0.5 * dot3(&f[0..3], &eps);
                let bending = 0.5 * dot3(&f[3..6], &khi);
                [membrane + bending, membrane, bending, 0., 0.]
            })
            .collect()
    };
    Ok((values, weights))
}

/// A free strain through a plate's thickness, ε_th(z) = p₀ + p₁ z + p₂ z²
/// on xx and yy (z from the mid-surface, along the facet's normal): the
/// thermal strain α (T(z) − T_ref) of a temperature parabolic in the
/// thickness (code_aster's `PREP_VARC`, `te0408`: T = TEMP_MIL + (TEMP_SUP −
/// TEMP_INF)/h z + 2 (TEMP_INF + TEMP_SUP − 2 TEMP_MIL)/h² z²).
pub type ThicknessProfile = [f64; 3];

/// The generalised efforts of a thickness profile `p` of free strain on a
/// homogeneous isotropic plate, isotropic in the plane (xx = yy, no xy):
/// N = E/(1 − ν) ∫ ε_th dz and M = E/(1 − ν) ∫ z ε_th dz — code_aster's
/// `dxefgt` with `dxmath`'s thermo-elastic matrices, whose
/// coe1 = (T_sup + T_inf + 4 T_mil)/6 − T_ref (Simpson, exact on the
/// parabola) and coe2 = (T_sup − T_inf)/h give the same.
pub fn thermal_efforts(
    material: &Elastic,
    section: &ShellSection,
    p: ThicknessProfile,
) -> (f64, f64) {
    let h = section.thickness;
    let c = material.e / (1.0 - material.nu);
    let h3 = h * h * h / 12.0;
    (c * (p[0] * h + p[2] * h3), c * p[1] * h3)
}

/// The stress σxx = σyy that a thickness profile `p` of free strain
/// removes at height z of a homogeneous isotropic plate (plane stress):
/// E/(1 − ν) ε_th(z) (code_aster's `dxsith` at each sub-point).
pub fn thermal_stress(material: &Elastic, p: ThicknessProfile, z: f64) -> f64 {
    material.e / (1.0 - material.nu) * (p[0] + p[1] * z + p[2] * z * z)
}

/// The nodal forces (global, node-major DX DY DZ DRX DRY DRZ) of a
/// thickness profile `p` of free strain on a facet with nodes at `xyz`:
/// ∫ Bᵀ (N, M) over the facet on its RIGI family, the efforts of
/// [`thermal_efforts`] (code_aster's `CHAR_MECA_TEMP_R`, `te0035`:
/// `dxefgt` then `dxbsig`). B's rows are the membrane strains and
/// curvatures of [`generalised_at`], evaluated for each unit
/// displacement. Layered (`DEFI_COMPOSITE`) and orthotropic sections are
/// errors (`dxmath`'s ELAS_COQMU branch is not reproduced).
pub fn thermal_load(
    theory: PlateTheory,
    xyz: &[[f64; 3]],
    material: &Elastic,
    section: &ShellSection,
    p: ThicknessProfile,
) -> Result<nalgebra::DVector<f64>, String> {
    check_nodes(theory, xyz)?;
    if section.layered.is_some() || material.orthotropic.is_some() {
        return Err(
            "a thermal strain on a layered (DEFI_COMPOSITE) or orthotropic plate is not implemented"
                .into(),
        );
    }
    let (n, m) = thermal_efforts(material, section, p);
    let (points, weights) = rigi_points(theory, xyz)?;
    let ndof = 6 * xyz.len();
    let mut f = nalgebra::DVector::zeros(ndof);
    let mut unit = vec![0.0; ndof];
    for i in 0..ndof {
        unit[i] = 1.0;
        let (_, strains) = generalised_at(
            theory,
            xyz,
            material,
            section,
            &unit,
            &points,
            Generalised::Strains,
        )?;
        unit[i] = 0.0;
        f[i] = strains
            .iter()
            .zip(&weights)
            .map(|(e, w)| w * (n * (e[0] + e[1]) + m * (e[3] + e[4])))
            .sum();
    }
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The displacements (node-major DX DY DZ DRX DRY DRZ) of a flat facet
    /// in z = 0 under the membrane strain e in every direction and the
    /// curvature k in every direction: u = e (x, y), w = −k (x² + y²)/2,
    /// DRX = ∂w/∂y, DRY = −∂w/∂x.
    fn field(xyz: &[[f64; 3]], e: f64, k: f64) -> nalgebra::DVector<f64> {
        nalgebra::DVector::from_iterator(
            6 * xyz.len(),
            xyz.iter().flat_map(|p| {
                let (x, y) = (p[0], p[1]);
                [e * x, e * y, -k * (x * x + y * y) / 2., -k * y, k * x, 0.]
            }),
        )
    }

    /// A free strain p₀ + p₁ z loads a facet as the stiffness does the
    /// field it would take freely (membrane strain p₀, curvature p₁, both
    /// exactly represented): F_th = K u. So a free plate takes that field
    /// without stress, and rigid motions do no work against F_th.
    #[test]
    fn the_thermal_load_is_the_stiffness_times_the_free_field() {
        let material = Elastic::new(2e11, 0.3).unwrap();
        let section = ShellSection::new(0.01);
        let tri = vec![[0.1, 0.0, 0.0], [1.2, 0.2, 0.0], [0.3, 0.9, 0.0]];
        let quad = vec![
            [0.0, 0.0, 0.0],
            [1.1, 0.1, 0.0],
            [1.0, 0.9, 0.0],
            [-0.1, 1.2, 0.0],
        ];
        let rect = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.5, 0.0],
            [0.0, 0.5, 0.0],
        ];
        let (e, k) = (3e-4, 0.1);
        for (theory, xyz) in [
            (PlateTheory::Dkt, &tri),
            (PlateTheory::Dkt, &quad),
            (PlateTheory::Dst, &tri),
            (PlateTheory::Q4g, &rect),
        ] {
            let f = thermal_load(theory, xyz, &material, &section, [e, k, 0.0]).unwrap();
            let ku = stiffness(theory, xyz, &material, &section).unwrap() * field(xyz, e, k);
            let scale = f.amax();
            assert!(scale > 0.0);
            assert!(
                (&f - &ku).amax() <= 1e-9 * scale,
                "{theory:?} on {} nodes: {f} against {ku}",
                xyz.len()
            );
            // A rigid rotation about z and a translation do no work.
            let rigid = nalgebra::DVector::from_iterator(
                6 * xyz.len(),
                xyz.iter()
                    .flat_map(|p| [-p[1] + 1.0, p[0], 0.5, 0., 0., 1.0]),
            );
            assert!(f.dot(&rigid).abs() <= 1e-9 * scale);
        }
    }

    #[test]
    fn the_thermal_efforts_integrate_the_profile_through_the_thickness() {
        let material = Elastic::new(2e11, 0.3).unwrap();
        let section = ShellSection::new(0.01);
        let h: f64 = 0.01;
        // A parabola with p₂: N = E/(1−ν)(p₀ h + p₂ h³/12) (Simpson's mean).
        let p = [1e-4, 0.1, 40.0];
        let (n, m) = thermal_efforts(&material, &section, p);
        let c = 2e11 / 0.7;
        let simpson = (p[0] - p[1] * h / 2.
            + p[2] * h * h / 4.
            + 4. * p[0]
            + p[0]
            + p[1] * h / 2.
            + p[2] * h * h / 4.)
            / 6.;
        assert!((n - c * h * simpson).abs() <= 1e-12 * n.abs());
        assert!((m - c * p[1] * h.powi(3) / 12.).abs() <= 1e-12 * m.abs());
        assert!(
            (thermal_stress(&material, p, h / 2.) - c * (p[0] + p[1] * h / 2. + p[2] * h * h / 4.))
                .abs()
                < 1e-3
        );
    }
}
