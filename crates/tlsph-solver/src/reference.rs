//! Reference-configuration update for the total-Lagrangian formulations (numerics.md §4,
//! choice `[C]` of this code; the same remedy as the "update threshold" of Ganzenmüller's
//! TLSPH in LAMMPS).
//!
//! TLSPH evaluates every gradient on the reference neighbourhood. Under plastic flow with
//! strains of order one, a particle's reference neighbours no longer surround it in the
//! current configuration, the corrected gradients stop describing the local deformation, and
//! the scheme ends with an inverted particle. When any particle's strain relative to the
//! reference exceeds the declared threshold, the current configuration becomes the new
//! reference: X := x, V := V_initial det F, F := I, bonds, ghosts and corrected gradients are
//! rebuilt on the current positions, and J0 = det F (relative to the initial configuration)
//! is carried into the constitutive update, where it multiplies det F wherever the density
//! enters. The Jaumann-rate stress, the plastic state and the internal energy continue
//! unchanged because they depend only on the rate of deformation and the density.

use crate::step::MIN_PARTICLES_PER_TASK;
use rayon::prelude::*;
use tlsph_math::{Tensor, Vector};

/// State of a declared reference update: only allocated when a scene asks for it.
#[derive(Debug, Clone)]
pub(crate) struct ReferenceState<const D: usize> {
    /// Update when max_I ‖E_I‖ exceeds this (E = ½(FᵀF − I) relative to the reference).
    pub strain_threshold: f64,
    /// Initial positions of the real particles (displacements are reported against them).
    pub initial_positions: Vec<Vector<D>>,
    /// det F0 of the current reference relative to the initial configuration, per real
    /// particle.
    pub jacobian: Vec<f64>,
    /// Reference updates so far.
    pub updates: u64,
}

impl<const D: usize> ReferenceState<D> {
    /// The initial configuration as reference.
    pub fn new(strain_threshold: f64, initial_positions: &[Vector<D>]) -> Self {
        Self {
            strain_threshold,
            initial_positions: initial_positions.to_vec(),
            jacobian: vec![1.0; initial_positions.len()],
            updates: 0,
        }
    }

    /// True when some particle's Green–Lagrange strain relative to the reference exceeds the
    /// threshold (a boolean reduction: the same answer for any thread count).
    pub fn due(&self, deformation_gradients: &[Tensor<D>]) -> bool {
        let limit = self.strain_threshold;
        deformation_gradients
            .par_iter()
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .any(|f| green_lagrange_norm(f) > limit)
    }
}

/// ‖½(FᵀF − I)‖ (Frobenius norm of the Green–Lagrange strain).
pub(crate) fn green_lagrange_norm<const D: usize>(f: &Tensor<D>) -> f64 {
    ((f.transpose() * f - Tensor::<D>::identity()) * 0.5).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rotation_is_not_strain_and_a_stretch_is() {
        let (c, s) = (0.6_f64, 0.8_f64);
        let rotation = Tensor::<2>::new(c, -s, s, c);
        assert!(green_lagrange_norm(&rotation) < 1e-15);
        // Uniaxial stretch λ = 1.2: E_xx = ½(1.44 − 1) = 0.22.
        let stretch = Tensor::<2>::new(1.2, 0.0, 0.0, 1.0);
        approx::assert_relative_eq!(green_lagrange_norm(&stretch), 0.22, epsilon = 1e-14);
        let state = ReferenceState::<2>::new(0.2, &[Vector::zeros(); 2]);
        assert!(!state.due(&[rotation, rotation]));
        assert!(state.due(&[rotation, rotation * stretch]));
    }
}
