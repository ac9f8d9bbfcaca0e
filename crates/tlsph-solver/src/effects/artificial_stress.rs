//! Monaghan/Gray artificial stress (numerics.md §10.3; F 3.5–3.7; Monaghan 2000,
//! Gray–Monaghan–Swift 2001) for updated-Lagrangian SPH: a short-range repulsion between
//! particles in tension that counters the tensile instability. Its work is booked like every
//! effect's, so the energy it injects or removes is visible in `energy.csv`.

use super::{Effect, EffectContext};
use rayon::prelude::*;
use tlsph_math::{project, Tensor3, Vector};

/// R_I = −ε Q diag(max(σ'_k, 0)/ρ_I²) Qᵀ from the principal stresses σ'_k and axes Q of σ_I
/// (tension positive); a_I = Σ_J m_J (R_I + R_J) f_IJⁿ ∇_I W_IJ with f_IJ = W_IJ / W(Δx).
/// Particles of bodies that do not carry the correction have R_I = 0 (no eigen-decomposition);
/// particles of bodies that cannot meet a carrying one (other kernel group) are skipped.
#[derive(Debug, Clone)]
pub struct MonaghanArtificialStress {
    epsilon: f64,
    exponent: f64,
    /// Per body: whether its particles carry R_I.
    carries: Vec<bool>,
    /// Per body: whether its particles can feel the term (it carries R or shares a kernel
    /// group with a body that does).
    feels: Vec<bool>,
    /// Body index of each particle (updated-Lagrangian symmetry ghosts included).
    body: Vec<u32>,
    /// W(Δx) of each body (Δx its initial spacing).
    reference_value: Vec<f64>,
    /// R_I per particle (3x3, in-plane block used).
    correction: Vec<Tensor3>,
}

impl MonaghanArtificialStress {
    /// `carries`, `feels` and `reference_value` = W(Δx) per body, `body` per particle.
    pub(crate) fn new(
        epsilon: f64,
        exponent: f64,
        carries: Vec<bool>,
        feels: Vec<bool>,
        body: Vec<u32>,
        reference_value: Vec<f64>,
    ) -> Self {
        let n = body.len();
        Self {
            epsilon,
            exponent,
            carries,
            feels,
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

    fn ghosts_rebuilt(&mut self, body: &[u32]) {
        self.body.clear();
        self.body.extend_from_slice(body);
        // A ghost's R is computed from its mirrored stress: M R M.
        self.correction.resize(body.len(), Tensor3::zeros());
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let Some(pairs) = ctx.pairs else {
            // Refused at setup for the total-Lagrangian formulations.
            return;
        };
        let epsilon = self.epsilon;
        let (body, carries) = (&self.body, &self.carries);
        self.correction
            .par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, r)| {
                if !carries[body[i] as usize] {
                    // Stays zero from construction.
                    return;
                }
                let density = p.masses[i] / (p.volumes0[i] * p.jacobian[i]);
                let eigen = p.stress[i].symmetric_eigen();
                let scaled = eigen
                    .eigenvalues
                    .map(|s| -epsilon * s.max(0.0) / (density * density));
                *r = eigen.eigenvectors
                    * Tensor3::from_diagonal(&scaled)
                    * eigen.eigenvectors.transpose();
            });
        let (reference, correction, feels) = (&self.reference_value, &self.correction, &self.feels);
        let exponent = self.exponent;
        out.par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, a)| {
                if !feels[body[i] as usize] {
                    // No pair of this particle has a non-zero R_I + R_J.
                    *a = Vector::zeros();
                    return;
                }
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
