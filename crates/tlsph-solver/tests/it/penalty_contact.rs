//! Fuller's particle-type penalty contact with friction (numerics.md §12.1): the elastic impact
//! stress and rebound of two bars, momentum to round-off, Coulomb's impulse ratio in a sliding
//! impact, frictionless sliding, a block resting on a deformable base, stick and slip on an
//! incline, determinism, and the setup checks.

use super::contact::{approaching_bars, body, body_velocity, config, materials, V};
use super::lattice;
use tlsph_contact::FrictionCoefficients;
use tlsph_math::Vector;
use tlsph_solver::{
    BoundaryDescription, ContactDescription, EffectsDescription, Formulation, Model, ParticleField,
    PenaltyContactDescription, SetupError, Simulation,
};

/// Fuller's penalty law (stiffness and range factors 1) with friction coefficient `friction`.
pub(super) fn penalty(friction: f64) -> Option<PenaltyContactDescription> {
    Some(PenaltyContactDescription {
        stiffness: 1.0,
        range: 1.0,
        friction: FrictionCoefficients::single(friction),
        pairs: None,
    })
}

/// Two identical 1D bars of n particles approaching at ±V in frictionless penalty contact,
/// their end particles 0.02 dx further apart than one spacing (the penalty range R = Δx).
fn bars_1d(n: usize, formulation: Formulation, end_time: f64) -> Model<1> {
    let effects = EffectsDescription {
        penalty_contact: penalty(0.0),
        ..Default::default()
    };
    approaching_bars(n, formulation, end_time, 0.02, effects)
}

#[test]
fn penalty_contact_bars_rebound_with_the_elastic_impact_stress_rho_c_v() {
    // Symmetric elastic impact (c = 1, ρ = 1): σ = ρcv at the middle particle from L/(2c)
    // after first touch to 3L/(2c). At rest the penalty force balances the bar stress, so the
    // plateau is ρcv to the SPH ringing (3 %, as for the potential law); the bars leave with
    // their speeds reversed to the ringing the contact spring leaves (5 %).
    for formulation in [
        Formulation::TotalLagrangianCorrected,
        Formulation::UpdatedLagrangian,
    ] {
        let n = 100;
        let mut sim = Simulation::new(bars_1d(n, formulation, 3.0)).unwrap();
        let middle = n / 2;
        let mut touch = f64::NAN;
        let (mut sum, mut count) = (0.0, 0);
        let p0 = sim.diagnostics().linear_momentum;
        let mut worst_momentum: f64 = 0.0;
        sim.run(|s, _| {
            let d = s.diagnostics();
            if touch.is_nan() && d.effect_force("contact").norm() > 0.0 {
                touch = s.time();
            }
            worst_momentum = worst_momentum.max((d.linear_momentum - p0).norm());
            let tau = s.time() - touch;
            if tau > 0.7 && tau < 1.3 {
                sum += -s.sample(ParticleField::Stress(0, 0), middle);
                count += 1;
            }
        })
        .unwrap();
        let plateau = sum / count as f64;
        let (left, right) = (body_velocity(&sim, 0)[0], body_velocity(&sim, 1)[0]);
        eprintln!(
            "{formulation:?}: plateau/ρcv {:.4}, rebound {:.4} {:.4}, momentum {worst_momentum:.1e}",
            plateau / V,
            left / V,
            right / V
        );
        assert!(count > 0, "{formulation:?}: the bars never touched");
        assert!(
            (plateau / V - 1.0).abs() < 0.03,
            "{formulation:?}: plateau {plateau:e} vs ρcv = {V:e}"
        );
        assert!(
            (left + V).abs() < 0.05 * V && (right - V).abs() < 0.05 * V,
            "{formulation:?}: rebound {left:e}, {right:e}"
        );
        // Total momentum is zero; pair forces are equal and opposite, so it stays zero to
        // round-off of the sums (mass 1 · V = 0.01 per bar).
        assert!(
            worst_momentum < 1e-15,
            "{formulation:?}: {worst_momentum:e}"
        );
        assert_eq!(sim.diagnostics().effect_force("contact").norm(), 0.0);
    }
}

/// Spacing of the slider and base of [`slider_and_base`].
pub(super) const SLIDER_DX: f64 = 0.05;

/// A slider of 8 × 6 particles above a base of 30 × 6 (spacing [`SLIDER_DX`]), their facing
/// rows `gap` + 1 spacings apart.
pub(super) fn slider_and_base(gap: f64) -> (Vec<Vector<2>>, Vec<Vector<2>>) {
    let dx = SLIDER_DX;
    let base = lattice([30, 6], dx)
        .iter()
        .map(|x| x - Vector::<2>::new(0.75, 0.3))
        .collect();
    let slider = lattice([8, 6], dx)
        .iter()
        .map(|x| x + Vector::<2>::new(-0.2, gap * dx))
        .collect();
    (slider, base)
}

/// A 2D block (dx 0.05, 8 × 6) falling at speed `v_n` onto a wider, heavier block at rest
/// while sliding along it at `v_t`; the faces start 0.01 dx beyond the penalty range.
fn sliding_impact(friction: f64, v_t: f64, v_n: f64, end_time: f64) -> Model<2> {
    let dx = SLIDER_DX;
    let (slider, base) = slider_and_base(0.01);
    Model {
        config: config(Formulation::TotalLagrangianCorrected, end_time),
        materials: materials(),
        bodies: vec![
            body("slider", 0, slider, dx, Vector::<2>::new(v_t, -v_n)),
            body("base", 1, base, dx, Vector::<2>::zeros()),
        ],
        boundaries: vec![],
        effects: EffectsDescription {
            penalty_contact: penalty(friction),
            ..Default::default()
        },
    }
}

/// Momentum of body `b`.
fn body_momentum(sim: &Simulation<2>, b: usize) -> Vector<2> {
    sim.bodies()[b]
        .range
        .clone()
        .map(|i| sim.velocity(i) * sim.masses()[i])
        .sum()
}

/// Runs a model to its end, returning (slider momentum change, worst total-momentum error
/// relative to the slider's initial momentum, whether contact ended before the end).
fn impulse(model: Model<2>) -> (Vector<2>, f64, bool) {
    let mut sim = Simulation::new(model).unwrap();
    let p0 = body_momentum(&sim, 0);
    let total0 = sim.diagnostics().linear_momentum;
    let (mut worst, mut touched, mut released) = (0.0_f64, false, false);
    sim.run(|s, _| {
        worst = worst.max((s.diagnostics().linear_momentum - total0).norm() / p0.norm());
        let in_contact = s.diagnostics().effect_force("contact").norm() > 0.0;
        touched |= in_contact;
        released |= touched && !in_contact;
    })
    .unwrap();
    (body_momentum(&sim, 0) - p0, worst, released)
}

/// Slider mass: 8 × 6 particles of ρ dx² = 0.0025.
const SLIDER_MASS: f64 = 48.0 * 0.0025;

#[test]
fn a_sliding_impact_transfers_mu_times_the_normal_impulse() {
    // Coulomb: while the slider slides (v_t = 5 v_n keeps it sliding: the tangential impulse
    // μ·2mv_n at most is far below m v_t) each pair's friction force is μ times its normal
    // force, so friction adds μ times the normal impulse to the tangential one. The normal
    // forces alone leave a small tangential impulse of their own (the frictionless run below:
    // the lattice faces passing each other), which is subtracted; the rest is μ Δp_n to the
    // variation of the normal impulse between the runs (measured 0.2 % for both; 2 %).
    let (v_t, v_n) = (0.05, 0.01);
    let (baseline, ..) = impulse(sliding_impact(0.0, v_t, v_n, 4.0));
    for mu in [0.1, 0.3] {
        let (dp, momentum, released) = impulse(sliding_impact(mu, v_t, v_n, 4.0));
        let ratio = -(dp[0] - baseline[0]) / dp[1];
        eprintln!(
            "μ = {mu}: Δp = ({:.4e}, {:.4e}), frictionless Δp_t {:.3e}, friction impulse / normal impulse {ratio:.4}, momentum {momentum:.1e}",
            dp[0], dp[1], baseline[0]
        );
        assert!(released, "μ = {mu}: the slider never left the base");
        assert!(dp[1] > 0.0 && dp[0] < 0.0, "μ = {mu}: {dp:?}");
        assert!((ratio / mu - 1.0).abs() < 0.02, "μ = {mu}: ratio {ratio}");
        assert!(momentum < 1e-12, "μ = {mu}: momentum error {momentum:e}");
    }
}

#[test]
fn without_friction_a_sliding_impact_rebounds_without_gaining_energy_or_tangential_momentum() {
    // μ = 0: only normal forces. The slider rebounds: its normal impulse lies between m v_n
    // (perfectly inelastic) and 2 m v_n (elastic); more would be energy created by the
    // contact, as a zone that switches a pair's whole force on and off while faces slide past
    // each other does (the tapered zone weight prevents it). Face pairs push along ±y and the
    // slider's corners take the base's face normal, so the tangential impulse stays a small
    // fraction of the normal one (measured 0.2 %, bounded by 3 %).
    let (v_t, v_n) = (0.05, 0.01);
    let (dp, momentum, released) = impulse(sliding_impact(0.0, v_t, v_n, 4.0));
    eprintln!(
        "μ = 0: Δp = ({:.4e}, {:.4e}), restitution {:.3}",
        dp[0],
        dp[1],
        dp[1] / (SLIDER_MASS * v_n) - 1.0
    );
    assert!(released);
    assert!(
        dp[1] > SLIDER_MASS * v_n && dp[1] < 2.0 * SLIDER_MASS * v_n,
        "normal impulse {:e} vs m v_n = {:e}",
        dp[1],
        SLIDER_MASS * v_n
    );
    assert!(dp[0].abs() < 0.03 * dp[1], "{dp:?}");
    assert!(momentum < 1e-12, "momentum error {momentum:e}");
}

#[test]
fn a_block_bouncing_off_a_fixed_body_books_no_work_on_the_fixed_particles() {
    // The base held fixed (every particle prescribed v = 0): the contact's force on it is taken
    // by the support and does no work. Booking the kick a fixed particle's velocity never
    // keeps would add m|a|²Δt²/2 per pressed particle and step: 0.25 KE0 over this contact.
    // What remains is the leap-frog error of the stiff, impulsive penalty force, the same as
    // against a free base: measured 3.2e-2 KE0 (free base 2.8e-2); bound 5 %. The reported
    // resultant is the force on the slider: its time integral is the slider's momentum change
    // to 1.2e-3 (f^n times Δt^n instead of the kick ½(Δt^n + Δt^{n+1})); bound 1 %.
    let (v_t, v_n) = (0.0, 0.01);
    let mut model = sliding_impact(0.0, v_t, v_n, 4.0);
    let n_base = model.bodies[1].positions.len();
    model.boundaries.push(BoundaryDescription {
        name: "support".into(),
        body: 1,
        particles: (0..n_base).collect(),
        velocity: Vector::<2>::zeros(),
        components: [true, true],
        amplitude: None,
    });
    let mut sim = Simulation::new(model).unwrap();
    let p0 = body_momentum(&sim, 0);
    let d0 = sim.diagnostics();
    let (e0, ke0) = (d0.total_energy(), d0.kinetic);
    let (mut worst_energy, mut impulse, mut previous) = (0.0_f64, Vector::<2>::zeros(), 0.0);
    let mut touched = false;
    while !sim.finished() {
        sim.step().unwrap();
        let d = sim.diagnostics();
        let force = d.effect_force("contact");
        touched |= force.norm() > 0.0;
        impulse += Vector::<2>::new(force[0], force[1]) * (sim.time() - previous);
        previous = sim.time();
        worst_energy = worst_energy.max((d.total_energy() - e0).abs() / ke0);
    }
    let dp = body_momentum(&sim, 0) - p0;
    eprintln!("fixed base: energy error {worst_energy:.2e} KE0, Δp = {dp:?}, ∫F dt = {impulse:?}");
    assert!(touched, "the slider never reached the base");
    assert!(dp[1] > SLIDER_MASS * v_n, "no rebound: {dp:?}");
    assert!(worst_energy < 0.05, "energy error {worst_energy:e} KE0");
    assert!(
        (impulse[1] - dp[1]).abs() < 0.01 * dp[1],
        "∫F dt {impulse:?} vs Δp {dp:?}"
    );
}

#[test]
fn penalty_contact_results_do_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        super::on_threads(threads, || {
            let mut sim = Simulation::new(sliding_impact(0.3, 0.05, 0.01, 4.0)).unwrap();
            sim.run(|_, _| {}).unwrap();
            (0..sim.n_particles())
                .map(|i| (sim.displacements()[i], sim.velocity(i)))
                .collect::<Vec<_>>()
        })
    };
    let one = run(1);
    for threads in [2, 3] {
        assert_eq!(run(threads), one, "{threads} threads");
    }
}

#[test]
fn penalty_contact_setup_errors_name_the_field() {
    let field_of = |m: Model<2>| match Simulation::new(m) {
        Err(SetupError::InvalidConfig { field, .. }) => field,
        other => panic!("expected an invalid-config error, got {other:?}"),
    };
    let with = |edit: &dyn Fn(&mut PenaltyContactDescription)| {
        let mut m = sliding_impact(0.1, 0.0, 0.01, 1.0);
        edit(m.effects.penalty_contact.as_mut().unwrap());
        m
    };
    assert_eq!(
        field_of(with(&|c| c.stiffness = 0.0)),
        "penalty_contact.stiffness"
    );
    assert_eq!(
        field_of(with(&|c| c.range = f64::NAN)),
        "penalty_contact.range"
    );
    assert_eq!(
        field_of(with(&|c| c.friction.kinetic = -0.1)),
        "penalty_contact.friction"
    );
    assert_eq!(
        field_of(with(&|c| c.friction.static_coefficient = 0.05)),
        "penalty_contact.friction",
        "a static coefficient below the kinetic 0.1"
    );
    assert_eq!(
        field_of(with(&|c| c.friction.static_coefficient = f64::INFINITY)),
        "penalty_contact.friction"
    );
    assert_eq!(
        field_of(with(&|c| {
            c.friction.static_coefficient = 0.5;
            c.friction.decay = Some(-1.0);
        })),
        "penalty_contact.friction"
    );
    // Self-contact needs a total-Lagrangian formulation: with "updated-lagrangian" a body
    // already interacts with itself through the kernel.
    let mut updated = with(&|c| c.pairs = Some(vec![(0, 0)]));
    updated.config.formulation = Formulation::UpdatedLagrangian;
    assert_eq!(field_of(updated), "penalty_contact.pairs");
    assert_eq!(
        field_of(with(&|c| c.pairs = Some(vec![(0, 2)]))),
        "penalty_contact.pairs"
    );
    let mut both = sliding_impact(0.1, 0.0, 0.01, 1.0);
    both.effects.contact = Some(ContactDescription {
        scale: 0.2,
        exponent: 4.0,
        pairs: None,
    });
    assert_eq!(field_of(both), "penalty_contact");
}

/// An 8 × 6 block (spacing 1) set 0.02 dx above a 40 × 6 base of the unit material whose bottom
/// row is clamped, pressed onto it by a body force on the block only, `gravity`, raised over a
/// smooth ramp of 100 time units (about 17 wave transits of the block), in penalty contact with
/// friction `friction`; h = 1.5Δx, CFL 0.3.
pub(super) fn block_on_base(gravity: Vector<2>, friction: f64, end_time: f64) -> Model<2> {
    use tlsph_solver::{BodyForceDescription, RampShape, VelocityRamp};
    let dx = 1.0;
    let base = lattice([40, 6], dx);
    let block: Vec<Vector<2>> = lattice([8, 6], dx)
        .iter()
        .map(|x| x + Vector::<2>::new(16.0, 6.02))
        .collect();
    let clamped: Vec<usize> = (0..base.len()).filter(|&i| base[i][1] < dx).collect();
    let mut config = config(Formulation::TotalLagrangianCorrected, end_time);
    config.smoothing_factor = 1.5;
    config.cfl = 0.3;
    Model {
        config,
        materials: materials(),
        bodies: vec![
            body("base", 0, base, dx, Vector::<2>::zeros()),
            body("block", 0, block, dx, Vector::<2>::zeros()),
        ],
        boundaries: vec![BoundaryDescription {
            name: "clamp".into(),
            body: 0,
            particles: clamped,
            velocity: Vector::<2>::zeros(),
            components: [true, true],
            amplitude: None,
        }],
        effects: EffectsDescription {
            penalty_contact: penalty(friction),
            body_force: Some(BodyForceDescription {
                acceleration: gravity,
                bodies: Some(vec![1]),
                amplitude: Some(
                    VelocityRamp {
                        duration: 100.0,
                        shape: RampShape::Smooth,
                    }
                    .into(),
                ),
            }),
            ..Default::default()
        },
    }
}

#[test]
fn a_block_resting_on_a_deformable_base_stays_at_rest() {
    // The block of `block_on_base` under g = 0.001 (ρgH/E = 0.7 % strain at its foot). A
    // conservative contact stores a non-negative energy (the `contact` column is its booked
    // work, so it may dip below zero only by the time integration's error; measured 0) and
    // leaves the pair vibrating gently after the ramp (kinetic / internal energy measured
    // ≤ 0.14; bound 0.3). Normals taken from the current surface turn with the surface
    // particles' zig-zag motion, and the contact force, held to them, is not the gradient of
    // any potential: it fed that motion until a block particle inverted at t = 135 (step 408).
    // The reference normals carried by F (Nanson's relation) do not see that motion.
    let model = block_on_base(Vector::<2>::new(0.0, -0.001), 0.0, 300.0);
    let mut sim = Simulation::new(model).unwrap();
    let contact = |s: &Simulation<2>| {
        s.diagnostics()
            .effect_energies
            .iter()
            .find(|(name, _)| name == "contact")
            .unwrap()
            .1
    };
    let (mut lowest, mut stored, mut worst_ratio) = (0.0_f64, 0.0_f64, 0.0_f64);
    let result = sim.run(|s, r| {
        let d = s.diagnostics();
        lowest = lowest.min(contact(s));
        stored = stored.max(contact(s));
        if r.time > 150.0 {
            worst_ratio = worst_ratio.max(d.kinetic / d.internal);
        }
    });
    eprintln!(
        "contact energy in [{lowest:.3e}, {stored:.3e}], kinetic / internal after the ramp ≤ {worst_ratio:.3}"
    );
    result.unwrap();
    assert!(lowest > -1e-3 * stored, "contact column {lowest:e}");
    assert!(worst_ratio < 0.3, "kinetic / internal {worst_ratio}");
}

#[test]
fn friction_holds_a_block_below_the_friction_angle_and_lets_it_slide_above() {
    // The block of `block_on_base` on an incline: g = (0.0003, −0.001), tangential over normal
    // 0.3, with hourglass control (α = 1; without it the sliding block's bottom row zig-zags
    // and digs into the base, as TLSPH surfaces under shear do). Averages over the whole block,
    // from the end of the ramp's transient (t = 200) to t = 400:
    // - μ = 0.5 > 0.3: Coulomb holds. What moves is elastic shear and the block's rocking;
    //   the mean displacement grows by 0.015 dx (measured). Kinetic friction without a stick
    //   state, regularised about zero sliding speed (Fuller's law, the previous one here),
    //   let it creep 0.137 dx; bound 0.05.
    // - μ = 0.2 < 0.3: the block slides with a = g_t − μ|g_n| = 1.0e-4 (measured 3.4 % low,
    //   the regularised law alike: the stick state changes nothing while a pair slides);
    //   bound 5 %.
    let run = |friction: f64| on_incline(FrictionCoefficients::single(friction), 0.0);
    let creep = run(0.5).creep;
    let acceleration = run(0.2).acceleration();
    eprintln!("μ = 0.5: creep {creep:.4} dx; μ = 0.2: a = {acceleration:.4e} (Coulomb 1.0e-4)");
    assert!(creep.abs() < 0.05, "creep {creep}");
    assert!(
        (acceleration / 1.0e-4 - 1.0).abs() < 0.05,
        "acceleration {acceleration:e}"
    );
}

/// Mean motion along the slope of the block of `on_incline` from t0 (the first sample at or
/// after t = 200, the end of the ramp's transient) to the end (t = 400), averaged over its
/// particles.
struct SlopeMotion {
    /// Displacement from t0 to the end.
    creep: f64,
    /// Velocity at t0 and at the end.
    velocities: (f64, f64),
    /// Time from t0 to the end.
    span: f64,
}

impl SlopeMotion {
    /// Mean acceleration from t0 to the end.
    fn acceleration(&self) -> f64 {
        (self.velocities.1 - self.velocities.0) / self.span
    }
}

/// The block of `block_on_base` on the incline g = (0.0003, −0.001) (tangential over normal
/// 0.3) with hourglass control (α = 1; without it the sliding block's bottom row zig-zags and
/// digs into the base, as TLSPH surfaces under shear do), the friction `coefficients`,
/// launched down the slope at `launch`.
fn on_incline(coefficients: FrictionCoefficients, launch: f64) -> SlopeMotion {
    let mut model = block_on_base(Vector::<2>::new(0.0003, -0.001), 0.0, 400.0);
    model.effects.hourglass_control = Some(1.0);
    model.effects.penalty_contact.as_mut().unwrap().friction = coefficients;
    for v in &mut model.bodies[1].velocities {
        v[0] = launch;
    }
    let mut sim = Simulation::new(model).unwrap();
    let block = sim.bodies()[1].range.clone();
    let n = block.len() as f64;
    let mean = |s: &Simulation<2>| {
        block.clone().fold((0.0, 0.0), |(u, v), i| {
            (u + s.total_displacement(i)[0] / n, v + s.velocity(i)[0] / n)
        })
    };
    let mut at_200 = None;
    sim.run(|s, r| {
        if at_200.is_none() && r.time >= 200.0 {
            at_200 = Some((r.time, mean(s)));
        }
    })
    .unwrap();
    let (t0, (u0, v0)) = at_200.unwrap();
    let (u1, v1) = mean(&sim);
    SlopeMotion {
        creep: u1 - u0,
        velocities: (v0, v1),
        span: sim.time() - t0,
    }
}

#[test]
fn static_friction_holds_a_block_that_kinetic_friction_lets_slide() {
    // The incline of `on_incline`, tangential over normal 0.3, with μ_k = 0.2 < 0.3 < μ_s = 1:
    // - at rest the block holds (creep measured 0.015 dx, as with a single μ = 0.5; bound
    //   0.05 as there). With μ = 0.2 alone it slides (the test above);
    // - launched down the slope at 0.01 (1 % of c) it slides from the start and keeps
    //   sliding under the kinetic force: a = g_t − μ_k|g_n| = 1.0e-4 (measured 2.4 % low);
    //   bound 5 % as for the single-coefficient slide. A pair sticks again once the static
    //   force could stop it within one step, below a speed of μ_s a_n Δt (about 3e-3 here):
    //   launched at 0.002 the block stopped as the load came on.
    // The hold is decided pair by pair on local loads, and the ratio of tangential to normal
    // force peaks at the block's edges. With μ_s = 0.5, 0.6 and 0.7 the block at rest slid
    // (4.7, 4.0 and 2.9 dx over the window; measured): once an edge pair slips, the kinetic
    // coefficient takes over and the slip runs through the contact. μ_s = 0.8 held.
    let coefficients = FrictionCoefficients {
        kinetic: 0.2,
        static_coefficient: 1.0,
        decay: None,
    };
    let creep = on_incline(coefficients, 0.0).creep;
    let acceleration = on_incline(coefficients, 0.01).acceleration();
    eprintln!("μ_k = 0.2, μ_s = 1: creep at rest {creep:.4} dx; launched a = {acceleration:.4e} (Coulomb 1.0e-4)");
    assert!(creep.abs() < 0.05, "creep {creep}");
    assert!(
        (acceleration / 1.0e-4 - 1.0).abs() < 0.05,
        "acceleration {acceleration:e}"
    );
}

#[test]
fn with_a_friction_decay_a_sliding_block_feels_the_speed_dependent_coefficient() {
    // The incline of `on_incline` with μ_k = 0.2, μ_s = 0.5 and d_c = 100: a sliding block
    // feels μ(v) = μ_k + (μ_s − μ_k) exp(−d_c v), which equals the load ratio 0.3 at
    // v* = ln 3 / d_c = 0.011. Slower, friction exceeds the pull; faster, it falls short.
    // - At rest the block holds, where the same coefficients without decay let it slide
    //   (the test above): an edge pair that slips does so at about the elastodynamic speed
    //   (μ_s − μ_k) p / (ρc) ≈ 2e-3, where μ(v) is still 0.45. Creep measured 0.019 dx;
    //   bound 0.05 as for the hold above.
    // - Launched at 0.02 > v*, it keeps sliding, and its mean velocity follows the rigid
    //   block's v' = g_t − μ(v)|g_n| from the measured velocity at t0: the speed gained over
    //   the window matches to 1.4 % (measured); bound 5 %, as for the Coulomb slide.
    // Not asserted: launched at 0.005 < v* the block slowed (mean speed 1.5e-3 at t = 200,
    // 7e-4 at 400) but crept on by 0.29 dx over the window instead of stopping as a rigid
    // block would; with a coefficient that falls with speed, an elastic block's contact row
    // can stick and slip in turn.
    let coefficients = FrictionCoefficients {
        kinetic: 0.2,
        static_coefficient: 0.5,
        decay: Some(100.0),
    };
    let (g_t, g_n) = (0.0003, 0.001);
    let mu = |v: f64| 0.2 + 0.3 * (-100.0 * v).exp();
    let at_rest = on_incline(coefficients, 0.0);
    let fast = on_incline(coefficients, 0.02);
    // The rigid block from the measured velocity at t0 (RK4, 2000 steps).
    let (mut v, steps) = (fast.velocities.0, 2000);
    let dt = fast.span / steps as f64;
    let a = |v: f64| g_t - mu(v) * g_n;
    for _ in 0..steps {
        let k1 = a(v);
        let k2 = a(v + 0.5 * dt * k1);
        let k3 = a(v + 0.5 * dt * k2);
        let k4 = a(v + dt * k3);
        v += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    let gained = fast.velocities.1 - fast.velocities.0;
    let rigid = v - fast.velocities.0;
    eprintln!(
        "d_c = 100: creep at rest {:.4} dx; launched at 0.02: gained {gained:.4e} vs rigid block {rigid:.4e}",
        at_rest.creep
    );
    assert!(at_rest.creep.abs() < 0.05, "creep {}", at_rest.creep);
    assert!(
        fast.velocities.0 > 0.02,
        "the fast block slowed: {:?}",
        fast.velocities
    );
    assert!(
        (gained / rigid - 1.0).abs() < 0.05,
        "gained {gained:e} vs {rigid:e}"
    );
}
