//! Deviatoric strength models: plastic return maps applied to the trial deviator s* of the
//! elastic Jaumann-rate predictor (numerics.md §8.1, §8.3–8.5). Pointwise only.
//!
//! The solver splits the Cauchy stress as σ = −(p + q) I + s (numerics.md §8.3): the pressure
//! comes from the hypoelastic bulk part or an equation of state, the deviator from
//! s* = s + 2GΔt D′ + rotation, then a model here maps s* back onto its yield surface.

mod johnson_cook;
mod von_mises;

pub use johnson_cook::{JohnsonCookStrength, JohnsonCookStrengthParameters};
pub use von_mises::VonMisesPlasticity;

use tlsph_math::{deviator, Tensor3};

/// Result of a plastic return map (numerics.md §8.4–8.5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlasticReturn {
    /// Stress deviator s after the return \[Pa\]; equals the trial deviator when the step is elastic.
    pub deviator: Tensor3,
    /// Increment Δε̄p ≥ 0 of the effective (accumulated) plastic strain over the step.
    pub plastic_strain_increment: f64,
}

impl PlasticReturn {
    /// The elastic outcome: the trial deviator is admissible and no plastic strain accrues.
    #[inline]
    pub(crate) fn elastic(trial_deviator: &Tensor3) -> Self {
        Self {
            deviator: *trial_deviator,
            plastic_strain_increment: 0.0,
        }
    }
}

/// Equivalent (von Mises) strain rate ε̇̄ = sqrt(2/3 D′:D′) \[1/s\] of the rate of deformation D,
/// D′ its deviator (numerics.md §8.5, the rate entering the Johnson–Cook ε̇* = ε̇̄/ε̇0).
///
/// For uniaxial stress with plastic incompressibility (D = ε̇ diag(1, −½, −½)) it returns |ε̇|.
#[inline]
pub fn equivalent_strain_rate(rate_of_deformation: &Tensor3) -> f64 {
    let d = deviator(rate_of_deformation);
    (2.0 / 3.0 * d.component_mul(&d).sum()).sqrt()
}

/// Equivalent stress σ̄ = sqrt(3/2 s:s) of a tensor taken as a deviator (numerics.md §0).
///
/// Unlike `tlsph_math::von_mises` it does not remove a trace first: return maps receive a
/// deviator and must scale exactly that tensor.
#[inline]
pub(crate) fn equivalent_stress_of_deviator(s: &Tensor3) -> f64 {
    (1.5 * s.component_mul(s).sum()).sqrt()
}
