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
//!
//! The kernel support on the new reference ([`ReferenceSupport`]): with the body's h for every
//! particle, a particle stretched by λ in some direction has neighbours only within 2h/λ
//! initial spacings along it (in a Taylor foot, λ ≈ 2 in the hoop direction: one ring of
//! neighbours at the edge of the support). Its gradients then hardly see that direction and
//! the foot spreads too far (16 % wider than FE in the copper benchmark, at every spacing).
//! By default each particle's smoothing length becomes h_I = h max(1, λ_max(F0_I)) with F0 the
//! deformation of the new reference from the initial configuration, so the support covers the
//! image of the initial one; pairs use h_IJ = (h_I + h_J)/2 (`bonds::PairKernel`).

use crate::model::ReferenceSupport;
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
    /// How supports are chosen on a new reference.
    pub support: ReferenceSupport,
    /// F0 of the current reference relative to the initial configuration, per real particle
    /// (only with [`ReferenceSupport::Stretched`]; empty otherwise).
    pub deformation: Vec<Tensor<D>>,
    /// Smoothing length over the body's, per real particle (empty: all 1).
    pub kernel_scale: Vec<f64>,
}

impl<const D: usize> ReferenceState<D> {
    /// The initial configuration as reference.
    pub fn new(
        strain_threshold: f64,
        support: ReferenceSupport,
        initial_positions: &[Vector<D>],
    ) -> Self {
        let n = initial_positions.len();
        let stretched = support == ReferenceSupport::Stretched;
        Self {
            strain_threshold,
            initial_positions: initial_positions.to_vec(),
            jacobian: vec![1.0; n],
            updates: 0,
            support,
            deformation: if stretched {
                vec![Tensor::identity(); n]
            } else {
                Vec::new()
            },
            kernel_scale: Vec::new(),
        }
    }

    /// Carries the deformation F (relative to the old reference) of every real particle into
    /// F0 and, with stretched supports, sets each particle's kernel factor max(1, λ_max(F0)).
    pub fn advance(&mut self, deformation_gradients: &[Tensor<D>]) {
        if self.support == ReferenceSupport::Fixed {
            return;
        }
        self.deformation
            .par_iter_mut()
            .zip(deformation_gradients)
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .for_each(|(f0, f)| *f0 = f * *f0);
        self.kernel_scale = self
            .deformation
            .par_iter()
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .map(support_factor)
            .collect();
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

/// max(1, λ_max) for the largest principal stretch λ_max = sqrt(max eig FᵀF) of a D×D
/// deformation gradient (the padding of a 1D or 2D F to 3×3 adds a stretch of exactly 1).
pub(crate) fn support_factor<const D: usize>(f: &Tensor<D>) -> f64 {
    let c: tlsph_math::Tensor3 = tlsph_math::embed_with_identity(&(f.transpose() * f));
    c.symmetric_eigenvalues()
        .iter()
        .fold(1.0f64, |a, &e| a.max(e))
        .sqrt()
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
        let state = ReferenceState::<2>::new(0.2, ReferenceSupport::Fixed, &[Vector::zeros(); 2]);
        assert!(!state.due(&[rotation, rotation]));
        assert!(state.due(&[rotation, rotation * stretch]));
    }

    #[test]
    fn support_factor_is_the_largest_stretch_and_never_shrinks_a_support() {
        let (c, s) = (0.6_f64, 0.8_f64);
        let rotation = Tensor::<2>::new(c, -s, s, c);
        approx::assert_relative_eq!(support_factor(&rotation), 1.0, epsilon = 1e-12);
        // Compressed 2 × in x and stretched 1.5 × in y, then rotated: λ_max = 1.5.
        let stretch = Tensor::<2>::new(0.5, 0.0, 0.0, 1.5);
        approx::assert_relative_eq!(support_factor(&(rotation * stretch)), 1.5, epsilon = 1e-12);
        // Pure compression: the factor stays 1 (the support is never made smaller than h).
        let squeeze = Tensor::<3>::from_diagonal(&Vector::<3>::new(0.5, 0.8, 0.9));
        approx::assert_relative_eq!(support_factor(&squeeze), 1.0, epsilon = 1e-12);
        // Simple shear γ = 2: λ_max = (γ + sqrt(γ² + 4)) / 2 = 1 + √2.
        let shear = Tensor::<2>::new(1.0, 2.0, 0.0, 1.0);
        approx::assert_relative_eq!(support_factor(&shear), 1.0 + 2f64.sqrt(), epsilon = 1e-12);
    }

    #[test]
    fn advance_composes_deformations_and_fixed_supports_keep_no_state() {
        let positions = [Vector::<2>::zeros(); 2];
        let step = Tensor::<2>::new(1.2, 0.0, 0.0, 1.0);
        let mut stretched = ReferenceState::<2>::new(0.1, ReferenceSupport::Stretched, &positions);
        stretched.advance(&[step, Tensor::identity()]);
        stretched.advance(&[step, Tensor::identity()]);
        approx::assert_relative_eq!(stretched.kernel_scale[0], 1.44, epsilon = 1e-12);
        approx::assert_relative_eq!(stretched.kernel_scale[1], 1.0, epsilon = 1e-12);
        let mut fixed = ReferenceState::<2>::new(0.1, ReferenceSupport::Fixed, &positions);
        fixed.advance(&[step, step]);
        assert!(fixed.deformation.is_empty() && fixed.kernel_scale.is_empty());
    }
}
