//! The cell-grid search returns exactly the brute-force pair list.

use tlsph_neighbours::{
    brute_force_neighbour_list, brute_force_neighbour_list_with_radii, build_neighbour_list,
    build_neighbour_list_with_radii, CellGrid, NeighbourList, Vector,
};

use crate::XorShift;

fn assert_same<const D: usize>(points: &[Vector<D>], radius: f64) -> NeighbourList {
    let fast = build_neighbour_list(points, radius).unwrap();
    let slow = brute_force_neighbour_list(points, radius);
    assert_eq!(
        fast,
        slow,
        "D = {D}, n = {}, radius = {radius}",
        points.len()
    );
    fast
}

/// Uniform cloud in a box of edge `box_size` with a negative corner.
fn uniform<const D: usize>(seed: u64, n: usize, box_size: f64) -> Vec<Vector<D>> {
    let mut rng = XorShift::new(seed);
    (0..n)
        .map(|_| rng.point(-0.4 * box_size, 0.6 * box_size))
        .collect()
}

/// A few tight clusters (many points per cell) plus background noise.
fn clustered<const D: usize>(seed: u64, n: usize) -> Vec<Vector<D>> {
    let mut rng = XorShift::new(seed);
    let centres: Vec<Vector<D>> = (0..4).map(|_| rng.point(-10.0, 10.0)).collect();
    (0..n)
        .map(|k| {
            if k % 5 == 0 {
                rng.point(-12.0, 12.0)
            } else {
                centres[k % centres.len()] + rng.point::<D>(-0.3, 0.3)
            }
        })
        .collect()
}

#[test]
fn random_clouds_match_brute_force() {
    for seed in 1..=4 {
        for radius in [0.05, 0.3, 1.0, 2.5] {
            assert_same(&uniform::<1>(seed, 800, 20.0), radius);
            assert_same(&uniform::<2>(seed, 1500, 10.0), radius);
            assert_same(&uniform::<3>(seed, 1500, 6.0), radius);
        }
    }
}

#[test]
fn clustered_clouds_match_brute_force() {
    for seed in 11..=13 {
        for radius in [0.02, 0.2, 1.5] {
            assert_same(&clustered::<1>(seed, 600), radius);
            assert_same(&clustered::<2>(seed, 1200), radius);
            assert_same(&clustered::<3>(seed, 1200), radius);
        }
    }
}

#[test]
fn sparse_fallback_matches_brute_force() {
    // Points spread over a box 10⁵ radii wide: far too many cells for a dense table, so the
    // sparse table is used. Pairs of nearby points make sure there is something to find.
    let mut rng = XorShift::new(99);
    let mut points: Vec<Vector<3>> = Vec::new();
    for _ in 0..300 {
        let p = rng.point::<3>(-1e4, 1e4);
        points.push(p);
        points.push(p + rng.point::<3>(-0.6, 0.6));
    }
    let list = assert_same(&points, 1.0);
    assert!(list.n_pairs() > 0);
    // Two bodies far apart along one axis (an impact set-up).
    let mut bodies = crate::lattice::<2>(20, 0.1, 0.0);
    bodies.extend(crate::lattice::<2>(20, 0.1, 5e4));
    assert_same(&bodies, 0.25);
}

#[test]
fn coarsened_grid_matches_brute_force() {
    // More than 2²¹ radii along an axis forces coarser cells.
    let mut rng = XorShift::new(5);
    let mut points: Vec<Vector<1>> = (0..400).map(|_| rng.point(0.0, 1e7)).collect();
    points.extend((0..400).map(|k| Vector::<1>::new(k as f64 * 0.3)));
    assert_same(&points, 1.0);
}

#[test]
fn pairs_exactly_at_the_radius_are_excluded() {
    // Integer lattices with radius equal to the spacing: distances are exact, neighbours at
    // exactly the radius must not appear, and points sit exactly on cell faces.
    for origin in [0.0, -3.0, -2.5] {
        let l1 = assert_same(&crate::lattice::<1>(30, 1.0, origin), 1.0);
        assert_eq!(l1.n_pairs(), 0);
        let l2 = assert_same(&crate::lattice::<2>(12, 0.5, origin), 0.5);
        assert_eq!(l2.n_pairs(), 0);
        let l3 = assert_same(&crate::lattice::<3>(8, 2.0, origin), 2.0);
        assert_eq!(l3.n_pairs(), 0);
        // Just above the spacing, the face neighbours appear: 2D interior has 4 of them.
        let l2 = assert_same(&crate::lattice::<2>(12, 0.5, origin), 0.5 * (1.0 + 1e-12));
        assert_eq!(
            l2.neighbours_of(5 * 12 + 5),
            &[4 * 12 + 5, 5 * 12 + 4, 5 * 12 + 6, 6 * 12 + 5]
        );
    }
    // Random points and their images at exactly the radius along an axis (dyadic values so the
    // distance is exact).
    let mut rng = XorShift::new(7);
    let mut points: Vec<Vector<2>> = Vec::new();
    for _ in 0..200 {
        let p = Vector::<2>::new(
            (rng.range(-8.0, 8.0) * 64.0).round() / 64.0,
            (rng.range(-8.0, 8.0) * 64.0).round() / 64.0,
        );
        points.push(p);
        points.push(p + Vector::<2>::new(0.75, 0.0));
    }
    let list = assert_same(&points, 0.75);
    for pair in 0..200 {
        assert!(!list
            .neighbours_of(2 * pair)
            .contains(&(2 * pair as u32 + 1)));
    }
}

#[test]
fn lists_are_symmetric_sorted_and_exclude_self() {
    let points = clustered::<3>(21, 2000);
    let list = build_neighbour_list(&points, 0.4).unwrap();
    assert_eq!(list.n_particles(), points.len());
    assert_eq!(list.offsets().len(), points.len() + 1);
    assert_eq!(*list.offsets().last().unwrap(), list.indices().len());
    for i in 0..points.len() {
        let neighbours = list.neighbours_of(i);
        assert!(neighbours.windows(2).all(|w| w[0] < w[1]));
        for &j in neighbours {
            assert_ne!(j as usize, i);
            assert!(list
                .neighbours_of(j as usize)
                .binary_search(&(i as u32))
                .is_ok());
        }
    }
    assert_eq!(list.n_pairs() % 2, 0);
}

#[test]
fn cell_grid_visits_every_close_point_from_any_query() {
    // Query points that are not grid points, including points outside the bounding box.
    let points = uniform::<2>(31, 1000, 10.0);
    let radius = 0.7;
    let grid = CellGrid::new(&points, radius).unwrap();
    assert!(grid.cell_size() >= radius);
    assert_eq!(grid.n_points(), points.len());
    let mut rng = XorShift::new(32);
    for _ in 0..500 {
        let q = rng.point::<2>(-5.5, 7.5);
        let mut seen = Vec::new();
        grid.for_each_candidate(&q, |j| seen.push(j));
        let mut with_position = Vec::new();
        grid.for_each_candidate_with_position(&q, |j, p| {
            assert_eq!(*p, points[j as usize]);
            with_position.push(j);
        });
        assert_eq!(seen, with_position);
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(
            seen.len(),
            with_position.len(),
            "a candidate was visited twice"
        );
        for (j, p) in points.iter().enumerate() {
            if (p - q).norm() < radius {
                assert!(seen.binary_search(&(j as u32)).is_ok());
            }
        }
    }
    // Far away from every point: nothing to visit.
    let mut count = 0;
    grid.for_each_candidate(&Vector::<2>::new(1e6, -1e6), |_| count += 1);
    assert_eq!(count, 0);
}

#[test]
fn variable_radii_match_brute_force_and_stay_symmetric() {
    for seed in 21..=23 {
        let mut rng = XorShift::new(seed);
        let points = uniform::<3>(seed, 1200, 6.0);
        // Radii spread over a factor of five, as after a reference update in a strongly
        // stretched region next to an undeformed one.
        let radii: Vec<f64> = (0..points.len()).map(|_| rng.range(0.2, 1.0)).collect();
        let fast = build_neighbour_list_with_radii(&points, &radii).unwrap();
        assert_eq!(
            fast,
            brute_force_neighbour_list_with_radii(&points, &radii),
            "seed {seed}"
        );
        for i in 0..points.len() {
            for &j in fast.neighbours_of(i) {
                assert!(fast.neighbours_of(j as usize).contains(&(i as u32)));
            }
        }
        // Equal radii: the fixed-radius search.
        let equal = vec![0.7; points.len()];
        assert_eq!(
            build_neighbour_list_with_radii(&points, &equal).unwrap(),
            build_neighbour_list(&points, 0.7).unwrap()
        );
    }
}

#[test]
fn a_bad_radius_is_named() {
    let points = uniform::<2>(5, 10, 1.0);
    let mut radii = vec![0.3; 10];
    radii[4] = f64::NAN;
    assert!(build_neighbour_list_with_radii(&points, &radii).is_err());
    radii[4] = -1.0;
    match build_neighbour_list_with_radii(&points, &radii) {
        Err(tlsph_neighbours::NeighbourError::InvalidRadius { radius }) => assert_eq!(radius, -1.0),
        other => panic!("expected InvalidRadius, got {other:?}"),
    }
}
