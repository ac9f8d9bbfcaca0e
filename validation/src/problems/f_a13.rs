//! F-A13: Peerlings linear-softening damage in a waisted bar under tension (Fuller §5.3.2,
//! Eqs 5.3–5.4, Figs 5.9, 5.12; App. A.13), TL mode. The damage band must form at the waist,
//! normal to the load, and separate the bar there, without damage elsewhere beyond transient
//! spots (problems.md F-A13). Geometry built directly as lattice points.

use super::fuller::{self, DamageRun, Loaded, Snapshot, DAMAGED};
use crate::report::{Curve, ProblemReport, ReportRow, Series, Tier};
use tlsph_io::particle_map::ParticleMapSpec;
use tlsph_materials::PeerlingsSoftening;
use tlsph_math::Vector;
use tlsph_solver::DamageModel;

/// Problem id.
pub const ID: &str = "F-A13";
/// Bar width (x) `[T]`.
pub const WIDTH: f64 = 40.0;
/// Bar height (y) `[T]`.
pub const HEIGHT: f64 = 100.0;
/// Damage threshold κ0 `[T]`.
pub const KAPPA0: f64 = 0.001;
/// Critical strain κc `[T]`.
pub const KAPPA_C: f64 = 0.01;
/// Speed of the top row (+y) and bottom row (−y) `[T]`.
pub const PULL_SPEED: f64 = 0.001;
/// Simulated time `[C]`: 1.2 % nominal elongation (2 v t / H), beyond κc = 1 %, so the waist
/// must have separated if the damage localises there.
pub const END_TIME: f64 = 600.0;
/// Interval of the damaged-fraction series.
pub const SAMPLE_INTERVAL: f64 = 10.0;
/// Thesis lattice spacing `[T]`.
pub const THESIS_SPACING: f64 = 1.0;
/// Quick tier: half resolution (20 × 51 lattice, a quarter of the particles and half the
/// steps, ≈ 1/8 of the cost), same geometry, loading and time.
pub const QUICK_SPACING: f64 = 2.0;
/// Half-width of the band around the centroid within which damage counts as "in the band"
/// (problems.md: centroid within ±5 of the waist; same ±5 for "elsewhere").
pub const BAND_HALF_WIDTH: f64 = 5.0;

/// Waist profile K(y) = (10/(7π)) w(|y − 50|/25), w the cubic-spline shape with w(0) = 1
/// (problems.md F-A13 reconstruction `[C]`, reproduces N = 3336 ± 3).
pub fn waist_kernel(y: f64) -> f64 {
    let q = (y - 0.5 * HEIGHT).abs() / 25.0;
    let w = if q < 1.0 {
        1.0 - 1.5 * q * q + 0.75 * q * q * q
    } else if q < 2.0 {
        0.25 * (2.0 - q).powi(3)
    } else {
        0.0
    };
    10.0 / (7.0 * std::f64::consts::PI) * w
}

/// Lattice points x = i Δx, y = j Δx with 20 K(y) ≤ x ≤ 40 − 20 K(y), 0 ≤ y ≤ 100
/// (40 × 101 lattice at Δx = 1: 3335 particles, thesis 3336).
pub fn positions(dx: f64) -> Vec<Vector<2>> {
    let nx = (WIDTH / dx).round() as usize;
    let ny = (HEIGHT / dx).round() as usize + 1;
    let mut out = Vec::new();
    for j in 0..ny {
        let y = j as f64 * dx;
        let k = waist_kernel(y);
        for i in 0..nx {
            let x = i as f64 * dx;
            if x >= 20.0 * k && x <= WIDTH - 20.0 * k {
                out.push(Vector::<2>::new(x, y));
            }
        }
    }
    out
}

/// Plane-strain bar-wave speed sqrt(E / (ρ (1 − ν²))) of M-F (ρ = 1): the speed of the step
/// waves that the suddenly pulled end rows launch along the bar.
pub fn bar_wave_speed() -> f64 {
    (fuller::YOUNGS_MODULUS / (1.0 - fuller::POISSON_RATIO.powi(2))).sqrt()
}

/// Time by which each end wave has crossed the whole bar once, H / c̄: the damage present then
/// is what the first crossing of the two step waves caused (the shock-induced kind).
pub fn first_transit_time() -> f64 {
    HEIGHT / bar_wave_speed()
}

/// Runs the bar at spacing `dx`; snapshots after the first transit and at the end.
pub fn simulate(dx: f64) -> DamageRun {
    let positions = positions(dx);
    let row = |y: f64| -> Vec<usize> {
        (0..positions.len())
            .filter(|&i| (positions[i][1] - y).abs() < 1e-9)
            .collect()
    };
    let loads = vec![
        Loaded {
            name: "top",
            particles: row(HEIGHT),
            axis: 1,
            velocity: PULL_SPEED,
        },
        Loaded {
            name: "bottom",
            particles: row(0.0),
            axis: 1,
            velocity: -PULL_SPEED,
        },
    ];
    let law = PeerlingsSoftening::new(KAPPA0, KAPPA_C).expect("F-A13 parameters are valid");
    let volumes = vec![dx * dx; positions.len()];
    let mut model = fuller::model(
        positions,
        volumes,
        dx,
        DamageModel::Peerlings(law),
        loads,
        END_TIME,
    );
    model.effects.pairwise_viscosity = Some(fuller::DAMAGE_VISCOSITY);
    fuller::run(model, SAMPLE_INTERVAL, &[first_transit_time()])
}

/// The pass criteria evaluated on the final damage field.
#[derive(Debug, Clone, Copy)]
pub struct Band {
    /// Mean reference y of the particles with D > 0.5.
    pub centroid: f64,
    /// Slope dy/dx of the least-squares line through them (0 = normal to the load).
    pub slope: f64,
    /// Fraction of all particles with D > 0.5 farther than 5 from the centroid.
    pub off_band_fraction: f64,
    /// Lattice columns (x positions of the narrowest row) that no failed particle within 5 of
    /// the centroid covers: 0 means the bar is separated across the whole width.
    pub uncut_columns: usize,
}

/// Evaluates the band of the final snapshot.
pub fn band(run: &DamageRun, dx: f64) -> Band {
    band_of(run.snapshots.last().expect("final snapshot"), dx)
}

/// Evaluates the band of one snapshot.
pub fn band_of(last: &Snapshot, dx: f64) -> Band {
    let damaged: Vec<Vector<2>> = last
        .positions0
        .iter()
        .zip(&last.damage)
        .filter(|(_, &d)| d > DAMAGED)
        .map(|(x, _)| *x)
        .collect();
    let n = damaged.len() as f64;
    let centroid = damaged.iter().map(|x| x[1]).sum::<f64>() / n;
    let mean_x = damaged.iter().map(|x| x[0]).sum::<f64>() / n;
    let sxx: f64 = damaged.iter().map(|x| (x[0] - mean_x).powi(2)).sum();
    let sxy: f64 = damaged
        .iter()
        .map(|x| (x[0] - mean_x) * (x[1] - centroid))
        .sum();
    let off = damaged
        .iter()
        .filter(|x| (x[1] - centroid).abs() > BAND_HALF_WIDTH)
        .count();
    // Columns of the narrowest row (the waist, y = 50).
    let waist_y = (0.5 * HEIGHT / dx).round() * dx;
    let columns: Vec<f64> = last
        .positions0
        .iter()
        .filter(|x| (x[1] - waist_y).abs() < 1e-9)
        .map(|x| x[0])
        .collect();
    let uncut = columns
        .iter()
        .filter(|&&cx| {
            !last.positions0.iter().zip(&last.damage).any(|(x, &d)| {
                d >= 1.0 && (x[0] - cx).abs() < 1e-9 && (x[1] - centroid).abs() <= BAND_HALF_WIDTH
            })
        })
        .count();
    Band {
        centroid,
        slope: sxy / sxx,
        off_band_fraction: off as f64 / last.damage.len() as f64,
        uncut_columns: uncut,
    }
}

/// Runs F-A13 at a tier.
pub fn run(tier: Tier) -> ProblemReport {
    let mut report = ProblemReport::default();
    let (dx, tag) = match tier {
        Tier::Quick => (QUICK_SPACING, "quick"),
        Tier::Full => (THESIS_SPACING, "full"),
    };
    let result = simulate(dx);
    let cost = result.cost;
    if let Some(e) = &result.error {
        report
            .notes
            .push(format!("F-A13 ({tag}) stopped early: {e}"));
    }
    let b = band(&result, dx);
    let label = |q: &str| format!("dx {dx}: {q}");
    report.rows.push(
        ReportRow::absolute(ID, &label("damage band centroid y"), b.centroid, 50.0, 5.0)
            .with_cost(cost),
    );
    // Normal to the load: the band's fitted line within ±15° of horizontal `[C]`.
    report.rows.push(
        ReportRow::absolute(
            ID,
            &label("damage band slope dy/dx (|.| ≤ tan 15°)"),
            b.slope,
            0.0,
            15f64.to_radians().tan(),
        )
        .with_cost(cost),
    );
    report.rows.push(
        ReportRow::absolute(
            ID,
            &label("waist columns not separated (count)"),
            b.uncut_columns as f64,
            0.0,
            0.0,
        )
        .with_cost(cost),
    );
    // Known deviation (shock-induced spots where the two end waves meet, reference-data/F-A13):
    // judged at the thesis resolution only.
    report.push_full_tier_row(
        tier,
        ReportRow::absolute(
            ID,
            &label("fraction of particles with D > 0.5 off the band"),
            b.off_band_fraction,
            0.0,
            0.02,
        )
        .with_cost(cost),
    );
    report.curves.push(Curve {
        name: format!("f-a13-damaged-fraction-{tag}"),
        title: format!("F-A13 waisted bar, Peerlings damage (dx = {dx})"),
        x_label: "time [t.u.]".into(),
        y_label: "fraction of particles".into(),
        series: vec![
            Series {
                label: "D > 0.5".into(),
                points: result.damaged_fraction.clone(),
                is_reference: false,
            },
            Series {
                label: "failed (D = 1)".into(),
                points: result.failed_fraction.clone(),
                is_reference: false,
            },
        ],
    });
    let last = result.snapshots.last().expect("final snapshot");
    report.maps.push((
        format!("f-a13-damage-{tag}"),
        ParticleMapSpec {
            title: format!(
                "F-A13 damage at t = {:.0} (dx = {dx}; cf. thesis Fig 5.12)",
                last.time
            ),
            x_label: "x".into(),
            y_label: "y".into(),
            value_label: "damage D".into(),
            range: Some((0.0, 1.0)),
            marker_size: dx,
            points: last.map_points(),
            outlines: Vec::new(),
        },
    ));
    report.notes.push(shock_note(&result, dx, tag));
    report.notes.push(format!(
        "F-A13 ({tag}): TL mode (corrected TLSPH, Jaumann rate, the thesis' artificial viscosity α = 1 (β = 2α, F 2.60); no XSPH or artificial stress); κ = max principal Hencky strain (history); {} particles, {} steps, {:.1} s.",
        cost.particles, cost.steps, cost.wall_s
    ));
    report
}

/// Where the off-band damage comes from: the strain of the end step waves against the damage
/// law, the time of the first failure against the quasi-static elongation, and the off-band
/// fraction already present after the first transit of the waves.
fn shock_note(result: &DamageRun, dx: f64, tag: &str) -> String {
    let step_strain = PULL_SPEED / bar_wave_speed();
    // D(κ) = κc (κ − κ0) / (κ (κc − κ0)) = ½  ⇔  κ = κ0 κc / (κc − ½ (κc − κ0)).
    let kappa_half = KAPPA0 * KAPPA_C / (KAPPA_C - 0.5 * (KAPPA_C - KAPPA0));
    let failure = result.first_failure.map_or("no particle failed".to_string(), |(t, _)| {
        format!(
            "the first particle fails at t = {t:.1}, at a nominal elongation 2vt/H of {:.2} % (κc = {:.0} %), when the crossing has swept |y − 50| ≤ c̄t − H/2 = {:.0}",
            200.0 * PULL_SPEED * t / HEIGHT,
            100.0 * KAPPA_C,
            bar_wave_speed() * t - 0.5 * HEIGHT
        )
    });
    let early = if result.snapshots.len() > 1 {
        format!(
            "; particles with D > 0.5 off the band after the first transit (t = H/c̄ = {:.0}): {:.1} %, at the end {:.1} %",
            first_transit_time(),
            100.0 * band_of(&result.snapshots[0], dx).off_band_fraction,
            100.0 * band(result, dx).off_band_fraction
        )
    } else {
        String::new()
    };
    format!(
        "F-A13 ({tag}) shock-induced damage: each pulled end launches a step wave of strain v/c̄ = {step_strain:.2e} (c̄ = {:.3}, plane-strain bar speed); where the two cross, the strain doubles to {:.2e}, beyond κ(D = 0.5) = {kappa_half:.2e}, so the crossing drives the slim waist toward D = 0.5 wherever it passes before the bar separates: {failure}{early}. The thesis reports such shock-induced spots (F §5.3.2) and proposes bounding the damage rate by a time scale as the remedy; tried here as Ḋ ≤ 1/τ driven by the current strain, it spreads the damage instead (off the band 4.4, 16.4 and 35 % for τ = 10, 30 and 95 at dx 1): the doubled strain is held until the bar separates, so it is not a short spike, and delaying the softening delays the unloading that confines the band. Not adopted; see reference-data/F-A13.",
        bar_wave_speed(),
        2.0 * step_strain
    )
}
