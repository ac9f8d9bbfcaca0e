//! Neighbour search for TLSPH: a uniform cell grid over a point set and compressed (CSR) lists
//! of all pairs closer than a radius. Geometry only; knows nothing about kernels or particles'
//! physics.
//!
//! The reference configuration's pair list (numerics.md §4.1: N_I = {J ≠ I : |X_I − X_J| < 2h0})
//! is built once with [`build_neighbour_list`]; current-configuration searches (contact,
//! numerics.md §12) can reuse [`CellGrid`] directly.
//!
//! Pairs are decided by the single floating-point predicate ‖x_j − x_i‖² < radius², evaluated the
//! same way by the grid search and by the [`brute_force_neighbour_list`] reference, so both give
//! identical lists, and a pair at exactly the radius is excluded.

#![warn(missing_docs)]

mod error;
mod grid;
mod list;
mod search;

pub use error::NeighbourError;
pub use grid::CellGrid;
pub use list::NeighbourList;
pub use search::{
    brute_force_neighbour_list, brute_force_neighbour_list_with_radii, build_neighbour_list,
    build_neighbour_list_with_radii,
};
pub use tlsph_math::Vector;
