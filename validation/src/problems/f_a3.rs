//! F-A3: linear momentum in colliding discs (Fuller §3.3.2, Figs 3.7–3.10, App. A.3). Disc A
//! (R = 12, 437 particles of mass 1) hits disc B at rest (437 particles of mass 0.1 … 0.6, so
//! M_A/M_B = 10 … 1.67) at U = 0.01c, 0.001c, 0.0001c. Thesis mode: updated-Lagrangian SPH,
//! the discs are different materials in one kernel group (`kernel_group = "discs"`), XSPH 0.5.
//! TL mode: the discs are separate TLSPH bodies (corrected gradients) that touch only through
//! Fuller's particle-type penalty contact (numerics.md §12.1, "F contact" of problems.md,
//! frictionless); the spec's pass criteria apply to it.

use super::fuller_scenes::{
    body_sums, gap, header, lattice_ring, parse, set_particles, sound_speed, thesis_effects,
    tl_penalty_effects, Mode, HOURGLASS, SMOOTHING,
};
use crate::report::{Curve, ProblemReport, ReportRow, RunCost, Series, Tier};
use std::time::Instant;
use tlsph_math::Vector;
use tlsph_solver::Simulation;

/// Problem id.
pub const ID: &str = "F-A3";
/// Disc radius \[Δx\] `[T]`.
pub const RADIUS: f64 = 12.0;
/// Particle masses of disc B `[T]` (= its density, `[C]` problems.md §4 #26).
pub const MASSES_B: [f64; 6] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
/// Incident speeds of disc A as fractions of c `[T]`.
pub const SPEEDS: [f64; 3] = [0.01, 0.001, 0.0001];
/// Smallest initial distance between particles of A and B (`[C]`: D_AB is not given).
/// Thesis mode: 2h, just outside the kernel support, so nothing interacts at t = 0; at
/// 0.0001c the approach through the support would take 2.6e4 τ (2e5 steps), so those runs
/// start at h, inside the support but stress-free (continuity density: only approach creates
/// pressure). TL mode: 1.3 d0, so that no pair starts inside a penalty zone (the lattice
/// disc's stepped faces have normals tilted by up to 29°, which at d0 put partners 13 % inside
/// the range R = d0: released at t = 0, that penetration kicked the discs with as much energy
/// as the impact itself).
pub fn initial_gap(mode: Mode, speed: f64) -> f64 {
    match mode {
        Mode::TotalLagrangian => 1.3,
        Mode::Thesis if speed < 0.001 => SMOOTHING,
        Mode::Thesis => 2.0 * SMOOTHING,
    }
}
/// Contact followed after the discs first come within 2h of each other, beyond the time to
/// close the initial gap to Δx \[τ\]: about 19 transits of a disc diameter at c (a rebound
/// takes a few); still together then = stuck.
pub const MAX_CONTACT: f64 = 500.0;
/// Free flight followed after the discs separate (out of reach, B faster than A) \[τ\].
pub const AFTER_SEPARATION: f64 = 5.0;
/// XSPH ε of A.3 `[T]`.
pub const XSPH: f64 = 0.5;

/// Elastic centre-of-mass velocities (V_A/U, V_B/U) for r = M_A/M_B `[A]`.
pub fn elastic(r: f64) -> (f64, f64) {
    ((r - 1.0) / (r + 1.0), 2.0 * r / (r + 1.0))
}

/// Scene: discs A (body 0) and B (body 1) at lattice spacing `spacing` \[Δx of the
/// thesis\] with placeholder shapes (replaced by the integer lattice); thesis mode puts them
/// in one kernel group, TL mode in contact with hourglass control.
pub fn scene(mode: Mode, mass_b: f64, end_time: f64, spacing: f64) -> String {
    let (formulation, effects) = match mode {
        Mode::Thesis => ("updated-lagrangian", thesis_effects(Some(XSPH), None)),
        Mode::TotalLagrangian => (
            "total-lagrangian-corrected",
            tl_penalty_effects(&[("A", "B")], 0.0),
        ),
    };
    let group = match mode {
        Mode::Thesis => "kernel_group = \"discs\"\n",
        Mode::TotalLagrangian => "",
    };
    header(
        formulation,
        end_time,
        &[("disc-a", 1.0), ("disc-b", mass_b)],
    ) + &format!(
        r#"
[[body]]
name = "A"
material = "disc-a"
{group}spacing = {spacing}
disc = {{ centre = [-20.0, 0.0], radius = 12.0 }}

[[body]]
name = "B"
material = "disc-b"
{group}spacing = {spacing}
disc = {{ centre = [20.0, 0.0], radius = 12.0 }}
"#
    ) + &effects
}

/// Result of one collision.
#[derive(Debug, Clone)]
pub struct Collision {
    /// How the discs interacted.
    pub mode: Mode,
    /// Lattice spacing \[Δx of the thesis\].
    pub spacing: f64,
    /// M_A/M_B.
    pub ratio: f64,
    /// U/c.
    pub speed: f64,
    /// Final V_A/U and V_B/U (centre of mass, x).
    pub velocities: (f64, f64),
    /// Whether the discs came apart (no pair within reach) before the contact limit.
    pub separated: bool,
    /// Contact duration \[τ\] (to the limit if they stayed together).
    pub contact_time: f64,
    /// Largest |P(t) − P0| / |P0| of the total linear momentum over the run.
    pub momentum_error: f64,
    /// Samples (time \[τ\], V_A/U, V_B/U).
    pub history: Vec<(f64, f64, f64)>,
    /// Cost.
    pub cost: RunCost,
}

/// Runs disc A at `speed`·c into disc B with particle mass `mass_b` on the thesis lattice.
pub fn simulate(mode: Mode, mass_b: f64, speed: f64) -> Collision {
    simulate_at(mode, mass_b, speed, 1.0)
}

/// As [`simulate`] on a lattice of spacing `spacing` (R/Δx = 12/spacing; the particle mass
/// is the density times Δx², so the disc masses stay those of the thesis).
pub fn simulate_at(mode: Mode, mass_b: f64, speed: f64, spacing: f64) -> Collision {
    let u = speed * sound_speed(1.0);
    let gap0 = initial_gap(mode, speed) * spacing;
    let limit = MAX_CONTACT + (gap0 - spacing) / u;
    let end_time = 2.0 * limit;
    let mut model = parse(&scene(mode, mass_b, end_time, spacing), "F-A3 scene");
    // A's rightmost particle at −gap0/2, B's leftmost at +gap0/2, rows aligned.
    let offset = RADIUS - spacing + 0.5 * gap0;
    let a = lattice_ring(Vector::<2>::new(-offset, 0.0), -1.0, RADIUS, spacing);
    let b = lattice_ring(Vector::<2>::new(offset, 0.0), -1.0, RADIUS, spacing);
    set_particles(&mut model, 0, a, |_| Vector::<2>::new(u, 0.0));
    set_particles(&mut model, 1, b, |_| Vector::<2>::zeros());
    let mut sim = Simulation::new(model).expect("F-A3 is valid");
    let start = Instant::now();
    let total = |sim: &Simulation<2>| body_sums(sim, 0).momentum + body_sums(sim, 1).momentum;
    let p0 = total(&sim);
    let reach = mode.reach() * spacing;
    let mut run = Collision {
        mode,
        spacing,
        ratio: 1.0 / mass_b,
        speed,
        velocities: (f64::NAN, f64::NAN),
        separated: false,
        contact_time: 0.0,
        momentum_error: 0.0,
        history: Vec::new(),
        cost: RunCost::default(),
    };
    let (mut touched, mut released) = (None::<f64>, None::<f64>);
    let mut next_sample = 0.0;
    // Thesis-mode contacts last hundreds of τ; TL-mode contacts tens, seen every step.
    let (sample_every, check_every) = match mode {
        Mode::Thesis => (limit / 200.0, 10),
        Mode::TotalLagrangian => (0.5, 1),
    };
    loop {
        sim.step().expect("F-A3 runs");
        let t = sim.time();
        if sim.steps_done() % check_every != 0 {
            continue;
        }
        let p = total(&sim);
        run.momentum_error = run.momentum_error.max((p - p0).norm() / p0.norm());
        // TL mode: a pair within d0 is exactly a non-zero contact force, a pass over the
        // particles instead of the all-pairs distance search the kernel reach needs.
        let in_reach = match mode {
            Mode::Thesis => gap(&sim, 0, 1) < reach,
            Mode::TotalLagrangian => sim.diagnostics().effect_force("contact").norm() > 0.0,
        };
        if touched.is_none() && in_reach {
            touched = Some(t);
        }
        if let Some(t0) = touched {
            let (va, vb) = (
                body_sums(&sim, 0).velocity()[0],
                body_sums(&sim, 1).velocity()[0],
            );
            if t >= next_sample {
                next_sample = t + sample_every;
                run.history.push((t - t0, va / u, vb / u));
            }
            // Apart = out of reach while B moves away from A; a touch again (a surface
            // particle bouncing back, the discs still closing) resets it.
            if in_reach {
                released = None;
            } else if released.is_none() && vb > va {
                released = Some(t);
            }
            if released.is_some_and(|t1| t >= t1 + AFTER_SEPARATION) || t >= t0 + limit {
                run.separated = released.is_some();
                run.contact_time = released.unwrap_or(t) - t0;
                break;
            }
        }
        if sim.finished() {
            break;
        }
    }
    let (va, vb) = (
        body_sums(&sim, 0).velocity()[0],
        body_sums(&sim, 1).velocity()[0],
    );
    run.velocities = (va / u, vb / u);
    run.cost = RunCost {
        particles: sim.n_particles(),
        steps: sim.steps_done() as usize,
        wall_s: start.elapsed().as_secs_f64(),
    };
    run
}

/// Thesis-mode cases (m_B, U/c). Quick: r = 10 and 2 at 0.01c; full: the six ratios at
/// 0.01c, r = 10 and 1.67 at 0.001c and r = 10 at 0.0001c (the sticking case): the slow
/// runs need 2e4–4e4 steps each, so the other ratios at the slow speeds are left out of the
/// full tier's budget. TL mode runs the whole sweep in both tiers (a collision takes a few
/// hundred steps at any speed: contact, not the approach through the kernel support).
pub fn thesis_cases(tier: Tier) -> Vec<(f64, f64)> {
    match tier {
        Tier::Quick => vec![(0.1, 0.01), (0.5, 0.01)],
        Tier::Full => MASSES_B
            .iter()
            .map(|&m| (m, SPEEDS[0]))
            .chain([(0.1, SPEEDS[1]), (0.6, SPEEDS[1]), (0.1, SPEEDS[2])])
            .collect(),
    }
}

/// Lattice spacings of the TL-mode resolution study (r = 10 and 1.67 at 0.01c, full tier).
pub const STUDY_SPACINGS: [f64; 2] = [1.0, 0.5];

/// Every case of the tier: thesis mode, the TL-mode sweep (six ratios × three speeds) and,
/// in the full tier, the TL-mode resolution study.
pub fn collisions(tier: Tier) -> Vec<Collision> {
    let mut runs: Vec<Collision> = thesis_cases(tier)
        .into_iter()
        .map(|(m, s)| simulate(Mode::Thesis, m, s))
        .collect();
    for &speed in &SPEEDS {
        for &m in &MASSES_B {
            runs.push(simulate(Mode::TotalLagrangian, m, speed));
        }
    }
    if tier == Tier::Full {
        for &m in &[MASSES_B[0], MASSES_B[5]] {
            for &dx in &STUDY_SPACINGS[1..] {
                runs.push(simulate_at(Mode::TotalLagrangian, m, SPEEDS[0], dx));
            }
        }
    }
    runs
}

/// Rows: momentum to round-off in every run; thesis mode's sticking at 0.0001c; TL mode's
/// rebound against the rigid-body formula (the spec's ±10 %, known to fail at the thesis
/// lattice for the large mass ratios: judged in the full tier) and its release at 0.0001c.
pub fn run(tier: Tier) -> ProblemReport {
    let runs = collisions(tier);
    let mut report = ProblemReport::default();
    for r in &runs {
        let tag = format!(
            "{}{}, r = {:.2}, U = {}c",
            r.mode.label(),
            if r.spacing == 1.0 {
                String::new()
            } else {
                format!(" R/dx = {}", RADIUS / r.spacing)
            },
            r.ratio,
            r.speed
        );
        // Pair terms of every force are equal and opposite: momentum to round-off.
        report.rows.push(
            ReportRow::with_error(
                ID,
                &format!("{tag}: max |P - P0| / |P0|"),
                r.momentum_error,
                0.0,
                r.momentum_error,
                1e-12,
            )
            .with_cost(r.cost),
        );
        let (ea, eb) = elastic(r.ratio);
        let release = r.velocities.1 - r.velocities.0;
        match r.mode {
            Mode::Thesis if r.speed < 0.001 && r.ratio > 9.0 => {
                // Thesis: the discs stick and tear at 0.0001c, r = 10. Stuck = moving
                // together: |V_B − V_A|/U below a tenth of its elastic value 1 (B starts at
                // rest, so this also needs the collision to have happened).
                report.rows.push(
                    ReportRow::with_error(
                        ID,
                        &format!("{tag}: |V_B - V_A|/U (thesis: stick, < 0.1)"),
                        release,
                        0.0,
                        (release.abs() - 0.1).max(0.0),
                        0.0,
                    )
                    .with_cost(r.cost),
                );
            }
            Mode::TotalLagrangian if r.spacing == 1.0 && r.speed >= 0.001 => {
                // The spec's ±10 % on V_B/U (vibration losses).
                report.push_full_tier_row(
                    tier,
                    ReportRow::relative(
                        ID,
                        &format!("{tag}: V_B/U (rigid-body elastic formula)"),
                        r.velocities.1,
                        eb,
                        0.1,
                    )
                    .with_cost(r.cost),
                );
            }
            Mode::TotalLagrangian if r.speed < 0.001 && r.ratio > 9.0 => {
                // The thesis' sticking case: with a contact instead of the kernel the discs
                // must come apart (restitution well above the thesis' ~0).
                report.rows.push(
                    ReportRow::with_error(
                        ID,
                        &format!("{tag}: (V_B - V_A)/U (contact, no sticking: > 0.5)"),
                        release,
                        0.5,
                        (0.5 - release).max(0.0),
                        0.0,
                    )
                    .with_cost(r.cost),
                );
            }
            _ => {}
        }
        report.notes.push(format!(
            "{tag}: V_A/U = {:.3} (rigid elastic {ea:.3}), V_B/U = {:.3} (rigid elastic {eb:.3}), restitution (V_B − V_A)/U = {release:.3}, {} after {:.1} τ of contact, momentum error {:.1e}, {} steps in {:.2} s ({:.2e} particle-steps/s).",
            r.velocities.0,
            r.velocities.1,
            if r.separated { "separated" } else { "still together" },
            r.contact_time,
            r.momentum_error,
            r.cost.steps,
            r.cost.wall_s,
            r.cost.particle_steps_per_s()
        ));
    }
    let study: Vec<String> = runs
        .iter()
        .filter(|r| r.mode == Mode::TotalLagrangian && r.speed == SPEEDS[0])
        .filter(|r| r.ratio > 9.0 || r.ratio < 1.7)
        .map(|r| {
            format!(
                "r = {:.2}, R/Δx = {}: V_B/U = {:.3}",
                r.ratio,
                RADIUS / r.spacing,
                r.velocities.1
            )
        })
        .collect();
    report.notes.push(format!(
        "TL mode against the rigid-body formula: the formula assumes a contact much longer than a wave transit of the discs; here it lasts 40–70 τ against 2R/c_A = 20.7 τ, so a few per cent of the kinetic energy stays in elastic vibration and V_B/U comes out a few per cent low. For r = 10 the rigid formula leaves almost no margin: losing 9.1 % of the energy already makes the collision perfectly inelastic (V_B = V_A), so V_B/U is the most sensitive quantity of the sweep. Resolution study ({}). With Fuller's penalty contact (the spec's \"F contact\") the ±10 % band holds; with the frictionless potential law of numerics.md §12.2 (this harness' choice until it had the penalty law) V_B/U was 11–19 % low for r ≥ 3.33. Momentum, the quantity F-A3 is about, is conserved to round-off in every run, and V/U barely depends on U, which the three speeds confirm.",
        study.join("; ")
    ));
    report.notes.push(
        "Thesis mode (updated-Lagrangian, kernel interaction across the discs through a shared kernel group) is strongly inelastic: across the interface the XSPH average (ε = 0.5) mixes the velocities of A and B particles, the α = 1 viscosity acts on every approaching pair, and on rebound the kernel's tensile 'stickiness' (F §3.6 iv) holds the discs back; the thesis reports a close match (Fig 3.9) with an unknown gap and time step. Its V/U are in the notes only; the spec's pass criteria are for TL mode.".into(),
    );
    report.notes.push(format!(
        "Set-up choices `[C]`: thesis mode — discs start with their nearest particles 2h = 3Δx apart (no interaction at t = 0; D_AB not given), h at 0.0001c; artificial stress (ε 0.3, n 6) and viscosity α = 1, β = 2 on both discs. TL mode — nearest particles 1.3Δx apart (no pair inside a contact zone at t = 0), Fuller's penalty contact (`law = \"penalty\"`: k_c = E Δx, R = Δx, μ = 0), hourglass control α = {HOURGLASS}, no viscosity, no XSPH. Both: ρ_B = m_B/Δx²; V = centre-of-mass velocity {AFTER_SEPARATION} τ after the discs came out of reach (2h, or no contact force in TL mode) with B moving away from A, or after {MAX_CONTACT} τ plus the time to close the initial gap to Δx if they never did."
    ));
    let suffix = if tier == Tier::Full { "full" } else { "quick" };
    for mode in [Mode::Thesis, Mode::TotalLagrangian] {
        report.curves.push(Curve {
            name: format!(
                "f-a3-velocities-{}-{suffix}",
                if mode == Mode::Thesis { "thesis" } else { "tl" }
            ),
            title: format!(
                "F-A3 {}: centre-of-mass velocities / U from first contact (Fig 3.8b)",
                mode.label()
            ),
            x_label: "time since the discs came within reach [τ]".into(),
            y_label: "V / U".into(),
            series: runs
                .iter()
                .filter(|r| r.mode == mode && r.spacing == 1.0 && r.speed == SPEEDS[0])
                .flat_map(|r| {
                    let tag = format!("r {:.2}, {}c", r.ratio, r.speed);
                    [
                        Series {
                            label: format!("A, {tag}"),
                            points: r.history.iter().map(|h| (h.0, h.1)).collect(),
                            is_reference: false,
                        },
                        Series {
                            label: format!("B, {tag}"),
                            points: r.history.iter().map(|h| (h.0, h.2)).collect(),
                            is_reference: false,
                        },
                    ]
                })
                .collect(),
        });
    }
    report
}
