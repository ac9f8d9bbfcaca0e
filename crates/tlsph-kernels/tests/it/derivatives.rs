//! First and second radial derivatives against central finite differences, gradients against
//! finite differences of W(|x|), and hand values from the literature.

use tlsph_kernels::{CubicSpline, Kernel, KernelKind, Vector};

use crate::{all_kernels, break_points};

/// Radii spread over (0, support) that stay at least `margin` away from break points.
fn sample_radii(kind: KernelKind, h: f64, margin: f64) -> Vec<f64> {
    let support = kind.support_factor() * h;
    let n = 401;
    (0..n)
        .map(|k| support * (k as f64 + 0.5) / n as f64)
        .filter(|r| {
            break_points(kind)
                .iter()
                .all(|b| (r - b * h).abs() > margin)
        })
        .collect()
}

#[test]
fn derivative_matches_finite_differences_of_value() {
    for kernel in all_kernels() {
        let h = kernel.smoothing_length();
        let delta = 1e-5 * h;
        // dW/dr scales like W(0)/h; the central difference errs by δ²/6·W''' ~ 10⁻¹¹ of that,
        // and round-off adds ε W / δ ~ 10⁻¹¹; 10⁻⁷ leaves room yet catches any wrong formula.
        let scale = kernel.value(0.0) / h;
        for r in sample_radii(kernel.kind(), h, 3.0 * delta) {
            let fd = (kernel.value(r + delta) - kernel.value(r - delta)) / (2.0 * delta);
            let exact = kernel.derivative(r);
            assert!(
                (fd - exact).abs() <= 1e-7 * scale,
                "{} {}D h={h} r={r}: dW/dr = {exact}, finite difference {fd}",
                kernel.kind().name(),
                kernel.dimension()
            );
        }
    }
}

#[test]
fn second_derivative_matches_finite_differences_of_derivative() {
    for kernel in all_kernels() {
        let h = kernel.smoothing_length();
        let delta = 1e-5 * h;
        let scale = kernel.value(0.0) / (h * h);
        for r in sample_radii(kernel.kind(), h, 3.0 * delta) {
            let fd = (kernel.derivative(r + delta) - kernel.derivative(r - delta)) / (2.0 * delta);
            let exact = kernel.second_derivative(r);
            assert!(
                (fd - exact).abs() <= 1e-7 * scale,
                "{} {}D h={h} r={r}: d²W/dr² = {exact}, finite difference {fd}",
                kernel.kind().name(),
                kernel.dimension()
            );
        }
    }
}

#[test]
fn derivatives_vanish_at_the_origin() {
    for kernel in all_kernels() {
        assert_eq!(kernel.derivative(0.0), 0.0);
        assert!(kernel.second_derivative(0.0) < 0.0);
    }
}

/// Gradient against the central difference of W(|x|) along each axis, in D dimensions.
fn check_gradient<const D: usize>(kernel: &impl Kernel, point: Vector<D>) {
    let h = kernel.smoothing_length();
    let delta = 1e-6 * h;
    let grad = kernel.gradient(&point);
    let scale = kernel.value(0.0) / h;
    for axis in 0..D {
        let mut plus = point;
        let mut minus = point;
        plus[axis] += delta;
        minus[axis] -= delta;
        let fd = (kernel.value(plus.norm()) - kernel.value(minus.norm())) / (2.0 * delta);
        assert!(
            (fd - grad[axis]).abs() <= 1e-6 * scale,
            "axis {axis}: gradient {} vs finite difference {fd}",
            grad[axis]
        );
    }
    // ∇_J W = −∇_I W (numerics.md §0).
    assert_eq!(kernel.gradient(&(-point)), -grad);
}

#[test]
fn gradient_matches_finite_differences_and_is_antisymmetric() {
    for kernel in all_kernels() {
        let h = kernel.smoothing_length();
        match kernel.dimension() {
            1 => {
                check_gradient(&kernel, Vector::<1>::new(0.7 * h));
                check_gradient(&kernel, Vector::<1>::new(-1.3 * h));
            }
            2 => {
                check_gradient(&kernel, Vector::<2>::new(0.3 * h, -0.5 * h));
                check_gradient(&kernel, Vector::<2>::new(1.1 * h, 0.6 * h));
            }
            _ => {
                check_gradient(&kernel, Vector::<3>::new(0.3 * h, -0.5 * h, 0.2 * h));
                check_gradient(&kernel, Vector::<3>::new(-0.9 * h, 0.8 * h, 0.7 * h));
            }
        }
    }
}

#[test]
fn gradient_is_zero_at_zero_separation() {
    for kernel in all_kernels() {
        assert_eq!(kernel.gradient(&Vector::<1>::zeros()), Vector::<1>::zeros());
        assert_eq!(kernel.gradient(&Vector::<2>::zeros()), Vector::<2>::zeros());
        assert_eq!(kernel.gradient(&Vector::<3>::zeros()), Vector::<3>::zeros());
    }
}

#[test]
fn cubic_spline_hand_values_reveles_table_6_2() {
    // 1D, h = 0.024 (R-P3; Reveles Table 6.2, column "C"): |dW/dr| at the first and second
    // neighbour for Δx = 0.02. By hand: C_1/h² = (2/3)/0.024² = 1157.407; q = 5/6 gives
    // w' = −3q + 9/4 q² = −0.9375, so dW/dr = −1085.069; q = 5/3 gives w' = −3/4 (1/3)² so
    // dW/dr = −96.4506.
    let kernel = CubicSpline::new(1, 0.024).unwrap();
    let d1 = kernel.derivative(0.02);
    let d2 = kernel.derivative(0.04);
    assert!(d1 < 0.0 && d2 < 0.0);
    assert!((d1.abs() - 1085.06).abs() <= 0.01, "dW/dr(0.02) = {d1}");
    assert!((d1.abs() - 1085.06).abs() <= 1e-4 * 1085.06);
    assert!((d2.abs() - 96.45).abs() <= 0.01, "dW/dr(0.04) = {d2}");
    // The gradient with respect to I of a pair with x_I − x_J = −0.02 points along +x.
    let g = kernel.gradient(&Vector::<1>::new(-0.02));
    assert!((g[0] - 1085.069).abs() < 1e-3);
}

#[test]
fn cubic_spline_second_derivative_vanishes_at_two_thirds() {
    for dimension in 1..=3 {
        let h = 0.8;
        let kernel = CubicSpline::new(dimension, h).unwrap();
        let scale = kernel.value(0.0) / (h * h);
        let q = 2.0 / 3.0;
        assert!(kernel.second_derivative(q * h).abs() < 1e-12 * scale);
        // W' is smallest there: W'' < 0 before, > 0 after (numerics.md §1.1, §15).
        assert!(kernel.second_derivative(0.6 * h) < 0.0);
        assert!(kernel.second_derivative(0.7 * h) > 0.0);
        assert!(kernel.second_derivative(1.9 * h) > 0.0);
    }
}
