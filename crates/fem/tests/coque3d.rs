//! code_aster's COQUE_3D QUAD9 and TRIA7 (`aster_fem::coque3d`) against
//! closed forms: symmetry, rigid motions, a cantilever strip (QUAD9 cells,
//! or each split into two TRIA7) under an end moment and an end tension
//! (exact: ν = 0, constant curvature and membrane strain are in the
//! elements' space) and under an end shear (beam theory, the two meshes
//! against each other), and a simply supported square plate under uniform
//! pressure against Kirchhoff's series, every geometry rotated in space.
#![allow(clippy::needless_range_loop)]

mod common;

use aster_fem::coque3d::{self, Coque3dSection};
use aster_fem::Elastic;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

fn rotation(axis: [f64; 3], angle: f64) -> Matrix3<f64> {
    let a = Vector3::from(axis).normalize();
    *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(a), angle).matrix()
}

fn tilted() -> Matrix3<f64> {
    rotation([0.3, -0.7, 0.65], 0.9)
}

/// A flat QUAD9 grid on [0, lx] × [0, ly], mapped by `r`: nodes on a
/// (2nx+1) × (2ny+1) lattice, each cell its eight edge nodes and its
/// centre; or the same squares each split along its diagonal into two
/// TRIA7 (the square's centre a mid-side node, each triangle's centre a
/// node of its own, appended).
struct Grid {
    nodes: Vec<[f64; 3]>,
    cells: Vec<Vec<usize>>,
    ny2: usize,
}

impl Grid {
    fn build(lx: f64, ly: f64, nx: usize, ny: usize, r: &Matrix3<f64>, tria: bool) -> Grid {
        let (nx2, ny2) = (2 * nx, 2 * ny);
        let mut nodes = Vec::new();
        for i in 0..=nx2 {
            for j in 0..=ny2 {
                let p =
                    r * Vector3::new(lx * i as f64 / nx2 as f64, ly * j as f64 / ny2 as f64, 0.);
                nodes.push([p[0], p[1], p[2]]);
            }
        }
        let id = |i: usize, j: usize| i * (ny2 + 1) + j;
        let mut cells = Vec::new();
        for ex in 0..nx {
            for ey in 0..ny {
                let (i, j) = (2 * ex, 2 * ey);
                if !tria {
                    cells.push(vec![
                        id(i, j),
                        id(i + 2, j),
                        id(i + 2, j + 2),
                        id(i, j + 2),
                        id(i + 1, j),
                        id(i + 2, j + 1),
                        id(i + 1, j + 2),
                        id(i, j + 1),
                        id(i + 1, j + 1),
                    ]);
                    continue;
                }
                for t in [
                    [
                        id(i, j),
                        id(i + 2, j),
                        id(i + 2, j + 2),
                        id(i + 1, j),
                        id(i + 2, j + 1),
                        id(i + 1, j + 1),
                    ],
                    [
                        id(i, j),
                        id(i + 2, j + 2),
                        id(i, j + 2),
                        id(i + 1, j + 1),
                        id(i + 1, j + 2),
                        id(i, j + 1),
                    ],
                ] {
                    let c = (0..3).fold([0.; 3], |a, k| {
                        [0, 1, 2].map(|d| a[d] + nodes[t[k]][d] / 3.)
                    });
                    nodes.push(c);
                    let mut cell = t.to_vec();
                    cell.push(nodes.len() - 1);
                    cells.push(cell);
                }
            }
        }
        Grid { nodes, cells, ny2 }
    }

    fn id(&self, i: usize, j: usize) -> usize {
        i * (self.ny2 + 1) + j
    }

    /// The element's DOFs in the global numbering (6 per node).
    fn dofs(c: &[usize]) -> Vec<usize> {
        let nb1 = c.len() - 1;
        let mut d = Vec::with_capacity(6 * nb1 + 3);
        for &n in &c[..nb1] {
            d.extend((0..6).map(|k| 6 * n + k));
        }
        d.extend((3..6).map(|k| 6 * c[nb1] + k));
        d
    }

    /// The edge nodes of a cell.
    fn xyz(&self, c: &[usize]) -> Vec<[f64; 3]> {
        c[..c.len() - 1].iter().map(|&n| self.nodes[n]).collect()
    }

    fn stiffness(&self, mat: &Elastic, sec: &Coque3dSection) -> DMatrix<f64> {
        let n = 6 * self.nodes.len();
        let mut k = DMatrix::zeros(n, n);
        for c in &self.cells {
            let ke = coque3d::stiffness(&self.xyz(c), mat, sec).expect("element");
            let d = Self::dofs(c);
            let nd = d.len();
            for a in 0..nd {
                for b in 0..nd {
                    k[(d[a], d[b])] += ke[a * nd + b];
                }
            }
        }
        k
    }

    /// The translations of the central nodes, which no element uses.
    fn centre_translations(&self) -> Vec<usize> {
        self.cells
            .iter()
            .flat_map(|c| (0..3).map(move |k| 6 * c[c.len() - 1] + k))
            .collect()
    }
}

use common::solve_held as solve;

fn add(f: &mut DVector<f64>, n: usize, c0: usize, r: &Matrix3<f64>, v: [f64; 3]) {
    let g = r * Vector3::from(v);
    for i in 0..3 {
        f[6 * n + c0 + i] += g[i];
    }
}

fn local(u: &DVector<f64>, n: usize, c0: usize, r: &Matrix3<f64>) -> Vector3<f64> {
    r.transpose() * Vector3::new(u[6 * n + c0], u[6 * n + c0 + 1], u[6 * n + c0 + 2])
}

/// A flat distorted QUAD9 (mid-side nodes moved in the plane), tilted.
fn distorted(r: &Matrix3<f64>) -> [[f64; 3]; 8] {
    let xy = [
        [0., 0.],
        [2.1, 0.2],
        [2.4, 1.9],
        [-0.2, 1.6],
        [1.1, 0.05],
        [2.3, 1.0],
        [1.0, 1.85],
        [-0.05, 0.8],
    ];
    xy.map(|[x, y]| {
        let p = r * Vector3::new(x, y, 0.);
        [p[0], p[1], p[2]]
    })
}

/// A flat distorted TRIA7 (mid-side nodes moved in the plane), tilted.
fn distorted_tria(r: &Matrix3<f64>) -> Vec<[f64; 3]> {
    let xy = [
        [0., 0.],
        [2.1, 0.2],
        [0.4, 1.9],
        [1.1, 0.2],
        [1.2, 1.1],
        [0.1, 0.9],
    ];
    xy.iter()
        .map(|&[x, y]| {
            let p = r * Vector3::new(x, y, 0.);
            [p[0], p[1], p[2]]
        })
        .collect()
}

#[test]
fn stiffness_is_symmetric_and_rigid_motions_are_stress_free() {
    let r = tilted();
    rigid_motions(&distorted(&r), &r);
}

#[test]
fn tria7_stiffness_is_symmetric_and_rigid_motions_are_stress_free() {
    let r = tilted();
    rigid_motions(&distorted_tria(&r), &r);
}

fn rigid_motions(xyz: &[[f64; 3]], r: &Matrix3<f64>) {
    let nb1 = xyz.len();
    let nddl = 6 * nb1 + 3;
    let mat = Elastic::new(2e11, 0.3).unwrap();
    let mut sec = Coque3dSection::new(0.05);
    for drilling in [0., 1e-5] {
        sec.drilling = drilling;
        let k = coque3d::stiffness(xyz, &mat, &sec).unwrap();
        assert_eq!(k.len(), nddl * nddl);
        let scale = (0..nddl).map(|i| k[i * nddl + i].abs()).fold(0., f64::max);
        for i in 0..nddl {
            for j in 0..nddl {
                assert!(
                    (k[i * nddl + j] - k[j * nddl + i]).abs() <= 1e-12 * scale,
                    "K[{i},{j}] = {} ≠ K[{j},{i}] = {}",
                    k[i * nddl + j],
                    k[j * nddl + i]
                );
            }
        }
        let normal = r * Vector3::z();
        // Rigid motions: three translations, three rotations about the
        // first node.
        let mut modes = Vec::new();
        for a in 0..3 {
            let mut u = vec![0.; nddl];
            for n in 0..nb1 {
                u[6 * n + a] = 1.;
            }
            modes.push((u, false));
        }
        let x0 = Vector3::from(xyz[0]);
        for a in 0..3 {
            let theta = Vector3::ith(a, 1.);
            let mut u = vec![0.; nddl];
            for n in 0..nb1 {
                let v = theta.cross(&(Vector3::from(xyz[n]) - x0));
                for c in 0..3 {
                    u[6 * n + c] = v[c];
                    u[6 * n + 3 + c] = theta[c];
                }
            }
            for c in 0..3 {
                u[6 * nb1 + c] = theta[c];
            }
            modes.push((u, theta.dot(&normal).abs() > 1e-12));
        }
        for (u, drills) in modes {
            let f: Vec<f64> = (0..nddl)
                .map(|i| (0..nddl).map(|j| k[i * nddl + j] * u[j]).sum())
                .collect();
            // The drilling spring holds the normal rotation absolutely
            // (code_aster's `matrkb`): a rigid rotation about the normal
            // loads only the rotation DOFs, by coef·(n·θ) along n.
            let fmax = f.iter().map(|v| v.abs()).fold(0., f64::max);
            if drilling == 0. || !drills {
                assert!(fmax <= 1e-9 * scale, "rigid motion loads {fmax:e}");
            } else {
                for n in 0..nb1 {
                    for c in 0..3 {
                        assert!(f[6 * n + c].abs() <= 1e-9 * scale, "translation loaded");
                    }
                }
                assert!(fmax > 1e-9 * scale);
            }
        }
    }
}

/// An 8 × 1 cantilever strip (L = 4, b = 0.5, h = 0.05, ν = 0) clamped at
/// x = 0: the loads on the tip edge's three nodes with the quadratic
/// edge's weights 1/6, 4/6, 1/6.
fn strip_tip(
    tria: bool,
    load: impl Fn(&mut DVector<f64>, usize, f64),
) -> (Grid, DVector<f64>, Matrix3<f64>) {
    let r = tilted();
    let (l, b, nx) = (4., 0.5, 8);
    let g = Grid::build(l, b, nx, 1, &r, tria);
    let mat = Elastic::new(2e11, 0.).unwrap();
    let sec = Coque3dSection::new(0.05);
    let k = g.stiffness(&mat, &sec);
    let mut f = DVector::zeros(k.nrows());
    for (j, w) in [(0, 1. / 6.), (1, 4. / 6.), (2, 1. / 6.)] {
        load(&mut f, g.id(2 * nx, j), w);
    }
    let mut fixed = g.centre_translations();
    for j in 0..=2 {
        fixed.extend((0..6).map(|c| 6 * g.id(0, j) + c));
    }
    let u = solve(&k, &f, &fixed);
    (g, u, r)
}

#[test]
fn cantilever_strip_under_end_moment_is_exact() {
    let (e, l, b, h, m) = (2e11, 4., 0.5, 0.05, 1e3);
    let ei = e * b * h * h * h / 12.;
    let r = tilted();
    for tria in [false, true] {
        let (g, u, _) = strip_tip(tria, |f, n, w| add(f, n, 3, &r, [0., m * w, 0.]));
        for j in 0..=2 {
            let n = g.id(16, j);
            let w = local(&u, n, 0, &r)[2];
            let th = local(&u, n, 3, &r)[1];
            let want_w = -m * l * l / (2. * ei);
            let want_th = m * l / ei;
            assert!(
                (w - want_w).abs() <= 1e-9 * want_w.abs(),
                "w {w} vs {want_w}"
            );
            assert!(
                (th - want_th).abs() <= 1e-9 * want_th,
                "θ {th} vs {want_th}"
            );
        }
        // Half way, w = −M·x²/(2EI).
        let w = local(&u, g.id(8, 1), 0, &r)[2];
        let want = -m * 4. / (2. * ei);
        assert!((w - want).abs() <= 1e-9 * want.abs(), "{w} vs {want}");
    }
}

#[test]
fn cantilever_strip_under_end_tension_is_exact() {
    let (e, l, b, h, n) = (2e11, 4., 0.5, 0.05, 1e6);
    let r = tilted();
    for tria in [false, true] {
        let (g, u, _) = strip_tip(tria, |f, node, w| add(f, node, 0, &r, [n * w, 0., 0.]));
        let want = n * l / (e * b * h);
        for j in 0..=2 {
            let ux = local(&u, g.id(16, j), 0, &r);
            assert!((ux[0] - want).abs() <= 1e-9 * want, "{} vs {want}", ux[0]);
            assert!(ux[2].abs() <= 1e-9 * want);
        }
    }
}

#[test]
fn cantilever_strip_under_end_shear_tria7_against_quad9_and_beam_theory() {
    // End force P along the normal: w = PL³/(3EI) + PL/(κGA) (Timoshenko
    // with code_aster's κ = 0.8333333, ν = 0: G = E/2). The cubic
    // deflection is outside both elements' space: the 8-cell QUAD9 strip
    // measured 7e-11 below the formula, its 16 TRIA7 5.8e-4 below (stiffer:
    // the triangle's shear on three reduced points, extrapolated linearly,
    // locks a little where the QUAD9's does not).
    let (e, l, b, h, p) = (2e11, 4., 0.5, 0.05, 10.);
    let ei = e * b * h * h * h / 12.;
    let want = p * l * l * l / (3. * ei) + p * l / (0.8333333 * e / 2. * b * h);
    let r = tilted();
    let tip = |tria: bool| {
        let (g, u, _) = strip_tip(tria, |f, node, w| add(f, node, 0, &r, [0., 0., p * w]));
        (0..=2)
            .map(|j| local(&u, g.id(16, j), 0, &r)[2])
            .sum::<f64>()
            / 3.
    };
    let (wq, wt) = (tip(false), tip(true));
    eprintln!(
        "end shear: QUAD9 {:e}, TRIA7 {:e}",
        wq / want - 1.,
        wt / want - 1.
    );
    assert!((wq - want).abs() <= 1e-5 * want, "QUAD9 {wq} vs {want}");
    assert!((wt - want).abs() <= 1e-3 * want, "TRIA7 {wt} vs {want}");
    assert!(wt < wq, "TRIA7 {wt} vs QUAD9 {wq}");
}

/// Simply supported square plate (a = 1, h = 0.01, ν = 0.3) under a
/// uniform pressure q: Kirchhoff's w(centre) = 0.00406235·q·a⁴/D. The
/// plate lies in z = 0 (the hard support holds the rotation along each
/// edge, a global component there).
fn plate_centre_deflection(n: usize, hard: bool) -> f64 {
    plate_centre_deflection_of(n, hard, false)
}

fn plate_centre_deflection_of(n: usize, hard: bool, tria: bool) -> f64 {
    let r = Matrix3::identity();
    let (a, h, q, e, nu) = (1., 0.01, 1e3, 2e11, 0.3);
    let g = Grid::build(a, a, n, n, &r, tria);
    let mat = Elastic::new(e, nu).unwrap();
    let sec = Coque3dSection::new(h);
    let k = g.stiffness(&mat, &sec);
    let mut f = DVector::zeros(k.nrows());
    // Consistent loads of the QUAD8 on a square: corners −1/12, mid-sides
    // 1/3 of the cell's area; of the straight TRIA6: corners 0, mid-sides
    // 1/3 of the triangle's.
    let area = (a / n as f64).powi(2);
    for c in &g.cells {
        let nb1 = c.len() - 1;
        let corners = nb1 / 2;
        for (i, &node) in c[..nb1].iter().enumerate() {
            let w = match (tria, i < corners) {
                (false, true) => -1. / 12.,
                (false, false) => 1. / 3.,
                (true, true) => 0.,
                (true, false) => 1. / 6.,
            };
            add(&mut f, node, 0, &r, [0., 0., q * area * w]);
        }
    }
    let mut fixed = g.centre_translations();
    let last = 2 * n;
    for i in 0..=last {
        for j in 0..=last {
            if i == 0 || j == 0 || i == last || j == last {
                fixed.extend((0..3).map(|c| 6 * g.id(i, j) + c));
            }
            // Edges x = 0, a run along y: the rotation about y is free,
            // the one about x (∂w/∂y) is held, and conversely.
            if hard && (i == 0 || i == last) {
                fixed.push(6 * g.id(i, j) + 3);
            }
            if hard && (j == 0 || j == last) {
                fixed.push(6 * g.id(i, j) + 4);
            }
        }
    }
    let u = solve(&k, &f, &fixed);
    let d = e * h * h * h / (12. * (1. - nu * nu));
    local(&u, g.id(n, n), 0, &r)[2] / (q * a.powi(4) / d)
}

#[test]
fn simply_supported_plate_under_pressure_converges_to_kirchhoff() {
    let exact = 0.00406235;
    // Hard support (the edge rotation held): the 2×2, 4×4, 8×8 meshes
    // measured −5.7 %, −0.51 %, +0.043 % (the limit, +0.05 % at 16×16, is
    // Mindlin's shear deflection at h/a = 0.01). The soft support (edge
    // rotations free) stays 0.9 % above at 16×16, its boundary layer.
    let errs: Vec<f64> = [2, 4, 8]
        .iter()
        .map(|&n| ((plate_centre_deflection(n, true) - exact) / exact).abs())
        .collect();
    assert!(
        errs[2] < 1e-3 && errs[1] < 1e-2 && errs[0] > errs[1],
        "{errs:?}"
    );
    let soft = (plate_centre_deflection(8, false) - exact) / exact;
    assert!(soft > 5e-3 && soft < 2e-2, "{soft}");
}

#[test]
fn simply_supported_plate_of_tria7_converges_to_kirchhoff() {
    // The same plate, each square split into two TRIA7 (hard support).
    let exact = 0.00406235;
    let errs: Vec<f64> = [2, 4, 8]
        .iter()
        .map(|&n| ((plate_centre_deflection_of(n, true, true) - exact) / exact).abs())
        .collect();
    // Measured: −73 %, −21 %, −3.7 % on 2², 4², 8² squares (8, 32, 128
    // triangles): the thin plate (h/a = 0.01) shows the triangle's shear
    // locking, which the QUAD9 (−0.51 % at 4²) does not.
    assert!(
        errs[2] < 0.05 && errs[1] < 0.25 && errs[0] > errs[1] && errs[1] > errs[2],
        "{errs:?}"
    );
}

#[test]
fn pressure_load_sums_to_pressure_times_area_along_the_normal() {
    let r = tilted();
    let xyz = distorted(&r);
    let f = coque3d::pressure_load(&xyz, &[2.5; 8]).unwrap();
    // The sum is −p·∫|a₁×a₂| along n (the cell is flat: every nodal
    // normal is n), checked against a fine rule.
    let mut total = Vector3::zeros();
    for n in 0..8 {
        total += Vector3::new(f[6 * n], f[6 * n + 1], f[6 * n + 2]);
        for c in 3..6 {
            assert_eq!(f[6 * n + c], 0.);
        }
    }
    let normal = r * Vector3::z();
    assert!(total.cross(&normal).norm() <= 1e-12 * total.norm());
    let area = -total.dot(&normal) / 2.5;
    // The area of the flat QUAD8: a 400×400 midpoint sum of det J (a
    // polynomial of degree ≤ 3 per direction, which FPG9COQ integrates
    // exactly; the midpoint sum is within ~1e-6).
    let xy: Vec<[f64; 2]> = xyz
        .iter()
        .map(|p| {
            let l = r.transpose() * Vector3::from(*p);
            [l[0], l[1]]
        })
        .collect();
    let nm = 400;
    let mut fine = 0.;
    for i in 0..nm {
        for j in 0..nm {
            let (x, y) = (
                -1. + (2 * i + 1) as f64 / nm as f64,
                -1. + (2 * j + 1) as f64 / nm as f64,
            );
            let d = qu8_derivatives(x, y);
            let (mut j11, mut j12, mut j21, mut j22) = (0., 0., 0., 0.);
            for n in 0..8 {
                j11 += d[0][n] * xy[n][0];
                j12 += d[0][n] * xy[n][1];
                j21 += d[1][n] * xy[n][0];
                j22 += d[1][n] * xy[n][1];
            }
            fine += (j11 * j22 - j12 * j21) * (2. / nm as f64).powi(2);
        }
    }
    assert!((area - fine).abs() <= 1e-5 * fine, "{area} vs {fine}");
}

#[test]
fn tria7_pressure_load_sums_to_pressure_times_area_along_the_normal() {
    // TRIA6 geometry with straight sides is the flat triangle (the
    // mid-side nodes moved along the sides would curve nothing): FPG7
    // integrates its constant det J exactly.
    let r = tilted();
    let xy = [[0., 0.], [2.1, 0.2], [0.4, 1.9]];
    let mid = |a: usize, c: usize| [(xy[a][0] + xy[c][0]) / 2., (xy[a][1] + xy[c][1]) / 2.];
    let pts = [xy[0], xy[1], xy[2], mid(0, 1), mid(1, 2), mid(2, 0)];
    let xyz: Vec<[f64; 3]> = pts
        .iter()
        .map(|&[x, y]| {
            let p = r * Vector3::new(x, y, 0.);
            [p[0], p[1], p[2]]
        })
        .collect();
    let f = coque3d::pressure_load(&xyz, &[2.5; 6]).unwrap();
    assert_eq!(f.len(), 39);
    let mut total = Vector3::zeros();
    for n in 0..6 {
        total += Vector3::new(f[6 * n], f[6 * n + 1], f[6 * n + 2]);
    }
    let area = ((xy[1][0] - xy[0][0]) * (xy[2][1] - xy[0][1])
        - (xy[2][0] - xy[0][0]) * (xy[1][1] - xy[0][1]))
        / 2.;
    let want = -(r * Vector3::z()) * 2.5 * area;
    assert!(
        (total - want).norm() <= 1e-13 * want.norm(),
        "{total} vs {want}"
    );
    // A straight-sided TRIA6 under uniform pressure loads its corners 0
    // and its mid-sides a third each.
    for n in 0..3 {
        assert!(Vector3::new(f[6 * n], f[6 * n + 1], f[6 * n + 2]).norm() <= 1e-13 * want.norm());
    }
}

fn qu8_derivatives(x: f64, y: f64) -> [[f64; 8]; 2] {
    [
        [
            -0.25 * (1. - y) * (-2. * x - y),
            0.25 * (1. - y) * (2. * x - y),
            0.25 * (1. + y) * (2. * x + y),
            -0.25 * (1. + y) * (-2. * x + y),
            -x * (1. - y),
            (1. - y * y) / 2.,
            -x * (1. + y),
            -(1. - y * y) / 2.,
        ],
        [
            -0.25 * (1. - x) * (-2. * y - x),
            -0.25 * (1. + x) * (-2. * y + x),
            0.25 * (1. + x) * (2. * y + x),
            0.25 * (1. - x) * (2. * y - x),
            -(1. - x * x) / 2.,
            -y * (1. + x),
            (1. - x * x) / 2.,
            -y * (1. - x),
        ],
    ]
}

#[test]
fn layer_stresses_of_the_strip_are_beam_theory() {
    // End moment M about local y (u = z·θ: the bottom shortens): σxx =
    // −6M/(b·h²), 0, +6M/(b·h²) at the bottom, middle and top of every
    // point; end tension: σxx = N/(b·h) everywhere.
    let (b, h, m, n) = (0.5, 0.05, 1e3, 1e6);
    let r = tilted();
    let mat = Elastic::new(2e11, 0.).unwrap();
    let sec = Coque3dSection::new(h);
    for (case, want, tria) in [
        (0, [-6. * m / (b * h * h), 0., 6. * m / (b * h * h)], false),
        (1, [n / (b * h); 3], false),
        (0, [-6. * m / (b * h * h), 0., 6. * m / (b * h * h)], true),
        (1, [n / (b * h); 3], true),
    ] {
        let (g, u, _) = strip_tip(tria, |f, node, w| {
            if case == 0 {
                add(f, node, 3, &r, [0., m * w, 0.])
            } else {
                add(f, node, 0, &r, [n * w, 0., 0.])
            }
        });
        for c in &g.cells {
            let d = Grid::dofs(c);
            let ue: Vec<f64> = d.iter().map(|&i| u[i]).collect();
            let s = coque3d::stresses(&g.xyz(c), &mat, &sec, &ue).unwrap();
            assert_eq!(s.len(), if c.len() == 9 { 27 } else { 21 });
            let scale = want.iter().map(|v: &f64| v.abs()).fold(0., f64::max);
            for (i, sig) in s.iter().enumerate() {
                let w = want[i % 3];
                if tria {
                    // The points' frames of the triangles on the diagonal
                    // are turned by 45°: the uniaxial state is found by
                    // its invariants (trace w, zero determinant).
                    let det = sig[0] * sig[1] - sig[3] * sig[3];
                    assert!(
                        (sig[0] + sig[1] - w).abs() <= 1e-7 * scale
                            && det.abs() <= 1e-7 * scale * scale,
                        "{case} {i}: {sig:?} vs {w}"
                    );
                    for k in [2, 4, 5] {
                        assert!(sig[k].abs() <= 1e-7 * scale, "{case} {i}: {sig:?}");
                    }
                    continue;
                }
                assert!(
                    (sig[0] - w).abs() <= 1e-7 * scale,
                    "{case} {i}: {sig:?} vs {w}"
                );
                for k in 1..6 {
                    assert!(sig[k].abs() <= 1e-7 * scale, "{case} {i}: {sig:?}");
                }
            }
        }
    }
}

#[test]
fn nodal_layer_stresses_of_the_strip_in_the_user_frame() {
    // End moment on the strip: SIGM_ELNO at every node, bottom/middle/top
    // = −6M/(bh²), 0, +6M/(bh²) along the strip's axis. With the user's x
    // along the strip (its projection of `direction`), SIXX carries it;
    // with the user's x across the strip, SIYY does.
    let (b, h, m) = (0.5, 0.05, 1e3);
    let r = tilted();
    let mat = Elastic::new(2e11, 0.).unwrap();
    let sec = Coque3dSection::new(h);
    let s0 = 6. * m / (b * h * h);
    let along = r * Vector3::new(1., 0., 0.3);
    let across = r * Vector3::new(0., 1., -0.2);
    for tria in [false, true] {
        let (g, u, _) = strip_tip(tria, |f, node, w| add(f, node, 3, &r, [0., m * w, 0.]));
        for (dir, k) in [(along, 0), (across, 1)] {
            for c in &g.cells {
                let d = Grid::dofs(c);
                let ue: Vec<f64> = d.iter().map(|&i| u[i]).collect();
                let dir = [dir[0], dir[1], dir[2]];
                let s = coque3d::sigm_elno(&g.xyz(c), &mat, &sec, &ue, dir).unwrap();
                assert_eq!(s.len(), c.len());
                for node in &s {
                    assert_eq!(node.len(), 3);
                    for (lvl, want) in [-s0, 0., s0].iter().enumerate() {
                        for comp in 0..6 {
                            let w = if comp == k { *want } else { 0. };
                            assert!(
                                (node[lvl][comp] - w).abs() <= 1e-7 * s0,
                                "{k} {lvl} {comp}: {:?}",
                                node[lvl]
                            );
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn efforts_of_the_strip_are_the_beams_resultants() {
    // End moment M and tension N on the tilted strip: EFGE_ELGA at every
    // normal point and EFGE_ELNO at every node are NXX = N/b, MXX = M/b
    // along the strip (NYY, MYY with the user's x across it), the rest 0,
    // with one layer and with three (Simpson per layer is exact through the
    // thickness of this linear stress); so is MECA_STATIQUE's EFGE_ELNO
    // (`ef0410`, from the reduced points, the layers ignored).
    let (b, h, m, n) = (0.5, 0.05, 1e3, 1e6);
    let r = tilted();
    let mat = Elastic::new(2e11, 0.).unwrap();
    let along = r * Vector3::new(1., 0., 0.3);
    let across = r * Vector3::new(0., 1., -0.2);
    for tria in [false, true] {
        let (g, u, _) = strip_tip(tria, |f, node, w| {
            add(f, node, 3, &r, [0., m * w, 0.]);
            add(f, node, 0, &r, [n * w, 0., 0.]);
        });
        for layers in [1, 3] {
            let sec = Coque3dSection {
                layers,
                ..Coque3dSection::new(h)
            };
            for (dir, k) in [(along, 0), (across, 1)] {
                let mut want = [0.; 8];
                want[k] = n / b;
                want[3 + k] = m / b;
                let dir = [dir[0], dir[1], dir[2]];
                for c in &g.cells {
                    let ue: Vec<f64> = Grid::dofs(c).iter().map(|&i| u[i]).collect();
                    let xyz = g.xyz(c);
                    let elga = coque3d::efge_elga(&xyz, &mat, &sec, &ue, dir).unwrap();
                    let elno = coque3d::efge_elno(&xyz, &mat, &sec, &ue, dir).unwrap();
                    let linear = coque3d::efge_elno_linear(&xyz, &mat, &sec, &ue, dir).unwrap();
                    assert_eq!(elga.len(), if tria { 7 } else { 9 });
                    assert_eq!(elno.len(), c.len());
                    assert_eq!(linear.len(), c.len());
                    for e in elga.iter().chain(&elno).chain(&linear) {
                        for comp in 0..8 {
                            let scale = if comp < 3 { n / b } else { m / b };
                            assert!(
                                (e[comp] - want[comp]).abs() <= 1e-8 * scale,
                                "{tria} {layers} {k} {comp}: {e:?}"
                            );
                        }
                    }
                }
            }
        }
    }
}

/// A TRIA7 cut from a cylinder of radius `radius` (axis z) and tilted:
/// corners at (θ, z) = (0, 0), (0.5, 0), (0, 0.5), the mid-side nodes on
/// the cylinder (off the straight midpoints of the chords).
fn curved_tria(radius: f64, r: &Matrix3<f64>) -> Vec<[f64; 3]> {
    let tz: [[f64; 2]; 6] = [
        [0., 0.],
        [0.5, 0.],
        [0., 0.5],
        [0.25, 0.],
        [0.25, 0.25],
        [0., 0.25],
    ];
    tz.iter()
        .map(|&[t, z]| {
            let p = r * Vector3::new(radius * t.cos(), radius * t.sin(), z);
            [p[0], p[1], p[2]]
        })
        .collect()
}

fn stiffness_with(
    xyz: &[[f64; 3]],
    h: f64,
    layers: u32,
    rule: coque3d::ThicknessRule,
) -> DVector<f64> {
    let mat = Elastic::new(2e11, 0.3).unwrap();
    let sec = Coque3dSection {
        layers,
        rule,
        ..Coque3dSection::new(h)
    };
    DVector::from_vec(coque3d::stiffness(xyz, &mat, &sec).unwrap())
}

/// MECA_STATIQUE's rule (`vdxrig`: two Gauss points through the
/// thickness) against the non-linear commands' (`vdxnlr`: Simpson). On a
/// flat cell both integrate the (quadratic in ξ₃) integrand exactly; on a
/// curved one the Jacobian varies through the thickness, and the error
/// terms of the two rules on [−1, 1] are E_S = −f⁗/90 and E_G = +f⁗/135:
/// against the integral (Simpson on 64 layers), K_G − K ≈ −2/3 (K_S − K).
#[test]
fn tria7_thickness_rules_of_meca_statique_and_stat_non_line() {
    use coque3d::ThicknessRule::{Gauss2, Simpson};
    let r = tilted();
    let h = 0.2;
    let flat = distorted_tria(&r);
    let (s, g) = (
        stiffness_with(&flat, h, 1, Simpson),
        stiffness_with(&flat, h, 1, Gauss2),
    );
    assert!(
        (&s - &g).amax() < 1e-9 * s.amax(),
        "flat: {}",
        (&s - &g).amax() / s.amax()
    );
    // vdxrig ignores COQUE_NCOU.
    let g3 = stiffness_with(&flat, h, 3, Gauss2);
    assert!((&g3 - &g).amax() < 1e-12 * g.amax());

    let curved = curved_tria(1., &r);
    let exact = stiffness_with(&curved, h, 64, Simpson);
    let ds = stiffness_with(&curved, h, 1, Simpson) - &exact;
    let dg = stiffness_with(&curved, h, 1, Gauss2) - &exact;
    // The rules differ well above round-off on the curved cell …
    assert!(
        ds.amax() > 1e-7 * exact.amax(),
        "{}",
        ds.amax() / exact.amax()
    );
    // … by their error terms' ratio.
    let ratio = dg.dot(&ds) / ds.dot(&ds);
    assert!((ratio + 2. / 3.).abs() < 0.01, "ratio {ratio}");
    assert!((&dg + &ds * (2. / 3.)).norm() < 0.01 * ds.norm());
}
