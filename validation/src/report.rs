//! Report rows and curves that every validation problem returns. No simulation code here.

use std::path::PathBuf;

/// How much work a validation run may do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Tier {
    /// Seconds per problem; used in CI.
    Quick,
    /// The thesis resolution.
    Full,
}

/// One compared quantity: a row of `summary.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportRow {
    /// Problem id, e.g. `R-P2`.
    pub problem: String,
    /// What was measured, e.g. `stress plateau` (include units where they are not the problem's own).
    pub quantity: String,
    /// Value from the simulation (or computation under test).
    pub measured: f64,
    /// Reference value.
    pub reference: f64,
    /// Error measure actually compared with `tolerance` (relative unless the quantity says otherwise).
    pub error: f64,
    /// Largest acceptable `error`.
    pub tolerance: f64,
    /// `error <= tolerance` (NaN fails).
    pub pass: bool,
    /// Wall time of the run that produced the value \[s\].
    pub wall_s: f64,
    /// Particle-steps per second of that run (0 when no particle simulation was involved).
    pub particle_steps_per_s: f64,
}

impl ReportRow {
    /// A row whose error is |measured − reference| / |reference|.
    pub fn relative(
        problem: &str,
        quantity: &str,
        measured: f64,
        reference: f64,
        tolerance: f64,
    ) -> Self {
        let error = ((measured - reference) / reference).abs();
        Self::with_error(problem, quantity, measured, reference, error, tolerance)
    }

    /// A row whose error is |measured − reference|.
    pub fn absolute(
        problem: &str,
        quantity: &str,
        measured: f64,
        reference: f64,
        tolerance: f64,
    ) -> Self {
        let error = (measured - reference).abs();
        Self::with_error(problem, quantity, measured, reference, error, tolerance)
    }

    /// A row with an error computed by the caller.
    pub fn with_error(
        problem: &str,
        quantity: &str,
        measured: f64,
        reference: f64,
        error: f64,
        tolerance: f64,
    ) -> Self {
        Self {
            problem: problem.to_string(),
            quantity: quantity.to_string(),
            measured,
            reference,
            error,
            tolerance,
            pass: error <= tolerance,
            wall_s: 0.0,
            particle_steps_per_s: 0.0,
        }
    }

    /// Attaches the cost of the run that produced this row.
    pub fn with_cost(mut self, cost: RunCost) -> Self {
        self.wall_s = cost.wall_s;
        self.particle_steps_per_s = cost.particle_steps_per_s();
        self
    }
}

/// Cost of one simulation run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RunCost {
    /// Number of particles.
    pub particles: usize,
    /// Number of time steps.
    pub steps: usize,
    /// Wall time \[s\].
    pub wall_s: f64,
}

impl RunCost {
    /// Particle-steps per second.
    pub fn particle_steps_per_s(&self) -> f64 {
        if self.wall_s > 0.0 {
            (self.particles * self.steps) as f64 / self.wall_s
        } else {
            0.0
        }
    }
}

/// A named (x, y) data series.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points in x order.
    pub points: Vec<(f64, f64)>,
    /// True for reference data (drawn dashed / as markers).
    pub is_reference: bool,
}

/// A plot-ready figure: simulation series against reference series.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// File stem, e.g. `r-p2-target-stress`.
    pub name: String,
    /// Title.
    pub title: String,
    /// X axis label with unit.
    pub x_label: String,
    /// Y axis label with unit.
    pub y_label: String,
    /// Series to draw.
    pub series: Vec<Series>,
}

/// Everything one problem returns.
#[derive(Debug, Clone, Default)]
pub struct ProblemReport {
    /// Compared quantities.
    pub rows: Vec<ReportRow>,
    /// Curves to write as CSV and PNG.
    pub curves: Vec<Curve>,
    /// Free-text notes (choices, explained mismatches) for the validation report.
    pub notes: Vec<String>,
    /// Particle maps (file stem, figure) to render as PNG.
    pub maps: Vec<(String, tlsph_io::particle_map::ParticleMapSpec)>,
}

impl ProblemReport {
    /// Adds a row whose criterion is stated for the thesis resolution and is known to fail
    /// there (an explained deviation): a pass/fail row in the full tier, and in the quick tier
    /// (CI, coarser lattices) a note with the measured value, so CI tracks regressions of what
    /// passes while the full tier keeps the deviation visible.
    pub fn push_full_tier_row(&mut self, tier: Tier, row: ReportRow) {
        match tier {
            Tier::Full => self.rows.push(row),
            Tier::Quick => self.notes.push(format!(
                "Judged in the full tier only (known deviation at the thesis resolution): {} = {:.4e} (reference {:.4e}, error {:.3e}, tolerance {:.3e}{}).",
                row.quantity,
                row.measured,
                row.reference,
                row.error,
                row.tolerance,
                if row.pass { ", within tolerance here" } else { ", outside here too" }
            )),
        }
    }
}

impl Series {
    /// The smallest nearest-neighbour ratio of a stability report against time (times scaled
    /// by `time_scale`, e.g. 1e3 for milliseconds).
    pub fn min_neighbour_ratio(
        label: &str,
        monitor: &tlsph_solver::stability::StabilityMonitor,
        time_scale: f64,
    ) -> Self {
        Self {
            label: label.into(),
            points: monitor
                .samples
                .iter()
                .map(|s| (s.time * time_scale, s.distances.min_ratio))
                .collect(),
            is_reference: false,
        }
    }
}

/// Root of the `reference-data/` folder of this workspace.
pub fn reference_data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("reference-data")
}
