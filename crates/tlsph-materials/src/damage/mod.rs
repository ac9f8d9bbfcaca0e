//! Pointwise damage and failure: Johnson–Cook failure strain, stress and plastic-strain
//! criteria, Peerlings linear softening and Grady–Kipp flaw activation (numerics.md §8.6, §9).
//!
//! Only the pointwise parts live here; removing failed particles from neighbour lists
//! (numerics.md §9.3) is the solver's job.

mod grady_kipp;
mod johnson_cook;
mod max_plastic_strain;
mod max_stress;
mod peerlings;

pub use grady_kipp::{GradyKipp, BENZ_ASPHAUG_CRACK_SPEED_RATIO};
pub use johnson_cook::{
    stress_triaxiality, JohnsonCookFailure, MIN_STRAIN_TO_FAILURE, TRIAXIALITY_STRESS_FLOOR,
};
pub use max_plastic_strain::MaxPlasticStrainFailure;
pub use max_stress::MaxStressFailure;
pub use peerlings::PeerlingsSoftening;

use crate::principal::positive_part;
use tlsph_math::Tensor3;

/// Degrades the tensile part of a stress (numerics.md §9.1 `[C]`, also used by §9.2): the
/// symmetric stress is split spectrally and its positive principal values are multiplied by
/// (1 − D), compressive ones are kept: σ_D = σ − D Σ_{σi > 0} σi nᵢ⊗nᵢ. D is clamped to \[0, 1\].
#[inline]
pub fn degrade_tensile_part(stress: &Tensor3, damage: f64) -> Tensor3 {
    let d = damage.clamp(0.0, 1.0);
    if d == 0.0 {
        return *stress;
    }
    stress - positive_part(stress) * d
}
