//! SPH smoothing kernels W(r, h) with their first and second radial derivatives. Pure functions of
//! a distance; knows nothing about particles, neighbours or configurations.
//!
//! Three kernels are provided, each normalised so that ∫ W dV = 1 in its dimension
//! (numerics.md §1):
//!
//! * [`CubicSpline`]: the B-spline of numerics.md §1.1 (R 2.3; F 2.5–2.10), support 2h;
//! * [`WendlandC2`]: Wendland's (1995) C² function, support 2h;
//! * [`Gaussian`]: numerics.md §1.2 (R 2.1), truncated at 3h and renormalised.
//!
//! The solver chooses a kernel by [`KernelKind`], builds an [`AnyKernel`] once, and matches on it
//! only when bonds are built, never inside a pair loop.

#![warn(missing_docs)]

mod cubic_spline;
mod erf;
mod gaussian;
mod wendland_c2;

use std::fmt;
use std::str::FromStr;

pub use cubic_spline::CubicSpline;
pub use gaussian::Gaussian;
pub use tlsph_math::Vector;
pub use wendland_c2::WendlandC2;

/// A radially symmetric smoothing kernel W(r, h) with compact support.
///
/// All radial functions take a distance r ≥ 0 \[length\]; every one of them is exactly zero for
/// r ≥ [`support_radius`](Kernel::support_radius).
pub trait Kernel: Send + Sync {
    /// W(r) \[1/length^d\].
    fn value(&self, r: f64) -> f64;
    /// dW/dr \[1/length^(d+1)\].
    fn derivative(&self, r: f64) -> f64;
    /// d²W/dr² \[1/length^(d+2)\].
    fn second_derivative(&self, r: f64) -> f64;
    /// Radius beyond which W == 0 exactly \[length\].
    fn support_radius(&self) -> f64;
    /// Smoothing length h \[length\].
    fn smoothing_length(&self) -> f64;

    /// ∇_I W(|x_I − x_J|) for r_ij = x_I − x_J: W'(r) r_ij / r, and the zero vector at r = 0
    /// (numerics.md §0, R 2.68). Note ∇_J W = −∇_I W.
    #[inline]
    fn gradient<const D: usize>(&self, r_ij: &Vector<D>) -> Vector<D>
    where
        Self: Sized,
    {
        let r = r_ij.norm();
        if r > 0.0 {
            r_ij * (self.derivative(r) / r)
        } else {
            Vector::<D>::zeros()
        }
    }
}

/// Why a kernel could not be built or named.
#[derive(Debug, Clone, PartialEq)]
pub enum KernelError {
    /// The spatial dimension is not 1, 2 or 3.
    InvalidDimension {
        /// The dimension that was asked for.
        dimension: usize,
    },
    /// The smoothing length is not finite or not strictly positive.
    InvalidSmoothingLength {
        /// The smoothing length that was asked for \[length\].
        h: f64,
    },
    /// A kernel name that [`KernelKind::from_str`] does not know.
    UnknownKind {
        /// The name that was given.
        name: String,
    },
}

impl fmt::Display for KernelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KernelError::InvalidDimension { dimension } => {
                write!(f, "kernel dimension must be 1, 2 or 3, got {dimension}")
            }
            KernelError::InvalidSmoothingLength { h } => {
                write!(f, "smoothing length must be finite and > 0, got {h}")
            }
            KernelError::UnknownKind { name } => {
                write!(f, "unknown kernel `{name}`; accepted names: ")?;
                for (i, kind) in KernelKind::ALL.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{}", kind.name())?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for KernelError {}

/// Checks the arguments every kernel constructor takes.
pub(crate) fn validate(dimension: usize, h: f64) -> Result<(), KernelError> {
    if !(1..=3).contains(&dimension) {
        return Err(KernelError::InvalidDimension { dimension });
    }
    if !(h.is_finite() && h > 0.0) {
        return Err(KernelError::InvalidSmoothingLength { h });
    }
    Ok(())
}

/// Which kernel a scene asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelKind {
    /// [`CubicSpline`].
    CubicSpline,
    /// [`WendlandC2`].
    WendlandC2,
    /// [`Gaussian`].
    Gaussian,
}

impl KernelKind {
    /// Every kernel kind, in a fixed order.
    pub const ALL: [KernelKind; 3] = [
        KernelKind::CubicSpline,
        KernelKind::WendlandC2,
        KernelKind::Gaussian,
    ];

    /// The name used in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            KernelKind::CubicSpline => "cubic-spline",
            KernelKind::WendlandC2 => "wendland-c2",
            KernelKind::Gaussian => "gaussian",
        }
    }

    /// Builds the kernel for `dimension` (1, 2 or 3) and smoothing length `h` \[length\].
    pub fn build(self, dimension: usize, h: f64) -> Result<AnyKernel, KernelError> {
        Ok(match self {
            KernelKind::CubicSpline => AnyKernel::CubicSpline(CubicSpline::new(dimension, h)?),
            KernelKind::WendlandC2 => AnyKernel::WendlandC2(WendlandC2::new(dimension, h)?),
            KernelKind::Gaussian => AnyKernel::Gaussian(Gaussian::new(dimension, h)?),
        })
    }

    /// Support radius divided by h: 2 (cubic spline), 2 (Wendland C2), 3 (truncated Gaussian).
    pub fn support_factor(self) -> f64 {
        match self {
            KernelKind::CubicSpline => cubic_spline::SUPPORT_FACTOR,
            KernelKind::WendlandC2 => wendland_c2::SUPPORT_FACTOR,
            KernelKind::Gaussian => gaussian::SUPPORT_FACTOR,
        }
    }
}

impl fmt::Display for KernelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for KernelKind {
    type Err = KernelError;

    /// Parses one of the names returned by [`KernelKind::name`].
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        KernelKind::ALL
            .into_iter()
            .find(|kind| kind.name() == s)
            .ok_or_else(|| KernelError::UnknownKind { name: s.to_owned() })
    }
}

/// Any of the kernels of this crate, chosen at run time; [`Kernel`] is implemented by `match`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyKernel {
    /// [`CubicSpline`].
    CubicSpline(CubicSpline),
    /// [`WendlandC2`].
    WendlandC2(WendlandC2),
    /// [`Gaussian`].
    Gaussian(Gaussian),
}

impl AnyKernel {
    /// Which kernel this is.
    pub fn kind(&self) -> KernelKind {
        match self {
            AnyKernel::CubicSpline(_) => KernelKind::CubicSpline,
            AnyKernel::WendlandC2(_) => KernelKind::WendlandC2,
            AnyKernel::Gaussian(_) => KernelKind::Gaussian,
        }
    }

    /// The spatial dimension the kernel is normalised for.
    pub fn dimension(&self) -> usize {
        match self {
            AnyKernel::CubicSpline(k) => k.dimension(),
            AnyKernel::WendlandC2(k) => k.dimension(),
            AnyKernel::Gaussian(k) => k.dimension(),
        }
    }
}

impl From<CubicSpline> for AnyKernel {
    fn from(k: CubicSpline) -> Self {
        AnyKernel::CubicSpline(k)
    }
}

impl From<WendlandC2> for AnyKernel {
    fn from(k: WendlandC2) -> Self {
        AnyKernel::WendlandC2(k)
    }
}

impl From<Gaussian> for AnyKernel {
    fn from(k: Gaussian) -> Self {
        AnyKernel::Gaussian(k)
    }
}

/// Forwards one `Kernel` method to the wrapped kernel.
macro_rules! dispatch {
    ($self:ident, $k:ident => $e:expr) => {
        match $self {
            AnyKernel::CubicSpline($k) => $e,
            AnyKernel::WendlandC2($k) => $e,
            AnyKernel::Gaussian($k) => $e,
        }
    };
}

impl Kernel for AnyKernel {
    #[inline]
    fn value(&self, r: f64) -> f64 {
        dispatch!(self, k => k.value(r))
    }
    #[inline]
    fn derivative(&self, r: f64) -> f64 {
        dispatch!(self, k => k.derivative(r))
    }
    #[inline]
    fn second_derivative(&self, r: f64) -> f64 {
        dispatch!(self, k => k.second_derivative(r))
    }
    #[inline]
    fn support_radius(&self) -> f64 {
        dispatch!(self, k => k.support_radius())
    }
    #[inline]
    fn smoothing_length(&self) -> f64 {
        dispatch!(self, k => k.smoothing_length())
    }
}
