//! Forward-mode dual numbers and 2 × 2 tensors used to differentiate the discrete force
//! functions of [`super::lattice`] exactly (to round-off), instead of by finite differences.
//!
//! A [`Dual`] carries a value and one directional derivative; every operation applies the chain
//! rule, so evaluating the force function with the seed `d = 1` on one coordinate returns one
//! column of the Jacobian ∂a/∂x with no step-size error and no subtractive cancellation. The
//! force code is written once, generic over [`Scalar`], and runs on plain `f64` as well (used for
//! the base state and for the finite-difference cross-check in the tests).

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// Arithmetic needed by the force functions: `f64` and [`Dual`].
pub trait Scalar:
    Copy
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
{
    /// A constant (zero derivative).
    fn constant(value: f64) -> Self;
    /// The value part.
    fn value(self) -> f64;
    /// f(self) for a scalar function f given its value `f` and slope `df` at `self.value()`
    /// (chain rule: the derivative part is multiplied by `df`).
    fn chain(self, f: f64, df: f64) -> Self;
    /// self × s for a plain number s.
    fn scale(self, s: f64) -> Self;

    /// Square root (chain rule d√x = dx / (2√x)).
    fn sqrt(self) -> Self {
        let r = self.value().sqrt();
        self.chain(r, 0.5 / r)
    }
    /// Natural logarithm (d ln x = dx / x).
    fn ln(self) -> Self {
        let v = self.value();
        self.chain(v.ln(), 1.0 / v)
    }
}

impl Scalar for f64 {
    #[inline]
    fn constant(value: f64) -> Self {
        value
    }
    #[inline]
    fn value(self) -> f64 {
        self
    }
    #[inline]
    fn chain(self, f: f64, _df: f64) -> Self {
        f
    }
    #[inline]
    fn scale(self, s: f64) -> Self {
        self * s
    }
}

/// A dual number v + d ε with ε² = 0: value `v` and derivative `d` along one seed direction.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Dual {
    /// Value.
    pub v: f64,
    /// Derivative along the seed direction.
    pub d: f64,
}

impl Dual {
    /// The independent variable itself: value `v`, derivative 1.
    pub fn variable(v: f64) -> Self {
        Self { v, d: 1.0 }
    }
}

impl Scalar for Dual {
    #[inline]
    fn constant(value: f64) -> Self {
        Self { v: value, d: 0.0 }
    }
    #[inline]
    fn value(self) -> f64 {
        self.v
    }
    #[inline]
    fn chain(self, f: f64, df: f64) -> Self {
        Self {
            v: f,
            d: df * self.d,
        }
    }
    #[inline]
    fn scale(self, s: f64) -> Self {
        Self {
            v: self.v * s,
            d: self.d * s,
        }
    }
}

impl Add for Dual {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self {
            v: self.v + o.v,
            d: self.d + o.d,
        }
    }
}

impl Sub for Dual {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self {
            v: self.v - o.v,
            d: self.d - o.d,
        }
    }
}

impl Mul for Dual {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self {
            v: self.v * o.v,
            d: self.d * o.v + self.v * o.d,
        }
    }
}

impl Div for Dual {
    type Output = Self;
    #[inline]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.v;
        Self {
            v: self.v * inv,
            d: (self.d - self.v * inv * o.d) * inv,
        }
    }
}

impl Neg for Dual {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            d: -self.d,
        }
    }
}

impl AddAssign for Dual {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        self.v += o.v;
        self.d += o.d;
    }
}

impl SubAssign for Dual {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        self.v -= o.v;
        self.d -= o.d;
    }
}

/// A 2-vector of scalars (plane-strain displacements, separations, kernel gradients).
pub type V2<S> = [S; 2];

/// A 2 × 2 tensor `m[i][j]` (row i, column j): F, L, σ, P of the 2D lattice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct M2<S> {
    /// Components, row-major.
    pub m: [[S; 2]; 2],
}

impl<S: Scalar> M2<S> {
    /// The zero tensor.
    pub fn zero() -> Self {
        let z = S::constant(0.0);
        Self {
            m: [[z, z], [z, z]],
        }
    }

    /// The identity.
    pub fn identity() -> Self {
        let (z, o) = (S::constant(0.0), S::constant(1.0));
        Self {
            m: [[o, z], [z, o]],
        }
    }

    /// A constant tensor from plain numbers.
    pub fn constant(m: [[f64; 2]; 2]) -> Self {
        Self {
            m: m.map(|row| row.map(S::constant)),
        }
    }

    /// a ⊗ b, (a ⊗ b)_ij = a_i b_j.
    pub fn outer(a: V2<S>, b: V2<S>) -> Self {
        Self {
            m: [[a[0] * b[0], a[0] * b[1]], [a[1] * b[0], a[1] * b[1]]],
        }
    }

    /// Transpose.
    pub fn transpose(self) -> Self {
        let m = self.m;
        Self {
            m: [[m[0][0], m[1][0]], [m[0][1], m[1][1]]],
        }
    }

    /// Trace.
    pub fn trace(self) -> S {
        self.m[0][0] + self.m[1][1]
    }

    /// Determinant.
    pub fn det(self) -> S {
        self.m[0][0] * self.m[1][1] - self.m[0][1] * self.m[1][0]
    }

    /// Inverse (no singularity check: the lattice states are far from det = 0).
    pub fn inverse(self) -> Self {
        let d = self.det();
        let m = self.m;
        Self {
            m: [[m[1][1] / d, -m[0][1] / d], [-m[1][0] / d, m[0][0] / d]],
        }
    }

    /// Symmetric part ½(A + Aᵀ).
    pub fn sym(self) -> Self {
        (self + self.transpose()).scale(0.5)
    }

    /// Skew part ½(A − Aᵀ).
    pub fn skew(self) -> Self {
        (self - self.transpose()).scale(0.5)
    }

    /// A × s for a scalar s.
    pub fn times(self, s: S) -> Self {
        Self {
            m: self.m.map(|row| row.map(|x| x * s)),
        }
    }

    /// A × s for a plain number s.
    pub fn scale(self, s: f64) -> Self {
        Self {
            m: self.m.map(|row| row.map(|x| x.scale(s))),
        }
    }

    /// Matrix–vector product A v.
    pub fn apply(self, v: V2<S>) -> V2<S> {
        let m = self.m;
        [
            m[0][0] * v[0] + m[0][1] * v[1],
            m[1][0] * v[0] + m[1][1] * v[1],
        ]
    }

    /// The value parts as plain numbers.
    pub fn values(self) -> [[f64; 2]; 2] {
        self.m.map(|row| row.map(Scalar::value))
    }
}

impl<S: Scalar> Add for M2<S> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let (a, b) = (self.m, o.m);
        Self {
            m: [
                [a[0][0] + b[0][0], a[0][1] + b[0][1]],
                [a[1][0] + b[1][0], a[1][1] + b[1][1]],
            ],
        }
    }
}

impl<S: Scalar> Sub for M2<S> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        let (a, b) = (self.m, o.m);
        Self {
            m: [
                [a[0][0] - b[0][0], a[0][1] - b[0][1]],
                [a[1][0] - b[1][0], a[1][1] - b[1][1]],
            ],
        }
    }
}

impl<S: Scalar> Mul for M2<S> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let (a, b) = (self.m, o.m);
        let e = |i: usize, j: usize| a[i][0] * b[0][j] + a[i][1] * b[1][j];
        Self {
            m: [[e(0, 0), e(0, 1)], [e(1, 0), e(1, 1)]],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dual_rules_match_hand_derivatives() {
        let x = Dual::variable(1.7);
        let f = (x * x + Dual::constant(2.0)) / x.sqrt() - x.ln().scale(3.0);
        // f = (x² + 2) x^(−1/2) − 3 ln x; f' = 1.5 x^(1/2) − x^(−3/2) − 3/x.
        let v = 1.7_f64;
        let want = 1.5 * v.sqrt() - v.powf(-1.5) - 3.0 / v;
        assert!((f.d - want).abs() < 1e-14, "{} vs {want}", f.d);
        assert!((f.v - ((v * v + 2.0) / v.sqrt() - 3.0 * v.ln())).abs() < 1e-14);
    }

    #[test]
    fn tensor_inverse_and_product() {
        let a = M2::<f64>::constant([[1.3, 0.2], [-0.4, 0.9]]);
        let p = (a * a.inverse()).values();
        for (i, row) in p.iter().enumerate() {
            for (j, &x) in row.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((x - want).abs() < 1e-15);
            }
        }
        assert!((a.det() - (1.3 * 0.9 + 0.2 * 0.4)).abs() < 1e-15);
        let s = a.sym() + a.skew() - a;
        assert!(s.values().iter().flatten().all(|x| x.abs() < 1e-16));
    }
}
