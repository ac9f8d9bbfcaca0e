//! The per-step hot loops: gathers over reference bonds and the constitutive update.
//! Every loop is a gather per particle (rayon over particles, no atomics, no allocation),
//! so results are bit-identical for any thread count.

use crate::bonds::Bonds;
use crate::particles::Particles;
use rayon::prelude::*;
use std::ops::Range;
use tlsph_materials::LinearElastic;
use tlsph_math::{
    embed_with_identity, embed_with_zeros, outer, project, sym, Tensor, Tensor3, Vector,
};

/// Minimum particles per rayon task: below this, splitting costs more than it saves.
pub(crate) const MIN_PARTICLES_PER_TASK: usize = 256;

/// F^n = I + Σ_J V0_J (u_J − u_I) ⊗ G̃_IJ and Ḟ^{n−½} = Σ_J V0_J (v_J − v_I) ⊗ G̃_IJ
/// (R 4.7–4.8, 4.24; numerics.md §4.2–4.3), gathered per particle.
///
/// `transport` replaces the particle velocities in Ḟ when XSPH is declared (numerics.md §10.4).
pub(crate) fn gather_kinematics<const D: usize>(
    bonds: &Bonds<D>,
    p: &mut Particles<D>,
    transport: Option<&[Vector<D>]>,
) {
    let u = &p.displacements[..];
    // Same length as `u`, so the bounds check on u[j] also covers v[j].
    let v = &transport.unwrap_or(&p.velocities)[..u.len()];
    p.deformation_gradient
        .par_iter_mut()
        .zip(p.deformation_rate.par_iter_mut())
        .enumerate()
        .with_min_len(MIN_PARTICLES_PER_TASK)
        .for_each(|(i, (f, f_dot))| (*f, *f_dot) = particle_kinematics(bonds, u, v, i));
}

/// (F^n, Ḟ^{n−½}) of particle `i` through its current bonds (the sums of
/// [`gather_kinematics`]); the same operations in the same order, so a particle whose bonds
/// did not change gets bit-identical values.
#[inline]
pub(crate) fn particle_kinematics<const D: usize>(
    bonds: &Bonds<D>,
    u: &[Vector<D>],
    v: &[Vector<D>],
    i: usize,
) -> (Tensor<D>, Tensor<D>) {
    let (ui, vi) = (u[i], v[i]);
    let mut grad_u = Tensor::<D>::zeros();
    let mut grad_v = Tensor::<D>::zeros();
    let r = bonds.range(i);
    for (&j, g) in bonds.neighbours[r.clone()].iter().zip(&bonds.gradient[r]) {
        let j = j as usize;
        grad_u += outer(&(u[j] - ui), g);
        grad_v += outer(&(v[j] - vi), g);
    }
    (Tensor::<D>::identity() + grad_u, grad_v)
}

/// m_I a_I = V0_I [P_I Σ_J V0_J G̃_IJ − Σ_J P_J V0_J G̃_JI] (numerics.md §4.5 form (c);
/// reduces to the symmetric sum form (a) of R 4.26 for uncorrected gradients), then the kick
/// v += `kick` a in the same pass (R 5.64–5.66).
/// Pair terms are equal and opposite, so linear momentum is conserved exactly.
pub(crate) fn gather_accelerations_and_kick<const D: usize>(
    bonds: &Bonds<D>,
    p: &mut Particles<D>,
    kick: f64,
) {
    let pk1 = &p.pk1;
    let volumes0 = &p.volumes0;
    let masses = &p.masses;
    p.accelerations
        .par_iter_mut()
        .zip(p.velocities.par_iter_mut())
        .enumerate()
        .with_min_len(MIN_PARTICLES_PER_TASK)
        .for_each(|(i, (a, v))| {
            let mut force = pk1[i] * bonds.gradient_sum[i];
            let r = bonds.range(i);
            for (&j, g) in bonds.neighbours[r.clone()]
                .iter()
                .zip(&bonds.reverse_gradient[r])
            {
                force -= pk1[j as usize] * g;
            }
            *a = force * (volumes0[i] / masses[i]);
            *v += *a * kick;
        });
}

/// (cof M, det M) of a 3x3 tensor, with cof M = det M · M⁻ᵀ (so J σ F⁻ᵀ = σ cof F, no division).
///
/// Minors and determinant use the same operations, in the same order, as nalgebra's
/// `try_inverse` and `determinant` for 3x3.
#[inline]
pub(crate) fn cofactor_and_determinant(m: &Tensor3) -> (Tensor3, f64) {
    let (m11, m12, m13) = (m[(0, 0)], m[(0, 1)], m[(0, 2)]);
    let (m21, m22, m23) = (m[(1, 0)], m[(1, 1)], m[(1, 2)]);
    let (m31, m32, m33) = (m[(2, 0)], m[(2, 1)], m[(2, 2)]);
    let minor_m12_m23 = m22 * m33 - m32 * m23;
    let minor_m11_m23 = m21 * m33 - m31 * m23;
    let minor_m11_m22 = m21 * m32 - m31 * m22;
    let det = m11 * minor_m12_m23 - m12 * minor_m11_m23 + m13 * minor_m11_m22;
    // `Tensor3::new` takes rows; these rows are the columns of the adjugate (cof M = adj Mᵀ).
    let cofactor = Tensor3::new(
        minor_m12_m23,
        -minor_m11_m23,
        minor_m11_m22,
        m13 * m32 - m33 * m12,
        m11 * m33 - m31 * m13,
        m12 * m31 - m32 * m11,
        m12 * m23 - m22 * m13,
        m13 * m21 - m23 * m11,
        m11 * m22 - m21 * m12,
    );
    (cofactor, det)
}

/// (M⁻¹, det M) of a 3x3 tensor sharing one determinant; the inverse is `None` when it is
/// singular or not finite (as [`tlsph_math::inverse3`]). Bit-identical to nalgebra's
/// `try_inverse` (each adjugate entry divided by det M) and `determinant`.
#[inline]
pub(crate) fn inverse_and_determinant(m: &Tensor3) -> (Option<Tensor3>, f64) {
    let (cofactor, det) = cofactor_and_determinant(m);
    if det == 0.0 {
        return (None, det);
    }
    let inverse = cofactor.transpose().map(|c| c / det);
    let finite = inverse.iter().all(|x| x.is_finite());
    (finite.then_some(inverse), det)
}

/// Rate of deformation D, spin W and det F at n−½ from F^n and Ḟ^{n−½}
/// (F^{n−½} = F^n − ½Δt Ḟ, L = Ḟ (F^{n−½})⁻¹, D = sym L, W = skew L; R 5.2, 5.26–5.29).
/// A singular F^{n−½} gives zero rates and a NaN determinant, which the inversion check reports.
#[inline]
pub(crate) fn midpoint_rates(f: &Tensor3, f_dot: &Tensor3, dt: f64) -> (Tensor3, Tensor3, f64) {
    let f_half = f - f_dot * (0.5 * dt);
    let (l, j_half) = match inverse_and_determinant(&f_half) {
        (Some(inv), det) => (f_dot * inv, det),
        (None, _) => (Tensor3::zeros(), f64::NAN),
    };
    (sym(&l), (l - l.transpose()) * 0.5, j_half)
}

/// The midpoint kinematics of one particle's rate-form constitutive update (R 5.2, 5.26–5.32):
/// D and W at n−½ from [`midpoint_rates`], and det F, cof F at n relative to the reference.
pub(crate) struct RateKinematics {
    /// Rate of deformation D^{n−½}.
    pub d: Tensor3,
    /// Spin W^{n−½}.
    pub w: Tensor3,
    /// Total J^{n−½} = J0 det F^{n−½} (NaN when F^{n−½} is singular).
    pub j_half: f64,
    /// Total J^n = J0 det F^n.
    pub j: f64,
    /// det F^n relative to the reference configuration.
    j_ref: f64,
    /// cof F^n relative to the reference: P = σ cof F is then relative to it too.
    cofactor: Tensor3,
}

impl RateKinematics {
    /// The kinematics of F^n, Ḟ^{n−½} over Δt, with J0 = det F0 of the reference (1 without a
    /// reference update).
    #[inline]
    pub fn new(f: &Tensor3, f_dot: &Tensor3, dt: f64, j0: f64) -> Self {
        let (d, w, j_half) = midpoint_rates(f, f_dot, dt);
        let (cofactor, j_ref) = cofactor_and_determinant(f);
        Self {
            d,
            w,
            j_half: j_half * j0,
            j: j_ref * j0,
            j_ref,
            cofactor,
        }
    }

    /// The end every rate-form update shares: with σ^n = `stress` and the artificial pressure
    /// `q` on the force-driving stress only (numerics.md §10.2), books
    /// e += Δt J^{n−½}/ρ0 (½(σ^{n−1} + σ^n) − q I):D (R 4.12, 4.28) when the step books energy,
    /// then stores σ^n, J^n and P^n = (σ^n − q I) cof F (R 5.32, numerics.md §4.4). A singular
    /// or non-finite F leaves P = NaN, which the inversion check reports.
    #[inline]
    pub fn store<const D: usize, R: ReferenceJacobian + ?Sized>(
        &self,
        step: &ConstitutiveStep<R>,
        stress: Tensor3,
        q: f64,
        slots: ConstitutiveSlots<'_, D>,
    ) {
        if step.book_energy {
            *slots.internal_energy += step.dt * self.j_half / step.density0
                * (0.5 * (*slots.stress + stress) - Tensor3::identity() * q)
                    .component_mul(&self.d)
                    .sum();
        }
        *slots.stress = stress;
        *slots.jacobian = self.j;
        *slots.pk1 = if self.j_ref != 0.0 && self.j_ref.is_finite() {
            project(&((stress - Tensor3::identity() * q) * self.cofactor))
        } else {
            Tensor::<D>::from_element(f64::NAN)
        };
    }
}

/// One particle's state written by a constitutive update: its entries of [`Particles`].
pub(crate) struct ConstitutiveSlots<'a, const D: usize> {
    /// σ: σ^{n−1} on entry, σ^n on exit.
    pub stress: &'a mut Tensor3,
    /// P^n.
    pub pk1: &'a mut Tensor<D>,
    /// J^n.
    pub jacobian: &'a mut f64,
    /// e: e^{n−1} on entry, e^n on exit.
    pub internal_energy: &'a mut f64,
}

impl<const D: usize> ConstitutiveSlots<'_, D> {
    /// A failed particle: no stress and J = 1, from now on; only its mass and momentum remain
    /// (numerics.md §9.3).
    #[inline]
    pub fn clear_failed(self) {
        *self.stress = Tensor3::zeros();
        *self.pk1 = Tensor::<D>::zeros();
        *self.jacobian = 1.0;
    }
}

/// What a constitutive update over the particle range `r` reads, F^n and Ḟ^{n−½}, and a
/// parallel iterator over what it writes, each particle's [`ConstitutiveSlots`] in order.
pub(crate) fn constitutive_view<const D: usize>(
    p: &mut Particles<D>,
    r: Range<usize>,
) -> (
    &[Tensor<D>],
    &[Tensor<D>],
    impl IndexedParallelIterator<Item = ConstitutiveSlots<'_, D>>,
) {
    let slots = p.stress[r.clone()]
        .par_iter_mut()
        .zip(p.pk1[r.clone()].par_iter_mut())
        .zip(p.jacobian[r.clone()].par_iter_mut())
        .zip(p.internal_energy[r.clone()].par_iter_mut())
        .map(
            |(((stress, pk1), jacobian), internal_energy)| ConstitutiveSlots {
                stress,
                pk1,
                jacobian,
                internal_energy,
            },
        );
    (
        &p.deformation_gradient[r.clone()],
        &p.deformation_rate[r],
        slots,
    )
}

/// det F0 of the reference configuration relative to the initial one, per body-local
/// particle: the constitutive update multiplies its det F (taken relative to the reference)
/// by it wherever the density enters (ρ = ρ0 / (J0 J), EOS, energy, bulk viscosity).
pub(crate) trait ReferenceJacobian: Sync {
    /// J0 of body-local particle `k`.
    fn at(&self, k: usize) -> f64;
}

/// The reference is the initial configuration (no `[reference_update]`): J0 = 1, compiled away.
pub(crate) struct InitialReference;

impl ReferenceJacobian for InitialReference {
    #[inline(always)]
    fn at(&self, _: usize) -> f64 {
        1.0
    }
}

/// An updated reference configuration: J0 per body-local particle.
impl ReferenceJacobian for [f64] {
    #[inline(always)]
    fn at(&self, k: usize) -> f64 {
        self[k]
    }
}

/// Inputs of one constitutive update over a body's particle range.
pub(crate) struct ConstitutiveStep<'a, R: ReferenceJacobian + ?Sized = InitialReference> {
    /// Particle range of the body.
    pub range: Range<usize>,
    /// Reference density ρ0 of the body's material.
    pub density0: f64,
    /// Δt^n: time from the previous stress state to this one (0 on the first step).
    pub dt: f64,
    /// Smoothing length h of the body (length scale ℓ of the bulk viscosity) \[m\].
    pub smoothing_length: f64,
    /// Sound speed at the reference density \[m/s\].
    pub sound_speed0: f64,
    /// det F0 of the current reference configuration (numerics.md §4 `[C]` reference update).
    pub reference_jacobian: &'a R,
    /// Per body-local particle: J / det F carried across neighbour-set rebuilds after failures
    /// (`None` without failure), so the EOS sees a continuous density (numerics.md §4.3, §9.3).
    pub jacobian_carry: Option<&'a [f64]>,
    /// Whether the loop books the internal-energy increment (total-Lagrangian formulations:
    /// the midpoint rule pairs with their bond forces). False for the updated-Lagrangian
    /// formulation, which books e from its own pair sums so that it pairs exactly with its
    /// pair forces (`UpdatedLagrangian::book_previous_stress_power`, numerics.md §3).
    pub book_energy: bool,
}

impl<R: ReferenceJacobian + ?Sized> ConstitutiveStep<'_, R> {
    /// The artificial pressure q of `viscosity` at these kinematics: density ρ0/J, sound speed
    /// c0 √J, length h (numerics.md §10.2).
    #[inline]
    pub fn artificial_pressure<V: Viscosity>(&self, viscosity: &V, at: &RateKinematics) -> f64 {
        let j = at.j;
        viscosity.pressure(
            at.d.trace(),
            self.density0 / j,
            self.sound_speed0 * j.max(0.0).sqrt(),
            self.smoothing_length,
        )
    }
}

/// Artificial pressure added to the force-driving stress (numerics.md §10.2).
pub(crate) trait Viscosity: Sync {
    /// q for tr D, density ρ, sound speed c and length ℓ; 0 when not compressing.
    fn pressure(&self, trace_d: f64, density: f64, sound_speed: f64, length: f64) -> f64;
}

/// No artificial viscosity: compiles to nothing.
pub(crate) struct NoViscosity;

impl Viscosity for NoViscosity {
    #[inline(always)]
    fn pressure(&self, _: f64, _: f64, _: f64, _: f64) -> f64 {
        0.0
    }
}

impl Viscosity for crate::model::BulkViscosity {
    #[inline]
    fn pressure(&self, trace_d: f64, density: f64, sound_speed: f64, length: f64) -> f64 {
        if trace_d < 0.0 {
            density
                * length
                * (self.quadratic * length * trace_d * trace_d
                    - self.linear * sound_speed * trace_d)
        } else {
            0.0
        }
    }
}

/// Cauchy stress with the Jaumann rate (Algorithms 2–3, R 5.26–5.32), for one body.
///
/// Rates are evaluated at n−½ with F^{n−½} = F^n − ½Δt Ḟ (exact because F is linear in u and
/// u^{n−½} = u^n − ½Δt v^{n−½}, R 5.2): L = Ḟ F^{−1}, D = sym L, W = skew L. Internal energy:
/// Δe = Δt σ^{n−½}:D / ρ^{n−½} with σ^{n−½} = ½(σ^{n−1} + σ^n) (R 4.12, 4.28).
pub(crate) fn update_jaumann_rate<const D: usize, V: Viscosity, R: ReferenceJacobian + ?Sized>(
    material: &LinearElastic,
    step: &ConstitutiveStep<R>,
    viscosity: &V,
    p: &mut Particles<D>,
) {
    let (f_all, f_dot_all, slots) = constitutive_view(p, step.range.clone());
    slots
        .enumerate()
        .with_min_len(MIN_PARTICLES_PER_TASK)
        .for_each(|(k, slots)| {
            let f = embed_with_identity(&f_all[k]);
            let f_dot = embed_with_zeros(&f_dot_all[k]);
            let at = RateKinematics::new(&f, &f_dot, step.dt, step.reference_jacobian.at(k));
            let stress = material.jaumann_update(slots.stress, &at.d, &at.w, step.dt);
            let q = step.artificial_pressure(viscosity, &at);
            at.store(step, stress, q, slots);
        });
}

/// St Venant–Kirchhoff stress from the Green–Lagrange strain (Algorithm 1, R 5.9–5.13), for
/// one body. S^n = C:E^n with E = ½(FᵀF − I); P = F S; σ = J⁻¹ F S Fᵀ.
/// Internal energy increment ½(S^{n−1} + S^n):(E^n − E^{n−1}) / ρ0 with F^{n−1} = F^n − Δt Ḟ,
/// which for this quadratic energy equals the exact change of strain energy.
///
/// Needs F relative to the initial configuration, so a reference update is rejected at setup
/// for this path (`step.reference_jacobian` is always the initial reference here).
pub(crate) fn update_green_lagrange<const D: usize, R: ReferenceJacobian + ?Sized>(
    material: &LinearElastic,
    step: &ConstitutiveStep<R>,
    p: &mut Particles<D>,
) {
    let dt = step.dt;
    let rho0 = step.density0;
    let (f_all, f_dot_all, slots) = constitutive_view(p, step.range.clone());
    let green_lagrange = |f: &Tensor3| (f.transpose() * f - Tensor3::identity()) * 0.5;
    slots
        .enumerate()
        .with_min_len(MIN_PARTICLES_PER_TASK)
        .for_each(|(k, slots)| {
            let f = embed_with_identity(&f_all[k]);
            let f_prev = f - embed_with_zeros(&f_dot_all[k]) * dt;
            let e = green_lagrange(&f);
            let e_prev = green_lagrange(&f_prev);
            let s = material.second_piola_kirchhoff(&e);
            let s_prev = material.second_piola_kirchhoff(&e_prev);
            if step.book_energy {
                *slots.internal_energy +=
                    0.5 * (s + s_prev).component_mul(&(e - e_prev)).sum() / rho0;
            }
            let j = f.determinant();
            *slots.jacobian = j;
            let fs = f * s;
            *slots.pk1 = project(&fs);
            *slots.stress = fs * f.transpose() / j;
        });
}
