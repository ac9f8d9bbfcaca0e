//! Optional effects declared by a scene (rigid walls, hourglass control, ...). Each effect is
//! one file; it owns its state, adds its accelerations once per step, votes on nothing it does
//! not constrain, and has its work booked so total energy closes. An effect that a scene does
//! not declare is not in the list: it allocates nothing and costs nothing.

mod artificial_stress;
mod body_force;
mod hourglass;
mod monaghan_viscosity;
mod particle_contact;
mod penalty_contact;
mod rigid_wall;

pub use artificial_stress::MonaghanArtificialStress;
pub use body_force::BodyForce;
pub use hourglass::HourglassControl;
pub use monaghan_viscosity::MonaghanViscosity;
pub use particle_contact::ParticleContact;
pub use penalty_contact::PenaltyContact;
pub use rigid_wall::RigidWall;

use crate::bonds::Bonds;
use crate::particles::Particles;
use tlsph_math::Vector;

/// Read-only view of the state at t^n that effects see.
pub(crate) struct EffectContext<'a, const D: usize> {
    /// Particle state (u^n, F^n, masses, ...).
    pub particles: &'a Particles<D>,
    /// Reference bonds.
    pub bonds: &'a Bonds<D>,
    /// Current-configuration pairs (updated-Lagrangian formulation only).
    pub pairs: Option<&'a crate::updated_lagrangian::CurrentPairs<D>>,
    /// Failed particles, ghosts included (empty unless a failure model is declared): they
    /// are out of every sum, so an effect that walks reference bonds skips them.
    pub removed: &'a [bool],
    /// This step's kick ½(Δt^n + Δt^{n+1}): velocities hold v^{n−½} + kick·a (internal forces).
    pub kick: f64,
    /// Time t^n of the configuration \[s\].
    pub time: f64,
}

/// Read-only view of the configuration at t^n on which effects vote for the time step
/// (velocities still hold v^{n−½}).
pub(crate) struct Configuration<'a, const D: usize> {
    /// Particle state (u^n, F^n, masses, ...).
    pub particles: &'a Particles<D>,
    /// Reference bonds (total-Lagrangian formulations).
    pub bonds: &'a Bonds<D>,
    /// Current-configuration pairs (updated-Lagrangian formulation only).
    pub pairs: Option<&'a crate::updated_lagrangian::CurrentPairs<D>>,
    /// Time t^n of the configuration \[s\].
    pub time: f64,
}

/// Whether particle `i` takes part in the sums (it has not failed).
#[inline]
pub(crate) fn alive(removed: &[bool], i: usize) -> bool {
    removed.get(i) != Some(&true)
}

/// An optional force contribution.
pub(crate) trait Effect<const D: usize>: Send + Sync + std::fmt::Debug {
    /// Name of the energy column booked for this effect in `energy.csv`.
    fn name(&self) -> &str;

    /// Writes this effect's accelerations at t^n into `out` (zeroed by the caller, one entry
    /// per particle). Must be a gather per particle (deterministic for any thread count).
    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]);

    /// Resultant force of the last step (e.g. the wall reaction), if the effect reports one.
    fn resultant(&self) -> Option<Vector<D>> {
        None
    }

    /// Records the resultant of the accelerations just computed.
    fn set_resultant(&mut self, _force: Vector<D>) {}

    /// Moment of the last step's force about the effect's own axis (a spinning wall: the
    /// torque its friction exerts on the particles) \[N m\], if the effect reports one.
    fn torque(&self) -> Option<f64> {
        None
    }

    /// Moment vector M = Σ (y − c) × F of the last step's force about the effect's reference
    /// point c (a wall with `report_moment`: its current point), padded to 3D \[N m\], if the
    /// effect reports one.
    fn moment(&self) -> Option<tlsph_math::Vector3> {
        None
    }

    /// Sees the accelerations `applied` that this effect's kick gave the particles at t^n
    /// (its own, less the prescribed components the drivers took over), for an effect that
    /// reports more than their resultant (a spinning wall's torque).
    fn record_applied(&mut self, _ctx: &EffectContext<'_, D>, _applied: &[Vector<D>]) {}

    /// Energy stored by a conservative effect at t^n (a penalty spring) \[J\]. When `Some`, it
    /// is booked directly instead of integrating the work, which for stiff, impulsive forces
    /// would carry the time-integration error of a few large steps.
    fn stored_energy(&self) -> Option<f64> {
        None
    }

    /// The effect's vote on the next step, (Δt limit, limiting particle), evaluated at x^n
    /// before the forces (numerics.md §7); `None` when it does not constrain the step.
    fn time_step_limit(&mut self, _at: &Configuration<'_, D>) -> Option<(f64, usize)> {
        None
    }

    /// Candidate-list rebuilds so far, for an effect that searches pairs (contact).
    fn contact_rebuilds(&self) -> Option<u64> {
        None
    }

    /// The reference configuration was replaced by the current one (numerics.md §4 `[C]`):
    /// an effect that keeps per-bond reference data rebuilds it from the new `bonds` and the
    /// reference positions and volumes in `particles`.
    fn reference_changed(&mut self, _particles: &Particles<D>, _bonds: &Bonds<D>) {}

    /// The symmetry ghosts were built or rebuilt (total-Lagrangian: at setup and at a
    /// reference update; updated-Lagrangian: with every Verlet list): `body` gives the body of
    /// every particle, ghosts (appended after the reals) included. An effect that keeps
    /// per-particle data indexed by neighbours extends it to the ghosts.
    fn ghosts_rebuilt(&mut self, _body: &[u32]) {}

    /// A boxed copy (simulations are `Clone`).
    fn clone_box(&self) -> Box<dyn Effect<D>>;
}

/// An effect with its booked energy: −∫ Σ f·v dt, the energy the mechanism has taken out of
/// the particles (stored in a penalty spring or dissipated).
#[derive(Debug)]
pub(crate) struct BookedEffect<const D: usize> {
    pub effect: Box<dyn Effect<D>>,
    /// Energy booked over all the kicks so far \[J\].
    pub energy: f64,
    /// The part of `energy` booked for the time after t^n (the forward half of the last
    /// kick), left out of the energy reported at t^n.
    pub pending: f64,
    /// The work of this step's force on the prescribed components, which their drivers took
    /// over (`Drivers::absorb`): booked here as the effect's, and by the drivers as done
    /// against it, so each column is the work of its own force \[J\].
    pub held_work: f64,
}

impl<const D: usize> BookedEffect<D> {
    /// `effect` with nothing booked yet.
    pub fn new(effect: Box<dyn Effect<D>>) -> Self {
        Self {
            effect,
            energy: 0.0,
            pending: 0.0,
            held_work: 0.0,
        }
    }
}

impl<const D: usize> Clone for BookedEffect<D> {
    fn clone(&self) -> Self {
        Self {
            effect: self.effect.clone_box(),
            energy: self.energy,
            pending: self.pending,
            held_work: self.held_work,
        }
    }
}
