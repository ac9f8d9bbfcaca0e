//! Symmetry planes by ghost particles: a quarter model with two planes reproduces the full
//! model's motion (numerics.md §13.1), for raw and corrected gradients and both stress paths.

use super::{model, Setup};
use tlsph_math::Vector;
use tlsph_solver::{Formulation, ReferenceUpdate, Simulation, StressUpdate, SymmetryPlane};

/// Cell-centred lattice on [-a, a] × [-b, b] (symmetric about both axes).
fn centred(nx: usize, ny: usize, dx: f64) -> Vec<Vector<2>> {
    let mut out = Vec::new();
    for i in 0..2 * nx {
        for j in 0..2 * ny {
            out.push(Vector::<2>::new(
                (i as f64 - nx as f64 + 0.5) * dx,
                (j as f64 - ny as f64 + 0.5) * dx,
            ));
        }
    }
    out
}

/// Mirror-symmetric velocity field: v_x odd in x and even in y, v_y the reverse.
fn symmetric_velocity(x: &Vector<2>) -> Vector<2> {
    Vector::<2>::new(
        0.01 * x[0] * (1.0 + 20.0 * x[1] * x[1]),
        -0.02 * x[1] * (1.0 + 10.0 * x[0] * x[0]),
    )
}

#[test]
fn a_quarter_model_with_two_planes_moves_like_the_full_model() {
    let dx = 0.05;
    for (formulation, update, reference_update) in [
        (
            Formulation::TotalLagrangian,
            StressUpdate::JaumannRate,
            None,
        ),
        (
            Formulation::TotalLagrangianCorrected,
            StressUpdate::JaumannRate,
            None,
        ),
        (
            Formulation::TotalLagrangian,
            StressUpdate::GreenLagrange,
            None,
        ),
        // Ghosts rebuilt at every reference update (numerics.md §4 [C]).
        (
            Formulation::TotalLagrangianCorrected,
            StressUpdate::JaumannRate,
            Some(2e-3),
        ),
    ] {
        let setup = || Setup {
            formulation,
            stress_update: update,
            end_time: 0.6,
            ..Setup::default()
        };
        let full_positions = centred(8, 6, dx);
        let quarter_positions: Vec<Vector<2>> = full_positions
            .iter()
            .copied()
            .filter(|x| x[0] > 0.0 && x[1] > 0.0)
            .collect();
        let mut full = model(full_positions.clone(), dx, symmetric_velocity, setup());
        full.effects.reference_update = reference_update.map(|strain_threshold| ReferenceUpdate {
            strain_threshold,
            support: Default::default(),
        });
        let mut quarter = model(quarter_positions.clone(), dx, symmetric_velocity, setup());
        quarter.effects.reference_update = full.effects.reference_update;
        quarter.effects.symmetry_planes = vec![
            SymmetryPlane {
                axis: 0,
                position: 0.0,
            },
            SymmetryPlane {
                axis: 1,
                position: 0.0,
            },
        ];
        let mut a = Simulation::new(full).unwrap();
        let mut b = Simulation::new(quarter).unwrap();
        assert_eq!(
            b.n_particles(),
            quarter_positions.len(),
            "ghosts are not counted as particles"
        );
        a.run(|_, _| {}).unwrap();
        b.run(|_, _| {}).unwrap();
        assert_eq!(a.steps_done(), b.steps_done());
        assert_eq!(a.reference_updates(), b.reference_updates());
        assert_eq!(reference_update.is_some(), a.reference_updates() > 1);
        let scale = (0..a.n_particles())
            .map(|i| a.total_displacement(i).norm())
            .fold(0.0, f64::max);
        for (k, x) in quarter_positions.iter().enumerate() {
            let i = full_positions.iter().position(|y| y == x).unwrap();
            let diff = (a.total_displacement(i) - b.total_displacement(k)).norm();
            assert!(
                diff < 1e-10 * scale,
                "{formulation:?}/{update:?} particle at {x}: {diff:e} (scale {scale:e})"
            );
            let ds = (a.stresses()[i] - b.stresses()[k]).norm() / a.stresses()[i].norm().max(1e-30);
            assert!(
                ds < 1e-8,
                "{formulation:?}/{update:?} stress at {x}: {ds:e}"
            );
        }
    }
}

#[test]
fn a_body_across_a_symmetry_plane_is_rejected() {
    let dx = 0.05;
    let mut m = model(
        centred(4, 4, dx),
        dx,
        |_| Vector::<2>::zeros(),
        Setup::default(),
    );
    m.effects.symmetry_planes = vec![SymmetryPlane {
        axis: 0,
        position: 0.0,
    }];
    let err = Simulation::new(m).unwrap_err();
    assert!(err.to_string().contains("both sides"), "{err}");
}

#[test]
fn a_quarter_model_fails_the_same_particles_as_the_full_model() {
    // The halves x < 0 and x > 0 fly apart at ±0.05 c (mirror-symmetric about both axes):
    // the two central columns yield, reach the failure strain and fail. With symmetry planes a
    // failed particle's mirror images must leave every sum with it, and the survivors'
    // gradients (including the mirrored reverse gradients) must be rebuilt exactly as in the
    // full model.
    use tlsph_materials::{LinearElastic, MaxPlasticStrainFailure, VonMisesPlasticity};
    use tlsph_solver::{
        ElasticPlastic, FailureModel, MaterialModel, ParticleField, PressureModel, StrengthModel,
    };
    let dx = 0.05;
    let setup = || Setup {
        formulation: Formulation::TotalLagrangianCorrected,
        end_time: 1.5,
        ..Setup::default()
    };
    let pull = |x: &Vector<2>| Vector::<2>::new(0.05 * x[0].signum(), 0.0);
    let material = MaterialModel::ElasticPlastic(ElasticPlastic {
        elastic: LinearElastic::new(0.9, 0.2).unwrap(),
        strength: StrengthModel::VonMises(VonMisesPlasticity::new(0.01, 0.0).unwrap()),
        pressure: PressureModel::Hypoelastic,
        min_pressure: None,
        thermal: None,
        failure: Some(FailureModel::MaxPlasticStrain(
            MaxPlasticStrainFailure::new(0.05).unwrap(),
        )),
    });
    let full_positions = centred(10, 4, dx);
    let quarter_positions: Vec<Vector<2>> = full_positions
        .iter()
        .copied()
        .filter(|x| x[0] > 0.0 && x[1] > 0.0)
        .collect();
    let mut full = model(full_positions.clone(), dx, pull, setup());
    full.materials[0].model = material;
    let mut quarter = model(quarter_positions.clone(), dx, pull, setup());
    quarter.materials[0].model = material;
    quarter.effects.symmetry_planes = vec![
        SymmetryPlane {
            axis: 0,
            position: 0.0,
        },
        SymmetryPlane {
            axis: 1,
            position: 0.0,
        },
    ];
    let mut a = Simulation::new(full).unwrap();
    let mut b = Simulation::new(quarter).unwrap();
    a.run(|_, _| {}).unwrap();
    b.run(|_, _| {}).unwrap();
    assert!(b.failed_particles() > 0, "the central column must fail");
    assert_eq!(a.failed_particles(), 4 * b.failed_particles());
    let scale = a
        .displacements()
        .iter()
        .map(|u| u.norm())
        .fold(0.0, f64::max);
    for (k, x) in quarter_positions.iter().enumerate() {
        let i = full_positions.iter().position(|y| y == x).unwrap();
        assert_eq!(
            a.sample(ParticleField::Damage, i),
            b.sample(ParticleField::Damage, k),
            "failure state at {x}"
        );
        let diff = (a.displacements()[i] - b.displacements()[k]).norm();
        assert!(
            diff < 1e-9 * scale,
            "particle at {x}: {diff:e} (scale {scale:e})"
        );
    }
}
