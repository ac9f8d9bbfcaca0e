//! ∫ W dV = 1 for every kernel and dimension.
//!
//! The radial integral ∫_0^R W(r) S_d(r) dr with S_1 = 2, S_2 = 2πr, S_3 = 4πr² is computed by
//! composite 5-point Gauss–Legendre on each smooth piece of the kernel. On the cubic spline and
//! Wendland pieces the integrand is a polynomial of degree ≤ 7 in r, which 5-point Gauss–Legendre
//! integrates exactly, so the only error is round-off (~10⁻¹⁵); for the Gaussian 64 panels per
//! unit of q leave an error far below 10⁻¹². A relative tolerance of 10⁻⁶ is therefore loose for
//! the quadrature yet tight enough to catch any wrong constant: a missing π, a wrong power of h,
//! or forgetting the truncation renormalisation of the Gaussian (which is 1.2·10⁻⁴ in 2D and
//! 2.2·10⁻⁵ in 1D).
//! Gauss–Legendre nodes never touch the panel ends, so the jump of the truncated Gaussian at 3h
//! does not enter.

use tlsph_kernels::{Gaussian, Kernel, KernelKind};

use crate::{all_kernels, break_points};

/// 5-point Gauss–Legendre nodes and weights on [−1, 1].
const GL5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// ∫_a^b f with `panels` panels of 5-point Gauss–Legendre.
fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let width = (b - a) / panels as f64;
    let mut total = 0.0;
    for p in 0..panels {
        let mid = a + (p as f64 + 0.5) * width;
        for (x, w) in GL5 {
            total += w * f(mid + 0.5 * width * x);
        }
    }
    0.5 * width * total
}

/// Surface measure of the sphere of radius r in `dimension` dimensions.
fn shell(dimension: usize, r: f64) -> f64 {
    match dimension {
        1 => 2.0,
        2 => 2.0 * std::f64::consts::PI * r,
        _ => 4.0 * std::f64::consts::PI * r * r,
    }
}

fn mass(kernel: &impl Kernel, kind: KernelKind, dimension: usize) -> f64 {
    let h = kernel.smoothing_length();
    break_points(kind)
        .windows(2)
        .map(|piece| {
            integrate(
                |r| kernel.value(r) * shell(dimension, r),
                piece[0] * h,
                piece[1] * h,
                64,
            )
        })
        .sum()
}

#[test]
fn every_kernel_integrates_to_one() {
    for kernel in all_kernels() {
        let m = mass(&kernel, kernel.kind(), kernel.dimension());
        assert!(
            (m - 1.0).abs() < 1e-6,
            "{} in {}D, h = {}: ∫W dV = {m}",
            kernel.kind().name(),
            kernel.dimension(),
            kernel.smoothing_length()
        );
    }
}

#[test]
fn quadrature_resolves_the_gaussian_truncation() {
    // Without renormalisation the truncated 2D Gaussian would hold 1 − e^(−9); check that the
    // quadrature really sees the difference the renormalisation makes.
    let kernel = Gaussian::new(2, 1.0).unwrap();
    let raw = mass(&kernel, KernelKind::Gaussian, 2) * (1.0 - (-9.0f64).exp());
    assert!((raw - 1.0).abs() > 1e-4);
}
