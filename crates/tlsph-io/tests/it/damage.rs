//! `damage = { ... }` on linear-elastic and elastic–plastic materials (numerics.md §9.1–9.2):
//! parsing, the default flaw seed, and located errors naming the field.

use super::{error_of, line_of};
use tlsph_io::{parse_scene, DimensionModel};
use tlsph_solver::{DamageModel, MaterialModel};

const DAMAGED: &str = r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.5
cfl = 0.3
end_time = 10.0

[[material]]
name = "bar"
model = "linear-elastic"
density = 1.0
youngs_modulus = 1.0
poisson_ratio = 0.3
damage = { model = "peerlings", kappa0 = 0.001, kappa_c = 0.01 }

[[material]]
name = "plate"
model = "linear-elastic"
density = 1.0
youngs_modulus = 1.0
poisson_ratio = 0.3
damage = { model = "grady-kipp", m = 8.5, k = 1.4e19, seed = 42 }

[[body]]
name = "bar"
material = "bar"
spacing = 1.0
box = { min = [0.0, 0.0], max = [4.0, 10.0] }

[[body]]
name = "plate"
material = "plate"
spacing = 1.0
box = { min = [10.0, 0.0], max = [18.0, 8.0] }

[[probe]]
name = "middle"
body = "bar"
at = [2.0, 5.0]
fields = ["damage", "stress_yy"]
interval = 1.0
"#;

#[test]
fn peerlings_and_grady_kipp_parse_with_their_parameters() {
    let scene = parse_scene(DAMAGED, "scene.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let MaterialModel::ElasticDamage(bar) = &model.materials[0].model else {
        panic!("bar is damaged elastic")
    };
    let DamageModel::Peerlings(p) = bar.damage else {
        panic!("Peerlings")
    };
    assert_eq!((p.kappa0(), p.kappa_c()), (0.001, 0.01));
    let MaterialModel::ElasticDamage(plate) = &model.materials[1].model else {
        panic!("plate is damaged elastic")
    };
    let DamageModel::GradyKipp { model: gk, seed } = plate.damage else {
        panic!("Grady–Kipp")
    };
    assert_eq!((gk.m(), gk.k(), seed), (8.5, 1.4e19, 42));
    // Without `seed` the documented default applies.
    let default = DAMAGED.replace(", seed = 42", "");
    let scene = parse_scene(&default, "scene.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let MaterialModel::ElasticDamage(plate) = &model.materials[1].model else {
        panic!("damaged")
    };
    assert!(matches!(
        plate.damage,
        DamageModel::GradyKipp { seed: 1, .. }
    ));
    // Without `damage` the material stays plain linear-elastic (no damage state, no cost).
    let plain = DAMAGED.replace(
        "damage = { model = \"peerlings\", kappa0 = 0.001, kappa_c = 0.01 }",
        "",
    );
    let plain = plain.replace("fields = [\"damage\", ", "fields = [");
    let scene = parse_scene(&plain, "scene.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert!(matches!(
        model.materials[0].model,
        MaterialModel::LinearElastic(_)
    ));
}

#[test]
fn damage_errors_name_the_field_and_line() {
    let peerlings = "damage = { model = \"peerlings\", kappa0 = 0.001, kappa_c = 0.01 }";
    let grady = "damage = { model = \"grady-kipp\", m = 8.5, k = 1.4e19, seed = 42 }";
    // (replace, with, field, message fragment)
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            peerlings,
            "damage = { model = \"peerlings\", kappa0 = 0.0, kappa_c = 0.01 }",
            "material[bar].damage.kappa0",
            "greater than 0",
        ),
        (
            peerlings,
            "damage = { model = \"peerlings\", kappa0 = 0.01, kappa_c = 0.005 }",
            "material[bar].damage.kappa_c",
            "greater than kappa0",
        ),
        (
            peerlings,
            "damage = { model = \"peerlings\", kappa0 = 0.001 }",
            "material[bar].damage.kappa_c",
            "is required by damage model `peerlings`",
        ),
        (
            peerlings,
            "damage = { model = \"peerlings\", kappa0 = 0.001, kappa_c = 0.01, m = 2.0 }",
            "material[bar].damage.m",
            "not a parameter of damage model `peerlings`",
        ),
        (
            peerlings,
            "damage = { model = \"mazars\" }",
            "material[bar].damage.model",
            "unknown damage model `mazars`",
        ),
        (
            grady,
            "damage = { model = \"grady-kipp\", m = -8.5, k = 1.4e19 }",
            "material[plate].damage.m",
            "greater than 0",
        ),
        (
            grady,
            "damage = { model = \"grady-kipp\", m = 8.5, k = 0.0 }",
            "material[plate].damage.k",
            "greater than 0",
        ),
        (
            grady,
            "damage = { model = \"grady-kipp\", m = 8.5, k = 1.4e19, seed = -3 }",
            "material[plate].damage.seed",
            "integer ≥ 0",
        ),
        (
            grady,
            "damage = { model = \"grady-kipp\", k = 1.4e19 }",
            "material[plate].damage.m",
            "is required",
        ),
    ];
    for (from, to, field, fragment) in cases {
        let text = DAMAGED.replace(from, to);
        assert_ne!(text, DAMAGED, "case {field} did not change the scene");
        let err = error_of(&text);
        assert_eq!(err.field, *field, "{err}");
        assert!(err.message.contains(fragment), "{field}: {err}");
        assert_eq!(err.line, Some(line_of(&text, to)), "{field}: {err}");
    }
}

/// The first material of [`DAMAGED`] made elastic-plastic (σ_y = 0.02) with `extra` lines.
fn plastic_bar(extra: &str) -> String {
    DAMAGED.replacen(
        "model = \"linear-elastic\"",
        &format!("model = \"elastic-plastic\"\nyield_stress = 0.02\n{extra}"),
        1,
    )
}

#[test]
fn elastic_plastic_and_johnson_cook_materials_take_damage() {
    let scene = parse_scene(&plastic_bar(""), "scene.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let MaterialModel::ElasticPlastic(bar) = &model.materials[0].model else {
        panic!("bar is elastic-plastic")
    };
    assert!(bar.failure.is_none());
    let Some(DamageModel::Peerlings(p)) = bar.damage else {
        panic!("Peerlings on the plastic bar")
    };
    assert_eq!((p.kappa0(), p.kappa_c()), (0.001, 0.01));
    assert!(model.materials[0].model.has_damage());
    // Johnson–Cook strength with Grady–Kipp flaws.
    let text = DAMAGED.replacen(
        "model = \"linear-elastic\"\ndensity = 1.0\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\ndamage = { model = \"grady-kipp\"",
        "model = \"johnson-cook\"\ndensity = 1.0\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\na = 0.01\nb = 0.02\nn = 0.3\nc = 0.0\nm = 1.0\nreference_strain_rate = 1.0\nroom_temperature = 293.0\nmelt_temperature = 1000.0\ndamage = { model = \"grady-kipp\"",
        1,
    );
    assert_ne!(text, DAMAGED);
    let scene = parse_scene(&text, "scene.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let MaterialModel::ElasticPlastic(plate) = &model.materials[1].model else {
        panic!("plate is Johnson–Cook")
    };
    assert!(matches!(
        plate.damage,
        Some(DamageModel::GradyKipp { seed: 42, .. })
    ));
    // Without `damage` nothing of it exists.
    let plain = plastic_bar("").replace(
        "damage = { model = \"peerlings\", kappa0 = 0.001, kappa_c = 0.01 }",
        "",
    );
    let plain = plain.replace("fields = [\"damage\", ", "fields = [");
    let scene = parse_scene(&plain, "scene.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let MaterialModel::ElasticPlastic(bar) = &model.materials[0].model else {
        panic!("bar is elastic-plastic")
    };
    assert!(bar.damage.is_none() && !model.materials[0].model.has_damage());
}

#[test]
fn damage_and_a_failure_criterion_are_read_together() {
    // The particle fails by whichever comes first (docs/scene-format.md, "Damage on plastic
    // materials"): both reach the model.
    let text = plastic_bar("failure = { model = \"max-plastic-strain\", limit = 0.1 }");
    let scene = parse_scene(&text, "scene.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let MaterialModel::ElasticPlastic(bar) = &model.materials[0].model else {
        panic!("bar is elastic-plastic")
    };
    assert!(matches!(bar.damage, Some(DamageModel::Peerlings(_))));
    assert!(matches!(
        bar.failure,
        Some(tlsph_solver::FailureModel::MaxPlasticStrain(_))
    ));
}

#[test]
fn damage_is_rejected_where_it_cannot_act() {
    // With an initial stress (the effective stress starts at zero, so it would be lost).
    let text = plastic_bar("").replacen(
        "spacing = 1.0\n",
        "spacing = 1.0\ninitial_stress = { xx = 0.001 }\n",
        1,
    );
    let err = error_of(&text);
    assert_eq!(err.field, "body[bar].initial_stress", "{err}");
    assert!(err.message.contains("damage model"), "{err}");
    // With the Green–Lagrange update (the damaged stress is the Jaumann-rate one).
    let text = DAMAGED.replace(
        "kernel = \"cubic-spline\"",
        "stress_update = \"green-lagrange\"\nkernel = \"cubic-spline\"",
    );
    let err = error_of(&text);
    assert_eq!(err.field, "simulation.stress_update");
    assert!(err.message.contains("damaged"), "{err}");
    // A damage probe on a body without damage.
    let text = DAMAGED.replace(
        "damage = { model = \"peerlings\", kappa0 = 0.001, kappa_c = 0.01 }",
        "",
    );
    let err = error_of(&text);
    assert_eq!(err.field, "probe[middle].fields");
}

/// [`DAMAGED`] with `extra` appended to the bar body's table.
fn with_bar_lines(extra: &str) -> String {
    let anchor = "box = { min = [0.0, 0.0], max = [4.0, 10.0] }\n";
    assert_eq!(DAMAGED.matches(anchor).count(), 1);
    DAMAGED.replace(anchor, &format!("{anchor}{extra}\n"))
}

fn model_2d(scene: tlsph_io::Scene) -> tlsph_solver::Model<2> {
    match scene.model {
        DimensionModel::Two(m) => m,
        _ => unreachable!("a 2D scene"),
    }
}

#[test]
fn an_initial_damage_is_read_uniform_or_from_a_table() {
    // Uniform: every particle of the bar, none of the plate, and the run starts from it.
    let model = model_2d(parse_scene(&with_bar_lines("initial_damage = 0.2"), "s.toml").unwrap());
    assert_eq!(model.bodies[0].initial_damage, Some(vec![0.2; 40]));
    assert_eq!(model.bodies[1].initial_damage, None);
    let sim = tlsph_solver::Simulation::new(model).unwrap();
    assert_eq!(sim.sample(tlsph_solver::ParticleField::Damage, 7), 0.2);
    // A table of D = 0.1 X on x = 0.5, 1.5, 2.5 (every y): the linear fit gives it back on the
    // sampled columns and would extrapolate to 0.35 on the bar's last one, x = 3.5; it is
    // kept within the table's largest value, 0.25.
    let dir = tempfile::tempdir().unwrap();
    let mut table = String::from("x, y, damage\n");
    for x in [0.5, 1.5, 2.5] {
        for j in 0..10 {
            table += &format!("{x}, {}, {}\n", j as f64 + 0.5, 0.1 * x);
        }
    }
    let key = "initial_damage_file = { path = \"fields/d.csv\", reach = 2.5, interpolation = \"linear\" }";
    let scene = super::load_with_table(dir.path(), &with_bar_lines(key), "fields/d.csv", &table);
    let model = model_2d(scene.unwrap());
    let body = &model.bodies[0];
    let damage = body.initial_damage.as_ref().unwrap();
    let mut extrapolated = 0;
    for (x, d) in body.positions.iter().zip(damage) {
        if x.x < 3.0 {
            assert!((d - 0.1 * x.x).abs() < 1e-14, "D {d} at {x:?}");
        } else {
            assert_eq!(*d, 0.25, "D at {x:?}");
            extrapolated += 1;
        }
    }
    assert_eq!(extrapolated, 10);
}

#[test]
fn initial_damage_errors_name_the_field_and_line() {
    let e = parse_scene(&with_bar_lines("initial_damage = 1.0"), "s.toml").unwrap_err();
    assert_eq!(e.field, "body[bar].initial_damage", "{e}");
    assert!(
        e.message
            .contains("finite number ≥ 0 and < 1, got 1 (D = 1 is a failed"),
        "{e}"
    );
    // A material without a damage law.
    let peerlings = "damage = { model = \"peerlings\", kappa0 = 0.001, kappa_c = 0.01 }\n";
    let undamaged = with_bar_lines("initial_damage = 0.1").replace(peerlings, "");
    let e = parse_scene(&undamaged, "s.toml").unwrap_err();
    assert_eq!(e.field, "body[bar].initial_damage", "{e}");
    assert!(
        e.message.contains("material `bar` has no damage law"),
        "{e}"
    );
    // A table cell of 1 (a failed particle) names its line; both keys together are refused.
    let dir = tempfile::tempdir().unwrap();
    let key = "initial_damage_file = { path = \"fields/d.csv\", reach = 10.0 }";
    let table = "x, y, damage\n1.0, 1.0, 0.5\n3.0, 5.0, 1.0\n";
    let e = super::load_with_table(dir.path(), &with_bar_lines(key), "fields/d.csv", table)
        .unwrap_err();
    assert_eq!(e.field, "body[bar].initial_damage_file.path", "{e}");
    assert!(
        e.message.contains("line 3: `damage` must be ≥ 0 and < 1"),
        "{e}"
    );
    let both = with_bar_lines(&format!("{key}\ninitial_damage = 0.1"));
    let table = "x, y, damage\n1.0, 1.0, 0.5\n";
    let e = super::load_with_table(dir.path(), &both, "fields/d.csv", table).unwrap_err();
    assert_eq!(e.field, "body[bar].initial_damage_file", "{e}");
    assert!(
        e.message
            .contains("`initial_damage` cannot be declared with it"),
        "{e}"
    );
}

/// [`plastic_bar`] with a Johnson–Cook failure law of constant failure strain 0.5 in place of
/// its softening law when `softening` is false, beside it when true, and `extra` appended to
/// the bar body's table.
fn johnson_cook_failure_bar(softening: bool, extra: &str) -> String {
    let failure = "failure = { model = \"johnson-cook\", d = [0.5, 0.0, 0.0, 0.0, 0.0], reference_strain_rate = 1.0, room_temperature = 293.0, melt_temperature = 1356.0 }";
    let peerlings = "damage = { model = \"peerlings\", kappa0 = 0.001, kappa_c = 0.01 }\n";
    let mut text = plastic_bar(failure);
    if !softening {
        assert_eq!(text.matches(peerlings).count(), 1);
        text = text.replace(peerlings, "");
    }
    let anchor = "box = { min = [0.0, 0.0], max = [4.0, 10.0] }\n";
    assert_eq!(text.matches(anchor).count(), 1);
    text.replace(anchor, &format!("{anchor}{extra}\n"))
}

#[test]
fn an_initial_johnson_cook_failure_damage_is_read_uniform_or_from_a_table() {
    // Uniform: every particle of the bar, none of the plate, and the run starts from it.
    let text = johnson_cook_failure_bar(false, "initial_failure_damage = 0.3");
    let model = model_2d(parse_scene(&text, "s.toml").unwrap());
    assert_eq!(model.bodies[0].initial_failure_damage, Some(vec![0.3; 40]));
    assert_eq!(model.bodies[0].initial_damage, None);
    assert_eq!(model.bodies[1].initial_failure_damage, None);
    let sim = tlsph_solver::Simulation::new(model).unwrap();
    assert_eq!(sim.sample(tlsph_solver::ParticleField::Damage, 7), 0.3);
    // With a softening law as well, each key sets its own variable.
    let both = "initial_failure_damage = 0.3\ninitial_damage = 0.1";
    let model = model_2d(parse_scene(&johnson_cook_failure_bar(true, both), "s.toml").unwrap());
    assert_eq!(model.bodies[0].initial_failure_damage, Some(vec![0.3; 40]));
    assert_eq!(model.bodies[0].initial_damage, Some(vec![0.1; 40]));
    // A table (nearest sample): D = 0.2 on the bar's left half, 0.6 on its right.
    let dir = tempfile::tempdir().unwrap();
    let table = "x, y, damage\n1.0, 5.0, 0.2\n3.0, 5.0, 0.6\n";
    let key = "initial_failure_damage_file = { path = \"fields/d.csv\", reach = 10.0 }";
    let text = johnson_cook_failure_bar(false, key);
    let scene = super::load_with_table(dir.path(), &text, "fields/d.csv", table).unwrap();
    assert_eq!(scene.field_tables.len(), 1);
    assert_eq!(
        scene.field_tables[0].field,
        "body[bar].initial_failure_damage_file"
    );
    let model = model_2d(scene);
    let body = &model.bodies[0];
    for (x, d) in body
        .positions
        .iter()
        .zip(body.initial_failure_damage.as_ref().unwrap())
    {
        assert_eq!(*d, if x.x < 2.0 { 0.2 } else { 0.6 }, "D at {x:?}");
    }
}

#[test]
fn initial_failure_damage_errors_name_the_field_and_the_other_key() {
    let text = johnson_cook_failure_bar(false, "initial_failure_damage = 1.0");
    let e = parse_scene(&text, "s.toml").unwrap_err();
    assert_eq!(e.field, "body[bar].initial_failure_damage", "{e}");
    assert!(e.message.contains("≥ 0 and < 1, got 1"), "{e}");
    // A softening law is not a failure law, and the softening key on a material with only the
    // failure law points to the failure key.
    let e = parse_scene(&with_bar_lines("initial_failure_damage = 0.1"), "s.toml").unwrap_err();
    assert_eq!(e.field, "body[bar].initial_failure_damage", "{e}");
    assert!(
        e.message
            .contains("material `bar` has no Johnson–Cook failure law"),
        "{e}"
    );
    let text = johnson_cook_failure_bar(false, "initial_damage = 0.1");
    let e = parse_scene(&text, "s.toml").unwrap_err();
    assert_eq!(e.field, "body[bar].initial_damage", "{e}");
    assert!(e.message.contains("set by `initial_failure_damage`"), "{e}");
    let dir = tempfile::tempdir().unwrap();
    let both = "initial_failure_damage_file = { path = \"d.csv\" }\ninitial_failure_damage = 0.1";
    let text = johnson_cook_failure_bar(false, both);
    let e = super::load_with_table(dir.path(), &text, "d.csv", "x, y, damage\n1.0, 1.0, 0.5\n")
        .unwrap_err();
    assert_eq!(e.field, "body[bar].initial_failure_damage_file", "{e}");
    assert!(
        e.message
            .contains("`initial_failure_damage` cannot be declared with it"),
        "{e}"
    );
}

#[test]
fn each_of_two_damages_has_its_own_output_field() {
    // A bar with both laws, started at softening D 0.1 and Johnson–Cook D 0.3: `damage` merges
    // them (the larger), `softening_damage` and `failure_damage` give each, in probes and in
    // the frames; with one law the frames carry `damage` only.
    use tlsph_solver::ParticleField;
    let both = "initial_failure_damage = 0.3\ninitial_damage = 0.1";
    let text = johnson_cook_failure_bar(true, both).replace(
        "fields = [\"damage\", \"stress_yy\"]",
        "fields = [\"damage\", \"softening_damage\", \"failure_damage\"]",
    );
    let scene = parse_scene(&text, "s.toml").unwrap();
    assert_eq!(
        scene.probes[0].fields,
        [
            ParticleField::Damage,
            ParticleField::SofteningDamage,
            ParticleField::FailureDamage
        ]
    );
    let sim = tlsph_solver::Simulation::new(model_2d(scene)).unwrap();
    let sample = |field| sim.sample(field, 7);
    assert_eq!(sample(ParticleField::Damage), 0.3);
    assert_eq!(sample(ParticleField::SofteningDamage), 0.1);
    assert_eq!(sample(ParticleField::FailureDamage), 0.3);
    let frame = tlsph_io::frame_of(&sim);
    let array = |name: &str| frame.arrays.iter().find(|a| a.name == name);
    assert_eq!(array("softening_damage").unwrap().values[7], 0.1);
    assert_eq!(array("failure_damage").unwrap().values[7], 0.3);
    assert_eq!(array("damage").unwrap().values[7], 0.3);
    let one_law = johnson_cook_failure_bar(false, "initial_failure_damage = 0.3");
    let sim = tlsph_solver::Simulation::new(model_2d(parse_scene(&one_law, "s.toml").unwrap()));
    let frame = tlsph_io::frame_of(&sim.unwrap());
    let names: Vec<&str> = frame.arrays.iter().map(|a| a.name.as_str()).collect();
    assert!(names.contains(&"damage"), "{names:?}");
    assert!(!names.iter().any(|n| n.ends_with("_damage")), "{names:?}");
    // A probe of a damage the body's material does not have is refused.
    let softening_only = with_bar_lines("").replace(
        "fields = [\"damage\", \"stress_yy\"]",
        "fields = [\"failure_damage\"]",
    );
    let e = error_of(&softening_only);
    assert_eq!(e.field, "probe[middle].fields", "{e}");
    assert!(
        e.message
            .contains("`failure_damage` needs a `failure` criterion"),
        "{e}"
    );
    let failure_only = johnson_cook_failure_bar(false, "").replace(
        "fields = [\"damage\", \"stress_yy\"]",
        "fields = [\"softening_damage\"]",
    );
    let e = error_of(&failure_only);
    assert!(
        e.message
            .contains("`softening_damage` needs a `damage` law"),
        "{e}"
    );
}
