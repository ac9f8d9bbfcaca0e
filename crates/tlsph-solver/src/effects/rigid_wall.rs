//! Rigid frictionless plane (e.g. an anvil): a penalty force pushes back every particle whose
//! half-spacing sphere penetrates the plane. Depends on current positions only.

use super::{Effect, EffectContext};
use rayon::prelude::*;
use tlsph_math::Vector;

/// Penalty stiffness in units of m (c0/h)²: the contact oscillator then has ω = 2 c0/h, so
/// ω Δt = 2 C_cfl ≤ 1.6 for C_cfl ≤ 0.8 — inside the leap-frog limit ω Δt < 2 without
/// reducing the CFL step. Penetration under a contact stress σ is about 0.36 (σ/M) Δx.
const STIFFNESS_FACTOR: f64 = 4.0;

/// A rigid frictionless plane through `point` with unit `normal` pointing into the half-space
/// where particles may be.
#[derive(Debug, Clone)]
pub struct RigidWall<const D: usize> {
    name: String,
    point: Vector<D>,
    normal: Vector<D>,
    /// Per-particle penalty stiffness divided by mass, (STIFFNESS_FACTOR c0²/h²) \[1/s²\].
    stiffness_per_mass: Vec<f64>,
    /// Per-particle contact radius: half its body's spacing \[m\].
    radius: Vec<f64>,
    resultant: Vector<D>,
    /// Σ ½ k δ² of the last evaluation \[J\].
    stored: f64,
    /// Per-chunk partial sums (reused every step).
    chunk_sums: Vec<f64>,
}

impl<const D: usize> RigidWall<D> {
    /// Builds the wall for particles whose bodies have smoothing lengths `h`, sound speeds
    /// `c0` and spacings `dx` (per particle).
    pub(crate) fn new(
        name: &str,
        point: Vector<D>,
        normal: Vector<D>,
        h: &[f64],
        c0: &[f64],
        dx: &[f64],
    ) -> Self {
        Self {
            name: format!("wall_{name}"),
            point,
            normal: normal.normalize(),
            stiffness_per_mass: h
                .iter()
                .zip(c0)
                .map(|(h, c)| STIFFNESS_FACTOR * c * c / (h * h))
                .collect(),
            radius: dx.iter().map(|d| 0.5 * d).collect(),
            resultant: Vector::zeros(),
            stored: 0.0,
            chunk_sums: Vec::new(),
        }
    }
}

impl<const D: usize> Effect<D> for RigidWall<D> {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        &self.name
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let (point, normal) = (self.point, self.normal);
        let (k, radius) = (&self.stiffness_per_mass, &self.radius);
        let penetration = |i: usize| {
            let distance = (p.positions0[i] + p.displacements[i] - point).dot(&normal);
            (radius[i] - distance).max(0.0)
        };
        out.par_iter_mut()
            .enumerate()
            .with_min_len(1024)
            .for_each(|(i, a)| {
                *a = normal * (k[i] * penetration(i));
            });
        // Stored energy Σ ½ m k δ², summed in fixed chunks (thread-count independent).
        const CHUNK: usize = 4096;
        let n = out.len();
        (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                (c * CHUNK..((c + 1) * CHUNK).min(n))
                    .map(|i| 0.5 * p.masses[i] * k[i] * penetration(i).powi(2))
                    .sum::<f64>()
            })
            .collect_into_vec(&mut self.chunk_sums);
        self.stored = self.chunk_sums.iter().sum();
    }

    fn stored_energy(&self) -> Option<f64> {
        Some(self.stored)
    }

    fn resultant(&self) -> Option<Vector<D>> {
        Some(self.resultant)
    }

    fn set_resultant(&mut self, force: Vector<D>) {
        self.resultant = force;
    }
}
