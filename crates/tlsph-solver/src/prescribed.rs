//! Prescribed velocities (`[[boundary]]`, numerics.md §13.2) and what holding them costs.
//!
//! A held velocity component is overwritten every step with the set's value, so the driver
//! exerts whatever force that takes. Per held component, with v_k = v^{n−½} + Δt* a^n the
//! velocity the kick gave (internal forces only: the effects' forces on held components are
//! taken over by the driver, see [`Drivers::absorb`]), a_e those effect accelerations, and
//! v_p the imposed v^{n+½}:
//! - the driver's force is f = m (v_p − v_k)/Δt* − m a_e, what it takes to move the component
//!   as imposed against its internal and effect forces, so a clamp reports the whole
//!   reaction, weight and contact included;
//! - the work booked is f·v̄ Δt*, with v̄ = ½(v^{n−½} + v_p) the mid-step velocity (the
//!   midpoint rule of the effects' work). Each effect books its own force's work on the held
//!   components at the same v̄ (`BookedEffect::held_work`; a conservative effect's stored
//!   energy already counts held particles), so kinetic + internal + booked energies close for
//!   driven scenes as for free ones, and `boundary_<name>` is the work of the reported force:
//!   a rigid indenter pushed into a block books the work of pushing it, not zero.
//!
//! The kick spans t^n − ½Δt^n … t^n + ½Δt^{n+1}; the work reported at t^n leaves out the share
//! ½Δt^{n+1}/Δt* of the last one. That makes it the trapezoidal rule that the internal energy
//! (midpoint stress over each step) follows: booked whole, the column led the instant by
//! ½Δt f·v, an O(Δt) error (measured 1.9e-2 of the work in a suddenly pulled block, against
//! 6.7e-4 and second order with the split).
//!
//! Nothing here is allocated without `[[boundary]]` tables; the per-step cost is one pass over
//! the held particles, and one more per declared effect.

use crate::model::Amplitude;
use crate::particles::Particles;
use tlsph_math::Vector;

/// Prescribed-velocity set in global indices.
#[derive(Debug, Clone)]
pub(crate) struct PrescribedSet<const D: usize> {
    /// Name (for the diagnostics' columns).
    pub name: String,
    pub particles: Vec<usize>,
    pub velocity: Vector<D>,
    pub components: [bool; D],
    pub amplitude: Option<Amplitude>,
}

impl<const D: usize> PrescribedSet<D> {
    /// The set's velocity at time `at` (scaled by its amplitude if it has one).
    fn velocity_at(&self, at: f64) -> Vector<D> {
        match &self.amplitude {
            None => self.velocity,
            Some(amplitude) => self.velocity * amplitude.factor(at),
        }
    }
}

/// Marks a component no set holds.
const FREE: u32 = u32::MAX;

/// One particle held in at least one component.
#[derive(Debug, Clone)]
struct Held<const D: usize> {
    /// Global particle index.
    particle: usize,
    /// Per component, the set whose value is imposed (the last set in scene order that holds
    /// it, as sets are applied in order), or [`FREE`].
    owner: [u32; D],
}

/// The prescribed-velocity sets with their bookkeeping: each set's force on its particles and
/// the work it has done.
#[derive(Debug, Clone)]
pub(crate) struct Drivers<const D: usize> {
    sets: Vec<PrescribedSet<D>>,
    /// Every held particle once, in ascending index order.
    held: Vec<Held<D>>,
    /// Each set's velocity at the last imposition time.
    current: Vec<Vector<D>>,
    /// Σ m a_e over the held components of each set: the effect forces taken over this step.
    absorbed: Vec<Vector<D>>,
    /// Σ m a_e·v̄ Δt* over the held components of each set: the effect forces' work this step.
    absorbed_work: Vec<f64>,
    /// Force of each set on its particles in the last step \[N\].
    forces: Vec<Vector<D>>,
    /// Work done by each set on its particles over all the kicks so far \[J\].
    work: Vec<f64>,
    /// The part of `work` done after t^n: the last kick spans t^n − ½Δt^n … t^n + ½Δt^{n+1},
    /// and the work up to t^n leaves out its share ½Δt^{n+1}/Δt* (the trapezoidal rule of the
    /// internal energy's midpoint stress, so the two stay paired at every instant).
    pending: Vec<f64>,
}

impl<const D: usize> Drivers<D> {
    /// The sets over `n_real` particles (particle indices already checked to be in range).
    pub fn new(sets: Vec<PrescribedSet<D>>, n_real: usize) -> Self {
        let mut owner = vec![[FREE; D]; if sets.is_empty() { 0 } else { n_real }];
        for (s, set) in sets.iter().enumerate() {
            for &i in &set.particles {
                for (o, &held) in owner[i].iter_mut().zip(&set.components) {
                    if held {
                        *o = s as u32;
                    }
                }
            }
        }
        let held = owner
            .into_iter()
            .enumerate()
            .filter(|(_, o)| o.iter().any(|&s| s != FREE))
            .map(|(particle, owner)| Held { particle, owner })
            .collect();
        let n = sets.len();
        let current = sets.iter().map(|s| s.velocity_at(0.0)).collect();
        Self {
            sets,
            held,
            current,
            absorbed: vec![Vector::zeros(); n],
            absorbed_work: vec![0.0; n],
            forces: vec![Vector::zeros(); n],
            work: vec![0.0; n],
            pending: vec![0.0; n],
        }
    }

    /// Each held particle (ascending global index) with the components held.
    pub fn held_components(&self) -> impl Iterator<Item = (usize, [bool; D])> + '_ {
        self.held
            .iter()
            .map(|h| (h.particle, h.owner.map(|s| s != FREE)))
    }

    /// Sets the held components of `velocities` to the sets' values at time `at` (no
    /// bookkeeping: the initial state, or velocities overwritten from outside).
    pub fn impose(&mut self, velocities: &mut [Vector<D>], at: f64) {
        self.update_current(at);
        self.impose_current(velocities);
    }

    /// Takes the sets' velocities at time `at` (the mid-point time of the coming drift) as
    /// the values this step imposes, before the effects are absorbed (their work on the held
    /// components is taken at the mid-step velocity, which ends at these values).
    pub fn prepare_step(&mut self, at: f64) {
        self.update_current(at);
    }

    /// Sets the held components of `field` to the values of the last imposition (the XSPH
    /// transport velocities, so a held particle never drifts with its neighbours' average).
    pub fn impose_current(&self, field: &mut [Vector<D>]) {
        for h in &self.held {
            for (c, &s) in h.owner.iter().enumerate() {
                if s != FREE {
                    field[h.particle][c] = self.current[s as usize][c];
                }
            }
        }
    }

    /// Takes an effect's accelerations `share` at the held components over: zeroes them there
    /// (the driver holds the component whatever acts on it, so the effect moves it not at all
    /// and is no part of its resultant), adds m a_e to the owning set's absorbed force, and
    /// returns the effect's work on the held components over the kick `kick`,
    /// Σ m a_e·v̄ Δt* with v̄ = ½(v^{n−½} + v_p) (module docs), which the set books as done
    /// against it. Call after [`Self::prepare_step`] and the internal-force kick (`particles`
    /// holds v^{n−½} + Δt* a^n and a^n).
    pub fn absorb(&mut self, share: &mut [Vector<D>], particles: &Particles<D>, kick: f64) -> f64 {
        let p = particles;
        let mut held_work = 0.0;
        for h in &self.held {
            let i = h.particle;
            for (c, &s) in h.owner.iter().enumerate() {
                if s != FREE {
                    let s = s as usize;
                    let a = &mut share[i][c];
                    let force = p.masses[i] * *a;
                    let before = p.velocities[i][c] - kick * p.accelerations[i][c];
                    let work = force * 0.5 * (before + self.current[s][c]) * kick;
                    self.absorbed[s][c] += force;
                    self.absorbed_work[s] += work;
                    held_work += work;
                    *a = 0.0;
                }
            }
        }
        held_work
    }

    /// After the kick by Δt* = ½(`dt` + `next_dt`) of the step that ends at t^n: imposes the
    /// sets' velocities taken by [`Self::prepare_step`] (at the mid-point time of the coming
    /// drift), stores the
    /// acceleration the held components actually had, (v_p − v^{n−½})/Δt*, so the velocity
    /// reported at t^n interpolates between the two half steps as for a free particle, and
    /// books each set's force and work (module docs).
    pub fn drive(&mut self, particles: &mut Particles<D>, dt: f64, next_dt: f64) {
        let kick = 0.5 * (dt + next_dt);
        let forward = if kick > 0.0 {
            0.5 * next_dt / kick
        } else {
            0.0
        };
        self.forces.fill(Vector::zeros());
        self.pending.fill(0.0);
        let p = particles;
        for h in &self.held {
            let i = h.particle;
            let m = p.masses[i];
            for (c, &s) in h.owner.iter().enumerate() {
                if s == FREE {
                    continue;
                }
                let s = s as usize;
                let kicked = p.velocities[i][c];
                let before = kicked - kick * p.accelerations[i][c];
                let imposed = self.current[s][c];
                let impulse = m * (imposed - kicked);
                let work = impulse * 0.5 * (before + imposed);
                self.work[s] += work;
                p.velocities[i][c] = imposed;
                self.pending[s] += work * forward;
                if kick > 0.0 {
                    self.forces[s][c] += impulse / kick;
                    p.accelerations[i][c] = (imposed - before) / kick;
                } else {
                    p.accelerations[i][c] = 0.0;
                }
            }
        }
        // The effect forces taken over: out of the force, and their work out of the work.
        for (s, (f, a)) in self.forces.iter_mut().zip(&mut self.absorbed).enumerate() {
            *f -= *a;
            *a = Vector::zeros();
            let taken = std::mem::take(&mut self.absorbed_work[s]);
            self.work[s] -= taken;
            self.pending[s] -= taken * forward;
        }
    }

    /// Each set's name, force on its particles in the last step \[N\] and work done up to
    /// t^n \[J\], in scene order.
    pub fn reports(&self) -> impl Iterator<Item = (&str, Vector<D>, f64)> + '_ {
        self.sets
            .iter()
            .zip(&self.forces)
            .zip(self.work.iter().zip(&self.pending))
            .map(|((s, f), (w, pending))| (s.name.as_str(), *f, w - pending))
    }

    fn update_current(&mut self, at: f64) {
        for (v, set) in self.current.iter_mut().zip(&self.sets) {
            *v = set.velocity_at(at);
        }
    }
}
