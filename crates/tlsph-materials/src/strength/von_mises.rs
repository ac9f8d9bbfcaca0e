//! Von Mises plasticity with linear isotropic hardening by radial return (numerics.md §8.4).
//! Pointwise: maps one trial deviator; never sees particles.

use super::{equivalent_stress_of_deviator, PlasticReturn};
use crate::error::{non_negative, positive, MaterialError};
use tlsph_math::Tensor3;

/// Von Mises plasticity with linear isotropic hardening, σ_y = σ_y0 + E_p ε̄p
/// (numerics.md §8.4; LS-DYNA plastic-kinematic with β = 1; elastic–perfectly plastic when
/// E_p = 0; the "elastic–plastic–hydrodynamic" material when combined with an EOS).
///
/// Used by M-CU6, M-ST10, M-DA1/2, M-ST7X (E_p = 0), M-PMMA (E_p = 300 MPa given directly)
/// and Fuller's A.9 (problems.md §1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VonMisesPlasticity {
    yield_stress: f64,
    plastic_modulus: f64,
}

impl VonMisesPlasticity {
    /// Builds the model from the initial yield stress σ_y0 \[Pa\] and the plastic (hardening)
    /// modulus E_p = dσ_y/dε̄p \[Pa\] (numerics.md §8.4).
    ///
    /// Rejects σ_y0 ≤ 0 (`yield_stress`) and E_p < 0 (`plastic_modulus`); E_p = 0 is elastic–perfectly plastic.
    pub fn new(yield_stress: f64, plastic_modulus: f64) -> Result<Self, MaterialError> {
        Ok(Self {
            yield_stress: positive("yield_stress", yield_stress)?,
            plastic_modulus: non_negative("plastic_modulus", plastic_modulus)?,
        })
    }

    /// Builds the model from the tangent modulus E_t of the uniaxial-stress curve \[Pa\]:
    /// E_p = E E_t/(E − E_t) (numerics.md §8.4 `[C]`; LS-DYNA plastic-kinematic ETAN).
    ///
    /// Rejects E ≤ 0 (`youngs_modulus`) and E_t outside \[0, E) (`tangent_modulus`).
    pub fn from_tangent_modulus(
        yield_stress: f64,
        youngs_modulus: f64,
        tangent_modulus: f64,
    ) -> Result<Self, MaterialError> {
        let e = positive("youngs_modulus", youngs_modulus)?;
        let et = tangent_modulus;
        if !(et.is_finite() && et >= 0.0 && et < e) {
            return Err(MaterialError {
                parameter: "tangent_modulus",
                value: et,
                expected: "at least 0 and less than youngs_modulus",
            });
        }
        Self::new(yield_stress, e * et / (e - et))
    }

    /// Initial yield stress σ_y0 \[Pa\].
    pub fn initial_yield_stress(&self) -> f64 {
        self.yield_stress
    }

    /// Plastic (hardening) modulus E_p \[Pa\].
    pub fn plastic_modulus(&self) -> f64 {
        self.plastic_modulus
    }

    /// Current yield stress σ_y = σ_y0 + E_p ε̄p \[Pa\] (numerics.md §8.4).
    #[inline]
    pub fn yield_stress(&self, plastic_strain: f64) -> f64 {
        self.yield_stress + self.plastic_modulus * plastic_strain
    }

    /// Radial return of the trial deviator s* (numerics.md §8.4):
    /// σ̄* = sqrt(3/2 s*:s*); if σ̄* > σ_y(ε̄p): Δε̄p = (σ̄* − σ_y)/(3G + E_p) and
    /// s = s*·(σ_y + E_p Δε̄p)/σ̄*; otherwise s = s*.
    ///
    /// `trial_deviator` must be traceless (it is scaled as given), `shear_modulus` is G \[Pa\] and
    /// `plastic_strain` the accumulated ε̄p at the start of the step. With linear hardening the
    /// return is exact: σ̄(s) = σ_y(ε̄p + Δε̄p) to round-off.
    #[inline]
    pub fn return_map(
        &self,
        trial_deviator: &Tensor3,
        shear_modulus: f64,
        plastic_strain: f64,
    ) -> PlasticReturn {
        debug_assert!(shear_modulus > 0.0);
        let trial = equivalent_stress_of_deviator(trial_deviator);
        let yield_stress = self.yield_stress(plastic_strain);
        if trial <= yield_stress {
            return PlasticReturn::elastic(trial_deviator);
        }
        let increment = (trial - yield_stress) / (3.0 * shear_modulus + self.plastic_modulus);
        let scale = (yield_stress + self.plastic_modulus * increment) / trial;
        PlasticReturn {
            deviator: trial_deviator * scale,
            plastic_strain_increment: increment,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_modulus_converts_to_plastic_modulus() {
        // M-CU6: E 110 GPa, E_t 1.1 GPa → E_p = 110·1.1/108.9 GPa = 1.1111… GPa.
        let m = VonMisesPlasticity::from_tangent_modulus(90e6, 110e9, 1.1e9).unwrap();
        assert!((m.plastic_modulus() - 110e9 * 1.1e9 / 108.9e9).abs() < 1e-3);
        assert_eq!(m.initial_yield_stress(), 90e6);
    }

    #[test]
    fn bad_parameters_name_their_field() {
        let cases = [
            (VonMisesPlasticity::new(0.0, 1.0), "yield_stress"),
            (VonMisesPlasticity::new(1.0, -1.0), "plastic_modulus"),
            (
                VonMisesPlasticity::from_tangent_modulus(1.0, 2.0, 2.0),
                "tangent_modulus",
            ),
            (
                VonMisesPlasticity::from_tangent_modulus(1.0, -2.0, 1.0),
                "youngs_modulus",
            ),
        ];
        for (result, name) in cases {
            assert_eq!(result.unwrap_err().parameter, name);
        }
    }

    #[test]
    fn below_yield_is_untouched() {
        let m = VonMisesPlasticity::new(1.0, 0.0).unwrap();
        let s = Tensor3::new(0.1, 0.2, 0.0, 0.2, -0.1, 0.0, 0.0, 0.0, 0.0);
        let r = m.return_map(&s, 10.0, 0.0);
        assert_eq!(r.deviator, s);
        assert_eq!(r.plastic_strain_increment, 0.0);
    }
}
