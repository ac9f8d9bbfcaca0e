//! Peerlings-type linear softening damage with a history variable (numerics.md §9.1; F 5.3–5.4).
//! Pointwise only.

use super::degrade_tensile_part;
use crate::error::{positive, MaterialError};
use tlsph_math::Tensor3;

/// Linear softening (numerics.md §9.1; F 5.3–5.4 with the history variable `[C]`):
/// D(κ) = 0 for κ ≤ κ0, D = (κc/κ)(κ − κ0)/(κc − κ0) for κ0 < κ < κc, D = 1 for κ ≥ κc,
/// κ = max over history of the maximum principal strain. In uniaxial tension
/// σ = (1 − D)Eε falls linearly from Eκ0 at κ0 to 0 at κc. F-A13: κ0 = 0.001, κc = 0.01.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeerlingsSoftening {
    kappa0: f64,
    kappa_c: f64,
}

impl PeerlingsSoftening {
    /// Builds the model from the damage threshold κ0 > 0 (`kappa0`) and the critical strain
    /// κc > κ0 (`kappa_c`).
    pub fn new(kappa0: f64, kappa_c: f64) -> Result<Self, MaterialError> {
        let kappa0 = positive("kappa0", kappa0)?;
        if !(kappa_c.is_finite() && kappa_c > kappa0) {
            return Err(MaterialError {
                parameter: "kappa_c",
                value: kappa_c,
                expected: "a finite strain greater than kappa0",
            });
        }
        Ok(Self { kappa0, kappa_c })
    }

    /// Damage threshold κ0.
    pub fn kappa0(&self) -> f64 {
        self.kappa0
    }

    /// Critical strain κc (D = 1).
    pub fn kappa_c(&self) -> f64 {
        self.kappa_c
    }

    /// History update κ ← max(κ, ε_max) (numerics.md §9.1 `[C]`): damage never heals
    /// (numerics.md §17 pitfall 16). ε_max is the maximum principal strain, e.g.
    /// [`max_principal_value`](crate::max_principal_value) of the strain tensor.
    #[inline]
    pub fn update_history(kappa: f64, max_principal_strain: f64) -> f64 {
        kappa.max(max_principal_strain)
    }

    /// Damage D(κ) ∈ \[0, 1\] (numerics.md §9.1; F 5.4).
    #[inline]
    pub fn damage(&self, kappa: f64) -> f64 {
        if kappa <= self.kappa0 {
            0.0
        } else if kappa >= self.kappa_c {
            1.0
        } else {
            (self.kappa_c / kappa) * (kappa - self.kappa0) / (self.kappa_c - self.kappa0)
        }
    }

    /// The history κ at which the law reaches damage `damage` = D ∈ \[0, 1\], the inverse of
    /// F 5.4 on κ0 ≤ κ ≤ κc: D(κc − κ0)κ = κc(κ − κ0) gives κ = κc κ0 / (κc − D(κc − κ0)).
    /// D = 0 gives κ0 (the threshold), D = 1 gives κc. A particle started with damage D and
    /// this κ reloads on the secant σ = (1 − D)Eε up to ε = κ, then softens like the virgin
    /// material. `None` for a D outside \[0, 1\] or not finite.
    pub fn history_for_damage(&self, damage: f64) -> Option<f64> {
        if !(0.0..=1.0).contains(&damage) {
            return None;
        }
        let (k0, kc) = (self.kappa0, self.kappa_c);
        Some(kc * k0 / (kc - damage * (kc - k0)))
    }

    /// Damaged stress: positive principal stresses × (1 − D), compressive ones unchanged
    /// (numerics.md §9.1 `[C]`; F 5.3 "(1 − D)E in tension, E in compression").
    #[inline]
    pub fn degrade(&self, stress: &Tensor3, damage: f64) -> Tensor3 {
        degrade_tensile_part(stress, damage)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn history_for_damage_inverts_the_law() {
        // F-A13's law: D(κ(D)) = D across [0, 1] to rounding, the ends at κ0 and κc, and
        // values outside [0, 1] refused.
        let law = PeerlingsSoftening::new(0.001, 0.01).unwrap();
        assert_eq!(law.history_for_damage(0.0), Some(0.001));
        assert!((law.history_for_damage(1.0).unwrap() - 0.01).abs() < 1e-15);
        for i in 0..=100 {
            let d = i as f64 / 100.0;
            let kappa = law.history_for_damage(d).unwrap();
            assert!(
                (law.damage(kappa) - d).abs() < 1e-14,
                "D = {d}: κ = {kappa}"
            );
        }
        for bad in [-1e-9, 1.0 + 1e-9, f64::NAN, f64::INFINITY] {
            assert_eq!(law.history_for_damage(bad), None);
        }
    }

    #[test]
    fn bad_parameters_name_their_field() {
        assert_eq!(
            PeerlingsSoftening::new(0.0, 0.01).unwrap_err().parameter,
            "kappa0"
        );
        assert_eq!(
            PeerlingsSoftening::new(0.01, 0.01).unwrap_err().parameter,
            "kappa_c"
        );
    }
}
