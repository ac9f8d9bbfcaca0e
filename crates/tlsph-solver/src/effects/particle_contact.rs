//! Frictionless potential-type particle-to-particle contact between bodies (Vignjevic et al.,
//! numerics.md §12.2 `[C]`). Depends on current positions and masses only; owns a Verlet list
//! of cross-body candidate pairs in the current configuration, rebuilt with a skin.
//!
//! For I in body A and K in body B (A ≠ B, the pair declared), r = |x_I − x_K|,
//! d0 = ½(Δx_A + Δx_B), h_c = ½(h_A + h_B), M* = min(M_A, M_B) with M = K_eff + 4G/3:
//!
//! f_I = a M* d0^{d−1} [(W(r, h_c)/W(d0, h_c))ⁿ − 1]₊ (x_I − x_K)/r,   f_K = −f_I.
//!
//! The force is the gradient of the pair potential φ(r) = a M* d0^{d−1} ∫_r^{d0} [(W/W0)ⁿ − 1] ds,
//! which is booked as stored energy, so total energy closes up to the time-integration error.
//! Both particles of a pair evaluate the same scalar from the same |x_I − x_K| (negation is
//! exact), so pair forces are equal and opposite bit for bit and linear momentum is conserved
//! to round-off.
//!
//! A body paired with itself gets self-contact (a TLSPH body folding onto itself, whose
//! particles would otherwise pass through each other): the same law between its particles
//! that were not kernel neighbours in the reference configuration (|X_I − X_K| ≥ 2h), so
//! self-contact never acts inside the continuum, only between surfaces that meet.

use super::contact_candidates::{ContactCandidates, MIN_PER_TASK};
use super::{Configuration, Effect, EffectContext};
use crate::particles::Particles;
use rayon::prelude::*;
use tlsph_kernels::{AnyKernel, Kernel};
use tlsph_math::Vector;

/// Verlet skin as a fraction of the smallest contact distance d0: the candidate list holds
/// every cross-body pair within (largest d0 + skin) and is rebuilt once any participating
/// particle has moved by half the skin since the last build, so no pair closer than d0 is
/// ever missing. Half a spacing keeps rebuilds to one every few steps even for a flyer at
/// 0.1 c (it moves ≈ 0.1 · C_cfl · h per step) while adding only a few candidates per
/// surface particle.
pub const CONTACT_SKIN_FRACTION: f64 = 0.5;

/// Safety factor of the contact time-step bound Δt ≤ 0.5 sqrt(m/k) (numerics.md §7 `[C]`).
const DT_FACTOR: f64 = 0.5;

/// 8-point Gauss–Legendre nodes and weights on [−1, 1] (exact for polynomials of degree 15:
/// the cubic-spline integrand (W/W0)⁴ − 1 is of degree 12 on each kernel piece).
const GAUSS_NODES: [f64; 8] = [
    -0.960_289_856_497_536_3,
    -0.796_666_477_413_626_7,
    -0.525_532_409_916_329,
    -0.183_434_642_495_649_8,
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
const GAUSS_WEIGHTS: [f64; 8] = [
    0.101_228_536_290_376_3,
    0.222_381_034_453_374_5,
    0.313_706_645_877_887_3,
    0.362_683_783_378_362,
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// Contact law of one (ordered) pair of bodies (numerics.md §12.2).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairLaw {
    /// Kernel with the pair smoothing length h_c = ½(h_A + h_B).
    pub kernel: AnyKernel,
    /// Contact distance d0 = ½(Δx_A + Δx_B) \[m\].
    pub d0: f64,
    /// a M* d0^{d−1} \[N\] (force per unit depth in 2D, N/m² · m in 1D).
    pub coefficient: f64,
    /// Self-contact only: pairs closer than this in the reference configuration (the
    /// kernel support 2h) are the body's own continuum and never in contact \[m\].
    pub exclusion: f64,
}

/// The law evaluated at one distance: force magnitude, potential and tangent stiffness.
struct PairState {
    force: f64,
    potential: f64,
    stiffness: f64,
}

/// Exponent n as an integer power when it is one (every Reveles deck uses 4).
#[derive(Debug, Clone, Copy)]
enum Power {
    Integer(i32),
    Real(f64),
}

impl Power {
    #[inline]
    fn apply(self, x: f64) -> f64 {
        match self {
            Power::Integer(n) => x.powi(n),
            Power::Real(n) => x.powf(n),
        }
    }
}

/// Laws of a pair of bodies with the kernel value W(d0, h_c) cached.
#[derive(Debug, Clone, Copy)]
struct Law {
    kernel: AnyKernel,
    d0: f64,
    coefficient: f64,
    /// 1 / W(d0, h_c).
    inv_w0: f64,
    /// Normal stiffness at first touch, −df/dr at r = d0 \[N/m\].
    touch_stiffness: f64,
    /// Squared reference-distance exclusion of self-contact (0 between different bodies).
    exclusion_sq: f64,
}

impl Law {
    /// g(s) = (W(s)/W0)ⁿ − 1, the dimensionless force shape.
    #[inline]
    fn shape(&self, s: f64, n: Power) -> f64 {
        n.apply(self.kernel.value(s) * self.inv_w0) - 1.0
    }

    /// Force, potential φ(r) = c ∫_r^{d0} g ds (Gauss–Legendre, split at the cubic spline's
    /// break point q = 1) and stiffness max(−df/dr, f/r) at distance r < d0.
    fn evaluate(&self, r: f64, n: Power, exponent: f64) -> PairState {
        let ratio = self.kernel.value(r) * self.inv_w0;
        let force = self.coefficient * (n.apply(ratio) - 1.0);
        // −df/dr = c n (W/W0)^{n−1} (−W'(r))/W0.
        let normal =
            self.coefficient * exponent * n.apply(ratio) * (-self.kernel.derivative(r)).max(0.0)
                / (self.kernel.value(r)).max(f64::MIN_POSITIVE);
        let transverse = if r > 0.0 { force / r } else { 0.0 };
        let h = self.kernel.smoothing_length();
        let potential = if r < h && h < self.d0 {
            self.integrate(r, h, n) + self.integrate(h, self.d0, n)
        } else {
            self.integrate(r, self.d0, n)
        };
        PairState {
            force,
            potential: self.coefficient * potential,
            stiffness: normal.max(transverse),
        }
    }

    fn integrate(&self, a: f64, b: f64, n: Power) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        GAUSS_NODES
            .iter()
            .zip(GAUSS_WEIGHTS)
            .map(|(x, w)| w * self.shape(mid + half * x, n))
            .sum::<f64>()
            * half
    }
}

/// Potential-type contact between particles of different bodies (numerics.md §12.2).
#[derive(Debug, Clone)]
pub struct ParticleContact<const D: usize> {
    /// Exponent n as given.
    exponent: f64,
    power: Power,
    n_bodies: usize,
    /// Law per ordered body pair (A · n_bodies + B), `None` when the pair has no contact.
    laws: Vec<Option<Law>>,
    /// Participants, their current positions and candidate partners.
    candidates: ContactCandidates<D>,
    /// Reference positions of the participants (self-contact exclusion).
    positions0: Vec<Vector<D>>,
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
    /// Contact with exponent n between the body pairs that have a law in `laws`
    /// (`n_bodies`² entries, symmetric; a diagonal entry is self-contact); `body_of` gives the
    /// body of each of the `n_real` real particles and `positions0` their reference
    /// positions. The resultant reported is the contact force on the lowest-index body that
    /// takes part.
    pub(crate) fn new(
        exponent: f64,
        laws: Vec<Option<PairLaw>>,
        n_bodies: usize,
        body_of: &[u32],
        positions0: &[Vector<D>],
    ) -> Self {
        let laws: Vec<Option<Law>> = laws
            .into_iter()
            .map(|l| {
                l.map(|l| Law {
                    kernel: l.kernel,
                    d0: l.d0,
                    coefficient: l.coefficient,
                    inv_w0: 1.0 / l.kernel.value(l.d0),
                    touch_stiffness: l.coefficient
                        * exponent
                        * (-l.kernel.derivative(l.d0)).max(0.0)
                        / l.kernel.value(l.d0),
                    exclusion_sq: l.exclusion * l.exclusion,
                })
            })
            .collect();
        let takes_part = |b: u32| {
            let row = b as usize * n_bodies;
            laws[row..row + n_bodies].iter().any(Option::is_some)
        };
        let d0s = laws.iter().flatten().map(|l| l.d0);
        let min_d0 = d0s.clone().fold(f64::INFINITY, f64::min);
        let max_d0 = d0s.fold(0.0, f64::max);
        let candidates =
            ContactCandidates::new(body_of, takes_part, max_d0, CONTACT_SKIN_FRACTION * min_d0);
        let reference = candidates
            .participants()
            .iter()
            .map(|&i| positions0[i as usize])
            .collect();
        let n = candidates.len();
        let power = if exponent.fract() == 0.0 && exponent.abs() < 64.0 {
            Power::Integer(exponent as i32)
        } else {
            Power::Real(exponent)
        };
        Self {
            exponent,
            power,
            n_bodies,
            laws,
            candidates,
            positions0: reference,
            force: vec![Vector::zeros(); n],
            half_potential: vec![0.0; n],
            stiffness: vec![0.0; n],
            stored: 0.0,
            resultant: Vector::zeros(),
            evaluated: false,
        }
    }

    /// Current positions, a rebuild of the candidate list if needed, and forces, potentials
    /// and stiffnesses at x^n (one gather per participant).
    fn evaluate(&mut self, p: &Particles<D>) {
        let (laws, n_bodies, positions0) = (&self.laws, self.n_bodies, &self.positions0);
        let law = |a: u32, b: u32| laws[a as usize * n_bodies + b as usize].as_ref();
        // Candidates: a participant of a body in contact; for self-contact, never a reference
        // kernel neighbour (nor I itself) — the exclusion is 0 between different bodies.
        self.candidates.refresh(p, |k, bk, j, bj| {
            law(bk, bj).is_some_and(|law| {
                bj != bk
                    || (positions0[j] - positions0[k]).norm_squared()
                        >= law.exclusion_sq.max(f64::MIN_POSITIVE)
            })
        });
        let (n, exponent) = (self.power, self.exponent);
        let candidates = &self.candidates;
        let (x, body, skin) = (candidates.positions(), candidates.body(), candidates.skin());
        self.force
            .par_iter_mut()
            .zip(self.half_potential.par_iter_mut())
            .zip(self.stiffness.par_iter_mut())
            .enumerate()
            .with_min_len(MIN_PER_TASK)
            .for_each(|(k, ((f, e), s))| {
                let (mut force, mut energy, mut stiffness) = (Vector::<D>::zeros(), 0.0, 0.0);
                let xk = x[k];
                for &j in candidates.of(k) {
                    let j = j as usize;
                    let Some(law) = law(body[k], body[j]) else {
                        continue;
                    };
                    let r_vec = xk - x[j];
                    let r = r_vec.norm();
                    // Beyond d0 no force, but a pair within the skin may touch during the
                    // next step: its stiffness at first touch joins the time-step vote, so a
                    // stiff contact is never entered with a step it cannot resolve.
                    if r >= law.d0 || r.is_nan() {
                        if r < law.d0 + skin {
                            stiffness += law.touch_stiffness;
                        }
                        continue;
                    }
                    // Coincident particles have no direction (force 0, potential booked).
                    let state = law.evaluate(r, n, exponent);
                    if r > 0.0 {
                        force += r_vec * (state.force / r);
                    }
                    energy += 0.5 * state.potential;
                    stiffness += state.stiffness;
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
