//! Numerical stability measured, not eyeballed: particle-distance distortion, clumping and
//! energy drift sampled during a run, with the first step at which any of them crosses its
//! threshold (or the state goes non-finite).
//!
//! Quantities, per sample (all dimensionless), with d_I the distance from particle I to the
//! nearest other surviving particle in the current configuration and Δx_I its body's initial
//! spacing:
//! - **spacing ratio** d_I / Δx_I: the plain measure, reported as its extremes;
//! - **nearest-neighbour ratio** d_I / (λ_min,I Δx_I), with λ_min,I the smallest principal
//!   stretch of the particle's deformation gradient F_I: the nearest neighbour of a lattice
//!   deformed by F sits λ_min Δx away, so this ratio is 1 under any smooth deformation, however
//!   large, and departs from 1 only where particles move differently from their neighbourhood.
//!   Its minimum shows clumping (the tensile instability pulls pairs together, R §6.1.1, Swegle
//!   et al.), its maximum voids and numerical fracture (nobody within 2Δx counts as 2/λ_min).
//!   The thresholds apply to this ratio, so a Taylor bar's large plastic compression is not
//!   mistaken for clumping.
//! - **clumping index**: the coefficient of variation std/mean of the nearest-neighbour ratio
//!   over particles; 0 on any smoothly deformed lattice, large once particles pair up.
//! - **energy drift**: |E − E0| / E_scale with E = kinetic + internal + booked effect energies
//!   and E_scale = the largest of |E0|, the kinetic and the |internal| energy seen so far
//!   (a run that starts at rest in a prestressed state has E0 = 0).

use crate::diagnostics::Diagnostics;
use crate::simulation::Simulation;

/// Thresholds of the stability report (defaults from the pass criteria of problems.md R-P1,
/// R-P5 and R-P9a).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabilityThresholds {
    /// Smallest acceptable nearest-neighbour ratio (clumping below; default 0.5).
    pub min_neighbour_ratio: f64,
    /// Largest acceptable nearest-neighbour ratio (voids above; default 1.5).
    pub max_neighbour_ratio: f64,
    /// Largest acceptable clumping index (default 0.2).
    pub clumping_index: f64,
    /// Largest acceptable relative energy drift (default 0.05).
    pub energy_drift: f64,
}

impl Default for StabilityThresholds {
    fn default() -> Self {
        Self {
            min_neighbour_ratio: 0.5,
            max_neighbour_ratio: 1.5,
            clumping_index: 0.2,
            energy_drift: 0.05,
        }
    }
}

/// Nearest-neighbour statistics of the current configuration (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeighbourDistances {
    /// min_I d_I/(λ_min,I Δx_I).
    pub min_ratio: f64,
    /// max_I d_I/(λ_min,I Δx_I) (d capped at 2Δx).
    pub max_ratio: f64,
    /// std/mean of d_I/(λ_min,I Δx_I).
    pub clumping_index: f64,
    /// min_I d_I/Δx_I.
    pub min_spacing_ratio: f64,
    /// max_I d_I/Δx_I (capped at 2).
    pub max_spacing_ratio: f64,
}

impl NeighbourDistances {
    /// All statistics NaN: no particles to measure, or non-finite positions.
    pub fn undefined() -> Self {
        Self {
            min_ratio: f64::NAN,
            max_ratio: f64::NAN,
            clumping_index: f64::NAN,
            min_spacing_ratio: f64::NAN,
            max_spacing_ratio: f64::NAN,
        }
    }
}

/// One sample of the stability report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabilitySample {
    /// Step index.
    pub step: u64,
    /// Time \[s\].
    pub time: f64,
    /// Nearest-neighbour statistics.
    pub distances: NeighbourDistances,
    /// Relative energy drift.
    pub energy_drift: f64,
}

/// The first threshold crossing of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    /// Step index of the first sample beyond a threshold.
    pub step: u64,
    /// Its time \[s\].
    pub time: f64,
    /// Which quantity crossed: `min_neighbour_ratio`, `max_neighbour_ratio`,
    /// `clumping_index`, `energy_drift` or `non_finite`.
    pub quantity: &'static str,
    /// Its value (NaN for `non_finite`).
    pub value: f64,
}

/// Samples the stability quantities of a run and remembers the first threshold crossing.
#[derive(Debug, Clone)]
pub struct StabilityMonitor {
    /// Thresholds in force.
    pub thresholds: StabilityThresholds,
    /// Samples so far.
    pub samples: Vec<StabilitySample>,
    /// First crossing, if any.
    pub first_crossing: Option<Crossing>,
    initial_energy: Option<f64>,
    energy_scale: f64,
}

impl StabilityMonitor {
    /// A monitor with the given thresholds.
    pub fn new(thresholds: StabilityThresholds) -> Self {
        Self {
            thresholds,
            samples: Vec::new(),
            first_crossing: None,
            initial_energy: None,
            energy_scale: 0.0,
        }
    }

    /// Samples the simulation's current state (one neighbour search: call at output
    /// intervals, not every step).
    pub fn observe<const D: usize>(&mut self, sim: &Simulation<D>) {
        self.observe_with(sim, &sim.diagnostics());
    }

    /// As [`StabilityMonitor::observe`] with diagnostics already computed for this instant.
    pub fn observe_with<const D: usize>(&mut self, sim: &Simulation<D>, diagnostics: &Diagnostics) {
        let energy = diagnostics.total_energy();
        let e0 = *self.initial_energy.get_or_insert(energy);
        self.energy_scale = self
            .energy_scale
            .max(e0.abs())
            .max(diagnostics.kinetic)
            .max(diagnostics.internal.abs());
        let energy_drift = if self.energy_scale > 0.0 {
            (energy - e0).abs() / self.energy_scale
        } else {
            0.0
        };
        let sample = StabilitySample {
            step: sim.steps_done().saturating_sub(1),
            time: sim.time(),
            distances: sim.neighbour_distances(),
            energy_drift,
        };
        if self.first_crossing.is_none() {
            let t = &self.thresholds;
            let d = &sample.distances;
            let crossed = [
                (
                    "min_neighbour_ratio",
                    d.min_ratio,
                    d.min_ratio < t.min_neighbour_ratio,
                ),
                (
                    "max_neighbour_ratio",
                    d.max_ratio,
                    d.max_ratio > t.max_neighbour_ratio,
                ),
                (
                    "clumping_index",
                    d.clumping_index,
                    d.clumping_index > t.clumping_index,
                ),
                ("energy_drift", energy_drift, energy_drift > t.energy_drift),
            ]
            .into_iter()
            .find(|&(_, value, crossed)| crossed || !value.is_finite());
            if let Some((quantity, value, _)) = crossed {
                self.first_crossing = Some(Crossing {
                    step: sample.step,
                    time: sample.time,
                    quantity: if value.is_finite() {
                        quantity
                    } else {
                        "non_finite"
                    },
                    value,
                });
            }
        }
        self.samples.push(sample);
    }

    /// Records that the run stopped on a non-finite or inverted state at `step`, `time`.
    pub fn observe_breakdown(&mut self, step: u64, time: f64) {
        if self.first_crossing.is_none() {
            self.first_crossing = Some(Crossing {
                step,
                time,
                quantity: "non_finite",
                value: f64::NAN,
            });
        }
    }

    /// Whether every sample stayed inside the thresholds.
    pub fn stayed_inside(&self) -> bool {
        self.first_crossing.is_none()
    }

    /// Extremes over all samples: (min of min ratio, max of max ratio, max clumping index,
    /// max energy drift).
    pub fn extremes(&self) -> (f64, f64, f64, f64) {
        self.samples.iter().fold(
            (f64::INFINITY, 0.0f64, 0.0f64, 0.0f64),
            |(lo, hi, c, e), s| {
                (
                    lo.min(s.distances.min_ratio),
                    hi.max(s.distances.max_ratio),
                    c.max(s.distances.clumping_index),
                    e.max(s.energy_drift),
                )
            },
        )
    }
}
