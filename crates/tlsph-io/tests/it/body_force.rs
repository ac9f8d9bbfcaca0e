//! `[body_force]` (numerics.md §4.5): parsed into the model, bad values named with field and
//! line, and a run books the potential energy in a `body_force` column.

use super::{energy_rows, error_of, line_of, PLATE_IMPACT};
use tlsph_io::{parse_scene, run_scene_to_dir, DimensionModel};

#[test]
fn a_body_force_table_becomes_the_description() {
    for (table, bodies) in [
        ("[body_force]\nacceleration = [-9.81]\n", None),
        (
            "[body_force]\nacceleration = [-9.81]\nbodies = [\"target\"]\n",
            Some(vec![0]),
        ),
    ] {
        let scene = parse_scene(&format!("{PLATE_IMPACT}\n{table}"), "scene.toml").unwrap();
        let DimensionModel::One(model) = &scene.model else {
            panic!("1D")
        };
        let b = model.effects.body_force.as_ref().expect("declared");
        assert_eq!(b.acceleration[0], -9.81);
        assert_eq!(b.bodies, bodies);
    }
}

#[test]
fn body_force_errors_name_the_field_and_line() {
    for (table, field, needle) in [
        (
            "[body_force]\nacceleration = [0.0, -9.81]\n",
            "body_force.acceleration",
            "acceleration",
        ),
        (
            "[body_force]\nacceleration = [-9.81]\nbodies = [\"flyer\"]\n",
            "body_force.bodies",
            "bodies",
        ),
        (
            "[body_force]\nacceleration = [-9.81]\nbodies = []\n",
            "body_force.bodies",
            "bodies",
        ),
        (
            "[[symmetry_plane]]\naxis = \"x\"\nposition = -0.5\n[body_force]\nacceleration = [-9.81]\n",
            "body_force.acceleration",
            "acceleration",
        ),
    ] {
        let text = format!("{PLATE_IMPACT}\n{table}");
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert_eq!(e.line, Some(line_of(&text, needle)), "{e}");
    }
    // An unknown key is refused by the TOML layer, with its line.
    let text = format!("{PLATE_IMPACT}\n[body_force]\nacceleration = [-9.81]\ngravity = 1.0\n");
    let e = error_of(&text);
    assert!(e.message.contains("gravity"), "{e}");
    assert_eq!(e.line, Some(line_of(&text, "gravity")), "{e}");
}

#[test]
fn a_run_under_gravity_books_the_potential_energy_and_the_total_closes() {
    // The plate-impact bar falling along −x while the flyer strikes it: the kinetic energy
    // grows by the potential energy booked, and the total closes as without gravity
    // (measured 2e-4 of the impact energy, the leap-frog error of the impact; bound 1e-3).
    let text = format!("{PLATE_IMPACT}\n[body_force]\nacceleration = [-0.05]\n");
    let scene = parse_scene(&text, "scene.toml").unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let (rows, column, total) = energy_rows(&dir, "body_force");
    // The booked column is −Σ m b·(x − x_start) = −M b Δx_cm, and the internal forces
    // conserve momentum, so Δx_cm = (P0/M) t + ½ b t² exactly: flyer 0.5 kg at 0.1 m/s gives
    // P0 = 0.05, the whole bar M = 2 (ρ = 1, length 2).
    let (b, p0, mass) = (-0.05, 0.05, 2.0);
    for r in &rows {
        let t = r[0];
        let expected = -b * (p0 * t + 0.5 * mass * b * t * t);
        assert!((r[column] - expected).abs() < 1e-9, "{r:?} vs {expected}");
    }
    let e0 = rows[0][total];
    for r in &rows {
        assert!((r[total] - e0).abs() < 1e-3 * e0, "{r:?}");
    }
}
