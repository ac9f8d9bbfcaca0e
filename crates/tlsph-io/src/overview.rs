//! What `tlsph check` tells a user about a scene before it runs: per body the particle count,
//! the wave speed of its material and the time step it allows at the start, how each field
//! table met its body's particles, the size of the run that follows from them (steps and
//! particle-steps, the cost measure of the harness), and notes on effects the scene is likely
//! to need.

use crate::scene::{DimensionModel, FieldTableSummary, Scene};
use std::fmt;
use tlsph_materials::EquationOfState;
use tlsph_solver::{Formulation, FrictionCoefficients, Model, WallShape};

/// One body of a [`SceneOverview`].
#[derive(Debug, Clone, PartialEq)]
pub struct BodyOverview {
    /// The body's `name`.
    pub name: String,
    /// The `name` of its material.
    pub material: String,
    /// Number of particles.
    pub particles: usize,
    /// Smoothing length h = `smoothing_factor` · `spacing` \[length\].
    pub smoothing_length: f64,
    /// Wave speed at the reference state c0 (`MaterialDescription::reference_wave_speed`)
    /// \[length/time\].
    pub wave_speed: f64,
    /// Largest initial particle speed |v| \[length/time\].
    pub fastest_particle: f64,
    /// The CFL step the body allows at the start (`Model::initial_time_steps`) \[time\].
    pub first_time_step: f64,
    /// Mie–Grüneisen only: the limiting compression μ_lim (ρ/ρ0 − 1) where the Hugoniot
    /// pressure becomes infinite (numerics.md §8.8); `None` for other materials or when the
    /// Hugoniot has no limit.
    pub compression_limit: Option<f64>,
    /// Polynomial EOS only: the compressions μ (ρ/ρ0 − 1) nearest the reference state, in
    /// tension and in compression, where its cold bulk modulus dp/dμ falls to zero
    /// (`PolynomialEos::stiffness_limits`, numerics.md §8.7); `(None, None)` otherwise.
    pub stiffness_limits: (Option<f64>, Option<f64>),
}

/// The scene at a glance: its bodies, the run's estimated size and advice on its set-up.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneOverview {
    /// Per body, in scene order.
    pub bodies: Vec<BodyOverview>,
    /// Simulated end time \[time\].
    pub end_time: f64,
    /// Set-up advice, one sentence each (printed as `note:` lines): effects a scene is likely
    /// to need for what it declares.
    pub notes: Vec<String>,
    /// How each field table read met its body's particles ([`Scene::field_tables`]).
    pub field_tables: Vec<FieldTableSummary>,
}

impl SceneOverview {
    /// The scene's first CFL step: the smallest over its bodies \[time\] (∞ without bodies).
    pub fn first_time_step(&self) -> f64 {
        self.bodies
            .iter()
            .map(|b| b.first_time_step)
            .fold(f64::INFINITY, f64::min)
    }

    /// Steps the run takes if the first step held to the end: end time / first step.
    /// Compression (a stiffening equation of state), faster particles and contact shorten the
    /// step; slowing particles lengthen it.
    pub fn estimated_steps(&self) -> f64 {
        (self.end_time / self.first_time_step()).ceil()
    }

    /// Particles × estimated steps: the run's size in the harness's cost unit.
    pub fn estimated_particle_steps(&self) -> f64 {
        self.estimated_steps() * self.bodies.iter().map(|b| b.particles).sum::<usize>() as f64
    }
}

impl Scene {
    /// The overview `tlsph check` prints (see [`SceneOverview`]).
    pub fn overview(&self) -> SceneOverview {
        let mut overview = match &self.model {
            DimensionModel::One(m) => overview_of(m),
            DimensionModel::Two(m) => overview_of(m),
            DimensionModel::Three(m) => overview_of(m),
        };
        overview.field_tables = self.field_tables.clone();
        overview
    }
}

fn overview_of<const D: usize>(model: &Model<D>) -> SceneOverview {
    let bodies = model
        .bodies
        .iter()
        .zip(model.initial_time_steps())
        .map(|(body, step)| {
            let material = &model.materials[body.material];
            let eos = material.model.equation_of_state().map(|(eos, _)| eos);
            let compression_limit = match eos {
                Some(EquationOfState::MieGruneisen(eos)) => {
                    Some(eos.compression_limit()).filter(|mu| mu.is_finite())
                }
                _ => None,
            };
            let stiffness_limits = match eos {
                Some(EquationOfState::Polynomial(eos)) => eos.stiffness_limits(),
                _ => (None, None),
            };
            BodyOverview {
                name: body.name.clone(),
                material: material.name.clone(),
                particles: body.positions.len(),
                smoothing_length: step.smoothing_length,
                wave_speed: step.wave_speed,
                fastest_particle: step.fastest_particle,
                first_time_step: step.time_step,
                compression_limit,
                stiffness_limits,
            }
        })
        .collect();
    SceneOverview {
        bodies,
        end_time: model.config.end_time,
        notes: set_up_notes(model),
        field_tables: Vec::new(),
    }
}

/// Advice on effects the scene is likely to need (see [`SceneOverview::notes`]).
///
/// Contact between total-Lagrangian bodies without hourglass control: TLSPH's alternating
/// (zig-zag) surface mode has no stiffness, and a contact load drives it. The potential law's
/// central pair forces push a pressed particle sideways, so a block resting on a base under a
/// steady load sinks between the base's surface particles (0.7 % strain, and more slowly at
/// 0.07 %); under the penalty law the surface zig-zags once pressed hard or sheared by
/// friction. Both were measured and are described in docs/scene-format.md.
///
/// A box wall in a total-Lagrangian scene without hourglass control: its edges make a kink in
/// the displacement that the zig-zag mode takes up (measured: a punch turned 30° to the
/// particle rows threw particles beside its faces off at a third of the sound speed as it
/// withdrew; with coefficient = 1 they stayed put; rounding its edges to a spacing halved the
/// energy error without it, and did not remove it).
///
/// A static friction coefficient above the kinetic one without a decay (walls and the penalty
/// contact): the hold is decided per particle or pair, a slip starts where the ratio of
/// tangential to normal load peaks, and with an instant drop to μ_k it spreads (measured:
/// block on an incline at load ratio 0.3 with μ_k = 0.2 slid for μ_s up to 0.7; with a decay
/// d_c = 100 it held at μ_s = 0.5).
fn set_up_notes<const D: usize>(model: &Model<D>) -> Vec<String> {
    let mut notes = Vec::new();
    let total_lagrangian = model.config.formulation != Formulation::UpdatedLagrangian;
    if total_lagrangian && model.effects.hourglass_control.is_none() {
        let effects = &model.effects;
        if effects.contact.is_some() {
            notes.push(
                "potential contact between total-Lagrangian bodies without \
                 [hourglass_control]: under a steady contact load, even a light one, the pair \
                 forces push surface particles apart into a zig-zag and the other body sinks \
                 between them; declare hourglass control (coefficient = 1 held the case \
                 measured in docs/scene-format.md)"
                    .into(),
            );
        }
        if effects.penalty_contact.is_some() {
            notes.push(
                "penalty contact between total-Lagrangian bodies without [hourglass_control]: \
                 a surface pressed hard, or sheared by friction, can zig-zag particle by \
                 particle and let the other surface dig in (also in self-contact); declare \
                 hourglass control (coefficient = 1 held the cases measured in \
                 docs/scene-format.md)"
                    .into(),
            );
        }
        for wall in &effects.walls {
            let (what, drives) = match wall.shape {
                WallShape::Box { .. } => (
                    "a box",
                    "its edges, pressed into a body, can drive the particle lattice's zig-zag \
                     mode and throw surface particles off beside its faces",
                ),
                WallShape::Cone { .. } => (
                    "a cone",
                    "its tip and flanks, pressed into a body, can drive the particle \
                     lattice's zig-zag mode and pierce the surface",
                ),
                WallShape::Pyramid { .. } => (
                    "a pyramid",
                    "its tip, edges and faces, pressed into a body, can drive the particle \
                     lattice's zig-zag mode and pierce the surface",
                ),
                _ => continue,
            };
            notes.push(format!(
                "wall `{}` is {what} in a total-Lagrangian scene without [hourglass_control]: \
                 {drives}; declare hourglass control (coefficient = 1 held the case \
                 measured in docs/scene-format.md)",
                wall.name
            ));
        }
    }
    let abrupt = |f: &FrictionCoefficients| f.decay.is_none() && f.static_coefficient > f.kinetic;
    let effects = &model.effects;
    let surfaces = effects
        .walls
        .iter()
        .filter(|w| abrupt(&w.friction))
        .map(|w| format!("wall `{}`", w.name))
        .chain(
            effects
                .penalty_contact
                .iter()
                .filter(|c| abrupt(&c.friction))
                .map(|_| "the penalty contact".to_string()),
        );
    for surface in surfaces {
        notes.push(format!(
            "{surface} has static_friction above friction and no friction_decay: a slip that \
             starts where the load ratio is highest (a contact face's edges) drops to the \
             kinetic coefficient at once and can run through the whole face, so a body may \
             slide although its average load ratio is below static_friction; friction_decay \
             keeps slow slips near the static coefficient (both measured in \
             docs/scene-format.md)"
        ));
    }
    notes
}

impl fmt::Display for SceneOverview {
    /// One line per body, then the run's size.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for b in &self.bodies {
            write!(
                f,
                "  body `{}`: {} particles of `{}`, h {:.4e}, wave speed {:.4e}, fastest particle \
                 {:.4e}, first step {:.4e}",
                b.name,
                b.particles,
                b.material,
                b.smoothing_length,
                b.wave_speed,
                b.fastest_particle,
                b.first_time_step
            )?;
            if let Some(mu) = b.compression_limit {
                write!(
                    f,
                    "; equation of state limited to compressions ρ/ρ0 − 1 < {mu:.3e}"
                )?;
            }
            let limits: Vec<String> = [b.stiffness_limits.0, b.stiffness_limits.1]
                .into_iter()
                .flatten()
                .map(|mu| format!("{mu:.3e}"))
                .collect();
            if !limits.is_empty() {
                write!(
                    f,
                    "; warning: the polynomial equation of state's bulk modulus dp/dμ vanishes at \
                     ρ/ρ0 − 1 = {}, and beyond it the pressure falls as the density rises (a fit \
                     used outside its range: waves there are unstable)",
                    limits.join(" and ")
                )?;
            }
            writeln!(f)?;
        }
        for t in &self.field_tables {
            let (fewest, most) = t.samples_per_particle;
            let fit = match t.interpolation {
                "linear" => format!(
                    "linear fit to the samples within {:.4e}: {fewest} to {most} samples per \
                     particle",
                    t.reach
                ),
                _ => format!("nearest sample within {:.4e}", t.reach),
            };
            writeln!(
                f,
                "  {} `{}`: {} samples, {fit}; the nearest sample at most {:.4e} from a \
                 particle; {} samples used by no particle",
                t.field,
                t.path.display(),
                t.samples,
                t.farthest_nearest_sample,
                t.unused_samples
            )?;
        }
        write!(
            f,
            "  about {:.0} steps at the first step ({:.2e} particle-steps); compression, faster \
             particles and contact shorten the step",
            self.estimated_steps(),
            self.estimated_particle_steps()
        )?;
        for note in &self.notes {
            write!(f, "\n  note: {note}")?;
        }
        Ok(())
    }
}
