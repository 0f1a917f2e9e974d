//! The finite-element model: which cells carry which element, and the DOF
//! numbering that follows from it.

use crate::dof::{Comp, DofNumbering};
use crate::error::FemError;
use crate::material::{Elastic, Hypothesis};
use crate::shape;
use aster_mesh::{CellId, CellType, Mesh};
use std::sync::Arc;

/// Frame in which spring stiffnesses are given (`REPERE`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Frame {
    /// Global axes.
    Global,
    /// Element axes: x along the segment (node 1 → node 2), y its normal
    /// (2D), or code_aster's default nautical angles with γ = 0 (3D).
    Local,
}

/// What a cell carries.
#[derive(Clone, Debug, PartialEq)]
pub enum ElementKind {
    /// Continuum element (`shape::PLANE_CELLS` in 2D, `shape::SOLID_CELLS` in 3D).
    Continuum {
        hypothesis: Hypothesis,
        material: Elastic,
    },
    /// Discrete spring: on SEG2 between its nodes (`K_T_D_L`, `K_TR_D_L`),
    /// on POI1 between the node and the ground (`K_T_D_N`, `K_TR_D_N`).
    /// `stiffness` has 2 values (`2D_DIS_T`: kx, ky), 3 (`DIS_T`: kx, ky,
    /// kz) or 6 (`DIS_TR`: kx, ky, kz, krx, kry, krz — the cell's nodes
    /// then carry the rotations DRX DRY DRZ).
    Spring { stiffness: Vec<f64>, frame: Frame },
    /// A cell of the model that carries no stiffness (e.g. a boundary SEG2
    /// of a D_PLAN model, used by edge loads); its nodes get DOFs.
    Boundary,
    /// A plate facet on TRIA3 or QUAD4, linear elastic, of the family
    /// `theory` ([`crate::plate`]: `DKT` — [`crate::dkt`], [`crate::dkq`]
    /// —, `DST` — [`crate::dst`] — or `Q4G` — [`crate::q4g`]); its nodes
    /// get the rotations DRX DRY DRZ beside the translations. 3D models
    /// only.
    Shell {
        material: Elastic,
        section: crate::dkt::ShellSection,
        theory: crate::plate::PlateTheory,
    },
    /// A straight beam on SEG2 ([`crate::beam`]): Euler–Bernoulli
    /// (`POU_D_E`, `section.shear` None) or Timoshenko (`POU_D_T`), linear
    /// elastic; its nodes get the rotations DRX DRY DRZ. 3D models only.
    Beam {
        material: Elastic,
        section: crate::beam::BeamSection,
    },
    /// A truss on SEG2 (`BARRE`: [`crate::bar`]), linear elastic, of
    /// cross-section `area`; its nodes carry DX DY DZ. 3D models only.
    Bar { material: Elastic, area: f64 },
    /// code_aster's `COQUE_3D` on QUAD9 or TRIA7 ([`crate::coque3d`]),
    /// linear elastic: its edge nodes (eight, six) carry DX DY DZ DRX DRY
    /// DRZ, its centre node DRX DRY DRZ only. 3D models only.
    Coque3d {
        material: Elastic,
        section: crate::coque3d::Coque3dSection,
    },
    /// A reinforcement grid on a surface cell ([`crate::grid`]):
    /// `GRILLE_MEMBRANE` (DX DY DZ) or, with an offset, `GRILLE_EXCENTRE`
    /// (its nodes carry DRX DRY DRZ too), linear elastic (E only). 3D
    /// models only.
    Grid {
        material: Elastic,
        section: crate::grid::GridSection,
    },
}

impl ElementKind {
    /// Whether the element's nodes carry the rotations DRX DRY DRZ.
    pub fn has_rotations(&self) -> bool {
        match self {
            ElementKind::Shell { .. } | ElementKind::Beam { .. } | ElementKind::Coque3d { .. } => {
                true
            }
            ElementKind::Spring { stiffness, .. } => stiffness.len() == 6,
            ElementKind::Grid { section, .. } => section.offset.is_some(),
            _ => false,
        }
    }
}

/// One element: a mesh cell and what it carries.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    pub cell: CellId,
    pub kind: ElementKind,
}

/// The model: mesh, elements and DOF numbering.
#[derive(Clone, Debug)]
pub struct Model {
    mesh: Arc<Mesh>,
    elements: Vec<Element>,
    dofs: DofNumbering,
    dim: usize,
    hypothesis: Option<Hypothesis>,
    /// Cells integrated with code_aster's under-integrated (`_SI`)
    /// stiffness family ([`shape::reduced_scheme`]).
    reduced: std::collections::BTreeSet<CellId>,
    /// `_SI` HEXA8 cells: code_aster's one-point element with hourglass
    /// stabilisation (`MECA_HEXS8`, [`crate::hexs8`]), computed by the
    /// behaviour cells of the non-linear operators only.
    stabilised: std::collections::BTreeSet<CellId>,
    /// Cells carrying an element with rotations (shell, beam, `DIS_TR`):
    /// they use six components per node.
    shells: std::collections::BTreeSet<CellId>,
    /// Cells of code_aster's mixed incompressible elements (`*_INCO_UPG`,
    /// [`crate::mixed_upg`]): displacement, pressure and swelling.
    mixed: std::collections::BTreeSet<CellId>,
    /// The mixed cells' linear matrix is code_aster's `RIGI_MECA`
    /// (`te0592` → `nirmtd`, MECA_STATIQUE) rather than the tangent of
    /// `nifipd` ([`crate::mixed_upg`]: their shear terms differ).
    mixed_rigi_meca: bool,
    /// Segments of a 3D model given a continuum modelisation: code_aster's
    /// edge elements (`MECA_ARETE2`/`3`), which carry no stiffness here but
    /// belong to the model for post-processing over cells (`POST_ELEM`).
    edges: std::collections::BTreeSet<CellId>,
    /// Cells carrying a reinforcement grid ([`crate::grid`]): their
    /// Gauss family is the grid's ([`crate::grid::scheme`]).
    grids: std::collections::BTreeSet<CellId>,
}

impl Model {
    /// Sets the rule through the thickness of every COQUE_3D cell's
    /// stiffness: `MECA_STATIQUE` takes code_aster's `RIGI_MECA`
    /// (`vdxrig`, [`crate::coque3d::ThicknessRule::Gauss2`]), the
    /// non-linear commands its tangent matrix (`vdxnlr`, `Simpson`, the
    /// default).
    pub fn set_coque3d_rule(&mut self, rule: crate::coque3d::ThicknessRule) {
        for el in &mut self.elements {
            if let ElementKind::Coque3d { section, .. } = &mut el.kind {
                section.rule = rule;
            }
        }
    }

    /// Builds a model and numbers its DOFs. Errors name the offending cell.
    ///
    /// As code_aster's AFFE_MODELE: a later element on the same cell
    /// replaces an earlier one; a continuum modelisation on a boundary cell
    /// (SEG2/SEG3 in 2D, TRIA3/TRIA6/TRIA7/QUAD4/QUAD8/QUAD9 in 3D) gives a boundary
    /// element (for edge and face loads); on a cell of lower dimension
    /// still (POI1, SEG2 in 3D) it gives no element.
    pub fn new(mesh: impl Into<Arc<Mesh>>, elements: Vec<Element>) -> Result<Model, FemError> {
        let mesh: Arc<Mesh> = mesh.into();
        let elements = normalise(&mesh, elements);
        let mut hypothesis: Option<Hypothesis> = None;
        let mut spring_dim: Option<usize> = None;
        let mut shell = false;
        let mut truss = false;
        let cell_name = |id: CellId| {
            mesh.cell_names
                .get(id.0 as usize)
                .cloned()
                .unwrap_or_else(|| format!("#{}", id.0 + 1))
        };
        for el in &elements {
            let Some(cell) = mesh.cells.get(el.cell.0 as usize) else {
                return Err(FemError::Model(format!(
                    "element on cell #{} which the mesh does not have ({} cells)",
                    el.cell.0 + 1,
                    mesh.cells.len()
                )));
            };
            if cell.nodes.len() != cell.ty.node_count() {
                return Err(FemError::Model(format!(
                    "cell {} is a {} with {} nodes; a {} has {}",
                    cell_name(el.cell),
                    cell.ty.name(),
                    cell.nodes.len(),
                    cell.ty.name(),
                    cell.ty.node_count()
                )));
            }
            if let Some(&n) = cell
                .nodes
                .iter()
                .find(|n| n.0 as usize >= mesh.coords.len())
            {
                return Err(FemError::Model(format!(
                    "cell {} refers to node #{} which the mesh does not have",
                    cell_name(el.cell),
                    n.0 + 1
                )));
            }
            match &el.kind {
                ElementKind::Continuum {
                    hypothesis: h,
                    material: _,
                } => {
                    let allowed: &[CellType] = if *h == Hypothesis::Solid3D {
                        &shape::SOLID_CELLS
                    } else {
                        &shape::PLANE_CELLS
                    };
                    if !allowed.contains(&cell.ty) {
                        let names: Vec<&str> = allowed.iter().map(|t| t.name()).collect();
                        return Err(FemError::Model(format!(
                            "cell {} is a {}: modelisation {} has no element for it (supported: {})",
                            cell_name(el.cell),
                            cell.ty.name(),
                            h.aster_name(),
                            names.join(", ")
                        )));
                    }
                    match hypothesis {
                        Some(prev) if prev != *h => {
                            return Err(FemError::Model(format!(
                            "cell {} is {} but the model is already {}: one hypothesis per model",
                            cell_name(el.cell),
                            h.aster_name(),
                            prev.aster_name()
                        )))
                        }
                        _ => hypothesis = Some(*h),
                    }
                }
                ElementKind::Spring { stiffness, .. } => {
                    if !matches!(cell.ty, CellType::SEG2 | CellType::POI1) {
                        return Err(FemError::Model(format!(
                            "cell {} is a {}: discrete springs need SEG2 (K_T_D_L) or POI1 (K_T_D_N)",
                            cell_name(el.cell),
                            cell.ty.name()
                        )));
                    }
                    if !matches!(stiffness.len(), 2 | 3 | 6) {
                        return Err(FemError::Model(format!(
                            "spring on cell {} has {} stiffness values; expected 2 (2D_DIS_T), 3 (DIS_T) or 6 (DIS_TR)",
                            cell_name(el.cell),
                            stiffness.len()
                        )));
                    }
                    if let Some(k) = stiffness.iter().find(|k| !k.is_finite()) {
                        return Err(FemError::Model(format!(
                            "spring on cell {} has a non-finite stiffness {k}",
                            cell_name(el.cell)
                        )));
                    }
                    let sdim = stiffness.len().min(3);
                    if stiffness.len() == 6 {
                        shell = true;
                    }
                    match spring_dim {
                        Some(d) if d != sdim => {
                            return Err(FemError::Model(format!(
                                "spring on cell {} has {} translation components, others have {d}",
                                cell_name(el.cell),
                                sdim
                            )))
                        }
                        _ => spring_dim = Some(sdim),
                    }
                    if cell.ty == CellType::SEG2 {
                        let (a, b) = (mesh.coord(cell.nodes[0]), mesh.coord(cell.nodes[1]));
                        let len =
                            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2))
                                .sqrt();
                        if len == 0. && stiffness.iter().any(|&k| k != 0.) {
                            if let ElementKind::Spring {
                                frame: Frame::Local,
                                ..
                            } = el.kind
                            {
                                return Err(FemError::Model(format!(
                                    "spring on cell {} has zero length: its local frame (REPERE='LOCAL') is undefined",
                                    cell_name(el.cell)
                                )));
                            }
                        }
                    }
                }
                ElementKind::Boundary => {}
                ElementKind::Shell { material, .. }
                | ElementKind::Beam { material, .. }
                | ElementKind::Bar { material, .. }
                | ElementKind::Coque3d { material, .. }
                | ElementKind::Grid { material, .. }
                    if !material.is_isotropic() =>
                {
                    return Err(FemError::Model(format!(
                        "cell {} is a shell or beam element with an orthotropic material (ELAS_ORTH): their sections are the isotropic law's",
                        cell_name(el.cell)
                    )));
                }
                ElementKind::Shell {
                    section, theory, ..
                } => {
                    if !matches!(cell.ty, CellType::TRIA3 | CellType::QUAD4) {
                        return Err(FemError::Model(format!(
                            "cell {} is a {}: the {} shell element exists on TRIA3 and QUAD4 cells only",
                            cell_name(el.cell),
                            cell.ty.name(),
                            theory.name()
                        )));
                    }
                    if !(section.thickness > 0. && section.thickness.is_finite()) {
                        return Err(FemError::Model(format!(
                            "shell on cell {} has thickness {}: it must be positive",
                            cell_name(el.cell),
                            section.thickness
                        )));
                    }
                    if !(section.drilling > 0. && section.drilling.is_finite()) {
                        return Err(FemError::Model(format!(
                            "shell on cell {} has drilling coefficient (COEF_RIGI_DRZ) {}: only code_aster's positive drilling spring is implemented",
                            cell_name(el.cell),
                            section.drilling
                        )));
                    }
                    shell = true;
                }
                ElementKind::Coque3d { section, .. } => {
                    if !matches!(cell.ty, CellType::QUAD9 | CellType::TRIA7) {
                        return Err(FemError::Model(format!(
                            "cell {} is a {}: the COQUE_3D element exists on QUAD9 and TRIA7 cells only",
                            cell_name(el.cell),
                            cell.ty.name()
                        )));
                    }
                    let s = section;
                    let positive = |v: f64| v > 0. && v.is_finite();
                    let valid = positive(s.thickness)
                        && positive(s.drilling)
                        && positive(s.shear_factor)
                        && s.layers > 0;
                    if !valid {
                        return Err(FemError::Model(format!(
                            "COQUE_3D on cell {}: thickness {}, COEF_RIGI_DRZ {}, A_CIS {} and {} layer(s): each must be positive",
                            cell_name(el.cell),
                            s.thickness,
                            s.drilling,
                            s.shear_factor,
                            s.layers
                        )));
                    }
                    shell = true;
                }
                ElementKind::Beam { section, .. } => {
                    if cell.ty != CellType::SEG2 {
                        return Err(FemError::Model(format!(
                            "cell {} is a {}: the POU_D_E beam element exists on SEG2 cells only",
                            cell_name(el.cell),
                            cell.ty.name()
                        )));
                    }
                    section.check().map_err(|m| {
                        FemError::Model(format!("beam on cell {}: {m}", cell_name(el.cell)))
                    })?;
                    shell = true;
                }
                ElementKind::Bar { area, .. } => {
                    if cell.ty != CellType::SEG2 {
                        return Err(FemError::Model(format!(
                            "cell {} is a {}: the BARRE element exists on SEG2 cells only",
                            cell_name(el.cell),
                            cell.ty.name()
                        )));
                    }
                    crate::bar::check_area(*area).map_err(|m| {
                        FemError::Model(format!("bar on cell {}: {m}", cell_name(el.cell)))
                    })?;
                    truss = true;
                }
                ElementKind::Grid { section, .. } => {
                    section.check(cell.ty).map_err(|m| {
                        FemError::Model(format!("grid on cell {} is {m}", cell_name(el.cell)))
                    })?;
                    truss = true;
                    if section.offset.is_some() {
                        shell = true;
                    }
                }
            }
            if let ElementKind::Continuum { .. } = el.kind {
                if !shape::supported(cell.ty) {
                    return Err(FemError::Model(format!(
                        "cell {}: no element for {}",
                        cell_name(el.cell),
                        cell.ty.name()
                    )));
                }
            }
        }
        let dim = match (hypothesis, spring_dim) {
            (Some(h), Some(d)) if h.dim() != d => {
                return Err(FemError::Model(format!(
                    "springs with {d} components in a {} model (use {})",
                    h.aster_name(),
                    if h.dim() == 2 { "2D_DIS_T" } else { "DIS_T" }
                )))
            }
            (Some(h), _) => h.dim(),
            (None, Some(d)) => d,
            (None, None) => {
                if mesh.dim >= 3 || shell || truss {
                    3
                } else {
                    2
                }
            }
        };
        if truss && dim != 3 {
            return Err(FemError::Model(format!(
                "BARRE elements in a {dim}D model: the 3D truss needs a 3D model (2D_BARRE is not reproduced)"
            )));
        }
        if shell && dim != 3 {
            return Err(FemError::Model(format!(
                "elements with rotations (DKT, POU_D_E, DIS_TR) in a {dim}D model: they need a 3D model"
            )));
        }
        // Component set per node: 0 the translations, 1 with the rotations
        // of the shells' nodes, 2 the rotations alone (the centre of a
        // COQUE_3D cell, which no other element may use).
        let mut set: Vec<Option<u8>> = vec![None; mesh.coords.len()];
        let mut shells = std::collections::BTreeSet::new();
        let mut centres = Vec::new();
        for el in &elements {
            let rot = el.kind.has_rotations();
            if rot {
                shells.insert(el.cell);
            }
            let nodes = &mesh.cells[el.cell.0 as usize].nodes;
            let edge = match el.kind {
                ElementKind::Coque3d { .. } => {
                    centres.push((nodes[nodes.len() - 1], el.cell));
                    &nodes[..nodes.len() - 1]
                }
                _ => &nodes[..],
            };
            for n in edge {
                let s = &mut set[n.0 as usize];
                *s = Some(s.unwrap_or(0).max(rot as u8));
            }
        }
        for &(n, cell) in &centres {
            let s = &mut set[n.0 as usize];
            if s.is_some_and(|s| s != 2) {
                return Err(FemError::Model(format!(
                    "the centre node of COQUE_3D cell {} is also a node of another element: it carries the rotations alone here",
                    cell_name(cell)
                )));
            }
            *s = Some(2);
        }
        let mut sets = vec![Comp::translations(dim).to_vec()];
        if shell {
            sets.push(Comp::ALL.to_vec());
        }
        if !centres.is_empty() {
            sets.push(vec![Comp::DRX, Comp::DRY, Comp::DRZ]);
        }
        let dofs = DofNumbering::per_node(sets, &set);
        let grids = elements
            .iter()
            .filter(|e| matches!(e.kind, ElementKind::Grid { .. }))
            .map(|e| e.cell)
            .collect();
        Ok(Model {
            grids,
            mesh,
            elements,
            dofs,
            dim,
            hypothesis,
            reduced: Default::default(),
            edges: Default::default(),
            stabilised: Default::default(),
            shells,
            mixed: Default::default(),
            mixed_rigi_meca: false,
        })
    }

    /// Integrates `cells` with the under-integrated stiffness family of
    /// code_aster's `_SI` modelisations ([`shape::reduced_scheme`]): their
    /// stiffness, internal forces and Gauss-point fields (SIEF_ELGA,
    /// VARI_ELGA) use it; their mass keeps the full family. Each cell must
    /// carry a continuum element of a type that has such a family.
    pub fn with_reduced_integration(
        mut self,
        cells: impl IntoIterator<Item = CellId>,
    ) -> Result<Model, FemError> {
        for cell in cells {
            let continuum = self
                .elements
                .iter()
                .any(|e| e.cell == cell && matches!(e.kind, ElementKind::Continuum { .. }));
            let ty = self.mesh.cell(cell).ty;
            let three_d = self.dim == 3;
            if continuum && three_d && ty == aster_mesh::CellType::HEXA8 {
                self.stabilised.insert(cell);
                continue;
            }
            if !continuum || shape::reduced_scheme(ty).is_none() {
                return Err(FemError::Model(format!(
                    "cell {} is a {}: under-integrated elements (_SI) exist here for QUAD8, HEXA20, TETRA10 and (3D) HEXA8 continuum cells only",
                    self.cell_name(cell),
                    ty.name()
                )));
            }
            self.reduced.insert(cell);
        }
        Ok(self)
    }

    /// Declares edge cells ([`Model::is_edge`]): segments of a 3D model
    /// that carry code_aster's `MECA_ARETE*` (no stiffness, no unknowns of
    /// their own). Cells that are not segments of a 3D model are refused.
    pub fn with_edges(
        mut self,
        cells: impl IntoIterator<Item = CellId>,
    ) -> Result<Model, FemError> {
        for cell in cells {
            let ty = self.mesh.cell(cell).ty;
            if self.dim != 3 || ty.dim() != 1 || !shape::supported(ty) {
                return Err(FemError::Model(format!(
                    "cell {} is a {}: edge elements are segments of a 3D model",
                    self.cell_name(cell),
                    ty.name()
                )));
            }
            self.edges.insert(cell);
        }
        Ok(self)
    }

    /// Makes `cells` code_aster's mixed displacement–pressure–swelling
    /// elements of `*_INCO_UPG` ([`crate::mixed_upg`]): their vertex nodes
    /// get the unknowns PRES and GONF after the translations. Each cell
    /// must carry a plane-strain, axisymmetric or 3D continuum element on
    /// a cell type that has such an element (TRIA6, QUAD8; HEXA20,
    /// PENTA15, TETRA10).
    pub fn with_mixed(
        mut self,
        cells: impl IntoIterator<Item = CellId>,
    ) -> Result<Model, FemError> {
        let mut vertices = vec![false; self.mesh.node_count()];
        for cell in cells {
            let hyp = match self.element_kind(cell) {
                Some(ElementKind::Continuum { hypothesis, .. }) => Some(*hypothesis),
                _ => None,
            };
            let ty = self.mesh.cell(cell).ty;
            let ok = hyp.is_some_and(|h| crate::mixed_upg::has_element(ty, h));
            if !ok || self.reduced.contains(&cell) || self.stabilised.contains(&cell) {
                return Err(FemError::Model(format!(
                    "cell {} is a {}: the mixed incompressible elements (_INCO_UPG) exist for TRIA6 and QUAD8 cells in D_PLAN and AXIS, HEXA20, PENTA15 and TETRA10 cells in 3D",
                    self.cell_name(cell),
                    ty.name()
                )));
            }
            let nodes = &self.mesh.cell(cell).nodes;
            for n in &nodes[..shape::corner_count(ty)] {
                if self.dofs.node_comps(*n).len() != self.dim {
                    return Err(FemError::Model(format!(
                        "cell {}: a vertex of a mixed incompressible element also carries rotations",
                        self.cell_name(cell)
                    )));
                }
                vertices[n.0 as usize] = true;
            }
            self.mixed.insert(cell);
        }
        if !self.mixed.is_empty() {
            self.dofs = self.dofs.extended(&vertices, &[Comp::PRES, Comp::GONF]);
        }
        Ok(self)
    }

    /// Makes the mixed cells' linear matrix code_aster's `RIGI_MECA`
    /// (MECA_STATIQUE: `nirmtd`, [`crate::mixed_upg::MixedCell::elastic_matrix`]).
    pub fn set_mixed_rigi_meca(&mut self, on: bool) {
        self.mixed_rigi_meca = on;
    }

    /// Whether the mixed cells' linear matrix is `RIGI_MECA`'s.
    pub fn mixed_rigi_meca(&self) -> bool {
        self.mixed_rigi_meca
    }

    /// Whether a cell is a mixed incompressible element ([`Model::with_mixed`]).
    pub fn is_mixed(&self, cell: CellId) -> bool {
        self.mixed.contains(&cell)
    }

    /// Whether the model has mixed incompressible elements.
    pub fn has_mixed(&self) -> bool {
        !self.mixed.is_empty()
    }

    /// How many components per node the element on `cell` uses: the
    /// first ones of each node's set (six on a shell, the translations
    /// otherwise).
    pub fn element_comps(&self, cell: CellId) -> usize {
        if self.shells.contains(&cell) {
            6
        } else {
            self.dim
        }
    }

    /// Whether `cell` carries a COQUE_3D element (the only element with
    /// rotations on a QUAD9 or TRIA7 cell).
    pub fn is_coque3d(&self, cell: CellId) -> bool {
        self.shells.contains(&cell)
            && matches!(self.mesh.cell(cell).ty, CellType::QUAD9 | CellType::TRIA7)
    }

    /// Whether the model has shell elements (`DKT`, `COQUE_3D`).
    pub fn has_shells(&self) -> bool {
        self.elements.iter().any(|e| {
            matches!(
                e.kind,
                ElementKind::Shell { .. } | ElementKind::Coque3d { .. }
            )
        })
    }

    /// Whether the model has COQUE_3D elements.
    pub fn has_coque3d(&self) -> bool {
        self.elements
            .iter()
            .any(|e| matches!(e.kind, ElementKind::Coque3d { .. }))
    }

    /// Whether the model has beams (`POU_D_E`, `POU_D_T`).
    pub fn has_beams(&self) -> bool {
        self.elements
            .iter()
            .any(|e| matches!(e.kind, ElementKind::Beam { .. }))
    }

    /// Whether the model has bars (`BARRE`).
    pub fn has_bars(&self) -> bool {
        self.elements
            .iter()
            .any(|e| matches!(e.kind, ElementKind::Bar { .. }))
    }

    /// Whether some nodes carry rotations (shells, beams, `DIS_TR`).
    pub fn has_rotations(&self) -> bool {
        !self.shells.is_empty()
    }

    /// Whether the model has reinforcement grids ([`crate::grid`]).
    pub fn has_grids(&self) -> bool {
        !self.grids.is_empty()
    }

    /// Whether a cell is code_aster's stabilised one-point HEXA8 of
    /// `3D_SI` ([`crate::hexs8`]).
    pub fn is_stabilised(&self, cell: CellId) -> bool {
        self.stabilised.contains(&cell)
    }

    /// Whether the model has stabilised one-point HEXA8 cells.
    pub fn has_stabilised(&self) -> bool {
        !self.stabilised.is_empty()
    }

    /// Whether a cell is an edge cell of a 3D model (a segment given a 3D
    /// modelisation: code_aster's `MECA_ARETE*`, no stiffness).
    pub fn is_edge(&self, cell: CellId) -> bool {
        self.edges.contains(&cell)
    }

    /// The edge cells ([`Model::is_edge`]).
    pub fn edge_cells(&self) -> impl Iterator<Item = CellId> + '_ {
        self.edges.iter().copied()
    }

    /// Whether a cell is under-integrated ([`Model::with_reduced_integration`]).
    pub fn is_reduced(&self, cell: CellId) -> bool {
        self.reduced.contains(&cell)
    }

    /// The stiffness Gauss family of a continuum cell: the reduced one of
    /// an `_SI` cell, else [`shape::stiffness_scheme`].
    pub fn stiffness_scheme(&self, cell: CellId) -> Vec<shape::GaussPoint> {
        let ty = self.mesh.cell(cell).ty;
        if self.grids.contains(&cell) {
            return crate::grid::scheme(ty);
        }
        if self.mixed.contains(&cell) {
            if let Some(h) = self.hypothesis {
                return crate::mixed_upg::scheme(ty, h);
            }
        }
        if self.reduced.contains(&cell) {
            if let Some(s) = shape::reduced_scheme(ty) {
                return s;
            }
        }
        shape::stiffness_scheme(ty, self.hypothesis)
    }

    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    pub fn mesh_arc(&self) -> &Arc<Mesh> {
        &self.mesh
    }

    pub fn elements(&self) -> &[Element] {
        &self.elements
    }

    /// What a cell carries (`None`: the cell is not in the model).
    pub fn element_kind(&self, cell: CellId) -> Option<&ElementKind> {
        self.elements
            .iter()
            .find(|e| e.cell == cell)
            .map(|e| &e.kind)
    }

    pub fn dofs(&self) -> &DofNumbering {
        &self.dofs
    }

    /// Space dimension of the unknowns (2 or 3).
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The continuum hypothesis, if the model has continuum elements.
    pub fn hypothesis(&self) -> Option<Hypothesis> {
        self.hypothesis
    }

    /// Name of a cell for messages.
    pub fn cell_name(&self, id: CellId) -> String {
        self.mesh.cell_name(id)
    }
}

/// Last assignment wins per cell; continuum modelisations on lower-
/// dimensional cells become boundary elements or nothing.
fn normalise(mesh: &Mesh, elements: Vec<Element>) -> Vec<Element> {
    let mut last: std::collections::HashMap<CellId, usize> = Default::default();
    for (k, el) in elements.iter().enumerate() {
        last.insert(el.cell, k);
    }
    let mut out = Vec::with_capacity(elements.len());
    for (k, el) in elements.into_iter().enumerate() {
        if last.get(&el.cell) != Some(&k) {
            continue;
        }
        let Some(cell) = mesh.cells.get(el.cell.0 as usize) else {
            out.push(el); // reported by Model::new
            continue;
        };
        if let ElementKind::Continuum { hypothesis, .. } = &el.kind {
            let cdim = cell.ty.dim() as usize;
            let hdim = hypothesis.dim();
            if cdim + 1 == hdim && shape::supported(cell.ty) {
                out.push(Element {
                    cell: el.cell,
                    kind: ElementKind::Boundary,
                });
                continue;
            }
            if cdim + 1 < hdim {
                continue;
            }
        }
        out.push(el);
    }
    out
}
