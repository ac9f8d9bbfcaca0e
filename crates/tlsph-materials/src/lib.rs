//! Pointwise constitutive models. A model sees one material point (3x3 tensors and scalars);
//! it never reads particle indices or neighbours and never spawns threads.
//!
//! 1D problems are uniaxial strain and 2D problems plane strain: the solver embeds its
//! `D`x`D` kinematics into 3x3 (see `tlsph_math::embed_with_identity`) before calling a model.
//!
//! - [`LinearElastic`]: elastic moduli, St Venant–Kirchhoff PK2 and the Jaumann-rate
//!   predictor (numerics.md §8.1–8.2);
//! - [`strength`]: return maps of the trial deviator — von Mises with linear hardening
//!   (§8.4) and Johnson–Cook (§8.5);
//! - [`eos`]: pressure from compression and energy — linear, polynomial, Mie–Grüneisen,
//!   pressure cutoff (§8.3, §8.7–8.9);
//! - [`damage`]: Johnson–Cook failure strain, stress/plastic-strain criteria, Peerlings
//!   softening and Grady–Kipp flaws (§8.6, §9.1–9.2);
//! - [`thermal`]: adiabatic temperature rise (§8.5).
//!
//! Every model validates its parameters on construction and reports a [`MaterialError`] that
//! names the scene-file field.

pub mod damage;
pub mod eos;
mod error;
mod linear_elastic;
mod principal;
mod rng;
pub mod strength;
pub mod thermal;

pub use damage::{
    GradyKipp, JohnsonCookFailure, MaxPlasticStrainFailure, MaxStressFailure, PeerlingsSoftening,
};
pub use eos::{EquationOfState, LinearEos, MieGruneisen, PolynomialEos, PressureCutoff};
pub use error::MaterialError;
pub use linear_elastic::LinearElastic;
pub use principal::max_principal_value;
pub use strength::{
    equivalent_strain_rate, JohnsonCookStrength, PlasticReturn, VonMisesPlasticity,
};
pub use thermal::adiabatic_temperature_rise;
