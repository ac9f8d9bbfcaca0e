//! Hourglass (zero-energy mode) control for TLSPH after Ganzenmüller (2015), numerics.md §10.5:
//! a penalty on the difference between each bond's current vector and the one the particles'
//! deformation gradients predict. Pairwise equal and opposite (momentum conserving); its work
//! is booked separately in the energy balance.

use super::{Effect, EffectContext};
use rayon::prelude::*;
use tlsph_kernels::Kernel;
use tlsph_math::Vector;

/// Ganzenmüller's hourglass penalty with dimensionless coefficient α.
///
/// f_I = ½ α Σ_J (V0_I V0_J W0_IJ / |X_IJ|²) E ((F_I + F_J) X_IJ − 2 x_IJ)·x_IJ/r · x_IJ/r,
/// with X_IJ = X_I − X_J, x_IJ = x_I − x_J, r = |x_IJ|, E the body's Young's modulus.
#[derive(Debug, Clone)]
pub struct HourglassControl {
    /// Per bond: V0_J W0_IJ / |X_IJ|².
    bond_weight: Vec<f64>,
    /// Per particle: ½ α E V0_I / m_I = ½ α E / ρ0 \[m²/s²\].
    particle_factor: Vec<f64>,
}

impl HourglassControl {
    /// Precomputes the bond weights from the reference configuration.
    /// `modulus_of(i)` is E of particle i's material \[Pa\], `kernel_of(i)` its body's kernel.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new<const D: usize, K: Kernel>(
        coefficient: f64,
        positions0: &[Vector<D>],
        volumes0: &[f64],
        masses: &[f64],
        offsets: &[usize],
        neighbours: &[u32],
        kernel_of: impl Fn(usize) -> K,
        modulus_of: impl Fn(usize) -> f64,
    ) -> Self {
        let n = offsets.len() - 1;
        let mut bond_weight = Vec::with_capacity(neighbours.len());
        for i in 0..n {
            let kernel = kernel_of(i);
            for &j in &neighbours[offsets[i]..offsets[i + 1]] {
                let j = j as usize;
                let r0 = (positions0[i] - positions0[j]).norm();
                bond_weight.push(volumes0[j] * kernel.value(r0) / (r0 * r0));
            }
        }
        let particle_factor = (0..n)
            .map(|i| 0.5 * coefficient * modulus_of(i) * volumes0[i] / masses[i])
            .collect();
        Self {
            bond_weight,
            particle_factor,
        }
    }
}

impl<const D: usize> Effect<D> for HourglassControl {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        "hourglass"
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        let p = ctx.particles;
        let b = ctx.bonds;
        let weight = &self.bond_weight;
        let factor = &self.particle_factor;
        let n_real = out.len();
        out.par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, a)| {
                let xi = p.positions0[i] + p.displacements[i];
                let mut force = Vector::<D>::zeros();
                let r = b.range(i);
                for (k, &j) in r.clone().zip(&b.neighbours[r]) {
                    let j = j as usize;
                    if j >= n_real {
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
