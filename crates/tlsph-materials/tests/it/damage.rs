//! Damage and failure (numerics.md §8.6, §9.1–9.2): Johnson–Cook failure strain, simple
//! criteria, Peerlings linear softening and Grady–Kipp flaws.
//!
//! Peerlings in uniaxial tension: for κ0 < κ < κc,
//! (1 − D)Eκ = Eκ − E κc(κ − κ0)/(κc − κ0) = Eκ0(κc − κ)/(κc − κ0),
//! a straight line from Eκ0 at κ0 to 0 at κc.
//!
//! Grady–Kipp growth: d(D^{1/3})/dt = n_act c_g/R_s with constant n_act integrates to
//! D(t) = (n_act c_g t/R_s)³ until the cap min(n_act/n_i, 1).

use approx::assert_relative_eq;
use tlsph_materials::damage::{
    stress_triaxiality, MIN_STRAIN_TO_FAILURE, TRIAXIALITY_STRESS_FLOOR,
};
use tlsph_materials::{
    max_principal_value, GradyKipp, JohnsonCookFailure, MaxPlasticStrainFailure, MaxStressFailure,
    PeerlingsSoftening,
};
use tlsph_math::{Tensor3, Vector3};

fn diag(a: f64, b: f64, c: f64) -> Tensor3 {
    Tensor3::from_diagonal(&Vector3::new(a, b, c))
}

#[test]
fn johnson_cook_failure_strain_values_by_hand() {
    // M-AL7010-D: D2 = D3 = 0 → ε_f = D1(1 + D4 ln ε̇*) = 0.45(1 + 0.0138 ln 1000).
    let al = JohnsonCookFailure::new(0.45, 0.0, 0.0, 0.0138, 0.0).unwrap();
    assert_relative_eq!(
        al.strain_to_failure(0.7, 1000.0, 0.3),
        0.492_897_160_282_479,
        max_relative = 1e-14
    );
    assert_eq!(al.strain_to_failure(-2.0, 1.0, 0.0), 0.45);
    // M-CU9: 0.54 + 4.89 exp(−3.03σ*).
    let cu = JohnsonCookFailure::new(0.54, 4.89, -3.03, 0.014, 0.0).unwrap();
    assert_relative_eq!(
        cu.strain_to_failure(1.0 / 3.0, 1.0, 0.0),
        2.321_030_810_104_749,
        max_relative = 1e-14
    );
    assert_relative_eq!(
        cu.strain_to_failure(-1.0 / 3.0, 1.0, 0.0),
        13.965_988_963_432_72,
        max_relative = 1e-14
    );
    assert_relative_eq!(
        cu.strain_to_failure(0.0, 1.0, 0.0),
        5.43,
        max_relative = 1e-15
    );
    assert_relative_eq!(
        cu.strain_to_failure(1.0 / 3.0, 1e4, 0.0),
        2.620_315_582_953_466,
        max_relative = 1e-14
    );
    // D5 term: 1 + D5 T*.
    let hot = JohnsonCookFailure::new(0.5, 0.0, 0.0, 0.0, 1.6).unwrap();
    assert_relative_eq!(
        hot.strain_to_failure(0.0, 1.0, 0.25),
        0.5 * 1.4,
        max_relative = 1e-15
    );
}

#[test]
fn johnson_cook_failure_guards() {
    let cu = JohnsonCookFailure::new(0.54, 4.89, -3.03, 0.014, 0.0).unwrap();
    // ε̇* < 1 is clamped to 1 inside the logarithm.
    assert_eq!(
        cu.strain_to_failure(0.5, 1e-3, 0.0),
        cu.strain_to_failure(0.5, 1.0, 0.0)
    );
    assert_eq!(
        cu.strain_to_failure(0.5, 0.0, 0.0),
        cu.strain_to_failure(0.5, 1.0, 0.0)
    );
    // T* is clipped to [0, 1].
    let hot = JohnsonCookFailure::new(0.5, 0.0, 0.0, 0.0, 1.0).unwrap();
    assert_eq!(hot.strain_to_failure(0.0, 1.0, 3.0), 1.0);
    assert_eq!(hot.strain_to_failure(0.0, 1.0, -3.0), 0.5);
    // ε_f never drops below 1e-4, even where a fit goes negative (iron-like D1 < 0: ε_f < 0
    // at high triaxiality, D1 + D2 > 0 at zero).
    let brittle = JohnsonCookFailure::new(-2.2, 5.43, -0.47, 0.0, 0.0).unwrap();
    assert_eq!(
        brittle.strain_to_failure(10.0, 1.0, 0.0),
        MIN_STRAIN_TO_FAILURE
    );
    assert_eq!(brittle.damage_increment(1e-5, 10.0, 1.0, 0.0), 0.1);
    // A fit with no positive failure strain even at zero triaxiality is refused.
    for (d1, d2) in [(0.0, 0.0), (-0.1, 0.0), (-0.5, 0.2)] {
        let e = JohnsonCookFailure::new(d1, d2, 0.0, 0.0, 0.0).unwrap_err();
        assert_eq!(e.parameter, "d", "{e}");
    }
    // Triaxiality σ* = −p/σ̄, skipped below 1e-9·A.
    let a = 90e6;
    assert_eq!(
        stress_triaxiality(-100e6, 300e6, TRIAXIALITY_STRESS_FLOOR * a),
        Some(1.0 / 3.0)
    );
    assert_eq!(
        stress_triaxiality(-100e6, 0.05, TRIAXIALITY_STRESS_FLOOR * a),
        None
    );
    assert_eq!(stress_triaxiality(-100e6, 0.0, 0.0), None);
    // Negative plastic increments do not heal.
    assert_eq!(cu.damage_increment(-1e-3, 0.3, 1.0, 0.0), 0.0);
    for (d, name) in [
        (JohnsonCookFailure::new(f64::NAN, 0.0, 0.0, 0.0, 0.0), "d1"),
        (
            JohnsonCookFailure::new(0.5, 0.0, f64::INFINITY, 0.0, 0.0),
            "d3",
        ),
        (JohnsonCookFailure::new(0.5, 0.0, 0.0, 0.0, f64::NAN), "d5"),
    ] {
        assert_eq!(d.unwrap_err().parameter, name);
    }
}

#[test]
fn johnson_cook_damage_reaches_one_at_the_failure_strain() {
    // Proportional loading at constant σ*: D = Σ Δε̄p / ε_f reaches 1 when ε̄p = ε_f.
    let cu = JohnsonCookFailure::new(0.54, 4.89, -3.03, 0.014, 0.0).unwrap();
    let eps_f = cu.strain_to_failure(1.0 / 3.0, 1e3, 0.0);
    let n = 1000;
    let damage: f64 = (0..n)
        .map(|_| cu.damage_increment(eps_f / n as f64, 1.0 / 3.0, 1e3, 0.0))
        .sum();
    assert_relative_eq!(damage, 1.0, max_relative = 1e-12);
}

#[test]
fn max_stress_and_max_plastic_strain_criteria() {
    let q = super::rotation([0.3, 1.0, -0.4], 1.3);
    let crit = MaxStressFailure::new(1e9).unwrap();
    let at = |s1: f64| q * diag(s1, -2e9, 0.5e9) * q.transpose();
    assert!(crit.fails(&at(1e9 * (1.0 + 1e-9))));
    assert!(!crit.fails(&at(1e9 * (1.0 - 1e-9))));
    assert_relative_eq!(max_principal_value(&at(1.2e9)), 1.2e9, max_relative = 1e-12);
    assert_eq!(
        MaxStressFailure::new(0.0).unwrap_err().parameter,
        "max_principal_stress"
    );

    let crit = MaxPlasticStrainFailure::new(0.8).unwrap();
    assert!(crit.fails(0.8));
    assert!(!crit.fails(0.799));
    assert_eq!(
        MaxPlasticStrainFailure::new(-1.0).unwrap_err().parameter,
        "max_plastic_strain"
    );
}

fn peerlings() -> PeerlingsSoftening {
    // F-A13: κ0 = 0.001, κc = 0.01.
    PeerlingsSoftening::new(0.001, 0.01).unwrap()
}

#[test]
fn peerlings_damage_is_piecewise() {
    let p = peerlings();
    assert_eq!(p.damage(0.0), 0.0);
    assert_eq!(p.damage(0.0005), 0.0);
    assert_eq!(p.damage(0.001), 0.0);
    // (0.01/0.005)(0.004/0.009) = 8/9.
    assert_relative_eq!(p.damage(0.005), 8.0 / 9.0, max_relative = 1e-14);
    // (0.01/0.002)(0.001/0.009) = 5/9.
    assert_relative_eq!(p.damage(0.002), 5.0 / 9.0, max_relative = 1e-14);
    assert_eq!(p.damage(0.01), 1.0);
    assert_eq!(p.damage(0.5), 1.0);
    // Continuous at both ends.
    assert!(p.damage(0.001 * (1.0 + 1e-9)) < 1e-7);
    assert!(p.damage(0.01 * (1.0 - 1e-9)) > 1.0 - 1e-7);
}

#[test]
fn peerlings_uniaxial_response_descends_linearly() {
    let p = peerlings();
    let e = 1.0; // Fuller's units: E = 1.
    for i in 0..=200 {
        let strain = 0.012 * i as f64 / 200.0;
        let kappa = PeerlingsSoftening::update_history(0.0, strain);
        let sigma = p.degrade(&diag(e * strain, 0.0, 0.0), p.damage(kappa))[(0, 0)];
        let expected = if strain <= 0.001 {
            e * strain
        } else if strain < 0.01 {
            e * 0.001 * (0.01 - strain) / (0.01 - 0.001)
        } else {
            0.0
        };
        assert_relative_eq!(sigma, expected, epsilon = 1e-15, max_relative = 1e-12);
    }
}

#[test]
fn peerlings_history_prevents_healing_and_compression_is_untouched() {
    let p = peerlings();
    // Load to 0.005, unload to 0.002: κ stays 0.005, so the secant modulus is (1 − 8/9)E.
    let mut kappa = 0.0;
    for strain in [0.001, 0.003, 0.005, 0.004, 0.002] {
        kappa = PeerlingsSoftening::update_history(kappa, strain);
    }
    assert_eq!(kappa, 0.005);
    let d = p.damage(kappa);
    assert_relative_eq!(
        p.degrade(&diag(0.002, 0.0, 0.0), d)[(0, 0)],
        0.002 / 9.0,
        max_relative = 1e-13
    );
    // Compressive principal stresses keep their full value; tensile ones are scaled.
    assert_eq!(
        p.degrade(&diag(-3.0, -1.0, 0.0), 0.9),
        diag(-3.0, -1.0, 0.0)
    );
    assert_relative_eq!(
        p.degrade(&diag(2.0, -3.0, 0.0), 0.5),
        diag(1.0, -3.0, 0.0),
        epsilon = 1e-14
    );
    assert_eq!(p.degrade(&diag(2.0, -3.0, 0.0), 0.0), diag(2.0, -3.0, 0.0));
    assert_relative_eq!(
        p.degrade(&diag(2.0, 1.0, -3.0), 1.0),
        diag(0.0, 0.0, -3.0),
        epsilon = 1e-14
    );
}

fn grady_kipp() -> GradyKipp {
    // F-A12: m = 8.5, k = 1.4e19 cm⁻² (lengths in cm, 2D).
    GradyKipp::new(8.5, 1.4e19).unwrap()
}

#[test]
fn grady_kipp_seeding_is_deterministic_and_counts_n_ln_n_flaws() {
    let gk = grady_kipp();
    let (n, area) = (400, 400.0); // 20 x 20 particles of 1 cm².
    let a = gk.seed_flaws(n, area, 2010);
    let b = gk.seed_flaws(n, area, 2010);
    let c = gk.seed_flaws(n, area, 2011);
    assert_eq!(a, b);
    assert_ne!(a, c);
    assert_eq!(a.len(), n);
    let total: usize = a.iter().map(Vec::len).sum();
    assert_eq!(total, (400.0 * f64::ln(400.0)).ceil() as usize);
    assert_eq!(total, GradyKipp::flaw_count(n));
    assert_eq!(c.iter().map(Vec::len).sum::<usize>(), total);
    // Roughly uniform: no particle hoards flaws (mean ln 400 ≈ 6).
    assert!(a.iter().all(|f| f.len() < 30));
}

#[test]
fn grady_kipp_thresholds_are_monotone_and_follow_weibull() {
    let gk = grady_kipp();
    let (n, area) = (400, 400.0);
    // Thresholds increase with the flaw index, ε_j = (j/(kV))^{1/m} …
    let eps: Vec<f64> = (1..=GradyKipp::flaw_count(n))
        .map(|j| gk.activation_strain(j, area))
        .collect();
    assert!(eps.windows(2).all(|w| w[0] < w[1]));
    assert_relative_eq!(
        eps[0],
        (1.0_f64 / (1.4e19 * 400.0)).powf(1.0 / 8.5),
        max_relative = 1e-14
    );
    // … so that the number of flaws below ε is the Weibull count kVε^m.
    for &probe in &[eps[10] * 1.000_001, eps[1000] * 1.000_001] {
        let below = eps.iter().filter(|&&x| x <= probe).count();
        assert_eq!(below, (1.4e19 * area * probe.powf(8.5)).floor() as usize);
    }
    // Each particle's list is ascending; its active count is a prefix length.
    let flaws = gk.seed_flaws(n, area, 7);
    for f in &flaws {
        assert!(f.windows(2).all(|w| w[0] <= w[1]));
        if let Some(&mid) = f.get(f.len() / 2) {
            assert_eq!(GradyKipp::active_flaws(f, mid), f.len() / 2 + 1);
        }
        assert_eq!(GradyKipp::active_flaws(f, 0.0), 0);
        assert_eq!(GradyKipp::active_flaws(f, f64::INFINITY), f.len());
    }
}

#[test]
fn grady_kipp_effective_strain() {
    assert_eq!(GradyKipp::effective_strain(-5.0, 0.0, 1.0), 0.0);
    assert_relative_eq!(
        GradyKipp::effective_strain(0.002, 0.5, 1.0),
        0.004,
        max_relative = 1e-15
    );
    assert_eq!(GradyKipp::effective_strain(0.002, 1.0, 1.0), f64::INFINITY);
}

#[test]
fn grady_kipp_growth_integrates_to_the_cube_law() {
    let gk = grady_kipp();
    let (c_g, r_s, dt) = (0.4 * 1.1602, 0.5, 1e-3);
    for n_act in [1usize, 3] {
        let rate = gk.damage_rate(n_act, n_act, c_g, r_s, 0.0);
        assert_relative_eq!(rate, n_act as f64 * c_g / r_s, max_relative = 1e-15);
        let mut damage = 0.0;
        let mut t = 0.0;
        loop {
            damage = gk.advance_damage(damage, n_act, n_act, c_g, r_s, dt);
            t += dt;
            let cube = (n_act as f64 * c_g * t / r_s).powi(3);
            if cube >= 1.0 {
                assert_eq!(damage, 1.0);
                break;
            }
            assert_relative_eq!(damage, cube, max_relative = 1e-10);
        }
        // Fully damaged: no further growth.
        assert_eq!(gk.damage_rate(n_act, n_act, c_g, r_s, 1.0), 0.0);
    }
}

#[test]
fn grady_kipp_damage_is_capped_by_the_active_fraction() {
    let gk = grady_kipp();
    let (c_g, r_s, dt) = (0.46, 0.5, 1e-2);
    assert_eq!(GradyKipp::damage_cap(1, 4), 0.25);
    assert_eq!(GradyKipp::damage_cap(0, 0), 0.0);
    let mut damage = 0.0;
    for _ in 0..1000 {
        damage = gk.advance_damage(damage, 1, 4, c_g, r_s, dt);
    }
    assert_eq!(damage, 0.25);
    assert_eq!(gk.damage_rate(1, 4, c_g, r_s, 0.25), 0.0);
    // Flaws deactivating on unloading do not heal the particle.
    assert_eq!(gk.advance_damage(0.25, 0, 4, c_g, r_s, dt), 0.25);
    // A particle without flaws never damages.
    assert_eq!(gk.advance_damage(0.0, 0, 0, c_g, r_s, dt), 0.0);
    // Tensile part degraded as in Peerlings.
    assert_relative_eq!(
        gk.degrade(&diag(4.0, -1.0, 0.0), 0.25),
        diag(3.0, -1.0, 0.0),
        epsilon = 1e-14
    );
}
