//! Constitutive update of elastic–plastic (hydrocode) materials for one body: Jaumann-rate
//! elastic predictor of the deviator, pressure from the bulk modulus or an EOS, a return map,
//! optional adiabatic heating, optional softening damage. Monomorphised per (strength,
//! pressure, state, softening) combination, so the per-particle loop has no branch on the
//! model (numerics.md §8.1, §8.3–8.5, §8.9, §9.1).

use crate::damage::{softened_points, DamageState, Softening, Undamaged};
use crate::model::{
    BulkViscosity, ElasticPlastic, FailureModel, PressureModel, StrengthModel, Thermal,
};
use crate::particles::Particles;
use crate::step::{
    constitutive_view, ConstitutiveStep, NoViscosity, RateKinematics, ReferenceJacobian, Viscosity,
    MIN_PARTICLES_PER_TASK,
};
use rayon::prelude::*;
use tlsph_materials::damage::{stress_triaxiality, TRIAXIALITY_STRESS_FLOOR};
use tlsph_materials::{
    equivalent_strain_rate, EquationOfState, JohnsonCookStrength, LinearEos, MieGruneisen,
    PlasticReturn, PolynomialEos, VonMisesPlasticity,
};
use tlsph_math::{deviator, embed_with_identity, embed_with_zeros, Tensor3};

/// Per-particle plastic state of a body: only what its material needs.
#[derive(Debug, Clone)]
pub(crate) enum PlasticState {
    /// The body's material has no plastic state.
    None,
    /// Effective plastic strain ε̄p.
    Strain(Vec<[f64; 1]>),
    /// [ε̄p, temperature T].
    StrainTemperature(Vec<[f64; 2]>),
    /// [ε̄p, damage D, status] (status: 0 intact, 1 failed this step, 2 failed and removed).
    StrainDamage(Vec<[f64; 3]>),
    /// [ε̄p, T, D, status].
    StrainTemperatureDamage(Vec<[f64; 4]>),
}

impl PlasticState {
    /// State for `n` particles of a material.
    pub fn for_material(model: &crate::model::MaterialModel, n: usize) -> Self {
        match model {
            crate::model::MaterialModel::ElasticPlastic(m) => match (m.thermal, m.failure) {
                (Some(t), None) => {
                    PlasticState::StrainTemperature(vec![[0.0, t.room_temperature]; n])
                }
                (None, None) => PlasticState::Strain(vec![[0.0]; n]),
                (None, Some(_)) => PlasticState::StrainDamage(vec![[0.0; 3]; n]),
                (Some(t), Some(_)) => {
                    PlasticState::StrainTemperatureDamage(vec![
                        [0.0, t.room_temperature, 0.0, 0.0];
                        n
                    ])
                }
            },
            crate::model::MaterialModel::LinearElastic(_)
            | crate::model::MaterialModel::ElasticDamage(_) => PlasticState::None,
        }
    }

    /// Sets the effective plastic strain of local particle `k` (nothing for a body whose
    /// material has no plastic state).
    pub fn set_plastic_strain(&mut self, k: usize, plastic_strain: f64) {
        match self {
            PlasticState::None => {}
            PlasticState::Strain(v) => v[k][0] = plastic_strain,
            PlasticState::StrainTemperature(v) => v[k][0] = plastic_strain,
            PlasticState::StrainDamage(v) => v[k][0] = plastic_strain,
            PlasticState::StrainTemperatureDamage(v) => v[k][0] = plastic_strain,
        }
    }

    /// Sets the Johnson–Cook cumulative damage D = Σ Δε̄p/ε_f of local particle `k`
    /// (numerics.md §8.6; 0 ≤ D < 1, checked by the caller): the particle fails once the
    /// increments add the remaining 1 − D. Nothing for a body without a failure model.
    pub fn set_failure_damage(&mut self, k: usize, damage: f64) {
        match self {
            PlasticState::StrainDamage(v) => v[k][1] = damage,
            PlasticState::StrainTemperatureDamage(v) => v[k][2] = damage,
            _ => {}
        }
    }

    /// Effective plastic strain of local particle `k`, if the body has one.
    pub fn plastic_strain(&self, k: usize) -> Option<f64> {
        match self {
            PlasticState::None => None,
            PlasticState::Strain(v) => Some(v[k][0]),
            PlasticState::StrainTemperature(v) => Some(v[k][0]),
            PlasticState::StrainDamage(v) => Some(v[k][0]),
            PlasticState::StrainTemperatureDamage(v) => Some(v[k][0]),
        }
    }

    /// Damage of local particle `k`, if the body's material has a failure model (1 once failed
    /// by a criterion without damage).
    pub fn damage(&self, k: usize) -> Option<f64> {
        match self {
            PlasticState::StrainDamage(v) => Some(if v[k][2] > 0.0 { 1.0 } else { v[k][1] }),
            PlasticState::StrainTemperatureDamage(v) => {
                Some(if v[k][3] > 0.0 { 1.0 } else { v[k][2] })
            }
            _ => None,
        }
    }

    /// Marks the particles that failed in the last update as removed and returns their local
    /// indices (empty for bodies without a failure model).
    pub fn take_newly_failed(&mut self) -> Vec<usize> {
        fn take<const N: usize>(v: &mut [[f64; N]]) -> Vec<usize> {
            let mut out = Vec::new();
            for (k, point) in v.iter_mut().enumerate() {
                if point[N - 1] == 1.0 {
                    point[N - 1] = 2.0;
                    out.push(k);
                }
            }
            out
        }
        match self {
            PlasticState::StrainDamage(v) => take(v),
            PlasticState::StrainTemperatureDamage(v) => take(v),
            _ => Vec::new(),
        }
    }

    /// Marks local particle `k` as failed and removed outside a constitutive update (a particle
    /// left without neighbours); nothing for bodies without a failure model.
    pub fn mark_removed(&mut self, k: usize) {
        match self {
            PlasticState::StrainDamage(v) => v[k][2] = 2.0,
            PlasticState::StrainTemperatureDamage(v) => v[k][3] = 2.0,
            _ => {}
        }
    }

    /// Temperature of local particle `k`, if the body tracks one.
    pub fn temperature(&self, k: usize) -> Option<f64> {
        match self {
            PlasticState::StrainTemperature(v) => Some(v[k][1]),
            PlasticState::StrainTemperatureDamage(v) => Some(v[k][1]),
            _ => None,
        }
    }
}

/// Per-particle state a return map reads and updates.
trait PointState: Send + Sync {
    /// Whether the state carries damage and a failure status.
    const HAS_FAILURE: bool = false;
    fn plastic_strain(&self) -> f64;
    /// Failure status (0 intact, 1 failed this step, 2 removed).
    fn status(&self) -> f64 {
        0.0
    }
    /// Adds damage and returns the new value.
    fn add_damage(&mut self, _increment: f64) -> f64 {
        0.0
    }
    /// Marks the particle as failed this step.
    fn fail(&mut self) {}
    fn temperature(&self) -> Option<f64>;
    fn add_plastic_strain(&mut self, increment: f64);
    /// Adds plastic work per unit mass w (J/kg) as heat, if the state has a temperature.
    fn heat(&mut self, work_per_mass: f64, thermal: Option<&Thermal>);
}

/// The packed per-particle state [ε̄p, (T), (D, status)]: N = 1 + (heating) + 2·(failure), so
/// N says which parts exist and every test on it below is resolved at compile time.
impl<const N: usize> PointState for [f64; N] {
    const HAS_FAILURE: bool = N >= 3;
    #[inline]
    fn plastic_strain(&self) -> f64 {
        self[0]
    }
    #[inline]
    fn temperature(&self) -> Option<f64> {
        N.is_multiple_of(2).then(|| self[1])
    }
    #[inline]
    fn add_plastic_strain(&mut self, increment: f64) {
        self[0] += increment;
    }
    #[inline]
    fn heat(&mut self, work_per_mass: f64, thermal: Option<&Thermal>) {
        if let (true, Some(t)) = (N.is_multiple_of(2), thermal) {
            // Adiabatic: all plastic work becomes heat (numerics.md §8.5).
            self[1] += work_per_mass / t.specific_heat;
        }
    }
    #[inline]
    fn status(&self) -> f64 {
        if N >= 3 {
            self[N.saturating_sub(1)]
        } else {
            0.0
        }
    }
    #[inline]
    fn add_damage(&mut self, increment: f64) -> f64 {
        if N >= 3 {
            let d = N.saturating_sub(2);
            self[d] += increment;
            self[d]
        } else {
            0.0
        }
    }
    #[inline]
    fn fail(&mut self) {
        if N >= 3 {
            self[N.saturating_sub(1)] = 1.0;
        }
    }
}

/// What a failure criterion sees of the end-of-step state.
struct FailureInputs<'a> {
    stress: &'a Tensor3,
    pressure: f64,
    equivalent_stress: f64,
    plastic_strain_increment: f64,
    rate: f64,
    temperature: f64,
    /// σ̄ below this carries no Johnson–Cook damage.
    stress_floor: f64,
}

/// Evaluates the failure model after the return map; true when the particle fails now.
#[inline]
fn fails<T: PointState>(
    failure: &Option<FailureModel>,
    point: &mut T,
    x: &FailureInputs<'_>,
) -> bool {
    match failure {
        None => false,
        Some(FailureModel::MaxPlasticStrain(m)) => m.fails(point.plastic_strain()),
        Some(FailureModel::MaxPrincipalStress(m)) => m.fails(x.stress),
        Some(FailureModel::JohnsonCook {
            model,
            reference_strain_rate,
            room_temperature,
            melt_temperature,
        }) => {
            // Skip while σ̄ is negligible: σ* is meaningless there (numerics.md §8.6 guard).
            let Some(triaxiality) =
                stress_triaxiality(x.pressure, x.equivalent_stress, x.stress_floor)
            else {
                return false;
            };
            let homologous =
                (x.temperature - room_temperature) / (melt_temperature - room_temperature);
            let increment = model.damage_increment(
                x.plastic_strain_increment,
                triaxiality,
                x.rate / reference_strain_rate,
                homologous,
            );
            point.add_damage(increment) >= 1.0
        }
    }
}

/// A deviatoric return map with everything but the point state fixed for the body.
trait Strength: Sync {
    fn return_map(
        &self,
        trial: &Tensor3,
        shear: f64,
        ep: f64,
        rate: f64,
        temperature: f64,
    ) -> PlasticReturn;
}

impl Strength for VonMisesPlasticity {
    #[inline]
    fn return_map(&self, trial: &Tensor3, shear: f64, ep: f64, _: f64, _: f64) -> PlasticReturn {
        VonMisesPlasticity::return_map(self, trial, shear, ep)
    }
}

struct JohnsonCook {
    model: JohnsonCookStrength,
    iterate: bool,
}

impl Strength for JohnsonCook {
    #[inline]
    fn return_map(
        &self,
        trial: &Tensor3,
        shear: f64,
        ep: f64,
        rate: f64,
        temperature: f64,
    ) -> PlasticReturn {
        self.model
            .return_map(trial, shear, ep, rate, temperature, self.iterate)
    }
}

/// Pressure at the end of the step.
trait Pressure: Sync {
    /// `p_old` at the start, `trace_d` = tr D at n−½, `j` = det F^n, `energy_v` = ρ0 e.
    fn pressure(&self, p_old: f64, trace_d: f64, dt: f64, j: f64, energy_v: f64) -> f64;
}

/// ṗ = −K tr D.
struct Hypoelastic {
    bulk: f64,
}

impl Pressure for Hypoelastic {
    #[inline]
    fn pressure(&self, p_old: f64, trace_d: f64, dt: f64, _: f64, _: f64) -> f64 {
        p_old - self.bulk * trace_d * dt
    }
}

macro_rules! eos_pressure {
    ($t:ty) => {
        impl Pressure for $t {
            #[inline]
            fn pressure(&self, _: f64, _: f64, _: f64, j: f64, energy_v: f64) -> f64 {
                // μ = ρ/ρ0 − 1 = 1/J − 1 (R 6.23).
                <$t>::pressure(self, 1.0 / j - 1.0, energy_v)
            }
        }
    };
}
eos_pressure!(LinearEos);
eos_pressure!(PolynomialEos);
eos_pressure!(MieGruneisen);

/// The per-particle states of one elastic–plastic body: its plastic state, and its damage
/// state with the body's spacing Δx (Grady–Kipp's R_s = ½Δx).
pub(crate) struct PlasticBody<'a> {
    /// ε̄p, T, failure.
    pub plastic: &'a mut PlasticState,
    /// Softening damage (`DamageState::None` without a `damage` law).
    pub damage: &'a mut DamageState,
    /// Δx of the body.
    pub spacing: f64,
}

/// Updates σ, P, J, e and the plastic and damage states of one body made of `material`.
pub(crate) fn update_elastic_plastic<const D: usize, R: ReferenceJacobian + ?Sized>(
    material: &ElasticPlastic,
    step: &ConstitutiveStep<R>,
    viscosity: Option<BulkViscosity>,
    p: &mut Particles<D>,
    state: PlasticBody<'_>,
) {
    let v = viscosity;
    match &material.pressure {
        PressureModel::Hypoelastic => {
            let law = Hypoelastic {
                bulk: material.elastic.bulk_modulus(),
            };
            with_strength(material, &law, step, v, p, state)
        }
        PressureModel::Eos(EquationOfState::Linear(e)) => {
            with_strength(material, e, step, v, p, state)
        }
        PressureModel::Eos(EquationOfState::Polynomial(e)) => {
            with_strength(material, e, step, v, p, state)
        }
        PressureModel::Eos(EquationOfState::MieGruneisen(e)) => {
            with_strength(material, e, step, v, p, state)
        }
    }
}

fn with_strength<const D: usize, P: Pressure, R: ReferenceJacobian + ?Sized>(
    material: &ElasticPlastic,
    pressure: &P,
    step: &ConstitutiveStep<R>,
    viscosity: Option<BulkViscosity>,
    p: &mut Particles<D>,
    state: PlasticBody<'_>,
) {
    match material.strength {
        StrengthModel::VonMises(vm) => {
            with_viscosity(material, pressure, &vm, step, viscosity, p, state)
        }
        StrengthModel::JohnsonCook { model, iterate } => with_viscosity(
            material,
            pressure,
            &JohnsonCook { model, iterate },
            step,
            viscosity,
            p,
            state,
        ),
    }
}

#[allow(clippy::too_many_arguments)]
fn with_viscosity<const D: usize, P: Pressure, S: Strength, R: ReferenceJacobian + ?Sized>(
    material: &ElasticPlastic,
    pressure: &P,
    strength: &S,
    step: &ConstitutiveStep<R>,
    viscosity: Option<BulkViscosity>,
    p: &mut Particles<D>,
    state: PlasticBody<'_>,
) {
    match viscosity {
        None => with_state(material, pressure, strength, step, &NoViscosity, p, state),
        Some(v) => with_state(material, pressure, strength, step, &v, p, state),
    }
}

/// Picks the loop for the body's point state and softening. With both a `damage` law and a
/// `failure` criterion the particle fails by whichever comes first; the criterion reads the
/// effective (undamaged) state that drives the plastic flow.
fn with_state<
    const D: usize,
    P: Pressure,
    S: Strength,
    V: Viscosity,
    R: ReferenceJacobian + ?Sized,
>(
    material: &ElasticPlastic,
    pressure: &P,
    strength: &S,
    step: &ConstitutiveStep<R>,
    viscosity: &V,
    p: &mut Particles<D>,
    state: PlasticBody<'_>,
) {
    let laws = Laws {
        material,
        pressure,
        strength,
        step,
        viscosity,
    };
    match (state.damage, &material.damage) {
        (DamageState::Damaged(body), Some(model)) => {
            let e = material.elastic.youngs_modulus();
            let (softening, points) =
                softened_points(model, body, e, step.sound_speed0, state.spacing);
            with_points(&laws, &softening, p, state.plastic, points)
        }
        _ => {
            // Zero-sized: no allocation, just the count the loop's zip needs.
            let mut none = vec![(); step.range.len()];
            with_points(&laws, &Undamaged, p, state.plastic, &mut none)
        }
    }
}

/// Picks the loop for the body's packed plastic point state, with the softening fixed.
fn with_points<
    const D: usize,
    P: Pressure,
    S: Strength,
    V: Viscosity,
    X: Softening,
    R: ReferenceJacobian + ?Sized,
>(
    laws: &Laws<'_, P, S, V, R>,
    softening: &X,
    p: &mut Particles<D>,
    plastic: &mut PlasticState,
    soft: &mut [X::Point],
) {
    match plastic {
        PlasticState::Strain(v) => update(laws, softening, p, v, soft),
        PlasticState::StrainTemperature(v) => update(laws, softening, p, v, soft),
        PlasticState::StrainDamage(v) => update(laws, softening, p, v, soft),
        PlasticState::StrainTemperatureDamage(v) => update(laws, softening, p, v, soft),
        PlasticState::None => unreachable!("an elastic-plastic body carries a plastic state"),
    }
}

/// The body's laws, fixed for one update.
struct Laws<'a, P, S, V, R: ReferenceJacobian + ?Sized> {
    material: &'a ElasticPlastic,
    pressure: &'a P,
    strength: &'a S,
    step: &'a ConstitutiveStep<'a, R>,
    viscosity: &'a V,
}

/// The per-particle loop (R 5.82–5.86 with a return map):
/// s* = Q s Qᵀ + 2G Δt D′ (Hughes–Winget Q), p from the pressure law (then the cutoff),
/// s = return_map(s*), σ_eff = −p I + s, ε̄p += Δε̄p, T += σ̄Δε̄p/(ρ c_v), σ = the softened
/// σ_eff (numerics.md §9.1; σ_eff itself without damage), e += Δt σ^{n−½}:D/ρ^{n−½}.
/// The update starts from σ_eff^{n−1}, so damage never feeds back into the plastic flow.
fn update<
    const D: usize,
    P: Pressure,
    S: Strength,
    V: Viscosity,
    T: PointState,
    X: Softening,
    R: ReferenceJacobian + ?Sized,
>(
    laws: &Laws<'_, P, S, V, R>,
    softening: &X,
    p: &mut Particles<D>,
    points: &mut [T],
    soft: &mut [X::Point],
) {
    let Laws {
        material,
        pressure: pressure_law,
        strength,
        step,
        viscosity,
    } = *laws;
    let dt = step.dt;
    let rho0 = step.density0;
    let shear = material.elastic.shear_modulus();
    let min_pressure = material.min_pressure.unwrap_or(f64::NEG_INFINITY);
    // σ̄ below 1e-9 of the initial yield stress carries no damage (numerics.md §8.6 guard).
    let stress_floor = TRIAXIALITY_STRESS_FLOOR
        * match material.strength {
            StrengthModel::VonMises(vm) => vm.initial_yield_stress(),
            StrengthModel::JohnsonCook { model, .. } => model.parameters().a,
        };
    let thermal = material.thermal.as_ref();
    let room_temperature = thermal.map_or(0.0, |t| t.room_temperature);
    let (f_all, f_dot_all, slots) = constitutive_view(p, step.range.clone());
    slots
        .zip(points.par_iter_mut())
        .zip(soft.par_iter_mut())
        .enumerate()
        .with_min_len(MIN_PARTICLES_PER_TASK)
        .for_each(|(k, ((slots, point), soft))| {
            if (T::HAS_FAILURE && point.status() > 0.0) || X::failed_before(soft) {
                slots.clear_failed();
                return;
            }
            let f = embed_with_identity(&f_all[k]);
            let f_dot = embed_with_zeros(&f_dot_all[k]);
            let at = RateKinematics::new(&f, &f_dot, dt, step.reference_jacobian.at(k));
            let (d, j) = (&at.d, at.j);
            // Elastic predictor of the deviator with an exactly orthogonal rotation.
            let start = X::start(soft, slots.stress);
            let s_old = deviator(&start);
            let p_old = -start.trace() / 3.0;
            let half = at.w * (0.5 * dt);
            let rotation = match (Tensor3::identity() - half).try_inverse() {
                Some(inv) => inv * (Tensor3::identity() + half),
                None => Tensor3::identity(),
            };
            let trial = rotation * s_old * rotation.transpose() + deviator(d) * (2.0 * shear * dt);
            let energy_v = rho0 * *slots.internal_energy;
            // The EOS is a state function of J: it reads the density carried across bond
            // rebuilds (a neighbour's removal changes the estimate det F, not the volume).
            let j_eos = j * step.jacobian_carry.map_or(1.0, |c| c[k]);
            let pressure = pressure_law
                .pressure(p_old, d.trace(), dt, j_eos, energy_v)
                .max(min_pressure);
            let temperature = point.temperature().unwrap_or(room_temperature);
            let rate = equivalent_strain_rate(d);
            let ret = strength.return_map(&trial, shear, point.plastic_strain(), rate, temperature);
            let mut sigma_new = ret.deviator - Tensor3::identity() * pressure;
            let mut q = step.artificial_pressure(viscosity, &at);
            // Plastic work per unit mass at the end-of-step flow stress: σ̄ Δε̄p / ρ.
            let flow = (1.5 * ret.deviator.component_mul(&ret.deviator).sum()).sqrt();
            point.heat(flow * ret.plastic_strain_increment * j / rho0, thermal);
            point.add_plastic_strain(ret.plastic_strain_increment);
            if T::HAS_FAILURE
                && fails(
                    &material.failure,
                    point,
                    &FailureInputs {
                        stress: &sigma_new,
                        pressure,
                        equivalent_stress: flow,
                        plastic_strain_increment: ret.plastic_strain_increment,
                        rate,
                        temperature,
                        stress_floor,
                    },
                )
            {
                // A particle failing now leaves this step's force sums: the forces at t^n see
                // neither its stress nor its artificial pressure, so its last energy increment
                // must not either (the half of σ^n in the increment pairs with the work of the
                // forces at t^n).
                // A softening law is then not advanced: one mechanism fails the particle, so
                // it is counted and removed once.
                point.fail();
                sigma_new = Tensor3::zeros();
                q = 0.0;
            } else {
                sigma_new = softening.soften(k, soft, &f, sigma_new, dt);
                if X::fails_now(soft) {
                    // As above: the particle leaves this step's force sums.
                    q = 0.0;
                }
            }
            at.store(step, sigma_new, q, slots);
        });
}
