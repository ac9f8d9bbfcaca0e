//! Reference-configuration update (numerics.md §4 `[C]`): re-referencing preserves the state
//! it inherits, stays deterministic, and is rejected where it cannot be right.

use super::plasticity::copper;
use super::{lattice, model, Setup};
use tlsph_contact::FrictionCoefficients;
use tlsph_materials::LinearElastic;
use tlsph_math::{Tensor, Vector};
use tlsph_solver::{
    BoundaryDescription, ContactDescription, Formulation, MaterialModel, Model, ParticleField,
    PenaltyContactDescription, ReferenceSupport, ReferenceUpdate, SetupError, Simulation,
    StressUpdate,
};

/// A plastic plane-strain block of 10 × 8 particles whose every particle is driven with
/// v = H X, so x = (I + tH) X stays exactly affine: F = I + tH reaches strains of about 0.5.
fn driven_block(reference_update: Option<f64>) -> Model<2> {
    driven_block_with(reference_update, ReferenceSupport::Stretched)
}

/// [`driven_block`] with the given choice of kernel supports on an updated reference.
fn driven_block_with(reference_update: Option<f64>, support: ReferenceSupport) -> Model<2> {
    let dx = 1e-3;
    let positions = lattice([10, 8], dx);
    let h = Tensor::<2>::new(-400.0, 150.0, 50.0, 250.0); // 1/s
    let mut m = model(
        positions.clone(),
        dx,
        |x| h * x,
        Setup {
            formulation: Formulation::TotalLagrangianCorrected,
            stress_update: StressUpdate::JaumannRate,
            end_time: 1e-3,
            ..Setup::default()
        },
    );
    m.materials[0].density = 8990.0;
    m.materials[0].model = MaterialModel::ElasticPlastic(copper());
    m.boundaries = positions
        .iter()
        .enumerate()
        .map(|(i, x)| BoundaryDescription {
            name: format!("p{i}"),
            body: 0,
            particles: vec![i],
            velocity: h * x,
            components: [true, true],
            amplitude: None,
        })
        .collect();
    m.effects.reference_update = reference_update.map(|strain_threshold| ReferenceUpdate {
        strain_threshold,
        support,
    });
    m
}

#[test]
fn re_referencing_an_affine_motion_changes_nothing_but_the_reference() {
    // With corrected gradients F is exact for an affine motion on any reference and any
    // kernel supports, so the run with updates must reproduce the run without them: stress,
    // plastic strain, density and energy to round-off (the rates D, W are the same; only F is
    // factored differently).
    for support in [ReferenceSupport::Stretched, ReferenceSupport::Fixed] {
        affine_motion_is_reproduced(support);
    }
}

fn affine_motion_is_reproduced(support: ReferenceSupport) {
    let mut plain = Simulation::new(driven_block(None)).unwrap();
    let mut updated = Simulation::new(driven_block_with(Some(0.05), support)).unwrap();
    plain.run(|_, _| {}).unwrap();
    updated.run(|_, _| {}).unwrap();
    assert_eq!(plain.steps_done(), updated.steps_done());
    assert!(
        updated.reference_updates() >= 5,
        "the strain path must cross the threshold several times ({} updates)",
        updated.reference_updates()
    );
    assert_eq!(plain.reference_updates(), 0);
    let scale = plain.stresses()[0].norm();
    for i in 0..plain.n_particles() {
        let ds = (plain.stresses()[i] - updated.stresses()[i]).norm();
        assert!(ds < 1e-8 * scale, "particle {i}: stress differs by {ds:e}");
        for field in [
            ParticleField::PlasticStrain,
            ParticleField::Density,
            ParticleField::InternalEnergy,
            ParticleField::Displacement(0),
            ParticleField::Displacement(1),
        ] {
            let (a, b) = (plain.sample(field, i), updated.sample(field, i));
            assert!(
                (a - b).abs() <= 1e-9 * a.abs().max(1e-12),
                "particle {i}: {field:?} {a} vs {b}"
            );
        }
        // The reference is now the current configuration: u is small, x is the same.
        let x = |s: &Simulation<2>| s.positions0()[i] + s.displacements()[i];
        assert!((x(&plain) - x(&updated)).norm() < 1e-15);
        assert_eq!(updated.initial_position(i), plain.positions0()[i]);
    }
    let (ep, rho) = (
        plain.sample(ParticleField::PlasticStrain, 0),
        plain.sample(ParticleField::Density, 0),
    );
    assert!(
        ep > 0.3,
        "the path must be well into the plastic range (ε̄p = {ep})"
    );
    // ρ = ρ0 / det(I + tH) at t = 1 ms.
    let det = (1.0 - 0.4) * (1.0 + 0.25) - 0.15 * 0.05;
    approx::assert_relative_eq!(rho, 8990.0 / det, max_relative = 1e-9);
}

/// Initial-configuration neighbour pairs (real particles) of a simulation's current bonds that
/// are no longer bonds, out of all initial pairs.
fn initial_pairs_lost(initial: &[Vec<u32>], sim: &Simulation<2>) -> (usize, usize) {
    let mut lost = 0;
    let mut total = 0;
    for (i, list) in initial.iter().enumerate() {
        for &j in list {
            total += 1;
            if !sim.bonds().neighbours_of(i).contains(&j) {
                lost += 1;
            }
        }
    }
    (lost, total)
}

#[test]
fn stretched_supports_keep_every_initial_neighbour_and_fixed_ones_lose_some() {
    // The driven block ends stretched by λ_max ≈ 1.3 (F = I + tH). A stretched support
    // h λ_max(F0) covers the image of every initial support, so no initial pair leaves the
    // bonds; with the body's h, pairs stretched beyond 2h drop out.
    let initial: Vec<Vec<u32>> = {
        let sim = Simulation::new(driven_block(None)).unwrap();
        (0..sim.n_particles())
            .map(|i| sim.bonds().neighbours_of(i).to_vec())
            .collect()
    };
    let run = |support| {
        let mut sim = Simulation::new(driven_block_with(Some(0.05), support)).unwrap();
        sim.run(|_, _| {}).unwrap();
        assert!(sim.reference_updates() >= 5);
        initial_pairs_lost(&initial, &sim)
    };
    let (lost, total) = run(ReferenceSupport::Stretched);
    assert_eq!(
        lost, 0,
        "{lost} of {total} initial pairs lost with stretched supports"
    );
    let (lost, total) = run(ReferenceSupport::Fixed);
    assert!(
        lost * 20 > total,
        "with fixed supports the stretch must cost initial pairs ({lost} of {total})"
    );
}

fn free_block_with_threads(threads: usize) -> (Vec<Vector<2>>, Vec<tlsph_math::Tensor3>, u64) {
    super::on_threads(threads, || {
        let mut m = driven_block(Some(1e-4));
        // Free (no prescribed velocities): the motion is no longer affine.
        m.boundaries.clear();
        m.config.end_time = 2e-4;
        let mut sim = Simulation::new(m).unwrap();
        sim.run(|_, _| {}).unwrap();
        let u = (0..sim.n_particles())
            .map(|i| sim.total_displacement(i))
            .collect();
        (u, sim.stresses().to_vec(), sim.reference_updates())
    })
}

#[test]
fn re_referenced_runs_are_bit_identical_for_any_thread_count() {
    let one = free_block_with_threads(1);
    let two = free_block_with_threads(2);
    assert!(
        one.2 > 1,
        "the run must update its reference ({} updates)",
        one.2
    );
    assert_eq!(one, two);
}

#[test]
fn a_reference_update_is_rejected_where_it_cannot_be_right() {
    let field_of = |m: Model<2>| match Simulation::new(m) {
        Err(SetupError::InvalidConfig { field, message }) => (field, message),
        other => panic!("expected a rejected reference update, got {other:?}"),
    };
    let mut bad_threshold = driven_block(Some(0.0));
    bad_threshold.boundaries.clear();
    assert_eq!(field_of(bad_threshold).0, "reference_update");
    let mut updated_lagrangian = driven_block(Some(0.1));
    updated_lagrangian.config.formulation = Formulation::UpdatedLagrangian;
    assert_eq!(field_of(updated_lagrangian).0, "reference_update");
    let mut elastic_green_lagrange = driven_block(Some(0.1));
    elastic_green_lagrange.materials[0].model =
        MaterialModel::LinearElastic(LinearElastic::new(110e9, 0.343).unwrap());
    elastic_green_lagrange.config.stress_update = StressUpdate::GreenLagrange;
    let (field, message) = field_of(elastic_green_lagrange);
    assert_eq!(field, "reference_update");
    assert!(message.contains("jaumann-rate"), "{message}");
    // A new reference bonds every pair within the kernel support: surfaces held together by
    // self-contact, of either law, would be welded.
    for penalty in [false, true] {
        let mut self_contact = driven_block(Some(0.1));
        if penalty {
            self_contact.effects.penalty_contact = Some(PenaltyContactDescription {
                stiffness: 1.0,
                range: 1.0,
                friction: FrictionCoefficients::single(0.2),
                pairs: Some(vec![(0, 0)]),
            });
        } else {
            self_contact.effects.contact = Some(ContactDescription {
                scale: 0.2,
                exponent: 4.0,
                pairs: Some(vec![(0, 0)]),
            });
        }
        let (field, message) = field_of(self_contact);
        assert_eq!(field, "reference_update", "penalty {penalty}");
        assert!(message.contains("self-contact"), "{message}");
    }
}
