//! Plastic materials, equations of state, rigid walls and hourglass control in scene files:
//! parsing, located errors, the Green–Lagrange setup error and the files a wall run writes.

use super::{error_of, line_of};
use std::fs;
use tlsph_io::{parse_scene, run_scene_to_dir, DimensionModel};
use tlsph_materials::EquationOfState;
use tlsph_solver::{MaterialModel, PressureModel, StrengthModel};

/// A copper bar (elastic-plastic, hypoelastic pressure) and a copper plate (Johnson–Cook with a
/// Mie–Grüneisen EOS and adiabatic heating), a wall under the bar and hourglass control.
const PLASTIC: &str = r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
stress_update = "jaumann-rate"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 1.0e-6

[[material]]
name = "copper"
model = "elastic-plastic"
density = 8990.0
youngs_modulus = 110.0e9
poisson_ratio = 0.343
yield_stress = 90.0e6
tangent_modulus = 1.1e9

[[material]]
name = "cu9"
model = "johnson-cook"
density = 8960.0
youngs_modulus = 128.4e9
poisson_ratio = 0.346
a = 90.0e6
b = 292.0e6
n = 0.31
c = 0.025
m = 1.09
reference_strain_rate = 1.0
room_temperature = 300.0
melt_temperature = 1356.0
specific_heat = 383.0
min_pressure = -1.0e9
eos = { model = "mie-gruneisen", sound_speed = 3940.0, s1 = 1.489, gamma0 = 2.02, a = 0.47 }

[[body]]
name = "bar"
material = "copper"
spacing = 0.5e-3
box = { min = [-2.0e-3, 0.0], max = [2.0e-3, 8.0e-3] }
velocity = [0.0, -100.0]

[[body]]
name = "plate"
material = "cu9"
spacing = 0.5e-3
box = { min = [10.0e-3, 0.0], max = [14.0e-3, 2.0e-3] }

[[wall]]
name = "anvil"
point = [0.0, 0.0]
normal = [0.0, 2.0]

[hourglass_control]
coefficient = 1.0

[[probe]]
name = "bar-foot"
body = "bar"
at = [0.0, 0.0]
fields = ["plastic_strain", "stress_yy"]
interval = 1.0e-7

[[probe]]
name = "plate-mid"
body = "plate"
at = [12.0e-3, 1.0e-3]
fields = ["temperature", "plastic_strain"]
interval = 1.0e-7
"#;

/// A 1D elastic-plastic bar striking a wall at x = 0 (50 particles, a few hundred steps).
const BAR_ON_WALL: &str = r#"
[simulation]
dimension = 1
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 2.0e-6

[[material]]
name = "copper"
model = "elastic-plastic"
density = 8990.0
youngs_modulus = 110.0e9
poisson_ratio = 0.343
yield_stress = 90.0e6

[[body]]
name = "bar"
material = "copper"
spacing = 0.1e-3
box = { min = [0.0], max = [5.0e-3] }
velocity = [-100.0]

[[wall]]
name = "anvil"
point = [0.0]
normal = [1.0]

[[probe]]
name = "foot"
body = "bar"
at = [0.0]
fields = ["plastic_strain", "stress_xx"]
interval = 1.0e-7

[output]
energy_interval = 1.0e-7
"#;

#[test]
fn plastic_materials_a_wall_and_hourglass_control_parse() {
    let scene = parse_scene(PLASTIC, "plastic.toml").unwrap();
    let DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let MaterialModel::ElasticPlastic(copper) = &model.materials[0].model else {
        panic!("copper is elastic-plastic")
    };
    let StrengthModel::VonMises(vm) = copper.strength else {
        panic!("von Mises")
    };
    // tangent_modulus E_t is converted to the plastic modulus E_p = E E_t/(E − E_t).
    let expected = 110.0e9 * 1.1e9 / (110.0e9 - 1.1e9);
    assert!((vm.plastic_modulus() / expected - 1.0).abs() < 1e-12);
    assert_eq!(vm.initial_yield_stress(), 90.0e6);
    assert!(matches!(copper.pressure, PressureModel::Hypoelastic));
    assert_eq!(copper.min_pressure, None);
    assert!(copper.thermal.is_none());

    let MaterialModel::ElasticPlastic(cu9) = &model.materials[1].model else {
        panic!("cu9 is elastic-plastic")
    };
    let StrengthModel::JohnsonCook { model: jc, iterate } = cu9.strength else {
        panic!("Johnson-Cook")
    };
    assert!(iterate, "accurate_iteration defaults to true");
    assert_eq!(jc.parameters().n, 0.31);
    assert_eq!(jc.parameters().melt_temperature, 1356.0);
    let PressureModel::Eos(EquationOfState::MieGruneisen(mg)) = cu9.pressure else {
        panic!("Mie-Gruneisen")
    };
    // The reference density is the material's; s2 and s3 default to 0.
    assert_eq!(mg.parameters().reference_density, 8960.0);
    assert_eq!((mg.parameters().s2, mg.parameters().s3), (0.0, 0.0));
    assert_eq!(mg.parameters().a, 0.47);
    assert_eq!(cu9.min_pressure, Some(-1.0e9));
    let thermal = cu9.thermal.expect("specific_heat enables heating");
    assert_eq!(
        (thermal.specific_heat, thermal.room_temperature),
        (383.0, 300.0)
    );

    let wall = &model.effects.walls[0];
    assert_eq!(wall.name, "anvil");
    assert_eq!((wall.point[0], wall.point[1]), (0.0, 0.0));
    assert_eq!(wall.normal[1], 2.0, "the normal is kept as given");
    assert_eq!(model.effects.hourglass_control, Some(1.0));
    assert_eq!(scene.probes.len(), 2);
}

#[test]
fn hardening_defaults_and_other_eos_models_parse() {
    let material = |extra: &str| {
        let text = PLASTIC.replace("tangent_modulus = 1.1e9", extra);
        let scene = parse_scene(&text, "plastic.toml").unwrap_or_else(|e| panic!("{extra}: {e}"));
        let DimensionModel::Two(model) = scene.model else {
            panic!("2D")
        };
        let MaterialModel::ElasticPlastic(m) = model.materials[0].model else {
            panic!("elastic-plastic")
        };
        m
    };
    // Neither tangent_modulus nor plastic_modulus: perfectly plastic.
    let m = material("");
    let StrengthModel::VonMises(vm) = m.strength else {
        panic!()
    };
    assert_eq!(vm.plastic_modulus(), 0.0);
    // plastic_modulus is used as given.
    let StrengthModel::VonMises(vm) = material("plastic_modulus = 300.0e6").strength else {
        panic!()
    };
    assert_eq!(vm.plastic_modulus(), 300.0e6);
    let m = material("eos = { model = \"linear\", bulk_modulus = 140.0e9 }");
    let PressureModel::Eos(EquationOfState::Linear(eos)) = m.pressure else {
        panic!("linear EOS")
    };
    assert_eq!(eos.bulk_modulus_at_reference(), 140.0e9);
    let m = material(
        "eos = { model = \"polynomial\", coefficients = [0.0, 140.0e9, 0.0, 0.0, 2.0, 0.0, 0.0] }",
    );
    let PressureModel::Eos(EquationOfState::Polynomial(eos)) = m.pressure else {
        panic!("polynomial EOS")
    };
    assert_eq!(eos.coefficients()[4], 2.0);
    let m = material("specific_heat = 383.0\nroom_temperature = 293.0");
    assert_eq!(m.thermal.map(|t| t.room_temperature), Some(293.0));
    // accurate_iteration = false selects the single radial return.
    let text = PLASTIC.replace(
        "melt_temperature = 1356.0",
        "melt_temperature = 1356.0\naccurate_iteration = false",
    );
    let DimensionModel::Two(model) = parse_scene(&text, "jc.toml").unwrap().model else {
        panic!("2D")
    };
    let MaterialModel::ElasticPlastic(m) = model.materials[1].model else {
        panic!()
    };
    assert!(matches!(
        m.strength,
        StrengthModel::JohnsonCook { iterate: false, .. }
    ));
}

#[test]
fn material_wall_and_hourglass_errors_are_named_with_field_and_line() {
    // (replace, with, field, a text on the line the error must point at, message fragment)
    let cases: &[(&str, &str, &str, &str, &str)] = &[
        (
            "tangent_modulus = 1.1e9",
            "n = 0.3",
            "material[copper].n",
            "n = 0.3",
            "not a parameter of model `elastic-plastic`",
        ),
        (
            "yield_stress = 90.0e6",
            "",
            "material[copper].yield_stress",
            "model = \"elastic-plastic\"",
            "is required by model `elastic-plastic`",
        ),
        (
            "melt_temperature = 1356.0",
            "melt_temperature = 250.0",
            "material[cu9].melt_temperature",
            "melt_temperature = 250.0",
            "greater than room_temperature",
        ),
        (
            "model = \"mie-gruneisen\"",
            "model = \"tillotson\"",
            "material[cu9].eos.model",
            "model = \"tillotson\"",
            "unknown EOS model `tillotson`",
        ),
        (
            "eos = { model = \"mie-gruneisen\", sound_speed = 3940.0, s1 = 1.489, gamma0 = 2.02, a = 0.47 }",
            "eos = { model = \"polynomial\", coefficients = [0.0, 1.4e11, 0.0, 0.0, 0.0, 0.0] }",
            "material[cu9].eos.coefficients",
            "model = \"polynomial\"",
            "needs 7 values C0..C6, got 6",
        ),
        (
            "fields = [\"plastic_strain\", \"stress_yy\"]",
            "fields = [\"temperature\", \"stress_yy\"]",
            "probe[bar-foot].fields",
            "fields = [\"temperature\", \"stress_yy\"]",
            "specific_heat",
        ),
        (
            "normal = [0.0, 2.0]",
            "normal = [0.0, 0.0]",
            "wall[anvil].normal",
            "normal = [0.0, 0.0]",
            "must not be zero",
        ),
        (
            "coefficient = 1.0",
            "coefficient = 0.0",
            "hourglass_control.coefficient",
            "coefficient = 0.0",
            "> 0",
        ),
        (
            "coefficient = 1.0",
            "coefficient = -2.0",
            "hourglass_control.coefficient",
            "coefficient = -2.0",
            "> 0",
        ),
        // More of the same kind.
        (
            "tangent_modulus = 1.1e9",
            "tangent_modulus = 1.1e9\nplastic_modulus = 1.0e9",
            "material[copper].tangent_modulus",
            "tangent_modulus = 1.1e9",
            "not both",
        ),
        (
            "tangent_modulus = 1.1e9",
            "tangent_modulus = 200.0e9",
            "material[copper].tangent_modulus",
            "tangent_modulus = 200.0e9",
            "less than youngs_modulus",
        ),
        (
            "tangent_modulus = 1.1e9",
            "specific_heat = 383.0",
            "material[copper].room_temperature",
            "specific_heat = 383.0",
            "required with specific_heat",
        ),
        (
            "tangent_modulus = 1.1e9",
            "accurate_iteration = true",
            "material[copper].accurate_iteration",
            "accurate_iteration = true",
            "not a parameter of model `elastic-plastic`",
        ),
        (
            "model = \"elastic-plastic\"",
            "model = \"plastic\"",
            "material[copper].model",
            "model = \"plastic\"",
            "unknown material model `plastic`",
        ),
        (
            "s1 = 1.489, ",
            "",
            "material[cu9].eos.s1",
            "model = \"mie-gruneisen\"",
            "is required by EOS model `mie-gruneisen`",
        ),
        (
            "sound_speed = 3940.0,",
            "sound_speed = 3940.0, bulk_modulus = 1.0e11,",
            "material[cu9].eos.bulk_modulus",
            "model = \"mie-gruneisen\"",
            "is not a parameter of EOS model `mie-gruneisen`",
        ),
        (
            "min_pressure = -1.0e9",
            "min_pressure = -inf",
            "material[cu9].min_pressure",
            "min_pressure = -inf",
            "finite",
        ),
        (
            "normal = [0.0, 2.0]",
            "normal = [0.0, 2.0, 0.0]",
            "wall[anvil].normal",
            "normal = [0.0, 2.0, 0.0]",
            "needs 2 components",
        ),
    ];
    for (from, to, field, line_text, fragment) in cases {
        assert!(PLASTIC.contains(from), "{from}");
        let text = PLASTIC.replacen(from, to, 1);
        let e = error_of(&text);
        assert_eq!(e.field, *field, "{to}: {e}");
        assert_eq!(e.line, Some(line_of(&text, line_text)), "{to}: {e}");
        assert!(e.message.contains(fragment), "{to}: {e}");
    }
}

#[test]
fn a_second_wall_with_the_same_name_is_rejected() {
    let text = PLASTIC.replace(
        "[hourglass_control]",
        "[[wall]]\nname = \"anvil\"\npoint = [0.0, 9.0e-3]\nnormal = [0.0, -1.0]\n\n[hourglass_control]",
    );
    let e = error_of(&text);
    assert_eq!(e.field, "wall.name", "{e}");
    assert_eq!(e.line, Some(line_of(&text, "normal = [0.0, -1.0]") - 2));
}

#[test]
fn elastic_plastic_with_green_lagrange_is_rejected_at_the_stress_update_line() {
    let text = PLASTIC.replace(
        "stress_update = \"jaumann-rate\"",
        "stress_update = \"green-lagrange\"",
    );
    let e = error_of(&text);
    assert_eq!(e.field, "simulation.stress_update", "{e}");
    assert_eq!(
        e.line,
        Some(line_of(&text, "stress_update = \"green-lagrange\""))
    );
    assert!(e.message.contains("jaumann-rate"), "{e}");
}

#[test]
fn a_wall_run_writes_walls_csv_and_its_energy_column_before_total() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let scene = parse_scene(BAR_ON_WALL, "bar.toml").unwrap();
    let record = run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    assert!(record.failure.is_none(), "{:?}", record.failure);

    let walls = fs::read_to_string(dir.join("walls.csv")).unwrap();
    let mut lines = walls.lines();
    assert_eq!(
        lines.next(),
        Some("time,wall_anvil_force_x,wall_anvil_force_y,wall_anvil_force_z")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    // The reaction on the particles points along the normal (+x) and peaks at about the
    // impact stress ρ c v (per unit area in 1D); y and z are zero in 1D.
    let peak = rows.iter().map(|r| r[1]).fold(0.0, f64::max);
    assert!(rows
        .iter()
        .all(|r| r[1] >= 0.0 && r[2] == 0.0 && r[3] == 0.0));
    assert!(peak > 1.0e8, "peak wall force {peak}");

    let energy = fs::read_to_string(dir.join("energy.csv")).unwrap();
    let mut lines = energy.lines();
    assert_eq!(lines.next(), Some("time,kinetic,internal,wall_anvil,total"));
    let mut stored_max: f64 = 0.0;
    for line in lines {
        let r: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert_eq!(r.len(), 5);
        stored_max = stored_max.max(r[3]);
        // total = kinetic + internal + the wall's stored energy.
        assert!(
            (r[1] + r[2] + r[3] - r[4]).abs() <= 1e-12 * r[4].abs(),
            "{line}"
        );
    }
    assert!(stored_max > 0.0);
    // Same sample times in both files.
    assert_eq!(walls.lines().count(), energy.lines().count());
    let foot = record.probe("foot").unwrap();
    let plastic = foot.series("plastic_strain".parse().unwrap()).unwrap();
    assert!(*plastic.last().unwrap() > 0.0, "the struck end yields");
}

#[test]
fn hourglass_energy_gets_its_column_after_the_walls() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let text = BAR_ON_WALL.replace(
        "[[probe]]",
        "[[wall]]\nname = \"back\"\npoint = [6.0e-3]\nnormal = [-1.0]\n\n[hourglass_control]\ncoefficient = 0.5\n\n[[probe]]",
    );
    let scene = parse_scene(&text, "bar.toml").unwrap();
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let energy = fs::read_to_string(dir.join("energy.csv")).unwrap();
    assert!(
        energy.starts_with("time,kinetic,internal,wall_anvil,wall_back,hourglass,total\n"),
        "{}",
        energy.lines().next().unwrap()
    );
    let walls = fs::read_to_string(dir.join("walls.csv")).unwrap();
    assert!(walls.starts_with(
        "time,wall_anvil_force_x,wall_anvil_force_y,wall_anvil_force_z,wall_back_force_x,wall_back_force_y,wall_back_force_z\n"
    ));
}

#[test]
fn without_walls_there_is_no_walls_csv() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let text = BAR_ON_WALL
        .replace(
            "[[wall]]\nname = \"anvil\"\npoint = [0.0]\nnormal = [1.0]\n",
            "",
        )
        .replace(
            "[[probe]]",
            "[hourglass_control]\ncoefficient = 0.5\n\n[[probe]]",
        );
    let scene = parse_scene(&text, "bar.toml").unwrap();
    run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    assert!(!dir.join("walls.csv").exists());
    let energy = fs::read_to_string(dir.join("energy.csv")).unwrap();
    assert!(energy.starts_with("time,kinetic,internal,hourglass,total\n"));
}

#[test]
fn frames_and_probes_carry_plastic_strain_and_temperature() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let text = PLASTIC
        .replace("end_time = 1.0e-6", "end_time = 0.4e-6")
        .replace(
            "[[probe]]\nname = \"bar-foot\"",
            "[output]\nframe_interval = 0.2e-6\n\n[[probe]]\nname = \"bar-foot\"",
        );
    let scene = parse_scene(&text, "plastic.toml").unwrap();
    let record = run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    assert!(record.failure.is_none());
    let vtu = fs::read_to_string(dir.join("frames/frame_00001.vtu")).unwrap();
    assert!(vtu.contains("Name=\"plastic_strain\""));
    assert!(vtu.contains("Name=\"temperature\""));
    // The plate is at rest and unstressed: room temperature, no plastic strain.
    let plate = record.probe("plate-mid").unwrap();
    assert!(plate.values.iter().all(|r| r[0] == 300.0 && r[1] == 0.0));
    let probe = fs::read_to_string(dir.join("probes/plate-mid.csv")).unwrap();
    assert!(probe.starts_with("time,temperature,plastic_strain\n"));

    // An elastic scene has neither array; its plastic_strain probe reads 0.
    let elastic = PLASTIC
        .replace("model = \"elastic-plastic\"", "model = \"linear-elastic\"")
        .replace("yield_stress = 90.0e6\ntangent_modulus = 1.1e9\n", "")
        .replace(
            "[[material]]\nname = \"cu9\"",
            "[[material]]\nname = \"unused\"",
        )
        .replace("material = \"cu9\"", "material = \"copper\"")
        .replace("fields = [\"temperature\", ", "fields = [")
        .replace("end_time = 1.0e-6", "end_time = 0.2e-6")
        .replace(
            "[[probe]]\nname = \"bar-foot\"",
            "[output]\nframe_interval = 0.2e-6\n\n[[probe]]\nname = \"bar-foot\"",
        );
    let scene = parse_scene(&elastic, "elastic.toml").unwrap();
    let dir = tmp.path().join("elastic");
    let record = run_scene_to_dir(&scene, &dir, &mut |_, _| {}).unwrap();
    let vtu = fs::read_to_string(dir.join("frames/frame_00001.vtu")).unwrap();
    assert!(!vtu.contains("Name=\"plastic_strain\""));
    assert!(!vtu.contains("Name=\"temperature\""));
    let foot = record.probe("bar-foot").unwrap();
    assert!(foot.values.iter().all(|r| r[0] == 0.0));
}

/// Bug: the linear and polynomial EOS accept `s2`, `s3` and `a` (Mie–Grüneisen keys) and
/// silently ignore them, while every other key of another EOS model is rejected.
#[test]
fn keys_of_another_eos_model_are_always_rejected() {
    for eos in [
        "eos = { model = \"linear\", bulk_modulus = 1.4e11, s2 = 1.0 }",
        "eos = { model = \"linear\", bulk_modulus = 1.4e11, a = 0.47 }",
        "eos = { model = \"polynomial\", coefficients = [0.0, 1.4e11, 0.0, 0.0, 0.0, 0.0, 0.0], s3 = 1.0 }",
    ] {
        let text = PLASTIC.replace("tangent_modulus = 1.1e9", eos);
        let e = error_of(&text);
        assert!(e.field.starts_with("material[copper].eos."), "{eos}: {e}");
    }
}

#[test]
fn failure_models_parse_and_their_errors_are_located() {
    let with = |failure: &str| {
        PLASTIC.replace(
            "tangent_modulus = 1.1e9",
            &format!("tangent_modulus = 1.1e9\nfailure = {failure}"),
        )
    };
    let ok = with("{ model = \"max-plastic-strain\", limit = 0.8 }");
    let scene = parse_scene(&ok, "fail.toml").unwrap();
    let DimensionModel::Two(m) = &scene.model else {
        panic!("2D")
    };
    let MaterialModel::ElasticPlastic(p) = &m.materials[0].model else {
        panic!("plastic")
    };
    assert!(p.failure.is_some());
    for (failure, field) in [
        // The scene's key is `limit`, whatever the quantity it limits.
        (
            "{ model = \"max-plastic-strain\", limit = -1.0 }",
            "failure.limit",
        ),
        (
            "{ model = \"max-principal-stress\", limit = 0.0 }",
            "failure.limit",
        ),
        // D1 + D2 = 0: no positive failure strain anywhere.
        (
            "{ model = \"johnson-cook\", d = [0.0, 0.0, 0.0, 0.0, 0.0], reference_strain_rate = 1.0, room_temperature = 293.0, melt_temperature = 1356.0 }",
            "failure.d",
        ),
        ("{ model = \"max-plastic-strain\" }", "failure.limit"),
        (
            "{ model = \"johnson-cook\", d = [0.5, 0.0, 0.0, 0.0] }",
            "failure.d",
        ),
        (
            "{ model = \"johnson-cook\", d = [0.5, 0.0, 0.0, 0.0, 0.0] }",
            "failure.reference_strain_rate",
        ),
        (
            "{ model = \"max-principal-stress\", limit = 1e9, d = [1.0] }",
            "failure.d",
        ),
        ("{ model = \"crack\" }", "failure.model"),
    ] {
        let text = with(failure);
        let e = error_of(&text);
        assert!(e.field.ends_with(field), "{failure}: {e}");
        assert_eq!(e.line, Some(line_of(&text, "failure = ")), "{failure}: {e}");
    }
}
