//! R-P4: clamped–free titanium rod released with a linear velocity field (Reveles §6.1.4,
//! Figs 6.12–6.16), normalised–corrected TLSPH (Algorithm 3) against the full modal series.
//! Also the linear-regime variant R-P4s (K = 1e3 /s) of problems.md.

use crate::analytic::rod_vibration::{
    peak_amplitude, zero_crossing_period, RodVibration, K_LINEAR_PER_S, K_THESIS_PER_S, LENGTH_M,
    STATIONS_M, TITANIUM,
};
use crate::report::{Curve, ProblemReport, ReportRow, RunCost, Series, Tier};
use crate::variants::{interpolate_at, model_1d, positions_1d, Variant, ALGORITHM_3};
use std::time::Instant;
use tlsph_solver::Simulation;

/// Problem id.
pub const ID: &str = "R-P4";
/// Simulated time: 12.4 µs ≈ 3.26 periods (Fig 6.16).
pub const END_TIME: f64 = 12.4e-6;
/// Particles of the thesis (Δx = 0.2 mm).
pub const THESIS_PARTICLES: usize = 31;

/// Scene text: `n` particles from the clamp (X = 0, fixed) to the free end particle
/// (X = L = 6 mm), i.e. Δx = L/(n − 1); the particle lattice then represents a rod whose free
/// surface is half a spacing beyond the last particle, L_eff = L + Δx/2.
pub fn scene(variant: &Variant, n: usize, velocity_gradient: f64) -> String {
    let dx = LENGTH_M / (n - 1) as f64;
    format!(
        r#"# R-P4 clamped-free titanium rod (material M-TI, E = 116 GPa, uniaxial strain)
[simulation]
dimension = 1
{sim}cfl = 0.3
end_time = {END_TIME:e}

[[material]]
name = "titanium"
model = "linear-elastic"
density = {rho}
youngs_modulus = {e:e}
poisson_ratio = {nu}

[[body]]
name = "rod"
material = "titanium"
spacing = {dx:e}
box = {{ min = [{min:e}], max = [{max:e}] }}
velocity_gradient = [[{velocity_gradient:e}]]

[[boundary]]
name = "clamp"
body = "rod"
at = [0.0]
fixed = true
"#,
        sim = variant.simulation_lines(),
        rho = TITANIUM.density,
        e = TITANIUM.youngs_modulus,
        nu = TITANIUM.poisson_ratio,
        min = -0.5 * dx,
        max = LENGTH_M + 0.5 * dx,
    )
}

/// What one R-P4 run measured.
#[derive(Debug, Clone)]
pub struct RodRun {
    /// Sample times \[s\].
    pub times: Vec<f64>,
    /// Displacement histories at the three stations (2, 3, 6 mm) \[m\].
    pub displacements: [Vec<f64>; 3],
    /// Kinetic energy per unit area [J/m²].
    pub kinetic: Vec<f64>,
    /// Internal energy per unit area [J/m²].
    pub internal: Vec<f64>,
    /// Particle spacing \[m\].
    pub spacing: f64,
    /// Cost.
    pub cost: RunCost,
}

/// Runs the rod with `n` particles and velocity gradient K \[1/s\].
pub fn simulate(variant: &Variant, n: usize, velocity_gradient: f64) -> RodRun {
    let model = model_1d(&scene(variant, n, velocity_gradient), "R-P4 scene");
    let mut sim = Simulation::new(model).expect("R-P4 scene is valid");
    let x0 = positions_1d(&sim);
    let mut run = RodRun {
        times: Vec::new(),
        displacements: Default::default(),
        kinetic: Vec::new(),
        internal: Vec::new(),
        spacing: LENGTH_M / (n - 1) as f64,
        cost: RunCost::default(),
    };
    let start = Instant::now();
    sim.run(|s, _| {
        run.times.push(s.time());
        for (k, x) in STATIONS_M.iter().enumerate() {
            run.displacements[k].push(interpolate_at(&x0, |i| s.displacements()[i][0], *x));
        }
        let d = s.diagnostics();
        run.kinetic.push(d.kinetic);
        run.internal.push(d.internal);
    })
    .expect("R-P4 is stable");
    run.cost = RunCost {
        particles: sim.n_particles(),
        steps: sim.steps_done() as usize,
        wall_s: start.elapsed().as_secs_f64(),
    };
    run
}

/// The modal series of the thesis rod (L = 6 mm, c = c_M). The particle lattice represents
/// the free surface only to within half a spacing (the measured period puts it ≈ 0.2 Δx beyond
/// the last particle), so the comparison converges at first order in Δx.
pub fn series_for(velocity_gradient: f64) -> RodVibration {
    RodVibration::new(LENGTH_M, TITANIUM.wave_speed(), velocity_gradient)
}

/// Largest displacement error at the three stations over the run, relative to the series
/// mode-1 amplitude B1.
pub fn max_displacement_error(run: &RodRun, series: &RodVibration) -> f64 {
    let b1 = series.modal_amplitude(1).abs();
    let mut worst: f64 = 0.0;
    for (k, x) in STATIONS_M.iter().enumerate() {
        for (t, u) in run.times.iter().zip(&run.displacements[k]) {
            worst = worst.max((u - series.displacement(*x, *t)).abs());
        }
    }
    worst / b1
}

/// Largest |E(t) − E(0)| / E(0) of kinetic + internal energy.
pub fn energy_drift(run: &RodRun) -> f64 {
    let e0 = run.kinetic[0] + run.internal[0];
    run.kinetic
        .iter()
        .zip(&run.internal)
        .map(|(k, i)| ((k + i) - e0).abs() / e0)
        .fold(0.0, f64::max)
}

/// Runs R-P4 (thesis amplitude, 31 particles; the full tier adds a 4× finer rod) and the
/// linear-regime study R-P4s (31 … 241 particles).
pub fn run(tier: Tier) -> ProblemReport {
    let mut report = ProblemReport::default();
    let series = series_for(K_THESIS_PER_S);
    let counts: &[usize] = match tier {
        Tier::Quick => &[THESIS_PARTICLES],
        Tier::Full => &[THESIS_PARTICLES, 4 * (THESIS_PARTICLES - 1) + 1],
    };
    for &n in counts {
        let tag = format!("alg3 {n} particles");
        let run = simulate(&ALGORITHM_3, n, K_THESIS_PER_S);
        let tip = &run.displacements[2];
        let period = zero_crossing_period(&run.times, tip).unwrap_or(f64::NAN);
        let amplitude = peak_amplitude(&run.times, tip);
        let series_tip: Vec<f64> = run
            .times
            .iter()
            .map(|t| series.displacement(LENGTH_M, *t))
            .collect();
        let series_amplitude = peak_amplitude(&run.times, &series_tip);
        let drift = energy_drift(&run);
        let c = run.cost;
        let rows = &mut report.rows;
        rows.push(
            ReportRow::relative(
                ID,
                &format!("{tag}: mode-1 period [s]"),
                period,
                series.period(),
                0.03,
            )
            .with_cost(c),
        );
        rows.push(
            ReportRow::relative(
                ID,
                &format!("{tag}: free-end amplitude [m]"),
                amplitude,
                series_amplitude,
                0.05,
            )
            .with_cost(c),
        );
        rows.push(
            ReportRow::with_error(
                ID,
                &format!("{tag}: max |KE+IE - E0| / E0"),
                drift,
                0.0,
                drift,
                0.01,
            )
            .with_cost(c),
        );
        if n == THESIS_PARTICLES {
            report
                .curves
                .extend(curves(&run, &series, "r-p4", "R-P4 (K = 1e5 /s)"));
        }
    }
    // R-P4s: linear regime (strain 1e-4). The spec's tolerances (period 0.5 %, displacement
    // 2 % of B1) are met once the free-surface ambiguity (first order in Δx) is below them;
    // the study also checks that order.
    let id_s = "R-P4s";
    let series = series_for(K_LINEAR_PER_S);
    let mut errors = Vec::new();
    for n in [31, 61, 121, 241] {
        let run = simulate(&ALGORITHM_3, n, K_LINEAR_PER_S);
        let period = zero_crossing_period(&run.times, &run.displacements[2]).unwrap_or(f64::NAN);
        let err = max_displacement_error(&run, &series);
        let c = run.cost;
        let rows = &mut report.rows;
        if n == 241 {
            rows.push(
                ReportRow::relative(
                    id_s,
                    "alg3 241 particles: mode-1 period [s]",
                    period,
                    series.period(),
                    0.005,
                )
                .with_cost(c),
            );
            rows.push(
                ReportRow::with_error(
                    id_s,
                    "alg3 241 particles: max displacement error / B1",
                    err,
                    0.0,
                    err,
                    0.02,
                )
                .with_cost(c),
            );
        }
        if n == THESIS_PARTICLES {
            report
                .curves
                .extend(curves(&run, &series, "r-p4s", "R-P4s (K = 1e3 /s)"));
        }
        report.notes.push(format!(
            "R-P4s, {n} particles: period error {:+.3} %, max displacement error {:.2} % of B1.",
            100.0 * (period / series.period() - 1.0),
            100.0 * err
        ));
        errors.push((run.spacing, err, c));
    }
    let (a, b) = (errors[errors.len() - 2], errors[errors.len() - 1]);
    let order = (a.1 / b.1).ln() / (a.0 / b.0).ln();
    report.rows.push(
        ReportRow::with_error(
            id_s,
            "alg3 observed convergence order (121 -> 241 particles)",
            order,
            1.0,
            (1.0 - order).max(0.0),
            0.1,
        )
        .with_cost(b.2),
    );
    report.notes.push("The 31 particles sit at X = 0 (clamped) … 6 mm; a particle lattice represents the free surface only to within half a spacing, so with corrected gradients the error converges at first order (the measured period puts the surface about 0.2 Δx beyond the last particle). At the thesis' 31 particles this costs 0.7 % in period, more than the 0.5 % the spec assumed from lattice dispersion alone; from about 240 particles on the spec's R-P4s tolerances hold.".into());
    report.notes.push("At K = 1e5 /s the peak strain is about 9.5 %, where the rate law σ = M ln λ departs from linear elasticity; the thesis-level tolerances (3 % period, 5 % amplitude) still hold.".into());
    report
}

fn curves(run: &RodRun, series: &RodVibration, stem: &str, title: &str) -> Vec<Curve> {
    let micro = |t: f64| t * 1e6;
    let mut displacement = Vec::new();
    let labels = ["2 mm", "3 mm", "6 mm"];
    for (k, x) in STATIONS_M.iter().enumerate() {
        displacement.push(Series {
            label: format!("TLSPH x = {}", labels[k]),
            points: run
                .times
                .iter()
                .zip(&run.displacements[k])
                .map(|(t, u)| (micro(*t), *u))
                .collect(),
            is_reference: false,
        });
        displacement.push(Series {
            label: format!("series x = {}", labels[k]),
            points: run
                .times
                .iter()
                .map(|t| (micro(*t), series.displacement(*x, *t)))
                .collect(),
            is_reference: true,
        });
    }
    let rho = TITANIUM.density;
    let energies = vec![
        Series {
            label: "TLSPH kinetic".into(),
            points: run
                .times
                .iter()
                .zip(&run.kinetic)
                .map(|(t, e)| (micro(*t), *e))
                .collect(),
            is_reference: false,
        },
        Series {
            label: "TLSPH internal".into(),
            points: run
                .times
                .iter()
                .zip(&run.internal)
                .map(|(t, e)| (micro(*t), *e))
                .collect(),
            is_reference: false,
        },
        Series {
            label: "series kinetic".into(),
            points: run
                .times
                .iter()
                .map(|t| (micro(*t), series.kinetic_energy(*t, rho)))
                .collect(),
            is_reference: true,
        },
        Series {
            label: "series internal".into(),
            points: run
                .times
                .iter()
                .map(|t| (micro(*t), series.internal_energy(*t, rho)))
                .collect(),
            is_reference: true,
        },
    ];
    vec![
        Curve {
            name: format!("{stem}-displacement"),
            title: format!("{title}: displacement histories (Fig 6.13)"),
            x_label: "time [µs]".into(),
            y_label: "displacement [m]".into(),
            series: displacement,
        },
        Curve {
            name: format!("{stem}-energy"),
            title: format!("{title}: energy exchange (Fig 6.14)"),
            x_label: "time [µs]".into(),
            y_label: "energy per unit area [J/m²]".into(),
            series: energies,
        },
    ]
}
