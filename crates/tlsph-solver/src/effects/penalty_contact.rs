//! Fuller's particle-type penalty contact with Coulomb friction (numerics.md §12.1, F §4.3–4.4):
//! the effect that drives `tlsph_contact::PenaltyLaw`.
//!
//! Every body is a particle type: kernel (stress) interactions stay inside a type, and bodies of
//! different types meet only through this contact. Each step, at x^n, the effect counts each
//! participant's live same-type neighbours within the kernel support (in a total-Lagrangian
//! formulation the support is the reference one, so the count is I's live bond count and a
//! failed neighbour no longer counts; in the updated-Lagrangian formulation it is the current
//! pairs within 2h). The fully surrounded count is the largest of the body at the first step
//! (24 in 2D and 92 in 3D for h = 1.5Δx). From the counts come the surface flags, the outward
//! normals of the surface particles, and the pair forces of the law (zone, penalty, friction).
//! In a total-Lagrangian formulation the normal is summed over the reference positions and
//! carried to the current configuration by Nanson's relation n ∝ F^{−T} N `[C]`: summed over
//! the current positions it turns with the near-zero-energy zig-zag of a surface row, and the
//! force held to it then feeds that motion (a block resting on a deformable base inverted).
//! Of two surface particles the flatter one gives the normal (see `defines_normal`).
//!
//! Friction has a stick state `[C]` (`PenaltyLaw::force_on_partner`): with friction declared,
//! `accelerations` first takes each participant's velocity after the step's other forces and
//! its normal load (the sum of |f_n| over its pair forces), from which each pair's stick rate
//! follows (`stick_rate`). Without friction neither is stored nor computed.
//!
//! Each pair contribution is one function of (I, K) evaluated identically from both ends, so
//! forces are equal and opposite and linear momentum is conserved to round-off. The force is
//! not the gradient of a potential (its direction is I's normal, not the pair line), so its
//! work −∫ Σ f·v dt is booked as the `contact` energy column: penalty energy still stored in
//! compressed pairs plus what friction dissipated.
//!
//! With symmetry planes a participant near a plane also meets the mirror images of the
//! participants beyond it (numerics.md §13.1): an image carries its parent's surface flag,
//! neighbour count, mass and normal load, and its reflected position, normal and velocity, as
//! the full model's particle there. The counts and normals of particles near a plane already include the
//! symmetry ghosts among their neighbours.
//!
//! A body paired with itself gets self-contact `[C]`: the same law, friction included, between
//! its particles that are not kernel neighbours in the reference configuration (not bonded to
//! the partner, nor to its symmetry ghost), so that a body folding onto itself meets itself
//! while nothing acts inside the continuum, where a surface particle's zone reaches its own
//! neighbours. Between two parts of one body that share no bond it is exactly the contact of
//! two bodies.
//!
//! Not built: Fuller's multiple-normal refinement and the corner class (n_I ≤ 0.5 n_full), which
//! only that refinement uses.

use super::{Configuration, Effect, EffectContext};
use crate::particles::Particles;
use rayon::prelude::*;
use tlsph_contact::{
    is_surface, ContactCandidates, OutwardNormal, PenaltyLaw, DT_FACTOR, PARTICIPANTS_PER_TASK,
    SKIN_FRACTION,
};
use tlsph_kernels::{AnyKernel, Kernel};
use tlsph_math::{PlaneReflections, Vector};

/// Fuller's particle-type penalty contact with friction (numerics.md §12.1).
#[derive(Debug, Clone)]
pub struct PenaltyContact<const D: usize> {
    n_bodies: usize,
    /// Law per ordered body pair (A · n_bodies + B), symmetric; `None`: no contact.
    laws: Vec<Option<PenaltyLaw>>,
    /// Kernel of each body (normal weights, updated-Lagrangian neighbour counts).
    kernels: Vec<AnyKernel>,
    /// Fully surrounded neighbour count of each body (set at the first evaluation).
    full_count: Vec<usize>,
    /// Per participant: its body's motion is entirely prescribed (every component of every
    /// particle), so its surface is the master surface of its pairs (see `defines_normal`).
    driven: Vec<bool>,
    /// Participants, their current positions and candidate partners (searched within the
    /// largest zone reach sqrt(R² + d0²) plus the skin).
    candidates: ContactCandidates<D>,
    /// Symmetry planes (self-contact's reference-neighbour test of an image partner).
    mirrors: PlaneReflections<D>,
    /// Per participant: same-type neighbour count, surface flag, unit outward normal (zero for
    /// interior particles).
    count: Vec<usize>,
    surface: Vec<bool>,
    normal: Vec<Vector<D>>,
    /// Per participant: velocity after the step's other forces (scratch; friction only),
    /// contact force, summed normal stiffness.
    velocity: Vec<Vector<D>>,
    force: Vec<Vector<D>>,
    stiffness: Vec<f64>,
    /// Per participant: the sum of the normal forces of its pair forces this step (friction
    /// only, else empty), over which its stick forces share its mass (`stick_rate`).
    normal_load: Vec<f64>,
    resultant: Vector<D>,
    /// Geometry holds x^n (set by `time_step_limit`, used by `accelerations`).
    prepared: bool,
}

impl<const D: usize> PenaltyContact<D> {
    /// Contact between the body pairs that have a law in `laws` (`n_bodies`² entries,
    /// symmetric; a diagonal entry is self-contact); `kernels` per body, `body_of` per real
    /// particle, `driven` per body (motion entirely prescribed). The resultant reported is the contact force on the
    /// lowest-index body that takes part. With symmetry planes `mirrors` a participant also
    /// meets the images of the participants beyond them, with reflected normals and
    /// velocities.
    pub(crate) fn new(
        laws: Vec<Option<PenaltyLaw>>,
        n_bodies: usize,
        kernels: Vec<AnyKernel>,
        body_of: &[u32],
        driven: Vec<bool>,
        mirrors: PlaneReflections<D>,
    ) -> Self {
        let takes_part = |b: u32| {
            let row = b as usize * n_bodies;
            laws[row..row + n_bodies].iter().any(Option::is_some)
        };
        let active = laws.iter().flatten();
        let min_reach = active
            .clone()
            .map(PenaltyLaw::reach)
            .fold(f64::INFINITY, f64::min);
        let max_zone = active
            .clone()
            .map(PenaltyLaw::zone_radius)
            .fold(0.0, f64::max);
        let friction = active.clone().any(PenaltyLaw::has_friction);
        let candidates =
            ContactCandidates::new(body_of, takes_part, max_zone, SKIN_FRACTION * min_reach)
                .with_mirrors(mirrors.clone());
        let n = candidates.len();
        let driven = candidates
            .body()
            .iter()
            .map(|&b| driven[b as usize])
            .collect();
        Self {
            n_bodies,
            laws,
            kernels,
            full_count: vec![0; n_bodies],
            driven,
            candidates,
            mirrors,
            count: vec![0; n],
            surface: vec![false; n],
            normal: vec![Vector::zeros(); n],
            velocity: if friction {
                vec![Vector::zeros(); n]
            } else {
                Vec::new()
            },
            force: vec![Vector::zeros(); n],
            stiffness: vec![0.0; n],
            normal_load: if friction { vec![0.0; n] } else { Vec::new() },
            resultant: Vector::zeros(),
            prepared: false,
        }
    }

    /// Calls `visit(j, x_j)` for every live same-type neighbour of real particle `i` at x^n:
    /// its bonds whose partner has not failed (total-Lagrangian: a failed particle's bonds
    /// carry zero gradients) or its current pairs within the kernel support `support`
    /// (updated-Lagrangian).
    fn for_each_neighbour(
        at: &Configuration<'_, D>,
        i: usize,
        support: f64,
        mut visit: impl FnMut(usize, Vector<D>),
    ) {
        let p = at.particles;
        let position = |j: usize| p.positions0[j] + p.displacements[j];
        match at.pairs {
            Some(pairs) => {
                let xi = position(i);
                for &j in &pairs.neighbours[pairs.range(i)] {
                    let xj = position(j as usize);
                    if (xi - xj).norm() < support {
                        visit(j as usize, xj);
                    }
                }
            }
            None => {
                let bonds = at.bonds;
                for (&j, g) in bonds
                    .neighbours_of(i)
                    .iter()
                    .zip(bonds.weighted_gradients_of(i))
                {
                    if g.iter().any(|c| *c != 0.0) {
                        visit(j as usize, position(j as usize));
                    }
                }
            }
        }
    }

    /// Positions, candidate list (rebuilt when stale), neighbour counts, surface flags and
    /// normals at x^n (numerics.md §12.1 items 1–3).
    fn prepare(&mut self, at: &Configuration<'_, D>) {
        let p = at.particles;
        let position = |j: usize| p.positions0[j] + p.displacements[j];
        let (laws, n_bodies, kernels) = (&self.laws, self.n_bodies, &self.kernels);
        let mirrors = &self.mirrors;
        // A participant of another body in contact, or of the same body (self-contact) unless
        // the two are kernel neighbours in the reference configuration, bonded to the partner
        // or to its symmetry ghost: |X_I − M(X_K)| < 2h, the rule the bonds are built by. So
        // self-contact never acts inside the continuum. (A reference update, which would move
        // X and re-bond, is refused with self-contact at setup.)
        self.candidates
            .refresh(&p.positions0, &p.displacements, |pair| {
                laws[pair.body_k as usize * n_bodies + pair.body_j as usize].is_some()
                    && (pair.across_bodies() || {
                        let support = kernels[pair.body_k as usize].support_radius();
                        let image0 = mirrors.point(&p.positions0[pair.particle_j], pair.mask);
                        (image0 - p.positions0[pair.particle_k]).norm_squared() >= support * support
                    })
            });
        // 1. Same-type neighbour counts.
        let (body, parts) = (self.candidates.body(), self.candidates.participants());
        let support = |k: usize| kernels[body[k] as usize].support_radius();
        self.count
            .par_iter_mut()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, c)| {
                *c = 0;
                Self::for_each_neighbour(at, parts[k] as usize, support(k), |_, _| *c += 1);
            });
        if self.full_count.iter().all(|&c| c == 0) {
            for (k, &c) in self.count.iter().enumerate() {
                let b = body[k] as usize;
                self.full_count[b] = self.full_count[b].max(c);
            }
        }
        let full = &self.full_count;
        let count = &self.count;
        self.surface
            .par_iter_mut()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, s)| *s = is_surface(count[k], full[body[k] as usize]));
        // 2. Outward normals of surface particles, from all live neighbours: in the current
        //    configuration (updated-Lagrangian), or in the reference one and carried to the
        //    current by Nanson's relation n ∝ F^{−T} N (total-Lagrangian).
        let surface = &self.surface;
        let total_lagrangian = at.pairs.is_none();
        self.normal
            .par_iter_mut()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, n)| {
                *n = Vector::zeros();
                if !surface[k] {
                    return;
                }
                let i = parts[k] as usize;
                let kernel = &kernels[body[k] as usize];
                let support = kernel.support_radius();
                if total_lagrangian {
                    let mut normal = OutwardNormal::new(p.positions0[i], kernel);
                    Self::for_each_neighbour(at, i, support, |j, _| normal.add(p.positions0[j]));
                    *n = current_normal(&p.deformation_gradient[i], normal.unit());
                } else {
                    let mut normal = OutwardNormal::new(position(i), kernel);
                    Self::for_each_neighbour(at, i, support, |_, xj| normal.add(xj));
                    *n = normal.unit();
                }
            });
        self.prepared = true;
    }

    /// Whether surface participant `a` defines the normal of its pair with `b` (numerics.md
    /// §12.1 `[C]`, in place of Fuller's multiple-normal refinement). `a` must be a surface
    /// particle; against a surface particle `b`:
    ///
    /// - **A driven body is the master surface.** Of a body whose motion is entirely
    ///   prescribed (a fixed wall, an indenter) and a deformable one, only the driven body's
    ///   normal acts, as a rigid surface is the master in finite-element contact. Its normals
    ///   do not change with the deformation, so each pair force is the gradient of a fixed
    ///   potential of the deformable particle's position. A deformable particle's normal, held
    ///   fixed for the force, turns as its neighbours move; the work of that turning is not
    ///   conserved, and with the noisy surface of an updated-Lagrangian ball pressed on a wall
    ///   it pumped 70 times the incident energy into the contact (taken out again by the
    ///   artificial viscosity).
    /// - **Otherwise the flatter surface defines it:** `b` must not have more same-type
    ///   neighbours than `a`. A corner pressed on a flat face is then pushed along the face
    ///   normal, not along its own diagonal normal (which would push a frictionless slider
    ///   sideways); two faces alike both act.
    #[inline]
    fn defines_normal(&self, a: usize, b: usize) -> bool {
        self.surface[a]
            && (!self.surface[b]
                || (self.driven[b], self.count[b]) <= (self.driven[a], self.count[a]))
    }

    /// Neighbour counts, surface flags and normals of the last evaluation, per participant
    /// (for the lattice check of numerics.md §12.1).
    #[cfg(test)]
    pub(crate) fn surface_state(
        &mut self,
        at: &Configuration<'_, D>,
    ) -> (&[usize], &[bool], &[Vector<D>]) {
        self.prepare(at);
        (&self.count, &self.surface, &self.normal)
    }

    /// Friction's inputs for this step (module doc): each participant's velocity after the
    /// step's other forces (a driven body's: its imposed velocity, which the kick does not
    /// change) and its normal load, the sum of |f_n| over its pair forces, from the same zones
    /// the forces use.
    fn prepare_friction(&mut self, p: &Particles<D>, kick: f64) {
        let parts = self.candidates.participants();
        let driven = &self.driven;
        self.velocity
            .par_iter_mut()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, v)| {
                let i = parts[k] as usize;
                *v = if driven[k] {
                    p.velocities[i] - p.accelerations[i] * kick
                } else {
                    p.velocities[i]
                };
            });
        let mut load = std::mem::take(&mut self.normal_load);
        let this = &*self;
        load.par_iter_mut()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, sum)| {
                *sum = this.sum_over_pair_forces(k, |law, d, n| {
                    law.normal_force_on_partner(d, n).unwrap_or(0.0)
                });
            });
        self.normal_load = load;
    }

    /// Σ over the pair forces of participant `k` of `term(law, d, n̂)`: each candidate partner
    /// and mirror image, in each role in which a normal acts (`defines_normal`), with d the
    /// partner's offset from the surface particle and n̂ the surface particle's normal (an
    /// image's position and normal reflected), at x^n.
    fn sum_over_pair_forces(
        &self,
        k: usize,
        term: impl Fn(&PenaltyLaw, &Vector<D>, &Vector<D>) -> f64,
    ) -> f64 {
        let (x, normal) = (self.candidates.positions(), &self.normal);
        let mirrors = self.candidates.mirrors();
        let mut sum = 0.0;
        let mut pair = |q: usize, x_q: Vector<D>, n_q: Vector<D>| {
            let Some(law) = self.law(k, q) else {
                return;
            };
            if self.defines_normal(k, q) {
                sum += term(law, &(x_q - x[k]), &normal[k]);
            }
            if self.defines_normal(q, k) {
                sum += term(law, &(x[k] - x_q), &n_q);
            }
        };
        for &q in self.candidates.of(k) {
            let q = q as usize;
            pair(q, x[q], normal[q]);
        }
        for image in self.candidates.images_of(k) {
            let (q, mask) = (image.partner as usize, image.mask);
            pair(
                q,
                mirrors.point(&x[q], mask),
                mirrors.vector(&normal[q], mask),
            );
        }
        sum
    }

    /// Stick rate λ of the pair (a, b) \[s/m\] (module doc, `PenaltyLaw::force_on_partner`):
    /// λ = 1/(Δt* (N_a/m_a + N_b/m_b)) with N the participants' normal loads and 1/m = 0 for a
    /// driven body, whose velocity no force changes. Each pair force then takes a share of a
    /// participant's mass in proportion to its normal force: where all of a particle's pairs
    /// slide alike, their stick forces together stop the sliding within the kick, no pair can
    /// reverse it, and a pair's stick and kinetic forces scale alike with its normal force.
    /// Zero without friction.
    #[inline]
    fn stick_rate(&self, p: &Particles<D>, a: usize, b: usize, kick: f64) -> f64 {
        if self.normal_load.is_empty() {
            return 0.0;
        }
        let parts = self.candidates.participants();
        let compliance = |k: usize| {
            if self.driven[k] {
                0.0
            } else {
                self.normal_load[k] / p.masses[parts[k] as usize]
            }
        };
        1.0 / (kick * (compliance(a) + compliance(b)))
    }

    /// Law between the bodies of participants `a` and `b`.
    #[inline]
    fn law(&self, a: usize, b: usize) -> Option<&PenaltyLaw> {
        let body = self.candidates.body();
        self.laws[body[a] as usize * self.n_bodies + body[b] as usize].as_ref()
    }
}

impl<const D: usize> Effect<D> for PenaltyContact<D> {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        "contact"
    }

    /// Δt ≤ 0.5 sqrt(m_I / k_I), k_I the summed normal stiffness of I's pairs at x^n (both as
    /// surface particle and as partner; numerics.md §7 `[C]`).
    fn time_step_limit(&mut self, at: &Configuration<'_, D>) -> Option<(f64, usize)> {
        self.prepare(at);
        let mut stiffness = std::mem::take(&mut self.stiffness);
        let this = &*self;
        let skin = this.candidates.skin();
        stiffness
            .par_iter_mut()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, s)| {
                *s = this.sum_over_pair_forces(k, |law, d, n| {
                    law.vote_stiffness(d, n, skin).unwrap_or(0.0)
                });
            });
        self.stiffness = stiffness;
        self.candidates
            .stiffness_time_step(&self.stiffness, &at.particles.masses, DT_FACTOR)
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        if !self.prepared {
            self.prepare(&Configuration {
                particles: ctx.particles,
                bonds: ctx.bonds,
                pairs: ctx.pairs,
                time: ctx.time,
            });
        }
        self.prepared = false;
        let p = ctx.particles;
        if !self.normal_load.is_empty() {
            self.prepare_friction(p, ctx.kick);
        }
        let mut force = std::mem::take(&mut self.force);
        let this = &*self;
        let (x, normal) = (this.candidates.positions(), &this.normal);
        let mirrors = this.candidates.mirrors();
        // Without friction no velocity is read (the buffer is empty).
        let velocity = |q: usize| this.velocity.get(q).copied().unwrap_or_else(Vector::zeros);
        force
            .par_iter_mut()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, f)| {
                let mut sum = Vector::<D>::zeros();
                let v_k = velocity(k);
                // Partner q at x_q with normal n_q and velocity v_q (an image: all reflected).
                let mut pair = |q: usize, x_q: Vector<D>, n_q: Vector<D>, v_q: Vector<D>| {
                    let Some(law) = this.law(k, q) else {
                        return;
                    };
                    let (k_surface, q_surface) =
                        (this.defines_normal(k, q), this.defines_normal(q, k));
                    if !(k_surface || q_surface) {
                        return;
                    }
                    let stick_rate = this.stick_rate(p, k, q, ctx.kick);
                    // k as the surface particle of the pair (k, q): it feels −f_q.
                    if k_surface {
                        if let Some(on_q) = law.force_on_partner(
                            &(x_q - x[k]),
                            &normal[k],
                            &(v_q - v_k),
                            stick_rate,
                        ) {
                            sum -= on_q;
                        }
                    }
                    // k as the partner of surface particle q.
                    if q_surface {
                        if let Some(on_k) =
                            law.force_on_partner(&(x[k] - x_q), &n_q, &(v_k - v_q), stick_rate)
                        {
                            sum += on_k;
                        }
                    }
                };
                for &q in this.candidates.of(k) {
                    let q = q as usize;
                    pair(q, x[q], normal[q], velocity(q));
                }
                for image in this.candidates.images_of(k) {
                    let (q, mask) = (image.partner as usize, image.mask);
                    pair(
                        q,
                        mirrors.point(&x[q], mask),
                        mirrors.vector(&normal[q], mask),
                        mirrors.vector(&velocity(q), mask),
                    );
                }
                *f = sum;
            });
        self.force = force;
        // Force on the reported body, summed in fixed chunks.
        self.resultant = self.candidates.totals(&[], &self.force).1;
        self.candidates
            .scatter_accelerations(&self.force, &p.masses, out);
    }

    fn resultant(&self) -> Option<Vector<D>> {
        Some(self.resultant)
    }

    fn contact_rebuilds(&self) -> Option<u64> {
        Some(self.candidates.rebuilds())
    }
}

/// The unit normal n = F^{−T} N / |F^{−T} N| of a surface whose reference unit normal is `N`
/// (Nanson's relation n da = J F^{−T} N dA), or zero when `N` is zero or F is singular.
#[inline]
fn current_normal<const D: usize>(
    deformation_gradient: &tlsph_math::Tensor<D>,
    reference_normal: Vector<D>,
) -> Vector<D> {
    let Some(inverse) = deformation_gradient.try_inverse() else {
        return Vector::zeros();
    };
    let normal = inverse.transpose() * reference_normal;
    let length = normal.norm();
    if length > 0.0 && length.is_finite() {
        normal / length
    } else {
        Vector::zeros()
    }
}
