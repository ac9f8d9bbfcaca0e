//! Contract tests for the pointwise material models.

use approx::assert_relative_eq;
use tlsph_materials::LinearElastic;
use tlsph_math::Tensor3;

fn steel() -> LinearElastic {
    LinearElastic::new(210e9, 0.3).unwrap()
}

/// Rotation about an arbitrary axis by angle θ (Rodrigues).
fn rotation(axis: [f64; 3], angle: f64) -> Tensor3 {
    let a = tlsph_math::Vector3::new(axis[0], axis[1], axis[2]).normalize();
    nalgebra_rotation(a, angle)
}

fn nalgebra_rotation(a: tlsph_math::Vector3, angle: f64) -> Tensor3 {
    let k = Tensor3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0);
    Tensor3::identity() + k * angle.sin() + k * k * (1.0 - angle.cos())
}

#[test]
fn moduli_follow_from_e_and_nu() {
    // R-P2 material M-ND2: E 0.9, ν 0.2 → K 0.5, G 0.375, M 1.0 (problems.md §1).
    let m = LinearElastic::new(0.9, 0.2).unwrap();
    assert_relative_eq!(m.bulk_modulus(), 0.5, max_relative = 1e-12);
    assert_relative_eq!(m.shear_modulus(), 0.375, max_relative = 1e-12);
    assert_relative_eq!(m.longitudinal_modulus(), 1.0, max_relative = 1e-12);
    assert_relative_eq!(m.sound_speed(1.0), 1.0, max_relative = 1e-12);
}

#[test]
fn impossible_parameters_are_rejected_with_their_name() {
    for (e, nu, name) in [
        (-1.0, 0.3, "youngs_modulus"),
        (0.0, 0.3, "youngs_modulus"),
        (f64::NAN, 0.3, "youngs_modulus"),
        (1.0, 0.5, "poisson_ratio"),
        (1.0, -1.0, "poisson_ratio"),
        (1.0, 0.7, "poisson_ratio"),
    ] {
        let err = LinearElastic::new(e, nu).unwrap_err();
        assert_eq!(err.parameter, name);
        assert!(err.to_string().contains(name));
    }
}

#[test]
fn zero_strain_gives_zero_stress() {
    let m = steel();
    assert_eq!(
        m.second_piola_kirchhoff(&Tensor3::zeros()),
        Tensor3::zeros()
    );
    assert_eq!(
        m.jaumann_update(
            &Tensor3::zeros(),
            &Tensor3::zeros(),
            &Tensor3::zeros(),
            1e-6
        ),
        Tensor3::zeros()
    );
}

#[test]
fn pk2_under_rigid_rotation_is_zero() {
    // E = ½(FᵀF − I) vanishes for F = R, so S = 0 to round-off.
    let r = rotation([1.0, 2.0, 3.0], 1.1);
    let e = (r.transpose() * r - Tensor3::identity()) * 0.5;
    let m = steel();
    let s = m.second_piola_kirchhoff(&e);
    // Round-off bound: |E| is a few machine epsilons, so |S| ≲ 10 ε M.
    assert!(
        s.norm() < 10.0 * f64::EPSILON * m.longitudinal_modulus(),
        "{s}"
    );
}

#[test]
fn uniaxial_strain_rate_gives_longitudinal_modulus() {
    let m = steel();
    let mut d = Tensor3::zeros();
    d[(0, 0)] = 1.0;
    let s = m.jaumann_update(&Tensor3::zeros(), &d, &Tensor3::zeros(), 1e-3);
    assert_relative_eq!(
        s[(0, 0)],
        m.longitudinal_modulus() * 1e-3,
        max_relative = 1e-12
    );
    assert_relative_eq!(s[(1, 1)], m.lambda() * 1e-3, max_relative = 1e-12);
}

#[test]
fn jaumann_update_is_objective_under_pure_spin() {
    // A pure spin rotates the stress without changing its invariants, for any step size.
    let m = steel();
    let sigma = Tensor3::new(3.0, 1.0, 0.5, 1.0, -2.0, 0.25, 0.5, 0.25, 1.0) * 1e8;
    let w = Tensor3::new(0.0, -2.0, 1.0, 2.0, 0.0, -0.5, -1.0, 0.5, 0.0) * 1e3;
    let mut s = sigma;
    for _ in 0..1000 {
        s = m.jaumann_update(&s, &Tensor3::zeros(), &w, 1e-4);
    }
    let eig0 = sigma.symmetric_eigenvalues();
    let eig1 = s.symmetric_eigenvalues();
    let mut a: Vec<f64> = eig0.iter().copied().collect();
    let mut b: Vec<f64> = eig1.iter().copied().collect();
    a.sort_by(f64::total_cmp);
    b.sort_by(f64::total_cmp);
    for (x, y) in a.iter().zip(&b) {
        assert_relative_eq!(x, y, max_relative = 1e-10);
    }
}

#[test]
fn strain_energy_is_consistent_with_pk2() {
    // S = ∂ψ/∂E checked by central differences.
    let m = LinearElastic::new(2.0, 0.25).unwrap();
    let e = Tensor3::new(0.01, 0.002, 0.0, 0.002, -0.003, 0.001, 0.0, 0.001, 0.004);
    let s = m.second_piola_kirchhoff(&e);
    let eps = 1e-7;
    for i in 0..3 {
        for j in 0..3 {
            let mut de = Tensor3::zeros();
            // Symmetric perturbation: ψ depends on the symmetric part only.
            de[(i, j)] += 0.5 * eps;
            de[(j, i)] += 0.5 * eps;
            let fd = (m.strain_energy_density(&(e + de)) - m.strain_energy_density(&(e - de)))
                / (2.0 * eps);
            let expected = 0.5 * (s[(i, j)] + s[(j, i)]);
            assert_relative_eq!(fd, expected, epsilon = 1e-8, max_relative = 1e-6);
        }
    }
}

mod damage;
mod drivers;
mod eos;
mod johnson_cook;
mod objectivity;
mod von_mises;
