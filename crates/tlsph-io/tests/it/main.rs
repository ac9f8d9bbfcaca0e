//! Scene parsing, error locations and run folders.

use std::fs;
use tlsph_io::{parse_scene, run_scene_to_dir, DimensionModel};

mod kernel_groups;
mod materials;

/// The scene shape of the foundation issue (R-P2 at a coarse spacing).
const PLATE_IMPACT: &str = r#"
[simulation]
dimension = 1
formulation = "total-lagrangian"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 2.0

[[material]]
name = "plate"
model = "linear-elastic"
density = 1.0
youngs_modulus = 0.9
poisson_ratio = 0.2

[[body]]
name = "target"
material = "plate"
spacing = 0.01

[[body.shape]]
box = { min = [0.0], max = [0.5] }
velocity = [0.1]

[[body.shape]]
box = { min = [0.5], max = [2.0] }
velocity = [0.0]

[[probe]]
name = "target-mid"
body = "target"
at = [1.25]
fields = ["stress_xx", "velocity_x", "displacement_x"]
interval = 0.01

[output]
dir = "out"
"#;

fn error_of(text: &str) -> tlsph_io::SceneError {
    parse_scene(text, "scene.toml").expect_err("scene must be rejected")
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .expect("needle in scene")
        + 1
}

#[test]
fn the_issue_scene_parses_into_a_bonded_flyer_and_target() {
    let scene = parse_scene(PLATE_IMPACT, "scene.toml").unwrap();
    assert_eq!(scene.dimension(), 1);
    assert_eq!(scene.n_particles(), 200);
    let DimensionModel::One(model) = &scene.model else {
        panic!("1D")
    };
    let body = &model.bodies[0];
    assert_eq!(body.velocities.iter().filter(|v| v[0] == 0.1).count(), 50);
    assert_eq!(scene.probes[0].fields.len(), 3);
    // The probe sits on the particle nearest to X = 1.25.
    assert!((body.positions[scene.probes[0].particle][0] - 1.25).abs() <= 0.005 + 1e-12);
}

#[test]
fn an_unknown_key_is_named_with_its_line() {
    let text = PLATE_IMPACT.replace("cfl = 0.3", "cfl = 0.3\ncfl_number = 0.3");
    let e = error_of(&text);
    assert_eq!(e.line, Some(line_of(&text, "cfl_number")));
    assert!(e.message.contains("cfl_number"), "{e}");
    assert!(e.to_string().starts_with("scene.toml:"), "{e}");
}

#[test]
fn impossible_values_are_named_with_field_and_line() {
    let cases = [
        (
            "poisson_ratio = 0.2",
            "poisson_ratio = 0.5",
            "material[plate].poisson_ratio",
        ),
        ("density = 1.0", "density = 0.0", "material[plate].density"),
        ("spacing = 0.01", "spacing = -0.01", "body[target].spacing"),
        (
            "material = \"plate\"",
            "material = \"steel\"",
            "body[target].material",
        ),
        ("at = [1.25]", "at = [3.5]", "probe[target-mid].at"),
        (
            "\"velocity_x\"",
            "\"velocity_y\"",
            "probe[target-mid].fields",
        ),
        (
            "kernel = \"cubic-spline\"",
            "kernel = \"quintic\"",
            "simulation.kernel",
        ),
        ("dimension = 1", "dimension = 4", "simulation.dimension"),
        (
            "name = \"target-mid\"",
            "name = \"../escape\"",
            "probe.name",
        ),
    ];
    for (from, to, field) in cases {
        let text = PLATE_IMPACT.replace(from, to);
        let e = error_of(&text);
        assert_eq!(e.field, field, "{to}: {e}");
        assert_eq!(e.line, Some(line_of(&text, to)), "{to}: {e}");
    }
}

#[test]
fn a_good_run_writes_the_documented_files() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let scene = parse_scene(
        &PLATE_IMPACT.replace("end_time = 2.0", "end_time = 0.2"),
        "scene.toml",
    )
    .unwrap();
    let record = run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    assert!(record.failure.is_none());
    let probe = fs::read_to_string(dir.join("probes/target-mid.csv")).unwrap();
    assert!(probe.starts_with("time,stress_xx,velocity_x,displacement_x\n"));
    // Samples every 0.01 from 0 to 0.2: 21 rows (+ header).
    assert_eq!(probe.lines().count(), 22);
    let energy = fs::read_to_string(dir.join("energy.csv")).unwrap();
    assert!(energy.starts_with("time,kinetic,internal,total\n"));
    let summary = fs::read_to_string(dir.join("summary.toml")).unwrap();
    assert!(summary.contains("status = \"complete\""));
    assert!(!tmp.path().join("out.partial").exists());
    // A second run replaces the first in place.
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    assert!(dir.join("summary.toml").exists());
}

#[test]
fn a_folder_that_is_not_a_run_is_never_overwritten() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("precious");
    fs::create_dir(&dir).unwrap();
    fs::write(dir.join("thesis.tex"), "keep me").unwrap();
    let scene = parse_scene(
        &PLATE_IMPACT.replace("end_time = 2.0", "end_time = 0.05"),
        "scene.toml",
    )
    .unwrap();
    let err = run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap_err();
    assert!(err.to_string().contains("refusing"), "{err}");
    assert_eq!(
        fs::read_to_string(dir.join("thesis.tex")).unwrap(),
        "keep me"
    );
}

#[test]
fn shapes_fill_disc_box_cylinder_and_sphere() {
    let two_d = r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
kernel = "wendland-c2"
smoothing_factor = 1.3
cfl = 0.3
end_time = 1.0
[[material]]
name = "m"
model = "linear-elastic"
density = 1.0
youngs_modulus = 1.0
poisson_ratio = 0.3
[[body]]
name = "disc"
material = "m"
spacing = 0.1
disc = { centre = [0.0, 0.0], radius = 1.0 }
velocity_gradient = [[0.0, -1.0], [1.0, 0.0]]
"#;
    let scene = parse_scene(two_d, "disc.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let body = &model.bodies[0];
    // Rigid spin v = ω × X about the origin.
    for (x, v) in body.positions.iter().zip(&body.velocities) {
        assert!((v[0] + x[1]).abs() < 1e-15 && (v[1] - x[0]).abs() < 1e-15);
    }
    let three_d = two_d
        .replace("dimension = 2", "dimension = 3")
        .replace(
            "disc = { centre = [0.0, 0.0], radius = 1.0 }",
            "cylinder = { base = [0.0, 0.0, 0.0], axis = \"z\", radius = 0.5, length = 1.0 }",
        )
        .replace(
            "velocity_gradient = [[0.0, -1.0], [1.0, 0.0]]",
            "velocity = [0.0, 0.0, -1.0]",
        );
    let scene = parse_scene(&three_d, "cyl.toml").unwrap();
    let n = scene.n_particles() as f64;
    // Volume π r² L / Δx³ = 785; the staircase boundary costs a few percent at r/Δx = 5.
    assert!((n / 785.4 - 1.0).abs() < 0.05, "{n}");
    let wrong = two_d.replace("disc = {", "sphere = {");
    let e = parse_scene(&wrong, "bad.toml").unwrap_err();
    assert!(e.message.contains("3D"), "{e}");
}

#[test]
fn frames_are_written_as_vtu_with_a_pvd_index() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let text = PLATE_IMPACT
        .replace("end_time = 2.0", "end_time = 0.1")
        .replace("dir = \"out\"", "dir = \"out\"\nframe_interval = 0.05");
    let scene = parse_scene(&text, "scene.toml").unwrap();
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let pvd = fs::read_to_string(dir.join("frames.pvd")).unwrap();
    // Frames at t = 0, 0.05 and the end 0.1.
    assert_eq!(pvd.matches("<DataSet").count(), 3, "{pvd}");
    let vtu = fs::read_to_string(dir.join("frames/frame_00002.vtu")).unwrap();
    for name in [
        "displacement",
        "velocity",
        "stress",
        "pressure",
        "von_mises",
        "density",
    ] {
        assert!(vtu.contains(&format!("Name=\"{name}\"")), "{name}");
    }
    assert!(vtu.contains("NumberOfPoints=\"200\""));
}
