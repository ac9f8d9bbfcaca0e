//! Von Mises plasticity (numerics.md §8.4) driven along uniaxial-strain, pure-shear and
//! simple-shear paths and compared with hand-derived solutions.
//!
//! Uniaxial strain ε_xx = ε, ε_yy = ε_zz = 0 (numerics.md §8.1 "1D"), compression ε < 0:
//! - elastic: σ_xx = Mε, σ_yy = σ_zz = λε, so σ̄ = |σ_xx − σ_yy| = 2G|ε| and p = −Kε;
//! - yield onset at |ε_y| = σ_y/(2G) = σ_y(1 + ν)/E, where the axial stress is the Hugoniot
//!   elastic limit |σ_xx| = Mσ_y/(2G) = σ_y(1 − ν)/(1 − 2ν);
//! - after yield the deviatoric strain rate is ε̇̄ = (2/3)|ε̇| and σ̄ = σ_y + E_p ε̄p with
//!   dσ̄ = 3G(dε̄ − dε̄p) = E_p dε̄p, so dε̄p = 2G d|ε|/(3G + E_p), dσ̄ = 2G E_p d|ε|/(3G + E_p);
//!   with p = K|ε| and |σ_xx| = p + (2/3)σ̄ the post-yield slope is
//!   d|σ_xx|/d|ε| = K + (4/3)·G E_p/(3G + E_p) (K when E_p = 0, M as E_p → ∞).
//!   Radial return is exact for linear hardening on this proportional path, for any step.
//!
//! Pure shear D = γ̇/2(e_x⊗e_y + e_y⊗e_x), W = 0: τ = Gγ, σ̄ = √3 τ, yield at τ = σ_y/√3
//! (γ_y = σ_y/(√3 G)); after yield τ = σ_y/√3 + G E_p (γ − γ_y)/(3G + E_p),
//! ε̄p = √3 G(γ − γ_y)/(3G + E_p).

use super::drivers::{shear_rate, simple_shear_spin, step_von_mises, uniaxial_strain_rate, Point};
use approx::assert_relative_eq;
use tlsph_materials::{LinearElastic, VonMisesPlasticity};
use tlsph_math::Tensor3;

/// M-CU6 (problems.md §1): E 110 GPa, ν 0.343, σ_y 90 MPa, E_t 1.1 GPa.
fn copper() -> (LinearElastic, VonMisesPlasticity) {
    (
        LinearElastic::new(110e9, 0.343).unwrap(),
        VonMisesPlasticity::from_tangent_modulus(90e6, 110e9, 1.1e9).unwrap(),
    )
}

/// M-ST7X (problems.md §1): E 210 GPa, ν 0.33, σ_y 1 GPa, elastic–perfectly plastic.
fn steel() -> (LinearElastic, VonMisesPlasticity) {
    (
        LinearElastic::new(210e9, 0.33).unwrap(),
        VonMisesPlasticity::new(1e9, 0.0).unwrap(),
    )
}

fn check_uniaxial_strain(elastic: LinearElastic, plastic: VonMisesPlasticity) {
    let (g, k, m, nu) = (
        elastic.shear_modulus(),
        elastic.bulk_modulus(),
        elastic.longitudinal_modulus(),
        elastic.poisson_ratio(),
    );
    let (sy, ep_mod) = (plastic.initial_yield_stress(), plastic.plastic_modulus());
    let strain_at_yield = sy / (2.0 * g);
    assert_relative_eq!(
        strain_at_yield,
        sy * (1.0 + nu) / elastic.youngs_modulus(),
        max_relative = 1e-14
    );
    let hel = sy * (1.0 - nu) / (1.0 - 2.0 * nu);
    assert_relative_eq!(hel, m * strain_at_yield, max_relative = 1e-14);
    let slope = k + 4.0 / 3.0 * g * ep_mod / (3.0 * g + ep_mod);

    // Steps of ε_y/7.3 so that yield falls inside a step; 40 ε_y of compression in all.
    let d_eps = strain_at_yield / 7.3;
    let dt = 1e-7;
    let d = uniaxial_strain_rate(-d_eps / dt);
    let mut point = Point::virgin();
    let mut first_plastic = None;
    for i in 1..=292 {
        point = step_von_mises(&elastic, &plastic, &point, &d, &Tensor3::zeros(), dt);
        let strain = i as f64 * d_eps; // |ε|
        let sxx = -point.stress[(0, 0)];
        assert_relative_eq!(point.pressure(), k * strain, max_relative = 1e-10);
        if strain <= strain_at_yield * (1.0 - 1e-12) {
            assert_eq!(point.plastic_strain, 0.0, "step {i} is elastic");
            assert_relative_eq!(sxx, m * strain, max_relative = 1e-10);
            assert_relative_eq!(
                -point.stress[(1, 1)],
                elastic.lambda() * strain,
                max_relative = 1e-10
            );
        } else {
            first_plastic.get_or_insert(i);
            let ep = 2.0 * g * (strain - strain_at_yield) / (3.0 * g + ep_mod);
            assert_relative_eq!(
                point.plastic_strain,
                ep,
                epsilon = 1e-10 * strain_at_yield,
                max_relative = 1e-10
            );
            assert_relative_eq!(
                sxx,
                hel + slope * (strain - strain_at_yield),
                max_relative = 1e-10
            );
            // On the yield surface after every return.
            assert_relative_eq!(
                point.equivalent_stress(),
                plastic.yield_stress(point.plastic_strain),
                max_relative = 1e-10
            );
            // σ_yy = σ_xx + σ̄ in compression.
            assert_relative_eq!(
                point.stress[(1, 1)],
                point.stress[(0, 0)] + point.equivalent_stress(),
                max_relative = 1e-10
            );
        }
    }
    // ε_y/Δε = 7.3: steps 1–7 elastic, step 8 the first plastic one.
    assert_eq!(first_plastic, Some(8));
}

#[test]
fn uniaxial_strain_with_linear_hardening_matches_hand_solution() {
    let (elastic, plastic) = copper();
    check_uniaxial_strain(elastic, plastic);
}

#[test]
fn uniaxial_strain_elastic_perfectly_plastic_matches_hand_solution() {
    let (elastic, plastic) = steel();
    check_uniaxial_strain(elastic, plastic);
}

#[test]
fn yield_onset_is_at_the_hugoniot_elastic_limit() {
    // Just below ε_y nothing yields, just above it does.
    let (elastic, plastic) = copper();
    let strain_at_yield = plastic.initial_yield_stress() / (2.0 * elastic.shear_modulus());
    for (factor, yields) in [(1.0 - 1e-9, false), (1.0 + 1e-9, true)] {
        let point = step_von_mises(
            &elastic,
            &plastic,
            &Point::virgin(),
            &uniaxial_strain_rate(-strain_at_yield * factor),
            &Tensor3::zeros(),
            1.0,
        );
        assert_eq!(point.plastic_strain > 0.0, yields, "factor {factor}");
    }
}

fn check_pure_shear(elastic: LinearElastic, plastic: VonMisesPlasticity) {
    let g = elastic.shear_modulus();
    let (sy, ep_mod) = (plastic.initial_yield_stress(), plastic.plastic_modulus());
    let gamma_y = sy / (3f64.sqrt() * g);
    let d_gamma = gamma_y / 9.7;
    let dt = 1e-7;
    let d = shear_rate(d_gamma / dt);
    let mut point = Point::virgin();
    for i in 1..=100 {
        point = step_von_mises(&elastic, &plastic, &point, &d, &Tensor3::zeros(), dt);
        let gamma = i as f64 * d_gamma;
        let tau = point.stress[(0, 1)];
        if gamma < gamma_y {
            assert_eq!(point.plastic_strain, 0.0);
            assert_relative_eq!(tau, g * gamma, max_relative = 1e-10);
        } else {
            let excess = gamma - gamma_y;
            assert_relative_eq!(
                tau,
                sy / 3f64.sqrt() + g * ep_mod * excess / (3.0 * g + ep_mod),
                max_relative = 1e-10
            );
            assert_relative_eq!(
                point.plastic_strain,
                3f64.sqrt() * g * excess / (3.0 * g + ep_mod),
                max_relative = 1e-9
            );
        }
        // Pure shear keeps p = 0 and no normal deviator.
        assert!(point.stress[(0, 0)].abs() < 1e-6 * sy);
    }
}

#[test]
fn pure_shear_yields_at_sigma_y_over_root_three() {
    let (elastic, plastic) = steel();
    check_pure_shear(elastic, plastic);
    let (elastic, plastic) = copper();
    check_pure_shear(elastic, plastic);
}

#[test]
fn simple_shear_with_spin_yields_at_sigma_y_over_root_three_and_stays_on_the_surface() {
    // With spin the Jaumann rate adds normal stresses of order Gγ² (elastic solution
    // σ_xy = G sin γ, σ̄ = 2√3 G sin(γ/2)), so τ at first yield is σ_y/√3 · cos(γ_y/2) up to
    // the step error — within 1e-4 for γ_y ≈ 0.007.
    let (elastic, plastic) = steel();
    let g = elastic.shear_modulus();
    let sy = plastic.initial_yield_stress();
    let gamma_y = sy / (3f64.sqrt() * g);
    let d_gamma = gamma_y / 200.0;
    let dt = 1e-7;
    let (d, w) = (shear_rate(d_gamma / dt), simple_shear_spin(d_gamma / dt));
    let mut point = Point::virgin();
    let mut yielded_at = None;
    for i in 1..=2000 {
        point = step_von_mises(&elastic, &plastic, &point, &d, &w, dt);
        if point.plastic_strain > 0.0 {
            if yielded_at.is_none() {
                yielded_at = Some(i as f64 * d_gamma);
                assert_relative_eq!(point.stress[(0, 1)], sy / 3f64.sqrt(), max_relative = 1e-4);
            }
            assert_relative_eq!(point.equivalent_stress(), sy, max_relative = 1e-10);
        }
    }
    assert_relative_eq!(yielded_at.unwrap(), gamma_y, max_relative = 1e-2);
}

#[test]
fn perfectly_plastic_return_factor_is_yield_over_trial() {
    let (elastic, plastic) = steel();
    let s = Tensor3::new(2.0, 0.3, 0.0, 0.3, -1.0, 0.1, 0.0, 0.1, -1.0) * 1e9;
    let trial = tlsph_math::von_mises(&s);
    let r = plastic.return_map(&s, elastic.shear_modulus(), 0.0);
    assert_relative_eq!(r.deviator, s * (1e9 / trial), max_relative = 1e-14);
    assert_relative_eq!(
        r.plastic_strain_increment,
        (trial - 1e9) / (3.0 * elastic.shear_modulus()),
        max_relative = 1e-14
    );
}
