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
    let (order, sorted_points) = grid.sorted();
    let r2 = radius * radius;
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
                grid.ranges_around(&x, |range| {
                    for (&j, p) in order[range.clone()].iter().zip(&sorted_points[range]) {
                        if (p - x).norm_squared() < r2 && j as usize != i {
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
    Ok(NeighbourList::from_parts(offsets, indices))
}

/// O(N²) reference used by tests: the same predicate ‖x_j − x_i‖² < radius², no validation (a
/// NaN coordinate or radius simply matches nothing).
pub fn brute_force_neighbour_list<const D: usize>(
    points: &[Vector<D>],
    radius: f64,
) -> NeighbourList {
    let r2 = radius * radius;
    let lists = points
        .iter()
        .enumerate()
        .map(|(i, x)| {
            points
                .iter()
                .enumerate()
                .filter(|&(j, p)| j != i && (p - x).norm_squared() < r2)
                .map(|(j, _)| j as u32)
                .collect()
        })
        .collect();
    NeighbourList::from_sorted_lists(lists)
}
