//! Prints the two particle-contact laws against distance, then finds the candidate pairs of two
//! small discs about to touch and the contact force between them.
//!
//! Run with `cargo run -p tlsph-contact --example contact_laws`.

use tlsph_contact::{
    ContactCandidates, FrictionCoefficients, KernelKind, PenaltyLaw, PotentialLaw, Vector,
    DT_FACTOR, SKIN_FRACTION,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Two 2D steel-like bodies with spacing Δx = 1 mm and h = 1.2Δx.
    let (dx, h, youngs, modulus) = (1e-3, 1.2e-3, 200e9, 270e9);

    // Potential law (numerics.md §12.2): a = 1, n = 4, d0 = Δx.
    let kernel = KernelKind::CubicSpline.build(2, h)?;
    let potential = PotentialLaw::new(kernel, dx, modulus * dx, 4.0, 0.0);
    // Penalty law (numerics.md §12.1): k_c = E d0, R = d0, μ = 0.2.
    let penalty = PenaltyLaw::new::<2>(1.0, 1.0, FrictionCoefficients::single(0.2), youngs, dx);
    let normal = Vector::<2>::new(0.0, 1.0);
    println!(
        "{:>6} {:>14} {:>14} {:>14}",
        "r/Δx", "potential f", "φ", "penalty f_n"
    );
    for step in 0..=10 {
        let r = dx * (0.5 + 0.05 * step as f64);
        let state = potential.evaluate(r);
        let f_n = penalty
            .force_on_partner(&(normal * r), &normal, &Vector::zeros(), 0.0)
            .map_or(0.0, |f| f[1]);
        println!(
            "{:>6.2} {:>14.4e} {:>14.4e} {:>14.4e}",
            r / dx,
            state.force,
            state.potential,
            f_n
        );
    }

    // Two discs of radius 5.5Δx, 0.8Δx apart at their closest particles.
    let disc = |centre: Vector<2>| {
        (-5..=5)
            .flat_map(move |i| (-5..=5).map(move |j| Vector::<2>::new(i as f64, j as f64)))
            .filter(|p| p.norm() <= 5.5)
            .map(move |p| centre + p * dx)
    };
    let positions: Vec<Vector<2>> = disc(Vector::zeros())
        .chain(disc(Vector::<2>::new(10.8 * dx, 0.0)))
        .collect();
    let n_a = positions.len() / 2;
    let body: Vec<u32> = (0..positions.len()).map(|i| u32::from(i >= n_a)).collect();
    let displacements = vec![Vector::zeros(); positions.len()];
    let masses = vec![7850.0 * dx * dx; positions.len()];

    let mut candidates =
        ContactCandidates::new(&body, |_| true, potential.d0(), SKIN_FRACTION * dx);
    candidates.refresh(&positions, &displacements, |pair| pair.across_bodies());
    let x = candidates.positions();
    let mut force = vec![Vector::<2>::zeros(); candidates.len()];
    let mut stiffness = vec![0.0; candidates.len()];
    let mut pairs = 0;
    for k in 0..candidates.len() {
        for &j in candidates.of(k) {
            pairs += 1;
            let d = x[k] - x[j as usize];
            let r = d.norm();
            if r < potential.d0() {
                let state = potential.evaluate(r);
                force[k] += d * (state.force / r);
                stiffness[k] += state.stiffness;
            }
        }
    }
    let (_, on_a) = candidates.totals(&[], &force);
    let vote = candidates.stiffness_time_step(&stiffness, &masses, DT_FACTOR);
    println!(
        "\n{} particles, {pairs} candidate pair entries; force on disc A {:.4e} N/m (x), time-step vote {:?}",
        positions.len(),
        on_a[0],
        vote.map(|(dt, i)| format!("{dt:.3e} s at particle {i}"))
    );
    Ok(())
}
