//! Wall `friction`, wall motion (`velocity`, `ramp_time`, `ramp_shape`) and the
//! `[body_force]` ramp in scene files: parsed into the model, bad values named with field and
//! line, and a run writes the friction's force and energy columns, with the total closing,
//! also when the floor slides under the block.

use super::{energy_rows, error_of, line_of};
use std::fs;
use tlsph_io::{parse_scene, run_scene_to_dir, DimensionModel};
use tlsph_solver::{
    Amplitude, AmplitudeTable, FrictionCoefficients, RampShape, TableShape, VelocityRamp,
};

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
    assert_eq!(
        model.effects.walls[0].friction,
        FrictionCoefficients::single(0.5)
    );
    let with_static = SLIDER.replace(
        "friction = 0.5\n",
        "friction = 0.5\nstatic_friction = 0.7\nfriction_decay = 3.0\n",
    );
    let scene = parse_scene(&with_static, "slider.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert_eq!(
        model.effects.walls[0].friction,
        FrictionCoefficients {
            kinetic: 0.5,
            static_coefficient: 0.7,
            decay: Some(3.0)
        }
    );
    assert_eq!(
        model.effects.body_force.as_ref().unwrap().amplitude,
        Some(Amplitude::Ramp(VelocityRamp {
            duration: 2.0,
            shape: RampShape::Linear
        }))
    );
    // Without the keys: frictionless, and the full body force from t = 0.
    let plain = SLIDER
        .replace("friction = 0.5\n", "")
        .replace("ramp_time = 2.0\nramp_shape = \"linear\"\n", "");
    let scene = parse_scene(&plain, "slider.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert_eq!(
        model.effects.walls[0].friction,
        FrictionCoefficients::single(0.0)
    );
    assert_eq!(model.effects.body_force.as_ref().unwrap().amplitude, None);
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
            "friction = 0.5",
            "friction = 0.5\nstatic_friction = 0.4",
            "wall[floor].static_friction",
            "≥ the (kinetic) `friction` 0.5",
        ),
        (
            "friction = 0.5",
            "friction = 0.5\nstatic_friction = -1.0",
            "wall[floor].static_friction",
            "≥ 0",
        ),
        (
            "friction = 0.5",
            "friction = 0.5\nstatic_friction = 0.5\nfriction_decay = 1.0",
            "wall[floor].friction_decay",
            "needs a `static_friction` above `friction` 0.5",
        ),
        (
            "friction = 0.5",
            "friction = 0.5\nstatic_friction = 0.6\nfriction_decay = inf",
            "wall[floor].friction_decay",
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
        // The key's own line (the last line of a replacement that adds one).
        let needle = to.lines().last().unwrap_or("ramp_shape");
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

#[test]
fn a_sliding_floor_parses_drags_the_block_along_and_the_total_closes() {
    // The block of `SLIDER` at rest on a floor that slides at −0.05: seen from the floor, it
    // is `SLIDER`'s block braked from 0.05, so its velocity less the floor's matches that
    // run's velocity (and `walls.csv` gives the floor's displacement). The runs take slightly
    // different steps (the CFL step counts each particle's own speed): measured 1.2e-5 of
    // 0.05 apart at t = 6 with the block still sliding at half its speed; bound 1e-3. The floor's work (its normal and friction
    // forces) is booked in its columns, so the total stays within 1e-3 of the relative
    // kinetic energy (measured 2.6e-5).
    let conveyor = SLIDER.replace("velocity = [0.05, 0.0]\n", "").replace(
        "friction = 0.5\n",
        "friction = 0.5\nvelocity = [-0.05, 0.0]\n",
    );
    let with_ramp = conveyor.replace(
        "velocity = [-0.05, 0.0]\n",
        "velocity = [-0.05, 0.0]\nramp_time = 0.5\nramp_shape = \"linear\"\n",
    );
    let scene = parse_scene(&with_ramp, "conveyor.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let motion = model.effects.walls[0].motion.as_ref().unwrap();
    assert_eq!((motion.velocity.x, motion.velocity.y), (-0.05, 0.0));
    assert_eq!(
        motion.amplitude,
        Some(Amplitude::Ramp(VelocityRamp {
            duration: 0.5,
            shape: RampShape::Linear
        }))
    );
    let final_velocity = |text: &str, name: &str| {
        let scene = parse_scene(text, name).unwrap();
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("out");
        run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
        let momentum = fs::read_to_string(dir.join("momentum.csv")).unwrap();
        let last: Vec<f64> = momentum
            .lines()
            .last()
            .unwrap()
            .split(',')
            .map(|x| x.parse().unwrap())
            .collect();
        let (rows, _, total) = energy_rows(&dir, "wall_floor_friction");
        let walls = fs::read_to_string(dir.join("walls.csv")).unwrap();
        (last[1] / 0.125, rows, total, walls)
    };
    let (braked, _, _, _) = final_velocity(SLIDER, "slider.toml");
    let (dragged, rows, total, walls) = final_velocity(&conveyor, "conveyor.toml");
    // walls.csv tracks the moving floor after the force columns: d = v t (no ramp here).
    assert!(
        walls.lines().next().unwrap().ends_with(
            ",wall_floor_friction_force_z,wall_floor_displacement_x,\
             wall_floor_displacement_y,wall_floor_displacement_z"
        ),
        "{walls}"
    );
    for line in walls.lines().skip(1) {
        let r: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert_eq!(r[7..], [-0.05 * r[0], 0.0, 0.0], "{line}");
    }
    assert!(braked > 0.005, "still sliding: {braked}");
    assert!(
        ((dragged + 0.05) - braked).abs() < 1e-3 * 0.05,
        "dragged {dragged}, braked {braked}"
    );
    let e0 = 0.5 * 0.125 * 0.05 * 0.05;
    for r in &rows {
        assert!((r[total] - rows[0][total]).abs() < 1e-3 * e0, "{r:?}");
    }
}

#[test]
fn wall_motion_errors_name_the_field_and_line() {
    let moving = SLIDER.replace(
        "friction = 0.5\n",
        "friction = 0.5\nvelocity = [-0.05, 0.0]\nramp_time = 0.5\n",
    );
    for (from, to, field, message, needle) in [
        (
            "velocity = [-0.05, 0.0]\nramp",
            "velocity = [-0.05]\nramp",
            "wall[floor].velocity",
            "2",
            "velocity = [-0.05]",
        ),
        (
            "velocity = [-0.05, 0.0]\nramp",
            "ramp",
            "wall[floor].ramp_time",
            "a fixed wall has nothing to scale in time",
            "ramp_time = 0.5",
        ),
        (
            "ramp_time = 0.5\n",
            "ramp_time = -1.0\n",
            "wall[floor].ramp_time",
            "> 0",
            "ramp_time = -1.0",
        ),
        (
            "ramp_time = 0.5\n",
            "ramp_shape = \"smooth\"\n",
            "wall[floor].ramp_shape",
            "needs `ramp_time`",
            "ramp_shape = \"smooth\"",
        ),
    ] {
        let text = moving.replace(from, to);
        assert_ne!(text, moving);
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert!(e.message.contains(message), "{e}");
        assert_eq!(e.line, Some(line_of(&text, needle)), "{e}");
    }
}

#[test]
fn a_floor_sliding_across_a_symmetry_plane_with_friction_is_refused() {
    // With a symmetry plane x = 0, a floor (normal y) sliding along x would drag the mirrored
    // half of the block the other way. Frictionless, the sliding is not felt and the scene
    // is accepted; a platen moving along its own normal is mirrored into a second platen
    // moving as its mirror image, a symmetric model, and is accepted too.
    let mirrored = format!(
        "{}\n[[symmetry_plane]]\naxis = \"x\"\nposition = 0.0\n",
        SLIDER.replace("velocity = [0.05, 0.0]\n", "")
    );
    let sliding = mirrored.replace(
        "friction = 0.5\n",
        "friction = 0.5\nvelocity = [-0.05, 0.0]\n",
    );
    let e = error_of(&sliding);
    assert_eq!(e.field, "wall[floor].velocity", "{e}");
    assert!(e.message.contains("symmetry plane"), "{e}");
    assert_eq!(e.line, Some(line_of(&sliding, "velocity = [-0.05, 0.0]")));
    assert!(parse_scene(&sliding.replace("friction = 0.5\n", ""), "s.toml").is_ok());
    let platen = mirrored.replace(
        "[[wall]]\n",
        "[[wall]]\nname = \"platen\"\npoint = [0.6, 0.0]\nnormal = [-1.0, 0.0]\n\
         friction = 0.5\nvelocity = [-0.01, 0.0]\n\n[[wall]]\n",
    );
    assert!(parse_scene(&platen, "p.toml").is_ok());
}

/// `SLIDER` with a grip pulling the block's top row up at 0.01 under the boundary keys
/// `keys`.
fn slider_with_grip(keys: &str) -> String {
    format!(
        "{SLIDER}\n[[boundary]]\nname = \"grip\"\nbody = \"block\"\nbox = {{ min = [0.0, 0.2], max = [0.5, 0.25] }}\nvelocity = [0.0, 0.01]\ncomponents = [\"y\"]\n{keys}\n"
    )
}

#[test]
fn amplitude_tables_parse_for_walls_boundaries_and_the_body_force_and_bad_ones_are_named() {
    let table = "amplitude = [[0.0, 0.0], [1.0, 1.0], [3.0, -0.5]]\n";
    let text = slider_with_grip(table)
        .replace(
            "friction = 0.5\n",
            &format!("friction = 0.5\nvelocity = [0.02, 0.0]\n{table}"),
        )
        .replace("ramp_time = 2.0\nramp_shape = \"linear\"\n", table);
    let scene = parse_scene(&text, "slider.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let expected = Some(Amplitude::Table(
        AmplitudeTable::new(vec![(0.0, 0.0), (1.0, 1.0), (3.0, -0.5)]).unwrap(),
    ));
    assert_eq!(model.boundaries[0].amplitude, expected);
    assert_eq!(
        model.effects.walls[0].motion.as_ref().unwrap().amplitude,
        expected
    );
    assert_eq!(
        model.effects.body_force.as_ref().unwrap().amplitude,
        expected
    );
    // Smooth steps between the points, on request.
    let scene = parse_scene(
        &slider_with_grip(&format!("{table}amplitude_shape = \"smooth-step\"")),
        "slider.toml",
    )
    .unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let Some(Amplitude::Table(grip)) = &model.boundaries[0].amplitude else {
        panic!("a table")
    };
    assert_eq!(grip.shape(), TableShape::SmoothStep);
    // Each mistake is named with its table's key and line.
    for (text, field, needle) in [
        // A ramp and a table both.
        (
            slider_with_grip(&format!("ramp_time = 1.0\n{table}")),
            "boundary[grip].ramp_time",
            "ramp_time = 1.0",
        ),
        (
            slider_with_grip(&format!("{table}amplitude_shape = \"cubic\"")),
            "boundary[grip].amplitude_shape",
            "amplitude_shape =",
        ),
        // A shape without a table.
        (
            slider_with_grip("ramp_time = 1.0\namplitude_shape = \"linear\""),
            "boundary[grip].amplitude_shape",
            "amplitude_shape =",
        ),
        (
            slider_with_grip("amplitude = [[0.0, 0.0], [1.0]]"),
            "boundary[grip].amplitude",
            "amplitude =",
        ),
        (
            slider_with_grip("amplitude = [[0.0, 0.0], [2.0, 1.0], [1.0, 0.0]]"),
            "boundary[grip].amplitude",
            "amplitude =",
        ),
        (
            SLIDER.replace("friction = 0.5\n", &format!("friction = 0.5\n{table}")),
            "wall[floor].amplitude",
            "amplitude =",
        ),
        (
            SLIDER.replace(
                "ramp_time = 2.0\nramp_shape = \"linear\"\n",
                "amplitude = [[-1.0, 0.0], [1.0, 1.0]]\n",
            ),
            "body_force.amplitude",
            "amplitude =",
        ),
    ] {
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert_eq!(e.line, Some(line_of(&text, needle)), "{e}");
    }
    // A fixed boundary has no velocity to scale.
    let fixed = slider_with_grip(table).replace(
        "velocity = [0.0, 0.01]\ncomponents = [\"y\"]",
        "fixed = true",
    );
    let e = error_of(&fixed);
    assert_eq!(e.field, "boundary[grip].amplitude", "{e}");
    assert!(e.message.contains("fixed boundary"), "{e}");
}

#[test]
fn a_floor_run_with_an_amplitude_table_tracks_the_integral_of_its_table() {
    // `SLIDER`'s floor slides at −0.05 r(t) with r: 0 → 1 over 1, held to 3, back to −0.5 at
    // 4, then held: walls.csv's displacement columns are −0.05 ∫₀ᵗ r at every sample (the
    // solver's own shift, so to round-off), and the total still closes (the floor's work is
    // booked), within 1e-3 of the block's initial kinetic energy (measured 1.1e-5).
    let text = SLIDER.replace(
        "friction = 0.5\n",
        "friction = 0.5\nvelocity = [-0.05, 0.0]\namplitude = [[0.0, 0.0], [1.0, 1.0], [3.0, 1.0], [4.0, -0.5]]\n",
    );
    let scene = parse_scene(&text, "table.toml").unwrap();
    let table = AmplitudeTable::new(vec![(0.0, 0.0), (1.0, 1.0), (3.0, 1.0), (4.0, -0.5)]).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let walls = fs::read_to_string(dir.join("walls.csv")).unwrap();
    let mut samples = 0;
    for line in walls.lines().skip(1) {
        let r: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let expected = -0.05 * table.integral(r[0]);
        assert!(
            (r[7] - expected).abs() < 1e-15,
            "{line}: expected {expected:e}"
        );
        assert_eq!(r[8..], [0.0, 0.0], "{line}");
        samples += 1;
    }
    assert!(samples > 10, "{samples} samples");
    let (rows, _, total) = energy_rows(&dir, "wall_floor_friction");
    let e0 = 0.5 * 0.125 * 0.05 * 0.05;
    let worst = rows
        .iter()
        .map(|r| (r[total] - rows[0][total]).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "amplitude floor: total within {:.1e} of the initial kinetic energy",
        worst / e0
    );
    assert!(worst < 1e-3 * e0, "total moved {worst:e}");
}

/// Runs `SLIDER` with a roll of radius 1 just below the floor's surface, spinning
/// counter-clockwise with friction 0.5 and the extra `keys`, and returns its `walls.csv`.
fn slider_on_roll(keys: &str) -> String {
    let text = SLIDER.replace(
        "[body_force]",
        &format!(
            "[[wall]]\nname = \"roll\"\nshape = \"ball\"\npoint = [0.275, -1.0]\nradius = 1.0\n\
             friction = 0.5\nspin = 0.05\n{keys}\n[body_force]"
        ),
    );
    let scene = parse_scene(&text, "roll.toml").unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    fs::read_to_string(dir.join("walls.csv")).unwrap()
}

#[test]
fn a_spinning_walls_torque_is_written_after_the_forces() {
    // The slider also rests on a roll of radius 1 just below the floor's surface, spinning
    // counter-clockwise (its top moves along −x, against the block). The roll's friction
    // torque about its spin gets a column of its own at the end of walls.csv; the floor, which
    // does not spin, has none. The roll touches the block at the surface points on top of it,
    // so over the run Σ T = −R Σ F_x of its friction (lever (0, R)), within 1/cos of the
    // contact's angle: measured 1.0000 (the block's bottom row touches the roll only near its
    // top, within 0.05 rad); bound 1 %.
    let walls = slider_on_roll("");
    let header: Vec<&str> = walls.lines().next().unwrap().split(',').collect();
    assert_eq!(header.len(), 1 + 4 * 3 + 1, "{header:?}");
    assert_eq!(header[10], "wall_roll_friction_force_x");
    assert_eq!(header[13], "wall_roll_friction_torque");
    assert!(!header
        .iter()
        .any(|h| h.starts_with("wall_floor") && h.ends_with("torque")));
    let (mut torque, mut lever_force) = (0.0, 0.0);
    for line in walls.lines().skip(1) {
        let r: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        torque += r[13];
        lever_force -= 1.0 * r[10];
    }
    println!("Σ T = {torque:.4e}, −R Σ F_x = {lever_force:.4e}");
    assert!(
        torque > 0.0,
        "the roll never dragged the block: Σ T = {torque:e}"
    );
    assert!(
        (torque / lever_force - 1.0).abs() < 0.01,
        "Σ T = {torque:e} against −R Σ F_x = {lever_force:e}"
    );
}

#[test]
fn report_moment_writes_a_walls_moment_vectors_after_the_torques() {
    // The spinning roll of the test above with `report_moment = true`: after its torque come
    // the moments about its centre, of its normal force (`wall_roll_moment_*`) and of its
    // friction (`wall_roll_friction_moment_*`). Its normal forces are radial, so their moment
    // about the centre vanishes to round-off (bound 1e-12 of R times the force); the friction's
    // moment is along z, and its z part is the torque about the spin axis (z, the roll turning
    // counter-clockwise), to round-off.
    let walls = slider_on_roll("report_moment = true\n");
    let header: Vec<&str> = walls.lines().next().unwrap().split(',').collect();
    assert_eq!(header.len(), 1 + 4 * 3 + 1 + 2 * 3, "{header:?}");
    assert_eq!(header[13], "wall_roll_friction_torque");
    assert_eq!(header[14], "wall_roll_moment_x");
    assert_eq!(header[19], "wall_roll_friction_moment_z");
    let mut touched = false;
    for line in walls.lines().skip(1) {
        let r: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let (normal_force, friction_force) = (r[7].hypot(r[8]), r[10].hypot(r[11]));
        touched |= friction_force > 0.0;
        assert!(
            r[14].abs() + r[15].abs() + r[16].abs() <= 1e-12 * normal_force,
            "{line}"
        );
        assert!(r[17] == 0.0 && r[18] == 0.0, "{line}");
        assert!((r[19] - r[13]).abs() <= 1e-12 * friction_force, "{line}");
    }
    assert!(touched, "the roll never touched the block");
    // A 1D wall has no moment to report.
    let one_d = "[simulation]\ndimension = 1\nformulation = \"total-lagrangian\"\n\
        kernel = \"cubic-spline\"\nsmoothing_factor = 1.2\ncfl = 0.5\nend_time = 1.0\n\n\
        [[material]]\nname = \"unit\"\nmodel = \"linear-elastic\"\ndensity = 1.0\n\
        youngs_modulus = 0.9\npoisson_ratio = 0.2\n\n[[body]]\nname = \"bar\"\nmaterial = \"unit\"\n\
        spacing = 0.1\nbox = { min = [0.0], max = [1.0] }\n\n[[wall]]\nname = \"end\"\n\
        point = [0.0]\nnormal = [1.0]\nreport_moment = true\n";
    let e = error_of(one_d);
    assert_eq!(e.field, "wall[end].report_moment", "{e}");
    assert_eq!(e.line, Some(line_of(one_d, "report_moment")), "{e}");
}
