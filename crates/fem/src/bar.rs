//! Straight truss (bar): code_aster's `BARRE` modelisation on SEG2
//! (`MECA_BARRE`), two nodes with DX DY DZ, an axial stiffness only,
//! linear elastic, small displacements.
//!
//! What it computes, following code_aster's `te0153` (stiffness, mass) and
//! `te0154`/`te0185` (efforts):
//! - the stiffness EA/L on the axial direction n = (x₂ − x₁)/L:
//!   K = EA/L·[n nᵀ, −n nᵀ; −n nᵀ, n nᵀ] (no stiffness across the bar:
//!   its nodes need another element or a condition there);
//! - the consistent mass (`MASS_MECA`) ρAL/6·[2I, I; I, 2I] on the three
//!   translations, the lumped one (`MASS_MECA_DIAG`) ρAL/2 on each;
//! - the normal force N = EA/L·n·(u₂ − u₁), constant along the bar
//!   (`SIEF_ELGA` at its one Gauss point, `EFGE_ELNO` at both nodes).
//!
//! Numerics only: the runner maps `AFFE_MODELE/MODELISATION='BARRE'` and
//! `AFFE_CARA_ELEM/BARRE` (the area A) onto
//! [`crate::model::ElementKind::Bar`].

use crate::material::Elastic;
use nalgebra::DMatrix;

/// Axis n and length L of a bar from node `a` to node `b`.
pub fn axis(a: [f64; 3], b: [f64; 3]) -> Result<([f64; 3], f64), String> {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if !(len > 0. && len.is_finite()) {
        return Err("the bar has zero length: its axis is undefined".into());
    }
    Ok(([d[0] / len, d[1] / len, d[2] / len], len))
}

/// Checks the cross-section area.
pub fn check_area(area: f64) -> Result<(), String> {
    if area.is_finite() && area > 0. {
        Ok(())
    } else {
        Err(format!("bar section has A = {area}: it must be positive"))
    }
}

/// The 6×6 global stiffness, node-major DX DY DZ.
pub fn stiffness(
    xyz: &[[f64; 3]; 2],
    material: &Elastic,
    area: f64,
) -> Result<DMatrix<f64>, String> {
    check_area(area)?;
    let (n, len) = axis(xyz[0], xyz[1])?;
    let k = material.e * area / len;
    let mut m = DMatrix::zeros(6, 6);
    for i in 0..3 {
        for j in 0..3 {
            let v = k * n[i] * n[j];
            m[(i, j)] = v;
            m[(3 + i, 3 + j)] = v;
            m[(i, 3 + j)] = -v;
            m[(3 + i, j)] = -v;
        }
    }
    Ok(m)
}

/// The 6×6 mass of a bar of density `rho` (`te0153`): consistent or
/// lumped; isotropic in the three translations, so frame-free.
pub fn mass(
    xyz: &[[f64; 3]; 2],
    rho: f64,
    area: f64,
    lumped: bool,
) -> Result<DMatrix<f64>, String> {
    check_area(area)?;
    let (_, len) = axis(xyz[0], xyz[1])?;
    let total = rho * area * len;
    let mut m = DMatrix::zeros(6, 6);
    for i in 0..3 {
        if lumped {
            m[(i, i)] = total / 2.;
            m[(3 + i, 3 + i)] = total / 2.;
        } else {
            m[(i, i)] = total / 3.;
            m[(3 + i, 3 + i)] = total / 3.;
            m[(i, 3 + i)] = total / 6.;
            m[(3 + i, i)] = total / 6.;
        }
    }
    Ok(m)
}

/// The normal force N of a bar from its global displacements `ue`
/// (node-major DX DY DZ): EA/L·n·(u₂ − u₁), positive in tension.
pub fn normal_force(
    xyz: &[[f64; 3]; 2],
    material: &Elastic,
    area: f64,
    ue: &[f64],
) -> Result<f64, String> {
    if ue.len() != 6 {
        return Err(format!("a bar has 6 DOFs, got {}", ue.len()));
    }
    check_area(area)?;
    let (n, len) = axis(xyz[0], xyz[1])?;
    let elong: f64 = (0..3).map(|i| n[i] * (ue[3 + i] - ue[i])).sum();
    Ok(material.e * area / len * elong)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_inclined_bar_carries_its_axial_force_only() {
        let m = Elastic::new(2e11, 0.3).unwrap();
        let xyz = [[0., 0., 0.], [3., 4., 0.]];
        let k = stiffness(&xyz, &m, 1e-4).unwrap();
        // Stretching along the axis by δ: N = EAδ/L, the nodal forces ±N n.
        let d = 1e-3;
        let ue = [0., 0., 0., 0.6 * d, 0.8 * d, 0.];
        let f = &k * nalgebra::DVector::from_column_slice(&ue);
        let n = normal_force(&xyz, &m, 1e-4, &ue).unwrap();
        assert!((n - 2e11 * 1e-4 * d / 5.).abs() < 1e-9 * n);
        assert!((f[3] - 0.6 * n).abs() < 1e-9 * n && (f[4] - 0.8 * n).abs() < 1e-9 * n);
        // A move across the axis costs nothing.
        let across = [0., 0., 0., -0.8, 0.6, 1.];
        let g = &k * nalgebra::DVector::from_column_slice(&across);
        assert!(g.amax() < 1e-6);
        assert!(normal_force(&xyz, &m, 1e-4, &across).unwrap().abs() < 1e-6);
        // The mass of a translation is ρAL, consistent or lumped.
        for lumped in [false, true] {
            let mm = mass(&xyz, 7800., 1e-4, lumped).unwrap();
            let v = nalgebra::DVector::from_column_slice(&[1., 0., 0., 1., 0., 0.]);
            let e = (v.transpose() * &mm * &v)[(0, 0)];
            assert!((e - 7800. * 1e-4 * 5.).abs() < 1e-12);
        }
        assert!(stiffness(&[[0.; 3], [0.; 3]], &m, 1.).is_err());
        assert!(stiffness(&xyz, &m, 0.).is_err());
    }
}
