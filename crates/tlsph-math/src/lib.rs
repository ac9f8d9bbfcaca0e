//! Dimension aliases and tensor helpers shared by every TLSPH crate. Pure maths; no physics.
//!
//! Particles live in `D` = 1, 2 or 3 spatial dimensions. Material models always see full
//! 3x3 tensors: a `D`x`D` deformation gradient is embedded with identity padding
//! (1D = uniaxial strain, 2D = plane strain, numerics.md §0), and a 3x3 stress is projected
//! back onto the `D`x`D` block the momentum equation needs.

pub use nalgebra;

/// A point or vector in `D` dimensions.
pub type Vector<const D: usize> = nalgebra::SVector<f64, D>;
/// A `D`x`D` second-order tensor (deformation gradient, its rate, PK1 block).
pub type Tensor<const D: usize> = nalgebra::SMatrix<f64, D, D>;
/// Full 3x3 tensor used by material models.
pub type Tensor3 = nalgebra::Matrix3<f64>;
/// 3-vector.
pub type Vector3 = nalgebra::Vector3<f64>;

/// Embeds a `D`x`D` deformation-like tensor into 3x3 with identity padding.
///
/// Used for F: the missing directions are unstretched (uniaxial strain in 1D, plane strain in 2D).
#[inline]
pub fn embed_with_identity<const D: usize>(m: &Tensor<D>) -> Tensor3 {
    let mut out = Tensor3::identity();
    for i in 0..D {
        for j in 0..D {
            out[(i, j)] = m[(i, j)];
        }
    }
    out
}

/// Embeds a `D`x`D` rate-like tensor into 3x3 with zero padding.
///
/// Used for Ḟ, L, D and W: nothing moves in the missing directions.
#[inline]
pub fn embed_with_zeros<const D: usize>(m: &Tensor<D>) -> Tensor3 {
    let mut out = Tensor3::zeros();
    for i in 0..D {
        for j in 0..D {
            out[(i, j)] = m[(i, j)];
        }
    }
    out
}

/// Leading `D`x`D` block of a 3x3 tensor.
#[inline]
pub fn project<const D: usize>(m: &Tensor3) -> Tensor<D> {
    Tensor::<D>::from_fn(|i, j| m[(i, j)])
}

/// Embeds a `D`-vector into 3D with zero padding.
#[inline]
pub fn vector_to_3d<const D: usize>(v: &Vector<D>) -> Vector3 {
    let mut out = Vector3::zeros();
    for i in 0..D {
        out[i] = v[i];
    }
    out
}

/// Outer product a ⊗ b, (a ⊗ b)_ij = a_i b_j.
#[inline]
pub fn outer<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> Tensor<D> {
    Tensor::<D>::from_fn(|i, j| a[i] * b[j])
}

/// Symmetric part ½(A + Aᵀ).
#[inline]
pub fn sym(m: &Tensor3) -> Tensor3 {
    (m + m.transpose()) * 0.5
}

/// Skew part ½(A − Aᵀ).
#[inline]
pub fn skew(m: &Tensor3) -> Tensor3 {
    (m - m.transpose()) * 0.5
}

/// Deviatoric part A − ⅓ tr(A) I.
#[inline]
pub fn deviator(m: &Tensor3) -> Tensor3 {
    m - Tensor3::identity() * (m.trace() / 3.0)
}

/// Von Mises equivalent stress σ̄ = sqrt(3/2 s:s) (numerics.md §0, R 6.20).
#[inline]
pub fn von_mises(stress: &Tensor3) -> f64 {
    let s = deviator(stress);
    (1.5 * s.component_mul(&s).sum()).sqrt()
}

/// Inverse of a 3x3 tensor, or `None` when it is singular or non-finite.
#[inline]
pub fn inverse3(m: &Tensor3) -> Option<Tensor3> {
    m.try_inverse()
        .filter(|inv| inv.iter().all(|x| x.is_finite()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn embedding_round_trips() {
        let m = Tensor::<2>::new(1.0, 2.0, 3.0, 4.0);
        let e = embed_with_identity(&m);
        assert_eq!(e[(2, 2)], 1.0);
        assert_eq!(project::<2>(&e), m);
        assert_eq!(embed_with_zeros(&m)[(2, 2)], 0.0);
    }

    #[test]
    fn von_mises_of_uniaxial_stress_is_the_stress() {
        let s = Tensor3::from_diagonal(&Vector3::new(7.0, 0.0, 0.0));
        assert_relative_eq!(von_mises(&s), 7.0, epsilon = 1e-12);
        // Hydrostatic stress has no deviator.
        assert_relative_eq!(von_mises(&Tensor3::identity()), 0.0, epsilon = 1e-12);
    }
}
