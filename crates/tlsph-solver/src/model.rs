//! Plain descriptions of a simulation (what to simulate). Built by `tlsph-io` from scene files
//! or directly in code; consumed once by `Simulation::new`.

pub use tlsph_contact::FrictionCoefficients;
use tlsph_kernels::KernelKind;
use tlsph_materials::{
    EquationOfState, GradyKipp, JohnsonCookFailure, JohnsonCookStrength, LinearElastic,
    MaxPlasticStrainFailure, MaxStressFailure, PeerlingsSoftening, VonMisesPlasticity,
};
use tlsph_math::{Tensor, Vector, Vector3};

/// How kernel gradients are formed in the reference configuration (numerics.md §5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Formulation {
    /// Raw reference-kernel gradients G_IJ = ∇W(X_I − X_J) (Reveles Algorithms 1 and 2).
    TotalLagrangian,
    /// Shepard quotient-rule gradient × Randles–Libersky correction B_I (Algorithm 3,
    /// numerics.md §6.1–6.2): F is exact for affine displacement fields, boundaries included.
    TotalLagrangianCorrected,
    /// Conventional ("Eulerian kernel", updated-Lagrangian) SPH: kernel in the current
    /// configuration, neighbours searched as particles move, continuity density, bodies of the
    /// same material interacting through the kernel (numerics.md §3). Suffers the tensile
    /// instability (R ch. 3); offered for comparison and very large deformation.
    UpdatedLagrangian,
}

impl Formulation {
    /// Name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::TotalLagrangian => "total-lagrangian",
            Formulation::TotalLagrangianCorrected => "total-lagrangian-corrected",
            Formulation::UpdatedLagrangian => "updated-lagrangian",
        }
    }
}

/// Which stress measure is integrated (numerics.md §5 step 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StressUpdate {
    /// Cauchy stress with the Jaumann rate, σ̇ = C:D + Wσ − σW, converted with P = Jσ F⁻ᵀ
    /// (Algorithms 2 and 3, R 5.26–5.32).
    JaumannRate,
    /// Second Piola–Kirchhoff stress from the Green–Lagrange strain, S = C:E, P = F S
    /// (Algorithm 1, R 5.9–5.13). Exactly objective.
    GreenLagrange,
}

impl StressUpdate {
    /// Name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            StressUpdate::JaumannRate => "jaumann-rate",
            StressUpdate::GreenLagrange => "green-lagrange",
        }
    }
}

/// Global settings of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationConfig {
    /// Gradient formulation.
    pub formulation: Formulation,
    /// Stress measure integrated in time.
    pub stress_update: StressUpdate,
    /// Smoothing kernel.
    pub kernel: KernelKind,
    /// h = smoothing_factor × particle spacing of each body.
    pub smoothing_factor: f64,
    /// Courant number C in Δt = C min h/(c + |v|) (R 5.69–5.70).
    pub cfl: f64,
    /// Simulated time at which the run ends \[s\].
    pub end_time: f64,
}

/// Constitutive model of a material (closed set; matched once per body per step).
// One value per material, never per particle: the size difference between variants is
// irrelevant, and boxing would only add an indirection.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MaterialModel {
    /// Isotropic linear elasticity (R 5.73–5.75).
    LinearElastic(LinearElastic),
    /// Hypoelastic–plastic hydrocode material: Jaumann-rate elastic deviator with a von Mises
    /// or Johnson–Cook return map, pressure from the bulk modulus or an equation of state
    /// (numerics.md §8.3–8.5, §8.7–8.9).
    ElasticPlastic(ElasticPlastic),
    /// Linear elasticity (Jaumann rate) with a softening damage law (numerics.md §9.1–9.3):
    /// the tensile principal part of the elastic stress is scaled by (1 − D); D = 1 fails the
    /// particle. A separate variant, so undamaged elastic bodies keep their own loop.
    ElasticDamage(ElasticDamage),
}

/// Softening damage law of an [`ElasticDamage`] material, or of an [`ElasticPlastic`] one
/// (numerics.md §9.1–9.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DamageModel {
    /// Peerlings linear softening D(κ), κ = max over history of the largest principal Hencky
    /// strain ln λ_max (numerics.md §9.1; F 5.3–5.4).
    Peerlings(PeerlingsSoftening),
    /// Grady–Kipp flaws with Benz–Asphaug growth (numerics.md §9.2; F §5.3.2).
    GradyKipp {
        /// Weibull m and k (k per unit body measure in the model's length unit).
        model: GradyKipp,
        /// Seed of the SplitMix64 generator that assigns flaws to particles (one draw
        /// sequence per body, seeded identically).
        seed: u64,
    },
}

/// A linear-elastic material that softens by damage (numerics.md §8.1 + §9.1–9.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticDamage {
    /// Elastic constants of the undamaged material.
    pub elastic: LinearElastic,
    /// Damage law.
    pub damage: DamageModel,
}

/// Deviatoric strength law (numerics.md §8.4–8.5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StrengthModel {
    /// Von Mises with linear isotropic hardening (perfectly plastic when E_p = 0).
    VonMises(VonMisesPlasticity),
    /// Johnson–Cook flow stress; `iterate` selects the "accurate" consistency iteration.
    JohnsonCook {
        /// The flow-stress law.
        model: JohnsonCookStrength,
        /// Solve the consistency condition (deck IT = 1) instead of one radial return.
        iterate: bool,
    },
}

impl StrengthModel {
    /// Yield stress of the virgin material, σ_y(ε̄p = 0) \[Pa\]: σ_y0 (von Mises) or A
    /// (Johnson–Cook at room temperature and a quasi-static rate, numerics.md §8.5). A starting
    /// stress with a larger von Mises stress lies outside the yield surface.
    pub fn initial_yield_stress(&self) -> f64 {
        match self {
            StrengthModel::VonMises(m) => m.initial_yield_stress(),
            StrengthModel::JohnsonCook { model, .. } => model.parameters().a,
        }
    }

    /// Yield stress σ_y(ε̄p) \[Pa\] at room temperature and a quasi-static rate: σ_y0 + E_p ε̄p
    /// (von Mises, numerics.md §8.4) or A + B ε̄p^n (Johnson–Cook, §8.5). It does not fall as
    /// ε̄p grows (E_p, B ≥ 0), so a work-hardened particle admits at least the stresses a
    /// virgin one does.
    pub fn quasi_static_yield_stress(&self, plastic_strain: f64) -> f64 {
        match self {
            StrengthModel::VonMises(m) => m.yield_stress(plastic_strain),
            StrengthModel::JohnsonCook { model, .. } => model.hardening(plastic_strain),
        }
    }
}

/// How the pressure of an elastic–plastic material is obtained (numerics.md §8.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PressureModel {
    /// Hypoelastic: ṗ = −K tr D with the bulk modulus of the elastic constants.
    Hypoelastic,
    /// An equation of state p(μ, E_v), μ = 1/J − 1, E_v = ρ0 e.
    Eos(EquationOfState),
}

/// Adiabatic heating by plastic work (numerics.md §8.5): ΔT = σ̄ Δε̄p / (ρ c_v).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thermal {
    /// Specific heat c_v \[J/(kg K)\].
    pub specific_heat: f64,
    /// Initial (room) temperature \[K\].
    pub room_temperature: f64,
}

/// When a particle of an elastic–plastic material fails (numerics.md §8.6, §9.3). A failed
/// particle carries no stress, leaves every kernel sum (its neighbours' gradients are rebuilt
/// without it) and moves on as a free point mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FailureModel {
    /// Johnson–Cook cumulative damage D = Σ Δε̄p/ε_f(σ*, ε̇*, T*), failure at D ≥ 1.
    JohnsonCook {
        /// D1 … D5.
        model: JohnsonCookFailure,
        /// ε̇0 of ε̇* = ε̇̄/ε̇0 \[1/s\].
        reference_strain_rate: f64,
        /// T_room of T* \[K\].
        room_temperature: f64,
        /// T_melt of T* \[K\].
        melt_temperature: f64,
    },
    /// Failure when ε̄p reaches a limit.
    MaxPlasticStrain(MaxPlasticStrainFailure),
    /// Failure when the largest principal stress reaches a limit (spall type 2).
    MaxPrincipalStress(MaxStressFailure),
}

/// An elastic–plastic hydrocode material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticPlastic {
    /// Elastic constants (G for the deviator, K for the hypoelastic pressure).
    pub elastic: LinearElastic,
    /// Deviatoric strength.
    pub strength: StrengthModel,
    /// Pressure law.
    pub pressure: PressureModel,
    /// Pressure cutoff in tension: p ← max(p, p_min) (numerics.md §8.9 type 1) \[Pa\].
    pub min_pressure: Option<f64>,
    /// Temperature from plastic work; absent: the temperature stays at the room value.
    pub thermal: Option<Thermal>,
    /// Failure criterion; absent: particles never fail.
    pub failure: Option<FailureModel>,
    /// Softening damage (numerics.md §9.1–9.3 on the elastic–plastic stress): the stress the
    /// update above produces is the undamaged ("effective") one, and the body feels it with its
    /// tensile principal part scaled by (1 − D); D = 1 fails the particle. Absent: no softening.
    /// Not together with `failure` (set-up refuses both).
    pub damage: Option<DamageModel>,
}

impl ElasticPlastic {
    /// Bulk modulus at the reference state \[Pa\]: the EOS's, or the elastic one.
    pub fn bulk_modulus(&self) -> f64 {
        match &self.pressure {
            PressureModel::Hypoelastic => self.elastic.bulk_modulus(),
            PressureModel::Eos(eos) => eos.bulk_modulus_at_reference(),
        }
    }
}

impl MaterialModel {
    /// Longitudinal modulus K + 4G/3 used for the sound speed \[Pa\] (numerics.md §7).
    pub fn longitudinal_modulus(&self) -> f64 {
        match self {
            MaterialModel::LinearElastic(m) => m.longitudinal_modulus(),
            MaterialModel::ElasticDamage(m) => m.elastic.longitudinal_modulus(),
            MaterialModel::ElasticPlastic(m) => {
                m.bulk_modulus() + 4.0 / 3.0 * m.elastic.shear_modulus()
            }
        }
    }

    /// The equation of state and the shear modulus G of a material whose pressure comes from
    /// one (for its current sound speed, numerics.md §8.10); `None` for a constant bulk modulus.
    pub fn equation_of_state(&self) -> Option<(EquationOfState, f64)> {
        match self {
            MaterialModel::ElasticPlastic(ElasticPlastic {
                pressure: PressureModel::Eos(eos),
                elastic,
                ..
            }) => Some((*eos, elastic.shear_modulus())),
            _ => None,
        }
    }

    /// Young's modulus E of the elastic part \[Pa\].
    pub fn youngs_modulus(&self) -> f64 {
        match self {
            MaterialModel::LinearElastic(m) => m.youngs_modulus(),
            MaterialModel::ElasticPlastic(m) => m.elastic.youngs_modulus(),
            MaterialModel::ElasticDamage(m) => m.elastic.youngs_modulus(),
        }
    }

    /// Whether the model carries an effective plastic strain.
    pub fn has_plastic_strain(&self) -> bool {
        matches!(self, MaterialModel::ElasticPlastic(_))
    }

    /// Whether particles of this material can fail (a failure or damage model is declared) and
    /// so carry a damage field (numerics.md §9.3).
    pub fn has_damage(&self) -> bool {
        match self {
            MaterialModel::LinearElastic(_) => false,
            MaterialModel::ElasticPlastic(m) => m.failure.is_some() || m.damage.is_some(),
            MaterialModel::ElasticDamage(_) => true,
        }
    }

    /// The softening damage law of the material (numerics.md §9.1–9.2), elastic or
    /// elastic–plastic; `None` without one.
    pub fn softening_damage(&self) -> Option<&DamageModel> {
        match self {
            MaterialModel::LinearElastic(_) => None,
            MaterialModel::ElasticPlastic(m) => m.damage.as_ref(),
            MaterialModel::ElasticDamage(m) => Some(&m.damage),
        }
    }

    /// The failure criterion of the material (numerics.md §8.6–8.9); `None` without one (elastic
    /// materials have none).
    pub fn failure(&self) -> Option<&FailureModel> {
        match self {
            MaterialModel::ElasticPlastic(m) => m.failure.as_ref(),
            MaterialModel::LinearElastic(_) | MaterialModel::ElasticDamage(_) => None,
        }
    }

    /// Whether the material fails by Johnson–Cook cumulative damage (numerics.md §8.6), the
    /// damage variable an initial failure damage sets.
    pub fn has_johnson_cook_failure(&self) -> bool {
        matches!(self.failure(), Some(FailureModel::JohnsonCook { .. }))
    }

    /// Whether the model carries a temperature.
    pub fn has_temperature(&self) -> bool {
        matches!(self, MaterialModel::ElasticPlastic(m) if m.thermal.is_some())
    }

    /// For an elastic–plastic material and a starting Cauchy stress outside the yield surface
    /// of a particle with the effective plastic strain `plastic_strain` (von Mises stress above
    /// [`StrengthModel::quasi_static_yield_stress`] by more than [`INITIAL_YIELD_TOLERANCE`]),
    /// the pair (von Mises stress, yield stress) \[Pa\]; `None` when the stress is admissible
    /// or the material has no yield surface.
    pub fn outside_yield_surface(
        &self,
        stress: &tlsph_math::Tensor3,
        plastic_strain: f64,
    ) -> Option<(f64, f64)> {
        let MaterialModel::ElasticPlastic(m) = self else {
            return None;
        };
        let equivalent = tlsph_math::von_mises(stress);
        let yield_stress = m.strength.quasi_static_yield_stress(plastic_strain);
        (equivalent > yield_stress * (1.0 + INITIAL_YIELD_TOLERANCE))
            .then_some((equivalent, yield_stress))
    }
}

/// Relative tolerance on the yield surface for a starting stress: a von Mises stress up to
/// σ_y0 (1 + 1e-9) counts as on the surface (a value copied from a table, rounded in print).
pub const INITIAL_YIELD_TOLERANCE: f64 = 1e-9;

/// A named material.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialDescription {
    /// Name referenced by bodies.
    pub name: String,
    /// Reference density ρ0 \[kg/m³\].
    pub density: f64,
    /// Constitutive model.
    pub model: MaterialModel,
}

impl MaterialDescription {
    /// Wave speed at the reference state c0 = sqrt(M/ρ0), M = K + 4G/3 with an equation of
    /// state's reference bulk modulus where one is declared (numerics.md §7; R 5.69).
    pub fn reference_wave_speed(&self) -> f64 {
        (self.model.longitudinal_modulus() / self.density).sqrt()
    }
}

/// The CFL step a body allows at the start of a run (see [`Model::initial_time_steps`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InitialTimeStep {
    /// Smoothing length h = `smoothing_factor` · spacing \[length\].
    pub smoothing_length: f64,
    /// [`MaterialDescription::reference_wave_speed`] of the body's material \[length/time\].
    pub wave_speed: f64,
    /// Largest initial particle speed |v| \[length/time\].
    pub fastest_particle: f64,
    /// C h / (c0 + |v|max) (R 5.69 at J = 1) \[time\].
    pub time_step: f64,
}

/// One body: a set of particles bonded to each other in the reference configuration.
/// Different bodies never interact (contact comes later).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyDescription<const D: usize> {
    /// Name used in error messages and probes.
    pub name: String,
    /// Index into `Model::materials`.
    pub material: usize,
    /// Particle spacing Δx \[m\]; h = smoothing_factor × Δx.
    pub spacing: f64,
    /// Reference positions X \[m\].
    pub positions: Vec<Vector<D>>,
    /// Reference volumes V0 \[m^D\].
    pub volumes: Vec<f64>,
    /// Initial velocities \[m/s\].
    pub velocities: Vec<Vector<D>>,
    /// Uniform initial Cauchy stress of every particle (symmetric 3x3, tension positive),
    /// e.g. a prestressed part; carried on by the rate-form (Jaumann) stress updates. See
    /// [`crate::Simulation::set_initial_stress`] for what refuses it.
    pub initial_stress: Option<tlsph_math::Tensor3>,
    /// Its gradient: the initial stress of the particle at X is σ0 + Σ_k X_k G_k, with
    /// G_k = ∂σ/∂X_k (symmetric) and σ0 = `initial_stress` (zero when absent), e.g. a stress
    /// in equilibrium with a body force. `None`: uniform.
    pub initial_stress_gradient: Option<[tlsph_math::Tensor3; D]>,
    /// An initial Cauchy stress per particle (same order as `positions`), e.g. a residual
    /// stress field mapped from a file; excludes `initial_stress` and
    /// `initial_stress_gradient`. `None`: as those two give.
    pub initial_stresses: Option<Vec<tlsph_math::Tensor3>>,
    /// An effective plastic strain ε̄p per particle at t = 0 (same order as `positions`), e.g.
    /// a work-hardened part or the strain left by a forming step; only for elastic–plastic
    /// materials. See [`crate::Simulation::set_initial_plastic_strains`]. `None`: 0.
    pub initial_plastic_strains: Option<Vec<f64>>,
    /// A softening damage D per particle at t = 0 (same order as `positions`), e.g. a part
    /// damaged by an earlier load; only for materials with a damage law. See
    /// [`crate::Simulation::set_initial_damage`]. `None`: 0.
    pub initial_damage: Option<Vec<f64>>,
    /// A Johnson–Cook cumulative damage D per particle at t = 0 (same order as `positions`),
    /// e.g. the ductile damage left by a forming step; only for materials with a
    /// `johnson-cook` failure law. See [`crate::Simulation::set_initial_failure_damage`].
    /// `None`: 0.
    pub initial_failure_damage: Option<Vec<f64>>,
}

/// The linear initial stress σ0 + Σ_k X_k G_k at reference position `x` (σ0 and the
/// G_k = ∂σ/∂X_k as in [`BodyDescription::initial_stress_gradient`]).
pub fn linear_stress_at<const D: usize>(
    at_origin: tlsph_math::Tensor3,
    gradient: &[tlsph_math::Tensor3; D],
    x: &Vector<D>,
) -> tlsph_math::Tensor3 {
    x.iter()
        .zip(gradient)
        .fold(at_origin, |sigma, (x_k, g_k)| sigma + g_k * *x_k)
}

/// Prescribed velocity on a set of particles of one body (numerics.md §13.2).
/// A fixed set is a prescribed velocity of zero in every component.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryDescription<const D: usize> {
    /// Name used in reports.
    pub name: String,
    /// Index into `Model::bodies`.
    pub body: usize,
    /// Particle indices local to the body.
    pub particles: Vec<usize>,
    /// Prescribed velocity \[m/s\] (only the components flagged in `components` are imposed).
    pub velocity: Vector<D>,
    /// Which velocity components are imposed.
    pub components: [bool; D],
    /// Time history r(t) of the prescribed velocity, v(t) = r(t) `velocity` (a start-up
    /// ramp or a table); `None`: the full velocity from t = 0.
    pub amplitude: Option<Amplitude>,
}

/// Start-up of a prescribed velocity: v(t) = r(t/T) v with r rising from 0 at t = 0 to 1 at
/// t = T and staying 1 afterwards (ours, not in the theses; for quasi-static loading in a
/// dynamic code, numerics.md §17 pitfall 12). Both shapes displace the set by v (t − T/2) once
/// t ≥ T.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityRamp {
    /// Ramp duration T \[s\] (> 0).
    pub duration: f64,
    /// How the velocity rises.
    pub shape: RampShape,
}

/// Shape r(s), 0 ≤ s ≤ 1, of a [`VelocityRamp`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RampShape {
    /// r(s) = s: constant acceleration, with a jump in acceleration at both ends.
    Linear,
    /// r(s) = ½(1 − cos πs): the acceleration rises from and returns to zero, so the ramp
    /// launches no acceleration step (the quieter start).
    Smooth,
}

impl VelocityRamp {
    /// Factor r(t/T) ∈ [0, 1] of the prescribed velocity at time `t`.
    pub fn factor(&self, t: f64) -> f64 {
        let s = (t / self.duration).clamp(0.0, 1.0);
        match self.shape {
            RampShape::Linear => s,
            RampShape::Smooth => 0.5 * (1.0 - (std::f64::consts::PI * s).cos()),
        }
    }
    /// Checks the duration (finite, > 0); the error message says what is wrong.
    pub fn validate(&self) -> Result<(), String> {
        if self.duration.is_finite() && self.duration > 0.0 {
            Ok(())
        } else {
            Err(format!(
                "ramp duration must be finite and > 0 (got {})",
                self.duration
            ))
        }
    }

    /// Integral ∫₀ᵗ r(s/T) ds of the factor \[s\]: the distance travelled by time `t` per unit
    /// of the full velocity; t − T/2 once the ramp is over, for both shapes.
    pub fn integral(&self, t: f64) -> f64 {
        let big_t = self.duration;
        if t <= 0.0 {
            return 0.0;
        }
        if t >= big_t {
            return t - 0.5 * big_t;
        }
        match self.shape {
            RampShape::Linear => t * t / (2.0 * big_t),
            RampShape::Smooth => {
                let pi = std::f64::consts::PI;
                0.5 * (t - big_t / pi * (pi * t / big_t).sin())
            }
        }
    }
}

/// Time history r(t) that scales a prescribed velocity, a wall's velocity or a body force:
/// v(t) = r(t) v (ours, not in the theses; numerics.md §17 pitfall 12 for the ramp).
#[derive(Debug, Clone, PartialEq)]
pub enum Amplitude {
    /// A start-up from 0 to 1 over a duration, then 1.
    Ramp(VelocityRamp),
    /// A piecewise-linear table: loading, holding, unloading, a pulse.
    Table(AmplitudeTable),
}

impl From<VelocityRamp> for Amplitude {
    fn from(ramp: VelocityRamp) -> Self {
        Amplitude::Ramp(ramp)
    }
}

impl Amplitude {
    /// Factor r(t) at time `t`.
    pub fn factor(&self, t: f64) -> f64 {
        match self {
            Amplitude::Ramp(ramp) => ramp.factor(t),
            Amplitude::Table(table) => table.factor(t),
        }
    }

    /// Integral ∫₀ᵗ r(s) ds \[s\]: the distance travelled by time `t` per unit of the full
    /// velocity (0 for t ≤ 0).
    pub fn integral(&self, t: f64) -> f64 {
        match self {
            Amplitude::Ramp(ramp) => ramp.integral(t),
            Amplitude::Table(table) => table.integral(t),
        }
    }

    /// Checks the ramp's duration (its fields are public); the error says what is wrong. A
    /// table was checked when it was built ([`AmplitudeTable::new`]).
    pub fn validate(&self) -> Result<(), String> {
        match self {
            Amplitude::Ramp(ramp) => ramp.validate(),
            Amplitude::Table(_) => Ok(()),
        }
    }
}

/// An amplitude through the points (t_k, r_k): r = r_0 before t_0, r_n after the last, and
/// between neighbouring points r = r_a + (r_b − r_a) w(ξ), ξ = (t − t_a)/(t_b − t_a), with
/// w of its [`TableShape`] (the tabular and smooth-step amplitudes of finite-element codes).
/// Times are ≥ 0 and strictly increasing.
#[derive(Debug, Clone, PartialEq)]
pub struct AmplitudeTable {
    /// The points (t_k \[s\], r_k).
    points: Vec<(f64, f64)>,
    /// ∫₀^{t_k} r ds at each point \[s\] (the same for both shapes: ∫₀¹ w = ½).
    integrals: Vec<f64>,
    /// How r goes from one point to the next.
    shape: TableShape,
}

/// How an [`AmplitudeTable`] goes between its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TableShape {
    /// w(ξ) = ξ: straight pieces; the rate jumps at every point.
    Linear,
    /// w(ξ) = ξ³ (10 − 15ξ + 6ξ²): the quintic smooth step, whose first and second
    /// derivatives vanish at both ends, so r, its rate and its second rate are continuous
    /// through every point (a velocity that starts, holds and stops without a jump in
    /// acceleration).
    SmoothStep,
}

impl TableShape {
    /// w(ξ) and its integral W(ξ) = ∫₀^ξ w, for 0 ≤ ξ ≤ 1.
    fn weight(self, xi: f64) -> (f64, f64) {
        match self {
            TableShape::Linear => (xi, 0.5 * xi * xi),
            TableShape::SmoothStep => {
                let xi3 = xi * xi * xi;
                (
                    xi3 * (10.0 - 15.0 * xi + 6.0 * xi * xi),
                    xi3 * xi * (2.5 - 3.0 * xi + xi * xi),
                )
            }
        }
    }
}

impl AmplitudeTable {
    /// The table through `points`: at least two, with finite values and finite times ≥ 0 that
    /// strictly increase; the error says which point is wrong.
    pub fn new(points: Vec<(f64, f64)>) -> Result<Self, String> {
        Self::check(&points)?;
        let (t0, r0) = points[0];
        let mut integrals = Vec::with_capacity(points.len());
        integrals.push(r0 * t0);
        for pair in points.windows(2) {
            let ((ta, ra), (tb, rb)) = (pair[0], pair[1]);
            let last = integrals[integrals.len() - 1];
            integrals.push(last + 0.5 * (ra + rb) * (tb - ta));
        }
        Ok(Self {
            points,
            integrals,
            shape: TableShape::Linear,
        })
    }

    /// The same points joined by `shape` (a new table is [`TableShape::Linear`]).
    pub fn with_shape(mut self, shape: TableShape) -> Self {
        self.shape = shape;
        self
    }

    /// How the table goes between its points.
    pub fn shape(&self) -> TableShape {
        self.shape
    }

    /// The points (t_k, r_k).
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points
    }

    fn check(points: &[(f64, f64)]) -> Result<(), String> {
        if points.len() < 2 {
            return Err(format!(
                "an amplitude table needs at least two points (t, r), got {}",
                points.len()
            ));
        }
        for (k, &(t, r)) in points.iter().enumerate() {
            if !(t.is_finite() && t >= 0.0 && r.is_finite()) {
                return Err(format!(
                    "amplitude point {k} ({t}, {r}) needs a finite time ≥ 0 and a finite factor"
                ));
            }
            if k > 0 && t <= points[k - 1].0 {
                return Err(format!(
                    "amplitude times must increase: point {k} at t = {t} follows t = {}",
                    points[k - 1].0
                ));
            }
        }
        Ok(())
    }

    /// Index of the segment [t_k, t_{k+1}) holding `t`, or `None` before the first point or
    /// at and after the last.
    fn segment(&self, t: f64) -> Option<usize> {
        let after = self.points.partition_point(|&(tk, _)| tk <= t);
        (after >= 1 && after < self.points.len()).then(|| after - 1)
    }

    /// Segment `k`'s points and w, W at `t` in it.
    fn within(&self, k: usize, t: f64) -> ((f64, f64), (f64, f64), f64, f64) {
        let ((ta, ra), (tb, rb)) = (self.points[k], self.points[k + 1]);
        let (w, big_w) = self.shape.weight((t - ta) / (tb - ta));
        ((ta, ra), (tb, rb), w, big_w)
    }

    /// r(t).
    pub fn factor(&self, t: f64) -> f64 {
        match self.segment(t) {
            Some(k) => {
                let ((_, ra), (_, rb), w, _) = self.within(k, t);
                ra + (rb - ra) * w
            }
            None if t < self.points[0].0 => self.points[0].1,
            None => self.points[self.points.len() - 1].1,
        }
    }

    /// ∫₀ᵗ r ds, exact for either shape (0 for t ≤ 0).
    pub fn integral(&self, t: f64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let (t0, r0) = self.points[0];
        if t < t0 {
            return r0 * t;
        }
        match self.segment(t) {
            Some(k) => {
                let ((ta, ra), (tb, rb), _, big_w) = self.within(k, t);
                self.integrals[k] + ra * (t - ta) + (rb - ra) * (tb - ta) * big_w
            }
            None => {
                let n = self.points.len() - 1;
                let (tn, rn) = self.points[n];
                self.integrals[n] + rn * (t - tn)
            }
        }
    }
}

/// A rigid plane (numerics.md §13; an anvil, or with [`WallMotion`] a platen), frictionless or
/// with Coulomb friction.
#[derive(Debug, Clone, PartialEq)]
pub struct WallDescription<const D: usize> {
    /// Name (its reaction is reported as `wall_<name>`).
    pub name: String,
    /// A point of the plane \[m\].
    pub point: Vector<D>,
    /// Normal pointing into the half-space where the particles are (need not be unit).
    pub normal: Vector<D>,
    /// Coulomb friction: kinetic and static coefficients and their decay with sliding speed
    /// (numerics.md §13 `[C]`); `FrictionCoefficients::single(0.0)`: frictionless, no
    /// friction effect is built.
    pub friction: FrictionCoefficients,
    /// Translation of the plane; `None`: the wall is fixed.
    pub motion: Option<WallMotion<D>>,
    /// The wall's shape: the unbounded plane, or (2D and 3D) a finite disc, a ball, a box or
    /// a cone (a wedge in 2D), or (3D) a cylinder or a pyramid.
    pub shape: WallShape<D>,
    /// Report the moment M = Σ (x_I − p(t)) × F_I of the wall's force on the particles (and of
    /// its friction force, separately) about the wall's current `point` p(t) (opt-in: without
    /// it nothing is computed).
    pub report_moment: bool,
}

/// The shape of a rigid wall (ours, not in the theses; numerics.md §13 `[C]` law on each).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WallShape<const D: usize> {
    /// The unbounded plane through `point` normal to `normal` (`tlsph_contact::RigidPlane`).
    Plane,
    /// The disc of this radius about `point` in that plane (the segment of this half-length in
    /// 2D), a plate with a rounded rim: a flat punch, a ledge (`tlsph_contact::FlatDisc`) \[m\].
    Disc {
        /// R \[m\].
        radius: f64,
    },
    /// The ball of this radius centred at `point` (a disc in 2D: a cylinder in plane strain),
    /// e.g. a spherical indenter (`tlsph_contact::RigidBall`); `normal` is not used.
    Ball {
        /// R \[m\].
        radius: f64,
    },
    /// (3D) The cylinder of this radius about the line through `point` along `axis`: unbounded
    /// in length, a roller, a cylindrical indenter longer than the body
    /// (`tlsph_contact::RigidCylinder`); or of a finite length centred at `point`, a solid
    /// with flat ends, a cylindrical punch, a pin (`tlsph_contact::FiniteCylinder`). `normal`
    /// is not used.
    Cylinder {
        /// R \[m\].
        radius: f64,
        /// Direction of the axis (need not be unit).
        axis: Vector<D>,
        /// L \[m\]: `None` for an unbounded cylinder.
        length: Option<f64>,
    },
    /// (2D and 3D) The rectangle or rectangular block of these edge lengths centred at
    /// `point`, its edges along the frame of `normal` and, in 3D, `axis`
    /// (`tlsph_contact::RigidBox::frame`): a rectangular punch with sharp edges, a die, a
    /// step (`tlsph_contact::RigidBox`).
    Box {
        /// Edge lengths a_k along the frame's e_k: (along the normal turned clockwise, along
        /// the normal) in 2D, (along the axis, along normal × axis, along the normal) in 3D
        /// \[m\].
        size: Vector<D>,
        /// (3D) Direction of the box's first edge, at right angles to `normal` (need not be
        /// unit); not used in 2D.
        axis: Vector<D>,
        /// Radius ρ to which its edges and corners are rounded, 0 ≤ ρ ≤ a_k/2 (0: sharp)
        /// \[m\].
        edge_radius: f64,
    },
    /// (2D and 3D) The cone with its tip at `point`, opening along `axis`, unbounded towards
    /// its base, with its tip sharp or rounded; in 2D a wedge (the cone in plane strain): a
    /// conical or wedge indenter (`tlsph_contact::RigidCone`). `normal` is not used.
    Cone {
        /// Direction from the tip into the cone (need not be unit).
        axis: Vector<D>,
        /// Half-angle α between the axis and the flanks, 0 < α < π/2 \[rad\].
        half_angle: f64,
        /// Radius ρ ≥ 0 of the sphere (circle in 2D) tangent to the flanks that rounds the tip
        /// (0: sharp) \[m\].
        tip_radius: f64,
    },
    /// (3D) The regular pyramid with its tip at `point`, opening along `axis`, unbounded
    /// towards its base, with its tip sharp or rounded: a Vickers or Berkovich indenter
    /// (`tlsph_contact::RigidPyramid`). `normal` is not used.
    Pyramid {
        /// Direction from the tip into the pyramid (need not be unit).
        axis: Vector<D>,
        /// Direction from the axis towards the middle of the first face, at right angles to
        /// the axis (need not be unit).
        face_direction: Vector<D>,
        /// Number N ≥ 3 of faces (4 Vickers, 3 Berkovich).
        sides: usize,
        /// Half-angle α between the axis and each face's centre line, 0 < α < π/2 \[rad\].
        half_angle: f64,
        /// Radius ρ ≥ 0 of the sphere that rounds the tip (0: sharp) \[m\].
        tip_radius: f64,
    },
}

impl<const D: usize> WallShape<D> {
    /// The edge frame of a box with the wall's `normal` (its columns e_k, from
    /// `tlsph_contact::RigidBox::frame`, or why there is none); `None` for any other shape.
    pub fn box_frame(&self, normal: Vector<D>) -> Option<Result<Tensor<D>, String>> {
        match self {
            WallShape::Box { axis, .. } => Some(tlsph_contact::RigidBox::frame(normal, *axis)),
            _ => None,
        }
    }

    /// The box of this shape centred at `point` with the wall's `normal`, for particles with
    /// smoothing lengths, sound speeds and spacings `particles` (empty slices: its geometry
    /// alone, its `distance` but not its contact), or why there is none: no frame, an edge
    /// length not finite and > 0, an edge radius not within 0 ≤ ρ ≤ a_k/2; `None` for any
    /// other shape.
    pub fn rigid_box(
        &self,
        point: Vector<D>,
        normal: Vector<D>,
        (h, c0, dx): (&[f64], &[f64], &[f64]),
    ) -> Option<Result<tlsph_contact::RigidBox<D>, String>> {
        let WallShape::Box {
            size, edge_radius, ..
        } = *self
        else {
            return None;
        };
        let frame = match self.box_frame(normal)? {
            Ok(frame) => frame,
            Err(why) => return Some(Err(why)),
        };
        if !size.iter().all(|a| a.is_finite() && *a > 0.0) {
            return Some(Err(format!(
                "a box's edge lengths must be finite and > 0, got {:?}",
                size.as_slice()
            )));
        }
        let half_shortest = 0.5 * size.min();
        if !(edge_radius >= 0.0 && edge_radius <= half_shortest) {
            return Some(Err(format!(
                "a box's edge radius must be ≥ 0 and at most half its shortest edge, {half_shortest:e}, got {edge_radius}"
            )));
        }
        let block = tlsph_contact::RigidBox::new(point, frame, size, h, c0, dx);
        Some(Ok(block.with_edge_radius(edge_radius)))
    }

    /// The cone of this shape with its tip at `point`, for particles with smoothing lengths,
    /// sound speeds and spacings `particles` (empty slices: its geometry alone, its `distance`
    /// but not its contact), or why there is none: a 1D scene, an axis not finite and
    /// non-zero, a half-angle not within 0 < α < π/2, a tip radius not finite and ≥ 0; `None`
    /// for any other shape.
    pub fn rigid_cone(
        &self,
        point: Vector<D>,
        (h, c0, dx): (&[f64], &[f64], &[f64]),
    ) -> Option<Result<tlsph_contact::RigidCone<D>, String>> {
        let WallShape::Cone {
            axis,
            half_angle,
            tip_radius,
        } = *self
        else {
            return None;
        };
        let why = if D < 2 {
            format!("a cone needs a 2D or 3D scene (in 2D it is a wedge), got {D}D")
        } else if !(axis.iter().all(|a| a.is_finite()) && axis.norm() > 0.0) {
            format!(
                "a cone's axis must be finite and non-zero, got {:?}",
                axis.as_slice()
            )
        } else if !(half_angle > 0.0 && half_angle < std::f64::consts::FRAC_PI_2) {
            format!(
                "a cone's half-angle must lie between 0 and 90°, got {}°",
                half_angle.to_degrees()
            )
        } else if !(tip_radius.is_finite() && tip_radius >= 0.0) {
            format!("a cone's tip radius must be finite and ≥ 0, got {tip_radius}")
        } else {
            return Some(Ok(tlsph_contact::RigidCone::new(
                point, axis, half_angle, tip_radius, h, c0, dx,
            )));
        };
        Some(Err(why))
    }

    /// The pyramid of this shape with its tip at `point`, for particles with smoothing
    /// lengths, sound speeds and spacings `particles` (empty slices: its geometry alone, its
    /// `distance` but not its contact), or why there is none
    /// (`tlsph_contact::RigidPyramid::new`); `None` for any other shape.
    pub fn rigid_pyramid(
        &self,
        point: Vector<D>,
        particles: (&[f64], &[f64], &[f64]),
    ) -> Option<Result<tlsph_contact::RigidPyramid<D>, String>> {
        let WallShape::Pyramid {
            axis,
            face_direction,
            sides,
            half_angle,
            tip_radius,
        } = *self
        else {
            return None;
        };
        Some(tlsph_contact::RigidPyramid::new(
            point,
            axis,
            face_direction,
            sides,
            half_angle,
            tip_radius,
            particles,
        ))
    }

    /// The axis a wall of this shape, with `normal`, may spin about (`WallMotion::spin`): its
    /// own axis of symmetry, so the spin moves its surface and not its shape. `Ok(Some(ê))`: a
    /// plane's or a disc's normal, a cylinder's or a cone's axis (3D), z for a ball in 2D;
    /// `Ok(None)`: any axis (a ball in 3D); `Err`: this wall cannot spin.
    pub fn spin_axis(&self, normal: Vector<D>) -> Result<Option<Vector3>, String> {
        match (D, self) {
            (3, WallShape::Plane | WallShape::Disc { .. }) => {
                Ok(Some(tlsph_math::vector_to_3d(&normal).normalize()))
            }
            (3, WallShape::Cylinder { axis, .. } | WallShape::Cone { axis, .. }) => {
                Ok(Some(tlsph_math::vector_to_3d(axis).normalize()))
            }
            (3, WallShape::Ball { .. }) => Ok(None),
            (2, WallShape::Ball { .. }) => Ok(Some(Vector3::z())),
            (_, WallShape::Box { .. }) => Err("a box cannot spin: it has no axis about which turning leaves its shape where it is".into()),
            (_, WallShape::Pyramid { .. }) => Err("a pyramid cannot spin: turning about its axis moves its faces".into()),
            (2, _) => Err("in 2D only a ball may spin (about z): a plane, a disc or a wedge turning in the plane would move its shape".into()),
            _ => Err(format!("a {D}D wall cannot spin")),
        }
    }
}

/// Prescribed motion of a rigid wall (a platen, a piston, a conveyor belt, a driven roller, a
/// turntable; ours, not in the theses): the translation v_w(t) = r(t) v with the optional
/// [`Amplitude`] r (a start-up ramp, or a table such as press, hold and withdraw), so the
/// wall's point is at X_w + v ∫₀ᵗ r, and the spin ω(t) = r_s(t) ω about an axis through that
/// point, with its own optional start-up ramp r_s (a roller pressed in and held while it keeps
/// turning).
#[derive(Debug, Clone, PartialEq)]
pub struct WallMotion<const D: usize> {
    /// Full velocity v of the plane \[m/s\] (any direction: along the normal it presses or
    /// withdraws, across it the wall slides under the particles).
    pub velocity: Vector<D>,
    /// Full angular velocity ω \[rad/s\] about an axis through the wall's point, (0, 0, ω_z)
    /// in 2D; `None`: the wall does not spin. Only about an axis of the wall's own symmetry (a
    /// plane's or a disc's normal, a cylinder's or a cone's axis, any axis of a ball; in 2D
    /// only a ball), so the spin moves the wall's surface, which its friction reads
    /// (`tlsph_contact::spin_velocity`), and not its shape.
    pub spin: Option<Vector3>,
    /// Time history r(t) of the velocity; `None`: the full velocity from t = 0.
    pub amplitude: Option<Amplitude>,
    /// Start-up ramp r_s(t) of the spin; `None`: the full spin from t = 0.
    pub spin_ramp: Option<VelocityRamp>,
}

impl<const D: usize> WallMotion<D> {
    /// Velocity of the plane at time `t` \[m/s\].
    pub fn velocity_at(&self, t: f64) -> Vector<D> {
        self.velocity * self.amplitude.as_ref().map_or(1.0, |r| r.factor(t))
    }

    /// Angular velocity of the wall at time `t` \[rad/s\], if it spins.
    pub fn spin_at(&self, t: f64) -> Option<Vector3> {
        let factor = self.spin_ramp.as_ref().map_or(1.0, |r| r.factor(t));
        self.spin.map(|omega| omega * factor)
    }

    /// Displacement of the plane from its position at t = 0, at time `t` \[m\].
    pub fn displacement_at(&self, t: f64) -> Vector<D> {
        self.velocity * self.amplitude.as_ref().map_or(t, |r| r.integral(t))
    }
}

/// A symmetry plane x_axis = position, modelled by mirror (ghost) particles
/// (numerics.md §13.1). Bodies must lie on one side of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetryPlane {
    /// Normal axis: 0 = x, 1 = y, 2 = z.
    pub axis: usize,
    /// Position of the plane along that axis \[m\].
    pub position: f64,
}

/// Artificial bulk ("nodal") viscosity (numerics.md §10.2, R §7.5–7.6): in compression
/// (tr D < 0) q = ρ ℓ (Q1 ℓ (tr D)² − Q2 c tr D) with ℓ = h is added to the pressure of the
/// stress that drives the forces (not to the stored elastic stress), and heats the material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BulkViscosity {
    /// Quadratic coefficient Q1.
    pub quadratic: f64,
    /// Linear coefficient Q2.
    pub linear: f64,
}

/// Optional effects of a run; absent effects cost nothing.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EffectsDescription<const D: usize> {
    /// Rigid walls acting on every body.
    pub walls: Vec<WallDescription<D>>,
    /// Ganzenmüller hourglass control coefficient α (numerics.md §10.5).
    pub hourglass_control: Option<f64>,
    /// Symmetry planes (several at once for quarter and eighth models).
    pub symmetry_planes: Vec<SymmetryPlane>,
    /// Artificial bulk viscosity.
    pub bulk_viscosity: Option<BulkViscosity>,
    /// Monaghan pairwise artificial viscosity (α, β) for the reference neighbour pairs
    /// (numerics.md §10.1).
    pub pairwise_viscosity: Option<(f64, f64)>,
    /// XSPH coefficient ε (numerics.md §10.4, TL variant): particles move, and Ḟ is built,
    /// with v̂_I = v_I + ε Σ_J V0_J (v_J − v_I) W̃_IJ.
    pub xsph: Option<f64>,
    /// Monaghan/Gray artificial stress (numerics.md §10.3; updated-Lagrangian only).
    pub artificial_stress: Option<ArtificialStress>,
    /// Kernel interaction group of each body, indexed like `Model::bodies`
    /// (updated-Lagrangian only; numerics.md §3, F §4.3 "particle types"): two bodies
    /// interact through the kernel iff their groups are equal. `None`: the material index, so
    /// bodies of the same material interact.
    pub kernel_groups: Option<Vec<usize>>,
    /// Potential-type particle-to-particle contact between bodies (numerics.md §12.2).
    pub contact: Option<ContactDescription>,
    /// Fuller's particle-type penalty contact with friction (numerics.md §12.1); exclusive
    /// with `contact` (both would book the `contact` energy column).
    pub penalty_contact: Option<PenaltyContactDescription>,
    /// Reference-configuration update for the total-Lagrangian formulations (numerics.md
    /// §4 `[C]`): when a particle's strain since the last reference configuration exceeds the
    /// threshold, the current configuration becomes the new reference.
    pub reference_update: Option<ReferenceUpdate>,
    /// A uniform body force per unit mass (gravity, a steady acceleration of the frame).
    pub body_force: Option<BodyForceDescription<D>>,
}

/// A uniform body force per unit mass b (numerics.md §4.5 and §3, R 4.11:
/// ρ0 ü = ∇·P + ρ0 b; added with the accelerations of §5 step 6):
/// gravity, or the inertial load of a steadily accelerating frame. Its work is booked in the
/// `body_force` energy column (the potential energy gained; with a ramp, the time-centred
/// work integral), so total energy closes.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyForceDescription<const D: usize> {
    /// Acceleration b \[m/s²\] (e.g. (0, −9.81) for gravity along −y).
    pub acceleration: Vector<D>,
    /// Bodies (indices into `Model::bodies`) that feel it; `None` = every body.
    pub bodies: Option<Vec<usize>>,
    /// Time history b(t) = r(t) b: a start-up ramp (the shapes of [`VelocityRamp`]), e.g. to
    /// load a body by its weight without the dynamic overshoot of a sudden load, or a table (a
    /// pulse, a load that comes and goes); `None`: the full b from t = 0.
    pub amplitude: Option<Amplitude>,
}

/// When to replace the reference configuration by the current one (TLSPH at large strain).
///
/// TLSPH gradients live on the reference neighbourhood; once the material has flowed far
/// (strains of order one) that neighbourhood no longer resembles the current one and the
/// kernel sums degrade until particles invert. Re-referencing rebuilds neighbours and
/// corrected gradients on the current positions, with volumes V = V0 det F, and carries
/// det F0 of the old reference in the constitutive update (density, EOS, energy), so the
/// Jaumann-rate stress, plastic state and energy continue unchanged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceUpdate {
    /// Update when max over particles of ‖E‖ (Frobenius norm of the Green–Lagrange strain
    /// ½(FᵀF − I) relative to the current reference) exceeds this value.
    pub strain_threshold: f64,
    /// How each particle's kernel support is chosen on the new reference.
    pub support: ReferenceSupport,
}

/// Kernel support of a particle on an updated reference (numerics.md §4 `[C]`, `reference.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ReferenceSupport {
    /// h_I = h λ_max(F0_I), at least h: the support grows with the largest principal stretch
    /// of the particle since the initial configuration, so it covers the image of its initial
    /// support and a particle stretched in one direction keeps neighbours in that direction.
    /// Costs more bonds where the material has stretched (about λ_max³/J times as many).
    #[default]
    Stretched,
    /// Every particle keeps its body's h: cheapest, but where the material has stretched by
    /// λ the support spans only 2h/λ initial spacings in that direction, and a Taylor foot
    /// comes out about 16 % too wide.
    Fixed,
}

/// Vignjevic-type potential contact between particles of different bodies (numerics.md §12.2
/// `[C]`): f_I = a M* d0^{d−1} [(W(r, h_c)/W(d0, h_c))ⁿ − 1]₊ (x_I − x_K)/r, f_K = −f_I.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactDescription {
    /// Scale a (deck card value; 2.0, 0.2 or 0.02 in the Reveles decks).
    pub scale: f64,
    /// Exponent n (4 in every Reveles deck).
    pub exponent: f64,
    /// Body pairs (indices into `Model::bodies`) in contact; `None` = every pair of different
    /// bodies (in the updated-Lagrangian formulation minus those that already interact through
    /// the kernel).
    pub pairs: Option<Vec<(usize, usize)>>,
}

/// Fuller's particle-type penalty contact (numerics.md §12.1, F §4.3–4.4): every body is a
/// particle type; for a surface particle I (at most 75 % of the fully surrounded neighbour
/// count) with outward normal n̂_I and a particle K of another body in I's zone
/// (r⊥ = (x_K − x_I)·n̂_I in [−d0, R), tangential offset ≤ d0, d0 = ½(Δx_A + Δx_B)):
/// f_K = k_c (R/max(r⊥, 0.05R) − 1) n̂_I − μ |f_n| v̂_t, f_I = −f_K, k_c = s E* d0^{d−1}, μ the
/// kinetic coefficient while the pair slides (a sticking pair takes the force that stops it,
/// up to the static coefficient).
#[derive(Debug, Clone, PartialEq)]
pub struct PenaltyContactDescription {
    /// Stiffness factor s of k_c = s E* d0^{d−1} (E* the smaller Young's modulus; Fuller: 1).
    pub stiffness: f64,
    /// Range R of the force as a multiple of d0 (Fuller: 1).
    pub range: f64,
    /// Coulomb friction between the pairs: kinetic and static coefficients and their decay
    /// with sliding speed (numerics.md §12.1, §13 `[C]`); `FrictionCoefficients::single(0.0)`:
    /// frictionless.
    pub friction: FrictionCoefficients,
    /// Body pairs (indices into `Model::bodies`) in contact; `None` = every pair of different
    /// bodies (in the updated-Lagrangian formulation minus those of one kernel group). A body
    /// paired with itself is self-contact between its particles that are not reference kernel
    /// neighbours (total-Lagrangian formulations).
    pub pairs: Option<Vec<(usize, usize)>>,
}

/// Monaghan/Gray artificial stress (numerics.md §10.3; F 3.5–3.7): per particle
/// R_I = −ε Q diag(σ'_k⁺/ρ²) Qᵀ over the tensile principal stresses σ'_k, and the pair term
/// (R_I + R_J) (W_IJ/W(Δx))ⁿ added inside the momentum bracket.
#[derive(Debug, Clone, PartialEq)]
pub struct ArtificialStress {
    /// ε (Gray–Monaghan–Swift 0.3).
    pub epsilon: f64,
    /// Exponent n of f_IJ = W_IJ/W(Δx) (Fuller 6).
    pub exponent: f64,
    /// Indices (into `Model::bodies`) of the bodies whose particles carry R_I (F §3.5: one
    /// ring with, one without, in the same run); `None`: every body. A body without it has
    /// R_I = 0 but still feels R_J of the corrected bodies it interacts with, so the pair term
    /// stays equal and opposite.
    pub bodies: Option<Vec<usize>>,
}

/// Everything needed to start a simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct Model<const D: usize> {
    /// Global settings.
    pub config: SimulationConfig,
    /// Materials.
    pub materials: Vec<MaterialDescription>,
    /// Bodies.
    pub bodies: Vec<BodyDescription<D>>,
    /// Prescribed-velocity sets.
    pub boundaries: Vec<BoundaryDescription<D>>,
    /// Optional effects.
    pub effects: EffectsDescription<D>,
}

impl<const D: usize> Model<D> {
    /// Per body, the CFL step C h/(c0 + |v|max) it allows at the start (R 5.69 at J = 1,
    /// before anything is compressed). The smallest of them is the first step the solver takes
    /// unless an effect (contact stiffness) votes lower.
    pub fn initial_time_steps(&self) -> Vec<InitialTimeStep> {
        self.bodies
            .iter()
            .map(|body| {
                let smoothing_length = self.config.smoothing_factor * body.spacing;
                let wave_speed = self.materials[body.material].reference_wave_speed();
                let fastest_particle = body.velocities.iter().map(|v| v.norm()).fold(0.0, f64::max);
                InitialTimeStep {
                    smoothing_length,
                    wave_speed,
                    fastest_particle,
                    time_step: self.config.cfl * smoothing_length / (wave_speed + fastest_particle),
                }
            })
            .collect()
    }

    /// Kernel interaction group of body `body` (updated-Lagrangian formulation): the declared
    /// group, else the body's material index. Bodies interact through the kernel iff their
    /// groups are equal.
    pub fn kernel_group(&self, body: usize) -> usize {
        match &self.effects.kernel_groups {
            Some(groups) => groups.get(body).copied().unwrap_or(usize::MAX),
            None => self.bodies[body].material,
        }
    }
}
