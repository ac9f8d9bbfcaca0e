//! Adiabatic heating of a material point from its internal energy (numerics.md §8.5).
//! Pointwise only.

/// Adiabatic temperature rise ΔT = (e − e0)/c_v \[K\] from the specific internal energy gained
/// since the reference state, e − e0 \[J/kg\] (typically the plastic work per unit mass), and
/// the specific heat c_v \[J/(kg K)\] (numerics.md §8.5 `[C]`): T = T_room + ΔT is the temperature
/// entering the Johnson–Cook thermal factor.
#[inline]
pub fn adiabatic_temperature_rise(plastic_work_per_mass: f64, specific_heat: f64) -> f64 {
    debug_assert!(specific_heat > 0.0);
    plastic_work_per_mass / specific_heat
}
