//! Linear equation of state p = K μ (LS-DYNA linear polynomial with C1 only; numerics.md §8.7).
//! Pointwise only.

use crate::error::{positive, MaterialError};

/// Linear equation of state p = K μ, μ = ρ/ρ0 − 1 (numerics.md §8.7 with only C1 = K non-zero,
/// LS-DYNA's linear polynomial; M-AL-POLY is this EOS with K = 68.63 GPa).
///
/// It ignores the internal energy. Note that the hypoelastic bulk update of numerics.md §8.1,
/// Δp = −K tr(D) Δt, integrates to p = −K ln J, whereas this form gives p = K(1/J − 1); the two
/// agree to first order in the volume change and differ by K μ²/2 at second order (about 0.5 %
/// of p at 1 % compression). Use the rate form for the purely elastic material and this form
/// only where a deck asks for the polynomial/linear EOS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearEos {
    bulk_modulus: f64,
}

impl LinearEos {
    /// Builds the EOS from the bulk modulus K \[Pa\]; rejects K ≤ 0 (`bulk_modulus`).
    pub fn new(bulk_modulus: f64) -> Result<Self, MaterialError> {
        Ok(Self {
            bulk_modulus: positive("bulk_modulus", bulk_modulus)?,
        })
    }

    /// Pressure p = K μ \[Pa\]; the energy argument is ignored (numerics.md §8.7, C1 term).
    #[inline]
    pub fn pressure(&self, mu: f64, _energy_per_reference_volume: f64) -> f64 {
        self.bulk_modulus * mu
    }

    /// (∂p/∂μ, ∂p/∂E_v) = (K, 0) (see [`super::EquationOfState::isentropic_bulk_modulus`]).
    #[inline]
    pub fn pressure_derivatives(&self, _mu: f64, _energy_per_reference_volume: f64) -> (f64, f64) {
        (self.bulk_modulus, 0.0)
    }

    /// K \[Pa\] (numerics.md §7 sound speed).
    #[inline]
    pub fn bulk_modulus_at_reference(&self) -> f64 {
        self.bulk_modulus
    }
}
