//! Errors for impossible material parameters. Each names the offending parameter.

use std::fmt;

/// A material parameter outside its physical range.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialError {
    /// Parameter name as written in a scene file, e.g. `poisson_ratio`.
    pub parameter: &'static str,
    /// The rejected value.
    pub value: f64,
    /// The admissible range in words, e.g. `between -1 and 0.5 (exclusive)`.
    pub expected: &'static str,
}

impl fmt::Display for MaterialError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} = {} is not allowed: it must be {}",
            self.parameter, self.value, self.expected
        )
    }
}

impl std::error::Error for MaterialError {}

/// Checks `value > 0` and finite.
pub(crate) fn positive(parameter: &'static str, value: f64) -> Result<f64, MaterialError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MaterialError {
            parameter,
            value,
            expected: "a finite number greater than 0",
        })
    }
}

/// Checks `value >= 0` and finite.
pub(crate) fn non_negative(parameter: &'static str, value: f64) -> Result<f64, MaterialError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(MaterialError {
            parameter,
            value,
            expected: "a finite number at least 0",
        })
    }
}

/// Checks that `value` is finite (any sign).
pub(crate) fn finite(parameter: &'static str, value: f64) -> Result<f64, MaterialError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(MaterialError {
            parameter,
            value,
            expected: "a finite number",
        })
    }
}
