//! The `tlsph` command. Parses arguments, runs a scene through `tlsph-io`, shows progress and
//! maps outcomes to exit codes: 0 finished, 1 the run stopped early or output failed,
//! 2 the scene was rejected (nothing written).

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};
use tlsph_io::{load_scene, run_scene_to_dir, RunError};

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
        /// No progress bar and no summary line.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Check a scene file without running it.
    Check {
        /// Scene file.
        scene: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Check { scene } => match load_scene(&scene) {
            Ok(s) => {
                println!(
                    "{}: {}D scene with {} particles, {} probes, end time {}",
                    scene.display(),
                    s.dimension(),
                    s.n_particles(),
                    s.probes.len(),
                    s.end_time()
                );
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

/// A progress bar that appears only on a terminal and only once a run has taken a second.
struct LazyProgress {
    enabled: bool,
    start: Instant,
    bar: Option<ProgressBar>,
}

/// Resolution of the bar: per-mille of the end time.
const BAR_STEPS: u64 = 1000;

impl LazyProgress {
    fn new(quiet: bool) -> Self {
        Self {
            enabled: !quiet && std::io::stderr().is_terminal(),
            start: Instant::now(),
            bar: None,
        }
    }

    fn update(&mut self, t: f64, end: f64) {
        if !self.enabled {
            return;
        }
        if self.bar.is_none() && self.start.elapsed() > Duration::from_secs(1) {
            let bar = ProgressBar::with_draw_target(Some(BAR_STEPS), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {wide_bar} {percent}% (eta {eta})",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            bar.set_position(((t / end).clamp(0.0, 1.0) * BAR_STEPS as f64) as u64);
        }
    }

    fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
