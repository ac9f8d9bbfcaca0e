//! Maximum principal stress failure criterion (numerics.md §8.9 type 2, §9.3). Pointwise only.

use crate::error::{positive, MaterialError};
use crate::max_principal_value;
use tlsph_math::Tensor3;

/// A point fails when the largest principal Cauchy stress (tension positive) reaches
/// σ_max (numerics.md §8.9 type 2 as a stand-alone criterion; failed points per §9.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaxStressFailure {
    max_principal_stress: f64,
}

impl MaxStressFailure {
    /// Builds the criterion from σ_max > 0 \[Pa\] (`max_principal_stress`).
    pub fn new(max_principal_stress: f64) -> Result<Self, MaterialError> {
        Ok(Self {
            max_principal_stress: positive("max_principal_stress", max_principal_stress)?,
        })
    }

    /// The limit σ_max \[Pa\].
    pub fn max_principal_stress(&self) -> f64 {
        self.max_principal_stress
    }

    /// Whether σ1(σ) ≥ σ_max for the Cauchy stress σ.
    #[inline]
    pub fn fails(&self, stress: &Tensor3) -> bool {
        max_principal_value(stress) >= self.max_principal_stress
    }
}
