//! Integration tests of tlsph-contact: each law against its own potential (finite differences)
//! and its defining formula, the surface test on a lattice, the candidate list against brute
//! force and across thread counts, the rigid plane and its friction.

mod candidates;
mod laws;
mod wall;
