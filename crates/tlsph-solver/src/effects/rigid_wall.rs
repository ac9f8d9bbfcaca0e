//! Rigid fixed plane (e.g. an anvil): a penalty force pushes back every particle whose
//! half-spacing sphere penetrates the plane (numerics.md §13 `[C]`). Depends on current
//! positions only. With a friction coefficient the wall also carries a Coulomb friction
//! effect of its own ([`WallFriction`]), booked and reported separately.

use super::{Effect, EffectContext};
use rayon::prelude::*;
use std::sync::Arc;
use tlsph_math::Vector;

/// Penalty stiffness in units of m (c0/h)²: the contact oscillator then has ω = 2 c0/h, so
/// ω Δt = 2 C_cfl ≤ 1.6 for C_cfl ≤ 0.8 — inside the leap-frog limit ω Δt < 2 without
/// reducing the CFL step. Penetration under a contact stress σ is about 0.36 (σ/M) Δx.
const STIFFNESS_FACTOR: f64 = 4.0;

/// Particles per rayon task of the wall loops.
const MIN_PER_TASK: usize = 1024;

/// Chunk of the fixed-order sums (stored energy).
const CHUNK: usize = 4096;

/// The plane and its per-particle penalty law, shared by the wall and its friction.
#[derive(Debug)]
struct WallGeometry<const D: usize> {
    point: Vector<D>,
    /// Unit normal into the half-space where particles may be.
    normal: Vector<D>,
    /// Per-particle penalty stiffness divided by mass, (STIFFNESS_FACTOR c0²/h²) \[1/s²\].
    stiffness_per_mass: Vec<f64>,
    /// Per-particle contact radius: half its body's spacing \[m\].
    radius: Vec<f64>,
}

impl<const D: usize> WallGeometry<D> {
    /// Penetration δ = Δx/2 − (x − point)·n̂ of particle `i` at `x`, or 0.
    #[inline]
    fn penetration(&self, i: usize, x: Vector<D>) -> f64 {
        (self.radius[i] - (x - self.point).dot(&self.normal)).max(0.0)
    }

    /// Normal acceleration magnitude k δ of the penalty spring on particle `i` at `x`.
    #[inline]
    fn normal_acceleration(&self, i: usize, x: Vector<D>) -> f64 {
        self.stiffness_per_mass[i] * self.penetration(i, x)
    }
}

/// A rigid frictionless plane through `point` with unit `normal` pointing into the half-space
/// where particles may be.
#[derive(Debug, Clone)]
pub struct RigidWall<const D: usize> {
    name: String,
    geometry: Arc<WallGeometry<D>>,
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
        let geometry = WallGeometry {
            point,
            normal: normal.normalize(),
            stiffness_per_mass: h
                .iter()
                .zip(c0)
                .map(|(h, c)| STIFFNESS_FACTOR * c * c / (h * h))
                .collect(),
            radius: dx.iter().map(|d| 0.5 * d).collect(),
        };
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
                    let a_n = wall.stiffness_per_mass[i] * delta;
                    *a = wall.normal * a_n;
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

/// Coulomb friction of a rigid wall (numerics.md §13 `[C]`), applied right after the wall's
/// normal force in the same step.
///
/// A touching particle (penetration δ > 0) has the normal acceleration a_n = k δ of the wall's
/// spring. With v* its velocity after this step's earlier kicks and v*_t the part of v*
/// tangential to the wall, the friction acceleration is
///
///   a_t = −min(μ a_n, |v*_t| / Δt_kick) v*_t / |v*_t|,
///
/// i.e. the Coulomb force μ m a_n against the sliding direction, unless a smaller force stops
/// the tangential motion within this kick, in which case exactly that force is applied and the
/// particle sticks (v_t^{n+½} = 0). The cap is what a rigid, fixed surface allows for every
/// particle on its own: it needs no slip regularisation, no history and no time-step limit,
/// and friction never reverses a particle's sliding direction. Its work −∫ Σ f·v dt (all
/// dissipated) is booked in the `wall_<name>_friction` column; its resultant, the tangential
/// force of the wall on the particles, is reported as `wall_<name>_friction`.
#[derive(Debug, Clone)]
pub struct WallFriction<const D: usize> {
    name: String,
    geometry: Arc<WallGeometry<D>>,
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
                let v = p.velocities[i];
                let v_t = v - wall.normal * v.dot(&wall.normal);
                let speed = v_t.norm();
                *a = if a_n > 0.0 && speed > 0.0 {
                    v_t * (-(mu * a_n).min(speed / kick) / speed)
                } else {
                    Vector::zeros()
                };
            });
    }

    fn resultant(&self) -> Option<Vector<D>> {
        Some(self.resultant)
    }

    fn set_resultant(&mut self, force: Vector<D>) {
        self.resultant = force;
    }
}
