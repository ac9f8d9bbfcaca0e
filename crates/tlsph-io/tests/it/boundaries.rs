//! `[[boundary]]` in whole runs: each boundary's force history in `boundaries.csv` and its
//! work in `energy.csv`, so the total closes for a driven scene; names that would break the
//! CSV headers are refused at their line.

use super::{energy_rows, error_of, line_of};
use std::fs;
use tlsph_io::{parse_scene, run_scene_to_dir};

/// A 2D steel strip, 10 × 20 mm, clamped along its bottom row and pulled up along its top row
/// at 1 m/s after a smooth 20 µs start (about five transit times of the strip).
const PULLED_STRIP: &str = r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 40.0e-6

[[material]]
name = "steel"
model = "linear-elastic"
density = 7850.0
youngs_modulus = 200.0e9
poisson_ratio = 0.3

[[body]]
name = "strip"
material = "steel"
spacing = 1.0e-3
box = { min = [0.0, 0.0], max = [10.0e-3, 20.0e-3] }

[[boundary]]
name = "clamp"
body = "strip"
box = { min = [-1.0, -1.0], max = [1.0, 1.0e-3] }
fixed = true

[[boundary]]
name = "grip"
body = "strip"
box = { min = [-1.0, 19.0e-3], max = [1.0, 1.0] }
velocity = [0.0, 1.0]
components = ["y"]
ramp_time = 20.0e-6

[output]
dir = "out"
energy_interval = 1.0e-6
"#;

#[test]
fn a_pulled_strip_reports_its_grip_forces_and_the_work_that_closes_the_energy() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let scene = parse_scene(PULLED_STRIP, "strip.toml").unwrap();
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();

    let text = fs::read_to_string(dir.join("boundaries.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time,boundary_clamp_force_x,boundary_clamp_force_y,boundary_clamp_force_z,\
         boundary_grip_force_x,boundary_grip_force_y,boundary_grip_force_z"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 41, "a row per energy sample");
    // The strip is stretched: the grip pulls up, the clamp holds down, and over the second
    // half (after the ramp) their means balance up to the strip's small momentum change
    // (measured 7e-5 of the grip force). Forces are per unit thickness (N/m): the 30 µm grip
    // travel over 19 mm at E/(1 − ν²) = 220 GPa across 10 mm gives about 3.5e6 N/m at the end.
    let late = &rows[20..];
    let mean = |k: usize| late.iter().map(|r| r[k]).sum::<f64>() / late.len() as f64;
    let (clamp_y, grip_y) = (mean(2), mean(5));
    assert!(
        grip_y > 1e5 && clamp_y < -1e5,
        "grip {grip_y:e}, clamp {clamp_y:e}"
    );
    assert!(
        (grip_y + clamp_y).abs() < 0.02 * grip_y,
        "grip {grip_y:e} vs clamp {clamp_y:e}"
    );

    // energy.csv: a column per boundary, the fixed clamp's exactly 0, and the total stays at
    // its start while kinetic + internal energy grows by the grip's work.
    let (rows, grip, total) = energy_rows(&dir, "boundary_grip");
    let (_, clamp, _) = energy_rows(&dir, "boundary_clamp");
    let work = rows.iter().map(|r| -r[grip]).fold(0.0, f64::max);
    let drift = rows
        .iter()
        .map(|r| (r[total] - rows[0][total]).abs())
        .fold(0.0, f64::max);
    assert!(rows.iter().all(|r| r[clamp] == 0.0));
    assert!(work > 0.0);
    // Measured 6e-7 of the work (54.6 J/m) for this smooth start; leaving the column out
    // would be off by all of it.
    assert!(drift < 1e-5 * work, "drift {drift:e} of work {work:e}");
}

#[test]
fn a_boundary_name_that_would_break_the_csv_columns_is_refused_at_its_line() {
    let text = PULLED_STRIP.replace("name = \"grip\"", "name = \"grip, top\"");
    let e = error_of(&text);
    assert_eq!(e.field, "boundary.name", "{e}");
    assert_eq!(e.line, Some(line_of(&text, "grip, top")), "{e}");
    assert!(e.message.contains("boundaries.csv"), "{e}");
}
