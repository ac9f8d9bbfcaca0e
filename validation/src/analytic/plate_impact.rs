//! R-P2 references (Reveles §6.1.2, Eqs 6.1–6.5): symmetric 1D uniaxial-strain plate impact.
//! Linear analytic values, exact finite-strain states for a general elastic law P(λ), a converged
//! 1D Lagrangian reference computation, and the pulse measurements (plateau, arrival, duration)
//! that are applied in the same way to the reference and to SPH gauge histories.
//!
//! Set-up (problems.md R-P2): flyer X ∈ [0, L_f] moving at V hits the target X ∈ [L_f, L_f + L_t]
//! at rest at t = 0; both have reference density ρ0 and the same law; the interface is bonded and
//! the outer faces are free. Lagrangian coordinate X, stretch λ = ∂x/∂X, first Piola–Kirchhoff
//! stress P(λ) (tension positive). In 1D uniaxial strain F = J = λ, so the Cauchy stress
//! σ = J⁻¹ P F = P: every "stress" below is both. The equations are
//! ∂λ/∂t = ∂v/∂X, ρ0 ∂v/∂t = ∂P/∂X, with Lagrangian wave speed c(λ) = sqrt(P'(λ)/ρ0).
//!
//! Wave types. A compressive front steepens into a shock when c grows with compression
//! (P'' < 0, e.g. the logarithmic rate law) and spreads into a centred fan when c falls with
//! compression (P'' > 0, e.g. St Venant–Kirchhoff in uniaxial strain: P'' = 3Mλ > 0). The
//! release that follows is then a fan or a shock respectively.

use std::fmt;

/// Problem id.
pub const PROBLEM: &str = "R-P2";

/// Courant number c_max Δt/ΔX of the reference computation (MUSCL–Hancock is stable up to 1).
pub const COURANT: f64 = 0.8;

/// One-dimensional uniaxial-strain elastic law P(λ), λ = stretch ∂x/∂X.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum UniaxialLaw {
    /// Small-strain law P = M (λ − 1); both fronts are discontinuities moving at c0.
    Linear {
        /// Longitudinal modulus M = K + 4G/3.
        modulus: f64,
    },
    /// Hypoelastic rate law (Jaumann rate, numerics.md §8.1, Algorithm 2) integrated in uniaxial
    /// strain: σ̇ = M D = M λ̇/λ, so σ = P = M ln λ.
    LogarithmicRate {
        /// Longitudinal modulus M = K + 4G/3.
        modulus: f64,
    },
    /// St Venant–Kirchhoff (Algorithm 1, numerics.md §8.2): S = M E, E = (λ² − 1)/2, P = λ S.
    StVenantKirchhoff {
        /// Longitudinal modulus M = K + 4G/3.
        modulus: f64,
    },
}

impl UniaxialLaw {
    /// Longitudinal modulus M.
    pub fn modulus(&self) -> f64 {
        match *self {
            Self::Linear { modulus }
            | Self::LogarithmicRate { modulus }
            | Self::StVenantKirchhoff { modulus } => modulus,
        }
    }

    /// Short name used in CSVs and report rows: `linear`, `log_rate`, `svk`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Linear { .. } => "linear",
            Self::LogarithmicRate { .. } => "log_rate",
            Self::StVenantKirchhoff { .. } => "svk",
        }
    }

    /// First Piola–Kirchhoff stress P(λ) = Cauchy stress in uniaxial strain.
    pub fn first_piola(&self, stretch: f64) -> f64 {
        self.evaluate(stretch).0
    }

    /// Tangent modulus dP/dλ.
    pub fn tangent(&self, stretch: f64) -> f64 {
        self.evaluate(stretch).1
    }

    /// Curvature d²P/dλ² (sign decides shock vs fan, see the module docs).
    pub fn curvature(&self, stretch: f64) -> f64 {
        self.evaluate(stretch).2
    }

    /// Lagrangian wave speed c(λ) = sqrt(P'(λ)/ρ0) (dX/dt of a characteristic).
    pub fn wave_speed(&self, stretch: f64, density: f64) -> f64 {
        (self.tangent(stretch) / density).sqrt()
    }

    /// (P, P', P'') at stretch λ.
    #[inline]
    pub fn evaluate(&self, stretch: f64) -> (f64, f64, f64) {
        let l = stretch;
        match *self {
            Self::Linear { modulus: m } => (m * (l - 1.0), m, 0.0),
            Self::LogarithmicRate { modulus: m } => (m * l.ln(), m / l, -m / (l * l)),
            Self::StVenantKirchhoff { modulus: m } => (
                0.5 * m * l * (l * l - 1.0),
                0.5 * m * (3.0 * l * l - 1.0),
                3.0 * m * l,
            ),
        }
    }
}

impl fmt::Display for UniaxialLaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Geometry, material and resolution of the plate-impact problem.
#[derive(Debug, Clone, PartialEq)]
pub struct PlateImpactConfig {
    /// Flyer thickness L_f (0.5, problems.md R-P2 `[T]`).
    pub flyer_length: f64,
    /// Target thickness L_t (1.5 `[T]`).
    pub target_length: f64,
    /// Reference density ρ0 (1 `[T]`).
    pub density: f64,
    /// Longitudinal modulus M used by [`linear_reference`] (1.0, material M-ND2).
    pub modulus: f64,
    /// Flyer velocity V (0.1 `[T]`).
    pub impact_velocity: f64,
    /// Cells of the reference computation over [0, L_f + L_t].
    pub n_cells: usize,
    /// End time of the reference computation.
    pub end_time: f64,
    /// Time of the stored profile (1.5, Fig 6.5).
    pub profile_time: f64,
    /// Gauge positions X (reference coordinates).
    pub gauges: Vec<f64>,
}

impl Default for PlateImpactConfig {
    /// The R-P2 set: L_f 0.5, L_t 1.5, ρ0 1, M 1, V 0.1; 8000 cells (ΔX = 2.5e-4, a quarter of
    /// the SPH spacing); end time 2.0; profile at 1.5; gauges at X = 1.25 (target middle) and 2.0
    /// (target rear face).
    fn default() -> Self {
        Self {
            flyer_length: 0.5,
            target_length: 1.5,
            density: 1.0,
            modulus: 1.0,
            impact_velocity: 0.1,
            n_cells: 8000,
            end_time: 2.0,
            profile_time: 1.5,
            gauges: vec![1.25, 2.0],
        }
    }
}

impl PlateImpactConfig {
    /// Total length L = L_f + L_t.
    pub fn total_length(&self) -> f64 {
        self.flyer_length + self.target_length
    }

    /// Same configuration with another resolution.
    pub fn with_cells(&self, n_cells: usize) -> Self {
        Self {
            n_cells,
            ..self.clone()
        }
    }
}

/// Linear analytic solution (R Eqs 6.1–6.5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearPlateImpact {
    /// C_e = sqrt(M/ρ0) (R 6.1).
    pub wave_speed: f64,
    /// U_p = V/2 behind the front.
    pub particle_velocity: f64,
    /// |σ| = ½ ρ0 V C_e (R 6.4); the stress itself is compressive (negative).
    pub plateau_stress: f64,
    /// Uniaxial strain magnitude U_p / C_e = σ/M (problems.md R-P2 ambiguity note).
    pub strain: f64,
    /// Pulse length Λ = 2 L_f.
    pub pulse_length: f64,
    /// Pulse duration t_p = 2 L_f / C_e (R 6.5).
    pub pulse_duration: f64,
    /// Arrival of the front at the target rear face, L_t / C_e.
    pub rear_arrival: f64,
    /// Free-surface velocity of the target rear face after arrival, 2 U_p = V.
    pub free_surface_velocity: f64,
    flyer_length: f64,
}

impl LinearPlateImpact {
    /// Arrival of the front at target point X (L_f ≤ X ≤ L): (X − L_f)/C_e.
    pub fn arrival(&self, x0: f64) -> f64 {
        (x0 - self.flyer_length) / self.wave_speed
    }
}

/// Linear analytic reference (R Eqs 6.1–6.5): for R-P2 C_e = 1, U_p = 0.05, |σ| = 0.05,
/// t_p = 1.0, rear arrival 1.5.
pub fn linear_reference(config: &PlateImpactConfig) -> LinearPlateImpact {
    let c = (config.modulus / config.density).sqrt();
    let up = 0.5 * config.impact_velocity;
    LinearPlateImpact {
        wave_speed: c,
        particle_velocity: up,
        plateau_stress: 0.5 * config.density * config.impact_velocity * c,
        strain: up / c,
        pulse_length: 2.0 * config.flyer_length,
        pulse_duration: 2.0 * config.flyer_length / c,
        rear_arrival: config.target_length / c,
        free_surface_velocity: 2.0 * up,
        flyer_length: config.flyer_length,
    }
}

/// Whether the impact-generated compressive front is a shock or a centred fan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrontKind {
    /// P'' ≤ 0 over the compressed range: Rankine–Hugoniot jump.
    Shock,
    /// P'' > 0 over the compressed range: centred simple (compression) fan.
    Fan,
}

/// State behind the impact front, identical in flyer and target by symmetry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactState {
    /// Shock or fan.
    pub kind: FrontKind,
    /// Stretch λ1 < 1 behind the front.
    pub stretch: f64,
    /// Stress P(λ1) = σ (negative: compression).
    pub stress: f64,
    /// Interface / target particle velocity V/2 (exact by symmetry for any law).
    pub velocity: f64,
    /// Lagrangian speed of the first signal: the shock speed U, or c(1) for a fan.
    pub leading_speed: f64,
    /// Lagrangian speed of the last signal: U for a shock, c(λ1) for a fan.
    pub trailing_speed: f64,
    /// Lagrangian speed of the 50 %-of-plateau stress level: U for a shock, c(λ_½) with
    /// P(λ_½) = P(λ1)/2 for a fan.
    pub half_stress_speed: f64,
}

/// Bisection for f(λ) = 0 on [lo, hi] with f(lo), f(hi) of opposite signs.
fn bisect(mut lo: f64, mut hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    let flo = f(lo);
    assert!(
        flo * f(hi) <= 0.0,
        "plate impact: root not bracketed in [{lo}, {hi}]"
    );
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if (f(mid) > 0.0) == (flo > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// ∫_a^b f by composite 3-point Gauss–Legendre on 20 panels (60 evaluations): round-off accuracy
/// for the smooth c(λ) of the supported laws over a 5 % strain range.
fn integrate(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    const PANELS: usize = 20;
    let nodes = [-(0.6f64).sqrt(), 0.0, (0.6f64).sqrt()];
    let weights = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let h = (b - a) / PANELS as f64;
    (0..PANELS)
        .map(|p| {
            let mid = a + (p as f64 + 0.5) * h;
            nodes
                .iter()
                .zip(&weights)
                .map(|(x, w)| w * f(mid + 0.5 * h * x))
                .sum::<f64>()
                * 0.5
                * h
        })
        .sum()
}

/// Smallest stretch for which the law is still hyperbolic (P' > 0), searched down from 1.
fn hyperbolic_floor(law: &UniaxialLaw) -> f64 {
    let mut lo = 1.0;
    while lo > 0.02 && law.tangent(lo - 0.01) > 0.0 {
        lo -= 0.01;
    }
    lo
}

/// Exact state behind the impact front (problems.md R-P2 "Finite strain matters").
///
/// By symmetry the interface moves at V/2 for any law. Shock (P'' ≤ 0 on [λ1, 1]):
/// Rankine–Hugoniot ρ0 U² = (P1 − P0)/(λ1 − λ0), ⟦v⟧ = −U ⟦λ⟧, solved for V/2 = U (1 − λ1).
/// Fan (P'' > 0): along the right-going simple wave dv = −c dλ, so V/2 = ∫_{λ1}^1 c(λ) dλ.
///
/// # Panics
/// If P'' changes sign between λ1 and 1 (non-convex law: use [`lagrangian_reference`]).
pub fn impact_state(law: &UniaxialLaw, config: &PlateImpactConfig) -> ImpactState {
    let rho = config.density;
    let up = 0.5 * config.impact_velocity;
    let p0 = law.first_piola(1.0);
    let floor = hyperbolic_floor(law) + 1e-9;
    let curv1 = law.curvature(1.0);
    let kind = if curv1 > 0.0 {
        FrontKind::Fan
    } else {
        FrontKind::Shock
    };
    let stretch = match kind {
        FrontKind::Shock => bisect(floor, 1.0 - 1e-15, |l| {
            ((p0 - law.first_piola(l)) * (1.0 - l) / rho).sqrt() - up
        }),
        FrontKind::Fan => bisect(floor, 1.0, |l| {
            integrate(l, 1.0, |s| law.wave_speed(s, rho)) - up
        }),
    };
    for k in 0..=16 {
        let l = stretch + (1.0 - stretch) * k as f64 / 16.0;
        let c = law.curvature(l);
        assert!(
            c == 0.0 || (c > 0.0) == (kind == FrontKind::Fan),
            "plate impact: P'' changes sign in [λ1, 1]; no exact solution for this law"
        );
    }
    let stress = law.first_piola(stretch);
    let half = bisect(stretch, 1.0, |l| {
        law.first_piola(l) - p0 - 0.5 * (stress - p0)
    });
    let (leading, trailing, half_speed) = match kind {
        FrontKind::Shock => {
            let u = ((p0 - stress) / (rho * (1.0 - stretch))).sqrt();
            (u, u, u)
        }
        FrontKind::Fan => (
            law.wave_speed(1.0, rho),
            law.wave_speed(stretch, rho),
            law.wave_speed(half, rho),
        ),
    };
    ImpactState {
        kind,
        stretch,
        stress,
        velocity: up,
        leading_speed: leading,
        trailing_speed: trailing,
        half_stress_speed: half_speed,
    }
}

/// Exact finite-strain values at a gauge where they exist in closed form.
///
/// * Arrival (50 % of the plateau on the rise): (X − L_f)/U for a shock, (X − L_f)/c(λ_½) for a
///   fan (centred at X = L_f, t = 0). At the free rear face this is the velocity rise, exact
///   for a shock only (a fan reflecting from the free face interacts with itself).
/// * Fall (50 % on the release): only when the front is a shock. The shock reaches the flyer's
///   free face at t_r = L_f/U and reflects as a centred release fan (P'' < 0 ⇒ fan on release);
///   the 50 % level travels at c(λ_½), so t_fall = t_r + X/c(λ_½), valid while that
///   characteristic has neither caught the shock nor met the wave reflected from the rear face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactGauge {
    /// Gauge position X.
    pub x0: f64,
    /// Arrival time, if exact.
    pub arrival: Option<f64>,
    /// Time of the 50 % crossing on the fall of |σ|, if exact.
    pub fall: Option<f64>,
}

impl ExactGauge {
    /// Pulse duration fall − arrival, if both are exact.
    pub fn duration(&self) -> Option<f64> {
        Some(self.fall? - self.arrival?)
    }
}

/// Exact values at target gauge X (see [`ExactGauge`]); `None` fields where no closed form
/// applies. Gauges in the flyer (X < L_f) get no exact values.
pub fn exact_gauge(law: &UniaxialLaw, config: &PlateImpactConfig, x0: f64) -> ExactGauge {
    let s = impact_state(law, config);
    let lf = config.flyer_length;
    let total = config.total_length();
    let mut out = ExactGauge {
        x0,
        arrival: None,
        fall: None,
    };
    if x0 < lf || x0 > total {
        return out;
    }
    let at_rear = (x0 - total).abs() < 1e-12;
    // Earliest time anything reflected from the rear face can reach X.
    let c_fast = law
        .wave_speed(s.stretch, config.density)
        .max(law.wave_speed(1.0, config.density));
    let rear_echo = (total - lf) / s.leading_speed + (total - x0) / c_fast;
    let arrival = (x0 - lf) / s.half_stress_speed;
    if s.kind == FrontKind::Shock || !at_rear {
        out.arrival = Some(arrival);
    }
    if s.kind == FrontKind::Shock && !at_rear {
        let p0 = law.first_piola(1.0);
        let half = bisect(s.stretch, 1.0, |l| {
            law.first_piola(l) - p0 - 0.5 * (s.stress - p0)
        });
        let fall = lf / s.leading_speed + x0 / law.wave_speed(half, config.density);
        if fall > arrival && fall < rear_echo {
            out.fall = Some(fall);
        }
    }
    out
}

/// Time history at one gauge of the reference computation.
#[derive(Debug, Clone, PartialEq)]
pub struct GaugeHistory {
    /// Gauge position X (reference coordinates).
    pub x0: f64,
    /// Cauchy = first Piola–Kirchhoff stress σ(X, t_k) (tension positive; elastic part, without
    /// the artificial viscosity), linear in X between cell centres, 0 at the free faces.
    pub stress: Vec<f64>,
    /// Particle velocity v(X, t_k), linear in X between nodes.
    pub velocity: Vec<f64>,
}

/// Fields along the bar at one time (cell centres).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// Time of the profile.
    pub time: f64,
    /// Reference positions X of the cell centres.
    pub x0: Vec<f64>,
    /// Current positions x of the cell centres.
    pub x: Vec<f64>,
    /// Stress σ = P per cell.
    pub stress: Vec<f64>,
    /// Velocity per cell (mean of its two nodes).
    pub velocity: Vec<f64>,
}

/// Result of [`lagrangian_reference`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceSolution {
    /// Law that was integrated.
    pub law: UniaxialLaw,
    /// Cells used.
    pub n_cells: usize,
    /// Sample times t_k (every time step, starting at t = 0).
    pub times: Vec<f64>,
    /// One history per requested gauge, in config order.
    pub gauges: Vec<GaugeHistory>,
    /// Stress/velocity profile at `config.profile_time` (Fig 6.5); empty with NaN time if the
    /// profile time lies after `config.end_time`.
    pub profile: Profile,
}

impl ReferenceSolution {
    /// History of the gauge at X = `x0` (exact match within 1e-12).
    pub fn gauge(&self, x0: f64) -> Option<&GaugeHistory> {
        self.gauges.iter().find(|g| (g.x0 - x0).abs() < 1e-12)
    }

    /// [`pulse_metrics`] of |σ| at gauge X = `x0`.
    pub fn stress_metrics(&self, x0: f64) -> Option<PulseMetrics> {
        pulse_metrics(&self.times, &self.gauge(x0)?.stress)
    }

    /// [`pulse_metrics`] of |v| at gauge X = `x0` (use at the free rear face, where σ ≡ 0).
    pub fn velocity_metrics(&self, x0: f64) -> Option<PulseMetrics> {
        pulse_metrics(&self.times, &self.gauge(x0)?.velocity)
    }
}

/// Converged 1D Lagrangian reference computation of the plate impact for any law P(λ).
///
/// Scheme: second-order Godunov finite volumes in the Lagrangian coordinate X. Cells carry the
/// conserved stretch λ and velocity v; faces get (v*, P*) from the acoustic (linearised)
/// Riemann solver with cell impedances Z = ρ0 c(λ):
/// v* = (Z_L v_L + Z_R v_R + P_R − P_L)/(Z_L + Z_R), P* = P_L + Z_L (v* − v_L),
/// and λ_j += Δt (v*_{j+½} − v*_{j−½})/ΔX, v_j += Δt (P*_{j+½} − P*_{j−½})/(ρ0 ΔX).
/// Second order comes from MUSCL–Hancock: monotonised-central limited slopes of (P, v), a half
/// step predictor with ∂P/∂t = ρ0 c² ∂v/∂X, ∂v/∂t = ∂P/∂X / ρ0, and face extrapolation. Free faces
/// impose P* = 0 through the outgoing characteristic (mirror ghost cells for the slopes); the
/// bonded interface is the face between the last flyer cell and the first target cell, so the
/// impact is an exact Riemann problem at t = 0. The face velocities also move the faces, so the
/// current geometry is exactly consistent with λ.
///
/// Why this scheme: the Lagrangian system has wave speeds ±c(λ), never zero, so the acoustic
/// solver needs no entropy fix and captures both compressive shocks (rate law) and expansive
/// shocks (St Venant–Kirchhoff release) as monotone 2–3 cell profiles without a tuned
/// viscosity; a staggered leapfrog with artificial viscosity was tried first and gave
/// dispersive trailing ringing whose skew delays the 50 % crossing of a weak shock by about one
/// cell (first-order convergence of arrival times). Fans are second order.
///
/// Cost: one stress and one square root per cell and step, Δt = 0.8 ΔX/c_max; O(n_cells² ·
/// end_time). About 0.3–0.5 s for the default 8000 cells in an optimised build.
///
/// # Panics
/// If the configuration is degenerate (fewer than 4 cells, non-positive lengths, density or end
/// time) or the stretch leaves the hyperbolic range (P' ≤ 0).
pub fn lagrangian_reference(law: &UniaxialLaw, config: &PlateImpactConfig) -> ReferenceSolution {
    match *law {
        UniaxialLaw::Linear { modulus } => {
            run_godunov(law, config, move |l| (modulus * (l - 1.0), modulus))
        }
        UniaxialLaw::LogarithmicRate { modulus } => {
            run_godunov(law, config, move |l: f64| (modulus * l.ln(), modulus / l))
        }
        UniaxialLaw::StVenantKirchhoff { modulus } => run_godunov(law, config, move |l| {
            (
                0.5 * modulus * l * (l * l - 1.0),
                0.5 * modulus * (3.0 * l * l - 1.0),
            )
        }),
    }
}

/// Minimum without NaN handling (compiles to a single instruction).
#[inline(always)]
fn fmin(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// Monotonised-central limited slope from the backward and forward differences: zero when they
/// disagree in sign or one of them is zero.
#[inline(always)]
fn mc_slope(back: f64, fwd: f64) -> f64 {
    let m = fmin(
        fmin(2.0 * back.abs(), 2.0 * fwd.abs()),
        0.5 * (back + fwd).abs(),
    );
    if back * fwd > 0.0 {
        m.copysign(back)
    } else {
        0.0
    }
}

/// Where a gauge reads the cell-centred fields: between two cell centres, or between a free face
/// (left or right) and the adjacent cell centre. `w` is the weight of the second point.
#[derive(Debug, Clone, Copy)]
enum Probe {
    Cells { j: usize, w: f64 },
    LeftFace { w: f64 },
    RightFace { w: f64 },
}

fn probe(x0: f64, dx: f64, n: usize) -> Probe {
    let total = n as f64 * dx;
    let x0 = x0.clamp(0.0, total);
    if x0 <= 0.5 * dx {
        // Face at 0 (weight 1 − w), centre of cell 0 (weight w).
        Probe::LeftFace { w: x0 / (0.5 * dx) }
    } else if x0 >= total - 0.5 * dx {
        // Centre of cell n − 1 (weight 1 − w), face at L (weight w).
        Probe::RightFace {
            w: (x0 - (total - 0.5 * dx)) / (0.5 * dx),
        }
    } else {
        let s = x0 / dx - 0.5;
        let j = (s.floor() as usize).min(n - 2);
        Probe::Cells { j, w: s - j as f64 }
    }
}

/// State of the finite-volume computation (structure of arrays; cells 0..n, faces 0..=n).
struct Fv {
    n: usize,
    dx: f64,
    rho: f64,
    stretch: Vec<f64>,
    vel: Vec<f64>,
    /// Face positions x_{j−½}, j = 0..=n.
    face_x: Vec<f64>,
    p: Vec<f64>,
    z: Vec<f64>,
    dp: Vec<f64>,
    dv: Vec<f64>,
    /// Predicted (P, v) on the left (minus) and right (plus) face of each cell.
    p_minus: Vec<f64>,
    v_minus: Vec<f64>,
    p_plus: Vec<f64>,
    v_plus: Vec<f64>,
    flux_v: Vec<f64>,
    flux_p: Vec<f64>,
}

impl Fv {
    /// Evaluates P and Z in every cell; returns the largest wave speed.
    fn constitutive(&mut self, stress: &impl Fn(f64) -> (f64, f64)) -> f64 {
        let rho = self.rho;
        let mut max_tangent: f64 = 0.0;
        let mut min_tangent = f64::INFINITY;
        for ((l, p), z) in self.stretch.iter().zip(&mut self.p).zip(&mut self.z) {
            let (pv, t) = stress(*l);
            *p = pv;
            *z = (rho * t).sqrt();
            max_tangent = if t > max_tangent { t } else { max_tangent };
            min_tangent = fmin(min_tangent, t);
        }
        assert!(
            min_tangent > 0.0,
            "plate impact: P'(λ) ≤ 0 somewhere (law not hyperbolic at this strain)"
        );
        (max_tangent / rho).sqrt()
    }

    /// Limited slopes of P and v, with mirror ghosts at the free faces (P odd, v even).
    fn slopes(&mut self) {
        let n = self.n;
        let (p, v) = (&self.p[..n], &self.vel[..n]);
        let (dp, dv) = (&mut self.dp[..n], &mut self.dv[..n]);
        for j in 1..n - 1 {
            dp[j] = mc_slope(p[j] - p[j - 1], p[j + 1] - p[j]);
            dv[j] = mc_slope(v[j] - v[j - 1], v[j + 1] - v[j]);
        }
        dp[0] = mc_slope(2.0 * p[0], p[1] - p[0]);
        dv[0] = mc_slope(0.0, v[1] - v[0]);
        dp[n - 1] = mc_slope(p[n - 1] - p[n - 2], -2.0 * p[n - 1]);
        dv[n - 1] = mc_slope(v[n - 1] - v[n - 2], 0.0);
    }

    /// Velocity of the left (0) or right (L) free face from the reconstructed boundary cell at
    /// the current time (outgoing characteristic with P* = 0).
    fn free_face_velocity(&self, right: bool) -> f64 {
        if right {
            let j = self.n - 1;
            let (p, v) = (self.p[j] + 0.5 * self.dp[j], self.vel[j] + 0.5 * self.dv[j]);
            v - p / self.z[j]
        } else {
            let (p, v) = (self.p[0] - 0.5 * self.dp[0], self.vel[0] - 0.5 * self.dv[0]);
            v + p / self.z[0]
        }
    }

    /// (σ, v) read by a probe at the current time (requires up-to-date P, Z and slopes).
    fn read(&self, probe: Probe) -> (f64, f64) {
        match probe {
            Probe::Cells { j, w } => (
                (1.0 - w) * self.p[j] + w * self.p[j + 1],
                (1.0 - w) * self.vel[j] + w * self.vel[j + 1],
            ),
            Probe::LeftFace { w } => (
                w * self.p[0],
                (1.0 - w) * self.free_face_velocity(false) + w * self.vel[0],
            ),
            Probe::RightFace { w } => {
                let j = self.n - 1;
                (
                    (1.0 - w) * self.p[j],
                    (1.0 - w) * self.vel[j] + w * self.free_face_velocity(true),
                )
            }
        }
    }

    /// One MUSCL–Hancock step of length dt (P, Z and slopes must be current).
    fn advance(&mut self, dt: f64) {
        let n = self.n;
        let (dx, rho) = (self.dx, self.rho);
        let half = 0.5 * dt / dx;
        let inv_rho = 1.0 / rho;
        // Half-step predictor and face extrapolation, cell by cell.
        for j in 0..n {
            let (z, dp, dv) = (self.z[j], self.dp[j], self.dv[j]);
            let p = self.p[j] + half * z * z * inv_rho * dv;
            let v = self.vel[j] + half * dp * inv_rho;
            self.p_minus[j] = p - 0.5 * dp;
            self.p_plus[j] = p + 0.5 * dp;
            self.v_minus[j] = v - 0.5 * dv;
            self.v_plus[j] = v + 0.5 * dv;
        }
        // Left free face: incoming characteristic P + Z v from cell 0, P* = 0.
        self.flux_p[0] = 0.0;
        self.flux_v[0] = self.v_minus[0] + self.p_minus[0] / self.z[0];
        // Interior faces: acoustic Riemann solver.
        for j in 1..n {
            let (zl, zr) = (self.z[j - 1], self.z[j]);
            let (pl, vl) = (self.p_plus[j - 1], self.v_plus[j - 1]);
            let (pr, vr) = (self.p_minus[j], self.v_minus[j]);
            let vs = (zl * vl + zr * vr + pr - pl) / (zl + zr);
            self.flux_v[j] = vs;
            self.flux_p[j] = pl + zl * (vs - vl);
        }
        // Right free face: outgoing characteristic P − Z v from cell n − 1, P* = 0.
        self.flux_p[n] = 0.0;
        self.flux_v[n] = self.v_plus[n - 1] - self.p_plus[n - 1] / self.z[n - 1];

        let a = dt / dx;
        let b = a * inv_rho;
        for j in 0..n {
            self.stretch[j] += a * (self.flux_v[j + 1] - self.flux_v[j]);
            self.vel[j] += b * (self.flux_p[j + 1] - self.flux_p[j]);
        }
        for (x, v) in self.face_x.iter_mut().zip(&self.flux_v) {
            *x += dt * v;
        }
    }
}

fn run_godunov(
    law: &UniaxialLaw,
    config: &PlateImpactConfig,
    stress: impl Fn(f64) -> (f64, f64),
) -> ReferenceSolution {
    let n = config.n_cells;
    let total = config.total_length();
    assert!(n >= 4, "plate impact: need at least 4 cells");
    assert!(
        config.flyer_length > 0.0 && config.target_length > 0.0 && config.density > 0.0,
        "plate impact: lengths and density must be > 0"
    );
    assert!(config.end_time > 0.0, "plate impact: end time must be > 0");
    let dx = total / n as f64;
    // Number of flyer cells; the interface is the face between cells n_f − 1 and n_f.
    let n_f = ((config.flyer_length / dx).round() as usize).clamp(1, n - 1);

    let mut fv = Fv {
        n,
        dx,
        rho: config.density,
        stretch: vec![1.0; n],
        vel: (0..n)
            .map(|j| if j < n_f { config.impact_velocity } else { 0.0 })
            .collect(),
        face_x: (0..=n).map(|j| j as f64 * dx).collect(),
        p: vec![0.0; n],
        z: vec![0.0; n],
        dp: vec![0.0; n],
        dv: vec![0.0; n],
        p_minus: vec![0.0; n],
        v_minus: vec![0.0; n],
        p_plus: vec![0.0; n],
        v_plus: vec![0.0; n],
        flux_v: vec![0.0; n + 1],
        flux_p: vec![0.0; n + 1],
    };

    let probes: Vec<Probe> = config.gauges.iter().map(|&g| probe(g, dx, n)).collect();
    let mut times = Vec::new();
    let mut gauges: Vec<GaugeHistory> = config
        .gauges
        .iter()
        .map(|&x0| GaugeHistory {
            x0,
            stress: Vec::new(),
            velocity: Vec::new(),
        })
        .collect();
    let mut profile: Option<Profile> = None;
    let profile_time = config.profile_time;
    let mut t = 0.0;

    loop {
        let c_max = fv.constitutive(&stress);
        fv.slopes();
        times.push(t);
        for (g, &pr) in gauges.iter_mut().zip(&probes) {
            let (s, v) = fv.read(pr);
            g.stress.push(s);
            g.velocity.push(v);
        }
        if profile.is_none() && (t - profile_time).abs() <= 1e-12 * profile_time.max(1.0) {
            profile = Some(Profile {
                time: t,
                x0: (0..n).map(|j| (j as f64 + 0.5) * dx).collect(),
                x: (0..n)
                    .map(|j| 0.5 * (fv.face_x[j] + fv.face_x[j + 1]))
                    .collect(),
                stress: fv.p.clone(),
                velocity: fv.vel.clone(),
            });
        }
        if t >= config.end_time * (1.0 - 1e-14) {
            break;
        }
        let mut dt = (COURANT * dx / c_max).min(config.end_time - t);
        if profile.is_none() && t < profile_time && t + dt > profile_time {
            dt = profile_time - t;
        }
        fv.advance(dt);
        t += dt;
    }

    let profile = profile.unwrap_or_else(|| Profile {
        time: f64::NAN,
        x0: Vec::new(),
        x: Vec::new(),
        stress: Vec::new(),
        velocity: Vec::new(),
    });
    ReferenceSolution {
        law: *law,
        n_cells: n,
        times,
        gauges,
        profile,
    }
}

/// Pulse measurements on a sampled gauge history (problems.md R-P2 Pass, §0 "plateau averages").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PulseMetrics {
    /// Mean |signal| over the middle 50 % of the interval between the rise and fall crossings
    /// (between the rise and the end of the record when no fall is recorded).
    pub plateau: f64,
    /// Time of the 50 %-of-plateau crossing on the rise (linear interpolation).
    pub arrival: f64,
    /// Time of the 50 %-of-plateau crossing on the fall; NaN when the record ends first.
    pub fall: f64,
    /// fall − arrival; NaN when no fall is recorded.
    pub duration: f64,
}

/// Plateau, arrival and duration of a single pulse in |values| (stress or velocity history).
///
/// Fixed-point iteration started from the median of the samples above a quarter of the peak:
/// threshold = ½ plateau; rise = first upward crossing of the threshold; fall = first later
/// downward crossing after which the signal stays below the threshold for at least 5 samples
/// and 2 % of the record (or to the end); plateau = time-weighted mean of |value| over the
/// middle 50 % of [rise, fall]. Overshoot spikes and ringing at sharp fronts therefore neither
/// set the threshold nor end the pulse early. Returns `None` if the
/// signal is empty, never non-zero, or has no rise.
pub fn pulse_metrics(times: &[f64], values: &[f64]) -> Option<PulseMetrics> {
    assert_eq!(times.len(), values.len(), "one value per time");
    if times.len() < 2 {
        return None;
    }
    let a: Vec<f64> = values.iter().map(|v| v.abs()).collect();
    let peak = a
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    if peak <= 0.0 {
        return None;
    }
    // Start from a robust level: the median of the samples above a quarter of the peak.
    // A single overshoot spike (Gibbs ringing at a sharp front) then cannot set the threshold.
    let mut strong: Vec<f64> = a
        .iter()
        .copied()
        .filter(|x| x.is_finite() && *x >= 0.25 * peak)
        .collect();
    strong.sort_by(f64::total_cmp);
    let mut level = strong[strong.len() / 2];
    // A fall only counts if the signal then stays below the threshold for a while: at least
    // 5 samples and 2 % of the record, so ringing dips inside the pulse are not taken for it.
    let hold_time = 0.02 * (times[times.len() - 1] - times[0]);
    let mut result = None;
    for _ in 0..50 {
        let thr = 0.5 * level;
        let rise_idx = a.iter().position(|&x| x >= thr)?;
        let arrival = if rise_idx == 0 {
            times[0]
        } else {
            crossing(times, &a, rise_idx - 1, thr)
        };
        let mut fall = f64::NAN;
        let mut k = rise_idx;
        while k + 1 < a.len() {
            if a[k] >= thr && a[k + 1] < thr {
                let below = a[k + 1..].iter().take_while(|&&x| x < thr).count();
                let to_end = k + 1 + below == a.len();
                let held = times[k + below] - times[k + 1];
                if to_end || (below >= 5 && held >= hold_time) {
                    fall = crossing(times, &a, k, thr);
                    break;
                }
            }
            k += 1;
        }
        let end = if fall.is_nan() { *times.last()? } else { fall };
        let plateau = window_mean(
            times,
            &a,
            arrival + 0.25 * (end - arrival),
            arrival + 0.75 * (end - arrival),
        )
        .unwrap_or(level);
        let converged = (plateau - level).abs() <= 1e-13 * level;
        result = Some(PulseMetrics {
            plateau,
            arrival,
            fall,
            duration: fall - arrival,
        });
        level = plateau;
        if converged {
            break;
        }
    }
    result
}

/// Time of the crossing of `thr` between samples k and k + 1 (linear interpolation).
fn crossing(times: &[f64], a: &[f64], k: usize, thr: f64) -> f64 {
    let (y0, y1) = (a[k], a[k + 1]);
    if y1 == y0 {
        return times[k + 1];
    }
    times[k] + (times[k + 1] - times[k]) * (thr - y0) / (y1 - y0)
}

/// Time average of the piecewise-linear signal over [t0, t1] (trapezoids, partial end intervals).
fn window_mean(times: &[f64], a: &[f64], t0: f64, t1: f64) -> Option<f64> {
    if t1 <= t0 {
        return None;
    }
    let interp = |k: usize, t: f64| {
        let (ta, tb) = (times[k], times[k + 1]);
        if tb == ta {
            a[k]
        } else {
            a[k] + (a[k + 1] - a[k]) * (t - ta) / (tb - ta)
        }
    };
    let mut integral = 0.0;
    for k in 0..times.len() - 1 {
        let lo = times[k].max(t0);
        let hi = times[k + 1].min(t1);
        if hi > lo {
            integral += 0.5 * (interp(k, lo) + interp(k, hi)) * (hi - lo);
        }
    }
    Some(integral / (t1 - t0))
}

/// Target-middle gauge X = L_f + L_t/2 (1.25 for R-P2).
pub fn mid_gauge(config: &PlateImpactConfig) -> f64 {
    config.flyer_length + 0.5 * config.target_length
}

/// Target rear (free) face X = L_f + L_t (2.0 for R-P2).
pub fn rear_gauge(config: &PlateImpactConfig) -> f64 {
    config.total_length()
}

/// The comparison quantities of R-P2 for one law, measured with [`pulse_metrics`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlateImpactMetrics {
    /// |σ| plateau at the mid gauge.
    pub plateau_stress: f64,
    /// Particle-velocity plateau at the mid gauge.
    pub plateau_velocity: f64,
    /// 50 % rise of |σ| at the mid gauge.
    pub arrival_mid: f64,
    /// Pulse duration of |σ| at the mid gauge (50 % rise to 50 % fall).
    pub duration_mid: f64,
    /// 50 % rise of the free-surface velocity at the rear face (σ ≡ 0 there).
    pub arrival_rear: f64,
    /// Free-surface velocity plateau at the rear face.
    pub free_surface_velocity: f64,
}

impl PlateImpactMetrics {
    /// (name, value) pairs in CSV order.
    pub fn named(&self) -> [(&'static str, f64); 6] {
        [
            ("plateau_stress_mid", self.plateau_stress),
            ("plateau_velocity_mid", self.plateau_velocity),
            ("arrival_mid", self.arrival_mid),
            ("duration_mid", self.duration_mid),
            ("arrival_rear", self.arrival_rear),
            ("free_surface_velocity_rear", self.free_surface_velocity),
        ]
    }
}

/// Applies [`pulse_metrics`] to a reference computation at the mid and rear gauges (both must
/// be among `config.gauges`); NaN where a gauge is missing or shows no pulse.
pub fn measure(solution: &ReferenceSolution, config: &PlateImpactConfig) -> PlateImpactMetrics {
    let nan = PulseMetrics {
        plateau: f64::NAN,
        arrival: f64::NAN,
        fall: f64::NAN,
        duration: f64::NAN,
    };
    let mid_s = solution.stress_metrics(mid_gauge(config)).unwrap_or(nan);
    let mid_v = solution.velocity_metrics(mid_gauge(config)).unwrap_or(nan);
    let rear_v = solution.velocity_metrics(rear_gauge(config)).unwrap_or(nan);
    PlateImpactMetrics {
        plateau_stress: mid_s.plateau,
        plateau_velocity: mid_v.plateau,
        arrival_mid: mid_s.arrival,
        duration_mid: mid_s.duration,
        arrival_rear: rear_v.arrival,
        free_surface_velocity: rear_v.plateau,
    }
}

/// Exact counterparts of [`PlateImpactMetrics`] where a closed form exists (NaN otherwise):
/// plateau |P(λ1)|, V/2, arrival/duration from [`exact_gauge`], and the free-surface velocity
/// after the front has reflected from the rear face, λ → 1:
/// * shock front: the reflection is a centred fan, v_fs = V/2 + ∫_{λ1}^1 c(λ) dλ (slightly
///   below V for the rate law, 0.0999986);
/// * fan front: the right-going Riemann invariant v − ∫_1^λ c carried from the plateau into the
///   free face gives v_fs = V exactly (the reflected expansion steepens only away from the face).
pub fn exact_metrics(law: &UniaxialLaw, config: &PlateImpactConfig) -> PlateImpactMetrics {
    let s = impact_state(law, config);
    let mid = exact_gauge(law, config, mid_gauge(config));
    let rear = exact_gauge(law, config, rear_gauge(config));
    PlateImpactMetrics {
        plateau_stress: s.stress.abs(),
        plateau_velocity: s.velocity,
        arrival_mid: mid.arrival.unwrap_or(f64::NAN),
        duration_mid: mid.duration().unwrap_or(f64::NAN),
        arrival_rear: rear.arrival.unwrap_or(f64::NAN),
        free_surface_velocity: match s.kind {
            FrontKind::Shock => {
                s.velocity + integrate(s.stretch, 1.0, |l| law.wave_speed(l, config.density))
            }
            FrontKind::Fan => 2.0 * s.velocity,
        },
    }
}

/// One row of `reference-data/R-P2/finite_strain.csv` (`law,quantity,method,value_nondim`).
#[derive(Debug, Clone, PartialEq)]
pub struct FiniteStrainRow {
    /// [`UniaxialLaw::name`].
    pub law: String,
    /// Quantity name (see [`PlateImpactMetrics::named`], plus `impact_stretch`,
    /// `front_speed_leading`, `front_speed_trailing`).
    pub quantity: String,
    /// `exact` or `fv_n<cells>`.
    pub method: String,
    /// Value (non-dimensional units of R-P2).
    pub value: f64,
}

/// The laws tabulated in `finite_strain.csv`, with modulus M = `config.modulus`.
pub fn tabulated_laws(config: &PlateImpactConfig) -> [UniaxialLaw; 3] {
    let m = config.modulus;
    [
        UniaxialLaw::Linear { modulus: m },
        UniaxialLaw::LogarithmicRate { modulus: m },
        UniaxialLaw::StVenantKirchhoff { modulus: m },
    ]
}

/// Exact rows plus measured rows of [`lagrangian_reference`] at each resolution, for every law
/// of [`tabulated_laws`] (the content of `finite_strain.csv`).
pub fn finite_strain_rows(
    config: &PlateImpactConfig,
    resolutions: &[usize],
) -> Vec<FiniteStrainRow> {
    let mut rows = Vec::new();
    for law in tabulated_laws(config) {
        let mut push = |quantity: &str, method: &str, value: f64| {
            if value.is_finite() {
                rows.push(FiniteStrainRow {
                    law: law.name().to_string(),
                    quantity: quantity.to_string(),
                    method: method.to_string(),
                    value,
                });
            }
        };
        let s = impact_state(&law, config);
        push("impact_stretch", "exact", s.stretch);
        push("front_speed_leading", "exact", s.leading_speed);
        push("front_speed_trailing", "exact", s.trailing_speed);
        for (q, v) in exact_metrics(&law, config).named() {
            push(q, "exact", v);
        }
        for &n in resolutions {
            let cfg = config.with_cells(n);
            let sol = lagrangian_reference(&law, &cfg);
            let method = format!("fv_n{n}");
            for (q, v) in measure(&sol, &cfg).named() {
                push(q, &method, v);
            }
        }
    }
    rows
}

/// CSV text of [`finite_strain_rows`] (header `law,quantity,method,value_nondim`, 10 significant
/// digits).
pub fn finite_strain_csv(rows: &[FiniteStrainRow]) -> String {
    let mut out = String::from("law,quantity,method,value_nondim\n");
    for r in rows {
        out.push_str(&format!(
            "{},{},{},{:.9e}\n",
            r.law, r.quantity, r.method, r.value
        ));
    }
    out
}

/// CSV text of the linear analytic values (header `quantity,value_nondim,provenance`).
pub fn linear_csv(config: &PlateImpactConfig) -> String {
    let l = linear_reference(config);
    let rows = [
        ("wave_speed", l.wave_speed, "R Eq 6.1 [T]"),
        (
            "particle_velocity",
            l.particle_velocity,
            "U_p = V/2 (R 6.1.2) [T]",
        ),
        (
            "plateau_stress",
            l.plateau_stress,
            "R Eq 6.4; compressive [T]",
        ),
        ("uniaxial_strain", l.strain, "sigma/M = U_p/C_e [A]"),
        ("pulse_length", l.pulse_length, "2 L_f (R 6.1.2) [T]"),
        ("pulse_duration", l.pulse_duration, "R Eq 6.5 [T]"),
        ("arrival_mid", l.arrival(mid_gauge(config)), "X = 1.25 [A]"),
        ("arrival_rear", l.rear_arrival, "L_t/C_e (R 6.1.2) [T]"),
        (
            "free_surface_velocity_rear",
            l.free_surface_velocity,
            "2 U_p [A]",
        ),
    ];
    let mut out = String::from("quantity,value_nondim,provenance\n");
    for (q, v, p) in rows {
        out.push_str(&format!("{q},{v:.9e},{p}\n"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::reference_data_dir;
    use std::collections::HashMap;
    use std::sync::OnceLock;

    const RESOLUTIONS: [usize; 2] = [4000, 8000];

    fn cfg() -> PlateImpactConfig {
        PlateImpactConfig::default()
    }

    fn log_law() -> UniaxialLaw {
        UniaxialLaw::LogarithmicRate { modulus: 1.0 }
    }

    fn svk_law() -> UniaxialLaw {
        UniaxialLaw::StVenantKirchhoff { modulus: 1.0 }
    }

    /// finite_strain_rows at the stored resolutions, computed once for all tests.
    fn rows() -> &'static Vec<FiniteStrainRow> {
        static ROWS: OnceLock<Vec<FiniteStrainRow>> = OnceLock::new();
        ROWS.get_or_init(|| finite_strain_rows(&cfg(), &RESOLUTIONS))
    }

    fn value(law: &str, quantity: &str, method: &str) -> f64 {
        rows()
            .iter()
            .find(|r| r.law == law && r.quantity == quantity && r.method == method)
            .unwrap_or_else(|| panic!("missing {law} {quantity} {method}"))
            .value
    }

    #[test]
    fn linear_reference_matches_thesis() {
        let l = linear_reference(&cfg());
        assert_eq!(l.wave_speed, 1.0);
        assert!((l.particle_velocity - 0.05).abs() < 1e-15);
        assert!((l.plateau_stress - 0.05).abs() < 1e-15);
        assert!((l.strain - 0.05).abs() < 1e-15);
        assert!((l.pulse_length - 1.0).abs() < 1e-15);
        assert!((l.pulse_duration - 1.0).abs() < 1e-15);
        assert!((l.rear_arrival - 1.5).abs() < 1e-15);
        assert!((l.arrival(1.25) - 0.75).abs() < 1e-15);
        assert!((l.free_surface_velocity - 0.1).abs() < 1e-15);
    }

    #[test]
    fn law_derivatives_are_consistent() {
        for law in tabulated_laws(&cfg()) {
            assert!(law.first_piola(1.0).abs() < 1e-15);
            assert!((law.tangent(1.0) - 1.0).abs() < 1e-15);
            for &l in &[0.9, 0.95, 1.0, 1.05] {
                let h = 1e-5;
                let d1 = (law.first_piola(l + h) - law.first_piola(l - h)) / (2.0 * h);
                let d2 = (law.tangent(l + h) - law.tangent(l - h)) / (2.0 * h);
                assert!((d1 - law.tangent(l)).abs() < 1e-8, "{law} P' at {l}");
                assert!((d2 - law.curvature(l)).abs() < 1e-8, "{law} P'' at {l}");
            }
        }
        // Rate law: integrating σ̇ = M λ̇/λ along a compression path gives M ln λ.
        let (mut sigma, steps) = (0.0, 10_000);
        for k in 0..steps {
            let (a, b) = (
                1.0 - 0.05 * k as f64 / steps as f64,
                1.0 - 0.05 * (k + 1) as f64 / steps as f64,
            );
            sigma += (b - a) / (0.5 * (a + b));
        }
        assert!((sigma - log_law().first_piola(0.95)).abs() < 1e-9);
        // St Venant–Kirchhoff: P = λ S with S = M E.
        let l: f64 = 0.93;
        assert!((svk_law().first_piola(l) - l * 0.5 * (l * l - 1.0)).abs() < 1e-15);
    }

    #[test]
    fn impact_states_match_problem_md() {
        let c = cfg();
        let lin = impact_state(&UniaxialLaw::Linear { modulus: 1.0 }, &c);
        assert!((lin.stress + 0.05).abs() < 1e-12 && (lin.stretch - 0.95).abs() < 1e-12);

        let log = impact_state(&log_law(), &c);
        assert_eq!(log.kind, FrontKind::Shock);
        assert!((log.stress.abs() - 0.0506).abs() < 5e-5, "{log:?}");
        // Rankine–Hugoniot: ρ0 U² (λ1 − 1) = P1 − P0 and V/2 = −U (λ1 − 1).
        let u = log.leading_speed;
        assert!((u * u * (log.stretch - 1.0) - log.stress).abs() < 1e-14);
        assert!((u * (1.0 - log.stretch) - 0.05).abs() < 1e-14);
        assert!(u > 1.0, "compression speeds the rate-law wave up");

        let svk = impact_state(&svk_law(), &c);
        assert_eq!(svk.kind, FrontKind::Fan, "SVK is a compression fan");
        assert!((svk.stress.abs() - 0.0481).abs() < 5e-5, "{svk:?}");
        assert!(svk.trailing_speed < svk.half_stress_speed && svk.half_stress_speed < 1.0);
        // Riemann invariant across the fan.
        let integral = integrate(svk.stretch, 1.0, |l| svk_law().wave_speed(l, 1.0));
        assert!((integral - 0.05).abs() < 1e-13);
    }

    #[test]
    fn exact_gauges_match_problem_md() {
        let c = cfg();
        let mid = exact_gauge(&log_law(), &c, 1.25);
        let rear = exact_gauge(&log_law(), &c, 2.0);
        // problems.md: mid/back arrivals 0.7405/1.4813, pulse 0.988 (rounded, see source.md).
        assert!((mid.arrival.unwrap() - 0.7405).abs() < 2e-4);
        assert!((rear.arrival.unwrap() - 1.4813).abs() < 2e-4);
        assert!((mid.duration().unwrap() - 0.988).abs() < 1e-3);
        assert!(rear.fall.is_none());
        let svk_mid = exact_gauge(&svk_law(), &c, 1.25);
        assert!(svk_mid.arrival.is_some() && svk_mid.fall.is_none());
        assert!(exact_gauge(&svk_law(), &c, 2.0).arrival.is_none());
        assert!(exact_gauge(&log_law(), &c, 0.25).arrival.is_none());
    }

    #[test]
    fn reference_converges_to_the_exact_solution() {
        for law in ["log_rate", "svk"] {
            for q in [
                "plateau_stress_mid",
                "plateau_velocity_mid",
                "arrival_mid",
                "duration_mid",
                "arrival_rear",
            ] {
                let coarse = value(law, q, "fv_n4000");
                let fine = value(law, q, "fv_n8000");
                // Halving the cell size changes nothing by more than 1e-4.
                assert!((fine - coarse).abs() < 1e-4, "{law} {q}: {coarse} → {fine}");
                if let Some(exact) = rows()
                    .iter()
                    .find(|r| r.law == law && r.quantity == q && r.method == "exact")
                {
                    let (e_c, e_f) = ((coarse - exact.value).abs(), (fine - exact.value).abs());
                    assert!(e_f < 6e-5, "{law} {q}: {fine} vs exact {}", exact.value);
                    assert!(e_f <= e_c + 1e-7, "{law} {q}: error grew {e_c} → {e_f}");
                }
            }
        }
        // problems.md: SVK plateau 0.0481, rate-law plateau 0.0506.
        assert!((value("svk", "plateau_stress_mid", "fv_n8000") - 0.0481).abs() < 5e-5);
        assert!((value("log_rate", "plateau_stress_mid", "fv_n8000") - 0.0506).abs() < 5e-5);
    }

    #[test]
    fn reference_reproduces_the_linear_solution() {
        let l = linear_reference(&cfg());
        let m = |q| value("linear", q, "fv_n8000");
        assert!((m("plateau_stress_mid") - l.plateau_stress).abs() < 1e-6);
        assert!((m("plateau_velocity_mid") - l.particle_velocity).abs() < 1e-6);
        assert!((m("arrival_mid") - 0.75).abs() < 2e-4);
        assert!((m("duration_mid") - 1.0).abs() < 2e-4);
        assert!((m("arrival_rear") - 1.5).abs() < 2e-4);
        assert!((m("free_surface_velocity_rear") - 0.1).abs() < 1e-5);
    }

    #[test]
    fn free_surface_velocity_matches_exact() {
        for law in ["log_rate", "svk"] {
            let exact = value(law, "free_surface_velocity_rear", "exact");
            let fine = value(law, "free_surface_velocity_rear", "fv_n8000");
            assert!((fine - exact).abs() < 1e-6, "{law}: {fine} vs {exact}");
        }
        assert!(
            (value("log_rate", "free_surface_velocity_rear", "exact") - 0.0999986).abs() < 1e-7
        );
    }

    #[test]
    fn profile_at_1_5_shows_the_pulse_in_the_target() {
        let c = cfg().with_cells(4000);
        let sol = lagrangian_reference(&log_law(), &c);
        let p = &sol.profile;
        assert!((p.time - 1.5).abs() < 1e-12);
        assert_eq!(p.x0.len(), 4000);
        // The shock has just reflected (1.4812 < 1.5): the rear 1 % is released, the region
        // behind it still at the plateau, the flyer fully released.
        let at = |x: f64| p.stress[((x / 2.0) * 4000.0) as usize];
        assert!((at(1.9) + 0.050634).abs() < 1e-4, "{}", at(1.9));
        assert!(at(0.3).abs() < 1e-3, "{}", at(0.3));
        assert!(p.x.windows(2).all(|w| w[1] > w[0]));
    }

    #[test]
    fn pulse_metrics_on_synthetic_signals() {
        let times: Vec<f64> = (0..=3000).map(|i| i as f64 * 1e-3).collect();
        // Trapezoid pulse −0.05 from 0.5 to 1.5 with 10 % Gibbs-like ringing after the rise.
        let sig: Vec<f64> = times
            .iter()
            .map(|&t| {
                let ramp =
                    ((t - 0.495) / 0.01).clamp(0.0, 1.0) - ((t - 1.495) / 0.01).clamp(0.0, 1.0);
                let ring = if t > 0.505 && t < 1.495 {
                    0.1 * (-(t - 0.505) / 0.05).exp() * ((t - 0.505) * 300.0).cos()
                } else {
                    0.0
                };
                -0.05 * (ramp + ring)
            })
            .collect();
        let m = pulse_metrics(&times, &sig).expect("pulse");
        assert!((m.plateau - 0.05).abs() < 1e-5, "{m:?}");
        assert!((m.arrival - 0.5).abs() < 1e-6, "{m:?}");
        assert!((m.duration - 1.0).abs() < 1e-6, "{m:?}");
        // Record ends before the fall.
        let m = pulse_metrics(&times[..1200], &sig[..1200]).expect("rise");
        assert!(m.duration.is_nan() && (m.arrival - 0.5).abs() < 1e-6);
        assert!((m.plateau - 0.05).abs() < 1e-5);
        // No pulse.
        assert!(pulse_metrics(&times, &vec![0.0; times.len()]).is_none());
        assert!(pulse_metrics(&[], &[]).is_none());
    }

    fn parse_rows(text: &str) -> HashMap<(String, String, String), f64> {
        text.lines()
            .skip(1)
            .filter(|l| !l.trim().is_empty())
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (
                    (f[0].to_string(), f[1].to_string(), f[2].to_string()),
                    f[3].trim().parse().unwrap(),
                )
            })
            .collect()
    }

    fn dir() -> std::path::PathBuf {
        reference_data_dir().join("R-P2")
    }

    #[test]
    fn stored_csvs_have_not_drifted() {
        let stored =
            std::fs::read_to_string(dir().join("finite_strain.csv")).expect("finite_strain.csv");
        assert!(stored.starts_with("law,quantity,method,value_nondim\n"));
        let stored = parse_rows(&stored);
        let fresh = parse_rows(&finite_strain_csv(rows()));
        assert_eq!(stored.len(), fresh.len());
        for (k, v) in &fresh {
            let s = stored
                .get(k)
                .unwrap_or_else(|| panic!("{k:?} missing from CSV"));
            assert!((s - v).abs() <= 1e-4 * v.abs(), "{k:?}: stored {s} vs {v}");
        }
        let lin = std::fs::read_to_string(dir().join("linear_analytic.csv"))
            .expect("linear_analytic.csv");
        assert_eq!(lin, linear_csv(&cfg()));
    }

    /// The reference converges: halving the cell size (4000 → 8000) moves the gauge times by
    /// less than 1e-4 and the plateaus by less than 1e-6 (first-order times, see source.md).
    #[test]
    fn reference_is_converged_in_resolution() {
        for law in [log_law(), svk_law()] {
            let coarse = cfg().with_cells(4000);
            let fine = cfg().with_cells(8000);
            let a = measure(&lagrangian_reference(&law, &coarse), &coarse);
            let b = measure(&lagrangian_reference(&law, &fine), &fine);
            for (x, y) in [
                (a.arrival_mid, b.arrival_mid),
                (a.arrival_rear, b.arrival_rear),
            ] {
                assert!((x - y).abs() < 1e-4, "{law}: times {x} vs {y}");
            }
            assert!(
                (a.plateau_stress - b.plateau_stress).abs() < 1e-6,
                "{law}: {a:?} vs {b:?}"
            );
            if b.duration_mid.is_finite() {
                assert!(
                    (a.duration_mid - b.duration_mid).abs() < 1e-4,
                    "{law}: {a:?} vs {b:?}"
                );
            }
        }
    }
}
