//! Uniform body force per unit mass b (gravity; numerics.md §4.5, R 4.11: ρ0 ü = ∇·P + ρ0 b).
//! Every real particle of the selected bodies gets the acceleration b, except the velocity
//! components a boundary prescribes: the drive holds those, so the body force does no work on
//! them. The force is conservative, so its energy column is the potential energy gained,
//! −Σ m b·(x − x_start) over the free components, evaluated at the same instant as the
//! kinetic energy (for a free fall leap-frog then closes the total to round-off, where a work
//! integral of the staggered velocities would leave an O(Δt) boundary term).

use super::{Effect, EffectContext};
use rayon::prelude::*;
use std::ops::Range;
use tlsph_math::Vector;

/// Particles per rayon task (filling a range, summing the potential energy).
const CHUNK: usize = 4096;

/// A uniform acceleration b on the particles of some bodies.
#[derive(Debug, Clone)]
pub struct BodyForce<const D: usize> {
    acceleration: Vector<D>,
    /// Global particle ranges of the bodies that feel it (disjoint).
    ranges: Vec<Range<usize>>,
    /// Particles of those bodies with prescribed velocity components (global index, which
    /// components), one entry per particle.
    held: Vec<(usize, [bool; D])>,
    /// Position of every real particle at the start of the run: x = X + u stays continuous
    /// through a reference update, so the potential energy does too.
    start: Vec<Vector<D>>,
    /// Potential energy gained −Σ m b·(x − x_start) at the last evaluation \[J\].
    potential: f64,
    /// Per-chunk partial sums (reused every step).
    chunk_sums: Vec<f64>,
}

impl<const D: usize> BodyForce<D> {
    /// The acceleration `acceleration` on the particles in `ranges` (duplicates merged), minus
    /// the prescribed components `held` (a particle may appear in several prescribed sets);
    /// `start` holds the initial positions of the real particles.
    pub(crate) fn new(
        acceleration: Vector<D>,
        mut ranges: Vec<Range<usize>>,
        held: impl IntoIterator<Item = (usize, [bool; D])>,
        start: Vec<Vector<D>>,
    ) -> Self {
        ranges.sort_by_key(|r| r.start);
        ranges.dedup();
        let mut merged: Vec<(usize, [bool; D])> = Vec::new();
        let mut held: Vec<_> = held.into_iter().collect();
        held.sort_by_key(|&(i, _)| i);
        for (i, mask) in held {
            if !ranges.iter().any(|r| r.contains(&i)) {
                continue;
            }
            match merged.last_mut() {
                Some((last, m)) if *last == i => m.iter_mut().zip(mask).for_each(|(a, b)| *a |= b),
                _ => merged.push((i, mask)),
            }
        }
        Self {
            acceleration,
            ranges,
            held: merged,
            start,
            potential: 0.0,
            chunk_sums: Vec::new(),
        }
    }
}

impl<const D: usize> Effect<D> for BodyForce<D> {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        "body_force"
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let b = self.acceleration;
        let p = ctx.particles;
        let start = &self.start;
        // m b·(x − x_start); (X − x_start) is exactly zero until the reference is replaced.
        let lowered =
            |i: usize| p.masses[i] * b.dot(&((p.positions0[i] - start[i]) + p.displacements[i]));
        self.chunk_sums.clear();
        for range in &self.ranges {
            out[range.clone()]
                .par_iter_mut()
                .with_min_len(CHUNK)
                .for_each(|a| *a = b);
            // Fixed chunks of the range: the same sum for any thread count.
            let chunks = range.len().div_ceil(CHUNK);
            self.chunk_sums
                .par_extend((0..chunks).into_par_iter().map(|c| {
                    let first = range.start + c * CHUNK;
                    (first..(first + CHUNK).min(range.end))
                        .map(lowered)
                        .sum::<f64>()
                }));
        }
        let mut work: f64 = self.chunk_sums.iter().sum();
        for &(i, components) in &self.held {
            let moved = (p.positions0[i] - start[i]) + p.displacements[i];
            for (c, held) in components.iter().enumerate() {
                if *held {
                    out[i][c] = 0.0;
                    work -= p.masses[i] * b[c] * moved[c];
                }
            }
        }
        self.potential = -work;
    }

    fn stored_energy(&self) -> Option<f64> {
        Some(self.potential)
    }
}
