//! Periodic particle lattices in a homogeneous uniaxial-strain state, the two discrete force
//! functions of numerics.md (TLSPH §4–5 and Eulerian SPH §3) written out for them, and the
//! stiffness (dynamical) matrix K = −∂a/∂x of the linearised equations ü = −K u.
//!
//! Everything here is self-contained: the forces are re-implemented from the specification (not
//! taken from the solver) so that the analysis checks the equations, not one implementation.
//! K is obtained by forward-mode automatic differentiation ([`super::dual`]) of those force
//! functions, column by column: exact to round-off, with no finite-difference step to choose.

use tlsph_kernels::{CubicSpline, Kernel};

use super::dual::{Dual, Scalar, M2, V2};

/// Elastic material of the lattice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Reference density ρ0 \[kg/m³\].
    pub density: f64,
    /// Longitudinal (uniaxial-strain, "constrained") modulus M = λ + 2μ \[Pa\].
    pub modulus: f64,
    /// Poisson ratio ν (2D plane strain only) \[-\].
    pub poisson: f64,
}

impl Material {
    /// Steel as in Reveles' stability tests (R §6.2.1): ρ0 = 7850 kg/m³, E = 200 GPa, ν = 0.3,
    /// so M = E(1 − ν)/((1 + ν)(1 − 2ν)) = 269.2 GPa. The results are reported
    /// non-dimensionally and do not depend on these numbers.
    pub fn steel() -> Self {
        let (e, nu) = (200.0e9, 0.3);
        Self {
            density: 7850.0,
            modulus: e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            poisson: nu,
        }
    }

    /// Lamé constants (λ, μ) with λ + 2μ = M (numerics.md §8.1, R 5.73–5.75) \[Pa\].
    pub fn lame(&self) -> (f64, f64) {
        let nu = self.poisson;
        (
            self.modulus * nu / (1.0 - nu),
            self.modulus * (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu)),
        )
    }

    /// Longitudinal wave speed c = √(M/ρ0) (numerics.md §8.10) \[m/s\].
    pub fn sound_speed(&self) -> f64 {
        (self.modulus / self.density).sqrt()
    }
}

/// One-dimensional (uniaxial-strain) stress–stretch law. In 1D the Cauchy stress equals the
/// nominal / first Piola–Kirchhoff stress (J = F = λ, numerics.md §4.4), so one function σ(λ) =
/// P(λ) serves both formulations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Law {
    /// σ = P = M (λ − 1): P linear in F, so the TLSPH force is linear in the displacements.
    Linear,
    /// The hypoelastic law of numerics.md §8.1 (σ̇ = M D with D = λ̇/λ) integrated exactly for
    /// uniaxial strain: σ = P = M ln λ. In 2D the same rate law is used with Jaumann rotation
    /// terms (see [`Lattice`]); it is the solver's default material (Algorithms 2–3).
    Hypoelastic,
    /// St Venant–Kirchhoff, the solver's Algorithm-1 material (numerics.md §8.2, R 5.11–5.12):
    /// S = M E with E = (λ² − 1)/2, P = F S.
    StVenantKirchhoff,
}

impl Law {
    /// σ(λ) = P(λ) \[Pa\] for a stretch λ (any [`Scalar`], so it can be differentiated).
    pub fn stress<S: Scalar>(self, stretch: S, modulus: f64) -> S {
        match self {
            Self::Linear => (stretch - S::constant(1.0)).scale(modulus),
            Self::Hypoelastic => stretch.ln().scale(modulus),
            Self::StVenantKirchhoff => {
                (stretch * (stretch * stretch - S::constant(1.0))).scale(0.5 * modulus)
            }
        }
    }

    /// Second Piola–Kirchhoff stress S = P/F (R 3.55) and material tangent C = dS/dE with
    /// E = (F² − 1)/2 (R 3.56–3.57), both at stretch λ \[Pa\].
    pub fn second_piola_and_tangent(self, stretch: f64, modulus: f64) -> (f64, f64) {
        let l = stretch;
        match self {
            Self::Linear => (modulus * (l - 1.0) / l, modulus / l.powi(3)),
            Self::Hypoelastic => (modulus * l.ln() / l, modulus * (1.0 - l.ln()) / l.powi(3)),
            Self::StVenantKirchhoff => (0.5 * modulus * (l * l - 1.0), modulus),
        }
    }

    /// C̄ = C F² + S (R 3.60), the stiffness of the perturbed nominal stress P̃ = C̄ F̃ (R 3.59)
    /// that enters R 3.63 and R 3.79 \[Pa\].
    pub fn reference_tangent(self, stretch: f64, modulus: f64) -> f64 {
        let (s, c) = self.second_piola_and_tangent(stretch, modulus);
        c * stretch * stretch + s
    }

    /// C̄^σ = C^στ + σ (R 3.66) with the Truesdell modulus C^στ = J⁻¹F⁴C (1D push-forward of C),
    /// the stiffness of σ̃ = C̄^σ F⁻¹ F̃ (R 3.99) that enters R 3.100 \[Pa\]. Equals λ dσ/dλ.
    pub fn current_tangent(self, stretch: f64, modulus: f64) -> f64 {
        let (_, c) = self.second_piola_and_tangent(stretch, modulus);
        c * stretch.powi(3) + self.stress(stretch, modulus)
    }

    /// The stretch λ0 at which σ(λ0) = `stress` (Newton for St Venant–Kirchhoff).
    pub fn stretch_for_stress(self, stress: f64, modulus: f64) -> f64 {
        let s = stress / modulus;
        match self {
            Self::Linear => 1.0 + s,
            Self::Hypoelastic => s.exp(),
            Self::StVenantKirchhoff => {
                let mut l = 1.0 + s;
                for _ in 0..50 {
                    let f = 0.5 * l * (l * l - 1.0) - s;
                    let df = 0.5 * (3.0 * l * l - 1.0);
                    let step = f / df;
                    l -= step;
                    if step.abs() < 1e-16 {
                        break;
                    }
                }
                l
            }
        }
    }

    /// Label used in report rows.
    pub fn label(self) -> &'static str {
        match self {
            Self::Linear => "linear",
            Self::Hypoelastic => "hypoelastic",
            Self::StVenantKirchhoff => "st_venant_kirchhoff",
        }
    }
}

/// Which discrete equations are linearised.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Formulation {
    /// Total-Lagrangian SPH (numerics.md §4–5): reference-configuration kernel gradients
    /// G_IJ = ∇_{X_I} W(|X_I − X_J|, h0), F_I from the difference form (§4.2, R 4.24), nominal
    /// stress P(F_I), symmetric momentum form (a) of §4.5: a_I = Σ_J m (P_I + P_J)/ρ0² G_IJ.
    Tlsph,
    /// Conventional (Eulerian, updated-Lagrangian) SPH of numerics.md §3 with the kernel in the
    /// current configuration, h fixed, summation density, and the symmetric momentum equation
    /// (R 2.54): a_I = Σ_J m (σ_I/ρ_I² + σ_J/ρ_J²) ∇_I W_IJ.
    EulerianSymmetric,
    /// The same Eulerian SPH with the single-sum momentum equation that Reveles linearises
    /// (R 3.80; raw gradient R 2.20): a_I = (1/ρ_I) Σ_J (m/ρ_J) σ_J ∇_I W_IJ.
    EulerianSingleSum,
}

impl Formulation {
    /// All formulations, in report order.
    pub const ALL: [Formulation; 3] = [
        Formulation::Tlsph,
        Formulation::EulerianSymmetric,
        Formulation::EulerianSingleSum,
    ];

    /// Label used in the growth-rate map and report rows.
    pub fn label(self) -> &'static str {
        match self {
            Self::Tlsph => "tlsph",
            Self::EulerianSymmetric => "eulerian_symmetric",
            Self::EulerianSingleSum => "eulerian_single_sum",
        }
    }

    /// Parses [`Formulation::label`].
    pub fn from_label(label: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.label() == label.trim())
    }

    /// True for the two Eulerian variants.
    pub fn is_eulerian(self) -> bool {
        !matches!(self, Self::Tlsph)
    }
}

/// One stability case: a periodic lattice, a formulation, a law and a homogeneous stress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    /// Spatial dimension: 1 (uniaxial strain) or 2 (plane strain, square lattice).
    pub dimension: usize,
    /// Particles per direction (N in 1D, n × n particles in 2D).
    pub cells: usize,
    /// Reference particle spacing Δx0 \[m\].
    pub spacing: f64,
    /// Smoothing length over reference spacing, h/Δx0 (h is fixed in both formulations).
    pub h_over_dx: f64,
    /// Axial stress of the homogeneous state over the modulus, σ0/M (tension positive).
    pub stress_over_modulus: f64,
    /// Discrete equations.
    pub formulation: Formulation,
    /// Stress law (2D supports [`Law::Hypoelastic`] only).
    pub law: Law,
    /// Material constants.
    pub material: Material,
}

impl Case {
    /// A 1D case with steel, Δx0 = 1 mm.
    pub fn one_d(
        cells: usize,
        h_over_dx: f64,
        stress_over_modulus: f64,
        formulation: Formulation,
        law: Law,
    ) -> Self {
        Self {
            dimension: 1,
            cells,
            spacing: 1.0e-3,
            h_over_dx,
            stress_over_modulus,
            formulation,
            law,
            material: Material::steel(),
        }
    }

    /// A 2D plane-strain case (hypoelastic Jaumann law) with steel, Δx0 = 1 mm.
    pub fn two_d(
        cells: usize,
        h_over_dx: f64,
        stress_over_modulus: f64,
        formulation: Formulation,
    ) -> Self {
        Self {
            dimension: 2,
            law: Law::Hypoelastic,
            ..Self::one_d(
                cells,
                h_over_dx,
                stress_over_modulus,
                formulation,
                Law::Hypoelastic,
            )
        }
    }

    /// Number of unknowns N·D.
    pub fn dofs(&self) -> usize {
        self.cells.pow(self.dimension as u32) * self.dimension
    }
}

/// A neighbour of a particle, with the periodic image it is seen through.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair {
    /// Neighbour index J.
    pub j: usize,
    /// Periodic shift added to x_J in the current configuration \[m\].
    pub shift: [f64; 2],
    /// Reference separation X_J − X_I (with image) \[m\].
    pub reference_sep: [f64; 2],
    /// Separation x_J − x_I in the homogeneous base state (with image) \[m\].
    pub base_sep: [f64; 2],
    /// TLSPH reference gradient G_IJ = ∇_{X_I} W(|X_I − X_J|, h0) (numerics.md §0) \[1/m^(d+1)\].
    pub reference_gradient: [f64; 2],
}

/// A case made concrete: kernel, homogeneous base state, neighbour lists.
///
/// Base state (uniaxial strain along x, numerics.md §8.1 "1D uniaxial strain"):
/// * stretch λ0 = σ⁻¹(σ0) of [`Law`] (2D: λ0 = exp(σ0/M) of the hypoelastic law), lateral stress
///   σ_yy = λ σ0/M (2D; ε_yy = 0);
/// * TLSPH: the lattice is stretched by λ_lat = 1 + (λ0 − 1)/γ with γ = −V0 Σ_J (X_J − X_I)_x
///   G_IJ,x (≠ 1 for h ≠ Δx: the uncorrected gradient is not first-order exact, R-P3), so that the
///   *discrete* F_I of §4.2 equals diag(λ0, 1) and the base stress is exactly σ0;
/// * Eulerian: the lattice is stretched by λ0 (current spacing λ0 Δx0, h unchanged). In 1D the
///   stress is σ(λ_I) with λ_I = λ0 ρ̄/ρ_I, ρ_I the summation density (R 2.48) and ρ̄ its value in
///   the base state; this equals σ0 in the base state, and its linearisation is identical to that
///   of the continuity equation (R 2.51) with V_J = m/ρ_J. In 2D the stress is the §8.1 Jaumann
///   update from the base state, σ_I = σ_b + λ tr(L_I) I + 2μ sym L_I + W_I σ_b − σ_b W_I with
///   L_I = Σ_J (m/ρ_J)(u_J − u_I) ⊗ ∇_I W_IJ (R 2.62, u = x − x_base), exact at linear order.
#[derive(Debug, Clone)]
pub struct Lattice {
    /// The case.
    pub case: Case,
    /// Cubic spline of numerics.md §1.1 with h = h/Δx0 · Δx0.
    pub kernel: CubicSpline,
    /// Physical stretch λ0 of the base state (F_xx).
    pub stretch: f64,
    /// Stretch applied to the lattice positions (λ_lat above).
    pub lattice_stretch: f64,
    /// Base Cauchy stress (σ_xx, σ_yy) \[Pa\] (σ_yy = 0 in 1D).
    pub base_stress: [f64; 2],
    /// Particle mass m = ρ0 Δx0^d \[kg/m^(3−d)\].
    pub mass: f64,
    /// Reference volume V0 = m/ρ0 = Δx0^d.
    pub reference_volume: f64,
    /// Summation density ρ̄ = Σ_J m W_IJ of the base state (Eulerian) or ρ0/λ0 (TLSPH).
    pub base_density: f64,
    /// Base-state deformation gradient of TLSPH computed with the discrete §4.2 sum
    /// (diag(λ0, 1) up to round-off; identity for Eulerian).
    pub base_deformation: [[f64; 2]; 2],
    /// Reference positions X (N·D, particle-major).
    pub reference_positions: Vec<f64>,
    /// Base-state positions x_b (N·D, particle-major).
    pub base_positions: Vec<f64>,
    /// Current periods of the lattice (L_x, L_y) \[m\].
    pub period: [f64; 2],
    /// Neighbour lists (reference configuration for TLSPH, base state for Eulerian; J ≠ I).
    pub pairs: Vec<Vec<Pair>>,
}

fn norm(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

impl Lattice {
    /// Builds the lattice of `case`.
    ///
    /// # Panics
    /// If the dimension is not 1 or 2, a 2D case does not use [`Law::Hypoelastic`], or the
    /// lattice is too small for the kernel support (N Δx0 must exceed twice the support).
    pub fn new(case: Case) -> Self {
        let d = case.dimension;
        assert!(d == 1 || d == 2, "R-C3: dimension must be 1 or 2");
        assert!(
            d == 1 || case.law == Law::Hypoelastic,
            "R-C3: the 2D lattice uses the hypoelastic (Jaumann) law"
        );
        let dx = case.spacing;
        let n = case.cells;
        let h = case.h_over_dx * dx;
        let kernel = CubicSpline::new(d, h).expect("valid cubic spline");
        let support = kernel.support_radius();
        let length = n as f64 * dx;
        let m = &case.material;
        let mass = m.density * dx.powi(d as i32);
        let volume = dx.powi(d as i32);
        let count = n.pow(d as u32);

        let mut reference = vec![0.0; count * d];
        for p in 0..count {
            reference[p * d] = (p % n) as f64 * dx;
            if d == 2 {
                reference[p * d + 1] = (p / n) as f64 * dx;
            }
        }
        let stretch = if d == 1 {
            case.law
                .stretch_for_stress(case.stress_over_modulus * m.modulus, m.modulus)
        } else {
            case.stress_over_modulus.exp()
        };
        let sigma_xx = case.law.stress(stretch, m.modulus);
        let (lambda, _) = m.lame();
        let base_stress = if d == 1 {
            [sigma_xx, 0.0]
        } else {
            [sigma_xx, lambda / m.modulus * sigma_xx]
        };

        // Moment γ of the uncorrected reference gradient along x (R 4.50–4.55 without the
        // correction): F_xx = 1 + (λ_lat − 1) γ on the lattice.
        let reference_grad = |s: [f64; 2]| -> [f64; 2] {
            // G_IJ = ∇W evaluated at X_I − X_J = −s.
            let r = norm(s);
            let w1 = kernel.derivative(r);
            [-w1 * s[0] / r, -w1 * s[1] / r]
        };
        let lattice_stretch = match case.formulation {
            Formulation::Tlsph => {
                let reach = (support / dx).ceil() as i64;
                // γ = V0 Σ_J (X_J − X_I)_x G_IJ,x, so that F_xx = 1 + (λ_lat − 1) γ.
                let mut gamma = 0.0;
                for jx in -reach..=reach {
                    let ys = if d == 2 { -reach..=reach } else { 0..=0 };
                    for jy in ys {
                        let s = [jx as f64 * dx, jy as f64 * dx];
                        let r = norm(s);
                        if r > 0.0 && r < support {
                            gamma += volume * s[0] * reference_grad(s)[0];
                        }
                    }
                }
                1.0 + (stretch - 1.0) / gamma
            }
            _ => stretch,
        };

        let period = [lattice_stretch * length, length];
        // Each pair must be seen through one periodic image only.
        assert!(
            2.0 * support < period[0].min(length),
            "R-C3: lattice of {n} cells too small for h/dx = {}",
            case.h_over_dx
        );
        let base: Vec<f64> = reference
            .iter()
            .enumerate()
            .map(|(k, &x)| if k % d == 0 { lattice_stretch * x } else { x })
            .collect();

        let images: Vec<[i64; 2]> = if d == 1 {
            (-1..=1).map(|a| [a, 0]).collect()
        } else {
            (-1..=1)
                .flat_map(|a| (-1..=1).map(move |b| [a, b]))
                .collect()
        };
        let reference_period = [length, length];
        let pick = |v: &[f64], p: usize| -> [f64; 2] {
            if d == 1 {
                [v[p], 0.0]
            } else {
                [v[2 * p], v[2 * p + 1]]
            }
        };
        let mut pairs = vec![Vec::new(); count];
        for (i, list) in pairs.iter_mut().enumerate() {
            for j in 0..count {
                for img in &images {
                    let shift = [img[0] as f64 * period[0], img[1] as f64 * period[1]];
                    let (xi, xj) = (pick(&base, i), pick(&base, j));
                    let (xi0, xj0) = (pick(&reference, i), pick(&reference, j));
                    let reference_sep = [
                        xj0[0] + img[0] as f64 * reference_period[0] - xi0[0],
                        xj0[1] + img[1] as f64 * reference_period[1] - xi0[1],
                    ];
                    let base_sep = [xj[0] + shift[0] - xi[0], xj[1] + shift[1] - xi[1]];
                    let r = match case.formulation {
                        Formulation::Tlsph => norm(reference_sep),
                        _ => norm(base_sep),
                    };
                    if r > 0.0 && r < support * (1.0 + 1e-9) {
                        list.push(Pair {
                            j,
                            shift,
                            reference_sep,
                            base_sep,
                            reference_gradient: reference_grad(reference_sep),
                        });
                    }
                }
            }
        }

        let mut lattice = Self {
            case,
            kernel,
            stretch,
            lattice_stretch,
            base_stress,
            mass,
            reference_volume: volume,
            base_density: case.material.density / stretch,
            base_deformation: [[1.0, 0.0], [0.0, 1.0]],
            reference_positions: reference,
            base_positions: base,
            period,
            pairs,
        };
        if case.formulation.is_eulerian() {
            let x: Vec<f64> = lattice.base_positions.clone();
            lattice.base_density = lattice.densities(&x)[0];
        } else {
            let x: Vec<f64> = lattice.base_positions.clone();
            lattice.base_deformation = lattice.deformation_gradient(&x, 0).values();
        }
        lattice
    }

    /// Number of particles.
    pub fn particles(&self) -> usize {
        self.case.cells.pow(self.case.dimension as u32)
    }

    /// Position of particle `p` from a state vector, as a 2-vector (y = 0 in 1D).
    fn position<S: Scalar>(&self, x: &[S], p: usize) -> V2<S> {
        if self.case.dimension == 1 {
            [x[p], S::constant(0.0)]
        } else {
            [x[2 * p], x[2 * p + 1]]
        }
    }

    /// Current separation x_J + shift − x_I of a pair.
    fn separation<S: Scalar>(&self, x: &[S], i: usize, pair: &Pair) -> V2<S> {
        let (xi, xj) = (self.position(x, i), self.position(x, pair.j));
        [
            xj[0] + S::constant(pair.shift[0]) - xi[0],
            xj[1] + S::constant(pair.shift[1]) - xi[1],
        ]
    }

    /// ∇_I W(x_I − x_J) for the current separation `sep` = x_J − x_I, as a function of the
    /// positions (R 2.68): W'(r) (x_I − x_J)/r.
    fn current_gradient<S: Scalar>(&self, sep: V2<S>) -> V2<S> {
        let e = [-sep[0], -sep[1]];
        if self.case.dimension == 1 {
            // W'(|e|) sgn(e); its derivative with respect to e is W''(|e|).
            let a = e[0].value().abs();
            let g = e[0].chain(
                self.kernel.derivative(a) * e[0].value().signum(),
                self.kernel.second_derivative(a),
            );
            [g, S::constant(0.0)]
        } else {
            let r = (e[0] * e[0] + e[1] * e[1]).sqrt();
            let w1 = r.chain(
                self.kernel.derivative(r.value()),
                self.kernel.second_derivative(r.value()),
            );
            let f = w1 / r;
            [e[0] * f, e[1] * f]
        }
    }

    /// W(|x_I − x_J|) for the current separation.
    fn current_value<S: Scalar>(&self, sep: V2<S>) -> S {
        let r = if self.case.dimension == 1 {
            if sep[0].value() < 0.0 {
                -sep[0]
            } else {
                sep[0]
            }
        } else {
            (sep[0] * sep[0] + sep[1] * sep[1]).sqrt()
        };
        r.chain(
            self.kernel.value(r.value()),
            self.kernel.derivative(r.value()),
        )
    }

    /// Summation densities ρ_I = Σ_J m W_IJ including J = I (R 2.48; F 2.22).
    pub fn densities<S: Scalar>(&self, x: &[S]) -> Vec<S> {
        let self_term = self.mass * self.kernel.value(0.0);
        (0..self.particles())
            .map(|i| {
                let mut rho = S::constant(self_term);
                for pair in &self.pairs[i] {
                    rho += self
                        .current_value(self.separation(x, i, pair))
                        .scale(self.mass);
                }
                rho
            })
            .collect()
    }

    /// TLSPH deformation gradient of particle `i`, difference form (numerics.md §4.2, R 4.24):
    /// F_I = I + Σ_J V0 (u_J − u_I) ⊗ G_IJ with u_J − u_I = (x_J − x_I) − (X_J − X_I).
    pub fn deformation_gradient<S: Scalar>(&self, x: &[S], i: usize) -> M2<S> {
        let mut f = M2::<S>::identity();
        for pair in &self.pairs[i] {
            let sep = self.separation(x, i, pair);
            let du = [
                sep[0] - S::constant(pair.reference_sep[0]),
                sep[1] - S::constant(pair.reference_sep[1]),
            ];
            let g = pair
                .reference_gradient
                .map(|c| S::constant(c * self.reference_volume));
            f = f + M2::outer(du, g);
        }
        if self.case.dimension == 1 {
            // Keep the unused lateral components at their identity values.
            f.m[0][1] = S::constant(0.0);
            f.m[1][0] = S::constant(0.0);
            f.m[1][1] = S::constant(1.0);
        }
        f
    }

    /// Jaumann hypoelastic increment from the base state (numerics.md §8.1):
    /// σ = σ_b + λ tr(L) I + 2μ sym L + W σ_b − σ_b W with W = skew L.
    pub fn jaumann_stress<S: Scalar>(&self, l: M2<S>) -> M2<S> {
        let (lambda, mu) = self.case.material.lame();
        let sigma_b = M2::<S>::constant([[self.base_stress[0], 0.0], [0.0, self.base_stress[1]]]);
        let w = l.skew();
        sigma_b
            + M2::identity().times(l.trace().scale(lambda))
            + l.sym().scale(2.0 * mu)
            + w * sigma_b
            - sigma_b * w
    }

    /// Accelerations a = ẍ of every particle for the state `x` (N·D, particle-major) — the
    /// discrete force function of the case's [`Formulation`] divided by the mass.
    pub fn accelerations<S: Scalar>(&self, x: &[S]) -> Vec<S> {
        match self.case.formulation {
            Formulation::Tlsph => self.tlsph_accelerations(x),
            _ => self.eulerian_accelerations(x),
        }
    }

    /// TLSPH (numerics.md §4.5 (a), R 4.26): a_I = Σ_J (V0/ρ0)(P_I + P_J) G_IJ with
    /// 1D: P = σ(F) of [`Law`] (F = λ); 2D: P = J σ F⁻ᵀ with the Jaumann stress increment
    /// [`Lattice::jaumann_stress`] driven by L = (F − F_b) F_b⁻¹ (numerics.md §4.3–4.4, §5
    /// Algorithm 2, exact at linear order).
    fn tlsph_accelerations<S: Scalar>(&self, x: &[S]) -> Vec<S> {
        let d = self.case.dimension;
        let modulus = self.case.material.modulus;
        let fb = M2::<S>::constant(self.base_deformation);
        let fb_inv = fb.inverse();
        let piola: Vec<M2<S>> = (0..self.particles())
            .map(|i| {
                let f = self.deformation_gradient(x, i);
                if d == 1 {
                    let mut p = M2::zero();
                    p.m[0][0] = self.case.law.stress(f.m[0][0], modulus);
                    p
                } else {
                    let sigma = self.jaumann_stress((f - fb) * fb_inv);
                    (sigma * f.inverse().transpose()).times(f.det())
                }
            })
            .collect();
        let c = self.reference_volume / self.case.material.density;
        let mut a = vec![S::constant(0.0); x.len()];
        for (i, list) in self.pairs.iter().enumerate() {
            let mut acc = [S::constant(0.0), S::constant(0.0)];
            for pair in list {
                let g = pair.reference_gradient.map(|v| S::constant(v * c));
                let t = (piola[i] + piola[pair.j]).apply(g);
                acc[0] += t[0];
                acc[1] += t[1];
            }
            a[i * d] = acc[0];
            if d == 2 {
                a[i * d + 1] = acc[1];
            }
        }
        a
    }

    /// Eulerian SPH (numerics.md §3): summation density, stress as described on [`Lattice`],
    /// symmetric (R 2.54) or single-sum (R 3.80) momentum equation.
    fn eulerian_accelerations<S: Scalar>(&self, x: &[S]) -> Vec<S> {
        let d = self.case.dimension;
        let n = self.particles();
        let rho = self.densities(x);
        let m = self.mass;
        let stress: Vec<M2<S>> = (0..n)
            .map(|i| {
                if d == 1 {
                    let stretch = (S::constant(self.stretch * self.base_density)) / rho[i];
                    let mut s = M2::zero();
                    s.m[0][0] = self.case.law.stress(stretch, self.case.material.modulus);
                    s
                } else {
                    let mut l = M2::<S>::zero();
                    for pair in &self.pairs[i] {
                        let sep = self.separation(x, i, pair);
                        let du = [
                            sep[0] - S::constant(pair.base_sep[0]),
                            sep[1] - S::constant(pair.base_sep[1]),
                        ];
                        let g = self.current_gradient(sep);
                        let v = S::constant(m) / rho[pair.j];
                        l = l + M2::outer(du, [g[0] * v, g[1] * v]);
                    }
                    self.jaumann_stress(l)
                }
            })
            .collect();
        let mut a = vec![S::constant(0.0); x.len()];
        for i in 0..n {
            let mut acc = [S::constant(0.0), S::constant(0.0)];
            let tau_i = stress[i].times(S::constant(1.0) / (rho[i] * rho[i]));
            for pair in &self.pairs[i] {
                let g = self.current_gradient(self.separation(x, i, pair));
                let t = match self.case.formulation {
                    Formulation::EulerianSymmetric => {
                        let tau_j =
                            stress[pair.j].times(S::constant(1.0) / (rho[pair.j] * rho[pair.j]));
                        (tau_i + tau_j).scale(m).apply(g)
                    }
                    _ => stress[pair.j]
                        .times(S::constant(m) / (rho[pair.j] * rho[i]))
                        .apply(g),
                };
                acc[0] += t[0];
                acc[1] += t[1];
            }
            a[i * d] = acc[0];
            if d == 2 {
                a[i * d + 1] = acc[1];
            }
        }
        a
    }

    /// Stiffness (dynamical) matrix K = −∂a/∂x at the base state, so that the linearised
    /// equations are ü = −K u (column-major, `dofs × dofs`). Column k is the derivative of the
    /// force function along coordinate k, evaluated exactly with a [`Dual`] seed.
    pub fn stiffness(&self) -> Vec<f64> {
        let n = self.case.dofs();
        let mut x: Vec<Dual> = self
            .base_positions
            .iter()
            .map(|&v| Dual::constant(v))
            .collect();
        let mut k = vec![0.0; n * n];
        for col in 0..n {
            x[col].d = 1.0;
            let a = self.accelerations(&x);
            x[col].d = 0.0;
            for (row, ai) in a.iter().enumerate() {
                k[col * n + row] = -ai.d;
            }
        }
        k
    }

    /// Non-dimensionalising factor for ω²: (Δx0/c)² with c = √(M/ρ0).
    pub fn omega2_scale(&self) -> f64 {
        (self.case.spacing / self.case.material.sound_speed()).powi(2)
    }
}
