//! Whole-model diagnostics: energies and momenta. Sums run sequentially in particle order so
//! they are bit-identical for any thread count.

use tlsph_math::Vector3;

/// Energies and momenta at one instant.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Diagnostics {
    /// Simulated time \[s\].
    pub time: f64,
    /// Σ ½ m |v|² \[J\].
    pub kinetic: f64,
    /// Σ m e \[J\] (R 4.12).
    pub internal: f64,
    /// Σ m v [kg m/s], padded to 3D.
    pub linear_momentum: Vector3,
    /// Σ m x × v about the origin [kg m²/s], padded to 3D.
    pub angular_momentum: Vector3,
    /// Energy booked for each declared effect (name, −∫ Σ f·v dt \[J\]): what the mechanism
    /// has taken out of the particles, stored (wall penalty) or dissipated (hourglass control);
    /// then one `boundary_<name>` per prescribed-velocity set (minus the work it has done on
    /// its particles), and `deleted_particles` with a failure model.
    pub effect_energies: Vec<(String, f64)>,
    /// Resultant force of each effect that reports one (walls: the reaction on the particles)
    /// \[N\], padded to 3D.
    pub effect_forces: Vec<(String, Vector3)>,
    /// Torque of each effect that reports one \[N m; 2D: N m per metre of thickness\]: a
    /// spinning wall's friction (`wall_<name>_friction`), the moment of its force on the
    /// particles about its spin axis ê = ω/|ω|, Σ m ê·((y − c) × a) over the touching surface
    /// points y (its normal force has no moment about that axis): positive while the wall
    /// drives the particles round with it; |ω| times it is the power the spin puts in.
    pub effect_torques: Vec<(String, f64)>,
    /// Moment vector of the force of each effect that reports one (a wall with
    /// `report_moment`: `wall_<name>` and `wall_<name>_friction`) about the wall's current
    /// point, Σ m (y − c) × a over the surface points y where the particles touch, in the last
    /// step \[N m\], padded to 3D (in 2D only z is non-zero).
    pub effect_moments: Vec<(String, Vector3)>,
    /// Force of each prescribed-velocity set (`boundary_<name>`) on its particles in the
    /// last step \[N\], padded to 3D: the reaction a grip or clamp exerts, every force on the
    /// held components included (numerics.md §13.2, see `prescribed.rs`).
    pub boundary_forces: Vec<(String, Vector3)>,
    /// Particles failed so far (out of every sum; their mass and momentum still count).
    pub failed_particles: usize,
}

impl Diagnostics {
    /// Kinetic + internal + booked effect energy \[J\]: constant up to time-integration error.
    pub fn total_energy(&self) -> f64 {
        self.kinetic + self.internal + self.effect_energies.iter().map(|(_, e)| e).sum::<f64>()
    }

    /// The resultant force of the effect called `name` (e.g. `"contact"`, a wall's name)
    /// \[N\], zero if no such effect reports one.
    pub fn effect_force(&self, name: &str) -> Vector3 {
        self.effect_forces
            .iter()
            .find(|(n, _)| n == name)
            .map_or(Vector3::zeros(), |(_, f)| *f)
    }

    /// The torque of the effect called `name` (a spinning wall's `wall_<name>_friction`)
    /// \[N m\], zero if no such effect reports one.
    pub fn effect_torque(&self, name: &str) -> f64 {
        self.effect_torques
            .iter()
            .find(|(n, _)| n == name)
            .map_or(0.0, |(_, t)| *t)
    }
}
