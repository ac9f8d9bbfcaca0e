//! Rigid wall (e.g. an anvil, or a flat punch of finite size): a penalty force pushes back
//! every particle whose half-spacing sphere penetrates the wall (numerics.md §13 `[C]`).
//! Depends on current positions only. The wall's shape is a type parameter
//! ([`WallGeometry`]: an unbounded `RigidPlane`, a finite `FlatDisc`, a `RigidBall` or an
//! unbounded `RigidCylinder`), so each shape's loop carries nothing of the others.
//! With a friction coefficient the wall also carries a Coulomb friction effect of its own
//! ([`WallFriction`]), booked and reported separately; a spinning wall's friction also reports
//! its torque about the spin axis. With `report_moment` both report the full moment vector of
//! their force about the wall's current point.
//!
//! A moving wall ([`WallMotion`]) is the same plane translated by d(t): the penetration of a
//! particle at x is that of x − d(t) against the plane at rest, and friction acts on the
//! velocity relative to the wall's. Its column is the stored energy less the work the wall has
//! done on the particles, Σ ½ m k δ² − ∫ F·v_w dt (trapezoidal in time over the steps, F the
//! wall's whole force on the particles): the spring's energy changes by −F·(v − v_w), so
//! kinetic + internal + this column is constant, as for a fixed wall.

use super::{Configuration, Effect, EffectContext};
use crate::model::WallMotion;
use rayon::prelude::*;
use std::sync::Arc;
use tlsph_contact::{
    spin_velocity, surface_point, wall_friction_acceleration, FrictionCoefficients, WallGeometry,
};
use tlsph_math::{vector_to_3d, Vector, Vector3};

/// Particles per rayon task of the wall loops.
const MIN_PER_TASK: usize = 1024;

/// Chunk of the fixed-order sums (stored energy).
const CHUNK: usize = 4096;

/// A rigid frictionless wall of shape `G`, fixed or moving with `motion`.
#[derive(Debug, Clone)]
pub struct RigidWall<const D: usize, G> {
    name: String,
    geometry: Arc<G>,
    motion: Option<WallMotion<D>>,
    resultant: Vector<D>,
    /// Σ ½ k δ² of the last evaluation \[J\].
    stored: f64,
    /// Moving wall: work ∫ F·v_w dt done on the particles up to the last evaluation \[J\],
    /// and the time and power F·v_w of that evaluation (the trapezoid's left end).
    work: f64,
    last_power: Option<(f64, f64)>,
    /// Per-chunk partial sums (reused every step): stored energy and whole force.
    chunk_sums: Vec<(f64, Vector<D>)>,
    /// Moving wall: the longest travel per step, C_cfl min h, and a particle of the body with
    /// that h (see [`Self::with_travel_limit`]).
    travel_limit: Option<(f64, usize)>,
    /// The moment is reported about the wall's point (its place at t = 0 here, moving with
    /// the wall); `None`: not reported, nothing computed.
    moment_point: Option<Vector<D>>,
    /// The moment of the last step's force \[N m\] and its per-chunk partial sums.
    moment: Vector3,
    chunk_moments: Vec<Vector3>,
}

impl<const D: usize, G: WallGeometry<D> + Clone + 'static> RigidWall<D, G> {
    /// Builds the wall of shape `geometry` (which holds the particles' springs); `motion`
    /// moves it, `None` holds it fixed.
    pub(crate) fn new(name: &str, geometry: G, motion: Option<WallMotion<D>>) -> Self {
        Self {
            name: format!("wall_{name}"),
            geometry: Arc::new(geometry),
            motion,
            resultant: Vector::zeros(),
            stored: 0.0,
            work: 0.0,
            last_power: None,
            chunk_sums: Vec::new(),
            travel_limit: None,
            moment_point: None,
            moment: Vector3::zeros(),
            chunk_moments: Vec::new(),
        }
    }

    /// Reports the moment of the wall's force (and of its friction's) about the wall's point,
    /// `point` at t = 0, moving with the wall.
    pub(crate) fn with_moment_about(mut self, point: Vector<D>) -> Self {
        self.moment_point = Some(point);
        self
    }

    /// A moving wall votes Δt ≤ `length` / |v_w(t^n)|: it advances at most `length`
    /// (C_cfl min h over the bodies, the bound the CFL condition puts on a particle's own
    /// travel, numerics.md §7) per step, so a wall faster than sound still enters the
    /// particles' contact spheres over several steps. It binds only when the wall is faster
    /// than c + |v| of the particle limiting the CFL step (about the sound speed or more);
    /// otherwise the step is unchanged. `particle`: a particle with that h, reported as
    /// limiting.
    pub(crate) fn with_travel_limit(mut self, length: f64, particle: usize) -> Self {
        self.travel_limit = Some((length, particle));
        self
    }

    /// Coulomb friction with `coefficients` on this wall's contacts, as an effect of its own
    /// named `wall_<name>_friction` (to be applied right after the wall). `point`: the wall's
    /// point at t = 0, on the axis a spinning wall turns about.
    pub(crate) fn friction(
        &self,
        coefficients: FrictionCoefficients,
        point: Vector<D>,
    ) -> WallFriction<D, G> {
        WallFriction {
            name: format!("{}_friction", self.name),
            geometry: Arc::clone(&self.geometry),
            motion: self.motion.clone(),
            point,
            coefficients,
            resultant: Vector::zeros(),
            spin_axis: self
                .motion
                .as_ref()
                .and_then(|m| m.spin)
                .map(|omega| omega.normalize()),
            report_moment: self.moment_point.is_some(),
            moment: Vector3::zeros(),
            chunk_moments: Vec::new(),
        }
    }
}

/// The moment M = Σ m (y − c) × a of the accelerations `applied` (one per particle) about the
/// wall's point c (`centre`, at t = 0; the particles are taken into the wall's frame by
/// `shift`), each force acting at the surface point y where its particle touches the wall
/// (`tlsph_contact::surface_point`; for the normal force any point of its line of action
/// gives the same moment, for friction it is the lever the wall exerts it with). Summed in
/// fixed chunks (thread-count independent).
fn moment_at_surface<const D: usize, G: WallGeometry<D>>(
    wall: &G,
    (shift, centre): (Vector<D>, Vector<D>),
    ctx: &EffectContext<'_, D>,
    applied: &[Vector<D>],
    chunks: &mut Vec<Vector3>,
) -> Vector3 {
    let p = ctx.particles;
    applied
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut moment = Vector3::zeros();
            for (k, a) in chunk.iter().enumerate() {
                if a.iter().all(|c| *c == 0.0) {
                    continue;
                }
                let i = c * CHUNK + k;
                let x = p.positions0[i] + p.displacements[i] - shift;
                let lever = surface_point(wall, i, x, wall.contact(i, x)) - centre;
                moment += vector_to_3d(&lever).cross(&vector_to_3d(a)) * p.masses[i];
            }
            moment
        })
        .collect_into_vec(chunks);
    chunks.iter().sum()
}

/// The wall's displacement from its place at t = 0, at time `t` (zero for a fixed wall).
fn wall_shift<const D: usize>(motion: &Option<WallMotion<D>>, t: f64) -> Vector<D> {
    motion
        .as_ref()
        .map_or(Vector::zeros(), |m| m.displacement_at(t))
}

impl<const D: usize, G: WallGeometry<D> + Clone + 'static> Effect<D> for RigidWall<D, G> {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        &self.name
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let wall = &*self.geometry;
        let shift = wall_shift(&self.motion, ctx.time);
        let position = |i: usize| p.positions0[i] + p.displacements[i] - shift;
        // One pass: the acceleration k δ n̂, the stored energy Σ ½ m k δ² and the whole force
        // Σ m k δ n̂, summed in fixed chunks (thread-count independent).
        out.par_chunks_mut(CHUNK)
            .enumerate()
            .map(|(c, chunk)| {
                let mut stored = 0.0;
                let mut force = Vector::<D>::zeros();
                for (k, a) in chunk.iter_mut().enumerate() {
                    let i = c * CHUNK + k;
                    let (delta, direction) = wall.contact(i, position(i));
                    let a_n = wall.stiffness_per_mass(i) * delta;
                    *a = direction * a_n;
                    stored += 0.5 * p.masses[i] * a_n * delta;
                    force += *a * p.masses[i];
                }
                (stored, force)
            })
            .collect_into_vec(&mut self.chunk_sums);
        self.stored = self.chunk_sums.iter().map(|(e, _)| e).sum();
        if let Some(motion) = &self.motion {
            let force = self
                .chunk_sums
                .iter()
                .fold(Vector::<D>::zeros(), |f, (_, cf)| f + cf);
            let power = force.dot(&motion.velocity_at(ctx.time));
            if let Some((t, last)) = self.last_power {
                self.work += 0.5 * (last + power) * (ctx.time - t);
            }
            self.last_power = Some((ctx.time, power));
        }
    }

    fn stored_energy(&self) -> Option<f64> {
        Some(self.stored - self.work)
    }

    fn time_step_limit(&mut self, at: &Configuration<'_, D>) -> Option<(f64, usize)> {
        let (length, particle) = self.travel_limit?;
        let speed = self.motion.as_ref()?.velocity_at(at.time).norm();
        (speed > 0.0).then(|| (length / speed, particle))
    }

    fn resultant(&self) -> Option<Vector<D>> {
        Some(self.resultant)
    }

    fn set_resultant(&mut self, force: Vector<D>) {
        self.resultant = force;
    }

    fn moment(&self) -> Option<Vector3> {
        self.moment_point.map(|_| self.moment)
    }

    /// The moment of the wall's force about its point, when reported (`moment_at_surface`).
    fn record_applied(&mut self, ctx: &EffectContext<'_, D>, applied: &[Vector<D>]) {
        let Some(centre) = self.moment_point else {
            return;
        };
        let shift = wall_shift(&self.motion, ctx.time);
        self.moment = moment_at_surface(
            &*self.geometry,
            (shift, centre),
            ctx,
            applied,
            &mut self.chunk_moments,
        );
    }
}

/// Coulomb friction of a rigid wall (numerics.md §13 `[C]`,
/// `tlsph_contact::wall_friction_acceleration`), applied right after the wall's normal force in
/// the same step, so it sees this step's normal kick: the force that stops the tangential
/// motion within the kick while it is at most μ_s m a_n, else the kinetic μ_k m a_n against the
/// sliding direction.
/// Its work −∫ Σ f·v dt (dissipated, less what a moving wall puts in) is booked in the
/// `wall_<name>_friction` column; its resultant, the tangential force of the wall on the
/// particles, is reported as `wall_<name>_friction`. On a moving wall it acts on the velocity
/// relative to the wall's at the middle of the kick, t^n + ½Δt* (of the step's; exact once
/// the wall's start-up is over). On a spinning wall the wall's velocity at a particle is that
/// of the surface point it touches, v_w + ω × (y − c) (`tlsph_contact::spin_velocity`, y the
/// particle's `surface_point`, c the wall's point); the work the spin puts in through
/// friction is booked in the same column, and its torque about the spin axis is reported
/// ([`Effect::torque`]).
#[derive(Debug, Clone)]
pub struct WallFriction<const D: usize, G> {
    name: String,
    geometry: Arc<G>,
    motion: Option<WallMotion<D>>,
    /// The wall's point at t = 0 (the spin's axis passes through it).
    point: Vector<D>,
    /// Kinetic and static friction coefficients (not both 0).
    coefficients: FrictionCoefficients,
    resultant: Vector<D>,
    /// A spinning wall's unit axis ê in the sense of its spin, ω/|ω|; `None` for a wall
    /// without spin (no torque reported).
    spin_axis: Option<Vector3>,
    /// Whether the moment vector is reported (it is computed for a spinning wall too, whose
    /// torque is its part along ê).
    report_moment: bool,
    /// Spinning or reporting wall: the moment of the last step about the wall's point
    /// \[N m\] and its per-chunk partial sums (reused every step).
    moment: Vector3,
    chunk_moments: Vec<Vector3>,
}

impl<const D: usize, G: WallGeometry<D> + Clone + 'static> Effect<D> for WallFriction<D, G> {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        &self.name
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let wall = &*self.geometry;
        let middle = ctx.time + 0.5 * ctx.kick;
        let wall_velocity = self
            .motion
            .as_ref()
            .map_or(Vector::zeros(), |m| m.velocity_at(middle));
        // A spinning wall adds ω × (y − c) at the surface point y (the axis through the
        // wall's point c, in the wall's frame); a wall without spin has no such term.
        match self.motion.as_ref().and_then(|m| m.spin_at(middle)) {
            None => self.apply(ctx, out, |_, _, _| wall_velocity),
            Some(omega) => self.apply(ctx, out, |i, x, contact| {
                let y = surface_point(wall, i, x, contact);
                wall_velocity + spin_velocity(&omega, &(y - self.point))
            }),
        }
    }

    fn resultant(&self) -> Option<Vector<D>> {
        Some(self.resultant)
    }

    fn set_resultant(&mut self, force: Vector<D>) {
        self.resultant = force;
    }

    fn torque(&self) -> Option<f64> {
        self.spin_axis.map(|axis| axis.dot(&self.moment))
    }

    fn moment(&self) -> Option<Vector3> {
        self.report_moment.then_some(self.moment)
    }

    /// The friction's moment M = Σ m (y − c) × a about the wall's point (`moment_at_surface`),
    /// for a spinning wall or when reported. A spinning wall's torque about its axis in the
    /// sense of its spin is T = ê·M with ê = ω/|ω|, each friction force acting at the surface
    /// point y where its particle touches (the lever the wall turns; on a ball or cylinder
    /// |y − c| = R). T > 0 while the wall drives the particles round with it; |ω| T is the
    /// power the spin puts in.
    fn record_applied(&mut self, ctx: &EffectContext<'_, D>, applied: &[Vector<D>]) {
        if self.spin_axis.is_none() && !self.report_moment {
            return;
        }
        let shift = wall_shift(&self.motion, ctx.time);
        self.moment = moment_at_surface(
            &*self.geometry,
            (shift, self.point),
            ctx,
            applied,
            &mut self.chunk_moments,
        );
    }
}

impl<const D: usize, G: WallGeometry<D>> WallFriction<D, G> {
    /// The friction acceleration of every particle, with `surface_velocity(i, x, (δ, n̂))` the
    /// velocity of the wall's surface where particle `i` at `x` (in the wall's frame) touches.
    fn apply(
        &self,
        ctx: &EffectContext<'_, D>,
        out: &mut [Vector<D>],
        surface_velocity: impl Fn(usize, Vector<D>, (f64, Vector<D>)) -> Vector<D> + Sync,
    ) {
        let p = ctx.particles;
        let wall = &*self.geometry;
        let (mu, kick) = (self.coefficients, ctx.kick);
        let shift = wall_shift(&self.motion, ctx.time);
        out.par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PER_TASK)
            .for_each(|(i, a)| {
                let x = p.positions0[i] + p.displacements[i] - shift;
                let contact = wall.contact(i, x);
                let a_n = wall.stiffness_per_mass(i) * contact.0;
                let sliding = p.velocities[i] - surface_velocity(i, x, contact);
                *a = wall_friction_acceleration(a_n, sliding, contact.1, mu, kick);
            });
    }
}
