//! Total-Lagrangian SPH for solids under dynamic loading (Reveles 2007, Algorithms 1–3).
//!
//! The solver owns particle state (structure of arrays), the reference-configuration bonds with
//! their (corrected) kernel gradients, the constitutive update per material group and the
//! staggered leap-frog integrator. It does no file access and no printing: setup returns a
//! [`SetupError`], a step returns a [`StepReport`] or a [`StepError`] naming step, particle and
//! field.
//!
//! Flow of one step (see `ARCHITECTURE.md`): drift u → gather F, Ḟ over bonds → constitutive
//! update per body → internal forces gathered over bonds → boundary conditions → new Δt (CFL)
//! → kick v.

mod bonds;
mod damage;
mod diagnostics;
mod effects;
mod error;
mod fields;
mod ghosts;
mod model;
mod particles;
mod plasticity;
mod prescribed;
mod reference;
mod simulation;
pub mod stability;
mod step;
mod updated_lagrangian;

pub use bonds::{Bonds, CorrectionReport};
pub use diagnostics::Diagnostics;
pub use error::{LimitingParticle, SetupError, StepError};
pub use fields::ParticleField;
pub use ghosts::MIN_PLANE_DISTANCE;
pub use model::{
    linear_stress_at, Amplitude, AmplitudeTable, ArtificialStress, BodyDescription,
    BodyForceDescription, BoundaryDescription, BulkViscosity, ContactDescription, DamageModel,
    EffectsDescription, ElasticDamage, ElasticPlastic, FailureModel, Formulation,
    FrictionCoefficients, InitialTimeStep, MaterialDescription, MaterialModel, Model,
    PenaltyContactDescription, PressureModel, RampShape, ReferenceSupport, ReferenceUpdate,
    SimulationConfig, StrengthModel, StressUpdate, SymmetryPlane, TableShape, Thermal,
    VelocityRamp, WallDescription, WallMotion, WallShape, INITIAL_YIELD_TOLERANCE,
};
pub use simulation::{
    check_kinetic_energy, particle_kinetic_energy, BodyInfo, BondMetrics, Simulation, StepReport,
};
pub use tlsph_kernels::KernelKind;
pub use updated_lagrangian::{CurrentPairs, SKIN_FRACTION};
