//! Uniform body force per unit mass b (gravity; numerics.md §4.5, R 4.11: ρ0 ü = ∇·P + ρ0 b).
//! Every real particle of the selected bodies gets the acceleration b. On the velocity
//! components a boundary prescribes, the driver takes that force over (it becomes part of the
//! boundary's reaction, and the driver's work includes lifting the held particles against
//! it, `prescribed.rs`). The force is conservative, so its energy column is the potential
//! energy gained, −Σ m b·(x − x_start) over every particle of the selected bodies, held ones
//! included, evaluated at the same instant as the kinetic energy (for a free fall leap-frog
//! then closes the total to round-off, where a work integral of the staggered velocities
//! would leave an O(Δt) boundary term).
//!
//! With an amplitude b(t) = r(t) b (a ramp or a table) the column is the work of the
//! time-dependent force in the same form: E = −r(t) Π(t) + ∫₀ᵗ r'(s) Π(s) ds,
//! Π = Σ m b·(x − x_start), whose rate is −Σ m b(t)·v. The integral is accumulated step by
//! step with Π linear between the evaluation times and r exact (through its integral ∫ r, so
//! a table's corners inside a step cost nothing: the trapezoidal rule on r' Π, used before,
//! left a first-order error at each corner, 7.5 % of the final kinetic energy for a pulse
//! table), and is constant while r is, so then the column is exact again.

use super::{Effect, EffectContext};
use crate::model::Amplitude;
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
    /// Position of every real particle at the start of the run: x = X + u stays continuous
    /// through a reference update, so the potential energy does too.
    start: Vec<Vector<D>>,
    /// Potential energy gained −Σ m b·(x − x_start) at the last evaluation \[J\].
    potential: f64,
    /// The time history r(t) of b and its work integral; `None`: b is constant.
    history: Option<History>,
    /// Per-chunk partial sums (reused every step).
    chunk_sums: Vec<f64>,
}

/// The amplitude of a time-dependent body force and the integral ∫ r' Π dt accumulated over it.
#[derive(Debug, Clone)]
struct History {
    amplitude: Amplitude,
    /// ∫₀ᵗ r'(s) Π(s) ds up to the last evaluation \[J\].
    integral: f64,
    /// The last evaluation.
    last: Option<Evaluation>,
}

/// What the next step's share of ∫ r' Π dt needs from the last evaluation.
#[derive(Debug, Clone, Copy)]
struct Evaluation {
    /// Time t_a \[s\].
    time: f64,
    /// Π(t_a) = Σ m b·(x − x_start) \[J\].
    lowered: f64,
    /// r(t_a).
    factor: f64,
    /// ∫₀^{t_a} r \[s\].
    integral: f64,
}

impl<const D: usize> BodyForce<D> {
    /// The acceleration `acceleration`, scaled by `amplitude` when given, on the particles in
    /// `ranges` (duplicates merged); `start` holds the initial positions of the real particles.
    pub(crate) fn new(
        acceleration: Vector<D>,
        mut ranges: Vec<Range<usize>>,
        start: Vec<Vector<D>>,
        amplitude: Option<Amplitude>,
    ) -> Self {
        ranges.sort_by_key(|r| r.start);
        ranges.dedup();
        Self {
            acceleration,
            ranges,
            start,
            potential: 0.0,
            history: amplitude.map(|amplitude| History {
                amplitude,
                integral: 0.0,
                last: None,
            }),
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
        let factor = self
            .history
            .as_ref()
            .map_or(1.0, |h| h.amplitude.factor(ctx.time));
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
                .for_each(|a| *a = b * factor);
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
        // Π = Σ m b·(x − x_start) with the full b, held components included (their share of
        // `out` is taken over by their driver after this call, whose work then holds what it
        // took to move them against b).
        let work: f64 = self.chunk_sums.iter().sum();
        self.potential = match &mut self.history {
            None => -work,
            Some(state) => {
                let (t, integral) = (ctx.time, state.amplitude.integral(ctx.time));
                if let Some(last) = state.last {
                    let span = t - last.time;
                    if span > 0.0 {
                        // ∫ r' Π ds over the step with Π linear between the evaluations and r
                        // exact: Π_a (r_b − r_a) + (Π_b − Π_a)(r_b − (I_b − I_a)/Δt), I = ∫ r.
                        state.integral += last.lowered * (factor - last.factor)
                            + (work - last.lowered) * (factor - (integral - last.integral) / span);
                    }
                }
                state.last = Some(Evaluation {
                    time: t,
                    lowered: work,
                    factor,
                    integral,
                });
                -factor * work + state.integral
            }
        };
    }

    fn stored_energy(&self) -> Option<f64> {
        Some(self.potential)
    }
}
