//! Fuller's particle-type penalty contact with Coulomb friction (numerics.md §12.1,
//! F §4.3–4.4): the law of one surface particle I and one partner K of another body, the
//! surface test and the outward normal. Pointwise; the solver supplies neighbour counts and
//! neighbour positions.
//!
//! 1. **Surface detection** (F §4.3.1): I is a surface particle if its count of same-body
//!    neighbours within the kernel support is at most [`SURFACE_FRACTION`] of the fully
//!    surrounded count ([`is_surface`]).
//! 2. **Normals** (F 4.1): n_I = Σ_J (x_I − x_J)/r_IJ W(r_IJ) over the live same-body
//!    neighbours, normalised ([`OutwardNormal`]); it points out of the body.
//! 3. **Interaction zone** (F §4.3.3): K is in contact with I when r⊥ = (x_K − x_I)·n̂_I lies in
//!    [−d0, R) and the tangential offset t = |(x_K − x_I) − r⊥ n̂_I| < d0, d0 = ½(Δx_A + Δx_B).
//!    In 2D this is Fuller's square; in 3D the zone is the cylinder of that radius `[C]` (a
//!    cube aligned with n̂ alone has no defined orientation about it).
//! 4. **Penalty force** (F 4.2 as corrected in numerics.md §12.1 `[C]`): the pair potential
//!    U = Φ(r⊥) w(t), Φ = k_c [R ln(R/r⊥) − (R − r⊥)] (so −Φ' = k_c (R/r⊥ − 1), Fuller's
//!    force; r⊥ floored at 0.05R), w = (1 − (t/d0)²)², with n̂_I held: f_K = −∇_K U, f_I = −f_K,
//!    k_c = s E* d0^{d−1} (E* the smaller Young's modulus of the pair, s the scene's stiffness
//!    factor, default 1), R = range · d0 (default 1). `[C]`: Fuller's zone switches a pair's
//!    whole force on and off at its sides, which is not conservative: faces sliding past each
//!    other pumped energy into the contact (a slider falling at v onto a plate while sliding at
//!    5v rebounded at 1.36v). The weight and its small tangential force −Φ w' t̂ make each pair
//!    conservative for a fixed normal.
//! 5. **Friction** (F 4.3, with a stick state `[C]`): f_K += −|f_n| μ(λ |v_t|) v_t/|v_t|,
//!    v_t the part of v_K − v_I tangential to n̂_I after the step's other forces and λ the
//!    caller's stick rate \[s/m\]: per unit of normal force, the friction force per unit of
//!    sliding speed that would stop the sliding within the step. μ(demand) is
//!    [`FrictionCoefficients::coefficient`]: the demand itself while it is at most the static
//!    μ_s (the pair sticks under exactly the force that stops it), else the kinetic μ_k (it
//!    slides under Coulomb's kinetic force). With μ_s = μ_k, min(μ, λ |v_t|).
//!    Fuller's law has no stick state; its regularised direction v_t / max(|v_t|, 1e-6 c*)
//!    chatters about zero sliding speed.

use crate::wall::FrictionCoefficients;
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

/// Whether a particle with `count` live same-body neighbours is on the surface of a body whose
/// fully surrounded particles have `full_count` (F §4.3.1). A particle without live neighbours
/// (failed, or cut loose) has no surface.
#[inline]
pub fn is_surface(count: usize, full_count: usize) -> bool {
    count > 0 && (count as f64) <= SURFACE_FRACTION * full_count as f64
}

/// Running sum of F 4.1, n_I ∝ Σ_J (x_I − x_J)/r_IJ W(r_IJ), over the live same-body
/// neighbours of a surface particle I. `[C]`: Fuller's preferred variant leaves out neighbours
/// that are surface particles themselves; on the stepped face of a lattice disc that tilted
/// face normals by up to 34° (all neighbours: 4°), and a tilted normal puts a partner one
/// spacing away up to 17 % inside the range, so all are used.
#[derive(Debug, Clone, Copy)]
pub struct OutwardNormal<'k, const D: usize> {
    x_i: Vector<D>,
    kernel: &'k AnyKernel,
    sum: Vector<D>,
}

impl<'k, const D: usize> OutwardNormal<'k, D> {
    /// An empty sum for the particle at `x_i` with its body's kernel.
    pub fn new(x_i: Vector<D>, kernel: &'k AnyKernel) -> Self {
        Self {
            x_i,
            kernel,
            sum: Vector::zeros(),
        }
    }

    /// Adds the neighbour at `x_j` (a coincident one has no direction and adds nothing).
    #[inline]
    pub fn add(&mut self, x_j: Vector<D>) {
        let d = self.x_i - x_j;
        let r = d.norm();
        if r > 0.0 {
            self.sum += d * (self.kernel.value(r) / r);
        }
    }

    /// The unit outward normal, or zero when the sum has no direction.
    pub fn unit(&self) -> Vector<D> {
        let length = self.sum.norm();
        if length > 0.0 && length.is_finite() {
            self.sum / length
        } else {
            Vector::zeros()
        }
    }
}

/// Penalty law of one pair of bodies (numerics.md §12.1).
#[derive(Debug, Clone, Copy)]
pub struct PenaltyLaw {
    /// k_c = s E* d0^{d−1} \[N\].
    stiffness: f64,
    /// Range R of the force along the normal \[m\].
    range: f64,
    /// d0 = ½(Δx_A + Δx_B): tangential half-width and penetration depth of the zone \[m\].
    reach: f64,
    /// Kinetic and static friction coefficients and the decay between them (μ_s = 0:
    /// frictionless).
    friction: FrictionCoefficients,
}

impl PenaltyLaw {
    /// The law of numerics.md §12.1 item 5 in dimension `D`: k_c = `stiffness_factor` ·
    /// `youngs` · d0^{D−1} (E* the smaller Young's modulus of the pair), R = `range_factor` ·
    /// d0, friction coefficients `friction` (`FrictionCoefficients::single(μ)` for one μ),
    /// d0 = `reach` = ½(Δx_A + Δx_B).
    pub fn new<const D: usize>(
        stiffness_factor: f64,
        range_factor: f64,
        friction: FrictionCoefficients,
        youngs: f64,
        reach: f64,
    ) -> Self {
        Self {
            stiffness: stiffness_factor * youngs * reach.powi(D as i32 - 1),
            range: range_factor * reach,
            reach,
            friction,
        }
    }

    /// Zone half-width and penetration depth d0 \[m\].
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// Farthest distance from I of a point of its zone, sqrt(R² + d0²) \[m\]: the candidate
    /// search radius before the skin.
    pub fn zone_radius(&self) -> f64 {
        self.range.hypot(self.reach)
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

    /// Pair potential U = Φ(r⊥) w(t) of K at offset `d` = x_K − x_I from surface particle I
    /// with unit normal `normal` (0 outside the zone) \[J\] (numerics.md §12.1 item 4).
    pub fn potential<const D: usize>(&self, d: &Vector<D>, normal: &Vector<D>) -> f64 {
        self.normal_offset(d, normal).map_or(0.0, |(r_n, _, t)| {
            self.weight(t).0 * self.normal_force(r_n).1
        })
    }

    /// Normal force magnitude |f_n| = w(t) k_c (R/r⊥ − 1) on K at offset `d` = x_K − x_I from
    /// surface particle I with unit normal `normal` (numerics.md §12.1 item 4; floored as the
    /// force is), or `None` outside I's zone.
    #[inline]
    pub fn normal_force_on_partner<const D: usize>(
        &self,
        d: &Vector<D>,
        normal: &Vector<D>,
    ) -> Option<f64> {
        let (r_n, _, t_len) = self.normal_offset(d, normal)?;
        Some((self.weight(t_len).0 * self.normal_force(r_n).0).abs())
    }

    /// Whether the law has friction (μ_s > 0: a pair can stick, even when μ_k = 0).
    pub fn has_friction(&self) -> bool {
        self.friction.is_frictional()
    }

    /// Force on K at offset `d` = x_K − x_I from surface particle I with unit normal `normal`:
    /// penalty −∇_K U plus friction (numerics.md §12.1 items 4–5, module doc item 5) from the
    /// relative velocity v_K − v_I after the step's other forces and the stick rate λ
    /// (`stick_rate` \[s/m\]: per unit of normal force, the friction force per unit of sliding
    /// speed that would stop the sliding within the step). `None` outside I's zone. I feels the
    /// opposite force.
    #[inline]
    pub fn force_on_partner<const D: usize>(
        &self,
        d: &Vector<D>,
        normal: &Vector<D>,
        relative_velocity: &Vector<D>,
        stick_rate: f64,
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
        if self.has_friction() {
            let v_t = tlsph_math::across(relative_velocity, normal);
            let speed = v_t.norm();
            if speed > 0.0 {
                // Kinetic Coulomb force, or the force that stops the sliding (stick) while it
                // is within the static limit.
                let coefficient = self.friction.coefficient(stick_rate * speed, speed);
                force -= v_t * (coefficient * f_n.abs() / speed);
            }
        }
        Some(force)
    }

    /// Normal stiffness of the pair for the time-step vote: the tangent stiffness
    /// w(t) k_c R / r⊥² inside the zone, the first-touch stiffness w(t) k_c / R within `skin`
    /// beyond R (it may touch during the next step), else `None`. Both carry the tangential
    /// weight, so the vote is continuous at the zone's side: a lattice partner one spacing to
    /// the side (t = d0, where the force is zero) must not swing the step on the last bit of
    /// its position, or a mirrored scene and its half model would step differently.
    #[inline]
    pub fn vote_stiffness<const D: usize>(
        &self,
        d: &Vector<D>,
        normal: &Vector<D>,
        skin: f64,
    ) -> Option<f64> {
        if let Some((r_n, _, t)) = self.normal_offset(d, normal) {
            return Some(self.weight(t).0 * self.normal_force(r_n).2);
        }
        let r_n = d.dot(normal);
        let t = (d - normal * r_n).norm();
        (r_n >= self.range && r_n < self.range + skin && t < self.reach)
            .then(|| self.weight(t).0 * self.stiffness / self.range)
    }
}
