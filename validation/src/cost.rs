//! Resolution sweeps: error against wall time for every formulation variant, so users can see
//! what accuracy costs (`cargo xtask cost`).

use crate::analytic::rod_vibration::K_LINEAR_PER_S;
use crate::problems::{r_p2, r_p4};
use crate::report::RunCost;
use crate::variants::{Variant, COST_VARIANTS};

/// One run of a sweep: a row of `cost.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct CostRow {
    /// Problem id.
    pub problem: String,
    /// Variant name.
    pub variant: String,
    /// Particle spacing.
    pub spacing: f64,
    /// Particles.
    pub particles: usize,
    /// Time steps.
    pub steps: usize,
    /// Wall time of the time loop \[s\].
    pub wall_s: f64,
    /// Particle-steps per second.
    pub particle_steps_per_s: f64,
    /// The problem's scalar error measure (see [`error_measure`]).
    pub error: f64,
}

/// Problems with an analytic (or converged) reference that the sweep covers.
pub const COST_PROBLEMS: [&str; 2] = [r_p2::ID, "R-P4s"];

/// What the `error` column means for each problem.
pub fn error_measure(problem: &str) -> &'static str {
    match problem {
        r_p2::ID => "L1 error of the X = 1.25 stress history against the exact finite-strain solution of the variant's own law, / (plateau × pulse duration)",
        _ => "max displacement error at x = 2, 3, 6 mm over 0–12.4 µs against the modal series, / B1",
    }
}

fn row(problem: &str, variant: &Variant, spacing: f64, cost: RunCost, error: f64) -> CostRow {
    CostRow {
        problem: problem.into(),
        variant: variant.name.into(),
        spacing,
        particles: cost.particles,
        steps: cost.steps,
        wall_s: cost.wall_s,
        particle_steps_per_s: cost.particle_steps_per_s(),
        error,
    }
}

/// Runs the sweep of one problem: four or more spacings × every variant. Calls `progress`
/// with a line of text before each run.
pub fn sweep(problem: &str, progress: &mut dyn FnMut(&str)) -> Option<Vec<CostRow>> {
    let mut rows = Vec::new();
    match problem {
        r_p2::ID => {
            for variant in &COST_VARIANTS {
                let reference = r_p2::finite_strain_reference(r_p2::law_of(variant), 8000);
                for spacing in [0.008, 0.004, 0.002, 0.001] {
                    progress(&format!("{problem} {} dx = {spacing}", variant.name));
                    let run = r_p2::simulate(variant, spacing);
                    let error = r_p2::history_error(&run, &reference);
                    rows.push(row(problem, variant, spacing, run.cost, error));
                }
            }
        }
        "R-P4s" => {
            for variant in &COST_VARIANTS {
                for n in [16, 31, 61, 121, 241] {
                    progress(&format!("{problem} {} {n} particles", variant.name));
                    let run = r_p4::simulate(variant, n, K_LINEAR_PER_S);
                    let series = r_p4::series_for(K_LINEAR_PER_S);
                    let error = r_p4::max_displacement_error(&run, &series);
                    rows.push(row(problem, variant, run.spacing, run.cost, error));
                }
            }
        }
        _ => return None,
    }
    Some(rows)
}
