//! KernelKind names and parsing, AnyKernel dispatch, and constructor errors.

use std::str::FromStr;

use tlsph_kernels::{
    AnyKernel, CubicSpline, Gaussian, Kernel, KernelError, KernelKind, Vector, WendlandC2,
};

#[test]
fn names_round_trip() {
    for kind in KernelKind::ALL {
        assert_eq!(KernelKind::from_str(kind.name()), Ok(kind));
        assert_eq!(kind.to_string(), kind.name());
    }
    assert_eq!(
        KernelKind::ALL.map(KernelKind::name),
        ["cubic-spline", "wendland-c2", "gaussian"]
    );
    assert_eq!(
        KernelKind::ALL.map(KernelKind::support_factor),
        [2.0, 2.0, 3.0]
    );
}

#[test]
fn unknown_name_lists_the_accepted_ones() {
    let err = "quintic".parse::<KernelKind>().unwrap_err();
    assert_eq!(
        err,
        KernelError::UnknownKind {
            name: "quintic".into()
        }
    );
    let message = err.to_string();
    for kind in KernelKind::ALL {
        assert!(message.contains(kind.name()), "{message}");
    }
    assert!(message.contains("quintic"));
}

#[test]
fn constructors_reject_bad_arguments() {
    for kind in KernelKind::ALL {
        for dimension in [0, 4] {
            assert_eq!(
                kind.build(dimension, 1.0),
                Err(KernelError::InvalidDimension { dimension })
            );
        }
        for h in [0.0, -1.0, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                kind.build(2, h),
                Err(KernelError::InvalidSmoothingLength { h })
            );
        }
        assert!(matches!(
            kind.build(2, f64::NAN),
            Err(KernelError::InvalidSmoothingLength { .. })
        ));
    }
    assert!(CubicSpline::new(0, 1.0).is_err());
    assert!(WendlandC2::new(1, -1.0).is_err());
    assert!(Gaussian::new(3, f64::NAN).is_err());
    let err: Box<dyn std::error::Error> = Box::new(KernelError::InvalidDimension { dimension: 7 });
    assert!(err.to_string().contains('7'));
}

#[test]
fn any_kernel_dispatches_to_the_concrete_kernel() {
    let h = 0.9;
    let concrete: [(AnyKernel, Box<dyn Kernel>); 3] = [
        (
            KernelKind::CubicSpline.build(3, h).unwrap(),
            Box::new(CubicSpline::new(3, h).unwrap()),
        ),
        (
            KernelKind::WendlandC2.build(3, h).unwrap(),
            Box::new(WendlandC2::new(3, h).unwrap()),
        ),
        (
            KernelKind::Gaussian.build(3, h).unwrap(),
            Box::new(Gaussian::new(3, h).unwrap()),
        ),
    ];
    for (any, direct) in &concrete {
        assert_eq!(any.dimension(), 3);
        assert_eq!(any.support_radius(), direct.support_radius());
        assert_eq!(any.smoothing_length(), direct.smoothing_length());
        for r in [0.0, 0.3, 1.0, 1.7, 2.5, 3.0] {
            assert_eq!(any.value(r), direct.value(r));
            assert_eq!(any.derivative(r), direct.derivative(r));
            assert_eq!(any.second_derivative(r), direct.second_derivative(r));
        }
        let x = Vector::<3>::new(0.2, -0.4, 0.1);
        let g = any.gradient(&x);
        let r = x.norm();
        assert_eq!(g, x * (direct.derivative(r) / r));
    }
    assert_eq!(
        AnyKernel::from(CubicSpline::new(2, 1.0).unwrap()).kind(),
        KernelKind::CubicSpline
    );
}
