//! Drives one material point of steel through uniaxial strain with both stress updates.
use tlsph_materials::LinearElastic;
use tlsph_math::Tensor3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steel = LinearElastic::new(210e9, 0.3)?;
    let strain_rate = 100.0; // [1/s]
    let dt = 1e-6; // [s]
    let mut cauchy = Tensor3::zeros();
    let mut d = Tensor3::zeros();
    d[(0, 0)] = strain_rate;
    for _ in 0..100 {
        cauchy = steel.jaumann_update(&cauchy, &d, &Tensor3::zeros(), dt);
    }
    let mut e = Tensor3::zeros();
    e[(0, 0)] = strain_rate * dt * 100.0;
    println!("rate form  sigma_xx = {:.4e} Pa", cauchy[(0, 0)]);
    println!(
        "PK2 (SVK)  S_xx     = {:.4e} Pa",
        steel.second_piola_kirchhoff(&e)[(0, 0)]
    );
    println!(
        "longitudinal modulus M = {:.4e} Pa",
        steel.longitudinal_modulus()
    );
    Ok(())
}
