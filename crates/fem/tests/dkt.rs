//! code_aster's DKT thin shells, the triangle (`aster_fem::dkt`) and the
//! quadrangle (`aster_fem::dkq`), against closed-form
//! plate and beam answers: rigid motions, the constant-curvature patch
//! test, a cantilever strip under an end moment and an end tension (exact
//! for DKT), a cantilever strip under an end shear force (Euler–Bernoulli
//! P·L³/(3EI)), a simply supported square plate under a central force
//! (Timoshenko's 0.01160·P·a²/D), all with the strip or plate rotated
//! arbitrarily in space.
#![allow(clippy::needless_range_loop)]

mod common;

use aster_fem::dkq::{self, Quad};
use aster_fem::dkt::{self, Facet, ShellSection};
use aster_fem::Elastic;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// A rotation of space (unit axis, angle).
fn rotation(axis: [f64; 3], angle: f64) -> Matrix3<f64> {
    let a = Vector3::from(axis).normalize();
    *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(a), angle).matrix()
}

/// A flat mesh of DKT triangles or quadrangles: nodes (global
/// coordinates) and connectivity.
struct Plate {
    nodes: Vec<[f64; 3]>,
    cells: Vec<Vec<usize>>,
}

/// Moments (MXX MYY MXY) at a Gauss point, and the shears where computed.
type MomentsAndShear = ([f64; 3], Option<[f64; 2]>);

/// Which facets a grid is made of.
#[derive(Clone, Copy, Debug)]
enum Cells {
    Tria,
    Quad,
}

impl Plate {
    /// nx × ny rectangles on [0, lx] × [0, ly] (z = 0), mapped by `r`:
    /// quadrangles, or each cut in two along alternating diagonals.
    fn grid(lx: f64, ly: f64, nx: usize, ny: usize, r: &Matrix3<f64>, cells: Cells) -> Plate {
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut nodes = Vec::new();
        for j in 0..=ny {
            for i in 0..=nx {
                let p = Vector3::new(lx * i as f64 / nx as f64, ly * j as f64 / ny as f64, 0.);
                let q = r * p;
                nodes.push([q[0], q[1], q[2]]);
            }
        }
        let mut conn = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                match cells {
                    Cells::Quad => conn.push(vec![a, b, c, d]),
                    Cells::Tria if (i + j) % 2 == 0 => {
                        conn.push(vec![a, b, c]);
                        conn.push(vec![a, c, d]);
                    }
                    Cells::Tria => {
                        conn.push(vec![a, b, d]);
                        conn.push(vec![b, c, d]);
                    }
                }
            }
        }
        Plate { nodes, cells: conn }
    }

    fn element_stiffness(&self, c: &[usize], mat: &Elastic, sec: &ShellSection) -> DMatrix<f64> {
        let x = |i: usize| self.nodes[c[i]];
        match c.len() {
            3 => dkt::stiffness(&[x(0), x(1), x(2)], mat, sec).unwrap(),
            _ => dkq::stiffness(&[x(0), x(1), x(2), x(3)], mat, sec).unwrap(),
        }
    }

    fn stiffness(&self, mat: &Elastic, sec: &ShellSection) -> DMatrix<f64> {
        let n = 6 * self.nodes.len();
        let mut k = DMatrix::zeros(n, n);
        for c in &self.cells {
            let ke = self.element_stiffness(c, mat, sec);
            for a in 0..ke.nrows() {
                for b in 0..ke.nrows() {
                    k[(6 * c[a / 6] + a % 6, 6 * c[b / 6] + b % 6)] += ke[(a, b)];
                }
            }
        }
        k
    }

    /// Moment tensors (strip axes, x along the strip) at the Gauss points
    /// of every element, with the transverse shears where computed.
    fn moments(
        &self,
        u: &DVector<f64>,
        mat: &Elastic,
        sec: &ShellSection,
        r: &Matrix3<f64>,
    ) -> Vec<(nalgebra::Matrix2<f64>, Option<[f64; 2]>)> {
        let mut out = Vec::new();
        for c in &self.cells {
            let x = |i: usize| self.nodes[c[i]];
            let ue: Vec<f64> = (0..6 * c.len()).map(|a| u[dof(c[a / 6], a % 6)]).collect();
            let (pgl, ef): (Matrix3<f64>, Vec<MomentsAndShear>) = match c.len() {
                3 => {
                    let xyz = [x(0), x(1), x(2)];
                    let ue: [f64; 18] = ue.try_into().unwrap();
                    let ef = dkt::efforts(&xyz, mat, sec, &ue).unwrap();
                    let pgl = Facet::new(&xyz).unwrap().pgl;
                    (
                        pgl,
                        ef.iter()
                            .map(|g| ([g[3], g[4], g[5]], Some([g[6], g[7]])))
                            .collect(),
                    )
                }
                _ => {
                    let xyz = [x(0), x(1), x(2), x(3)];
                    let ue: [f64; 24] = ue.try_into().unwrap();
                    let ef = dkq::efforts(&xyz, mat, sec, &ue).unwrap();
                    let pgl = Quad::new(&xyz).unwrap().pgl;
                    (pgl, ef.iter().map(|g| ([g[3], g[4], g[5]], None)).collect())
                }
            };
            // strip axes → facet axes; both normals coincide.
            let q = pgl * r;
            let q2 = q.fixed_view::<2, 2>(0, 0).into_owned();
            for (m, shear) in ef {
                let mf = nalgebra::Matrix2::new(m[0], m[2], m[2], m[1]);
                out.push((q2.transpose() * mf * q2, shear));
            }
        }
        out
    }

    /// Solves K u = f with the DOFs of `fixed` set to zero.
    fn solve(&self, k: &DMatrix<f64>, f: &DVector<f64>, fixed: &[usize]) -> DVector<f64> {
        common::solve_held(k, f, fixed)
    }
}

/// Global DOF of node `n`, component `c` (0..6: DX DY DZ DRX DRY DRZ).
fn dof(n: usize, c: usize) -> usize {
    6 * n + c
}

/// Adds the global vector `r·v` to the translation (c0 = 0) or rotation
/// (c0 = 3) triple of node `n`.
fn add(f: &mut DVector<f64>, n: usize, c0: usize, r: &Matrix3<f64>, v: [f64; 3]) {
    let g = r * Vector3::from(v);
    for i in 0..3 {
        f[dof(n, c0 + i)] += g[i];
    }
}

/// The local (x, y, z) components of a node's translation or rotation.
fn local(u: &DVector<f64>, n: usize, c0: usize, r: &Matrix3<f64>) -> Vector3<f64> {
    r.transpose() * Vector3::new(u[dof(n, c0)], u[dof(n, c0 + 1)], u[dof(n, c0 + 2)])
}

fn tilted() -> Matrix3<f64> {
    rotation([0.3, -0.7, 0.65], 0.9)
}

#[test]
fn rigid_motions_are_stress_free() {
    let mat = Elastic::new(2.1e11, 0.3).unwrap();
    let sec = ShellSection {
        thickness: 0.02,
        drilling: 0.,
        rotary_inertia: false,
        layered: None,
        offset: 0.,
    };
    let xyz = [[0.1, 0.2, -0.3], [1.3, 0.4, 0.2], [0.5, 1.1, 0.6]];
    let k = dkt::stiffness(&xyz, &mat, &sec).unwrap();
    let scale = k.amax();
    for mode in 0..6 {
        let mut u = DVector::zeros(18);
        for n in 0..3 {
            let x = Vector3::from(xyz[n]);
            let (t, w) = if mode < 3 {
                let mut t = Vector3::zeros();
                t[mode] = 1.;
                (t, Vector3::zeros())
            } else {
                let mut w = Vector3::zeros();
                w[mode - 3] = 1.;
                (w.cross(&x), w)
            };
            for i in 0..3 {
                u[6 * n + i] = t[i];
                u[6 * n + 3 + i] = w[i];
            }
        }
        let f = &k * &u;
        assert!(f.amax() < 1e-9 * scale, "mode {mode}: |K·u| = {}", f.amax());
    }
    // Symmetric and positive semi-definite: without the drilling spring,
    // nine zero eigenvalues (six rigid motions, three free DRZ); with it,
    // six (the rotation about the normal stays free only with DRZ = 0).
    assert!((&k - k.transpose()).amax() < 1e-12 * scale);
    for (drilling, zeros) in [(0., 9), (1e-5, 6)] {
        let sec = ShellSection {
            thickness: 0.02,
            drilling,
            rotary_inertia: false,
            layered: None,
            offset: 0.,
        };
        let k = dkt::stiffness(&xyz, &mat, &sec).unwrap();
        let eig = k.symmetric_eigen().eigenvalues;
        let zero = eig.iter().filter(|&&l| l.abs() < 1e-12 * scale).count();
        assert_eq!(zero, zeros, "drilling {drilling}: eigenvalues {eig}");
        assert!(eig.iter().all(|&l| l > -1e-12 * scale));
    }
}

#[test]
fn drilling_spring_is_code_aster_fraction_of_the_bending_rotations() {
    let mat = Elastic::new(2.0e11, 0.3).unwrap();
    let xyz = [[0., 0., 0.], [2., 0., 0.], [0.5, 1.5, 0.]];
    let off = dkt::stiffness(
        &xyz,
        &mat,
        &ShellSection {
            thickness: 0.1,
            drilling: 0.,
            rotary_inertia: false,
            layered: None,
            offset: 0.,
        },
    )
    .unwrap();
    let on = dkt::stiffness(&xyz, &mat, &ShellSection::new(0.1)).unwrap();
    // The facet lies in the global xy plane with x along node 1 → 2: local
    // and global axes coincide, DRZ is the drilling rotation.
    let min = (0..3)
        .flat_map(|n| [off[(6 * n + 3, 6 * n + 3)], off[(6 * n + 4, 6 * n + 4)]])
        .fold(f64::INFINITY, f64::min);
    for n in 0..3 {
        let d = 6 * n + 5;
        assert_eq!(off[(d, d)], 0.);
        assert!((on[(d, d)] - 1e-5 * min).abs() <= 1e-15 * min);
    }
    assert!((&on - &off).amax() <= 1e-5 * min * (1. + 1e-12));
}

#[test]
fn constant_curvature_is_reproduced_exactly() {
    // w = a x² + b x y + c y² in the facet's frame: curvatures
    // (βx,x, βy,y, βx,y + βy,x) = (−2a, −2c, −2b) at every point, moments
    // Df·κ, no transverse shear, no membrane effort.
    let (e, nu, h) = (7.0e10, 0.25, 0.05);
    let mat = Elastic::new(e, nu).unwrap();
    let sec = ShellSection::new(h);
    let (a, b, c) = (0.3, -0.2, 0.45);
    let r = tilted();
    let local_xy = [[0., 0.], [1.7, 0.], [0.4, 1.2]];
    let mut xyz = [[0.; 3]; 3];
    let mut u = [0.; 18];
    for n in 0..3 {
        let [x, y] = local_xy[n];
        let g = r * Vector3::new(x, y, 0.);
        xyz[n] = [g[0], g[1], g[2]];
        let w = a * x * x + b * x * y + c * y * y;
        // θx = w,y, θy = −w,x (β = −∇w, βx = θy, βy = −θx).
        let (wx, wy) = (2. * a * x + b * y, b * x + 2. * c * y);
        let t = r * Vector3::new(0., 0., w);
        let th = r * Vector3::new(wy, -wx, 0.);
        for i in 0..3 {
            u[6 * n + i] = t[i];
            u[6 * n + 3 + i] = th[i];
        }
    }
    let facet = Facet::new(&xyz).unwrap();
    assert!(
        (facet.pgl - r.transpose()).amax() < 1e-12,
        "frame {}",
        facet.pgl
    );
    let d = e * h.powi(3) / (12. * (1. - nu * nu));
    let kappa = [-2. * a, -2. * c, -2. * b];
    let m = [
        d * (kappa[0] + nu * kappa[1]),
        d * (nu * kappa[0] + kappa[1]),
        d * (1. - nu) / 2. * kappa[2],
    ];
    let ef = dkt::efforts(&xyz, &mat, &sec, &u).unwrap();
    assert_eq!(ef.len(), 3);
    let scale = m.iter().fold(0f64, |s, v| s.max(v.abs()));
    for g in &ef {
        for i in 0..3 {
            assert!(g[i].abs() < 1e-9 * scale, "membrane {g:?}");
            assert!(
                (g[3 + i] - m[i]).abs() < 1e-9 * scale,
                "moment {i}: {g:?} vs {m:?}"
            );
        }
        assert!(
            g[6].abs() < 1e-9 * scale && g[7].abs() < 1e-9 * scale,
            "shear {g:?}"
        );
    }
}

/// Cantilever strip L × b, clamped at x = 0 (every DOF), ν = 0 so that the
/// strip bends as a beam of inertia b·h³/12.
struct Strip {
    plate: Plate,
    r: Matrix3<f64>,
    nx: usize,
    ny: usize,
    l: f64,
    b: f64,
    h: f64,
    e: f64,
}

impl Strip {
    fn new(nx: usize, ny: usize, cells: Cells) -> Strip {
        let (l, b) = (2.0, 0.4);
        let r = tilted();
        Strip {
            plate: Plate::grid(l, b, nx, ny, &r, cells),
            r,
            nx,
            ny,
            l,
            b,
            h: 0.02,
            e: 2.0e11,
        }
    }

    fn tip_nodes(&self) -> Vec<usize> {
        (0..=self.ny).map(|j| j * (self.nx + 1) + self.nx).collect()
    }

    fn clamped(&self) -> Vec<usize> {
        (0..=self.ny)
            .flat_map(|j| (0..6).map(move |c| (j, c)))
            .map(|(j, c)| dof(j * (self.nx + 1), c))
            .collect()
    }

    /// Solves with `load(f)` filling the global force vector.
    fn solve(&self, load: impl Fn(&mut DVector<f64>)) -> DVector<f64> {
        let mat = Elastic::new(self.e, 0.).unwrap();
        let k = self.plate.stiffness(&mat, &ShellSection::new(self.h));
        let mut f = DVector::zeros(k.nrows());
        load(&mut f);
        self.plate.solve(&k, &f, &self.clamped())
    }

    /// Nodal weights of a uniform edge load on the tip edge (trapezoid).
    fn edge_weights(&self) -> Vec<f64> {
        let n = self.ny;
        (0..=n)
            .map(|j| if j == 0 || j == n { 0.5 } else { 1. } / n as f64)
            .collect()
    }
}

#[test]
fn cantilever_strip_under_end_moment_is_exact() {
    // Moment M about the local y axis at the tip: w(L) = −M·L²/(2EI),
    // θy(L) = M·L/(EI), and Mxx = M/b everywhere (DKT and DKQ pass the
    // constant-curvature patch test, so the answer is exact on any mesh).
    for cells in [Cells::Tria, Cells::Quad] {
        let s = Strip::new(6, 2, cells);
        let moment = 150.;
        let u = s.solve(|f| {
            for (n, w) in s.tip_nodes().into_iter().zip(s.edge_weights()) {
                add(f, n, 3, &s.r, [0., moment * w, 0.]);
            }
        });
        let ei = s.e * s.b * s.h.powi(3) / 12.;
        let w_ref = -moment * s.l * s.l / (2. * ei);
        for n in s.tip_nodes() {
            let t = local(&u, n, 0, &s.r);
            let th = local(&u, n, 3, &s.r);
            assert!(
                (t[2] - w_ref).abs() < 1e-9 * w_ref.abs(),
                "{cells:?}: w {} vs {w_ref}",
                t[2]
            );
            assert!(
                (th[1] - moment * s.l / ei).abs() < 1e-9 * th[1].abs(),
                "{cells:?}"
            );
            assert!(t[0].abs() < 1e-9 * w_ref.abs() && t[1].abs() < 1e-9 * w_ref.abs());
        }
        let mat = Elastic::new(s.e, 0.).unwrap();
        let m_ref = moment / s.b;
        for (ms, shear) in s.plate.moments(&u, &mat, &ShellSection::new(s.h), &s.r) {
            assert!(
                (ms[(0, 0)] - m_ref).abs() < 1e-8 * m_ref,
                "{cells:?}: Mxx {ms}"
            );
            assert!(ms[(1, 1)].abs() < 1e-8 * m_ref && ms[(0, 1)].abs() < 1e-8 * m_ref);
            if let Some(q) = shear {
                assert!(
                    q[0].abs() < 1e-8 * m_ref && q[1].abs() < 1e-8 * m_ref,
                    "{q:?}"
                );
            }
        }
    }
}

#[test]
fn cantilever_strip_under_end_tension_is_exact() {
    // Membrane: u(L) = N·L/(E·b·h) (ν = 0: a uniform strain, which both
    // the constant-strain triangle and the bilinear quadrangle represent).
    for cells in [Cells::Tria, Cells::Quad] {
        let s = Strip::new(5, 3, cells);
        let force = 4.0e4;
        let u = s.solve(|f| {
            for (n, w) in s.tip_nodes().into_iter().zip(s.edge_weights()) {
                add(f, n, 0, &s.r, [force * w, 0., 0.]);
            }
        });
        let u_ref = force * s.l / (s.e * s.b * s.h);
        for n in s.tip_nodes() {
            let t = local(&u, n, 0, &s.r);
            assert!(
                (t[0] - u_ref).abs() < 1e-9 * u_ref,
                "{cells:?}: u {} vs {u_ref}",
                t[0]
            );
            assert!(t[1].abs() < 1e-9 * u_ref && t[2].abs() < 1e-9 * u_ref);
        }
    }
}

/// Relative error of the tip deflection of a strip under an end force,
/// on nx × ny meshes (largest over the tip nodes, signed).
fn end_shear_errors(cells: Cells, meshes: &[(usize, usize)]) -> Vec<f64> {
    meshes
        .iter()
        .map(|&(nx, ny)| {
            let s = Strip::new(nx, ny, cells);
            let p = 300.;
            let u = s.solve(|f| {
                for (n, w) in s.tip_nodes().into_iter().zip(s.edge_weights()) {
                    add(f, n, 0, &s.r, [0., 0., p * w]);
                }
            });
            let ei = s.e * s.b * s.h.powi(3) / 12.;
            let w_ref = p * s.l.powi(3) / (3. * ei);
            s.tip_nodes()
                .iter()
                .map(|&n| (local(&u, n, 0, &s.r)[2] - w_ref) / w_ref)
                .fold(0f64, |m, e| if e.abs() > m.abs() { e } else { m })
        })
        .collect()
}

#[test]
fn cantilever_strip_under_end_shear_converges_to_euler_bernoulli() {
    // End force P: w(L) = P·L³/(3EI) (ν = 0, no shear deformation in a
    // Kirchhoff element). On triangles the discrete Kirchhoff constraints
    // hold at points only: the tip deflection converges at second order,
    // from above (measured 2.6e-3, 5.9e-4, 1.5e-4; 3.7e-5 on 40 × 8). On
    // rectangles DKQ represents the cubic deflection: exact on any mesh
    // (measured ≤ 3e-10, the dense solve's round-off).
    let meshes = [(5usize, 1usize), (10, 2), (20, 4)];
    let errors = end_shear_errors(Cells::Tria, &meshes);
    eprintln!("Tria end shear: relative errors {errors:?}");
    assert!(errors.iter().all(|&e| e > 0.), "{errors:?}");
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((3.5..4.6).contains(&ratio), "order: {errors:?}");
    }
    assert!(errors[2] < 2e-4, "{errors:?}");
    let errors = end_shear_errors(Cells::Quad, &meshes);
    eprintln!("Quad end shear: relative errors {errors:?}");
    assert!(errors.iter().all(|e| e.abs() < 1e-8), "{errors:?}");
}

#[test]
fn simply_supported_square_plate_under_central_force() {
    // Timoshenko & Woinowsky-Krieger, table 23: w = 0.01160·P·a²/D at the
    // centre of a simply supported square plate (ν = 0.3), Kirchhoff
    // theory; DKT and DKQ converge to it as the mesh is refined (soft
    // support: w = 0 on the edges, rotations free).
    let (a, h, e, nu): (f64, f64, f64, f64) = (1.0, 0.01, 2.0e11, 0.3);
    let d = e * h.powi(3) / (12. * (1. - nu * nu));
    let p = 1000.;
    let w_ref = 0.01160 * p * a * a / d;
    let r = tilted();
    for cells in [Cells::Tria, Cells::Quad] {
        let mut errors = Vec::new();
        for n in [4usize, 8, 16] {
            let plate = Plate::grid(a, a, n, n, &r, cells);
            let mat = Elastic::new(e, nu).unwrap();
            let k = plate.stiffness(&mat, &ShellSection::new(h));
            let id = |i: usize, j: usize| j * (n + 1) + i;
            let mut fixed = Vec::new();
            for j in 0..=n {
                for i in 0..=n {
                    if i == 0 || j == 0 || i == n || j == n {
                        // w = 0 on the edges; the in-plane translations too,
                        // to remove the membrane rigid motions (membrane and
                        // bending are uncoupled here).
                        for c in 0..3 {
                            fixed.push(dof(id(i, j), c));
                        }
                    }
                }
            }
            let mut f = DVector::zeros(k.nrows());
            let centre = id(n / 2, n / 2);
            add(&mut f, centre, 0, &r, [0., 0., p]);
            let u = plate.solve(&k, &f, &fixed);
            let w = local(&u, centre, 0, &r)[2];
            errors.push((w - w_ref) / w_ref);
        }
        eprintln!("{cells:?} simply supported plate: relative errors {errors:?}");
        // Measured: triangles 2.97 %, 1.05 %, 0.36 %; quadrangles 9.4 %,
        // 2.9 %, 0.87 %, both from above (the reference has 4 digits).
        assert!(errors.iter().all(|&e| e > 0.), "{cells:?}: {errors:?}");
        for pair in errors.windows(2) {
            assert!(pair[0] / pair[1] > 2.5, "{cells:?} order: {errors:?}");
        }
        let tolerance = match cells {
            Cells::Tria => 5e-3,
            Cells::Quad => 1e-2,
        };
        assert!(errors[2] < tolerance, "{cells:?}: {errors:?}");
    }
}

#[test]
fn degenerate_triangle_is_an_error() {
    let mat = Elastic::new(2.0e11, 0.3).unwrap();
    let xyz = [[0., 0., 0.], [1., 1., 1.], [2., 2., 2.]];
    let err = dkt::stiffness(&xyz, &mat, &ShellSection::new(0.1)).unwrap_err();
    assert!(err.contains("degenerate"), "{err}");
}

/// A distorted, slightly skewed quadrangle in the local plane, and the
/// same placed in space by `r`.
fn distorted_quad(r: &Matrix3<f64>) -> ([[f64; 2]; 4], [[f64; 3]; 4]) {
    let xy = [[0., 0.], [1.6, 0.2], [1.9, 1.4], [0.3, 1.1]];
    let mut xyz = [[0.; 3]; 4];
    for n in 0..4 {
        let g = r * Vector3::new(xy[n][0], xy[n][1], 0.);
        xyz[n] = [g[0], g[1], g[2]];
    }
    (xy, xyz)
}

#[test]
fn quadrangle_rigid_motions_are_stress_free() {
    let mat = Elastic::new(2.1e11, 0.3).unwrap();
    let (_, xyz) = distorted_quad(&tilted());
    let scale = dkq::stiffness(&xyz, &mat, &ShellSection::new(0.02))
        .unwrap()
        .amax();
    for (drilling, zeros) in [(0., 10), (1e-5, 6)] {
        let sec = ShellSection {
            thickness: 0.02,
            drilling,
            rotary_inertia: false,
            layered: None,
            offset: 0.,
        };
        let k = dkq::stiffness(&xyz, &mat, &sec).unwrap();
        assert!((&k - k.transpose()).amax() < 1e-12 * scale);
        // Rigid motions (checked without the spring, which resists the
        // rotation about the normal).
        for mode in (0..6).filter(|_| drilling == 0.) {
            let mut u = DVector::zeros(24);
            for n in 0..4 {
                let x = Vector3::from(xyz[n]);
                let (t, w) = if mode < 3 {
                    let mut t = Vector3::zeros();
                    t[mode] = 1.;
                    (t, Vector3::zeros())
                } else {
                    let mut w = Vector3::zeros();
                    w[mode - 3] = 1.;
                    (w.cross(&x), w)
                };
                for i in 0..3 {
                    u[6 * n + i] = t[i];
                    u[6 * n + 3 + i] = w[i];
                }
            }
            let f = &k * &u;
            assert!(f.amax() < 1e-9 * scale, "mode {mode}: |K·u| = {}", f.amax());
        }
        // Without the spring: six rigid motions and four free DRZ.
        let eig = k.symmetric_eigen().eigenvalues;
        let zero = eig.iter().filter(|&&l| l.abs() < 1e-12 * scale).count();
        assert_eq!(zero, zeros, "drilling {drilling}: eigenvalues {eig}");
        assert!(eig.iter().all(|&l| l > -1e-12 * scale));
    }
}

#[test]
fn quadrangle_constant_curvature_and_membrane_strain_are_exact() {
    // On a distorted quadrangle: w = a x² + b x y + c y² gives the moments
    // Df·(−2a, −2c, −2b), and u = G·x the membrane efforts Dm·ε, at every
    // Gauss point.
    let (e, nu, h) = (7.0e10, 0.25, 0.05);
    let mat = Elastic::new(e, nu).unwrap();
    let sec = ShellSection::new(h);
    let (a, b, c) = (0.3, -0.2, 0.45);
    let g = [[1e-3, 4e-4], [-2e-4, 6e-4]];
    let r = tilted();
    let (xy, xyz) = distorted_quad(&r);
    let quad = Quad::new(&xyz).unwrap();
    assert!(quad.warping() < 1e-12);
    // Local frame of the facet in the plane's own axes (x from the middle
    // of side 4–1 to the middle of side 2–3).
    let q = quad.pgl * r;
    let mut u = [0.; 24];
    for n in 0..4 {
        let [x, y] = xy[n];
        let w = a * x * x + b * x * y + c * y * y;
        let (wx, wy) = (2. * a * x + b * y, b * x + 2. * c * y);
        let um = [g[0][0] * x + g[0][1] * y, g[1][0] * x + g[1][1] * y];
        let t = r * Vector3::new(um[0], um[1], w);
        let th = r * Vector3::new(wy, -wx, 0.);
        for i in 0..3 {
            u[6 * n + i] = t[i];
            u[6 * n + 3 + i] = th[i];
        }
    }
    let dm = e * h / (1. - nu * nu);
    let d = e * h.powi(3) / (12. * (1. - nu * nu));
    let tensor = |m: [f64; 3]| nalgebra::Matrix2::new(m[0], m[2], m[2], m[1]);
    // Plane-axes tensors, then in the facet's axes.
    let eps = [g[0][0], g[1][1], g[0][1] + g[1][0]];
    let n_plane = tensor([
        dm * (eps[0] + nu * eps[1]),
        dm * (nu * eps[0] + eps[1]),
        dm * (1. - nu) / 2. * eps[2],
    ]);
    let kappa = [-2. * a, -2. * c, -2. * b];
    let m_plane = tensor([
        d * (kappa[0] + nu * kappa[1]),
        d * (nu * kappa[0] + kappa[1]),
        d * (1. - nu) / 2. * kappa[2],
    ]);
    let q2 = q.fixed_view::<2, 2>(0, 0).into_owned();
    let n_ref = q2 * n_plane * q2.transpose();
    let m_ref = q2 * m_plane * q2.transpose();
    let ef = dkq::efforts(&xyz, &mat, &sec, &u).unwrap();
    assert_eq!(ef.len(), 4);
    for p in &ef {
        let n = tensor([p[0], p[1], p[2]]);
        let m = tensor([p[3], p[4], p[5]]);
        assert!((n - n_ref).amax() < 1e-9 * n_ref.amax(), "N {n} vs {n_ref}");
        assert!((m - m_ref).amax() < 1e-9 * m_ref.amax(), "M {m} vs {m_ref}");
    }
}

#[test]
fn quadrangle_errors_and_warping() {
    let mat = Elastic::new(2.0e11, 0.3).unwrap();
    let sec = ShellSection::new(0.1);
    let flat = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
    // A dart (node 3 re-entrant): negative Jacobian at a Gauss point.
    let dart = [[0., 0., 0.], [2., 0., 0.], [0.2, 0.2, 0.], [0., 2., 0.]];
    let err = dkq::stiffness(&dart, &mat, &sec).unwrap_err();
    assert!(err.contains("Jacobian"), "{err}");
    let line = [[0., 0., 0.], [1., 0., 0.], [2., 0., 0.], [3., 0., 0.]];
    let err = dkq::stiffness(&line, &mat, &sec).unwrap_err();
    assert!(err.contains("degenerate"), "{err}");
    let negative = ShellSection {
        thickness: 0.1,
        drilling: -1e-5,
        rotary_inertia: false,
        layered: None,
        offset: 0.,
    };
    let err = dkq::stiffness(&flat, &mat, &negative).unwrap_err();
    assert!(err.contains("COEF_RIGI_DRZ"), "{err}");
    // Node 4 lifted by 0.01 out of the plane of nodes 1–3: dxqpgl's
    // measure is the distance over |x₁₄|.
    let warped = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.01]];
    let quad = Quad::new(&warped).unwrap();
    let expected = 0.01 / (1f64 + 1e-4).sqrt();
    assert!(
        (quad.warping() - expected).abs() < 1e-12,
        "{}",
        quad.warping()
    );
    assert_eq!(Quad::new(&flat).unwrap().warping(), 0.);
}
