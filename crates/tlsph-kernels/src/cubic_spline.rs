//! The cubic B-spline kernel (numerics.md §1.1). Pure function of a distance.

use std::f64::consts::PI;

use crate::{validate, Kernel, KernelError};

/// Support radius divided by h.
pub(crate) const SUPPORT_FACTOR: f64 = 2.0;

/// Cubic B-spline kernel, numerics.md §1.1 (R 2.3; F 2.5–2.10), support 2h.
///
/// W(r, h) = (C_d / h^d) w(q), q = r/h, with
/// w(q) = 1 − 3/2 q² + 3/4 q³ (0 ≤ q ≤ 1), 1/4 (2 − q)³ (1 ≤ q ≤ 2), 0 (q ≥ 2),
/// and C_1 = 2/3, C_2 = 10/(7π), C_3 = 1/π (F 2.7; R 2.3 prints an extra 1/π, numerics.md §17).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CubicSpline {
    dimension: usize,
    h: f64,
    inv_h: f64,
    support: f64,
    /// C_d / h^d, C_d / h^(d+1), C_d / h^(d+2).
    scale: [f64; 3],
}

impl CubicSpline {
    /// Builds the kernel for `dimension` ∈ {1, 2, 3} and smoothing length `h` \[length\] > 0.
    pub fn new(dimension: usize, h: f64) -> Result<Self, KernelError> {
        validate(dimension, h)?;
        let c = match dimension {
            1 => 2.0 / 3.0,
            2 => 10.0 / (7.0 * PI),
            _ => 1.0 / PI,
        };
        let inv_h = 1.0 / h;
        let value_scale = c * inv_h.powi(dimension as i32);
        Ok(Self {
            dimension,
            h,
            inv_h,
            support: SUPPORT_FACTOR * h,
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
}

impl Kernel for CubicSpline {
    #[inline]
    fn value(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let q = r * self.inv_h;
        let w = if q < 1.0 {
            1.0 - q * q * (1.5 - 0.75 * q)
        } else {
            // 2 − q computed from (2h − r) so that it stays > 0 for every r < 2h.
            let t = (self.support - r) * self.inv_h;
            0.25 * t * t * t
        };
        self.scale[0] * w
    }

    #[inline]
    fn derivative(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let q = r * self.inv_h;
        // w'(q), F 2.10.
        let dw = if q < 1.0 {
            q * (-3.0 + 2.25 * q)
        } else {
            let t = (self.support - r) * self.inv_h;
            -0.75 * t * t
        };
        self.scale[1] * dw
    }

    #[inline]
    fn second_derivative(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let q = r * self.inv_h;
        let d2w = if q < 1.0 {
            -3.0 + 4.5 * q
        } else {
            1.5 * (self.support - r) * self.inv_h
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
