//! Dimension aliases and tensor helpers shared by every TLSPH crate. Pure maths; no physics.
//!
//! Particles live in `D` = 1, 2 or 3 spatial dimensions. Material models always see full
//! 3x3 tensors: a `D`x`D` deformation gradient is embedded with identity padding
//! (1D = uniaxial strain, 2D = plane strain, numerics.md §0), and a 3x3 stress is projected
//! back onto the `D`x`D` block the momentum equation needs.
//!
//! [`PlaneReflections`] maps points and vectors across sets of coordinate planes: the mirror
//! images of symmetry models (numerics.md §13.1), shared by the solver's ghost particles and
//! the contact search.

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

/// The part of `v` across the unit vector `unit`, v − (v·n̂) n̂: a particle's offset from a
/// cylinder's axis or within a plane, a tangential velocity.
#[inline]
pub fn across<const D: usize>(v: &Vector<D>, unit: &Vector<D>) -> Vector<D> {
    v - unit * v.dot(unit)
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

/// Reflections across a set of coordinate planes x_a = c (the symmetry planes of
/// numerics.md §13.1), indexed by a mask of planes (bit k: plane k; mask 0 is the identity).
/// Across the planes of a mask a point maps to x_a → 2c − x_a and a vector to M v with the
/// diagonal M = diag(s), s_a = −1 along the normal of each plane in the mask. Several masks
/// reach the corner images where planes meet (a quarter model's corner ghost: mask 0b11).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PlaneReflections<const D: usize> {
    /// (normal axis, position) of each plane.
    planes: Vec<(usize, f64)>,
    /// Diagonal of M for every mask.
    signs: Vec<Vector<D>>,
}

impl<const D: usize> PlaneReflections<D> {
    /// The planes x_axis = position; `None` if an axis does not exist in `D` dimensions, a
    /// position is not finite or there are more than 8 planes.
    pub fn new(planes: impl IntoIterator<Item = (usize, f64)>) -> Option<Self> {
        let planes: Vec<(usize, f64)> = planes.into_iter().collect();
        if planes.len() > 8 || planes.iter().any(|&(a, c)| a >= D || !c.is_finite()) {
            return None;
        }
        let signs = (0..1usize << planes.len())
            .map(|mask| {
                let mut s = Vector::<D>::repeat(1.0);
                for (k, &(axis, _)) in planes.iter().enumerate() {
                    if mask & (1 << k) != 0 {
                        s[axis] = -s[axis];
                    }
                }
                s
            })
            .collect();
        Some(Self { planes, signs })
    }

    /// Whether there are no planes.
    pub fn is_empty(&self) -> bool {
        self.planes.is_empty()
    }

    /// The masks of the non-empty plane sets, 1 .. 2^planes.
    pub fn masks(&self) -> std::ops::Range<u32> {
        1..self.signs.len().max(1) as u32
    }

    /// Diagonal s of the reflection M of `mask`.
    #[inline]
    pub fn signs(&self, mask: u32) -> Vector<D> {
        self.signs[mask as usize]
    }

    /// Diagonal of M for every mask (index = mask; 0: the identity).
    pub fn sign_table(&self) -> &[Vector<D>] {
        &self.signs
    }

    /// Image of the point `x` across every plane in `mask`: x_a → 2c − x_a.
    #[inline]
    pub fn point(&self, x: &Vector<D>, mask: u32) -> Vector<D> {
        let mut image = *x;
        for (k, &(axis, position)) in self.planes.iter().enumerate() {
            if mask & (1 << k) != 0 {
                image[axis] = 2.0 * position - image[axis];
            }
        }
        image
    }

    /// Image M v of the vector `v` (a velocity, a normal) across every plane in `mask`.
    #[inline]
    pub fn vector(&self, v: &Vector<D>, mask: u32) -> Vector<D> {
        v.component_mul(&self.signs[mask as usize])
    }

    /// Whether `x` lies closer than `reach` to every plane in `mask`: only then can its
    /// image across them come within `reach` of a point on the same side of the planes.
    #[inline]
    pub fn within(&self, x: &Vector<D>, mask: u32, reach: f64) -> bool {
        self.planes
            .iter()
            .enumerate()
            .all(|(k, &(axis, position))| {
                mask & (1 << k) == 0 || (x[axis] - position).abs() < reach
            })
    }
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
    fn the_part_across_a_unit_vector_is_normal_to_it() {
        let n = Vector3::new(0.0, 0.6, 0.8);
        let v = Vector3::new(1.0, 2.0, -3.0);
        let t = across(&v, &n);
        assert_relative_eq!(t.dot(&n), 0.0, epsilon = 1e-15);
        // v·n̂ = −1.2: v = t + (−1.2) n̂.
        assert_relative_eq!(t, Vector3::new(1.0, 2.72, -2.04), epsilon = 1e-15);
    }

    #[test]
    fn von_mises_of_uniaxial_stress_is_the_stress() {
        let s = Tensor3::from_diagonal(&Vector3::new(7.0, 0.0, 0.0));
        assert_relative_eq!(von_mises(&s), 7.0, epsilon = 1e-12);
        // Hydrostatic stress has no deviator.
        assert_relative_eq!(von_mises(&Tensor3::identity()), 0.0, epsilon = 1e-12);
    }

    #[test]
    fn reflections_are_involutions_and_compose_at_corners() {
        let m = PlaneReflections::<3>::new([(0, 1.0), (1, -2.0)]).unwrap();
        assert_eq!(m.masks(), 1..4);
        let x = Vector::<3>::new(1.5, -1.0, 7.0);
        // Across x = 1: 0.5; across y = −2: −3; the corner image takes both.
        assert_eq!(m.point(&x, 0b01), Vector::<3>::new(0.5, -1.0, 7.0));
        assert_eq!(m.point(&x, 0b10), Vector::<3>::new(1.5, -3.0, 7.0));
        assert_eq!(m.point(&x, 0b11), Vector::<3>::new(0.5, -3.0, 7.0));
        for mask in 0..4 {
            assert_eq!(m.point(&m.point(&x, mask), mask), x);
            // An isometry: distances to images are the distances of images.
            let y = Vector::<3>::new(2.0, 0.5, 6.0);
            assert_relative_eq!(
                (m.point(&x, mask) - y).norm(),
                (x - m.point(&y, mask)).norm(),
                epsilon = 1e-14
            );
        }
        let v = Vector::<3>::new(1.0, 2.0, 3.0);
        assert_eq!(m.vector(&v, 0b11), Vector::<3>::new(-1.0, -2.0, 3.0));
        // Within 1 of both planes is needed for the corner.
        assert!(m.within(&x, 0b01, 1.0));
        assert!(!m.within(&x, 0b11, 1.0));
        assert!(m.within(&x, 0b11, 1.01));
        assert!(PlaneReflections::<2>::new([(2, 0.0)]).is_none());
        assert!(PlaneReflections::<2>::new([(0, f64::NAN)]).is_none());
        assert!(PlaneReflections::<2>::new([]).unwrap().masks().is_empty());
    }
}
