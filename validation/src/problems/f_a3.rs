//! F-A3: linear momentum in colliding discs (Fuller §3.3.2, Figs 3.7–3.10, App. A.3). Disc A
//! (R = 12, 437 particles of mass 1) hits disc B at rest (437 particles of mass 0.1 … 0.6, so
//! M_A/M_B = 10 … 1.67) at U = 0.01c, 0.001c, 0.0001c. Thesis mode: updated-Lagrangian SPH,
//! the discs are different materials in one kernel group (`kernel_group = "discs"`), XSPH 0.5.
//! TL mode needs a contact model between bodies, which does not exist yet.

use super::fuller_scenes::{
    body_sums, gap, header, integer_ring, parse, set_particles, sound_speed, thesis_effects,
    SMOOTHING,
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
/// Smallest initial distance between particles of A and B (`[C]`: D_AB is not given): 2h,
/// just outside the kernel support, so nothing interacts at t = 0; at 0.0001c the approach
/// through the support would take 2.6e4 τ (2e5 steps), so those runs start at h, inside the
/// support but stress-free (continuity density: only approach creates pressure).
pub fn initial_gap(speed: f64) -> f64 {
    if speed < 0.001 {
        SMOOTHING
    } else {
        2.0 * SMOOTHING
    }
}
/// Contact followed after the discs first come within 2h of each other, beyond the time to
/// close the initial gap to Δx \[τ\]: about 19 transits of a disc diameter at c (a rebound
/// takes a few); still together then = stuck.
pub const MAX_CONTACT: f64 = 500.0;
/// Free flight followed after the discs separate \[τ\].
pub const AFTER_SEPARATION: f64 = 5.0;
/// XSPH ε of A.3 `[T]`.
pub const XSPH: f64 = 0.5;

/// Elastic centre-of-mass velocities (V_A/U, V_B/U) for r = M_A/M_B `[A]`.
pub fn elastic(r: f64) -> (f64, f64) {
    ((r - 1.0) / (r + 1.0), 2.0 * r / (r + 1.0))
}

/// Scene: discs A (body 0) and B (body 1) with placeholder shapes (replaced by the integer
/// lattice), one kernel group.
pub fn scene(mass_b: f64, end_time: f64) -> String {
    header(
        "updated-lagrangian",
        end_time,
        &[("disc-a", 1.0), ("disc-b", mass_b)],
    ) + r#"
[[body]]
name = "A"
material = "disc-a"
kernel_group = "discs"
spacing = 1.0
disc = { centre = [-20.0, 0.0], radius = 12.0 }

[[body]]
name = "B"
material = "disc-b"
kernel_group = "discs"
spacing = 1.0
disc = { centre = [20.0, 0.0], radius = 12.0 }
"# + &thesis_effects(Some(XSPH), None)
}

/// Result of one collision.
#[derive(Debug, Clone, Default)]
pub struct Collision {
    /// M_A/M_B.
    pub ratio: f64,
    /// U/c.
    pub speed: f64,
    /// Final V_A/U and V_B/U (centre of mass, x).
    pub velocities: (f64, f64),
    /// Whether the discs came apart (no pair within 2h) before the contact limit.
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

/// Runs disc A at `speed`·c into disc B with particle mass `mass_b`.
pub fn simulate(mass_b: f64, speed: f64) -> Collision {
    let u = speed * sound_speed(1.0);
    let gap0 = initial_gap(speed);
    let limit = MAX_CONTACT + (gap0 - 1.0) / u;
    let end_time = 2.0 * limit;
    let mut model = parse(&scene(mass_b, end_time), "F-A3 scene");
    // A's rightmost particle at −INITIAL_GAP/2, B's leftmost at +INITIAL_GAP/2, rows aligned.
    let offset = RADIUS - 1.0 + 0.5 * gap0;
    let a = integer_ring(Vector::<2>::new(-offset, 0.0), -1.0, RADIUS);
    let b = integer_ring(Vector::<2>::new(offset, 0.0), -1.0, RADIUS);
    set_particles(&mut model, 0, a, |_| Vector::<2>::new(u, 0.0));
    set_particles(&mut model, 1, b, |_| Vector::<2>::zeros());
    let mut sim = Simulation::new(model).expect("F-A3 is valid");
    let start = Instant::now();
    let total = |sim: &Simulation<2>| body_sums(sim, 0).momentum + body_sums(sim, 1).momentum;
    let p0 = total(&sim);
    let support = 2.0 * SMOOTHING;
    let mut run = Collision {
        ratio: 1.0 / mass_b,
        speed,
        ..Collision::default()
    };
    let (mut touched, mut released) = (None::<f64>, None::<f64>);
    let mut next_sample = 0.0;
    let sample_every = limit / 200.0;
    loop {
        sim.step().expect("F-A3 runs");
        let t = sim.time();
        if sim.steps_done() % 10 != 0 {
            continue;
        }
        let p = total(&sim);
        run.momentum_error = run.momentum_error.max((p - p0).norm() / p0.norm());
        let d = gap(&sim, 0, 1);
        if touched.is_none() && d < support {
            touched = Some(t);
        }
        if let Some(t0) = touched {
            if t >= next_sample {
                next_sample = t + sample_every;
                let (va, vb) = (
                    body_sums(&sim, 0).velocity()[0],
                    body_sums(&sim, 1).velocity()[0],
                );
                run.history.push((t - t0, va / u, vb / u));
            }
            if released.is_none() && d >= support {
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

/// Quick: r = 10 and 2 at 0.01c; full: the six ratios at 0.01c, r = 10 and 1.67 at 0.001c
/// and r = 10 at 0.0001c (the sticking case). The slow runs need 2e4–4e4 steps each, so the
/// other ratios at the slow speeds are left out of the 2-minute budget.
pub fn run(tier: Tier) -> ProblemReport {
    let cases: Vec<(f64, f64)> = match tier {
        Tier::Quick => vec![(0.1, 0.01), (0.5, 0.01)],
        Tier::Full => MASSES_B
            .iter()
            .map(|&m| (m, SPEEDS[0]))
            .chain([(0.1, SPEEDS[1]), (0.6, SPEEDS[1]), (0.1, SPEEDS[2])])
            .collect(),
    };
    let runs: Vec<Collision> = cases.iter().map(|&(m, s)| simulate(m, s)).collect();
    let mut report = ProblemReport::default();
    for r in &runs {
        let tag = format!("r = {:.2}, U = {}c", r.ratio, r.speed);
        // Pair terms of every force are equal and opposite: momentum to round-off.
        report.rows.push(
            ReportRow::with_error(
                ID,
                &format!("thesis mode, {tag}: max |P - P0| / |P0|"),
                r.momentum_error,
                0.0,
                r.momentum_error,
                1e-12,
            )
            .with_cost(r.cost),
        );
        let (ea, eb) = elastic(r.ratio);
        if r.speed >= 0.001 {
            // The spec's ±10 % on V_B/U (vibration losses), applied to thesis mode.
            report.rows.push(
                ReportRow::relative(
                    ID,
                    &format!("thesis mode, {tag}: V_B/U (elastic formula)"),
                    r.velocities.1,
                    eb,
                    0.1,
                )
                .with_cost(r.cost),
            );
        }
        if r.speed < 0.001 && r.ratio > 9.0 {
            // Thesis: the discs stick and tear at 0.0001c, r = 10. Stuck = moving together:
            // |V_B − V_A|/U below a tenth of its elastic value 1 (B starts at rest, so this
            // also needs the collision to have happened).
            let separation = r.velocities.1 - r.velocities.0;
            report.rows.push(
                ReportRow::with_error(
                    ID,
                    &format!("thesis mode, {tag}: |V_B - V_A|/U (thesis: stick, < 0.1)"),
                    separation,
                    0.0,
                    (separation.abs() - 0.1).max(0.0),
                    0.0,
                )
                .with_cost(r.cost),
            );
        }
        report.notes.push(format!(
            "{tag}: V_A/U = {:.3} (elastic {ea:.3}), V_B/U = {:.3} (elastic {eb:.3}), {} after {:.0} τ of contact, momentum error {:.1e}, {} steps in {:.1} s.",
            r.velocities.0,
            r.velocities.1,
            if r.separated { "separated" } else { "still together" },
            r.contact_time,
            r.momentum_error,
            r.cost.steps,
            r.cost.wall_s
        ));
    }
    report.notes.push(
        "TL mode (the spec's pass criteria: discs as separate TLSPH bodies with Fuller's particle-type contact, N§12.1) is not run: there is no contact model between bodies yet, and TLSPH bodies never interact through the kernel. The rows above are thesis mode (updated-Lagrangian, kernel interaction across the discs through a shared kernel group), with the spec's TL tolerances applied for comparison.".into(),
    );
    report.notes.push(
        "The V_B/U rows fail: kernel contact in thesis mode is strongly inelastic here (V_B about 0.6–0.65 of the elastic value at 0.01c, less at 0.001c). Across the interface the XSPH average (ε = 0.5) mixes the velocities of A and B particles, the α = 1 viscosity acts on every approaching pair, and on rebound the kernel's tensile 'stickiness' (F §3.6 iv) holds the discs back; the thesis reports a close match (Fig 3.9) with an unknown gap and time step. Momentum, the quantity F-A3 is about, is conserved to round-off in every run, and the 0.0001c, r = 10 discs stick as in the thesis (both move at the common centre-of-mass velocity r/(r + 1) U = 0.909 U).".into(),
    );
    report.notes.push(format!(
        "Set-up choices `[C]`: discs start with their nearest particles 2h = 3Δx apart (no interaction at t = 0; D_AB not given), h at 0.0001c; ρ_B = m_B/Δx²; artificial stress (ε 0.3, n 6) and viscosity α = 1, β = 2 on both discs; V = centre-of-mass velocity {AFTER_SEPARATION} τ after the last pair left the kernel support, or after {MAX_CONTACT} τ plus the time to close the initial gap to Δx if they never did."
    ));
    let suffix = if tier == Tier::Full { "full" } else { "quick" };
    report.curves.push(Curve {
        name: format!("f-a3-velocities-{suffix}"),
        title: "F-A3 centre-of-mass velocities / U from first contact (Fig 3.8b)".into(),
        x_label: "time since the discs came within 2h [τ]".into(),
        y_label: "V / U".into(),
        series: runs
            .iter()
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
    report
}
