//! R-P1: 1D stability test, symmetric impact of two elastic aluminium rods (Reveles §6.1.1,
//! Figs 6.1–6.2). The interface alternates between compression and tension with period 4L/c;
//! conventional (updated-Lagrangian) SPH clumps once the reflected wave puts the rods in
//! tension, TLSPH stays ordered.

use crate::report::{Curve, ProblemReport, ReportRow, RunCost, Series, Tier};
use crate::variants::{interpolate_at, model_1d, positions_1d};
use std::time::Instant;
use tlsph_solver::stability::{StabilityMonitor, StabilityThresholds};
use tlsph_solver::{ParticleField, Simulation};

/// Problem id.
pub const ID: &str = "R-P1";
/// Length of each rod \[m\] (problems.md `[C]`: 1000 particles of 0.02 m).
pub const ROD: f64 = 20.0;
/// Impact speed of each rod \[m/s\].
pub const SPEED: f64 = 10.0;
/// M-AL1: ρ 2700 kg/m³, E 70 GPa, ν 0.3.
pub const DENSITY: f64 = 2700.0;
/// Uniaxial-strain modulus M = E(1 − ν)/((1 + ν)(1 − 2ν)) of M-AL1 \[Pa\].
pub const MODULUS: f64 = 7.0e10 * 0.7 / (1.3 * 0.4);
/// Thesis spacing \[m\] (2000 particles, h = 0.024 m = 1.2Δx).
pub const THESIS_SPACING: f64 = 0.02;
/// Quick-tier spacing \[m\] (200 particles per rod).
pub const QUICK_SPACING: f64 = 0.1;
/// Simulated time: three periods 4L/c plus a margin \[s\].
pub const END_TIME: f64 = 3.05 * 4.0 * ROD / 5907.6;

/// c_M = sqrt(M/ρ) \[m/s\] (5907.6).
pub fn wave_speed() -> f64 {
    (MODULUS / DENSITY).sqrt()
}

/// Interface stress plateau ρ c v \[Pa\] (159.5 MPa).
pub fn plateau() -> f64 {
    DENSITY * wave_speed() * SPEED
}

/// Half period 2L/c: length of each compressive or tensile phase \[s\].
pub fn half_period() -> f64 {
    2.0 * ROD / wave_speed()
}

/// The formulations compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kernel {
    /// Total-Lagrangian, corrected gradients (Algorithm 3).
    TotalLagrangian,
    /// Conventional SPH with the kernel in the current configuration.
    UpdatedLagrangian,
}

impl Kernel {
    /// Scene name of the formulation.
    pub fn formulation(self) -> &'static str {
        match self {
            Kernel::TotalLagrangian => "total-lagrangian-corrected",
            Kernel::UpdatedLagrangian => "updated-lagrangian",
        }
    }

    /// Label for reports.
    pub fn label(self) -> &'static str {
        match self {
            Kernel::TotalLagrangian => "TLSPH",
            Kernel::UpdatedLagrangian => "conventional SPH",
        }
    }
}

/// Scene: the two rods as one body with the velocity jump at x = 0 (problems.md `[C]`).
pub fn scene(kernel: Kernel, spacing: f64) -> String {
    format!(
        r#"# R-P1 symmetric impact of two elastic aluminium rods (M-AL1)
[simulation]
dimension = 1
formulation = "{formulation}"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = {END_TIME:e}

[[material]]
name = "aluminium"
model = "linear-elastic"
density = {DENSITY:e}
youngs_modulus = 7.0e10
poisson_ratio = 0.3

[[body]]
name = "rods"
material = "aluminium"
spacing = {spacing:e}

[[body.shape]]
box = {{ min = [-{ROD:e}], max = [0.0] }}
velocity = [{SPEED:e}]

[[body.shape]]
box = {{ min = [0.0], max = [{ROD:e}] }}
velocity = [-{SPEED:e}]
"#,
        formulation = kernel.formulation()
    )
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct RodRun {
    /// Sample times \[s\].
    pub times: Vec<f64>,
    /// σ_xx at the interface (tension +) \[Pa\].
    pub interface_stress: Vec<f64>,
    /// The stability report (thresholds: |Δd/Δx| ≤ 1 %, problems.md R-P1 criterion 2).
    pub stability: StabilityMonitor,
    /// The step error that stopped the run, if any.
    pub breakdown: Option<String>,
    /// Cost.
    pub cost: RunCost,
}

/// Stability thresholds of R-P1: nearest neighbours within 1 % of Δx (about 6× the physical
/// strain 1.69e-3), the energy to 1 %.
pub fn thresholds() -> StabilityThresholds {
    StabilityThresholds {
        min_neighbour_ratio: 0.99,
        max_neighbour_ratio: 1.01,
        clumping_index: 0.01,
        energy_drift: 0.01,
    }
}

/// Runs one formulation at `spacing`, sampling the stability report 400 times.
pub fn simulate(kernel: Kernel, spacing: f64) -> RodRun {
    let model = model_1d(&scene(kernel, spacing), "R-P1 scene");
    let mut sim = Simulation::new(model).expect("R-P1 scene is valid");
    let x0 = positions_1d(&sim);
    let mut run = RodRun {
        times: Vec::new(),
        interface_stress: Vec::new(),
        stability: StabilityMonitor::new(thresholds()),
        breakdown: None,
        cost: RunCost::default(),
    };
    let interval = END_TIME / 400.0;
    let mut next_sample = 0.0;
    let start = Instant::now();
    while !sim.finished() {
        match sim.step() {
            Ok(_) => {}
            Err(e) => {
                run.stability
                    .observe_breakdown(sim.steps_done(), sim.time());
                run.breakdown = Some(e.to_string());
                break;
            }
        }
        run.times.push(sim.time());
        run.interface_stress.push(interpolate_at(
            &x0,
            |i| sim.sample(ParticleField::Stress(0, 0), i),
            0.0,
        ));
        if sim.time() >= next_sample || sim.finished() {
            run.stability.observe(&sim);
            next_sample += interval;
        }
    }
    run.cost = RunCost {
        particles: sim.n_particles(),
        steps: sim.steps_done() as usize,
        wall_s: start.elapsed().as_secs_f64(),
    };
    run
}

/// Per phase (the six compressive and tensile phases of three periods, central 80 % of
/// each, compression in even phases): (worst |mean σ·sign − ρcv|/ρcv, worst single-sample
/// deviation). The first is the plateau level; the second includes the ringing that an
/// inviscid discretisation of a velocity jump carries (Gibbs oscillation of the fronts that
/// reflect through the interface), reported but not the plateau criterion.
pub fn plateau_errors(run: &RodRun) -> (f64, f64) {
    let half = half_period();
    let target = plateau();
    let (mut worst_mean, mut worst_sample) = (0.0f64, 0.0f64);
    for phase in 0..6 {
        let sign = if phase % 2 == 0 { -1.0 } else { 1.0 };
        let (a, b) = ((phase as f64 + 0.1) * half, (phase as f64 + 0.9) * half);
        let window: Vec<f64> = run
            .times
            .iter()
            .zip(&run.interface_stress)
            .filter(|(t, _)| **t >= a && **t <= b)
            .map(|(_, s)| sign * s)
            .collect();
        if window.is_empty() {
            return (f64::INFINITY, f64::INFINITY);
        }
        let mean = window.iter().sum::<f64>() / window.len() as f64;
        worst_mean = worst_mean.max((mean - target).abs() / target);
        for s in &window {
            worst_sample = worst_sample.max((s - target).abs() / target);
        }
    }
    (worst_mean, worst_sample)
}

/// Runs TLSPH and conventional SPH (quick: 200 particles per rod; full: the thesis' 1000).
pub fn run(tier: Tier) -> ProblemReport {
    let spacing = match tier {
        Tier::Quick => QUICK_SPACING,
        Tier::Full => THESIS_SPACING,
    };
    let per_rod = (ROD / spacing).round() as usize;
    let mut report = ProblemReport::default();
    let tl = simulate(Kernel::TotalLagrangian, spacing);
    let ul = simulate(Kernel::UpdatedLagrangian, spacing);
    let tag = |k: Kernel| format!("{per_rod} particles/rod {}", k.label());

    let (plateau_error, ringing) = plateau_errors(&tl);
    report.rows.push(
        ReportRow::with_error(
            ID,
            &format!(
                "{}: worst phase-mean interface |stress| vs rho c v over 3 periods",
                tag(Kernel::TotalLagrangian)
            ),
            plateau_error,
            0.0,
            plateau_error,
            0.03,
        )
        .with_cost(tl.cost),
    );
    let (lo, hi, _, drift) = tl.stability.extremes();
    let distortion = (1.0 - lo).max(hi - 1.0);
    report.rows.push(
        ReportRow::with_error(
            ID,
            &format!(
                "{}: max |d/dx - 1| of nearest neighbours (no clumping)",
                tag(Kernel::TotalLagrangian)
            ),
            distortion,
            0.0,
            distortion,
            0.01,
        )
        .with_cost(tl.cost),
    );
    report.rows.push(
        ReportRow::with_error(
            ID,
            &format!("{}: max energy drift", tag(Kernel::TotalLagrangian)),
            drift,
            0.0,
            drift,
            0.01,
        )
        .with_cost(tl.cost),
    );
    // Conventional SPH must break criterion (2) in the first tensile phase (thesis: the
    // computation stops): "expected failure reproduced".
    let half = half_period();
    let crossing = ul.stability.first_crossing.clone();
    let crossing_time = crossing.as_ref().map_or(f64::INFINITY, |c| c.time);
    let outside = if crossing_time < half {
        (half - crossing_time) / half
    } else if crossing_time > 2.0 * half {
        (crossing_time - 2.0 * half) / half
    } else {
        0.0
    };
    report.rows.push(
        ReportRow::with_error(
            ID,
            &format!(
                "{}: first stability crossing [ms] in the first tensile phase (expected failure)",
                tag(Kernel::UpdatedLagrangian)
            ),
            crossing_time * 1e3,
            1.5 * half * 1e3,
            outside,
            0.0,
        )
        .with_cost(ul.cost),
    );
    report.notes.push(format!(
        "Plateau ρ c v = {:.1} MPa, half period 2L/c = {:.2} ms. TLSPH: worst phase-mean deviation {:.2} %, ringing about it up to {:.1} % (no artificial viscosity), nearest-neighbour ratio in [{lo:.5}, {hi:.5}], energy drift {drift:.1e}, {:.1} s. Conventional SPH: first crossing {} ; {}.",
        plateau() * 1e-6,
        half * 1e3,
        100.0 * plateau_error,
        100.0 * ringing,
        tl.cost.wall_s,
        crossing.as_ref().map_or("none".into(), |c| format!("{} = {:.4} at step {} (t = {:.3} ms)", c.quantity, c.value, c.step, c.time * 1e3)),
        ul.breakdown.as_deref().map_or("the run reached the end time".into(), |e| format!("the run stopped: {e}")),
    ));
    let suffix = if tier == Tier::Full { "full" } else { "quick" };
    let ms = |t: &f64| t * 1e3;
    report.curves.push(Curve {
        name: format!("r-p1-interface-stress-{suffix}"),
        title: "R-P1 interface stress (Figs 6.1–6.2)".into(),
        x_label: "time [ms]".into(),
        y_label: "stress σ_xx [Pa] (tension +)".into(),
        series: [
            (&tl, Kernel::TotalLagrangian),
            (&ul, Kernel::UpdatedLagrangian),
        ]
        .iter()
        .map(|(r, k)| Series {
            label: k.label().into(),
            points: r
                .times
                .iter()
                .map(ms)
                .zip(r.interface_stress.iter().copied())
                .collect(),
            is_reference: false,
        })
        .chain([Series {
            label: "analytic ±ρcv".into(),
            points: (0..=6)
                .flat_map(|k| {
                    let s = if k % 2 == 0 { -plateau() } else { plateau() };
                    [
                        (k as f64 * half * 1e3, s),
                        ((k as f64 + 1.0) * half * 1e3, s),
                    ]
                })
                .collect(),
            is_reference: true,
        }])
        .collect(),
    });
    report.curves.push(Curve {
        name: format!("r-p1-nearest-neighbour-{suffix}"),
        title: "R-P1 smallest nearest-neighbour distance / Δx".into(),
        x_label: "time [ms]".into(),
        y_label: "min d/Δx".into(),
        series: vec![
            Series::min_neighbour_ratio(Kernel::TotalLagrangian.label(), &tl.stability, 1e3),
            Series::min_neighbour_ratio(Kernel::UpdatedLagrangian.label(), &ul.stability, 1e3),
        ],
    });
    report
}
