//! `initial_velocity_file`: an initial velocity field read from a CSV table of sample points.

use std::fmt::Write as _;
use std::fs;
use std::path::Path;
use tlsph_io::{load_scene, parse_scene, DimensionModel, SceneError};
use tlsph_math::Vector;
use tlsph_solver::{Model, Simulation};

/// A 1D rod 0 ≤ X ≤ 1 (ρ = 1, E = 0.9, ν = 0.2, so the uniaxial-strain wave speed c = 1),
/// spacing 0.01, held at X = 0 by fixing its first particle; `velocity` is the lines of the
/// body table that set its initial velocity.
fn rod(velocity: &str) -> String {
    format!(
        r#"
[simulation]
dimension = 1
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 1.5

[[material]]
name = "m"
model = "linear-elastic"
density = 1.0
youngs_modulus = 0.9
poisson_ratio = 0.2

[[body]]
name = "rod"
material = "m"
spacing = 0.01
box = {{ min = [0.0], max = [1.0] }}
{velocity}

[[boundary]]
name = "root"
body = "rod"
box = {{ min = [-1.0], max = [0.01] }}
fixed = true

[output]
dir = "out"
"#
    )
}

const KEY: &str = "initial_velocity_file = { path = \"fields/velocity.csv\" }";

/// Writes `scene` and `table` (as `fields/velocity.csv`) into `dir` and loads the scene.
fn load_with_table(dir: &Path, scene: &str, table: &str) -> Result<tlsph_io::Scene, SceneError> {
    super::load_with_table(dir, scene, "fields/velocity.csv", table)
}

fn model_1d(scene: tlsph_io::Scene) -> Model<1> {
    match scene.model {
        DimensionModel::One(m) => m,
        _ => unreachable!("a 1D scene"),
    }
}

/// The table `vx, x` of `velocity` at `points` (shortest round-trip formatting, so the
/// numbers read back exactly; the columns in another order than the coordinates first).
fn table_of(points: &[Vector<1>], velocity: impl Fn(f64) -> f64) -> String {
    let mut table = String::from("# a comment line\nvx, x\n");
    for x in points {
        writeln!(table, "{}, {}", velocity(x.x), x.x).unwrap();
    }
    table
}

#[test]
fn a_linear_field_read_at_the_particles_is_the_declared_velocity_gradient_to_the_bit() {
    let dir = tempfile::tempdir().unwrap();
    let declared = "velocity = [0.01]\nvelocity_gradient = [[-0.02]]\nvelocity_origin = [0.3]";
    let linear = model_1d(parse_scene(&rod(declared), "rod.toml").unwrap());
    let body = &linear.bodies[0];
    let mut table = String::from("vx, x\n");
    for (x, v) in body.positions.iter().zip(&body.velocities) {
        writeln!(table, "{}, {}", v.x, x.x).unwrap();
    }
    let from_file = model_1d(load_with_table(dir.path(), &rod(KEY), &table).unwrap());
    assert_eq!(from_file.bodies[0].velocities, body.velocities);
    // Not a field of zeros: from 0.01 + 0.02 × 0.295 at the root to 0.01 − 0.02 × 0.695.
    assert!(body.velocities[0].x > 0.0158 && body.velocities[99].x < -0.0038);
}

#[test]
fn a_rod_started_in_its_first_mode_from_a_file_swings_with_the_mode_s_period_and_amplitude() {
    // v(X) = V sin(πX/2L), the first mode of a rod fixed at X = 0 and free at X = L: the free
    // end moves as u = (V/ω) sin ωt with ω = πc/2L, so it first stops at t = L/c = 1 with
    // u = 2V/π. A shape's velocity keys give only linear fields; this one comes from a file.
    let dir = tempfile::tempdir().unwrap();
    let v0 = 1.0e-3;
    let template = model_1d(parse_scene(&rod(""), "rod.toml").unwrap());
    let mode = |x: f64| v0 * (std::f64::consts::FRAC_PI_2 * x).sin();
    let table = table_of(&template.bodies[0].positions, mode);
    let model = model_1d(load_with_table(dir.path(), &rod(KEY), &table).unwrap());
    let mut sim = Simulation::new(model).unwrap();
    let tip = sim.n_particles() - 1;
    let (mut peak, mut peak_time) = (0.0_f64, 0.0);
    while !sim.finished() {
        sim.step().unwrap();
        let u = sim.displacements()[tip].x;
        if u > peak {
            (peak, peak_time) = (u, sim.time());
        }
    }
    // Measured: peak 0.9994 of 2V/π at t = 0.993. The fixed particle sits at X = 0.005, so
    // the rod is 0.5 % short (ω 0.5 % high), and the peak is read at steps Δt ≈ 0.0036 apart
    // on a flat crest: 1 % on the amplitude and 1.5 % on the time cover both, and a wrong or
    // missing field (zero, or the mode of another length) is far outside.
    let expected = 2.0 * v0 / std::f64::consts::PI;
    assert!(
        (peak / expected - 1.0).abs() < 0.01,
        "peak {peak:e} vs {expected:e}"
    );
    assert!((peak_time - 1.0).abs() < 0.015, "peak at t = {peak_time}");
}

/// Largest |v − mode| over the rod's particles, over V, and the free end's first peak
/// displacement over 2V/π, for the first mode read from a table of 11 samples (X = 0, 0.1,
/// …, 1: one per 10 particles) mapped with `interpolation`.
fn coarse_mode(interpolation: &str) -> (f64, f64) {
    let dir = tempfile::tempdir().unwrap();
    let v0 = 1.0e-3;
    let mode = |x: f64| v0 * (std::f64::consts::FRAC_PI_2 * x).sin();
    let samples: Vec<Vector<1>> = (0..=10).map(|k| Vector::<1>::new(0.1 * k as f64)).collect();
    let key = format!(
        "initial_velocity_file = {{ path = \"fields/velocity.csv\", reach = 0.15, interpolation = \"{interpolation}\" }}"
    );
    let model =
        model_1d(load_with_table(dir.path(), &rod(&key), &table_of(&samples, mode)).unwrap());
    let body = &model.bodies[0];
    let field_error = body
        .positions
        .iter()
        .zip(&body.velocities)
        .map(|(x, v)| (v.x - mode(x.x)).abs() / v0)
        .fold(0.0, f64::max);
    let mut sim = Simulation::new(model).unwrap();
    let tip = sim.n_particles() - 1;
    let mut peak = 0.0_f64;
    while !sim.finished() {
        sim.step().unwrap();
        peak = peak.max(sim.displacements()[tip].x);
    }
    (field_error, peak / (2.0 * v0 / std::f64::consts::PI))
}

#[test]
fn a_coarse_table_mapped_linearly_gives_the_mode_where_the_nearest_sample_gives_steps() {
    // Between samples 0.1 apart, a linear fit of V sin(πX/2) is off by at most about
    // |f''| h²/8 = 2.5 V × 0.01/8 = 0.003 V (the fit over 3 samples adds a similar amount);
    // the nearest sample is off by up to |f'| h/2 = 1.6 V × 0.05 = 0.08 V.
    // Measured: 0.0046 V and 0.071 V. The peaks, 0.9956 (linear) and 0.9981 (nearest) of
    // 2V/π, differ less: the steps average out over the rod, the field pointwise does not.
    let (linear_error, linear_peak) = coarse_mode("linear");
    let (nearest_error, _) = coarse_mode("nearest");
    assert!(
        linear_error < 0.008,
        "linear: field off by {linear_error} V"
    );
    assert!(
        nearest_error > 0.05,
        "nearest: field off by {nearest_error} V"
    );
    // The rod swings with the mode's amplitude (tolerance as for the table at the particles).
    assert!(
        (linear_peak - 1.0).abs() < 0.01,
        "linear: peak {linear_peak} of 2V/π"
    );
}

#[test]
fn tlsph_check_tells_how_a_table_met_the_particles() {
    // The rod's particles lie at X = 0.005, 0.015, ..., 0.995; the table has 16 samples every
    // 0.1 from 0 to 1.5, reaching half a rod past its end. Nearest sample within 0.06: each
    // particle takes the nearest multiple of 0.1, at most 0.045 away, and the samples at
    // 1.1–1.5 serve none (5). Linear fit within 0.25: a particle at the rod's end fits the 3
    // samples 0, 0.1, 0.2; inside, 5; the samples at 1.1 and 1.2 are within 0.25 of the last
    // particles, so only 1.3–1.5 serve none (3).
    let samples: Vec<Vector<1>> = (0..=15).map(|k| Vector::<1>::new(0.1 * k as f64)).collect();
    let table = table_of(&samples, |x| 0.1 * x);
    let summary = |interpolation: &str, reach: &str| {
        let dir = tempfile::tempdir().unwrap();
        let key = format!(
            "initial_velocity_file = {{ path = \"fields/velocity.csv\", reach = {reach}, interpolation = \"{interpolation}\" }}"
        );
        let scene = load_with_table(dir.path(), &rod(&key), &table).unwrap();
        let overview = scene.overview().to_string();
        assert_eq!(scene.field_tables.len(), 1);
        (scene.field_tables[0].clone(), overview)
    };
    let (nearest, printed) = summary("nearest", "0.06");
    assert_eq!(nearest.field, "body[rod].initial_velocity_file");
    assert!(nearest.path.ends_with("fields/velocity.csv"));
    assert_eq!(
        (nearest.samples, nearest.interpolation, nearest.reach),
        (16, "nearest", 0.06)
    );
    assert_eq!(nearest.samples_per_particle, (1, 1));
    assert!((nearest.farthest_nearest_sample - 0.045).abs() < 1e-12);
    assert_eq!(nearest.unused_samples, 5);
    assert!(
        printed.contains("body[rod].initial_velocity_file `")
            && printed.contains("velocity.csv`: 16 samples, nearest sample within 6.0000e-2; the nearest sample at most 4.5000e-2 from a particle; 5 samples used by no particle"),
        "{printed}"
    );
    let (linear, printed) = summary("linear", "0.25");
    assert_eq!(linear.samples_per_particle, (3, 5));
    assert_eq!(linear.unused_samples, 3);
    assert!(
        printed.contains(
            "16 samples, linear fit to the samples within 2.5000e-1: 3 to 5 samples per particle"
        ),
        "{printed}"
    );
    // Without its tables a scene has nothing to tell.
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir_all(dir.path().join("fields")).unwrap();
    fs::write(dir.path().join("scene.toml"), rod(KEY)).unwrap();
    let scene = tlsph_io::load_scene_without_field_tables(&dir.path().join("scene.toml")).unwrap();
    assert!(scene.field_tables.is_empty());
}

#[test]
fn linear_interpolation_s_default_reach_takes_in_a_table_at_the_particles() {
    // Twice the spacing: each particle fits its own sample and its neighbours', so a linear
    // field comes back to round-off (the nearest-sample default, one spacing, gives it
    // exactly).
    let dir = tempfile::tempdir().unwrap();
    let template = model_1d(parse_scene(&rod(""), "rod.toml").unwrap());
    let table = table_of(&template.bodies[0].positions, |x| 0.3 - 0.2 * x);
    let key =
        "initial_velocity_file = { path = \"fields/velocity.csv\", interpolation = \"linear\" }";
    let model = model_1d(load_with_table(dir.path(), &rod(key), &table).unwrap());
    for (x, v) in model.bodies[0]
        .positions
        .iter()
        .zip(&model.bodies[0].velocities)
    {
        assert!(
            (v.x - (0.3 - 0.2 * x.x)).abs() < 1e-15,
            "{} at {}",
            v.x,
            x.x
        );
    }
}

#[test]
fn velocity_file_errors_name_the_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    // Samples every spacing from 0.005 to 0.995: the rod's particles.
    let rows: String = (0..100)
        .map(|k| format!("{}, 0.0\n", 0.005 + 0.01 * k as f64))
        .collect();
    let good = format!("x, vx\n{rows}");
    for (extra, scene_key, table, field, message) in [
        (
            "",
            KEY,
            "x, vx\n0.5, nan\n",
            "path",
            "line 2: `vx` must be a finite number",
        ),
        (
            "",
            KEY,
            "x\n0.5\n",
            "path",
            "names no field column; give at least one of vx",
        ),
        ("", KEY, "x, vx, vy\n", "path", "unknown column `vy`"),
        (
            "",
            KEY,
            "x, vx\n0.5, 0.0\n",
            "",
            "particle 0 at [0.005] has no sample within reach",
        ),
        (
            "",
            "initial_velocity_file = { path = \"fields/velocity.csv\", reach = 0.0 }",
            "x, vx\n",
            "reach",
            "",
        ),
        (
            "",
            "initial_velocity_file = { path = \"fields/velocity.csv\", interpolation = \"cubic\" }",
            &good,
            "interpolation",
            "unknown interpolation `cubic` (expected \"nearest\" or \"linear\")",
        ),
        (
            "",
            "initial_velocity_file = { path = \"fields/velocity.csv\", reach = 0.005, interpolation = \"linear\" }",
            &good,
            "",
            "particle 0 at [0.005]: the samples within reach 5e-3 (1 of them) lie on one point",
        ),
        (
            "velocity = [0.1]",
            KEY,
            &good,
            "",
            "no shape of the body can declare `velocity`",
        ),
        (
            "velocity_origin = [0.1]",
            KEY,
            &good,
            "",
            "no shape of the body can declare `velocity_origin`",
        ),
    ] {
        let scene = rod(&format!("{extra}\n{scene_key}"));
        let e = load_with_table(dir.path(), &scene, table).unwrap_err();
        let expected_field = match field {
            "" => "body[rod].initial_velocity_file".to_string(),
            sub => format!("body[rod].initial_velocity_file.{sub}"),
        };
        assert_eq!(e.field, expected_field, "{table}: {e}");
        assert!(e.message.contains(message), "{table}: {e}");
        let key_line = scene
            .lines()
            .position(|l| l.starts_with("initial_velocity_file"))
            .unwrap()
            + 1;
        assert_eq!(e.line, Some(key_line), "{e}");
        if field == "path" {
            assert!(e.message.contains("velocity.csv"), "names the table: {e}");
        }
    }
    // A uniform field of 1e200 everywhere names the first particle and its sample's line.
    let huge: String = (0..100)
        .map(|k| format!("{}, 1e200\n", 0.005 + 0.01 * k as f64))
        .collect();
    let e = load_with_table(dir.path(), &rod(KEY), &format!("# c\nx, vx\n{huge}")).unwrap_err();
    assert!(
        e.message.contains("particle 0 at [0.005] (line 3 of `")
            && e.message
                .contains("): the kinetic energy ½ρV|v|² of its velocity [1e200]")
            && !e.message.contains("particle 0:"),
        "{e}"
    );
    // With ρ = 20, each particle's ½ρV|v|² = ½ × 20 × 0.01 × 1e308 = 1e307 is finite; the
    // sum over the rod's 100 particles is not.
    let large: String = (0..100)
        .map(|k| format!("{}, 1e154\n", 0.005 + 0.01 * k as f64))
        .collect();
    let dense = rod(KEY).replace("density = 1.0", "density = 20.0");
    let e = load_with_table(dir.path(), &dense, &format!("x, vx\n{large}")).unwrap_err();
    assert_eq!(e.field, "body[rod].initial_velocity_file", "{e}");
    assert!(
        e.message
            .contains("the body's kinetic energy is not a finite number"),
        "{e}"
    );
}

#[test]
fn a_velocity_file_works_with_body_shape_tables_and_cuts() {
    // Two shapes and a cut: the file sets the velocity of the particles that remain.
    let dir = tempfile::tempdir().unwrap();
    let scene = rod(KEY).replace(
        "box = { min = [0.0], max = [1.0] }",
        "[[body.shape]]\nbox = { min = [0.0], max = [0.5] }\n\n[[body.shape]]\nbox = { min = [0.5], max = [1.0] }\n\n[[body.cut]]\nbox = { min = [0.4], max = [0.6] }\n",
    );
    // The key now sits after the cut table: move it onto the body.
    let scene = scene.replace(&format!("{KEY}\n"), "").replacen(
        "spacing = 0.01\n",
        &format!("spacing = 0.01\n{KEY}\n"),
        1,
    );
    let rows: String = (0..100)
        .map(|k| {
            let x = 0.005 + 0.01 * k as f64;
            format!("{x}, {}\n", 0.1 * x)
        })
        .collect();
    let table = format!("x, vx\n{rows}");
    let model = model_1d(load_with_table(dir.path(), &scene, &table).unwrap());
    let body = &model.bodies[0];
    assert_eq!(body.positions.len(), 80);
    for (x, v) in body.positions.iter().zip(&body.velocities) {
        assert!((v.x - 0.1 * x.x).abs() < 1e-15, "{} at {}", v.x, x.x);
    }
    // A velocity inside one of the shape tables is refused too.
    let with_velocity = scene.replacen(
        "box = { min = [0.5], max = [1.0] }\n",
        "box = { min = [0.5], max = [1.0] }\nvelocity = [0.2]\n",
        1,
    );
    assert_ne!(with_velocity, scene);
    let e = load_with_table(dir.path(), &with_velocity, &table).unwrap_err();
    assert_eq!(e.field, "body[rod].initial_velocity_file", "{e}");
    assert!(
        e.message
            .contains("no shape of the body can declare `velocity`"),
        "{e}"
    );
}

#[test]
fn without_its_tables_a_scene_loads_as_if_the_table_keys_were_absent() {
    // For writing a table's template before the table exists (`tlsph particles`).
    let dir = tempfile::tempdir().unwrap();
    let scene = rod(&format!(
        "{KEY}\ninitial_stress_file = {{ path = \"fields/stress.csv\" }}"
    ));
    fs::write(dir.path().join("scene.toml"), &scene).unwrap();
    let e = load_scene(&dir.path().join("scene.toml")).unwrap_err();
    assert!(e.message.contains("cannot read"), "{e}");
    let loaded = tlsph_io::load_scene_without_field_tables(&dir.path().join("scene.toml"));
    let model = model_1d(loaded.unwrap());
    let plain = model_1d(parse_scene(&rod(""), "rod.toml").unwrap());
    let (body, plain) = (&model.bodies[0], &plain.bodies[0]);
    assert_eq!(body.positions, plain.positions);
    assert_eq!(body.velocities, plain.velocities);
    assert!(body.initial_stresses.is_none());
}
