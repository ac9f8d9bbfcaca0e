//! Johnson–Cook failure strain and damage accumulation (numerics.md §8.6; R 6.18–6.21).
//! Pointwise only.

use crate::error::{finite, MaterialError};

/// Lower bound on the failure strain ε_f (numerics.md §8.6 guard `[C]`), so that a negative or
/// vanishing fit never produces an infinite damage increment.
pub const MIN_STRAIN_TO_FAILURE: f64 = 1e-4;

/// Guard ratio for the triaxiality (numerics.md §8.6 `[C]`): skip damage accumulation while
/// σ̄ < 1e-9·A (A the Johnson–Cook yield constant), where σ_m/σ̄ is meaningless.
pub const TRIAXIALITY_STRESS_FLOOR: f64 = 1e-9;

/// Stress triaxiality σ* = σ_m/σ̄ = −p/σ̄ (numerics.md §8.6; tension positive, p compression
/// positive), or `None` when σ̄ < `min_equivalent_stress` — use
/// [`TRIAXIALITY_STRESS_FLOOR`]·A — in which case the step accumulates no damage.
#[inline]
pub fn stress_triaxiality(
    pressure: f64,
    equivalent_stress: f64,
    min_equivalent_stress: f64,
) -> Option<f64> {
    (equivalent_stress >= min_equivalent_stress && equivalent_stress > 0.0)
        .then(|| -pressure / equivalent_stress)
}

/// Johnson–Cook failure model (numerics.md §8.6; R 6.18–6.21):
/// ε_f = \[D1 + D2 exp(D3 σ*)\]\[1 + D4 ln ε̇*\]\[1 + D5 T*\], D = Σ Δε̄p/ε_f, failure at D ≥ 1.
///
/// M-AL7010-D: D1 0.45, D2 = D3 = 0, D4 0.0138, D5 0; M-CU9: D1 0.54, D2 4.89, D3 −3.03,
/// D4 0.014, D5 0 (problems.md §1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JohnsonCookFailure {
    d: [f64; 5],
}

impl JohnsonCookFailure {
    /// Builds the model from D1 … D5 (dimensionless); each must be finite (errors name `d1` …
    /// `d5`). Negative values are allowed (D3 is usually negative, D1 is for some steels and
    /// iron), but the failure strain at zero triaxiality, reference rate and room temperature,
    /// D1 + D2, must be positive (error names `d`): otherwise every plastic increment fails the
    /// particle at the floor [`MIN_STRAIN_TO_FAILURE`], a fit that cannot be meant.
    pub fn new(d1: f64, d2: f64, d3: f64, d4: f64, d5: f64) -> Result<Self, MaterialError> {
        let d = [d1, d2, d3, d4, d5];
        for (name, value) in ["d1", "d2", "d3", "d4", "d5"].into_iter().zip(d) {
            finite(name, value)?;
        }
        if d1 + d2 <= 0.0 {
            return Err(MaterialError {
                parameter: "d",
                value: d1 + d2,
                expected: "positive as D1 + D2, the failure strain at zero triaxiality, reference rate and room temperature",
            });
        }
        Ok(Self { d })
    }

    /// The constants `[D1, …, D5]`.
    pub fn constants(&self) -> [f64; 5] {
        self.d
    }

    /// Failure strain ε_f (numerics.md §8.6) for the triaxiality σ* = −p/σ̄ (finite), the
    /// dimensionless strain rate ε̇* = ε̇̄/ε̇0 (clamped ≥ 1 inside the logarithm) and the
    /// homologous temperature T* (clipped to \[0, 1\]); never below [`MIN_STRAIN_TO_FAILURE`].
    #[inline]
    pub fn strain_to_failure(
        &self,
        triaxiality: f64,
        strain_rate_star: f64,
        homologous_temperature: f64,
    ) -> f64 {
        let [d1, d2, d3, d4, d5] = self.d;
        let stress_term = d1 + d2 * (d3 * triaxiality).exp();
        let rate_term = 1.0 + d4 * strain_rate_star.max(1.0).ln();
        let thermal_term = 1.0 + d5 * homologous_temperature.clamp(0.0, 1.0);
        (stress_term * rate_term * thermal_term).max(MIN_STRAIN_TO_FAILURE)
    }

    /// Damage increment ΔD = Δε̄p/ε_f(σ*, ε̇*, T*) (numerics.md §8.6; R 6.21); a negative plastic
    /// strain increment counts as 0. Obtain σ* from [`stress_triaxiality`] and skip the call when
    /// it returns `None`.
    #[inline]
    pub fn damage_increment(
        &self,
        plastic_strain_increment: f64,
        triaxiality: f64,
        strain_rate_star: f64,
        homologous_temperature: f64,
    ) -> f64 {
        plastic_strain_increment.max(0.0)
            / self.strain_to_failure(triaxiality, strain_rate_star, homologous_temperature)
    }
}
