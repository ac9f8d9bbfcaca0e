//! `[contact]` (numerics.md §12.2): parsed into the model, bad values named with field and
//! line, and a run books a `contact` energy column.

use super::{energy_rows, error_of, line_of};
use tlsph_io::{parse_scene, run_scene_to_dir, DimensionModel};
use tlsph_solver::FrictionCoefficients;

const TWO_BARS: &str = r#"
[simulation]
dimension = 1
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.5
end_time = 1.5

[[material]]
name = "unit"
model = "linear-elastic"
density = 1.0
youngs_modulus = 0.9
poisson_ratio = 0.2

[[body]]
name = "flyer"
material = "unit"
spacing = 0.02
box = { min = [-0.5], max = [0.0] }
velocity = [0.01]

[[body]]
name = "target"
material = "unit"
spacing = 0.02
box = { min = [0.0], max = [1.0] }

[contact]
scale = 0.2
pairs = [["flyer", "target"]]

[output]
energy_interval = 0.01
"#;

#[test]
fn a_contact_table_becomes_the_contact_description() {
    let scene = parse_scene(TWO_BARS, "scene.toml").unwrap();
    let DimensionModel::One(model) = &scene.model else {
        panic!("1D")
    };
    let c = model.effects.contact.as_ref().unwrap();
    assert_eq!((c.scale, c.exponent), (0.2, 4.0));
    assert_eq!(c.pairs, Some(vec![(0, 1)]));
    let all = parse_scene(
        &TWO_BARS.replace("pairs = [[\"flyer\", \"target\"]]", "exponent = 6"),
        "scene.toml",
    )
    .unwrap();
    let DimensionModel::One(model) = &all.model else {
        panic!("1D")
    };
    let c = model.effects.contact.as_ref().unwrap();
    assert_eq!((c.exponent, c.pairs.clone()), (6.0, None));
}

#[test]
fn a_body_paired_with_itself_is_self_contact_in_tlsph_only() {
    let text = TWO_BARS.replace(
        "pairs = [[\"flyer\", \"target\"]]",
        "pairs = [[\"flyer\", \"target\"], [\"target\", \"target\"]]",
    );
    let scene = parse_scene(&text, "scene.toml").unwrap();
    let DimensionModel::One(model) = &scene.model else {
        panic!("1D")
    };
    let pairs = model.effects.contact.as_ref().unwrap().pairs.clone();
    assert_eq!(pairs, Some(vec![(0, 1), (1, 1)]));
    // With the updated-Lagrangian formulation a body already interacts with itself through
    // the kernel: refused, naming the field and the line.
    let text = text.replace(
        "formulation = \"total-lagrangian-corrected\"",
        "formulation = \"updated-lagrangian\"\n",
    );
    let text = text.replace(
        "material = \"unit\"\nspacing = 0.02\nbox = { min = [0.0]",
        "material = \"unit\"\nkernel_group = \"t\"\nspacing = 0.02\nbox = { min = [0.0]",
    );
    let e = error_of(&text);
    assert_eq!(e.field, "contact.pairs", "{e}");
    assert!(e.message.contains("self-contact"), "{e}");
    assert_eq!(e.line, Some(line_of(&text, "pairs =")), "{e}");
}

#[test]
fn both_laws_take_self_contact_but_not_with_a_reference_update() {
    for law in ["scale = 0.2", "law = \"penalty\"\nfriction = 0.3"] {
        let text = TWO_BARS.replace(
            "scale = 0.2\npairs = [[\"flyer\", \"target\"]]",
            &format!("{law}\npairs = [[\"flyer\", \"target\"], [\"target\", \"target\"]]"),
        );
        let scene = parse_scene(&text, "scene.toml").unwrap();
        let DimensionModel::One(model) = &scene.model else {
            panic!("1D")
        };
        let pairs = match (&model.effects.contact, &model.effects.penalty_contact) {
            (Some(c), None) => c.pairs.clone(),
            (None, Some(c)) => c.pairs.clone(),
            other => panic!("one law expected, got {other:?}"),
        };
        assert_eq!(pairs, Some(vec![(0, 1), (1, 1)]), "{law}");
        // A new reference would bond the surfaces that self-contact holds together.
        let text = format!("{text}\n[reference_update]\nstrain_threshold = 0.1\n");
        let e = error_of(&text);
        assert_eq!(e.field, "reference_update", "{e}");
        assert!(e.message.contains("self-contact of body `target`"), "{e}");
        assert_eq!(e.line, Some(line_of(&text, "strain_threshold =")), "{e}");
    }
}

#[test]
fn bad_contact_values_are_named_with_field_and_line() {
    let cases = [
        ("scale = 0.2", "scale = -0.2", "contact.scale"),
        (
            "scale = 0.2",
            "scale = 0.2\nexponent = 0.5",
            "contact.exponent",
        ),
        (
            "pairs = [[\"flyer\", \"target\"]]",
            "pairs = [[\"flyer\", \"anvil\"]]",
            "contact.pairs",
        ),
        (
            "pairs = [[\"flyer\", \"target\"]]",
            "pairs = [[\"flyer\"]]",
            "contact.pairs",
        ),
        // Same material in the updated-Lagrangian formulation: already kernel-coupled.
        (
            "formulation = \"total-lagrangian-corrected\"",
            "formulation = \"updated-lagrangian\"",
            "contact.pairs",
        ),
    ];
    for (from, to, field) in cases {
        let text = TWO_BARS.replace(from, to);
        let e = error_of(&text);
        assert_eq!(e.field, field, "{to}: {e}");
        let needle = if field == "contact.pairs" {
            "pairs ="
        } else {
            to.lines().last().unwrap()
        };
        assert_eq!(e.line, Some(line_of(&text, needle)), "{to}: {e}");
    }
    // A missing scale is named by the TOML layer with its line.
    let text = TWO_BARS.replace("scale = 0.2\n", "");
    let e = error_of(&text);
    assert!(e.message.contains("scale"), "{e}");
    assert!(e.line.is_some(), "{e}");
}

#[test]
fn a_contact_run_books_its_energy_column_and_closes() {
    let scene = parse_scene(TWO_BARS, "scene.toml").unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let (rows, contact, total) = energy_rows(&dir, "contact");
    assert!(
        rows.iter().any(|r| r[contact] > 0.0),
        "contact stored energy"
    );
    // Impact energy ½ m v² = ½ · 0.5 · 1e-4; total closes to 1.5 % of it (see the solver's
    // contact tests for the bound).
    let e0 = rows[0][total];
    for r in &rows {
        assert!((r[total] - e0).abs() < 1.5e-2 * e0, "{r:?}");
    }
}

/// `TWO_BARS` with Fuller's penalty law instead of the potential one.
fn penalty_bars(keys: &str) -> String {
    TWO_BARS.replace("scale = 0.2\n", &format!("law = \"penalty\"\n{keys}"))
}

#[test]
fn a_penalty_contact_table_becomes_the_penalty_description() {
    let scene = parse_scene(&penalty_bars("friction = 0.3\nrange = 1.5\n"), "scene.toml").unwrap();
    let DimensionModel::One(model) = &scene.model else {
        panic!("1D")
    };
    assert!(model.effects.contact.is_none());
    let c = model.effects.penalty_contact.as_ref().unwrap();
    assert_eq!((c.stiffness, c.range), (1.0, 1.5));
    // Without `static_friction` one coefficient sticks and slides.
    assert_eq!(c.friction, FrictionCoefficients::single(0.3));
    assert_eq!(c.pairs, Some(vec![(0, 1)]));
    let scene = parse_scene(
        &penalty_bars(
            "friction = 0.3
static_friction = 0.5
friction_decay = 20.0
",
        ),
        "scene.toml",
    )
    .unwrap();
    let DimensionModel::One(model) = &scene.model else {
        panic!("1D")
    };
    let c = model.effects.penalty_contact.as_ref().unwrap();
    assert_eq!(
        c.friction,
        FrictionCoefficients {
            kinetic: 0.3,
            static_coefficient: 0.5,
            decay: Some(20.0)
        }
    );
    // `law = "potential"` is the default law, spelled out.
    let scene = parse_scene(
        &TWO_BARS.replace("scale = 0.2\n", "law = \"potential\"\nscale = 0.2\n"),
        "scene.toml",
    )
    .unwrap();
    let DimensionModel::One(model) = &scene.model else {
        panic!("1D")
    };
    assert!(model.effects.contact.is_some() && model.effects.penalty_contact.is_none());
}

#[test]
fn bad_penalty_contact_keys_are_named_with_field_and_line() {
    let cases = [
        (
            penalty_bars("friction = -0.1\n"),
            "contact.friction",
            "friction =",
        ),
        (
            penalty_bars("stiffness = 0\n"),
            "contact.stiffness",
            "stiffness =",
        ),
        (penalty_bars("range = -1\n"), "contact.range", "range ="),
        (
            penalty_bars("friction = 0.3\nstatic_friction = 0.2\n"),
            "contact.static_friction",
            "static_friction =",
        ),
        // A decay without a static coefficient above the kinetic one has nothing to decay.
        (
            penalty_bars("friction = 0.3\nfriction_decay = 10.0\n"),
            "contact.friction_decay",
            "friction_decay =",
        ),
        (
            penalty_bars("friction = 0.3\nstatic_friction = 0.5\nfriction_decay = -1.0\n"),
            "contact.friction_decay",
            "friction_decay =",
        ),
        // A key of the other law.
        (penalty_bars("scale = 0.2\n"), "contact.scale", "scale ="),
        (
            TWO_BARS.replace("scale = 0.2\n", "scale = 0.2\nfriction = 0.2\n"),
            "contact.friction",
            "friction =",
        ),
        (
            TWO_BARS.replace("scale = 0.2\n", "scale = 0.2\nstatic_friction = 0.2\n"),
            "contact.static_friction",
            "static_friction =",
        ),
        (
            TWO_BARS.replace("scale = 0.2\n", "law = \"coulomb\"\n"),
            "contact.law",
            "law =",
        ),
    ];
    for (text, field, needle) in cases {
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert_eq!(e.line, Some(line_of(&text, needle)), "{e}");
    }
}

#[test]
fn a_penalty_contact_run_books_its_work_and_closes() {
    // The penalty force is not a potential gradient: its work is booked in the `contact`
    // column, which holds the energy of the compressed pairs while the bars touch and returns
    // to about zero once they part (frictionless). Total closes as for the potential law.
    let scene = parse_scene(&penalty_bars(""), "scene.toml").unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let (rows, contact, total) = energy_rows(&dir, "contact");
    let e0 = rows[0][total];
    assert!(rows.iter().any(|r| r[contact] > 1e-2 * e0), "contact work");
    for r in &rows {
        assert!((r[total] - e0).abs() < 1.5e-2 * e0, "{r:?}");
    }
}
