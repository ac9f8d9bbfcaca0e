//! Rigid fixed plane (e.g. an anvil): a penalty force pushes back every particle whose
//! half-spacing sphere penetrates the plane (numerics.md §13 `[C]`). Depends on current
//! positions only. With a friction coefficient the wall also carries a Coulomb friction
//! effect of its own ([`WallFriction`]), booked and reported separately.

use super::{Effect, EffectContext};
use rayon::prelude::*;
use std::sync::Arc;
use tlsph_contact::{wall_friction_acceleration, RigidPlane};
use tlsph_math::Vector;

/// Particles per rayon task of the wall loops.
const MIN_PER_TASK: usize = 1024;

/// Chunk of the fixed-order sums (stored energy).
const CHUNK: usize = 4096;

/// A rigid frictionless plane through `point` with unit `normal` pointing into the half-space
/// where particles may be.
#[derive(Debug, Clone)]
pub struct RigidWall<const D: usize> {
    name: String,
    geometry: Arc<RigidPlane<D>>,
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
        let geometry = RigidPlane::new(point, normal, h, c0, dx);
        Self {
            name: format!("wall_{name}"),
            geometry: Arc::new(geometry),
            resultant: Vector::zeros(),
            stored: 0.0,
            chunk_sums: Vec::new(),
        }
    }

    /// Coulomb friction with coefficient `coefficient` on this wall's contacts, as an effect
    /// of its own named `wall_<name>_friction` (to be applied right after the wall).
    pub(crate) fn friction(&self, coefficient: f64) -> WallFriction<D> {
        WallFriction {
            name: format!("{}_friction", self.name),
            geometry: Arc::clone(&self.geometry),
            coefficient,
            resultant: Vector::zeros(),
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
        let wall = &*self.geometry;
        let position = |i: usize| p.positions0[i] + p.displacements[i];
        // One pass: the acceleration k δ n̂ and the stored energy Σ ½ m k δ², summed in fixed
        // chunks (thread-count independent).
        out.par_chunks_mut(CHUNK)
            .enumerate()
            .map(|(c, chunk)| {
                let mut stored = 0.0;
                for (k, a) in chunk.iter_mut().enumerate() {
                    let i = c * CHUNK + k;
                    let delta = wall.penetration(i, position(i));
                    let a_n = wall.stiffness_per_mass(i) * delta;
                    *a = wall.normal() * a_n;
                    stored += 0.5 * p.masses[i] * a_n * delta;
                }
                stored
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

/// Coulomb friction of a rigid wall (numerics.md §13 `[C]`,
/// `tlsph_contact::wall_friction_acceleration`), applied right after the wall's normal force in
/// the same step, so it sees this step's normal kick: the Coulomb force μ m a_n against the
/// sliding direction, capped at the force that stops the tangential motion within the kick.
/// Its work −∫ Σ f·v dt (all dissipated) is booked in the `wall_<name>_friction` column; its
/// resultant, the tangential force of the wall on the particles, is reported as
/// `wall_<name>_friction`.
#[derive(Debug, Clone)]
pub struct WallFriction<const D: usize> {
    name: String,
    geometry: Arc<RigidPlane<D>>,
    /// Friction coefficient μ > 0.
    coefficient: f64,
    resultant: Vector<D>,
}

impl<const D: usize> Effect<D> for WallFriction<D> {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        &self.name
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let wall = &*self.geometry;
        let (mu, kick) = (self.coefficient, ctx.kick);
        out.par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PER_TASK)
            .for_each(|(i, a)| {
                let a_n = wall.normal_acceleration(i, p.positions0[i] + p.displacements[i]);
                *a = wall_friction_acceleration(a_n, p.velocities[i], wall.normal(), mu, kick);
            });
    }

    fn resultant(&self) -> Option<Vector<D>> {
        Some(self.resultant)
    }

    fn set_resultant(&mut self, force: Vector<D>) {
        self.resultant = force;
    }
}
