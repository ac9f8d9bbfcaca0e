//! R-P2: elastic uniaxial-strain wave from a two-plate impact (Reveles §6.1.2, Figs 6.3–6.5).
//! Compares target gauge stress and velocity, the arrival at the rear face, pulse duration and
//! the flyer strain with the linear analytic solution and with the exact finite-strain
//! solution of each algorithm's own constitutive law (problems.md R-P2).

use crate::analytic::plate_impact::{
    impact_state, lagrangian_reference, linear_reference, pulse_metrics, PlateImpactConfig,
    ReferenceSolution, UniaxialLaw,
};
use crate::report::{Curve, ProblemReport, ReportRow, RunCost, Series, Tier};
use crate::variants::{
    interpolate_at, model_1d, positions_1d, sample_series, Variant, ALGORITHM_1, ALGORITHM_2,
    ALGORITHM_3,
};
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};
use std::time::Instant;
use tlsph_math::Tensor3;
use tlsph_solver::{ParticleField, Simulation};

/// Problem id.
pub const ID: &str = "R-P2";
/// Target gauge (middle of the target), reference coordinate.
pub const GAUGE_X: f64 = 1.25;
/// Time of the stress profile of Fig 6.5.
pub const PROFILE_TIME: f64 = 1.5;
/// Time at which the flyer strain is measured: the flyer is compressed from X = 0.05 to 0.5
/// and nothing has been released yet (the front reaches the flyer's rear face at t = 0.5).
pub const FLYER_STRAIN_TIME: f64 = 0.45;
/// The thesis spacing: 2000 particles over a length of 2.
pub const FULL_SPACING: f64 = 0.001;
/// Quick-tier spacing (500 particles).
pub const QUICK_SPACING: f64 = 0.004;

/// Scene text of R-P2 for a variant and spacing (flyer bonded to the target; with equal
/// impedances the interface never goes into tension before t = 1.5, problems.md R-P2).
pub fn scene(variant: &Variant, spacing: f64) -> String {
    format!(
        r#"# R-P2 two-plate impact, material M-ND2 (non-dimensional)
[simulation]
dimension = 1
{sim}cfl = 0.3
end_time = 2.0

[[material]]
name = "nd2"
model = "linear-elastic"
density = 1.0
youngs_modulus = 0.9
poisson_ratio = 0.2

[[body]]
name = "plates"
material = "nd2"
spacing = {spacing}

[[body.shape]]
box = {{ min = [0.0], max = [0.5] }}
velocity = [0.1]

[[body.shape]]
box = {{ min = [0.5], max = [2.0] }}
"#,
        sim = variant.simulation_lines()
    )
}

/// Everything measured in one R-P2 run.
#[derive(Debug, Clone)]
pub struct PlateImpactRun {
    /// Sample times (every step).
    pub times: Vec<f64>,
    /// σ_xx at X = 1.25 (interpolated between particles).
    pub gauge_stress: Vec<f64>,
    /// v_x at X = 1.25.
    pub gauge_velocity: Vec<f64>,
    /// v_x of the rear-most target particle.
    pub rear_velocity: Vec<f64>,
    /// Compressive strain of the flyer between X = 0.1 and 0.4 at t = 0.45.
    pub flyer_strain: f64,
    /// (X, σ_xx) along the plates at t = 1.5.
    pub profile: Vec<(f64, f64)>,
    /// Cost of the run.
    pub cost: RunCost,
}

/// Runs R-P2 for one variant and spacing.
pub fn simulate(variant: &Variant, spacing: f64) -> PlateImpactRun {
    let model = model_1d(&scene(variant, spacing), "R-P2 scene");
    let mut sim = Simulation::new(model).expect("R-P2 scene is valid");
    let x0 = positions_1d(&sim);
    let rear = x0.len() - 1;
    let mut run = PlateImpactRun {
        times: Vec::new(),
        gauge_stress: Vec::new(),
        gauge_velocity: Vec::new(),
        rear_velocity: Vec::new(),
        flyer_strain: f64::NAN,
        profile: Vec::new(),
        cost: RunCost::default(),
    };
    let stress = ParticleField::Stress(0, 0);
    let velocity = ParticleField::Velocity(0);
    let start = Instant::now();
    sim.run(|s, _| {
        let t = s.time();
        run.times.push(t);
        run.gauge_stress
            .push(interpolate_at(&x0, |i| s.sample(stress, i), GAUGE_X));
        run.gauge_velocity
            .push(interpolate_at(&x0, |i| s.sample(velocity, i), GAUGE_X));
        run.rear_velocity.push(s.sample(velocity, rear));
        if run.flyer_strain.is_nan() && t >= FLYER_STRAIN_TIME {
            let u = |x: f64| interpolate_at(&x0, |i| s.displacements()[i][0], x);
            run.flyer_strain = -(u(0.4) - u(0.1)) / 0.3;
        }
        if run.profile.is_empty() && t >= PROFILE_TIME {
            run.profile = x0
                .iter()
                .zip(s.stresses())
                .map(|(x, sigma): (&f64, &Tensor3)| (*x, sigma[(0, 0)]))
                .collect();
        }
    })
    .expect("R-P2 is stable");
    run.cost = RunCost {
        particles: sim.n_particles(),
        steps: sim.steps_done() as usize,
        wall_s: start.elapsed().as_secs_f64(),
    };
    run
}

/// The constitutive law each variant integrates (1D uniaxial strain): rate form gives
/// σ = M ln λ, St Venant–Kirchhoff gives P = M λ(λ² − 1)/2.
pub fn law_of(variant: &Variant) -> UniaxialLaw {
    let modulus = 1.0;
    match variant.stress_update {
        "green-lagrange" => UniaxialLaw::StVenantKirchhoff { modulus },
        _ => UniaxialLaw::LogarithmicRate { modulus },
    }
}

/// The converged finite-strain reference of a law, computed once per process and resolution.
pub fn finite_strain_reference(law: UniaxialLaw, n_cells: usize) -> ReferenceSolution {
    static CACHE: OnceLock<Mutex<HashMap<String, ReferenceSolution>>> = OnceLock::new();
    let key = format!("{}-{n_cells}", law.name());
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(r) = cache.lock().expect("cache lock").get(&key) {
        return r.clone();
    }
    let config = PlateImpactConfig::default().with_cells(n_cells);
    let reference = lagrangian_reference(&law, &config);
    cache
        .lock()
        .expect("cache lock")
        .insert(key, reference.clone());
    reference
}

/// Cells of the finite-strain reference per tier (converged to < 0.1 % in plateau and times).
fn reference_cells(tier: Tier) -> usize {
    match tier {
        Tier::Quick => 4000,
        Tier::Full => 8000,
    }
}

/// L1 error of the gauge stress history against the own-law reference over the whole run,
/// normalised by plateau × pulse duration (the area of the exact pulse): a single number
/// that falls with resolution and captures front smearing and ringing.
pub fn history_error(run: &PlateImpactRun, reference: &ReferenceSolution) -> f64 {
    let gauge = reference
        .gauge(GAUGE_X)
        .expect("reference has the X = 1.25 gauge");
    let metrics = reference.stress_metrics(GAUGE_X).expect("reference pulse");
    let mut integral = 0.0;
    for k in 1..run.times.len() {
        let (t0, t1) = (run.times[k - 1], run.times[k]);
        let e0 =
            (run.gauge_stress[k - 1] - sample_series(&reference.times, &gauge.stress, t0)).abs();
        let e1 = (run.gauge_stress[k] - sample_series(&reference.times, &gauge.stress, t1)).abs();
        integral += 0.5 * (e0 + e1) * (t1 - t0);
    }
    integral / (metrics.plateau * metrics.duration)
}

/// Runs R-P2 at a tier: Algorithm 2 (the thesis default) against the linear solution and its
/// own finite-strain law; at the full tier also Algorithms 1 and 3 against their own laws.
pub fn run(tier: Tier) -> ProblemReport {
    let spacing = match tier {
        Tier::Quick => QUICK_SPACING,
        Tier::Full => FULL_SPACING,
    };
    let mut report = ProblemReport::default();
    let linear = linear_reference(&PlateImpactConfig::default());
    let variants: &[Variant] = match tier {
        Tier::Quick => &[ALGORITHM_2],
        Tier::Full => &[ALGORITHM_2, ALGORITHM_1, ALGORITHM_3],
    };
    for (k, variant) in variants.iter().enumerate() {
        let run = simulate(variant, spacing);
        let law = law_of(variant);
        let reference = finite_strain_reference(law, reference_cells(tier));
        let own = reference.stress_metrics(GAUGE_X).expect("reference pulse");
        let own_rear = reference
            .velocity_metrics(2.0)
            .expect("reference rear pulse");
        let own_strain = 1.0 - impact_state(&law, &PlateImpactConfig::default()).stretch;
        let sph =
            pulse_metrics(&run.times, &run.gauge_stress).expect("a stress pulse at the gauge");
        let sph_v = pulse_metrics(&run.times, &run.gauge_velocity).expect("a velocity pulse");
        let sph_rear = pulse_metrics(&run.times, &run.rear_velocity).expect("a rear pulse");
        // Tolerances: the problems.md values, widened only by effects computed here, never
        // by hand: (a) the fixed consistency error of raw gradients on a lattice (wave speed,
        // hence arrival times and durations, and strain at given stress), (b) for comparisons
        // with the linear solution, the shift of the variant's own finite-strain law.
        let speed = variant.lattice_speed_error();
        let stiffness = (1.0 + speed).powi(2) - 1.0;
        let shift = |own: f64, linear: f64| ((own - linear) / linear).abs();
        let tag = variant.name;
        let rows = &mut report.rows;
        let c = run.cost;
        let row = |q: &str, measured: f64, reference: f64, tol: f64| {
            ReportRow::relative(ID, &format!("{tag}: {q}"), measured, reference, tol).with_cost(c)
        };
        rows.push(row(
            "stress plateau vs own-law exact",
            sph.plateau,
            own.plateau,
            0.02,
        ));
        rows.push(row(
            "pulse duration at X=1.25 vs own-law exact",
            sph.duration,
            own.duration,
            0.03 + speed,
        ));
        rows.push(row(
            "arrival at X=1.25 vs own-law exact",
            sph.arrival,
            own.arrival,
            0.02 + speed,
        ));
        rows.push(row(
            "arrival at target rear vs own-law exact",
            sph_rear.arrival,
            own_rear.arrival,
            0.02 + speed,
        ));
        rows.push(row(
            "flyer compressive strain vs own-law exact",
            run.flyer_strain,
            own_strain,
            0.03 + stiffness,
        ));
        if k == 0 {
            // Thesis comparison (linear analytic, R 6.1–6.5).
            rows.push(row(
                "stress plateau vs linear",
                sph.plateau,
                linear.plateau_stress,
                0.02 + shift(own.plateau, linear.plateau_stress),
            ));
            rows.push(row(
                "particle velocity plateau vs linear",
                sph_v.plateau,
                linear.particle_velocity,
                0.02,
            ));
            rows.push(row(
                "pulse duration at X=1.25 vs linear",
                sph.duration,
                linear.pulse_duration,
                0.03 + speed + shift(own.duration, linear.pulse_duration),
            ));
            rows.push(row(
                "arrival at target rear vs linear",
                sph_rear.arrival,
                linear.rear_arrival,
                0.02 + speed + shift(own_rear.arrival, linear.rear_arrival),
            ));
            rows.push(row(
                "flyer compressive strain vs linear",
                run.flyer_strain,
                linear.strain,
                0.03 + stiffness + shift(own_strain, linear.strain),
            ));
            report.curves.extend(curves(&run, &reference, tier));
        }
        if speed > 0.0 {
            report.notes.push(format!(
                "{tag}: raw kernel gradients at h = {}Δx over-estimate the wave speed by {:.2} % at every resolution (lattice sum, R-P3 method C); timing tolerances include it, and the cost sweep shows this error does not fall with refinement.",
                variant.smoothing_factor(),
                100.0 * speed
            ));
        }
    }
    report.notes.push(format!(
        "Linear theory gives |σ| = U_p = 0.05 exactly; the rate (Jaumann) law integrates to σ = M ln λ and the St Venant–Kirchhoff law to P = Mλ(λ²−1)/2, so at 5 % strain each algorithm is also compared with the exact 1D finite-strain solution of its own law (converged Godunov reference, {} cells).",
        reference_cells(tier)
    ));
    report.notes.push("Gauge at X = 1.25 is interpolated linearly between the two nearest particles; the rear arrival uses the velocity of the rear-most particle (X = 2 − Δx/2) against the reference at X = 2.".into());
    report
}

fn curves(run: &PlateImpactRun, reference: &ReferenceSolution, tier: Tier) -> Vec<Curve> {
    let tier_name = match tier {
        Tier::Quick => "quick",
        Tier::Full => "full",
    };
    let linear = linear_reference(&PlateImpactConfig::default());
    let arrival = linear.arrival(GAUGE_X);
    let step = |level: f64| -> Vec<(f64, f64)> {
        vec![
            (0.0, 0.0),
            (arrival, 0.0),
            (arrival, level),
            (arrival + linear.pulse_duration, level),
            (arrival + linear.pulse_duration, 0.0),
            (2.0, 0.0),
        ]
    };
    let gauge = reference.gauge(GAUGE_X).expect("gauge");
    let thin = |times: &[f64], values: &[f64]| -> Vec<(f64, f64)> {
        let stride = (times.len() / 2000).max(1);
        times
            .iter()
            .zip(values)
            .step_by(stride)
            .map(|(t, v)| (*t, *v))
            .collect()
    };
    let series = |label: &str, points: Vec<(f64, f64)>, is_reference: bool| Series {
        label: label.into(),
        points,
        is_reference,
    };
    let mut out = vec![
        Curve {
            name: format!("r-p2-gauge-stress-{tier_name}"),
            title: "R-P2 stress history at X = 1.25 (Fig 6.3)".into(),
            x_label: "time".into(),
            y_label: "stress σ_xx (tension +)".into(),
            series: vec![
                series(
                    "TLSPH alg. 2",
                    run.times
                        .iter()
                        .copied()
                        .zip(run.gauge_stress.iter().copied())
                        .collect(),
                    false,
                ),
                series("linear analytic", step(-linear.plateau_stress), true),
                series(
                    "finite-strain exact (rate law)",
                    thin(&reference.times, &gauge.stress),
                    true,
                ),
            ],
        },
        Curve {
            name: format!("r-p2-gauge-velocity-{tier_name}"),
            title: "R-P2 particle velocity at X = 1.25 (Fig 6.4)".into(),
            x_label: "time".into(),
            y_label: "velocity v_x".into(),
            series: vec![
                series(
                    "TLSPH alg. 2",
                    run.times
                        .iter()
                        .copied()
                        .zip(run.gauge_velocity.iter().copied())
                        .collect(),
                    false,
                ),
                series("linear analytic", step(linear.particle_velocity), true),
                series(
                    "finite-strain exact (rate law)",
                    thin(&reference.times, &gauge.velocity),
                    true,
                ),
            ],
        },
    ];
    let profile = &reference.profile;
    out.push(Curve {
        name: format!("r-p2-profile-t1.5-{tier_name}"),
        title: "R-P2 stress along the plates at t = 1.5 (Fig 6.5)".into(),
        x_label: "reference position X".into(),
        y_label: "stress σ_xx (tension +)".into(),
        series: vec![
            series("TLSPH alg. 2", run.profile.clone(), false),
            series(
                "finite-strain exact (rate law)",
                profile
                    .x0
                    .iter()
                    .copied()
                    .zip(profile.stress.iter().copied())
                    .collect(),
                true,
            ),
        ],
    });
    out
}
