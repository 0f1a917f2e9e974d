//! A forward-mode dual number with three partial derivatives, so each
//! reference element's shape functions are written once (as code_aster
//! states them) and their derivatives follow exactly, instead of being
//! derived by hand for every node of every family.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value and its gradient with respect to the reference coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ad {
    pub v: f64,
    pub d: [f64; 3],
}

impl Ad {
    pub const fn constant(v: f64) -> Ad {
        Ad { v, d: [0.; 3] }
    }

    /// The k-th coordinate (∂/∂ξₖ = 1) at value `v`.
    pub fn variable(v: f64, k: usize) -> Ad {
        let mut d = [0.; 3];
        d[k] = 1.;
        Ad { v, d }
    }

    /// The three reference coordinates of a point as variables.
    pub fn point(xi: [f64; 3]) -> [Ad; 3] {
        [
            Ad::variable(xi[0], 0),
            Ad::variable(xi[1], 1),
            Ad::variable(xi[2], 2),
        ]
    }
}

impl Add for Ad {
    type Output = Ad;
    fn add(self, o: Ad) -> Ad {
        Ad {
            v: self.v + o.v,
            d: [self.d[0] + o.d[0], self.d[1] + o.d[1], self.d[2] + o.d[2]],
        }
    }
}

impl Sub for Ad {
    type Output = Ad;
    fn sub(self, o: Ad) -> Ad {
        self + (-o)
    }
}

impl Neg for Ad {
    type Output = Ad;
    fn neg(self) -> Ad {
        Ad {
            v: -self.v,
            d: [-self.d[0], -self.d[1], -self.d[2]],
        }
    }
}

impl Mul for Ad {
    type Output = Ad;
    // The product rule: (fg)' = f'g + fg'.
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn mul(self, o: Ad) -> Ad {
        Ad {
            v: self.v * o.v,
            d: std::array::from_fn(|k| self.d[k] * o.v + self.v * o.d[k]),
        }
    }
}

impl Div for Ad {
    type Output = Ad;
    // The quotient rule: (f/g)' = (f'g − fg')/g².
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, o: Ad) -> Ad {
        let inv = 1. / o.v;
        Ad {
            v: self.v * inv,
            d: std::array::from_fn(|k| (self.d[k] * o.v - self.v * o.d[k]) * inv * inv),
        }
    }
}

impl Add<f64> for Ad {
    type Output = Ad;
    fn add(self, c: f64) -> Ad {
        Ad {
            v: self.v + c,
            d: self.d,
        }
    }
}

impl Sub<f64> for Ad {
    type Output = Ad;
    fn sub(self, c: f64) -> Ad {
        self + (-c)
    }
}

impl Mul<f64> for Ad {
    type Output = Ad;
    fn mul(self, c: f64) -> Ad {
        Ad {
            v: self.v * c,
            d: [self.d[0] * c, self.d[1] * c, self.d[2] * c],
        }
    }
}

impl Div<f64> for Ad {
    type Output = Ad;
    fn div(self, c: f64) -> Ad {
        self * (1. / c)
    }
}

impl Add<Ad> for f64 {
    type Output = Ad;
    fn add(self, a: Ad) -> Ad {
        a + self
    }
}

impl Sub<Ad> for f64 {
    type Output = Ad;
    fn sub(self, a: Ad) -> Ad {
        (-a) + self
    }
}

impl Mul<Ad> for f64 {
    type Output = Ad;
    fn mul(self, a: Ad) -> Ad {
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
}
