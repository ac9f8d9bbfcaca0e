//! Criterion benchmark: neighbour list of a 3D cubic lattice of ~100k points (47³ = 103 823) at
//! radius 2.4 spacing (the cubic spline with h = 1.2 Δx, 56 neighbours inside).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use tlsph_neighbours::{build_neighbour_list, CellGrid, Vector};

fn lattice(n_side: usize, spacing: f64) -> Vec<Vector<3>> {
    let mut points = Vec::with_capacity(n_side * n_side * n_side);
    for k in 0..n_side {
        for j in 0..n_side {
            for i in 0..n_side {
                points.push(Vector::<3>::new(i as f64, j as f64, k as f64) * spacing);
            }
        }
    }
    points
}

fn bench_build(c: &mut Criterion) {
    let spacing = 1e-3;
    let points = lattice(47, spacing);
    let radius = 2.4 * spacing;
    let mut group = c.benchmark_group("lattice_3d_103823");
    group.sample_size(20);
    group.bench_function("build_neighbour_list", |b| {
        b.iter(|| build_neighbour_list(black_box(&points), radius).unwrap())
    });
    group.bench_function("cell_grid_only", |b| {
        b.iter(|| CellGrid::new(black_box(&points), radius).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench_build);
criterion_main!(benches);
