//! Built-in contact scenes, generated in code (no mesh file), with their fem
//! models and loads: the ZZZZ237 two-block scene (soft square pressed onto
//! a near-rigid block) with `n × n` cells per block, the SSNP121 kind of
//! two plates, and the Hertz cylinder on a plane ([`hertz_problem`], on the
//! mesh of [`crate::hertz::hertz_mesh`]). The tests, the benchmarks and
//! aster-study build their scenes here, so they all solve the same problem.

use aster_fem::{
    Comp, Dof, Elastic, Element, ElementKind, FemError, Frame, Hypothesis, Load, Loads, Model,
    Multiplier,
};
use aster_mesh::{Cell, CellId, CellType, Group, Mesh, NodeId};

/// The ZZZZ237 geometry with `n × n` QUAD4 in the square ABCD (100 × 100)
/// and `2n × n` in the block EFGH (200 × 100); `n = 1` is code_aster's mesh.
///
/// Nodes A=(0,0) B=(100,0) C=(100,100) D=(0,100) R1=(0,200) R2=(100,200)
/// E=(−50,0) F=(−50,−100) G=(150,−100) H=(150,0). Cell groups: `ABCD`,
/// `EFGH`, `AB` (slave, A→B), `HE` (master, H→E), `CD`, `FG`, `K1` (R1–D),
/// `K2` (R2–C). Node groups: the named points and every cell group.
pub fn two_blocks_mesh(n: usize) -> Result<Mesh, FemError> {
    if n == 0 {
        return Err(FemError::Model(
            "two_blocks_mesh: n must be at least 1".into(),
        ));
    }
    let mut m = Mesh {
        dim: 2,
        ..Mesh::default()
    };
    let mut named: Vec<(&str, NodeId)> = Vec::new();
    // Square: (n+1)² nodes, row-major from A.
    let sqn = |i: usize, j: usize| NodeId((j * (n + 1) + i) as u32);
    for j in 0..=n {
        for i in 0..=n {
            m.coords.push([
                100.0 * i as f64 / n as f64,
                100.0 * j as f64 / n as f64,
                0.0,
            ]);
        }
    }
    // Block: (2n+1)×(n+1) nodes from F.
    let base = m.coords.len();
    let bl = |i: usize, j: usize| NodeId((base + j * (2 * n + 1) + i) as u32);
    for j in 0..=n {
        for i in 0..=2 * n {
            m.coords.push([
                -50.0 + 200.0 * i as f64 / (2 * n) as f64,
                -100.0 + 100.0 * j as f64 / n as f64,
                0.0,
            ]);
        }
    }
    let r1 = NodeId(m.coords.len() as u32);
    m.coords.push([0.0, 200.0, 0.0]);
    let r2 = NodeId(m.coords.len() as u32);
    m.coords.push([100.0, 200.0, 0.0]);
    let (a, b, c, d) = (sqn(0, 0), sqn(n, 0), sqn(n, n), sqn(0, n));
    named.extend([("A", a), ("B", b), ("C", c), ("D", d)]);
    named.extend([
        ("E", bl(0, n)),
        ("F", bl(0, 0)),
        ("G", bl(2 * n, 0)),
        ("H", bl(2 * n, n)),
    ]);
    named.extend([("R1", r1), ("R2", r2)]);

    let push = |m: &mut Mesh, ty: CellType, nodes: Vec<NodeId>| {
        m.cells.push(Cell { ty, nodes });
        CellId((m.cells.len() - 1) as u32)
    };
    let mut abcd = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let nodes = vec![sqn(i, j), sqn(i + 1, j), sqn(i + 1, j + 1), sqn(i, j + 1)];
            abcd.push(push(&mut m, CellType::QUAD4, nodes));
        }
    }
    let mut efgh = Vec::new();
    for j in 0..n {
        for i in 0..2 * n {
            efgh.push(push(
                &mut m,
                CellType::QUAD4,
                vec![bl(i, j), bl(i + 1, j), bl(i + 1, j + 1), bl(i, j + 1)],
            ));
        }
    }
    let ab: Vec<CellId> = (0..n)
        .map(|i| push(&mut m, CellType::SEG2, vec![sqn(i, 0), sqn(i + 1, 0)]))
        .collect();
    let cd: Vec<CellId> = (0..n)
        .rev()
        .map(|i| push(&mut m, CellType::SEG2, vec![sqn(i + 1, n), sqn(i, n)]))
        .collect();
    let he: Vec<CellId> = (0..2 * n)
        .rev()
        .map(|i| push(&mut m, CellType::SEG2, vec![bl(i + 1, n), bl(i, n)]))
        .collect();
    let fg: Vec<CellId> = (0..2 * n)
        .map(|i| push(&mut m, CellType::SEG2, vec![bl(i, 0), bl(i + 1, 0)]))
        .collect();
    let k1 = vec![push(&mut m, CellType::SEG2, vec![r1, d])];
    let k2 = vec![push(&mut m, CellType::SEG2, vec![r2, c])];

    m.node_names = (1..=m.coords.len()).map(|i| format!("N{i}")).collect();
    for (name, id) in &named {
        m.node_names[id.0 as usize] = name.to_string();
    }
    m.cell_names = (1..=m.cells.len()).map(|i| format!("M{i}")).collect();
    add_groups(
        &mut m,
        [
            ("ABCD", abcd),
            ("EFGH", efgh),
            ("AB", ab),
            ("CD", cd),
            ("HE", he),
            ("FG", fg),
            ("K1", k1),
            ("K2", k2),
        ],
        named,
    );
    Ok(m)
}

/// The ZZZZ237 A model on a [`two_blocks_mesh`]: D_PLAN blocks (E = 2e9 for
/// ABCD, `2e9 × stiffness_ratio` for EFGH, ν = 0.3), springs K1 K2
/// (K_T_D_L 10, 10), FG and R1 R2 clamped, CD moved by DY = −t
/// (all eliminated, as AFFE_CHAR_CINE does).
pub fn two_blocks_problem(mesh: Mesh, stiffness_ratio: f64) -> Result<(Model, Loads), FemError> {
    let group = |name: &str| -> Result<Vec<CellId>, FemError> {
        mesh.group_ma(name)
            .map(|g| g.members.clone())
            .ok_or_else(|| FemError::Model(format!("mesh has no group {name}")))
    };
    let nodes = |name: &str| -> Result<Vec<NodeId>, FemError> {
        mesh.group_no(name)
            .map(|g| g.members.clone())
            .ok_or_else(|| FemError::Model(format!("mesh has no node group {name}")))
    };
    let soft = Elastic::new(2e9, 0.3)?;
    let hard = Elastic::new(2e9 * stiffness_ratio, 0.3)?;
    let mut elements = Vec::new();
    for (g, material) in [("ABCD", soft), ("EFGH", hard)] {
        for cell in group(g)? {
            elements.push(Element {
                cell,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material,
                },
            });
        }
    }
    for g in ["K1", "K2"] {
        for cell in group(g)? {
            elements.push(Element {
                cell,
                kind: ElementKind::Spring {
                    stiffness: vec![10.0, 10.0],
                    frame: Frame::Local,
                },
            });
        }
    }
    let mut loads = Loads::new();
    let mut fixed = nodes("FG")?;
    fixed.extend(nodes("R1")?);
    fixed.extend(nodes("R2")?);
    for n in fixed {
        for comp in [Comp::DX, Comp::DY] {
            loads.push(Load::Eliminated {
                dof: Dof::new(n, comp),
                value: 0.0,
            });
        }
    }
    for n in nodes("CD")? {
        loads.add(
            Load::Eliminated {
                dof: Dof::new(n, Comp::DY),
                value: -1.0,
            },
            Multiplier::from_fn(Ok),
        );
    }
    let model = Model::new(mesh, elements)?;
    Ok((model, loads))
}

/// Two plates pressed together (the SSNP121 kind of scene): an upper plate
/// `[-1, 1] × [0, 1]` with `n_up × n_up` QUAD4 and a lower plate
/// `[-1, 1] × [-1, 0]` with `n_low × n_low` QUAD4, meeting on y = 0 with
/// non-matching nodes when `n_up ≠ n_low`. Cell groups: `UP`, `LOW`,
/// `AB` (upper plate's bottom, A=(−1,0) → B=(1,0)), `EF` (lower plate's top,
/// F=(1,0) → E=(−1,0)), `CD` (top, y = 1), `GH` (bottom, y = −1). Node
/// groups: every cell group and A B E F.
pub fn two_plates_mesh(n_up: usize, n_low: usize) -> Result<Mesh, FemError> {
    if n_up == 0 || n_low == 0 {
        return Err(FemError::Model(
            "two_plates_mesh: each plate needs at least one cell".into(),
        ));
    }
    let mut m = Mesh {
        dim: 2,
        ..Mesh::default()
    };
    let mut groups: Vec<(&str, Vec<CellId>)> = Vec::new();
    let mut named: Vec<(&str, NodeId)> = Vec::new();
    for (upper, n) in [(true, n_up), (false, n_low)] {
        let base = m.coords.len();
        let id = |i: usize, j: usize| NodeId((base + j * (n + 1) + i) as u32);
        let y0 = if upper { 0.0 } else { -1.0 };
        for j in 0..=n {
            for i in 0..=n {
                m.coords.push([
                    -1.0 + 2.0 * i as f64 / n as f64,
                    y0 + j as f64 / n as f64,
                    0.0,
                ]);
            }
        }
        let mut push = |ty: CellType, nodes: Vec<NodeId>| {
            m.cells.push(Cell { ty, nodes });
            CellId((m.cells.len() - 1) as u32)
        };
        let mut body = Vec::new();
        for j in 0..n {
            for i in 0..n {
                body.push(push(
                    CellType::QUAD4,
                    vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
                ));
            }
        }
        let bottom: Vec<CellId> = (0..n)
            .map(|i| push(CellType::SEG2, vec![id(i, 0), id(i + 1, 0)]))
            .collect();
        let top: Vec<CellId> = (0..n)
            .rev()
            .map(|i| push(CellType::SEG2, vec![id(i + 1, n), id(i, n)]))
            .collect();
        if upper {
            named.extend([("A", id(0, 0)), ("B", id(n, 0))]);
            groups.extend([("UP", body), ("AB", bottom), ("CD", top)]);
        } else {
            named.extend([("E", id(0, n)), ("F", id(n, n))]);
            groups.extend([("LOW", body), ("GH", bottom), ("EF", top)]);
        }
    }
    m.node_names = (1..=m.coords.len()).map(|i| format!("N{i}")).collect();
    m.cell_names = (1..=m.cells.len()).map(|i| format!("M{i}")).collect();
    add_groups(&mut m, groups, named);
    Ok(m)
}

/// The SSNP121 loading on a [`two_plates_mesh`]: D_PLAN, E = 2e6, ν = 0 for
/// both plates; `CD` moved by (0, −0.1 t), `GH` clamped (eliminated).
/// Exact answer with a perfect interface: σ_yy = −1e5, the interface at
/// DY = −0.05.
pub fn two_plates_problem(mesh: Mesh) -> Result<(Model, Loads), FemError> {
    two_plates_problem_as(mesh, Hypothesis::PlaneStrain)
}

/// [`two_plates_problem`] under another 2D `hypothesis`. With ν = 0 the
/// answer is the same uniaxial one under AXIS (for a mesh in x ≥ 0, e.g.
/// shifted by +1): σ_yy = −1e5 and no radial displacement.
pub fn two_plates_problem_as(
    mesh: Mesh,
    hypothesis: Hypothesis,
) -> Result<(Model, Loads), FemError> {
    let material = Elastic::new(2e6, 0.0)?;
    let mut elements = Vec::new();
    for g in ["UP", "LOW"] {
        let cells = mesh
            .group_ma(g)
            .ok_or_else(|| FemError::Model(format!("mesh has no group {g}")))?;
        for &cell in &cells.members {
            elements.push(Element {
                cell,
                kind: ElementKind::Continuum {
                    hypothesis,
                    material,
                },
            });
        }
    }
    let mut loads = Loads::new();
    for (g, dy) in [("CD", -0.1), ("GH", 0.0)] {
        let nodes = mesh
            .group_no(g)
            .ok_or_else(|| FemError::Model(format!("mesh has no node group {g}")))?;
        for &n in &nodes.members {
            loads.push(Load::Eliminated {
                dof: Dof::new(n, Comp::DX),
                value: 0.0,
            });
            loads.add(
                Load::Eliminated {
                    dof: Dof::new(n, Comp::DY),
                    value: dy,
                },
                Multiplier::from_fn(Ok),
            );
        }
    }
    let model = Model::new(mesh, elements)?;
    Ok((model, loads))
}

/// Two plates pressed, then sheared (the friction scene, on a
/// [`two_plates_mesh`]): D_PLAN, E = 2e6, ν = 0; `GH` clamped; `CD` moved
/// down by 0.1 t up to t = 1, then sideways by `shear × (t − 1)` (all
/// eliminated). With `rigid_base` the whole lower plate is clamped (a
/// flat rigid master): at full slip the friction forces then carry μ times
/// the normal force, Σ FX(CD) = μ Σ FY(CD).
pub fn two_plates_shear_problem(
    mesh: Mesh,
    shear: f64,
    rigid_base: bool,
) -> Result<(Model, Loads), FemError> {
    let material = Elastic::new(2e6, 0.0)?;
    let mut elements = Vec::new();
    for g in ["UP", "LOW"] {
        let cells = mesh
            .group_ma(g)
            .ok_or_else(|| FemError::Model(format!("mesh has no group {g}")))?;
        for &cell in &cells.members {
            elements.push(Element {
                cell,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material,
                },
            });
        }
    }
    let mut loads = Loads::new();
    let node_group = |g: &str| {
        mesh.group_no(g)
            .map(|g| g.members.clone())
            .ok_or_else(|| FemError::Model(format!("mesh has no node group {g}")))
    };
    let clamped = if rigid_base {
        node_group("LOW")?
    } else {
        node_group("GH")?
    };
    for n in clamped {
        for comp in [Comp::DX, Comp::DY] {
            loads.push(Load::Eliminated {
                dof: Dof::new(n, comp),
                value: 0.0,
            });
        }
    }
    for n in node_group("CD")? {
        loads.add(
            Load::Eliminated {
                dof: Dof::new(n, Comp::DY),
                value: -0.1,
            },
            Multiplier::from_fn(|t: f64| Ok(t.min(1.0))),
        );
        loads.add(
            Load::Eliminated {
                dof: Dof::new(n, Comp::DX),
                value: shear,
            },
            Multiplier::from_fn(|t: f64| Ok((t - 1.0).max(0.0))),
        );
    }
    let model = Model::new(mesh, elements)?;
    Ok((model, loads))
}

/// Adds each cell group and the node group of its cells under the same
/// name, then the one-node groups `named`.
/// The Hertz problem on a [`crate::hertz::hertz_mesh`]: plane strain, the
/// half cylinder `CYL` and the layer `PLAN` of one elastic `material`; the
/// base of `PLAN` clamped, the symmetry line `SYME` held in DX, the hub
/// `HUB` held in DX and pushed down by `depth × t` (all eliminated). The
/// contact pair is `MAIT` (the plane) and `ESCL` (the cylinder).
pub fn hertz_problem(
    mesh: Mesh,
    material: Elastic,
    depth: f64,
) -> Result<(Model, Loads), FemError> {
    let cells = |g: &str| {
        mesh.group_ma(g)
            .map(|g| g.members.clone())
            .ok_or_else(|| FemError::Model(format!("the Hertz mesh has no cell group {g}")))
    };
    let nodes = |g: &str| {
        mesh.group_no(g)
            .map(|g| g.members.clone())
            .ok_or_else(|| FemError::Model(format!("the Hertz mesh has no node group {g}")))
    };
    let mut elements = Vec::new();
    for g in ["CYL", "PLAN"] {
        for cell in cells(g)? {
            elements.push(Element {
                cell,
                kind: ElementKind::Continuum {
                    hypothesis: Hypothesis::PlaneStrain,
                    material,
                },
            });
        }
    }
    let fixed = |n, comp| Load::Eliminated {
        dof: Dof::new(n, comp),
        value: 0.0,
    };
    let mut loads = Loads::new();
    for n in nodes("PLAN")? {
        loads.push(fixed(n, Comp::DX));
        loads.push(fixed(n, Comp::DY));
    }
    for n in nodes("SYME")? {
        loads.push(fixed(n, Comp::DX));
    }
    for n in nodes("HUB")? {
        loads.push(fixed(n, Comp::DX));
        loads.add(
            Load::Eliminated {
                dof: Dof::new(n, Comp::DY),
                value: -depth,
            },
            Multiplier::from_fn(Ok),
        );
    }
    let model = Model::new(mesh, elements)?;
    Ok((model, loads))
}

fn add_groups<'a>(
    m: &mut Mesh,
    groups: impl IntoIterator<Item = (&'a str, Vec<CellId>)>,
    named: impl IntoIterator<Item = (&'a str, NodeId)>,
) {
    for (name, cells) in groups {
        let mut nodes: Vec<NodeId> = cells
            .iter()
            .flat_map(|c| m.cells[c.0 as usize].nodes.clone())
            .collect();
        nodes.sort();
        nodes.dedup();
        m.groups_ma.push(Group {
            name: name.into(),
            members: cells,
        });
        m.groups_no.push(Group {
            name: name.into(),
            members: nodes,
        });
    }
    for (name, id) in named {
        m.groups_no.push(Group {
            name: name.into(),
            members: vec![id],
        });
    }
}
