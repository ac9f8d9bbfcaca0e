//! Reading a scene: parse the TOML, check every value, build particles from shapes, and turn
//! it into a solver `Model`. Every error names the file, line, column and field.

use crate::geometry::{fill_shape, hole_rings, sampled_cell_volumes, Shape};
use crate::scene_field_file::{FieldSamples, Interpolation, SampleMapping};
use crate::scene_file::{
    BodyTable, BoundaryTable, FieldFileTable, ProbeTable, SceneFile, ShapeTable, StabilityTable,
    StressComponents, StressGradients,
};
use crate::scene_wall::build_wall;
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};
use tlsph_kernels::KernelKind;
use tlsph_math::{Tensor, Vector};
use tlsph_solver::stability::StabilityThresholds;
use tlsph_solver::{
    Amplitude, AmplitudeTable, ArtificialStress, BodyDescription, BodyForceDescription,
    BoundaryDescription, BulkViscosity, ContactDescription, EffectsDescription, Formulation,
    FrictionCoefficients, MaterialDescription, MaterialModel, Model, ParticleField,
    PenaltyContactDescription, PressureModel, RampShape, ReferenceSupport, SimulationConfig,
    StressUpdate, SymmetryPlane, TableShape, VelocityRamp,
};
use toml::Spanned;

/// A scene that cannot be run, located in its file.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// Scene file (or `<string>` for scenes given as text).
    pub file: String,
    /// 1-based line of the offending value, when known.
    pub line: Option<usize>,
    /// 1-based column of the offending value, when known.
    pub column: Option<usize>,
    /// Dotted path of the field, e.g. `material[plate].poisson_ratio`.
    pub field: String,
    /// What is wrong and what is expected.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(column) = self.column {
                write!(f, ":{column}")?;
            }
        }
        if self.field.is_empty() {
            write!(f, ": {}", self.message)
        } else {
            write!(f, ": {}: {}", self.field, self.message)
        }
    }
}

impl std::error::Error for SceneError {}

/// A probe: fields sampled at the particle nearest to a point of the reference configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeSpec {
    /// Name; the CSV is `probes/<name>.csv`.
    pub name: String,
    /// Body index.
    pub body: usize,
    /// Particle index within the body.
    pub particle: usize,
    /// Sampled fields, in column order.
    pub fields: Vec<ParticleField>,
    /// Sampling interval \[s\]; a sample is taken at the first step at or after each multiple.
    pub interval: f64,
}

/// Where and how often whole-model histories are written.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputSpec {
    /// Output folder (relative paths are relative to the working directory).
    pub dir: PathBuf,
    /// Interval of `energy.csv` / `momentum.csv` rows \[s\].
    pub energy_interval: f64,
    /// Interval of VTK particle frames (`frames/*.vtu`, `frames.pvd`) \[s\]; `None` for none.
    pub frame_interval: Option<f64>,
    /// Thresholds of the stability report (`stability.csv`, `[stability]` of `summary.toml`).
    pub stability: StabilityThresholds,
}

/// A solver model in the scene's dimension.
#[derive(Debug, Clone)]
pub enum DimensionModel {
    /// 1D (uniaxial strain).
    One(Model<1>),
    /// 2D (plane strain).
    Two(Model<2>),
    /// 3D.
    Three(Model<3>),
}

/// A checked scene, ready to run.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Where it came from (for messages).
    pub origin: String,
    /// The model for the solver.
    pub model: DimensionModel,
    /// Probes.
    pub probes: Vec<ProbeSpec>,
    /// Output settings.
    pub output: OutputSpec,
    /// How each field table read met its body's particles, in scene order (empty when no
    /// table was read, e.g. by [`load_scene_without_field_tables`]).
    pub field_tables: Vec<FieldTableSummary>,
}

/// How a field table (`initial_stress_file`, `initial_velocity_file`,
/// `initial_plastic_strain_file`, `initial_damage_file`, `initial_failure_damage_file`) met its
/// body's particles, as `tlsph check` reports it: how many samples each particle's value came
/// from, how far the nearest sample lay, and how many samples no particle used (a table
/// reaching beyond the body, or misplaced).
#[derive(Debug, Clone, PartialEq)]
pub struct FieldTableSummary {
    /// The scene key, e.g. `body[plate].initial_stress_file`.
    pub field: String,
    /// The table's file.
    pub path: PathBuf,
    /// Samples (data rows) read.
    pub samples: usize,
    /// `"nearest"` or `"linear"`.
    pub interpolation: &'static str,
    /// The `reach` used \[length\].
    pub reach: f64,
    /// Fewest and most samples a particle's value came from ((1, 1) for the nearest sample).
    pub samples_per_particle: (usize, usize),
    /// Largest distance from a particle to its nearest sample \[length\].
    pub farthest_nearest_sample: f64,
    /// Samples that no particle's value came from.
    pub unused_samples: usize,
}

impl Scene {
    /// Spatial dimension.
    pub fn dimension(&self) -> usize {
        match self.model {
            DimensionModel::One(_) => 1,
            DimensionModel::Two(_) => 2,
            DimensionModel::Three(_) => 3,
        }
    }

    /// Total particle count.
    pub fn n_particles(&self) -> usize {
        match &self.model {
            DimensionModel::One(m) => m.bodies.iter().map(|b| b.positions.len()).sum(),
            DimensionModel::Two(m) => m.bodies.iter().map(|b| b.positions.len()).sum(),
            DimensionModel::Three(m) => m.bodies.iter().map(|b| b.positions.len()).sum(),
        }
    }

    /// Reference positions of the particles of the body named `body`, in particle order, each
    /// as its D coordinates (the rows of an `initial_stress_file` or `initial_velocity_file`
    /// template); `None` if no body has that name.
    pub fn body_positions(&self, body: &str) -> Option<Vec<Vec<f64>>> {
        fn rows<const D: usize>(m: &Model<D>, body: &str) -> Option<Vec<Vec<f64>>> {
            let b = m.bodies.iter().find(|b| b.name == body)?;
            Some(
                b.positions
                    .iter()
                    .map(|x| x.iter().copied().collect())
                    .collect(),
            )
        }
        match &self.model {
            DimensionModel::One(m) => rows(m, body),
            DimensionModel::Two(m) => rows(m, body),
            DimensionModel::Three(m) => rows(m, body),
        }
    }

    /// Names of the bodies, in file order.
    pub fn body_names(&self) -> Vec<String> {
        fn names<const D: usize>(m: &Model<D>) -> Vec<String> {
            m.bodies.iter().map(|b| b.name.clone()).collect()
        }
        match &self.model {
            DimensionModel::One(m) => names(m),
            DimensionModel::Two(m) => names(m),
            DimensionModel::Three(m) => names(m),
        }
    }

    /// Simulated end time \[s\].
    pub fn end_time(&self) -> f64 {
        match &self.model {
            DimensionModel::One(m) => m.config.end_time,
            DimensionModel::Two(m) => m.config.end_time,
            DimensionModel::Three(m) => m.config.end_time,
        }
    }
}

/// Reads and checks a scene file.
/// Files the scene names (an `initial_stress_file` or `initial_velocity_file`) are read
/// relative to its folder.
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    load_scene_reading(path, true)
}

/// Reads and checks a scene file like [`load_scene`] but leaves out the tables of initial
/// fields (`initial_stress_file`, `initial_velocity_file`): the bodies start as if those keys
/// were absent. The particles do not depend on the tables, so this is how the template of a
/// table (`tlsph particles`) is written before the table exists.
pub fn load_scene_without_field_tables(path: &Path) -> Result<Scene, SceneError> {
    load_scene_reading(path, false)
}

/// [`load_scene`], reading the tables of initial fields or not.
fn load_scene_reading(path: &Path, read_field_tables: bool) -> Result<Scene, SceneError> {
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| SceneError {
        file: origin.clone(),
        line: None,
        column: None,
        field: String::new(),
        message: format!("cannot read the file: {e}"),
    })?;
    let folder = path.parent().unwrap_or(Path::new(""));
    parse_scene_in(&text, &origin, folder, read_field_tables)
}

/// Parses and checks scene text; `origin` names it in errors. Files the scene names are read
/// relative to the working directory.
pub fn parse_scene(text: &str, origin: &str) -> Result<Scene, SceneError> {
    parse_scene_in(text, origin, Path::new(""), true)
}

/// Parses and checks scene text whose relative file names are relative to `folder`, reading
/// the tables of initial fields if `read_field_tables`.
fn parse_scene_in(
    text: &str,
    origin: &str,
    folder: &Path,
    read_field_tables: bool,
) -> Result<Scene, SceneError> {
    let ctx = Context {
        text,
        origin,
        folder,
        read_field_tables,
        field_tables: Default::default(),
    };
    let file: SceneFile = toml::from_str(text).map_err(|e| {
        let (line, column) = match e.span() {
            Some(span) => {
                let (l, c) = ctx.line_col(span.start);
                (Some(l), Some(c))
            }
            None => (None, None),
        };
        SceneError {
            file: origin.to_string(),
            line,
            column,
            field: String::new(),
            message: e.message().trim().to_string(),
        }
    })?;
    let dimension = *file.simulation.dimension.get_ref();
    match dimension {
        1 => build::<1>(&ctx, &file).map(|(m, p, o)| ctx.scene(DimensionModel::One(m), p, o)),
        2 => build::<2>(&ctx, &file).map(|(m, p, o)| ctx.scene(DimensionModel::Two(m), p, o)),
        3 => build::<3>(&ctx, &file).map(|(m, p, o)| ctx.scene(DimensionModel::Three(m), p, o)),
        other => Err(ctx.error(
            &file.simulation.dimension.span(),
            "simulation.dimension",
            format!("must be 1, 2 or 3, got {other}"),
        )),
    }
}

pub(crate) struct Context<'a> {
    text: &'a str,
    origin: &'a str,
    /// Folder that relative file names in the scene are relative to.
    folder: &'a Path,
    /// Whether `initial_stress_file` and `initial_velocity_file` tables are read (or the keys
    /// left out, for [`load_scene_without_field_tables`]).
    read_field_tables: bool,
    /// What each field table read met ([`Scene::field_tables`]).
    field_tables: std::cell::RefCell<Vec<FieldTableSummary>>,
}

impl Context<'_> {
    fn line_col(&self, offset: usize) -> (usize, usize) {
        let before = &self.text[..offset.min(self.text.len())];
        let line = before.matches('\n').count() + 1;
        let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
        (line, column)
    }

    pub(crate) fn error(&self, span: &Range<usize>, field: &str, message: String) -> SceneError {
        let (line, column) = self.line_col(span.start);
        SceneError {
            file: self.origin.to_string(),
            line: Some(line),
            column: Some(column),
            field: field.to_string(),
            message,
        }
    }

    /// Checks that `name` is a plain name (letters, digits, `-`, `_`, `.`, not first), as a
    /// file name or CSV column needs; the error says what the name `is_for`.
    fn plain_name(
        &self,
        name: &Spanned<String>,
        field: &str,
        is_for: &str,
    ) -> Result<(), SceneError> {
        if is_safe_file_stem(name.get_ref()) {
            return Ok(());
        }
        Err(self.error(
            &name.span(),
            field,
            format!(
                "`{}` {is_for}: use letters, digits, `-`, `_` and `.` (not first), at most {MAX_NAME_LENGTH} characters",
                name.get_ref()
            ),
        ))
    }

    fn scene(&self, model: DimensionModel, probes: Vec<ProbeSpec>, output: OutputSpec) -> Scene {
        Scene {
            origin: self.origin.to_string(),
            model,
            probes,
            output,
            field_tables: self.field_tables.take(),
        }
    }

    /// A finite value ≥ 0, or an error at its span.
    pub(crate) fn non_negative(
        &self,
        value: &Spanned<f64>,
        field: &str,
    ) -> Result<f64, SceneError> {
        let v = *value.get_ref();
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.error(
                &value.span(),
                field,
                format!("must be a finite number ≥ 0, got {v}"),
            ))
        }
    }

    /// The friction of the table at `prefix` (a wall or the contact) from its keys `friction`
    /// (kinetic μ ≥ 0, default 0), `static_friction` (μ_s ≥ μ, default μ) and
    /// `friction_decay` (d_c ≥ 0, only with μ_s > μ).
    pub(crate) fn friction_coefficients(
        &self,
        friction: &Option<Spanned<f64>>,
        static_friction: &Option<Spanned<f64>>,
        friction_decay: &Option<Spanned<f64>>,
        prefix: &str,
    ) -> Result<FrictionCoefficients, SceneError> {
        let kinetic = match friction {
            Some(mu) => self.non_negative(mu, &format!("{prefix}.friction"))?,
            None => 0.0,
        };
        let static_coefficient = match static_friction {
            Some(mu) => {
                let field = format!("{prefix}.static_friction");
                let value = self.non_negative(mu, &field)?;
                if value < kinetic {
                    return Err(self.error(
                        &mu.span(),
                        &field,
                        format!(
                            "must be ≥ the (kinetic) `friction` {kinetic}: a surface held at rest resists at least as much as one sliding"
                        ),
                    ));
                }
                Some(value)
            }
            None => None,
        };
        let decay = match friction_decay {
            Some(d) => {
                let field = format!("{prefix}.friction_decay");
                let value = self.non_negative(d, &field)?;
                if static_coefficient.is_none_or(|mu_s| mu_s == kinetic) {
                    return Err(self.error(
                        &d.span(),
                        &field,
                        format!(
                            "needs a `static_friction` above `friction` {kinetic}: the decay takes the sliding coefficient from the static to the kinetic one"
                        ),
                    ));
                }
                Some(value)
            }
            None => None,
        };
        Ok(FrictionCoefficients {
            kinetic,
            static_coefficient: static_coefficient.unwrap_or(kinetic),
            decay,
        })
    }

    pub(crate) fn positive(&self, value: &Spanned<f64>, field: &str) -> Result<f64, SceneError> {
        let v = *value.get_ref();
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.error(
                &value.span(),
                field,
                format!("must be a finite number > 0, got {v}"),
            ))
        }
    }

    /// An optional keyword key: `default` when absent, else the value paired with the word in
    /// `choices`; an unknown word is an error naming `field` and listing the choices, e.g.
    /// "unknown ramp shape `steep` (expected \"smooth\" or \"linear\")".
    pub(crate) fn keyword<T: Copy>(
        &self,
        value: Option<&Spanned<String>>,
        field: &str,
        what: &str,
        default: T,
        choices: &[(&str, T)],
    ) -> Result<T, SceneError> {
        let Some(value) = value else {
            return Ok(default);
        };
        let word = value.get_ref().as_str();
        match choices.iter().find(|(name, _)| *name == word) {
            Some(&(_, choice)) => Ok(choice),
            None => {
                let names: Vec<String> = choices.iter().map(|(n, _)| format!("\"{n}\"")).collect();
                Err(self.error(
                    &value.span(),
                    field,
                    format!("unknown {what} `{word}` (expected {})", names.join(" or ")),
                ))
            }
        }
    }

    /// Indices of the bodies named in `names` (each must exist).
    fn body_indices<const D: usize>(
        &self,
        names: &Spanned<Vec<String>>,
        field: &str,
        bodies: &[BodyDescription<D>],
    ) -> Result<Vec<usize>, SceneError> {
        names
            .get_ref()
            .iter()
            .map(|name| {
                bodies.iter().position(|b| &b.name == name).ok_or_else(|| {
                    self.error(&names.span(), field, format!("no body named `{name}`"))
                })
            })
            .collect()
    }

    pub(crate) fn vector<const D: usize>(
        &self,
        value: &Spanned<Vec<f64>>,
        field: &str,
    ) -> Result<Vector<D>, SceneError> {
        self.components(value.get_ref(), &value.span(), field)
    }

    fn components<const D: usize>(
        &self,
        v: &[f64],
        span: &Range<usize>,
        field: &str,
    ) -> Result<Vector<D>, SceneError> {
        if v.len() != D {
            return Err(self.error(
                span,
                field,
                format!("needs {D} components in a {D}D scene, got {}", v.len()),
            ));
        }
        if !v.iter().all(|x| x.is_finite()) {
            return Err(self.error(span, field, "components must be finite numbers".into()));
        }
        Ok(Vector::<D>::from_iterator(v.iter().copied()))
    }
}

/// Thresholds from `[stability]`, defaults where a key is absent; the minimum ratio must be
/// in (0, 1), the maximum above 1, the others > 0.
fn stability_thresholds(
    ctx: &Context<'_>,
    table: Option<&StabilityTable>,
) -> Result<StabilityThresholds, SceneError> {
    let mut t = StabilityThresholds::default();
    let Some(table) = table else {
        return Ok(t);
    };
    if let Some(v) = &table.min_neighbour_ratio {
        t.min_neighbour_ratio = ctx.positive(v, "stability.min_neighbour_ratio")?;
        if t.min_neighbour_ratio >= 1.0 {
            return Err(ctx.error(
                &v.span(),
                "stability.min_neighbour_ratio",
                format!("must be below 1, got {}", t.min_neighbour_ratio),
            ));
        }
    }
    if let Some(v) = &table.max_neighbour_ratio {
        t.max_neighbour_ratio = ctx.positive(v, "stability.max_neighbour_ratio")?;
        if t.max_neighbour_ratio <= 1.0 {
            return Err(ctx.error(
                &v.span(),
                "stability.max_neighbour_ratio",
                format!("must be above 1, got {}", t.max_neighbour_ratio),
            ));
        }
    }
    if let Some(v) = &table.clumping_index {
        t.clumping_index = ctx.positive(v, "stability.clumping_index")?;
    }
    if let Some(v) = &table.energy_drift {
        t.energy_drift = ctx.positive(v, "stability.energy_drift")?;
    }
    Ok(t)
}

type Built<const D: usize> = (Model<D>, Vec<ProbeSpec>, OutputSpec);

fn build<const D: usize>(ctx: &Context<'_>, file: &SceneFile) -> Result<Built<D>, SceneError> {
    let sim = &file.simulation;
    let formulation = match sim.formulation.get_ref().as_str() {
        "total-lagrangian" => Formulation::TotalLagrangian,
        "total-lagrangian-corrected" => Formulation::TotalLagrangianCorrected,
        "updated-lagrangian" => Formulation::UpdatedLagrangian,
        other => {
            return Err(ctx.error(
                &sim.formulation.span(),
                "simulation.formulation",
                format!("unknown formulation `{other}`; use `total-lagrangian`, `total-lagrangian-corrected` or `updated-lagrangian`"),
            ))
        }
    };
    let stress_update = match sim
        .stress_update
        .as_ref()
        .map(|s| (s.get_ref().as_str(), s.span()))
    {
        None | Some(("jaumann-rate", _)) => StressUpdate::JaumannRate,
        Some(("green-lagrange", _)) => StressUpdate::GreenLagrange,
        Some((other, span)) => {
            return Err(ctx.error(
                &span,
                "simulation.stress_update",
                format!("unknown stress update `{other}`; use `jaumann-rate` or `green-lagrange`"),
            ))
        }
    };
    let kernel: KernelKind =
        sim.kernel
            .get_ref()
            .parse()
            .map_err(|e: <KernelKind as std::str::FromStr>::Err| {
                ctx.error(&sim.kernel.span(), "simulation.kernel", e.to_string())
            })?;
    let smoothing_factor = ctx.positive(&sim.smoothing_factor, "simulation.smoothing_factor")?;
    let cfl = ctx.positive(&sim.cfl, "simulation.cfl")?;
    if cfl > 1.0 {
        return Err(ctx.error(
            &sim.cfl.span(),
            "simulation.cfl",
            format!("must be at most 1, got {cfl}"),
        ));
    }
    let end_time = ctx.positive(&sim.end_time, "simulation.end_time")?;
    let config = SimulationConfig {
        formulation,
        stress_update,
        kernel,
        smoothing_factor,
        cfl,
        end_time,
    };

    let mut materials = Vec::with_capacity(file.material.len());
    for m in &file.material {
        let name = m.name.get_ref().clone();
        if materials
            .iter()
            .any(|x: &MaterialDescription| x.name == name)
        {
            return Err(ctx.error(
                &m.name.span(),
                "material.name",
                format!("material `{name}` is defined twice"),
            ));
        }
        let field = |key: &str| format!("material[{name}].{key}");
        let density = ctx.positive(&m.density, &field("density"))?;
        let model = crate::scene_material::material_model(ctx, m, &field)?;
        materials.push(MaterialDescription {
            name,
            density,
            model,
        });
    }

    let mut bodies: Vec<BodyDescription<D>> = Vec::with_capacity(file.body.len());
    for b in &file.body {
        let body = build_body::<D>(ctx, b, &materials)?;
        if bodies.iter().any(|x| x.name == body.name) {
            return Err(ctx.error(
                &b.name.span(),
                "body.name",
                format!("body `{}` is defined twice", body.name),
            ));
        }
        if stress_update == StressUpdate::GreenLagrange {
            let given = (b
                .initial_stress
                .as_ref()
                .map(|t| ("initial_stress", t.span())))
            .or_else(|| {
                (b.initial_stress_gradient.as_ref()).map(|t| ("initial_stress_gradient", t.span()))
            })
            .or_else(|| {
                (b.initial_stress_file.as_ref()).map(|t| ("initial_stress_file", t.span()))
            });
            if let Some((key, span)) = given {
                return Err(ctx.error(
                    &span,
                    &format!("body[{}].{key}", body.name),
                    "needs stress_update = \"jaumann-rate\" (the Green-Lagrange path computes stress from F alone)".into(),
                ));
            }
        }
        bodies.push(body);
    }
    if let Some((later, earlier, how)) = first_overlap(&bodies) {
        let (a, b) = (&bodies[earlier].name, &bodies[later].name);
        let what = match how {
            Overlap::TooClose(at, distance) => format!(
                "starts inside body `{a}`: its particle at [{}] is {distance:.3e} from one of `{a}`'s, less than half the smaller spacing",
                point_text(&at)
            ),
            Overlap::Embedded(at, owner) if owner == later => format!(
                "starts inside body `{a}`: the cell of its particle at [{}] (the cube of side `spacing` around it) lies within the cells of `{a}`'s particles",
                point_text(&at)
            ),
            Overlap::Embedded(at, _) => format!(
                "starts around body `{a}`: the cell of `{a}`'s particle at [{}] (the cube of side `spacing` around it) lies within the cells of `{b}`'s particles",
                point_text(&at)
            ),
        };
        return Err(ctx.error(
            &file.body[later].name.span(),
            &format!("body[{b}]"),
            format!("{what}; bodies must not overlap (leave at least one spacing between their outer particle rows)"),
        ));
    }
    if bodies.is_empty() {
        return Err(SceneError {
            file: ctx.origin.to_string(),
            line: None,
            column: None,
            field: "body".into(),
            message: "the scene has no [[body]]".into(),
        });
    }
    if stress_update == StressUpdate::GreenLagrange {
        if let Some(b) = bodies.iter().find(|b| {
            let model = &materials[b.material].model;
            model.has_plastic_strain() || model.softening_damage().is_some()
        }) {
            let span = sim
                .stress_update
                .as_ref()
                .map_or(sim.formulation.span(), |s| s.span());
            return Err(ctx.error(
                &span,
                "simulation.stress_update",
                format!(
                    "body `{}` is elastic-plastic or damaged, which needs \"jaumann-rate\" (the Green-Lagrange path is hyperelastic only)",
                    b.name
                ),
            ));
        }
    }
    let find_body = |name: &Spanned<String>, field: &str| {
        bodies
            .iter()
            .position(|b| &b.name == name.get_ref())
            .ok_or_else(|| {
                ctx.error(
                    &name.span(),
                    field,
                    format!("no body named `{}`", name.get_ref()),
                )
            })
    };

    let mut boundaries: Vec<BoundaryDescription<D>> = Vec::with_capacity(file.boundary.len());
    for t in &file.boundary {
        if boundaries.iter().any(|b| &b.name == t.name.get_ref()) {
            return Err(ctx.error(
                &t.name.span(),
                "boundary.name",
                format!("boundary `{}` is defined twice", t.name.get_ref()),
            ));
        }
        // The name heads CSV columns (`boundary_<name>`): no separators or quotes in it.
        ctx.plain_name(
            &t.name,
            "boundary.name",
            "names columns of energy.csv and boundaries.csv",
        )?;
        let body = find_body(&t.body, &format!("boundary[{}].body", t.name.get_ref()))?;
        boundaries.push(build_boundary::<D>(ctx, t, body, &bodies[body])?);
    }

    let mut probes = Vec::with_capacity(file.probe.len());
    for t in &file.probe {
        let body = find_body(&t.body, &format!("probe[{}].body", t.name.get_ref()))?;
        ctx.plain_name(&t.name, "probe.name", "cannot be a file name")?;
        if probes
            .iter()
            .any(|p: &ProbeSpec| &p.name == t.name.get_ref())
        {
            return Err(ctx.error(
                &t.name.span(),
                "probe.name",
                format!("probe `{}` is defined twice", t.name.get_ref()),
            ));
        }
        probes.push(build_probe::<D>(ctx, t, body, &bodies[body], &materials)?);
    }

    let mut effects = EffectsDescription::<D>::default();
    for w in &file.wall {
        let name = w.name.get_ref().clone();
        if !is_safe_file_stem(&name) || effects.walls.iter().any(|x| x.name == name) {
            return Err(ctx.error(
                &w.name.span(),
                "wall.name",
                format!("`{name}` must be unique and a plain name (letters, digits, -, _, .)"),
            ));
        }
        let wall = build_wall(ctx, w, name, &bodies, &file.symmetry_plane)?;
        effects.walls.push(wall);
    }
    for plane in &file.symmetry_plane {
        let axis = axis_index(plane.axis.get_ref()).unwrap_or(D);
        if axis >= D {
            let axes = ["x", "y", "z"][..D].join(", ");
            return Err(ctx.error(
                &plane.axis.span(),
                "symmetry_plane.axis",
                format!(
                    "`{}` is not an axis of a {D}D scene (axes: {axes})",
                    plane.axis.get_ref()
                ),
            ));
        }
        if effects.symmetry_planes.iter().any(|p| p.axis == axis) {
            return Err(ctx.error(
                &plane.axis.span(),
                "symmetry_plane.axis",
                format!(
                    "a second plane normal to `{}`: a model has at most one symmetry plane per axis (two parallel planes would mirror each other's images without end)",
                    plane.axis.get_ref()
                ),
            ));
        }
        let position = *plane.position.get_ref();
        if !position.is_finite() {
            return Err(ctx.error(
                &plane.position.span(),
                "symmetry_plane.position",
                "must be finite".into(),
            ));
        }
        let mut modelled_side: Option<(&str, bool)> = None;
        for b in &bodies {
            let above = b.positions.iter().all(|x| x[axis] > position);
            let below = b.positions.iter().all(|x| x[axis] < position);
            if !(above || below) {
                return Err(ctx.error(
                    &plane.position.span(),
                    "symmetry_plane.position",
                    format!("body `{}` has particles on both sides of, or on, this plane; model only one side", b.name),
                ));
            }
            // Closer than a quarter spacing, a particle would sit within half a spacing of
            // its own image (the solver's rule, checked here to name the line).
            let limit = tlsph_solver::MIN_PLANE_DISTANCE * b.spacing;
            if let Some(x) = b
                .positions
                .iter()
                .find(|x| (x[axis] - position).abs() < limit)
            {
                return Err(ctx.error(
                    &plane.position.span(),
                    "symmetry_plane.position",
                    format!(
                        "body `{}` has a particle at [{}], {:.3e} from this plane: less than a quarter of its spacing ({}), so within half a spacing of its own mirror image; put the particles next to the plane half a spacing from it (as `clip` and a box face on the plane do)",
                        b.name,
                        point_text(x),
                        (x[axis] - position).abs(),
                        b.spacing
                    ),
                ));
            }
            match modelled_side {
                None => modelled_side = Some((&b.name, above)),
                Some((first, side)) if side != above => {
                    return Err(ctx.error(
                        &plane.position.span(),
                        "symmetry_plane.position",
                        format!("body `{}` lies on the other side of this plane than body `{first}`; a symmetry model keeps every body on the modelled side (the plane mirrors each into the other half)", b.name),
                    ));
                }
                Some(_) => {}
            }
        }
        effects
            .symmetry_planes
            .push(SymmetryPlane { axis, position });
    }
    if let Some(v) = &file.bulk_viscosity {
        effects.bulk_viscosity = Some(BulkViscosity {
            quadratic: ctx.non_negative(&v.quadratic, "bulk_viscosity.quadratic")?,
            linear: ctx.non_negative(&v.linear, "bulk_viscosity.linear")?,
        });
        if stress_update == StressUpdate::GreenLagrange {
            return Err(ctx.error(
                &v.quadratic.span(),
                "bulk_viscosity",
                "needs stress_update = \"jaumann-rate\"".into(),
            ));
        }
    }
    if let Some(v) = &file.artificial_viscosity {
        let alpha = ctx.non_negative(&v.alpha, "artificial_viscosity.alpha")?;
        let beta = ctx.non_negative(&v.beta, "artificial_viscosity.beta")?;
        effects.pairwise_viscosity = Some((alpha, beta));
    }
    if let Some(x) = &file.xsph {
        let epsilon = *x.epsilon.get_ref();
        if !(epsilon.is_finite() && epsilon > 0.0 && epsilon <= 1.0) {
            return Err(ctx.error(
                &x.epsilon.span(),
                "xsph.epsilon",
                format!("must be in (0, 1], got {epsilon}"),
            ));
        }
        if let Some(b) = bodies
            .iter()
            .find(|b| materials[b.material].model.has_damage())
        {
            return Err(ctx.error(
                &x.epsilon.span(),
                "xsph",
                format!(
                    "cannot be combined with a damage or failure model yet (material `{}` of body `{}` has one; the XSPH averages would keep failed particles in)",
                    materials[b.material].name, b.name
                ),
            ));
        }
        effects.xsph = Some(epsilon);
    }
    let updated_lagrangian = formulation == Formulation::UpdatedLagrangian;
    if let Some(a) = &file.artificial_stress {
        if !updated_lagrangian {
            return Err(ctx.error(
                &a.span(),
                "artificial_stress",
                "needs formulation = \"updated-lagrangian\" (TLSPH has no tensile instability to correct)".into(),
            ));
        }
        let a = a.get_ref();
        let or_default = |v: &Option<Spanned<f64>>, field: &str, default: f64| {
            v.as_ref().map_or(Ok(default), |v| ctx.positive(v, field))
        };
        let carriers = match &a.bodies {
            None => None,
            Some(names) => Some(ctx.body_indices(names, "artificial_stress.bodies", &bodies)?),
        };
        effects.artificial_stress = Some(ArtificialStress {
            epsilon: or_default(&a.epsilon, "artificial_stress.epsilon", 0.3)?,
            exponent: or_default(&a.exponent, "artificial_stress.exponent", 6.0)?,
            bodies: carriers,
        });
    }
    if let Some((b, group)) = file
        .body
        .iter()
        .find_map(|b| b.kernel_group.as_ref().map(|g| (b, g)))
    {
        if !updated_lagrangian {
            return Err(ctx.error(
                &group.span(),
                &format!("body[{}].kernel_group", b.name.get_ref()),
                "needs formulation = \"updated-lagrangian\" (TLSPH bodies interact only through contact)".into(),
            ));
        }
        if let Some((b, g)) = file.body.iter().find_map(|b| {
            b.kernel_group
                .as_ref()
                .filter(|g| g.get_ref().trim().is_empty())
                .map(|g| (b, g))
        }) {
            return Err(ctx.error(
                &g.span(),
                &format!("body[{}].kernel_group", b.name.get_ref()),
                "must be a non-empty name".into(),
            ));
        }
        // Group names: the explicit one, else the material name; indices by first appearance.
        let mut names: Vec<&str> = Vec::new();
        let groups = file
            .body
            .iter()
            .map(|b| {
                let name = b
                    .kernel_group
                    .as_ref()
                    .map_or(b.material.get_ref().as_str(), |g| g.get_ref().as_str());
                match names.iter().position(|n| *n == name) {
                    Some(k) => k,
                    None => {
                        names.push(name);
                        names.len() - 1
                    }
                }
            })
            .collect();
        effects.kernel_groups = Some(groups);
    }
    if let Some(c) = &file.contact {
        match build_contact(
            ctx,
            c,
            &bodies,
            effects.kernel_groups.as_deref(),
            updated_lagrangian,
        )? {
            Contact::Potential(c) => effects.contact = Some(c),
            Contact::Penalty(c) => effects.penalty_contact = Some(c),
        }
    }
    if let Some(h) = &file.hourglass_control {
        if updated_lagrangian {
            return Err(ctx.error(
                &h.coefficient.span(),
                "hourglass_control",
                "not available with formulation = \"updated-lagrangian\" (it corrects the reference-bond F of TLSPH); use [artificial_viscosity]".into(),
            ));
        }
        effects.hourglass_control =
            Some(ctx.positive(&h.coefficient, "hourglass_control.coefficient")?);
    }
    if let Some(f) = &file.body_force {
        let acceleration = ctx.vector::<D>(&f.acceleration, "body_force.acceleration")?;
        if let Some(plane) = file
            .symmetry_plane
            .iter()
            .find(|p| axis_index(p.axis.get_ref()).is_some_and(|a| a < D && acceleration[a] != 0.0))
        {
            return Err(ctx.error(
                &f.acceleration.span(),
                "body_force.acceleration",
                format!(
                    "has a component along {}, the normal of a symmetry plane: the mirrored half would be pulled the other way, so the model is not symmetric",
                    plane.axis.get_ref()
                ),
            ));
        }
        let selected = match &f.bodies {
            None => None,
            Some(names) => {
                if names.get_ref().is_empty() {
                    return Err(ctx.error(
                        &names.span(),
                        "body_force.bodies",
                        "lists no body; omit `bodies` for every body".into(),
                    ));
                }
                Some(ctx.body_indices(names, "body_force.bodies", &bodies)?)
            }
        };
        let amplitude = parse_amplitude(
            ctx,
            &f.ramp_time,
            &f.ramp_shape,
            &f.amplitude,
            &f.amplitude_shape,
            &|key: &str| format!("body_force.{key}"),
        )?;
        effects.body_force = Some(BodyForceDescription {
            acceleration,
            bodies: selected,
            amplitude,
        });
    }
    if let Some(r) = &file.reference_update {
        let span = r.strain_threshold.span();
        if updated_lagrangian {
            return Err(ctx.error(
                &span,
                "reference_update",
                "not available with formulation = \"updated-lagrangian\", which has no reference configuration".into(),
            ));
        }
        if file.xsph.is_some() {
            return Err(ctx.error(
                &span,
                "reference_update",
                "cannot be combined with [xsph] yet".into(),
            ));
        }
        let self_paired = |pairs: &Option<Vec<(usize, usize)>>| {
            pairs.iter().flatten().find(|(a, b)| a == b).map(|p| p.0)
        };
        let self_contact = effects
            .contact
            .as_ref()
            .and_then(|c| self_paired(&c.pairs))
            .or_else(|| {
                effects
                    .penalty_contact
                    .as_ref()
                    .and_then(|c| self_paired(&c.pairs))
            });
        if let Some(b) = self_contact {
            return Err(ctx.error(
                &span,
                "reference_update",
                format!(
                    "cannot be combined with the self-contact of body `{}`: a new reference bonds every pair of particles within the kernel support, so surfaces that self-contact holds together would be welded",
                    bodies[b].name
                ),
            ));
        }
        if let Some(b) = bodies
            .iter()
            .find(|b| materials[b.material].model.has_damage())
        {
            return Err(ctx.error(
                &span,
                "reference_update",
                format!(
                    "cannot be combined with a damage or failure model yet (material `{}` of body `{}` has one; failed particles are removed from the initial bonds)",
                    materials[b.material].name, b.name
                ),
            ));
        }
        let support = ctx.keyword(
            r.support.as_ref(),
            "reference_update.support",
            "support",
            ReferenceSupport::Stretched,
            &[
                ("stretched", ReferenceSupport::Stretched),
                ("fixed", ReferenceSupport::Fixed),
            ],
        )?;
        effects.reference_update = Some(tlsph_solver::ReferenceUpdate {
            strain_threshold: ctx
                .positive(&r.strain_threshold, "reference_update.strain_threshold")?,
            support,
        });
    }
    let output = OutputSpec {
        dir: match file.output.as_ref().and_then(|o| o.dir.as_ref()) {
            Some(d) => {
                let dir = PathBuf::from(d.get_ref());
                crate::run::check_output_dir(&dir)
                    .map_err(|message| ctx.error(&d.span(), "output.dir", message))?;
                dir
            }
            None => PathBuf::from("out"),
        },
        energy_interval: match file
            .output
            .as_ref()
            .and_then(|o| o.energy_interval.as_ref())
        {
            Some(i) => ctx.positive(i, "output.energy_interval")?,
            None => end_time / 1000.0,
        },
        frame_interval: match file.output.as_ref().and_then(|o| o.frame_interval.as_ref()) {
            Some(i) => Some(ctx.positive(i, "output.frame_interval")?),
            None => None,
        },
        stability: stability_thresholds(ctx, file.stability.as_ref())?,
    };
    Ok((
        Model {
            config,
            materials,
            bodies,
            boundaries,
            effects,
        },
        probes,
        output,
    ))
}

/// The contact law a `[contact]` table declares.
enum Contact {
    Potential(ContactDescription),
    Penalty(PenaltyContactDescription),
}

/// `[contact]`: `law = "potential"` (default; numerics.md §12.2: scale a > 0, exponent n ≥ 1,
/// default 4) or `law = "penalty"` (§12.1: stiffness factor > 0 and range > 0, default 1,
/// friction μ ≥ 0, default 0, static friction μ_s ≥ μ, default μ, and its decay d_c ≥ 0); the
/// keys of the other law are errors. Optional body pairs by name (default: every pair of
/// different bodies; a body paired with itself is self-contact, of either law). With the
/// updated-Lagrangian formulation bodies of the same kernel group, and every body with itself,
/// already interact through the kernel, so naming such a pair is an error (and "all pairs"
/// leaves them out).
fn build_contact<const D: usize>(
    ctx: &Context<'_>,
    table: &Spanned<crate::scene_file::ContactTable>,
    bodies: &[BodyDescription<D>],
    kernel_groups: Option<&[usize]>,
    updated_lagrangian: bool,
) -> Result<Contact, SceneError> {
    // Kernel interaction group of a body: the declared one, else its material.
    let group = |b: usize| kernel_groups.map_or(bodies[b].material, |g| g[b]);
    let c = table.get_ref();
    let penalty = match &c.law {
        None => false,
        Some(law) => match law.get_ref().as_str() {
            "potential" => false,
            "penalty" => true,
            other => {
                return Err(ctx.error(
                    &law.span(),
                    "contact.law",
                    format!("unknown law `{other}`; expected \"potential\" or \"penalty\""),
                ))
            }
        },
    };
    // Keys that belong to the other law.
    let potential_keys = [(&c.scale, "scale"), (&c.exponent, "exponent")];
    let penalty_keys = [
        (&c.stiffness, "stiffness"),
        (&c.range, "range"),
        (&c.friction, "friction"),
        (&c.static_friction, "static_friction"),
        (&c.friction_decay, "friction_decay"),
    ];
    let foreign: &[(&Option<Spanned<f64>>, &str)] = if penalty {
        &potential_keys
    } else {
        &penalty_keys
    };
    for &(value, key) in foreign {
        if let Some(v) = value {
            let (this, other) = if penalty {
                ("penalty", "potential")
            } else {
                ("potential", "penalty")
            };
            return Err(ctx.error(
                &v.span(),
                &format!("contact.{key}"),
                format!("belongs to law = \"{other}\", not to the {this} law of this table"),
            ));
        }
    }
    let law = if penalty {
        let factor = |v: &Option<Spanned<f64>>, key: &str| {
            v.as_ref()
                .map_or(Ok(1.0), |v| ctx.positive(v, &format!("contact.{key}")))
        };
        LawKeys::Penalty {
            stiffness: factor(&c.stiffness, "stiffness")?,
            range: factor(&c.range, "range")?,
            friction: ctx.friction_coefficients(
                &c.friction,
                &c.static_friction,
                &c.friction_decay,
                "contact",
            )?,
        }
    } else {
        let Some(scale) = &c.scale else {
            return Err(ctx.error(
                &table.span(),
                "contact.scale",
                "missing: the potential law needs its scale a (e.g. `scale = 2.0`), or set `law = \"penalty\"`".into(),
            ));
        };
        let scale = ctx.positive(scale, "contact.scale")?;
        let exponent = match &c.exponent {
            None => 4.0,
            Some(e) => {
                let v = ctx.positive(e, "contact.exponent")?;
                if v < 1.0 {
                    return Err(ctx.error(
                        &e.span(),
                        "contact.exponent",
                        format!(
                            "must be ≥ 1 (the force must stiffen as particles approach), got {v}"
                        ),
                    ));
                }
                v
            }
        };
        LawKeys::Potential { scale, exponent }
    };
    if bodies.len() < 2 && c.pairs.is_none() {
        return Err(ctx.error(
            &table.span(),
            "contact",
            "needs at least two bodies, or `pairs` naming a body with itself (self-contact)".into(),
        ));
    }
    let pairs = match &c.pairs {
        None => None,
        Some(list) => {
            let span = list.span();
            let err = |message: String| Err(ctx.error(&span, "contact.pairs", message));
            if list.get_ref().is_empty() {
                return err("lists no pair; omit `pairs` for every pair of bodies".into());
            }
            let mut pairs = Vec::new();
            for pair in list.get_ref() {
                let [a, b] = pair.as_slice() else {
                    return err(format!(
                        "each entry must be two body names, e.g. [\"flyer\", \"target\"], got {pair:?}"
                    ));
                };
                let find = |name: &String| bodies.iter().position(|x| &x.name == name);
                let (Some(ia), Some(ib)) = (find(a), find(b)) else {
                    let missing = if find(a).is_none() { a } else { b };
                    return err(format!("no body named `{missing}`"));
                };
                if updated_lagrangian && ia == ib {
                    return err(format!(
                        "self-contact of body `{a}` needs a total-Lagrangian formulation: with formulation = \"updated-lagrangian\" a body already interacts with itself through the kernel"
                    ));
                }
                if updated_lagrangian && group(ia) == group(ib) {
                    return err(format!(
                        "bodies `{a}` and `{b}` share a kernel group (by default their material) and so already interact through the kernel with formulation = \"updated-lagrangian\"; contact would count their interaction twice"
                    ));
                }
                pairs.push((ia, ib));
            }
            Some(pairs)
        }
    };
    Ok(match law {
        LawKeys::Potential { scale, exponent } => Contact::Potential(ContactDescription {
            scale,
            exponent,
            pairs,
        }),
        LawKeys::Penalty {
            stiffness,
            range,
            friction,
        } => Contact::Penalty(PenaltyContactDescription {
            stiffness,
            range,
            friction,
            pairs,
        }),
    })
}

/// The law-specific values of a `[contact]` table, checked.
enum LawKeys {
    Potential {
        scale: f64,
        exponent: f64,
    },
    Penalty {
        stiffness: f64,
        range: f64,
        friction: FrictionCoefficients,
    },
}

fn build_body<const D: usize>(
    ctx: &Context<'_>,
    b: &BodyTable,
    materials: &[MaterialDescription],
) -> Result<BodyDescription<D>, SceneError> {
    let name = b.name.get_ref().clone();
    let field = |key: &str| format!("body[{name}].{key}");
    let material = materials
        .iter()
        .position(|m| &m.name == b.material.get_ref())
        .ok_or_else(|| {
            ctx.error(
                &b.material.span(),
                &field("material"),
                format!(
                    "no material named `{}` (define it in a [[material]] table)",
                    b.material.get_ref()
                ),
            )
        })?;
    let spacing = ctx.positive(&b.spacing, &field("spacing"))?;
    let inline = ShapeTable {
        box_: b.box_.clone(),
        cylinder: b.cylinder.clone(),
        sphere: b.sphere.clone(),
        disc: b.disc.clone(),
        velocity: b.velocity.clone(),
        velocity_gradient: b.velocity_gradient.clone(),
        velocity_origin: b.velocity_origin.clone(),
        clip: b.clip.clone(),
    };
    let has_inline_shape = inline.box_.is_some()
        || inline.cylinder.is_some()
        || inline.sphere.is_some()
        || inline.disc.is_some();
    let shapes: Vec<&ShapeTable> = match (has_inline_shape, b.shape.is_empty()) {
        (true, true) => vec![&inline],
        (false, false) => {
            if inline.velocity.is_some()
                || inline.velocity_gradient.is_some()
                || inline.velocity_origin.is_some()
                || inline.clip.is_some()
            {
                return Err(ctx.error(
                    &b.name.span(),
                    &field("velocity"),
                    "with [[body.shape]] tables, give velocity, velocity_gradient, velocity_origin and clip inside each shape".into(),
                ));
            }
            b.shape.iter().collect()
        }
        (true, false) => {
            return Err(ctx.error(
                &b.name.span(),
                &field("shape"),
                "give either one shape on the body or [[body.shape]] tables, not both".into(),
            ))
        }
        (false, true) => {
            return Err(ctx.error(
                &b.name.span(),
                &field("shape"),
                "has no shape: add box, cylinder, sphere or disc".into(),
            ))
        }
    };
    let mut positions: Vec<Vector<D>> = Vec::new();
    let mut velocities: Vec<Vector<D>> = Vec::new();
    let mut fills: Vec<Fill<D>> = Vec::new();
    for (k, s) in shapes.iter().enumerate() {
        let sfield = |key: &str| {
            if shapes.len() == 1 {
                field(key)
            } else {
                format!("body[{name}].shape[{k}].{key}")
            }
        };
        let (shape, span) = shape_of::<D>(ctx, s, &sfield)?;
        let velocity = match &s.velocity {
            Some(v) => ctx.vector::<D>(v, &sfield("velocity"))?,
            None => Vector::<D>::zeros(),
        };
        let gradient = match &s.velocity_gradient {
            Some(g) => {
                let rows = g.get_ref();
                if rows.len() != D
                    || rows.iter().any(|r| r.len() != D)
                    || rows.iter().flatten().any(|x| !x.is_finite())
                {
                    return Err(ctx.error(
                        &g.span(),
                        &sfield("velocity_gradient"),
                        format!("must be a {D}x{D} array of finite numbers"),
                    ));
                }
                Tensor::<D>::from_fn(|i, j| rows[i][j])
            }
            None => Tensor::<D>::zeros(),
        };
        let origin = match &s.velocity_origin {
            Some(o) => ctx.vector::<D>(o, &sfield("velocity_origin"))?,
            None => Vector::<D>::zeros(),
        };
        let mut points = fill_shape(&shape, spacing, &positions);
        let clip = match &s.clip {
            Some(clip) => {
                let span = clip.span();
                let min = ctx.components::<D>(&clip.get_ref().min, &span, &sfield("clip.min"))?;
                let max = ctx.components::<D>(&clip.get_ref().max, &span, &sfield("clip.max"))?;
                Some(Shape::Box { min, max })
            }
            None => None,
        };
        if let Some(clip) = &clip {
            points.retain(|x| clip.contains(x));
        }
        if points.is_empty() {
            return Err(ctx.error(&span, &sfield("shape"), format!("contains no particle at spacing {spacing} (is it smaller than the spacing, or fully inside an earlier shape?)")));
        }
        let fill = Fill {
            shape,
            clip,
            velocity,
            gradient,
            origin,
        };
        let first = velocities.len();
        for x in points {
            velocities.push(fill.velocity_at(&x));
            positions.push(x);
        }
        // Cuts only take particles and volume away, so a shape that passes here passes after.
        let shape_volumes = vec![spacing.powi(D as i32); velocities.len() - first];
        let density = materials[material].density;
        if let Err(message) =
            tlsph_solver::check_kinetic_energy(&velocities[first..], &shape_volumes, density)
        {
            // Blame the gradient only if the uniform part alone is fine.
            let uniform_fine =
                tlsph_solver::check_kinetic_energy(&[fill.velocity], &shape_volumes[..1], density)
                    .is_ok();
            let (span, key) = match (&s.velocity, &s.velocity_gradient) {
                (_, Some(g)) if uniform_fine => (g.span(), "velocity_gradient"),
                (Some(v), _) => (v.span(), "velocity"),
                _ => (span.clone(), "shape"),
            };
            return Err(ctx.error(
                &span,
                &sfield(key),
                format!("{message} (the shape's particles are numbered from 0)"),
            ));
        }
        fills.push(fill);
    }
    let mut volumes = vec![spacing.powi(D as i32); positions.len()];
    apply_cuts(
        ctx,
        b,
        spacing,
        &fills,
        &mut positions,
        &mut velocities,
        &mut volumes,
    )?;
    if let Some(t) = b
        .initial_velocity_file
        .as_ref()
        .filter(|_| ctx.read_field_tables)
    {
        velocities = initial_velocity_file::<D>(
            ctx,
            t,
            &field("initial_velocity_file"),
            &shapes,
            materials[material].density,
            spacing,
            &positions,
            &volumes,
        )?;
    }
    let initial_plastic_strains =
        initial_plastic_strains::<D>(ctx, b, &field, &materials[material], spacing, &positions)?;
    let damage_field = |which| {
        initial_damage::<D>(
            ctx,
            b,
            &field,
            &materials[material],
            spacing,
            &positions,
            which,
        )
    };
    let initial_damage = damage_field(InitialDamage::Softening)?;
    let initial_failure_damage = damage_field(InitialDamage::JohnsonCookFailure)?;
    // Each particle's ε̄p for the yield checks below; `None` where it is not known (its table
    // is not read, for `tlsph particles`), and then no yield check is made.
    let plastic_strain_unknown = b.initial_plastic_strain_file.is_some() && !ctx.read_field_tables;
    let plastic_strain_of = |k: usize| match &initial_plastic_strains {
        Some(strains) => Some(strains[k]),
        None if plastic_strain_unknown => None,
        None => Some(0.0),
    };
    let initial_stress = match &b.initial_stress {
        Some(t) => Some(initial_stress::<D>(
            ctx,
            t,
            &field("initial_stress"),
            &materials[material],
            (0..positions.len())
                .map(plastic_strain_of)
                .try_fold(f64::INFINITY, |least, e| Some(least.min(e?))),
        )?),
        None => None,
    };
    let initial_stress_gradient = match &b.initial_stress_gradient {
        Some(t) => Some(initial_stress_gradient::<D>(
            ctx,
            t,
            &field("initial_stress_gradient"),
            &materials[material],
            initial_stress.unwrap_or_else(tlsph_math::Tensor3::zeros),
            &positions,
            plastic_strain_of,
        )?),
        None => None,
    };
    let initial_stresses = match b
        .initial_stress_file
        .as_ref()
        .filter(|_| ctx.read_field_tables)
    {
        Some(t) => {
            let other = b.initial_stress.as_ref().map(|_| "initial_stress").or(b
                .initial_stress_gradient
                .as_ref()
                .map(|_| "initial_stress_gradient"));
            if let Some(other) = other {
                return Err(ctx.error(
                    &t.span(),
                    &field("initial_stress_file"),
                    format!("gives the whole initial stress field, so `{other}` cannot be declared with it"),
                ));
            }
            Some(initial_stress_file::<D>(
                ctx,
                t,
                &field("initial_stress_file"),
                &materials[material],
                spacing,
                &positions,
                plastic_strain_of,
            )?)
        }
        None => None,
    };
    Ok(BodyDescription {
        name: name.clone(),
        material,
        spacing,
        volumes,
        positions,
        velocities,
        initial_stress,
        initial_stress_gradient,
        initial_stresses,
        initial_plastic_strains,
        initial_damage,
        initial_failure_damage,
    })
}

/// The symmetric stress of `initial_stress`: finite components; in 1D only the normal ones
/// (uniaxial strain), in 2D no out-of-plane shear (plane strain); not for materials whose
/// stress is a function of state (an equation of state or a damage model).
fn initial_stress<const D: usize>(
    ctx: &Context<'_>,
    table: &Spanned<StressComponents>,
    field: &str,
    material: &MaterialDescription,
    least_plastic_strain: Option<f64>,
) -> Result<tlsph_math::Tensor3, SceneError> {
    let c = table.get_ref();
    let span = table.span();
    let components = [c.xx, c.yy, c.zz, c.xy, c.yz, c.xz];
    stress_components_allowed::<D>(ctx, &span, field, &components.map(|x| x.is_some()))?;
    let [xx, yy, zz, xy, yz, xz] = components.map(|x| x.unwrap_or(0.0));
    if ![xx, yy, zz, xy, yz, xz].iter().all(|x| x.is_finite()) {
        return Err(ctx.error(&span, field, "components must be finite numbers".into()));
    }
    stress_is_not_state(ctx, &span, field, material)?;
    let stress = tlsph_math::Tensor3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
    let outside = least_plastic_strain
        .and_then(|e| Some((e, material.model.outside_yield_surface(&stress, e)?)));
    if let Some((least_plastic_strain, (equivalent, yield_stress))) = outside {
        return Err(ctx.error(
            &span,
            field,
            format!(
                "lies outside the yield surface of material `{}`: its von Mises stress {equivalent:e} Pa exceeds the {} {yield_stress:e} Pa (the first step would silently return it to the surface)",
                material.name,
                yield_stress_name(least_plastic_strain),
            ),
        ));
    }
    Ok(stress)
}

/// G_k = ∂σ/∂X_k of `initial_stress_gradient` (each component an array of D finite
/// derivatives, the components allowed as for `initial_stress`). With the stress `at_origin`
/// σ0 every particle's σ0 + Σ_k X_k G_k must lie on or inside the initial yield surface; the
/// error names the first that does not.
fn initial_stress_gradient<const D: usize>(
    ctx: &Context<'_>,
    table: &Spanned<StressGradients>,
    field: &str,
    material: &MaterialDescription,
    at_origin: tlsph_math::Tensor3,
    positions: &[Vector<D>],
    plastic_strain_of: impl Fn(usize) -> Option<f64>,
) -> Result<[tlsph_math::Tensor3; D], SceneError> {
    let c = table.get_ref();
    let span = table.span();
    let components = [&c.xx, &c.yy, &c.zz, &c.xy, &c.yz, &c.xz];
    stress_components_allowed::<D>(ctx, &span, field, &components.map(|x| x.is_some()))?;
    let mut slopes = [[0.0; 6]; D];
    for (index, (name, values)) in crate::scene_field_file::STRESS_COLUMNS
        .iter()
        .zip(components)
        .enumerate()
    {
        let Some(values) = values else { continue };
        if values.len() != D || !values.iter().all(|x| x.is_finite()) {
            return Err(ctx.error(
                &span,
                field,
                format!(
                    "`{name}` must be {D} finite numbers (its derivatives along {}), got {values:?}",
                    ["x", "y", "z"][..D].join(", ")
                ),
            ));
        }
        for (k, value) in values.iter().enumerate() {
            slopes[k][index] = *value;
        }
    }
    stress_is_not_state(ctx, &span, field, material)?;
    let gradient = slopes.map(|[xx, yy, zz, xy, yz, xz]| {
        tlsph_math::Tensor3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
    });
    within_initial_yield(
        ctx,
        &span,
        field,
        material,
        positions,
        |k| tlsph_solver::linear_stress_at(at_origin, &gradient, &positions[k]),
        plastic_strain_of,
        |_| String::new(),
    )?;
    Ok(gradient)
}

/// Checks that the initial stress `stress_of(k)` of each particle k at `positions` lies on or
/// inside the yield surface of `material` at its initial plastic strain `plastic_strain_of(k)`
/// (no check where that is `None`, not known); the error names the first particle that does
/// not, and where its stress came from (`source(k)`, formatted only then).
#[allow(clippy::too_many_arguments)]
fn within_initial_yield<const D: usize>(
    ctx: &Context<'_>,
    span: &Range<usize>,
    field: &str,
    material: &MaterialDescription,
    positions: &[Vector<D>],
    stress_of: impl Fn(usize) -> tlsph_math::Tensor3,
    plastic_strain_of: impl Fn(usize) -> Option<f64>,
    source: impl Fn(usize) -> String,
) -> Result<(), SceneError> {
    for (k, x) in positions.iter().enumerate() {
        let Some(plastic_strain) = plastic_strain_of(k) else {
            continue;
        };
        if let Some((equivalent, yield_stress)) = material
            .model
            .outside_yield_surface(&stress_of(k), plastic_strain)
        {
            let source = source(k);
            return Err(ctx.error(
                span,
                field,
                format!(
                    "takes the particle at [{}] outside the yield surface of material `{}`: its von Mises stress {equivalent:e} Pa{source} exceeds the {} {yield_stress:e} Pa",
                    point_text(x),
                    material.name,
                    yield_stress_name(plastic_strain),
                ),
            ));
        }
    }
    Ok(())
}

/// How a yield-check message names the yield stress of a particle with `plastic_strain`.
fn yield_stress_name(plastic_strain: f64) -> String {
    if plastic_strain > 0.0 {
        format!("yield stress at its initial plastic strain {plastic_strain}")
    } else {
        "initial yield stress".into()
    }
}

/// The stress of each particle from `initial_stress_file`: the CSV table at `path` (relative
/// to the scene's folder), each particle given the stress of its nearest sample within
/// `reach` (default: the body's `spacing`); the components allowed and the materials as for
/// `initial_stress`, and every particle's stress on or inside the initial yield surface (the
/// error names the first that is not, and the line of its sample).
fn initial_stress_file<const D: usize>(
    ctx: &Context<'_>,
    table: &Spanned<FieldFileTable>,
    field: &str,
    material: &MaterialDescription,
    spacing: f64,
    positions: &[Vector<D>],
    plastic_strain_of: impl Fn(usize) -> Option<f64>,
) -> Result<Vec<tlsph_math::Tensor3>, SceneError> {
    let (samples, mapping, path) = mapped_field_table(
        ctx,
        table,
        field,
        &crate::scene_field_file::STRESS_COLUMNS,
        spacing,
        positions,
        |given| {
            stress_components_allowed::<D>(ctx, &table.span(), field, given)?;
            stress_is_not_state(ctx, &table.span(), field, material)
        },
    )?;
    let stresses: Vec<tlsph_math::Tensor3> = (0..positions.len())
        .map(|k| {
            let [xx, yy, zz, xy, yz, xz] = mapping.values(&samples, k);
            tlsph_math::Tensor3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
        })
        .collect();
    within_initial_yield(
        ctx,
        &table.span(),
        field,
        material,
        positions,
        |k| stresses[k],
        plastic_strain_of,
        |k| format!(" ({})", sample_source(&samples, &mapping, k, &path)),
    )?;
    Ok(stresses)
}

/// A scalar initial field of a body, given by a uniform key (`initial_plastic_strain`) or by a
/// field table of one column (`initial_plastic_strain_file`), never both.
struct ScalarInitialField<'a> {
    uniform: Option<&'a Spanned<f64>>,
    table: Option<&'a Spanned<FieldFileTable>>,
    /// The uniform key and the table key.
    keys: [&'static str; 2],
    /// The table's column: the name of the output field.
    column: &'static [&'static str; 1],
    /// What the field is, in messages ("plastic strain").
    what: &'static str,
    /// Whether a value is allowed, the rule in words ("≥ 0"), and what to do instead, appended
    /// to the error ("" or " (...)").
    allowed: fn(f64) -> bool,
    rule: &'static str,
    hint: &'static str,
    /// A linear fit's value, given the fitted value and the table's largest value: the fit may
    /// undershoot or overshoot at the edge of a region of constant value.
    fitted: fn(f64, f64) -> f64,
}

impl ScalarInitialField<'_> {
    /// The declared key and its span, or `None` if the body declares neither key.
    fn declared(
        &self,
        ctx: &Context<'_>,
        field: &dyn Fn(&str) -> String,
    ) -> Result<Option<(Range<usize>, &'static str)>, SceneError> {
        let [uniform_key, table_key] = self.keys;
        match (self.uniform, self.table) {
            (None, None) => Ok(None),
            (Some(_), Some(t)) => Err(ctx.error(
                &t.span(),
                &field(table_key),
                format!(
                    "gives the whole {} field, so `{uniform_key}` cannot be declared with it",
                    self.what
                ),
            )),
            (Some(v), None) => Ok(Some((v.span(), uniform_key))),
            (None, Some(t)) => Ok(Some((t.span(), table_key))),
        }
    }

    /// The value of each particle at `positions` and, for messages, where it came from (" (line
    /// L of `path`)"); `None` if the body declares neither key or its table is not read. The
    /// uniform value and every table cell must be allowed (the error names the key, or the
    /// table's line); a linear fit's value is passed through `fitted`.
    #[allow(clippy::type_complexity)]
    fn values<const D: usize>(
        &self,
        ctx: &Context<'_>,
        field: &dyn Fn(&str) -> String,
        spacing: f64,
        positions: &[Vector<D>],
    ) -> Result<Option<(Vec<f64>, Box<dyn Fn(usize) -> String>)>, SceneError> {
        let [uniform_key, table_key] = self.keys;
        match (self.uniform, self.table) {
            (Some(v), _) => {
                let value = *v.get_ref();
                if !(value.is_finite() && (self.allowed)(value)) {
                    return Err(ctx.error(
                        &v.span(),
                        &field(uniform_key),
                        format!(
                            "must be a finite number {}, got {value}{}",
                            self.rule, self.hint
                        ),
                    ));
                }
                Ok(Some((
                    vec![value; positions.len()],
                    Box::new(|_| String::new()),
                )))
            }
            (None, Some(t)) if ctx.read_field_tables => {
                let key = field(table_key);
                let (samples, mapping, path) =
                    mapped_field_table(ctx, t, &key, self.column, spacing, positions, |_| Ok(()))?;
                if let Some(s) = samples.values.iter().position(|v| !(self.allowed)(v[0])) {
                    return Err(ctx.error(
                        &t.get_ref().path.span(),
                        &format!("{key}.path"),
                        format!(
                            "`{}` line {}: `{}` must be {}, got {}{}",
                            path.display(),
                            samples.lines[s],
                            self.column[0],
                            self.rule,
                            samples.values[s][0],
                            self.hint
                        ),
                    ));
                }
                let largest = samples.values.iter().map(|v| v[0]).fold(0.0, f64::max);
                let values = (0..positions.len())
                    .map(|k| (self.fitted)(mapping.values(&samples, k)[0], largest))
                    .collect();
                let source = move |k| format!(" ({})", sample_source(&samples, &mapping, k, &path));
                Ok(Some((values, Box::new(source))))
            }
            _ => Ok(None),
        }
    }
}

/// The effective plastic strain ε̄p of each particle at t = 0 from `initial_plastic_strain`
/// (uniform) or `initial_plastic_strain_file` (a CSV table with the column `plastic_strain`,
/// mapped as the other field tables), or `None` if the body declares neither (or its table is
/// not read). Only for elastic–plastic materials; every value finite and ≥ 0 (a table cell
/// below 0 is an error naming its line; a linear fit's undershoot below 0 at the edge of a
/// region at 0 is taken as 0), and below the failure strain of a `max-plastic-strain` failure
/// law (the error names the first particle at or above it).
fn initial_plastic_strains<const D: usize>(
    ctx: &Context<'_>,
    b: &BodyTable,
    field: &dyn Fn(&str) -> String,
    material: &MaterialDescription,
    spacing: f64,
    positions: &[Vector<D>],
) -> Result<Option<Vec<f64>>, SceneError> {
    let strain_field = ScalarInitialField {
        uniform: b.initial_plastic_strain.as_ref(),
        table: b.initial_plastic_strain_file.as_ref(),
        keys: ["initial_plastic_strain", "initial_plastic_strain_file"],
        column: &crate::scene_field_file::PLASTIC_STRAIN_COLUMNS,
        what: "plastic strain",
        allowed: |e| e >= 0.0,
        rule: "≥ 0",
        hint: "",
        fitted: |e, _| e.max(0.0),
    };
    let Some((span, key)) = strain_field.declared(ctx, field)? else {
        return Ok(None);
    };
    let MaterialModel::ElasticPlastic(plastic) = &material.model else {
        return Err(ctx.error(
            &span,
            &field(key),
            format!(
                "material `{}` has no plastic strain (only `elastic-plastic` and `johnson-cook` materials have one)",
                material.name
            ),
        ));
    };
    let Some((strains, source)) = strain_field.values(ctx, field, spacing, positions)? else {
        return Ok(None);
    };
    if let Some(tlsph_solver::FailureModel::MaxPlasticStrain(limit)) = plastic.failure {
        if let Some(k) = strains.iter().position(|e| limit.fails(*e)) {
            return Err(ctx.error(
                &span,
                &field(key),
                format!(
                    "the particle at [{}] starts at plastic strain {}{}, at or beyond the failure strain of material `{}`",
                    point_text(&positions[k]),
                    strains[k],
                    source(k),
                    material.name
                ),
            ));
        }
    }
    Ok(Some(strains))
}

/// Which damage variable an initial damage field sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum InitialDamage {
    /// The softening damage of a `damage` law (`initial_damage`, numerics.md §9.1–9.2).
    Softening,
    /// The cumulative damage of a `johnson-cook` failure law (`initial_failure_damage`,
    /// numerics.md §8.6).
    JohnsonCookFailure,
}

/// The damage D of each particle at t = 0 of the variable `which` names: from
/// `initial_damage` / `initial_failure_damage` (uniform) or `initial_damage_file` /
/// `initial_failure_damage_file` (a CSV table with the column `damage`, the name of the output
/// field, mapped as the other field tables), or `None` if the body declares neither (or its
/// table is not read). Only for materials with that variable (a `damage` law; a `johnson-cook`
/// failure law); every value in \[0, 1) (a failed particle, D = 1, is not started: it would be
/// cut from the body). A linear fit is kept within \[0, the table's largest value\].
fn initial_damage<const D: usize>(
    ctx: &Context<'_>,
    b: &BodyTable,
    field: &dyn Fn(&str) -> String,
    material: &MaterialDescription,
    spacing: f64,
    positions: &[Vector<D>],
    which: InitialDamage,
) -> Result<Option<Vec<f64>>, SceneError> {
    let (uniform, table, keys) = match which {
        InitialDamage::Softening => (
            &b.initial_damage,
            &b.initial_damage_file,
            ["initial_damage", "initial_damage_file"],
        ),
        InitialDamage::JohnsonCookFailure => (
            &b.initial_failure_damage,
            &b.initial_failure_damage_file,
            ["initial_failure_damage", "initial_failure_damage_file"],
        ),
    };
    let damage_field = ScalarInitialField {
        uniform: uniform.as_ref(),
        table: table.as_ref(),
        keys,
        column: &crate::scene_field_file::DAMAGE_COLUMNS,
        what: "damage",
        allowed: |d| (0.0..1.0).contains(&d),
        rule: "≥ 0 and < 1",
        hint:
            " (D = 1 is a failed particle: leave that part out of the body with a `[[body.cut]]`)",
        fitted: |d, largest| d.clamp(0.0, largest),
    };
    let Some((span, key)) = damage_field.declared(ctx, field)? else {
        return Ok(None);
    };
    let johnson_cook_failure = material.model.has_johnson_cook_failure();
    let missing = match which {
        InitialDamage::Softening if material.model.softening_damage().is_none() => {
            Some(if johnson_cook_failure {
                "has no damage law (declare `damage` on it); its Johnson–Cook failure damage is set by `initial_failure_damage`"
            } else {
                "has no damage law (declare `damage` on it)"
            })
        }
        InitialDamage::JohnsonCookFailure if !johnson_cook_failure => Some(
            "has no Johnson–Cook failure law (declare `failure` with model `johnson-cook` on it)",
        ),
        _ => None,
    };
    if let Some(missing) = missing {
        return Err(ctx.error(
            &span,
            &field(key),
            format!("material `{}` {missing}", material.name),
        ));
    }
    Ok(damage_field
        .values(ctx, field, spacing, positions)?
        .map(|(damages, _)| damages))
}

/// Reads the table of a field-table key (`{ path, reach, interpolation }`) with the given
/// component `columns`, checks which components it gives (`check_given`, before the mapping),
/// and maps it to the particles at `positions`: each particle's values from its nearest sample
/// (`interpolation = "nearest"`, the default) or a linear fit over the samples around it
/// (`"linear"`), within `reach` (default: the body's `spacing`, twice that for `linear`).
/// Returns the samples, the mapping and the table's path (relative to the scene's folder).
fn mapped_field_table<const D: usize, const N: usize>(
    ctx: &Context<'_>,
    table: &Spanned<FieldFileTable>,
    field: &str,
    columns: &[&str; N],
    spacing: f64,
    positions: &[Vector<D>],
    check_given: impl FnOnce(&[bool; N]) -> Result<(), SceneError>,
) -> Result<(FieldSamples<D, N>, SampleMapping, PathBuf), SceneError> {
    let t = table.get_ref();
    let interpolation = ctx.keyword(
        t.interpolation.as_ref(),
        &format!("{field}.interpolation"),
        "interpolation",
        Interpolation::Nearest,
        &[
            ("nearest", Interpolation::Nearest),
            ("linear", Interpolation::Linear),
        ],
    )?;
    let reach = match (&t.reach, interpolation) {
        (Some(r), _) => ctx.positive(r, &format!("{field}.reach"))?,
        (None, Interpolation::Nearest) => spacing,
        // A table at the particles' own positions then gives each particle its neighbours.
        (None, Interpolation::Linear) => 2.0 * spacing,
    };
    let path = ctx.folder.join(t.path.get_ref());
    let samples = crate::scene_field_file::read_field_samples::<D, N>(&path, columns)
        .map_err(|message| ctx.error(&t.path.span(), &format!("{field}.path"), message))?;
    check_given(&samples.given)?;
    let mapping = crate::scene_field_file::map_samples(&samples, positions, reach, interpolation)
        .map_err(|message| {
        ctx.error(
            &table.span(),
            field,
            format!("`{}`: {message}", path.display()),
        )
    })?;
    let (samples_per_particle, unused_samples) = mapping.usage(samples.points.len());
    let farthest_nearest_sample = positions
        .iter()
        .enumerate()
        .map(|(k, x)| (samples.points[mapping.nearest(k)] - x).norm())
        .fold(0.0, f64::max);
    ctx.field_tables.borrow_mut().push(FieldTableSummary {
        field: field.to_string(),
        path: path.clone(),
        samples: samples.points.len(),
        interpolation: match interpolation {
            Interpolation::Nearest => "nearest",
            Interpolation::Linear => "linear",
        },
        reach,
        samples_per_particle,
        farthest_nearest_sample,
        unused_samples,
    });
    Ok((samples, mapping, path))
}

/// Where particle `k`'s values in a field table come from, for messages: "line L of `path`"
/// for a nearest sample, and the number of samples fitted and the nearest one's line for a
/// linear fit.
fn sample_source<const D: usize, const N: usize>(
    samples: &FieldSamples<D, N>,
    mapping: &SampleMapping,
    k: usize,
    path: &Path,
) -> String {
    let line = samples.lines[mapping.nearest(k)];
    match mapping.sample_count(k) {
        1 => format!("line {line} of `{}`", path.display()),
        n => format!(
            "fitted to {n} samples of `{}`, the nearest on line {line}",
            path.display()
        ),
    }
}

/// The velocity of each particle from `initial_velocity_file`: the CSV table at `path`
/// (relative to the scene's folder) with columns `vx`, `vy`, `vz` (the first D; absent ones 0),
/// each particle given the velocity of its nearest sample within `reach` (default: the body's
/// `spacing`). It replaces the velocity keys of the body's `shapes`, so none may be declared;
/// every particle's kinetic energy ½ρV|v|² must be finite (the error names the particle and
/// the line of its sample).
#[allow(clippy::too_many_arguments)]
fn initial_velocity_file<const D: usize>(
    ctx: &Context<'_>,
    table: &Spanned<FieldFileTable>,
    field: &str,
    shapes: &[&ShapeTable],
    density: f64,
    spacing: f64,
    positions: &[Vector<D>],
    volumes: &[f64],
) -> Result<Vec<Vector<D>>, SceneError> {
    let declared = shapes.iter().find_map(|s| {
        (s.velocity.as_ref().map(|_| "velocity"))
            .or(s.velocity_gradient.as_ref().map(|_| "velocity_gradient"))
            .or(s.velocity_origin.as_ref().map(|_| "velocity_origin"))
    });
    if let Some(key) = declared {
        return Err(ctx.error(
            &table.span(),
            field,
            format!("gives the whole initial velocity field, so no shape of the body can declare `{key}`"),
        ));
    }
    let (samples, mapping, path) = mapped_field_table(
        ctx,
        table,
        field,
        &std::array::from_fn::<_, D, _>(|i| crate::scene_field_file::VELOCITY_COLUMNS[i]),
        spacing,
        positions,
        |_| Ok(()),
    )?;
    let velocities: Vec<Vector<D>> = (0..positions.len())
        .map(|k| Vector::<D>::from(mapping.values(&samples, k)))
        .collect();
    // One pass: each particle's energy is checked (to name it and its line) and summed.
    let mut total = 0.0;
    for (k, v) in velocities.iter().enumerate() {
        match tlsph_solver::particle_kinetic_energy(v, volumes[k], density) {
            Ok(energy) => total += energy,
            Err(message) => {
                return Err(ctx.error(
                    &table.span(),
                    field,
                    format!(
                        "particle {k} at [{}] ({}): {message}",
                        point_text(&positions[k]),
                        sample_source(&samples, &mapping, k, &path),
                    ),
                ));
            }
        }
    }
    if !total.is_finite() {
        return Err(ctx.error(
            &table.span(),
            field,
            "the body's kinetic energy is not a finite number".into(),
        ));
    }
    Ok(velocities)
}

/// Which stress components a D-dimensional scene may set (`given`: xx, yy, zz, xy, yz, xz):
/// in 1D only the normal ones (uniaxial strain), in 2D no out-of-plane shear (plane strain).
fn stress_components_allowed<const D: usize>(
    ctx: &Context<'_>,
    span: &Range<usize>,
    field: &str,
    given: &[bool; 6],
) -> Result<(), SceneError> {
    for (present, needs, name) in [
        (given[3], 2, "xy"),
        (given[4], 3, "yz"),
        (given[5], 3, "xz"),
    ] {
        if present && D < needs {
            return Err(ctx.error(
                span,
                field,
                format!("`{name}` is not a stress component of a {D}D scene (1D: xx, yy, zz; 2D: also xy)"),
            ));
        }
    }
    Ok(())
}

/// Refuses an initial stress for a material whose stress is a function of the current state
/// (an equation of state, or a damage model's effective stress): it would be lost.
fn stress_is_not_state(
    ctx: &Context<'_>,
    span: &Range<usize>,
    field: &str,
    material: &MaterialDescription,
) -> Result<(), SceneError> {
    let state_stress = match &material.model {
        MaterialModel::ElasticPlastic(m) => {
            matches!(m.pressure, PressureModel::Eos(_)) || m.damage.is_some()
        }
        MaterialModel::ElasticDamage(_) => true,
        MaterialModel::LinearElastic(_) => false,
    };
    if state_stress {
        return Err(ctx.error(
            span,
            field,
            format!(
                "material `{}` computes its stress from the current state (an equation of state or a damage model), so an initial stress would be lost",
                material.name
            ),
        ));
    }
    Ok(())
}

/// One filled shape of a body: the region its particles came from (its shape, within its
/// `clip`) and the initial velocity field v = v0 + L (X − X_origin) they start with.
struct Fill<const D: usize> {
    shape: Shape<D>,
    clip: Option<Shape<D>>,
    velocity: Vector<D>,
    gradient: Tensor<D>,
    origin: Vector<D>,
}

impl<const D: usize> Fill<D> {
    /// Whether the reference point `x` lies in this shape and its clip box.
    fn covers(&self, x: &Vector<D>) -> bool {
        self.shape.contains(x) && self.clip.as_ref().is_none_or(|c| c.contains(x))
    }

    /// Initial velocity at `x`.
    fn velocity_at(&self, x: &Vector<D>) -> Vector<D> {
        self.velocity + self.gradient * (x - self.origin)
    }
}

/// A round cut whose rim is followed by `rings` rings of particles ([`hole_rings`]): a disc
/// in 2D, or a cylinder in 3D, whose rings are laid in every lattice layer it passes through.
struct RingedCut<const D: usize> {
    cut: usize,
    /// Disc centre or cylinder base.
    centre: Vector<D>,
    radius: f64,
    rings: usize,
    /// The two axes of the plane the rings lie in.
    plane: [usize; 2],
    /// A cylinder's axis and the closed range [lo, hi] of that coordinate it spans.
    axial: Option<(usize, f64, f64)>,
}

impl<const D: usize> RingedCut<D> {
    /// Outer radius of the ring zone: the lattice points inside it are replaced by the rings.
    fn outer(&self, spacing: f64) -> f64 {
        self.radius + self.rings as f64 * spacing
    }

    /// Whether `x` lies within `reach` of the hole's axis (2D: its centre) and, for a
    /// cylinder, within its extent along the axis.
    fn within(&self, x: &Vector<D>, reach: f64) -> bool {
        let [a, b] = self.plane;
        let radial = (x[a] - self.centre[a]).hypot(x[b] - self.centre[b]);
        radial < reach
            && self
                .axial
                .is_none_or(|(k, lo, hi)| (lo..=hi).contains(&x[k]))
    }

    /// Whether the ring zones of `self` and `other` could share a particle or a neighbour of
    /// one: for holes along the same axis (or two discs), the in-plane centre distance is
    /// below the sum of the outer radii and the axial extents overlap; for cylinders along
    /// different axes, the boxes around their zones widened by two spacings meet.
    fn overlaps(&self, other: &Self, spacing: f64) -> bool {
        let [a, b] = self.plane;
        let axis = |r: &Self| r.axial.map(|(k, _, _)| k);
        if axis(self) == axis(other) {
            let apart = (self.centre[a] - other.centre[a]).hypot(self.centre[b] - other.centre[b]);
            let along = match (self.axial, other.axial) {
                (Some((_, lo, hi)), Some((_, lo2, hi2))) => lo <= hi2 && lo2 <= hi,
                _ => true,
            };
            return along && apart < self.outer(spacing) + other.outer(spacing);
        }
        let (lo1, hi1) = self.zone_box(spacing);
        let (lo2, hi2) = other.zone_box(spacing);
        (0..D).all(|k| lo1[k] <= hi2[k] && lo2[k] <= hi1[k])
    }

    /// Corners of the box around the ring zone, widened by two spacings.
    fn zone_box(&self, spacing: f64) -> (Vector<D>, Vector<D>) {
        let reach = self.outer(spacing) + 2.0 * spacing;
        let mut lo = self.centre.add_scalar(-reach);
        let mut hi = self.centre.add_scalar(reach);
        if let Some((k, a, b)) = self.axial {
            lo[k] = a - 2.0 * spacing;
            hi[k] = b + 2.0 * spacing;
        }
        (lo, hi)
    }

    /// The ring particles ([`hole_rings`]) of the lattice layer at coordinate `layer` along
    /// the cylinder's axis (2D: `None`, the plane itself).
    fn rings_in(&self, layer: Option<f64>, spacing: f64) -> Vec<Vector<D>> {
        let [a, b] = self.plane;
        let centre = Vector::<2>::new(self.centre[a], self.centre[b]);
        hole_rings(&centre, self.radius, self.rings, spacing)
            .into_iter()
            .map(|p| {
                let mut y = Vector::<D>::zeros();
                y[a] = p[0];
                y[b] = p[1];
                if let (Some((k, _, _)), Some(s)) = (self.axial, layer) {
                    y[k] = s;
                }
                y
            })
            .collect()
    }
}

/// Largest `rings` a cut accepts (a guard against typos that would fill memory).
const MAX_RINGS: i64 = 1000;

/// Removes the lattice points of every `[[body.cut]]` from a filled body (holes, notches):
/// a point goes when it lies in the cut's shape ([`Shape::contains`]). A disc cut (2D) or a
/// cylinder cut (3D) with `rings` also replaces the lattice within `rings` spacings of its rim
/// by concentric rings of particles ([`hole_rings`]), in 3D in every lattice layer along the
/// cylinder's axis that the cut passes through; the particles within two spacings of such a
/// zone then take their Voronoi cell in the body (in 3D: in their layer, times the spacing) as
/// reference volume ([`ring_zone_volumes`]), so the volumes still add up to the body's
/// measure. A cut that removes nothing, rings on another shape or that overlap, and cuts that
/// leave the body empty are errors naming the cut.
fn apply_cuts<const D: usize>(
    ctx: &Context<'_>,
    b: &BodyTable,
    spacing: f64,
    fills: &[Fill<D>],
    positions: &mut Vec<Vector<D>>,
    velocities: &mut Vec<Vector<D>>,
    volumes: &mut Vec<f64>,
) -> Result<(), SceneError> {
    let name = b.name.get_ref();
    let mut keep = vec![true; positions.len()];
    let mut cuts: Vec<Shape<D>> = Vec::new();
    let mut ringed: Vec<RingedCut<D>> = Vec::new();
    // Each ringed cut with the lattice layers it passes through (2D: the one plane, `None`).
    let mut ring_layers: Vec<(usize, Option<f64>)> = Vec::new();
    for (k, cut) in b.cut.iter().enumerate() {
        let field = |key: &str| format!("body[{name}].cut[{k}].{key}");
        if cut.box_.is_none()
            && cut.cylinder.is_none()
            && cut.sphere.is_none()
            && cut.disc.is_none()
        {
            return Err(ctx.error(
                &b.name.span(),
                &field("shape"),
                "has no shape: add box, cylinder, sphere or disc".into(),
            ));
        }
        let as_shape = ShapeTable {
            box_: cut.box_.clone(),
            cylinder: cut.cylinder.clone(),
            sphere: cut.sphere.clone(),
            disc: cut.disc.clone(),
            ..ShapeTable::default()
        };
        let (shape, span) = shape_of::<D>(ctx, &as_shape, &field)?;
        let mut removed = 0usize;
        for (x, kept) in positions.iter().zip(keep.iter_mut()) {
            if shape.contains(x) {
                removed += usize::from(*kept);
                *kept = false;
            }
        }
        if removed == 0 {
            return Err(ctx.error(
                &span,
                &field("shape"),
                format!("removes no particle of body `{name}` (is it outside the body, between lattice points, or inside an earlier cut?)"),
            ));
        }
        if let Some(rings) = &cut.rings {
            let count = *rings.get_ref();
            if !(0..=MAX_RINGS).contains(&count) {
                return Err(ctx.error(
                    &rings.span(),
                    &field("rings"),
                    format!("must be a whole number from 0 to {MAX_RINGS}, got {count}"),
                ));
            }
            let this = match (&shape, D) {
                (_, _) if count == 0 => None,
                (Shape::Ball { centre, radius }, 2) => Some(RingedCut {
                    cut: k,
                    centre: *centre,
                    radius: *radius,
                    rings: count as usize,
                    plane: [0, 1],
                    axial: None,
                }),
                (
                    Shape::Cylinder {
                        base,
                        axis,
                        radius,
                        length,
                    },
                    3,
                ) => {
                    let others: Vec<usize> = (0..3).filter(|j| j != axis).collect();
                    Some(RingedCut {
                        cut: k,
                        centre: *base,
                        radius: *radius,
                        rings: count as usize,
                        plane: [others[0], others[1]],
                        axial: Some((*axis, base[*axis], base[*axis] + length)),
                    })
                }
                _ => return Err(ctx.error(
                    &rings.span(),
                    &field("rings"),
                    "rings follow the rim of a round hole: they need a `disc` cut in a 2D scene or a `cylinder` cut in a 3D one"
                        .into(),
                )),
            };
            if let Some(this) = this {
                if let Some(other) = ringed.iter().find(|o| o.overlaps(&this, spacing)) {
                    return Err(ctx.error(
                        &rings.span(),
                        &field("rings"),
                        format!("the ring zone of this cut (radius + rings x spacing) overlaps that of body[{name}].cut[{}]; use fewer rings or move the holes apart", other.cut),
                    ));
                }
                let outer = this.outer(spacing);
                let mut along_axis: Vec<f64> = Vec::new();
                for (x, kept) in positions.iter().zip(keep.iter_mut()) {
                    let in_zone = this.within(x, outer);
                    if in_zone {
                        *kept = false;
                    }
                    if let Some((axis, _, _)) = this.axial.filter(|_| in_zone || shape.contains(x))
                    {
                        along_axis.push(x[axis]);
                    }
                }
                let ring = ringed.len();
                match this.axial {
                    Some(_) => ring_layers.extend(
                        distinct_layers(along_axis)
                            .into_iter()
                            .map(|s| (ring, Some(s))),
                    ),
                    None => ring_layers.push((ring, None)),
                }
                ringed.push(this);
            }
        }
        cuts.push(shape);
    }
    keep_particles(&keep, positions, velocities, volumes);
    let in_body =
        |x: &Vector<D>| fills.iter().any(|f| f.covers(x)) && !cuts.iter().any(|c| c.contains(x));
    for &(ring, layer) in &ring_layers {
        for x in ringed[ring].rings_in(layer, spacing) {
            if cuts.iter().any(|c| c.contains(&x)) {
                continue;
            }
            // Outside every shape of the body (a hole near its edge): not made.
            if let Some(fill) = fills.iter().find(|f| f.covers(&x)) {
                velocities.push(fill.velocity_at(&x));
                positions.push(x);
                volumes.push(0.0);
            }
        }
    }
    if !ringed.is_empty() {
        let near = |x: &Vector<D>| {
            ringed
                .iter()
                .any(|r| r.within(x, r.outer(spacing) + 2.0 * spacing))
        };
        let targets: Vec<usize> = (0..positions.len())
            .filter(|&i| near(&positions[i]))
            .collect();
        ring_zone_volumes(
            ctx, b, &ringed, spacing, positions, &targets, &in_body, volumes,
        )?;
        // A particle without any sample of the body nearest to it has no share of the body
        // (a ring particle on its very edge): it goes rather than carry a zero mass.
        let keep: Vec<bool> = volumes.iter().map(|v| *v > 0.0).collect();
        keep_particles(&keep, positions, velocities, volumes);
    }
    if positions.is_empty() {
        return Err(ctx.error(
            &b.name.span(),
            &format!("body[{name}].cut"),
            format!("the cuts remove every particle of body `{name}`"),
        ));
    }
    Ok(())
}

/// Whether two coordinates along an axis belong to the same lattice layer (equal to 1e-9,
/// relative to the larger of 1 and the coordinate).
fn same_layer(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// The distinct layers ([`same_layer`]) among the coordinates `along_axis`, in increasing order.
fn distinct_layers(mut along_axis: Vec<f64>) -> Vec<f64> {
    along_axis.sort_by(f64::total_cmp);
    along_axis.dedup_by(|a, b| same_layer(*a, *b));
    along_axis
}

/// Sets the reference volumes of the particles `targets` (those within two spacings of a ring
/// zone) to their Voronoi cells in the body ([`sampled_cell_volumes`]). In 2D the cells are
/// those of the whole body. In 3D the rings of a cylinder lie in the lattice layers along its
/// axis, and each layer is measured on its own: the area of a particle's cell among the
/// particles of its layer, times the spacing. That is the particle's 3D Voronoi cell whenever
/// the layers above and below are laid out alike (a through hole in a plate), costs a 2D
/// sampling per layer instead of a 3D one (32 times fewer samples per cell, 5 times fewer
/// cells), and adds up to the midpoint rule of the body's volume over the layers. Layers of a
/// target set that are less than a spacing apart (shapes of the body whose lattices are
/// shifted along the axis) cannot be measured so and are an error at the cut's `rings`.
#[allow(clippy::too_many_arguments)]
fn ring_zone_volumes<const D: usize>(
    ctx: &Context<'_>,
    b: &BodyTable,
    ringed: &[RingedCut<D>],
    spacing: f64,
    positions: &[Vector<D>],
    targets: &[usize],
    in_body: &dyn Fn(&Vector<D>) -> bool,
    volumes: &mut [f64],
) -> Result<(), SceneError> {
    if D != 3 {
        let cells = sampled_cell_volumes(positions, targets, spacing, in_body);
        for (&i, v) in targets.iter().zip(cells) {
            volumes[i] = v;
        }
        return Ok(());
    }
    // Rings of several cylinders along different axes never share a target (their zones are
    // two spacings apart, `RingedCut::overlaps`), so each target is measured in the plane of
    // the cut it is near.
    for (r, ring) in ringed.iter().enumerate() {
        let Some((axis, _, _)) = ring.axial else {
            continue;
        };
        let reach = ring.outer(spacing) + 2.0 * spacing;
        let mine: Vec<usize> = targets
            .iter()
            .copied()
            .filter(|&i| ring.within(&positions[i], reach))
            .filter(|&i| {
                !ringed[..r]
                    .iter()
                    .any(|o| o.within(&positions[i], o.outer(spacing) + 2.0 * spacing))
            })
            .collect();
        let layers = distinct_layers(mine.iter().map(|&i| positions[i][axis]).collect());
        if let Some(w) = layers
            .windows(2)
            .find(|w| w[1] - w[0] < (1.0 - 1e-9) * spacing)
        {
            let rings = b.cut[ring.cut]
                .rings
                .as_ref()
                .expect("a ringed cut has `rings`");
            return Err(ctx.error(
                &rings.span(),
                &format!("body[{}].cut[{}].rings", b.name.get_ref(), ring.cut),
                format!(
                    "rings in 3D need the body's lattice layers along the cylinder's axis to be one spacing apart, but near this hole there are layers at {} and {} (shapes of the body whose lattices are shifted against each other)",
                    w[0], w[1]
                ),
            ));
        }
        let [a, c] = ring.plane;
        for s in layers {
            let members: Vec<usize> = (0..positions.len())
                .filter(|&i| same_layer(positions[i][axis], s))
                .collect();
            let flat: Vec<Vector<2>> = members
                .iter()
                .map(|&i| Vector::<2>::new(positions[i][a], positions[i][c]))
                .collect();
            let local: Vec<usize> = members
                .iter()
                .enumerate()
                .filter(|(_, &i)| mine.binary_search(&i).is_ok())
                .map(|(j, _)| j)
                .collect();
            let lift = |p: &Vector<2>| {
                let mut x = positions[members[0]];
                x[a] = p[0];
                x[c] = p[1];
                x
            };
            let cells = sampled_cell_volumes(&flat, &local, spacing, |p| in_body(&lift(p)));
            for (&j, v) in local.iter().zip(cells) {
                volumes[members[j]] = v * spacing;
            }
        }
    }
    Ok(())
}

/// Keeps the particles whose flag in `keep` is set, in every per-particle list.
fn keep_particles<const D: usize>(
    keep: &[bool],
    positions: &mut Vec<Vector<D>>,
    velocities: &mut Vec<Vector<D>>,
    volumes: &mut Vec<f64>,
) {
    let mut flags = keep.iter();
    positions.retain(|_| *flags.next().expect("one flag per particle"));
    let mut flags = keep.iter();
    velocities.retain(|_| *flags.next().expect("one flag per particle"));
    let mut flags = keep.iter();
    volumes.retain(|_| *flags.next().expect("one flag per particle"));
}

fn shape_of<const D: usize>(
    ctx: &Context<'_>,
    s: &ShapeTable,
    field: &dyn Fn(&str) -> String,
) -> Result<(Shape<D>, Range<usize>), SceneError> {
    let count = [
        s.box_.is_some(),
        s.cylinder.is_some(),
        s.sphere.is_some(),
        s.disc.is_some(),
    ]
    .iter()
    .filter(|x| **x)
    .count();
    let wrong_dim = |span: Range<usize>, key: &str, need: usize| {
        Err(ctx.error(
            &span,
            &field(key),
            format!("is only available in {need}D scenes, this one is {D}D"),
        ))
    };
    if count > 1 {
        let span = s
            .box_
            .as_ref()
            .map(|x| x.span())
            .or(s.cylinder.as_ref().map(|x| x.span()))
            .unwrap_or(0..0);
        return Err(ctx.error(
            &span,
            &field("shape"),
            "give exactly one of box, cylinder, sphere, disc per shape".into(),
        ));
    }
    let check_len = |v: &[f64], span: &Range<usize>, key: &str| {
        if v.len() != D || !v.iter().all(|x| x.is_finite()) {
            Err(ctx.error(
                span,
                &field(key),
                format!(
                    "needs {D} finite components in a {D}D scene, got {}",
                    v.len()
                ),
            ))
        } else {
            Ok(Vector::<D>::from_iterator(v.iter().copied()))
        }
    };
    let positive = |x: f64, span: &Range<usize>, key: &str| {
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(ctx.error(span, &field(key), format!("must be > 0, got {x}")))
        }
    };
    if let Some(b) = &s.box_ {
        let span = b.span();
        let min = check_len(&b.get_ref().min, &span, "box.min")?;
        let max = check_len(&b.get_ref().max, &span, "box.max")?;
        if (0..D).any(|k| max[k] <= min[k]) {
            return Err(ctx.error(
                &span,
                &field("box"),
                "max must exceed min in every component".into(),
            ));
        }
        return Ok((Shape::Box { min, max }, span));
    }
    if let Some(c) = &s.cylinder {
        let span = c.span();
        if D != 3 {
            return wrong_dim(span, "cylinder", 3);
        }
        let c = c.get_ref();
        let base = check_len(&c.base, &span, "cylinder.base")?;
        let axis = match c.axis.as_str() {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            other => {
                return Err(ctx.error(
                    &span,
                    &field("cylinder.axis"),
                    format!("must be \"x\", \"y\" or \"z\", got \"{other}\""),
                ))
            }
        };
        let radius = positive(c.radius, &span, "cylinder.radius")?;
        let length = positive(c.length, &span, "cylinder.length")?;
        return Ok((
            Shape::Cylinder {
                base,
                axis,
                radius,
                length,
            },
            span,
        ));
    }
    if let Some(r) = &s.sphere {
        let span = r.span();
        if D != 3 {
            return wrong_dim(span, "sphere", 3);
        }
        let centre = check_len(&r.get_ref().centre, &span, "sphere.centre")?;
        let radius = positive(r.get_ref().radius, &span, "sphere.radius")?;
        return Ok((Shape::Ball { centre, radius }, span));
    }
    if let Some(r) = &s.disc {
        let span = r.span();
        if D != 2 {
            return wrong_dim(span, "disc", 2);
        }
        let centre = check_len(&r.get_ref().centre, &span, "disc.centre")?;
        let radius = positive(r.get_ref().radius, &span, "disc.radius")?;
        return Ok((Shape::Ball { centre, radius }, span));
    }
    Err(ctx.error(
        &(0..0),
        &field("shape"),
        "has no shape: add box, cylinder, sphere or disc".into(),
    ))
}

/// The first time-history key given (`ramp_time`, then `amplitude`) with its place, for the
/// error of a fixed wall or boundary that has no velocity to scale.
pub(crate) fn history_key(
    ramp_time: &Option<Spanned<f64>>,
    amplitude: &Option<Spanned<Vec<Vec<f64>>>>,
) -> Option<(&'static str, std::ops::Range<usize>)> {
    ramp_time
        .as_ref()
        .map(|t| ("ramp_time", t.span()))
        .or(amplitude.as_ref().map(|a| ("amplitude", a.span())))
}

/// The time history of a boundary's velocity, a wall's velocity or the body force: either
/// `ramp_time` / `ramp_shape`, a [`VelocityRamp`] (smooth unless `ramp_shape = "linear"`), or
/// `amplitude = [[t, r], ...]`, an [`AmplitudeTable`] joined as `amplitude_shape` says
/// (`"linear"`, default, or `"smooth-step"`), not both; `None` when neither is given.
/// `field` names a key of the table.
pub(crate) fn parse_amplitude(
    ctx: &Context<'_>,
    time: &Option<Spanned<f64>>,
    shape: &Option<Spanned<String>>,
    table: &Option<Spanned<Vec<Vec<f64>>>>,
    table_shape: &Option<Spanned<String>>,
    field: &dyn Fn(&str) -> String,
) -> Result<Option<Amplitude>, SceneError> {
    if let (Some(shape), None) = (table_shape, table) {
        return Err(ctx.error(
            &shape.span(),
            &field("amplitude_shape"),
            "needs an `amplitude` table (a ramp's shape is `ramp_shape`)".into(),
        ));
    }
    if let Some(table) = table {
        let span = table.span();
        if let Some(key) = time
            .as_ref()
            .map(|t| t.span())
            .or(shape.as_ref().map(|s| s.span()))
        {
            return Err(ctx.error(
                &key,
                &field(if time.is_some() { "ramp_time" } else { "ramp_shape" }),
                "a ramp and an `amplitude` table both give the time history; keep one (a table can start with a ramp)".into(),
            ));
        }
        let mut points = Vec::with_capacity(table.get_ref().len());
        for point in table.get_ref() {
            let [t, r] = point.as_slice() else {
                return Err(ctx.error(
                    &span,
                    &field("amplitude"),
                    format!("each point must be [time, factor], got {point:?}"),
                ));
            };
            points.push((*t, *r));
        }
        let shape = ctx.keyword(
            table_shape.as_ref(),
            &field("amplitude_shape"),
            "amplitude shape",
            TableShape::Linear,
            &[
                ("linear", TableShape::Linear),
                ("smooth-step", TableShape::SmoothStep),
            ],
        )?;
        let table = AmplitudeTable::new(points)
            .map_err(|message| ctx.error(&span, &field("amplitude"), message))?;
        return Ok(Some(Amplitude::Table(table.with_shape(shape))));
    }
    let time = match (time, shape) {
        (None, None) => return Ok(None),
        (None, Some(shape)) => {
            return Err(ctx.error(
                &shape.span(),
                &field("ramp_shape"),
                "needs `ramp_time` (the duration of the ramp)".into(),
            ))
        }
        (Some(time), _) => time,
    };
    let duration = ctx.positive(time, &field("ramp_time"))?;
    let shape = ctx.keyword(
        shape.as_ref(),
        &field("ramp_shape"),
        "ramp shape",
        RampShape::Smooth,
        &[("smooth", RampShape::Smooth), ("linear", RampShape::Linear)],
    )?;
    Ok(Some(Amplitude::Ramp(VelocityRamp { duration, shape })))
}

fn build_boundary<const D: usize>(
    ctx: &Context<'_>,
    t: &BoundaryTable,
    body_index: usize,
    body: &BodyDescription<D>,
) -> Result<BoundaryDescription<D>, SceneError> {
    let name = t.name.get_ref().clone();
    let field = |key: &str| format!("boundary[{name}].{key}");
    let particles: Vec<usize> = match (&t.box_, &t.at) {
        (Some(b), None) => {
            let span = b.span();
            let min = ctx.components::<D>(&b.get_ref().min, &span, &field("box.min"))?;
            let max = ctx.components::<D>(&b.get_ref().max, &span, &field("box.max"))?;
            let inside: Vec<usize> = body
                .positions
                .iter()
                .enumerate()
                .filter(|(_, x)| (0..D).all(|k| x[k] >= min[k] && x[k] <= max[k]))
                .map(|(i, _)| i)
                .collect();
            if inside.is_empty() {
                return Err(ctx.error(
                    &span,
                    &field("box"),
                    format!("selects no particle of body `{}`", body.name),
                ));
            }
            inside
        }
        (None, Some(at)) => {
            let point = ctx.vector::<D>(at, &field("at"))?;
            vec![nearest_particle(
                ctx,
                body,
                &point,
                &at.span(),
                &field("at"),
            )?]
        }
        _ => {
            return Err(ctx.error(
                &t.name.span(),
                &field("box"),
                "select particles with exactly one of `box` or `at`".into(),
            ))
        }
    };
    let fixed = t.fixed.as_ref().is_some_and(|f| *f.get_ref());
    let velocity = match (&t.velocity, fixed) {
        (Some(v), false) => ctx.vector::<D>(v, &field("velocity"))?,
        (None, true) => Vector::<D>::zeros(),
        (Some(v), true) => {
            return Err(ctx.error(
                &v.span(),
                &field("velocity"),
                "give either `fixed = true` or `velocity`, not both".into(),
            ))
        }
        (None, false) => {
            return Err(ctx.error(
                &t.name.span(),
                &field("fixed"),
                "needs `fixed = true` or a prescribed `velocity`".into(),
            ))
        }
    };
    let mut components = [true; D];
    if let Some(c) = &t.components {
        if c.get_ref().is_empty() {
            return Err(ctx.error(
                &c.span(),
                &field("components"),
                "lists no axis; leave it out to impose every component".into(),
            ));
        }
        components = [false; D];
        for axis in c.get_ref() {
            let k = match axis.as_str() {
                "x" => 0,
                "y" => 1,
                "z" => 2,
                _ => D,
            };
            if k >= D {
                let axes = ["x", "y", "z"][..D].join(", ");
                return Err(ctx.error(
                    &c.span(),
                    &field("components"),
                    format!("`{axis}` is not an axis of a {D}D scene (axes: {axes})"),
                ));
            }
            components[k] = true;
        }
    }
    if let (Some((key, span)), true) = (history_key(&t.ramp_time, &t.amplitude), fixed) {
        return Err(ctx.error(
            &span,
            &field(key),
            format!(
                "a fixed boundary has nothing to scale in time; give a `velocity` or drop `{key}`"
            ),
        ));
    }
    let amplitude = parse_amplitude(
        ctx,
        &t.ramp_time,
        &t.ramp_shape,
        &t.amplitude,
        &t.amplitude_shape,
        &field,
    )?;
    Ok(BoundaryDescription {
        name,
        body: body_index,
        particles,
        velocity,
        components,
        amplitude,
    })
}

fn build_probe<const D: usize>(
    ctx: &Context<'_>,
    t: &ProbeTable,
    body_index: usize,
    body: &BodyDescription<D>,
    materials: &[MaterialDescription],
) -> Result<ProbeSpec, SceneError> {
    let name = t.name.get_ref().clone();
    let field = |key: &str| format!("probe[{name}].{key}");
    let point = ctx.vector::<D>(&t.at, &field("at"))?;
    let particle = nearest_particle(ctx, body, &point, &t.at.span(), &field("at"))?;
    let mut fields = Vec::with_capacity(t.fields.get_ref().len());
    for f in t.fields.get_ref() {
        let parsed: ParticleField = f
            .parse()
            .map_err(|e: String| ctx.error(&t.fields.span(), &field("fields"), e))?;
        let model = &materials[body.material].model;
        let missing = match parsed {
            ParticleField::Damage if !model.has_damage() => Some("a failure or damage model"),
            ParticleField::SofteningDamage if model.softening_damage().is_none() => {
                Some("a `damage` law")
            }
            ParticleField::FailureDamage if model.failure().is_none() => {
                Some("a `failure` criterion")
            }
            _ => None,
        };
        if let Some(missing) = missing {
            return Err(ctx.error(
                &t.fields.span(),
                &field("fields"),
                format!(
                    "`{parsed}` needs {missing} in the material of body `{}`",
                    body.name
                ),
            ));
        }
        if parsed == ParticleField::Temperature && !materials[body.material].model.has_temperature()
        {
            return Err(ctx.error(
                &t.fields.span(),
                &field("fields"),
                format!(
                    "`temperature` needs adiabatic heating in the material of body `{}` (specific_heat)",
                    body.name
                ),
            ));
        }
        if !parsed.exists_in(D) {
            return Err(ctx.error(
                &t.fields.span(),
                &field("fields"),
                format!("`{f}` does not exist in a {D}D scene"),
            ));
        }
        if fields.contains(&parsed) {
            // `stress_yx` is `stress_xy`: two equal columns would share one CSV header.
            return Err(ctx.error(
                &t.fields.span(),
                &field("fields"),
                format!("`{f}` is listed twice (as `{parsed}`)"),
            ));
        }
        fields.push(parsed);
    }
    if fields.is_empty() {
        return Err(ctx.error(&t.fields.span(), &field("fields"), "lists no field".into()));
    }
    let interval = ctx.positive(&t.interval, &field("interval"))?;
    Ok(ProbeSpec {
        name,
        body: body_index,
        particle,
        fields,
        interval,
    })
}

/// How two bodies were found to start inside each other.
#[derive(Debug, Clone, Copy)]
enum Overlap<const D: usize> {
    /// A particle of the later body closer to one of the earlier body's than half the smaller
    /// spacing (at, distance).
    TooClose(Vector<D>, f64),
    /// A particle whose cell (the cube of side `spacing` centred on it) lies entirely within
    /// the cells of the other body's particles: one body is embedded in the other, whatever
    /// the offset between their lattices (at, that particle's body).
    Embedded(Vector<D>, usize),
}

/// A body's particles binned at half its spacing, with their bounding box grown by half a
/// spacing: every point within a cell of one of its particles lies in the box.
struct BinnedBody<'a, const D: usize> {
    body: &'a BodyDescription<D>,
    grid: tlsph_neighbours::CellGrid<D>,
    lower: Vector<D>,
    upper: Vector<D>,
}

impl<'a, const D: usize> BinnedBody<'a, D> {
    fn new(body: &'a BodyDescription<D>) -> Option<Self> {
        let half = 0.5 * body.spacing;
        let grid = tlsph_neighbours::CellGrid::new(&body.positions, half).ok()?;
        let (mut lower, mut upper) = (body.positions[0], body.positions[0]);
        for x in &body.positions {
            lower = lower.inf(x);
            upper = upper.sup(x);
        }
        let pad = Vector::<D>::repeat(half);
        Some(Self {
            body,
            grid,
            lower: lower - pad,
            upper: upper + pad,
        })
    }

    fn may_hold(&self, x: &Vector<D>) -> bool {
        (0..D).all(|k| x[k] >= self.lower[k] && x[k] <= self.upper[k])
    }

    /// Distance from `x` to the nearest particle closer than `limit` (≤ half the spacing).
    fn nearest_within(&self, x: &Vector<D>, limit: f64) -> Option<f64> {
        let mut nearest: Option<f64> = None;
        if self.may_hold(x) {
            self.grid.for_each_candidate_with_position(x, |_, y| {
                let d = (x - y).norm();
                if d < limit && nearest.is_none_or(|n| d < n) {
                    nearest = Some(d);
                }
            });
        }
        nearest
    }

    /// Whether `x` lies inside the cell of one of the particles, the cube of side `spacing`
    /// centred on it (the grid's cell is half a spacing, so its neighbourhood holds them all).
    fn covers(&self, x: &Vector<D>) -> bool {
        let half = 0.5 * self.body.spacing;
        let mut inside = false;
        if self.may_hold(x) {
            self.grid.for_each_candidate_with_position(x, |_, y| {
                inside |= (x - y).amax() < half;
            });
        }
        inside
    }

    /// Whether the cell of a particle at `x` with `spacing` lies within the union of this
    /// body's cells: each corner of it, moved inward by 1e-6 of the spacing (so that cells
    /// meeting face to face do not count), lies in one of them. Lattice cells tile without
    /// gaps, so the corners decide.
    fn embeds(&self, x: &Vector<D>, spacing: f64) -> bool {
        let reach = 0.5 * spacing * (1.0 - 1e-6);
        (0..1usize << D).all(|corner| {
            let c = Vector::<D>::from_fn(|k, _| {
                if corner >> k & 1 == 1 {
                    x[k] + reach
                } else {
                    x[k] - reach
                }
            });
            self.covers(&c)
        })
    }
}

/// The first pair of bodies that start inside each other: (later body, earlier body, how),
/// for the first pair in body order. Within a pair, the later body's particles are tested
/// first: closer to an earlier body's particle than half the smaller spacing, or their cell
/// embedded in the earlier body's cells; then the earlier body's cells embedded in the later
/// one's (a small body inside a coarser one, or a coarse one around a fine one). Each body is
/// binned at half its own spacing, so a query visits a few particles whatever the ratio of
/// the spacings; particles outside the other body's bounding box are skipped.
fn first_overlap<const D: usize>(
    bodies: &[BodyDescription<D>],
) -> Option<(usize, usize, Overlap<D>)> {
    if bodies.len() < 2 {
        return None;
    }
    // Coordinates and spacings are checked finite by now; a body that cannot be binned means
    // nothing to report here (the solver names the bad value).
    let binned: Vec<Option<BinnedBody<'_, D>>> = bodies.iter().map(BinnedBody::new).collect();
    for later in 1..bodies.len() {
        let Some(b) = &binned[later] else { continue };
        for (earlier, a) in binned[..later].iter().enumerate() {
            let Some(a) = a else { continue };
            let limit = 0.5 * a.body.spacing.min(b.body.spacing);
            for x in &b.body.positions {
                if let Some(d) = a.nearest_within(x, limit) {
                    return Some((later, earlier, Overlap::TooClose(*x, d)));
                }
                if a.embeds(x, b.body.spacing) {
                    return Some((later, earlier, Overlap::Embedded(*x, later)));
                }
            }
            for y in &a.body.positions {
                if b.embeds(y, a.body.spacing) {
                    return Some((later, earlier, Overlap::Embedded(*y, earlier)));
                }
            }
        }
    }
    None
}

/// A point as its coordinates separated by commas, for messages ("0.0005, 0.0005").
pub(crate) fn point_text<const D: usize>(x: &Vector<D>) -> String {
    let parts: Vec<String> = x.iter().map(|c| format!("{c}")).collect();
    parts.join(", ")
}

/// Index of a coordinate axis named "x", "y" or "z".
pub(crate) fn axis_index(name: &str) -> Option<usize> {
    ["x", "y", "z"].iter().position(|a| *a == name)
}

/// The longest plain name: a probe's becomes the file name `<name>.csv`, and file systems
/// allow 255 bytes.
const MAX_NAME_LENGTH: usize = 200;

/// A probe name becomes `probes/<name>.csv`: only plain file names are allowed.
fn is_safe_file_stem(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= MAX_NAME_LENGTH
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
}

/// Nearest particle of `body` to `point` in the reference configuration; an error when the
/// point is more than one spacing away from every particle (outside the body).
fn nearest_particle<const D: usize>(
    ctx: &Context<'_>,
    body: &BodyDescription<D>,
    point: &Vector<D>,
    span: &Range<usize>,
    field: &str,
) -> Result<usize, SceneError> {
    let (index, distance) = body
        .positions
        .iter()
        .enumerate()
        .map(|(i, x)| (i, (x - point).norm()))
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .expect("bodies are never empty");
    if distance > body.spacing {
        return Err(ctx.error(
            span,
            field,
            format!(
                "is outside body `{}`: the nearest particle is {distance:e} away, more than one spacing ({})",
                body.name, body.spacing
            ),
        ));
    }
    Ok(index)
}
