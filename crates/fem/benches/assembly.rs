//! Assembling and factorising a 2D plane-strain QUAD4 problem (issue 5's
//! speed bar: 1 million DOFs under 5 s on 2 cores, under 4 GB).
//!
//! `cargo bench -p aster-fem --bench assembly` runs 100k and 1M DOFs.
//! Set `ASTER_BENCH_QUICK=1` to run only the 100k case.

use aster_fem::assembly::{assemble_stiffness, restrict};
use aster_fem::linalg;
use aster_fem::*;
use aster_mesh::{Cell, CellId, CellType, Mesh, NodeId};
use criterion::{criterion_group, criterion_main, Criterion};
use std::time::Duration;

/// An n×n grid of QUAD4 on the unit square, bottom edge clamped.
fn problem(n: usize) -> (Model, Vec<usize>) {
    let mut mesh = Mesh {
        dim: 2,
        ..Mesh::default()
    };
    for j in 0..=n {
        for i in 0..=n {
            mesh.coords
                .push([i as f64 / n as f64, j as f64 / n as f64, 0.]);
            mesh.node_names.push(format!("N{}", j * (n + 1) + i + 1));
        }
    }
    let id = |i: usize, j: usize| NodeId((j * (n + 1) + i) as u32);
    for j in 0..n {
        for i in 0..n {
            mesh.cells.push(Cell {
                ty: CellType::QUAD4,
                nodes: vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
            });
            mesh.cell_names.push(format!("M{}", j * n + i + 1));
        }
    }
    let material = Elastic::new(2e11, 0.3).unwrap();
    let elements = (0..mesh.cells.len())
        .map(|c| Element {
            cell: CellId(c as u32),
            kind: ElementKind::Continuum {
                hypothesis: Hypothesis::PlaneStrain,
                material,
            },
        })
        .collect();
    let model = Model::new(mesh, elements).unwrap();
    let mut map = vec![0; model.dofs().len()];
    let mut nfree = 0;
    for (k, m) in map.iter_mut().enumerate() {
        let dof = model.dofs().dof(k);
        if dof.node.0 as usize <= n {
            *m = usize::MAX; // bottom row clamped (eliminated)
        } else {
            *m = nfree;
            nfree += 1;
        }
    }
    (model, map)
}

fn assemble_and_factorise(model: &Model, map: &[usize], coords: &[[f64; 3]]) -> f64 {
    let k = assemble_stiffness(model).unwrap();
    let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
    let kff = restrict(&k, map, nfree);
    let mut b = vec![0.0; nfree];
    b[nfree - 1] = 1e6;
    let r = linalg::solve_with(&kff, &b, nfree, true, Some(coords)).unwrap();
    r.x[nfree - 1]
}

fn bench(c: &mut Criterion) {
    let quick = std::env::var_os("ASTER_BENCH_QUICK").is_some();
    let sizes: &[usize] = if quick { &[224] } else { &[224, 707] };
    let mut g = c.benchmark_group("plane_strain_quad4");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(20));
    for &n in sizes {
        let (model, map) = problem(n);
        let dofs = model.dofs().len();
        // Coordinates of the free unknowns, as the solver gives them.
        let coords: Vec<[f64; 3]> = (0..dofs)
            .filter(|&i| map[i] != usize::MAX)
            .map(|i| model.mesh().coord(model.dofs().dof(i).node))
            .collect();
        g.bench_function(format!("assemble+factorise {dofs} dofs"), |bch| {
            bch.iter(|| assemble_and_factorise(&model, &map, &coords))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
