//! One TLSPH step on a 3D elastic block of about 100 000 particles, with 1 and 2 threads.
//! Criterion's throughput is set to the particle count, so "elements/s" is particle-steps/s.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use tlsph_materials::LinearElastic;
use tlsph_math::Vector;
use tlsph_solver::{
    BodyDescription, Formulation, KernelKind, MaterialDescription, MaterialModel, Model,
    Simulation, SimulationConfig, StressUpdate,
};

fn block(n: usize, formulation: Formulation) -> Simulation<3> {
    let dx = 1e-3;
    let mut positions = Vec::with_capacity(n * n * n);
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                positions.push(Vector::<3>::new(i as f64, j as f64, k as f64) * dx);
            }
        }
    }
    // A shear velocity field so every particle has a non-trivial stress update.
    let velocities = positions
        .iter()
        .map(|x| Vector::<3>::new(10.0 * x.y, 0.0, 0.0))
        .collect();
    let model = Model {
        config: SimulationConfig {
            formulation,
            stress_update: StressUpdate::JaumannRate,
            kernel: KernelKind::CubicSpline,
            smoothing_factor: 1.2,
            cfl: 0.3,
            end_time: 1.0,
        },
        materials: vec![MaterialDescription {
            name: "steel".into(),
            density: 7850.0,
            model: MaterialModel::LinearElastic(LinearElastic::new(210e9, 0.3).unwrap()),
        }],
        bodies: vec![BodyDescription {
            name: "block".into(),
            material: 0,
            spacing: dx,
            volumes: vec![dx * dx * dx; positions.len()],
            positions,
            velocities,
            initial_stress: None,
        }],
        boundaries: vec![],
        effects: Default::default(),
    };
    let mut sim = Simulation::new(model).expect("valid model");
    sim.step().expect("first step");
    sim
}

fn bench_step(c: &mut Criterion) {
    let n = 46; // 46³ = 97 336 particles
    let mut group = c.benchmark_group("tl_step_3d_block");
    group.throughput(Throughput::Elements((n * n * n) as u64));
    group.sample_size(10);
    // The updated-Lagrangian step includes the per-step kernel evaluation of the current
    // pairs and the displacement check of the Verlet list (rebuilds are rare at this speed).
    for formulation in [
        Formulation::TotalLagrangian,
        Formulation::TotalLagrangianCorrected,
        Formulation::UpdatedLagrangian,
    ] {
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut sim = pool.install(|| block(n, formulation));
            group.bench_with_input(
                BenchmarkId::new(formulation.name(), format!("{threads}-threads")),
                &threads,
                |b, _| b.iter(|| pool.install(|| sim.step().expect("stable step"))),
            );
        }
    }
    group.finish();
}

criterion_group!(benches, bench_step);
criterion_main!(benches);
