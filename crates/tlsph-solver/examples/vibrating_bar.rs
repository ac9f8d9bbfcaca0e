//! A clamped–free titanium bar (1D, uniaxial strain) released with the linear velocity field
//! v = K X, built as a `Model` in code and run with `Simulation::run`: no scene file, no I/O
//! crate. Prints kinetic, internal and total energy about every 100 steps; with no artificial
//! viscosity the total stays constant while energy swaps between the two forms.
//!
//! ```sh
//! cargo run -p tlsph-solver --example vibrating_bar
//! ```

use tlsph_materials::LinearElastic;
use tlsph_math::Vector;
use tlsph_solver::{
    BodyDescription, BoundaryDescription, Formulation, KernelKind, MaterialDescription,
    MaterialModel, Model, Simulation, SimulationConfig, StressUpdate,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Titanium (Reveles problem 4): ρ0 [kg/m³], E [Pa], ν.
    let titanium = LinearElastic::new(1.16e11, 0.342)?;
    let density = 4530.0;
    // 31 particles at X = 0, 0.2 mm, …, 6 mm; each stands for a cell of length Δx (volume Δx per
    // unit cross-section in 1D).
    let n = 31;
    let spacing = 2.0e-4; // Δx [m]
    let velocity_gradient = 1.0e3; // K [1/s]: 6 m/s at the free end, well inside the linear regime
    let positions: Vec<Vector<1>> = (0..n)
        .map(|i| Vector::<1>::new(i as f64 * spacing))
        .collect();
    let velocities: Vec<Vector<1>> = positions.iter().map(|x| x * velocity_gradient).collect();

    let model = Model {
        config: SimulationConfig {
            formulation: Formulation::TotalLagrangianCorrected,
            stress_update: StressUpdate::JaumannRate,
            kernel: KernelKind::CubicSpline,
            smoothing_factor: 1.2,
            cfl: 0.3,
            end_time: 12.4e-6, // [s], about 3.3 periods of the first mode
        },
        materials: vec![MaterialDescription {
            name: "titanium".into(),
            density,
            model: MaterialModel::LinearElastic(titanium),
        }],
        bodies: vec![BodyDescription {
            name: "bar".into(),
            material: 0,
            spacing,
            volumes: vec![spacing; n],
            positions,
            velocities,
            initial_stress: None,
            initial_stress_gradient: None,
            initial_stresses: None,
            initial_plastic_strains: None,
            initial_damage: None,
            initial_failure_damage: None,
        }],
        // Clamp: particle 0 (X = 0) held at zero velocity.
        boundaries: vec![BoundaryDescription {
            name: "clamp".into(),
            body: 0,
            particles: vec![0],
            velocity: Vector::<1>::zeros(),
            components: [true],
            amplitude: None,
        }],
        effects: Default::default(),
    };

    let mut sim = Simulation::new(model)?;
    let wave_speed = titanium.sound_speed(density);
    let period = 4.0 * (n as f64 - 0.5) * spacing / wave_speed; // free end half a cell beyond X = 6 mm
    println!(
        "c = {wave_speed:.1} m/s, first-mode period ≈ {:.3} µs",
        period * 1e6
    );
    println!(
        "{:>6} {:>10} {:>13} {:>13} {:>13}",
        "step", "t [µs]", "kinetic", "internal", "total [J/m²]"
    );
    let initial = sim.diagnostics().total_energy();
    sim.run(|sim, report| {
        if report.step % 100 == 0 || sim.finished() {
            print_energies(sim, report.step);
        }
    })?;
    let drift = sim.diagnostics().total_energy() / initial - 1.0;
    println!(
        "{} steps; relative change of total energy {drift:.2e}",
        sim.steps_done()
    );
    Ok(())
}

/// One table row: energies per unit cross-sectional area at the current time.
fn print_energies(sim: &Simulation<1>, step: u64) {
    let d = sim.diagnostics();
    println!(
        "{step:>6} {:>10.4} {:>13.6e} {:>13.6e} {:>13.6e}",
        d.time * 1e6,
        d.kinetic,
        d.internal,
        d.total_energy()
    );
}
