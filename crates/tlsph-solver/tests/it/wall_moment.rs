//! The moment vector a wall reports with `report_moment` (numerics.md §13 `[C]`): the moment
//! of its force about its current point closes the angular-momentum balance of the body it
//! holds, a friction force acting in a plane has no moment about a point of that plane, and
//! without the flag nothing is reported.

use tlsph_math::{vector_to_3d, Vector, Vector3};
use tlsph_solver::{Model, Simulation, WallMotion};

/// The block of `wall_friction::block_on_floor` (10 × 5 at dx 0.05 resting on the floor y = 0
/// through the origin, c = 1) under the gravity `g` until t = 6 at CFL 0.15, the floor with
/// friction `friction`, moving along itself at `belt` (a conveyor) and reporting its moment.
fn block_on_floor(g: Vector<2>, friction: f64, belt: f64) -> Model<2> {
    let mut m = super::wall_friction::block_on_floor(g, Vector::zeros(), friction, 6.0);
    // Half the usual CFL number: the balance below is a rectangle rule over the steps.
    m.config.cfl = 0.15;
    let floor = &mut m.effects.walls[0];
    floor.report_moment = true;
    floor.motion = (belt != 0.0).then(|| WallMotion {
        velocity: Vector::<2>::new(belt, 0.0),
        spin: None,
        spin_ramp: None,
        amplitude: None,
    });
    m
}

/// The moment the effect `name` reported in the last step (zero if none).
fn moment(sim: &Simulation<2>, name: &str) -> Vector3 {
    sim.diagnostics()
        .effect_moments
        .iter()
        .find(|(n, _)| n == name)
        .map_or(Vector3::zeros(), |(_, m)| *m)
}

#[test]
fn a_walls_moment_closes_the_angular_momentum_balance_of_the_body_it_holds() {
    // The block rests, loaded at once by its weight, on a frictionless conveyor running at
    // 0.01 (the block does not feel it), so the floor's point, about
    // which it reports, moves: p(t) = (0.01 t, 0). About the origin the floor's force F then
    // has the moment M_p + p × F, gravity the moment m x_c × g, and over the run
    //   ∫ (M_p + p × F + m x_c × g) dt = L(T) − L(0),
    // the angular momentum about the origin. The block's centre is 0.25 from the origin, so
    // the floor's moment about its own point is far from zero (and from the moment about the
    // origin). The rectangle rule over the steps leaves 5.1e-4 of the weight's angular impulse
    // (measured at CFL 0.15). It is first order in the step: on a block twice as tall dropped
    // from 0.01 it left 6.5e-4, 3.2e-4 and 1.6e-4 at CFL 0.3, 0.15 and 0.075. Bound 1e-3.
    let g = Vector::<2>::new(0.0, -0.02);
    let belt = 0.01;
    let mut sim = Simulation::new(block_on_floor(g, 0.0, belt)).unwrap();
    let mass: f64 = sim.masses().iter().sum();
    let centre = |s: &Simulation<2>| {
        (0..s.n_particles())
            .map(|i| (s.initial_position(i) + s.total_displacement(i)) * s.masses()[i])
            .sum::<Vector<2>>()
            / mass
    };
    let l0 = sim.diagnostics().angular_momentum.z;
    let (mut impulse, mut gravity, mut about_point) = (0.0, 0.0, 0.0_f64);
    let g3 = vector_to_3d(&g);
    // Each step's forces are those at its start t^n, where the block's centre was `last`.
    let (mut last_t, mut last) = (0.0, centre(&sim));
    sim.run(|s, r| {
        let dt = r.time - last_t;
        let d = s.diagnostics();
        let force = d.effect_force("wall_floor");
        let point = Vector3::new(belt * last_t, 0.0, 0.0);
        let m_p = moment(s, "wall_floor");
        about_point = about_point.max(m_p.z.abs());
        impulse += (m_p + point.cross(&force)).z * dt;
        gravity += (vector_to_3d(&last) * mass).cross(&g3).z * dt;
        (last_t, last) = (r.time, centre(s));
    })
    .unwrap();
    let change = sim.diagnostics().angular_momentum.z - l0;
    let scale = mass * g.norm() * 0.25 * sim.time();
    eprintln!(
        "∫M dt {impulse:.6e}, gravity {gravity:.6e}, ΔL {change:.6e}, largest |M_p| {about_point:.4e}"
    );
    assert!(
        (impulse + gravity - change).abs() < 1e-3 * scale,
        "angular impulse balance off by {:e} (scale {scale:e})",
        impulse + gravity - change
    );
    assert!(
        about_point > 0.1 * mass * g.norm() * 0.25,
        "{about_point:e}"
    );
}

#[test]
fn friction_in_the_plane_has_no_moment_about_a_point_of_it_and_unrequested_moments_are_not_reported(
) {
    // The block on a floor with μ = 0.5 under a sideways pull (tangential over normal 0.2):
    // friction holds it, acting in the floor's plane at the points where the particles touch,
    // so in 2D its moment about the floor's point (a point of the plane) vanishes to
    // round-off; taken at the particles instead, half a spacing above the plane, it would be
    // about 0.025 times the friction force. The normal force's moment is the weight's, with
    // the tipping moment of the pull.
    let g = Vector::<2>::new(0.004, -0.02);
    let mut sim = Simulation::new(block_on_floor(g, 0.5, 0.0)).unwrap();
    let (mut friction, mut lever) = (0.0_f64, 0.0_f64);
    sim.run(|s, _| {
        let f = s.diagnostics().effect_force("wall_floor_friction");
        friction = friction.max(f.norm());
        lever = lever.max(moment(s, "wall_floor_friction").norm());
    })
    .unwrap();
    eprintln!("largest friction force {friction:.3e}, largest friction moment {lever:.1e}");
    assert!(friction > 0.0);
    assert!(lever <= 1e-12 * friction, "{lever:e} vs {friction:e}");
    // Without the flag no moment is reported.
    let mut quiet = block_on_floor(g, 0.5, 0.0);
    quiet.effects.walls[0].report_moment = false;
    let mut sim = Simulation::new(quiet).unwrap();
    sim.step().unwrap();
    assert!(sim.diagnostics().effect_moments.is_empty());
}
