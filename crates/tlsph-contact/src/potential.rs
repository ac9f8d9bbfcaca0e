//! The potential-type particle contact law of numerics.md §12.2 `[C]` (after Vignjevic et al.):
//! one pair of particles at distance r. Pointwise; knows nothing about which pairs exist.
//!
//! For I in body A and K in body B, r = |x_I − x_K|, d0 = ½(Δx_A + Δx_B),
//! h_c = ½(h_A + h_B), M* = min(M_A, M_B) with M = K_eff + 4G/3:
//!
//! f_I = a M* d0^{d−1} [(W(r, h_c)/W(d0, h_c))ⁿ − 1]₊ (x_I − x_K)/r,   f_K = −f_I.
//!
//! The force is the gradient of the pair potential φ(r) = a M* d0^{d−1} ∫_r^{d0} [(W/W0)ⁿ − 1] ds,
//! so a solver can book it as stored energy and total energy closes.

use tlsph_kernels::{AnyKernel, Kernel};

/// 8-point Gauss–Legendre nodes and weights on [−1, 1] (exact for polynomials of degree 15:
/// the cubic-spline integrand (W/W0)⁴ − 1 is of degree 12 on each kernel piece).
const GAUSS_NODES: [f64; 8] = [
    -0.960_289_856_497_536_3,
    -0.796_666_477_413_626_7,
    -0.525_532_409_916_329,
    -0.183_434_642_495_649_8,
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
const GAUSS_WEIGHTS: [f64; 8] = [
    0.101_228_536_290_376_3,
    0.222_381_034_453_374_5,
    0.313_706_645_877_887_3,
    0.362_683_783_378_362,
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// Exponent n as an integer power when it is one (every Reveles deck uses 4).
#[derive(Debug, Clone, Copy)]
enum Power {
    Integer(i32),
    Real(f64),
}

impl Power {
    fn new(exponent: f64) -> Self {
        if exponent.fract() == 0.0 && exponent.abs() < 64.0 {
            Power::Integer(exponent as i32)
        } else {
            Power::Real(exponent)
        }
    }

    #[inline]
    fn apply(self, x: f64) -> f64 {
        match self {
            Power::Integer(n) => x.powi(n),
            Power::Real(n) => x.powf(n),
        }
    }
}

/// The law evaluated at one distance r < d0 (numerics.md §12.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PotentialPairState {
    /// Repulsive force magnitude f(r) = a M* d0^{d−1} [(W(r)/W0)ⁿ − 1] ≥ 0 \[N\].
    pub force: f64,
    /// Pair potential φ(r) = ∫_r^{d0} f ds \[J\] (per unit depth in 2D).
    pub potential: f64,
    /// Tangent stiffness max(−df/dr, f/r) for the time-step vote \[N/m\].
    pub stiffness: f64,
}

/// Contact law of one pair of bodies (numerics.md §12.2) with W(d0, h_c) cached.
#[derive(Debug, Clone, Copy)]
pub struct PotentialLaw {
    kernel: AnyKernel,
    d0: f64,
    coefficient: f64,
    exponent: f64,
    power: Power,
    /// 1 / W(d0, h_c).
    inv_w0: f64,
    /// Normal stiffness at first touch, −df/dr at r = d0 \[N/m\].
    touch_stiffness: f64,
    /// Squared reference-distance exclusion of self-contact (0 between different bodies).
    exclusion_sq: f64,
}

impl PotentialLaw {
    /// The law with the pair kernel (smoothing length h_c = ½(h_A + h_B)), contact distance
    /// `d0` (W(d0) > 0 required), `coefficient` a M* d0^{d−1} \[N\] and exponent n ≥ 1.
    /// `exclusion` is for self-contact: pairs closer than it in the reference configuration
    /// (the kernel support 2h) are the body's own continuum and never in contact; 0 between
    /// different bodies.
    pub fn new(
        kernel: AnyKernel,
        d0: f64,
        coefficient: f64,
        exponent: f64,
        exclusion: f64,
    ) -> Self {
        let w0 = kernel.value(d0);
        Self {
            kernel,
            d0,
            coefficient,
            exponent,
            power: Power::new(exponent),
            inv_w0: 1.0 / w0,
            touch_stiffness: coefficient * exponent * (-kernel.derivative(d0)).max(0.0) / w0,
            exclusion_sq: exclusion * exclusion,
        }
    }

    /// Contact distance d0: the force acts only for r < d0 \[m\].
    pub fn d0(&self) -> f64 {
        self.d0
    }

    /// Normal stiffness at first touch, −df/dr at r = d0 \[N/m\]: the time-step vote of a
    /// pair that is not yet touching but may touch within the next step.
    pub fn touch_stiffness(&self) -> f64 {
        self.touch_stiffness
    }

    /// Whether two particles of one body, `reference_distance_sq` = |X_I − X_K|² apart in
    /// the reference configuration, may contact: only beyond the exclusion (and never a
    /// particle with itself).
    pub fn allows_self_pair(&self, reference_distance_sq: f64) -> bool {
        reference_distance_sq >= self.exclusion_sq.max(f64::MIN_POSITIVE)
    }

    /// g(s) = (W(s)/W0)ⁿ − 1, the dimensionless force shape.
    #[inline]
    fn shape(&self, s: f64) -> f64 {
        self.power.apply(self.kernel.value(s) * self.inv_w0) - 1.0
    }

    /// Force, potential φ(r) = c ∫_r^{d0} g ds (Gauss–Legendre, split at the cubic spline's
    /// break point q = 1) and stiffness max(−df/dr, f/r) at distance r < d0.
    pub fn evaluate(&self, r: f64) -> PotentialPairState {
        let ratio = self.kernel.value(r) * self.inv_w0;
        let force = self.coefficient * (self.power.apply(ratio) - 1.0);
        // −df/dr = c n (W/W0)^{n−1} (−W'(r))/W0.
        let normal = self.coefficient
            * self.exponent
            * self.power.apply(ratio)
            * (-self.kernel.derivative(r)).max(0.0)
            / (self.kernel.value(r)).max(f64::MIN_POSITIVE);
        let transverse = if r > 0.0 { force / r } else { 0.0 };
        let h = self.kernel.smoothing_length();
        let potential = if r < h && h < self.d0 {
            self.integrate(r, h) + self.integrate(h, self.d0)
        } else {
            self.integrate(r, self.d0)
        };
        PotentialPairState {
            force,
            potential: self.coefficient * potential,
            stiffness: normal.max(transverse),
        }
    }

    fn integrate(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        GAUSS_NODES
            .iter()
            .zip(GAUSS_WEIGHTS)
            .map(|(x, w)| w * self.shape(mid + half * x))
            .sum::<f64>()
            * half
    }
}
