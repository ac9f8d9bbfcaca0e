//! Grady–Kipp flaw-activation damage in the Benz & Asphaug (1995) form (numerics.md §9.2;
//! F §5.3.2, App. A.12): Weibull flaw seeding, activation, growth of D^{1/3} and its cap.
//! Pointwise, except the one-off seeding, which returns per-particle data and never sees
//! neighbours.

use super::degrade_tensile_part;
use crate::error::{positive, MaterialError};
use crate::rng::SplitMix64;
use tlsph_math::Tensor3;

/// Crack growth speed as a fraction of the longitudinal sound speed, c_g = 0.4 c_l
/// (numerics.md §9.2; Benz & Asphaug 1995).
pub const BENZ_ASPHAUG_CRACK_SPEED_RATIO: f64 = 0.4;

/// Grady–Kipp damage with explicit Weibull flaws (numerics.md §9.2 `[C]`, Benz & Asphaug 1995).
///
/// - Flaw density n(ε) = k ε^m per unit body measure (volume in 3D, area in 2D, length in 1D:
///   k and the `total_volume` passed to [`seed_flaws`](Self::seed_flaws) must use the same
///   length unit; F-A12: m = 8.5, k = 1.4e19 cm⁻² with Δx = 1 cm).
/// - A particle's flaws activate when ε_eff = σ1⁺/((1 − D)E) reaches their thresholds.
/// - Growth d(D^{1/3})/dt = n_act c_g/R_s, capped by D ≤ n_act/n_i and D ≤ 1.
/// - The tensile stress is degraded by (1 − D) as in §9.1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradyKipp {
    m: f64,
    k: f64,
}

impl GradyKipp {
    /// Builds the model from the Weibull exponent m > 0 (`m`) and coefficient k > 0 (`k`)
    /// \[flaws per unit body measure\].
    pub fn new(m: f64, k: f64) -> Result<Self, MaterialError> {
        Ok(Self {
            m: positive("m", m)?,
            k: positive("k", k)?,
        })
    }

    /// Weibull exponent m.
    pub fn m(&self) -> f64 {
        self.m
    }

    /// Weibull coefficient k.
    pub fn k(&self) -> f64 {
        self.k
    }

    /// Total number of flaws for a body of `n_particles`: N_f = ⌈N ln N⌉, at least 1 for N ≥ 1
    /// (numerics.md §9.2; N ln N draws cover every particle on average, coupon collector).
    pub fn flaw_count(n_particles: usize) -> usize {
        match n_particles {
            0 => 0,
            1 => 1,
            n => ((n as f64) * (n as f64).ln()).ceil() as usize,
        }
    }

    /// Activation strain of flaw j (1-based) in a body of measure V: ε_j = (j/(kV))^{1/m}
    /// (inverse of the Weibull law n(ε) V = j; numerics.md §9.2).
    #[inline]
    pub fn activation_strain(&self, flaw: usize, total_volume: f64) -> f64 {
        (flaw as f64 / (self.k * total_volume)).powf(1.0 / self.m)
    }

    /// Seeds N_f = [`flaw_count`](Self::flaw_count)(N) flaws over N particles (numerics.md §9.2):
    /// flaw j = 1 … N_f gets ε_j = (j/(kV))^{1/m} and goes to a particle drawn uniformly by a
    /// SplitMix64 generator started from `seed`. Returns each particle's activation strains in
    /// ascending order. The same (N, V, seed) always gives the same flaws.
    ///
    /// Exactly N_f flaws are drawn, so on average about one particle receives none and can never
    /// damage; Benz & Asphaug instead keep drawing until every particle has a flaw.
    pub fn seed_flaws(&self, n_particles: usize, total_volume: f64, seed: u64) -> Vec<Vec<f64>> {
        let mut flaws = vec![Vec::new(); n_particles];
        if n_particles == 0 {
            return flaws;
        }
        let mut rng = SplitMix64::new(seed);
        for j in 1..=Self::flaw_count(n_particles) {
            flaws[rng.below(n_particles)].push(self.activation_strain(j, total_volume));
        }
        flaws
    }

    /// Effective tensile strain ε_eff = σ1⁺/((1 − D)E) (numerics.md §9.2) from the maximum
    /// principal stress σ1 \[Pa\], the current damage D and Young's modulus E \[Pa\]. Zero in
    /// compression; +∞ for a fully damaged point under tension.
    #[inline]
    pub fn effective_strain(max_principal_stress: f64, damage: f64, youngs_modulus: f64) -> f64 {
        let tension = max_principal_stress.max(0.0);
        if tension == 0.0 {
            return 0.0;
        }
        let intact = 1.0 - damage.clamp(0.0, 1.0);
        if intact == 0.0 {
            f64::INFINITY
        } else {
            tension / (intact * youngs_modulus)
        }
    }

    /// Number of active flaws n_act = #{ε_j ≤ ε_eff} of one particle, given its activation
    /// strains in ascending order (as returned by [`seed_flaws`](Self::seed_flaws)).
    #[inline]
    pub fn active_flaws(activation_strains: &[f64], effective_strain: f64) -> usize {
        activation_strains.partition_point(|&threshold| threshold <= effective_strain)
    }

    /// Damage cap min(n_act/n_i, 1) (numerics.md §9.2): a particle with n_i flaws, n_act of
    /// them active, cannot be damaged beyond the active fraction. Zero when n_i = 0.
    #[inline]
    pub fn damage_cap(active_flaws: usize, total_flaws: usize) -> f64 {
        if total_flaws == 0 {
            0.0
        } else {
            (active_flaws as f64 / total_flaws as f64).min(1.0)
        }
    }

    /// Growth rate of the cube root of damage, d(D^{1/3})/dt = n_act c_g/R_s \[1/s\]
    /// (numerics.md §9.2, Benz & Asphaug 1995), or 0 once D has reached the cap
    /// min(n_act/n_i, 1). `crack_speed` is c_g \[m/s\] (0.4 c_l, see
    /// [`BENZ_ASPHAUG_CRACK_SPEED_RATIO`]), `particle_radius` R_s = ½Δx \[m\].
    ///
    /// The rate is of D^{1/3}, not of D: dD/dt = 3D^{2/3}·(this) vanishes at D = 0, so the
    /// solver must integrate D^{1/3} (see [`advance_damage`](Self::advance_damage)).
    #[inline]
    pub fn damage_rate(
        &self,
        active_flaws: usize,
        total_flaws: usize,
        crack_speed: f64,
        particle_radius: f64,
        damage: f64,
    ) -> f64 {
        if damage >= Self::damage_cap(active_flaws, total_flaws) {
            return 0.0;
        }
        active_flaws as f64 * crack_speed / particle_radius
    }

    /// One explicit step of the growth law: D^{1/3} ← D^{1/3} + Δt·n_act c_g/R_s, then the cap
    /// (numerics.md §9.2). Damage never decreases: if the cap has fallen below D (flaws
    /// deactivated on unloading) D is kept.
    #[inline]
    pub fn advance_damage(
        &self,
        damage: f64,
        active_flaws: usize,
        total_flaws: usize,
        crack_speed: f64,
        particle_radius: f64,
        dt: f64,
    ) -> f64 {
        let rate = self.damage_rate(
            active_flaws,
            total_flaws,
            crack_speed,
            particle_radius,
            damage,
        );
        if rate == 0.0 {
            return damage;
        }
        let grown = (damage.max(0.0).cbrt() + rate * dt).powi(3);
        grown
            .min(Self::damage_cap(active_flaws, total_flaws))
            .max(damage)
    }

    /// Damaged stress: positive principal stresses × (1 − D) (numerics.md §9.2 "as in 9.1").
    #[inline]
    pub fn degrade(&self, stress: &Tensor3, damage: f64) -> Tensor3 {
        degrade_tensile_part(stress, damage)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_parameters_name_their_field() {
        assert_eq!(GradyKipp::new(0.0, 1.0).unwrap_err().parameter, "m");
        assert_eq!(GradyKipp::new(8.5, -1.0).unwrap_err().parameter, "k");
    }

    #[test]
    fn flaw_counts() {
        assert_eq!(GradyKipp::flaw_count(0), 0);
        assert_eq!(GradyKipp::flaw_count(1), 1);
        // 100 ln 100 = 460.517… → 461.
        assert_eq!(GradyKipp::flaw_count(100), 461);
    }
}
