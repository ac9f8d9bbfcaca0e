//! Optional effects: rigid walls and hourglass control conserve what they must and book
//! their energy so that the total closes.

use super::{lattice, model, Setup};
use tlsph_math::{Tensor, Vector};
use tlsph_solver::{Formulation, FrictionCoefficients, Simulation, WallDescription};

#[test]
fn an_elastic_block_bounces_off_a_wall_with_its_momentum_reversed() {
    // A 2D elastic block (c = 1) hits a rigid wall at v = 0.01 c and rebounds. Contact lasts
    // about 2H/c = 1 for a block of height H = 0.5; we run to t = 2.
    let dx = 0.05;
    let positions: Vec<Vector<2>> = lattice([10, 10], dx)
        .iter()
        .map(|x| x + Vector::<2>::new(0.0, 0.001))
        .collect();
    let mut m = model(
        positions,
        dx,
        |_| Vector::<2>::new(0.0, -0.01),
        Setup {
            end_time: 2.0,
            ..Setup::default()
        },
    );
    m.effects.walls.push(WallDescription {
        name: "floor".into(),
        report_moment: false,
        point: Vector::<2>::zeros(),
        normal: Vector::<2>::new(0.0, 1.0),
        friction: FrictionCoefficients::single(0.0),
        motion: None,
        shape: tlsph_solver::WallShape::Plane,
    });
    let mut sim = Simulation::new(m).unwrap();
    let mut impulse = 0.0;
    let mut last_t = 0.0;
    let mut worst_energy: f64 = 0.0;
    let mut e0 = None;
    sim.run(|s, r| {
        let d = s.diagnostics();
        let (_, f) = &d.effect_forces[0];
        impulse += f.y * (r.time - last_t);
        last_t = r.time;
        let e = *e0.get_or_insert(d.total_energy());
        worst_energy = worst_energy.max((d.total_energy() - e).abs() / e);
    })
    .unwrap();
    let d = sim.diagnostics();
    let mass: f64 = sim.masses().iter().sum();
    // Momentum reversed: the block leaves upwards with most of its impact speed (measured
    // 0.85 v; the rest of the energy stays as elastic vibration of the block).
    let p = d.linear_momentum.y / mass;
    assert!(p > 0.8 * 0.01 && p <= 0.01, "rebound velocity {p}");
    // The wall's impulse equals the momentum change (rectangle-rule time integral, 2 %).
    assert!(
        (impulse - (d.linear_momentum.y + 0.01 * mass)).abs() < 0.02 * 0.02 * mass,
        "impulse {impulse}"
    );
    // Total energy including the stored penalty energy closes to 1 % (measured 0.8 %: the
    // penalty oscillator runs at ω Δt = 0.6, where leap-frog's energy error is a few percent
    // of the contact energy).
    assert!(worst_energy < 1e-2, "energy error {worst_energy:e}");
}

#[test]
fn hourglass_control_vanishes_for_affine_motion_and_conserves_momentum() {
    let dx = 0.1;
    let positions = lattice([8, 7], dx);
    // Affine initial velocity: with corrected gradients F is exact, so the hourglass error
    // vectors F X_IJ − x_IJ vanish and so must the hourglass forces.
    let h = Tensor::<2>::new(0.02, -0.01, 0.005, 0.01);
    let setup = || Setup {
        formulation: Formulation::TotalLagrangianCorrected,
        end_time: 0.5,
        ..Setup::default()
    };
    let mut with = model(positions.clone(), dx, |x| h * x, setup());
    with.effects.hourglass_control = Some(1.0);
    let without = model(positions.clone(), dx, |x| h * x, setup());
    let mut a = Simulation::new(with).unwrap();
    let mut b = Simulation::new(without).unwrap();
    // One step from the affine state: forces identical to round-off.
    a.step().unwrap();
    b.step().unwrap();
    let dt = a.next_dt();
    a.step().unwrap();
    b.step().unwrap();
    for i in 0..a.n_particles() {
        let diff = (a.velocity(i) - b.velocity(i)).norm();
        assert!(
            diff < 1e-12 * dt.max(1e-300) + 1e-15,
            "particle {i}: {diff:e}"
        );
    }
    // A rough velocity field excites hourglass forces; momentum stays exact, and the total
    // energy with the booked hourglass work closes to time-integration accuracy: the closure
    // error must shrink when the step does (measured 1.7 % at CFL 0.1, 0.5 % at 0.03; the
    // same field without hourglass control closes to 1.1 % at CFL 0.3).
    let (error_coarse, hourglass) = rough_run(&positions, dx, 0.1);
    let (error_fine, _) = rough_run(&positions, dx, 0.03);
    assert!(hourglass.abs() > 0.0, "hourglass forces were active");
    assert!(
        error_coarse < 0.03,
        "energy closure {error_coarse:e} at CFL 0.1"
    );
    assert!(
        error_fine < 0.5 * error_coarse,
        "closure must converge: {error_fine:e} vs {error_coarse:e}"
    );
}

/// Runs a block with a rough initial velocity field and hourglass control (α = 2) at `cfl`;
/// returns the worst relative energy-closure error and the final booked hourglass energy.
fn rough_run(positions: &[Vector<2>], dx: f64, cfl: f64) -> (f64, f64) {
    let rough = |x: &Vector<2>| {
        Vector::<2>::new(
            0.01 * ((x[0] * 37.0).sin() + (x[1] * 53.0).cos()),
            0.01 * (x[0] * 29.0 + x[1] * 11.0).sin(),
        )
    };
    let mut m = model(
        positions.to_vec(),
        dx,
        rough,
        Setup {
            formulation: Formulation::TotalLagrangianCorrected,
            end_time: 3.0,
            ..Setup::default()
        },
    );
    m.config.cfl = cfl;
    m.effects.hourglass_control = Some(2.0);
    let mut sim = Simulation::new(m).unwrap();
    let mut first = None;
    let mut worst_p: f64 = 0.0;
    let mut worst_e: f64 = 0.0;
    sim.run(|s, _| {
        let d = s.diagnostics();
        let (p0, e0) = *first.get_or_insert((d.linear_momentum, d.total_energy()));
        worst_p = worst_p.max((d.linear_momentum - p0).norm());
        worst_e = worst_e.max((d.total_energy() - e0).abs() / e0);
    })
    .unwrap();
    let scale: f64 = sim.masses().iter().sum::<f64>() * 0.01;
    assert!(worst_p < 1e-12 * scale, "momentum drift {worst_p:e}");
    (worst_e, sim.diagnostics().effect_energies[0].1)
}

#[test]
fn bulk_viscosity_heats_without_losing_energy_and_xsph_leaves_uniform_motion_alone() {
    use tlsph_solver::BulkViscosity;
    // Two halves of a block colliding at ±0.05 c: the viscosity turns kinetic energy into heat
    // (internal energy) in compression; the total still closes and momentum stays exact.
    let dx = 0.05;
    let positions = lattice([20, 6], dx);
    let collide = |x: &Vector<2>| Vector::<2>::new(if x[0] < 0.5 { 0.05 } else { -0.05 }, 0.0);
    let run = |viscosity: Option<BulkViscosity>, cfl: f64| {
        let mut m = model(
            positions.clone(),
            dx,
            collide,
            Setup {
                end_time: 0.4,
                ..Setup::default()
            },
        );
        m.config.cfl = cfl;
        m.effects.bulk_viscosity = viscosity;
        let (kinetic, _, energy, momentum) = conservation(m);
        (kinetic, energy, momentum)
    };
    let viscous = Some(BulkViscosity {
        quadratic: 2.0,
        linear: 0.5,
    });
    let (ke_plain, _, _) = run(None, 0.3);
    let (ke_viscous, e_viscous, p_viscous) = run(viscous, 0.3);
    let (_, e_fine, _) = run(viscous, 0.1);
    assert!(
        ke_viscous < ke_plain,
        "viscosity must take kinetic energy: {ke_viscous} vs {ke_plain}"
    );
    assert!(p_viscous < 1e-15, "momentum {p_viscous:e}");
    // Heat is booked in the internal energy: the total closes to time-integration accuracy
    // (the heating uses q at the end of the step; measured 0.9 % at CFL 0.3) and converges.
    assert!(e_viscous < 0.015, "energy closure {e_viscous:e}");
    assert!(
        e_fine < 0.5 * e_viscous,
        "closure must converge: {e_fine:e} vs {e_viscous:e}"
    );

    // XSPH: a uniform translation has v̂ = v, so particles move exactly with it.
    let mut m = model(
        positions.clone(),
        dx,
        |_| Vector::<2>::new(0.01, -0.02),
        Setup {
            end_time: 0.3,
            ..Setup::default()
        },
    );
    m.effects.xsph = Some(0.5);
    let mut sim = Simulation::new(m).unwrap();
    sim.run(|_, _| {}).unwrap();
    for u in sim.displacements() {
        assert!(
            (u - Vector::<2>::new(0.01, -0.02) * sim.time()).norm() < 1e-14,
            "{u}"
        );
    }
}

#[test]
fn pairwise_artificial_viscosity_dissipates_conserving_momentum() {
    // Two halves of a 1D rod colliding: Monaghan's viscosity (α = 1, β = 2) takes kinetic
    // energy on approach, books it, and leaves linear momentum exact (pairwise forces).
    let dx = 0.02;
    let positions = lattice([50], dx);
    let collide = |x: &Vector<1>| Vector::<1>::new(if x[0] < 0.5 { 0.05 } else { -0.05 });
    let run = |viscosity: Option<(f64, f64)>, cfl: f64| {
        let mut m = model(
            positions.clone(),
            dx,
            collide,
            Setup {
                end_time: 0.4,
                ..Setup::default()
            },
        );
        m.config.cfl = cfl;
        m.effects.pairwise_viscosity = viscosity;
        conservation(m)
    };
    let (ke_plain, _, _, _) = run(None, 0.3);
    let (ke_av, booked, closure, momentum) = run(Some((1.0, 2.0)), 0.3);
    let (_, _, closure_fine, _) = run(Some((1.0, 2.0)), 0.1);
    assert!(
        ke_av < ke_plain,
        "viscosity must take kinetic energy: {ke_av} vs {ke_plain}"
    );
    assert!(
        booked > 0.0,
        "the viscosity's work is booked as dissipated energy: {booked}"
    );
    assert!(momentum < 1e-15, "momentum {momentum:e}");
    assert!(closure < 0.02, "energy closure {closure:e}");
    assert!(
        closure_fine < 0.6 * closure,
        "closure must converge: {closure_fine:e} vs {closure:e}"
    );
}

/// Runs a model to its end time and measures conservation: final kinetic energy, the energy
/// booked by the first declared effect (0 without one), the worst relative total-energy error
/// and the worst linear-momentum drift.
fn conservation<const D: usize>(m: tlsph_solver::Model<D>) -> (f64, f64, f64, f64) {
    let mut sim = Simulation::new(m).unwrap();
    let mut first = None;
    let (mut worst_e, mut worst_p): (f64, f64) = (0.0, 0.0);
    sim.run(|s, _| {
        let d = s.diagnostics();
        let (e0, p0) = *first.get_or_insert((d.total_energy(), d.linear_momentum));
        worst_e = worst_e.max((d.total_energy() - e0).abs() / e0);
        worst_p = worst_p.max((d.linear_momentum - p0).norm());
    })
    .unwrap();
    let d = sim.diagnostics();
    let booked = d.effect_energies.first().map_or(0.0, |e| e.1);
    (d.kinetic, booked, worst_e, worst_p)
}
