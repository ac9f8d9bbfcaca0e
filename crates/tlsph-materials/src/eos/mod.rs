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
