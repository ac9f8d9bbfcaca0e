//! Monaghan/Gray artificial stress (numerics.md §10.3; F 3.5–3.7; Monaghan 2000,
//! Gray–Monaghan–Swift 2001) for updated-Lagrangian SPH: a short-range repulsion between
//! particles in tension that counters the tensile instability. Its work is booked like every
//! effect's, so the energy it injects or removes is visible in `energy.csv`.

use super::{Effect, EffectContext};
use rayon::prelude::*;
use tlsph_math::{project, Tensor3, Vector};

/// R_I = −ε Q diag(max(σ'_k, 0)/ρ_I²) Qᵀ from the principal stresses σ'_k and axes Q of σ_I
/// (tension positive); a_I = Σ_J m_J (R_I + R_J) f_IJⁿ ∇_I W_IJ with f_IJ = W_IJ / W(Δx).
#[derive(Debug, Clone)]
pub struct MonaghanArtificialStress {
    epsilon: f64,
    exponent: f64,
    /// Body index of each particle.
    body: Vec<u32>,
    /// W(Δx) of each body (Δx its initial spacing).
    reference_value: Vec<f64>,
    /// R_I per particle (3x3, in-plane block used).
    correction: Vec<Tensor3>,
}

impl MonaghanArtificialStress {
    /// `reference_value` = W(Δx) per body, `body` per particle.
    pub(crate) fn new(
        epsilon: f64,
        exponent: f64,
        body: Vec<u32>,
        reference_value: Vec<f64>,
    ) -> Self {
        let n = body.len();
        Self {
            epsilon,
            exponent,
            body,
            reference_value,
            correction: vec![Tensor3::zeros(); n],
        }
    }
}

impl<const D: usize> Effect<D> for MonaghanArtificialStress {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        "artificial_stress"
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let Some(pairs) = ctx.pairs else {
            // Refused at setup for the total-Lagrangian formulations.
            return;
        };
        let epsilon = self.epsilon;
        self.correction
            .par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, r)| {
                let density = p.masses[i] / (p.volumes0[i] * p.jacobian[i]);
                let eigen = p.stress[i].symmetric_eigen();
                let scaled = eigen
                    .eigenvalues
                    .map(|s| -epsilon * s.max(0.0) / (density * density));
                *r = eigen.eigenvectors
                    * Tensor3::from_diagonal(&scaled)
                    * eigen.eigenvectors.transpose();
            });
        let (body, reference, correction) = (&self.body, &self.reference_value, &self.correction);
        let exponent = self.exponent;
        out.par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, a)| {
                let r_i = correction[i];
                let mut acc = Vector::<D>::zeros();
                let range = pairs.range(i);
                for ((&j, g), w) in pairs.neighbours[range.clone()]
                    .iter()
                    .zip(&pairs.gradient[range.clone()])
                    .zip(&pairs.value[range])
                {
                    let j = j as usize;
                    let w_ref = 0.5 * (reference[body[i] as usize] + reference[body[j] as usize]);
                    let f = (w / w_ref).powf(exponent);
                    acc += project::<D>(&(r_i + correction[j])) * g * (p.masses[j] * f);
                }
                *a = acc;
            });
    }
}
