//! Softening damage (numerics.md §8.1, §9.1–9.3): a body integrates its undamaged
//! ("effective") Cauchy stress as if nothing were damaged, a damage law turns the kinematics
//! into D, and the stress the body feels is the effective stress with its tensile principal
//! part scaled by (1 − D). D = 1 marks the particle failed; the simulation then takes it out of
//! every sum (`Bonds::remove_failed`).
//!
//! Two materials soften: damaged linear-elastic bodies, whose loop is here
//! ([`update_damaged_elastic`]), and elastic–plastic bodies with a `damage` law, whose loop in
//! `plasticity.rs` takes a [`Softening`] type parameter: [`Undamaged`] (no state, no work) or
//! [`Softened`]. Bodies without a damage model carry none of this state ([`DamageState::None`]).

use crate::model::{BulkViscosity, DamageModel, ElasticDamage, MaterialModel};
use crate::particles::Particles;
use crate::step::{
    constitutive_view, ConstitutiveStep, NoViscosity, RateKinematics, ReferenceJacobian, Viscosity,
    MIN_PARTICLES_PER_TASK,
};
use rayon::prelude::*;
use tlsph_materials::damage::{degrade_tensile_part, BENZ_ASPHAUG_CRACK_SPEED_RATIO};
use tlsph_materials::{max_principal_value, GradyKipp, LinearElastic, PeerlingsSoftening};
use tlsph_math::{embed_with_identity, embed_with_zeros, Tensor3};

/// Failure status values stored in a particle's state (as in `plasticity.rs`).
const INTACT: u8 = 0;
const FAILED_NOW: u8 = 1;
const REMOVED: u8 = 2;

/// Per-particle damage state of one body; `None` unless its material declares damage.
#[derive(Debug, Clone)]
pub(crate) enum DamageState {
    /// The body's material has no damage law: nothing stored, nothing run.
    None,
    /// A damaged (softening) body.
    Damaged(Box<DamagedBody>),
}

/// State of a softening body.
#[derive(Debug, Clone)]
pub(crate) struct DamagedBody {
    /// One state per particle.
    points: Vec<DamagePoint>,
    /// Grady–Kipp flaws of the body (empty for Peerlings).
    flaws: Flaws,
}

/// Damage state of one particle.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DamagePoint {
    /// Undamaged Cauchy stress σ_eff (numerics.md §8.1, §9.1).
    effective: Tensor3,
    /// History variable: κ = max ε_max (Peerlings) or the largest ε_eff reached (Grady–Kipp).
    history: f64,
    /// Damage D ∈ [0, 1].
    damage: f64,
    /// 0 intact, 1 failed in the last update, 2 failed and removed.
    status: u8,
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
    /// material has a softening damage law). Grady–Kipp flaws are seeded here, once per body,
    /// from the body's total reference measure Σ V0 and the declared seed (numerics.md §9.2).
    pub fn for_material(model: &MaterialModel, volumes0: &[f64]) -> Self {
        let Some(damage) = model.softening_damage() else {
            return DamageState::None;
        };
        let n = volumes0.len();
        let flaws = match *damage {
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
        let intact = DamagePoint {
            effective: Tensor3::zeros(),
            history: 0.0,
            damage: 0.0,
            status: INTACT,
        };
        DamageState::Damaged(Box::new(DamagedBody {
            points: vec![intact; n],
            flaws,
        }))
    }

    /// Damage of local particle `k` (1 once failed), if the body has a damage law.
    pub fn damage(&self, k: usize) -> Option<f64> {
        match self {
            DamageState::None => None,
            DamageState::Damaged(b) => {
                let point = &b.points[k];
                Some(if point.status != INTACT {
                    1.0
                } else {
                    point.damage
                })
            }
        }
    }

    /// Starts local particle `k` with damage `damage` (0 ≤ D < 1, checked by the caller) of
    /// the law `model`: Peerlings also gets the history κ at which its law reaches D
    /// ([`PeerlingsSoftening::history_for_damage`]), so it reloads on the secant (1 − D)E and
    /// softens further only past κ; Grady–Kipp keeps D, which its growth law never lowers.
    /// D = 0 leaves the particle as it is. Nothing for bodies without damage.
    pub fn set_initial_damage(&mut self, model: &DamageModel, k: usize, damage: f64) {
        let DamageState::Damaged(b) = self else {
            return;
        };
        if damage == 0.0 {
            return;
        }
        let point = &mut b.points[k];
        point.damage = damage;
        if let DamageModel::Peerlings(law) = model {
            point.history = law.history_for_damage(damage).unwrap_or(point.history);
        }
    }

    /// Marks local particle `k` as failed and removed outside a constitutive update (a particle
    /// left without neighbours); nothing for bodies without damage.
    pub fn mark_removed(&mut self, k: usize) {
        if let DamageState::Damaged(b) = self {
            b.points[k].status = REMOVED;
            b.points[k].damage = 1.0;
        }
    }

    /// Marks the particles that failed in the last update as removed and returns their local
    /// indices (empty for bodies without damage).
    pub fn take_newly_failed(&mut self) -> Vec<usize> {
        match self {
            DamageState::None => Vec::new(),
            DamageState::Damaged(b) => {
                let mut out = Vec::new();
                for (k, point) in b.points.iter_mut().enumerate() {
                    if point.status == FAILED_NOW {
                        point.status = REMOVED;
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
pub(crate) trait Law: Sync {
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
pub(crate) struct GradyKippBody<'a> {
    model: GradyKipp,
    flaws: &'a Flaws,
    youngs_modulus: f64,
    /// c_g = 0.4 c_l \[m/s\].
    crack_speed: f64,
    /// R_s = ½Δx \[m\].
    particle_radius: f64,
}

impl<'a> GradyKippBody<'a> {
    /// The law for a body of Young's modulus `youngs_modulus`, reference sound speed
    /// `sound_speed0` and spacing `spacing` (c_g = 0.4 c_l, R_s = ½Δx).
    fn new(
        model: GradyKipp,
        flaws: &'a Flaws,
        youngs_modulus: f64,
        sound_speed0: f64,
        spacing: f64,
    ) -> Self {
        GradyKippBody {
            model,
            flaws,
            youngs_modulus,
            crack_speed: BENZ_ASPHAUG_CRACK_SPEED_RATIO * sound_speed0,
            particle_radius: 0.5 * spacing,
        }
    }
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

/// Either law behind one type, for the elastic–plastic loop: one predictable branch per
/// damaged particle instead of a second copy of that (already many-fold monomorphised) loop.
pub(crate) enum AnyLaw<'a> {
    /// Peerlings linear softening.
    Peerlings(PeerlingsSoftening),
    /// Grady–Kipp flaws.
    GradyKipp(GradyKippBody<'a>),
}

impl Law for AnyLaw<'_> {
    #[inline]
    fn advance(
        &self,
        k: usize,
        f: &Tensor3,
        effective: &Tensor3,
        damage: f64,
        history: &mut f64,
        dt: f64,
    ) -> f64 {
        match self {
            AnyLaw::Peerlings(law) => law.advance(k, f, effective, damage, history, dt),
            AnyLaw::GradyKipp(law) => law.advance(k, f, effective, damage, history, dt),
        }
    }
}

/// What a constitutive loop does with the undamaged stress it has just integrated
/// (numerics.md §9.1): keep it ([`Undamaged`]) or soften it by a damage law ([`Softened`]).
/// A type parameter of the loop, so an undamaged body's loop has neither state nor branch for
/// damage.
pub(crate) trait Softening: Sync {
    /// Per-particle state: `()` when undamaged.
    type Point: Send;
    /// The undamaged stress at the start of the step: σ_eff^{n−1}, or the stored σ^{n−1}.
    fn start(point: &Self::Point, stress: &Tensor3) -> Tensor3;
    /// Whether the particle failed in an earlier update (it carries no stress any more).
    fn failed_before(point: &Self::Point) -> bool;
    /// Whether the particle failed in this update.
    fn fails_now(point: &Self::Point) -> bool;
    /// Takes the new undamaged stress σ_eff^n of local particle `k` (deformation gradient
    /// `f`) and returns the stress the body feels: σ_eff − D Σ_{σi > 0} σi nᵢ⊗nᵢ, or zero when
    /// D reaches 1 (the point is then flagged as failed now, numerics.md §9.1, §9.3).
    fn soften(
        &self,
        k: usize,
        point: &mut Self::Point,
        f: &Tensor3,
        effective: Tensor3,
        dt: f64,
    ) -> Tensor3;
}

/// No damage: the integrated stress is the stress.
pub(crate) struct Undamaged;

impl Softening for Undamaged {
    type Point = ();
    #[inline]
    fn start(_: &(), stress: &Tensor3) -> Tensor3 {
        *stress
    }
    #[inline]
    fn failed_before(_: &()) -> bool {
        false
    }
    #[inline]
    fn fails_now(_: &()) -> bool {
        false
    }
    #[inline]
    fn soften(&self, _: usize, _: &mut (), _: &Tensor3, effective: Tensor3, _: f64) -> Tensor3 {
        effective
    }
}

/// Softening by the damage law `L`.
pub(crate) struct Softened<L: Law> {
    law: L,
}

impl<L: Law> Softening for Softened<L> {
    type Point = DamagePoint;
    #[inline]
    fn start(point: &DamagePoint, _: &Tensor3) -> Tensor3 {
        point.effective
    }
    #[inline]
    fn failed_before(point: &DamagePoint) -> bool {
        point.status != INTACT
    }
    #[inline]
    fn fails_now(point: &DamagePoint) -> bool {
        point.status == FAILED_NOW
    }
    #[inline]
    fn soften(
        &self,
        k: usize,
        point: &mut DamagePoint,
        f: &Tensor3,
        effective: Tensor3,
        dt: f64,
    ) -> Tensor3 {
        point.effective = effective;
        point.damage =
            self.law
                .advance(k, f, &point.effective, point.damage, &mut point.history, dt);
        if point.damage >= 1.0 {
            point.status = FAILED_NOW;
            point.damage = 1.0;
            Tensor3::zeros()
        } else {
            degrade_tensile_part(&point.effective, point.damage)
        }
    }
}

/// The softening of a damaged elastic–plastic body and its particles' states, for the loop in
/// `plasticity.rs`. `youngs_modulus`, `sound_speed0` and `spacing` are the body's E, c_0 and
/// Δx (Grady–Kipp's ε_eff = σ1⁺/E, c_g and R_s).
pub(crate) fn softened_points<'a>(
    model: &DamageModel,
    body: &'a mut DamagedBody,
    youngs_modulus: f64,
    sound_speed0: f64,
    spacing: f64,
) -> (Softened<AnyLaw<'a>>, &'a mut [DamagePoint]) {
    let DamagedBody { points, flaws } = body;
    let law = match *model {
        DamageModel::Peerlings(law) => AnyLaw::Peerlings(law),
        DamageModel::GradyKipp { model, .. } => AnyLaw::GradyKipp(GradyKippBody::new(
            model,
            flaws,
            youngs_modulus,
            sound_speed0,
            spacing,
        )),
    };
    (Softened { law }, points)
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
    let DamagedBody { points, flaws } = &mut **body;
    let elastic = &material.elastic;
    match (&material.damage, viscosity) {
        (DamageModel::Peerlings(law), None) => update(
            elastic,
            &Softened { law: *law },
            step,
            &NoViscosity,
            p,
            points,
        ),
        (DamageModel::Peerlings(law), Some(v)) => {
            update(elastic, &Softened { law: *law }, step, &v, p, points)
        }
        (DamageModel::GradyKipp { model, .. }, v) => {
            let law = GradyKippBody::new(
                *model,
                flaws,
                elastic.youngs_modulus(),
                step.sound_speed0,
                spacing,
            );
            let softening = Softened { law };
            match v {
                None => update(elastic, &softening, step, &NoViscosity, p, points),
                Some(v) => update(elastic, &softening, step, &v, p, points),
            }
        }
    }
}

/// The per-particle loop: σ_eff^n = Jaumann update of σ_eff^{n−1} (R 5.82–5.86), then the
/// softening (D^n from the law, σ^n = σ_eff − D Σ_{σi > 0} σi nᵢ⊗nᵢ, numerics.md §9.1),
/// e += Δt σ^{n−½}:D/ρ^{n−½} with the damaged stress (so the energy damage releases stays in
/// e), P = σ cof F. A particle reaching D = 1 fails: zero stress from now on (numerics.md §9.3).
fn update<const D: usize, L: Law, V: Viscosity, R: ReferenceJacobian + ?Sized>(
    elastic: &LinearElastic,
    softening: &Softened<L>,
    step: &ConstitutiveStep<R>,
    viscosity: &V,
    p: &mut Particles<D>,
    points: &mut [DamagePoint],
) {
    let dt = step.dt;
    let (f_all, f_dot_all, slots) = constitutive_view(p, step.range.clone());
    slots
        .zip(points.par_iter_mut())
        .enumerate()
        .with_min_len(MIN_PARTICLES_PER_TASK)
        .for_each(|(k, (slots, point))| {
            if point.status != INTACT {
                slots.clear_failed();
                return;
            }
            let f = embed_with_identity(&f_all[k]);
            let f_dot = embed_with_zeros(&f_dot_all[k]);
            let at = RateKinematics::new(&f, &f_dot, dt, step.reference_jacobian.at(k));
            let effective = elastic.jaumann_update(&point.effective, &at.d, &at.w, dt);
            let stress = softening.soften(k, point, &f, effective, dt);
            // A particle failing now leaves this step's force sums, so neither its stress nor
            // q enters its last energy increment (they would not pair with any force work).
            let q = if point.status == FAILED_NOW {
                0.0
            } else {
                step.artificial_pressure(viscosity, &at)
            };
            at.store(step, stress, q, slots);
        });
}
