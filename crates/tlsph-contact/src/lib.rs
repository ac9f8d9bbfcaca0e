//! Contact between SPH bodies in the current configuration (numerics.md §12–13). Pair laws and
//! the bookkeeping of who may touch whom; knows nothing about stresses, bonds, time stepping or
//! energy booking, which stay with the solver that drives it.
//!
//! * [`ContactCandidates`]: the particles that take part, their current positions, and a
//!   Verlet list of candidate partners over a cell grid, rebuilt only once a participant has
//!   moved half the skin; deterministic sums and the stiffness time-step vote.
//! * [`PotentialLaw`]: the potential-type particle contact of numerics.md §12.2 (Vignjevic et
//!   al.), f = a M* d0^{d−1} [(W(r)/W(d0))ⁿ − 1]₊ along the pair line, with its potential and
//!   tangent stiffness.
//! * [`PenaltyLaw`]: Fuller's particle-type penalty contact with Coulomb friction
//!   (numerics.md §12.1, F §4.3–4.4), with the surface test [`is_surface`] and the outward
//!   normal [`OutwardNormal`] it needs.
//! * [`RigidPlane`]: a fixed rigid plane (an anvil) pushing back particles by a penalty
//!   spring, [`FlatDisc`]: a flat wall of finite size (a disc, a segment in 2D) with a rounded
//!   rim, [`RigidBall`]: a rigid sphere (an indenter), [`RigidCylinder`]: a rigid cylinder of
//!   unbounded length (a roller), [`FiniteCylinder`]: a solid cylinder with flat ends (a
//!   cylindrical punch, a pin), [`RigidBox`]: a rectangle or a rectangular block with sharp
//!   or rounded edges (a rectangular punch, a die, a step), [`RigidCone`]: a cone (a wedge in
//!   2D) with a sharp or rounded tip (a conical or wedge indenter), [`RigidPyramid`]: a
//!   regular pyramid with a sharp or rounded tip (a Vickers or Berkovich indenter), all behind
//!   [`WallGeometry`]; and their Coulomb friction
//!   [`wall_friction_acceleration`], which on a spinning wall reads the velocity
//!   [`spin_velocity`] of the wall's [`surface_point`]. Both friction laws take
//!   [`FrictionCoefficients`]: static and kinetic, with an optional exponential decay of the
//!   sliding coefficient with speed (numerics.md §13).
//!
//! Every law is a function of one pair (or one particle and the plane), evaluated identically
//! from both ends, so a solver that gathers per particle gets equal and opposite forces bit
//! for bit, whatever the thread count.
//!
//! ```
//! use tlsph_contact::{ContactCandidates, KernelKind, PotentialLaw, Vector, SKIN_FRACTION};
//!
//! // Two particles of different bodies 0.8Δx apart, Δx = 1, h = 1.2, n = 4.
//! let kernel = KernelKind::CubicSpline.build(2, 1.2).unwrap();
//! let law = PotentialLaw::new(kernel, 1.0, 2.0, 4.0, 0.0);
//! let positions = [Vector::<2>::new(0.0, 0.0), Vector::<2>::new(0.8, 0.0)];
//! let displacements = [Vector::<2>::zeros(); 2];
//! let mut list = ContactCandidates::new(&[0, 1], |_| true, law.d0(), SKIN_FRACTION);
//! list.refresh(&positions, &displacements, |pair| pair.across_bodies());
//! assert_eq!(list.of(0), &[1]);
//! let state = law.evaluate(0.8);
//! assert!(state.force > 0.0 && state.potential > 0.0);
//! assert!(law.evaluate(law.d0()).force.abs() < 1e-12); // zero at the contact distance
//! ```

#![warn(missing_docs)]

mod candidates;
mod penalty;
mod potential;
mod wall;

pub use candidates::{CandidateOffer, ContactCandidates, ImagePartner, PARTICIPANTS_PER_TASK};
pub use penalty::{is_surface, OutwardNormal, PenaltyLaw, SURFACE_FRACTION};
pub use potential::{PotentialLaw, PotentialPairState};
pub use tlsph_kernels::{AnyKernel, Kernel, KernelKind};
pub use tlsph_math::{PlaneReflections, Vector};
pub use wall::{
    spin_velocity, surface_point, wall_friction_acceleration, FiniteCylinder, FlatDisc,
    FrictionCoefficients, RigidBall, RigidBox, RigidCone, RigidCylinder, RigidPlane, RigidPyramid,
    WallGeometry, WALL_STIFFNESS_FACTOR,
};

/// Verlet skin of a candidate list as a fraction of the smallest contact distance d0: the list
/// holds every pair within (largest reach + skin) and is rebuilt once any participant has
/// moved by half the skin since the last build, so no pair that can touch is ever missing.
/// Half a spacing keeps rebuilds to one every few steps even for a flyer at 0.1 c (it moves
/// ≈ 0.1 · C_cfl · h per step) while adding only a few candidates per surface particle.
pub const SKIN_FRACTION: f64 = 0.5;

/// Safety factor of the contact time-step bound Δt ≤ 0.5 sqrt(m/k) (numerics.md §7 `[C]`),
/// used with [`ContactCandidates::stiffness_time_step`].
pub const DT_FACTOR: f64 = 0.5;
