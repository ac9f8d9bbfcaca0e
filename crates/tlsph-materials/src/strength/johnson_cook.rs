//! Johnson–Cook strength with single or iterated ("accurate") radial return (numerics.md §8.5,
//! R 6.16–6.17). Pointwise: maps one trial deviator; never sees particles.

use super::{equivalent_stress_of_deviator, PlasticReturn};
use crate::error::{non_negative, positive, MaterialError};
use tlsph_math::Tensor3;

/// Scene-file parameters of [`JohnsonCookStrength`] (numerics.md §8.5; R 6.16–6.17).
///
/// No `Default`: every value is a property of the material (M-AL7010, M-CU9 in problems.md §1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JohnsonCookStrengthParameters {
    /// Quasi-static initial yield stress A \[Pa\] (> 0).
    pub a: f64,
    /// Hardening coefficient B \[Pa\] (≥ 0).
    pub b: f64,
    /// Hardening exponent n (> 0).
    pub n: f64,
    /// Strain-rate coefficient C (≥ 0).
    pub c: f64,
    /// Thermal-softening exponent m (> 0).
    pub m: f64,
    /// Reference strain rate ε̇0 \[1/s\] (> 0).
    pub reference_strain_rate: f64,
    /// Room (reference) temperature T_room \[K\] (≥ 0).
    pub room_temperature: f64,
    /// Melt temperature T_melt \[K\] (> T_room).
    pub melt_temperature: f64,
}

impl JohnsonCookStrengthParameters {
    /// OFHC copper (Johnson and Cook 1983; M-CU9 in problems.md §1): A = 90 MPa,
    /// B = 292 MPa, n = 0.31, C = 0.025, m = 1.09, ε̇0 = 1/s, T_room = 300 K, T_melt = 1356 K.
    pub const OFHC_COPPER: Self = Self {
        a: 90e6,
        b: 292e6,
        n: 0.31,
        c: 0.025,
        m: 1.09,
        reference_strain_rate: 1.0,
        room_temperature: 300.0,
        melt_temperature: 1356.0,
    };
}

/// Johnson–Cook flow stress (numerics.md §8.5; R 6.16–6.17):
/// σ_y = (A + B ε̄p^n)(1 + C ln ε̇*)(1 − T*^m), ε̇* = max(ε̇̄/ε̇0, 1) inside the logarithm,
/// T* = (T − T_room)/(T_melt − T_room) clipped to \[0, 1\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JohnsonCookStrength {
    p: JohnsonCookStrengthParameters,
}

/// Relative residual |f|/σ̄* at which the accurate iteration stops. A few tens of machine
/// epsilons: f = σ̄* − 3GΔε̄p − σ_y cancels terms of size σ̄*, so it cannot be resolved better.
const CONSISTENCY_TOLERANCE: f64 = 1e-14;
/// Upper bound on safeguarded-Newton iterations; bisection alone reaches machine precision of
/// the bracket in about 60, so this is only a backstop against pathological input.
const MAX_ITERATIONS: usize = 200;

impl JohnsonCookStrength {
    /// Validates and stores the parameters. Errors name the scene-file field: `a` > 0, `b` ≥ 0,
    /// `n` > 0, `c` ≥ 0, `m` > 0, `reference_strain_rate` > 0, `room_temperature` ≥ 0 and
    /// `melt_temperature` must exceed `room_temperature`.
    pub fn new(parameters: JohnsonCookStrengthParameters) -> Result<Self, MaterialError> {
        let p = parameters;
        positive("a", p.a)?;
        non_negative("b", p.b)?;
        positive("n", p.n)?;
        non_negative("c", p.c)?;
        positive("m", p.m)?;
        positive("reference_strain_rate", p.reference_strain_rate)?;
        non_negative("room_temperature", p.room_temperature)?;
        if !(p.melt_temperature.is_finite() && p.melt_temperature > p.room_temperature) {
            return Err(MaterialError {
                parameter: "melt_temperature",
                value: p.melt_temperature,
                expected: "a finite temperature greater than room_temperature",
            });
        }
        Ok(Self { p })
    }

    /// The validated parameters.
    pub fn parameters(&self) -> &JohnsonCookStrengthParameters {
        &self.p
    }

    /// Homologous temperature T* = (T − T_room)/(T_melt − T_room) clipped to \[0, 1\]
    /// (numerics.md §8.5; also the T* of the damage model §8.6).
    #[inline]
    pub fn homologous_temperature(&self, temperature: f64) -> f64 {
        let t = (temperature - self.p.room_temperature)
            / (self.p.melt_temperature - self.p.room_temperature);
        t.clamp(0.0, 1.0)
    }

    /// Dimensionless strain rate ε̇* = ε̇̄/ε̇0, not clamped (numerics.md §8.5–8.6).
    #[inline]
    pub fn strain_rate_star(&self, equivalent_strain_rate: f64) -> f64 {
        equivalent_strain_rate / self.p.reference_strain_rate
    }

    /// Rate factor 1 + C ln ε̇* with ε̇* clamped ≥ 1 inside the logarithm (numerics.md §8.5 `[C]`),
    /// so rates below ε̇0 never weaken the material.
    #[inline]
    pub fn strain_rate_factor(&self, equivalent_strain_rate: f64) -> f64 {
        1.0 + self.p.c * self.strain_rate_star(equivalent_strain_rate).max(1.0).ln()
    }

    /// Thermal factor 1 − T*^m with clipped T* (numerics.md §8.5): 1 at or below room
    /// temperature, 0 at and above melt.
    #[inline]
    pub fn thermal_factor(&self, temperature: f64) -> f64 {
        1.0 - self.homologous_temperature(temperature).powf(self.p.m)
    }

    /// Flow stress σ_y(ε̄p, ε̇̄, T) = (A + B ε̄p^n)(1 + C ln ε̇*)(1 − T*^m) \[Pa\]
    /// (numerics.md §8.5; R 6.16). `equivalent_strain_rate` is ε̇̄ \[1/s\] (see
    /// [`equivalent_strain_rate`](crate::strength::equivalent_strain_rate)), `temperature` T \[K\].
    /// A negative plastic strain is read as 0.
    #[inline]
    pub fn yield_stress(
        &self,
        plastic_strain: f64,
        equivalent_strain_rate: f64,
        temperature: f64,
    ) -> f64 {
        self.hardening(plastic_strain)
            * self.strain_rate_factor(equivalent_strain_rate)
            * self.thermal_factor(temperature)
    }

    /// Strain-hardening part A + B ε̄p^n \[Pa\]: the flow stress at the reference strain rate
    /// and room temperature (numerics.md §8.5). A negative plastic strain is read as 0.
    #[inline]
    pub fn hardening(&self, plastic_strain: f64) -> f64 {
        self.p.a + self.p.b * plastic_strain.max(0.0).powf(self.p.n)
    }

    /// d(A + B ε̄p^n)/dε̄p = nB ε̄p^(n−1); +∞ at ε̄p = 0 when n < 1 (handled by the caller).
    #[inline]
    fn hardening_slope(&self, plastic_strain: f64) -> f64 {
        if self.p.b == 0.0 {
            return 0.0;
        }
        self.p.n * self.p.b * plastic_strain.max(0.0).powf(self.p.n - 1.0)
    }

    /// Radial return of the trial deviator s* (numerics.md §8.5), with the rate ε̇̄ \[1/s\] and
    /// temperature T \[K\] held fixed over the step, shear modulus G \[Pa\] and ε̄p at step start.
    ///
    /// - `iterate = false` (deck IT = 0): one radial return to the flow stress at the start of
    ///   the step, σ_y = σ_y(ε̄p): Δε̄p = (σ̄* − σ_y)/(3G), s = s*·σ_y/σ̄*.
    /// - `iterate = true` (deck IT = 1, "accurate iteration"): solves the consistency condition
    ///   f(Δε̄p) = σ̄* − 3GΔε̄p − σ_y(ε̄p + Δε̄p, ε̇̄, T) = 0 for Δε̄p ≥ 0, then
    ///   s = s*·σ_y(ε̄p + Δε̄p)/σ̄*, which lies on the updated yield surface.
    ///
    /// The solver is a safeguarded Newton method: f is strictly decreasing, f(0) > 0 and
    /// f(Δ_pp) ≤ 0 at the perfectly plastic estimate Δ_pp = (σ̄* − σ_y(ε̄p))/(3G), so the root is
    /// bracketed in \[0, Δ_pp\]; Newton steps that leave the bracket, or whose slope is not
    /// finite (nB ε^(n−1) → ∞ at ε̄p = 0 for n < 1), are replaced by bisection.
    pub fn return_map(
        &self,
        trial_deviator: &Tensor3,
        shear_modulus: f64,
        plastic_strain: f64,
        equivalent_strain_rate: f64,
        temperature: f64,
        iterate: bool,
    ) -> PlasticReturn {
        debug_assert!(shear_modulus > 0.0);
        let trial = equivalent_stress_of_deviator(trial_deviator);
        let ep = plastic_strain.max(0.0);
        let factor =
            self.strain_rate_factor(equivalent_strain_rate) * self.thermal_factor(temperature);
        let yield_start = self.hardening(ep) * factor;
        if trial <= yield_start {
            return PlasticReturn::elastic(trial_deviator);
        }
        let three_g = 3.0 * shear_modulus;
        let perfectly_plastic = (trial - yield_start) / three_g;
        let (increment, yield_end) = if iterate {
            let increment = self.solve_consistency(trial, three_g, ep, factor, perfectly_plastic);
            (increment, self.hardening(ep + increment) * factor)
        } else {
            (perfectly_plastic, yield_start)
        };
        PlasticReturn {
            deviator: trial_deviator * (yield_end / trial),
            plastic_strain_increment: increment,
        }
    }

    /// Root of f(Δ) = σ̄* − 3GΔ − factor·(A + B(ε̄p + Δ)^n) in \[0, upper\] (see `return_map`).
    ///
    /// For n < 1 the slope nB(ε̄p + Δ)^(n−1) is unbounded near ε̄p + Δ = 0 and the root can be
    /// astronomically small (for n = 0.1 just above yield, Δ ~ 1e-60), where Newton in Δ stalls
    /// and bisection needs hundreds of halvings. There the unknown is changed to
    /// z = (ε̄p + Δ)^n: f(z) = σ̄* − 3G(z^(1/n) − ε̄p) − factor·(A + Bz) has the finite slope
    /// −(3G/n) z^(1/n − 1) − factor·B, is concave, and Newton converges quadratically.
    fn solve_consistency(&self, trial: f64, three_g: f64, ep: f64, factor: f64, upper: f64) -> f64 {
        let (a, b, n) = (self.p.a, self.p.b, self.p.n);
        let tolerance = CONSISTENCY_TOLERANCE * trial;
        if n < 1.0 && b > 0.0 {
            let inv_n = 1.0 / n;
            let residual = |z: f64| {
                let d = (z.powf(inv_n) - ep).max(0.0);
                let f = trial - three_g * d - factor * (a + b * z);
                let slope = -three_g * inv_n * z.powf(inv_n - 1.0) - factor * b;
                (f, slope)
            };
            let z = safeguarded_newton(residual, ep.powf(n), (ep + upper).powf(n), tolerance);
            (z.powf(inv_n) - ep).clamp(0.0, upper)
        } else {
            let residual = |d: f64| {
                let f = trial - three_g * d - self.hardening(ep + d) * factor;
                let slope = -three_g - self.hardening_slope(ep + d) * factor;
                (f, slope)
            };
            safeguarded_newton(residual, 0.0, upper, tolerance)
        }
    }
}

/// Root of a strictly decreasing function on \[lo, hi\] with f(lo) ≥ 0 ≥ f(hi): Newton steps from
/// `hi`, replaced by bisection whenever the step leaves the current bracket or the slope is not
/// finite. Stops when |f| ≤ `tolerance`, when the Newton correction is below round-off, or when
/// the bracket has shrunk to round-off.
fn safeguarded_newton(
    residual_and_slope: impl Fn(f64) -> (f64, f64),
    mut lo: f64,
    mut hi: f64,
    tolerance: f64,
) -> f64 {
    let mut x = hi;
    for _ in 0..MAX_ITERATIONS {
        let (f, slope) = residual_and_slope(x);
        if f.abs() <= tolerance {
            return x;
        }
        if f > 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        if hi - lo <= 2.0 * f64::EPSILON * hi.abs() {
            return 0.5 * (lo + hi);
        }
        let newton = x - f / slope;
        // A Newton correction below round-off of x: f is at its noise floor.
        if slope.is_finite() && (newton - x).abs() <= 4.0 * f64::EPSILON * x.abs() {
            return newton.clamp(lo, hi);
        }
        x = if slope.is_finite() && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn copper() -> JohnsonCookStrengthParameters {
        JohnsonCookStrengthParameters::OFHC_COPPER
    }

    #[test]
    fn bad_parameters_name_their_field() {
        let base = copper();
        let cases = [
            (JohnsonCookStrengthParameters { a: 0.0, ..base }, "a"),
            (JohnsonCookStrengthParameters { b: -1.0, ..base }, "b"),
            (JohnsonCookStrengthParameters { n: 0.0, ..base }, "n"),
            (JohnsonCookStrengthParameters { c: -0.1, ..base }, "c"),
            (JohnsonCookStrengthParameters { m: 0.0, ..base }, "m"),
            (
                JohnsonCookStrengthParameters {
                    reference_strain_rate: 0.0,
                    ..base
                },
                "reference_strain_rate",
            ),
            (
                JohnsonCookStrengthParameters {
                    room_temperature: f64::NAN,
                    ..base
                },
                "room_temperature",
            ),
            (
                JohnsonCookStrengthParameters {
                    melt_temperature: 300.0,
                    ..base
                },
                "melt_temperature",
            ),
        ];
        for (p, name) in cases {
            assert_eq!(JohnsonCookStrength::new(p).unwrap_err().parameter, name);
        }
    }

    #[test]
    fn quasi_static_room_temperature_virgin_yield_is_a() {
        let jc = JohnsonCookStrength::new(copper()).unwrap();
        assert_eq!(jc.yield_stress(0.0, 0.5, 250.0), 90e6);
        assert_eq!(jc.yield_stress(0.0, 1.0, 1356.0), 0.0);
    }
}
