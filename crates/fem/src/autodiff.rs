//! A forward-mode dual number: a value and its N partial derivatives, so
//! each reference element's shape functions are written once (as
//! code_aster states them) and their derivatives follow exactly, instead
//! of being derived by hand for every node of every family ([`Ad`], three
//! reference coordinates), and a contact point's residual gives its exact
//! tangent (`aster_contact::mortar_classique`, one derivative per local
//! unknown).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value and its gradient with respect to N variables.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual<const N: usize> {
    pub v: f64,
    pub d: [f64; N],
}

/// A value and its gradient with respect to the reference coordinates.
pub type Ad = Dual<3>;

impl<const N: usize> Dual<N> {
    pub const fn constant(v: f64) -> Self {
        Dual { v, d: [0.; N] }
    }

    /// The k-th variable (∂/∂xₖ = 1) at value `v`.
    pub fn variable(v: f64, k: usize) -> Self {
        let mut d = [0.; N];
        d[k] = 1.;
        Dual { v, d }
    }

    /// √x, with (√x)' = x' / (2√x).
    pub fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        let f = 0.5 / s;
        Dual {
            v: s,
            d: std::array::from_fn(|k| self.d[k] * f),
        }
    }
}

impl Dual<3> {
    /// The three reference coordinates of a point as variables.
    pub fn point(xi: [f64; 3]) -> [Ad; 3] {
        [
            Ad::variable(xi[0], 0),
            Ad::variable(xi[1], 1),
            Ad::variable(xi[2], 2),
        ]
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Dual {
            v: self.v + o.v,
            d: std::array::from_fn(|k| self.d[k] + o.d[k]),
        }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Dual {
            v: self.v - o.v,
            d: std::array::from_fn(|k| self.d[k] - o.d[k]),
        }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    fn neg(self) -> Self {
        Dual {
            v: -self.v,
            d: std::array::from_fn(|k| -self.d[k]),
        }
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    // The product rule: (fg)' = f'g + fg'.
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn mul(self, o: Self) -> Self {
        Dual {
            v: self.v * o.v,
            d: std::array::from_fn(|k| self.d[k] * o.v + self.v * o.d[k]),
        }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    // The quotient rule: (f/g)' = (f'g − fg')/g².
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, o: Self) -> Self {
        let inv = 1. / o.v;
        Dual {
            v: self.v * inv,
            d: std::array::from_fn(|k| (self.d[k] * o.v - self.v * o.d[k]) * inv * inv),
        }
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    fn add(self, c: f64) -> Self {
        Dual {
            v: self.v + c,
            d: self.d,
        }
    }
}

impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    fn sub(self, c: f64) -> Self {
        self + (-c)
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    fn mul(self, c: f64) -> Self {
        Dual {
            v: self.v * c,
            d: std::array::from_fn(|k| self.d[k] * c),
        }
    }
}

impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    fn div(self, c: f64) -> Self {
        self * (1. / c)
    }
}

impl<const N: usize> Add<Dual<N>> for f64 {
    type Output = Dual<N>;
    fn add(self, a: Dual<N>) -> Dual<N> {
        a + self
    }
}

impl<const N: usize> Sub<Dual<N>> for f64 {
    type Output = Dual<N>;
    fn sub(self, a: Dual<N>) -> Dual<N> {
        (-a) + self
    }
}

impl<const N: usize> Mul<Dual<N>> for f64 {
    type Output = Dual<N>;
    fn mul(self, a: Dual<N>) -> Dual<N> {
        a * self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn product_and_quotient_rules() {
        let [x, y, _] = Ad::point([2., 3., 0.]);
        let f = (x * y + 1.) / (1. - x); // (xy+1)/(1-x)
        assert_eq!(f.v, -7.);
        // ∂/∂x = (y(1-x) + (xy+1)) / (1-x)² = (-3 + 7) / 1 = 4
        assert!((f.d[0] - 4.).abs() < 1e-14);
        // ∂/∂y = x / (1-x) = -2
        assert!((f.d[1] + 2.).abs() < 1e-14);
        assert_eq!(f.d[2], 0.);
    }

    #[test]
    fn square_root_rule() {
        let x = Dual::<2>::variable(4., 1);
        let r = (x * x + 9.).sqrt(); // √(x² + 9) = 5 at x = 4
        assert_eq!(r.v, 5.);
        // ∂/∂x = x / √(x² + 9) = 4/5
        assert!((r.d[1] - 0.8).abs() < 1e-15);
        assert_eq!(r.d[0], 0.);
    }
}
