//! Shared set-up of the Fuller damage problems (problems.md §3 "Common Fuller settings", M-F):
//! non-dimensional units, square lattice, cubic spline with h = 1.5Δx, 2D plane strain, the
//! linear-elastic M-F material with a damage law, and a run loop that records the damaged
//! fraction and where the first particle failed. TL mode: corrected TLSPH, Jaumann rate, no
//! artificial viscosity, XSPH or artificial stress (the thesis' Eulerian stabilisers; XSPH
//! cannot be combined with failure, and the pairwise viscosity would keep failed particles
//! coupled to their old neighbours).

use crate::report::RunCost;
use std::time::Instant;
use tlsph_io::particle_map::MapPoint;
use tlsph_materials::LinearElastic;
use tlsph_math::Vector;
use tlsph_solver::{
    BodyDescription, BoundaryDescription, DamageModel, ElasticDamage, Formulation, KernelKind,
    MaterialDescription, MaterialModel, Model, ParticleField, Simulation, SimulationConfig,
    StressUpdate,
};

/// M-F (problems.md §1): ρ = 1, E = 1, ν = 0.3 `[T]`; c_l = sqrt(M/ρ) = 1.1602.
pub const YOUNGS_MODULUS: f64 = 1.0;
/// M-F Poisson's ratio.
pub const POISSON_RATIO: f64 = 0.3;
/// h = 1.5Δx `[T]`.
pub const SMOOTHING_FACTOR: f64 = 1.5;
/// Courant number `[C]` (the thesis does not print one; the suite's usual value).
pub const CFL: f64 = 0.3;
/// The damage problems' artificial viscosity (App. A.12, A.13: α = 1 `[T]`) in the form of
/// F 2.60, whose quadratic term is 2α μ²: (α, β) = (1, 2) of numerics.md §10.1. Failed
/// particles leave its sums with their bonds. It damps the ringing behind the step waves that
/// the suddenly pulled edges launch, whose overshoot would otherwise activate damage far
/// from the crack (F §5.3.2 notes such shock-induced spots).
pub const DAMAGE_VISCOSITY: (f64, f64) = (1.0, 2.0);
/// D above which a particle counts as damaged in the area fractions and criteria (problems.md
/// F-A12/F-A13 "D > 0.5").
pub const DAMAGED: f64 = 0.5;

/// A prescribed velocity on a row or column of the lattice: one velocity component imposed,
/// the other free `[C]` (problems.md F-A1).
pub struct Loaded {
    pub name: &'static str,
    pub particles: Vec<usize>,
    pub axis: usize,
    pub velocity: f64,
}

/// The M-F model with `damage` on one body of particles at `positions` with reference
/// `volumes` (lattice spacing `dx`, which also sets h).
pub fn model(
    positions: Vec<Vector<2>>,
    volumes: Vec<f64>,
    dx: f64,
    damage: DamageModel,
    loads: Vec<Loaded>,
    end_time: f64,
) -> Model<2> {
    let elastic = LinearElastic::new(YOUNGS_MODULUS, POISSON_RATIO).expect("M-F is valid");
    let n = positions.len();
    Model {
        config: SimulationConfig {
            formulation: Formulation::TotalLagrangianCorrected,
            stress_update: StressUpdate::JaumannRate,
            kernel: KernelKind::CubicSpline,
            smoothing_factor: SMOOTHING_FACTOR,
            cfl: CFL,
            end_time,
        },
        materials: vec![MaterialDescription {
            name: "M-F".into(),
            density: 1.0,
            model: MaterialModel::ElasticDamage(ElasticDamage { elastic, damage }),
        }],
        bodies: vec![BodyDescription {
            name: "specimen".into(),
            material: 0,
            spacing: dx,
            volumes,
            velocities: vec![Vector::<2>::zeros(); n],
            initial_stress: None,
            initial_stress_gradient: None,
            initial_stresses: None,
            initial_plastic_strains: None,
            initial_damage: None,
            initial_failure_damage: None,
            positions,
        }],
        boundaries: loads
            .into_iter()
            .map(|l| {
                let mut velocity = Vector::<2>::zeros();
                velocity[l.axis] = l.velocity;
                let mut components = [false; 2];
                components[l.axis] = true;
                BoundaryDescription {
                    name: l.name.into(),
                    body: 0,
                    particles: l.particles,
                    velocity,
                    components,
                    amplitude: None,
                }
            })
            .collect(),
        effects: Default::default(),
    }
}

/// What a damage run records.
#[derive(Debug, Clone)]
pub struct DamageRun {
    /// (t, fraction of particles with D > 0.5) every `sample_interval`.
    pub damaged_fraction: Vec<(f64, f64)>,
    /// (t, fraction of failed particles) at the same times.
    pub failed_fraction: Vec<(f64, f64)>,
    /// Time, reference position of the first particle(s) to fail (lowest index if several
    /// failed in the same step).
    pub first_failure: Option<(f64, Vector<2>)>,
    /// Reference positions X and damage D of every particle at each snapshot time requested.
    pub snapshots: Vec<Snapshot>,
    /// Cost of the run.
    pub cost: RunCost,
    /// The run stopped early (message), if it did.
    pub error: Option<String>,
}

/// The damage field at one time.
#[derive(Debug, Clone)]
pub struct Snapshot {
    /// Time.
    pub time: f64,
    /// Reference positions.
    pub positions0: Vec<Vector<2>>,
    /// Current positions.
    pub positions: Vec<Vector<2>>,
    /// Damage D (1 once failed).
    pub damage: Vec<f64>,
}

impl Snapshot {
    /// Particle map points (current positions, colour = D).
    pub fn map_points(&self) -> Vec<MapPoint> {
        self.positions
            .iter()
            .zip(&self.damage)
            .map(|(x, d)| MapPoint::new(x[0], x[1], *d))
            .collect()
    }
}

fn snapshot(sim: &Simulation<2>) -> Snapshot {
    let n = sim.n_particles();
    Snapshot {
        time: sim.time(),
        positions0: sim.positions0().to_vec(),
        positions: (0..n)
            .map(|i| sim.positions0()[i] + sim.displacements()[i])
            .collect(),
        damage: (0..n)
            .map(|i| sim.sample(ParticleField::Damage, i))
            .collect(),
    }
}

/// Runs `model`, sampling the damaged fractions every `sample_interval` and keeping the
/// damage field at each of `snapshot_times` (and at the end).
pub fn run(model: Model<2>, sample_interval: f64, snapshot_times: &[f64]) -> DamageRun {
    let mut sim = Simulation::new(model).expect("Fuller damage model is valid");
    let n = sim.n_particles();
    let mut out = DamageRun {
        damaged_fraction: Vec::new(),
        failed_fraction: Vec::new(),
        first_failure: None,
        snapshots: Vec::new(),
        cost: RunCost::default(),
        error: None,
    };
    let mut next_sample = 0.0;
    let mut pending: Vec<f64> = snapshot_times.to_vec();
    let mut steps = 0usize;
    let start = Instant::now();
    let result = sim.run(|s, _| {
        steps += 1;
        let t = s.time();
        if out.first_failure.is_none() && s.failed_particles() > 0 {
            let i = (0..n)
                .find(|&i| s.sample(ParticleField::Damage, i) >= 1.0)
                .expect("a failed particle has D = 1");
            out.first_failure = Some((t, s.positions0()[i]));
        }
        if !pending.is_empty() && t >= pending[0] {
            pending.remove(0);
            out.snapshots.push(snapshot(s));
        }
        if t + 1e-9 >= next_sample || s.finished() {
            next_sample += sample_interval;
            let damaged = (0..n)
                .filter(|&i| s.sample(ParticleField::Damage, i) > DAMAGED)
                .count();
            out.damaged_fraction.push((t, damaged as f64 / n as f64));
            out.failed_fraction
                .push((t, s.failed_particles() as f64 / n as f64));
        }
    });
    out.cost = RunCost {
        particles: n,
        steps,
        wall_s: start.elapsed().as_secs_f64(),
    };
    if let Err(e) = result {
        out.error = Some(e.to_string());
    }
    out.snapshots.push(snapshot(&sim));
    out
}

/// Linear interpolation of a sampled (t, y) series at `t` (clamped at the ends).
pub fn sample_at(series: &[(f64, f64)], t: f64) -> f64 {
    match series.iter().position(|&(ts, _)| ts >= t) {
        None => series.last().map_or(f64::NAN, |p| p.1),
        Some(0) => series[0].1,
        Some(k) => {
            let (t0, y0) = series[k - 1];
            let (t1, y1) = series[k];
            y0 + (y1 - y0) * (t - t0) / (t1 - t0)
        }
    }
}
