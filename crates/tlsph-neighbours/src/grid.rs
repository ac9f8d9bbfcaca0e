//! Uniform cell grid over a point set (a cell-linked list stored as a counting sort). Geometry
//! only; it never filters by distance.

use std::ops::Range;

use rayon::prelude::*;
use tlsph_math::Vector;

use crate::NeighbourError;

/// Cells are made this much (relative) larger than asked for.
///
/// Cell coordinates floor((x − origin)/cell) carry a rounding error of a few ε times the cell
/// coordinate, at most 2²¹ (see `max_axis_cells`), i.e. < 10⁻⁹. The margin absorbs it, so two
/// points whose computed distance is below the requested size are never two cells apart.
const CELL_MARGIN: f64 = 1e-8;

/// A dense cell table is used while it needs at most this many cells per point (plus a constant);
/// sparser point sets (far-apart bodies, tiny radius) fall back to a sorted table of occupied
/// cells, so memory stays O(N) whatever the bounding box.
const DENSE_CELLS_PER_POINT: u64 = 4;
/// Constant allowance of the dense table \[cells\].
const DENSE_CELLS_EXTRA: u64 = 4096;

/// Largest number of cells along one axis: keeps a cell key within 63 bits and cell coordinates
/// within the range where `CELL_MARGIN` covers rounding. Beyond it cells are coarsened (still
/// correct, only slower).
fn max_axis_cells(dimension: usize) -> u64 {
    1u64 << (63 / dimension).min(21)
}

/// Where the points of each cell start in the sorted order.
#[derive(Debug, Clone)]
enum CellIndex {
    /// `starts[key]..starts[key + 1]` for every cell of the box (length n_cells + 1).
    Dense { starts: Vec<u32> },
    /// Occupied cells only: sorted unique `keys` and `starts` (length keys.len() + 1).
    Sparse { keys: Vec<u64>, starts: Vec<u32> },
}

/// A uniform cell grid over a point set, reusable for searches around arbitrary points.
///
/// Building is O(N): cell keys are counting-sorted (points of a cell keep ascending index order).
/// [`for_each_candidate`](Self::for_each_candidate) visits every point in the 3^D cells around a
/// query point, which includes every point closer than the requested cell size.
#[derive(Debug, Clone)]
pub struct CellGrid<const D: usize> {
    origin: Vector<D>,
    cell_size: f64,
    inv_cell_size: f64,
    dims: [u64; D],
    strides: [u64; D],
    index: CellIndex,
    /// Point indices sorted by cell.
    order: Vec<u32>,
    /// Positions in the same order as `order` (contiguous per cell for cache-friendly scans).
    sorted_points: Vec<Vector<D>>,
}

impl<const D: usize> CellGrid<D> {
    /// Bins `points` into cubic cells of edge at least `cell_size` \[length\].
    ///
    /// Errors on a non-finite coordinate (naming the first such point), a non-finite or
    /// non-positive `cell_size`, more than `u32::MAX` points, or a bounding box whose extent
    /// overflows. A box too large for a dense cell table is handled by a sparse one, and more
    /// than 2²¹ cells along an axis by coarser cells.
    pub fn new(points: &[Vector<D>], cell_size: f64) -> Result<Self, NeighbourError> {
        const { assert!(D > 0, "a cell grid needs at least one dimension") };
        if !(cell_size.is_finite() && cell_size > 0.0) {
            return Err(NeighbourError::InvalidRadius { radius: cell_size });
        }
        if points.len() > u32::MAX as usize {
            return Err(NeighbourError::TooManyPoints {
                n_points: points.len(),
            });
        }
        if let Some(index) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(NeighbourError::NonFiniteCoordinate { index });
        }

        // Bounding box.
        let (origin, upper) = match points.first() {
            None => (Vector::<D>::zeros(), Vector::<D>::zeros()),
            Some(first) => points
                .iter()
                .fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p))),
        };
        let extent = upper - origin;
        if let Some(axis) = extent.iter().position(|e| !e.is_finite()) {
            return Err(NeighbourError::BoundingBoxOverflow { axis });
        }

        let axis_cap = max_axis_cells(D);
        let mut cell = cell_size * (1.0 + CELL_MARGIN);
        // Leave two cells of slack below the cap for rounding of extent / cell.
        cell = cell.max(extent.max() / (axis_cap - 2) as f64);
        let inv_cell_size = 1.0 / cell;

        let mut dims = [1u64; D];
        let mut strides = [1u64; D];
        for axis in 0..D {
            // Same formula as `coordinate`, so every point lands in [0, dims).
            dims[axis] = ((extent[axis] * inv_cell_size).floor() as u64 + 1).min(axis_cap);
            if axis > 0 {
                strides[axis] = strides[axis - 1] * dims[axis - 1];
            }
        }
        let n_cells = strides[D - 1] * dims[D - 1];

        let mut grid = Self {
            origin,
            cell_size: cell,
            inv_cell_size,
            dims,
            strides,
            index: CellIndex::Dense { starts: Vec::new() },
            order: Vec::new(),
            sorted_points: Vec::new(),
        };
        let keys: Vec<u64> = points.par_iter().map(|p| grid.key_of(p)).collect();

        let n = points.len() as u64;
        if n_cells <= DENSE_CELLS_PER_POINT * n + DENSE_CELLS_EXTRA {
            // Counting sort: count per cell, prefix-sum, then place points in index order so that
            // each cell lists its points ascending.
            let mut starts = vec![0u32; n_cells as usize + 1];
            for &key in &keys {
                starts[key as usize + 1] += 1;
            }
            for c in 0..n_cells as usize {
                starts[c + 1] += starts[c];
            }
            let mut cursor = starts[..n_cells as usize].to_vec();
            let mut order = vec![0u32; points.len()];
            for (i, &key) in keys.iter().enumerate() {
                let slot = &mut cursor[key as usize];
                order[*slot as usize] = i as u32;
                *slot += 1;
            }
            grid.order = order;
            grid.index = CellIndex::Dense { starts };
        } else {
            // Sparse fallback: sort (key, index) pairs; unique, so the order is deterministic.
            let mut pairs: Vec<(u64, u32)> = keys
                .iter()
                .enumerate()
                .map(|(i, &key)| (key, i as u32))
                .collect();
            pairs.par_sort_unstable();
            let mut occupied = Vec::new();
            let mut starts = Vec::new();
            for (slot, &(key, _)) in pairs.iter().enumerate() {
                if occupied.last() != Some(&key) {
                    occupied.push(key);
                    starts.push(slot as u32);
                }
            }
            starts.push(pairs.len() as u32);
            grid.order = pairs.into_iter().map(|(_, i)| i).collect();
            grid.index = CellIndex::Sparse {
                keys: occupied,
                starts,
            };
        }
        grid.sorted_points = grid.order.iter().map(|&i| points[i as usize]).collect();
        Ok(grid)
    }

    /// Edge length of the cells actually used \[length\]: the requested size plus a 10⁻⁸ relative
    /// margin, or more if the bounding box needed coarser cells.
    pub fn cell_size(&self) -> f64 {
        self.cell_size
    }

    /// Number of points binned.
    pub fn n_points(&self) -> usize {
        self.order.len()
    }

    /// Calls `f(index)` for every point in the 3^D cells around `point` (fewer at the edge of the
    /// grid), without filtering by distance. Every point closer to `point` than the requested
    /// cell size is visited; `point` need not be one of the grid's points, nor inside its box.
    #[inline]
    pub fn for_each_candidate(&self, point: &Vector<D>, mut f: impl FnMut(u32)) {
        self.for_each_range(point, |range| {
            for &i in &self.order[range] {
                f(i);
            }
        });
    }

    /// Like [`for_each_candidate`](Self::for_each_candidate), also passing the candidate's
    /// position (read from the grid's cell-ordered copy, which is cache-friendly).
    #[inline]
    pub fn for_each_candidate_with_position(
        &self,
        point: &Vector<D>,
        mut f: impl FnMut(u32, &Vector<D>),
    ) {
        self.for_each_range(point, |range| {
            for (&i, p) in self.order[range.clone()]
                .iter()
                .zip(&self.sorted_points[range])
            {
                f(i, p);
            }
        });
    }

    /// Cell coordinate of `x` along `axis`; saturates far outside the box (and maps NaN to 0).
    #[inline]
    fn coordinate(&self, point: &Vector<D>, axis: usize) -> i64 {
        ((point[axis] - self.origin[axis]) * self.inv_cell_size).floor() as i64
    }

    /// Linear cell key of a point inside the box (axis 0 fastest).
    #[inline]
    fn key_of(&self, point: &Vector<D>) -> u64 {
        (0..D)
            .map(|axis| {
                let c = self
                    .coordinate(point, axis)
                    .clamp(0, self.dims[axis] as i64 - 1);
                c as u64 * self.strides[axis]
            })
            .sum()
    }

    /// Positions in the sorted order of the points whose cell key lies in `first..=last`.
    #[inline]
    fn key_range(&self, first: u64, last: u64) -> Range<usize> {
        match &self.index {
            CellIndex::Dense { starts } => {
                starts[first as usize] as usize..starts[last as usize + 1] as usize
            }
            CellIndex::Sparse { keys, starts } => {
                let lo = keys.partition_point(|&k| k < first);
                let hi = lo + keys[lo..].partition_point(|&k| k <= last);
                starts[lo] as usize..starts[hi] as usize
            }
        }
    }

    /// Calls `f` with one range of the sorted order per row of cells around `point`.
    ///
    /// Along axis 0 the three neighbouring cells have consecutive keys, so their points are
    /// contiguous: one range covers a whole row, 3^(D−1) ranges cover the neighbourhood.
    #[inline]
    fn for_each_range(&self, point: &Vector<D>, f: impl FnMut(Range<usize>)) {
        self.for_each_range_within(point, 1, f)
    }

    /// Like [`for_each_range`](Self::for_each_range) over the (2 `reach` + 1)^D cells around
    /// `point`.
    #[inline]
    fn for_each_range_within(
        &self,
        point: &Vector<D>,
        reach: i64,
        mut f: impl FnMut(Range<usize>),
    ) {
        let mut lo = [0u64; D];
        let mut hi = [0u64; D];
        for axis in 0..D {
            let c = self.coordinate(point, axis);
            let first = c.saturating_sub(reach).max(0);
            let last = c.saturating_add(reach).min(self.dims[axis] as i64 - 1);
            if first > last {
                return;
            }
            lo[axis] = first as u64;
            hi[axis] = last as u64;
        }
        // Odometer over axes 1..D.
        let mut current = lo;
        loop {
            let base: u64 = (1..D).map(|a| current[a] * self.strides[a]).sum();
            let range = self.key_range(base + lo[0], base + hi[0]);
            if !range.is_empty() {
                f(range);
            }
            let mut axis = 1;
            loop {
                if axis == D {
                    return;
                }
                if current[axis] < hi[axis] {
                    current[axis] += 1;
                    break;
                }
                current[axis] = lo[axis];
                axis += 1;
            }
        }
    }

    /// The grid's cell-ordered view, for the pair search in this crate.
    #[inline]
    pub(crate) fn sorted(&self) -> (&[u32], &[Vector<D>]) {
        (&self.order, &self.sorted_points)
    }

    /// Crate-internal access to the row ranges of every cell that can hold a point closer to
    /// `point` than `distance`.
    #[inline]
    pub(crate) fn ranges_within(
        &self,
        point: &Vector<D>,
        distance: f64,
        f: impl FnMut(Range<usize>),
    ) {
        // |a − b| < distance puts a and b at most ⌈distance / cell⌉ cells apart; one more
        // covers rounding of the cell coordinates.
        let reach = (distance * self.inv_cell_size).floor() as i64 + 1;
        self.for_each_range_within(point, reach, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_sparse<const D: usize>(grid: &CellGrid<D>) -> bool {
        matches!(grid.index, CellIndex::Sparse { .. })
    }

    #[test]
    fn compact_bodies_use_the_dense_table() {
        let points: Vec<Vector<3>> = (0..1000)
            .map(|k| Vector::<3>::new((k % 10) as f64, ((k / 10) % 10) as f64, (k / 100) as f64))
            .collect();
        let grid = CellGrid::new(&points, 2.4).unwrap();
        assert!(!is_sparse(&grid));
        assert_eq!(grid.dims, [4, 4, 4]);
        // Points of a cell are listed in ascending index order.
        let (order, _) = grid.sorted();
        let CellIndex::Dense { starts } = &grid.index else {
            unreachable!()
        };
        for cell in starts.windows(2) {
            let members = &order[cell[0] as usize..cell[1] as usize];
            assert!(members.windows(2).all(|w| w[0] < w[1]));
        }
    }

    #[test]
    fn far_apart_bodies_use_the_sparse_table() {
        let mut points: Vec<Vector<2>> =
            (0..100).map(|k| Vector::<2>::new(k as f64, 0.0)).collect();
        points.extend((0..100).map(|k| Vector::<2>::new(k as f64, 1e5)));
        let grid = CellGrid::new(&points, 1.0).unwrap();
        assert!(is_sparse(&grid));
        assert_eq!(grid.cell_size(), 1.0 + CELL_MARGIN);
    }

    #[test]
    fn very_long_axes_coarsen_the_cells() {
        let points = vec![Vector::<1>::new(0.0), Vector::<1>::new(1e9)];
        let grid = CellGrid::new(&points, 1.0).unwrap();
        assert!(grid.cell_size() > 1e9 / max_axis_cells(1) as f64);
        assert!(grid.dims[0] <= max_axis_cells(1));
        let mut seen = Vec::new();
        grid.for_each_candidate(&Vector::<1>::new(1e9), |j| seen.push(j));
        assert_eq!(seen, [1]);
    }

    #[test]
    fn cell_keys_fit_in_63_bits() {
        for d in 1..=3 {
            assert!(max_axis_cells(d).pow(d as u32) <= 1 << 63);
        }
    }
}
