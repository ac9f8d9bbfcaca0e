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

/// Particle centres on `rings` concentric rings that follow the rim of a circular hole of
/// `radius` about `centre` (2D): ring k lies at r_k = radius + (k + ½)·`spacing` and holds the
/// even number of particles n_k nearest to 2π r_k / spacing, at angles (i + ½)·2π / n_k, so
/// the pitch along a ring is within a few per cent of the spacing and every ring is symmetric
/// about both axes through `centre`. The rings replace the stair-step rim a square lattice
/// gives a hole (`[[body.cut]] rings`, scene-format.md).
pub fn hole_rings(centre: &Vector<2>, radius: f64, rings: usize, spacing: f64) -> Vec<Vector<2>> {
    let mut out = Vec::new();
    for k in 0..rings {
        let r = radius + (k as f64 + 0.5) * spacing;
        let count = 2 * ((std::f64::consts::PI * r / spacing).round() as usize).max(2);
        let pitch = std::f64::consts::TAU / count as f64;
        out.extend((0..count).map(|i| {
            let angle = (i as f64 + 0.5) * pitch;
            centre + r * Vector::<2>::new(angle.cos(), angle.sin())
        }));
    }
    out
}

/// Sub-samples per spacing along each axis used by [`sampled_cell_volumes`]: a lattice cell
/// holds exactly 32^D samples whatever the offset of the sample grid, so a regular lattice
/// gets its cell volume back exactly; an irregular cell is measured to about 1 %.
pub const VOLUME_SUBSAMPLES: usize = 32;

/// Reference volumes of the particles `targets` as the measure of their Voronoi cells inside
/// the body. The cells of pitch `spacing` within two spacings of a target are sampled at pitch
/// `spacing` / [`VOLUME_SUBSAMPLES`] along each axis; each sample point for which `inside`
/// holds counts for the particle of `positions` nearest to it (ties to the lower index), and
/// a sample farther than two spacings from every particle counts for none. The volumes of all
/// particles of a body then add up to the body's measure (up to the sampling of its curved
/// edges), whatever the arrangement of the particles, which is what an irregular packing such
/// as [`hole_rings`] needs. Cost: 32^D samples per cell near a target; in 2D about 20 ms per
/// hundred targets (release build: 0.08 s for the rings of the F-A1 plate, 1.1 s for a hole of
/// radius 200Δx). In 3D a cell holds 32 times the samples and a target has 5 times the
/// cells, so keep 3D target sets small (the scene reader measures the rings of a drilled
/// hole layer by layer in 2D instead).
pub fn sampled_cell_volumes<const D: usize>(
    positions: &[Vector<D>],
    targets: &[usize],
    spacing: f64,
    inside: impl Fn(&Vector<D>) -> bool,
) -> Vec<f64> {
    let mut volumes = vec![0.0; targets.len()];
    if targets.is_empty() {
        return volumes;
    }
    let reach = 2.0 * spacing;
    let Ok(grid) = CellGrid::new(positions, reach) else {
        return volumes;
    };
    let mut slot = vec![usize::MAX; positions.len()];
    for (t, &i) in targets.iter().enumerate() {
        slot[i] = t;
    }
    // Sample only the cells of pitch `spacing` (anchored at the first target) within two
    // spacings of a target, so the cost follows the number of targets, not their extent.
    let origin = positions[targets[0]];
    let cell_of = |x: &Vector<D>| -> [i64; D] {
        std::array::from_fn(|k| ((x[k] - origin[k]) / spacing).floor() as i64)
    };
    let offsets = lattice(&[5; D], |idx| {
        Vector::<D>::from_fn(|k, _| idx[k] as f64 - 2.0)
    });
    let mut cells = std::collections::BTreeSet::new();
    for &i in targets {
        let c = cell_of(&positions[i]);
        for off in &offsets {
            cells.insert(std::array::from_fn::<i64, D, _>(|k| c[k] + off[k] as i64));
        }
    }
    let n = VOLUME_SUBSAMPLES;
    let pitch = spacing / n as f64;
    let per_cell = n.pow(D as u32);
    let mut samples = vec![0usize; targets.len()];
    for cell in &cells {
        for s in 0..per_cell {
            let x = Vector::<D>::from_fn(|k, _| {
                let sub = (s / n.pow(k as u32)) % n;
                origin[k] + cell[k] as f64 * spacing + (sub as f64 + 0.5) * pitch
            });
            if !inside(&x) {
                continue;
            }
            let mut nearest = (reach, usize::MAX);
            grid.for_each_candidate(&x, |j| {
                let d = (positions[j as usize] - x).norm();
                // Ties go to the lower index, so the result does not depend on the grid.
                if d < nearest.0 || (d == nearest.0 && (j as usize) < nearest.1) {
                    nearest = (d, j as usize);
                }
            });
            if nearest.1 != usize::MAX && slot[nearest.1] != usize::MAX {
                samples[slot[nearest.1]] += 1;
            }
        }
    }
    let sample_volume = pitch.powi(D as i32);
    for (v, count) in volumes.iter_mut().zip(&samples) {
        *v = *count as f64 * sample_volume;
    }
    volumes
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

    #[test]
    fn hole_rings_are_even_symmetric_and_evenly_spaced() {
        let centre = Vector::<2>::new(1.0, -2.0);
        let p = hole_rings(&centre, 2.0, 3, 0.5);
        // r = 2.25, 2.75, 3.25: the even counts nearest 2πr/Δx = 28.3, 34.6, 40.8.
        assert_eq!(p.len(), 28 + 34 + 40);
        for x in &p {
            let r = (x - centre).norm();
            assert!([2.25, 2.75, 3.25]
                .iter()
                .any(|ring| (r - ring).abs() < 1e-12));
            // Mirror images about both axes through the centre are ring points too.
            for m in [
                Vector::<2>::new(2.0 * centre[0] - x[0], x[1]),
                Vector::<2>::new(x[0], 2.0 * centre[1] - x[1]),
            ] {
                assert!(p.iter().any(|y| (y - m).norm() < 1e-12), "{x:?}");
            }
        }
        // Neighbours along a ring are within 3 % of the spacing apart.
        let ring: Vec<&Vector<2>> = p[..28].iter().collect();
        for w in ring.windows(2) {
            assert!(((w[1] - w[0]).norm() / 0.5 - 1.0).abs() < 0.03);
        }
    }

    #[test]
    fn sampled_volumes_give_a_lattice_its_cells_and_an_edge_its_share() {
        let square = Shape::<2>::Box {
            min: Vector::<2>::new(0.0, 0.0),
            max: Vector::<2>::new(1.0, 1.0),
        };
        let p = fill_shape(&square, 0.1, &[]);
        let all: Vec<usize> = (0..p.len()).collect();
        let v = sampled_cell_volumes(&p, &all, 0.1, |x| square.contains(x));
        for vi in &v {
            assert!((vi / 0.01 - 1.0).abs() < 1e-12, "{vi}");
        }
        // Without the particles of the last column, the cells of the column before take the
        // emptied strip as well: two cells each, and the total is still the square's area.
        let kept: Vec<Vector<2>> = p.iter().copied().filter(|x| x[0] < 0.9).collect();
        let all: Vec<usize> = (0..kept.len()).collect();
        let v = sampled_cell_volumes(&kept, &all, 0.1, |x| square.contains(x));
        let total: f64 = v.iter().sum();
        assert!((total - 1.0).abs() < 1e-12, "{total}");
        for (x, vi) in kept.iter().zip(&v) {
            let cells = if (x[0] - 0.85).abs() < 1e-9 { 2.0 } else { 1.0 };
            assert!((vi / 0.01 - cells).abs() < 1e-12, "{x:?}: {vi}");
        }
    }
}
