//! Criterion benchmark: two 3D lattice blocks of 30³ = 27 000 particles each, face to face 0.8
//! spacing apart, as a contact sees them every step: the stale check of the candidate list
//! (no rebuild), a full rebuild, and one gather of the potential law over all candidates.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use tlsph_contact::{
    CandidateOffer, ContactCandidates, KernelKind, PotentialLaw, Vector, SKIN_FRACTION,
};

fn blocks(n_side: usize, spacing: f64) -> (Vec<Vector<3>>, Vec<u32>) {
    let mut points = Vec::with_capacity(2 * n_side.pow(3));
    let mut body = Vec::with_capacity(2 * n_side.pow(3));
    for (b, x0) in [(0u32, 0.0), (1, n_side as f64 - 0.2)] {
        for k in 0..n_side {
            for j in 0..n_side {
                for i in 0..n_side {
                    points.push(Vector::<3>::new(x0 + i as f64, j as f64, k as f64) * spacing);
                    body.push(b);
                }
            }
        }
    }
    (points, body)
}

fn bench_contact(c: &mut Criterion) {
    let dx = 1e-3;
    let (points, body) = blocks(30, dx);
    let displacements = vec![Vector::<3>::zeros(); points.len()];
    let cross = |pair: CandidateOffer| pair.across_bodies();
    let law = PotentialLaw::new(
        KernelKind::CubicSpline.build(3, 1.2 * dx).unwrap(),
        dx,
        1e8,
        4.0,
        0.0,
    );
    let new_list = || ContactCandidates::new(&body, |_| true, law.d0(), SKIN_FRACTION * dx);
    let mut group = c.benchmark_group("two_blocks_54000");
    group.sample_size(20);
    group.bench_function("refresh_without_rebuild", |b| {
        let mut list = new_list();
        list.refresh(&points, &displacements, cross);
        b.iter(|| list.refresh(black_box(&points), &displacements, cross))
    });
    group.bench_function("rebuild", |b| {
        b.iter(|| {
            let mut list = new_list();
            list.refresh(black_box(&points), &displacements, cross);
            list
        })
    });
    group.bench_function("potential_law_gather", |b| {
        let mut list = new_list();
        list.refresh(&points, &displacements, cross);
        let x = list.positions();
        b.iter(|| {
            let mut sum = 0.0;
            for k in 0..list.len() {
                for &j in list.of(k) {
                    let r = (x[k] - x[j as usize]).norm();
                    if r < law.d0() {
                        sum += law.evaluate(r).force;
                    }
                }
            }
            black_box(sum)
        })
    });
    group.finish();
}

criterion_group!(benches, bench_contact);
criterion_main!(benches);
