//! Compact support: exactly zero at and beyond the support radius, positive inside.

use tlsph_kernels::{Kernel, KernelKind};

use crate::all_kernels;

#[test]
fn exactly_zero_at_and_beyond_support() {
    for kernel in all_kernels() {
        let support = kernel.support_radius();
        assert_eq!(
            support,
            kernel.kind().support_factor() * kernel.smoothing_length()
        );
        for r in [
            support,
            support * (1.0 + 1e-15),
            1.5 * support,
            1e300,
            f64::INFINITY,
        ] {
            assert_eq!(kernel.value(r), 0.0, "{:?} r = {r}", kernel);
            assert_eq!(kernel.derivative(r), 0.0);
            assert_eq!(kernel.second_derivative(r), 0.0);
        }
    }
}

#[test]
fn positive_inside_support() {
    for kernel in all_kernels() {
        let support = kernel.support_radius();
        let just_inside = f64::from_bits(support.to_bits() - 1);
        let n = 1000;
        for r in (0..n)
            .map(|k| support * k as f64 / n as f64)
            .chain([just_inside])
        {
            assert!(kernel.value(r) > 0.0, "{:?} r = {r}", kernel);
        }
        // Monotone: W' ≤ 0 everywhere inside.
        for k in 0..n {
            let r = support * k as f64 / n as f64;
            assert!(kernel.derivative(r) <= 0.0);
        }
        if kernel.kind() != KernelKind::Gaussian {
            // Spline and Wendland go to zero continuously.
            assert!(kernel.value(just_inside) < 1e-30);
        }
    }
}

#[test]
fn value_at_origin_matches_the_normalisation_constants() {
    use std::f64::consts::PI;
    let h: f64 = 0.5;
    let cases = [
        (KernelKind::CubicSpline, 1, 2.0 / 3.0 / h),
        (KernelKind::CubicSpline, 2, 10.0 / (7.0 * PI) / h.powi(2)),
        (KernelKind::CubicSpline, 3, 1.0 / PI / h.powi(3)),
        (KernelKind::WendlandC2, 1, 5.0 / 8.0 / h),
        (KernelKind::WendlandC2, 2, 7.0 / (4.0 * PI) / h.powi(2)),
        (KernelKind::WendlandC2, 3, 21.0 / (16.0 * PI) / h.powi(3)),
    ];
    for (kind, dimension, want) in cases {
        let got = kind.build(dimension, h).unwrap().value(0.0);
        assert!((got - want).abs() <= 1e-14 * want, "{kind} {dimension}D");
    }
    // Gaussian: π^(−d/2) h^(−d) slightly raised by the truncation renormalisation.
    for dimension in 1..=3 {
        let raw = PI.powf(-0.5 * dimension as f64) / h.powi(dimension as i32);
        let got = KernelKind::Gaussian.build(dimension, h).unwrap().value(0.0);
        assert!(got > raw && got < raw * (1.0 + 5e-4));
    }
}
