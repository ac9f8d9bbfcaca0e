//! Taylor's one-dimensional plastic-wave model of a rod striking a rigid anvil (Taylor 1948;
//! the model behind the "theoretical analysis" that Reveles §6.2.2 quotes for R-P6).
//!
//! A plastic front runs from the anvil into the rod. Material crossing it is brought to rest
//! and its cross-section grows from A0 to A, at constant volume. With e = 1 − A0/A, mass
//! conservation across the front gives U = (1 − e)(v + U) (U the front speed, v the speed of
//! the undeformed part), and momentum conservation with the flow stress σ on both sides,
//! ρ A0 (v + U) v = σ (A − A0), gives
//!
//! ρ v² / σ = e² / (1 − e),   so   e = (√(q² + 4q) − q) / 2,  q = ρ v² / σ.
//!
//! At impact (v = V) this fixes the area ratio A/A0 = 1/(1 − e) of the foot, the same for a
//! plane-strain slab (width ratio W/W0 = A/A0) and for an axisymmetric rod (diameter ratio
//! D/D0 = √(A/A0)). That kinematics-independence is what the R-P6 report uses to compare its
//! 2D and 3D runs. With linear hardening the flow stress is taken at the foot's own true
//! strain, σ = σ_y + E_p ln(A/A0), and the area ratio solved self-consistently.
//! The model neglects the elastic precursor and radial inertia, so it is an estimate.

/// Inputs of the model (SI units).
#[derive(Debug, Clone, Copy)]
pub struct TaylorImpact {
    /// Density ρ \[kg/m³\].
    pub density: f64,
    /// Impact speed V \[m/s\].
    pub velocity: f64,
    /// Initial yield stress σ_y \[Pa\].
    pub yield_stress: f64,
    /// Linear plastic hardening modulus E_p = dσ/dε̄p \[Pa\] (0: perfectly plastic).
    pub plastic_modulus: f64,
}

impl TaylorImpact {
    /// Area ratio A/A0 = 1/(1 − e) for flow stress `stress`, from ρV²/σ = e²/(1 − e).
    pub fn area_ratio_at_stress(&self, stress: f64) -> f64 {
        let q = self.density * self.velocity * self.velocity / stress;
        let e = 0.5 * ((q * q + 4.0 * q).sqrt() - q);
        1.0 / (1.0 - e)
    }

    /// Flow stress at the true strain ln(A/A0) of a foot with area ratio `ratio` \[Pa\].
    pub fn flow_stress(&self, ratio: f64) -> f64 {
        self.yield_stress + self.plastic_modulus * ratio.ln()
    }

    /// Foot area ratio A/A0 solved self-consistently with the hardening, by bisection on
    /// r − A/A0(σ(r)) over [1, A/A0(σ_y)] (the residual is negative at 1 and non-negative at
    /// the perfectly plastic ratio, and increases monotonically in between).
    pub fn foot_area_ratio(&self) -> f64 {
        let residual = |r: f64| r - self.area_ratio_at_stress(self.flow_stress(r));
        let (mut lo, mut hi) = (1.0, self.area_ratio_at_stress(self.yield_stress));
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if residual(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// Final foot width of a plane-strain slab of initial width `width0` \[m\].
    pub fn plane_strain_foot_width(&self, width0: f64) -> f64 {
        width0 * self.foot_area_ratio()
    }

    /// Final foot diameter of an axisymmetric rod of initial diameter `diameter0` \[m\].
    pub fn axisymmetric_foot_diameter(&self, diameter0: f64) -> f64 {
        diameter0 * self.foot_area_ratio().sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn copper(plastic_modulus: f64) -> TaylorImpact {
        TaylorImpact {
            density: 8990.0,
            velocity: 100.0,
            yield_stress: 90e6,
            plastic_modulus,
        }
    }

    #[test]
    fn unit_impact_number_gives_the_golden_ratio() {
        // q = ρV²/σ = 1: e² + e − 1 = 0, e = (√5 − 1)/2 = 1/φ and A/A0 = 1/(1 − e) = φ²,
        // φ = (1 + √5)/2, so a round rod's diameter grows by exactly φ.
        let model = TaylorImpact {
            density: 1.0,
            velocity: 1.0,
            yield_stress: 1.0,
            plastic_modulus: 0.0,
        };
        let golden = 0.5 * (1.0 + 5f64.sqrt());
        assert_relative_eq!(
            model.foot_area_ratio(),
            golden * golden,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            model.axisymmetric_foot_diameter(2.0),
            2.0 * golden,
            max_relative = 1e-12
        );
    }

    #[test]
    fn hardening_solution_satisfies_the_jump_conditions() {
        let model = copper(292e6);
        let r = model.foot_area_ratio();
        let e = 1.0 - 1.0 / r;
        let sigma = model.flow_stress(r);
        // ρV²/σ(r) = e²/(1 − e) at the solution.
        assert_relative_eq!(
            8990.0 * 1e4 / sigma,
            e * e / (1.0 - e),
            max_relative = 1e-10
        );
        // Hardening makes the foot smaller than the perfectly plastic one, never below 1.
        assert!(r > 1.0 && r < copper(0.0).foot_area_ratio());
    }

    #[test]
    fn no_impact_no_foot() {
        let mut model = copper(292e6);
        model.velocity = 0.0;
        assert_relative_eq!(model.foot_area_ratio(), 1.0, max_relative = 1e-12);
    }

    #[test]
    fn plane_strain_and_axisymmetric_share_the_area_ratio() {
        let model = copper(292e6);
        let w = model.plane_strain_foot_width(1.0);
        let d = model.axisymmetric_foot_diameter(1.0);
        assert_relative_eq!(w, d * d, max_relative = 1e-12);
    }
}
