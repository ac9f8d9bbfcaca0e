//! Degenerate inputs and errors.

use tlsph_neighbours::{
    brute_force_neighbour_list, build_neighbour_list, CellGrid, NeighbourError, NeighbourList,
    Vector,
};

#[test]
fn empty_input() {
    let points: Vec<Vector<3>> = Vec::new();
    let list = build_neighbour_list(&points, 1.0).unwrap();
    assert_eq!(list.n_particles(), 0);
    assert_eq!(list.n_pairs(), 0);
    assert_eq!(list.offsets(), &[0]);
    assert_eq!(list, NeighbourList::default());
    assert_eq!(list, NeighbourList::from_sorted_lists(Vec::new()));
    assert_eq!(list, brute_force_neighbour_list(&points, 1.0));
    let grid = CellGrid::new(&points, 1.0).unwrap();
    let mut count = 0;
    grid.for_each_candidate(&Vector::<3>::zeros(), |_| count += 1);
    assert_eq!(count, 0);
}

#[test]
fn single_point() {
    let points = vec![Vector::<2>::new(-3.0, 4.0)];
    let list = build_neighbour_list(&points, 0.5).unwrap();
    assert_eq!(list.n_particles(), 1);
    assert_eq!(list.neighbours_of(0), &[] as &[u32]);
    assert_eq!(list.offsets(), &[0, 0]);
}

#[test]
fn coincident_points_are_all_neighbours() {
    let points = vec![Vector::<3>::new(1.5, -2.0, 0.25); 50];
    let list = build_neighbour_list(&points, 1e-6).unwrap();
    assert_eq!(list.n_pairs(), 50 * 49);
    for i in 0..50 {
        let expected: Vec<u32> = (0..50).filter(|&j| j != i).collect();
        assert_eq!(list.neighbours_of(i as usize), expected.as_slice());
    }
    assert_eq!(list, brute_force_neighbour_list(&points, 1e-6));
}

#[test]
fn from_sorted_lists_round_trips() {
    let list = NeighbourList::from_sorted_lists(vec![vec![1, 2], vec![0], vec![0], vec![]]);
    assert_eq!(list.n_particles(), 4);
    assert_eq!(list.n_pairs(), 4);
    assert_eq!(list.offsets(), &[0, 2, 3, 4, 4]);
    assert_eq!(list.indices(), &[1, 2, 0, 0]);
    assert_eq!(list.neighbours_of(0), &[1, 2]);
    assert_eq!(list.neighbours_of(3), &[] as &[u32]);
}

#[test]
#[should_panic(expected = "not strictly ascending")]
fn from_sorted_lists_rejects_unsorted() {
    NeighbourList::from_sorted_lists(vec![vec![2, 1], vec![], vec![]]);
}

#[test]
#[should_panic(expected = "lists itself")]
fn from_sorted_lists_rejects_self() {
    NeighbourList::from_sorted_lists(vec![vec![0]]);
}

#[test]
fn invalid_radius() {
    let points = vec![Vector::<2>::zeros(); 3];
    for radius in [0.0, -1.0, f64::INFINITY] {
        assert_eq!(
            build_neighbour_list(&points, radius),
            Err(NeighbourError::InvalidRadius { radius })
        );
        assert!(CellGrid::new(&points, radius).is_err());
    }
    assert!(matches!(
        build_neighbour_list(&points, f64::NAN),
        Err(NeighbourError::InvalidRadius { .. })
    ));
}

#[test]
fn non_finite_coordinate_names_the_point() {
    let mut points = vec![Vector::<3>::new(0.0, 1.0, 2.0); 10];
    points[7].y = f64::NAN;
    points[8].z = f64::INFINITY;
    let err = build_neighbour_list(&points, 1.0).unwrap_err();
    assert_eq!(err, NeighbourError::NonFiniteCoordinate { index: 7 });
    assert!(err.to_string().contains('7'));
    let err: Box<dyn std::error::Error> = Box::new(err);
    assert!(!err.to_string().is_empty());
}

#[test]
fn overflowing_bounding_box_is_an_error() {
    let points = vec![Vector::<1>::new(-1e308), Vector::<1>::new(1e308)];
    assert_eq!(
        build_neighbour_list(&points, 1.0),
        Err(NeighbourError::BoundingBoxOverflow { axis: 0 })
    );
}

#[test]
fn huge_coordinates_and_tiny_radius() {
    // Far from the origin the spacing is many ulps; the search still matches brute force.
    let points: Vec<Vector<2>> = crate::lattice::<2>(20, 1e-3, 1e6);
    let fast = build_neighbour_list(&points, 2.4e-3).unwrap();
    assert_eq!(fast, brute_force_neighbour_list(&points, 2.4e-3));
    // A radius below every spacing gives no pairs (and a sparse grid).
    let none = build_neighbour_list(&points, 1e-9).unwrap();
    assert_eq!(none.n_pairs(), 0);
}
