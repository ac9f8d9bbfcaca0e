//! Errors of the neighbour search. Data only.

use std::fmt;

/// Why a cell grid or neighbour list could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum NeighbourError {
    /// A point has a NaN or infinite coordinate.
    NonFiniteCoordinate {
        /// Index of the first offending point.
        index: usize,
    },
    /// The search radius (or cell size) is not finite or not strictly positive.
    InvalidRadius {
        /// The radius that was given \[length\].
        radius: f64,
    },
    /// More points than `u32` indices can address (neighbour indices are stored as `u32`).
    TooManyPoints {
        /// The number of points that was given.
        n_points: usize,
    },
    /// The bounding box of the points is so large that its extent overflows `f64`.
    BoundingBoxOverflow {
        /// The axis whose extent is not finite.
        axis: usize,
    },
}

impl fmt::Display for NeighbourError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NeighbourError::NonFiniteCoordinate { index } => {
                write!(f, "point {index} has a non-finite coordinate")
            }
            NeighbourError::InvalidRadius { radius } => {
                write!(
                    f,
                    "search radius / cell size must be finite and > 0, got {radius}"
                )
            }
            NeighbourError::TooManyPoints { n_points } => write!(
                f,
                "{n_points} points exceed the {} a u32-indexed neighbour list can hold",
                u32::MAX
            ),
            NeighbourError::BoundingBoxOverflow { axis } => write!(
                f,
                "the bounding box extent along axis {axis} overflows f64; coordinates are too far apart"
            ),
        }
    }
}

impl std::error::Error for NeighbourError {}
