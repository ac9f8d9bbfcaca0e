//! Reference-configuration bonds (CSR) with their kernel gradients, built once per TL body.
//!
//! For bond b = (I → J) we store the weighted gradient V0_J G̃_IJ used by the F and Ḟ gathers
//! (numerics.md §4.2–4.3) and the weighted reverse gradient V0_J G̃_JI used by the
//! momentum-conserving force sum m_I a_I = Σ_J V0_I V0_J (P_I G̃_IJ − P_J G̃_JI)
//! (numerics.md §4.5 form (c)). Storing both keeps the per-step loops streaming through memory.

use rayon::prelude::*;
use std::ops::Range;
use tlsph_kernels::{AnyKernel, Kernel};
use tlsph_math::{embed_with_identity, outer, project, Tensor, Tensor3, Vector};
use tlsph_neighbours::NeighbourList;

/// Singular values of the correction matrix A_I below this are clipped (numerics.md §6.2 guard).
/// A_I ≈ I with full support; a boundary particle in 1D has ≈ 0.5, so 0.1 only catches
/// genuinely degenerate neighbourhoods (too few or collinear neighbours).
const MIN_CORRECTION_SINGULAR_VALUE: f64 = 0.1;

/// CSR bonds over all particles; bonds never cross bodies.
#[derive(Debug, Clone, Default)]
pub struct Bonds<const D: usize> {
    /// offsets[i]..offsets[i+1] are the bonds of particle i.
    pub(crate) offsets: Vec<usize>,
    /// Global index of the neighbour J of each bond.
    pub(crate) neighbours: Vec<u32>,
    /// V0_J G̃_IJ for each bond.
    pub(crate) gradient: Vec<Vector<D>>,
    /// V0_J G̃_JI for each bond.
    pub(crate) reverse_gradient: Vec<Vector<D>>,
    /// Σ_J V0_J G̃_IJ per particle (vanishes in the interior; needed by the force sum).
    pub(crate) gradient_sum: Vec<Vector<D>>,
    /// Per particle (ghosts included), its smoothing length over its body's, when a reference
    /// update has widened supports (empty: all 1). See [`PairKernel`].
    pub(crate) kernel_scale: Vec<f64>,
}

/// What the gradient correction had to do at setup.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CorrectionReport {
    /// Particles whose correction matrix was ill-conditioned and was regularised
    /// (global indices).
    pub regularised_particles: Vec<usize>,
}

impl<const D: usize> Bonds<D> {
    /// Number of bonds (each unordered pair counted twice).
    pub fn n_bonds(&self) -> usize {
        self.neighbours.len()
    }

    /// Bond range of particle `i`.
    #[inline]
    pub fn range(&self, i: usize) -> Range<usize> {
        self.offsets[i]..self.offsets[i + 1]
    }

    /// Neighbours of particle `i` (global indices).
    pub fn neighbours_of(&self, i: usize) -> &[u32] {
        &self.neighbours[self.range(i)]
    }

    /// Corrected (or raw) gradients V0_J G̃_IJ of particle `i`, in neighbour order.
    pub fn weighted_gradients_of(&self, i: usize) -> &[Vector<D>] {
        &self.gradient[self.range(i)]
    }
}

/// Per-body input to [`build_bonds`]: the body's real particles first, then its symmetry
/// ghosts (numerics.md §13.1), in body-local indices.
pub(crate) struct BodyBonds<const D: usize> {
    /// Global index of each local point (reals, then ghosts).
    pub global: Vec<usize>,
    /// Number of real particles (local indices below this).
    pub n_real: usize,
    /// Reference positions of the local points.
    pub positions0: Vec<Vector<D>>,
    /// Reference volumes.
    pub volumes0: Vec<f64>,
    /// For each ghost (local index n_real + g): (parent local index, reflection mask).
    pub ghosts: Vec<(usize, u32)>,
    /// Local index of the ghost of (local real particle, mask).
    pub ghost_of: std::collections::HashMap<(usize, u32), usize>,
    /// Component signs of each reflection mask (index = mask).
    pub signs: Vec<Vector<D>>,
    /// Reference neighbour list over all local points.
    pub neighbours: NeighbourList,
    /// The body's kernel.
    pub kernel: AnyKernel,
    /// Per local point, its smoothing length over the body's (empty: all 1; see
    /// [`PairKernel`]).
    pub kernel_scale: Vec<f64>,
}

/// Builds bonds for all bodies (in order) and their gradients.
///
/// Real particles get bonds (to reals and ghosts); ghosts get none. `n_total` is the global
/// particle count including ghosts, whose (empty) bond ranges follow the reals.
pub(crate) fn build_bonds<const D: usize>(
    bodies: &[BodyBonds<D>],
    corrected: bool,
    n_total: usize,
) -> (Bonds<D>, CorrectionReport) {
    let mut bonds = Bonds::<D>::default();
    let mut report = CorrectionReport::default();
    bonds.offsets.push(0);
    for body in bodies {
        let list = &body.neighbours;
        let n = body.n_real;
        // Per-particle gradients G̃_IJ (unweighted) in neighbour order, for real particles.
        let per_particle: Vec<(Vec<Vector<D>>, bool)> = (0..n)
            .into_par_iter()
            .map(|i| particle_gradients(i, body, corrected))
            .collect();
        if !body.kernel_scale.is_empty() {
            bonds.kernel_scale.resize(n_total, 1.0);
            for (&g, &s) in body.global.iter().zip(&body.kernel_scale) {
                bonds.kernel_scale[g] = s;
            }
        }
        let base = bonds.neighbours.len();
        for (i, (grads, regularised)) in per_particle.iter().enumerate() {
            if *regularised {
                report.regularised_particles.push(body.global[i]);
            }
            for (&j, g) in list.neighbours_of(i).iter().zip(grads) {
                bonds.neighbours.push(body.global[j as usize] as u32);
                bonds.gradient.push(g * body.volumes0[j as usize]);
            }
            bonds.offsets.push(bonds.neighbours.len());
        }
        // Reverse gradients: bond I→J finds I in J's sorted list.
        for i in 0..n {
            for (k, &j) in list.neighbours_of(i).iter().enumerate() {
                let j = j as usize;
                // A ghost J = reflection M of real particle p sees I as p sees the ghost of I
                // under the same M, mirrored: G̃_JI = M G̃_{p, M(I)} (planes commute, M² = I).
                let (source, target, mask) = if j < n {
                    (j, i, 0)
                } else {
                    let (parent, mask) = body.ghosts[j - n];
                    let mirror = *body
                        .ghost_of
                        .get(&(i, mask))
                        .expect("the mirror of a particle near a ghost is a ghost too");
                    (parent, mirror, mask)
                };
                let back = list
                    .neighbours_of(source)
                    .binary_search(&(target as u32))
                    .expect("reference neighbour lists are symmetric");
                let g_ji = per_particle[source].0[back].component_mul(&body.signs[mask as usize]);
                bonds.reverse_gradient.push(g_ji * body.volumes0[j]);
                debug_assert_eq!(
                    bonds.reverse_gradient.len(),
                    base + list.offsets()[i] + k + 1
                );
            }
        }
    }
    // Ghosts (and nothing else) follow the reals: empty bond ranges.
    while bonds.offsets.len() < n_total + 1 {
        bonds.offsets.push(bonds.neighbours.len());
    }
    bonds.gradient_sum = (0..bonds.offsets.len() - 1)
        .into_par_iter()
        .map(|i| {
            bonds.gradient[bonds.offsets[i]..bonds.offsets[i + 1]]
                .iter()
                .fold(Vector::<D>::zeros(), |s, g| s + g)
        })
        .collect();
    (bonds, report)
}

impl<const D: usize> Bonds<D> {
    /// Takes newly failed particles out of every kernel sum (numerics.md §9.3): their bonds
    /// get zero weight, and every surviving neighbour's gradients are rebuilt without them —
    /// Shepard sum, quotient rule and correction B_I included — together with the reverse
    /// gradients that other particles read from them. Sequential and rare (only when a
    /// particle fails), so results stay deterministic.
    ///
    /// With symmetry planes (`mirrors`), a failed particle's mirror images are out of the sums
    /// too (`removed` flags them): the bond I → ghost(F, M) of every real I with F → ghost(I, M)
    /// is dropped, and when a survivor P's gradients are rebuilt, the mirrored reverse gradient
    /// of every bond I → ghost(P, M) follows, G̃_{ghost(P,M), I} = M G̃_{P, ghost(I,M)} (as at
    /// setup), so a quarter model keeps failing like the full one.
    ///
    /// Returns the surviving real particles whose gradients were rebuilt (ascending): the
    /// only ones whose F and Ḟ change.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn remove_failed(
        &mut self,
        failed_now: &[usize],
        removed: &[bool],
        positions0: &[Vector<D>],
        volumes0: &[f64],
        kernel_of: impl Fn(usize) -> AnyKernel,
        corrected: bool,
        mirrors: &impl MirrorMap<D>,
    ) -> Vec<usize> {
        let mut affected = Vec::new();
        for &f in failed_now {
            for b in self.range(f) {
                let j = self.neighbours[b] as usize;
                self.gradient[b] = Vector::zeros();
                self.reverse_gradient[b] = Vector::zeros();
                let back = match mirrors.mirror(f, j) {
                    // j = ghost(i, M): the real i loses its bond to ghost(f, M).
                    Some((i, image, _)) => self.bond(i, image).map(|back| (i, back)),
                    None => self.bond(j, f).map(|back| (j, back)),
                };
                if let Some((owner, back)) = back {
                    self.gradient[back] = Vector::zeros();
                    self.reverse_gradient[back] = Vector::zeros();
                    if !removed[owner] {
                        affected.push(owner);
                    }
                }
            }
            self.gradient_sum[f] = Vector::zeros();
        }
        affected.sort_unstable();
        affected.dedup();
        for &i in &affected {
            let kernel = PairKernel {
                kernel: &kernel_of(i),
                scale: &self.kernel_scale,
            };
            let range = self.range(i);
            let alive: Vec<usize> = self.neighbours[range.clone()]
                .iter()
                .map(|&j| j as usize)
                .filter(|&j| !removed[j])
                .collect();
            let gradients = gradients_of(i, &alive, positions0, volumes0, &kernel, corrected).0;
            let mut by_neighbour = alive.iter().zip(&gradients);
            let mut next = by_neighbour.next();
            let mut sum = Vector::<D>::zeros();
            for b in range {
                let j = self.neighbours[b] as usize;
                match next {
                    Some((&a, g)) if a == j => {
                        self.gradient[b] = g * volumes0[j];
                        sum += self.gradient[b];
                        match mirrors.mirror(i, j) {
                            Some((owner, image, signs)) => {
                                if let Some(back) = self.bond(owner, image) {
                                    self.reverse_gradient[back] =
                                        g.component_mul(&signs) * volumes0[image];
                                }
                            }
                            None => {
                                if let Some(back) = self.bond(j, i) {
                                    self.reverse_gradient[back] = g * volumes0[i];
                                }
                            }
                        }
                        next = by_neighbour.next();
                    }
                    _ => {
                        self.gradient[b] = Vector::zeros();
                        self.reverse_gradient[b] = Vector::zeros();
                    }
                }
            }
            self.gradient_sum[i] = sum;
        }
        affected
    }

    /// Index of bond (i → j), if j is a neighbour of i.
    fn bond(&self, i: usize, j: usize) -> Option<usize> {
        let r = self.range(i);
        self.neighbours[r.clone()]
            .binary_search(&(j as u32))
            .ok()
            .map(|k| r.start + k)
    }
}

/// Mirror images of symmetry ghosts, as the bond rebuild after failures needs them.
pub(crate) trait MirrorMap<const D: usize> {
    /// For a real particle `p` and a neighbour `j`: if `j` is the ghost of real particle `i`
    /// under reflection M, `Some((i, ghost(p, M), signs of M))`; `None` for a real `j`.
    fn mirror(&self, p: usize, j: usize) -> Option<(usize, usize, Vector<D>)>;
}

/// G̃_IJ for all neighbours J of particle `i` (body-local), and whether the correction was
/// regularised.
fn particle_gradients<const D: usize>(
    i: usize,
    body: &BodyBonds<D>,
    corrected: bool,
) -> (Vec<Vector<D>>, bool) {
    let neighbours: Vec<usize> = body
        .neighbours
        .neighbours_of(i)
        .iter()
        .map(|&j| j as usize)
        .collect();
    gradients_of(
        i,
        &neighbours,
        &body.positions0,
        &body.volumes0,
        &PairKernel {
            kernel: &body.kernel,
            scale: &body.kernel_scale,
        },
        corrected,
    )
}

/// G̃_IJ of particle `i` towards `neighbours` (indices into `x` and `v0`): raw kernel
/// gradients, or with `corrected` the Shepard quotient-rule gradient times the
/// Randles–Libersky correction (numerics.md §6.1–6.2). Also whether B_I was regularised.
fn gradients_of<const D: usize>(
    i: usize,
    neighbours: &[usize],
    x: &[Vector<D>],
    v0: &[f64],
    kernel: &PairKernel<'_>,
    corrected: bool,
) -> (Vec<Vector<D>>, bool) {
    let raw: Vec<Vector<D>> = neighbours
        .iter()
        .map(|&j| kernel.gradient(i, j, &(x[i] - x[j])))
        .collect();
    if !corrected {
        return (raw, false);
    }
    // Shepard sum including the particle itself (R 4.32): S_I = Σ_J V0_J W_IJ.
    let mut shepard = v0[i] * kernel.value(i, i, 0.0);
    let mut gradient_sum = Vector::<D>::zeros();
    for (&j, g) in neighbours.iter().zip(&raw) {
        shepard += v0[j] * kernel.value(i, j, (x[i] - x[j]).norm());
        gradient_sum += g * v0[j];
    }
    // Quotient-rule Shepard gradient (R 6.7): ∇W̃_IJ = (G_IJ S_I − W_IJ Σ_K V0_K G_IK) / S_I².
    let normalised: Vec<Vector<D>> = neighbours
        .iter()
        .zip(&raw)
        .map(|(&j, g)| {
            let w = kernel.value(i, j, (x[i] - x[j]).norm());
            (g * shepard - gradient_sum * w) / (shepard * shepard)
        })
        .collect();
    // Randles–Libersky correction (R 4.50–4.55): A_I = Σ_J V0_J (X_J − X_I) ⊗ ∇W̃_IJ,
    // G̃_IJ = B_Iᵀ ∇W̃_IJ with B_I = A_I⁻¹, so that Σ_J V0_J (X_J − X_I) ⊗ G̃_IJ = I.
    let mut a = Tensor::<D>::zeros();
    for (&j, g) in neighbours.iter().zip(&normalised) {
        a += outer(&(x[j] - x[i]), g) * v0[j];
    }
    let (b, regularised) = guarded_inverse(&a);
    let corrected = normalised.iter().map(|g| b.transpose() * g).collect();
    (corrected, regularised)
}

/// A body's kernel for the pair (I, J) with the smoothing length h_IJ = s_IJ h, where
/// s_IJ = (s_I + s_J)/2 is the mean of the two particles' factors (symmetric, so the reference
/// neighbour lists stay symmetric and G_IJ = −G_JI for the raw kernel). A kernel of the form
/// W(r, h) = h^−d w(r/h) (numerics.md §1) gives W(r, s h) = s^−d W(r/s, h) and
/// ∇W(r, s h) = s^−(d+1) ∇W(r/s, h). All factors are 1 (the body kernel itself) unless a
/// reference update has widened supports (`reference.rs`).
pub(crate) struct PairKernel<'a> {
    /// The body's kernel (smoothing length h).
    pub kernel: &'a AnyKernel,
    /// Factor s per particle, indexed like the positions passed in (empty: all 1).
    pub scale: &'a [f64],
}

impl PairKernel<'_> {
    /// s_IJ.
    #[inline]
    fn scale(&self, i: usize, j: usize) -> f64 {
        if self.scale.is_empty() {
            1.0
        } else {
            0.5 * (self.scale[i] + self.scale[j])
        }
    }

    /// W(r, h_IJ).
    #[inline]
    pub fn value(&self, i: usize, j: usize, r: f64) -> f64 {
        let s = self.scale(i, j);
        if s == 1.0 {
            return self.kernel.value(r);
        }
        self.kernel.value(r / s) / s.powi(self.kernel.dimension() as i32)
    }

    /// ∇_I W(|r_IJ|, h_IJ).
    #[inline]
    pub fn gradient<const D: usize>(&self, i: usize, j: usize, r_ij: &Vector<D>) -> Vector<D> {
        let s = self.scale(i, j);
        if s == 1.0 {
            return self.kernel.gradient(r_ij);
        }
        self.kernel.gradient(&(r_ij / s)) / s.powi(self.kernel.dimension() as i32 + 1)
    }
}

/// A⁻¹, or a pseudo-inverse with singular values clipped from below when A is degenerate
/// (numerics.md §6.2 guard). Returns whether clipping happened.
fn guarded_inverse<const D: usize>(a: &Tensor<D>) -> (Tensor<D>, bool) {
    // Identity padding leaves the D×D block's inverse unchanged and lets us use 3x3 routines.
    let a3: Tensor3 = embed_with_identity(a);
    let svd = a3.svd(true, true);
    let (u, v_t) = match (svd.u, svd.v_t) {
        (Some(u), Some(v_t)) => (u, v_t),
        _ => return (Tensor::identity(), true),
    };
    let degenerate = svd
        .singular_values
        .iter()
        .any(|s| !(s.is_finite() && *s >= MIN_CORRECTION_SINGULAR_VALUE));
    if !degenerate {
        if let Some(inverse) = a.try_inverse() {
            return (inverse, false);
        }
    }
    let mut inv_sigma = Tensor3::zeros();
    for k in 0..3 {
        let s = svd.singular_values[k];
        let s = if s.is_finite() {
            s.max(MIN_CORRECTION_SINGULAR_VALUE)
        } else {
            1.0
        };
        inv_sigma[(k, k)] = 1.0 / s;
    }
    let inverse = v_t.transpose() * inv_sigma * u.transpose();
    (project::<D>(&inverse), true)
}
