//! `tlsph check`'s overview: the time step it announces is the one the solver takes, an
//! equation of state's limiting compression is shown where a typo would make it tiny, and a
//! polynomial equation of state that softens within reach is flagged.

use tlsph_io::{parse_scene, DimensionModel};
use tlsph_solver::Simulation;

/// Two bodies of different stiffness and speed; the one with the smaller CFL step sets it.
const TWO_BLOCKS: &str = r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.3
cfl = 0.25
end_time = 1.0e-4

[[material]]
name = "steel"
model = "linear-elastic"
density = 7850.0
youngs_modulus = 200.0e9
poisson_ratio = 0.3

[[material]]
name = "copper"
model = "elastic-plastic"
density = 8930.0
youngs_modulus = 117.0e9
poisson_ratio = 0.35
yield_stress = 400.0e6
eos = { model = "mie-gruneisen", sound_speed = 3940.0, s1 = 1.489, gamma0 = 2.02 }

[[body]]
name = "fast"
material = "copper"
spacing = 1.0e-3
box = { min = [0.0, 0.0], max = [0.01, 0.01] }
velocity = [600.0, 0.0]

[[body]]
name = "still"
material = "steel"
spacing = 2.0e-3
box = { min = [0.02, 0.0], max = [0.04, 0.01] }
"#;

#[test]
fn the_announced_first_step_is_the_one_the_solver_takes() {
    let scene = parse_scene(TWO_BLOCKS, "blocks.toml").unwrap();
    let overview = scene.overview();
    let fast = &overview.bodies[0];
    // c0 of the copper: sqrt((ρ0C² + 4G/3)/ρ0) with its Mie–Grüneisen bulk modulus.
    let shear = 117.0e9 / (2.0 * 1.35);
    let c_copper = ((8930.0 * 3940.0_f64.powi(2) + 4.0 / 3.0 * shear) / 8930.0).sqrt();
    assert!((fast.wave_speed - c_copper).abs() <= 1e-12 * c_copper);
    assert_eq!(fast.fastest_particle, 600.0);
    assert_eq!(fast.particles, 100);
    // The copper block has the finer spacing and moves: it sets the step.
    assert_eq!(overview.first_time_step(), fast.first_time_step);
    assert!(overview.bodies[1].first_time_step > fast.first_time_step);
    let DimensionModel::Two(model) = scene.model else {
        panic!("a 2D scene")
    };
    let mut sim = Simulation::new(model).unwrap();
    sim.step().unwrap();
    let taken = sim.next_dt();
    assert!(
        (taken - overview.first_time_step()).abs() <= 1e-12 * taken,
        "solver {taken:e}, announced {:e}",
        overview.first_time_step()
    );
    // 1e-4 s at that step, over the 150 particles.
    let steps = (1.0e-4 / taken).ceil();
    assert_eq!(overview.estimated_steps(), steps);
    assert_eq!(overview.estimated_particle_steps(), 150.0 * steps);
}

#[test]
fn a_mie_gruneisen_limit_is_shown_so_a_typo_in_s1_is_visible() {
    // D(μ) = 1 − (S1 − 1)μ for S2 = S3 = 0: μ_lim = 1/(S1 − 1). Copper's 1.489 gives 2.045;
    // a slip of the decimal point (1489) gives 6.7e-4: that body cannot be compressed by more
    // than 0.07 %, which check now says before the run stops on it.
    for (s1, limit) in [(1.489, 1.0 / 0.489), (1489.0, 1.0 / 1488.0)] {
        let text = TWO_BLOCKS.replace("s1 = 1.489", &format!("s1 = {s1}"));
        let overview = parse_scene(&text, "blocks.toml").unwrap().overview();
        let shown = overview.bodies[0].compression_limit.unwrap();
        assert!((shown - limit).abs() <= 1e-9 * limit, "{shown} vs {limit}");
        assert!(overview.to_string().contains(&format!("{limit:.3e}")));
        // A material without an equation of state has no limit to show.
        assert_eq!(overview.bodies[1].compression_limit, None);
    }
}

#[test]
fn a_polynomial_eos_that_softens_is_flagged() {
    // C2 = −100 GPa against C1 = 70 GPa: dp/dμ = 70 − 200μ GPa vanishes at μ = 0.35 (a
    // compression reached in a strong impact), and the copper's wave speed would fall to the
    // shear term there. The check says where; a C2 of +100 GPa stiffens and is not flagged.
    let softening = TWO_BLOCKS.replace(
        r#"eos = { model = "mie-gruneisen", sound_speed = 3940.0, s1 = 1.489, gamma0 = 2.02 }"#,
        r#"eos = { model = "polynomial", coefficients = [0.0, 70.0e9, -100.0e9, 0.0, 0.0, 0.0, 0.0] }"#,
    );
    assert_ne!(softening, TWO_BLOCKS);
    let overview = parse_scene(&softening, "blocks.toml").unwrap().overview();
    assert_eq!(overview.bodies[0].stiffness_limits, (None, Some(0.35)));
    let text = overview.to_string();
    assert!(
        text.contains("warning: the polynomial equation of state's bulk modulus dp/dμ vanishes at ρ/ρ0 − 1 = 3.500e-1"),
        "{text}"
    );
    assert_eq!(overview.bodies[1].stiffness_limits, (None, None));
    let stiffening = softening.replace("-100.0e9", "100.0e9");
    let overview = parse_scene(&stiffening, "blocks.toml").unwrap().overview();
    assert_eq!(overview.bodies[0].stiffness_limits, (None, None));
    assert!(!overview.to_string().contains("warning"));
}

#[test]
fn contact_without_hourglass_control_gets_a_note() {
    // docs/scene-format.md, contact: TLSPH surfaces in contact zig-zag and let the partner dig
    // in (penalty law: pressed hard or sheared by friction) or sink in (potential law: under
    // any steady load) unless hourglass control is declared. The check says so, naming the
    // law, for a total-Lagrangian scene with contact and no control, and stays silent once the
    // control is declared or the formulation is updated-Lagrangian.
    let notes = |text: &str| parse_scene(text, "blocks.toml").unwrap().overview().notes;
    for (law, start) in [
        ("penalty", "penalty contact"),
        ("potential", "potential contact"),
    ] {
        let keys = if law == "potential" {
            "scale = 0.2\n"
        } else {
            ""
        };
        let with_contact = format!("{TWO_BLOCKS}\n[contact]\nlaw = \"{law}\"\n{keys}");
        let advised = notes(&with_contact);
        assert_eq!(advised.len(), 1, "{advised:?}");
        assert!(advised[0].starts_with(start), "{advised:?}");
        assert!(advised[0].contains("[hourglass_control]"));
        let overview = parse_scene(&with_contact, "blocks.toml")
            .unwrap()
            .overview();
        assert!(overview.to_string().contains(&format!("\n  note: {start}")));
        let controlled = format!("{with_contact}\n[hourglass_control]\ncoefficient = 1.0\n");
        assert!(notes(&controlled).is_empty());
        let updated = with_contact.replace(
            "formulation = \"total-lagrangian-corrected\"",
            "formulation = \"updated-lagrangian\"",
        );
        assert_ne!(updated, with_contact);
        assert!(notes(&updated).is_empty(), "{law}");
    }
    assert!(notes(TWO_BLOCKS).is_empty(), "no contact, no note");
}

#[test]
fn a_box_or_cone_wall_without_hourglass_control_gets_a_note() {
    // docs/scene-format.md, boxes and cones: a box's sharp edges and a cone's tip drive
    // TLSPH's zig-zag mode. The check names each box or cone wall of a total-Lagrangian scene
    // without hourglass control, and is silent for the other shapes, with the control, or in
    // updated-Lagrangian.
    let notes = |text: &str| parse_scene(text, "blocks.toml").unwrap().overview().notes;
    let with_box = format!(
        "{TWO_BLOCKS}\n[[wall]]\nname = \"die\"\nshape = \"box\"\npoint = [5.0e-3, 14.0e-3]\nsize = [4.0e-3, 2.0e-3]\n"
    );
    let advised = notes(&with_box);
    assert_eq!(advised.len(), 1, "{advised:?}");
    assert!(
        advised[0].starts_with("wall `die` is a box") && advised[0].contains("[hourglass_control]"),
        "{advised:?}"
    );
    // A cone (a wedge in 2D) pointing down at the blocks: the same note.
    let cone = with_box
        .replace("shape = \"box\"", "shape = \"cone\"\naxis = [0.0, 1.0]")
        .replace("size = [4.0e-3, 2.0e-3]", "half_angle = 60.0");
    let advised = notes(&cone);
    assert_eq!(advised.len(), 1, "{advised:?}");
    assert!(
        advised[0].starts_with("wall `die` is a cone")
            && advised[0].contains("[hourglass_control]"),
        "{advised:?}"
    );
    let disc = with_box
        .replace("shape = \"box\"", "shape = \"disc\"\nnormal = [0.0, -1.0]")
        .replace("size = [4.0e-3, 2.0e-3]", "radius = 2.0e-3");
    assert!(notes(&disc).is_empty(), "{:?}", notes(&disc));
    let controlled = format!("{with_box}\n[hourglass_control]\ncoefficient = 1.0\n");
    assert!(notes(&controlled).is_empty());
    let updated = with_box.replace(
        "formulation = \"total-lagrangian-corrected\"",
        "formulation = \"updated-lagrangian\"",
    );
    assert_ne!(updated, with_box);
    assert!(notes(&updated).is_empty());
}

#[test]
fn static_friction_without_a_decay_gets_a_note() {
    // docs/scene-format.md, wall friction and penalty contact: with μ_s > μ_k and no decay, a
    // slip that starts at a face's edge runs through the face. The check names each such
    // surface, and is silent with a decay or with one coefficient.
    let notes = |text: &str| parse_scene(text, "blocks.toml").unwrap().overview().notes;
    let wall = |keys: &str| {
        format!(
            "{TWO_BLOCKS}\n[[wall]]\nname = \"floor\"\npoint = [0.0, -1.0]\nnormal = [0.0, 1.0]\n{keys}"
        )
    };
    let advised = notes(&wall("friction = 0.2\nstatic_friction = 0.5\n"));
    assert_eq!(advised.len(), 1, "{advised:?}");
    assert!(
        advised[0].starts_with("wall `floor` has static_friction"),
        "{advised:?}"
    );
    assert!(advised[0].contains("friction_decay"));
    assert!(notes(&wall(
        "friction = 0.2\nstatic_friction = 0.5\nfriction_decay = 50.0\n"
    ))
    .is_empty());
    assert!(notes(&wall("friction = 0.2\n")).is_empty());
    assert!(notes(&wall("friction = 0.2\nstatic_friction = 0.2\n")).is_empty());
    // The penalty contact, with hourglass control so that only this note remains.
    let contact = |keys: &str| {
        format!(
            "{TWO_BLOCKS}\n[hourglass_control]\ncoefficient = 1.0\n\n[contact]\nlaw = \"penalty\"\n{keys}"
        )
    };
    let advised = notes(&contact("friction = 0.2\nstatic_friction = 0.5\n"));
    assert_eq!(advised.len(), 1, "{advised:?}");
    assert!(
        advised[0].starts_with("the penalty contact has static_friction"),
        "{advised:?}"
    );
    assert!(notes(&contact(
        "friction = 0.2\nstatic_friction = 0.5\nfriction_decay = 50.0\n"
    ))
    .is_empty());
}
