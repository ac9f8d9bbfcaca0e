//! `[[body]] kernel_group` and `[artificial_stress] bodies`: parsed into the model, and
//! rejected with the field and line named.

use super::{error_of, line_of};
use tlsph_io::{parse_scene, DimensionModel};

/// Two discs of different density (Fuller F-A3) in updated-Lagrangian SPH; `extra_a` and
/// `extra_b` are lines added to the two bodies, `tail` is appended.
fn discs(formulation: &str, extra_a: &str, extra_b: &str, tail: &str) -> String {
    format!(
        r#"
[simulation]
dimension = 2
formulation = "{formulation}"
kernel = "cubic-spline"
smoothing_factor = 1.5
cfl = 0.3
end_time = 1.0

[[material]]
name = "heavy"
model = "linear-elastic"
density = 1.0
youngs_modulus = 1.0
poisson_ratio = 0.3

[[material]]
name = "light"
model = "linear-elastic"
density = 0.1
youngs_modulus = 1.0
poisson_ratio = 0.3

[[body]]
name = "discA"
material = "heavy"
spacing = 1.0
disc = {{ centre = [-14.0, 0.0], radius = 4.0 }}
{extra_a}

[[body]]
name = "discB"
material = "light"
spacing = 1.0
disc = {{ centre = [14.0, 0.0], radius = 4.0 }}
{extra_b}
{tail}
"#
    )
}

fn model(text: &str) -> tlsph_solver::Model<2> {
    match parse_scene(text, "scene.toml").expect("valid scene").model {
        DimensionModel::Two(m) => m,
        _ => unreachable!("2D scene"),
    }
}

#[test]
fn kernel_groups_default_to_the_material_and_name_shared_groups() {
    let ul = "updated-lagrangian";
    assert_eq!(model(&discs(ul, "", "", "")).effects.kernel_groups, None);
    let shared = "kernel_group = \"discs\"";
    let m = model(&discs(ul, shared, shared, ""));
    assert_eq!(m.effects.kernel_groups, Some(vec![0, 0]));
    // A group named after a material joins that material's default group.
    let m = model(&discs(ul, "", "kernel_group = \"heavy\"", ""));
    assert_eq!(m.effects.kernel_groups, Some(vec![0, 0]));
    let m = model(&discs(ul, "kernel_group = \"a\"", "", ""));
    assert_eq!(m.effects.kernel_groups, Some(vec![0, 1]));
}

#[test]
fn artificial_stress_bodies_are_resolved_by_name() {
    let ul = "updated-lagrangian";
    let m = model(&discs(
        ul,
        "",
        "",
        "[artificial_stress]\nbodies = [\"discB\"]",
    ));
    let a = m.effects.artificial_stress.expect("declared");
    assert_eq!(a.bodies, Some(vec![1]));
    assert_eq!((a.epsilon, a.exponent), (0.3, 6.0));
    let m = model(&discs(ul, "", "", "[artificial_stress]"));
    assert_eq!(m.effects.artificial_stress.expect("declared").bodies, None);
}

#[test]
fn kernel_group_and_artificial_stress_body_errors_name_field_and_line() {
    let cases = [
        (
            discs(
                "total-lagrangian-corrected",
                "kernel_group = \"discs\"",
                "",
                "",
            ),
            "body[discA].kernel_group",
            "kernel_group = \"discs\"",
            "updated-lagrangian",
        ),
        (
            discs("updated-lagrangian", "", "kernel_group = \" \"", ""),
            "body[discB].kernel_group",
            "kernel_group = \" \"",
            "non-empty",
        ),
        (
            discs(
                "updated-lagrangian",
                "",
                "",
                "[artificial_stress]\nbodies = [\"discC\"]",
            ),
            "artificial_stress.bodies",
            "bodies = [\"discC\"]",
            "no body named `discC`",
        ),
    ];
    for (text, field, line_text, fragment) in cases {
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert_eq!(e.line, Some(line_of(&text, line_text)), "{e}");
        assert!(e.message.contains(fragment), "{e}");
    }
}
