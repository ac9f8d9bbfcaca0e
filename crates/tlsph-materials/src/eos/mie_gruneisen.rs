//! Mie–Grüneisen equation of state with a linear-to-cubic U_s–u_p shock Hugoniot as reference
//! (numerics.md §8.8; R 6.24–6.25; LS-DYNA *EOS_GRUNEISEN). Pointwise only.

use crate::error::{finite, positive, MaterialError};

/// Scene-file parameters of [`MieGruneisen`] (numerics.md §8.8).
///
/// No `Default`: these are material data (M-CU9, M-AL-GR, M-PMMA in problems.md §1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MieGruneisenParameters {
    /// Reference density ρ0 \[kg/m³\] (> 0).
    pub reference_density: f64,
    /// Intercept C of the U_s–u_p relation (bulk sound speed) \[m/s\] (> 0).
    pub sound_speed: f64,
    /// First slope S1 of the U_s–u_p relation.
    pub s1: f64,
    /// Second coefficient S2 (U_s = C + S1 u_p + S2 u_p²/U_s + S3 u_p³/U_s²).
    pub s2: f64,
    /// Third coefficient S3.
    pub s3: f64,
    /// Grüneisen gamma γ0.
    pub gamma0: f64,
    /// First-order volume correction a to γ0 (R §6.3.6 calls it "b").
    pub a: f64,
}

/// Mie–Grüneisen EOS (numerics.md §8.8; R 6.24–6.25), pressure compression positive:
///
/// - compressed (μ > 0):
///   p = ρ0C²μ\[1 + (1 − γ0/2)μ − (a/2)μ²\] / D(μ)² + (γ0 + aμ) E_v,
///   D(μ) = 1 − (S1 − 1)μ − S2 μ²/(μ + 1) − S3 μ³/(μ + 1)²;
/// - expanded (μ ≤ 0): p = ρ0C²μ + (γ0 + aμ) E_v;
///
/// with μ = ρ/ρ0 − 1 and E_v = ρ0 e the internal energy per reference volume \[J/m³\].
///
/// The compressed branch is exactly p = p_H(μ) + Γ(μ)(E_v − E_H(μ)) with Γ = γ0 + aμ, the
/// Hugoniot pressure p_H = ρ0C²μ(1 + μ)/D² (see [`hugoniot_pressure`](Self::hugoniot_pressure))
/// and the Hugoniot energy E_H = ½ p_H μ/(1 + μ) (Rankine–Hugoniot), so it reproduces the shock
/// Hugoniot exactly, a-term included.
///
/// Denominator guard (our choice, documented here): D vanishes at the limiting compression
/// μ_lim (first root; about 2.04 for copper, 2.96 for aluminium), where the Hugoniot pressure is
/// infinite. For μ ≥ μ_lim [`pressure`](Self::pressure) returns `+∞` instead of evaluating a
/// formula that would change sign; the solver's non-finite check then stops the run and names
/// the particle. Compressions near μ_lim mean pressures of tens of TPa and a broken step; a
/// finite clamp would hide that.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MieGruneisen {
    p: MieGruneisenParameters,
    /// ρ0C² \[Pa\].
    rho_c2: f64,
    /// First positive root of D(μ), or +∞.
    compression_limit: f64,
}

impl MieGruneisen {
    /// Validates and stores the parameters: `reference_density` > 0, `sound_speed` > 0 and
    /// `s1`, `s2`, `s3`, `gamma0`, `a` finite (errors name the field). Also locates the limiting
    /// compression μ_lim (first root of the Hugoniot denominator).
    pub fn new(parameters: MieGruneisenParameters) -> Result<Self, MaterialError> {
        let p = parameters;
        positive("reference_density", p.reference_density)?;
        positive("sound_speed", p.sound_speed)?;
        finite("s1", p.s1)?;
        finite("s2", p.s2)?;
        finite("s3", p.s3)?;
        finite("gamma0", p.gamma0)?;
        finite("a", p.a)?;
        Ok(Self {
            p,
            rho_c2: p.reference_density * p.sound_speed * p.sound_speed,
            compression_limit: first_root_of_denominator(p.s1, p.s2, p.s3),
        })
    }

    /// The validated parameters.
    pub fn parameters(&self) -> &MieGruneisenParameters {
        &self.p
    }

    /// Limiting compression μ_lim: the first μ > 0 where D(μ) = 0, or +∞ if D stays positive
    /// (numerics.md §8.8 guard). For S2 = S3 = 0 it is 1/(S1 − 1).
    pub fn compression_limit(&self) -> f64 {
        self.compression_limit
    }

    /// Hugoniot denominator D(μ) = 1 − (S1 − 1)μ − S2 μ²/(μ + 1) − S3 μ³/(μ + 1)²
    /// (numerics.md §8.8).
    #[inline]
    pub fn denominator(&self, mu: f64) -> f64 {
        let q = mu / (mu + 1.0);
        1.0 - (self.p.s1 - 1.0) * mu - self.p.s2 * mu * q - self.p.s3 * mu * q * q
    }

    /// Grüneisen coefficient of the energy term, γ0 + aμ (numerics.md §8.8).
    #[inline]
    pub fn gruneisen_coefficient(&self, mu: f64) -> f64 {
        self.p.gamma0 + self.p.a * mu
    }

    /// Pressure p(μ, E_v) \[Pa\], compression positive (numerics.md §8.8; R 6.24–6.25).
    /// Returns `+∞` for μ ≥ [`compression_limit`](Self::compression_limit) (see the type docs).
    #[inline]
    pub fn pressure(&self, mu: f64, energy_per_reference_volume: f64) -> f64 {
        let energy_term = self.gruneisen_coefficient(mu) * energy_per_reference_volume;
        if mu <= 0.0 {
            return self.rho_c2 * mu + energy_term;
        }
        let d = self.denominator(mu);
        if mu >= self.compression_limit || d <= 0.0 {
            return f64::INFINITY;
        }
        let numerator = 1.0 + (1.0 - 0.5 * self.p.gamma0) * mu - 0.5 * self.p.a * mu * mu;
        self.rho_c2 * mu * numerator / (d * d) + energy_term
    }

    /// (∂p/∂μ, ∂p/∂E_v) of [`pressure`](Self::pressure) (see
    /// [`super::EquationOfState::isentropic_bulk_modulus`]). Compressed, with N(μ) = 1 +
    /// (1 − γ0/2)μ − (a/2)μ²: ∂p/∂μ = ρ0C²[(N + μN′)/D² − 2μN D′/D³] + a E_v, where
    /// D′ = −(S1 − 1) − S2 μ(2 + μ)/(1 + μ)² − S3 μ²(3 + μ)/(1 + μ)³; expanded: ρ0C² + a E_v;
    /// ∂p/∂E_v = γ0 + aμ. `+∞` beyond the limiting compression, as the pressure.
    #[inline]
    pub fn pressure_derivatives(&self, mu: f64, energy_per_reference_volume: f64) -> (f64, f64) {
        let gamma = self.gruneisen_coefficient(mu);
        let energy_slope = self.p.a * energy_per_reference_volume;
        if mu <= 0.0 {
            return (self.rho_c2 + energy_slope, gamma);
        }
        let d = self.denominator(mu);
        if mu >= self.compression_limit || d <= 0.0 {
            return (f64::INFINITY, gamma);
        }
        let (gamma0, a) = (self.p.gamma0, self.p.a);
        let n = 1.0 + (1.0 - 0.5 * gamma0) * mu - 0.5 * a * mu * mu;
        let dn = (1.0 - 0.5 * gamma0) - a * mu;
        let one = 1.0 + mu;
        let dd = -(self.p.s1 - 1.0)
            - self.p.s2 * mu * (2.0 + mu) / (one * one)
            - self.p.s3 * mu * mu * (3.0 + mu) / (one * one * one);
        let slope = self.rho_c2 * ((n + mu * dn) / (d * d) - 2.0 * mu * n * dd / (d * d * d));
        (slope + energy_slope, gamma)
    }

    /// ρ0C² \[Pa\], the bulk modulus at the reference state (numerics.md §7 sound speed).
    #[inline]
    pub fn bulk_modulus_at_reference(&self) -> f64 {
        self.rho_c2
    }

    /// Shock-Hugoniot pressure p_H(μ) = ρ0C²μ(1 + μ)/D(μ)² \[Pa\] for μ > 0, which equals
    /// ρ0 U_s u_p on the shock relation of numerics.md §8.8 (`+∞` beyond the limiting
    /// compression). For μ ≤ 0 it returns the reference curve the EOS uses in tension, ρ0C²μ
    /// (not a shock state).
    pub fn hugoniot_pressure(&self, mu: f64) -> f64 {
        if mu <= 0.0 {
            return self.rho_c2 * mu;
        }
        let d = self.denominator(mu);
        if mu >= self.compression_limit || d <= 0.0 {
            return f64::INFINITY;
        }
        self.rho_c2 * mu * (1.0 + mu) / (d * d)
    }

    /// Internal energy per reference volume on the Hugoniot, E_H = ρ0 e_H with
    /// e_H = ½ p_H (v0 − v) (Rankine–Hugoniot energy jump from rest, e0 = 0, p0 = 0), i.e.
    /// E_H = ½ p_H μ/(1 + μ) \[J/m³\] (= ½ ρ0 u_p²). Zero for μ ≤ 0.
    pub fn hugoniot_energy(&self, mu: f64) -> f64 {
        if mu <= 0.0 {
            return 0.0;
        }
        0.5 * self.hugoniot_pressure(mu) * mu / (1.0 + mu)
    }

    /// Shock velocity U_s \[m/s\] for particle velocity u_p ≥ 0 \[m/s\] from
    /// U_s = C + S1 u_p + S2 u_p²/U_s + S3 u_p³/U_s² (numerics.md §8.8). Closed form for
    /// S2 = S3 = 0, otherwise Newton's method from U_s = C + S1 u_p (converges in a few steps
    /// while u_p/U_s is well below 1).
    pub fn shock_velocity(&self, particle_velocity: f64) -> f64 {
        let (c, s1, s2, s3) = (self.p.sound_speed, self.p.s1, self.p.s2, self.p.s3);
        let u = particle_velocity;
        let mut us = c + s1 * u;
        if s2 == 0.0 && s3 == 0.0 {
            return us;
        }
        for _ in 0..50 {
            let (r, r2) = (u / us, (u / us) * (u / us));
            let h = us - c - s1 * u - s2 * u * r - s3 * u * r2;
            let dh = 1.0 + s2 * r2 + 2.0 * s3 * r2 * r;
            let step = h / dh;
            us -= step;
            if step.abs() <= 4.0 * f64::EPSILON * us.abs() {
                break;
            }
        }
        us
    }
}

/// First positive root μ of D(μ), or +∞. With η = μ/(1 + μ) ∈ (0, 1),
/// D = (1 + μ) g(η), g(η) = 1 − S1η − S2η² − S3η³, so the root is found on the bounded η
/// interval by a sign scan and bisection, then mapped back with μ = η/(1 − η).
fn first_root_of_denominator(s1: f64, s2: f64, s3: f64) -> f64 {
    // A cubic changes sign at most three times; 4096 samples resolve any root pair of a
    // physical fit. The grid stops short of η = 1 (μ = ∞).
    const SAMPLES: usize = 4096;
    let g = |eta: f64| 1.0 - eta * (s1 + eta * (s2 + eta * s3));
    let mut lo = 0.0;
    for i in 1..SAMPLES {
        let hi = i as f64 / SAMPLES as f64;
        if g(hi) <= 0.0 {
            let (mut a, mut b) = (lo, hi);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                if mid <= a || mid >= b {
                    break;
                }
                if g(mid) > 0.0 {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            return a / (1.0 - a);
        }
        lo = hi;
    }
    f64::INFINITY
}

#[cfg(test)]
mod tests {
    use super::*;

    fn aluminium() -> MieGruneisenParameters {
        // M-AL-GR (problems.md §1).
        MieGruneisenParameters {
            reference_density: 2780.0,
            sound_speed: 5328.0,
            s1: 1.338,
            s2: 0.0,
            s3: 0.0,
            gamma0: 2.0,
            a: 0.48,
        }
    }

    #[test]
    fn limiting_compression_is_one_over_s1_minus_one() {
        let eos = MieGruneisen::new(aluminium()).unwrap();
        let expected = 1.0 / 0.338;
        assert!((eos.compression_limit() - expected).abs() < 1e-12 * expected);
        assert_eq!(eos.pressure(3.0, 0.0), f64::INFINITY);
        assert!(eos.pressure(2.9, 0.0).is_finite());
    }

    #[test]
    fn no_limit_when_the_denominator_stays_positive() {
        // S1 < 1: D = 1 + (1 − S1)μ never vanishes.
        let eos = MieGruneisen::new(MieGruneisenParameters {
            s1: 0.9,
            ..aluminium()
        })
        .unwrap();
        assert_eq!(eos.compression_limit(), f64::INFINITY);
    }

    #[test]
    fn bad_parameters_name_their_field() {
        let base = aluminium();
        for (p, name) in [
            (
                MieGruneisenParameters {
                    reference_density: 0.0,
                    ..base
                },
                "reference_density",
            ),
            (
                MieGruneisenParameters {
                    sound_speed: -1.0,
                    ..base
                },
                "sound_speed",
            ),
            (
                MieGruneisenParameters {
                    s2: f64::INFINITY,
                    ..base
                },
                "s2",
            ),
            (
                MieGruneisenParameters {
                    gamma0: f64::NAN,
                    ..base
                },
                "gamma0",
            ),
        ] {
            assert_eq!(MieGruneisen::new(p).unwrap_err().parameter, name);
        }
    }
}
