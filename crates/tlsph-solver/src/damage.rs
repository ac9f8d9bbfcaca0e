//! Constitutive update of damaged linear-elastic bodies (numerics.md §8.1, §9.1–9.3): the
//! undamaged ("effective") Cauchy stress is integrated with the Jaumann rate, a damage law
//! turns the kinematics into D, and the stress the body feels is the effective stress with its
//! tensile principal part scaled by (1 − D). D = 1 marks the particle failed; the simulation
//! then takes it out of every sum (`Bonds::remove_failed`).
//!
//! The update is monomorphised per damage law (a [`Law`] type parameter), so the particle loop
//! has no branch on the model; bodies without a damage model never reach this file and carry
//! none of its state ([`DamageState::None`]).

use crate::model::{BulkViscosity, DamageModel, ElasticDamage, MaterialModel};
use crate::particles::Particles;
use crate::step::{
    cofactor_and_determinant, midpoint_rates, ConstitutiveStep, NoViscosity, ReferenceJacobian,
    Viscosity, MIN_PARTICLES_PER_TASK,
};
use rayon::prelude::*;
use tlsph_materials::damage::{degrade_tensile_part, BENZ_ASPHAUG_CRACK_SPEED_RATIO};
use tlsph_materials::{max_principal_value, GradyKipp, LinearElastic, PeerlingsSoftening};
use tlsph_math::{embed_with_identity, embed_with_zeros, project, Tensor, Tensor3};

/// Failure status values stored in a particle's state (as in `plasticity.rs`).
const INTACT: u8 = 0;
const FAILED_NOW: u8 = 1;
const REMOVED: u8 = 2;

/// Per-particle damage state of one body; `None` unless its material declares damage.
#[derive(Debug, Clone)]
pub(crate) enum DamageState {
    /// The body's material has no damage law: nothing stored, nothing run.
    None,
    /// A damaged elastic body.
    Damaged(Box<DamagedBody>),
}

/// State of a damaged elastic body.
#[derive(Debug, Clone)]
pub(crate) struct DamagedBody {
    /// Undamaged Cauchy stress σ_eff integrated with the Jaumann rate (numerics.md §8.1).
    effective: Vec<Tensor3>,
    /// History variable: κ = max ε_max (Peerlings) or the largest ε_eff reached (Grady–Kipp).
    history: Vec<f64>,
    /// Damage D ∈ [0, 1].
    damage: Vec<f64>,
    /// 0 intact, 1 failed in the last update, 2 failed and removed.
    status: Vec<u8>,
    /// Grady–Kipp flaws of the body (empty for Peerlings).
    flaws: Flaws,
}

/// Flaw activation strains of every particle of a body in CSR form (numerics.md §9.2): the
/// thresholds of local particle k are `thresholds[offsets[k]..offsets[k + 1]]`, ascending.
#[derive(Debug, Clone, Default)]
struct Flaws {
    offsets: Vec<usize>,
    thresholds: Vec<f64>,
}

impl DamageState {
    /// State for the `volumes0.len()` particles of a body made of `model` (nothing unless the
    /// material has a damage law). Grady–Kipp flaws are seeded here, once per body, from the
    /// body's total reference measure Σ V0 and the declared seed (numerics.md §9.2).
    pub fn for_material(model: &MaterialModel, volumes0: &[f64]) -> Self {
        let MaterialModel::ElasticDamage(m) = model else {
            return DamageState::None;
        };
        let n = volumes0.len();
        let flaws = match m.damage {
            DamageModel::Peerlings(_) => Flaws::default(),
            DamageModel::GradyKipp { model, seed } => {
                // Sequential sum in particle order: the same total for any thread count.
                let total: f64 = volumes0.iter().sum();
                let per_particle = model.seed_flaws(n, total, seed);
                let mut offsets = Vec::with_capacity(n + 1);
                offsets.push(0);
                let mut thresholds = Vec::with_capacity(GradyKipp::flaw_count(n));
                for list in per_particle {
                    thresholds.extend(list);
                    offsets.push(thresholds.len());
                }
                Flaws {
                    offsets,
                    thresholds,
                }
            }
        };
        DamageState::Damaged(Box::new(DamagedBody {
            effective: vec![Tensor3::zeros(); n],
            history: vec![0.0; n],
            damage: vec![0.0; n],
            status: vec![INTACT; n],
            flaws,
        }))
    }

    /// Damage of local particle `k` (1 once failed), if the body has a damage law.
    pub fn damage(&self, k: usize) -> Option<f64> {
        match self {
            DamageState::None => None,
            DamageState::Damaged(b) => Some(if b.status[k] != INTACT {
                1.0
            } else {
                b.damage[k]
            }),
        }
    }

    /// Marks local particle `k` as failed and removed outside a constitutive update (a particle
    /// left without neighbours); nothing for bodies without damage.
    pub fn mark_removed(&mut self, k: usize) {
        if let DamageState::Damaged(b) = self {
            b.status[k] = REMOVED;
            b.damage[k] = 1.0;
        }
    }

    /// Marks the particles that failed in the last update as removed and returns their local
    /// indices (empty for bodies without damage).
    pub fn take_newly_failed(&mut self) -> Vec<usize> {
        match self {
            DamageState::None => Vec::new(),
            DamageState::Damaged(b) => {
                let mut out = Vec::new();
                for (k, s) in b.status.iter_mut().enumerate() {
                    if *s == FAILED_NOW {
                        *s = REMOVED;
                        out.push(k);
                    }
                }
                out
            }
        }
    }
}

/// A damage law as the particle loop sees it: the new D of local particle `k` from its
/// deformation gradient F^n, its effective stress σ_eff^n, its previous damage and history.
trait Law: Sync {
    fn advance(
        &self,
        k: usize,
        f: &Tensor3,
        effective: &Tensor3,
        damage: f64,
        history: &mut f64,
        dt: f64,
    ) -> f64;
}

/// Largest principal Hencky (logarithmic) strain ε_max = ln λ_max = ½ ln μ_max(FᵀF)
/// (numerics.md §9.1 `[C]`). Hencky, because the Jaumann-rate elastic law this body uses
/// integrates to σ = C : ln V for coaxial stretching, so in uniaxial tension σ_eff = E ε_max
/// exactly as in F 5.3; ln_1p keeps full precision at small strain.
#[inline]
pub(crate) fn max_principal_log_strain(f: &Tensor3) -> f64 {
    let c = f.transpose() * f;
    0.5 * (max_principal_value(&c) - 1.0).ln_1p()
}

impl Law for PeerlingsSoftening {
    /// κ ← max(κ, ε_max), D = D(κ) (numerics.md §9.1; F 5.4 with the history variable).
    #[inline]
    fn advance(&self, _: usize, f: &Tensor3, _: &Tensor3, _: f64, kappa: &mut f64, _: f64) -> f64 {
        *kappa = PeerlingsSoftening::update_history(*kappa, max_principal_log_strain(f));
        self.damage(*kappa)
    }
}

/// Grady–Kipp with everything but the point fixed for the body (numerics.md §9.2).
struct GradyKippBody<'a> {
    model: GradyKipp,
    flaws: &'a Flaws,
    youngs_modulus: f64,
    /// c_g = 0.4 c_l \[m/s\].
    crack_speed: f64,
    /// R_s = ½Δx \[m\].
    particle_radius: f64,
}

impl Law for GradyKippBody<'_> {
    /// ε_eff = σ1⁺/((1 − D)E) of the damaged stress = σ1⁺(σ_eff)/E (the spectral split scales
    /// the positive principal values by exactly 1 − D, so this form needs no division by
    /// 1 − D); n_act = #{ε_j ≤ ε_eff}; D^{1/3} grows by Δt n_act c_g/R_s up to the cap
    /// min(n_act/n_i, 1) (numerics.md §9.2, Benz & Asphaug 1995).
    #[inline]
    fn advance(
        &self,
        k: usize,
        _: &Tensor3,
        effective: &Tensor3,
        damage: f64,
        largest: &mut f64,
        dt: f64,
    ) -> f64 {
        let strain = max_principal_value(effective).max(0.0) / self.youngs_modulus;
        *largest = largest.max(strain);
        let mine = &self.flaws.thresholds[self.flaws.offsets[k]..self.flaws.offsets[k + 1]];
        let active = GradyKipp::active_flaws(mine, strain);
        self.model.advance_damage(
            damage,
            active,
            mine.len(),
            self.crack_speed,
            self.particle_radius,
            dt,
        )
    }
}

/// Updates σ, P, J, e and the damage state of one damaged elastic body (numerics.md §9).
/// `spacing` is the body's Δx (R_s = ½Δx of Grady–Kipp).
pub(crate) fn update_damaged_elastic<const D: usize, R: ReferenceJacobian + ?Sized>(
    material: &ElasticDamage,
    step: &ConstitutiveStep<R>,
    viscosity: Option<BulkViscosity>,
    spacing: f64,
    p: &mut Particles<D>,
    state: &mut DamageState,
) {
    let DamageState::Damaged(body) = state else {
        unreachable!("damaged elastic bodies always carry a damage state")
    };
    let elastic = &material.elastic;
    match (&material.damage, viscosity) {
        (DamageModel::Peerlings(law), None) => update(elastic, law, step, &NoViscosity, p, body),
        (DamageModel::Peerlings(law), Some(v)) => update(elastic, law, step, &v, p, body),
        (DamageModel::GradyKipp { model, .. }, v) => {
            let flaws = std::mem::take(&mut body.flaws);
            let law = GradyKippBody {
                model: *model,
                flaws: &flaws,
                youngs_modulus: elastic.youngs_modulus(),
                crack_speed: BENZ_ASPHAUG_CRACK_SPEED_RATIO * step.sound_speed0,
                particle_radius: 0.5 * spacing,
            };
            match v {
                None => update(elastic, &law, step, &NoViscosity, p, body),
                Some(v) => update(elastic, &law, step, &v, p, body),
            }
            body.flaws = flaws;
        }
    }
}

/// The per-particle loop: σ_eff^n = Jaumann update of σ_eff^{n−1} (R 5.82–5.86), D^n from the
/// law, σ^n = σ_eff − D Σ_{σi > 0} σi nᵢ⊗nᵢ (numerics.md §9.1), e += Δt σ^{n−½}:D/ρ^{n−½}
/// with the damaged stress (so the energy damage releases stays in e), P = σ cof F. A particle
/// reaching D = 1 fails: zero stress from now on (numerics.md §9.3).
fn update<const D: usize, L: Law, V: Viscosity, R: ReferenceJacobian + ?Sized>(
    elastic: &LinearElastic,
    law: &L,
    step: &ConstitutiveStep<R>,
    viscosity: &V,
    p: &mut Particles<D>,
    body: &mut DamagedBody,
) {
    let (c0, length, dt, rho0) = (
        step.sound_speed0,
        step.smoothing_length,
        step.dt,
        step.density0,
    );
    let r = step.range.clone();
    let f_all = &p.deformation_gradient[r.clone()];
    let f_dot_all = &p.deformation_rate[r.clone()];
    p.stress[r.clone()]
        .par_iter_mut()
        .zip(p.pk1[r.clone()].par_iter_mut())
        .zip(p.jacobian[r.clone()].par_iter_mut())
        .zip(p.internal_energy[r].par_iter_mut())
        .zip(body.effective.par_iter_mut())
        .zip(body.history.par_iter_mut())
        .zip(body.damage.par_iter_mut())
        .zip(body.status.par_iter_mut())
        .enumerate()
        .with_min_len(MIN_PARTICLES_PER_TASK)
        .for_each(
            |(k, (((((((sigma, pk1), jac), energy), effective), history), damage), status))| {
                if *status != INTACT {
                    // Failed: no stress, no bonds; only its mass and momentum remain (§9.3).
                    *sigma = Tensor3::zeros();
                    *pk1 = Tensor::<D>::zeros();
                    *jac = 1.0;
                    return;
                }
                let f = embed_with_identity(&f_all[k]);
                let f_dot = embed_with_zeros(&f_dot_all[k]);
                let (d, w, j_half) = midpoint_rates(&f, &f_dot, dt);
                *effective = elastic.jaumann_update(effective, &d, &w, dt);
                *damage = law.advance(k, &f, effective, *damage, history, dt);
                let sigma_new = if *damage >= 1.0 {
                    *status = FAILED_NOW;
                    *damage = 1.0;
                    Tensor3::zeros()
                } else {
                    degrade_tensile_part(effective, *damage)
                };
                // cof F relative to the reference gives P relative to it; J is the total one.
                let (cofactor, j_ref) = cofactor_and_determinant(&f);
                let j0 = step.reference_jacobian.at(k);
                let (j, j_half) = (j_ref * j0, j_half * j0);
                // Artificial pressure on the force-driving stress only (numerics.md §10.2). A
                // particle failing now leaves this step's force sums, so neither its stress nor
                // q enters its last energy increment (they would not pair with any force work).
                let q = if *status == FAILED_NOW {
                    0.0
                } else {
                    viscosity.pressure(d.trace(), rho0 / j, c0 * j.max(0.0).sqrt(), length)
                };
                if step.book_energy {
                    *energy += dt * j_half / rho0
                        * (0.5 * (*sigma + sigma_new) - Tensor3::identity() * q)
                            .component_mul(&d)
                            .sum();
                }
                *sigma = sigma_new;
                *jac = j;
                *pk1 = if j_ref != 0.0 && j_ref.is_finite() {
                    project(&((sigma_new - Tensor3::identity() * q) * cofactor))
                } else {
                    Tensor::<D>::from_element(f64::NAN)
                };
            },
        );
}
