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

    /// The compressions μ nearest the reference state at which the cold bulk modulus
    /// dp/dμ at E_v = 0 (numerics.md §8.7: C1 + 3C3μ² in tension, C1 + 2C2μ + 3C3μ² in
    /// compression) falls to zero: `(tension, compression)`, each `None` when the modulus stays
    /// positive on that side (tension only over the physical range μ > −1). Beyond them the
    /// pressure falls as the material is compressed, or rises as it expands: the fit is used
    /// outside its range, a wave there is unstable, and the time step's sound speed is 0.
    pub fn stiffness_limits(&self) -> (Option<f64>, Option<f64>) {
        let [_, c1, c2, c3, ..] = self.c;
        // Tension: C1 + 3C3μ² = 0 at μ = −sqrt(C1/(−3C3)) when C3 < 0.
        let tension = (c3 < 0.0)
            .then(|| -(c1 / (-3.0 * c3)).sqrt())
            .filter(|&mu| mu > -1.0);
        // Compression: the smallest positive root of 3C3μ² + 2C2μ + C1 (C1 > 0).
        let compression = smallest_positive_root(3.0 * c3, 2.0 * c2, c1);
        (tension, compression)
    }
}

/// The smallest positive root of aμ² + bμ + c with c > 0, or `None`; the roots are taken as
/// q/a and c/q with q = −(b + sign(b) sqrt(b² − 4ac))/2, which loses no digits to cancellation.
fn smallest_positive_root(a: f64, b: f64, c: f64) -> Option<f64> {
    if a == 0.0 {
        return (b < 0.0).then(|| -c / b);
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 {
        return None;
    }
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    [q / a, c / q]
        .into_iter()
        .filter(|&mu| mu > 0.0 && mu.is_finite())
        .min_by(f64::total_cmp)
}
