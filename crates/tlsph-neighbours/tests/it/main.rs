//! Integration tests of tlsph-neighbours: grid search equals brute force, lattice counts,
//! determinism across thread counts, robustness and errors.

mod brute_force;
mod edge_cases;
mod lattice;

use tlsph_neighbours::Vector;

/// Tiny deterministic xorshift64* generator (no `rand` dependency).
pub struct XorShift(u64);

impl XorShift {
    pub fn new(seed: u64) -> Self {
        Self(seed.max(1))
    }

    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    pub fn point<const D: usize>(&mut self, lo: f64, hi: f64) -> Vector<D> {
        Vector::<D>::from_fn(|_, _| self.range(lo, hi))
    }
}

/// A cubic lattice with `n_side` points per axis, spacing `spacing`, starting at `origin`.
pub fn lattice<const D: usize>(n_side: usize, spacing: f64, origin: f64) -> Vec<Vector<D>> {
    let total = n_side.pow(D as u32);
    (0..total)
        .map(|mut k| {
            Vector::<D>::from_fn(|_, _| {
                let i = k % n_side;
                k /= n_side;
                origin + i as f64 * spacing
            })
        })
        .collect()
}
