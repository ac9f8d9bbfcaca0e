//! One TLSPH step on a 3D block of about 100 000 particles, with 1 and 2 threads: elastic in
//! every formulation, and Johnson–Cook with a Mie–Grüneisen EOS (return map, EOS pressure and
//! the EOS's isentropic sound speed in the time step). Criterion's throughput is set to the
//! particle count, so "elements/s" is particle-steps/s.

use criterion::measurement::WallTime;
use criterion::{
    criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, Throughput,
};
use tlsph_materials::eos::MieGruneisenParameters;
use tlsph_materials::strength::JohnsonCookStrengthParameters;
use tlsph_materials::{JohnsonCookStrength, LinearElastic, MieGruneisen};
use tlsph_math::Vector;
use tlsph_solver::{
    BodyDescription, ElasticPlastic, Formulation, KernelKind, MaterialDescription, MaterialModel,
    Model, PressureModel, Simulation, SimulationConfig, StrengthModel, StressUpdate,
};

/// Steel (E = 210 GPa, ν = 0.3), elastic.
fn elastic_steel() -> MaterialModel {
    MaterialModel::LinearElastic(LinearElastic::new(210e9, 0.3).unwrap())
}

/// 4340 steel: Johnson–Cook strength (published constants) and a Mie–Grüneisen EOS.
fn johnson_cook_steel() -> MaterialModel {
    let strength = JohnsonCookStrength::new(JohnsonCookStrengthParameters {
        a: 792e6,
        b: 510e6,
        n: 0.26,
        c: 0.014,
        m: 1.03,
        reference_strain_rate: 1.0,
        room_temperature: 293.0,
        melt_temperature: 1793.0,
    })
    .unwrap();
    let eos = MieGruneisen::new(MieGruneisenParameters {
        reference_density: 7850.0,
        sound_speed: 4569.0,
        s1: 1.49,
        s2: 0.0,
        s3: 0.0,
        gamma0: 2.17,
        a: 0.0,
    })
    .unwrap();
    MaterialModel::ElasticPlastic(ElasticPlastic {
        elastic: LinearElastic::new(210e9, 0.3).unwrap(),
        strength: StrengthModel::JohnsonCook {
            model: strength,
            iterate: true,
        },
        pressure: PressureModel::Eos(eos.into()),
        min_pressure: None,
        thermal: None,
        failure: None,
        damage: None,
    })
}

fn block(n: usize, formulation: Formulation, material: MaterialModel) -> Simulation<3> {
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
            model: material,
        }],
        bodies: vec![BodyDescription {
            name: "block".into(),
            material: 0,
            spacing: dx,
            volumes: vec![dx * dx * dx; positions.len()],
            positions,
            velocities,
            initial_stress: None,
            initial_stress_gradient: None,
            initial_stresses: None,
            initial_plastic_strains: None,
            initial_damage: None,
            initial_failure_damage: None,
        }],
        boundaries: vec![],
        effects: Default::default(),
    };
    let mut sim = Simulation::new(model).expect("valid model");
    sim.step().expect("first step");
    sim
}

/// Benchmarks one step of an n³ block of `material` on a pool of `threads` threads.
fn bench_block(
    group: &mut BenchmarkGroup<'_, WallTime>,
    n: usize,
    formulation: Formulation,
    threads: usize,
    material: fn() -> MaterialModel,
) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let mut sim = pool.install(|| block(n, formulation, material()));
    group.bench_with_input(
        BenchmarkId::new(formulation.name(), format!("{threads}-threads")),
        &threads,
        |b, _| b.iter(|| pool.install(|| sim.step().expect("stable step"))),
    );
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
            bench_block(&mut group, n, formulation, threads, elastic_steel);
        }
    }
    group.finish();
    let mut group = c.benchmark_group("johnson_cook_mie_gruneisen_step_3d_block");
    group.throughput(Throughput::Elements((n * n * n) as u64));
    group.sample_size(10);
    for threads in [1usize, 2] {
        let formulation = Formulation::TotalLagrangianCorrected;
        bench_block(&mut group, n, formulation, threads, johnson_cook_steel);
    }
    group.finish();
}

criterion_group!(benches, bench_step);
criterion_main!(benches);
