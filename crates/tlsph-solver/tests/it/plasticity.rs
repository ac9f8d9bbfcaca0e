//! Elastic–plastic bodies: the solver's constitutive wiring reproduces a material-point
//! integration of the same model on a homogeneous deformation path.

use super::{lattice, model, Setup};
use tlsph_materials::{LinearElastic, VonMisesPlasticity};
use tlsph_math::{deviator, Tensor, Tensor3, Vector};
use tlsph_solver::{
    ElasticPlastic, Formulation, MaterialModel, ParticleField, PressureModel, Simulation,
    StrengthModel, StressUpdate,
};

/// The M-CU6 copper of R-P6 (numerics.md §8.2 linear hardening, E_t = 1.1 GPa).
pub(super) fn copper() -> ElasticPlastic {
    let elastic = LinearElastic::new(110e9, 0.343).unwrap();
    ElasticPlastic {
        elastic,
        strength: StrengthModel::VonMises(
            VonMisesPlasticity::from_tangent_modulus(90e6, 110e9, 1.1e9).unwrap(),
        ),
        pressure: PressureModel::Hypoelastic,
        min_pressure: None,
        thermal: None,
        failure: None,
    }
}

#[test]
fn homogeneous_compression_matches_the_material_point() {
    // A 2D block driven through F(t) = diag(1 − ε̇t, 1) (plane-strain uniaxial compression to
    // 5 %). With corrected gradients every particle sees the exact F, so each must follow the
    // material-point integration of the same model with the same steps to round-off.
    let dx = 1e-3;
    let positions = lattice([8, 6], dx);
    let mut m = model(
        positions.clone(),
        dx,
        |_| Vector::<2>::zeros(),
        Setup {
            formulation: Formulation::TotalLagrangianCorrected,
            stress_update: StressUpdate::JaumannRate,
            end_time: 1.0,
            ..Setup::default()
        },
    );
    let material = copper();
    m.materials[0].density = 8990.0;
    m.materials[0].model = MaterialModel::ElasticPlastic(material);
    let mut sim = Simulation::new(m).unwrap();
    let rate = 1000.0; // compressive strain rate [1/s]
    let steps = 100;
    let dt_drive = 0.05 / rate / steps as f64;
    let stretch = |t: f64| 1.0 - rate * t;
    let displacement = |t: f64| -> Vec<Vector<2>> {
        positions
            .iter()
            .map(|x| Vector::<2>::new((stretch(t) - 1.0) * x[0], 0.0))
            .collect()
    };
    sim.step().unwrap();
    // Material point: same midpoint kinematics as the solver, D_xx = −ε̇/λ^{n−½}.
    let (g, k) = (
        material.elastic.shear_modulus(),
        material.elastic.bulk_modulus(),
    );
    let StrengthModel::VonMises(vm) = material.strength else {
        unreachable!()
    };
    let mut s = Tensor3::zeros();
    let mut p = 0.0;
    let mut ep = 0.0;
    let mut t = 0.0;
    for _ in 0..steps {
        let own = sim.next_dt();
        let now = displacement(t);
        let next = displacement(t + dt_drive);
        let v: Vec<Vector<2>> = now.iter().zip(&next).map(|(a, b)| (b - a) / own).collect();
        sim.set_displacements(&now);
        sim.set_velocities(&v);
        sim.step().unwrap();
        // The solver used Δt = own for this step with the same velocities.
        let f_dot = -rate * dt_drive / own;
        let f_half = stretch(t + dt_drive) - 0.5 * own * f_dot;
        let mut d = Tensor3::zeros();
        d[(0, 0)] = f_dot / f_half;
        p -= k * d.trace() * own;
        let trial = s + deviator(&d) * (2.0 * g * own);
        let ret = vm.return_map(&trial, g, ep);
        s = ret.deviator;
        ep += ret.plastic_strain_increment;
        t += dt_drive;
    }
    let expected = s - Tensor3::identity() * p;
    assert!(
        ep > 0.01,
        "the path must go well into the plastic range (ε̄p = {ep})"
    );
    for i in 0..sim.n_particles() {
        let sigma = sim.stresses()[i];
        assert!(
            (sigma - expected).norm() < 1e-6 * expected.norm(),
            "particle {i}: {sigma} vs {expected}"
        );
        let ep_i = sim.sample(ParticleField::PlasticStrain, i);
        assert!(
            (ep_i - ep).abs() < 1e-9 * ep,
            "particle {i}: ε̄p {ep_i} vs {ep}"
        );
    }
    let _ = Tensor::<2>::identity();
}

#[test]
fn plasticity_needs_the_rate_form() {
    let dx = 1e-3;
    let mut m = model(
        lattice([4, 4], dx),
        dx,
        |_| Vector::<2>::zeros(),
        Setup {
            stress_update: StressUpdate::GreenLagrange,
            ..Setup::default()
        },
    );
    m.materials[0].model = MaterialModel::ElasticPlastic(copper());
    let err = Simulation::new(m).unwrap_err();
    assert!(err.to_string().contains("jaumann-rate"), "{err}");
}

#[test]
fn a_failed_particle_leaves_every_sum_and_the_halves_separate() {
    // Both formulations: TLSPH rebuilds the survivors' reference gradients, conventional SPH
    // drops the failed particle from its current pairs.
    for formulation in [
        Formulation::TotalLagrangianCorrected,
        Formulation::UpdatedLagrangian,
    ] {
        failed_particle_case(formulation);
    }
}

fn failed_particle_case(formulation: Formulation) {
    // A 1D bar whose halves fly apart at ±0.05 c: the centre yields in tension, reaches the
    // failure strain and fails; afterwards no tension crosses the gap, so the halves keep
    // moving apart, momentum stays zero, and the failed particle carries no stress.
    use tlsph_materials::MaxPlasticStrainFailure;
    use tlsph_solver::FailureModel;
    let dx = 0.01;
    let positions = lattice([100], dx);
    let mut m = model(
        positions.clone(),
        dx,
        |x| Vector::<1>::new(if x[0] < 0.5 { -0.05 } else { 0.05 }),
        Setup {
            formulation,
            end_time: 3.0,
            ..Setup::default()
        },
    );
    let elastic = LinearElastic::new(0.9, 0.2).unwrap();
    m.materials[0].model = MaterialModel::ElasticPlastic(ElasticPlastic {
        elastic,
        strength: StrengthModel::VonMises(VonMisesPlasticity::new(0.01, 0.0).unwrap()),
        pressure: PressureModel::Hypoelastic,
        min_pressure: None,
        thermal: None,
        failure: Some(FailureModel::MaxPlasticStrain(
            MaxPlasticStrainFailure::new(0.05).unwrap(),
        )),
    });
    let mut sim = Simulation::new(m).unwrap();
    let mut worst_p: f64 = 0.0;
    sim.run(|s, _| worst_p = worst_p.max(s.diagnostics().linear_momentum.x.abs()))
        .unwrap();
    assert!(sim.failed_particles() >= 1, "the centre must fail");
    assert!(worst_p < 1e-15, "momentum {worst_p:e}");
    let failed: Vec<usize> = (0..sim.n_particles())
        .filter(|&i| sim.sample(ParticleField::Damage, i) >= 1.0)
        .collect();
    assert_eq!(failed.len(), sim.failed_particles());
    for &i in &failed {
        assert_eq!(sim.stresses()[i], Tensor3::zeros());
        // Failed particles sit near the centre, where the tension was largest.
        assert!(
            (positions[i][0] - 0.5).abs() < 0.1,
            "failed at {}",
            positions[i][0]
        );
    }
    // The halves separate: the right half moves right, the left half left.
    let v_left = sim.velocity(10)[0];
    let v_right = sim.velocity(89)[0];
    assert!(v_left < 0.0 && v_right > 0.0, "{v_left} {v_right}");
    let gap = sim.displacements()[99][0] - sim.displacements()[0][0];
    assert!(gap > 0.1, "halves did not separate: {gap}");
    // The failed particles' internal energy moves from `internal` to its own booked column:
    // exactly Σ m e over the failed particles, and the total is unchanged by the move.
    let d = sim.diagnostics();
    let deleted: f64 = failed
        .iter()
        .map(|&i| sim.masses()[i] * sim.internal_energies()[i])
        .sum();
    let all: f64 = (0..sim.n_particles())
        .map(|i| sim.masses()[i] * sim.internal_energies()[i])
        .sum();
    let column = d
        .effect_energies
        .iter()
        .find(|(name, _)| name == "deleted_particles")
        .map(|(_, e)| *e)
        .expect("a deleted_particles column with a failure model");
    assert!(deleted > 0.0);
    assert!((column - deleted).abs() <= 1e-12 * all.abs());
    assert!((d.internal + column - all).abs() <= 1e-12 * all.abs());
}
