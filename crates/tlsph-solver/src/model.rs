//! Plain descriptions of a simulation (what to simulate). Built by `tlsph-io` from scene files
//! or directly in code; consumed once by `Simulation::new`.

use tlsph_kernels::KernelKind;
use tlsph_materials::LinearElastic;
use tlsph_math::Vector;

/// How kernel gradients are formed in the reference configuration (numerics.md §5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Formulation {
    /// Raw reference-kernel gradients G_IJ = ∇W(X_I − X_J) (Reveles Algorithms 1 and 2).
    TotalLagrangian,
    /// Shepard quotient-rule gradient × Randles–Libersky correction B_I (Algorithm 3,
    /// numerics.md §6.1–6.2): F is exact for affine displacement fields, boundaries included.
    TotalLagrangianCorrected,
}

impl Formulation {
    /// Name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::TotalLagrangian => "total-lagrangian",
            Formulation::TotalLagrangianCorrected => "total-lagrangian-corrected",
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MaterialModel {
    /// Isotropic linear elasticity (R 5.73–5.75).
    LinearElastic(LinearElastic),
}

impl MaterialModel {
    /// Longitudinal modulus K + 4G/3 used for the sound speed \[Pa\] (numerics.md §7).
    pub fn longitudinal_modulus(&self) -> f64 {
        match self {
            MaterialModel::LinearElastic(m) => m.longitudinal_modulus(),
        }
    }
}

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
}
