//! The compressed (CSR) neighbour list. Storage and access only; building lives in `search`.

/// Compressed (CSR) neighbour list: for particle i, its neighbours are
/// `indices[offsets[i]..offsets[i+1]]`, sorted ascending, never containing i itself.
///
/// Each unordered pair {i, j} appears twice, once in each particle's list.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NeighbourList {
    /// Length `n_particles + 1`, starting at 0 and non-decreasing.
    offsets: Vec<usize>,
    indices: Vec<u32>,
}

impl Default for NeighbourList {
    /// The list of zero particles (`offsets == [0]`).
    fn default() -> Self {
        Self {
            offsets: vec![0],
            indices: Vec::new(),
        }
    }
}

impl NeighbourList {
    /// Assembles a list from parts the caller guarantees to be valid.
    pub(crate) fn from_parts(offsets: Vec<usize>, indices: Vec<u32>) -> Self {
        debug_assert_eq!(offsets.first(), Some(&0));
        debug_assert_eq!(offsets.last(), Some(&indices.len()));
        Self { offsets, indices }
    }

    /// Number of particles the list covers.
    #[inline]
    pub fn n_particles(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Total number of entries; each unordered pair appears twice.
    #[inline]
    pub fn n_pairs(&self) -> usize {
        self.indices.len()
    }

    /// Neighbours of particle `i`, sorted ascending. Panics if `i >= n_particles()`.
    #[inline]
    pub fn neighbours_of(&self, i: usize) -> &[u32] {
        &self.indices[self.offsets[i]..self.offsets[i + 1]]
    }

    /// CSR offsets, length `n_particles() + 1`.
    #[inline]
    pub fn offsets(&self) -> &[usize] {
        &self.offsets
    }

    /// All neighbour indices, particle by particle.
    #[inline]
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// Builds a list from one neighbour list per particle (convenient for tests and small cases).
    ///
    /// # Panics
    /// If a list is not strictly ascending or contains its own particle's index.
    pub fn from_sorted_lists(lists: Vec<Vec<u32>>) -> Self {
        let mut offsets = Vec::with_capacity(lists.len() + 1);
        offsets.push(0);
        let mut indices = Vec::with_capacity(lists.iter().map(Vec::len).sum());
        for (i, list) in lists.into_iter().enumerate() {
            assert!(
                list.windows(2).all(|w| w[0] < w[1]),
                "neighbours of particle {i} are not strictly ascending"
            );
            assert!(
                !list.iter().any(|&j| j as usize == i),
                "particle {i} lists itself as a neighbour"
            );
            indices.extend_from_slice(&list);
            offsets.push(indices.len());
        }
        Self { offsets, indices }
    }
}
