//! Setup and step errors. Every error names what went wrong and where (body, particle, step).

use std::fmt;

/// A model that cannot be simulated.
#[derive(Debug, Clone, PartialEq)]
pub enum SetupError {
    /// A configuration value is out of range.
    InvalidConfig {
        /// Field name, e.g. `cfl`.
        field: &'static str,
        /// What is wrong.
        message: String,
    },
    /// A body refers to a material index that does not exist.
    UnknownMaterial {
        /// Body name.
        body: String,
        /// The bad index.
        material: usize,
    },
    /// A body is unusable (no particles, inconsistent array lengths, bad spacing or volume).
    InvalidBody {
        /// Body name.
        body: String,
        /// What is wrong.
        message: String,
    },
    /// A boundary set is unusable.
    InvalidBoundary {
        /// Boundary name.
        boundary: String,
        /// What is wrong.
        message: String,
    },
    /// The kernel could not be built.
    Kernel(String),
    /// The neighbour search failed (e.g. a non-finite coordinate).
    Neighbours {
        /// Body name.
        body: String,
        /// Message from the search.
        message: String,
    },
}

impl fmt::Display for SetupError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SetupError::InvalidConfig { field, message } => write!(f, "{field}: {message}"),
            SetupError::UnknownMaterial { body, material } => {
                write!(
                    f,
                    "body `{body}` refers to material #{material}, which does not exist"
                )
            }
            SetupError::InvalidBody { body, message } => write!(f, "body `{body}`: {message}"),
            SetupError::InvalidBoundary { boundary, message } => {
                write!(f, "boundary `{boundary}`: {message}")
            }
            SetupError::Kernel(message) => write!(f, "kernel: {message}"),
            SetupError::Neighbours { body, message } => {
                write!(f, "neighbour search for body `{body}`: {message}")
            }
        }
    }
}

impl std::error::Error for SetupError {}

/// A step that could not be completed; the state before the step is left untouched where
/// possible, and everything recorded so far stays valid.
#[derive(Debug, Clone, PartialEq)]
pub enum StepError {
    /// A value became NaN or infinite.
    NonFinite {
        /// Step number.
        step: u64,
        /// Simulated time \[s\].
        time: f64,
        /// Body name.
        body: String,
        /// Particle index within the body.
        particle: usize,
        /// Field that is non-finite, e.g. `stress` or `velocity`.
        field: &'static str,
    },
    /// The deformation gradient of a particle lost positive determinant (inversion).
    Inverted {
        /// Step number.
        step: u64,
        /// Simulated time \[s\].
        time: f64,
        /// Body name.
        body: String,
        /// Particle index within the body.
        particle: usize,
        /// det F.
        jacobian: f64,
    },
    /// The stable time step came out zero or not a number, so the run cannot advance (e.g. a
    /// speed whose square overflows, or a contact stiffness that does). Without this error the
    /// run would look finished.
    TimeStepCollapse {
        /// Step number.
        step: u64,
        /// Simulated time \[s\].
        time: f64,
        /// The particle that set the limit, when one did (not an effect's vote).
        particle: Option<LimitingParticle>,
        /// The step the stability limit gave.
        dt: f64,
    },
    /// The reference configuration could not be rebuilt on the current positions (e.g. a
    /// particle crossed a symmetry plane).
    ReferenceUpdate {
        /// Step number.
        step: u64,
        /// Simulated time \[s\].
        time: f64,
        /// What went wrong.
        message: String,
    },
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StepError::NonFinite {
                step,
                time,
                body,
                particle,
                field,
            } => write!(
                f,
                "step {step} (t = {time:e}): {field} of particle {particle} of body `{body}` is not finite"
            ),
            StepError::Inverted {
                step,
                time,
                body,
                particle,
                jacobian,
            } => write!(
                f,
                "step {step} (t = {time:e}): particle {particle} of body `{body}` is inverted or crushed (det F = {jacobian:e} <= 0)"
            ),
            StepError::TimeStepCollapse {
                step,
                time,
                particle,
                dt,
            } => {
                write!(
                    f,
                    "step {step} (t = {time:e}): the stable time step is {dt:e}, so the run cannot advance"
                )?;
                match particle {
                    Some(LimitingParticle {
                        body,
                        particle,
                        speed,
                        sound_speed,
                    }) => {
                        write!(
                            f,
                            " (limited by particle {particle} of body `{body}`: speed {speed:e}, sound speed {sound_speed:e}"
                        )?;
                        if sound_speed.is_infinite() {
                            write!(f, ": compressed beyond its equation of state's limit")?;
                        }
                        write!(f, ")")
                    }
                    None => Ok(()),
                }
            }
            StepError::ReferenceUpdate {
                step,
                time,
                message,
            } => write!(
                f,
                "step {step} (t = {time:e}): the reference configuration could not be updated: {message}"
            ),
        }
    }
}

impl std::error::Error for StepError {}

/// The particle whose CFL limit h/(c + |v|) collapsed the time step.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitingParticle {
    /// Body name.
    pub body: String,
    /// Particle index within the body.
    pub particle: usize,
    /// |v| \[m/s\].
    pub speed: f64,
    /// Current sound speed c \[m/s\] (numerics.md §8.10).
    pub sound_speed: f64,
}
