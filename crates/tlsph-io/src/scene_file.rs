//! The TOML scene schema as written by users (serde types with source spans). Only parsing
//! lives here; checking and conversion into a solver model is in `scene.rs`.
//! Documented for users in `docs/scene-format.md` — keep the two in step.

use serde::Deserialize;
use toml::Spanned;

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SceneFile {
    pub simulation: SimulationTable,
    #[serde(default)]
    pub material: Vec<MaterialTable>,
    #[serde(default)]
    pub body: Vec<BodyTable>,
    #[serde(default)]
    pub boundary: Vec<BoundaryTable>,
    #[serde(default)]
    pub probe: Vec<ProbeTable>,
    #[serde(default)]
    pub output: Option<OutputTable>,
    #[serde(default)]
    pub wall: Vec<WallTable>,
    #[serde(default)]
    pub hourglass_control: Option<HourglassTable>,
    #[serde(default)]
    pub reference_update: Option<ReferenceUpdateTable>,
    #[serde(default)]
    pub symmetry_plane: Vec<SymmetryPlaneTable>,
    #[serde(default)]
    pub bulk_viscosity: Option<BulkViscosityTable>,
    #[serde(default)]
    pub xsph: Option<XsphTable>,
    #[serde(default)]
    pub artificial_viscosity: Option<ArtificialViscosityTable>,
    #[serde(default)]
    pub artificial_stress: Option<Spanned<ArtificialStressTable>>,
    #[serde(default)]
    pub stability: Option<StabilityTable>,
    #[serde(default)]
    pub contact: Option<Spanned<ContactTable>>,
    #[serde(default)]
    pub body_force: Option<BodyForceTable>,
}

/// `[body_force]`: a uniform acceleration (gravity) on every body or on the named ones.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BodyForceTable {
    pub acceleration: Spanned<Vec<f64>>,
    pub bodies: Option<Spanned<Vec<String>>>,
    pub ramp_time: Option<Spanned<f64>>,
    pub ramp_shape: Option<Spanned<String>>,
    pub amplitude: Option<Spanned<Vec<Vec<f64>>>>,
    pub amplitude_shape: Option<Spanned<String>>,
}

/// `[contact]`: particle-to-particle contact between bodies, potential-type (numerics.md §12.2,
/// the default) or Fuller's particle-type penalty with friction (`law = "penalty"`, §12.1).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ContactTable {
    pub law: Option<Spanned<String>>,
    pub scale: Option<Spanned<f64>>,
    pub exponent: Option<Spanned<f64>>,
    pub stiffness: Option<Spanned<f64>>,
    pub range: Option<Spanned<f64>>,
    pub friction: Option<Spanned<f64>>,
    pub static_friction: Option<Spanned<f64>>,
    pub friction_decay: Option<Spanned<f64>>,
    pub pairs: Option<Spanned<Vec<Vec<String>>>>,
}

/// `[stability]`: thresholds of the per-run stability report.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct StabilityTable {
    pub min_neighbour_ratio: Option<Spanned<f64>>,
    pub max_neighbour_ratio: Option<Spanned<f64>>,
    pub clumping_index: Option<Spanned<f64>>,
    pub energy_drift: Option<Spanned<f64>>,
}

/// `[artificial_stress]`: Monaghan/Gray artificial stress (updated-Lagrangian only).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ArtificialStressTable {
    pub epsilon: Option<Spanned<f64>>,
    pub exponent: Option<Spanned<f64>>,
    /// Names of the bodies that carry the correction (default: every body).
    pub bodies: Option<Spanned<Vec<String>>>,
}

/// `[artificial_viscosity]`: Monaghan's pairwise viscosity.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ArtificialViscosityTable {
    pub alpha: Spanned<f64>,
    pub beta: Spanned<f64>,
}

/// `[bulk_viscosity]`: artificial bulk viscosity coefficients.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BulkViscosityTable {
    pub quadratic: Spanned<f64>,
    pub linear: Spanned<f64>,
}

/// `[xsph]`: XSPH velocity smoothing.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct XsphTable {
    pub epsilon: Spanned<f64>,
}

/// `[[symmetry_plane]]`: a coordinate plane modelled with mirror (ghost) particles.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SymmetryPlaneTable {
    pub axis: Spanned<String>,
    pub position: Spanned<f64>,
}

/// `[[wall]]`: a rigid plane, or a disc, ball or cylinder of `radius`, or a box of `size`
/// (optionally with an `edge_radius`), or a cone or a pyramid of `half_angle` (optionally with
/// a `tip_radius`), frictionless unless `friction` is given, fixed unless `velocity` is given
/// (with an optional start-up ramp or amplitude).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct WallTable {
    pub name: Spanned<String>,
    pub point: Spanned<Vec<f64>>,
    /// Required by a plane or a disc; optional for a box; none for a ball, a cylinder, a cone
    /// or a pyramid.
    pub normal: Option<Spanned<Vec<f64>>>,
    pub friction: Option<Spanned<f64>>,
    pub static_friction: Option<Spanned<f64>>,
    pub friction_decay: Option<Spanned<f64>>,
    pub velocity: Option<Spanned<Vec<f64>>>,
    pub ramp_time: Option<Spanned<f64>>,
    pub ramp_shape: Option<Spanned<String>>,
    pub amplitude: Option<Spanned<Vec<Vec<f64>>>>,
    pub amplitude_shape: Option<Spanned<String>>,
    /// "plane" (default), "disc" (the default with `radius`), "ball", "cylinder", "box",
    /// "cone" or "pyramid".
    pub shape: Option<Spanned<String>>,
    /// Finite size: the disc (segment in 2D) or the ball of this radius about `point`, or the
    /// cylinder of this radius about its axis.
    pub radius: Option<Spanned<f64>>,
    /// Direction of a cylinder's axis (through `point`), of a cone's or a pyramid's (from its
    /// tip at `point` into it), or of a spinning ball's spin axis.
    pub axis: Option<Spanned<Vec<f64>>>,
    /// A cylinder's length, centred at `point` (none: unbounded).
    pub length: Option<Spanned<f64>>,
    /// A box's edge lengths, along its frame (its edges along the coordinate axes unless
    /// `normal`, and in 3D `axis`, turn it).
    pub size: Option<Spanned<Vec<f64>>>,
    /// The radius to which a box's edges and corners are rounded (none: sharp).
    pub edge_radius: Option<Spanned<f64>>,
    /// A cone's half-angle between its axis and its flanks, or a pyramid's between its axis
    /// and each face's centre line \[degrees\].
    pub half_angle: Option<Spanned<f64>>,
    /// The radius to which a cone's or a pyramid's tip is rounded (none: sharp).
    pub tip_radius: Option<Spanned<f64>>,
    /// A pyramid's number of faces (4 Vickers, 3 Berkovich).
    pub sides: Option<Spanned<i64>>,
    /// Direction from a pyramid's axis towards the middle of its first face.
    pub face_direction: Option<Spanned<Vec<f64>>>,
    /// Angular speed ω of the wall about its own axis (right-handed): a plane's or a disc's
    /// normal, a cylinder's, a cone's or a ball's `axis`, z for a ball in 2D \[rad/s\].
    pub spin: Option<Spanned<f64>>,
    /// Duration of the spin's smooth start-up \[s\].
    pub spin_ramp_time: Option<Spanned<f64>>,
    /// Write the moment vector of the wall's force (and of its friction's) about its point.
    pub report_moment: Option<Spanned<bool>>,
}

/// `[reference_update]`: replace the TLSPH reference configuration by the current one when
/// the strain relative to it exceeds a threshold.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ReferenceUpdateTable {
    pub strain_threshold: Spanned<f64>,
    /// "stretched" (default) or "fixed".
    pub support: Option<Spanned<String>>,
}

/// `[hourglass_control]`: Ganzenmüller's penalty.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct HourglassTable {
    pub coefficient: Spanned<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SimulationTable {
    pub dimension: Spanned<i64>,
    pub formulation: Spanned<String>,
    #[serde(default)]
    pub stress_update: Option<Spanned<String>>,
    pub kernel: Spanned<String>,
    pub smoothing_factor: Spanned<f64>,
    pub cfl: Spanned<f64>,
    pub end_time: Spanned<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MaterialTable {
    pub name: Spanned<String>,
    pub model: Spanned<String>,
    pub density: Spanned<f64>,
    pub youngs_modulus: Option<Spanned<f64>>,
    pub poisson_ratio: Option<Spanned<f64>>,
    // elastic-plastic (von Mises)
    pub yield_stress: Option<Spanned<f64>>,
    pub tangent_modulus: Option<Spanned<f64>>,
    pub plastic_modulus: Option<Spanned<f64>>,
    // johnson-cook
    pub a: Option<Spanned<f64>>,
    pub b: Option<Spanned<f64>>,
    pub n: Option<Spanned<f64>>,
    pub c: Option<Spanned<f64>>,
    pub m: Option<Spanned<f64>>,
    pub reference_strain_rate: Option<Spanned<f64>>,
    pub melt_temperature: Option<Spanned<f64>>,
    pub accurate_iteration: Option<Spanned<bool>>,
    // shared by the plastic models
    pub room_temperature: Option<Spanned<f64>>,
    pub specific_heat: Option<Spanned<f64>>,
    pub min_pressure: Option<Spanned<f64>>,
    pub eos: Option<Spanned<EosTable>>,
    pub failure: Option<Spanned<FailureTable>>,
    // linear-elastic only
    pub damage: Option<Spanned<DamageTable>>,
}

/// `damage = { model = "...", ... }` of a linear-elastic material.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct DamageTable {
    pub model: String,
    pub kappa0: Option<f64>,
    pub kappa_c: Option<f64>,
    pub m: Option<f64>,
    pub k: Option<f64>,
    pub seed: Option<i64>,
}

/// `failure = { model = "...", ... }` of a plastic material.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct FailureTable {
    pub model: String,
    pub d: Option<Vec<f64>>,
    pub limit: Option<f64>,
    pub reference_strain_rate: Option<f64>,
    pub room_temperature: Option<f64>,
    pub melt_temperature: Option<f64>,
}

/// `eos = { model = "...", ... }` of a plastic material.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct EosTable {
    pub model: String,
    pub bulk_modulus: Option<f64>,
    pub coefficients: Option<Vec<f64>>,
    pub sound_speed: Option<f64>,
    pub s1: Option<f64>,
    pub s2: Option<f64>,
    pub s3: Option<f64>,
    pub gamma0: Option<f64>,
    pub a: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BodyTable {
    pub name: Spanned<String>,
    pub material: Spanned<String>,
    /// Kernel interaction group (updated-Lagrangian; default: the material name).
    pub kernel_group: Option<Spanned<String>>,
    pub spacing: Spanned<f64>,
    /// A single shape may be given directly on the body ...
    #[serde(rename = "box")]
    pub box_: Option<Spanned<BoxShape>>,
    pub cylinder: Option<Spanned<CylinderShape>>,
    pub sphere: Option<Spanned<RoundShape>>,
    pub disc: Option<Spanned<RoundShape>>,
    pub velocity: Option<Spanned<Vec<f64>>>,
    pub velocity_gradient: Option<Spanned<Vec<Vec<f64>>>>,
    pub velocity_origin: Option<Spanned<Vec<f64>>>,
    /// Keep only the lattice points inside this box (e.g. a quarter of a cylinder).
    pub clip: Option<Spanned<BoxShape>>,
    /// ... or several in `[[body.shape]]` tables.
    #[serde(default)]
    pub shape: Vec<ShapeTable>,
    /// Holes and notches: `[[body.cut]]` tables whose lattice points are removed.
    #[serde(default)]
    pub cut: Vec<CutTable>,
    /// Uniform initial Cauchy stress (its value at the origin with a gradient).
    pub initial_stress: Option<Spanned<StressComponents>>,
    /// Gradient of the initial stress: per component, its derivatives along x, y, z.
    pub initial_stress_gradient: Option<Spanned<StressGradients>>,
    /// An initial stress field read from a CSV file of sample points.
    pub initial_stress_file: Option<Spanned<FieldFileTable>>,
    /// An initial velocity field read from a CSV file of sample points.
    pub initial_velocity_file: Option<Spanned<FieldFileTable>>,
    /// Uniform effective plastic strain of every particle at t = 0 (a work-hardened part).
    pub initial_plastic_strain: Option<Spanned<f64>>,
    /// An effective plastic strain field read from a CSV file of sample points.
    pub initial_plastic_strain_file: Option<Spanned<FieldFileTable>>,
    /// Uniform softening damage D of every particle at t = 0 (a part damaged before).
    pub initial_damage: Option<Spanned<f64>>,
    /// A damage field read from a CSV file of sample points.
    pub initial_damage_file: Option<Spanned<FieldFileTable>>,
    /// Uniform Johnson–Cook cumulative (failure) damage of every particle at t = 0.
    pub initial_failure_damage: Option<Spanned<f64>>,
    /// A Johnson–Cook failure damage field read from a CSV file of sample points.
    pub initial_failure_damage_file: Option<Spanned<FieldFileTable>>,
}

/// `initial_stress_file = { path = "residual.csv", reach = 2e-3, interpolation = "linear" }`
/// (or `initial_velocity_file`): the table to read (relative to the scene file's folder), how
/// far the samples a particle takes its values from may lie (default: the body's spacing, twice
/// that for `linear`), and how they give its values (`nearest`, the default, or `linear`).
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct FieldFileTable {
    pub path: Spanned<String>,
    pub reach: Option<Spanned<f64>>,
    pub interpolation: Option<Spanned<String>>,
}

/// `initial_stress_gradient = { yy = [0.0, 7.7e4], ... }`: per stress component its D
/// derivatives ∂σ/∂X_k, absent = 0.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct StressGradients {
    pub xx: Option<Vec<f64>>,
    pub yy: Option<Vec<f64>>,
    pub zz: Option<Vec<f64>>,
    pub xy: Option<Vec<f64>>,
    pub yz: Option<Vec<f64>>,
    pub xz: Option<Vec<f64>>,
}

/// `initial_stress = { xx = .., yy = .., ... }`: components of a symmetric stress, absent = 0.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct StressComponents {
    pub xx: Option<f64>,
    pub yy: Option<f64>,
    pub zz: Option<f64>,
    pub xy: Option<f64>,
    pub yz: Option<f64>,
    pub xz: Option<f64>,
}

/// `[[body.cut]]`: a region removed from the body after all its shapes are filled.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct CutTable {
    #[serde(rename = "box")]
    pub box_: Option<Spanned<BoxShape>>,
    pub cylinder: Option<Spanned<CylinderShape>>,
    pub sphere: Option<Spanned<RoundShape>>,
    pub disc: Option<Spanned<RoundShape>>,
    /// Rings of particles that follow the rim of a disc cut (2D), replacing the lattice there.
    pub rings: Option<Spanned<i64>>,
}

/// One shape of a body with its own initial velocity field.
#[derive(Debug, Deserialize, Clone, Default)]
#[serde(deny_unknown_fields)]
pub(crate) struct ShapeTable {
    #[serde(rename = "box")]
    pub box_: Option<Spanned<BoxShape>>,
    pub cylinder: Option<Spanned<CylinderShape>>,
    pub sphere: Option<Spanned<RoundShape>>,
    pub disc: Option<Spanned<RoundShape>>,
    pub velocity: Option<Spanned<Vec<f64>>>,
    pub velocity_gradient: Option<Spanned<Vec<Vec<f64>>>>,
    pub velocity_origin: Option<Spanned<Vec<f64>>>,
    /// Keep only the lattice points inside this box (e.g. a quarter of a cylinder).
    pub clip: Option<Spanned<BoxShape>>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct BoxShape {
    pub min: Vec<f64>,
    pub max: Vec<f64>,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct CylinderShape {
    /// Centre of the base disc.
    pub base: Vec<f64>,
    /// "x", "y" or "z".
    pub axis: String,
    pub radius: f64,
    pub length: f64,
}

#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(crate) struct RoundShape {
    pub centre: Vec<f64>,
    pub radius: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BoundaryTable {
    pub name: Spanned<String>,
    pub body: Spanned<String>,
    #[serde(rename = "box")]
    pub box_: Option<Spanned<BoxShape>>,
    pub at: Option<Spanned<Vec<f64>>>,
    #[serde(default)]
    pub fixed: Option<Spanned<bool>>,
    pub velocity: Option<Spanned<Vec<f64>>>,
    pub components: Option<Spanned<Vec<String>>>,
    pub ramp_time: Option<Spanned<f64>>,
    pub ramp_shape: Option<Spanned<String>>,
    pub amplitude: Option<Spanned<Vec<Vec<f64>>>>,
    pub amplitude_shape: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ProbeTable {
    pub name: Spanned<String>,
    pub body: Spanned<String>,
    pub at: Spanned<Vec<f64>>,
    pub fields: Spanned<Vec<String>>,
    pub interval: Spanned<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct OutputTable {
    pub dir: Option<Spanned<String>>,
    pub energy_interval: Option<Spanned<f64>>,
    pub frame_interval: Option<Spanned<f64>>,
}
