//! Integration tests of tlsph-kernels: normalisation, derivatives against finite differences,
//! compact support, gradients, hand values and the kind/error API.

mod api;
mod derivatives;
mod normalisation;
mod support;

use tlsph_kernels::{AnyKernel, KernelKind};

/// Every kernel in every dimension, with a smoothing length that is not 1 so that wrong powers of
/// h show up.
pub fn all_kernels() -> Vec<AnyKernel> {
    let mut out = Vec::new();
    for kind in KernelKind::ALL {
        for dimension in 1..=3 {
            for h in [0.37, 1.0, 2.5] {
                out.push(kind.build(dimension, h).unwrap());
            }
        }
    }
    out
}

/// Radial break points of a kernel's piecewise definition (where a higher derivative jumps), as
/// multiples of h.
pub fn break_points(kind: KernelKind) -> &'static [f64] {
    match kind {
        KernelKind::CubicSpline => &[0.0, 1.0, 2.0],
        KernelKind::WendlandC2 => &[0.0, 2.0],
        KernelKind::Gaussian => &[0.0, 3.0],
    }
}
