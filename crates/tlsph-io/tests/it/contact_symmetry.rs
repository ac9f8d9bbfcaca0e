//! A half model in contact at its symmetry plane, from scene text to output files: a disc
//! dropped on a plate, written once whole and once as the half x ≥ 0 (`clip` plus a
//! `[[symmetry_plane]]` through the disc's axis). The contact of the particles next to the
//! plane meets the mirror images of the plate's particles beyond it (scene-format.md,
//! `[[symmetry_plane]]`), so the half model's `walls.csv` contact force and `energy.csv`
//! columns are half the full model's at every sample.

use std::fs;
use std::path::Path;
use tlsph_io::{parse_scene, run_scene_to_dir};

/// The full model: a disc of radius 0.5 (spacing 0.05, centred on a cell corner) whose lowest
/// particle starts 1.05Δx above the plate's top row, falling at 0.05 c onto a 2 × 0.2 plate.
/// `CONTACT` and `HALF` are replaced by the contact table and the half-model lines.
const DISC_ON_PLATE: &str = r#"
[simulation]
dimension = 2
formulation = "FORMULATION"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 1.6

[[material]]
name = "unit"
model = "linear-elastic"
density = 1.0
youngs_modulus = 1.0
poisson_ratio = 0.25

[[body]]
name = "disc"
material = "unit"
spacing = 0.05
disc = { centre = [0.0, 0.5025], radius = 0.5 }
velocity = [0.0, -0.05]
DISC_CLIP
DISC_GROUP

[[body]]
name = "plate"
material = "unit"
spacing = 0.05
box = { min = [-1.0, -0.2], max = [1.0, 0.0] }
PLATE_CLIP

CONTACT

[output]
energy_interval = 0.02
"#;

/// A run's CSV as its header and rows.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("column {name} in {header:?}"))
}

/// Runs the scene whole (`half = false`) or as the half x ≥ 0 and returns, per sample, the
/// vertical contact force on the disc and the `contact`, `kinetic` and `total` energies.
fn run(formulation: &str, contact: &str, half: bool) -> Vec<[f64; 4]> {
    let (disc_clip, plate_clip) = if half {
        (
            "clip = { min = [0.0, -1.0], max = [1.0, 2.0] }",
            "clip = { min = [0.0, -1.0], max = [1.0, 1.0] }\n\n[[symmetry_plane]]\naxis = \"x\"\nposition = 0.0",
        )
    } else {
        ("", "")
    };
    // In conventional SPH bodies of one kernel group interact through the kernel: the disc
    // gets its own group so that the two meet only through the contact law.
    let disc_group = if formulation == "updated-lagrangian" {
        "kernel_group = \"disc\""
    } else {
        ""
    };
    let text = DISC_ON_PLATE
        .replace("FORMULATION", formulation)
        .replace("DISC_CLIP", disc_clip)
        .replace("DISC_GROUP", disc_group)
        .replace("PLATE_CLIP", plate_clip)
        .replace("CONTACT", contact);
    let scene = parse_scene(&text, "disc-on-plate.toml").unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let (walls_header, walls) = read_csv(&dir.join("walls.csv"));
    let (energy_header, energy) = read_csv(&dir.join("energy.csv"));
    let force = column(&walls_header, "contact_force_y");
    let [stored, kinetic, total] =
        ["contact", "kinetic", "total"].map(|name| column(&energy_header, name));
    assert_eq!(walls.len(), energy.len());
    walls
        .iter()
        .zip(&energy)
        .map(|(w, e)| [w[force], e[stored], e[kinetic], e[total]])
        .collect()
}

/// The half model's histories, doubled, against the full model's, each relative to the
/// largest value of its quantity (the peak force; the initial kinetic energy).
fn assert_half_is_half_of_full(formulation: &str, contact: &str) {
    let full = run(formulation, contact, false);
    let half = run(formulation, contact, true);
    assert_eq!(full.len(), half.len());
    let peak = |q: usize| full.iter().map(|s| s[q].abs()).fold(0.0, f64::max);
    let (peak_force, energy) = (peak(0), full[0][2]);
    // The disc strikes: the force peaks at about ρ c v per unit contact width.
    assert!(peak_force > 1e-3, "{formulation} {contact}: no impact");
    // The half model sums over half the particles (and their images) in another order than
    // the full model, whose box lattice is symmetric only to round-off (1e-16 of a spacing):
    // without friction the histories agree to 1e-13 of their peaks, far below the 6 % that
    // missing images gave (solver tests, contact_symmetry.rs). Friction divides the
    // tangential velocity by a regularising speed of 1e-6 c (numerics.md §12.1): where a pair
    // is at stick, as the pairs on the axis are by symmetry, that gain turns velocity
    // round-off into friction forces a million times larger, and the two models drift apart
    // (measured: at most 7e-8 of the peak in TL, 1.5e-5 in conventional SPH, whose neighbour
    // lists follow the particles). 1e-4 there, still far below the mismatches this test
    // exists to catch.
    let tolerance = if contact.contains("friction") {
        1e-4
    } else {
        1e-9
    };
    for (step, (f, h)) in full.iter().zip(&half).enumerate() {
        for q in 0..4 {
            let scale = if q == 0 { peak_force } else { energy };
            assert!(
                (2.0 * h[q] - f[q]).abs() <= tolerance * scale,
                "{formulation} {contact}: sample {step}, quantity {q}: half ×2 {} vs full {}",
                2.0 * h[q],
                f[q]
            );
        }
    }
}

#[test]
fn a_half_model_with_potential_contact_at_its_plane_matches_the_full_model() {
    assert_half_is_half_of_full("total-lagrangian", "[contact]\nscale = 0.2");
}

#[test]
fn a_half_model_with_penalty_contact_and_friction_at_its_plane_matches_the_full_model() {
    // The first scene-level run of this pair found the half model stepping differently from
    // the full one (17 % of the peak force): the penalty law's time-step vote counted a
    // partner exactly one spacing to the side at full first-touch stiffness, so whether the
    // diagonal lattice neighbour voted hung on the last bit of its position. The vote now
    // carries the tangential weight, zero at the zone's side.
    for formulation in ["total-lagrangian", "total-lagrangian-corrected"] {
        assert_half_is_half_of_full(formulation, "[contact]\nlaw = \"penalty\"\nfriction = 0.3");
    }
}

#[test]
fn an_updated_lagrangian_half_model_in_contact_at_its_plane_matches_the_full_model() {
    assert_half_is_half_of_full("updated-lagrangian", "[contact]\nscale = 0.2");
    assert_half_is_half_of_full(
        "updated-lagrangian",
        "[contact]\nlaw = \"penalty\"\nfriction = 0.3",
    );
}
