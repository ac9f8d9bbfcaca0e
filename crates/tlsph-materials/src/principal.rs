//! Principal values of symmetric 3x3 tensors, shared by the failure and softening models.
//! Pure maths on one point.

use tlsph_math::{sym, Tensor3};

/// Largest principal value of the symmetric part of `t` (e.g. σ1 of a Cauchy stress, tension
/// positive, or ε_max of a strain; numerics.md §8.9, §9.1–9.2).
#[inline]
pub fn max_principal_value(t: &Tensor3) -> f64 {
    sym(t).symmetric_eigenvalues().max()
}

/// Splits the symmetric part of `t` spectrally and returns its positive part
/// Σ_{λi > 0} λi nᵢ⊗nᵢ (numerics.md §9.1, the tensile part of the stress).
#[inline]
pub(crate) fn positive_part(t: &Tensor3) -> Tensor3 {
    let eigen = sym(t).symmetric_eigen();
    let mut out = Tensor3::zeros();
    for (i, &value) in eigen.eigenvalues.iter().enumerate() {
        if value > 0.0 {
            let n = eigen.eigenvectors.column(i);
            out += n * n.transpose() * value;
        }
    }
    out
}
