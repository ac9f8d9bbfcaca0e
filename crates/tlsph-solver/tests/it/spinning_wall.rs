//! Walls spinning about their own axis (`WallMotion::spin`): the spin moves the surface, which
//! friction reads, and not the shape. Two counter-rotating rolls feed a strip at their surface
//! speed; a turntable spins a block up to its own angular velocity; the energy the spin puts in
//! through friction is booked; spins that would move the shape are refused.

use super::{lattice, model, Setup};
use tlsph_math::{Vector, Vector3};
use tlsph_solver::{
    BoundaryDescription, Diagnostics, FrictionCoefficients, Model, RampShape, SetupError,
    Simulation, VelocityRamp, WallDescription, WallMotion, WallShape,
};

/// A spin ω about the wall's point, reached after a smooth start over `ramp`.
fn spinning(omega: Vector3, ramp: f64) -> Option<WallMotion<2>> {
    Some(WallMotion {
        velocity: Vector::<2>::zeros(),
        spin: Some(omega),
        amplitude: None,
        spin_ramp: Some(VelocityRamp {
            duration: ramp,
            shape: RampShape::Smooth,
        }),
    })
}

/// A strip 1 long and 0.2 thick (20 × 4 particles, Δx = 0.05, c = 1) at rest, pinched between
/// two rolls of radius 0.5 at x = 0.5 whose surfaces press 0.05 Δx into its rows' contact
/// spheres, spinning (counter-rotating) so that both surfaces move at `surface_speed` along +x
/// where they touch it; static friction μ = `mu`.
fn rolling_feed(surface_speed: f64, mu: f64, end_time: f64) -> Model<2> {
    rolled_strip([20, 4], 0.05, surface_speed, mu, end_time)
}

/// The strip of [`rolling_feed`] as `particles` (columns × rows) of spacing `dx`, rolls
/// pinching it at x = 0.5.
fn rolled_strip(
    particles: [usize; 2],
    dx: f64,
    surface_speed: f64,
    mu: f64,
    end_time: f64,
) -> Model<2> {
    let radius = 0.5;
    let press = 0.05 * dx;
    let thickness = particles[1] as f64 * dx;
    let mut m = model(
        lattice(particles, dx),
        dx,
        |_| Vector::<2>::zeros(),
        Setup {
            end_time,
            ..Setup::default()
        },
    );
    let omega = surface_speed / radius;
    // The top roll's bottom moves along +x when it turns counter-clockwise (ω ẑ × (−R ŷ) =
    // ω R x̂), the bottom roll's top when it turns clockwise.
    for (name, centre_y, spin) in [
        ("top", thickness - press + radius, omega),
        ("bottom", press - radius, -omega),
    ] {
        m.effects.walls.push(WallDescription {
            name: name.into(),
            report_moment: false,
            point: Vector::<2>::new(0.5, centre_y),
            normal: Vector::<2>::new(0.0, 1.0),
            friction: FrictionCoefficients::single(mu),
            motion: spinning(Vector3::new(0.0, 0.0, spin), 0.5),
            shape: WallShape::Ball { radius },
        });
    }
    m
}

/// Mean velocity Σ m v / Σ m of the particles.
fn mean_velocity(sim: &Simulation<2>) -> Vector<2> {
    let masses = sim.masses();
    let momentum =
        (0..masses.len()).fold(Vector::<2>::zeros(), |p, i| p + sim.velocity(i) * masses[i]);
    momentum / masses.iter().sum::<f64>()
}

/// The energy booked in the friction columns.
fn friction_energy(d: &Diagnostics) -> f64 {
    d.effect_energies
        .iter()
        .filter(|(name, _)| name.ends_with("_friction"))
        .map(|(_, e)| e)
        .sum()
}

/// Runs `model` to its end after one step (the start-up of the penalty springs moves the
/// total by the leap-frog's ⅛Δt² Σ m|a|² for a few steps, then returns); from t = 1 on, the
/// worst |total − total after step 1| and, from `from` on, the strip's mean velocity along x
/// relative to `speed` (mean, least, largest) and the largest across.
fn feed_run(model: Model<2>, speed: f64, from: f64) -> (f64, [f64; 3], f64, Diagnostics) {
    let mut sim = Simulation::new(model).unwrap();
    sim.step().unwrap();
    let start = sim.diagnostics().total_energy();
    let (mut worst_total, mut worst_across) = (0.0_f64, 0.0_f64);
    let (mut sum, mut samples, mut least, mut largest) = (0.0, 0.0, f64::INFINITY, 0.0_f64);
    sim.run(|s, r| {
        if r.time > 1.0 {
            worst_total = worst_total.max((s.diagnostics().total_energy() - start).abs());
        }
        if r.time >= from {
            let v = mean_velocity(s);
            sum += v.x / speed;
            samples += 1.0;
            least = least.min(v.x / speed);
            largest = largest.max(v.x / speed);
            worst_across = worst_across.max(v.y.abs() / speed);
        }
    })
    .unwrap();
    (
        worst_total,
        [sum / samples, least, largest],
        worst_across,
        sim.diagnostics(),
    )
}

#[test]
fn counter_rotating_rolls_feed_a_strip_at_their_surface_speed() {
    // Rolls of radius R = 0.5 spinning up (smoothly, over 0.5) to a surface speed of 0.01 c
    // pull the pinched strip along by friction alone, until it moves with their surfaces.
    // Measured: the strip's mean velocity from t = 4 to 8 averages 1.024 of ω R along x
    // (0.986–1.075: the strip rings as the lattice passes the nip), and stays below 1e-10 of
    // it across. Bounds: 5 % on the average, 10 % on the extremes. Without the spin's surface
    // velocity in the friction law the strip stays at rest; with the sense of ω × r reversed
    // it runs the other way.
    // The spin puts the strip's kinetic and internal energy in through friction, and the
    // friction columns book that work (negative: put in), so the total stays put as well as it
    // does for the same strip passing a frictionless nip at the same speed, whose penalty
    // springs make the total wobble as particles enter and leave it. Measured: worst
    // |total − start| after t = 1 is 1.2e-6 (17 % of the 7.2e-6 put in), against 1.0e-6 for
    // the frictionless nip; bound: 30 % of the work put in, where leaving the spin's work out
    // of the booking would leave it off by all of it.
    let speed = 0.01;
    let (worst_total, [mean, least, largest], across, d) =
        feed_run(rolling_feed(speed, 1.0, 8.0), speed, 4.0);
    let put_in = -friction_energy(&d);
    let mut nip = rolling_feed(speed, 0.0, 8.0);
    for wall in &mut nip.effects.walls {
        wall.motion = None;
    }
    for v in &mut nip.bodies[0].velocities {
        v.x = speed;
    }
    let (nip_total, [nip_mean, ..], _, _) = feed_run(nip, speed, 4.0);
    println!(
        "strip at {mean:.4} ({least:.4}–{largest:.4}) of ωR, across {across:.2e}; total {worst_total:.2e} of work {put_in:.3e}; frictionless nip {nip_total:.2e}, strip at {nip_mean:.4}"
    );
    assert!(
        (mean - 1.0).abs() < 0.05 && least > 0.9 && largest < 1.1,
        "strip moved at {mean:.4} ({least:.4}–{largest:.4}) of the rolls' surface speed"
    );
    assert!(across < 1e-6, "the strip drifted across: {across:.2e}");
    assert!(
        worst_total < 0.3 * put_in,
        "total moved by {worst_total:.2e}, the spin put in {put_in:.2e}"
    );
}

/// A 6 × 6 × 3 block (Δx = 0.05, c = 1) centred on the z axis on the plane z = 0, which
/// spins about its normal (smooth start over 0.5) at `omega`, held down by a frictionless
/// plane pressing 0.05 Δx into the top row; friction μ = 1 on the table.
fn turntable(omega: f64, end_time: f64) -> Model<3> {
    let dx = 0.05;
    let press = 0.05 * dx;
    let positions: Vec<Vector<3>> = lattice([6, 6, 3], dx)
        .into_iter()
        .map(|x| x - Vector::<3>::new(0.15, 0.15, 0.0))
        .collect();
    let mut m = model(
        positions,
        dx,
        |_| Vector::<3>::zeros(),
        Setup {
            end_time,
            ..Setup::default()
        },
    );
    m.effects.walls.push(WallDescription {
        name: "table".into(),
        report_moment: false,
        point: Vector::<3>::new(0.0, 0.0, press),
        normal: Vector::<3>::new(0.0, 0.0, 2.0),
        friction: FrictionCoefficients::single(1.0),
        motion: Some(WallMotion {
            velocity: Vector::<3>::zeros(),
            spin: Some(Vector3::new(0.0, 0.0, omega)),
            amplitude: None,
            spin_ramp: Some(VelocityRamp {
                duration: 0.5,
                shape: RampShape::Smooth,
            }),
        }),
        shape: WallShape::Plane,
    });
    m.effects.walls.push(WallDescription {
        name: "lid".into(),
        report_moment: false,
        point: Vector::<3>::new(0.0, 0.0, 0.15 - press),
        normal: Vector::<3>::new(0.0, 0.0, -1.0),
        friction: FrictionCoefficients::single(0.0),
        motion: None,
        shape: WallShape::Plane,
    });
    m
}

#[test]
fn a_turntable_spins_a_block_up_to_its_own_angular_velocity() {
    // A 6 × 6 × 3 block (Δx = 0.05, c = 1) centred on the z axis sits on the plane z = 0
    // spinning about its normal at ω = 0.05 (surface speed at the block's corners 0.008 c),
    // held down by a frictionless plane pressing 0.05 Δx into the top row. Friction (μ = 1)
    // turns the block with the table: from t = 3 on, its angular velocity about z,
    // Σ m (r × v)_z / Σ m r², is that of the table on average. Measured: 0.988 of ω on
    // average from t = 3 to 5 (0.70–1.18: the block rings in torsion after the spin-up, with
    // nothing to damp it but slip); bound 3 % on the average. Its centre stays on the axis (a
    // spin about z cannot push it sideways): measured in-plane mean velocity 1e-15; bound
    // 1e-6 of the corner speed.
    let omega = 0.05;
    let m = turntable(omega, 5.0);
    let mut sim = Simulation::new(m).unwrap();
    let (mut slowest, mut fastest, mut drift) = (f64::INFINITY, 0.0_f64, 0.0_f64);
    let (mut sum, mut samples) = (0.0, 0.0);
    sim.run(|s, r| {
        if r.time < 3.0 {
            return;
        }
        let (mut spin, mut inertia) = (0.0, 0.0);
        let mut momentum = Vector::<3>::zeros();
        for (i, m) in s.masses().iter().enumerate() {
            let x = s.positions0()[i] + s.displacements()[i];
            let v = s.velocity(i);
            spin += m * (x.x * v.y - x.y * v.x);
            inertia += m * (x.x * x.x + x.y * x.y);
            momentum += Vector::<3>::new(v.x, v.y, 0.0) * *m;
        }
        sum += spin / inertia / omega;
        samples += 1.0;
        slowest = slowest.min(spin / inertia / omega);
        fastest = fastest.max(spin / inertia / omega);
        drift = drift.max(momentum.norm() / s.masses().iter().sum::<f64>());
    })
    .unwrap();
    let mean = sum / samples;
    println!("block at {mean:.4} ({slowest:.4}–{fastest:.4}) of ω, centre drift {drift:.2e}");
    assert!(
        (mean - 1.0).abs() < 0.03 && slowest > 0.5 && fastest < 1.5,
        "block turned at {mean:.4} ({slowest:.4}–{fastest:.4}) of the table's ω"
    );
    assert!(
        drift < 1e-6 * omega * 0.15,
        "the block's centre drifted: {drift:.2e}"
    );
}

#[test]
fn a_turntables_torque_is_the_rate_of_the_blocks_angular_momentum() {
    // The table's friction is the only force on the block with a moment about z (the table's
    // and the lid's normal forces are along z), so the torque the table reports,
    // T = Σ m ẑ·((y − c) × a), integrated over time is the block's angular momentum about the
    // axis: L_z(t) = ∫₀ᵗ T dt. The leap-frog's change of Σ x × m v from t^n to t^{n+1} is
    // exactly the trapezoidal rule ½Δt (T^n + T^{n+1}) of the torques at the two instants
    // (the internal forces' moments cancel), so the two agree to round-off. Measured over the
    // spin-up and the ringing after it (t ≤ 2): worst |L_z − ∫T dt| is 1.1e-15 of the largest
    // L_z; bound 1e-9 (round-off over some thousand steps). With the lever reversed, the
    // torque would miss by twice L_z.
    let omega = 0.05;
    let mut sim = Simulation::new(turntable(omega, 2.0)).unwrap();
    let first = sim.diagnostics();
    let (mut impulse, mut last) = (
        0.0,
        (first.time, first.effect_torque("wall_table_friction")),
    );
    let (mut worst, mut largest) = (0.0_f64, 0.0_f64);
    sim.run(|s, _| {
        let d = s.diagnostics();
        let torque = d.effect_torque("wall_table_friction");
        impulse += 0.5 * (last.1 + torque) * (d.time - last.0);
        last = (d.time, torque);
        let spin = d.angular_momentum.z - first.angular_momentum.z;
        worst = worst.max((spin - impulse).abs());
        largest = largest.max(spin.abs());
    })
    .unwrap();
    println!(
        "L_z up to {largest:.4e}, worst |L_z − ∫T dt| {worst:.2e} ({:.2e} of it)",
        worst / largest
    );
    assert!(largest > 0.0, "the block never turned");
    assert!(
        worst < 1e-9 * largest,
        "∫T dt missed the block's angular momentum by {worst:.2e} of {largest:.2e}"
    );
}

#[test]
fn a_torque_taken_by_a_held_layer_is_not_the_walls() {
    // The turntable's block, moved 0.3 off the axis, has its bottom layer (the one touching
    // the table) held still in the plane by a prescribed velocity: the table's friction there
    // is taken by the grip (as it is out of the friction's resultant), so the table reports
    // neither force nor torque on the particles. Measured: both exactly 0 at every step,
    // while the table slides under the layer (at 0.015 at its middle) and the grip reports a
    // force of up to 4.0e-3 (the friction's drag along y); bound: 0 (the held components are
    // removed before the torque is summed; summed before, it would be the drag's moment).
    let omega = 0.05;
    let mut m = turntable(omega, 1.0);
    for x in &mut m.bodies[0].positions {
        x.x += 0.3;
    }
    let bottom: Vec<usize> = (0..m.bodies[0].positions.len())
        .filter(|&i| m.bodies[0].positions[i].z < 0.05)
        .collect();
    m.boundaries.push(BoundaryDescription {
        name: "grip".into(),
        body: 0,
        particles: bottom,
        velocity: Vector::<3>::zeros(),
        components: [true, true, false],
        amplitude: None,
    });
    let mut sim = Simulation::new(m).unwrap();
    let (mut worst, mut grip) = (0.0_f64, 0.0_f64);
    sim.run(|s, _| {
        let d = s.diagnostics();
        let force = d.effect_force("wall_table_friction");
        worst = worst
            .max(d.effect_torque("wall_table_friction").abs())
            .max(force.x.abs())
            .max(force.y.abs());
        grip = grip.max(d.boundary_forces[0].1.norm());
    })
    .unwrap();
    println!("held layer: worst torque or force {worst:.2e}, grip force up to {grip:.3e}");
    assert!(grip > 0.0, "the table's friction never reached the grip");
    assert_eq!(worst, 0.0, "the table reported the grip's share");
}

#[test]
fn a_rolls_torque_is_its_radius_times_the_friction_it_feeds_with() {
    // A roll of radius R touches the strip at the surface points straight below (above) its
    // centre, so the torque it reports about its spin (positive: it drives the particles round
    // with it) is R times the friction it drags the strip with: ∫T dt = R ∫F_x dt over the
    // spin-up and the catch-up (t ≤ 2), within 1/cos of the contact patch's half-angle (about
    // 0.1 rad: F_x is the sum of the tangential forces' x components, at most 0.5 % short).
    // Measured: 1.0014 for both rolls; bound 1 %. With the lever taken to the particle's
    // centre, not the touching surface point, it would come out at (R + Δx/2)/R = 1.05.
    // |ω| T is the power the spin puts in; the friction column books that less what slip
    // dissipates, so the work booked as put in is positive and at most ∫ |ω| T dt. Measured:
    // 0.39 of it (the strip, started at rest between rolls pressed into it, slides on them
    // while it catches up, and rings across its thickness, slipping on both); bound: above 0
    // and at most 1 + 1e-3 of it (the trapezoidal rule over the samples). With the torque's
    // sense reversed the spin's work would come out negative.
    let speed = 0.01;
    let model = rolling_feed(speed, 1.0, 2.0);
    let radius = 0.5;
    let spins: Vec<WallMotion<2>> = model
        .effects
        .walls
        .iter()
        .map(|w| w.motion.clone().unwrap())
        .collect();
    let names = ["wall_top_friction", "wall_bottom_friction"];
    let sample = |d: &Diagnostics| -> [[f64; 2]; 3] {
        let torque = names.map(|n| d.effect_torque(n));
        let force = names.map(|n| d.effect_force(n).x);
        let power = [0, 1].map(|k| spins[k].spin_at(d.time).unwrap().norm() * torque[k]);
        [torque, force, power]
    };
    let mut sim = Simulation::new(model).unwrap();
    let (mut integrals, mut last) = ([[0.0; 2]; 3], (0.0, sample(&sim.diagnostics())));
    sim.run(|s, _| {
        let d = s.diagnostics();
        let now = sample(&d);
        for (q, sum) in integrals.iter_mut().enumerate() {
            for k in 0..2 {
                sum[k] += 0.5 * (last.1[q][k] + now[q][k]) * (d.time - last.0);
            }
        }
        last = (d.time, now);
    })
    .unwrap();
    let [impulse, force_impulse, spin_work] = integrals;
    let ratios = [
        impulse[0] / (radius * force_impulse[0]),
        impulse[1] / (radius * force_impulse[1]),
    ];
    let put_in = -friction_energy(&sim.diagnostics());
    let booked = put_in / (spin_work[0] + spin_work[1]);
    println!(
        "∫T dt / (R ∫F_x dt): top {:.5}, bottom {:.5}; booked {put_in:.4e} = {booked:.5} of ∫ωT dt",
        ratios[0], ratios[1]
    );
    assert!(
        force_impulse[0] > 0.0 && force_impulse[1] > 0.0,
        "{force_impulse:?}"
    );
    for ratio in ratios {
        assert!(
            (ratio - 1.0).abs() < 0.01,
            "∫T dt / (R ∫F_x dt) = {ratio:.5}"
        );
    }
    assert!(
        booked > 0.0 && booked < 1.0 + 1e-3,
        "friction booked {booked:.5} of the spin's work ∫ωT dt"
    );
}

#[test]
fn a_spinning_walls_torque_is_bit_identical_for_one_and_two_threads() {
    // The torque is summed in fixed chunks of particles, so it does not depend on how rayon
    // splits the work. A strip of 128 × 40 particles (more than one chunk of 4096) pinched by
    // the spinning rolls for 0.1 (59 steps, the spin 10 % up): the torques and the
    // displacements of one and of two threads agree bit for bit.
    let run = |threads: usize| {
        super::on_threads(threads, || {
            let mut sim = Simulation::new(rolled_strip([128, 40], 0.005, 0.01, 1.0, 0.1)).unwrap();
            let mut torques = Vec::new();
            sim.run(|s, _| {
                let d = s.diagnostics();
                torques.push(d.effect_torque("wall_top_friction").to_bits());
                torques.push(d.effect_torque("wall_bottom_friction").to_bits());
            })
            .unwrap();
            let u: Vec<[u64; 2]> = sim
                .displacements()
                .iter()
                .map(|u| [u.x.to_bits(), u.y.to_bits()])
                .collect();
            (torques, u)
        })
    };
    let (one, two) = (run(1), run(2));
    assert!(
        one.0.iter().any(|t| f64::from_bits(*t) != 0.0),
        "the rolls never turned the strip"
    );
    assert_eq!(one.0, two.0, "torques differ between thread counts");
    assert_eq!(one.1, two.1, "displacements differ between thread counts");
}

#[test]
fn the_solver_refuses_a_spin_that_would_move_the_shape_or_could_not_be_felt() {
    // A library user builds the model without the scene reader's checks.
    let refused = |shape: WallShape<2>, spin: Vector3, mu: f64| {
        let mut m = rolling_feed(0.01, mu, 0.1);
        m.effects.walls[0].shape = shape;
        m.effects.walls[0].motion.as_mut().unwrap().spin = Some(spin);
        match Simulation::new(m) {
            Err(SetupError::InvalidConfig { field, message }) => {
                assert_eq!(field, "wall");
                message
            }
            other => panic!("expected a wall error, got {other:?}"),
        }
    };
    let ball = WallShape::Ball { radius: 0.5 };
    let about_z = Vector3::new(0.0, 0.0, 0.02);
    let message = refused(ball, about_z, 0.0);
    assert!(message.contains("only through friction"), "{message}");
    let message = refused(ball, Vector3::new(0.02, 0.0, 0.0), 0.5);
    assert!(message.contains("own axis"), "{message}");
    let message = refused(WallShape::Plane, about_z, 0.5);
    assert!(message.contains("only a ball may spin"), "{message}");
    let message = refused(ball, Vector3::new(0.0, 0.0, f64::NAN), 0.5);
    assert!(message.contains("finite spin"), "{message}");
}
