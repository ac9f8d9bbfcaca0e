//! Drives one copper material point (M-CU6, the R-P6 Taylor bar: elastic–plastic with linear
//! hardening) through uniaxial-strain compression and prints σ_xx, p, σ̄ and ε̄p.
use tlsph_materials::{LinearElastic, VonMisesPlasticity};
use tlsph_math::{deviator, von_mises, Tensor3};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // M-CU6 (problems.md §1): E 110 GPa, ν 0.343, σ_y 90 MPa, E_t 1.1 GPa.
    let elastic = LinearElastic::new(110e9, 0.343)?;
    let plastic = VonMisesPlasticity::from_tangent_modulus(90e6, 110e9, 1.1e9)?;
    let g = elastic.shear_modulus();

    let strain_rate = -1e4; // [1/s], compression
    let dt = 1e-8; // [s]
    let steps = 500; // total ε_xx = −5 %
    let mut d = Tensor3::zeros();
    d[(0, 0)] = strain_rate;

    let strain_at_yield = plastic.initial_yield_stress() / (2.0 * g);
    println!(
        "yield onset at eps_xx = -{strain_at_yield:.4e} (sigma_y/2G), HEL sigma_xx = -{:.4e} Pa",
        elastic.longitudinal_modulus() * strain_at_yield
    );
    println!(
        "{:>10} {:>14} {:>14} {:>14} {:>12}",
        "eps_xx", "sigma_xx [Pa]", "p [Pa]", "sigma_eq [Pa]", "eps_p"
    );
    let mut stress = Tensor3::zeros();
    let mut plastic_strain = 0.0;
    for i in 1..=steps {
        // Elastic Jaumann predictor, then radial return of the deviator (numerics.md §8.1, §8.4).
        let trial = elastic.jaumann_update(&stress, &d, &Tensor3::zeros(), dt);
        let pressure = -trial.trace() / 3.0;
        let r = plastic.return_map(&deviator(&trial), g, plastic_strain);
        stress = r.deviator - Tensor3::identity() * pressure;
        plastic_strain += r.plastic_strain_increment;
        if i % 25 == 0 || i == 1 {
            println!(
                "{:>10.4} {:>14.5e} {:>14.5e} {:>14.5e} {:>12.5e}",
                strain_rate * dt * i as f64,
                stress[(0, 0)],
                pressure,
                von_mises(&stress),
                plastic_strain
            );
        }
    }
    Ok(())
}
