//! Symmetry planes by ghost particles: a quarter model with two planes reproduces the full
//! model's motion (numerics.md §13.1), for raw and corrected gradients, both stress paths and
//! the updated-Lagrangian formulation.

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

/// The planes x = 0 and y = 0 of a quarter model.
fn quarter_planes() -> Vec<SymmetryPlane> {
    [0, 1]
        .map(|axis| SymmetryPlane {
            axis,
            position: 0.0,
        })
        .to_vec()
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
    for (formulation, update, reference_update, numerical_effects) in [
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
        // Ghosts rebuilt from the current positions with every Verlet list.
        (
            Formulation::UpdatedLagrangian,
            StressUpdate::JaumannRate,
            None,
        ),
    ]
    .into_iter()
    .map(|(f, u, r)| (f, u, r, false))
    // Hourglass control and pairwise viscosity act across the planes: bonds to ghosts count,
    // with the ghosts' mirrored F and motion.
    .chain([
        (
            Formulation::TotalLagrangianCorrected,
            StressUpdate::JaumannRate,
            None,
            true,
        ),
        (
            Formulation::TotalLagrangianCorrected,
            StressUpdate::JaumannRate,
            Some(2e-3),
            true,
        ),
        (
            Formulation::UpdatedLagrangian,
            StressUpdate::JaumannRate,
            None,
            true,
        ),
    ]) {
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
        if numerical_effects {
            full.effects.pairwise_viscosity = Some((1.0, 2.0));
            if formulation != Formulation::UpdatedLagrangian {
                full.effects.hourglass_control = Some(1.0);
            }
        }
        let mut quarter = model(quarter_positions.clone(), dx, symmetric_velocity, setup());
        quarter.effects.reference_update = full.effects.reference_update;
        quarter.effects.pairwise_viscosity = full.effects.pairwise_viscosity;
        quarter.effects.hourglass_control = full.effects.hourglass_control;
        quarter.effects.symmetry_planes = quarter_planes();
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
        // Every numerical mechanism booked a quarter of the full model's energy.
        let (da, db) = (a.diagnostics(), b.diagnostics());
        assert_eq!(
            da.effect_energies.len(),
            usize::from(numerical_effects)
                * (1 + usize::from(formulation != Formulation::UpdatedLagrangian))
        );
        for ((name, ea), (_, eb)) in da.effect_energies.iter().zip(&db.effect_energies) {
            assert!(*ea > 0.0, "{formulation:?}: {name} booked {ea:e}");
            assert!(
                (ea - 4.0 * eb).abs() <= 1e-8 * ea.abs(),
                "{formulation:?}: {name}: full {ea:e}, quarter {eb:e}"
            );
        }
        let scale = (0..a.n_particles())
            .map(|i| a.total_displacement(i).norm())
            .fold(0.0, f64::max);
        for (k, x) in quarter_positions.iter().enumerate() {
            let i = full_positions.iter().position(|y| y == x).unwrap();
            let diff = (a.total_displacement(i) - b.total_displacement(k)).norm();
            assert!(
                diff < 1e-10 * scale,
                "{formulation:?}/{update:?}/{numerical_effects} particle at {x}: {diff:e} (scale {scale:e})"
            );
            let ds = (a.stresses()[i] - b.stresses()[k]).norm() / a.stresses()[i].norm().max(1e-30);
            assert!(
                ds < 1e-8,
                "{formulation:?}/{update:?}/{numerical_effects} stress at {x}: {ds:e}"
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
fn bodies_on_both_sides_of_a_symmetry_plane_are_rejected() {
    // Each block lies on one side of x = 0, but on different sides: the image of each would
    // overlap the other, so the model would not be the mirror-symmetric half of anything.
    let dx = 0.05;
    let block = |x0: f64| -> Vec<Vector<2>> {
        super::lattice([4, 4], dx)
            .iter()
            .map(|x| x + Vector::<2>::new(x0, 0.0))
            .collect()
    };
    let mut m = model(block(0.1), dx, |_| Vector::<2>::zeros(), Setup::default());
    let mut other = m.bodies[0].clone();
    other.name = "left".into();
    other.positions = block(-0.4);
    m.bodies.push(other);
    m.effects.symmetry_planes = vec![SymmetryPlane {
        axis: 0,
        position: 0.0,
    }];
    let err = Simulation::new(m).unwrap_err();
    assert!(
        err.to_string().contains("`left`")
            && err.to_string().contains("other side of the symmetry plane"),
        "{err}"
    );
}

#[test]
fn a_particle_closer_to_a_plane_than_a_quarter_spacing_is_rejected() {
    // The lattice's first column at x = offset from the plane x = 0: at half a spacing (as a
    // lattice cut by the plane puts it) and down to a quarter the model is accepted; closer,
    // the particle would sit within half a spacing of its own image (a first-user review ran
    // a column 0.05 spacing from the plane without comment).
    let dx = 0.05;
    let block = |offset: f64| -> Vec<Vector<2>> {
        super::lattice([4, 4], dx)
            .iter()
            .map(|x| x + Vector::<2>::new(offset * dx - 0.5 * dx, 0.0))
            .collect()
    };
    let with_plane = |offset: f64| {
        let mut m = model(
            block(offset),
            dx,
            |_| Vector::<2>::zeros(),
            Setup::default(),
        );
        m.effects.symmetry_planes = vec![SymmetryPlane {
            axis: 0,
            position: 0.0,
        }];
        Simulation::new(m)
    };
    for offset in [0.5, 0.25] {
        with_plane(offset).unwrap();
    }
    for offset in [0.2, 0.05] {
        let err = with_plane(offset).unwrap_err().to_string();
        assert!(
            err.contains("particle 0 at")
                && err.contains("less than a quarter of the spacing")
                && err.contains("its own mirror image"),
            "offset {offset}: {err}"
        );
    }
}

#[test]
fn two_planes_normal_to_one_axis_are_rejected() {
    // A plane declared twice (or two parallel planes) would mirror each other's images without
    // end; before this check the bond builder panicked on it.
    let dx = 0.05;
    let block: Vec<Vector<2>> = super::lattice([4, 4], dx)
        .iter()
        .map(|x| x + Vector::<2>::new(0.1, 0.0))
        .collect();
    for second in [0.0, 1.0] {
        let mut m = model(
            block.clone(),
            dx,
            |_| Vector::<2>::zeros(),
            Setup::default(),
        );
        m.effects.symmetry_planes = vec![
            SymmetryPlane {
                axis: 0,
                position: 0.0,
            },
            SymmetryPlane {
                axis: 0,
                position: second,
            },
        ];
        let err = Simulation::new(m).unwrap_err();
        assert!(
            err.to_string().contains("symmetry_planes")
                && err.to_string().contains("one symmetry plane per axis"),
            "{err}"
        );
    }
}

#[test]
fn a_quarter_model_fails_the_same_particles_as_the_full_model() {
    // The halves x < 0 and x > 0 fly apart at ±0.05 c (mirror-symmetric about both axes):
    // the two central columns yield, reach the failure strain and fail. With symmetry planes a
    // failed particle's mirror images must leave every sum with it, and the survivors'
    // gradients (including the mirrored reverse gradients) must be rebuilt exactly as in the
    // full model; in updated-Lagrangian SPH the failed particle is no longer mirrored.
    use tlsph_solver::ParticleField;
    let dx = 0.05;
    for formulation in [
        Formulation::TotalLagrangianCorrected,
        Formulation::UpdatedLagrangian,
    ] {
        let setup = || Setup {
            formulation,
            end_time: 1.5,
            ..Setup::default()
        };
        let pull = |x: &Vector<2>| Vector::<2>::new(0.05 * x[0].signum(), 0.0);
        let material = super::plasticity::brittle_plastic();
        let full_positions = centred(10, 4, dx);
        let quarter_positions: Vec<Vector<2>> = full_positions
            .iter()
            .copied()
            .filter(|x| x[0] > 0.0 && x[1] > 0.0)
            .collect();
        let mut full = model(full_positions.clone(), dx, pull, setup());
        full.materials[0].model = material;
        // The numerical mechanisms that walk neighbours must drop failed particles too.
        full.effects.pairwise_viscosity = Some((1.0, 2.0));
        if formulation != Formulation::UpdatedLagrangian {
            full.effects.hourglass_control = Some(1.0);
        }
        let mut quarter = model(quarter_positions.clone(), dx, pull, setup());
        quarter.materials[0].model = material;
        quarter.effects.pairwise_viscosity = full.effects.pairwise_viscosity;
        quarter.effects.hourglass_control = full.effects.hourglass_control;
        quarter.effects.symmetry_planes = quarter_planes();
        let mut a = Simulation::new(full).unwrap();
        let mut b = Simulation::new(quarter).unwrap();
        // A failed particle leaves every sum: from the step it fails on, it flies on with
        // the velocity it had.
        let mut velocity_at_failure = vec![None; a.n_particles()];
        a.run(|sim, _| {
            for (i, v) in velocity_at_failure.iter_mut().enumerate() {
                if sim.sample(ParticleField::Damage, i) == 1.0 {
                    let now = sim.velocity(i);
                    let then = *v.get_or_insert(now);
                    assert!(
                        (now - then).norm() <= 1e-12 * then.norm(),
                        "{formulation:?}: failed particle {i} was accelerated: {then} -> {now}"
                    );
                }
            }
        })
        .unwrap();
        b.run(|_, _| {}).unwrap();
        assert!(
            b.failed_particles() > 0,
            "{formulation:?}: the central column must fail"
        );
        assert_eq!(
            a.failed_particles(),
            4 * b.failed_particles(),
            "{formulation:?}"
        );
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
                "{formulation:?}: failure state at {x}"
            );
            let diff = (a.displacements()[i] - b.displacements()[k]).norm();
            assert!(
                diff < 1e-9 * scale,
                "{formulation:?}: particle at {x}: {diff:e} (scale {scale:e})"
            );
        }
    }
}

#[test]
fn an_updated_lagrangian_half_model_meets_its_mirror_image_like_the_full_model() {
    // Two blocks of one material, 6Δx apart, approach each other at ±0.05 c and interact
    // through the kernel (conventional SPH). The half model x > 0 has the plane x = 0
    // instead of the other block: it starts 3.5Δx from the plane, beyond the reach of the
    // mirror images (support 2.4Δx + skin 0.3Δx), so it has no ghosts until it comes close and
    // the ghost set must grow, and change, with the Verlet list. The pairwise artificial
    // viscosity, the artificial stress and XSPH read the ghosts' mirrored motion and stress.
    use tlsph_solver::ArtificialStress;
    let dx = 0.05;
    let (nx, ny) = (8, 6);
    let gap = 6.0 * dx;
    let mut full_positions = Vec::new();
    for side in [-1.0, 1.0] {
        for i in 0..nx {
            for j in 0..ny {
                full_positions.push(Vector::<2>::new(
                    side * (0.5 * gap + (i as f64 + 0.5) * dx),
                    j as f64 * dx,
                ));
            }
        }
    }
    let half_positions: Vec<Vector<2>> = full_positions
        .iter()
        .copied()
        .filter(|x| x[0] > 0.0)
        .collect();
    let approach = |x: &Vector<2>| Vector::<2>::new(-0.05 * x[0].signum(), 0.0);
    let with_effects = |positions: Vec<Vector<2>>| {
        let mut m = model(
            positions,
            dx,
            approach,
            Setup {
                formulation: Formulation::UpdatedLagrangian,
                end_time: 3.2,
                ..Setup::default()
            },
        );
        m.effects.pairwise_viscosity = Some((1.0, 2.0));
        m.effects.artificial_stress = Some(ArtificialStress {
            epsilon: 0.3,
            exponent: 4.0,
            bodies: None,
        });
        m.effects.xsph = Some(0.3);
        m
    };
    let mut half = with_effects(half_positions.clone());
    half.effects.symmetry_planes = vec![SymmetryPlane {
        axis: 0,
        position: 0.0,
    }];
    let mut a = Simulation::new(with_effects(full_positions.clone())).unwrap();
    let mut b = Simulation::new(half).unwrap();
    let (mut closest, mut fastest_rebound) = (f64::INFINITY, 0.0f64);
    a.run(|_, _| {}).unwrap();
    b.run(|sim, _| {
        for k in 0..sim.n_particles() {
            let x = sim.initial_position(k) + sim.total_displacement(k);
            closest = closest.min(x[0]);
            fastest_rebound = fastest_rebound.max(sim.velocity(k)[0]);
        }
    })
    .unwrap();
    // The half block came within the support 2h of its image (h of the plane; h = 1.2Δx)
    // and was pushed back.
    assert!(
        closest < 1.2 * dx,
        "closest approach to the plane {closest}"
    );
    assert!(fastest_rebound > 0.0, "no particle rebounded");
    assert!(
        b.neighbour_rebuilds().unwrap() > 1,
        "the Verlet list was never rebuilt"
    );
    assert_eq!(a.steps_done(), b.steps_done());
    let scale = (0..a.n_particles())
        .map(|i| a.total_displacement(i).norm())
        .fold(0.0, f64::max);
    for (k, x) in half_positions.iter().enumerate() {
        let i = full_positions.iter().position(|y| y == x).unwrap();
        let diff = (a.total_displacement(i) - b.total_displacement(k)).norm();
        assert!(
            diff < 1e-10 * scale,
            "particle at {x}: {diff:e} (scale {scale:e})"
        );
        let ds = (a.stresses()[i] - b.stresses()[k]).norm() / a.stresses()[i].norm().max(1e-30);
        assert!(ds < 1e-8, "stress at {x}: {ds:e}");
    }
    // Every numerical mechanism booked half the full model's energy.
    let (da, db) = (a.diagnostics(), b.diagnostics());
    for ((name, ea), (_, eb)) in da.effect_energies.iter().zip(&db.effect_energies) {
        assert!(
            (ea - 2.0 * eb).abs() <= 1e-9 * ea.abs().max(1e-30),
            "{name}: full {ea:e}, half {eb:e}"
        );
    }
    assert!((da.kinetic - 2.0 * db.kinetic).abs() < 1e-9 * da.kinetic);
}
