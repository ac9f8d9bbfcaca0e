//! Named per-particle output quantities (probes, frames). Stress is Cauchy, tension positive.

use std::fmt;
use std::str::FromStr;

/// A scalar quantity that can be sampled at a particle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ParticleField {
    /// Cauchy stress component σ_ij \[Pa\] (i, j in 0..3; plane-strain/uniaxial-strain
    /// out-of-plane components included).
    Stress(usize, usize),
    /// Pressure p = −tr σ / 3 \[Pa\] (compression positive, numerics.md §0).
    Pressure,
    /// Von Mises stress sqrt(3/2 s:s) \[Pa\] (R 6.20).
    VonMises,
    /// Velocity component \[m/s\].
    Velocity(usize),
    /// Displacement component u = x − X \[m\].
    Displacement(usize),
    /// Current position component x \[m\].
    Position(usize),
    /// Current density ρ = ρ0 / det F \[kg/m³\] (R 4.9).
    Density,
    /// det F.
    Jacobian,
    /// Specific internal energy \[J/kg\].
    InternalEnergy,
    /// Effective plastic strain ε̄p (0 in elastic bodies).
    PlasticStrain,
    /// Temperature \[K\] (bodies with adiabatic heating only).
    Temperature,
    /// Damage D (Johnson–Cook, Peerlings, Grady–Kipp; the larger of the two where a material
    /// has a softening law and a failure criterion) or 1 once failed; 0 in bodies without a
    /// failure or damage model.
    Damage,
    /// The damage D of the material's softening `damage` law alone (Peerlings, Grady–Kipp;
    /// numerics.md §9.1–9.2), or 1 once failed; 0 in bodies without one. Differs from
    /// [`ParticleField::Damage`] only where a material also has a failure criterion.
    SofteningDamage,
    /// The damage D of the material's failure criterion alone (Johnson–Cook D = Σ Δε̄p/ε_f,
    /// numerics.md §8.6; 0 for the other criteria until the particle fails), or 1 once
    /// failed; 0 in bodies without one. Differs from [`ParticleField::Damage`] only where a
    /// material also has a softening law.
    FailureDamage,
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl ParticleField {
    /// Every field name accepted by [`FromStr`], for error messages and docs.
    pub const NAMES: &'static [&'static str] = &[
        "stress_xx",
        "stress_yy",
        "stress_zz",
        "stress_xy",
        "stress_yz",
        "stress_xz",
        "pressure",
        "von_mises",
        "velocity_x",
        "velocity_y",
        "velocity_z",
        "displacement_x",
        "displacement_y",
        "displacement_z",
        "position_x",
        "position_y",
        "position_z",
        "density",
        "jacobian",
        "internal_energy",
        "plastic_strain",
        "temperature",
        "damage",
        "softening_damage",
        "failure_damage",
    ];

    /// Whether the field exists in a `dimension`-D run (vector components beyond the
    /// dimension do not; all stress components do, as plane/uniaxial strain keeps them).
    pub fn exists_in(self, dimension: usize) -> bool {
        match self {
            ParticleField::Velocity(k)
            | ParticleField::Displacement(k)
            | ParticleField::Position(k) => k < dimension,
            _ => true,
        }
    }
}

impl fmt::Display for ParticleField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ParticleField::Stress(i, j) => write!(f, "stress_{}{}", AXES[i.min(j)], AXES[i.max(j)]),
            ParticleField::Pressure => f.write_str("pressure"),
            ParticleField::VonMises => f.write_str("von_mises"),
            ParticleField::Velocity(k) => write!(f, "velocity_{}", AXES[k]),
            ParticleField::Displacement(k) => write!(f, "displacement_{}", AXES[k]),
            ParticleField::Position(k) => write!(f, "position_{}", AXES[k]),
            ParticleField::Density => f.write_str("density"),
            ParticleField::Jacobian => f.write_str("jacobian"),
            ParticleField::InternalEnergy => f.write_str("internal_energy"),
            ParticleField::PlasticStrain => f.write_str("plastic_strain"),
            ParticleField::Temperature => f.write_str("temperature"),
            ParticleField::Damage => f.write_str("damage"),
            ParticleField::SofteningDamage => f.write_str("softening_damage"),
            ParticleField::FailureDamage => f.write_str("failure_damage"),
        }
    }
}

impl FromStr for ParticleField {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let axis = |c: char| "xyz".find(c);
        let unknown = || {
            format!(
                "unknown field `{s}`; known fields: {}",
                Self::NAMES.join(", ")
            )
        };
        let field = match s {
            "pressure" => ParticleField::Pressure,
            "von_mises" => ParticleField::VonMises,
            "density" => ParticleField::Density,
            "jacobian" => ParticleField::Jacobian,
            "internal_energy" => ParticleField::InternalEnergy,
            "plastic_strain" => ParticleField::PlasticStrain,
            "temperature" => ParticleField::Temperature,
            "damage" => ParticleField::Damage,
            "softening_damage" => ParticleField::SofteningDamage,
            "failure_damage" => ParticleField::FailureDamage,
            _ => {
                let (prefix, suffix) = s.rsplit_once('_').ok_or_else(unknown)?;
                let chars: Vec<char> = suffix.chars().collect();
                match (prefix, chars.as_slice()) {
                    ("stress", [a, b]) => match (axis(*a), axis(*b)) {
                        (Some(i), Some(j)) => ParticleField::Stress(i.min(j), i.max(j)),
                        _ => return Err(unknown()),
                    },
                    ("velocity", [a]) => ParticleField::Velocity(axis(*a).ok_or_else(unknown)?),
                    ("displacement", [a]) => {
                        ParticleField::Displacement(axis(*a).ok_or_else(unknown)?)
                    }
                    ("position", [a]) => ParticleField::Position(axis(*a).ok_or_else(unknown)?),
                    _ => return Err(unknown()),
                }
            }
        };
        Ok(field)
    }
}
