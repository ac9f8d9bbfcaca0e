//! Pressure cutoff and spall options (numerics.md §8.9; deck fields PC and SPALL, LS-DYNA
//! semantics). Pointwise: limits one pressure or flags one point as failed.

use crate::error::MaterialError;
use crate::max_principal_value;
use tlsph_math::Tensor3;

/// Tensile pressure cutoff / spall model (numerics.md §8.9, deck SPALL = 1, 2, 3).
///
/// Build it with [`limit`](Self::limit), [`max_principal_stress`](Self::max_principal_stress),
/// [`min_pressure`](Self::min_pressure) or [`from_spall_type`](Self::from_spall_type), which
/// validate the value; the variants are public so that the solver can match on them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PressureCutoff {
    /// Type 1: p ← max(p, p_min); tension is limited, the point does not fail
    /// (R-P8, R-P10: p_min = −800 MPa).
    Limit {
        /// Most tensile pressure allowed, p_min ≤ 0 \[Pa\].
        min_pressure: f64,
    },
    /// Type 2: the point spalls (fails, numerics.md §9.3) when the maximum principal stress
    /// σ1 ≥ |limit| (R-P9 deck: PC = +4.9 GPa, sign ignored).
    MaxPrincipalStress {
        /// Spall strength; its magnitude is used \[Pa\].
        limit: f64,
    },
    /// Type 3: the point fails when the hydrostatic tension −p ≥ |limit|.
    MinPressure {
        /// Hydrostatic tensile strength; its magnitude is used \[Pa\].
        limit: f64,
    },
}

impl PressureCutoff {
    /// Type 1 with p_min ≤ 0 \[Pa\]; a positive or non-finite value is rejected
    /// (`pressure_cutoff`), since it would put every point in compression.
    pub fn limit(min_pressure: f64) -> Result<Self, MaterialError> {
        if min_pressure.is_finite() && min_pressure <= 0.0 {
            Ok(Self::Limit { min_pressure })
        } else {
            Err(MaterialError {
                parameter: "pressure_cutoff",
                value: min_pressure,
                expected: "a finite pressure at most 0 (tension is negative)",
            })
        }
    }

    /// Type 2 with spall strength |limit| > 0 \[Pa\] (`pressure_cutoff`).
    pub fn max_principal_stress(limit: f64) -> Result<Self, MaterialError> {
        Ok(Self::MaxPrincipalStress {
            limit: non_zero(limit)?,
        })
    }

    /// Type 3 with tensile strength |limit| > 0 \[Pa\] (`pressure_cutoff`).
    pub fn min_pressure(limit: f64) -> Result<Self, MaterialError> {
        Ok(Self::MinPressure {
            limit: non_zero(limit)?,
        })
    }

    /// From the deck pair (SPALL, PC): 1 → [`Limit`](Self::Limit), 2 →
    /// [`MaxPrincipalStress`](Self::MaxPrincipalStress), 3 → [`MinPressure`](Self::MinPressure);
    /// any other type is rejected (`spall_type`).
    pub fn from_spall_type(spall_type: u32, pressure_cutoff: f64) -> Result<Self, MaterialError> {
        match spall_type {
            1 => Self::limit(pressure_cutoff),
            2 => Self::max_principal_stress(pressure_cutoff),
            3 => Self::min_pressure(pressure_cutoff),
            other => Err(MaterialError {
                parameter: "spall_type",
                value: f64::from(other),
                expected: "1 (pressure limit), 2 (max principal stress) or 3 (min pressure)",
            }),
        }
    }

    /// Applies the type-1 limit p ← max(p, p_min); types 2 and 3 return p unchanged
    /// (numerics.md §8.9).
    #[inline]
    pub fn limit_pressure(&self, pressure: f64) -> f64 {
        match *self {
            Self::Limit { min_pressure } => pressure.max(min_pressure),
            _ => pressure,
        }
    }

    /// Whether the point fails (numerics.md §8.9): type 2 when the largest principal value of
    /// the Cauchy stress σ (tension positive) is ≥ |limit|, type 3 when −p ≥ |limit|; type 1
    /// never fails. `pressure` is p (compression positive), `stress` the full σ.
    #[inline]
    pub fn fails(&self, pressure: f64, stress: &Tensor3) -> bool {
        match *self {
            Self::Limit { .. } => false,
            Self::MaxPrincipalStress { limit } => max_principal_value(stress) >= limit.abs(),
            Self::MinPressure { limit } => -pressure >= limit.abs(),
        }
    }
}

fn non_zero(limit: f64) -> Result<f64, MaterialError> {
    if limit.is_finite() && limit != 0.0 {
        Ok(limit)
    } else {
        Err(MaterialError {
            parameter: "pressure_cutoff",
            value: limit,
            expected: "a finite non-zero stress (its magnitude is the strength)",
        })
    }
}
