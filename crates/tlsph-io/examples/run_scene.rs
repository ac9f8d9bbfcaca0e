//! Parses a scene from a TOML string, runs it in memory (no files written) and prints the
//! probe history: the 1D plate impact of `docs/scene-format.md` at a coarse spacing. The stress
//! at the middle of the target jumps to the plateau −ρ c v/2 = −0.05 when the wave arrives
//! (t ≈ 0.75) and returns to zero when the release from the flyer's rear face arrives (t ≈ 1.75).
//!
//! ```sh
//! cargo run -p tlsph-io --example run_scene
//! ```

use tlsph_io::{parse_scene, run_scene};

const SCENE: &str = r#"
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
name = "plates"
material = "plate"
spacing = 0.01

[[body.shape]]
box = { min = [0.0], max = [0.5] }
velocity = [0.1]

[[body.shape]]
box = { min = [0.5], max = [2.0] }

[[probe]]
name = "target-mid"
body = "plates"
at = [1.25]
fields = ["stress_xx", "velocity_x"]
interval = 0.05
"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Errors name the origin, line, column and field, e.g. `<plate impact>:12:7: simulation.cfl: ...`.
    let scene = parse_scene(SCENE, "<plate impact>")?;
    println!(
        "{}D scene, {} particles, end time {}",
        scene.dimension(),
        scene.n_particles(),
        scene.end_time()
    );
    let record = run_scene(&scene, &mut |_time, _end_time| {})?;
    if let Some(failure) = &record.failure {
        return Err(failure.clone().into());
    }
    for probe in &record.probes {
        println!("probe `{}`", probe.name);
        let header: Vec<String> = probe
            .fields
            .iter()
            .map(|f| format!("{:>10}", f.to_string()))
            .collect();
        println!("{:>8} {}", "time", header.join(" "));
        for (t, row) in probe.times.iter().zip(&probe.values) {
            let values: Vec<String> = row.iter().map(|v| format!("{v:>10.5}")).collect();
            println!("{t:>8.4} {}", values.join(" "));
        }
    }
    let first = record.diagnostics.first().map_or(0.0, |d| d.total_energy());
    let last = record.diagnostics.last().map_or(0.0, |d| d.total_energy());
    println!(
        "{} steps; total energy {first:.6e} at t = 0, {last:.6e} at the end",
        record.steps
    );
    Ok(())
}
