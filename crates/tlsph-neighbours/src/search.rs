//! Building neighbour lists: the O(N) cell-grid search and the O(N²) brute-force reference.

use rayon::prelude::*;
use tlsph_math::Vector;

use crate::{CellGrid, NeighbourError, NeighbourList};

/// Particles per parallel work item: large enough that each chunk's two buffers amortise their
/// allocation, small enough to balance load on a few cores.
const CHUNK: usize = 512;

/// All pairs i ≠ j with |x_i − x_j| < `radius` (strict; decided as ‖x_j − x_i‖² < radius²), built
/// with a cell-linked list in O(N).
///
/// Parallel with rayon over particles (each gathers its own neighbours), and bit-identical for any
/// thread count: a particle's list depends only on the point set, and chunks are concatenated in
/// index order. Coincident points are neighbours of each other.
pub fn build_neighbour_list<const D: usize>(
    points: &[Vector<D>],
    radius: f64,
) -> Result<NeighbourList, NeighbourError> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(NeighbourError::InvalidRadius { radius });
    }
    let grid = CellGrid::new(points, radius)?;
    let r2 = radius * radius;
    Ok(search(points, &grid, |_| radius, |_, _, d2| d2 < r2))
}

/// All pairs i ≠ j closer than the mean of their own radii, |x_i − x_j| < (r_i + r_j)/2
/// (decided as ‖x_j − x_i‖² < ((r_i + r_j)/2)²): the neighbours of particles with different
/// smoothing lengths, symmetric by construction. Cells are as wide as the smallest radius and
/// each point scans the cells within (r_i + r_max)/2 of it, so a few large radii do not make
/// every point scan their volume. Parallel and bit-identical for any thread count, as
/// [`build_neighbour_list`].
pub fn build_neighbour_list_with_radii<const D: usize>(
    points: &[Vector<D>],
    radii: &[f64],
) -> Result<NeighbourList, NeighbourError> {
    assert_eq!(points.len(), radii.len(), "one radius per point");
    if let Some(&radius) = radii.iter().find(|r| !(r.is_finite() && **r > 0.0)) {
        return Err(NeighbourError::InvalidRadius { radius });
    }
    let smallest = radii.iter().copied().fold(f64::INFINITY, f64::min);
    let largest = radii.iter().copied().fold(0.0, f64::max);
    if points.is_empty() {
        return Ok(NeighbourList::from_parts(vec![0], Vec::new()));
    }
    let grid = CellGrid::new(points, smallest)?;
    Ok(search(
        points,
        &grid,
        |i| 0.5 * (radii[i] + largest),
        |i, j, d2| {
            let r = 0.5 * (radii[i] + radii[j]);
            d2 < r * r
        },
    ))
}

/// Cell-list search: for every point i, the candidates j ≠ i in the cells within `reach(i)` of
/// it for which `keep(i, j, ‖x_j − x_i‖²)` holds (a predicate that implies d < reach(i)).
fn search<const D: usize>(
    points: &[Vector<D>],
    grid: &CellGrid<D>,
    reach: impl Fn(usize) -> f64 + Sync,
    keep: impl Fn(usize, usize, f64) -> bool + Sync,
) -> NeighbourList {
    let (order, sorted_points) = grid.sorted();
    let n = points.len();

    // Per chunk: neighbour counts and the concatenated sorted lists of its particles.
    let chunks: Vec<(Vec<u32>, Vec<u32>)> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let particles = c * CHUNK..n.min((c + 1) * CHUNK);
            let mut counts = Vec::with_capacity(particles.len());
            let mut indices = Vec::new();
            for i in particles {
                let x = points[i];
                let start = indices.len();
                grid.ranges_within(&x, reach(i), |range| {
                    for (&j, p) in order[range.clone()].iter().zip(&sorted_points[range]) {
                        if j as usize != i && keep(i, j as usize, (p - x).norm_squared()) {
                            indices.push(j);
                        }
                    }
                });
                indices[start..].sort_unstable();
                counts.push((indices.len() - start) as u32);
            }
            (counts, indices)
        })
        .collect();

    let total: usize = chunks.iter().map(|(_, idx)| idx.len()).sum();
    let mut offsets = Vec::with_capacity(n + 1);
    let mut indices = Vec::with_capacity(total);
    offsets.push(0);
    for (counts, chunk_indices) in chunks {
        for count in counts {
            offsets.push(offsets.last().copied().unwrap_or(0) + count as usize);
        }
        indices.extend_from_slice(&chunk_indices);
    }
    NeighbourList::from_parts(offsets, indices)
}

/// O(N²) reference used by tests: the same predicate ‖x_j − x_i‖² < radius², no validation (a
/// NaN coordinate or radius simply matches nothing).
pub fn brute_force_neighbour_list<const D: usize>(
    points: &[Vector<D>],
    radius: f64,
) -> NeighbourList {
    let r2 = radius * radius;
    brute_force(points, |_, _, d2| d2 < r2)
}

/// O(N²) reference for [`build_neighbour_list_with_radii`], with its predicate
/// ‖x_j − x_i‖² < ((r_i + r_j)/2)²; no validation.
pub fn brute_force_neighbour_list_with_radii<const D: usize>(
    points: &[Vector<D>],
    radii: &[f64],
) -> NeighbourList {
    brute_force(points, |i, j, d2| {
        let r = 0.5 * (radii[i] + radii[j]);
        d2 < r * r
    })
}

/// Every pair i ≠ j for which `keep(i, j, ‖x_j − x_i‖²)` holds, by testing all of them.
fn brute_force<const D: usize>(
    points: &[Vector<D>],
    keep: impl Fn(usize, usize, f64) -> bool,
) -> NeighbourList {
    let lists = points
        .iter()
        .enumerate()
        .map(|(i, x)| {
            points
                .iter()
                .enumerate()
                .filter(|&(j, p)| j != i && keep(i, j, (p - x).norm_squared()))
                .map(|(j, _)| j as u32)
                .collect()
        })
        .collect();
    NeighbourList::from_sorted_lists(lists)
}
