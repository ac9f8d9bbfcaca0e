//! Isotropic linear elasticity, in the two forms the TLSPH algorithms use: St Venant–Kirchhoff
//! (PK2 from Green–Lagrange strain, Algorithm 1) and the hypoelastic Jaumann-rate update of
//! Cauchy stress (Algorithms 2 and 3). Pointwise only.

use crate::error::{positive, MaterialError};
use tlsph_math::Tensor3;

/// Isotropic linear elastic material (R 5.73–5.75; numerics.md §8.1–8.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearElastic {
    youngs_modulus: f64,
    poisson_ratio: f64,
    /// First Lamé parameter λ = Eν/((1+ν)(1−2ν)) \[Pa\].
    lambda: f64,
    /// Shear modulus μ = G = E/(2(1+ν)) \[Pa\].
    shear: f64,
}

impl LinearElastic {
    /// Builds the material from Young's modulus E \[Pa\] and Poisson's ratio ν.
    ///
    /// Rejects E ≤ 0 and ν outside (−1, 0.5), where the bulk or shear modulus would not be positive.
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self, MaterialError> {
        let e = positive("youngs_modulus", youngs_modulus)?;
        let nu = poisson_ratio;
        if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
            return Err(MaterialError {
                parameter: "poisson_ratio",
                value: nu,
                expected: "between -1 and 0.5 (both exclusive)",
            });
        }
        Ok(Self {
            youngs_modulus: e,
            poisson_ratio: nu,
            lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            shear: e / (2.0 * (1.0 + nu)),
        })
    }

    /// Young's modulus E \[Pa\].
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }

    /// Poisson's ratio ν.
    pub fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }

    /// First Lamé parameter λ \[Pa\] (R 5.73).
    pub fn lambda(&self) -> f64 {
        self.lambda
    }

    /// Shear modulus G = μ \[Pa\] (R 5.74).
    pub fn shear_modulus(&self) -> f64 {
        self.shear
    }

    /// Bulk modulus K = λ + 2G/3 \[Pa\] (R 5.75).
    pub fn bulk_modulus(&self) -> f64 {
        self.lambda + 2.0 * self.shear / 3.0
    }

    /// Longitudinal (P-wave, uniaxial-strain) modulus M = K + 4G/3 = λ + 2G \[Pa\] (R 6.1).
    pub fn longitudinal_modulus(&self) -> f64 {
        self.lambda + 2.0 * self.shear
    }

    /// Longitudinal sound speed c = sqrt(M/ρ) \[m/s\] at density ρ (numerics.md §7, §8.10).
    pub fn sound_speed(&self, density: f64) -> f64 {
        (self.longitudinal_modulus() / density).sqrt()
    }

    /// Second Piola–Kirchhoff stress of St Venant–Kirchhoff: S = λ tr(E) I + 2μ E (R 5.11–5.12).
    #[inline]
    pub fn second_piola_kirchhoff(&self, green_lagrange: &Tensor3) -> Tensor3 {
        green_lagrange * (2.0 * self.shear)
            + Tensor3::identity() * (self.lambda * green_lagrange.trace())
    }

    /// Strain energy per unit reference volume of St Venant–Kirchhoff, ½λ(tr E)² + μ E:E \[J/m³\].
    #[inline]
    pub fn strain_energy_density(&self, green_lagrange: &Tensor3) -> f64 {
        let tr = green_lagrange.trace();
        0.5 * self.lambda * tr * tr
            + self.shear * green_lagrange.component_mul(green_lagrange).sum()
    }

    /// Hypoelastic Cauchy stress update over one step with the Jaumann rate
    /// (R 5.82–5.86, numerics.md §8.1):
    /// σ̇ = λ tr(D) I + 2μ D + W σ − σ W.
    ///
    /// The rotation part is integrated with the Hughes–Winget rotation
    /// Q = (I − ½Δt W)⁻¹ (I + ½Δt W), σ ← Q σ Qᵀ, which is exactly orthogonal for any step,
    /// so a rigid spin never changes the stress invariants (objectivity); then the elastic
    /// increment Δt (λ tr D I + 2μ D) is added.
    #[inline]
    pub fn jaumann_update(
        &self,
        stress: &Tensor3,
        rate_of_deformation: &Tensor3,
        spin: &Tensor3,
        dt: f64,
    ) -> Tensor3 {
        let rotated = hughes_winget_rotate(stress, spin, dt);
        let d = rate_of_deformation;
        rotated + (d * (2.0 * self.shear) + Tensor3::identity() * (self.lambda * d.trace())) * dt
    }
}

/// Rotates a symmetric tensor by the Hughes–Winget increment of the spin W over Δt.
#[inline]
fn hughes_winget_rotate(stress: &Tensor3, spin: &Tensor3, dt: f64) -> Tensor3 {
    let half = spin * (0.5 * dt);
    let identity = Tensor3::identity();
    // I − ½ΔtW is always invertible for skew W (its eigenvalues are 1 ± i·θ).
    match (identity - half).try_inverse() {
        Some(inv) => {
            let q = inv * (identity + half);
            q * stress * q.transpose()
        }
        None => stress + (spin * stress - stress * spin) * dt,
    }
}
