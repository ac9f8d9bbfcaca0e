//! End-to-end checks of the `tlsph` binary: exit codes, messages and the run folder.

use std::fs;
use std::process::Command;

const SCENE: &str = r#"
[simulation]
dimension = 1
formulation = "total-lagrangian"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 0.1

[[material]]
name = "plate"
model = "linear-elastic"
density = 1.0
youngs_modulus = 0.9
poisson_ratio = 0.2

[[body]]
name = "target"
material = "plate"
box = { min = [0.0], max = [1.5] }
spacing = 0.01
velocity = [0.0]

[[boundary]]
name = "push"
body = "target"
at = [0.0]
velocity = [0.01]

[[probe]]
name = "target-mid"
body = "target"
at = [0.75]
fields = ["stress_xx", "velocity_x", "displacement_x"]
interval = 0.01

[output]
dir = "out"
"#;

fn tlsph() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tlsph"))
}

#[test]
fn run_writes_probes_and_energy_and_exits_zero() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("scene.toml");
    fs::write(&scene, SCENE).unwrap();
    let out = tlsph()
        .current_dir(tmp.path())
        .args(["run", "scene.toml"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let probe = fs::read_to_string(tmp.path().join("out/probes/target-mid.csv")).unwrap();
    assert!(probe.starts_with("time,stress_xx,velocity_x,displacement_x"));
    assert!(tmp.path().join("out/energy.csv").exists());
}

#[test]
fn a_bad_scene_exits_two_names_file_line_and_field_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("bad.toml");
    fs::write(
        &scene,
        SCENE.replace("poisson_ratio = 0.2", "poisson_ratio = 0.6"),
    )
    .unwrap();
    let out = tlsph()
        .current_dir(tmp.path())
        .args(["run", "bad.toml"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    let line = SCENE
        .lines()
        .position(|l| l.starts_with("poisson_ratio"))
        .unwrap()
        + 1;
    assert!(err.contains(&format!("bad.toml:{line}:")), "{err}");
    assert!(err.contains("poisson_ratio"), "{err}");
    assert!(!tmp.path().join("out").exists());
    assert!(!tmp.path().join("out.partial").exists());
}

#[test]
fn a_missing_file_exits_two() {
    let out = tlsph()
        .args(["run", "/nonexistent/scene.toml"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/scene.toml"));
}

#[test]
fn check_reports_the_particle_count() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("scene.toml");
    fs::write(&scene, SCENE).unwrap();
    let out = tlsph().arg("check").arg(&scene).output().unwrap();
    assert!(out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("150 particles"), "{stdout}");
    // Then one line per body and the run's estimated size: M = 1 and ρ = 1 give c = 1, so the
    // first step is C h / c = 0.3 × 0.012 and 0.1 takes 28 such steps.
    assert!(
        stdout.contains(
            "body `target`: 150 particles of `plate`, h 1.2000e-2, wave speed 1.0000e0, \
             fastest particle 0.0000e0, first step 3.6000e-3"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains("about 28 steps at the first step (4.20e3 particle-steps)"),
        "{stdout}"
    );
}

#[test]
fn a_run_that_breaks_down_exits_one_names_the_particle_and_keeps_its_output() {
    // A rod crushed at ten times its wave speed inverts within a few steps.
    let tmp = tempfile::tempdir().unwrap();
    let scene = SCENE
        .replace(
            "velocity = [0.0]",
            "velocity_gradient = [[-100.0]]\nvelocity_origin = [0.75]",
        )
        .replace("end_time = 0.1", "end_time = 1.0");
    fs::write(tmp.path().join("crush.toml"), scene).unwrap();
    let out = tlsph()
        .current_dir(tmp.path())
        .args(["run", "crush.toml"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("particle") && err.contains("target") && err.contains("step"),
        "{err}"
    );
    let summary = fs::read_to_string(tmp.path().join("out/summary.toml")).unwrap();
    assert!(summary.contains("status = \"failed\""), "{summary}");
    // One numbering: the run failed at step k after k − 1 completed time steps.
    let number_after = |text: &str, key: &str| -> u64 {
        let rest = &text[text.find(key).unwrap_or_else(|| panic!("{key} in {text}")) + key.len()..];
        rest.chars()
            .take_while(char::is_ascii_digit)
            .collect::<String>()
            .parse()
            .unwrap()
    };
    let failed = number_after(&err, "step ");
    assert_eq!(
        number_after(&summary, "\nsteps = "),
        failed - 1,
        "{err}\n{summary}"
    );
    let probe = fs::read_to_string(tmp.path().join("out/probes/target-mid.csv")).unwrap();
    assert!(
        probe.lines().count() >= 2,
        "the samples before the failure are kept"
    );
}

#[test]
fn the_example_scene_is_valid() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/plate_impact.toml");
    let out = tlsph().arg("check").arg(scene).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn run_prints_the_set_up_notes_of_check_unless_quiet() {
    // The advice `tlsph check` gives (here: contact between total-Lagrangian bodies without
    // hourglass control) reaches a user who only runs the scene, on stderr before the run;
    // `--quiet` silences it with the rest, and the run goes ahead either way.
    let tmp = tempfile::tempdir().unwrap();
    let with_contact = SCENE.replace(
        "[[probe]]",
        "[[body]]\nname = \"flyer\"\nmaterial = \"plate\"\nbox = { min = [1.52], max = [1.7] }\n\
         spacing = 0.01\n\n[contact]\nscale = 0.2\n\n[[probe]]",
    );
    assert_ne!(with_contact, SCENE);
    fs::write(tmp.path().join("scene.toml"), &with_contact).unwrap();
    let run = |quiet: bool| {
        let mut args = vec!["run", "scene.toml"];
        if quiet {
            args.push("--quiet");
        }
        let out = tlsph().current_dir(tmp.path()).args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "{stderr}");
        stderr
    };
    let stderr = run(false);
    assert!(
        stderr.contains("note: potential contact between total-Lagrangian bodies"),
        "{stderr}"
    );
    assert!(!run(true).contains("note:"));
}

#[test]
fn particles_writes_a_bodys_positions_as_a_stress_table_template() {
    let tmp = tempfile::tempdir().unwrap();
    fs::write(tmp.path().join("scene.toml"), SCENE).unwrap();
    let out = tlsph()
        .current_dir(tmp.path())
        .args(["particles", "scene.toml", "target", "target.csv"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let table = fs::read_to_string(tmp.path().join("target.csv")).unwrap();
    let lines: Vec<&str> = table.lines().collect();
    // Header and one row per particle, at the cell centres of the lattice (Δx = 0.01).
    assert_eq!(lines.len(), 151);
    assert_eq!(lines[0], "x");
    for (k, line) in lines[1..].iter().enumerate() {
        let x: f64 = line.parse().unwrap();
        assert!((x - 0.01 * (k as f64 + 0.5)).abs() < 1e-12, "{k}: {x}");
    }
    // A scene that already names its table writes the same template before the table exists,
    // though the scene cannot be checked without it.
    let with_file = SCENE.replace(
        "spacing = 0.01\n",
        "spacing = 0.01\ninitial_stress_file = { path = \"stress.csv\" }\n",
    );
    assert_ne!(with_file, SCENE);
    fs::write(tmp.path().join("stressed.toml"), with_file).unwrap();
    let out = tlsph()
        .current_dir(tmp.path())
        .args(["particles", "stressed.toml", "target", "template.csv"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    assert_eq!(
        fs::read_to_string(tmp.path().join("template.csv")).unwrap(),
        table
    );
    let out = tlsph()
        .arg("check")
        .arg(tmp.path().join("stressed.toml"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("cannot read `") && stderr.contains("stress.csv"),
        "{stderr}"
    );
    // The table with a stress column added is a valid `initial_stress_file`.
    let stressed: String = std::iter::once("x,xx".to_string())
        .chain(lines[1..].iter().map(|x| format!("{x},1e-3")))
        .collect::<Vec<_>>()
        .join("\n");
    fs::write(tmp.path().join("stress.csv"), stressed).unwrap();
    let out = tlsph()
        .arg("check")
        .arg(tmp.path().join("stressed.toml"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    // An unknown body exits 2, lists the bodies and writes nothing.
    let out = tlsph()
        .current_dir(tmp.path())
        .args(["particles", "scene.toml", "flyer", "flyer.csv"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("no body named `flyer`; the bodies are `target`"),
        "{stderr}"
    );
    assert!(!tmp.path().join("flyer.csv").exists());
}
