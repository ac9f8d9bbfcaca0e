//! Shared scene set-up of the Fuller kernel-interaction problems F-A2..F-A5 (problems.md §3 "Common Fuller settings"): material
//! M-F in non-dimensional units (Δx = 1, ρ = 1, E = 1, ν = 0.3, τ = Δx sqrt(ρ/E)), 2D plane
//! strain, cubic spline with h = 1.5Δx, Monaghan viscosity α = 1, β = 2α (F 2.60), the thesis'
//! integer lattices, and per-body sums (momentum, kinetic energy) over a running simulation.

use tlsph_io::{parse_scene, DimensionModel};
use tlsph_math::Vector;
use tlsph_solver::{Model, Simulation};

/// Young's modulus of M-F.
pub const YOUNGS: f64 = 1.0;
/// Poisson ratio of M-F.
pub const POISSON: f64 = 0.3;
/// Smoothing length h / Δx (F §2.2.2: "h = 1.5, three particle spacings").
pub const SMOOTHING: f64 = 1.5;
/// Courant number of N§7 (problems.md §0: Δt ≈ 0.3 h/c).
pub const CFL: f64 = 0.3;
/// Artificial stress ε (problems.md §4 #27 `[C]`, Gray–Monaghan–Swift) and exponent n = 6 `[T]`.
pub const ARTIFICIAL_STRESS: (f64, f64) = (0.3, 6.0);

/// Plane-strain P-wave speed of M-F at density ρ: c = sqrt(E(1−ν)/(ρ(1+ν)(1−2ν))) (1.1602 at
/// ρ = 1, problems.md §0).
pub fn sound_speed(density: f64) -> f64 {
    (YOUNGS * (1.0 - POISSON) / (density * (1.0 + POISSON) * (1.0 - 2.0 * POISSON))).sqrt()
}

/// `[simulation]` and one M-F `[[material]]` per (name, density).
pub fn header(formulation: &str, end_time: f64, materials: &[(&str, f64)]) -> String {
    let mut text = format!(
        r#"[simulation]
dimension = 2
formulation = "{formulation}"
kernel = "cubic-spline"
smoothing_factor = {SMOOTHING}
cfl = {CFL}
end_time = {end_time:e}
"#
    );
    for (name, density) in materials {
        text += &format!(
            r#"
[[material]]
name = "{name}"
model = "linear-elastic"
density = {density:e}
youngs_modulus = {YOUNGS}
poisson_ratio = {POISSON}
"#
        );
    }
    text
}

/// Fuller's stabilisation of thesis mode: Monaghan viscosity α = 1, β = 2 (F 2.60), XSPH ε if
/// given (F 3.2), artificial stress on the listed bodies (`Some(&[])`: none; `None`: every
/// body; F 3.5–3.7).
pub fn thesis_effects(xsph: Option<f64>, artificial_stress: Option<&[&str]>) -> String {
    let mut text = "\n[artificial_viscosity]\nalpha = 1.0\nbeta = 2.0\n".to_string();
    if let Some(epsilon) = xsph.filter(|e| *e > 0.0) {
        text += &format!("\n[xsph]\nepsilon = {epsilon}\n");
    }
    let (epsilon, exponent) = ARTIFICIAL_STRESS;
    match artificial_stress {
        Some([]) => {}
        None => {
            text += &format!("\n[artificial_stress]\nepsilon = {epsilon}\nexponent = {exponent}\n")
        }
        Some(bodies) => {
            let names: Vec<String> = bodies.iter().map(|b| format!("\"{b}\"")).collect();
            text += &format!(
                "\n[artificial_stress]\nepsilon = {epsilon}\nexponent = {exponent}\nbodies = [{}]\n",
                names.join(", ")
            );
        }
    }
    text
}

/// How the bodies of a Fuller multi-body problem interact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Fuller's scheme: updated-Lagrangian SPH, kernel interaction across the discs, XSPH,
    /// viscosity and artificial stress.
    Thesis,
    /// Separate TLSPH bodies (corrected gradients) in particle contact (numerics.md §12.2)
    /// with hourglass control; no XSPH, no viscosity, no artificial stress (no tensile
    /// instability to correct).
    TotalLagrangian,
}

impl Mode {
    /// Label in rows and curves.
    pub fn label(self) -> &'static str {
        match self {
            Mode::Thesis => "thesis mode",
            Mode::TotalLagrangian => "TL mode",
        }
    }

    /// Distance between two particles at which the bodies interact \[Δx\]: the kernel
    /// support 2h (thesis) or the contact distance d0 = Δx (TL).
    pub fn reach(self) -> f64 {
        match self {
            Mode::Thesis => 2.0 * SMOOTHING,
            Mode::TotalLagrangian => 1.0,
        }
    }
}

/// Contact scale a of TL mode `[C]`: F-A3's rebound velocities move by < 3 % between a = 0.05
/// and 2.0 (the Reveles P8/P10 card), while a = 2.0 costs 3× the steps (the contact's
/// time-step vote); 0.5 keeps the CFL step.
pub const CONTACT_SCALE: f64 = 0.5;

/// Hourglass-control coefficient of TL mode `[C]` (Ganzenmüller penalty, numerics.md
/// §10.5). Contact forces act on single surface particles and excite TLSPH's zero-energy
/// modes in the face layer; uncontrolled, the faces chatter and the rebound loses its
/// resolution convergence (in the F-A3 study run to choose this value, V_B/U at r = 10 was 1.45,
/// 0.99 and below 0.9 at R/Δx = 12, 24, 48).
/// With α = 1 the rebound converges (see F-A3's full-tier resolution notes).
pub const HOURGLASS: f64 = 1.0;

/// TL mode's effects: the particle contact between the named body pairs (a body named
/// twice: self-contact) and hourglass control.
pub fn tl_contact_effects(pairs: &[(&str, &str)]) -> String {
    format!(
        "\n[contact]\nscale = {CONTACT_SCALE}\npairs = {}\n\n[hourglass_control]\ncoefficient = {HOURGLASS}\n",
        pair_list(pairs)
    )
}

/// The scene's `pairs = [["a", "b"], ...]` value for the named body pairs.
fn pair_list(pairs: &[(&str, &str)]) -> String {
    let pairs: Vec<String> = pairs
        .iter()
        .map(|(a, b)| format!("[\"{a}\", \"{b}\"]"))
        .collect();
    format!("[{}]", pairs.join(", "))
}

/// TL mode's effects with Fuller's particle-type penalty contact (numerics.md §12.1: stiffness
/// E* d0^{d−1}, range d0, friction μ) between the named body pairs, and hourglass control.
pub fn tl_penalty_effects(pairs: &[(&str, &str)], friction: f64) -> String {
    format!(
        "\n[contact]\nlaw = \"penalty\"\nfriction = {friction}\npairs = {}\n\n[hourglass_control]\ncoefficient = {HOURGLASS}\n",
        pair_list(pairs)
    )
}

/// Parses a 2D scene written by this harness.
pub fn parse(text: &str, what: &str) -> Model<2> {
    match parse_scene(text, what).map(|s| s.model) {
        Ok(DimensionModel::Two(m)) => m,
        Ok(_) => unreachable!("{what} is 2D"),
        Err(e) => panic!("{what}: {e}"),
    }
}

/// The thesis lattice of a disc or ring: integer offsets (i, j) from `centre` with
/// inner < sqrt(i² + j²) < outer (inner < 0 for a full disc). R = 12 gives Fuller's 437
/// particles; the ring 30 < r < 35 gives 1020 (thesis 1018).
pub fn integer_ring(centre: Vector<2>, inner: f64, outer: f64) -> Vec<Vector<2>> {
    lattice_ring(centre, inner, outer, 1.0)
}

/// The same lattice refined: offsets (i, j)·Δx with inner < Δx sqrt(i² + j²) < outer, for
/// resolution studies of the thesis shapes.
pub fn lattice_ring(centre: Vector<2>, inner: f64, outer: f64, spacing: f64) -> Vec<Vector<2>> {
    let (inner, outer) = (inner / spacing, outer / spacing);
    let m = outer.ceil() as i64;
    let mut points = Vec::new();
    for i in -m..=m {
        for j in -m..=m {
            let r = ((i * i + j * j) as f64).sqrt();
            if r > inner && r < outer {
                points.push(centre + Vector::<2>::new(i as f64, j as f64) * spacing);
            }
        }
    }
    points
}

/// Replaces body `body`'s particles by `positions` (volumes Δx² of the body's `spacing`) with
/// velocities `velocity(x)`; the scene gave the body a placeholder shape. Boundaries of the
/// body must not be declared (their particle indices would refer to the placeholder).
pub fn set_particles(
    model: &mut Model<2>,
    body: usize,
    positions: Vec<Vector<2>>,
    velocity: impl Fn(&Vector<2>) -> Vector<2>,
) {
    let b = &mut model.bodies[body];
    assert!(model.boundaries.iter().all(|s| s.body != body));
    b.velocities = positions.iter().map(velocity).collect();
    b.volumes = vec![b.spacing * b.spacing; positions.len()];
    b.positions = positions;
}

/// Mass, momentum, centre-of-mass velocity and kinetic energy of one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodySums {
    /// Σ m.
    pub mass: f64,
    /// Σ m v.
    pub momentum: Vector<2>,
    /// Σ ½ m |v|².
    pub kinetic: f64,
    /// Σ m x / Σ m (current positions).
    pub centre: Vector<2>,
}

impl BodySums {
    /// Centre-of-mass velocity.
    pub fn velocity(&self) -> Vector<2> {
        self.momentum / self.mass
    }
}

/// Sums over the particles of body `body` in particle order (deterministic).
pub fn body_sums(sim: &Simulation<2>, body: usize) -> BodySums {
    let range = sim.bodies()[body].range.clone();
    let mut sums = BodySums {
        mass: 0.0,
        momentum: Vector::<2>::zeros(),
        kinetic: 0.0,
        centre: Vector::<2>::zeros(),
    };
    for i in range {
        let m = sim.masses()[i];
        let v = sim.velocity(i);
        sums.mass += m;
        sums.momentum += v * m;
        sums.kinetic += 0.5 * m * v.norm_squared();
        sums.centre += (sim.positions0()[i] + sim.displacements()[i]) * m;
    }
    sums.centre /= sums.mass;
    sums
}

/// Smallest current distance between a particle of body `a` and one of body `b`.
pub fn gap(sim: &Simulation<2>, a: usize, b: usize) -> f64 {
    let x = |i: usize| sim.positions0()[i] + sim.displacements()[i];
    let (ra, rb) = (sim.bodies()[a].range.clone(), sim.bodies()[b].range.clone());
    let mut best = f64::INFINITY;
    for i in ra {
        let xi = x(i);
        for j in rb.clone() {
            best = best.min((xi - x(j)).norm());
        }
    }
    best
}
