//! Pointwise constitutive models. A model sees one material point (3x3 tensors and scalars);
//! it never reads particle indices or neighbours and never spawns threads.
//!
//! 1D problems are uniaxial strain and 2D problems plane strain: the solver embeds its
//! `D`x`D` kinematics into 3x3 (see `tlsph_math::embed_with_identity`) before calling a model.

mod error;
mod linear_elastic;

pub use error::MaterialError;
pub use linear_elastic::LinearElastic;
