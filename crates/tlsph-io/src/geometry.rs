//! Particle lattices filling simple shapes. A shape is filled with a cell-centred lattice of
//! pitch Δx (problems.md §0 "Lattices"): boxes are anchored at their `min` corner, round
//! shapes are centred on their axis or centre so the lattice is symmetric.

use tlsph_math::Vector;
use tlsph_neighbours::CellGrid;

/// A region of the reference configuration.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape<const D: usize> {
    /// Axis-aligned box [min, max].
    Box {
        /// Lower corner.
        min: Vector<D>,
        /// Upper corner.
        max: Vector<D>,
    },
    /// Disc (2D) or sphere (3D).
    Ball {
        /// Centre.
        centre: Vector<D>,
        /// Radius.
        radius: f64,
    },
    /// Axis-aligned circular cylinder (3D).
    Cylinder {
        /// Centre of the base.
        base: Vector<D>,
        /// Axis index (0 = x, 1 = y, 2 = z).
        axis: usize,
        /// Radius.
        radius: f64,
        /// Length along the axis.
        length: f64,
    },
}

impl<const D: usize> Shape<D> {
    /// Whether the point `x` lies in the shape, by the rules a cut (`[[body.cut]]`) removes
    /// lattice points with: a box is closed (min ≤ x ≤ max, like `clip` and boundary boxes);
    /// a disc, sphere or cylinder keeps the strict radial test of [`fill_shape`]
    /// (distance < radius), and a cylinder is closed along its axis (0 ≤ s ≤ length).
    pub fn contains(&self, x: &Vector<D>) -> bool {
        match self {
            Shape::Box { min, max } => (0..D).all(|k| x[k] >= min[k] && x[k] <= max[k]),
            Shape::Ball { centre, radius } => (x - centre).norm() < *radius,
            Shape::Cylinder {
                base,
                axis,
                radius,
                length,
            } => {
                let s = x[*axis] - base[*axis];
                let r2: f64 = (0..D)
                    .filter(|k| k != axis)
                    .map(|k| (x[k] - base[k]).powi(2))
                    .sum();
                (0.0..=*length).contains(&s) && r2.sqrt() < *radius
            }
        }
    }
}

/// Lattice points of `shape` at pitch `spacing`, leaving out points closer than half a spacing
/// to any point of `existing` (so later shapes of a body do not duplicate earlier ones).
pub fn fill_shape<const D: usize>(
    shape: &Shape<D>,
    spacing: f64,
    existing: &[Vector<D>],
) -> Vec<Vector<D>> {
    let candidates = match shape {
        Shape::Box { min, max } => {
            let counts: [usize; D] = std::array::from_fn(|k| cells_along(max[k] - min[k], spacing));
            lattice(&counts, |idx| {
                Vector::<D>::from_fn(|k, _| min[k] + (idx[k] as f64 + 0.5) * spacing)
            })
        }
        Shape::Ball { centre, radius } => {
            let m = (radius / spacing).ceil() as usize;
            let counts = [2 * m; D];
            lattice(&counts, |idx| {
                Vector::<D>::from_fn(|k, _| centre[k] + (idx[k] as f64 - m as f64 + 0.5) * spacing)
            })
            .into_iter()
            .filter(|x| (x - centre).norm() < *radius)
            .collect()
        }
        Shape::Cylinder {
            base,
            axis,
            radius,
            length,
        } => {
            let m = (radius / spacing).ceil() as usize;
            let counts: [usize; D] = std::array::from_fn(|k| {
                if k == *axis {
                    cells_along(*length, spacing)
                } else {
                    2 * m
                }
            });
            lattice(&counts, |idx| {
                Vector::<D>::from_fn(|k, _| {
                    if k == *axis {
                        base[k] + (idx[k] as f64 + 0.5) * spacing
                    } else {
                        base[k] + (idx[k] as f64 - m as f64 + 0.5) * spacing
                    }
                })
            })
            .into_iter()
            .filter(|x| {
                let mut r2 = 0.0;
                for k in (0..D).filter(|k| k != axis) {
                    r2 += (x[k] - base[k]).powi(2);
                }
                r2.sqrt() < *radius
            })
            .collect()
        }
    };
    if existing.is_empty() {
        return candidates;
    }
    let half = 0.5 * spacing;
    match CellGrid::new(existing, half) {
        Ok(grid) => candidates
            .into_iter()
            .filter(|x| {
                let mut taken = false;
                grid.for_each_candidate(x, |j| taken |= (existing[j as usize] - x).norm() < half);
                !taken
            })
            .collect(),
        // A grid that cannot be built (absurd extent) means no overlap test: keep everything.
        Err(_) => candidates,
    }
}

/// Number of lattice cells of pitch `spacing` in a length; lengths within 1e-9 of a whole
/// number of cells are rounded so that 1.5 / 0.001 gives 1500, not 1499.
fn cells_along(length: f64, spacing: f64) -> usize {
    let n = length / spacing;
    let rounded = n.round();
    if (n - rounded).abs() < 1e-9 * n.max(1.0) {
        rounded as usize
    } else {
        n.floor() as usize
    }
}

/// Calls `point` for every multi-index below `counts` (last index fastest).
fn lattice<const D: usize>(
    counts: &[usize; D],
    point: impl Fn(&[usize; D]) -> Vector<D>,
) -> Vec<Vector<D>> {
    let total: usize = counts.iter().product();
    let mut out = Vec::with_capacity(total);
    let mut idx = [0usize; D];
    for _ in 0..total {
        out.push(point(&idx));
        for k in (0..D).rev() {
            idx[k] += 1;
            if idx[k] < counts[k] {
                break;
            }
            idx[k] = 0;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_counts_are_exact_for_whole_numbers_of_cells() {
        let s = Shape::<1>::Box {
            min: Vector::<1>::new(0.5),
            max: Vector::<1>::new(2.0),
        };
        let p = fill_shape(&s, 0.001, &[]);
        assert_eq!(p.len(), 1500);
        assert!((p[0][0] - 0.5005).abs() < 1e-12);
    }

    #[test]
    fn touching_boxes_do_not_overlap_but_coincident_ones_do() {
        let a = Shape::<2>::Box {
            min: Vector::<2>::new(0.0, 0.0),
            max: Vector::<2>::new(1.0, 1.0),
        };
        let b = Shape::<2>::Box {
            min: Vector::<2>::new(1.0, 0.0),
            max: Vector::<2>::new(2.0, 1.0),
        };
        let pa = fill_shape(&a, 0.1, &[]);
        assert_eq!(pa.len(), 100);
        assert_eq!(fill_shape(&b, 0.1, &pa).len(), 100);
        assert!(fill_shape(&a, 0.1, &pa).is_empty());
    }

    #[test]
    fn containment_follows_the_documented_boundary_rules() {
        let b = Shape::<2>::Box {
            min: Vector::<2>::new(0.0, 0.0),
            max: Vector::<2>::new(1.0, 2.0),
        };
        assert!(
            b.contains(&Vector::<2>::new(1.0, 2.0)),
            "box faces belong to the box"
        );
        assert!(!b.contains(&Vector::<2>::new(1.0 + 1e-12, 1.0)));
        let d = Shape::<2>::Ball {
            centre: Vector::<2>::new(1.0, 1.0),
            radius: 1.0,
        };
        assert!(
            !d.contains(&Vector::<2>::new(2.0, 1.0)),
            "a disc's rim is outside"
        );
        assert!(d.contains(&Vector::<2>::new(1.999, 1.0)));
        let c = Shape::<3>::Cylinder {
            base: Vector::<3>::new(0.0, 0.0, 1.0),
            axis: 2,
            radius: 0.5,
            length: 2.0,
        };
        assert!(c.contains(&Vector::<3>::new(0.4, 0.0, 3.0)));
        assert!(!c.contains(&Vector::<3>::new(0.4, 0.0, 3.01)));
        assert!(!c.contains(&Vector::<3>::new(0.0, 0.0, 0.99)));
        assert!(
            !c.contains(&Vector::<3>::new(0.3, 0.4, 2.0)),
            "radius 0.5 is outside"
        );
    }

    #[test]
    fn disc_area_matches_particle_count() {
        let s = Shape::<2>::Ball {
            centre: Vector::<2>::zeros(),
            radius: 1.0,
        };
        let n = fill_shape(&s, 0.01, &[]).len() as f64;
        // Area π r² / Δx²; the staircase boundary error is O(perimeter / Δx) ~ 1e-3 relative.
        assert!((n * 1e-4 / std::f64::consts::PI - 1.0).abs() < 2e-3, "{n}");
    }
}
