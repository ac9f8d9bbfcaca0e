//! `initial_plastic_strain` and `initial_plastic_strain_file`: a work-hardened body.

use std::fs;
use std::path::Path;
use tlsph_io::{load_scene, parse_scene, DimensionModel, SceneError};
use tlsph_solver::{Model, ParticleField, Simulation};

/// A 1D rod 0 ≤ X ≤ 1 (ρ = 1, E = 1, ν = 0.25: G = 0.4, c = 1.095) of an elastic–plastic
/// material (σ_y0 = 0.004, E_p = 0.1), spacing 0.01, compressed in uniaxial strain by the
/// initial velocity v = −0.03 X: until the release waves from its free ends arrive
/// (t ≈ 0.45 at the centre) the centre deforms homogeneously with ε = ln(1 − 0.03 t).
/// `extra` is more lines of the body table.
fn rod(extra: &str) -> String {
    format!(
        r#"
[simulation]
dimension = 1
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 0.3

[[material]]
name = "steel"
model = "elastic-plastic"
density = 1.0
youngs_modulus = 1.0
poisson_ratio = 0.25
yield_stress = 0.004
plastic_modulus = 0.1

[[body]]
name = "rod"
material = "steel"
spacing = 0.01
box = {{ min = [0.0], max = [1.0] }}
velocity = [0.0]
velocity_gradient = [[-0.03]]
{extra}

[output]
dir = "out"
"#
    )
}

const SHEAR_MODULUS: f64 = 0.4;
const YIELD_STRESS: f64 = 0.004;
const PLASTIC_MODULUS: f64 = 0.1;

fn model_1d(scene: tlsph_io::Scene) -> Model<1> {
    match scene.model {
        DimensionModel::One(m) => m,
        _ => unreachable!("a 1D scene"),
    }
}

/// Runs the rod and returns, at the centre particle, the largest relative departure of the von
/// Mises stress from the elastic 2G|ε| while |ε| < `elastic_until`, and the von Mises stress,
/// plastic strain and |ε| at the end.
fn compress(model: Model<1>, elastic_until: f64) -> (f64, f64, f64, f64) {
    let mut sim = Simulation::new(model).unwrap();
    let centre = sim.n_particles() / 2;
    let mut elastic_error = 0.0_f64;
    while !sim.finished() {
        sim.step().unwrap();
        let strain = -(1.0 - 0.03 * sim.time()).ln();
        let von_mises = sim.sample(ParticleField::VonMises, centre);
        if strain < elastic_until {
            let elastic = 2.0 * SHEAR_MODULUS * strain;
            elastic_error = elastic_error.max((von_mises - elastic).abs() / elastic);
        }
    }
    let strain = -(1.0 - 0.03 * sim.time()).ln();
    (
        elastic_error,
        sim.sample(ParticleField::VonMises, centre),
        sim.sample(ParticleField::PlasticStrain, centre),
        strain,
    )
}

#[test]
fn a_pre_strained_rod_yields_at_its_raised_yield_stress() {
    // In uniaxial strain σ_vM = 2G|ε| while elastic; past yield, with linear hardening,
    // σ_vM = 2G|ε| − 3G Δε̄p = σ_y0 + E_p (ε̄p0 + Δε̄p), so
    // Δε̄p = (2G|ε| − σ_y(ε̄p0)) / (3G + E_p). Virgin: yield at |ε| = 0.005; pre-strained to
    // ε̄p0 = 0.02, σ_y = 0.006: yield at |ε| = 0.0075. Both runs end at |ε| = 0.00904.
    let pre_strain = 0.02;
    let virgin = model_1d(parse_scene(&rod(""), "rod.toml").unwrap());
    let hardened = model_1d(
        parse_scene(
            &rod(&format!("initial_plastic_strain = {pre_strain}")),
            "rod.toml",
        )
        .unwrap(),
    );
    let hardened_yield = YIELD_STRESS + PLASTIC_MODULUS * pre_strain;
    let (virgin_elastic, virgin_stress, virgin_plastic, strain) =
        compress(virgin, 0.99 * YIELD_STRESS / (2.0 * SHEAR_MODULUS));
    let (hardened_elastic, hardened_stress, hardened_plastic, _) =
        compress(hardened, 0.99 * hardened_yield / (2.0 * SHEAR_MODULUS));
    let flow = |yield_stress: f64| {
        let increment =
            (2.0 * SHEAR_MODULUS * strain - yield_stress) / (3.0 * SHEAR_MODULUS + PLASTIC_MODULUS);
        (yield_stress + PLASTIC_MODULUS * increment, increment)
    };
    let (virgin_expected_stress, virgin_increment) = flow(YIELD_STRESS);
    let (hardened_expected_stress, hardened_increment) = flow(hardened_yield);
    // Elastic up to its own yield point: the rate update follows the homogeneous compression
    // up to its time discretisation (measured 9e-10 relative, 1e-6 asserted). The hardened
    // rod stays elastic 50 % longer.
    assert!(
        virgin_elastic < 1e-6,
        "virgin elastic error {virgin_elastic:e}"
    );
    assert!(
        hardened_elastic < 1e-6,
        "hardened elastic error {hardened_elastic:e}"
    );
    // The flow stress and the plastic strain gained against the closed form: the radial
    // return is exact for linear hardening, so only the strain's time discretisation is left
    // (measured 1e-8 on σ_vM, 5e-7 on Δε̄p; 1e-6 and 1e-5 asserted).
    for (stress, expected) in [
        (virgin_stress, virgin_expected_stress),
        (hardened_stress, hardened_expected_stress),
    ] {
        assert!(
            (stress / expected - 1.0).abs() < 1e-6,
            "σ_vM {stress:e} vs {expected:e}"
        );
    }
    for (gained, expected) in [
        (virgin_plastic, virgin_increment),
        (hardened_plastic - pre_strain, hardened_increment),
    ] {
        assert!(
            (gained / expected - 1.0).abs() < 1e-5,
            "Δε̄p {gained:e} vs {expected:e}"
        );
    }
    // And the two differ by far more than that: 2.5 times the virgin rod's plastic strain gain.
    assert!(virgin_plastic > 2.5 * (hardened_plastic - pre_strain));
}

/// Writes `scene` and `table` (as `fields/ep.csv`) into `dir` and loads the scene.
fn load_with_table(dir: &Path, scene: &str, table: &str) -> Result<tlsph_io::Scene, SceneError> {
    super::load_with_table(dir, scene, "fields/ep.csv", table)
}

#[test]
fn a_plastic_strain_table_is_mapped_to_the_particles() {
    // ε̄p = 0.1 X sampled every 0.1: the linear fit gives it back at every particle, the
    // nearest sample a staircase.
    let dir = tempfile::tempdir().unwrap();
    let rows: String = (0..=10)
        .map(|k| format!("{}, {}\n", 0.1 * k as f64, 0.01 * k as f64))
        .collect();
    let table = format!("x, plastic_strain\n{rows}");
    let key = |interpolation: &str| {
        format!("initial_plastic_strain_file = {{ path = \"fields/ep.csv\", reach = 0.15, interpolation = \"{interpolation}\" }}")
    };
    let model = model_1d(load_with_table(dir.path(), &rod(&key("linear")), &table).unwrap());
    let body = &model.bodies[0];
    let strains = body.initial_plastic_strains.as_ref().unwrap();
    for (x, e) in body.positions.iter().zip(strains) {
        assert!((e - 0.1 * x.x).abs() < 1e-15, "ε̄p {e} at {}", x.x);
    }
    // The run starts from it.
    let sim = Simulation::new(model).unwrap();
    assert!((sim.sample(ParticleField::PlasticStrain, 50) - 0.1 * 0.505).abs() < 1e-15);
    let model = model_1d(load_with_table(dir.path(), &rod(&key("nearest")), &table).unwrap());
    // X = 0.505 is nearest the sample at 0.5.
    assert_eq!(
        model.bodies[0].initial_plastic_strains.as_ref().unwrap()[50],
        0.05
    );
    // `tlsph particles` reads the scene without its tables, so the table need not exist.
    fs::remove_file(dir.path().join("fields/ep.csv")).unwrap();
    assert!(load_scene(&dir.path().join("scene.toml")).is_err());
    let scene = tlsph_io::load_scene_without_field_tables(&dir.path().join("scene.toml"));
    assert!(model_1d(scene.unwrap()).bodies[0]
        .initial_plastic_strains
        .is_none());
    // Nor is a stress above the virgin yield stress refused there: without the table the
    // particles' yield stress is not known.
    let key = "initial_plastic_strain_file = { path = \"fields/ep.csv\" }";
    let stressed = rod(&format!("{key}\ninitial_stress = {{ xx = -0.0055 }}"));
    fs::write(dir.path().join("scene.toml"), stressed).unwrap();
    assert!(tlsph_io::load_scene_without_field_tables(&dir.path().join("scene.toml")).is_ok());
}

#[test]
fn plastic_strain_errors_name_the_field_and_the_particle_or_line() {
    let dir = tempfile::tempdir().unwrap();
    let load = |extra: &str, material: &str| {
        let scene = rod(extra).replace("model = \"elastic-plastic\"", material);
        parse_scene(&scene, "rod.toml").unwrap_err()
    };
    let ep = "model = \"elastic-plastic\"";
    let e = load("initial_plastic_strain = -0.1", ep);
    assert_eq!(e.field, "body[rod].initial_plastic_strain", "{e}");
    assert!(e.message.contains("finite number ≥ 0, got -0.1"), "{e}");
    // A linear-elastic material has no plastic strain.
    let elastic = "model = \"linear-elastic\"";
    let scene = rod("initial_plastic_strain = 0.1")
        .replace("model = \"elastic-plastic\"", elastic)
        .replace("yield_stress = 0.004\nplastic_modulus = 0.1\n", "");
    let e = parse_scene(&scene, "rod.toml").unwrap_err();
    assert_eq!(e.field, "body[rod].initial_plastic_strain", "{e}");
    assert!(e.message.contains("has no plastic strain"), "{e}");
    // At or beyond a max-plastic-strain failure law's limit the particle would start failed.
    let failing = format!("{ep}\nfailure = {{ model = \"max-plastic-strain\", limit = 0.2 }}");
    let e = load("initial_plastic_strain = 0.2", &failing);
    assert_eq!(e.field, "body[rod].initial_plastic_strain", "{e}");
    assert!(
        e.message
            .contains("the particle at [0.005] starts at plastic strain 0.2")
            && e.message.contains("failure strain"),
        "{e}"
    );
    assert!(parse_scene(
        &rod("initial_plastic_strain = 0.19").replace(ep, &failing),
        "rod.toml"
    )
    .is_ok());
    // A table cell below 0 names its line; both keys together are refused.
    let key = "initial_plastic_strain_file = { path = \"fields/ep.csv\", reach = 0.6 }";
    let e = load_with_table(
        dir.path(),
        &rod(key),
        "x, plastic_strain\n0.0, 0.1\n1.0, -0.1\n",
    )
    .unwrap_err();
    assert_eq!(e.field, "body[rod].initial_plastic_strain_file.path", "{e}");
    assert!(
        e.message.contains("line 3: `plastic_strain` must be ≥ 0"),
        "{e}"
    );
    let both = rod(&format!("{key}\ninitial_plastic_strain = 0.1"));
    let e = load_with_table(dir.path(), &both, "x, plastic_strain\n0.5, 0.1\n").unwrap_err();
    assert_eq!(e.field, "body[rod].initial_plastic_strain_file", "{e}");
    assert!(
        e.message
            .contains("`initial_plastic_strain` cannot be declared with it"),
        "{e}"
    );
}

#[test]
fn a_pre_strain_admits_an_initial_stress_up_to_its_raised_yield_stress() {
    // σ_xx = −0.0055 in uniaxial strain (1D): von Mises 0.0055, above σ_y0 = 0.004 and below
    // σ_y(0.02) = 0.006.
    let stress = "initial_stress = { xx = -0.0055 }";
    let e = parse_scene(&rod(stress), "rod.toml").unwrap_err();
    assert!(
        e.message.contains("exceeds the initial yield stress 4e-3"),
        "{e}"
    );
    let hardened = rod(&format!("{stress}\ninitial_plastic_strain = 0.02"));
    let model = model_1d(parse_scene(&hardened, "rod.toml").unwrap());
    let sim = Simulation::new(model).unwrap();
    assert_eq!(sim.sample(ParticleField::Stress(0, 0), 10), -0.0055);
    // Still refused above the raised yield stress, which the message names.
    let above = rod("initial_stress = { xx = -0.0065 }\ninitial_plastic_strain = 0.02");
    let e = parse_scene(&above, "rod.toml").unwrap_err();
    assert!(
        e.message
            .contains("exceeds the yield stress at its initial plastic strain 0.02 6e-3"),
        "{e}"
    );
}
