//! The rigid walls' penalty springs (the unbounded plane, the finite disc, the ball, the
//! cylinder, the finite cylinder, the box, the cone, the pyramid), the surface point and spin
//! velocity their friction reads, and their Coulomb friction (numerics.md §13).

use approx::assert_relative_eq;
use tlsph_contact::{
    spin_velocity, surface_point, wall_friction_acceleration, FiniteCylinder, FlatDisc,
    FrictionCoefficients, RigidBall, RigidBox, RigidCone, RigidCylinder, RigidPlane, RigidPyramid,
    Vector, WallGeometry, WALL_STIFFNESS_FACTOR,
};
use tlsph_math::Vector3;

#[test]
fn a_particle_is_pushed_back_by_its_half_spacing_penetration() {
    // Plane y = 0 (normal given unnormalised), h = 1.2, c0 = 3, Δx = 1.
    let plane = RigidPlane::<2>::new(
        Vector::zeros(),
        Vector::<2>::new(0.0, 2.0),
        &[1.2],
        &[3.0],
        &[1.0],
    );
    assert_eq!(plane.normal(), Vector::<2>::new(0.0, 1.0));
    let k = WALL_STIFFNESS_FACTOR * 9.0 / 1.44;
    assert_relative_eq!(plane.stiffness_per_mass(0), k, max_relative = 1e-15);
    // Centre 0.3 above the plane: δ = 0.5 − 0.3.
    assert_relative_eq!(
        plane.penetration(0, Vector::<2>::new(7.0, 0.3)),
        0.2,
        max_relative = 1e-14
    );
    assert_relative_eq!(
        plane.normal_acceleration(0, Vector::<2>::new(7.0, 0.3)),
        0.2 * k,
        max_relative = 1e-14
    );
    assert_eq!(plane.penetration(0, Vector::<2>::new(0.0, 0.5)), 0.0);
    assert_eq!(plane.penetration(0, Vector::<2>::new(0.0, 4.0)), 0.0);
}

#[test]
fn wall_friction_is_coulomb_until_it_would_stop_the_particle() {
    let n = Vector::<3>::new(0.0, 0.0, 1.0);
    // Sliding fast: μ a_n against the tangential velocity, the normal part ignored.
    let a = wall_friction_acceleration(
        10.0,
        Vector::<3>::new(3.0, 4.0, -2.0),
        n,
        FrictionCoefficients::single(0.5),
        1e-3,
    );
    assert_relative_eq!(a, Vector::<3>::new(-3.0, -4.0, 0.0), max_relative = 1e-14);
    // Sliding slowly: only what stops the motion within the kick (|v_t| / Δt = 1 < μ a_n).
    let slow = wall_friction_acceleration(
        10.0,
        Vector::<3>::new(6e-4, 8e-4, 0.0),
        n,
        FrictionCoefficients::single(0.5),
        1e-3,
    );
    assert_relative_eq!(
        slow,
        Vector::<3>::new(-0.6, -0.8, 0.0),
        max_relative = 1e-12
    );
    // Not touching, or not sliding: nothing.
    assert_eq!(
        wall_friction_acceleration(
            0.0,
            Vector::<3>::new(1.0, 0.0, 0.0),
            n,
            FrictionCoefficients::single(0.5),
            1e-3
        ),
        Vector::<3>::zeros()
    );
    assert_eq!(
        wall_friction_acceleration(
            10.0,
            Vector::<3>::new(0.0, 0.0, -1.0),
            n,
            FrictionCoefficients::single(0.5),
            1e-3
        ),
        Vector::<3>::zeros()
    );
}

#[test]
fn a_static_coefficient_holds_more_than_the_kinetic_one_slides_with() {
    // μ_k = 0.3, μ_s = 0.6, a_n = 10, kick 1e-3: a particle is held while stopping it within
    // the kick takes at most μ_s a_n = 6; beyond, it slides against μ_k a_n = 3, never the
    // force that would have stopped it.
    let n = Vector::<2>::new(0.0, 1.0);
    let friction = FrictionCoefficients {
        kinetic: 0.3,
        static_coefficient: 0.6,
        decay: None,
    };
    let at = |speed: f64| {
        wall_friction_acceleration(10.0, Vector::<2>::new(speed, 0.0), n, friction, 1e-3)
    };
    // |v_t|/Δt = 5 ≤ 6: stopped exactly (with one coefficient 0.3 it would slide at −3).
    assert_relative_eq!(at(5e-3).x, -5.0, max_relative = 1e-12);
    assert_relative_eq!(
        wall_friction_acceleration(
            10.0,
            Vector::<2>::new(5e-3, 0.0),
            n,
            FrictionCoefficients::single(0.3),
            1e-3
        )
        .x,
        -3.0,
        max_relative = 1e-12
    );
    // At the limit it still holds; above it the kinetic force, below the stopping one.
    assert_relative_eq!(at(6e-3).x, -6.0, max_relative = 1e-12);
    assert_relative_eq!(at(7e-3).x, -3.0, max_relative = 1e-12);
    assert_relative_eq!(at(-7e-3).x, 3.0, max_relative = 1e-12);
}

#[test]
fn with_a_decay_the_sliding_coefficient_falls_from_the_static_to_the_kinetic_one() {
    // μ_k = 0.3, μ_s = 0.6, d_c = 100 s/m: a sliding contact feels
    // μ(v) = 0.3 + 0.3 exp(−100 v); a sticking one still takes exactly the stopping force.
    let friction = FrictionCoefficients {
        kinetic: 0.3,
        static_coefficient: 0.6,
        decay: Some(100.0),
    };
    assert_eq!(friction.coefficient(0.4, 0.01), 0.4);
    for speed in [1e-4, 0.01, 0.05] {
        assert_relative_eq!(
            friction.coefficient(2.0, speed),
            0.3 + 0.3 * (-100.0 * speed).exp(),
            max_relative = 1e-14
        );
    }
    // Slow sliding feels almost μ_s, fast sliding μ_k; without a decay, μ_k at once.
    assert!(friction.coefficient(2.0, 1e-6) > 0.5999);
    assert_relative_eq!(friction.coefficient(2.0, 1.0), 0.3, max_relative = 1e-15);
    let abrupt = FrictionCoefficients {
        decay: None,
        ..friction
    };
    assert_eq!(abrupt.coefficient(2.0, 1e-6), 0.3);
    // Through the wall law: a_n = 10, kick 1e-3, sliding at 0.01 needs 10/(1e-3·10) = 1 > μ_s,
    // so the particle slides against μ(0.01) a_n.
    let a = wall_friction_acceleration(
        10.0,
        Vector::<2>::new(0.01, 0.0),
        Vector::<2>::new(0.0, 1.0),
        friction,
        1e-3,
    );
    assert_relative_eq!(
        a.x,
        -10.0 * (0.3 + 0.3 * (-1.0f64).exp()),
        max_relative = 1e-14
    );
}

/// A disc of radius 2 about the origin in the plane z = 0 (normal given unnormalised), for one
/// particle with h = 1.2, c0 = 3, Δx = 1 (contact radius ½).
fn disc() -> FlatDisc<3> {
    FlatDisc::<3>::new(
        Vector::zeros(),
        Vector::<3>::new(0.0, 0.0, 5.0),
        2.0,
        &[1.2],
        &[3.0],
        &[1.0],
    )
}

#[test]
fn a_finite_wall_pushes_off_its_faces_and_around_its_rim() {
    let disc = disc();
    let z = Vector::<3>::z();
    // In front of the face: the plane's law.
    let (delta, n) = disc.contact(0, Vector::<3>::new(1.0, -1.0, 0.3));
    assert_relative_eq!(delta, 0.2, max_relative = 1e-14);
    assert_eq!(n, z);
    // Behind the face: pushed back, away from the plate (it has two faces).
    let (delta, n) = disc.contact(0, Vector::<3>::new(0.5, 0.5, -0.4));
    assert_relative_eq!(delta, 0.1, max_relative = 1e-13);
    assert_eq!(n, -z);
    // Past the rim: away from the nearest rim point (2, 0, 0), here at 45° around the edge.
    let (delta, n) = disc.contact(0, Vector::<3>::new(2.3, 0.0, 0.3));
    assert_relative_eq!(delta, 0.5 - 0.3 * 2f64.sqrt(), max_relative = 1e-13);
    assert_relative_eq!(
        n,
        Vector::<3>::new(1.0, 0.0, 1.0).normalize(),
        max_relative = 1e-14
    );
    // Level with the plate, beside it: pushed sideways; further out: untouched.
    let (delta, n) = disc.contact(0, Vector::<3>::new(0.0, -2.4, 0.0));
    assert_relative_eq!(delta, 0.1, max_relative = 1e-13);
    assert_relative_eq!(n, Vector::<3>::new(0.0, -1.0, 0.0), max_relative = 1e-14);
    assert_eq!(disc.contact(0, Vector::<3>::new(2.4, 0.0, 0.4)).0, 0.0);
    assert_eq!(disc.contact(0, Vector::<3>::new(0.0, 0.0, 0.6)).0, 0.0);
    // The same stiffness as the plane's.
    assert_relative_eq!(
        disc.stiffness_per_mass(0),
        WALL_STIFFNESS_FACTOR * 9.0 / 1.44,
        max_relative = 1e-15
    );
}

/// The push k δ n̂ of `wall` must be −∇(½ k δ²) at every point of `points` (all touching),
/// or a particle moving along the wall would gain or lose energy: central differences.
fn assert_push_is_energy_gradient(wall: &impl WallGeometry<3>, points: &[Vector<3>]) {
    let energy = |x: Vector<3>| 0.5 * wall.contact(0, x).0.powi(2);
    let eps = 1e-6;
    for &at in points {
        let (x, y, z) = (at.x, at.y, at.z);
        let (delta, n) = wall.contact(0, at);
        assert!(delta > 0.0, "({x}, {y}, {z}) must touch");
        let push = n * delta;
        for axis in 0..3 {
            let mut step = Vector::<3>::zeros();
            step[axis] = eps;
            let slope = (energy(at + step) - energy(at - step)) / (2.0 * eps);
            assert!(
                (push[axis] + slope).abs() < 1e-8,
                "({x}, {y}, {z}), axis {axis}: push {} vs −∂E {}",
                push[axis],
                -slope
            );
        }
    }
}

#[test]
fn a_finite_wall_pushes_down_the_gradient_of_its_spring_energy() {
    // In front of the face, over the rounded rim and beside it.
    assert_push_is_energy_gradient(
        &disc(),
        &[
            (0.3, 0.2, 0.35),
            (1.99, 0.0, 0.2),
            (2.1, 0.1, 0.2),
            (1.5, 1.5, 0.1),
            (2.2, -0.3, -0.15),
            (0.0, 2.3, 0.0),
            (-1.6, -1.3, 0.4),
        ]
        .map(|(x, y, z)| Vector::<3>::new(x, y, z)),
    );
}

#[test]
fn a_ball_pushes_radially_by_the_penetration_of_its_surface() {
    // Ball of radius 2 about (1, 0, 0), particle contact radius ½: δ = 2.5 − |x − c|.
    let ball = RigidBall::<3>::new(Vector::<3>::new(1.0, 0.0, 0.0), 2.0, &[1.2], &[3.0], &[1.0]);
    let (delta, n) = ball.contact(0, Vector::<3>::new(1.0, 0.0, 2.3));
    assert_relative_eq!(delta, 0.2, max_relative = 1e-13);
    assert_eq!(n, Vector::<3>::z());
    let (delta, n) = ball.contact(0, Vector::<3>::new(2.2, 1.6, 0.0));
    assert_relative_eq!(delta, 0.5, max_relative = 1e-13);
    assert_relative_eq!(n, Vector::<3>::new(0.6, 0.8, 0.0), max_relative = 1e-14);
    assert_eq!(ball.contact(0, Vector::<3>::new(1.0, -2.6, 0.0)).0, 0.0);
    assert_relative_eq!(
        ball.stiffness_per_mass(0),
        WALL_STIFFNESS_FACTOR * 9.0 / 1.44,
        max_relative = 1e-15
    );
    assert_push_is_energy_gradient(
        &ball,
        &[
            (1.0, 0.0, 2.3),
            (2.2, 1.6, 0.1),
            (-0.4, -1.2, 1.1),
            (1.0, 2.45, 0.0),
        ]
        .map(|(x, y, z)| Vector::<3>::new(x, y, z)),
    );
}

#[test]
fn a_cylinder_pushes_away_from_its_axis_by_the_penetration_of_its_surface() {
    // Cylinder of radius 2 about the line through (1, 0, 0) along (0, 1, 1)/√2, particle
    // contact radius ½: δ = 2.5 − r, r the distance to the axis, whatever the position along it.
    let cylinder = RigidCylinder::<3>::new(
        Vector::<3>::new(1.0, 0.0, 0.0),
        Vector::<3>::new(0.0, 3.0, 3.0),
        2.0,
        &[1.2],
        &[3.0],
        &[1.0],
    );
    let across = Vector::<3>::new(0.0, 1.0, -1.0).normalize();
    for along in [-7.0, 0.0, 0.4, 12.5] {
        let on_axis = Vector::<3>::new(1.0, along, along);
        let (delta, n) = cylinder.contact(0, on_axis + across * 2.3);
        assert_relative_eq!(delta, 0.2, max_relative = 1e-13);
        assert_relative_eq!(n, across, epsilon = 1e-13);
        let (delta, n) = cylinder.contact(0, on_axis + Vector::<3>::new(-1.8, 0.0, 0.0));
        assert_relative_eq!(delta, 0.7, max_relative = 1e-13);
        assert_relative_eq!(n, -Vector::<3>::x(), epsilon = 1e-13);
        assert_eq!(cylinder.contact(0, on_axis + across * 2.6).0, 0.0);
    }
    // At the axis' point itself: the whole penetration, across the axis.
    let (delta, n) = cylinder.contact(0, Vector::<3>::new(1.0, 0.0, 0.0));
    assert_eq!(delta, 2.5);
    assert!(n.dot(&Vector::<3>::new(0.0, 1.0, 1.0)).abs() < 1e-15);
    assert!((n.norm() - 1.0).abs() < 1e-15);
    assert_relative_eq!(
        cylinder.stiffness_per_mass(0),
        WALL_STIFFNESS_FACTOR * 9.0 / 1.44,
        max_relative = 1e-15
    );
    assert_push_is_energy_gradient(
        &cylinder,
        &[
            (1.0, 0.3, 2.3),
            (2.2, 1.6, 0.1),
            (-0.4, -1.2, 1.1),
            (3.2, 5.0, 5.3),
        ]
        .map(|(x, y, z)| Vector::<3>::new(x, y, z)),
    );
}

/// The contact of particle 0 at `x` with `wall` must be (δ, n̂) = `expected`, and the
/// surface point a wall's friction reads must lie on the surface, where the wall's signed
/// `distance` is 0.
fn assert_contact(
    wall: &impl WallGeometry<3>,
    distance: impl Fn(Vector<3>) -> f64,
    x: Vector<3>,
    expected: (f64, Vector<3>),
) {
    let (d, direction) = wall.contact(0, x);
    assert_relative_eq!(d, expected.0, epsilon = 1e-13);
    assert_relative_eq!(direction, expected.1, epsilon = 1e-13);
    let y = surface_point(wall, 0, x, (d, direction));
    assert_relative_eq!(distance(y), 0.0, epsilon = 1e-13);
}

#[test]
fn a_finite_cylinder_pushes_out_of_its_mantle_its_end_faces_and_round_its_rims() {
    // Cylinder of radius 2 and length 4 centred at (1, 0, 0) along (0, 1, 1)/√2, particle
    // contact radius ½: δ = ½ − s with s the distance to the solid, along its outward normal.
    let cylinder = FiniteCylinder::<3>::new(
        Vector::<3>::new(1.0, 0.0, 0.0),
        Vector::<3>::new(0.0, 3.0, 3.0),
        2.0,
        4.0,
        &[1.2],
        &[3.0],
        &[1.0],
    );
    let axis = Vector::<3>::new(0.0, 1.0, 1.0).normalize();
    let across = Vector::<3>::new(0.0, 1.0, -1.0).normalize();
    let at = |along: f64, r: f64| Vector::<3>::new(1.0, 0.0, 0.0) + axis * along + across * r;
    let check = |x: Vector<3>, delta: f64, n: Vector<3>| {
        assert_contact(&cylinder, |y| cylinder.distance(y).0, x, (delta, n))
    };
    // Beside the mantle, anywhere along the length: the unbounded cylinder's law.
    for along in [-1.9, 0.0, 1.5] {
        check(at(along, 2.3), 0.2, across);
        check(at(along, -2.1), 0.4, -across);
    }
    // In front of either end face, anywhere within the radius: the plane's law.
    for r in [0.0, 1.0, -1.9] {
        check(at(2.3, r), 0.2, axis);
        check(at(-2.4, r), 0.1, -axis);
    }
    // Past a rim: away from the nearest rim point, at the distance to it.
    let s = 0.2_f64.hypot(0.2);
    check(at(2.2, 2.2), 0.5 - s, (axis + across).normalize());
    check(
        at(-2.1, -2.3),
        0.5 - 0.1_f64.hypot(0.3),
        (-axis * 0.1 - across * 0.3) / 0.1_f64.hypot(0.3),
    );
    assert_eq!(cylinder.contact(0, at(2.3, 2.5)).0, 0.0);
    assert_eq!(cylinder.contact(0, at(0.0, 2.6)).0, 0.0);
    assert_eq!(cylinder.contact(0, at(2.6, 0.0)).0, 0.0);
    // Pushed inside: out through the nearer face, by the contact radius plus the depth.
    check(at(1.5, 0.5), 1.0, axis);
    check(at(0.2, -1.7), 0.8, -across);
    // In each region, and off the plane of the cases above (across along x).
    let points = [
        at(1.0, 2.3),
        at(2.3, 1.0),
        at(2.2, 2.2),
        at(-2.1, -2.3),
        at(1.5, 0.5),
        at(0.2, -1.7),
        at(2.15, 0.0) + Vector::<3>::new(2.1, 0.0, 0.0),
    ];
    assert_push_is_energy_gradient(&cylinder, &points);
}

#[test]
fn a_box_pushes_off_its_faces_round_its_edges_and_corners_and_out_of_its_inside() {
    // Box of edges 4 × 2 × 6 centred at (1, 0, 0), its normal along (0, 1, 1)/√2 and its axis
    // along x, particle contact radius ½: δ = ½ − s with s the distance to the solid.
    let normal = Vector::<3>::new(0.0, 1.0, 1.0);
    let frame = RigidBox::<3>::frame(normal * 2.0, Vector::<3>::new(3.0, 0.0, 0.0)).unwrap();
    let e0 = Vector::<3>::x();
    let e2 = normal.normalize();
    let e1 = e2.cross(&e0);
    assert_relative_eq!(frame.column(0).into_owned(), e0, epsilon = 1e-15);
    assert_relative_eq!(frame.column(1).into_owned(), e1, epsilon = 1e-15);
    assert_relative_eq!(frame.column(2).into_owned(), e2, epsilon = 1e-15);
    let centre = Vector::<3>::new(1.0, 0.0, 0.0);
    let size = Vector::<3>::new(4.0, 2.0, 6.0);
    let block = RigidBox::<3>::new(centre, frame, size, &[1.2], &[3.0], &[1.0]);
    let at = |a: f64, b: f64, c: f64| centre + e0 * a + e1 * b + e2 * c;
    let check = |x: Vector<3>, delta: f64, n: Vector<3>| {
        assert_contact(&block, |y| block.distance(y).0, x, (delta, n))
    };
    // In front of each face, anywhere over it: the plane's law.
    check(at(0.3, -0.9, 3.2), 0.3, e2);
    check(at(-1.9, 0.5, -3.4), 0.1, -e2);
    check(at(2.1, 0.0, 2.9), 0.4, e0);
    check(at(0.0, -1.45, -1.0), 0.05, -e1);
    // Past an edge (two faces): away from the nearest edge point; past a corner: from it.
    check(
        at(2.2, 0.3, 3.1),
        0.5 - 0.2_f64.hypot(0.1),
        (e0 * 0.2 + e2 * 0.1) / 0.2_f64.hypot(0.1),
    );
    let corner = Vector::<3>::new(-0.1, -0.2, 0.2);
    check(
        at(-2.1, -1.2, 3.2),
        0.5 - corner.norm(),
        (e0 * corner.x + e1 * corner.y + e2 * corner.z) / corner.norm(),
    );
    assert_eq!(block.contact(0, at(0.0, 0.0, 3.6)).0, 0.0);
    assert_eq!(block.contact(0, at(2.4, 1.4, 0.0)).0, 0.0);
    // Pushed inside: out through the nearest face, by the contact radius plus the depth.
    check(at(0.5, 0.2, 2.6), 0.9, e2);
    check(at(-1.8, 0.1, 0.0), 0.7, -e0);
    check(at(0.0, -0.7, -1.0), 0.8, -e1);
    // In each region, including off the planes of symmetry of the box.
    let points = [
        at(0.3, -0.9, 3.2),
        at(2.1, 0.4, 2.9),
        at(2.2, 0.3, 3.1),
        at(-2.1, -1.2, 3.2),
        at(0.5, 0.2, 2.6),
        at(-1.8, 0.1, 0.3),
    ];
    assert_push_is_energy_gradient(&block, &points);
}

#[test]
fn a_cone_pushes_off_its_flanks_round_its_tip_and_out_of_its_inside() {
    // Cone of half-angle 60° with its tip at (1, 0, 0), opening along (0, 1, 1)/√2, particle
    // contact radius ½: δ = ½ − s with s the distance to the solid, along its outward normal.
    let (sin, cos) = 60f64.to_radians().sin_cos();
    let tip = Vector::<3>::new(1.0, 0.0, 0.0);
    let e2 = Vector::<3>::new(0.0, 1.0, 1.0).normalize();
    let (e0, e1) = (Vector::<3>::x(), e2.cross(&Vector::<3>::x()));
    let at = |a: f64, b: f64, c: f64| tip + e0 * a + e1 * b + e2 * c;
    let cone = |radius: f64| {
        RigidCone::<3>::new(
            tip,
            e2 * 3.0,
            60f64.to_radians(),
            radius,
            &[1.2],
            &[3.0],
            &[1.0],
        )
    };
    let sharp = cone(0.0);
    let check = |cone: &RigidCone<3>, x: Vector<3>, delta: f64, n: Vector<3>| {
        assert_contact(cone, |y| cone.distance(y).0, x, (delta, n))
    };
    // Beside a flank (any azimuth): 0.3 out along its normal from a point of the flank.
    for azimuth in [e0, (e0 - e1 * 2.0).normalize()] {
        let normal = azimuth * cos - e2 * sin;
        let on_flank = tip + azimuth * (2.0 * sin / cos) + e2 * 2.0;
        check(&sharp, on_flank + normal * 0.3, 0.2, normal);
    }
    // Below the tip, and round it where the point is past the flank's end: from the tip.
    check(&sharp, at(0.0, 0.0, -0.3), 0.2, -e2);
    let past_tip = Vector::<3>::new(0.1, 0.0, -0.3);
    check(
        &sharp,
        at(0.1, 0.0, -0.3),
        0.5 - past_tip.norm(),
        (e0 * 0.1 - e2 * 0.3) / past_tip.norm(),
    );
    // Pushed inside: out through the nearer flank, by the contact radius plus the depth.
    check(
        &sharp,
        at(0.5, 0.0, 3.0),
        0.5 - (0.5 * cos - 3.0 * sin),
        e0 * cos - e2 * sin,
    );
    assert_eq!(sharp.contact(0, at(5.0, 0.0, 1.0)).0, 0.0);
    assert_eq!(sharp.contact(0, at(0.0, 0.0, -0.6)).0, 0.0);
    // Its tip rounded to ρ = 0.4: the tip point is where it was, round the tip the push is
    // from the sphere's centre, and far up a flank the surface stands ρ (1 − sin α) further
    // out than the sharp cone's (its flanks are the sharp cone's from tip + ρ â, moved out by
    // ρ).
    let rounded = cone(0.4);
    check(&rounded, at(0.0, 0.0, -0.3), 0.2, -e2);
    let from_centre = Vector::<3>::new(0.2, 0.0, -0.5);
    check(
        &rounded,
        at(0.2, 0.0, -0.1),
        0.5 - (from_centre.norm() - 0.4),
        (e0 * 0.2 - e2 * 0.5) / from_centre.norm(),
    );
    let far_up = at(6.0, 0.0, 3.0);
    assert_relative_eq!(
        rounded.contact(0, far_up).0 - sharp.contact(0, far_up).0,
        0.4 * (1.0 - sin),
        epsilon = 1e-13
    );
    // In each region and on either side of where the flank meets the tip's region (where the
    // height from the apex is −r tan α: just above and just below it at r = 0.15).
    let points = [
        at(1.8, 0.4, 0.8),
        at(-0.3, 0.2, -0.2),
        at(0.2, -0.3, 1.5),
        at(0.15, 0.0, -0.25),
        at(0.15, 0.0, -0.27),
    ];
    assert_push_is_energy_gradient(&sharp, &points);
    // (The flank meets the rounded tip's region where the height from tip + ρ â is −r tan α.)
    let mut points = points.map(|x| x + e2 * 0.2);
    points[3..].copy_from_slice(&[at(0.15, 0.0, 0.15), at(0.15, 0.0, 0.13)]);
    assert_push_is_energy_gradient(&rounded, &points);
}

#[test]
fn a_cone_in_2d_is_a_wedge() {
    // Wedge of half-angle 45° with its edge at the origin, opening along y: each flank pushes
    // along its own outward normal, below the edge the push is from the edge.
    let wedge = RigidCone::<2>::new(
        Vector::<2>::zeros(),
        Vector::<2>::y(),
        45f64.to_radians(),
        0.0,
        &[1.2],
        &[3.0],
        &[1.0],
    );
    let half = std::f64::consts::FRAC_1_SQRT_2;
    for side in [1.0, -1.0] {
        let (delta, n) = wedge.contact(0, Vector::<2>::new(side, 0.5));
        assert_relative_eq!(delta, 0.5 - 0.5 * half, epsilon = 1e-15);
        assert_relative_eq!(n, Vector::<2>::new(side * half, -half), epsilon = 1e-15);
    }
    let (delta, n) = wedge.contact(0, Vector::<2>::new(0.0, -0.2));
    assert_relative_eq!(delta, 0.3, epsilon = 1e-15);
    assert_eq!(n, -Vector::<2>::y());
}

#[test]
fn a_box_with_rounded_edges_is_the_sharp_box_over_its_faces_and_a_cylinder_round_its_edges() {
    // The box of edges 4 × 2 × 6 about the origin on the coordinate axes, its edges rounded
    // to ρ = 0.4, particle contact radius ½.
    let identity = tlsph_math::Tensor::<3>::identity();
    let size = Vector::<3>::new(4.0, 2.0, 6.0);
    let sharp = RigidBox::<3>::new(Vector::<3>::zeros(), identity, size, &[1.2], &[3.0], &[1.0]);
    let rounded = sharp.clone().with_edge_radius(0.4);
    let check = |x: Vector<3>, delta: f64, n: Vector<3>| {
        assert_contact(&rounded, |y| rounded.distance(y).0, x, (delta, n))
    };
    // Over a face, away from its rounded rim (more than ρ in from the edges): the sharp box
    // (to round-off: the depth is measured from the inner box, less ρ).
    for x in [
        Vector::<3>::new(0.3, 0.2, 3.2),
        Vector::<3>::new(1.5, -0.5, -3.4),
        Vector::<3>::new(2.1, 0.5, 2.5),
    ] {
        let ((d, n), (d_sharp, n_sharp)) = (rounded.contact(0, x), sharp.contact(0, x));
        assert_relative_eq!(d, d_sharp, epsilon = 1e-14);
        assert_eq!(n, n_sharp);
    }
    // Round an edge (x = 2, z = 3): a cylinder of radius ρ about the line x = 1.6, z = 2.6.
    let off = Vector::<3>::new(0.5, 0.0, 0.3);
    check(
        Vector::<3>::new(1.6, 0.2, 2.6) + off,
        0.9 - off.norm(),
        off / off.norm(),
    );
    // Round a corner: a ball of radius ρ about (1.6, 0.6, 2.6); the sharp box's corner
    // (2, 1, 3) itself is 0.4 (√3 − 1) clear of the rounded surface.
    let off = Vector::<3>::new(0.3, 0.2, 0.4);
    check(
        Vector::<3>::new(1.6, 0.6, 2.6) + off,
        0.9 - off.norm(),
        off / off.norm(),
    );
    let corner = Vector::<3>::new(2.0, 1.0, 3.0);
    assert_relative_eq!(
        rounded.distance(corner).0,
        0.4 * (3f64.sqrt() - 1.0),
        epsilon = 1e-14
    );
    assert_eq!(sharp.distance(corner).0, 0.0);
    // Inside: out through the nearest face, at the same depth as the sharp box.
    check(Vector::<3>::new(0.5, 0.2, 2.6), 0.9, Vector::<3>::z());
    assert_push_is_energy_gradient(
        &rounded,
        &[
            (2.0, 0.3, 3.1),
            (2.15, 0.9, 2.9),
            (1.8, -1.1, -3.05),
            (0.5, 0.2, 2.6),
        ]
        .map(|(x, y, z)| Vector::<3>::new(x, y, z)),
    );
}

#[test]
fn a_box_frame_is_right_handed_about_its_normal_and_refuses_a_slanted_axis() {
    // 2D: the normal y gives the coordinate axes, and e_0 is the normal turned clockwise.
    let frame = RigidBox::<2>::frame(Vector::<2>::new(0.0, 2.0), Vector::<2>::zeros()).unwrap();
    assert_eq!(frame, tlsph_math::Tensor::<2>::identity());
    let frame = RigidBox::<2>::frame(Vector::<2>::new(1.0, 1.0), Vector::<2>::zeros()).unwrap();
    let r = 0.5_f64.sqrt();
    assert_relative_eq!(
        frame.column(0).into_owned(),
        Vector::<2>::new(r, -r),
        epsilon = 1e-15
    );
    assert_relative_eq!(frame.determinant(), 1.0, epsilon = 1e-15);
    // A 2D rectangle of 2 × 1 on its frame: pushes off its long face like the plane.
    let rectangle = RigidBox::<2>::new(
        Vector::<2>::zeros(),
        tlsph_math::Tensor::<2>::identity(),
        Vector::<2>::new(2.0, 1.0),
        &[1.2],
        &[3.0],
        &[1.0],
    );
    let (delta, n) = rectangle.contact(0, Vector::<2>::new(0.9, 0.7));
    assert_relative_eq!(delta, 0.3, epsilon = 1e-15);
    assert_eq!(n, Vector::<2>::y());
    // 3D: normal z and axis x give the coordinate axes.
    let frame = RigidBox::<3>::frame(Vector::<3>::z(), Vector::<3>::x()).unwrap();
    assert_eq!(frame, tlsph_math::Tensor::<3>::identity());
    let slanted = RigidBox::<3>::frame(Vector::<3>::z(), Vector::<3>::new(1.0, 0.0, 0.1));
    assert!(slanted.unwrap_err().contains("right angles"));
    let zero = RigidBox::<3>::frame(Vector::<3>::zeros(), Vector::<3>::x());
    assert!(zero.unwrap_err().contains("normal"));
    assert!(RigidBox::<1>::frame(Vector::<1>::x(), Vector::<1>::x()).is_err());
}

#[test]
fn inside_its_footprint_a_finite_wall_is_the_plane() {
    // In 2D (a segment of half-length 3 on y = 1), a particle in front of the segment feels
    // exactly what it feels from the unbounded plane.
    let plane = RigidPlane::<2>::new(
        Vector::<2>::new(0.0, 1.0),
        Vector::<2>::new(0.0, 1.0),
        &[1.2],
        &[3.0],
        &[1.0],
    );
    let segment = FlatDisc::<2>::new(
        Vector::<2>::new(0.0, 1.0),
        Vector::<2>::new(0.0, 1.0),
        3.0,
        &[1.2],
        &[3.0],
        &[1.0],
    );
    for x in [-3.0, -1.2, 0.0, 2.9, 3.0] {
        for y in [1.0, 1.1, 1.37, 1.5, 2.0] {
            let at = Vector::<2>::new(x, y);
            assert_eq!(segment.contact(0, at), plane.contact(0, at), "({x}, {y})");
        }
    }
}

#[test]
fn the_surface_point_is_where_the_particle_meets_the_wall() {
    // Contact radius ½ for every shape. Plane z = 0: the foot of the normal, for a particle
    // just touching or pushed in (friction asks only for touching particles).
    let plane = RigidPlane::<3>::new(
        Vector::zeros(),
        Vector::<3>::new(0.0, 0.0, 2.0),
        &[1.2],
        &[3.0],
        &[1.0],
    );
    for z in [-0.2, 0.3, 0.5] {
        let x = Vector::<3>::new(1.5, -2.0, z);
        let y = surface_point(&plane, 0, x, plane.contact(0, x));
        assert_relative_eq!(y, Vector::<3>::new(1.5, -2.0, 0.0), epsilon = 1e-15);
    }
    // Disc of radius 2 in z = 0: past the rim, the nearest rim point.
    let disc = disc();
    let x = Vector::<3>::new(2.3, 0.0, 0.4);
    let y = surface_point(&disc, 0, x, disc.contact(0, x));
    assert_relative_eq!(y, Vector::<3>::new(2.0, 0.0, 0.0), epsilon = 1e-15);
    // Ball of radius 2 about (1, 0, 0), cylinder of radius 2 about the x axis: on the surface,
    // radially below the particle.
    let ball = RigidBall::<3>::new(Vector::<3>::new(1.0, 0.0, 0.0), 2.0, &[1.2], &[3.0], &[1.0]);
    let x = Vector::<3>::new(2.2, 1.6, 0.0);
    let y = surface_point(&ball, 0, x, ball.contact(0, x));
    assert_relative_eq!(y, Vector::<3>::new(2.2, 1.6, 0.0), epsilon = 1e-15);
    let x = Vector::<3>::new(1.0, 0.0, 2.3);
    let y = surface_point(&ball, 0, x, ball.contact(0, x));
    assert_relative_eq!(y, Vector::<3>::new(1.0, 0.0, 2.0), epsilon = 1e-15);
    let cylinder = RigidCylinder::<3>::new(
        Vector::zeros(),
        Vector::<3>::x(),
        2.0,
        &[1.2],
        &[3.0],
        &[1.0],
    );
    let x = Vector::<3>::new(7.0, 1.8, 1.35);
    let y = surface_point(&cylinder, 0, x, cylinder.contact(0, x));
    assert_relative_eq!(y, Vector::<3>::new(7.0, 1.6, 1.2), epsilon = 1e-14);
}

#[test]
fn a_spinning_surface_moves_at_omega_cross_its_offset_from_the_axis() {
    // ω = 3 about z: at r = (2, 0, 0) the surface moves at (0, 6, 0); the offset along the
    // axis does not count; in 2D the same spin turns the plane's point (0, −2) to (6, 0).
    let omega = Vector3::new(0.0, 0.0, 3.0);
    assert_eq!(
        spin_velocity(&omega, &Vector::<3>::new(2.0, 0.0, 5.0)),
        Vector::<3>::new(0.0, 6.0, 0.0)
    );
    assert_eq!(
        spin_velocity(&omega, &Vector::<2>::new(0.0, -2.0)),
        Vector::<2>::new(6.0, 0.0)
    );
    // About an oblique axis: perpendicular to the axis and to the offset, of size |ω| r.
    let omega = Vector3::new(1.0, 2.0, 2.0);
    let offset = Vector::<3>::new(0.5, -1.0, 4.0);
    let v = spin_velocity(&omega, &offset);
    assert!(v.dot(&omega).abs() < 1e-14 && v.dot(&offset).abs() < 1e-14);
    let r = (offset - omega * (offset.dot(&omega) / 9.0)).norm();
    assert_relative_eq!(v.norm(), 3.0 * r, max_relative = 1e-14);
}

/// A Vickers pyramid (4 faces at α = 68° to the axis) and a Berkovich (3 faces at 65.27°),
/// each with its tip at (1, 0, 0), opening along (0, 1, 1)/√2, its first face towards x,
/// sharp or with its tip rounded to `tip_radius`; particle contact radius ½.
fn pyramids(tip_radius: f64) -> [(RigidPyramid<3>, usize, f64); 2] {
    [(4, 68.0), (3, 65.27)].map(|(sides, degrees): (usize, f64)| {
        let pyramid = RigidPyramid::<3>::new(
            Vector::<3>::new(1.0, 0.0, 0.0),
            Vector::<3>::new(0.0, 2.0, 2.0),
            Vector::<3>::x() * 3.0,
            sides,
            degrees.to_radians(),
            tip_radius,
            (&[1.2], &[3.0], &[1.0]),
        )
        .unwrap();
        (pyramid, sides, degrees.to_radians())
    })
}

/// The faces' outward normals and the edges' directions of the sharp pyramid of `sides`
/// faces at `alpha` to the axis â, its first face towards ê₁ (frame ê₁, ê₂ = â × ê₁, â), built
/// from its corners: at unit height the cross-section is the regular polygon of inradius
/// tan α with a side's middle towards ê₁, so corner k lies at the circumradius
/// tan α / cos(π/N), half a side's angle past face k; face k is spanned by corners k − 1 and k.
fn pyramid_from_corners(
    sides: usize,
    alpha: f64,
    (e1, e2, axis): (Vector<3>, Vector<3>, Vector<3>),
) -> (Vec<Vector<3>>, Vec<Vector<3>>) {
    let step = std::f64::consts::TAU / sides as f64;
    let circumradius = alpha.tan() / (0.5 * step).cos();
    let corners: Vec<Vector<3>> = (0..sides)
        .map(|k| {
            let angle = (k as f64 + 0.5) * step;
            axis + (e1 * angle.cos() + e2 * angle.sin()) * circumradius
        })
        .collect();
    let normals = (0..sides)
        .map(|k| {
            let before = corners[(k + sides - 1) % sides];
            // Corners run counter-clockwise about â, so before × corner points inwards.
            -before.cross(&corners[k]).normalize()
        })
        .collect();
    (normals, corners.iter().map(|c| c.normalize()).collect())
}

/// A lattice of 9 × 9 × 7 points 0.37 apart round `apex` in `frame` (ê₁, ê₂, â), off its
/// planes of symmetry: beside the faces and edges, round the tip, inside and far outside.
fn points_round(
    apex: Vector<3>,
    frame: (Vector<3>, Vector<3>, Vector<3>),
) -> impl Iterator<Item = Vector<3>> {
    (0..9)
        .flat_map(|a| (0..9).flat_map(move |b| (0..7).map(move |c| (a, b, c))))
        .map(move |(a, b, c)| {
            let q = Vector::<3>::new(a as f64 - 4.0, b as f64 - 4.0, c as f64 - 2.0) * 0.37
                + Vector::<3>::new(0.011, 0.007, 0.003);
            apex + frame.0 * q.x + frame.1 * q.y + frame.2 * q.z
        })
}

#[test]
fn a_pyramid_touches_exactly_the_particles_its_distance_says_it_does() {
    // The contact law skips a particle standing at least Δx/2 + ρ above a face's plane
    // without computing its distance; everywhere else δ = Δx/2 − s. Over the lattice, sharp
    // and rounded (ρ = 0.4: the skip must allow for it), the two agree to the bit, and some
    // points touch while most are skipped.
    let axis = Vector::<3>::new(0.0, 1.0, 1.0).normalize();
    let frame = (Vector::<3>::x(), axis.cross(&Vector::<3>::x()), axis);
    for tip_radius in [0.0, 0.4] {
        for (pyramid, ..) in pyramids(tip_radius) {
            let mut touching = 0;
            for x in points_round(Vector::<3>::new(1.0, 0.0, 0.0), frame) {
                let delta = pyramid.contact(0, x).0;
                assert_eq!(delta, (0.5 - pyramid.distance(x).0).max(0.0), "{x:?}");
                touching += usize::from(delta > 0.0);
            }
            assert!(touching > 50, "{touching} touching");
        }
    }
}

#[test]
fn a_pyramid_pushes_a_particle_out_from_its_nearest_surface_point() {
    // Outside, the push must come from the Euclidean projection p* of the particle's centre x
    // onto the solid pyramid: p* on its surface and x − p* making no acute angle with any
    // direction into the solid from p* (towards the apex and along every edge, which span
    // it). Inside, from the nearest face. Checked on a lattice of points round the tip,
    // beside faces and edges, with the faces and edges built from the corners, not as the
    // wall builds them.
    let axis = Vector::<3>::new(0.0, 1.0, 1.0).normalize();
    let frame = (Vector::<3>::x(), axis.cross(&Vector::<3>::x()), axis);
    let apex = Vector::<3>::new(1.0, 0.0, 0.0);
    let (mut outside, mut inside) = (0, 0);
    for (pyramid, sides, alpha) in pyramids(0.0) {
        let (normals, edges) = pyramid_from_corners(sides, alpha, frame);
        for (n, m) in normals.iter().zip(pyramid.face_normals()) {
            assert_relative_eq!(n, m, epsilon = 1e-14);
        }
        for (e, f) in edges.iter().zip(pyramid.edges()) {
            assert_relative_eq!(e, f, epsilon = 1e-14);
        }
        let depth = |y: Vector<3>| {
            normals
                .iter()
                .map(|n| n.dot(&(y - apex)))
                .fold(f64::NEG_INFINITY, f64::max)
        };
        for x in points_round(apex, frame) {
            let (s, n) = pyramid.distance(x);
            assert_relative_eq!(n.norm(), 1.0, epsilon = 1e-13);
            let foot = x - n * s;
            assert!(
                depth(foot).abs() < 1e-12,
                "{x:?}: foot {foot:?} off the surface"
            );
            if s > 0.0 {
                outside += 1;
                let away = x - foot;
                assert!(away.dot(&(apex - foot)) < 1e-12, "{x:?}");
                for e in &edges {
                    assert!(away.dot(e) < 1e-12, "{x:?}: along edge {e:?}");
                }
            } else {
                inside += 1;
                assert_relative_eq!(s, depth(x), epsilon = 1e-14);
            }
        }
    }
    assert!(
        outside > 500 && inside > 50,
        "{outside} outside, {inside} inside"
    );
}

#[test]
fn a_rounded_pyramid_is_the_sharp_one_grown_by_its_tip_radius_and_pushes_down_its_energy_gradient()
{
    // Rounded to ρ = 0.4, the tip stays at `point`: the sharp pyramid whose rounding it is has
    // its apex at tip + ρ â, and the surface is everything within ρ of it, so s = s_sharp − ρ.
    let axis = Vector::<3>::new(0.0, 1.0, 1.0).normalize();
    let tip = Vector::<3>::new(1.0, 0.0, 0.0);
    let e1 = Vector::<3>::x();
    let e2 = axis.cross(&e1);
    for ((sharp, sides, alpha), (rounded, ..)) in pyramids(0.0).into_iter().zip(pyramids(0.4)) {
        assert_eq!(rounded.apex(), tip + axis * 0.4);
        // The foremost point is the tip: a particle 0.3 before it along the axis touches by
        // δ = 0.2, pushed straight back.
        let (delta, n) = rounded.contact(0, tip - axis * 0.3);
        assert_relative_eq!(delta, 0.2, epsilon = 1e-14);
        assert_relative_eq!(n, -axis, epsilon = 1e-14);
        for x in [
            tip + e1 * 2.0 + axis * 1.5,
            tip - e2 * 0.7 + axis * 0.1,
            tip + (e1 + e2) * 0.3 - axis * 0.2,
        ] {
            let shifted = x - axis * 0.4;
            assert_relative_eq!(
                rounded.distance(x).0,
                sharp.distance(shifted).0 - 0.4,
                epsilon = 1e-13
            );
            assert_relative_eq!(
                rounded.distance(x).1,
                sharp.distance(shifted).1,
                epsilon = 1e-13
            );
        }
        // Beside face 0, high up: 0.3 out along its normal from a point on its centre line.
        let normal = e1 * alpha.cos() - axis * alpha.sin();
        let on_face = tip + axis * 3.0 + e1 * (3.0 * alpha.tan());
        assert_contact(
            &sharp,
            |y| sharp.distance(y).0,
            on_face + normal * 0.3,
            (0.2, normal),
        );
        // Past an edge (between faces 0 and 1): pushed away from the edge line, from a point
        // 0.3 out along the edge's outward radial direction at right angles to it.
        let radial = e1 * (std::f64::consts::PI / sides as f64).cos()
            + e2 * (std::f64::consts::PI / sides as f64).sin();
        let edge = sharp.edges()[0];
        let out = (radial - edge * radial.dot(&edge)).normalize();
        assert_contact(
            &sharp,
            |y| sharp.distance(y).0,
            tip + edge * 2.5 + out * 0.3,
            (0.2, out),
        );
        // The push is the gradient of ½ k δ²: beside a face, past an edge, round the tip and
        // pushed in, sharp and rounded.
        let points = [
            on_face + normal * 0.2,
            tip + edge * 2.5 + out * 0.2,
            tip - axis * 0.2 + e1 * 0.05 + e2 * 0.03,
            tip + axis * 2.0 + e1 * 0.1 + e2 * 0.05,
        ];
        assert_push_is_energy_gradient(&sharp, &points);
        assert_push_is_energy_gradient(&rounded, &points.map(|x| x + axis * 0.2));
    }
}

#[test]
fn a_pyramid_needs_three_sides_a_face_direction_across_its_axis_and_a_3d_scene() {
    let particles: (&[f64], &[f64], &[f64]) = (&[], &[], &[]);
    let build = |axis: Vector<3>, face: Vector<3>, sides: usize, alpha: f64, rho: f64| {
        RigidPyramid::<3>::new(
            Vector::<3>::zeros(),
            axis,
            face,
            sides,
            alpha,
            rho,
            particles,
        )
        .map(|_| ())
    };
    let (z, x) = (Vector::<3>::z(), Vector::<3>::x());
    assert!(build(z, x, 4, 1.2, 0.0).is_ok());
    let refused = |built: Result<(), String>, expected: &str| match built {
        Err(why) => assert!(why.contains(expected), "{why}"),
        Ok(()) => panic!("expected `{expected}`"),
    };
    refused(build(z, x, 2, 1.2, 0.0), "at least 3 sides");
    refused(build(z, x + z * 1e-6, 4, 1.2, 0.0), "at right angles");
    refused(
        build(Vector::<3>::zeros(), x, 4, 1.2, 0.0),
        "axis must be finite",
    );
    refused(
        build(z, z * f64::NAN, 4, 1.2, 0.0),
        "face direction must be finite",
    );
    for bad in [0.0, std::f64::consts::FRAC_PI_2, f64::NAN] {
        refused(
            build(z, x, 4, bad, 0.0),
            "half-angle must lie between 0 and 90°",
        );
    }
    refused(
        build(z, x, 4, 1.2, -0.1),
        "tip radius must be finite and ≥ 0",
    );
    let flat = RigidPyramid::<2>::new(
        Vector::<2>::zeros(),
        Vector::<2>::y(),
        Vector::<2>::x(),
        4,
        1.2,
        0.0,
        (&[], &[], &[]),
    );
    assert!(flat.unwrap_err().contains("needs a 3D scene"));
}
