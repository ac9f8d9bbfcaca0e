//! R-P9a: 2D plane-strain spall set-up, Ti flyer on an Al target at 660 m/s (Reveles §6.3.4,
//! Figs 6.31–6.32), TLSPH against conventional (updated-Lagrangian) SPH, no failure model.
//! The bodies touch through the particle-to-particle contact of numerics.md §12.2. Rows:
//! TLSPH keeps every lattice-neighbour pair within 2h0 and the target's (deformation-
//! normalised) nearest-neighbour ratio spread below 1.5 for the whole run; conventional SPH
//! is expected to open voids/clumps in the spall zone; the peak interface stress against
//! the elastic impedance estimate (informative).

use crate::report::{Curve, ProblemReport, ReportRow, RunCost, Series, Tier};
use std::time::Instant;
use tlsph_io::particle_map::{MapPoint, ParticleMapSpec};
use tlsph_io::{parse_scene, DimensionModel};
use tlsph_solver::stability::{NeighbourDistances, StabilityMonitor, StabilityThresholds};
use tlsph_solver::{BondMetrics, Model, ParticleField, Simulation};

/// Problem id.
pub const ID: &str = "R-P9a";
/// Impact velocity \[m/s\] `[T]`.
pub const VELOCITY: f64 = 660.0;
/// Time of the thesis' effective-stress pictures \[s\] `[T]`.
pub const END_TIME: f64 = 18e-6;
/// Flyer thickness and target thickness \[m\] `[C]` (ratio 1:2 as in R-P9b).
pub const FLYER_THICKNESS: f64 = 2e-3;
/// Target thickness \[m\] `[C]`.
pub const TARGET_THICKNESS: f64 = 4e-3;
/// Height of both plates \[m\] `[C]`.
pub const HEIGHT: f64 = 20e-3;
/// Contact scale a: the R-P9 deck-A card value `[D]`. The deck-B value 0.2 would make the
/// contact step bound 0.5 sqrt(m/k) ≈ 0.40 Δx/c, cutting the CFL step 0.84 Δx/c by more than
/// 2× (numerics.md §12.2 says to lower a then); with 0.02 the bound is ≈ 1.25 Δx/c at first
/// touch and binds only briefly at the deepest penetration.
pub const CONTACT_SCALE: f64 = 0.02;
/// Threshold on the nearest-neighbour distance ratio d_nn/Δx (problems.md pass criterion).
pub const RATIO_LIMIT: f64 = 1.5;

/// Longitudinal (uniaxial-strain) modulus M = E(1−ν)/((1+ν)(1−2ν)) \[Pa\].
fn longitudinal(e: f64, nu: f64) -> f64 {
    e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))
}

/// Elastic impedance estimate of the impact stress σ = v Z1 Z2/(Z1 + Z2), Z = sqrt(ρ M)
/// (problems.md R-P9a `[A]`: ≈ 7.0 GPa).
pub fn elastic_impact_stress() -> f64 {
    let z_ti = (4530.0 * longitudinal(1.16e11, 0.342)).sqrt();
    let z_al = (2780.0 * longitudinal(70e9, 0.33)).sqrt();
    VELOCITY * z_ti * z_al / (z_ti + z_al)
}

/// Bulk-wave estimate `[A]`: the same with Z = sqrt(ρ K) plus the flow-stress offset
/// (2/3)σ_y of the target, what a strongly plastic shock carries behind the elastic
/// precursor (the lower end of the plausible band).
pub fn plastic_impact_stress() -> f64 {
    let bulk = |e: f64, nu: f64| e / (3.0 * (1.0 - 2.0 * nu));
    let z_ti = (4530.0 * bulk(1.16e11, 0.342)).sqrt();
    let z_al = (2780.0 * bulk(70e9, 0.33)).sqrt();
    VELOCITY * z_ti * z_al / (z_ti + z_al) + 2.0 / 3.0 * 479e6
}

/// Ganzenmüller hourglass-control coefficient of the controlled TLSPH runs `[C]`: the
/// smallest of the R-P6 study's values (1, 10); it holds the target's lattice at every
/// spacing run here, which the uncontrolled runs do not (see [`run`]).
pub const HOURGLASS: f64 = 1.0;

/// One scheme of the comparison: formulation and optional hourglass control.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scheme {
    /// Label in rows, curves and maps.
    pub label: &'static str,
    /// Scene `formulation`.
    pub formulation: &'static str,
    /// `[hourglass_control] coefficient`, if declared.
    pub hourglass: Option<f64>,
}

/// TLSPH (corrected gradients) with hourglass control: the pass criteria apply to it.
pub const TLSPH_CONTROLLED: Scheme = Scheme {
    label: "TLSPH + hourglass control",
    formulation: "total-lagrangian-corrected",
    hourglass: Some(HOURGLASS),
};
/// TLSPH as the thesis ran it, without hourglass control.
pub const TLSPH_PLAIN: Scheme = Scheme {
    label: "TLSPH",
    formulation: "total-lagrangian-corrected",
    hourglass: None,
};
/// Conventional (updated-Lagrangian) SPH.
pub const CONVENTIONAL: Scheme = Scheme {
    label: "conventional SPH",
    formulation: "updated-lagrangian",
    hourglass: None,
};

/// Scene text for a scheme and spacing. Flyer x ∈ [−2, 0] mm moving +x, target
/// x ∈ [0, 4] mm; the faces touch (particle centres d0 = Δx apart: zero contact force).
pub fn scene(scheme: Scheme, spacing: f64) -> String {
    let half = 0.5 * HEIGHT;
    let formulation = scheme.formulation;
    let hourglass = scheme.hourglass.map_or(String::new(), |alpha| {
        format!(
            "\n[hourglass_control]             # Ganzenmueller (2015) [C]\ncoefficient = {alpha}\n"
        )
    });
    format!(
        r#"# R-P9a Ti flyer on Al target, plane strain, 660 m/s, no failure
[simulation]
dimension = 2
formulation = "{formulation}"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.7                      # R-P9 decks [D]
end_time = {END_TIME:e}

[[material]]
name = "titanium"              # M-TI + sigma_y 880 MPa, E_t 1.16 GPa [C]
model = "elastic-plastic"
density = 4530
youngs_modulus = 1.16e11
poisson_ratio = 0.342
yield_stress = 880e6
tangent_modulus = 1.16e9

[[material]]
name = "aluminium"             # rho 2780, E 70 GPa, nu 0.33, sigma_y 479 MPa, E_t 0.7 GPa [C]
model = "elastic-plastic"
density = 2780
youngs_modulus = 70e9
poisson_ratio = 0.33
yield_stress = 479e6
tangent_modulus = 0.7e9

[[body]]
name = "flyer"
material = "titanium"
spacing = {spacing:e}
box = {{ min = [{fx:e}, {lo:e}], max = [0.0, {half:e}] }}
velocity = [{VELOCITY}, 0.0]

[[body]]
name = "target"
material = "aluminium"
spacing = {spacing:e}
box = {{ min = [0.0, {lo:e}], max = [{TARGET_THICKNESS:e}, {half:e}] }}

[bulk_viscosity]               # problems.md default for impact problems [C]
quadratic = 1.5
linear = 0.06

[contact]
scale = {CONTACT_SCALE}
pairs = [["flyer", "target"]]
{hourglass}"#,
        fx = -FLYER_THICKNESS,
        lo = -half,
    )
}

fn model(scheme: Scheme, spacing: f64) -> Model<2> {
    match parse_scene(&scene(scheme, spacing), "R-P9a scene").map(|s| s.model) {
        Ok(DimensionModel::Two(m)) => m,
        Ok(_) => unreachable!("2D scene"),
        Err(e) => panic!("R-P9a scene: {e}"),
    }
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct ImpactRun {
    /// Scheme label.
    pub label: &'static str,
    /// Particle spacing \[m\].
    pub spacing: f64,
    /// Stability report of the whole run (default thresholds).
    pub stability: StabilityMonitor,
    /// Target-only nearest-neighbour statistics at 18 µs (deformation-normalised ratios
    /// d_I/(λ_min Δx), raw spacing ratios d_I/Δx, clumping index; nearest neighbour searched
    /// in the target alone, so the gap across the contact does not count).
    pub target_end: NeighbourDistances,
    /// Largest target spread max/min of the normalised ratio over the samples.
    pub worst_target_spread: f64,
    /// Smallest target normalised nearest-neighbour ratio over the samples.
    pub min_target_ratio: f64,
    /// History (t \[µs\], target spread max/min of the normalised ratio).
    pub target_history: Vec<(f64, f64)>,
    /// Reference-bond geometry at 18 µs (nearest-neighbour bonds against 2h0).
    pub bonds: BondMetrics,
    /// Largest nearest-neighbour bond length / 2h0 over the samples.
    pub worst_nearest_bond: f64,
    /// Interface stress history (t \[µs\], contact force / (height × unit depth) \[GPa\]).
    pub interface: Vec<(f64, f64)>,
    /// Peak interface stress \[Pa\].
    pub peak_interface: f64,
    /// Largest effective plastic strain at the end.
    pub max_plastic_strain: f64,
    /// Smallest Δt taken / first Δt (the contact's vote shows as a dip).
    pub min_dt_ratio: f64,
    /// Contact candidate-list rebuilds.
    pub rebuilds: u64,
    /// Von Mises stress map at the end.
    pub map: Vec<MapPoint>,
    /// Step error that stopped the run, if any.
    pub breakdown: Option<String>,
    /// Cost.
    pub cost: RunCost,
}

/// Runs one scheme to 18 µs.
pub fn simulate(scheme: Scheme, spacing: f64) -> ImpactRun {
    let mut sim = Simulation::new(model(scheme, spacing)).expect("R-P9a scene is valid");
    let mut run = ImpactRun {
        label: scheme.label,
        spacing,
        stability: StabilityMonitor::new(StabilityThresholds::default()),
        target_end: NeighbourDistances::undefined(),
        worst_target_spread: 0.0,
        min_target_ratio: f64::INFINITY,
        target_history: Vec::new(),
        bonds: BondMetrics::undefined(),
        worst_nearest_bond: 0.0,
        interface: Vec::new(),
        peak_interface: 0.0,
        max_plastic_strain: 0.0,
        min_dt_ratio: f64::INFINITY,
        rebuilds: 0,
        map: Vec::new(),
        breakdown: None,
        cost: RunCost::default(),
    };
    let start = Instant::now();
    let mut first_dt = None;
    let mut next_sample = 0.0;
    while !sim.finished() {
        let report = match sim.step() {
            Ok(r) => r,
            Err(e) => {
                run.stability
                    .observe_breakdown(sim.steps_done(), sim.time());
                run.breakdown = Some(e.to_string());
                break;
            }
        };
        if !sim.finished() {
            let dt0 = *first_dt.get_or_insert(report.next_dt);
            run.min_dt_ratio = run.min_dt_ratio.min(report.next_dt / dt0);
        }
        let d = sim.diagnostics();
        // Contact force on the flyer (body 0); its −x component presses on the target.
        let stress = -d.effect_force("contact").x / HEIGHT;
        run.peak_interface = run.peak_interface.max(stress);
        run.interface.push((sim.time() * 1e6, stress * 1e-9));
        if sim.time() >= next_sample || sim.finished() {
            next_sample = sim.time() + 0.5e-6;
            run.stability.observe_with(&sim, &d);
            let target = sim.body_neighbour_distances(1);
            let spread = target.max_ratio / target.min_ratio;
            run.worst_target_spread = run.worst_target_spread.max(spread);
            run.min_target_ratio = run.min_target_ratio.min(target.min_ratio);
            run.target_history.push((sim.time() * 1e6, spread));
            run.worst_nearest_bond = run
                .worst_nearest_bond
                .max(sim.bond_metrics().max_nearest_bond_over_support);
        }
    }
    run.target_end = sim.body_neighbour_distances(1);
    run.bonds = sim.bond_metrics();
    run.rebuilds = sim.contact_rebuilds().unwrap_or(0);
    let n = sim.n_particles();
    run.max_plastic_strain = (0..n)
        .map(|i| sim.sample(ParticleField::PlasticStrain, i))
        .fold(0.0, f64::max);
    run.map = (0..n)
        .map(|i| {
            let x = sim.positions0()[i] + sim.displacements()[i];
            MapPoint::new(x[0], x[1], sim.sample(ParticleField::VonMises, i) * 1e-9)
        })
        .collect();
    run.cost = RunCost {
        particles: n,
        steps: sim.steps_done() as usize,
        wall_s: start.elapsed().as_secs_f64(),
    };
    run
}

/// Spacings of a tier `[C]`: quick 0.4 mm (750 particles); full 0.2 mm (3000) with every
/// scheme and 0.1 mm (12 000) with the two TLSPH schemes, the resolution sweep of the
/// accuracy-cost report.
pub fn spacings(tier: Tier) -> &'static [f64] {
    match tier {
        Tier::Quick => &[0.4e-3],
        Tier::Full => &[0.2e-3, 0.1e-3],
    }
}

/// Every run of a tier: the three schemes at the first spacing, the TLSPH schemes at the
/// finer ones.
pub fn runs(tier: Tier) -> Vec<ImpactRun> {
    let dx = spacings(tier);
    let mut runs: Vec<ImpactRun> = [TLSPH_CONTROLLED, TLSPH_PLAIN, CONVENTIONAL]
        .into_iter()
        .map(|s| simulate(s, dx[0]))
        .collect();
    for &d in &dx[1..] {
        runs.extend([TLSPH_CONTROLLED, TLSPH_PLAIN].map(|s| simulate(s, d)));
    }
    runs
}

/// The report: pass rows for TLSPH with hourglass control, plain TLSPH reported in the
/// notes, the expected conventional-SPH failure, the interface stress (informative),
/// curves and von Mises maps at 18 µs.
pub fn run(tier: Tier) -> ProblemReport {
    let runs = runs(tier);
    let mut report = ProblemReport::default();
    let tag = |r: &ImpactRun| format!("dx {} mm {}", r.spacing * 1e3, r.label);
    let spread = |r: &ImpactRun| r.target_end.max_ratio / r.target_end.min_ratio;
    for r in &runs {
        // problems.md pass criteria, held over the whole run: no lattice-neighbour pair
        // pulled beyond 2h0 (the numerical-fracture measure of R-P7), and the target's
        // max/min nearest-neighbour ratio below 1.5. The ratio is deformation-normalised
        // (d_I / λ_min Δx, `tlsph_solver::stability`): the shock compresses the plate and the
        // lateral release bends it, which moves raw spacings by ~40 % without any particle
        // leaving its neighbourhood; raw spacings are in the notes.
        if r.label == TLSPH_CONTROLLED.label {
            report.rows.push(
                ReportRow::with_error(
                    ID,
                    &format!(
                        "{}: largest lattice-neighbour distance / 2h0 over 0-18 us (no fracture: < 1)",
                        tag(r)
                    ),
                    r.worst_nearest_bond,
                    1.0,
                    (r.worst_nearest_bond - 1.0).max(0.0),
                    0.0,
                )
                .with_cost(r.cost),
            );
            report.rows.push(
                ReportRow::with_error(
                    ID,
                    &format!(
                        "{}: target max/min normalised nearest-neighbour ratio over 0-18 us (< 1.5)",
                        tag(r)
                    ),
                    r.worst_target_spread,
                    RATIO_LIMIT,
                    (r.worst_target_spread - RATIO_LIMIT).max(0.0),
                    0.0,
                )
                .with_cost(r.cost),
            );
        }
        if r.label == CONVENTIONAL.label {
            // The expected failure (voids/clumps, ratio ≫ 1.5) reproduced or not.
            report.rows.push(
                ReportRow::with_error(
                    ID,
                    &format!(
                        "{}: target max/min normalised nearest-neighbour ratio at 18 us (expected failure: >> 1.5)",
                        tag(r)
                    ),
                    spread(r),
                    RATIO_LIMIT,
                    (RATIO_LIMIT - spread(r)).max(0.0),
                    0.0,
                )
                .with_cost(r.cost),
            );
        }
        if r.breakdown.is_some() {
            report.rows.push(ReportRow::with_error(
                ID,
                &format!("{}: reached 18 us", tag(r)),
                0.0,
                1.0,
                1.0,
                0.0,
            ));
        }
    }
    // Interface stress (informative): elastic estimate 7.0 GPa; a plastic shock carries
    // less (bulk-wave estimate ≈ 6.1 GPa), and the particle contact smears the rise. 20 %
    // covers the plastic estimate and the SPH smearing of one rise over a few spacings.
    let reference = elastic_impact_stress();
    for r in runs.iter().filter(|r| r.label != TLSPH_PLAIN.label) {
        report.rows.push(
            ReportRow::relative(
                ID,
                &format!(
                    "{}: peak interface stress [GPa] vs elastic impedance estimate (informative)",
                    tag(r)
                ),
                r.peak_interface * 1e-9,
                reference * 1e-9,
                0.2,
            )
            .with_cost(r.cost),
        );
    }
    let suffix = if tier == Tier::Full { "full" } else { "quick" };
    let base: Vec<&ImpactRun> = runs
        .iter()
        .filter(|r| r.spacing == runs[0].spacing)
        .collect();
    report.curves.push(Curve {
        name: format!("r-p9a-interface-stress-{suffix}"),
        title: "R-P9a interface stress (contact force / plate height)".into(),
        x_label: "time [µs]".into(),
        y_label: "stress [GPa]".into(),
        series: base
            .iter()
            .map(|r| Series {
                label: r.label.into(),
                points: r.interface.clone(),
                is_reference: false,
            })
            .chain(std::iter::once(Series {
                label: "elastic impedance estimate".into(),
                points: vec![(0.0, reference * 1e-9), (END_TIME * 1e6, reference * 1e-9)],
                is_reference: true,
            }))
            .collect(),
    });
    report.curves.push(Curve {
        name: format!("r-p9a-target-neighbour-ratio-{suffix}"),
        title: "R-P9a target max/min normalised nearest-neighbour ratio".into(),
        x_label: "time [µs]".into(),
        y_label: "max / min of d / (λ_min Δx)".into(),
        series: runs
            .iter()
            .map(|r| Series {
                label: tag(r),
                points: r.target_history.clone(),
                is_reference: false,
            })
            .collect(),
    });
    for r in &base {
        let key = match r.label {
            l if l == TLSPH_CONTROLLED.label => "tl-hourglass",
            l if l == TLSPH_PLAIN.label => "tl",
            _ => "ul",
        };
        report.maps.push((
            format!("r-p9a-von-mises-{key}-{suffix}"),
            ParticleMapSpec {
                title: format!(
                    "R-P9a {} at 18 µs, dx = {} mm: von Mises stress (cf. thesis Figs 6.31–6.32)",
                    r.label,
                    r.spacing * 1e3
                ),
                x_label: "x [m]".into(),
                y_label: "y [m]".into(),
                value_label: "von Mises stress [GPa]".into(),
                range: None,
                marker_size: 1.2 * r.spacing,
                points: r.map.clone(),
                outlines: vec![],
            },
        ));
    }
    for r in &runs {
        let (lo, hi, clump, drift) = r.stability.extremes();
        let t = &r.target_end;
        report.notes.push(format!(
            "{}: {} steps in {:.2} s ({:.2e} particle-steps/s), {} contact list rebuilds, smallest Δt / first Δt {:.3}, max ε̄p {:.3}; target over the run: worst max/min normalised ratio {:.3}; at 18 µs: normalised d/(λ_min Δx) in [{:.3}, {:.3}], raw d/Δx in [{:.3}, {:.3}], clumping index {:.3}; stability monitor (all bodies): normalised ratio in [{lo:.3}, {hi:.3}], clumping up to {clump:.3}, energy drift up to {drift:.3}, first crossing {}; lattice-neighbour bonds: longest {:.3} × 2h0 over the run, {} bond ends beyond 2h0 at 18 µs; all kernel bonds at 18 µs: stretch in [{:.3}, {:.3}], hourglass distortion {:.2e}{}.",
            tag(r),
            r.cost.steps,
            r.cost.wall_s,
            r.cost.particle_steps_per_s(),
            r.rebuilds,
            r.min_dt_ratio,
            r.max_plastic_strain,
            r.worst_target_spread,
            t.min_ratio,
            t.max_ratio,
            t.min_spacing_ratio,
            t.max_spacing_ratio,
            t.clumping_index,
            r.stability.first_crossing.as_ref().map_or("none".into(), |c| format!(
                "{} = {:.3} at {:.2} µs",
                c.quantity,
                c.value,
                c.time * 1e6
            )),
            r.worst_nearest_bond,
            r.bonds.nearest_bonds_beyond_support,
            r.bonds.min_stretch,
            r.bonds.max_stretch,
            r.bonds.hourglass_rms,
            r.breakdown.as_ref().map_or(String::new(), |e| format!("; stopped: {e}")),
        ));
    }
    let plain: Vec<String> = runs
        .iter()
        .filter(|r| r.label == TLSPH_PLAIN.label)
        .map(|r| {
            format!(
                "dx {} mm: longest lattice-neighbour distance {:.2} × 2h0, worst max/min normalised ratio {:.2}, smallest normalised ratio {:.3}",
                r.spacing * 1e3,
                r.worst_nearest_bond,
                r.worst_target_spread,
                r.min_target_ratio,
            )
        })
        .collect();
    report.notes.push(format!(
        "Zero-energy modes, not the tensile instability. TLSPH without hourglass control (the thesis' scheme, run at one coarse resolution there) is reported, not judged: {}. Its target lattice distorts in the contact-face layer near the plate edges, where the flyer's particles slide over the face particles during the lateral plastic flow and push them apart at lattice scale; nothing in plain TLSPH resists that zero-energy pattern (numerics.md §10.5, Ganzenmüller 2015),. The pass criteria are judged on TLSPH with [hourglass_control] coefficient = {HOURGLASS}, which holds the lattice at every spacing. For a plastic impact with contact, declare hourglass control.",
        plain.join("; ")
    ));
    report.notes.push(format!(
        "Impact stress estimates [A]: elastic impedance {:.2} GPa, bulk-wave + (2/3)σ_y {:.2} GPa. Contact scale a = {CONTACT_SCALE} (R-P9 deck A) [D]; bulk viscosity (1.5, 0.06) [C]. Conventional SPH's monitor d/Δx (all bodies) also sees the flyer–target gap across the contact, so the target-only ratio is the criterion.",
        elastic_impact_stress() * 1e-9,
        plastic_impact_stress() * 1e-9,
    ));
    report
}
