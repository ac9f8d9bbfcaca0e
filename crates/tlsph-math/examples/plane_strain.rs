//! Embeds a 2D deformation gradient as plane strain and computes its Green-Lagrange strain.
use tlsph_math::{embed_with_identity, Tensor};

fn main() {
    let f2 = Tensor::<2>::new(1.01, 0.02, 0.0, 0.99);
    let f = embed_with_identity(&f2);
    let green_lagrange = (f.transpose() * f - tlsph_math::Tensor3::identity()) * 0.5;
    println!("F (plane strain) = {f}");
    println!("E = {green_lagrange}");
}
