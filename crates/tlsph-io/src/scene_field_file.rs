//! Initial fields read from CSV tables of sample points (`initial_stress_file`,
//! `initial_velocity_file`, `initial_plastic_strain_file`, `initial_damage_file`,
//! `initial_failure_damage_file`), each particle given the values of its nearest sample or of
//! a linear moving-least-squares fit over the samples around it (ours, not in the theses, which
//! start from rest or from uniform or linear fields). Typical sources: a residual stress, a
//! velocity, a plastic strain or a damage field computed by another code, or a field measured
//! on a grid.

use std::path::Path;
use tlsph_math::Vector;
use tlsph_neighbours::CellGrid;

/// Stress columns in the order of a `[xx, yy, zz, xy, yz, xz]` component array.
pub(crate) const STRESS_COLUMNS: [&str; 6] = ["xx", "yy", "zz", "xy", "yz", "xz"];

/// Velocity columns in the order of a velocity vector's components.
pub(crate) const VELOCITY_COLUMNS: [&str; 3] = ["vx", "vy", "vz"];

/// The effective plastic strain column (named as the `plastic_strain` output field).
pub(crate) const PLASTIC_STRAIN_COLUMNS: [&str; 1] = ["plastic_strain"];

/// The damage column, softening or Johnson–Cook (named as the `damage` output field).
pub(crate) const DAMAGE_COLUMNS: [&str; 1] = ["damage"];

/// The sample points of a field table and the field's N components at each.
#[derive(Debug, Clone)]
pub(crate) struct FieldSamples<const D: usize, const N: usize> {
    /// Sample positions X (reference configuration) \[length\].
    pub points: Vec<Vector<D>>,
    /// The components at each sample, in the order of the reader's component names (absent
    /// components 0).
    pub values: Vec<[f64; N]>,
    /// 1-based line of each sample in the file, for messages.
    pub lines: Vec<u64>,
    /// Which of the component names the header names.
    pub given: [bool; N],
}

/// Reads a field table: a header naming the coordinates `x`, `y`, `z` (the first D, all
/// required) and at least one of `components`, in any order, then one row
/// of numbers per sample, separated by commas. Blank lines and lines starting with `#` are
/// skipped; cells may be padded with spaces. Errors name the file and, for a bad row, its line
/// (counting every line of the file).
pub(crate) fn read_field_samples<const D: usize, const N: usize>(
    path: &Path,
    components: &[&str; N],
) -> Result<FieldSamples<D, N>, String> {
    let shown = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read `{shown}`: {e}"))?;
    let mut lines = (1u64..).zip(text.lines()).filter(|(_, l)| {
        let l = l.trim();
        !(l.is_empty() || l.starts_with('#'))
    });
    let Some((_, header)) = lines.next() else {
        return Err(format!("`{shown}` has no header line"));
    };
    let coordinates = &["x", "y", "z"][..D];
    // For each column: Ok(axis) for a coordinate, Err(component) for a field component.
    let mut columns: Vec<Result<usize, usize>> = Vec::new();
    for name in header.split(',').map(str::trim) {
        let column = match (
            coordinates.iter().position(|c| *c == name),
            components.iter().position(|c| *c == name),
        ) {
            (Some(axis), _) => Ok(axis),
            (None, Some(component)) => Err(component),
            (None, None) => {
                return Err(format!(
                "`{shown}`: unknown column `{name}` in the header; use {} and components among {}",
                coordinates.join(", "),
                components.join(", ")
            ))
            }
        };
        if columns.contains(&column) {
            return Err(format!(
                "`{shown}`: column `{name}` appears twice in the header"
            ));
        }
        columns.push(column);
    }
    if let Some(missing) = (0..D).find(|axis| !columns.contains(&Ok(*axis))) {
        return Err(format!(
            "`{shown}`: the header has no column `{}` (a {D}D scene needs {})",
            coordinates[missing],
            coordinates.join(", ")
        ));
    }
    let given = std::array::from_fn(|c| columns.contains(&Err(c)));
    if !given.contains(&true) {
        return Err(format!(
            "`{shown}`: the header names no field column; give at least one of {}",
            components.join(", ")
        ));
    }
    let mut samples = FieldSamples {
        points: Vec::new(),
        values: Vec::new(),
        lines: Vec::new(),
        given,
    };
    for (line, row) in lines {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        if cells.len() != columns.len() {
            return Err(format!(
                "`{shown}` line {line}: {} cells, but the header names {} columns",
                cells.len(),
                columns.len()
            ));
        }
        let mut point = Vector::<D>::zeros();
        let mut values = [0.0; N];
        for (cell, column) in cells.iter().zip(&columns) {
            let value = cell.parse::<f64>().ok().filter(|v| v.is_finite());
            let Some(value) = value else {
                let name = match column {
                    Ok(axis) => coordinates[*axis],
                    Err(component) => components[*component],
                };
                return Err(format!(
                    "`{shown}` line {line}: `{name}` must be a finite number, got `{cell}`"
                ));
            };
            match column {
                Ok(axis) => point[*axis] = value,
                Err(component) => values[*component] = value,
            }
        }
        samples.points.push(point);
        samples.values.push(values);
        samples.lines.push(line);
    }
    if samples.points.is_empty() {
        return Err(format!("`{shown}` has a header but no sample rows"));
    }
    Ok(samples)
}

/// How a field table's samples give each particle its values (`interpolation` on the key).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Interpolation {
    /// The values of the nearest sample: the field is piecewise constant over the samples'
    /// cells.
    Nearest,
    /// A first-order moving-least-squares fit over the samples within reach (see
    /// [`linear_shape_functions`]): exact for a field linear in X, so a table coarser than the
    /// particles gives a smooth field rather than a blocky one.
    Linear,
}

/// Each particle's values as a weighted sum of samples, f(Xₚ) = Σᵢ φᵢ fᵢ with Σᵢ φᵢ = 1: the
/// nearest sample with weight 1, or the moving-least-squares shape functions.
#[derive(Debug, Clone)]
pub(crate) struct SampleMapping {
    /// Particle k's terms are `terms[offsets[k]..offsets[k + 1]]`.
    offsets: Vec<usize>,
    /// (sample index, weight φ).
    terms: Vec<(usize, f64)>,
    /// Each particle's nearest sample (named in messages).
    nearest: Vec<usize>,
}

impl SampleMapping {
    /// The field's N components at particle `k`: Σᵢ φᵢ fᵢ; with a single term (nearest
    /// sample) exactly that sample's values.
    pub fn values<const D: usize, const N: usize>(
        &self,
        samples: &FieldSamples<D, N>,
        k: usize,
    ) -> [f64; N] {
        let terms = &self.terms[self.offsets[k]..self.offsets[k + 1]];
        if let [(index, _)] = terms {
            return samples.values[*index];
        }
        let mut values = [0.0; N];
        for (index, weight) in terms {
            for (value, sample) in values.iter_mut().zip(&samples.values[*index]) {
                *value += weight * sample;
            }
        }
        values
    }

    /// Particle `k`'s nearest sample (the first in file order among equally near ones).
    pub fn nearest(&self, k: usize) -> usize {
        self.nearest[k]
    }

    /// How many samples give particle `k` its values.
    pub fn sample_count(&self, k: usize) -> usize {
        self.offsets[k + 1] - self.offsets[k]
    }

    /// The fewest and most samples any particle's values come from ((0, 0) without
    /// particles), and how many of the `samples` no particle's values come from.
    pub fn usage(&self, samples: usize) -> ((usize, usize), usize) {
        let counts = self.offsets.windows(2).map(|w| w[1] - w[0]);
        let fewest = counts.clone().min().unwrap_or(0);
        let most = counts.max().unwrap_or(0);
        let mut used = vec![false; samples];
        for (index, _) in &self.terms {
            used[*index] = true;
        }
        ((fewest, most), used.iter().filter(|u| !**u).count())
    }
}

/// Maps the samples to each of `positions`. Every particle's nearest sample (the first in file
/// order among equally near ones) must lie within `reach`; with [`Interpolation::Linear`] the
/// samples closer than `reach` must also span the space (D + 1 of them not on one point, line
/// or plane). The error names the first particle that fails and why.
pub(crate) fn map_samples<const D: usize, const N: usize>(
    samples: &FieldSamples<D, N>,
    positions: &[Vector<D>],
    reach: f64,
    interpolation: Interpolation,
) -> Result<SampleMapping, String> {
    let grid = CellGrid::new(&samples.points, reach).map_err(|e| e.to_string())?;
    let mut mapping = SampleMapping {
        offsets: Vec::with_capacity(positions.len() + 1),
        terms: Vec::new(),
        nearest: Vec::with_capacity(positions.len()),
    };
    mapping.offsets.push(0);
    // (sample index, distance²) of the samples within reach of one particle.
    let mut near: Vec<(usize, f64)> = Vec::new();
    for (k, x) in positions.iter().enumerate() {
        near.clear();
        grid.for_each_candidate_with_position(x, |index, point| {
            let distance_squared = (point - x).norm_squared();
            if distance_squared <= reach * reach {
                near.push((index as usize, distance_squared));
            }
        });
        // File order, so the sums below do not depend on the grid's cell order.
        near.sort_unstable_by_key(|&(index, _)| index);
        let Some(&(nearest, _)) = near.iter().min_by(|a, b| a.1.total_cmp(&b.1)) else {
            let closest = samples
                .points
                .iter()
                .map(|p| (p - x).norm())
                .fold(f64::INFINITY, f64::min);
            return Err(format!(
                "particle {k} at [{}] has no sample within reach {reach:e} (the nearest is {closest:e} away): the file does not cover the body, or its coordinates are in other units or another frame",
                crate::scene::point_text(x)
            ));
        };
        mapping.nearest.push(nearest);
        match interpolation {
            Interpolation::Nearest => mapping.terms.push((nearest, 1.0)),
            Interpolation::Linear => {
                linear_shape_functions(samples, &near, x, reach, &mut mapping.terms).ok_or_else(
                    || {
                        format!(
                            "particle {k} at [{}]: the samples within reach {reach:e} ({} of them) lie on one {}, so a linear fit is not defined there; raise `reach` to take in samples around the particle, or use interpolation = \"nearest\"",
                            crate::scene::point_text(x),
                            near.iter().filter(|n| n.1 < reach * reach).count(),
                            ["point", "point or line", "point, line or plane"][D - 1],
                        )
                    },
                )?;
            }
        }
        mapping.offsets.push(mapping.terms.len());
    }
    Ok(mapping)
}

/// Appends to `terms` the first-order moving-least-squares shape functions at `x` of the
/// samples `near` (index, distance²; ours, the standard MLS of Lancaster and Salkauskas 1981):
/// with qᵢ = (Xᵢ − x)/reach, weights wᵢ = (1 − |qᵢ|²)² and pᵢ = [1, qᵢ], the fit
/// a + b·q minimising Σ wᵢ (fᵢ − a − b·qᵢ)² has a = Σ φᵢ fᵢ with φᵢ = wᵢ pᵢᵀ M⁻¹ e₁,
/// M = Σ wᵢ pᵢ pᵢᵀ. Σ φᵢ = 1 and Σ φᵢ qᵢ = 0, so a field linear in X is reproduced exactly.
/// Returns `None` if M/Σwᵢ has a smallest eigenvalue below 10⁻⁹ of its largest: the samples
/// with weight lie on one point, line or plane (D ≤ 3; the unused rows of the 4 × 4 system
/// are the identity).
fn linear_shape_functions<const D: usize, const N: usize>(
    samples: &FieldSamples<D, N>,
    near: &[(usize, f64)],
    x: &Vector<D>,
    reach: f64,
    terms: &mut Vec<(usize, f64)>,
) -> Option<()> {
    use tlsph_math::nalgebra::{Matrix4, Vector4};
    let basis = |index: usize| {
        let q = (samples.points[index] - x) / reach;
        let mut p = Vector4::zeros();
        p[0] = 1.0;
        for axis in 0..D {
            p[axis + 1] = q[axis];
        }
        p
    };
    let weight = |distance_squared: f64| (1.0 - distance_squared / (reach * reach)).powi(2);
    let mut moment = Matrix4::zeros();
    let mut total_weight = 0.0;
    for &(index, distance_squared) in near {
        let p = basis(index);
        let w = weight(distance_squared);
        moment += w * p * p.transpose();
        total_weight += w;
    }
    if total_weight <= 0.0 {
        return None;
    }
    moment /= total_weight;
    for unused in D + 1..4 {
        moment[(unused, unused)] = 1.0;
    }
    let eigenvalues = moment.symmetric_eigenvalues();
    if eigenvalues.min() < 1e-9 * eigenvalues.max() {
        return None;
    }
    let c = moment.cholesky()?.solve(&Vector4::x());
    for &(index, distance_squared) in near {
        let w = weight(distance_squared);
        if w > 0.0 {
            terms.push((index, w / total_weight * c.dot(&basis(index))));
        }
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn samples_1d(points: &[f64]) -> FieldSamples<1, 1> {
        FieldSamples {
            points: points.iter().map(|x| Vector::<1>::new(*x)).collect(),
            values: points.iter().map(|x| [*x]).collect(),
            lines: (2..).take(points.len()).collect(),
            given: [true],
        }
    }

    fn nearest(samples: &FieldSamples<1, 1>, particles: &[Vector<1>], reach: f64) -> Vec<usize> {
        let mapping = map_samples(samples, particles, reach, Interpolation::Nearest).unwrap();
        (0..particles.len()).map(|k| mapping.nearest(k)).collect()
    }

    #[test]
    fn each_particle_takes_its_nearest_sample_and_ties_go_to_the_earlier_row() {
        // Samples at 0, 1, 1 (a repeated point) and 2.5; particles at 0.4, 1.0, 1.75, 2.2.
        let samples = samples_1d(&[0.0, 1.0, 1.0, 2.5]);
        let particles: Vec<Vector<1>> = [0.4, 1.0, 1.75, 2.2]
            .iter()
            .map(|x| Vector::<1>::new(*x))
            .collect();
        // 1.75 is equally near 1.0 (rows 1 and 2) and 2.5: the earliest row wins.
        assert_eq!(nearest(&samples, &particles, 1.0), vec![0, 1, 1, 3]);
        // And its values are that sample's, exactly.
        let mapping = map_samples(&samples, &particles, 1.0, Interpolation::Nearest).unwrap();
        let values: Vec<f64> = (0..4).map(|k| mapping.values(&samples, k)[0]).collect();
        assert_eq!(values, vec![0.0, 1.0, 1.0, 2.5]);
    }

    #[test]
    fn a_particle_beyond_reach_of_every_sample_is_named() {
        let samples = samples_1d(&[0.0, 1.0]);
        // Particle 0 has both samples within reach (enough for a linear fit), particle 1 none.
        let particles = [Vector::<1>::new(0.5), Vector::<1>::new(1.6)];
        for interpolation in [Interpolation::Nearest, Interpolation::Linear] {
            let e = map_samples(&samples, &particles, 0.55, interpolation).unwrap_err();
            assert!(
                e.contains("particle 1 at [1.6]") && e.contains("the nearest is 6"),
                "{e}"
            );
        }
        // With a longer reach it is covered.
        assert_eq!(nearest(&samples, &particles, 0.7), vec![0, 1]);
    }

    /// A 2D field f = (3 + 2x − 5y, −1 + 0.5x + 4y) sampled on a coarse, sheared, irregular
    /// set of points, and particles on a finer lattice over the same region.
    fn linear_field_2d() -> (
        FieldSamples<2, 2>,
        Vec<Vector<2>>,
        impl Fn(&Vector<2>) -> [f64; 2],
    ) {
        let field = |p: &Vector<2>| [3.0 + 2.0 * p.x - 5.0 * p.y, -1.0 + 0.5 * p.x + 4.0 * p.y];
        let mut points = Vec::new();
        for i in 0..8 {
            for j in 0..6 {
                // Jittered grid of spacing 0.3, rows shifted: no two samples equally spaced.
                let jitter = 0.04 * ((7 * i + 3 * j) % 5) as f64 - 0.08;
                points.push(Vector::<2>::new(
                    0.3 * i as f64 + 0.1 * j as f64 + jitter,
                    0.3 * j as f64 - jitter,
                ));
            }
        }
        let values = points.iter().map(field).collect();
        let samples = FieldSamples {
            lines: (2..).take(points.len()).collect(),
            points,
            values,
            given: [true, true],
        };
        let particles = (0..20)
            .flat_map(|i| {
                (0..15).map(move |j| Vector::<2>::new(0.3 + 0.07 * i as f64, 0.1 + 0.1 * j as f64))
            })
            .collect();
        (samples, particles, field)
    }

    #[test]
    fn linear_interpolation_reproduces_a_linear_field_where_nearest_gives_steps() {
        let (samples, particles, field) = linear_field_2d();
        let reach = 0.6;
        let error = |interpolation| {
            let mapping = map_samples(&samples, &particles, reach, interpolation).unwrap();
            particles
                .iter()
                .enumerate()
                .flat_map(|(k, x)| {
                    let (got, want) = (mapping.values(&samples, k), field(x));
                    [(got[0] - want[0]).abs(), (got[1] - want[1]).abs()]
                })
                .fold(0.0, f64::max)
        };
        // The fit is exact for a linear field: what is left is round-off in values of order 10
        // (measured 2e-15; a 3 × 3 solve with condition below 10³).
        let linear = error(Interpolation::Linear);
        assert!(linear < 1e-12, "linear interpolation error {linear:e}");
        // The nearest sample is up to about half a sample spacing away, |∇f| ≈ 5.4: steps of
        // order 0.5.
        let nearest = error(Interpolation::Nearest);
        assert!(nearest > 0.3, "nearest-sample error {nearest:e}");
    }

    #[test]
    fn linear_weights_sum_to_one_and_stay_positive_inside_a_regular_table() {
        // Samples on a regular grid, a particle inside it: the MLS shape functions are a
        // partition of unity and, with the symmetric neighbourhood, all positive (no
        // overshoot of the sampled values).
        let points: Vec<Vector<2>> = (0..5)
            .flat_map(|i| (0..5).map(move |j| Vector::<2>::new(i as f64, j as f64)))
            .collect();
        let samples = FieldSamples {
            values: points.iter().map(|p| [p.x * p.x]).collect(),
            lines: (2..).take(points.len()).collect(),
            points,
            given: [true],
        };
        let particle = [Vector::<2>::new(2.0, 2.0)];
        let mapping = map_samples(&samples, &particle, 1.5, Interpolation::Linear).unwrap();
        let terms = &mapping.terms[mapping.offsets[0]..mapping.offsets[1]];
        // The 9 samples within 1.5 of (2, 2).
        assert_eq!(mapping.sample_count(0), 9);
        let sum: f64 = terms.iter().map(|t| t.1).sum();
        assert!((sum - 1.0).abs() < 1e-14, "Σφ = {sum}");
        assert!(terms.iter().all(|t| t.1 > 0.0), "{terms:?}");
        // x² is convex and not linear: with positive weights symmetric about X = 2 the fit lies
        // above x² = 4 there and below the largest sample value, 9.
        let value = mapping.values(&samples, 0)[0];
        assert!(value > 4.0 && value < 9.0, "{value}");
    }

    #[test]
    fn in_3d_a_linear_field_comes_back_and_samples_on_one_plane_are_refused() {
        let field = |p: &Vector<3>| [1.0 - p.x + 2.0 * p.y + 0.5 * p.z];
        let grid = |nz: usize| -> FieldSamples<3, 1> {
            let points: Vec<Vector<3>> = (0..4)
                .flat_map(|i| (0..4).flat_map(move |j| (0..nz).map(move |k| (i, j, k))))
                .map(|(i, j, k)| Vector::<3>::new(i as f64, j as f64, k as f64))
                .collect();
            FieldSamples {
                values: points.iter().map(field).collect(),
                lines: (2..).take(points.len()).collect(),
                points,
                given: [true],
            }
        };
        // Particles between the samples of a 4 × 4 × 4 grid of pitch 1, reach 1.5.
        let particles: Vec<Vector<3>> = (0..5)
            .map(|i| {
                Vector::<3>::new(
                    0.3 + 0.6 * i as f64,
                    1.7 - 0.3 * i as f64,
                    0.2 + 0.5 * i as f64,
                )
            })
            .collect();
        let samples = grid(4);
        let mapping = map_samples(&samples, &particles, 1.5, Interpolation::Linear).unwrap();
        for (k, x) in particles.iter().enumerate() {
            let got = mapping.values(&samples, k)[0];
            assert!((got - field(x)[0]).abs() < 1e-13, "{got} at {x:?}");
        }
        // All samples on the plane z = 0: a fit in z is not defined.
        let flat = grid(1);
        let on_plane = [Vector::<3>::new(1.5, 1.5, 0.2)];
        let e = map_samples(&flat, &on_plane, 1.5, Interpolation::Linear).unwrap_err();
        assert!(
            e.contains("particle 0 at [1.5, 1.5, 0.2]") && e.contains("one point, line or plane"),
            "{e}"
        );
    }

    #[test]
    fn linear_interpolation_refuses_samples_on_one_line_and_names_the_particle() {
        // In 2D, samples along y = 0 only: a fit in y is not defined.
        let points: Vec<Vector<2>> = (0..6).map(|i| Vector::<2>::new(i as f64, 0.0)).collect();
        let samples = FieldSamples {
            values: points.iter().map(|p| [p.x]).collect(),
            lines: (2..).take(points.len()).collect(),
            points,
            given: [true],
        };
        let particles = [Vector::<2>::new(2.5, 0.0), Vector::<2>::new(2.5, 0.2)];
        // Reach 1.6: the particle on the line has the 4 samples at x = 1..4 within it.
        let e = map_samples(&samples, &particles, 1.6, Interpolation::Linear).unwrap_err();
        assert!(
            e.contains("particle 0 at [2.5, 0]")
                && e.contains("(4 of them)")
                && e.contains("one point or line"),
            "{e}"
        );
        // One sample off the line makes the fit defined.
        let mut samples = samples;
        samples.points.push(Vector::<2>::new(2.0, 1.0));
        samples.values.push([2.0]);
        samples.lines.push(8);
        let mapping = map_samples(&samples, &particles, 1.6, Interpolation::Linear).unwrap();
        assert!((mapping.values(&samples, 1)[0] - 2.5).abs() < 1e-12);
        // In 1D, a single sample within reach is a point.
        let samples = samples_1d(&[0.0, 3.0]);
        let e = map_samples(
            &samples,
            &[Vector::<1>::new(0.5)],
            1.0,
            Interpolation::Linear,
        )
        .unwrap_err();
        assert!(
            e.contains("(1 of them)") && e.contains("lie on one point,"),
            "{e}"
        );
    }
}
