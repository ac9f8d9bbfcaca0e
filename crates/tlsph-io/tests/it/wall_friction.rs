//! Wall `friction` and the `[body_force]` ramp in scene files: parsed into the model, bad
//! values named with field and line, and a run writes the friction's force and energy
//! columns, with the total closing.

use super::{energy_rows, error_of, line_of};
use std::fs;
use tlsph_io::{parse_scene, run_scene_to_dir, DimensionModel};
use tlsph_solver::RampShape;

/// A 2D block (10 × 5 at 0.05, c = 1) sliding at 0.05 on a floor with friction 0.5 under a
/// gravity of 0.01 that rises over 2 time units.
const SLIDER: &str = r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 6.0

[[material]]
name = "unit"
model = "linear-elastic"
density = 1.0
youngs_modulus = 0.9
poisson_ratio = 0.2

[[body]]
name = "block"
material = "unit"
spacing = 0.05
box = { min = [0.0, 0.0], max = [0.5, 0.25] }
velocity = [0.05, 0.0]

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
friction = 0.5

[body_force]
acceleration = [0.0, -0.01]
ramp_time = 2.0
ramp_shape = "linear"

[output]
dir = "out"
"#;

#[test]
fn wall_friction_and_the_body_force_ramp_become_the_description() {
    let scene = parse_scene(SLIDER, "slider.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert_eq!(model.effects.walls[0].friction, 0.5);
    let ramp = model.effects.body_force.as_ref().unwrap().ramp.unwrap();
    assert_eq!((ramp.duration, ramp.shape), (2.0, RampShape::Linear));
    // Without the keys: frictionless, and the full body force from t = 0.
    let plain = SLIDER
        .replace("friction = 0.5\n", "")
        .replace("ramp_time = 2.0\nramp_shape = \"linear\"\n", "");
    let scene = parse_scene(&plain, "slider.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert_eq!(model.effects.walls[0].friction, 0.0);
    assert_eq!(model.effects.body_force.as_ref().unwrap().ramp, None);
}

#[test]
fn friction_and_ramp_errors_name_the_field_and_line() {
    for (from, to, field, message) in [
        (
            "friction = 0.5",
            "friction = -0.5",
            "wall[floor].friction",
            "≥ 0",
        ),
        (
            "ramp_time = 2.0",
            "ramp_time = 0.0",
            "body_force.ramp_time",
            "> 0",
        ),
        (
            "ramp_shape = \"linear\"",
            "ramp_shape = \"cubic\"",
            "body_force.ramp_shape",
            "unknown ramp shape",
        ),
        (
            "ramp_time = 2.0\n",
            "",
            "body_force.ramp_shape",
            "needs `ramp_time`",
        ),
    ] {
        let text = SLIDER.replace(from, to);
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert!(e.message.contains(message), "{e}");
        let needle = if to.is_empty() { "ramp_shape" } else { to };
        assert_eq!(e.line, Some(line_of(&text, needle)), "{e}");
    }
}

#[test]
fn a_friction_run_writes_its_force_and_energy_columns_and_the_total_closes() {
    let scene = parse_scene(SLIDER, "slider.toml").unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let walls = fs::read_to_string(dir.join("walls.csv")).unwrap();
    let header = walls.lines().next().unwrap();
    assert_eq!(
        header,
        "time,wall_floor_force_x,wall_floor_force_y,wall_floor_force_z,\
         wall_floor_friction_force_x,wall_floor_friction_force_y,wall_floor_friction_force_z"
    );
    // Friction on the particles opposes the sliding (+x) and stays within μ of the normal
    // force at every sample.
    for line in walls.lines().skip(1) {
        let r: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!(
            r[4] <= 0.0 && r[4].abs() <= 0.5 * r[2] * (1.0 + 1e-12),
            "{line}"
        );
    }
    let (rows, column, total) = energy_rows(&dir, "wall_floor_friction");
    // Kinetic energy 0.5 · 0.125 · 0.05² = 1.6e-4 at the start; the friction column only
    // grows (it books dissipation: 75 % of it by t = 6), and the total closes to within 1 %
    // of it (measured 0.16 %: the penalty wall's leap-frog error).
    let e0 = 0.5 * 0.125 * 0.05 * 0.05;
    let mut last = 0.0;
    for r in &rows {
        assert!(r[column] >= last - 1e-15 * e0, "{r:?}");
        last = r[column];
        assert!((r[total] - rows[0][total]).abs() < 0.01 * e0, "{r:?}");
    }
    assert!(last > 0.5 * e0, "friction dissipated only {last:e}");
}
