//! Monaghan's pairwise artificial viscosity (numerics.md §10.1): for TLSPH evaluated in the
//! current configuration for the reference neighbour pairs of each body (TL use), for
//! updated-Lagrangian SPH over the current pairs. Repulsive on approach, pairwise antisymmetric
//! (momentum conserving); its work is booked as dissipation.

use super::{alive, Effect, EffectContext};
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
    /// Body index of each particle (updated-Lagrangian symmetry ghosts included).
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

    fn ghosts_rebuilt(&mut self, body: &[u32]) {
        self.body.clear();
        self.body.extend_from_slice(body);
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let removed = ctx.removed;
        let this = &*self;
        let position = |j: usize| p.positions0[j] + p.displacements[j];
        match ctx.pairs {
            // Updated-Lagrangian: the current pairs with their (pair-averaged) gradients.
            Some(pairs) => this.gather(ctx, out, |i| {
                let r = pairs.range(i);
                pairs.neighbours[r.clone()]
                    .iter()
                    .zip(&pairs.gradient[r])
                    .map(|(&j, g)| (j as usize, *g))
            }),
            // TLSPH: the reference neighbours of the same body (symmetry ghosts included,
            // failed particles not), kernel at x^n.
            None => this.gather(ctx, out, |i| {
                let kernel = &this.kernels[this.body[i] as usize];
                let xi = position(i);
                let live = alive(removed, i);
                ctx.bonds
                    .neighbours_of(i)
                    .iter()
                    .map(|&j| j as usize)
                    .filter(move |&j| live && alive(removed, j))
                    .map(move |j| (j, kernel.gradient(&(xi - position(j)))))
            }),
        }
    }
}

impl MonaghanViscosity {
    /// a_I = −Σ_J m_J Π_IJ ∇_I W_IJ over the pairs `pairs_of(I)` = (J, ∇_I W_IJ), with v^n,
    /// ρ = ρ0/J and c = c0 sqrt(J) of each particle and h̄ = ½(h_I + h_J).
    fn gather<const D: usize, I: Iterator<Item = (usize, Vector<D>)>>(
        &self,
        ctx: &EffectContext<'_, D>,
        out: &mut [Vector<D>],
        pairs_of: impl Fn(usize) -> I + Sync,
    ) {
        let p = ctx.particles;
        // Velocity at t^n: undo half of this step's kick.
        let velocity = |j: usize| p.velocities[j] - p.accelerations[j] * (0.5 * ctx.kick);
        let state = |j: usize| {
            let body = self.body[j] as usize;
            (
                self.density0[body] / p.jacobian[j],
                self.sound_speed0[body] * p.jacobian[j].max(0.0).sqrt(),
                self.kernels[body].smoothing_length(),
            )
        };
        out.par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, a)| {
                let xi = p.positions0[i] + p.displacements[i];
                let vi = velocity(i);
                let (rho_i, c_i, h_i) = state(i);
                let mut acc = Vector::<D>::zeros();
                for (j, gradient) in pairs_of(i) {
                    let x_ij = xi - (p.positions0[j] + p.displacements[j]);
                    let approach = (vi - velocity(j)).dot(&x_ij);
                    if approach >= 0.0 {
                        continue;
                    }
                    let (rho_j, c_j, h_j) = state(j);
                    let h = 0.5 * (h_i + h_j);
                    let mu = h * approach / (x_ij.norm_squared() + 0.01 * h * h);
                    let pi = (-self.alpha * 0.5 * (c_i + c_j) * mu + self.beta * mu * mu)
                        / (0.5 * (rho_i + rho_j));
                    acc -= gradient * (p.masses[j] * pi);
                }
                *a = acc;
            });
    }
}
