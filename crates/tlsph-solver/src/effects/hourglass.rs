//! Hourglass (zero-energy mode) control for TLSPH after Ganzenmüller (2015), numerics.md §10.5:
//! a penalty on the difference between each bond's current vector and the one the particles'
//! deformation gradients predict. Pairwise equal and opposite (momentum conserving); its work
//! is booked separately in the energy balance.

use super::{alive, Effect, EffectContext};
use crate::bonds::{Bonds, PairKernel};
use crate::particles::Particles;
use rayon::prelude::*;
use tlsph_kernels::{AnyKernel, Kernel};
use tlsph_math::Vector;

/// Ganzenmüller's hourglass penalty with dimensionless coefficient α.
///
/// f_I = ½ α Σ_J (V0_I V0_J W0_IJ / |X_IJ|²) E ((F_I + F_J) X_IJ − 2 x_IJ)·x_IJ/r · x_IJ/r,
/// with X_IJ = X_I − X_J, x_IJ = x_I − x_J, r = |x_IJ|, E the body's Young's modulus.
#[derive(Debug, Clone)]
pub struct HourglassControl {
    coefficient: f64,
    /// Kernel of each body.
    kernels: Vec<AnyKernel>,
    /// Young's modulus of each body \[Pa\].
    youngs: Vec<f64>,
    /// Body index of each real particle.
    body: Vec<u32>,
    /// Per bond: V0_J W0_IJ / |X_IJ|².
    bond_weight: Vec<f64>,
    /// Per particle: ½ α E V0_I / m_I = ½ α E / ρ0 \[m²/s²\].
    particle_factor: Vec<f64>,
}

impl HourglassControl {
    /// Precomputes the bond weights from the reference configuration. `kernels` and `youngs`
    /// (E \[Pa\]) are per body, `body` per real particle.
    pub(crate) fn new<const D: usize>(
        coefficient: f64,
        kernels: Vec<AnyKernel>,
        youngs: Vec<f64>,
        body: Vec<u32>,
        particles: &Particles<D>,
        bonds: &Bonds<D>,
    ) -> Self {
        let mut hourglass = Self {
            coefficient,
            kernels,
            youngs,
            body,
            bond_weight: Vec::new(),
            particle_factor: Vec::new(),
        };
        hourglass.weigh(particles, bonds);
        hourglass
    }

    /// Bond weights and particle factors on the current reference positions and volumes.
    fn weigh<const D: usize>(&mut self, particles: &Particles<D>, bonds: &Bonds<D>) {
        let (x0, v0) = (&particles.positions0, &particles.volumes0);
        let n = self.body.len();
        self.bond_weight.clear();
        for i in 0..n {
            let kernel = self.kernels[self.body[i] as usize];
            // The bond's own kernel: wider than the body's after a reference update that
            // widened supports.
            let pair = PairKernel {
                kernel: &kernel,
                scale: &bonds.kernel_scale,
            };
            for &j in bonds.neighbours_of(i) {
                let j = j as usize;
                let r0 = (x0[i] - x0[j]).norm();
                // |X_IJ| ≥ ½h: never binding on a lattice (spacing ≥ h/2), but a reference
                // update can bring two particles closer, where 1/|X_IJ|² would blow up.
                let r_floor = r0.max(0.5 * kernel.smoothing_length());
                self.bond_weight
                    .push(v0[j] * pair.value(i, j, r0) / (r_floor * r_floor));
            }
        }
        self.particle_factor = (0..n)
            .map(|i| {
                0.5 * self.coefficient * self.youngs[self.body[i] as usize] * v0[i]
                    / particles.masses[i]
            })
            .collect();
    }
}

impl<const D: usize> Effect<D> for HourglassControl {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        "hourglass"
    }

    fn reference_changed(&mut self, particles: &Particles<D>, bonds: &Bonds<D>) {
        self.weigh(particles, bonds);
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let b = ctx.bonds;
        let weight = &self.bond_weight;
        let factor = &self.particle_factor;
        let removed = ctx.removed;
        out.par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, a)| {
                if !alive(removed, i) {
                    *a = Vector::zeros();
                    return;
                }
                let xi = p.positions0[i] + p.displacements[i];
                let mut force = Vector::<D>::zeros();
                let r = b.range(i);
                // Bonds to symmetry ghosts count (their F is the mirrored F of the parent),
                // bonds to failed particles do not.
                for (k, &j) in r.clone().zip(&b.neighbours[r]) {
                    let j = j as usize;
                    if !alive(removed, j) {
                        continue;
                    }
                    let x_ij = xi - (p.positions0[j] + p.displacements[j]);
                    let dist = x_ij.norm();
                    if dist <= 0.0 {
                        continue;
                    }
                    let big_x = p.positions0[i] - p.positions0[j];
                    let predicted = (p.deformation_gradient[i] + p.deformation_gradient[j]) * big_x;
                    let delta = (predicted - x_ij * 2.0).dot(&x_ij) / dist;
                    force += x_ij * (weight[k] * delta / dist);
                }
                *a = force * factor[i];
            });
    }
}
