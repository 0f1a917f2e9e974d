//! The plane joint element of `MODELISATION='PLAN_JOINT'` on QUAD4
//! (`MFPLQU4`: `te0201` → `nmfi2d`, `nmfisa`; `FORC_NODA`: `te0202` →
//! `nmfifi`): a cell whose face 1-2 lies on one body and face 3-4 (node 4
//! facing node 1, node 3 facing node 2) on the other, as
//! `MODI_MAILLAGE/ORIE_FISSURE` numbers it.
//!
//! At each of its two Gauss points (code_aster's `FIS2`: the weights
//! c = (1 ± 1/√3)/2 on the face's two nodes), the displacement jump in the
//! frame of face 1-2 — the normal n = (Δy, −Δx)/L (the right-hand normal
//! of 1 → 2, pointing away from the other face for a counter-clockwise
//! cell) and the tangent t = (−n_y, n_x) — is
//!
//! ```text
//! δ = B u,  δ_n = n·(c u1 + (1−c) u2 − (1−c) u3 − c u4),  δ_t likewise with t
//! ```
//!
//! and the internal forces and tangent are `Σ_g (L/2) Bᵀ σ` and
//! `Σ_g (L/2) Bᵀ (∂σ/∂δ) B` (`L` the length of face 1-2; plane, per unit
//! thickness). The traction σ (`SIGN`, `SITX`) comes from a cohesive law
//! ([`crate::cohesive`]).

/// The two Gauss points' weights of node 1 (code_aster's `coef`).
pub fn gauss_coefficients() -> [f64; 2] {
    let r = 3f64.sqrt() / 3.0;
    [0.5 * (1.0 + r), 0.5 * (1.0 - r)]
}

/// The jump operator and the integration weight of Gauss point `kpg`
/// (0 or 1) of a joint QUAD4 whose corners are `geom` (code_aster's
/// `nmfisa`, plane case). Rows: normal, tangential jump; columns: DX, DY
/// of nodes 1 to 4.
pub fn jump_operator(geom: &[[f64; 2]; 4], kpg: usize) -> (f64, [[f64; 8]; 2]) {
    let coef = gauss_coefficients()[kpg];
    let dx = geom[1][0] - geom[0][0];
    let dy = geom[1][1] - geom[0][1];
    let aire = (dx * dx + dy * dy).sqrt();
    let poids = aire / 2.0;
    let (co, si) = (dy, -dx);
    let norm = (co * co + si * si).sqrt();
    let (c, s) = (co / norm, si / norm);
    let w = [coef, 1.0 - coef, -(1.0 - coef), -coef];
    let mut b = [[0.0; 8]; 2];
    for (a, wa) in w.iter().enumerate() {
        b[0][2 * a] = c * wa;
        b[0][2 * a + 1] = s * wa;
        b[1][2 * a] = -s * wa;
        b[1][2 * a + 1] = c * wa;
    }
    (poids, b)
}

/// The jumps (normal, tangential) at the two Gauss points for the element
/// displacements `u` (DX, DY of nodes 1 to 4).
pub fn jumps(geom: &[[f64; 2]; 4], u: &[f64; 8]) -> [[f64; 2]; 2] {
    let mut out = [[0.0; 2]; 2];
    for (kpg, o) in out.iter_mut().enumerate() {
        let (_, b) = jump_operator(geom, kpg);
        for q in 0..2 {
            o[q] = (0..8).map(|j| b[q][j] * u[j]).sum();
        }
    }
    out
}

/// Internal forces `Σ_g w Bᵀ σ_g` (code_aster's `nmfifi`).
pub fn forces(geom: &[[f64; 2]; 4], sigma: &[[f64; 2]; 2]) -> [f64; 8] {
    let mut f = [0.0; 8];
    for (kpg, s) in sigma.iter().enumerate() {
        let (w, b) = jump_operator(geom, kpg);
        for (i, fi) in f.iter_mut().enumerate() {
            *fi += w * (b[0][i] * s[0] + b[1][i] * s[1]);
        }
    }
    f
}

/// Tangent `Σ_g w Bᵀ D_g B` (code_aster's `nmfi2d`), row-major 8×8.
pub fn tangent(geom: &[[f64; 2]; 4], d: &[[[f64; 2]; 2]; 2]) -> [[f64; 8]; 8] {
    let mut k = [[0.0; 8]; 8];
    for (kpg, dg) in d.iter().enumerate() {
        let (w, b) = jump_operator(geom, kpg);
        for i in 0..8 {
            for j in 0..8 {
                let mut v = 0.0;
                for q in 0..2 {
                    for s in 0..2 {
                        v += b[q][i] * dg[q][s] * b[s][j];
                    }
                }
                k[i][j] += w * v;
            }
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A joint of length 2 along x, thickness 0.1, counter-clockwise from
    /// its lower face.
    const GEOM: [[f64; 2]; 4] = [[0.0, 0.0], [2.0, 0.0], [2.0, 0.1], [0.0, 0.1]];

    #[test]
    fn a_rigid_motion_has_no_jump_and_an_opening_is_a_positive_normal_jump() {
        let rigid = [0.3, -0.2, 0.3, -0.2, 0.3, -0.2, 0.3, -0.2];
        for j in jumps(&GEOM, &rigid) {
            assert!(j[0].abs() < 1e-15 && j[1].abs() < 1e-15);
        }
        // The upper face moved up by 1e-3 and along x by 2e-3.
        let open = [0.0, 0.0, 0.0, 0.0, 2e-3, 1e-3, 2e-3, 1e-3];
        for j in jumps(&GEOM, &open) {
            assert!((j[0] - 1e-3).abs() < 1e-15, "{j:?}");
            assert!((j[1].abs() - 2e-3).abs() < 1e-15, "{j:?}");
        }
    }

    #[test]
    fn a_uniform_traction_gives_its_resultant_on_each_face() {
        let f = forces(&GEOM, &[[5.0, 0.0], [5.0, 0.0]]);
        // Normal traction 5 on a face of length 2: 10 in all, 5 per node,
        // pulling the faces together (upper face down, lower face up).
        assert!((f[1] + 5.0).abs() < 1e-12 && (f[3] + 5.0).abs() < 1e-12, "{f:?}");
        assert!((f[5] - 5.0).abs() < 1e-12 && (f[7] - 5.0).abs() < 1e-12, "{f:?}");
    }

    #[test]
    fn the_tangent_is_the_derivative_of_the_forces_for_a_linear_law() {
        let d = [[[3.0, 0.5], [0.5, 2.0]], [[3.0, 0.5], [0.5, 2.0]]];
        let k = tangent(&GEOM, &d);
        let u = [0.1, 0.2, -0.3, 0.05, 0.7, -0.1, 0.2, 0.4];
        let j = jumps(&GEOM, &u);
        let sigma = [0, 1].map(|g| {
            [
                d[g][0][0] * j[g][0] + d[g][0][1] * j[g][1],
                d[g][1][0] * j[g][0] + d[g][1][1] * j[g][1],
            ]
        });
        let f = forces(&GEOM, &sigma);
        for i in 0..8 {
            let ku: f64 = (0..8).map(|c| k[i][c] * u[c]).sum();
            assert!((ku - f[i]).abs() < 1e-12, "{i}: {ku} vs {}", f[i]);
        }
    }
}
