//! Equations of state and pressure cutoffs (numerics.md §8.7–8.9).
//!
//! Hugoniot check (numerics.md §8.8): for a shock from rest with particle velocity u_p,
//! mass conservation ρ0 U_s = ρ(U_s − u_p) gives μ = ρ/ρ0 − 1 = U_s/(U_s − u_p) − 1, momentum
//! gives p_H = ρ0 U_s u_p and energy gives e_H = ½ p_H (v0 − v) = ½ u_p², so the energy per
//! reference volume is E_H = ρ0 e_H = ½ p_H μ/(1 + μ) = ½ ρ0 u_p². Writing η = μ/(1 + μ)
//! = u_p/U_s, the shock relation U_s = C + S1 u_p + S2 u_p²/U_s + S3 u_p³/U_s² becomes
//! U_s = C/(1 − S1η − S2η² − S3η³), hence p_H = ρ0C²η/(1 − S1η − …)² = ρ0C²μ(1 + μ)/D(μ)²
//! with D the LS-DYNA denominator. The compressed branch equals
//! p_H(μ) + (γ0 + aμ)(E_v − E_H(μ)) — expanding (γ0 + aμ)E_H = ρ0C²μ(γ0μ/2 + aμ²/2)/D² gives
//! exactly the numerator 1 + (1 − γ0/2)μ − (a/2)μ² — so p(μ, E_H) = p_H holds exactly,
//! the a-term included.

use approx::assert_relative_eq;
use tlsph_materials::eos::MieGruneisenParameters;
use tlsph_materials::{EquationOfState, LinearEos, MieGruneisen, PolynomialEos, PressureCutoff};
use tlsph_math::Tensor3;

fn cu9() -> MieGruneisen {
    MieGruneisen::new(MieGruneisenParameters {
        reference_density: 8924.0,
        sound_speed: 3940.0,
        s1: 1.489,
        s2: 0.0,
        s3: 0.0,
        gamma0: 2.02,
        a: 0.47,
    })
    .unwrap()
}

fn al_gr() -> MieGruneisen {
    MieGruneisen::new(MieGruneisenParameters {
        reference_density: 2780.0,
        sound_speed: 5328.0,
        s1: 1.338,
        s2: 0.0,
        s3: 0.0,
        gamma0: 2.0,
        a: 0.48,
    })
    .unwrap()
}

/// M-PMMA (problems.md §1): S2 ≠ 0 exercises the curved U_s–u_p relation; a = 0.
fn pmma() -> MieGruneisen {
    MieGruneisen::new(MieGruneisenParameters {
        reference_density: 1180.0,
        sound_speed: 2180.0,
        s1: 2.088,
        s2: -1.124,
        s3: 0.0,
        gamma0: 0.85,
        a: 0.0,
    })
    .unwrap()
}

#[test]
fn mie_gruneisen_reproduces_the_hugoniot() {
    for (eos, rho0, c, s1) in [
        (cu9(), 8924.0, 3940.0, 1.489),
        (al_gr(), 2780.0, 5328.0, 1.338),
    ] {
        for up in [10.0, 100.0, 305.0, 500.0, 1000.0, 2000.0, 4000.0] {
            let us = c + s1 * up;
            assert_relative_eq!(eos.shock_velocity(up), us, max_relative = 1e-15);
            let mu = us / (us - up) - 1.0;
            let p_h = rho0 * us * up;
            let e_h = 0.5 * p_h * mu / (1.0 + mu);
            assert_relative_eq!(e_h, 0.5 * rho0 * up * up, max_relative = 1e-12);
            assert_relative_eq!(eos.hugoniot_pressure(mu), p_h, max_relative = 1e-9);
            assert_relative_eq!(eos.hugoniot_energy(mu), e_h, max_relative = 1e-9);
            assert_relative_eq!(eos.pressure(mu, e_h), p_h, max_relative = 1e-9);
            // Off the Hugoniot the energy enters with γ0 + aμ.
            let de = 1e9;
            assert_relative_eq!(
                eos.pressure(mu, e_h + de) - p_h,
                eos.gruneisen_coefficient(mu) * de,
                max_relative = 1e-6
            );
        }
    }
}

#[test]
fn curved_shock_relation_is_reproduced_too() {
    let eos = pmma();
    for up in [50.0, 300.0, 1000.0, 2500.0] {
        let us = eos.shock_velocity(up);
        // The implicit relation itself.
        assert_relative_eq!(
            us,
            2180.0 + 2.088 * up - 1.124 * up * up / us,
            max_relative = 1e-13
        );
        let mu = us / (us - up) - 1.0;
        let p_h = 1180.0 * us * up;
        assert_relative_eq!(
            eos.pressure(mu, 0.5 * 1180.0 * up * up),
            p_h,
            max_relative = 1e-9
        );
    }
}

#[test]
fn mie_gruneisen_is_continuous_at_zero_compression() {
    for eos in [cu9(), al_gr(), pmma()] {
        let k0 = eos.bulk_modulus_at_reference();
        for e in [0.0, 1e8, -3e7] {
            let g0 = eos.gruneisen_coefficient(0.0);
            assert_eq!(eos.pressure(0.0, e), g0 * e);
            let h = 1e-9;
            let (plus, minus) = (eos.pressure(h, e), eos.pressure(-h, e));
            let energy = |mu: f64| eos.gruneisen_coefficient(mu) * e;
            assert_relative_eq!(plus, energy(h) + k0 * h, epsilon = 1e-6 * k0 * h);
            assert_relative_eq!(minus, energy(-h) - k0 * h, epsilon = 1e-6 * k0 * h);
        }
    }
}

#[test]
fn mie_gruneisen_expanded_branch_is_linear() {
    let eos = cu9();
    let k0 = 8924.0 * 3940.0 * 3940.0;
    assert_relative_eq!(eos.bulk_modulus_at_reference(), k0, max_relative = 1e-15);
    assert_relative_eq!(eos.pressure(-0.01, 0.0), -0.01 * k0, max_relative = 1e-14);
    assert_relative_eq!(
        eos.pressure(-0.01, 2e8),
        -0.01 * k0 + (2.02 - 0.0047) * 2e8,
        max_relative = 1e-14
    );
}

#[test]
fn mie_gruneisen_guard_beyond_the_limiting_compression() {
    let eos = cu9();
    let limit = eos.compression_limit();
    assert_relative_eq!(limit, 1.0 / 0.489, max_relative = 1e-12);
    assert!(eos.denominator(0.99 * limit) > 0.0);
    assert_eq!(eos.pressure(limit, 0.0), f64::INFINITY);
    assert_eq!(eos.pressure(2.5, 0.0), f64::INFINITY);
    assert_eq!(eos.hugoniot_pressure(2.5), f64::INFINITY);
    // PMMA's denominator never vanishes: no limit.
    assert_eq!(pmma().compression_limit(), f64::INFINITY);
    assert!(pmma().pressure(5.0, 0.0).is_finite());
}

#[test]
fn linear_eos_is_k_mu() {
    let eos = LinearEos::new(68.63e9).unwrap();
    assert_eq!(eos.pressure(0.01, 1e9), 68.63e9 * 0.01);
    assert_eq!(eos.pressure(-0.01, 0.0), -68.63e9 * 0.01);
    assert_eq!(eos.bulk_modulus_at_reference(), 68.63e9);
    assert_eq!(LinearEos::new(0.0).unwrap_err().parameter, "bulk_modulus");
}

#[test]
fn polynomial_eos_distinguishes_tension_and_compression() {
    let c = [1e6, 70e9, 50e9, 20e9, 1.5, 0.5, 0.25];
    let eos = PolynomialEos::new(c).unwrap();
    let e = 1e8;
    // Compression: every term.
    let mu = 0.05;
    let expected = c[0]
        + c[1] * mu
        + c[2] * mu * mu
        + c[3] * mu.powi(3)
        + (c[4] + c[5] * mu + c[6] * mu * mu) * e;
    assert_relative_eq!(eos.pressure(mu, e), expected, max_relative = 1e-14);
    // Tension: the μ̄² terms (C2, C6) vanish.
    let mu = -0.05;
    let expected = c[0] + c[1] * mu + c[3] * mu.powi(3) + (c[4] + c[5] * mu) * e;
    assert_relative_eq!(eos.pressure(mu, e), expected, max_relative = 1e-14);
    // Continuous at μ = 0, with slope C1 on both sides.
    let h = 1e-9;
    let p0 = eos.pressure(0.0, e);
    assert_eq!(p0, c[0] + c[4] * e);
    assert_relative_eq!(
        (eos.pressure(h, e) - p0) / h,
        c[1] + c[5] * e,
        max_relative = 1e-5
    );
    assert_relative_eq!(
        (p0 - eos.pressure(-h, e)) / h,
        c[1] + c[5] * e,
        max_relative = 1e-5
    );
    assert_eq!(eos.bulk_modulus_at_reference(), 70e9);
    // M-AL-POLY: only C1 → same as the linear EOS.
    let al = PolynomialEos::new([0.0, 68.63e9, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
    let lin = LinearEos::new(68.63e9).unwrap();
    for mu in [-0.02, 0.0, 0.03] {
        assert_eq!(al.pressure(mu, 5e8), lin.pressure(mu, 5e8));
    }
}

#[test]
fn polynomial_eos_reports_where_its_cold_stiffness_vanishes() {
    // dp/dμ at E_v = 0 is C1 + 2C2μ + 3C3μ² in compression and C1 + 3C3μ² in tension
    // (numerics.md §8.7); the limits are its zeros nearest μ = 0, hand-solved here.
    // ([C0, C1, C2, C3], (tension limit, compression limit))
    type Limits = (Option<f64>, Option<f64>);
    let cases: [([f64; 4], Limits); 5] = [
        // A softening C2: 70 − 200μ = 0 at μ = 0.35; tension has no C2 term.
        ([0.0, 70e9, -100e9, 0.0], (None, Some(0.35))),
        // A negative C3: 60 − 240μ² = 0 at μ = ±0.5, on both sides.
        ([0.0, 60e9, 0.0, -80e9], (Some(-0.5), Some(0.5))),
        // C3 = −1 GPa: zeros at μ = ±4.83, in tension beyond μ = −1 (infinite expansion).
        ([0.0, 70e9, 0.0, -1e9], (None, Some((70.0f64 / 3.0).sqrt()))),
        // A softening C2 outweighed by C3: 70 − 20μ + 60μ² has no real zero.
        ([0.0, 70e9, -10e9, 20e9], (None, None)),
        // M-AL-POLY: C1 only.
        ([0.0, 68.63e9, 0.0, 0.0], (None, None)),
    ];
    for ([c0, c1, c2, c3], expected) in cases {
        let eos = PolynomialEos::new([c0, c1, c2, c3, 0.0, 0.0, 0.0]).unwrap();
        let (tension, compression) = eos.stiffness_limits();
        for (found, wanted) in [(tension, expected.0), (compression, expected.1)] {
            match (found, wanted) {
                (Some(mu), Some(want)) => {
                    assert_relative_eq!(mu, want, max_relative = 1e-14);
                    // The slope vanishes there and is positive just inside.
                    let slope = |mu: f64| eos.pressure_derivatives(mu, 0.0).0;
                    assert!(
                        slope(mu).abs() < 1e-12 * c1,
                        "{c:?}: {}",
                        slope(mu),
                        c = [c1, c2, c3]
                    );
                    assert!(slope(0.99 * mu) > 0.0);
                }
                (None, None) => {}
                other => panic!("{:?}: {other:?}", [c1, c2, c3]),
            }
        }
    }
}

#[test]
fn polynomial_eos_rejects_bad_coefficients_by_name() {
    let good = [0.0, 1e9, 0.0, 0.0, 0.0, 0.0, 0.0];
    assert_eq!(
        PolynomialEos::new([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
            .unwrap_err()
            .parameter,
        "c1"
    );
    for i in [0, 3, 6] {
        let mut c = good;
        c[i] = f64::NAN;
        let err = PolynomialEos::new(c).unwrap_err();
        assert_eq!(err.parameter, ["c0", "c1", "c2", "c3", "c4", "c5", "c6"][i]);
    }
}

#[test]
fn enum_dispatch_matches_the_models() {
    let models: [EquationOfState; 3] = [
        LinearEos::new(68.63e9).unwrap().into(),
        PolynomialEos::new([0.0, 68.63e9, 1e10, 0.0, 2.0, 0.0, 0.0])
            .unwrap()
            .into(),
        cu9().into(),
    ];
    for eos in &models {
        for mu in [-0.03, 0.0, 0.02, 0.4] {
            let direct = match eos {
                EquationOfState::Linear(m) => m.pressure(mu, 1e8),
                EquationOfState::Polynomial(m) => m.pressure(mu, 1e8),
                EquationOfState::MieGruneisen(m) => m.pressure(mu, 1e8),
            };
            assert_eq!(eos.pressure(mu, 1e8), direct);
        }
    }
    assert_eq!(models[0].bulk_modulus_at_reference(), 68.63e9);
    assert_eq!(models[1].bulk_modulus_at_reference(), 68.63e9);
    assert_relative_eq!(
        models[2].bulk_modulus_at_reference(),
        138.53e9,
        max_relative = 1e-3
    );
}

#[test]
fn compression_from_jacobian() {
    use tlsph_materials::eos::compression_from_jacobian;
    assert_eq!(compression_from_jacobian(1.0), 0.0);
    assert_relative_eq!(compression_from_jacobian(0.8), 0.25, max_relative = 1e-15);
    assert_relative_eq!(compression_from_jacobian(1.25), -0.2, max_relative = 1e-15);
}

/// Rotates a diagonal stress so that principal values must be found, not read off.
fn rotated(diagonal: [f64; 3]) -> Tensor3 {
    let q = super::rotation([1.0, -2.0, 0.5], 0.7);
    q * Tensor3::from_diagonal(&tlsph_math::Vector3::from(diagonal)) * q.transpose()
}

#[test]
fn cutoff_type_1_limits_tension_only() {
    // R-P10: PC = −800 MPa.
    let cutoff = PressureCutoff::from_spall_type(1, -800e6).unwrap();
    assert_eq!(
        cutoff,
        PressureCutoff::Limit {
            min_pressure: -800e6
        }
    );
    assert_eq!(cutoff.limit_pressure(-1.2e9), -800e6);
    assert_eq!(cutoff.limit_pressure(-500e6), -500e6);
    assert_eq!(cutoff.limit_pressure(3e9), 3e9);
    assert!(!cutoff.fails(-5e9, &rotated([5e9, 5e9, 5e9])));
    assert_eq!(
        PressureCutoff::limit(1.0).unwrap_err().parameter,
        "pressure_cutoff"
    );
}

#[test]
fn cutoff_type_2_fails_on_max_principal_stress() {
    // R-P9 deck: PC = +4.9 GPa (sign ignored), spall type 2.
    for pc in [4.9e9, -4.9e9] {
        let cutoff = PressureCutoff::from_spall_type(2, pc).unwrap();
        assert_eq!(cutoff.limit_pressure(-7e9), -7e9);
        assert!(cutoff.fails(0.0, &rotated([4.9e9 * (1.0 + 1e-9), -1e9, 0.0])));
        assert!(!cutoff.fails(0.0, &rotated([4.9e9 * (1.0 - 1e-9), -1e9, 0.0])));
        // Pure compression never spalls, however large.
        assert!(!cutoff.fails(10e9, &rotated([-10e9, -20e9, -1e9])));
    }
}

#[test]
fn cutoff_type_3_fails_on_hydrostatic_tension() {
    let cutoff = PressureCutoff::from_spall_type(3, -1e9).unwrap();
    assert!(cutoff.fails(-1e9, &Tensor3::zeros()));
    assert!(!cutoff.fails(-0.999e9, &Tensor3::zeros()));
    assert!(!cutoff.fails(5e9, &Tensor3::zeros()));
    assert_eq!(cutoff.limit_pressure(-2e9), -2e9);
}

#[test]
fn cutoff_rejects_unknown_types_and_zero_strengths() {
    assert_eq!(
        PressureCutoff::from_spall_type(4, -1.0)
            .unwrap_err()
            .parameter,
        "spall_type"
    );
    assert_eq!(
        PressureCutoff::from_spall_type(2, 0.0)
            .unwrap_err()
            .parameter,
        "pressure_cutoff"
    );
    assert_eq!(
        PressureCutoff::min_pressure(f64::NAN)
            .unwrap_err()
            .parameter,
        "pressure_cutoff"
    );
}

/// K_s = ρ(∂p/∂ρ)_s measured by a central difference *along an isentrope*: a compression
/// step dμ carries the energy dE_v = p dμ/(1 + μ)² (de = p dρ/ρ², E_v = ρ0 e, ρ = ρ0(1 + μ)).
fn isentropic_difference(eos: &EquationOfState, mu: f64, energy: f64) -> f64 {
    let delta = 1e-6;
    let p = eos.pressure(mu, energy);
    let de = p * delta / ((1.0 + mu) * (1.0 + mu));
    let up = eos.pressure(mu + delta, energy + de);
    let down = eos.pressure(mu - delta, energy - de);
    (1.0 + mu) * (up - down) / (2.0 * delta)
}

#[test]
fn the_isentropic_bulk_modulus_is_the_slope_of_pressure_along_an_isentrope() {
    let models: [(&str, EquationOfState); 5] = [
        ("cu9", cu9().into()),
        ("al-gr", al_gr().into()),
        ("pmma", pmma().into()),
        ("linear", LinearEos::new(68.6e9).unwrap().into()),
        (
            "polynomial",
            PolynomialEos::new([1e8, 70e9, 40e9, 20e9, 0.5, 1.5, 0.8])
                .unwrap()
                .into(),
        ),
    ];
    // Tension, reference, moderate and strong compression; cold and hot (E_v up to the
    // below the Hugoniot energy of a 1 km/s impact on copper, ½ρ0u_p² ≈ 4.5e9 J/m³).
    for (name, eos) in &models {
        for mu in [-0.05, -1e-3, 0.0 + 2e-6, 0.05, 0.3, 0.6] {
            for energy in [0.0, 1e8, 2e9] {
                let exact = eos.isentropic_bulk_modulus(mu, energy);
                let measured = isentropic_difference(eos, mu, energy);
                // A central difference of step 1e-6 is exact to O(1e-12) in the curvature
                // terms; round-off in p/δ (p ≈ 1e11, ε ≈ 1e-16) leaves ≈ 1e-5 of K.
                assert_relative_eq!(exact, measured, max_relative = 1e-6);
                assert!(exact.is_finite() && exact > 0.0, "{name} μ={mu} E={energy}");
            }
        }
        // At rest and unstressed it is the reference modulus (the polynomial's C0 = 1e8 Pa
        // adds C0·C4 there, the thermal pressure's stiffening).
        let rest = eos.isentropic_bulk_modulus(0.0, 0.0);
        let thermal = eos.pressure(0.0, 0.0) * eos.pressure_derivatives(0.0, 0.0).1;
        assert_relative_eq!(
            rest,
            eos.bulk_modulus_at_reference() + thermal,
            max_relative = 1e-12
        );
    }
    // Copper stiffens: at the 1 km/s Hugoniot state (μ ≈ 0.19) K_s is about twice ρ0C².
    let cu: EquationOfState = cu9().into();
    let mu = 0.19;
    let ratio =
        cu.isentropic_bulk_modulus(mu, cu9().hugoniot_energy(mu)) / cu.bulk_modulus_at_reference();
    assert!((1.7..2.6).contains(&ratio), "K_s/K0 = {ratio}");
    // Beyond the limiting compression the modulus is infinite, as the pressure.
    let limit = cu9().compression_limit();
    assert_eq!(cu.isentropic_bulk_modulus(limit * 1.01, 0.0), f64::INFINITY);
}
