//! Builds neighbour lists for a random 3D point cloud and prints neighbour-count statistics.
//!
//! Run with `cargo run --release -p tlsph-neighbours --example point_cloud [n_points]`.

use std::time::Instant;

use tlsph_neighbours::{build_neighbour_list, Vector};

/// xorshift64*: deterministic, good enough for a demonstration cloud.
fn next_uniform(state: &mut u64) -> f64 {
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
}

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("n_points must be an integer"))
        .unwrap_or(100_000);
    // Unit mean spacing: a cube of edge n^(1/3).
    let edge = (n as f64).cbrt();
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let points: Vec<Vector<3>> = (0..n)
        .map(|_| {
            Vector::<3>::new(
                edge * next_uniform(&mut state),
                edge * next_uniform(&mut state),
                edge * next_uniform(&mut state),
            )
        })
        .collect();

    println!("{n} random points in a cube of edge {edge:.2} (mean spacing 1)");
    println!(
        "{:>8} {:>10} {:>6} {:>8} {:>6} {:>9} {:>10}",
        "radius", "pairs", "min", "mean", "max", "isolated", "time [ms]"
    );
    for radius in [1.0, 1.5, 2.4, 3.0] {
        let start = Instant::now();
        let list = build_neighbour_list(&points, radius).expect("finite points, positive radius");
        let elapsed = start.elapsed().as_secs_f64() * 1e3;
        let counts: Vec<usize> = (0..list.n_particles())
            .map(|i| list.neighbours_of(i).len())
            .collect();
        let min = counts.iter().min().copied().unwrap_or(0);
        let max = counts.iter().max().copied().unwrap_or(0);
        let mean = list.n_pairs() as f64 / n.max(1) as f64;
        let isolated = counts.iter().filter(|&&c| c == 0).count();
        println!(
            "{radius:>8.2} {:>10} {min:>6} {mean:>8.2} {max:>6} {isolated:>9} {elapsed:>10.1}",
            list.n_pairs()
        );
    }
    // Expected mean count in the bulk: (4/3)π r³ per unit density, less near the faces.
    println!(
        "bulk expectation at radius 2.4: {:.1}",
        4.0 / 3.0 * std::f64::consts::PI * 2.4f64.powi(3)
    );
}
