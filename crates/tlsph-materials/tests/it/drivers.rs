//! Material-point drivers: one point pushed along a prescribed velocity gradient with the
//! hypoelastic predictor (numerics.md §8.1) and a strength model's return map (§8.4–8.5).

use tlsph_materials::{JohnsonCookStrength, LinearElastic, PlasticReturn, VonMisesPlasticity};
use tlsph_math::{deviator, Tensor3};

/// State of one material point: Cauchy stress (tension positive) and ε̄p.
#[derive(Debug, Clone, Copy)]
pub struct Point {
    pub stress: Tensor3,
    pub plastic_strain: f64,
}

impl Point {
    pub fn virgin() -> Self {
        Self {
            stress: Tensor3::zeros(),
            plastic_strain: 0.0,
        }
    }

    /// Pressure p = −tr σ/3 (compression positive, numerics.md §0).
    pub fn pressure(&self) -> f64 {
        -self.stress.trace() / 3.0
    }

    /// Von Mises stress σ̄.
    pub fn equivalent_stress(&self) -> f64 {
        tlsph_math::von_mises(&self.stress)
    }
}

/// One step: elastic Jaumann predictor of the full stress, p kept from the predictor
/// (hypoelastic bulk response, numerics.md §8.1), deviator returned by `map`.
pub fn step(
    elastic: &LinearElastic,
    point: &Point,
    rate_of_deformation: &Tensor3,
    spin: &Tensor3,
    dt: f64,
    map: impl Fn(&Tensor3, f64) -> PlasticReturn,
) -> Point {
    let trial = elastic.jaumann_update(&point.stress, rate_of_deformation, spin, dt);
    let pressure = -trial.trace() / 3.0;
    let r = map(&deviator(&trial), point.plastic_strain);
    Point {
        stress: r.deviator - Tensor3::identity() * pressure,
        plastic_strain: point.plastic_strain + r.plastic_strain_increment,
    }
}

/// Von Mises step.
pub fn step_von_mises(
    elastic: &LinearElastic,
    plastic: &VonMisesPlasticity,
    point: &Point,
    rate_of_deformation: &Tensor3,
    spin: &Tensor3,
    dt: f64,
) -> Point {
    let g = elastic.shear_modulus();
    step(elastic, point, rate_of_deformation, spin, dt, |s, ep| {
        plastic.return_map(s, g, ep)
    })
}

/// Johnson–Cook step at room temperature with the rate taken from D.
pub fn step_johnson_cook(
    elastic: &LinearElastic,
    jc: &JohnsonCookStrength,
    point: &Point,
    rate_of_deformation: &Tensor3,
    dt: f64,
    iterate: bool,
) -> Point {
    let g = elastic.shear_modulus();
    let rate = tlsph_materials::equivalent_strain_rate(rate_of_deformation);
    let t_room = jc.parameters().room_temperature;
    step(
        elastic,
        point,
        rate_of_deformation,
        &Tensor3::zeros(),
        dt,
        |s, ep| jc.return_map(s, g, ep, rate, t_room, iterate),
    )
}

/// D = rate · e_x ⊗ e_x: uniaxial strain along x (numerics.md §8.1 "1D").
pub fn uniaxial_strain_rate(rate: f64) -> Tensor3 {
    let mut d = Tensor3::zeros();
    d[(0, 0)] = rate;
    d
}

/// Shear rate γ̇ in the x–y plane: D = γ̇/2 (e_x⊗e_y + e_y⊗e_x).
pub fn shear_rate(gamma_dot: f64) -> Tensor3 {
    let mut d = Tensor3::zeros();
    d[(0, 1)] = 0.5 * gamma_dot;
    d[(1, 0)] = 0.5 * gamma_dot;
    d
}

/// Spin of simple shear v_x = γ̇ y: W = ½(L − Lᵀ), W_xy = γ̇/2.
pub fn simple_shear_spin(gamma_dot: f64) -> Tensor3 {
    let mut w = Tensor3::zeros();
    w[(0, 1)] = 0.5 * gamma_dot;
    w[(1, 0)] = -0.5 * gamma_dot;
    w
}
