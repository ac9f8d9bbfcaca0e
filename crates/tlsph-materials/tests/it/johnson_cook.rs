//! Johnson–Cook strength (numerics.md §8.5): flow-stress values, rate and thermal factors, and
//! both return maps, including the n < 1 start from ε̄p = 0 where dσ_y/dε̄p is infinite.

use super::drivers::{step_johnson_cook, uniaxial_strain_rate, Point};
use approx::assert_relative_eq;
use tlsph_materials::strength::JohnsonCookStrengthParameters;
use tlsph_materials::{JohnsonCookStrength, LinearElastic};
use tlsph_math::Tensor3;

/// M-AL7010 (problems.md §1) with ε̇0 = 1 /s (R-P10).
fn al7010() -> JohnsonCookStrengthParameters {
    JohnsonCookStrengthParameters {
        a: 479e6,
        b: 323e6,
        n: 0.41,
        c: 0.101,
        m: 1.80,
        reference_strain_rate: 1.0,
        room_temperature: 300.0,
        melt_temperature: 850.0,
    }
}

/// M-CU9 (problems.md §1).
fn cu9() -> JohnsonCookStrengthParameters {
    JohnsonCookStrengthParameters::OFHC_COPPER
}

/// G of M-AL7010 (deck 0.2632 Mbar).
const G_AL: f64 = 26.32e9;

#[test]
fn flow_stress_values_by_hand() {
    let jc = JohnsonCookStrength::new(al7010()).unwrap();
    // (479 + 323·0.1^0.41) MPa at ε̇* = 1, T = T_room.
    assert_relative_eq!(
        jc.yield_stress(0.1, 1.0, 300.0),
        604.661_581_833_152_7e6,
        max_relative = 1e-13
    );
    // Rate factor 1 + 0.101 ln 1000 = 1.697683283177196.
    assert_relative_eq!(
        jc.strain_rate_factor(1000.0),
        1.697_683_283_177_196,
        max_relative = 1e-14
    );
    // T* = (575 − 300)/(850 − 300) = 0.5: 1 − 0.5^1.8 = 0.7128254112507413.
    assert_relative_eq!(
        jc.thermal_factor(575.0),
        0.712_825_411_250_741_3,
        max_relative = 1e-14
    );
    // All three together: ε̄p 0.2, ε̇* 100, T 500 K.
    assert_relative_eq!(
        jc.yield_stress(0.2, 100.0, 500.0),
        793.208_465_007_560_7e6,
        max_relative = 1e-13
    );
    // Virgin, quasi-static, room temperature: A.
    assert_eq!(jc.yield_stress(0.0, 1.0, 300.0), 479e6);
}

#[test]
fn rate_and_thermal_terms_follow_the_formula() {
    let jc = JohnsonCookStrength::new(cu9()).unwrap();
    let base = jc.yield_stress(0.3, 1.0, 300.0);
    // Rate term: ratio 1 + C ln ε̇*, and rates below ε̇0 are clamped (no weakening).
    for rate in [10.0, 1e3, 1e5] {
        assert_relative_eq!(
            jc.yield_stress(0.3, rate, 300.0) / base,
            1.0 + 0.025 * f64::ln(rate),
            max_relative = 1e-14
        );
    }
    assert_eq!(jc.yield_stress(0.3, 1e-3, 300.0), base);
    assert_eq!(jc.yield_stress(0.3, 0.0, 300.0), base);
    // Thermal term: ratio 1 − T*^m, clipped at room temperature and at melt.
    for t in [400.0, 800.0, 1300.0] {
        let t_star: f64 = (t - 300.0) / 1056.0;
        assert_relative_eq!(
            jc.yield_stress(0.3, 1.0, t) / base,
            1.0 - t_star.powf(1.09),
            max_relative = 1e-13
        );
    }
    assert_eq!(jc.yield_stress(0.3, 1.0, 250.0), base);
    assert_eq!(jc.yield_stress(0.3, 1.0, 1356.0), 0.0);
    assert_eq!(jc.yield_stress(0.3, 1.0, 2000.0), 0.0);
    assert_eq!(jc.homologous_temperature(2000.0), 1.0);
    // Monotone: harder with strain and rate, softer with temperature.
    assert!(jc.yield_stress(0.31, 1.0, 300.0) > base);
    assert!(jc.yield_stress(0.3, 2.0, 300.0) > base);
    assert!(jc.yield_stress(0.3, 1.0, 301.0) < base);
}

fn trial_deviators() -> Vec<Tensor3> {
    let shapes = [
        Tensor3::new(2.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0),
        Tensor3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        Tensor3::new(1.0, 0.4, -0.2, 0.4, 0.5, 0.3, -0.2, 0.3, -1.5),
    ];
    shapes
        .iter()
        .map(|s| s / tlsph_math::von_mises(s))
        .collect()
}

/// Residual of the consistency condition f = σ̄* − 3GΔε̄p − σ_y(ε̄p + Δε̄p) relative to σ̄*.
fn consistency_residual(
    jc: &JohnsonCookStrength,
    trial: f64,
    g: f64,
    ep: f64,
    dep: f64,
    rate: f64,
    t: f64,
) -> f64 {
    (trial - 3.0 * g * dep - jc.yield_stress(ep + dep, rate, t)) / trial
}

#[test]
fn accurate_iteration_satisfies_the_consistency_condition() {
    for (params, g) in [(al7010(), G_AL), (cu9(), 47.7e9)] {
        for n in [params.n, 0.1, 1.0, 2.5] {
            let jc =
                JohnsonCookStrength::new(JohnsonCookStrengthParameters { n, ..params }).unwrap();
            for shape in trial_deviators() {
                for ep in [0.0, 1e-6, 0.05, 0.8] {
                    for (rate, t) in [(1.0, 300.0), (3e4, 300.0), (1e3, 700.0)] {
                        let yield0 = jc.yield_stress(ep, rate, t);
                        for overshoot in [1e-9, 1e-3, 0.2, 5.0] {
                            let trial = yield0 * (1.0 + overshoot);
                            let r = jc.return_map(&(shape * trial), g, ep, rate, t, true);
                            let dep = r.plastic_strain_increment;
                            assert!(dep > 0.0);
                            let f = consistency_residual(&jc, trial, g, ep, dep, rate, t);
                            assert!(
                                f.abs() <= 1e-10,
                                "n {n} ep {ep} overshoot {overshoot}: f = {f:e}"
                            );
                            // The returned deviator lies on the updated yield surface, coaxial with s*.
                            assert_relative_eq!(
                                tlsph_math::von_mises(&r.deviator),
                                jc.yield_stress(ep + dep, rate, t),
                                max_relative = 1e-10
                            );
                            assert_relative_eq!(
                                r.deviator * trial,
                                shape * trial * tlsph_math::von_mises(&r.deviator),
                                max_relative = 1e-10
                            );
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn accurate_iteration_converges_from_zero_plastic_strain_with_n_below_one() {
    // dσ_y/dε̄p = nBε̄p^(n−1) is infinite at ε̄p = 0 for n < 1: Newton from 0 would fail; the
    // bracketed solver must still land on the root, even when it is astronomically small.
    let g = G_AL;
    for n in [0.05, 0.1, 0.31, 0.41, 0.9] {
        let jc = JohnsonCookStrength::new(JohnsonCookStrengthParameters { n, ..al7010() }).unwrap();
        for overshoot in [1e-12, 1e-6, 1e-2, 1.0, 100.0] {
            let trial = 479e6 * (1.0 + overshoot);
            let s =
                Tensor3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0) * (trial / 3f64.sqrt());
            let r = jc.return_map(&s, g, 0.0, 1.0, 300.0, true);
            let dep = r.plastic_strain_increment;
            assert!(dep > 0.0 && dep.is_finite());
            let f = consistency_residual(&jc, trial, g, 0.0, dep, 1.0, 300.0);
            assert!(f.abs() <= 1e-10, "n {n} overshoot {overshoot}: f = {f:e}");
        }
    }
}

#[test]
fn single_return_uses_the_flow_stress_at_step_start() {
    let jc = JohnsonCookStrength::new(cu9()).unwrap();
    let g = 47.7e9;
    let (ep, rate, t) = (0.2, 500.0, 450.0);
    let yield0 = jc.yield_stress(ep, rate, t);
    let shape = trial_deviators()[2];
    let trial = 1.7 * yield0;
    let r = jc.return_map(&(shape * trial), g, ep, rate, t, false);
    assert_relative_eq!(
        r.plastic_strain_increment,
        (trial - yield0) / (3.0 * g),
        max_relative = 1e-13
    );
    assert_relative_eq!(
        tlsph_math::von_mises(&r.deviator),
        yield0,
        max_relative = 1e-13
    );
    // Iterating with hardening gives less plastic strain and a higher (hardened) stress.
    let it = jc.return_map(&(shape * trial), g, ep, rate, t, true);
    assert!(it.plastic_strain_increment < r.plastic_strain_increment);
    assert!(tlsph_math::von_mises(&it.deviator) > yield0);
}

#[test]
fn without_hardening_both_returns_agree() {
    let jc =
        JohnsonCookStrength::new(JohnsonCookStrengthParameters { b: 0.0, ..al7010() }).unwrap();
    let s = trial_deviators()[0] * 900e6;
    let a = jc.return_map(&s, G_AL, 0.3, 10.0, 400.0, false);
    let b = jc.return_map(&s, G_AL, 0.3, 10.0, 400.0, true);
    assert_relative_eq!(a.deviator, b.deviator, max_relative = 1e-13);
    assert_relative_eq!(
        a.plastic_strain_increment,
        b.plastic_strain_increment,
        max_relative = 1e-12
    );
}

#[test]
fn elastic_trial_and_melted_material() {
    let jc = JohnsonCookStrength::new(cu9()).unwrap();
    let s = trial_deviators()[1] * 80e6;
    let r = jc.return_map(&s, 47.7e9, 0.0, 1.0, 300.0, true);
    assert_eq!(r.deviator, s);
    assert_eq!(r.plastic_strain_increment, 0.0);
    // At T ≥ T_melt the flow stress vanishes: the whole trial deviator is plastic.
    for iterate in [false, true] {
        let r = jc.return_map(&s, 47.7e9, 0.0, 1.0, 1400.0, iterate);
        assert_eq!(r.deviator, Tensor3::zeros());
        assert_relative_eq!(
            r.plastic_strain_increment,
            80e6 / (3.0 * 47.7e9),
            max_relative = 1e-14
        );
    }
}

#[test]
fn uniaxial_strain_driver_hardens_along_the_curve() {
    // Al 7010 point in uniaxial-strain compression at 1e4 /s: on every plastic step the
    // iterated return sits on σ_y(ε̄p, ε̇̄ = (2/3)|ε̇|, T_room).
    let elastic = LinearElastic::new(70e9, 0.33).unwrap();
    let jc = JohnsonCookStrength::new(al7010()).unwrap();
    let rate = -1e4;
    let d = uniaxial_strain_rate(rate);
    let dt = 1e-8;
    let mut point = Point::virgin();
    let mut plastic_steps = 0;
    for _ in 0..2000 {
        let before = point.plastic_strain;
        point = step_johnson_cook(&elastic, &jc, &point, &d, dt, true);
        if point.plastic_strain > before {
            plastic_steps += 1;
            assert_relative_eq!(
                point.equivalent_stress(),
                jc.yield_stress(point.plastic_strain, 2.0 / 3.0 * rate.abs(), 300.0),
                max_relative = 1e-10
            );
        }
    }
    assert!(plastic_steps > 1000);
}

#[test]
fn equivalent_strain_rate_of_simple_paths() {
    use tlsph_materials::equivalent_strain_rate;
    // Isochoric uniaxial stress D = ε̇ diag(1, −½, −½): ε̇̄ = |ε̇|.
    let d = Tensor3::from_diagonal(&tlsph_math::Vector3::new(3.0, -1.5, -1.5));
    assert_relative_eq!(equivalent_strain_rate(&d), 3.0, max_relative = 1e-15);
    // Uniaxial strain: ε̇̄ = (2/3)|ε̇|; volumetric rate alone: 0.
    assert_relative_eq!(
        equivalent_strain_rate(&uniaxial_strain_rate(-3.0)),
        2.0,
        max_relative = 1e-15
    );
    assert_eq!(equivalent_strain_rate(&Tensor3::identity()), 0.0);
    // Pure shear γ̇: ε̇̄ = γ̇/√3.
    assert_relative_eq!(
        equivalent_strain_rate(&super::drivers::shear_rate(2.0)),
        2.0 / 3f64.sqrt(),
        max_relative = 1e-15
    );
}

#[test]
fn adiabatic_heating() {
    // 383 J/(kg K) for copper (M-CU9): 38.3 kJ/kg of plastic work heats by 100 K.
    assert_relative_eq!(
        tlsph_materials::adiabatic_temperature_rise(38_300.0, 383.0),
        100.0,
        max_relative = 1e-15
    );
}
