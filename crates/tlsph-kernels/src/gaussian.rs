//! The Gaussian kernel truncated at 3h and renormalised (numerics.md §1.2). Pure function of a
//! distance.

use std::f64::consts::PI;

use crate::erf::erf;
use crate::{validate, Kernel, KernelError};

/// Support radius divided by h (the truncation point q = 3).
pub(crate) const SUPPORT_FACTOR: f64 = 3.0;

/// Gaussian kernel, numerics.md §1.2 (R 2.1), truncated at q = r/h = 3 and renormalised `[C]`.
///
/// W(r, h) = π^(−d/2) h^(−d) exp(−q²) / Z_d for r < 3h and exactly 0 beyond, where Z_d is the
/// mass of the untruncated kernel inside the ball of radius 3h `[A]`:
/// * Z_1 = erf(3);
/// * Z_2 = 1 − e^(−9);
/// * Z_3 = erf(3) − (6/√π) e^(−9).
///
/// With Z_d the truncated kernel integrates to exactly 1. W jumps from about 1.2·10⁻⁴ W(0) to 0
/// at r = 3h; derivatives are those of the smooth part inside and 0 outside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gaussian {
    dimension: usize,
    h: f64,
    inv_h: f64,
    support: f64,
    /// C / h^d, C / h^(d+1), C / h^(d+2) with C = π^(−d/2) / Z_d.
    scale: [f64; 3],
}

/// Z_d: ∫ over |x| < 3 of π^(−d/2) exp(−|x|²) dx in `dimension` dimensions.
fn truncated_mass(dimension: usize) -> f64 {
    let a = SUPPORT_FACTOR;
    let tail = (-a * a).exp();
    match dimension {
        // ∫_{−a}^{a} π^(−1/2) e^(−q²) dq = erf(a).
        1 => erf(a),
        // ∫_0^a π^(−1) e^(−q²) 2πq dq = 1 − e^(−a²).
        2 => 1.0 - tail,
        // ∫_0^a π^(−3/2) e^(−q²) 4πq² dq = erf(a) − (2a/√π) e^(−a²).
        _ => erf(a) - 2.0 * a / PI.sqrt() * tail,
    }
}

impl Gaussian {
    /// Builds the kernel for `dimension` ∈ {1, 2, 3} and smoothing length `h` \[length\] > 0.
    pub fn new(dimension: usize, h: f64) -> Result<Self, KernelError> {
        validate(dimension, h)?;
        let c = PI.powf(-0.5 * dimension as f64) / truncated_mass(dimension);
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

impl Kernel for Gaussian {
    #[inline]
    fn value(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let q = r * self.inv_h;
        self.scale[0] * (-q * q).exp()
    }

    #[inline]
    fn derivative(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let q = r * self.inv_h;
        // w' = −2q e^(−q²).
        self.scale[1] * (-2.0 * q * (-q * q).exp())
    }

    #[inline]
    fn second_derivative(&self, r: f64) -> f64 {
        if r >= self.support {
            return 0.0;
        }
        let q = r * self.inv_h;
        // w'' = (4q² − 2) e^(−q²).
        self.scale[2] * ((4.0 * q * q - 2.0) * (-q * q).exp())
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
