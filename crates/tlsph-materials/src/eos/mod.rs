//! Equations of state: pressure p (compression positive) from the compression μ = ρ/ρ0 − 1 and
//! the internal energy per reference volume E_v = ρ0 e (numerics.md §8.3, §8.7–8.9).
//! Pointwise only.

mod linear;
mod mie_gruneisen;
mod polynomial;
mod pressure_cutoff;

pub use linear::LinearEos;
pub use mie_gruneisen::{MieGruneisen, MieGruneisenParameters};
pub use polynomial::PolynomialEos;
pub use pressure_cutoff::PressureCutoff;

/// Compression μ = ρ/ρ0 − 1 = 1/J − 1 from the Jacobian J = det F (numerics.md §8.3, R 6.23;
/// in Total-Lagrangian form ρ/ρ0 = 1/J).
#[inline]
pub fn compression_from_jacobian(jacobian: f64) -> f64 {
    1.0 / jacobian - 1.0
}

/// The equations of state a material group may use (numerics.md §8.7–8.8). The solver matches
/// once per material group, outside its particle loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EquationOfState {
    /// p = K μ ([`LinearEos`]).
    Linear(LinearEos),
    /// Linear polynomial EOS ([`PolynomialEos`], numerics.md §8.7).
    Polynomial(PolynomialEos),
    /// Mie–Grüneisen EOS with a shock-Hugoniot reference ([`MieGruneisen`], numerics.md §8.8).
    MieGruneisen(MieGruneisen),
}

impl EquationOfState {
    /// Pressure p(μ, E_v) \[Pa\], compression positive, from μ = ρ/ρ0 − 1 and the internal
    /// energy per reference volume E_v = ρ0 e \[J/m³\] (numerics.md §8.3).
    #[inline]
    pub fn pressure(&self, mu: f64, energy_per_reference_volume: f64) -> f64 {
        match self {
            Self::Linear(eos) => eos.pressure(mu, energy_per_reference_volume),
            Self::Polynomial(eos) => eos.pressure(mu, energy_per_reference_volume),
            Self::MieGruneisen(eos) => eos.pressure(mu, energy_per_reference_volume),
        }
    }

    /// Isentropic bulk modulus K_s = ρ (∂p/∂ρ)_s \[Pa\] at compression μ and energy E_v: with
    /// ρ = ρ0(1 + μ), E_v = ρ0 e and de = (p/ρ²) dρ along an isentrope,
    /// K_s = (1 + μ) ∂p/∂μ + (p/(1 + μ)) ∂p/∂E_v. The sound speed of the stability limit is
    /// c = sqrt((K_s + 4G/3)/ρ) (numerics.md §7, §8.10, with K_eff the current tangent rather
    /// than the reference value: a Mie–Grüneisen solid stiffens several-fold under strong
    /// compression, and a step sized for K0 is then unstable). At μ = 0, E_v = 0 it is
    /// [`bulk_modulus_at_reference`](Self::bulk_modulus_at_reference).
    #[inline]
    pub fn isentropic_bulk_modulus(&self, mu: f64, energy_per_reference_volume: f64) -> f64 {
        let e = energy_per_reference_volume;
        let (dp_dmu, dp_de) = self.pressure_derivatives(mu, e);
        let one = 1.0 + mu;
        let thermal = if dp_de == 0.0 {
            0.0
        } else {
            self.pressure(mu, e) / one * dp_de
        };
        one * dp_dmu + thermal
    }

    /// (∂p/∂μ, ∂p/∂E_v) at (μ, E_v): the slopes of [`pressure`](Self::pressure).
    #[inline]
    pub fn pressure_derivatives(&self, mu: f64, energy_per_reference_volume: f64) -> (f64, f64) {
        let e = energy_per_reference_volume;
        match self {
            Self::Linear(eos) => eos.pressure_derivatives(mu, e),
            Self::Polynomial(eos) => eos.pressure_derivatives(mu, e),
            Self::MieGruneisen(eos) => eos.pressure_derivatives(mu, e),
        }
    }

    /// Bulk modulus at the reference state K0 \[Pa\] for the sound speed
    /// c = sqrt((K0 + 4G/3)/ρ) (numerics.md §7, §8.10): K, C1 or ρ0C².
    #[inline]
    pub fn bulk_modulus_at_reference(&self) -> f64 {
        match self {
            Self::Linear(eos) => eos.bulk_modulus_at_reference(),
            Self::Polynomial(eos) => eos.bulk_modulus_at_reference(),
            Self::MieGruneisen(eos) => eos.bulk_modulus_at_reference(),
        }
    }
}

impl From<LinearEos> for EquationOfState {
    fn from(eos: LinearEos) -> Self {
        Self::Linear(eos)
    }
}

impl From<PolynomialEos> for EquationOfState {
    fn from(eos: PolynomialEos) -> Self {
        Self::Polynomial(eos)
    }
}

impl From<MieGruneisen> for EquationOfState {
    fn from(eos: MieGruneisen) -> Self {
        Self::MieGruneisen(eos)
    }
}
