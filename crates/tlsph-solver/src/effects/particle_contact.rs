//! Frictionless potential-type particle-to-particle contact between bodies (numerics.md §12.2
//! `[C]`): the effect that drives `tlsph_contact::PotentialLaw` over a Verlet list of
//! cross-body candidate pairs in the current configuration. Depends on current positions and
//! masses only.
//!
//! The force is the gradient of a pair potential, which is booked as stored energy, so total
//! energy closes up to the time-integration error. Both particles of a pair evaluate the same
//! scalar from the same |x_I − x_K| (negation is exact), so pair forces are equal and opposite
//! bit for bit and linear momentum is conserved to round-off.
//!
//! A body paired with itself gets self-contact (a TLSPH body folding onto itself, whose
//! particles would otherwise pass through each other): the same law between its particles
//! that were not kernel neighbours in the reference configuration (|X_I − X_K| ≥ 2h), so
//! self-contact never acts inside the continuum, only between surfaces that meet.
//!
//! With symmetry planes a participant near a plane also meets the mirror images of the
//! participants beyond it (numerics.md §13.1), as the full model's particles there, with the
//! same law; each image pair is evaluated from both ends (I with the image of K, K with the
//! image of I), so momentum and the stored energy are those of the modelled part of the full
//! model.

use super::{Configuration, Effect, EffectContext};
use crate::particles::Particles;
use rayon::prelude::*;
use tlsph_contact::{
    ContactCandidates, PotentialLaw, DT_FACTOR, PARTICIPANTS_PER_TASK, SKIN_FRACTION,
};
use tlsph_math::{PlaneReflections, Vector};

/// Potential-type contact between particles of different bodies (numerics.md §12.2).
#[derive(Debug, Clone)]
pub struct ParticleContact<const D: usize> {
    n_bodies: usize,
    /// Law per ordered body pair (A · n_bodies + B), `None` when the pair has no contact.
    laws: Vec<Option<PotentialLaw>>,
    /// Participants, their current positions and candidate partners.
    candidates: ContactCandidates<D>,
    /// Symmetry planes whose images the contact sees (empty: none).
    mirrors: PlaneReflections<D>,
    /// Per participant: contact force, half of its pairs' potential, summed pair stiffness.
    force: Vec<Vector<D>>,
    half_potential: Vec<f64>,
    stiffness: Vec<f64>,
    stored: f64,
    resultant: Vector<D>,
    /// Forces hold the current positions (set by `time_step_limit`, used by `accelerations`).
    evaluated: bool,
}

impl<const D: usize> ParticleContact<D> {
    /// Contact between the body pairs that have a law in `laws` (`n_bodies`² entries,
    /// symmetric; a diagonal entry is self-contact); `body_of` gives the body of each of the
    /// real particles. The resultant reported is
    /// the contact force on the lowest-index body that takes part. With symmetry planes
    /// `mirrors` a participant also meets the images of the participants beyond them.
    pub(crate) fn new(
        laws: Vec<Option<PotentialLaw>>,
        n_bodies: usize,
        body_of: &[u32],
        mirrors: PlaneReflections<D>,
    ) -> Self {
        let takes_part = |b: u32| {
            let row = b as usize * n_bodies;
            laws[row..row + n_bodies].iter().any(Option::is_some)
        };
        let d0s = laws.iter().flatten().map(PotentialLaw::d0);
        let min_d0 = d0s.clone().fold(f64::INFINITY, f64::min);
        let max_d0 = d0s.fold(0.0, f64::max);
        let candidates =
            ContactCandidates::new(body_of, takes_part, max_d0, SKIN_FRACTION * min_d0)
                .with_mirrors(mirrors.clone());
        let n = candidates.len();
        Self {
            n_bodies,
            laws,
            candidates,
            mirrors,
            force: vec![Vector::zeros(); n],
            half_potential: vec![0.0; n],
            stiffness: vec![0.0; n],
            stored: 0.0,
            resultant: Vector::zeros(),
            evaluated: false,
        }
    }

    /// Current positions, a rebuild of the candidate list if needed, and forces, potentials
    /// and stiffnesses at x^n (one gather per participant, over its partners and, with
    /// symmetry planes, their mirror images).
    fn evaluate(&mut self, p: &Particles<D>) {
        let (laws, n_bodies) = (&self.laws, self.n_bodies);
        let mirrors = &self.mirrors;
        let law = |a: u32, b: u32| laws[a as usize * n_bodies + b as usize].as_ref();
        // Candidates: a participant of a body in contact; for self-contact, never a reference
        // kernel neighbour (nor I itself), images included (a bond to a ghost). The reference
        // positions are the initial ones: a reference update is refused with self-contact.
        self.candidates
            .refresh(&p.positions0, &p.displacements, |pair| {
                law(pair.body_k, pair.body_j).is_some_and(|law| {
                    pair.across_bodies() || {
                        let image0 = mirrors.point(&p.positions0[pair.particle_j], pair.mask);
                        law.allows_self_pair(
                            (image0 - p.positions0[pair.particle_k]).norm_squared(),
                        )
                    }
                })
            });
        let candidates = &self.candidates;
        let (x, body, skin) = (candidates.positions(), candidates.body(), candidates.skin());
        let mirrors = candidates.mirrors();
        self.force
            .par_iter_mut()
            .zip(self.half_potential.par_iter_mut())
            .zip(self.stiffness.par_iter_mut())
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, ((f, e), s))| {
                let (mut force, mut energy, mut stiffness) = (Vector::<D>::zeros(), 0.0, 0.0);
                let xk = x[k];
                let mut pair = |law: &PotentialLaw, xj: Vector<D>| {
                    let r_vec = xk - xj;
                    let r = r_vec.norm();
                    // Beyond d0 no force, but a pair within the skin may touch during the
                    // next step: its stiffness at first touch joins the time-step vote, so a
                    // stiff contact is never entered with a step it cannot resolve.
                    if r >= law.d0() || r.is_nan() {
                        if r < law.d0() + skin {
                            stiffness += law.touch_stiffness();
                        }
                        return;
                    }
                    // Coincident particles have no direction (force 0, potential booked).
                    let state = law.evaluate(r);
                    if r > 0.0 {
                        force += r_vec * (state.force / r);
                    }
                    energy += 0.5 * state.potential;
                    stiffness += state.stiffness;
                };
                for &j in candidates.of(k) {
                    if let Some(law) = law(body[k], body[j as usize]) {
                        pair(law, x[j as usize]);
                    }
                }
                // The full model's images beyond the symmetry planes: the image pair's
                // energy is split as any pair's (the image of I holds the other half).
                for image in candidates.images_of(k) {
                    let j = image.partner as usize;
                    if let Some(law) = law(body[k], body[j]) {
                        pair(law, mirrors.point(&x[j], image.mask));
                    }
                }
                *f = force;
                *e = energy;
                *s = stiffness;
            });
        // Stored energy and the reported body's force, summed in fixed chunks.
        (self.stored, self.resultant) = self.candidates.totals(&self.half_potential, &self.force);
        self.evaluated = true;
    }
}

impl<const D: usize> Effect<D> for ParticleContact<D> {
    fn clone_box(&self) -> Box<dyn Effect<D>> {
        Box::new(self.clone())
    }

    fn name(&self) -> &str {
        "contact"
    }

    /// Δt ≤ 0.5 sqrt(m_I / k_I) with k_I the summed tangent stiffness of I's active pairs
    /// (numerics.md §7 `[C]`), evaluated at x^n; also caches the forces at x^n.
    fn time_step_limit(&mut self, at: &Configuration<'_, D>) -> Option<(f64, usize)> {
        self.evaluate(at.particles);
        self.candidates
            .stiffness_time_step(&self.stiffness, &at.particles.masses, DT_FACTOR)
    }

    fn accelerations(&mut self, ctx: &EffectContext<'_, D>, out: &mut [Vector<D>]) {
        if !self.evaluated {
            self.evaluate(ctx.particles);
        }
        self.evaluated = false;
        self.candidates
            .scatter_accelerations(&self.force, &ctx.particles.masses, out);
    }

    fn stored_energy(&self) -> Option<f64> {
        Some(self.stored)
    }

    fn resultant(&self) -> Option<Vector<D>> {
        Some(self.resultant)
    }

    fn contact_rebuilds(&self) -> Option<u64> {
        Some(self.candidates.rebuilds())
    }
}
