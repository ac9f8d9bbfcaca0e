//! Running a scene: drives the solver to the end time, samples probes and diagnostics, and
//! writes a run folder. Files are written into `<dir>.partial/` and the folder is renamed into
//! place at the end, so an existing result is never left half-overwritten.

use crate::scene::{DimensionModel, ProbeSpec, Scene};
use crate::vtk::{write_pvd, write_vtu, Frame, FrameArray};
use std::fmt;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tlsph_solver::stability::{StabilityMonitor, StabilityThresholds};
use tlsph_solver::{Diagnostics, Model, ParticleField, SetupError, Simulation, StepError};

/// Samples of one probe.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeHistory {
    /// Probe name.
    pub name: String,
    /// Column order of `values`.
    pub fields: Vec<ParticleField>,
    /// Sample times \[s\].
    pub times: Vec<f64>,
    /// One row per sample, one value per field.
    pub values: Vec<Vec<f64>>,
}

impl ProbeHistory {
    /// The time series of one field, or `None` if the probe does not record it.
    pub fn series(&self, field: ParticleField) -> Option<Vec<f64>> {
        let k = self.fields.iter().position(|f| *f == field)?;
        Some(self.values.iter().map(|row| row[k]).collect())
    }
}

/// Everything a run produced, in memory.
#[derive(Debug, Clone)]
pub struct RunRecord {
    /// Probe histories, in scene order.
    pub probes: Vec<ProbeHistory>,
    /// Energies and momenta at the output interval (first at t = 0, last at the final time).
    pub diagnostics: Vec<Diagnostics>,
    /// Time steps taken: the last step's index (step 0 evaluates the state at t = 0, step k
    /// ends at t^k), the numbering of `stability.csv` and of a failed step's message.
    pub steps: u64,
    /// Particle count.
    pub particles: usize,
    /// Wall time of the time loop \[s\] (setup excluded).
    pub wall_s: f64,
    /// Why the run stopped early, if it did.
    pub failure: Option<StepError>,
    /// The stability report, sampled with the diagnostics (see `tlsph_solver::stability`).
    pub stability: StabilityMonitor,
}

impl RunRecord {
    /// Particle-steps per second of the time loop.
    pub fn particle_steps_per_s(&self) -> f64 {
        if self.wall_s > 0.0 {
            self.particles as f64 * self.steps as f64 / self.wall_s
        } else {
            0.0
        }
    }

    /// The probe called `name`.
    pub fn probe(&self, name: &str) -> Option<&ProbeHistory> {
        self.probes.iter().find(|p| p.name == name)
    }
}

/// A run that could not start or whose output could not be written.
#[derive(Debug)]
pub enum RunError {
    /// The solver rejected the model.
    Setup(SetupError),
    /// A file operation failed.
    Io {
        /// Path involved.
        path: PathBuf,
        /// What failed.
        message: String,
    },
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::Setup(e) => write!(f, "cannot set up the simulation: {e}"),
            RunError::Io { path, message } => write!(f, "{}: {message}", path.display()),
        }
    }
}

impl std::error::Error for RunError {}

/// Progress callback: called with (simulated time, end time) after every step.
pub type Progress<'a> = &'a mut dyn FnMut(f64, f64);

/// Frame callback: receives a particle frame at every frame interval.
pub type FrameSink<'a> = &'a mut dyn FnMut(&Frame);

/// Sampling settings of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intervals {
    /// Thresholds of the stability report sampled with the diagnostics.
    pub stability: StabilityThresholds,
    /// Interval of energy/momentum rows \[s\].
    pub energy: f64,
    /// Interval of particle frames \[s\]; `None` for no frames.
    pub frames: Option<f64>,
}

/// A 3D-padded particle frame of the current state: positions, displacement, velocity,
/// Cauchy stress (tensor), pressure, von Mises stress, density, det F, specific internal
/// energy and the body index.
pub fn frame_of<const D: usize>(sim: &Simulation<D>) -> Frame {
    let n = sim.n_particles();
    let pad =
        |v: &[f64]| -> [f64; 3] { std::array::from_fn(|k| if k < v.len() { v[k] } else { 0.0 }) };
    let vector = |name: &str, f: &dyn Fn(usize) -> [f64; 3]| FrameArray {
        name: name.into(),
        components: 3,
        values: (0..n).flat_map(f).collect(),
    };
    let scalar = |field: ParticleField| FrameArray {
        name: field.to_string(),
        components: 1,
        values: (0..n).map(|i| sim.sample(field, i)).collect(),
    };
    let positions = (0..n)
        .map(|i| pad((sim.positions0()[i] + sim.displacements()[i]).as_slice()))
        .collect();
    let mut arrays = vec![
        vector("displacement", &|i| {
            pad(sim.total_displacement(i).as_slice())
        }),
        vector("velocity", &|i| pad(sim.velocity(i).as_slice())),
        FrameArray {
            name: "stress".into(),
            components: 9,
            // Row-major: VTK reads tensors as (xx, xy, xz, yx, ...).
            values: sim
                .stresses()
                .iter()
                .flat_map(|s| {
                    let t = s.transpose();
                    t.as_slice().to_vec()
                })
                .collect(),
        },
        scalar(ParticleField::Pressure),
        scalar(ParticleField::VonMises),
        scalar(ParticleField::Density),
        scalar(ParticleField::Jacobian),
        scalar(ParticleField::InternalEnergy),
        FrameArray {
            name: "body".into(),
            components: 1,
            values: (0..n).map(|i| sim.body_of(i) as f64).collect(),
        },
    ];
    // Optional state only where the scene declared it.
    if sim.has_plastic_strain() {
        arrays.push(scalar(ParticleField::PlasticStrain));
    }
    if sim.has_temperature() {
        arrays.push(scalar(ParticleField::Temperature));
    }
    if sim.has_failure() {
        arrays.push(scalar(ParticleField::Damage));
    }
    // Each of the two damages `damage` merges, for a material that has both.
    if sim.has_two_damages() {
        arrays.push(scalar(ParticleField::SofteningDamage));
        arrays.push(scalar(ParticleField::FailureDamage));
    }
    Frame {
        time: sim.time(),
        positions,
        arrays,
    }
}

/// Runs a model in memory, sampling `probes` at their intervals and diagnostics every
/// `energy_interval`. Returns the record and the final simulation state. A step failure ends
/// the run early and is reported in `RunRecord::failure`; everything sampled before is kept.
pub fn run_model<const D: usize>(
    model: Model<D>,
    probes: &[ProbeSpec],
    intervals: Intervals,
    on_frame: FrameSink<'_>,
    progress: Progress<'_>,
) -> Result<(RunRecord, Simulation<D>), SetupError> {
    let mut sim = Simulation::new(model)?;
    let end_time = sim.config().end_time;
    let globals: Vec<usize> = probes
        .iter()
        .map(|p| sim.bodies()[p.body].range.start + p.particle)
        .collect();
    let mut histories: Vec<ProbeHistory> = probes
        .iter()
        .map(|p| ProbeHistory {
            name: p.name.clone(),
            fields: p.fields.clone(),
            times: Vec::new(),
            values: Vec::new(),
        })
        .collect();
    let mut next_probe = vec![0.0f64; probes.len()];
    let mut next_energy = 0.0f64;
    let mut next_frame = 0.0f64;
    let mut diagnostics = Vec::new();
    let mut stability = StabilityMonitor::new(intervals.stability);
    let start = Instant::now();
    let mut failure = None;
    while !sim.finished() {
        if let Err(e) = sim.step() {
            stability.observe_breakdown(sim.steps_done(), sim.time());
            failure = Some(e);
            break;
        }
        let t = sim.time();
        let last = sim.finished();
        for (k, p) in probes.iter().enumerate() {
            if t >= next_probe[k] || last {
                let h = &mut histories[k];
                h.times.push(t);
                h.values.push(
                    p.fields
                        .iter()
                        .map(|f| sim.sample(*f, globals[k]))
                        .collect(),
                );
                next_probe[k] = next_multiple(t, p.interval);
            }
        }
        if t >= next_energy || last {
            let d = sim.diagnostics();
            stability.observe_with(&sim, &d);
            diagnostics.push(d);
            next_energy = next_multiple(t, intervals.energy);
        }
        if let Some(interval) = intervals.frames {
            if t >= next_frame || last {
                on_frame(&frame_of(&sim));
                next_frame = next_multiple(t, interval);
            }
        }
        progress(t, end_time);
    }
    let record = RunRecord {
        probes: histories,
        diagnostics,
        steps: sim.steps_done().saturating_sub(1),
        particles: sim.n_particles(),
        wall_s: start.elapsed().as_secs_f64(),
        failure,
        stability,
    };
    Ok((record, sim))
}

/// First multiple of `interval` strictly after `t` (robust to round-off at the multiple).
fn next_multiple(t: f64, interval: f64) -> f64 {
    let k = (t / interval * (1.0 + 1e-12)).floor() + 1.0;
    k * interval
}

/// Runs a scene in memory (no files); frames, if the scene asks for them, go to `on_frame`.
pub fn run_scene_with_frames(
    scene: &Scene,
    on_frame: FrameSink<'_>,
    progress: Progress<'_>,
) -> Result<RunRecord, SetupError> {
    let intervals = Intervals {
        stability: scene.output.stability,
        energy: scene.output.energy_interval,
        frames: scene.output.frame_interval,
    };
    let probes = &scene.probes;
    match &scene.model {
        DimensionModel::One(m) => {
            run_model(m.clone(), probes, intervals, on_frame, progress).map(|r| r.0)
        }
        DimensionModel::Two(m) => {
            run_model(m.clone(), probes, intervals, on_frame, progress).map(|r| r.0)
        }
        DimensionModel::Three(m) => {
            run_model(m.clone(), probes, intervals, on_frame, progress).map(|r| r.0)
        }
    }
}

/// Runs a scene in memory (no files, frames discarded).
pub fn run_scene(scene: &Scene, progress: Progress<'_>) -> Result<RunRecord, SetupError> {
    run_scene_with_frames(scene, &mut |_| {}, progress)
}

/// Runs a scene and writes its run folder `dir` (see `docs/scene-format.md`, "Outputs").
///
/// Setup errors leave the file system untouched. A run that stops on a step error still
/// writes everything recorded so far, with `status = "failed"` and the reason in
/// `summary.toml`.
pub fn run_scene_to_dir(
    scene: &Scene,
    dir: &Path,
    progress: Progress<'_>,
) -> Result<RunRecord, RunError> {
    check_replaceable(dir)?;
    let partial = prepare_partial(dir)?;
    let mut frames: Vec<(f64, PathBuf)> = Vec::new();
    let mut frame_error: Option<RunError> = None;
    let mut sink = |frame: &Frame| {
        if frame_error.is_some() {
            return;
        }
        let name = PathBuf::from("frames").join(format!("frame_{:05}.vtu", frames.len()));
        match write_vtu(&partial.join(&name), frame) {
            Ok(()) => frames.push((frame.time, name)),
            Err(e) => {
                frame_error = Some(RunError::Io {
                    path: partial.join(&name),
                    message: e.to_string(),
                })
            }
        }
    };
    let record = match run_scene_with_frames(scene, &mut sink, progress) {
        Ok(record) => record,
        Err(e) => {
            // A rejected scene leaves nothing behind: the folder made above is empty.
            let _ = fs::remove_dir_all(&partial);
            return Err(RunError::Setup(e));
        }
    };
    if let Some(e) = frame_error {
        return Err(e);
    }
    if !frames.is_empty() {
        let pvd = partial.join("frames.pvd");
        write_pvd(&pvd, &frames).map_err(|e| RunError::Io {
            path: pvd.clone(),
            message: e.to_string(),
        })?;
    }
    write_run_folder(scene, &record, &partial, dir)?;
    Ok(record)
}

/// The file that marks `<dir>.partial/` as this tool's working folder, so that only a folder
/// it made itself is ever deleted. It is removed just before the folder is renamed into place.
const PARTIAL_MARKER: &str = ".tlsph-partial";

/// Makes an empty `<dir>.partial/` before the run (a stale one an interrupted run left, known
/// by its marker file, is removed), so an output location that cannot be written is reported
/// before any time is spent computing, not after.
fn prepare_partial(dir: &Path) -> Result<PathBuf, RunError> {
    let partial = sibling(dir, "partial");
    let io = |e: std::io::Error| RunError::Io {
        path: partial.clone(),
        message: format!("cannot create the run's working folder here: {e}"),
    };
    if partial.exists() {
        fs::remove_dir_all(&partial).map_err(io)?;
    }
    fs::create_dir_all(&partial).map_err(io)?;
    fs::write(partial.join(PARTIAL_MARKER), b"").map_err(io)?;
    Ok(partial)
}

/// The last component of an output folder must be a plain folder name (not empty, `.` or `..`):
/// the run's working folders `<name>.partial` and `<name>.old` sit next to it.
pub fn check_output_dir(dir: &Path) -> Result<(), String> {
    // Read the text: `Path::components` drops a trailing `.` (`results/.` would pass as
    // `results`, yet `<dir>.partial` would land beside its parent).
    let text = dir.to_string_lossy();
    let last = text
        .trim_end_matches(std::path::is_separator)
        .rsplit(std::path::is_separator)
        .next()
        .unwrap_or("");
    match last {
        "" | "." | ".." => Err(format!(
            "`{}` does not end in a folder name (the run folder is made next to its siblings `<name>.partial` and `<name>.old`); give e.g. \"out\" or \"results/run-1\"",
            dir.display()
        )),
        _ => Ok(()),
    }
}

/// Refuses, before the run, every output location whose swap could lose data: `dir` must be
/// absent, empty or a previous run (it has `summary.toml`); `<dir>.partial` absent or this
/// tool's own stale working folder (it has the marker file); `<dir>.old` absent (the swap
/// makes it and removes it; one that exists is a user's folder or an interrupted swap's
/// previous result, and is never deleted).
fn check_replaceable(dir: &Path) -> Result<(), RunError> {
    check_output_dir(dir).map_err(|message| RunError::Io {
        path: dir.to_path_buf(),
        message,
    })?;
    let refuse = |path: PathBuf, message: &str| {
        Err(RunError::Io {
            path,
            message: message.into(),
        })
    };
    let partial = sibling(dir, "partial");
    if partial.exists() && !partial.join(PARTIAL_MARKER).is_file() {
        return refuse(partial, "exists and is not this tool's working folder (no marker file); it may hold the results of a run whose final rename failed; move or delete it");
    }
    let old = sibling(dir, "old");
    if old.symlink_metadata().is_ok() {
        return refuse(old, "exists: the run moves the previous results there while it swaps the new ones in, and never deletes a folder it did not make; move or delete it");
    }
    if !dir.exists() {
        return Ok(());
    }
    if !dir.is_dir() {
        return refuse(
            dir.to_path_buf(),
            "exists and is not a folder; choose another output dir",
        );
    }
    let empty = fs::read_dir(dir)
        .map_err(|e| RunError::Io {
            path: dir.to_path_buf(),
            message: e.to_string(),
        })?
        .next()
        .is_none();
    if empty || dir.join("summary.toml").is_file() {
        Ok(())
    } else {
        refuse(
            dir.to_path_buf(),
            "exists and is not a previous run folder (no summary.toml); refusing to overwrite it",
        )
    }
}

/// Swaps the finished `partial` folder into place as `dir`. The previous result survives at
/// `<dir>.old` until the new one is there; if a rename fails, the error says where each result
/// is, and nothing is deleted that holds the only copy of a result.
fn swap_into_place(partial: &Path, dir: &Path) -> Result<(), RunError> {
    let marker = partial.join(PARTIAL_MARKER);
    // From here on the working folder holds a finished result: no later run may delete it.
    fs::remove_file(&marker).map_err(|e| RunError::Io {
        path: marker.clone(),
        message: e.to_string(),
    })?;
    let stranded = |what: String, e: std::io::Error| RunError::Io {
        path: dir.to_path_buf(),
        message: format!(
            "{what}: {e}; this run's results are complete in `{}`",
            partial.display()
        ),
    };
    let old = sibling(dir, "old");
    let moved_aside = dir.exists();
    if moved_aside {
        fs::rename(dir, &old).map_err(|e| {
            stranded(
                format!(
                    "cannot move the previous results aside to `{}`",
                    old.display()
                ),
                e,
            )
        })?;
    }
    if let Err(e) = fs::rename(partial, dir) {
        let restored = moved_aside && fs::rename(&old, dir).is_ok();
        let previous = match (moved_aside, restored) {
            (false, _) => String::new(),
            (true, true) => " (the previous results are back in place)".into(),
            (true, false) => format!(" (the previous results are in `{}`)", old.display()),
        };
        return Err(stranded(
            format!("cannot rename the finished run into place{previous}"),
            e,
        ));
    }
    if moved_aside {
        fs::remove_dir_all(&old).map_err(|e| RunError::Io {
            path: old.clone(),
            message: format!(
                "the new results are in place, but the previous ones here could not be deleted: {e}; delete it before the next run"
            ),
        })?;
    }
    Ok(())
}

/// Position of a moving wall at a time, padded to 3D.
type WallTrack<'a> = (String, Box<dyn Fn(f64) -> tlsph_math::Vector3 + 'a>);

/// Writes the forces `forces` picks from each sample, `<name>_force_x/y/z`, then the
/// displacement of each of `tracks` at the sample's time, `<name>_displacement_x/y/z`, then
/// the torques `torques` picks, `<name>_torque`, then the moments `moments` picks,
/// `<name>_moment_x/y/z`; nothing without forces.
fn write_forces(
    path: &Path,
    diagnostics: &[Diagnostics],
    forces: impl Fn(&Diagnostics) -> &Vec<(String, tlsph_math::Vector3)>,
    tracks: &[WallTrack<'_>],
    (torques, moments): (
        impl Fn(&Diagnostics) -> &[(String, f64)],
        impl Fn(&Diagnostics) -> &[(String, tlsph_math::Vector3)],
    ),
) -> Result<(), RunError> {
    let Some(first) = diagnostics.first().filter(|d| !forces(d).is_empty()) else {
        return Ok(());
    };
    let mut header = vec!["time".to_string()];
    for (n, _) in forces(first) {
        header.extend(["x", "y", "z"].map(|c| format!("{n}_force_{c}")));
    }
    for (n, _) in tracks {
        header.extend(["x", "y", "z"].map(|c| format!("{n}_displacement_{c}")));
    }
    header.extend(torques(first).iter().map(|(n, _)| format!("{n}_torque")));
    for (n, _) in moments(first) {
        header.extend(["x", "y", "z"].map(|c| format!("{n}_moment_{c}")));
    }
    let rows = diagnostics.iter().map(|d| {
        let mut row = vec![d.time];
        for (_, f) in forces(d) {
            row.extend([f.x, f.y, f.z]);
        }
        for (_, track) in tracks {
            let u = track(d.time);
            row.extend([u.x, u.y, u.z]);
        }
        row.extend(torques(d).iter().map(|(_, t)| *t));
        for (_, m) in moments(d) {
            row.extend([m.x, m.y, m.z]);
        }
        row
    });
    write_csv(path, &header, rows)
}

/// The moving walls of `model` (not one that only spins: it stays in place), `wall_<name>`
/// with the displacement of the plane from its place at t = 0 (`WallMotion::displacement_at`,
/// what the solver shifts the plane by).
fn wall_tracks<const D: usize>(model: &Model<D>) -> Vec<WallTrack<'_>> {
    model
        .effects
        .walls
        .iter()
        .filter_map(|w| {
            let motion = w
                .motion
                .as_ref()
                .filter(|m| m.spin.is_none() || m.velocity.iter().any(|v| *v != 0.0))?;
            let track: Box<dyn Fn(f64) -> tlsph_math::Vector3> =
                Box::new(move |t| tlsph_math::vector_to_3d(&motion.displacement_at(t)));
            Some((format!("wall_{}", w.name), track))
        })
        .collect()
}

/// Writes the run's files into the working folder `partial` (made by [`prepare_partial`],
/// possibly holding frames already) and swaps it into place as `dir`.
fn write_run_folder(
    scene: &Scene,
    record: &RunRecord,
    partial: &Path,
    dir: &Path,
) -> Result<(), RunError> {
    let io = |path: &Path, e: std::io::Error| RunError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    fs::create_dir_all(partial.join("probes")).map_err(|e| io(partial, e))?;
    for probe in &record.probes {
        let mut header = vec!["time".to_string()];
        header.extend(probe.fields.iter().map(|f| f.to_string()));
        let rows = probe.times.iter().zip(&probe.values).map(|(t, row)| {
            let mut r = vec![*t];
            r.extend(row);
            r
        });
        write_csv(
            &partial.join("probes").join(format!("{}.csv", probe.name)),
            &header,
            rows,
        )?;
    }
    // Booked energies of declared effects get a column each, before `total`.
    let effect_names: Vec<String> = record
        .diagnostics
        .first()
        .map(|d| d.effect_energies.iter().map(|(n, _)| n.clone()).collect())
        .unwrap_or_default();
    let mut energy_header: Vec<String> = ["time", "kinetic", "internal"].map(String::from).to_vec();
    energy_header.extend(effect_names.iter().cloned());
    energy_header.push("total".into());
    let energy_rows = record.diagnostics.iter().map(|d| {
        let mut row = vec![d.time, d.kinetic, d.internal];
        row.extend(d.effect_energies.iter().map(|(_, e)| *e));
        row.push(d.total_energy());
        row
    });
    write_csv(&partial.join("energy.csv"), &energy_header, energy_rows)?;
    let tracks = match &scene.model {
        DimensionModel::One(m) => wall_tracks(m),
        DimensionModel::Two(m) => wall_tracks(m),
        DimensionModel::Three(m) => wall_tracks(m),
    };
    write_forces(
        &partial.join("walls.csv"),
        &record.diagnostics,
        |d| &d.effect_forces,
        &tracks,
        (|d| &d.effect_torques, |d| &d.effect_moments),
    )?;
    write_forces(
        &partial.join("boundaries.csv"),
        &record.diagnostics,
        |d| &d.boundary_forces,
        &[],
        (|_| &[], |_| &[]),
    )?;
    let momentum_rows = record.diagnostics.iter().map(|d| {
        let (p, l) = (d.linear_momentum, d.angular_momentum);
        vec![d.time, p.x, p.y, p.z, l.x, l.y, l.z]
    });
    write_csv(
        &partial.join("momentum.csv"),
        &[
            "time",
            "momentum_x",
            "momentum_y",
            "momentum_z",
            "angular_momentum_x",
            "angular_momentum_y",
            "angular_momentum_z",
        ]
        .map(String::from),
        momentum_rows,
    )?;
    let stability_rows = record.stability.samples.iter().map(|s| {
        vec![
            s.time,
            s.step as f64,
            s.distances.min_ratio,
            s.distances.max_ratio,
            s.distances.clumping_index,
            s.distances.min_spacing_ratio,
            s.distances.max_spacing_ratio,
            s.energy_drift,
        ]
    });
    write_csv(
        &partial.join("stability.csv"),
        &[
            "time",
            "step",
            "min_neighbour_ratio",
            "max_neighbour_ratio",
            "clumping_index",
            "min_spacing_ratio",
            "max_spacing_ratio",
            "energy_drift",
        ]
        .map(String::from),
        stability_rows,
    )?;
    let (status, message) = match &record.failure {
        None => ("complete", String::new()),
        Some(e) => ("failed", e.to_string()),
    };
    let summary = format!(
        "# Written by tlsph at the end of a run.\nstatus = \"{status}\"\nmessage = {message:?}\nscene = {origin:?}\nparticles = {}\nsteps = {}\nend_time = {}\nwall_s = {}\nparticle_steps_per_s = {}\nfailed_particles = {}\n",
        record.particles,
        record.steps,
        scene.end_time(),
        record.wall_s,
        record.particle_steps_per_s(),
        record.diagnostics.last().map_or(0, |d| d.failed_particles),
        origin = scene.origin,
    );
    let summary = summary + &stability_summary(&record.stability);
    let summary_path = partial.join("summary.toml");
    fs::write(&summary_path, summary).map_err(|e| io(&summary_path, e))?;
    swap_into_place(partial, dir)
}

/// The `[stability]` table of `summary.toml`: thresholds, extremes and the first crossing.
fn stability_summary(monitor: &StabilityMonitor) -> String {
    let t = &monitor.thresholds;
    let (lo, hi, clumping, drift) = monitor.extremes();
    let mut out = format!(
        "\n[stability]\nstayed_inside = {}\nmin_neighbour_ratio = {}\nmax_neighbour_ratio = {}\nmax_clumping_index = {}\nmax_energy_drift = {}\n",
        monitor.stayed_inside(),
        toml_number(lo),
        toml_number(hi),
        toml_number(clumping),
        toml_number(drift),
    );
    out += &format!(
        "\n[stability.thresholds]\nmin_neighbour_ratio = {}\nmax_neighbour_ratio = {}\nclumping_index = {}\nenergy_drift = {}\n",
        t.min_neighbour_ratio, t.max_neighbour_ratio, t.clumping_index, t.energy_drift
    );
    if let Some(c) = &monitor.first_crossing {
        out += &format!(
            "\n[stability.first_crossing]\nquantity = {:?}\nstep = {}\ntime = {}\nvalue = {}\n",
            c.quantity,
            c.step,
            c.time,
            toml_number(c.value)
        );
    }
    out
}

/// A float as TOML (which spells infinities and NaN `inf` and `nan`).
fn toml_number(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        }
    } else {
        format!("{x:?}")
    }
}

/// `<dir>.<suffix>` next to `dir`.
fn sibling(dir: &Path, suffix: &str) -> PathBuf {
    let mut name = dir
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_else(|| "out".into());
    name.push(format!(".{suffix}"));
    dir.with_file_name(name)
}

/// Writes a CSV file (header + rows of numbers) through a temporary file and a rename.
pub fn write_csv(
    path: &Path,
    header: &[String],
    rows: impl IntoIterator<Item = Vec<f64>>,
) -> Result<(), RunError> {
    let io = |e: std::io::Error| RunError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    if let Some(parent) = path.parent() {
        fs::create_dir_all(parent).map_err(io)?;
    }
    let tmp = path.with_extension("csv.tmp");
    {
        let file = fs::File::create(&tmp).map_err(io)?;
        let mut w = std::io::BufWriter::new(file);
        writeln!(w, "{}", header.join(",")).map_err(io)?;
        for row in rows {
            let line: Vec<String> = row.iter().map(|x| format!("{x:e}")).collect();
            writeln!(w, "{}", line.join(",")).map_err(io)?;
        }
        w.flush().map_err(io)?;
    }
    fs::rename(&tmp, path).map_err(io)
}
