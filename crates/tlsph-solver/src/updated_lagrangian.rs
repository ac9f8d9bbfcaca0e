//! Updated-Lagrangian ("Eulerian kernel", conventional) SPH: the kernel lives in the current
//! configuration, neighbours are searched as particles move, and bodies of the same kernel
//! group (by default: the same material) interact through the kernel (numerics.md §3; R 2.51–2.67; F 2.21, 2.47, 2.59).
//!
//! The scheme shares the time integrator and every constitutive update with TLSPH. Per step:
//!
//! 1. [`UpdatedLagrangian::rebuild_due`] / [`UpdatedLagrangian::rebuild`]: rebuild the
//!    Verlet list if any particle has moved more than half the skin since the last build (with
//!    symmetry planes the caller first remakes the mirror particles at x^n, numerics.md §13.1;
//!    they join the list as neighbours and own no pairs), then
//!    [`UpdatedLagrangian::evaluate_kernel`]: ∇_I W_IJ at x^n for every listed pair (zero
//!    beyond the support).
//! 2. [`UpdatedLagrangian::gather_kinematics`]: the velocity gradient in Fuller's
//!    density-weighted form L_I = −(1/ρ_I) Σ_J m_J (v_I − v_J) ⊗ ∇_I W_IJ (F 2.14, 2.47),
//!    whose trace is exactly the continuity equation Dρ_I/Dt = Σ_J m_J (v_I − v_J)·∇_I W_IJ
//!    (F 2.21). F is carried along with Ḟ = L F by the implicit midpoint rule
//!    F^n = F^{n−1} + Δt Ḟ, Ḟ = (I − ½Δt L)⁻¹ L F^{n−1}, so the constitutive update recovers L
//!    exactly from (F^n, Ḟ) and ρ^n = ρ0 / det F^n is the continuity equation integrated with
//!    the same rule (design choice, documented in numerics terms in ARCHITECTURE.md).
//! 3. The constitutive update of the body (shared with TLSPH) gives σ^n, J^n and the
//!    force-driving P^n (artificial bulk viscosity included when declared).
//! 4. [`UpdatedLagrangian::gather_accelerations_and_stress_power`]: the symmetrised momentum
//!    equation a_I = Σ_J m_J (σ_I/ρ_I² + σ_J/ρ_J²)·∇_I W_IJ (R 2.54; F 2.59). Pair terms are
//!    equal and opposite, so linear momentum is conserved exactly. Pairwise artificial
//!    viscosity and artificial stress are declared effects that read the same pair list.
//!
//! The internal energy is not the constitutive loop's σ:D/ρ but the SPH energy equation
//! (R 2.59) from the same pair sums as the forces, in two halves per step:
//! [`UpdatedLagrangian::book_previous_stress_power`] (forces at t^{n−1}) before step 1 and the
//! stress power in step 4 (forces at t^n), both with the drift velocity v^{n−½}. Each half is
//! minus the work of those forces, so the energy closes with the leap-frog to round-off,
//! also across neighbour rebuilds and failures (design choice).

use crate::particles::Particles;
use crate::step::MIN_PARTICLES_PER_TASK;
use rayon::prelude::*;
use tlsph_kernels::{AnyKernel, Kernel};
use tlsph_math::{Tensor, Vector};
use tlsph_neighbours::build_neighbour_list;

/// Skin of the Verlet list as a fraction of the smallest smoothing length: the list holds all
/// pairs within (largest support + skin) and is rebuilt once any particle has moved by half the
/// skin, so no pair inside the support is ever missing (F §8.4).
pub const SKIN_FRACTION: f64 = 0.25;

/// Current-configuration pairs of every particle with their kernel gradients at x^n.
#[derive(Debug, Clone, Default)]
pub struct CurrentPairs<const D: usize> {
    /// CSR offsets: particle I's pairs are `offsets[I]..offsets[I + 1]`.
    pub offsets: Vec<usize>,
    /// Neighbour J of each pair (same interaction group, I ≠ J, within support + skin).
    pub neighbours: Vec<u32>,
    /// Particle I that owns each pair.
    pub owner: Vec<u32>,
    /// ∇_I W_IJ at x^n for each pair (zero beyond the support); pair-averaged over the two
    /// bodies' kernels when their smoothing lengths differ (R 2.4–2.7).
    pub gradient: Vec<Vector<D>>,
    /// W_IJ at x^n for each pair (filled only when an effect needs kernel values).
    pub value: Vec<f64>,
}

impl<const D: usize> CurrentPairs<D> {
    /// Pair index range of particle `i`.
    #[inline]
    pub fn range(&self, i: usize) -> std::ops::Range<usize> {
        self.offsets[i]..self.offsets[i + 1]
    }
}

/// State of the updated-Lagrangian formulation (allocated only when a scene selects it).
#[derive(Debug, Clone)]
pub(crate) struct UpdatedLagrangian<const D: usize> {
    /// Number of real particles (symmetry ghosts follow them).
    n_real: usize,
    /// Body of each particle (ghosts: their parent's).
    body: Vec<u32>,
    /// Kernel interaction group of each particle (`EffectsDescription::kernel_groups`, by
    /// default the material index): only equal groups interact.
    group: Vec<u32>,
    /// Kernel of each body.
    kernels: Vec<AnyKernel>,
    /// Verlet skin \[length\].
    skin: f64,
    /// Search radius of the Verlet list: largest support + skin \[length\].
    search_radius: f64,
    /// Positions at the last rebuild.
    positions_at_build: Vec<Vector<D>>,
    /// Scratch: current positions.
    positions: Vec<Vector<D>>,
    /// Pairs and kernel gradients at x^n.
    pub pairs: CurrentPairs<D>,
    /// Whether effects need kernel values W_IJ.
    need_values: bool,
    /// σ_I/ρ_I² of the force-driving stress.
    stress_over_density2: Vec<Tensor<D>>,
    /// Rebuilds of the Verlet list so far.
    rebuilds: u64,
    /// Force a rebuild at the next refresh (particles failed).
    stale: bool,
    /// XSPH ε and the transport velocities v̂ (F 3.2), if declared.
    pub xsph: Option<(f64, Vec<Vector<D>>)>,
}

impl<const D: usize> UpdatedLagrangian<D> {
    /// State for particles with the given body and group indices; `kernels` per body.
    pub fn new(
        body: Vec<u32>,
        group: Vec<u32>,
        kernels: Vec<AnyKernel>,
        need_values: bool,
        xsph: Option<(f64, Vec<Vector<D>>)>,
    ) -> Self {
        let n = body.len();
        let min_h = kernels
            .iter()
            .map(|k| k.smoothing_length())
            .fold(f64::INFINITY, f64::min);
        let max_support = kernels
            .iter()
            .map(|k| k.support_radius())
            .fold(0.0, f64::max);
        let skin = SKIN_FRACTION * min_h;
        Self {
            n_real: n,
            body,
            group,
            kernels,
            skin,
            search_radius: max_support + skin,
            positions_at_build: Vec::new(),
            positions: vec![Vector::zeros(); n],
            pairs: CurrentPairs::default(),
            need_values,
            stress_over_density2: vec![Tensor::zeros(); n],
            rebuilds: 0,
            stale: true,
            xsph,
        }
    }

    /// Number of Verlet-list rebuilds so far.
    pub fn rebuilds(&self) -> u64 {
        self.rebuilds
    }

    /// Requests a rebuild at the next refresh (after particles failed).
    pub fn mark_stale(&mut self) {
        self.stale = true;
    }

    /// Search radius of the Verlet list (largest support + skin) \[length\]: also how far
    /// from a symmetry plane a particle gets a mirror image.
    pub fn search_radius(&self) -> f64 {
        self.search_radius
    }

    /// Step 1a: takes the current positions x^n = X + u of every particle (ghosts included)
    /// and returns whether the Verlet list must be rebuilt: after failures, at the first step,
    /// or once any particle has moved more than half the skin since the last build.
    pub fn rebuild_due(&mut self, p: &Particles<D>) -> bool {
        self.take_positions(p);
        let half_skin_sq = 0.25 * self.skin * self.skin;
        self.stale
            || self
                .positions
                .par_iter()
                .zip(self.positions_at_build.par_iter())
                .any(|(x, x_b)| (x - x_b).norm_squared() > half_skin_sq)
    }

    fn take_positions(&mut self, p: &Particles<D>) {
        self.positions.resize(p.len(), Vector::zeros());
        self.positions
            .par_iter_mut()
            .zip(p.positions0.par_iter().zip(p.displacements.par_iter()))
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .for_each(|(x, (x0, u))| *x = x0 + u);
    }

    /// The symmetry ghosts were rebuilt (`Ghosts::rebuild_current`): particle `n_real + g`
    /// now mirrors `parents[g]` and takes its body and interaction group; the per-particle
    /// scratch follows the new particle count.
    pub fn set_ghost_parents(&mut self, n_real: usize, parents: &[usize]) {
        for field in [&mut self.body, &mut self.group] {
            field.truncate(n_real);
            for &parent in parents {
                let value = field[parent];
                field.push(value);
            }
        }
        let n = n_real + parents.len();
        self.stress_over_density2.resize(n, Tensor::zeros());
        if let Some((_, vhat)) = &mut self.xsph {
            vhat.resize(n, Vector::zeros());
        }
    }

    /// Body of every particle (ghosts: their parent's).
    pub fn particle_bodies(&self) -> &[u32] {
        &self.body
    }

    /// Step 1b: rebuilds the Verlet list at x^n for the current particles (ghosts included;
    /// pairs are owned by real particles only, since only they gather). `removed` flags failed
    /// particles (empty when no failure model is declared).
    pub fn rebuild(&mut self, p: &Particles<D>, removed: &[bool]) -> Result<(), String> {
        self.take_positions(p);
        self.build_list(removed)
    }

    fn build_list(&mut self, removed: &[bool]) -> Result<(), String> {
        let list =
            build_neighbour_list(&self.positions, self.search_radius).map_err(|e| e.to_string())?;
        let alive = |i: usize| removed.is_empty() || !removed[i];
        let n = self.positions.len();
        self.pairs.offsets.clear();
        self.pairs.neighbours.clear();
        self.pairs.owner.clear();
        self.pairs.offsets.push(0);
        for i in 0..n {
            // Ghosts (index n_real on) own no pairs: they never gather.
            if i < self.n_real && alive(i) {
                let group = self.group[i];
                self.pairs.neighbours.extend(
                    list.neighbours_of(i)
                        .iter()
                        .filter(|&&j| self.group[j as usize] == group && alive(j as usize)),
                );
            }
            let added = self.pairs.neighbours.len() - self.pairs.owner.len();
            self.pairs
                .owner
                .extend(std::iter::repeat_n(i as u32, added));
            self.pairs.offsets.push(self.pairs.neighbours.len());
        }
        let n_pairs = self.pairs.neighbours.len();
        self.pairs.gradient.resize(n_pairs, Vector::zeros());
        if self.need_values {
            self.pairs.value.resize(n_pairs, 0.0);
        }
        self.positions_at_build.clone_from(&self.positions);
        self.rebuilds += 1;
        self.stale = false;
        Ok(())
    }

    /// Step 1c: ∇_I W_IJ (and W_IJ when needed) at x^n for every pair (one independent task
    /// per pair).
    pub fn evaluate_kernel(&mut self) {
        let x = &self.positions;
        let (body, kernels) = (&self.body, &self.kernels);
        let pairs = &mut self.pairs;
        let (owner, neighbours) = (&pairs.owner, &pairs.neighbours);
        let kernel_pair = |k: usize| -> (Vector<D>, f64) {
            let (i, j) = (owner[k] as usize, neighbours[k] as usize);
            let r = x[i] - x[j];
            let (bi, bj) = (body[i] as usize, body[j] as usize);
            let ki = &kernels[bi];
            if bi == bj {
                (ki.gradient(&r), ki.value(r.norm()))
            } else {
                // Kernel averaging: antisymmetric gradient for unequal h (R 2.4–2.7).
                let kj = &kernels[bj];
                let d = r.norm();
                (
                    (ki.gradient(&r) + kj.gradient(&r)) * 0.5,
                    0.5 * (ki.value(d) + kj.value(d)),
                )
            }
        };
        if self.need_values {
            pairs
                .gradient
                .par_iter_mut()
                .zip(pairs.value.par_iter_mut())
                .enumerate()
                .with_min_len(4 * MIN_PARTICLES_PER_TASK)
                .for_each(|(k, (g, w))| (*g, *w) = kernel_pair(k));
        } else {
            pairs
                .gradient
                .par_iter_mut()
                .enumerate()
                .with_min_len(4 * MIN_PARTICLES_PER_TASK)
                .for_each(|(k, g)| *g = kernel_pair(k).0);
        }
    }

    /// Step 2: L_I = −(1/ρ_I) Σ_J m_J (v_I − v_J) ⊗ ∇_I W_IJ with ρ_I = ρ0/J_I^{n−1}
    /// (F 2.14, 2.47), then F^n = F^{n−1} + Δt Ḟ with Ḟ = (I − ½Δt L)⁻¹ L F^{n−1}
    /// (implicit midpoint rule for Ḟ = L F). A singular (I − ½Δt L) leaves NaN in F for the
    /// inversion check.
    pub fn gather_kinematics(&self, p: &mut Particles<D>, dt: f64) {
        let v = &p.velocities[..];
        let masses = &p.masses[..];
        let volumes0 = &p.volumes0[..];
        let pairs = &self.pairs;
        p.deformation_gradient
            .par_iter_mut()
            .zip(p.deformation_rate.par_iter_mut())
            .zip(p.jacobian.par_iter())
            .enumerate()
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .for_each(|(i, ((f, f_dot), &j_prev))| {
                let vi = v[i];
                let mut weighted = Tensor::<D>::zeros();
                let r = pairs.range(i);
                for (&j, g) in pairs.neighbours[r.clone()].iter().zip(&pairs.gradient[r]) {
                    let j = j as usize;
                    weighted += (v[j] - vi) * g.transpose() * masses[j];
                }
                // 1/ρ_I = J_I V0_I / m_I.
                let l = weighted * (j_prev * volumes0[i] / masses[i]);
                let f_prev = *f;
                let rate = match (Tensor::<D>::identity() - l * (0.5 * dt)).try_inverse() {
                    Some(inv) => inv * l * f_prev,
                    None => Tensor::<D>::from_element(f64::NAN),
                };
                *f_dot = rate;
                *f = f_prev + rate * dt;
            });
    }

    /// σ_I/ρ_I² of the force-driving stress from P = J σ F⁻ᵀ: σ/ρ² = P Fᵀ J / ρ0².
    pub fn update_stress_over_density2(&mut self, p: &Particles<D>) {
        self.stress_over_density2
            .par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .for_each(|(i, s)| {
                *s = stress_over_density2(
                    &p.pk1[i],
                    &p.deformation_gradient[i],
                    p.jacobian[i],
                    p.volumes0[i] / p.masses[i],
                )
            });
    }

    /// First half of the internal-energy increment of the step from t^{n−1} to t^n, taken
    /// before the list moves to x^n: the stress power of the forces at t^{n−1} (their σ/ρ²,
    /// pairs and ∇W at x^{n−1}) with the drift velocity v^{n−½},
    /// e_I += ½Δt^n (σ_I/ρ_I²)^{n−1} : Σ_J m_J (v_J − v_I)^{n−½} ⊗ ∇_I W_IJ(x^{n−1}).
    ///
    /// With the second half ([`Self::gather_accelerations_and_stress_power`]) this is the SPH
    /// energy equation (numerics.md §3; R 2.59) integrated so that it pairs exactly with the
    /// leap-frog kinetic energy: for one pair set Σ_I m_I (σ_I/ρ_I²):Σ_J m_J (v_J − v_I)⊗∇_I W_IJ
    /// = −Σ_I m_I a_I·v_I, so each half step's change of internal energy is minus the work of
    /// the same forces. Particles that fail at t^n leave the forces at t^n with σ/ρ² = 0 and
    /// their pairs, and therefore this booking too. Artificial bulk viscosity is part of the
    /// force-driving σ/ρ², so its heating is included.
    pub fn book_previous_stress_power(&self, p: &mut Particles<D>, dt: f64) {
        let s = &self.stress_over_density2;
        let (v, masses) = (&p.velocities, &p.masses);
        let pairs = &self.pairs;
        p.internal_energy[..self.n_real]
            .par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .for_each(|(i, energy)| {
                let (si, vi) = (s[i], v[i]);
                let mut power = 0.0;
                let r = pairs.range(i);
                for (&j, g) in pairs.neighbours[r.clone()].iter().zip(&pairs.gradient[r]) {
                    let j = j as usize;
                    power += masses[j] * (v[j] - vi).dot(&(si * g));
                }
                *energy += 0.5 * dt * power;
            });
    }

    /// Step 4: a_I = Σ_J m_J (σ_I/ρ_I² + σ_J/ρ_J²) ∇_I W_IJ (R 2.54; F 2.59) at t^n, and in
    /// the same pass the second half of the internal-energy increment of the step of `dt`
    /// from t^{n−1}: e_I += ½Δt (σ_I/ρ_I²)^n : Σ_J m_J (v_J − v_I)^{n−½} ⊗ ∇_I W_IJ(x^n) (see
    /// [`Self::book_previous_stress_power`]). The kick follows in [`kick`], since this pass
    /// reads the neighbours' velocities. Failed particles (no pairs) get a = 0.
    pub fn gather_accelerations_and_stress_power(&self, p: &mut Particles<D>, dt: f64) {
        let s = &self.stress_over_density2;
        let (v, masses) = (&p.velocities, &p.masses);
        let pairs = &self.pairs;
        p.accelerations
            .par_iter_mut()
            .zip(p.internal_energy.par_iter_mut())
            .enumerate()
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .for_each(|(i, (a, energy))| {
                let (si, vi) = (s[i], v[i]);
                let (mut acc, mut power) = (Vector::<D>::zeros(), 0.0);
                let r = pairs.range(i);
                for (&j, g) in pairs.neighbours[r.clone()].iter().zip(&pairs.gradient[r]) {
                    let j = j as usize;
                    let si_g = si * g;
                    acc += (si_g + s[j] * g) * masses[j];
                    power += masses[j] * (v[j] - vi).dot(&si_g);
                }
                *a = acc;
                // Ghosts and failed particles own no pairs: nothing is added to them.
                *energy += 0.5 * dt * power;
            });
    }

    /// XSPH transport velocity v̂_I = v_I + ε Σ_J (m_J/ρ̄_IJ)(v_J − v_I) W_IJ at x^n
    /// (F 3.2; numerics.md §10.4), ρ̄_IJ = ½(ρ_I + ρ_J). Particles drift with v̂; the momentum
    /// equation and L use v.
    pub fn update_xsph(&mut self, p: &Particles<D>) {
        let Some((epsilon, vhat)) = &mut self.xsph else {
            return;
        };
        let epsilon = *epsilon;
        let pairs = &self.pairs;
        let density = |i: usize| p.masses[i] / (p.volumes0[i] * p.jacobian[i]);
        vhat.par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PARTICLES_PER_TASK)
            .for_each(|(i, out)| {
                let vi = p.velocities[i];
                let rho_i = density(i);
                let mut sum = Vector::<D>::zeros();
                let r = pairs.range(i);
                for (&j, w) in pairs.neighbours[r.clone()].iter().zip(&pairs.value[r]) {
                    let j = j as usize;
                    sum +=
                        (p.velocities[j] - vi) * (p.masses[j] * w / (0.5 * (rho_i + density(j))));
                }
                *out = vi + sum * epsilon;
            });
    }
}

/// The leap-frog kick v += `kick` a of every particle (R 5.64–5.66).
pub(crate) fn kick<const D: usize>(p: &mut Particles<D>, kick: f64) {
    p.velocities
        .par_iter_mut()
        .zip(p.accelerations.par_iter())
        .with_min_len(MIN_PARTICLES_PER_TASK)
        .for_each(|(v, a)| *v += a * kick);
}

/// σ/ρ² of a force-driving stress from P = J σ F⁻ᵀ: P Fᵀ J / ρ0², with `inv_rho0` = V0/m.
fn stress_over_density2<const D: usize>(
    pk1: &Tensor<D>,
    f: &Tensor<D>,
    jacobian: f64,
    inv_rho0: f64,
) -> Tensor<D> {
    pk1 * f.transpose() * (jacobian * inv_rho0 * inv_rho0)
}
