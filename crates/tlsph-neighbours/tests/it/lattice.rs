//! Neighbour counts on cubic lattices (numerics.md §1.1) and determinism across thread counts.

use rayon::ThreadPoolBuilder;
use tlsph_neighbours::{build_neighbour_list, NeighbourList, Vector};

/// Index of the centre point of a lattice with an odd `n_side`.
fn centre<const D: usize>(n_side: usize) -> usize {
    (0..D).map(|a| (n_side / 2) * n_side.pow(a as u32)).sum()
}

fn centre_count<const D: usize>(n_side: usize, spacing: f64, radius: f64, origin: f64) -> usize {
    let points = crate::lattice::<D>(n_side, spacing, origin);
    let list = build_neighbour_list(&points, radius).unwrap();
    list.neighbours_of(centre::<D>(n_side)).len()
}

#[test]
fn interior_counts_for_h_equal_1_2_spacing() {
    // Radius 2h = 2.4Δx: 5 / 21 / 57 including self (R §2.1.2), so 4 / 20 / 56 neighbours.
    for (spacing, origin) in [(1.0, 0.0), (1.0, -3.7), (1e-3, 0.25), (0.1, -1e3)] {
        let radius = 2.4 * spacing;
        assert_eq!(centre_count::<1>(9, spacing, radius, origin), 4);
        assert_eq!(centre_count::<2>(9, spacing, radius, origin), 20);
        assert_eq!(centre_count::<3>(9, spacing, radius, origin), 56);
    }
}

#[test]
fn interior_counts_for_h_equal_1_5_spacing() {
    // Radius 3Δx (h = 1.5Δx), excluding self: 24 in 2D, 92 in 3D (numerics.md §1.1); 4 in 1D
    // since the point at exactly 3Δx is excluded.
    assert_eq!(centre_count::<1>(11, 1.0, 3.0, 0.0), 4);
    assert_eq!(centre_count::<2>(11, 1.0, 3.0, 0.0), 24);
    assert_eq!(centre_count::<3>(11, 1.0, 3.0, 0.0), 92);
}

#[test]
fn every_lattice_point_has_the_expected_count() {
    // Boundary points have fewer neighbours; the whole list of a mid-size lattice with a negative
    // corner equals brute force, and no point has more than the interior 56.
    let points = crate::lattice::<3>(12, 0.5, -1.0);
    let fast = build_neighbour_list(&points, 1.2).unwrap();
    let slow = tlsph_neighbours::brute_force_neighbour_list(&points, 1.2);
    assert_eq!(fast, slow);
    let max = (0..fast.n_particles())
        .map(|i| fast.neighbours_of(i).len())
        .max();
    assert_eq!(max, Some(56));
}

fn build_with_threads<const D: usize>(
    points: &[Vector<D>],
    radius: f64,
    threads: usize,
) -> NeighbourList {
    ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| build_neighbour_list(points, radius).unwrap())
}

#[test]
fn identical_for_one_and_two_threads() {
    let mut rng = crate::XorShift::new(77);
    // Enough particles for many parallel chunks; random order so chunks see different cells.
    let cloud: Vec<Vector<3>> = (0..20_000).map(|_| rng.point(0.0, 12.0)).collect();
    let one = build_with_threads(&cloud, 0.9, 1);
    let two = build_with_threads(&cloud, 0.9, 2);
    assert_eq!(one, two);
    assert_eq!(one.offsets(), two.offsets());
    assert_eq!(one.indices(), two.indices());
    let lattice = crate::lattice::<2>(150, 1.0, -20.0);
    assert_eq!(
        build_with_threads(&lattice, 2.4, 1),
        build_with_threads(&lattice, 2.4, 2)
    );
}
