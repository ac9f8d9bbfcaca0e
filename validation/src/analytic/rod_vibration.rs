//! R-P4 reference (Reveles §6.1.4, Eqs 6.11–6.15): clamped–free elastic rod in uniaxial strain,
//! released with u = 0 and v = K x. Exact displacement, velocity, strain and energies, plus the
//! period and amplitude measurements the validation applies to SPH gauge histories.
//!
//! The modal series of problems.md R-P4,
//! u(x,t) = Σ_n B_n sin(k_n x) sin(ω_n t), k_n = (2n−1)π/(2L), ω_n = c k_n,
//! B_n = 16 K L² (−1)^{n+1} / ((2n−1)³ π³ c),
//! is the eigenfunction expansion of the d'Alembert solution
//! u = [Φ(x+ct) − Φ(x−ct)]/(2c), Φ' = g̃, where g̃ is the extension of the initial velocity
//! g(x) = K x that is odd about x = 0 and even about x = L (a triangle wave of period 4L and
//! amplitude K L). [`RodVibration::displacement`], [`RodVibration::velocity`] and
//! [`RodVibration::strain`] evaluate that closed form, i.e. the series summed over all modes, to
//! round-off; [`RodVibration::displacement_modal`] sums the first N modes and the tests check
//! that the two agree.

use std::f64::consts::PI;

/// Number of modes after which the truncated displacement series is within 1e-9 of the full sum,
/// relative to B_1: the tail is bounded by B_1 π³/32 · 1/(4(2N−1)²) ≤ 6.3e-10 B_1 for N = 10⁴.
/// (Velocity and strain coefficients decay only like 1/n², so their series are not summed
/// term by term; the closed form is used instead.)
pub const MODES_FOR_1E9: usize = 10_000;

/// Displacement stations of Fig 6.13 \[m\] (problems.md R-P4 `[C]`: 0.002, 0.003, 0.006 m).
pub const STATIONS_M: [f64; 3] = [0.002, 0.003, 0.006];
/// Rod length L = 0.006 m (problems.md R-P4 `[T]`).
pub const LENGTH_M: f64 = 0.006;
/// Thesis velocity gradient K = 0.1 µs⁻¹ = 1e5 s⁻¹ (problems.md R-P4 `[T/A]`).
pub const K_THESIS_PER_S: f64 = 1.0e5;
/// Linear-regime variant R-P4s, K = 1e3 s⁻¹ (problems.md R-P4 `[C]`).
pub const K_LINEAR_PER_S: f64 = 1.0e3;
/// Particle count of the thesis discretisation (problems.md R-P4 `[T]`).
pub const PARTICLES: usize = 31;
/// Particle spacing Δx = 2e-4 m (problems.md R-P4 `[C]`: thesis "2E-2" read as cm).
pub const SPACING_M: f64 = 2.0e-4;
/// End time of the thesis comparison, 12.4 µs (Fig 6.16).
pub const END_TIME_S: f64 = 12.4e-6;

/// Isotropic linear-elastic material of a uniaxial-strain rod.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodMaterial {
    /// Young's modulus E \[Pa\].
    pub youngs_modulus: f64,
    /// Poisson's ratio ν [-].
    pub poisson_ratio: f64,
    /// Density ρ \[kg/m³\].
    pub density: f64,
}

/// Material M-TI of problems.md §1 (R-P4): E = 1.16e11 Pa `[C]`, ν = 0.342, ρ = 4530 kg/m³.
pub const TITANIUM: RodMaterial = RodMaterial {
    youngs_modulus: 1.16e11,
    poisson_ratio: 0.342,
    density: 4530.0,
};

impl RodMaterial {
    /// Longitudinal (uniaxial-strain) modulus M = K + 4G/3 = E(1−ν)/((1+ν)(1−2ν)) \[Pa\]
    /// (problems.md §0, R 6.1).
    pub fn uniaxial_modulus(&self) -> f64 {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))
    }

    /// Uniaxial-strain wave speed c_M = sqrt(M/ρ) \[m/s\] (R 6.1; 6303.4 m/s for M-TI).
    pub fn wave_speed(&self) -> f64 {
        (self.uniaxial_modulus() / self.density).sqrt()
    }

    /// Thin-bar speed sqrt(E/ρ) of R 6.15 \[m/s\] (5060.3 m/s for M-TI; not used by the reference).
    pub fn bar_wave_speed(&self) -> f64 {
        (self.youngs_modulus / self.density).sqrt()
    }
}

/// Clamped (x = 0) – free (x = L) rod with u(x,0) = 0, v(x,0) = K x (problems.md R-P4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodVibration {
    /// Rod length L \[m\].
    pub length: f64,
    /// Longitudinal wave speed c \[m/s\].
    pub wave_speed: f64,
    /// Initial velocity gradient K \[1/s\].
    pub velocity_gradient: f64,
}

/// Kinetic and internal energy per unit cross-section area [J/m²].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodEnergies {
    /// KE = ∫ ½ ρ v² dx.
    pub kinetic: f64,
    /// IE = ∫ ½ M ε² dx with M = ρ c².
    pub internal: f64,
}

impl RodVibration {
    /// A rod of length `length` \[m\], wave speed `wave_speed` \[m/s\], initial gradient K \[1/s\].
    pub fn new(length: f64, wave_speed: f64, velocity_gradient: f64) -> Self {
        assert!(
            length > 0.0 && wave_speed > 0.0,
            "length and wave speed must be > 0"
        );
        Self {
            length,
            wave_speed,
            velocity_gradient,
        }
    }

    /// The consistent R-P4 set: L = 0.006 m, c = c_M of [`TITANIUM`] (6303.4 m/s), given K.
    pub fn reveles_problem4(velocity_gradient: f64) -> Self {
        Self::new(LENGTH_M, TITANIUM.wave_speed(), velocity_gradient)
    }

    /// Wavenumber k_n = (2n−1)π/(2L) [1/m], n ≥ 1 (R 6.13).
    pub fn wavenumber(&self, n: usize) -> f64 {
        assert!(n >= 1, "modes are numbered from 1");
        (2 * n - 1) as f64 * PI / (2.0 * self.length)
    }

    /// Angular frequency ω_n = c k_n [rad/s] (R 6.13).
    pub fn angular_frequency(&self, n: usize) -> f64 {
        self.wave_speed * self.wavenumber(n)
    }

    /// Modal amplitude B_n = 16 K L² (−1)^{n+1} / ((2n−1)³ π³ c) \[m\] (problems.md R-P4; the
    /// thesis B_1 = 0.02941 "units" of R 6.14 is 2.941e-4 m read in cm).
    pub fn modal_amplitude(&self, n: usize) -> f64 {
        assert!(n >= 1, "modes are numbered from 1");
        let m = (2 * n - 1) as f64;
        let sign = if n % 2 == 1 { 1.0 } else { -1.0 };
        sign * 16.0 * self.velocity_gradient * self.length * self.length
            / (m * m * m * PI.powi(3) * self.wave_speed)
    }

    /// Fundamental period T_1 = 2π/ω_1 = 4L/c \[s\] (3.8075 µs for R-P4).
    pub fn period(&self) -> f64 {
        4.0 * self.length / self.wave_speed
    }

    /// Extended initial velocity g̃(s): triangle wave of period 4L, odd about 0, even about L,
    /// equal to K s on [0, L] \[m/s\].
    fn extended_velocity(&self, s: f64) -> f64 {
        let l = self.length;
        let s = s.rem_euclid(4.0 * l);
        let (s, sign) = if s > 2.0 * l {
            (4.0 * l - s, -1.0)
        } else {
            (s, 1.0)
        };
        let tri = if s <= l { s } else { 2.0 * l - s };
        sign * self.velocity_gradient * tri
    }

    /// Φ(s) = ∫_0^s g̃: even, 4L-periodic [m²/s].
    fn velocity_potential(&self, s: f64) -> f64 {
        let l = self.length;
        let s = s.rem_euclid(4.0 * l);
        let s = if s > 2.0 * l { 4.0 * l - s } else { s };
        let k = self.velocity_gradient;
        if s <= l {
            0.5 * k * s * s
        } else {
            let d = 2.0 * l - s;
            // KL² − K(2L − s)²/2: symmetric about s = L with Φ(2L) = K L².
            k * l * l - 0.5 * k * d * d
        }
    }

    /// Displacement u(x, t) \[m\]: the full modal series of problems.md R-P4 (R 6.13) summed in
    /// closed form, u = [Φ(x+ct) − Φ(x−ct)]/(2c).
    pub fn displacement(&self, x: f64, t: f64) -> f64 {
        let ct = self.wave_speed * t;
        (self.velocity_potential(x + ct) - self.velocity_potential(x - ct))
            / (2.0 * self.wave_speed)
    }

    /// Velocity ∂u/∂t = [g̃(x+ct) + g̃(x−ct)]/2 \[m/s\].
    pub fn velocity(&self, x: f64, t: f64) -> f64 {
        let ct = self.wave_speed * t;
        0.5 * (self.extended_velocity(x + ct) + self.extended_velocity(x - ct))
    }

    /// Strain ∂u/∂x = [g̃(x+ct) − g̃(x−ct)]/(2c) [-].
    pub fn strain(&self, x: f64, t: f64) -> f64 {
        let ct = self.wave_speed * t;
        (self.extended_velocity(x + ct) - self.extended_velocity(x - ct)) / (2.0 * self.wave_speed)
    }

    /// Truncated modal series Σ_{n ≤ modes} B_n sin(k_n x) sin(ω_n t) (R 6.13) \[m\]; use
    /// [`MODES_FOR_1E9`] modes for 1e-9 relative accuracy.
    pub fn displacement_modal(&self, x: f64, t: f64, modes: usize) -> f64 {
        (1..=modes)
            .map(|n| {
                self.modal_amplitude(n)
                    * (self.wavenumber(n) * x).sin()
                    * (self.angular_frequency(n) * t).sin()
            })
            .sum()
    }

    /// x positions in (0, L) where v(·,t) and ε(·,t) have kinks (x ± ct ≡ L mod 2L), sorted and
    /// bracketed by 0 and L.
    fn breakpoints(&self, t: f64) -> Vec<f64> {
        let l = self.length;
        let ct = self.wave_speed * t;
        let mut pts = vec![0.0, l];
        for shift in [ct, -ct] {
            // x = L + 2mL − shift for integer m, inside (0, L).
            let m_lo = ((shift - l) / (2.0 * l)).floor() as i64 - 1;
            for m in m_lo..=m_lo + 3 {
                let x = l + 2.0 * m as f64 * l - shift;
                if x > 0.0 && x < l {
                    pts.push(x);
                }
            }
        }
        pts.sort_by(|a, b| a.total_cmp(b));
        pts
    }

    /// ∫_0^L f(x)² dx for f piecewise linear between [`Self::breakpoints`]: two-point Gauss per
    /// piece, exact for the quadratic integrand.
    fn integral_of_square(&self, t: f64, f: impl Fn(f64) -> f64) -> f64 {
        let g = 0.5 / 3f64.sqrt();
        self.breakpoints(t)
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let (mid, half) = (0.5 * (a + b), b - a);
                let f1 = f(mid - g * half);
                let f2 = f(mid + g * half);
                0.5 * half * (f1 * f1 + f2 * f2)
            })
            .sum()
    }

    /// Kinetic energy per unit area ∫_0^L ½ ρ v² dx [J/m²], by exact piecewise quadrature of the
    /// closed-form velocity.
    pub fn kinetic_energy(&self, t: f64, density: f64) -> f64 {
        0.5 * density * self.integral_of_square(t, |x| self.velocity(x, t))
    }

    /// Internal (strain) energy per unit area ∫_0^L ½ M ε² dx with M = ρ c² [J/m²], by exact
    /// piecewise quadrature of the closed-form strain.
    pub fn internal_energy(&self, t: f64, density: f64) -> f64 {
        let modulus = density * self.wave_speed * self.wave_speed;
        0.5 * modulus * self.integral_of_square(t, |x| self.strain(x, t))
    }

    /// Both energies at time t (see [`Self::kinetic_energy`], [`Self::internal_energy`]).
    pub fn energies(&self, t: f64, density: f64) -> RodEnergies {
        RodEnergies {
            kinetic: self.kinetic_energy(t, density),
            internal: self.internal_energy(t, density),
        }
    }

    /// Modal-series energies: mode n carries ¼ ρ L ω_n² B_n² split as cos²/sin²(ω_n t) between
    /// kinetic and internal energy (orthogonality of sin k_n x on [0, L]) [J/m²].
    pub fn energies_modal(&self, t: f64, density: f64, modes: usize) -> RodEnergies {
        let mut e = RodEnergies {
            kinetic: 0.0,
            internal: 0.0,
        };
        for n in 1..=modes {
            let w = self.angular_frequency(n);
            let en = 0.25 * density * self.length * (w * self.modal_amplitude(n)).powi(2);
            let (s, c) = (w * t).sin_cos();
            e.kinetic += en * c * c;
            e.internal += en * s * s;
        }
        e
    }

    /// Total energy per unit area = initial kinetic energy ρ K² L³ / 6 [J/m²].
    pub fn total_energy(&self, density: f64) -> f64 {
        density * self.velocity_gradient.powi(2) * self.length.powi(3) / 6.0
    }
}

/// Sample times 0, 0.05, …, 12.4 µs of the reference CSVs \[s\].
pub fn reference_times() -> Vec<f64> {
    (0..=248).map(|i| i as f64 * 5.0e-8).collect()
}

/// Mean period from successive same-direction zero crossings of a sampled signal \[s\].
///
/// Crossings are located by linear interpolation between samples; upward crossings (− → +) and
/// downward crossings (+ → −) are paired only with crossings of the same direction, and every
/// interval between consecutive same-direction crossings counts once in the mean. Samples that
/// are exactly 0 (or not finite) are skipped, so a signal starting at u = 0 does not produce a
/// spurious crossing at t = 0. Returns `None` when neither direction has two crossings.
pub fn zero_crossing_period(times: &[f64], values: &[f64]) -> Option<f64> {
    assert_eq!(times.len(), values.len(), "one value per time");
    let mut up = Vec::new();
    let mut down = Vec::new();
    // Index of the last sample with a non-zero value.
    let mut last: Option<usize> = None;
    for i in 0..values.len() {
        let v = values[i];
        if v == 0.0 || !v.is_finite() {
            continue;
        }
        if let Some(j) = last {
            let u = values[j];
            if u.signum() != v.signum() {
                let t = times[j] + (times[i] - times[j]) * u / (u - v);
                if v > 0.0 {
                    up.push(t);
                } else {
                    down.push(t);
                }
            }
        }
        last = Some(i);
    }
    let mut sum = 0.0;
    let mut count = 0usize;
    for list in [&up, &down] {
        for w in list.windows(2) {
            sum += w[1] - w[0];
            count += 1;
        }
    }
    (count > 0).then(|| sum / count as f64)
}

/// Largest |value| of a sampled signal, refined by a parabola through the largest sample and its
/// two neighbours (non-uniform spacing allowed) [unit of `values`]. 0 for an empty signal.
pub fn peak_amplitude(times: &[f64], values: &[f64]) -> f64 {
    assert_eq!(times.len(), values.len(), "one value per time");
    let Some((k, &peak)) = values
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_finite())
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
    else {
        return 0.0;
    };
    let peak = peak.abs();
    if k == 0 || k + 1 >= values.len() {
        return peak;
    }
    let (t0, t1, t2) = (times[k - 1], times[k], times[k + 1]);
    let (y0, y1, y2) = (values[k - 1].abs(), peak, values[k + 1].abs());
    // Divided differences of the interpolating parabola.
    let d01 = (y1 - y0) / (t1 - t0);
    let d12 = (y2 - y1) / (t2 - t1);
    let a = (d12 - d01) / (t2 - t0);
    // Not a maximum (or degenerate/NaN curvature): keep the sample value.
    if a.is_nan() || a >= 0.0 {
        return peak;
    }
    let b = d01 - a * (t0 + t1);
    let t_star = -b / (2.0 * a);
    if !(t0..=t2).contains(&t_star) {
        return peak;
    }
    let refined = y1 + d01 * (t_star - t1) + a * (t_star - t0) * (t_star - t1);
    refined.max(peak)
}

/// CSV text of u at [`STATIONS_M`] on [`reference_times`]: header
/// `time_s,u_2mm_m,u_3mm_m,u_6mm_m`, 13 significant digits.
pub fn displacement_csv(rod: &RodVibration) -> String {
    let mut out = String::from("time_s,u_2mm_m,u_3mm_m,u_6mm_m\n");
    for t in reference_times() {
        out.push_str(&format!("{t:.12e}"));
        for x in STATIONS_M {
            out.push_str(&format!(",{:.12e}", rod.displacement(x, t)));
        }
        out.push('\n');
    }
    out
}

/// CSV text of the energies per unit area on [`reference_times`]: header
/// `time_s,kinetic_j_per_m2,internal_j_per_m2`, 13 significant digits.
pub fn energies_csv(rod: &RodVibration, density: f64) -> String {
    let mut out = String::from("time_s,kinetic_j_per_m2,internal_j_per_m2\n");
    for t in reference_times() {
        let e = rod.energies(t, density);
        out.push_str(&format!(
            "{t:.12e},{:.12e},{:.12e}\n",
            e.kinetic, e.internal
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::reference_data_dir;

    fn thesis_rod() -> RodVibration {
        RodVibration::reveles_problem4(K_THESIS_PER_S)
    }

    /// Rod with the rounded problems.md wave speed c = 6303.4 m/s.
    fn rounded_rod() -> RodVibration {
        RodVibration::new(LENGTH_M, 6303.4, K_THESIS_PER_S)
    }

    #[test]
    fn titanium_constants_match_problem_md() {
        let m = TITANIUM.uniaxial_modulus();
        assert!((m / 179.99e9 - 1.0).abs() < 1e-4, "M = {m}");
        assert!((TITANIUM.wave_speed() / 6303.4 - 1.0).abs() < 2e-5);
        assert!((TITANIUM.bar_wave_speed() / 5060.3 - 1.0).abs() < 2e-5);
    }

    #[test]
    fn first_mode_amplitude_and_period() {
        let rod = rounded_rod();
        assert!((rod.modal_amplitude(1) / 2.9471e-4 - 1.0).abs() < 1e-4);
        assert!((rod.period() / 3.8075e-6 - 1.0).abs() < 1e-4);
        assert!((thesis_rod().period() / 3.8075e-6 - 1.0).abs() < 1e-4);
        // Bar speed would give 3.671e-4 m (problems.md R-P4, inconsistent with the thesis 2.941e-4).
        let bar = RodVibration::new(LENGTH_M, TITANIUM.bar_wave_speed(), K_THESIS_PER_S);
        assert!((bar.modal_amplitude(1) / 3.671e-4 - 1.0).abs() < 1e-3);
        assert!(rod.modal_amplitude(2) < 0.0);
    }

    #[test]
    fn clamped_end_stays_at_rest_and_free_end_is_stress_free() {
        let rod = thesis_rod();
        for i in 0..200 {
            let t = i as f64 * 0.0731e-6;
            assert!(rod.displacement(0.0, t).abs() < 1e-15 * rod.modal_amplitude(1));
            assert!(rod.velocity(0.0, t).abs() < 1e-9);
            assert!(rod.strain(LENGTH_M, t).abs() < 1e-15);
        }
    }

    #[test]
    fn initial_conditions() {
        let rod = thesis_rod();
        for i in 0..=30 {
            let x = i as f64 * SPACING_M;
            assert_eq!(rod.displacement(x, 0.0), 0.0);
            assert!((rod.velocity(x, 0.0) - K_THESIS_PER_S * x).abs() < 1e-9);
        }
    }

    #[test]
    fn quarter_period_free_end_equals_full_series_sum() {
        // At t = T/4 every sin(ω_n t) sin(k_n L) = (−1)^{n+1}, so u(L) = Σ|B_n| = K L²/(2c).
        let rod = rounded_rod();
        let t = rod.period() / 4.0;
        let exact = K_THESIS_PER_S * LENGTH_M * LENGTH_M / (2.0 * rod.wave_speed);
        assert!((rod.displacement(LENGTH_M, t) / exact - 1.0).abs() < 1e-12);
        let series = rod.displacement_modal(LENGTH_M, t, MODES_FOR_1E9);
        assert!((series / exact - 1.0).abs() < 1e-9);
        // One term only (R 6.14) overshoots the true free-end peak by 32/π³ − 1 = 3.2 %.
        assert!((rod.modal_amplitude(1) / exact - 32.0 / PI.powi(3)).abs() < 1e-12);
    }

    #[test]
    fn closed_form_equals_modal_series() {
        let rod = thesis_rod();
        let b1 = rod.modal_amplitude(1);
        for &x in &[0.0005, 0.002, 0.003, 0.0047, 0.006] {
            for i in 0..12 {
                let t = i as f64 * 1.037e-6;
                let closed = rod.displacement(x, t);
                let series = rod.displacement_modal(x, t, MODES_FOR_1E9);
                assert!((closed - series).abs() < 1e-9 * b1, "x {x} t {t}");
            }
        }
        // Velocity and strain against finite differences of the closed form.
        let (x, t) = (0.0037, 2.3e-6);
        let (dx, dt) = (1e-7, 1e-11);
        let v_fd = (rod.displacement(x, t + dt) - rod.displacement(x, t - dt)) / (2.0 * dt);
        let e_fd = (rod.displacement(x + dx, t) - rod.displacement(x - dx, t)) / (2.0 * dx);
        assert!((v_fd - rod.velocity(x, t)).abs() < 1e-6 * 600.0);
        assert!((e_fd - rod.strain(x, t)).abs() < 1e-6 * 0.1);
    }

    #[test]
    fn energy_is_conserved_and_matches_modal_energies() {
        let rod = thesis_rod();
        let rho = TITANIUM.density;
        let total = rod.total_energy(rho);
        assert!((total - 0.5 * rho * 1e10 * LENGTH_M.powi(3) / 3.0).abs() < 1e-12 * total);
        for i in 0..400 {
            let t = i as f64 * 0.0313e-6;
            let e = rod.energies(t, rho);
            assert!(
                ((e.kinetic + e.internal) / total - 1.0).abs() < 1e-9,
                "t {t}"
            );
        }
        for &t in &[0.0, 0.4e-6, 0.95e-6, 1.9e-6, 3.1e-6, 11.7e-6] {
            let e = rod.energies(t, rho);
            let m = rod.energies_modal(t, rho, 2000);
            assert!((e.kinetic - m.kinetic).abs() < 1e-9 * total, "t {t}");
            assert!((e.internal - m.internal).abs() < 1e-9 * total, "t {t}");
        }
        // All energy is strain energy at T/4 for every mode.
        let e = rod.energies(rod.period() / 4.0, rho);
        assert!(e.kinetic / total < 0.1);
    }

    #[test]
    fn period_and_amplitude_measurements() {
        let rod = thesis_rod();
        let times: Vec<f64> = (0..=1240).map(|i| i as f64 * 1e-8).collect();
        let u: Vec<f64> = times
            .iter()
            .map(|&t| rod.displacement(LENGTH_M, t))
            .collect();
        let period = zero_crossing_period(&times, &u).expect("three periods");
        // The free end of this exact solution crosses zero exactly every T/2 (triangle-like
        // motion of a clamped–free rod released from a linear velocity field).
        assert!((period / rod.period() - 1.0).abs() < 1e-4, "{period}");
        let amp = peak_amplitude(&times, &u);
        let exact = K_THESIS_PER_S * LENGTH_M * LENGTH_M / (2.0 * rod.wave_speed);
        assert!((amp / exact - 1.0).abs() < 1e-3, "{amp} vs {exact}");

        // Pure sine with a phase: period and amplitude.
        let s: Vec<f64> = times
            .iter()
            .map(|&t| 2.0 * (2.0 * PI * t / 3.3e-6 + 0.4).sin())
            .collect();
        assert!((zero_crossing_period(&times, &s).unwrap() / 3.3e-6 - 1.0).abs() < 1e-5);
        assert!((peak_amplitude(&times, &s) / 2.0 - 1.0).abs() < 1e-5);
        assert_eq!(zero_crossing_period(&times[..10], &s[..10]), None);
        assert_eq!(peak_amplitude(&[], &[]), 0.0);
    }

    fn compare_csv(path: &std::path::Path, generated: &str) {
        let stored = std::fs::read_to_string(path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
        let parse = |s: &str| -> (String, Vec<Vec<f64>>) {
            let mut lines = s.lines();
            let header = lines.next().unwrap_or_default().to_string();
            let rows = lines
                .filter(|l| !l.trim().is_empty())
                .map(|l| {
                    l.split(',')
                        .map(|v| v.trim().parse::<f64>().unwrap())
                        .collect()
                })
                .collect();
            (header, rows)
        };
        let (h1, a) = parse(&stored);
        let (h2, b) = parse(generated);
        assert_eq!(h1, h2, "{}", path.display());
        assert_eq!(a.len(), b.len(), "{}", path.display());
        let cols = a[0].len();
        for c in 0..cols {
            let scale = b.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
            for (ra, rb) in a.iter().zip(&b) {
                assert!(
                    (ra[c] - rb[c]).abs() <= 1e-9 * rb[c].abs().max(scale * 1e-3),
                    "{} col {c}: {} vs {}",
                    path.display(),
                    ra[c],
                    rb[c]
                );
            }
        }
    }

    fn dir() -> std::path::PathBuf {
        reference_data_dir().join("R-P4")
    }

    #[test]
    fn stored_reference_csvs_have_not_drifted() {
        let thesis = thesis_rod();
        let linear = RodVibration::reveles_problem4(K_LINEAR_PER_S);
        compare_csv(
            &dir().join("displacement_K1e5.csv"),
            &displacement_csv(&thesis),
        );
        compare_csv(
            &dir().join("displacement_K1e3.csv"),
            &displacement_csv(&linear),
        );
        compare_csv(
            &dir().join("energies_K1e5.csv"),
            &energies_csv(&thesis, TITANIUM.density),
        );
    }
}
