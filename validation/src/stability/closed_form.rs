//! Closed-form dispersion relations ω²(κ) of the lattices of [`super::lattice`], evaluated at the
//! Bloch wavenumbers of the periodic lattice: R 3.79 (TLSPH, 1D), R 3.100 (Eulerian SPH, 1D, with
//! W' in the first bracket as numerics.md §15 corrects) and its symmetric-momentum counterpart,
//! and their 2D generalisations `[A]`. They are written from the formulas, independently of the
//! force functions, so that agreement with the matrix eigenvalues validates both.
//!
//! Particle volumes: Reveles writes R 3.72–3.100 without the V_J = m_J/ρ_J factors of the SPH
//! sums (as for unit volume); they are restored here (V0 = Δx0 in TLSPH, V = m/ρ̄ in Eulerian
//! SPH), which makes the formulas dimensionally consistent.

use std::f64::consts::PI;

use faer::c64;
use tlsph_kernels::Kernel;

use super::lattice::{Formulation, Lattice};

/// Bloch wavenumber κ_k = 2πk/(N Δ) of a periodic lattice of N particles at spacing Δ.
pub fn bloch_wavenumber(k: usize, cells: usize, spacing: f64) -> f64 {
    2.0 * PI * k as f64 / (cells as f64 * spacing)
}

/// Signed W'(X) = dW(|X|)/dX of a 1D kernel (odd in X).
fn signed_derivative(lat: &Lattice, x: f64) -> f64 {
    lat.kernel.derivative(x.abs()) * x.signum()
}

/// Lattice offsets j (in spacings) inside the kernel support, both sides, j ≠ 0.
fn offsets(lat: &Lattice, spacing: f64) -> Vec<i64> {
    let reach = (lat.kernel.support_radius() / spacing).ceil() as i64;
    (-reach..=reach)
        .filter(|&j| j != 0 && (j as f64 * spacing).abs() < lat.kernel.support_radius())
        .collect()
}

/// R 3.79, TLSPH on a uniform 1D lattice (volumes restored):
/// ω² = (C̄/ρ0) V0² Σ_J W'(X_I − X_J) Σ_K W'(X_K − X_J) cos(κ(X_K − X_I)),
/// with C̄ = C F² + S (R 3.60, [`super::lattice::Law::reference_tangent`]) at the base stretch.
/// Evaluated literally as the double sum, one value per Bloch wavenumber κ_k, k = 0 … N − 1.
pub fn tlsph_1d(lat: &Lattice) -> Vec<f64> {
    let case = &lat.case;
    let dx = case.spacing;
    let cbar = case
        .law
        .reference_tangent(lat.stretch, case.material.modulus);
    let js = offsets(lat, dx);
    let v0 = lat.reference_volume;
    (0..case.cells)
        .map(|k| {
            let kappa = bloch_wavenumber(k, case.cells, dx);
            let mut sum = 0.0;
            for &j in &js {
                let xj = j as f64 * dx;
                let outer = signed_derivative(lat, -xj);
                for &l in &js {
                    let xk = xj + l as f64 * dx;
                    sum += outer * signed_derivative(lat, xk - xj) * (kappa * xk).cos();
                }
            }
            cbar / case.material.density * v0 * v0 * sum
        })
        .collect()
}

/// Weight α of the stress terms: 1 for the single-sum momentum equation that R 3.100 is derived
/// from (R 3.80), 2 for the symmetric form (R 2.54), whose σ_I/ρ_I² and σ_J/ρ_J² terms each
/// contribute one copy `[A]`. Not used for TLSPH.
pub fn stress_weight(formulation: Formulation) -> f64 {
    match formulation {
        Formulation::EulerianSymmetric => 2.0,
        _ => 1.0,
    }
}

/// R 3.100, Eulerian SPH on a uniform 1D lattice of current spacing Δx (W' in the first bracket,
/// numerics.md §15; volumes restored):
/// ω² = (C̄^σ/ρ)[V Σ_j W'(jΔx) sin(κjΔx)]² − α (σ/ρ){V Σ_j W''(jΔx)[1 − cos(κjΔx)]
///      − [V Σ_j W'(jΔx) sin(κjΔx)]²},
/// with C̄^σ = C^στ + σ (R 3.66, [`super::lattice::Law::current_tangent`]), ρ = ρ̄ the base
/// summation density, V = m/ρ̄, sums over all j ≠ 0 in the support, α from [`stress_weight`]
/// (α = 1 is R 3.100 as printed). One value per Bloch wavenumber κ_k = 2πk/(NΔx).
pub fn eulerian_1d(lat: &Lattice, alpha: f64) -> Vec<f64> {
    let case = &lat.case;
    let dx = lat.lattice_stretch * case.spacing;
    let modulus = case.material.modulus;
    let cbar = case.law.current_tangent(lat.stretch, modulus);
    let sigma = lat.base_stress[0];
    let rho = lat.base_density;
    let v = lat.mass / rho;
    let js = offsets(lat, dx);
    (0..case.cells)
        .map(|k| {
            let kappa = bloch_wavenumber(k, case.cells, dx);
            let (mut s1, mut s2) = (0.0, 0.0);
            for &j in &js {
                let x = j as f64 * dx;
                s1 += signed_derivative(lat, x) * (kappa * x).sin();
                s2 += lat.kernel.second_derivative(x.abs()) * (1.0 - (kappa * x).cos());
            }
            let b1 = v * s1;
            cbar / rho * b1 * b1 - alpha * sigma / rho * (v * s2 - b1 * b1)
        })
        .collect()
}

/// The lattice sum of Swegle's criterion σ W'' > 0 (numerics.md §15) for the 1D Eulerian lattice:
/// S₂(κ_k) = Σ_j W''(jΔx)[1 − cos(κ_k jΔx)], one value per Bloch wavenumber. It is the bracket
/// of R 3.100 that multiplies −σ; a mode can grow only where σ S₂ > 0, and at the cut-off
/// κ = π/Δx, where the W' terms vanish, it grows if and only if σ S₂ > 0.
pub fn swegle_sum_1d(lat: &Lattice) -> Vec<f64> {
    let case = &lat.case;
    let dx = lat.lattice_stretch * case.spacing;
    let js = offsets(lat, dx);
    (0..case.cells)
        .map(|k| {
            let kappa = bloch_wavenumber(k, case.cells, dx);
            js.iter()
                .map(|&j| {
                    let x = j as f64 * dx;
                    lat.kernel.second_derivative(x.abs()) * (1.0 - (kappa * x).cos())
                })
                .sum()
        })
        .collect()
}

type T2 = [[f64; 2]; 2];

fn mul(a: T2, b: T2) -> T2 {
    let e = |i: usize, j: usize| a[i][0] * b[0][j] + a[i][1] * b[1][j];
    [[e(0, 0), e(0, 1)], [e(1, 0), e(1, 1)]]
}

fn transpose(a: T2) -> T2 {
    [[a[0][0], a[1][0]], [a[0][1], a[1][1]]]
}

fn inverse(a: T2) -> T2 {
    let d = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    [[a[1][1] / d, -a[0][1] / d], [-a[1][0] / d, a[0][0] / d]]
}

fn lin(ca: f64, a: T2, cb: f64, b: T2) -> T2 {
    let e = |i: usize, j: usize| ca * a[i][j] + cb * b[i][j];
    [[e(0, 0), e(0, 1)], [e(1, 0), e(1, 1)]]
}

/// Jaumann stress increment of numerics.md §8.1 for a displacement-gradient increment L:
/// 𝒞(L) = λ tr L I + μ (L + Lᵀ) + ½(L − Lᵀ) σ_b − ½ σ_b (L − Lᵀ).
fn jaumann(lat: &Lattice, l: T2) -> T2 {
    let (lambda, mu) = lat.case.material.lame();
    let sb = [[lat.base_stress[0], 0.0], [0.0, lat.base_stress[1]]];
    let w = lin(0.5, l, -0.5, transpose(l));
    let tr = l[0][0] + l[1][1];
    let mut out = lin(mu, l, mu, transpose(l));
    out = lin(1.0, out, 1.0, lin(1.0, mul(w, sb), -1.0, mul(sb, w)));
    out[0][0] += lambda * tr;
    out[1][1] += lambda * tr;
    out
}

/// Tangent dP = A : dF of TLSPH's nominal stress P = J σ F⁻ᵀ (numerics.md §4.4) at the base
/// state, with the Jaumann increment dσ = 𝒞(dF F_b⁻¹):
/// dP = J tr(dL) σ_b F_b⁻ᵀ + J 𝒞(dL) F_b⁻ᵀ − J σ_b F_b⁻ᵀ dFᵀ F_b⁻ᵀ, dL = dF F_b⁻¹.
fn piola_tangent(lat: &Lattice, df: T2) -> T2 {
    let fb = lat.base_deformation;
    let fb_inv = inverse(fb);
    let fb_it = transpose(fb_inv);
    let j = fb[0][0] * fb[1][1] - fb[0][1] * fb[1][0];
    let sb = [[lat.base_stress[0], 0.0], [0.0, lat.base_stress[1]]];
    let dl = mul(df, fb_inv);
    let tr = dl[0][0] + dl[1][1];
    let a = mul(sb, fb_it);
    let b = mul(jaumann(lat, dl), fb_it);
    let c = mul(mul(a, transpose(df)), fb_it);
    lin(1.0, lin(j * tr, a, j, b), -j, c)
}

/// Eigenvalues of a real 2 × 2 matrix (complex when the discriminant is negative).
fn eig2(q: T2) -> [c64; 2] {
    let half_tr = 0.5 * (q[0][0] + q[1][1]);
    let disc = 0.25 * (q[0][0] - q[1][1]).powi(2) + q[0][1] * q[1][0];
    if disc >= 0.0 {
        let r = disc.sqrt();
        [c64::new(half_tr - r, 0.0), c64::new(half_tr + r, 0.0)]
    } else {
        let r = (-disc).sqrt();
        [c64::new(half_tr, -r), c64::new(half_tr, r)]
    }
}

/// Lattice separations s (both components, in the support, s ≠ 0) of a rectangular lattice.
fn separations_2d(lat: &Lattice, spacing: [f64; 2]) -> Vec<[f64; 2]> {
    let support = lat.kernel.support_radius();
    let rx = (support / spacing[0]).ceil() as i64;
    let ry = (support / spacing[1]).ceil() as i64;
    let mut out = Vec::new();
    for jx in -rx..=rx {
        for jy in -ry..=ry {
            let s = [jx as f64 * spacing[0], jy as f64 * spacing[1]];
            let r = s[0].hypot(s[1]);
            if r > 0.0 && r < support {
                out.push(s);
            }
        }
    }
    out
}

/// 2D generalisation of R 3.79 / R 3.100 `[A]` for the plane-strain square lattice, two values
/// per Bloch wavevector κ = 2π(k_x/L_x, k_y/L_y), k_x, k_y = 0 … n − 1 (k_y-major order).
///
/// With the lattice wavevector k̂(κ) = V Σ_s ∇W(s) sin(κ·s) (the SPH image of κ: k̂ → −γκ for
/// small κ) and Ĥ(κ) = Σ_s H(s)(1 − cos κ·s), H the Hessian of W:
/// * TLSPH: ω² = eig Q/ρ0 with the acoustic tensor Q_ij = [A(e_j ⊗ k̂) k̂]_i of the nominal-stress
///   tangent A = ∂P/∂F at the base state — the 2D form of R 3.79, ω² = C̄ k̂²/ρ0: stable iff the
///   continuum is (R 3.63), with a zero (not growing) mode wherever k̂ = 0;
/// * Eulerian SPH: ω² = eig Q/ρ̄ with Q g = 𝒞(g ⊗ k̂) k̂ + α σ_b k̂ (k̂·g) − α V σ_b Ĥ g, the 2D
///   form of R 3.100 (α from [`stress_weight`]): the last term is the Swegle term.
pub fn dispersion_2d(lat: &Lattice) -> Vec<c64> {
    let case = &lat.case;
    let n = case.cells;
    let dx0 = case.spacing;
    let eulerian = case.formulation.is_eulerian();
    let spacing = if eulerian {
        [lat.lattice_stretch * dx0, dx0]
    } else {
        [dx0, dx0]
    };
    let seps = separations_2d(lat, spacing);
    let volume = if eulerian {
        lat.mass / lat.base_density
    } else {
        lat.reference_volume
    };
    let density = if eulerian {
        lat.base_density
    } else {
        case.material.density
    };
    let alpha = stress_weight(case.formulation);
    let sb = [[lat.base_stress[0], 0.0], [0.0, lat.base_stress[1]]];
    let mut out = Vec::with_capacity(2 * n * n);
    for ky in 0..n {
        for kx in 0..n {
            let kappa = [
                bloch_wavenumber(kx, n, spacing[0]),
                bloch_wavenumber(ky, n, spacing[1]),
            ];
            let mut k_hat = [0.0; 2];
            let mut h_hat = [[0.0; 2]; 2];
            for s in &seps {
                let r = s[0].hypot(s[1]);
                let phase = kappa[0] * s[0] + kappa[1] * s[1];
                let w1 = lat.kernel.derivative(r);
                let w2 = lat.kernel.second_derivative(r);
                let e = [s[0] / r, s[1] / r];
                for a in 0..2 {
                    k_hat[a] += volume * w1 * e[a] * phase.sin();
                    for b in 0..2 {
                        let delta = if a == b { 1.0 } else { 0.0 };
                        let hess = w2 * e[a] * e[b] + w1 / r * (delta - e[a] * e[b]);
                        h_hat[a][b] += hess * (1.0 - phase.cos());
                    }
                }
            }
            let mut q = [[0.0; 2]; 2];
            for j in 0..2 {
                let mut g = [0.0; 2];
                g[j] = 1.0;
                let gk = [
                    [g[0] * k_hat[0], g[0] * k_hat[1]],
                    [g[1] * k_hat[0], g[1] * k_hat[1]],
                ];
                let t = if eulerian {
                    jaumann(lat, gk)
                } else {
                    piola_tangent(lat, gk)
                };
                for i in 0..2 {
                    q[i][j] = t[i][0] * k_hat[0] + t[i][1] * k_hat[1];
                    if eulerian {
                        let sk = sb[i][0] * k_hat[0] + sb[i][1] * k_hat[1];
                        let sh = sb[i][0] * h_hat[0][j] + sb[i][1] * h_hat[1][j];
                        q[i][j] += alpha * (sk * k_hat[j] - volume * sh);
                    }
                }
            }
            let q = [
                [q[0][0] / density, q[0][1] / density],
                [q[1][0] / density, q[1][1] / density],
            ];
            out.extend(eig2(q));
        }
    }
    out
}

/// The closed-form ω² of a lattice, N·D values (as complex numbers; real in 1D): R 3.79 for
/// TLSPH, R 3.100 with α = 1 for the single-sum and α = 2 for the symmetric Eulerian form, or
/// [`dispersion_2d`] in 2D. Wavenumber order (not sorted).
pub fn dispersion(lat: &Lattice) -> Vec<c64> {
    if lat.case.dimension == 2 {
        return dispersion_2d(lat);
    }
    let values = match lat.case.formulation {
        Formulation::Tlsph => tlsph_1d(lat),
        f => eulerian_1d(lat, stress_weight(f)),
    };
    values.into_iter().map(|w| c64::new(w, 0.0)).collect()
}
