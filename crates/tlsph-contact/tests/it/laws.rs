//! The potential law (numerics.md §12.2) and the penalty law (§12.1) checked against their
//! potentials by central differences, and the surface test and normals on a lattice.

use approx::assert_relative_eq;
use tlsph_contact::{
    is_surface, AnyKernel, FrictionCoefficients, Kernel, KernelKind, OutwardNormal, PenaltyLaw,
    PotentialLaw, Vector,
};

fn cubic(dimension: usize, h: f64) -> AnyKernel {
    KernelKind::CubicSpline.build(dimension, h).unwrap()
}

/// Reveles' decks: d0 = Δx = 1, h_c = 1.2, a M* d0 = 2 (2D).
fn potential_law(exponent: f64) -> PotentialLaw {
    PotentialLaw::new(cubic(2, 1.2), 1.0, 2.0, exponent, 0.0)
}

#[test]
fn potential_law_force_is_minus_the_derivative_of_its_potential() {
    // Central differences with step 1e-6 have truncation error ~ φ''' e² ≈ 1e-12 and
    // round-off ~ 1e-16 φ / e ≈ 1e-10 relative to a force of order 1: 1e-7 leaves margin.
    for exponent in [4.0, 2.5] {
        let law = potential_law(exponent);
        for r in [0.35, 0.5, 0.7, 0.9, 0.99] {
            let e = 1e-6;
            let slope = (law.evaluate(r + e).potential - law.evaluate(r - e).potential) / (2.0 * e);
            let state = law.evaluate(r);
            assert!(state.force > 0.0, "repulsive inside d0 at r = {r}");
            assert_relative_eq!(state.force, -slope, max_relative = 1e-7, epsilon = 1e-9);
            // The time-step stiffness bounds the normal stiffness −df/dr.
            let df = (law.evaluate(r + e).force - law.evaluate(r - e).force) / (2.0 * e);
            assert!(state.stiffness >= -df * (1.0 - 1e-6), "r = {r}");
        }
    }
}

#[test]
fn potential_law_vanishes_at_the_contact_distance_and_touches_with_its_tangent_stiffness() {
    let law = potential_law(4.0);
    let at_d0 = law.evaluate(law.d0());
    assert!(at_d0.force.abs() < 1e-14 && at_d0.potential.abs() < 1e-14);
    // One-sided difference just inside d0: −df/dr → touch stiffness (error O(e)).
    let e = 1e-7;
    let slope = law.evaluate(law.d0() - e).force / e;
    assert_relative_eq!(law.touch_stiffness(), slope, max_relative = 1e-5);
    // By hand: c n (−W'(d0))/W(d0) for the 2D cubic spline at q = 1/1.2.
    let kernel = cubic(2, 1.2);
    let by_hand = 2.0 * 4.0 * -kernel.derivative(1.0) / kernel.value(1.0);
    assert_relative_eq!(law.touch_stiffness(), by_hand, max_relative = 1e-14);
}

#[test]
fn self_contact_excludes_the_reference_support() {
    let law = PotentialLaw::new(cubic(2, 1.2), 1.0, 2.0, 4.0, 2.4);
    assert!(
        !law.allows_self_pair(0.0),
        "a particle never contacts itself"
    );
    assert!(!law.allows_self_pair(2.39 * 2.39));
    assert!(law.allows_self_pair(2.4 * 2.4));
    let between_bodies = potential_law(4.0);
    assert!(between_bodies.allows_self_pair(1e-300) && !between_bodies.allows_self_pair(0.0));
}

/// k_c = E d0^{d−1} with E = 1, d0 = 1, R = d0, μ as given.
fn penalty_law<const D: usize>(friction: f64) -> PenaltyLaw {
    penalty_law_with::<D>(FrictionCoefficients::single(friction))
}

/// The same law with kinetic and static coefficients.
fn penalty_law_with<const D: usize>(friction: FrictionCoefficients) -> PenaltyLaw {
    PenaltyLaw::new::<D>(1.0, 1.0, friction, 1.0, 1.0)
}

fn check_penalty_gradient<const D: usize>(normal: Vector<D>, offsets: &[Vector<D>]) {
    let law = penalty_law::<D>(0.0);
    let zero = Vector::<D>::zeros();
    for d in offsets {
        let force = law
            .force_on_partner(d, &normal, &zero, 0.0)
            .expect("inside the zone");
        // −∇_K U by central differences (U is smooth inside the zone above the floor).
        let e = 1e-6;
        let gradient = Vector::<D>::from_fn(|a, _| {
            let mut plus = *d;
            let mut minus = *d;
            plus[a] += e;
            minus[a] -= e;
            (law.potential(&plus, &normal) - law.potential(&minus, &normal)) / (2.0 * e)
        });
        for a in 0..D {
            assert_relative_eq!(force[a], -gradient[a], epsilon = 1e-7);
        }
    }
}

#[test]
fn penalty_force_is_the_gradient_of_its_pair_potential_with_the_normal_held() {
    let n2 = Vector::<2>::new(0.6, 0.8);
    let t2 = Vector::<2>::new(-0.8, 0.6);
    check_penalty_gradient::<2>(
        n2,
        &[
            n2 * 0.5,
            n2 * 0.3 + t2 * 0.4,
            n2 * 0.9 - t2 * 0.7,
            n2 * -0.5 + t2 * 0.2,
        ],
    );
    let n3 = Vector::<3>::new(0.0, 0.0, 1.0);
    check_penalty_gradient::<3>(
        n3,
        &[
            Vector::<3>::new(0.1, -0.2, 0.4),
            Vector::<3>::new(0.5, 0.5, 0.8),
            Vector::<3>::new(-0.3, 0.0, -0.6),
        ],
    );
}

#[test]
fn penalty_zone_is_the_square_in_2d_and_the_cylinder_in_3d() {
    let law = penalty_law::<2>(0.0);
    let (n, zero) = (Vector::<2>::new(0.0, 1.0), Vector::<2>::zeros());
    let inside = |d: Vector<2>| law.force_on_partner(&d, &n, &zero, 0.0).is_some();
    // r⊥ ∈ [−d0, R), |t| < d0.
    assert!(inside(Vector::<2>::new(0.0, 0.999)) && !inside(Vector::<2>::new(0.0, 1.0)));
    assert!(inside(Vector::<2>::new(0.0, -1.0)) && !inside(Vector::<2>::new(0.0, -1.001)));
    assert!(inside(Vector::<2>::new(0.999, 0.5)) && !inside(Vector::<2>::new(1.0, 0.5)));
    let law3 = penalty_law::<3>(0.0);
    let (n3, zero3) = (Vector::<3>::new(0.0, 0.0, 1.0), Vector::<3>::zeros());
    let inside3 = |d: Vector<3>| law3.force_on_partner(&d, &n3, &zero3, 0.0).is_some();
    // A point at |t| = 0.99 on the diagonal is inside the cylinder (a cube would hold 0.99√2).
    assert!(inside3(Vector::<3>::new(0.7, 0.7, 0.5)));
    assert!(!inside3(Vector::<3>::new(0.72, 0.72, 0.5)));
    assert_relative_eq!(law.zone_radius(), 2f64.sqrt(), max_relative = 1e-15);
}

#[test]
fn penalty_force_on_the_axis_is_fullers_and_friction_opposes_slip() {
    let law = penalty_law::<2>(0.4);
    let n = Vector::<2>::new(0.0, 1.0);
    let on_axis = Vector::<2>::new(0.0, 0.5);
    // On I's axis at r⊥ = 0.5: f_n = k_c (R/r⊥ − 1) = 1 (F 4.2), no tangential penalty part.
    let still = law
        .force_on_partner(&on_axis, &n, &Vector::zeros(), 1e3)
        .unwrap();
    assert_relative_eq!(still[1], 1.0, max_relative = 1e-14);
    assert_eq!(still[0], 0.0);
    assert_relative_eq!(
        law.normal_force_on_partner(&on_axis, &n).unwrap(),
        1.0,
        max_relative = 1e-14
    );
    // Sliding at 0.1 along +x (the normal part of the velocity plays no role), with a stick
    // rate λ = 100 s/m: stopping it would take λ|v_t| = 10 times the normal force, more than
    // μ = 0.4, so the pair slides and friction is Coulomb's −μ|f_n| in x.
    let sliding_velocity = Vector::<2>::new(0.1, -0.05);
    let sliding = law
        .force_on_partner(&on_axis, &n, &sliding_velocity, 100.0)
        .unwrap();
    assert_relative_eq!(sliding[0], -0.4, max_relative = 1e-12);
    assert_relative_eq!(sliding[1], 1.0, max_relative = 1e-14);
    // With λ = 2 s/m the stopping force λ|v_t| |f_n| = 0.2 is below μ|f_n|: exactly that
    // force acts and the pair sticks.
    let sticking = law
        .force_on_partner(&on_axis, &n, &sliding_velocity, 2.0)
        .unwrap();
    assert_relative_eq!(sticking[0], -0.2, max_relative = 1e-12);
    // At rest (or without a stick rate) there is no friction force and no division by zero.
    for (velocity, rate) in [(Vector::zeros(), 2.0), (sliding_velocity, 0.0)] {
        let f = law.force_on_partner(&on_axis, &n, &velocity, rate).unwrap();
        assert_eq!(f[0], 0.0);
    }
    // Below the floor 0.05R the force stays at 19 k_c.
    let deep = law
        .force_on_partner(&Vector::<2>::new(0.0, 0.01), &n, &Vector::zeros(), 0.0)
        .unwrap();
    assert_relative_eq!(deep[1], 19.0, max_relative = 1e-12);
    // Outside the zone: no normal force.
    assert_eq!(
        law.normal_force_on_partner(&Vector::<2>::new(0.0, 1.5), &n),
        None
    );
}

#[test]
fn penalty_friction_sticks_up_to_the_static_coefficient_and_slides_at_the_kinetic_one() {
    // μ_k = 0.2, μ_s = 0.5; on I's axis at r⊥ = 0.5 the normal force is 1, sliding at 0.1
    // along +x.
    let friction = FrictionCoefficients {
        kinetic: 0.2,
        static_coefficient: 0.5,
        decay: None,
    };
    let law = penalty_law_with::<2>(friction);
    assert!(law.has_friction());
    let n = Vector::<2>::new(0.0, 1.0);
    let on_axis = Vector::<2>::new(0.0, 0.5);
    let v = Vector::<2>::new(0.1, 0.0);
    let tangential = |rate: f64| law.force_on_partner(&on_axis, &n, &v, rate).unwrap()[0];
    // Demand λ|v_t| = 0.3: above μ_k, within μ_s, so the pair sticks under exactly that force
    // (one coefficient μ = 0.2 would let it slide under 0.2).
    assert_relative_eq!(tangential(3.0), -0.3, max_relative = 1e-12);
    assert_relative_eq!(
        penalty_law::<2>(0.2)
            .force_on_partner(&on_axis, &n, &v, 3.0)
            .unwrap()[0],
        -0.2,
        max_relative = 1e-12
    );
    // At the static limit it still sticks; beyond it the pair slides under μ_k, not μ_s.
    assert_relative_eq!(tangential(5.0), -0.5, max_relative = 1e-12);
    assert_relative_eq!(tangential(5.0 + 1e-9), -0.2, max_relative = 1e-12);
    // A static coefficient alone is friction too: it holds, and lets go without a kinetic
    // force.
    let static_only = penalty_law_with::<2>(FrictionCoefficients {
        kinetic: 0.0,
        static_coefficient: 0.5,
        decay: None,
    });
    assert!(static_only.has_friction() && !penalty_law::<2>(0.0).has_friction());
    let f = |rate: f64| {
        static_only
            .force_on_partner(&on_axis, &n, &v, rate)
            .unwrap()[0]
    };
    assert_relative_eq!(f(3.0), -0.3, max_relative = 1e-12);
    assert_eq!(f(10.0), 0.0);
}

#[test]
fn penalty_vote_covers_pairs_that_may_touch_within_the_skin() {
    let law = penalty_law::<2>(0.0);
    let n = Vector::<2>::new(0.0, 1.0);
    // Beyond R but within the skin: first-touch stiffness w(t) k_c/R, w = (1 − t²)² at
    // t = 0.2 → 0.9216.
    assert_relative_eq!(
        law.vote_stiffness(&Vector::<2>::new(0.2, 1.3), &n, 0.5)
            .unwrap(),
        0.9216,
        max_relative = 1e-14
    );
    // At the zone's side the force is zero and so is the vote, continuously: a partner a
    // round-off inside it votes next to nothing, one just outside not at all.
    let side = law
        .vote_stiffness(&Vector::<2>::new(1.0 - 1e-15, 1.3), &n, 0.5)
        .unwrap();
    assert!(side < 1e-28, "{side}");
    assert_eq!(
        law.vote_stiffness(&Vector::<2>::new(1.0 + 1e-15, 1.3), &n, 0.5),
        None
    );
    assert_eq!(
        law.vote_stiffness(&Vector::<2>::new(0.2, 1.6), &n, 0.5),
        None
    );
    // Inside: w(t) k_c R / r⊥² at t = 0, r⊥ = 0.5 → 4.
    assert_eq!(
        law.vote_stiffness(&Vector::<2>::new(0.0, 0.5), &n, 0.5),
        Some(4.0)
    );
}

/// Live neighbour counts within 2h = 3Δx on an n × n lattice of unit spacing.
fn lattice_counts(n: i32) -> Vec<((i32, i32), usize)> {
    let inside = |i: i32, j: i32| (0..n).contains(&i) && (0..n).contains(&j);
    let mut counts = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let mut c = 0;
            for di in -2..=2 {
                for dj in -2..=2 {
                    if (di, dj) != (0, 0) && di * di + dj * dj < 9 && inside(i + di, j + dj) {
                        c += 1;
                    }
                }
            }
            counts.push(((i, j), c));
        }
    }
    counts
}

#[test]
fn surface_test_separates_a_flat_face_from_the_row_beneath() {
    // numerics.md §12.1 lattice check: 24 neighbours inside, 14 (58 %) on a face, 19 (79 %)
    // on the row beneath.
    let counts = lattice_counts(12);
    let full = counts.iter().map(|c| c.1).max().unwrap();
    assert_eq!(full, 24);
    let count_at = |p: (i32, i32)| counts.iter().find(|c| c.0 == p).unwrap().1;
    assert_eq!(count_at((6, 0)), 14);
    assert_eq!(count_at((6, 1)), 19);
    assert!(is_surface(14, full) && !is_surface(19, full));
    for ((i, j), c) in counts {
        let outermost = i == 0 || j == 0 || i == 11 || j == 11;
        if outermost {
            assert!(is_surface(c, full), "({i}, {j}) with {c} neighbours");
        }
        if (2..10).contains(&i) && (2..10).contains(&j) {
            assert!(!is_surface(c, full), "({i}, {j}) is interior");
        }
    }
    assert!(
        !is_surface(0, full),
        "a particle without live neighbours has no surface"
    );
}

#[test]
fn outward_normals_of_a_face_and_a_corner() {
    let kernel = cubic(2, 1.5);
    let lattice: Vec<Vector<2>> = (0..10)
        .flat_map(|i| (0..10).map(move |j| Vector::<2>::new(i as f64, j as f64)))
        .collect();
    let normal_at = |x: Vector<2>| {
        let mut normal = OutwardNormal::new(x, &kernel);
        for &y in &lattice {
            if (x - y).norm() < kernel.support_radius() {
                normal.add(y);
            }
        }
        normal.unit()
    };
    // Middle of the bottom face (mirror-symmetric in x up to the lattice's 4.5 centre, so
    // use a face point with symmetric neighbours: x = 4 has 2 left and 2 right within 3).
    let face = normal_at(Vector::<2>::new(4.0, 0.0));
    assert_relative_eq!(face[1], -1.0, epsilon = 1e-14);
    assert!(face[0].abs() < 1e-14);
    let corner = normal_at(Vector::<2>::new(0.0, 0.0));
    let diagonal = -Vector::<2>::new(1.0, 1.0).normalize();
    assert_relative_eq!(corner, diagonal, epsilon = 1e-14);
    // A lone particle (or one on top of its only neighbour) has no normal.
    let lone = OutwardNormal::new(Vector::<2>::zeros(), &kernel);
    assert_eq!(lone.unit(), Vector::<2>::zeros());
}
