//! Monaghan's pairwise artificial viscosity for TLSPH (numerics.md §10.1, TL use): evaluated in
//! the current configuration for the reference neighbour pairs of each body, repulsive on
//! approach, pairwise antisymmetric (momentum conserving); its work is booked as dissipation.

use super::{Effect, EffectContext};
use rayon::prelude::*;
use tlsph_kernels::{AnyKernel, Kernel};
use tlsph_math::Vector;

/// Π_IJ = (−α c̄ μ_IJ + β μ_IJ²)/ρ̄_IJ for v_IJ·x_IJ < 0, μ_IJ = h v_IJ·x_IJ/(|x_IJ|² + 0.01h²);
/// a_I = −Σ_J m_J Π_IJ ∇_I W(x_I − x_J, h).
#[derive(Debug, Clone)]
pub struct MonaghanViscosity {
    alpha: f64,
    beta: f64,
    /// Kernel of each body.
    kernels: Vec<AnyKernel>,
    /// Body index of each real particle.
    body: Vec<u32>,
    /// Reference density and sound speed of each body.
    density0: Vec<f64>,
    sound_speed0: Vec<f64>,
}

impl MonaghanViscosity {
    /// `kernels`, `density0`, `sound_speed0` per body; `body` per real particle.
    pub(crate) fn new(
        alpha: f64,
        beta: f64,
        kernels: Vec<AnyKernel>,
        body: Vec<u32>,
        density0: Vec<f64>,
        sound_speed0: Vec<f64>,
    ) -> Self {
        Self {
            alpha,
            beta,
            kernels,
            body,
            density0,
            sound_speed0,
        }
    }
}

impl<const D: usize> Effect<D> for MonaghanViscosity {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        "artificial_viscosity"
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let b = ctx.bonds;
        let n_real = out.len();
        let this = &*self;
        out.par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, a)| {
                let body = this.body[i] as usize;
                let kernel = &this.kernels[body];
                let h = kernel.smoothing_length();
                let xi = p.positions0[i] + p.displacements[i];
                // Velocity at t^n: undo half of this step's kick.
                let vi = p.velocities[i] - p.accelerations[i] * (0.5 * ctx.kick);
                let rho_i = this.density0[body] / p.jacobian[i];
                let c_i = this.sound_speed0[body] * p.jacobian[i].max(0.0).sqrt();
                let mut acc = Vector::<D>::zeros();
                for &j in b.neighbours_of(i) {
                    let j = j as usize;
                    if j >= n_real {
                        continue;
                    }
                    let x_ij = xi - (p.positions0[j] + p.displacements[j]);
                    let v_ij = vi - (p.velocities[j] - p.accelerations[j] * (0.5 * ctx.kick));
                    let approach = v_ij.dot(&x_ij);
                    if approach >= 0.0 {
                        continue;
                    }
                    let mu = h * approach / (x_ij.norm_squared() + 0.01 * h * h);
                    let rho_j = this.density0[body] / p.jacobian[j];
                    let c_j = this.sound_speed0[body] * p.jacobian[j].max(0.0).sqrt();
                    let pi = (-this.alpha * 0.5 * (c_i + c_j) * mu + this.beta * mu * mu)
                        / (0.5 * (rho_i + rho_j));
                    acc -= kernel.gradient(&x_ij) * (p.masses[j] * pi);
                }
                *a = acc;
            });
    }
}
