//! Linear polynomial equation of state (numerics.md §8.7; R 6.22–6.23; LS-DYNA
//! *EOS_LINEAR_POLYNOMIAL). Pointwise only.

use crate::error::{finite, positive, MaterialError};

/// Linear polynomial EOS (numerics.md §8.7; R 6.22–6.23):
/// p = C0 + C1 μ + C2 μ̄² + C3 μ³ + (C4 + C5 μ + C6 μ̄²) E_v, with μ = ρ/ρ0 − 1,
/// μ̄ = max(μ, 0) (the C2 and C6 terms vanish in tension, LS-DYNA convention) and E_v the
/// internal energy per reference volume \[J/m³\].
///
/// M-AL-POLY: C1 = 68.63 GPa, all others 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolynomialEos {
    c: [f64; 7],
}

const NAMES: [&str; 7] = ["c0", "c1", "c2", "c3", "c4", "c5", "c6"];

impl PolynomialEos {
    /// Builds the EOS from `[C0, C1, …, C6]`: C0, C1, C2, C3 \[Pa\], C4, C5, C6 dimensionless.
    ///
    /// Every coefficient must be finite (error names `c0` … `c6`) and C1 — the bulk modulus at
    /// the reference state — must be positive (`c1`), since it sets the sound speed.
    pub fn new(coefficients: [f64; 7]) -> Result<Self, MaterialError> {
        for (name, value) in NAMES.iter().zip(coefficients) {
            finite(name, value)?;
        }
        positive("c1", coefficients[1])?;
        Ok(Self { c: coefficients })
    }

    /// The coefficients `[C0, …, C6]`.
    pub fn coefficients(&self) -> [f64; 7] {
        self.c
    }

    /// Pressure \[Pa\], compression positive (numerics.md §8.7).
    #[inline]
    pub fn pressure(&self, mu: f64, energy_per_reference_volume: f64) -> f64 {
        let c = &self.c;
        let mu_bar = mu.max(0.0);
        let mu_bar2 = mu_bar * mu_bar;
        c[0] + c[1] * mu
            + c[2] * mu_bar2
            + c[3] * mu * mu * mu
            + (c[4] + c[5] * mu + c[6] * mu_bar2) * energy_per_reference_volume
    }

    /// (∂p/∂μ, ∂p/∂E_v) of [`pressure`](Self::pressure): (C1 + 2C2μ̄ + 3C3μ² + (C5 + 2C6μ̄)E_v,
    /// C4 + C5μ + C6μ̄²) (see [`super::EquationOfState::isentropic_bulk_modulus`]).
    #[inline]
    pub fn pressure_derivatives(&self, mu: f64, energy_per_reference_volume: f64) -> (f64, f64) {
        let c = &self.c;
        let mu_bar = mu.max(0.0);
        (
            c[1] + 2.0 * c[2] * mu_bar
                + 3.0 * c[3] * mu * mu
                + (c[5] + 2.0 * c[6] * mu_bar) * energy_per_reference_volume,
            c[4] + c[5] * mu + c[6] * mu_bar * mu_bar,
        )
    }

    /// C1 \[Pa\] (numerics.md §7 sound speed).
    #[inline]
    pub fn bulk_modulus_at_reference(&self) -> f64 {
        self.c[1]
    }
}
