//! Initial fields read from CSV tables of sample points (`initial_stress_file`,
//! `initial_velocity_file`), each particle given the values of its nearest sample (ours, not in
//! the theses, which start from rest or from uniform or linear fields). Typical sources: a
//! residual stress or a velocity field computed by another code, or a field measured on a grid.

use std::path::Path;
use tlsph_math::Vector;
use tlsph_neighbours::CellGrid;

/// Stress columns in the order of a `[xx, yy, zz, xy, yz, xz]` component array.
pub(crate) const STRESS_COLUMNS: [&str; 6] = ["xx", "yy", "zz", "xy", "yz", "xz"];

/// Velocity columns in the order of a velocity vector's components.
pub(crate) const VELOCITY_COLUMNS: [&str; 3] = ["vx", "vy", "vz"];

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

/// For each of `positions`, the index of the nearest sample (the first in file order among
/// equally near ones), which must lie within `reach`. The error names the first particle with
/// no sample that near and how far its nearest sample is.
pub(crate) fn nearest_samples<const D: usize, const N: usize>(
    samples: &FieldSamples<D, N>,
    positions: &[Vector<D>],
    reach: f64,
) -> Result<Vec<usize>, String> {
    let grid = CellGrid::new(&samples.points, reach).map_err(|e| e.to_string())?;
    let mut nearest = Vec::with_capacity(positions.len());
    for (k, x) in positions.iter().enumerate() {
        let mut best: Option<(f64, usize)> = None;
        grid.for_each_candidate_with_position(x, |index, point| {
            let candidate = ((point - x).norm_squared(), index as usize);
            if best.is_none_or(|b| candidate < b) {
                best = Some(candidate);
            }
        });
        match best {
            Some((distance_squared, index)) if distance_squared <= reach * reach => {
                nearest.push(index)
            }
            _ => {
                let closest = samples
                    .points
                    .iter()
                    .map(|p| (p - x).norm())
                    .fold(f64::INFINITY, f64::min);
                return Err(format!(
                    "particle {k} at [{}] has no sample within reach {reach:e} (the nearest is {closest:e} away): the file does not cover the body, or its coordinates are in other units or another frame",
                    crate::scene::point_text(x)
                ));
            }
        }
    }
    Ok(nearest)
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

    #[test]
    fn each_particle_takes_its_nearest_sample_and_ties_go_to_the_earlier_row() {
        // Samples at 0, 1, 1 (a repeated point) and 2.5; particles at 0.4, 1.0, 1.75, 2.2.
        let samples = samples_1d(&[0.0, 1.0, 1.0, 2.5]);
        let particles: Vec<Vector<1>> = [0.4, 1.0, 1.75, 2.2]
            .iter()
            .map(|x| Vector::<1>::new(*x))
            .collect();
        // 1.75 is equally near 1.0 (rows 1 and 2) and 2.5: the earliest row wins.
        assert_eq!(
            nearest_samples(&samples, &particles, 1.0).unwrap(),
            vec![0, 1, 1, 3]
        );
    }

    #[test]
    fn a_particle_beyond_reach_of_every_sample_is_named() {
        let samples = samples_1d(&[0.0, 1.0]);
        let particles = [Vector::<1>::new(0.1), Vector::<1>::new(1.6)];
        let e = nearest_samples(&samples, &particles, 0.5).unwrap_err();
        assert!(
            e.contains("particle 1 at [1.6]") && e.contains("the nearest is 6"),
            "{e}"
        );
        // With a longer reach it is covered.
        assert_eq!(
            nearest_samples(&samples, &particles, 0.7).unwrap(),
            vec![0, 1]
        );
    }
}
