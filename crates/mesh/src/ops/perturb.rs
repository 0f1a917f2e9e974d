//! `MODI_MAILLAGE(DEFORME=_F(OPTION='TRAN', ALEA=a))` (code_aster's
//! `modi_alea`): every node moved by a pseudo-random amount, at most `a`
//! times the mesh's extent along each axis, to keep apart points that would
//! otherwise coincide to the machine's precision.

use crate::Mesh;

/// code_aster's `ggubs`: the minimal standard generator of Park and Miller
/// (multiplier 16807, modulus 2³¹ − 1) on a real seed; every product is
/// exact in double precision (the seed stays below 2³¹), so the sequence is
/// code_aster's to the last bit.
fn ggubs(seed: &mut f64) -> f64 {
    const D2P31M: f64 = 2147483647.0;
    const D2P31: f64 = 2147483648.0;
    let idseed = (16807.0 * *seed / D2P31M).trunc();
    *seed = 16807.0 * *seed - idseed * D2P31M;
    *seed / D2P31
}

impl Mesh {
    /// Moves node k (in order) by r·alea·(max − min) along x, y, z in
    /// turn, r = 2·(u − ½) with u the next number of `ggubs` from the seed
    /// 24331 (three per node, z included on a plane mesh, as code_aster
    /// stores three coordinates).
    pub fn perturb_randomly(&mut self, alea: f64) {
        let Some(first) = self.coords.first().copied() else {
            return;
        };
        let (mut lo, mut hi) = (first, first);
        for p in &self.coords {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let size: Vec<f64> = (0..3).map(|k| alea * (hi[k] - lo[k])).collect();
        let mut seed = 24331.0;
        for p in &mut self.coords {
            for k in 0..3 {
                let r = 2.0 * (ggubs(&mut seed) - 0.5);
                p[k] += r * size[k];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_generator_is_park_and_miller_s_minimal_standard() {
        // x₁ = 16807·24331 mod (2³¹ − 1) = 408931117; x₂ = 16807·x₁ mod …
        let mut seed = 24331.0;
        let u1 = ggubs(&mut seed);
        assert_eq!(seed, 408931117.0);
        assert_eq!(u1, 408931117.0 / 2147483648.0);
        ggubs(&mut seed);
        assert_eq!(seed, ((408931117u64 * 16807) % 2147483647) as f64);
        // The 10000th value from seed 1 is Park and Miller's check number.
        let mut s = 1.0;
        for _ in 0..10000 {
            ggubs(&mut s);
        }
        assert_eq!(s, 1043618065.0);
    }

    #[test]
    fn nodes_move_within_alea_times_the_extent() {
        let mut m = Mesh {
            dim: 2,
            coords: vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0]],
            ..Mesh::default()
        };
        let before = m.coords.clone();
        m.perturb_randomly(1e-3);
        for (a, b) in before.iter().zip(&m.coords) {
            assert!((a[0] - b[0]).abs() <= 2e-3 && a[0] != b[0]);
            assert!((a[1] - b[1]).abs() <= 1e-3 && a[1] != b[1]);
            assert_eq!(a[2], b[2]);
        }
        // Node 1 moves by the first two numbers of the sequence.
        let r = 2.0 * (408931117.0 / 2147483648.0 - 0.5);
        assert_eq!(m.coords[0][0], r * 2e-3);
    }
}
