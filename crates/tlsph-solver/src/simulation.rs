//! The `Simulation`: setup from a `Model`, the staggered leap-frog step, and read access to
//! the state for probes and diagnostics.

use crate::bonds::{build_bonds, BodyBonds, Bonds, CorrectionReport};
use crate::damage::{update_damaged_elastic, DamageState};
use crate::diagnostics::Diagnostics;
use crate::effects::{
    BodyForce, BookedEffect, Configuration, EffectContext, HourglassControl,
    MonaghanArtificialStress, MonaghanViscosity, ParticleContact, PenaltyContact, RigidWall,
};
use crate::error::{LimitingParticle, SetupError, StepError};
use crate::fields::ParticleField;
use crate::ghosts::{check_planes, reflections, Ghosts};
use crate::model::{
    FailureModel, Formulation, MaterialModel, Model, SimulationConfig, StressUpdate, WallShape,
};
use crate::particles::Particles;
use crate::plasticity::{update_elastic_plastic, PlasticBody, PlasticState};
use crate::prescribed::{Drivers, PrescribedSet};
use crate::reference::ReferenceState;
use crate::stability::NeighbourDistances;
use crate::step::{
    gather_accelerations_and_kick, gather_kinematics, particle_kinematics, update_green_lagrange,
    update_jaumann_rate, ConstitutiveStep, InitialReference, NoViscosity, ReferenceJacobian,
};
use crate::updated_lagrangian::UpdatedLagrangian;
use rayon::prelude::*;
use std::ops::Range;
use tlsph_contact::{
    FiniteCylinder, FlatDisc, FrictionCoefficients, PenaltyLaw, PotentialLaw, RigidBall, RigidBox,
    RigidCone, RigidCylinder, RigidPlane, RigidPyramid, WallGeometry,
};
use tlsph_kernels::Kernel;
use tlsph_math::{vector_to_3d, von_mises, Vector, Vector3};
use tlsph_neighbours::build_neighbour_list;
/// Static facts about one body of a running simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyInfo {
    /// Body name.
    pub name: String,
    /// Global particle range.
    pub range: Range<usize>,
    /// Index of its material.
    pub material: usize,
    /// Particle spacing Δx \[m\].
    pub spacing: f64,
    /// Smoothing length h \[m\].
    pub smoothing_length: f64,
    /// Reference density ρ0 \[kg/m³\].
    pub density0: f64,
    /// Sound speed at reference density c0 = sqrt(M/ρ0) \[m/s\].
    pub sound_speed0: f64,
}

/// Bond geometry at one instant (see [`Simulation::bond_metrics`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BondMetrics {
    /// Smallest |x_IJ|/|X_IJ| (clumping shows as a value far below 1).
    pub min_stretch: f64,
    /// Largest |x_IJ|/|X_IJ| (numerical fracture shows as a value far above 1).
    pub max_stretch: f64,
    /// RMS of |F_I X_IJ − x_IJ|/|X_IJ| over bonds: the zero-energy (hourglass) distortion.
    pub hourglass_rms: f64,
    /// Largest |x_IJ| / 2h0 over nearest-neighbour bonds (|X_IJ| ≤ 1.01 Δx of I's body):
    /// above 1, a pair that started as lattice neighbours has left each other's kernel
    /// support — numerical fracture in the sense of problems.md R-P7. Smooth deformation,
    /// however large, moves it only by the stretch (a 50 % stretch gives 1.5Δx/2h0 = 0.5
    /// at h = 1.5Δx).
    pub max_nearest_bond_over_support: f64,
    /// Nearest-neighbour bonds longer than 2h0 (each pair counted from both ends).
    pub nearest_bonds_beyond_support: usize,
}

impl BondMetrics {
    /// Metrics of no measurement yet: NaN ratios, no bond beyond the support.
    pub fn undefined() -> Self {
        Self {
            min_stretch: f64::NAN,
            max_stretch: f64::NAN,
            hourglass_rms: f64::NAN,
            max_nearest_bond_over_support: f64::NAN,
            nearest_bonds_beyond_support: 0,
        }
    }
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepReport {
    /// Index of the completed step (0 is the initial evaluation at t = 0).
    pub step: u64,
    /// Time of the state now held \[s\].
    pub time: f64,
    /// Step size that will be taken next \[s\].
    pub next_dt: f64,
    /// Global index of the particle that limits the next step (CFL).
    pub limiting_particle: usize,
}

/// A running TLSPH simulation in `D` dimensions.
///
/// After [`Simulation::step`] returns, every quantity describes the same instant t^n:
/// displacements u^n, Cauchy stress σ^n, internal energy e^n and (via [`Simulation::velocity`])
/// v^n. Internally the velocity array holds the staggered v^{n+½} (R 5.61–5.71).
#[derive(Debug, Clone)]
pub struct Simulation<const D: usize> {
    config: SimulationConfig,
    materials: Vec<MaterialModel>,
    bodies: Vec<BodyInfo>,
    particles: Particles<D>,
    bonds: Bonds<D>,
    /// Prescribed velocities with their forces and work (empty without `[[boundary]]`).
    drivers: Drivers<D>,
    /// Symmetry ghosts (empty without symmetry planes).
    ghosts: Ghosts<D>,
    /// The declared symmetry planes (to rebuild the ghosts at a reference update).
    planes: Vec<crate::model::SymmetryPlane>,
    /// Artificial bulk viscosity, if declared.
    viscosity: Option<crate::model::BulkViscosity>,
    /// XSPH transport velocities, if declared (total-Lagrangian variant).
    xsph: Option<Xsph<D>>,
    /// Current-configuration pairs and state of the updated-Lagrangian formulation (None for
    /// the total-Lagrangian formulations).
    updated: Option<UpdatedLagrangian<D>>,
    /// Each body's kernel (to rebuild gradients when particles fail).
    kernels: Vec<tlsph_kernels::AnyKernel>,
    /// Failed particles, out of every sum (empty unless a failure model is declared).
    removed: Vec<bool>,
    /// Per real particle, J / det F accumulated over the bond rebuilds after failures (all 1
    /// until a neighbour fails; empty without failure): keeps the EOS density continuous.
    jacobian_carry: Vec<f64>,
    /// Number of failed particles.
    failed_count: usize,
    /// Plastic state per body (empty for elastic bodies).
    plastic: Vec<PlasticState>,
    /// Damage state per body (`DamageState::None` unless its material declares damage).
    damage: Vec<DamageState>,
    /// Reference-configuration update, if declared (TL formulations only).
    reference: Option<ReferenceState<D>>,
    /// Declared effects with their booked energies (empty when none is declared).
    effects: Vec<BookedEffect<D>>,
    /// Each declared effect's share of the accelerations of the current step (one array per
    /// declared effect; none without effects).
    effect_shares: Vec<Vec<Vector<D>>>,
    /// Per-chunk partial sums for deterministic reductions (allocated with the effects).
    chunk_sums: Vec<(f64, Vector<D>)>,
    correction: CorrectionReport,
    time: f64,
    /// Steps completed (0 before the first call to `step`).
    steps_done: u64,
    /// Δt^{n+1}: the step the next call will take (0 before the first call).
    next_dt: f64,
}

impl<const D: usize> Simulation<D> {
    /// Validates the model, builds reference neighbour lists and gradients per body.
    pub fn new(model: Model<D>) -> Result<Self, SetupError> {
        let config = model.config.clone();
        validate_config(&config)?;
        if !(1..=3).contains(&D) {
            return Err(SetupError::InvalidConfig {
                field: "dimension",
                message: format!("{D} is not 1, 2 or 3"),
            });
        }
        let n_total: usize = model.bodies.iter().map(|b| b.positions.len()).sum();
        let mut particles = Particles::with_capacity(n_total);
        let mut bodies = Vec::with_capacity(model.bodies.len());
        for body in &model.bodies {
            let material =
                model
                    .materials
                    .get(body.material)
                    .ok_or_else(|| SetupError::UnknownMaterial {
                        body: body.name.clone(),
                        material: body.material,
                    })?;
            validate_body(body, material.density)?;
            let first = particles.len();
            for ((x, &v0), vel) in body
                .positions
                .iter()
                .zip(&body.volumes)
                .zip(&body.velocities)
            {
                particles.push(*x, v0, material.density, *vel);
            }
            bodies.push(BodyInfo {
                name: body.name.clone(),
                range: first..particles.len(),
                material: body.material,
                spacing: body.spacing,
                smoothing_length: config.smoothing_factor * body.spacing,
                density0: material.density,
                sound_speed0: material.reference_wave_speed(),
            });
        }
        let n_real = particles.len();
        let kernels = bodies
            .iter()
            .map(|info| {
                config
                    .kernel
                    .build(D, info.smoothing_length)
                    .map_err(|e| SetupError::Kernel(e.to_string()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let corrected = config.formulation == Formulation::TotalLagrangianCorrected;
        // Updated-Lagrangian ghosts follow the current positions and are built with the first
        // Verlet list; the reference bonds (for the stability metrics) then have none.
        let updated_lagrangian = config.formulation == Formulation::UpdatedLagrangian;
        check_planes(
            bodies.iter().map(|info| {
                (
                    info.name.as_str(),
                    &particles.positions0[info.range.clone()],
                    info.spacing,
                )
            }),
            &model.effects.symmetry_planes,
        )?;
        let reference_planes: &[crate::model::SymmetryPlane] = if updated_lagrangian {
            &[]
        } else {
            &model.effects.symmetry_planes
        };
        let (ghosts, bonds, correction) = build_reference(
            &bodies,
            &kernels,
            &mut particles,
            reference_planes,
            &[],
            corrected,
        )?;

        let prescribed = model
            .boundaries
            .iter()
            .map(|b| {
                let info = bodies
                    .get(b.body)
                    .ok_or_else(|| SetupError::InvalidBoundary {
                        boundary: b.name.clone(),
                        message: format!("body #{} does not exist", b.body),
                    })?;
                let n = info.range.len();
                if let Some(&bad) = b.particles.iter().find(|&&i| i >= n) {
                    return Err(SetupError::InvalidBoundary {
                        boundary: b.name.clone(),
                        message: format!(
                            "particle {bad} is outside body `{}` ({n} particles)",
                            info.name
                        ),
                    });
                }
                if !b.velocity.iter().all(|x| x.is_finite()) {
                    return Err(SetupError::InvalidBoundary {
                        boundary: b.name.clone(),
                        message: "velocity is not finite".into(),
                    });
                }
                if let Some(amplitude) = &b.amplitude {
                    amplitude
                        .validate()
                        .map_err(|message| SetupError::InvalidBoundary {
                            boundary: b.name.clone(),
                            message,
                        })?;
                }
                Ok(PrescribedSet {
                    name: b.name.clone(),
                    particles: b.particles.iter().map(|i| info.range.start + i).collect(),
                    velocity: b.velocity,
                    components: b.components,
                    amplitude: b.amplitude.clone(),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let drivers = Drivers::new(prescribed, n_real);
        if config.stress_update == StressUpdate::GreenLagrange {
            if let Some(m) = model
                .bodies
                .iter()
                .map(|b| &model.materials[b.material])
                .find(|m| m.model.has_plastic_strain())
            {
                return Err(SetupError::InvalidConfig {
                    field: "stress_update",
                    message: format!(
                        "material `{}` is elastic-plastic, which needs stress_update = \"jaumann-rate\" (the Green-Lagrange path is hyperelastic only)",
                        m.name
                    ),
                });
            }
        }
        let plastic = bodies
            .iter()
            .map(|b| PlasticState::for_material(&model.materials[b.material].model, b.range.len()))
            .collect();
        let damage = bodies
            .iter()
            .map(|b| {
                DamageState::for_material(
                    &model.materials[b.material].model,
                    &particles.volumes0[b.range.clone()],
                )
            })
            .collect();
        if config.stress_update == StressUpdate::GreenLagrange {
            if let Some(m) = model
                .materials
                .iter()
                .find(|m| m.model.softening_damage().is_some())
            {
                return Err(SetupError::InvalidConfig {
                    field: "stress_update",
                    message: format!(
                        "material `{}` has a damage model, which needs stress_update = \"jaumann-rate\"",
                        m.name
                    ),
                });
            }
        }
        let any_failure = bodies
            .iter()
            .any(|b| model.materials[b.material].model.has_damage());
        if let Some(v) = model.effects.bulk_viscosity {
            let ok = [v.quadratic, v.linear]
                .iter()
                .all(|c| c.is_finite() && *c >= 0.0);
            if !ok || config.stress_update == StressUpdate::GreenLagrange {
                return Err(SetupError::InvalidConfig {
                    field: "bulk_viscosity",
                    message: "coefficients must be finite and ≥ 0, and the viscosity needs stress_update = \"jaumann-rate\"".into(),
                });
            }
        }
        if any_failure && model.effects.xsph.is_some() {
            return Err(SetupError::InvalidConfig {
                field: "xsph",
                message: "XSPH cannot be combined with a failure model yet (its averages would keep failed particles in)".into(),
            });
        }
        if updated_lagrangian {
            check_updated_lagrangian_effects(&model)?;
        } else if model.effects.artificial_stress.is_some() {
            return Err(SetupError::InvalidConfig {
                field: "artificial_stress",
                message: "artificial stress is for formulation = \"updated-lagrangian\" only (TLSPH has no tensile instability to correct)".into(),
            });
        }
        if let Some(groups) = &model.effects.kernel_groups {
            if !updated_lagrangian {
                return Err(SetupError::InvalidConfig {
                    field: "kernel_group",
                    message: "kernel interaction groups are for formulation = \"updated-lagrangian\" only (TLSPH bodies interact only through contact)".into(),
                });
            }
            if groups.len() != bodies.len() {
                return Err(SetupError::InvalidConfig {
                    field: "kernel_group",
                    message: format!(
                        "{} groups given for {} bodies (one per body)",
                        groups.len(),
                        bodies.len()
                    ),
                });
            }
        }
        let xsph = match model.effects.xsph {
            None => None,
            Some(_) if updated_lagrangian => None,
            Some(epsilon)
                if epsilon.is_finite() && (0.0..=1.0).contains(&epsilon) && epsilon > 0.0 =>
            {
                Some(Xsph::new(
                    epsilon, &bonds, &particles, &kernels, &bodies, n_real,
                ))
            }
            Some(epsilon) => {
                return Err(SetupError::InvalidConfig {
                    field: "xsph",
                    message: format!("epsilon must be in (0, 1], got {epsilon}"),
                })
            }
        };
        let removed = if any_failure {
            vec![false; particles.len()]
        } else {
            Vec::new()
        };
        let reference = match model.effects.reference_update {
            None => None,
            Some(update) => {
                check_reference_update(&model, update, any_failure)?;
                Some(ReferenceState::new(
                    update.strain_threshold,
                    update.support,
                    &particles.positions0[..n_real],
                ))
            }
        };
        let effects = build_effects(
            &model, &bodies, &kernels, &particles, &bonds, &drivers, n_real,
        )?;
        let updated = updated_lagrangian.then(|| {
            let body = body_indices(&bodies, n_real);
            let group = body
                .iter()
                .map(|&b| model.kernel_group(b as usize) as u32)
                .collect();
            let xsph = model
                .effects
                .xsph
                .map(|epsilon| (epsilon, particles.velocities.clone()));
            let need_values = xsph.is_some() || model.effects.artificial_stress.is_some();
            UpdatedLagrangian::new(body, group, kernels.clone(), need_values, xsph)
        });
        let n_effect = if effects.is_empty() { 0 } else { n_real };
        let mut sim = Self {
            effect_shares: vec![vec![Vector::zeros(); n_real]; effects.len()],
            chunk_sums: Vec::with_capacity(n_effect.div_ceil(CHUNK)),
            effects,
            ghosts,
            planes: model.effects.symmetry_planes.clone(),
            reference,
            viscosity: model.effects.bulk_viscosity,
            xsph,
            updated,
            kernels,
            jacobian_carry: if any_failure {
                vec![1.0; n_real]
            } else {
                Vec::new()
            },
            removed,
            failed_count: 0,
            config,
            materials: model.materials.iter().map(|m| m.model).collect(),
            bodies,
            particles,
            bonds,
            drivers,
            plastic,
            damage,
            correction,
            time: 0.0,
            steps_done: 0,
            next_dt: 0.0,
        };
        for (b, body) in model.bodies.iter().enumerate() {
            // Before the stresses: a work-hardened particle's yield surface is larger.
            if let Some(strains) = &body.initial_plastic_strains {
                sim.set_initial_plastic_strains(b, strains)?;
            }
            if let Some(damages) = &body.initial_damage {
                sim.set_initial_damage(b, damages)?;
            }
            if let Some(damages) = &body.initial_failure_damage {
                sim.set_initial_failure_damage(b, damages)?;
            }
            if let Some(stresses) = &body.initial_stresses {
                if body.initial_stress.is_some() || body.initial_stress_gradient.is_some() {
                    return Err(SetupError::InvalidBody {
                        body: body.name.clone(),
                        message: "an initial stress per particle excludes a uniform or linear one (initial_stress, initial_stress_gradient)".into(),
                    });
                }
                sim.set_initial_stresses(b, stresses)?;
                continue;
            }
            match (body.initial_stress, body.initial_stress_gradient) {
                (None, None) => {}
                (Some(stress), None) => sim.set_initial_stress(b, stress)?,
                (uniform, Some(gradient)) => {
                    let at_origin = uniform.unwrap_or_else(tlsph_math::Tensor3::zeros);
                    sim.set_initial_stress_field(b, |x| {
                        crate::model::linear_stress_at(at_origin, &gradient, x)
                    })?;
                }
            }
        }
        sim.announce_reference_ghosts();
        // Prescribed velocities hold from t = 0.
        sim.impose_velocities(0.0);
        Ok(sim)
    }

    /// Advances to the next time level (the first call evaluates the state at t = 0 and takes
    /// the half kick of R 5.66). Returns an error naming step, particle and field if a value
    /// becomes non-finite or a particle inverts; the state then stays inspectable.
    pub fn step(&mut self) -> Result<StepReport, StepError> {
        let dt = self.next_dt;
        if self.steps_done > 0 {
            // Drift: u^n = u^{n−1} + Δt^n v^{n−½} (R 5.67), with the XSPH velocity if declared.
            let transport = match (&self.xsph, &self.updated) {
                (Some(x), _) => &x.velocity,
                (
                    None,
                    Some(UpdatedLagrangian {
                        xsph: Some((_, v)), ..
                    }),
                ) => v,
                _ => &self.particles.velocities,
            };
            self.particles
                .displacements
                .par_iter_mut()
                .zip(transport.par_iter())
                .for_each(|(u, v)| *u += v * dt);
            self.time += dt;
        }
        let step = self.steps_done;
        self.ghosts.refresh_kinematics(&mut self.particles);
        match &mut self.updated {
            Some(updated) => {
                if step > 0 {
                    // First half of this step's internal energy: the stress power of the
                    // forces at t^{n−1} (their pairs, ∇W and σ/ρ²) with v^{n−½}, before the
                    // list moves to x^n. An equation of state then reads e with this half.
                    updated.book_previous_stress_power(&mut self.particles, dt);
                }
                if updated.rebuild_due(&self.particles) {
                    if !self.planes.is_empty() {
                        rebuild_current_ghosts(
                            updated,
                            &mut self.ghosts,
                            &mut self.particles,
                            &mut self.removed,
                            &mut self.effects,
                            &self.planes,
                        );
                    }
                    if updated.rebuild(&self.particles, &self.removed).is_err() {
                        // The neighbour search only fails on non-finite positions.
                        let first = self.particles.displacements.len();
                        return Err(self.non_finite(step, first.saturating_sub(1)));
                    }
                }
                updated.evaluate_kernel();
                updated.gather_kinematics(&mut self.particles, dt);
            }
            None => gather_kinematics(
                &self.bonds,
                &mut self.particles,
                self.xsph.as_ref().map(|x| &x.velocity[..]),
            ),
        }
        // The updated-Lagrangian formulation books e from its pair sums instead (below).
        let book_energy = self.updated.is_none();
        for (b, info) in self.bodies.iter().enumerate() {
            let body = BodyUpdate {
                material: &self.materials[info.material],
                stress_update: self.config.stress_update,
                viscosity: self.viscosity,
                spacing: info.spacing,
                plastic: &mut self.plastic[b],
                damage: &mut self.damage[b],
            };
            match &self.reference {
                None => body.update(
                    &constitutive_step(
                        info,
                        dt,
                        &InitialReference,
                        &self.jacobian_carry,
                        book_energy,
                    ),
                    &mut self.particles,
                ),
                Some(reference) => body.update(
                    &constitutive_step(
                        info,
                        dt,
                        &reference.jacobian[info.range.clone()],
                        &self.jacobian_carry,
                        book_energy,
                    ),
                    &mut self.particles,
                ),
            }
        }
        self.ghosts.refresh_stress(&mut self.particles);
        if !self.removed.is_empty() {
            self.remove_newly_failed(dt);
        }
        if let Some(i) = first_index_where(&self.particles.jacobian, |j| j.is_nan() || *j <= 0.0) {
            let jacobian = self.particles.jacobian[i];
            if !jacobian.is_finite() {
                // A non-finite F comes from non-finite kinematics: name the root cause.
                return Err(self.non_finite(step, i));
            }
            let (body, particle) = self.locate(i);
            return Err(StepError::Inverted {
                step,
                time: self.time,
                body,
                particle,
                jacobian,
            });
        }
        // The CFL step reads v^{n−½} and J^n only, so it can be taken before the forces, which
        // lets the force gather apply the kick in the same pass.
        // Effects vote at x^n too (contact stiffness, numerics.md §7); none declared: no vote.
        let mut effect_limit = (f64::INFINITY, usize::MAX);
        let at = Configuration {
            particles: &self.particles,
            bonds: &self.bonds,
            pairs: self.updated.as_ref().map(|u| &u.pairs),
            time: self.time,
        };
        for booked in &mut self.effects {
            if let Some(limit) = booked.effect.time_step_limit(&at) {
                effect_limit = min_by_value_then_index(effect_limit, limit);
            }
        }
        let (next_dt, limiting_particle) = self.stable_dt(effect_limit, step)?;
        // Kick: v^{n+½} = v^{n−½} + ½(Δt^n + Δt^{n+1}) a^n (R 5.64–5.66; Δt^0 = 0 gives the
        // first half step).
        let kick = 0.5 * (dt + next_dt);
        match &mut self.updated {
            Some(updated) => {
                updated.update_stress_over_density2(&self.particles);
                updated.gather_accelerations_and_stress_power(&mut self.particles, dt);
                crate::updated_lagrangian::kick(&mut self.particles, kick);
            }
            None => gather_accelerations_and_kick(&self.bonds, &mut self.particles, kick),
        }
        // Held components take their prescribed value at the mid-point of the coming drift.
        let velocity_time = self.time + 0.5 * next_dt;
        self.drivers.prepare_step(velocity_time);
        self.apply_effects(
            kick,
            if kick > 0.0 {
                0.5 * next_dt / kick
            } else {
                0.0
            },
        );
        // The kicked velocity is v^{n+½} of the coming drift, centred at t^n + ½Δt^{n+1}.
        // Held components take their prescribed value there (the kick they got is the
        // driver's impulse, booked as its force and work).
        self.drivers.drive(&mut self.particles, dt, next_dt);
        if let Some(xsph) = &mut self.xsph {
            xsph.update(
                &self.bonds,
                &self.particles.velocities,
                self.ghosts.first_or(self.particles.len()),
            );
            self.drivers.impose_current(&mut xsph.velocity);
            self.ghosts.mirror(&mut xsph.velocity);
        }
        if let Some(updated) = &mut self.updated {
            // Neighbours' v^{n+½} (ghosts: their parents' after every kick and imposition).
            self.ghosts.refresh_motion(&mut self.particles);
            updated.update_xsph(&self.particles);
            if let Some((_, transport)) = &mut updated.xsph {
                self.drivers.impose_current(transport);
            }
        }
        self.next_dt = next_dt;
        self.steps_done += 1;
        self.check_finite(step)?;
        if let Some(reference) = &self.reference {
            let n_real = self.n_particles();
            if reference.due(&self.particles.deformation_gradient[..n_real]) {
                self.update_reference(step)?;
            }
        }
        Ok(StepReport {
            step,
            time: self.time,
            next_dt,
            limiting_particle,
        })
    }

    /// Runs until `end_time`, calling `observe` after every step (including the first one,
    /// at t = 0).
    pub fn run(&mut self, mut observe: impl FnMut(&Self, &StepReport)) -> Result<(), StepError> {
        while !self.finished() {
            let report = self.step()?;
            observe(self, &report);
        }
        Ok(())
    }

    /// True once the state at `end_time` has been computed.
    pub fn finished(&self) -> bool {
        self.steps_done > 0 && self.next_dt <= 0.0
    }

    /// Δt^{n+1} = C_cfl min_I h_I / (c_I + |v_I|) with c_I = c0 sqrt(J_I) (R 5.69–5.70; for a
    /// material with an equation of state c_I = sqrt((K_s + 4G/3)/ρ_I) with the EOS's current
    /// isentropic bulk modulus K_s and the J the EOS reads, numerics.md §8.10 `[C]`), or
    /// the effects' limit (contact, numerics.md §7) when smaller, clipped so the run ends
    /// exactly at `end_time`. A limit that is zero, not a number, or too small to advance the
    /// clock (a speed whose square overflows, say) is an error: the run could not advance, yet
    /// would look finished.
    fn stable_dt(&self, effect_limit: (f64, usize), step: u64) -> Result<(f64, usize), StepError> {
        let mut best = (f64::INFINITY, 0usize);
        let p = &self.particles;
        for info in &self.bodies {
            let r = info.range.clone();
            let h = info.smoothing_length;
            let velocities = p.velocities[r.clone()].par_iter();
            let jacobians = p.jacobian[r.clone()].par_iter();
            let local = match self.materials[info.material].equation_of_state() {
                // c = sqrt((K_s(μ, E_v) + 4G/3) J/ρ0): the EOS's current isentropic
                // stiffness, which grows several-fold in a strong shock. J is the one the EOS
                // reads: carried across neighbour-set rebuilds after failures (§4.3, §9.3).
                Some((eos, shear)) => {
                    let (rho0, shear_term) = (info.density0, 4.0 / 3.0 * shear);
                    let limit = |k: usize, v: &Vector<D>, j: f64, e: f64| {
                        let c = eos_sound_speed(&eos, shear_term, rho0, j, e);
                        (h / (c + v.norm()), r.start + k)
                    };
                    let energies = p.internal_energy[r.clone()].par_iter();
                    if self.jacobian_carry.is_empty() {
                        velocities
                            .zip(jacobians)
                            .zip(energies)
                            .enumerate()
                            .map(|(k, ((v, &j), &e))| limit(k, v, j, e))
                            .reduce(|| (f64::INFINITY, usize::MAX), min_by_value_then_index)
                    } else {
                        velocities
                            .zip(jacobians.zip(self.jacobian_carry[r.clone()].par_iter()))
                            .zip(energies)
                            .enumerate()
                            .map(|(k, ((v, (&j, &carry)), &e))| limit(k, v, j * carry, e))
                            .reduce(|| (f64::INFINITY, usize::MAX), min_by_value_then_index)
                    }
                }
                // A constant modulus: c = c0 sqrt(J) (R 5.69–5.70).
                None => velocities
                    .zip(jacobians)
                    .enumerate()
                    .map(|(k, (v, j))| {
                        let c = info.sound_speed0 * j.max(0.0).sqrt();
                        (h / (c + v.norm()), r.start + k)
                    })
                    .reduce(|| (f64::INFINITY, usize::MAX), min_by_value_then_index),
            };
            best = min_by_value_then_index(best, local);
        }
        let remaining = self.config.end_time - self.time;
        best.0 *= self.config.cfl;
        if effect_limit.0 < best.0 || effect_limit.0.is_nan() {
            best = effect_limit;
        }
        let dt = best.0;
        // `time + dt == time`: a step too small to move the clock would never end the run.
        if dt.is_nan() || dt <= 0.0 || self.time + dt == self.time {
            let limiting = (best.1 < self.n_particles()).then(|| {
                let (body, particle) = self.locate(best.1);
                LimitingParticle {
                    body,
                    particle,
                    speed: p.velocities[best.1].norm(),
                    sound_speed: self.sound_speed(best.1),
                }
            });
            return Err(StepError::TimeStepCollapse {
                step,
                time: self.time,
                particle: limiting,
                dt,
            });
        }
        // Avoid a sliver of a final step: stretch into the end when within 1 % of it.
        let dt = if remaining <= dt * 1.01 {
            remaining.max(0.0)
        } else {
            dt
        };
        Ok((dt, best.1))
    }

    /// The current sound speed of particle `i` as the time step sees it (the per-body loops of
    /// [`Self::stable_dt`], for one particle; for error messages).
    fn sound_speed(&self, i: usize) -> f64 {
        let p = &self.particles;
        let info = &self.bodies[body_index(&self.bodies, i)];
        match self.materials[info.material].equation_of_state() {
            Some((eos, shear)) => eos_sound_speed(
                &eos,
                4.0 / 3.0 * shear,
                info.density0,
                p.jacobian[i] * self.jacobian_carry.get(i).copied().unwrap_or(1.0),
                p.internal_energy[i],
            ),
            None => info.sound_speed0 * p.jacobian[i].max(0.0).sqrt(),
        }
    }

    /// Makes the current configuration the reference (numerics.md §4 `[C]`, `reference.rs`):
    /// X := x, u := 0, V := m J / ρ0, F := I, J0 := J; ghosts, bonds, corrected gradients and
    /// the effects' bond data are rebuilt on the new reference. The state at t^n (velocities,
    /// stresses, plastic state, energies) is untouched.
    fn update_reference(&mut self, step: u64) -> Result<(), StepError> {
        let n_real = self.n_particles();
        let Some(reference) = &mut self.reference else {
            return Ok(());
        };
        let p = &mut self.particles;
        reference.advance(&p.deformation_gradient[..n_real]);
        for info in &self.bodies {
            let r = info.range.clone();
            p.positions0[r.clone()]
                .par_iter_mut()
                .zip(p.displacements[r.clone()].par_iter_mut())
                .zip(p.volumes0[r.clone()].par_iter_mut())
                .zip(p.deformation_gradient[r.clone()].par_iter_mut())
                .zip(reference.jacobian[r.clone()].par_iter_mut())
                .zip(p.masses[r.clone()].par_iter().zip(&p.jacobian[r]))
                .for_each(|(((((x, u), volume), f), j0), (&m, &j))| {
                    *x += *u;
                    *u = Vector::zeros();
                    *volume = m * j / info.density0;
                    *f = tlsph_math::Tensor::identity();
                    *j0 = j;
                });
        }
        reference.updates += 1;
        p.truncate(n_real);
        let corrected = self.config.formulation == Formulation::TotalLagrangianCorrected;
        let (ghosts, bonds, correction) = build_reference(
            &self.bodies,
            &self.kernels,
            p,
            &self.planes,
            &reference.kernel_scale,
            corrected,
        )
        .map_err(|e| StepError::ReferenceUpdate {
            step,
            time: self.time,
            message: e.to_string(),
        })?;
        self.ghosts = ghosts;
        self.bonds = bonds;
        self.correction = correction;
        // Ghost stresses and kinematics follow their (new) parents, as after any step.
        self.ghosts.refresh_kinematics(&mut self.particles);
        self.ghosts.refresh_stress(&mut self.particles);
        for booked in &mut self.effects {
            booked
                .effect
                .reference_changed(&self.particles, &self.bonds);
        }
        self.announce_reference_ghosts();
        Ok(())
    }

    /// Tells the effects the body of every particle, total-Lagrangian symmetry ghosts included
    /// (at setup and after a reference update rebuilt them); nothing to tell without ghosts.
    fn announce_reference_ghosts(&mut self) {
        if self.ghosts.parent.is_empty() {
            return;
        }
        let n_real = self.ghosts.first;
        let mut body = body_indices(&self.bodies, n_real);
        for &parent in &self.ghosts.parent {
            body.push(body[parent]);
        }
        for booked in &mut self.effects {
            booked.effect.ghosts_rebuilt(&body);
        }
    }

    /// Takes the particles that failed in this step's constitutive update (of a step of `dt`)
    /// out of every sum, before the forces at t^n are gathered.
    fn remove_newly_failed(&mut self, dt: f64) {
        let mut newly = Vec::new();
        for (b, info) in self.bodies.iter().enumerate() {
            newly.extend(
                self.plastic[b]
                    .take_newly_failed()
                    .into_iter()
                    .chain(self.damage[b].take_newly_failed())
                    .map(|k| info.range.start + k),
            );
        }
        if newly.is_empty() {
            return;
        }
        self.mark_removed(&newly);
        if let Some(updated) = &mut self.updated {
            // The failed particles leave this step's force sums already: the pair list at x^n
            // is rebuilt without them (a non-finite position, reported by the step's checks,
            // leaves it to the next step).
            match updated.rebuild(&self.particles, &self.removed) {
                Ok(()) => updated.evaluate_kernel(),
                Err(_) => updated.mark_stale(),
            }
        }
        self.failed_count += newly.len();
        let rebuilt = self.remove_bonds_of(&newly);
        if self.updated.is_none() {
            self.regather_after_failure(&rebuilt, dt);
            self.fail_orphans(&rebuilt);
        }
    }

    /// Flags `failed` (real particles) and their mirror images as out of every sum.
    fn mark_removed(&mut self, failed: &[usize]) {
        for &i in failed {
            self.removed[i] = true;
        }
        // A failed particle's mirror images leave the sums with it.
        for (k, &parent) in self.ghosts.parent.iter().enumerate() {
            if self.removed[parent] {
                self.removed[self.ghosts.first + k] = true;
            }
        }
    }

    /// Takes the reference bonds of `failed` out and rebuilds their survivors' gradients;
    /// returns the survivors whose gradients were rebuilt.
    fn remove_bonds_of(&mut self, failed: &[usize]) -> Vec<usize> {
        let bodies = &self.bodies;
        let kernels = &self.kernels;
        let body_of = |i: usize| body_index(bodies, i);
        self.bonds.remove_failed(
            failed,
            &self.removed,
            &self.particles.positions0,
            &self.particles.volumes0,
            |i| kernels[body_of(i)],
            self.config.formulation == Formulation::TotalLagrangianCorrected,
            &self.ghosts,
        )
    }

    /// TLSPH: a surviving particle whose reference neighbours have all failed is a lone point
    /// mass. Nothing can strain it any more, so a stress it kept would stay frozen for the rest
    /// of the run; it fails with them instead (numerics.md §9.3: no stress, mass and momentum
    /// kept, its internal energy moves to `deleted_particles`). Its last energy increment was
    /// already re-paired with its empty gradient sum by [`Self::regather_after_failure`].
    /// Removing it changes no surviving particle's bonds, so this never cascades. Only the
    /// particles that just lost bonds (`rebuilt`) can have become orphans.
    fn fail_orphans(&mut self, rebuilt: &[usize]) {
        let (bonds, removed) = (&self.bonds, &self.removed);
        let orphans: Vec<usize> = rebuilt
            .iter()
            .copied()
            .filter(|&i| bonds.neighbours_of(i).iter().all(|&j| removed[j as usize]))
            .collect();
        if orphans.is_empty() {
            return;
        }
        for &i in &orphans {
            let b = body_index(&self.bodies, i);
            let k = i - self.bodies[b].range.start;
            self.plastic[b].mark_removed(k);
            self.damage[b].mark_removed(k);
            self.particles.stress[i] = tlsph_math::Tensor3::zeros();
            self.particles.pk1[i] = tlsph_math::Tensor::<D>::zeros();
        }
        self.mark_removed(&orphans);
        self.failed_count += orphans.len();
        // Its bonds all lead to removed particles: only its own gradient sum is left to clear.
        self.remove_bonds_of(&orphans);
        self.ghosts.refresh_stress(&mut self.particles);
    }

    /// After a bond rebuild (failures), for every survivor whose gradients were rebuilt
    /// (`rebuilt`, TLSPH):
    /// - J / det F ← (J / det F)·det F_old / det F_new at the same displacements u^n, so the
    ///   density the EOS reads stays continuous (DJ/Dt = J tr D, numerics.md §4.3) instead of
    ///   jumping with the kernel estimate; a jump would change p(J, e) without any p dV work
    ///   booked in e;
    /// - e ← e + ½Δt (V0/m) P^n : (Ḟ_new − Ḟ_old), with both rates from the same v^{n−½}. The
    ///   increment of e just taken paired P^n with the old bonds' Ḟ, but the forces at t^n
    ///   act through the new bonds: the discrete identity Σ V0 P:Ḟ = −Σ m a·v (numerics.md
    ///   §4.5–4.6) holds for one set of gradients, so without this the total energy jumps at
    ///   every removal step.
    ///
    /// F^n and Ḟ^{n−½} of the old bonds are still in the particle arrays (gathered this step);
    /// they are replaced by the new bonds' values.
    fn regather_after_failure(&mut self, rebuilt: &[usize], dt: f64) {
        if self.jacobian_carry.is_empty() {
            return;
        }
        let p = &self.particles;
        let regathered: Vec<_> = rebuilt
            .par_iter()
            .map(|&i| particle_kinematics(&self.bonds, &p.displacements, &p.velocities, i))
            .collect();
        let p = &mut self.particles;
        for (&i, (f_new, f_dot_new)) in rebuilt.iter().zip(regathered) {
            p.internal_energy[i] += 0.5 * dt * p.volumes0[i] / p.masses[i]
                * p.pk1[i]
                    .component_mul(&(f_dot_new - p.deformation_rate[i]))
                    .sum();
            p.deformation_rate[i] = f_dot_new;
            let det_old = tlsph_math::embed_with_identity(&p.deformation_gradient[i]).determinant();
            let det_new = tlsph_math::embed_with_identity(&f_new).determinant();
            if det_old > 0.0 && det_new > 0.0 {
                self.jacobian_carry[i] *= det_old / det_new;
            }
            p.deformation_gradient[i] = f_new;
        }
        // The ghosts' F follows their parents' regathered F (hourglass control reads it).
        self.ghosts.refresh_stress(&mut self.particles);
    }

    /// Geometric health of the reference bonds at the current time (for stability and
    /// hourglass diagnostics; one pass over the bonds, not part of a step):
    /// the smallest and largest bond stretch |x_IJ|/|X_IJ| over real–real bonds of surviving
    /// particles, and the RMS of the hourglass error |F_I X_IJ − x_IJ| / |X_IJ|
    /// (numerics.md §10.5: zero for any deformation F reproduces exactly), and the
    /// numerical-fracture measure of nearest-neighbour bonds (see [`BondMetrics`]).
    pub fn bond_metrics(&self) -> BondMetrics {
        let n = self.n_particles();
        let p = &self.particles;
        let alive = |i: usize| self.removed.is_empty() || !self.removed[i];
        let (mut min, mut max, mut sum_sq, mut count) = (f64::INFINITY, 0.0f64, 0.0f64, 0usize);
        let (mut nearest_max, mut nearest_beyond) = (0.0f64, 0usize);
        for info in &self.bodies {
            // Lattice neighbours: |X_IJ| within 1 % of the body's spacing (R-P7).
            let nearest0 = 1.01 * info.spacing;
            let support = 2.0 * info.smoothing_length;
            for i in info.range.clone().filter(|&i| alive(i)) {
                let xi = p.positions0[i] + p.displacements[i];
                for &j in self.bonds.neighbours_of(i) {
                    let j = j as usize;
                    if j >= n || !alive(j) {
                        continue;
                    }
                    let big_x = p.positions0[i] - p.positions0[j];
                    let small_x = xi - (p.positions0[j] + p.displacements[j]);
                    let length0 = big_x.norm();
                    let length = small_x.norm();
                    let stretch = length / length0;
                    min = min.min(stretch);
                    max = max.max(stretch);
                    let error = (p.deformation_gradient[i] * big_x - small_x).norm() / length0;
                    sum_sq += error * error;
                    count += 1;
                    if length0 <= nearest0 {
                        nearest_max = nearest_max.max(length / support);
                        if length > support {
                            nearest_beyond += 1;
                        }
                    }
                }
            }
        }
        BondMetrics {
            min_stretch: min,
            max_stretch: max,
            hourglass_rms: if count > 0 {
                (sum_sq / count as f64).sqrt()
            } else {
                0.0
            },
            max_nearest_bond_over_support: nearest_max,
            nearest_bonds_beyond_support: nearest_beyond,
        }
    }

    /// Nearest-neighbour distances of the surviving real particles in the current
    /// configuration, relative to each body's initial spacing and to the spacing the local
    /// deformation predicts (see [`crate::stability`]).
    /// One cell-list search: a diagnostic for output intervals, not part of a step.
    pub fn neighbour_distances(&self) -> NeighbourDistances {
        self.neighbour_distances_among(0..self.n_particles())
    }

    /// As [`Simulation::neighbour_distances`] for the particles of body `body` alone, with the
    /// nearest neighbour searched among that body's particles (intra-body clumping, e.g. one of
    /// two colliding rings, F §3.5). An index beyond the bodies gives NaN statistics.
    pub fn body_neighbour_distances(&self, body: usize) -> NeighbourDistances {
        match self.bodies.get(body) {
            Some(b) => self.neighbour_distances_among(b.range.clone()),
            None => NeighbourDistances::undefined(),
        }
    }

    fn neighbour_distances_among(&self, members: std::ops::Range<usize>) -> NeighbourDistances {
        let n = self.n_particles();
        let p = &self.particles;
        let alive: Vec<usize> = members
            .filter(|&i| self.removed.is_empty() || !self.removed[i])
            .collect();
        let positions: Vec<Vector<D>> = alive
            .iter()
            .map(|&i| p.positions0[i] + p.displacements[i])
            .collect();
        let mut spacing = vec![0.0; n];
        for b in &self.bodies {
            spacing[b.range.clone()].fill(b.spacing);
        }
        let cap = 2.0;
        let largest = self.bodies.iter().map(|b| b.spacing).fold(0.0, f64::max);
        let Ok(list) = build_neighbour_list(&positions, cap * largest) else {
            // Only non-finite positions make the search fail.
            return NeighbourDistances::undefined();
        };
        let stretch: Vec<f64> = alive
            .par_iter()
            .map(|&i| smallest_stretch(&p.deformation_gradient[i]))
            .collect();
        let spacing_ratios: Vec<f64> = alive
            .par_iter()
            .enumerate()
            .map(|(k, &i)| {
                let nearest = list
                    .neighbours_of(k)
                    .iter()
                    .map(|&m| (positions[m as usize] - positions[k]).norm())
                    .fold(f64::INFINITY, f64::min);
                (nearest / spacing[i]).min(cap)
            })
            .collect();
        let ratios: Vec<f64> = spacing_ratios
            .iter()
            .zip(&stretch)
            .map(|(r, l)| r / l)
            .collect();
        let count = ratios.len().max(1) as f64;
        let mean = ratios.iter().sum::<f64>() / count;
        let variance = ratios.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / count;
        let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        NeighbourDistances {
            min_ratio: min(&ratios),
            max_ratio: max(&ratios),
            clumping_index: if mean > 0.0 {
                variance.sqrt() / mean
            } else {
                f64::NAN
            },
            min_spacing_ratio: min(&spacing_ratios),
            max_spacing_ratio: max(&spacing_ratios),
        }
    }

    /// Candidate-list rebuilds of the particle contact so far (`None` without `[contact]`).
    pub fn contact_rebuilds(&self) -> Option<u64> {
        self.effects
            .iter()
            .find_map(|b| b.effect.contact_rebuilds())
    }

    /// Verlet-list rebuilds so far (updated-Lagrangian formulation only).
    pub fn neighbour_rebuilds(&self) -> Option<u64> {
        self.updated.as_ref().map(|u| u.rebuilds())
    }

    /// Reference-configuration updates so far (0 unless `[reference_update]` is declared).
    pub fn reference_updates(&self) -> u64 {
        self.reference.as_ref().map_or(0, |r| r.updates)
    }

    /// Initial position of real particle `i` (equal to the reference position unless the
    /// reference configuration was updated).
    pub fn initial_position(&self, i: usize) -> Vector<D> {
        match &self.reference {
            Some(r) => r.initial_positions[i],
            None => self.particles.positions0[i],
        }
    }

    /// Displacement of real particle `i` from its initial position, x^n − X_initial.
    pub fn total_displacement(&self, i: usize) -> Vector<D> {
        let p = &self.particles;
        p.positions0[i] + p.displacements[i] - self.initial_position(i)
    }

    /// Number of particles that have failed so far.
    pub fn failed_particles(&self) -> usize {
        self.failed_count
    }

    /// Whether particle `i` has failed (numerics.md §9.3): it carries no stress and has left
    /// every kernel sum.
    pub fn is_failed(&self, i: usize) -> bool {
        self.removed.get(i).copied().unwrap_or(false)
    }

    /// Whether any body has a failure or damage model (and so a damage field).
    pub fn has_failure(&self) -> bool {
        !self.removed.is_empty()
    }

    /// Whether any body's material has both a softening `damage` law and a failure criterion,
    /// whose damages [`ParticleField::Damage`] merges (the larger of the two).
    pub fn has_two_damages(&self) -> bool {
        self.bodies.iter().any(|b| {
            let material = &self.materials[b.material];
            material.softening_damage().is_some() && material.failure().is_some()
        })
    }

    /// Adds every declared effect's accelerations at t^n, kicks with them, and books their
    /// work −Σ m a·v^n Δt* and resultant force, both summed in fixed chunks so the result does
    /// not depend on the thread count. The work is booked once every effect has kicked, with
    /// v^n = v^{n+½} − ½Δt* a the midpoint of the whole kick: booked one effect at a time, the
    /// later effects' share of the kick would be missing from v^n, an error m a_k·a_j Δt*²/2 per
    /// step that adds up to first order in Δt wherever two effects act on the same particles
    /// (a contact face and its hourglass control). `forward` = ½Δt^{n+1}/Δt* is the share of
    /// this kick that lies after t^n: it is held back from the energy reported at t^n, which
    /// makes the booked work the trapezoidal rule that the kinetic and internal energies at
    /// t^n follow (booked whole, every column led the instant by ½Δt f·v, an O(Δt) error).
    fn apply_effects(&mut self, kick: f64, forward: f64) {
        for (booked, share) in self.effects.iter_mut().zip(&mut self.effect_shares) {
            share.fill(Vector::zeros());
            // Effects read their neighbours' motion, symmetry ghosts included: mirror the
            // parents' after the previous kick.
            self.ghosts.refresh_motion(&mut self.particles);
            let ctx = EffectContext {
                particles: &self.particles,
                bonds: &self.bonds,
                pairs: self.updated.as_ref().map(|u| &u.pairs),
                removed: &self.removed,
                kick,
                time: self.time,
            };
            booked.effect.accelerations(&ctx, share);
            // A prescribed component moves as imposed whatever acts on it: the effect's force
            // there is taken by the driver (and counted in its reaction) and is no part of the
            // resultant. Its work there is still the effect's: booked below, and by the
            // driver as done against it (a rigid indenter pressed into a block books the
            // work of pressing it).
            booked.held_work = self.drivers.absorb(share, &self.particles, kick);
            booked.effect.record_applied(&ctx, share);
            let p = &mut self.particles;
            let masses = &p.masses;
            p.accelerations
                .par_chunks_mut(CHUNK)
                .zip(p.velocities.par_chunks_mut(CHUNK))
                .zip(share.par_chunks(CHUNK))
                .enumerate()
                .map(|(c, ((a, v), s))| {
                    let mut force = Vector::<D>::zeros();
                    for k in 0..s.len() {
                        a[k] += s[k];
                        v[k] += s[k] * kick;
                        force += s[k] * masses[c * CHUNK + k];
                    }
                    (0.0, force)
                })
                .collect_into_vec(&mut self.chunk_sums);
            let force = self
                .chunk_sums
                .iter()
                .fold(Vector::<D>::zeros(), |f, (_, cf)| f + cf);
            booked.effect.set_resultant(force);
        }
        for (booked, share) in self.effects.iter_mut().zip(&self.effect_shares) {
            if let Some(stored) = booked.effect.stored_energy() {
                booked.energy = stored;
                booked.pending = 0.0;
                continue;
            }
            let p = &self.particles;
            let masses = &p.masses;
            p.accelerations
                .par_chunks(CHUNK)
                .zip(p.velocities.par_chunks(CHUNK))
                .zip(share.par_chunks(CHUNK))
                .enumerate()
                .map(|(c, ((a, v), s))| {
                    let mut work = 0.0;
                    for k in 0..s.len() {
                        let v_mid = v[k] - a[k] * (0.5 * kick);
                        work += masses[c * CHUNK + k] * s[k].dot(&v_mid) * kick;
                    }
                    (work, Vector::<D>::zeros())
                })
                .collect_into_vec(&mut self.chunk_sums);
            let work: f64 = self.chunk_sums.iter().map(|(w, _)| w).sum::<f64>() + booked.held_work;
            booked.energy -= work;
            // The kick spans t^n − ½Δt^n … t^n + ½Δt^{n+1}: the energy at t^n leaves out the
            // later part (trapezoidal rule, as the kinetic energy at t^n sees it).
            booked.pending = -work * forward;
        }
    }

    /// Imposes the prescribed velocities as they are at time `at`.
    fn impose_velocities(&mut self, at: f64) {
        self.drivers.impose(&mut self.particles.velocities, at);
    }

    fn check_finite(&self, step: u64) -> Result<(), StepError> {
        let p = &self.particles;
        let bad_velocity = first_index_where(&p.velocities, |v| !v.iter().all(|x| x.is_finite()));
        match bad_velocity {
            None => Ok(()),
            Some(first_bad) => Err(self.non_finite(step, first_bad)),
        }
    }

    /// The error for a non-finite state first seen at particle `seen`: names the first
    /// particle with a non-finite stress, else displacement, else velocity, since a bad stress
    /// poisons its neighbours' accelerations and a bad velocity its neighbours' F.
    fn non_finite(&self, step: u64, seen: usize) -> StepError {
        let p = &self.particles;
        let finite3 = |s: &tlsph_math::Tensor3| s.iter().all(|x| x.is_finite());
        let finite = |v: &Vector<D>| v.iter().all(|x| x.is_finite());
        let (i, field) = if let Some(i) = p.stress.iter().position(|s| !finite3(s)) {
            (i, "stress")
        } else if let Some(i) = p.displacements.iter().position(|u| !finite(u)) {
            (i, "displacement")
        } else if let Some(i) = p.velocities.iter().position(|v| !finite(v)) {
            (i, "velocity")
        } else {
            (seen, "deformation gradient")
        };
        let (body, particle) = self.locate(i);
        StepError::NonFinite {
            step,
            time: self.time,
            body,
            particle,
            field,
        }
    }

    /// (body name, local index) of a global particle index.
    fn locate(&self, i: usize) -> (String, usize) {
        // A symmetry ghost stands for its parent.
        let i = match i.checked_sub(self.ghosts.first) {
            Some(g) if g < self.ghosts.parent.len() => self.ghosts.parent[g],
            _ => i,
        };
        let info = self
            .bodies
            .iter()
            .find(|b| b.range.contains(&i))
            .expect("every particle belongs to a body");
        (info.name.clone(), i - info.range.start)
    }

    /// Sets a uniform initial Cauchy stress σ0 (symmetric, tension positive; for an
    /// elastic–plastic material on or inside its initial yield surface, to
    /// [`crate::INITIAL_YIELD_TOLERANCE`]) on every particle
    /// of body `body` before the first step, e.g. a prestressed state (problems.md R-P5). The
    /// rate-form stress updates carry it on; the Green–Lagrange path computes stress from F
    /// alone, an equation of state computes pressure from J alone and a damage model keeps its
    /// own effective stress, so those refuse it.
    pub fn set_initial_stress(
        &mut self,
        body: usize,
        stress: tlsph_math::Tensor3,
    ) -> Result<(), SetupError> {
        self.set_initial_stress_field(body, |_| stress)
    }

    /// Sets an initial Cauchy stress σ0(X) that varies over body `body`: particle by particle,
    /// `field` of its reference position X, e.g. the linear field in equilibrium with a body
    /// force (σ_yy = ρ g (y − H) for a column of height H under gravity g). The same conditions
    /// as [`Simulation::set_initial_stress`] hold at every particle; an error names the first
    /// particle that breaks them.
    pub fn set_initial_stress_field(
        &mut self,
        body: usize,
        field: impl Fn(&Vector<D>) -> tlsph_math::Tensor3,
    ) -> Result<(), SetupError> {
        let range = match self.bodies.get(body) {
            Some(info) => info.range.clone(),
            None => 0..0,
        };
        let stresses: Vec<tlsph_math::Tensor3> =
            self.particles.positions0[range].iter().map(field).collect();
        self.set_initial_stresses(body, &stresses)
    }

    /// Sets an initial Cauchy stress particle by particle on body `body` (`stresses[k]` for its
    /// particle k, one per particle), e.g. a residual stress field mapped from a file. The
    /// same conditions as [`Simulation::set_initial_stress`] hold at every particle; an error
    /// names the first particle that breaks them.
    pub fn set_initial_stresses(
        &mut self,
        body: usize,
        stresses: &[tlsph_math::Tensor3],
    ) -> Result<(), SetupError> {
        let refuse = |message: String| {
            Err(SetupError::InvalidConfig {
                field: "initial_stress",
                message,
            })
        };
        let range = self.initial_field_range(body, "initial_stress", stresses.len(), "stresses")?;
        let info = &self.bodies[body];
        let material = &self.materials[info.material];
        let stress_from_state = self.config.stress_update == StressUpdate::GreenLagrange
            || matches!(material, MaterialModel::ElasticPlastic(m) if matches!(m.pressure, crate::model::PressureModel::Eos(_)))
            || material.softening_damage().is_some();
        if stress_from_state {
            return refuse(format!(
                "body `{}`: its stress is a function of the current state (Green–Lagrange path, an equation of state, or a damage model's effective stress), so an initial stress would be lost",
                info.name
            ));
        }
        for (k, stress) in stresses.iter().enumerate() {
            let at = || self.particle_label(body, k);
            if !(stress.iter().all(|x| x.is_finite())
                && (stress - stress.transpose()).norm() == 0.0)
            {
                return refuse(format!("{}: stress must be finite and symmetric", at()));
            }
            let plastic_strain = self.plastic[body].plastic_strain(k).unwrap_or(0.0);
            if let Some((equivalent, yield_stress)) =
                material.outside_yield_surface(stress, plastic_strain)
            {
                return refuse(format!(
                    "{}: the stress lies outside the yield surface (von Mises {equivalent:e} Pa > yield stress {yield_stress:e} Pa at plastic strain {plastic_strain}); the first step would return it to the surface",
                    at()
                ));
            }
        }
        for (i, &stress) in range.zip(stresses) {
            self.particles.stress[i] = stress;
            // P = J σ F⁻ᵀ = σ at the reference state (F = I).
            self.particles.pk1[i] = tlsph_math::project(&stress);
        }
        self.ghosts.refresh_stress(&mut self.particles);
        Ok(())
    }

    /// Sets the effective plastic strain ε̄p of body `body`'s particles before the first step
    /// (`strains[k]` for its particle k, one per particle), e.g. a work-hardened part: the
    /// yield stress starts at σ_y(ε̄p) and a failure or damage law that reads ε̄p starts from
    /// it. Refused for a material without plastic strain, for a value that is negative or not
    /// finite, and for one at which a `max-plastic-strain` failure law has already failed the
    /// particle; the error names the first particle. Set it before an initial stress, which
    /// is checked against the yield surface at this ε̄p.
    pub fn set_initial_plastic_strains(
        &mut self,
        body: usize,
        strains: &[f64],
    ) -> Result<(), SetupError> {
        let refuse = |message: String| {
            Err(SetupError::InvalidConfig {
                field: "initial_plastic_strain",
                message,
            })
        };
        self.initial_field_range(
            body,
            "initial_plastic_strain",
            strains.len(),
            "plastic strains",
        )?;
        let info = &self.bodies[body];
        let MaterialModel::ElasticPlastic(material) = &self.materials[info.material] else {
            return refuse(format!(
                "body `{}`: its material has no plastic strain (only elastic–plastic ones do)",
                info.name
            ));
        };
        for (k, &strain) in strains.iter().enumerate() {
            let at = self.particle_label(body, k);
            if !(strain.is_finite() && strain >= 0.0) {
                return refuse(format!(
                    "{at}: the plastic strain must be a finite number ≥ 0, got {strain}"
                ));
            }
            if let Some(FailureModel::MaxPlasticStrain(limit)) = material.failure {
                if limit.fails(strain) {
                    return refuse(format!(
                        "{at}: the plastic strain {strain} has already reached the failure strain of its material"
                    ));
                }
            }
        }
        for (k, &strain) in strains.iter().enumerate() {
            self.plastic[body].set_plastic_strain(k, strain);
        }
        Ok(())
    }

    /// Sets the softening damage D of body `body`'s particles before the first step
    /// (`damages[k]` for its particle k, one per particle), e.g. a part damaged by an earlier
    /// load (numerics.md §9.1–9.2): a particle carries σ_eff with its tensile part scaled by
    /// (1 − D) from the start; a Peerlings law resumes from the history κ at which it reaches
    /// D (it reloads on the secant (1 − D)E up to ε = κ), a Grady–Kipp law grows D further
    /// only once its active flaws allow more. Refused for a material without a `damage` law,
    /// and for a value that is not finite, negative, or 1 or more (a failed particle: leave it
    /// out of the body instead); the error names the first particle.
    pub fn set_initial_damage(&mut self, body: usize, damages: &[f64]) -> Result<(), SetupError> {
        let field = "initial_damage";
        let refuse = |message: String| Err(SetupError::InvalidConfig { field, message });
        self.initial_field_range(body, field, damages.len(), "damage values")?;
        let info = &self.bodies[body];
        let material = &self.materials[info.material];
        let Some(model) = material.softening_damage().copied() else {
            let hint = if material.has_johnson_cook_failure() {
                "; its Johnson–Cook failure damage is set by `initial_failure_damage`"
            } else {
                ""
            };
            return refuse(format!(
                "body `{}`: its material has no damage law (declare `damage` on it){hint}",
                info.name
            ));
        };
        self.check_damage_range(body, field, damages)?;
        for (k, &damage) in damages.iter().enumerate() {
            self.damage[body].set_initial_damage(&model, k, damage);
        }
        Ok(())
    }

    /// Sets the Johnson–Cook cumulative damage D = Σ Δε̄p/ε_f of body `body`'s particles
    /// before the first step (`damages[k]` for its particle k, one per particle), e.g. the
    /// ductile damage left by a forming step or an earlier impact (numerics.md §8.6): a
    /// particle fails once its plastic increments add the remaining 1 − D. The damage does not
    /// soften the stress (Johnson–Cook damage never does). Refused for a material without a
    /// `johnson-cook` failure law, and for a value that is not finite, negative, or 1 or more
    /// (a failed particle: leave it out of the body instead); the error names the first
    /// particle.
    pub fn set_initial_failure_damage(
        &mut self,
        body: usize,
        damages: &[f64],
    ) -> Result<(), SetupError> {
        let field = "initial_failure_damage";
        self.initial_field_range(body, field, damages.len(), "damage values")?;
        let info = &self.bodies[body];
        if !self.materials[info.material].has_johnson_cook_failure() {
            return Err(SetupError::InvalidConfig {
                field,
                message: format!(
                    "body `{}`: its material has no Johnson–Cook failure law (declare `failure` \
                     with model `johnson-cook` on it)",
                    info.name
                ),
            });
        }
        self.check_damage_range(body, field, damages)?;
        for (k, &damage) in damages.iter().enumerate() {
            self.plastic[body].set_failure_damage(k, damage);
        }
        Ok(())
    }

    /// Refuses (as `field`) the first of body `body`'s initial damage values that is not a
    /// finite number in [0, 1), naming its particle.
    fn check_damage_range(
        &self,
        body: usize,
        field: &'static str,
        damages: &[f64],
    ) -> Result<(), SetupError> {
        match damages.iter().position(|d| !(0.0..1.0).contains(d)) {
            None => Ok(()),
            Some(k) => Err(SetupError::InvalidConfig {
                field,
                message: format!(
                    "{}: the damage must be a finite number with 0 ≤ D < 1, got {}",
                    self.particle_label(body, k),
                    damages[k]
                ),
            }),
        }
    }

    /// The particle range of body `body` for a setter of an initial field given per particle
    /// (`field` in errors): the body must exist, no step may have been taken yet, and `given`
    /// values (`what`, e.g. "stresses") must match its particles one to one.
    fn initial_field_range(
        &self,
        body: usize,
        field: &'static str,
        given: usize,
        what: &str,
    ) -> Result<Range<usize>, SetupError> {
        let refuse = |message: String| Err(SetupError::InvalidConfig { field, message });
        let Some(info) = self.bodies.get(body) else {
            return refuse(format!("body #{body} does not exist"));
        };
        if self.steps_done > 0 {
            return refuse("must be set before the first step".into());
        }
        if given != info.range.len() {
            return refuse(format!(
                "body `{}` has {} particles but {given} {what} were given",
                info.name,
                info.range.len(),
            ));
        }
        Ok(info.range.clone())
    }

    /// "body `name`, particle k at [X]" for body `body`'s particle `k` (local index), in errors.
    fn particle_label(&self, body: usize, k: usize) -> String {
        let info = &self.bodies[body];
        let x = self.particles.positions0[info.range.start + k];
        let text: Vec<String> = x.iter().map(|c| format!("{c:e}")).collect();
        format!(
            "body `{}`, particle {k} at [{}]",
            info.name,
            text.join(", ")
        )
    }

    /// Overwrites the displacements u (one per particle). Before the first step this sets an
    /// initial displacement field; later it drives the kinematics directly (tests, coupling).
    /// The next step evaluates F from these displacements after its drift.
    pub fn set_displacements(&mut self, displacements: &[Vector<D>]) {
        assert_eq!(
            displacements.len(),
            self.n_particles(),
            "one displacement per particle"
        );
        self.particles.displacements.copy_from_slice(displacements);
    }

    /// Overwrites the staggered velocities v^{n+½} that the next drift uses, and clears the
    /// stored accelerations so [`Simulation::velocity`] reports exactly these values.
    pub fn set_velocities(&mut self, velocities: &[Vector<D>]) {
        assert_eq!(
            velocities.len(),
            self.n_particles(),
            "one velocity per particle"
        );
        self.particles.velocities.copy_from_slice(velocities);
        self.particles.accelerations.fill(Vector::zeros());
        self.impose_velocities(self.time + 0.5 * self.next_dt);
    }

    /// Step size the next call to [`Simulation::step`] will take (0 before the first step).
    pub fn next_dt(&self) -> f64 {
        self.next_dt
    }

    /// Material velocity gradients Ḟ^{n−½} of the last step.
    pub fn deformation_rates(&self) -> &[tlsph_math::Tensor<D>] {
        &self.particles.deformation_rate[..self.n_particles()]
    }

    /// Current simulated time \[s\].
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps completed.
    pub fn steps_done(&self) -> u64 {
        self.steps_done
    }

    /// Total number of particles.
    pub fn n_particles(&self) -> usize {
        self.ghosts.first_or(self.particles.len())
    }

    /// Configuration of the run.
    pub fn config(&self) -> &SimulationConfig {
        &self.config
    }

    /// Bodies in order.
    pub fn bodies(&self) -> &[BodyInfo] {
        &self.bodies
    }

    /// Reference bonds.
    pub fn bonds(&self) -> &Bonds<D> {
        &self.bonds
    }

    /// What the gradient correction regularised at setup.
    pub fn correction_report(&self) -> &CorrectionReport {
        &self.correction
    }

    /// Reference positions X: the initial positions, or the positions at the last reference
    /// update (see [`Simulation::initial_position`]). x^n = X + u^n either way.
    pub fn positions0(&self) -> &[Vector<D>] {
        &self.particles.positions0[..self.n_particles()]
    }

    /// Displacements u^n = x^n − X from the reference positions (from the initial positions
    /// unless the reference was updated; see [`Simulation::total_displacement`]).
    pub fn displacements(&self) -> &[Vector<D>] {
        &self.particles.displacements[..self.n_particles()]
    }

    /// Masses.
    pub fn masses(&self) -> &[f64] {
        &self.particles.masses[..self.n_particles()]
    }

    /// Cauchy stresses σ^n.
    pub fn stresses(&self) -> &[tlsph_math::Tensor3] {
        &self.particles.stress[..self.n_particles()]
    }

    /// Deformation gradients F^n relative to the reference configuration (the initial one
    /// unless the reference was updated).
    pub fn deformation_gradients(&self) -> &[tlsph_math::Tensor<D>] {
        &self.particles.deformation_gradient[..self.n_particles()]
    }

    /// Specific internal energies e^n \[J/kg\].
    pub fn internal_energies(&self) -> &[f64] {
        &self.particles.internal_energy[..self.n_particles()]
    }

    /// Velocity of particle `i` at the current time t^n: v^n = v^{n+½} − ½Δt^{n+1} a^n,
    /// consistent with the kick of R 5.64 (and exact at t = 0).
    #[inline]
    pub fn velocity(&self, i: usize) -> Vector<D> {
        self.particles.velocities[i] - self.particles.accelerations[i] * (0.5 * self.next_dt)
    }

    /// Samples a field at particle `i` (global index) at the current time.
    pub fn sample(&self, field: ParticleField, i: usize) -> f64 {
        let p = &self.particles;
        let component = |v: Vector<D>, k: usize| if k < D { v[k] } else { 0.0 };
        // The particle's body b and its index k in that body, for the per-body state.
        let in_body = || {
            let b = self.body_of(i);
            (b, i - self.bodies[b].range.start)
        };
        match field {
            ParticleField::Stress(a, b) => p.stress[i][(a, b)],
            ParticleField::Pressure => -p.stress[i].trace() / 3.0,
            ParticleField::VonMises => von_mises(&p.stress[i]),
            ParticleField::Velocity(k) => component(self.velocity(i), k),
            ParticleField::Displacement(k) => component(self.total_displacement(i), k),
            ParticleField::Position(k) => component(p.positions0[i] + p.displacements[i], k),
            // A failed particle is a free point mass: it has no neighbours to measure a volume
            // by (its F is left at I), so its J and density are not defined.
            ParticleField::Density | ParticleField::Jacobian if self.is_failed(i) => f64::NAN,
            ParticleField::Density => {
                let info = &self.bodies[self.body_of(i)];
                info.density0 / p.jacobian[i]
            }
            ParticleField::Jacobian => p.jacobian[i],
            ParticleField::InternalEnergy => p.internal_energy[i],
            ParticleField::PlasticStrain => {
                let (b, k) = in_body();
                // Elastic bodies have no plastic strain: 0 is the true value.
                self.plastic[b].plastic_strain(k).unwrap_or(0.0)
            }
            ParticleField::Damage => {
                let (b, k) = in_body();
                // With a softening law and a failure criterion on one material, the larger of
                // the two damages (both read 1 once the particle has failed).
                match (self.plastic[b].damage(k), self.damage[b].damage(k)) {
                    (Some(criterion), Some(softening)) => criterion.max(softening),
                    (criterion, softening) => criterion.or(softening).unwrap_or(0.0),
                }
            }
            ParticleField::SofteningDamage => {
                let (b, k) = in_body();
                self.damage[b].damage(k).unwrap_or(0.0)
            }
            ParticleField::FailureDamage => {
                let (b, k) = in_body();
                self.plastic[b].damage(k).unwrap_or(0.0)
            }
            ParticleField::Temperature => {
                let (b, k) = in_body();
                self.plastic[b].temperature(k).unwrap_or(f64::NAN)
            }
        }
    }

    /// Whether any body tracks a temperature (adiabatic heating declared).
    pub fn has_temperature(&self) -> bool {
        self.bodies
            .iter()
            .any(|b| self.materials[b.material].has_temperature())
    }

    /// Whether any body carries an effective plastic strain.
    pub fn has_plastic_strain(&self) -> bool {
        self.plastic
            .iter()
            .any(|s| !matches!(s, PlasticState::None))
    }

    /// Index of the body that owns global particle `i`.
    pub fn body_of(&self, i: usize) -> usize {
        body_index(&self.bodies, i)
    }

    /// Energies and momenta at the current time (sequential sums: thread-count independent).
    pub fn diagnostics(&self) -> Diagnostics {
        let p = &self.particles;
        let mut d = Diagnostics {
            time: self.time,
            ..Diagnostics::default()
        };
        let mut deleted = 0.0;
        for i in 0..self.n_particles() {
            let m = p.masses[i];
            let v = vector_to_3d(&self.velocity(i));
            let x: Vector3 = vector_to_3d(&(p.positions0[i] + p.displacements[i]));
            d.kinetic += 0.5 * m * v.norm_squared();
            if self.removed.is_empty() || !self.removed[i] {
                d.internal += m * p.internal_energy[i];
            } else {
                deleted += m * p.internal_energy[i];
            }
            d.linear_momentum += v * m;
            d.angular_momentum += x.cross(&v) * m;
        }
        d.failed_particles = self.failed_count;
        for booked in &self.effects {
            let name = booked.effect.name().to_string();
            if let Some(f) = booked.effect.resultant() {
                d.effect_forces.push((name.clone(), vector_to_3d(&f)));
            }
            if let Some(torque) = booked.effect.torque() {
                d.effect_torques.push((name.clone(), torque));
            }
            if let Some(moment) = booked.effect.moment() {
                d.effect_moments.push((name.clone(), moment));
            }
            d.effect_energies
                .push((name, booked.energy - booked.pending));
        }
        // Each `[[boundary]]` set: its energy column is minus the work it has done on the
        // particles (what it took out), so the total closes for driven scenes too.
        for (name, force, work) in self.drivers.reports() {
            d.effect_energies.push((format!("boundary_{name}"), -work));
            d.boundary_forces
                .push((format!("boundary_{name}"), vector_to_3d(&force)));
        }
        if !self.removed.is_empty() {
            // The internal energy failed particles carried when they left the sums (strain
            // energy released and plastic work): its own column, so `internal` is the energy
            // of the intact material and the total still closes.
            d.effect_energies
                .push(("deleted_particles".to_string(), deleted));
        }
        d
    }
}

/// XSPH (numerics.md §10.4, TL variant): v̂_I = v_I + ε Σ_J V0_J (v_J − v_I) W̃_IJ with the
/// Shepard-normalised reference kernel W̃_IJ = W0_IJ / S_I. Particles drift with v̂ and Ḟ is
/// built from v̂, so u stays the time integral of the velocity that F sees.
#[derive(Debug, Clone)]
struct Xsph<const D: usize> {
    epsilon: f64,
    /// Per bond: V0_J W0_IJ / S_I.
    weights: Vec<f64>,
    /// v̂ per particle (ghosts mirrored).
    velocity: Vec<Vector<D>>,
}

impl<const D: usize> Xsph<D> {
    fn new(
        epsilon: f64,
        bonds: &Bonds<D>,
        particles: &Particles<D>,
        kernels: &[tlsph_kernels::AnyKernel],
        bodies: &[BodyInfo],
        n_real: usize,
    ) -> Self {
        let x = &particles.positions0;
        let v0 = &particles.volumes0;
        let mut weights = vec![0.0; bonds.n_bonds()];
        for (b, info) in bodies.iter().enumerate() {
            let kernel = kernels[b];
            for i in info.range.clone() {
                let r = bonds.range(i);
                let shepard = v0[i] * kernel.value(0.0)
                    + bonds.neighbours[r.clone()]
                        .iter()
                        .map(|&j| v0[j as usize] * kernel.value((x[i] - x[j as usize]).norm()))
                        .sum::<f64>();
                for k in r {
                    let j = bonds.neighbours[k] as usize;
                    weights[k] = v0[j] * kernel.value((x[i] - x[j]).norm()) / shepard;
                }
            }
        }
        let _ = n_real;
        Self {
            epsilon,
            weights,
            velocity: particles.velocities.clone(),
        }
    }

    /// v̂ of the real particles from the current velocities (gather per particle).
    fn update(&mut self, bonds: &Bonds<D>, velocities: &[Vector<D>], n_real: usize) {
        let (epsilon, weights) = (self.epsilon, &self.weights);
        self.velocity[..n_real]
            .par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each(|(i, vhat)| {
                let vi = velocities[i];
                let mut sum = Vector::<D>::zeros();
                let r = bonds.range(i);
                for (&j, w) in bonds.neighbours[r.clone()].iter().zip(&weights[r]) {
                    sum += (velocities[j as usize] - vi) * *w;
                }
                *vhat = vi + sum * epsilon;
            });
    }
}

/// The constitutive inputs of body `info` for a step of `dt`, with the reference's J0;
/// `book_energy`: whether the loop books the internal energy (see [`ConstitutiveStep`]).
fn constitutive_step<'a, R: ReferenceJacobian + ?Sized>(
    info: &BodyInfo,
    dt: f64,
    reference_jacobian: &'a R,
    jacobian_carry: &'a [f64],
    book_energy: bool,
) -> ConstitutiveStep<'a, R> {
    ConstitutiveStep {
        range: info.range.clone(),
        density0: info.density0,
        dt,
        smoothing_length: info.smoothing_length,
        sound_speed0: info.sound_speed0,
        reference_jacobian,
        jacobian_carry: (!jacobian_carry.is_empty()).then(|| &jacobian_carry[info.range.clone()]),
        book_energy,
    }
}

/// One body's constitutive update: the material `match` happens here, once per body and
/// step, outside the particle loops.
struct BodyUpdate<'a> {
    material: &'a MaterialModel,
    stress_update: StressUpdate,
    viscosity: Option<crate::model::BulkViscosity>,
    spacing: f64,
    plastic: &'a mut PlasticState,
    damage: &'a mut DamageState,
}

impl BodyUpdate<'_> {
    fn update<const D: usize, R: ReferenceJacobian + ?Sized>(
        self,
        step: &ConstitutiveStep<R>,
        particles: &mut Particles<D>,
    ) {
        match (self.material, self.stress_update) {
            (MaterialModel::LinearElastic(m), StressUpdate::JaumannRate) => match self.viscosity {
                None => update_jaumann_rate(m, step, &NoViscosity, particles),
                Some(v) => update_jaumann_rate(m, step, &v, particles),
            },
            // The reference update is rejected at setup for the Green–Lagrange path, which
            // needs F relative to the initial configuration.
            (MaterialModel::LinearElastic(m), StressUpdate::GreenLagrange) => {
                update_green_lagrange(m, step, particles)
            }
            // Rejected at setup for the Green–Lagrange path.
            (MaterialModel::ElasticPlastic(m), _) => update_elastic_plastic(
                m,
                step,
                self.viscosity,
                particles,
                PlasticBody {
                    plastic: self.plastic,
                    damage: self.damage,
                    spacing: self.spacing,
                },
            ),
            // Rejected at setup for the Green–Lagrange path.
            (MaterialModel::ElasticDamage(m), _) => update_damaged_elastic(
                m,
                step,
                self.viscosity,
                self.spacing,
                particles,
                self.damage,
            ),
        }
    }
}

/// Updated-Lagrangian symmetry ghosts at a Verlet-list rebuild (numerics.md §13.1 at the
/// current positions): the ghosts are rebuilt for the surviving particles within the list's
/// search radius of the planes, the failure flags follow the new particle count (ghosts start
/// alive: only survivors are mirrored), and the formulation and the effects learn each ghost's
/// body.
fn rebuild_current_ghosts<const D: usize>(
    updated: &mut UpdatedLagrangian<D>,
    ghosts: &mut Ghosts<D>,
    particles: &mut Particles<D>,
    removed: &mut Vec<bool>,
    effects: &mut [BookedEffect<D>],
    planes: &[crate::model::SymmetryPlane],
) {
    let n_real = ghosts.first_or(particles.len());
    let flags: &[bool] = removed;
    let alive = |i: usize| flags.is_empty() || !flags[i];
    ghosts.rebuild_current(particles, n_real, planes, updated.search_radius(), alive);
    if !removed.is_empty() {
        removed.truncate(n_real);
        removed.resize(particles.len(), false);
    }
    updated.set_ghost_parents(n_real, &ghosts.parent);
    for booked in effects {
        booked.effect.ghosts_rebuilt(updated.particle_bodies());
    }
}

/// Symmetry ghosts (appended to `particles` after the reals, which are all it may hold) and
/// reference bonds with their gradients, built on the reference positions `positions0`
/// (numerics.md §4.2, §6, §13.1): at setup, and again at every reference update.
///
/// At setup every body lies strictly on one side of each plane (`check_planes` ran). At a
/// reference update a particle that has drifted across a plane (a discretisation artefact
/// next to the plane, which the full model shows as two mirror particles passing each other)
/// is mirrored like any other: the plane is a symmetry of the solution, not a wall.
fn build_reference<const D: usize>(
    bodies: &[BodyInfo],
    kernels: &[tlsph_kernels::AnyKernel],
    particles: &mut Particles<D>,
    planes: &[crate::model::SymmetryPlane],
    kernel_scale: &[f64],
    corrected: bool,
) -> Result<(Ghosts<D>, Bonds<D>, CorrectionReport), SetupError> {
    let n_real = particles.len();
    let mut ghosts = Ghosts::default();
    let mut body_bonds = Vec::with_capacity(bodies.len());
    for (info, &kernel) in bodies.iter().zip(kernels) {
        // The body's kernel factors s_I (empty: all 1, unless a reference update widened them).
        let scale = kernel_scale
            .get(info.range.clone())
            .filter(|s| s.iter().any(|&s| s != 1.0))
            .unwrap_or(&[]);
        let mut local = mirror_body(info, particles, planes, kernel, scale);
        // Append this body's ghosts as particles (never integrated; refreshed each step).
        for (k, &(parent, mask)) in local.ghosts.iter().enumerate() {
            let global_parent = info.range.start + parent;
            let signs = local.signs[mask as usize];
            let position0 = local.positions0[local.n_real + k];
            let velocity = particles.velocities[global_parent].component_mul(&signs);
            let volume0 = particles.volumes0[global_parent];
            particles.push(position0, volume0, info.density0, velocity);
            // The parent's mass (ρ0 V0 at setup; the reference volume is V0 J0 after an update).
            let ghost = particles.len() - 1;
            particles.masses[ghost] = particles.masses[global_parent];
            local.global.push(ghost);
            ghosts.parent.push(global_parent);
            ghosts.signs.push(signs);
            ghosts.mask.push(mask);
            ghosts.of.insert((global_parent, mask), ghost);
        }
        let neighbours = if scale.is_empty() {
            build_neighbour_list(&local.positions0, kernel.support_radius())
        } else {
            // Per-particle supports 2h s_I (a ghost has its parent's factor); a pair is kept
            // within its own support 2h (s_I + s_J)/2.
            local.kernel_scale = local
                .global
                .iter()
                .map(|&g| kernel_scale[g.checked_sub(n_real).map_or(g, |k| ghosts.parent[k])])
                .collect();
            let radii: Vec<f64> = local
                .kernel_scale
                .iter()
                .map(|s| s * kernel.support_radius())
                .collect();
            tlsph_neighbours::build_neighbour_list_with_radii(&local.positions0, &radii)
        };
        local.neighbours = neighbours.map_err(|e| SetupError::Neighbours {
            body: info.name.clone(),
            message: e.to_string(),
        })?;
        body_bonds.push(local);
    }
    ghosts.first = n_real;
    let (bonds, correction) = build_bonds(&body_bonds, corrected, particles.len());
    Ok((ghosts, bonds, correction))
}

/// The body's reals and their mirror images across every non-empty combination of symmetry
/// planes within the kernel support (corner ghosts when several planes meet). With kernel
/// factors `scale` (body-local, empty: all 1), the image of particle I can meet a particle J
/// within 2h (s_I + s_J)/2, so I is mirrored within 2h (s_I + s_max)/2 of a plane.
fn mirror_body<const D: usize>(
    info: &BodyInfo,
    particles: &Particles<D>,
    planes: &[crate::model::SymmetryPlane],
    kernel: tlsph_kernels::AnyKernel,
    scale: &[f64],
) -> BodyBonds<D> {
    let largest = scale.iter().copied().fold(1.0, f64::max);
    let support = |i: usize| match scale.get(i) {
        None => kernel.support_radius(),
        Some(s) => 0.5 * (s + largest) * kernel.support_radius(),
    };
    let reals = &particles.positions0[info.range.clone()];
    let n_real = reals.len();
    // How far particles have drifted across each plane (0 at setup): a particle within
    // support of the ghost of a drifted particle needs a ghost of its own, so the band of
    // mirrored particles widens by that depth.
    let depth: Vec<f64> = planes
        .iter()
        .map(|plane| {
            let offset = |x: &Vector<D>| x[plane.axis] - plane.position;
            let side = reals.iter().map(offset).sum::<f64>().signum();
            reals
                .iter()
                .map(|x| (-side * offset(x)).max(0.0))
                .fold(0.0, f64::max)
        })
        .collect();
    let mirror = reflections::<D>(planes);
    let mut positions0 = reals.to_vec();
    let mut volumes0 = particles.volumes0[info.range.clone()].to_vec();
    let mut ghosts = Vec::new();
    let mut ghost_of = std::collections::HashMap::new();
    for mask in mirror.masks() {
        for (i, x) in reals.iter().enumerate() {
            let near = planes.iter().enumerate().all(|(k, plane)| {
                mask & (1 << k) == 0
                    || (x[plane.axis] - plane.position).abs() < support(i) + depth[k]
            });
            if !near {
                continue;
            }
            let image = mirror.point(x, mask);
            ghost_of.insert((i, mask), positions0.len());
            ghosts.push((i, mask));
            positions0.push(image);
            volumes0.push(volumes0[i]);
        }
    }
    BodyBonds {
        global: info.range.clone().collect(),
        n_real,
        positions0,
        volumes0,
        ghosts,
        ghost_of,
        signs: mirror.sign_table().to_vec(),
        neighbours: Default::default(),
        kernel,
        kernel_scale: Vec::new(),
    }
}

/// Chunk length of deterministic parallel reductions and searches.
const CHUNK: usize = 4096;

/// Index of the body owning global particle `i` (bodies are contiguous index ranges; a few
/// bodies, so a linear search: for lookups outside per-particle loops).
fn body_index(bodies: &[BodyInfo], i: usize) -> usize {
    bodies
        .iter()
        .position(|b| b.range.contains(&i))
        .expect("every particle belongs to a body")
}

/// The body of each of the first `n` particles, filled range by range (O(n)).
fn body_indices(bodies: &[BodyInfo], n: usize) -> Vec<u32> {
    let mut of = vec![0u32; n];
    for (b, info) in bodies.iter().enumerate() {
        let r = info.range.start.min(n)..info.range.end.min(n);
        of[r].fill(b as u32);
    }
    of
}

/// Builds the declared effects (none declared: an empty list, nothing allocated).
fn build_effects<const D: usize>(
    model: &Model<D>,
    bodies: &[BodyInfo],
    kernels: &[tlsph_kernels::AnyKernel],
    particles: &Particles<D>,
    bonds: &Bonds<D>,
    drivers: &Drivers<D>,
    n_real: usize,
) -> Result<Vec<BookedEffect<D>>, SetupError> {
    let mut effects: Vec<BookedEffect<D>> = Vec::new();
    let n = n_real;
    let body_of = |i: usize| body_index(bodies, i);
    let per_particle = |f: &dyn Fn(&BodyInfo) -> f64| -> Vec<f64> {
        (0..n).map(|i| f(&bodies[body_of(i)])).collect()
    };
    if let Some(body_force) = &model.effects.body_force {
        effects.push(BookedEffect::new(Box::new(build_body_force(
            model,
            body_force,
            bodies,
            &particles.positions0[..n],
        )?)));
    }
    for wall in &model.effects.walls {
        // A ball, a cylinder, a cone or a pyramid has no normal; their axis is checked like
        // a normal.
        let direction = match wall.shape {
            WallShape::Plane | WallShape::Disc { .. } | WallShape::Box { .. } => {
                Some(("normal", wall.normal))
            }
            WallShape::Ball { .. } => None,
            WallShape::Cylinder { axis, .. }
            | WallShape::Cone { axis, .. }
            | WallShape::Pyramid { axis, .. } => Some(("axis", axis)),
        };
        let direction_ok =
            direction.is_none_or(|(_, n)| n.norm() > 0.0 && n.iter().all(|x| x.is_finite()));
        if !(direction_ok && wall.point.iter().all(|x| x.is_finite())) {
            let needs = match direction {
                Some((name, _)) => format!("a finite point and a finite, non-zero {name}"),
                None => "a finite point (its centre)".into(),
            };
            return Err(SetupError::InvalidConfig {
                field: "wall",
                message: format!("wall `{}` needs {needs}", wall.name),
            });
        }
        let h = per_particle(&|b| b.smoothing_length);
        let c0 = per_particle(&|b| b.sound_speed0);
        let dx = per_particle(&|b| b.spacing);
        let wall_error = |message: String| SetupError::InvalidConfig {
            field: "wall",
            message: format!("wall `{}`: {message}", wall.name),
        };
        let coefficients = wall.friction;
        coefficients.check().map_err(wall_error)?;
        if let Some(motion) = &wall.motion {
            if !motion.velocity.iter().all(|v| v.is_finite()) {
                return Err(wall_error("needs a finite velocity".into()));
            }
            if let Some(amplitude) = &motion.amplitude {
                amplitude.validate().map_err(wall_error)?;
            }
            if let Some(omega) = motion.spin {
                check_spin(&wall.shape, wall.normal, omega, coefficients).map_err(wall_error)?;
            }
            if let Some(ramp) = &motion.spin_ramp {
                if motion.spin.is_none() {
                    return Err(wall_error("has a spin ramp but no spin".into()));
                }
                crate::model::Amplitude::from(*ramp)
                    .validate()
                    .map_err(wall_error)?;
            }
        }
        let (point, normal, motion) = (wall.point, wall.normal, wall.motion.clone());
        let checked_radius = |radius: f64| {
            if D < 2 || !(radius.is_finite() && radius > 0.0) {
                Err(wall_error(format!(
                    "radius must be finite and > 0 in a 2D or 3D scene, got {radius} in {D}D"
                )))
            } else {
                Ok(radius)
            }
        };
        let (name, report_moment) = (&wall.name, wall.report_moment);
        // A moving wall advances at most C_cfl min h per step (RigidWall::with_travel_limit).
        let travel = bodies
            .iter()
            .filter(|b| !b.range.is_empty())
            .map(|b| (model.config.cfl * b.smoothing_length, b.range.start))
            .fold((f64::INFINITY, usize::MAX), min_by_value_then_index);
        let friction = (coefficients, point, report_moment);
        let particles = (&h[..], &c0[..], &dx[..]);
        match wall.shape {
            WallShape::Plane => {
                let plane = RigidPlane::new(point, normal, &h, &c0, &dx);
                let wall = RigidWall::new(name, plane, motion);
                push_wall(&mut effects, travel, wall, friction);
            }
            WallShape::Disc { radius } => {
                let radius = checked_radius(radius)?;
                let disc = FlatDisc::new(point, normal, radius, &h, &c0, &dx);
                let wall = RigidWall::new(name, disc, motion);
                push_wall(&mut effects, travel, wall, friction);
            }
            WallShape::Ball { radius } => {
                let radius = checked_radius(radius)?;
                let ball = RigidBall::new(point, radius, &h, &c0, &dx);
                let wall = RigidWall::new(name, ball, motion);
                push_wall(&mut effects, travel, wall, friction);
            }
            WallShape::Cylinder {
                radius,
                axis,
                length,
            } => {
                let radius = checked_radius(radius)?;
                if D != 3 {
                    return Err(wall_error(format!(
                        "a cylinder needs a 3D scene (in 2D a ball is the cylinder in plane strain), got {D}D"
                    )));
                }
                match length {
                    None => {
                        let cylinder = RigidCylinder::new(point, axis, radius, &h, &c0, &dx);
                        let wall = RigidWall::new(name, cylinder, motion);
                        push_wall(&mut effects, travel, wall, friction);
                    }
                    Some(length) => {
                        if !(length.is_finite() && length > 0.0) {
                            return Err(wall_error(format!(
                                "a cylinder's length must be finite and > 0, got {length}"
                            )));
                        }
                        let cylinder =
                            FiniteCylinder::new(point, axis, radius, length, &h, &c0, &dx);
                        let wall = RigidWall::new(name, cylinder, motion);
                        push_wall(&mut effects, travel, wall, friction);
                    }
                }
            }
            WallShape::Box { .. } => {
                let block: RigidBox<D> =
                    built_shape(wall.shape.rigid_box(point, normal, particles), "box")
                        .map_err(wall_error)?;
                let wall = RigidWall::new(name, block, motion);
                push_wall(&mut effects, travel, wall, friction);
            }
            WallShape::Cone { .. } => {
                let cone: RigidCone<D> =
                    built_shape(wall.shape.rigid_cone(point, particles), "cone")
                        .map_err(wall_error)?;
                let wall = RigidWall::new(name, cone, motion);
                push_wall(&mut effects, travel, wall, friction);
            }
            WallShape::Pyramid { .. } => {
                let pyramid: RigidPyramid<D> =
                    built_shape(wall.shape.rigid_pyramid(point, particles), "pyramid")
                        .map_err(wall_error)?;
                let wall = RigidWall::new(name, pyramid, motion);
                push_wall(&mut effects, travel, wall, friction);
            }
        }
    }
    if let Some((alpha, beta)) = model.effects.pairwise_viscosity {
        if !(alpha.is_finite() && beta.is_finite() && alpha >= 0.0 && beta >= 0.0) {
            return Err(SetupError::InvalidConfig {
                field: "artificial_viscosity",
                message: format!("alpha and beta must be finite and ≥ 0, got {alpha}, {beta}"),
            });
        }
        effects.push(BookedEffect::new(Box::new(MonaghanViscosity::new(
            alpha,
            beta,
            kernels.to_vec(),
            body_indices(bodies, n),
            bodies.iter().map(|b| b.density0).collect(),
            bodies.iter().map(|b| b.sound_speed0).collect(),
        ))));
    }
    if let Some(a) = &model.effects.artificial_stress {
        if !(a.epsilon.is_finite() && a.epsilon > 0.0 && a.exponent.is_finite() && a.exponent > 0.0)
        {
            return Err(SetupError::InvalidConfig {
                field: "artificial_stress",
                message: format!(
                    "epsilon and exponent must be finite and > 0, got {}, {}",
                    a.epsilon, a.exponent
                ),
            });
        }
        let carries = match &a.bodies {
            None => vec![true; bodies.len()],
            Some(list) => {
                let mut carries = vec![false; bodies.len()];
                for &b in list {
                    *carries
                        .get_mut(b)
                        .ok_or_else(|| SetupError::InvalidConfig {
                            field: "artificial_stress.bodies",
                            message: format!("body #{b} does not exist ({} bodies)", bodies.len()),
                        })? = true;
                }
                carries
            }
        };
        // A body feels the term iff it carries R itself or shares a kernel group with a body
        // that does; every other body is skipped by the effect's loops.
        let group = |b: usize| model.kernel_group(b);
        let feels: Vec<bool> = (0..bodies.len())
            .map(|b| (0..bodies.len()).any(|c| carries[c] && group(c) == group(b)))
            .collect();
        effects.push(BookedEffect::new(Box::new(MonaghanArtificialStress::new(
            a.epsilon,
            a.exponent,
            carries,
            feels,
            body_indices(bodies, n),
            bodies
                .iter()
                .zip(kernels)
                .map(|(b, k)| k.value(b.spacing))
                .collect(),
        ))));
    }
    if let Some(contact) = &model.effects.penalty_contact {
        if model.effects.contact.is_some() {
            return Err(SetupError::InvalidConfig {
                field: "penalty_contact",
                message: "one contact law per run: both the potential and the penalty contact are declared".into(),
            });
        }
        effects.push(BookedEffect::new(Box::new(build_penalty_contact(
            model, contact, bodies, kernels, drivers,
        )?)));
    }
    if let Some(contact) = &model.effects.contact {
        effects.push(BookedEffect::new(Box::new(build_contact(
            model,
            contact,
            bodies,
            &particles.positions0[..n],
        )?)));
    }
    if let Some(alpha) = model.effects.hourglass_control {
        if !(alpha.is_finite() && alpha > 0.0) {
            return Err(SetupError::InvalidConfig {
                field: "hourglass_control",
                message: format!("coefficient must be > 0, got {alpha}"),
            });
        }
        let youngs: Vec<f64> = bodies
            .iter()
            .map(|b| model.materials[b.material].model.youngs_modulus())
            .collect();
        let hourglass = HourglassControl::new(
            alpha,
            kernels.to_vec(),
            youngs,
            body_indices(bodies, n),
            particles,
            bonds,
        );
        effects.push(BookedEffect::new(Box::new(hourglass)));
    }
    Ok(effects)
}

/// The body force of numerics.md §4.5 on the declared bodies (or every body), checked: a
/// finite acceleration, existing bodies, and no component along a symmetry plane's normal
/// (the mirrored half would be pulled the other way, so the model would not be symmetric).
fn build_body_force<const D: usize>(
    model: &Model<D>,
    body_force: &crate::model::BodyForceDescription<D>,
    bodies: &[BodyInfo],
    positions0: &[Vector<D>],
) -> Result<BodyForce<D>, SetupError> {
    let b = body_force.acceleration;
    if !b.iter().all(|x| x.is_finite()) {
        return Err(SetupError::InvalidConfig {
            field: "body_force.acceleration",
            message: format!("must be finite, got {:?}", b.as_slice()),
        });
    }
    if let Some(plane) = model
        .effects
        .symmetry_planes
        .iter()
        .find(|plane| plane.axis < D && b[plane.axis] != 0.0)
    {
        return Err(SetupError::InvalidConfig {
            field: "body_force.acceleration",
            message: format!(
                "has a component {} along axis {}, the normal of the symmetry plane at {}: \
                 the mirrored half would be pulled the other way, so the model is not symmetric",
                b[plane.axis], plane.axis, plane.position
            ),
        });
    }
    let ranges = match &body_force.bodies {
        None => bodies.iter().map(|info| info.range.clone()).collect(),
        Some(list) => list
            .iter()
            .map(|&k| {
                bodies.get(k).map(|info| info.range.clone()).ok_or_else(|| {
                    SetupError::InvalidConfig {
                        field: "body_force.bodies",
                        message: format!("body #{k} does not exist ({} bodies)", bodies.len()),
                    }
                })
            })
            .collect::<Result<Vec<_>, _>>()?,
    };
    if let Some(amplitude) = &body_force.amplitude {
        amplitude
            .validate()
            .map_err(|message| SetupError::InvalidConfig {
                field: "body_force.amplitude",
                message,
            })?;
    }
    Ok(BodyForce::new(
        b,
        ranges,
        positions0.to_vec(),
        body_force.amplitude.clone(),
    ))
}

/// The particle contact of numerics.md §12.2 for the declared body pairs (or every pair of
/// different bodies); a body paired with itself gets self-contact beyond its reference
/// kernel support. In the updated-Lagrangian formulation bodies that already interact
/// through the kernel (same interaction group: same material, as in `UpdatedLagrangian`, and
/// every body with itself) get no contact: an explicit pair of them is an error, "all pairs"
/// skips them.
fn build_contact<const D: usize>(
    model: &Model<D>,
    contact: &crate::model::ContactDescription,
    bodies: &[BodyInfo],
    positions0: &[Vector<D>],
) -> Result<ParticleContact<D>, SetupError> {
    let n_real = positions0.len();
    let fail =
        |field: &'static str, message: String| Err(SetupError::InvalidConfig { field, message });
    if !(contact.scale.is_finite() && contact.scale > 0.0) {
        return fail(
            "contact.scale",
            format!("must be finite and > 0, got {}", contact.scale),
        );
    }
    if !(contact.exponent.is_finite() && contact.exponent >= 1.0) {
        return fail(
            "contact.exponent",
            format!("must be finite and ≥ 1, got {}", contact.exponent),
        );
    }
    let nb = bodies.len();
    let pairs = contact_pairs(model, contact.pairs.as_deref(), bodies, "contact.pairs")?;
    let mut laws: Vec<Option<PotentialLaw>> = vec![None; nb * nb];
    for (a, b) in pairs {
        let (ba, bb) = (&bodies[a], &bodies[b]);
        let modulus = |info: &BodyInfo| model.materials[info.material].model.longitudinal_modulus();
        let d0 = 0.5 * (ba.spacing + bb.spacing);
        let h_c = 0.5 * (ba.smoothing_length + bb.smoothing_length);
        let kernel = model
            .config
            .kernel
            .build(D, h_c)
            .map_err(|e| SetupError::Kernel(e.to_string()))?;
        if !(d0 < kernel.support_radius() && kernel.value(d0) > 0.0) {
            return fail(
                "contact",
                format!(
                    "bodies `{}` and `{}`: the contact distance d0 = {d0:e} must lie inside the kernel support of h_c = {h_c:e}",
                    ba.name, bb.name
                ),
            );
        }
        let law = PotentialLaw::new(
            kernel,
            d0,
            contact.scale * modulus(ba).min(modulus(bb)) * d0.powi(D as i32 - 1),
            contact.exponent,
            if a == b { kernel.support_radius() } else { 0.0 },
        );
        laws[a * nb + b] = Some(law);
        laws[b * nb + a] = Some(law);
    }
    Ok(ParticleContact::new(
        laws,
        nb,
        &body_indices(bodies, n_real),
        reflections(&model.effects.symmetry_planes),
    ))
}

/// The body pairs of a contact law: the declared ones (checked to exist and, in the
/// updated-Lagrangian formulation, not to share a kernel group) or every pair of different
/// bodies that does not already interact through the kernel.
fn contact_pairs<const D: usize>(
    model: &Model<D>,
    declared: Option<&[(usize, usize)]>,
    bodies: &[BodyInfo],
    field: &'static str,
) -> Result<Vec<(usize, usize)>, SetupError> {
    let nb = bodies.len();
    let updated = model.config.formulation == Formulation::UpdatedLagrangian;
    let kernel_linked =
        |a: usize, b: usize| updated && model.kernel_group(a) == model.kernel_group(b);
    match declared {
        Some(pairs) => {
            for &(a, b) in pairs {
                let message = if a >= nb || b >= nb {
                    format!("({a}, {b}) is not a pair of existing bodies")
                } else if kernel_linked(a, b) {
                    format!(
                        "bodies `{}` and `{}` already interact through the kernel in the updated-Lagrangian formulation (same kernel group); contact would count their interaction twice",
                        bodies[a].name, bodies[b].name
                    )
                } else {
                    continue;
                };
                return Err(SetupError::InvalidConfig { field, message });
            }
            Ok(pairs.to_vec())
        }
        None => Ok((0..nb)
            .flat_map(|a| (a + 1..nb).map(move |b| (a, b)))
            .filter(|&(a, b)| !kernel_linked(a, b))
            .collect()),
    }
}

/// A wall spins only about an axis of its own symmetry, so that the spin moves its surface and
/// not its shape (`WallMotion::spin`): ω finite, along a plane's or a disc's normal or a
/// cylinder's or a cone's axis, any for a ball; in 2D only a ball spins, about z. The spin is
/// felt only through friction, so a frictionless wall may not spin.
fn check_spin<const D: usize>(
    shape: &WallShape<D>,
    normal: Vector<D>,
    omega: tlsph_math::Vector3,
    coefficients: FrictionCoefficients,
) -> Result<(), String> {
    if !omega.iter().all(|w| w.is_finite()) {
        return Err(format!("needs a finite spin, got {omega:?}"));
    }
    if !coefficients.is_frictional() {
        return Err("a spin is felt only through friction; give the wall a friction coefficient, or no spin".into());
    }
    let Some(axis) = shape.spin_axis(normal)? else {
        return Ok(());
    };
    if omega.cross(&axis).norm() > 1e-12 * omega.norm() {
        return Err(format!(
            "the spin {omega:?} must be about the wall's own axis {axis:?} (a plane's or a disc's normal, a cylinder's or a cone's axis; about z in 2D): about any other axis the wall's shape would move"
        ));
    }
    Ok(())
}

/// A wall's shape as `WallShape` builds it after its own checks (`rigid_box`, `rigid_cone`,
/// `rigid_pyramid`), or why there is none; `what` names the shape for a variant mismatch.
fn built_shape<G>(shape: Option<Result<G, String>>, what: &str) -> Result<G, String> {
    shape.unwrap_or_else(|| Err(format!("is not a {what}")))
}

/// Adds a wall of shape `G`, with its travel limit per step (`length`, a particle with that
/// h; it binds only if the wall moves), and, when its surface has friction `coefficients`,
/// its friction effect right after it (so the friction sees this step's normal kick; a spin
/// turns about the axis through `point`, the wall's point).
fn push_wall<const D: usize, G: WallGeometry<D> + Clone + 'static>(
    effects: &mut Vec<BookedEffect<D>>,
    (length, particle): (f64, usize),
    wall: RigidWall<D, G>,
    (coefficients, point, report_moment): (FrictionCoefficients, Vector<D>, bool),
) {
    let wall = wall.with_travel_limit(length, particle);
    let wall = if report_moment {
        wall.with_moment_about(point)
    } else {
        wall
    };
    let friction = coefficients
        .is_frictional()
        .then(|| wall.friction(coefficients, point));
    effects.push(BookedEffect::new(Box::new(wall)));
    if let Some(friction) = friction {
        effects.push(BookedEffect::new(Box::new(friction)));
    }
}

/// Fuller's particle-type penalty contact (numerics.md §12.1) for the declared body pairs (or
/// every pair of different bodies): k_c = s E* d0^{d−1} with E* the smaller Young's modulus,
/// R = range · d0, kinetic and static friction coefficients. A body paired with itself gets
/// self-contact between its particles that are not kernel neighbours in the reference
/// configuration (total-Lagrangian formulations; `contact_pairs` refuses it with
/// `"updated-lagrangian"`). A body whose every particle has every velocity component
/// prescribed is driven: its surface is the master surface of its pairs.
fn build_penalty_contact<const D: usize>(
    model: &Model<D>,
    contact: &crate::model::PenaltyContactDescription,
    bodies: &[BodyInfo],
    kernels: &[tlsph_kernels::AnyKernel],
    drivers: &Drivers<D>,
) -> Result<PenaltyContact<D>, SetupError> {
    let fail =
        |field: &'static str, message: String| Err(SetupError::InvalidConfig { field, message });
    for (field, value) in [
        ("penalty_contact.stiffness", contact.stiffness),
        ("penalty_contact.range", contact.range),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return fail(field, format!("must be finite and > 0, got {value}"));
        }
    }
    let friction = contact.friction;
    if let Err(message) = friction.check() {
        return fail("penalty_contact.friction", message);
    }
    let nb = bodies.len();
    let pairs = contact_pairs(
        model,
        contact.pairs.as_deref(),
        bodies,
        "penalty_contact.pairs",
    )?;
    let mut laws = vec![None; nb * nb];
    for (a, b) in pairs {
        let youngs = |info: &BodyInfo| model.materials[info.material].model.youngs_modulus();
        let law = PenaltyLaw::new::<D>(
            contact.stiffness,
            contact.range,
            friction,
            youngs(&bodies[a]).min(youngs(&bodies[b])),
            0.5 * (bodies[a].spacing + bodies[b].spacing),
        );
        laws[a * nb + b] = Some(law);
        laws[b * nb + a] = Some(law);
    }
    let n_real = bodies.last().map_or(0, |b| b.range.end);
    let mut fully_held = vec![false; n_real];
    for (i, held) in drivers.held_components() {
        fully_held[i] = held.iter().all(|&c| c);
    }
    let driven = bodies
        .iter()
        .map(|b| fully_held[b.range.clone()].iter().all(|&h| h))
        .collect();
    Ok(PenaltyContact::new(
        laws,
        nb,
        kernels.to_vec(),
        &body_indices(bodies, n_real),
        driven,
        reflections(&model.effects.symmetry_planes),
    ))
}

/// Effects that need the reference bonds or mirror particles, refused for the
/// updated-Lagrangian formulation with a message saying why.
/// A reference update needs a total-Lagrangian formulation, the Jaumann-rate stress update
/// (the Green–Lagrange path needs F relative to the initial configuration) and no damage or
/// failure model and no XSPH (their state is tied to the initial bonds), and no self-contact
/// (the new reference bonds every pair within the kernel support, so surfaces that
/// self-contact holds together would be welded); the threshold must be a positive strain.
fn check_reference_update<const D: usize>(
    model: &Model<D>,
    update: crate::model::ReferenceUpdate,
    any_failure: bool,
) -> Result<(), SetupError> {
    let problem = if !(update.strain_threshold.is_finite() && update.strain_threshold > 0.0) {
        Some(format!(
            "strain_threshold must be finite and > 0, got {}",
            update.strain_threshold
        ))
    } else if model.config.formulation == Formulation::UpdatedLagrangian {
        Some("formulation = \"updated-lagrangian\" has no reference configuration to update".into())
    } else if model.config.stress_update == StressUpdate::GreenLagrange {
        Some("it needs stress_update = \"jaumann-rate\" (the Green-Lagrange path needs F relative to the initial configuration)".into())
    } else if any_failure {
        Some("it cannot be combined with a damage or failure model yet (failed particles are removed from the initial bonds)".into())
    } else if model.effects.xsph.is_some() {
        Some("it cannot be combined with XSPH yet".into())
    } else if let Some((a, _)) = model
        .effects
        .contact
        .iter()
        .flat_map(|c| c.pairs.iter().flatten())
        .chain(
            model
                .effects
                .penalty_contact
                .iter()
                .flat_map(|c| c.pairs.iter().flatten()),
        )
        .find(|(a, b)| a == b)
    {
        Some(format!(
            "it cannot be combined with self-contact (body `{}`): the new reference bonds every pair of particles within the kernel support, so surfaces that self-contact holds together would be welded",
            model.bodies.get(*a).map_or("?", |b| b.name.as_str())
        ))
    } else {
        None
    };
    match problem {
        Some(message) => Err(SetupError::InvalidConfig {
            field: "reference_update",
            message,
        }),
        None => Ok(()),
    }
}

fn check_updated_lagrangian_effects<const D: usize>(model: &Model<D>) -> Result<(), SetupError> {
    let refuse = |field: &'static str, why: &str| {
        Err(SetupError::InvalidConfig {
            field,
            message: format!("not available with formulation = \"updated-lagrangian\": {why}"),
        })
    };
    if model.effects.hourglass_control.is_some() {
        return refuse(
            "hourglass_control",
            "it corrects the reference-bond F of TLSPH; use artificial_viscosity",
        );
    }
    Ok(())
}

/// Smallest principal stretch sqrt(min eig FᵀF) of a D×D deformation gradient (NaN for a
/// non-finite F).
fn smallest_stretch<const D: usize>(f: &tlsph_math::Tensor<D>) -> f64 {
    let c = f.transpose() * f;
    let smallest = match D {
        1 => c[(0, 0)],
        2 => {
            let (a, b, d) = (c[(0, 0)], c[(0, 1)], c[(1, 1)]);
            let mean = 0.5 * (a + d);
            mean - (0.25 * (a - d) * (a - d) + b * b).sqrt()
        }
        _ => {
            let c3 = tlsph_math::embed_with_identity(&c);
            c3.symmetric_eigenvalues().min()
        }
    };
    smallest.max(0.0).sqrt()
}

/// Index of the first item that satisfies `pred`, searched in parallel by chunks.
///
/// Cheaper than `position_first` on a flat iterator, which synchronises per item; the answer is
/// the same (the lowest index) for any thread count.
fn first_index_where<T: Sync>(items: &[T], pred: impl Fn(&T) -> bool + Sync) -> Option<usize> {
    items
        .par_chunks(CHUNK)
        .enumerate()
        .find_map_first(|(c, chunk)| chunk.iter().position(&pred).map(|k| c * CHUNK + k))
}

pub(crate) fn min_by_value_then_index(a: (f64, usize), b: (f64, usize)) -> (f64, usize) {
    // Total order (value, index) makes the reduction independent of how rayon splits it.
    match a.0.total_cmp(&b.0) {
        std::cmp::Ordering::Less => a,
        std::cmp::Ordering::Greater => b,
        std::cmp::Ordering::Equal => {
            if a.1 <= b.1 {
                a
            } else {
                b
            }
        }
    }
}

fn validate_config(c: &SimulationConfig) -> Result<(), SetupError> {
    let check = |field: &'static str, ok: bool, message: String| {
        if ok {
            Ok(())
        } else {
            Err(SetupError::InvalidConfig { field, message })
        }
    };
    check(
        "smoothing_factor",
        c.smoothing_factor.is_finite() && c.smoothing_factor > 0.0,
        format!("must be > 0, got {}", c.smoothing_factor),
    )?;
    check(
        "cfl",
        c.cfl.is_finite() && c.cfl > 0.0 && c.cfl <= 1.0,
        format!("must be in (0, 1], got {}", c.cfl),
    )?;
    check(
        "end_time",
        c.end_time.is_finite() && c.end_time > 0.0,
        format!("must be > 0, got {}", c.end_time),
    )
}

fn validate_body<const D: usize>(
    body: &crate::model::BodyDescription<D>,
    density: f64,
) -> Result<(), SetupError> {
    let fail = |message: String| {
        Err(SetupError::InvalidBody {
            body: body.name.clone(),
            message,
        })
    };
    let n = body.positions.len();
    if n == 0 {
        return fail("has no particles".into());
    }
    if body.volumes.len() != n || body.velocities.len() != n {
        return fail(format!(
            "{n} positions but {} volumes and {} velocities",
            body.volumes.len(),
            body.velocities.len()
        ));
    }
    if !(body.spacing.is_finite() && body.spacing > 0.0) {
        return fail(format!("spacing must be > 0, got {}", body.spacing));
    }
    if !(density.is_finite() && density > 0.0) {
        return fail(format!("material density must be > 0, got {density}"));
    }
    if let Some(i) = body
        .volumes
        .iter()
        .position(|v| !(v.is_finite() && *v > 0.0))
    {
        return fail(format!("particle {i} has volume {}", body.volumes[i]));
    }
    if let Some(i) = body
        .velocities
        .iter()
        .position(|v| !v.iter().all(|x| x.is_finite()))
    {
        return fail(format!("particle {i} has a non-finite velocity"));
    }
    if let Err(message) = check_kinetic_energy(&body.velocities, &body.volumes, density) {
        return fail(message);
    }
    Ok(())
}

/// Sound speed c = sqrt((K_s + 4G/3) J/ρ0) of a particle whose pressure comes from `eos`,
/// with K_s the isentropic bulk modulus at μ = 1/J − 1 and E_v = ρ0 e (numerics.md §8.10;
/// `shear_term` = 4G/3, `specific_energy` = e). Infinite beyond a limiting compression.
#[inline]
fn eos_sound_speed(
    eos: &tlsph_materials::EquationOfState,
    shear_term: f64,
    rho0: f64,
    jacobian: f64,
    specific_energy: f64,
) -> f64 {
    let modulus = eos.isentropic_bulk_modulus(1.0 / jacobian - 1.0, rho0 * specific_energy);
    ((modulus + shear_term) * jacobian / rho0).max(0.0).sqrt()
}

/// The kinetic energy ½ ρ0 V |v|² of one particle, or a message (naming its velocity, not the
/// particle) if it overflows f64; [`check_kinetic_energy`] does this for a whole body.
pub fn particle_kinetic_energy<const D: usize>(
    velocity: &Vector<D>,
    volume: f64,
    density: f64,
) -> Result<f64, String> {
    let energy = 0.5 * density * volume * velocity.norm_squared();
    if energy.is_finite() {
        Ok(energy)
    } else {
        Err(format!(
            "the kinetic energy ½ρV|v|² of its velocity {:?} is not a finite number",
            velocity.as_slice()
        ))
    }
}

/// The kinetic energy Σ ½ ρ0 V_I |v_I|² of a body's starting state, or a message naming the
/// first particle (or the body as a whole) whose kinetic energy overflows f64. A velocity whose
/// square overflows (|v| ≳ 1e154) leaves no finite energy balance and no finite time step
/// (numerics.md §6: Δt ∝ h / (c + |v|)), so a run would end after one step of nothing.
pub fn check_kinetic_energy<const D: usize>(
    velocities: &[Vector<D>],
    volumes: &[f64],
    density: f64,
) -> Result<f64, String> {
    let mut total = 0.0;
    for (i, (v, volume)) in velocities.iter().zip(volumes).enumerate() {
        total += particle_kinetic_energy(v, *volume, density)
            .map_err(|message| format!("particle {i}: {message}"))?;
    }
    if !total.is_finite() {
        return Err("the body's kinetic energy is not a finite number".into());
    }
    Ok(total)
}

#[cfg(test)]
mod penalty_contact_tests {
    use super::*;
    use crate::model::{
        BodyDescription, FrictionCoefficients, MaterialDescription, PenaltyContactDescription,
        SimulationConfig,
    };
    use tlsph_kernels::KernelKind;
    use tlsph_materials::LinearElastic;

    /// An n × n block of spacing 1 with its lower-left particle at `origin`.
    fn block(name: &str, n: usize, origin: [f64; 2]) -> BodyDescription<2> {
        let positions: Vec<Vector<2>> = (0..n * n)
            .map(|k| Vector::<2>::new(origin[0] + (k % n) as f64, origin[1] + (k / n) as f64))
            .collect();
        BodyDescription {
            name: name.into(),
            material: 0,
            spacing: 1.0,
            volumes: vec![1.0; positions.len()],
            velocities: vec![Vector::zeros(); positions.len()],
            positions,
            initial_stress: None,
            initial_stress_gradient: None,
            initial_stresses: None,
            initial_plastic_strains: None,
            initial_damage: None,
            initial_failure_damage: None,
        }
    }

    #[test]
    fn surface_detection_reproduces_the_lattice_counts_and_normals() {
        // numerics.md §12.1 item 2, lattice check [A] (2D, h = 1.5Δx, support 3Δx): a fully
        // surrounded particle has 24 neighbours, a flat face 14 (58 %), the row beneath it 19
        // (79 %), a convex corner 8 (33 %) and a face particle next to the corner 11 (46 %);
        // with the 75 % threshold the face and corner rows are surface, the row beneath is not.
        let model = Model {
            config: SimulationConfig {
                formulation: Formulation::TotalLagrangianCorrected,
                stress_update: crate::model::StressUpdate::JaumannRate,
                kernel: KernelKind::CubicSpline,
                smoothing_factor: 1.5,
                cfl: 0.5,
                end_time: 1.0,
            },
            materials: vec![MaterialDescription {
                name: "unit".into(),
                density: 1.0,
                model: MaterialModel::LinearElastic(LinearElastic::new(1.0, 0.25).unwrap()),
            }],
            bodies: vec![block("a", 10, [0.0, 0.0]), block("b", 3, [40.0, 0.0])],
            boundaries: vec![],
            effects: Default::default(),
        };
        let sim = Simulation::new(model.clone()).unwrap();
        let description = PenaltyContactDescription {
            stiffness: 1.0,
            range: 1.0,
            friction: FrictionCoefficients::single(0.0),
            pairs: None,
        };
        let mut contact = build_penalty_contact(
            &model,
            &description,
            &sim.bodies,
            &sim.kernels,
            &sim.drivers,
        )
        .unwrap();
        let at = Configuration {
            particles: &sim.particles,
            bonds: &sim.bonds,
            pairs: None,
            time: 0.0,
        };
        let (count, surface, normal) = contact.surface_state(&at);
        let index = |x: usize, y: usize| y * 10 + x;
        let expect = [
            ((5, 5), 24, false),
            ((5, 0), 14, true),
            ((5, 1), 19, false),
            ((0, 0), 8, true),
            ((1, 0), 11, true),
        ];
        for ((x, y), n, is_surface) in expect {
            let i = index(x, y);
            assert_eq!(
                (count[i], surface[i]),
                (n, is_surface),
                "particle ({x}, {y})"
            );
        }
        // Normals point out of the body: exactly −y mid-face (mirror symmetry), along the
        // diagonal at the corner.
        let face = normal[index(5, 0)];
        assert!(
            (face - Vector::<2>::new(0.0, -1.0)).norm() < 1e-12,
            "{face:?}"
        );
        let corner = normal[index(0, 0)];
        let diagonal = Vector::<2>::new(-1.0, -1.0) / 2f64.sqrt();
        assert!((corner - diagonal).norm() < 1e-12, "{corner:?}");
        assert_eq!(normal[index(5, 5)], Vector::<2>::zeros());
    }
}

#[cfg(test)]
mod time_step_tests {
    use super::*;
    use crate::model::{
        BodyDescription, ElasticPlastic, FailureModel, MaterialDescription, PressureModel,
        SimulationConfig, StrengthModel,
    };
    use tlsph_kernels::KernelKind;
    use tlsph_materials::eos::MieGruneisenParameters;
    use tlsph_materials::{
        EquationOfState, LinearElastic, MaxPlasticStrainFailure, MieGruneisen, VonMisesPlasticity,
    };

    #[test]
    fn the_time_step_reads_the_density_the_equation_of_state_reads() {
        // A copper rod (M-CU9 Mie–Grüneisen, a failure criterion, so J is carried across
        // neighbour-set rebuilds) compressed uniformly to J = 0.9. One particle's carried J
        // is set to 0.8 of its kernel estimate, as a neighbour's removal can leave it: its
        // EOS reads J = 0.72 and is stiffer there, so it limits Δt with the sound speed of that
        // J (numerics.md §8.10). The kernel estimate alone would give a 29 % longer step.
        let (n, dx, rho0) = (20, 1e-4, 8924.0);
        let eos: EquationOfState = MieGruneisen::new(MieGruneisenParameters {
            reference_density: rho0,
            sound_speed: 3940.0,
            s1: 1.489,
            s2: 0.0,
            s3: 0.0,
            gamma0: 2.02,
            a: 0.47,
        })
        .unwrap()
        .into();
        let elastic = LinearElastic::new(110e9, 0.343).unwrap();
        let material = ElasticPlastic {
            elastic,
            strength: StrengthModel::VonMises(VonMisesPlasticity::new(90e6, 0.0).unwrap()),
            pressure: PressureModel::Eos(eos),
            min_pressure: None,
            thermal: None,
            failure: Some(FailureModel::MaxPlasticStrain(
                MaxPlasticStrainFailure::new(10.0).unwrap(),
            )),
            damage: None,
        };
        let positions: Vec<Vector<1>> = (0..n)
            .map(|k| Vector::<1>::new((k as f64 + 0.5) * dx))
            .collect();
        let model = Model {
            config: SimulationConfig {
                formulation: Formulation::TotalLagrangianCorrected,
                stress_update: StressUpdate::JaumannRate,
                kernel: KernelKind::CubicSpline,
                smoothing_factor: 1.2,
                cfl: 0.3,
                end_time: 1.0,
            },
            materials: vec![MaterialDescription {
                name: "copper".into(),
                density: rho0,
                model: MaterialModel::ElasticPlastic(material),
            }],
            bodies: vec![BodyDescription {
                name: "rod".into(),
                material: 0,
                spacing: dx,
                volumes: vec![dx; n],
                velocities: vec![Vector::zeros(); n],
                positions: positions.clone(),
                initial_stress: None,
                initial_stress_gradient: None,
                initial_stresses: None,
                initial_plastic_strains: None,
                initial_damage: None,
                initial_failure_damage: None,
            }],
            boundaries: vec![],
            effects: Default::default(),
        };
        let mut sim = Simulation::new(model).unwrap();
        let j = 0.9;
        let u: Vec<Vector<1>> = positions.iter().map(|x| x * (j - 1.0)).collect();
        sim.set_displacements(&u);
        // The first step has Δt = 0: the rod's state is J = 0.9 and e = 0 everywhere.
        sim.step().unwrap();
        let (limited, carry) = (7, 0.8);
        sim.jacobian_carry[limited] = carry;
        let (dt, particle) = sim.stable_dt((f64::INFINITY, usize::MAX), 1).unwrap();
        // c = sqrt((K_s(μ) + 4G/3) J/ρ0) at e = 0 (numerics.md §8.10).
        let shear_term = 4.0 / 3.0 * sim.materials[0].equation_of_state().unwrap().1;
        let sound_speed = |j: f64| {
            ((eos.isentropic_bulk_modulus(1.0 / j - 1.0, 0.0) + shear_term) * j / rho0).sqrt()
        };
        let c = sound_speed(j * carry);
        let expected = 0.3 * 1.2 * dx / c;
        assert_eq!(particle, limited);
        assert!(
            (dt / expected - 1.0).abs() < 1e-12,
            "Δt = {dt:e}, expected {expected:e}"
        );
        assert!((sim.sound_speed(limited) / c - 1.0).abs() < 1e-12);
        // The carry matters here: the kernel estimate's J gives a sound speed 1.29 times lower.
        assert!(c / sound_speed(j) > 1.25);
    }
}
