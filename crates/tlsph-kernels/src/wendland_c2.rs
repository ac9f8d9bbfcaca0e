//! Wendland's C² kernel (Wendland 1995) with support 2h. Pure function of a distance.

use std::f64::consts::PI;

use crate::{validate, Kernel, KernelError};

/// Support radius divided by h.
pub(crate) const SUPPORT_FACTOR: f64 = 2.0;

/// Wendland C² kernel (Wendland 1995, the ψ_{3,1} / ψ_{2,1} functions), support 2h.
///
/// With q = r/h and s = 1 − q/2 (0 ≤ q < 2):
/// * 1D: W = 5/(8h) · s³ (1 + 3q/2);
/// * 2D: W = 7/(4πh²) · s⁴ (1 + 2q);
/// * 3D: W = 21/(16πh³) · s⁴ (1 + 2q).
///
/// Radial derivatives (derived, `[A]`): 1D w' = −3q s², w'' = 3s(3q/2 − 1);
/// 2D/3D w' = −5q s³, w'' = 5s²(2q − 1). These constants integrate to 1 exactly (checked by
/// quadrature in the tests).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WendlandC2 {
    dimension: usize,
    h: f64,
    inv_h: f64,
    support: f64,
    inv_support: f64,
    /// C_d / h^d, C_d / h^(d+1), C_d / h^(d+2).
    scale: [f64; 3],
}

impl WendlandC2 {
    /// Builds the kernel for `dimension` ∈ {1, 2, 3} and smoothing length `h` \[length\] > 0.
    pub fn new(dimension: usize, h: f64) -> Result<Self, KernelError> {
        validate(dimension, h)?;
        let c = match dimension {
            1 => 5.0 / 8.0,
            2 => 7.0 / (4.0 * PI),
            _ => 21.0 / (16.0 * PI),
        };
        let inv_h = 1.0 / h;
        let support = SUPPORT_FACTOR * h;
        let value_scale = c * inv_h.powi(dimension as i32);
        Ok(Self {
            dimension,
            h,
            inv_h,
            support,
            inv_support: 1.0 / support,
            scale: [
                value_scale,
                value_scale * inv_h,
                value_scale * inv_h * inv_h,
            ],
        })
    }

    /// The spatial dimension the kernel is normalised for.
    pub fn dimension(&self) -> usize {
        self.dimension
    }

    /// (q, s) with s = 1 − q/2 computed from (2h − r) so that s > 0 for every r < 2h.
    #[inline]
    fn q_s(&self, r: f64) -> (f64, f64) {
        (r * self.inv_h, (self.support - r) * self.inv_support)
    }
}

impl Kernel for WendlandC2 {
    #[inline]
    fn value(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let (q, s) = self.q_s(r);
        let s2 = s * s;
        let w = if self.dimension == 1 {
            s2 * s * (1.0 + 1.5 * q)
        } else {
            s2 * s2 * (1.0 + 2.0 * q)
        };
        self.scale[0] * w
    }

    #[inline]
    fn derivative(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let (q, s) = self.q_s(r);
        let dw = if self.dimension == 1 {
            -3.0 * q * s * s
        } else {
            -5.0 * q * s * s * s
        };
        self.scale[1] * dw
    }

    #[inline]
    fn second_derivative(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let (q, s) = self.q_s(r);
        let d2w = if self.dimension == 1 {
            3.0 * s * (1.5 * q - 1.0)
        } else {
            5.0 * s * s * (2.0 * q - 1.0)
        };
        self.scale[2] * d2w
    }

    #[inline]
    fn support_radius(&self) -> f64 {
        self.support
    }

    #[inline]
    fn smoothing_length(&self) -> f64 {
        self.h
    }
}
