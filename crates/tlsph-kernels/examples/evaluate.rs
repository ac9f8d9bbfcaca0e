//! Prints W and dW/dr of the three kernels at a few q = r/h in 3D.
//!
//! Run with `cargo run -p tlsph-kernels --example evaluate`.

use tlsph_kernels::{Kernel, KernelKind};

fn main() {
    let h = 1.0;
    let qs = [0.0, 0.5, 2.0 / 3.0, 1.0, 1.5, 2.0, 2.5, 3.0];
    println!("3D kernels, h = {h}");
    for kind in KernelKind::ALL {
        let kernel = kind.build(3, h).expect("valid dimension and h");
        println!(
            "\n{} (support {} h)",
            kind.name(),
            kernel.support_radius() / h
        );
        println!("{:>8} {:>14} {:>14} {:>14}", "q", "W", "dW/dr", "d2W/dr2");
        for q in qs {
            let r = q * h;
            println!(
                "{:>8.4} {:>14.6e} {:>14.6e} {:>14.6e}",
                q,
                kernel.value(r),
                kernel.derivative(r),
                kernel.second_derivative(r)
            );
        }
    }
}
