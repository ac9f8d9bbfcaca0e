//! Analytic and converged reference solutions used by the problem modules.
pub mod plate_impact;
pub mod rod_vibration;
pub mod taylor_impact;
