//! Objectivity contracts (layout convention 6): every pointwise map of a tensor commutes with
//! rotations, f(Q s Qᵀ) = Q f(s) Qᵀ, and its scalar outputs are unchanged.

use approx::assert_relative_eq;
use tlsph_materials::strength::JohnsonCookStrengthParameters;
use tlsph_materials::{
    max_principal_value, JohnsonCookStrength, PeerlingsSoftening, PlasticReturn, VonMisesPlasticity,
};
use tlsph_math::{deviator, Tensor3};

fn rotations() -> Vec<Tensor3> {
    vec![
        super::rotation([1.0, 0.0, 0.0], std::f64::consts::FRAC_PI_2),
        super::rotation([1.0, 2.0, 3.0], 1.1),
        super::rotation([-0.3, 0.2, 1.0], 2.9),
    ]
}

fn trial_deviators(scale: f64) -> Vec<Tensor3> {
    [
        Tensor3::new(2.0, 0.3, -0.1, 0.3, -1.0, 0.7, -0.1, 0.7, -1.0),
        Tensor3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        Tensor3::new(-1.5, 0.2, 0.9, 0.2, 0.5, -0.4, 0.9, -0.4, 1.0),
    ]
    .iter()
    .map(|s| deviator(s) * scale)
    .collect()
}

fn check(map: impl Fn(&Tensor3) -> PlasticReturn, scale: f64) {
    for s in trial_deviators(scale) {
        let reference = map(&s);
        assert!(
            reference.plastic_strain_increment > 0.0,
            "trial must be plastic"
        );
        for q in rotations() {
            let rotated = map(&(q * s * q.transpose()));
            assert_relative_eq!(
                rotated.deviator,
                q * reference.deviator * q.transpose(),
                epsilon = 1e-12 * scale,
                max_relative = 1e-12
            );
            assert_relative_eq!(
                rotated.plastic_strain_increment,
                reference.plastic_strain_increment,
                max_relative = 1e-12
            );
        }
    }
}

#[test]
fn von_mises_return_map_is_objective() {
    let vm = VonMisesPlasticity::from_tangent_modulus(90e6, 110e9, 1.1e9).unwrap();
    check(|s| vm.return_map(s, 41e9, 0.05), 1e9);
}

#[test]
fn johnson_cook_return_maps_are_objective() {
    let jc = JohnsonCookStrength::new(JohnsonCookStrengthParameters {
        a: 479e6,
        b: 323e6,
        n: 0.41,
        c: 0.101,
        m: 1.8,
        reference_strain_rate: 1.0,
        room_temperature: 300.0,
        melt_temperature: 850.0,
    })
    .unwrap();
    for iterate in [false, true] {
        check(|s| jc.return_map(s, 26.32e9, 0.0, 1e3, 400.0, iterate), 2e9);
    }
}

#[test]
fn tensile_degradation_and_principal_values_are_objective() {
    let p = PeerlingsSoftening::new(0.001, 0.01).unwrap();
    let sigma = Tensor3::new(3.0, 1.0, 0.5, 1.0, -2.0, 0.25, 0.5, 0.25, 1.0) * 1e8;
    let reference = p.degrade(&sigma, 0.6);
    for q in rotations() {
        let rotated = q * sigma * q.transpose();
        assert_relative_eq!(
            p.degrade(&rotated, 0.6),
            q * reference * q.transpose(),
            epsilon = 1e-6,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            max_principal_value(&rotated),
            max_principal_value(&sigma),
            max_relative = 1e-12
        );
    }
}
