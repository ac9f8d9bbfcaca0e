//! Scene parsing, error locations and run folders.

use std::fs;
use tlsph_io::{parse_scene, run_scene_to_dir, DimensionModel};
use tlsph_solver::ReferenceSupport;

mod body_force;
mod boundaries;
mod contact;
mod contact_symmetry;
mod cuts;
mod damage;
mod documented_scenes;
mod failure;
mod kernel_groups;
mod materials;
mod overview;
mod placement;
mod plastic_strain;
mod stress_file;
mod velocity_file;
mod wall_friction;

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

/// [`PLATE_IMPACT`] cut to a few steps, for tests of the run folder.
fn short_plate_impact() -> tlsph_io::Scene {
    parse_scene(
        &PLATE_IMPACT.replace("end_time = 2.0", "end_time = 0.05"),
        "scene.toml",
    )
    .unwrap()
}

/// Writes `scene` (as `scene.toml`) and `table` (at `table_path`, relative to `dir`, its
/// folders made) into `dir` and loads the scene from there, as a run would.
fn load_with_table(
    dir: &std::path::Path,
    scene: &str,
    table_path: &str,
    table: &str,
) -> Result<tlsph_io::Scene, tlsph_io::SceneError> {
    let table_path = dir.join(table_path);
    fs::create_dir_all(table_path.parent().unwrap()).unwrap();
    fs::write(table_path, table).unwrap();
    fs::write(dir.join("scene.toml"), scene).unwrap();
    tlsph_io::load_scene(&dir.join("scene.toml"))
}

fn error_of(text: &str) -> tlsph_io::SceneError {
    parse_scene(text, "scene.toml").expect_err("scene must be rejected")
}

/// Rows of a run's `energy.csv` with the indices of the column `name` and of `total`.
fn energy_rows(dir: &std::path::Path, name: &str) -> (Vec<Vec<f64>>, usize, usize) {
    let energy = fs::read_to_string(dir.join("energy.csv")).unwrap();
    let mut lines = energy.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header.iter().position(|h| *h == name).unwrap();
    let total = header.iter().position(|h| *h == "total").unwrap();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (rows, column, total)
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
        // A field listed twice would give two equal CSV headers.
        (
            "\"displacement_x\"]",
            "\"displacement_x\", \"velocity_x\"]",
            "probe[target-mid].fields",
        ),
        // Finite, but ½ρV|v|² overflows: the run would take one step of Δt = 0 and stop.
        (
            "velocity = [0.1]",
            "velocity = [1e200]",
            "body[target].shape[0].velocity",
        ),
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
    let scene = short_plate_impact();
    let err = run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap_err();
    assert!(err.to_string().contains("refusing"), "{err}");
    assert_eq!(
        fs::read_to_string(dir.join("thesis.tex")).unwrap(),
        "keep me"
    );
}

#[test]
fn the_run_never_deletes_a_sibling_folder_it_did_not_make() {
    // `<dir>.old` and `<dir>.partial` are the swap's working names. Before, a user's `out.old`
    // was deleted by the swap, and a `out.partial` of any origin by the next run.
    let scene = short_plate_impact();
    for sibling in ["out.old", "out.partial"] {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("out");
        let theirs = tmp.path().join(sibling);
        fs::create_dir(&theirs).unwrap();
        fs::write(theirs.join("thesis.tex"), "keep me").unwrap();
        let mut steps_seen = 0;
        let err = run_scene_to_dir(&scene, &dir, &mut |_, _| steps_seen += 1).unwrap_err();
        assert_eq!(steps_seen, 0, "refused only after the run: {err}");
        assert!(err.to_string().contains(sibling), "{err}");
        assert_eq!(
            fs::read_to_string(theirs.join("thesis.tex")).unwrap(),
            "keep me"
        );
        assert!(!dir.exists());
    }
    // A file named `out.old` is refused the same way (it would have stranded the results).
    let tmp = tempfile::tempdir().unwrap();
    fs::write(tmp.path().join("out.old"), "keep me").unwrap();
    let err = run_scene_to_dir(&scene, &tmp.path().join("out"), &mut |_, _| {}).unwrap_err();
    assert!(err.to_string().contains("out.old"), "{err}");
}

#[test]
fn a_stale_working_folder_of_an_interrupted_run_is_replaced() {
    let scene = short_plate_impact();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    // An interrupted run leaves its working folder with the marker file in it.
    let stale = tmp.path().join("out.partial");
    fs::create_dir(&stale).unwrap();
    fs::write(stale.join(".tlsph-partial"), "").unwrap();
    fs::write(stale.join("energy.csv"), "half-written").unwrap();
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    assert!(!stale.exists());
    assert!(dir.join("summary.toml").is_file());
    assert!(
        !dir.join(".tlsph-partial").exists(),
        "the marker is not part of a run folder"
    );
}

#[test]
fn a_swap_that_fails_keeps_both_results_and_says_where_they_are() {
    let scene = short_plate_impact();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let first_summary = fs::read_to_string(dir.join("summary.toml")).unwrap();
    // During the second run a file appears at `out.old`: moving the previous results aside
    // fails (a folder cannot be renamed onto a file).
    let old = tmp.path().join("out.old");
    let err = run_scene_to_dir(&scene, &dir, &mut |_, _| {
        if !old.exists() {
            fs::write(&old, "in the way").unwrap();
        }
    })
    .unwrap_err();
    let message = err.to_string();
    assert!(
        message.contains("out.partial") && message.contains("results are complete"),
        "{message}"
    );
    // The previous results are untouched, the new ones complete in the working folder.
    assert_eq!(
        fs::read_to_string(dir.join("summary.toml")).unwrap(),
        first_summary
    );
    let partial = tmp.path().join("out.partial");
    let new_summary = fs::read_to_string(partial.join("summary.toml")).unwrap();
    assert!(new_summary.contains("status = \"complete\""));
    // The next run refuses rather than deleting the stranded results.
    fs::remove_file(&old).unwrap();
    let err = run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap_err();
    assert!(err.to_string().contains("out.partial"), "{err}");
    assert!(partial.join("summary.toml").is_file());
}

#[test]
fn an_output_dir_without_a_folder_name_or_a_too_long_probe_name_is_refused_at_check() {
    for dir in ["", ".", "results/.."] {
        let text = PLATE_IMPACT.replace("dir = \"out\"", &format!("dir = {dir:?}"));
        let e = error_of(&text);
        assert_eq!(e.field, "output.dir", "{dir:?}: {e}");
    }
    let tmp = tempfile::tempdir().unwrap();
    let scene = parse_scene(PLATE_IMPACT, "scene.toml").unwrap();
    let err = run_scene_to_dir(&scene, &tmp.path().join("."), &mut |_, _| {}).unwrap_err();
    assert!(err.to_string().contains("folder name"), "{err}");
    // `probes/<name>.csv` must fit a file system's 255-byte name.
    let long = "p".repeat(300);
    let e = error_of(&PLATE_IMPACT.replace("target-mid", &long));
    assert_eq!(e.field, "probe.name", "{e}");
    assert!(e.message.contains("at most 200"), "{e}");
}

#[test]
fn an_output_location_that_cannot_be_written_is_reported_before_the_run() {
    // The run folder's parent is a file: nothing can be created there. The error must come
    // before any step is computed (the progress callback never runs), not after the run.
    let tmp = tempfile::tempdir().unwrap();
    fs::write(tmp.path().join("a-file"), "not a folder").unwrap();
    let dir = tmp.path().join("a-file").join("run");
    let scene = parse_scene(PLATE_IMPACT, "scene.toml").unwrap();
    let mut steps_seen = 0;
    let err = run_scene_to_dir(&scene, &dir, &mut |_, _| steps_seen += 1).unwrap_err();
    assert_eq!(steps_seen, 0, "the run went ahead: {err}");
    let message = err.to_string();
    assert!(
        message.contains("run.partial") && message.contains("cannot create"),
        "{message}"
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

/// Two 1D rods meeting at x = 0.5 with ±0.01 (R-P1 in miniature, strain 1 %): the wave
/// reflected from the free ends puts the interface in tension at t = 1 (c = 1, rods 0.5 long).
fn rod_impact(formulation: &str) -> String {
    PLATE_IMPACT
        .replace("\"total-lagrangian\"", &format!("\"{formulation}\""))
        .replace("end_time = 2.0", "end_time = 3.0")
        .replace(
            "box = { min = [0.5], max = [2.0] }",
            "box = { min = [0.5], max = [1.0] }",
        )
        .replace("velocity = [0.1]", "velocity = [0.01]")
        .replace("velocity = [0.0]", "velocity = [-0.01]")
        .replace("at = [1.25]", "at = [0.75]")
}

#[test]
fn every_run_writes_a_stability_report_and_names_the_first_crossing() {
    // TLSPH keeps the lattice inside the default thresholds; conventional SPH clumps once
    // the rods are in tension (1 < t < 2), which the report must name with step and time.
    let tmp = tempfile::tempdir().unwrap();
    for (formulation, stays_inside) in [
        ("total-lagrangian-corrected", true),
        ("updated-lagrangian", false),
    ] {
        let text = rod_impact(formulation)
            + "\n[stability]\nmin_neighbour_ratio = 0.95\nmax_neighbour_ratio = 1.05\n";
        let scene = parse_scene(&text, "scene.toml").unwrap();
        let dir = tmp.path().join(formulation);
        let record = run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
        assert_eq!(
            record.stability.stayed_inside(),
            stays_inside,
            "{formulation}"
        );
        let csv = fs::read_to_string(dir.join("stability.csv")).unwrap();
        assert!(csv.starts_with(
            "time,step,min_neighbour_ratio,max_neighbour_ratio,clumping_index,min_spacing_ratio,max_spacing_ratio,energy_drift\n"
        ));
        assert_eq!(csv.lines().count(), record.diagnostics.len() + 1);
        let summary: toml::Table = fs::read_to_string(dir.join("summary.toml"))
            .unwrap()
            .parse()
            .unwrap();
        // One numbering: `steps` is the last step's number in stability.csv (always sampled).
        let last_step: f64 = csv
            .lines()
            .last()
            .unwrap()
            .split(',')
            .nth(1)
            .unwrap()
            .parse()
            .unwrap();
        assert_eq!(
            summary["steps"].as_integer(),
            Some(last_step as i64),
            "{formulation}"
        );
        let stability = summary["stability"].as_table().unwrap();
        assert_eq!(stability["stayed_inside"].as_bool(), Some(stays_inside));
        if !stays_inside {
            let crossing = stability["first_crossing"].as_table().unwrap();
            let t = crossing["time"].as_float().unwrap();
            assert!((1.0..2.0).contains(&t), "crossing at t = {t}");
            assert_eq!(crossing["quantity"].as_str(), Some("min_neighbour_ratio"));
        }
    }
}

#[test]
fn stability_thresholds_are_checked_with_field_and_line() {
    for (bad, field) in [
        ("min_neighbour_ratio = 1.2", "stability.min_neighbour_ratio"),
        ("max_neighbour_ratio = 0.9", "stability.max_neighbour_ratio"),
        ("clumping_index = -1.0", "stability.clumping_index"),
        ("energy_drift = 0.0", "stability.energy_drift"),
    ] {
        let text = format!("{PLATE_IMPACT}\n[stability]\n{bad}\n");
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert_eq!(e.line, Some(line_of(&text, bad)), "{e}");
    }
}

#[test]
fn updated_lagrangian_scenes_parse_and_refuse_total_lagrangian_only_effects() {
    let ul = rod_impact("updated-lagrangian");
    let ok = format!("{ul}\n[artificial_stress]\nexponent = 4.0\n");
    let scene = parse_scene(&ok, "scene.toml").unwrap();
    match scene.model {
        DimensionModel::One(m) => {
            let a = m.effects.artificial_stress.unwrap();
            assert_eq!((a.epsilon, a.exponent), (0.3, 4.0));
        }
        _ => unreachable!(),
    }
    for (extra, field, needle) in [
        (
            "\n[hourglass_control]\ncoefficient = 1.0\n",
            "hourglass_control",
            "coefficient",
        ),
        (
            "\n[artificial_stress]\nepsilon = -0.3\n",
            "artificial_stress.epsilon",
            "epsilon",
        ),
    ] {
        let text = format!("{ul}{extra}");
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert_eq!(e.line, Some(line_of(&text, needle)), "{e}");
    }
    let tl = format!("{PLATE_IMPACT}\n[artificial_stress]\nepsilon = 0.3\n");
    assert_eq!(error_of(&tl).field, "artificial_stress");
}

#[test]
fn an_initial_stress_is_carried_from_the_scene_into_the_run() {
    // A free 1D bar at rest with σ_xx = 1e-3 prestress: the stress is the declared one at
    // t = 0, and with free ends it releases from the ends inward (the middle keeps it until
    // the release waves, travelling at c = 1, arrive).
    let text = PLATE_IMPACT
        .replace(
            "spacing = 0.01",
            "spacing = 0.01\ninitial_stress = { xx = 1e-3, yy = 2.5e-4, zz = 2.5e-4 }",
        )
        .replace("velocity = [0.1]", "velocity = [0.0]")
        .replace("end_time = 2.0", "end_time = 0.5");
    let scene = parse_scene(&text, "scene.toml").unwrap();
    let DimensionModel::One(m) = &scene.model else {
        unreachable!()
    };
    let s = m.bodies[0].initial_stress.unwrap();
    assert_eq!(
        (s[(0, 0)], s[(1, 1)], s[(2, 2)], s[(0, 1)]),
        (1e-3, 2.5e-4, 2.5e-4, 0.0)
    );
    let record = tlsph_io::run_scene(&scene, &mut |_, _| {}).unwrap();
    let stress = record
        .probe("target-mid")
        .unwrap()
        .series(tlsph_solver::ParticleField::Stress(0, 0))
        .unwrap();
    // Probe at x = 1.25, 0.75 from the far end: untouched until t = 0.5.
    assert!(stress.iter().all(|s| (s - 1e-3).abs() < 1e-9), "{stress:?}");
}

#[test]
fn initial_stress_errors_name_the_field_and_line() {
    // A shear component the 1D (uniaxial-strain) scene does not have, and an unknown key.
    for (bad, message) in [
        ("initial_stress = { xx = 1.0, xy = 2.0 }", "`xy`"),
        ("initial_stress = { xx = 1.0, shear = 2.0 }", "shear"),
    ] {
        let text = PLATE_IMPACT.replace("spacing = 0.01", &format!("spacing = 0.01\n{bad}"));
        let e = error_of(&text);
        assert_eq!(e.line, Some(line_of(&text, bad)), "{e}");
        assert!(e.message.contains(message), "{e}");
    }
    let gl = PLATE_IMPACT
        .replace(
            "spacing = 0.01",
            "spacing = 0.01\ninitial_stress = { xx = 1.0 }",
        )
        .replace("cfl = 0.3", "cfl = 0.3\nstress_update = \"green-lagrange\"");
    let e = error_of(&gl);
    assert_eq!(e.field, "body[target].initial_stress", "{e}");
    // Elastic–plastic, σ_y0 = 0.01: a uniaxial 0.02 lies outside the yield surface (before, the
    // first step returned it to the surface without a word); 0.01 is on it and a large
    // hydrostatic stress (von Mises 0) inside it.
    let plastic = |stress: &str| {
        PLATE_IMPACT
            .replace(
                "model = \"linear-elastic\"",
                "model = \"elastic-plastic\"\nyield_stress = 0.01",
            )
            .replace("spacing = 0.01", &format!("spacing = 0.01\n{stress}"))
    };
    let outside = plastic("initial_stress = { xx = 0.02 }");
    let e = error_of(&outside);
    assert_eq!(e.field, "body[target].initial_stress", "{e}");
    assert_eq!(e.line, Some(line_of(&outside, "xx = 0.02")), "{e}");
    assert!(e.message.contains("outside the yield surface"), "{e}");
    for inside in [
        "initial_stress = { xx = 0.01 }",
        "initial_stress = { xx = -5.0, yy = -5.0, zz = -5.0 }",
    ] {
        assert!(
            parse_scene(&plastic(inside), "scene.toml").is_ok(),
            "{inside}"
        );
    }
}

#[test]
fn an_initial_stress_gradient_is_read_and_checked_with_field_and_line() {
    // The 1D bar (X from 0 to 2): σ_xx = 1e-3 + 2e-3 X, σ_yy = −1e-3 X.
    let gradient = "initial_stress_gradient = { xx = [2e-3], yy = [-1e-3] }";
    let with = |extra: &str| {
        PLATE_IMPACT.replace(
            "spacing = 0.01",
            &format!(
                "spacing = 0.01
initial_stress = {{ xx = 1e-3 }}
{extra}"
            ),
        )
    };
    let scene = parse_scene(&with(gradient), "scene.toml").unwrap();
    let DimensionModel::One(m) = &scene.model else {
        unreachable!()
    };
    let [g] = m.bodies[0].initial_stress_gradient.unwrap();
    assert_eq!((g[(0, 0)], g[(1, 1)], g[(2, 2)]), (2e-3, -1e-3, 0.0));
    // The run starts with the field: the particle at X has σ_xx = 1e-3 + 2e-3 X.
    let mut sim = tlsph_solver::Simulation::new(m.clone()).unwrap();
    for i in 0..sim.n_particles() {
        let x = sim.positions0()[i].x;
        let expected = 1e-3 + 2e-3 * x;
        assert!((sim.stresses()[i][(0, 0)] - expected).abs() < 1e-15, "{x}");
        assert!((sim.stresses()[i][(1, 1)] + 1e-3 * x).abs() < 1e-15, "{x}");
    }
    sim.step().unwrap();
    // Errors, at the key's line.
    for (bad, message) in [
        (
            "initial_stress_gradient = { xx = [1.0, 2.0] }",
            "1 finite numbers",
        ),
        ("initial_stress_gradient = { xy = [1.0] }", "`xy`"),
        ("initial_stress_gradient = { shear = [1.0] }", "shear"),
    ] {
        let text = with(bad);
        let e = error_of(&text);
        assert_eq!(e.line, Some(line_of(&text, bad)), "{bad}: {e}");
        assert!(e.message.contains(message), "{bad}: {e}");
    }
    // Elastic–plastic with σ_y0 = 0.01: 1e-3 + 5e-3 X leaves the surface at X = 1.8.
    let plastic = with("initial_stress_gradient = { xx = [5e-3] }").replace(
        "model = \"linear-elastic\"",
        "model = \"elastic-plastic\"\nyield_stress = 0.01",
    );
    let e = error_of(&plastic);
    assert_eq!(e.field, "body[target].initial_stress_gradient", "{e}");
    assert!(
        e.message.contains("takes the particle at [1.8") && e.message.contains("yield surface"),
        "{e}"
    );
    // The Green–Lagrange path refuses it as it refuses a uniform one.
    let gl = PLATE_IMPACT
        .replace(
            "spacing = 0.01",
            &format!(
                "spacing = 0.01
{gradient}"
            ),
        )
        .replace("cfl = 0.3", "cfl = 0.3\nstress_update = \"green-lagrange\"");
    assert_eq!(error_of(&gl).field, "body[target].initial_stress_gradient");
}

#[test]
fn reference_update_is_read_and_checked_with_field_and_line() {
    let ok = format!("{PLATE_IMPACT}\n[reference_update]\nstrain_threshold = 0.1\n");
    match parse_scene(&ok, "scene.toml").unwrap().model {
        DimensionModel::One(m) => assert_eq!(
            m.effects
                .reference_update
                .map(|r| (r.strain_threshold, r.support)),
            Some((0.1, ReferenceSupport::Stretched))
        ),
        _ => unreachable!(),
    }
    let fixed = format!("{ok}support = \"fixed\"\n");
    match parse_scene(&fixed, "scene.toml").unwrap().model {
        DimensionModel::One(m) => assert_eq!(
            m.effects.reference_update.map(|r| r.support),
            Some(ReferenceSupport::Fixed)
        ),
        _ => unreachable!(),
    }
    for (base, bad, field) in [
        (
            PLATE_IMPACT.to_string(),
            "strain_threshold = -0.1",
            "reference_update.strain_threshold",
        ),
        (
            PLATE_IMPACT.to_string(),
            "strain_threshold = 0.1\nsupport = \"adaptive\"",
            "reference_update.support",
        ),
        (
            rod_impact("updated-lagrangian"),
            "strain_threshold = 0.1",
            "reference_update",
        ),
    ] {
        let text = format!("{base}\n[reference_update]\n{bad}\n");
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        let last_line = bad.lines().last().unwrap();
        assert_eq!(e.line, Some(line_of(&text, last_line)), "{e}");
    }
}
