//! Symmetry planes by ghost (mirror) particles (numerics.md §13.1).
//!
//! A plane x_a = c reflects a point by M(x)_a = 2c − x_a and a vector or tensor by the
//! diagonal M = diag(s) with s_a = −1. Every real particle I within reach of the planes of a
//! set (mask) gets an image ghost(I, mask), appended to the particle arrays after the reals,
//! with X_g = M(X_I), u_g = M u_I (so x_g = M(x_I)), v_g = M v_I, σ_g = M σ_I M and the
//! parent's mass, volume and J. Ghosts are never integrated: their state is copied from their
//! parents before every evaluation that reads it.
//!
//! - Total-Lagrangian formulations: the ghosts and their bonds are built once in the reference
//!   configuration (`simulation::build_reference`), again at a reference update.
//! - Updated-Lagrangian SPH: particles move relative to the planes, so the ghosts are rebuilt
//!   from the current positions at every rebuild of the Verlet list ([`Ghosts::rebuild_current`]),
//!   for every particle within the list's search radius (support + skin) of a plane.

use crate::error::SetupError;
use crate::model::SymmetryPlane;
use crate::particles::Particles;
use rayon::prelude::*;
use tlsph_math::{PlaneReflections, Vector};

/// Symmetry ghosts: particle `first + g` mirrors real particle `parent[g]` with component
/// signs `signs[g]` (numerics.md §13.1: u_g = M u_p, v_g = M v_p, P_g = M P_p M).
#[derive(Debug, Clone, Default)]
pub(crate) struct Ghosts<const D: usize> {
    /// Index of the first ghost (the number of real particles).
    pub first: usize,
    /// Real parent of each ghost.
    pub parent: Vec<usize>,
    /// Reflection signs of each ghost (the diagonal of M).
    pub signs: Vec<Vector<D>>,
    /// Reflection mask of each ghost (bit k: plane k).
    pub mask: Vec<u32>,
    /// Ghost index of (real parent, mask): filled for the total-Lagrangian ghosts, whose bonds
    /// need the mirror images when particles fail; empty for the updated-Lagrangian ghosts,
    /// which no bond refers to.
    pub of: std::collections::HashMap<(usize, u32), usize>,
}

impl<const D: usize> crate::bonds::MirrorMap<D> for Ghosts<D> {
    fn mirror(&self, p: usize, j: usize) -> Option<(usize, usize, Vector<D>)> {
        if self.parent.is_empty() || j < self.first {
            return None;
        }
        let k = j - self.first;
        let image = *self.of.get(&(p, self.mask[k]))?;
        Some((self.parent[k], image, self.signs[k]))
    }
}

impl<const D: usize> Ghosts<D> {
    /// Index of the first ghost, or `n` when there are none.
    pub fn first_or(&self, n: usize) -> usize {
        if self.parent.is_empty() {
            n
        } else {
            self.first
        }
    }

    /// Mirrors a per-particle vector field (e.g. XSPH velocities) from the parents.
    pub fn mirror(&self, field: &mut [Vector<D>]) {
        if self.parent.is_empty() {
            return;
        }
        let (real, ghost) = field.split_at_mut(self.first);
        ghost.par_iter_mut().enumerate().for_each(|(g, x)| {
            *x = real[self.parent[g]].component_mul(&self.signs[g]);
        });
    }

    /// Mirrors displacements and velocities from the parents (gather per ghost).
    pub fn refresh_kinematics(&self, p: &mut Particles<D>) {
        self.mirror_two(&mut p.displacements, &mut p.velocities);
    }

    /// Mirrors velocities and accelerations from the parents: an effect that reads a
    /// neighbour's velocity at t^n (v − ½ kick a) sees the ghost's as its parent's.
    pub fn refresh_motion(&self, p: &mut Particles<D>) {
        self.mirror_two(&mut p.velocities, &mut p.accelerations);
    }

    /// Mirrors two per-particle vector fields from the parents in one gather.
    fn mirror_two(&self, a: &mut [Vector<D>], b: &mut [Vector<D>]) {
        if self.parent.is_empty() {
            return;
        }
        let (real_a, ghost_a) = a.split_at_mut(self.first);
        let (real_b, ghost_b) = b.split_at_mut(self.first);
        ghost_a
            .par_iter_mut()
            .zip(ghost_b.par_iter_mut())
            .enumerate()
            .for_each(|(g, (x, y))| {
                let (parent, signs) = (self.parent[g], self.signs[g]);
                *x = real_a[parent].component_mul(&signs);
                *y = real_b[parent].component_mul(&signs);
            });
    }

    /// Mirrors first Piola–Kirchhoff and Cauchy stress, F (M F M) and det F from the parents.
    pub fn refresh_stress(&self, p: &mut Particles<D>) {
        if self.parent.is_empty() {
            return;
        }
        let (real_p, ghost_p) = p.pk1.split_at_mut(self.first);
        let (real_s, ghost_s) = p.stress.split_at_mut(self.first);
        let (real_f, ghost_f) = p.deformation_gradient.split_at_mut(self.first);
        let (real_j, ghost_j) = p.jacobian.split_at_mut(self.first);
        ghost_p
            .par_iter_mut()
            .zip(ghost_s.par_iter_mut())
            .zip(ghost_f.par_iter_mut().zip(ghost_j.par_iter_mut()))
            .enumerate()
            .for_each(|(g, ((pk1, sigma), (f, j)))| {
                let (parent, signs) = (self.parent[g], self.signs[g]);
                // (M A M)_kl = s_k s_l A_kl for a diagonal reflection M = diag(s).
                *pk1 = real_p[parent].map_with_location(|k, l, x| x * signs[k] * signs[l]);
                *f = real_f[parent].map_with_location(|k, l, x| x * signs[k] * signs[l]);
                let sign = |k: usize| if k < D { signs[k] } else { 1.0 };
                *sigma = real_s[parent].map_with_location(|k, l, x| x * sign(k) * sign(l));
                *j = real_j[parent];
            });
    }

    /// Updated-Lagrangian ghosts at the current configuration: drops the ghosts in `p` (index
    /// `n_real` on) and appends ghost(I, mask) for every real I with `alive(I)` whose current
    /// position x_I lies within `reach` of every plane in the mask (corner images where planes
    /// meet), then copies the parents' state into them. With `reach` = support + skin of the
    /// Verlet list, every image that can come within the support of a real particle before the
    /// next rebuild exists: an image is at least as far from any real particle as its parent is
    /// from the plane, and no particle moves more than half the skin between rebuilds.
    /// Allocates only when the number of ghosts grows.
    pub fn rebuild_current(
        &mut self,
        p: &mut Particles<D>,
        n_real: usize,
        planes: &[SymmetryPlane],
        reach: f64,
        alive: impl Fn(usize) -> bool,
    ) {
        p.truncate(n_real);
        self.first = n_real;
        self.parent.clear();
        self.signs.clear();
        self.mask.clear();
        self.of.clear();
        let mirror = reflections::<D>(planes);
        for mask in mirror.masks() {
            for i in (0..n_real).filter(|&i| alive(i)) {
                let x = p.positions0[i] + p.displacements[i];
                if !mirror.within(&x, mask, reach) {
                    continue;
                }
                let image0 = mirror.point(&p.positions0[i], mask);
                p.push(image0, p.volumes0[i], 0.0, Vector::zeros());
                let ghost = p.len() - 1;
                p.masses[ghost] = p.masses[i];
                self.parent.push(i);
                self.signs.push(mirror.signs(mask));
                self.mask.push(mask);
            }
        }
        self.refresh_kinematics(p);
        self.refresh_motion(p);
        self.refresh_stress(p);
    }
}

/// The reflections across the declared planes (numerics.md §13.1). The planes passed
/// [`check_planes`] at setup (every axis exists, every position is finite, at most 8 planes),
/// so the construction cannot fail here.
pub(crate) fn reflections<const D: usize>(planes: &[SymmetryPlane]) -> PlaneReflections<D> {
    PlaneReflections::new(planes.iter().map(|p| (p.axis, p.position))).unwrap_or_default()
}

/// Least distance of a particle from a symmetry plane, in spacings (numerics.md §13.1
/// ghosts): closer, it would be within half a spacing of its own mirror image, as two
/// particles of one lattice never are (the rule for two bodies that start inside each other).
pub const MIN_PLANE_DISTANCE: f64 = 0.25;

/// Input check of a symmetry model: at most 8 planes, each existing in `D` dimensions, and
/// every body (name, particles at setup, spacing) strictly on one side of each plane, the same
/// side for all bodies (a body on the far side would meet the images of the others, not the
/// modelled half), no particle closer to a plane than a quarter of its spacing (it would sit
/// within half a spacing of its own image). The error names the first body at fault.
pub(crate) fn check_planes<'a, const D: usize>(
    bodies: impl IntoIterator<Item = (&'a str, &'a [Vector<D>], f64)>,
    planes: &[SymmetryPlane],
) -> Result<(), SetupError> {
    if planes.is_empty() {
        return Ok(());
    }
    for (k, plane) in planes.iter().enumerate() {
        if planes[..k].iter().any(|p| p.axis == plane.axis) {
            return Err(SetupError::InvalidConfig {
                field: "symmetry_planes",
                message: format!(
                    "two planes normal to axis {}: at most one symmetry plane per axis (parallel planes would mirror each other's images without end)",
                    plane.axis
                ),
            });
        }
    }
    let mut first: Option<(&str, Vec<f64>)> = None;
    for (name, positions, spacing) in bodies {
        check_plane_sides(name, positions, spacing, planes)?;
        let Some(x) = positions.first() else {
            continue;
        };
        let sides: Vec<f64> = planes
            .iter()
            .map(|p| (x[p.axis] - p.position).signum())
            .collect();
        match &first {
            None => first = Some((name, sides)),
            Some((other, expected)) => {
                if let Some(k) = (0..planes.len()).find(|&k| sides[k] != expected[k]) {
                    return Err(SetupError::InvalidBody {
                        body: name.to_string(),
                        message: format!(
                            "lies on the other side of the symmetry plane x[{}] = {} than body `{other}`: a symmetry model keeps every body on the modelled side",
                            planes[k].axis, planes[k].position
                        ),
                    });
                }
            }
        }
    }
    if PlaneReflections::<D>::new(planes.iter().map(|p| (p.axis, p.position))).is_none() {
        return Err(SetupError::InvalidConfig {
            field: "symmetry_plane",
            message: format!("at most 8 symmetry planes, got {}", planes.len()),
        });
    }
    Ok(())
}

/// Input check: every plane exists in `D` dimensions and the body `name` (its particles at
/// `positions`) lies strictly on one side of each plane. The error names the first particle
/// off the body's side (the side of its first particle).
fn check_plane_sides<const D: usize>(
    name: &str,
    positions: &[Vector<D>],
    spacing: f64,
    planes: &[SymmetryPlane],
) -> Result<(), SetupError> {
    for plane in planes {
        if plane.axis >= D || !plane.position.is_finite() {
            return Err(SetupError::InvalidConfig {
                field: "symmetry_plane",
                message: format!(
                    "a plane normal to axis {} at {} does not exist in {D}D",
                    plane.axis, plane.position
                ),
            });
        }
        let side = |x: &Vector<D>| (x[plane.axis] - plane.position).signum();
        let body_side = positions.first().map_or(1.0, side);
        let off_side = positions
            .iter()
            .position(|x| x[plane.axis] == plane.position || side(x) != body_side);
        if let Some(k) = off_side {
            return Err(SetupError::InvalidBody {
                body: name.to_string(),
                message: format!(
                    "has particles on both sides of, or on, the symmetry plane x[{}] = {} (particle {k} at {:?})",
                    plane.axis,
                    plane.position,
                    positions[k].as_slice()
                ),
            });
        }
        let limit = MIN_PLANE_DISTANCE * spacing;
        if let Some(k) = positions
            .iter()
            .position(|x| (x[plane.axis] - plane.position).abs() < limit)
        {
            return Err(SetupError::InvalidBody {
                body: name.to_string(),
                message: format!(
                    "particle {k} at {:?} is {:.3e} from the symmetry plane x[{}] = {}, less than a quarter of the spacing {spacing}: it would sit within half a spacing of its own mirror image (a lattice puts the particles next to the plane half a spacing from it)",
                    positions[k].as_slice(),
                    (positions[k][plane.axis] - plane.position).abs(),
                    plane.axis,
                    plane.position
                ),
            });
        }
    }
    Ok(())
}
