//! The `tlsph` command. Parses arguments, runs a scene through `tlsph-io`, shows progress and
//! maps outcomes to exit codes: 0 finished, 1 the run stopped early or output failed,
//! 2 the scene was rejected (nothing written).

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};
use tlsph_io::{
    load_scene, load_scene_without_field_tables, run_scene_to_dir, write_csv, RunError,
};

#[derive(Parser)]
#[command(
    name = "tlsph",
    version,
    about = "Total-Lagrangian SPH for solids under dynamic loading"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene and write its run folder (probes/*.csv, energy.csv, momentum.csv, summary.toml).
    Run {
        /// Scene file (TOML, see docs/scene-format.md).
        scene: PathBuf,
        /// Output folder; overrides `[output] dir` of the scene.
        #[arg(long, short)]
        output: Option<PathBuf>,
        /// No set-up notes, no progress bar and no summary line.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Check a scene file without running it.
    Check {
        /// Scene file.
        scene: PathBuf,
    },
    /// Write a body's reference particle positions as CSV (header `x,y,z`, the first D of them;
    /// one row per particle), the template of an `initial_stress_file` or
    /// `initial_velocity_file` table (the scene's own tables are not read: they need not exist).
    Particles {
        /// Scene file.
        scene: PathBuf,
        /// Name of the body.
        body: String,
        /// CSV file to write (through a temporary file and a rename).
        output: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Check { scene } => match load_scene(&scene) {
            Ok(s) => {
                let probes = s.probes.len();
                println!(
                    "{}: {}D scene with {} particles, {probes} probe{}, end time {}",
                    scene.display(),
                    s.dimension(),
                    s.n_particles(),
                    if probes == 1 { "" } else { "s" },
                    s.end_time()
                );
                println!("{}", s.overview());
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Run {
            scene,
            output,
            quiet,
        } => run(scene, output, quiet),
        Command::Particles {
            scene,
            body,
            output,
        } => particles(scene, &body, output),
    }
}

fn particles(path: PathBuf, body: &str, output: PathBuf) -> ExitCode {
    // The template is written before its table exists, so the scene's tables are not read.
    let scene = match load_scene_without_field_tables(&path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let Some(rows) = scene.body_positions(body) else {
        eprintln!(
            "error: {}: no body named `{body}`; the bodies are {}",
            path.display(),
            scene
                .body_names()
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        return ExitCode::from(2);
    };
    let header: Vec<String> = ["x", "y", "z"][..scene.dimension()]
        .iter()
        .map(|c| c.to_string())
        .collect();
    let n = rows.len();
    match write_csv(&output, &header, rows) {
        Ok(()) => {
            println!("{n} particles of body `{body}` -> {}", output.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

fn run(path: PathBuf, output: Option<PathBuf>, quiet: bool) -> ExitCode {
    let scene = match load_scene(&path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if !quiet {
        for note in scene.overview().notes {
            eprintln!("note: {note}");
        }
    }
    let dir = output.unwrap_or_else(|| scene.output.dir.clone());
    let mut progress = LazyProgress::new(quiet);
    let result = run_scene_to_dir(&scene, &dir, &mut |t, end| progress.update(t, end));
    progress.finish();
    match result {
        Ok(record) => {
            if let Some(failure) = &record.failure {
                eprintln!("error: the run stopped early: {failure}");
                eprintln!("everything recorded until then is in {}", dir.display());
                return ExitCode::from(1);
            }
            if !quiet {
                println!(
                    "{} steps, {} particles, {:.2} s, {:.3e} particle-steps/s -> {}",
                    record.steps,
                    record.particles,
                    record.wall_s,
                    record.particle_steps_per_s(),
                    dir.display()
                );
            }
            ExitCode::SUCCESS
        }
        Err(RunError::Setup(e)) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

/// Seconds still to go for a run that took `elapsed` seconds to reach the fraction `fraction`
/// of its end time, at its average pace so far; `None` before any progress.
fn time_to_go(elapsed: f64, fraction: f64) -> Option<u64> {
    (fraction > 0.0 && elapsed.is_finite())
        .then(|| (elapsed * (1.0 - fraction) / fraction).round() as u64)
}

/// `h:mm:ss`, or `m:ss` under an hour.
fn format_duration(seconds: u64) -> String {
    let (h, m, s) = (seconds / 3600, seconds / 60 % 60, seconds % 60);
    if h > 0 {
        format!("{h}:{m:02}:{s:02}")
    } else {
        format!("{m}:{s:02}")
    }
}

/// A progress bar that appears only on a terminal and only once a run has taken a second.
/// Its time to go is the run's own average: elapsed × (1 − f)/f at the fraction f of the end
/// time reached (a bar that starts at f > 0 would give a rate estimator a jump in zero time
/// and show an ETA near zero at first).
struct LazyProgress {
    enabled: bool,
    start: Instant,
    bar: Option<ProgressBar>,
    /// Last time to go shown \[s\] (the message is rewritten only when it changes).
    shown_eta: Option<u64>,
}

/// Resolution of the bar: per-mille of the end time.
const BAR_STEPS: u64 = 1000;

impl LazyProgress {
    fn new(quiet: bool) -> Self {
        Self {
            enabled: !quiet && std::io::stderr().is_terminal(),
            start: Instant::now(),
            bar: None,
            shown_eta: None,
        }
    }

    fn update(&mut self, t: f64, end: f64) {
        if !self.enabled {
            return;
        }
        if self.bar.is_none() && self.start.elapsed() > Duration::from_secs(1) {
            let bar = ProgressBar::with_draw_target(Some(BAR_STEPS), ProgressDrawTarget::stderr())
                .with_elapsed(self.start.elapsed())
                .with_message("?");
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {wide_bar} {percent}% (eta {msg})",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            let fraction = (t / end).clamp(0.0, 1.0);
            bar.set_position((fraction * BAR_STEPS as f64) as u64);
            let eta = time_to_go(self.start.elapsed().as_secs_f64(), fraction);
            if eta != self.shown_eta {
                self.shown_eta = eta;
                bar.set_message(eta.map_or_else(|| "?".to_string(), format_duration));
            }
        }
    }

    fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{format_duration, time_to_go};

    #[test]
    fn the_time_to_go_is_the_average_pace_so_far() {
        // 2 s for the first 5 %: 38 s for the other 95 %.
        assert_eq!(time_to_go(2.0, 0.05), Some(38));
        assert_eq!(time_to_go(10.0, 1.0), Some(0));
        assert_eq!(time_to_go(1.0, 0.0), None);
        assert_eq!(format_duration(38), "0:38");
        assert_eq!(format_duration(3 * 3600 + 5 * 60 + 7), "3:05:07");
    }
}
