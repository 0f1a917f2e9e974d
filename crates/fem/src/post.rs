//! Post-processing on a displacement field: stresses at Gauss points
//! (SIEF_ELGA), nodal forces (FORC_NODA, REAC_NODA), extrapolation to nodes
//! (SIGM_ELNO/SIEF_ELNO), nodal averages (SIGM_NOEU) and equivalent stresses
//! (SIEQ).

use crate::element::{element_dofs, model_gauss, shell_stiffness, spring_stiffness};
use crate::error::FemError;
use crate::loads::Loads;
use crate::material::Hypothesis;
use crate::model::{ElementKind, Model};
use crate::shape;
use aster_mesh::{CellId, CellType, NodeId};
use nalgebra::{DMatrix, DVector};

/// Values of one cell at its points (Gauss points for ELGA, the cell's
/// nodes in order for ELNO).
#[derive(Clone, Debug, PartialEq)]
pub struct CellValues {
    pub cell: CellId,
    /// Component names (SIXX SIYY SIZZ SIXY [SIXZ SIYZ]; N VY [VZ] for
    /// springs).
    pub names: Vec<&'static str>,
    /// `points[p][c]`: value of component c at point p.
    pub points: Vec<Vec<f64>>,
}

impl CellValues {
    pub fn get(&self, point: usize, name: &str) -> Option<f64> {
        let c = self.names.iter().position(|&n| n == name)?;
        self.points.get(point)?.get(c).copied()
    }
}

/// A field with values per node (SIGM_NOEU…): `values[node]` is `None` for
/// nodes no cell of the field touches.
#[derive(Clone, Debug, PartialEq)]
pub struct NodalValues {
    pub names: Vec<&'static str>,
    pub values: Vec<Option<Vec<f64>>>,
}

impl NodalValues {
    pub fn get(&self, node: NodeId, name: &str) -> Option<f64> {
        let c = self.names.iter().position(|&n| n == name)?;
        self.values.get(node.0 as usize)?.as_ref()?.get(c).copied()
    }
}

/// An error when the model has stabilised one-point HEXA8 cells
/// (`crate::hexs8`): `what` is computed by code_aster's `te0395`/`te0015`…
/// of `MECA_HEXS8`, not reproduced.
pub fn refuse_stabilised(model: &Model, what: &str) -> Result<(), FemError> {
    match model.elements().iter().find(|e| model.is_stabilised(e.cell)) {
        Some(e) => Err(FemError::Model(format!(
            "{what} on the under-integrated HEXA8 of 3D_SI (cell {}) are not implemented: its forces and stiffness come from its one-point behaviour and 72 hourglass stresses",
            model.cell_name(e.cell)
        ))),
        None => Ok(()),
    }
}

fn cell_error(model: &Model, cell: CellId, m: String) -> FemError {
    FemError::Model(format!("cell {} is {m}", model.cell_name(cell)))
}

/// code_aster's `EFGE` components of the DKT and DKQ plates (`MEDKTR3`,
/// `MEDKQU4`): the membrane forces, moments and transverse shears.
const EFGE_NAMES: [&str; 8] = ["NXX", "NYY", "NXY", "MXX", "MYY", "MXY", "QX", "QY"];

/// The components of the shells' generalised strains (`DEGE_*`).
const DEGE_NAMES: [&str; 8] = ["EXX", "EYY", "EXY", "KXX", "KYY", "KXY", "GAX", "GAY"];

/// `EFGE_ELNO` of the beams (`POU_D_E`, `POU_D_T`): N VY VZ MT MFY MFZ at their two
/// nodes (the bars, `BARRE`: N alone), in each beam's local frame ([`crate::beam::efforts`]).
pub fn beam_efge_elno(model: &Model, u: &[f64]) -> Result<Vec<CellValues>, FemError> {
    let mut out = Vec::new();
    for el in model.elements() {
        let err = |m: String| cell_error(model, el.cell, m);
        let e = match &el.kind {
            ElementKind::Beam { material, section } => {
                let xyz = crate::element::beam_coords(model.mesh(), el.cell).map_err(err)?;
                let ue: Vec<f64> = element_dofs(model, el.cell).iter().map(|&i| u[i]).collect();
                crate::beam::efforts(&xyz, material, section, &ue).map_err(err)?
            }
            ElementKind::Bar { material, area } => {
                let xyz = crate::element::beam_coords(model.mesh(), el.cell).map_err(err)?;
                let ue: Vec<f64> = element_dofs(model, el.cell).iter().map(|&i| u[i]).collect();
                let n = crate::bar::normal_force(&xyz, material, *area, &ue).map_err(err)?;
                out.push(CellValues {
                    cell: el.cell,
                    names: vec!["N"],
                    points: vec![vec![n], vec![n]],
                });
                continue;
            }
            _ => continue,
        };
        out.push(CellValues {
            cell: el.cell,
            names: crate::beam::EFFORT_NAMES.to_vec(),
            points: e.iter().map(|p| p.to_vec()).collect(),
        });
    }
    Ok(out)
}

/// `DEGE_ELNO` of the beams (`POU_D_E`, `POU_D_T`): EPXX GAXY GAXZ GAT KY KZ at their
/// two nodes, in each beam's local frame ([`crate::beam::generalised_strains`]).
pub fn beam_dege_elno(model: &Model, u: &[f64]) -> Result<Vec<CellValues>, FemError> {
    let mut out = Vec::new();
    for el in model.elements() {
        let ElementKind::Beam { material, section } = &el.kind else {
            continue;
        };
        let err = |m: String| cell_error(model, el.cell, m);
        let xyz = crate::element::beam_coords(model.mesh(), el.cell).map_err(err)?;
        let ue: Vec<f64> = element_dofs(model, el.cell).iter().map(|&i| u[i]).collect();
        let e = crate::beam::generalised_strains(&xyz, material, section, &ue).map_err(err)?;
        out.push(CellValues {
            cell: el.cell,
            names: crate::beam::STRAIN_NAMES.to_vec(),
            points: e.iter().map(|p| p.to_vec()).collect(),
        });
    }
    Ok(out)
}

/// Where, and by which of code_aster's paths, the efforts (`EFGE`) of
/// shells are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EffortsAt {
    /// `EFGE_ELGA`, at the Gauss points.
    Gauss,
    /// `EFGE_ELNO` of a non-linear result (`STAT_NON_LINE`, code_aster's
    /// `PNONLIN` = 1): DKT/DKQ `ef0031` (the Gauss points' efforts
    /// extrapolated to the nodes, `ppgan2`), COQUE_3D `ef0415`.
    NodesNonLinear,
    /// `EFGE_ELNO` of a linear result (`MECA_STATIQUE`): DKT/DKQ `ef0033`
    /// (`dxefgv`: the efforts evaluated at the nodes), COQUE_3D `ef0410`.
    NodesLinear,
    /// `EFGE_ELGA` of a linear result: DKT/DKQ `dktedg`/`dkqedg` at the
    /// Gauss points (an offset DKQ's N then reads the bilinear rotations'
    /// curvature, [`crate::dkt::Generalised::EffortsLinear`]); COQUE_3D
    /// as [`EffortsAt::Gauss`].
    GaussLinear,
}

/// Generalised efforts at the Gauss points (`EFGE_ELGA`) of the shell
/// elements, in the user's frame of each facet: its x axis is the
/// projection on the facet of the global direction `direction(cell)`
/// (code_aster's `ANGL_REP`/`VECTEUR`, by default global X; `coqrep`), its
/// z axis the facet's normal. NXX NYY NXY MXX MYY MXY QX QY. A direction
/// normal to a facet is an error naming the cell (code_aster's
/// `PLATE1_40`).
pub fn efge_elga(
    model: &Model,
    u: &[f64],
    direction: &dyn Fn(CellId) -> [f64; 3],
) -> Result<Vec<CellValues>, FemError> {
    shell_efforts(model, u, direction, EffortsAt::Gauss)
}

/// The efforts of the DKT/DKQ shells of `model` as [`efge_elga`], where
/// and as `at` says (`EFGE_ELNO`: at the cells' nodes).
pub fn shell_efforts(
    model: &Model,
    u: &[f64],
    direction: &dyn Fn(CellId) -> [f64; 3],
    at: EffortsAt,
) -> Result<Vec<CellValues>, FemError> {
    let what = if matches!(at, EffortsAt::NodesLinear | EffortsAt::GaussLinear) {
        crate::dkt::Generalised::EffortsLinear
    } else {
        crate::dkt::Generalised::Efforts
    };
    shell_generalised(model, u, direction, at, what)
}

/// The generalised strains EXX EYY EXY KXX KYY KXY GAX GAY of the DKT/DKQ
/// shells of `model` (`te0033`, `DEGE_ELGA` at the Gauss points, or with
/// `at_nodes` `DEGE_ELNO` evaluated at the nodes), in the user's frame of
/// each facet as [`efge_elga`]'s efforts.
pub fn shell_strains(
    model: &Model,
    u: &[f64],
    direction: &dyn Fn(CellId) -> [f64; 3],
    at_nodes: bool,
) -> Result<Vec<CellValues>, FemError> {
    let at = if at_nodes {
        EffortsAt::NodesLinear
    } else {
        EffortsAt::Gauss
    };
    shell_generalised(model, u, direction, at, crate::dkt::Generalised::Strains)
}

fn shell_generalised(
    model: &Model,
    u: &[f64],
    direction: &dyn Fn(CellId) -> [f64; 3],
    at: EffortsAt,
    what: crate::dkt::Generalised,
) -> Result<Vec<CellValues>, FemError> {
    let names: &[&str] = match what {
        crate::dkt::Generalised::Efforts | crate::dkt::Generalised::EffortsLinear => &EFGE_NAMES,
        crate::dkt::Generalised::Strains => &DEGE_NAMES,
    };
    let mut out = Vec::new();
    for el in model.elements() {
        let ElementKind::Shell {
            material,
            section,
            theory,
        } = &el.kind
        else {
            continue;
        };
        let dofs = element_dofs(model, el.cell);
        let c = model.mesh().cell(el.cell);
        if !matches!(c.ty, CellType::TRIA3 | CellType::QUAD4) {
            continue;
        }
        let err = |m: String| cell_error(model, el.cell, m);
        let xyz: Vec<[f64; 3]> = c.nodes.iter().map(|&n| model.mesh().coord(n)).collect();
        let ue: Vec<f64> = dofs.iter().map(|&i| u[i]).collect();
        let points: Vec<[f64; 2]> = match at {
            EffortsAt::NodesLinear => crate::plate::nodes(c.ty),
            _ => crate::plate::rigi_scheme(*theory, c.ty)
                .iter()
                .map(|g| [g.xi[0], g.xi[1]])
                .collect(),
        };
        let (pgl, efforts) =
            crate::plate::generalised_at(*theory, &xyz, material, section, &ue, &points, what)
                .map_err(err)?;
        // Rotation of the in-plane tensors from pgl's (x, y) to the user's
        // axes (`coqrep`): c, s are the cosine and sine of the user's x
        // axis in pgl.
        let d = nalgebra::Vector3::from(direction(el.cell));
        let n = pgl.row(2).transpose();
        let proj = d - n * d.dot(&n);
        let norm = proj.norm();
        if norm <= f64::EPSILON * d.norm().max(1.0) {
            return Err(cell_error(
                model,
                el.cell,
                "a shell whose reference direction (ANGL_REP/VECTEUR) is normal to its plane: the efforts' frame is undefined".into(),
            ));
        }
        let proj = proj / norm;
        let (c0, s0) = (
            pgl.row(0).transpose().dot(&proj),
            pgl.row(1).transpose().dot(&proj),
        );
        let cs = c0 / (c0 * c0 + s0 * s0).sqrt();
        let sn = s0 / (cs * cs + s0 * s0).sqrt();
        let rot = |xx: f64, yy: f64, xy: f64| {
            (
                cs * cs * xx + sn * sn * yy + 2. * cs * sn * xy,
                sn * sn * xx + cs * cs * yy - 2. * cs * sn * xy,
                -cs * sn * xx + cs * sn * yy + (cs * cs - sn * sn) * xy,
            )
        };
        // A non-linear result's DKTG efforts are its SIEF_ELGA, N and M
        // of the generalised behaviour without shear forces (`te0409`
        // leaves Q at zero unless Q4GG; `ef0409`, `te0546` copy them).
        let no_shear = *theory == crate::plate::PlateTheory::Dktg
            && matches!(at, EffortsAt::Gauss | EffortsAt::NodesNonLinear)
            && what != crate::dkt::Generalised::Strains;
        let points = efforts
            .iter()
            .map(|e| {
                let (nxx, nyy, nxy) = rot(e[0], e[1], e[2]);
                let (mxx, myy, mxy) = rot(e[3], e[4], e[5]);
                let (qx, qy) = if no_shear {
                    (0.0, 0.0)
                } else {
                    (cs * e[6] + sn * e[7], -sn * e[6] + cs * e[7])
                };
                vec![nxx, nyy, nxy, mxx, myy, mxy, qx, qy]
            })
            .collect::<Vec<Vec<f64>>>();
        // ef0031: the Gauss points' efforts carried to the nodes by the
        // RIGI family's extrapolation (FPG3, FPG4: `ppgan2`); the frame is
        // the cell's, so turning and extrapolating commute.
        let points = if at == EffortsAt::NodesNonLinear {
            let scheme = crate::plate::rigi_scheme(*theory, c.ty);
            let e = extrapolation(c.ty, &scheme);
            (0..e.nrows())
                .map(|n| {
                    (0..names.len())
                        .map(|k| (0..points.len()).map(|p| e[(n, p)] * points[p][k]).sum())
                        .collect()
                })
                .collect()
        } else {
            points
        };
        out.push(CellValues {
            cell: el.cell,
            names: names.to_vec(),
            points,
        });
    }
    Ok(out)
}

/// A level through the thickness of a shell (code_aster's sub-points of
/// `SIGM_ELNO`/`SIEF_ELGA` on DKT cells, `POST_CHAMP/EXTR_COQUE`): layer
/// `layer` (1-based) of `COQUE_NCOU` equal layers, at its bottom
/// (`NIVE_COUCHE='INF'`, position 0), middle (`MOY`, ½) or top (`SUP`, 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellLevel {
    pub layer: u32,
    pub position: f64,
}

/// The stresses SIXX SIYY SIZZ SIXY of the shells of `model` at one
/// level, extrapolated to the cells' nodes (`SIGM_ELNO` of that sub-point),
/// in the efforts' frame of each cell ([`efge_elga`]'s `direction`).
///
/// A DKT/DKQ facet is a homogeneous elastic plate: code_aster's
/// stress at the height z of a Gauss point is H (ε + z κ), and with
/// N = h H ε and M = h³/12 H κ that is N/h + 12 z M / h³ (SIZZ = 0); z is
/// measured from the mid-surface, −h/2 at the bottom of the first layer.
/// The Gauss values (FPG3, FPG4; FPG1 on Q4G's triangle) are extrapolated
/// to the nodes as code_aster's `te0004` does for each sub-point. `layers`
/// gives a cell's `COQUE_NCOU`. The plates with a transverse shear strain
/// (DST, Q4G) add SIXZ SIYZ, `dstsie`'s parabola through the thickness
/// (`d1i` with z from −h/2 to h/2): 3/(2h)·(1 − 4z²/h²)·(QX, QY); the DKT
/// facets have none here.
pub fn shell_sigm_elno(
    model: &Model,
    u: &[f64],
    direction: &dyn Fn(CellId) -> [f64; 3],
    layers: &dyn Fn(CellId) -> u32,
    level: ShellLevel,
) -> Result<Vec<CellValues>, FemError> {
    let efforts = efge_elga(model, u, direction)?;
    let mut out = Vec::with_capacity(efforts.len());
    for cv in efforts {
        let Some(ElementKind::Shell {
            material,
            section,
            theory,
        }) = model.element_kind(cv.cell)
        else {
            continue;
        };
        if let Some(layered) = &section.layered {
            out.push(layered_sigm_elno(
                model,
                cv.cell,
                u,
                (material, section, *theory),
                layered,
                level,
            )?);
            continue;
        }
        let shear = theory.has_shear_strain();
        let n = layers(cv.cell).max(1);
        if level.layer == 0 || level.layer > n {
            return Err(cell_error(
                model,
                cv.cell,
                format!(
                    "layer {} asked of a shell with {n} layer(s) (COQUE_NCOU)",
                    level.layer
                ),
            ));
        }
        let h = section.thickness;
        let z = -0.5 * h + h * (f64::from(level.layer - 1) + level.position) / f64::from(n);
        let parabola = 1.5 / h * (1.0 - 4.0 * z * z / (h * h));
        // With an offset e the efforts are about the reference surface
        // (M = D κ + e·N): `dktsie`'s H (ε + (z + e) κ) at the height z
        // from the mid-surface is N/h + 12 z (M − e·N)/h³, and its shear
        // parabola (a z² + b z + c between e − h/2 and e + h/2) the same
        // function of z.
        let off = section.offset;
        let gauss: Vec<Vec<f64>> = cv
            .points
            .iter()
            .map(|e| {
                let at = |k: usize| e[k] / h + 12.0 * z * (e[k + 3] - off * e[k]) / (h * h * h);
                let mut s = vec![at(0), at(1), 0.0, at(2)];
                if shear {
                    s.extend([parabola * e[6], parabola * e[7]]);
                }
                s
            })
            .collect();
        let ty = model.mesh().cell(cv.cell).ty;
        let scheme = crate::plate::rigi_scheme(*theory, ty);
        let e = extrapolation(ty, &scheme);
        let ncomp = if shear { 6 } else { 4 };
        let points = (0..ty.node_count())
            .map(|node| {
                (0..ncomp)
                    .map(|c| (0..gauss.len()).map(|p| e[(node, p)] * gauss[p][c]).sum())
                    .collect()
            })
            .collect();
        let names = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
        out.push(CellValues {
            cell: cv.cell,
            names: names[..ncomp].to_vec(),
            points,
        });
    }
    out.extend(coque3d_sigm_elno_at(model, u, direction, level)?);
    Ok(out)
}

/// The stresses SIXX SIYY SIZZ SIXY of a layered facet ([`crate::laminate`])
/// at one level of one of its plies, at its nodes, in its efforts' frame:
/// `dktsie`/`dstsie` with `dxdmul` — the ply's stiffness in the facet's
/// frame times the strain ε + z κ at the level's height z, at the RIGI
/// points, turned to the user's frame and extrapolated to the nodes as the
/// homogeneous plate's. The transverse shears by ply SIXZ SIYZ are
/// `dxdmul`'s d1i·Q + d2i·λ with the moments' derivatives λ
/// ([`crate::dst::moment_derivatives`] on the DST and DSQ facets, `dktlxy`
/// on the DKT triangle, `q4glxy` on the Q4γ quadrangle, none on the T3γ
/// triangle: `t3gsie`'s d1i·Q); the DKQ plies give none here.
fn layered_sigm_elno(
    model: &Model,
    cell: CellId,
    u: &[f64],
    (material, section, theory): (
        &crate::material::Elastic,
        &crate::dkt::ShellSection,
        crate::plate::PlateTheory,
    ),
    layered: &crate::laminate::LayeredSection,
    level: ShellLevel,
) -> Result<CellValues, FemError> {
    let plies = layered.laminate.layers.len();
    let ply = level.layer as usize;
    let at = if level.position <= 0.0 {
        -1
    } else if level.position >= 1.0 {
        1
    } else {
        0
    };
    let data = (ply >= 1)
        .then(|| layered.ply_level(ply - 1, at, section.offset))
        .flatten()
        .ok_or_else(|| {
            cell_error(
                model,
                cell,
                format!("layer {ply} asked of a composite of {plies} layer(s) (DEFI_COMPOSITE)"),
            )
        })?;
    let c = model.mesh().cell(cell);
    let xyz: Vec<[f64; 3]> = c.nodes.iter().map(|&n| model.mesh().coord(n)).collect();
    let dofs = element_dofs(model, cell);
    let ue: Vec<f64> = dofs.iter().map(|&i| u[i]).collect();
    let scheme = crate::plate::rigi_scheme(theory, c.ty);
    let points: Vec<[f64; 2]> = scheme.iter().map(|g| [g.xi[0], g.xi[1]]).collect();
    let (_, strains) = crate::plate::generalised_at(
        theory,
        &xyz,
        material,
        section,
        &ue,
        &points,
        crate::dkt::Generalised::Strains,
    )
    .map_err(|m| cell_error(model, cell, m))?;
    // The transverse shears by ply: d1i·Q + d2i·λ (DST, DSQ, the DKT
    // triangle, the Q4γ quadrangle).
    use crate::plate::PlateTheory;
    let lambda: Option<Vec<[f64; 4]>> = match (theory.base(), xyz.as_slice()) {
        (PlateTheory::Dst, _) => Some(
            crate::dst::moment_derivatives(&xyz, material, section, &ue, &points)
                .map_err(|m| cell_error(model, cell, m))?,
        ),
        (PlateTheory::Dkt, [a, b, c]) => {
            let l = crate::dkt::moment_derivatives(&[*a, *b, *c], material, section, &ue)
                .map_err(|m| cell_error(model, cell, m))?;
            Some(vec![l; points.len()])
        }
        // `t3gsie`: d1i·Q alone.
        (PlateTheory::Q4g, [_, _, _]) => Some(vec![[0.0; 4]; points.len()]),
        (PlateTheory::Q4g, [a, b, c, d]) => Some(
            crate::q4g::moment_derivatives(&[*a, *b, *c, *d], material, section, &ue, &points)
                .map_err(|m| cell_error(model, cell, m))?,
        ),
        _ => None,
    };
    let shear = match lambda {
        Some(lambda) => {
            let (_, efforts) = crate::plate::generalised_at(
                theory,
                &xyz,
                material,
                section,
                &ue,
                &points,
                crate::dkt::Generalised::Efforts,
            )
            .map_err(|m| cell_error(model, cell, m))?;
            Some(
                efforts
                    .iter()
                    .zip(&lambda)
                    .map(|(e, l)| {
                        let v = [e[6], e[7]];
                        let t: [f64; 2] = std::array::from_fn(|i| {
                            (0..2).map(|j| data.d1i[i][j] * v[j]).sum::<f64>()
                                + (0..4).map(|j| data.d2i[i][j] * l[j]).sum::<f64>()
                        });
                        t
                    })
                    .collect::<Vec<_>>(),
            )
        }
        _ => None,
    };
    let (cs, sn) = layered.cos_sin;
    let gauss: Vec<Vec<f64>> = strains
        .iter()
        .enumerate()
        .map(|(p, g)| {
            let eps = [
                g[0] + data.z * g[3],
                g[1] + data.z * g[4],
                2. * (g[2] + data.z * g[5]),
            ];
            let sig: [f64; 3] =
                std::array::from_fn(|i| (0..3).map(|j| data.h[i][j] * eps[j]).sum());
            let (xx, yy, xy) = (sig[0], sig[1], sig[2]);
            let mut v = vec![
                cs * cs * xx + sn * sn * yy + 2. * cs * sn * xy,
                sn * sn * xx + cs * cs * yy - 2. * cs * sn * xy,
                0.0,
                -cs * sn * xx + cs * sn * yy + (cs * cs - sn * sn) * xy,
            ];
            if let Some(t) = &shear {
                let [qx, qy] = t[p];
                v.extend([cs * qx + sn * qy, -sn * qx + cs * qy]);
            }
            v
        })
        .collect();
    let ncomp = if shear.is_some() { 6 } else { 4 };
    let e = extrapolation(c.ty, &scheme);
    let nodes = (0..c.ty.node_count())
        .map(|node| {
            (0..ncomp)
                .map(|k| (0..gauss.len()).map(|p| e[(node, p)] * gauss[p][k]).sum())
                .collect()
        })
        .collect();
    let names = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    Ok(CellValues {
        cell,
        names: names[..ncomp].to_vec(),
        points: nodes,
    })
}

/// `SIGM_ELNO` of the COQUE_3D cells at one sub-point (layer `layer`,
/// level INF/MOY/SUP: sub-point 3·(layer − 1) + level of
/// [`crate::coque3d::sigm_elno`]), SIXX SIYY SIZZ SIXY SIXZ SIYZ at the
/// nodes (nine, seven) in the user's frame (`direction`).
fn coque3d_sigm_elno_at(
    model: &Model,
    u: &[f64],
    direction: &dyn Fn(CellId) -> [f64; 3],
    level: ShellLevel,
) -> Result<Vec<CellValues>, FemError> {
    coque3d_cells(model, u, &|cell, material, section, xyz, ue| {
        if level.layer == 0 || level.layer > section.layers {
            return Err(format!(
                "layer {} asked of a shell with {} layer(s) (COQUE_NCOU)",
                level.layer, section.layers
            ));
        }
        let lvl = (level.position * 2.).round().clamp(0., 2.) as usize;
        let sub = 3 * (level.layer as usize - 1) + lvl;
        let nodes = crate::coque3d::sigm_elno(xyz, material, section, ue, direction(cell))?;
        Ok((
            vec!["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"],
            nodes.iter().map(|n| n[sub].to_vec()).collect(),
        ))
    })
}

/// One [`CellValues`] per COQUE_3D cell of `model`: `f` of the cell, its
/// material, section, coordinates and displacements (from `u`) gives the
/// component names and the values; its error is located at the cell.
#[allow(clippy::type_complexity)]
fn coque3d_cells(
    model: &Model,
    u: &[f64],
    f: &dyn Fn(
        CellId,
        &crate::Elastic,
        &crate::coque3d::Coque3dSection,
        &[[f64; 3]],
        &[f64],
    ) -> Result<(Vec<&'static str>, Vec<Vec<f64>>), String>,
) -> Result<Vec<CellValues>, FemError> {
    let mut out = Vec::new();
    for el in model.elements() {
        let ElementKind::Coque3d { material, section } = &el.kind else {
            continue;
        };
        let err = |m: String| cell_error(model, el.cell, m);
        let xyz = crate::element::coque3d_coords(model.mesh(), el.cell).map_err(err)?;
        let ue: Vec<f64> = element_dofs(model, el.cell).iter().map(|&i| u[i]).collect();
        let (names, points) = f(el.cell, material, section, &xyz, &ue).map_err(err)?;
        out.push(CellValues {
            cell: el.cell,
            names,
            points,
        });
    }
    Ok(out)
}

/// The efforts NXX NYY NXY MXX MYY MXY QX QY of the COQUE_3D cells of
/// `model` in the user's frame (`direction`), where and as `at` says
/// (`EFGE_ELGA` at the normal Gauss points, `EFGE_ELNO` of a non-linear or
/// a linear result: [`EffortsAt`]).
pub fn coque3d_efge(
    model: &Model,
    u: &[f64],
    direction: &dyn Fn(CellId) -> [f64; 3],
    at: EffortsAt,
) -> Result<Vec<CellValues>, FemError> {
    use crate::coque3d as c3;
    coque3d_cells(model, u, &|cell, material, section, xyz, ue| {
        let d = direction(cell);
        let efforts = match at {
            EffortsAt::Gauss | EffortsAt::GaussLinear => {
                c3::efge_elga(xyz, material, section, ue, d)
            }
            EffortsAt::NodesNonLinear => c3::efge_elno(xyz, material, section, ue, d),
            EffortsAt::NodesLinear => c3::efge_elno_linear(xyz, material, section, ue, d),
        }?;
        Ok((
            EFGE_NAMES.to_vec(),
            efforts.iter().map(|e| e.to_vec()).collect(),
        ))
    })
}

/// Stresses at Gauss points (SIEF_ELGA) for continuum elements, and the
/// local forces N, VY(, VZ) of springs, for a total displacement `u`.
pub fn sief_elga(model: &Model, u: &[f64]) -> Result<Vec<CellValues>, FemError> {
    let mut out = Vec::with_capacity(model.elements().len());
    for el in model.elements() {
        let dofs = element_dofs(model, el.cell);
        let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
        match &el.kind {
            ElementKind::Continuum {
                hypothesis,
                material,
            } => {
                if model.is_mixed(el.cell) {
                    let m = crate::mixed_upg::MixedCell::new(model, el.cell, *hypothesis)
                        .map_err(|m| cell_error(model, el.cell, m))?;
                    let ue: Vec<f64> = m.dofs.iter().map(|&i| u[i]).collect();
                    out.push(CellValues {
                        cell: el.cell,
                        names: crate::mixed_upg::stress_names(*hypothesis),
                        points: m.elastic_stress(material, &ue),
                    });
                    continue;
                }
                let g = model_gauss(model, el.cell, *hypothesis)
                    .map_err(|m| cell_error(model, el.cell, m))?;
                let d = material.hooke(*hypothesis);
                let points = g
                    .iter()
                    .map(|gp| {
                        let s = &d * (&gp.b * &ue);
                        s.iter().copied().collect()
                    })
                    .collect();
                out.push(CellValues {
                    cell: el.cell,
                    names: hypothesis.stress_names().to_vec(),
                    points,
                });
            }
            ElementKind::Spring { stiffness, frame } => {
                let dim = stiffness.len();
                let (_, r) = spring_stiffness(model.mesh(), el.cell, stiffness, *frame);
                let du: DVector<f64> = if ue.len() == 2 * dim {
                    DVector::from_iterator(dim, (0..dim).map(|k| ue[dim + k] - ue[k]))
                } else {
                    ue.clone()
                };
                let local = &r * du;
                let f: Vec<f64> = (0..dim).map(|k| stiffness[k] * local[k]).collect();
                out.push(CellValues {
                    cell: el.cell,
                    names: ["N", "VY", "VZ", "MT", "MFY", "MFZ"][..dim].to_vec(),
                    points: vec![f],
                });
            }
            // Grids: SIXX = E ε at each point (te0433).
            ElementKind::Grid { material, section } => {
                let mesh = model.mesh();
                let eps = crate::grid::strains(
                    mesh.cell(el.cell).ty,
                    &crate::element::cell_coords(mesh, el.cell),
                    section,
                    ue.as_slice(),
                )
                .map_err(|m| cell_error(model, el.cell, m))?;
                out.push(CellValues {
                    cell: el.cell,
                    names: vec!["SIXX"],
                    points: eps.iter().map(|e| vec![material.e * e]).collect(),
                });
            }
            // Shells' stresses are by layer (code_aster's sub-points), not
            // computed: their efforts are [`efge_elga`]'s.
            ElementKind::Boundary
            | ElementKind::Shell { .. }
            | ElementKind::Beam { .. }
            | ElementKind::Bar { .. }
            | ElementKind::Coque3d { .. } => {}
        }
    }
    Ok(out)
}

/// Small total strains at Gauss points (EPSI_ELGA) of the continuum
/// elements for a total displacement `u`: ε(u) = B u, with code_aster's
/// tensor shear components (EPXY = γxy/2). The strain of the displacement
/// alone (thermal strains included, as code_aster's EPSI_ELGA). Plane
/// stress (C_PLAN): εzz from σzz = 0 with the elastic matrix, as
/// code_aster's `epsvmc`, without thermal strain.
pub fn epsi_elga(model: &Model, u: &[f64]) -> Result<Vec<CellValues>, FemError> {
    epsi_elga_on(model, u, |_| true)
}

/// [`epsi_elga`] on the cells `keep` accepts only.
pub fn epsi_elga_on(
    model: &Model,
    u: &[f64],
    keep: impl Fn(CellId) -> bool,
) -> Result<Vec<CellValues>, FemError> {
    // Mixed cells (`*_INCO_UPG`): ε(u) of the displacement alone at the
    // element's points (code_aster's te0453 in 3D, te0447 in 2D), what
    // B u on their displacement unknowns gives.
    let mut out = Vec::with_capacity(model.elements().len());
    for el in model.elements() {
        if let ElementKind::Grid { section, .. } = &el.kind {
            // Grids: the strain along the bars, EXX (te0433).
            if !keep(el.cell) {
                continue;
            }
            let mesh = model.mesh();
            let ue: Vec<f64> = element_dofs(model, el.cell).iter().map(|&i| u[i]).collect();
            let eps = crate::grid::strains(
                mesh.cell(el.cell).ty,
                &crate::element::cell_coords(mesh, el.cell),
                section,
                &ue,
            )
            .map_err(|m| cell_error(model, el.cell, m))?;
            out.push(CellValues {
                cell: el.cell,
                names: vec!["EXX"],
                points: eps.iter().map(|e| vec![*e]).collect(),
            });
            continue;
        }
        let ElementKind::Continuum {
            hypothesis,
            material,
        } = &el.kind
        else {
            continue;
        };
        if !keep(el.cell) {
            continue;
        }
        // Plane stress: code_aster's `epsvmc` completes εzz from σzz = 0
        // with the *elastic* matrix whatever the behaviour,
        // εzz = −(D₃₁εxx + D₃₂εyy + 2D₃₄εxy)/D₃₃ = −ν/(1−ν)(εxx + εyy)
        // for an isotropic material (the thermal strain is the caller's
        // to refuse).
        let plane_stress_nu = match (hypothesis, material) {
            (Hypothesis::PlaneStress, m) if !m.is_isotropic() => {
                return Err(cell_error(
                    model,
                    el.cell,
                    "EPSI_ELGA of plane stress (C_PLAN) cells of an orthotropic material is not computed".into(),
                ));
            }
            (Hypothesis::PlaneStress, m) => Some(m.nu),
            _ => None,
        };
        let dofs = element_dofs(model, el.cell);
        let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
        let g =
            model_gauss(model, el.cell, *hypothesis).map_err(|m| cell_error(model, el.cell, m))?;
        let points = g
            .iter()
            .map(|gp| {
                let e = &gp.b * &ue;
                // Engineering shears (after the three normal strains) halved.
                let mut v: Vec<f64> = e
                    .iter()
                    .enumerate()
                    .map(|(k, v)| if k >= 3 { 0.5 * v } else { *v })
                    .collect();
                if let Some(nu) = plane_stress_nu {
                    v[2] = -nu / (1.0 - nu) * (v[0] + v[1]);
                }
                v
            })
            .collect();
        let names: &[&'static str] = match hypothesis {
            Hypothesis::Solid3D => &["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ"],
            _ => &["EPXX", "EPYY", "EPZZ", "EPXY"],
        };
        out.push(CellValues {
            cell: el.cell,
            names: names.to_vec(),
            points,
        });
    }
    Ok(out)
}

/// code_aster's `EPSP_ELGA` in small strains: the inelastic strain
/// ε − D⁻¹σ at each point (tensor shears, EPXY = γxy/2), from the total
/// strains `eps` ([`epsi_elga`]) and the stresses at the same points, with
/// the isotropic compliance of the cell's material. It holds the thermal
/// strain too: the caller subtracts it or refuses a result that has one.
pub fn inelastic_strain_elga(
    model: &Model,
    eps: &[CellValues],
    stress: &[CellValues],
) -> Result<Vec<CellValues>, FemError> {
    let mut out = Vec::with_capacity(eps.len());
    for ev in eps {
        let Some(ElementKind::Continuum { material, .. }) = model.element_kind(ev.cell) else {
            continue;
        };
        if !material.is_isotropic() {
            return Err(FemError::Model(format!(
                "cell {}: EPSP of an orthotropic material (ELAS_ORTH) is not computed",
                model.cell_name(ev.cell)
            )));
        }
        let Some(sv) = stress.iter().find(|s| s.cell == ev.cell) else {
            return Err(cell_error(
                model,
                ev.cell,
                "no stress to compute EPSP from".into(),
            ));
        };
        if sv.points.len() != ev.points.len() {
            return Err(cell_error(
                model,
                ev.cell,
                format!(
                    "{} strain points for {} stress points",
                    ev.points.len(),
                    sv.points.len()
                ),
            ));
        }
        let (e, nu) = (material.e, material.nu);
        let points = (0..ev.points.len())
            .map(|p| {
                let s = |n: &str| sv.get(p, n).unwrap_or(0.0);
                let tr = s("SIXX") + s("SIYY") + s("SIZZ");
                ev.names
                    .iter()
                    .zip(&ev.points[p])
                    .map(|(name, total)| {
                        let sig = format!("SI{}", &name[2..]);
                        let elastic = if name[2..3] == name[3..4] {
                            ((1.0 + nu) * s(&sig) - nu * tr) / e
                        } else {
                            (1.0 + nu) * s(&sig) / e
                        };
                        total - elastic
                    })
                    .collect()
            })
            .collect();
        out.push(CellValues {
            cell: ev.cell,
            names: ev.names.clone(),
            points,
        });
    }
    Ok(out)
}

/// Nodal internal forces (FORC_NODA): Σ ∫ Bᵀσ over continuum elements plus
/// spring forces, per DOF index of the model. In AXIS they are per radian.
pub fn forc_noda(model: &Model, u: &[f64]) -> Result<Vec<f64>, FemError> {
    refuse_stabilised(model, "nodal forces (FORC_NODA, REAC_NODA)")?;
    crate::mixed_upg::refuse_mixed(model, "FORC_NODA/REAC_NODA")?;
    let mut f = vec![0.0; model.dofs().len()];
    for el in model.elements() {
        let dofs = element_dofs(model, el.cell);
        let ue = DVector::from_iterator(dofs.len(), dofs.iter().map(|&i| u[i]));
        let fe: DVector<f64> = match &el.kind {
            ElementKind::Continuum {
                hypothesis,
                material,
            } => {
                let g = model_gauss(model, el.cell, *hypothesis)
                    .map_err(|m| cell_error(model, el.cell, m))?;
                let d = material.hooke(*hypothesis);
                let mut fe = DVector::zeros(dofs.len());
                for gp in &g {
                    let s = &d * (&gp.b * &ue);
                    fe += gp.b.transpose() * s * gp.w;
                }
                fe
            }
            ElementKind::Spring { stiffness, frame } => {
                let (k, _) = spring_stiffness(model.mesh(), el.cell, stiffness, *frame);
                k * ue
            }
            ElementKind::Shell {
                material,
                section,
                theory,
            } => {
                shell_stiffness(model.mesh(), el.cell, material, section, *theory)
                    .map_err(|m| cell_error(model, el.cell, m))?
                    * ue
            }
            ElementKind::Beam { material, section } => {
                crate::element::beam_stiffness(model.mesh(), el.cell, material, section)
                    .map_err(|m| cell_error(model, el.cell, m))?
                    * ue
            }
            ElementKind::Bar { material, area } => {
                crate::element::bar_stiffness(model.mesh(), el.cell, material, *area)
                    .map_err(|m| cell_error(model, el.cell, m))?
                    * ue
            }
            ElementKind::Coque3d { material, section } => {
                crate::element::coque3d_stiffness(model.mesh(), el.cell, material, section)
                    .map_err(|m| cell_error(model, el.cell, m))?
                    * ue
            }
            ElementKind::Grid { material, section } => {
                crate::element::grid_stiffness(model.mesh(), el.cell, material, section)
                    .map_err(|m| cell_error(model, el.cell, m))?
                    * ue
            }
            ElementKind::Boundary => continue,
        };
        for (a, &i) in dofs.iter().enumerate() {
            f[i] += fe[a];
        }
    }
    Ok(f)
}

/// Reactions (REAC_NODA), code_aster's definition: FORC_NODA minus the
/// applied external loads at time t. Non-zero only where supports act.
pub fn reac_noda(model: &Model, loads: &Loads, t: f64, u: &[f64]) -> Result<Vec<f64>, FemError> {
    let mut f = forc_noda(model, u)?;
    let fext = loads.external_forces(model, t)?;
    for (a, b) in f.iter_mut().zip(fext) {
        *a -= b;
    }
    Ok(f)
}

/// The linear cell with the corners of `ty` (the corners of code_aster's
/// quadratic reference cells are those of the linear ones).
fn linear_type(ty: CellType) -> CellType {
    match ty {
        CellType::SEG3 | CellType::SEG4 => CellType::SEG2,
        CellType::TRIA6 | CellType::TRIA7 => CellType::TRIA3,
        CellType::QUAD8 | CellType::QUAD9 => CellType::QUAD4,
        CellType::TETRA10 => CellType::TETRA4,
        CellType::PENTA15 | CellType::PENTA18 => CellType::PENTA6,
        CellType::HEXA20 | CellType::HEXA27 => CellType::HEXA8,
        CellType::PYRAM13 => CellType::PYRAM5,
        other => other,
    }
}

/// Extrapolation matrix from Gauss points to the nodes of a cell type
/// (nodes × points). TRIA3/TETRA4 (one point): constant. QUAD4, HEXA8,
/// TRIA6: the field interpolated through the Gauss points with the linear
/// (corner) shape functions of the cell, evaluated at every node (mid-side
/// nodes get the mean of their corners). More points than corners (QUAD8/9,
/// TETRA10, HEXA20/27, PENTA15/18, PYRAM13): least-squares fit with the
/// linear cell's functions, evaluated at the corners, mid-nodes as means.
pub fn extrapolation(ty: CellType, scheme: &[shape::GaussPoint]) -> DMatrix<f64> {
    let np = scheme.len();
    let nodes = shape::reference_nodes(ty);
    let nn = nodes.len();
    if np == 1 {
        return DMatrix::from_element(nn, 1, 1.0);
    }
    let lin = linear_type(ty);
    let ncorner = lin.node_count();
    // A: points × corner functions; fit coefficients c = (AᵀA)⁻¹Aᵀ v.
    let mut a = DMatrix::zeros(np, ncorner);
    for (p, gp) in scheme.iter().enumerate() {
        let s = shape::shape(lin, gp.xi);
        for c in 0..ncorner {
            a[(p, c)] = s.n[c];
        }
    }
    let ata = a.transpose() * &a;
    let fit = match ata.try_inverse() {
        Some(inv) => inv * a.transpose(),
        None => DMatrix::from_element(ncorner, np, 1. / np as f64),
    };
    let mut e = DMatrix::zeros(nn, np);
    for n in 0..nn {
        let s = shape::shape(lin, nodes[n]);
        for c in 0..ncorner {
            for p in 0..np {
                e[(n, p)] += s.n[c] * fit[(c, p)];
            }
        }
    }
    e
}

/// Gauss-point values extrapolated to the nodes of each cell (ELNO).
pub fn elno(model: &Model, elga: &[CellValues]) -> Vec<CellValues> {
    let mesh = model.mesh();
    elga.iter()
        .map(|cv| {
            let ty = mesh.cell(cv.cell).ty;
            let nn = ty.node_count();
            let e = if cv.points.len() == 1 {
                DMatrix::from_element(nn, 1, 1.0)
            } else {
                extrapolation(ty, &model.stiffness_scheme(cv.cell))
            };
            let points = (0..nn)
                .map(|n| {
                    (0..cv.names.len())
                        .map(|c| {
                            (0..cv.points.len())
                                .map(|p| e[(n, p)] * cv.points[p][c])
                                .sum()
                        })
                        .collect()
                })
                .collect();
            CellValues {
                cell: cv.cell,
                names: cv.names.clone(),
                points,
            }
        })
        .collect()
}

/// Nodal average of ELNO values over the cells sharing each node (NOEU).
/// Cells whose components differ from the first cell's (springs) are skipped.
pub fn noeu(model: &Model, elno: &[CellValues]) -> NodalValues {
    let mesh = model.mesh();
    let names = elno
        .iter()
        .find(|c| c.names.first() == Some(&"SIXX"))
        .or(elno.first())
        .map(|c| c.names.clone())
        .unwrap_or_default();
    let mut sum: Vec<Option<(Vec<f64>, usize)>> = vec![None; mesh.node_count()];
    for cv in elno {
        if cv.names != names {
            continue;
        }
        for (k, &n) in mesh.cell(cv.cell).nodes.iter().enumerate() {
            let slot = sum[n.0 as usize].get_or_insert_with(|| (vec![0.0; names.len()], 0));
            for (c, v) in cv.points[k].iter().enumerate() {
                slot.0[c] += v;
            }
            slot.1 += 1;
        }
    }
    NodalValues {
        names,
        values: sum
            .into_iter()
            .map(|s| s.map(|(v, n)| v.into_iter().map(|x| x / n as f64).collect()))
            .collect(),
    }
}

/// Names of the equivalent-stress components (SIEQ_*), code_aster's first ones.
pub const SIEQ_NAMES: [&str; 7] = [
    "VMIS", "TRESCA", "PRIN_1", "PRIN_2", "PRIN_3", "VMIS_SG", "TRSIG",
];

/// Equivalent stresses of one stress tensor given as SIXX SIYY SIZZ SIXY
/// [SIXZ SIYZ]: von Mises, Tresca, principal stresses (ascending), signed
/// von Mises (sign of the trace) and the trace.
pub fn sieq(s: &[f64]) -> [f64; 7] {
    let (xx, yy, zz, xy) = (s[0], s[1], s[2], s[3]);
    let (xz, yz) = if s.len() >= 6 { (s[4], s[5]) } else { (0., 0.) };
    let m = nalgebra::Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
    let mut ev: Vec<f64> = m.symmetric_eigenvalues().iter().copied().collect();
    ev.sort_by(f64::total_cmp);
    let tr = xx + yy + zz;
    let p = tr / 3.;
    let dev2 =
        (xx - p).powi(2) + (yy - p).powi(2) + (zz - p).powi(2) + 2. * (xy * xy + xz * xz + yz * yz);
    let vmis = (1.5 * dev2).sqrt();
    let tresca = ev[2] - ev[0];
    let sg = if tr < 0. { -vmis } else { vmis };
    [vmis, tresca, ev[0], ev[1], ev[2], sg, tr]
}

/// SIEQ at every point of a stress field (ELGA, ELNO); springs are skipped.
pub fn sieq_field(field: &[CellValues]) -> Vec<CellValues> {
    field
        .iter()
        .filter(|cv| cv.names.first() == Some(&"SIXX"))
        .map(|cv| CellValues {
            cell: cv.cell,
            names: SIEQ_NAMES.to_vec(),
            points: cv.points.iter().map(|p| sieq(p).to_vec()).collect(),
        })
        .collect()
}

/// SIEQ of a nodal field.
pub fn sieq_nodal(field: &NodalValues) -> NodalValues {
    NodalValues {
        names: SIEQ_NAMES.to_vec(),
        values: field
            .values
            .iter()
            .map(|v| v.as_ref().map(|s| sieq(s).to_vec()))
            .collect(),
    }
}
