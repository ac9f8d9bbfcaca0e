//! Fuller's particle-type penalty contact with Coulomb friction (numerics.md §12.1, F §4.3–4.4).
//!
//! Every body is a particle type: kernel (stress) interactions stay inside a type, and bodies of
//! different types meet only through this contact. Each step, at x^n:
//!
//! 1. **Surface detection** (F §4.3.1): n_I = number of same-type neighbours of I within the
//!    kernel support — in a total-Lagrangian formulation the support is the reference one, so
//!    n_I is I's live bond count (a failed neighbour no longer counts); in the
//!    updated-Lagrangian formulation it is the current pairs within 2h. n_full is the largest
//!    n_I of the body at the first step (the fully surrounded lattice value, 24 in 2D and 92 in
//!    3D for h = 1.5Δx). I is a surface particle if n_I ≤ [`SURFACE_FRACTION`] · n_full.
//! 2. **Normals** (F 4.1): n_I = Σ_J (x_I − x_J)/r_IJ W(r_IJ) over all live same-type
//!    neighbours, normalised to unit length; it points out of the body. `[C]`: Fuller's
//!    preferred variant leaves out neighbours that are surface particles themselves; on the
//!    stepped face of a lattice disc that tilted face normals by up to 34° (all neighbours: 4°),
//!    and a tilted normal puts a partner one spacing away up to 17 % inside the range.
//! 3. **Interaction zone** (F §4.3.3): K of another type is in contact with surface particle I
//!    when r⊥ = (x_K − x_I)·n̂_I lies in [−d0, R) and the tangential offset
//!    t = |(x_K − x_I) − r⊥ n̂_I| < d0, with d0 = ½(Δx_A + Δx_B). In 2D this is Fuller's square;
//!    in 3D the zone is the cylinder of that radius `[C]` (a cube aligned with n̂ alone has no
//!    defined orientation about it). Of two surface particles the flatter one gives the normal
//!    (see `defines_normal`).
//! 4. **Penalty force** (F 4.2 as corrected in numerics.md §12.1 `[C]`): the pair potential
//!    U = Φ(r⊥) w(t), Φ = k_c [R ln(R/r⊥) − (R − r⊥)] (so −Φ' = k_c (R/r⊥ − 1), Fuller's
//!    force; r⊥ floored at 0.05R), w = (1 − (t/d0)²)², with n̂_I held: f_K = −∇_K U, f_I = −f_K,
//!    k_c = s E* d0^{d−1} (E* the smaller Young's modulus of the pair, s the scene's stiffness
//!    factor, default 1), R = range · d0 (default 1). `[C]`: Fuller's zone switches a pair's
//!    whole force on and off at its sides, which is not conservative: faces sliding past each
//!    other pumped energy into the contact (a slider falling at v onto a plate while sliding at
//!    5v rebounded at 1.36v). The weight and its small tangential force −Φ w' t̂ make each
//!    pair conservative for a fixed normal.
//! 5. **Friction** (F 4.3): f_K += −μ |f_n| v̂_t, v_t the part of v_K − v_I tangential to n̂_I at
//!    t^n, v̂_t = v_t / max(|v_t|, 1e-6 c*) (c* the smaller sound speed); f_I gets the opposite.
//!
//! Each pair contribution is one function of (I, K) evaluated identically from both ends, so
//! forces are equal and opposite and linear momentum is conserved to round-off. The force is
//! not the gradient of a potential (its direction is I's normal, not the pair line), so its
//! work −∫ Σ f·v dt is booked as the `contact` energy column: penalty energy still stored in
//! compressed pairs plus what friction dissipated.
//!
//! Not built: Fuller's multiple-normal refinement and the corner class (n_I ≤ 0.5 n_full), which
//! only that refinement uses.

use super::contact_candidates::{ContactCandidates, MIN_PER_TASK};
use super::{Configuration, Effect, EffectContext};
use rayon::prelude::*;
use tlsph_kernels::{AnyKernel, Kernel};
use tlsph_math::Vector;

/// Surface threshold: a particle with at most this fraction of the fully surrounded neighbour
/// count is a surface particle (F §4.3.1: 75 %). The lattice check of numerics.md §12.1 puts a
/// flat face at 58 % (2D) / 63 % (3D) and the row beneath it at 79 % / 86 %, so the threshold
/// separates them in both dimensions.
pub const SURFACE_FRACTION: f64 = 0.75;

/// Penetration floor of the penalty law as a fraction of R (numerics.md §12.1 `[C]`): the force
/// stops growing at 19 k_c once a particle is 95 % of the way through the range.
const FLOOR_FRACTION: f64 = 0.05;

/// Friction regularisation speed as a fraction of the smaller sound speed (numerics.md §12.1).
const SLIP_FRACTION: f64 = 1e-6;

/// Verlet skin of the cross-type candidate list as a fraction of the smallest d0 (as the
/// potential contact, `CONTACT_SKIN_FRACTION`).
const SKIN_FRACTION: f64 = 0.5;

/// Safety factor of the contact time-step bound Δt ≤ 0.5 sqrt(m/k) (numerics.md §7 `[C]`).
const DT_FACTOR: f64 = 0.5;

/// Penalty law of one pair of bodies (numerics.md §12.1).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PenaltyPairLaw {
    /// k_c = s E* d0^{d−1} \[N/m^{3−d}·m^{d−1} = force\].
    pub stiffness: f64,
    /// Range R of the force along the normal \[m\].
    pub range: f64,
    /// d0 = ½(Δx_A + Δx_B): tangential half-width and penetration depth of the zone \[m\].
    pub reach: f64,
    /// Friction coefficient μ (0: frictionless).
    pub friction: f64,
    /// Regularisation speed 1e-6 c* of the friction direction \[m/s\].
    pub slip_speed: f64,
}

impl PenaltyPairLaw {
    /// Builds the law from the pair's moduli and spacings (numerics.md §12.1 item 5).
    pub(crate) fn new<const D: usize>(
        stiffness_factor: f64,
        range_factor: f64,
        friction: f64,
        youngs: f64,
        sound_speed: f64,
        reach: f64,
    ) -> Self {
        Self {
            stiffness: stiffness_factor * youngs * reach.powi(D as i32 - 1),
            range: range_factor * reach,
            reach,
            friction,
            slip_speed: SLIP_FRACTION * sound_speed,
        }
    }

    /// Whether K at offset d = x_K − x_I from surface particle I (normal n̂) is in I's zone,
    /// and if so (r⊥, tangential offset vector t, |t|).
    #[inline]
    fn normal_offset<const D: usize>(
        &self,
        d: &Vector<D>,
        normal: &Vector<D>,
    ) -> Option<(f64, Vector<D>, f64)> {
        let r_n = d.dot(normal);
        if !(r_n >= -self.reach && r_n < self.range) {
            return None;
        }
        let t = d - normal * r_n;
        let t_len = t.norm();
        (t_len < self.reach).then_some((r_n, t, t_len))
    }

    /// Tangential weight w(t) = (1 − (t/d0)²)² and dw/dt: 1 on I's axis, zero with zero slope
    /// at the zone's side.
    #[inline]
    fn weight(&self, t: f64) -> (f64, f64) {
        let s = t / self.reach;
        let q = 1.0 - s * s;
        (q * q, -4.0 * s * q / self.reach)
    }

    /// Normal force magnitude −dΦ/dr⊥, potential Φ(r⊥) and tangent stiffness at r⊥ (floored:
    /// constant force below the floor).
    #[inline]
    fn normal_force(&self, r_n: f64) -> (f64, f64, f64) {
        let floor = FLOOR_FRACTION * self.range;
        let r = r_n.max(floor);
        let force = self.stiffness * (self.range / r - 1.0);
        let potential = self.stiffness * (self.range * (self.range / r).ln() - (self.range - r))
            + force * (r - r_n);
        (force, potential, self.stiffness * self.range / (r * r))
    }

    /// Force on K from surface particle I: penalty plus friction (numerics.md §12.1 items 5–6).
    #[inline]
    fn force_on_partner<const D: usize>(
        &self,
        d: &Vector<D>,
        normal: &Vector<D>,
        relative_velocity: &Vector<D>,
    ) -> Option<Vector<D>> {
        let (r_n, t, t_len) = self.normal_offset(d, normal)?;
        let (w, dw) = self.weight(t_len);
        let (f, phi, _) = self.normal_force(r_n);
        let f_n = w * f;
        let mut force = normal * f_n;
        // −∂(Φ w)/∂t: with n̂ held, the pair force is the gradient of Φ(r⊥) w(t).
        if t_len > 0.0 {
            force -= t * (phi * dw / t_len);
        }
        if self.friction > 0.0 {
            let v_t = relative_velocity - normal * relative_velocity.dot(normal);
            let speed = v_t.norm().max(self.slip_speed);
            force -= v_t * (self.friction * f_n.abs() / speed);
        }
        Some(force)
    }

    /// Normal stiffness of the pair for the time-step vote: the tangent stiffness inside the
    /// zone, the first-touch stiffness k_c/R within the skin beyond R (it may touch during the
    /// next step), else `None`.
    #[inline]
    fn vote_stiffness<const D: usize>(
        &self,
        d: &Vector<D>,
        normal: &Vector<D>,
        skin: f64,
    ) -> Option<f64> {
        if let Some((r_n, _, t)) = self.normal_offset(d, normal) {
            return Some(self.weight(t).0 * self.normal_force(r_n).2);
        }
        let r_n = d.dot(normal);
        let tangential = d - normal * r_n;
        (r_n >= self.range
            && r_n < self.range + skin
            && tangential.norm_squared() <= self.reach * self.reach)
            .then_some(self.stiffness / self.range)
    }
}

/// Fuller's particle-type penalty contact with friction (numerics.md §12.1).
#[derive(Debug, Clone)]
pub struct PenaltyContact<const D: usize> {
    n_bodies: usize,
    /// Law per ordered body pair (A · n_bodies + B), symmetric; `None`: no contact.
    laws: Vec<Option<PenaltyPairLaw>>,
    /// Kernel of each body (normal weights, updated-Lagrangian neighbour counts).
    kernels: Vec<AnyKernel>,
    /// Fully surrounded neighbour count of each body (set at the first evaluation).
    full_count: Vec<usize>,
    /// Participants, their current positions and candidate partners (searched within the
    /// largest zone reach sqrt(R² + d0²) plus the skin).
    candidates: ContactCandidates<D>,
    /// Per participant: same-type neighbour count, surface flag, unit outward normal (zero for
    /// interior particles).
    count: Vec<usize>,
    surface: Vec<bool>,
    normal: Vec<Vector<D>>,
    /// Per participant: velocity at t^n (scratch), contact force, summed normal stiffness.
    velocity: Vec<Vector<D>>,
    force: Vec<Vector<D>>,
    stiffness: Vec<f64>,
    resultant: Vector<D>,
    /// Geometry holds x^n (set by `time_step_limit`, used by `accelerations`).
    prepared: bool,
}

impl<const D: usize> PenaltyContact<D> {
    /// Contact between the body pairs that have a law in `laws` (`n_bodies`² entries,
    /// symmetric, no diagonal); `kernels` per body, `body_of` per real particle. The resultant
    /// reported is the contact force on the lowest-index body that takes part.
    pub(crate) fn new(
        laws: Vec<Option<PenaltyPairLaw>>,
        n_bodies: usize,
        kernels: Vec<AnyKernel>,
        body_of: &[u32],
    ) -> Self {
        let takes_part = |b: u32| {
            let row = b as usize * n_bodies;
            laws[row..row + n_bodies].iter().any(Option::is_some)
        };
        let active = laws.iter().flatten();
        let min_reach = active
            .clone()
            .map(|l| l.reach)
            .fold(f64::INFINITY, f64::min);
        let max_zone = active.map(|l| l.range.hypot(l.reach)).fold(0.0, f64::max);
        let candidates =
            ContactCandidates::new(body_of, takes_part, max_zone, SKIN_FRACTION * min_reach);
        let n = candidates.len();
        Self {
            n_bodies,
            laws,
            kernels,
            full_count: vec![0; n_bodies],
            candidates,
            count: vec![0; n],
            surface: vec![false; n],
            normal: vec![Vector::zeros(); n],
            velocity: vec![Vector::zeros(); n],
            force: vec![Vector::zeros(); n],
            stiffness: vec![0.0; n],
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
        let (laws, n_bodies) = (&self.laws, self.n_bodies);
        self.candidates.refresh(p, |_, bk, _, bj| {
            laws[bk as usize * n_bodies + bj as usize].is_some()
        });
        // 1. Same-type neighbour counts.
        let (kernels, body, parts) = (
            &self.kernels,
            self.candidates.body(),
            self.candidates.participants(),
        );
        let support = |k: usize| kernels[body[k] as usize].support_radius();
        self.count
            .par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PER_TASK)
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
            .with_min_len(MIN_PER_TASK)
            .for_each(|(k, s)| {
                // A particle without live neighbours (failed, or cut loose) has no surface.
                *s = count[k] > 0
                    && (count[k] as f64) <= SURFACE_FRACTION * full[body[k] as usize] as f64;
            });
        // 2. Outward normals of surface particles, from all live neighbours.
        let surface = &self.surface;
        self.normal
            .par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PER_TASK)
            .for_each(|(k, n)| {
                *n = Vector::zeros();
                if !surface[k] {
                    return;
                }
                let i = parts[k] as usize;
                let kernel = &kernels[body[k] as usize];
                let xi = position(i);
                let mut direction = Vector::<D>::zeros();
                Self::for_each_neighbour(at, i, kernel.support_radius(), |_, xj| {
                    let d = xi - xj;
                    let r = d.norm();
                    if r > 0.0 {
                        direction += d * (kernel.value(r) / r);
                    }
                });
                let length = direction.norm();
                if length > 0.0 && length.is_finite() {
                    *n = direction / length;
                }
            });
        self.prepared = true;
    }

    /// Whether surface participant `a` defines the normal of its pair with `b` (numerics.md
    /// §12.1 `[C]`, in place of Fuller's multiple-normal refinement): `a` is a surface
    /// particle and `b` is not a flatter one (a surface particle with more same-type
    /// neighbours). The smoother surface of the two gives the contact normal, so a corner
    /// pressed on a flat face is pushed along the face normal, not along its own diagonal
    /// normal (which would push a frictionless slider sideways); two faces alike both act.
    #[inline]
    fn defines_normal(&self, a: usize, b: usize) -> bool {
        self.surface[a] && !(self.surface[b] && self.count[b] > self.count[a])
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

    /// Law between the bodies of participants `a` and `b`.
    #[inline]
    fn law(&self, a: usize, b: usize) -> Option<&PenaltyPairLaw> {
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
        let (x, normal) = (this.candidates.positions(), &this.normal);
        let skin = this.candidates.skin();
        stiffness
            .par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PER_TASK)
            .for_each(|(k, s)| {
                let mut sum = 0.0;
                for &q in this.candidates.of(k) {
                    let q = q as usize;
                    let Some(law) = this.law(k, q) else {
                        continue;
                    };
                    let d = x[q] - x[k];
                    if this.defines_normal(k, q) {
                        sum += law.vote_stiffness(&d, &normal[k], skin).unwrap_or(0.0);
                    }
                    if this.defines_normal(q, k) {
                        sum += law.vote_stiffness(&-d, &normal[q], skin).unwrap_or(0.0);
                    }
                }
                *s = sum;
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
            });
        }
        self.prepared = false;
        let p = ctx.particles;
        let parts = self.candidates.participants();
        // Velocity at t^n: undo half of this step's kick.
        self.velocity
            .par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PER_TASK)
            .for_each(|(k, v)| {
                let i = parts[k] as usize;
                *v = p.velocities[i] - p.accelerations[i] * (0.5 * ctx.kick);
            });
        let mut force = std::mem::take(&mut self.force);
        let this = &*self;
        let (x, v, normal) = (this.candidates.positions(), &this.velocity, &this.normal);
        force
            .par_iter_mut()
            .enumerate()
            .with_min_len(MIN_PER_TASK)
            .for_each(|(k, f)| {
                let mut sum = Vector::<D>::zeros();
                for &q in this.candidates.of(k) {
                    let q = q as usize;
                    let Some(law) = this.law(k, q) else {
                        continue;
                    };
                    // k as the surface particle of the pair (k, q): it feels −f_q.
                    if this.defines_normal(k, q) {
                        if let Some(on_q) =
                            law.force_on_partner(&(x[q] - x[k]), &normal[k], &(v[q] - v[k]))
                        {
                            sum -= on_q;
                        }
                    }
                    // k as the partner of surface particle q.
                    if this.defines_normal(q, k) {
                        if let Some(on_k) =
                            law.force_on_partner(&(x[k] - x[q]), &normal[q], &(v[k] - v[q]))
                        {
                            sum += on_k;
                        }
                    }
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
