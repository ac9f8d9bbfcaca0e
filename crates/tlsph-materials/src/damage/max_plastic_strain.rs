//! Maximum effective plastic strain failure criterion (numerics.md §9.3; LS-DYNA FAIL of the
//! plastic-kinematic material). Pointwise only.

use crate::error::{positive, MaterialError};

/// A point fails when its accumulated effective plastic strain ε̄p (numerics.md §8.4) reaches
/// ε̄p,max (failed points per numerics.md §9.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaxPlasticStrainFailure {
    max_plastic_strain: f64,
}

impl MaxPlasticStrainFailure {
    /// Builds the criterion from ε̄p,max > 0 (`max_plastic_strain`).
    pub fn new(max_plastic_strain: f64) -> Result<Self, MaterialError> {
        Ok(Self {
            max_plastic_strain: positive("max_plastic_strain", max_plastic_strain)?,
        })
    }

    /// The limit ε̄p,max.
    pub fn max_plastic_strain(&self) -> f64 {
        self.max_plastic_strain
    }

    /// Whether ε̄p ≥ ε̄p,max.
    #[inline]
    pub fn fails(&self, plastic_strain: f64) -> bool {
        plastic_strain >= self.max_plastic_strain
    }
}
